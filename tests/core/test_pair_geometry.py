"""The pair quantities geargen.core.geometry gained for ``geargen pair``, against independent
constructions: specific sliding from the velocities of the two bodies at points of the line of
action built from the base and tip circles; the balanced split of a shift sum checked with those
velocities; the normal working pressure angle from the working helix angle; the circumferential
backlash at the reference circle from the involute function written out here (tan a - a)."""

import math

import numpy as np
import pytest

from geargen.core import geometry as geo
from geargen.core.geometry import GearPair
from geargen.design.gear import GearSpec

DEG = math.pi / 180


def spec(**kw) -> GearSpec:
    base = dict(teeth=20, module=2.0, pressure_angle=20 * DEG, face_width=30.0)
    base.update(kw)
    return GearSpec(**base)


def inv(angle: float) -> float:
    return math.tan(angle) - angle


def sliding_by_velocities(g1: GearSpec, g2: GearSpec, a: float):
    """Specific sliding at the ends of the path of contact, from body velocities.

    Gear 1 at the origin turning at omega_1 = 1, gear 2 at (a, 0) at omega_2 = -z1/z2. The line
    of action is the internal common tangent of the base circles; its ends are where it leaves
    the tip circles. At a point P the flanks' common tangent is perpendicular to the line, and each
    flank moves past the contact at the tangential component of omega x (P - O) of its body.
    Returns ((root 1, root 2), (tip 1, tip 2)): gear 1's root is where gear 2's tip meets the line.
    """
    rb1, rb2 = g1.base_radius, g2.base_radius
    o1, o2 = np.array([0.0, 0.0]), np.array([a, 0.0])
    cos_w = (rb1 + rb2) / a
    d = np.array([math.sqrt(1 - cos_w ** 2), cos_w])
    tangent = np.array([-d[1], d[0]])
    pitch_point = np.array([a * rb1 / (rb1 + rb2), 0.0])
    w1, w2 = 1.0, -g1.teeth / g2.teeth

    def zeta(p, own):
        v1 = w1 * np.array([-(p - o1)[1], (p - o1)[0]]) @ tangent
        v2 = w2 * np.array([-(p - o2)[1], (p - o2)[0]]) @ tangent
        return (v1 - v2) / v1 if own == 1 else (v2 - v1) / v2

    def tip_end(centre, radius, towards):
        # the two crossings of the line with a tip circle; the one nearer the point ``towards``
        f = pitch_point - centre
        b, c = f @ d, f @ f - radius ** 2
        ends = [pitch_point + (-b + s * math.sqrt(b * b - c)) * d for s in (-1, 1)]
        return min(ends, key=lambda e: np.linalg.norm(e - towards))

    t1 = o1 + rb1 * np.array([d[1], -d[0]]) * np.sign(np.array([d[1], -d[0]]) @ (pitch_point - o1))
    t2 = o2 + rb2 * np.array([-d[1], d[0]]) * np.sign(np.array([-d[1], d[0]]) @ (pitch_point - o2))
    start = tip_end(o2, g2.tip_radius, t1)  # gear 2's tip: gear 1's root contact
    end = tip_end(o1, g1.tip_radius, t2)  # gear 1's tip: gear 2's root contact
    return (zeta(start, 1), zeta(end, 2)), (zeta(end, 1), zeta(start, 2))


PAIRS = {
    "shifted spur 12/24": (dict(teeth=12, module=3.0, profile_shift=0.6), dict(teeth=24, module=3.0, profile_shift=0.36)),
    "helical 12/60": (dict(teeth=12, module=3.0, helix_angle=30 * DEG, hand="right", profile_shift=0.09809),
                      dict(teeth=60, module=3.0, helix_angle=30 * DEG, hand="left")),
    "paper 16/48": (dict(teeth=16, module=25.4 / 32), dict(teeth=48, module=25.4 / 32)),
}


