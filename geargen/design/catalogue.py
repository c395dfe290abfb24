"""What every drive kind's default hardware is chosen from: standard bearings, music wire, motor
frames, the rounding of a default length, and how a partial ``[parts]`` table is told and completed.

Each drive kind states its own rules in ``geargen/drives/<kind>/defaults.py`` (its docstring is
the rule list ``docs/design-files.md`` shows); the loader completes a file with them through the
kind's keys module (``KEYS[kind].DEFAULTS``), handing them its non-validating readers
(:class:`Readers`). A value the file gives is never changed; each default is recorded with the rule
that chose it (:class:`Defaulted`), which ``geargen check`` prints.

Pure arithmetic on the parsed file: no CAD kernel.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, replace
from typing import Any, Callable, Mapping

from geargen.design.schema import read_table
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES, MM_PER_IN

#: (bore, outer diameter, width, designation), mm, by ISO 15 dimension series: 18 (thin section,
#: shielded widths), 19 (light thin section), 10 (the 60xx light series) and 02 (the 62xx medium series)
METRIC_SERIES: dict[str, tuple[tuple[float, float, float, str], ...]] = {
    "18": ((3, 7, 3, "683ZZ"), (4, 9, 4, "684ZZ"), (5, 11, 5, "685ZZ"), (6, 13, 5, "686ZZ"), (7, 14, 5, "687ZZ"),
           (8, 16, 5, "688ZZ"), (9, 17, 5, "689ZZ"), (10, 19, 5, "6800ZZ"), (12, 21, 5, "6801ZZ"),
           (15, 24, 5, "6802ZZ"), (17, 26, 5, "6803ZZ"), (20, 32, 7, "6804ZZ"), (25, 37, 7, "6805ZZ"),
           (30, 42, 7, "6806ZZ"), (35, 47, 7, "6807ZZ"), (40, 52, 7, "6808ZZ"), (45, 58, 7, "6809ZZ"),
           (50, 65, 7, "6810ZZ")),
    "19": ((5, 13, 4, "619/5"), (6, 15, 5, "619/6"), (7, 17, 5, "619/7"), (8, 19, 6, "619/8"), (9, 20, 6, "619/9"),
           (10, 22, 6, "61900"), (12, 24, 6, "61901"), (15, 28, 7, "61902"), (17, 30, 7, "61903"),
           (20, 37, 9, "61904"), (25, 42, 9, "61905"), (30, 47, 9, "61906"), (35, 55, 10, "61907"),
           (40, 62, 12, "61908"), (45, 68, 12, "61909"), (50, 72, 12, "61910")),
    "10": ((10, 26, 8, "6000"), (12, 28, 8, "6001"), (15, 32, 9, "6002"), (17, 35, 10, "6003"), (20, 42, 12, "6004"),
           (25, 47, 12, "6005"), (30, 55, 13, "6006"), (35, 62, 14, "6007"), (40, 68, 15, "6008"),
           (45, 75, 16, "6009"), (50, 80, 16, "6010")),
    "02": ((10, 30, 9, "6200"), (12, 32, 10, "6201"), (15, 35, 11, "6202"), (17, 40, 12, "6203"), (20, 47, 14, "6204"),
           (25, 52, 15, "6205"), (30, 62, 16, "6206"), (35, 72, 17, "6207"), (40, 80, 18, "6208"),
           (45, 85, 19, "6209"), (50, 90, 20, "6210")),
}
#: the thin series the dual pinion's shafts take
METRIC_BEARINGS = METRIC_SERIES["18"]
#: (bore, outer diameter, width, designation), inches: ABMA R series, shielded widths
INCH_BEARINGS = (
    (0.125, 0.375, 0.1562, "R2ZZ"), (0.1875, 0.5, 0.196, "R3ZZ"), (0.25, 0.625, 0.196, "R4ZZ"),
    (0.375, 0.875, 0.2812, "R6ZZ"), (0.5, 1.125, 0.3125, "R8ZZ"), (0.625, 1.375, 0.3438, "R10ZZ"),
    (0.75, 1.625, 0.4375, "R12ZZ"), (0.875, 1.875, 0.5, "R14ZZ"), (1.0, 2.0, 0.5, "R16ZZ"),
)

#: music-wire diameters (mm) and the tensile strength S = A / d^m (A in MPa mm^m; Shigley's Table 10-4)
WIRE_DIAMETERS = (0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.4, 1.6, 1.8, 2.0, 2.2, 2.5, 2.8, 3.0,
                  3.5, 4.0, 4.5, 5.0)
MUSIC_WIRE_A, MUSIC_WIRE_M = 2211.0, 0.145
#: the static allowable shear stress of music wire as a fraction of its tensile strength
MUSIC_WIRE_ALLOWABLE_FRACTION = 0.45
STEEL_E_GPA, STEEL_G_GPA = 207.0, 79.3

#: NEMA frames as motor envelopes: (frame, flange side mm, body length mm, shaft mm, torque N·m)
MOTORS = (("NEMA 8", 20.3, 30.0, 4.0, 0.02), ("NEMA 11", 28.2, 32.0, 5.0, 0.06),
          ("NEMA 14", 35.2, 34.0, 5.0, 0.14), ("NEMA 17", 42.3, 40.0, 5.0, 0.40),
          ("NEMA 23", 56.4, 56.0, 6.35, 1.0), ("NEMA 34", 86.0, 80.0, 14.0, 3.5))


@dataclass(frozen=True)
class Defaulted:
    """One value the file did not give: where it went (``section.key``), the value, the rule."""

    key: str
    value: Any
    why: str

    def __str__(self) -> str:
        return f"{self.key} = {self.value!r}  ({self.why})"


@dataclass(frozen=True)
class Readers:
    """The loader's readers a kind's defaults size from (the loader passes them: the defaults sit
    below it). ``design``: the parsed file -> a Design, its gears read, nothing else validated;
    ``layout``: a Design -> its ``[layout]`` settings; ``preload``: a ``[preload]`` table -> its
    PreloadSpec; ``torque_units``: torque suffix -> N·mm."""

    design: Callable[[Mapping[str, Any]], Any]
    layout: Callable[[Any], dict[str, Any]]
    preload: Callable[[Mapping[str, Any]], Any]
    torque_units: Mapping[str, float]


# ---------------------------------------------------------------- lengths

def length_step(unit: str) -> float:
    """The step a default length is rounded to (mm): 0.5 mm, or 1/32 in."""
    return 0.5 if unit == "mm" else MM_PER_IN / 32


def rounded(mm: float, unit: str, up: bool = True) -> float:
    """``mm`` rounded to 0.5 mm (or 1/32 in), up or down, in the design's unit."""
    step = length_step(unit)
    n = math.ceil(mm / step - 1e-9) if up else math.floor(mm / step + 1e-9)
    value = n * step
    return round(value, 6) if unit == "mm" else round(value / MM_PER_IN, 6)


