"""Triangle mesh of a straight bevel gear solid straight from its exact geometry (numpy only).

The solid (:mod:`geargen.families.bevel.solid`) has, apart from its core's planes and bore, faces of
two kinds: cones through the apex over a curve on the unit sphere (flanks, meridian planes, tip and
root cones), between the toe sphere R_i and the heel sphere R_e, and pieces of those spheres. So:

- The tooth outline is sampled once on the unit sphere, in rows of polar angle theta from the root
  cone to the tip cone (each row a run of azimuths across the tooth, its ends on the two flanks)
  and along the root arc between teeth. A side face between two neighbouring outline nodes u_a,
  u_b is the planar quad R_i u_a, R_i u_b, R_e u_b, R_e u_a: its rulings are exact, so its only
  error is the chord's sag across them, largest at the heel: R_e times the sag on the unit sphere
  (flanks: measured at 7 points a chord and halved until within the tolerance; tip and root arcs:
  R_e sin theta (1 - cos(dphi / 2)), exact).
- The spherical faces are strips between those rows (and rings of latitude inside the root cone,
  down to the bore, the web's circle or the pole), their nodes the outline's own (watertight). A
  flat triangle with its corners on a sphere of radius R strays from it by at most
  R - sqrt(R^2 - rho^2), rho the radius of the triangle's smallest enclosing circle (the distance
  to the centre is an affine function's minimum over the triangle): every triangle is checked
  and the spacing made finer until all are within the tolerance.
- Planes (the flat back, the web) are exact; the bore's quads sag rb (1 - cos(pi / M)).

Every vertex is an exact surface point (the flank's on the spherical involute, within the solid's
B-spline fit of it, 1e-10 R_e); every tooth is tooth 0's nodes turned by its pitch. The result is
checked closed and consistently oriented (every directed edge met once, its reverse once); a case
this cannot mesh raises TessellationError (the caller then asks the kernel).
"""

from __future__ import annotations

import math

import numpy as np

from geargen.families.bevel.geometry import bevel_core, tooth_half_angle, tooth_outline
from geargen.families.bevel.spec import BevelGearSpec
from geargen.profile.tessellate import TessellationError, enclosing_radius_squared

#: the fraction of the tolerance a flank chord's sag is held to: the sag is measured at 7 points of
#: the chord, which see all but a few per mille of its maximum
_FLANK_SHARE = 0.95
_MAX_ROUNDS = 12


def _unit(theta, phi) -> np.ndarray:
    """Unit vectors ``(n, 3)`` at polar angles ``theta`` and azimuths ``phi``."""
    theta, phi = np.broadcast_arrays(np.asarray(theta, float), np.asarray(phi, float))
    s = np.sin(theta)
    return np.stack([s * np.cos(phi), s * np.sin(phi), np.cos(theta)], axis=-1)


def _sphere_step(radius: float, tolerance: float) -> float:
    """The starting node spacing (rad on the unit sphere) for triangles on the sphere ``radius``:
    a right isosceles triangle of legs h has the enclosing radius h / sqrt 2, and may reach
    rho = sqrt(2 R tol - tol^2)."""
    rho = math.sqrt(max(2 * radius * tolerance - tolerance * tolerance, 0.0))
    return min(math.sqrt(2.0) * rho / radius, 0.5)


def _arc_count(span: float, sin_polar: float, step: float, radius: float, tolerance: float) -> int:
    """Segments of an arc of latitude spanning ``span`` rad of azimuth at polar sine ``sin_polar``: each
    at most ``step`` long on the unit sphere, its chord's sag on the cone at ``radius`` within
    ``tolerance`` (rho (1 - cos(dphi / 2)), rho = radius sin theta)."""
    rho = radius * sin_polar
    sag_step = 2 * math.acos(max(-1.0, 1.0 - tolerance / rho)) if tolerance < rho else math.pi
    along = step / max(sin_polar, 1e-300)
    return max(1, int(math.ceil(span / min(sag_step, along) - 1e-9)))


