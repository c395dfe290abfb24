"""Model-free noise estimate from short-range differences.

The noise level is taken from the data alone, before any model is fitted, so that the final
"is the residual noise?" test compares against something the model cannot have shaped.

Method. Along time, take every run of four consecutive samples (t_j, y_j), j = 0..3, and form
the third divided difference ``sum_j y_j / prod_{k != j} (t_j - t_k)``. Its weights annihilate
any polynomial of degree <= 2 in t, so the signal's own offset, slope and curvature over the
four samples cancel exactly, for any (uneven) spacing; what survives of the signal is its third
derivative times the cube of the spacing, negligible when the trace is sampled densely compared
with its fastest order (a 1 um sinusoid sampled 20 times per period leaks < 0.005 um).
Scaling the weights to unit norm turns each difference into one draw of the noise,
``N(0, sigma^2)`` for white noise of any distribution with that variance. Runs that span a
drop-out (spacing more than ``gap_ratio`` times the median) are skipped. The noise level is
1.4826 x the median absolute contrast, which ignores the few runs where the signal is not
smooth (a reversal, a kink of the play operator, a step).

For a torque-deflection record the residual is ``T - law(theta)``, so its noise is
``e_T - k e_theta`` with k the local stiffness dT/dtheta. The torque and rotation channels get
their own robust levels; k is the local slope of torque against rotation over a few dozen
neighbouring samples, as the ratio of the two channels' slopes against time (from the data, not
from the model; a slope of one noisy channel on the other would be biased low); the residual's
noise variance at each sample is ``s_T^2 + k^2 s_theta^2``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

MAD_TO_SIGMA = 1.482602218505602  # 1 / Phi^-1(3/4)


@dataclass(frozen=True, eq=False)
class NoiseEstimate:
    """Noise of the residual, from the data alone.

    ``rms``: the noise level in residual units (rms over the samples of the per-sample level);
    ``variance``: (n,) the noise variance at each sample; ``windows``: runs of samples used;
    ``method``: how it was made; ``channels``: per-channel levels where there are several.
    """

    rms: float
    variance: np.ndarray
    windows: int
    method: str
    channels: dict
    #: lag-one correlation of the residual's noise (0: white), and of each channel's
    ar1: float = 0.0
    ar1_channels: dict = None
    ar1_scatter: float = 0.0  # standard error of ar1
    ar1_scatters: dict = None  # of each channel's
    #: per channel: False where the sampling does not resolve the signal (:func:`channel_level`)
    resolved: dict = None

    @property
    def independent_fraction(self) -> float:
        """n_effective / n of AR(1) noise for a slowly varying fit: (1 - phi) / (1 + phi)."""
        return (1.0 - self.ar1) / (1.0 + self.ar1)

    def block_variance_factor(self, block: int, phi: float | None = None) -> float:
        """Var(sum of ``block`` consecutive noise samples) / (block x variance) for AR(1) noise
        (of lag-one correlation ``phi``, default :attr:`ar1`)."""
        phi = self.ar1 if phi is None else phi
        if phi == 0.0:
            return 1.0
        k = np.arange(1, block)
        return float(1.0 + 2.0 * np.sum((block - k) * phi ** k) / block)


#: runs of four samples handled at a time: the contrasts' temporaries stay this size at any length
RUN_BLOCK = 1 << 17


def _time_scale(median_spacing: float) -> float:
    """A power of two that brings the median sample spacing near 1. Scaling the times by a power
    of two is exact, and the unit-norm contrasts do not depend on the time unit, so the contrasts
    are bit for bit those of the unscaled times, without the products of three spacings
    overflowing or underflowing for very long or very short spacings."""
    if not (math.isfinite(median_spacing) and median_spacing > 0):
        return 1.0
    return math.ldexp(1.0, -math.frexp(median_spacing)[1])


def _contrast_block(ts: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """Unit-norm third divided differences of the runs starting at each of ts[:-3] (ts scaled)."""
    m = ts.size - 3
    tj = [ts[j:m + j] for j in range(4)]
    weights = []
    for j in range(4):
        den = np.ones(m)
        for k in range(4):
            if k != j:
                den = den * (tj[j] - tj[k])
        weights.append(1.0 / den)
    norm = np.sqrt(sum(w * w for w in weights))
    return sum(w * ys[j:m + j] for j, w in enumerate(weights)) / norm


def _runs(t: np.ndarray, y: np.ndarray, gap_ratio: float, block: int = RUN_BLOCK):
    """(start, contrasts, valid) for consecutive blocks of the n-3 runs of four samples."""
    n = t.size
    median = float(np.median(np.diff(t), overwrite_input=True))
    scale = _time_scale(median)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for lo in range(0, n - 3, block):
            hi = min(lo + block, n - 3)
            c = _contrast_block(t[lo:hi + 3] * scale, y[lo:hi + 3])
            spacing = np.diff(t[lo:hi + 3])
            widest = np.maximum(np.maximum(spacing[:-2], spacing[1:-1]), spacing[2:])
            yield lo, c, np.isfinite(c) & (widest <= gap_ratio * median)


def difference_contrasts(t: np.ndarray, y: np.ndarray, gap_ratio: float = 4.0):
    """Unit-norm third divided differences of y along t over every run of four samples.

    t, y: (n,) float, t strictly increasing. Returns ``(contrast, valid)``, both (n-3,): the
    contrast of the run starting at each sample and whether the run is free of drop-outs.
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    n = t.size
    if n < 4:
        return np.zeros(0), np.zeros(0, bool)
    contrast = np.empty(n - 3)
    valid = np.empty(n - 3, bool)
    for lo, c, v in _runs(t, y, gap_ratio):
        contrast[lo:lo + c.size] = c
        valid[lo:lo + c.size] = v
    return contrast, valid


