"""The signed distances of geargen.model.bodies (compiled once per body, polygons read all edges at
once) against the per-node recursion they replaced (issue 28), kept here as the reference: on
every hardware body of the shipped designs and on random polygons, the two agree to the last bit
but signed zeros (both are the same float operations on each point, in the same order)."""

import math
from pathlib import Path

import numpy as np
import pytest

from geargen.design.assembly import load_design
from geargen.drives.resolver import resolve
from geargen.model.bodies import _node_box, _rect_sdf, polygon_distance, primitive_tree, signed_distance, spring_helix
from geargen.model.components import analytic_body
from geargen.model.layout import is_drive

ASSEMBLIES = Path(__file__).resolve().parents[2] / "assemblies"
# the shipped designs that are drives (dual_motor.toml is a train study: no placed hardware)
DESIGNS = sorted(p.stem for p in ASSEMBLIES.glob("*.toml") if is_drive(load_design(p)))


def reference_polygon_distance(px, py, poly):
    """The edge-by-edge reading (geargen before issue 28)."""
    d = np.full(px.shape, np.inf)
    inside = np.zeros(px.shape, bool)
    m = len(poly)
    for i in range(m):
        ax, ay = poly[i]
        bx, by = poly[(i + 1) % m]
        ex, ey = bx - ax, by - ay
        wx, wy = px - ax, py - ay
        length2 = ex * ex + ey * ey
        t = np.clip((wx * ex + wy * ey) / length2, 0.0, 1.0) if length2 > 0 else 0.0
        d = np.minimum(d, np.hypot(wx - t * ex, wy - t * ey))
        crosses = (ay > py) != (by > py)
        with np.errstate(divide="ignore", invalid="ignore"):
            xc = ax + (py - ay) * ex / np.where(ey == 0, 1.0, ey)
        inside ^= crosses & (px < xc)
    return np.where(inside, -d, d)


def reference_spring_sdf(args, p):
    """The spring's distance with each Newton step's sines and cosines computed twice (before issue 28)."""
    d, mean, length, coils = args[:4]
    z0, pitch = spring_helix(args)
    radius = mean / 2
    theta = np.arctan2(p[:, 1], p[:, 0]) % (2 * math.pi)
    best = np.full(len(p), np.inf)
    k0 = np.floor((p[:, 2] - z0) / pitch - theta / (2 * math.pi))
    for dk in (-1.0, 0.0, 1.0, 2.0):
        t = np.clip(theta + 2 * math.pi * (k0 + dk), 0.0, 2 * math.pi * coils)
        for _ in range(4):
            c = pitch / (2 * math.pi)
            hx, hy, hz = radius * np.cos(t), radius * np.sin(t), z0 + c * t
            dx, dy, dz = hx - p[:, 0], hy - p[:, 1], hz - p[:, 2]
            g = dx * (-radius * np.sin(t)) + dy * (radius * np.cos(t)) + dz * c
            h = radius * radius + c * c - (dx * radius * np.cos(t) + dy * radius * np.sin(t))
            t = np.clip(t - g / np.where(np.abs(h) < 1e-12, 1e-12, h), 0.0, 2 * math.pi * coils)
        c = pitch / (2 * math.pi)
        dist = np.sqrt((radius * np.cos(t) - p[:, 0]) ** 2 + (radius * np.sin(t) - p[:, 1]) ** 2
                       + (z0 + c * t - p[:, 2]) ** 2)
        best = np.minimum(best, dist)
    return np.maximum(best - d / 2, np.abs(p[:, 2] - length / 2) - length / 2)


def reference_node_sdf(n, p):
    """The per-node recursion (geargen before issue 28)."""
    op, a = n.op, n.args
    if op == "box":
        lo, hi = np.asarray(a[0]), np.asarray(a[1])
        c, h = (lo + hi) / 2, (hi - lo) / 2
        qx, qy, qz = (np.abs(p[:, i] - c[i]) - h[i] for i in range(3))
        outside = np.sqrt(np.maximum(qx, 0.0) ** 2 + np.maximum(qy, 0.0) ** 2 + np.maximum(qz, 0.0) ** 2)
        return outside + np.minimum(np.maximum(np.maximum(qx, qy), qz), 0.0)
    if op == "cyl":
        d, height, bore = a
        r = np.hypot(p[:, 0], p[:, 1])
        qr = r - d / 2
        if bore > 0:
            qr = np.maximum(qr, bore / 2 - r)
        qz = np.abs(p[:, 2] - height / 2) - height / 2
        return _rect_sdf(qr, qz)
    if op == "cone":
        r0, r1, height, bore = a
        r = np.hypot(p[:, 0], p[:, 1])
        poly = np.array([[bore / 2, 0.0], [r0, 0.0], [r1, height], [bore / 2, height]])
        return reference_polygon_distance(r, p[:, 2], poly)
    if op == "spring":
        return reference_spring_sdf(a, p)
    if op == "rev":
        return reference_polygon_distance(np.hypot(p[:, 0], p[:, 1]), p[:, 2], np.asarray(a))
    if op == "move":
        return reference_node_sdf(a[0], p - np.asarray(a[1]))
    if op == "union":
        return np.min([reference_node_sdf(c, p) for c in a], axis=0)
    if op == "inter":
        return np.max([reference_node_sdf(c, p) for c in a], axis=0)
    if op == "diff":
        out = reference_node_sdf(a[0], p)
        for t in a[1]:
            out = np.maximum(out, -reference_node_sdf(t, p))
        return out
    raise ValueError(op)


