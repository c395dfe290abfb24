"""The gear as designed: :class:`GearSpec` (validated on construction) and its design-file table.

Internal units: mm and rad. A spec always holds the *normal* system (normal module, normal
pressure angle, normal profile shift coefficient); a design written in the transverse system
is converted once, in :func:`gear_from_table`. For a spur gear normal and transverse coincide.

Design-file table (``[gear]`` or an entry of ``[gears.*]``)::

    teeth = 21
    diametral_pitch_per_in = 32        # or module_mm = 0.8
    pitch_system = "normal"            # helical only: is the pitch/pressure angle normal or transverse
    pressure_angle_deg = 20
    helix_angle_deg = 20               # 0 for spur
    hand = "right"
    face_width_in = 0.5
    profile_shift = 0.0                # x, in the pitch system given
    thinning_circumferential_in = 0.0  # tooth thinning: transverse arc at the reference circle
    # or thinning_normal_in            #   ... or normal tooth thickness at the reference cylinder
    thickness_upper_deviation_um = -20 # tooth-thickness allowance E_sns, E_sni (normal, <= 0); without
    thickness_lower_deviation_um = -45 #   them a drive chooses it from its backlash (geargen.core.allowance)
    bore_diameter_mm = 10
    accuracy_grade = 6                 # optional: ISO 1328-1:2013 flank tolerance class 1..11
    accuracy_standard = "ISO 1328-1:2013"   # optional; the only standard implemented
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, ClassVar, Mapping

from geargen.design.schema import GEAR_NAME_MAX, Field, read_table
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES, MM_PER_IN, from_mm, length_text, module_from_diametral_pitch

DEG = math.pi / 180.0

HANDS = ("right", "left")

#: the accuracy standards a gear may name; ISO 1328-1:2013 only (AGMA 2015-1-A01 is not implemented:
#: its formulas and rounding could not be established from a citable source; inch designs use ISO)
ISO_1328 = "ISO 1328-1:2013"
ACCURACY_STANDARDS = (ISO_1328,)

#: ISO 1328-1:2013, clause 1 (scope): the tolerance formulas hold only in these ranges and must not be
#: extrapolated beyond them. Quantity -> (lowest, highest, unit); read by geargen.core.accuracy too.
ISO_1328_SCOPE = {"grade": (1, 11, ""), "teeth": (5, 1000, ""), "normal_module": (0.5, 70.0, "mm"),
                  "reference_diameter": (5.0, 15000.0, "mm"), "face_width": (4.0, 1200.0, "mm")}


def iso1328_scope_problem(quantity: str, value: float) -> str | None:
    """Why ``value`` of ``quantity`` (a key of :data:`ISO_1328_SCOPE`, internal units) is outside
    ISO 1328-1:2013's scope, or None when it is inside."""
    lo, hi, unit = ISO_1328_SCOPE[quantity]
    if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) and lo <= value <= hi:
        return None
    return f"{value!r}{' ' + unit if unit else ''} is outside {ISO_1328}'s range"


def iso1328_scope_text(quantity: str) -> str:
    lo, hi, unit = ISO_1328_SCOPE[quantity]
    return f"[{lo:g}, {hi:g}]{' ' + unit if unit else ''}"


@dataclass(frozen=True)
class Hub:
    """Bore, keyway and hub of a gear blank (mm). Zero means "none"."""

    bore_diameter: float = 0.0
    keyway_width: float = 0.0
    keyway_depth: float = 0.0  # radial depth of the keyway beyond the bore
    hub_diameter: float = 0.0
    hub_length: float = 0.0  # hub protrudes this far beyond one face

    def __post_init__(self):
        for name in ("bore_diameter", "keyway_width", "keyway_depth", "hub_diameter", "hub_length"):
            v = getattr(self, name)
            if not math.isfinite(v) or v < 0:
                raise DesignError(name, f"{v} is out of range", ">= 0 mm")
        if (self.keyway_width > 0) != (self.keyway_depth > 0):
            raise DesignError("keyway_width", "keyway needs both width and depth", "both > 0 or both 0")
        if self.keyway_width > 0 and self.bore_diameter == 0:
            raise DesignError("keyway_width", "a keyway needs a bore", "bore_diameter > 0")
        if self.keyway_width >= self.bore_diameter > 0:
            raise DesignError("keyway_width", f"{self.keyway_width} mm is not narrower than the bore",
                              f"< {self.bore_diameter} mm")
        if (self.hub_diameter > 0) != (self.hub_length > 0):
            raise DesignError("hub_diameter", "a hub needs both diameter and length", "both > 0 or both 0")
        if 0 < self.hub_diameter <= self.bore_diameter + 2 * self.keyway_depth:
            raise DesignError("hub_diameter", f"{self.hub_diameter} mm leaves no wall around the bore",
                              f"> {self.bore_diameter + 2 * self.keyway_depth} mm")


