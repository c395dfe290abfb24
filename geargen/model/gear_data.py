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


def gear_data(spec: GearSpec, profile, allowance=None, errors=None, material=None) -> dict:
    """Radii, thicknesses, undercut, span and over-pins/balls of ``spec`` in its length unit, and
    the ``accuracy`` block of its grade's tolerances (um) when it has one.

    ``allowance`` (:class:`geargen.core.allowance.ThicknessAllowance`, e.g. from
    :func:`geargen.model.allowance.drive_allowances`): adds ``thickness_allowance`` and the
    ``limits`` [smallest, largest] of the span and over-pins dimension (thinnest and thickest
    tooth, the same k and pin diameter as the nominal values).

    ``errors`` (:class:`geargen.design.synthesis.GearErrors`, the gear's entered error budget): a
    gear without an accuracy grade gets the ``accuracy`` block of the coarsest grade that holds its
    budget's pitch-line eccentricity and tooth-to-tooth TIRs (what the shop must make it to), with
    ``grade_source`` saying so; a budget finer than grade 1 is a warning, not a made-up grade.

    ``material`` (:class:`geargen.design.duty.GearMaterial`, the ISO 6336-5 material the design's
    rating names for the gear): the drawing's material, heat treatment and hardness where the gear
    table gives none (:func:`shop_data`)."""
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
    if family_of(spec).TOOTH_FORM.helices == 2:
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
        from geargen.core.measuring_pins import standard_pin
        pins, series = standard_pin(spec)
        out["over_pins"] = {"kind": pins.kind, "diameter": L(pins.pin_diameter), "dimension": L(pins.dimension),
                            "centre_radius": L(pins.centre_radius), "contact_radius": L(pins.contact_radius),
                            "series": series, "ideal_diameter": L(geometry.ideal_pin_diameter(spec))}
    except GeargenError as exc:
        out["over_pins"] = None
        out["warnings"].append(f"over pins: {exc}")
    chord = geometry.chordal_tooth(spec)  # external teeth only reach here (a ring's data is its family's)
    out["chordal_tooth"] = {"thickness_normal": L(chord.thickness), "height": L(chord.height),
                            "virtual_diameter": L(chord.virtual_diameter),
                            "convention": "at the reference circle of the normal section's virtual spur gear "
                                          "(d_v = d / cos^2 beta), height from the tip"}
    if allowance is not None:
        _add_limits(out, spec, allowance, L)
    out.update(shop_data(spec, profile, out.get("accuracy"), material))
    return out


#: the axial runout tolerance of the reference face B, referred to the bore axis A: the face's tilt
#: over its diameter may take a fifth of what the helix tolerance allows over the face width. This is
#: geargen's convention: the form was recalled as ISO/TR 10064-3 Table 3's, but no text of that
#: report could be found to check it against (searched 2026-11), so no standard is cited for it
FACE_RUNOUT_FORMULA = "0.2 (d_f / b) F_βT"
FACE_RUNOUT_RULE = ("geargen's convention, not a value of a standard: t_B = 0.2 (d_f / b) F_βT, d_f the root "
                    "diameter (the face's outer diameter below the teeth), b the face width, F_βT the total helix "
                    "tolerance of the accuracy grade")


def _tolerance(size_mm: float, code: str | None, deviations, default: str, u: str, feature: str) -> dict:
    """A size's tolerance: its ISO 286 class (the design's or ``default``) or its deviations, with the
    limits [smallest, largest] in the unit ``u`` and the deviations in um."""
    from geargen.core.iso286 import tolerance_class
    if deviations is not None:
        upper, lower = deviations[0] * 1e3, deviations[1] * 1e3
        out = {"standard": None, "code": None, "source": "the design's deviations"}
    else:
        tc = tolerance_class(code or default, size_mm, feature)
        upper, lower = tc.upper_um, tc.lower_um
        out = {"standard": "ISO 286-1:2010", "code": tc.code,
               "source": "the design's tolerance class" if code else "geargen's default class"}
    out |= {"nominal": float(from_mm(size_mm, u)), "upper_deviation_um": upper, "lower_deviation_um": lower,
            "limits": [float(from_mm(size_mm + lower * 1e-3, u)), float(from_mm(size_mm + upper * 1e-3, u))]}
    return out


