"""geargen.report.truetype reads the drawing font as fontTools does: for every character the font maps
(both weights of DejaVu Sans, the drawings' font), the same glyph advance and the same PDF path operators
(fontTools' glyph set drawn with a BasePen writing the operators as geargen's PDF writes them:
``%g`` for moves and lines, one decimal for curves), and the same units per em, box, ascent and descent.
Also a character the font lacks (.notdef) and characters beyond the Basic Multilingual Plane."""

import pytest

from geargen.report.truetype import OutlinePen, TrueTypeFont
from geargen.report.vector import FONT_FILES, _font_path


def _fonttools_ops(glyphs, name):
    from fontTools.pens.basePen import BasePen

    class Pen(BasePen):
        def __init__(self, glyph_set):
            super().__init__(glyph_set)
            self.ops = []

        def _moveTo(self, p):
            self.ops.append(f"{p[0]:g} {p[1]:g} m")

        def _lineTo(self, p):
            self.ops.append(f"{p[0]:g} {p[1]:g} l")

        def _curveToOne(self, a, b, c):
            self.ops.append(" ".join(f"{v:.1f}" for v in (*a, *b, *c)) + " c")

        def _closePath(self):
            self.ops.append("h")

    pen = Pen(glyphs)
    glyphs[name].draw(pen)
    return pen.ops


@pytest.mark.parametrize("weight", sorted(FONT_FILES))
def test_every_glyph_as_fonttools_draws_it(weight):
    from fontTools.ttLib import TTFont

    path = _font_path(weight)
    theirs = TTFont(str(path))
    ours = TrueTypeFont(path.read_bytes())
    head, hhea = theirs["head"], theirs["hhea"]
    assert (ours.units_per_em, ours.bbox) == (head.unitsPerEm, (head.xMin, head.yMin, head.xMax, head.yMax))
    assert (ours.ascent, ours.descent) == (hhea.ascent, hhea.descent)
    cmap, glyphs, metrics = theirs.getBestCmap(), theirs.getGlyphSet(), theirs["hmtx"].metrics
    order = theirs.getGlyphOrder()
    codes = sorted(cmap) + [0x10FFFD, 0xE0FFF, max(cmap) + 1]  # the last three: not in the font
    assert len(cmap) > 3000  # the whole map is compared, not a few letters
    differ = []
    for code in codes:
        name = cmap.get(code, ".notdef")
        glyph = ours.glyph_id(code)
        pen = OutlinePen()
        ours.draw(glyph, pen)
        if order[glyph] != name or ours.advance(glyph) != metrics[name][0] or pen.ops != _fonttools_ops(glyphs, name):
            differ.append(hex(code))
    assert differ == []
