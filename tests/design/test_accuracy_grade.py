"""A gear's accuracy_grade in a design: the error budget it sets, one truth per number, the gear JSON.

The robot joint (inch design, 32 DP) with grades on its gears must give the same synthesis, worst
case and Monte Carlo as the same design with the grades' TIRs typed in. The typed-in values are
worked out here from ISO 1328-1:2013 (m_n = 25.4 / 32 = 0.79375 mm, d = z m_n, s = sqrt(2)^(A-5)):

    gear           z    d mm     A  F_rT = 0.9 (0.002 d + 0.55 sqrt(d) + 0.7 m_n + 12) s   f_pT = (0.001 d + 0.4 m_n + 5) s
    input          16   12.7     5  13.087 -> 13 um                                        5.330 -> 5.5 um
    cluster_large  48   38.1     5  14.424 -> 14 um                                        5.356 -> 5.5 um
    cluster_small  21   16.669   6  18.881 -> 19 um                                        7.544 -> 7.5 um
    output         112  88.9     6  22.807 -> 23 um                                        7.646 -> 7.5 um

(rounding of 5.2.3: above 10 um to 1 um, 5..10 um to 0.5 um).
"""

import json
import re
from pathlib import Path

import pytest

from geargen.cli import main
from geargen.core.accuracy import error_budget_inputs, gear_errors
from geargen.design.assembly import load_design
from geargen.design.schema import DesignErrors
from geargen.errors import DesignError

ROBOT = Path(__file__).resolve().parents[2] / "assemblies" / "robot_joint.toml"
IN_PER_UM = 1 / 25400
GRADES = {"input": 5, "cluster_large": 5, "cluster_small": 6, "output": 6}
TYPED_UM = {"input": (13, 5.5), "cluster_large": (14, 5.5), "cluster_small": (19, 7.5), "output": (23, 7.5)}


def _errors_table(text: str, gear: str) -> re.Match:
    m = re.search(rf"(\[errors\.{gear}\]\nbearing_eccentricity_tir_in = [0-9.]+)\n"
                  r"pitch_line_eccentricity_tir_in = [0-9.]+\ntooth_to_tooth_tir_in = [0-9.]+\n", text)
    assert m, gear
    return m


def robot_files(tmp_path: Path) -> tuple[Path, Path]:
    """The robot joint with grades (each [errors.*] keeps only its bearing eccentricity), and with the
    grades' TIRs typed in, in inches."""
    graded = typed = ROBOT.read_text()
    for gear, grade in GRADES.items():
        graded = re.sub(rf"(\[gears\.{gear}\][^\n]*\n)", rf"\1accuracy_grade = {grade}\n", graded)
        m = _errors_table(graded, gear)
        graded = graded.replace(m.group(0), m.group(1) + "\n")
        m = _errors_table(typed, gear)
        runout, pitch = TYPED_UM[gear]
        typed = typed.replace(m.group(0), f"{m.group(1)}\npitch_line_eccentricity_tir_in = {runout * IN_PER_UM!r}\n"
                                          f"tooth_to_tooth_tir_in = {pitch * IN_PER_UM!r}\n")
    (tmp_path / "graded.toml").write_text(graded)
    (tmp_path / "typed.toml").write_text(typed)
    return tmp_path / "graded.toml", tmp_path / "typed.toml"


def test_a_grade_sets_the_same_budget_as_its_tirs_typed_in(tmp_path):
    graded_path, typed_path = robot_files(tmp_path)
    graded, typed = load_design(graded_path), load_design(typed_path)
    eg, et = error_budget_inputs(graded), error_budget_inputs(typed)
    for a, b in zip(eg, et):
        for kind in ("bearing_eccentricity_tir", "pitch_line_eccentricity_tir", "tooth_to_tooth_tir"):
            assert getattr(a, kind) == pytest.approx(getattr(b, kind), rel=1e-12, abs=0)
    # the pair-by-pair reader (the checks' worst case and Monte Carlo, the train) sees the same
    for gear in GRADES:
        assert gear_errors(graded, gear).tooth_to_tooth_tir == pytest.approx(gear_errors(typed, gear).tooth_to_tooth_tir,
                                                                            rel=1e-12)
    assert eg[3].sources[1] == "ISO 1328-1:2013 grade 6: F_rT 23 um"
    assert eg[0].sources == ("", "ISO 1328-1:2013 grade 5: F_rT 13 um", "ISO 1328-1:2013 grade 5: f_pT 5.5 um")


def test_synth_and_monte_carlo_agree_and_the_table_names_the_source(tmp_path, capsys):
    graded_path, typed_path = robot_files(tmp_path)
    out = {}
    for name, path in (("graded", graded_path), ("typed", typed_path)):
        assert main(["synth", str(path), "--monte-carlo", "--samples", "2000", "--seed", "3", "--json", "-"]) == 0
        out[name] = json.loads(capsys.readouterr().out)
        assert main(["synth", str(path)]) == 0
        out[name + "_text"] = capsys.readouterr().out
    g, t = out["graded"], out["typed"]
    for key in ("dx1", "dx1_sum", "dx1_rss", "total_error", "pitch_line_eccentricity_tir", "tooth_to_tooth_tir"):
        assert g["error_budget"][key] == pytest.approx(t["error_budget"][key], rel=1e-9), key
    assert g["exact_error_budget"]["travel_resolved"] == pytest.approx(t["exact_error_budget"]["travel_resolved"],
                                                                      rel=1e-9)
    # the same seed draws the same samples from the same budget
    assert json.dumps(g["monte_carlo"], sort_keys=True) == json.dumps(t["monte_carlo"], sort_keys=True)
    assert "sources" in g["error_budget"] and "sources" not in t["error_budget"]
    # the table: the typed-in design's, plus one line per derived row saying where it came from
    source_lines = [line for line in out["graded_text"].splitlines() if "ISO 1328-1:2013 grade" in line]
    assert len(source_lines) == 8
    assert "Pitch Line Eccen of gear 4 (output): ISO 1328-1:2013 grade 6: F_rT 23 um" in source_lines
    kept = "\n".join(line for line in out["graded_text"].splitlines() if line not in source_lines)
    assert kept == out["typed_text"].rstrip("\n")


