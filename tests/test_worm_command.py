"""``geargen gear --kind worm`` / ``--kind worm_wheel`` and ``[gear] kind = "worm"``."""

import json
import math

import pytest

from geargen.cli import main
from geargen.design.gear import gear_from_table
from geargen.design.worm import WormSpec

KHK = ["--module", "3", "--starts", "2", "--wheel-teeth", "30", "--worm-diameter", "44", "--pressure-angle", "20"]


def test_design_table_kind_worm_reads_the_set():
    spec = gear_from_table({"kind": "worm", "module_mm": 3, "starts": 2, "wheel_teeth": 30,
                            "worm_reference_diameter_mm": 44, "worm_face_length_mm": 30, "wheel_face_width_mm": 28})
    assert isinstance(spec, WormSpec) and spec.set.pressure_angle == pytest.approx(math.radians(20))


def test_a_cylindrical_option_is_refused_for_a_worm(tmp_path, capsys):
    assert main(["gear", "--kind", "worm", *KHK, "--teeth", "30", "--worm-length", "30", "--wheel-width", "28",
                 "--out", str(tmp_path / "w")]) != 0
    assert "--teeth: does not apply to --kind worm" in capsys.readouterr().err


@pytest.mark.slow
def test_gear_command_writes_the_worm(tmp_path, capsys):
    out = tmp_path / "worm"
    assert main(["gear", "--kind", "worm", *KHK, "--worm-length", "30", "--wheel-width", "28",
                 "--backlash", "0.05", "--backlash-on", "worm", "--no-stl", "--out", str(out)]) == 0
    data = json.loads((out / "worm.json").read_text())
    # KHK Gear Technical Reference Table 4.17: gamma 7.76517 deg, a 67 mm, throat diameter 96 mm
    assert data["lead_angle_deg"] == pytest.approx(7.76517, abs=5e-6)
    assert (data["centre_distance"], data["throat_diameter"]) == pytest.approx((67.0, 96.0))
    # the worm is thinned by the backlash: axial thread thickness p_x/2 - j
    assert data["worm_axial_thread_thickness"] == pytest.approx(math.pi * 3 / 2 - 0.05)
    assert (out / "worm.step").stat().st_size > 0


@pytest.mark.slow
def test_gear_command_writes_the_worm_wheel(tmp_path):
    out = tmp_path / "wheel"
    assert main(["gear", "--kind", "worm_wheel", *KHK, "--worm-length", "30", "--wheel-width", "28",
                 "--backlash", "0.05", "--no-stl", "--out", str(out)]) == 0
    data = json.loads((out / "worm_wheel.json").read_text())
    # KHK Gear Technical Reference Table 4.17: throat diameter 96, outside diameter 99, root diameter 82.5
    assert data["kind"] == "worm_wheel"
    assert (data["throat_diameter"], data["wheel_outside_diameter"], data["wheel_root_diameter"]) == \
        pytest.approx((96.0, 99.0, 82.5))
    assert (out / "worm_wheel.step").stat().st_size > 0 and not (out / "worm_wheel.stl").exists()
