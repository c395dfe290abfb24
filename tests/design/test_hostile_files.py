"""Design files that are not what a designer writes (issue 31): nested thousands deep, not UTF-8,
with a byte-order mark, with absurd numbers. Each is refused on load, exit status 2, naming the
file or the key and the cause; none reaches the model (exit 4, a traceback) or hangs.

Every check here goes through ``geargen.cli.main`` in-process, as the user runs it; a refused file
stops at the loader, so each takes milliseconds.
"""

from __future__ import annotations

import re
import time
from pathlib import Path

import pytest

from geargen.cli import main
from geargen.design.assembly import load_design
from geargen.design.schema import MAX_FILE_BYTES, MAX_NESTING, PLAUSIBLE

ROOT = Path(__file__).resolve().parents[2]
SHIPPED = sorted((ROOT / "assemblies").glob("*.toml"))
IN = 25.4


def run(capsys, *argv) -> tuple[int, str]:
    code = main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert "Traceback" not in err and "internal error" not in err, err
    return code, err


def write(tmp_path: Path, name: str, content: str | bytes) -> Path:
    path = tmp_path / name
    path.write_bytes(content if isinstance(content, bytes) else content.encode())
    return path


def variant(tmp_path: Path, source: Path, pattern: str, replacement: str) -> Path:
    text, n = re.subn(pattern, replacement, source.read_text(), count=1, flags=re.MULTILINE)
    assert n == 1, f"{pattern!r} not in {source.name}"
    return write(tmp_path, source.name, text)


def test_all_nine_shipped_files_are_covered():
    assert len(SHIPPED) == 9


# ------------------------------------------------------------------ nesting

@pytest.mark.parametrize("source", SHIPPED, ids=lambda p: p.stem)
def test_a_file_nested_5000_deep_is_refused_naming_the_depth(source, tmp_path, capsys):
    # arrays recurse in the TOML reader (Python's stack runs out near 1000 frames); before: exit 4
    deep = source.read_text() + "\njunk = " + "[" * 5000 + "]" * 5000 + "\n"
    path = write(tmp_path, source.name, deep)
    code, err = run(capsys, "check", path)
    assert code == 2
    assert f"{path}: nested deeper than {MAX_NESTING} levels of tables and arrays" in err


@pytest.mark.parametrize("kind, text", [
    ("inline tables", "junk = " + "{a = " * 5000 + "1" + "}" * 5000),
    ("dotted keys", ".".join(["a"] * 5000) + " = 1"),  # nests without the reader recursing
    ("one past the limit", "junk = " + "[" * MAX_NESTING + "]" * MAX_NESTING),  # the file itself is level 1
])
def test_every_way_of_nesting_is_measured(kind, text, tmp_path, capsys):
    path = write(tmp_path, "robot_joint.toml", (ROOT / "assemblies" / "robot_joint.toml").read_text() + "\n" + text)
    code, err = run(capsys, "synth", path)
    assert code == 2 and f"nested deeper than {MAX_NESTING} levels" in err, (kind, err)


def test_a_dotted_key_of_two_million_parts_is_refused_at_once(tmp_path, capsys):
    # the TOML reader's time grows with the square of a dotted key's parts (8000 parts: 1 s), so a 4 MiB
    # file of one would not end: the parts are counted before it reads the file
    path = write(tmp_path, "deep.toml", ".".join(["a"] * 1_900_000) + " = 1\n")
    t0 = time.perf_counter()
    code, err = run(capsys, "check", path)
    assert code == 2 and f"nested deeper than {MAX_NESTING} levels" in err
    assert time.perf_counter() - t0 < 3.0  # 0.1 s measured; generous for a loaded 2-core machine


def test_nesting_at_the_limit_reaches_the_schema(tmp_path, capsys):
    # the file is level 1, so an array of MAX_NESTING - 1 levels is allowed: the schema then names the key
    path = write(tmp_path, "robot_joint.toml", "junk = " + "[" * (MAX_NESTING - 1) + "]" * (MAX_NESTING - 1) + "\n"
                 + (ROOT / "assemblies" / "robot_joint.toml").read_text())
    code, err = run(capsys, "synth", path)
    assert code == 2 and "junk: unknown key or section" in err and "nested" not in err


