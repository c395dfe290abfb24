"""The effect library: physical effects a declared model may lack, as array functions.

Each effect is a small, separately testable function of arrays; the models in
:mod:`geargen.fit.model` combine them with the declared model and fit all parameters together.

========== ============================================= ==================================
effect     law (added to the model, residual units)      parameters (JSON names)
========== ============================================= ==================================
harmonic   ``A cos(q*theta - phi)``, theta output angle  ``order`` q, ``amplitude`` A,
                                                         ``phase_deg`` phi
drift      ``c * (v - v_ref)``, v temperature or time    ``per_kelvin`` / ``per_second`` c
hysteresis play operator of half-width h (friction)      ``half_width`` h
stiffening ``A sign(phi) |phi/phi_ref|^n`` (Hertzian)    ``exponent`` n, ``amplitude`` A at
                                                         phi_ref = 1 mrad
dead_band  zone of width w around zero torque with no    ``width_urad`` w
           stiffness: the law sees ``dead_zone(phi, w)``
========== ============================================= ==================================

``harmonic`` applies to ``preload_trace``; ``stiffening`` and ``dead_band`` to
``torque_deflection``; ``drift`` and ``hysteresis`` to both.
"""

from __future__ import annotations

import numpy as np

#: effect name -> (measurement kinds it applies to, parameters it reports, one-line meaning)
LIBRARY: dict[str, tuple[tuple[str, ...], tuple[str, ...], str]] = {
    "harmonic": (("preload_trace",), ("order", "amplitude", "phase_deg", "shaft", "multiple"),
                 "a sinusoid at an order the declared model lacks"),
    "drift": (("preload_trace", "torque_deflection"), ("per_kelvin", "per_second"),
              "a slow change with temperature, or with time when there is no temperature column"),
    "hysteresis": (("preload_trace", "torque_deflection"), ("half_width",),
                   "friction: a play operator of half-width h, the signal depends on the direction of motion"),
    "stiffening": (("torque_deflection",), ("exponent", "amplitude"),
                   "contact stiffness that rises with load (Hertzian), the curve bends upward"),
    "dead_band": (("torque_deflection",), ("width_urad",),
                  "lost motion: a zone around zero torque with no stiffness"),
}

#: number of free parameters each effect adds (the harmonic's order counts: it is searched for)
PARAMETER_COUNT = {"harmonic": 3, "drift": 1, "hysteresis": 1, "stiffening": 2, "dead_band": 1}

#: reference rotation of the stiffening law, rad: ``amplitude`` is the extra torque there
STIFFENING_REFERENCE_RAD = 1.0e-3


def effects_for(kind: str) -> tuple[str, ...]:
    """Names of the library effects that apply to a measurement kind."""
    return tuple(name for name, (kinds, _, _) in LIBRARY.items() if kind in kinds)


# ----------------------------------------------------------------------------------- harmonic

def harmonic_basis(angle_rad: np.ndarray, order: float) -> np.ndarray:
    """Columns ``cos(q*theta)``, ``sin(q*theta)``: (n, 2) float for angles (n,) rad, order q."""
    phase = order * np.asarray(angle_rad, dtype=float)
    return np.column_stack([np.cos(phase), np.sin(phase)])


def harmonic_parameters(cos_coefficient: float, sin_coefficient: float) -> tuple[float, float]:
    """(amplitude, phase_deg in [0, 360)) of ``a cos + b sin = A cos(q theta - phi)``."""
    amplitude = float(np.hypot(cos_coefficient, sin_coefficient))
    phase = float(np.degrees(np.arctan2(sin_coefficient, cos_coefficient)) % 360.0)
    return amplitude, phase


def harmonic(angle_rad: np.ndarray, order: float, amplitude: float, phase_deg: float) -> np.ndarray:
    """``A cos(q*theta - phi)``: (n,) for angles (n,) rad."""
    return amplitude * np.cos(order * np.asarray(angle_rad, dtype=float) - np.radians(phase_deg))


# -------------------------------------------------------------------------------------- drift

