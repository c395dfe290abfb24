"""The few parts of a TrueType font the drawings use, read straight from the file's tables.

:mod:`geargen.report.vector` lays text out with the font's advance widths and draws its glyphs in the
PDF; it needs the header's units per em and box (``head``), the ascent and descent (``hhea``), the
advance widths (``hmtx``), the character map (``cmap``: format 12 or 4, the subtable fontTools'
``getBestCmap`` would choose) and the glyph outlines (``loca``, ``glyf``: simple glyphs and composite
ones, decomposed). Reading only those tables, and only the glyphs drawn, costs a fraction of loading the
whole font with fontTools (its import and the decoding of every glyph, name and map entry: about a
third of the build's drawings process). The outlines are drawn as fontTools' ``Glyph.draw`` with its
``BasePen`` (TrueType quadratic segments, implied on-curve points, each quadratic raised to a cubic)
and ``TransformPen`` (components) would, with the same arithmetic: tests/report/test_truetype.py compares
every character of the font with fontTools.
"""

from __future__ import annotations

import bisect
import struct

#: the cmap subtables in the order fontTools' getBestCmap takes them: (platform, encoding)
CMAP_PREFERENCE = ((3, 10), (0, 6), (0, 4), (3, 1), (0, 3), (0, 2), (0, 1), (0, 0))
_ON_CURVE, _REPEAT, _X_SHORT, _Y_SHORT, _X_SAME, _Y_SAME = 0x01, 0x08, 0x02, 0x04, 0x10, 0x20
_WORDS, _XY_VALUES, _SCALE, _MORE, _XY_SCALE, _TWO_BY_TWO = 0x0001, 0x0002, 0x0008, 0x0020, 0x0040, 0x0080
_IDENTITY = (1, 0, 0, 1, 0, 0)


