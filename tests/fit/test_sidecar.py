"""The sidecar NAME.toml: hostile files are refused with exit 2 naming the file and why, never a
traceback (issue 31: a sidecar nested thousands deep crashed ``fit`` with exit 4); the ``[test]``
table and a torque sidecar without ``[model]`` are read as the contract says."""

import subprocess
import sys

import numpy as np
import pytest

from geargen.cli import main
from geargen.fit.measurement import LOST_MOTION_FRACTION, DatasheetSettings, read_measurement

TORQUE_HEAD = 'kind = "torque_deflection"\n[model]\ndrive = "type1"\n'


def _csv(tmp_path, stem="rec"):
    rng = np.random.default_rng(4)
    t = np.arange(400) * 0.1
    torque = 20.0 * np.sin(np.linspace(0.0, 4 * np.pi, 400))
    rotation = torque / 4e5 * 1e6 + 0.1 * rng.normal(size=400)
    rows = "\n".join(f"{a:.2f},{b + 0.02 * rng.normal():.5f},{c:.4f}" for a, b, c in zip(t, torque, rotation))
    path = tmp_path / f"{stem}.csv"
    path.write_text("time_s,output_torque_Nm,output_rotation_urad\n" + rows + "\n")
    return path


HOSTILE = {
    # tomllib parses nested arrays and inline tables recursively: 5,000 levels exhaust Python's stack
    "arrays nested 5,000 deep": ("x = " + "[" * 5000 + "]" * 5000 + "\n").encode(),
    "inline tables nested 5,000 deep": ("x = " + "{a = " * 5000 + "1" + "}" * 5000 + "\n").encode(),
    "invalid UTF-8": b'kind = "torque_deflection"\ndescription = "\xff\xfe bad"\n[model]\ndrive = "type1"\n',
}
# the sidecar is read as a design file is (geargen.design.schema.read_toml): the same words
WHY = {"arrays nested 5,000 deep": "nested deeper than 16 levels",
       "inline tables nested 5,000 deep": "nested deeper than 16 levels",
       "invalid UTF-8": "not UTF-8 at byte"}


def test_a_sidecar_with_a_byte_order_mark_is_read(tmp_path):
    """A byte-order mark carries no content (editors add it unseen): taken, as in a design file."""
    csv = _csv(tmp_path)
    csv.with_suffix(".toml").write_bytes(b"\xef\xbb\xbf" + TORQUE_HEAD.encode())
    assert read_measurement(csv).kind == "torque_deflection"


@pytest.mark.parametrize("name", list(HOSTILE))
def test_a_hostile_sidecar_exits_2_naming_the_file_and_why(tmp_path, name):
    csv = _csv(tmp_path)
    csv.with_suffix(".toml").write_bytes(HOSTILE[name])
    res = subprocess.run([sys.executable, "-m", "geargen.cli", "fit", str(csv), "--no-plots"],
                         capture_output=True, text=True, timeout=60)
    assert res.returncode == 2, res.stderr
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr
    assert f"rec.toml: {WHY[name]}" in res.stderr
    assert not (tmp_path / "rec.fit.json").exists()


def test_the_test_table_is_read_and_checked_by_key(tmp_path, capsys):
    csv = _csv(tmp_path)
    csv.with_suffix(".toml").write_text(TORQUE_HEAD + "[test]\nrated_torque_Nm = 25.0\nlost_motion_fraction = 0.05\n"
                                        "stiffness_limits_Nm = [4.0, 12.0]\n")
    meas = read_measurement(csv)
    assert meas.test == DatasheetSettings(rated_torque_Nm=25.0, lost_motion_fraction=0.05, stiffness_limits_Nm=(4.0, 12.0))
    for table, key in (("stiffness_limits_Nm = [12.0, 4.0]", "test.stiffness_limits_Nm"),
                       ("lost_motion_fraction = 1.5", "test.lost_motion_fraction"),
                       ("rated_torque_Nm = -3", "test.rated_torque_Nm"),
                       ("rated_torque = 3.0", "test.rated_torque")):
        csv.with_suffix(".toml").write_text(TORQUE_HEAD + "[test]\n" + table + "\n")
        assert main(["fit", str(csv), "--no-plots"]) == 2
        assert f"rec.toml: {key}" in capsys.readouterr().err


def test_a_torque_record_without_a_model_is_fitted_as_a_type1_law_from_the_data(tmp_path):
    csv = _csv(tmp_path)
    csv.with_suffix(".toml").write_text('kind = "torque_deflection"\ndescription = "a bought servo"\n')
    meas = read_measurement(csv)
    assert meas.model.drive_type == "type1" and not meas.model.has_nominal
    assert meas.test.lost_motion_fraction == LOST_MOTION_FRACTION
    assert any("no [model]" in n for n in meas.notes)


def test_a_transmission_sidecar_names_its_bad_stages(tmp_path, capsys):
    path = tmp_path / "te.csv"
    t = np.arange(200) * 0.1
    path.write_text("time_s,input_angle_deg,output_angle_deg\n" + "\n".join(
        f"{a:.2f},{9 * a * 3:.6f},{a * 3:.6f}" for a in t) + "\n")
    for stages, words in (("[[12, 36], [15]]", "model.stages"), ("[[12, 3]]", "model.stages"),
                          ("[12, 36]", "model.stages")):
        path.with_suffix(".toml").write_text(f'kind = "transmission_error"\n[model]\nstages = {stages}\n')
        assert main(["fit", str(path), "--no-plots"]) == 2
        err = capsys.readouterr().err
        assert f"te.toml: {words}" in err and "[driver, driven]" in err
