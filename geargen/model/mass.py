"""Mass properties of the resolved drive's rotating parts, from the parts' own geometry: no solid
is built (issue 28: ``geargen train`` in a fraction of a second).

A cylindrical gear is its exact transverse outline (sampled densely: the polygon's area and polar
moment converge as the square of the spacing) times its face width, less its bore, with its hub;
a one-piece cluster its two gears and the spacer between them; a double-helical gear its two
halves and the groove's cylinder in the gap (:func:`geargen.profile.tooth.centre_gap_radius`); a ring (internal gear) its rim less its teeth's outline; a bevel
gear of the hardware its family's closed forms (``toothed_mass``: the bevel's :func:`geargen.families.bevel.geometry.bevel_volume`,
:func:`~geargen.families.bevel.geometry.bevel_axial_moment`); a
hardware component its body (:func:`geargen.model.bodies.mass_properties`). All of unit density, in
the part's own frame: ``axial_moment`` about its own axis, the one it turns about.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from geargen.design.cluster import ClusterSpec
from geargen.families.registry import family_of, tooth_form
from geargen.model.bodies import MassProperties, mass_properties
from geargen.model.components import analytic_body
from geargen.profile.internal import internal_profile
from geargen.profile.segments import sample_outline
from geargen.profile.tooth import centre_gap_radius, tooth_profile

#: outline sampling step as a fraction of the module: the polygon's area and polar moment are then
#: within ~1e-6 of the exact outline's (measured against the kernel's integration of the gear
#: solids, tests/model/test_model_mass.py)
STEP_PER_MODULE = 0.01


def polygon_moments(points: np.ndarray) -> tuple[float, float]:
    """(area, integral of r^2 dA) of the closed polygon ``points`` (k, 2), counter-clockwise (mm^2, mm^4)."""
    x, y = points[:, 0], points[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cross = x * y1 - x1 * y
    area = float(np.sum(cross) / 2)
    polar = float(np.sum(cross * (x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1)) / 12.0)
    return area, polar


def _disc(radius: float) -> tuple[float, float]:
    return math.pi * radius ** 2, math.pi * radius ** 4 / 2


def bore_moments(hub) -> tuple[float, float]:
    """(area, polar moment) of the bore with its keyway (mm^2, mm^4), exactly: the bore's sector
    outside the keyway plus the pentagon from the axis through the keyway's corners."""
    rb = hub.bore_diameter / 2
    if rb <= 0:
        return 0.0, 0.0
    if hub.keyway_width <= 0:
        return _disc(rb)
    w2 = hub.keyway_width / 2
    a = math.asin(w2 / rb)
    xk, xf = math.sqrt(rb * rb - w2 * w2), rb + hub.keyway_depth
    sweep = 2 * math.pi - 2 * a
    pentagon = np.array([(0.0, 0.0), (xk, -w2), (xf, -w2), (xf, w2), (xk, w2)])
    area, polar = polygon_moments(pentagon)
    return sweep * rb * rb / 2 + area, sweep * rb ** 4 / 4 + polar


@lru_cache(maxsize=256)
def section_moments(spec) -> tuple[float, float]:
    """(area, polar moment) of a cylindrical gear's transverse section with its bore (mm^2, mm^4):
    an external gear's outline less the bore; a ring's rim disc less its teeth's outline."""
    form = tooth_form(spec)
    if form is not None and form.rim_outside_root:
        hole = sample_outline(internal_profile(spec).outline(), STEP_PER_MODULE * spec.module)
        area, polar = polygon_moments(hole)
        rim_area, rim_polar = _disc(spec.rim_diameter / 2)
        return rim_area - abs(area), rim_polar - abs(polar)
    outline = sample_outline(tooth_profile(spec, warn=False).outline(), STEP_PER_MODULE * spec.module)
    area, polar = polygon_moments(outline)
    bore_area, bore_polar = bore_moments(spec.hub)
    return abs(area) - bore_area, abs(polar) - bore_polar


