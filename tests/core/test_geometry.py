"""geargen.core.geometry against published cases and independent numerical constructions.

The independent constructions build tooth flanks from their definitions (an involute string
unwound from the base circle, crossing the reference circle at half the tooth thickness, swept
along a helix for helical gears) and then measure them the way an instrument would: parallel
tangent planes for the span, a ball pressed into a tooth space for over-pins, lines of action
for backlash and contact ratio, a rack rolled through the blank for undercut. None of them uses
the involute function or the closed forms under test.
"""

import math
import pathlib
import tomllib

import numpy as np
import pytest
from scipy.optimize import brentq, least_squares, minimize_scalar, root

from geargen.core import geometry as geo
from geargen.core.geometry import GearPair
from geargen.design.gear import GearSpec
from geargen.errors import DesignError, GeometryError
from geargen.units import from_mm, module_from_diametral_pitch

DATA = tomllib.loads((pathlib.Path(__file__).parents[1] / "data" / "published_cases.toml").read_text())
DEG = math.pi / 180


def printed(computed: float, text: str) -> bool:
    """True when ``computed`` rounds to the printed ``text`` (within half a unit of its last digit)."""
    decimals = len(text.split(".")[1]) if "." in text else 0
    return abs(computed - float(text)) <= 0.5 * 10.0 ** (-decimals) * (1 + 1e-9)


def spec(**kw) -> GearSpec:
    base = dict(teeth=20, module=2.0, pressure_angle=20 * DEG, face_width=30.0)
    base.update(kw)
    return GearSpec(**base)


# ---------------------------------------------------------------------------------------------
# Independent flank model
# ---------------------------------------------------------------------------------------------

class Flank:
    """One flank of ``g``: an involute of the base circle, swept along the helix (w is axial).

    The tooth is centred at polar angle ``centre`` in the section w = 0; ``side`` +1 is its flank
    at positive polar angle, -1 the mirror one. The involute's origin is found numerically so that
    the flank crosses the reference circle at half the reference tooth thickness.
    """

    def __init__(self, g: GearSpec, centre: float, side: int):
        m_t = g.module / math.cos(g.helix_angle)
        alpha_t = math.atan(math.tan(g.pressure_angle) / math.cos(g.helix_angle))
        r = g.teeth * m_t / 2
        self.rb = r * math.cos(alpha_t)
        thickness = math.pi * m_t / 2 + 2 * g.profile_shift * g.module * math.tan(alpha_t) - g.thinning
        t_ref = math.sqrt((r / self.rb) ** 2 - 1)
        self.theta0 = 0.0
        self.theta0 = brentq(lambda th0: self._polar(t_ref, th0) - thickness / (2 * r), -2.0, 2.0, xtol=1e-16)
        self.centre, self.side = centre, side
        hand = 1.0 if g.hand == "right" else -1.0
        self.twist = hand * math.tan(g.helix_angle) / r  # rotation of a transverse section per axial length

    def _local(self, t, theta0=None):
        th = (self.theta0 if theta0 is None else theta0) - t  # tangent point moves clockwise as the string unwinds
        return self.rb * np.array([np.cos(th) - t * np.sin(th), np.sin(th) + t * np.cos(th)])

    def _polar(self, t, theta0):
        x, y = self._local(t, theta0)
        return math.atan2(y, x)

    def _rot(self, w):
        a = self.centre + self.twist * w
        return np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])

    def point(self, t, w=0.0):
        q = self._local(t) * np.array([1.0, self.side])
        return np.append(self._rot(w) @ q, w)

    def d_t(self, t, w=0.0):
        th = self.theta0 - t
        dq = self.rb * t * np.array([math.cos(th), math.sin(th)]) * np.array([1.0, self.side])
        return np.append(self._rot(w) @ dq, 0.0)

    def d_w(self, t, w=0.0):
        x, y = self.point(t, w)[:2]
        return np.array([-self.twist * y, self.twist * x, 1.0])

    def normal(self, t, w=0.0):
        n = np.cross(self.d_t(t, w), self.d_w(t, w))
        return n / np.linalg.norm(n)

    def roll_at_radius(self, radius):
        return math.sqrt((radius / self.rb) ** 2 - 1)


def cross2(a, b) -> float:
    """z component of the cross product of the first two components."""
    return float(a[0] * b[1] - a[1] * b[0])


def roots_on_grid(f, lo, hi, n=400):
    ts = np.linspace(lo, hi, n)
    vals = np.array([f(t) for t in ts])
    return [brentq(f, ts[i], ts[i + 1], xtol=1e-15) for i in np.nonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))[0]]


# ---------------------------------------------------------------------------------------------
# Published cases
# ---------------------------------------------------------------------------------------------

def test_shifted_spur_pair_matches_published():
    c = DATA["shifted_spur"]
    g1, g2 = (spec(teeth=z, module=c["module_mm"], pressure_angle=c["pressure_angle_deg"] * DEG, profile_shift=x)
              for z, x in zip(c["teeth"], c["profile_shift"]))
    mesh = geo.mesh_geometry(GearPair(g1, g2), tip_radii=c["tip_radii"])
    e = c["expected"]
    assert printed(math.degrees(mesh.working_pressure_angle), e["working_pressure_angle_deg"])
    assert printed(mesh.centre_distance, e["centre_distance_mm"])
    assert printed(mesh.transverse_contact_ratio, e["transverse_contact_ratio"])
    inv = c["inverse"]
    x_sum = geo.shift_sum_for_centre_distance(inv["centre_distance_mm"], sum(c["teeth"]), c["module_mm"],
                                              c["pressure_angle_deg"] * DEG)
    assert printed(x_sum, inv["shift_sum"])


