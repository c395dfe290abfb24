"""Design-file sections for centre synthesis: ``[synthesis]``, ``[errors.*]`` and ``[monte_carlo]``.

Each section becomes a frozen dataclass, validated on construction, in internal units (mm, rad).
The drive is the dual-pinion train of Hale & Slocum's robot-joint case study (Fig. 11): the
design's gears named ``input`` (gear 1), ``cluster_large`` (gear 2), ``cluster_small`` (gear 3)
and ``output`` (gear 4); mesh 1 is input/cluster_large, mesh 2 is cluster_small/output. Two
identical clusters sit mirrored about the symmetry line.

Layout::

    [synthesis]
    centre_distance_mesh1_in = 1.004                  # operating centre distances
    centre_distance_mesh2_in = 2.078125
    circumferential_backlash_max_mesh1_in = 0.0050    # B: see below
    circumferential_backlash_min_mesh1_in = 0.0040
    circumferential_backlash_max_mesh2_in = 0.0042
    circumferential_backlash_min_mesh2_in = 0.0008
    start_angle_A1_deg = -70.0                        # nominal A1 to start from
    rounding = "whole_down"                           # see ROUNDING_RULES

    [errors.input]                                    # one table per gear name, TIR values
    bearing_eccentricity_tir_in = 0.0002
    pitch_line_eccentricity_tir_in = 0.0008
    tooth_to_tooth_tir_in = 0.0005

    [errors.output]                                   # a gear with accuracy_grade: its grade sets
    bearing_eccentricity_tir_in = 0.0002              # the other two (geargen.core.accuracy)

    [monte_carlo]                                     # optional; every key has a default
    samples = 1000000
    seed = 1994
    model = "exact"                                   # "exact" or "appendix"
    error_shape = "physical"                          # "physical", "uniform" or "normal3"
    include_backlash_tolerance = false
    histogram_bins = 80

**Backlash** B of a mesh is the transverse circumferential backlash referred to the reference
pitch circles, B = j_bt / cos(alpha_t), with j_bt the base-tangent backlash (the clearance
between the non-working flanks along the transverse line of action; for spur gears the normal
backlash) at the mesh's operating centre distance. Each gear of the mesh then turns freely
through B / r (r its reference pitch radius) while its mate is held: this is the Appendix's
"Ang. Backlash" Ba = B / r. Positive means clearance. ``max`` is the backlash with the thinnest
teeth the tolerances allow, ``min`` with the thickest.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import math
from dataclasses import dataclass, field

from geargen.design.gear import with_field_prefix
from geargen.design.schema import Field, read_table
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES

if TYPE_CHECKING:  # the type only: the loader imports this module
    from geargen.design.assembly import Design

DEG = math.pi / 180.0

#: design gear names in the order of the paper's gears 1..4
GEAR_ROLES = ("input", "cluster_large", "cluster_small", "output")

#: how the increment count i of Eq. 7 is rounded. "whole_*" keep i even (whole teeth of the input
#: gear, the Appendix's "N" rounded), "half_*" allow any half-tooth increment (the paper's text).
ROUNDING_RULES = ("whole_down", "whole_nearest", "half_down", "half_nearest")

ERROR_KINDS = ("bearing_eccentricity_tir", "pitch_line_eccentricity_tir", "tooth_to_tooth_tir")
#: the rows a gear's accuracy_grade sets (with which tolerance: geargen.core.accuracy.GRADED_ROWS); the
#: bearing eccentricity is the seat's, not the gear's, and stays entered
GRADE_SET_KINDS = ("pitch_line_eccentricity_tir", "tooth_to_tooth_tir")

MONTE_CARLO_MODELS = ("exact", "appendix")
ERROR_SHAPES = ("physical", "uniform", "normal3")


def _length_text(value_mm: float, unit: str) -> str:
    return f"{value_mm / LENGTH_SUFFIXES[unit]:.6g} {unit}"


@dataclass(frozen=True)
class SynthesisInputs:
    """Inputs of the centre synthesis, mm and rad (transverse module and pressure angle per mesh).

    Field names are the ``[synthesis]`` keys without their unit suffix; so are the fields that
    errors name (``circumferential_backlash_min_mesh1``).

    ``teeth`` are of gears 1..4 (input, cluster large, cluster small, output). Backlash values
    are the circumferential backlash B of the module docstring at the operating centre
    distance. ``start_angle_A1`` is the direction of the vector from cluster A's centre to the
    input gear's centre, from +x (negative, as in the Appendix). ``length_unit`` is the design's
    unit, used in messages and reports only.
    """

    teeth: tuple[int, int, int, int]
    module_mesh1: float
    module_mesh2: float
    pressure_angle_mesh1: float
    pressure_angle_mesh2: float
    centre_distance_mesh1: float
    centre_distance_mesh2: float
    circumferential_backlash_max_mesh1: float
    circumferential_backlash_min_mesh1: float
    circumferential_backlash_max_mesh2: float
    circumferential_backlash_min_mesh2: float
    start_angle_A1: float
    rounding: str = "whole_down"
    length_unit: str = "mm"

    def __post_init__(self):
        object.__setattr__(self, "teeth", tuple(self.teeth))
        u = self.length_unit
        if u not in LENGTH_SUFFIXES:
            raise DesignError("length_unit", f"{u!r} is not a valid choice", "'mm', 'in'")
        if len(self.teeth) != 4 or not all(isinstance(z, int) and not isinstance(z, bool) and z >= 4 for z in self.teeth):
            raise DesignError("teeth", f"{self.teeth!r} is not four tooth counts", "four whole numbers >= 4")
        for name in ("module_mesh1", "module_mesh2"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise DesignError(name, f"{v!r} is out of range", "> 0 mm")
        for name in ("pressure_angle_mesh1", "pressure_angle_mesh2"):
            v = getattr(self, name)
            if not (math.isfinite(v) and 5 * DEG <= v <= 45 * DEG):
                raise DesignError(name, f"{v!r} is out of range", "[5, 45] deg")
        if self.rounding not in ROUNDING_RULES:
            raise DesignError("rounding", f"{self.rounding!r} is not a valid choice", ", ".join(map(repr, ROUNDING_RULES)))
        for mesh in (1, 2):
            c = getattr(self, f"centre_distance_mesh{mesh}")
            lo = self.base_radius_sum(mesh)
            if not (math.isfinite(c) and c > lo):
                raise DesignError(f"centre_distance_mesh{mesh}", f"{c / LENGTH_SUFFIXES[u]:.6g} {u} is out of range",
                                  f"> {_length_text(lo, u)} (the sum of the base radii)")
            bmax = self.backlash(mesh, "max")
            bmin = self.backlash(mesh, "min")
            pitch = math.pi * getattr(self, f"module_mesh{mesh}")
            for kind, b in (("max", bmax), ("min", bmin)):
                if not (math.isfinite(b) and 0.0 <= b < pitch / 2):
                    raise DesignError(f"circumferential_backlash_{kind}_mesh{mesh}",
                                      f"{b / LENGTH_SUFFIXES[u]:.6g} {u} is out of range"
                                      + (" (negative backlash is interference)" if b < 0 else ""),
                                      f"[0, {_length_text(pitch / 2, u)}) (half the circular pitch)")
            if bmin > bmax:
                raise DesignError(f"circumferential_backlash_min_mesh{mesh}",
                                  f"{_length_text(bmin, u)} is more than the maximum {_length_text(bmax, u)}",
                                  f"[0, {_length_text(bmax, u)}]")
        a1 = self.start_angle_A1
        if not (math.isfinite(a1) and -math.pi / 2 < a1 < 0):
            raise DesignError("start_angle_A1", f"{a1 / DEG:.6g} deg is out of range", "(-90, 0) deg")
        c1, c2 = self.centre_distance_mesh1, self.centre_distance_mesh2
        if abs(c1 * math.sin(a1)) > c2:  # Eq. 8 has no solution
            lo = -math.asin(c2 / c1) / DEG
            raise DesignError("start_angle_A1",
                              f"Eq. 8 has no solution: |C1 sin A1| = {_length_text(abs(c1 * math.sin(a1)), u)} "
                              f"exceeds C2 = {_length_text(c2, u)}", f"({lo:.6g}, 0) deg for these centre distances")

    def reference_radius(self, gear: int) -> float:
        """Reference pitch radius of gear 1..4 (mm)."""
        m = self.module_mesh1 if gear in (1, 2) else self.module_mesh2
        return self.teeth[gear - 1] * m / 2.0

    def pressure_angle(self, mesh: int) -> float:
        return self.pressure_angle_mesh1 if mesh == 1 else self.pressure_angle_mesh2

    def standard_centre_distance(self, mesh: int) -> float:
        """Sum of the reference radii of the mesh's gears (mm)."""
        a, b = (1, 2) if mesh == 1 else (3, 4)
        return self.reference_radius(a) + self.reference_radius(b)

    def base_radius_sum(self, mesh: int) -> float:
        return self.standard_centre_distance(mesh) * math.cos(self.pressure_angle(mesh))

    def centre_distance(self, mesh: int) -> float:
        return self.centre_distance_mesh1 if mesh == 1 else self.centre_distance_mesh2

    def backlash(self, mesh: int, kind: str) -> float:
        """Circumferential backlash B (mm) of mesh 1 or 2, ``kind`` "max" or "min"."""
        return getattr(self, f"circumferential_backlash_{kind}_mesh{mesh}")

    @property
    def ratio_mesh1(self) -> float:
        """R1 = z2 / z1."""
        return self.teeth[1] / self.teeth[0]

    @property
    def ratio_mesh2(self) -> float:
        """R2 = z4 / z3."""
        return self.teeth[3] / self.teeth[2]


