"""The manufacturing drawing of a rack: its side view (the whole length, the tooth outline of the model
over the back), a detail of a tooth space in the normal section with the measuring pin (ball) and the
dimension from the back face over it, and the data block with the tooth-thickness allowance, the
tooth thickness at the pitch line and the over-pin dimension with their limits. Every value from the
rack's JSON dict (:func:`geargen.families.rack.data.rack_data`)."""

from __future__ import annotations

import math

import numpy as np

from geargen.families.rack.geometry import pin_contact_height, rack_outline
from geargen.report.drawing import pitch_rows, format_limits, format_number, format_um, NOT_SPECIFIED, scale_text, write_figure
from geargen.report.drawing_sheet import (VIEWS, angle_text, chain_line, closing_rows, dimension, draw_sheet,
                                          polyline, value_text, view_title)
from geargen.units import from_mm, to_mm

SIDE_VIEW = (VIEWS[0], 185.0, VIEWS[2], 262.0)
DETAIL_VIEW = (VIEWS[0], 18.0, VIEWS[2], 165.0)


def rack_rows(data: dict) -> list[tuple[str, str, str]]:
    u = data["length_unit"]
    L = lambda v: value_text(v, u)  # noqa: E731 - one formatter for every length on the sheet
    allowance = data.get("thickness_allowance")
    pin = data["over_pin"]
    kind = pin["kind"]
    rack = data["basic_rack"]
    return [
        ("Number of teeth", "z", f"{data['teeth']}"),
        *pitch_rows(data["normal_module_mm"], u),
        ("Normal pressure angle", "α_n", angle_text(data["normal_pressure_angle_deg"])),
        ("Helix angle and hand", "β", f"{data['helix_angle_deg']:.4f}° {data['hand']} hand" if data["hand"]
         else "0° (straight teeth)"),
        ("Tooth proportions", "", f"h_a {rack['addendum_coefficient']:.3g} m_n, h_f {rack['dedendum_coefficient']:.3g} m_n"),
        ("Normal pitch", "p_n", L(data["normal_pitch"])),
        ("Length", "l", L(data["length"])),
        ("Face width", "b", L(data["face_width"])),
        ("Back face to pitch line", "H", L(data["pitch_line_height"])),
        ("Overall height", "", L(data["height"])),
        ("Tooth thickness allowance, upper", "A_sne",
         format_um(allowance["upper_um"], u, signed=True) if allowance else NOT_SPECIFIED),
        ("Tooth thickness allowance, lower", "A_sni",
         format_um(allowance["lower_um"], u, signed=True) if allowance else NOT_SPECIFIED),
        ("Tooth thickness at the pitch line (normal)", "s_n", L(data["tooth_thickness_normal_model"])),
        ("Tooth thickness limits", "s_n", format_limits(data["tooth_thickness_normal_limits"], u)
         if data["tooth_thickness_normal_limits"] else NOT_SPECIFIED),
        (f"{kind.capitalize()} diameter", "D_M", L(pin["diameter"])),
        (f"{kind.capitalize()} series", "", pin["series"]),
        (f"Back face over {kind}", "M", L(pin["dimension_to_back"])),
        (f"Over-{kind} limits", "M", format_limits(pin["limits"], u) if pin["limits"] else NOT_SPECIFIED),
        ("Thinning in the model (along the pitch line)", "", L(data["thinning_circumferential"])),
    ]


def _side_views(spec, data, scale_side: float, scale_detail: float):
    u = data["length_unit"]
    N = lambda v: format_number(from_mm(v, u), u)  # noqa: E731
    outline = rack_outline(spec)
    H = spec.pitch_line_height

    def views(sheet):
        # side view: the z = 0 section along the length (x), the back face at the bottom
        box = SIDE_VIEW
        k = scale_side
        length = spec.length
        ox = box[0] + (box[2] - box[0] - length * k) / 2
        oy = box[1] + 8
        x = np.linspace(0.0, length, max(400, int(length * k * 4)))
        top = H + outline.height_at(x * math.cos(spec.helix_angle))  # transverse x to the normal section's
        pts = np.vstack([[[0.0, 0.0]], np.column_stack([x, top]), [[length, 0.0]], [[0.0, 0.0]]])
        polyline(sheet, pts, (ox, oy), k)
        chain_line(sheet, [ox - 3, ox + length * k + 3], [oy + H * k] * 2)
        view_title(sheet, box, f"Side view ({scale_text(k)})")
        # detail: three pitches of the normal section around a space, the pin in it
        box = DETAIL_VIEW
        k = scale_detail
        p = outline.pitch
        cx = (box[0] + box[2]) / 2
        oy = box[1] + 18
        xs = np.linspace(-1.5 * p, 1.5 * p, 1201)
        prof = H + outline.height_at(xs)
        detail = np.vstack([[[-1.5 * p, 0.0]], np.column_stack([xs, prof]), [[1.5 * p, 0.0]], [[-1.5 * p, 0.0]]])
        polyline(sheet, detail, (cx, oy), k)
        chain_line(sheet, [cx - 1.5 * p * k - 3, cx + 1.5 * p * k + 3], [oy + H * k] * 2)
        pin = to_mm(data["over_pin"]["diameter"], u)  # the series' pin the data block dimensions over
        y_c = H + pin_contact_height(spec, pin, -spec.thinning_normal)[0]
        t = np.linspace(0, 2 * math.pi, 181)
        polyline(sheet, np.column_stack([pin / 2 * np.cos(t), y_c + pin / 2 * np.sin(t)]), (cx, oy), k, lw=0.35)
        top = y_c + pin / 2
        x_dim = cx + 1.5 * p * k + 8
        dimension(sheet, (x_dim, oy), (x_dim, oy + top * k), f"M = {N(top)}", vertical=True)
        sheet.line([cx, x_dim + 1.5], [oy + top * k] * 2, lw=0.18)
        sheet.line([cx + 1.5 * p * k, x_dim + 1.5], [oy, oy], lw=0.18)
        sheet.text(cx, oy - 3, "back face", 10, ha="center", va="top")
        view_title(sheet, box, f"Detail: measuring {data['over_pin']['kind']} in a tooth space, "
                               f"{data['over_pin']['section']} section ({scale_text(k)})")
    return views


def draw_rack(data: dict, spec, source: str, design_file: str, version: str):
    from geargen.report.drawing import preferred_scale
    u = data["length_unit"]
    side = min(preferred_scale(spec.length, SIDE_VIEW[2] - SIDE_VIEW[0] - 10),
               preferred_scale(spec.height, SIDE_VIEW[3] - SIDE_VIEW[1] - 14))
    p = rack_outline(spec).pitch
    detail = min(preferred_scale(3 * p, DETAIL_VIEW[2] - DETAIL_VIEW[0] - 40),
                 preferred_scale(spec.height + p, DETAIL_VIEW[3] - DETAIL_VIEW[1] - 30))
    rows = rack_rows(data) + closing_rows(u, side, version, source)
    return draw_sheet(data["name"], rows, _side_views(spec, data, side, detail), design_file, u, side, version)


def rack_drawings(data: dict, spec, folder, name: str, source: str, design_file: str) -> dict:
    """``name-drawing.svg``/``.pdf`` of the rack into ``folder``, recorded in ``data["drawing"]``."""
    from geargen import __version__
    data["drawing"] = {"svg": f"{name}-drawing.svg", "pdf": f"{name}-drawing.pdf"}
    return write_figure(draw_rack(data, spec, source, design_file, __version__), folder, name)


__all__ = ["rack_rows", "draw_rack", "rack_drawings"]
