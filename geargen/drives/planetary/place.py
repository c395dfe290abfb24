"""A planetary upstream stage placed (:mod:`geargen.design.planetary_stage`): the one home of its
carrier radius, planet angles and every phase.

Sun and ring on the input gear's axis, the planets at the carrier radius ``a`` and the carrier
angles of :func:`geargen.core.planetary.assembly_angles`; all faces centred on one level. Phases
(:func:`geargen.core.planetary.planet_phases`): the sun's tooth 0 on +x, each planet and the ring
in the middle of both plays, in the level's lowest plane (carried to each gear's own face by its
helix). Tooth thickness as modelled: for a ``model_tooth_thickness`` point the sun and planet are
made at that point of their allowances (from the sun-planet backlash range at ``a``), then the
ring's spaces widened for the same backlash in the planet-ring mesh.

The meshes: each sun-planet mesh a :class:`MeshPlacement` (the external checker); the
planet-ring meshes are checked on the placed exact outlines by
:mod:`geargen.drives.planetary.verdict`, which reads the placements from the Layout.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from geargen.design.gear import GearSpec, with_changes
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES


@dataclass(frozen=True)
class PlacedPlanetary:
    """The placements and meshes of one planetary stage, its height (mm) and notes."""

    gears: list
    meshes: list
    notes: list
    height: float


def core_stage(gears, st, sun=None, planet=None, ring=None):
    """The stage ``st`` as :class:`geargen.core.planetary.PlanetaryStage` (the design's ``gears`` by
    table name, or the modelled ones given)."""
    from geargen.core.planetary import PlanetaryStage
    s, p, r = (g if g is not None else gears[n] for g, n in ((sun, st.sun), (planet, st.planet), (ring, st.ring)))
    return PlanetaryStage(s.teeth, p.teeth, r.teeth, st.planets, s.module, s.pressure_angle, s.helix_angle,
                          s.profile_shift, p.profile_shift, r.profile_shift, 2 * p.tip_radius,
                          st.planet_tip_clearance, st.coaxiality_tolerance)


def planet_part(planet: str, i: int) -> str:
    """Part name of planet ``i`` (from 1) of the gear table ``planet``."""
    return f"{planet}_{i}"


def internal_backlash(planet: GearSpec, ring: GearSpec, centre_distance: float) -> float:
    """Planet-ring backlash (mm) at ``centre_distance``, in the resolved model's kind
    (circumferential at the planet's reference circle: j_bt / cos alpha_t)."""
    from geargen.families.internal.geometry import internal_pair_geometry
    pair = internal_pair_geometry(planet, ring, centre_distance)
    return pair.backlash_transverse / math.cos(planet.transverse_pressure_angle)


def _modelled_gears(design, st, a: float, rule: str):
    from geargen.model.allowance import MeshRange, model_gears
    from geargen.model.layout import running_backlash
    sun, planet, ring = design.gear(st.sun), design.gear(st.planet), design.gear(st.ring)
    if rule == "as_designed":
        return sun, planet, ring, []
    made = model_gears(design, rule, [MeshRange(sun, planet, st.backlash_min, st.backlash_max, a, _range_keys(st))])
    sun, planet = made[sun.name], made[planet.name]
    target = running_backlash(sun, planet, a)  # the planet-ring mesh is given the sun-planet mesh's backlash
    ring0 = with_changes(ring, thinning=0.0)
    # widening the ring's spaces by t adds t to this backlash (both at the planet's reference circle)
    extra = target - internal_backlash(planet, ring0, a)
    if extra < -1e-12:
        raise DesignError(f"stages.{st.name}.carrier_radius", f"the planet-ring mesh already has "
                          f"{target - extra:.4g} mm of backlash at {a:.6g} mm, more than the {target:.4g} mm modelled",
                          "a carrier radius nearer the planet-ring zero-backlash distance, or ring profile shift")
    ring = with_changes(ring0, thinning=max(extra, 0.0))
    unit = design.length_unit
    k = LENGTH_SUFFIXES[unit]
    note = (f"stage {st.name}: thinning made at {rule} of each allowance: {st.sun} {sun.thinning / k:.6g}, "
            f"{st.planet} {planet.thinning / k:.6g}, {st.ring} {ring.thinning / k:.6g} (space widened for the same "
            f"backlash) {unit}")
    return sun, planet, ring, [note]


def _range_keys(st) -> tuple[str, str]:
    """The design keys of the stage's sun-planet backlash range (without their unit suffix)."""
    return f"stages.{st.name}.circumferential_backlash_min", f"stages.{st.name}.circumferential_backlash_max"


def place_planetary_stage(design, st, centre: tuple[float, float], level: float, rule: str) -> PlacedPlanetary:
    """Place the planetary stage ``st`` coaxial with ``centre`` from height ``level`` (mm)."""
    from geargen.core.planetary import assembly_angles, planet_phases, sun_planet_working
    from geargen.model.layout import GearPlacement, MeshPlacement, running_backlash
    from geargen.profile.tooth import section_rotation

    from geargen.design.parts import parts_settings
    parts = parts_settings(design)
    plate, gap = parts["carriage_plate_thickness"], parts["bearing_clearance"]
    if plate is None:
        raise DesignError("parts.carriage_plate_thickness", "missing: the planet carrier's plates are this thick",
                          "a length")
    stage = core_stage(design.gears, st)
    a = st.carrier_radius if st.carrier_radius is not None else sun_planet_working(stage)[1]
    sun, planet, ring, notes = _modelled_gears(design, st, a, rule)
    angles = assembly_angles(stage, equal_spacing=st.planet_spacing == "equal")
    height = max(g.face_width for g in (sun, planet, ring))
    # the carrier's lower plate from ``level``, the gears a bearing clearance above it
    base = level + plate + gap
    z = {g.name: base + (height - g.face_width) / 2 for g in (sun, planet, ring)}
    level = base
    sun_rotation = 0.0
    rho, ring_rotation = planet_phases(sun.teeth, planet.teeth, ring.teeth, sun_rotation, angles)
    group = f"stage_{st.name}"
    gears = [GearPlacement(st.sun, sun, tuple(centre), z[sun.name], sun_rotation - section_rotation(sun, level - z[sun.name]),
                           group, ("planetary_sun",)),
             GearPlacement(st.ring, ring, tuple(centre), z[ring.name],
                           ring_rotation - section_rotation(ring, level - z[ring.name]), group, ("planetary_ring",))]
    meshes = []
    lo = max(z[sun.name], z[planet.name])
    hi = min(z[sun.name] + sun.face_width, z[planet.name] + planet.face_width)
    modelled = running_backlash(sun, planet, a)
    for i, (phi, r) in enumerate(zip(angles, rho), start=1):
        name = planet_part(st.planet, i)
        c = (centre[0] + a * math.cos(phi), centre[1] + a * math.sin(phi))
        gears.append(GearPlacement(name, planet, c, z[planet.name],
                                   r - section_rotation(planet, level - z[planet.name]), group, ("planetary_planet",)))
        meshes.append(MeshPlacement(f"stage_{st.name}_sun_{name}", st.sun, sun, name, planet, (lo + hi) / 2,
                                    st.backlash_min, st.backlash_max, modelled, True, "", a, _range_keys(st)))
    unit = design.length_unit
    notes.append(f"stage {st.name}: planetary, {len(angles)} planets on the carrier radius "
                 f"{a / LENGTH_SUFFIXES[unit]:.6g} {unit} at "
                 + ", ".join(f"{math.degrees(phi):.6g}" for phi in angles) + " deg; its meshes are not in the "
                 "loop's stiffness model (taken as rigid); geargen train gives its lost motion and stiffness")
    return PlacedPlanetary(gears, meshes, notes, plate + gap + height + gap + plate)


@dataclass(frozen=True)
class Carrier:
    """The planet carrier of a placed planetary stage (mm): two plates of ``thickness`` on the
    stage's axis through ``centre``, the lower from ``z_lower`` (the input gear's shaft ends in
    its bore, ``bore``), the upper from ``z_upper`` (the motor shaft passes its ``hole``); each a
    bearing clearance from the gears; their ``radius`` reaches a pin diameter past the pins, which
    run through both plates at ``pins`` (the planets' centres), of the planets' bore."""

    name: str
    centre: tuple[float, float]
    z_lower: float
    z_upper: float
    thickness: float
    radius: float
    pins: tuple[tuple[float, float], ...]
    pin_diameter: float
    bore: float
    hole: float

    @property
    def top(self) -> float:
        return self.z_upper + self.thickness

    @property
    def lower_top(self) -> float:
        return self.z_lower + self.thickness


def carrier(layout, parts, st) -> Carrier:
    """The carrier of the planetary stage ``st`` as ``layout`` places it (sizes: [parts] plate
    thickness and clearance, the planets' bore, the input's and the sun's bores)."""
    from geargen.model.shafts import bore_of as _bore
    plate, gap = parts["carriage_plate_thickness"], parts["bearing_clearance"]
    sun = layout.gear(st.sun)
    planets = [g for g in layout.gears if g.group == f"stage_{st.name}" and "planetary_planet" in g.roles]
    members = [sun, layout.gear(st.ring)] + planets
    lo, hi = min(g.height[0] for g in members), max(g.height[1] for g in members)
    pin = _bore(planets[0].spec)
    if not pin > 0:
        raise DesignError(f"gears.{st.planet}.bore_diameter", "missing: the planets turn on carrier pins of this "
                          "diameter", "> 0")
    a = max(math.dist(p.centre, sun.centre) for p in planets)
    return Carrier(f"carrier_{st.name}", tuple(sun.centre), lo - gap - plate, hi + gap, plate, a + pin,
                   tuple(tuple(p.centre) for p in planets), pin, _bore(layout.gear("input").spec),
                   _bore(sun.spec) + 2 * gap)


__all__ = ["PlacedPlanetary", "Carrier", "core_stage", "planet_part", "internal_backlash", "place_planetary_stage", "carrier"]
