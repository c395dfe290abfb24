"""The load each flank of every mesh of a resolved drive carries over the duty (pure, numpy).

:func:`mesh_loads` takes the resolved drive (:class:`geargen.model.layout.Layout`), its stiffness
summary (:func:`geargen.model.analysis.stiffness`: the two-path model
:class:`geargen.core.drive.TwoPathDrive` at the output, k1, k2, k3 and the loop preload P) and
the duty (:class:`geargen.design.duty.DutySpec`) and gives, per mesh, the nominal tangential load
F_t at gear 1's reference circle for the preload alone and for every level of the spectrum.

**Flanks.** A flank of a mesh is named by the sense in which gear 1 turns when it drives through
that flank, seen from +z (the gear axes of the layout): flank "ccw" is the flank of gear 1 that
leads, and pushes gear 2, when gear 1 turns counter-clockwise, with the flank of gear 2 it touches.
It is the convention of :attr:`geargen.model.layout.MeshPlacement.working_flank`, whose word
"ccw"/"cw" is gear 1's sense: a preloaded mesh's working flank is the one its path's preload
loads. A planetary stage's meshes are seen from the carrier (sun, planet and ring turn relative
to it). The two flanks of a gear are told apart by the way each faces: gear 1's loaded flank, and
an external gear 2's, faces gear 1's sense, an internal gear 2's the opposite sense.

**Signs.** A positive output torque is one that path 1 carries in the sense of its own preload
(path 1 carries +P at zero drive torque, :class:`~geargen.core.drive.TwoPathDrive`; the stiff path
of a type 1, the cluster "a" of a dual pinion, the path of a [stiffness] mesh component of scope
path1). Each path's meshes are loaded on their working flank only: a path never reverses, it
unloads into its backlash.

**The loop (Hale & Slocum Eqs. 2-6).** The torques the two paths carry at the output for a drive
torque T are :meth:`TwoPathDrive.path_torques` at :meth:`TwoPathDrive.rotation` (T): while both
are loaded ``f1 = P + g1 T / k_D`` and ``f2 = -P + g2 T / k_D`` (type 2: Eq. 5's k_D with the
preload spring k3, ``g1 = k1 (2 k2 + k3) / (k1 + k2 + k3)``, equal paths P +- T/2; type 1: k_D =
k1 + k2 of Eq. 2, ``g = k``: the stiff path takes k1/(k1 + k2) of T, what the compliant one does
not); beyond the torque that unloads a path (2P for equal type 2 paths, about P for the stiff path
of a type 1) the other carries all of T. A mesh whose gear 2 turns n_2 times as fast as the output
carries ``F_t = |f| / (n_2 r_2)`` at the reference circles (r_2 gear 2's reference radius; the
force is the same at either gear's reference circle), losses neglected.

**Upstream stages** (pair stages, a planetary stage, the robot joint's bevel pair) are not
preloaded: each carries the drive torque T only, ``|T| / (n_1 r_1)`` on the flank T's sign gives; a
planetary stage's sun shares its torque equally between its planets (a floating sun's ideal, as
``geargen train`` takes it), each planet carrying the same F_t at the sun and at the ring. The
bevel pair and an upstream stage without gear tables (a bought gearhead) are listed with the
torque they carry and why they are not rated here.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from geargen.core.load_capacity import rating_scope
from geargen.design.duty import DutySpec
from geargen.families.registry import tooth_form

#: where a load comes from: the preload alone (zero drive torque); the preload with the path's share of
#: the drive torque (both paths loaded); all of the drive torque (the other path unloaded); the drive
#: torque of a stage outside the loop
PRELOAD, SHARED, ALONE, DRIVE = SOURCES = ("preload", "preload and drive share", "drive torque, the other path unloaded",
                                          "drive torque")


@dataclass(frozen=True)
class FlankLoad:
    """One load a mesh carries: ``tangential_load`` F_t at gear 1's reference circle (N) on
    ``flank`` (gear 1's "ccw" or "cw", see the module); ``source`` one of :data:`SOURCES`;
    ``output_torque`` the drive torque at the output (N·mm, signed; 0 for the preload alone);
    ``path_torque`` the torque this mesh's path carries at the output (N·mm, positive; the drive
    torque itself outside the loop); ``share`` of the life (None: the preload alone, rated as if
    it acted for the whole life); ``level`` the duty level it belongs to (from 1; None: the preload)."""

    flank: str
    tangential_load: float
    source: str
    output_torque: float
    path_torque: float
    share: float | None
    level: int | None


@dataclass(frozen=True)
class MeshLoads:
    """The loads of one mesh over the duty.

    ``role``: "path 1" or "path 2" (the preloaded loop), "stage NAME", "stage NAME sun-planet"
    or "... planet-ring", "upstream Z1:Z2". ``speed``: gear 1's speed over the output's (relative
    to the carrier for a planetary mesh). ``torque_per_output``: gear 1's torque per N·mm of the
    torque its path (or the drive) carries at the output. ``preload``: F_t of the preload alone on
    ``working_flank`` (N; None outside the loop). ``load_cycles_per_turn``: how often one flank of
    each gear is loaded per turn (a sun meshing with 3 planets: 3). ``reversed_bending``: per gear,
    whether its teeth are loaded on both flanks (both flanks of this mesh, or the other flank by a
    mesh over the same face). ``scope``: None when ISO 6336 rates the mesh; else why it is not rated.
    """

    name: str
    role: str
    part1: str
    part2: str
    gear1: object
    gear2: object
    centre_distance: float | None
    speed: float
    torque_per_output: float
    preload: float | None
    working_flank: str | None
    loads: tuple[FlankLoad, ...]
    load_cycles_per_turn: tuple[float, float] = (1.0, 1.0)
    reversed_bending: tuple[bool, bool] = (False, False)
    scope: str | None = None

    @property
    def peak_load(self) -> float:
        """The largest F_t (N) on either flank; 0 without loads."""
        return max((load.tangential_load for load in self.loads), default=0.0)


def flipped(sense: str) -> str:
    return "cw" if sense == "ccw" else "ccw"


def gear_sense(working_flank: str) -> str | None:
    """Gear 1's sense in a :attr:`MeshPlacement.working_flank` ("input ccw", "pinion cw (stiff path)")."""
    found = re.search(r"\b(ccw|cw)\b", working_flank or "")
    return found.group(1) if found else None


