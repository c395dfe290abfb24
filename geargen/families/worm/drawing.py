"""The manufacturing drawings of a worm and of its worm wheel (one sheet each).

Worm: the axial section (the ZA thread's straight-sided axial profile above and below the axis over
the thread length) with tip and root diameters and the length dimensioned; data block with lead,
lead angle, axial pitch, thread thickness (axial and normal), the mate and the pair's centre distance
and backlash. Wheel: the section through its axis in the worm's plane (the throated rim, the root
the hob cuts) with outside, throat and root diameters and face width; data block with its tooth
thickness, the mate, and the hob's data. Every value from the part's JSON dict
(:func:`geargen.families.worm.data.worm_part_data`)."""

from __future__ import annotations

import math

import numpy as np

from geargen.families.worm.geometry import rim_radius, worm_geometry
from geargen.report.drawing import pitch_row, pitch_rows, format_number, NOT_SPECIFIED, scale_text, write_figure
from geargen.report.drawing_sheet import (VIEWS, angle_text, chain_line, closing_rows, dimension, draw_sheet, fit_scale,
                                          polyline, value_text, view_title)
from geargen.units import from_mm


def _set_rows(data: dict) -> list[tuple[str, str, str]]:
    u = data["length_unit"]
    L = lambda v: value_text(v, u)  # noqa: E731
    check = data.get("pair_check")
    return [
        ("Centre distance", "a", L(data["centre_distance"])),
        ("Design backlash (arc at wheel d)", "j_t", f"{L(data['backlash_circumferential'])} on the "
                                                      f"{data['backlash_on'].replace('_', ' ')}"),
        ("Backlash, pair check", "", f"{L(check['backlash_circumferential'])}" +
         (", interference" if check["interference"] else "") if check else NOT_SPECIFIED),
    ]


def worm_rows(data: dict) -> list[tuple[str, str, str]]:
    u = data["length_unit"]
    L = lambda v: value_text(v, u)  # noqa: E731 - one formatter for every length on the sheet
    return [
        ("Worm type", "", data["worm_type"]),
        ("Number of starts", "z_1", f"{data['starts']}"),
        *pitch_rows(data["axial_module_mm"], u, "Axial", "x"),
        *pitch_rows(data["normal_module_mm"], u),
        ("Normal pressure angle", "α_n", angle_text(data["normal_pressure_angle_deg"])),
        ("Axial pressure angle", "α_x", angle_text(data["axial_pressure_angle_deg"])),
        ("Hand", "", data["hand"]),
        ("Lead angle", "γ", angle_text(data["lead_angle_deg"])),
        ("Lead", "p_z", L(data["lead"])),
        ("Axial pitch", "p_x", L(data["axial_pitch"])),
        ("Diameter quotient", "q", f"{data['diameter_quotient']:.6g}"),
        ("Reference diameter", "d_1", L(data["worm_reference_diameter"])),
        ("Tip diameter", "d_a1", L(data["worm_tip_diameter"])),
        ("Root diameter", "d_f1", L(data["worm_root_diameter"])),
        ("Thread length", "b_1", L(data["worm_face_length"])),
        ("Axial thread thickness at d_1", "s_x1", L(data["worm_axial_thread_thickness"])),
        ("Normal thread thickness at d_1", "s_n1", L(data["worm_normal_thread_thickness"])),
        ("Addendum (tip to d_1)", "h_a1", L(data["worm_addendum"])),
        ("Accuracy grade", "", NOT_SPECIFIED),
        ("Mating wheel", "z_2", f"{data['wheel_teeth']} teeth"),
    ] + _set_rows(data)