@pytest.mark.parametrize("name", PAIRS)
@pytest.mark.parametrize("widen", [0.0, 0.1])
def test_specific_sliding_matches_body_velocities(name, widen):
    kw1, kw2 = PAIRS[name]
    g1, g2 = spec(**kw1), spec(**kw2)
    pair = GearPair(g1, g2)
    a = geo.mesh_geometry(pair).centre_distance + widen * g1.module
    got = geo.specific_sliding(pair, a)
    root, tip = sliding_by_velocities(g1, g2, a)
    assert got.root == pytest.approx(root, rel=1e-10)
    assert got.tip == pytest.approx(tip, rel=1e-10)
    assert got.root[0] < 0 < got.tip[0] and got.root[1] < 0 < got.tip[1]


def test_specific_sliding_is_unbounded_when_the_mate_tip_passes_the_base_tangent_point():
    # 8 teeth against 80 unshifted: the wheel's tip reaches past the pinion's interference point
    g1, g2 = spec(teeth=8, module=2.0), spec(teeth=80, module=2.0)
    assert geo.specific_sliding(GearPair(g1, g2)).root[0] == -math.inf


@pytest.mark.parametrize("name, shift_sum", [("shifted spur 12/24", 0.96), ("helical 12/60", 0.09809),
                                             ("paper 16/48", 0.0), ("paper 16/48", 0.5)])
def test_split_balances_root_sliding(name, shift_sum):
    kw1, kw2 = PAIRS[name]
    g1, g2 = spec(**kw1), spec(**kw2)
    split = geo.split_profile_shift(GearPair(g1, g2), shift_sum)
    assert split.success and split.raised_for_undercut == (False, False)
    x1, x2 = split.profile_shifts
    assert x1 + x2 == pytest.approx(shift_sum, abs=1e-12)
    h1, h2 = spec(**{**kw1, "profile_shift": x1}), spec(**{**kw2, "profile_shift": x2})
    a = geo.working_centre_distance(shift_sum, g1.teeth + g2.teeth, g1.module, g1.pressure_angle, g1.helix_angle)
    (root1, root2), _ = sliding_by_velocities(h1, h2, a)
    assert root1 == pytest.approx(root2, rel=1e-8)
    assert split.root_specific_sliding == pytest.approx((root1, root2), rel=1e-8)
    assert x1 > x2  # the pinion takes the larger share, as every split chart has it


def test_published_shifted_pair_is_nearly_the_balanced_split():
    # An observation, not a published claim: the KHK-style example pair (x 0.6 / 0.36, see
    # tests/data/published_cases.toml [shifted_spur]) lies within 0.001 of equal root sliding.
    split = geo.split_profile_shift(GearPair(spec(teeth=12, module=3.0), spec(teeth=24, module=3.0)), 0.96)
    assert split.profile_shifts == pytest.approx((0.6, 0.36), abs=1e-3)


def test_split_raises_a_shift_below_its_undercut_minimum():
    # 12/13 teeth with a sum just above the two minima together: the balanced split leaves gear 2
    # below its minimum; the rule raises it there and gives gear 1 the rest
    g1, g2 = spec(teeth=12, module=3.0), spec(teeth=13, module=3.0)
    split = geo.split_profile_shift(GearPair(g1, g2), 0.538)
    # minimum without undercut for the default rack (h_f* 1.25, tip radius 0.38 m or the largest
    # that the 0.25 m clearance holds, 0.25 / (1 - sin 20 deg) = 0.37995 m): the straight flank ends
    # h_ae* = 1.25 - rho* (1 - sin 20 deg) beyond the datum; x_min = h_ae* - z sin^2(20 deg) / 2
    rho = min(0.38, 0.25 / (1 - math.sin(20 * DEG)))
    h_ae = 1.25 - rho * (1 - math.sin(20 * DEG))
    x_min = [h_ae - z * math.sin(20 * DEG) ** 2 / 2 for z in (12, 13)]
    assert split.minimum_profile_shifts == pytest.approx(x_min, abs=1e-12)
    assert split.balanced_shifts[1] < x_min[1]
    assert split.raised_for_undercut == (False, True) and split.success
    assert split.profile_shifts == pytest.approx((0.538 - x_min[1], x_min[1]), abs=1e-12)
    assert split.profile_shifts[0] >= x_min[0]