def check_shop_keys(spec: GearSpec, prefix: str | None = None) -> None:
    """Each ISO 286 class the gear's table names exists at its feature's size (a bore fit needs a
    bore) and its DIN 3967 designation is one; errors name the key under ``prefix`` (default
    ``gears.NAME.``). The tables are core's, above the design layer, so this runs where the gear
    is used (``geargen gear``, a build's gear data), not where the table is read."""
    from geargen.core.din3967 import parse_designation
    from geargen.core.iso286 import tolerance_class
    from geargen.errors import DesignError
    p = f"gears.{spec.name}." if prefix is None else prefix
    shop = spec.shop
    if shop.bore_fit is not None:
        if spec.hub.bore_diameter <= 0:
            raise DesignError(p + "bore_fit", "a fit needs a bore", "bore_diameter_* > 0, or no bore_fit")
        tolerance_class(shop.bore_fit, spec.hub.bore_diameter, "hole", p + "bore_fit")
    if shop.tip_diameter_class is not None:
        tolerance_class(shop.tip_diameter_class, 2 * spec.tip_radius, "shaft", p + "tip_diameter_tolerance")
    if shop.face_width_class is not None:
        tolerance_class(shop.face_width_class, spec.face_width, "shaft", p + "face_width_tolerance")
    if shop.thickness_allowance_series is not None:
        parse_designation(shop.thickness_allowance_series, p + "thickness_allowance_series")


def check_gear_tables(design) -> None:
    """:func:`check_shop_keys` of every cylindrical gear ``design`` declares: run by ``geargen check``
    and ``geargen build`` alike before anything is checked or built, so a drawing key that the gear
    data would refuse is refused by both with the same key."""
    for spec in design.gears.values():
        if isinstance(spec, GearSpec):
            check_shop_keys(spec)


def shop_data(spec: GearSpec, profile, accuracy: dict | None, material=None) -> dict:
    """The drawing's data besides the teeth (gear-data keys): part number and revision, material,
    heat treatment, hardness and flank finish (the gear table's keys, else the rating's ISO 6336-5
    ``material``, else None: not specified), the datums, the bore's, tip diameter's and face width's
    tolerances (ISO 286-1) and the tolerances referred to the datums."""
    check_shop_keys(spec)
    shop, u = spec.shop, spec.length_unit
    out = {"part_number": shop.part_number, "revision": shop.revision}
    mat = {"material": shop.material, "heat_treatment": shop.heat_treatment, "hardness": None,
           "source": "the gear table" if (shop.material or shop.heat_treatment or shop.hardness) else None}
    if shop.hardness is not None:
        mat["hardness"] = {"value": shop.hardness[0], "unit": shop.hardness[1]}
    if material is not None:
        from geargen.design.iso6336_5 import TABLE_8
        taken = []
        if mat["material"] is None:
            mat["material"] = TABLE_8[material.name][0]
            taken.append("material")
        if mat["heat_treatment"] is None:
            mat["heat_treatment"] = f"{material.name.replace('_', ' ')}, ISO 6336-5 {material.quality}"
            taken.append("heat treatment")
        if mat["hardness"] is None and material.hardness is not None:
            mat["hardness"] = {"value": material.hardness, "unit": "HV"}
            taken.append("hardness")
        if taken:
            mat["source"] = (mat["source"] + "; " if mat["source"] else "") + \
                f"{', '.join(taken)} from the load-capacity rating's material ({material.source})"
    out["material"] = mat
    out["flank_roughness_Ra_um"] = None if shop.flank_roughness_Ra is None else shop.flank_roughness_Ra * 1e3
    bore = spec.hub.bore_diameter
    # B is the face at z = b, the one without the hub (the hub stands on z < 0, geargen.cad.gear_solid)
    out["datums"] = {"A": "bore axis" if bore > 0 else "axis of the tip cylinder (no bore)",
                     "B": "face at z = b, opposite the hub" if spec.hub.hub_length > 0 else "face at z = b"}
    if bore > 0:
        from geargen.core.iso286 import tolerance_class
        b = {"nominal": float(from_mm(bore, u)), "code": shop.bore_fit, "standard": None,
             "upper_deviation_um": None, "lower_deviation_um": None, "limits": None}
        if shop.bore_fit:
            tc = tolerance_class(shop.bore_fit, bore, "hole")
            b |= {"code": tc.code, "standard": "ISO 286-1:2010", "upper_deviation_um": tc.upper_um,
                  "lower_deviation_um": tc.lower_um,
                  "limits": [float(from_mm(bore + tc.lower_um * 1e-3, u)), float(from_mm(bore + tc.upper_um * 1e-3, u))]}
        out["bore"] = b
    else:
        out["bore"] = None
    from geargen.design.gear import DEFAULT_FACE_WIDTH_CLASS, DEFAULT_TIP_CLASS
    out["tip_diameter_tolerance"] = _tolerance(2 * profile.tip_radius, shop.tip_diameter_class,
                                               shop.tip_diameter_deviations, DEFAULT_TIP_CLASS, u, "shaft")
    out["face_width_tolerance"] = _tolerance(spec.face_width, shop.face_width_class, shop.face_width_deviations,
                                             DEFAULT_FACE_WIDTH_CLASS, u, "shaft")
    geo = {"datum_axis": "A", "radial_runout_um": None, "helix_total_um": None, "face_axial_runout_um": None,
           "face_axial_runout_formula": FACE_RUNOUT_FORMULA, "face_axial_runout_rule": FACE_RUNOUT_RULE}
    if accuracy:
        geo["radial_runout_um"] = accuracy.get("runout_um")
        geo["helix_total_um"] = accuracy.get("helix_total_um")
        if accuracy.get("helix_total_um") is not None:
            geo["face_axial_runout_um"] = 0.2 * (2 * profile.root_radius / spec.face_width) * accuracy["helix_total_um"]
    out["datum_tolerances"] = geo
    return out


