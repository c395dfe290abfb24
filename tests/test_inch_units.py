"""An inch design speaks inches (issue 27, "the design's units everywhere").

The shipped inch design ``split_pinion_inch`` (and the inch dual-pinion starter, for ``synth``) goes
through ``check``, ``synth``, ``stiffness``, ``train``, ``build`` and ``gear``; every human-readable
output (stdout, stderr, the build's report, warnings and drawings' text, the strings inside its
JSON) is searched for a metric unit the design file did not itself use. Which units a file "used"
is read here from its keys' suffixes, independently of geargen's own choice
(:func:`geargen.units.text_units`).

One build only (about 12 s): every assertion on the build's files reads that one output.
"""

from __future__ import annotations

import html
import json
import os
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
INCH_DESIGN = ROOT / "assemblies" / "split_pinion_inch.toml"

#: metric unit text -> the key suffixes that make it the file's own (a file writing a modulus in
#: GPa uses the SI stress unit; a torsional stiffness in N·m/rad uses N·m)
METRIC_UNITS = {
    "mm": ("_mm",),
    "µm": ("_um",),
    "N·m": ("_Nm", "_Nm_per_rad", "_Nm_per_deg", "_Nm_per_arcmin"),
    "N·mm": ("_Nmm", "_Nmm_per_rad"),
    "N/mm": ("_N_per_mm",),
    "N/µm": ("_N_per_um",),
    "MPa": ("_MPa", "_GPa", "_kPa", "_Pa"),
    "N": ("_N",),
}
#: how each unit may be spelled in text (the longer spellings first so "N/mm" is not read as "N")
_SPELLINGS = [("N·mm", r"N·mm|N mm|Nmm"), ("N·m", r"N·m|N m|Nm"), ("N/mm", r"N/mm"), ("N/µm", r"N/µm|N/um"),
              ("MPa", r"MPa"), ("µm", r"µm|um"), ("mm", r"mm"),
              # a bare N is a force only after a number ("277.7 N"); "N" is also the teeth symbol
              ("N", r"(?<=\d )N")]
_TOKEN = re.compile("|".join(f"(?P<u{i}>(?<![A-Za-z_·/])(?:{rx})(?![A-Za-z_0-9·/]))"
                             for i, (_, rx) in enumerate(_SPELLINGS)))
#: text that names a unit without being a length, torque, force, stiffness or stress of the design:
#: the oil's viscosity (its only key is viscosity_mm2_per_s: cSt is the unit oil is sold in)
_NOT_A_FINDING = re.compile(r"mm\^?2/s|mm²/s|viscosity_mm2_per_s")


def _keys(table):
    for key, value in table.items():
        yield key
        if isinstance(value, dict):
            yield from _keys(value)


def units_used_by(design: Path) -> set[str]:
    """The metric units the design file's keys are written in."""
    keys = list(_keys(tomllib.loads(design.read_text())))
    return {unit for unit, suffixes in METRIC_UNITS.items() if any(k.endswith(s) for k in keys for s in suffixes)}


def findings(text: str, allowed: set[str], where: str) -> list[str]:
    """Every line of ``text`` naming a metric unit not in ``allowed``."""
    out = []
    for number, line in enumerate(text.splitlines(), 1):
        cleaned = _NOT_A_FINDING.sub("", line)
        for m in _TOKEN.finditer(cleaned):
            unit = _SPELLINGS[int(m.lastgroup[1:])][0]
            if unit not in allowed:
                out.append(f"{where}:{number}: {unit}: {line.strip()[:160]}")
                break
    return out


def test_the_finder_finds_what_it_should():
    # the issue's own examples are found; inch text and the file's own units are not
    assert findings("involute starts at radius 5.96749 mm", set(), "t")
    assert findings("a path unloads at -17.26 / +109.7 N·m", set(), "t")
    assert findings("mesh_stiff 2.3899e+05 N/mm at r=53.7 mm", {"mm"}, "t")  # N/mm is not mm
    assert findings("pinion_stiff 277.7 N: deflects", set(), "t")
    assert not findings("No. of Teeth        N        16", set(), "t")
    assert not findings("13.56 in·lbf; 0.5 in; 3709 in·lbf/rad; 85 lbf/in", set(), "t")
    assert not findings("R_a 0.4 um", {"µm"}, "t")
    assert not findings("nu_40 100 mm^2/s", set(), "t")


def _geargen(*args, cwd: Path) -> str:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-m", "geargen.cli", *map(str, args)], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode in (0, 2), f"geargen {' '.join(map(str, args))}: exit {done.returncode}\n{done.stderr}"
    return done.stdout + "\n" + done.stderr


