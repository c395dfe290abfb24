"""Least-squares periodogram over orders per output revolution.

For each trial order q the residual r (n,) sampled at output angles theta (n,) is fitted by
``a cos(q theta) + b sin(q theta)`` by least squares; the periodogram is the drop in the sum of
squares that fit buys (Lomb-Scargle in its least-squares form). Least squares needs no even
spacing, no whole number of revolutions and no filled gaps: drop-outs are simply samples that
are not there, and a trace that turns back covers the same angles twice.

The sums ``sum r exp(-i q theta)`` and ``sum exp(-2 i q theta)`` over the whole order grid come
from one FFT each: samples are spread onto a fine regular angle grid with linear (tent) weights,
whose transfer ``sinc^2`` is divided out; the grid is 32 points per period of the highest order,
so the spreading error is below 0.3 % in amplitude. Peaks are then refined by exact sums.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True, eq=False)
class Periodogram:
    """``orders`` (m,) per output revolution; ``reduction`` (m,) drop in sum of squares of the
    two-term fit at each order (residual units squared); ``amplitude`` (m,) fitted amplitude;
    ``resolution``: 1 / revolutions spanned (orders)."""

    orders: np.ndarray
    reduction: np.ndarray
    amplitude: np.ndarray
    resolution: float


#: samples spread onto the grid at a time (the spreading's temporaries stay this size)
SPREAD_BLOCK = 1 << 17


def _spread(position: np.ndarray, weights: np.ndarray, length: int) -> np.ndarray:
    """Linear (tent) spreading of weights at fractional grid positions onto a grid."""
    i0 = np.floor(position).astype(np.int64)
    frac = position - i0
    grid = np.bincount(i0, weights * (1.0 - frac), minlength=length + 2)
    grid += np.bincount(i0 + 1, weights * frac, minlength=length + 2)
    return grid


def _spread_blocks(theta: np.ndarray, rev0: float, d_rev: float, weights: np.ndarray | None, offset: float,
                   length: int, out: np.ndarray) -> None:
    """Add the tent spreading of ``weights - offset`` (ones when None) at angles ``theta`` (rad,
    turned into grid positions ``(theta / 2 pi - rev0) / d_rev``) to ``out[:length + 2]``, block
    by block."""
    n = theta.size
    for lo in range(0, n, SPREAD_BLOCK):
        hi = min(lo + SPREAD_BLOCK, n)
        position = (theta[lo:hi] / TWO_PI - rev0) / d_rev
        w = np.ones(hi - lo) if weights is None else weights[lo:hi] - offset if offset else weights[lo:hi]
        out[:length + 2] += _spread(position, w, length)


def _two_term_fit(c, s, cc, ss, cs):
    """Least-squares (a, b) and sum-of-squares drop of ``a cos + b sin`` from the sums."""
    det = cc * ss - cs * cs
    safe = np.where(det > 0, det, np.inf)
    a = (ss * c - cs * s) / safe
    b = (cc * s - cs * c) / safe
    return a, b, a * c + b * s


#: the spreading grid of :func:`ls_periodogram` holds at most this many points, or one per two
#: samples for longer records; its FFTs then cost about as much memory as two of the record's arrays
MIN_GRID_CAP = 1 << 20


def ls_periodogram(angle_rad: np.ndarray, residual: np.ndarray, order_min: float, order_max: float,
                   oversample: int = 5, offset: float = 0.0) -> Periodogram:
    """Least-squares periodogram of ``residual - offset`` (n,) at output angles (n,) rad over
    [order_min, order_max] (the offset is taken off block by block, without a copy of the residual).

    The spreading grid is bounded (:data:`MIN_GRID_CAP`, or n / 2 points): a record spanning so
    many revolutions that 32 points per period of ``order_max`` with a step of resolution /
    ``oversample`` would not fit takes, in turn, fewer grid points per period (down to 4, the
    tent's aliasing then below about 10 % of a peak's power; peaks are refined by exact sums
    anyway), a coarser order step (down to the resolution), and at last a lower top order:
    ``orders`` says how far the spectrum reaches.
    """
    theta = np.asarray(angle_rad, dtype=float)
    r = np.asarray(residual, dtype=float)
    rev0 = float(theta.min()) / TWO_PI  # = min(theta / 2 pi): dividing by a constant keeps the order
    span = max(float(theta.max()) / TWO_PI - rev0, 1e-12)
    resolution = 1.0 / span
    top = max(order_max, 1.0)
    d_rev = 1.0 / (32.0 * top)  # grid step, revolutions
    # FFT length gives an order step of resolution / oversample
    n_fft = int(2 ** math.ceil(math.log2(max(oversample * span / d_rev, span / d_rev + 4))))
    cap = max(MIN_GRID_CAP, 2 ** int(math.floor(math.log2(max(r.size // 2, 1)))))
    if n_fft > cap:
        n_fft = cap
        coarsest = 1.0 / (4.0 * top)
        d_rev = max(d_rev, oversample * span / (n_fft - 8))
        if d_rev > coarsest:
            d_rev = max(coarsest, span / (n_fft - 8))
    d_rev = oversample * span / n_fft if oversample * span / n_fft <= d_rev else d_rev
    order_step = 1.0 / (n_fft * d_rev)
    length = int(math.ceil(span / d_rev)) + 2
    if length + 2 > n_fft:
        n_fft = int(2 ** math.ceil(math.log2(length + 2)))
        order_step = 1.0 / (n_fft * d_rev)
    g_r = np.zeros(n_fft)
    _spread_blocks(theta, rev0, d_rev, r, offset, length, g_r)
    f_r = np.fft.rfft(g_r)
    del g_r
    g_1 = np.zeros(n_fft)
    _spread_blocks(theta, rev0, d_rev, None, 0.0, length, g_1)
    f_1 = np.fft.rfft(g_1)
    del g_1
    k_lo = max(int(math.floor(order_min / order_step)), 1)
    k_hi = int(math.ceil(min(order_max, 1.0 / (4.0 * d_rev)) / order_step))
    k_hi = min(k_hi, (f_1.size - 1) // 2)
    k = np.arange(k_lo, k_hi + 1)
    q = k * order_step
    transfer = np.sinc(q * d_rev) ** 2
    transfer2 = np.sinc(2 * q * d_rev) ** 2
    # sum r exp(-i 2 pi q rev) = exp(-i 2 pi q rev0) * FFT; same at 2q for the normal equations
    s_r = f_r[k] * np.exp(-1j * TWO_PI * q * rev0) / transfer
    s_2 = f_1[2 * k] * np.exp(-1j * TWO_PI * 2 * q * rev0) / transfer2
    n = r.size
    c = s_r.real
    s = -s_r.imag
    cc = 0.5 * (n + s_2.real)
    ss = 0.5 * (n - s_2.real)
    cs = -0.5 * s_2.imag
    a, b, red = _two_term_fit(c, s, cc, ss, cs)
    return Periodogram(orders=q, reduction=np.maximum(red, 0.0), amplitude=np.hypot(a, b), resolution=resolution)


def exact_fit(angle_rad: np.ndarray, residual: np.ndarray, order: float) -> tuple[float, float, float]:
    """(a, b, drop in sum of squares) of ``a cos(q theta) + b sin(q theta)`` fitted exactly."""
    phase = order * np.asarray(angle_rad, dtype=float)
    cos, sin = np.cos(phase), np.sin(phase)
    r = np.asarray(residual, dtype=float)
    a, b, red = _two_term_fit(float(cos @ r), float(sin @ r), float(cos @ cos), float(sin @ sin), float(cos @ sin))
    return float(a), float(b), float(red)


def refine_order(angle_rad: np.ndarray, residual: np.ndarray, order: float, half_width: float) -> tuple[float, float]:
    """The order within ``order +- half_width`` where the exact two-term fit removes most; (order, drop)."""
    res = minimize_scalar(lambda q: -exact_fit(angle_rad, residual, q)[2], bounds=(order - half_width, order + half_width),
                          method="bounded", options={"xatol": 1e-7 * max(1.0, abs(order))})
    q = float(res.x)
    return q, exact_fit(angle_rad, residual, q)[2]


def peaks(pg: Periodogram, count: int, exclude: list[float] = (), exclusion: float | None = None) -> list[int]:
    """Indices of the ``count`` highest local maxima, skipping orders within ``exclusion`` of ``exclude``."""
    red = pg.reduction
    if red.size < 3:
        return []
    local = np.flatnonzero((red[1:-1] >= red[:-2]) & (red[1:-1] >= red[2:])) + 1
    if exclusion is None:
        exclusion = pg.resolution
    ok = np.ones(local.size, bool)
    for e in exclude:
        ok &= np.abs(pg.orders[local] - e) > exclusion
    local = local[ok]
    order = np.argsort(red[local])[::-1]
    chosen: list[int] = []
    for i in local[order]:
        if all(abs(pg.orders[i] - pg.orders[j]) > pg.resolution for j in chosen):
            chosen.append(int(i))
        if len(chosen) >= count:
            break
    return chosen