def wheel_rows(data: dict) -> list[tuple[str, str, str]]:
    u = data["length_unit"]
    L = lambda v: value_text(v, u)  # noqa: E731
    hob = data["hob"]
    return [
        ("Number of teeth", "z_2", f"{data['wheel_teeth']}"),
        pitch_row(data["axial_module_mm"], u, "Transverse", "t"),  # = the worm's axial pitch
        ("Transverse pressure angle (= α_x)", "α_t", angle_text(data["axial_pressure_angle_deg"])),
        ("Hand and lead angle", "γ", f"{data['hand']}, {angle_text(data['lead_angle_deg'])}"),
        ("Profile shift coefficient", "x_2", f"{data['wheel_profile_shift']:+.4f}"),
        ("Reference diameter", "d_2", L(data["wheel_reference_diameter"])),
        ("Throat diameter", "d_a2", L(data["throat_diameter"])),
        ("Throat radius", "r_i", L(data["throat_radius"])),
        ("Outside diameter", "d_e2", L(data["wheel_outside_diameter"])),
        ("Root diameter", "d_f2", L(data["wheel_root_diameter"])),
        ("Face width", "b_2", L(data["wheel_face_width"])),
        ("Tooth thickness at d_2, mid plane", "s_t2", L(data["wheel_tooth_thickness_transverse"])),
        ("Thinning for backlash", "", L(data["wheel_thinning"])),
        ("Accuracy grade", "", NOT_SPECIFIED),
        ("Mating worm", "z_1", f"{data['starts']} starts, d_1 {L(data['worm_reference_diameter'])}"),
    ] + _set_rows(data) + [
        ("Hob", "", hob["what"]),
        ("Hob reference diameter", "", L(hob["reference_diameter"])),
        ("Hob tip diameter", "", L(hob["tip_diameter"])),
        ("Hob tip clearance", "c", L(hob["tip_clearance"])),
        ("Hob lead", "", L(hob["lead"])),
        ("Hob axial thread thickness", "", L(hob["axial_thread_thickness"])),
        ("Hob normal thread thickness", "", L(hob["normal_thread_thickness"])),
        ("Hob root diameter, at most", "", L(hob["root_diameter_max"])),
    ]


def thread_section(spec, side: int, samples: int = 1601) -> np.ndarray:
    """(x, r) of the worm's axial section on one side of the axis (mm): the ZA thread, whose axial
    profile is straight with flank angle alpha_x; the side below the axis (``side`` -1) sees the
    thread half a lead further on."""
    s = spec.set
    g = worm_geometry(s)
    half = s.worm_face_length / 2
    x = np.linspace(-half, half, samples)
    shift = 0.0 if side > 0 else (g.lead / 2) % g.axial_pitch
    off = np.abs((x - shift + g.axial_pitch / 2) % g.axial_pitch - g.axial_pitch / 2)  # to the thread centre
    r1 = g.worm_reference_diameter / 2
    r = r1 + (g.worm_axial_thickness / 2 - off) / math.tan(g.axial_pressure_angle)
    r = np.clip(r, g.worm_root_diameter / 2, g.worm_tip_diameter / 2)
    return np.column_stack([x, r])


def _worm_views(spec, data, scale):
    g = worm_geometry(spec.set)
    u = data["length_unit"]
    N = lambda v: format_number(from_mm(v, u), u)  # noqa: E731

    def views(sheet):
        box = VIEWS
        k = scale
        cx, cy = (box[0] + box[2]) / 2, (box[1] + box[3]) / 2
        half = spec.set.worm_face_length / 2
        for side in (1, -1):
            pts = thread_section(spec, side)
            ends = np.array([[-half, 0.0], *pts, [half, 0.0]])
            polyline(sheet, ends * [1, side], (cx, cy), k)
            chain_line(sheet, [cx - half * k - 2, cx + half * k + 2], [cy + side * g.worm_reference_diameter / 2 * k] * 2)
        chain_line(sheet, [cx - half * k - 5, cx + half * k + 5], [cy, cy])
        for i, dia in enumerate((g.worm_root_diameter, g.worm_tip_diameter)):
            x = cx - half * k - 8 - 9 * i
            dimension(sheet, (x, cy - dia / 2 * k), (x, cy + dia / 2 * k), f"⌀{N(dia)}", vertical=True)
        y = cy - g.worm_tip_diameter / 2 * k - 8
        dimension(sheet, (cx - half * k, y), (cx + half * k, y), N(spec.set.worm_face_length), vertical=False)
        view_title(sheet, box, f"Axial section of the worm ({scale_text(k)})")
    return views