def loop_paths(layout, components) -> dict[str, int]:
    """The preloaded meshes of ``layout`` (those with a working flank, engaged) -> their path, 1 or 2:
    the path of the ``[stiffness]`` mesh component (``components``) of the same two gears with scope
    path1 or path2, else the cluster a dual pinion names "a" (path 1) or "b" (path 2)."""
    scoped = {}
    for c in components:
        if c.kind == "mesh" and c.scope in ("path1", "path2"):
            scoped[frozenset(c.gears)] = 1 if c.scope == "path1" else 2
    out = {}
    for m in layout.meshes:
        if not (m.working_flank and m.engaged):
            continue
        path = scoped.get(frozenset((m.gear1.name, m.gear2.name)))
        if path is None:
            path = 1 if m.name.endswith("_a") else 2 if m.name.endswith("_b") else None
        if path is not None:
            out[m.name] = path
    return out


def mesh_loads(layout, summary, duty: DutySpec) -> tuple[MeshLoads, ...]:
    """Every mesh of the resolved drive ``layout`` with the loads it carries over ``duty``, from the
    stiffness ``summary`` (see the module docstring): the loop's meshes first, then the upstream
    stages from the loop towards the motor."""
    drive = summary.drive
    spec = layout.resolved.stiffness.stiffness
    train = layout.resolved.drive_train
    speeds = _SpeedOf(train, spec.components)
    paths = loop_paths(layout, spec.components)
    levels = duty.signed_levels()
    torques = np.array([t for t, _, _ in levels], dtype=float)
    f1, f2 = drive.path_torques(drive.rotation(torques)) if levels else (np.zeros(0), np.zeros(0))
    carried = {1: [float(f) for f in f1], 2: [-float(f) for f in f2]}  # both positive (Python floats: JSON)
    out: list[MeshLoads] = []
    fastest = None  # (sense, speed) of path 1's fastest gear 1: it turns with the input
    for m in layout.meshes:
        if m.name not in paths:
            continue
        path = paths[m.name]
        sense = gear_sense(m.working_flank)
        speed2 = speeds(m.gear2.name)
        if speed2 is None or sense is None:
            out.append(_unrated(m, f"path {path}", "not rated: " + (
                f"the speed of {m.gear2.name} is not known (a custom [stiffness] train needs a component of kind "
                "mesh for this mesh)" if speed2 is None else f"its working flank {m.working_flank!r} names no sense")))
            continue
        speed1 = speed2 * m.gear2.teeth / m.gear1.teeth
        per_output = 1.0 / speed1
        to_force = 1.0 / (speed2 * m.gear2.reference_radius)
        other = carried[3 - path]
        loads = [FlankLoad(sense, drive.preload * to_force, PRELOAD, 0.0, drive.preload, None, None)]
        for (torque, share, number), own, theirs in zip(levels, carried[path], other):
            if own <= 0.0:
                continue  # this path is unloaded at this level: no load, no damage
            source = SHARED if theirs > 0.0 else ALONE
            loads.append(FlankLoad(sense, own * to_force, source, torque, own, share, number))
        if drive.preload == 0.0:
            loads = loads[1:]
        out.append(MeshLoads(m.name, f"path {path}", m.part1, m.part2, m.gear1, m.gear2, m.centre_distance,
                             speed1, per_output, drive.preload * to_force, sense, tuple(loads)))
        if path == 1 and (fastest is None or speed1 > fastest[1]):
            fastest = (sense, speed1)
    out += _upstream(layout, train, levels, fastest[0] if fastest else "ccw")
    return _with_reversed_bending(layout, tuple(out))


