"""Gear accuracy grades: the tolerances of ISO 1328-1:2013 and the error budget a grade sets.

ISO 1328-1:2013 ("Cylindrical gears - ISO system of flank tolerance classification - Part 1")
gives each tolerance of a flank tolerance class (grade) A = 1 (finest) .. 11 as its class-5
value times the step factor sqrt(2)^(A - 5) (clause 5.2.2), with d the reference diameter,
m_n the normal module and b the face width in mm and the result in um:

====================  ============================================  =========
single pitch          f_pT  = (0.001 d + 0.4 m_n + 5)                formula 5
cumulative pitch      F_pT  = (0.002 d + 0.55 sqrt(d) + 0.7 m_n + 12)  formula 6
profile slope         f_HaT = (0.4 m_n + 0.001 d + 4)                formula 7
profile form          f_faT = (0.55 m_n + 5)                         formula 8
profile total         F_aT  = sqrt(f_HaT^2 + f_faT^2)                formula 9
helix slope           f_HbT = (0.05 sqrt(d) + 0.35 sqrt(b) + 4)       formula 10
helix form            f_fbT = (0.07 sqrt(d) + 0.45 sqrt(b) + 4)       formula 11
helix total           F_bT  = sqrt(f_HbT^2 + f_fbT^2)                formula 12
runout                F_rT  = 0.9 F_pT                               runout annex
====================  ============================================  =========

Each final value (after the step factor, and the totals from the *unrounded* slope and form
values) is rounded by clause 5.2.3: above 10 um to the nearest whole um, from 5 to 10 um to the
nearest 0.5 um, below 5 um to the nearest 0.1 um (halves up). Runout is not one of the
edition's normative tolerances: the edition moved it to an informative annex, which relates it
to the cumulative pitch tolerance as F_rT = 0.9 F_pT (F_pT unrounded, the result rounded as
above). The formulas hold for 5 <= z <= 1000, 5 <= d <= 15000 mm, 0.5 <= m_n <= 70 mm,
4 <= b <= 1200 mm, beta <= 45 deg (clause 1) and must not be extrapolated: outside, a
:class:`~geargen.errors.DesignError` names the quantity and the range.

The edition's single-flank composite tolerances (f_isT, F_isT) depend on the design's own
tooth-to-tooth transmission error f_is(design); they are not computed here (see
:func:`gear_error_budget` for the tooth-to-tooth row of the error budget).

Sources of the formula text (the standard itself is not public): independent public
implementations quoting formulas 5-12, clause 5.2.2 and the rounding of 5.2.3 agree term for
term; the scope ranges are quoted in FreeCAD pull request #26676.

Radial composite (double-flank) tolerances are those of ISO 1328-2:1997 ("Cylindrical gears - ISO
system of accuracy - Part 2: Definitions and allowable values of deviations relevant to radial
composite deviations and runout information"), clause 7, see :func:`iso1328_2_radial_composite`.

ANSI/AGMA 2015-1-A01 (classes A2..A11) is not implemented: its formulas and rounding could not
be established from a citable source. Inch designs use ISO 1328-1:2013 with the gear's own mm
values (the formulas are in mm and um).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from decimal import ROUND_HALF_UP, Decimal

from geargen.design.gear import ISO_1328, ISO_1328_SCOPE, GearSpec, iso1328_scope_problem, iso1328_scope_text
from geargen.design.synthesis import (ERROR_KINDS, GEAR_ROLES, GRADE_SET_KINDS, GearErrors, error_table,
                                      error_tables)
from geargen.errors import DesignError

UM = 1e-3  # mm per um

#: ISO 1328-1:2013 5.2.3: (lower bound of the band in um, rounding step in um), coarsest band first;
#: a value above 10 um rounds to 1 um, from 5 to 10 um to 0.5 um, below 5 um to 0.1 um
ROUNDING_BANDS = ((10.0, "1"), (5.0, "0.5"), (0.0, "0.1"))


def iso1328_round(value_um: float) -> float:
    """``value_um`` rounded as ISO 1328-1:2013 5.2.3 rounds a tolerance (halves away from zero).

    Decimal arithmetic on the value first rounded to 1e-9 um, so that a formula landing on a tie
    (5.75 um) rounds up whatever the last bit of its floating-point sum (5.7499999999999991).
    """
    if not (math.isfinite(value_um) and value_um >= 0):
        raise ValueError(f"a tolerance is >= 0 um, got {value_um!r}")
    v = Decimal(repr(round(value_um, 9)))
    for lower, step in ROUNDING_BANDS:
        # 10 um itself is in the 0.5 um band ("from 5 to 10"), 5 um in it too
        if (v > Decimal(lower)) if lower == 10.0 else (v >= Decimal(lower)):
            q = Decimal(step)
            return float((v / q).quantize(Decimal(1), rounding=ROUND_HALF_UP) * q)
    raise AssertionError("unreachable: the last band starts at 0")


@dataclass(frozen=True)
class AccuracyTolerances:
    """The tolerances of one gear for one grade of ``standard``, um, rounded as the standard rounds.

    ``reference_diameter``, ``normal_module`` and ``face_width`` (mm) are the inputs.
    """

    standard: str
    grade: int
    reference_diameter: float
    normal_module: float
    face_width: float
    single_pitch: float
    cumulative_pitch: float
    profile_slope: float
    profile_form: float
    profile_total: float
    helix_slope: float
    helix_form: float
    helix_total: float
    runout: float
    #: the radial composite block (:func:`radial_composite_block`) of the same grade number
    radial_composite: dict | None = None

    def to_dict(self) -> dict:
        """The gear-data contract's ``accuracy`` block (keys of ../shared/contracts/gear-data.md,
        plus the slope and form tolerances and the ``radial_composite`` block)."""
        return {"standard": self.standard, "grade": self.grade,
                "single_pitch_um": self.single_pitch, "cumulative_pitch_um": self.cumulative_pitch,
                "profile_total_um": self.profile_total, "helix_total_um": self.helix_total,
                "runout_um": self.runout,
                "profile_slope_um": self.profile_slope, "profile_form_um": self.profile_form,
                "helix_slope_um": self.helix_slope, "helix_form_um": self.helix_form,
                "radial_composite": self.radial_composite}


def _check_scope(field: str, quantity: str, value) -> None:
    if iso1328_scope_problem(quantity, value):
        raise DesignError(field, f"{value!r} is outside the range of {ISO_1328} (its formulas must not be "
                          "extrapolated)", iso1328_scope_text(quantity))


def iso1328_tolerances(grade: int, reference_diameter: float, normal_module: float,
                       face_width: float) -> AccuracyTolerances:
    """ISO 1328-1:2013 tolerances (um) of flank tolerance class ``grade`` for a gear of reference
    diameter, normal module and face width in mm (formulas 5-12, runout annex, rounding 5.2.3)."""
    if isinstance(grade, bool) or not isinstance(grade, int):
        raise DesignError("grade", f"expected a whole number, got {grade!r}", iso1328_scope_text("grade"))
    _check_scope("grade", "grade", grade)
    _check_scope("reference_diameter", "reference_diameter", reference_diameter)
    _check_scope("normal_module", "normal_module", normal_module)
    _check_scope("face_width", "face_width", face_width)
    d, mn, b = float(reference_diameter), float(normal_module), float(face_width)
    step = math.sqrt(2.0) ** (grade - 5)  # 5.2.2
    f_pt = (0.001 * d + 0.4 * mn + 5.0) * step
    F_pt = (0.002 * d + 0.55 * math.sqrt(d) + 0.7 * mn + 12.0) * step
    f_hat = (0.4 * mn + 0.001 * d + 4.0) * step
    f_fat = (0.55 * mn + 5.0) * step
    f_hbt = (0.05 * math.sqrt(d) + 0.35 * math.sqrt(b) + 4.0) * step
    f_fbt = (0.07 * math.sqrt(d) + 0.45 * math.sqrt(b) + 4.0) * step
    r = iso1328_round
    return AccuracyTolerances(
        standard=ISO_1328, grade=grade, reference_diameter=d, normal_module=mn, face_width=b,
        single_pitch=r(f_pt), cumulative_pitch=r(F_pt), profile_slope=r(f_hat), profile_form=r(f_fat),
        profile_total=r(math.hypot(f_hat, f_fat)),  # 9: from the unrounded slope and form values
        helix_slope=r(f_hbt), helix_form=r(f_fbt), helix_total=r(math.hypot(f_hbt, f_fbt)),  # 12: likewise
        runout=r(0.9 * F_pt), radial_composite=radial_composite_block(grade, d, mn))


# --- ISO 1328-2:1997: radial composite (double-flank) tolerances ------------------------------------

ISO_1328_2 = "ISO 1328-2:1997"
#: ISO 1328-2:1997 clause 6 and 7: grades 4 (finest) .. 12; normal module 0.2 .. 10 mm and reference
#: diameter 5 .. 1000 mm, each in ranges whose bounds are these (a value on a bound belongs to the
#: range below it, the first range includes its lower bound)
ISO_1328_2_GRADES = (4, 12)
ISO_1328_2_MODULE_BOUNDS = (0.2, 0.5, 0.8, 1.0, 1.5, 2.5, 4.0, 6.0, 10.0)
ISO_1328_2_DIAMETER_BOUNDS = (5.0, 20.0, 50.0, 125.0, 280.0, 560.0, 1000.0)


def _range_mean(field: str, value: float, bounds: tuple[float, ...]) -> float:
    """The geometric mean sqrt(lo hi) of the ISO 1328-2:1997 range holding ``value`` (mm): the
    standard evaluates its formulas there, not at the gear's own value."""
    if not (isinstance(value, (int, float)) and math.isfinite(value) and bounds[0] <= value <= bounds[-1]):
        raise DesignError(field, f"{value!r} is outside the range of {ISO_1328_2} (its formulas must not be "
                          "extrapolated)", f"[{bounds[0]:g}, {bounds[-1]:g}] mm")
    hi = next(b for b in bounds[1:] if value <= b)
    lo = bounds[bounds.index(hi) - 1]
    return math.sqrt(lo * hi)