def robust_level(contrast: np.ndarray, valid: np.ndarray) -> float:
    """1.4826 x median |contrast| over the valid runs (sigma for Gaussian noise)."""
    c = np.abs(contrast[valid])
    if c.size == 0:
        return float("nan")
    return float(MAD_TO_SIGMA * np.median(c))


def level_of(t: np.ndarray, y: np.ndarray, gap_ratio: float = 4.0) -> tuple[float, int]:
    """(robust level, valid runs) of one channel: :func:`robust_level` of
    :func:`difference_contrasts`, made block by block into one array of |contrast| (the only
    full-length temporary), so its memory is one float per sample."""
    magnitudes = contrast_magnitudes(t, y, gap_ratio)
    return level_of_contrasts(magnitudes, y), magnitudes.size


def level_of_contrasts(magnitudes: np.ndarray, y: np.ndarray, resolved: bool = True) -> float:
    """The noise level of the readings ``y`` from their |contrasts| (:func:`contrast_magnitudes`):
    1.4826 x their median, or, for a coarsely quantised reading, what its step implies. NaN
    without contrasts. Reorders ``magnitudes`` in place.

    A quantised reading (:func:`reading_quantum` finds its step q) is never given a level below
    its reading error q / sqrt(12): an encoder read at 10 Hz while it holds still gives runs of
    four equal counts, whose contrasts are zero (or a float's last digit), and a level of 1e-10
    of a count would weigh every fit. ``resolved`` False says the contrasts see the signal itself
    (it changes faster than the sampling resolves, :func:`coloured_level`): their rms is then the
    signal's, not the noise's, and the level is the larger of the median and q / sqrt(12)."""
    if magnitudes.size == 0:
        return float("nan")
    level = float(MAD_TO_SIGMA * np.median(magnitudes))
    q = reading_quantum(y)
    # a sensor's step (a dial's division, an encoder's count) is a visible fraction of what it
    # reads; a step of a millionth of the range is the number format of the file, below any noise
    if q >= 1e-6 * float(np.ptp(y)) and q > 0:
        reading_error = q / math.sqrt(12.0)
        if resolved and reading_error > 0.5 * level:
            # a coarse quantiser: most runs read a staircase, and the median of the contrasts (a
            # discrete distribution) no longer measures their spread. For a signal that sweeps
            # across the levels the reading error is uniform, q^2/12, plus the noise underneath:
            # the contrasts' (trimmed) rms holds both
            level = trimmed_rms(magnitudes)
        level = max(level, reading_error)
    return level