#: the most characters of each text a gear's drawing prints as the designer wrote it: the lines
#: geargen.report.drawing gives it (DRAWN_TEXT_LINES: material 4, heat treatment 2 in the blank
#: table's 74 mm value column; part number 2, revision 1 in their title-block cells) times the
#: letters of the widest character it may hold ("m", 3.53 mm at 10 pt; schema.DRAWN_TEXT_RANGES)
#: that one line holds: 19 in the value column, 17 in the part-number cell, 8 in the revision
#: cell (tests/report/test_drawn_text_limits.py measures them again and draws the longest)
DRAWN_TEXT_MAX = {"material": 76, "heat_treatment": 38, "part_number": 34, "revision": 8}


#: the default tolerance class of the tip diameter and the face width when the design gives none:
#: ISO 286-1 h11, the usual class of a tip that is not a datum (ISO/TR 10064-3 leaves it to the blank)
DEFAULT_TIP_CLASS = "h11"
DEFAULT_FACE_WIDTH_CLASS = "h11"


@dataclass(frozen=True)
class ShopData:
    """What the drawing states about a gear besides its teeth (design keys of the gear table; None:
    not given): ``part_number``, ``revision``, ``material``, ``heat_treatment``, surface
    ``hardness`` as (value, "HV" or "HRC"), ``flank_roughness_Ra`` (mm), the bore's ISO 286 class
    ``bore_fit`` (``"H7"``), the tip diameter's and the face width's ISO 286 class or their
    (upper, lower) deviations in mm, and the DIN 3967 designation of the tooth-thickness
    allowance ``thickness_allowance_series`` (``"cd25"``)."""

    part_number: str | None = None
    revision: str | None = None
    material: str | None = None
    heat_treatment: str | None = None
    hardness: tuple[float, str] | None = None
    flank_roughness_Ra: float | None = None
    bore_fit: str | None = None
    tip_diameter_class: str | None = None
    tip_diameter_deviations: tuple[float, float] | None = None
    face_width_class: str | None = None
    face_width_deviations: tuple[float, float] | None = None
    thickness_allowance_series: str | None = None


class HelicalTeeth:
    """The transverse quantities of teeth cut by a rack of normal ``module`` and ``pressure_angle``
    at ``helix_angle`` (a cylindrical gear's and a rack's: one home for both)."""

    module: float
    pressure_angle: float
    helix_angle: float

    @property
    def is_helical(self) -> bool:
        return self.helix_angle > 0.0

    @property
    def transverse_module(self) -> float:
        return self.module / math.cos(self.helix_angle)

    @property
    def transverse_pressure_angle(self) -> float:
        return math.atan(math.tan(self.pressure_angle) / math.cos(self.helix_angle))


