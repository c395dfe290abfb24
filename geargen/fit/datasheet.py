"""The figures a gearbox datasheet gives, taken from the record itself, model-free
(contracts/measurements.md, ``datasheet``).

``torque_deflection``, per test (the record's ``test_nr``; without one, runs of load cycles of
about the same torque amplitude, :func:`split_tests`):

- ``hysteresis_loss_urad``: the rotation where the torque crosses zero on the falling branch
  minus where it crosses zero on the rising branch (means over the test's crossings);
- ``lost_motion_urad``: on the loop's mid-line (the mean of the rising and falling branches), the
  rotation at +T minus the rotation at -T, T = ``lost_motion_fraction`` x the rated torque;
- ``torsion_urad`` (added): the mid-line rotation at + minus at - the rated torque (or the highest
  level both branches reach): the whole play under load that a servo's lost-motion test reads;
- ``stiffness``: K1, K2, K3, the slopes of the mid-line between 0 and T1, T1 and T2, T2 and the
  largest torque, both load directions together (one slope, an intercept per direction): the
  three-segment convention of strain-wave and cycloid gearbox catalogues.

A branch is a stretch of the record where the applied torque rises (or falls) monotonically: the
driving signal of :func:`geargen.fit.effects.driving_signal` (the measured torque with its noise
smoothed out, exactly monotone between reversals), so each branch crosses a torque level at most
once. The rotation at a crossing is interpolated linearly between the two samples that bracket
it. The mid-line at a level is the mean of the rising branches' mean rotation and the falling
branches' there. Each test's first loading (up to its first reversal) is left out: it starts
from wherever the previous test, or the record's start, left the play, not from the loop.

``transmission_error``: ``transmission_accuracy_urad``, the largest positive plus the largest
negative deviation of the transmission error from its mean (its peak to peak) over each complete
output revolution of each run in one direction; the largest over the record.
"""

from __future__ import annotations

import math

import numpy as np

from geargen.fit import effects as fx
from geargen.fit.measurement import Measurement

#: T1 and T2 of the three-segment stiffness when the sidecar does not set them, as fractions of
#: the test's torque amplitude (strain-wave catalogues put T1 near 20 % and T2 near 70 % of the
#: rated torque)
STIFFNESS_LIMIT_FRACTIONS = (0.2, 0.7)
#: two load cycles belong to one test when their torque amplitudes differ by less than this factor
SAME_TEST_RATIO = 1.3
#: a load reversal is a turn of the applied torque by more than this fraction of its largest |value|
REVERSAL_FRACTION = 0.1
#: torque levels on each side of zero at which the mid-line is taken for the stiffness fits
MIDLINE_LEVELS = 48


# ----------------------------------------------------------------------------------- tests

def split_tests(torque_applied: np.ndarray, test_nr: np.ndarray | None = None) -> list[tuple[int, np.ndarray]]:
    """The tests of a torque-deflection record: [(test number, row indices (k,) int)], in time order.

    With ``test_nr`` (n,) each number is a test. Otherwise the applied torque (n,), noise-free
    (:func:`geargen.fit.effects.driving_signal`), is cut at its reversals (turns of more than
    :data:`REVERSAL_FRACTION` of its largest |value|); each reversal's |torque| is a half cycle's
    amplitude; consecutive half cycles whose amplitudes differ by less than
    :data:`SAME_TEST_RATIO` are one test, numbered 0, 1, 2 ... A new test starts where the torque
    last crossed zero before its first reversal (or halfway between the reversals)."""
    n = torque_applied.size
    if test_nr is not None:
        numbers = list(dict.fromkeys(np.asarray(test_nr).tolist()))
        return [(int(k), np.flatnonzero(test_nr == k)) for k in numbers]
    T = np.asarray(torque_applied, dtype=float)
    peak = float(np.max(np.abs(T)))
    turns = fx.reversals(T, REVERSAL_FRACTION * peak) if peak > 0 else np.zeros(0, int)
    if turns.size < 2:
        return [(0, np.arange(n))]
    amplitudes = np.abs(T[turns])
    groups = [[0]]  # reversal numbers of each test
    for j in range(1, turns.size):
        reference = float(np.median(amplitudes[groups[-1]]))
        if reference > 0 and 1.0 / SAME_TEST_RATIO < amplitudes[j] / reference < SAME_TEST_RATIO:
            groups[-1].append(j)
        else:
            groups.append([j])
    groups = _merge_lone_turns(groups, amplitudes)
    starts = [0]
    for group in groups[1:]:
        j = group[0]
        lo, hi = int(turns[j - 1]), int(turns[j])
        cross = np.flatnonzero(np.sign(T[lo:hi]) != np.sign(T[lo + 1:hi + 1]))
        starts.append(lo + 1 + int(cross[-1]) if cross.size else (lo + hi) // 2)
    bounds = starts + [n]
    return [(k, np.arange(a, b)) for k, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])) if b > a]