def in_unit(mm: float, unit: str) -> float:
    """``mm`` in the design's unit, to 1 nm (or 1e-6 in)."""
    return round(mm if unit == "mm" else mm / MM_PER_IN, 6)


def metric_or_inch(mm: float, inch: float, unit: str) -> float:
    """A stated size (mm) of a metric design, or its stated inch size in an inch design (mm)."""
    return mm if unit == "mm" else inch * MM_PER_IN


# ---------------------------------------------------------------- bearings

def bearing_table(unit: str, series: str = "18") -> tuple[tuple[float, float, float, str], ...]:
    """The standard bearings of the design's unit: the metric ``series``, or the inch R series."""
    return METRIC_SERIES[series] if unit == "mm" else INCH_BEARINGS


def standard_bearing(bore_mm_max: float, unit: str, series: str = "18") -> tuple[float, float, float, str] | None:
    """The standard bearing (mm: bore, outer, width, designation) of the largest bore <= ``bore_mm_max``."""
    scale = LENGTH_SUFFIXES[unit]
    fits = [b for b in bearing_table(unit, series) if b[0] * scale <= bore_mm_max + 1e-9]
    if not fits:
        return None
    d, od, w, name = fits[-1]
    return d * scale, od * scale, w * scale, name


def bearing_for_bore(bore_mm: float, unit: str, series: str = "18") -> tuple[float, float, float, str] | None:
    """The standard bearing (mm: bore, outer, width, designation) whose bore is ``bore_mm``, or None."""
    found = standard_bearing(bore_mm, unit, series)
    return found if found is not None and abs(found[0] - bore_mm) <= 1e-6 else None


