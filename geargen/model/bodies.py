"""What a non-gear part is made of, as numbers: the body of a component of the resolved drive.

A :class:`Body` is a small expression (a kind and its numbers, mm, in the part's own frame) that
two readers evaluate: the CAD layer turns it into a solid (:mod:`geargen.cad.components`, one
builder per kind) and the checks, the structure and the train read its geometry here without a
kernel: its bounding box, its signed distance (:func:`signed_distance`: negative inside), whether
two bodies share volume or touch (:mod:`geargen.checks.hardware`), its volume and moment about
its own axis (:func:`mass_properties`). Both readers see the same numbers, so a collision
``geargen check`` reports is the one ``geargen build`` finds on the solids.

Kinds mirror the machine elements of the drives (a shaft, a bearing ring, a motor envelope, a
plate with holes, the robot link's tray and cover, a quill, a clamp collar, a compression spring)
and the few operations composite parts are made of (fuse, cut, translate). A composite kind is
expanded (:func:`primitive_tree`) into boxes, cylinders and frusta for the analytic readers;
the CAD layer builds it with the kernel's own primitives, as it always has.

Constructors check their numbers and raise ``ValueError`` for impossible ones (a bore wider
than its cylinder): a hardware rule that lets such numbers through is a bug, and the resolver
turns the error into a :class:`~geargen.errors.DesignError` naming the part (the hardware rules
are meant to refuse first, naming the key).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from geargen.units import length_text


@dataclass(frozen=True)
class Body:
    """A part's geometry as data: ``kind`` (see :data:`KINDS`) and its numbers ``args`` (mm,
    nested tuples of floats, bodies for the operations). Hashable: equal bodies build one solid."""

    kind: str
    args: tuple

    def aabb(self) -> tuple[np.ndarray, np.ndarray]:
        """The axis-aligned box holding the body, in its own frame: ``(lo (3,), hi (3,))`` mm."""
        return _aabb(self)


class SizeError(ValueError):
    """A body its sizes cannot make. ``problem`` has a ``{}`` for each of ``lengths`` (mm), so the
    message can be given in a design's unit (:meth:`in_unit`); ``str()`` gives it in mm."""

    def __init__(self, problem: str, *lengths: float):
        self.problem, self.lengths = problem, lengths
        super().__init__(self.in_unit("mm"))

    def in_unit(self, unit: str) -> str:
        return self.problem.format(*(length_text(v, unit, 6) for v in self.lengths))


def _f(*values) -> tuple[float, ...]:
    return tuple(float(v) for v in values)


def _positive(**values) -> None:
    for name, v in values.items():
        if not (math.isfinite(v) and v > 0):
            raise SizeError(f"{name} = {{}} must be a positive length", v)


# ============================================================================ constructors


def cylinder(diameter: float, height: float, bore: float = 0.0) -> Body:
    """A (hollow) cylinder on +z, z in [0, height]."""
    _positive(diameter=diameter, height=height)
    if not 0 <= bore < diameter:
        raise SizeError("bore {} must lie in [0, {})", bore, diameter)
    return Body("cylinder", _f(diameter, height, bore))


def box(size_x: float, size_y: float, size_z: float, corner=(0.0, 0.0, 0.0)) -> Body:
    """An axis-aligned box with its lowest corner at ``corner``."""
    _positive(size_x=size_x, size_y=size_y, size_z=size_z)
    return Body("box", (_f(*corner), _f(size_x, size_y, size_z)))


def box_between(lo, hi) -> Body:
    """The axis-aligned box from corner ``lo`` to corner ``hi``."""
    return box(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], lo)


def frustum(bottom_radius: float, top_radius: float, height: float, bore: float = 0.0) -> Body:
    """A cone frustum on +z: radius ``bottom_radius`` at z = 0, ``top_radius`` at ``height``."""
    _positive(bottom_radius=bottom_radius, top_radius=top_radius, height=height)
    if not 0 <= bore < 2 * min(bottom_radius, top_radius):
        raise SizeError("bore {} must be smaller than both end diameters", bore)
    return Body("frustum", _f(bottom_radius, top_radius, height, bore))


def shaft(diameter: float, length: float, bore: float = 0.0) -> Body:
    """A round (hollow) shaft on +z, z in [0, length]."""
    return Body("shaft", cylinder(diameter, length, bore).args)


def bearing(bore: float, outer_diameter: float, width: float) -> Body:
    """A rolling bearing as its envelope ring, z in [0, width]."""
    if not outer_diameter > bore:
        raise SizeError("bearing outer diameter {} is not larger than its bore {}", outer_diameter, bore)
    return Body("bearing", _f(bore, outer_diameter, width))


def servo_motor(body_diameter: float, body_length: float, flange_width: float, flange_thickness: float,
                shaft_diameter: float, shaft_length: float) -> Body:
    """A servo-motor envelope: square flange z in [0, t], round body z in [t, t + L], shaft stub
    z in [-shaft_length, 0]."""
    _positive(body_diameter=body_diameter, body_length=body_length, flange_width=flange_width,
              flange_thickness=flange_thickness, shaft_diameter=shaft_diameter, shaft_length=shaft_length)
    if not shaft_diameter < min(body_diameter, flange_width):
        raise ValueError("the motor's shaft is not thinner than the motor")
    return Body("servo_motor", _f(body_diameter, body_length, flange_width, flange_thickness, shaft_diameter,
                                  shaft_length))


def blade_flexure(thickness: float, length: float, width: float) -> Body:
    """A blade: ``thickness`` along x, ``width`` along y, ``length`` along z from 0; centred on x = y = 0."""
    _positive(thickness=thickness, length=length, width=width)
    return Body("blade_flexure", _f(thickness, length, width))


def compression_spring(wire_diameter: float, mean_coil_diameter: float, length: float, total_coils: float,
                       ground: bool) -> Body:
    """A helical compression spring (right hand) at ``length``, z in [0, length]: the wire swept along
    a helix of ``total_coils`` turns. Ground ends (``ground``): the helix runs from z = 0 to
    ``length`` and the slab [0, length] grinds half the wire off each end, so the coils close at
    d N_t, the solid height of :data:`geargen.design.stiffness.SPRING_ENDS`' ground types; plain
    ends: from d/2 to length - d/2, closing at d (N_t + 1)."""
    _positive(wire_diameter=wire_diameter, mean_coil_diameter=mean_coil_diameter, length=length,
              total_coils=total_coils)
    if not mean_coil_diameter > 2 * wire_diameter:
        raise ValueError("spring index D/d must exceed 2")
    solid = wire_diameter * (total_coils if ground else total_coils + 1)
    if not length > solid:
        raise SizeError("spring length {} closes its coils (solid height {})", length, solid)
    return Body("compression_spring", _f(wire_diameter, mean_coil_diameter, length, total_coils) + (bool(ground),))


