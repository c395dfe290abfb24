"""The design-file reference (docs/design-files.md) is the schema written out, and unknown keys
get a "did you mean" (issue 11).

The document is regenerated and compared with the committed file, so it cannot drift from what
``load_design`` reads; every Field of every section module is looked up in it independently of
the generator's own list of tables; the examples in it are checked against the schema.
"""

import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from geargen.cli import main
from geargen.design import reference
from geargen.design.assembly import SECTIONS, design_from_dict, load_design
from geargen.design.checks import CHECKS_FIELDS
from geargen.design.export import EXPORT_FIELDS
from geargen.design.gear import GEAR_FIELDS, gear_from_table
from geargen.design.layout import layout_fields
from geargen.design.parts import hardware_fields
from geargen.design.schema import DesignErrors, close_keys, read_table, typo_distance
from geargen.design.stiffness import (BEAM_FIELDS, BEAM_QUANTITIES, COMPONENT_FIELDS, COMPONENT_QUANTITIES,
                                      ENGAGEMENT_FIELDS, FLEXURE_FIELDS, FLEXURE_QUANTITIES, MODULI,
                                      PRELOAD_FIELDS, PRELOAD_QUANTITIES, SPRING_FIELDS, SPRING_QUANTITIES,
                                      STIFFNESS_FIELDS, preload_spec_from_table)
from geargen.design.synthesis import ERROR_FIELDS, ERROR_KINDS, MONTE_CARLO_FIELDS, SYNTHESIS_FIELDS
from geargen.design.validate import DRIVE_FIELDS, TOP_FIELDS, key_schema
from geargen.errors import DesignError

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "design-files.md"
ROBOT = ROOT / "assemblies" / "robot_joint.toml"
REGENERATE = "regenerate it: python -m geargen.design.reference > docs/design-files.md"

#: heading in the document -> every key list of the section modules documented under it
SCHEMA = {
    "Top-level keys": TOP_FIELDS,
    "[drive]": DRIVE_FIELDS,
    "[gears.NAME] and [gear_defaults]": GEAR_FIELDS,
    "[synthesis]": SYNTHESIS_FIELDS,
    "[errors.GEAR]": ERROR_FIELDS,
    "[monte_carlo]": MONTE_CARLO_FIELDS,
    "[checks]": CHECKS_FIELDS + [key_schema({}, ("checks", "centre_distance_mm"))],  # read by checks itself
    "[stiffness]": STIFFNESS_FIELDS + MODULI,
    "[stiffness.components.NAME]": COMPONENT_FIELDS + COMPONENT_QUANTITIES,
    "[preload]": PRELOAD_FIELDS + PRELOAD_QUANTITIES,
    "[flexures]": FLEXURE_FIELDS + FLEXURE_QUANTITIES,
    "[springs]": SPRING_FIELDS + SPRING_QUANTITIES,
    "[beam_pinion]": BEAM_FIELDS + BEAM_QUANTITIES,
    "[engagement]": ENGAGEMENT_FIELDS,
    "[layout]": layout_fields(),
    "[parts] of a dual pinion on a preload carriage": hardware_fields("dual_pinion"),
    "[parts] of a dual pinion with a beam-spring pinion": hardware_fields("beam_pinion"),
    "[parts] of a split pinion": hardware_fields("split_pinion"),
    "[export]": EXPORT_FIELDS,
}


def _sections(text: str) -> dict[str, str]:
    parts = re.split(r"^### (.+)$", text, flags=re.MULTILINE)
    return dict(zip(parts[1::2], parts[2::2]))


def _row(section: str, name: str, unit: bool) -> list[str]:
    key = f"`{name}_<unit>`" if unit else f"`{name}`"
    rows = [line for line in section.splitlines() if line.startswith(f"| {key} |")]
    assert len(rows) == 1, f"{key}: {len(rows)} rows"
    return [cell.strip() for cell in rows[0].strip("|").split(" | ")]


# ------------------------------------------------------------------ the document is the schema

def test_committed_reference_is_what_the_schema_generates():
    assert DOC.read_text() == reference.design_files_markdown(), f"docs/design-files.md is stale: {REGENERATE}"


def test_the_module_command_writes_the_reference():
    out = subprocess.run([sys.executable, "-m", "geargen.design.reference"], capture_output=True, text=True,
                         check=True, cwd=ROOT).stdout
    assert out == DOC.read_text()


def test_every_field_of_every_section_is_in_the_reference_with_its_meaning():
    sections = _sections(DOC.read_text())
    assert set(SCHEMA) <= set(sections)
    for heading, fields in SCHEMA.items():
        for schema in fields:
            assert schema.help, f"{heading} {schema.name} has no help"
            unit = not hasattr(schema, "kind") or schema.kind in ("length", "angle")
            cells = _row(sections[heading], schema.name, unit)
            assert cells[-1] == schema.help.replace("|", "\\|")
    # ... and the reference lists no key the schema does not have
    for heading, fields in SCHEMA.items():
        key_rows = [line for line in sections[heading].splitlines()
                    if line.startswith("| `") and len(re.split(r"(?<!\\) \| ", line)) == 5]
        documented = [re.match(r"\| `([a-zA-Z0-9_]+?)(?:_<unit>)?` \|", line).group(1) for line in key_rows]
        assert set(documented) == {f.name for f in fields}, heading


