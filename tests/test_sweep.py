"""geargen sweep: sweep files, one truth with synth/stiffness/check, identical tables on 1 and 2 workers.

One small sweep of the robot joint (a grid value the design file refuses, two random centre
distances of mesh 1, the carriage Monte Carlo in four chunks) runs twice through the command:
on a local cluster of one process worker (``--workers 1``) and on a two-worker cluster started
here (``--scheduler``). The cluster is shared by the module: starting one costs seconds.
"""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from geargen.cli import main
from geargen.design.sweep import MonteCarloBlock, sweep_from_dict
from geargen.errors import DesignError

ROOT = Path(__file__).resolve().parents[1]
ROBOT = ROOT / "assemblies/robot_joint.toml"
MM_PER_IN = 25.4

SMALL_SWEEP = """
[parameters]
"flexures.thickness_in" = [0.010, -0.001]           # the second is refused by the design file
"synthesis.centre_distance_mesh1_in" = { uniform = [1.0025, 1.0055] }
"checks.monte_carlo_samples" = [12]

[random]
count = 2
seed = 7

[monte_carlo]
samples = 20000
chunk_size = 6000
seed = 1994
"""


@pytest.fixture(scope="module")
def scheduler():
    """The address of a local cluster of two process workers, as geargen starts one."""
    from geargen.sweep import dask_client
    with dask_client(2) as client:
        yield client.scheduler.address


@pytest.fixture(scope="module")
def sweeps(tmp_path_factory, scheduler):
    """The small sweep through the command on 1 worker and on the 2-worker cluster: (tables, folders)."""
    import pandas as pd
    root = tmp_path_factory.mktemp("sweep")
    sweep = root / "small.toml"
    sweep.write_text(SMALL_SWEEP)
    out = {}
    for name, how in (("one", ["--workers", "1"]), ("two", ["--scheduler", scheduler])):
        folder = root / name
        assert main(["sweep", str(ROBOT), str(sweep), "--out", str(folder), "--quiet", *how]) == 0
        out[name] = (pd.read_parquet(folder / "sweep.parquet"), folder)
    return out


@pytest.mark.slow
def test_one_and_two_workers_give_identical_tables(sweeps):
    import pandas as pd
    one, two = sweeps["one"][0], sweeps["two"][0]
    pd.testing.assert_frame_equal(one, two, check_exact=True)
    assert len(one) == 4 and list(one["design"]) == [0, 1, 2, 3]
    # the design order of the file: grid point (flexure) slowest, the two draws within it, shared by both points
    assert list(one["flexures.thickness_in"]) == [0.010, 0.010, -0.001, -0.001]
    cd = one["synthesis.centre_distance_mesh1_in"].to_numpy()
    assert cd[0] == cd[2] and cd[1] == cd[3] and cd[0] != cd[1]
    rng = np.random.default_rng(np.random.SeedSequence(7).spawn(2)[1])
    assert cd[1] == rng.uniform(1.0025, 1.0055)