def _same(new, old):
    # exact equality: the same operations on the same floats (np.array_equal treats -0.0 == 0.0)
    assert new.shape == old.shape
    assert np.array_equal(new, old)


@pytest.mark.parametrize("name", DESIGNS)
def test_every_shipped_body_reads_as_the_per_node_recursion(name):
    layout = resolve(load_design(ASSEMBLIES / f"{name}.toml"))
    assert layout.hardware is not None and layout.hardware.components
    rng = np.random.default_rng(28)
    for component in layout.hardware.components:
        body = analytic_body(component)
        tree = primitive_tree(body)
        lo, hi = _node_box(tree)
        span = np.maximum(hi - lo, 1.0)
        # the box widened by a fifth each way: points inside, on the boundary band and outside
        points = lo - 0.2 * span + rng.uniform(0.0, 1.4, size=(4000, 3)) * span
        _same(signed_distance(body, points), reference_node_sdf(tree, points))


def test_random_polygons_read_as_edge_by_edge():
    rng = np.random.default_rng(7)
    for m in (3, 4, 17, 150):
        angles = np.sort(rng.uniform(0.0, 2 * np.pi, m))
        radii = rng.uniform(0.5, 2.0, m)
        poly = np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])
        poly[1] = poly[0]  # a zero-length edge: read at its start point
        poly[2, 1] = poly[3, 1] if m > 3 else poly[2, 1]  # a horizontal edge (ey == 0)
        px, py = rng.uniform(-2.5, 2.5, (2, 3000))
        px[:m], py[:m] = poly[:, 0], poly[:, 1]  # on the vertices
        _same(polygon_distance(px, py, poly), reference_polygon_distance(px, py, poly))
    # a grid of points (2-D shape kept) and more points than one block of edges
    px, py = np.meshgrid(np.linspace(-3, 3, 300), np.linspace(-3, 3, 40))
    _same(polygon_distance(px, py, poly), reference_polygon_distance(px, py, poly))


def test_cone_and_nested_trees_read_as_the_recursion():
    """A cone (no shipped body has one) inside a union, an intersection and a difference."""
    from geargen.model.bodies import _Node, _node_sdf
    cone = _Node("cone", (12.0, 5.0, 20.0, 4.0))
    tree = _Node("diff", (_Node("union", (cone, _Node("move", (_Node("cyl", (30.0, 3.0, 8.0)), (0.0, 0.0, 20.0))))),
                          (_Node("inter", (_Node("box", ((-2.0, -2.0, -1.0), (2.0, 2.0, 30.0))), cone)),)))
    points = np.random.default_rng(5).uniform(-20.0, 30.0, size=(5000, 3))
    _same(_node_sdf(tree, points), reference_node_sdf(tree, points))


def _shipped_gear_sections():
    from geargen.checks.hardware import gear_section
    from geargen.errors import GeometryError
    seen = {}
    for name in DESIGNS:
        for spec in resolve(load_design(ASSEMBLIES / f"{name}.toml")).design.gears.values():
            try:
                seen.setdefault(repr(spec), gear_section(spec)[0])
            except GeometryError:
                continue
    return list(seen.values())


def test_polygon_grid_reads_as_every_edge():
    """PolygonDistance (each point against its grid cell's edges, issue 28) against polygon_distance
    (every edge): on the shipped gears' sections and random polygons, points spread over the
    polygon's box and beyond it (the outside ones read every edge), on the vertices, on the grid's
    lines and cells' corners (the bounds' own points), exactly the same."""
    from geargen.model.bodies import PolygonDistance
    rng = np.random.default_rng(28)
    polygons = _shipped_gear_sections()
    assert len(polygons) >= 5
    for m in (3, 17, 150):
        angles = np.sort(rng.uniform(0.0, 2 * np.pi, m))
        poly = np.column_stack([np.cos(angles), np.sin(angles)]) * rng.uniform(0.5, 2.0, (m, 1))
        poly[1] = poly[0]  # a zero-length edge
        polygons.append(poly)
    for poly in polygons:
        lo, hi = poly.min(axis=0), poly.max(axis=0)
        # the grid over the polygon's box, over a part of it (as the parts check's tooth band) and
        # over a larger box: the edges kept per cell follow from the cell alone
        for box in (None, (lo + 0.55 * (hi - lo), hi - 0.05 * (hi - lo)), (lo - 0.3 * (hi - lo), hi + 0.1 * (hi - lo))):
            grid = PolygonDistance(poly, box=box)
            pad = 0.2 * (hi - lo)
            px, py = rng.uniform(lo - pad, hi + pad, (4000, 2)).T
            lines = grid.lo + grid.size * np.arange(grid.cells + 1)[:, None]
            gx, gy = np.meshgrid(lines[:, 0], lines[:, 1])
            px = np.concatenate([px, poly[:, 0], gx.ravel(), rng.uniform(lo[0], hi[0], 200)])
            py = np.concatenate([py, poly[:, 1], gy.ravel(), np.repeat(lines[5, 1], 200)])
            _same(grid(px, py), polygon_distance(px, py, poly))