def test_helical_pair_matches_published():
    c = DATA["helical_normal_system"]
    g1, g2 = (spec(teeth=z, module=c["module_mm"], pressure_angle=c["pressure_angle_deg"] * DEG,
                   helix_angle=c["helix_angle_deg"] * DEG, hand=h, profile_shift=x, face_width=c["face_width_mm"])
              for z, x, h in zip(c["teeth"], c["profile_shift"], c["hands"]))
    mesh = geo.mesh_geometry(GearPair(g1, g2), tip_radii=c["tip_radii"])
    e = c["expected"]
    assert printed(mesh.centre_distance, e["centre_distance_mm"])
    assert printed(math.degrees(mesh.transverse_pressure_angle), e["transverse_pressure_angle_deg"])
    assert printed(math.degrees(mesh.working_pressure_angle), e["working_pressure_angle_deg"])
    assert printed(mesh.transverse_contact_ratio, e["transverse_contact_ratio"])
    assert printed(mesh.face_contact_ratio, e["face_contact_ratio"])
    assert mesh.total_contact_ratio == pytest.approx(mesh.transverse_contact_ratio + mesh.face_contact_ratio, rel=1e-15)


def line_of_action_contact(g1: GearSpec, g2: GearSpec, a: float, ra1: float, ra2: float):
    """Path of contact built directly: the common internal tangent of the base circles, clipped by
    both tip circles and by its tangent points. Returns (length, radius on gear 1 where gear 2's tip
    meets the line, radius on gear 2 where gear 1's tip meets it)."""
    rb1, rb2 = g1.base_radius, g2.base_radius
    o1, o2 = np.array([0.0, 0.0]), np.array([a, 0.0])
    cos_w = (rb1 + rb2) / a
    d = np.array([math.sqrt(1 - cos_w ** 2), cos_w])  # line direction
    p = np.array([a * rb1 / (rb1 + rb2), 0.0])  # the tangents cross the line of centres in the ratio rb1 : rb2

    def chord(centre, radius):  # parameters of the line inside a circle
        f = p - centre
        b, cc = f @ d, f @ f - radius ** 2
        root = math.sqrt(b * b - cc)
        return -b - root, -b + root

    t1 = -(p - o1) @ d  # foot of the perpendicular from each centre: the tangent points
    t2 = -(p - o2) @ d
    lo1, hi1 = chord(o1, ra1)
    lo2, hi2 = chord(o2, ra2)
    lo, hi = max(lo1, lo2, min(t1, t2)), min(hi1, hi2, max(t1, t2))
    # the mate's tip reaches each gear where its own chord ends inside the other gear
    end_on_1 = p + (lo2 if abs(lo2 - t1) < abs(hi2 - t1) else hi2) * d
    end_on_2 = p + (lo1 if abs(lo1 - t2) < abs(hi1 - t2) else hi1) * d
    return hi - lo, float(np.linalg.norm(end_on_1 - o1)), float(np.linalg.norm(end_on_2 - o2))


def test_paper_gears():
    c = DATA["paper_robot_joint"]
    m = module_from_diametral_pitch(c["diametral_pitch_per_in"])
    gears = [spec(teeth=z, module=m, pressure_angle=c["pressure_angle_deg"] * DEG, face_width=6.35) for z in c["teeth"]]
    for g, text in zip(gears, c["expected"]["reference_diameter_in"]):
        assert printed(from_mm(2 * g.reference_radius, "in"), text)
        # base radius from the definition: r cos(phi), phi = 20 deg, r = N / (2 P)
        r_in = g.teeth / (2 * c["diametral_pitch_per_in"])
        assert from_mm(g.base_radius, "in") == pytest.approx(r_in * math.cos(20 * DEG), rel=1e-14)
    for (i, j), text in zip(c["meshes"], c["expected"]["standard_centre_distance_in"]):
        pair = GearPair(gears[i], gears[j])
        mesh = geo.mesh_geometry(pair)
        assert printed(from_mm(mesh.centre_distance, "in"), text)
        assert mesh.centre_distance == pytest.approx(pair.standard_centre_distance, rel=1e-15)
        length, sap1, sap2 = line_of_action_contact(gears[i], gears[j], mesh.centre_distance,
                                                    gears[i].tip_radius, gears[j].tip_radius)
        base_pitch = 2 * math.pi * gears[i].base_radius / gears[i].teeth
        assert mesh.transverse_contact_ratio == pytest.approx(length / base_pitch, abs=1e-12)
        assert mesh.active_profile_start_radii == pytest.approx((sap1, sap2), abs=1e-12)
        assert mesh.face_contact_ratio == 0.0
        assert 1.4 < mesh.transverse_contact_ratio < 1.8  # sanity: full-depth 20 deg spur pairs


