"""The planetary stages of a resolved drive, checked as placed (:mod:`geargen.drives.planetary.place`).

Everything is read from the Layout's placements (centres, rotations, the modelled teeth):

- each planet-ring mesh on the exact outlines (:class:`geargen.families.internal.pair.RingMaterial`
  against the planet's sampled exact outline): the planet turned both ways from where it is placed,
  the ring held, until it touches (bisection): free play on both sides, its sum against the design
  range and against the closed form (:func:`geargen.drives.planetary.place.internal_backlash`),
  and over one planet pitch of mesh positions (:func:`ring_mesh_sweep`);
  and the internal pair's named checks (:func:`geargen.families.internal.pair.check_internal`:
  involute, tip and trochoid interference, radial-assembly fouling);
- the stage's conditions: coaxiality (planet-ring minus sun-planet zero-backlash working centre
  distance of the design's gears, within ``coaxiality_tolerance``), assembly (each placed planet's
  carrier angle times (z_s + z_r) / 2 pi whole), the neighbour clearance of the planets' tip circles.

The sun-planet meshes are :class:`MeshPlacement` meshes: the external checker has them.
"""

from __future__ import annotations

import math

import numpy as np

from geargen.checks.results import Failure
from geargen.units import LENGTH_SUFFIXES

#: the measured planet-ring backlash may differ from the closed form by this much (mm): the
#: bisection on outlines sampled 1e-3 m_n apart is far finer
PLANETARY_BACKLASH_TOLERANCE = 1e-4


def placed_ring_play(planet_spec, planet_centre, planet_rotation, ring_spec, ring_centre, ring_rotation,
                     step: float | None = None) -> tuple[float, float]:
    """Free rotation (rad) of the placed planet counter-clockwise and clockwise about its own
    centre, the ring held, on the exact outlines (both sections at the same height; rotations of
    that section). Negative both: the planet already overlaps the ring (the deepest point's
    depth over the planet's reference radius, as an angle)."""
    from geargen.families.internal.pair import RingMaterial, pinion_points, placed_points
    from geargen.profile.internal import internal_profile
    from geargen.profile.tooth import tooth_profile
    profile = tooth_profile(planet_spec, warn=False)
    material = RingMaterial(internal_profile(ring_spec))
    pts = pinion_points(profile, step or 1e-3 * planet_spec.module)
    centre = (planet_centre[0] - ring_centre[0], planet_centre[1] - ring_centre[1])

    def placed(turn: float, pts: np.ndarray) -> np.ndarray:
        return placed_points(pts, centre, planet_rotation + turn)

    # only the points a turn of up to one pitch can bring to the ring's teeth
    reach = np.hypot(*placed(0.0, pts).T)
    pts = pts[reach > material.ring.tip_radius - profile.tip_radius * 2 * math.pi / planet_spec.teeth]

    def depth(turn: float, pts: np.ndarray = pts) -> float:
        return float(np.max(material.depth(placed(turn, pts), ring_rotation)))

    d0 = depth(0.0)
    if d0 >= 0:
        return -d0 / planet_spec.reference_radius, -d0 / planet_spec.reference_radius
    pitch = 2 * math.pi / planet_spec.teeth
    out = []
    for sign in (1.0, -1.0):
        lo, hi = 0.0, 0.0
        while True:
            hi += 0.01 * pitch
            if depth(sign * hi) >= 0:
                break
            lo = hi
            if hi > pitch:
                raise ValueError("no contact within one pitch")
        # the bisection reads only the points that can reach the ring's tip circle between lo and hi:
        # a point |p| from the planet's centre moves at most |p| (hi - lo) / 2 from where it is at the
        # middle turn, so the others stay below the tip circle, at a negative depth, and "does any
        # point reach the ring?" has the same answer (1e-9 mm covers rounding; as free_play's)
        r_mid = np.hypot(*placed(sign * 0.5 * (lo + hi), pts).T)
        near = pts[r_mid + np.hypot(pts[:, 0], pts[:, 1]) * 0.5 * (hi - lo) + 1e-9 >= material.ring.tip_radius]
        while hi - lo > 1e-13:
            mid = 0.5 * (lo + hi)
            if depth(sign * mid, near) >= 0:
                hi = mid
            else:
                lo = mid
        out.append(0.5 * (lo + hi))
    return out[0], out[1]


