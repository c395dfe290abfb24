"""Path, drive and loop stiffness of a two-path anti-backlash drive; preload and its variation.

Hale & Slocum's four facts (modelling section): stiffnesses in parallel add; compliances in
series add; a stiffness reflected through a ratio ``R`` grows by ``R^2``; a linear stiffness at a
lever arm ``r`` is a torsional stiffness ``k r^2``. Eq. 1 gives the tooth-mesh stiffness
``k = E w / 11`` (linear, along the line of action). Every path is reduced to one place and kind:
torsion at the output unless asked otherwise. :class:`geargen.core.drive.TwoPathDrive` then gives
Eqs. 2-6 and the piecewise torque-deflection law.

Internal units: mm, N, rad; torque N·mm, linear stiffness N/mm, torsional stiffness N·mm/rad,
moduli MPa. ``ratio`` of a shaft is its speed over the output's (the input shaft of the robot
joint turns 16 times per output turn), so a torsional stiffness ``k`` on it is ``k R^2`` at the
output, a torque ``T`` there is ``T R`` at the output and a rotation ``theta`` is ``theta / R``.

Preload motion (radial or axial, Fig. 9): a carriage displacement ``x`` along the preload
direction turns the two paths ``+lambda x`` and ``-lambda x`` (output rotation), with the lever
``lambda = cos(gamma) / (R2 r_b2)`` for radial motion (``gamma`` the angle between the motion and
each mesh-1 line of action, ``r_b2`` the base radius of the cluster's large gear, ``R2`` the
cluster-to-output ratio) and ``lambda = tan(beta) / (R2 r_2)`` for axial motion of a helical
input. The preload spring ``k3`` of the drive model (lever 1 on each path, ``F1 - F2 = k3 (s - w)``)
is then ``k_carriage / lambda^2``; the carriage force is ``F_e = 2 lambda P`` for a loop preload
``P``; a carriage travel ``dx`` (the synthesis error budget ``dx1``) is a loop error
``delta_L = 2 lambda dx`` of output rotation, and changes the preload by ``k_L delta_L`` (Eq. 6).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, Mapping, Sequence

import numpy as np

from geargen.core.drive import TwoPathDrive
from geargen.core.flexures import (BeamPinion, BladeDesign, BladeFlexure, CompressionSpring, HelicalEngagement,
                                   SlidingMesh, beam_pinion, blade_flexure, compression_spring, design_blade_flexure,
                                   helical_engagement, round_section_second_moment)
from geargen.design.stiffness import (TRAIN_SHAFTS, ComponentSpec, StiffnessDesign, StiffnessSpec,
                                      engagement_meshes, stiffness_design)
from geargen.errors import DesignError
from geargen.units import TextUnits

#: Eq. 1's divisor: k_mesh = E w / 11 (Shigley, bending + shear + contact of a typical mesh)
MESH_DIVISOR = 11.0


# ----------------------------------------------------------------------------------------------
# Component stiffnesses and their combination

def mesh_stiffness(elastic_modulus, face_width):
    """Tooth-mesh stiffness along the line of action, N/mm: ``k = E w / 11`` (Eq. 1).

    ``elastic_modulus`` in MPa, ``face_width`` (engaged face, mm). Arrays broadcast.
    """
    return np.asarray(elastic_modulus, dtype=float) * np.asarray(face_width, dtype=float) / MESH_DIVISOR


def gear_mesh_stiffness(gear_a, gear_b, face_width: float, elastic_modulus: float, method: str = "eq1",
                        where: str = "stiffness") -> tuple[float, str, tuple[str, ...]]:
    """A tooth mesh of two gears along its (transverse) line of action, N/mm, by ``method``
    (``[stiffness] mesh_stiffness``): "eq1", ``E w / 11``; "iso6336", ISO 6336-1:2019 method B,
    ``c_gamma_alpha w`` (:func:`geargen.core.iso6336.pair_stiffness`: the gears' teeth, shifts,
    module, helix and basic rack; eps_alpha at the working centre distance of their shifts; solid
    blanks; no load correction; ``E`` of both gears). Returns (stiffness, detail text, warnings).
    ``where`` is the design key errors name."""
    if method == "eq1":
        return float(mesh_stiffness(elastic_modulus, face_width)), f"Eq. 1: E w / 11, w={face_width:.4g} mm", ()
    if method != "iso6336":
        raise DesignError("stiffness.mesh_stiffness", f"{method!r} is not a valid choice", "'eq1', 'iso6336'")
    from geargen.core.geometry import GearPair
    from geargen.core.iso6336 import METHOD, pair_stiffness

    try:
        result = pair_stiffness(GearPair(gear_a, gear_b), face_width=face_width, elastic_modulus=elastic_modulus)
    except DesignError as exc:  # the gears do not make a pair ISO 6336 can rate: say which entry named them
        raise DesignError(where, f"ISO 6336 mesh stiffness: {exc.field}: {exc.problem}", exc.allowed) from None
    detail = (f"{METHOD}: c_gamma_alpha w, {result.mesh_stiffness:.4g} N/(mm um) x w={face_width:.4g} mm (c' "
              f"{result.single_stiffness:.4g}, eps_alpha {result.transverse_contact_ratio:.4f}, E/E_st "
              f"{result.material_factor:.4g})")
    return result.line_of_action_stiffness, detail, result.warnings


def shaft_torsional_stiffness(shear_modulus: float, diameter: float, length: float, bore: float = 0.0) -> float:
    """Torsional stiffness of a round (hollow) shaft, N·mm/rad: ``G J / L``, ``J = pi (d^4 - di^4)/32``."""
    j = math.pi * (diameter ** 4 - bore ** 4) / 32.0
    return shear_modulus * j / length


def shaft_bending_stiffness(elastic_modulus: float, diameter: float, span: float | None, load_position: float,
                            support: str = "simple", bore: float = 0.0) -> float:
    """Lateral stiffness at the gear of a round shaft in bending, N/mm.

    ``support``: "simple" (two bearings), ``3 EI L / (a^2 b^2)``; "fixed" (both ends built in),
    ``3 EI L^3 / (a^3 b^3)``; "cantilever" (overhang ``a = load_position``, ``span`` unused),
    ``3 EI / a^3``. ``a`` is the gear's distance from one support, ``b = L - a``.
    """
    ei = elastic_modulus * round_section_second_moment(diameter, bore)
    a = load_position
    if support == "cantilever":
        return 3.0 * ei / a ** 3
    if span is None or not 0 < a < span:
        raise DesignError("load_position", f"{a!r} mm is not between the supports", "(0, span)")
    b = span - a
    if support == "simple":
        return 3.0 * ei * span / (a * a * b * b)
    if support == "fixed":
        return 3.0 * ei * span ** 3 / (a ** 3 * b ** 3)
    raise DesignError("support", f"{support!r} is not a valid choice", "'simple', 'fixed', 'cantilever'")


def supported_shaft_compliance(elastic_modulus: float, diameter: float, span: float, load_position: float,
                               bearing_stiffness: tuple[float, float], bore: float = 0.0) -> tuple[float, float]:
    """Lateral compliance (mm/N) and slope per unit load (rad/N) at a gear on a round shaft carried
    by two bearings ``span`` apart, the gear at ``load_position`` from the first (negative, or
    beyond ``span``: overhung), the bearings of radial stiffness ``bearing_stiffness`` (N/mm):
    :func:`shaft_influence` at the load itself."""
    return shaft_influence(elastic_modulus, diameter, span, load_position, load_position, bearing_stiffness, bore)


def shaft_influence(elastic_modulus: float, diameter: float, span: float, load_position: float, at: float,
                    bearing_stiffness: tuple[float, float], bore: float = 0.0) -> tuple[float, float]:
    """Lateral displacement (mm/N) and slope (rad/N) at ``at`` of a round shaft on two elastic
    supports ``span`` apart under a unit load at ``load_position`` (both measured from the first
    support; outside ``[0, span]``: overhung).

    Exact for a linear beam on elastic point supports: the beam on rigid supports by virtual work,
    ``int M m / EI``, with ``M`` the moment of the unit load and ``m`` that of a unit load
    (displacement) or a unit couple (slope) at ``at`` -- both piecewise linear between the supports
    and the two points, so Simpson's rule on each piece is exact -- plus the rigid-body motion of the
    shaft on its bearings, whose reactions follow the lever (``R1 = (L - z) / L``, ``R2 = z / L``).
    """
    ei = elastic_modulus * round_section_second_moment(diameter, bore)
    L, p, q = span, load_position, at
    if not L > 0:
        raise DesignError("span", f"{L!r} mm: two bearings at one place", "> 0")

    def step(x_side: float, point: float) -> float:  # [x > point], read on the open piece
        return 1.0 if x_side > point else 0.0

    def moment_of_load(x: float, side: float, z: float) -> float:
        """Moment at x of a unit load at z (reactions (L - z)/L and z/L), summed from the left."""
        return (L - z) / L * x * step(side, 0.0) + z / L * (x - L) * step(side, L) - (x - z) * step(side, z)

    def moment_of_couple(x: float, side: float, z: float) -> float:
        """d/dz of moment_of_load: a unit couple at z."""
        return -x / L * step(side, 0.0) + (x - L) / L * step(side, L) + step(side, z)

    points = sorted({0.0, L, p, q})
    bending = slope = 0.0
    for a, b in zip(points[:-1], points[1:]):
        mid = (a + b) / 2
        w = (b - a) / 6
        for x, weight in ((a, w), (mid, 4 * w), (b, w)):
            big = moment_of_load(x, mid, p)
            bending += weight * big * moment_of_load(x, mid, q)
            slope += weight * big * moment_of_couple(x, mid, q)
    k1, k2 = bearing_stiffness
    u1, u2 = (L - p) / L / k1, p / L / k2  # the bearings give way under their reactions
    return u1 + (u2 - u1) * q / L + bending / ei, (u2 - u1) / L + slope / ei


def supported_gear_response(spec: ComponentSpec, elastic_modulus: float) -> tuple[float, float, float]:
    """A gear on its placed shaft (a ``shaft_support`` component) under its mesh force and the shaft's
    other mesh forces (``spec.other_loads``, in proportion): per unit force at the gear, its
    displacement and slope along that force, and the compliance the path sees, ``sum_ij f_i f_j
    cos(theta_i - theta_j) C_ij`` -- the work of all the forces, so the output rotation."""
    supports = spec.support_stiffness or (spec.stiffness, spec.stiffness)
    loads = ((spec.load_position, 1.0, 0.0),) + tuple(spec.other_loads)

    def influence(load: float, at: float) -> tuple[float, float]:
        return shaft_influence(elastic_modulus, spec.diameter, spec.span, load, at, supports, spec.bore_diameter)

    displacement = slope = compliance = 0.0
    for z_i, f_i, t_i in loads:
        d, s = influence(z_i, spec.load_position)
        displacement += f_i * math.cos(t_i) * d
        slope += f_i * math.cos(t_i) * s
        for z_j, f_j, t_j in loads:
            compliance += f_i * f_j * math.cos(t_i - t_j) * influence(z_j, z_i)[0]
    return displacement, slope, compliance


def series(*stiffnesses):
    """Stiffnesses in series: ``1 / sum(1/k)``. ``inf`` (rigid) adds nothing; arrays broadcast."""
    with np.errstate(divide="ignore"):
        compliance = sum(1.0 / np.asarray(k, dtype=float) for k in stiffnesses)
        out = 1.0 / np.asarray(compliance, dtype=float)
    return float(out) if np.ndim(out) == 0 else out


def parallel(*stiffnesses):
    """Stiffnesses in parallel: ``sum(k)``."""
    out = sum(np.asarray(k, dtype=float) for k in stiffnesses)
    return float(out) if np.ndim(out) == 0 else out


def reflect(stiffness, ratio):
    """A torsional stiffness on a shaft turning ``ratio`` times the reference shaft, seen at the
    reference: ``k R^2``. (Going the other way, pass ``1/R``.)"""
    return np.asarray(stiffness, dtype=float) * np.asarray(ratio, dtype=float) ** 2


def torsional_from_linear(stiffness, radius):
    """A linear stiffness acting at lever arm ``radius`` as a torsional stiffness: ``k r^2``."""
    return np.asarray(stiffness, dtype=float) * np.asarray(radius, dtype=float) ** 2


def linear_from_torsional(stiffness, radius):
    """The inverse of :func:`torsional_from_linear`: ``k / r^2``."""
    return np.asarray(stiffness, dtype=float) / np.asarray(radius, dtype=float) ** 2


# ----------------------------------------------------------------------------------------------
# The dual-pinion train and its components

@dataclass(frozen=True)
class DualPinionTrain:
    """Input gear between two identical clusters (large gear meshes the input, small gear the output).

    ``gears`` maps role ("input", "cluster_large", "cluster_small", "output") to the design's
    gear spec; ``names`` maps role to the gear's name in the design.
    """

    gears: Mapping[str, Any]
    names: Mapping[str, str]
    # the gears of the stages before the input (geargen.design.stages), each to its shaft's speed
    # over the output's
    upstream: Mapping[str, float] = field(default_factory=dict)

    @property
    def ratio_mesh1(self) -> float:
        """R1 = z_cluster_large / z_input."""
        return self.gears["cluster_large"].teeth / self.gears["input"].teeth

    @property
    def ratio_mesh2(self) -> float:
        """R2 = z_output / z_cluster_small."""
        return self.gears["output"].teeth / self.gears["cluster_small"].teeth

    @property
    def ratio(self) -> float:
        """Input speed over output speed, R1 R2."""
        return self.ratio_mesh1 * self.ratio_mesh2

    shafts = TRAIN_SHAFTS["dual_pinion"]

    def shaft_ratio(self, shaft: str) -> float:
        """Speed of ``shaft`` ("input", "cluster", "output") over the output's."""
        return {"output": 1.0, "cluster": self.ratio_mesh2, "input": self.ratio}[shaft]

    def shaft_of_gear(self, name: str) -> str | None:
        role = next((r for r, n in self.names.items() if n == name), None)
        return None if role is None else {"input": "input", "cluster_large": "cluster",
                                          "cluster_small": "cluster", "output": "output"}[role]

    def gear_ratio(self, name: str) -> float | None:
        """Speed of the shaft carrying gear ``name`` over the output's; None for a gear off the train."""
        if name in self.upstream:
            return self.upstream[name]
        shaft = self.shaft_of_gear(name)
        return None if shaft is None else self.shaft_ratio(shaft)

    @property
    def mesh1_face_width(self) -> float:
        return min(self.gears["input"].face_width, self.gears["cluster_large"].face_width)

    @property
    def mesh2_face_width(self) -> float:
        return min(self.gears["cluster_small"].face_width, self.gears["output"].face_width)