@dataclass(frozen=True)
class GearSpec(HelicalTeeth):
    """An external involute gear (spur when ``helix_angle`` is 0), normal system, mm and rad.

    ``thinning`` is the tooth-thickness reduction for backlash, as a transverse arc length at
    the reference circle (circumferential); :attr:`thinning_normal` gives the normal one.
    ``rack_tip_radius_coefficient`` is the generating rack's tip radius over the normal module;
    it shapes the trochoidal root.

    The other cylindrical families are its subclasses in their folders (the ring
    :class:`geargen.families.internal.spec.InternalGearSpec`, the double-helical gear
    :class:`geargen.families.double_helical.spec.DoubleHelicalGearSpec`): each sets ``kind`` and
    overrides what its teeth do differently (tip and root radii, rim, halves), so that this class
    asks no family's name. ``rim_diameter`` and ``centre_gap`` are keys of the cylindrical table all
    of them read; this class refuses them (:meth:`_check_rim_given`, :meth:`_check_halves`).
    """

    #: the default tip radius of the generating tool over m_n: ISO 53 profile A's rack (0.38)
    DEFAULT_TOOL_TIP_RADIUS: ClassVar[float] = 0.38

    teeth: int
    module: float
    pressure_angle: float
    face_width: float
    helix_angle: float = 0.0
    hand: str = "right"
    profile_shift: float = 0.0
    addendum_coefficient: float = 1.0
    dedendum_coefficient: float = 1.25
    rack_tip_radius_coefficient: float | None = None  # None: min(0.38, largest that fits)
    thinning: float = 0.0
    hub: Hub = field(default_factory=Hub)
    # entered tooth-thickness allowance (E_sns, E_sni): normal deviations at the reference cylinder,
    # mm, <= 0; None: none entered (a drive chooses one from its backlash, geargen.core.allowance)
    thickness_deviations: tuple[float, float] | None = None
    name: str = "gear"
    length_unit: str = "mm"  # the unit the design was written in; reports and exports use it
    accuracy_grade: int | None = None  # flank tolerance class of accuracy_standard; None: not specified
    accuracy_standard: str | None = None  # None with a grade: ISO 1328-1:2013
    kind: str = field(default="external", init=False)  # the family's (a subclass sets its own)
    # a ring's (InternalGearSpec): outer diameter of the ring blank (mm); None: its default rule
    rim_diameter: float | None = None
    # a double-helical gear's: axial gap between the two halves (mm), a relief groove at the root
    # diameter; 0 is a herringbone whose flanks meet at the apex
    centre_gap: float = 0.0
    # drawing data: part number, material, finish, blank tolerances (geargen.report.drawing)
    shop: ShopData = field(default_factory=ShopData)

    def __post_init__(self):
        self._check_rim_given()
        check_number("teeth", self.teeth, 4, 2000, "")
        if not isinstance(self.teeth, int):
            raise DesignError("teeth", f"expected a whole number, got {self.teeth!r}")
        check_number("module", self.module, 0.01, 200.0, "mm", exclusive_lo=True)
        check_number("pressure_angle", self.pressure_angle, 10 * DEG, 35 * DEG, "rad")
        check_number("face_width", self.face_width, 0.0, 5000.0, "mm", exclusive_lo=True, length_unit=self.length_unit)
        check_number("helix_angle", self.helix_angle, 0.0, 45 * DEG, "rad")
        self._check_halves()
        if self.hand not in HANDS:
            raise DesignError("hand", f"{self.hand!r} is not a valid choice", "'right', 'left'")
        check_number("profile_shift", self.profile_shift, -1.5, 1.5, "")
        check_number("addendum_coefficient", self.addendum_coefficient, 0.3, 1.5, "")
        check_number("dedendum_coefficient", self.dedendum_coefficient, 0.5, 2.0, "")
        rho_max = self.max_rack_tip_radius_coefficient
        if self.rack_tip_radius_coefficient is None:
            # the family's tool (DEFAULT_TOOL_TIP_RADIUS), or the full-radius fillet when it does not fit
            object.__setattr__(self, "rack_tip_radius_coefficient", min(self.DEFAULT_TOOL_TIP_RADIUS, rho_max))
        check_number("rack_tip_radius_coefficient", self.rack_tip_radius_coefficient, 0.0, rho_max, "")
        check_number("thinning", self.thinning, 0.0, 0.5 * self.transverse_pitch / 2, "mm", length_unit=self.length_unit)
        if self.thickness_deviations is not None:
            upper, lower = self.thickness_deviations
            if not (math.isfinite(upper) and math.isfinite(lower) and lower <= upper <= 0):
                raise DesignError("thickness_upper_deviation", f"({upper!r}, {lower!r}) mm is out of range",
                                  "lower <= upper <= 0")
        if self.length_unit not in ("mm", "in"):
            raise DesignError("length_unit", f"{self.length_unit!r} is not a valid choice", "'mm', 'in'")
        self._check_accuracy()
        self._check_body()
        # a root at or below the axis is the profile's "negative_root" error, not a bore problem
        if (self.hub.bore_diameter > 0 and self.root_radius_standard > 0
                and self.hub.bore_diameter + 2 * self.hub.keyway_depth >= 2 * self.root_radius_standard * 0.98):
            raise DesignError("bore_diameter", "bore (with keyway) cuts into the tooth root",
                              f"< {length_text(2 * self.root_radius_standard * 0.98 - 2 * self.hub.keyway_depth, self.length_unit)}")

    def _check_rim_given(self) -> None:
        """A rim belongs to a ring (its subclass accepts one)."""
        if self.rim_diameter is not None:
            raise DesignError("rim_diameter", f"{self.kind} gears have no rim", "only with kind = 'internal'")

    def _check_halves(self) -> None:
        """A centre gap belongs to a double-helical gear (its subclass checks its halves)."""
        gap = self.centre_gap
        if gap != 0:
            written = length_text(gap, self.length_unit, 6) if isinstance(gap, (int, float)) else repr(gap)
            raise DesignError("centre_gap", f"{written}: only a double_helical gear has a centre gap", "0")

    def _check_body(self) -> None:
        """The body's own rules once the teeth are valid (a ring's rim); none for a gear on a bore."""

    @property
    def half_face_width(self) -> float:
        """Face width of each helical half: the whole face width (one helix; a double-helical gear's
        halves are (b - gap) / 2)."""
        return self.face_width

    @property
    def half_hands(self) -> tuple[str, ...]:
        """Hand of each helical half from z = 0 up: the spec's hand (one helix)."""
        return (self.hand,)

    def _check_accuracy(self) -> None:
        """A grade is a whole number of the standard's classes, and the gear lies in the standard's
        scope (the formulas must not be extrapolated); a standard needs a grade."""
        if self.accuracy_grade is None:
            if self.accuracy_standard is not None:
                raise DesignError("accuracy_standard", "names a standard without accuracy_grade",
                                  "accuracy_grade = 1..11 with it, or neither")
            return
        if self.accuracy_standard is None:
            object.__setattr__(self, "accuracy_standard", ISO_1328)
        if self.accuracy_standard not in ACCURACY_STANDARDS:
            raise DesignError("accuracy_standard", f"{self.accuracy_standard!r} is not a valid choice",
                              ", ".join(map(repr, ACCURACY_STANDARDS)))
        grade = self.accuracy_grade
        if isinstance(grade, bool) or not isinstance(grade, int) or iso1328_scope_problem("grade", grade):
            raise DesignError("accuracy_grade", f"{grade!r} is not a flank tolerance class of {ISO_1328}",
                              f"a whole number in {iso1328_scope_text('grade')}")
        for quantity, value, what in (("teeth", self.teeth, "teeth"), ("normal_module", self.module, "normal module"),
                                      ("reference_diameter", 2 * self.reference_radius, "reference diameter"),
                                      ("face_width", self.face_width, "face width")):
            if iso1328_scope_problem(quantity, value):
                lo, hi, unit = ISO_1328_SCOPE[quantity]
                shown = f"{value:.6g}{' ' + unit if unit else ''}"
                raise DesignError("accuracy_grade", f"the gear's {what} {shown} is outside the range of {ISO_1328}, "
                                  "whose formulas must not be extrapolated",
                                  f"a gear with {what} in {iso1328_scope_text(quantity)}, or no accuracy_grade")

    # --- closed-form basics (and HelicalTeeth's); the full involute geometry lives in geargen.core ---
    @property
    def transverse_pitch(self) -> float:
        """Circular pitch on the reference circle, transverse section (mm)."""
        return math.pi * self.transverse_module

    @property
    def reference_radius(self) -> float:
        return self.teeth * self.transverse_module / 2.0

    @property
    def base_radius(self) -> float:
        return self.reference_radius * math.cos(self.transverse_pressure_angle)

    @property
    def base_helix_angle(self) -> float:
        return math.asin(math.sin(self.helix_angle) * math.cos(self.pressure_angle))

    @property
    def signed_helix_angle(self) -> float:
        """Helix angle with the hand as sign: right positive, left negative."""
        return self.helix_angle if self.hand == "right" else -self.helix_angle

    @property
    def lead(self) -> float:
        """Axial advance of one helix turn at the reference cylinder (inf for spur)."""
        if not self.is_helical:
            return math.inf
        return 2 * math.pi * self.reference_radius / math.tan(self.helix_angle)

    @property
    def is_internal(self) -> bool:
        """Whether its teeth point inward (a ring: its subclass)."""
        return False

    @property
    def tip_radius(self) -> float:
        """r + m_n (h_a* + x)."""
        return self.reference_radius + self.module * (self.addendum_coefficient + self.profile_shift)

    @property
    def root_radius_standard(self) -> float:
        """Root radius cut by the rack: r - m_n (h_f* - x)."""
        return self.reference_radius - self.module * (self.dedendum_coefficient - self.profile_shift)

    @property
    def max_rack_tip_radius_coefficient(self) -> float:
        """Largest rack tip radius (over m_n) that fits the rack's clearance and tooth space."""
        c = self.dedendum_coefficient - self.addendum_coefficient  # tip clearance coefficient
        a = self.pressure_angle
        by_clearance = c / (1 - math.sin(a)) if c > 0 else 0.0
        # the rack tooth tip half-width at its tip line: pi/4 - h_f* tan(a), fillet must fit in it
        half_tip = math.pi / 4 - self.dedendum_coefficient * math.tan(a)
        by_width = half_tip * math.cos(a) / (1 - math.sin(a)) if half_tip > 0 else 0.0
        return max(0.0, min(by_clearance, by_width))

    @property
    def thinning_normal(self) -> float:
        """Tooth thinning as normal thickness at the reference cylinder (mm)."""
        return self.thinning * math.cos(self.helix_angle)