@dataclass(frozen=True)
class RadialCompositeTolerances:
    """ISO 1328-2:1997 radial composite tolerances (um) of one gear and grade, rounded as ISO 1328
    rounds; ``diameter_mean`` and ``module_mean`` (mm) are the range means the formulas used."""

    standard: str
    grade: int
    diameter_mean: float
    module_mean: float
    total: float  # F_i'' : total radial composite deviation, one revolution against a master gear
    tooth_to_tooth: float  # f_i'' : its largest change over one pitch

    def to_dict(self) -> dict:
        return {"standard": self.standard, "grade": self.grade,
                "total_radial_composite_um": self.total, "tooth_to_tooth_radial_composite_um": self.tooth_to_tooth,
                "range_mean_diameter_mm": self.diameter_mean, "range_mean_normal_module_mm": self.module_mean}


def iso1328_2_radial_composite(grade: int, reference_diameter: float, normal_module: float) -> RadialCompositeTolerances:
    """ISO 1328-2:1997 clause 7 tolerances of grade ``grade`` (4..12) for a gear of reference diameter and
    normal module in mm, with d and m_n the geometric means of the standard's ranges holding them:

        F_i'' = (3.2 m_n + 1.01 sqrt(d) + 6.4) sqrt(2)^(grade - 5)    total radial composite
        f_i'' = (2.96 m_n + 0.01 sqrt(d) + 0.8) sqrt(2)^(grade - 5)   tooth-to-tooth radial composite

    each rounded as :func:`iso1328_round` (the 1997 edition's rule is the same: whole um above 10 um,
    0.5 um from 5 to 10 um, 0.1 um below). Source of the formula text (the standard is not public): a
    public implementation quoting it with the ranges above, geometric means and rounding (the MITCalc
    web port's "Standard Engineering Tables", ``calcISO1328Tolerances``, "ISO 1328 - Part 2 (Radial
    composite and runout)"); the grade range 4..12 and module range 0.2..10 mm are also stated in the
    edition's published abstract (Document Center, ISO-1328-2 1997 edition)."""
    if isinstance(grade, bool) or not isinstance(grade, int) or not ISO_1328_2_GRADES[0] <= grade <= ISO_1328_2_GRADES[1]:
        raise DesignError("grade", f"{grade!r} is not a radial composite grade of {ISO_1328_2}",
                          f"a whole number in [{ISO_1328_2_GRADES[0]}, {ISO_1328_2_GRADES[1]}]")
    d = _range_mean("reference_diameter", reference_diameter, ISO_1328_2_DIAMETER_BOUNDS)
    mn = _range_mean("normal_module", normal_module, ISO_1328_2_MODULE_BOUNDS)
    step = math.sqrt(2.0) ** (grade - 5)
    return RadialCompositeTolerances(
        standard=ISO_1328_2, grade=grade, diameter_mean=d, module_mean=mn,
        total=iso1328_round((3.2 * mn + 1.01 * math.sqrt(d) + 6.4) * step),
        tooth_to_tooth=iso1328_round((2.96 * mn + 0.01 * math.sqrt(d) + 0.8) * step))