def spring_helix(args) -> tuple[float, float]:
    """(z of the helix's start, pitch) of a :func:`compression_spring`'s wire centre line."""
    d, _, length, coils, ground = args
    return (0.0, length / coils) if ground else (d / 2, (length - d) / coils)


def coil_envelope(wire_diameter: float, mean_coil_diameter: float, length: float) -> Body:
    """A spring as its envelope tube: inner diameter D - d, outer D + d, z in [0, length]."""
    return cylinder(mean_coil_diameter + wire_diameter, length, mean_coil_diameter - wire_diameter)


def plate_with_holes(size_x: float, size_y: float, thickness: float, holes, corner=(0.0, 0.0, 0.0)) -> Body:
    """An axis-aligned plate from ``corner`` with through holes ``(x, y, diameter)`` along z."""
    _positive(size_x=size_x, size_y=size_y, thickness=thickness)
    holes = tuple(_f(*h) for h in holes)
    for x, y, d in holes:
        _positive(hole_diameter=d)
    return Body("plate_with_holes", (_f(size_x, size_y, thickness), holes, _f(*corner)))


def relieved(bosses) -> tuple[tuple[float, ...], ...]:
    """Bosses ``(x, y, diameter, height[, relief])`` with their relief (0: none), checked."""
    out = tuple(_f(*b) + (0.0,) * (5 - len(b)) for b in bosses)
    for _, _, d, _, r in out:
        if not 0 <= r < d:
            raise SizeError("relief {} leaves no boss around it", r)
    return out


def link_tray(radius: float, length: float, height: float, wall: float, floor: float, bosses=()) -> Body:
    """The robot link as an open-top tray (:func:`geargen.cad.parts.link_tray`)."""
    _positive(radius=radius, length=length, height=height, wall=wall, floor=floor)
    if not (wall < radius and floor < height):
        raise ValueError("the link's walls and floor leave no room inside")
    return Body("link_tray", (_f(radius, length, height, wall, floor), relieved(bosses)))


def link_cover(radius: float, wall: float, x_end: float, thickness: float, seats=()) -> Body:
    """The cover over the link's round end (:func:`geargen.cad.parts.link_cover`)."""
    _positive(radius=radius, wall=wall, x_end=x_end, thickness=thickness)
    if not radius - wall > 0:
        raise ValueError("the link's walls leave no room inside")
    return Body("link_cover", (_f(radius, wall, x_end, thickness), tuple(_f(*s) for s in seats)))


def quill(outer_diameter: float, length: float, bores, lug_length: float, lug_width: float,
          lug_thickness: float) -> Body:
    """A bearing quill with stepped bores and a lug (:func:`geargen.cad.parts.quill`)."""
    _positive(outer_diameter=outer_diameter, length=length, lug_length=lug_length, lug_width=lug_width,
              lug_thickness=lug_thickness)
    spans = tuple(sorted(_f(*b) for b in bores))
    radius = outer_diameter / 2
    for (z0, z1, d), following in zip(spans, spans[1:] + ((length, length, 0.0),)):
        if not (0 <= z0 < z1 <= following[0] and 0 < d < outer_diameter):
            raise SizeError("quill bore from z {} to {}, diameter {}, is out of range", z0, z1, d)
    if not lug_width < outer_diameter:
        raise ValueError("the quill's lug is not narrower than its sleeve")
    if not math.hypot(quill_lug_root(outer_diameter, spans, lug_thickness), lug_width / 2) < radius:
        raise ValueError("the quill's lug is too wide for the sleeve's wall")
    return Body("quill", (_f(outer_diameter, length), spans, _f(lug_length, lug_width, lug_thickness)))


def quill_lug_root(outer_diameter: float, bores, lug_thickness: float) -> float:
    """Where the quill's lug starts (its root, inside the sleeve's wall): the middle of the wall
    around the widest bore at the lug's height."""
    widest = max((d for z0, z1, d in bores if z0 < lug_thickness), default=0.0)
    return (widest / 2 + outer_diameter / 2) / 2


def split_collar(bore: float, outer_diameter: float, width: float, slot: float) -> Body:
    """A clamp collar: a ring with one radial slot of width ``slot`` on +x, z in [0, width]."""
    cylinder(outer_diameter, width, bore)
    return Body("split_collar", _f(bore, outer_diameter, width, slot))


def revolve(profile) -> Body:
    """A body of revolution about the local z axis: the closed polygon ``profile`` ``(r, z)`` (r >= 0)
    turned a full turn. An analytic envelope only (a toothed part's blank: the CAD layer builds the
    part itself by its family), read by the checks."""
    pts = tuple(_f(r, z) for r, z in profile)
    if len(pts) < 3 or any(r < 0 for r, _ in pts):
        raise ValueError("a revolved profile needs three or more points at r >= 0")
    return Body("revolve", pts)


def fuse(bodies, what: str = "fused part") -> Body:
    """Touching or overlapping bodies made one part."""
    bodies = tuple(bodies)
    if not bodies:
        raise ValueError("nothing to fuse")
    return Body("fuse", (bodies, what))


def cut(body: Body, *tools: Body) -> Body:
    """``body`` less ``tools``."""
    return Body("cut", (body, tuple(tools)))


def translate(body: Body, vector) -> Body:
    """``body`` moved by ``vector`` (mm)."""
    return Body("translate", (body, _f(*vector)))


def single(body: Body, what: str) -> Body:
    """``body``, which must be one solid (the CAD layer checks it)."""
    return Body("single", (body, what))


def ring_relief(outer_diameter: float, bore: float) -> float:
    """Diameter of the relief under a bearing seated by its outer ring: the ring's middle
    diameter, so the seat bears on the outer ring only (inner ring and shaft end run clear)."""
    return (outer_diameter + bore) / 2


KINDS = ("cylinder", "box", "frustum", "shaft", "bearing", "servo_motor", "blade_flexure", "compression_spring",
         "plate_with_holes", "link_tray", "link_cover", "quill", "split_collar", "revolve", "fuse", "cut", "translate",
         "single")


# ============================================================================ the analytic readers
#
# Every kind is expanded into a tree of three primitives (box, cylinder, frustum; a cylinder may be
# hollow) joined by union, intersection and difference, translated: the readers below need only those.


