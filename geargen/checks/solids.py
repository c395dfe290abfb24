"""Path 2: the mesh check on sections of the exported solids (what will be machined).

Each gear's exported solid (an STL read with trimesh, or a STEP file sectioned through
:mod:`geargen.cad.measure`) is cut by planes z = const along the face; each section is a set
of straight segments in the part's own frame (axis on z, tooth 0 on +x at z = 0, the section
already carrying the helical twist of its height). The two gears' sections at the same height
are placed as the mesh places the gears, and the free rotation of gear 1 against gear 2 is
found exactly for these polygons: contact between two polygons turning about a centre happens
where a vertex of one meets an edge of the other, so every vertex of gear 2 is turned back onto
the circles it crosses gear 1's edges on, and every vertex of gear 1 forward onto gear 2's
edges (circle-segment intersections, closed form). Nothing here uses the analytic profile: the
only inputs are the section segments and the placement.

Accuracy: an STL triangle lies within its chordal tolerance ``c`` of the exact surface, and its
chords cut into the convex involute flanks, so each flank of the section lies up to ``c``
inside the exact one (plus the spline tolerance ``s`` of the solid itself). The normal
backlash measured here therefore exceeds the exact one by between ``-2 s`` and ``2 (c + s)``;
:func:`stated_tolerance` gives that bound, which the agreement test uses.

Conventions as in :mod:`geargen.checks.results` (mm, rad; gear 1 turned, gear 2 held).
"""

from __future__ import annotations

import math
import tempfile
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from geargen.checks.mesh2d import CheckSettings, MeshSetup, interference_failures, mesh_positions
from geargen.checks.results import Failure, MeshCheck, MeshSweep
from geargen.design.gear import GearSpec
from geargen.profile.tooth import UndercutWarning


@dataclass
class GearSections:
    """Section segments of one gear's solid, in its own frame.

    ``planes`` ``(P,)`` heights (mm); ``segments[k]`` ``(m, 2, 2)`` the section at ``planes[k]``
    as straight segments (mm). ``deviation`` (mm): how far the segments may lie from the exact
    surface (chordal tolerance plus the solid's spline tolerance); ``source`` names the file.
    """

    spec: GearSpec
    planes: np.ndarray
    segments: list[np.ndarray]
    deviation: float
    source: str = ""
    notes: list[str] = field(default_factory=list)


# ---------------------------------------------------------------------------------- sections
def sections_from_triangles(spec: GearSpec, triangles: np.ndarray, planes, deviation: float,
                            source: str = "") -> GearSections:
    """Sections of a triangle mesh ``(n, 3, 3)`` (mm) at ``planes`` with trimesh (vertices are not
    merged: the mesh is used exactly as written)."""
    import trimesh

    tri = np.asarray(triangles, dtype=float)
    mesh = trimesh.Trimesh(vertices=tri.reshape(-1, 3), faces=np.arange(tri.shape[0] * 3).reshape(-1, 3),
                           process=False, validate=False)
    segs = []
    for z in np.atleast_1d(planes):
        s = trimesh.intersections.mesh_plane(mesh, plane_normal=[0.0, 0.0, 1.0], plane_origin=[0.0, 0.0, float(z)])
        s = np.asarray(s, dtype=float)[:, :, :2]
        keep = np.linalg.norm(s[:, 1] - s[:, 0], axis=1) > 1e-12
        segs.append(s[keep])
    return GearSections(spec, np.atleast_1d(np.asarray(planes, dtype=float)), segs, deviation, source)


def sections_from_stl(spec: GearSpec, path, planes, chordal_tolerance: float, spline_tolerance: float = 0.0) -> GearSections:
    """Sections of an STL file (mm, as :func:`geargen.cad.export.export_stl` writes them)."""
    import trimesh

    mesh = trimesh.load(str(path), file_type="stl", process=False)
    tri = np.asarray(mesh.triangles, dtype=float)
    return sections_from_triangles(spec, tri, planes, chordal_tolerance + spline_tolerance, str(path))


def sections_from_step(spec: GearSpec, path, planes, samples_per_face: int = 64,
                       chord_tolerance: float = 5e-5) -> GearSections:
    """Sections of a STEP file through :func:`geargen.cad.measure.section`: exact points of the
    section curves, joined by chords that are bisected on the curve until each chord's middle
    lies within ``chord_tolerance`` (mm) of the curve; the largest remaining deviation is
    reported as ``deviation``."""
    from geargen.cad.export import read_step

    shape = read_step(path).shape
    return sections_from_shape(spec, shape, planes, samples_per_face, str(path), chord_tolerance)


def sections_from_shape(spec: GearSpec, shape, planes, samples_per_face: int = 64, source: str = "",
                        chord_tolerance: float = 5e-5) -> GearSections:
    """Sections of an OCCT shape (see :func:`sections_from_step`)."""
    from geargen.cad.measure import section

    segs, worst = [], 0.0
    for z in np.atleast_1d(planes):
        cut = section(shape, float(z), samples_per_face)
        parts, dev = _bisected(cut, chord_tolerance)
        segs.append(parts)
        worst = max(worst, dev)
    return GearSections(spec, np.atleast_1d(np.asarray(planes, dtype=float)), segs, worst, source)