@dataclass(frozen=True)
class GearErrors:
    """One gear's error budget, each a total indicator reading (peak to peak), mm.

    ``sources`` says, per row of ERROR_KINDS, where a derived value came from ("" for a value
    the design file gives); it takes no part in comparisons.
    """

    bearing_eccentricity_tir: float = 0.0
    pitch_line_eccentricity_tir: float = 0.0
    tooth_to_tooth_tir: float = 0.0
    sources: tuple[str, str, str] = field(default=("", "", ""), compare=False)

    def __post_init__(self):
        for name in ERROR_KINDS:
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise DesignError(name, f"{v!r} is out of range", ">= 0 mm")

    @property
    def total_tir(self) -> float:
        """The Appendix's "Total Error": the sum of the three readings."""
        return self.bearing_eccentricity_tir + self.pitch_line_eccentricity_tir + self.tooth_to_tooth_tir


@dataclass(frozen=True)
class MonteCarloSettings:
    """Settings of the tolerance simulation (see geargen.core.tolerance.monte_carlo)."""

    samples: int = 100_000
    seed: int = 0
    model: str = "exact"
    error_shape: str = "physical"
    include_backlash_tolerance: bool = False
    histogram_bins: int = 80

    def __post_init__(self):
        if not (isinstance(self.samples, int) and 100 <= self.samples <= 100_000_000):
            raise DesignError("samples", f"{self.samples!r} is out of range", "[100, 100000000]")
        if not (isinstance(self.seed, int) and self.seed >= 0):
            raise DesignError("seed", f"{self.seed!r} is out of range", ">= 0")
        if self.model not in MONTE_CARLO_MODELS:
            raise DesignError("model", f"{self.model!r} is not a valid choice", ", ".join(map(repr, MONTE_CARLO_MODELS)))
        if self.error_shape not in ERROR_SHAPES:
            raise DesignError("error_shape", f"{self.error_shape!r} is not a valid choice",
                              ", ".join(map(repr, ERROR_SHAPES)))
        if self.model == "exact" and self.error_shape != "physical":
            raise DesignError("error_shape", f"{self.error_shape!r} needs model = 'appendix'",
                              "'physical' with model = 'exact'")
        if not (isinstance(self.histogram_bins, int) and 5 <= self.histogram_bins <= 1000):
            raise DesignError("histogram_bins", f"{self.histogram_bins!r} is out of range", "[5, 1000]")


