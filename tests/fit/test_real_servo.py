"""Real records: the lost-motion logs of two UART servos (Feetech STS3215 and STS3250, Robonine's
test stand, CC BY 4.0; ../shared/data/real/sts_servo_backlash/SOURCE.md says where they come from
and how they were shaped into the contract's torque_deflection).

Their output encoder reads 4096 counts a turn (1534 urad), about 10 times a second, while the
torque (estimated from two puller servos, 0.147 N·m at full stretch) steps between -T, 0 and +T in
a few samples and dwells at zero between pulses. What the fit must do with them: read them, not
crash, report the lost motion each shows, and never call them explained with absurd parameters.
The datasheet figures are checked against the contract's definitions computed here from the CSV
with the standard library (zero crossings of the torque on rising and falling branches; the
mid-line and a straight line per torque segment).

Measured (this code): STS3215 hysteresis loss 11,367 urad (0.65 deg; the source's paper: 0.62 deg
unloaded), torsion between +-0.144 N·m 23,285 urad (15.2 counts; paper: about 15), lost motion at
+-3 % of the rated torque 113 urad; STS3250 1,023 urad, 7,274 urad (4.7 counts; paper 4.6), 926 urad.
"""

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

from geargen.cli import main
from geargen.fit.datasheet import MIDLINE_LEVELS, STIFFNESS_LIMIT_FRACTIONS

ROOT = Path(__file__).resolve().parents[2]
LOGS = ("sts3215_single_lost_motion", "sts3250_single_lost_motion")
COUNT_URAD = 2 * math.pi / 4096 * 1e6  # one count of the servos' 12-bit output encoder


def _shared_data() -> Path:
    """ROOT/../shared/data/real; for a git worktree, beside the main working tree too (the clone
    CI runs has ../shared beside it)."""
    places = [ROOT.parent / "shared" / "data" / "real"]
    git = ROOT / ".git"
    if git.is_file():  # a worktree: "gitdir: MAIN/.git/worktrees/NAME"
        main_git = Path(git.read_text().split(":", 1)[1].strip()).parents[1]
        places.append(main_git.parent.parent / "shared" / "data" / "real")
    for place in places:
        if (place / "sts_servo_backlash").is_dir():
            return place / "sts_servo_backlash"
    raise AssertionError(f"the real servo logs are missing: looked in {', '.join(map(str, places))}")


def _columns(path: Path) -> dict[str, list[float]]:
    with path.open(newline="") as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows] for key in ("output_torque_Nm", "output_rotation_urad", "dut_pos_count")}


@pytest.fixture(scope="module", params=LOGS)
def fitted(request, tmp_path_factory):
    folder = _shared_data()
    out = tmp_path_factory.mktemp(request.param)
    assert main(["fit", str(folder / f"{request.param}.csv"), "--json", str(out / "fit.json"), "--report", str(out / "rep"),
                 "--no-plots"]) == 0
    return json.loads((out / "fit.json").read_text()), _columns(folder / f"{request.param}.csv")


def _first_reversal(torque: list[float]) -> int:
    """The first sample where the torque, beyond half its peak, turns back (the last of a plateau)."""
    peak = max(abs(v) for v in torque)
    for i in range(len(torque) - 1):
        if abs(torque[i]) >= 0.5 * peak and abs(torque[i + 1]) < abs(torque[i]):
            return i
    raise AssertionError("the torque never turns back")


def _crossings(torque, rotation, level):
    """Rotations where the torque crosses ``level`` rising and falling, interpolated in torque."""
    rising, falling = [], []
    for i in range(len(torque) - 1):
        a, b = torque[i], torque[i + 1]
        if a < level <= b or a > level >= b:
            at = rotation[i] + (level - a) / (b - a) * (rotation[i + 1] - rotation[i])
            (rising if b > a else falling).append(at)
    return rising, falling


def _mid(torque, rotation, level):
    rising, falling = _crossings(torque, rotation, level)
    return 0.5 * (sum(rising) / len(rising) + sum(falling) / len(falling)) if rising and falling else None


