"""A rack's data as ``geargen gear --kind rack`` writes it to ``<name>.json`` (lengths in the rack's
length unit, angles in degrees), the keys of the gear-data contract that apply plus the rack's own."""

from __future__ import annotations

import math

from geargen.core.rack import normal_section_area_per_pitch, rack_outline, rack_volume
from geargen.design.rack import RackSpec
from geargen.units import from_mm


def rack_data(spec: RackSpec) -> dict:
    u = spec.length_unit

    def L(v):
        return float(from_mm(v, u))

    outline = rack_outline(spec)
    return {
        "name": spec.name, "kind": "rack", "length_unit": u, "teeth": spec.teeth,
        "normal_module_mm": spec.module, "transverse_module_mm": spec.transverse_module,
        "normal_pressure_angle_deg": math.degrees(spec.pressure_angle),
        "transverse_pressure_angle_deg": math.degrees(spec.transverse_pressure_angle),
        "helix_angle_deg": math.degrees(spec.helix_angle), "hand": spec.hand if spec.is_helical else None,
        "basic_rack": {"addendum_coefficient": spec.addendum_coefficient,
                       "dedendum_coefficient": spec.dedendum_coefficient,
                       "tip_rounding": spec.tip_rounding, "tip_radius_coefficient": spec.tip_radius_coefficient,
                       "root_fillet_coefficient": spec.root_fillet_coefficient},
        "face_width": L(spec.face_width), "length": L(spec.length),
        "normal_pitch": L(spec.normal_pitch), "transverse_pitch": L(spec.transverse_pitch),
        "pitch_line_height": L(spec.pitch_line_height), "back_height": L(spec.back_height),
        "height": L(spec.height),
        "normal_tooth_thickness_at_pitch_line": L(spec.normal_tooth_thickness),
        "transverse_tooth_thickness_at_pitch_line": L(spec.normal_tooth_thickness / math.cos(spec.helix_angle)),
        "thinning_circumferential": L(spec.thinning),
        "tip_land_normal": L(2 * (outline.pitch / 2 - outline.tip_land_start)),
        "root_land_normal": L(2 * outline.root_land_half),
        "straight_flank_heights_from_pitch_line": [L(outline.flank_root_u), L(outline.flank_tip_u)],
        "normal_section_area_per_pitch": float(from_mm(from_mm(normal_section_area_per_pitch(spec), u), u)),
        "volume": float(from_mm(from_mm(from_mm(rack_volume(spec), u), u), u)),
        "warnings": [],
    }