def _json_strings(value):
    if isinstance(value, str):
        yield value
    elif isinstance(value, dict):
        for k, v in value.items():
            # "units" and "length_unit" declare what a block's numbers are in (an STL has no unit
            # field of its own: geargen writes it in mm and says so); they report no quantity
            if k not in ("units", "length_unit"):
                yield from _json_strings(v)
    elif isinstance(value, list):
        for v in value:
            yield from _json_strings(v)


def _svg_text(path: Path) -> str:
    """The text elements of a drawing, one a line (matplotlib writes each cell's text as one)."""
    return "\n".join(html.unescape(t) for t in re.findall(r"<text[^>]*>([^<]*)</text>", path.read_text()))


@pytest.fixture(scope="module")
def inch_build(tmp_path_factory) -> tuple[Path, str]:
    """The one build of the inch design: its folder, and what ``geargen build`` printed."""
    tmp = tmp_path_factory.mktemp("inch_build")
    build = tmp / "build"
    return build, _geargen("build", "--quiet", INCH_DESIGN, "--out", build, cwd=tmp)


@pytest.fixture(scope="module")
def outputs(tmp_path_factory, inch_build) -> dict[str, tuple[str, set[str]]]:
    """Every human-readable output: where -> (text, the metric units its design file used)."""
    tmp = tmp_path_factory.mktemp("inch")
    design_units = units_used_by(INCH_DESIGN)
    out: dict[str, tuple[str, set[str]]] = {}
    for command, extra in (("check", ()), ("stiffness", ("--out", tmp / "stiffness")),
                           ("train", ("--out", tmp / "train"))):
        out[f"{command} split_pinion_inch"] = (_geargen(command, INCH_DESIGN, *extra, cwd=tmp), design_units)
    # synth places a dual-pinion drive: the inch starter has the [synthesis] section
    starter = tmp / "starter_in.toml"
    _geargen("new", "dual_pinion", "--units", "in", starter, cwd=tmp)
    starter_units = units_used_by(starter)
    for command, extra in (("synth", ()), ("check", ()), ("stiffness", ("--out", tmp / "starter_stiffness"))):
        out[f"{command} starter_in"] = (_geargen(command, starter, *extra, cwd=tmp), starter_units)
    # an error in an inch file: its range in inches
    bad = tmp / "bad.toml"
    bad.write_text(INCH_DESIGN.read_text().replace("face_width_in = 0.5", "face_width_in = 50"))
    out["check of a bad inch file"] = (_geargen("check", bad, cwd=tmp), design_units)
    # a standalone gear from inch options (no file: no metric unit is the user's)
    out["gear --diametral-pitch"] = (_geargen("gear", "--teeth", 18, "--diametral-pitch", 20, "--face-width-in", 0.5,
                                              "--bore-in", 0.5, "--no-stl", "--out", tmp / "gear", cwd=tmp), set())
    for svg in sorted((tmp / "gear").glob("*.svg")):
        out[f"gear drawing/{svg.name}"] = (_svg_text(svg), set())
    build, printed = inch_build
    out["build split_pinion_inch"] = (printed, design_units)
    for path in sorted(build.rglob("*")):
        where = str(path.relative_to(build.parent))
        if path.suffix in (".md", ".txt", ".html"):
            out[where] = (path.read_text(), design_units)
        elif path.suffix == ".svg" and path.parent.name == "drawings":
            out[where] = (_svg_text(path), design_units)
        elif path.suffix == ".json":
            out[where] = ("\n".join(_json_strings(json.loads(path.read_text()))), design_units)
        elif path.name == "data.js":  # the review page's data: one JSON object assigned to a global
            data = json.loads(path.read_text().split("=", 1)[1].strip().rstrip(";"))
            out[where] = ("\n".join(_json_strings(data)), design_units)
    return out


def _report(outputs, select) -> list[str]:
    found = []
    for where, (text, allowed) in outputs.items():
        if select(where):
            found += findings(text, allowed, where)
    return found


def test_the_inch_design_uses_units_of_its_own():
    # the premise: split_pinion_inch writes torques in in·lbf and lengths in inches, so neither mm
    # nor N·m nor a force in N is the file's; its stiffnesses are N/µm and its moduli GPa
    used = units_used_by(INCH_DESIGN)
    assert {"mm", "N·m", "N", "N/mm"}.isdisjoint(used)
    assert {"N/µm", "MPa"} <= used


@pytest.mark.parametrize("command", ["check ", "synth ", "stiffness ", "train ", "gear ", "check of a bad inch file"])
def test_command_text_has_no_metric_unit_the_file_did_not_use(outputs, command):
    found = _report(outputs, lambda where: where.startswith(command) and "/" not in where)
    assert not found, "\n".join(found)


