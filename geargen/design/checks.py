"""The ``[checks]`` section: what the geometric mesh checks sweep, require and compare.

Every key is optional::

    [checks]
    steps_per_tooth = 24            # mesh positions per tooth of the turned gear
    revolutions = 1.0               # of the turned gear; default one tooth cycle (whole hunting
                                    # period of the teeth when errors are swept)
    section_planes = 5              # transverse planes of a helical pair (path 1)
    min_contact_ratio = 1.1         # transverse for spur pairs, total for helical
    min_tip_land_modules = 0.2      # tip land below this many normal modules: pointed_tooth
    require_backlash = true         # every mesh must keep backlash (false: zero-backlash meshes allowed)
    tolerances = true               # worst case and Monte Carlo over the [errors.*] budget
    monte_carlo_samples = 400
    seed = 0
    sections = false                # also check sections of the exported solids (path 2)
    sections_planes = 3
    stl_chordal_tolerance_mm = 0.001
    carriage_travel_limit_in = 0.02 # preload carriage: largest travel either way from nominal
    centre_distance_tolerance_um = 10  # +-f_a of every mesh's centre distance: the allowance route and
                                    # each mesh's backlash range (geargen.core.allowance); default 0
    structure = "fail"              # build: how the parts hold together (geargen.checks.structure);
                                    # "report" lists its findings as warnings instead
    min_S_H = 1.0                   # load capacity (geargen.checks.rating): a mesh fails below these
    min_S_F = 1.4                   #   safety factors against pitting and tooth root bending

    # pairs to check in a design without [synthesis]; centre distance per pair (one number for
    # one pair, or a list), in any length unit
    meshes = [["pinion", "wheel"]]
    centre_distance_mm = 25.5

Gear names in ``meshes`` are ``[gears.NAME]`` tables; the first of a pair is the one turned.
Error budgets of declared pairs are read from ``[errors.NAME]`` tables (same keys as the
synthesis error budget: ``bearing_eccentricity_tir_*``, ``pitch_line_eccentricity_tir_*``,
``tooth_to_tooth_tir_*``, each optional, default 0; a gear's accuracy grade sets the last two),
by :func:`geargen.core.accuracy.gear_errors`; a gear without one has no errors.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import math
from dataclasses import dataclass, field
from typing import Any

from geargen.design.gear import with_field_prefix
from geargen.design.schema import Field, check_range, read_table
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES

if TYPE_CHECKING:  # the type only: the loader imports this module
    from geargen.design.assembly import Design

#: S_Hmin, S_Fmin when [checks] gives none: ISO 6336 leaves them to agreement between the parties and
#: recommends none; these are the usual industrial values (a root fracture ends the drive, a pit does
#: not at once, hence the larger S_Fmin). geargen.core.load_capacity takes the same defaults.
MINIMUM_SAFETY = (1.0, 1.4)


@dataclass(frozen=True)
class DeclaredMesh:
    """A pair named in ``[checks] meshes``: gear names (first turned) and centre distance (mm)."""

    gear1: str
    gear2: str
    centre_distance: float

    @property
    def name(self) -> str:
        return f"{self.gear1}-{self.gear2}"


@dataclass(frozen=True)
class ChecksSettings:
    """The ``[checks]`` section in internal units (mm); see the module docstring."""

    steps_per_tooth: int = 24
    revolutions: float | None = None
    section_planes: int = 5
    min_contact_ratio: float = 1.1
    min_tip_land_modules: float = 0.2
    require_backlash: bool = True
    tolerances: bool = True
    monte_carlo_samples: int = 400
    seed: int = 0
    sections: bool = False
    sections_planes: int = 3
    stl_chordal_tolerance: float = 1e-3
    carriage_travel_limit: float | None = None
    centre_distance_tolerance: float = 0.0
    structure: str = "fail"
    meshes: tuple[DeclaredMesh, ...] = field(default=())
    min_S_H: float = MINIMUM_SAFETY[0]
    min_S_F: float = MINIMUM_SAFETY[1]

    def __post_init__(self):
        for name, lo, hi in (("steps_per_tooth", 2, 10000), ("section_planes", 1, 200), ("sections_planes", 1, 200),
                             ("monte_carlo_samples", 0, 10_000_000)):
            v = getattr(self, name)
            if not (isinstance(v, int) and lo <= v <= hi):
                raise DesignError(name, f"{v!r} is out of range", f"[{lo}, {hi}]")
        if self.revolutions is not None and not (math.isfinite(self.revolutions) and self.revolutions > 0):
            raise DesignError("revolutions", f"{self.revolutions!r} is out of range", "> 0")
        if not (isinstance(self.seed, int) and self.seed >= 0):
            raise DesignError("seed", f"{self.seed!r} is out of range", ">= 0")
        if not (math.isfinite(self.centre_distance_tolerance) and self.centre_distance_tolerance >= 0):
            raise DesignError("centre_distance_tolerance", f"{self.centre_distance_tolerance!r} is out of range", ">= 0 mm")
        if not (math.isfinite(self.stl_chordal_tolerance) and self.stl_chordal_tolerance > 0):
            raise DesignError("stl_chordal_tolerance", f"{self.stl_chordal_tolerance!r} is out of range", "> 0 mm")


CHECKS_FIELDS: list[Field] = [
    Field("steps_per_tooth", "integer", required=False, default=24, minimum=2, maximum=10000,
          help="mesh positions checked per tooth of the turned gear"),
    # at most the longest hunting period: the turned gear's revolutions until a mate of 2000 teeth repeats
    Field("revolutions", "number", required=False, default=None, minimum=0.0, exclusive_minimum=True, maximum=2000.0,
          help="revolutions of the turned gear to sweep (default: one tooth cycle, or the whole hunting period when "
               "errors are swept)"),
    Field("section_planes", "integer", required=False, default=5, minimum=1, maximum=200,
          help="transverse planes through a helical pair (path 1)"),
    Field("min_contact_ratio", "number", required=False, default=1.1, minimum=0.0, maximum=10.0,
          help="smallest contact ratio accepted (transverse for spur pairs, total for helical)"),
    Field("min_tip_land_modules", "number", required=False, default=0.2, minimum=0.0, maximum=2.0,
          help="a tip land below this many normal modules fails as pointed_tooth"),
    Field("require_backlash", "bool", required=False, default=True,
          help="every mesh must keep backlash (false: zero-backlash meshes pass)"),
    Field("tolerances", "bool", required=False, default=True,
          help="worst case and Monte Carlo of the minimum backlash over the [errors.*] budget"),
    Field("monte_carlo_samples", "integer", required=False, default=400, minimum=0, maximum=10_000_000,
          help="random builds of the error budget"),
    Field("seed", "integer", required=False, default=0, minimum=0, help="seed of the Monte Carlo draws"),
    Field("sections", "bool", required=False, default=False,
          help="also check sections of the exported solids (path 2)"),
    Field("sections_planes", "integer", required=False, default=3, minimum=1, maximum=200,
          help="planes sectioned per gear by path 2"),
    Field("stl_chordal_tolerance", "length", required=False, default=1e-3, minimum=0.0, exclusive_minimum=True,
          help="chordal tolerance of the meshes sectioned by path 2"),
    Field("carriage_travel_limit", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="largest preload-carriage travel either way from nominal the error budget may need"),
    Field("centre_distance_tolerance", "length", required=False, default=0.0, minimum=0.0,
          help="+- tolerance f_a of every mesh's centre distance: the thickness allowances chosen from the backlash "
               "ranges (thickest teeth at a - f_a, thinnest at a + f_a) and the backlash range checked"),
    Field("structure", "string", required=False, default="fail", choices=("fail", "report"),
          help="build: every part grounded through contacts, rotating parts on stationary ones only through "
               "bearings, every bearing seated on both sides; fail the build, or report the findings as warnings"),
    Field("min_S_H", "number", required=False, default=MINIMUM_SAFETY[0], minimum=0.0, exclusive_minimum=True,
          maximum=10.0, help="smallest safety factor against pitting S_H a rated mesh may have (ISO 6336-2; the "
                             "load capacity of every mesh fails below it)"),
    Field("min_S_F", "number", required=False, default=MINIMUM_SAFETY[1], minimum=0.0, exclusive_minimum=True,
          maximum=10.0, help="smallest safety factor against tooth root bending S_F a rated mesh may have "
                             "(ISO 6336-3; the load capacity of every mesh fails below it)"),
    Field("meshes", "list", required=False, default=None,
          help="pairs to check in a design without [synthesis] or [layout]: [[\"gear1\", \"gear2\"], ...], the first "
               "turned"),
]

CENTRE_KEYS = tuple(f"centre_distance_{u}" for u in LENGTH_SUFFIXES)


def checks_settings(design: Design) -> ChecksSettings:
    """Read ``[checks]`` of ``design`` (absent: all defaults)."""
    raw = dict(design.section("checks"))
    centre_keys = [k for k in raw if k in CENTRE_KEYS]
    centre_raw = {k: raw.pop(k) for k in centre_keys}
    v = read_table(raw, CHECKS_FIELDS, "checks", read_elsewhere=CENTRE_KEYS)
    meshes = _declared_meshes(design, v["meshes"], centre_raw)
    kwargs = {k: v[k] for k in ("steps_per_tooth", "revolutions", "section_planes", "min_contact_ratio",
                                "min_tip_land_modules", "require_backlash", "tolerances", "monte_carlo_samples",
                                "seed", "sections", "sections_planes", "stl_chordal_tolerance",
                                "carriage_travel_limit", "centre_distance_tolerance", "structure", "min_S_H",
                                "min_S_F")}
    return with_field_prefix("checks.", lambda: ChecksSettings(meshes=meshes, **kwargs), v["_units"])


def _declared_meshes(design: Design, meshes: Any, centre_raw: dict[str, Any]) -> tuple[DeclaredMesh, ...]:
    if meshes is None:
        if centre_raw:
            key = next(iter(centre_raw))
            raise DesignError(f"checks.{key}", "a centre distance needs meshes = [[gear1, gear2], ...]", "checks.meshes")
        return ()
    if not meshes or not all(isinstance(m, list) and len(m) == 2 and all(isinstance(g, str) for g in m) for m in meshes):
        raise DesignError("checks.meshes", f"{meshes!r} is not a list of gear-name pairs",
                          '[["gear1", "gear2"], ...] naming [gears.*] tables')
    for m in meshes:
        for g in m:
            if g not in design.gears:
                raise DesignError("checks.meshes", f"{g!r} is not a gear of this design", ", ".join(design.gears))
        if m[0] == m[1]:
            raise DesignError("checks.meshes", f"{m[0]!r} cannot mesh with itself", "two different gears")
        for g in m:
            kind = getattr(design.gears[g], "kind", "external")
            if kind != "external":  # the declared-pair checker measures two external outlines
                raise DesignError("checks.meshes", f"{g!r} is a gear of kind {kind!r}; declared pairs are of "
                                  "external gears", "pairs of external gears")
    if len(centre_raw) != 1:
        raise DesignError("checks.centre_distance_mm", "missing" if not centre_raw else "given twice",
                          "one of " + ", ".join(CENTRE_KEYS))
    key, raw = next(iter(centre_raw.items()))
    scale = LENGTH_SUFFIXES[key[len("centre_distance_"):]]
    values = raw if isinstance(raw, list) else [raw]
    if len(values) != len(meshes):
        raise DesignError(f"checks.{key}", f"{len(values)} centre distances for {len(meshes)} meshes",
                          "one number per mesh")
    f = Field("centre_distance", "length", minimum=0.0, exclusive_minimum=True)
    out = []
    for k, (m, c) in enumerate(zip(meshes, values)):
        where = f"checks.{key}" + (f"[{k}]" if isinstance(raw, list) else "")
        if isinstance(c, bool) or not isinstance(c, (int, float)):
            raise DesignError(where, f"expected a number, got {c!r}")
        unit = key[len("centre_distance_"):]
        check_range(f, float(c) * scale, where, scale, unit)
        # two involutes touch only on a line of action between the base circles: the pair needs a > r_b1 + r_b2
        bases = design.gears[m[0]].base_radius + design.gears[m[1]].base_radius
        if float(c) * scale <= bases:
            raise DesignError(where, f"{c:.6g} {unit} does not clear the base circles of {m[0]} and {m[1]}",
                              f"> {bases / scale:.6g} {unit}")
        out.append(DeclaredMesh(m[0], m[1], float(c) * scale))
    return tuple(out)


__all__ = ["ChecksSettings", "DeclaredMesh", "CHECKS_FIELDS", "MINIMUM_SAFETY", "checks_settings"]