def test_contact_ratio_at_a_widened_centre_distance_matches_line_of_action():
    # the paper's mesh 1 runs at 1.004 in instead of 1.000 in
    m = module_from_diametral_pitch(32)
    g1, g2 = spec(teeth=16, module=m), spec(teeth=48, module=m)
    a = 1.004 * 25.4
    mesh = geo.mesh_geometry(GearPair(g1, g2), centre_distance=a)
    length, *_ = line_of_action_contact(g1, g2, a, g1.tip_radius, g2.tip_radius)
    assert mesh.transverse_contact_ratio == pytest.approx(length / (2 * math.pi * g1.base_radius / 16), abs=1e-12)
    assert mesh.transverse_contact_ratio < geo.mesh_geometry(GearPair(g1, g2)).transverse_contact_ratio


def test_undercut_limit_matches_published():
    c = DATA["undercut_limit"]
    for deg, text in zip(c["pressure_angle_deg"], c["minimum_teeth"]):
        z = geo.minimum_teeth_without_undercut(deg * DEG, dedendum_coefficient=1.0, rack_tip_radius_coefficient=0.0)
        assert printed(z, text)


def test_span_matches_published():
    c = DATA["span_spur"]
    g = spec(teeth=c["teeth"], module=c["module_mm"], pressure_angle=c["pressure_angle_deg"] * DEG,
             profile_shift=c["profile_shift"])
    e = c["expected"]
    span = geo.span_measurement(g)
    assert span.teeth_spanned == e["teeth_spanned"]
    assert printed(span.span, e["span_mm"])
    assert printed(2 * span.contact_radius, e["contact_diameter_mm"])
    assert printed(geo.span_length(g, 4) - geo.span_length(g, 3), e["base_pitch_mm"])


# ---------------------------------------------------------------------------------------------
# Working pressure angle and centre distance
# ---------------------------------------------------------------------------------------------

def test_working_centre_distance_and_inverse_round_trip_on_arrays():
    shifts = np.linspace(-0.8, 2.0, 28).reshape(7, 4)
    for beta in (0.0, 15 * DEG, 35 * DEG):
        aw = geo.working_centre_distance(shifts, 57, 1.25, 20 * DEG, beta)
        assert aw.shape == (7, 4)
        back = geo.shift_sum_for_centre_distance(aw, 57, 1.25, 20 * DEG, beta)
        np.testing.assert_allclose(back, shifts, rtol=0, atol=1e-11)
        # more shift, wider centre distance; zero shift is the standard distance
        assert np.all(np.diff(aw.ravel()) > 0)
    a0 = geo.working_centre_distance(0.0, 57, 1.25, 20 * DEG, 35 * DEG)
    assert a0 == pytest.approx(57 * 1.25 / (2 * math.cos(35 * DEG)), rel=1e-15)


def test_working_pressure_angle_is_where_shifted_teeth_fill_the_working_pitch():
    # independent: at the working pitch circles the two tooth thicknesses add up to the pitch,
    # thicknesses measured on the numerically built flanks
    g1, g2 = spec(teeth=13, profile_shift=0.45), spec(teeth=29, profile_shift=0.2)
    mesh = geo.mesh_geometry(GearPair(g1, g2))
    pitch = 0.0
    for g, r_w in zip((g1, g2), mesh.working_pitch_radii):
        f = Flank(g, 0.0, +1)
        x, y, _ = f.point(f.roll_at_radius(r_w))
        pitch += 2 * r_w * math.atan2(y, x)
    assert pitch == pytest.approx(2 * math.pi * mesh.working_pitch_radii[0] / 13, abs=1e-12)


# ---------------------------------------------------------------------------------------------
# Backlash
# ---------------------------------------------------------------------------------------------

def half_gap_on_line_of_action(g1: GearSpec, g2: GearSpec, a: float) -> float:
    """Gear 1's tooth centred on the line of centres sits in gear 2's space; the gap, along the line
    of action, between gear 1's flank and the facing flank of gear 2 (positive: clearance)."""
    rb1, rb2 = g1.base_radius, g2.base_radius
    cos_w = (rb1 + rb2) / a
    p = np.array([a * rb1 / (rb1 + rb2), 0.0])
    flank1 = Flank(g1, 0.0, +1)
    flank2 = Flank(g2, math.pi - math.pi / g2.teeth, +1)  # gear 2's tooth just above its space at angle pi
    o2 = np.array([a, 0.0])
    for d in (np.array([math.sqrt(1 - cos_w ** 2), cos_w]), np.array([-math.sqrt(1 - cos_w ** 2), cos_w])):
        def crossing(fl, origin):
            f = lambda t: cross2(origin + fl.point(t)[:2] - p, d)
            ts = roots_on_grid(f, 1e-6, 3.0)
            return [origin + fl.point(t)[:2] for t in ts], [fl.normal(t)[:2] for t in ts]
        q1s, n1s = crossing(flank1, np.zeros(2))
        for q1, n1 in zip(q1s, n1s):
            n1 = n1 / np.linalg.norm(n1)  # transverse part of the flank normal
            if abs(cross2(n1, d)) > 1e-9:  # this line is not normal to the flank here
                continue
            q2s, n2s = crossing(flank2, o2)
            q2, n2 = min(zip(q2s, n2s), key=lambda qn: np.linalg.norm(qn[0] - q1))
            assert abs(cross2(n2 / np.linalg.norm(n2), d)) < 1e-9  # also normal to gear 2's flank: the line of action
            outward = n1 if n1[1] > 0 else -n1  # gear 1's tooth is centred on +x; this flank faces +y
            return float((q2 - q1) @ outward)
    raise AssertionError("no line of action found")


