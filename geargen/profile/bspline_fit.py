"""Few-pole B-spline fits of the exact outline's segments (numpy/scipy only).

The CAD layer gives every flank and fillet of a gear its own face; each face's curve is one
clamped B-spline of degree ``degree`` (default 7) on uniform knots. The end points and end
tangents are exact (neighbouring faces meet in the exact joint with the exact tangent); the
poles in between are a least-squares fit to exact points (24 per span, Chebyshev-spaced), and
the number of spans grows until the distance between the spline and the exact curve at the
same parameter - an upper bound on the geometric distance - is within ``tolerance`` at every
check point (32 per span, evenly spaced, none a fit point). A high degree on few spans keeps
the pole count low: the curves are analytic, so the error falls like ``h^(degree + 1)``
(degree 3 needs 3-4x the poles of degree 7 for a fillet at 1 nm; degrees 5-9 differ little).

Parametrisation (``by_length``): by arc length, so the parameter runs evenly - for the
involute in closed form (s = r_b (t^2 - t0^2) / 2 in the roll angle t), for the fillet through
a Chebyshev fit of the inverse of its Gauss-Legendre arc length. OCCT's mesher follows the
parameter: on the 112-tooth spur gear an arc-length fillet face tessellates at 1 um into ~24
triangles, a roll-angle one into ~4300. Without ``by_length`` the segment's own parameter
(roll angle, rack-tip angle) scaled to the length is used.

:func:`fit_rotation` fits the unit circle ``(cos(k z), sin(k z))`` over a helical gear's face
the same way; turning a profile spline's poles by that approximate rotation, row by row, gives
the helicoid surface's poles (see :mod:`geargen.cad.gear_solid`).

Conventions: mm and rad; ``poles`` ``(n, 2) float``; knots as distinct values with
multiplicities, clamped (end multiplicity ``degree + 1``), parameter from 0 to ``length``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import BSpline

from geargen.profile.segments import InvoluteCurve

#: default B-spline degree of the fitted curves (fewest poles at the gear tolerances, module docstring)
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
    s = ``length``, linear in between unless ``by_length`` (then s is the arc length).
    """

    degree: int
    knots: np.ndarray
    mults: tuple[int, ...]
    poles: np.ndarray
    max_error: float
    length: float
    native: tuple[float, float]
    by_length: bool = False

    def full_knots(self) -> np.ndarray:
        return np.repeat(self.knots, self.mults)


def fit_fractions(per_span: int) -> np.ndarray:
    """Where the fit points sit inside a span, as fractions in (0, 1): Chebyshev nodes, denser at
    the span's ends (where a B-spline's error would otherwise gather)."""
    return 0.5 - 0.5 * np.cos(np.pi * (np.arange(per_span) + 0.5) / per_span)


def fit_nodes(spans: int, per_span: int, chebyshev: bool) -> np.ndarray:
    """Parameters in [0, 1]: both ends and ``per_span`` points inside each of ``spans`` uniform
    spans (Chebyshev-spaced, :func:`fit_fractions`), or without ``chebyshev`` evenly spaced without
    either end (check points, none of them a fit point)."""
    k = np.arange(per_span)
    frac = fit_fractions(per_span) if chebyshev else (k + 1) / (per_span + 1)
    inner = ((np.arange(spans)[:, None] + frac[None, :]) / spans).ravel()
    return np.concatenate([[0.0], inner, [1.0]]) if chebyshev else inner


def clamped_uniform_knots(spans: int, degree: int) -> np.ndarray:
    """Knots (flat) of a clamped B-spline of ``spans`` uniform spans on [0, 1]."""
    return np.concatenate([np.zeros(degree), np.linspace(0.0, 1.0, spans + 1), np.ones(degree)])


