"""The ``[duty]`` and ``[materials.GEAR]`` sections: what the load capacity of every mesh of a drive
is rated for (:mod:`geargen.checks.rating`, ISO 6336-2/-3 method B and ISO 6336-6).

Every key is optional; a drive without either section is rated with the defaults below::

    [duty]
    output_torque_levels_Nm = [5.0, 2.5, 0.5]   # the load spectrum at the output (any torque suffix);
                                                # default: [preload] max_output_torque_* as the one level
    level_shares = [0.1, 0.3, 0.6]              # of the life at each level; or level_hours = [...],
                                                # or level_cycles = [...] (output revolutions)
    direction = "both"                          # each level half its share each way; "signed": levels
                                                # carry a sign (positive: the way path 1 carries its preload)
    output_speed_rpm = 60
    life_hours = 20000
    application_factor = 1.0                    # K_A
    viscosity_mm2_per_s = 100                   # the lubricant's nu_40 (its ISO VG number)
    roughness_Ra_um = 1.6                       # flanks and roots
    accuracy_grade = 7                          # ISO 1328-1, for gears whose table gives none
    material = "through_hardened"               # every gear without a [materials.GEAR] table
    quality = "MQ"
    hardness_HV = 300

    [materials.output]                          # one table per gear table name
    material = "case_carburised"
    quality = "MQ"

The defaults and why (each Field's help says it too): the spectrum is the paper's maximum load
(``[preload] max_output_torque_*``) in both directions for the whole life: the most any level
can be, so nothing is credited that the file does not state. 20,000 h at 60 output rpm is 7.2e7
output revolutions, past the endurance knee of every ISO 6336 life curve (at most 5e7 cycles), so
no gear is credited with a limited-life factor above 1: a long-life rating. K_A = 1: the stated
torques are the peaks the output sees (ISO 6336-6 rates a stated spectrum with K_A = 1). The
material is through hardened alloy steel (42CrMo4 / AISI 4140, quenched and tempered) of ISO
6336-5 quality MQ at 300 HV (about 30 HRC): the hardest such steel still hobbed or shaped after
heat treatment, so fine-pitch precision gears like the shipped drives' are cut to their accuracy
without grinding; accuracy grade 7 and R_a 1.6 um are what that cutting holds; ISO VG 100 is the
lightest of the usual enclosed-gear oils (ISO 12925-1 CKC), the conservative end for Z_L.

ISO 6336-5's numbers are lines in the surface hardness for each material and quality
(:mod:`geargen.design.iso6336_5`): a hardness outside the line's range is refused naming the
range, and a material whose numbers grow with hardness (through hardened, induction hardened)
needs its hardness (the default material's is the default hardness).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from geargen.design.iso6336_5 import MATERIAL_NAMES, QUALITY_GRADES, hardness_needed, hardness_range
from geargen.design.schema import Field, as_float, check_range, read_table, shown, unknown_key
from geargen.design.stiffness import QUANTITY_SUFFIXES, Quantity, read_quantity_section, preload_spec_from_table
from geargen.errors import DesignError

DIRECTIONS = ("both", "signed")
#: the defaults of the module docstring (rpm, h, mm^2/s, mm, HV)
DEFAULT_OUTPUT_SPEED = 60.0
DEFAULT_LIFE = 20000.0
DEFAULT_VISCOSITY = 100.0
DEFAULT_ROUGHNESS = 1.6e-3
DEFAULT_ACCURACY_GRADE = 7
DEFAULT_MATERIAL = "through_hardened"
DEFAULT_QUALITY = "MQ"
DEFAULT_HARDNESS = 300.0
#: the most levels a spectrum may have: far more than any measured load collective is binned into
MAX_LEVELS = 1000
#: the largest share (1), hours (1e7, as life_hours) and output revolutions (1e15) one level may have
_MOST = {"level_shares": 1.0, "level_hours": 1e7, "level_cycles": 1e15}
#: how far level_shares may sum from 1 (then scaled to 1): three typed decimals of thirds
SHARE_SUM_TOLERANCE = 1e-3

_MATERIAL_HELP = "ISO 6336-5 material and heat treatment"
DUTY_FIELDS = [
    Field("level_shares", "list", required=False, default=None,
          help="fraction of the life spent at each torque level (summing to 1); or level_hours or level_cycles "
               "(default: one level, the whole life)"),
    Field("level_hours", "list", required=False, default=None,
          help="hours at each torque level: the life is their sum (instead of level_shares and life_hours)"),
    Field("level_cycles", "list", required=False, default=None,
          help="output revolutions at each torque level: the life is their sum at output_speed_rpm (instead of "
               "level_shares and life_hours)"),
    Field("direction", "string", required=False, default="both", choices=DIRECTIONS,
          help="both: each level acts half its share each way (a positioning drive reverses); signed: the levels "
               "carry a sign, positive the way path 1 (the stiff path of a type 1) carries its preload"),
    Field("output_speed_rpm", "number", required=False, default=DEFAULT_OUTPUT_SPEED, minimum=0.0,
          exclusive_minimum=True, maximum=1e5,
          help="speed of the output while it carries the spectrum (default 60 rpm: with the default life 7.2e7 "
               "output revolutions, past every ISO 6336 life curve's endurance knee: a long-life rating)"),
    Field("life_hours", "number", required=False, default=DEFAULT_LIFE, minimum=0.0, exclusive_minimum=True, maximum=1e7,
          help="required life (default 20,000 h: ten years of one shift, a machine's usual design life)"),
    Field("application_factor", "number", required=False, default=1.0, minimum=1.0, maximum=10.0,
          help="K_A (ISO 6336-1; default 1: the stated torques are the peaks the output sees, as ISO 6336-6 rates "
               "a stated spectrum)"),
    Field("viscosity_mm2_per_s", "number", required=False, default=DEFAULT_VISCOSITY, minimum=2.0, maximum=3200.0,
          help="the lubricant's kinematic viscosity at 40 deg C, nu_40 (its ISO VG number; default ISO VG 100, the "
               "lightest usual enclosed-gear oil: the conservative end for Z_L)"),
    Field("roughness_Ra", "length", required=False, default=DEFAULT_ROUGHNESS, minimum=0.0, exclusive_minimum=True,
          maximum=0.05, help="arithmetic mean roughness R_a of flanks and roots (R_z taken as 6 R_a; default 1.6 um, "
                             "hobbed or shaped flanks)"),
    Field("accuracy_grade", "integer", required=False, default=DEFAULT_ACCURACY_GRADE, minimum=1, maximum=11,
          help="ISO 1328-1:2013 flank tolerance class of the gears whose table gives no accuracy_grade (default 7: "
               "what hobbing holds); a mesh is rated at the coarser of its two gears' grades"),
    Field("face_load_factor", "number", required=False, default=None, minimum=1.0, maximum=10.0,
          help="K_Hbeta of every mesh, given (default: ISO 6336-1 method C, each pinion centred between its "
               "bearings on a stiff shaft, no helix correction)"),
    Field("tip_relief", "length", required=False, default=0.0, minimum=0.0, maximum=1.0,
          help="tip relief C_a of every gear (ISO 6336-1 K_v; default none)"),
    Field("material", "string", required=False, default=DEFAULT_MATERIAL, choices=MATERIAL_NAMES,
          help=_MATERIAL_HELP + " of every gear without a [materials.GEAR] table (default through_hardened: "
               "quenched and tempered alloy steel, hobbed after hardening)"),
    Field("quality", "string", required=False, default=DEFAULT_QUALITY, choices=QUALITY_GRADES,
          help="ISO 6336-5 quality grade of that material (default MQ: what an experienced maker meets at moderate "
               "cost)"),
    Field("hardness_HV", "number", required=False, default=None, minimum=100.0, maximum=1000.0,
          help="surface hardness of that material, HV (default 300 HV for through_hardened, about 30 HRC: the hardest "
               "still cut after hardening; the range ISO 6336-5 covers for the material is checked)"),
]
DUTY_QUANTITIES = [
    Quantity("output_torque_levels", ("torque",), minimum=None, exclusive_minimum=False,
             help="the load spectrum: a list of drive torques at the output, largest first or in any order "
                  "(default: [preload] max_output_torque_*, the paper's maximum load, as the one level)"),
]
MATERIAL_FIELDS = [
    Field("material", "string", required=False, default=None, choices=MATERIAL_NAMES,
          help=_MATERIAL_HELP + " of this gear (default: [duty] material)"),
    Field("quality", "string", required=False, default=None, choices=QUALITY_GRADES,
          help="ISO 6336-5 quality grade ML, MQ or ME (default: [duty] quality)"),
    Field("hardness_HV", "number", required=False, default=None, minimum=100.0, maximum=1000.0,
          help="surface hardness, HV (default: [duty]'s when the material is [duty]'s; needed where the material's "
               "numbers grow with hardness)"),
]


@dataclass(frozen=True)
class GearMaterial:
    """One gear's ISO 6336-5 material: ``name`` (of :data:`geargen.design.iso6336_5.TABLE_8`),
    ``quality`` ML/MQ/ME, surface ``hardness`` in HV (None where the numbers do not depend on it),
    ``source``: the table it comes from."""

    name: str
    quality: str
    hardness: float | None
    source: str


@dataclass(frozen=True)
class DutySpec:
    """``[duty]`` in internal units: ``levels`` (output torque N·mm, share of the life) as the file
    states them (or the one level of ``[preload] max_output_torque``; empty without either),
    ``levels_source`` where they come from, ``torque_unit`` the suffix the file wrote torques in;
    ``output_speed`` rpm, ``life`` h, ``roughness`` and ``tip_relief`` mm, ``viscosity`` mm^2/s;
    ``material`` every gear's without its own table; ``defaulted`` the keys the file did not give."""

    levels: tuple[tuple[float, float], ...]
    levels_source: str
    torque_unit: str
    direction: str = "both"
    output_speed: float = DEFAULT_OUTPUT_SPEED
    life: float = DEFAULT_LIFE
    application_factor: float = 1.0
    viscosity: float = DEFAULT_VISCOSITY
    roughness: float = DEFAULT_ROUGHNESS
    accuracy_grade: int = DEFAULT_ACCURACY_GRADE
    face_load_factor: float | None = None
    tip_relief: float = 0.0
    material: GearMaterial = GearMaterial(DEFAULT_MATERIAL, DEFAULT_QUALITY, DEFAULT_HARDNESS, "geargen's default")
    defaulted: tuple[str, ...] = ()

    def signed_levels(self) -> tuple[tuple[float, float, int], ...]:
        """(output torque N·mm with its sign, share of the life, level number from 1): with direction
        "both" a nonzero level is two, +T and -T, each with half its share."""
        out = []
        for number, (torque, share) in enumerate(self.levels, start=1):
            if self.direction == "both" and torque != 0.0:
                out += [(abs(torque), share / 2, number), (-abs(torque), share / 2, number)]
            else:
                out.append((torque, share, number))
        return tuple(out)