@dataclass(frozen=True)
class SplitPinionTrain:
    """Two pinions on one axis (concentric shafts turning together, Fig. 8) meshing one output.

    ``gears`` and ``names`` map role ("pinion_stiff", "pinion_compliant", "output", as
    ``[layout]`` names them) to the gear spec and its name. The pinions' shaft is "input".
    """

    gears: Mapping[str, Any]
    names: Mapping[str, str]
    shafts = TRAIN_SHAFTS["split_pinion"]

    @property
    def ratio(self) -> float:
        """Input (pinion) speed over output speed, z_output / z_pinion."""
        return self.gears["output"].teeth / self.gears["pinion_stiff"].teeth

    def shaft_ratio(self, shaft: str) -> float:
        """Speed of ``shaft`` ("input": the pinions', "output") over the output's."""
        return {"output": 1.0, "input": self.ratio}[shaft]

    def gear_ratio(self, name: str) -> float | None:
        """Speed of the shaft carrying gear ``name`` over the output's; None for a gear off the train."""
        role = next((r for r, n in self.names.items() if n == name), None)
        return None if role is None else self.shaft_ratio("output" if role == "output" else "input")


def split_pinion_train(design) -> SplitPinionTrain:
    """The split pinion of ``design``, its gears as ``[layout]`` names them."""
    from geargen.design.layout import layout_settings
    settings = layout_settings(design)
    names = {role: settings[role] for role in ("pinion_stiff", "pinion_compliant", "output")}
    for role, name in names.items():
        if name not in design.gears:
            raise DesignError(f"layout.{role}", f"no gear named {name!r} in the design", ", ".join(design.gears))
    # both pinions have one tooth count ([layout] checks it), so either gives the ratio
    return SplitPinionTrain(gears={role: design.gears[name] for role, name in names.items()}, names=names)


