"""Triangle meshes of the worm and the worm wheel straight from the exact geometry (numpy only).

Used for their STL (the kernel's mesher with deflection control took 20-170 s for them at 1 um,
and its wheel mesh was not closed). Every vertex is an exact surface point and every vertex that
faces share is one array entry; the points are rounded to single precision (an STL's) and
triangles that then collapse left out, so what is written is closed (watertight).

- The worm (:func:`worm_triangles`): its faces are ruled between helices at equal angles, so the
  mesh's rows are those rulings (straight: the flank's generator, an axial line on the tip and
  root), at angles a step apart for the helix's sag, the flank rows split for the helicoid's
  twist, cut by the end planes; the ends are fans from the axis.
- The wheel (:func:`wheel_triangles`): a row per plane z, a column per point of the ring of runs
  round the axis (per tooth: flank, trochoid, root arc, trochoid, flank, rim arc), the last column
  joined to the first (:func:`ring_mesh`), each quad split along its shorter diagonal; the ends are
  one sector between the outline and a circle inside it, ear-clipped and repeated by index on the
  ring's own points, and a fan inside the circle. :func:`refine` spaces the points (per kind of run,
  on a map that crowds them where the run bends) and the rows (per z range) until, at every edge's
  midpoint and every quad's centre, the exact point lies within 3/4 of ``chordal_tolerance`` of
  the chord or the split diagonal (along the surface normal): a flat triangle strays from a
  quadratic surface at most 4/3 of its worst edge-midpoint sag.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from geargen.families.worm.geometry import WormGeometry, flank_axial_offset, wheel_outline, worm_geometry, z_ranges
from geargen.families.worm.spec import WormGearSet
from geargen.profile.tessellate import TessellationError, ear_clip

#: starting segments per run kind and per z range, and the least growth factor of a refinement
_START = 4
_GROWTH = 1.5
_MAX_ROUNDS = 30


def refine(evaluate: Callable, kinds: dict, ranges: list[tuple[float, float]], tolerance: float):
    """Parameters of a grid within ``tolerance`` (mm; module docstring). ``evaluate(z, params)``
    gives the exact rows {run: (len(z), n, 3)} in planes ``z`` at each kind's parameters
    ``params[kind]`` in [0, 1] (both ends included); ``kinds`` maps each run to its kind; rows at
    both ends of every z range of ``ranges``. Returns (z rows, params by kind, largest sag)."""
    counts = dict.fromkeys(set(kinds.values()), _START)
    rows = [_START] * len(ranges)
    warp = _warps(evaluate, kinds, ranges)
    for _ in range(_MAX_ROUNDS):
        params = {k: warp[k](np.linspace(0.0, 1.0, n + 1)) for k, n in counts.items()}
        both = {k: warp[k](np.linspace(0.0, 1.0, 2 * n + 1)) for k, n in counts.items()}  # the points and the midpoints
        z = [np.linspace(lo, hi, n + 1) for (lo, hi), n in zip(ranges, rows)]
        zs = np.concatenate(z)
        zm = np.concatenate([0.5 * (zz[:-1] + zz[1:]) for zz in z])
        grid = evaluate(zs, params)
        along_u = evaluate(zs, both)
        along_z = evaluate(zm, params)
        centre = evaluate(zm, both)
        # row pairs inside a range (not across the joins of two ranges)
        lower = np.concatenate([np.arange(len(zz) - 1) + sum(len(x) for x in z[:i]) for i, zz in enumerate(z)])
        range_of = np.concatenate([np.full(len(zz) - 1, i) for i, zz in enumerate(z)])
        sag_u = dict.fromkeys(counts, 0.0)
        sag_z = np.zeros(len(ranges))
        diag = {}  # (kind, range) -> the split diagonals' largest sag
        for run, pts in grid.items():
            kind = kinds[run]
            low, high = pts[lower], pts[lower + 1]
            # the quads' normals (the cross product of their diagonals): a sag is the exact point's
            # distance from the chord ALONG the normal (the rest is the parameter's own drift)
            normal = np.cross(high[:, 1:] - low[:, :-1], high[:, :-1] - low[:, 1:])
            normal /= np.maximum(np.linalg.norm(normal, axis=-1, keepdims=True), 1e-300)
            # a row's edges take the normal of the quad above (the last row's: below; a range's
            # last row the next range's first quad, near enough)
            row_normal = normal[np.minimum(np.arange(len(pts)), len(lower) - 1)]
            u_sag = np.abs(np.sum((along_u[run][:, 1::2] - 0.5 * (pts[:, :-1] + pts[:, 1:])) * row_normal, axis=-1))
            sag_u[kind] = max(sag_u[kind], float(np.max(u_sag)))
            col_normal = np.concatenate([normal, normal[:, -1:]], axis=1)
            z_sag = np.abs(np.sum((along_z[run] - 0.5 * (low + high)) * col_normal, axis=-1))
            np.maximum.at(sag_z, range_of, np.max(z_sag, axis=1))
            # each quad is split along its shorter diagonal (ring_mesh)
            c = centre[run][:, 1::2]
            rising = np.abs(np.sum((c - 0.5 * (low[:, :-1] + high[:, 1:])) * normal, axis=-1))
            falling = np.abs(np.sum((c - 0.5 * (low[:, 1:] + high[:, :-1])) * normal, axis=-1))
            shorter = _rising(low[:, :-1], low[:, 1:], high[:, 1:], high[:, :-1])
            split = np.max(np.where(shorter, rising, falling), axis=1)
            for i in range(len(ranges)):
                diag[kind, i] = max(diag.get((kind, i), 0.0), float(np.max(split[range_of == i])))
        limit = 0.75 * tolerance  # a flat triangle strays at most 4/3 of its worst edge-midpoint sag
        worst = max(max(sag_u.values()), float(np.max(sag_z)), max(diag.values()))
        if worst <= limit:
            return zs, params, worst
        # a chord's sag goes as its length squared: each side grows by its own need; a diagonal too
        # far out while both its sides are within (their sags add) takes both down
        grow_u = {k: math.sqrt(sag / limit) for k, sag in sag_u.items() if sag > limit}
        grow_z = {i: math.sqrt(sag / limit) for i, sag in enumerate(sag_z) if sag > limit}
        for (kind, i), sag in diag.items():
            if sag > limit and kind not in grow_u and i not in grow_z:
                grow_u[kind] = grow_z[i] = math.sqrt(sag / limit)
        for kind, f in grow_u.items():
            counts[kind] = int(math.ceil(counts[kind] * min(4.0, max(_GROWTH, f))))
        for i, f in grow_z.items():
            rows[i] = int(math.ceil(rows[i] * min(4.0, max(_GROWTH, f))))
    raise TessellationError(f"no mesh within {tolerance:g} mm in {_MAX_ROUNDS} refinements")


def _warps(evaluate: Callable, kinds: dict, ranges: list[tuple[float, float]], fine: int = 129) -> dict:
    """Per kind of run, a map of [0, 1] onto its parameter spacing the points where the run bends:
    a chord's sag goes as h^2 |x''|, so even sags need the density sqrt|x''| (its component across
    the chord, the largest over 9 planes a range), with a floor of a tenth of its mean so that
    straight stretches keep some points."""
    u = np.linspace(0.0, 1.0, fine)
    z = np.concatenate([np.linspace(lo, hi, 9) for lo, hi in ranges])
    rows = evaluate(z, dict.fromkeys(set(kinds.values()), u))
    bend = {}
    for run, pts in rows.items():
        second = pts[:, :-2] - 2 * pts[:, 1:-1] + pts[:, 2:]
        chord = pts[:, 2:] - pts[:, :-2]
        chord /= np.maximum(np.linalg.norm(chord, axis=-1, keepdims=True), 1e-300)
        across = second - np.sum(second * chord, axis=-1, keepdims=True) * chord
        b = np.max(np.linalg.norm(across, axis=-1), axis=0)
        kind = kinds[run]
        bend[kind] = np.maximum(bend.get(kind, 0.0), b)
    out = {}
    for kind, b in bend.items():
        density = np.sqrt(b)
        density = np.maximum(density, 0.1 * density.mean() + 1e-300)
        density = np.concatenate([[density[0]], density, [density[-1]]])  # at the points of u
        cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (density[:-1] + density[1:]))])
        cumulative /= cumulative[-1]
        out[kind] = lambda t, c=cumulative: np.interp(t, c, u)
    return out


def _ring(runs: list[np.ndarray], sectors: int, turn: float) -> np.ndarray:
    """The grid (nz, sectors * per, 3) of the rows of one sector's ``runs`` (each (nz, n_i, 3), each
    starting where the previous ends; the last ends where the next sector starts), joined (each
    joint once, the sector's end left to the next sector) and turned ``turn`` rad a sector."""
    sector = np.concatenate([r[:, :-1] for r in runs], axis=1)
    out = []
    for k in range(sectors):
        c, s = math.cos(k * turn), math.sin(k * turn)
        out.append(np.stack([c * sector[..., 0] - s * sector[..., 1], s * sector[..., 0] + c * sector[..., 1],
                             sector[..., 2]], axis=-1))
    return np.concatenate(out, axis=1)


def _rising(a, b, c, d) -> np.ndarray:
    """Whether each quad (a, b, c, d) (counterclockwise) is split along a-c (shorter than b-d)."""
    return np.linalg.norm(c - a, axis=-1) <= np.linalg.norm(d - b, axis=-1)


def ring_mesh(grid: np.ndarray, sectors: int) -> np.ndarray:
    """Closed triangle mesh (n, 3, 3), outward normals by vertex order, of a body whose side is
    ``grid`` (nz, nc, 3): rows at increasing z, each a ring of ``nc`` points counterclockwise round
    the z axis (the last joined to the first), ``sectors``-fold (nc / sectors columns a sector),
    with flat ends in the first and last rows' planes. Each quad is split along its shorter
    diagonal. The points are rounded to single precision (an STL's), neighbours in a row within
    :func:`_merge_distance` of a chain's first point made that point (where a run shrinks to a
    point, e.g. a trochoid of nanometres at a face end), and triangles whose corners then
    coincide left out: what is written is closed."""
    per = grid.shape[1] // sectors
    merge = _merge_distance(grid)
    # which neighbours are one point is decided on sector 0's exact points and done by index in
    # every sector: the ends' triangles are sector 0's repeated by index, and the sectors' rounded
    # points differ (the 22 points of a 9 nm trochoid round to 13 distinct ones in one sector, 3 in another)
    anchor = np.broadcast_to(np.arange(per), (len(grid), per)).copy()
    steps = np.linalg.norm(np.diff(grid[:, :per], axis=1), axis=-1)
    for i, j in np.argwhere(steps < merge):  # row by row, in order: a chain takes its first point
        if np.linalg.norm(grid[i, j + 1] - grid[i, anchor[i, j]]) < merge:
            anchor[i, j + 1] = anchor[i, j]
    grid = grid.astype(np.float32).astype(float)
    rows, cols = np.nonzero(anchor != np.arange(per))
    for k in range(sectors):
        grid[rows, k * per + cols] = grid[rows, k * per + anchor[rows, cols]]
    a, b = grid[:-1], np.roll(grid[:-1], -1, axis=1)
    c, d = np.roll(grid[1:], -1, axis=1), grid[1:]
    rising = _rising(a, b, c, d)[..., None, None]
    first = np.where(rising, np.stack([a, b, c], axis=2), np.stack([a, b, d], axis=2)).reshape(-1, 3, 3)
    second = np.where(rising, np.stack([a, c, d], axis=2), np.stack([b, c, d], axis=2)).reshape(-1, 3, 3)
    return _uncollapsed(np.concatenate([first, second, _cap(grid[0], sectors)[:, ::-1], _cap(grid[-1], sectors)]))


def _merge_distance(grid: np.ndarray) -> float:
    """Neighbours closer than this (mm) are one point: four single-precision steps at the grid's
    largest coordinate, so that points kept apart stay apart, in order, once rounded (each moves
    at most half a step a coordinate); 15 nm on a wheel of 125 mm, far inside any chordal tolerance."""
    return 4 * float(np.spacing(np.float32(np.max(np.abs(grid)))))


def _uncollapsed(tris: np.ndarray) -> np.ndarray:
    """The triangles whose three corners are distinct points."""
    same = (np.all(tris[:, 0] == tris[:, 1], axis=1) | np.all(tris[:, 1] == tris[:, 2], axis=1)
            | np.all(tris[:, 0] == tris[:, 2], axis=1))
    return tris[~same]


def _cap(ring: np.ndarray, sectors: int, arc_nodes: int = 4) -> np.ndarray:
    """Triangles (counterclockwise seen from +z) of the flat end bounded by ``ring`` (nc, 3)."""
    nc = len(ring)
    per = nc // sectors
    z = ring[0, 2]
    radius = 0.5 * float(np.min(np.hypot(ring[:, 0], ring[:, 1])))
    start = math.atan2(ring[0, 1], ring[0, 0])
    steps = sectors * (arc_nodes - 1)
    angles = start + 2 * math.pi * np.arange(steps) / steps
    circle = np.column_stack([radius * np.cos(angles), radius * np.sin(angles), np.full(steps, z)])
    # sector 0: the outline from column 0 to column ``per`` (the next sector's first), the circle back
    outline = np.arange(per + 1)
    arc = np.arange(arc_nodes)[::-1]
    # a run shrunk to a point (a trochoid of no length at a face end) repeats a point: once is enough
    poly = np.concatenate([ring[outline % nc, :2], circle[arc % steps, :2]])
    keep = np.concatenate([[True], np.any(poly[1:] != poly[:-1], axis=1)])
    tris = np.flatnonzero(keep)[ear_clip(poly[keep])]
    ids = np.concatenate([np.concatenate([(outline + k * per) % nc, nc + (arc + k * (arc_nodes - 1)) % steps])[tris]
                          for k in range(sectors)])
    points = np.concatenate([ring, circle])
    inner = np.arange(steps)
    fan = np.stack([np.broadcast_to([0.0, 0.0, z], (steps, 3)), circle, circle[np.roll(inner, -1)]], axis=1)
    return np.concatenate([points[ids], fan])


def _counterclockwise(grid: np.ndarray) -> np.ndarray:
    """The grid with its columns reversed if its first ring runs clockwise round the axis."""
    xy = grid[0, :, :2]
    area = np.sum(xy[:, 0] * np.roll(xy[:, 1], -1) - np.roll(xy[:, 0], -1) * xy[:, 1])
    return grid if area > 0 else grid[:, ::-1]


def _lift(rows: dict, z: np.ndarray) -> dict:
    """Rows of 2-D points (nz, n, 2) in the planes ``z`` as 3-D points."""
    return {run: np.concatenate([xy, np.broadcast_to(z[:, None, None], xy.shape[:2] + (1,))], axis=2)
            for run, xy in rows.items()}


# ---------------------------------------------------------------- the worm


def _zip(lower: np.ndarray, upper: np.ndarray, a: np.ndarray, b: np.ndarray) -> list:
    """Triangles (index triples, counterclockwise in (row, v)) between two rows of points with
    parameters ``a`` (row k, increasing) and ``b`` (row k + 1), indices ``lower`` and ``upper``."""
    out, i, j = [], 0, 0
    while i < len(a) - 1 or j < len(b) - 1:
        if j == len(b) - 1 or (i < len(a) - 1 and a[i + 1] <= b[j + 1]):
            out.append((lower[i], upper[j], lower[i + 1]))
            i += 1
        else:
            out.append((lower[i], upper[j], upper[j + 1]))
            j += 1
    return out


def worm_triangles(s: WormGearSet, chordal_tolerance: float) -> np.ndarray:
    """The worm's closed mesh (n, 3, 3), mm, outward normals, within ``chordal_tolerance`` (mm), in
    the frame of geargen.families.worm.solid (axis Z, mid plane z = 0).

    Its faces are ruled between consecutive helices at equal angles (straight flank generators,
    axial lines on the tip and root), so the mesh's rows are the rulings themselves, at angles
    theta a step apart (the helix's sag r dtheta^2 / 8 within half the tolerance at the tip) plus
    every helix's end angles (and these a turn on and back: the last root face meets thread 0
    one lead on). A flank row is split into segments enough for its twist (the helicoid's
    S_r_theta . n = -p / |S_r x S_theta|: a triangle spanning dr and dtheta strays up to
    |S_r_theta . n| dr dtheta / 4, counted over two segments where rows shift at the ends) within
    the other half; a tip or root row is one straight segment. Rows are cut by the end planes
    z = -+L/2 (straight lines in (theta, v)); the ends are fans from the axis (the outline's polar
    angle is monotone)."""
    g = worm_geometry(s)
    p = s.hand_sign * g.screw_parameter
    half = s.worm_face_length / 2
    rf, ra = g.worm_root_diameter / 2, g.worm_tip_diameter / 2
    tol = chordal_tolerance
    corners = [(rf, -1), (ra, -1), (ra, 1), (rf, 1)]
    helices = [(r, float(flank_axial_offset(g, side, r)) + k * g.axial_pitch) for k in range(s.starts)
               for r, side in corners]
    helices.append((rf, helices[0][1] + g.lead))  # thread 0's root helix one lead on (the last root face's)
    turn = g.lead / p  # +-2 pi: the angle at which the lead-on helix meets thread 0's
    ends = np.array([[(e * half - c) / p for e in (-1, 1)] for _, c in helices])
    lo, hi = float(ends.min()), float(ends.max())
    steps = int(math.ceil(2 * math.pi / math.sqrt(4 * (tol / 2) / ra)))
    d_theta = 2 * math.pi / steps
    grid = d_theta * np.arange(math.floor(lo / d_theta), math.ceil(hi / d_theta) + 1)
    whole = int(math.ceil((hi - lo) / abs(turn))) + 1
    extra = (ends.ravel()[:, None] + turn * np.arange(-whole, whole + 1)[None, :]).ravel()
    thetas = np.unique(np.concatenate([grid, extra]))
    thetas = thetas[(thetas >= lo - 1e-12) & (thetas <= hi + 1e-12)]
    # angles a rounding apart (a helix end on the grid, two ends a turn apart) are one row: two rows
    # that close would make the same points twice in an STL's single precision
    eps = 1e-6 * d_theta
    thetas = thetas[np.concatenate([[True], np.diff(thetas) > eps])]

    points, count = [], [0]  # the vertex pool

    def add(xyz):
        xyz = np.asarray(xyz, float).reshape(-1, 3)
        points.append(xyz)
        count[0] += len(xyz)
        return np.arange(count[0] - len(xyz), count[0])

    def helix_point(r, c, theta):
        return np.column_stack([r * np.cos(theta), r * np.sin(theta), p * theta + c])

    # each helix's vertices at the rows inside its span (its end rows' z exactly -+L/2)
    on_helix = []
    for i, (r, c) in enumerate(helices[:-1]):
        t0, t1 = sorted(ends[i])
        ts = thetas[(thetas >= t0 - eps) & (thetas <= t1 + eps)]
        xyz = helix_point(r, c, ts)
        xyz[np.argmin(np.abs(ts - ends[i][0])), 2], xyz[np.argmin(np.abs(ts - ends[i][1])), 2] = -half, half
        on_helix.append((ts, add(xyz)))
    base_ts, base_ids = on_helix[0]
    on_helix.append((base_ts - turn, base_ids))  # the lead-on helix: thread 0's vertices, its angles a turn back

    def helix_vertex(i, theta):
        ts, ids = on_helix[i]
        k = int(np.argmin(np.abs(ts - theta)))
        if abs(ts[k] - theta) > eps:  # every row angle is on every helix it reaches, by construction
            raise TessellationError(f"worm mesh: no vertex of helix {i} at the row angle {theta:.9g}")
        return ids[k]

    tris, end_vertices = [], {-1: [], 1: []}
    for j in range(len(helices) - 1):
        (ra_, ca), (rb, cb) = helices[j], helices[j + 1]
        flank = j % 2 == 0
        if flank:
            twist = abs(p) / math.sqrt(p * p + min(ra_, rb) ** 2 * (1 + math.tan(g.axial_pressure_angle) ** 2))
            segments = max(1, int(math.ceil(twist * 2 * abs(rb - ra_) * d_theta / 4 / (tol / 2))))
        else:
            segments = 1
        inner = np.linspace(0.0, 1.0, segments + 1)[1:-1]
        # the rows' v interval: the end planes cut theta = (-+L/2 - c(v)) / p, c(v) = ca + v (cb - ca)
        t_lo = lambda v, e: (e * half - ca - v * (cb - ca)) / p  # noqa: E731
        span = sorted([t_lo(0, -1), t_lo(0, 1), t_lo(1, -1), t_lo(1, 1)])
        rows = thetas[(thetas >= span[0] - eps) & (thetas <= span[-1] + eps)]
        row_ids, row_vs = [], []
        for theta in rows:
            # v where z(theta, v) = p theta + ca + v (cb - ca) stays within -+L/2
            z0, dz = p * theta + ca, cb - ca
            v_a, v_b = sorted([(-half - z0) / dz, (half - z0) / dz])
            v0, v1 = max(0.0, v_a), min(1.0, v_b)
            if v1 < v0 - 1e-6:
                continue
            # within a millionth of a helix, on it; an interval that short is a corner's row (the end
            # line meets the helix there): the corner alone
            v0, v1 = (0.0 if v0 < 1e-6 else v0), (1.0 if v1 > 1 - 1e-6 else v1)
            if v1 - v0 < 1e-6:
                vs = np.array([0.0 if v0 == 0.0 else 1.0])
            else:
                vs = np.concatenate([[v0], inner[(inner > v0 + 1e-6) & (inner < v1 - 1e-6)], [v1]])
            ids = []
            for v in vs:
                if v == 0.0:
                    ids.append(helix_vertex(j, theta))
                elif v == 1.0:
                    ids.append(helix_vertex(j + 1, theta))
                else:
                    r = ra_ + v * (rb - ra_)
                    xyz = np.array([r * math.cos(theta), r * math.sin(theta), z0 + v * dz])
                    on_end = 0
                    if abs(xyz[2] - half) < 1e-9:
                        xyz[2], on_end = half, 1
                    elif abs(xyz[2] + half) < 1e-9:
                        xyz[2], on_end = -half, -1
                    vid = int(add(xyz)[0])
                    ids.append(vid)
                    if on_end:
                        end_vertices[on_end].append(vid)
            row_ids.append(ids)
            row_vs.append(vs)
        face = []
        for k in range(len(row_ids) - 1):
            face += _zip(row_ids[k], row_ids[k + 1], row_vs[k], row_vs[k + 1])
        tris.append((np.array(face), j))
    pts = np.concatenate(points)
    out = []
    for face, j in tris:
        t = pts[face]
        normal = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        # outward: a -1 flank faces -z, a +1 flank +z (the thread lies between), tip and root away
        # from the axis (each triangle its own radial direction: a strip winds round several turns)
        if j % 2 == 0:
            along = normal[:, 2] * (-1.0 if j % 4 == 0 else 1.0)
        else:
            centre = t.mean(axis=1)
            along = normal[:, 0] * centre[:, 0] + normal[:, 1] * centre[:, 1]
        out.append(face if along.sum() > 0 else face[:, ::-1])
    # the ends: every vertex in the plane (helix ends and end-edge points), by polar angle, fanned
    for e in (-1, 1):
        ids = np.unique(np.concatenate([np.array(end_vertices[e], int)] + [
            ids[np.abs(pts[ids, 2] - e * half) < 1e-12] for _, ids in on_helix]))
        ring = ids[np.argsort(np.arctan2(pts[ids, 1], pts[ids, 0]))]
        centre = int(add([0.0, 0.0, e * half])[0])
        fan = np.column_stack([np.full(len(ring), centre), ring, np.roll(ring, -1)])
        out.append(fan if e > 0 else fan[:, ::-1])
    return _uncollapsed(np.concatenate(points).astype(np.float32).astype(float)[np.concatenate(out)])


# ---------------------------------------------------------------- the wheel


_WHEEL_RUNS = (("flank", 1), ("trochoid", 1), "root", ("trochoid", -1), ("flank", -1), "tip")


def _wheel_rows(s: WormGearSet, g: WormGeometry, z: np.ndarray, params: dict) -> dict:
    """The wheel's space on +Y and the rim to the next space, in planes ``z``, as runs in
    counterclockwise order (the -1 side's runs reversed: they are computed from the rim down)."""
    rows = _lift(wheel_outline(s, g, z, params["flank"], params["trochoid"], params["arc"]), z)
    for run in (("flank", -1), ("trochoid", -1)):
        rows[run] = rows[run][:, ::-1]
    return rows


def wheel_triangles(s: WormGearSet, chordal_tolerance: float) -> np.ndarray:
    """The worm wheel's closed mesh (n, 3, 3), mm, outward normals, within ``chordal_tolerance``
    (mm), in the frame of geargen.families.worm_wheel.solid (axis Z, mid plane z = 0, a space on +Y).
    Rows at the crease (z = +-z_c, the rim's kink) and at both faces."""
    g = worm_geometry(s)
    kinds = {run: run[0] if isinstance(run, tuple) else "arc" for run in _WHEEL_RUNS}
    z, params, _ = refine(lambda zz, prm: _wheel_rows(s, g, zz, prm), kinds, z_ranges(s, g), chordal_tolerance)
    # the range joins appear twice in z (the end of one range, the start of the next): once is enough
    keep = np.concatenate([[True], np.diff(z) > 0])
    z = z[keep]
    rows = _wheel_rows(s, g, z, params)
    grid = _ring([rows[run] for run in _WHEEL_RUNS], s.wheel_teeth, 2 * math.pi / s.wheel_teeth)
    return ring_mesh(_counterclockwise(grid), s.wheel_teeth)


__all__ = ["refine", "ring_mesh", "worm_triangles", "wheel_triangles"]