def _numbers(raw: Any, where: str, family: str | None = None, scale: float = 1.0, unit: str = "",
             positive: bool = True, maximum: float | None = None) -> list[float]:
    """A list of finite numbers (times ``scale``), each positive when ``positive``, at most ``maximum``."""
    if not isinstance(raw, list) or not raw:
        raise DesignError(where, f"expected a list of numbers, got {shown(raw)}", "[x1, x2, ...]")
    if len(raw) > MAX_LEVELS:
        raise DesignError(where, f"{len(raw):,} levels", f"at most {MAX_LEVELS}")
    bound = Field(where, "number", minimum=0.0 if positive else None, exclusive_minimum=positive, maximum=maximum)
    out = []
    for i, item in enumerate(raw):
        at = f"{where}[{i}]"
        if isinstance(item, bool) or not isinstance(item, (int, float)):
            raise DesignError(at, f"expected a number, got {shown(item)}")
        value = as_float(item, at) * scale
        check_range(bound, value, at, scale, unit, family=family)
        out.append(value)
    return out


def duty_settings(design) -> DutySpec:
    """Read ``[duty]`` of ``design`` (absent: every default; the spectrum from ``[preload]``)."""
    data = design.section("duty")
    level_keys = DUTY_QUANTITIES[0].keys()
    v = read_quantity_section(data, DUTY_FIELDS, [], "duty", tables=tuple(level_keys))
    given = [k for k in data if k in level_keys]
    if len(given) > 1:
        raise DesignError(f"duty.{given[1]}", f"given twice, also as {given[0]}", "one spelling")
    timing = [k for k in ("level_shares", "level_hours", "level_cycles") if v[k] is not None]
    if len(timing) > 1:
        raise DesignError(f"duty.{timing[1]}", f"given with {timing[0]}", "one of level_shares, level_hours and "
                          "level_cycles")
    if given:
        key = given[0]
        family, unit = level_keys[key]
        levels = _numbers(data[key], f"duty.{key}", family, QUANTITY_SUFFIXES[family][unit], unit,
                          positive=False)
        if v["direction"] == "both" and min(levels) < 0:
            i = next(i for i, t in enumerate(levels) if t < 0)
            raise DesignError(f"duty.{key}[{i}]", f"{data[key][i]} is negative, but direction = \"both\" acts each "
                              "level both ways", ">= 0, or direction = \"signed\"")
        source = f"[duty] {key}"
    else:
        if timing:
            raise DesignError(f"duty.{timing[0]}", "needs the levels it times", "output_torque_levels_<torque unit>")
        levels, source, unit = _preload_level(design)
    if "life_hours" in data and timing and timing[0] != "level_shares":
        raise DesignError("duty.life_hours", f"given with {timing[0]}, whose sum is the life", "one of them")
    life = v["life_hours"]
    shares = [1.0 / len(levels)] * len(levels) if levels and not timing else []
    if timing:
        key = timing[0]
        amounts = _numbers(v[key], f"duty.{key}", maximum=_MOST[key])
        if len(amounts) != len(levels):
            raise DesignError(f"duty.{key}", f"{len(amounts)} values for {len(levels)} torque levels",
                              "one per level of output_torque_levels")
        total = sum(amounts)
        if key == "level_shares" and abs(total - 1.0) > SHARE_SUM_TOLERANCE:
            raise DesignError("duty.level_shares", f"sum to {total:.6g}", f"1 (within {SHARE_SUM_TOLERANCE:g})")
        if key == "level_hours":
            life = total
        elif key == "level_cycles":
            life = total / (60.0 * v["output_speed_rpm"])
        shares = [a / total for a in amounts]
        if len(levels) == 1 and key == "level_shares":
            shares = [1.0]
    if levels and not timing and len(levels) > 1:
        raise DesignError("duty.level_shares", f"missing: {len(levels)} torque levels need their shares of the life",
                          "level_shares, level_hours or level_cycles, one value per level")
    material = _duty_material(v)
    # the keys whose default the rating used (the spectrum's own keys are said by levels_source)
    defaulted = tuple(f.name for f in DUTY_FIELDS if f.name not in ("level_shares", "level_hours", "level_cycles")
                      and not any(k in data for k in f.keys()))
    return DutySpec(levels=tuple(zip(levels, shares)), levels_source=source, torque_unit=unit,
                    direction=v["direction"], output_speed=v["output_speed_rpm"], life=life,
                    application_factor=v["application_factor"], viscosity=v["viscosity_mm2_per_s"],
                    roughness=v["roughness_Ra"], accuracy_grade=v["accuracy_grade"],
                    face_load_factor=v["face_load_factor"], tip_relief=v["tip_relief"], material=material,
                    defaulted=defaulted)