def test_build_output_has_no_metric_unit_the_file_did_not_use(outputs):
    found = _report(outputs, lambda where: where.startswith("build") and not where.endswith(".svg"))
    assert not found, "\n".join(found)


def test_drawing_text_has_no_metric_unit_the_file_did_not_use(outputs):
    found = _report(outputs, lambda where: where.endswith(".svg"))
    assert not found, "\n".join(found)


def test_stiffness_torques_come_back_in_the_files_unit(outputs):
    # [preload] max_output_torque_in_lbf = 120: the stiffness summary prints 120 in·lbf back
    text = outputs["stiffness split_pinion_inch"][0]
    assert re.search(r"maximum drive torque\s+120 in·lbf", text), text


def test_the_manifests_check_lengths_come_in_inches_too(inch_build):
    # the checks block keeps its mm keys (length_unit "mm") and adds each length as <key>_in; the
    # file's own numbers come back: [layout] centre_distance_in = 2.7, circumferential_backlash_min_in =
    # 0.0015 and _max_in = 0.003 for each pinion's mesh with the output
    checks = json.loads((inch_build[0] / "manifest.json").read_text())["checks"]
    assert checks["length_unit"] == "mm" and checks["design_length_unit"] == "in"
    output_meshes = [m for m in checks["meshes"] if "output" in (m["gear1"], m["gear2"])]
    assert output_meshes
    for m in output_meshes:
        # 1e-9 in: the file's decimal inches round-trip through mm (x 25.4 and back) in floating point
        assert m["centre_distance_in"] == pytest.approx(2.7, abs=1e-9)
        assert (m["design_min_in"], m["design_max_in"]) == (pytest.approx(0.0015, abs=1e-9), pytest.approx(0.003, abs=1e-9))
    converted = 0
    for record in checks["meshes"] + checks["tolerances"] + checks["bevel_meshes"]:
        for key, value in record.items():
            if key.endswith("_in") and isinstance(value, float):
                # one inch is 25.4 mm exactly; 1e-12 relative: one floating-point division
                assert value == pytest.approx(record[key[:-3]] / 25.4, rel=1e-12), key
                converted += 1
    # the meshes' backlash range, centre distance and plane and the tolerance study's backlashes at least
    assert converted >= 3 * len(checks["meshes"])


def _inch_design_with(replace: dict[str, str]):
    from geargen.design.assembly import design_from_dict
    text = INCH_DESIGN.read_text()
    for old, new in replace.items():
        assert old in text
        text = text.replace(old, new)
    return design_from_dict(tomllib.loads(text))


def test_a_length_in_the_other_unit_is_warned_about_when_it_reads_like_an_inch():
    # the case: a 1/16 in pinion gap written with _mm builds a 0.0625 mm gap
    design = _inch_design_with({"pinion_axial_gap_in = 0.0625": "pinion_axial_gap_mm = 0.0625"})
    (warning,) = design.unit_warnings
    # 0.0625 mm / 25.4 = 0.0024606 in, printed to 4 digits
    assert warning.startswith("layout.pinion_axial_gap_mm = 0.0625 is read in mm (0.002461 in)")
    assert "write pinion_axial_gap_in" in warning
    # a face width of 0.5 "mm" beside inch-sized gears
    design = _inch_design_with({"teeth = 18\nface_width_in = 0.5": "teeth = 18\nface_width_mm = 0.5"})
    assert [w.split(" = ")[0] for w in design.unit_warnings] == ["gears.pinion_stiff.face_width_mm"]


def test_a_plausible_length_in_the_other_unit_is_not_warned_about():
    # 12.7 mm is the 1/2 in bore: the same size as the file's inches, read as written
    design = _inch_design_with({"bore_diameter_in = 0.5 ": "bore_diameter_mm = 12.7 "})
    assert design.unit_warnings == ()
    assert design.gears["pinion_stiff"].hub.bore_diameter == pytest.approx(12.7)


@pytest.mark.parametrize("design", sorted((ROOT / "assemblies").glob("*.toml")), ids=lambda p: p.stem)
def test_no_shipped_design_is_warned_about(design):
    # the robot joint writes its STL tolerances in mm beside inch lengths: small by nature, not warned
    from geargen.design.assembly import load_design
    assert load_design(design).unit_warnings == ()


