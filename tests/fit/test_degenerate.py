"""``geargen fit`` on degenerate records: a clear error naming the file and the column, exit 2,
no traceback, and no JSON or report written.

Each record is what a bench produces when something goes wrong: a probe stuck or disconnected
(constant, one value repeated, every cell empty), a logger that wrote too few rows or no time,
a torque test with the torque or the rotation channel dead or read with the wrong sign, an
output that never turned, a signal computed rather than measured (no noise at all).
"""

import subprocess
import sys

import numpy as np
import pytest

from geargen.cli import main

PRELOAD_TOML = 'kind = "preload_trace"\n[model]\ndrive = "type2"\nteeth = [16, 48, 21, 112]\n'
TORQUE_TOML = ('kind = "torque_deflection"\n[model]\ndrive = "type2"\nk1_Nm_per_rad = 4.0e5\n'
               'k2_Nm_per_rad = 4.0e5\nk3_Nm_per_rad = 4.0e4\npreload_Nm = 25.0\n')
N = 400


def _preload_columns(n=N):
    rng = np.random.default_rng(7)
    t = np.arange(n) * 0.1
    angle = np.linspace(0.0, 720.0, n)
    carriage = 5.0 * np.sin(np.radians(angle)) + 0.3 * rng.normal(size=n)
    return {"time_s": t, "output_angle_deg": angle, "carriage_x_um": carriage}


def _torque_columns(n=N):
    rng = np.random.default_rng(8)
    t = np.arange(n) * 0.1
    torque = 80.0 * np.sin(np.linspace(0.0, 4 * np.pi, n))
    rotation = torque / 8e5 * 1e6 + 0.1 * rng.normal(size=n)
    return {"time_s": t, "output_torque_Nm": torque + 0.05 * rng.normal(size=n), "output_rotation_urad": rotation}