def _preload_level(design) -> tuple[list[float], str, str]:
    """The one level of ``[preload] max_output_torque_*`` (none without it), where it comes from and
    the torque suffix the file wrote it in."""
    table = design.section("preload")
    key = next((k for k in table if k.startswith("max_output_torque_")), None)
    if key is None:
        return [], "", "Nm"
    spec = preload_spec_from_table(table)
    return [spec.max_output_torque], f"[preload] {key} (the paper's maximum load, the whole life)", \
        key[len("max_output_torque_"):]


def _checked(name: str, quality: str, hardness: float | None, where: str, hardness_key: str | None) -> float | None:
    """``hardness`` within ISO 6336-5's range for ``name`` ``quality`` (None where the numbers do
    not depend on it); ``hardness_key`` the key the file gave it as (None: not given)."""
    lo, hi = hardness_range(name, quality)
    allowed = f"{lo:g}..{hi:g} HV (ISO 6336-5 Table 8, {name} {quality})"
    if hardness is None:
        if hardness_needed(name, quality):
            raise DesignError(f"{where}.hardness_HV", f"missing: the allowable stresses of {name} are lines in the "
                              "surface hardness", allowed)
        return None
    if not lo <= hardness <= hi:
        raise DesignError(f"{where}.{hardness_key or 'hardness_HV'}", f"{hardness:g} HV is outside the range ISO "
                          f"6336-5 gives numbers for", allowed)
    return hardness


