"""The drawing of a cluster gear as made: one sheet with both gears on their one bore.

Views: the end view from the small gear's side (the large gear's outline thin, the small gear's
thick, tooth 0 of the large gear on +x and the small gear turned by the tooth phase, the two tooth
centre lines drawn); the axial section (both faces, the gap, the bore) with the face widths,
positions and overall length dimensioned. Data block: both gears' main data (their full tooth data,
allowances and inspection dimensions on each gear's own sheet, named), the bore, the axial layout,
the tooth phase and its tolerance. Every value from the cluster's JSON dict
(:func:`geargen.model.cluster_data.cluster_data`)."""

from __future__ import annotations

import math

import numpy as np

from geargen.report import drawing as sheet_parts
from geargen.report.drawing import pitch_row, write_figure
from geargen.report.drawing_sheet import (VIEWS, angle_text, chain_line, closing_rows, dimension, draw_sheet,
                                          polyline, value_text, view_title)
from geargen.units import from_mm

END_VIEW = (VIEWS[0], 60.0, 150.0, 262.0)
AXIAL_VIEW = (158.0, 60.0, VIEWS[2], 262.0)


def cluster_rows(data: dict) -> list[tuple[str, str, str]]:
    u = data["length_unit"]
    L = lambda v: value_text(v, u)  # noqa: E731 - one formatter for every length on the sheet
    rows = [("Construction", "", data["construction"])]
    for key, label in (("large", "Large gear"), ("small", "Small gear")):
        g = data[key]
        helix = f"{g['helix_angle_deg']:.4f}° {g['hand']}" if g["hand"] else "0° (spur)"
        pitch = pitch_row(g["normal_module_mm"], u, "")
        rows += [(f"{label}: teeth, {pitch[0]}", f"z, {pitch[1]}", f"{g['teeth']}, {pitch[2]}"),
                 (f"{label}: pressure angle, helix", "α_n, β", f"{g['normal_pressure_angle_deg']:.4f}°, {helix}"),
                 (f"{label}: profile shift", "x_n", f"{g['profile_shift_normal']:+.4f}"),
                 (f"{label}: reference diameter", "d", L(g["reference_diameter"])),
                 (f"{label}: tip diameter", "d_a", L(g["tip_diameter"])),
                 (f"{label}: face width", "b", L(g["face_width"])),
                 (f"{label}: tooth data sheet", "", g["tooth_data_drawing"])]
    rows += [
        ("Large gear face (from datum face)", "", f"{L(data['large_face'][0])} to {L(data['large_face'][1])}"),
        ("Small gear face (from datum face)", "", f"{L(data['small_face'][0])} to {L(data['small_face'][1])}"),
        ("Gap between the faces", "", L(data["axial_gap"])),
        ("Overall length", "", L(data["overall_length"])),
        ("Bore (one, through both gears)", "", L(data["bore_diameter"]) if data["bore_diameter"] else "none"),
        ("Keyway", "", f"{L(data['keyway']['width'])} x {L(data['keyway']['depth'])}" if data["keyway"] else "none"),
        ("Tooth phase, large to small", "φ", angle_text(data["tooth_phase_deg"])),
        ("Tooth phase tolerance", "", (f"± {data['tooth_phase_tolerance_deg']:.4f}° (± "
                                       f"{L(data['tooth_phase_tolerance_arc_small'])} at the small d)")
         if data["tooth_phase_tolerance_deg"] is not None else sheet_parts.NOT_SPECIFIED),
        ("Tooth phase measured", "", data["tooth_phase_definition"]),
    ]
    return rows