def check_number(name: str, value, lo: float, hi: float, unit: str = "", exclusive_lo: bool = False,
                 length_unit: str = "mm") -> None:
    """DesignError naming ``name`` unless ``value`` is a finite number (not a bool) in [lo, hi] (or (lo, hi]);
    every gear family's spec validates its numbers with it. A length (``unit`` "mm") is reported in
    the design's ``length_unit``."""
    number = isinstance(value, (int, float)) and not isinstance(value, bool)
    ok = number and math.isfinite(value) and (value > lo if exclusive_lo else value >= lo) and value <= hi
    if not ok:
        left = "(" if exclusive_lo else "["
        written = repr(value)
        if unit == "mm" and length_unit != "mm":
            written = f"{from_mm(value, length_unit):.6g} {length_unit}" if number and math.isfinite(value) else written
            lo, hi, unit = from_mm(lo, length_unit), from_mm(hi, length_unit), length_unit
        raise DesignError(name, f"{written} is out of range", f"{left}{lo:.6g}, {hi:.6g}] {unit}".rstrip())


GEAR_FIELDS: list[Field] = [
    Field("kind", "string", required=False, default="external",
          help="the gear's kind: external (spur or helical), internal (a ring), double_helical (two helical halves "
               "of opposite hand); the other families have their own tables"),
    Field("name", "name", required=False, default=None, maximum=GEAR_NAME_MAX,
          help="the gear's label in reports and exports (default: the table's name, which stays the gear's "
               "identity in the design); the name of a [gear] file's gear"),
    Field("teeth", "integer", minimum=4, maximum=2000, help="number of teeth"),
    Field("module", "length", required=False, units=("mm",), minimum=0.01, exclusive_minimum=True, maximum=200.0,
          help="module in the pitch system given (normal unless pitch_system = \"transverse\"); give this or "
               "diametral_pitch_per_in"),
    # the same module range as teeth per inch: 25.4 / 200 <= P < 25.4 / 0.01
    Field("diametral_pitch_per_in", "number", required=False, minimum=MM_PER_IN / 200.0, maximum=MM_PER_IN / 0.01,
          exclusive_maximum=True,
          help="teeth per inch of pitch diameter (module = 25.4 mm / P); give this or module_mm"),
    Field("pitch_system", "string", required=False, default="normal", choices=("normal", "transverse"),
          help="helical gears: whether module or pitch, pressure angle and profile shift are normal or transverse "
               "values"),
    Field("pressure_angle", "angle", units=("deg", "rad"), minimum=10 * DEG, maximum=35 * DEG,
          help="pressure angle of the generating rack, in the pitch system given"),
    Field("helix_angle", "angle", required=False, default=0.0, units=("deg", "rad"), minimum=0.0, maximum=45 * DEG,
          help="helix angle at the reference cylinder; 0 for a spur gear"),
    Field("hand", "string", required=False, default="right", choices=HANDS, help="hand of the helix (helical gears)"),
    Field("face_width", "length", minimum=0.0, exclusive_minimum=True, maximum=5000.0,
          help="face width along the axis"),
    Field("centre_gap", "length", required=False, default=0.0, minimum=0.0,
          help="double_helical only: axial gap between the two helical halves, a relief groove at the root "
               "diameter (0: a herringbone, the halves' flanks meeting at the apex; < face_width)"),
    Field("profile_shift", "number", required=False, default=0.0, minimum=-1.5, maximum=1.5,
          help="profile shift coefficient x (shift over the module), in the pitch system given"),
    Field("addendum_coefficient", "number", required=False, default=1.0, minimum=0.3, maximum=1.5,
          help="addendum over the normal module (tip radius r + m (h_a* + x))"),
    Field("dedendum_coefficient", "number", required=False, default=1.25, minimum=0.5, maximum=2.0,
          help="dedendum over the normal module (root cut by the rack at r - m (h_f* - x))"),
    Field("rack_tip_radius_coefficient", "number", required=False, default=None, minimum=0.0, maximum=1.0,
          help="tip radius of the generating rack over the normal module; shapes the trochoidal root (default: "
               "0.38, or the largest that fits)"),
    Field("thinning_circumferential", "length", required=False, default=None, minimum=0.0,
          help="tooth thinning for backlash, as a transverse arc at the reference circle (give at most one "
               "thinning)"),
    Field("thinning_normal", "length", required=False, default=None, minimum=0.0,
          help="tooth thinning for backlash, as normal tooth thickness at the reference cylinder (give at most one "
               "thinning)"),
    Field("thickness_upper_deviation", "length", required=False, default=None, maximum=0.0,
          help="tooth-thickness allowance: upper deviation E_sns of the normal tooth thickness from the zero-backlash "
               "tooth (<= 0; give both deviations, or neither to let a drive choose them from its backlash range)"),
    Field("thickness_lower_deviation", "length", required=False, default=None, maximum=0.0,
          help="tooth-thickness allowance: lower deviation E_sni (<= the upper deviation)"),
    Field("bore_diameter", "length", required=False, default=0.0, minimum=0.0,
          help="bore of the gear blank (0: none); must clear the tooth root"),
    Field("keyway_width", "length", required=False, default=0.0, minimum=0.0,
          help="keyway width (0: none; needs a bore and a depth)"),
    Field("keyway_depth", "length", required=False, default=0.0, minimum=0.0,
          help="radial depth of the keyway beyond the bore"),
    Field("hub_diameter", "length", required=False, default=0.0, minimum=0.0,
          help="hub diameter (0: no hub; needs a length)"),
    Field("hub_length", "length", required=False, default=0.0, minimum=0.0,
          help="how far the hub stands out beyond one face"),
    Field("rim_diameter", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="internal gears only: outer diameter of the ring blank (default: root diameter + 7 m_n, the rim "
               "of ISO 6336-3's Y_B = 1; at least root diameter + 1 m_n)"),
    Field("accuracy_grade", "integer", required=False, default=None, minimum=1, maximum=11,
          help="flank tolerance class of ISO 1328-1:2013 (1 finest .. 11); sets the gear's tolerances and, in "
               "[errors.NAME], its pitch-line eccentricity and tooth-to-tooth TIRs"),
    Field("accuracy_standard", "string", required=False, default=None, choices=ACCURACY_STANDARDS,
          help="the standard of accuracy_grade (default and only choice: ISO 1328-1:2013, inch designs too)"),
    Field("part_number", "string", required=False, default=None, maximum=DRAWN_TEXT_MAX["part_number"],
          help="the drawing's part (identification) number; the title block says \"not specified\" without it"),
    Field("revision", "string", required=False, default=None, maximum=DRAWN_TEXT_MAX["revision"],
          help="the drawing's revision index"),
    Field("material", "string", required=False, default=None, maximum=DRAWN_TEXT_MAX["material"],
          help="the gear's material as the drawing names it (e.g. \"42CrMo4 (1.7225)\"; default: the ISO 6336-5 "
               "material of the gear's [materials] or [duty] rating when the design names one)"),
    Field("heat_treatment", "string", required=False, default=None, maximum=DRAWN_TEXT_MAX["heat_treatment"],
          help="the heat treatment the drawing asks for (e.g. \"quenched and tempered\"; default: that of the "
               "rating's material)"),
    Field("hardness_HV", "number", required=False, default=None, minimum=50.0, maximum=1200.0,
          help="surface hardness, Vickers (give this or hardness_HRC; default: the rating's)"),
    Field("hardness_HRC", "number", required=False, default=None, minimum=20.0, maximum=70.0,
          help="surface hardness, Rockwell C (give this or hardness_HV)"),
    Field("flank_roughness_Ra", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          maximum=0.1, help="roughness R_a of the tooth flanks (e.g. flank_roughness_Ra_um = 0.8)"),
    Field("bore_fit", "string", required=False, default=None,
          help="ISO 286-1 tolerance class of the bore (H or JS with grade 4..13, e.g. \"H7\"); its limits are "
               "computed from ISO 286-1 and drawn; needs a bore"),
    Field("tip_diameter_tolerance", "string", required=False, default=None,
          help=f"ISO 286-1 tolerance class of the tip diameter (h or js with grade 4..13; default "
               f"{DEFAULT_TIP_CLASS!r}); or give tip_diameter_upper/lower_deviation_*"),
    Field("tip_diameter_upper_deviation", "length", required=False, default=None,
          help="upper deviation of the tip diameter (with the lower one, instead of tip_diameter_tolerance)"),
    Field("tip_diameter_lower_deviation", "length", required=False, default=None,
          help="lower deviation of the tip diameter (<= the upper one)"),
    Field("face_width_tolerance", "string", required=False, default=None,
          help=f"ISO 286-1 tolerance class of the face width (h or js with grade 4..13; default "
               f"{DEFAULT_FACE_WIDTH_CLASS!r}); or give face_width_upper/lower_deviation_*"),
    Field("face_width_upper_deviation", "length", required=False, default=None,
          help="upper deviation of the face width (with the lower one, instead of face_width_tolerance)"),
    Field("face_width_lower_deviation", "length", required=False, default=None,
          help="lower deviation of the face width (<= the upper one)"),
    Field("thickness_allowance_series", "string", required=False, default=None,
          help="DIN 3967 designation of the tooth-thickness allowance (upper series a..h and tolerance series "
               "21..30, e.g. \"cd25\"); a gear without deviations of its own and outside a drive gets \"cd25\""),
]