@pytest.mark.slow
def test_output_folder_holds_table_plots_and_manifest(sweeps):
    folder = sweeps["two"][1]
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["generator"] == "geargen sweep"
    assert set(manifest["files"]) == {"sweep.parquet", "summary.png", "summary.svg"}
    assert manifest["workers"] == 2 and manifest["sweep"]["designs"] == 4
    assert (folder / "summary.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert b"<svg" in (folder / "summary.svg").read_bytes()[:400]
    assert not [p for p in folder.parent.iterdir() if p.name.startswith(".")]  # no temporary folder left


@pytest.mark.slow
def test_rejected_designs_carry_their_tag(sweeps):
    t = sweeps["one"][0]
    refused = t[t["flexures.thickness_in"] < 0]
    assert set(refused["status"]) == {"rejected"}
    assert set(refused["tag"]) == {"invalid:flexures.thickness_in"}
    assert all(m.startswith("flexures.thickness_in: ") for m in refused["message"])
    # mesh 1's backlash follows its centre distance: outside 0.0040-0.0050 in the check rejects it
    placed = t[t["flexures.thickness_in"] > 0]
    for _, row in placed.iterrows():
        backlash_in = row["backlash_min_mm.mesh1_a"] / MM_PER_IN
        inside = 0.0040 - 1e-9 <= backlash_in <= 0.0050 + 1e-9
        assert (row["status"] == "ok") == inside
        if not inside:
            assert row["tag"].split(";")[:2] == ["backlash_out_of_range:mesh1_a", "backlash_out_of_range:mesh1_b"]
            assert math.isnan(row["mc_travel_mean_mm"])  # no Monte Carlo for a rejected design
    assert (placed["status"] == "ok").sum() == 1  # seed 7: one draw inside the range, one outside


def _design_file(tmp_path, row) -> Path:
    """The robot joint with the row's values written into the file as a user would."""
    text = ROBOT.read_text()
    text = re.sub(r"(?m)^centre_distance_mesh1_in = 1\.004", f"centre_distance_mesh1_in = "
                  f"{float(row['synthesis.centre_distance_mesh1_in'])!r}", text)
    text = re.sub(r"(?m)^thickness_in = 0\.010", f"thickness_in = {float(row['flexures.thickness_in'])!r}", text)
    text += f"\n[checks]\nmonte_carlo_samples = {int(row['checks.monte_carlo_samples'])}\n"
    path = tmp_path / "robot_joint_row.toml"
    path.write_text(text)
    return path


@pytest.mark.slow
def test_row_equals_synth_stiffness_and_check(sweeps, tmp_path, capsys):
    t = sweeps["one"][0]
    row = t[t["status"] == "ok"].iloc[0]
    design = _design_file(tmp_path, row)
    assert main(["stiffness", str(design), "--no-plots", "--json", str(tmp_path / "s.json")]) == 0
    assert main(["synth", str(design), "--json", str(tmp_path / "y.json")]) == 0
    assert main(["check", str(design), "--json", str(tmp_path / "c.json")]) == 0
    capsys.readouterr()
    s = json.loads((tmp_path / "s.json").read_text())
    y = json.loads((tmp_path / "y.json").read_text())
    c = json.loads((tmp_path / "c.json").read_text())
    assert row["drive_stiffness_Nm_per_rad"] == s["drive"]["stiffness_Nm_per_rad"]
    assert row["loop_stiffness_Nm_per_rad"] == s["loop"]["stiffness_Nm_per_rad"]
    assert row["preload_Nm"] == s["preload_Nm"]
    mean = next(v for v in s["preload_variation"] if v["label"] == "mean")
    assert row["preload_variation_Nm"] == mean["range_Nm"]
    for m in y["resolved"]["meshes"]:  # synth's placed centres, in the design's inches
        assert row[f"centre_distance_mm.{m['name']}"] == pytest.approx(m["centre_distance"] * MM_PER_IN, rel=1e-14)
    for tol in c["tolerances"]:  # check's worst case and Monte Carlo minimum per mesh, inches
        assert row[f"worst_case_backlash_mm.{tol['mesh']}"] == pytest.approx(tol["worst_case_min_backlash"] * MM_PER_IN,
                                                                             rel=1e-14)
        assert row[f"mc_min_backlash_mm.{tol['mesh']}"] == pytest.approx(tol["monte_carlo_min_backlash"] * MM_PER_IN,
                                                                         rel=1e-14)
    assert row["ratio"] == 32.0

    # the Monte Carlo: synth's simulation, chunk i drawn from SeedSequence(1994).spawn(4)[i], joined in order
    from geargen.commands.synth import compute
    from geargen.core.tolerance import monte_carlo
    from geargen.design.assembly import load_design
    run = compute(load_design(design))
    block = MonteCarloBlock(20000, 6000, 1994)
    assert block.chunk_sizes() == [6000, 6000, 6000, 2000]
    travel = np.concatenate([monte_carlo(run.synthesis, run.errors, n, np.random.default_rng(seed)).travel
                             for n, seed in zip(block.chunk_sizes(), block.seeds())])
    assert row["mc_samples"] == 20000
    assert row["mc_travel_mean_mm"] == np.mean(travel)
    assert row["mc_travel_std_mm"] == np.std(travel)
    spread = np.percentile(travel, 99.865) - np.percentile(travel, 0.135)
    assert row["mc_travel_spread_99_73_mm"] == spread
    # the preload band of that travel: k_L times the loop error 2 lambda travel (Eq. 3/6), N·m
    lever = s["preload"]["lever_rad_per_mm"]
    assert row["mc_preload_variation_Nm"] == pytest.approx(s["loop"]["stiffness_Nm_per_rad"] * 2 * lever * spread,
                                                           rel=1e-12)
    assert 0 < row["mc_preload_variation_Nm"] < row["preload_variation_Nm"]  # below the Appendix's (Sum+RSS)/2


@pytest.mark.slow
def test_shipped_sweep_file_is_valid_for_the_robot_joint():
    from geargen.design.sweep import load_sweep
    from geargen.sweep import check_sweep
    spec = load_sweep(ROOT / "assemblies/sweeps/robot_joint_stiffness.toml")
    check_sweep(ROBOT, spec)
    assert spec.size == 18 and spec.monte_carlo.chunks == 4


# ---------------------------------------------------------------- the sweep file and its errors


def _error(data) -> DesignError:
    with pytest.raises(DesignError) as info:
        sweep_from_dict(data)
    return info.value


@pytest.mark.parametrize("data, field, words", [
    ({"parameters": {"gears.input.teeth": [16]}, "grid": {}}, "grid", "[parameters], [random], [monte_carlo]"),
    ({}, "parameters", "nothing to vary"),
    ({"parameters": {"teeth": [16]}}, 'parameters."teeth"', "dotted path"),
    ({"parameters": {"gears.input.teeth": []}}, 'parameters."gears.input.teeth"', "empty list"),
    ({"parameters": {"gears.input.teeth": 16}}, 'parameters."gears.input.teeth"', "neither a list nor a distribution"),
    ({"parameters": {"gears.input.teeth": {"gauss": [1, 2]}}}, 'parameters."gears.input.teeth"', "uniform"),
    ({"parameters": {"a.b": {"uniform": [2.0, 1.0]}}, "random": {"count": 2, "seed": 1}}, 'parameters."a.b".uniform',
     "above high"),
    ({"parameters": {"a.b": {"integers": [1.5, 3]}}, "random": {"count": 2, "seed": 1}}, 'parameters."a.b".integers',
     "whole numbers"),
    ({"parameters": {"a.b": {"normal": [0.0, -1.0]}}, "random": {"count": 2, "seed": 1}}, 'parameters."a.b".normal',
     "negative"),
    ({"parameters": {"a.b": {"uniform": [0, 1]}}}, "random.count", "missing"),
    ({"parameters": {"a.b": {"uniform": [0, 1]}}, "random": {"count": 0, "seed": 1}}, "random.count", "1 to 100,000"),
    ({"parameters": {"a.b": [1]}, "random": {"count": 3}}, "random", "no parameter is random"),
    ({"parameters": {"a.b": [1]}, "monte_carlo": {"samples": 10, "chunk_size": 0, "seed": 1}}, "monte_carlo.chunk_size",
     "1 to 10,000,000"),
    ({"parameters": {"a.b": [1]}, "monte_carlo": {"samples": 10**8, "chunk_size": 10, "seed": 1}},
     "monte_carlo.chunk_size", "at most 100,000 chunks"),
    ({"parameters": {"a.b": [1]}, "monte_carlo": {"samples": 10, "chunks": 2, "seed": 1}}, "monte_carlo.chunks",
     "did you mean chunk_size"),
    ({"parameters": {"a.b": list(range(400)), "a.c": list(range(400))}}, "parameters", "at most 100,000"),
    ({"parameters": {"a.b": [1], "a.b.c": [2]}}, 'parameters."a.b.c"', "inside"),
])
def test_bad_sweep_files_name_the_key_and_the_range(data, field, words):
    err = _error(data)
    errors = getattr(err, "errors", [err])
    match = [e for e in errors if e.field == field]
    assert match, f"no error for {field}: {err}"
    assert words in str(match[0]), str(match[0])


def test_grid_and_random_designs():
    spec = sweep_from_dict({"parameters": {"a.x": [1, 2, 3], "a.y": {"integers": [10, 20]}, "a.z": ["p", "q"]},
                            "random": {"count": 2, "seed": 11}})
    designs = spec.designs()
    assert spec.size == len(designs) == 12
    # the last grid parameter fastest, the draws within each grid point
    assert [(d["a.x"], d["a.z"]) for d in designs[::2]] == [(1, "p"), (1, "q"), (2, "p"), (2, "q"), (3, "p"), (3, "q")]
    draws = [np.random.default_rng(s).integers(10, 20, endpoint=True) for s in np.random.SeedSequence(11).spawn(2)]
    assert [d["a.y"] for d in designs] == [int(v) for v in draws] * 6
    assert list(designs[0]) == ["a.x", "a.y", "a.z"]  # the file's order


@pytest.mark.parametrize("path, words", [
    ("gears.input.teth", "did you mean teeth"),
    ("gears.inptu.teeth", "has no [gears.inptu]"),
    ("flexure.thickness_in", "did you mean flexures"),
])
def test_a_parameter_naming_no_key_of_the_design_is_refused(path, words, tmp_path, capsys):
    sweep = tmp_path / "s.toml"
    sweep.write_text(f'[parameters]\n"{path}" = [16]\n')
    assert main(["sweep", str(ROBOT), str(sweep), "--out", str(tmp_path / "out"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert f'parameters."{path}"' in err and words in err
    assert not (tmp_path / "out").exists()


def test_bad_options_are_refused_before_any_work(tmp_path, capsys):
    sweep = tmp_path / "s.toml"
    sweep.write_text('[parameters]\n"flexures.thickness_in" = [0.01]\n')
    out = str(tmp_path / "out")
    assert main(["sweep", str(ROBOT), str(sweep), "--out", out, "--workers", "0"]) == 2
    assert "--workers: 0 is out of range (allowed: 1 to 1024)" in capsys.readouterr().err
    assert main(["sweep", str(ROBOT), str(sweep), "--out", out, "--workers", "2", "--scheduler", "tcp://x:1"]) == 2
    assert "one of --workers and --scheduler" in capsys.readouterr().err
    assert main(["sweep", str(ROBOT), str(tmp_path / "missing.toml"), "--out", out]) == 3
    assert "no such sweep file" in capsys.readouterr().err
    no_budget = tmp_path / "mc.toml"
    no_budget.write_text('[parameters]\n"gears.output.teeth" = [60]\n[monte_carlo]\nsamples = 10\nchunk_size = 5\n'
                         'seed = 1\n')
    assert main(["sweep", str(ROOT / "assemblies/split_pinion.toml"), str(no_budget), "--out", out]) == 2
    assert "monte_carlo: the design split_pinion.toml has no error budget" in capsys.readouterr().err
    assert main(["sweep", str(ROOT / "assemblies/dual_motor.toml"), str(sweep), "--out", out]) == 2
    assert "layout: the design dual_motor.toml is no drive" in capsys.readouterr().err
    assert not Path(out).exists()


def test_pareto_front():
    from geargen.sweep import pareto_front
    stiffness = np.array([1.0, 2.0, 3.0, 2.0, 3.0, np.nan, 0.5])
    variation = np.array([1.0, 1.0, 2.0, 0.5, 2.0, 0.1, 0.4])
    # 0 beaten by 3 (stiffer, steadier); 1 beaten by 3; 2 and 4 tie (neither beats the other); 5 has no stiffness
    assert pareto_front(stiffness, variation).tolist() == [False, False, True, True, True, False, True]


@pytest.mark.slow
def test_output_folder_policy(scheduler, tmp_path, capsys):
    """Its own earlier sweep is replaced; another sweep file's needs --overwrite; a user's file is never deleted."""
    a, b = tmp_path / "a.toml", tmp_path / "b.toml"
    a.write_text('[parameters]\n"flexures.thickness_in" = [-0.001]\n')  # rejected at once: a cheap sweep
    b.write_text('[parameters]\n"flexures.thickness_in" = [-0.002]\n')
    out = tmp_path / "out"
    run = ["--out", str(out), "--quiet", "--scheduler", scheduler]
    assert main(["sweep", str(ROBOT), str(a), *run]) == 0
    assert main(["sweep", str(ROBOT), str(a), *run]) == 0
    assert main(["sweep", str(ROBOT), str(b), *run]) == 3
    assert "--overwrite replaces it" in capsys.readouterr().err
    assert main(["sweep", str(ROBOT), str(b), *run, "--overwrite"]) == 0
    import pandas as pd
    assert pd.read_parquet(out / "sweep.parquet")["flexures.thickness_in"].tolist() == [-0.002]
    (out / "notes.txt").write_text("mine")
    assert main(["sweep", str(ROBOT), str(b), *run, "--overwrite"]) == 3
    assert (out / "notes.txt").read_text() == "mine"
