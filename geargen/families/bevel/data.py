"""A straight bevel gear's data as ``geargen gear`` writes it to ``<name>.json`` (gear-data contract keys
that apply, and the bevel family's own), lengths in the gear's length unit, angles in degrees."""

from __future__ import annotations

import math

from geargen.families.bevel.geometry import (back_plane_distance, bevel_geometry, chordal_tooth, spherical_contact_ratio,
                                virtual_contact_ratio)
from geargen.families.bevel.spec import BevelGearSpec
from geargen.units import from_mm


#: ISO 17485 accuracy grades are accepted and recorded; their tolerance values are not computed. Searched
#: again 2026-11 (issue 27): the public abstracts (NEN, SAI Global, iTeh) give the scope (grades 2..11,
#: 1 <= m_mn <= 50 mm, 5 <= z <= 400, 5 <= d_T <= 2500 mm) and name the equations of clause 5.4, but no
#: citable text of those equations nor of the tolerance diameter d_T, nor of ANSI/AGMA 2009-B01's 7.2, was found
ACCURACY_NOTE = ("ISO 17485 tolerance values not computed: the standard's tolerance equations could not be "
                 "established from a citable source; the grade is stated for the shop to apply")


def back_data(spec: BevelGearSpec) -> dict:
    """The back and heel of the solid as built (mm): a flat back is the plane through the heel root
    circle, R_e cos delta_f from the apex; a spherical back is the heel sphere (its pole R_e from the
    apex). The mounting distance is the apex to the back face along the axis; the heel of the teeth
    is the sphere R_e about the apex from the tip cone to the root cone in both cases (no back cone)."""
    g = bevel_geometry(spec)
    re = g.cone_distance
    apex_to_back = back_plane_distance(spec) if spec.back == "flat" else re
    return {"back": spec.back, "mounting_distance": apex_to_back,
            "crown_to_back": apex_to_back - re * math.cos(g.tip_cone_angle),
            "heel_sphere_radius": re, "back_face_diameter": 2 * re * math.sin(g.root_cone_angle)
            if spec.back == "flat" else None}


def bevel_gear_data(spec: BevelGearSpec) -> dict:
    g = bevel_geometry(spec)
    u = spec.length_unit

    def L(v):
        return None if v is None else float(from_mm(v, u))

    back = back_data(spec)
    heel, mean = chordal_tooth(spec, g.cone_distance), chordal_tooth(spec, g.mean_cone_distance)
    return {
        "name": spec.name, "kind": "bevel", "length_unit": u, "teeth": spec.teeth, "mate_teeth": spec.mate_teeth,
        "shaft_angle_deg": math.degrees(spec.shaft_angle), "module_mm": spec.module,
        "pressure_angle_deg": math.degrees(spec.pressure_angle), "profile_shift": spec.profile_shift,
        "tooth_form": "spherical involute (base cone sin delta_b = sin delta cos alpha); standard addendum and "
                      "dedendum at the heel, tip and root cones through the apex (no constant clearance); "
                      "no root fillet; spherical toe and heel sphere; back "
                      + ("flat (the plane through the heel root circle)" if spec.back == "flat" else "the heel sphere"),
        "back": spec.back,
        "face_width": L(spec.face_width), "bore_diameter": L(spec.bore_diameter),
        "thinning_circumferential": L(spec.thinning),
        "pitch_cone_angle_deg": math.degrees(g.pitch_cone_angle),
        "mate_pitch_cone_angle_deg": math.degrees(g.mate_pitch_cone_angle),
        "base_cone_angle_deg": math.degrees(g.base_cone_angle),
        "tip_cone_angle_deg": math.degrees(g.tip_cone_angle), "root_cone_angle_deg": math.degrees(g.root_cone_angle),
        "addendum_angle_deg": math.degrees(g.addendum_angle), "dedendum_angle_deg": math.degrees(g.dedendum_angle),
        "outer_cone_distance": L(g.cone_distance), "inner_cone_distance": L(g.toe_cone_distance),
        "mean_cone_distance": L(g.mean_cone_distance),
        "addendum": L(spec.addendum), "dedendum": L(spec.dedendum),
        "reference_diameter": L(g.reference_diameter), "tip_diameter": L(g.tip_diameter),
        "root_diameter": L(g.root_diameter),
        "mounting": {"apex_to_crown": L(g.apex_to_crown), "axial_face_width": L(g.axial_face_width),
                     "solid_tip_diameter": L(g.solid_tip_diameter), "solid_apex_to_crown": L(g.solid_apex_to_crown),
                     "solid_apex_to_back": L(back["mounting_distance"]),
                     "solid_crown_to_back": L(back["crown_to_back"])},
        # the solid as built: its back, mounting distance (apex to back face) and heel (core.bevel)
        "mounting_distance": L(back["mounting_distance"]), "crown_to_back": L(back["crown_to_back"]),
        "heel_sphere_radius": L(back["heel_sphere_radius"]), "back_face_diameter": L(back["back_face_diameter"]),
        "outside_diameter_as_built": L(g.solid_tip_diameter), "apex_to_crown_as_built": L(g.solid_apex_to_crown),
        # the back-cone (Tredgold) equivalent the chordal rule of thumb uses: not a surface of the solid
        "back_cone": {"angle_deg": 90.0 - math.degrees(g.pitch_cone_angle),
                      "distance": L(g.virtual_reference_radius) if math.isfinite(g.virtual_reference_radius) else None,
                      "surface_of_the_solid": False},
        "chordal_thickness_heel": L(heel.thickness), "chordal_height_heel": L(heel.height),
        "chordal_thickness_mean": L(mean.thickness), "chordal_height_mean": L(mean.height),
        "chordal_definition": "on the sphere about the apex (heel: R_e, mean: R_e - b/2): the chord between the "
                              "flanks on the pitch cone, and the crown (tip cone, tooth centre) to that chord's midpoint",
        "accuracy": None if spec.accuracy_grade is None else
        {"standard": "ISO 17485", "grade": spec.accuracy_grade, "tolerances": ACCURACY_NOTE},
        "virtual_teeth": g.virtual_teeth if math.isfinite(g.virtual_teeth) else None,
        "virtual_contact_ratio": (virtual_contact_ratio(spec) if max(g.pitch_cone_angle, g.mate_pitch_cone_angle)
                                  < math.radians(89.9) else None),
        # the pair's own, on the great circle of action (mate: the same proportions with shift -x)
        "spherical_contact_ratio": (spherical_contact_ratio(spec) if max(g.pitch_cone_angle, g.mate_pitch_cone_angle)
                                    < math.radians(89.9) else None),
        "warnings": list(g.warnings),
    }