def drift(variable: np.ndarray, rate: float, reference: float) -> np.ndarray:
    """``rate * (v - reference)``: a linear change with temperature (K) or time (s)."""
    return rate * (np.asarray(variable, dtype=float) - reference)


# --------------------------------------------------------------------------------- hysteresis

def play_operator(u: np.ndarray, half_width: float, initial: float | None = None) -> np.ndarray:
    """The play (backlash) operator: output y lags input u by a play of half-width h.

    ``y[k] = clip(y[k-1], u[k] - h, u[k] + h)`` with ``y[-1] = initial`` (default ``u[0]``).
    u: (n,) float; returns (n,) float. Computed without a Python loop over samples (see
    :func:`_play_block`), in blocks of :data:`PLAY_BLOCK` samples.
    """
    u = np.asarray(u, dtype=float)
    h = float(half_width)
    if h < 0:
        raise ValueError("half_width must be >= 0")
    y = np.empty(u.size)
    previous = float(u[0]) if initial is None else float(initial)
    for start in range(0, u.size, PLAY_BLOCK):
        stop = min(start + PLAY_BLOCK, u.size)
        y[start:stop] = _play_block(u[start:stop], h, previous)
        previous = float(y[stop - 1])
    return y


#: samples of the play operator composed at a time: the doubling scan's temporaries stay this size
PLAY_BLOCK = 1 << 17


def play_structure(u: np.ndarray, half_width: float, initial: float | None = None):
    """Play operator output and its local linear structure.

    Returns ``(y, source, side)``: y (n,) the play output; ``source`` (n,) int the index of the
    sample whose input the output currently rests on (the last engagement; 0 before the first);
    ``side`` (n,) float -1 where the output was last pushed up (y = u[source] - h), +1 where
    pushed down (y = u[source] + h), 0 before the first engagement. Locally
    ``y = u[source] + side * h``, which makes the play linear in u and h for Gauss-Newton fits.

    Long inputs are processed in blocks of :data:`PLAY_BLOCK` samples, each started from the
    previous block's last output (the play is a recursion, so this is exact) and carrying the
    last engagement across.
    """
    u = np.asarray(u, dtype=float)
    h = float(half_width)
    if h < 0:
        raise ValueError("half_width must be >= 0")
    n = u.size
    y = np.empty(n)
    source = np.empty(n, dtype=np.int64)
    side = np.empty(n)
    previous = float(u[0]) if initial is None else float(initial)
    last_source, last_side = 0, 0.0  # before the first engagement
    for start in range(0, n, PLAY_BLOCK):
        stop = min(start + PLAY_BLOCK, n)
        ub = u[start:stop]
        yb = _play_block(ub, h, previous)
        y[start:stop] = yb
        previous = float(yb[-1])
        index = np.arange(stop - start)
        if h == 0.0:  # y = u; the side is the one the play would take as h grows from zero
            source[start:stop] = index + start
            side[start:stop] = -np.sign(np.diff(ub, prepend=u[start - 1] if start else u[0]))
            continue
        pushed_up = yb == ub - h
        pushed_down = (yb == ub + h) & ~pushed_up
        engaged = pushed_up | pushed_down
        last = np.maximum.accumulate(np.where(engaged, index, -1))
        side_now = np.where(pushed_up, -1.0, np.where(pushed_down, 1.0, 0.0))
        seen = last >= 0
        side[start:stop] = np.where(seen, side_now[np.maximum(last, 0)], last_side)
        source[start:stop] = np.where(seen, last + start, last_source)
        if seen[-1]:
            last_source, last_side = int(last[-1]) + start, float(side_now[last[-1]])
    return y, source, side


def _play_block(u: np.ndarray, h: float, y0: float) -> np.ndarray:
    """The play output over u (n,) from the output y0 before it: every step is a clamp map
    ``y -> clip(y, L, U)``, clamp maps compose into clamp maps (later-after-earlier is
    ``(clip(L_e, L_l, U_l), clip(U_e, L_l, U_l))``), so the prefix compositions come from a
    log2(n)-step doubling scan. The values are exact: only min/max are taken."""
    n = u.size
    lo = u - h
    hi = u + h
    step = 1
    while step < n:
        new_lo = np.minimum(np.maximum(lo[:-step], lo[step:]), hi[step:])
        new_hi = np.minimum(np.maximum(hi[:-step], lo[step:]), hi[step:])
        lo[step:] = new_lo
        hi[step:] = new_hi
        step *= 2
    return np.minimum(np.maximum(y0, lo), hi)