def test_every_top_level_section_is_documented():
    assert reference.documented_sections() == set(SECTIONS)


def test_the_error_fields_keep_their_order():
    assert tuple(f.name for f in ERROR_FIELDS) == ERROR_KINDS


@pytest.mark.parametrize("heading, name, unit, range_, default", [
    # module in (0.01, 200] mm; diametral pitch the same range as 25.4 / module: [0.127, 2540)
    ("[gears.NAME] and [gear_defaults]", "teeth", False, "[4, 2000]", "required"),
    ("[gears.NAME] and [gear_defaults]", "module", True, "(0.01, 200] mm", ""),
    ("[gears.NAME] and [gear_defaults]", "diametral_pitch_per_in", False, f"[{25.4 / 200:g}, {25.4 / 0.01:g})", ""),
    ("[gears.NAME] and [gear_defaults]", "pressure_angle", True, "[10, 35] deg", "required"),
    ("[gears.NAME] and [gear_defaults]", "helix_angle", True, "[0, 45] deg", "0 deg"),
    ("[preload]", "line_of_action_angle", True, "(-60, 60) deg", "0 deg"),
    # a key that sets no bound of its own on a side has the plausible one of its kind (schema.PLAUSIBLE):
    # a torque at most 1e11 N·mm, a positive one at least 1e-6; a length at most 10 m; an angle a turn
    ("[preload]", "max_output_torque", True, "[1e-06, 1e+11] N·mm", "required"),
    ("[preload]", "preload", True, "[0, 1e+11] N·mm", ""),
    ("[flexures]", "poisson_ratio", False, "[0, 0.5)", "0.29"),
    ("[flexures]", "elastic_modulus", True, "[1e-06, 1e+07] MPa", "207 GPa"),
    ("[springs]", "shear_modulus", True, "[1e-06, 1e+07] MPa", "79.3 GPa"),
    # 0.5 rad is 28.6479 deg; 1e-9 rad is 5.72958e-08 deg
    ("[export]", "stl_angular_tolerance", True, "[5.72958e-08, 360] deg", "0.5 rad"),
    ("[export]", "stl_chordal_tolerance", True, "[1e-06, 10000] mm", "0.005 mm"),
    ("[parts] of a dual pinion on a preload carriage", "bearing_clearance", True, "[0, 10000] mm", "0.5 mm"),
    ("[errors.GEAR]", "tooth_to_tooth_tir", True, "[0, 10000] mm", "required"),
    ("[layout]", "upstream_stages", False, "", "[]"),
    ("[checks]", "require_backlash", False, "", "true"),
])
def test_ranges_and_defaults_in_the_reference(heading, name, unit, range_, default):
    cells = _row(_sections(DOC.read_text())[heading], name, unit)
    assert (cells[2], cells[3]) == (range_, default)


def test_unit_columns_list_the_suffixes_a_key_accepts():
    sections = _sections(DOC.read_text())
    assert _row(sections["[gears.NAME] and [gear_defaults]"], "module", True)[1] == "length: _mm"
    assert _row(sections["[gears.NAME] and [gear_defaults]"], "face_width", True)[1] == "length: _mm _in _um _m"
    assert _row(sections["[preload]"], "max_output_torque", True)[1] == "torque: _Nmm _Nm _in_lbf _ft_lbf"
    assert _row(sections["[drive]"], "type", False)[1] == 'one of "type1", "type2"'


def test_each_example_is_made_of_keys_the_schema_knows():
    for table in reference.TABLES:
        text = reference.example_text(table.example) if table.example else table.example_text
        data = tomllib.loads(text)
        context = {**table.context, **data}

        def walk(node, path):
            for key, value in node.items():
                if isinstance(value, dict):
                    walk(value, path + (key,))
                else:
                    assert key_schema(context, path + (key,)) is not None, f"{table.heading}: {path + (key,)}"

        walk(data, ())
        assert data, table.heading


def test_examples_are_cut_where_the_next_table_begins(tmp_path):
    (tmp_path / "d.toml").write_text('name = "d"\n\n[a]\nx = 1   # one\n        # continued\n\n'
                                     '# about [b]\n[b]\ny = 2\n')
    assert reference.example_text(reference.Example("d.toml", ("a",)), tmp_path) == "[a]\nx = 1   # one\n        # continued\n"
    assert reference.example_text(reference.Example("d.toml", ("", "b")), tmp_path) == 'name = "d"\n\n[b]\ny = 2\n'


# ------------------------------------------------------------------ did you mean

