"""The ``[train]`` and ``[dual_motor]`` sections: what ``geargen train`` needs beyond the drive.

``[train]`` (every key optional)::

    [train]
    material = "steel"                      # of every rotating part not in [train.part_materials]
    mesh_friction_coefficient = 0.05        # sliding friction in the meshes (preload friction)
    allowed_lost_motion_arcsec = 20         # at the output: which stages need to be anti-backlash
    motor_rotor_inertia_kg_cm2 = 0.33       # the motor's data sheet (the rotor is not a modelled solid)
    motor_torque_constant_Nm_per_A = 0.11
    motor_peak_torque_Nm = 0.95
    load_inertia_kg_m2 = 0.02               # what the output drives, beyond the modelled parts
    bandwidth_Hz = 30                       # position loop: give a bandwidth and damping ratio of the
    damping_ratio = 0.7                     #   geared drive, or the gains at the motor:
    # position_gain_Nm_per_rad = 12.0 ; velocity_gain_Nm_s_per_rad = 0.05
    upstream_backlash_arcmin = [12]         # per [layout] upstream_stages entry (at its driven shaft)
    upstream_stiffness_Nm_per_arcmin = [2.5]

    [train.materials]                       # density (kg/m^3) per material; these four are known
    steel = 7850

    [train.part_materials]                  # part name -> material
    output = "aluminium"

``[dual_motor]`` describes a drive of two motors, each with its own pinion on one output gear (Fig. 1);
the meshes and their centre distance are ``[checks] meshes``, so ``geargen check`` checks them::

    [dual_motor]
    pinions = ["pinion_a", "pinion_b"]
    output = "output"
    control = "bias"                        # "bias" (Fig. 1b) or "unidirectional" (Fig. 1a)
    bias_torque_Nm = 60                     # at the output
    motor_peak_torque_Nm = 12               # each motor, at its shaft
    max_output_torque_Nm = 100              # the load either way
    upstream_ratio = 5                      # a gearhead between each motor and its pinion
    upstream_stiffness_Nm_per_arcmin = 9    # the gearhead's torsional stiffness at its output
    pinion_shaft_diameter_mm = 20           # each pinion's shaft twists from the gearhead to the pinion
    pinion_shaft_length_mm = 40
    elastic_modulus_GPa = 207               # gears (Eq. 1) and shafts
    shear_modulus_GPa = 79.3
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

from geargen.design.layout import layout_settings
from geargen.design.schema import Field, as_float, check_range, shown
from geargen.design.stiffness import Quantity, read_quantity_section, value_of
from geargen.errors import DesignError

#: densities (kg/m^3) geargen knows; [train.materials] adds to them or replaces one
DENSITIES = {"steel": 7850.0, "stainless_steel": 7900.0, "aluminium": 2700.0, "brass": 8500.0,
             "bronze": 8800.0, "cast_iron": 7200.0, "titanium": 4430.0, "acetal": 1410.0, "nylon": 1140.0}

TRAIN_FIELDS = [
    Field("material", "string", required=False, default="steel",
          help="material of every rotating part not named in [train.part_materials] (a [train.materials] name)"),
    Field("mesh_friction_coefficient", "number", required=False, default=0.05, minimum=0.0, maximum=1.0,
          help="sliding friction coefficient of the tooth flanks (the preload's friction torque)"),
    Field("allowed_lost_motion", "angle", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          units=("urad", "arcsec", "arcmin", "deg"),
          help="lost motion the output may have: the strategy advice names the stages to preload for it"),
    Field("damping_ratio", "number", required=False, default=None, minimum=0.0, maximum=10.0,
          help="damping ratio of the geared drive's position loop (with bandwidth_Hz)"),
    Field("upstream_backlash_arcmin", "list", required=False, default=(),
          help="backlash of each [layout] upstream_stages entry, at its driven shaft (arcmin; a gearhead's data "
               "sheet)"),
    Field("upstream_stiffness_Nm_per_arcmin", "list", required=False, default=(),
          help="torsional stiffness of each [layout] upstream_stages entry at its driven shaft (N·m/arcmin)"),
]
TRAIN_QUANTITIES = [
    Quantity("motor_rotor_inertia", ("inertia",), help="the motor rotor's moment of inertia (data sheet)"),
    Quantity("motor_torque_constant", ("torque_constant",), help="the motor's torque constant"),
    Quantity("motor_peak_torque", ("torque",), help="the motor's peak torque, at its shaft"),
    Quantity("load_inertia", ("inertia",), exclusive_minimum=False, minimum=0.0,
             help="inertia the output drives beyond the modelled parts"),
    Quantity("bandwidth", ("frequency",), help="natural frequency of the geared drive's position loop"),
    Quantity("position_gain", ("torsional_stiffness",), help="position-loop gain at the motor (the servo's stiffness)"),
    Quantity("velocity_gain", ("rotary_damping",), exclusive_minimum=False, minimum=0.0,
             help="velocity (derivative) gain at the motor"),
]
_TRAIN_TABLES = ("materials", "part_materials")


@dataclass(frozen=True)
class TrainSettings:
    """``[train]`` in SI for the servo (kg·m², N·m/rad, N·m·s/rad, rad/s, N·m/A), N·mm for the
    motor's peak torque (geargen's torque unit), rad for angles."""

    material: str = "steel"
    densities: Mapping[str, float] = field(default_factory=lambda: dict(DENSITIES))
    part_materials: Mapping[str, str] = field(default_factory=dict)
    mesh_friction_coefficient: float = 0.05
    allowed_lost_motion: float | None = None
    motor_rotor_inertia: float | None = None
    motor_torque_constant: float | None = None
    motor_peak_torque: float | None = None  # N·mm
    load_inertia: float = 0.0
    bandwidth: float | None = None  # rad/s
    damping_ratio: float | None = None
    position_gain: float | None = None  # N·m/rad at the motor
    velocity_gain: float | None = None  # N·m·s/rad at the motor
    upstream_backlash: tuple[float, ...] = ()  # rad at each upstream stage's driven shaft
    upstream_stiffness: tuple[float, ...] = ()  # N·m/rad at each upstream stage's driven shaft

    def material_of(self, part: str) -> str:
        return self.part_materials.get(part, self.material)

    def density(self, part: str) -> float:
        """kg/m^3 of ``part``."""
        return self.densities[self.material_of(part)]

    @property
    def has_servo(self) -> bool:
        return self.motor_rotor_inertia is not None and (self.bandwidth is not None or self.position_gain is not None)


def _numbers(values: Any, where: str, family: str, scale: float, unit: str) -> tuple[float, ...]:
    """A list of positive numbers written in ``unit`` (``scale`` of the :data:`PLAUSIBLE` family's
    internal unit each), each in that family's plausible range."""
    if not isinstance(values, (list, tuple)):
        raise DesignError(where, f"expected a list of numbers, got {shown(values)}", "[number, ...]")
    positive = Field(where, "number", minimum=0.0, exclusive_minimum=True)
    out = []
    for i, v in enumerate(values):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise DesignError(f"{where}[{i}]", f"expected a number, got {shown(v)}", "[number, ...]")
        check_range(positive, as_float(v, f"{where}[{i}]") * scale, f"{where}[{i}]", scale, unit, family)
        out.append(float(v))
    return tuple(out)


