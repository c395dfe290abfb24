"""geargen.core.involute against published values and an independent rack-generation model.

The independent model cuts the flank the way a hob does: the generating rack (defined in its
normal section by module, pressure angle, profile shift and thinning) rolls on the reference
circle, and each rack flank point leaves the gear point where its normal passes through the
pitch point. Nothing in it uses the involute function.
"""

import math
import pathlib
import tomllib

import numpy as np
import pytest
from scipy.optimize import brentq

from geargen.core.involute import (involute, inverse_involute, pointed_tip_radius, pressure_angle_at_radius,
                                   reference_tooth_thickness, tip_land_thickness, tooth_half_angle,
                                   tooth_thickness_at_radius)
from geargen.design.gear import GearSpec

DATA = tomllib.loads((pathlib.Path(__file__).parents[1] / "data" / "published_cases.toml").read_text())
DEG = math.pi / 180


def printed_tolerance(text: str) -> float:
    """Half a unit in the last printed digit of ``text``."""
    decimals = len(text.split(".")[1]) if "." in text else 0
    return 0.5 * 10.0 ** (-decimals)


def spec(**kw):
    base = dict(teeth=20, module=2.0, pressure_angle=20 * DEG, face_width=10.0)
    base.update(kw)
    return GearSpec(**base)


def rack_generated_point(g: GearSpec, depth):
    """Gear point cut by the rack's flank point ``depth`` mm inside the rolling line (transverse).

    Returns (radius, psi): psi is the polar angle of that flank point from its tooth centreline.
    """
    m_t = g.module / math.cos(g.helix_angle)
    tan_t = math.tan(g.pressure_angle) / math.cos(g.helix_angle)  # normal-section slope, widths / cos(beta)
    r = g.teeth * m_t / 2
    v = -np.asarray(depth, float)  # across the rack, outward positive; rolling line v = 0
    datum = g.profile_shift * g.module  # the rack's datum line lies x m_n outside the rolling line
    # rack tooth (it cuts the space): pi m_n / 2 wide on the datum line in the normal section,
    # widened by the thinning, flanks at alpha_n; in the transverse section widths grow by 1/cos(beta)
    u = math.pi * m_t / 4 + g.thinning / 2 + (v - datum) * tan_t
    phi = (u + v / tan_t) / r  # the flank normal (cos a_t, -sin a_t) meets the rolling line at r phi
    fx, fy = u - r * phi, r + v
    gx, gy = np.cos(phi) * fx + np.sin(phi) * fy, -np.sin(phi) * fx + np.cos(phi) * fy
    # this flank borders the space centred on +y; its tooth is centred pi/z further clockwise
    return np.hypot(gx, gy), np.arctan2(gy, gx) - (math.pi / 2 - math.pi / g.teeth)


def interference_depth(g: GearSpec) -> float:
    """Depth of the interference point inside the rolling line, r sin^2(alpha_t): rack points deeper
    than this touch the line of action beyond the base circle and cut the other involute branch."""
    return g.reference_radius * math.sin(g.transverse_pressure_angle) ** 2


def rack_point_at_radius(g: GearSpec, radius):
    """psi of the rack-generated flank at ``radius`` (solving for the rack depth)."""
    return float(rack_generated_point(g, brentq(lambda d: rack_generated_point(g, d)[0] - radius,
                                                -3 * g.module, interference_depth(g), xtol=1e-15))[1])


# --- the involute function -------------------------------------------------------------------

def test_involute_matches_published_table():
    case = DATA["involute_table"]
    for deg, text in zip(case["pressure_angle_deg"], case["involute"]):
        assert abs(involute(deg * DEG) - float(text)) <= printed_tolerance(text)


@pytest.mark.parametrize("angles", [np.linspace(0.0, 1.55, 1001), np.array([1e-6, 1e-3, 0.3490658503988659])])
def test_inverse_involute_round_trips_angles(angles):
    back = inverse_involute(involute(angles))
    assert back.shape == angles.shape
    # near 0, inv(a) ~ a^3/3 loses relative precision in a: compare the involute values there
    np.testing.assert_allclose(back, angles, rtol=1e-12, atol=2e-6)
    np.testing.assert_allclose(involute(back), involute(angles), rtol=1e-13, atol=1e-300)