class TrueTypeFont:
    """A TrueType font file's metrics, character map and glyph outlines (see the module docstring)."""

    def __init__(self, data: bytes):
        self.data = data
        count = struct.unpack_from(">H", data, 4)[0]
        self.tables = {}
        for i in range(count):
            tag, _, offset, _ = struct.unpack_from(">4sIII", data, 12 + 16 * i)
            self.tables[tag.decode("latin-1")] = offset
        head, hhea = self.tables["head"], self.tables["hhea"]
        self.units_per_em = struct.unpack_from(">H", data, head + 18)[0]
        self.bbox = struct.unpack_from(">hhhh", data, head + 36)  # xMin, yMin, xMax, yMax
        self._long_loca = struct.unpack_from(">h", data, head + 50)[0] == 1
        self.ascent, self.descent = struct.unpack_from(">hh", data, hhea + 4)
        self._metrics = struct.unpack_from(">H", data, hhea + 34)[0]
        self._cmap = self._best_cmap()

    # ---------------------------------------------------------------- character map and metrics

    def _best_cmap(self):
        data, cmap = self.data, self.tables["cmap"]
        subtables = {}
        for i in range(struct.unpack_from(">H", data, cmap + 2)[0]):
            platform, encoding, offset = struct.unpack_from(">HHI", data, cmap + 4 + 8 * i)
            subtables.setdefault((platform, encoding), cmap + offset)
        for key in CMAP_PREFERENCE:
            if key in subtables and struct.unpack_from(">H", data, subtables[key])[0] in (4, 12):
                return subtables[key]
        raise ValueError("the font has no Unicode character map of format 4 or 12")

    def glyph_id(self, code: int) -> int:
        """The glyph of character ``code``; 0 (.notdef) if the font has none."""
        data, at = self.data, self._cmap
        if struct.unpack_from(">H", data, at)[0] == 12:
            groups = struct.unpack_from(">I", data, at + 12)[0]
            starts = _Column(data, at + 16, groups)
            i = bisect.bisect_right(starts, code) - 1
            if i < 0:
                return 0
            start, end, glyph = struct.unpack_from(">III", data, at + 16 + 12 * i)
            return glyph + code - start if code <= end else 0
        segments = struct.unpack_from(">H", data, at + 6)[0] // 2
        ends = at + 14
        i = bisect.bisect_left(_Column(data, ends, segments, ">H", 2), code)
        if i >= segments:
            return 0
        starts, deltas, ranges = ends + 2 * segments + 2, ends + 4 * segments + 2, ends + 6 * segments + 2
        start = struct.unpack_from(">H", data, starts + 2 * i)[0]
        if code < start:
            return 0
        delta = struct.unpack_from(">h", data, deltas + 2 * i)[0]
        offset = struct.unpack_from(">H", data, ranges + 2 * i)[0]
        if offset == 0:
            return (code + delta) & 0xFFFF
        glyph = struct.unpack_from(">H", data, ranges + 2 * i + offset + 2 * (code - start))[0]
        return (glyph + delta) & 0xFFFF if glyph else 0

    def advance(self, glyph: int) -> int:
        """The glyph's advance width (font units)."""
        return struct.unpack_from(">H", self.data, self.tables["hmtx"] + 4 * min(glyph, self._metrics - 1))[0]

    def _left_bearing(self, glyph: int) -> int:
        hmtx, n = self.tables["hmtx"], self._metrics
        at = hmtx + 4 * glyph + 2 if glyph < n else hmtx + 4 * n + 2 * (glyph - n)
        return struct.unpack_from(">h", self.data, at)[0]

    # ---------------------------------------------------------------- outlines

    def _glyph_data(self, glyph: int) -> tuple[int, int]:
        loca = self.tables["loca"]
        if self._long_loca:
            start, end = struct.unpack_from(">II", self.data, loca + 4 * glyph)
        else:
            start, end = (2 * v for v in struct.unpack_from(">HH", self.data, loca + 2 * glyph))
        return self.tables["glyf"] + start, end - start

    def draw(self, glyph: int, pen: "OutlinePen", transforms: tuple = (), top: bool = True) -> None:
        """Draw ``glyph`` onto ``pen`` as fontTools' ``Glyph.draw`` does (components decomposed, each
        through the transforms of the components it is in, innermost first)."""
        at, length = self._glyph_data(glyph)
        if length == 0:
            return
        data = self.data
        contours, x_min = struct.unpack_from(">hh", data, at)
        if contours < 0:
            at += 10
            more = True
            while more:
                flags, component = struct.unpack_from(">HH", data, at)
                at += 4
                if flags & _WORDS:
                    x, y = struct.unpack_from(">hh" if flags & _XY_VALUES else ">HH", data, at)
                    at += 4
                else:
                    x, y = struct.unpack_from(">bb" if flags & _XY_VALUES else ">BB", data, at)
                    at += 2
                if not flags & _XY_VALUES:
                    raise ValueError(f"glyph {glyph}: components placed by matching points are not read")
                if flags & _SCALE:
                    s = struct.unpack_from(">h", data, at)[0] / (1 << 14)
                    at += 2
                    matrix = (s, 0, 0, s)
                elif flags & _XY_SCALE:
                    sx, sy = (v / (1 << 14) for v in struct.unpack_from(">hh", data, at))
                    at += 4
                    matrix = (sx, 0, 0, sy)
                elif flags & _TWO_BY_TWO:
                    matrix = tuple(v / (1 << 14) for v in struct.unpack_from(">hhhh", data, at))
                    at += 8
                else:
                    matrix = (1, 0, 0, 1)
                transform = (*matrix, x, y)
                self.draw(component, pen, transforms + ((transform,) if transform != _IDENTITY else ()), False)
                more = flags & _MORE
            return
        offset = self._left_bearing(glyph) - x_min if top else 0  # fontTools: lsb - xMin, at the top only
        ends = struct.unpack_from(f">{contours}H", data, at + 10)
        at += 10 + 2 * contours
        at += 2 + struct.unpack_from(">H", data, at)[0]  # the instructions
        count = ends[-1] + 1 if contours else 0
        flags = []
        while len(flags) < count:
            f = data[at]
            at += 1
            flags.append(f)
            if f & _REPEAT:
                flags.extend([f] * data[at])
                at += 1
        coordinates = []
        for short, same in ((_X_SHORT, _X_SAME), (_Y_SHORT, _Y_SAME)):
            value, values = 0, []
            for f in flags:
                if f & short:
                    value += data[at] if f & same else -data[at]
                    at += 1
                elif not f & same:
                    value += struct.unpack_from(">h", data, at)[0]
                    at += 2
                values.append(value)
            coordinates.append(values)
        points = [(float(x + offset), float(y)) for x, y in zip(*coordinates)]  # fontTools' coordinates: floats
        pen.transforms = transforms
        start = 0
        for end in ends:
            contour = points[start:end + 1]
            on = [f & _ON_CURVE for f in flags[start:end + 1]]
            start = end + 1
            if 1 not in on:  # no on-curve point: the implied one between the last and the first starts it
                pen.q_curve_to(contour + [None])
            else:  # start at the first on-curve point, so the contour ends on it
                first = on.index(1) + 1
                contour, on = contour[first:] + contour[:first], on[first:] + on[:first]
                pen.move_to(contour[-1])
                while contour:
                    following = on.index(1) + 1
                    if following == 1:
                        if len(contour) > 1:  # the closing line is implied
                            pen.line_to(contour[0])
                    else:
                        pen.q_curve_to(contour[:following])
                    contour, on = contour[following:], on[following:]
            pen.close()