def standard_bores(unit: str, series: str = "18") -> str:
    """The standard bores of a series, as an error's allowed values."""
    return ", ".join(f"{b[0]:g}" for b in bearing_table(unit, series)) + f" {unit}"


def series_name(unit: str, series: str) -> str:
    """What a bearing table is called in a rule's text."""
    return f"ISO 15 series {series}" if unit == "mm" else "ABMA R series"


def put_bearing(completion: "Completion", unit: str, prefix: str, bore_mm: float, series: str, gear: str,
                reason: str) -> tuple[float, float]:
    """``[parts] <prefix>_outer_diameter`` and ``<prefix>_width``: the standard bearing of ``series``
    whose bore is the shaft's, ``bore_mm`` (``gear``'s bore, which the shaft fills); the file's own
    values stand. A bore that is no standard one needs the file's bearing: refused naming the key to
    give. Returns the (outer diameter, width), mm, the drive is sized with."""
    od_name, width_name = f"{prefix}_outer_diameter", f"{prefix}_width"
    od, width = given_number(completion.parts, od_name), given_number(completion.parts, width_name)
    if od is not None and width is not None:
        return od, width
    if not bore_mm > 0:
        raise DesignError(f"gears.{gear}.bore_diameter", "missing: the default bearing fits the shaft the bore "
                          "gives", f"bore_diameter_* > 0, or [parts] {od_name}_* and {width_name}_*")
    found = bearing_for_bore(bore_mm, unit, series)
    if found is None:
        missing = od_name if od is None else width_name
        raise DesignError(f"parts.{missing}_{unit}", f"missing, and the {in_unit(bore_mm, unit):g} {unit} bore of "
                          f"gears.{gear} is no standard bearing bore ({series_name(unit, series)}) to size it from",
                          f"the bearing's outer diameter and width, or a standard bore: {standard_bores(unit, series)}")
    d, outer, wide, name = found
    why = (f"{name}, {in_unit(d, unit):g} x {in_unit(outer, unit):g} x {in_unit(wide, unit):g} {unit} "
           f"({series_name(unit, series)}): {reason}")
    completion.put("parts", f"{od_name}_{unit}", in_unit(outer, unit), why)
    completion.put("parts", f"{width_name}_{unit}", in_unit(wide, unit), why)
    return (od if od is not None else outer), (width if width is not None else wide)


# ---------------------------------------------------------------- springs

def music_wire_allowable(wire_mm: float) -> float:
    """Static allowable shear stress of music wire (ASTM A228), MPa: 0.45 of S_ut = A / d^m."""
    return MUSIC_WIRE_ALLOWABLE_FRACTION * MUSIC_WIRE_A / wire_mm ** MUSIC_WIRE_M


def wahl_stress_per_newton(wire_mm: float, mean_mm: float) -> float:
    """Wire shear stress per newton of a helical spring (MPa/N): the Wahl factor x 8 D / (pi d^3)."""
    index = mean_mm / wire_mm
    wahl = (4 * index - 1) / (4 * index - 4) + 0.615 / index
    return wahl * 8 * mean_mm / (math.pi * wire_mm ** 3)


