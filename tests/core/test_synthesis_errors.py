"""Impossible or malformed synthesis inputs give errors that name the key and what is allowed."""

from __future__ import annotations

import copy
import math
import tomllib
from dataclasses import replace
from pathlib import Path

import pytest

from geargen.cli import main
from geargen.commands.synth import compute
from geargen.core.synthesis import place_gears, round_increments, synthesize_centres
from geargen.design.assembly import design_from_dict
from geargen.core.accuracy import error_budget_inputs
from geargen.design.synthesis import (GearErrors, MonteCarloSettings, monte_carlo_settings,
                                      synthesis_inputs)
from geargen.errors import DesignError, GeometryError

ROBOT = Path(__file__).resolve().parents[2] / "assemblies" / "robot_joint.toml"
BASE = tomllib.loads(ROBOT.read_text())


def robot(**changes):
    """The robot-joint design dictionary with dotted-path changes (None deletes the key)."""
    data = copy.deepcopy(BASE)
    for path, value in changes.items():
        *head, last = path.split("__")
        table = data
        for part in head:
            table = table.setdefault(part, {})
        if value is None:
            table.pop(last, None)
        else:
            table[last] = value
    return design_from_dict(data)


@pytest.mark.parametrize("changes, field, text", [
    # Eq. 8 has no solution: |C1 sin A1| > C2
    ({"synthesis__centre_distance_mesh2_in": 0.9, "gears__output__teeth": 36, "gears__cluster_small__teeth": 21},
     "synthesis.start_angle_A1_deg", "Eq. 8 has no solution"),
    # inverted backlash range
    ({"synthesis__circumferential_backlash_min_mesh1_in": 0.006}, "synthesis.circumferential_backlash_min_mesh1_in",
     "[0, 0.005 in]"),
    # negative backlash
    ({"synthesis__circumferential_backlash_max_mesh2_in": -0.001}, "synthesis.circumferential_backlash_max_mesh2_in",
     "negative backlash"),
    ({"synthesis__circumferential_backlash_min_mesh2_um": -1, "synthesis__circumferential_backlash_min_mesh2_in": None},
     "synthesis.circumferential_backlash_min_mesh2_um", "negative backlash"),
    # unknown, missing, out of range
    ({"synthesis__backlash_max_mesh1_in": 0.005}, "synthesis.backlash_max_mesh1_in", "circumferential_backlash_max_mesh1_in"),
    ({"synthesis__rounding": None}, "synthesis.rounding", "rounding"),
    ({"synthesis__rounding": "up"}, "synthesis.rounding", "'half_nearest'"),
    ({"synthesis__start_angle_A1_deg": 10.0}, "synthesis.start_angle_A1_deg", "(-90, 0) deg"),
    ({"synthesis__centre_distance_mesh1_in": 0.9}, "synthesis.centre_distance_mesh1_in", "sum of the base radii"),
    ({"synthesis__centre_distance_mesh1_in": 1.2}, "synthesis.centre_distance_mesh1_in", "sum of the tip radii"),
    # above zero: a length's plausible 1 nm to 10 m (schema.PLAUSIBLE), in inches
    ({"synthesis__centre_distance_mesh1_in": 0.0}, "synthesis.centre_distance_mesh1_in", "[3.93701e-08, 393.701] in"),
    # a mesh with two pitches
    ({"gears__cluster_large__diametral_pitch_per_in": 24}, "gears.cluster_large", "the same pitch"),
])
def test_bad_synthesis_input_names_the_key(changes, field, text):
    with pytest.raises(DesignError) as info:
        synthesis_inputs(robot(**changes))
    assert info.value.field == field
    assert text in str(info.value)


def test_missing_gear_and_missing_section_are_named():
    with pytest.raises(DesignError) as info:
        synthesis_inputs(robot(gears__output=None))
    assert info.value.field == "gears.output"
    with pytest.raises(DesignError) as info:
        synthesis_inputs(robot(synthesis=None))
    assert info.value.field == "synthesis"


@pytest.mark.parametrize("changes, field, text", [
    ({"errors__flywheel": {"tooth_to_tooth_tir_in": 0.0}}, "errors.flywheel", "cluster_small"),
    ({"errors__output": None}, "errors.output", "missing"),
    ({"errors__input__runout_in": 0.001}, "errors.input.runout_in", "bearing_eccentricity_tir_in"),
    ({"errors__input__tooth_to_tooth_tir_in": None}, "errors.input.tooth_to_tooth_tir", "missing"),
    ({"errors__cluster_small__pitch_line_eccentricity_tir_in": -0.0001},
     "errors.cluster_small.pitch_line_eccentricity_tir_in", "[0, 393.701] in"),  # at most 10 m
])
def test_bad_error_table_names_the_key(changes, field, text):
    with pytest.raises(DesignError) as info:
        error_budget_inputs(robot(**changes))
    assert info.value.field == field
    assert text in str(info.value)


