"""geargen's vector writer (geargen.report.vector) through the drawing sheet: one record, two encodings.

- every character the sheets print (±, °, µ, ², Greek, ⌀, ↗, —) comes back out of the PDF through
  pdftotext (poppler, an independent reader) and out of the SVG's text;
- a text's width is the font file's advance widths read independently here (FreeType through
  matplotlib's ft2font, unhinted), its box the font's ascent and descent;
- the PDF page is the A3 sheet, rasterised by pdftoppm its hatching lies inside the hatched polygon;
- two writes give the same bytes.
"""

import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from geargen.report.drawing import MM_PER_PT, SHEET_MM, Sheet, write_figure

SYMBOLS = "z ± 0.0050° µm d² α_n β ρ_fP F_αT ⌀19.6435 ↗ δ_a Σ φ — ’"


def _sheet() -> Sheet:
    sheet = Sheet()
    sheet.text(30.0, 250.0, SYMBOLS, 10.0)
    sheet.text(30.0, 230.0, "Gear data (ISO 1340)", 10.0, weight="bold")
    sheet.hatch([(100.0, 100.0), (140.0, 100.0), (140.0, 120.0), (100.0, 120.0)])
    return sheet


def test_every_printed_character_comes_back_from_the_pdf_and_the_svg(tmp_path, poppler):
    files = write_figure(_sheet(), tmp_path, "v")
    text = subprocess.run([poppler["pdftotext"], "-raw", str(files["pdf"]), "-"], capture_output=True, text=True,
                          check=True).stdout
    assert SYMBOLS in text and "Gear data (ISO 1340)" in text, text
    svg = ET.parse(files["svg"]).getroot()
    # the user unit the point (what the cell tests map Chromium's boxes through)
    assert [float(v) for v in svg.get("viewBox").split()] == pytest.approx([0, 0, *(v / MM_PER_PT for v in SHEET_MM)],
                                                                          abs=5e-4)  # 3 decimals written
    assert [t.text for t in svg.iter("{http://www.w3.org/2000/svg}text")] == [SYMBOLS, "Gear data (ISO 1340)"]


def test_widths_are_the_fonts_advances_and_boxes_its_ascent_and_descent():
    from matplotlib.ft2font import FT2Font, LoadFlags

    from geargen.report.vector import _font_path
    sheet = _sheet()
    for t, weight in zip(sheet.texts[:2], ("normal", "bold")):
        font = FT2Font(str(_font_path(weight)))
        font.set_size(10.0, 72)  # 10 pt at 72 dpi: 1 px = 1 pt
        advances = [font.load_char(ord(c), flags=LoadFlags.NO_HINTING).linearHoriAdvance / 65536 for c in t.text]
        width_mm = sum(advances) * MM_PER_PT
        # 1e-6 mm: FreeType's 16.16 fixed-point advance against the font units' exact ratio
        assert t.box[2] - t.box[0] == pytest.approx(width_mm, abs=1e-6)
        ascent, descent = font.ascender / font.units_per_EM, -font.descender / font.units_per_EM
        assert t.box[3] - t.box[1] == pytest.approx((ascent + descent) * 10.0 * MM_PER_PT, abs=1e-9)


def test_hatching_lies_inside_its_polygon_on_the_rendered_pdf(tmp_path, poppler):
    files = write_figure(_sheet(), tmp_path, "v")
    subprocess.run([poppler["pdftoppm"], "-r", "72", "-gray", "-png", str(files["pdf"]), str(tmp_path / "v")],
                   check=True)
    from PIL import Image
    img = np.asarray(Image.open(next(tmp_path.glob("v-*.png"))))
    assert img.shape[:2] == (round(SHEET_MM[1] / MM_PER_PT), round(SHEET_MM[0] / MM_PER_PT))
    ink = img < 200
    px = lambda x_mm, y_mm: (round((SHEET_MM[1] - y_mm) / MM_PER_PT), round(x_mm / MM_PER_PT))  # noqa: E731
    (r1, c0), (r0, c1) = px(100.0, 100.0), px(140.0, 120.0)
    inside = ink[r0:r1, c0:c1].sum()
    # a 2 px ring round the polygon: anti-aliasing reaches 1 px past its edge
    ring = ink[r0 - 4:r1 + 4, c0 - 4:c1 + 4].sum() - ink[r0 - 2:r1 + 2, c0 - 2:c1 + 2].sum()
    assert inside > 0.1 * (r1 - r0) * (c1 - c0) and ring == 0


def test_the_same_sheet_gives_the_same_bytes(tmp_path):
    a, b = write_figure(_sheet(), tmp_path / "a", "v"), write_figure(_sheet(), tmp_path / "b", "v")
    for fmt in ("svg", "pdf"):
        assert a[fmt].read_bytes() == b[fmt].read_bytes()