def _bisected(cut, chord_tolerance: float) -> tuple[np.ndarray, float]:
    """The section ``cut`` (:func:`geargen.cad.measure.section`) as chords ``(m, 2, 2)``, each
    bisected on its curve until its middle lies within ``chord_tolerance`` of the curve, and the
    largest remaining deviation; curve by curve, in the order of the parameter.

    All curves' chords are bisected together, level by level (:meth:`SectionCurve.xy_still`: each
    curve's midpoints in one call). That gives each chord the same points as bisecting it alone
    when every solve ends at the parameter it started from (the curve's guess, which then never
    moves): then no point depends on what was solved before it. A curve where one does not, or
    whose chord leaves its face, is bisected alone, chord after chord (:func:`_bisect_curve`)."""
    same = cut.edge_index[1:] == cut.edge_index[:-1]  # a curve's samples lie together, in order
    first = np.nonzero(same)[0]
    ta, tb = cut.params[first], cut.params[first + 1]
    ax, ay = cut.points[first, 0], cut.points[first, 1]
    bx, by = cut.points[first + 1, 0], cut.points[first + 1, 1]
    cid = cut.edge_index[first]
    alone: set[int] = set()
    found, accepted = [], []  # (curve, t, x, y) of the midpoints kept; (curve, deviation) of the chords
    while cid.size:
        tm = 0.5 * (ta + tb)
        qx, qy = np.empty_like(tm), np.empty_like(tm)
        ok = np.ones(tm.size, dtype=bool)
        ends = np.nonzero(np.concatenate([[True], cid[1:] != cid[:-1], [True]]))[0]
        for i, j in zip(ends[:-1].tolist(), ends[1:].tolist()):
            q = cut.curves[cid[i]].xy_still(tm[i:j])
            if q is None:
                alone.add(int(cid[i]))
                ok[i:j] = False
                continue
            qx[i:j], qy[i:j] = np.array(q).T
        if not ok.all():
            ta, tb, tm, ax, ay, bx, by, qx, qy, cid = (x[ok] for x in (ta, tb, tm, ax, ay, bx, by, qx, qy, cid))
        dx, dy = qx - 0.5 * (ax + bx), qy - 0.5 * (ay + by)
        dev = np.sqrt(dx * dx + dy * dy)
        split = (dev > chord_tolerance) & (np.abs(tb - ta) > 1e-12 * np.maximum(1.0, np.abs(tm)))
        accepted.append((cid[~split], dev[~split]))
        found.append((cid[split], tm[split], qx[split], qy[split]))
        # each split chord's halves, in order
        ta, tb = np.stack([ta[split], tm[split]], 1).ravel(), np.stack([tm[split], tb[split]], 1).ravel()
        ax, ay, bx, by = (np.stack(pair, 1).ravel() for pair in ((ax[split], qx[split]), (ay[split], qy[split]),
                                                                 (qx[split], bx[split]), (qy[split], by[split])))
        cid = np.repeat(cid[split], 2)
    drop = np.array(sorted(alone), dtype=int)
    c = np.concatenate([cut.edge_index] + [f[0] for f in found])
    t = np.concatenate([cut.params] + [f[1] for f in found])
    x = np.concatenate([cut.points[:, 0]] + [f[2] for f in found])
    y = np.concatenate([cut.points[:, 1]] + [f[3] for f in found])
    order = np.lexsort((t, c))
    order = order[~np.isin(c[order], drop)]
    c, x, y = c[order], x[order], y[order]
    link = np.nonzero(c[1:] == c[:-1])[0]
    chords = np.stack([np.column_stack([x[link], y[link]]), np.column_stack([x[link + 1], y[link + 1]])], 1)
    worst = 0.0
    for e, d in accepted:
        d = d[~np.isin(e, drop)]
        if d.size:
            worst = max(worst, float(np.max(d)))
    if not alone:
        return (chords if chords.size else np.empty((0, 2, 2))), worst
    # the curves bisected alone, put in their places (curve order)
    parts = {}
    at = np.concatenate([[0], np.cumsum(np.bincount(c[link], minlength=len(cut.curves)))])
    for e in range(len(cut.curves)):
        if e in alone:
            rows = np.nonzero(cut.edge_index == e)[0]
            got, dev = _bisect_curve(cut.curves[e], cut.params[rows].tolist(),
                                     [tuple(q) for q in cut.points[rows].tolist()], chord_tolerance)
            parts[e] = got
            worst = max(worst, dev)
        elif at[e + 1] > at[e]:
            parts[e] = chords[at[e]:at[e + 1]].tolist()
    out = [seg for e in sorted(parts) for seg in parts[e]]
    return (np.array(out, dtype=float) if out else np.empty((0, 2, 2))), worst