# ------------------------------------------------------------------ encodings

@pytest.mark.parametrize("source", SHIPPED, ids=lambda p: p.stem)
def test_invalid_utf8_is_refused_naming_the_byte_and_line(source, tmp_path, capsys):
    raw = source.read_bytes()
    at = raw.index(b"#")  # in the first comment: 0xff is never UTF-8
    path = write(tmp_path, source.name, raw[:at + 1] + b"\xff" + raw[at + 1:])
    line = raw[:at].count(b"\n") + 1
    code, err = run(capsys, "check", path)  # before: exit 4 (UnicodeDecodeError)
    assert code == 2
    assert f"{path}: not UTF-8 at byte {at + 1} (line {line}): byte 0xff" in err
    assert "save it as UTF-8" in err


def test_a_byte_order_mark_is_accepted(tmp_path):
    # before: "not valid TOML: Invalid statement (at line 1, column 1)", with no word of the mark
    source = ROOT / "assemblies" / "robot_joint.toml"
    path = write(tmp_path, "robot_joint.toml", b"\xef\xbb\xbf" + source.read_bytes())
    with_mark, plain = load_design(path), load_design(source)
    assert (with_mark.name, with_mark.gears, with_mark.sections) == (plain.name, plain.gears, plain.sections)


def test_an_integer_of_thousands_of_digits_is_refused(tmp_path, capsys):
    # Python converts at most 4300 digits: the reader's ValueError was exit 4
    path = variant(tmp_path, ROOT / "assemblies" / "robot_joint.toml", r"^count = 3", "count = " + "7" * 5000)
    code, err = run(capsys, "synth", path)
    assert code == 2 and f"{path}: holds a number Python cannot read" in err


def test_an_integer_too_big_for_a_float_names_its_key(tmp_path, capsys):
    path = variant(tmp_path, ROOT / "assemblies" / "robot_joint.toml", r"^length_in = 1\.0$", "length_in = 1" + "0" * 400)
    code, err = run(capsys, "synth", path)  # before: OverflowError, exit 4
    assert code == 2 and "flexures.length_in: " in err and "is out of range" in err


def test_a_file_bigger_than_any_design_is_refused_unread(tmp_path, capsys):
    path = write(tmp_path, "big.toml", "# " + "x" * MAX_FILE_BYTES + "\n")
    t0 = time.perf_counter()
    code, err = run(capsys, "check", path)
    assert code == 2 and f"{path}: is {MAX_FILE_BYTES + 3:,} bytes: too big for a design file" in err
    assert time.perf_counter() - t0 < 2.0  # refused from its size: generous for a loaded 2-core machine


def test_a_50_mb_name_is_refused_at_once(tmp_path, capsys):
    # before: load accepted it and the STEP writer ran for more than 400 s; now the file's size (or,
    # below it, the name's length) stops it at load
    source = ROOT / "assemblies" / "robot_joint.toml"
    for length in (50_000_000, 100_000):
        path = variant(tmp_path, source, r'^name = "robot_joint"', f'name = "{"n" * length}"')
        t0 = time.perf_counter()
        code, err = run(capsys, "build", path, "--out", tmp_path / "out")
        assert code == 2 and time.perf_counter() - t0 < 5.0, err  # 5 s: the 50 MB write itself, on a busy machine
        assert "too big for a design file" in err if length > MAX_FILE_BYTES else f"is {length:,} characters long" in err
        assert len(err) < 2000  # the message does not repeat the name
    assert not (tmp_path / "out").exists()


# ------------------------------------------------------------------ absurd numbers

