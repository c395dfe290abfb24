"""Few-pole B-spline fits of the exact outline's segments (numpy/scipy only).

The CAD layer gives every flank and fillet of a gear its own face; each face's curve is one
B-spline of degree ``degree`` (default 7) on uniform knots, parametrised evenly: by the
segment's own parameter scaled to its length (roll angle for an involute, the rack-tip angle
for a fillet), so the parametric speed varies only as much as the curve's own. The end points
and end tangents are exact (neighbouring faces meet in the exact joint with the exact tangent);
the poles in between are a least-squares fit to dense exact points, and the number of uniform
spans grows until the distance between the spline and the exact curve at the same parameter -
an upper bound on the geometric distance - is within ``tolerance`` at every check point (eight
per span more than were fitted, offset from them). A high degree on few spans is what keeps the
pole count low: an involute is analytic, so the error falls like ``h^(degree + 1)``.

:func:`fit_rotation` fits the unit circle ``(cos(k z), sin(k z))`` over a helical gear's face
the same way; turning a profile spline's poles by that approximate rotation, row by row, gives
the helicoid surface's poles (see :mod:`geargen.cad.gear_solid`).

Conventions: mm and rad; ``poles`` ``(n, 2) float``; knots as distinct values with
multiplicities, clamped (end multiplicity ``degree + 1``), parameter from 0 to ``length``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import BSpline

#: default B-spline degree of the fitted flank and fillet curves (see bench/bench_gear.py)
FIT_DEGREE = 7
#: fitted points per span (the least-squares problem), and check points per span
_FIT_PER_SPAN = 24
_CHECK_PER_SPAN = 32


@dataclass(frozen=True)
class SplineFit:
    """A clamped B-spline on uniform knots and its measured distance from the exact curve.

    ``knots`` distinct knot values (0 .. ``length``), ``mults`` their multiplicities, ``poles``
    ``(n, d)``; ``max_error`` the largest distance (mm) to the exact curve at the same
    parameter over the check points; ``native`` the exact curve's parameter at s = 0 and at
    s = ``length`` (linear in between).
    """

    degree: int
    knots: np.ndarray
    mults: tuple[int, ...]
    poles: np.ndarray
    max_error: float
    length: float
    native: tuple[float, float]

    @property
    def spans(self) -> int:
        return len(self.knots) - 1

    def full_knots(self) -> np.ndarray:
        return np.repeat(self.knots, self.mults)

    def evaluate(self, s) -> np.ndarray:
        """Spline points ``(n, d)`` at parameters ``s`` (0 .. length)."""
        return BSpline(self.full_knots(), self.poles, self.degree)(np.ravel(s))

    def native_parameter(self, s) -> np.ndarray:
        """The exact curve's parameter at spline parameters ``s``."""
        t0, t1 = self.native
        return t0 + (t1 - t0) * np.asarray(s, dtype=float) / self.length


def _fit(point, deriv, length: float, tolerance: float, degree: int, max_spans: int):
    """Fewest uniform spans whose constrained least-squares fit of ``point`` is within ``tolerance``.

    ``point(s)``/``deriv(s)`` give ``(n, d)`` exact values and d/ds for s in [0, length].
    Returns (poles, knots, mults, max_error).
    """
    p0, p1 = point(np.array([0.0, length]))
    d0, d1 = deriv(np.array([0.0, length]))
    for spans in range(1, max_spans + 1):
        knots = np.linspace(0.0, length, spans + 1)
        mults = (degree + 1,) + (1,) * (spans - 1) + (degree + 1,)
        t = np.repeat(knots, mults)
        n = spans + degree
        h0, h1 = knots[1] - knots[0], knots[-1] - knots[-2]
        fixed = {0: p0, 1: p0 + d0 * h0 / degree, n - 2: p1 - d1 * h1 / degree, n - 1: p1}
        free = [i for i in range(n) if i not in fixed]
        # fit points: interior Chebyshev-like nodes per span (denser at the span ends)
        frac = 0.5 - 0.5 * np.cos(np.pi * (np.arange(_FIT_PER_SPAN) + 0.5) / _FIT_PER_SPAN)
        s_fit = (knots[:-1, None] + np.diff(knots)[:, None] * frac[None, :]).ravel()
        a = BSpline.design_matrix(s_fit, t, degree).toarray()
        rhs = point(s_fit) - sum(a[:, i:i + 1] * v[None, :] for i, v in fixed.items())
        poles = np.empty((n, len(p0)))
        for i, v in fixed.items():
            poles[i] = v
        if free:
            poles[free] = np.linalg.lstsq(a[:, free], rhs, rcond=None)[0]
        # check points: evenly spaced, none of them a fit point
        s_chk = np.linspace(0.0, length, spans * _CHECK_PER_SPAN + 2)
        err = float(np.max(np.linalg.norm(BSpline(t, poles, degree)(s_chk) - point(s_chk), axis=1)))
        if err <= tolerance:
            return poles, knots, mults, err
    raise ValueError(f"no fit within {tolerance:g} mm on {max_spans} spans of degree {degree}")


