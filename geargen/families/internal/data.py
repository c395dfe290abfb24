"""An internal gear's data as ``geargen gear --kind internal`` writes it to ``<name>.json``.

The gear-data contract's keys that apply to a ring, with the same meaning (radii of the ring's
own circles: its tip circle is the inner one), and the ring's own: rim, form radius (where the
cutter-generated fillet meets the involute), the shaper cutter the root was generated with, the
space width, and the between-pins dimension of a spur ring. Lengths in the gear's ``length_unit``.
"""

from __future__ import annotations

import math

from geargen.core.involute import involute, inverse_involute
from geargen.design.gear import GearSpec
from geargen.profile.internal import InternalProfile, internal_profile, space_width
from geargen.units import from_mm


def reference_pin_diameter(spec: GearSpec) -> float:
    """Pin diameter (mm) that touches the ring's flanks at the reference circle (transverse).

    A pin in the space touches both flanks where their normals - tangent to the base circle - pass
    through its centre; its centre lies on the involute parallel to the flank, ``d_p / 2`` inside
    the space: ``inv(a_M) = psi_b - d_p / (2 r_b)`` and the contact roll length is
    ``r_b tan(a_M) + d_p / 2``. Contact at the reference circle: ``r_b tan(a_M) + d_p / 2 = r_b tan(a_t)``.
    """
    rb = spec.base_radius
    psi_b = space_width(spec) / (2 * spec.reference_radius) + involute(spec.transverse_pressure_angle)
    target = rb * math.tan(spec.transverse_pressure_angle)

    def excess(d):
        inv = psi_b - d / (2 * rb)
        return rb * math.tan(inverse_involute(max(inv, 0.0))) + d / 2 - target

    lo, hi = 0.0, 2 * rb * psi_b  # at hi the pin centre reaches the base circle
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if excess(mid) > 0:  # the excess falls as the pin grows (its centre moves in faster than d / 2)
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def between_pins(spec: GearSpec, pin_diameter: float) -> float:
    """Between-pins dimension (mm) of a spur ring: the smallest distance between two pins in opposite
    spaces (odd teeth: the spaces nearest opposite). ``inv(a_M) = psi_b - d_p / (2 r_b)``, pin centre
    radius ``r_b / cos(a_M)``; ``M = 2 R_M - d_p`` (even), ``2 R_M cos(pi / (2 z)) - d_p`` (odd)."""
    rb = spec.base_radius
    psi_b = space_width(spec) / (2 * spec.reference_radius) + involute(spec.transverse_pressure_angle)
    centre = rb / math.cos(inverse_involute(psi_b - pin_diameter / (2 * rb)))
    factor = 1.0 if spec.teeth % 2 == 0 else math.cos(math.pi / (2 * spec.teeth))
    return 2 * centre * factor - pin_diameter


def internal_gear_data(spec: GearSpec, profile: InternalProfile | None = None) -> dict:
    """Radii, rim, space and tooth thickness, cutter and between-pins size of a ring."""
    profile = profile or internal_profile(spec)
    u = spec.length_unit

    def L(v):
        return None if v is None else float(from_mm(v, u))

    e = space_width(spec)
    out = {
        "name": spec.name, "kind": "internal", "length_unit": u, "teeth": spec.teeth,
        "normal_module_mm": spec.module, "transverse_module_mm": spec.transverse_module,
        "normal_pressure_angle_deg": math.degrees(spec.pressure_angle),
        "transverse_pressure_angle_deg": math.degrees(spec.transverse_pressure_angle),
        "helix_angle_deg": math.degrees(spec.helix_angle), "hand": spec.hand if spec.is_helical else None,
        "lead": L(spec.lead) if spec.is_helical else None,
        "profile_shift_normal": spec.profile_shift,
        "profile_shift_convention": "ISO 21771 / KHK: x > 0 moves the profile away from the axis "
                                    "(tip radius r - m_n (h_a* - x))",
        "face_width": L(spec.face_width), "rim_diameter": L(spec.rim_diameter),
        "reference_radius": L(profile.reference_radius), "base_radius": L(profile.base_radius),
        "tip_radius": L(profile.tip_radius), "root_radius": L(profile.root_radius),
        "root_radius_nominal": L(spec.root_radius_standard), "form_radius": L(profile.form_radius),
        "reference_space_width_transverse": L(e),
        "reference_tooth_thickness_transverse": L(spec.transverse_pitch - e),
        "thinning_circumferential": L(spec.thinning),
        "tip_land_transverse": L(profile.tip_land),
        "shaper_cutter": {"teeth": profile.cutter_teeth, "addendum_coefficient": spec.dedendum_coefficient,
                          "tip_radius_coefficient": spec.rack_tip_radius_coefficient, "profile_shift": 0.0},
        "warnings": list(profile.warnings),
    }
    if not spec.is_helical:
        d_p = reference_pin_diameter(spec)
        out["between_pins"] = {"pin_diameter": L(d_p), "dimension": L(between_pins(spec, d_p))}
    return out


__all__ = ["internal_gear_data", "between_pins", "reference_pin_diameter"]
