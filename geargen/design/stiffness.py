"""Design-file sections of the stiffness and preload step, read into frozen dataclasses.

Sections: ``[stiffness]`` (with ``[stiffness.components.NAME]`` tables), ``[preload]``,
``[flexures]``, ``[springs]``, ``[beam_pinion]``, ``[engagement]``. Lengths and angles use the
suffixes of :mod:`geargen.units`; forces, torques, stiffnesses and stresses use the suffixes of
the tables below (:data:`QUANTITY_SUFFIXES`). Every value comes back in internal units:

========================  =================  ==========================================
quantity                  internal unit      accepted suffixes
========================  =================  ==========================================
force                     N                  ``_N`` ``_kN`` ``_lbf``
torque                    N·mm               ``_Nmm`` ``_Nm`` ``_in_lbf`` ``_ft_lbf``
linear stiffness          N/mm               ``_N_per_mm`` ``_N_per_um`` ``_N_per_m``
                                             ``_kN_per_mm`` ``_lbf_per_in``
torsional stiffness       N·mm/rad           ``_Nmm_per_rad`` ``_Nm_per_rad`` ``_kNm_per_rad``
                                             ``_Nm_per_deg`` ``_Nm_per_arcmin`` ``_in_lbf_per_rad``
stress, elastic modulus   MPa (N/mm²)        ``_MPa`` ``_GPa`` ``_Pa`` ``_kPa`` ``_psi`` ``_ksi`` ``_Mpsi``
========================  =================  ==========================================

Example (the robot joint, abridged)::

    [stiffness]
    elastic_modulus_GPa = 207          # gear and shaft material (Eq. 1: k_mesh = E w / 11)
    mesh_stiffness = "eq1"             # or "iso6336": ISO 6336-1 method B, c_gamma_alpha w
    shear_modulus_GPa = 79.3
    reduce_to = "output"               # where path stiffnesses are shown: "output", "cluster", "input"
    train = "dual_pinion"              # the two meshes of each path come from the gears (the default;
                                       # "split_pinion" for a [layout] kind = "split_pinion"); "custom":
                                       # list every component (meshes too, kind = "mesh") with its ratio
    # gear roles of the dual-pinion train (defaults shown)
    input_gear = "input"
    cluster_large_gear = "cluster_large"
    cluster_small_gear = "cluster_small"
    output_gear = "output"

    [stiffness.components.cluster_shaft]
    kind = "shaft_torsion"             # "torsion", "linear", "shaft_torsion", "shaft_bending"
    shaft = "cluster"                  # "input", "cluster", "output"
    diameter_in = 0.25
    length_in = 0.30
    scope = "each_path"                # "each_path", "path1", "path2", "common"

    [preload]
    max_output_torque_Nm = 5.0         # largest drive torque at the output, either direction
    loop_error_carriage_travel_in = 0.0095

The meshes of the dual-pinion train (Eq. 1) are not listed: they come from the gears.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from geargen.design.schema import (Field, as_float, bound_text, check_name, check_range, raise_unknown_keys, read_table,
                                   shown, unknown_key)
from geargen.drives.keys import KEYS, kind_of
from geargen.errors import DesignError
from geargen.units import ANGLE_SUFFIXES, LENGTH_SUFFIXES, QUANTITY_SUFFIXES

#: geargen's steel, MPa: the default Young's modulus of gears and shafts (Eq. 1's E)
STEEL_ELASTIC_MODULUS = 207e3

_ALL_SUFFIXES = set(LENGTH_SUFFIXES) | set(ANGLE_SUFFIXES) | {s for t in QUANTITY_SUFFIXES.values() for s in t}

#: the internal unit of each family, for messages and reports
INTERNAL_UNITS = {"force": "N", "torque": "N·mm", "linear_stiffness": "N/mm",
                  "torsional_stiffness": "N·mm/rad", "stress": "MPa", "inertia": "kg·m²",
                  "rotary_damping": "N·m·s/rad", "torque_constant": "N·m/A", "frequency": "Hz"}


def convert_quantity(value: float, family: str, suffix: str) -> float:
    """A value written with ``suffix`` (e.g. ``"Nm_per_rad"``) in internal units."""
    return float(value) * QUANTITY_SUFFIXES[family][suffix]


@dataclass(frozen=True)
class Quantity:
    """A design key whose unit suffix is a force, torque, stiffness or stress unit.

    ``families`` lists the quantity families accepted under this name (a stiffness may be
    linear or torsional; the suffix decides). Bounds are in internal units. ``help`` is the key's
    one-line meaning (as :attr:`geargen.design.schema.Field.help`).
    """

    name: str
    families: tuple[str, ...]
    required: bool = False
    # above zero unless a quantity says otherwise: a force, torque, stiffness or modulus of zero or
    # below is no part's, and a stiffness or modulus is divided by
    minimum: float | None = 0.0
    exclusive_minimum: bool = True
    maximum: float | None = None
    help: str = ""

    def keys(self) -> dict[str, tuple[str, str]]:
        """Accepted spellings -> (family, suffix)."""
        return {f"{self.name}_{s}": (fam, s) for fam in self.families for s in QUANTITY_SUFFIXES[fam]}


def read_quantity_section(data: Mapping[str, Any], fields: list[Field], quantities: list[Quantity], where: str,
                  tables: tuple[str, ...] = ()) -> dict[str, Any]:
    """``read_table`` extended with :class:`Quantity` keys; ``tables`` are sub-tables read elsewhere.

    Quantities come back as ``{name: (value_internal, family)}`` or ``None`` when absent.
    """
    if not isinstance(data, Mapping):
        raise DesignError(where, "expected a table")
    prefix = f"{where}."
    qkeys: dict[str, tuple[Quantity, str, str]] = {}
    for q in quantities:
        for key, (fam, suf) in q.keys().items():
            qkeys[key] = (q, fam, suf)
    field_keys = {k for f in fields for k in f.keys()}
    unknown = [key for key in data if key not in qkeys and key not in field_keys and key not in tables]
    if unknown:
        allowed = ", ".join(sorted(field_keys | set(tables)) + [f"{q.name}_<unit>" for q in quantities])
        known = [k for f in fields for k in f.keys()] + list(tables) + list(qkeys)
        raise_unknown_keys([unknown_key(prefix + key, key, known, allowed) for key in unknown])
    out = read_table({k: v for k, v in data.items() if k in field_keys}, fields, where)
    for q in quantities:
        present = [k for k in data if k in qkeys and qkeys[k][0] is q]
        if len(present) > 1:
            raise DesignError(prefix + present[1], f"given twice, also as {present[0]}", "one spelling")
        if not present:
            if q.required:
                fams = " or ".join(q.families)
                raise DesignError(prefix + q.name, "missing",
                                  f"{q.name}_<unit> with a {fams} unit, e.g. {next(iter(q.keys()))}")
            out[q.name] = None
            continue
        key = present[0]
        raw = data[key]
        if isinstance(raw, bool) or not isinstance(raw, (int, float)):
            raise DesignError(prefix + key, f"expected a number, got {shown(raw)}")
        _, fam, suf = qkeys[key]
        scale = QUANTITY_SUFFIXES[fam][suf]
        value = as_float(raw, prefix + key) * scale
        bounds = Field(q.name, "number", minimum=q.minimum, maximum=q.maximum,
                       exclusive_minimum=q.exclusive_minimum)
        check_range(bounds, value, prefix + key, scale, suf, family=fam)
        out[q.name] = (value, fam)
        out["_units"][q.name] = suf
    return out


def value_of(entry) -> float | None:
    return None if entry is None else entry[0]


def _user_keys(where: str, data: Mapping[str, Any], make):
    """Run ``make``; re-raise a DesignError naming ``where.NAME`` with the key the file used
    (``NAME_<unit>``) when the table gives the value with a unit suffix."""
    try:
        return make()
    except DesignError as exc:
        head, _, name = exc.field.rpartition(".")
        if head == where and name not in data:
            spelled = [k for k in data if k.startswith(name + "_") and k[len(name) + 1:] in _ALL_SUFFIXES]
            if len(spelled) == 1:
                raise DesignError(f"{where}.{spelled[0]}", exc.problem, exc.allowed) from None
        raise


def _length_text(value_mm: float, unit: str, toward: str | None = None) -> str:
    """A length in ``unit``; ``toward`` "down"/"up" rounds an upper/lower bound inwards."""
    value = value_mm / LENGTH_SUFFIXES[unit]
    return f"{bound_text(value, toward) if toward else f'{value:.6g}'} {unit}"


def _key(v: Mapping[str, Any], where: str, name: str) -> str:
    """The key of field ``name`` as the file spelled it (with its unit suffix)."""
    unit = v["_units"].get(name)
    return f"{where}.{name}_{unit}" if unit else f"{where}.{name}"


def _positive(name: str, value, allow_none: bool = False) -> None:
    if value is None and allow_none:
        return
    if value is None or not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise DesignError(name, f"{value!r} is out of range", "> 0 and finite")


# ----------------------------------------------------------------------------------------------
# [stiffness]

SHAFTS = ("input", "cluster", "output")
LOCATIONS = SHAFTS
TRAINS = ("dual_pinion", "split_pinion", "custom")
#: trains that only one kind of drive has (its keys module's STIFFNESS_TRAIN)
DRIVE_TRAINS = tuple(k.STIFFNESS_TRAIN for k in KEYS.values() if k.STIFFNESS_TRAIN)
#: the shafts of each train a component may name; their speeds come from the teeth (a split
#: pinion's "input" is the pinions' shaft: both pinions turn together, z_output / z_pinion times the
#: output). A custom train has none: each component types its ratio.
TRAIN_SHAFTS = {"dual_pinion": SHAFTS, "split_pinion": ("input", "output"), "custom": ()}
SCOPES = ("each_path", "path1", "path2", "common")
COMPONENT_KINDS = ("torsion", "linear", "shaft_torsion", "shaft_bending", "shaft_support", "mesh")
SUPPORTS = ("simple", "fixed", "cantilever")
#: how a tooth mesh's stiffness is computed: Eq. 1 of the paper (E w / 11) or ISO 6336-1:2019 method B
#: (c_gamma_alpha w, geargen.core.iso6336)
MESH_METHODS = ("eq1", "iso6336")

#: keys each component kind uses besides kind, scope, count, shaft and ratio; anything else is an error
KIND_KEYS = {
    "torsion": {"gear", "stiffness"},
    "linear": {"gear", "radius", "stiffness"},
    "shaft_torsion": {"gear", "diameter", "bore_diameter", "length", "shear_modulus", "from_geometry"},
    "shaft_bending": {"gear", "radius", "diameter", "bore_diameter", "span", "load_position", "support", "from_geometry",
                      "elastic_modulus"},
    "shaft_support": {"gear", "stiffness", "from_geometry", "elastic_modulus"},
    "mesh": {"gears", "face_width", "elastic_modulus"},
}


@dataclass(frozen=True)
class ComponentSpec:
    """One stiffness component of a path, internal units (mm, N, rad).

    Where it sits, in a train geargen models (dual or split pinion): ``shaft`` (one of
    :data:`TRAIN_SHAFTS`) or a ``gear`` (the shaft carrying it; for a mesh its second gear), whose
    speed over the output's comes from the teeth; in a custom train: ``ratio``, the speed of its
    shaft over the output's, typed (and only there, so that it never disagrees with the teeth).
    Kinds:

      * ``torsion``: a torsional stiffness value (key, coupling, bearing tilt), N·mm/rad;
      * ``linear``: a linear stiffness (bearing, support), N/mm, acting along the line of action
        at the base radius of ``gear`` (or at ``radius``);
      * ``shaft_torsion``: a round shaft of ``diameter`` (optional ``bore_diameter``) and ``length``
        (``from_geometry``: the placed ``shaft``, or the placed shaft carrying ``gear``);
      * ``shaft_bending``: the shaft carrying ``gear`` bends under its mesh force: a round beam of
        ``diameter`` over ``span`` with the gear at ``load_position`` from one support
        (``support`` "simple", "fixed" both ends, or "cantilever" of overhang ``load_position``);
      * ``shaft_support``: the shaft carrying ``gear`` on its two placed bearings (``from_geometry``
        only): the shaft bending between or beyond them (an overhung gear) and each bearing's
        radial ``stiffness`` (N/mm per bearing) through the lever of its distance to the gear; a
        support that is itself on another placed shaft (a clamp collar on a hollow shaft) adds
        that shaft's compliance there, on its bearings of the same ``stiffness``;
      * ``mesh``: a tooth mesh of the two ``gears`` (Eq. 1, ``E w / 11`` along the line of action, or
        ISO 6336's ``c_gamma_alpha w`` with ``[stiffness] mesh_stiffness = "iso6336"``; ``w`` the
        smaller face width unless ``face_width`` is given), acting at the second gear.

    ``count`` identical components act in parallel. ``scope`` puts it in each path, in one
    path only (type 1 compliant path), or in series with the whole drive (``common``).
    """

    name: str
    kind: str
    scope: str = "each_path"
    count: int = 1
    shaft: str | None = None
    ratio: float | None = None
    gear: str | None = None
    gears: tuple[str, str] | None = None
    face_width: float | None = None
    radius: float | None = None
    stiffness: float | None = None
    diameter: float | None = None
    bore_diameter: float = 0.0
    length: float | None = None
    span: float | None = None
    load_position: float | None = None
    support: str = "simple"
    elastic_modulus: float | None = None
    shear_modulus: float | None = None
    # True: diameter, length, span and load position are those of the placed shaft
    # (geargen.model.shafts), never typed a second time here; ``placed``: they have been filled in
    # from it (geargen.model.analysis.placed_components)
    from_geometry: bool = False
    placed: bool = False
    # placed shaft_support: radial stiffness (N/mm) of the lower and the upper support
    support_stiffness: tuple[float, float] | None = None
    # placed shaft_support: the other mesh forces on the same shaft (a cluster's other gear), each
    # (distance from the lower support mm, its force over this gear's, its angle from this gear's rad)
    other_loads: tuple[tuple[float, float, float], ...] = ()

    def __post_init__(self):
        where = f"stiffness.components.{self.name}"
        if self.kind not in COMPONENT_KINDS:
            raise DesignError(f"{where}.kind", f"{self.kind!r} is not a valid choice", ", ".join(map(repr, COMPONENT_KINDS)))
        if self.scope not in SCOPES:
            raise DesignError(f"{where}.scope", f"{self.scope!r} is not a valid choice", ", ".join(map(repr, SCOPES)))
        if self.shaft is not None and self.shaft not in SHAFTS:
            raise DesignError(f"{where}.shaft", f"{self.shaft!r} is not a valid choice", ", ".join(map(repr, SHAFTS)))
        if self.support not in SUPPORTS:
            raise DesignError(f"{where}.support", f"{self.support!r} is not a valid choice", ", ".join(map(repr, SUPPORTS)))
        if not isinstance(self.count, int) or self.count < 1:
            raise DesignError(f"{where}.count", f"{self.count!r} is out of range", "a whole number >= 1")
        if self.shaft is not None and self.ratio is not None:
            raise DesignError(f"{where}.ratio", "give shaft or ratio, not both", "one of shaft, ratio")
        _positive(f"{where}.ratio", self.ratio, allow_none=True)
        located = self.shaft is not None or self.ratio is not None
        if self.kind in ("torsion", "shaft_torsion") and not (located or self.gear is not None):
            raise DesignError(f"{where}.shaft", "missing", "shaft = " + " | ".join(map(repr, SHAFTS))
                              + ", gear = NAME (the shaft carrying it) or ratio (a custom train)")
        if self.kind in ("torsion", "linear", "shaft_support"):
            _positive(f"{where}.stiffness", self.stiffness)
        if self.kind == "shaft_support" and (not self.from_geometry or self.gear is None):
            raise DesignError(f"{where}.from_geometry", "a shaft support is the placed shaft's: give gear = NAME and "
                              "from_geometry = true", "from_geometry = true with gear")
        if self.kind in ("linear", "shaft_bending"):
            if (self.gear is None) == (self.radius is None):
                raise DesignError(f"{where}.gear", "give exactly one of gear and radius_*",
                                  "gear = NAME (its base radius) or radius_* with shaft or ratio")
            if self.radius is not None and not located:
                raise DesignError(f"{where}.shaft", "missing (a radius needs its shaft)",
                                  "shaft = " + " | ".join(map(repr, SHAFTS)) + " or ratio")
        if self.kind == "mesh":
            if (self.gears is None or len(self.gears) != 2 or not all(isinstance(g, str) for g in self.gears)):
                raise DesignError(f"{where}.gears", f"{self.gears!r} is not a pair of gear names", "[\"PINION\", \"GEAR\"]")
            _positive(f"{where}.face_width", self.face_width, allow_none=True)
        if self.placed:
            return  # lengths of the placed shafts (geargen.model.shafts), checked where they are made
        if self.from_geometry:
            typed = [k for k in ("diameter", "length", "span", "load_position") if getattr(self, k) is not None]
            if typed:
                raise DesignError(f"{where}.{typed[0]}", "is the placed shaft's (from_geometry = true): "
                                  "one home for every length", "leave it out, or from_geometry = false")
            if self.kind == "shaft_torsion" and self.shaft is None and self.gear is None:
                raise DesignError(f"{where}.shaft", "missing: which placed shaft twists",
                                  " | ".join(map(repr, SHAFTS)) + ", or gear = NAME (the shaft carrying it)")
            if self.kind in ("shaft_bending", "shaft_support") and self.gear is None:
                raise DesignError(f"{where}.gear", "missing: the gear whose mesh force bends its shaft", "a gear name")
        elif self.kind == "shaft_torsion":
            _positive(f"{where}.diameter", self.diameter)
            _positive(f"{where}.length", self.length)
        if self.kind == "shaft_bending" and not self.from_geometry:
            _positive(f"{where}.diameter", self.diameter)
            _positive(f"{where}.load_position", self.load_position)
            if self.support == "cantilever":
                if self.span is not None:
                    raise DesignError(f"{where}.span", "a cantilever has no span", "load_position_* is the overhang")
            else:
                _positive(f"{where}.span", self.span)
                if not self.load_position < self.span:
                    raise DesignError(f"{where}.load_position", "must lie between the supports", "< span")
        if self.diameter is not None and not self.bore_diameter < self.diameter:
            raise DesignError(f"{where}.bore_diameter", "must be smaller than the diameter", "< diameter")


@dataclass(frozen=True)
class StiffnessSpec:
    """``[stiffness]``: materials, gear roles of the dual-pinion train, where to reduce, components."""

    elastic_modulus: float = STEEL_ELASTIC_MODULUS
    shear_modulus: float = 79.3e3  # MPa
    reduce_to: str = "output"
    train: str = "dual_pinion"
    input_gear: str = "input"
    cluster_large_gear: str = "cluster_large"
    cluster_small_gear: str = "cluster_small"
    output_gear: str = "output"
    components: tuple[ComponentSpec, ...] = ()
    mesh_stiffness: str = "eq1"

    def __post_init__(self):
        _positive("stiffness.elastic_modulus", self.elastic_modulus)
        if self.mesh_stiffness not in MESH_METHODS:
            raise DesignError("stiffness.mesh_stiffness", f"{self.mesh_stiffness!r} is not a valid choice",
                              ", ".join(map(repr, MESH_METHODS)))
        _positive("stiffness.shear_modulus", self.shear_modulus)
        if self.reduce_to not in LOCATIONS:
            raise DesignError("stiffness.reduce_to", f"{self.reduce_to!r} is not a valid choice", ", ".join(map(repr, LOCATIONS)))
        if self.train not in TRAINS:
            raise DesignError("stiffness.train", f"{self.train!r} is not a valid choice", ", ".join(map(repr, TRAINS)))
        if self.train == "custom" and self.reduce_to != "output":
            raise DesignError("stiffness.reduce_to", "a custom train is reduced to the output", "'output'")
        shafts = TRAIN_SHAFTS[self.train]
        if self.train == "split_pinion" and self.reduce_to not in shafts:
            raise DesignError("stiffness.reduce_to", f"{self.reduce_to!r} is not a shaft of a split pinion",
                              ", ".join(map(repr, shafts)))
        for c in self.components:
            where = f"stiffness.components.{c.name}"
            if self.train == "custom" and c.shaft is not None:
                raise DesignError(f"{where}.shaft", "a custom train has no named shafts",
                                  "ratio = speed of the shaft / speed of the output")
            if c.shaft is not None and c.shaft not in shafts:
                raise DesignError(f"{where}.shaft", f"{c.shaft!r} is not a shaft of a {self.train} train",
                                  ", ".join(map(repr, shafts)))

    @property
    def roles(self) -> dict[str, str]:
        """Gear role -> gear name in the design."""
        return {"input": self.input_gear, "cluster_large": self.cluster_large_gear,
                "cluster_small": self.cluster_small_gear, "output": self.output_gear}


STIFFNESS_FIELDS = [
    Field("reduce_to", "string", required=False, default="output", choices=LOCATIONS,
          help="where path stiffnesses are reported, as torsion of that shaft (a split pinion: input or output; a "
               "custom train: the output)"),
    Field("train", "string", required=False, default=None, choices=TRAINS,
          help="dual_pinion (the default): each path's two meshes come from the gears; split_pinion (the default, "
               "and the only train, of a [layout] kind = 'split_pinion'): the pinions and output that [layout] "
               "names, the pinions' shaft 'input'; custom: list every component (meshes too) with its ratio"),
    Field("mesh_stiffness", "string", required=False, default="eq1", choices=MESH_METHODS,
          help="every tooth mesh's stiffness: eq1, the paper's E w / 11; iso6336, ISO 6336-1:2019 method B, "
               "c_gamma_alpha w from the gears' teeth, shifts, module, helix, basic rack (dedendum) and E / E_st "
               "(solid blanks, no load correction); w the narrower face either way"),
    Field("input_gear", "string", required=False, default="input",
          help="dual-pinion train: the gear table of the input (gear 1)"),
    Field("cluster_large_gear", "string", required=False, default="cluster_large",
          help="dual-pinion train: the gear table of a cluster's large gear (gear 2)"),
    Field("cluster_small_gear", "string", required=False, default="cluster_small",
          help="dual-pinion train: the gear table of a cluster's small gear (gear 3)"),
    Field("output_gear", "string", required=False, default="output",
          help="dual-pinion train: the gear table of the output (gear 4)"),
]
MODULI = [Quantity("elastic_modulus", ("stress",), minimum=0.0,
                    help="Young's modulus of gears and shafts (Eq. 1: k_mesh = E w / 11)"),
           Quantity("shear_modulus", ("stress",), minimum=0.0, help="shear modulus of the shafts (torsion)")]

COMPONENT_FIELDS = [
    Field("kind", "string", choices=COMPONENT_KINDS,
          help="torsion: a torsional stiffness; linear: a linear stiffness on a line of action; shaft_torsion, "
               "shaft_bending: a round shaft; shaft_support: a gear on its placed shaft and bearings "
               "(from_geometry); mesh: a tooth mesh (Eq. 1)"),
    Field("scope", "string", required=False, default="each_path", choices=SCOPES,
          help="in each path, in path 1 or path 2 only, or common: in series with the whole drive"),
    Field("count", "integer", required=False, default=1, minimum=1, maximum=1000,
          help="identical components acting in parallel"),
    Field("shaft", "string", required=False, default=None, choices=SHAFTS,
          help="dual-pinion train: the shaft it sits on, input, cluster or output; split pinion: input (the "
               "pinions') or output (or give gear)"),
    Field("ratio", "number", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="custom train only: speed of its shaft over the output's (the other trains take it from the teeth)"),
    Field("gear", "string", required=False, default=None,
          help="linear, shaft_bending, shaft_support: the gear on whose line of action it acts (at its base radius); "
               "torsion, shaft_torsion: the gear on its shaft (with from_geometry: the placed shaft that twists); "
               "its shaft's speed comes from the teeth"),
    Field("gears", "list", required=False, default=None,
          help="mesh: the two gears, [\"PINION\", \"GEAR\"]; it acts at the second"),
    Field("face_width", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="mesh: face width in contact (default: the narrower gear's)"),
    Field("radius", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="linear, shaft_bending: the radius it acts at, instead of gear (needs shaft or ratio)"),
    Field("diameter", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="shaft_torsion, shaft_bending: shaft diameter"),
    Field("bore_diameter", "length", required=False, default=0.0, minimum=0.0,
          help="shaft_torsion, shaft_bending: bore of a hollow shaft (0: solid)"),
    Field("length", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="shaft_torsion: the twisted length"),
    Field("span", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="shaft_bending: distance between the supports (not for a cantilever)"),
    Field("load_position", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="shaft_bending: the gear's distance from one support (a cantilever's overhang)"),
    Field("support", "string", required=False, default="simple", choices=SUPPORTS,
          help="shaft_bending: simply supported, fixed at both ends, or a cantilever"),
    Field("from_geometry", "bool", required=False, default=False,
          help="shaft_torsion, shaft_bending, shaft_support: diameter, length, span and load position are the "
               "placed shaft's (geargen.model.shafts), never typed here"),
]
COMPONENT_QUANTITIES = [Quantity("stiffness", ("linear_stiffness", "torsional_stiffness"), minimum=0.0,
                                  help="torsion: a torsional stiffness; linear: a linear stiffness"),
                         Quantity("elastic_modulus", ("stress",), minimum=0.0,
                                  help="this component's Young's modulus (default: [stiffness] elastic_modulus_*)"),
                         Quantity("shear_modulus", ("stress",), minimum=0.0,
                                  help="this component's shear modulus (default: [stiffness] shear_modulus_*)")]


def component_from_table(name: str, data: Mapping[str, Any]) -> ComponentSpec:
    where = f"stiffness.components.{name}"
    v = read_quantity_section(data, COMPONENT_FIELDS, COMPONENT_QUANTITIES, where)
    kind = v["kind"]
    used = KIND_KEYS[kind] | {"kind", "scope", "count", "shaft", "ratio"}
    given = {f.name for f in COMPONENT_FIELDS if any(k in data for k in f.keys())}
    given |= {q.name for q in COMPONENT_QUANTITIES if v[q.name] is not None}
    extra = sorted(given - used)
    if extra:
        raise DesignError(f"{where}.{extra[0]}", f"not used by kind {kind!r}", ", ".join(sorted(used)))
    stiffness = v["stiffness"]
    if stiffness is not None:
        want = "torsional_stiffness" if kind == "torsion" else "linear_stiffness"
        if stiffness[1] != want:
            raise DesignError(f"{where}.stiffness", f"kind {kind!r} needs a {want.replace('_', ' ')}",
                              ", ".join(f"stiffness_{s}" for s in QUANTITY_SUFFIXES[want]))
    gears = tuple(v["gears"]) if v["gears"] is not None else None
    return _user_keys(where, data, lambda: ComponentSpec(name=name, kind=kind, scope=v["scope"], count=v["count"], shaft=v["shaft"], ratio=v["ratio"],
                         gear=v["gear"], gears=gears, face_width=v["face_width"], radius=v["radius"], stiffness=value_of(stiffness), diameter=v["diameter"],
                         bore_diameter=v["bore_diameter"], length=v["length"], span=v["span"],
                         load_position=v["load_position"], support=v["support"],
                         elastic_modulus=value_of(v["elastic_modulus"]), shear_modulus=value_of(v["shear_modulus"]),
                         from_geometry=v["from_geometry"]))


def stiffness_spec_from_table(data: Mapping[str, Any], required_train: str | None = None) -> StiffnessSpec:
    """``[stiffness]`` read; ``required_train``: the train the design's drive requires (a split
    pinion's own train is the only one that describes it: a custom train would type the ratios its
    teeth give), or None (dual_pinion by default, or custom). A train that belongs to a drive needs
    that drive."""
    v = read_quantity_section(data, STIFFNESS_FIELDS, MODULI, "stiffness", tables=("components",))
    if v["train"] is None:
        v["train"] = required_train or "dual_pinion"
    elif required_train is not None and v["train"] != required_train:
        raise DesignError("stiffness.train", f"{v['train']!r} does not describe this drive (its train is "
                          f"{required_train!r})", f"{required_train!r} (or leave train out)")
    elif required_train is None and v["train"] in DRIVE_TRAINS:
        owner = next(k.LAYOUT_KIND for k in KEYS.values() if k.STIFFNESS_TRAIN == v["train"])
        raise DesignError("stiffness.train", f"{v['train']!r} needs [layout] kind = {owner!r} (its gears are that "
                          "drive's)", "'dual_pinion', 'custom'")
    comps = data.get("components", {})
    if not isinstance(comps, Mapping):
        raise DesignError("stiffness.components", "expected tables [stiffness.components.NAME]")
    components = []
    for cname, table in comps.items():
        check_name(f"stiffness.components.{cname}", cname)  # it names the component in reports and plots
        if not isinstance(table, Mapping):
            raise DesignError(f"stiffness.components.{cname}", "expected a table")
        components.append(component_from_table(cname, table))
    kwargs = {k: v[k] for k in ("reduce_to", "train", "input_gear", "cluster_large_gear", "cluster_small_gear", "output_gear",
                                "mesh_stiffness")}
    for q in ("elastic_modulus", "shear_modulus"):
        if v[q] is not None:
            kwargs[q] = v[q][0]
    return _user_keys("stiffness", data, lambda: StiffnessSpec(components=tuple(components), **kwargs))


def check_stiffness_gears(spec: StiffnessSpec, gears: Mapping[str, Any]) -> None:
    """Every gear ``[stiffness]`` names (train roles, components) is a gear of the design."""
    def named(key: str, name) -> None:
        if name not in gears:
            raise DesignError(key, f"no gear named {name!r} in the design", ", ".join(gears) or "a [gears.NAME] table")

    if spec.train == "dual_pinion":
        for role, name in spec.roles.items():
            named(f"stiffness.{role}_gear", name)
    for c in spec.components:
        where = f"stiffness.components.{c.name}"
        if c.gear is not None:
            named(f"{where}.gear", c.gear)
        for g in c.gears or ():
            named(f"{where}.gears", g)


# ----------------------------------------------------------------------------------------------
# [preload]

LOOP_BUDGETS = ("mean", "sum", "rss")


@dataclass(frozen=True)
class PreloadSpec:
    """``[preload]``: the load spectrum, the preload setting, loop errors (internal units).

    ``max_output_torque`` (N·mm) is the largest drive torque at the output in either direction.
    ``preload`` (N·mm, optional) is the loop preload: the output torque each path carries at zero
    drive torque; without it the springs' installed force sets it, else the paper's rule.
    ``line_of_action_angle`` (rad) is the angle between the preload motion and each mesh-1 line
    of action (0: the optimal configuration of Fig. 9). ``loop_error_carriage_travel`` (mm,
    peak-to-peak travel of the preload carriage) or ``loop_error_rotation`` (rad, peak-to-peak
    loop error as output rotation) is used when the synthesis error budget is not available.
    ``preload_spring_stiffness`` adds a preload-spring stiffness not described by
    [springs]/[flexures]/[beam_pinion]: linear at the carriage (N/mm) or torsional at the output
    (N·mm/rad). ``path_backlash`` (rad at the output) is drawn in the preload diagram.
    """

    max_output_torque: float
    preload: float | None = None
    line_of_action_angle: float = 0.0
    loop_error_carriage_travel: float | None = None
    loop_error_rotation: float | None = None
    loop_error_budget: str = "mean"
    preload_spring_linear: float | None = None
    preload_spring_torsional: float | None = None
    path_backlash: float | None = None

    def __post_init__(self):
        _positive("preload.max_output_torque", self.max_output_torque)
        if self.preload is not None and not (math.isfinite(self.preload) and self.preload >= 0):
            raise DesignError("preload.preload", f"{self.preload!r} is out of range", ">= 0")
        if not abs(self.line_of_action_angle) < math.radians(60):
            raise DesignError("preload.line_of_action_angle", f"{self.line_of_action_angle!r} rad is out of range",
                              "(-60, 60) deg")
        if self.loop_error_budget not in LOOP_BUDGETS:
            raise DesignError("preload.loop_error_budget", f"{self.loop_error_budget!r} is not a valid choice",
                              ", ".join(map(repr, LOOP_BUDGETS)))
        if self.loop_error_carriage_travel is not None and self.loop_error_rotation is not None:
            raise DesignError("preload.loop_error_rotation", "give at most one loop error",
                              "loop_error_carriage_travel_* or loop_error_rotation_*")


PRELOAD_FIELDS = [
    Field("line_of_action_angle", "angle", required=False, default=0.0, units=("deg", "rad"),
          minimum=-math.radians(60), maximum=math.radians(60), exclusive_minimum=True, exclusive_maximum=True,
          help="angle between the preload motion and each mesh-1 line of action (0: the optimal configuration of "
               "Fig. 9)"),
    Field("loop_error_carriage_travel", "length", required=False, default=None, minimum=0.0,
          help="peak-to-peak preload-carriage travel from loop errors, used without a synthesis error budget"),
    Field("loop_error_rotation", "angle", required=False, default=None, minimum=0.0,
          help="peak-to-peak loop error as output rotation, used without a synthesis error budget"),
    Field("loop_error_budget", "string", required=False, default="mean", choices=LOOP_BUDGETS,
          help="which synthesis budget the headline uses: mean ((sum + rss) / 2), sum or rss"),
    Field("path_backlash", "angle", required=False, default=None, minimum=0.0,
          help="flank clearance of one path as output rotation, drawn in the preload diagram"),
]
PRELOAD_QUANTITIES = [
    Quantity("max_output_torque", ("torque",), required=True, minimum=0.0,
             help="largest drive torque at the output, either direction"),
    Quantity("preload", ("torque",), minimum=0.0, exclusive_minimum=False,
             help="output torque each path carries at zero drive torque (default: the springs' installed force, "
                  "else the paper's rule)"),
    Quantity("preload_spring_stiffness", ("linear_stiffness", "torsional_stiffness"), minimum=0.0,
             help="a preload spring not described by [springs], [flexures] or [beam_pinion]: linear at the carriage "
                  "or torsional at the output"),
]


def preload_spec_from_table(data: Mapping[str, Any]) -> PreloadSpec:
    v = read_quantity_section(data, PRELOAD_FIELDS, PRELOAD_QUANTITIES, "preload")
    spring = v["preload_spring_stiffness"]
    return _user_keys("preload", data, lambda: PreloadSpec(max_output_torque=v["max_output_torque"][0], preload=value_of(v["preload"]),
                       line_of_action_angle=v["line_of_action_angle"],
                       loop_error_carriage_travel=v["loop_error_carriage_travel"],
                       loop_error_rotation=v["loop_error_rotation"], loop_error_budget=v["loop_error_budget"],
                       preload_spring_linear=spring[0] if spring and spring[1] == "linear_stiffness" else None,
                       preload_spring_torsional=spring[0] if spring and spring[1] == "torsional_stiffness" else None,
                       path_backlash=v["path_backlash"]))


# ----------------------------------------------------------------------------------------------
# [flexures]

@dataclass(frozen=True)
class FlexureSpec:
    """``[flexures]``: ``count`` identical parallel blades guiding the preload carriage (mm, MPa).

    Each blade is clamped at both ends (fixed-guided), ``length`` free between the clamps,
    ``thickness`` in the direction of motion, ``width`` across it. ``travel`` is the largest
    deflection from the blades' unstressed position the design must allow (stress check).
    ``neutral_offset`` is the distance from the carriage's operating position to the blades'
    unstressed position, measured in the preload direction: the blades then push the carriage
    with ``k * neutral_offset`` (adds to the springs' preload force). ``target_stiffness``
    (optional, N/mm, all blades) asks the design helper for a thickness and length.
    """

    thickness: float
    length: float
    width: float
    allowable_stress: float
    travel: float
    count: int = 3
    elastic_modulus: float = 207e3
    poisson_ratio: float = 0.29
    neutral_offset: float = 0.0
    target_stiffness: float | None = None

    def __post_init__(self):
        for name in ("thickness", "length", "width", "allowable_stress", "travel", "elastic_modulus"):
            _positive(f"flexures.{name}", getattr(self, name))
        if not isinstance(self.count, int) or self.count < 1:
            raise DesignError("flexures.count", f"{self.count!r} is out of range", ">= 1")
        if not 0 <= self.poisson_ratio < 0.5:
            raise DesignError("flexures.poisson_ratio", f"{self.poisson_ratio!r} is out of range", "[0, 0.5)")
        if not self.thickness < self.width:
            raise DesignError("flexures.thickness", "a blade is thinner than it is wide", "< width")
        if not math.isfinite(self.neutral_offset):
            raise DesignError("flexures.neutral_offset", "must be finite")
        _positive("flexures.target_stiffness", self.target_stiffness, allow_none=True)

    # closed forms of the fixed-guided blade (geargen.core.flexures has the full model)
    @property
    def stress_at_travel(self) -> float:
        """Bending stress at the clamps at ``travel`` from unstressed, MPa: ``3 E t delta / L^2``."""
        return 3.0 * self.elastic_modulus * self.thickness * self.travel / self.length ** 2

    @property
    def travel_limit(self) -> float:
        """Deflection at which the clamp stress reaches the allowable, mm."""
        return self.allowable_stress * self.length ** 2 / (3.0 * self.elastic_modulus * self.thickness)


FLEXURE_FIELDS = [
    Field("count", "integer", required=False, default=3, minimum=1, maximum=100,
          help="identical parallel blades guiding the preload carriage"),
    Field("thickness", "length", minimum=0.0, exclusive_minimum=True, help="blade thickness, along the motion"),
    Field("length", "length", minimum=0.0, exclusive_minimum=True,
          help="free blade length between the clamps (clamped at both ends)"),
    Field("width", "length", minimum=0.0, exclusive_minimum=True, help="blade width, across the motion"),
    Field("travel", "length", minimum=0.0, exclusive_minimum=True,
          help="largest deflection from unstressed the blades must take (stress 3 E t travel / L^2 within the "
               "allowable)"),
    Field("neutral_offset", "length", required=False, default=0.0,
          help="operating position to the blades' unstressed position, along the preload (the blades then add k x "
               "offset)"),
    Field("poisson_ratio", "number", required=False, default=0.29, minimum=0.0, maximum=0.5, exclusive_maximum=True,
          help="Poisson's ratio of the blade material"),
]
FLEXURE_QUANTITIES = [Quantity("elastic_modulus", ("stress",), minimum=0.0, help="Young's modulus of the blades"),
                       Quantity("allowable_stress", ("stress",), required=True, minimum=0.0,
                                help="allowable bending stress at the clamps"),
                       Quantity("target_stiffness", ("linear_stiffness",), minimum=0.0,
                                help="asks the design helper for blades of this stiffness (all blades, along the "
                                     "motion)")]


def flexure_spec_from_table(data: Mapping[str, Any], length_unit: str | None = None) -> FlexureSpec:
    """``[flexures]`` read and checked: blades thinner than wide, within their allowable stress at
    the travel, operating within the travel. Lengths in messages are in ``length_unit`` (default:
    the unit the file gave the travel in)."""
    v = read_quantity_section(data, FLEXURE_FIELDS, FLEXURE_QUANTITIES, "flexures")
    kwargs = dict(count=v["count"], thickness=v["thickness"], length=v["length"], width=v["width"],
                  travel=v["travel"], neutral_offset=v["neutral_offset"], poisson_ratio=v["poisson_ratio"],
                  allowable_stress=v["allowable_stress"][0], target_stiffness=value_of(v["target_stiffness"]))
    if v["elastic_modulus"] is not None:
        kwargs["elastic_modulus"] = v["elastic_modulus"][0]
    unit = length_unit or v["_units"]["travel"]
    if not v["thickness"] < v["width"]:
        raise DesignError(_key(v, "flexures", "thickness"), f"{_length_text(v['thickness'], unit)} is not thinner "
                          "than the blade is wide", f"< width = {_length_text(v['width'], unit)}")
    spec = _user_keys("flexures", data, lambda: FlexureSpec(**kwargs))
    if spec.stress_at_travel > spec.allowable_stress:
        raise DesignError(_key(v, "flexures", "travel"),
                          f"{_length_text(spec.travel, unit)} bends the blades to {spec.stress_at_travel:.4g} MPa at "
                          f"the clamps, past the allowable {spec.allowable_stress:.4g} MPa",
                          f"(0, {_length_text(spec.travel_limit, unit, 'down')}] for these blades (3 E t travel / L^2 "
                          "<= allowable_stress)")
    if abs(spec.neutral_offset) > spec.travel:
        raise DesignError(_key(v, "flexures", "neutral_offset"),
                          f"{_length_text(spec.neutral_offset, unit)} puts the operating position outside the travel",
                          f"[-{_length_text(spec.travel, unit)}, {_length_text(spec.travel, unit)}] (within travel)")
    return spec


# ----------------------------------------------------------------------------------------------
# [springs]

#: per end type: (inactive coils added to the active ones, wire diameters added to the solid height)
SPRING_ENDS: dict[str, tuple[float, float]] = {
    "plain": (0.0, 1.0),           # Nt = Na,     Ls = d (Nt + 1)
    "plain_ground": (1.0, 0.0),    # Nt = Na + 1, Ls = d Nt
    "squared": (2.0, 1.0),         # Nt = Na + 2, Ls = d (Nt + 1)
    "squared_ground": (2.0, 0.0),  # Nt = Na + 2, Ls = d Nt
}
END_TYPES = tuple(SPRING_ENDS)


@dataclass(frozen=True)
class SpringSpec:
    """``[springs]``: ``count`` identical helical compression springs pushing the carriage (mm, MPa).

    ``installed_length`` (optional) is the spring length at the carriage's operating position;
    with it the springs set the preload force.
    """

    wire_diameter: float
    mean_coil_diameter: float
    active_coils: float
    free_length: float
    allowable_shear_stress: float
    count: int = 2
    end_type: str = "squared_ground"
    installed_length: float | None = None
    shear_modulus: float = 79.3e3

    def __post_init__(self):
        for name in ("wire_diameter", "mean_coil_diameter", "active_coils", "free_length",
                     "allowable_shear_stress", "shear_modulus"):
            _positive(f"springs.{name}", getattr(self, name))
        if not isinstance(self.count, int) or self.count < 1:
            raise DesignError("springs.count", f"{self.count!r} is out of range", ">= 1")
        if self.end_type not in END_TYPES:
            raise DesignError("springs.end_type", f"{self.end_type!r} is not a valid choice", ", ".join(map(repr, END_TYPES)))
        if not self.mean_coil_diameter > 2 * self.wire_diameter:
            raise DesignError("springs.mean_coil_diameter", "spring index D/d must exceed 2", "> 2 * wire_diameter")
        if self.installed_length is not None and not 0 < self.installed_length <= self.free_length:
            raise DesignError("springs.installed_length", f"{self.installed_length!r} mm is out of range",
                              f"(0, free_length = {self.free_length:.6g} mm]")

    # closed forms of the helical compression spring (geargen.core.flexures has the full model)
    @property
    def index(self) -> float:
        """Spring index C = D / d."""
        return self.mean_coil_diameter / self.wire_diameter

    @property
    def solid_height(self) -> float:
        """Length compressed solid, mm: d (Na + inactive coils + ends not ground)."""
        extra, add = SPRING_ENDS[self.end_type]
        return self.wire_diameter * (self.active_coils + extra + add)

    @property
    def rate(self) -> float:
        """N/mm of one spring: ``G d^4 / (8 D^3 Na)``."""
        return self.shear_modulus * self.wire_diameter ** 4 / (8.0 * self.mean_coil_diameter ** 3 * self.active_coils)

    def shear_stress(self, force: float) -> float:
        """Wire shear stress at ``force`` N, MPa: ``K 8 F D / (pi d^3)``, K the Wahl factor."""
        c = self.index
        wahl = (4.0 * c - 1.0) / (4.0 * c - 4.0) + 0.615 / c
        return wahl * 8.0 * force * self.mean_coil_diameter / (math.pi * self.wire_diameter ** 3)

    @property
    def shortest_installed_length(self) -> float:
        """The shortest installed length within the allowable shear stress (not below solid), mm."""
        allowed_force = self.allowable_shear_stress / self.shear_stress(1.0)
        return max(self.free_length - allowed_force / self.rate, self.solid_height)


SPRING_FIELDS = [
    Field("count", "integer", required=False, default=2, minimum=1, maximum=100,
          help="identical helical compression springs pushing the preload carriage"),
    Field("wire_diameter", "length", minimum=0.0, exclusive_minimum=True, help="wire diameter d"),
    Field("mean_coil_diameter", "length", minimum=0.0, exclusive_minimum=True,
          help="mean coil diameter D (spring index D/d above 2)"),
    Field("active_coils", "number", minimum=0.5, maximum=500.0, help="active coils Na (rate G d^4 / (8 D^3 Na))"),
    Field("end_type", "string", required=False, default="squared_ground", choices=END_TYPES,
          help="how the ends are finished: sets the inactive coils and the solid height"),
    Field("free_length", "length", minimum=0.0, exclusive_minimum=True, help="unloaded length"),
    Field("installed_length", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="length at the carriage's operating position: sets the preload force"),
]
SPRING_QUANTITIES = [Quantity("shear_modulus", ("stress",), minimum=0.0, help="shear modulus of the wire"),
                      Quantity("allowable_shear_stress", ("stress",), required=True, minimum=0.0,
                               help="allowable wire shear stress (Wahl-corrected) at the installed length")]


def spring_spec_from_table(data: Mapping[str, Any], length_unit: str | None = None) -> SpringSpec:
    """``[springs]`` read and checked: a coil wider than twice its wire, a free length above the
    solid height, an installed length above it and within the allowable shear stress. Lengths in
    messages are in ``length_unit`` (default: the unit the file gave the free length in)."""
    v = read_quantity_section(data, SPRING_FIELDS, SPRING_QUANTITIES, "springs")
    kwargs = dict(count=v["count"], wire_diameter=v["wire_diameter"], mean_coil_diameter=v["mean_coil_diameter"],
                  active_coils=v["active_coils"], end_type=v["end_type"], free_length=v["free_length"],
                  installed_length=v["installed_length"], allowable_shear_stress=v["allowable_shear_stress"][0])
    if v["shear_modulus"] is not None:
        kwargs["shear_modulus"] = v["shear_modulus"][0]
    unit = length_unit or v["_units"]["free_length"]
    d, mean = v["wire_diameter"], v["mean_coil_diameter"]
    if not mean > 2 * d:
        raise DesignError(_key(v, "springs", "mean_coil_diameter"),
                          f"{_length_text(mean, unit)} is not more than twice the wire ({_length_text(d, unit)}): "
                          f"spring index {mean / d:.3g}, the coils would close on the axis",
                          f"> {_length_text(2 * d, unit)} (spring index D/d > 2)")
    installed = kwargs.pop("installed_length")
    spec = _user_keys("springs", data, lambda: SpringSpec(**kwargs))
    solid = spec.solid_height
    if not spec.free_length > solid:
        raise DesignError(_key(v, "springs", "free_length"),
                          f"{_length_text(spec.free_length, unit)} is not above the solid height "
                          f"{_length_text(solid, unit)}", f"> {_length_text(solid, unit)}")
    if installed is not None:
        key = _key(v, "springs", "installed_length")
        shortest = spec.shortest_installed_length
        allowed = f"({_length_text(solid, unit)}, {_length_text(spec.free_length, unit)}]" if shortest <= solid else \
            f"[{_length_text(shortest, unit, 'up')}, {_length_text(spec.free_length, unit)}]"
        if installed <= solid:
            raise DesignError(key, f"{_length_text(installed, unit)} is at or below the solid height "
                              f"{_length_text(solid, unit)}: the coils would have to pass through each other", allowed)
        if installed > spec.free_length:
            raise DesignError(key, f"{_length_text(installed, unit)} is longer than the free length "
                              f"{_length_text(spec.free_length, unit)}: a compression spring cannot pull", allowed)
        stress = spec.shear_stress(spec.rate * (spec.free_length - installed))
        if stress > spec.allowable_shear_stress:
            raise DesignError(key, f"{_length_text(installed, unit)} compresses the wire to {stress:.4g} MPa shear, past "
                              f"the allowable {spec.allowable_shear_stress:.4g} MPa", allowed)
        spec = SpringSpec(**kwargs, installed_length=installed)
    return spec


# ----------------------------------------------------------------------------------------------
# [beam_pinion]

@dataclass(frozen=True)
class BeamPinionSpec:
    """``[beam_pinion]``: a long pinion, simply supported, whose bending is the preload spring.

    ``gear`` names the pinion; the beam section is ``diameter`` (default: the pinion's root
    diameter). ``span`` is the bearing span and ``mesh_position`` the distance from one bearing
    to the middle of the mesh (default: mid-span, where the slope is zero). Without ``span``,
    ``target_stiffness`` (N/mm at the mesh) sets the span.
    """

    gear: str
    span: float | None = None
    mesh_position: float | None = None
    target_stiffness: float | None = None
    diameter: float | None = None
    elastic_modulus: float = 207e3
    allowable_stress: float | None = None

    def __post_init__(self):
        if self.span is None and self.target_stiffness is None:
            raise DesignError("beam_pinion.span", "missing", "span_* or target_stiffness_*")
        if self.span is not None and self.target_stiffness is not None:
            raise DesignError("beam_pinion.target_stiffness", "give span or target stiffness, not both",
                              "one of span_*, target_stiffness_*")
        _positive("beam_pinion.span", self.span, allow_none=True)
        _positive("beam_pinion.target_stiffness", self.target_stiffness, allow_none=True)
        _positive("beam_pinion.diameter", self.diameter, allow_none=True)
        _positive("beam_pinion.elastic_modulus", self.elastic_modulus)
        _positive("beam_pinion.allowable_stress", self.allowable_stress, allow_none=True)
        if self.mesh_position is not None:
            _positive("beam_pinion.mesh_position", self.mesh_position)
            if self.span is not None and not self.mesh_position < self.span:
                raise DesignError("beam_pinion.mesh_position", "must lie between the bearings", "< span")


BEAM_FIELDS = [
    Field("gear", "string", help="the long pinion whose bending is the preload spring"),
    Field("span", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="bearing span of the pinion (or give target_stiffness)"),
    Field("mesh_position", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="distance from one bearing to the middle of the mesh (default: mid-span, zero slope)"),
    Field("diameter", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="diameter of the bending section (default: the pinion's root diameter)"),
]
BEAM_QUANTITIES = [Quantity("target_stiffness", ("linear_stiffness",), minimum=0.0,
                             help="stiffness at the mesh that sets the span (instead of span)"),
                    Quantity("elastic_modulus", ("stress",), minimum=0.0, help="Young's modulus of the pinion"),
                    Quantity("allowable_stress", ("stress",), minimum=0.0,
                             help="allowable bending stress of the pinion under the preload (a warning past it)")]


def beam_pinion_spec_from_table(data: Mapping[str, Any], gears: Mapping[str, Any] | None = None) -> BeamPinionSpec:
    """``[beam_pinion]`` read and checked; with ``gears`` (the design's), its gear must be one of them."""
    v = read_quantity_section(data, BEAM_FIELDS, BEAM_QUANTITIES, "beam_pinion")
    kwargs = dict(gear=v["gear"], span=v["span"], mesh_position=v["mesh_position"], diameter=v["diameter"],
                  target_stiffness=value_of(v["target_stiffness"]), allowable_stress=value_of(v["allowable_stress"]))
    if v["elastic_modulus"] is not None:
        kwargs["elastic_modulus"] = v["elastic_modulus"][0]
    if gears is not None and v["gear"] not in gears:
        raise DesignError("beam_pinion.gear", f"no gear named {v['gear']!r} in the design", ", ".join(gears))
    return _user_keys("beam_pinion", data, lambda: BeamPinionSpec(**kwargs))


# ----------------------------------------------------------------------------------------------
# [engagement]

@dataclass(frozen=True)
class EngagementSpec:
    """``[engagement]``: helical dual pinions sliding axially into mesh (mm).

    ``gear`` is the helical gear at whose mesh the pinions slide (helix angle, pitch radius).
    ``backlash`` is the circumferential clearance at its reference circle that the sliding
    pinions need while entering. ``preload_windup`` is the circumferential loop deflection at that
    circle when preloaded (default: from the drive model). ``engagement_length`` is the axial
    overlap when engaged (default: the gear's face width); ``clearance`` the axial gap when
    retracted.
    """

    gear: str
    backlash: float
    preload_windup: float | None = None
    engagement_length: float | None = None
    clearance: float = 0.0

    def __post_init__(self):
        if not (math.isfinite(self.backlash) and self.backlash >= 0):
            raise DesignError("engagement.backlash", f"{self.backlash!r} is out of range", ">= 0")
        if self.preload_windup is not None and not (math.isfinite(self.preload_windup) and self.preload_windup >= 0):
            raise DesignError("engagement.preload_windup", f"{self.preload_windup!r} is out of range", ">= 0")
        _positive("engagement.engagement_length", self.engagement_length, allow_none=True)
        if not (math.isfinite(self.clearance) and self.clearance >= 0):
            raise DesignError("engagement.clearance", f"{self.clearance!r} is out of range", ">= 0")


ENGAGEMENT_FIELDS = [
    Field("gear", "string", help="the helical gear the pinions slide into mesh with"),
    Field("backlash", "length", minimum=0.0,
          help="circumferential clearance at its reference circle that the sliding pinions need to enter"),
    Field("preload_windup", "length", required=False, default=None, minimum=0.0,
          help="circumferential loop deflection at that circle when preloaded (default: from the drive model)"),
    Field("engagement_length", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="axial overlap when engaged (default: the gear's face width)"),
    Field("clearance", "length", required=False, default=0.0, minimum=0.0,
          help="axial gap to the gear when retracted"),
]


#: per cluster gear role of the dual-pinion train: its mate's role, the cluster's other gear's
#: role and that gear's mate's role (both gears of a cluster slide together)
_CLUSTER_MESHES = {"cluster_small": ("output", "cluster_large", "input"),
                   "cluster_large": ("input", "cluster_small", "output")}


def engagement_meshes(gear: str, stiffness: StiffnessSpec | None = None) -> tuple[tuple[str, str], tuple[str, str]]:
    """The two meshes of the dual pinion that carries ``gear``, as (sliding gear, mate) names.

    The first is the mesh the pinions slide into (``gear`` against its mate), the second the
    cluster's other mesh, which stays engaged while the cluster slides (its gear slides too, and
    its helix turns the cluster). Gear roles from ``stiffness`` (``[stiffness]``, default roles
    when None). The gear must be one of the cluster's: sliding the input or the output moves both
    paths alike and opens nothing between them.
    """
    stiffness = stiffness if stiffness is not None else StiffnessSpec()
    if stiffness.train != "dual_pinion":
        why = ("a custom train does not say which gears slide with the pinion" if stiffness.train == "custom"
               else "a split pinion has no sliding clusters")
        raise DesignError("engagement.gear", why, "a dual-pinion train ([stiffness] train = 'dual_pinion')")
    roles = stiffness.roles
    role = next((r for r in _CLUSTER_MESHES if roles[r] == gear), None)
    if role is None:
        raise DesignError("engagement.gear", f"{gear!r} is not a gear of the sliding dual pinions (sliding the input "
                          "or the output moves both paths alike)", " or ".join(repr(roles[r]) for r in _CLUSTER_MESHES))
    mate, other, other_mate = _CLUSTER_MESHES[role]
    return (gear, roles[mate]), (roles[other], roles[other_mate])


def _turn_rate(gear) -> float:
    """rad/mm a helical gear slid along its axis turns to keep its mesh with a held mate (signed by
    hand); the closed form of ``geargen.core.flexures.SlidingMesh.turn_rate``."""
    return (1.0 if gear.hand == "right" else -1.0) * math.tan(gear.helix_angle) / gear.reference_radius


def engagement_spec_from_table(data: Mapping[str, Any], gears: Mapping[str, Any] | None = None,
                               length_unit: str | None = None,
                               stiffness: StiffnessSpec | None = None) -> EngagementSpec:
    """``[engagement]`` read; with ``gears`` (the design's) also checked against the sliding cluster.

    The sliding pinions are turned apart as one leads the other: sliding a cluster turns it
    through the helix of its other mesh (the large gear along the long input pinion) against the
    helix of the pinion in the bull gear, so the leader's pinion turns ``|kappa_o - kappa_e|``
    per mm of lead against the trailer's (``kappa = s tan(beta) / r`` of each gear; derivation in
    :func:`geargen.core.flexures.helical_engagement`). The lead ``(backlash + preload_windup) /
    (|kappa_o - kappa_e| r_e)`` must be closed by the trailer while it is in mesh, so it may not
    exceed the engagement length (travel stops that do not allow the lead are refused). Without
    ``preload_windup`` (then it comes from the stiffness model) the check uses the backlash
    alone, a lower bound of the lead. The engagement length cannot exceed the gear's face.
    Gear roles from ``stiffness`` (``[stiffness]``; default roles when None). Lengths in messages
    are in ``length_unit`` (default: the unit of ``backlash_*``).
    """
    v = read_table(data, ENGAGEMENT_FIELDS, "engagement")
    spec = EngagementSpec(gear=v["gear"], backlash=v["backlash"], preload_windup=v["preload_windup"],
                          engagement_length=v["engagement_length"], clearance=v["clearance"])
    if gears is None:
        return spec
    unit = length_unit or v["_units"]["backlash"]
    gear = gears.get(spec.gear)
    if gear is None:
        raise DesignError("engagement.gear", f"no gear named {spec.gear!r} in the design", ", ".join(gears))
    face = gear.face_width
    length = face
    if spec.engagement_length is not None:
        length = spec.engagement_length
        if length > face * (1 + 1e-12):
            raise DesignError(_key(v, "engagement", "engagement_length"),
                              f"{_length_text(length, unit)} is more than the face width of gears.{spec.gear} "
                              f"({_length_text(face, unit)}): the pinion cannot overlap the mesh by more",
                              f"(0, {_length_text(face, unit)}]")
    (_, mate), (other, _) = engagement_meshes(spec.gear, stiffness)
    if other not in gears or mate not in gears:
        return spec  # a role that names no gear: reported by check_stiffness_gears
    kappa_e, kappa_o = _turn_rate(gear), _turn_rate(gears[other])
    if not abs(kappa_o - kappa_e) > 1e-12 * (abs(kappa_e) + abs(kappa_o)) or kappa_e == kappa_o:
        why = ("neither gear of the cluster is helical" if kappa_e == kappa_o == 0 else
               f"gears.{spec.gear} and gears.{other} have one hand and one helix lead: the cluster slides like a screw")
        raise DesignError("engagement.gear", f"sliding the cluster cannot turn gears.{spec.gear} against gears.{mate} "
                          f"to open backlash: {why}",
                          "a cluster whose gears turn by different rates as it slides (tan(helix) / reference radius, "
                          "signed by hand)")
    per_lead = abs(kappa_o - kappa_e) * gear.reference_radius  # opened at the pinion's reference circle per mm
    windup = spec.preload_windup or 0.0
    lead = (spec.backlash + windup) / per_lead
    if lead > length * (1 + 1e-12):
        capacity = length * per_lead  # what the whole engagement length turns the pinions apart
        name = "backlash" if windup < capacity else "preload_windup"
        most = capacity - (windup if name == "backlash" else spec.backlash)
        raise DesignError(_key(v, "engagement", name),
                          f"needs a lead of {_length_text(lead, unit)} between the sliding pinions ((backlash + "
                          f"preload windup) / {per_lead:.6g}, the opening at the reference circle of gears.{spec.gear} "
                          f"per unit of lead from the helices of gears.{spec.gear} and gears.{other}), more than the "
                          f"engagement length {_length_text(length, unit)}: the trailing pinion would reach the "
                          "bull gear before the lead has opened the backlash for it",
                          f"[0, {_length_text(max(most, 0.0), unit, 'down')}]")
    return spec


# ----------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class StiffnessDesign:
    """All sections of the stiffness step of one design, validated (internal units)."""

    stiffness: StiffnessSpec
    preload: PreloadSpec | None = None
    flexures: FlexureSpec | None = None
    springs: SpringSpec | None = None
    beam_pinion: BeamPinionSpec | None = None
    engagement: EngagementSpec | None = None


def stiffness_design(design) -> StiffnessDesign:
    """Read the stiffness-step sections of a loaded :class:`~geargen.design.assembly.Design`."""
    def opt(name, reader):
        table = design.section(name)
        return reader(table) if table else None

    unit, gears = design.length_unit, design.gears
    spec = stiffness_spec_from_table(design.section("stiffness"), KEYS[kind_of(design)].STIFFNESS_TRAIN)
    if design.section("stiffness"):
        check_stiffness_gears(spec, gears)
    return StiffnessDesign(stiffness=spec,
                           preload=opt("preload", preload_spec_from_table),
                           flexures=opt("flexures", lambda t: flexure_spec_from_table(t, unit)),
                           springs=opt("springs", lambda t: spring_spec_from_table(t, unit)),
                           beam_pinion=opt("beam_pinion", lambda t: beam_pinion_spec_from_table(t, gears)),
                           engagement=opt("engagement", lambda t: engagement_spec_from_table(t, gears, unit, spec)))


def check_swept_spring(design, unit: str) -> None:
    """The swept-wire spring model (all ``Nt`` coils as one helix between ground ends) needs a
    pitch above the wire: an installed length above ``d (Nt + 1)``, a wire more than the solid
    height of a squared-and-ground spring."""
    table = design.section("springs")
    spring = spring_spec_from_table(table, unit)
    if spring.installed_length is None:
        return
    coils = spring.active_coils + SPRING_ENDS[spring.end_type][0]
    shortest = spring.wire_diameter * (coils + 1)
    if not spring.installed_length > shortest:
        key = next(k for k in table if k.startswith("installed_length_"))
        scale = LENGTH_SUFFIXES[unit]
        raise DesignError(f"springs.{key}", f"{spring.installed_length / scale:.6g} {unit} is too short for the "
                          f"swept-wire model of the spring ({coils:g} coils of {spring.wire_diameter / scale:.6g} {unit} "
                          "wire would touch)", f"> {shortest / scale:.6g} {unit}, or parts.spring_model = 'envelope'")


__all__ = ["QUANTITY_SUFFIXES", "INTERNAL_UNITS", "convert_quantity", "Quantity", "ComponentSpec", "StiffnessSpec",
           "PreloadSpec", "FlexureSpec", "SpringSpec", "BeamPinionSpec", "EngagementSpec", "StiffnessDesign",
           "stiffness_design", "check_swept_spring", "component_from_table", "stiffness_spec_from_table", "preload_spec_from_table",
           "flexure_spec_from_table", "spring_spec_from_table", "beam_pinion_spec_from_table",
           "engagement_spec_from_table", "engagement_meshes", "check_stiffness_gears", "SHAFTS", "SCOPES", "COMPONENT_KINDS", "END_TYPES",
           "SPRING_ENDS"]