def _duty_material(v: Mapping[str, Any]) -> GearMaterial:
    name, quality, hardness = v["material"], v["quality"], v["hardness_HV"]
    given = hardness is not None
    if hardness is None and name == DEFAULT_MATERIAL:
        hardness = DEFAULT_HARDNESS
    hardness = _checked(name, quality, hardness, "duty", "hardness_HV" if given else None)
    return GearMaterial(name, quality, hardness, "[duty]")


def gear_materials(design, duty: DutySpec | None = None) -> dict[str, GearMaterial]:
    """Every gear table's material: its ``[materials.GEAR]`` table over ``[duty]``'s (``duty``:
    the design's, read when not given)."""
    duty = duty or duty_settings(design)
    tables = design.section("materials")
    if not isinstance(tables, Mapping):
        raise DesignError("materials", "expected tables [materials.GEAR]")
    names = list(design.gears)
    for gear in tables:
        if gear not in design.gears:
            raise unknown_key(f"materials.{gear}", gear, names, ", ".join(names) or "a [gears.NAME] table",
                              "no gear table of this name")
    out = {}
    default = duty.material
    for gear in names:
        table = tables.get(gear)
        if table is None:
            out[gear] = default
            continue
        where = f"materials.{gear}"
        if not isinstance(table, Mapping):
            raise DesignError(where, f"expected a table, got {type(table).__name__}")
        v = read_table(table, MATERIAL_FIELDS, where)
        name = v["material"] or default.name
        quality = v["quality"] or default.quality
        hardness = v["hardness_HV"]
        given = hardness is not None
        if hardness is None and name == default.name:
            hardness = default.hardness
        out[gear] = GearMaterial(name, quality, _checked(name, quality, hardness, where,
                                                         "hardness_HV" if given else None), f"[{where}]")
    return out


__all__ = ["DIRECTIONS", "DUTY_FIELDS", "DUTY_QUANTITIES", "MATERIAL_FIELDS", "GearMaterial", "DutySpec",
           "duty_settings", "gear_materials"]