def contrast_magnitudes(t: np.ndarray, y: np.ndarray, gap_ratio: float = 4.0) -> np.ndarray:
    """|contrast| of every valid run (:func:`difference_contrasts`), made block by block into one
    array (the only full-length temporary: one float per sample)."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    n = t.size
    if n < 4:
        return np.zeros(0)
    magnitudes = np.empty(n - 3)
    count = 0
    for _, c, v in _runs(t, y, gap_ratio):
        kept = np.abs(c[v])
        magnitudes[count:count + kept.size] = kept
        count += kept.size
    return magnitudes[:count]


#: E[c^2 | |c| <= its 99 % quantile] / sigma^2 for Gaussian c: the bias of a 1 % trimmed mean square
_TRIM_99 = 0.9247625


def trimmed_rms(magnitudes: np.ndarray) -> float:
    """rms of |contrasts| below their 99th percentile (the kinks and reversals of the signal left
    out), scaled to sigma for Gaussian contrasts. Sorts ``magnitudes`` in place."""
    m = np.asarray(magnitudes)
    cut = int(0.99 * m.size)
    m.partition(cut)
    return float(math.sqrt(np.mean(np.square(m[:cut])) / _TRIM_99))


#: a reading is on a grid of step q when it lies within this fraction of q of a grid point
GRID_TOLERANCE = 0.05
#: ... and a channel is read on that grid when at least this fraction of its readings are
GRID_SHARE = 0.95


def reading_quantum(y: np.ndarray) -> float:
    """The resolution the channel was read or written with (an encoder's count, a dial's division,
    a current sensor's LSB), estimated from the readings; 0 when they sit on no grid.

    Candidates are steps between neighbouring distinct readings, and between the readings read at
    least as often as the median one (their 2nd, 10th, 25th and 50th percentiles; a float's last
    digits, below 1e-9 of the range, are no step). The largest
    candidate on whose grid (offset by the first reading) at least :data:`GRID_SHARE` of the
    readings lie within :data:`GRID_TOLERANCE` of a step is taken, and refined by least squares
    of the distinct on-grid readings on their step numbers. So a few stray readings (a glitch, a
    reading of another scale), a count converted to other units and rounded to a few decimals, or
    an offset, still give the step; readings of a continuous quantity (about 10 % of them within
    5 % of any grid) give none."""
    values, counts = np.unique(np.asarray(y, dtype=float), return_counts=True)
    if values.size < 3:
        return 0.0
    span = float(values[-1] - values[0])
    candidates = set()
    # steps between neighbouring distinct readings, and between those read at least as often as
    # the median one (stray readings, read once or twice, split the grid's steps)
    for chosen in (values, values[counts >= np.median(counts)]):
        steps = np.diff(chosen)
        steps = steps[steps > 1e-9 * span]  # (a float's last digits are no step)
        if steps.size:
            candidates.update(np.percentile(steps, [2.0, 10.0, 25.0, 50.0]).tolist())
    offsets = values - values[0]
    total = float(counts.sum())
    best = 0.0
    for q in sorted(candidates, reverse=True):
        if not q > 0:
            continue
        k = np.round(offsets / q)
        on_grid = np.abs(offsets / q - k) <= GRID_TOLERANCE
        if counts[on_grid].sum() >= GRID_SHARE * total:
            # the step (and an offset) by least squares over the distinct on-grid readings
            A = np.column_stack([np.ones(int(on_grid.sum())), k[on_grid]])
            offset_and_step = np.linalg.lstsq(A, offsets[on_grid], rcond=None)[0]
            best = float(offset_and_step[1]) if offset_and_step[1] > 0 else q
            break
    return best


def contrast_variance(rho: float) -> float:
    """Variance of a unit-norm third difference (weights (-1, 3, -3, 1) / sqrt 20) of unit AR(1)
    noise whose samples ``rho`` apart in the run correlate by ``rho``: (1 - rho)(1 - rho/2 + rho^2/10)."""
    return (1.0 - rho) * (1.0 - 0.5 * rho + 0.1 * rho * rho)


#: |lag-one correlation| below this is taken as white (the estimate's own scatter is about 0.02)
AR1_WHITE = 0.05
AR1_RANGE = (-0.5, 0.95)


_UNRESOLVED_TEXT = (" the signal changes faster than the sampling resolves (differences over every other sample "
                    "exceed those over consecutive ones as no noise colour can): the level is the median, an upper "
                    "bound, floored at the reading error of a quantised channel")


def _unresolved_ratio() -> float:
    """(L2 / L1)^2 at the top of :data:`AR1_RANGE`: AR(1) noise gives at most this (2.0 at 0.95)."""
    phi = AR1_RANGE[1]
    return contrast_variance(phi * phi) / contrast_variance(phi)


def coloured_level(t: np.ndarray, y: np.ndarray, gap_ratio: float = 4.0) -> tuple[float, int, float]:
    """(noise level, runs, lag-one correlation phi) of one channel, for white or AR(1) noise.

    The third differences over runs of consecutive samples (``L1``) and over runs of every other
    sample (``L2``, both interleaved halves) see AR(1) noise differently: their variances are
    ``sigma^2 f(phi)`` and ``sigma^2 f(phi^2)`` (:func:`contrast_variance`), and
    ``f(phi^2) / f(phi) = (L2 / L1)^2`` rises from 0.35 (phi -0.5) through 1 (white) to 2 (phi
    -> 1), so it gives phi, and ``sigma = L1 / sqrt(f(phi))``. Exact for evenly spaced samples.

    A ratio at or beyond what AR(1) noise can give (2.0, at the top of :data:`AR1_RANGE`) is no
    noise colour: the signal changes faster than the sampling resolves (a load stepped within a
    few samples of a 10 Hz logger, an encoder's count stepping now and then: an isolated step
    gives 2, a smooth signal up to 64, as third differences grow with the cube of the spacing),
    and the differences hold the signal. The level is then the contrasts' median, floored at a quantised
    channel's reading error (:func:`level_of_contrasts` with ``resolved=False``), taken as white:
    correcting it for a correlation of 0.95 would multiply it by 5.7."""
    level, count, phi, _ = channel_level(t, y, gap_ratio)
    return level, count, phi


def channel_level(t: np.ndarray, y: np.ndarray, gap_ratio: float = 4.0) -> tuple[float, int, float, bool]:
    """:func:`coloured_level` and whether the sampling resolves the signal (see there)."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    magnitudes = contrast_magnitudes(t, y, gap_ratio)
    count = magnitudes.size
    if y.size < 16 or count == 0:
        return level_of_contrasts(magnitudes, y), count, 0.0, True
    # the ratio from the contrasts' trimmed rms (nearly the efficiency of the rms for Gaussian
    # noise, where the median loses a third; the few kinks of the signal trimmed away)
    stride1 = trimmed_rms(magnitudes)
    stride2 = trimmed_rms(np.concatenate([contrast_magnitudes(t[i::2], y[i::2], gap_ratio) for i in (0, 1)]))
    resolved = not (stride1 > 0 and stride2 > 0 and (stride2 / stride1) ** 2 >= _unresolved_ratio())
    l1 = level_of_contrasts(magnitudes, y, resolved)
    if not resolved or not l1 > 0 or not (stride1 > 0 and stride2 > 0):
        return l1, count, 0.0, resolved
    ratio = (stride2 / stride1) ** 2

    def excess(phi):
        return contrast_variance(phi * phi) / contrast_variance(phi) - ratio

    lo, hi = AR1_RANGE
    if excess(lo) >= 0:
        phi = lo
    else:  # (excess(hi) > 0: a ratio at the top of the range is an unresolved signal, above)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if excess(mid) < 0 else (lo, mid)
        phi = 0.5 * (lo + hi)
    if abs(phi) < AR1_WHITE:
        return l1, count, 0.0, True
    return l1 / math.sqrt(contrast_variance(phi)), count, phi, True


def ar1_scatter(t: np.ndarray, y: np.ndarray, gap_ratio: float = 4.0, parts: int = 4) -> float:
    """Standard error of the lag-one correlation of the whole record: the spread of its estimates
    on ``parts`` consecutive parts, over sqrt(parts)."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    edges = np.linspace(0, t.size, parts + 1).astype(int)
    values = [coloured_level(t[a:b], y[a:b], gap_ratio)[2] for a, b in zip(edges[:-1], edges[1:]) if b - a >= 64]
    if len(values) < 2:
        return 0.0
    return float(np.std(values, ddof=1) / math.sqrt(len(values)))


def noise_of_signal(t: np.ndarray, y: np.ndarray, gap_ratio: float = 4.0) -> NoiseEstimate:
    """Stationary noise of one channel y(t) (the carriage reading of a preload trace), white or
    AR(1) (:func:`coloured_level`).

    ``variance`` is a read-only broadcast of the one level (no memory per sample)."""
    sigma, windows, phi, resolved = channel_level(t, y, gap_ratio)
    n = np.asarray(y).size
    method = "third divided differences along time over 4-sample runs, 1.4826 x median"
    if not resolved:
        method += _UNRESOLVED_TEXT
    scatter = 0.0
    if phi:
        scatter = ar1_scatter(t, y, gap_ratio)
        method += (f"; lag-one correlation {phi:.3f} +- {scatter:.3f} from the differences over every other sample "
                   "(AR(1)), the level corrected for it")
    return NoiseEstimate(rms=sigma, variance=np.broadcast_to(sigma * sigma, (n,)), windows=windows,
                         method=method, channels={"signal": sigma}, ar1=phi, ar1_channels={"signal": phi},
                         ar1_scatter=scatter, resolved={"signal": resolved})


def noise_of_transmission(t: np.ndarray, input_urad: np.ndarray, output_urad: np.ndarray, te_urad: np.ndarray,
                          gap_ratio: float = 4.0) -> NoiseEstimate:
    """Noise of a transmission error record: the transmission error's own (:func:`noise_of_signal`:
    both encoders' noise and steps as they reach it), with each encoder's level in its
    ``channels`` (``input_angle``, ``output_angle``, urad at its shaft)."""
    est = noise_of_signal(t, te_urad, gap_ratio)
    levels = {"input_angle": channel_level(t, input_urad, gap_ratio)[0],
              "output_angle": channel_level(t, output_urad, gap_ratio)[0]}
    return replace(est, channels={**est.channels, **levels})


def local_slope(x: np.ndarray, y: np.ndarray, half_window: int = 12) -> np.ndarray:
    """Least-squares slope dy/dx over +-half_window neighbouring samples (in record order)."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    n = x.size
    xc = x - x.mean()
    yc = y - y.mean()
    c = [np.concatenate([[0.0], np.cumsum(v)]) for v in (np.ones(n), xc, yc, xc * xc, xc * yc)]
    idx = np.arange(n)
    a = np.clip(idx - half_window, 0, n)
    b = np.clip(idx + half_window + 1, 0, n)
    s0, sx, sy, sxx, sxy = (ci[b] - ci[a] for ci in c)
    var = sxx - sx * sx / s0
    cov = sxy - sx * sy / s0
    return np.where(var > 0, cov / np.where(var > 0, var, 1.0), 0.0)


def stiffness_along_time(t: np.ndarray, torque: np.ndarray, rotation: np.ndarray, s_rotation: float,
                         half_window: int = 48) -> np.ndarray:
    """Local dT/dtheta of the data as (dT/dt) / (dtheta/dt), each slope fitted against time over
    +-half_window samples. Time carries no noise, so neither slope is attenuated by the other
    channel's noise (a slope of torque on a noisy rotation would be: errors in variables). Where
    the rotation barely moves within the window (a load reversal, a dwell) the ratio is not
    determined, and the nearest determined value is taken."""
    n = np.asarray(t).size
    k_t = local_slope(t, torque, half_window)
    k_r = local_slope(t, rotation, half_window)
    # the rotation's slope is determined when it moves by several noise levels across the window
    span = np.abs(k_r) * np.abs(local_spacing(t, half_window)) * (2 * half_window)
    good = span > 6.0 * max(s_rotation, 1e-300) + 1e-300
    if not good.any():
        return local_slope(rotation, torque, half_window)
    ratio = np.empty(n)
    ratio[good] = k_t[good] / k_r[good]
    idx = np.arange(n)
    ratio[~good] = np.interp(idx[~good], idx[good], ratio[good])
    return ratio


def local_spacing(t: np.ndarray, half_window: int) -> np.ndarray:
    """Mean sample spacing over +-half_window samples."""
    t = np.asarray(t, dtype=float)
    n = t.size
    idx = np.arange(n)
    a = np.clip(idx - half_window, 0, n - 1)
    b = np.clip(idx + half_window, 0, n - 1)
    return (t[b] - t[a]) / np.maximum(b - a, 1)


def noise_of_torque_residual(t: np.ndarray, torque: np.ndarray, rotation: np.ndarray,
                             gap_ratio: float = 4.0) -> NoiseEstimate:
    """Noise of ``torque - law(rotation)`` in torque units, from both channels (see module doc)."""
    s_t, w_t, phi_t, res_t = channel_level(t, torque, gap_ratio)
    s_r, w_r, phi_r, res_r = channel_level(t, rotation, gap_ratio)
    k = stiffness_along_time(t, torque, rotation, s_r)
    scatter = {"torque": ar1_scatter(t, torque, gap_ratio) if phi_t else 0.0,
               "rotation": ar1_scatter(t, rotation, gap_ratio) if phi_r else 0.0}
    return _torque_noise(s_t, s_r, phi_t, phi_r, k, min(w_t, w_r),
                         "the local stiffness dT/dtheta of the data, taken as (dT/dt) / (dtheta/dt) so that neither "
                         "channel's noise biases it", scatter, {"torque": res_t, "rotation": res_r})


def _torque_noise(s_t: float, s_r: float, phi_t: float, phi_r: float, k: np.ndarray, windows: int,
                  source: str, scatter: dict | None = None, resolved: dict | None = None) -> NoiseEstimate:
    """The torque residual's noise from the channels' levels and lag-one correlations, the
    rotation's carried by the stiffness ``k``: variance ``s_T^2 + k^2 s_theta^2``; the residual's
    correlation the variance-weighted mean of the channels'."""
    torque_part = s_t * s_t
    rotation_part = (np.asarray(k, dtype=float) * s_r) ** 2
    variance = torque_part + rotation_part
    total = float(np.sum(variance))
    share_t = torque_part * variance.size / total if total > 0 else 1.0
    phi = float(phi_t * share_t + phi_r * (1.0 - share_t))
    scatter = scatter or {}
    phi_scatter = float(share_t * scatter.get("torque", 0.0) + (1.0 - share_t) * scatter.get("rotation", 0.0))
    method = ("third divided differences along time of torque and of rotation, 1.4826 x median; rotation noise "
              f"carried into torque by {source}")
    if phi_t or phi_r:
        method += f"; lag-one correlations {phi_t:.3f} (torque), {phi_r:.3f} (rotation): AR(1), levels corrected"
    resolved = resolved or {"torque": True, "rotation": True}
    for channel, ok in resolved.items():
        if not ok:
            method += f"; {channel}:{_UNRESOLVED_TEXT}"
    return NoiseEstimate(rms=float(np.sqrt(np.mean(variance))), variance=variance, windows=windows, method=method,
                         channels={"torque": s_t, "rotation": s_r}, ar1=phi,
                         ar1_channels={"torque": phi_t, "rotation": phi_r}, ar1_scatter=phi_scatter,
                         ar1_scatters=dict(scatter), resolved=dict(resolved))


def with_stiffness(noise: NoiseEstimate, stiffness: np.ndarray, source: str) -> NoiseEstimate:
    """``noise`` of a torque residual with the rotation channel's noise carried into torque by
    ``stiffness`` (n,) (dT/dtheta, torque units per rotation unit) instead: the effective variance
    ``s_T^2 + k^2 s_theta^2``. The channels' own levels stay the model-free ones."""
    ar = noise.ar1_channels or {}
    return _torque_noise(noise.channels["torque"], noise.channels["rotation"], ar.get("torque", 0.0),
                         ar.get("rotation", 0.0), stiffness, noise.windows, source, noise.ar1_scatters, noise.resolved)


def spike_threshold(samples: int, false_per_record: float = 0.05) -> float:
    """Deviation (in noise levels) that white Gaussian noise exceeds about ``false_per_record``
    times in a record of ``samples``: two-sided, ``Phi^-1(1 - false / (2 n))``."""
    from scipy.special import ndtri
    return float(ndtri(1.0 - false_per_record / (2.0 * max(samples, 1))))


def isolated_spikes(t: np.ndarray, y: np.ndarray, sigma: float, gap_ratio: float = 4.0,
                    passes: int = 3) -> np.ndarray:
    """Samples (bool, (n,)) that jump away from their neighbours: a logger's or probe's glitch.

    A sample i is a spike when the straight lines through its two neighbours on each side, each
    extrapolated to it, both miss it on the same side by more than the noise allows
    (:func:`spike_threshold` x sqrt(6) sigma, the spread of ``y_i - (2 y_(i-1) - y_(i-2))`` for
    white noise) and by more than four times the change between those neighbours. A reversal or
    a kink of the signal makes the two extrapolations straddle it or miss by about one step; a
    step of the signal is missed from one side only; so neither is taken for a spike. Samples
    whose neighbours span a drop-out (``gap_ratio`` x the median spacing) are not judged. Spikes
    next to each other hide each other; ``passes`` rounds, each on the samples not yet rejected,
    find them too."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    n = t.size
    spikes = np.zeros(n, dtype=bool)
    if n < 5 or not sigma > 0:
        return spikes
    limit = spike_threshold(n) * math.sqrt(6.0) * sigma
    spacing = float(np.median(np.diff(t)))
    for _ in range(passes):
        keep = np.flatnonzero(~spikes)
        ts, ys = t[keep], y[keep]
        if ts.size < 5:
            break
        i = np.arange(2, ts.size - 2)
        left = ys[i - 1] + (ys[i - 1] - ys[i - 2]) * (ts[i] - ts[i - 1]) / (ts[i - 1] - ts[i - 2])
        right = ys[i + 1] + (ys[i + 1] - ys[i + 2]) * (ts[i + 1] - ts[i]) / (ts[i + 2] - ts[i + 1])
        d_left, d_right = ys[i] - left, ys[i] - right
        steps = np.maximum(np.abs(ys[i - 1] - ys[i - 2]), np.abs(ys[i + 2] - ys[i + 1]))
        near = (ts[i + 2] - ts[i - 2]) <= 4 * gap_ratio * spacing
        miss = np.minimum(np.abs(d_left), np.abs(d_right))
        found = near & (np.sign(d_left) == np.sign(d_right)) & (miss > limit) & (miss > 4.0 * steps)
        if not found.any():
            break
        spikes[keep[i[found]]] = True
    return spikes