def _flank_rows(spec: BevelGearSpec, outline, step: float, sag: float) -> np.ndarray:
    """Polar angles of the tooth's rows, root cone to tip cone: at most ``step`` apart, a row at the
    base cone when the flank starts there, and the flank's chords between rows within ``sag`` of
    the unit-sphere curve (bisected where not)."""
    cuts = [outline.root] + ([outline.flank_start] if outline.meridian else []) + [outline.tip]
    rows = [np.linspace(a, b, max(1, int(math.ceil((b - a) / step))) + 1) for a, b in zip(cuts[:-1], cuts[1:])]
    meridian = rows[0] if outline.meridian else np.empty(0)
    flank = rows[-1]
    check = np.linspace(0.0, 1.0, 9)[1:-1]
    for _ in range(40):
        a, b = flank[:-1], flank[1:]
        pa, pb = _unit(a, -tooth_half_angle(spec, a)), _unit(b, -tooth_half_angle(spec, b))
        inner_theta = a[:, None] + (b - a)[:, None] * check
        inner = _unit(inner_theta, -tooth_half_angle(spec, inner_theta))
        chord = pb - pa
        length = np.linalg.norm(chord, axis=1)
        dev = np.linalg.norm(np.cross(inner - pa[:, None], chord[:, None]), axis=-1).max(axis=1) / length
        bad = dev > sag
        if not np.any(bad):
            return np.concatenate([meridian[:-1], flank])
        flank = np.insert(flank, np.nonzero(bad)[0] + 1, 0.5 * (a + b)[bad])
    raise TessellationError(f"{spec.name}: the flank needs too many chords for a sag of {sag:g} (unit sphere)")


def _strip(lower: np.ndarray, upper: np.ndarray, key_lower: np.ndarray, key_upper: np.ndarray) -> np.ndarray:
    """Triangles (index triples) between two rows of node indices, ``lower`` nearer the axis (or the
    pole), both running the same way along their keys (azimuth, or a share of the row): the
    segments of both rows taken in the order of their midpoints' keys, each closed by the other
    row's current node. Counter-clockwise in (radial coordinate, azimuth), so on a sphere the
    normals point outward (+r), on a plane z = c up (+z)."""
    mid_l = 0.5 * (key_lower[:-1] + key_lower[1:])
    mid_u = 0.5 * (key_upper[:-1] + key_upper[1:])
    # the other row's node each segment closes with: how many of its segments come first
    j_of_u = np.searchsorted(mid_l, mid_u, side="right")
    k_of_l = np.searchsorted(mid_u, mid_l, side="left")
    n_l, n_u = len(mid_l), len(mid_u)
    from_lower = np.column_stack([lower[:n_l], upper[k_of_l], lower[1:n_l + 1]])
    from_upper = np.column_stack([lower[j_of_u], upper[:n_u], upper[1:n_u + 1]])
    return np.concatenate([from_lower, from_upper])


def _fan(centre: int, ring: np.ndarray) -> np.ndarray:
    """Triangles from ``centre`` to each segment of ``ring`` (closed, counter-clockwise about the axis)."""
    return np.column_stack([np.full(len(ring) - 1, centre), ring[:-1], ring[1:]])


class _Mesh:
    """Vertices and triangles (index triples) put together face by face."""

    def __init__(self):
        self.points: list[np.ndarray] = []
        self.count = 0
        self.faces: list[np.ndarray] = []

    def add(self, points: np.ndarray) -> np.ndarray:
        points = np.asarray(points, float).reshape(-1, 3)
        self.points.append(points)
        index = np.arange(self.count, self.count + len(points))
        self.count += len(points)
        return index

    def face(self, triangles: np.ndarray, outward: bool = True) -> None:
        triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
        self.faces.append(triangles if outward else triangles[:, ::-1])

    def triangles(self) -> np.ndarray:
        points = np.concatenate(self.points)
        faces = np.concatenate(self.faces)
        _check_closed(faces, self.count)
        return points[faces]


def _check_closed(faces: np.ndarray, count: int) -> None:
    """TessellationError unless every directed edge occurs once and its reverse once (closed and
    consistently oriented) and no triangle repeats a vertex."""
    if np.any((faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 2] == faces[:, 0])):
        raise TessellationError("a triangle repeats a vertex")
    a = faces.ravel()
    b = np.roll(faces, -1, axis=1).ravel()
    directed = a * count + b
    unique, seen = np.unique(directed, return_counts=True)
    if np.any(seen != 1):
        raise TessellationError("an edge is used twice the same way")
    if not np.array_equal(np.sort(b * count + a), unique):
        raise TessellationError("the mesh is not closed")


def sphere_sag(tri: np.ndarray, radius: float) -> np.ndarray:
    """The largest distance of each flat triangle ``(n, 3, 3)`` (corners on the sphere ``radius``
    about the origin) from that sphere: R - sqrt(R^2 - rho^2), rho its enclosing radius."""
    return radius - np.sqrt(np.maximum(radius * radius - enclosing_radius_squared(tri), 0.0))


