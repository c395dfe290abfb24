"""[duty] and [materials.GEAR] (issue 29 phase 2): the spectrum, speed, life and materials every mesh
is rated for, read and refused like every section (the key and the allowed range named)."""

import tomllib
from pathlib import Path

import pytest

from geargen.design.assembly import design_from_dict
from geargen.design.checks import checks_settings
from geargen.design.duty import DEFAULT_LIFE, DEFAULT_OUTPUT_SPEED, duty_settings, gear_materials
from geargen.design.iso6336_5 import TABLE_8, hardness_range
from geargen.errors import DesignError

ROOT = Path(__file__).resolve().parents[2]
ROBOT = ROOT / "assemblies" / "robot_joint.toml"
NMM_PER_IN_LBF = 4.4482216152605 * 25.4  # N per lbf (exact by definition) times mm per in


def robot_with(extra: str):
    """The shipped robot joint without its [duty] and [materials] (geargen's defaults), plus ``extra``."""
    data = tomllib.loads(ROBOT.read_text())
    data.pop("duty", None)
    data.pop("materials", None)
    data.update(tomllib.loads(extra))
    return design_from_dict(data, validate=True)


def test_without_duty_the_spectrum_is_the_papers_maximum_load_for_the_whole_life():
    duty = duty_settings(robot_with(""))
    assert duty.levels == ((5000.0, 1.0),)  # [preload] max_output_torque_Nm = 5.0
    assert "max_output_torque_Nm" in duty.levels_source and duty.torque_unit == "Nm"
    assert (duty.life, duty.output_speed) == (DEFAULT_LIFE, DEFAULT_OUTPUT_SPEED)
    # the defaults' claim: 20,000 h at 60 rpm pass the 5e7 cycles of the latest endurance knee
    assert 60 * DEFAULT_OUTPUT_SPEED * DEFAULT_LIFE > 5e7
    # both ways, half the life each
    assert duty.signed_levels() == ((5000.0, 0.5, 1), (-5000.0, 0.5, 1))
    mats = gear_materials(robot_with(""))
    assert set(mats) == {"input", "cluster_large", "cluster_small", "output"}
    assert {(m.name, m.quality, m.hardness) for m in mats.values()} == {("through_hardened", "MQ", 300.0)}


def test_levels_in_inch_pounds_hours_and_cycles():
    duty = duty_settings(robot_with("[duty]\noutput_torque_levels_in_lbf = [40, 10]\nlevel_hours = [100, 900]"))
    assert duty.levels[0][0] == pytest.approx(40 * NMM_PER_IN_LBF, rel=1e-15)
    assert duty.torque_unit == "in_lbf"
    assert duty.life == 1000.0  # the hours' sum
    assert [s for _, s in duty.levels] == pytest.approx([0.1, 0.9], rel=1e-15)
    cycles = duty_settings(robot_with("[duty]\noutput_torque_levels_Nm = [4, 1]\nlevel_cycles = [1e6, 3e6]\n"
                                      "output_speed_rpm = 20"))
    assert cycles.life == pytest.approx(4e6 / (60 * 20), rel=1e-15)  # revolutions / (60 n)
    assert [s for _, s in cycles.levels] == pytest.approx([0.25, 0.75], rel=1e-15)
    signed = duty_settings(robot_with("[duty]\ndirection = \"signed\"\noutput_torque_levels_Nm = [4, -2, 0]\n"
                                      "level_shares = [0.2, 0.3, 0.5]"))
    assert signed.signed_levels() == ((4000.0, 0.2, 1), (-2000.0, 0.3, 2), (0.0, 0.5, 3))


@pytest.mark.parametrize("extra, key, allowed", [
    ("[duty]\noutput_torque_levels_Nm = [4, -2]\nlevel_shares = [0.5, 0.5]", "duty.output_torque_levels_Nm[1]",
     ">= 0"),
    ("[duty]\noutput_torque_levels_Nm = [4, 2]\nlevel_shares = [0.5, 0.6]", "duty.level_shares", "1 (within 0.001)"),
    ("[duty]\noutput_torque_levels_Nm = [4, 2]", "duty.level_shares", "one value per level"),
    ("[duty]\noutput_torque_levels_Nm = [4, 2]\nlevel_shares = [1]", "duty.level_shares", "one per level"),
    ("[duty]\noutput_torque_levels_Nm = [4]\nlevel_hours = [10]\nlife_hours = 5", "duty.life_hours", "one of them"),
    ("[duty]\nhardness_HV = 400", "duty.hardness_HV", "200..360 HV"),
    ("[duty]\nmaterial = \"induction_hardened\"", "duty.hardness_HV", "500..570 HV"),
    ("[duty]\nmaterial = \"case_hardened\"", "duty.material", "'case_carburised'"),
    ("[duty]\nviscosity_mm2_per_s = 1", "duty.viscosity_mm2_per_s", "[2, 3200]"),
    ("[duty]\nroughness_Ra_um = 100", "duty.roughness_Ra_um", "[0.001, 50] um"),
    ("[materials.outptu]\nmaterial = \"case_carburised\"", "materials.outptu", "output"),
    ("[materials.output]\nmaterial = \"case_carburised\"\nhardness_HV = 500", "materials.output.hardness_HV",
     "660..800 HV"),
    ("[checks]\nmin_S_F = 0", "checks.min_S_F", "[1e-09, 10]"),
])
def test_a_bad_duty_is_refused_on_load_naming_the_key_and_the_range(extra, key, allowed):
    with pytest.raises(DesignError) as exc:
        robot_with(extra)
    assert exc.value.field == key
    assert allowed in exc.value.allowed


def test_a_gear_table_overrides_duty_and_inherits_what_it_does_not_say():
    design = robot_with("[duty]\nmaterial = \"induction_hardened\"\nhardness_HV = 550\nquality = \"ME\"\n"
                        "[materials.output]\nmaterial = \"case_carburised\"\n"
                        "[materials.input]\nquality = \"MQ\"\n[checks]\nmin_S_H = 1.2\nmin_S_F = 2.0")
    mats = gear_materials(design)
    assert (mats["output"].name, mats["output"].quality, mats["output"].hardness) == ("case_carburised", "ME", None)
    assert (mats["input"].name, mats["input"].quality, mats["input"].hardness) == ("induction_hardened", "MQ", 550.0)
    assert mats["cluster_large"].source == "[duty]" and mats["input"].source == "[materials.input]"
    settings = checks_settings(design)
    assert (settings.min_S_H, settings.min_S_F) == (1.2, 2.0)


def test_hardness_ranges_are_where_both_of_the_standards_lines_give_numbers():
    # induction hardened MQ: contact line 500-615 HV, bending line 500-570 HV (ISO 6336-5 Table 8)
    assert TABLE_8["induction_hardened"][1]["contact"]["MQ"][2:] == (500, 615)
    assert TABLE_8["induction_hardened"][1]["bending"]["MQ"][2:] == (500, 570)
    assert hardness_range("induction_hardened", "MQ") == (500, 570)