def fit_clamped(data: np.ndarray, params: np.ndarray, spans: int, degree: int) -> np.ndarray:
    """Poles (m, spans + degree, d) of the clamped uniform B-splines on [0, 1] fitting ``data``
    (m, n, d) at ``params`` (n,) by least squares, each with its end poles the data's end points
    (``params`` from :func:`fit_nodes`, which include both ends)."""
    design = BSpline.design_matrix(params, clamped_uniform_knots(spans, degree), degree).toarray()
    n = spans + degree
    poles = np.empty((data.shape[0], n, data.shape[2]))
    poles[:, 0], poles[:, -1] = data[:, 0], data[:, -1]
    rhs = data - design[None, :, :1] @ poles[:, :1] - design[None, :, -1:] @ poles[:, -1:]
    inner = np.linalg.lstsq(design[:, 1:-1], rhs.transpose(1, 0, 2).reshape(len(params), -1), rcond=None)[0]
    poles[:, 1:-1] = inner.reshape(n - 2, data.shape[0], data.shape[2]).transpose(1, 0, 2)
    return poles


def clamped_values(poles: np.ndarray, params: np.ndarray, spans: int, degree: int) -> np.ndarray:
    """The clamped uniform B-splines of ``poles`` (m, n, d) at ``params``: (m, len(params), d)."""
    basis = BSpline.design_matrix(params, clamped_uniform_knots(spans, degree), degree).toarray()
    return np.einsum("pi,mid->mpd", basis, poles)


def greville_abscissae(knots: np.ndarray, degree: int) -> np.ndarray:
    """Greville abscissae ``(n,)`` of the basis on the flat ``knots``: the poles of the identity
    function s -> s (so a spline with these as its z poles has z(s) = s exactly)."""
    return np.array([knots[i + 1:i + degree + 1].mean() for i in range(len(knots) - degree - 1)])


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
        frac = fit_fractions(_FIT_PER_SPAN)
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


def _arc_length_map(segment, order: int = 24):
    """A smooth map s -> t (spline parameter by arc length -> the segment's parameter) and its
    derivative: the segment's arc length on a Gauss-Legendre grid, inverted by a Chebyshev fit of
    t(s). Only the parametrisation depends on it (every point C(t(s)) lies on the exact curve);
    returns None if the fitted map is not monotone (then the caller keeps the own parameter)."""
    t0, t1 = segment.t0, segment.t1
    if isinstance(segment.curve, InvoluteCurve):
        return _involute_length_map(segment)
    # arc length at the ends of 64 pieces, 8-point Gauss-Legendre on each (~1e-15 relative)
    edges = np.linspace(t0, t1, 65)
    x, w = np.polynomial.legendre.leggauss(8)
    half = 0.5 * np.diff(edges)
    nodes = (0.5 * (edges[:-1] + edges[1:]))[:, None] + half[:, None] * x[None, :]
    speed = np.linalg.norm(segment.derivative(nodes.ravel()), axis=1).reshape(nodes.shape)
    arc = np.concatenate([[0.0], np.cumsum(np.abs(half) * (speed @ w))])
    tt = edges
    length = float(arc[-1])
    cheb = np.polynomial.chebyshev.Chebyshev.fit(arc, tt, order, domain=[0.0, length])
    dcheb = cheb.deriv()
    probe = dcheb(np.linspace(0.0, length, 1001)) * (1.0 if t1 >= t0 else -1.0)
    if not np.all(probe > 0):
        return None
    # pin the ends exactly (the fit is good to ~1e-12 of the range; the ends must be the joints)
    e0, e1 = float(cheb(0.0)) - t0, float(cheb(length)) - t1

    def t_of(s):
        s = np.asarray(s, dtype=float)
        return cheb(s) - e0 - (e1 - e0) * s / length

    def dt_ds(s):
        return dcheb(np.asarray(s, dtype=float)) - (e1 - e0) / length

    return length, t_of, dt_ds


def _involute_length_map(segment):
    """The involute's own arc length: s = r_b |t^2 - t0^2| / 2 from roll angle t0, so
    t(s) = sqrt(t0^2 +- 2 s / r_b) in closed form. None when the flank starts too near the base
    circle (t -> 0 makes dt/ds unbounded and the fit slow to converge): the roll angle is kept."""
    t0, t1 = segment.t0, segment.t1
    if min(t0, t1) < 0.1 * max(t0, t1):
        return None
    rb = segment.curve.base_radius
    sign = 1.0 if t1 >= t0 else -1.0
    length = rb * abs(t1 * t1 - t0 * t0) / 2

    def t_of(s):
        return np.sqrt(t0 * t0 + sign * 2.0 * np.asarray(s, dtype=float) / rb)

    def dt_ds(s):
        return sign / (rb * t_of(s))

    return length, t_of, dt_ds


