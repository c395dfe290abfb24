"""The resolved drive's parts checked against each other without building a solid: path 1 of the
parts check (the build's boolean intersections of the solids are path 2).

Every part is read as a signed distance (mm, negative inside) in the drive's frame: a hardware
component from its body (:mod:`geargen.model.bodies`), a gear from its exact transverse outline
(one pitch, folded: :func:`gear_section`) between its faces, turned with its helix. For each pair
of parts whose boxes meet, the volume they share is integrated on an octree: a cell is inside
both when both distances at its centre are below minus its half diagonal, outside when either is
above plus it, and split otherwise, down to cells of ``resolution`` mm, whose centres decide.
The same octree gives how close two parts come (for a joint, which must be a contact).

What fails is what the build's overlap check fails: two parts with no joint sharing more than
``tolerance`` mm^3 (``overlap``), two joined parts running into each other (``interpenetrating``),
a joint whose parts do not touch (``missing_contact``). Meshing pairs are the mesh checkers'.
Pure numpy: ``geargen check`` runs it on every design, ``geargen build`` beside the solids.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any, Callable

import numpy as np

from geargen.design.cluster import ClusterSpec
from geargen.errors import GeometryError
from geargen.families.registry import tooth_form
from geargen.model.bodies import PolygonDistance, column_distance_function, distance_cost, world_box
from geargen.model.components import analytic_body
from geargen.profile.internal import internal_profile
from geargen.profile.tooth import section_rotation, tooth_profile
from geargen.units import LENGTH_SUFFIXES, length_text

#: shared volume below which two parts only touch (mm^3; the build's overlap check uses the same)
OVERLAP_TOLERANCE = 1e-3
#: how far apart the two parts of a joint may be and still touch (mm; as the build's)
CONTACT_TOLERANCE = 1e-3
#: cells an octree level may hold; beyond, the undecided cells' centres decide (midpoint rule)
MAX_CELLS = 200_000


@dataclass(frozen=True)
class AnalyticPart:
    """A part as its world box and signed distance (world points (k, 3) -> (k,), mm); ``cost``: about
    how long its distance takes a point, relative to a cylinder's (:func:`closest_approach` reads the
    cheaper part of two first)."""

    name: str
    lo: np.ndarray
    hi: np.ndarray
    distance: Callable[[np.ndarray], np.ndarray]
    cost: float = 1.0


def _inverse(m: np.ndarray) -> np.ndarray:
    inv = np.eye(4)
    r = m[:3, :3]
    inv[:3, :3] = r.T
    inv[:3, 3] = -r.T @ m[:3, 3]
    return inv


def _local(points: np.ndarray, inverse: np.ndarray) -> list[np.ndarray]:
    """The points' coordinates (x, y, z) in the frame of ``inverse``, as three columns."""
    # column by column: numpy's matmul of a (k, 3) array by a 3 x 3 is ~6x slower than these sums
    x, y, z = points[:, 0], points[:, 1], points[:, 2]
    r, t = inverse[:3, :3], inverse[:3, 3]
    return [r[i, 0] * x + r[i, 1] * y + r[i, 2] * z + t[i] for i in range(3)]


def _axis_of(row: np.ndarray, shift: float) -> tuple[int, float] | None:
    """``(j, sign)`` when the frame's row ``row`` is ``sign`` times axis j exactly (the other two
    entries zeros) and its shift is not -0.0: then, for finite points, ``row . p + shift`` of
    :func:`_local` is ``shift + p_j`` or ``shift - p_j`` to the last bit (1 * p and -1 * p are exact,
    each zero term is a signed zero, which a nonzero sum absorbs and which ``+ shift`` turns into
    ``shift``'s own zero or value)."""
    nonzero = np.flatnonzero(row)
    if nonzero.size != 1 or abs(row[nonzero[0]]) != 1.0 or (shift == 0.0 and math.copysign(1.0, shift) < 0):
        return None
    return int(nonzero[0]), float(row[nonzero[0]])


