"""``geargen check``: the [checks] section, the table, --json, exit status, plots; the layering."""

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from geargen.cli import main
from geargen.design.assembly import design_from_dict
from geargen.design.checks import checks_settings
from geargen.errors import DesignError

ROBOT = str(Path(__file__).resolve().parents[2] / "assemblies" / "robot_joint.toml")

PAIR = """
name = "pair"
[gear_defaults]
module_mm = 2
pressure_angle_deg = 20
face_width_mm = 10
[gears.pinion]
teeth = 18
thinning_circumferential_mm = 0.04
[gears.wheel]
teeth = 45
thinning_circumferential_mm = 0.04
[checks]
meshes = [["pinion", "wheel"]]
centre_distance_mm = {a}
steps_per_tooth = 8
monte_carlo_samples = 20
"""


def _write(tmp_path, text, name="pair.toml"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text))
    return p


def test_a_good_pair_passes_and_writes_json(tmp_path, capsys):
    p = _write(tmp_path, PAIR.format(a=63.05) + """
[errors.pinion]
pitch_line_eccentricity_tir_um = 10
tooth_to_tooth_tir_um = 5
[errors.wheel]
pitch_line_eccentricity_tir_um = 15
""")
    out = tmp_path / "out" / "check.json"
    assert main(["check", str(p), "--json", str(out), "--plots", str(tmp_path / "plots")]) == 0
    text = capsys.readouterr().out
    assert "pinion-wheel" in text and "result: ok" in text and "worst case" in text
    data = json.loads(out.read_text())
    assert data["ok"] and data["length_unit"] == "mm"
    m = data["meshes"][0]
    assert m["mesh"] == "pinion-wheel" and m["failures"] == []
    assert 0.1 < m["circumferential_backlash_min"] < 0.2
    assert data["tolerances"][0]["monte_carlo_samples"] == 20
    assert data["tolerances"][0]["worst_case_min_backlash"] < m["circumferential_backlash_min"]
    assert all((tmp_path / "plots" / f).stat().st_size > 5000 for f in ("pinion-wheel_backlash.png",
                                                                         "pinion-wheel_tolerance.png"))


def test_crowded_pair_fails_with_exit_status_1(tmp_path, capsys):
    # standard centre distance 63 mm, 0.5 mm tip clearance; with 0.8 mm of allowance on each gear
    # the flanks keep backlash at 0.6 mm of crowding while the tips reach into the roots
    p = _write(tmp_path, PAIR.format(a=62.4).replace("0.04", "0.8"))
    assert main(["check", str(p), "--json", "-", "--no-tolerances"]) == 1
    data = json.loads(capsys.readouterr().out)
    kinds = {f["kind"] for f in data["meshes"][0]["failures"]}
    assert "tip_to_root_interference" in kinds
    assert data["meshes"][0]["min_clearance"] < 0


def test_bad_checks_key_is_a_design_error(tmp_path, capsys):
    p = _write(tmp_path, PAIR.format(a=63.05).replace("steps_per_tooth = 8", "step_per_tooth = 8"))
    assert main(["check", str(p)]) == 2
    assert "checks.step_per_tooth: unknown key" in capsys.readouterr().err


@pytest.mark.parametrize("patch, field", [
    ({"meshes": [["pinion", "gearX"]], "centre_distance_mm": 63}, "checks.meshes"),
    ({"meshes": [["pinion", "wheel"]]}, "checks.centre_distance_mm"),
    ({"meshes": [["pinion", "wheel"]], "centre_distance_mm": [63, 64]}, "checks.centre_distance_mm"),
    ({"meshes": [["pinion", "wheel"]], "centre_distance_in": -1}, "checks.centre_distance_in"),
    ({"steps_per_tooth": 1}, "checks.steps_per_tooth"),
    ({"stl_chordal_tolerance_um": 0}, "checks.stl_chordal_tolerance_um"),
])
def test_checks_section_names_the_bad_key(patch, field):
    data = {"gear_defaults": {"module_mm": 2, "pressure_angle_deg": 20, "face_width_mm": 10},
            "gears": {"pinion": {"teeth": 18}, "wheel": {"teeth": 45}}, "checks": patch}
    with pytest.raises(DesignError) as info:
        checks_settings(design_from_dict(data))
    assert info.value.field == field


def test_checks_section_units():
    data = {"gear_defaults": {"diametral_pitch_per_in": 32, "pressure_angle_deg": 20, "face_width_in": 0.25},
            "gears": {"a": {"teeth": 16}, "b": {"teeth": 48}},
            "checks": {"meshes": [["a", "b"]], "centre_distance_in": 1.004, "carriage_travel_limit_in": 0.02,
                       "stl_chordal_tolerance_um": 2}}
    s = checks_settings(design_from_dict(data))
    assert s.meshes[0].centre_distance == pytest.approx(1.004 * 25.4, rel=1e-15)
    assert s.carriage_travel_limit == pytest.approx(0.508) and s.stl_chordal_tolerance == pytest.approx(0.002)
    assert s.meshes[0].name == "a-b"


def test_robot_joint_command(capsys):
    assert main(["check", ROBOT, "--samples", "30"]) == 0
    text = capsys.readouterr().out
    for mesh in ("mesh1_a", "mesh1_b", "mesh2_a", "mesh2_b"):
        assert text.count(mesh) >= 2  # sweep row and tolerance row
    assert "preloaded" in text and "carriage travel" in text
    # the bevel pair, measured on its exact outlines: the design's 0.0015 in (tests/test_robot_bevel.py)
    assert "bevel pair (bevel_gear - bevel_pinion)" in text and "measured 0.001500  design 0.001500" in text


def test_pure_check_modules_do_not_load_the_cad_kernel():
    mods = ["geargen.checks.mesh2d", "geargen.checks.tolerance", "geargen.checks.results",
            "geargen.design.checks", "geargen.report.checks", "geargen.commands.check"]
    code = ("import sys, importlib\n"
            f"for m in {mods!r}: importlib.import_module(m)\n"
            "print(','.join(m for m in sys.modules if m.split('.')[0] in ('cadquery', 'OCP', 'trimesh', 'matplotlib')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == ""


def test_json_lengths_are_in_the_design_unit():
    from geargen.checks.results import DesignCheck, Failure

    r = DesignCheck("d", "in", [], agreement=[{"mesh": "m", "normal_backlash_difference_max": 0.0254, "tolerance": 0.0508,
                                               "min_clearance_difference": None, "agree": True}],
                    failures=[Failure("paths_disagree", "m", "x", "path_difference", 0.254, 0.0254)])
    d = r.to_dict()
    assert d["agreement"][0]["normal_backlash_difference_max"] == pytest.approx(0.001)
    assert d["agreement"][0]["tolerance"] == pytest.approx(0.002)
    assert d["failures"][0]["value"] == pytest.approx(0.01) and d["failures"][0]["unit"] == "in"