class _SpeedOf:
    """A gear's speed over the output's: from the teeth in a train geargen models, else from the
    ratio of the custom train's mesh component acting at it (its second gear)."""

    def __init__(self, train, components):
        self.train = train
        self.typed = {c.gears[1]: c.ratio for c in components if c.kind == "mesh" and c.ratio is not None}

    def __call__(self, gear: str) -> float | None:
        if self.train is not None:
            return self.train.gear_ratio(gear)
        return self.typed.get(gear)


def _unrated(m, role: str, scope: str) -> MeshLoads:
    return MeshLoads(m.name, role, m.part1, m.part2, m.gear1, m.gear2, m.centre_distance, math.nan, math.nan, None,
                     None, (), scope=scope)


def _level_loads(levels, positive: str, to_force: float) -> tuple[FlankLoad, ...]:
    """The drive torque's loads of a mesh outside the loop: F_t = |T| to_force on the flank of T's sign."""
    return tuple(FlankLoad(positive if t > 0 else flipped(positive), abs(t) * to_force, DRIVE, t, abs(t), share, number)
                 for t, share, number in levels if t != 0.0)


def _upstream(layout, train, levels, input_sense: str) -> list[MeshLoads]:
    """The stages between the motor and the loop, from the loop towards the motor."""
    out: list[MeshLoads] = []
    shaft_sense = input_sense  # the sense, at positive output torque, of the shaft the next stage drives
    for st in reversed(layout.resolved.stages):
        if st.kind == "planetary":
            out += _planetary(layout, train, st, levels, shaft_sense)
            continue
        m = layout.mesh(f"stage_{st.name}")
        driver_sense = flipped(shaft_sense)  # an external pair turns its gears opposite ways
        speed1 = train.gear_ratio(st.driver)
        loads = _level_loads(levels, driver_sense, 1.0 / (speed1 * m.gear1.reference_radius))
        out.append(MeshLoads(m.name, f"stage {st.name}", m.part1, m.part2, m.gear1, m.gear2, m.centre_distance,
                             speed1, 1.0 / speed1, None, None, loads))
        shaft_sense = driver_sense
    if not layout.resolved.stages:
        speed = float(layout.ratio.get("train", 1))
        for z1, z2 in reversed(list(layout.settings.get("upstream_stages", ()))):
            out.append(_upstream_pair(layout, int(z1), int(z2), speed))
            speed *= z2 / z1
    return out


def _upstream_pair(layout, z1: int, z2: int, driven_speed: float) -> MeshLoads:
    """An upstream stage known by its teeth only ([layout] upstream_stages): the robot joint's
    bevel pair when [parts] places one of these teeth, else a stage without gears."""
    from geargen.drives.dual_pinion.bevel import bevel_drive
    placed = bevel_drive(layout) if layout.resolved.has("parts") else None
    speed1 = driven_speed * z2 / z1
    name = f"upstream {z1}:{z2}"
    if placed is not None and (placed.pinion.teeth, placed.gear.teeth) == (z1, z2):
        return MeshLoads(name, name + " (bevel)", "bevel_pinion", "bevel_gear", placed.pinion, placed.gear, None,
                         speed1, 1.0 / speed1, None, None, (), scope=rating_scope(placed.pinion))
    return MeshLoads(name, name, f"{z1} T", f"{z2} T", None, None, None, speed1, 1.0 / speed1, None, None, (),
                     scope="not rated: the stage has no gear tables in the design (a bought gearhead: its maker "
                           "rates it for the torque shown)")