BACKLASH_PAIRS = [
    (dict(teeth=16), dict(teeth=48), 0.0),
    (dict(teeth=12, profile_shift=0.6, thinning=0.05), dict(teeth=24, profile_shift=0.36, thinning=0.02), 0.0),
    (dict(teeth=21, thinning=0.03), dict(teeth=112, profile_shift=-0.2), 0.1),
    (dict(teeth=14, helix_angle=30 * DEG, profile_shift=0.3, thinning=0.04),
     dict(teeth=33, helix_angle=30 * DEG, hand="left", profile_shift=0.1, thinning=0.01), 0.05),
    (dict(teeth=15, helix_angle=12 * DEG, hand="left"), dict(teeth=19, helix_angle=12 * DEG), -0.01),
]


@pytest.mark.parametrize("kw1, kw2, extra", BACKLASH_PAIRS)
def test_backlash_matches_line_of_action_construction(kw1, kw2, extra):
    g1, g2 = spec(**kw1), spec(**kw2)
    pair = GearPair(g1, g2)
    a = geo.mesh_geometry(pair).centre_distance + extra
    b = geo.backlash_at_centre_distance(pair, a)
    assert b.base_tangent == pytest.approx(2 * half_gap_on_line_of_action(g1, g2, a), abs=1e-9)
    assert b.circumferential == pytest.approx(b.base_tangent / math.cos(b.working_pressure_angle), rel=1e-14)
    # normal backlash: tilt of the flank normal out of the transverse plane, read off the helicoid
    n = Flank(g1, 0.0, +1).normal(1.0)
    assert b.normal == pytest.approx(b.base_tangent * math.hypot(n[0], n[1]), abs=1e-12)
    assert b.angular1 * g1.base_radius == pytest.approx(b.base_tangent, abs=1e-13)
    assert b.angular2 * g2.base_radius == pytest.approx(b.base_tangent, abs=1e-13)


def test_backlash_at_the_shift_centre_distance_is_the_thinning():
    g1, g2 = spec(teeth=12, profile_shift=0.6, thinning=0.05), spec(teeth=24, profile_shift=0.36, thinning=0.02)
    pair = GearPair(g1, g2)
    b = geo.backlash_at_centre_distance(pair, geo.mesh_geometry(pair).centre_distance)
    # a_w from the shifts makes the unthinned teeth touch; thinning (arc on the reference circle)
    # becomes base-circle arc times cos(alpha_t)
    assert b.base_tangent == pytest.approx(0.07 * math.cos(20 * DEG), abs=1e-13)
    assert geo.backlash_at_centre_distance(pair, geo.tight_mesh_centre_distance(pair)).circumferential == \
        pytest.approx(0.0, abs=1e-12)


def test_backlash_from_centre_distance_change():
    g1, g2 = spec(teeth=18, module=3.0), spec(teeth=30, module=3.0)
    pair = GearPair(g1, g2)
    a_w = geo.tight_mesh_centre_distance(pair)
    assert a_w == pytest.approx(72.0, rel=1e-15)
    da = np.array([1e-5, 1e-4, 1e-3, 1e-2])
    b = geo.backlash_at_centre_distance(pair, a_w + da)
    assert b.normal.shape == (4,)
    # small changes: j_n ~ 2 da sin(alpha_w), error of second order in da
    for jn, d in zip(b.normal, da):
        assert abs(jn - 2 * d * math.sin(20 * DEG)) < 2 * d * d
    assert abs(b.normal[0] - 2 * da[0] * math.sin(20 * DEG)) < 1e-9
    # exact: j_n = (z1 + z2) m cos(alpha) (inv(alpha_w') - inv(alpha_w)), computed here from scratch
    alpha_new = np.arccos(72.0 * math.cos(20 * DEG) / (a_w + da))
    inv = lambda x: np.tan(x) - x
    np.testing.assert_allclose(b.normal, 48 * 3.0 * math.cos(20 * DEG) * (inv(alpha_new) - inv(20 * DEG)),
                               rtol=1e-11, atol=1e-15)
    np.testing.assert_allclose(b.centre_distance_change, da, rtol=1e-9)


# ---------------------------------------------------------------------------------------------
# Undercut and start of the involute
# ---------------------------------------------------------------------------------------------

def rack_penetration(g: GearSpec, u, v):
    """How deep transverse rack point(s) (u, v) lie inside the rack tooth cutting the space at u = 0
    (v outward from the gear, 0 on the rolling line); negative outside. Rack in its normal section:
    pi m_n / 2 wide (plus thinning) on the datum line x m_n outside the rolling line, flanks at
    alpha_n, tip h_f* m_n inside the datum line, tip fillet of radius rho tangent to tip and flank."""
    m_n, a_n = g.module, g.pressure_angle
    un = np.abs(u) * math.cos(g.helix_angle)
    datum = g.profile_shift * m_n
    tip = datum - g.dedendum_coefficient * m_n
    rho = g.rack_tip_radius_coefficient * m_n
    half = lambda vv: math.pi * m_n / 4 + g.thinning * math.cos(g.helix_angle) / 2 + (vv - datum) * math.tan(a_n)
    vc = tip + rho
    uc = half(vc) - rho / math.cos(a_n)
    pen = np.minimum(v - tip, half(v) - un)
    corner = (un > uc) & (v < vc)
    return np.where(corner, np.minimum(pen, rho - np.hypot(un - uc, v - vc)), pen)