def train_settings(design) -> TrainSettings:
    """``[train]`` of ``design`` read and checked (absent: every default)."""
    raw = design.section("train")
    v = read_quantity_section(raw, TRAIN_FIELDS, TRAIN_QUANTITIES, "train", _TRAIN_TABLES)
    densities = dict(DENSITIES)
    materials = raw.get("materials", {})
    if not isinstance(materials, Mapping):
        raise DesignError("train.materials", "expected a table", "material = density in kg/m^3")
    for name, rho in materials.items():
        if isinstance(rho, bool) or not isinstance(rho, (int, float)) or not 100 <= rho <= 25000:
            raise DesignError(f"train.materials.{name}", f"{rho!r} is out of range", "a density 100 to 25000 kg/m^3")
        densities[name] = float(rho)
    part_materials = raw.get("part_materials", {})
    if not isinstance(part_materials, Mapping):
        raise DesignError("train.part_materials", "expected a table", "part name = material name")
    for part, material in {"": v["material"], **part_materials}.items():
        where = f"train.part_materials.{part}" if part else "train.material"
        if material not in densities:
            raise DesignError(where, f"{material!r} is not a known material", ", ".join(sorted(densities)))
    count = len(layout_settings(design)["upstream_stages"]) if design.section("layout") else 0
    lists = {}
    # (key, unit, its family, internal units per unit, the model's units per unit: rad, N·m/rad)
    for key, unit, family, internal, model in (
            ("upstream_backlash_arcmin", "arcmin", "angle", math.pi / 10800.0, math.pi / 10800.0),
            ("upstream_stiffness_Nm_per_arcmin", "Nm_per_arcmin", "torsional_stiffness", 1e3 * 10800.0 / math.pi,
             10800.0 / math.pi)):
        values = _numbers(v[key], f"train.{key}", family, internal, unit)
        if values and len(values) != count:
            raise DesignError(f"train.{key}", f"{len(values)} values for {count} [layout] upstream_stages",
                              "one per upstream stage")
        lists[key] = tuple(x * model for x in values)
    given = {k: value_of(v[k]) for k in ("bandwidth", "position_gain", "velocity_gain")}
    if given["bandwidth"] is not None and given["position_gain"] is not None:
        raise DesignError("train.position_gain", "given with bandwidth_Hz", "one of bandwidth_Hz (with damping_ratio) "
                          "or position_gain_* (with velocity_gain_*)")
    if given["bandwidth"] is not None and v["damping_ratio"] is None:
        raise DesignError("train.damping_ratio", "missing: bandwidth_Hz needs a damping ratio", "0 to 10")
    if given["position_gain"] is not None and given["velocity_gain"] is None:
        raise DesignError("train.velocity_gain", "missing: position_gain needs a velocity gain", "velocity_gain_Nm_s_per_rad")
    return TrainSettings(
        material=v["material"], densities=densities, part_materials=dict(part_materials),
        mesh_friction_coefficient=v["mesh_friction_coefficient"], allowed_lost_motion=v["allowed_lost_motion"],
        motor_rotor_inertia=value_of(v["motor_rotor_inertia"]),
        motor_torque_constant=value_of(v["motor_torque_constant"]),
        motor_peak_torque=value_of(v["motor_peak_torque"]), load_inertia=value_of(v["load_inertia"]) or 0.0,
        bandwidth=None if given["bandwidth"] is None else 2 * math.pi * given["bandwidth"],
        damping_ratio=v["damping_ratio"],
        position_gain=None if given["position_gain"] is None else given["position_gain"] / 1e3,
        velocity_gain=given["velocity_gain"],
        upstream_backlash=lists["upstream_backlash_arcmin"], upstream_stiffness=lists["upstream_stiffness_Nm_per_arcmin"])


