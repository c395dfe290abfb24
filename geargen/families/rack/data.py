"""A rack's data as ``geargen gear --kind rack`` writes it to ``<name>.json`` (lengths in the rack's
length unit, angles in degrees), the keys of the gear-data contract that apply plus the rack's own."""

from __future__ import annotations

import math

from geargen.families.rack.geometry import (normal_section_area_per_pitch, over_pin_to_back, pin_contact_height,
                               pitch_line_pin_diameter, rack_outline, rack_volume, standard_rack_pin)
from geargen.families.rack.spec import RackSpec
from geargen.units import from_mm


def rack_inspection(spec: RackSpec) -> dict:
    """What a shop measures on the rack (mm): the normal tooth thickness at the pitch line and the
    dimension from the back face over a pin (a ball on a helical rack) in a tooth space, each for the
    model's thinning and at the limits of the allowance (when the rack states one). The pin is the
    series' size nearest the one touching the zero-backlash tooth at the pitch line
    (:func:`geargen.families.rack.geometry.standard_rack_pin`); every contact must lie on the
    straight flank, else a warning."""
    outline = rack_outline(spec)
    model = -spec.thinning_normal
    deviations = {"model": model}
    if spec.thickness_deviations is not None:
        deviations |= {"upper": spec.thickness_deviations[0], "lower": spec.thickness_deviations[1]}
    pin, series = standard_rack_pin(spec, deviations.values())
    warnings = []
    for name, dev in deviations.items():
        contact = pin_contact_height(spec, pin, dev)[1]
        if not outline.flank_root_u <= contact <= outline.flank_tip_u:
            warnings.append(f"the pin touches the {name} tooth at {contact:.6g} mm from the pitch line, off its "
                            f"straight flank [{outline.flank_root_u:.6g}, {outline.flank_tip_u:.6g}] mm")
    out = {"thickness_nominal": spec.normal_pitch / 2, "thickness_model": spec.normal_pitch / 2 + model,
           "pin_diameter": pin, "pin_series": series, "over_pin_model": over_pin_to_back(spec, pin, model), "warnings": warnings}
    if spec.thickness_deviations is not None:
        upper, lower = spec.thickness_deviations
        out["thickness_limits"] = [spec.normal_pitch / 2 + lower, spec.normal_pitch / 2 + upper]
        out["over_pin_limits"] = [over_pin_to_back(spec, pin, lower), over_pin_to_back(spec, pin, upper)]
        if not lower - 1e-12 <= model <= upper + 1e-12:
            warnings.append(f"the model's thinning {-model:.6g} mm (normal) is outside the allowance "
                            f"[{-upper:.6g}, {-lower:.6g}] mm")
    return out


def rack_data(spec: RackSpec) -> dict:
    u = spec.length_unit

    def L(v):
        return float(from_mm(v, u))

    outline = rack_outline(spec)
    shop = rack_inspection(spec)
    allowance = spec.thickness_deviations
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
        "thickness_allowance": None if allowance is None else
        {"upper_um": allowance[0] * 1e3, "lower_um": allowance[1] * 1e3,
         "method": "entered: normal deviations at the pitch line from the zero-backlash tooth p_n/2"},
        "tooth_thickness_normal_zero_backlash": L(shop["thickness_nominal"]),
        "tooth_thickness_normal_model": L(shop["thickness_model"]),
        "tooth_thickness_normal_limits": None if allowance is None else [L(v) for v in shop["thickness_limits"]],
        "over_pin": {"kind": "ball" if spec.is_helical else "pin", "diameter": L(shop["pin_diameter"]),
                     "series": shop["pin_series"], "ideal_diameter": L(pitch_line_pin_diameter(spec)),
                     "section": "normal" if spec.is_helical else "transverse",
                     "dimension_to_back": L(shop["over_pin_model"]),
                     "limits": None if allowance is None else [L(v) for v in shop["over_pin_limits"]],
                     "note": "back face to the top of the pin resting in a tooth space; the pin touches the "
                             "series' size nearest the ideal_diameter (the pin touching the zero-backlash tooth at the pitch line)"},
        "warnings": shop["warnings"],
    }