def bevel_triangles(spec: BevelGearSpec, back: str, chordal_tolerance: float) -> np.ndarray:
    """The closed triangle mesh ``(n, 3, 3)`` (mm, outward) of :func:`geargen.families.bevel.solid.build_bevel`'s
    solid of ``spec`` with ``back``, within ``chordal_tolerance`` mm of it (module docstring)."""
    if not chordal_tolerance > 0:
        raise ValueError("chordal_tolerance must be > 0")
    ri, re = spec.toe_cone_distance, spec.cone_distance
    heel_step, toe_step = _sphere_step(re, chordal_tolerance), _sphere_step(ri, chordal_tolerance)
    for _ in range(_MAX_ROUNDS):
        tri, sags = _mesh(spec, back, chordal_tolerance, heel_step, toe_step)
        worst_heel, worst_toe = sags
        if worst_heel <= chordal_tolerance and worst_toe <= chordal_tolerance:
            return tri
        # a sag goes as the spacing squared: shrink each side by its own need (at least 10 %)
        if worst_heel > chordal_tolerance:
            heel_step *= min(0.9, math.sqrt(chordal_tolerance / worst_heel))
        if worst_toe > chordal_tolerance:
            toe_step *= min(0.9, math.sqrt(chordal_tolerance / worst_toe))
    raise TessellationError(f"{spec.name}: no mesh within {chordal_tolerance:g} mm in {_MAX_ROUNDS} refinements")


