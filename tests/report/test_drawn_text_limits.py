"""The designer's texts a drawing prints (part number, revision, material, heat treatment) have a
length limit measured on the drawing (geargen.design.gear.DRAWN_TEXT_MAX): the lines each may take
in its cell (geargen.report.drawing.DRAWN_TEXT_LINES) times the letters of the widest character it
may hold that one line takes. A longer value is refused where it is read, naming the key and the
limit (exit 2, no traceback); the longest is drawn inside its cells.

Before: a 200-letter material raised ValueError in the drawing ("the gear data block needs more
than 104 mm"): exit 4, an internal error for user input; a long part number was cut off silently.
"""

import math

import pytest
from matplotlib.font_manager import FontProperties, findfont
from matplotlib.ft2font import FT2Font

from geargen.cli import main
from geargen.design.gear import DRAWN_TEXT_MAX, gear_from_table
from geargen.design.schema import DRAWN_TEXT_EXTRA, DRAWN_TEXT_RANGES, drawn_character
from geargen.model.gear_data import gear_data
from geargen.profile.tooth import tooth_profile
from geargen.report.drawing import (BLANK_BLOCK, BLANK_COLUMNS_MM, DRAWN_TEXT_LINES, FONT, MIN_FONT_PT, PAD_MM,
                                    WRAP_FILL, Sheet, draw_gear, title_cell_width, title_cells, write_drawing)
from tests.drawing_support import cell_texts, table_rows

WIDEST = "—"  # "@", "©", "®", "—", "―", "…": one em (3.53 mm at 10 pt), the widest the drawn characters have (measured below)

TABLE = {"teeth": 40, "module_mm": 1.0, "pressure_angle_deg": 20, "face_width_mm": 12.0, "bore_diameter_mm": 20.0,
         "bore_fit": "H7", "accuracy_grade": 6, "hardness_HV": 650, "flank_roughness_Ra_um": 0.4}


def _widths():
    sheet = Sheet()
    return sheet, (lambda text: sheet.width_mm(text, MIN_FONT_PT))


def test_no_drawn_character_is_wider_than_the_widest_letter_and_the_font_has_each():
    _, width = _widths()
    charmap = FT2Font(findfont(FontProperties(family=FONT))).get_charmap()
    allowed = [chr(c) for lo, hi in DRAWN_TEXT_RANGES for c in range(lo, hi + 1) if drawn_character(chr(c))]
    allowed += list(DRAWN_TEXT_EXTRA)
    assert len(allowed) > 400  # Latin-1, Latin Extended-A, Greek, punctuation
    assert all(ord(c) in charmap for c in allowed), [c for c in allowed if ord(c) not in charmap]
    # ten of a kind measured: the font's own advance widths, as the sheet lays text out
    w = width(WIDEST * 10)
    wider = [c for c in allowed if width(c * 10) > w]
    assert not wider, wider
    assert not drawn_character("\n") and not drawn_character("Œ")


@pytest.mark.parametrize("key", ["material", "heat_treatment", "part_number", "revision"])
def test_each_limit_is_the_lines_of_widest_letters_its_cell_holds(key):
    _, width = _widths()
    cell_mm = (BLANK_COLUMNS_MM[2] - 2 * PAD_MM if key in ("material", "heat_treatment")
               else title_cell_width(title_cells()[key])) * WRAP_FILL
    per_line = max(n for n in range(1, 80) if width(WIDEST * n) <= cell_mm)
    assert DRAWN_TEXT_MAX[key] == DRAWN_TEXT_LINES[key] * per_line
    assert width(WIDEST * (per_line + 1)) > cell_mm  # one more letter takes another line