def _hub(spec, side: str) -> tuple[float, float, float]:
    """(volume, first moment along z, axial moment) of a gear's hub: below its face (z < 0) or,
    ``side="top"``, above it (a cluster's small gear)."""
    hub = spec.hub
    if not hub.hub_length > 0:
        return 0.0, 0.0, 0.0
    bore_area, bore_polar = bore_moments(hub)
    area = math.pi * (hub.hub_diameter / 2) ** 2 - bore_area
    polar = math.pi * (hub.hub_diameter / 2) ** 4 / 2 - bore_polar
    middle = -hub.hub_length / 2 if side == "bottom" else spec.face_width + hub.hub_length / 2
    volume = area * hub.hub_length
    return volume, volume * middle, polar * hub.hub_length


def gear_mass(spec, hub_side: str = "bottom") -> MassProperties:
    """Mass properties of one cylindrical gear (external, helical, double helical, internal) in its
    own frame (its face from z = 0; its hub below, or above with ``hub_side="top"``)."""
    area, polar = section_moments(spec)
    face = spec.face_width
    volume, first, moment = area * face, area * face * face / 2, polar * face
    gap = getattr(spec, "centre_gap", 0.0)
    if gap > 0:  # the centre gap holds the groove's cylinder, not teeth
        h = spec.half_face_width
        ring_area, ring_polar = _disc(centre_gap_radius(spec, tooth_profile(spec, warn=False)))
        bore_area, bore_polar = bore_moments(spec.hub)
        volume = 2 * h * area + gap * (ring_area - bore_area)
        first = volume * face / 2  # symmetric about the gap's middle
        moment = 2 * h * polar + gap * (ring_polar - bore_polar)
    hv, hm, hj = _hub(spec, hub_side)
    volume, first, moment = volume + hv, first + hm, moment + hj
    return MassProperties(volume, (0.0, 0.0, first / volume), moment)


def cluster_mass(spec: ClusterSpec) -> MassProperties:
    """Mass properties of a one-piece cluster: its large gear from z = 0, the spacer, its small gear."""
    parts = []
    for gear, z0, side in ((spec.large, 0.0, "bottom"), (spec.small, spec.small_gear_z, "top")):
        m = gear_mass(gear, side)
        parts.append((m.volume, m.volume * (m.centre[2] + z0), m.axial_moment))
    if spec.axial_gap > 0:
        disc_area, disc_polar = _disc(spec.spacer_diameter_resolved / 2)
        bore_area, bore_polar = bore_moments(spec.large.hub)
        v = (disc_area - bore_area) * spec.axial_gap
        parts.append((v, v * (spec.large.face_width + spec.axial_gap / 2), (disc_polar - bore_polar) * spec.axial_gap))
    volume = sum(p[0] for p in parts)
    return MassProperties(volume, (0.0, 0.0, sum(p[1] for p in parts) / volume), sum(p[2] for p in parts))


def placed_gear_mass(placed) -> MassProperties:
    """Mass properties of a toothed part of the layout (:class:`geargen.model.GearPlacement`)."""
    return cluster_mass(placed.spec) if isinstance(placed.spec, ClusterSpec) else gear_mass(placed.spec)


def component_mass(component) -> MassProperties:
    """Mass properties of a hardware component: its body's, or a toothed part's closed forms."""
    closed = None if component.toothed is None else family_of(component.toothed.spec).toothed_mass(
        component.toothed.spec, component.toothed.back)
    if closed is not None:  # its family's closed forms (a bevel gear's); the centre is not needed
        volume, axial_moment = closed
        return MassProperties(volume, (0.0, 0.0, math.nan), axial_moment)
    return mass_properties(analytic_body(component))


__all__ = ["STEP_PER_MODULE", "polygon_moments", "section_moments", "gear_mass", "cluster_mass",
           "placed_gear_mass", "component_mass"]