def _bisect_curve(curve, t: list, p: list, chord_tolerance: float) -> tuple[list, float]:
    """The chords between the points ``p`` (pairs of floats) at parameters ``t`` of ``curve``, each
    bisected on the curve until its middle lies within ``chord_tolerance``, chord after chord (a
    chord that leaves the face ends on its boundary on both sides): the chords' ends as pairs and
    the largest remaining deviation."""
    worst = 0.0
    k = 0
    while k < len(t) - 1:  # bisect chords until their middles lie on the curve
        if p[k] is None or p[k + 1] is None:
            k += 1
            continue
        tm = 0.5 * (t[k] + t[k + 1])
        q = curve.xy(tm)
        if q is None:  # the chord leaves the face: end both sides at the face's boundary
            ends = []
            for on, off in ((t[k], tm), (t[k + 1], tm)):
                for _ in range(40):
                    mid = 0.5 * (on + off)
                    if curve.xy(mid) is None:
                        off = mid
                    else:
                        on = mid
                ends.append(on)
            t[k + 1:k + 1] = [ends[0], math.nan, ends[1]]
            p[k + 1:k + 1] = [curve.xy(ends[0]), None, curve.xy(ends[1])]
            continue
        (ax, ay), (bx, by) = p[k], p[k + 1]
        dx, dy = q[0] - 0.5 * (ax + bx), q[1] - 0.5 * (ay + by)
        dev = math.sqrt(dx * dx + dy * dy)  # numpy's norm of (dx, dy), the same bits
        if dev > chord_tolerance and abs(t[k + 1] - t[k]) > 1e-12 * max(1.0, abs(tm)):
            t.insert(k + 1, tm)
            p.insert(k + 1, q)
            continue
        worst = max(worst, dev)
        k += 1
    return [(p[k], p[k + 1]) for k in range(len(p) - 1) if p[k] is not None and p[k + 1] is not None], worst


def export_and_section(spec: GearSpec, planes, folder=None, chordal_tolerance: float = 1e-3) -> GearSections:
    """Build ``spec`` (:func:`geargen.cad.gear_solid.build_gear`), export it as STL into ``folder``
    (a temporary one by default), read the file back and section it."""
    from geargen.cad.export import export_stl
    from geargen.cad.gear_solid import build_gear

    with warnings.catch_warnings():  # an undercut is reported by the checks themselves
        warnings.simplefilter("ignore", UndercutWarning)
        solid = build_gear(spec)
    with tempfile.TemporaryDirectory() as tmp:
        where = Path(folder) if folder is not None else Path(tmp)
        path = where / f"{spec.name}.stl"
        export_stl(solid, path, chordal_tolerance=chordal_tolerance)
        return sections_from_stl(spec, path, planes, chordal_tolerance, solid.tolerance)


def section_planes(setup: MeshSetup, count: int = 3) -> np.ndarray:
    """Heights (mm, gear 1's face coordinates) inside the common face: ``count`` planes, kept off
    the end faces by a tenth of the common face (a section exactly on an end face is degenerate)."""
    lo = max(0.0, setup.face_offset2)
    hi = min(setup.gear1.face_width, setup.face_offset2 + setup.gear2.face_width)
    if count == 1:
        return np.array([0.5 * (lo + hi)])
    margin = 0.1 * (hi - lo)
    return np.linspace(lo + margin, hi - margin, count)


def stated_tolerance(sections1: GearSections, sections2: GearSections) -> float:
    """Bound (mm) on the difference between this path's normal backlash and the exact one."""
    return 2.0 * max(sections1.deviation, sections2.deviation)


# ---------------------------------------------------------------------------------- polygons
def _place(segs: np.ndarray, centre, angle) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    rot = np.array([[c, -s], [s, c]])
    # the ends as one (2m, 2) matrix: one product, ~20x faster than m stacked (2, 2) ones and the
    # same numbers (no difference in 12 million random ends)
    return (segs.reshape(-1, 2) @ rot.T).reshape(segs.shape) + np.asarray(centre, dtype=float)


def _distances(points: np.ndarray, centre) -> np.ndarray:
    """Distances of ``points`` (``(..., 2)``) from ``centre``: numpy's norm over the last axis, the
    same numbers at half its cost."""
    dx, dy = points[..., 0] - centre[0], points[..., 1] - centre[1]
    return np.sqrt(dx * dx + dy * dy)


def _near(segs: np.ndarray, centre, radius: float) -> np.ndarray:
    d = _distances(segs, np.asarray(centre, dtype=float))
    return segs[np.minimum(d[:, 0], d[:, 1]) <= radius]  # the nearer end (numpy's min over an axis of 2: 5x slower)


def placed_near(segs1: np.ndarray, segs2: np.ndarray, st, i: int, reach1: float, reach2: float):
    """Two gears' section segments at mesh position ``i`` of the states ``st``: each turned and moved
    to its centre, and kept where within the other gear's reach (its tip radius and a module; the
    polygon play and root clearance read nothing farther): (segments 1, segments 2, centre 1, centre 2)."""
    c1, c2 = st.centre1[i], st.centre2[i]
    return (_near(_place(segs1, c1, st.angle1[i]), c2, reach2), _near(_place(segs2, c2, st.angle2[i]), c1, reach1),
            c1, c2)