def wheel_section(spec, samples: int = 401) -> tuple[np.ndarray, np.ndarray]:
    """(z, r) of the wheel's rim and root in the plane through its axis and the worm's (mm): the rim
    the throat torus capped by the outside cylinder (:func:`geargen.families.worm.geometry.rim_radius`), the root
    the torus the hob's tip cuts (minor radius the hob tip radius about the worm axis)."""
    g = worm_geometry(spec.set)
    z = np.linspace(-spec.set.wheel_face_width / 2, spec.set.wheel_face_width / 2, samples)
    rim = rim_radius(g, z)
    root = g.centre_distance - np.sqrt(np.maximum(g.hob_tip_radius ** 2 - z * z, 0.0))
    return np.column_stack([z, rim]), np.column_stack([z, root])


def _wheel_views(spec, data, scale):
    g = worm_geometry(spec.set)
    u = data["length_unit"]
    N = lambda v: format_number(from_mm(v, u), u)  # noqa: E731

    def views(sheet):
        box = VIEWS
        k = scale
        cx, cy = (box[0] + box[2]) / 2, (box[1] + box[3]) / 2
        rim, root = wheel_section(spec)
        half = spec.set.wheel_face_width / 2
        for side in (1, -1):
            outline = np.vstack([[[-half, 0.0]], rim, [[half, 0.0]]])
            polyline(sheet, outline * [1, side], (cx, cy), k)
            polyline(sheet, root * [1, side], (cx, cy), k, lw=0.18, linestyle=(0, (1, 1)))
            chain_line(sheet, [cx - half * k - 2, cx + half * k + 2], [cy + side * g.wheel_reference_diameter / 2 * k] * 2)
        chain_line(sheet, [cx, cx], [cy - g.wheel_outside_diameter / 2 * k - 4, cy + g.wheel_outside_diameter / 2 * k + 4])
        dims = (g.wheel_root_diameter, g.throat_diameter, g.wheel_outside_diameter)
        for i, dia in enumerate(dims):
            x = cx - half * k - 8 - 9 * i
            dimension(sheet, (x, cy - dia / 2 * k), (x, cy + dia / 2 * k), f"⌀{N(dia)}", vertical=True)
        y = cy - g.wheel_outside_diameter / 2 * k - 8
        dimension(sheet, (cx - half * k, y), (cx + half * k, y), N(spec.set.wheel_face_width), vertical=False)
        view_title(sheet, box, f"Section through the wheel axis, in the worm's plane ({scale_text(k)})")
    return views


def draw_worm_part(data: dict, spec, source: str, design_file: str, version: str):
    """The worm's or the wheel's sheet (a :class:`geargen.report.drawing.Sheet`)."""
    g = worm_geometry(spec.set)
    u = data["length_unit"]
    if spec.kind == "worm":
        scale = fit_scale(spec.set.worm_face_length + 40, g.worm_tip_diameter, VIEWS)
        views, rows = _worm_views(spec, data, scale), worm_rows(data)
    else:
        scale = fit_scale(spec.set.wheel_face_width + 40, g.wheel_outside_diameter, VIEWS)
        views, rows = _wheel_views(spec, data, scale), wheel_rows(data)
    return draw_sheet(data["name"], rows + closing_rows(u, scale, version, source), views, design_file, u, scale,
                      version)


def worm_drawings(data: dict, spec, folder, name: str, source: str, design_file: str) -> dict:
    """``name-drawing.svg``/``.pdf`` of the worm or wheel into ``folder``, recorded in ``data["drawing"]``."""
    from geargen import __version__
    data["drawing"] = {"svg": f"{name}-drawing.svg", "pdf": f"{name}-drawing.pdf"}
    return write_figure(draw_worm_part(data, spec, source, design_file, __version__), folder, name)


__all__ = ["worm_rows", "wheel_rows", "thread_section", "wheel_section", "draw_worm_part", "worm_drawings"]
