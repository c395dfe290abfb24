"""Names that become file names (issue 31): a gear's, a design's, a stage's.

Every name that reaches a path (``--name``, ``[gear] name``, a gear table's key, a gear's ``name``
label, the top-level ``name``, a stage's key) is checked on load like the top-level name: ASCII
letters, digits, "_", "-", "." and no more characters than the drawing holds. A name pointing out
of the output folder (``../``, an absolute path), a line break or 300 characters is refused, exit
status 2, naming the key; and the folder the output would go into, with its parents up to the test's
own folder, is listed before and after: nothing is written anywhere. Behind the names,
:func:`geargen.outputs.confined` refuses any write outside the folder being written.

A gear's ``name`` key labels it; its table's key stays its identity everywhere in the model.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import pytest

from geargen.cli import main
from geargen.design.assembly import load_design
from geargen.design.schema import GEAR_NAME_MAX, NAME_MAX
from geargen.errors import DesignError, OutputRefused
from geargen.outputs import OutputFolder, atomic_path

ROOT = Path(__file__).resolve().parents[2]
SPLIT_INCH = ROOT / "assemblies" / "split_pinion_inch.toml"
METRIC = ROOT / "assemblies" / "metric_dual_pinion.toml"


def run(capsys, *argv) -> tuple[int, str]:
    code = main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert "Traceback" not in err and "internal error" not in err, err
    return code, err


def listing(folder: Path) -> dict[str, bytes | None]:
    """Every file (with its bytes) and folder under ``folder``."""
    out = {}
    for root, dirs, files in os.walk(folder):
        for d in dirs:
            out[os.path.relpath(os.path.join(root, d), folder) + "/"] = None
        for f in files:
            p = os.path.join(root, f)
            out[os.path.relpath(p, folder)] = Path(p).read_bytes()
    return out


def toml_string(text: str) -> str:
    return json.dumps(text)  # a JSON string is a TOML basic string (escapes \n, \", \\)


def hostile_names(work: Path) -> dict[str, str]:
    return {"dotdot": "../../X", "absolute": str(work / "victim" / "precious"), "newline": "gear\nX",
            "long": "n" * 300}


def rename_gear(text: str, old: str, new: str) -> str:
    """The design text with gear ``old`` renamed ``new`` everywhere: its table, [layout] and the
    stiffness components that name it (the tester's split pinion)."""
    text = text.replace(f"[gears.{old}]", f"[gears.{toml_string(new)}]")
    return text.replace(f'"{old}"', toml_string(new))


def cases(work: Path, name: str) -> list[tuple[str, list[list[str]], str]]:
    """(what, command lines, the field the refusal names) for every way ``name`` reaches a path."""
    out = work / "a" / "b" / "c" / "out"
    designs = work / "designs"
    designs.mkdir(exist_ok=True)
    split = SPLIT_INCH.read_text()

    gear_file = designs / "gear_file.toml"
    gear_file.write_text(f"[gear]\nname = {toml_string(name)}\nteeth = 21\nmodule_mm = 1\npressure_angle_deg = 20\n"
                         "face_width_mm = 5\n")
    keyed = designs / "keyed.toml"  # the tester's: [layout] pinion_compliant and the gear table renamed
    keyed.write_text(rename_gear(split, "pinion_compliant", name))
    labelled = designs / "labelled.toml"
    labelled.write_text(split.replace("[gears.pinion_compliant]", f"[gears.pinion_compliant]\nname = {toml_string(name)}", 1))
    top = designs / "top.toml"
    top.write_text(re.sub(r'^name = "split_pinion_inch"', lambda m: f"name = {toml_string(name)}", split, count=1,
                          flags=re.M))
    staged = designs / "staged.toml"
    staged.write_text(METRIC.read_text().replace("[stages.idler]", f"[stages.{toml_string(name)}]"))
    options = ["--teeth", "21", "--module", "1", "--face-width", "5"]
    return [
        ("--name", [["gear", *options, "--name", name, "--out", out]], "--name"),
        ("[gear] name", [["gear", gear_file, "--out", out]], "gear.name"),
        ("gear table key", [["build", keyed, "--out", out, "--quiet"], ["gear", keyed, "--gear", name, "--out", out],
                            ["stiffness", keyed, "--out", out], ["check", keyed]], "gears."),
        ("gear name label", [["build", labelled, "--out", out, "--quiet"],
                             ["gear", labelled, "--gear", "pinion_compliant", "--out", out]],
         "gears.pinion_compliant.name"),
        ("top-level name", [["build", top, "--out", out, "--quiet"], ["stiffness", top, "--out", out]], "name: "),
        ("stage key", [["build", staged, "--out", out, "--quiet"]], "stages."),
    ]


@pytest.mark.parametrize("which", ["dotdot", "absolute", "newline", "long"])
def test_no_name_that_reaches_a_path_writes_outside_the_output_folder(which, tmp_path, capsys):
    work = tmp_path / "work"
    (work / "victim").mkdir(parents=True)
    (work / "victim" / "precious.json").write_text('{"the user\'s": "data"}\n')
    name = hostile_names(work)[which]
    all_cases = cases(work, name)
    before = listing(work)
    for what, argvs, field in all_cases:
        for argv in argvs:
            code, err = run(capsys, *argv)
            assert code == 2, (what, argv[0], err)
            assert field in err and ("not a valid name" in err or "characters long" in err), (what, argv[0], err)
            if which == "long":
                assert f"at most {GEAR_NAME_MAX if field != 'name: ' and 'stages' not in field else NAME_MAX} " \
                       "characters" in err, (what, err)
    assert listing(work) == before  # nothing written, nothing changed, the victim's file as it was


def test_the_tester_split_pinion_no_longer_overwrites_a_users_file(tmp_path, capsys):
    # before: exit 0, and victim/precious.json held the pinion's gear data
    victim = tmp_path / "victim"
    victim.mkdir()
    (victim / "precious.json").write_text("precious\n")
    design = tmp_path / "designs" / "split.toml"
    design.parent.mkdir()
    design.write_text(rename_gear(SPLIT_INCH.read_text(), "pinion_compliant", "../../../../victim/precious"))
    code, err = run(capsys, "build", design, "--out", tmp_path / "designs" / "exports" / "x" / "out", "--quiet")
    assert code == 2 and 'gears.../../../../victim/precious: \'../../../../victim/precious\' holds \'/\'' in err
    assert (victim / "precious.json").read_text() == "precious\n"
    assert not (tmp_path / "designs" / "exports").exists()


def test_a_name_of_140_characters_is_refused_at_load_with_the_allowed_length(tmp_path, capsys):
    # before: the build ran and crashed on the drawing (exit 4, "the gear data block needs more than 235 mm")
    design = tmp_path / "split.toml"
    design.write_text(rename_gear(SPLIT_INCH.read_text(), "pinion_compliant", "p" * 140))
    code, err = run(capsys, "build", design, "--out", tmp_path / "out", "--quiet")
    assert code == 2 and f"is 140 characters long (allowed: at most {GEAR_NAME_MAX} characters" in err
    code, err = run(capsys, "gear", "--teeth", "21", "--module", "1", "--face-width", "5", "--name", "p" * 140,
                    "--out", tmp_path / "g")
    assert code == 2 and "--name: " in err and f"at most {GEAR_NAME_MAX} characters" in err
    assert not (tmp_path / "out").exists() and not (tmp_path / "g").exists()


def test_a_newline_in_name_is_refused(tmp_path, capsys):
    code, err = run(capsys, "gear", "--teeth", "21", "--module", "1", "--face-width", "5", "--name", "a\nb",
                    "--out", tmp_path / "g")
    assert code == 2 and "--name: 'a\\nb' holds '\\n' (character 2): not a valid name" in err
    assert not (tmp_path / "g").exists()


@pytest.mark.parametrize("name", ["manifest", "Assembly"])
def test_a_name_of_a_file_geargen_writes_itself_is_refused(name, tmp_path, capsys):
    # a gear called manifest would write manifest.json over the folder's own manifest
    code, err = run(capsys, "gear", "--teeth", "21", "--module", "1", "--face-width", "5", "--name", name,
                    "--out", tmp_path / "g")
    assert code == 2 and f"{name!r} is the name of a file geargen writes beside it" in err


def test_the_drawing_holds_the_longest_gear_name():
    """A gear with two mates (a split pinion's output: the most any placed drive gives a gear) whose
    three names are GEAR_NAME_MAX of the widest letter, and a 100-character design file path: the
    gear data block holds it at its own row spacing without the chordal tooth's rows, two letters more
    overflow that (the limit is the drawing's); and as drawn (every row, closer together when full:
    geargen.report.drawing.fit_data_block) the block holds it with the chordal tooth's rows."""
    from geargen.core.allowance import ThicknessAllowance
    from geargen.design.gear import GearSpec
    from geargen.model.gear_data import gear_data
    from geargen.profile.tooth import tooth_profile
    from geargen.report.drawing import draw_data_block, fit_data_block, Sheet, data_rows

    spec = GearSpec(teeth=21, module=1.0, pressure_angle=0.3490658503988659, face_width=10.0, helix_angle=0.3,
                    accuracy_grade=6)  # every row the block can have: helical, graded, an allowance
    profile = tooth_profile(spec, warn=False)
    allowance = ThicknessAllowance(-0.02, -0.045, "entered (--thickness-allowance)", "--thickness-allowance")
    path = "/" + "d" * 94 + ".toml"

    def fits(length: int, chordal: bool = False, draw=draw_data_block) -> bool:
        name = "W" * length  # "W" is the widest of a name's letters in DejaVu Sans (2025 of 2048 units an em)
        data = gear_data(spec, profile, allowance)
        if not chordal:
            del data["chordal_tooth"]
        data["name"] = name
        data["mating_gears"] = [{"name": name, "teeth": 90, "centre_distance": 55.5,
                                 "centre_distance_tolerance": [-0.01, 0.01]}] * 2
        source = f"gear {name} from {path} [gears.{name}]"  # geargen gear FILE --gear NAME: the longest source
        try:
            draw(Sheet(), data_rows(data, "2:1 (section 1:1, detail 10:1)", "0.0.0", source))
            return True
        except ValueError:
            return False

    assert fits(GEAR_NAME_MAX)
    assert not fits(GEAR_NAME_MAX + 2)
    assert fits(GEAR_NAME_MAX, chordal=True, draw=fit_data_block)


# ------------------------------------------------------------------ the name only labels

def test_a_name_key_labels_the_gear_and_its_table_key_stays_its_identity(tmp_path, capsys):
    # before: exit 2, "no placed shaft carrying gears.pinion_stiff": the model looked the gear up by its label
    design = tmp_path / "split_pinion_inch.toml"
    design.write_text(SPLIT_INCH.read_text().replace("[gears.pinion_stiff]", '[gears.pinion_stiff]\nname = "stiff_pinion"', 1))
    loaded = load_design(design)
    assert loaded.gears["pinion_stiff"].name == "pinion_stiff"
    assert loaded.labels == {"pinion_stiff": "stiff_pinion"} and loaded.label("pinion_stiff") == "stiff_pinion"
    assert loaded.label("output") == "output"
    code, err = run(capsys, "stiffness", design, "--no-plots")
    assert code == 0, err


@pytest.mark.parametrize("edit, field, problem", [
    ('[gears.pinion_stiff]\nname = "output"', "gears.pinion_stiff.name", "'output' is also the name of gears.output"),
    ('[gears.pinion_stiff]\nname = "Output"', "gears.pinion_stiff.name", "'Output' is also the name of gears.output"),
])
def test_a_label_another_gear_has_is_refused(edit, field, problem, tmp_path):
    design = tmp_path / "split.toml"
    design.write_text(SPLIT_INCH.read_text().replace("[gears.pinion_stiff]", edit, 1))
    with pytest.raises(DesignError) as info:
        load_design(design)
    assert f"{field}: {problem}" in str(info.value)


def test_gear_keys_alike_but_for_case_are_refused(tmp_path):
    design = tmp_path / "split.toml"
    design.write_text(SPLIT_INCH.read_text() + "\n[gears.OUTPUT]\nteeth = 90\nface_width_in = 0.75\n")
    with pytest.raises(DesignError) as info:
        load_design(design)
    assert "gears.OUTPUT: differs from gears.output only in case" in str(info.value)


def test_a_gear_file_is_named_by_name_option_then_its_name_key_then_its_file_name(tmp_path, capsys):
    table = "teeth = 21\nmodule_mm = 1\npressure_angle_deg = 20\nface_width_mm = 5\n"
    named = tmp_path / "file_stem.toml"
    named.write_text(f'[gear]\nname = "from_key"\n{table}')
    unnamed = tmp_path / "bad stem.toml"  # a file name no gear may have: said, with what would do
    unnamed.write_text(f"[gear]\n{table}")
    from geargen.commands.gear import add_arguments, spec_from_args
    import argparse
    parser = argparse.ArgumentParser()
    add_arguments(parser)
    assert spec_from_args(parser.parse_args([str(named)]))[0].name == "from_key"
    assert spec_from_args(parser.parse_args([str(named), "--name", "opt"]))[0].name == "opt"
    code, err = run(capsys, "gear", unnamed, "--out", tmp_path / "g")
    assert code == 2 and "gear.name: missing, and the file's name 'bad stem' is not a valid gear name" in err


def test_name_with_gear_is_refused_not_ignored(capsys, tmp_path):
    code, err = run(capsys, "gear", SPLIT_INCH, "--gear", "output", "--name", "x", "--out", tmp_path / "g")
    assert code == 2 and "--name: the gear of --gear is named by its table [gears.output]" in err


# ------------------------------------------------------------------ the one check behind every writer

def test_a_write_outside_the_folder_being_written_is_refused(tmp_path):
    folder = OutputFolder(tmp_path / "out", "geargen test", "source")
    work = folder.prepare()
    before = listing(tmp_path)
    outside = tmp_path / "outside"
    outside.mkdir()
    (work / "link").symlink_to(outside)
    try:
        for path in (work / ".." / ".." / "X.json", tmp_path / "abs.json", work / "link" / "y.json"):
            with pytest.raises(OutputRefused, match="outside the output folder being written"):
                with atomic_path(path) as tmp:
                    tmp.write_text("x")
        with atomic_path(work / "inside.json") as tmp:  # inside: written
            tmp.write_text("x")
        with atomic_path(tmp_path / "user.json", user_file=True) as tmp:  # a file the user named (--json)
            tmp.write_text("x")
    finally:
        folder.discard()
    after = listing(tmp_path)
    assert set(after) - set(before) == {"outside/", "user.json"}  # the folder the test made, the user's file
    with atomic_path(tmp_path / "later.json") as tmp:  # no folder being written: no confinement
        tmp.write_text("x")