def play_operator_reference(u: np.ndarray, half_width: float, initial: float | None = None) -> np.ndarray:
    """The play operator by its definition, one sample at a time (for tests)."""
    u = np.asarray(u, dtype=float)
    y = np.empty_like(u)
    prev = float(u[0]) if initial is None else float(initial)
    for k, uk in enumerate(u):
        prev = min(max(prev, uk - half_width), uk + half_width)
        y[k] = prev
    return y


# --------------------------------------------------------------------------------- stiffening

def stiffening(rotation_rad: np.ndarray, amplitude: float, exponent: float,
               reference_rad: float = STIFFENING_REFERENCE_RAD) -> np.ndarray:
    """Extra torque of contact stiffening: ``A sign(phi) |phi / phi_ref|^n`` (Hertz: n = 1.5).

    rotation (n,) rad, amplitude A in residual units (the extra torque at phi_ref), exponent n > 1.
    """
    phi = np.asarray(rotation_rad, dtype=float)
    return amplitude * np.sign(phi) * np.abs(phi / reference_rad) ** exponent


# ---------------------------------------------------------------------------------- dead band

def dead_zone(rotation: np.ndarray, width: float) -> np.ndarray:
    """What the drive's springs see across a dead band of total width w centred on zero.

    ``sign(phi) * max(|phi| - w/2, 0)``: zero inside the band, shifted by w/2 outside.
    """
    phi = np.asarray(rotation, dtype=float)
    return np.sign(phi) * np.maximum(np.abs(phi) - 0.5 * width, 0.0)


def dead_zone_inverse(spring_rotation: np.ndarray, width: float) -> np.ndarray:
    """Rotation for a spring rotation outside the band: ``phi + sign(phi) w/2`` (0 stays 0)."""
    phi = np.asarray(spring_rotation, dtype=float)
    return phi + np.sign(phi) * 0.5 * width


# -------------------------------------------------------------------------------- smoothing

def _window_line(x0, y, lo, hi, cums):
    """Straight-line fit over samples [lo, hi) for every sample: (value at x0, residual sum of squares)."""
    s0, s1, s2, sy, sxy, syy = (c[hi] - c[lo] for c in cums)
    det = s0 * s2 - s1 * s1
    ok = det > 1e-12 * np.maximum(s0 * s2, 1e-300)
    slope = np.where(ok, (s0 * sxy - s1 * sy) / np.where(ok, det, 1.0), 0.0)
    intercept = (sy - slope * s1) / s0
    rss = syy - intercept * sy - slope * sxy
    return intercept + slope * x0, np.maximum(rss, 0.0)