def _mesh(spec: BevelGearSpec, back: str, tol: float, heel_step: float, toe_step: float):
    """One mesh at the unit-sphere spacings ``heel_step`` (the outline, the tooth ends, the heel cap) and
    ``toe_step`` (the toe cap); returns it and the largest sphere sags (heel side, toe side), mm."""
    o = tooth_outline(spec)
    core = bevel_core(spec, back)
    ri, re = spec.toe_cone_distance, spec.cone_distance
    rb = spec.bore_diameter / 2
    teeth = spec.teeth
    pitch = 2 * math.pi / teeth
    if o.tip >= math.pi - 1e-9 or o.root <= 1e-9:
        raise TessellationError(f"{spec.name}: a cone angle out of the mesher's range")

    # tooth 0 on the unit sphere: its rows (root cone to tip cone), then the root arc's inner nodes
    rows_theta = _flank_rows(spec, o, heel_step, _FLANK_SHARE * tol / re)
    thetas, phis, rows = [], [], []
    count = 0
    for i, t in enumerate(rows_theta):
        half = float(tooth_half_angle(spec, t))
        if i == len(rows_theta) - 1:  # the tip arc: its chords' sag on the tip cone too
            n = _arc_count(2 * half, math.sin(t), heel_step, re, tol)
        else:
            n = max(1, int(math.ceil(2 * half * math.sin(t) / heel_step - 1e-9)))
        phi = np.linspace(-half, half, n + 1)
        thetas.append(np.full(n + 1, t))
        phis.append(phi)
        rows.append(np.arange(count, count + n + 1))
        count += n + 1
    root_span = pitch - 2 * o.root_half_angle
    n_root = _arc_count(root_span, math.sin(o.root), heel_step, re, tol)
    root_phi = o.root_half_angle + root_span * np.arange(1, n_root) / n_root
    thetas.append(np.full(n_root - 1, o.root))
    phis.append(root_phi)
    root_nodes = np.arange(count, count + n_root - 1)
    count += n_root - 1
    per_tooth = count
    theta0, phi0 = np.concatenate(thetas), np.concatenate(phis)
    k = np.arange(teeth)
    unit = _unit(np.tile(theta0, teeth), (phi0[None, :] + pitch * k[:, None]).ravel())
    offset = (per_tooth * k)[:, None]

    mesh = _Mesh()
    toe = mesh.add(ri * unit)
    heel = mesh.add(re * unit)

    # the side faces: one planar quad per segment of the outline, toe to heel
    lower = [r[0] for r in rows]
    upper = [r[-1] for r in rows[::-1]]
    outline0 = np.concatenate([lower, rows[-1][1:], upper[1:], root_nodes])
    outline = (outline0[None, :] + offset).ravel()
    a, b = outline, np.roll(outline, -1)
    mesh.face(np.concatenate([np.column_stack([toe[a], toe[b], heel[b]]), np.column_stack([toe[a], heel[b], heel[a]])]))

    # the tooth ends: strips between its rows, keyed by the share of the row's width
    strips = []
    for r0, r1 in zip(rows[:-1], rows[1:]):
        share0 = np.linspace(0.0, 1.0, len(r0))
        share1 = np.linspace(0.0, 1.0, len(r1))
        strips.append(_strip(r0, r1, share0, share1))
    ends = (np.concatenate(strips)[None] + offset[:, :, None]).reshape(-1, 3)
    mesh.face(toe[ends], outward=False)
    heel_sag = float(sphere_sag(re * unit[ends], re).max())
    toe_sag = 0.0

    # the ring on the root cone (bases of the teeth and root arcs), azimuth from tooth 0's first node
    ring0 = np.concatenate([rows[0], root_nodes])
    ring = np.append((ring0[None, :] + offset).ravel(), 0)
    ring_phi = np.append((np.concatenate([phis[0], root_phi])[None, :] + pitch * k[:, None]).ravel(),
                         phis[0][0] + 2 * math.pi)
    start = phis[0][0]

    def circle(count_: int, radius: float, z: float):
        phi = start + 2 * math.pi * np.arange(count_) / count_
        return mesh.add(np.column_stack([radius * np.cos(phi), radius * np.sin(phi), np.full(count_, z)])), phi

    def closed(index, phi):
        return np.append(index, index[0]), np.append(phi, phi[0] + 2 * math.pi)

    bore_count = 0
    if rb > 0:
        cyl = 2 * math.acos(max(-1.0, 1.0 - tol / rb)) if tol < rb else math.pi / 2
        bore_count = max(8, int(math.ceil(2 * math.pi / cyl)),
                         int(math.ceil(2 * math.pi * rb / (ri * toe_step))), int(math.ceil(2 * math.pi * rb / (re * heel_step))))

    def cap(radius: float, step: float, inner_polar: float, inner_count: int, outward: bool, sphere_vertices):
        """The sphere ``radius`` inside the root cone down to ``inner_polar`` (0: the pole): rings of
        latitude at most ``step`` apart; returns the inner ring (index, azimuth) or None and the sag."""
        n = max(1, int(math.ceil((o.root - inner_polar) / step - 1e-9)))
        polar = np.linspace(o.root, inner_polar, n + 1)
        outer_index, outer_phi = sphere_vertices[ring], ring_phi
        tris = []
        inner = None
        for j, t in enumerate(polar[1:], 1):
            if j == n and inner_polar <= 0:
                pole = mesh.add(np.array([[0.0, 0.0, radius]]))[0]
                tris.append(_fan(pole, outer_index))
                break
            m = inner_count if j == n else max(6, int(math.ceil(2 * math.pi * math.sin(t) / step - 1e-9)))
            index, phi = circle(m, radius * math.sin(t), radius * math.cos(t))
            index, phi = closed(index, phi)
            tris.append(_strip(index, outer_index, phi, outer_phi))
            outer_index, outer_phi = index, phi
            inner = (index, phi)
        tris = np.concatenate(tris)
        mesh.face(tris, outward)
        points = np.concatenate(mesh.points)
        return inner, float(sphere_sag(points[tris], radius).max())

    def plane(outer, outer_phi, z: float, outward: bool):
        """The plane ``z`` from the closed ring ``outer`` in to the bore (its circle made here and
        returned) or to the axis."""
        if rb > 0:
            bore = closed(*circle(bore_count, rb, z))
            mesh.face(_strip(bore[0], outer, bore[1], outer_phi), outward)
            return bore
        mesh.face(_fan(mesh.add(np.array([[0.0, 0.0, z]]))[0], outer), outward)
        return None

    # the toe face: the tooth ends above and the cap inside the root cone, down to the bore, the web or the pole
    toe_inner_count = bore_count if core.toe_inner_face == "bore" else \
        max(8, int(math.ceil(2 * math.pi * math.sin(core.toe_inner) / toe_step)))
    toe_inner, toe_sag = cap(ri, toe_step, core.toe_inner, toe_inner_count, False, toe)
    bore_low = toe_inner if core.toe_inner_face == "bore" else None
    if core.toe_inner_face == "web":  # the web's face, from the toe sphere's circle in (outward: -z)
        bore_low = plane(*toe_inner, core.web_z, False)
    # the heel: each tooth's end (a patch of the heel sphere), then the plane within the heel root circle
    # (a flat back) or the heel sphere's cap
    mesh.face(heel[ends])
    if core.back == "flat":
        bore_high = plane(heel[ring], ring_phi, core.back_z, True)
    else:
        bore_high, cap_sag = cap(re, heel_step, core.heel_inner, bore_count, True, heel)
        heel_sag = max(heel_sag, cap_sag)
    if rb > 0:
        low, high = bore_low[0], bore_high[0]
        # quads between the bore's two circles (the same azimuths), normals towards the axis
        mesh.face(np.concatenate([np.column_stack([low[:-1], high[1:], low[1:]]),
                                  np.column_stack([low[:-1], high[:-1], high[1:]])]))
    return mesh.triangles(), (heel_sag, toe_sag)


__all__ = ["bevel_triangles", "sphere_sag"]