def _merge_lone_turns(groups: list[list[int]], amplitudes: np.ndarray) -> list[list[int]]:
    """Groups of reversals with any group of a single reversal (half a cycle: no test; a peak that
    fell in a probe drop-out reads low) merged into the neighbour of the nearer amplitude, and
    neighbours of about the same amplitude (within :data:`SAME_TEST_RATIO`) merged again."""
    def level(group):
        return math.log(max(float(np.median(amplitudes[group])), 1e-300))

    groups = [list(g) for g in groups]
    while len(groups) > 1:
        lone = next((k for k, g in enumerate(groups) if len(g) < 2), None)
        if lone is not None:
            sides = [k for k in (lone - 1, lone + 1) if 0 <= k < len(groups)]
            into = min(sides, key=lambda k: abs(level(groups[k]) - level(groups[lone])))
            a, b = sorted((lone, into))
            groups[a:b + 1] = [groups[a] + groups[b]]
            continue
        same = next((k for k in range(len(groups) - 1)
                     if abs(level(groups[k]) - level(groups[k + 1])) < math.log(SAME_TEST_RATIO)), None)
        if same is None:
            break
        groups[same:same + 2] = [groups[same] + groups[same + 1]]
    return groups


# ------------------------------------------------------------------------------- crossings

def level_crossings(applied: np.ndarray, rotation: np.ndarray, level: float) -> tuple[np.ndarray, np.ndarray]:
    """Rotations where the applied torque crosses ``level``: (on rising branches, on falling
    branches), each (k,) float in time order. A rising crossing lies between samples i and i+1
    with ``T_i < level <= T_(i+1)``, a falling one with ``T_i > level >= T_(i+1)``; the rotation
    is interpolated linearly in torque between the two samples."""
    T = np.asarray(applied, dtype=float)
    a, b = T[:-1], T[1:]
    out = []
    for hit in ((a < level) & (b >= level), (a > level) & (b <= level)):
        i = np.flatnonzero(hit)
        frac = (level - a[i]) / (b[i] - a[i])
        out.append(rotation[i] + frac * (rotation[i + 1] - rotation[i]))
    return out[0], out[1]


def _midline(applied: np.ndarray, rotation: np.ndarray, level: float) -> tuple[float | None, int, int]:
    """(mid-line rotation at ``level`` or None, rising crossings, falling crossings)."""
    up, down = level_crossings(applied, rotation, level)
    if up.size == 0 or down.size == 0:
        return None, up.size, down.size
    return 0.5 * (float(up.mean()) + float(down.mean())), up.size, down.size


def _segment_slope(levels: np.ndarray, mids: np.ndarray, lo: float, hi: float) -> tuple[float | None, int]:
    """Slope dT/dtheta (Nm/rad) of the mid-line points with lo <= |T| <= hi, one slope for both
    load directions with an intercept for each (least squares of torque on rotation in rad); and
    the points used. None when fewer than two points, or no spread of rotation, on some side."""
    pick = (np.abs(levels) >= lo - 1e-12) & (np.abs(levels) <= hi + 1e-12) & np.isfinite(mids)
    sides = [pick & (levels > 0), pick & (levels < 0)]
    sides = [s for s in sides if s.sum() >= 2]
    if not sides:
        return None, 0
    rows = np.concatenate([np.flatnonzero(s) for s in sides])
    columns = [mids[rows] * 1e-6] + [np.isin(rows, np.flatnonzero(s)).astype(float) for s in sides]
    A = np.column_stack(columns)
    if np.linalg.matrix_rank(A) < A.shape[1]:
        return None, rows.size
    slope = float(np.linalg.lstsq(A, levels[rows], rcond=None)[0][0])
    return slope, rows.size