def _turned(points: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return points @ np.array([[c, s], [-s, c]])


def draw_cluster(data: dict, large, small, source: str, design_file: str, version: str):
    """The cluster's sheet (a :class:`geargen.report.drawing.Sheet`); ``large``/``small`` the two gears' specs (mm)."""
    from geargen.profile.tooth import tooth_profile

    u = data["length_unit"]
    N = lambda v_mm: sheet_parts.format_number(from_mm(v_mm, u), u)  # noqa: E731
    lp, sp = tooth_profile(large, warn=False), tooth_profile(small, warn=False)
    d_max = 2 * max(lp.tip_radius, sp.tip_radius)
    scale = min(sheet_parts.preferred_scale(d_max, min(END_VIEW[2] - END_VIEW[0], END_VIEW[3] - END_VIEW[1]) - 12),
                sheet_parts.preferred_scale(d_max, AXIAL_VIEW[3] - AXIAL_VIEW[1] - 20))
    length = float(data["overall_length"]) / float(from_mm(1.0, u))  # mm
    scale = min(scale, sheet_parts.preferred_scale(length, AXIAL_VIEW[2] - AXIAL_VIEW[0] - 30))
    phase = math.radians(data["tooth_phase_deg"])
    k = scale

    def views(sheet):
        # end view, from the small gear's end: +z towards the reader, counter-clockwise as drawn
        cx, cy = (END_VIEW[0] + END_VIEW[2]) / 2, (END_VIEW[1] + END_VIEW[3]) / 2
        polyline(sheet, sheet_parts.outline_points(lp, sheet_parts.OUTLINE_STEP_MM / k), (cx, cy), k, lw=0.18, color="0.35")
        polyline(sheet, _turned(sheet_parts.outline_points(sp, sheet_parts.OUTLINE_STEP_MM / k), phase), (cx, cy), k, lw=0.5)
        bore = sheet_parts.bore_points(large.hub)
        if bore is not None:
            polyline(sheet, np.vstack([bore, bore[:1]]), (cx, cy), k, lw=0.5)
        sheet_parts.centre_cross(sheet, cx, cy, lp.tip_radius * k + 4)
        r_out = max(lp.tip_radius, sp.tip_radius) * k + 6
        for angle, label in ((0.0, "large tooth 0"), (phase, "small tooth")):
            chain_line(sheet, [cx, cx + r_out * math.cos(angle)], [cy, cy + r_out * math.sin(angle)])
        sheet.text(cx + r_out + 1, cy, f"φ = {data['tooth_phase_deg']:.4f}°", 10, va="center")
        view_title(sheet, END_VIEW, f"End view from the small gear ({sheet_parts.scale_text(k)})")
        # axial section: the datum face (large gear's lower face) on the left, the axis horizontal
        ox = AXIAL_VIEW[0] + 18
        oy = (AXIAL_VIEW[1] + AXIAL_VIEW[3]) / 2
        rb = large.hub.bore_diameter / 2
        to_mm = lambda v: v / float(from_mm(1.0, u))  # noqa: E731 - the JSON's length back in mm
        faces = [(to_mm(data["large_face"][0]), to_mm(data["large_face"][1]), lp),
                 (to_mm(data["small_face"][0]), to_mm(data["small_face"][1]), sp)]
        for z0, z1, prof in faces:
            for sign in (1, -1):
                pts = np.array([(z0, rb), (z0, prof.tip_radius), (z1, prof.tip_radius), (z1, rb)]) * [1, sign]
                polyline(sheet, pts, (ox, oy), k)
                chain_line(sheet, [ox + z0 * k - 1, ox + z1 * k + 1], [oy + sign * prof.reference_radius * k] * 2)
        if faces[1][0] > faces[0][1]:  # the gap: the shaft or spacer between the faces
            r_gap = (data["spacer_diameter"] / 2 / float(from_mm(1.0, u))) if data["spacer_diameter"] else \
                min(lp.root_radius, sp.root_radius) * 0.9
            for sign in (1, -1):
                polyline(sheet, np.array([(faces[0][1], r_gap), (faces[1][0], r_gap)]) * [1, sign], (ox, oy), k)
        if rb > 0:
            for sign in (1, -1):
                polyline(sheet, np.array([(0.0, rb), (length, rb)]) * [1, sign], (ox, oy), k, lw=0.5)
        chain_line(sheet, [ox - 3, ox + length * k + 3], [oy, oy])
        y = oy - max(lp.tip_radius, sp.tip_radius) * k - 6
        for z0, z1, _ in faces:
            dimension(sheet, (ox + z0 * k, y), (ox + z1 * k, y), N(z1 - z0), vertical=False)
        dimension(sheet, (ox, y - 9), (ox + length * k, y - 9), N(length), vertical=False)
        sheet.text(ox, oy + max(lp.tip_radius, sp.tip_radius) * k + 3, "datum face", 10, ha="center", va="bottom")
        view_title(sheet, AXIAL_VIEW, f"Axial section ({sheet_parts.scale_text(k)})")

    rows = cluster_rows(data) + closing_rows(u, scale, version, source)
    return draw_sheet(data["name"], rows, views, design_file, u, scale, version)


def cluster_drawings(data: dict, large, small, folder, name: str, source: str, design_file: str) -> dict:
    """``name-drawing.svg``/``.pdf`` of the cluster into ``folder``, recorded in ``data["drawing"]``."""
    from geargen import __version__
    data["drawing"] = {"svg": f"{name}-drawing.svg", "pdf": f"{name}-drawing.pdf"}
    return write_figure(draw_cluster(data, large, small, source, design_file, __version__), folder, name)


__all__ = ["cluster_rows", "draw_cluster", "cluster_drawings"]
