"""The face-width solve (geargen.core.load_capacity._narrowest_face_width) after issue 28 (each
width rated once for both safety factors: the two searches and brentq all start at the same two
ends) against the code it replaced, kept here as the reference: the same widths and messages to the
last bit, with fewer ratings."""

import math

import pytest

from geargen.core import load_capacity as lc
from geargen.core.load_capacity import FaceWidthSolution

from test_load_capacity import CARBURISED, CONDITIONS, DEG, helical_gears


def reference_narrowest_face_width(geo, safeties, minimum_safety):
    """geargen before issue 28: every margin rated anew."""
    from scipy.optimize import brentq

    m_n = geo.normal_module
    lo, hi = math.log(0.05 * m_n), math.log(1000.0 * m_n)

    def margin(log_b, which, minimum):
        return safeties(geo.with_face_width(math.exp(log_b)))[which] - minimum

    def solve(which, key, minimum):
        a, z = margin(lo, which, minimum), margin(hi, which, minimum)
        if a >= 0:
            return math.exp(lo), f"{key} reaches {minimum:g} at the narrowest width searched"
        if z < 0:
            return None, f"{key} stays below {minimum:g} up to {math.exp(hi):.4g} mm of face"
        return math.exp(brentq(margin, lo, hi, args=(which, minimum), xtol=1e-13, rtol=1e-14)), ""

    b_h, msg_h = solve(0, "S_H", minimum_safety[0])
    b_f, msg_f = solve(1, "S_F", minimum_safety[1])
    return FaceWidthSolution(pitting=b_h, bending=b_f, message="; ".join(m for m in (msg_h, msg_f) if m))


@pytest.mark.parametrize("load, minimum", [(2 * 160e3 / (19 * 3 / math.cos(22 * DEG)), (1.1, 1.6)),
                                           (9000.0, (1.0, 1.4)), (50.0, (1.0, 1.4)), (5e7, (1.3, 2.0))],
                         ids=["solved", "solved light", "narrowest suffices", "never enough"])
def test_widths_as_before(load, minimum):
    g1, g2 = helical_gears()
    geo = lc.rating_geometry(g1, g2, 136.0)
    count = [0]

    def safeties(at_width):
        count[0] += 1
        r = lc.rate_pair(at_width, load, CONDITIONS, CARBURISED)
        return min(r["S_H"]), min(r["S_F"])

    got = lc._narrowest_face_width(geo, safeties, minimum)
    new_count, count[0] = count[0], 0
    want = reference_narrowest_face_width(geo, safeties, minimum)
    assert got == want
    assert new_count < count[0]  # the two ends rated once, not up to six times
