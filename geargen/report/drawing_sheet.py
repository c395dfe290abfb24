"""The A3 sheet of a part that is not one cylindrical gear (bevel gear, worm, worm wheel, rack, one-piece
cluster): the frame, data block and title block of :mod:`geargen.report.drawing` around the family's own
views, written as SVG and PDF the same way.

A family module gives its data rows ``(name, symbol, value)`` (every value from the part's JSON dict,
so the sheet and the JSON agree) and a function drawing its views into :data:`VIEWS` (sheet mm).
"""

from __future__ import annotations

from pathlib import Path

from geargen.report import drawing as sheet_parts

#: the sheet's room for a family's views (sheet mm: left, bottom, right, top), left of the data block
VIEWS = (25.0, 18.0, 225.0, 270.0)


def value_text(value, unit: str) -> str:
    """A length of the part's JSON (in ``unit``) as the data block writes it."""
    return sheet_parts.format_length(value, unit)


def angle_text(deg) -> str:
    return sheet_parts.NOT_SPECIFIED if deg is None else f"{deg:.4f}°"


def closing_rows(unit: str, scale: float, version: str, source: str) -> list[tuple[str, str, str]]:
    """The rows every sheet ends with (as the gear drawing's)."""
    return [("Drawing units", "", f"{unit} (angles in degrees)"),
            ("Drawing scale", "", sheet_parts.scale_text(scale)),
            ("Generator", "", f"geargen {version}"),
            ("Source", "", source)]


def draw_sheet(name: str, rows, draw_views, design_file: str, unit: str, scale: float, version: str):
    """The figure: frame, ``draw_views(sheet)`` (a :class:`geargen.report.drawing._Sheet`), the data
    block of ``rows`` and the title block."""
    import matplotlib

    with matplotlib.rc_context({"hatch.linewidth": 0.18 / sheet_parts.MM_PER_PT, "hatch.color": "0.35"}):
        sheet = sheet_parts._Sheet()
        sheet_parts._frame(sheet)
        draw_views(sheet)
        sheet_parts._data_block(sheet, rows)
        sheet_parts._title_block(sheet, name, design_file, unit, sheet_parts.scale_text(scale), version)
    return sheet.fig


def write_sheet(fig, folder, name: str) -> dict[str, Path]:
    """``folder/name-drawing.svg`` and ``.pdf`` from ``fig`` (atomically; text kept as text, no dates:
    the same bytes twice, as :func:`geargen.report.drawing.write_drawing`)."""
    import matplotlib

    from geargen.outputs import atomic_path

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    out = {}
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "geargen", "pdf.fonttype": 3}):
        for fmt, meta in (("svg", {"Date": None}), ("pdf", {"CreationDate": None, "ModDate": None})):
            path = folder / f"{name}-drawing.{fmt}"
            with atomic_path(path) as tmp:
                fig.savefig(tmp, format=fmt, facecolor="white", metadata=meta)
            out[fmt] = path
    return out


def polyline(sheet, points, origin, scale: float, lw: float = 0.5, **kw):
    """Part points ``(n, 2)`` (mm) drawn at ``scale`` from the sheet point ``origin``."""
    return sheet.line(origin[0] + points[:, 0] * scale, origin[1] + points[:, 1] * scale, lw=lw, **kw)


def chain_line(sheet, xs, ys):
    """A thin chain line (centre lines, pitch lines: ISO 128)."""
    return sheet.line(xs, ys, lw=0.18, linestyle=(0, (12, 2, 1.5, 2)), color="0.25")


def dimension(sheet, p, q, text: str, vertical: bool) -> None:
    sheet_parts._dimension(sheet, p, q, text, vertical)


def view_title(sheet, box, text: str) -> None:
    sheet_parts._view_title(sheet, box, text)


def fit_scale(width_mm: float, height_mm: float, box) -> float:
    """The largest ISO 5455 scale at which a view of ``width_mm`` x ``height_mm`` fits ``box``
    with 20 mm left for its dimensions."""
    return min(sheet_parts.preferred_scale(width_mm, box[2] - box[0] - 20.0),
               sheet_parts.preferred_scale(height_mm, box[3] - box[1] - 20.0))


__all__ = ["VIEWS", "value_text", "angle_text", "closing_rows", "draw_sheet", "write_sheet", "polyline",
           "chain_line", "dimension", "view_title", "fit_scale"]
