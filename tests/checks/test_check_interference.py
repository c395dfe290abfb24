"""Failure kinds of path 1: crowded centres (the paper's warning), flank, involute and
tip-to-root interference, undercut, pointed teeth, low contact ratio; depth and area."""

import math
from dataclasses import replace

import numpy as np
import pytest
from matplotlib.path import Path as MplPath

from geargen.checks.mesh2d import MeshSetup, check_mesh, overlap_area, polar_outline, tip_clearance
from geargen.core.geometry import GearPair, mesh_geometry, tight_mesh_centre_distance
from geargen.profile.segments import sample_outline

from checks_support import gear, inch_gear, theory_normal_backlash, tight_centre_distance

PINION, WHEEL = inch_gear(16, name="pinion"), inch_gear(48, name="wheel")


def test_crowded_centres_with_backlash_allowance_give_tip_to_root_interference():
    """Hale & Slocum: gears made with backlash allowance may run with tip-to-root interference
    at a crowded centre distance; gear details should specify zero allowance."""
    m = PINION.module
    thinned = (replace(PINION, thinning=0.35 * m), replace(WHEEL, thinning=0.35 * m))
    plain = (PINION, WHEEL)
    # crowd each pair until the flanks close on both sides (zero backlash)
    a_thin = tight_mesh_centre_distance(GearPair(*thinned))
    a_plain = tight_mesh_centre_distance(GearPair(*plain))
    assert a_thin < a_plain - 0.25 * m  # the allowance lets the centres come closer than the clearance
    c = check_mesh(MeshSetup.centred(*thinned, a_thin + 1e-4, "crowded"))
    assert "tip_to_root_interference" in c.failure_kinds
    assert "flank_interference" not in c.failure_kinds  # the flanks still have (a little) backlash
    assert c.min_clearance == pytest.approx(a_thin + 1e-4 - WHEEL.tip_radius - PINION.root_radius_standard, abs=1e-9)
    assert c.min_clearance < 0
    worst = max(f.value for f in c.failures if f.kind == "tip_to_root_interference")
    assert worst == pytest.approx(-c.min_clearance, rel=1e-9)
    # the same crowding of gears made without allowance leaves the tips clear
    c0 = check_mesh(MeshSetup.centred(*plain, a_plain + 1e-4, "crowded, no allowance"))
    assert not set(c0.failure_kinds) & {"tip_to_root_interference", "involute_interference", "flank_interference"}
    assert c0.min_clearance == pytest.approx(0.25 * m + 1e-4, abs=1e-9)


def test_flank_interference_depth_is_the_negative_backlash():
    g1, g2 = gear(20), gear(41)
    a = tight_centre_distance(g1, g2) - 0.05
    c = check_mesh(MeshSetup.centred(g1, g2, a))
    assert "flank_interference" in c.failure_kinds
    assert c.max_interference_depth == pytest.approx(-theory_normal_backlash(g1, g2, a), abs=1e-9)
    assert c.min_normal_backlash == pytest.approx(theory_normal_backlash(g1, g2, a), abs=1e-9)
    assert c.max_interference_area > 0