def gear_from_table(data: Mapping[str, Any], where: str = "gear", name: str | None = None,
                    length_unit: str | None = None) -> GearSpec:
    """An external gear's :class:`GearSpec` from a design table (:func:`cylindrical_from_table`)."""
    return cylindrical_from_table(data, where, name, length_unit, GearSpec)


def cylindrical_from_table(data: Mapping[str, Any], where: str, name: str | None, length_unit: str | None,
                           spec_class: type[GearSpec]) -> GearSpec:
    """Build a ``spec_class`` (:class:`GearSpec` or a cylindrical family's subclass of it, whose
    ``kind`` the table must name) from a design table, converting the transverse system if used.

    ``name`` is the gear's identity (an assembly's table key), which the table's own ``name`` key
    (a label) never replaces; without it the table's ``name`` names the gear. ``length_unit`` is
    the design's unit for reports; by default inches for a diametral-pitch design and mm for a
    module design. A table of any family is read by :func:`geargen.families.registry.read_gear`.
    """
    v = read_table(data, GEAR_FIELDS, where)
    p = f"{where}."
    if v["kind"] != spec_class.kind:  # another family's table: read_gear reads it with its family's reader
        raise DesignError(p + "kind", f"{v['kind']!r} is not read as a {spec_class.kind} gear",
                          f"{spec_class.kind!r}, or the table read by geargen.families.registry.read_gear")
    if (v["module"] is None) == (v["diametral_pitch_per_in"] is None):
        raise DesignError(p + "module_mm", "give exactly one of module_mm and diametral_pitch_per_in",
                          "module_mm in (0.01, 200] or diametral_pitch_per_in in [0.127, 2540)")
    if v["module"] is not None:
        module = v["module"]
        unit = "mm"
    else:
        module = module_from_diametral_pitch(v["diametral_pitch_per_in"])
        unit = "in"
    beta = v["helix_angle"]
    alpha = v["pressure_angle"]
    shift = v["profile_shift"]
    if v["pitch_system"] == "transverse" and beta > 0:
        module_n = module * math.cos(beta)
        alpha_n = math.atan(math.tan(alpha) * math.cos(beta))
        shift_n = shift * module / module_n  # same shift in mm: x_t m_t = x_n m_n
    else:
        module_n, alpha_n, shift_n = module, alpha, shift
    if v["thinning_circumferential"] is not None and v["thinning_normal"] is not None:
        raise DesignError(p + "thinning_normal", "give at most one tooth-thinning kind",
                          "thinning_circumferential_* or thinning_normal_*")
    if v["thinning_normal"] is not None:
        thinning = v["thinning_normal"] / math.cos(beta)
    else:
        thinning = v["thinning_circumferential"] or 0.0
    most = math.pi * module_n / math.cos(beta) / 4  # a quarter of the transverse pitch (GearSpec's limit)
    if thinning > most:
        kind = "thinning_normal" if v["thinning_normal"] is not None else "thinning_circumferential"
        unit_t = v["_units"][kind]
        factor = math.cos(beta) if kind == "thinning_normal" else 1.0
        scale = LENGTH_SUFFIXES[unit_t]
        raise DesignError(f"{p}{kind}_{unit_t}", f"{thinning * factor / scale:.6g} {unit_t} is out of range",
                          f"[0, {most * factor / scale:.6g}] {unit_t} (a quarter of the circular pitch)")
    deviations = None
    if (v["thickness_upper_deviation"] is None) != (v["thickness_lower_deviation"] is None):
        given = "upper" if v["thickness_upper_deviation"] is not None else "lower"
        missing = "lower" if given == "upper" else "upper"
        raise DesignError(f"{p}thickness_{missing}_deviation_um", f"missing: the {given} deviation is given",
                          "both thickness_upper_deviation_* and thickness_lower_deviation_*, or neither")
    if v["thickness_upper_deviation"] is not None:
        upper, lower = v["thickness_upper_deviation"], v["thickness_lower_deviation"]
        if upper < lower:
            unit_d = v["_units"]["thickness_lower_deviation"]
            scale = LENGTH_SUFFIXES[unit_d]
            raise DesignError(f"{p}thickness_lower_deviation_{unit_d}", f"{lower / scale:.6g} {unit_d} is above the "
                              "upper deviation", f"<= {upper / scale:.6g} {unit_d}")
        deviations = (upper, lower)
    hub = with_field_prefix(p, lambda: Hub(v["bore_diameter"], v["keyway_width"], v["keyway_depth"],
                                            v["hub_diameter"], v["hub_length"]), v["_units"])
    kwargs = dict(teeth=v["teeth"], module=module_n, pressure_angle=alpha_n, face_width=v["face_width"],
                  helix_angle=beta, hand=v["hand"], profile_shift=shift_n,
                  addendum_coefficient=v["addendum_coefficient"], dedendum_coefficient=v["dedendum_coefficient"],
                  thinning=thinning, hub=hub, name=name or v["name"] or "gear", thickness_deviations=deviations,
                  length_unit=length_unit or unit, accuracy_grade=v["accuracy_grade"],
                  accuracy_standard=v["accuracy_standard"], rim_diameter=v["rim_diameter"],
                  centre_gap=v["centre_gap"])
    kwargs["rack_tip_radius_coefficient"] = v["rack_tip_radius_coefficient"]
    kwargs["shop"] = _shop_data(v, p)
    if hub.bore_diameter > 0:
        # GearSpec's bore rule, checked first so that the message is in the unit of the key
        plain = with_field_prefix(p, lambda: spec_class(**{**kwargs, "hub": Hub()}), v["_units"])
        root = plain.root_radius_standard
        most = 2 * root * 0.98 - 2 * hub.keyway_depth
        if root > 0 and hub.bore_diameter >= most:
            unit_b = v["_units"]["bore_diameter"]
            scale = LENGTH_SUFFIXES[unit_b]
            raise DesignError(f"{p}bore_diameter_{unit_b}", f"{hub.bore_diameter / scale:.6g} {unit_b}: the bore (with "
                              "keyway) cuts into the tooth root", f"< {most / scale:.6g} {unit_b}")
    return with_field_prefix(p, lambda: spec_class(**kwargs), v["_units"])


