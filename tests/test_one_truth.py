"""One truth per number: every command reports the same resolved drive.

``synth``, ``check``, ``stiffness`` and ``build`` (its manifest, resolved.json and report) all
start from :func:`geargen.model.resolve`; this test runs each command on each shipped assembly
through :func:`geargen.cli.main` and asserts that the backlash, the operating centre distance and
the phase of every gear agree to 1 nm (1e-6 mm), and that sections of the exported STEP solids
measure the same backlash (with the section chords bisected to 0.2 nm of the curves).
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from geargen.cli import main
from geargen.units import LENGTH_SUFFIXES

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]
DESIGNS = {"robot_joint": ROOT / "assemblies/robot_joint.toml", "c_axis": ROOT / "assemblies/c_axis.toml",
           "split_pinion": ROOT / "assemblies/split_pinion.toml"}
NM = 1e-6  # mm


def _json_of(capsys, *argv) -> tuple[int, dict]:
    capsys.readouterr()
    code = main(list(argv))
    return code, json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("name", list(DESIGNS))
def test_every_command_reports_the_same_resolved_drive(built_assemblies, capsys, name):
    folder = built_assemblies[name]
    resolved = json.loads((folder / "resolved.json").read_text())
    manifest = json.loads((folder / "manifest.json").read_text())
    unit = resolved["length_unit"]
    tol = NM / LENGTH_SUFFIXES[unit]  # 1 nm in the design's unit
    meshes = {m["name"]: m for m in resolved["meshes"]}
    gears = {g["name"]: g for g in resolved["gears"]}

    # check: the same verdict (the build passed, so check passes) and the same numbers
    code, checked = _json_of(capsys, "check", str(DESIGNS[name]), "--json", "-")
    assert code == 0 and checked["ok"], checked["failures"]
    assert checked["length_unit"] == unit
    for b in checked["backlash"]:
        m = meshes[b["mesh"]]
        assert b["centre_distance"] == pytest.approx(m["centre_distance"], abs=tol)
        if b["engaged"]:
            # measured on the exact outlines over a tooth cycle: constant, and the modelled value
            assert b["min"] == pytest.approx(m["backlash"], abs=tol), b["mesh"]
            assert b["max"] == pytest.approx(m["backlash"], abs=tol), b["mesh"]
            assert b["modelled"] == pytest.approx(m["backlash"], abs=tol)

    # build manifest (mm): path 1 in the design kind
    k = LENGTH_SUFFIXES[unit]
    for e in manifest["checks"]["meshes"]:
        m = meshes[e["mesh"]]
        assert e["centre_distance"] == pytest.approx(m["centre_distance"] * k, abs=NM)
        if e["engaged"]:
            assert e["backlash_min"] == pytest.approx(m["backlash"] * k, abs=NM)
            assert e["backlash_max"] == pytest.approx(m["backlash"] * k, abs=NM)
    assert manifest["status"] == "ok"

    # synth (dual-pinion drives): the placement it prints is the resolved one
    if "mesh1_a" in meshes:
        code, synth = _json_of(capsys, "synth", str(DESIGNS[name]), "--json", "-")
        assert code == 0
        again = synth["resolved"]
        for g in again["gears"]:
            assert g["centre"] == pytest.approx(gears[g["name"]]["centre"], abs=tol)
            assert g["rotation_rad"] == pytest.approx(gears[g["name"]]["rotation_rad"], abs=1e-12)
        for m in again["meshes"]:
            assert m["backlash"] == pytest.approx(meshes[m["name"]]["backlash"], abs=tol)
            assert m["centre_distance"] == pytest.approx(meshes[m["name"]]["centre_distance"], abs=tol)
    else:
        assert main(["synth", str(DESIGNS[name])]) == 2  # no synthesis to report: a clear error, not a number

    # the report prints the same backlash (as many digits as it shows)
    report = (folder / "report.md").read_text()
    for m in resolved["meshes"]:
        if m["engaged"]:
            assert f"{m['backlash']:.5g}" in report, m["name"]


@pytest.mark.parametrize("name", list(DESIGNS))
def test_sections_of_the_exported_step_measure_the_resolved_backlash(built_assemblies, name):
    """The teeth in the STEP files are the resolved ones: mid-face sections of the re-imported solids
    (chords within 0.2 nm of the exact section curves) give the resolved backlash to 1 nm plus the
    build's stated spline tolerance on the two flanks."""
    from geargen import pipeline as pl
    from geargen.cad.gear_solid import default_tolerance
    from geargen.checks.verdict import design_backlash

    folder = built_assemblies[name]
    resolved = json.loads((folder / "resolved.json").read_text())
    manifest = json.loads((folder / "manifest.json").read_text())
    layout = pl.place(pl.load(DESIGNS[name]))
    mesh = next(m for m in layout.meshes if m.engaged)
    shapes = []
    for part in (mesh.part1, mesh.part2):
        from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
        from geargen.cad.assembly import _trsf
        inv = np.linalg.inv(np.asarray(manifest["parts"][part]["placement_matrix_mm"], dtype=float))
        shapes.append(BRepBuilderAPI_Transform(built_assemblies.step(name, part).shape, _trsf(inv), True).Shape())
    result = pl.section_check(layout, mesh, *shapes, chord_tolerance=2e-7)
    lo, hi = design_backlash(result, mesh.gear1.reference_radius)
    want = next(m for m in resolved["meshes"] if m["name"] == mesh.name)["backlash"] * LENGTH_SUFFIXES[resolved["length_unit"]]
    # each flank spline lies within the build's gear_solid_tolerance of the exact surface (the
    # C-axis builds its helicoids to 0.1 um): two flanks, along the normal, seen on the reference circle
    spline = pl.export_config(layout.design)["gear_solid_tolerance"] or default_tolerance(mesh.gear1)
    g = mesh.gear1
    allowed = NM + 2 * spline / (math.cos(g.transverse_pressure_angle) * math.cos(g.base_helix_angle))
    assert lo == pytest.approx(want, abs=allowed) and hi == pytest.approx(want, abs=allowed), (lo, hi, want, allowed)