def local_linear_smooth(x: np.ndarray, y: np.ndarray, half_window: int) -> np.ndarray:
    """Value at each sample of a straight line fitted to y against x near it, keeping corners sharp.

    x, y (n,) float, x increasing. Three windows of 2*half_window+1 samples are tried at each
    sample (centred, ending at it, starting at it) and the one whose line fits best is used, so a
    ramp that reverses (the applied torque at its peak) is not rounded off. Used to take the noise
    out of a measured driving variable before it enters the play operator, which otherwise
    ratchets on noise peaks.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    n = x.size
    w = int(half_window)
    if n < 2 * w + 2 or w < 1:
        return y.copy()
    x0 = x - x.mean()
    y0 = y.mean()
    yc = y - y0
    cums = [np.concatenate([[0.0], np.cumsum(v)]) for v in (np.ones(n), x0, x0 * x0, yc, x0 * yc, yc * yc)]
    idx = np.arange(n)
    best_val = None
    for start in (idx - w, idx - 2 * w, idx):
        lo = np.clip(start, 0, n - 2 * w - 1)
        hi = lo + 2 * w + 1
        val, rss = _window_line(x0, yc, lo, hi, cums)
        if best_val is None:
            best_val, best_rss = val, rss
        else:
            better = rss < best_rss
            best_val = np.where(better, val, best_val)
            best_rss = np.where(better, rss, best_rss)
    return best_val + y0


def reversals(y: np.ndarray, threshold: float) -> np.ndarray:
    """Indices where a slowly driven signal turns back: the extreme reached before it retreats by
    more than ``threshold`` (a zig-zag filter). y (n,) float; returns increasing int indices."""
    y = np.asarray(y, dtype=float)
    out = []
    i_max = i_min = i_ext = 0
    direction = 0
    for i in range(1, y.size):
        v = y[i]
        if direction == 0:  # until the first move larger than the threshold
            if v > y[i_max]:
                i_max = i
            if v < y[i_min]:
                i_min = i
            if v - y[i_min] > threshold:
                direction, i_ext = 1, i
            elif y[i_max] - v > threshold:
                direction, i_ext = -1, i
        elif direction > 0:
            if v >= y[i_ext]:
                i_ext = i
            elif y[i_ext] - v > threshold:
                out.append(i_ext)
                direction, i_ext = -1, i
        else:
            if v <= y[i_ext]:
                i_ext = i
            elif v - y[i_ext] > threshold:
                out.append(i_ext)
                direction, i_ext = 1, i
    return np.array(out, dtype=int)


def _refine_corner(x: np.ndarray, y: np.ndarray, r: int, w: int) -> int:
    """The split near r where a line before it and a line after it fit y best (a sharp corner)."""
    n = y.size
    best, best_k = np.inf, r
    for k in range(max(r - w, 2), min(r + w, n - 3) + 1):
        sse = 0.0
        for lo, hi in ((max(k - 2 * w, 0), k + 1), (k + 1, min(k + 2 + 2 * w, n))):
            if hi - lo < 3:
                continue
            coef = np.polyfit(x[lo:hi] - x[k], y[lo:hi], 1)
            sse += float(np.sum((np.polyval(coef, x[lo:hi] - x[k]) - y[lo:hi]) ** 2))
        if sse < best:
            best, best_k = sse, k
    return best_k


def driving_signal(x: np.ndarray, y: np.ndarray, noise: float, half_window: int = 8) -> np.ndarray:
    """The noise-free course of a measured driving variable (the applied torque) for the play.

    The record is cut at its reversals (zig-zag filter at 6 x noise or 2 % of the range, corners
    refined to the split where two straight lines fit best); within each monotone stretch y is
    smoothed by a local straight line over +-half_window samples (windows never cross a reversal,
    so corners stay sharp) and then made exactly monotone (isotonic regression), so the play sees
    no noise-made reversals: a play of any half-width then engages only where the drive turns.
    """
    from scipy.optimize import isotonic_regression

    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    n = y.size
    if n < 4 * half_window + 4:
        return y.copy()
    rough = local_linear_smooth(x, y, half_window)
    threshold = max(6.0 * noise, 0.02 * float(np.ptp(rough)))
    cuts = [_refine_corner(x, y, int(r), half_window) for r in reversals(rough, threshold)]
    bounds = [0] + [c + 1 for c in cuts] + [n]
    out = np.empty(n)
    for a, b in zip(bounds[:-1], bounds[1:]):
        if b - a < 3:
            out[a:b] = y[a:b]
            continue
        xs, ys = x[a:b], y[a:b]
        m = b - a
        x0 = xs - xs.mean()
        cums = [np.concatenate([[0.0], np.cumsum(v)]) for v in (np.ones(m), x0, x0 * x0, ys - ys.mean(),
                                                                 x0 * (ys - ys.mean()), (ys - ys.mean()) ** 2)]
        idx = np.arange(m)
        lo = np.clip(idx - half_window, 0, m)
        hi = np.clip(idx + half_window + 1, 0, m)
        val, _ = _window_line(x0, ys - ys.mean(), lo, hi, cums)
        val = val + ys.mean()
        increasing = val[-1] >= val[0]
        out[a:b] = isotonic_regression(val, increasing=increasing).x
    return out
