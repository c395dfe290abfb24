"""Helical dual pinions sliding into mesh: the closed form of geargen.core.flexures.helical_engagement
against an independent kinematic solve on the exact involute helicoids.

The solve knows nothing of the rates: it places the gears' exact transverse outlines
(geargen.profile.tooth) at a section plane, slides the cluster along its axis, finds by root-finding
the cluster turn that keeps the large gear's working flank where it was against the held input
pinion, and measures by geometry (how far each gear can turn before its outline meets the other's)
what that does to the gap at the output mesh.
"""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from geargen.core import flexures as fx
from geargen.core.synthesis import mate_rotation
from geargen.design.gear import gear_from_table
from geargen.errors import DesignError
from geargen.profile.tooth import section_rotation, tooth_profile

C_AXIS = Path(__file__).resolve().parents[2] / "assemblies" / "c_axis.toml"

# ---------------------------------------------------------------------------------------------
# the independent solve: first contact of two exact outlines turned about one centre


def _near_segments(profile, centre, angle, other_centre, reach, teeth_each_side=3):
    """The outline pieces of a gear (turned by ``angle``, at ``centre``) within ``reach`` of the
    other gear's centre, from the few teeth facing it: the only ones that can touch it."""
    toward = math.atan2(other_centre[1] - centre[1], other_centre[0] - centre[0])
    pitch = 2 * math.pi / profile.teeth
    nearest = round((toward - angle) / pitch)
    out = []
    for k in range(nearest - teeth_each_side, nearest + teeth_each_side + 1):
        for seg in profile.pitch_segments():
            seg = seg.rotated(angle + k * pitch)
            if seg.kind == "root_arc":
                continue
            if np.min(np.linalg.norm(seg.sample(9) + centre - other_centre, axis=1)) < reach:
                out.append(seg)
    return out


def _crossings(points, pivot, direction, seg, offset, grid=96):
    """Coarse first-hit angles of ``points`` (n, 2) turned about ``pivot`` in ``direction`` onto
    the curve ``seg`` (placed at ``offset``): where each point's circle crosses the curve's
    sampled radius, interpolated linearly (inf where it does not cross)."""
    q = seg.sample(grid) + offset - pivot
    radius, angle = np.hypot(q[:, 0], q[:, 1]), np.unwrap(np.arctan2(q[:, 1], q[:, 0]))
    rel = points - pivot
    rho, alpha = np.hypot(rel[:, 0], rel[:, 1]), np.arctan2(rel[:, 1], rel[:, 0])
    f = radius[None, :] - rho[:, None]
    cross = np.sign(f[:, :-1]) * np.sign(f[:, 1:]) <= 0
    w = np.where(cross, f[:, :-1] / np.where(cross, f[:, :-1] - f[:, 1:], 1.0), 0.0)
    hit = angle[None, :-1] + w * (angle[None, 1:] - angle[None, :-1])
    turn = (direction * (hit - alpha[:, None])) % (2 * math.pi)
    return np.where(cross, turn, np.inf).min(axis=1)


def _hits(point, pivot, direction, segments, offset, grid=32):
    """Angles (rad, > 0) by which ``point`` turned about ``pivot`` in ``direction`` (+1 ccw) meets
    the curves ``segments`` (placed at ``offset``): every crossing of its circle, refined to
    machine precision on the exact curve."""
    rho = np.linalg.norm(point - pivot)
    alpha = math.atan2(point[1] - pivot[1], point[0] - pivot[0])
    out = []
    for seg in segments:
        t = seg.parameters(grid)
        f = np.linalg.norm(seg.point(t) + offset - pivot, axis=1) - rho
        for j in np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) <= 0)[0]:
            def radial(u):
                return float(np.linalg.norm(seg.point(u)[0] + offset - pivot) - rho)
            a, b = t[j], t[j + 1]
            u = a if radial(a) == 0 else (b if radial(b) == 0 else brentq(radial, a, b, xtol=1e-15, rtol=1e-15))
            q = seg.point(u)[0] + offset - pivot
            out.append((direction * (math.atan2(q[1], q[0]) - alpha)) % (2 * math.pi))
    return out