class _Column:
    """A big-endian column of numbers in ``data`` (every ``stride`` bytes from ``at``), for bisect."""

    def __init__(self, data: bytes, at: int, count: int, fmt: str = ">I", stride: int = 12):
        self.data, self.at, self.count, self.fmt, self.stride = data, at, count, fmt, stride

    def __len__(self) -> int:
        return self.count

    def __getitem__(self, i: int) -> int:
        return struct.unpack_from(self.fmt, self.data, self.at + self.stride * i)[0]


class OutlinePen:
    """Glyph outlines as PDF path operators, as fontTools' ``BasePen`` decomposes them (each quadratic
    segment raised to a cubic with the 2/3 rule) and a ``TransformPen`` per enclosing component places them."""

    def __init__(self):
        self.ops: list[str] = []
        self.transforms: tuple = ()
        self._current = None

    def _place(self, p):
        for xx, xy, yx, yy, dx, dy in reversed(self.transforms):  # innermost component first
            x, y = p
            p = (xx * x + yx * y + dx, xy * x + yy * y + dy)
        return p

    def move_to(self, p) -> None:
        p = self._place(p)
        self.ops.append(f"{p[0]:g} {p[1]:g} m")
        self._current = p

    def line_to(self, p) -> None:
        p = self._place(p)
        self.ops.append(f"{p[0]:g} {p[1]:g} l")
        self._current = p

    def q_curve_to(self, points: list) -> None:
        """TrueType off-curve points and the on-curve end (``None``: a contour without on-curve points)."""
        if points[-1] is None:
            points = [self._place(p) for p in points[:-1]]
            (x, y), (nx, ny) = points[-1], points[0]
            implied = (0.5 * (x + nx), 0.5 * (y + ny))
            self._current = implied
            self.ops.append(f"{implied[0]:g} {implied[1]:g} m")
            points = points + [implied]
        else:
            points = [self._place(p) for p in points]
        if len(points) == 1:
            self.ops.append(f"{points[0][0]:g} {points[0][1]:g} l")
            self._current = points[0]
            return
        pieces = [(points[i], (0.5 * (points[i][0] + points[i + 1][0]), 0.5 * (points[i][1] + points[i + 1][1])))
                  for i in range(len(points) - 2)] + [(points[-2], points[-1])]
        for (x1, y1), (x2, y2) in pieces:
            x0, y0 = self._current
            values = (x0 + 0.66666666666666667 * (x1 - x0), y0 + 0.66666666666666667 * (y1 - y0),
                      x2 + 0.66666666666666667 * (x1 - x2), y2 + 0.66666666666666667 * (y1 - y2), x2, y2)
            self.ops.append(" ".join(f"{v:.1f}" for v in values) + " c")
            self._current = (x2, y2)

    def close(self) -> None:
        self.ops.append("h")
        self._current = None


__all__ = ["CMAP_PREFERENCE", "TrueTypeFont", "OutlinePen"]