#: mesh positions over one planet pitch at which the planet-ring backlash is measured
RING_SWEEP_POSITIONS = 8


def ring_mesh_sweep(planet, ring, centre_distance: float) -> tuple[float, float]:
    """Smallest and largest planet-ring backlash (mm, at the planet's reference circle) over
    :data:`RING_SWEEP_POSITIONS` mesh positions of one planet pitch, on the exact outlines
    (:func:`geargen.families.internal.pair.free_play`; the same for every planet of a stage: one
    geometry at one carrier radius)."""
    from geargen.families.internal.pair import RingMaterial, free_play
    from geargen.families.internal.geometry import internal_pair_geometry
    from geargen.profile.internal import internal_profile
    from geargen.profile.tooth import tooth_profile
    pair = internal_pair_geometry(planet, ring, centre_distance)
    profile, ring_profile = tooth_profile(planet, warn=False), internal_profile(ring)
    material = RingMaterial(ring_profile)
    values = []
    for phase in np.linspace(0.0, 2 * math.pi / planet.teeth, RING_SWEEP_POSITIONS, endpoint=False):
        play = free_play(pair, profile, ring_profile, float(phase), material=material)
        values.append(planet.reference_radius * (play.ccw + play.cw))
    return min(values), max(values)


def planetary_meshes(layout, result) -> list[dict]:
    """Rows (mm, rad) of every planet-ring mesh and every stage's conditions; the failures go to
    ``result.failures``."""
    from geargen.families.internal.pair import check_internal
    from geargen.core.planetary import planet_ring_working, sun_planet_working
    from geargen.drives.planetary.place import core_stage, internal_backlash, planet_part

    gears = layout.resolved.gears
    k, unit = LENGTH_SUFFIXES[layout.identity.length_unit], layout.identity.length_unit
    rows = []
    for st in layout.resolved.stages:
        if st.kind != "planetary":
            continue
        sun, ring = layout.gear(st.sun), layout.gear(st.ring)
        planets = [g for g in layout.gears if g.group == f"stage_{st.name}" and "planetary_planet" in g.roles]
        stage_name = f"stage_{st.name}"
        ring_spec, sun_spec = ring.spec, sun.spec
        z_s, z_r = sun_spec.teeth, ring_spec.teeth
        # the stage's conditions
        core = core_stage(gears, st)
        coax = planet_ring_working(core)[1] - sun_planet_working(core)[1]
        if abs(coax) > st.coaxiality_tolerance:
            result.failures.append(Failure("planetary_coaxiality", stage_name,
                                           f"planet-ring zero-backlash centre distance differs from the sun-planet one "
                                           f"by {coax / k:.4g} {unit} (allowed {st.coaxiality_tolerance / k:.4g} {unit}; "
                                           f"stages.{st.name}: the ring's profile shift)", "path_difference",
                                           abs(coax), st.coaxiality_tolerance))
        angles = [math.atan2(p.centre[1] - sun.centre[1], p.centre[0] - sun.centre[0]) for p in planets]
        steps = [phi * (z_s + z_r) / (2 * math.pi) for phi in angles]
        off = max(abs(x - round(x)) for x in steps)
        if off > 1e-9:
            result.failures.append(Failure("planetary_assembly", stage_name,
                                           f"a planet's carrier angle is {off:.4g} of an assembly step (2 pi / (z_s + "
                                           f"z_r)) off: stages.{st.name}.planets cannot all mesh sun and ring"))
        tip = max(p.spec.tip_radius for p in planets)
        gap = min((math.dist(p.centre, q.centre) - 2 * tip for i, p in enumerate(planets) for q in planets[i + 1:]),
                  default=math.inf)
        if not gap > st.planet_tip_clearance:
            result.failures.append(Failure("planet_neighbour_clearance", stage_name,
                                           f"neighbouring planets' tip circles are {gap / k:.4g} {unit} apart "
                                           f"(stages.{st.name}.planet_tip_clearance: > {st.planet_tip_clearance / k:.4g} "
                                           f"{unit})", "min_clearance", gap, st.planet_tip_clearance))
        a = math.dist(planets[0].centre, sun.centre)
        named = check_internal(planets[0].spec, ring_spec, a, mesh=f"{stage_name}_ring")
        sweep = ring_mesh_sweep(planets[0].spec, ring_spec, a)
        for i, p in enumerate(planets, start=1):
            name = f"{stage_name}_{planet_part(st.planet, i)}_ring"
            a_i = math.dist(p.centre, ring.centre)
            z = max(p.face_z(p.spec)[0], ring.face_z(ring_spec)[0])
            ccw, cw = placed_ring_play(p.spec, p.centre, p.rotation_at(p.spec, z), ring_spec, ring.centre,
                                       ring.rotation_at(ring_spec, z))
            measured = p.spec.reference_radius * (ccw + cw)
            closed = internal_backlash(p.spec, ring_spec, a_i)
            for f in named.failures:  # the same geometry for every planet: named per mesh
                result.failures.append(Failure(f.kind, name, f.message, f.quantity, f.value, f.limit))
            if min(ccw, cw) < 0:
                result.failures.append(Failure("flank_interference", name, f"the planet overlaps the ring by "
                                               f"{-min(ccw, cw) * p.spec.reference_radius / k:.4g} {unit} as placed",
                                               "circumferential_backlash", min(ccw, cw) * p.spec.reference_radius, 0.0))
            elif min(ccw, cw) == 0:
                result.failures.append(Failure("no_backlash", name, "the planet touches the ring on both sides",
                                               "circumferential_backlash", 0.0, 0.0))
            elif not (st.backlash_min - 1e-6 <= min(measured, sweep[0])
                      and max(measured, sweep[1]) <= st.backlash_max + 1e-6):
                worst = min(measured, sweep[0]) if min(measured, sweep[0]) < st.backlash_min else max(measured, sweep[1])
                result.failures.append(Failure("backlash_out_of_range", name,
                                               f"planet-ring backlash {worst / k:.6g} {unit} (as placed, or over a "
                                               f"planet pitch of mesh positions) is outside the design range "
                                               f"{st.backlash_min / k:.6g} to {st.backlash_max / k:.6g} {unit}",
                                               "circumferential_backlash", worst,
                                               st.backlash_min if worst < st.backlash_min else st.backlash_max))
            elif abs(measured - closed) > PLANETARY_BACKLASH_TOLERANCE:
                result.failures.append(Failure("paths_disagree", name,
                                               f"planet-ring backlash measured {measured / k:.6g} {unit}, closed form "
                                               f"{closed / k:.6g} {unit}", "path_difference", abs(measured - closed),
                                               PLANETARY_BACKLASH_TOLERANCE))
            rows.append(dict(table="planetary", mesh=name, gear1=p.name, gear2=ring.name, stage=st.name, centre_distance=a_i,
                             backlash=measured, closed_form_backlash=closed, play_ccw=ccw * p.spec.reference_radius,
                             play_cw=cw * p.spec.reference_radius, design_min=st.backlash_min,
                             design_max=st.backlash_max, carrier_angle=angles[i - 1],
                             sweep_min=sweep[0], sweep_max=sweep[1],
                             margins={m: v for m, v in named.margins.items()},
                             contact_ratio=named.geometry.contact_ratio,
                             where="planet's reference circle, circumferential, on the exact outlines as placed"))
        rows.append(dict(table="planetary", mesh=stage_name, stage=st.name, ratio=float(st.ratio(gears)), carrier_radius=a,
                         coaxiality_difference=coax, coaxiality_tolerance=st.coaxiality_tolerance,
                         assembly_step_error=off, neighbour_tip_gap=gap, planet_tip_clearance=st.planet_tip_clearance,
                         planets=len(planets), minimum_tooth_difference=named.minimum_tooth_difference))
    return rows


__all__ = ["PLANETARY_BACKLASH_TOLERANCE", "RING_SWEEP_POSITIONS", "placed_ring_play", "ring_mesh_sweep",
           "planetary_meshes"]