def _spaced(n: int) -> str:
    """``n`` characters in words of 7 widest letters: breaking at words wastes most of each line."""
    return " ".join(WIDEST * 7 for _ in range(n // 8 + 1))[:n]


@pytest.mark.parametrize("make", [lambda n: WIDEST * n, _spaced], ids=["one word", "words"])
def test_the_longest_values_are_drawn_inside_their_cells(make, tmp_path):
    longest = {key: make(n) for key, n in DRAWN_TEXT_MAX.items()}
    spec = gear_from_table({**TABLE, **longest}, "gears.wheel", "wheel")
    profile = tooth_profile(spec, warn=False)
    data = gear_data(spec, profile)
    data["accuracy"] = {"standard": "ISO 1328-1:2013", "grade": 6, "single_pitch_um": 5.5, "cumulative_pitch_um": 16.0,
                        "profile_total_um": 6.5, "helix_total_um": 9.0, "runout_um": 13.0,
                        "grade_source": "the coarsest grade within the design's error budget"}
    data["datum_tolerances"]["face_axial_runout_um"] = 0.2 * (2 * profile.root_radius / spec.face_width) * 9.0
    sheet = draw_gear(data, profile, "gear wheel from test", "design.toml", "0.0")
    from geargen.report.drawing import parse_cell_gid
    outside = []
    for text, box, gid in sheet.text_boxes():  # as laid out by the font's metrics, sheet mm
        cell = parse_cell_gid(gid)
        if cell is None:
            continue
        slack = 0.09  # half the thinnest rule (0.18 mm) drawn on the cell's side
        if not (box[0] >= cell[0] - slack and box[2] <= cell[2] + slack and box[1] >= cell[1] - slack
                and box[3] <= cell[3] + slack):
            outside.append((text, cell))
    assert not outside, outside
    files = write_drawing(data, profile, tmp_path, spec.name, "gear wheel from test", "design.toml", "0.0")
    cells = cell_texts(files["svg"])
    blank = table_rows(cells, BLANK_BLOCK, join="")
    # every letter printed: the lines of the cell joined give the value back (spaces at a break kept)
    for key, row in (("material", "Material"), ("heat_treatment", "Heat treatment")):
        assert blank[row].replace(" ", "") == longest[key].replace(" ", "")
    title = {t[0]: "".join(t[1:]) for c, t in cells.items() if c[1] < BLANK_BLOCK[1] + 40 and c[0] > BLANK_BLOCK[2]}
    assert title["Part number"].replace(" ", "") == longest["part_number"].replace(" ", "")
    assert title["Revision"].replace(" ", "") == longest["revision"].replace(" ", "")


def _run(capsys, *argv):
    code = main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert "Traceback" not in err and "internal error" not in err, err
    return code, err


@pytest.mark.parametrize("key", ["material", "heat_treatment", "part_number", "revision"])
def test_a_longer_value_is_refused_naming_the_key_and_its_limit(key, tmp_path, capsys):
    most = DRAWN_TEXT_MAX[key]
    design = tmp_path / "gear.toml"
    body = "\n".join(f"{k} = {v!r}" if isinstance(v, str) else f"{k} = {v}" for k, v in TABLE.items())
    design.write_text(f"[gear]\n{body}\n{key} = \"{WIDEST * (most + 1)}\"\n")
    code, err = _run(capsys, "gear", design, "--out", tmp_path / "a")
    assert code == 2 and f"gear.{key}: " in err and f"{most + 1} characters long" in err
    assert f"at most {most} characters" in err
    flag = "--" + key.replace("_", "-")
    code, err = _run(capsys, "gear", "--teeth", 21, "--module", 1, "--face-width", 5, flag, WIDEST * (most + 1),
                     "--out", tmp_path / "b")
    assert code == 2 and f"{flag}: " in err and f"at most {most} characters" in err
    code, err = _run(capsys, "gear", "--teeth", 21, "--module", 1, "--face-width", 5, flag, "a\nb", "--out", tmp_path / "c")
    assert code == 2 and f"{flag}: " in err and "'\\n' (character 2)" in err
    assert not any((tmp_path / d).exists() for d in "abc")


@pytest.mark.slow
def test_geargen_gear_draws_the_longest_values(tmp_path, capsys):
    args = []
    for key, most in DRAWN_TEXT_MAX.items():
        args += ["--" + key.replace("_", "-"), WIDEST * most]
    code, err = _run(capsys, "gear", "--teeth", 21, "--module", 1, "--face-width", 5, "--bore", 6, *args,
                     "--out", tmp_path / "g")
    assert code == 0, err
    svg = next((tmp_path / "g").rglob("*-drawing.svg"))
    blank = table_rows(cell_texts(svg), BLANK_BLOCK, join="")
    assert blank["Material"] == WIDEST * DRAWN_TEXT_MAX["material"]
    assert math.isfinite(len(blank["Heat treatment"])) and blank["Heat treatment"] == WIDEST * DRAWN_TEXT_MAX["heat_treatment"]
