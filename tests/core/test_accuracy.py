"""ISO 1328-1:2013 tolerances against values worked out here from the standard's text.

Every expected value below is computed in the test from the edition's formulas, with their
numbers written out (not by calling geargen.core.accuracy), and rounded by hand by clause 5.2.3:
above 10 um to 1 um, from 5 to 10 um to 0.5 um, below 5 um to 0.1 um. With s = sqrt(2)^(A - 5):

    f_pT  = (0.001 d + 0.4 m_n + 5) s                       (5)
    F_pT  = (0.002 d + 0.55 sqrt(d) + 0.7 m_n + 12) s       (6)
    f_HaT = (0.4 m_n + 0.001 d + 4) s,  f_faT = (0.55 m_n + 5) s,  F_aT = hypot(f_HaT, f_faT)   (7-9)
    f_HbT = (0.05 sqrt(d) + 0.35 sqrt(b) + 4) s,  f_fbT = (0.07 sqrt(d) + 0.45 sqrt(b) + 4) s,
    F_bT  = hypot(f_HbT, f_fbT)                             (10-12)
    F_rT  = 0.9 F_pT                                         (runout annex)
"""

import math

import pytest

from geargen.core.accuracy import grade_for_budget, iso1328_round, iso1328_tolerances
from geargen.design.gear import gear_from_table
from geargen.errors import DesignError

R2 = math.sqrt(2.0)


def raw(grade, d, mn, b):
    """The unrounded tolerances, written out from the formulas above (um)."""
    s = R2 ** (grade - 5)
    f_h_a, f_f_a = (0.4 * mn + 0.001 * d + 4) * s, (0.55 * mn + 5) * s
    f_h_b, f_f_b = (0.05 * math.sqrt(d) + 0.35 * math.sqrt(b) + 4) * s, (0.07 * math.sqrt(d) + 0.45 * math.sqrt(b) + 4) * s
    F_p = (0.002 * d + 0.55 * math.sqrt(d) + 0.7 * mn + 12) * s
    return {"single_pitch": (0.001 * d + 0.4 * mn + 5) * s, "cumulative_pitch": F_p,
            "profile_total": math.hypot(f_h_a, f_f_a), "helix_total": math.hypot(f_h_b, f_f_b), "runout": 0.9 * F_p,
            "profile_slope": f_h_a, "profile_form": f_f_a, "helix_slope": f_h_b, "helix_form": f_f_b}