@pytest.mark.parametrize("name", list(DESIGNS))
def test_check_sections_the_builds_own_stl_files(built_assemblies, capsys, name):
    """`check --sections --exported DIR` on the build's own STL files (assembly frame, the build's
    chordal tolerance from its manifest): every mesh agrees with the exact path 1 (it reported
    "differs by inf mm" before the exported parts were taken back into their own frames)."""
    folder = built_assemblies[name]
    code, data = _json_of(capsys, "check", str(DESIGNS[name]), "--sections", "--exported", str(folder),
                          "--no-tolerances", "--json", "-")
    assert code == 0, data["failures"]
    assert data["agreement"] and all(a["agree"] for a in data["agreement"])
    assert all(np.isfinite(a["normal_backlash_difference_max"]) for a in data["agreement"])


def test_check_refuses_an_exported_folder_of_another_design(built_assemblies, capsys):
    code = main(["check", str(DESIGNS["split_pinion"]), "--sections", "--exported", str(built_assemblies["robot_joint"])])
    assert code == 2
    assert "--exported" in capsys.readouterr().err


def test_gear_data_of_an_assembly_gear_is_the_resolved_gear(tmp_path, capsys):
    """`geargen gear DESIGN --gear NAME` writes the gear the assembly builds: the C-axis makes its
    gears at the middle of their allowances, and the gear data says so, with the same number."""
    from geargen.design.assembly import load_design
    from geargen.drives.resolver import resolve

    layout = resolve(load_design(DESIGNS["c_axis"]))
    want = next(g for p in layout.gears for g in p.gears if g.name == "output").thinning
    assert main(["gear", str(DESIGNS["c_axis"]), "--gear", "output", "--out", str(tmp_path / "g"), "--no-stl"]) == 0
    data = json.loads((tmp_path / "g" / "output.json").read_text())
    assert data["thinning_circumferential"] == pytest.approx(want, abs=NM) and want > 0.03
    assert data["thinning_source"].startswith("mid_tolerance: the middle of its tooth-thickness tolerance")
