"""``geargen gear``: STEP, STL, manifest and the derived-quantities JSON, from options or a file."""

import json

import pytest

from geargen.cli import main

pytestmark = pytest.mark.slow


def test_gear_from_options(tmp_path, capsys):
    out = tmp_path / "g"
    rc = main(["gear", "--teeth", "21", "--diametral-pitch", "32", "--helix-angle", "20", "--hand", "left",
               "--face-width", "0.5", "--bore", "0.125", "--out", str(out), "--name", "pinion"])
    assert rc == 0
    assert {p.name for p in out.iterdir()} == {"pinion.step", "pinion.stl", "pinion.json", "manifest.json",
                                               "pinion-drawing.svg", "pinion-drawing.pdf", "pinion.dxf"}
    data = json.loads((out / "pinion.json").read_text())
    assert data["drawing"] == {"svg": "pinion-drawing.svg", "pdf": "pinion-drawing.pdf", "dxf": "pinion.dxf"}
    assert data["length_unit"] == "in"
    assert data["teeth"] == 21 and data["hand"] == "left"
    assert data["face_width"] == pytest.approx(0.5)
    assert data["reference_radius"] == pytest.approx(21 / 32 / 2 / 0.9396926207859084, rel=1e-12)
    for key in ("base_radius", "tip_radius", "root_radius", "tip_land_transverse", "involute_start_radius",
                "span", "over_pins"):
        assert data[key] is not None, key
    assert data["over_pins"]["kind"] == "balls"
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["files"]["pinion.step"]["length_unit"] == "in"
    assert manifest["files"]["pinion.stl"]["chordal_tolerance_mm"] == 0.001
    assert "CONVERSION_BASED_UNIT('INCH'" in (out / "pinion.step").read_text()


def test_gear_from_a_design_file_with_undercut_warning(tmp_path, capsys):
    design = tmp_path / "small.toml"
    design.write_text('[gear]\nteeth = 9\nmodule_mm = 1.0\npressure_angle_deg = 20\nface_width_mm = 4\n'
                      'bore_diameter_mm = 2\n')
    rc = main(["gear", str(design), "--out", str(tmp_path / "o"), "--measure", "--no-stl"])
    assert rc == 0
    assert "undercut" in capsys.readouterr().err
    data = json.loads((tmp_path / "o" / "small.json").read_text())
    assert data["length_unit"] == "mm" and data["undercut"] is True
    assert data["measured"]["flank_deviation_max_um"] < 0.1


def test_bad_options_are_design_errors(tmp_path, capsys):
    assert main(["gear", "--teeth", "21", "--module", "1", "--out", str(tmp_path)]) == 2
    assert "face-width" in capsys.readouterr().err
    assert main(["gear", "--teeth", "10", "--module", "1", "--face-width", "5", "--profile-shift", "1.5",
                 "--out", str(tmp_path)]) == 2
    assert "pointed_tooth" in capsys.readouterr().err