def torque_test_figures(test: int, applied: np.ndarray, rotation_urad: np.ndarray, spec) -> dict:
    """The datasheet entry of one test: applied torque (k,) Nm, noise-free; rotation (k,) urad;
    ``spec`` the sidecar's :class:`~geargen.fit.measurement.DatasheetSettings`."""
    amplitude = float(np.max(np.abs(applied)))
    rated = spec.rated_torque_Nm if spec.rated_torque_Nm is not None else amplitude
    how = {}
    # the loop is taken on the test's cycles: the first loading, up to the first reversal, starts
    # from wherever the previous test (or the record's start) left the play, not from the loop
    turns = fx.reversals(applied, REVERSAL_FRACTION * amplitude) if amplitude > 0 else np.zeros(0, int)
    first = int(turns[0]) if turns.size else 0
    applied, rotation_urad = applied[first:], rotation_urad[first:]
    up, down = level_crossings(applied, rotation_urad, 0.0)
    if up.size and down.size:
        hysteresis = float(down.mean() - up.mean())
        how["hysteresis_loss"] = (f"rotation at the {down.size} falling minus the {up.size} rising zero crossings of the "
                                  "torque (means), interpolated between the bracketing samples")
    else:
        hysteresis = None
        how["hysteresis_loss"] = (f"not measured: the torque crosses zero {up.size} times rising and {down.size} times "
                                  "falling in this test; both are needed")
    at = spec.lost_motion_fraction * rated
    plus, minus = _midline(applied, rotation_urad, at), _midline(applied, rotation_urad, -at)
    if at < amplitude and plus[0] is not None and minus[0] is not None:
        lost_motion = plus[0] - minus[0]
        how["lost_motion"] = (f"mid-line rotation at +{at:.4g} Nm minus at -{at:.4g} Nm ({spec.lost_motion_fraction:g} x "
                              f"the rated {rated:.4g} Nm); the mid-line is the mean of the rising ({plus[1]}, {minus[1]} "
                              f"crossings) and falling ({plus[2]}, {minus[2]}) branches")
    else:
        lost_motion = None
        how["lost_motion"] = (f"not measured: +-{at:.4g} Nm is not crossed by both a rising and a falling branch on each "
                              "side" if at < amplitude else
                              f"not measured: +-{at:.4g} Nm is beyond the test's largest torque {amplitude:.4g} Nm")
    if spec.stiffness_limits_Nm is not None:
        t1, t2 = spec.stiffness_limits_Nm
        chosen = "the sidecar's [test] stiffness_limits_Nm"
    else:
        t1, t2 = (f * amplitude for f in STIFFNESS_LIMIT_FRACTIONS)
        chosen = (f"the tool's choice: {STIFFNESS_LIMIT_FRACTIONS[0]:g} and {STIFFNESS_LIMIT_FRACTIONS[1]:g} x the test's "
                  "largest torque")
    top = amplitude * (1.0 - 0.5 / MIDLINE_LEVELS)  # (at the very peak the branches meet in a point)
    levels = np.linspace(top / MIDLINE_LEVELS, top, MIDLINE_LEVELS)
    levels = np.concatenate([-levels[::-1], levels])
    mids = np.array([(_midline(applied, rotation_urad, L)[0]) for L in levels], dtype=float)
    # the whole torsion over the test (what a servo's lost-motion test reads as its play under load)
    torsion_at = min(rated, top)
    torsion = _midline(applied, rotation_urad, torsion_at)[0], _midline(applied, rotation_urad, -torsion_at)[0]
    torsion = None if None in torsion else torsion[0] - torsion[1]
    how["torsion"] = (f"mid-line rotation at +{torsion_at:.4g} Nm minus at -{torsion_at:.4g} Nm (the rated torque, or the "
                      "highest level both branches reach)")
    stiffness = {"T1_Nm": t1, "T2_Nm": t2}
    used = []
    for key, lo, hi in (("K1_Nm_per_rad", 0.0, t1), ("K2_Nm_per_rad", t1, t2), ("K3_Nm_per_rad", t2, amplitude)):
        slope, points = _segment_slope(levels, mids, lo, hi) if hi <= amplitude else (None, 0)
        stiffness[key] = slope
        used.append(points)
    how["stiffness"] = (f"T1 = {t1:.4g} Nm and T2 = {t2:.4g} Nm ({chosen}); each K the least-squares slope of torque on "
                        f"mid-line rotation over its segment, both load directions together (one slope, an intercept "
                        f"each), from the mid-line at {2 * MIDLINE_LEVELS} torque levels ({used[0]}, {used[1]} and "
                        f"{used[2]} of them in the three segments)")
    return {"test": int(test), "torque_amplitude_Nm": amplitude, "rated_torque_Nm": rated,
            "hysteresis_loss_urad": hysteresis, "lost_motion_urad": lost_motion, "lost_motion_at_Nm": at,
            "stiffness": stiffness, "torsion_urad": torsion, "torsion_at_Nm": torsion_at, "samples": int(applied.size),
            "how": how}