SYNTHESIS_FIELDS: list[Field] = [
    Field("centre_distance_mesh1", "length", minimum=0.0, exclusive_minimum=True,
          help="operating centre distance of mesh 1 (input and cluster_large), above the sum of the base radii"),
    Field("centre_distance_mesh2", "length", minimum=0.0, exclusive_minimum=True,
          help="operating centre distance of mesh 2 (cluster_small and output), above the sum of the base radii"),
    Field("circumferential_backlash_max_mesh1", "length",
          help="mesh 1 backlash with the thinnest teeth the tolerances allow; in [0, half the circular pitch)"),
    Field("circumferential_backlash_min_mesh1", "length",
          help="mesh 1 backlash with the thickest teeth; in [0, the maximum]"),
    Field("circumferential_backlash_max_mesh2", "length",
          help="mesh 2 backlash with the thinnest teeth the tolerances allow; in [0, half the circular pitch)"),
    Field("circumferential_backlash_min_mesh2", "length",
          help="mesh 2 backlash with the thickest teeth; in [0, the maximum]"),
    Field("start_angle_A1", "angle", units=("deg", "rad"),
          help="nominal direction from cluster A's centre to the input's centre, from +x; in (-90, 0) deg"),
    Field("rounding", "string", choices=ROUNDING_RULES,
          help="how the increment count of Eq. 7 is rounded: whole_* keep whole teeth of the input gear, half_* "
               "allow half teeth"),
]

