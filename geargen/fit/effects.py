"""The effect library: physical effects a declared model may lack, as array functions.

Each effect is a small, separately testable function of arrays; the models in
:mod:`geargen.fit.model` combine them with the declared model and fit all parameters together.

==================== =================================== ===================================
effect               law (added to the model, residual       parameters (JSON names)
                     units)
==================== =================================== ===================================
harmonic             ``A cos(q*theta - phi)``, theta the     ``order`` q, ``amplitude`` A,
                     output angle                            ``phase_deg`` phi
drift                ``c * (v - v_ref)``, v temperature or   ``per_kelvin`` / ``per_second`` c
                     time
hysteresis           play operator of half-width h           ``half_width`` h
                     (friction; backlash at reversals of a
                     transmission)
amplitude_hysteresis a play whose half-width grows with the  ``half_width`` h_ref at
                     cycle's amplitude A: h_ref (A/A_ref)^m  ``reference_amplitude`` A_ref,
                                                             ``exponent`` m
stiffening           ``A sign(phi) |phi/phi_ref|^n``         ``exponent`` n, ``amplitude`` A at
                     (Hertzian)                              phi_ref = 1 mrad
dead_band            zone of width w around zero torque      ``width_urad`` w
                     with no stiffness: the law sees
                     ``dead_zone(phi, w)``
tooth_pulse          a raised-cosine pulse once per turn of  ``shaft``, ``angle_deg``,
                     a shaft (:func:`tooth_pulse`)           ``amplitude``, ``width_deg``
sidebands            sinusoids at a mesh order +- a shaft    ``order`` (the mesh's), ``shaft``,
                     order (a modulated mesh)                ``amplitude`` (each sideband)
ratio_error          ``-relative * theta`` (urad): the       ``relative`` (measured / declared
                     measured ratio is not the declared one  ratio - 1)
==================== =================================== ===================================

``harmonic`` applies to ``preload_trace`` and ``transmission_error``; ``stiffening``,
``dead_band`` and ``amplitude_hysteresis`` to ``torque_deflection``; ``tooth_pulse``,
``sidebands`` and ``ratio_error`` to ``transmission_error``; ``drift`` and ``hysteresis`` to all.
"""

from __future__ import annotations

import math

import numpy as np

#: effect name -> (measurement kinds it applies to, parameters it reports, one-line meaning)
LIBRARY: dict[str, tuple[tuple[str, ...], tuple[str, ...], str]] = {
    "harmonic": (("preload_trace", "transmission_error"), ("order", "amplitude", "phase_deg", "shaft", "multiple"),
                 "a sinusoid at an order the declared model lacks"),
    "drift": (("preload_trace", "torque_deflection", "transmission_error"), ("per_kelvin", "per_second"),
              "a slow change with temperature, or with time when there is no temperature column"),
    "hysteresis": (("preload_trace", "torque_deflection", "transmission_error"), ("half_width",),
                   "friction: a play operator of half-width h, the signal depends on the direction of motion"),
    "amplitude_hysteresis": (("torque_deflection",), ("half_width", "reference_amplitude", "exponent"),
                             "friction whose width grows with the amplitude of the cycle"),
    "stiffening": (("torque_deflection",), ("exponent", "amplitude"),
                   "contact stiffness that rises with load (Hertzian), the curve bends upward"),
    "dead_band": (("torque_deflection",), ("width_urad",),
                  "lost motion: a zone around zero torque with no stiffness"),
    "tooth_pulse": (("transmission_error",), ("shaft", "angle_deg", "amplitude", "width_deg"),
                    "one tooth out of place or damaged: a short pulse once per revolution of its shaft"),
    "sidebands": (("transmission_error",), ("order", "shaft", "amplitude"),
                  "a mesh order modulated by a shaft's turn: lines at mesh order +- shaft order"),
    "ratio_error": (("transmission_error",), ("relative",),
                    "the measured ratio differs from the declared one: the error grows linearly with angle"),
}

