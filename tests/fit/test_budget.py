"""The loop back into the design: a simulated bench run of the robot joint, made with the exact
loop geometry (every gear's pitch circle offset and turning, the carriage re-solved at each
sample: geargen.core.synthesis.solve_loop), is fitted; the fitted amplitudes, turned back into
TIRs through the gradients of that geometry, are set beside the design's error budget."""

from pathlib import Path

import numpy as np
import pytest

from geargen.core.synthesis import OFFSET_GEARS, solve_loop
from geargen.design.assembly import load_design
from geargen.design.synthesis import GEAR_ROLES
from geargen.fit.measurement import read_measurement
from geargen.fit.selection import diagnose
from geargen.drives import resolve

ROOT = Path(__file__).resolve().parents[2]
ROBOT = ROOT / "assemblies/robot_joint.toml"
ROLE = {"input": "input", "cluster_large_a": "cluster_large", "cluster_large_b": "cluster_large",
        "cluster_small_a": "cluster_small", "cluster_small_b": "cluster_small", "output": "output"}


def _bench_run(tmp_path, scale: dict[str, float], seed: int = 1, samples: int = 3000, noise_um: float = 0.1):
    """A preload trace of the robot joint over 1.5 output revolutions: each gear's eccentricity at
    ``scale[role]`` x its budgeted TIR (bearing + pitch line), at a random phase, turning with the
    gear (the clusters at -R2 the output's speed, the input at R1 R2); the carriage re-solved
    exactly at every sample; 0.1 um probe noise. Returns the CSV path and the true TIRs (mm)."""
    run = resolve(load_design(ROBOT)).synthesis
    syn, errors = run.synthesis, run.errors
    r1, r2 = syn.ratio_mesh1, syn.ratio_mesh2
    speed = {"input": r1 * r2, "cluster_large": -r2, "cluster_small": -r2, "output": 1.0}
    rng = np.random.default_rng(seed)
    theta = np.linspace(0.0, 3 * np.pi, samples)
    offsets = np.zeros((samples, 6, 2))
    tir = {}
    for k, gear in enumerate(OFFSET_GEARS):
        role = ROLE[gear]
        e = errors[GEAR_ROLES.index(role)]
        tir[gear] = scale.get(role, 1.0) * (e.bearing_eccentricity_tir + e.pitch_line_eccentricity_tir)
        phase = rng.uniform(0, 2 * np.pi)
        offsets[:, k, 0] = tir[gear] / 2 * np.cos(speed[role] * theta + phase)
        offsets[:, k, 1] = tir[gear] / 2 * np.sin(speed[role] * theta + phase)
    x = solve_loop(syn, offsets=offsets).check().carriage_x
    carriage = (x - x.mean()) * 1e3 + noise_um * rng.normal(size=samples)
    t = np.linspace(0.0, 600.0, samples)
    csv = tmp_path / "robot_bench.csv"
    csv.write_text("time_s,output_angle_deg,carriage_x_um\n" + "\n".join(
        f"{a:.4f},{np.degrees(b):.6f},{c:.5f}" for a, b, c in zip(t, theta, carriage)) + "\n")
    (tmp_path / "robot_bench.toml").write_text(f'kind = "preload_trace"\nassembly = "{ROBOT.as_posix()}"\n')
    return csv, tir