def _local_function(inverse: np.ndarray):
    """:func:`_local` in the frame of ``inverse`` as a function of the points, each coordinate of
    a row along an axis (most parts are placed square: :func:`_axis_of`) read as one sum, the others
    as :func:`_local` reads them: the same numbers."""
    r, t = inverse[:3, :3], inverse[:3, 3]
    axes = [_axis_of(r[i], float(t[i])) for i in range(3)]
    if not any(axes):
        return lambda p: _local(p, inverse)

    def local(points):
        out = []
        for i, axis in enumerate(axes):
            if axis is None:
                out.append(r[i, 0] * points[:, 0] + r[i, 1] * points[:, 1] + r[i, 2] * points[:, 2] + t[i])
            else:
                j, sign = axis
                out.append(t[i] + points[:, j] if sign > 0 else t[i] - points[:, j])
        return out
    return local


def component_part(component) -> AnalyticPart:
    """A hardware component as an :class:`AnalyticPart` (its body, or a toothed part's envelope)."""
    body = analytic_body(component)
    lo, hi = world_box(body, component.placement)
    local = _local_function(_inverse(np.asarray(component.placement, float)))
    distance = column_distance_function(body)
    return AnalyticPart(component.name, lo, hi, lambda p: distance(*local(p)), distance_cost(body))


@lru_cache(maxsize=64)
def gear_section(spec) -> tuple[np.ndarray, float, float]:
    """One pitch of a cylindrical gear's transverse outline at its own z = 0, closed through the
    gear's centre: ``(polygon (m, 2), start angle, pitch angle)``. A point at polar angle phi is in
    the gear's section (for an internal gear: in its hole, the teeth's outline) when, turned back
    by whole pitches into [start, start + pitch), it lies in the polygon."""
    profile = internal_profile(spec) if _is_ring(spec) else tooth_profile(spec, warn=False)
    points = np.vstack([seg.sample(24)[:-1] for seg in profile.pitch_segments()])
    start = math.atan2(points[0, 1], points[0, 0])
    return np.vstack([[0.0, 0.0], points]), start, profile.pitch_angle


@lru_cache(maxsize=64)
def _section_polygon(spec) -> PolygonDistance:
    """The polygon of :func:`gear_section` for many distance calls (the parts check's octree), its
    grid over the box of the pitch sector's tooth band, where :func:`_section_distance` folds every
    point it asks about (not over the centre the polygon closes through; a point outside the grid
    is still measured, against every edge)."""
    polygon, start, pitch = gear_section(spec)
    radii = np.hypot(*polygon[1:].T)
    turn = np.linspace(start, start + pitch, 257)
    edge = np.concatenate([r * np.column_stack([np.cos(turn), np.sin(turn)]) for r in (radii.min(), radii.max())])
    lo, hi = edge.min(axis=0), edge.max(axis=0)
    pad = 1e-3 * (hi - lo)  # the arcs bulge past their 257 chords by (pitch / 256)^2 / 8 of the radius at most
    return PolygonDistance(polygon, box=(lo - pad, hi + pad))


def _is_ring(spec) -> bool:
    """Whether ``spec``'s body is a rim outside its teeth (its family's tooth form)."""
    form = tooth_form(spec)
    return form is not None and form.rim_outside_root


def _section_distance(spec, p: np.ndarray) -> np.ndarray:
    """Signed 2-D distance of gear-frame points from the outline of :func:`gear_section` (a bound
    outside the tooth band, where the nearest of the root and tip circles stands in)."""
    r = np.hypot(p[:, 0], p[:, 1])
    try:
        polygon, start, pitch = gear_section(spec)
    except GeometryError:  # teeth that cannot be drawn (the mesh check names why): read by their tip circle
        return r - spec.tip_radius  # an internal gear's hole: its tip circle
    # outside the tooth band the nearest circle bounds the distance (sign exact): no polygon needed
    root, tip = float(np.min(np.hypot(*polygon[1:].T))), float(np.max(np.hypot(*polygon[1:].T)))
    d2 = np.where(r < root, r - root, r - tip)
    band = (r >= root) & (r <= tip)
    if np.any(band):
        q = p[band]
        phi = np.arctan2(q[:, 1], q[:, 0]) - section_rotation(spec, q[:, 2])
        folded = start + np.mod(phi - start, pitch)
        d2[band] = _section_polygon(spec)(r[band] * np.cos(folded), r[band] * np.sin(folded))
    return d2


