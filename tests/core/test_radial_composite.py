"""ISO 1328-2:1997 radial composite tolerances against values worked out here by hand.

The formulas (clause 7; the standard itself is not public: quoted by a public implementation, the
MITCalc web port's "Standard Engineering Tables", calcISO1328Tolerances, "ISO 1328 - Part 2"), with
d and m_n the geometric means of the standard's ranges holding the gear's own values and
s = sqrt(2)^(grade - 5):

    F_i'' = (3.2 m_n + 1.01 sqrt(d) + 6.4) s     total radial composite
    f_i'' = (2.96 m_n + 0.01 sqrt(d) + 0.8) s    tooth-to-tooth radial composite

ranges: m_n 0.2 / 0.5 / 0.8 / 1.0 / 1.5 / 2.5 / 4 / 6 / 10 mm, d 5 / 20 / 50 / 125 / 280 / 560 /
1000 mm (a value on a bound in the range below it). Rounding as ISO 1328: whole um above 10 um,
0.5 um from 5 to 10 um, 0.1 um below. No table of the standard (Annex A) could be found to read
values from, so every expected value below is the formula worked out by hand, step by step.
"""

import pytest

from geargen.core.accuracy import (ISO_1328_2, iso1328_2_radial_composite, iso1328_tolerances,
                                   radial_composite_block)
from geargen.errors import DesignError


def test_grade_5_in_the_20_to_50_mm_and_1_to_1_5_mm_ranges():
    # d 31 mm -> range (20, 50]: sqrt(1000) = 31.6228, sqrt = 5.62341; m_n 1.25 -> (1.0, 1.5]: sqrt(1.5) = 1.22474
    # F_i'' = 3.2 * 1.22474 + 1.01 * 5.62341 + 6.4 = 3.91918 + 5.67964 + 6.4 = 15.9988 -> 16
    # f_i'' = 2.96 * 1.22474 + 0.01 * 5.62341 + 0.8 = 3.62524 + 0.05623 + 0.8 = 4.48147 -> 4.5
    t = iso1328_2_radial_composite(5, 31.0, 1.25)
    assert (t.total, t.tooth_to_tooth) == (16.0, 4.5)
    assert t.standard == ISO_1328_2 and t.grade == 5
    assert t.diameter_mean == pytest.approx(31.6227766, abs=1e-6)  # sqrt(20 * 50), to the digits written out


def test_the_smallest_ranges_and_a_value_on_a_bound():
    # d 20 mm is on a bound: range [5, 20], mean sqrt(100) = 10, sqrt = 3.16228; m_n 0.5 on a bound: [0.2, 0.5],
    # mean sqrt(0.1) = 0.316228
    # F_i'' = 1.01193 + 3.19390 + 6.4 = 10.6058 -> 11;  f_i'' = 0.93603 + 0.03162 + 0.8 = 1.76765 -> 1.8
    t = iso1328_2_radial_composite(5, 20.0, 0.5)
    assert (t.total, t.tooth_to_tooth) == (11.0, 1.8)


def test_the_step_factor_applies_to_the_unrounded_value():
    # grade 8 (s = 2 sqrt 2 = 2.82843), d 100 -> (50, 125]: sqrt(6250) = 79.0569, sqrt = 8.89140;
    # m_n 2 -> (1.5, 2.5]: sqrt(3.75) = 1.93649
    # F_i'' = (6.19677 + 8.98031 + 6.4) * 2.82843 = 21.57708 * 2.82843 = 61.0293 -> 61
    # f_i'' = (5.73201 + 0.08891 + 0.8) * 2.82843 = 6.62092 * 2.82843 = 18.7268 -> 19
    t = iso1328_2_radial_composite(8, 100.0, 2.0)
    assert (t.total, t.tooth_to_tooth) == (61.0, 19.0)
    # grade 4 (s = 1/sqrt 2): f_i'' = 6.62092 * 0.707107 = 4.68170 -> 4.7 (the 0.1 um band)
    assert iso1328_2_radial_composite(4, 100.0, 2.0).tooth_to_tooth == 4.7


@pytest.mark.parametrize("args, field", [
    ((3, 50.0, 1.0), "grade"), ((13, 50.0, 1.0), "grade"), ((5, 4.9, 1.0), "reference_diameter"),
    ((5, 1000.1, 1.0), "reference_diameter"), ((5, 50.0, 0.19), "normal_module"), ((5, 50.0, 10.5), "normal_module"),
])
def test_outside_the_standard_is_an_error_naming_the_key(args, field):
    with pytest.raises(DesignError) as exc:
        iso1328_2_radial_composite(*args)
    assert exc.value.field == field


def test_the_accuracy_block_carries_the_radial_block_of_the_same_grade_number():
    out = iso1328_tolerances(5, 31.0, 1.25, 10.0).to_dict()
    radial = out["radial_composite"]
    assert radial["grade"] == 5 and radial["standard"] == ISO_1328_2
    # the worked-out values of the first test: the same gear, the same grade
    assert (radial["total_radial_composite_um"], radial["tooth_to_tooth_radial_composite_um"]) == (16.0, 4.5)
    assert "grade_rule" in radial


def test_no_radial_values_outside_the_standard_only_the_reason():
    # grade 2 is a flank class of ISO 1328-1:2013 but no radial composite grade of ISO 1328-2:1997 (4..12)
    block = radial_composite_block(2, 40.0, 1.0)
    assert block["grade"] is None and "total_radial_composite_um" not in block
    assert "grade" in block["not_given"] and block["scope"]["grades"] == [4, 12]
    # a module finer than 0.2 mm: ISO 1328-1:2013 refuses it too, so only the block speaks for it here
    assert radial_composite_block(6, 40.0, 0.15)["not_given"].startswith("the normal module is outside")