def _length(segment) -> float:
    """Length of a segment (mm): polyline of 257 points, ~1e-6 relative (only the scale of the
    parameter depends on it, not the accuracy of the fit)."""
    p = segment.point(segment.parameters(257))
    return float(np.sum(np.linalg.norm(np.diff(p, axis=0), axis=1)))


def fit_segment(segment, tolerance: float, degree: int = FIT_DEGREE, max_spans: int = 64) -> SplineFit:
    """Fit a :class:`geargen.profile.segments.Segment` in its direction of traversal (t0 -> t1).

    The spline parameter s runs from 0 to the segment's length, linear in the segment's own
    parameter. Raises ValueError if ``max_spans`` uniform spans do not reach ``tolerance`` mm.
    """
    length = _length(segment)
    t0, t1 = segment.t0, segment.t1
    scale = (t1 - t0) / length

    def point(s):
        return segment.point(t0 + scale * s)

    def deriv(s):
        return segment.derivative(t0 + scale * s) * scale

    poles, knots, mults, err = _fit(point, deriv, length, tolerance, degree, max_spans)
    return SplineFit(degree, knots, mults, poles, err, length, (t0, t1))


def fit_rotation(rate: float, length: float, tolerance: float, degree: int = FIT_DEGREE,
                 max_spans: int = 64) -> SplineFit:
    """Fit ``(cos(rate z), sin(rate z))`` for z in [0, length] (mm; ``rate`` rad/mm) to
    ``tolerance`` (unitless: the distance on the unit circle, which is also the operator norm of
    the error of the rotation matrix built from it). Exact at both ends (end poles ``(1, 0)`` and
    ``(cos, sin)(rate length)``)."""
    def point(z):
        return np.column_stack([np.cos(rate * z), np.sin(rate * z)])

    def deriv(z):
        return rate * np.column_stack([-np.sin(rate * z), np.cos(rate * z)])

    poles, knots, mults, err = _fit(point, deriv, length, tolerance, degree, max_spans)
    return SplineFit(degree, knots, mults, poles, err, length, (0.0, rate * length))


def greville(fit: SplineFit) -> np.ndarray:
    """Greville abscissae ``(n,)`` of ``fit``'s basis: the poles of the identity function s -> s
    (so a spline with these as its z poles has z(s) = s exactly)."""
    t = fit.full_knots()
    p = fit.degree
    return np.array([t[i + 1:i + p + 1].mean() for i in range(len(t) - p - 1)])


def parameter_speed_ratio(segment, samples: int = 257) -> float:
    """max/min of |dC/dt| over the segment: how unevenly its own parameter runs (1 = by arc length)."""
    d = np.linalg.norm(segment.derivative(segment.parameters(samples)), axis=1)
    return float(np.max(d) / max(np.min(d), 1e-300)) if math.isfinite(float(np.min(d))) else math.inf


__all__ = ["SplineFit", "fit_segment", "fit_rotation", "greville", "parameter_speed_ratio", "FIT_DEGREE"]