def _all_but_one(value, n=N):
    v = np.full(n, value)
    v[n // 3] = value + 1.0
    return v


def _text(columns: dict) -> str:
    rows = zip(*columns.values())
    return ",".join(columns) + "\n" + "\n".join(
        ",".join("" if np.isnan(v) else f"{v:.6f}" for v in row) for row in rows) + "\n"


# name -> (sidecar, csv text, column named in the message, words of the message)
CASES = {
    "constant carriage": (PRELOAD_TOML, _preload_columns() | {"carriage_x_um": np.full(N, 3.0)},
                          "column carriage_x_um", "is constant"),
    "one carriage value repeated": (PRELOAD_TOML, _preload_columns() | {"carriage_x_um": _all_but_one(3.0)},
                                    "column carriage_x_um", f"reads 3 in {N - 1} of {N}"),
    "every carriage cell empty": (PRELOAD_TOML, _preload_columns() | {"carriage_x_um": np.full(N, np.nan)},
                                  "column carriage_x_um", "empty in every one"),
    "too few rows": (PRELOAD_TOML, _preload_columns(12),
                     "columns time_s, output_angle_deg, carriage_x_um", "only 12 rows"),
    "zero time span": (PRELOAD_TOML, _preload_columns() | {"time_s": np.full(N, 5.0)},
                       "column time_s", "spans no time"),
    "output never turns": (PRELOAD_TOML, _preload_columns() | {"output_angle_deg": np.full(N, 10.0)},
                           "column output_angle_deg", "turns only 0 deg"),
    "output at one angle but one row": (PRELOAD_TOML, _preload_columns() | {"output_angle_deg": _all_but_one(10.0) +
                                                                            np.where(np.arange(N) == N // 3, 400.0, 0.0)},
                                        "column output_angle_deg", "cannot tell the declared orders"),
    "carriage beyond double precision": (PRELOAD_TOML, _preload_columns() | {"carriage_x_um": _preload_columns()["carriage_x_um"] * 1e200},
                                         "column carriage_x_um", "magnitude"),
    "constant torque": (TORQUE_TOML, _torque_columns() | {"output_torque_Nm": np.full(N, 5.0)},
                        "column output_torque_Nm", "never changes"),
    "constant rotation": (TORQUE_TOML, _torque_columns() | {"output_rotation_urad": np.full(N, 1.0)},
                          "column output_rotation_urad", "is constant"),
    "one torque value repeated": (TORQUE_TOML, _torque_columns() | {"output_torque_Nm": _all_but_one(5.0)},
                                  "column output_torque_Nm", f"reads 5 in {N - 1} of {N}"),
    "one rotation value repeated": (TORQUE_TOML, _torque_columns() | {"output_rotation_urad": _all_but_one(2.0)},
                                    "column output_rotation_urad", f"reads 2 in {N - 1} of {N}"),
    "every torque cell empty": (TORQUE_TOML, _torque_columns() | {"output_torque_Nm": np.full(N, np.nan)},
                                "column output_torque_Nm", "empty in every one"),
    "rotation read with the wrong sign": (TORQUE_TOML, _torque_columns() | {"output_rotation_urad": -_torque_columns()["output_rotation_urad"]},
                                          "columns output_torque_Nm, output_rotation_urad", "does not rise"),
}


def _write(tmp_path, name, toml_text, columns):
    stem = name.replace(" ", "_")
    (tmp_path / f"{stem}.csv").write_text(_text(columns))
    (tmp_path / f"{stem}.toml").write_text(toml_text)
    return tmp_path / f"{stem}.csv"


@pytest.mark.parametrize("name", list(CASES))
def test_degenerate_record_is_refused_by_name(tmp_path, capsys, name):
    toml_text, columns, column, words = CASES[name]
    csv = _write(tmp_path, name, toml_text, columns)
    out_json, report = tmp_path / "out" / "fit.json", tmp_path / "report"
    assert main(["fit", str(csv), "--json", str(out_json), "--report", str(report)]) == 2
    captured = capsys.readouterr()
    assert f"{csv.name}: {column}" in captured.err
    assert words in captured.err
    assert "Traceback" not in captured.err + captured.out
    assert not out_json.exists() and not out_json.parent.exists()
    assert not report.exists()
    assert not csv.with_name(f"{csv.stem}.fit.json").exists()


def test_header_only(tmp_path, capsys):
    (tmp_path / "empty.csv").write_text("time_s,output_angle_deg,carriage_x_um\n")
    (tmp_path / "empty.toml").write_text(PRELOAD_TOML)
    assert main(["fit", str(tmp_path / "empty.csv")]) == 2
    err = capsys.readouterr().err
    assert "empty.csv: columns time_s, output_angle_deg, carriage_x_um: no data rows" in err
    assert not (tmp_path / "empty.fit.json").exists()


def test_constant_carriage_as_a_user_runs_it(tmp_path):
    """The reviewer's reproduction: a preload trace whose carriage column is constant died with a
    ZeroDivisionError traceback (exit 1)."""
    toml_text, columns, column, words = CASES["constant carriage"]
    csv = _write(tmp_path, "constant carriage", toml_text, columns)
    res = subprocess.run([sys.executable, "-m", "geargen.cli", "fit", str(csv), "--json", str(tmp_path / "r.json")],
                         capture_output=True, text=True)
    assert res.returncode == 2
    assert "Traceback" not in res.stderr
    assert f"{csv.name}: {column}: {words}" in res.stderr
    assert not (tmp_path / "r.json").exists()


def test_a_partly_stuck_probe_is_still_fitted(tmp_path, capsys):
    """A probe that reads one value in fewer than half of its rows still has a noise level: the
    record is fitted, not refused."""
    columns = _preload_columns()
    carriage = columns["carriage_x_um"].copy()
    carriage[: N // 3] = 1.0
    csv = _write(tmp_path, "partly stuck", PRELOAD_TOML, columns | {"carriage_x_um": carriage})
    assert main(["fit", str(csv), "--no-plots"]) == 0
    assert csv.with_name("partly_stuck.fit.json").exists()