def test_inverse_involute_round_trips_values():
    # tan(a) - a cancels for small a (relative error ~ 1e-16 / a^2), so tight only above 1e-5
    values = np.logspace(-5, 3, 400)
    np.testing.assert_allclose(involute(inverse_involute(values)), values, rtol=1e-12)
    tiny = np.logspace(-14, -5, 50)
    c = np.cbrt(3 * tiny)  # inv(a) = a^3/3 + 2 a^5/15 + O(a^7)  =>  a = c - 2 c^3/15 + O(c^5)
    np.testing.assert_allclose(inverse_involute(tiny), c - 2 * c ** 3 / 15, rtol=1e-6)
    assert isinstance(inverse_involute(0.014904383867336446), float)
    assert inverse_involute(0.0) == 0.0
    assert abs(inverse_involute(0.014904383867336446) - 20 * DEG) < 1e-14


def test_inverse_involute_rejects_negative_and_nan():
    with pytest.raises(ValueError):
        inverse_involute(-1e-9)
    with pytest.raises(ValueError):
        inverse_involute(np.array([0.1, np.nan]))


# --- tooth thickness against rack generation --------------------------------------------------

CASES = [
    dict(),
    dict(teeth=13, profile_shift=0.4),
    dict(teeth=31, profile_shift=-0.3, thinning=0.08),
    dict(teeth=17, helix_angle=25 * DEG, profile_shift=0.2, thinning=0.05, module=1.5),
    dict(teeth=40, helix_angle=40 * DEG, pressure_angle=14.5 * DEG, hand="left", profile_shift=0.1),
]


@pytest.mark.parametrize("kw", CASES)
def test_tooth_half_angle_matches_rack_generation(kw):
    g = spec(**kw)
    depths = np.linspace(-g.module, 0.999 * interference_depth(g), 37)  # tip region down to the base circle
    radius, psi = rack_generated_point(g, depths)
    keep = (radius > g.base_radius * 1.0001) & (radius < g.tip_radius)
    assert keep.sum() > 20
    # the generated flank is the involute: same polar angle at the same radius, to rounding
    np.testing.assert_allclose(tooth_half_angle(g, radius[keep]), psi[keep], rtol=0, atol=1e-13)
    np.testing.assert_allclose(tooth_thickness_at_radius(g, radius[keep]), 2 * radius[keep] * psi[keep],
                               rtol=0, atol=1e-11)


@pytest.mark.parametrize("kw", CASES)
def test_reference_thickness_and_tip_land_match_rack_generation(kw):
    g = spec(**kw)
    r = g.reference_radius
    assert abs(reference_tooth_thickness(g) - 2 * r * rack_point_at_radius(g, r)) < 1e-11
    assert abs(tip_land_thickness(g) - 2 * g.tip_radius * rack_point_at_radius(g, g.tip_radius)) < 1e-11


def test_pointed_tip_radius_is_where_the_generated_flank_reaches_the_centreline():
    g = spec(teeth=9, profile_shift=0.7, addendum_coefficient=1.2)  # tooth comes to a point below its tip
    depth = brentq(lambda d: rack_generated_point(g, d)[1], -2 * g.module, 0.0, xtol=1e-15)
    r_point = float(rack_generated_point(g, depth)[0])
    assert abs(pointed_tip_radius(g) - r_point) < 1e-10
    assert pointed_tip_radius(g) < g.tip_radius and tip_land_thickness(g) < 0
    assert abs(tooth_thickness_at_radius(g, pointed_tip_radius(g))) < 1e-12


def test_pressure_angle_at_radius():
    g = spec(helix_angle=30 * DEG)
    np.testing.assert_allclose(pressure_angle_at_radius(g, g.reference_radius), g.transverse_pressure_angle, atol=1e-15)
    r = np.array([[g.base_radius, 1.1 * g.base_radius], [g.tip_radius, 2 * g.base_radius]])
    out = pressure_angle_at_radius(g, r)
    assert out.shape == (2, 2)
    np.testing.assert_allclose(np.cos(out) * r, g.base_radius, rtol=1e-15)
    with pytest.raises(ValueError, match="base circle"):
        pressure_angle_at_radius(g, 0.99 * g.base_radius)