@dataclass(frozen=True)
class _Node:
    op: str  # "box" | "cyl" | "cone" | "union" | "inter" | "diff" | "move" | "spring"
    args: tuple


def primitive_tree(body: Body) -> _Node:
    """``body`` as primitives joined by set operations (the analytic readers' form)."""
    k, a = body.kind, body.args
    if k in ("cylinder", "shaft"):
        return _Node("cyl", a)
    if k == "box":
        (x, y, z), (sx, sy, sz) = a
        return _Node("box", ((x, y, z), (x + sx, y + sy, z + sz)))
    if k == "frustum":
        return _Node("cone", a)
    if k == "revolve":
        return _Node("rev", a)
    if k == "bearing":
        bore, od, w = a
        return _Node("cyl", (od, w, bore))
    if k == "servo_motor":
        d, length, w, t, ds, ls = a
        return _Node("union", (_Node("box", ((-w / 2, -w / 2, 0.0), (w / 2, w / 2, t))),
                               _Node("move", (_Node("cyl", (d, length, 0.0)), (0.0, 0.0, t))),
                               _Node("move", (_Node("cyl", (ds, ls, 0.0)), (0.0, 0.0, -ls)))))
    if k == "blade_flexure":
        t, length, w = a
        return _Node("box", ((-t / 2, -w / 2, 0.0), (t / 2, w / 2, length)))
    if k == "compression_spring":
        return _Node("spring", a)
    if k == "plate_with_holes":
        (sx, sy, t), holes, (x0, y0, z0) = a
        plate = _Node("box", ((x0, y0, z0), (x0 + sx, y0 + sy, z0 + t)))
        if not holes:
            return plate
        return _Node("diff", (plate, tuple(_Node("move", (_Node("cyl", (d, t, 0.0)), (x, y, z0))) for x, y, d in holes)))
    if k == "link_tray":
        (radius, length, height, wall, floor), bosses = a

        def outline(r, z0, h):
            return _Node("union", (_Node("move", (_Node("cyl", (2 * r, h, 0.0)), (0.0, 0.0, z0))),
                                   _Node("box", ((0.0, -r, z0), (length - (radius - r), r, z0 + h)))))
        tray = _Node("diff", (outline(radius, 0.0, height), (outline(radius - wall, floor, height - floor),)))
        extra = tuple(_Node("move", (_Node("cyl", (d, h, 0.0)), (x, y, floor))) for x, y, d, h, _ in bosses)
        if extra:
            tray = _Node("union", (tray,) + extra)
        reliefs = tuple(_Node("move", (_Node("cyl", (r, h, 0.0)), (x, y, floor))) for x, y, d, h, r in bosses if r > 0)
        return _Node("diff", (tray, reliefs)) if reliefs else tray
    if k == "link_cover":
        (radius, wall, x_end, t), seats = a
        r = radius - wall
        cover = _Node("inter", (_Node("union", (_Node("cyl", (2 * r, t, 0.0)), _Node("box", ((0.0, -r, 0.0), (x_end, r, t))))),
                                _Node("box", ((-r, -r, 0.0), (x_end, r, t)))))
        bosses = tuple(_Node("move", (_Node("cyl", (d, depth, 0.0)), (x, y, -depth))) for x, y, d, depth, _ in seats
                       if depth > 0)
        if bosses:
            cover = _Node("union", (cover,) + bosses)
        bores = tuple(_Node("move", (_Node("cyl", (rl, t + depth, 0.0)), (x, y, -depth))) for x, y, _, depth, rl in seats
                      if rl > 0)
        return _Node("diff", (cover, bores)) if bores else cover
    if k == "quill":
        (d_out, length), spans, (lug_l, lug_w, lug_t) = a
        sleeve = _Node("cyl", (d_out, length, 0.0))
        if spans:
            sleeve = _Node("diff", (sleeve, tuple(_Node("move", (_Node("cyl", (d, z1 - z0, 0.0)), (0.0, 0.0, z0)))
                                                  for z0, z1, d in spans)))
        root = quill_lug_root(d_out, spans, lug_t)
        lug = _Node("box", ((root, -lug_w / 2, 0.0), (d_out / 2 + lug_l, lug_w / 2, lug_t)))
        return _Node("union", (sleeve, lug))
    if k == "split_collar":
        bore, d_out, w, slot = a
        ring = _Node("cyl", (d_out, w, bore))
        if slot <= 0:
            return ring
        return _Node("diff", (ring, (_Node("box", ((0.0, -slot / 2, 0.0), (d_out, slot / 2, w))),)))
    if k == "fuse":
        return _Node("union", tuple(primitive_tree(b) for b in a[0]))
    if k == "cut":
        return _Node("diff", (primitive_tree(a[0]), tuple(primitive_tree(t) for t in a[1])))
    if k == "translate":
        return _Node("move", (primitive_tree(a[0]), a[1]))
    if k == "single":
        return primitive_tree(a[0])
    raise ValueError(f"unknown body kind {k!r}")


def _node_box(n: _Node) -> tuple[np.ndarray, np.ndarray]:
    op, a = n.op, n.args
    if op == "box":
        return np.array(a[0], float), np.array(a[1], float)
    if op == "cyl":
        r = a[0] / 2
        return np.array([-r, -r, 0.0]), np.array([r, r, a[1]])
    if op == "cone":
        r = max(a[0], a[1])
        return np.array([-r, -r, 0.0]), np.array([r, r, a[2]])
    if op == "spring":
        d, mean, length = a[:3]
        r = mean / 2 + d / 2
        return np.array([-r, -r, 0.0]), np.array([r, r, length])
    if op == "rev":
        pr = np.asarray(a)
        r = float(pr[:, 0].max())
        return np.array([-r, -r, pr[:, 1].min()]), np.array([r, r, pr[:, 1].max()])
    if op == "move":
        lo, hi = _node_box(a[0])
        return lo + np.asarray(a[1]), hi + np.asarray(a[1])
    if op == "union":
        boxes = [_node_box(c) for c in a]
        return np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)
    if op == "inter":
        boxes = [_node_box(c) for c in a]
        return np.max([b[0] for b in boxes], axis=0), np.min([b[1] for b in boxes], axis=0)
    if op == "diff":
        return _node_box(a[0])
    raise ValueError(op)


def _aabb(body: Body) -> tuple[np.ndarray, np.ndarray]:
    return _node_box(primitive_tree(body))