def _gear_distance(spec, p: np.ndarray) -> np.ndarray:
    """Signed distance (a bound) of gear-frame points from ``spec``'s body: its section between
    z = 0 and its face width, less its bore (hubs are not teeth: added apart); an internal gear's
    ring between its teeth and its rim."""
    r = np.hypot(p[:, 0], p[:, 1])
    if _is_ring(spec):
        d2 = np.maximum(r - spec.rim_diameter / 2, -_section_distance(spec, p))
    else:
        d2 = _section_distance(spec, p)
    bore = spec.hub.bore_diameter / 2 if hasattr(spec, "hub") else 0.0
    if bore > 0:
        d2 = np.maximum(d2, bore - r)
    dz = np.abs(p[:, 2] - spec.face_width / 2) - spec.face_width / 2
    out = np.hypot(np.maximum(d2, 0.0), np.maximum(dz, 0.0)) + np.minimum(np.maximum(d2, dz), 0.0)
    if hasattr(spec, "hub") and spec.hub.hub_length > 0:
        rh = spec.hub.hub_diameter / 2
        qr = np.maximum(r - rh, bore - r)
        qz = np.abs(p[:, 2] + spec.hub.hub_length / 2) - spec.hub.hub_length / 2
        hub = np.hypot(np.maximum(qr, 0.0), np.maximum(qz, 0.0)) + np.minimum(np.maximum(qr, qz), 0.0)
        out = np.minimum(out, hub)
    return out


def gear_part(placement, meshes=()) -> AnalyticPart:
    """A placed toothed part of the layout (:class:`geargen.model.GearPlacement`): a cylindrical
    gear or a cluster's two gears by their exact outlines; any other family by its envelope."""
    spec = placement.spec
    c, s = math.cos(placement.rotation), math.sin(placement.rotation)
    cx, cy = placement.centre
    members = [(g, placement.face_z(g)[0]) for g in placement.gears]

    def distance(p):
        x, y = p[:, 0] - cx, p[:, 1] - cy
        out = np.full(len(p), np.inf)
        for gear, z0 in members:
            local = np.column_stack([c * x + s * y, -s * x + c * y, p[:, 2] - z0])
            out = np.minimum(out, _member_distance(gear, local))
        return out

    reach = max(_reach(g) for g, _ in members)
    z_lo = min(z0 - (g.hub.hub_length if hasattr(g, "hub") else 0.0) for g, z0 in members)
    z_hi = max(z0 + g.face_width for g, z0 in members)
    if isinstance(spec, ClusterSpec) and spec.axial_gap > 0:
        spacer = spec.spacer_diameter_resolved / 2
        z_sp = placement.z + spec.large.face_width

        def distance(p, base=distance):  # noqa: F811 - the spacer between the cluster's gears
            r = np.hypot(p[:, 0] - cx, p[:, 1] - cy)
            qr = np.maximum(r - spacer, spec.large.hub.bore_diameter / 2 - r)
            qz = np.abs(p[:, 2] - z_sp - spec.axial_gap / 2) - spec.axial_gap / 2
            d = np.hypot(np.maximum(qr, 0.0), np.maximum(qz, 0.0)) + np.minimum(np.maximum(qr, qz), 0.0)
            return np.minimum(base(p), d)
    lo = np.array([cx - reach, cy - reach, z_lo])
    hi = np.array([cx + reach, cy + reach, z_hi])
    return AnalyticPart(placement.name, lo, hi, distance, GEAR_DISTANCE_COST * len(members))


#: a gear's distance (its section polygon, folded) per point, relative to a cylinder's (measured on
#: the shipped designs' parts check: 0.2-0.5 us a point against a shaft's 0.02-0.03)
GEAR_DISTANCE_COST = 12.0


def _reach(gear) -> float:
    if _is_ring(gear):
        return gear.rim_diameter / 2
    if _is_rack(gear):
        return math.hypot(gear.length, gear.height)
    return max(gear.tip_radius, gear.hub.hub_diameter / 2 if gear.hub.hub_length > 0 else 0.0)


def _is_rack(spec) -> bool:
    """Whether ``spec``'s teeth are straight-flanked (its family's tooth form): read by its box."""
    form = tooth_form(spec)
    return form is not None and form.curvature == 0