def test_zero_upstream_stiffness_is_refused_before_it_divides(tmp_path, capsys):
    # before: ZeroDivisionError in geargen.model.train (1 / k of the gearhead), exit 4
    path = variant(tmp_path, ROOT / "assemblies" / "dual_motor.toml", r"^upstream_stiffness_Nm_per_arcmin = 6",
                   "upstream_stiffness_Nm_per_arcmin = 0")
    code, err = run(capsys, "train", path, "--no-plots")
    assert code == 2
    # a torsional stiffness above zero is 1e-6 to 1e18 N·mm/rad, 1e-9 to 1e15 N·m/rad, x pi / 10800 per arcmin
    assert "dual_motor.upstream_stiffness_Nm_per_arcmin: 0 is out of range (allowed: [2.90888e-13, 2.90888e+11] " \
           "Nm_per_arcmin)" in err


def test_a_zero_upstream_stiffness_in_the_train_list_is_refused(tmp_path, capsys):
    path = variant(tmp_path, ROOT / "assemblies" / "c_axis.toml", r"^upstream_stiffness_Nm_per_arcmin = \[40\]",
                   "upstream_stiffness_Nm_per_arcmin = [0]")
    code, err = run(capsys, "train", path, "--no-plots")
    assert code == 2 and "train.upstream_stiffness_Nm_per_arcmin[0]: 0 is out of range" in err


# (file, line, replacement, the key as named, the range in the key's unit): 10 m = 1e4 mm = 393.701 in = 1e7 um
ABSURD = [
    ("metric_dual_pinion", r"^length_mm = 25$", "length_mm = 9.9e307", "flexures.length_mm", "[1e-06, 10000] mm"),
    ("metric_dual_pinion", r"^pitch_line_eccentricity_tir_um = 15", "pitch_line_eccentricity_tir_um = 1e300",
     "errors.input.pitch_line_eccentricity_tir_um", "[0, 1e+07] um"),
    ("metric_dual_pinion", r"^carriage_width_mm = 30", "carriage_width_mm = 1e300", "parts.carriage_width_mm",
     "[1e-06, 10000] mm"),
    ("c_axis", r"^input_bearing_width_mm = 16", "input_bearing_width_mm = 1e12", "parts.input_bearing_width_mm",
     "[1e-06, 10000] mm"),
    ("robot_joint", r"^length_in = 1\.0$", "length_in = 9.9e307", "flexures.length_in", "[3.93701e-08, 393.701] in"),
]


@pytest.mark.parametrize("name, pattern, replacement, key, allowed", ABSURD, ids=[a[3] for a in ABSURD])
def test_an_absurd_number_is_refused_naming_its_key_and_range(name, pattern, replacement, key, allowed, tmp_path,
                                                               capsys):
    # before: each crashed (exit 4: NaN in the mesh check, inf in the hardware) or the build wrote nonsense
    path = variant(tmp_path, ROOT / "assemblies" / f"{name}.toml", pattern, replacement)
    for command in ("synth", "check", "stiffness", "build"):
        argv = [command, path] + (["--out", tmp_path / command] if command in ("stiffness", "build") else [])
        code, err = run(capsys, *argv)
        assert code == 2 and f"{key}: " in err and f"(allowed: {allowed})" in err, (command, err)
    assert not any((tmp_path / c).exists() for c in ("stiffness", "build"))


def test_the_plausible_length_is_ten_metres_and_a_positive_one_at_least_a_nanometre():
    assert PLAUSIBLE["length"] == (1e-6, 1e4)  # mm


def test_the_largest_plausible_values_load(tmp_path):
    # the bounds are inclusive: 10 m itself is a length the loader takes (here a flexure blade's width)
    path = variant(tmp_path, ROOT / "assemblies" / "metric_dual_pinion.toml", r"^width_mm = 12$", "width_mm = 10000")
    assert load_design(path).sections["flexures"]["width_mm"] == 10000


def test_an_unknown_key_of_100000_characters_is_named_cut_and_at_once(tmp_path, capsys):
    # before: the message repeated all 100,000 characters
    path = variant(tmp_path, ROOT / "assemblies" / "robot_joint.toml", r"^count = 3", "k" * 100_000 + " = 3")
    t0 = time.perf_counter()
    code, err = run(capsys, "synth", path)
    assert code == 2 and "flexures.kkkk" in err and "(100,009 characters)" in err  # "flexures." + the key
    assert len(err) < 3000 and time.perf_counter() - t0 < 3.0  # 0.05 s measured; generous for a loaded machine