# ---------------------------------------------------------------------------------------------
# [dual_motor]

DUAL_MOTOR_FIELDS = [
    Field("pinions", "list", help="the two motors' pinions, [gears] names, each meshing the output"),
    Field("output", "string", help="the output gear, a [gears] name"),
    Field("control", "string", choices=("bias", "unidirectional"),
          help="Fig. 1b (a constant bias torque between the motors) or Fig. 1a (unidirectional torques)"),
    Field("upstream_ratio", "number", required=False, default=1.0, minimum=1.0,
          help="reduction between each motor and its pinion (a gearhead; 1: the pinion on the motor)"),
    Field("pinion_shaft_diameter", "length", minimum=0.0, exclusive_minimum=True,
          help="each pinion's shaft, twisting between the gearhead (or motor) and the pinion"),
    Field("pinion_shaft_length", "length", minimum=0.0, exclusive_minimum=True,
          help="twisting length of each pinion's shaft"),
    Field("mesh_stiffness", "string", required=False, default="eq1", choices=("eq1", "iso6336"),
          help="each pinion's mesh: eq1, the paper's E w / 11; iso6336, ISO 6336-1:2019 method B, c_gamma_alpha w "
               "(as [stiffness] mesh_stiffness)"),
]
DUAL_MOTOR_QUANTITIES = [
    Quantity("bias_torque", ("torque",), required=True, help="bias between the motors, at the output"),
    Quantity("motor_peak_torque", ("torque",), required=True, help="each motor's peak torque, at its shaft"),
    Quantity("max_output_torque", ("torque",), required=True, help="the largest load either way, at the output"),
    Quantity("upstream_stiffness", ("torsional_stiffness",), help="the gearhead's stiffness at its output (absent: rigid)"),
    Quantity("elastic_modulus", ("stress",), help="the gears' and shafts' elastic modulus (default 207 GPa)"),
    Quantity("shear_modulus", ("stress",), help="the shafts' shear modulus (default 79.3 GPa)"),
]