def torque_datasheet(meas: Measurement, applied: np.ndarray) -> list[dict]:
    """One datasheet entry per test of a torque-deflection record; ``applied`` (n,) the applied
    torque without its noise (the model's driving signal)."""
    rotation_urad = meas.rotation_rad * 1e6
    out = []
    for test, rows in split_tests(applied, meas.test_nr):
        if rows.size < 4:
            continue
        out.append(torque_test_figures(test, applied[rows], rotation_urad[rows], meas.test))
    return out


# ------------------------------------------------------------------------ transmission error

#: an output run in one direction ends where the output turns back by more than this, rad
REVOLUTION_REVERSAL_RAD = math.radians(1.0)


def revolutions(angle_rad: np.ndarray) -> list[np.ndarray]:
    """Row indices of each complete output revolution: the record is cut where the output turns
    back (by more than 1 deg); each run in one direction is cut into consecutive whole turns from
    where it starts; a remainder of less than a turn is left out. [(k,) int, ...] in time order."""
    theta = np.asarray(angle_rad, dtype=float)
    turns = fx.reversals(theta, REVOLUTION_REVERSAL_RAD)
    bounds = [0] + [int(k) + 1 for k in turns] + [theta.size]
    out = []
    for a, b in zip(bounds[:-1], bounds[1:]):
        run = theta[a:b]
        if run.size < 2:
            continue
        travel = (run - run[0]) * (1.0 if run[-1] >= run[0] else -1.0)
        whole = int(math.floor(float(travel.max()) / (2.0 * math.pi)))
        for k in range(whole):
            inside = np.flatnonzero((travel >= 2.0 * math.pi * k) & (travel <= 2.0 * math.pi * (k + 1)))
            out.append(a + inside)
    return out


def transmission_accuracy(meas: Measurement) -> dict:
    """The transmission accuracy of a transmission-error record, with the figure of each complete
    output revolution and how it was measured."""
    te = meas.te_urad
    per_turn = [float(np.ptp(te[rows])) for rows in revolutions(meas.angle_rad)]
    if not per_turn:
        return {"transmission_accuracy_urad": None, "per_revolution_urad": [],
                "how": "not measured: the record holds no complete output revolution in one direction"}
    return {"transmission_accuracy_urad": max(per_turn), "per_revolution_urad": per_turn,
            "how": (f"largest positive plus largest negative deviation of the transmission error (output angle - input "
                    f"angle / {meas.model.ratio:.6g}) from its mean over each of {len(per_turn)} complete output "
                    "revolutions; the largest")}


def datasheet(meas: Measurement, applied: np.ndarray | None = None) -> dict | None:
    """The contract's ``datasheet`` block of a record (None for a preload trace, which has none).
    ``applied``: a torque-deflection record's applied torque without noise (made here if None)."""
    if meas.kind == "torque_deflection":
        if applied is None:
            from geargen.fit.noise import level_of
            applied = fx.driving_signal(meas.time_s, meas.torque_Nm, level_of(meas.time_s, meas.torque_Nm)[0])
        return {"tests": torque_datasheet(meas, applied), "transmission_accuracy_urad": None}
    if meas.kind == "transmission_error":
        acc = transmission_accuracy(meas)
        return {"tests": [], **acc}
    return None