def max_cut(g: GearSpec, radius: float) -> float:
    """Largest penetration of the rack into the involute point at ``radius`` while it rolls by."""
    flank = Flank(g, math.pi / 2 - math.pi / g.teeth, +1)  # borders the space centred on +y
    px, py, _ = flank.point(flank.roll_at_radius(radius))
    r = g.reference_radius

    def pen(phi):
        phi = np.asarray(phi)
        fx, fy = np.cos(phi) * px - np.sin(phi) * py, np.sin(phi) * px + np.cos(phi) * py
        return rack_penetration(g, fx + r * phi, fy - r)

    span = 3 * math.pi / g.teeth
    phis = np.linspace(-span, span, 40001)
    vals = pen(phis)
    best = vals.max()
    # the corner of the rack grazes the point in a peak far narrower than the grid: refine every
    # local maximum of the grid, not only the largest values
    peaks = np.nonzero((vals[1:-1] >= vals[:-2]) & (vals[1:-1] >= vals[2:]))[0] + 1
    for i in peaks:
        res = minimize_scalar(lambda f: -float(pen(f)), bounds=(phis[i - 1], phis[i + 1]), method="bounded",
                              options={"xatol": 1e-15})
        best = max(best, -res.fun)
    return float(best)


UNDERCUT_CASES = [
    dict(teeth=10, module=1.0),
    dict(teeth=16, module=1.0),
    dict(teeth=10, module=1.0, rack_tip_radius_coefficient=0.0),  # sharp rack corner: trochoid
    dict(teeth=9, module=1.0, helix_angle=30 * DEG),  # elliptical fillet in the transverse section
    dict(teeth=13, module=1.0, helix_angle=20 * DEG, thinning=0.1, profile_shift=-0.1),
    dict(teeth=8, module=1.0, profile_shift=0.2, pressure_angle=25 * DEG),
]


@pytest.mark.parametrize("kw", UNDERCUT_CASES)
def test_undercut_boundary_matches_rolling_the_rack_through_the_blank(kw):
    g = spec(**kw)
    u = geo.undercut(g)
    assert u.is_undercut
    lo, hi = g.base_radius * (1 + 1e-9), g.reference_radius
    assert max_cut(g, lo) > 1e-6 and max_cut(g, hi) < 1e-11
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if max_cut(g, mid) > 1e-11 else (lo, mid)
    # the brute force resolves the boundary to its penetration threshold (1e-11 mm) over the slope
    # of the penetration across the boundary: ~1e-10 mm for a fillet, ~2e-9 mm for a sharp corner
    assert u.involute_start_radius == pytest.approx(hi, abs=5e-9)


def test_involute_start_without_undercut_is_where_the_rack_flank_ends():
    for kw in (dict(teeth=30), dict(teeth=14, profile_shift=0.5), dict(teeth=25, helix_angle=25 * DEG, thinning=0.1)):
        g = spec(**kw)
        assert not geo.undercut(g).is_undercut
        # the rack flank ends where its tip fillet is tangent: rho sin(alpha_n) outside the fillet centre
        m_n = g.module
        rho = g.rack_tip_radius_coefficient * m_n
        v_end = g.profile_shift * m_n - g.dedendum_coefficient * m_n + rho - rho * math.sin(g.pressure_angle)
        # that point touches on the line of action at depth -v_end: distance -v_end / sin(alpha_t) from
        # the pitch point, measured towards the base tangent point, which is r sin(alpha_t) away
        a_t = math.atan(math.tan(g.pressure_angle) / math.cos(g.helix_angle))
        r = g.reference_radius
        pitch_point = np.array([0.0, r])
        toward_t1 = np.array([-math.cos(a_t), -math.sin(a_t)]) * 0 + np.array([math.sin(a_t) * math.cos(a_t),
                                                                               -math.sin(a_t) ** 2]) / math.sin(a_t)
        point = pitch_point + (-v_end / math.sin(a_t)) * toward_t1
        assert geo.involute_start_radius(g) == pytest.approx(float(np.linalg.norm(point)), abs=1e-12)


def test_undercut_limit_and_minimum_shift():
    z_min = geo.minimum_teeth_without_undercut(20 * DEG, 0.0, 0.0, 1.25, 0.38)
    assert 17 < z_min < 17.1
    assert geo.undercut(spec(teeth=17)).is_undercut and not geo.undercut(spec(teeth=18)).is_undercut
    z = np.array([10, 14, 20])
    assert geo.minimum_teeth_without_undercut(20 * DEG, profile_shift=z * 0.1).shape == (3,)
    for kw in (dict(teeth=11), dict(teeth=8, helix_angle=28 * DEG), dict(teeth=24, pressure_angle=14.5 * DEG)):
        g = spec(**kw)
        x_min = geo.undercut(g).minimum_profile_shift
        at_limit = spec(**kw, profile_shift=x_min)
        # at x_min the rack flank ends exactly at the interference point: the involute starts at the base circle
        assert geo.involute_start_radius(at_limit) == pytest.approx(g.base_radius, abs=1e-6)
        z_min = geo.minimum_teeth_without_undercut(g.pressure_angle, g.helix_angle, x_min, 1.25,
                                                   g.rack_tip_radius_coefficient)
        assert z_min == pytest.approx(g.teeth, rel=1e-12)
        assert geo.undercut(spec(**kw, profile_shift=x_min - 0.01)).is_undercut
        for dx in (1e-6, 1e-9):  # barely undercut: the involute starts at the base circle
            barely = spec(**kw, profile_shift=x_min - dx)
            assert geo.undercut(barely).is_undercut
            assert geo.involute_start_radius(barely) == pytest.approx(g.base_radius, rel=1e-9)
        assert not geo.undercut(spec(**kw, profile_shift=x_min + 0.01)).is_undercut


