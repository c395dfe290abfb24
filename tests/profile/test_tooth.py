"""The exact tooth outline: flanks on the involute, fillet cut by the rack, undercut, errors."""

import math
import warnings

import numpy as np
import pytest

from geargen.core.involute import tooth_half_angle
from geargen.design.gear import GearSpec
from geargen.errors import DesignError, GeometryError
from geargen.profile.tooth import UndercutWarning, section_rotation, tooth_profile, twist_rate
from geargen.profile.hermite import hermite_error, hermite_nodes
from geargen.profile.segments import outline_area, sample_outline

DP32 = 25.4 / 32
DEG = math.pi / 180


def spec(teeth=21, module=DP32, helix=0.0, **kw):
    kw.setdefault("pressure_angle", 20 * DEG)
    kw.setdefault("face_width", 5.0)
    return GearSpec(teeth=teeth, module=module, helix_angle=helix * DEG, **kw)


CASES = {
    "112T spur": spec(112),
    "21T helical 20": spec(21, helix=20),
    "12T undercut": spec(12),
    "7T undercut shifted": spec(7, profile_shift=0.2),
    "12/30deg normal system": spec(12, module=3.0, helix=30, profile_shift=0.09809),
    "thinned, full-radius rack": spec(30, module=2.0, thinning=0.05, rack_tip_radius_coefficient=None,
                                      dedendum_coefficient=1.4),
    "sharp rack corner": spec(40, module=1.0, rack_tip_radius_coefficient=0.0),
    "left hand 35deg": spec(17, module=1.5, helix=35, hand="left", profile_shift=0.4),
}


def profile(name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UndercutWarning)
        return tooth_profile(CASES[name])


@pytest.mark.parametrize("name", CASES)
def test_flanks_lie_on_the_exact_involute(name):
    p = profile(name)
    for seg in p.tooth_segments():
        if seg.kind != "involute":
            continue
        xy = seg.sample(101)
        r = np.hypot(xy[:, 0], xy[:, 1])
        ang = np.abs(np.arctan2(xy[:, 1], xy[:, 0]))
        # the core's thickness function, independent of the roll-angle parametrisation
        np.testing.assert_allclose(ang, tooth_half_angle(p.spec, r), rtol=0, atol=1e-14)
        assert r.min() == pytest.approx(p.involute_start_radius, abs=1e-12)
        assert r.max() == pytest.approx(p.tip_radius, abs=1e-12)


@pytest.mark.parametrize("name", CASES)
def test_derivatives_are_exact(name):
    """Analytic derivatives against a 4th-order central difference (error ~h^4 f^(5) ~ 1e-9)."""
    p = profile(name)
    for seg in p.outline()[:7]:
        t = seg.parameters(9)[1:-1]
        h = 1e-4 * abs(seg.t1 - seg.t0)
        fd = (-seg.point(t + 2 * h) + 8 * seg.point(t + h) - 8 * seg.point(t - h) + seg.point(t - 2 * h)) / (12 * h)
        scale = np.max(np.abs(seg.derivative(t)))
        np.testing.assert_allclose(seg.derivative(t), fd, atol=1e-8 * max(scale, 1.0))


@pytest.mark.parametrize("name", CASES)
def test_outline_is_closed_and_smooth_where_it_should_be(name):
    p = profile(name)
    segs = p.outline()
    for a, b in zip(segs, segs[1:] + segs[:1]):
        assert np.linalg.norm(a.end - b.start) < 1e-12 * p.tip_radius
        smooth = {("fillet", "involute"), ("involute", "fillet"), ("root_arc", "fillet"), ("fillet", "root_arc"),
                  ("fillet", "fillet")}
        if (a.kind, b.kind) in smooth and not (p.undercut and "involute" in (a.kind, b.kind)):
            cos = float(a.tangent(a.t1)[0] @ b.tangent(b.t0)[0])
            assert cos > 1 - 1e-12, (a.kind, b.kind)
    radii = np.hypot(*sample_outline(segs[:7], 0.01 * p.spec.module).T)
    assert radii.min() == pytest.approx(p.root_radius, abs=1e-12)
    assert p.root_radius == pytest.approx(p.spec.root_radius_standard, abs=1e-12)
    assert radii.max() == pytest.approx(p.tip_radius, abs=1e-12)