def _member_distance(gear, local: np.ndarray) -> np.ndarray:
    if not _is_rack(gear):
        return _gear_distance(gear, local)
    # a rack: its box (x across the teeth from its datum, y along it), an envelope
    dz = np.abs(local[:, 2] - gear.face_width / 2) - gear.face_width / 2
    lo = np.array([-gear.height, -gear.length / 2])
    hi = np.array([gear.addendum, gear.length / 2])
    qr = np.max(np.maximum(lo - local[:, :2], local[:, :2] - hi), axis=1)
    return np.hypot(np.maximum(qr, 0.0), np.maximum(dz, 0.0)) + np.minimum(np.maximum(qr, dz), 0.0)


# ============================================================================ the octree


@dataclass
class PairReading:
    """What the octree found of two parts: ``volume`` they share (mm^3, estimated at the finest
    cells), ``closest`` the least of max(d1, d2) over the cells visited (mm; about half the gap
    between them when apart, negative when they overlap) and ``near`` the cell centres that gave it."""

    volume: float
    closest: float
    near: np.ndarray = field(default_factory=lambda: np.empty((0, 3)))


#: points per call of a part's distance: the distances are point by point, and their numpy
#: temporaries at this size stay in cache (a level of 1e5 cells read at once was ~1.4x slower;
#: parts_check's CPU on the C-axis 0.82 -> 0.60 s, 4096 and 32768 points slower than 8192)
_DISTANCE_BLOCK = 8192


def _distance(part: AnalyticPart, points: np.ndarray) -> np.ndarray:
    """``part.distance`` of ``points`` (k, 3), in blocks of :data:`_DISTANCE_BLOCK` points."""
    if len(points) <= _DISTANCE_BLOCK:
        return part.distance(points)
    return np.concatenate([part.distance(points[i:i + _DISTANCE_BLOCK])
                           for i in range(0, len(points), _DISTANCE_BLOCK)])


def _cell_maxima(a: AnalyticPart, b: AnalyticPart, centres: np.ndarray, diag: np.ndarray) -> np.ndarray:
    """max(d_a, d_b) at the octree cells ``centres`` wherever a cell can be inside both parts or
    undecided (the maximum within the cell's half-diagonal ``diag``); elsewhere the cheaper part's
    distance, already beyond it. The costlier part is read only where the cheaper is within ``diag``:
    the same cells inside and undecided, with the same numbers, as from both parts everywhere."""
    cheap_first = a.cost <= b.cost
    first, second = (a, b) if cheap_first else (b, a)
    both = _distance(first, centres)
    near = both <= diag
    if near.all():
        other = _distance(second, centres)
        return np.maximum(both, other) if cheap_first else np.maximum(other, both)
    other = _distance(second, centres[near])
    # np.maximum's arguments in the order of (a, b)
    both[near] = np.maximum(both[near], other) if cheap_first else np.maximum(other, both[near])
    return both


def read_pair(a: AnalyticPart, b: AnalyticPart, resolution: float = 0.05, margin: float = 0.0,
              tolerance: float = 0.0, nearest: bool = True) -> PairReading:
    """The octree of the module docstring over the intersection of ``a``'s and ``b``'s boxes
    (widened by ``margin``). With ``tolerance`` > 0 it stops as soon as the volume found plus
    every undecided cell's volume stays below ``tolerance`` (no overlap can reach it). Without
    ``nearest`` only the shared volume is read (``best`` inf, ``near`` empty; see :func:`_cell_maxima`)."""
    lo = np.maximum(a.lo, b.lo) - margin
    hi = np.minimum(a.hi, b.hi) + margin
    if np.any(hi < lo):
        return PairReading(0.0, math.inf)
    size = float(np.max(hi - lo))
    if size <= 0:
        return PairReading(0.0, math.inf)
    cell = max(size / 12, resolution)
    n = np.maximum(np.ceil((hi - lo) / cell).astype(int), 1)
    centres = np.stack(np.meshgrid(*[lo[i] + (np.arange(n[i]) + 0.5) * cell for i in range(3)], indexing="ij"),
                       axis=-1).reshape(-1, 3)
    half = np.full(len(centres), cell / 2)
    volume, best, best_points = 0.0, math.inf, np.empty((0, 3))
    offsets = np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)], float)
    while len(centres):
        diag = half * math.sqrt(3)
        if not nearest:
            both = _cell_maxima(a, b, centres, diag)
        else:
            both = np.maximum(_distance(a, centres), _distance(b, centres))
            lowest = np.argpartition(both, min(3, len(both) - 1))[:4]  # the four lowest, unsorted: cheaper than argsort
            order = lowest[np.argsort(both[lowest])]
            if both[order[0]] < best + 2 * half[order[0]] * math.sqrt(3):
                best = min(best, float(both[order[0]]))
                best_points = np.vstack([best_points, centres[order]])[-8:]
        inside = both < -diag
        volume += float(np.sum((2 * half[inside]) ** 3))
        undecided = ~inside & (both <= diag)
        finest = half <= resolution / 2
        volume += float(np.sum((2 * half[undecided & finest & (both < 0)]) ** 3))
        split = undecided & ~finest
        if tolerance > 0 and volume + float(np.sum((2 * half[split]) ** 3)) < tolerance:
            break  # whatever the undecided cells hold, the two cannot share the tolerance
        if 8 * np.count_nonzero(split) > MAX_CELLS:
            # a wide band of undecided cells (faces that meet along a large area): their centres decide
            volume += float(np.sum((2 * half[split & (both < 0)]) ** 3))
            break
        if not np.any(split):
            break
        c, h = centres[split], half[split] / 2
        centres = (c[:, None, :] + offsets[None, :, :] * h[:, None, None]).reshape(-1, 3)
        half = np.repeat(h, 8)
    return PairReading(volume, best, best_points)


