"""A gear's data as `geargen gear` writes it to ``<name>.json`` (see ../shared/contracts/gear-data.md).

One function serves every writer of gear data (the gear command, the build's drawings), so a
number on a drawing is the number in the JSON. Lengths in the gear's ``length_unit``.
"""

from __future__ import annotations

import math

from geargen.design.gear import GearSpec
from geargen.errors import GeargenError
from geargen.families.registry import family_of
from geargen.units import from_mm


def gear_data(spec: GearSpec, profile, allowance=None, errors=None) -> dict:
    """Radii, thicknesses, undercut, span and over-pins/balls of ``spec`` in its length unit, and
    the ``accuracy`` block of its grade's tolerances (um) when it has one.

    ``allowance`` (:class:`geargen.core.allowance.ThicknessAllowance`, e.g. from
    :func:`geargen.model.allowance.drive_allowances`): adds ``thickness_allowance`` and the
    ``limits`` [smallest, largest] of the span and over-pins dimension (thinnest and thickest
    tooth, the same k and pin diameter as the nominal values).

    ``errors`` (:class:`geargen.design.synthesis.GearErrors`, the gear's entered error budget): a
    gear without an accuracy grade gets the ``accuracy`` block of the coarsest grade that holds its
    budget's pitch-line eccentricity and tooth-to-tooth TIRs (what the shop must make it to), with
    ``grade_source`` saying so; a budget finer than grade 1 is a warning, not a made-up grade."""
    own = family_of(spec).gear_data(spec)
    if own is not None:  # a GearSpec kind with its own data (a ring)
        return own
    from geargen.core import geometry
    from geargen.core.accuracy import gear_tolerances
    from geargen.core.involute import pointed_tip_radius, reference_tooth_thickness

    u = spec.length_unit

    def L(v):
        return None if v is None else float(from_mm(v, u))

    out = {
        "name": spec.name, "length_unit": u, "teeth": spec.teeth,
        "normal_module_mm": spec.module, "transverse_module_mm": spec.transverse_module,
        "normal_pressure_angle_deg": math.degrees(spec.pressure_angle),
        "transverse_pressure_angle_deg": math.degrees(spec.transverse_pressure_angle),
        "helix_angle_deg": math.degrees(spec.helix_angle), "hand": spec.hand if spec.is_helical else None,
        "base_helix_angle_deg": math.degrees(spec.base_helix_angle),
        "lead": L(spec.lead) if spec.is_helical else None,
        "profile_shift_normal": spec.profile_shift,
        "basic_rack": {"addendum_coefficient": spec.addendum_coefficient,
                       "dedendum_coefficient": spec.dedendum_coefficient,
                       "tip_radius_coefficient": spec.rack_tip_radius_coefficient},
        "face_width": L(spec.face_width), "bore_diameter": L(spec.hub.bore_diameter),
        "reference_radius": L(profile.reference_radius), "base_radius": L(profile.base_radius),
        "tip_radius": L(profile.tip_radius), "root_radius": L(profile.root_radius),
        "reference_tooth_thickness_transverse": L(reference_tooth_thickness(spec)),
        "thinning_circumferential": L(spec.thinning),
        "tip_land_transverse": L(profile.tip_land), "pointed_tip_radius": L(pointed_tip_radius(spec)),
        "undercut": profile.undercut, "involute_start_radius": L(profile.involute_start_radius),
        "warnings": list(profile.warnings),
    }
    if spec.kind == "double_helical":
        # two helical halves of opposite hand from z = 0 up, the relief groove (root diameter) between
        out["double_helical"] = {"centre_gap": L(spec.centre_gap), "half_face_width": L(spec.half_face_width),
                                 "half_hands": list(spec.half_hands)}
    tolerances = gear_tolerances(spec)
    if tolerances is not None:
        out["accuracy"] = tolerances.to_dict() | {"grade_source": "the design's accuracy_grade"}
    elif errors is not None:
        _add_budget_grade(out, spec, errors)
    try:
        uc = geometry.undercut(spec)
        out["minimum_teeth_without_undercut"] = uc.minimum_teeth
        out["minimum_profile_shift_without_undercut"] = uc.minimum_profile_shift
    except GeargenError as exc:
        out["warnings"].append(str(exc))
    try:
        span = geometry.span_measurement(spec)
        out["span"] = {"teeth_spanned": span.teeth_spanned, "span_normal": L(span.span),
                       "span_transverse": L(span.transverse_span), "contact_radius": L(span.contact_radius)}
    except GeargenError as exc:
        out["span"] = None
        out["warnings"].append(f"span: {exc}")
    try:
        pins = geometry.over_pins_measurement(spec)
        out["over_pins"] = {"kind": pins.kind, "diameter": L(pins.pin_diameter), "dimension": L(pins.dimension),
                            "centre_radius": L(pins.centre_radius), "contact_radius": L(pins.contact_radius)}
    except GeargenError as exc:
        out["over_pins"] = None
        out["warnings"].append(f"over pins: {exc}")
    if allowance is not None:
        _add_limits(out, spec, allowance, L)
    return out


def _add_limits(out: dict, spec: GearSpec, allowance, L) -> None:
    """The allowance and the span and over-pins limits it gives (contract: gear-data.md)."""
    from geargen.core.allowance import over_pins_limits, span_limits
    from geargen.units import to_mm

    out["thickness_allowance"] = {"method": allowance.method, "upper_um": allowance.upper_um,
                                  "lower_um": allowance.lower_um}
    for key, limits, size in (("span", span_limits, "teeth_spanned"), ("over_pins", over_pins_limits, "diameter")):
        if not out.get(key):
            continue
        value = out[key][size] if key == "span" else to_mm(out[key][size], spec.length_unit)
        try:
            out[key]["limits"] = [L(v) for v in limits(spec, allowance, value)]
        except GeargenError as exc:  # e.g. the thinnest tooth's anvils leave the involute
            out[key]["limits"] = None
            out["warnings"].append(f"{key} limits: {exc}")


def _add_budget_grade(out: dict, spec: GearSpec, errors) -> None:
    """The accuracy block of the coarsest ISO 1328-1:2013 grade within the gear's error budget."""
    from geargen.core.accuracy import grade_for_budget, iso1328_tolerances
    d, m_n, b = 2 * spec.reference_radius, spec.module, spec.face_width
    try:
        grade = grade_for_budget(d, m_n, b, errors.pitch_line_eccentricity_tir, errors.tooth_to_tooth_tir)
    except GeargenError as exc:  # outside the standard's scope (e.g. m_n < 0.5 mm)
        out["warnings"].append(f"accuracy: no ISO 1328-1:2013 grade for the error budget: {exc}")
        return
    if grade is None:
        out["warnings"].append("accuracy: the error budget's TIRs are finer than ISO 1328-1:2013 grade 1")
        return
    out["accuracy"] = iso1328_tolerances(grade, d, m_n, b).to_dict() | {
        "grade_source": "the coarsest grade within the design's error budget (pitch-line eccentricity and "
                        "tooth-to-tooth TIRs)"}
