"""``geargen fit NAME.csv --json REPORT.json --report DIR`` end to end, through the files."""

import json
import subprocess
import sys

import numpy as np

from geargen.cli import main
from geargen.fit.measurement import write_measurement
from geargen.fit.simulate import PreloadTruth, TorqueTruth, simulate_preload_trace, simulate_torque_deflection

CONTRACT_KEYS = ["kind", "samples", "units", "noise_rms", "stages", "effects_added", "unexplained"]
EFFECT_KEYS = {"harmonic": {"order", "amplitude", "phase_deg", "shaft", "multiple"},
               "drift": {"per_kelvin"}, "hysteresis": {"half_width"}, "stiffening": {"exponent"},
               "dead_band": {"width_urad"}}


#: keys added to the contract since (adding is allowed, changing is not)
ADDED_KEYS = {"noise_channels", "noise_ar1", "rejected_samples", "ambiguous", "budget"}
#: ... and the datasheet, in the reports of the kinds that have datasheet figures
DATASHEET_KINDS = {"torque_deflection", "transmission_error"}


def _check(j, kind, units):
    added = ADDED_KEYS | ({"datasheet"} if kind in DATASHEET_KINDS else set())
    assert [k for k in j if k not in added] == CONTRACT_KEYS and added <= set(j)
    channels = {"preload_trace": {"carriage_x_um"}, "torque_deflection": {"output_torque_Nm", "output_rotation_urad"}}
    assert set(j["noise_channels"]) == channels[kind] and all(v > 0 for v in j["noise_channels"].values())
    assert j["kind"] == kind and j["units"] == units
    assert isinstance(j["samples"], int) and j["noise_rms"] > 0
    for name in ("declared", "extended"):
        assert set(j["stages"][name]) == {"rms", "max_abs"}
    assert isinstance(j["unexplained"], bool)
    for e in j["effects_added"]:
        assert EFFECT_KEYS[e["effect"]] <= set(e) and e["evidence"]


def test_cli_preload_trace(tmp_path, capsys):
    sim = simulate_preload_trace(PreloadTruth(harmonics=((2.0, 3.0, 40.0),), drift_per_kelvin=1.0),
                                 np.random.default_rng(1))
    csv = write_measurement(sim.measurement, tmp_path, "bench_run",
                            extra_columns={"probe_volts": np.zeros(sim.measurement.samples)})
    out = tmp_path / "out" / "report.json"
    assert main(["fit", str(csv), "--json", str(out), "--report", str(tmp_path / "rep")]) == 0
    j = json.loads(out.read_text())
    _check(j, "preload_trace", "um")
    assert j["stages"]["nominal"]["rms"] > j["stages"]["declared"]["rms"] > j["stages"]["extended"]["rms"]
    assert sorted(e["effect"] for e in j["effects_added"]) == ["drift", "harmonic"]
    assert j["unexplained"] is False
    md = (tmp_path / "rep" / "report.md").read_text()
    assert "probe_volts" in md                      # the ignored column is noted
    for png in ("fit_data.png", "fit_residuals.png", "fit_spectrum.png", "fit_dependence.png"):
        assert (tmp_path / "rep" / png).stat().st_size > 1000
        assert png in md
    assert "unexplained: no" in capsys.readouterr().out


def test_cli_torque_deflection_default_paths(tmp_path):
    sim = simulate_torque_deflection(TorqueTruth(dead_band_urad=15.0), np.random.default_rng(2))
    csv = write_measurement(sim.measurement, tmp_path, "stiff")
    assert main(["fit", str(csv), "--no-plots"]) == 0
    j = json.loads((tmp_path / "stiff.fit.json").read_text())
    _check(j, "torque_deflection", "Nm")
    assert [e["effect"] for e in j["effects_added"]] == ["dead_band"]
    assert (tmp_path / "stiff_fit" / "report.md").exists()


def test_cli_error_names_the_column(tmp_path, capsys):
    (tmp_path / "bad.csv").write_text("time_s,output_angle_deg\n" + "\n".join(f"{i},{i}" for i in range(60)))
    (tmp_path / "bad.toml").write_text('kind = "preload_trace"\n[model]\nteeth = [16, 48, 21, 112]\n')
    assert main(["fit", str(tmp_path / "bad.csv"), "--json", str(tmp_path / "r.json")]) == 2
    assert "carriage_x_um" in capsys.readouterr().err
    assert not (tmp_path / "r.json").exists()


def test_json_dash_is_standard_output(tmp_path, capsys, monkeypatch):
    """``--json -`` means standard output, as for the other commands: the JSON alone there, the
    human summary on standard error, no file named '-', the report in its default place."""
    sim = simulate_preload_trace(PreloadTruth(), np.random.default_rng(3))
    csv = write_measurement(sim.measurement, tmp_path, "run")
    monkeypatch.chdir(tmp_path)
    assert main(["fit", str(csv), "--json", "-", "--no-plots"]) == 0
    captured = capsys.readouterr()
    _check(json.loads(captured.out), "preload_trace", "um")
    assert "unexplained: no" in captured.err and "wrote standard output" in captured.err
    assert not (tmp_path / "-").exists()
    assert not (tmp_path / "run.fit.json").exists()
    assert (tmp_path / "run_fit" / "report.md").exists()  # beside the CSV


def test_json_dash_keeps_the_report_folder(tmp_path, capsys, monkeypatch):
    sim = simulate_torque_deflection(TorqueTruth(), np.random.default_rng(4))
    csv = write_measurement(sim.measurement, tmp_path, "stiff")
    monkeypatch.chdir(tmp_path)
    assert main(["fit", str(csv), "--json", "-", "--report", str(tmp_path / "rep"), "--no-plots"]) == 0
    _check(json.loads(capsys.readouterr().out), "torque_deflection", "Nm")
    assert (tmp_path / "rep" / "report.md").exists() and not (tmp_path / "-").exists()


def test_json_dash_as_a_user_runs_it(tmp_path):
    sim = simulate_preload_trace(PreloadTruth(), np.random.default_rng(5))
    csv = write_measurement(sim.measurement, tmp_path, "run")
    res = subprocess.run([sys.executable, "-m", "geargen.cli", "fit", str(csv), "--json", "-", "--no-plots"],
                         capture_output=True, text=True, cwd=tmp_path, check=True)
    _check(json.loads(res.stdout), "preload_trace", "um")  # nothing but the JSON on standard output
    assert "preload_trace:" in res.stderr
    assert not (tmp_path / "-").exists()