#: how the radial composite grade is chosen: ISO 1328-2 grades are a system of their own, not the flank
#: tolerance class; geargen gives the radial grade of the same number so that a shop inspecting
#: double-flank gets limits of the accuracy the drawing names, and says so
RADIAL_GRADE_RULE = ("the grade number of the flank tolerance class (ISO 1328-2 grades are a separate system; "
                     "agree another with the shop if double-flank inspection is used)")


def radial_composite_block(grade: int, reference_diameter: float, normal_module: float) -> dict:
    """The gear data's ``accuracy.radial_composite`` block: the ISO 1328-2:1997 tolerances of the grade
    with the flank class's number, or, where the standard gives none (grade or size outside its range),
    ``{"standard": ..., "grade": None, "not_given": why, "scope": its ranges}``: never an extrapolated value.
    ``why`` names no unit (the JSON's text is read in the design's unit); the ranges' keys carry theirs."""
    scope = {"grades": list(ISO_1328_2_GRADES),
             "normal_module_mm": [ISO_1328_2_MODULE_BOUNDS[0], ISO_1328_2_MODULE_BOUNDS[-1]],
             "reference_diameter_mm": [ISO_1328_2_DIAMETER_BOUNDS[0], ISO_1328_2_DIAMETER_BOUNDS[-1]]}
    outside = [what for what, value, (lo, hi) in (
        ("grade", grade, scope["grades"]), ("normal module", normal_module, scope["normal_module_mm"]),
        ("reference diameter", reference_diameter, scope["reference_diameter_mm"])) if not lo <= value <= hi]
    if outside:
        return {"standard": ISO_1328_2, "grade": None, "scope": scope,
                "not_given": f"the {' and the '.join(outside)} {'is' if len(outside) == 1 else 'are'} outside the "
                             "standard's range (its formulas must not be extrapolated)"}
    return iso1328_2_radial_composite(grade, reference_diameter, normal_module).to_dict() | {
        "grade_rule": RADIAL_GRADE_RULE}