def drive_train(design, spec: StiffnessSpec) -> DualPinionTrain | SplitPinionTrain | None:
    """The train of ``design`` that ``[stiffness] train`` names; None for a custom train (its
    components type their ratios)."""
    if spec.train == "dual_pinion":
        return train_from_design(design, spec)
    return split_pinion_train(design) if spec.train == "split_pinion" else None


def train_from_design(design, spec: StiffnessSpec) -> DualPinionTrain:
    """The dual-pinion train of ``design`` with the gear roles named in ``[stiffness]``."""
    gears, names = {}, {}
    for role, name in spec.roles.items():
        if name not in design.gears:
            raise DesignError(f"stiffness.{role}_gear", f"no gear named {name!r} in the design",
                              ", ".join(design.gears) or "a [gears.NAME] table")
        gears[role] = design.gears[name]
        names[role] = name
    from geargen.design.stages import shaft_speeds, stages
    train = DualPinionTrain(gears=gears, names=names)
    return replace(train, upstream=shaft_speeds(design, stages(design), train.ratio))


@dataclass(frozen=True)
class ComponentStiffness:
    """One component reduced to torsion at the output.

    ``local`` is its stiffness where it acts, in ``local_unit`` ("N/mm" along a line at
    ``radius``, or "N·mm/rad" on its shaft); ``ratio`` is its shaft's speed over the output's.
    """

    name: str
    kind: str
    scope: str
    local: float
    local_unit: str
    ratio: float
    radius: float | None
    at_output: float
    detail: str = ""
    warnings: tuple[str, ...] = ()  # of its formula's range (ISO 6336 meshes)


def _component_location(spec: ComponentSpec, train: DualPinionTrain | SplitPinionTrain | None, gear: str | None,
                        where: str) -> float:
    """The speed of the component's shaft over the output's: typed in a custom train (``train``
    None), else from the teeth, for the shaft or the ``gear`` it names."""
    if train is None:
        if spec.ratio is None:
            raise DesignError(f"{where}.ratio", "missing (a custom train needs each component's ratio)",
                              "ratio = speed of its shaft / speed of the output")
        return spec.ratio
    shafts = " | ".join(map(repr, train.shafts))
    if spec.shaft is not None:  # (never with a ratio: the spec refuses both)
        return train.shaft_ratio(spec.shaft)
    known = train.gear_ratio(gear) if gear else None
    if spec.ratio is not None:
        # typed, it could disagree with the teeth: the one home of a speed is the teeth
        teeth = (f"the teeth give {known:.6g} for the shaft of gears.{gear}" if known is not None else
                 "the teeth give the shafts' speeds: " + ", ".join(f"{s!r} {train.shaft_ratio(s):.6g}"
                                                                   for s in train.shafts))
        raise DesignError(f"{where}.ratio", f"{spec.ratio:g} typed, but {teeth} (a ratio is typed only in a custom "
                          "train)", f"no ratio: shaft = {shafts} or gear = NAME (the shaft carrying it)")
    if known is None:
        raise DesignError(f"{where}.shaft", f"gear {gear!r} is not one of the train's gears; say where it sits"
                          if gear else "missing: which shaft it sits on", f"shaft = {shafts}")
    return known


def _gear_base_radius(gears: Mapping[str, Any], name: str, where: str) -> float:
    if name not in gears:
        raise DesignError(where, f"no gear named {name!r} in the design", ", ".join(gears))
    return gears[name].base_radius


def component_stiffness(spec: ComponentSpec, gears: Mapping[str, Any], stiffness: StiffnessSpec,
                        train: DualPinionTrain | SplitPinionTrain | None) -> ComponentStiffness:
    """Reduce one design component to torsion at the output (``gears``: the design's, by name)."""
    where = f"stiffness.components.{spec.name}"
    if spec.from_geometry and not spec.placed:
        raise DesignError(f"{where}.from_geometry", "its lengths come from the placed shafts, which only the resolved "
                          "drive knows (geargen.model.analysis.stiffness)", "a design with [parts] placing its shafts")
    e = spec.elastic_modulus or stiffness.elastic_modulus
    g = spec.shear_modulus or stiffness.shear_modulus
    radius = None
    notes: tuple[str, ...] = ()
    if spec.kind == "torsion":
        local, unit, detail = spec.stiffness, "N·mm/rad", "given torsional stiffness"
        ratio = _component_location(spec, train, spec.gear, where)
    elif spec.kind == "shaft_torsion":
        local = shaft_torsional_stiffness(g, spec.diameter, spec.length, spec.bore_diameter)
        unit, detail = "N·mm/rad", f"shaft d={spec.diameter:.4g} mm, L={spec.length:.4g} mm, G J / L"
        ratio = _component_location(spec, train, spec.gear, where)
    elif spec.kind in ("linear", "shaft_bending"):
        radius = (_gear_base_radius(gears, spec.gear, f"{where}.gear") if spec.gear is not None else spec.radius)
        if spec.kind == "linear":
            local, detail = spec.stiffness, "given linear stiffness"
        else:
            local = shaft_bending_stiffness(e, spec.diameter, spec.span, spec.load_position, spec.support,
                                            spec.bore_diameter)
            detail = f"{spec.support} shaft d={spec.diameter:.4g} mm in bending"
        unit = "N/mm"
        ratio = _component_location(spec, train, spec.gear, where)
    elif spec.kind == "shaft_support":
        radius = _gear_base_radius(gears, spec.gear, f"{where}.gear")
        local, unit = 1.0 / supported_gear_response(spec, e)[2], "N/mm"
        supports = spec.support_stiffness or (spec.stiffness, spec.stiffness)
        where_load = ("between its supports" if 0 <= spec.load_position <= spec.span else "overhung")
        each = (f"{supports[0]:.4g} N/mm each" if supports[0] == supports[1]
                else f"{supports[0]:.4g} and {supports[1]:.4g} N/mm")
        detail = (f"shaft d={spec.diameter:.4g} mm on supports {spec.span:.4g} mm apart ({each}), "
                  f"gear {where_load} at {spec.load_position:.4g} mm")
        for z, share, angle in spec.other_loads:
            detail += (f"; with the shaft's other mesh force ({share:.3g} x, at {z:.4g} mm, "
                       f"{math.degrees(angle) % 360:.0f} deg from the gear's)")
        ratio = _component_location(spec, train, spec.gear, where)
    elif spec.kind == "mesh":
        a, b = spec.gears
        for gname in (a, b):
            if gname not in gears:
                raise DesignError(f"{where}.gears", f"no gear named {gname!r} in the design", ", ".join(gears))
        w = spec.face_width or min(gears[a].face_width, gears[b].face_width)
        local, detail, notes = gear_mesh_stiffness(gears[a], gears[b], w, e, stiffness.mesh_stiffness,
                                                   f"{where}.gears")
        unit = "N/mm"
        radius = gears[b].base_radius
        ratio = _component_location(spec, train, b, where)
    else:  # pragma: no cover - the spec validates kinds
        raise DesignError(f"{where}.kind", f"unknown kind {spec.kind!r}")
    local *= spec.count
    if spec.count > 1:
        detail += f", {spec.count} in parallel"
    torsional = local if radius is None else float(torsional_from_linear(local, radius))
    return ComponentStiffness(name=spec.name, kind=spec.kind, scope=spec.scope, local=float(local), local_unit=unit,
                              ratio=float(ratio), radius=radius, at_output=float(reflect(torsional, ratio)),
                              detail=detail, warnings=notes)