def test_grade_and_tir_both_given_is_refused_naming_both_keys(tmp_path):
    text = re.sub(r"(\[gears\.output\][^\n]*\n)", r"\1accuracy_grade = 6\n", ROBOT.read_text())
    path = tmp_path / "both.toml"
    path.write_text(text)
    with pytest.raises((DesignError, DesignErrors)) as exc:
        load_design(path)
    message = str(exc.value)
    assert "errors.output.pitch_line_eccentricity_tir_in" in message and "gears.output.accuracy_grade" in message


def test_a_graded_gear_still_needs_its_bearing_eccentricity(tmp_path):
    graded_path, _ = robot_files(tmp_path)
    text = graded_path.read_text().replace("[errors.output]\nbearing_eccentricity_tir_in = 0.0005\n", "[errors.output]\n")
    graded_path.write_text(text)
    with pytest.raises((DesignError, DesignErrors)) as exc:
        load_design(graded_path)
    assert "errors.output.bearing_eccentricity_tir" in str(exc.value)


@pytest.mark.slow
def test_gear_command_writes_the_contracts_accuracy_block(tmp_path):
    out = tmp_path / "g"
    assert main(["gear", "--teeth", "30", "--module", "4", "--face-width-mm", "40", "--accuracy-grade", "8",
                 "--out", str(out), "--no-stl"]) == 0
    data = json.loads((out / "gear_30.json").read_text())
    # d 120 mm, m_n 4, b 40, grade 8: the medium gear of tests/core/test_accuracy.py
    # f_pT 6.72 * 2 sqrt(2) = 19.007 -> 19; F_pT 21.065 * 2.828 = 59.58 -> 60; F_rT 53.62 -> 54;
    # F_aT hypot(5.72, 7.2) * 2.828 = 26.009 -> 26; F_bT hypot(6.7613, 7.6129) * 2.828 = 28.80 -> 29
    assert {k: data["accuracy"][k] for k in ("standard", "grade", "single_pitch_um", "cumulative_pitch_um",
                                             "profile_total_um", "helix_total_um", "runout_um")} == {
        "standard": "ISO 1328-1:2013", "grade": 8, "single_pitch_um": 19.0, "cumulative_pitch_um": 60.0,
        "profile_total_um": 26.0, "helix_total_um": 29.0, "runout_um": 54.0}


def test_gear_data_has_no_accuracy_block_without_a_grade():
    from geargen.design.gear import gear_from_table
    from geargen.model.gear_data import gear_data
    from geargen.profile.tooth import tooth_profile

    table = {"teeth": 30, "module_mm": 4, "pressure_angle_deg": 20, "face_width_mm": 40}
    plain = gear_from_table(table)
    graded = gear_from_table({**table, "accuracy_grade": 8})
    assert "accuracy" not in gear_data(plain, tooth_profile(plain))
    assert gear_data(graded, tooth_profile(graded))["accuracy"]["single_pitch_um"] == 19.0


def test_a_drive_with_typed_tirs_states_the_grade_its_budget_holds():
    """The build's gear data (and drawing) of a gear with TIRs and no grade names the coarsest
    grade within its budget. Robot joint output (d 88.9 mm; pitch-line TIR 0.0012 in = 30.48 um,
    tooth-to-tooth 0.0005 in = 12.7 um): grade 6 F_rT 23 um, f_pT 7.5 um (table above) fit; grade 7
    F_rT = 22.807 x sqrt2 = 32.25 -> 32 um > 30.48 does not: grade 6. cluster_small (d 16.669 mm;
    pitch-line 0.0016 in = 40.64 um, tooth-to-tooth 12.7 um): f_pT at grade 5 = 0.016669 + 0.3175
    + 5 = 5.334 um, grade 7 x2 = 10.67 -> 11 um fits, grade 8 x2.828 = 15.09 -> 15 um does not;
    F_rT grade 7 = 18.881 x sqrt2 = 26.70 -> 27 um fits: grade 7, set by the tooth-to-tooth TIR."""
    from geargen.model.gear_data import gear_data
    from geargen.profile.tooth import tooth_profile

    design = load_design(ROBOT)
    for name, grade in (("output", 6), ("cluster_small", 7)):
        spec = design.gear(name)
        data = gear_data(spec, tooth_profile(spec, warn=False), errors=gear_errors(design, name))
        assert data["accuracy"]["grade"] == grade, name
        assert "budget" in data["accuracy"]["grade_source"]
    spec = design.gear("output")
    assert "accuracy" not in gear_data(spec, tooth_profile(spec, warn=False))  # no budget given: no grade made up