ERROR_FIELDS: list[Field] = [
    Field("bearing_eccentricity_tir", "length", minimum=0.0,
          help="runout of the gear's bearing seat (total indicator reading)"),
    Field("pitch_line_eccentricity_tir", "length", minimum=0.0,
          help="runout of the pitch circle about the bore (total indicator reading); a gear with accuracy_grade "
               "takes its grade's runout tolerance instead (give one of the two)"),
    Field("tooth_to_tooth_tir", "length", minimum=0.0,
          help="tooth-to-tooth composite error (total indicator reading); a gear with accuracy_grade takes its "
               "grade's single pitch tolerance instead (give one of the two)"),
]

MONTE_CARLO_FIELDS: list[Field] = [
    Field("samples", "integer", required=False, default=100_000, minimum=100, maximum=100_000_000,
          help="random builds drawn from the error budget"),
    Field("seed", "integer", required=False, default=0, minimum=0,
          help="seed of the random draws (the same seed gives the same result)"),
    Field("model", "string", required=False, default="exact", choices=MONTE_CARLO_MODELS,
          help="exact: re-solve the loop geometry per sample; appendix: the spreadsheet's linear factors"),
    Field("error_shape", "string", required=False, default="physical", choices=ERROR_SHAPES,
          help="how errors are drawn: physical (eccentricities at a random phase, tooth-to-tooth uniform); the "
               "appendix model also takes uniform or normal3 (its range as +-3 sigma)"),
    Field("include_backlash_tolerance", "bool", required=False, default=False,
          help="also draw each mesh's backlash within its [min, max]"),
    Field("histogram_bins", "integer", required=False, default=80, minimum=5, maximum=1000,
          help="bins of the carriage-travel histogram"),
]


def synthesis_inputs(design: Design) -> SynthesisInputs:
    """Read ``[synthesis]`` and the four gears of ``design`` into :class:`SynthesisInputs`.

    Gears of one mesh must share transverse module and pressure angle; each operating centre
    distance must lie between the sums of base and tip radii of its gears.
    """
    raw = design.section("synthesis")
    if not raw:
        raise DesignError("synthesis", "missing", "a [synthesis] table: " + ", ".join(
            k for f in SYNTHESIS_FIELDS for k in f.keys()[:1]))
    v = read_table(raw, SYNTHESIS_FIELDS, "synthesis")
    gears = [design.gear(role) for role in GEAR_ROLES]
    for mesh, (a, b) in ((1, (0, 1)), (2, (2, 3))):
        ga, gb = gears[a], gears[b]
        if not math.isclose(ga.transverse_module, gb.transverse_module, rel_tol=1e-12):
            raise DesignError(f"gears.{GEAR_ROLES[b]}", f"transverse module {gb.transverse_module:.6g} mm differs from "
                              f"gears.{GEAR_ROLES[a]} ({ga.transverse_module:.6g} mm) in mesh {mesh}", "the same pitch")
        if not math.isclose(ga.transverse_pressure_angle, gb.transverse_pressure_angle, rel_tol=1e-12):
            raise DesignError(f"gears.{GEAR_ROLES[b]}", f"pressure angle differs from gears.{GEAR_ROLES[a]} in mesh {mesh}",
                              "the same pressure angle")
        tip_sum = ga.tip_radius + gb.tip_radius
        c = v[f"centre_distance_mesh{mesh}"]
        if c >= tip_sum:
            unit = v["_units"][f"centre_distance_mesh{mesh}"]
            raise DesignError(f"synthesis.centre_distance_mesh{mesh}_{unit}",
                              f"{c / LENGTH_SUFFIXES[unit]:.6g} {unit} leaves the teeth out of mesh",
                              f"< {tip_sum / LENGTH_SUFFIXES[unit]:.6g} {unit} (the sum of the tip radii)")
    kwargs = {f.name: v[f.name] for f in SYNTHESIS_FIELDS}  # the keys are the dataclass's field names
    kwargs.update(teeth=tuple(g.teeth for g in gears),
                  module_mesh1=gears[0].transverse_module, module_mesh2=gears[2].transverse_module,
                  pressure_angle_mesh1=gears[0].transverse_pressure_angle,
                  pressure_angle_mesh2=gears[2].transverse_pressure_angle, length_unit=design.length_unit)
    return with_field_prefix("synthesis.", lambda: SynthesisInputs(**kwargs), v["_units"])