def test_split_says_when_no_split_avoids_undercut():
    g1, g2 = spec(teeth=10, module=3.0), spec(teeth=30, module=3.0)
    split = geo.split_profile_shift(GearPair(g1, g2), -0.4)
    assert not split.success and "no split avoids undercut" in split.message


def test_normal_working_pressure_angle_from_the_working_helix():
    kw1, kw2 = PAIRS["helical 12/60"]
    g1, g2 = spec(**kw1), spec(**kw2)
    for widen in (0.0, 0.3):
        mesh = geo.mesh_geometry(GearPair(g1, g2), geo.mesh_geometry(GearPair(g1, g2)).centre_distance + widen)
        # the helix on the working pitch cylinder: tan(beta_w) = tan(beta) r_w / r; the normal
        # section there: tan(alpha_wn) = tan(alpha_wt) cos(beta_w)
        beta_w = math.atan(math.tan(30 * DEG) * mesh.working_pitch_radii[0] / g1.reference_radius)
        expected = math.atan(math.tan(mesh.working_pressure_angle) * math.cos(beta_w))
        assert mesh.normal_working_pressure_angle == pytest.approx(expected, rel=1e-13)
    spur = geo.mesh_geometry(GearPair(spec(teeth=16), spec(teeth=48)), 64.5)
    assert spur.normal_working_pressure_angle == pytest.approx(spur.working_pressure_angle, rel=1e-15)


def test_circumferential_backlash_at_the_reference_circle():
    # unshifted, unthinned spur pair opened by dC: the working pitch p_w less the two thicknesses
    # 2 r_w (pi/(2z) + inv(alpha) - inv(alpha_w)) is j_wt = 2 a' (inv(alpha_w) - inv(alpha)); on
    # the reference circles (r / r_w = cos(alpha_w) / cos(alpha)) that is 2 a (inv(alpha_w) - inv(alpha))
    m = 25.4 / 32
    g1, g2 = spec(teeth=16, module=m), spec(teeth=48, module=m)
    a0 = 32 * m
    for da in (0.004 * 25.4, 0.05, 0.3):
        a = a0 + da
        alpha_w = math.acos(a0 * math.cos(20 * DEG) / a)
        b = geo.backlash_at_centre_distance(GearPair(g1, g2), a)
        assert b.circumferential == pytest.approx(2 * a * (inv(alpha_w) - inv(20 * DEG)), rel=1e-11)
        assert b.circumferential_reference == pytest.approx(2 * a0 * (inv(alpha_w) - inv(20 * DEG)), rel=1e-11)
        # first order: 2 dC tan(alpha)
        assert b.circumferential_reference == pytest.approx(2 * da * math.tan(20 * DEG), rel=0.05)
    # shifted, thinned helical pair at the working centre distance of its shifts: the free play on
    # the reference circles is exactly the thinning taken off the two teeth there
    kw1, kw2 = PAIRS["helical 12/60"]
    g1, g2 = spec(**kw1, thinning=0.03), spec(**kw2, thinning=0.05)
    b = geo.backlash_at_centre_distance(GearPair(g1, g2), geo.mesh_geometry(GearPair(g1, g2)).centre_distance)
    assert b.circumferential_reference == pytest.approx(0.08, rel=1e-10)


def test_profile_shift_limits_put_the_tip_on_the_base_circle():
    # lowest shift: r + (1 + x) m = r cos(alpha_t), i.e. x = -1 - z (1 - cos(alpha_t)) / (2 cos(beta))
    for kw in (dict(teeth=12, module=3.0), dict(teeth=10, module=1.0, helix_angle=20 * DEG)):
        g = spec(**kw)
        alpha_t = math.atan(math.tan(20 * DEG) / math.cos(g.helix_angle))
        lowest = -1 - g.teeth * (1 - math.cos(alpha_t)) / (2 * math.cos(g.helix_angle))
        assert geo.profile_shift_limits(g) == pytest.approx((lowest, 1.5), abs=1e-12)
    # for many teeth GearSpec's -1.5 is the tighter bound
    assert geo.profile_shift_limits(spec(teeth=200)) == (-1.5, 1.5)