def _first_contact(moving_segs, moving_offset, held_segs, held_offset, pivot, direction, coarse=32):
    """Smallest turn of the ``moving`` outline about ``pivot`` before one of its points meets the
    ``held`` outline: coarse over the moving curves' parameters, then a bounded minimisation of
    the exact first-hit angle around the best one (contact is a smooth minimum of it)."""
    best = (math.inf, None, None)
    for seg in moving_segs:
        points = seg.sample(coarse) + moving_offset
        turns = np.min([_crossings(points, pivot, direction, h, held_offset) for h in held_segs], axis=0)
        i = int(np.argmin(turns))
        if turns[i] < best[0]:
            best = (turns[i], seg, i)
    _, seg, i = best
    if seg is None:
        return math.inf
    t = seg.parameters(coarse)
    lo, hi = sorted((t[max(i - 1, 0)], t[min(i + 1, coarse - 1)]))

    def first_hit(u):
        h = _hits(seg.point(u)[0] + moving_offset, pivot, direction, held_segs, held_offset)
        return min(h) if h else math.inf

    # the first hit is quadratic in the parameter about its minimum: 1e-10 there is ~1e-19 rad
    res = minimize_scalar(first_hit, bounds=(lo, hi), method="bounded", options={"xatol": 1e-10})
    return min(res.fun, first_hit(lo), first_hit(hi))


def free_turn(moving, held, direction):
    """How far (rad) the ``moving`` gear can turn about its centre in ``direction`` (+1 ccw, -1 cw)
    before its outline meets the ``held`` gear's, in one transverse plane.

    ``moving`` and ``held``: (ToothProfile, centre (2,), section angle at the plane). A point of
    either outline may be where they meet: the moving outline's points are turned forward about
    the moving centre, the held outline's backward about it."""
    (pm, cm, am), (ph, ch, ah) = moving, held
    cm, ch = np.asarray(cm, float), np.asarray(ch, float)
    ms = _near_segments(pm, cm, am, ch, ph.tip_radius + 0.5)
    hs = _near_segments(ph, ch, ah, cm, pm.tip_radius + 0.5)
    return min(_first_contact(ms, cm, hs, ch, cm, direction), _first_contact(hs, ch, ms, cm, cm, -direction))


# ---------------------------------------------------------------------------------------------
# the cluster slid along its axis


class Cluster:
    """A cluster (large gear meshing the held input, small gear meshing the held output) whose
    rotation and axial shift can be changed; every gear's section at a plane from its helix."""

    def __init__(self, large, small, centre, rotation, z_large, z_small, inp, out):
        self.large, self.small = large, small  # (spec, profile)
        self.centre, self.rotation = np.asarray(centre, float), rotation
        self.z = {"large": z_large, "small": z_small}
        self.inp, self.out = inp, out  # (spec, profile, centre, rotation of its z0 section, z0)
        self._unshifted = {}

    def _moving(self, which, plane, turn, shift):
        spec, profile = self.large if which == "large" else self.small
        angle = self.rotation + turn + section_rotation(spec, plane - (self.z[which] + shift))
        return profile, self.centre, angle

    @staticmethod
    def _held(gear, plane):
        spec, profile, centre, rotation, z0 = gear
        return profile, np.asarray(centre, float), rotation + section_rotation(spec, plane - z0)

    def gap(self, mesh, plane, direction, turn=0.0, shift=0.0):
        """Free turn of the cluster (rad) in ``direction`` at ``mesh`` 1 (large gear, input) or 2
        (small gear, output), at world height ``plane``, the cluster turned by ``turn`` and slid
        by ``shift`` along +z."""
        which, mate = ("large", self.inp) if mesh == 1 else ("small", self.out)
        return free_turn(self._moving(which, plane, turn, shift), self._held(mate, plane), direction)

    def turn_keeping(self, mesh, plane, direction, shift, first_step=0.02):
        """The cluster turn that keeps the gap of ``mesh`` what it is unshifted (measured in
        ``direction``), the cluster slid by ``shift``: root-finding (secant), from the cluster
        turned to the middle of the backlash (where every flank is clear) and continued from a short
        first slide (a turn off by more than the backlash would put the teeth into each other,
        where no gap is defined)."""
        key = (mesh, plane, direction)
        if key not in self._unshifted:
            working, idle = self.gap(mesh, plane, direction), self.gap(mesh, plane, -direction)
            centred = direction * (working - (working + idle) / 2)  # turning towards a flank shortens its gap
            self._unshifted[key] = (centred, self.gap(mesh, plane, direction, centred), (working + idle) / 3)
        centred, target, window = self._unshifted[key]
        psi, slope, z = centred, 0.0, 0.0
        for z_next in (math.copysign(min(first_step, abs(shift)), shift), shift):
            guess = psi + slope * (z_next - z)
            root = _secant(lambda p: self.gap(mesh, plane, direction, p, z_next) - target, guess, window)
            if z_next != z:
                slope = (root - psi) / (z_next - z)
            psi, z = root, z_next
        return psi - centred


