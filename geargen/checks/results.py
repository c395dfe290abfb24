"""What a geometric mesh check returns: failure kinds, the sweep of one mesh, the check of a design.

Conventions (every check, both paths):

- internal units mm and rad; ``to_dict(unit)`` converts lengths to the design's unit at the edge;
- gear 1 of a mesh is the one that is turned (the "moving" gear), gear 2 is held;
- ``mesh_position`` is gear 1's rotation (rad, counter-clockwise) from the reference phase;
  gear 2 turns with it at the nominal ratio;
- backlash is always named by its kind, and positive means clearance:

  * ``angular_backlash``: free rotation of gear 1 (rad) with gear 2 held between its flanks'
    contacts with the mate's flanks (``conjugate_play_ccw + conjugate_play_cw``); a tip or
    fillet that stops the gear earlier is interference, reported separately;
  * ``circumferential_backlash``: that rotation as arc length on gear 1's operating pitch circle
    (radius ``a z1 / (z1 + z2)`` at the actual centre distance ``a``), transverse section, mm;
  * ``normal_backlash``: the shortest distance between the non-working flanks, normal to the
    teeth: gear 1's base radius times the angular backlash times ``cos(beta_b)`` (exact for
    involute flanks, whose normals are tangent to the base circle), mm;

- ``min_clearance`` is the tip clearance: the smallest distance from a root arc of either gear
  (the deepest point of the gap where the fillets meet without one) to the mate's tip lands
  (arcs and their corners), negative where a tip reaches below the mate's root circle. With a
  tip land centred over a root it is the classical ``a - r_a - r_f``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from geargen.units import LENGTH_SUFFIXES

#: failure kind -> what it means. A failure names one of these.
FAILURE_KINDS: dict[str, str] = {
    "tip_to_root_interference": "a tip of one gear reaches into the mate's root (below its root outline): "
                                "the crowded-centre risk",
    "involute_interference": "a tip works on the mate's non-involute flank (fillet or undercut, below "
                             "where the mate's involute starts): non-conjugate contact",
    "flank_interference": "the involute flanks overlap on both sides: the tooth does not fit the mate's "
                          "space at this centre distance (negative backlash)",
    "no_backlash": "a mesh meant to run with backlash has none (flanks touch on both sides)",
    "undercut": "the involute is undercut where the mate's tip works (the active profile reaches into the "
                "undercut), or the profile could not be cut without it",
    "pointed_tooth": "the tip land is below the minimum (or the flanks meet below the tip circle)",
    "low_contact_ratio": "contact ratio below the minimum (1.1 by default)",
    "backlash_lost": "across the tolerances of the error budget the minimum backlash of a mesh meant to "
                     "run with backlash reaches zero",
    "preload_contact_lost": "a preloaded mesh cannot stay in contact across the tolerances (its non-working "
                            "flanks close, or the loop does not close: the springs no longer set the preload)",
    "carriage_travel_exceeded": "across the tolerances the preload carriage must travel further than its "
                                "hardware allows (flexure travel, spring solid height or free length, or "
                                "[checks] carriage_travel_limit)",
    "paths_disagree": "the exact 2-D check and the section check of the exported solid disagree beyond "
                      "the stated tolerance",
    "backlash_out_of_range": "the backlash of the mesh as modelled and placed is outside the design range",
    "allowance_range_disagrees": "the backlash range from the tooth-thickness allowances and the centre-distance "
                                 "tolerance differs from the one measured on the thinnest and thickest teeth",
    "allowance_range_outside_design": "the backlash range from the tooth-thickness allowances and the "
                                      "centre-distance tolerance leaves the design range",
    "thinning_outside_allowance": "a gear's modelled tooth thinning (its solids, STEP, STL, DXF and gear data) lies "
                                  "outside its tooth-thickness allowance: the exported gear fails its own drawing's "
                                  "inspection",
    "disengaged_overlap": "a pinion slid out of mesh still overlaps its mate axially",
    "ratio_mismatch": "the exact ratio of the train is not one the design requires",
    "load_capacity": "a safety factor of a mesh under the stated [duty] is below [checks] min_S_H (pitting, "
                     "ISO 6336-2) or min_S_F (tooth-root bending, ISO 6336-3), the spectrum summed by ISO 6336-6",
    "trochoid_interference": "internal pair: leaving mesh, the pinion's tip corner cuts the ring's tip corner",
    "radial_assembly_fouling": "internal pair: the pinion cannot be moved into mesh along the line of centres",
    "planetary_assembly": "planetary stage: a planet's carrier angle is no assembly angle (2 pi k / (z_s + z_r)): "
                          "it cannot mesh both the sun and the ring",
    "planetary_coaxiality": "planetary stage: the sun-planet and planet-ring working centre distances differ",
    "planet_neighbour_clearance": "planetary stage: neighbouring planets' tip circles do not clear",
    "parts_overlap": "two parts with no joint between them share volume (the resolved drive's components, read "
                     "analytically; the build intersects the solids too)",
    "parts_interpenetrating": "two parts meant to touch run into each other",
    "contact_missing": "two parts meant to touch (a joint of the drive) are apart",
    "structure": "a part is not held to the ground, a rotating body is joined rigidly to a stationary one, or a "
                 "joint element joins nothing",
    "spring_overstressed": "a preload spring's wire shear stress (Wahl-corrected) exceeds its allowable, 0.45 of "
                           "the music wire's tensile strength, at its working force or closed solid",
}

#: kinds that are interference (teeth overlapping), in the order they are reported
INTERFERENCE_KINDS = ("tip_to_root_interference", "involute_interference", "flank_interference")

#: per-position interference code used in sweep arrays: index into ``("",) + INTERFERENCE_KINDS``
INTERFERENCE_CODES = ("",) + INTERFERENCE_KINDS


@dataclass(frozen=True)
class Failure:
    """One failed check. ``value`` is the offending quantity in internal units (mm, rad or a
    plain number, named by ``quantity``); ``limit`` the bound it broke."""

    kind: str
    mesh: str
    message: str
    quantity: str = ""
    value: float | None = None
    limit: float | None = None
    mesh_position: float | None = None  # rad of gear 1, where it is worst

    def __post_init__(self):
        if self.kind not in FAILURE_KINDS:
            raise ValueError(f"unknown failure kind {self.kind!r}; allowed: {', '.join(FAILURE_KINDS)}")

    def to_dict(self, unit: str = "mm") -> dict[str, Any]:
        scale = 1.0 / LENGTH_SUFFIXES[unit]
        is_length = self.quantity.endswith("_length") or self.quantity in LENGTH_QUANTITIES
        conv = (lambda v: None if v is None else v * scale) if is_length else (lambda v: v)
        return {"kind": self.kind, "mesh": self.mesh, "message": self.message, "quantity": self.quantity,
                "value": _num(conv(self.value)), "limit": _num(conv(self.limit)),
                "unit": unit if is_length else ("rad" if self.quantity.endswith("_rad") else ""),
                "mesh_position_deg": None if self.mesh_position is None else math.degrees(self.mesh_position)}


#: quantities (names used in Failure.quantity) that are lengths
PLANETARY_LENGTHS = ("centre_distance", "backlash", "closed_form_backlash", "play_ccw", "play_cw", "design_min",
                      "sweep_min", "sweep_max",
                      "design_max", "carrier_radius", "coaxiality_difference", "coaxiality_tolerance",
                      "neighbour_tip_gap", "planet_tip_clearance")
BEVEL_LENGTHS = ("backlash", "design_backlash", "play_positive", "play_negative", "tip_clearance", "apex_distance")
RACK_LENGTHS = ("backlash_min", "backlash_max", "design_min", "design_max", "placed_backlash", "working_flank_gap",
                 "free_flank_gap", "tip_clearance", "centre_offset", "carriage_y", "carriage_deviation",
                 "carriage_needed", "carriage_travel", "carriage_y_nominal", "loop_error_travel", "rack_offset",
                 "rack_backlash")

LENGTH_QUANTITIES = ("circumferential_backlash", "normal_backlash", "min_clearance", "interference_depth",
                     "tip_land", "path_difference", "carriage_travel", "circumferential_thinning")


def _num(v):
    if v is None:
        return None
    v = float(v)
    return v if math.isfinite(v) else None


@dataclass
class MeshSweep:
    """A mesh checked at ``n`` mesh positions (arrays ``(n,)``; see the module docstring).

    ``play_ccw``/``play_cw`` (rad): free rotation of gear 1 counter-clockwise / clockwise from
    its phase until first contact with gear 2 (negative: overlap to be backed out);
    ``conjugate_play_ccw``/``_cw``: the same counting only involute-on-involute contact (and the
    tip corners on the mate's involute), so ``conjugate - play > 0`` measures a non-conjugate
    feature (fillet, root, undercut edge) limiting the motion before the flanks meet.
    ``centre_distance`` (mm) is the actual distance of the tooth centres at each position.
    ``interference_depth`` (mm): for a non-conjugate feature, how far gear 1 must turn back from
    its running position (flank contact) until the feature clears, as a length along its line
    of action (base radius x angle); for overlapping flanks the overlap along the line of
    action; for a tip past the mate's root, the radial depth under the tip circle.
    ``interference_area`` (mm^2): overlap area in the transverse section at gear 1's running
    positions (the worst of: as placed, on either flank, centred). ``interference`` holds codes into
    :data:`INTERFERENCE_CODES` (0: none).
    For helical gears the arrays hold the worst of the section planes at each position.
    """

    mesh_position: np.ndarray
    centre_distance: np.ndarray
    play_ccw: np.ndarray
    play_cw: np.ndarray
    conjugate_play_ccw: np.ndarray
    conjugate_play_cw: np.ndarray
    angular_backlash: np.ndarray
    circumferential_backlash: np.ndarray
    normal_backlash: np.ndarray
    min_clearance: np.ndarray
    interference_depth: np.ndarray
    interference_area: np.ndarray
    interference: np.ndarray
    planes: np.ndarray = field(default_factory=lambda: np.zeros(1))  # z of the sections checked (mm)

    def __len__(self) -> int:
        return len(self.mesh_position)


@dataclass
class MeshCheck:
    """The geometric check of one mesh: its sweep, summary numbers and failures.

    ``path`` is ``"exact_2d"`` (analytic profiles) or ``"sections"`` (sections of exported
    solids). Backlash summaries are in mm (circumferential on gear 1's operating pitch circle,
    and normal); ``contact_ratio`` is the measured transverse contact ratio (NaN when not
    measured) and ``total_contact_ratio`` adds the overlap ratio of helical gears.
    """

    mesh: str
    gear1: str
    gear2: str
    path: str
    centre_distance: float
    sweep: MeshSweep
    failures: list[Failure] = field(default_factory=list)
    contact_ratio: float = float("nan")
    total_contact_ratio: float = float("nan")
    notes: list[str] = field(default_factory=list)
    tolerance: float = 0.0  # stated accuracy of the backlash values (mm); path 2: tessellation

    @property
    def ok(self) -> bool:
        return not self.failures

    @property
    def failure_kinds(self) -> list[str]:
        seen: list[str] = []
        for f in self.failures:
            if f.kind not in seen:
                seen.append(f.kind)
        return seen

    def _finite(self, a):
        a = np.asarray(a, dtype=float)
        return a[np.isfinite(a)]

    @staticmethod
    def _extreme(a, fn) -> float:
        a = np.asarray(a, dtype=float)
        return float(fn(a)) if a.size and not np.all(np.isnan(a)) else float("nan")

    @property
    def min_backlash(self) -> float:
        """Smallest circumferential backlash over the sweep (mm)."""
        return self._extreme(self.sweep.circumferential_backlash, np.nanmin)

    @property
    def max_backlash(self) -> float:
        return self._extreme(self.sweep.circumferential_backlash, np.nanmax)

    @property
    def min_normal_backlash(self) -> float:
        return self._extreme(self.sweep.normal_backlash, np.nanmin)

    @property
    def max_normal_backlash(self) -> float:
        return self._extreme(self.sweep.normal_backlash, np.nanmax)

    @property
    def min_clearance(self) -> float:
        c = self._finite(self.sweep.min_clearance)
        return float(np.min(c)) if c.size else float("nan")

    @property
    def max_interference_depth(self) -> float:
        return float(np.max(self.sweep.interference_depth, initial=0.0))

    @property
    def max_interference_area(self) -> float:
        return float(np.max(self.sweep.interference_area, initial=0.0))

    def to_dict(self, unit: str = "mm", arrays: bool = False) -> dict[str, Any]:
        s = 1.0 / LENGTH_SUFFIXES[unit]
        out: dict[str, Any] = {
            "mesh": self.mesh, "gear1": self.gear1, "gear2": self.gear2, "path": self.path,
            "length_unit": unit,
            "centre_distance": self.centre_distance * s,
            "positions": len(self.sweep),
            "section_planes": [float(z) * s for z in np.atleast_1d(self.sweep.planes)],
            "circumferential_backlash_min": _num(self.min_backlash * s),
            "circumferential_backlash_max": _num(self.max_backlash * s),
            "normal_backlash_min": _num(self.min_normal_backlash * s),
            "normal_backlash_max": _num(self.max_normal_backlash * s),
            "angular_backlash_min_rad": _num(self._extreme(self.sweep.angular_backlash, np.nanmin)),
            "angular_backlash_max_rad": _num(self._extreme(self.sweep.angular_backlash, np.nanmax)),
            "min_clearance": _num(self.min_clearance * s),
            "interference_depth_max": self.max_interference_depth * s,
            "interference_area_max": self.max_interference_area * s * s,
            "contact_ratio": _num(self.contact_ratio),
            "total_contact_ratio": _num(self.total_contact_ratio),
            "tolerance": self.tolerance * s,
            "ok": self.ok,
            "failures": [f.to_dict(unit) for f in self.failures],
            "notes": list(self.notes),
        }
        if arrays:
            sw = self.sweep
            out["sweep"] = {
                "mesh_position_deg": np.degrees(sw.mesh_position).tolist(),
                "centre_distance": (sw.centre_distance * s).tolist(),
                "circumferential_backlash": [_num(v) for v in sw.circumferential_backlash * s],
                "normal_backlash": [_num(v) for v in sw.normal_backlash * s],
                "min_clearance": [_num(v) for v in sw.min_clearance * s],
                "interference_depth": (sw.interference_depth * s).tolist(),
                "interference": [INTERFERENCE_CODES[int(c)] for c in sw.interference],
            }
        return out


@dataclass(frozen=True)
class CarriageTravelLimits:
    """How far the preload carriage may move from its nominal position (mm, + away from the output).

    ``low`` (<= 0) and ``high`` (>= 0) are the travel limits each way, None where nothing limits
    it; ``low_source``/``high_source`` say which limit applies (e.g. ``"[flexures] travel"``,
    ``"[springs] solid height"``, ``"[checks] carriage_travel_limit"``).
    """

    low: float | None = None
    high: float | None = None
    low_source: str = ""
    high_source: str = ""
    notes: tuple[str, ...] = ()

    @property
    def limited(self) -> bool:
        return self.low is not None or self.high is not None


@dataclass
class ToleranceResult:
    """Minimum backlash of one mesh across the tolerances of the error budget (mm, circumferential
    at gear 1's reference circle - the resolved model's kind - and normal).

    ``worst_case_*``: the smallest backlash any error state within the budget can give - a bound
    no build at any instant falls below (how it is found: ``worst_case_method``, see
    :mod:`geargen.checks.tolerance`). ``monte_carlo_min_backlash``: per sample (one random build,
    ``samples`` draws of a seeded :class:`numpy.random.Generator`) its minimum over the positions
    ``monte_carlo_coverage`` names. ``nominal_min_backlash`` is the error-free minimum.
    ``meant_for`` is ``"backlash"`` (must stay positive) or ``"preloaded"`` (must stay in contact).
    Carriage quantities (meshes on a preload carriage): ``carriage_travel_low``/``_high`` the
    worst-case travel each way from nominal, ``monte_carlo_travel`` per sample, ``carriage_limits``
    the hardware's limits.
    """

    mesh: str
    meant_for: str
    nominal_min_backlash: float
    worst_case_min_backlash: float
    worst_case_min_normal_backlash: float
    monte_carlo_min_backlash: np.ndarray  # (samples,) per-sample minimum over monte_carlo_coverage
    worst_case_centre_distance_change: float  # mm, radial (negative: closer)
    failures: list[Failure] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    carriage_travel: float = float("nan")  # mm, largest worst-case travel either way of a preload carriage
    revolutions: MeshSweep | None = None  # the mesh over its hunting period with the eccentricities aligned
    monte_carlo_coverage: str = ""
    monte_carlo_model_difference: float = float("nan")  # mm, largest |exact - model| at the samples' minima
    worst_case_method: str = ""
    carriage_travel_low: float = float("nan")
    carriage_travel_high: float = float("nan")
    monte_carlo_travel: np.ndarray = field(default_factory=lambda: np.empty(0))
    carriage_limits: CarriageTravelLimits | None = None
    loop_samples_without_backlash: int | None = None  # builds losing backlash in some mesh of the loop

    @property
    def samples(self) -> int:
        return int(self.monte_carlo_min_backlash.size)

    @property
    def samples_without_backlash(self) -> int:
        """Samples whose minimum backlash over the positions they cover is <= 0."""
        return int(np.count_nonzero(self.monte_carlo_min_backlash <= 0))

    @property
    def monte_carlo_minimum(self) -> float:
        return float(np.min(self.monte_carlo_min_backlash)) if self.samples else float("nan")

    def monte_carlo_quantile(self, q: float) -> float:
        return float(np.quantile(self.monte_carlo_min_backlash, q)) if self.samples else float("nan")

    @property
    def ok(self) -> bool:
        return not self.failures

    def to_dict(self, unit: str = "mm") -> dict[str, Any]:
        s = 1.0 / LENGTH_SUFFIXES[unit]
        travel = self.monte_carlo_travel
        lim = self.carriage_limits
        out = {
            "mesh": self.mesh, "meant_for": self.meant_for, "length_unit": unit,
            "nominal_min_backlash": self.nominal_min_backlash * s,
            "worst_case_min_backlash": self.worst_case_min_backlash * s,
            "worst_case_min_normal_backlash": self.worst_case_min_normal_backlash * s,
            "worst_case_centre_distance_change": self.worst_case_centre_distance_change * s,
            "worst_case_method": self.worst_case_method,
            "monte_carlo_samples": self.samples,
            "monte_carlo_coverage": self.monte_carlo_coverage,
            "monte_carlo_samples_without_backlash": self.samples_without_backlash,
            "monte_carlo_min_backlash": _num(self.monte_carlo_minimum * s),
            "monte_carlo_min_backlash_p01": _num(self.monte_carlo_quantile(0.01) * s),
            "monte_carlo_min_backlash_median": _num(self.monte_carlo_quantile(0.5) * s),
            "monte_carlo_model_difference": _num(self.monte_carlo_model_difference * s),
            "carriage_travel": _num(self.carriage_travel * s),
            "carriage_travel_low": _num(self.carriage_travel_low * s),
            "carriage_travel_high": _num(self.carriage_travel_high * s),
            "monte_carlo_carriage_travel_low": _num(travel.min() * s) if travel.size else None,
            "monte_carlo_carriage_travel_high": _num(travel.max() * s) if travel.size else None,
            "ok": self.ok,
            "failures": [f.to_dict(unit) for f in self.failures],
            "notes": list(self.notes),
        }
        if lim is not None:
            out["carriage_travel_limit_low"] = None if lim.low is None else lim.low * s
            out["carriage_travel_limit_high"] = None if lim.high is None else lim.high * s
            out["carriage_travel_limit_low_source"] = lim.low_source
            out["carriage_travel_limit_high_source"] = lim.high_source
        if self.loop_samples_without_backlash is not None:
            out["loop_samples_without_backlash"] = self.loop_samples_without_backlash
        return out


#: keys of a path-agreement record (geargen.checks.solids.compare_paths) that are lengths
_AGREEMENT_LENGTHS = ("normal_backlash_difference_max", "normal_backlash_difference_mean", "min_clearance_difference",
                      "tolerance")


#: keys of a design-kind backlash record (DesignCheck.backlash) that are lengths
_BACKLASH_LENGTHS = ("centre_distance", "modelled", "design_min", "design_max", "min", "max", "axial_clearance")


#: keys of a backlash-range record (DesignCheck.backlash_range) that are lengths or pairs of lengths
_RANGE_LENGTHS = ("centre_distance", "centre_distance_tolerance", "analytic", "measured", "difference",
                  "agreement_tolerance", "design")


def _scaled(v, s):
    return [_num(x * s) for x in v] if isinstance(v, (list, tuple)) else _num(v * s)


@dataclass
class DesignCheck:
    """Every mesh of a design checked: per-mesh results, tolerance results, design-level failures."""

    design: str
    length_unit: str
    meshes: list[MeshCheck]
    tolerances: list[ToleranceResult] = field(default_factory=list)
    agreement: list[dict[str, Any]] = field(default_factory=list)  # path 1 vs path 2 per mesh
    failures: list[Failure] = field(default_factory=list)  # design-level (not tied to one sweep)
    notes: list[str] = field(default_factory=list)
    # per mesh, in the resolved model's kind (geargen.model.BACKLASH_KIND, mm): min/max measured on
    # path 1, the modelled value, the design range, the centre distance where the mesh runs
    backlash: list[dict[str, Any]] = field(default_factory=list)
    # per mesh with thickness allowances (geargen.checks.allowance, mm): the range they give with the
    # centre-distance tolerance, analytic and measured on the thinnest and thickest teeth
    backlash_range: list[dict[str, Any]] = field(default_factory=list)
    # the drive kind's own rows (geargen.drives.kind.DriveKind.rows: placed pairs the mesh checker
    # does not check, mm, rad, N), each naming the table it belongs to ("table")
    rows: list[dict[str, Any]] = field(default_factory=list)
    # the resolved drive's parts read against each other (geargen.checks.hardware.PartsReport) and how
    # they hold together (geargen.checks.structure.StructureReport); None: the drive has no hardware
    parts: Any = None
    structure: Any = None
    # the values the file does not give as the drive uses them (geargen.drives.defaulted) and the
    # resolved [parts] as TOML to paste into the file (geargen.drives.parts_table)
    defaulted: tuple = ()
    parts_table: str = ""
    # every mesh's load capacity (geargen.checks.rating.DriveRating); None: not a resolved drive
    load_capacity: Any = None

    def table(self, name: str) -> list[dict[str, Any]]:
        """The drive kind's rows of table ``name``."""
        return [r for r in self.rows if r.get("table") == name]

    @property
    def bevel(self) -> list[dict[str, Any]]:
        return self.table("bevel")

    @property
    def planetary(self) -> list[dict[str, Any]]:
        return self.table("planetary")

    @property
    def rack(self) -> list[dict[str, Any]]:
        return self.table("rack")

    @property
    def all_failures(self) -> list[Failure]:
        out = list(self.failures)
        for m in self.meshes:
            out.extend(m.failures)
        for t in self.tolerances:
            out.extend(t.failures)
        return out

    @property
    def ok(self) -> bool:
        return not self.all_failures

    def to_dict(self, arrays: bool = False) -> dict[str, Any]:
        u = self.length_unit
        s = 1.0 / LENGTH_SUFFIXES[u]
        return {
            "design": self.design, "length_unit": u, "ok": self.ok,
            "meshes": [m.to_dict(u, arrays=arrays) for m in self.meshes],
            "tolerances": [t.to_dict(u) for t in self.tolerances],
            "agreement": [{k: (v * s if k in _AGREEMENT_LENGTHS and v is not None else v) for k, v in a.items()}
                          for a in self.agreement],
            "failures": [f.to_dict(u) for f in self.failures],
            "notes": list(self.notes),
            "backlash": [{key: (_num(v * s) if key in _BACKLASH_LENGTHS and v is not None else v)
                          for key, v in b.items()} for b in self.backlash],
            "backlash_range": [{key: (_scaled(v, s) if key in _RANGE_LENGTHS else v) for key, v in r.items()}
                               for r in self.backlash_range],
            "bevel": [{key: (_num(v * s) if key in BEVEL_LENGTHS else v) for key, v in b.items()} for b in self.bevel],
            "planetary": [{key: (_num(v * s) if key in PLANETARY_LENGTHS else v) for key, v in b.items()}
                          for b in self.planetary],
            "rack": [{key: (_num(v * s) if key in RACK_LENGTHS and v is not None else v) for key, v in b.items()}
                     for b in self.rack],
            "load_capacity": None if self.load_capacity is None else self.load_capacity.to_dict(),
        }


__all__ = ["FAILURE_KINDS", "INTERFERENCE_KINDS", "INTERFERENCE_CODES", "Failure", "MeshSweep", "MeshCheck",
           "CarriageTravelLimits", "ToleranceResult", "DesignCheck", "BEVEL_LENGTHS", "PLANETARY_LENGTHS",
           "RACK_LENGTHS"]