# (d mm, m_n mm, b mm, grade): {quantity: (unrounded value as worked out by hand, rounded by 5.2.3)}
CASES = {
    # small: z 25, m_n 0.8 mm spur -> d 20 mm, b 8 mm
    (20.0, 0.8, 8.0, 4): {
        "single_pitch": (3.776, 3.8),         # (0.02 + 0.32 + 5) / sqrt(2) = 3.776; < 5: to 0.1
        "cumulative_pitch": (10.649, 11.0),   # (0.04 + 2.4597 + 0.56 + 12) / sqrt(2) = 10.649; just > 10: to 1 (10.5 in the 0.5 band)
        "profile_total": (4.921, 4.9),        # hypot(3.0688, 3.8467) = 4.921; < 5: to 0.1
        "helix_total": (5.403, 5.5),          # hypot(3.6865, 3.9498) = 5.403; 5..10: to 0.5
        "runout": (9.584, 9.5),               # 0.9 * 10.649 = 9.584; 5..10: to 0.5
    },
    (20.0, 0.8, 8.0, 7): {
        "single_pitch": (10.68, 11.0),        # 5.34 * 2
        "cumulative_pitch": (30.119, 30.0),   # 15.060 * 2
        "profile_total": (13.918, 14.0),      # hypot(8.68, 10.88)
        "helix_total": (15.282, 15.0),        # hypot(10.427, 11.172)
        "runout": (27.107, 27.0),
        "profile_slope": (8.68, 8.5),         # 4.34 * 2; 5..10: to 0.5
    },
    # medium: z 30, m_n 4 mm spur -> d 120 mm, b 40 mm
    (120.0, 4.0, 40.0, 5): {
        "single_pitch": (6.72, 6.5),          # 0.12 + 1.6 + 5
        "cumulative_pitch": (21.065, 21.0),   # 0.24 + 6.0249 + 2.8 + 12
        "profile_total": (9.196, 9.0),        # hypot(5.72, 7.2)
        "helix_total": (10.182, 10.0),        # hypot(6.7613, 7.6129); just > 10: to 1
        "runout": (18.959, 19.0),
        "profile_form": (7.2, 7.0),           # 2.2 + 5
    },
    (120.0, 4.0, 40.0, 8): {
        # 6.72 * 2 sqrt(2) = 19.007 -> 19; rounding the class-5 value first (6.5 * 2.828 = 18.38) would give 18
        "single_pitch": (19.007, 19.0),
        "cumulative_pitch": (59.581, 60.0),
        "profile_total": (26.009, 26.0),
        "helix_total": (28.799, 29.0),
        "runout": (53.623, 54.0),
    },
    # large: z 60, m_n 16 mm spur -> d 960 mm, b 200 mm
    (960.0, 16.0, 200.0, 1): {
        "single_pitch": (3.09, 3.1),          # (0.96 + 6.4 + 5) / 4
        "cumulative_pitch": (10.540, 11.0),   # (1.92 + 17.041 + 11.2 + 12) / 4
        "profile_total": (4.469, 4.5),        # hypot(2.84, 3.45)
        "helix_total": (4.087, 4.1),
        "runout": (9.486, 9.5),
    },
    (960.0, 16.0, 200.0, 6): {
        "single_pitch": (17.480, 17.0),       # 12.36 * sqrt(2)
        "cumulative_pitch": (59.625, 60.0),
        "profile_total": (25.278, 25.0),
        "helix_total": (23.121, 23.0),
        "runout": (53.662, 54.0),
        "helix_slope": (14.848, 15.0),
    },
}


@pytest.mark.parametrize("case", list(CASES), ids=lambda c: f"d{c[0]:g}-m{c[1]:g}-b{c[2]:g}-A{c[3]}")
def test_tolerances_match_the_standards_formulas_and_rounding(case):
    d, mn, b, grade = case
    t = iso1328_tolerances(grade, d, mn, b)
    assert (t.standard, t.grade) == ("ISO 1328-1:2013", grade)
    unrounded = raw(grade, d, mn, b)
    for quantity, (by_hand, rounded) in CASES[case].items():
        # the hand arithmetic in the table is the formula's (guards the table against typos)
        assert unrounded[quantity] == pytest.approx(by_hand, abs=6e-4), quantity
        assert getattr(t, quantity) == rounded, quantity


def test_every_rounding_band_and_its_edges():
    # 5.2.3 by hand: > 10 -> 1 um; 5..10 -> 0.5 um; < 5 -> 0.1 um; halves up
    assert iso1328_round(10.0) == 10.0            # 10 itself is in the 0.5 band
    assert iso1328_round(10.49) == 10.0 and iso1328_round(10.5) == 11.0
    assert iso1328_round(9.74) == 9.5 and iso1328_round(9.75) == 10.0
    assert iso1328_round(5.0) == 5.0 and iso1328_round(5.24) == 5.0 and iso1328_round(5.25) == 5.5
    assert iso1328_round(4.94) == 4.9 and iso1328_round(4.95) == 5.0   # rounds up out of the 0.1 band
    assert iso1328_round(0.04) == 0.0 and iso1328_round(0.05) == 0.1


def test_a_formula_landing_on_a_tie_rounds_up():
    # d 150, m_n 1.5, grade 5: f_pT = 0.15 + 0.6 + 5 = 5.75 exactly -> 6.0 (5.5 if the sum's last bit fell short)
    assert iso1328_tolerances(5, 150.0, 1.5, 10.0).single_pitch == 6.0