#: number of free parameters each effect adds (the harmonic's order counts: it is searched for; a
#: tooth pulse's angle and width, an amplitude hysteresis's exponent too)
PARAMETER_COUNT = {"harmonic": 3, "drift": 1, "hysteresis": 1, "stiffening": 2, "dead_band": 1,
                   "amplitude_hysteresis": 2, "tooth_pulse": 3, "sidebands": 4, "ratio_error": 1}

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


# -------------------------------------------------------------------------------- tooth pulse

def wrap_deg(angle_deg: np.ndarray) -> np.ndarray:
    """Angles folded into [-180, 180) deg."""
    return np.mod(np.asarray(angle_deg, dtype=float) + 180.0, 360.0) - 180.0


def tooth_pulse(shaft_angle_rad: np.ndarray, angle_deg: float, width_deg: float) -> np.ndarray:
    """A unit pulse once per turn of a shaft: ``(1 + cos(2 pi d / w)) / 2`` for |d| < w / 2, else
    0, d the shaft's angle from ``angle_deg`` (folded into a turn), w = ``width_deg`` (a raised
    cosine: a displaced or damaged tooth disturbs the motion while it is in mesh, about one tooth
    pitch of its gear). shaft angle (n,) rad; returns (n,) float in [0, 1]."""
    d = wrap_deg(np.degrees(shaft_angle_rad) - angle_deg)
    inside = np.abs(d) < 0.5 * width_deg
    return np.where(inside, 0.5 * (1.0 + np.cos(2.0 * np.pi * d / width_deg)), 0.0)


# -------------------------------------------------------------------------------------- drift

def drift(variable: np.ndarray, rate: float, reference: float) -> np.ndarray:
    """``rate * (v - reference)``: a linear change with temperature (K) or time (s)."""
    return rate * (np.asarray(variable, dtype=float) - reference)


# --------------------------------------------------------------------------------- hysteresis

