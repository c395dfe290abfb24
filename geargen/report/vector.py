"""geargen's own vector writer for the manufacturing drawings: one recorded sheet, written as SVG and PDF.

A :class:`Drawing` records primitives in sheet mm (y up from the sheet's bottom left): stroked or
filled paths (ISO 128 line widths in mm, dash patterns, an optional clipping box) and texts (size in
pt, weight, grey, alignment point, rotation, an optional SVG group id). :func:`svg_bytes` and
:func:`pdf_bytes` encode the same record, so the two files are one drawing.

Text is DejaVu Sans (regular and bold), the font the SVG names and a browser renders: its advance
widths (unhinted, read once per glyph from the font file: geargen.report.truetype) lay the text out, and the
PDF draws the very glyphs as Type 3 fonts (each glyph's outline once per process) with a ToUnicode
map, so a PDF reader extracts every character (±, °, µ, Greek, ⌀, ↗) and the text sits where the
SVG's does. Both encodings are deterministic (no dates, no ids from memory).
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import numpy as np

MM_PER_PT = 25.4 / 72.0
FONT = "DejaVu Sans"
FONT_FILES = {"normal": "DejaVuSans.ttf", "bold": "DejaVuSans-Bold.ttf"}
#: where the font files are looked for: the system's DejaVu (what a browser on this machine renders),
#: else the copy matplotlib ships (the same family, for a machine without it)
FONT_DIRS = (Path("/usr/share/fonts/truetype/dejavu"), Path("/usr/share/fonts/dejavu"))
#: PDF path and SVG path coordinates are written in these units of a mm (whole numbers: 10 um)
UNITS_PER_MM = 100


def _font_path(weight: str) -> Path:
    name = FONT_FILES[weight]
    for folder in FONT_DIRS:
        if (folder / name).is_file():
            return folder / name
    import importlib.util
    spec = importlib.util.find_spec("matplotlib")
    for root in spec.submodule_search_locations or []:
        path = Path(root) / "mpl-data" / "fonts" / "ttf" / name
        if path.is_file():
            return path
    raise FileNotFoundError(f"{name} ({FONT}) not found in {', '.join(map(str, FONT_DIRS))} nor matplotlib's fonts")


class Face:
    """One weight of the drawing font: advance widths (em) per character, cached, and each glyph's
    outline as a PDF path in font units (for the PDF's Type 3 font), read by
    :class:`geargen.report.truetype.TrueTypeFont`."""

    def __init__(self, weight: str):
        from geargen.report.truetype import TrueTypeFont

        self.font = TrueTypeFont(_font_path(weight).read_bytes())
        self.upm = self.font.units_per_em
        self.ascent = self.font.ascent / self.upm  # em: what a browser's text box reaches above the baseline
        self.descent = -self.font.descent / self.upm  # and below
        self.bbox = self.font.bbox
        self._advance: dict[str, float] = {}
        self._units: dict[str, int] = {}
        self._procs: dict[str, bytes] = {}

    def advance_units(self, ch: str) -> int:
        units = self._units.get(ch)
        if units is None:
            units = self._units[ch] = self.font.advance(self.font.glyph_id(ord(ch)))
        return units

    def width_em(self, text: str) -> float:
        adv = self._advance
        total = 0.0
        for ch in text:
            a = adv.get(ch)
            if a is None:
                a = adv[ch] = self.advance_units(ch) / self.upm
            total += a
        return total

    def char_proc(self, ch: str) -> bytes:
        """The Type 3 glyph procedure of ``ch``: its advance (``d0``) and filled outline in font units,
        deflated (a PDF stream's data; once per glyph and process)."""
        proc = self._procs.get(ch)
        if proc is None:
            from geargen.report.truetype import OutlinePen

            pen = OutlinePen()
            self.font.draw(self.font.glyph_id(ord(ch)), pen)
            body = " ".join(pen.ops)
            proc = self._procs[ch] = zlib.compress(
                (f"{self.advance_units(ch)} 0 d0\n" + (body + " f" if body else "")).encode(), 6)
        return proc


@lru_cache(maxsize=None)
def face(weight: str = "normal") -> Face:
    """The drawing font's face of ``weight`` ("normal" or "bold"), loaded once per process."""
    return Face(weight)


def grey(color) -> float:
    """A matplotlib-style colour of the sheets ("black", "white", "0.35") as a grey level 0..1."""
    if color in ("black", "k", None):
        return 0.0
    if color in ("white", "w"):
        return 1.0
    return float(color)


@dataclass
class Path_:
    """A polyline (sheet mm) stroked with ``lw`` mm in grey ``stroke`` (None: not stroked), filled in
    grey ``fill`` (None: not filled), dashed by ``dash`` (mm, on/off), clipped to ``clip`` (x0, y0, x1, y1)."""

    points: np.ndarray
    lw: float = 0.35
    stroke: float | None = 0.0
    fill: float | None = None
    closed: bool = False
    dash: tuple[float, ...] | None = None
    clip: tuple[float, float, float, float] | None = None


@dataclass
class Text:
    """A one-line text: ``x``, ``y`` its anchor on the baseline (sheet mm) where ``anchor`` (start,
    middle, end) of the text sits, turned ``rotation`` degrees counter-clockwise about it; ``box``
    the text's extent (sheet mm: the advance widths along, ascent and descent across)."""

    text: str
    x: float
    y: float
    size: float
    weight: str = "normal"
    grey: float = 0.0
    anchor: str = "start"
    rotation: float = 0.0
    box: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    gid: str | None = None

    def get_text(self) -> str:
        return self.text


@dataclass
class Drawing:
    """The recorded sheet: ``size`` (mm) and its primitives in drawing order."""

    size: tuple[float, float]
    items: list = field(default_factory=list)


_ANCHOR_SHARE = {"start": 0.0, "middle": 0.5, "end": 1.0}


def _ints(points: np.ndarray) -> list[int]:
    return np.rint(np.asarray(points, dtype=float) * UNITS_PER_MM).astype(np.int64).ravel().tolist()


def _num(v: float, digits: int = 4) -> str:
    s = f"{v:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


# ---------------------------------------------------------------- SVG


def _xml(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


def _svg_grey(g: float) -> str:
    v = int(round(g * 255))
    return f"#{v:02x}{v:02x}{v:02x}"


def svg_bytes(drawing: Drawing) -> bytes:
    """The drawing as SVG: the user unit the point, y down from the sheet's top (paths in a group that
    scales 1/100 mm with y up onto it); every text a ``<text>`` (searchable, in the font named), a text
    with a group id inside its ``<g id>``."""
    w_mm, h_mm = drawing.size
    w_pt, h_pt = w_mm / MM_PER_PT, h_mm / MM_PER_PT
    k = 1.0 / (MM_PER_PT * UNITS_PER_MM)
    out = ['<?xml version="1.0" encoding="utf-8" standalone="no"?>\n',
           f'<svg xmlns="http://www.w3.org/2000/svg" width="{_num(w_pt, 3)}pt" height="{_num(h_pt, 3)}pt" '
           f'viewBox="0 0 {_num(w_pt, 3)} {_num(h_pt, 3)}" version="1.1">\n',
           f'<rect x="0" y="0" width="{_num(w_pt, 3)}" height="{_num(h_pt, 3)}" fill="#ffffff"/>\n']
    clips: dict[tuple, str] = {}
    defs = []
    body = []
    group_open = False
    for item in drawing.items:
        if isinstance(item, Path_):
            if not group_open:
                body.append(f'<g transform="matrix({k:.8f} 0 0 {-k:.8f} 0 {_num(h_pt, 3)})" '
                            'style="stroke-linejoin:round;stroke-linecap:butt">\n')
                group_open = True
            nums = _ints(item.points)
            d = ("M%d %d" + " %d %d" * (len(nums) // 2 - 1)) % tuple(nums) + ("Z" if item.closed else "")
            style = [f"fill:{_svg_grey(item.fill)}" if item.fill is not None else "fill:none"]
            if item.stroke is not None:
                style.append(f"stroke:{_svg_grey(item.stroke)};stroke-width:{_num(item.lw * UNITS_PER_MM, 2)}")
                if item.dash:
                    style.append("stroke-dasharray:" + ",".join(_num(v * UNITS_PER_MM, 2) for v in item.dash))
            clip = ""
            if item.clip is not None:
                if item.clip not in clips:
                    clips[item.clip] = f"clip{len(clips) + 1}"
                    x0, y0, x1, y1 = (round(v * UNITS_PER_MM) for v in item.clip)
                    defs.append(f'<clipPath id="{clips[item.clip]}"><rect x="{x0}" y="{y0}" width="{x1 - x0}" '
                                f'height="{y1 - y0}"/></clipPath>\n')
                clip = f' clip-path="url(#{clips[item.clip]})"'
            body.append(f'<path d="{d}" style="{";".join(style)}"{clip}/>\n')
        else:
            if group_open:
                body.append("</g>\n")
                group_open = False
            x, y = item.x / MM_PER_PT, (h_mm - item.y) / MM_PER_PT
            turn = f' transform="rotate({_num(-item.rotation)} {_num(x)} {_num(y)})"' if item.rotation else ""
            bold = " font-weight:bold;" if item.weight == "bold" else ""
            fill = f" fill:{_svg_grey(item.grey)};" if item.grey else ""
            text = (f'<text x="{_num(x)}" y="{_num(y)}"{turn} style="font-family:\'{FONT}\'; font-size:{_num(item.size)}px;'
                    f'{bold}{fill} text-anchor:{item.anchor}" xml:space="preserve">{_xml(item.text)}</text>')
            body.append(f'<g id="{item.gid}">{text}</g>\n' if item.gid else text + "\n")
    if group_open:
        body.append("</g>\n")
    if defs:
        # the clip boxes are in the paths' units (1/100 mm, y up): they live inside the scaled group
        out.append("<defs>\n" + "".join(defs) + "</defs>\n")
    return "".join(out + body + ["</svg>\n"]).encode("utf-8")


# ---------------------------------------------------------------- PDF


def _to_unicode(chars: list[str]) -> bytes:
    lines = ["/CIDInit /ProcSet findresource begin", "12 dict begin", "begincmap",
             "/CIDSystemInfo << /Registry (Adobe) /Ordering (UCS) /Supplement 0 >> def",
             "/CMapName /Adobe-Identity-UCS def", "/CMapType 2 def",
             "1 begincodespacerange", "<00> <FF>", "endcodespacerange"]
    pairs = [f"<{code:02X}> <{ch.encode('utf-16-be').hex().upper()}>" for code, ch in enumerate(chars, start=1)]
    for i in range(0, len(pairs), 100):
        chunk = pairs[i:i + 100]
        lines += [f"{len(chunk)} beginbfchar", *chunk, "endbfchar"]
    lines += ["endcmap", "CMapName currentdict /CMap defineresource pop", "end", "end"]
    return "\n".join(lines).encode()


class _Fonts:
    """The Type 3 fonts of one PDF: per weight, the characters used in first-use order, 255 to a font."""

    def __init__(self):
        self.chars: dict[tuple[str, int], list[str]] = {}
        self.codes: dict[tuple[str, str], tuple[str, int]] = {}  # (weight, char) -> (resource name, code)
        self.names: dict[tuple[str, int], str] = {}

    def encode(self, weight: str, text: str) -> list[tuple[str, bytes]]:
        """``text`` as runs of (font resource name, codes)."""
        runs: list[tuple[str, bytearray]] = []
        for ch in text:
            key = (weight, ch)
            if key not in self.codes:
                n = 0
                while len(self.chars.setdefault((weight, n), [])) >= 255:
                    n += 1
                self.chars[(weight, n)].append(ch)
                font = self.names.setdefault((weight, n), f"F{len(self.names) + 1}")
                self.codes[key] = (font, len(self.chars[(weight, n)]))
            font, code = self.codes[key]
            if not runs or runs[-1][0] != font:
                runs.append((font, bytearray()))
            runs[-1][1].append(code)
        return [(f, bytes(c)) for f, c in runs]


def _pdf_string(codes: bytes) -> str:
    return "<" + codes.hex().upper() + ">"


def pdf_bytes(drawing: Drawing) -> bytes:
    """The drawing as a one-page PDF (page size the sheet's), paths in 1/100 mm, text in Type 3
    fonts of DejaVu Sans's glyphs with ToUnicode maps."""
    w_mm, h_mm = drawing.size
    k = 1.0 / (MM_PER_PT * UNITS_PER_MM)
    fonts = _Fonts()
    ops = [f"{k:.8f} 0 0 {k:.8f} 0 0 cm 0 J 1 j"]
    for item in drawing.items:
        if isinstance(item, Path_):
            nums = _ints(item.points)
            n = len(nums) // 2
            path = ("%d %d m" + " %d %d l" * (n - 1)) % tuple(nums) + (" h" if item.closed else "")
            state = []
            if item.clip is not None:
                x0, y0, x1, y1 = (round(v * UNITS_PER_MM) for v in item.clip)
                state.append(f"{x0} {y0} {x1 - x0} {y1 - y0} re W n")
            if item.fill is not None:
                state.append(f"{_num(item.fill)} g")
            if item.stroke is not None:
                dash = " ".join(_num(v * UNITS_PER_MM, 2) for v in item.dash) if item.dash else ""
                state.append(f"{_num(item.stroke)} G {_num(item.lw * UNITS_PER_MM, 2)} w [{dash}] 0 d")
            paint = "B" if item.fill is not None and item.stroke is not None else "f" if item.fill is not None else "S"
            ops.append("q " + " ".join(state) + "\n" + path + " " + paint + " Q")
        else:
            share = _ANCHOR_SHARE[item.anchor]
            width = face(item.weight).width_em(item.text) * item.size * MM_PER_PT
            c, s = (np.cos(np.radians(item.rotation)), np.sin(np.radians(item.rotation))) if item.rotation else (1.0, 0.0)
            x, y = item.x - c * share * width, item.y - s * share * width  # the baseline's start
            size = item.size * MM_PER_PT * UNITS_PER_MM
            runs = fonts.encode(item.weight, item.text)
            parts = [f"BT {_num(item.grey)} g {_num(c, 6)} {_num(s, 6)} {_num(-s, 6)} {_num(c, 6)} "
                     f"{_num(x * UNITS_PER_MM, 2)} {_num(y * UNITS_PER_MM, 2)} Tm"]
            for font, codes in runs:
                parts.append(f"/{font} {_num(size, 3)} Tf {_pdf_string(codes)} Tj")
            ops.append(" ".join(parts) + " ET")
    content = zlib.compress("\n".join(ops).encode("latin-1"), 1)  # the fastest level: whole numbers deflate well

    objects: list[bytes] = []

    def add(body: bytes) -> int:
        objects.append(body)
        return len(objects)

    def stream(data: bytes, extra: str = "") -> bytes:
        return f"<< /Length {len(data)}{extra} >>\nstream\n".encode() + data + b"\nendstream"

    font_refs = {}
    for key, chars in fonts.chars.items():
        if not chars:
            continue
        weight = key[0]
        f = face(weight)
        procs = {}
        for i, ch in enumerate(chars, start=1):
            procs[f"g{i}"] = add(stream(f.char_proc(ch), " /Filter /FlateDecode"))
        cmap = add(stream(zlib.compress(_to_unicode(chars), 6), " /Filter /FlateDecode"))
        widths = " ".join(str(f.advance_units(ch)) for ch in chars)
        char_procs = " ".join(f"/{n} {r} 0 R" for n, r in procs.items())
        diffs = " ".join(f"/{n}" for n in procs)
        font_refs[fonts.names[key]] = add(
            (f"<< /Type /Font /Subtype /Type3 /Name /{fonts.names[key]} /FontBBox [{' '.join(map(str, f.bbox))}] "
             f"/FontMatrix [{1 / f.upm:.10g} 0 0 {1 / f.upm:.10g} 0 0] /CharProcs << {char_procs} >> "
             f"/Encoding << /Type /Encoding /Differences [1 {diffs}] >> /FirstChar 1 /LastChar {len(chars)} "
             f"/Widths [{widths}] /ToUnicode {cmap} 0 R /Resources << >> >>").encode())
    contents = add(stream(content, " /Filter /FlateDecode"))
    font_dict = " ".join(f"/{n} {r} 0 R" for n, r in sorted(font_refs.items(), key=lambda kv: int(kv[0][1:])))
    w_pt, h_pt = w_mm / MM_PER_PT, h_mm / MM_PER_PT
    pages_ref = len(objects) + 2
    page = add((f"<< /Type /Page /Parent {pages_ref} 0 R /MediaBox [0 0 {_num(w_pt, 3)} {_num(h_pt, 3)}] "
                f"/Contents {contents} 0 R /Resources << /Font << {font_dict} >> >> >>").encode())
    add(f"<< /Type /Pages /Kids [{page} 0 R] /Count 1 >>".encode())
    catalog = add(f"<< /Type /Catalog /Pages {pages_ref} 0 R >>".encode())
    info = add(b"<< /Producer (geargen) >>")

    out = bytearray(b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n")
    offsets = []
    for i, body in enumerate(objects, start=1):
        offsets.append(len(out))
        out += f"{i} 0 obj\n".encode() + body + b"\nendobj\n"
    xref = len(out)
    out += f"xref\n0 {len(objects) + 1}\n0000000000 65535 f \n".encode()
    out += "".join(f"{o:010d} 00000 n \n" for o in offsets).encode()
    out += f"trailer\n<< /Size {len(objects) + 1} /Root {catalog} 0 R /Info {info} 0 R >>\nstartxref\n{xref}\n%%EOF\n".encode()
    return bytes(out)


__all__ = ["MM_PER_PT", "FONT", "Face", "face", "grey", "Path_", "Text", "Drawing", "svg_bytes", "pdf_bytes"]