def test_typo_distance_prices_neighbouring_keys_and_case():
    assert typo_distance("mn", "mm") == 0.5  # n is next to m on the keyboard
    assert typo_distance("mn", "m") == 1.0
    assert typo_distance("mn", "in") == 1.0
    assert typo_distance("nm", "Nm") == 0.25
    assert typo_distance("widht", "width") == 1.0  # two neighbours swapped
    assert typo_distance("face", "face") == 0.0


@pytest.mark.parametrize("written, expected", [
    ("face_width_mn", ["face_width_mm"]),  # not face_width_m, one deletion away too
    ("face_widht_mm", ["face_width_mm"]),
    ("facewidth_in", ["face_width_in"]),
    ("pressure_angle_degrees", ["pressure_angle_deg"]),
    ("teeths", ["teeth"]),
    ("thinning_mm", ["thinning_circumferential_mm", "thinning_normal_mm"]),
    ("face_width", ["face_width_mm", "face_width_in", "face_width_um"]),  # the unit left out
    ("diametral_pitch", ["diametral_pitch_per_in"]),
    ("colour", []),
])
def test_close_keys_of_a_gear_table(written, expected):
    assert close_keys(written, [k for f in GEAR_FIELDS for k in f.keys()]) == expected


def test_a_misspelt_gear_key_names_the_key_and_the_closest_one():
    table = {"teeth": 20, "module_mm": 1.0, "pressure_angle_deg": 20, "face_width_mn": 5}
    with pytest.raises(DesignError) as info:
        gear_from_table(table, where="gears.pinion")
    assert info.value.field == "gears.pinion.face_width_mn"
    assert info.value.problem == "unknown key; did you mean face_width_mm?"
    assert "face_width_mm" in info.value.allowed  # the whole list is still given


def test_every_unknown_key_of_a_table_is_reported():
    with pytest.raises(DesignErrors) as info:
        read_table({"stl_chordal_tolerence_mm": 0.01, "render_veiw": [-60, 30]}, EXPORT_FIELDS, "export")
    assert [(e.field, e.problem) for e in info.value.errors] == [
        ("export.stl_chordal_tolerence_mm", "unknown key; did you mean stl_chordal_tolerance_mm?"),
        ("export.render_veiw", "unknown key; did you mean render_view?")]


def test_a_key_nothing_resembles_gets_no_suggestion():
    with pytest.raises(DesignError) as info:
        read_table({"colour": "red"}, EXPORT_FIELDS, "export")
    assert info.value.problem == "unknown key"


def test_quantity_suffixes_are_suggested_in_their_case():
    with pytest.raises(DesignError) as info:
        preload_spec_from_table({"max_output_torque_nm": 5})
    assert (info.value.field, info.value.problem) == ("preload.max_output_torque_nm",
                                                      "unknown key; did you mean max_output_torque_Nm?")


def test_checks_suggests_the_centre_distance_keys_it_reads_itself():
    data = {"gears": {"p": {"teeth": 20, "module_mm": 1, "pressure_angle_deg": 20, "face_width_mm": 5},
                      "w": {"teeth": 30, "module_mm": 1, "pressure_angle_deg": 20, "face_width_mm": 5}},
            "checks": {"meshes": [["p", "w"]], "centre_distanse_mm": 25.1}}
    with pytest.raises(DesignError) as info:
        design_from_dict(data, validate=True)
    assert (info.value.field, info.value.problem) == ("checks.centre_distanse_mm",
                                                      "unknown key; did you mean centre_distance_mm?")


def test_misspellings_across_a_file_are_reported_together(tmp_path):
    text = ROBOT.read_text()
    for old, new in (("[monte_carlo]", "[monte_carl]"), ("wire_diameter_in = 0.045", "wire_diamter_in = 0.045"),
                     ("max_output_torque_Nm = 5.0", "max_output_torque_nm = 5.0"),
                     ("diametral_pitch_per_in = 32\npressure_angle_deg = 20",
                      "diametral_pitch_per_in = 32\npressure_angle_dg = 20")):
        assert old in text
        text = text.replace(old, new, 1)
    path = tmp_path / "typos.toml"
    path.write_text(text)
    with pytest.raises(DesignErrors) as info:
        load_design(path)
    problems = {e.field: e.problem for e in info.value.errors}
    assert problems["monte_carl"] == "unknown key or section; did you mean monte_carlo?"
    assert problems["springs.wire_diamter_in"] == "unknown key; did you mean wire_diameter_in?"
    assert problems["preload.max_output_torque_nm"] == "unknown key; did you mean max_output_torque_Nm?"
    # a [gear_defaults] key is named once, where the file has it, not once per gear
    assert problems["gear_defaults.pressure_angle_dg"] == "unknown key; did you mean pressure_angle_deg?"
    assert not any(f.startswith("gears.") and f.endswith("pressure_angle_dg") for f in problems)


def test_the_command_line_shows_the_suggestion(tmp_path, capsys):
    path = tmp_path / "typo.toml"
    path.write_text(ROBOT.read_text().replace("[flexures]", "[flexure]", 1))
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "flexure: unknown key or section; did you mean flexures?" in err
    assert "Traceback" not in err