def _shop_data(v: Mapping[str, Any], p: str) -> ShopData:
    """The drawing keys of a gear table (validated ranges; the ISO 286 classes are checked against
    the gear's sizes by :func:`_check_shop_classes`)."""
    if v["hardness_HV"] is not None and v["hardness_HRC"] is not None:
        raise DesignError(p + "hardness_HRC", "give at most one hardness", "hardness_HV or hardness_HRC")
    hardness = ((v["hardness_HV"], "HV") if v["hardness_HV"] is not None
                else (v["hardness_HRC"], "HRC") if v["hardness_HRC"] is not None else None)
    pairs = {}
    for stem in ("tip_diameter", "face_width"):
        up, lo = v[f"{stem}_upper_deviation"], v[f"{stem}_lower_deviation"]
        if (up is None) != (lo is None):
            missing = "lower" if up is not None else "upper"
            raise DesignError(f"{p}{stem}_{missing}_deviation_mm", "missing: the other deviation is given",
                              f"both {stem}_upper_deviation_* and {stem}_lower_deviation_*, or neither")
        if up is not None:
            if v[f"{stem}_tolerance"] is not None:
                raise DesignError(f"{p}{stem}_tolerance", "given with deviations", "a tolerance class or deviations")
            if lo > up:
                unit = v["_units"][f"{stem}_lower_deviation"]
                scale = LENGTH_SUFFIXES[unit]
                raise DesignError(f"{p}{stem}_lower_deviation_{unit}", f"{lo / scale:.6g} {unit} is above the upper "
                                  "deviation", f"<= {up / scale:.6g} {unit}")
            pairs[stem] = (up, lo)
    return ShopData(part_number=v["part_number"], revision=v["revision"], material=v["material"],
                    heat_treatment=v["heat_treatment"], hardness=hardness, flank_roughness_Ra=v["flank_roughness_Ra"],
                    bore_fit=v["bore_fit"], tip_diameter_class=v["tip_diameter_tolerance"],
                    tip_diameter_deviations=pairs.get("tip_diameter"), face_width_class=v["face_width_tolerance"],
                    face_width_deviations=pairs.get("face_width"),
                    thickness_allowance_series=v["thickness_allowance_series"])


