"""The gear data of a worm or worm wheel (``geargen gear --kind worm|worm_wheel``'s JSON).

Lengths in the set's length unit; the set's derived dimensions (geargen.core.worm) are written for
both parts, so the two JSONs of a set agree on the centre distance, lead and throat."""

from __future__ import annotations

import math

from geargen.core.worm import worm_geometry
from geargen.units import from_mm


def worm_part_data(spec) -> dict:
    s = spec.set
    g = worm_geometry(s)
    u = s.length_unit

    def L(v):
        return None if v is None else float(from_mm(v, u))

    return {
        "name": spec.name, "kind": spec.kind, "length_unit": u, "worm_type": "ZA (DIN 3975: straight axial profile, "
        "Archimedean helicoid)", "starts": s.starts, "wheel_teeth": s.wheel_teeth, "ratio": g.ratio,
        "axial_module_mm": s.axial_module, "normal_module_mm": g.normal_module,
        "diameter_quotient": s.diameter_quotient, "hand": s.hand,
        "normal_pressure_angle_deg": math.degrees(g.normal_pressure_angle),
        "axial_pressure_angle_deg": math.degrees(g.axial_pressure_angle),
        "lead_angle_deg": math.degrees(g.lead_angle), "lead": L(g.lead), "axial_pitch": L(g.axial_pitch),
        "centre_distance": L(g.centre_distance), "wheel_profile_shift": s.wheel_profile_shift,
        "worm_reference_diameter": L(g.worm_reference_diameter), "worm_tip_diameter": L(g.worm_tip_diameter),
        "worm_root_diameter": L(g.worm_root_diameter), "worm_face_length": L(s.worm_face_length),
        "wheel_reference_diameter": L(g.wheel_reference_diameter), "throat_diameter": L(g.throat_diameter),
        "throat_radius": L(g.throat_radius), "wheel_root_diameter": L(g.wheel_root_diameter),
        "wheel_outside_diameter": L(g.wheel_outside_diameter), "wheel_face_width": L(s.wheel_face_width),
        "worm_axial_thread_thickness": L(g.worm_axial_thickness),
        "backlash_circumferential": L(s.backlash), "backlash_on": s.backlash_on,
        "warnings": [],
    }


__all__ = ["worm_part_data"]