def _secant(f, guess, window, tol=1e-14):
    """A root of ``f`` within ``window`` of ``guess`` by the secant method (the gap is linear in
    the turn while every flank stays clear, so it converges in a step or two)."""
    x0, x1 = guess, guess + window / 10
    f0, f1 = f(x0), f(x1)
    for _ in range(20):
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        assert abs(x2 - guess) <= window, "the turn left the window where the gap is defined"
        if abs(x2 - x1) < tol:
            return x2
        x0, f0, x1, f1 = x1, f1, x2, f(x2)
    raise AssertionError("the secant did not converge")


def _profile(spec):
    return spec, tooth_profile(spec, warn=False)


def _synthetic_cluster(hand_large, hand_small, beta_large_deg, beta_small_deg):
    """Input (20 teeth) - cluster (60/20) - output (120), mates of the other hand, centre distances
    0.1 mm over standard, held gears turned to centre the cluster's teeth in their gaps."""
    other = {"right": "left", "left": "right"}

    def gear(teeth, module, beta, hand):
        return gear_from_table({"teeth": teeth, "module_mm": module, "pressure_angle_deg": 20,
                                "helix_angle_deg": beta, "hand": hand, "face_width_mm": 30})

    g_in = gear(20, 2.0, beta_large_deg, other[hand_large])
    g_large = gear(60, 2.0, beta_large_deg, hand_large)
    g_small = gear(20, 2.5, beta_small_deg, hand_small)
    g_out = gear(120, 2.5, beta_small_deg, other[hand_small])
    a1 = g_in.reference_radius + g_large.reference_radius + 0.1
    a2 = g_small.reference_radius + g_out.reference_radius + 0.1
    cluster = np.array([a1, 0.0])
    direction2 = math.radians(70.0)
    output = cluster + a2 * np.array([math.cos(direction2), math.sin(direction2)])
    rot_in = float(mate_rotation(0.0, 0.0, g_in.teeth, g_large.teeth, 0.0, 0))
    rot_out = float(mate_rotation(direction2 + math.pi, 0.0, g_out.teeth, g_small.teeth, 0.0, 0))
    return Cluster(_profile(g_large), _profile(g_small), cluster, 0.0, 0.0, 0.0,
                   (*_profile(g_in), (0.0, 0.0), rot_in, 0.0), (*_profile(g_out), output, rot_out, 0.0))


def _sliding(spec, name, mate):
    return fx.SlidingMesh(name, mate, spec.helix_angle, spec.reference_radius, spec.hand)


# ---------------------------------------------------------------------------------------------
# closed forms by hand


def test_turn_rate_is_tan_helix_over_radius_signed_by_hand():
    beta, r = math.radians(15.0), 25.0
    assert fx.SlidingMesh("p", "g", beta, r, "right").turn_rate == pytest.approx(math.tan(beta) / r, rel=1e-15)
    assert fx.SlidingMesh("p", "g", beta, r, "left").turn_rate == pytest.approx(-math.tan(beta) / r, rel=1e-15)
    assert fx.SlidingMesh("p", "g", 0.0, r).turn_rate == 0.0
    # a spur other gear (or none) leaves the pinion's own helix: the single-gear rate, reversed
    pinion = fx.SlidingMesh("p", "g", beta, r, "left")
    assert fx.cluster_opening_rate(pinion) == pytest.approx(math.tan(beta) / r, rel=1e-15)
    assert fx.cluster_opening_rate(pinion, fx.SlidingMesh("l", "i", 0.0, 60.0)) == fx.cluster_opening_rate(pinion)
    with pytest.raises(DesignError):
        fx.SlidingMesh("p", "g", beta, r, "up")


