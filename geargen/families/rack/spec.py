"""A gear rack as designed: :class:`RackSpec` (validated on construction) and its design-file table.

Internal units: mm and rad. The spec holds the *normal* system (normal module, normal pressure
angle), like :class:`geargen.design.gear.GearSpec`; a helical rack's teeth are inclined at the
helix angle to the rack's width direction, so it meshes with a helical pinion of the same normal
module, pressure angle and helix angle. A rack's ``hand`` is that of the pinion it meshes with
(the teeth lie along the pinion's teeth at the contact; see :class:`RackSpec` for the frame).

Design-file table (``[gear]`` with ``kind = "rack"``)::

    kind = "rack"
    module_mm = 2                     # or diametral_pitch_per_in
    pressure_angle_deg = 20
    helix_angle_deg = 0               # 0: spur rack
    hand = "right"
    teeth = 30                        # or length_mm = 188.4956 (a whole number of transverse pitches)
    face_width_mm = 20
    pitch_line_height_mm = 20         # back face to pitch line; or back_height_mm (back face to root line)
    tip_rounding = "sharp"            # or "generating" (see RackSpec)
    root_fillet_coefficient = 0.38    # root fillet radius over the module; 0: sharp root corners
    thinning_circumferential_mm = 0.02

Rack outline, normal section (heights from the pitch line, positive toward the tips): straight
flanks at the pressure angle from the tooth's centre line, a tip land at ``h_a* m`` and a root
land at ``-h_f* m``; the tooth thickness at the pitch line is ``pi m / 2`` minus the normal thinning.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from geargen.design.gear import DEG, HANDS, HelicalTeeth, check_number, with_field_prefix
from geargen.design.schema import GEAR_NAME_MAX, Field, read_table
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES, MM_PER_IN, module_from_diametral_pitch

#: "sharp": the tip corners are sharp (the basic rack's straight outline);
#: "generating": each tip corner is a circular arc (normal section) of radius
#: ``tip_radius_coefficient * m`` tangent to the flank and the tip land - the tip of the basic rack
#: that generates the mating pinion (GearSpec.rack_tip_radius_coefficient). With the same radius the
#: rack's tooth lies inside that cutter's tooth (its tip line h_a* <= the cutter's h_f*), so the rack
#: cannot reach the pinion's generated (trochoidal) root: no trochoid interference by construction.
TIP_ROUNDINGS = ("sharp", "generating")

#: lands and flanks the arcs leave shorter than this (over the module) and longer than ZERO_SEGMENT
#: are refused; up to ZERO_SEGMENT they are the full-radius form, built without them
SHORTEST_SEGMENT = 1e-5
ZERO_SEGMENT = 1e-9

#: ISO 53:1998 basic rack profile A: root fillet radius 0.38 m (also the default generating tip radius)
ISO53_FILLET = 0.38


def corner_tangent_length(pressure_angle: float) -> float:
    """Distance (over the radius) from a rack corner (flank meets land, the inner angle is
    ``pi/2 + alpha`` at tips and roots alike) to the tangent points of a fillet of that radius:
    ``cot(pi/4 + alpha/2) = (1 - sin alpha) / cos alpha``."""
    return (1.0 - math.sin(pressure_angle)) / math.cos(pressure_angle)


@dataclass(frozen=True)
class RackSpec(HelicalTeeth):
    """A straight-tooth (spur, ``helix_angle`` 0) or helical rack, normal system, mm and rad.

    Frame of the solid (:mod:`geargen.families.rack.solid`): x along the rack's length (0 .. length),
    y up from the back face (y = 0) through the pitch line (``pitch_line_height``) to the tips,
    z across the face width (0 .. face_width). Tooth ``i`` is centred at
    ``x = (i + 1/2) p_t`` in the z = 0 section; the section at z is that section moved by
    ``z tan(beta)`` along +x for a right hand and -x for a left hand (teeth leaning like a
    right-hand helix's teeth seen from the pinion side: a right-hand helical pinion above the rack
    meshes with a right-hand rack). ``thinning`` is the tooth-thickness reduction as a transverse
    length along the pitch line (circumferential, like the gear's).
    """

    teeth: int
    module: float
    pressure_angle: float
    face_width: float
    pitch_line_height: float
    helix_angle: float = 0.0
    hand: str = "right"
    addendum_coefficient: float = 1.0
    dedendum_coefficient: float = 1.25
    tip_rounding: str = "sharp"
    tip_radius_coefficient: float | None = None  # "generating" only; None: min(0.38, largest that fits)
    root_fillet_coefficient: float | None = None  # None: min(0.38, largest that fits); 0: sharp
    thinning: float = 0.0
    name: str = "rack"
    length_unit: str = "mm"
    kind: str = "rack"
    # tooth-thickness allowance (E_sns, E_sni): normal deviations at the pitch line from the
    # zero-backlash tooth p_n / 2 (mm, lower <= upper <= 0); None: not specified
    thickness_deviations: tuple[float, float] | None = None

    def __post_init__(self):
        if self.kind != "rack":
            raise DesignError("kind", f"{self.kind!r} is not a rack", "'rack'")
        if isinstance(self.teeth, bool) or not isinstance(self.teeth, int):
            raise DesignError("teeth", f"expected a whole number, got {self.teeth!r}")
        check_number("teeth", self.teeth, 1, 10000, "")
        check_number("module", self.module, 0.01, 200.0, "mm", exclusive_lo=True)
        check_number("pressure_angle", self.pressure_angle, 10 * DEG, 35 * DEG, "rad")
        check_number("face_width", self.face_width, 0.0, 5000.0, "mm", exclusive_lo=True, length_unit=self.length_unit)
        check_number("helix_angle", self.helix_angle, 0.0, 45 * DEG, "rad")
        if self.hand not in HANDS:
            raise DesignError("hand", f"{self.hand!r} is not a valid choice", "'right', 'left'")
        check_number("addendum_coefficient", self.addendum_coefficient, 0.3, 1.5, "")
        check_number("dedendum_coefficient", self.dedendum_coefficient, 0.5, 2.0, "")
        check_number("thinning", self.thinning, 0.0, 0.25 * self.transverse_pitch, "mm", length_unit=self.length_unit)
        if self.thickness_deviations is not None:
            upper, lower = self.thickness_deviations
            if not (math.isfinite(upper) and math.isfinite(lower) and lower <= upper <= 0):
                raise DesignError("thickness_upper_deviation", f"({upper!r}, {lower!r}) mm is out of range",
                                  "lower <= upper <= 0")
        if self.tip_rounding not in TIP_ROUNDINGS:
            raise DesignError("tip_rounding", f"{self.tip_rounding!r} is not a valid choice",
                              ", ".join(map(repr, TIP_ROUNDINGS)))
        if self.tip_land_half_width <= 0:
            raise DesignError("addendum_coefficient", "the rack's teeth come to a point below their tip line",
                              f"< {self._pointed_addendum_coefficient():.6g} with this pressure angle and thinning")
        if self.root_space_half_width <= 0:
            raise DesignError("dedendum_coefficient", "the rack's tooth spaces close below their root line",
                              f"< {self._closed_dedendum_coefficient():.6g} with this pressure angle")
        if self.tip_rounding == "sharp":
            if self.tip_radius_coefficient not in (None, 0, 0.0):
                raise DesignError("tip_radius_coefficient", "a tip radius needs tip_rounding = \"generating\"",
                                  "no tip radius with sharp tips")
            object.__setattr__(self, "tip_radius_coefficient", 0.0)
        elif self.tip_radius_coefficient is None:
            object.__setattr__(self, "tip_radius_coefficient", min(ISO53_FILLET, self.max_tip_radius_coefficient(0.0)))
        check_number("tip_radius_coefficient", self.tip_radius_coefficient, 0.0, self.max_tip_radius_coefficient(0.0),
                     "")
        if self.root_fillet_coefficient is None:
            object.__setattr__(self, "root_fillet_coefficient",
                               min(ISO53_FILLET, self.max_root_fillet_coefficient(self.tip_radius_coefficient)))
        check_number("root_fillet_coefficient", self.root_fillet_coefficient, 0.0,
               self.max_root_fillet_coefficient(self.tip_radius_coefficient), "")
        self._check_short_segments()
        check_number("pitch_line_height", self.pitch_line_height, self.dedendum, 1e5, "mm", exclusive_lo=True, length_unit=self.length_unit)
        if self.length_unit not in ("mm", "in"):
            raise DesignError("length_unit", f"{self.length_unit!r} is not a valid choice", "'mm', 'in'")

    def _check_short_segments(self) -> None:
        """A land or flank that the arcs leave shorter than SHORTEST_SEGMENT modules but not zero
        cannot be built (edges below the kernel's tolerance): refused, naming the radius. Zero
        (within ZERO_SEGMENT modules) is the full-radius form and is built without that segment."""
        t = corner_tangent_length(self.pressure_angle)
        m = self.module
        flank = (self.addendum + self.dedendum) / math.cos(self.pressure_angle)
        for name, what, length in (
                ("root_fillet_coefficient", "root land", 2 * (self.root_space_half_width - self.root_fillet_radius * t)),
                ("tip_radius_coefficient", "tip land", 2 * (self.tip_land_half_width - self.tip_radius * t)),
                ("root_fillet_coefficient", "flank", flank - (self.tip_radius + self.root_fillet_radius) * t)):
            if ZERO_SEGMENT * m < length < SHORTEST_SEGMENT * m:
                raise DesignError(name, f"{getattr(self, name)!r} leaves a {what} of {length:.3g} mm, too short to "
                                  "build", f"a {what} of 0 (the largest radius) or of at least {SHORTEST_SEGMENT:g} "
                                  "modules")

    # --- closed-form basics (and HelicalTeeth's; the pair geometry lives in geargen.families.rack.geometry)
    @property
    def normal_pitch(self) -> float:
        return math.pi * self.module

    @property
    def transverse_pitch(self) -> float:
        """Pitch along the rack's length (mm)."""
        return math.pi * self.transverse_module

    @property
    def length(self) -> float:
        """Length of the rack: a whole number of transverse pitches (mm)."""
        return self.teeth * self.transverse_pitch

    @property
    def signed_helix_angle(self) -> float:
        return self.helix_angle if self.hand == "right" else -self.helix_angle

    @property
    def addendum(self) -> float:
        return self.addendum_coefficient * self.module

    @property
    def dedendum(self) -> float:
        return self.dedendum_coefficient * self.module

    @property
    def back_height(self) -> float:
        """Back face to root line (mm)."""
        return self.pitch_line_height - self.dedendum

    @property
    def height(self) -> float:
        """Back face to tip line (mm)."""
        return self.pitch_line_height + self.addendum

    @property
    def thinning_normal(self) -> float:
        return self.thinning * math.cos(self.helix_angle)

    @property
    def normal_tooth_thickness(self) -> float:
        """Normal tooth thickness at the pitch line (mm)."""
        return self.normal_pitch / 2 - self.thinning_normal

    @property
    def tip_land_half_width(self) -> float:
        """Half the normal tooth thickness at the tip line of the straight flanks (sharp corners)."""
        return self.normal_tooth_thickness / 2 - self.addendum * math.tan(self.pressure_angle)

    @property
    def root_space_half_width(self) -> float:
        """Half the normal space width at the root line of the straight flanks (sharp corners)."""
        return self.normal_pitch / 2 - self.normal_tooth_thickness / 2 - self.dedendum * math.tan(self.pressure_angle)

    def _pointed_addendum_coefficient(self) -> float:
        return self.normal_tooth_thickness / 2 / math.tan(self.pressure_angle) / self.module

    def _closed_dedendum_coefficient(self) -> float:
        return (self.normal_pitch / 2 - self.normal_tooth_thickness / 2) / math.tan(self.pressure_angle) / self.module

    def _flank_room(self) -> float:
        """Straight flank length (sharp corners) over the module's tangent length unit."""
        return (self.addendum + self.dedendum) / math.cos(self.pressure_angle) / corner_tangent_length(self.pressure_angle)

    def max_tip_radius_coefficient(self, root_fillet_coefficient: float = 0.0) -> float:
        """Largest tip radius (over m) whose arc fits the tip land and, with the root fillet, the flank."""
        t = corner_tangent_length(self.pressure_angle)
        return max(0.0, min(self.tip_land_half_width / t, self._flank_room() - root_fillet_coefficient * self.module)
                   / self.module)

    def max_root_fillet_coefficient(self, tip_radius_coefficient: float = 0.0) -> float:
        """Largest root fillet radius (over m) that fits the root space and, with the tip arc, the flank."""
        t = corner_tangent_length(self.pressure_angle)
        return max(0.0, min(self.root_space_half_width / t, self._flank_room() - tip_radius_coefficient * self.module)
                   / self.module)

    @property
    def tip_radius(self) -> float:
        return self.tip_radius_coefficient * self.module

    @property
    def root_fillet_radius(self) -> float:
        return self.root_fillet_coefficient * self.module


RACK_FIELDS: list[Field] = [
    Field("kind", "string", choices=("rack",), help="\"rack\": a spur or helical gear rack"),
    Field("name", "name", required=False, default=None, maximum=GEAR_NAME_MAX,
          help="the rack's label in reports and exports (default: the table's name, its identity)"),
    Field("teeth", "integer", required=False, default=None, minimum=1, maximum=10000,
          help="number of teeth along the rack (its length is teeth x the transverse pitch); give this or length"),
    Field("length", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="length of the rack: a whole number of transverse pitches (give this or teeth)"),
    Field("module", "length", required=False, units=("mm",), minimum=0.01, exclusive_minimum=True, maximum=200.0,
          help="normal module; give this or diametral_pitch_per_in"),
    Field("diametral_pitch_per_in", "number", required=False, minimum=MM_PER_IN / 200.0, maximum=MM_PER_IN / 0.01,
          exclusive_maximum=True, help="normal diametral pitch (module = 25.4 mm / P); give this or module_mm"),
    Field("pressure_angle", "angle", required=False, default=20 * DEG, units=("deg", "rad"), minimum=10 * DEG,
          maximum=35 * DEG, help="normal pressure angle: the flank's angle to the tooth's centre line"),
    Field("helix_angle", "angle", required=False, default=0.0, units=("deg", "rad"), minimum=0.0, maximum=45 * DEG,
          help="angle of the teeth to the rack's width direction (the mating pinion's helix angle); 0: spur"),
    Field("hand", "string", required=False, default="right", choices=HANDS,
          help="hand of the mating helical pinion (a right-hand pinion meshes with a right-hand rack)"),
    Field("face_width", "length", minimum=0.0, exclusive_minimum=True, maximum=5000.0, help="width of the rack"),
    Field("pitch_line_height", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="back face to pitch line (give this or back_height; default: back_height of 2 modules)"),
    Field("back_height", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="back face to root line (give this or pitch_line_height)"),
    Field("addendum_coefficient", "number", required=False, default=1.0, minimum=0.3, maximum=1.5,
          help="rack addendum over the module (pitch line to tip line)"),
    Field("dedendum_coefficient", "number", required=False, default=1.25, minimum=0.5, maximum=2.0,
          help="rack dedendum over the module (pitch line to root line)"),
    Field("tip_rounding", "string", required=False, default="sharp", choices=TIP_ROUNDINGS,
          help="sharp tip corners, or \"generating\": tip corners rounded like the tip of the basic rack that cuts "
               "the pinion (radius tip_radius_coefficient x m), so the rack cannot touch the pinion's generated root"),
    Field("tip_radius_coefficient", "number", required=False, default=None, minimum=0.0, maximum=1.0,
          help="tip_rounding = \"generating\": tip radius over the module (default 0.38, or the largest that fits)"),
    Field("root_fillet_coefficient", "number", required=False, default=None, minimum=0.0, maximum=1.0,
          help="root fillet radius over the module (default 0.38 as ISO 53 profile A, or the largest that fits; "
               "0: sharp root corners)"),
    Field("thinning_circumferential", "length", required=False, default=None, minimum=0.0,
          help="tooth thinning for backlash along the pitch line, transverse (give at most one thinning)"),
    Field("thinning_normal", "length", required=False, default=None, minimum=0.0,
          help="tooth thinning for backlash, normal tooth thickness at the pitch line (give at most one thinning)"),
    Field("thickness_upper_deviation", "length", required=False, default=None, maximum=0.0,
          help="tooth-thickness allowance: upper deviation E_sns of the normal tooth thickness at the pitch line from "
               "p_n / 2 (<= 0; give both deviations, or neither: not specified)"),
    Field("thickness_lower_deviation", "length", required=False, default=None, maximum=0.0,
          help="tooth-thickness allowance: lower deviation E_sni (<= the upper deviation)"),
]

#: back height (under the root line) when neither height is given, over the module
DEFAULT_BACK_MODULES = 2.0


def rack_from_table(data: Mapping[str, Any], where: str = "gear", name: str | None = None,
                    length_unit: str | None = None) -> RackSpec:
    """Build a :class:`RackSpec` from a design table (same signature as ``gear_from_table``)."""
    v = read_table(data, RACK_FIELDS, where)
    p = f"{where}."
    units = v["_units"]
    if (v["module"] is None) == (v["diametral_pitch_per_in"] is None):
        raise DesignError(p + "module_mm", "give exactly one of module_mm and diametral_pitch_per_in",
                          "module_mm in (0.01, 200] or diametral_pitch_per_in in [0.127, 2540)")
    if v["module"] is not None:
        module, unit = v["module"], "mm"
    else:
        module, unit = module_from_diametral_pitch(v["diametral_pitch_per_in"]), "in"
    beta = v["helix_angle"]
    pitch_t = math.pi * module / math.cos(beta)
    if (v["teeth"] is None) == (v["length"] is None):
        raise DesignError(p + "teeth", "give exactly one of teeth and length", "teeth >= 1 or length_* > 0")
    teeth = v["teeth"]
    if teeth is None:
        n = round(v["length"] / pitch_t)
        scale = LENGTH_SUFFIXES[units["length"]]
        if n < 1 or abs(v["length"] - n * pitch_t) > 1e-9 * max(1.0, v["length"]) + 1e-9:
            near = sorted({max(1, n), max(1, n) + 1} if n * pitch_t < v["length"] else {max(1, n - 1), max(1, n)})
            raise DesignError(f"{p}length_{units['length']}", f"{v['length'] / scale:.9g} {units['length']} is not a "
                              "whole number of transverse pitches", " or ".join(
                                  f"{k * pitch_t / scale:.9g}" for k in near) + f" {units['length']} (or give teeth)")
        teeth = int(n)
    if v["thinning_circumferential"] is not None and v["thinning_normal"] is not None:
        raise DesignError(p + "thinning_normal", "give at most one tooth-thinning kind",
                          "thinning_circumferential_* or thinning_normal_*")
    thinning = (v["thinning_normal"] / math.cos(beta) if v["thinning_normal"] is not None
                else v["thinning_circumferential"] or 0.0)
    most = pitch_t / 4  # RackSpec's limit: a quarter of the transverse pitch
    if thinning > most:
        kind = "thinning_normal" if v["thinning_normal"] is not None else "thinning_circumferential"
        factor = math.cos(beta) if kind == "thinning_normal" else 1.0
        scale = LENGTH_SUFFIXES[units[kind]]
        raise DesignError(f"{p}{kind}_{units[kind]}", f"{thinning * factor / scale:.6g} {units[kind]} is out of range",
                          f"[0, {most * factor / scale:.6g}] {units[kind]} (a quarter of the pitch)")
    if v["pitch_line_height"] is not None and v["back_height"] is not None:
        raise DesignError(p + "back_height", "give at most one of pitch_line_height and back_height",
                          "pitch_line_height_* or back_height_*")
    dedendum = v["dedendum_coefficient"] * module
    if v["pitch_line_height"] is not None:
        height = v["pitch_line_height"]
    else:
        height = dedendum + (v["back_height"] if v["back_height"] is not None else DEFAULT_BACK_MODULES * module)
    if (v["thickness_upper_deviation"] is None) != (v["thickness_lower_deviation"] is None):
        missing = "lower" if v["thickness_upper_deviation"] is not None else "upper"
        raise DesignError(f"{p}thickness_{missing}_deviation_um", "missing: the other deviation is given",
                          "both thickness_upper_deviation_* and thickness_lower_deviation_*, or neither")
    deviations = None
    if v["thickness_upper_deviation"] is not None:
        deviations = (v["thickness_upper_deviation"], v["thickness_lower_deviation"])
        if deviations[1] > deviations[0]:
            unit_d = units["thickness_lower_deviation"]
            scale = LENGTH_SUFFIXES[unit_d]
            raise DesignError(f"{p}thickness_lower_deviation_{unit_d}", f"{deviations[1] / scale:.6g} {unit_d} is "
                              "above the upper deviation", f"<= {deviations[0] / scale:.6g} {unit_d}")
    kwargs = dict(teeth=teeth, module=module, pressure_angle=v["pressure_angle"], face_width=v["face_width"],
                  pitch_line_height=height, helix_angle=beta, hand=v["hand"],
                  addendum_coefficient=v["addendum_coefficient"], dedendum_coefficient=v["dedendum_coefficient"],
                  tip_rounding=v["tip_rounding"], tip_radius_coefficient=v["tip_radius_coefficient"],
                  root_fillet_coefficient=v["root_fillet_coefficient"], thinning=thinning,
                  name=name or v["name"] or "rack", length_unit=length_unit or unit, thickness_deviations=deviations)
    if v["thinning_normal"] is not None:
        units = {**units, "thinning": units["thinning_normal"]}
        renamed = {"thinning": "thinning_normal"}
    else:
        units = {**units, "thinning": units.get("thinning_circumferential", unit)}
        renamed = {"thinning": "thinning_circumferential"}
    try:
        return with_field_prefix("", lambda: RackSpec(**kwargs), units)
    except DesignError as exc:
        key = exc.field
        stem = key.rsplit("_", 1)[0] if key.rsplit("_", 1)[-1] in LENGTH_SUFFIXES else key
        if stem in renamed:
            key = f"{renamed[stem]}_{units['thinning']}"
        if stem == "pitch_line_height" and v["back_height"] is not None:
            key = f"back_height_{units['back_height']}"
        raise DesignError(p + key, exc.problem, exc.allowed) from None


__all__ = ["RackSpec", "RACK_FIELDS", "TIP_ROUNDINGS", "rack_from_table", "corner_tangent_length"]