def closest_approach(a: AnalyticPart, b: AnalyticPart, starts: np.ndarray, radius: float,
                     rng: np.random.Generator | None = None, rounds: int = 20, until: float = 0.0,
                     restarts: int = 0) -> float:
    """The least of max(d_a, d_b) (mm) near the points ``starts``: about half the gap between two
    parts that are apart, 0 where they touch. A shrinking cloud around each start's best point so
    far, all starts at once: ``radius`` wide, 256 points a start, the radius times 0.6 each round,
    ``rounds`` rounds (the last cloud 3.7e-5 of the first: 0.015 um for the parts check's 0.4 mm,
    1/70 of its contact tolerance).

    Along the narrow valley of two faces that touch along a line (a motor's round body on a flat
    saddle) the cloud can shrink faster than the best point walks along the valley, and stop short
    of the line: while the least value found is above ``until``, the search starts again from its
    best points with the first cloud's width, ``restarts`` times at most. A value at or below
    ``until`` is returned as the first search found it."""
    rng = rng if rng is not None else np.random.default_rng(0)
    best = np.asarray(starts, float).reshape(-1, 3)
    if not len(best):
        return math.inf
    value = np.maximum(a.distance(best), b.distance(best))
    cheap_first = a.cost <= b.cost
    first, second = (a, b) if cheap_first else (b, a)
    r = radius
    for round_number in range(rounds * (restarts + 1)):
        if round_number and round_number % rounds == 0:
            if not float(np.min(value)) > until:
                break
            r = radius
        cloud = best[:, None, :] + r * rng.uniform(-1.0, 1.0, size=(len(best), 256, 3))
        points = cloud.reshape(-1, 3)
        values = first.distance(points)
        # the costlier part only where the cheaper is below the start's best: elsewhere max(d_a, d_b)
        # cannot improve on it, so the improving points, their order and the start's minimum are
        # the same (the others: inf)
        below = values < np.repeat(value, 256)
        other = second.distance(points[below])
        values[below] = np.maximum(values[below], other) if cheap_first else np.maximum(other, values[below])
        values[~below] = np.inf
        values = values.reshape(len(best), 256)
        i = np.argmin(values, axis=1)
        found = values[np.arange(len(best)), i]
        better = found < value
        best[better], value[better] = cloud[np.arange(len(best)), i][better], found[better]
        r *= 0.6
    return float(np.min(value))


# ============================================================================ the check


@dataclass(frozen=True)
class PartFinding:
    """One failure of the parts check: ``kind`` ("overlap", "interpenetrating", "missing_contact"),
    the two parts, the shared volume (mm^3) or gap (mm), and the joint's reason where there is one."""

    kind: str
    part1: str
    part2: str
    amount: float
    why: str = ""
    length_unit: str = "mm"  # the design's: what the message says the amount in

    @property
    def message(self) -> str:
        unit = self.length_unit
        volume = f"{self.amount / LENGTH_SUFFIXES[unit] ** 3:.4g} {unit}^3"
        if self.kind == "overlap":
            return f"parts overlap: {self.part1} and {self.part2} share {volume}"
        if self.kind == "interpenetrating":
            return f"parts meant to touch run into each other: {self.part1} and {self.part2} share {volume} ({self.why})"
        return (f"intended contact missing: {self.part1} and {self.part2} are {length_text(self.amount, unit)} apart, "
                f"not touching ({self.why})")


