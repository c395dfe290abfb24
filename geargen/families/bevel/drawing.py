"""The manufacturing drawing of a straight bevel gear: its axial half-sections (apex, cones, heel sphere,
back face and bore as built) with the mounting distance, outside diameter and face width dimensioned,
and the cone data, chordal tooth, accuracy grade and mate in the data block. Every value comes from
the gear's JSON dict (:func:`geargen.families.bevel.data.bevel_gear_data`)."""

from __future__ import annotations

import math

import numpy as np

from geargen.families.bevel.geometry import bevel_geometry, flat_back_envelope
from geargen.families.bevel.spec import BevelGearSpec
from geargen.families.bevel.geometry import back_plane_distance
from geargen.report.drawing import pitch_row, format_number, NOT_SPECIFIED, scale_text, write_figure
from geargen.report.drawing_sheet import (VIEWS, angle_text, chain_line, closing_rows, dimension, draw_sheet, fit_scale,
                                          polyline, value_text, view_title)
from geargen.units import from_mm


def bevel_rows(data: dict) -> list[tuple[str, str, str]]:
    """The data block of a bevel gear from its JSON dict (lengths in ``data["length_unit"]``)."""
    u = data["length_unit"]
    L = lambda v: value_text(v, u)  # noqa: E731 - one formatter for every length on the sheet
    acc = data.get("accuracy")
    mate = data.get("mating_gear")
    rows = [
        ("Number of teeth", "z", f"{data['teeth']}"),
        pitch_row(data["module_mm"], u, "Heel", "e"),
        ("Pressure angle", "α", angle_text(data["pressure_angle_deg"])),
        ("Shaft angle", "Σ", angle_text(data["shaft_angle_deg"])),
        ("Profile shift coefficient", "x", f"{data['profile_shift']:+.4f}"),
        ("Pitch cone angle", "δ", angle_text(data["pitch_cone_angle_deg"])),
        ("Face (tip) cone angle", "δ_a", angle_text(data["tip_cone_angle_deg"])),
        ("Root cone angle", "δ_f", angle_text(data["root_cone_angle_deg"])),
        ("Outer cone distance", "R_e", L(data["outer_cone_distance"])),
        ("Mean cone distance", "R_m", L(data["mean_cone_distance"])),
        ("Face width (along the cone)", "b", L(data["face_width"])),
        ("Reference diameter at the heel", "d_e", L(data["reference_diameter"])),
        ("Outside diameter as built", "d_ae", L(data["outside_diameter_as_built"])),
        ("Back", "", "flat: plane through the heel root circle" if data["back"] == "flat" else "heel sphere"),
        ("Mounting distance (apex to back)", "A", L(data["mounting_distance"])),
        ("Crown to back", "", L(data["crown_to_back"])),
        ("Heel sphere radius about the apex", "", L(data["heel_sphere_radius"])),
        ("Back face diameter", "", L(data["back_face_diameter"])),
        ("Heel chordal tooth thickness", "s_c", L(data["chordal_thickness_heel"])),
        ("Heel chordal height", "h_c", L(data["chordal_height_heel"])),
        ("Mean chordal tooth thickness", "s_cm", L(data["chordal_thickness_mean"])),
        ("Mean chordal height", "h_cm", L(data["chordal_height_mean"])),
        ("Thinning (arc at the heel pitch circle)", "", L(data["thinning_circumferential"])),
        ("Bore diameter", "", L(data["bore_diameter"]) if data["bore_diameter"] else "none"),
        ("Accuracy grade", "", f"{acc['standard']} grade {acc['grade']} (tolerance values not computed)"
         if acc else NOT_SPECIFIED),
        ("Mating gear", "", f"{mate['name']} ({mate['teeth']} teeth)" if mate else f"{data['mate_teeth']} teeth"),
        ("Pair backlash, heel pitch arc", "j_t",
         L(mate.get("backlash_circumferential")) if mate else NOT_SPECIFIED),
    ]
    return rows