@pytest.mark.parametrize("name", CASES)
def test_area_by_greens_theorem_matches_a_converged_polygon(name):
    """Shoelace area of the sampled outline converges as h^2; Richardson on h and h/2 removes
    that term, leaving O(h^4) (~1e-12 relative at these spacings)."""
    p = profile(name)
    tooth = p.pitch_segments()

    def shoelace(step):
        xy = sample_outline(tooth, step)
        xy = np.vstack([xy, tooth[-1].end])
        closed = np.vstack([[0.0, 0.0], xy])  # the sector from the axis: exact for arcs about it too
        x, y = closed[:, 0], closed[:, 1]
        return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))

    h = 0.002 * p.spec.module
    a1, a2 = shoelace(h), shoelace(h / 2)
    richardson = a2 + (a2 - a1) / 3
    assert outline_area(tooth) == pytest.approx(richardson, rel=1e-9)
    assert p.area() == pytest.approx(p.teeth * richardson, rel=1e-9)


def _rack_outline(p, n=120):
    """The generating rack's tooth space boundary (u, v) in the transverse section, one pitch:
    straight flanks, rounded tips (ellipses), tip lines; the same rack as the docstring of
    geargen.profile.tooth, built here from its definition, independently of FilletCurve."""
    s = p.spec
    cb = math.cos(s.helix_angle)
    m = s.module
    h_f = (s.dedendum_coefficient - s.profile_shift) * m
    rho = s.rack_tip_radius_coefficient * m
    from geargen.core.involute import reference_tooth_thickness
    s_t = reference_tooth_thickness(s)
    a_n, a_t = s.pressure_angle, s.transverse_pressure_angle
    v_c = -h_f + rho
    u_c = (s_t * cb / 2 - v_c * math.tan(a_n) + rho / math.cos(a_n)) / cb
    th = np.linspace(math.pi + a_n, 1.5 * math.pi, n)
    fillet = np.column_stack([u_c + rho * np.cos(th) / cb, v_c + rho * np.sin(th)])
    v_top = s.addendum_coefficient * m + 2 * m
    v_f = fillet[0, 1]
    flank_v = np.linspace(v_top, v_f, n)
    flank = np.column_stack([s_t / 2 - flank_v * math.tan(a_t), flank_v])
    tip = np.column_stack([np.linspace(u_c, s.transverse_pitch / 2, n), np.full(n, -h_f)])
    right = np.vstack([flank, fillet, tip])
    left = right[::-1] * [-1, 1]
    return np.vstack([left, right])


@pytest.mark.parametrize("name", CASES)
def test_outline_is_the_envelope_of_the_generating_rack(name):
    """Roll the rack (its own geometry, sampled) round the gear: it never cuts into the outline,
    and every fillet and flank point of the outline is touched by it."""
    p = profile(name)
    r = p.reference_radius
    rack = _rack_outline(p)
    sigmas = np.linspace(-0.9 * p.spec.transverse_pitch, 0.9 * p.spec.transverse_pitch, 500)
    phi = -sigmas / r
    x = r + rack[None, :, 1]
    y = rack[None, :, 0] + sigmas[:, None]
    gx = np.cos(phi)[:, None] * x - np.sin(phi)[:, None] * y
    gy = np.sin(phi)[:, None] * x + np.cos(phi)[:, None] * y
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    # rack points never inside the tooth (polar test: tooth 0 spans |angle| < half angle at radius)
    tooth = np.vstack([s.sample(400) for s in p.tooth_segments()])
    rad = np.hypot(pts[:, 0], pts[:, 1])
    ang = np.arctan2(pts[:, 1], pts[:, 0])
    sel = (rad > p.involute_start_radius) & (rad < p.tip_radius) & (np.abs(ang) < math.pi / p.teeth)
    inside = np.abs(ang[sel]) < p.involute_half_angle(rad[sel]) - 1e-12
    assert not np.any(inside)
    # every outline point of tooth 0 (not the tip) has a rack point within the sampling error
    from scipy.spatial import cKDTree
    d, _ = cKDTree(pts).query(np.vstack([s.sample(60) for s in p.tooth_segments() if s.kind != "tip_arc"]))
    spacing = max(np.max(np.linalg.norm(np.diff(rack, axis=0), axis=1)), r * np.max(np.diff(phi)) * 2)
    assert np.max(d) < spacing