def _planetary(layout, train, st, levels, carrier_sense: str) -> list[MeshLoads]:
    """The sun-planet and planet-ring meshes of a planetary stage (ring fixed, sun in, carrier on
    the shaft the loop's input turns), in the carrier's frame."""
    group = [g for g in layout.gears if g.group == f"stage_{st.name}"]
    ring = next(g for g in group if "planetary_ring" in g.roles)
    planets = [g for g in group if "planetary_planet" in g.roles]
    k = len(planets)
    sun_speed = train.gear_ratio(st.sun)
    carrier = sun_speed / float(st.ratio(layout.resolved.gears))
    relative = sun_speed - carrier  # the sun in the carrier's frame: the same sense as the carrier
    out = []
    for i, planet in enumerate(planets):
        m = next((mm for mm in layout.meshes if mm.name.startswith(f"stage_{st.name}_sun_")
                  and mm.part2 == planet.name), None)
        if m is None:  # a planet not placed in mesh with the sun carries nothing
            continue
        # the sun's torque, |T| / n_sun, shared by the k planets at the sun's reference radius
        to_force = 1.0 / (sun_speed * m.gear1.reference_radius * k)
        loads = _level_loads(levels, carrier_sense, to_force)
        out.append(MeshLoads(m.name, f"stage {st.name} sun-planet", m.part1, m.part2, m.gear1, m.gear2,
                             m.centre_distance, relative, 1.0 / (sun_speed * k), None, None, loads,
                             load_cycles_per_turn=(float(k), 1.0)))
        # the planet turns the other way in the carrier's frame and drives the ring with the same F_t
        planet_speed = relative * m.gear1.teeth / m.gear2.teeth
        ring_loads = _level_loads(levels, flipped(carrier_sense), to_force)
        out.append(MeshLoads(f"stage_{st.name}_planet_ring_{i + 1}", f"stage {st.name} planet-ring", planet.name,
                             ring.name, m.gear2, ring.spec, m.centre_distance, planet_speed,
                             m.gear2.reference_radius * to_force, None, None, ring_loads,
                             load_cycles_per_turn=(1.0, float(k))))
    return out


def _contact_height(layout, part: str, gear, mate_part: str, mate) -> tuple[float, float] | None:
    """The height range (world z) over which the faces of a mesh's two gears overlap."""
    try:
        a, b = layout.gear(part).face_z(gear), layout.gear(mate_part).face_z(mate)
    except KeyError:
        return None
    return max(a[0], b[0]), min(a[1], b[1])


def _with_reversed_bending(layout, meshes: tuple[MeshLoads, ...]) -> tuple[MeshLoads, ...]:
    """Each mesh with, per gear, whether its teeth are loaded on both flanks: by this mesh's loads,
    or by another mesh loading the gear's other flank over an overlapping part of its face."""
    from dataclasses import replace
    seen: list[tuple[str, str, tuple[float, float] | None]] = []  # part, facing, contact heights
    for ml in meshes:
        height = _contact_height(layout, ml.part1, ml.gear1, ml.part2, ml.gear2)
        form = tooth_form(ml.gear2)
        concave = form is not None and form.curvature < 0  # a ring's loaded flank faces the pinion's way
        for load in ml.loads:
            seen.append((ml.part1, load.flank, height))
            seen.append((ml.part2, flipped(load.flank) if concave else load.flank, height))

    def both(part: str, height) -> bool:
        facings = {f for p, f, h in seen if p == part and _overlap(h, height)}
        return len(facings) > 1

    out = []
    for ml in meshes:
        height = _contact_height(layout, ml.part1, ml.gear1, ml.part2, ml.gear2)
        # a planet is loaded on one flank by the sun and on the other by the ring: an idler
        out.append(replace(ml, reversed_bending=(both(ml.part1, height), both(ml.part2, height))) if ml.loads else ml)
    return tuple(out)


def _overlap(a, b) -> bool:
    """Two height ranges share some face (an unknown range overlaps everything)."""
    if a is None or b is None:
        return True
    return min(a[1], b[1]) > max(a[0], b[0])


__all__ = ["SOURCES", "PRELOAD", "SHARED", "ALONE", "DRIVE", "FlankLoad", "MeshLoads", "mesh_loads", "loop_paths", "gear_sense", "flipped"]