def test_tip_land():
    g = spec(teeth=25, helix_angle=30 * DEG, profile_shift=0.3)
    land = geo.check_tip_land(g, minimum_thickness=0.2 * g.module)
    f = Flank(g, 0.0, +1)
    x, y, _ = f.point(f.roll_at_radius(g.tip_radius))
    assert land.thickness == pytest.approx(2 * g.tip_radius * math.atan2(y, x), abs=1e-12)
    # the tooth band on the tip cylinder, unrolled, is bounded by helices of lead L: tan(beta_a) = 2 pi r_a / L
    beta_a = math.atan(2 * math.pi * g.tip_radius / g.lead)
    assert land.normal_thickness == pytest.approx(land.thickness * math.cos(beta_a), rel=1e-13)
    assert not land.is_pointed and land.pointed_radius > g.tip_radius
    pointed = spec(teeth=8, profile_shift=0.9, addendum_coefficient=1.2)
    assert geo.tip_land(pointed).is_pointed
    with pytest.raises(GeometryError) as err:
        geo.check_tip_land(pointed)
    assert err.value.kind == "pointed_tooth"
    with pytest.raises(GeometryError, match="pointed_tooth"):
        geo.check_tip_land(g, minimum_thickness=land.thickness * 1.01)


# ---------------------------------------------------------------------------------------------
# Span measurement
# ---------------------------------------------------------------------------------------------

def _tangent_plane_partner(a: Flank, b: Flank, ta: float, t_max: float):
    """Points of flank b whose normal is parallel to flank a's normal at roll ta (section w = 0)."""
    na = a.normal(ta)
    out = []
    for tb in roots_on_grid(lambda t: cross2(na, b.normal(t)), 1e-3, t_max, 200):
        nb = b.normal(tb)  # (the sign of a normal from the parametrisation is arbitrary)
        assert np.linalg.norm(np.cross(na, nb)) < 1e-12  # parallel in 3-D too, not only in the section
        out.append(tb)
    return na, out


def measured_span(g: GearSpec, k: int) -> float:
    """Distance between the two parallel planes that touch the outer flanks of k teeth.

    A plane touches a flank where the flank's normal is the plane's normal: take a point on one
    flank, find the point of the other flank with the same normal direction, and measure the
    distance between the two tangent planes."""
    a = Flank(g, 0.0, -1)
    b = Flank(g, 2 * math.pi * (k - 1) / g.teeth, +1)
    t_tip = a.roll_at_radius(g.tip_radius)
    results = []
    for frac in (0.35, 0.5, 0.65, 0.8):
        ta = frac * t_tip
        na, partners = _tangent_plane_partner(a, b, ta, 2 * t_tip)
        results += [abs(na @ (b.point(tb) - a.point(ta))) for tb in partners]
    assert len(results) >= 2
    # the span does not depend on where the planes touch (base tangent length property)
    assert max(results) - min(results) < 1e-10
    return results[0]


def measured_symmetric_contact_radius(g: GearSpec, k: int) -> float:
    """Radius at which both anvils touch when they touch at equal radii in one transverse section.

    A plane touches a helicoid along a straight generator (the surface is developable): the line
    through the contact point perpendicular to the normal within the plane spanned by the normal
    and the axis. Flank a's contact is taken in the section w = 0; flank b's contact line is
    followed to that section; the roll on a is adjusted until both radii agree."""
    a = Flank(g, 0.0, -1)
    b = Flank(g, 2 * math.pi * (k - 1) / g.teeth, +1)
    t_tip = a.roll_at_radius(g.tip_radius)

    def radius_difference(ta):
        na, partners = _tangent_plane_partner(a, b, ta, 2 * t_tip)
        pb = b.point(partners[0])
        axis = np.array([0.0, 0.0, 1.0])
        line = axis - (axis @ na) * na
        on_section = pb - pb[2] / line[2] * line
        return float(np.hypot(*a.point(ta)[:2]) - np.hypot(*on_section[:2]))

    ta = brentq(radius_difference, 0.2 * t_tip, t_tip, xtol=1e-15)
    return float(np.hypot(*a.point(ta)[:2]))


SPAN_CASES = [
    (dict(teeth=20), 3),
    (dict(teeth=21, profile_shift=0.5), 3),
    (dict(teeth=48, thinning=0.1, profile_shift=-0.25), 6),
    (dict(teeth=17, helix_angle=20 * DEG, profile_shift=0.2, thinning=0.05), 3),
    (dict(teeth=40, helix_angle=35 * DEG, hand="left", module=1.25, thinning=0.03), 6),
    (dict(teeth=112, module=25.4 / 32, face_width=6.35), 13),
]


@pytest.mark.parametrize("kw, k", SPAN_CASES)
def test_span_matches_parallel_tangent_planes(kw, k):
    g = spec(**kw)
    assert geo.span_length(g, k) == pytest.approx(measured_span(g, k), abs=1e-9)
    ks = np.array([[k - 1, k], [k + 1, k + 2]])
    w = geo.span_length(g, ks)
    assert w.shape == (2, 2)
    assert w[0, 1] == pytest.approx(measured_span(g, k), abs=1e-9)