def _graded_kinds(design: Design, gear: str) -> tuple[str, ...]:
    """The rows of ``gear``'s budget its accuracy grade sets (none without a grade)."""
    spec = design.gears.get(gear)
    if spec is None or spec.accuracy_grade is None:
        return ()
    return GRADE_SET_KINDS


def error_tables(design: Design) -> dict | None:
    """The raw ``[errors]`` section with its gear names checked against the synthesis' four
    (each must have a table); None when the design has none."""
    raw = design.section("errors")
    if not raw:
        return None
    unknown = [k for k in raw if k not in GEAR_ROLES]
    if unknown:
        raise DesignError(f"errors.{unknown[0]}", "unknown gear", ", ".join(GEAR_ROLES))
    for role in GEAR_ROLES:
        if role not in raw:
            raise DesignError(f"errors.{role}", "missing", "a table with " + ", ".join(f"{k}_in" for k in ERROR_KINDS))
    return raw


def error_table(design: Design, gear: str, required: bool) -> dict[str, float] | None:
    """The TIRs (mm) ``[errors.GEAR]`` gives, kind -> value; None when the design has no such table.

    ``required``: every row the gear's grade does not set must be given (the synthesis); else a
    row not given is 0 (a pair check). A row that the gear's ``accuracy_grade`` sets is refused
    when the table gives it too, naming both keys (one number, one source). The values of the
    graded rows are geargen.core.accuracy's (:func:`geargen.core.accuracy.gear_error_budget`).
    """
    raw = design.section("errors").get(gear)
    if raw is None:
        return None
    where = f"errors.{gear}"
    graded = _graded_kinds(design, gear)
    for kind in graded:
        given = [k for k in raw if k.startswith(kind + "_")]
        if given:
            spec = design.gear(gear)
            raise DesignError(f"{where}.{given[0]}", f"is set by gears.{gear}.accuracy_grade = {spec.accuracy_grade} "
                              f"({spec.accuracy_standard}); give one of the two",
                              f"gears.{gear}.accuracy_grade or {where}.{given[0]}, not both")
    fields = [f for f in ERROR_FIELDS if f.name not in graded]
    if not required:
        fields = [Field(f.name, f.kind, required=False, default=0.0, minimum=0.0) for f in fields]
    v = read_table(raw, fields, where)
    entered = {f.name: v[f.name] for f in fields}
    # the range rule of GearErrors, with the key as written
    with_field_prefix(where + ".", lambda: GearErrors(**entered), v["_units"])
    return entered


def validate_error_budget(design: Design) -> None:
    """Read and check the synthesis' ``[errors.*]`` tables (what load_design runs)."""
    if error_tables(design) is not None:
        for role in GEAR_ROLES:
            error_table(design, role, required=True)


def monte_carlo_settings(design: Design) -> MonteCarloSettings:
    """Read ``[monte_carlo]`` (all keys optional; an absent section gives the defaults)."""
    v = read_table(design.section("monte_carlo"), MONTE_CARLO_FIELDS, "monte_carlo")
    return with_field_prefix("monte_carlo.", lambda: MonteCarloSettings(**{f.name: v[f.name] for f in MONTE_CARLO_FIELDS}),
                              {})


__all__ = ["GEAR_ROLES", "ROUNDING_RULES", "ERROR_KINDS", "SynthesisInputs", "GearErrors", "MonteCarloSettings",
           "synthesis_inputs", "error_tables", "error_table", "validate_error_budget", "monte_carlo_settings"]