def test_the_fit_reads_the_logs_and_reports_their_lost_motion(fitted):
    report, data = fitted
    assert report["kind"] == "torque_deflection" and report["samples"] == len(data["output_torque_Nm"])
    (test,) = report["datasheet"]["tests"]  # one test: every pulse is the same +-0.147 N·m
    for key in ("hysteresis_loss_urad", "lost_motion_urad", "torsion_urad"):
        assert test[key] is not None and math.isfinite(test[key])
    # the play under load spans whole encoder counts: 15 of the STS3215 (the source: 15), 4.7 of the STS3250 (4.6)
    counts = test["torsion_urad"] / COUNT_URAD
    assert 4.0 < counts < 17.0


def test_never_explained_with_absurd_parameters(fitted):
    """The quantised, slowly sampled rotation has a noise level no lower than its reading error
    (a count / sqrt 12: 443 urad; it was 2e-10 urad for such a channel); any friction play is
    narrower than the torque's range and any dead band than the rotation's; the rest is honestly
    unexplained or explained."""
    report, data = fitted
    # (the CSV holds the counts converted to urad and rounded to 0.1 urad, the JSON 6 digits: 1e-5)
    assert report["noise_channels"]["output_rotation_urad"] >= COUNT_URAD / math.sqrt(12) * (1 - 1e-5)
    torque_span = max(data["output_torque_Nm"]) - min(data["output_torque_Nm"])
    rotation_span = max(data["output_rotation_urad"]) - min(data["output_rotation_urad"])
    for e in report["effects_added"]:
        if e["effect"] == "hysteresis":
            assert 2 * e["half_width"] < torque_span
        if e["effect"] == "dead_band":
            assert e["width_urad"] < rotation_span
    if not report["unexplained"]:
        assert report["stages"]["extended"]["rms"] <= 1.15 * report["noise_rms"]


def test_datasheet_against_the_definitions_computed_here(fitted):
    report, data = fitted
    (test,) = report["datasheet"]["tests"]
    first = _first_reversal(data["output_torque_Nm"])  # the loop, not the first loading
    torque = data["output_torque_Nm"][first:]
    rotation = data["output_rotation_urad"][first:]
    peak = max(abs(v) for v in data["output_torque_Nm"])
    assert test["torque_amplitude_Nm"] == pytest.approx(peak, rel=1e-5)  # (the JSON holds 6 significant digits)
    rising, falling = _crossings(torque, rotation, 0.0)
    assert test["hysteresis_loss_urad"] == pytest.approx(sum(falling) / len(falling) - sum(rising) / len(rising),
                                                         rel=1e-5)
    at = 0.03 * peak
    assert test["lost_motion_urad"] == pytest.approx(_mid(torque, rotation, at) - _mid(torque, rotation, -at), rel=1e-5)
    # three segments of the mid-line, both directions together: torque = K rotation + an intercept per direction
    top = peak * (1 - 0.5 / MIDLINE_LEVELS)
    levels = [top * (k + 1) / MIDLINE_LEVELS for k in range(MIDLINE_LEVELS)]
    t1, t2 = (f * peak for f in STIFFNESS_LIMIT_FRACTIONS)
    for key, lo, hi in (("K1_Nm_per_rad", 0.0, t1), ("K2_Nm_per_rad", t1, t2), ("K3_Nm_per_rad", t2, peak)):
        rows = []
        for sign in (1.0, -1.0):
            for level in levels:
                mid = _mid(torque, rotation, sign * level)
                if lo <= level <= hi and mid is not None:
                    rows.append((mid * 1e-6, 1.0 if sign > 0 else 0.0, 1.0 if sign < 0 else 0.0, sign * level))
        A = np.array([r[:3] for r in rows])
        slope = np.linalg.lstsq(A, np.array([r[3] for r in rows]), rcond=None)[0][0]
        assert test["stiffness"][key] == pytest.approx(slope, rel=1e-5), key