def train_mesh_components(train: DualPinionTrain, elastic_modulus: float,
                          method: str = "eq1") -> list[ComponentStiffness]:
    """The two meshes of each path of a dual-pinion train (Eq. 1, or ISO 6336 by ``method``:
    :func:`gear_mesh_stiffness`), reduced to the output."""
    n = train.names
    out = []
    for label, (a, b), w, shaft in (("mesh 1", ("input", "cluster_large"), train.mesh1_face_width, "cluster"),
                                    ("mesh 2", ("cluster_small", "output"), train.mesh2_face_width, "output")):
        k, detail, notes = gear_mesh_stiffness(train.gears[a], train.gears[b], w, elastic_modulus, method,
                                               f"stiffness.{a}_gear")
        rb = train.gears[b].base_radius
        ratio = train.shaft_ratio(shaft)
        out.append(ComponentStiffness(
            name=f"{label} ({n[a]}-{n[b]})", kind="mesh", scope="each_path", local=k, local_unit="N/mm",
            ratio=ratio, radius=rb, at_output=float(reflect(torsional_from_linear(k, rb), ratio)),
            detail=f"{detail}, at base radius {rb:.4g} mm of {n[b]}", warnings=notes))
    return out


@dataclass(frozen=True)
class PathStiffness:
    """A path (or the common part) as components in series, torsion at the output (N·mm/rad)."""

    name: str
    components: tuple[ComponentStiffness, ...]

    @property
    def stiffness(self) -> float:
        """Series sum of the components at the output; ``inf`` when there are none."""
        if not self.components:
            return math.inf
        return series(*(c.at_output for c in self.components))

    def compliance_shares(self) -> dict[str, float]:
        """Each component's share of the path's compliance (sums to 1)."""
        total = sum(1.0 / c.at_output for c in self.components)
        return {c.name: (1.0 / c.at_output) / total for c in self.components}


def split_paths(components: Sequence[ComponentStiffness]) -> tuple[PathStiffness, PathStiffness, PathStiffness]:
    """Path 1, path 2 and the common part (in series with the whole drive) from scoped components."""
    p1 = tuple(c for c in components if c.scope in ("each_path", "path1"))
    p2 = tuple(c for c in components if c.scope in ("each_path", "path2"))
    common = tuple(c for c in components if c.scope == "common")
    return PathStiffness("path 1", p1), PathStiffness("path 2", p2), PathStiffness("common", common)


# ----------------------------------------------------------------------------------------------
# Preload

def preload_lever(train: DualPinionTrain, method: str = "radial", line_of_action_angle: float = 0.0) -> float:
    """Output rotation of each path per unit preload motion of the input gear, rad/mm.

    radial: ``cos(gamma) / (R2 r_b2)``; axial: ``tan(beta) / (R2 r_2)`` (helical input, ``beta``
    its helix angle; ``r_2`` the reference radius of the cluster's large gear).
    """
    large = train.gears["cluster_large"]
    if method == "radial":
        return math.cos(line_of_action_angle) / (train.ratio_mesh2 * large.base_radius)
    if method == "axial":
        beta = train.gears["input"].helix_angle
        if beta <= 0:
            raise DesignError("drive.preload", "axial preload needs a helical input gear", "helix_angle_deg > 0")
        return math.tan(beta) / (train.ratio_mesh2 * large.reference_radius)
    raise DesignError("drive.preload", f"no preload lever for the {method!r} method",
                      "'radial' or 'axial'; otherwise give preload_spring_stiffness_Nm_per_rad at the output")


def preload_spring_at_output(linear_stiffness, lever: float):
    """A linear preload-spring stiffness at the carriage as ``k3`` of the drive model: ``k / lambda^2``."""
    return np.asarray(linear_stiffness, dtype=float) / lever ** 2


def loop_error_from_carriage_travel(travel, lever: float):
    """Loop error (output rotation, rad) of a carriage travel (mm): ``2 lambda travel``."""
    return 2.0 * lever * np.asarray(travel, dtype=float)


def carriage_force(preload, lever: float):
    """Preload force on the carriage (N) for a loop preload (N·mm at the output): ``2 lambda P``."""
    return 2.0 * lever * np.asarray(preload, dtype=float)


def required_preload(max_torque: float, drive_type: str) -> float:
    """The paper's recommendation: type 2 at least half the maximum load, type 1 the maximum load."""
    if drive_type == "type2":
        return 0.5 * max_torque
    if drive_type == "type1":
        return float(max_torque)
    raise DesignError("drive.type", f"{drive_type!r} is not a valid choice", "'type1', 'type2'")


def preload_to_carry(max_torque: float, drive_type: str, k1: float, k2: float, k3: float = math.inf) -> float:
    """The smallest loop preload at which neither path unloads for drive torques up to ``max_torque``.

    From the two-path model: path 2 unloads at ``T = k_D P / g2`` and path 1 at ``-k_D P / g1``
    (``g`` the rates of path force with drive displacement), so ``P = T max(g1, g2) / k_D``. It
    equals half the load for equal type 2 paths and ``T k1/(k1 + k2)`` for type 1 with stiff path 1
    -- a little below the paper's rule, which the paper calls some degree of conservatism.
    """
    unit = TwoPathDrive(drive_type, k1, k2, 1.0, k3)
    g1, g2 = unit.path_force_rates
    return max_torque * max(g1, g2) / unit.drive_stiffness


@dataclass(frozen=True)
class LoopError:
    """A peak-to-peak loop error: ``rotation`` (rad at the output), from ``carriage_travel`` (mm) if so given."""

    label: str
    rotation: float
    carriage_travel: float | None = None
    source: str = "design"


@dataclass(frozen=True)
class PreloadVariation:
    """Preload band caused by a loop error (N·mm at the output, rad) and, where the preload device
    slides on a fit with friction (``friction_to_preload`` rho: the friction force over the spring
    force, :mod:`geargen.core.axial_preload`), by that friction: the spring force sets the preload
    only to within ``1 / (1 +- rho)``, the shaft sticking anywhere between."""

    label: str
    loop_error: float
    loop_stiffness: float
    preload: float
    carriage_travel: float | None = None
    source: str = "design"
    friction_to_preload: float = 0.0

    @property
    def loop_range(self) -> float:
        """Peak-to-peak preload change from the loop error alone, ``k_L delta_L`` (Eq. 3/6): the
        spring force's change."""
        return self.loop_stiffness * self.loop_error

    @property
    def range(self) -> float:
        """Peak-to-peak preload: the loop error's band widened by the friction band."""
        return self.high - self.low

    @property
    def low(self) -> float:
        return (self.preload - self.loop_range / 2.0) / (1.0 + self.friction_to_preload)

    @property
    def high(self) -> float:
        if self.friction_to_preload >= 1.0:  # the fit locks: the spring no longer bounds the preload
            return math.inf
        return (self.preload + self.loop_range / 2.0) / (1.0 - self.friction_to_preload)

    @property
    def relative(self) -> float:
        """Peak-to-peak change over the nominal preload (inf at zero preload)."""
        return self.range / self.preload if self.preload > 0 else math.inf

    @property
    def unloads(self) -> bool:
        """True when the low end of the band loses the preload entirely."""
        return self.low <= 0.0


def preload_variation(drive: TwoPathDrive, loop_error, label: str = "loop error",
                      carriage_travel: float | None = None, source: str = "design",
                      friction_to_preload: float = 0.0) -> PreloadVariation:
    """Preload band of ``drive`` for a peak-to-peak loop error (rad at the drive's reference) and
    the preload device's friction (see :class:`PreloadVariation`)."""
    return PreloadVariation(label=label, loop_error=float(loop_error), loop_stiffness=drive.loop_stiffness,
                            preload=drive.preload, carriage_travel=carriage_travel, source=source,
                            friction_to_preload=friction_to_preload)