def test_undercut_is_reported_and_warned():
    with pytest.warns(UndercutWarning, match="undercut"):
        p = tooth_profile(spec(10))
    assert p.undercut and p.warnings
    assert p.involute_start_radius > p.base_radius
    assert p.fillet_joint_roll < 0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        q = tooth_profile(spec(30))
    assert not q.undercut and not q.warnings


@pytest.mark.parametrize("name", CASES)
def test_involute_start_agrees_with_core_geometry(name):
    geometry = pytest.importorskip("geargen.core.geometry")
    p = profile(name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UndercutWarning)
        assert p.involute_start_radius == pytest.approx(geometry.involute_start_radius(p.spec), abs=1e-9)
        assert p.undercut == geometry.undercut(p.spec).is_undercut


def test_helix_sign_and_rate():
    right = spec(21, helix=20, hand="right")
    left = spec(21, helix=20, hand="left")
    assert section_rotation(right, 3.0) > 0 > section_rotation(left, 3.0)
    assert section_rotation(right, 3.0) == pytest.approx(-section_rotation(left, 3.0))
    # at the base cylinder the flank's helix angle is the base helix angle
    assert math.atan(twist_rate(right) * right.base_radius) == pytest.approx(right.base_helix_angle, rel=1e-12)
    assert section_rotation(spec(21), 5.0) == 0.0
    # one lead turns the section once
    assert section_rotation(right, right.lead) == pytest.approx(2 * math.pi, rel=1e-12)


def test_negative_root_is_refused():
    """GearSpec itself refuses a root circle at or below the axis (as a bore/root conflict, even
    without a bore), before the profile's own ``negative_root`` check is reached."""
    with pytest.raises((DesignError, GeometryError)):
        tooth_profile(spec(teeth=4, profile_shift=-1.5, dedendum_coefficient=2.0, rack_tip_radius_coefficient=0.0))


@pytest.mark.parametrize("kw, kind", [
    (dict(teeth=10, profile_shift=1.5), "pointed_tooth"),
    (dict(teeth=30, pressure_angle=35 * DEG, dedendum_coefficient=1.5, rack_tip_radius_coefficient=0.0), "pointed_rack"),
    (dict(teeth=5, profile_shift=-1.0, addendum_coefficient=0.3, pressure_angle=30 * DEG), "no_involute"),
    # found by the sweep: the rack tips' paths from both flanks cross the tooth centreline
    (dict(teeth=5, profile_shift=-0.37, addendum_coefficient=0.873, dedendum_coefficient=1.496,
          pressure_angle=22.5 * DEG), "severed_tooth"),
])
def test_impossible_gears_raise_geometry_error(kw, kind):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UndercutWarning)
        with pytest.raises(GeometryError) as exc:
            tooth_profile(spec(**kw))
    assert exc.value.kind == kind


@pytest.mark.parametrize("name", CASES)
def test_hermite_nodes_meet_their_tolerance(name):
    """Checked against the exact curve at 1000 points per interval-set, not at the check points."""
    p = profile(name)
    for seg in p.tooth_segments():
        params = hermite_nodes(seg, 1e-6)
        dense = np.sort(np.concatenate([np.linspace(a, b, 50) for a, b in zip(params[:-1], params[1:])]))
        assert hermite_error(seg, params) <= 1e-6
        # the interpolant at dense points (own evaluation, not hermite_error's check points)
        from geargen.profile.hermite import hermite_eval
        idx = np.clip(np.searchsorted(params, dense, side="right") - 1, 0, len(params) - 2) if params[-1] > params[0] \
            else None
        if idx is None:
            continue
        h = params[idx + 1] - params[idx]
        frac = (dense - params[idx]) / h
        p0, p1 = seg.point(params[idx]), seg.point(params[idx + 1])
        d0, d1 = seg.derivative(params[idx]), seg.derivative(params[idx + 1])
        approx = np.array([hermite_eval(p0[i:i + 1], p1[i:i + 1], d0[i:i + 1], d1[i:i + 1], h[i], np.array([frac[i]]))[0, 0]
                           for i in range(len(dense))])
        assert np.max(np.linalg.norm(approx - seg.point(dense), axis=1)) <= 1.2e-6