def _raster_overlap(g1, g2, state, i, coarse=0.01, fine=0.001, outline_step=0.005, dilate=3, teeth=5):
    """Independent estimate of the overlap area: polygons of five teeth of each outline (points
    5 um apart; the flanks' chord sagitta is ~1e-6 mm), a point-in-polygon count on a 10 um grid
    over the lens of the tip circles, refined to 1 um in the cells at and near the overlap."""
    polys = []
    c1, c2 = state.centre1[i], state.centre2[i]
    for g, c, a, other in ((g1, c1, state.angle1[i], c2), (g2, c2, state.angle2[i], c1)):
        p = 2 * math.pi / g.teeth
        k0 = round((math.atan2(other[1] - c[1], other[0] - c[0]) - a) / p)
        segs = [sg for sg in polar_outline(g).profile.outline(a + (k0 - teeth // 2) * p) if sg.tooth < teeth]
        polys.append(MplPath(np.vstack([c, sample_outline(segs, outline_step) + c, c])))

    def inside(P):
        m = ((np.hypot(P[:, 0] - c1[0], P[:, 1] - c1[1]) < g1.tip_radius)
             & (np.hypot(P[:, 0] - c2[0], P[:, 1] - c2[1]) < g2.tip_radius))
        out = np.zeros(len(P), bool)
        out[m] = polys[0].contains_points(P[m]) & polys[1].contains_points(P[m])
        return out

    d = c2 - c1
    a = np.linalg.norm(d)
    u, n = d / a, np.array([-d[1], d[0]]) / a
    x_i = (a * a + g1.tip_radius ** 2 - g2.tip_radius ** 2) / (2 * a)
    half = math.sqrt(g1.tip_radius ** 2 - x_i ** 2)
    S, T = np.meshgrid(np.arange(a - g2.tip_radius, g1.tip_radius, coarse), np.arange(-half, half, coarse))

    def xy(s, t):
        return np.column_stack([c1[0] + s * u[0] + t * n[0], c1[1] + s * u[1] + t * n[1]])

    hit = inside(xy(S.ravel(), T.ravel())).reshape(S.shape)
    near = hit.copy()
    for _ in range(dilate):
        near = near | np.roll(near, 1, 0) | np.roll(near, -1, 0)
        near = near | np.roll(near, 1, 1) | np.roll(near, -1, 1)
    k = int(round(coarse / fine))
    SX, SY = np.meshgrid((np.arange(k) + 0.5) * fine - 0.5 * coarse, (np.arange(k) + 0.5) * fine - 0.5 * coarse)
    P = xy((S[near][:, None] + SX.ravel()[None]).ravel(), (T[near][:, None] + SY.ravel()[None]).ravel())
    return inside(P).sum() * fine * fine


def test_overlap_area_agrees_with_a_raster_count():
    g1, g2 = gear(20, 1.0), gear(41, 1.0)
    su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) - 0.03)
    st = su.states([0.07])
    exact = overlap_area(polar_outline(g1), polar_outline(g2), st)[0]
    raster = _raster_overlap(g1, g2, st, 0)
    # the raster's error: about half a 1 um cell along the ~10 mm boundary of the overlap (~0.5 %)
    assert exact == pytest.approx(raster, rel=0.01), (exact, raster)
    # no overlap when the pair has backlash
    st2 = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + 0.03).states([0.0])
    assert overlap_area(polar_outline(g1), polar_outline(g2), st2)[0] == 0.0


def test_long_addendum_mate_works_on_the_fillet_involute_interference():
    g1 = gear(30, 1.0, name="g1")  # cut by the standard rack (tip radius 0.38 m): involute ends 1.0 m deep
    g2 = gear(100, 1.0, name="g2", addendum_coefficient=1.2)  # its tip works 1.2 m deep, clearance 0.05 m
    a = g1.reference_radius + g2.reference_radius + 0.02
    c = check_mesh(MeshSetup.centred(g1, g2, a))
    assert c.failure_kinds == ["involute_interference"]
    assert c.min_clearance > 0  # not tip-to-root: the tip land clears the root
    assert mesh_geometry(GearPair(g1, g2), a).involute_interference == (True, False)
    assert 0 < c.max_interference_depth < 0.1 and c.max_interference_area > 0
    # the standard mate is fine
    ok = check_mesh(MeshSetup.centred(g1, replace(g2, addendum_coefficient=1.0), a))
    assert ok.ok


def test_undercut_pinion_where_the_mate_works():
    g1, g2 = gear(10, 1.0, name="g1"), gear(40, 1.0, name="g2")
    c = check_mesh(MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + 0.02))
    assert "undercut" in c.failure_kinds
    assert c.contact_ratio < mesh_geometry(GearPair(g1, g2), tight_centre_distance(g1, g2) + 0.02).transverse_contact_ratio
    # shifted out of undercut it passes
    g1s = replace(g1, profile_shift=0.5)
    assert "undercut" not in check_mesh(MeshSetup.centred(g1s, g2, tight_centre_distance(g1s, g2) + 0.02)).failure_kinds