@dataclass(frozen=True)
class PreloadSpring:
    """The preload spring of a type 2 drive: parts in parallel at the carriage, and ``k3`` at the output.

    ``linear_parts`` are (name, N/mm along the preload motion); ``torsional_parts`` are
    (name, N·mm/rad at the output); ``lever`` is rad per mm (None without a carriage).
    """

    lever: float | None
    linear_parts: tuple[tuple[str, float], ...]
    torsional_parts: tuple[tuple[str, float], ...]

    @property
    def linear_stiffness(self) -> float:
        """Carriage stiffness along the preload motion, N/mm (all parts, torsional ones referred)."""
        total = sum(k for _, k in self.linear_parts)
        if self.lever is not None:
            total += sum(k for _, k in self.torsional_parts) * self.lever ** 2
        return total

    @property
    def stiffness(self) -> float:
        """k3 at the output, N·mm/rad."""
        total = sum(k for _, k in self.torsional_parts)
        if self.linear_parts:
            total += float(preload_spring_at_output(sum(k for _, k in self.linear_parts), self.lever))
        return total


# ----------------------------------------------------------------------------------------------
# The whole summary of a design

LOCATION_NAMES = {"output": "output torsion", "cluster": "cluster-shaft torsion", "input": "input torsion"}


@dataclass(frozen=True)
class SupportDeflection:
    """A gear on its placed shaft and bearings under the mesh force of the preload, with the
    shaft's other mesh forces (a cluster's other gear) (mm, rad, N): how far it moves along its line of action and how much it tilts, and the misalignment that
    tilt makes across its face (``tilt * face_width``)."""

    component: str
    gear: str
    force: float
    deflection: float
    tilt: float
    face_width: float

    @property
    def misalignment(self) -> float:
        return abs(self.tilt) * self.face_width


#: a tilt making more than this across a face (mm) is warned about: about the helix-form tolerance
#: of an ISO 1328 grade 6 gear of 20-100 mm face, which a mesh misaligned by more loses
MISALIGNMENT_WARNING = 0.010