def _half_section(spec: BevelGearSpec, points: int = 48) -> list[np.ndarray]:
    """(rho, z) outlines (mm) of the solid as built, z from the apex: the flat back's envelope
    (:func:`geargen.families.bevel.geometry.flat_back_envelope`) or, for a spherical back, toe sphere, tip cone,
    heel sphere and bore."""
    if spec.back == "flat":
        return flat_back_envelope(spec, points)
    g = bevel_geometry(spec)
    ri, re, da, rb = g.toe_cone_distance, g.cone_distance, g.tip_cone_angle, spec.bore_diameter / 2
    heel = np.linspace(da, math.asin(min(rb / re, 1.0)), points)
    toe = np.linspace(math.asin(min(rb / ri, 1.0)), da, points)
    outline = [(ri * math.sin(da), ri * math.cos(da))] + [(re * math.sin(p), re * math.cos(p)) for p in heel]
    outline += [(ri * math.sin(p), ri * math.cos(p)) for p in toe[:-1]]
    return [np.array(outline)]


def draw_bevel(data: dict, spec: BevelGearSpec, source: str, design_file: str, version: str):
    """The bevel gear's sheet (a :class:`geargen.report.drawing.Sheet`)."""
    u = data["length_unit"]
    g = bevel_geometry(spec)
    # apex to the back face along the axis (mm), as the JSON's mounting distance
    a_mm = back_plane_distance(spec) if spec.back == "flat" else g.cone_distance
    length_mm = max(g.cone_distance, a_mm) + 2.0
    scale = fit_scale(length_mm, g.solid_tip_diameter, VIEWS)
    N = lambda v_mm: format_number(from_mm(v_mm, u), u)  # noqa: E731

    def views(sheet):
        box = VIEWS
        k = scale
        # the axis horizontal, the apex on the left, the back on the right
        ox = box[0] + 15.0 + (box[2] - box[0] - 30.0 - length_mm * k) / 2
        oy = (box[1] + box[3]) / 2
        for outline in _half_section(spec):
            closed = np.vstack([outline, outline[:1]])
            for sign in (1, -1):
                polyline(sheet, np.column_stack([closed[:, 1], sign * closed[:, 0]]), (ox, oy), k)
        chain_line(sheet, [ox - 4, ox + (length_mm + 2) * k], [oy, oy])
        d = g.pitch_cone_angle
        for sign in (1, -1):  # pitch cone generators, apex to heel
            chain_line(sheet, [ox, ox + g.cone_distance * math.cos(d) * k],
                       [oy, oy + sign * g.cone_distance * math.sin(d) * k])
        y = oy - g.solid_tip_diameter / 2 * k - 8
        dimension(sheet, (ox, y), (ox + a_mm * k, y), f"A = {N(a_mm)}", vertical=False)
        for x in (ox, ox + a_mm * k):
            sheet.line([x, x], [y - 1.5, oy - 1], lw=0.18)
        x_crown = ox + g.solid_apex_to_crown * k
        r_tip = g.solid_tip_diameter / 2 * k
        x_dim = ox + (length_mm + 1) * k + 4
        dimension(sheet, (x_dim, oy - r_tip), (x_dim, oy + r_tip), f"⌀{N(g.solid_tip_diameter)}", vertical=True)
        for sign in (1, -1):
            sheet.line([x_crown, x_dim + 1.5], [oy + sign * r_tip, oy + sign * r_tip], lw=0.18)
        sheet.text(ox - 2, oy + 2, "apex", 10, ha="right", va="bottom")
        view_title(sheet, box, f"Axial section through the apex, teeth unsectioned ({scale_text(k)})")

    rows = bevel_rows(data) + closing_rows(u, scale, version, source)
    return draw_sheet(data["name"], rows, views, design_file, u, scale, version)


def bevel_drawings(data: dict, spec: BevelGearSpec, folder, name: str, source: str, design_file: str) -> dict:
    """``name-drawing.svg``/``.pdf`` of the bevel gear into ``folder``, their names recorded in
    ``data["drawing"]`` first (the JSON lists them). Returns ``{"svg"|"pdf": path}``."""
    from geargen import __version__
    data["drawing"] = {"svg": f"{name}-drawing.svg", "pdf": f"{name}-drawing.pdf"}
    return write_figure(draw_bevel(data, spec, source, design_file, __version__), folder, name)


__all__ = ["bevel_rows", "draw_bevel", "bevel_drawings"]