def test_cluster_of_one_hand_subtracts_its_helices_and_of_two_hands_adds_them():
    beta, r_e, r_o = math.radians(15.0), 25.0, 60.0
    e = fx.SlidingMesh("small", "out", beta, r_e, "left")
    same = fx.helical_engagement(e, 0.05, 0.25, 30.0, other=fx.SlidingMesh("large", "in", beta, r_o, "left"))
    mixed = fx.helical_engagement(e, 0.05, 0.25, 30.0, other=fx.SlidingMesh("large", "in", beta, r_o, "right"))
    assert same.circumferential_rate == pytest.approx(math.tan(beta) * (1 - r_e / r_o), rel=1e-14)
    assert mixed.circumferential_rate == pytest.approx(math.tan(beta) * (1 + r_e / r_o), rel=1e-14)
    assert same.lead == pytest.approx(0.30 / (math.tan(beta) * (1 - r_e / r_o)), rel=1e-14)
    assert mixed.lead == pytest.approx(0.30 / (math.tan(beta) * (1 + r_e / r_o)), rel=1e-14)
    # whatever the rate, the lead turns the pinions apart by (b + w) at the reference circle
    for g in (same, mixed):
        assert g.relative_rotation * r_e == pytest.approx(0.30, rel=1e-14)
        assert g.loop_windup(g.lead) == pytest.approx(-0.05, rel=1e-12)  # the backlash to slide in with
        assert g.loop_windup(0.0) == pytest.approx(0.25, rel=1e-15)      # engaged: the preload windup
    assert same.opening_turn == "ccw" and same.opening_rate > 0  # left hand: -kappa_e dominates
    assert mixed.opening_turn == "ccw"
    right = fx.helical_engagement(fx.SlidingMesh("small", "out", beta, r_e, "right"), 0.05, 0.25, 30.0,
                                  other=fx.SlidingMesh("large", "in", beta, r_o, "right"))
    assert right.opening_turn == "cw" and right.opening_rate == pytest.approx(-same.opening_rate, rel=1e-15)


def test_a_cluster_that_slides_like_a_screw_opens_nothing():
    # both gears of one hand and one helix lead (tan(beta) / r equal): the cluster turns as a screw
    beta_e = math.radians(10.0)
    r_e, r_o = 25.0, 60.0
    beta_o = math.atan(math.tan(beta_e) * r_o / r_e)
    e = fx.SlidingMesh("small", "out", beta_e, r_e, "left")
    with pytest.raises(DesignError) as info:
        fx.helical_engagement(e, 0.05, 0.2, 30.0, other=fx.SlidingMesh("large", "in", beta_o, r_o, "left"))
    assert info.value.field == "engagement.gear" and "screw" in str(info.value)
    with pytest.raises(DesignError) as info:
        fx.helical_engagement(fx.SlidingMesh("small", "out", 0.0, r_e), 0.05, 0.2, 30.0,
                              other=fx.SlidingMesh("large", "in", 0.0, r_o))
    assert "no mesh of the sliding cluster is helical" in str(info.value)


def test_a_lead_longer_than_the_engagement_is_refused():
    beta, r_e, r_o = math.radians(15.0), 25.0, 60.0
    e, o = fx.SlidingMesh("small", "out", beta, r_e, "left"), fx.SlidingMesh("large", "in", beta, r_o, "left")
    per_mm = math.tan(beta) * (1 - r_e / r_o)
    ok = fx.helical_engagement(e, 30 * per_mm - 0.1, 0.1, 30.0, other=o)  # exactly the engagement length
    assert ok.lead == pytest.approx(30.0, rel=1e-12)
    with pytest.raises(DesignError) as info:
        fx.helical_engagement(e, 30 * per_mm, 0.1, 30.0, other=o)
    assert info.value.field == "engagement.backlash" and info.value.allowed == f"[0, {30 * per_mm - 0.1:.6g}] mm"
    with pytest.raises(DesignError) as info:
        fx.helical_engagement(e, 0.0, 30 * per_mm + 0.1, 30.0, other=o)
    assert info.value.field == "engagement.preload_windup"


# ---------------------------------------------------------------------------------------------
# the independent solve


