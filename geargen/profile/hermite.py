"""Piecewise cubic Hermite interpolation of a segment to a given accuracy (numpy only).

The CAD layer turns each analytic segment into a C1 cubic B-spline that interpolates exact
points with exact derivatives at nodes chosen here; :func:`hermite_nodes` picks the fewest
evenly spaced nodes for which the interpolant stays within ``tolerance`` of the exact curve
(checked against the exact curve at interior points of every interval, not estimated).
"""

from __future__ import annotations

import numpy as np

# where inside each interval the interpolant is compared with the exact curve
_CHECK = np.array([0.1, 0.21132487, 0.5, 0.78867513, 0.9])


def hermite_eval(p0, p1, d0, d1, h, s):
    """Cubic Hermite interpolant between ``p0``/``p1`` (``(n, 2)``) with derivatives ``d0``/``d1``
    w.r.t. a parameter spanning ``h`` per interval, at fractions ``s`` ``(k,)`` of each interval.

    Returns ``(n, k, 2)``.
    """
    s = s[None, :, None]
    h00 = 2 * s ** 3 - 3 * s ** 2 + 1
    h10 = s ** 3 - 2 * s ** 2 + s
    h01 = -2 * s ** 3 + 3 * s ** 2
    h11 = s ** 3 - s ** 2
    hh = np.asarray(h, dtype=float).reshape(-1, 1, 1)
    return (h00 * p0[:, None, :] + h10 * hh * d0[:, None, :] + h01 * p1[:, None, :]
            + h11 * hh * d1[:, None, :])


def hermite_errors(segment, params: np.ndarray) -> np.ndarray:
    """Per interval, the largest distance (mm) between the segment and its Hermite interpolant on
    ``params`` (checked at five interior points of each interval)."""
    p = segment.point(params)
    d = segment.derivative(params)
    h = np.diff(params)
    approx = hermite_eval(p[:-1], p[1:], d[:-1], d[1:], h, _CHECK)
    exact = segment.point((params[:-1, None] + h[:, None] * _CHECK[None, :]).ravel()).reshape(approx.shape)
    return np.max(np.linalg.norm(approx - exact, axis=2), axis=1)


def hermite_error(segment, params: np.ndarray) -> float:
    """Largest distance (mm) between the segment and its Hermite interpolant on ``params``."""
    return float(np.max(hermite_errors(segment, params)))


def hermite_nodes(segment, tolerance: float, min_intervals: int = 2, max_nodes: int = 4097) -> np.ndarray:
    """Parameters from ``segment.t0`` to ``segment.t1`` (traversal order) whose cubic Hermite
    interpolant is within ``tolerance`` mm of the segment.

    Starts from ``min_intervals`` even intervals and halves every interval whose error (checked
    against the exact curve) exceeds the tolerance, so nodes crowd where the curve needs them.
    """
    params = segment.parameters(max(1, min_intervals) + 1)
    while True:
        bad = hermite_errors(segment, params) > tolerance
        if not np.any(bad):
            return params
        mids = 0.5 * (params[:-1] + params[1:])[bad]
        params = np.insert(params, np.nonzero(bad)[0] + 1, mids)
        if len(params) > max_nodes:
            raise ValueError(f"{segment.kind} segment needs more than {max_nodes} Hermite nodes "
                             f"for {tolerance:g} mm")


def hermite_poles(values: np.ndarray, derivs: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """C1 cubic B-spline poles (along axis 0) of the Hermite interpolant of ``values`` with
    derivatives ``derivs`` at the increasing parameters ``tau`` ``(n + 1,)``: ``(2n + 2, ...)``.

    Each interval's Bezier inner poles are ``p +/- h d / 3``; with the knots of
    :func:`hermite_knots` (interior multiplicity 2) the spline is exactly the Hermite cubic."""
    h = np.diff(tau).reshape((-1,) + (1,) * (values.ndim - 1))
    after = values[:-1] + h * derivs[:-1] / 3.0
    before = values[1:] - h * derivs[1:] / 3.0
    out = np.empty((2 * len(tau),) + values.shape[1:])
    out[0] = values[0]
    out[1:-1:2] = after
    out[2:-1:2] = before
    out[-1] = values[-1]
    return out


def hermite_knots(tau: np.ndarray):
    """Knots of :func:`hermite_poles`: ``(values, multiplicities)``, ``tau`` with multiplicity 4
    at the ends and 2 inside."""
    return tau, [4] + [2] * (len(tau) - 2) + [4]


def segment_spline(segment, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
    """A C1 cubic B-spline within ``tolerance`` mm of ``segment`` (traversal order): poles
    ``(2n + 2, 2)`` (mm) and the full knot vector ``(2n + 6,)`` (parameter distance from the start).
    The first and last poles are the segment's exact end points."""
    params = hermite_nodes(segment, tolerance)
    sign = 1.0 if segment.t1 >= segment.t0 else -1.0
    tau = np.abs(params - params[0])
    poles = hermite_poles(segment.point(params), segment.derivative(params) * sign, tau)
    values, mults = hermite_knots(tau)
    return poles, np.repeat(values, mults)
