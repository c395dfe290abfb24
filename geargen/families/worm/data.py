"""The gear data of a worm or worm wheel (``geargen gear --kind worm|worm_wheel``'s JSON).

Lengths in the set's length unit; the set's derived dimensions (geargen.families.worm.geometry) are written for
both parts, so the two JSONs of a set agree on the centre distance, lead and throat."""

from __future__ import annotations

import math

from geargen.families.worm.geometry import worm_geometry
from geargen.units import from_mm


def wheel_tooth_thickness(s, g) -> float:
    """Transverse arc tooth thickness of the wheel at its reference circle in the mid plane (mm): there
    the worm's straight-sided axial section generates it as a rack of module m_x and pressure angle
    alpha_x whose reference line lies x2 m_x outside the reference circle, and the wheel's thinning
    takes the backlash off it: s_t2 = m_x (pi / 2 + 2 x2 tan alpha_x) - thinning."""
    m = s.axial_module
    return m * (math.pi / 2 + 2 * s.wheel_profile_shift * math.tan(g.axial_pressure_angle)) - g.wheel_thinning


def hob_data(s, g) -> dict:
    """The hob that cuts the wheel (mm): the worm's thread (starts, lead, hand, reference diameter,
    axial profile) at its nominal thickness p_x / 2 (a worm thinned for backlash is not the hob) and
    with its tip raised by the tip clearance c = (h_f* - h_a*) m_x, so it cuts the wheel's root; its
    root must clear the wheel's throat (the largest root diameter that does: 2 r_throat)."""
    return {"starts": s.starts, "hand": s.hand, "lead": g.lead, "lead_angle": g.lead_angle,
            "reference_diameter": g.worm_reference_diameter, "tip_diameter": 2 * g.hob_tip_radius,
            "tip_clearance": g.hob_tip_radius - g.worm_tip_diameter / 2,
            "axial_thread_thickness": g.hob_axial_thickness,
            "normal_thread_thickness": g.hob_axial_thickness * math.cos(g.lead_angle),
            "axial_pressure_angle": g.axial_pressure_angle, "root_diameter_max": 2 * g.throat_radius}


def pair_check_data(check, unit: str) -> dict:
    """The JSON block of a worm pair check's result (:func:`geargen.families.worm.pair.worm_pair_check`,
    run by the caller: the model layer does not run checks), lengths in ``unit``."""
    return {"backlash_circumferential": float(from_mm(check.backlash, unit)), "interference": bool(check.interference),
            "centre_distance": float(from_mm(check.centre_distance, unit)),
            "method": "geargen.families.worm.pair: the worm against the wheel's envelope in 9 planes across the face"}


def worm_part_data(spec) -> dict:
    s = spec.set
    g = worm_geometry(s)
    u = s.length_unit

    def L(v):
        return None if v is None else float(from_mm(v, u))

    hob = hob_data(s, g)
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
        # on the worm reference cylinder, normal to the thread: s_n1 = s_x1 cos(gamma)
        "worm_normal_thread_thickness": L(g.worm_axial_thickness * math.cos(g.lead_angle)),
        "worm_addendum": L((g.worm_tip_diameter - g.worm_reference_diameter) / 2),
        "wheel_tooth_thickness_transverse": L(wheel_tooth_thickness(s, g)),
        "wheel_thinning": L(g.wheel_thinning),
        "hob": {"what": "the worm's thread at its nominal thickness p_x/2, tip raised by the tip clearance; "
                        "root at most the wheel's throat", "starts": hob["starts"], "hand": hob["hand"],
                "lead": L(hob["lead"]), "lead_angle_deg": math.degrees(hob["lead_angle"]),
                "reference_diameter": L(hob["reference_diameter"]), "tip_diameter": L(hob["tip_diameter"]),
                "tip_clearance": L(hob["tip_clearance"]), "axial_thread_thickness": L(hob["axial_thread_thickness"]),
                "normal_thread_thickness": L(hob["normal_thread_thickness"]),
                "axial_pressure_angle_deg": math.degrees(hob["axial_pressure_angle"]),
                "root_diameter_max": L(hob["root_diameter_max"])},
        "backlash_circumferential": L(s.backlash), "backlash_on": s.backlash_on,

        "warnings": [],
    }


__all__ = ["worm_part_data", "wheel_tooth_thickness", "hob_data", "pair_check_data"]