def test_free_turn_measures_the_backlash_of_a_spur_mesh():
    # the solver alone, against the involute closed form: two standard spur gears 0.1 mm over the
    # standard centre distance have backlash 2 a (inv(alpha_w) - inv(alpha)) along the operating
    # pitch circles; both flanks' free turns add up to it
    from geargen.core.involute import involute
    g1 = gear_from_table({"teeth": 20, "module_mm": 2.0, "pressure_angle_deg": 20, "face_width_mm": 10})
    g2 = gear_from_table({"teeth": 60, "module_mm": 2.0, "pressure_angle_deg": 20, "face_width_mm": 10})
    a0 = g1.reference_radius + g2.reference_radius
    a = a0 + 0.1
    alpha = math.radians(20.0)
    alpha_w = math.acos(a0 * math.cos(alpha) / a)
    # as a turn of gear 1: over its operating pitch radius a z1 / (z1 + z2)
    backlash_turn = 2 * (involute(alpha_w) - involute(alpha)) * (g1.teeth + g2.teeth) / g1.teeth
    rot2 = float(mate_rotation(math.pi, 0.0, g2.teeth, g1.teeth, 0.0, 0))
    moving = (tooth_profile(g1), (0.0, 0.0), 0.0)
    held = (tooth_profile(g2), (a, 0.0), rot2)
    ccw, cw = free_turn(moving, held, +1), free_turn(moving, held, -1)
    assert ccw + cw == pytest.approx(backlash_turn, rel=1e-7)
    assert ccw == pytest.approx(cw, rel=1e-6)  # centred by mate_rotation(flank=0)


@pytest.mark.parametrize("hands, betas", [
    (("left", "left"), (15.0, 15.0)),     # the C-axis: one hand on the cluster, helices subtract
    (("right", "left"), (15.0, 15.0)),    # two hands: they add
    (("left", "right"), (12.0, 20.0)),    # two helix angles
    (("right", "right"), (0.0, 15.0)),    # a spur large gear: the pinion's helix alone
])
def test_opening_rate_matches_the_kinematic_solve(hands, betas):
    cl = _synthetic_cluster(*hands, *betas)
    (large, _), (small, _) = cl.large, cl.small
    plane, dz = 15.0, 1.5
    # mesh 1 alone: the turn that keeps the large gear's flank on the held input, per mm
    psi1 = cl.turn_keeping(1, plane, +1, dz)
    assert psi1 / dz == pytest.approx(_sliding(large, "large", "input").turn_rate, rel=1e-6, abs=1e-10)
    # mesh 2 alone: the pinion's own helix
    psi2 = cl.turn_keeping(2, plane, +1, dz)
    assert psi2 / dz == pytest.approx(_sliding(small, "small", "output").turn_rate, rel=1e-6)
    # the cluster held by mesh 1 stands psi1 - psi2 (ccw) from where mesh 2 wants it: the pinion is
    # turned that much against the held output, its cw gap grows and its ccw gap shrinks by as much
    omega = fx.cluster_opening_rate(_sliding(small, "small", "output"), _sliding(large, "large", "input"))
    assert (psi1 - psi2) / dz == pytest.approx(omega, rel=1e-6)  # the brief asks < 1 %
    # measured as gaps directly over a short slide (a long one would close the other flank past
    # its backlash: with input and output held, the teeth would have to overlap)
    short = 0.05
    psi_short = cl.turn_keeping(1, plane, +1, short)
    cw0, ccw0 = cl.gap(2, plane, -1), cl.gap(2, plane, +1)
    opened_cw = cl.gap(2, plane, -1, psi_short, short) - cw0
    closed_ccw = ccw0 - cl.gap(2, plane, +1, psi_short, short)
    assert opened_cw / short == pytest.approx(omega, rel=1e-6)
    assert closed_ccw / short == pytest.approx(omega, rel=1e-6)


# ---------------------------------------------------------------------------------------------
# the C-axis as resolved, on its own placements


@pytest.fixture(scope="module")
def c_axis():
    from geargen.design.assembly import load_design
    from geargen.model.analysis import stiffness
    from geargen.drives import resolve
    design = load_design(C_AXIS)
    layout = resolve(design)
    return design, layout, stiffness(design, layout)[0]


