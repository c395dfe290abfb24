"""The A3 sheet of a part that is not one cylindrical gear (bevel gear, worm, worm wheel, rack, one-piece
cluster): the frame, data block and title block of :mod:`geargen.report.drawing` around the family's own
views, written as SVG and PDF the same way.

A family module gives its data rows ``(name, symbol, value)`` (every value from the part's JSON dict,
so the sheet and the JSON agree) and a function drawing its views into :data:`VIEWS` (sheet mm).
"""

from __future__ import annotations

from geargen.report import drawing as sheet_parts
from geargen.report.drawing import dimension, view_title  # the family sheets draw them as the gear drawing does

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
    """The sheet (a :class:`geargen.report.drawing.Sheet`): frame, ``draw_views(sheet)``, the data
    block of ``rows`` and the title block."""
    sheet = sheet_parts.Sheet()
    sheet_parts.draw_frame(sheet)
    draw_views(sheet)
    sheet_parts.draw_data_block(sheet, rows)
    sheet_parts.draw_title_block(sheet, name, design_file, unit, sheet_parts.scale_text(scale), version)
    return sheet


def polyline(sheet, points, origin, scale: float, lw: float = 0.5, **kw):
    """Part points ``(n, 2)`` (mm) drawn at ``scale`` from the sheet point ``origin``."""
    return sheet.line(origin[0] + points[:, 0] * scale, origin[1] + points[:, 1] * scale, lw=lw, **kw)


def chain_line(sheet, xs, ys):
    """A thin chain line (centre lines, pitch lines: ISO 128)."""
    return sheet.line(xs, ys, lw=0.18, linestyle=(0, (12, 2, 1.5, 2)), color="0.25")


def fit_scale(width_mm: float, height_mm: float, box) -> float:
    """The largest ISO 5455 scale at which a view of ``width_mm`` x ``height_mm`` fits ``box``
    with 20 mm left for its dimensions."""
    return min(sheet_parts.preferred_scale(width_mm, box[2] - box[0] - 20.0),
               sheet_parts.preferred_scale(height_mm, box[3] - box[1] - 20.0))


__all__ = ["VIEWS", "value_text", "angle_text", "closing_rows", "draw_sheet", "polyline",
           "chain_line", "dimension", "view_title", "fit_scale"]