def _circle_crossings(points: np.ndarray, segs: np.ndarray):
    """Where the circles about the origin through ``points`` ``(V, 2)`` cross ``segs`` ``(E, 2, 2)``:
    (vertex index, x, y) of every crossing. Edges are sorted by their nearest radius, so
    each vertex only meets the edges whose radial span can hold it; what each crossing needs of
    its edge or vertex is computed once per edge or vertex and picked per crossing (the same
    numbers as computed per crossing)."""
    if points.size == 0 or segs.size == 0:
        return np.empty(0, dtype=int), np.empty(0), np.empty(0)
    rho = np.hypot(points[:, 0], points[:, 1])
    edges = _edge_terms(segs)
    v, e = _radial_pairs(rho, edges)
    return _pair_crossings(rho, edges, v, e)


def _edge_terms(segs: np.ndarray) -> tuple:
    """What the circle crossings need of each edge ``(E, 2, 2)`` (taken from the centre): its
    start, its direction, their products, its nearest and farthest radius."""
    ax, ay = segs[:, 0, 0], segs[:, 0, 1]
    dx, dy = segs[:, 1, 0] - ax, segs[:, 1, 1] - ay
    dd = dx * dx + dy * dy
    ad = ax * dx + ay * dy
    tn = np.clip(-ad / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    rmin = np.hypot(ax + tn * dx, ay + tn * dy)
    rmax = np.maximum(np.hypot(ax, ay), np.hypot(segs[:, 1, 0], segs[:, 1, 1]))
    return ax, ay, dx, dy, dd, ad, rmin, rmax


def _radial_pairs(rho: np.ndarray, edges: tuple) -> tuple[np.ndarray, np.ndarray]:
    """The (vertex, edge) pairs whose edge's radial span holds the vertex's radius ``rho``."""
    rmin, rmax = edges[6], edges[7]
    order = np.argsort(rmin)
    rmin_s = rmin[order]
    span = float(np.max(rmax - rmin)) * (1 + 1e-12) + 1e-15
    lo = np.searchsorted(rmin_s, rho - span, side="left")
    hi = np.searchsorted(rmin_s, rho, side="right")
    count = hi - lo
    v = np.repeat(np.arange(rho.size), count)
    e = order[np.repeat(lo - (np.cumsum(count) - count), count) + np.arange(v.size)]
    keep = rho[v] <= rmax[e]
    return v[keep], e[keep]


def _pair_crossings(rho: np.ndarray, edges: tuple, v: np.ndarray, e: np.ndarray):
    """Where the circle through vertex ``v`` crosses edge ``e``, pair by pair: (vertex index, x, y)."""
    if v.size == 0:
        return v, np.empty(0), np.empty(0)
    ax, ay, dx, dy, dd, ad = edges[:6]
    A, B, C = dd[e], (2 * ad)[e], (ax * ax + ay * ay)[e] - (rho ** 2)[v]
    disc = np.sqrt(np.maximum(B * B - 4 * A * C, 0.0))
    B, A = -B, 2 * A
    t1, t2 = (B - disc) / A, (B + disc) / A
    ok1 = (t1 >= -1e-12) & (t1 <= 1 + 1e-12)
    ok2 = (t2 >= -1e-12) & (t2 <= 1 + 1e-12)
    e = np.concatenate([e[ok1], e[ok2]])
    t = np.clip(np.concatenate([t1[ok1], t2[ok2]]), 0, 1)
    return np.concatenate([v[ok1], v[ok2]]), ax[e] + t * dx[e], ay[e] + t * dy[e]


def _wrap(a):
    """``a`` (rad) into [-pi, pi): (a + pi) mod 2 pi - pi, the modulo taken only where a + pi lies
    outside [0, 2 pi) (inside it is a + pi itself): the same numbers, 4x faster on arrays."""
    x = a + math.pi
    if np.ndim(x) == 0:
        return x % (2 * math.pi) - math.pi
    out = x - math.pi
    beyond = (x < 0) | (x >= 2 * math.pi)
    if beyond.any():
        out[beyond] = x[beyond] % (2 * math.pi) - math.pi
    return out


def _inside(points: np.ndarray, segs: np.ndarray, centre) -> np.ndarray:
    """Whether ``points`` ``(V, 2)`` lie inside the gear whose nearby outline is ``segs``, centred
    at ``centre``: the parity of the crossings of the ray from the centre outward beyond each
    point (a tooth outline is radially monotone, so a point in a tooth is left through one flank
    or the tip land; one in a space never meets the outline further out). Edges are sorted by
    polar angle, so each point meets only the edges at its own angle."""
    c = np.asarray(centre, dtype=float)
    u = points - c
    return _inside_from(u, segs - c, np.arctan2(u[:, 1], u[:, 0]))


def _inside_from(u: np.ndarray, q: np.ndarray, polar: np.ndarray) -> np.ndarray:
    """:func:`_inside` of the points ``u`` and segments ``q``, both taken from the centre, ``polar``
    the points' polar angles (``arctan2``: the caller may have them). What each (point, edge)
    pair needs of its point or its edge is computed once per point or edge and picked per pair
    (the same numbers as computed per pair)."""
    inside = np.zeros(u.shape[0], dtype=bool)
    if u.size == 0 or q.size == 0:
        return inside
    # a ray from beyond the outline's farthest end meets nothing (the crossings lie within that
    # radius, computed to ~1e-16 of it): only the points within it are tested
    rad = np.hypot(u[:, 0], u[:, 1])
    near = np.nonzero(rad <= float(np.max(np.hypot(q[..., 0], q[..., 1]))) * (1 + 1e-9))[0]
    if near.size == 0:
        return inside
    u, polar, rad = u[near], polar[near], rad[near]
    ref = math.atan2(float(np.mean(q[..., 1])), float(np.mean(q[..., 0])))  # the outline lies around here
    ang = _wrap(np.arctan2(q[..., 1], q[..., 0]) - ref)
    lo, hi = np.minimum(ang[:, 0], ang[:, 1]), np.maximum(ang[:, 0], ang[:, 1])  # ~10x faster than min(axis=1)
    order = np.argsort(lo)
    lo_s = lo[order]
    span = float(np.max(hi - lo)) + 1e-15
    pa = _wrap(polar - ref)
    first = np.searchsorted(lo_s, pa - span, side="left")
    last = np.searchsorted(lo_s, pa, side="right")
    count = last - first
    v = np.repeat(np.arange(u.shape[0]), count)
    e = order[np.repeat(first - (np.cumsum(count) - count), count) + np.arange(v.size)]
    keep = pa[v] <= hi[e]
    v, e = v[keep], e[keep]
    scale = np.where(rad > 0, rad, 1.0)
    unx, uny = (u[:, 0] / scale)[v], (u[:, 1] / scale)[v]
    q0x, q0y = q[:, 0, 0], q[:, 0, 1]
    dqx, dqy = q[:, 1, 0] - q0x, q[:, 1, 1] - q0y
    cross = (q0x * dqy - q0y * dqx)[e]
    q0x, q0y, dqx, dqy = q0x[e], q0y[e], dqx[e], dqy[e]
    den = unx * dqy - uny * dqx
    with np.errstate(divide="ignore", invalid="ignore"):
        lam = cross / den  # distance along the ray
        t = (q0x * uny - q0y * unx) / den  # parameter along the edge
    hit = (den != 0) & (t >= 0) & (t < 1) & (lam > rad[v])
    inside[near] = np.bincount(v[hit], minlength=u.shape[0]) % 2 == 1
    return inside


def _vertices(segs: np.ndarray) -> np.ndarray:
    """The vertices ``(V, 2)`` of the segments ``(m, 2, 2)``, each end shared by two segments of a
    chain (one's end is, bit for bit, the next one's start) once: half the vertices of a section
    to turn, with the same results (the two copies give the same values)."""
    if len(segs) < 2:
        return segs.reshape(-1, 2)
    shared = (segs[1:, 0, 0] == segs[:-1, 1, 0]) & (segs[1:, 0, 1] == segs[:-1, 1, 1])
    return np.concatenate([segs[np.concatenate([[True], ~shared]), 0], segs[:, 1]])


def polygon_play(seg1: np.ndarray, seg2: np.ndarray, centre1, centre2=None) -> tuple[float, float]:
    """Free rotation (rad) of polygon 1 about ``centre1`` against polygon 2 held: (ccw, cw).

    Exact for the polygons: contact happens where a vertex of one meets an edge of the other,
    so each vertex is turned along its circle about ``centre1`` onto the first edge either way.
    A vertex already inside the other gear (``centre2`` is that gear's centre for the inside
    test of polygon 1's vertices) gives a negative value on the side it overlaps: the turn back
    that frees it, as in the exact check.

    Where no vertex is inside, only the turns of at most a window (1/32 rad, then 8 times as wide)
    are found, the pairs whose vertex lies farther from the edge than the chord of that turn
    left out: if both answers lie within the window, no pair left out (each a turn beyond it) can
    be smaller, and they are the same numbers as from every pair; else the next window, then every
    pair.
    """
    c = np.asarray(centre1, dtype=float)
    c2 = c if centre2 is None else np.asarray(centre2, dtype=float)
    sides = []
    for verts, edges, own, inside_centre in ((_vertices(seg2), seg1, False, c),
                                             (_vertices(seg1), seg2, True, c2)):
        u, q = verts - c, edges - c
        if u.size == 0 or q.size == 0:
            continue
        polar = np.arctan2(u[:, 1], u[:, 0])  # each vertex's once: the same numbers as per crossing
        # about centre 1 (2's vertices against 1), as the crossings: their numbers serve again
        inside = _inside_from(u, q, polar) if inside_centre is c else _inside(verts, edges, inside_centre)
        rho = np.hypot(u[:, 0], u[:, 1])
        terms = _edge_terms(q)
        v, e = _radial_pairs(rho, terms)
        sides.append((own, u, q, polar, inside, inside.any(), rho, terms, v, e))
    window = 1 / 32
    while True:
        ccw, cw = _play_within(sides, window)
        if window is None or (ccw <= window and cw <= window):
            return ccw, cw
        window = 8 * window if 8 * window < 1.0 else None


def _play_within(sides: list, window: float | None) -> tuple[float, float]:
    """:func:`polygon_play` from the turns of at most ``window`` (rad; None: every turn) on the
    sides with no vertex inside, every turn on the others."""
    ccw_c, cw_c = [math.inf], [math.inf]
    for own, u, q, polar, inside, any_inside, rho, terms, v, e in sides:
        if window is not None and not any_inside:
            near = _within_turn(u, q, rho, terms, v, e, window)
            vi, x, y = _pair_crossings(rho, terms, v[near], e[near])
        else:
            vi, x, y = _pair_crossings(rho, terms, v, e)
        if vi.size == 0:
            continue
        if own:  # a vertex of 1 turning onto an edge of 2
            d = _wrap(np.arctan2(y, x) - polar[vi])
        else:  # an edge of 1 turning onto a vertex of 2
            d = _wrap(polar[vi] - np.arctan2(y, x))
        if not any_inside:  # the first contact either way: the smallest turn of all (no vertex's own needed)
            ccw_c.append(np.min(d[d >= 0], initial=math.inf))
            cw_c.append(np.min(-d[d < 0], initial=math.inf))
            continue
        n = u.shape[0]
        pos = np.full(n, np.inf)
        neg = np.full(n, np.inf)
        np.minimum.at(pos, vi[d >= 0], d[d >= 0])
        np.minimum.at(neg, vi[d < 0], -d[d < 0])
        # outside: first contact either way; inside: freed by the shorter turn, i.e. overlapping
        # on the other side (turning counter-clockwise frees a vertex that overlaps clockwise)
        out = ~inside
        ccw_c.append(np.min(pos[out], initial=math.inf))
        cw_c.append(np.min(neg[out], initial=math.inf))
        free_ccw = inside & (pos <= neg)
        free_cw = inside & (neg < pos)
        cw_c.append(np.min(-pos[free_ccw], initial=math.inf))
        ccw_c.append(np.min(-neg[free_cw], initial=math.inf))
    return float(min(ccw_c)), float(min(cw_c))


def _within_turn(u: np.ndarray, q: np.ndarray, rho: np.ndarray, edges: tuple, v: np.ndarray, e: np.ndarray,
                 window: float) -> np.ndarray:
    """Which pairs (vertex ``v``, edge ``e``) may cross at a turn of at most ``window`` (rad, below
    pi) about the centre: ``u`` the vertices, ``q`` the edges, ``rho`` the vertices' radii,
    ``edges`` the edges' terms (:func:`_edge_terms`), all taken from the centre. The crossing of a
    turn d lies 2 rho sin(|d| / 2) from its vertex, and at least the distance from the vertex to
    the edge's middle less its half length: a pair farther apart than the chord of the window (a
    margin of 1e-9 of it over rounding, ~1e-15) turns beyond it."""
    reach = 2.0 * rho * math.sin(0.5 * window) * (1 + 1e-9) + 1e-12
    mx, my = q[:, 0, 0] + 0.5 * edges[2], q[:, 0, 1] + 0.5 * edges[3]
    gx, gy = u[v, 0] - mx[e], u[v, 1] - my[e]
    r = 0.5 * np.sqrt(edges[4])[e] + reach[v]
    return gx * gx + gy * gy <= r * r


def _distance_to_segments(vx, vy, a0x, a0y, dx, dy):
    """Distance from the points (vx, vy) to the segments from (a0x, a0y) along (dx, dy), for
    arrays that broadcast (a column of points against a row of segments: every pair)."""
    wx, wy = vx - a0x, vy - a0y
    t = np.clip((wx * dx + wy * dy) / np.maximum(dx * dx + dy * dy, 1e-300), 0, 1)
    return np.hypot(wx - t * dx, wy - t * dy)


def _root_clearance(own: np.ndarray, own_centre, r_root: float, other: np.ndarray, other_centre,
                    r_tip: float, deviation: float = 0.0) -> float:
    """Distance from the root-arc vertices of ``own`` to the tip lands of ``other`` (its chords on
    the tip circle, corners included); negative for a vertex inside ``other`` (parity of a
    radially outward ray from ``other``'s centre). A vertex counts as on a circle within the
    outline's ``deviation`` from the exact surface (a section of an STL cuts the triangles'
    diagonals, inside the surface by up to the chordal tolerance), but at least ``2e-7 r``
    (float32 rounding of STL coordinates). Fillet points that close to the root circle count as
    root; the smallest clearance, with a tip centred over a root, is not affected."""
    v = _vertices(own)
    c = np.asarray(own_centre, dtype=float)
    oc = np.asarray(other_centre, dtype=float)
    r = _distances(v, c)
    root = r <= r_root + max(deviation, 2e-6, 2e-7 * r_root)
    v, r = v[root], r[root]
    ends = _distances(other, oc)
    tip = r_tip - max(deviation, 2e-6, 2e-7 * r_tip)
    on_tip = (ends[:, 0] >= tip) & (ends[:, 1] >= tip)
    land = other[on_tip]
    if v.size == 0 or land.size == 0:
        return math.inf
    a0, d = land[:, 0], land[:, 1] - land[:, 0]
    u = v - oc
    rad = _distances(u, (0.0, 0.0))
    cand = np.nonzero(rad < r_tip)[0]
    if cand.size == 0:
        # no vertex inside: the smallest distance of all (vertex, land) pairs. A pair is measured
        # only if neither of two lower bounds of its distance exceeds the distance of one pair (the
        # vertex nearest the other gear to its nearest land): the vertex's from the other centre
        # less the lands' largest radius, the land's from this centre less the vertices' largest
        # radius. The margin (1e-9 of the size) covers the bounds' rounding (~1e-16 of it), so the
        # nearest pair is among those measured, and its distance is the same number.
        near = int(np.argmin(rad))
        bound = np.min(_distance_to_segments(v[near, 0], v[near, 1], a0[:, 0], a0[:, 1], d[:, 0], d[:, 1]))
        bound += 1e-9 * (1.0 + float(np.max(np.abs(oc - c))) + r_tip)
        v = v[rad - np.max(ends[on_tip]) <= bound]
        lands = _distance_to_segments(c[0], c[1], a0[:, 0], a0[:, 1], d[:, 0], d[:, 1]) - np.max(r) <= bound
        a0, d = a0[lands], d[lands]
        return float(np.min(_distance_to_segments(v[:, None, 0], v[:, None, 1], a0[None, :, 0], a0[None, :, 1],
                                                  d[None, :, 0], d[None, :, 1])))
    dist = _distance_to_segments(v[:, None, 0], v[:, None, 1], a0[None, :, 0], a0[None, :, 1],
                                 d[None, :, 0], d[None, :, 1]).min(axis=1)
    # inside test, only for vertices within the other gear's tip circle
    inside = np.zeros(v.shape[0], dtype=bool)
    un = u[cand] / rad[cand, None]
    q0 = other[:, 0] - oc
    dq = other[:, 1] - other[:, 0]
    cross_d = un[:, None, 0] * dq[None, :, 1] - un[:, None, 1] * dq[None, :, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        # solve q0 + s dq = lam un: s = (un x q0) / (dq x un), lam = (q0 x dq) / (un x dq)
        s = (un[:, None, 0] * q0[None, :, 1] - un[:, None, 1] * q0[None, :, 0]) / -cross_d
        lam = (q0[None, :, 0] * dq[None, :, 1] - q0[None, :, 1] * dq[None, :, 0]) / cross_d
    hits = (s >= 0) & (s < 1) & (lam > rad[cand, None])
    inside[cand] = np.count_nonzero(hits, axis=1) % 2 == 1
    return float(np.min(np.where(inside, -dist, dist)))


def section_phase_error(sections: GearSections) -> np.ndarray:
    """How far (rad, per plane, in (-p/2, p/2]) the teeth in each section sit from where the gear's
    twist puts them at that height (tooth 0 centred at ``section_rotation(spec, z)``): the mean
    polar angle of the tip-land vertices, taken modulo the pitch. Near 0 for sections taken in
    the gear's own face coordinates (face from z = 0)."""
    from geargen.profile.tooth import section_rotation

    spec = sections.spec
    z = spec.teeth
    out = []
    for plane, segs in zip(sections.planes, sections.segments):
        v = segs.reshape(-1, 2)
        r = np.hypot(v[:, 0], v[:, 1])
        tip = v[r >= spec.tip_radius - max(sections.deviation, 2e-6, 2e-7 * spec.tip_radius)]
        if tip.size == 0:
            out.append(math.nan)
            continue
        phase = np.angle(np.mean(np.exp(1j * z * np.arctan2(tip[:, 1], tip[:, 0])))) / z
        out.append(_wrap((phase - section_rotation(spec, float(plane))) * z) / z)
    return np.asarray(out)


def check_mesh_sections(setup: MeshSetup, sections1: GearSections, sections2: GearSections,
                        settings: CheckSettings = CheckSettings(), positions=None) -> MeshCheck:
    """Path 2 check of one mesh from the two gears' sections (at the same heights: gear 2's
    planes are gear 1's minus ``setup.face_offset2``).

    Returns a :class:`MeshCheck` (path ``"sections"``) with play, backlash and tip clearance per
    mesh position (worst of the planes), and whether the sections overlap (flank interference;
    depth and area are left to path 1). ``tolerance`` is :func:`stated_tolerance`.
    """
    g1, g2 = setup.gear1, setup.gear2
    if positions is None:
        positions = mesh_positions(setup, settings.steps_per_tooth, settings.revolutions)
    positions = np.atleast_1d(np.asarray(positions, dtype=float))
    from geargen.profile.tooth import section_rotation

    st = setup.states(positions)  # gear 1's plane z = 0 ...
    # ... but each section carries its own gear's twist: place both gears by their rotation at
    # their own z = 0 (gear 2's z = 0 is face_offset2 above gear 1's)
    st = replace(st, angle2=st.angle2 - section_rotation(g2, -setup.face_offset2))
    n, P = positions.size, sections1.planes.size
    if not np.allclose(sections1.planes - setup.face_offset2, sections2.planes, atol=1e-9):
        raise ValueError("the two gears' sections must be at the same heights")
    for sec in (sections1, sections2):
        err = section_phase_error(sec)
        bad = np.abs(err) > 0.1 * 2 * math.pi / sec.spec.teeth
        if np.any(bad):
            k = int(np.argmax(bad))
            raise ValueError(f"{sec.spec.name}: the section at z = {sec.planes[k]:.6g} mm shows the teeth "
                             f"{math.degrees(err[k]):.4g} deg away from where the helix puts them at that height: "
                             "give the planes in the gear's own face coordinates (its face from z = 0)")
    reach1 = g1.tip_radius + g1.module
    reach2 = g2.tip_radius + g2.module
    dev = max(sections1.deviation, sections2.deviation)
    tol = stated_tolerance(sections1, sections2)
    ccw = np.full((P, n), np.inf)
    cw = np.full((P, n), np.inf)
    clear = np.full((P, n), np.inf)
    for k in range(P):
        a, b = sections1.segments[k], sections2.segments[k]
        for i in range(n):
            s1, s2, c1, c2 = placed_near(a, b, st, i, reach1, reach2)
            ccw[k, i], cw[k, i] = polygon_play(s1, s2, c1, c2)
            clear[k, i] = min(_root_clearance(s1, c1, g1.root_radius_standard, s2, c2, g2.tip_radius, dev),
                              _root_clearance(s2, c2, g2.root_radius_standard, s1, c1, g1.tip_radius, dev))
    play_ccw, play_cw = ccw.min(axis=0), cw.min(axis=0)
    ang = play_ccw + play_cw
    a = st.centre_distance
    rb1 = g1.base_radius
    normal = ang * rb1 * math.cos(g1.base_helix_angle)
    min_clear = clear.min(axis=0)
    # interference the sections can resolve: overlap beyond their tolerance
    depth = np.maximum(np.maximum(-normal, -min_clear), 0.0)
    code = np.where(-min_clear > tol, 1, np.where(-normal > tol, 3, 0))
    depth = np.where(code > 0, depth, 0.0)
    sw = MeshSweep(mesh_position=positions, centre_distance=a, play_ccw=play_ccw, play_cw=play_cw,
                   conjugate_play_ccw=play_ccw, conjugate_play_cw=play_cw, angular_backlash=ang,
                   circumferential_backlash=ang * a * g1.teeth / (g1.teeth + g2.teeth),
                   normal_backlash=normal, min_clearance=min_clear,
                   interference_depth=depth, interference_area=np.zeros(n), interference=code,
                   planes=sections1.planes)
    fails = interference_failures(setup.name, sw)
    if settings.require_backlash and not np.any(code == 3) and float(np.min(normal)) <= tol:
        fails.append(Failure("no_backlash", setup.name,
                             f"normal backlash {float(np.min(normal)):.3g} mm is within the section tolerance "
                             f"{tol:.3g} mm of zero", "normal_backlash", float(np.min(normal)), tol))
    notes = [f"sections: {sections1.source or g1.name}, {sections2.source or g2.name}; "
             f"{P} planes; outline deviation {max(sections1.deviation, sections2.deviation):.3g} mm"]
    return MeshCheck(mesh=setup.name, gear1=g1.name, gear2=g2.name, path="sections",
                     centre_distance=setup.centre_distance, sweep=sw, failures=fails, notes=notes, tolerance=tol)


def compare_paths(setup: MeshSetup, sections: MeshCheck) -> dict:
    """Path 2 against path 1 on the same mesh positions and section planes (mm): the largest
    difference of the normal backlash and the difference of the smallest tip clearance, against
    the stated tolerance of path 2."""
    from geargen.checks.mesh2d import sweep_mesh

    exact = sweep_mesh(setup, sections.sweep.mesh_position, sections.sweep.planes, areas=False)
    d_j = sections.sweep.normal_backlash - exact.normal_backlash
    c1 = float(np.min(exact.min_clearance))
    c2 = float(np.min(sections.sweep.min_clearance))
    tol = sections.tolerance
    worst = float(np.max(np.abs(d_j)))
    clear_ok = not (math.isfinite(c1) and math.isfinite(c2)) or abs(c2 - c1) <= tol + 1e-9
    return {
        "mesh": setup.name,
        "normal_backlash_difference_max": worst,
        "normal_backlash_difference_mean": float(np.mean(d_j)),
        "min_clearance_difference": float(c2 - c1) if math.isfinite(c1) and math.isfinite(c2) else None,
        "tolerance": tol,
        "agree": bool(worst <= tol + 1e-9 and clear_ok),
    }


__all__ = ["GearSections", "sections_from_triangles", "sections_from_stl", "sections_from_step",
           "sections_from_shape", "export_and_section", "section_planes", "stated_tolerance", "polygon_play",
           "section_phase_error", "check_mesh_sections", "compare_paths"]
