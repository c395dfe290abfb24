"""A straight bevel gear as designed: :class:`BevelGearSpec` and its design-file table.

A bevel gear is defined with its mate: the pitch cone angle follows from both tooth numbers and
the shaft angle. Internal units mm and rad; the module (or diametral pitch) is the heel's (outer
cone's), the face width is measured along the cone.

Tooth proportions: *standard* (equal-addendum) proportions, addendum h_a = (h_a* + x) m and
dedendum h_f = (h_f* - x) m at the heel, with h_a* = 1 and h_f* = 1.25 by default (KHK Gear
Technical Reference, "standard straight bevel gears"). A Gleason-style unequal addendum is the
same thing with x1 = -x2 (:func:`geargen.families.bevel.geometry.gleason_profile_shift` gives the shift of
Gleason's addendum rule). Tip and root cones pass through the apex (the tooth depth tapers to
the apex, no constant clearance).

Design-file table (``[gear]`` or ``[gears.NAME]``)::

    kind = "bevel"
    teeth = 15
    mate_teeth = 30
    shaft_angle_deg = 90              # default 90
    diametral_pitch_per_in = 32       # or module_mm = 0.8 (at the heel)
    pressure_angle_deg = 20           # default 20
    face_width_in = 0.15              # along the cone; up to a third of the cone distance
    profile_shift = 0.0
    thinning_circumferential_in = 0.0 # arc at the heel pitch circle
    bore_diameter_in = 0.0
    back = "flat"                     # or "spherical" (the heel sphere), default flat as the build
    accuracy_grade = 7                # optional, ISO 17485 accuracy grade 2..11
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from geargen.design.gear import check_number
from geargen.design.schema import GEAR_NAME_MAX, Field, read_table
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES, MM_PER_IN, module_from_diametral_pitch

DEG = math.pi / 180.0


@dataclass(frozen=True)
class BevelGearSpec:
    """A straight bevel gear with spherical-involute teeth (mm, rad); see the module docstring.

    ``thinning`` is the tooth-thickness reduction for backlash as an arc of the heel pitch circle.
    ``warnings`` lists the design rules the gear breaks without being impossible (face width
    beyond a third of the cone distance).
    """

    teeth: int
    mate_teeth: int
    module: float
    face_width: float
    shaft_angle: float = 90 * DEG
    pressure_angle: float = 20 * DEG
    profile_shift: float = 0.0
    addendum_coefficient: float = 1.0
    dedendum_coefficient: float = 1.25
    thinning: float = 0.0
    bore_diameter: float = 0.0
    name: str = "bevel"
    length_unit: str = "mm"
    kind: str = "bevel"
    # the back the solid is cut with (geargen.families.bevel.geometry.BACKS): flat through the heel root circle,
    # as the robot joint's pair is built, so `geargen gear` and the build describe one solid
    back: str = "flat"
    accuracy_grade: int | None = None  # ISO 17485 accuracy grade (2..11), None: not specified

    def __post_init__(self):
        if self.kind != "bevel":
            raise DesignError("kind", f"{self.kind!r} is not a bevel gear kind", "'bevel'")
        for name in ("teeth", "mate_teeth"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int):
                raise DesignError(name, f"expected a whole number, got {value!r}")
            check_number(name, value, 5, 1000, "")
        check_number("module", self.module, 0.05, 100.0, "mm", exclusive_lo=True)
        check_number("shaft_angle", self.shaft_angle, 10 * DEG, 170 * DEG, "rad")
        check_number("pressure_angle", self.pressure_angle, 10 * DEG, 30 * DEG, "rad")
        check_number("profile_shift", self.profile_shift, -0.8, 0.8, "")
        check_number("addendum_coefficient", self.addendum_coefficient, 0.5, 1.5, "")
        check_number("dedendum_coefficient", self.dedendum_coefficient, 0.8, 2.0, "")
        if self.dedendum_coefficient <= self.addendum_coefficient:
            raise DesignError("dedendum_coefficient", "leaves no tip clearance with the mate",
                              f"> addendum_coefficient ({self.addendum_coefficient:g})")
        if self.pitch_cone_angle > 90 * DEG + 1e-12:
            raise DesignError("shaft_angle", f"makes the pitch cone angle {math.degrees(self.pitch_cone_angle):.4g} deg: "
                              "an internal bevel gear, which is not built",
                              f"shaft angle <= {math.degrees(90 * DEG + self.mate_pitch_cone_angle):.6g} deg "
                              "(pitch cone angle <= 90 deg)")
        if self.back not in ("flat", "spherical"):
            raise DesignError("back", f"{self.back!r} is not a bevel gear back", "'flat', 'spherical'")
        if self.accuracy_grade is not None:
            if isinstance(self.accuracy_grade, bool) or not isinstance(self.accuracy_grade, int):
                raise DesignError("accuracy_grade", f"expected a whole number, got {self.accuracy_grade!r}")
            check_number("accuracy_grade", self.accuracy_grade, 2, 11, "")
        if self.length_unit not in ("mm", "in"):
            raise DesignError("length_unit", f"{self.length_unit!r} is not a valid choice", "'mm', 'in'")
        # the toe must stay a real sphere with a whole tooth on it: at most 0.6 R_e (a third is the rule)
        check_number("face_width", self.face_width, 0.0, 0.6 * self.cone_distance, "mm", exclusive_lo=True, length_unit=self.length_unit)
        check_number("thinning", self.thinning, 0.0, 0.25 * math.pi * self.module, "mm", length_unit=self.length_unit)
        check_number("bore_diameter", self.bore_diameter, 0.0, math.inf, "mm", length_unit=self.length_unit)
        if self.bore_diameter > 0:
            # the bore runs along the axis and must stay inside the root cone at the toe
            most = 2 * self.toe_cone_distance * math.sin(self.pitch_cone_angle - self.dedendum_angle) * 0.95
            if self.bore_diameter >= most:
                raise DesignError("bore_diameter", "cuts into the tooth root at the toe", f"< {most:.6g} mm")

    # --- the pair's cones (closed forms; the rest of the geometry is geargen.families.bevel.geometry) ---
    @property
    def pitch_cone_angle(self) -> float:
        """delta: tan delta = sin Sigma / (z_mate / z + cos Sigma)."""
        s = self.shaft_angle
        return math.atan2(math.sin(s), self.mate_teeth / self.teeth + math.cos(s))

    @property
    def mate_pitch_cone_angle(self) -> float:
        return self.shaft_angle - self.pitch_cone_angle

    @property
    def reference_diameter(self) -> float:
        """Pitch diameter at the heel, d = z m."""
        return self.teeth * self.module

    @property
    def cone_distance(self) -> float:
        """Outer cone distance R_e = d / (2 sin delta)."""
        return self.reference_diameter / (2 * math.sin(self.pitch_cone_angle))

    @property
    def toe_cone_distance(self) -> float:
        return self.cone_distance - self.face_width

    @property
    def addendum(self) -> float:
        return (self.addendum_coefficient + self.profile_shift) * self.module

    @property
    def dedendum(self) -> float:
        return (self.dedendum_coefficient - self.profile_shift) * self.module

    @property
    def addendum_angle(self) -> float:
        return math.atan(self.addendum / self.cone_distance)

    @property
    def dedendum_angle(self) -> float:
        return math.atan(self.dedendum / self.cone_distance)

    @property
    def warnings(self) -> list[str]:
        out = []
        if self.face_width > self.cone_distance / 3 * (1 + 1e-9):
            out.append(f"face width {self.face_width:.6g} mm is more than a third of the outer cone distance "
                       f"{self.cone_distance:.6g} mm (the usual limit)")
        return out


BEVEL_FIELDS: list[Field] = [
    Field("kind", "string", choices=("bevel",), help="\"bevel\": a straight bevel gear with spherical-involute teeth"),
    Field("name", "name", required=False, default=None, maximum=GEAR_NAME_MAX,
          help="the gear's label in reports and exports (default: the table's name, its identity)"),
    Field("teeth", "integer", minimum=5, maximum=1000, help="number of teeth"),
    Field("mate_teeth", "integer", minimum=5, maximum=1000,
          help="number of teeth of the mating bevel gear (sets the pitch cone angle)"),
    Field("shaft_angle", "angle", required=False, default=90 * DEG, units=("deg", "rad"), minimum=10 * DEG,
          maximum=170 * DEG, help="angle between the two gears' axes (pitch cone angles sum to it)"),
    Field("module", "length", required=False, units=("mm",), minimum=0.05, exclusive_minimum=True, maximum=100.0,
          help="module at the heel (outer cone); give this or diametral_pitch_per_in"),
    Field("diametral_pitch_per_in", "number", required=False, minimum=MM_PER_IN / 100.0, maximum=MM_PER_IN / 0.05,
          exclusive_maximum=True, help="teeth per inch of heel pitch diameter (module = 25.4 mm / P)"),
    Field("pressure_angle", "angle", required=False, default=20 * DEG, units=("deg", "rad"), minimum=10 * DEG,
          maximum=30 * DEG, help="pressure angle of the spherical involute at the pitch cone"),
    Field("face_width", "length", minimum=0.0, exclusive_minimum=True,
          help="face width along the cone (at most 0.6 of the outer cone distance; a warning beyond a third)"),
    Field("profile_shift", "number", required=False, default=0.0, minimum=-0.8, maximum=0.8,
          help="profile shift coefficient x at the heel (Gleason-style unequal addendum: x on the pinion, -x on "
               "the gear)"),
    Field("addendum_coefficient", "number", required=False, default=1.0, minimum=0.5, maximum=1.5,
          help="addendum over the module at the heel"),
    Field("dedendum_coefficient", "number", required=False, default=1.25, minimum=0.8, maximum=2.0,
          help="dedendum over the module at the heel"),
    Field("thinning_circumferential", "length", required=False, default=0.0, minimum=0.0,
          help="tooth thinning for backlash, as an arc of the heel pitch circle"),
    Field("bore_diameter", "length", required=False, default=0.0, minimum=0.0,
          help="bore along the axis (0: none); must stay inside the root cone at the toe"),
    Field("back", "string", required=False, default="flat", choices=("flat", "spherical"),
          help="the gear's back: \"flat\" (the plane through the heel root circle, as the robot joint's pair is "
               "built) or \"spherical\" (the heel sphere)"),
    Field("accuracy_grade", "integer", required=False, default=None, minimum=2, maximum=11,
          help="ISO 17485 accuracy grade of the bevel gear (2 finest .. 11)"),
]


def bevel_from_table(data: Mapping[str, Any], where: str = "gear", name: str | None = None,
                     length_unit: str | None = None) -> BevelGearSpec:
    """Build a :class:`BevelGearSpec` from a design table (errors name the key as written)."""
    v = read_table(data, BEVEL_FIELDS, where)
    p = f"{where}."
    if (v["module"] is None) == (v["diametral_pitch_per_in"] is None):
        raise DesignError(p + "module_mm", "give exactly one of module_mm and diametral_pitch_per_in",
                          "module_mm in (0.05, 100] or diametral_pitch_per_in in [0.254, 508)")
    if v["module"] is not None:
        module, unit = v["module"], "mm"
    else:
        module, unit = module_from_diametral_pitch(v["diametral_pitch_per_in"]), "in"
    kwargs = dict(teeth=v["teeth"], mate_teeth=v["mate_teeth"], module=module, face_width=v["face_width"],
                  shaft_angle=v["shaft_angle"], pressure_angle=v["pressure_angle"], profile_shift=v["profile_shift"],
                  addendum_coefficient=v["addendum_coefficient"], dedendum_coefficient=v["dedendum_coefficient"],
                  thinning=v["thinning_circumferential"], bore_diameter=v["bore_diameter"],
                  back=v["back"], accuracy_grade=v["accuracy_grade"],
                  name=name or v["name"] or "bevel", length_unit=length_unit or unit)
    try:
        return BevelGearSpec(**kwargs)
    except DesignError as exc:
        key = {"thinning": "thinning_circumferential"}.get(exc.field, exc.field)
        problem, allowed = exc.problem, exc.allowed
        unit_k = v["_units"].get(key)
        if unit_k is not None:
            key = f"{key}_{unit_k}"
            if unit_k != "mm" and allowed and allowed.endswith(" mm"):
                allowed = f"{allowed} (in {unit_k}: divide by {LENGTH_SUFFIXES[unit_k]:g})"
        raise DesignError(p + key, problem, allowed) from None


__all__ = ["BevelGearSpec", "BEVEL_FIELDS", "bevel_from_table"]