@pytest.mark.parametrize("kw, k", SPAN_CASES)
def test_span_contact_radius_and_recommendation(kw, k):
    g = spec(**kw)
    m = geo.span_measurement(g, k)
    assert m.contact_radius == pytest.approx(measured_symmetric_contact_radius(g, k), abs=1e-9)
    assert m.involute_start_radius <= m.contact_radius <= g.tip_radius
    k_best = geo.recommended_teeth_spanned(g)
    # the recommendation puts the contact nearest the middle of the working depth
    target = g.reference_radius + g.profile_shift * g.module
    dist = lambda kk: abs(float(geo.span_contact_radius(g, kk)) - target)
    assert dist(k_best) <= min(dist(k_best - 1), dist(k_best + 1))


def test_span_errors():
    g = spec(teeth=20)
    for bad in (0, 20, 2.5, -1):
        with pytest.raises(DesignError) as err:
            geo.span_length(g, bad)
        assert err.value.field == "teeth_spanned"
    with pytest.raises(GeometryError, match="above the tip radius") as err:
        geo.span_measurement(g, 8)
    assert err.value.kind == "span_contact"
    with pytest.raises(GeometryError, match="below the start of the involute"):
        geo.span_measurement(spec(teeth=60), 1)
    narrow = spec(teeth=40, helix_angle=30 * DEG, face_width=5.0)
    with pytest.raises(GeometryError) as err:
        geo.span_measurement(narrow)
    assert err.value.kind == "span_face_width"


# ---------------------------------------------------------------------------------------------
# Measurement over pins and balls
# ---------------------------------------------------------------------------------------------

def foot_point(flank: Flank, c: np.ndarray, t0: float):
    """Nearest point of the flank surface to ``c``: (distance, roll t, axial w).

    Least squares finds the distance (accurate to second order); the location is then polished by
    solving the foot-point conditions (P - c) . dP/dt = (P - c) . dP/dw = 0 directly."""
    res = least_squares(lambda p: flank.point(p[0], p[1]) - c, x0=[t0, 0.0],
                        jac=lambda p: np.column_stack([flank.d_t(p[0], p[1]), flank.d_w(p[0], p[1])]),
                        method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15)
    conditions = lambda p: [(flank.point(*p) - c) @ flank.d_t(*p), (flank.point(*p) - c) @ flank.d_w(*p)]
    sol = root(conditions, res.x, method="hybr", options={"xtol": 1e-15})
    t, w = sol.x
    return float(np.linalg.norm(flank.point(t, w) - c)), t, w


def measured_over_pins(g: GearSpec, d: float):
    """Press a ball of diameter d into the tooth space at polar angle pi/z (section w = 0) until it
    touches the flank; measure over it and the ball in the (nearly) opposite space, same section."""
    flank = Flank(g, 0.0, +1)
    other = Flank(g, 2 * math.pi / g.teeth, -1)
    direction = np.array([math.cos(math.pi / g.teeth), math.sin(math.pi / g.teeth), 0.0])

    def gap(radius):
        dist, *_ = foot_point(flank, radius * direction, flank.roll_at_radius(radius))
        return dist - d / 2

    guess = float(geo.pin_centre_radius(g, d))  # only to place the bracket
    rc = brentq(gap, guess - 0.2 * g.module, guess + 0.2 * g.module, xtol=1e-14)
    dist, t, w = foot_point(flank, rc * direction, flank.roll_at_radius(rc))
    dist_other, *_ = foot_point(other, rc * direction, other.roll_at_radius(rc))
    assert dist_other == pytest.approx(d / 2, abs=1e-10)  # it touches both flanks of the space
    contact_radius = float(np.hypot(*flank.point(t, w)[:2]))
    j = g.teeth // 2  # even: the opposite space; odd: the space pi (1 - 1/z) away
    angle = 2 * math.pi * j / g.teeth
    turn = np.array([[math.cos(angle), -math.sin(angle), 0], [math.sin(angle), math.cos(angle), 0], [0, 0, 1]])
    second = turn @ (rc * direction)
    return float(np.linalg.norm(second - rc * direction)) + d, rc, contact_radius


PIN_CASES = [
    (dict(teeth=20), None),
    (dict(teeth=21), 3.5),
    (dict(teeth=12, profile_shift=0.5, thinning=0.06), None),
    (dict(teeth=37, profile_shift=-0.3, thinning=0.1), 3.2),
    (dict(teeth=24, helix_angle=25 * DEG), None),
    (dict(teeth=25, helix_angle=25 * DEG, hand="left", thinning=0.05), 3.3),
    (dict(teeth=15, helix_angle=40 * DEG, profile_shift=0.4, module=1.0), None),
    (dict(teeth=112, module=25.4 / 32, face_width=6.35), None),
]


@pytest.mark.parametrize("kw, d", PIN_CASES)
def test_over_pins_matches_a_ball_pressed_into_the_space(kw, d):
    g = spec(**kw)
    m = geo.over_pins_measurement(g, d)
    assert m.kind == ("balls" if g.is_helical else "pins")
    dimension, rc, contact = measured_over_pins(g, m.pin_diameter)
    assert m.dimension == pytest.approx(dimension, abs=1e-9)
    assert m.centre_radius == pytest.approx(rc, abs=1e-10)
    assert m.contact_radius == pytest.approx(contact, abs=1e-9)
    if d is None:  # the ideal pin touches on the reference circle
        assert contact == pytest.approx(g.reference_radius, abs=1e-9)
    sizes = m.pin_diameter * np.array([0.95, 1.0, 1.05])
    assert geo.over_pins_dimension(g, sizes).shape == (3,)
    assert geo.over_pins_dimension(g, sizes)[1] == pytest.approx(m.dimension, rel=1e-15)