@dataclass
class PartsReport:
    """The parts check of a resolved drive (path 1): pairs read and what failed."""

    parts: int
    pairs_read: int
    findings: list[PartFinding] = field(default_factory=list)
    tolerance: float = OVERLAP_TOLERANCE
    contact_tolerance: float = CONTACT_TOLERANCE

    @property
    def ok(self) -> bool:
        return not self.findings

    @property
    def failures(self) -> list[str]:
        return [f.message for f in self.findings]

    def to_dict(self) -> dict[str, Any]:
        return {"parts": self.parts, "pairs_read": self.pairs_read, "tolerance_mm3": self.tolerance,
                "contact_tolerance_mm": self.contact_tolerance,
                "findings": [{"kind": f.kind, "part1": f.part1, "part2": f.part2, "amount": f.amount, "why": f.why}
                             for f in self.findings]}


def analytic_parts(layout) -> list[AnalyticPart]:
    """Every part of the resolved drive, gears first, as :class:`AnalyticPart`."""
    parts = [gear_part(g) for g in layout.gears]
    if layout.hardware is not None:
        parts += [component_part(c) for c in layout.hardware.components]
    return parts


def parts_check(layout, tolerance: float = OVERLAP_TOLERANCE, contact_tolerance: float = CONTACT_TOLERANCE,
                resolution: float = 0.05) -> PartsReport:
    """The parts check of the module docstring on the resolved drive ``layout``."""
    hardware = layout.hardware
    unit = layout.identity.length_unit
    parts = analytic_parts(layout)
    report = PartsReport(len(parts), 0, tolerance=tolerance, contact_tolerance=contact_tolerance)
    if hardware is None:
        return report
    meshing = {frozenset((m.part1, m.part2)) for m in layout.meshes} | {frozenset((j.a, j.b)) for j in hardware.joints
                                                                       if j.kind == "mesh"}
    joints = {frozenset((j.a, j.b)): j for j in hardware.joints if j.kind != "mesh"}
    by_name = {p.name: p for p in parts}
    for i, a in enumerate(parts):
        for b in parts[i + 1:]:
            key = frozenset((a.name, b.name))
            if key in meshing or key in joints:
                continue
            if np.any(np.minimum(a.hi, b.hi) - np.maximum(a.lo, b.lo) <= 0):
                continue
            report.pairs_read += 1
            reading = read_pair(a, b, resolution, tolerance=tolerance, nearest=False)  # its volume alone decides
            if reading.volume > tolerance:
                report.findings.append(PartFinding("overlap", a.name, b.name, reading.volume, length_unit=unit))
    for key, joint in joints.items():
        if joint.a not in by_name or joint.b not in by_name:
            report.findings.append(PartFinding("missing_contact", joint.a, joint.b, math.inf, joint.why + " (no such part)",
                                                   length_unit=unit))
            continue
        report.pairs_read += 1
        a, b = by_name[joint.a], by_name[joint.b]
        # a joint's contact is by construction: read coarsely for running into each other, then
        # how close the two come, refined from the nearest cells
        reading = read_pair(a, b, 8 * resolution, margin=max(contact_tolerance, 8 * resolution))
        gap = (2 * closest_approach(a, b, reading.near[:3], 8 * resolution, until=contact_tolerance / 2, restarts=4)
               if len(reading.near) else math.inf)
        if gap > contact_tolerance:
            report.findings.append(PartFinding("missing_contact", joint.a, joint.b, gap, joint.why, unit))
        elif reading.volume > tolerance:
            report.findings.append(PartFinding("interpenetrating", joint.a, joint.b, reading.volume, joint.why, unit))
    return report


__all__ = ["OVERLAP_TOLERANCE", "CONTACT_TOLERANCE", "AnalyticPart", "component_part", "gear_part", "gear_section",
           "read_pair", "closest_approach", "PairReading", "PartFinding", "PartsReport", "analytic_parts", "parts_check"]