def fit_segment(segment, tolerance: float, degree: int = FIT_DEGREE, max_spans: int = 64,
                by_length: bool = False) -> SplineFit:
    """Fit a :class:`geargen.profile.segments.Segment` in its direction of traversal (t0 -> t1).

    The spline parameter s runs from 0 to the segment's length: linear in the segment's own
    parameter, or (``by_length``) the arc length itself (unit speed, within ~1e-6). Raises
    ValueError if ``max_spans`` uniform spans do not reach ``tolerance`` mm.
    """
    t0, t1 = segment.t0, segment.t1
    mapped = _arc_length_map(segment) if by_length else None
    if mapped is None:
        length = _length(segment)
        scale = (t1 - t0) / length

        def t_of(s):
            return t0 + scale * np.asarray(s, dtype=float)

        def dt_ds(s):
            return np.full(np.shape(s), scale)
    else:
        length, t_of, dt_ds = mapped

    def point(s):
        return segment.point(t_of(s))

    def deriv(s):
        return segment.derivative(t_of(s)) * dt_ds(s)[:, None]

    poles, knots, mults, err = _fit(point, deriv, length, tolerance, degree, max_spans)
    return SplineFit(degree, knots, mults, poles, err, length, (t0, t1), mapped is not None)


def fit_function(point, deriv, length: float, tolerance: float, degree: int = FIT_DEGREE,
                 max_spans: int = 64) -> SplineFit:
    """Fit any smooth curve ``point(s)`` ``(n, d)`` for s in [0, ``length``] (``deriv`` its d/ds) the
    same way as a segment (exact ends and end tangents, fewest uniform spans within ``tolerance`` at
    the same parameter); its columns may mix coordinates, e.g. a 3-D curve with its curve on a
    surface, which then share knots and parameter."""
    poles, knots, mults, err = _fit(point, deriv, length, tolerance, degree, max_spans)
    return SplineFit(degree, knots, mults, poles, err, length, (0.0, length))


def fit_rotation(rate: float, length: float, tolerance: float, degree: int | None = FIT_DEGREE,
                 max_spans: int = 64) -> SplineFit:
    """Fit ``(cos(rate z), sin(rate z))`` for z in [0, length] (mm; ``rate`` rad/mm) to
    ``tolerance`` (unitless: the distance on the unit circle, which is also the operator norm of
    the error of the rotation matrix built from it). Exact at both ends (end poles ``(1, 0)`` and
    ``(cos, sin)(rate length)``). ``degree`` None: the fewest poles, one span of degree 3 to
    :data:`FIT_DEGREE` if one reaches ``tolerance`` (a small twist: 5-7 poles where degree 7 has 8),
    else spans of degree :data:`FIT_DEGREE`."""
    def point(z):
        return np.column_stack([np.cos(rate * z), np.sin(rate * z)])

    def deriv(z):
        return rate * np.column_stack([-np.sin(rate * z), np.cos(rate * z)])

    if degree is None:
        for low in range(3, FIT_DEGREE):
            try:
                poles, knots, mults, err = _fit(point, deriv, length, tolerance, low, 1)
            except ValueError:
                continue
            return SplineFit(low, knots, mults, poles, err, length, (0.0, rate * length))
        degree = FIT_DEGREE
    poles, knots, mults, err = _fit(point, deriv, length, tolerance, degree, max_spans)
    return SplineFit(degree, knots, mults, poles, err, length, (0.0, rate * length))


def greville(fit: SplineFit) -> np.ndarray:
    """Greville abscissae ``(n,)`` of ``fit``'s basis (:func:`greville_abscissae`)."""
    return greville_abscissae(fit.full_knots(), fit.degree)


__all__ = ["SplineFit", "fit_segment", "fit_function", "fit_rotation", "greville", "FIT_DEGREE", "fit_fractions",
           "fit_nodes", "clamped_uniform_knots", "fit_clamped", "clamped_values", "greville_abscissae"]