@dataclass(frozen=True)
class DualMotorSpec:
    """``[dual_motor]`` in internal units (mm, N·mm, N·mm/rad, MPa)."""

    pinions: tuple[str, str]
    output: str
    control: str
    bias_torque: float
    motor_peak_torque: float
    max_output_torque: float
    upstream_ratio: float
    pinion_shaft_diameter: float
    pinion_shaft_length: float
    upstream_stiffness: float | None
    elastic_modulus: float
    shear_modulus: float
    centre_distances: tuple[float, float]  # from [checks] meshes
    mesh_stiffness: str = "eq1"  # "eq1" or "iso6336" (geargen.core.stiffness.gear_mesh_stiffness)


def dual_motor_spec(design) -> DualMotorSpec:
    """``[dual_motor]`` read and checked: two pinions and the output are gears of the file, and
    ``[checks] meshes`` declares each pinion with the output (their centre distances)."""
    from geargen.design.checks import checks_settings
    v = read_quantity_section(design.section("dual_motor"), DUAL_MOTOR_FIELDS, DUAL_MOTOR_QUANTITIES, "dual_motor")
    pinions = v["pinions"]
    if not (isinstance(pinions, (list, tuple)) and len(pinions) == 2 and all(isinstance(p, str) for p in pinions)
            and pinions[0] != pinions[1]):
        raise DesignError("dual_motor.pinions", f"{pinions!r} is not two different gear names", '["pinion_a", "pinion_b"]')
    for key, name in (("pinions", pinions[0]), ("pinions", pinions[1]), ("output", v["output"])):
        if name not in design.gears:
            raise DesignError(f"dual_motor.{key}", f"no gear named {name!r}", ", ".join(design.gears))
    declared = {frozenset((m.gear1, m.gear2)): m.centre_distance for m in checks_settings(design).meshes}
    centres = []
    for p in pinions:
        if frozenset((p, v["output"])) not in declared:
            raise DesignError("checks.meshes", f"[dual_motor] drives the output through {p}, but [checks] meshes does "
                              f"not declare the pair", f'["{p}", "{v["output"]}"] with its centre distance')
        centres.append(declared[frozenset((p, v["output"]))])
    a, b = (design.gears[p] for p in pinions)
    if a.teeth != b.teeth:
        raise DesignError("dual_motor.pinions", f"{a.teeth} and {b.teeth} teeth: the two motors turn alike only with "
                          "equal pinions", "two pinions of one tooth count")
    peak = value_of(v["motor_peak_torque"]) * v["upstream_ratio"] * design.gears[v["output"]].teeth / a.teeth
    bias, load = value_of(v["bias_torque"]), value_of(v["max_output_torque"])
    if v["control"] == "bias" and load / 2 + bias > peak * (1 + 1e-12):
        raise DesignError("dual_motor.bias_torque", f"{bias / 1e3:g} N·m with a {load / 1e3:g} N·m load asks "
                          f"{(load / 2 + bias) / 1e3:.4g} N·m of one motor at the output, more than its peak "
                          f"{peak / 1e3:.4g} N·m", f"at most {(peak - load / 2) / 1e3:.4g} N·m")
    if v["control"] == "unidirectional" and load + bias > peak * (1 + 1e-12):
        raise DesignError("dual_motor.max_output_torque", f"{load / 1e3:g} N·m plus the bias is more than one motor's "
                          f"peak at the output ({peak / 1e3:.4g} N·m): with unidirectional torques one motor carries "
                          "the load", f"at most {(peak - bias) / 1e3:.4g} N·m")
    return DualMotorSpec(pinions=tuple(pinions), output=v["output"], control=v["control"], bias_torque=bias,
                         motor_peak_torque=value_of(v["motor_peak_torque"]), max_output_torque=load,
                         upstream_ratio=v["upstream_ratio"], pinion_shaft_diameter=v["pinion_shaft_diameter"],
                         pinion_shaft_length=v["pinion_shaft_length"], upstream_stiffness=value_of(v["upstream_stiffness"]),
                         elastic_modulus=value_of(v["elastic_modulus"]) or 207e3,
                         shear_modulus=value_of(v["shear_modulus"]) or 79.3e3, centre_distances=tuple(centres),
                         mesh_stiffness=v["mesh_stiffness"])


__all__ = ["DENSITIES", "TRAIN_FIELDS", "TRAIN_QUANTITIES", "TrainSettings", "train_settings", "DUAL_MOTOR_FIELDS",
           "DUAL_MOTOR_QUANTITIES", "DualMotorSpec", "dual_motor_spec"]