def test_to_dict_has_the_contracts_keys():
    t = iso1328_tolerances(6, 120.0, 3.0, 30.0)
    out = t.to_dict()
    for key in ("standard", "grade", "single_pitch_um", "cumulative_pitch_um", "profile_total_um", "helix_total_um",
                "runout_um"):
        assert key in out
    # grade 6, d 120, m_n 3: f_pT = (0.12 + 1.2 + 5) sqrt(2) = 8.938 -> 9.0
    assert out["single_pitch_um"] == 9.0 and out["runout_um"] == t.runout


@pytest.mark.parametrize("args, field, allowed", [
    ((12, 120.0, 3.0, 30.0), "grade", "[1, 11]"),
    ((0, 120.0, 3.0, 30.0), "grade", "[1, 11]"),
    ((6, 4.9, 0.5, 30.0), "reference_diameter", "[5, 15000] mm"),
    ((6, 15001.0, 30.0, 30.0), "reference_diameter", "[5, 15000] mm"),
    ((6, 120.0, 0.49, 30.0), "normal_module", "[0.5, 70] mm"),
    ((6, 1200.0, 71.0, 30.0), "normal_module", "[0.5, 70] mm"),
    ((6, 120.0, 3.0, 3.9), "face_width", "[4, 1200] mm"),
    ((6, 120.0, 3.0, 1201.0), "face_width", "[4, 1200] mm"),
])
def test_outside_the_editions_range_names_the_field(args, field, allowed):
    with pytest.raises(DesignError) as exc:
        iso1328_tolerances(*args)
    assert exc.value.field == field and exc.value.allowed == allowed


def test_the_range_edges_are_inside():
    iso1328_tolerances(1, 5.0, 0.5, 4.0)
    iso1328_tolerances(11, 15000.0, 70.0, 1200.0)


def test_a_gear_table_outside_the_scope_is_refused_naming_accuracy_grade():
    table = {"teeth": 20, "module_mm": 0.3, "pressure_angle_deg": 20, "face_width_mm": 5, "accuracy_grade": 6}
    with pytest.raises(DesignError) as exc:
        gear_from_table(table, where="gears.pinion")
    assert exc.value.field == "gears.pinion.accuracy_grade" and "[0.5, 70] mm" in exc.value.allowed
    with pytest.raises(DesignError) as exc:
        gear_from_table({**table, "module_mm": 1.0, "accuracy_grade": 12}, where="gears.pinion")
    assert exc.value.field == "gears.pinion.accuracy_grade" and exc.value.allowed == "[1, 11]"
    with pytest.raises(DesignError) as exc:
        no_grade = {k: v for k, v in table.items() if k != "accuracy_grade"}
        gear_from_table({**no_grade, "module_mm": 1.0, "accuracy_standard": "ISO 1328-1:2013"}, where="gears.pinion")
    assert exc.value.field == "gears.pinion.accuracy_standard"


def test_grade_for_budget_is_the_coarsest_grade_within_the_tirs():
    d, mn, b = 120.0, 4.0, 40.0   # the medium gear above
    # grade 8: F_rT 54, f_pT 19 um; grade 9: F_rT = 0.9 * 84.260 = 75.8 -> 76, f_pT 26.88 -> 27 um
    assert grade_for_budget(d, mn, b, 0.054, 0.019) == 8
    assert grade_for_budget(d, mn, b, 0.076, 0.027) == 9
    assert grade_for_budget(d, mn, b, 0.076, 0.0269) == 8     # the tooth-to-tooth TIR holds it back
    assert grade_for_budget(d, mn, b, 0.0539, 1.0) == 7       # the runout does
    # grade 1: F_rT = 0.9 * 5.266 = 4.7, f_pT 1.68 -> 1.7 um: a tighter budget has no grade
    assert grade_for_budget(d, mn, b, 0.0046, 0.0017) is None
    assert grade_for_budget(d, mn, b, 1.0, 1.0) == 11