def test_the_gear_beyond_its_eccentricity_budget_is_named_with_its_tir(tmp_path):
    """The output gear at 3 x its budgeted eccentricity, the others at theirs: the output row says
    it exceeds, with the TIR put in (within 2 %); input and clusters are inside, the input's TIR
    measured within 2 %."""
    csv, tir = _bench_run(tmp_path, {"output": 3.0})
    report = diagnose(read_measurement(csv)).to_json()
    budget = report["budget"]
    assert budget["assembly"] == "robot_joint.toml"
    rows = {r["part"]: r for r in budget["terms"]}
    out = rows["output"]
    assert out["verdict"] == "exceeds"
    assert out["measured_tir_um"] == pytest.approx(tir["output"] * 1e3, rel=0.02)
    assert out["budget_tir_um"] == pytest.approx(tir["output"] * 1e3 / 3, rel=1e-9)
    assert out["excess_tir_um"] == pytest.approx(out["measured_tir_um"] - out["budget_tir_um"], rel=1e-9)
    assert rows["input"]["verdict"] == "at the budget"  # (at exactly its budget, to the noise)
    assert rows["input"]["measured_tir_um"] == pytest.approx(tir["input"] * 1e3, rel=0.02)
    assert rows["cluster"]["verdict"] == "inside"
    assert rows["cluster"]["amplitude_um"] <= rows["cluster"]["budget_amplitude_um"]
    assert "output eccentricity TIR" in budget["summary"] and "exceeds the budget" in budget["summary"]


def test_a_drive_inside_its_budget_says_so(tmp_path):
    csv, tir = _bench_run(tmp_path, {"output": 0.5, "input": 0.5}, seed=2)
    budget = diagnose(read_measurement(csv)).to_json()["budget"]
    assert all(r["verdict"] == "inside" for r in budget["terms"])
    rows = {r["part"]: r for r in budget["terms"]}
    assert rows["output"]["measured_tir_um"] == pytest.approx(tir["output"] * 1e3, rel=0.02)
    assert budget["summary"].startswith("every measured error is inside")


def test_update_design_writes_the_measured_errors_and_the_preload_band_before_and_after(tmp_path):
    """``--update-design``: a copy of the robot joint with the output's measured eccentricity (the
    bearing's as designed, the pitch-line one the rest), the design file untouched, and the preload
    band the design predicts before and after: wider with the output 3 x out of round."""
    import hashlib
    from geargen.commands.fit import fit_files
    from geargen.design.assembly import load_design

    csv, tir = _bench_run(tmp_path, {"output": 3.0})
    original = hashlib.sha256(ROBOT.read_bytes()).hexdigest()
    out = tmp_path / "robot_joint_measured.toml"
    summary = fit_files(csv, tmp_path / "fit.json", tmp_path / "report", plots=False, update_design=out)["summary"]
    assert hashlib.sha256(ROBOT.read_bytes()).hexdigest() == original
    updated = load_design(out)
    errors = resolve(updated).synthesis.errors
    e = errors[GEAR_ROLES.index("output")]
    measured = next(r for r in summary["budget"]["terms"] if r["part"] == "output")["measured_tir_um"]
    assert (e.bearing_eccentricity_tir + e.pitch_line_eccentricity_tir) * 1e3 == pytest.approx(measured, rel=1e-5)
    designed = resolve(load_design(ROBOT)).synthesis.errors[GEAR_ROLES.index("output")]
    assert e.bearing_eccentricity_tir == pytest.approx(designed.bearing_eccentricity_tir, rel=1e-9)
    update = summary["design_update"]
    assert "errors.output.pitch_line_eccentricity_tir" in {c["key"] for c in update["changes"]}
    before, after = update["preload_variation"]["before"], update["preload_variation"]["after"]
    assert after["range_Nm"] > before["range_Nm"]
    assert out.read_text().startswith("# Updated by geargen fit robot_bench.csv")
    page = (tmp_path / "report" / "report.html").read_text()
    assert "error budget" in page and "<td>exceeds</td>" in page


def test_update_design_needs_an_assembly_and_writes_nothing_without_one(tmp_path):
    from geargen.commands.fit import fit_files
    from geargen.errors import DesignError
    csv, _ = _bench_run(tmp_path, {})
    (tmp_path / "robot_bench.toml").write_text('kind = "preload_trace"\n[model]\nteeth = [16, 48, 21, 112]\n')
    out = tmp_path / "never.toml"
    with pytest.raises(DesignError, match="--update-design"):
        fit_files(csv, tmp_path / "fit.json", tmp_path / "report", plots=False, update_design=out)
    assert not out.exists() and not (tmp_path / "fit.json").exists()