def gear_tolerances(spec: GearSpec) -> AccuracyTolerances | None:
    """The tolerances of ``spec``'s accuracy grade (None when it has none), from its own reference
    diameter, normal module and face width in mm whatever its length unit."""
    if spec.accuracy_grade is None:
        return None
    return iso1328_tolerances(spec.accuracy_grade, 2 * spec.reference_radius, spec.module, spec.face_width)


def grade_for_budget(reference_diameter: float, normal_module: float, face_width: float,
                     pitch_line_eccentricity_tir: float, tooth_to_tooth_tir: float) -> int | None:
    """The coarsest ISO 1328-1:2013 grade whose runout tolerance does not exceed
    ``pitch_line_eccentricity_tir`` and whose tooth-to-tooth tolerance (the single pitch
    tolerance, see :func:`gear_error_budget`) does not exceed ``tooth_to_tooth_tir`` (both mm):
    what a shop must hold so that the gear meets the budget. None when even grade 1 does not."""
    for field, v in (("pitch_line_eccentricity_tir", pitch_line_eccentricity_tir),
                     ("tooth_to_tooth_tir", tooth_to_tooth_tir)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
            raise DesignError(field, f"{v!r} is out of range", ">= 0 mm")
    lo, hi, _ = ISO_1328_SCOPE["grade"]
    for grade in range(hi, lo - 1, -1):  # tolerances grow with the grade: the first that fits is the coarsest
        t = iso1328_tolerances(grade, reference_diameter, normal_module, face_width)
        # compare in um, as the standard's rounded values are stated
        if t.runout <= pitch_line_eccentricity_tir / UM + 1e-9 and t.single_pitch <= tooth_to_tooth_tir / UM + 1e-9:
            return grade
    return None


# --- the error budget ------------------------------------------------------------------------------

#: the error-budget rows a grade sets, and the tolerance that sets each. Pitch-line eccentricity is
#: the runout of the teeth about the gear's own axis: the runout tolerance F_rT (a total indicator
#: reading, as the row). The Appendix's tooth-to-tooth composite error is, in geargen's error model
#: (geargen.core.tolerance), a tooth displaced along the pitch circle within a band of width t from
#: one tooth to the next; the edition's tolerance of that is the single pitch tolerance f_pT (the
#: difference between adjacent teeth's positions, |f_p| <= f_pT, so a band t = f_pT). Its single-
#: flank tooth-to-tooth composite f_isT would also fit but needs the design's transmission error.
GRADED_ROWS = dict(zip(GRADE_SET_KINDS, (("runout", "F_rT"), ("single_pitch", "f_pT"))))


def graded_errors(spec: GearSpec, entered: dict[str, float]) -> GearErrors:
    """``spec``'s error budget (mm): the rows its grade sets from its tolerances, the others as
    ``entered`` (kind -> mm; the bearing eccentricity, a property of the seat, not of the gear).
    Each graded row records its source, e.g. "ISO 1328-1:2013 grade 6: F_rT 25 um"."""
    t = gear_tolerances(spec)
    values = dict(entered)
    sources = {}
    if t is not None:
        for kind, (attr, symbol) in GRADED_ROWS.items():
            um = getattr(t, attr)
            values[kind] = um * UM
            sources[kind] = f"{t.standard} grade {t.grade}: {symbol} {um:g} um"
    return GearErrors(*(values.get(k, 0.0) for k in ERROR_KINDS), sources=tuple(sources.get(k, "") for k in ERROR_KINDS))


def gear_error_budget(design, gear: str, required: bool) -> GearErrors | None:
    """The ``[errors.GEAR]`` budget of one gear (TIR, mm), the rows its accuracy grade sets derived
    from the grade; None when the design has no such table. The one reader of error budgets
    (the synthesis, the checks' worst case and Monte Carlo, the sweep, the train's runout):
    ``required`` as in :func:`geargen.design.synthesis.error_table`."""
    entered = error_table(design, gear, required)
    if entered is None:
        return None
    return graded_errors(design.gear(gear), entered)


def error_budget_inputs(design) -> tuple[GearErrors, GearErrors, GearErrors, GearErrors] | None:
    """The synthesis' budget: ``[errors.input]`` ... ``[errors.output]``, all four required (see
    :func:`geargen.design.synthesis.error_tables`); None when the design has no ``[errors]``."""
    if error_tables(design) is None:
        return None
    return tuple(gear_error_budget(design, role, required=True) for role in GEAR_ROLES)


def gear_errors(design, gear: str) -> GearErrors | None:
    """One gear's budget in a design checked pair by pair (every row optional, default 0)."""
    return gear_error_budget(design, gear, required=False)


__all__ = ["AccuracyTolerances", "RadialCompositeTolerances", "iso1328_2_radial_composite", "radial_composite_block",
           "ISO_1328_2", "iso1328_round", "iso1328_tolerances", "gear_tolerances", "grade_for_budget",
           "GRADED_ROWS", "graded_errors", "gear_error_budget", "error_budget_inputs", "gear_errors", "ROUNDING_BANDS"]