def play_operator(u: np.ndarray, half_width: float, initial: float | None = None) -> np.ndarray:
    """The play (backlash) operator: output y lags input u by a play of half-width h.

    ``y[k] = clip(y[k-1], u[k] - h, u[k] + h)`` with ``y[-1] = initial`` (default ``u[0]``).
    u: (n,) float; h a number or (n,) float (a half-width per sample); returns (n,) float. Computed without a Python loop over samples (see
    :func:`_play_block`), in blocks of :data:`PLAY_BLOCK` samples.
    """
    u = np.asarray(u, dtype=float)
    h = np.asarray(half_width, dtype=float)
    if np.any(h < 0):
        raise ValueError("half_width must be >= 0")
    varying = h.ndim > 0  # (a half-width per sample: friction that changes along the record)
    y = np.empty(u.size)
    previous = float(u[0]) if initial is None else float(initial)
    for start in range(0, u.size, PLAY_BLOCK):
        stop = min(start + PLAY_BLOCK, u.size)
        y[start:stop] = _play_block(u[start:stop], h[start:stop] if varying else float(h), previous)
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
    more than ``threshold`` (a zig-zag filter). y (n,) float; returns increasing int indices.

    Only the samples where y changes direction (and the ends of flat runs) can be an extreme or
    end a retreat's run, so the filter walks those alone (:func:`reversals_reference` walks every
    sample; the indices are the same): a slowly driven record of 100,000 samples has a few
    hundred of them."""
    y = np.asarray(y, dtype=float)
    if y.size < 3:
        return np.zeros(0, dtype=int)
    s = np.sign(np.diff(y))
    turns = np.flatnonzero(s[1:] != s[:-1]) + 1
    keep = np.concatenate([[0], turns, [y.size - 1]])
    return keep[_zig_zag(y[keep], threshold)]


def reversals_reference(y: np.ndarray, threshold: float) -> np.ndarray:
    """:func:`reversals` walking every sample (for tests)."""
    y = np.asarray(y, dtype=float)
    return np.asarray(_zig_zag(y, threshold), dtype=int)


def _zig_zag(y: np.ndarray, threshold: float) -> list[int]:
    """Positions in y of the extremes a zig-zag filter of ``threshold`` keeps (see :func:`reversals`)."""
    out = []
    i_max = i_min = i_ext = 0
    direction = 0
    values = y.tolist()
    for i in range(1, len(values)):
        v = values[i]
        if direction == 0:  # until the first move larger than the threshold
            if v > values[i_max]:
                i_max = i
            if v < values[i_min]:
                i_min = i
            if v - values[i_min] > threshold:
                direction, i_ext = 1, i
            elif values[i_max] - v > threshold:
                direction, i_ext = -1, i
        elif direction > 0:
            if v >= values[i_ext]:
                i_ext = i
            elif values[i_ext] - v > threshold:
                out.append(i_ext)
                direction, i_ext = -1, i
        else:
            if v <= values[i_ext]:
                i_ext = i
            elif v - values[i_ext] > threshold:
                out.append(i_ext)
                direction, i_ext = 1, i
    return out


def _hinge(x: np.ndarray, y: np.ndarray, r: int, w: int, lo: int, hi: int) -> tuple[int, np.ndarray]:
    """A turn of a ramp near sample r, fitted by a hinge: two straight lines meeting at a time tc
    (continuous, anywhere between samples), least squares over the samples within 2w of it inside
    [lo, hi). tc is searched at the samples within w of r, then refined between the neighbours of
    the best. Returns (the sample at the turn: of the two around tc, the one the hinge puts
    further out; the hinge's values over [lo, hi), NaN outside its window). A triangle peak's
    value then comes from both ramps' samples (about 4w of them), not from the few noisy samples
    at the turn, and a noise-free ramp is reproduced exactly."""
    from scipy.optimize import minimize_scalar

    def fit(tc):
        k = int(np.clip(np.searchsorted(x, tc), lo, hi - 1))
        a, b = max(lo, k - 2 * w), min(hi, k + 2 * w + 1)
        d = x[a:b] - tc
        A = np.column_stack([np.ones(b - a), np.minimum(d, 0.0), np.maximum(d, 0.0)])
        coef, *_ = np.linalg.lstsq(A, y[a:b], rcond=None)
        return float(np.sum((A @ coef - y[a:b]) ** 2)) / (b - a), a, b, coef

    # (the smoothed record places a turn to a few samples, or further across a probe drop-out:
    # the search starts from the measured extreme near it)
    a, b = max(r - 2 * w, lo), min(r + 2 * w + 1, hi)
    if b - a >= 3:
        near = y[a:b]
        is_peak = y[r] >= 0.5 * (float(near.max()) + float(near.min()))
        r = a + int(np.argmax(near) if is_peak else np.argmin(near))
    candidates = range(max(r - w, lo + 2), min(r + w, hi - 3) + 1)
    if not candidates:
        return r, np.full(hi - lo, np.nan)
    # (at the samples and halfway to the next: a turn inside a drop-out lies between two samples)
    starts = [t for j in candidates for t in (float(x[j]), 0.5 * float(x[j] + x[j + 1]))]
    t0 = min(starts, key=lambda t: fit(t)[0])
    k = int(np.clip(np.searchsorted(x, t0), lo + 1, hi - 1))
    res = minimize_scalar(lambda tc: fit(tc)[0], bounds=(x[max(k - 2, lo)], x[min(k + 1, hi - 1)]), method="bounded",
                          options={"xatol": 1e-9 * max(1.0, abs(float(x[k])))})
    tc = float(res.x) if res.fun <= fit(t0)[0] else t0
    _, a, b, coef = fit(tc)
    d = x[a:b] - tc
    fitted = coef[0] + coef[1] * np.minimum(d, 0.0) + coef[2] * np.maximum(d, 0.0)
    values = np.full(hi - lo, np.nan)
    values[a - lo:b - lo] = fitted
    after = int(np.clip(np.searchsorted(x, tc), lo + 1, hi - 1))
    peak = 1.0 if coef[1] > 0 else -1.0  # a peak rises into the turn, a trough falls into it
    before, after_value = values[after - 1 - lo], values[after - lo]
    turn = after - 1 if not np.isfinite(after_value) or peak * (before - after_value) >= 0 else after
    return turn, values


def driving_signal(x: np.ndarray, y: np.ndarray, noise: float, half_window: int = 8) -> np.ndarray:
    """The noise-free course of a measured driving variable (the applied torque) for the play.

    The record is cut at its reversals (zig-zag filter at 6 x noise or 2 % of the range); each
    turn is fitted by a hinge, two straight lines meeting at a sample (:func:`_hinge`), which
    places it and gives the values within +-half_window samples of it; elsewhere in each monotone
    stretch y is smoothed by a local straight line over +-half_window samples (windows never
    cross a reversal, so corners stay sharp); each stretch is then made exactly monotone
    (isotonic regression), so the play sees no noise-made reversals: a play of any half-width
    then engages only where the drive turns.

    ``half_window`` 0 smooths nothing: for a torque read without noise worth the name, or sampled
    so coarsely that a load step takes a few samples (a line over 17 samples would round it off
    and overshoot the plateau), the stretches between reversals are only made monotone.
    """
    from scipy.optimize import isotonic_regression

    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    n = y.size
    w = int(half_window)
    smooth = w > 0
    if smooth and n < 4 * w + 4:
        return y.copy()
    rough = local_linear_smooth(x, y, w) if smooth else y
    threshold = max(6.0 * noise, 0.02 * float(np.ptp(rough)))
    turns = reversals(rough, threshold)
    # the hinge's lines must see the ramp rise well above the noise: over at least 8 noise levels
    # of travel (a densely sampled record moves less than the noise from sample to sample)
    travel = float(np.median(np.abs(np.diff(rough)))) if n > 1 else 0.0
    w_hinge = int(min(max(w, math.ceil(8.0 * noise / travel) if travel > 0 else w), 16 * max(w, 1)))
    hinges = []
    cuts = []
    for j, r in enumerate(turns):
        if not smooth:
            cuts.append(int(r))
            continue
        lo = cuts[-1] + 1 if cuts else 0
        hi = int(turns[j + 1]) if j + 1 < turns.size else n
        k, values = _hinge(x, y, int(r), w_hinge, lo, hi)
        cuts.append(k)
        hinges.append((lo, values, k))
    bounds = [0] + [c + 1 for c in cuts] + [n]
    out = np.empty(n)
    for a, b in zip(bounds[:-1], bounds[1:]):
        if b - a < 3 or not smooth:
            out[a:b] = y[a:b]
            continue
        xs, ys = x[a:b], y[a:b]
        m = b - a
        x0 = xs - xs.mean()
        cums = [np.concatenate([[0.0], np.cumsum(v)]) for v in (np.ones(m), x0, x0 * x0, ys - ys.mean(),
                                                                 x0 * (ys - ys.mean()), (ys - ys.mean()) ** 2)]
        idx = np.arange(m)
        lo = np.clip(idx - w, 0, m)
        hi = np.clip(idx + w + 1, 0, m)
        val, _ = _window_line(x0, ys - ys.mean(), lo, hi, cums)
        out[a:b] = val + ys.mean()
    for lo, values, k in hinges:  # the turns themselves from their hinges
        near = np.arange(max(k - w_hinge, lo), min(k + w_hinge + 1, lo + values.size))
        near = near[np.isfinite(values[near - lo])]
        out[near] = values[near - lo]
    for a, b in zip(bounds[:-1], bounds[1:]):
        if b - a >= 2:
            out[a:b] = isotonic_regression(out[a:b], increasing=out[b - 1] >= out[a]).x
    return out
