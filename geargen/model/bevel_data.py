"""A straight bevel gear's data as ``geargen gear`` writes it to ``<name>.json`` (gear-data contract keys
that apply, and the bevel family's own), lengths in the gear's length unit, angles in degrees."""

from __future__ import annotations

import math

from geargen.core.bevel import bevel_geometry, spherical_contact_ratio, virtual_contact_ratio
from geargen.design.bevel import BevelGearSpec
from geargen.units import from_mm


def bevel_gear_data(spec: BevelGearSpec) -> dict:
    g = bevel_geometry(spec)
    u = spec.length_unit

    def L(v):
        return float(from_mm(v, u))

    return {
        "name": spec.name, "kind": "bevel", "length_unit": u, "teeth": spec.teeth, "mate_teeth": spec.mate_teeth,
        "shaft_angle_deg": math.degrees(spec.shaft_angle), "module_mm": spec.module,
        "pressure_angle_deg": math.degrees(spec.pressure_angle), "profile_shift": spec.profile_shift,
        "tooth_form": "spherical involute (base cone sin delta_b = sin delta cos alpha); standard addendum and "
                      "dedendum at the heel, tip and root cones through the apex (no constant clearance); "
                      "no root fillet; spherical toe and heel",
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
                     "solid_apex_to_back": L(g.solid_apex_to_back),
                     "solid_crown_to_back": L(g.solid_crown_to_back)},
        "virtual_teeth": g.virtual_teeth if math.isfinite(g.virtual_teeth) else None,
        "virtual_contact_ratio": (virtual_contact_ratio(spec) if max(g.pitch_cone_angle, g.mate_pitch_cone_angle)
                                  < math.radians(89.9) else None),
        # the pair's own, on the great circle of action (mate: the same proportions with shift -x)
        "spherical_contact_ratio": (spherical_contact_ratio(spec) if max(g.pitch_cone_angle, g.mate_pitch_cone_angle)
                                    < math.radians(89.9) else None),
        "warnings": list(g.warnings),
    }