def gear_keys_written(data: Mapping[str, Any]) -> dict[str, str]:
    """Field name -> the key ``data`` gives it under (``"face_width": "face_width_in"``)."""
    out = {}
    for f in GEAR_FIELDS:
        for key in f.keys():
            if key in data:
                out[f.name] = key
    return out


def with_field_prefix(prefix: str, make, units: Mapping[str, str]):
    """Run ``make``; re-raise a DesignError with the design-file key path (name plus unit suffix)."""
    try:
        return make()
    except DesignError as exc:
        key = exc.field
        if key in units:
            key = f"{key}_{units[key]}"
        raise DesignError(prefix + key, exc.problem, exc.allowed) from None


def with_changes(spec: GearSpec, **changes) -> GearSpec:
    """A copy of ``spec`` with fields replaced (validated again)."""
    return replace(spec, **changes)


__all__ = ["DRAWN_TEXT_MAX", "ShopData", "DEFAULT_TIP_CLASS", "DEFAULT_FACE_WIDTH_CLASS",
           "GearSpec", "HelicalTeeth", "Hub", "GEAR_FIELDS",
           "ISO_1328", "ACCURACY_STANDARDS", "ISO_1328_SCOPE",
           "iso1328_scope_problem", "iso1328_scope_text", "cylindrical_from_table", "gear_from_table", "gear_keys_written", "with_changes", "MM_PER_IN"]
