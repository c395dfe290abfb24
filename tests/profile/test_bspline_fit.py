"""Few-pole B-spline fits of the exact outline: error within the tolerance against the exact curve
at points of its own (not the fitter's check points), exact ends, arc-length parametrisation."""

import math

import numpy as np
import pytest
from scipy.interpolate import BSpline

from geargen.design.gear import GearSpec
from geargen.profile.tooth import tooth_profile
from geargen.profile.bspline_fit import fit_rotation, fit_segment, greville

DEG = math.pi / 180
GEARS = {
    "21T 32DP helical": GearSpec(teeth=21, module=25.4 / 32, pressure_angle=20 * DEG, face_width=12.7,
                                 helix_angle=20 * DEG),
    "112T 32DP": GearSpec(teeth=112, module=25.4 / 32, pressure_angle=20 * DEG, face_width=6.35),
    "7T undercut": GearSpec(teeth=7, module=1.0, pressure_angle=20 * DEG, face_width=5.0),
}


def spline(fit, s):
    return BSpline(np.repeat(fit.knots, fit.mults), fit.poles, fit.degree)(s)


def polyline_distance(points, line):
    """Distance of each of ``points`` (n, 2) to the polyline ``line`` (m, 2): nearest vertex, then
    the two pieces either side of it."""
    from scipy.spatial import cKDTree
    _, i = cKDTree(line).query(points)
    best = np.full(len(points), np.inf)
    for off in (-1, 0):
        a = line[np.clip(i + off, 0, len(line) - 1)]
        b = line[np.clip(i + off + 1, 0, len(line) - 1)]
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", points - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
        best = np.minimum(best, np.linalg.norm(a + t[:, None] * ab - points, axis=1))
    return best


@pytest.mark.parametrize("name", GEARS)
@pytest.mark.parametrize("by_length", [False, True])
def test_fit_within_tolerance_of_the_exact_curve(name, by_length):
    """Distance from the exact segment, measured here: for 20 001 points of the exact curve the
    distance to a polyline through 200 001 spline points (chords ~1e-5 mm long, so the polyline
    is within ~1e-10 mm of the spline: curvature radius >= 0.3 mm)."""
    tol = 1e-6
    for seg in tooth_profile(GEARS[name], warn=False).tooth_segments():
        if seg.kind not in ("involute", "fillet"):
            continue
        fit = fit_segment(seg, tol, by_length=by_length)
        exact = seg.point(np.linspace(seg.t0, seg.t1, 20001))
        approx = spline(fit, np.linspace(0.0, fit.length, 200001))
        assert polyline_distance(exact, approx).max() <= tol
        # the ends are the exact joints, the end tangents the exact directions
        assert np.allclose(fit.poles[0], seg.start, rtol=0, atol=1e-14)
        assert np.allclose(fit.poles[-1], seg.end, rtol=0, atol=1e-14)
        t_exact = seg.tangent(np.array([seg.t0, seg.t1]))
        d_fit = np.array([fit.poles[1] - fit.poles[0], fit.poles[-1] - fit.poles[-2]])
        d_fit /= np.linalg.norm(d_fit, axis=1, keepdims=True)
        assert np.allclose(d_fit, t_exact, rtol=0, atol=1e-12)
        assert len(fit.poles) <= 16  # few poles: what keeps the STEP small (bench/bench_step.py)


@pytest.mark.parametrize("name", GEARS)
def test_arc_length_parametrisation_runs_at_unit_speed(name):
    """|dB/ds| = 1 within 1e-3 on the fitted spline (derivative of the spline itself, by scipy):
    the parameter is the arc length, so a mesher sees no parametric stretching. The 7-tooth
    involute starts at the base circle's roll angle ~0 and keeps its roll angle (docstring)."""
    for seg in tooth_profile(GEARS[name], warn=False).tooth_segments():
        if seg.kind not in ("involute", "fillet"):
            continue
        fit = fit_segment(seg, 1e-6, by_length=True)
        if not fit.by_length:
            assert seg.kind == "involute" and min(seg.t0, seg.t1) < 0.1 * max(seg.t0, seg.t1)
            continue
        b = BSpline(np.repeat(fit.knots, fit.mults), fit.poles, fit.degree)
        speed = np.linalg.norm(b.derivative()(np.linspace(0.0, fit.length, 5001)), axis=1)
        assert np.max(np.abs(speed - 1.0)) <= 1e-3
        # the length is the exact one (closed form r_b (t1^2 - t0^2) / 2 for the involute)
        if seg.kind == "involute":
            rb = seg.curve.base_radius
            assert fit.length == pytest.approx(rb * abs(seg.t1 ** 2 - seg.t0 ** 2) / 2, rel=1e-14)


def test_rotation_fit_and_greville_heights():
    """cos/sin of k z over the bench pinion's 29.8 deg of twist (k = tan 20 deg / r, r = 21 x
    (25.4/32) / cos 20 deg / 2): within the tolerance at 10 001 points, exact at both ends; the
    Greville abscissae reproduce z (a spline with them as poles is the identity)."""
    r = 21 * 25.4 / 32 / math.cos(20 * DEG) / 2
    k, length = math.tan(20 * DEG) / r, 12.7
    fit = fit_rotation(k, length, 1e-10)
    z = np.linspace(0.0, length, 10001)
    err = np.linalg.norm(spline(fit, z) - np.column_stack([np.cos(k * z), np.sin(k * z)]), axis=1)
    assert err.max() <= 1e-10
    assert fit.poles[0].tolist() == [1.0, 0.0]
    assert fit.poles[-1].tolist() == [math.cos(k * length), math.sin(k * length)]
    zz = BSpline(np.repeat(fit.knots, fit.mults), greville(fit), fit.degree)(z)
    assert np.max(np.abs(zz - z)) <= 1e-13
    assert len(fit.poles) <= 8  # one span: the helical surfaces have 8 rows of poles


@pytest.mark.parametrize("twist", [0.05, 0.17, 0.52, 1.5])
def test_rotation_fit_of_fewest_poles(twist):
    """``degree=None`` takes the lowest degree (one span) that reaches the tolerance: within it at
    10 001 points, exact at the ends, and one degree lower (same span) would miss it - so no pole is
    spent that the accuracy does not need. Tolerance 3e-10: 0.01 nm at a 33 mm radius."""
    tol = 3e-10
    fit = fit_rotation(twist, 1.0, tol, degree=None)
    z = np.linspace(0.0, 1.0, 10001)
    err = np.linalg.norm(spline(fit, z) - np.column_stack([np.cos(twist * z), np.sin(twist * z)]), axis=1)
    assert err.max() <= tol
    assert fit.poles[-1].tolist() == [math.cos(twist), math.sin(twist)]
    if len(fit.knots) == 2 and fit.degree > 3:  # one span: the degree below misses
        with pytest.raises(ValueError):
            fit_rotation(twist, 1.0, tol, degree=fit.degree - 1, max_spans=1)
    assert len(fit.poles) <= len(fit_rotation(twist, 1.0, tol).poles)  # never more than degree 7's