def _add_limits(out: dict, spec: GearSpec, allowance, L) -> None:
    """The allowance and the span and over-pins limits it gives (contract: gear-data.md)."""
    from geargen.core.allowance import over_pins_limits, span_limits
    from geargen.units import to_mm

    out["thickness_allowance"] = {"method": allowance.method, "upper_um": allowance.upper_um,
                                  "lower_um": allowance.lower_um}
    if out.get("chordal_tooth"):  # the thinnest and thickest tooth's chords, read at the modelled height
        from geargen.core.allowance import thickest, thinnest
        from geargen.core.geometry import chordal_tooth
        out["chordal_tooth"]["limits"] = [L(chordal_tooth(t(spec, allowance)).thickness)
                                          for t in (thinnest, thickest)]
    for key, limits, size in (("span", span_limits, "teeth_spanned"), ("over_pins", over_pins_limits, "diameter")):
        if not out.get(key):
            continue
        value = out[key][size] if key == "span" else to_mm(out[key][size], spec.length_unit)
        try:
            out[key]["limits"] = [L(v) for v in limits(spec, allowance, value)]
        except GeargenError as exc:  # e.g. the thinnest tooth's anvils leave the involute
            out[key]["limits"] = None
            out["warnings"].append(f"{key} limits: {exc}")


def hold_rated_grade(out: dict, spec: GearSpec, rated_grade: int) -> None:
    """A drive gear without a grade of its own is made to the finer of its error budget's grade and
    the ``[duty] accuracy_grade`` its load capacity is rated at: a gear cut coarser than the rating
    assumed (K_v, K_Hbeta, K_Halpha) would not have the rated safety factors."""
    from geargen.core.accuracy import gear_tolerances, iso1328_tolerances
    if gear_tolerances(spec) is not None:  # its own grade: the rating reads it too
        return
    budget = out.get("accuracy", {}).get("grade")
    if budget is not None and budget <= rated_grade:
        return
    d, m_n, b = 2 * spec.reference_radius, spec.module, spec.face_width
    try:
        tolerances = iso1328_tolerances(rated_grade, d, m_n, b)
    except GeargenError as exc:  # outside the standard's scope: the budget's block (or none) stays
        out["warnings"].append(f"accuracy: the rated grade {rated_grade} has no ISO 1328-1:2013 tolerances: {exc}")
        return
    why = (f"the [duty] accuracy_grade the load capacity is rated at (finer than grade {budget}, the coarsest "
           "within the error budget)" if budget is not None else "the [duty] accuracy_grade the load capacity "
           "is rated at")
    out["accuracy"] = tolerances.to_dict() | {"grade_source": why}


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