@dataclass(frozen=True)
class StiffnessSummary:
    """Everything the stiffness step knows about a design; output-referred internal units.

    ``drive`` is referred to the output (N·mm, rad); :meth:`drive_at` refers it elsewhere.
    ``location`` is where the design asks results to be shown (``location_ratio`` its speed over
    the output's).
    """

    name: str
    drive_type: str
    preload_method: str | None
    location: str
    location_ratio: float
    shaft_ratios: Mapping[str, float]
    length_unit: str
    components: tuple[ComponentStiffness, ...]
    path1: PathStiffness
    path2: PathStiffness
    common: PathStiffness
    preload_spring: PreloadSpring | None
    drive: TwoPathDrive
    max_output_torque: float
    preload_source: str
    required_preload: float
    preload_to_carry: float
    carriage_force: float | None
    lever: float | None
    variations: tuple[PreloadVariation, ...]
    headline_budget: str | None
    path_backlash: float | None
    flexure: BladeFlexure | None = None
    flexure_design: BladeDesign | None = None
    flexure_design_gauge: BladeDesign | None = None
    spring: CompressionSpring | None = None
    spring_count: int = 0
    spring_installed_length_for_preload: float | None = None
    beam: BeamPinion | None = None
    beam_supports: tuple[float, float] | None = None  # N/mm under the beam's lower and upper bearing
    engagement: HelicalEngagement | None = None
    warnings: tuple[str, ...] = field(default_factory=tuple)
    supports: tuple["SupportDeflection", ...] = ()
    #: the units its text is shown in (the design's: :attr:`geargen.design.assembly.Design.text_units`)
    units: TextUnits = TextUnits()

    # --- drive quantities ---
    @property
    def drive_stiffness(self) -> float:
        """Eq. 2/5 at the output (both paths loaded), N·mm/rad."""
        return self.drive.drive_stiffness

    @property
    def drive_stiffness_with_common(self) -> float:
        """Drive stiffness in series with the common components, N·mm/rad at the output."""
        return series(self.drive.drive_stiffness, self.common.stiffness)

    @property
    def loop_stiffness(self) -> float:
        return self.drive.loop_stiffness

    @property
    def preload_ok(self) -> bool:
        """The set preload meets the paper's recommendation."""
        return self.drive.preload >= self.required_preload * (1 - 1e-12)

    @property
    def headline(self) -> PreloadVariation | None:
        for v in self.variations:
            if v.label == self.headline_budget:
                return v
        return self.variations[0] if self.variations else None

    def drive_at(self, location: str | None = None) -> TwoPathDrive:
        """The drive referred to ``location`` ("output", "cluster", "input"; default the design's)."""
        ratio = self.location_ratio if location is None else self._ratio_of(location)
        d = self.drive
        k3 = d.k3 if d.k3 == math.inf else d.k3 / ratio ** 2
        return TwoPathDrive(d.drive_type, d.k1 / ratio ** 2, d.k2 / ratio ** 2, d.preload / ratio, k3)

    def _ratio_of(self, location: str) -> float:
        if location not in self.shaft_ratios:
            raise DesignError("location", f"{location!r} is not available for this design",
                              ", ".join(map(repr, self.shaft_ratios)))
        return self.shaft_ratios[location]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary; units in the key names (SI-style: N·m, N/mm, rad, µm)."""
        d = self.drive
        nm = 1e-3  # N·mm -> N·m
        out: dict[str, Any] = {
            "name": self.name,
            "drive_type": self.drive_type,
            "preload_method": self.preload_method,
            "reference": "output torsion",
            "report_location": self.location,
            "report_location_ratio": self.location_ratio,
            "supports": [{"component": u.component, "gear": u.gear, "force_N": u.force, "deflection_um": u.deflection * 1e3,
                          "stiffness_N_per_um": u.force / u.deflection * 1e-3, "tilt_urad": u.tilt * 1e6,
                          "misalignment_um": u.misalignment * 1e3, "face_width_mm": u.face_width}
                         for u in self.supports],
            "paths": [
                {"name": p.name, "stiffness_Nm_per_rad": p.stiffness * nm,
                 "components": [{"name": c.name, "kind": c.kind, "scope": c.scope, "local": c.local,
                                 "local_unit": c.local_unit, "ratio": c.ratio,
                                 "radius_mm": c.radius, "at_output_Nm_per_rad": c.at_output * nm,
                                 "compliance_share": p.compliance_shares()[c.name], "detail": c.detail}
                                for c in p.components]}
                for p in (self.path1, self.path2)],
            "common": {"stiffness_Nm_per_rad": None if self.common.stiffness == math.inf else self.common.stiffness * nm,
                       "components": [{"name": c.name, "at_output_Nm_per_rad": c.at_output * nm, "detail": c.detail}
                                      for c in self.common.components]},
            "k1_Nm_per_rad": d.k1 * nm,
            "k2_Nm_per_rad": d.k2 * nm,
            "k3_Nm_per_rad": None if d.k3 == math.inf else d.k3 * nm,
            "preload_spring_parts_N_per_mm": None if self.preload_spring is None else dict(
                self.preload_spring.linear_parts),
            "beam_supports_N_per_mm": None if self.beam_supports is None else list(self.beam_supports),
            "preload_Nm": d.preload * nm,
            "drive": {
                "stiffness_Nm_per_rad": d.drive_stiffness * nm,
                "stiffness_with_common_Nm_per_rad": self.drive_stiffness_with_common * nm,
                "unloading_torques_Nm": [t * nm for t in d.unloading_torques],
                "unloading_rotations_urad": [r * 1e6 for r in d.unloading_rotations],
                "stiffness_beyond_Nm_per_rad": [d.stiffness_beyond(-1) * nm, d.stiffness_beyond(+1) * nm],
            },
            "loop": {"stiffness_Nm_per_rad": d.loop_stiffness * nm, "kD_over_kL": d.stiffness_ratio},
            "preload": {
                "max_output_torque_Nm": self.max_output_torque * nm,
                "preload_Nm": d.preload * nm,
                "source": self.preload_source,
                "required_paper_rule_Nm": self.required_preload * nm,
                "required_model_Nm": self.preload_to_carry * nm,
                "meets_recommendation": self.preload_ok,
                "carriage_force_N": self.carriage_force,
                "lever_rad_per_mm": self.lever,
                "path_backlash_urad": None if self.path_backlash is None else self.path_backlash * 1e6,
            },
            "preload_variation": [
                {"label": v.label, "source": v.source,
                 "carriage_travel_mm": v.carriage_travel, "loop_error_urad": v.loop_error * 1e6,
                 "range_Nm": v.range * nm, "low_Nm": v.low * nm, "high_Nm": v.high * nm,
                 "relative": v.relative, "loop_error_range_Nm": v.loop_range * nm,
                 "friction_to_preload": v.friction_to_preload,
                 "carriage_force_range_N": None if self.lever is None else float(carriage_force(v.loop_range, self.lever))}
                for v in self.variations],
            "headline_budget": self.headline_budget,
            "warnings": list(self.warnings),
        }
        if self.preload_spring is not None:
            ps = self.preload_spring
            out["preload_spring"] = {"linear_parts_N_per_mm": dict(ps.linear_parts),
                                     "torsional_parts_Nm_per_rad": {n: k * nm for n, k in ps.torsional_parts},
                                     "carriage_stiffness_N_per_mm": ps.linear_stiffness,
                                     "k3_Nm_per_rad": ps.stiffness * nm}
        if self.flexure is not None:
            f = self.flexure
            out["flexures"] = {"count": f.count, "stiffness_along_N_per_mm": f.stiffness_along,
                               "stiffness_lateral_N_per_mm": f.stiffness_lateral,
                               "stiffness_axial_N_per_mm": f.stiffness_axial, "travel_mm": f.travel,
                               "stress_at_travel_MPa": f.stress_at_travel, "allowable_MPa": f.allowable_stress,
                               "travel_limit_mm": f.travel_limit, "parasitic_shortening_mm": f.parasitic_shortening}
            for key, b in (("design_helper_shortest", self.flexure_design),
                           ("design_helper_at_gauge", self.flexure_design_gauge)):
                if b is not None:
                    out["flexures"][key] = {"thickness_mm": b.thickness, "length_mm": b.length,
                                            "stiffness_N_per_mm": b.stiffness,
                                            "stress_at_travel_MPa": b.stress_at_travel, "success": b.success,
                                            "message": b.message}
        if self.spring is not None:
            s = self.spring
            out["springs"] = {"count": self.spring_count, "rate_N_per_mm": s.rate, "index": s.index,
                              "wahl_factor": s.wahl_factor, "solid_height_mm": s.solid_height,
                              "installed_force_N": s.installed_force, "installed_stress_MPa": s.installed_stress,
                              "solid_stress_MPa": s.solid_stress, "allowable_MPa": s.allowable_shear_stress,
                              "installed_length_for_preload_mm": self.spring_installed_length_for_preload}
        if self.beam is not None:
            b = self.beam
            out["beam_pinion"] = {"span_mm": b.span, "mesh_position_mm": b.mesh_position,
                                  "zero_slope_position_mm": b.zero_slope_position, "stiffness_N_per_mm": b.stiffness,
                                  "force_N": b.force, "deflection_mm": b.deflection, "slope_at_mesh_rad": b.slope_at_mesh,
                                  "face_misalignment_mm": b.face_misalignment, "max_stress_MPa": b.max_stress}
        if self.engagement is not None:
            g = self.engagement
            out["engagement"] = {"lead_mm": g.lead, "relative_rotation_rad": g.relative_rotation,
                                 "opening_rate_rad_per_mm": g.opening_rate,
                                 "opening_at_reference_circle_mm_per_mm": g.circumferential_rate,
                                 "turn_rate_rad_per_mm": {f"{m.gear}-{m.mate}": m.turn_rate
                                                          for m in (g.engaging, g.other) if m is not None},
                                 "backlash_mm": g.backlash, "preload_windup_mm": g.preload_windup,
                                 "leader_stops_mm": [g.leader_retracted_stop, g.leader_engaged_stop],
                                 "trailer_stops_mm": [g.trailer_retracted_stop, g.trailer_engaged_stop]}
        return out


def _design_loop_errors(sd: StiffnessDesign, lever: float | None) -> list[LoopError]:
    p = sd.preload
    if p.loop_error_rotation is not None:
        return [LoopError("design", p.loop_error_rotation, None, "design")]
    if p.loop_error_carriage_travel is not None:
        if lever is None:
            raise DesignError("preload.loop_error_carriage_travel", "this drive has no preload carriage",
                              "loop_error_rotation_* at the output")
        return [LoopError("design", float(loop_error_from_carriage_travel(p.loop_error_carriage_travel, lever)),
                          p.loop_error_carriage_travel, "design")]
    return []


def loop_errors_from_travels(travels: Mapping[str, float], lever: float, source: str = "synthesis") -> list[LoopError]:
    """Loop errors from carriage travels (mm) such as the synthesis budget ``{"sum": .., "rss": .., "mean": ..}``."""
    return [LoopError(label, float(loop_error_from_carriage_travel(t, lever)), float(t), source)
            for label, t in travels.items()]


@dataclass(frozen=True)
class StiffnessInputs:
    """What the stiffness summary reads of a design, read and validated once: its stiffness-step
    sections, drive type and preload method, the units its text speaks, its gears by name and the
    train ``[stiffness] train`` names (the resolved drive carries them:
    :attr:`geargen.model.layout.ResolvedSettings.stiffness_inputs`)."""

    name: str
    length_unit: str
    sections: StiffnessDesign
    drive_type: str
    preload_method: str | None
    text_units: TextUnits
    gears: Mapping[str, Any]
    train: DualPinionTrain | SplitPinionTrain | None


def stiffness_inputs(design, sections: StiffnessDesign | None = None) -> StiffnessInputs:
    """The :class:`StiffnessInputs` of ``design`` (``sections``: its stiffness-step sections if already
    read); refuses a design without ``[preload]`` or a drive type, naming the key."""
    sd = sections if sections is not None else stiffness_design(design)
    if sd.preload is None:
        raise DesignError("preload", "missing", "a [preload] section with max_output_torque_*")
    if design.drive_type is None:
        raise DesignError("drive.type", "missing", "'type1', 'type2'")
    return StiffnessInputs(design.name, design.length_unit, sd, design.drive_type, design.preload_method, design.text_units, design.gears,
                           drive_train(design, sd.stiffness))


def stiffness_summary(design, carriage_travels: Mapping[str, float] | None = None,
                      travel_source: str = "synthesis", components=None,
                      beam_supports: tuple[float, float] | None = None,
                      placed_lever: float | None = None, placed_friction: float = 0.0) -> StiffnessSummary:
    """Path, drive and loop stiffness, preload and its variation, preload hardware of ``design`` (a
    design, or its :class:`StiffnessInputs` already read).

    ``beam_supports``: radial stiffness (N/mm) of the structure under the long pinion's lower and
    upper bearing (:meth:`geargen.drives.beam_pinion.shafts.DriveColumn.support_stiffness`); the beam pinion's
    spring is then the beam in series with them through its reactions. Default: rigid supports.

    ``carriage_travels`` (mm, peak-to-peak; e.g. the synthesis error budget by label) replace
    the loop error of the ``[preload]`` section when given. ``components``: the design's
    ``[stiffness.components]`` with the lengths of the placed shafts filled in
    (:func:`geargen.model.analysis.placed_components`); default: as the design gives them.
    ``placed_lever`` (rad/mm): output rotation of each path per unit preload motion where the
    resolved drive places it rather than a dual-pinion train (the axial preload's slide,
    :mod:`geargen.drives.axial_preload.place`); ``placed_friction``: the friction force of its sliding fit
    over the spring force (the preload band then includes the friction's, :class:`PreloadVariation`).
    """
    inputs = design if isinstance(design, StiffnessInputs) else stiffness_inputs(design)
    sd, train = inputs.sections, inputs.train
    spec, pre = sd.stiffness, sd.preload
    drive_type = inputs.drive_type
    warnings: list[str] = []
    u = inputs.text_units  # the warnings speak the design's units

    comps: list[ComponentStiffness] = []
    if isinstance(train, DualPinionTrain):
        comps += train_mesh_components(train, spec.elastic_modulus, spec.mesh_stiffness)
    comps += [component_stiffness(c, inputs.gears, spec, train) for c in (spec.components if components is None
                                                                          else components)]
    warnings += [f"{c.name}: {w}" for c in comps for w in c.warnings]
    path1, path2, common = split_paths(comps)
    for p in (path1, path2):
        if not p.components:
            raise DesignError("stiffness.components", f"{p.name} has no components", "components with scope each_path")
    k1, k2 = path1.stiffness, path2.stiffness

    method = inputs.preload_method
    lever = None
    if isinstance(train, DualPinionTrain) and method in ("radial", "axial"):
        lever = preload_lever(train, method, pre.line_of_action_angle)
    elif placed_lever is not None:
        lever = placed_lever

    # --- the preload spring (type 2) ---
    linear_parts: list[tuple[str, float]] = []
    torsional_parts: list[tuple[str, float]] = []
    flex = flex_design = flex_gauge = spring = None
    if sd.flexures is not None:
        f = sd.flexures
        flex = blade_flexure(f.count, f.thickness, f.length, f.width, f.elastic_modulus, f.allowable_stress,
                             f.travel, f.poisson_ratio)
        linear_parts.append(("flexures", flex.stiffness_along))
        if f.target_stiffness is not None:
            flex_design = design_blade_flexure(f.target_stiffness, f.travel, f.width, f.elastic_modulus,
                                               f.allowable_stress, f.count)
            flex_gauge = design_blade_flexure(f.target_stiffness, f.travel, f.width, f.elastic_modulus,
                                              f.allowable_stress, f.count, thickness=f.thickness)
    if sd.springs is not None:
        s = sd.springs
        spring = compression_spring(s.wire_diameter, s.mean_coil_diameter, s.active_coils, s.free_length,
                                    s.shear_modulus, s.allowable_shear_stress, s.end_type, s.installed_length)
        linear_parts.append(("springs", s.count * spring.rate))
    beam_spec = sd.beam_pinion
    beam_stiffness = None
    if beam_spec is not None:
        probe = sized_beam_pinion(inputs.gears, beam_spec)
        beam_stiffness = probe.stiffness
        if beam_supports is not None:
            # the supports give way under their reactions, (L - a)/L and a/L of the mesh force
            upper_share = probe.mesh_position / probe.span
            beam_stiffness = 1.0 / (1.0 / probe.stiffness + (1 - upper_share) ** 2 / beam_supports[0]
                                    + upper_share ** 2 / beam_supports[1])
        linear_parts.append(("beam pinion" if beam_supports is None else "beam pinion on its column", beam_stiffness))
    if pre.preload_spring_linear is not None:
        linear_parts.append(("preload spring", pre.preload_spring_linear))
    if pre.preload_spring_torsional is not None:
        torsional_parts.append(("preload spring", pre.preload_spring_torsional))

    preload_spring = None
    k3 = math.inf
    if drive_type == "type2":
        if not linear_parts and not torsional_parts:
            raise DesignError("preload.preload_spring_stiffness", "a type2 drive needs a preload spring",
                              "[springs], [flexures], [beam_pinion] or preload_spring_stiffness_*")
        if linear_parts and lever is None:
            raise DesignError("drive.preload", f"a linear preload spring needs radial or axial preload motion "
                              f"in a dual-pinion train (got {method!r})",
                              "preload = 'radial' | 'axial', or preload_spring_stiffness_Nm_per_rad at the output")
        preload_spring = PreloadSpring(lever, tuple(linear_parts), tuple(torsional_parts))
        k3 = preload_spring.stiffness
        if k3 > min(k1, k2) / 3.0:
            hint = ""
            if lever is not None and linear_parts and not torsional_parts:
                # k3 = k lambda^-2: the linear stiffness along the preload motion that gives a third of the path
                hint = (f"; a third of it needs {u.text('linear_stiffness', min(k1, k2) / 3.0 * lever ** 2)} along the "
                        f"preload motion (now {u.text('linear_stiffness', preload_spring.linear_stiffness)})")
            warnings.append(f"preload spring k3 = {u.text('torsional_stiffness', k3)} is not several times softer than a path "
                            f"({u.text('torsional_stiffness', min(k1, k2))}): the loop stiffness, and so the preload variation, "
                            f"is set by the paths{hint}")
    elif linear_parts or torsional_parts:
        raise DesignError("drive.type", "a type1 drive has no preload spring, but the design gives one "
                          f"({', '.join(n for n, _ in linear_parts + torsional_parts)})",
                          "type = 'type2', or remove the preload-spring sections")

    # --- the preload ---
    rule = required_preload(pre.max_output_torque, drive_type)
    fixed_forces = 0.0
    if flex is not None and sd.flexures.neutral_offset != 0.0:
        fixed_forces += flex.stiffness_along * sd.flexures.neutral_offset
    springs_set = sd.springs is not None and sd.springs.installed_length is not None
    if springs_set:
        fixed_forces += sd.springs.count * spring.installed_force
    if pre.preload is not None:
        if springs_set:
            raise DesignError("preload.preload", "the preload is set twice: by preload_* and by the springs' "
                              "installed length", "one of preload_* and springs.installed_length_*")
        preload, source = pre.preload, "design"
    elif springs_set:
        if lever is None:
            raise DesignError("springs.installed_length", "no preload carriage to turn a spring force into preload",
                              "radial or axial preload in a dual-pinion train")
        preload, source = fixed_forces / (2.0 * lever), "springs (installed length)"
    else:
        preload, source = rule, "paper rule (no preload given)"
    if preload < 0:
        raise DesignError("flexures.neutral_offset", "the carriage forces pull the gears out of mesh (negative preload)",
                          "a larger spring force or a positive neutral offset")
    drive = TwoPathDrive(drive_type, k1, k2, preload, k3)
    to_carry = preload_to_carry(pre.max_output_torque, drive_type, k1, k2, k3)
    fe = None if lever is None else float(carriage_force(preload, lever))
    if preload < rule * (1 - 1e-12):
        warnings.append(f"preload {u.text('torque', preload)} is below the paper's recommendation "
                        f"{u.text('torque', rule)} ({'half ' if drive_type == 'type2' else ''}the maximum load)")
    t_lo, t_hi = drive.unloading_torques
    if min(-t_lo, t_hi) < pre.max_output_torque * (1 - 1e-12):
        warnings.append(f"a path unloads at {u.text('torque', min(-t_lo, t_hi))}, below the maximum load "
                        f"{u.text('torque', pre.max_output_torque)}")

    # spring length for this preload when the springs do not set it
    installed_for_preload = None
    if spring is not None and fe is not None and not springs_set:
        per_spring = (fe - fixed_forces) / sd.springs.count
        installed_for_preload = sd.springs.free_length - per_spring / spring.rate
    if spring is not None:
        if spring.installed_length is not None and spring.installed_length <= spring.solid_height:
            warnings.append("springs: installed length is at or below the solid height")
        if spring.installed_stress > spring.allowable_shear_stress:
            warnings.append(f"springs: installed stress {u.text('stress', spring.installed_stress)} exceeds the allowable "
                            f"{u.text('stress', spring.allowable_shear_stress)}")
        if not spring.solid_safe:
            warnings.append(f"springs: closed solid the stress would be {u.text('stress', spring.solid_stress)} "
                            f"(allowable {u.text('stress', spring.allowable_shear_stress)}); keep them off solid")

    # --- loop errors and the preload band ---
    if carriage_travels:
        if lever is None:
            raise DesignError("drive.preload", "carriage travels need a preload carriage", "radial or axial preload")
        errors = loop_errors_from_travels(carriage_travels, lever, travel_source)
        headline = pre.loop_error_budget if pre.loop_error_budget in carriage_travels else next(iter(carriage_travels))
    else:
        errors = _design_loop_errors(sd, lever)
        headline = "design" if errors else None
    variations = tuple(preload_variation(drive, e.rotation, e.label, e.carriage_travel, e.source, placed_friction)
                       for e in errors)
    for v in variations:
        if v.unloads:
            warnings.append(f"loop error ({v.label}) unloads the preload: band {u.value('torque', v.low):.4g} to {u.text('torque', v.high)}")
        elif v.low < rule * (1 - 1e-12) and v.label == headline:
            warnings.append(f"loop error ({v.label}) takes the preload down to {u.text('torque', v.low)}, below the "
                            f"recommended {u.text('torque', rule)}")

    # --- flexure travel and stress ---
    if flex is not None:
        needed = abs(sd.flexures.neutral_offset) + max((v.carriage_travel or 0.0) for v in variations) / 2.0 \
            if variations else abs(sd.flexures.neutral_offset)
        if needed > flex.travel * (1 + 1e-12):
            warnings.append(f"flexures: the loop error needs {u.text('length', needed)} of travel from neutral, more than the "
                            f"{u.text('length', flex.travel)} designed")
        if not flex.stress_ok:
            warnings.append(f"flexures: stress {u.text('stress', flex.stress_at_travel)} at {u.text('length', flex.travel)} exceeds the "
                            f"allowable {u.text('stress', flex.allowable_stress)}")

    # --- beam pinion at the preload force ---
    beam = None
    if beam_spec is not None:
        pin = _beam_gear(inputs.gears, beam_spec.gear)
        force = (fe - fixed_forces) if fe is not None else 0.0
        beam = beam_pinion(probe.diameter, beam_spec.elastic_modulus, force, span=probe.span,
                           mesh_position=probe.mesh_position, face_width=pin.face_width,
                           allowable_stress=beam_spec.allowable_stress)
        if beam.stress_ok is False:
            warnings.append(f"beam pinion: stress {u.text('stress', beam.max_stress)} exceeds the allowable {u.text('stress', beam.allowable_stress)}")
        if abs(beam.zero_slope_offset) > 1e-9 * beam.span:
            warnings.append(f"beam pinion: the mesh is {u.value('length', beam.zero_slope_offset):+.4g} {u.length} from the zero-slope point "
                            "(put the bearings symmetric about the mesh)")

    # --- helical engagement ---
    engagement = None
    if sd.engagement is not None:
        eg = sd.engagement
        gear = _beam_gear(inputs.gears, eg.gear, "engagement.gear")
        windup = eg.preload_windup
        if windup is None:
            ratio = None if train is None else train.gear_ratio(eg.gear)
            if ratio is None:
                raise DesignError("engagement.preload_windup", "missing (the gear is not in the train)",
                                  "preload_windup_* circumferential at its reference circle")
            # the loop deflection at the preload, as relative rotation of the pinions, at the reference circle
            windup = preload / drive.loop_stiffness * ratio * gear.reference_radius
        # the whole cluster slides: its other gear's helix turns it too (geargen.core.flexures.helical_engagement)
        engaging, other = (_sliding_mesh(inputs.gears, g, m) for g, m in engagement_meshes(eg.gear, spec))
        engagement = helical_engagement(engaging, eg.backlash, windup, eg.engagement_length or gear.face_width,
                                        eg.clearance, other=other)

    # --- gears on placed shafts: deflection and tilt under the preload's mesh force ---
    supports = []
    used = {c.name: c for c in (spec.components if components is None else components)}
    for comp in comps:
        c = used.get(comp.name)
        if c is None or c.kind != "shaft_support":
            continue
        e = c.elastic_modulus or spec.elastic_modulus
        compliance, tilt, _ = supported_gear_response(c, e)
        force = preload / (comp.ratio * comp.radius)  # the path's preload torque as mesh force at the gear
        sup = SupportDeflection(c.name, c.gear, force, force * compliance, force * tilt,
                                inputs.gears[c.gear].face_width)
        supports.append(sup)
        if sup.misalignment > MISALIGNMENT_WARNING:
            warnings.append(f"{c.name}: at the preload's mesh force {u.text('force', force)} gears.{c.gear} deflects "
                            f"{u.small_length(sup.deflection)} and tilts {sup.tilt * 1e6:.4g} urad: "
                            f"{u.small_length(sup.misalignment, 3)} of misalignment across its {u.text('length', sup.face_width)} face "
                            f"(more than {u.small_length(MISALIGNMENT_WARNING, 3)}: the flank contact moves to one end)")

    location = spec.reduce_to
    ratios = {"output": 1.0} if train is None else {s: train.shaft_ratio(s) for s in train.shafts}
    return StiffnessSummary(
        name=inputs.name, drive_type=drive_type, preload_method=method, location=location,
        location_ratio=ratios[location], shaft_ratios=ratios, length_unit=inputs.length_unit, units=inputs.text_units,
        components=tuple(comps), path1=path1,
        path2=path2, common=common, preload_spring=preload_spring, drive=drive,
        max_output_torque=pre.max_output_torque, preload_source=source, required_preload=rule,
        preload_to_carry=to_carry, carriage_force=fe, lever=lever, variations=variations, headline_budget=headline,
        path_backlash=pre.path_backlash, flexure=flex, flexure_design=flex_design,
        flexure_design_gauge=flex_gauge, spring=spring,
        spring_count=0 if sd.springs is None else sd.springs.count,
        spring_installed_length_for_preload=installed_for_preload, beam=beam, beam_supports=beam_supports,
        engagement=engagement,
        warnings=tuple(warnings), supports=tuple(supports))


def sized_beam_pinion(gears, beam_spec) -> BeamPinion:
    """The ``[beam_pinion]`` beam, unloaded: its span given, or sized for its target stiffness
    (``gears``: the design's gears by table name)."""
    pin = _beam_gear(gears, beam_spec.gear)
    diameter = beam_spec.diameter or 2.0 * pin.root_radius_standard
    return beam_pinion(diameter, beam_spec.elastic_modulus, 0.0, span=beam_spec.span,
                       mesh_position=beam_spec.mesh_position, target_stiffness=beam_spec.target_stiffness)


def _sliding_mesh(gears: Mapping[str, Any], gear: str, mate: str) -> SlidingMesh:
    """``gear`` of the sliding cluster against its ``mate`` (both named by the [stiffness] gear roles)."""
    g = _beam_gear(gears, gear, "engagement.gear")
    _beam_gear(gears, mate, "engagement.gear")
    return SlidingMesh(gear, mate, g.helix_angle, g.reference_radius, g.hand)


def _beam_gear(gears, name: str, where: str = "beam_pinion.gear"):
    if name not in gears:
        raise DesignError(where, f"no gear named {name!r} in the design", ", ".join(gears))
    return gears[name]


__all__ = [
    "MESH_DIVISOR", "mesh_stiffness", "gear_mesh_stiffness", "shaft_torsional_stiffness", "shaft_bending_stiffness",
    "supported_shaft_compliance", "series", "parallel",
    "reflect", "torsional_from_linear", "linear_from_torsional", "DualPinionTrain", "train_from_design",
    "SplitPinionTrain", "split_pinion_train", "drive_train", "StiffnessInputs", "stiffness_inputs",
    "ComponentStiffness", "component_stiffness", "train_mesh_components", "PathStiffness", "split_paths",
    "preload_lever", "preload_spring_at_output", "loop_error_from_carriage_travel", "carriage_force",
    "required_preload", "preload_to_carry", "LoopError", "PreloadVariation", "preload_variation", "PreloadSpring",
    "StiffnessSummary", "SupportDeflection", "MISALIGNMENT_WARNING", "loop_errors_from_travels", "stiffness_summary",
]