def coil_rate(wire_mm: float, mean_mm: float, active_coils: float, shear_modulus_GPa: float = STEEL_G_GPA) -> float:
    """Rate of a helical compression spring, N/mm: G d^4 / (8 D^3 n)."""
    return shear_modulus_GPa * 1e3 * wire_mm ** 4 / (8 * mean_mm ** 3 * active_coils)


# ---------------------------------------------------------------- motors

def motor_for(torque_Nm: float, key: str = "preload.max_output_torque"):
    """The smallest :data:`MOTORS` frame giving ``torque_Nm``; refused naming ``key`` beyond the largest."""
    for frame in MOTORS:
        if frame[4] >= torque_Nm:
            return frame
    raise DesignError(key, f"the motor must give {torque_Nm:.3g} N·m, more than the largest default frame "
                      f"({MOTORS[-1][0]}, {MOTORS[-1][4]:g} N·m)", "a [parts] table with the motor")


def put_motor(completion: "Completion", frame, torque_Nm: float) -> None:
    """The motor's envelope keys of ``frame`` (:func:`motor_for`): its flange, its body as wide as
    the flange and the frame's length, the flange 0.08 of its side thick (at least 3 mm); sized
    from the file's flange where it gives one."""
    name, flange, body_length, _, _ = frame
    unit, put = completion.unit, completion.put
    why = f"{name} envelope: the smallest frame for {torque_Nm:.3g} N·m at the motor"
    flange = completion.number("motor_flange", flange)
    put("parts", f"motor_body_diameter_{unit}", rounded(flange, unit), why)
    put("parts", f"motor_body_length_{unit}", rounded(body_length, unit), why)
    put("parts", f"motor_flange_{unit}", rounded(flange, unit), why)
    put("parts", f"motor_flange_thickness_{unit}", rounded(max(3.0, 0.08 * flange), unit), why)


# ---------------------------------------------------------------- the file's [parts]

def field_name(key: str) -> str:
    """A [parts] key without its unit suffix (``motor_flange_mm`` -> ``motor_flange``)."""
    for suffix in ("_mm", "_in", "_per_in"):
        if key.endswith(suffix):
            return key[: -len(suffix)]
    return key


def given(table: Mapping[str, Any], key: str, synonyms: Mapping[str, str] | None = None) -> bool:
    """Whether the file's table gives ``key`` in any unit (or its synonym)."""
    name = field_name(key)
    names = {field_name(k) for k in table}
    return name in names or (synonyms or {}).get(name) in names


def given_number(table: Mapping[str, Any], name: str, unit: str | None = None) -> float | None:
    """The file's value of the length or number ``name`` (mm for a length), or None (also for a bad
    value: the validating load refuses it, naming it; nothing is sized from it)."""
    for k, v in table.items():
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
            continue
        if k == name:
            return float(v)
        for suffix, scale in LENGTH_SUFFIXES.items():
            if k == f"{name}_{suffix}":
                return float(v) * scale
    return None


def partial_table(table: Any, fields: list, where: str = "parts") -> bool:
    """Whether ``table`` leaves out a key its ``fields`` need and gives only values they accept (a
    bad one is the validating load's to refuse, naming it; nothing is sized from it)."""
    if not isinstance(table, Mapping):
        return False
    try:
        read_table(table, [replace(f, required=False) for f in fields], where)
    except DesignError:
        return False
    return any(f.required and not given(table, f.name) for f in fields)