def test_an_inch_gears_range_error_names_its_own_option_in_inches(tmp_path, capsys):
    from geargen.cli import main
    assert main(["gear", "--teeth", "18", "--diametral-pitch", "20", "--face-width-in", "0.5", "--thinning", "0.06",
                 "--no-stl", "--out", str(tmp_path / "gear")]) == 2
    err = capsys.readouterr().err
    # a quarter of the circular pitch: pi / (4 x 20) = 0.0392699 in; the option is --thinning (was
    # named --bevel-thinning, the bevel kind's option)
    assert "--thinning: 0.06 in is out of range (allowed: [0, 0.0392699] in" in err


def test_hardware_that_cannot_be_made_is_refused_in_inches(tmp_path, capsys):
    # a clamp collar narrower than the inner shaft it clamps: the body library's message, in inches
    from geargen.cli import main
    bad = tmp_path / "collar.toml"
    bad.write_text(INCH_DESIGN.read_text().replace("collar_outer_diameter_in = 0.875", "collar_outer_diameter_in = 0.00001"))
    assert main(["check", str(bad)]) == 2
    err = capsys.readouterr().err
    # the collar's bore is the inner shaft's 1/4 in (the compliant pinion's bore_diameter_in)
    assert "the hardware cannot be made: bore 0.25 in must lie in [0, 1e-05 in)" in err
    assert findings(err, set(), "stderr") == []


def test_the_robot_joints_undercut_note_is_in_inches():
    # the "involute starts at radius 5.96749 mm" on the 16-tooth 32 DP input: 5.96749 / 25.4
    import warnings
    from geargen.design.assembly import load_design
    from geargen.profile.tooth import UndercutWarning, tooth_profile
    spec = load_design(ROOT / "assemblies" / "robot_joint.toml").gears["input"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UndercutWarning)
        (note,) = tooth_profile(spec).warnings
    assert "the usable involute starts at radius 0.234941 in instead" in note


def test_train_gives_an_inch_designs_masses_and_inertias_in_lb_and_lb_in2(tmp_path):
    """``geargen train`` of the inch design: each part's mass in lb and its inertias in lb·in^2, equal
    to the JSON's kg and kg·m² over the exact definitions 1 lb = 0.45359237 kg, 1 in = 0.0254 m."""
    text = _geargen("train", INCH_DESIGN, "--no-plots", "--json", tmp_path / "train.json", "--out", tmp_path / "t",
                    cwd=tmp_path)
    data = json.loads((tmp_path / "train.json").read_text())
    lb, lb_in2 = 0.45359237, 0.45359237 * 0.0254 ** 2
    assert "mass lb" in text and "lb·in^2" in text and "kg" not in text
    rows = {line.split()[0]: line.split() for line in text.splitlines() if line.startswith("  ")}
    for part in data["parts"]:
        row = rows[part["name"]]
        # 4 significant digits printed: half a unit of the 4th digit, relative
        assert float(row[1]) == pytest.approx(part["mass_kg"] / lb, rel=5e-4)
        assert float(row[2]) == pytest.approx(part["inertia_own_axis_kg_m2"] / lb_in2, rel=5e-4)
        assert float(row[4]) == pytest.approx(part["reflected_to_motor_kg_m2"] / lb_in2, rel=5e-4)
    total = re.search(r"inertia at the motor (\S+) lb·in\^2", text)
    assert float(total.group(1)) == pytest.approx(data["totals"]["inertia_at_motor_kg_m2"] / lb_in2, rel=5e-4)


def test_a_metric_designs_masses_stay_in_kg():
    from geargen.units import TextUnits
    assert TextUnits(length="mm").text("mass", 1.5) == "1.5 kg"
    assert TextUnits(length="mm").text("inertia", 2e-4) == "0.0002 kg·m^2"
    # 1 kg = 2.2046 lb; 1 kg·m^2 = 1 / (0.45359237 x 0.0254^2) = 3417.2 lb·in^2
    assert TextUnits(length="in").text("mass", 1.0) == "2.205 lb"
    assert TextUnits(length="in").text("inertia", 1.0) == "3417 lb·in^2"


def test_the_robot_joints_family_sheets_give_the_diametral_pitch(built_assemblies):
    # the inch robot joint's bevel and cluster sheets printed their module in mm
    # ("Module at the heel m_e 0.79375 mm", "Large gear: teeth, module 48, 0.79375 mm") beside inch
    # lengths; an inch sheet names the diametral pitch instead (32 1/in: 25.4 / 0.79375)
    drawings = built_assemblies["robot_joint"] / "drawings"
    for name in ("bevel_gear", "bevel_pinion", "cluster"):
        text = _svg_text(drawings / f"{name}-drawing.svg")
        assert not re.search(r"(?<![A-Za-z_])mm(?![A-Za-z_])", text), name
        assert "1/in" in text and "diametral pitch" in text, name
