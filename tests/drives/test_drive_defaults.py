"""Default hardware per drive kind (issue 26): a file may leave out its whole [parts] table or any
key of it; the kind's rules (``geargen/drives/<kind>/defaults.py``) size what is missing, and the
drive so resolved passes the analytic parts check (geargen.checks.hardware.parts_check, what
``geargen check`` reports as parts_overlap, parts_interpenetrating, contact_missing).

For every shipped design of each kind: the whole table left out, then each key in turn. Where a
shipped value follows the rule the resolved value equals it; where the shipped file chose
otherwise the rule's value and why the file differs are stated here (:data:`WHOLE`,
:data:`SINGLE`). Values are compared exactly: the rules round to 0.5 mm (1/32 in) or copy a
catalogue, so the same inputs give the same numbers to the last bit.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from geargen.checks.hardware import parts_check
from geargen.commands.check import check_design
from geargen.design.assembly import design_from_dict, load_design
from geargen.design.catalogue import INCH_BEARINGS, METRIC_SERIES, standard_bores
from geargen.design.checks import checks_settings
from geargen.design.parts import parts_settings
from geargen.drives.keys import KEYS, kind_of
from geargen.drives.resolver import resolve
from geargen.errors import DesignError

ROOT = Path(__file__).resolve().parents[2]
DESIGNS = ("robot_joint", "metric_dual_pinion", "planetary_dual_pinion", "c_axis", "split_pinion",
           "split_pinion_inch", "axial_preload", "rack_drive")

#: bearings on a bore no standard bearing has (16 and 8.5 mm): the file must give them, and leaving
#: one out is refused naming it
GIVEN = {"split_pinion": ("bearing_outer_diameter_mm", "bearing_width_mm", "compliant_bearing_outer_diameter_mm",
                          "compliant_bearing_width_mm"),
         "rack_drive": ("path_bearing_outer_diameter_mm", "path_bearing_width_mm")}

# why the shipped files differ from the rules
_PAPER_MOTOR = "the shipped motor is the designer's (a small servo), the rule's the smallest NEMA frame for the load"
_THIN_OUTPUT = "the shipped output bearing is a thin-section 1 x 1.5 x 0.25 in, the rule's the R series (R16)"
_C_AXIS_MOTOR = "the shipped 110 mm servo with its gearhead is the designer's; the rule's NEMA 34 covers 2.78 N·m"
_STAGED_MOTOR = "the shipped motor is a small servo; the rule's NEMA 14 covers the load through loop and stages"
_SERIES_18 = "the rule's series 18 bearing of the 5 mm input shaft (685, 5 x 11 x 5); the file's is a 695"
_LINK = "the rule's link encloses the gears at any cluster angle with 3 mm walls; the file's is tighter"

#: the whole [parts] left out (but :data:`GIVEN`): file key -> (the rule's value, why the file differs)
WHOLE = {
    "robot_joint": {
        "bearing_clearance_in": (0.03125, "the rule's 0.5 mm rounded to 1/32 in; the file's 0.02 in"),
        "bevel_face_width_in": (0.125, "the rule's face under a third of the cone distance, rounded down"),
        "input_shaft_to_bevel_in": (0.5625, "the rule clears the NEMA 17 the rule picks (the file's motor is smaller)"),
        "motor_body_diameter_in": (1.6875, _PAPER_MOTOR), "motor_body_length_in": (1.59375, _PAPER_MOTOR),
        "motor_flange_in": (1.6875, _PAPER_MOTOR), "motor_flange_thickness_in": (0.15625, _PAPER_MOTOR),
        "motor_shaft_diameter_in": (0.1969, _PAPER_MOTOR), "motor_shaft_length_in": (0.125, "3 mm rounded up"),
        "output_bearing_outer_diameter_in": (2.0, _THIN_OUTPUT), "output_bearing_width_in": (0.5, _THIN_OUTPUT),
        "carriage_width_in": (1.0625, "the rule's four plates around the input; the file's is tighter"),
        "link_radius_in": (3.125, "the rule encloses every gear at any cluster angle; the file's link is tighter"),
        "link_wall_in": (0.125, "3 mm rounded to 1/32 in"), "link_floor_in": (0.1875, "a wall plus 1 mm"),
        "link_top_clearance_in": (0.125, "2.5 mm rounded to 1/32 in"),
        "spring_y_offset_in": (0.4375, "the rule's springs side by side; the file's stand wider apart"),
    },
    "metric_dual_pinion": {
        "motor_body_diameter_mm": (35.5, _STAGED_MOTOR), "motor_body_length_mm": (34.0, _STAGED_MOTOR),
        "motor_flange_mm": (35.5, _STAGED_MOTOR),
        "input_bearing_outer_diameter_mm": (11.0, _SERIES_18), "input_bearing_width_mm": (5.0, _SERIES_18),
        "carriage_plate_thickness_mm": (3.0, "2.5 mesh-1 modules, at least 3 mm; the file's plates are 4 mm"),
        "carriage_width_mm": (32.0, "the input and two 3 mm plates either side; the file's carriage is 30 mm"),
        "link_radius_mm": (124.0, _LINK), "link_wall_mm": (3.0, _LINK), "link_floor_mm": (4.0, _LINK),
        "link_top_clearance_mm": (2.5, _LINK),
        "spring_y_offset_mm": (12.0, "the springs side by side; the file's stand wider apart"),
    },
    "planetary_dual_pinion": {},  # as the metric one, and the stage bearing (below)
    "c_axis": {
        "locknut_width_mm": (7.5, "a quarter of the shaft; the file's KM6 locknut is 7 mm"),
        "stop_lug_length_mm": (34.0, "a stop, a clearance and a lug's width; the file rounds up to 35"),
        "gearhead_diameter_mm": (86.0, _C_AXIS_MOTOR), "gearhead_length_mm": (80.0, _C_AXIS_MOTOR),
        "motor_body_diameter_mm": (86.0, _C_AXIS_MOTOR), "motor_body_length_mm": (80.0, _C_AXIS_MOTOR),
        "motor_flange_mm": (86.0, _C_AXIS_MOTOR), "motor_flange_thickness_mm": (7.0, _C_AXIS_MOTOR),
        "drive_column_width_mm": (93.0, "1.5 bearing diameters; the file's 14 mm around the bearing"),
    },
    "split_pinion": {
        "hollow_shaft_length_mm": (83.0, "the inner shaft's 10 diameters; the file's twists over 80 mm (9.4)"),
        "collar_outer_diameter_mm": (28.0, "1.75 hollow-shaft diameters; the file's collar is 30 mm"),
        "collar_width_mm": (13.0, "1.5 inner-shaft diameters; the file's collar is 10 mm wide"),
    },
    "split_pinion_inch": {
        "bearing_spacing_in": (1.28125, "three overhangs; the file spaces its pair 1.5 in apart"),
        "collar_slot_in": (0.0625, "a 1/16 in saw cut; the file's slot is 0.05 in"),
        "output_bearing_outer_diameter_in": (2.0, _THIN_OUTPUT), "output_bearing_width_in": (0.5, _THIN_OUTPUT),
    },
    "axial_preload": {
        "spring_wire_diameter_mm": (3.5, "the thinnest stock wire with 6 coils at 20 N/mm; the file's 3.4 mm"),
        "spring_installed_length_mm": (47.0, "solid and two wires; the file installs its spring at 45 mm"),
        "motor_stub_length_mm": (18.0, "1.5 shaft diameters; the file's stub is 20 mm"),
    },
    "rack_drive": {},
}
WHOLE["planetary_dual_pinion"] = {**WHOLE["metric_dual_pinion"], "stage_bearing_outer_diameter_mm": (
    11.0, "no stage shaft: the series 18 bearing of the motor shaft's 5 mm (685); the file names a 686")}

#: one key left out: file key -> (the value the drive gets, why it differs from the file's); a key the
#: file gives with a complete table otherwise takes the schema's default where it has one
_SCHEMA = "an optional key of an otherwise complete table takes the schema's default"
SINGLE = {
    "robot_joint": {**{k: WHOLE["robot_joint"][k] for k in (
        "bevel_face_width_in", "input_shaft_to_bevel_in", "motor_flange_in", "motor_shaft_diameter_in",
        "motor_shaft_length_in", "output_bearing_outer_diameter_in", "output_bearing_width_in", "carriage_width_in",
        "link_radius_in", "link_wall_in", "link_floor_in", "link_top_clearance_in", "spring_y_offset_in")},
        "bearing_clearance_in": (0.5 / 25.4, _SCHEMA + " (0.5 mm)"),
        "motor_body_length_in": (1.59375, _PAPER_MOTOR)},
    "c_axis": {**{k: WHOLE["c_axis"][k] for k in ("locknut_width_mm", "stop_lug_length_mm", "motor_flange_mm",
                                                  "motor_body_length_mm", "drive_column_width_mm")},
               "bearing_clearance_mm": (0.5, _SCHEMA),
               "gearhead_diameter_mm": (115.0, "as wide as the file's 115 mm motor flange"),
               "gearhead_length_mm": (180.0, "as long as the file's 180 mm motor body"),
               "motor_body_diameter_mm": (115.0, "as wide as the file's 115 mm flange"),
               "motor_flange_thickness_mm": (9.5, "0.08 of the file's 115 mm flange")},
    "split_pinion": {**{k: WHOLE["split_pinion"][k] for k in WHOLE["split_pinion"]},
                     "bearing_spacing_mm": (None, _SCHEMA + " (the pair side by side)")},
    "split_pinion_inch": {**{k: WHOLE["split_pinion_inch"][k] for k in ("collar_slot_in", "output_bearing_outer_diameter_in",
                                                                        "output_bearing_width_in")},
                          "bearing_clearance_in": (0.5 / 25.4, _SCHEMA + " (0.5 mm)"),
                          "bearing_spacing_in": (None, _SCHEMA + " (the pair side by side)"),
                          "housing_margin_in": (5.0 / 25.4, _SCHEMA + " (5 mm)")},
    "axial_preload": {"spring_wire_diameter_mm": WHOLE["axial_preload"]["spring_wire_diameter_mm"],
                      "motor_stub_length_mm": WHOLE["axial_preload"]["motor_stub_length_mm"],
                      "spring_installed_length_mm": (42.0, "solid and two wires of the file's 3.4 mm wire (8.3 coils)")},
    "rack_drive": {},
}
SINGLE["metric_dual_pinion"] = {**{k: WHOLE["metric_dual_pinion"][k] for k in WHOLE["metric_dual_pinion"]
                                   if k not in ("motor_body_diameter_mm", "carriage_width_mm")},
                                "motor_body_length_mm": (34.0, _STAGED_MOTOR),
                                "carriage_width_mm": (36.0, "the input and the file's 4 mm plates, two either side")}
SINGLE["planetary_dual_pinion"] = {**SINGLE["metric_dual_pinion"], "stage_bearing_outer_diameter_mm":
                                   WHOLE["planetary_dual_pinion"]["stage_bearing_outer_diameter_mm"]}


def _path(name: str) -> Path:
    return ROOT / "assemblies" / f"{name}.toml"


def _name(key: str) -> str:
    """A [parts] key without its unit suffix."""
    if key.endswith("_per_in"):
        return key
    return key.rsplit("_", 1)[0] if key.endswith(("_mm", "_in")) else key


def _load(data: dict, name: str):
    return design_from_dict(data, path=_path(name), validate=True)


def _with_parts(name: str, keep) -> dict:
    data = tomllib.loads(_path(name).read_text())
    table = {k: v for k, v in data.pop("parts").items() if keep(k)}
    if table:
        data["parts"] = table
    return data


def _compare(name: str, design, differences: dict, only=None) -> None:
    """The resolved [parts] against the shipped file's: equal, or the stated rule's value."""
    shipped_design = load_design(_path(name))
    shipped, got = parts_settings(shipped_design), parts_settings(design)
    scale = shipped_design.mm_per_unit
    for key, value in tomllib.loads(_path(name).read_text())["parts"].items():
        if only is not None and key != only:
            continue
        field = _name(key)
        if key in differences:
            want = differences[key][0]
            if want is None or isinstance(want, str):
                assert got[field] == want, key
            else:  # the rule's value in the file's unit, to the 1e-6 its rounding writes
                assert got[field] / scale == pytest.approx(want, abs=1e-6), key
                assert got[field] != shipped[field], f"{key}: stated as different but equal"
        else:
            assert got[field] == shipped[field], f"{key}: {got[field] / scale} against the file's {value}"


def _parts_ok(design) -> None:
    report = parts_check(resolve(design))
    assert report.ok, report.failures


@pytest.mark.parametrize("name", DESIGNS)
def test_the_whole_table_left_out_is_sized_by_the_rules_and_checks(name):
    data = _with_parts(name, lambda k: k in GIVEN.get(name, ()))
    design = _load(data, name)
    assert {d.key.split(".")[0] for d in design.defaulted} == {"parts"}
    assert all(d.why for d in design.defaulted)  # every value with its rule
    _compare(name, design, WHOLE[name])
    # geargen check on it: the parts check and every other check pass
    result = check_design(design, checks_settings(design), tolerances=False)
    assert result.parts is not None and result.parts.ok, result.parts.failures
    assert result.ok, [f.message for f in result.failures]


@pytest.mark.parametrize("name", DESIGNS)
def test_each_key_left_out_is_sized_and_the_drive_checks(name):
    keys = list(tomllib.loads(_path(name).read_text())["parts"])
    for key in keys:
        if key in GIVEN.get(name, ()):
            continue
        design = _load(_with_parts(name, lambda k: k != key), name)
        _compare(name, design, SINGLE[name], only=key)
        if key in SINGLE[name]:  # a value the file does not have: the drive so resolved must still fit
            _parts_ok(design)


@pytest.mark.parametrize("name, key", [(n, k) for n in GIVEN for k in GIVEN[n]])
def test_a_bearing_of_no_standard_bore_is_refused_naming_its_key(name, key):
    with pytest.raises(DesignError) as err:
        _load(_with_parts(name, lambda k: k != key), name)
    assert err.value.field == f"parts.{key}"
    assert "no standard bearing bore" in err.value.problem
    # the refusal lists the series' bores: 15 and 17 around the files' 16 mm, 8 and 9 around 8.5 mm
    assert standard_bores("mm", "19") in err.value.allowed and "15, 17" in err.value.allowed


@pytest.mark.parametrize("name", DESIGNS)
def test_a_partial_table_of_two_keys_resolves_with_them(name):
    """Two keys of the file (those :data:`GIVEN` besides): the rest defaulted, the two standing."""
    chosen = [k for k in tomllib.loads(_path(name).read_text())["parts"] if k not in GIVEN.get(name, ())][-2:]
    design = _load(_with_parts(name, lambda k: k in chosen or k in GIVEN.get(name, ())), name)
    defaulted = {d.key for d in design.defaulted}
    assert not any(f"parts.{k}" in defaulted for k in chosen)
    shipped = parts_settings(load_design(_path(name)))
    got = parts_settings(design)
    assert all(got[_name(k)] == shipped[_name(k)] for k in chosen)
    _parts_ok(design)


@pytest.mark.parametrize("name", DESIGNS)
def test_a_bad_value_in_a_partial_table_is_refused_naming_it(name):
    keys = [k for k in tomllib.loads(_path(name).read_text())["parts"]
            if k.endswith(("_mm", "_in")) and k not in GIVEN.get(name, ())]
    bad = keys[0]
    data = _with_parts(name, lambda k: k in GIVEN.get(name, ()))
    data["parts"] = {**data.get("parts", {}), bad: -1.0}
    with pytest.raises(DesignError) as err:
        _load(data, name)
    fields = [e.field for e in getattr(err.value, "errors", [err.value])]
    assert f"parts.{bad}" in fields


def test_every_kind_has_its_rules_in_the_reference():
    """Each kind's defaults module states its rules (the reference prints its docstring) and every
    [parts] key of the kind appears in them."""
    reference = (ROOT / "docs/design-files.md").read_text()
    for kind in ("split_pinion", "beam_pinion", "axial_preload", "rack_dual_pinion"):
        keys = KEYS[kind]
        doc = keys.defaults.__doc__
        assert f"### {kind}" in reference and doc.split("\n\n", 1)[1].split("\n")[0] in reference
        for field in keys.PARTS_FIELDS:
            words = field.name.split("_")
            # named, or as a group (`input_bearing_*`, `motor_*`)
            named = [field.name] + ["_".join(words[:n]) + "_*" for n in range(1, len(words))]
            assert any(f"`{n}`" in doc for n in named), (kind, field.name)


def test_the_bearing_tables_are_the_standard_series():
    """The catalogue's series, by their published dimensions: each series' outer diameter grows with
    the bore, and the three the shipped files name are there (6001 12 x 28 x 8, 61905 25 x 42 x 9,
    6206 30 x 62 x 16)."""
    for series in METRIC_SERIES.values():
        assert all(a[0] < b[0] and a[1] < b[1] for a, b in zip(series, series[1:]))
    assert (12, 28, 8, "6001") in METRIC_SERIES["10"]
    assert (25, 42, 9, "61905") in METRIC_SERIES["19"]
    assert (30, 62, 16, "6206") in METRIC_SERIES["02"]
    assert (0.25, 0.625, 0.196, "R4ZZ") in INCH_BEARINGS


def test_the_rack_spring_rule_by_hand():
    """The rack drive's carriage spring, worked by hand: 800 N at 50 N/mm, index 5. 4.5 mm wire: 7.14
    coils (G d / (8 C^3 k) = 79.3e3 x 4.5 / 50e3), solid 41.1 mm, installed 4.5 mm above (the wire),
    rounded to 46 mm: 1045 N closed solid, 8 x 22.5 / (pi 4.5^3) x Wahl 1.3105 = 0.824 MPa/N, 861
    MPa against 0.45 x 2211 / 4.5^0.145 = 799 MPa: too weak. 5 mm wire: 7.93 coils, solid 49.65 mm,
    installed 55 mm, 1067 N, 712 MPa against 788: the shipped spring, exactly."""
    data = _with_parts("rack_drive", lambda k: k in GIVEN["rack_drive"])
    got = {d.key: d.value for d in _load(data, "rack_drive").defaulted}
    assert (got["parts.spring_wire_diameter_mm"], got["parts.spring_mean_diameter_mm"],
            got["parts.spring_installed_length_mm"]) == (5.0, 25.0, 55.0)
    wahl = (4 * 5 - 1) / (4 * 5 - 4) + 0.615 / 5
    assert wahl == pytest.approx(1.3105, abs=1e-4)
    d45, d5 = 4.5, 5.0
    solid45 = d45 * (79.3e3 * d45 / (8 * 125 * 50) + 2)
    assert 8 * 5 * d45 * wahl / (3.141592653589793 * d45 ** 3) * (800 + 50 * (46 - solid45)) > 0.45 * 2211 / d45 ** 0.145
    solid5 = d5 * (79.3e3 * d5 / (8 * 125 * 50) + 2)
    assert 8 * 5 * d5 * wahl / (3.141592653589793 * d5 ** 3) * (800 + 50 * (55 - solid5)) <= 0.45 * 2211 / d5 ** 0.145


def test_the_kind_of_a_file_picks_its_rules():
    """The loader reaches each kind's rules through its keys module: one per kind, none shared."""
    for name in DESIGNS:
        kind = kind_of(tomllib.loads(_path(name).read_text()))
        assert KEYS[kind].defaults.__name__ == f"geargen.drives.{kind}.defaults"