def _layout_cluster(layout, side):
    g = {p.name: p for p in layout.gears}
    large, small, inp, out = g[f"cluster_large_{side}"], g[f"cluster_small_{side}"], g["input"], g["output"]
    assert large.rotation == small.rotation and large.centre == small.centre  # one rigid cluster
    return Cluster(_profile(large.spec), _profile(small.spec), large.centre, large.rotation, large.z, small.z,
                   (*_profile(inp.spec), inp.centre, inp.rotation, inp.z),
                   (*_profile(out.spec), out.centre, out.rotation, out.z))


def _closing(mesh):
    """Direction (+1 ccw) the cluster turns to close the working flank of a placed mesh: mesh 1's
    label names the input's turn (the cluster, pushed back onto it, turns the same way), mesh 2's
    the cluster's."""
    return +1 if mesh.working_flank.endswith(" ccw") else -1


def test_c_axis_rates_and_lead_on_the_placed_gears(c_axis):
    design, layout, summary = c_axis
    eng = summary.engagement
    large, small = design.gears["cluster_large"], design.gears["cluster_small"]
    # the reviewer's rates: 4.31 mrad/mm (large gear along the long pinion), 10.35 (pinion in the bull gear)
    assert abs(eng.other.turn_rate) * 1e3 == pytest.approx(4.3137, abs=1e-4)
    assert abs(eng.engaging.turn_rate) * 1e3 == pytest.approx(10.3528, abs=1e-4)
    assert eng.opening_rate * 1e3 == pytest.approx(10.3528 - 4.3137, abs=2e-4)
    # (b + w) / c: 80 um + the windup of 300 N m, over 0.1563 mm per mm instead of tan(15 deg)
    assert eng.circumferential_rate == pytest.approx(math.tan(large.helix_angle) * (1 - 50 / 120), rel=1e-12)
    assert eng.lead == pytest.approx((0.08 + eng.preload_windup) / eng.circumferential_rate, rel=1e-12)
    # the reviewer's case, the windup of the stiffness modelled then (294.3 um at 300 N m): 2.40 mm
    # where the single-helix rule gave 1.397 mm, which opens only 218 um
    reviewer_windup = 0.2943
    assert (eng.backlash + reviewer_windup) / eng.circumferential_rate == pytest.approx(2.394, abs=2e-3)
    old_lead = (eng.backlash + reviewer_windup) / math.tan(small.helix_angle)
    assert old_lead == pytest.approx(1.397, abs=1e-3)
    assert eng.circumferential_rate * old_lead == pytest.approx(0.218, abs=1e-3)
    # the drive as resolved now: each path about 3.1e5 N m/rad with the cluster overhung on its quill
    # bearings, k3 the long pinion on its drive column (geargen.model.shafts), so the loop winds up
    # 605 um at 300 N m: a 4.38 mm lead
    assert eng.preload_windup == pytest.approx(0.6052, abs=5e-4)
    assert eng.lead == pytest.approx(4.384, abs=2e-3)
    assert float(eng.loop_windup(eng.lead)) == pytest.approx(-eng.backlash, rel=1e-12)


def _opening(cl, m1, m2, shift):
    """The kinematic solve on a placed cluster slid by ``shift``: the turn the large gear's working
    flank on the held long pinion imposes, minus the turn the pinion's working flank on the held
    bull gear would need; as the growth of that working flank's gap, a turn of the cluster (rad)."""
    psi1 = cl.turn_keeping(1, m1.plane, _closing(m1), shift)
    psi2 = cl.turn_keeping(2, m2.plane, _closing(m2), shift)
    return -_closing(m2) * (psi1 - psi2), psi1, psi2