def _rect_sdf(qx: np.ndarray, qz: np.ndarray) -> np.ndarray:
    """Signed distance of a 2-D rectangle given the per-axis distances past its sides (negative inside)."""
    outside = np.hypot(np.maximum(qx, 0.0), np.maximum(qz, 0.0))
    return outside + np.minimum(np.maximum(qx, qz), 0.0)


#: points x edges per block of :func:`polygon_distance`: small enough for the temporaries to stay
#: in cache (larger blocks measured slower on 1e4-1e5 points)
_POLYGON_BLOCK = 16_384


def _edge_distance(wx, wy, ex, ey, safe_len, inv_len):
    """Distance of points at ``(wx, wy)`` from edge starts to the edges ``(ex, ey)`` (broadcasting)."""
    t = np.clip((wx * ex + wy * ey) / safe_len, 0.0, 1.0) * inv_len
    return np.hypot(wx - t * ex, wy - t * ey)


def _ray_crosses(x, y, ax, ay, by, ex, ey_safe):
    """Whether the ray from ``(x, y)`` towards +x crosses the edges from ``(ax, ay)`` (broadcasting)."""
    crosses = (ay > y) != (by > y)
    xc = ax + (y - ay) * ex / ey_safe
    return crosses & (x < xc)


def _edges(poly: np.ndarray):
    """Per edge of the closed polygon: the next vertex, direction, and guards against zero lengths."""
    nxt = np.roll(poly, -1, axis=0)
    ex, ey = nxt[:, 0] - poly[:, 0], nxt[:, 1] - poly[:, 1]
    length2 = ex * ex + ey * ey
    degenerate = length2 <= 0
    inv_len = np.where(degenerate, 0.0, 1.0)  # a zero-length edge: its start point (t = 0)
    safe_len = np.where(degenerate, 1.0, length2)
    ey_safe = np.where(ey == 0, 1.0, ey)
    return nxt, ex, ey, inv_len, safe_len, ey_safe