def test_ideal_pin_at_other_radii():
    for kw in (dict(teeth=30), dict(teeth=30, helix_angle=30 * DEG)):
        g = spec(**kw)
        for radius in (g.reference_radius - 0.5 * g.module, g.reference_radius + 0.5 * g.module):
            d = geo.ideal_pin_diameter(g, radius)
            _, _, contact = measured_over_pins(g, d)
            assert contact == pytest.approx(radius, abs=1e-9)


def test_pin_errors():
    g = spec(teeth=20)
    with pytest.raises(DesignError) as err:
        geo.over_pins_measurement(g, -1.0)
    assert err.value.field == "pin_diameter"
    with pytest.raises(GeometryError) as err:
        geo.over_pins_measurement(g, 0.3 * g.module)
    assert err.value.kind == "pin_contact"
    with pytest.raises(GeometryError, match="above the tip radius"):
        geo.over_pins_measurement(g, 4 * g.module)
    with pytest.raises(DesignError) as err:
        geo.ideal_pin_diameter(g, g.tip_radius + 1)
    assert err.value.field == "contact_radius"


# ---------------------------------------------------------------------------------------------
# Pair validation and other errors
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("kw1, kw2, field", [
    ({}, dict(module=2.5), "gear2.module"),
    ({}, dict(pressure_angle=25 * DEG), "gear2.pressure_angle"),
    (dict(helix_angle=15 * DEG), dict(helix_angle=20 * DEG, hand="left"), "gear2.helix_angle"),
    ({}, dict(helix_angle=15 * DEG), "gear2.helix_angle"),
    (dict(helix_angle=15 * DEG), dict(helix_angle=15 * DEG), "gear2.hand"),
])
def test_pair_mismatch_names_the_field(kw1, kw2, field):
    with pytest.raises(DesignError) as err:
        GearPair(spec(**kw1), spec(**kw2))
    assert err.value.field == field


def test_valid_pairs():
    GearPair(spec(hand="left"), spec(hand="left"))  # spur: the hand means nothing
    GearPair(spec(helix_angle=15 * DEG, hand="left"), spec(teeth=31, helix_angle=15 * DEG, hand="right"))


def test_other_errors_name_the_field():
    pair = GearPair(spec(teeth=20), spec(teeth=30))
    cases = [
        (lambda: GearPair("gear", spec()), "gear1"),
        (lambda: geo.mesh_geometry(pair, tip_radii="short"), "tip_radii"),
        (lambda: geo.mesh_geometry(pair, centre_distance=40.0), "centre_distance"),
        (lambda: geo.mesh_geometry(pair, face_width=0.0), "face_width"),
        (lambda: geo.backlash_at_centre_distance(pair, [50.0, 45.0]), "centre_distance"),
        (lambda: geo.shift_sum_for_centre_distance(40.0, 50, 2.0, 20 * DEG), "centre_distance"),
        (lambda: geo.working_pressure_angle(-20.0, 50, 20 * DEG), "profile_shift"),
    ]
    for call, field in cases:
        with pytest.raises(DesignError) as err:
            call()
        assert err.value.field == field


def test_interference_flag_matches_line_of_action():
    # 10 teeth against 60: the big gear's tip circle reaches past the pinion's interference point
    # (the tangent point T1 of the line of action on the pinion's base circle)
    g1, g2 = spec(teeth=10), spec(teeth=60)
    mesh = geo.mesh_geometry(GearPair(g1, g2))
    rb1, rb2, a = g1.base_radius, g2.base_radius, mesh.centre_distance
    cos_w = (rb1 + rb2) / a
    t1 = rb1 * np.array([cos_w, -math.sqrt(1 - cos_w ** 2)])
    assert np.linalg.norm(t1 - np.array([a, 0.0])) < g2.tip_radius
    assert mesh.involute_interference == (True, False)
    # shifted 0.5 the pinion has no undercut and the mate's tip stays on its involute
    shifted = spec(teeth=10, profile_shift=0.5)
    mesh = geo.mesh_geometry(GearPair(shifted, g2))
    _, sap1, sap2 = line_of_action_contact(shifted, g2, mesh.centre_distance, shifted.tip_radius, g2.tip_radius)
    assert mesh.active_profile_start_radii == pytest.approx((sap1, sap2), abs=1e-12)
    assert sap1 > geo.involute_start_radius(shifted) and sap2 > geo.involute_start_radius(g2)
    assert mesh.involute_interference == (False, False)
    # shifted 0.8 the mate's tip reaches below where the involute begins
    shifted = spec(teeth=10, profile_shift=0.8, addendum_coefficient=0.8)
    mesh = geo.mesh_geometry(GearPair(shifted, g2))
    _, sap1, _ = line_of_action_contact(shifted, g2, mesh.centre_distance, shifted.tip_radius, g2.tip_radius)
    assert sap1 < geo.involute_start_radius(shifted) and mesh.involute_interference == (True, False)