def test_c_axis_trailer_slid_back_by_the_lead_opens_backlash_plus_windup(c_axis):
    # the independent check on the resolved layout: cluster B (the trailer) slid back by the lead
    # from the engaged position; the turn its large gear's working flank on the held long pinion
    # imposes against the turn its pinion's working flank on the held bull gear needs opens that
    # flank by the backlash plus the preload windup at the pinion's reference circle
    design, layout, summary = c_axis
    eng = summary.engagement
    assert eng.leader_retracted_stop - eng.trailer_retracted_stop == pytest.approx(eng.lead, rel=1e-12)
    cl = _layout_cluster(layout, "b")
    m1, m2 = layout.mesh("mesh1_b"), layout.mesh("mesh2_b")
    r_e = design.gears["cluster_small"].reference_radius
    # engaged, both working flanks sit at the modelled loaded-flank gap (0.5 um); the others have backlash
    for mesh, m in ((1, m1), (2, m2)):
        working, idle = cl.gap(mesh, m.plane, _closing(m)), cl.gap(mesh, m.plane, -_closing(m))
        assert working < 2e-3 / r_e < idle
    opened, psi1, psi2 = _opening(cl, m1, m2, -eng.lead)
    assert psi1 / -eng.lead * 1e3 == pytest.approx(-4.3137, abs=1e-4)   # the reviewer's 4.31 mrad/mm
    assert psi2 / -eng.lead * 1e3 == pytest.approx(-10.3528, abs=1e-4)  # and 10.35
    assert opened * r_e == pytest.approx(eng.backlash + eng.preload_windup, rel=1e-6)  # the brief asks < 1 %
    # the single-helix lead of the reviewer's case (1.397 mm) would open only 218 um there
    old_lead = (eng.backlash + 0.2943) / math.tan(eng.helix_angle)
    assert _opening(cl, m1, m2, -old_lead)[0] * r_e == pytest.approx(0.2183, abs=1e-4)
    # a short slide keeps every flank clear: the working flank's gap, measured directly, grows
    short = -0.05
    psi = cl.turn_keeping(1, m1.plane, _closing(m1), short)
    grown = cl.gap(2, m2.plane, _closing(m2), psi, short) - cl.gap(2, m2.plane, _closing(m2))
    assert grown * r_e == pytest.approx(eng.circumferential_rate * abs(short), rel=1e-6)


def test_c_axis_leader_is_the_path_the_lead_opens(c_axis):
    # cluster A leads (layout, CAD stops): its pinion, ahead by the lead, turns opening_turn
    # against the trailer's; that must lift A's working flank at the bull gear, i.e. A closes it
    # by turning the other way
    design, layout, summary = c_axis
    eng = summary.engagement
    assert layout.mesh("mesh2_a").working_flank == ("cluster cw" if eng.opening_turn == "ccw" else "cluster ccw")
    cl = _layout_cluster(layout, "a")
    m1, m2 = layout.mesh("mesh1_a"), layout.mesh("mesh2_a")
    r_e = design.gears["cluster_small"].reference_radius
    opened, _, _ = _opening(cl, m1, m2, 1.0)  # A 1 mm ahead of its engaged place (B held there)
    assert opened * r_e == pytest.approx(eng.circumferential_rate, rel=1e-6)


def test_c_axis_engagement_too_short_for_the_preload_windup_is_refused():
    # the load can only check the backlash (the windup comes from the stiffness model): 2 mm of
    # engagement pass it (0.08 / 0.1563 = 0.51 mm of lead) but not the stiffness step, where the
    # windup of 300 N m (the drive as resolved, its pinions on their placed quills) needs more
    import tomllib
    from geargen.design.assembly import design_from_dict
    from geargen.drives import resolve
    data = tomllib.loads(C_AXIS.read_text())
    data["engagement"]["engagement_length_mm"] = 2
    design = design_from_dict(data, validate=True)
    with pytest.raises(DesignError) as info:
        resolve(design)  # the engagement is part of the resolved drive
    per_lead = math.tan(math.radians(15)) * (1 - 50 / 120)
    full = resolve(design_from_dict({**data, "engagement": {**data["engagement"], "engagement_length_mm": 30}}))
    # the refusal comes in the first round, the long pinion's column taken as rigid (the housing it is
    # clamped in follows the strokes): the lead it quotes is a lower bound, and says so
    from geargen.core.stiffness import stiffness_summary
    from geargen.model.analysis import placed_components
    rigid = stiffness_summary(full.design, components=placed_components(full.design, full)).engagement
    assert rigid.lead < full.engagement.lead
    windup = rigid
    # the windup alone (554 um rigid, 605 um on the column) is more than 2 mm of engagement opens
    # (313 um): it is the key named
    assert info.value.field == "engagement.preload_windup"
    assert f"needs a lead of {windup.lead:.4g}" in str(info.value)
    assert "column taken as rigid (on the column it needs more)" in str(info.value)
    assert "more than the engagement length 2 mm" in str(info.value)
    most = 2 * per_lead - windup.backlash
    assert info.value.allowed == f"[0, {most:.6g}] mm"