@pytest.mark.parametrize("shift, kind", [(0.6, "pointed_tooth"), (0.75, "pointed_tooth"), (0.3, None)])
def test_pointed_tooth(shift, kind):
    g1, g2 = gear(10, 1.0, x=shift, name="g1"), gear(40, 1.0, name="g2")
    c = check_mesh(MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + 0.02))
    if kind:
        assert kind in c.failure_kinds
    else:
        assert "pointed_tooth" not in c.failure_kinds


def test_low_contact_ratio():
    g1 = gear(20, 1.0, addendum_coefficient=0.55, name="g1")
    g2 = gear(20, 1.0, addendum_coefficient=0.55, name="g2")
    a = g1.reference_radius + g2.reference_radius + 0.01
    c = check_mesh(MeshSetup.centred(g1, g2, a))
    assert "low_contact_ratio" in c.failure_kinds
    assert c.contact_ratio == pytest.approx(mesh_geometry(GearPair(g1, g2), a).transverse_contact_ratio, abs=1e-5)
    assert c.contact_ratio < 1.1


def test_zero_backlash_mesh_fails_only_when_backlash_is_required():
    from geargen.checks.mesh2d import CheckSettings

    su = MeshSetup.centred(PINION, WHEEL, tight_centre_distance(PINION, WHEEL))
    assert check_mesh(su).failure_kinds == ["no_backlash"]
    assert check_mesh(su, CheckSettings(require_backlash=False)).ok


def test_tip_clearance_is_exact_on_the_line_of_centres():
    su = MeshSetup.centred(PINION, WHEEL, 1.004 * 25.4)
    st = su.states([0.0, math.pi / 16])  # a pinion tooth, then a pinion space, on the line of centres
    c = tip_clearance(polar_outline(PINION), polar_outline(WHEEL), st)
    assert c.min() == pytest.approx(1.004 * 25.4 - PINION.tip_radius - WHEEL.root_radius_standard, abs=1e-12)


def test_flank_offsets_equal_the_same_thickness_cut_by_the_rack():
    """Moving both flanks of every tooth out by e is the outline a rack shifted by e r cuts (a
    tangential rack shift turns each generated side by the shift over r): play and overlap area
    with flank offsets equal those of the thicker gear."""
    from geargen.checks.mesh2d import MeshState, free_play

    g1, g2 = gear(20, 1.0, thinning=0.08), gear(41, 1.0)
    e = 0.03 / (2 * g1.reference_radius)  # 0.03 mm thicker at the reference circle
    thick = replace(g1, thinning=0.05)
    a = tight_centre_distance(g1, g2) - 0.1  # crowded: the teeth overlap
    base = MeshSetup.centred(g1, g2, a).states([0.0, 0.05])
    offs = MeshState(base.centre1, base.angle1, base.centre2, base.angle2,
                     np.tile([e, e], (g1.teeth, 1)), None)
    ref = MeshSetup.centred(thick, g2, a).states([0.0, 0.05])
    p_off = free_play(polar_outline(g1), polar_outline(g2), offs)
    p_ref = free_play(polar_outline(thick), polar_outline(g2), ref)
    assert np.allclose(p_off.conjugate_ccw, p_ref.conjugate_ccw, atol=1e-13)
    assert np.allclose(p_off.conjugate_cw, p_ref.conjugate_cw, atol=1e-13)
    a_off = overlap_area(polar_outline(g1), polar_outline(g2), offs)
    a_ref = overlap_area(polar_outline(thick), polar_outline(g2), ref)
    assert np.all(a_ref > 0) and np.allclose(a_off, a_ref, rtol=1e-9)
    # and the same with gear 2 carrying the offsets
    g2t = replace(g2, thinning=0.04)
    e2 = 0.04 / (2 * g2.reference_radius)
    offs2 = MeshState(ref.centre1, ref.angle1, ref.centre2, ref.angle2, None, np.tile([-e2, -e2], (g2.teeth, 1)))
    a2 = overlap_area(polar_outline(thick), polar_outline(g2), offs2)
    a2_ref = overlap_area(polar_outline(thick), polar_outline(g2t), ref)
    assert np.allclose(a2, a2_ref, rtol=1e-9, atol=1e-15)