def polygon_distance(px, py, poly) -> np.ndarray:
    """Signed distance (negative inside) of points (px, py) from the closed polygon ``poly`` (m, 2).

    Edges are read in blocks, as many at once as keep a block near :data:`_POLYGON_BLOCK` values:
    one numpy call per edge cost more than the arithmetic on a few hundred points (the gear
    sections have ~150 edges), a block of all edges more on 1e5 points (cache). For many calls on
    one polygon, :class:`PolygonDistance` gives the same numbers faster."""
    px, py = np.asarray(px, dtype=float), np.asarray(py, dtype=float)
    poly = np.asarray(poly, dtype=float)
    nxt, ex, ey, inv_len, safe_len, ey_safe = _edges(poly)
    x, y = px.reshape(-1, 1), py.reshape(-1, 1)
    d = np.full(x.shape[0], np.inf)
    crossings = np.zeros(x.shape[0], dtype=np.int64)
    step = max(1, _POLYGON_BLOCK // max(x.shape[0], 1))
    for s in range(0, len(poly), step):
        e = slice(s, s + step)
        ax, ay = poly[e, 0], poly[e, 1]
        d = np.minimum(d, np.min(_edge_distance(x - ax, y - ay, ex[e], ey[e], safe_len[e], inv_len[e]), axis=1))
        crossings += np.count_nonzero(_ray_crosses(x, y, ax, ay, nxt[e, 1], ex[e], ey_safe[e]), axis=1)
    return np.where(crossings % 2 == 1, -d, d).reshape(px.shape)


class PolygonDistance:
    """:func:`polygon_distance` of one polygon, for many calls on many points: the same numbers,
    each point measured against only the edges that can hold its nearest point or cross its ray.

    A grid of ``cells`` x ``cells`` over the polygon's box: for each cell, ``U`` the least over the
    edges of the largest distance from the cell to the edge (at a corner: the distance from a
    segment is convex), which bounds every point's distance in the cell from above; the edges
    whose box lies farther from the cell than ``U`` cannot be any point's nearest and are left
    out. The parity count keeps the edges whose height range meets the cell's and which reach
    the cell's left side (an edge not crossing a point's height, or crossing it left of the point,
    counts nothing). Both tests have a margin of 1e-9 of the polygon's size over rounding, so the
    edges kept always hold the nearest one and every crossing, and each distance is the same
    formula on the same numbers: the result is :func:`polygon_distance`'s to the last bit. Points
    outside the grid are measured against every edge.

    ``box`` ``(lo, hi)``: the grid's rectangle, where the calls' points lie if not the polygon's
    box (a gear section's teeth: the points come from its tooth band, a thin part of the box that
    reaches the centre); the edges kept per cell follow from the cell alone, so any box gives the
    same numbers, a tighter one fewer edges per point.
    """

    def __init__(self, poly, cells: int = 32, box=None):
        poly = np.asarray(poly, dtype=float)
        self.poly = poly
        nxt, ex, ey, inv_len, safe_len, ey_safe = _edges(poly)
        self._edges = (poly[:, 0], poly[:, 1], nxt[:, 1], ex, ey, inv_len, safe_len, ey_safe)
        margin = 1e-9 * max(float(np.max(poly.max(axis=0) - poly.min(axis=0))), 1e-300)
        lo, hi = (poly.min(axis=0), poly.max(axis=0)) if box is None else (np.asarray(box[0], float),
                                                                            np.asarray(box[1], float))
        self.lo, self.cells = lo, cells
        self.size = np.maximum(hi - lo, 1e-300) / cells
        gx = lo[0] + self.size[0] * np.arange(cells + 1)
        gy = lo[1] + self.size[1] * np.arange(cells + 1)
        cx, cy = (v.reshape(-1, 1) for v in np.meshgrid(gx, gy, indexing="ij"))
        corner = _edge_distance(cx - poly[:, 0], cy - poly[:, 1], ex, ey, safe_len, inv_len)
        corner = corner.reshape(cells + 1, cells + 1, -1)
        far = np.maximum(np.maximum(corner[:-1, :-1], corner[1:, :-1]), np.maximum(corner[:-1, 1:], corner[1:, 1:]))
        bound = far.min(axis=2)  # (c, c): every point of the cell is at most this far from the polygon
        x0, x1 = gx[:-1, None, None], gx[1:, None, None]
        y0, y1 = gy[None, :-1, None], gy[None, 1:, None]
        e_x0, e_x1 = np.minimum(poly[:, 0], nxt[:, 0]), np.maximum(poly[:, 0], nxt[:, 0])
        e_y0, e_y1 = np.minimum(poly[:, 1], nxt[:, 1]), np.maximum(poly[:, 1], nxt[:, 1])
        gap_x = np.maximum(np.maximum(e_x0 - x1, x0 - e_x1), 0.0)
        gap_y = np.maximum(np.maximum(e_y0 - y1, y0 - e_y1), 0.0)
        near = np.hypot(gap_x, gap_y) <= bound[..., None] + margin  # (c, c, E)
        cross = (e_y0 <= y1 + margin) & (e_y1 >= y0 - margin) & (e_x1 >= x0 - margin)
        cross = np.broadcast_to(cross, near.shape)
        self._near = self._padded(near.reshape(cells * cells, -1))
        self._cross = self._padded(cross.reshape(cells * cells, -1))

    @staticmethod
    def _padded(mask: np.ndarray):
        """Per cell its edges, all cells' in one array: (edge indices, each cell's first, count)."""
        count = mask.sum(axis=1)
        return np.nonzero(mask)[1], np.cumsum(count) - count, count

    @staticmethod
    def _pairs(table, cell: np.ndarray):
        """(point, edge) index pairs of the points in ``cell`` against their cells' edges, grouped by point."""
        edges, first, count = table
        n = count[cell]
        starts = np.cumsum(n) - n
        point = np.repeat(np.arange(cell.size), n)
        return point, edges[np.repeat(first[cell] - starts, n) + np.arange(point.size)], starts

    def __call__(self, px, py) -> np.ndarray:
        px, py = np.asarray(px, dtype=float), np.asarray(py, dtype=float)
        x, y = px.ravel(), py.ravel()
        i = np.floor((x - self.lo[0]) / self.size[0]).astype(np.int64)
        j = np.floor((y - self.lo[1]) / self.size[1]).astype(np.int64)
        in_grid = (i >= 0) & (i < self.cells) & (j >= 0) & (j < self.cells)
        out = np.empty(x.shape)
        if not np.all(in_grid):
            outside = ~in_grid
            out[outside] = polygon_distance(x[outside], y[outside], self.poly)
        if np.any(in_grid):
            cell = i[in_grid] * self.cells + j[in_grid]
            xs, ys = x[in_grid], y[in_grid]
            ax, ay, by, ex, ey, inv_len, safe_len, ey_safe = self._edges
            v, k, starts = self._pairs(self._near, cell)  # every cell has an edge: its bound's
            d = np.minimum.reduceat(_edge_distance(xs[v] - ax[k], ys[v] - ay[k], ex[k], ey[k], safe_len[k],
                                                   inv_len[k]), starts)
            v, k, _ = self._pairs(self._cross, cell)
            hit = _ray_crosses(xs[v], ys[v], ax[k], ay[k], by[k], ex[k], ey_safe[k])
            crossings = np.bincount(v[hit], minlength=cell.size)
            out[in_grid] = np.where(crossings % 2 == 1, -d, d)
        return out.reshape(px.shape)


#: profiles of more edges than this are measured through a :class:`PolygonDistance` grid (the same
#: numbers; the robot joint's bevel gears, 97 edges, read by the parts check 1.7-1.9 -> 0.2-0.6 us a point)
_GRID_EDGES = 16


def _compiled(n: _Node):
    """``n``'s signed distance as a function of points (k, 3) (:func:`_compiled_columns` of their columns)."""
    f = _compiled_columns(n)
    return lambda p: f(p[:, 0], p[:, 1], p[:, 2])


def _compiled_columns(n: _Node):
    """``n``'s signed distance as a function of the points' coordinates ``(x, y, z)`` (arrays of one
    shape): the tree read once, its constants (box centres, polygons, offsets) computed once, so a
    call does only the points' arithmetic, column by column (a move shifts three columns, not a
    (k, 3) copy; the primitives read contiguous columns, not strided ones: the same operations on
    the same numbers as on rows of points)."""
    op, a = n.op, n.args
    if op == "box":
        lo, hi = np.asarray(a[0]), np.asarray(a[1])
        c, h = (lo + hi) / 2, (hi - lo) / 2

        def box(x, y, z):
            # per axis (reductions over an axis of length 3 are slow in numpy)
            qx, qy, qz = (np.abs(v - c[i]) - h[i] for i, v in enumerate((x, y, z)))
            outside = np.sqrt(np.maximum(qx, 0.0) ** 2 + np.maximum(qy, 0.0) ** 2 + np.maximum(qz, 0.0) ** 2)
            return outside + np.minimum(np.maximum(np.maximum(qx, qy), qz), 0.0)
        return box
    if op == "cyl":
        d, height, bore = a

        def cyl(x, y, z):
            r = np.hypot(x, y)
            qr = r - d / 2
            if bore > 0:
                qr = np.maximum(qr, bore / 2 - r)
            return _rect_sdf(qr, np.abs(z - height / 2) - height / 2)
        return cyl
    if op in ("cone", "rev"):
        if op == "cone":
            r0, r1, height, bore = a
            poly = np.array([[bore / 2, 0.0], [r0, 0.0], [r1, height], [bore / 2, height]])
        else:
            poly = np.asarray(a, dtype=float)
        if len(poly) > _GRID_EDGES:  # a long profile (a bevel gear's): its edges near each point only
            lo, hi = poly.min(axis=0), poly.max(axis=0)
            pad = 0.1 * (hi - lo)  # points a little outside the profile's box still on the grid
            near = PolygonDistance(poly, box=((0.0, lo[1] - pad[1]), hi + pad))
            return lambda x, y, z: near(np.hypot(x, y), z)
        return lambda x, y, z: polygon_distance(np.hypot(x, y), z, poly)
    if op == "spring":
        return lambda x, y, z: _spring_columns(a, x, y, z)
    if op == "move":
        inner, offset = _compiled_columns(a[0]), np.asarray(a[1])
        ox, oy, oz = offset[0], offset[1], offset[2]
        return lambda x, y, z: inner(x - ox, y - oy, z - oz)
    if op in ("union", "inter"):
        parts = [_compiled_columns(c) for c in a]
        join = np.minimum if op == "union" else np.maximum

        def joined(x, y, z):
            out = parts[0](x, y, z)
            for f in parts[1:]:
                out = join(out, f(x, y, z))
            return out
        return joined
    if op == "diff":
        base, tools = _compiled_columns(a[0]), [_compiled_columns(t) for t in a[1]]

        def diff(x, y, z):
            out = base(x, y, z)
            for f in tools:
                out = np.maximum(out, -f(x, y, z))
            return out
        return diff
    raise ValueError(op)


def _node_sdf(n: _Node, p: np.ndarray) -> np.ndarray:
    """Signed distance (mm, negative inside) of points ``p`` (k, 3). Exact for the primitives;
    for unions, intersections and differences the usual min/max bound (exact in sign, a lower
    bound of the distance outside)."""
    return _compiled(n)(p)


def _spring_columns(args, px: np.ndarray, py: np.ndarray, pz: np.ndarray) -> np.ndarray:
    """The swept wire of :func:`compression_spring` at the points ``(px, py, pz)``: distance from its
    helix (:func:`spring_helix`) less d/2, cut to the slab [0, L]. The helix's nearest point is sought
    among the turns above and below the point's own angle, each refined by Newton steps."""
    d, mean, length, coils = args[:4]
    z0, pitch = spring_helix(args)
    radius = mean / 2
    theta = np.arctan2(py, px) % (2 * math.pi)
    best = np.full(len(px), np.inf)
    k0 = np.floor((pz - z0) / pitch - theta / (2 * math.pi))
    for dk in (-1.0, 0.0, 1.0, 2.0):
        t = np.clip(theta + 2 * math.pi * (k0 + dk), 0.0, 2 * math.pi * coils)
        for _ in range(4):  # Newton on the squared distance to (R cos t, R sin t, z0 + pitch t / 2 pi)
            c = pitch / (2 * math.pi)
            cos_t, sin_t = np.cos(t), np.sin(t)  # each read once: the trigonometry is most of the time
            hx, hy, hz = radius * cos_t, radius * sin_t, z0 + c * t
            dx, dy, dz = hx - px, hy - py, hz - pz
            g = dx * (-radius * sin_t) + dy * (radius * cos_t) + dz * c
            h = radius * radius + c * c - (dx * radius * cos_t + dy * radius * sin_t)
            t = np.clip(t - g / np.where(np.abs(h) < 1e-12, 1e-12, h), 0.0, 2 * math.pi * coils)
        c = pitch / (2 * math.pi)
        dist = np.sqrt((radius * np.cos(t) - px) ** 2 + (radius * np.sin(t) - py) ** 2
                       + (z0 + c * t - pz) ** 2)
        best = np.minimum(best, dist)
    wire = best - d / 2
    slab = np.abs(pz - length / 2) - length / 2
    return np.maximum(wire, slab)


def signed_distance(body: Body, points: np.ndarray) -> np.ndarray:
    """Signed distance (mm; negative inside) of ``points`` (k, 3), in the body's own frame."""
    return distance_function(body)(points)


def distance_function(body: Body):
    """:func:`signed_distance` of ``body`` as a function of the points (the body read once)."""
    sdf = _compiled(primitive_tree(body))
    return lambda points: sdf(np.asarray(points, dtype=float).reshape(-1, 3))


#: per point, relative to a cylinder's: a spring's Newton steps on its helix (measured 0.7 us a point
#: against a shaft's 0.02-0.03), a profile's polygon (per edge read)
_SPRING_COST = 30.0


def _node_cost(n: _Node) -> float:
    op, a = n.op, n.args
    if op in ("box", "cyl"):
        return 1.0
    if op == "spring":
        return _SPRING_COST
    if op in ("cone", "rev"):
        edges = 4 if op == "cone" else len(a)
        return 1.0 + (8.0 if edges > _GRID_EDGES else edges / 2)
    if op == "move":
        return _node_cost(a[0])
    if op == "diff":
        return _node_cost(a[0]) + sum(_node_cost(t) for t in a[1])
    return sum(_node_cost(c) for c in a)  # union, inter


def distance_cost(body: Body) -> float:
    """About how long :func:`column_distance_function` of ``body`` takes a point, relative to a
    cylinder's (to read the cheaper of two bodies first where the other is read only in part)."""
    return _node_cost(primitive_tree(body))


def column_distance_function(body: Body):
    """:func:`distance_function` of ``body`` as a function of the points' coordinates ``(x, y, z)``
    (float arrays of one shape: the same numbers, without stacking them into rows)."""
    return _compiled_columns(primitive_tree(body))


# ---------------------------------------------------------------- mass properties


@dataclass(frozen=True)
class MassProperties:
    """Of a body of unit density in its own frame (mm): ``volume`` mm^3, ``centre`` mm,
    ``axial_moment`` = integral of r^2 dV about the local z axis (mm^5)."""

    volume: float
    centre: tuple[float, float, float]
    axial_moment: float

    @property
    def off_axis(self) -> float:
        return math.hypot(self.centre[0], self.centre[1])


def _prim_mass(n: _Node) -> tuple[float, np.ndarray, float] | None:
    """(volume, first moment (3,), axial moment) of a primitive or a tree of disjoint pieces;
    None when the tree's pieces may overlap (then integrated numerically)."""
    op, a = n.op, n.args
    if op == "cyl":
        d, h, bore = a
        v = math.pi / 4 * (d * d - bore * bore) * h
        return v, np.array([0.0, 0.0, v * h / 2]), math.pi * h * ((d / 2) ** 4 - (bore / 2) ** 4) / 2
    if op == "box":
        lo, hi = np.asarray(a[0]), np.asarray(a[1])
        s = hi - lo
        v = float(np.prod(s))
        c = (lo + hi) / 2
        ix = s[0] ** 2 / 12 + c[0] ** 2
        iy = s[1] ** 2 / 12 + c[1] ** 2
        return v, v * c, v * (ix + iy)
    if op == "cone":
        r0, r1, h, bore = a
        if bore > 0:
            return None
        v = math.pi * h * (r0 * r0 + r0 * r1 + r1 * r1) / 3
        # integral of z dV and of r^2 dV over the frustum, r(z) = r0 + (r1 - r0) z / h
        zs, w = np.polynomial.legendre.leggauss(8)
        z = (zs + 1) * h / 2
        r = r0 + (r1 - r0) * z / h
        mz = float(np.sum(w * math.pi * r * r * z) * h / 2)
        jz = float(np.sum(w * math.pi * r ** 4 / 2) * h / 2)
        return v, np.array([0.0, 0.0, mz]), jz
    if op == "move":
        inner = _prim_mass(a[0])
        if inner is None:
            return None
        v, m, j = inner
        t = np.asarray(a[1])
        c = m / v if v else np.zeros(3)
        # parallel axis about z: shift of the centre in x, y
        cx, cy = c[0] + t[0], c[1] + t[1]
        j_new = j + v * ((cx * cx + cy * cy) - (c[0] ** 2 + c[1] ** 2))
        return v, m + v * t, j_new
    return None


def _disjoint(nodes) -> bool:
    boxes = [_node_box(c) for c in nodes]
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            lo = np.maximum(boxes[i][0], boxes[j][0])
            hi = np.minimum(boxes[i][1], boxes[j][1])
            if np.all(hi - lo > 1e-12):
                return False
    return True


def _tree_mass(n: _Node):
    own = _prim_mass(n)
    if own is not None:
        return own
    if n.op == "diff":
        base = _tree_mass(n.args[0])
        lo, hi = _node_box(n.args[0])
        tools = n.args[1]
        if base is None:
            return None
        v, m, j = base
        base_node = n.args[0]
        bore = base_node.args[2] if base_node.op == "cyl" else 0.0
        if base_node.op not in ("box", "cyl"):
            return None
        for t in tools:
            tm = _tree_mass(t)
            tlo, thi = _node_box(t)
            # a tool removes exactly its own mass only where the base is solid: inside the base's
            # box and, for a hollow cylinder, clear of its bore (the box's nearest point to the axis)
            if tm is None or np.any(tlo < lo - 1e-9) or np.any(thi > hi + 1e-9):
                return None
            near = np.hypot(max(tlo[0], 0.0, -thi[0]), max(tlo[1], 0.0, -thi[1]))
            if bore > 0 and near < bore / 2:
                return None
            v, m, j = v - tm[0], m - tm[1], j - tm[2]
        if not _disjoint(tools):
            return None
        return v, m, j
    if n.op == "union" and _disjoint(n.args):
        parts = [_tree_mass(c) for c in n.args]
        if any(p is None for p in parts):
            return None
        return sum(p[0] for p in parts), sum(p[1] for p in parts), sum(p[2] for p in parts)
    return None


def _slot_moments(bore: float, outer_diameter: float, slot: float) -> tuple[float, float, float]:
    """(area, first moment along x, polar moment) of the part of the ring bore/2 < r < D/2 in the
    radial slot x > 0, |y| < slot/2, in closed form: strips along x between the circles, integrated
    over y with the antiderivatives of sqrt(R^2 - y^2), y^2 sqrt(R^2 - y^2) and (R^2 - y^2)/2."""
    def strip(radius: float, y: float) -> np.ndarray:  # the integrals to y of x, x^2/2, x^3/3 + y^2 x at x = sqrt(R^2 - y^2)
        x = math.sqrt(max(radius * radius - y * y, 0.0))
        arc = radius * radius * math.asin(min(y / radius, 1.0))
        area = (y * x + arc) / 2
        y2x = (y * (2 * y * y - radius * radius) * x + radius * radius * arc) / 8
        return np.array([area, (radius * radius * y - y ** 3 / 3) / 2, (radius * radius * area + 2 * y2x) / 3])

    a, b = bore / 2, outer_diameter / 2
    h = min(slot / 2, b)
    total = 2 * strip(b, h)  # out to the outer circle over the whole slot (symmetric in y)
    if a > 0:
        total -= 2 * strip(a, min(h, a))  # less the bore's side, where the slot crosses it
    return float(total[0]), float(total[1]), float(total[2])


def _split_collar_mass(bore: float, outer_diameter: float, width: float, slot: float) -> MassProperties:
    ring_area = math.pi * (outer_diameter ** 2 - bore ** 2) / 4
    ring_polar = math.pi * (outer_diameter ** 4 - bore ** 4) / 32
    area, first_x, polar = _slot_moments(bore, outer_diameter, slot) if slot > 0 else (0.0, 0.0, 0.0)
    section = ring_area - area
    return MassProperties(section * width, (-first_x / section, 0.0, width / 2), (ring_polar - polar) * width)


def mass_properties(body: Body, cells: int = 96) -> MassProperties:
    """Volume, centre of mass and moment about the own z axis of ``body`` (unit density).

    Closed form for primitives and for pieces that do not overlap (bores and holes inside their
    part); otherwise a midpoint integration of the inside of the signed distance on a grid of
    ``cells`` per side of the body's box (the error is of the order of the boundary cells' share,
    ~1/cells)."""
    if body.kind == "split_collar":
        return _split_collar_mass(*body.args)
    tree = primitive_tree(body)
    closed = _tree_mass(tree)
    if closed is not None:
        v, m, j = closed
        c = m / v
        return MassProperties(float(v), (float(c[0]), float(c[1]), float(c[2])), float(j))
    lo, hi = _node_box(tree)
    axes = [np.linspace(lo[i], hi[i], cells + 1) for i in range(3)]
    mids = [(ax[1:] + ax[:-1]) / 2 for ax in axes]
    cell = float(np.prod((hi - lo) / cells))
    total_v, total_m, total_j = 0.0, np.zeros(3), 0.0
    gx, gy = np.meshgrid(mids[0], mids[1], indexing="ij")
    for z in mids[2]:
        pts = np.column_stack([gx.ravel(), gy.ravel(), np.full(gx.size, z)])
        inside = _node_sdf(tree, pts) < 0
        q = pts[inside]
        total_v += cell * len(q)
        total_m += cell * q.sum(axis=0)
        total_j += cell * float(np.sum(q[:, 0] ** 2 + q[:, 1] ** 2))
    c = total_m / total_v
    return MassProperties(total_v, (float(c[0]), float(c[1]), float(c[2])), total_j)


# ---------------------------------------------------------------- extents


def _axis_map(placement: np.ndarray) -> tuple[int, float]:
    """(world axis index, sign) that a placement turns the local z axis onto; ValueError when it
    is not a world axis (a round part's extent is exact only along the world's axes)."""
    axis = np.asarray(placement, float)[:3, 2]
    i = int(np.argmax(np.abs(axis)))
    if not abs(abs(axis[i]) - 1.0) < 1e-12:
        raise ValueError("a round part's extent is exact only when its axis is a world axis")
    return i, float(np.sign(axis[i]))


def _profile_extent(profile: np.ndarray, h: float, largest: bool) -> float | None:
    """Over the region of the closed polygon ``profile`` (r, s) where r > h: the smallest (or
    ``largest``) s. None when no part of it reaches beyond r = h."""
    found = []
    m = len(profile)
    for i in range(m):
        (r0, s0), (r1, s1) = profile[i], profile[(i + 1) % m]
        if r0 > h:
            found.append(s0)
        if (r0 - h) * (r1 - h) < 0:
            found.append(s0 + (h - r0) * (s1 - s0) / (r1 - r0))
    if not found:
        return None
    return max(found) if largest else min(found)


def _max_radius_in(profile: np.ndarray, lo: float, hi: float) -> float | None:
    """The largest r of the polygon ``profile`` (r, s) between s = lo and s = hi (None: none there)."""
    found = []
    m = len(profile)
    for i in range(m):
        (r0, s0), (r1, s1) = profile[i], profile[(i + 1) % m]
        if lo <= s0 <= hi:
            found.append(r0)
        for cut_s in (lo, hi):
            if (s0 - cut_s) * (s1 - cut_s) < 0:
                found.append(r0 + (cut_s - s0) * (r1 - r0) / (s1 - s0))
    return max(found) if found else None


def _prim_profile(n: _Node) -> np.ndarray:
    """A round primitive's (r, s) profile along its own axis (s: local z)."""
    if n.op == "cyl":
        d, h, bore = n.args
        return np.array([[bore / 2, 0.0], [d / 2, 0.0], [d / 2, h], [bore / 2, h]])
    if n.op == "cone":
        r0, r1, h, bore = n.args
        return np.array([[bore / 2, 0.0], [r0, 0.0], [r1, h], [bore / 2, h]])
    if n.op == "spring":
        d, mean, length = n.args[:3]
        return np.array([[mean / 2 - d / 2, 0.0], [mean / 2 + d / 2, 0.0], [mean / 2 + d / 2, length],
                         [mean / 2 - d / 2, length]])
    return np.asarray(n.args, float)  # "rev"


def _lowest_x(n: _Node, m: np.ndarray, z_min: float) -> float:
    op, a = n.op, n.args
    if op == "move":
        t = np.eye(4)
        t[:3, 3] = a[1]
        return _lowest_x(a[0], m @ t, z_min)
    if op == "union":
        return min(_lowest_x(c, m, z_min) for c in a)
    if op == "inter":
        return max(_lowest_x(c, m, z_min) for c in a)
    if op == "diff":  # what a cut removes is not subtracted: a bound from below
        return _lowest_x(a[0], m, z_min)
    if op == "box":  # the box cut by the plane z = z_min: its corners above and its edges' crossings
        idx = [(i, j, k) for i in (0, 1) for j in (0, 1) for k in (0, 1)]
        corners = {c: (np.array([a[c[0]][0], a[c[1]][1], a[c[2]][2], 1.0]) @ m.T)[:3] for c in idx}
        points = [p for p in corners.values() if p[2] > z_min]
        for c in idx:
            for axis in range(3):
                if c[axis] == 0:
                    d = list(c)
                    d[axis] = 1
                    p, q = corners[c], corners[tuple(d)]
                    if (p[2] - z_min) * (q[2] - z_min) < 0:
                        points.append(p + (z_min - p[2]) / (q[2] - p[2]) * (q - p))
        return float(min(p[0] for p in points)) if points else math.inf
    axis, sign = _axis_map(m)
    t = m[:3, 3]
    prof = _prim_profile(n)
    if axis == 2:  # round in x and y: its widest radius over the heights above z_min
        s_lo = (z_min - t[2]) * sign
        lo, hi = (s_lo, math.inf) if sign > 0 else (-math.inf, s_lo)
        r = _max_radius_in(prof, lo, hi)
        return math.inf if r is None else float(t[0] - r)
    if axis == 0:  # along x: the end of the part nearest -x that reaches above z_min
        s = _profile_extent(prof, z_min - t[2], largest=sign < 0)
        return math.inf if s is None else float(t[0] + sign * s)
    # along y: round in x and z
    h = z_min - t[2]
    r = float(prof[:, 0].max())
    if h <= 0:
        return float(t[0] - r)
    return float(t[0] - math.sqrt(r * r - h * h)) if h < r else math.inf


def lowest_x_above(body: Body, placement: np.ndarray, z_min: float) -> float:
    """The smallest world x of ``body``'s material above world height ``z_min`` (inf: none there),
    ``body`` placed by ``placement``. Exact for boxes in any placement and for round primitives
    whose axis is a world axis (ValueError for one that is not); what a cut removes is not
    subtracted (a bound from below)."""
    return _lowest_x(primitive_tree(body), np.asarray(placement, float), z_min)


def _world_box(n: _Node, m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    op, a = n.op, n.args
    if op == "move":
        t = np.eye(4)
        t[:3, 3] = a[1]
        return _world_box(a[0], m @ t)
    if op in ("union", "inter"):
        boxes = [_world_box(c, m) for c in a]
        if op == "union":
            return np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)
        return np.max([b[0] for b in boxes], axis=0), np.min([b[1] for b in boxes], axis=0)
    if op == "diff":
        return _world_box(a[0], m)
    if op == "box":
        corners = np.array([[x, y, z, 1.0] for x in (a[0][0], a[1][0]) for y in (a[0][1], a[1][1])
                            for z in (a[0][2], a[1][2])]) @ m.T
        return corners[:, :3].min(axis=0), corners[:, :3].max(axis=0)
    # round: each end circle (s, radius) of the profile spans +-r sqrt(1 - a_i^2) about its centre
    axis = m[:3, 2]
    spread = np.sqrt(np.clip(1.0 - axis * axis, 0.0, 1.0))
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for r, z in _prim_profile(n):
        c = (m @ np.array([0.0, 0.0, z, 1.0]))[:3]
        lo, hi = np.minimum(lo, c - r * spread), np.maximum(hi, c + r * spread)
    return lo, hi


def world_box(body: Body, placement: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The axis-aligned box (world, mm) of ``body`` placed by ``placement``: exact for boxes and for
    round primitives in any placement (each piece's own box, not the box of the body's box turned);
    what a cut removes is not subtracted."""
    return _world_box(primitive_tree(body), np.asarray(placement, float))


def describe(body: Body) -> dict[str, Any]:
    """The body as JSON-able data (kind and numbers), for ``resolved.json``."""
    def plain(v):
        if isinstance(v, Body):
            return describe(v)
        if isinstance(v, tuple):
            return [plain(x) for x in v]
        return v
    return {"kind": body.kind, "args": plain(body.args)}


__all__ = ["Body", "KINDS", "cylinder", "box", "box_between", "frustum", "shaft", "bearing", "servo_motor",
           "blade_flexure", "compression_spring", "spring_helix", "coil_envelope", "plate_with_holes", "link_tray", "link_cover",
           "quill", "quill_lug_root", "split_collar", "revolve", "fuse", "cut", "translate", "single", "ring_relief", "relieved",
           "primitive_tree", "signed_distance", "distance_function", "column_distance_function", "distance_cost", "polygon_distance", "lowest_x_above", "world_box", "MassProperties", "mass_properties", "describe"]