@pytest.mark.parametrize("changes, field", [
    ({"monte_carlo__samples": 10}, "monte_carlo.samples"),
    ({"monte_carlo__model": "guess"}, "monte_carlo.model"),
    ({"monte_carlo__error_shape": "uniform"}, "monte_carlo.error_shape"),  # needs model = "appendix"
    ({"monte_carlo__seeds": 3}, "monte_carlo.seeds"),
])
def test_bad_monte_carlo_settings_name_the_key(changes, field):
    with pytest.raises(DesignError) as info:
        monte_carlo_settings(robot(**changes))
    assert info.value.field == field


def test_monte_carlo_defaults_when_the_section_is_absent():
    assert monte_carlo_settings(robot(monte_carlo=None)) == MonteCarloSettings()
    assert error_budget_inputs(robot(errors=None)) is None
    with pytest.raises(DesignError, match="needs \\[errors"):
        compute(robot(errors=None), run_monte_carlo=True)


def test_rounding_that_leaves_no_solution_near_the_start_angle():
    # at A1 = -89.9 deg the count (80.61 half teeth) rounded to the nearest half tooth, 81, needs A1 < -90 deg
    changes = {"synthesis__start_angle_A1_deg": -89.9, "synthesis__rounding": "half_nearest"}
    inputs = synthesis_inputs(robot(**changes))
    result = synthesize_centres(inputs)
    assert not result.success and math.isnan(result.A1) and result.increments == 81
    assert "no solution of Eqs. 7-8 near the start angle" in result.message
    with pytest.raises(GeometryError, match="no solution of Eqs. 7-8"):
        result.check()
    with pytest.raises(GeometryError, match="centre synthesis"):
        compute(robot(**changes))
    # the same start with the count rounded down does have a solution
    assert synthesize_centres(replace(inputs, rounding="half_down")).success


def test_solver_reports_eq8_failure_instead_of_raising():
    # a start angle past the Eq. 8 limit, built without the design-file check (direct core use)
    inputs = synthesis_inputs(robot())
    object.__setattr__(inputs, "centre_distance_mesh2", 0.5 * inputs.centre_distance_mesh1)
    result = synthesize_centres(inputs)
    assert not result.success and "Eq. 8 has no solution" in result.message


def test_gear_errors_and_inputs_validate_on_construction():
    with pytest.raises(DesignError, match="tooth_to_tooth_tir"):
        GearErrors(tooth_to_tooth_tir=-1.0)
    inputs = synthesis_inputs(robot())
    with pytest.raises(DesignError) as info:
        replace(inputs, circumferential_backlash_min_mesh2=inputs.circumferential_backlash_max_mesh2 * 2)
    assert info.value.field == "circumferential_backlash_min_mesh2" and "0.0042 in" in str(info.value)
    with pytest.raises(DesignError):
        replace(inputs, rounding="whole_up")


def test_placement_rejects_impossible_gaps():
    s = synthesize_centres(synthesis_inputs(robot())).check()
    assert not place_gears(s, loaded_flank_gap=-0.01).success
    p = place_gears(s, loaded_flank_gap=1.0)
    assert not p.success and "exceeds" in p.message
    with pytest.raises(GeometryError):
        p.check()


@pytest.mark.parametrize("value, rule, expected", [
    (70.34, "whole_down", 70), (70.34, "whole_nearest", 70), (70.34, "half_down", 70), (70.34, "half_nearest", 70),
    (71.6, "whole_down", 70), (71.6, "whole_nearest", 72), (71.6, "half_down", 71), (71.6, "half_nearest", 72),
    (73.2, "whole_down", 72), (73.2, "whole_nearest", 74), (73.2, "half_down", 73), (73.2, "half_nearest", 73),
])
def test_rounding_rules(value, rule, expected):
    assert round_increments(value, rule) == expected


def test_command_reports_design_errors_with_exit_code_2(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(ROBOT.read_text().replace("circumferential_backlash_min_mesh1_in = 0.0040",
                                             "circumferential_backlash_min_mesh1_in = 0.0060"))
    assert main(["synth", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "synthesis.circumferential_backlash_min_mesh1_in" in err and "allowed" in err