class Completion:
    """A parsed design file being completed: :meth:`put` adds a value the file does not give (a
    ``[parts]`` key the file gives stands) with its rule; ``data`` is the completed copy, ``added``
    what was added."""

    def __init__(self, data: Mapping[str, Any], synonyms: Mapping[str, str] | None = None, unit: str = "mm"):
        self.original = data
        self.data = copy.deepcopy(dict(data))
        self.added: list[Defaulted] = []
        self.synonyms = synonyms or {}
        self.unit = unit

    @property
    def parts(self) -> Mapping[str, Any]:
        """The file's own [parts] (empty when it gives none)."""
        table = self.original.get("parts")
        return table if isinstance(table, Mapping) else {}

    def put(self, section: str, key: str, value: Any, why: str) -> None:
        if section == "parts" and given(self.parts, key, self.synonyms):
            return  # the file's value stands
        table = self.data.setdefault(section, {})
        if "." in key:  # a sub-table (stiffness.components.NAME)
            sub, key = key.rsplit(".", 1)
            for part in sub.split("."):
                table = table.setdefault(part, {})
            where = f"{section}.{sub}.{key}"
        else:
            where = f"{section}.{key}"
        table[key] = value
        self.added.append(Defaulted(where, value, why))

    def number(self, name: str, default: float) -> float:
        """The file's [parts] value of ``name`` (mm for a length), else ``default``."""
        value = given_number(self.parts, name)
        return default if value is None else value

    def length(self, name: str, mm: float, why: str, exact: bool = False) -> float:
        """``[parts] <name>_<unit>``: ``mm`` rounded up to 0.5 mm (1/32 in), or to 1 nm when
        ``exact`` (a size another part must equal). Returns the length the drive gets (mm): the
        file's, else this default."""
        value = in_unit(mm, self.unit) if exact else rounded(mm, self.unit)
        self.put("parts", f"{name}_{self.unit}", value, why)
        return self.number(name, value * LENGTH_SUFFIXES[self.unit])

    def stated(self, name: str, mm: float, inch: float, why: str) -> float:
        """``[parts] <name>_<unit>``: a stated size, ``mm`` (``inch`` in an inch design). Returns the
        length the drive gets (mm): the file's, else this default."""
        value = mm if self.unit == "mm" else inch
        self.put("parts", f"{name}_{self.unit}", value, why)
        return self.number(name, value * LENGTH_SUFFIXES[self.unit])

    def shown(self, mm: float) -> str:
        """A length for a rule's text, in the design's unit."""
        return f"{mm / LENGTH_SUFFIXES[self.unit]:.4g} {self.unit}"

    def result(self) -> tuple[dict[str, Any], tuple[Defaulted, ...]]:
        return self.data, tuple(self.added)


def parts_wanted(data: Mapping[str, Any], fields: list) -> bool:
    """Whether the file's ``[parts]`` is to be completed: it gives none, or a partial one."""
    return "parts" not in data or partial_table(data["parts"], fields)


def completing(data: Mapping[str, Any], readers: Readers, fields: list, gears: tuple[str, ...] = (),
               roles: tuple[str, ...] = ()):
    """Where a kind's rules start: ``(design, layout settings, gears, Completion)``, the file as read
    (its gears, its ``[layout]``), the gears named by ``gears`` and by the ``[layout]`` keys ``roles``,
    and the completion to put the defaults in; None when the file gives its whole [parts] (``fields``:
    the kind's) or cannot be read so (the validating load then reports the problem)."""
    if not parts_wanted(data, fields):
        return None
    try:
        design = readers.design(data)
        settings = readers.layout(design)
    except DesignError:
        return None
    names = list(gears) + [settings.get(role) for role in roles]
    if any(n not in design.gears for n in names):
        return None  # a missing gear: the validating load says which
    return design, settings, [design.gears[n] for n in names], Completion(data, unit=design.length_unit)


__all__ = ["METRIC_SERIES", "METRIC_BEARINGS", "INCH_BEARINGS", "WIRE_DIAMETERS", "MUSIC_WIRE_A", "MUSIC_WIRE_M",
           "STEEL_E_GPA", "STEEL_G_GPA", "MOTORS", "Defaulted", "Readers", "Completion", "length_step", "rounded",
           "in_unit", "metric_or_inch", "bearing_table", "standard_bearing", "bearing_for_bore", "standard_bores",
           "series_name", "put_bearing",
           "music_wire_allowable", "wahl_stress_per_newton", "coil_rate", "motor_for", "put_motor", "field_name",
           "given", "given_number", "partial_table", "parts_wanted", "completing"]
