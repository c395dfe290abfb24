"""A rendered view of an assembly, headless: tessellate each part, project, rasterise with a depth buffer.

No display and no OpenGL: every part is tessellated by the kernel (or its exported STL is
reused), the triangles are projected orthographically onto the view plane, shaded by the angle
between their normal and a light from the viewer's upper left, and rasterised in numpy with a
depth buffer: each pixel shows the nearest opaque surface, and the translucent parts (reference
bodies) in front of it are blended over it nearest last. A depth buffer decides per pixel; a
painter's algorithm (whole triangles sorted by their centroid's depth, as this module did) cannot
draw a triangle that passes through another surface, e.g. a bearing's outer cylinder standing in
a gear's bore: the half of the cylinder's triangles whose centroid lies above the gear's face
were drawn whole, over the face, as a ring of spikes.

The result is plain data (:class:`RenderedView`: the image, which part each pixel shows, the
view's frame and scale); :mod:`geargen.report.view` draws it with labels, a scale bar and an
axis triad. matplotlib is not needed here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Iterable

import numpy as np

BACKGROUND = (1.0, 1.0, 1.0)
_FRAGMENTS_PER_CHUNK = 1_000_000  # bounds the rasteriser's temporaries (~100 MB); larger chunks were slower


def view_basis(azimuth_deg: float, elevation_deg: float) -> np.ndarray:
    """Rows: the view's right, up and towards-viewer unit vectors ``(3, 3)`` for a camera at
    ``azimuth`` (from +x towards +y) and ``elevation`` (above the xy plane), z up."""
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    towards = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
    right = np.cross([0.0, 0.0, 1.0], towards)
    right /= np.linalg.norm(right)
    up = np.cross(towards, right)
    return np.vstack([right, up, towards])


@dataclass
class RenderedView:
    """A rasterised view.

    ``image`` ``(h, w, 3)`` float RGB in [0, 1], row 0 at the top; ``part_index`` ``(h, w)`` int:
    the part (index into ``names``) seen at each pixel: the nearest opaque surface, else the
    nearest translucent one, -1 for the background;
    ``extent`` ``(left, right, bottom, top)``: the image's edges in view coordinates (mm, along the
    view's right and up vectors); ``basis`` the view's right/up/towards rows (:func:`view_basis`);
    ``colours`` the parts' RGBA."""

    image: np.ndarray
    part_index: np.ndarray
    names: list[str]
    colours: list[tuple[float, float, float, float]]
    extent: tuple[float, float, float, float]
    basis: np.ndarray
    title: str = ""
    kinds: list[str] = field(default_factory=list)  # each part's kind (its colour key), when known

    @property
    def mm_per_pixel(self) -> float:
        return (self.extent[1] - self.extent[0]) / self.image.shape[1]

    def to_view(self, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """View coordinates ``(k, 2)`` mm of pixel centres (``rows``, ``cols``)."""
        s = self.mm_per_pixel
        return np.column_stack([self.extent[0] + (np.asarray(cols) + 0.5) * s,
                                self.extent[3] - (np.asarray(rows) + 0.5) * s])


def render_parts(parts: Iterable, view=(-60.0, 30.0), size=(9.0, 6.5), dpi: int = 110, title: str = "",
                 detail: float = 400.0, meshes: dict[str, np.ndarray] | None = None) -> RenderedView:
    """Rasterise placed parts (``PlacedPart`` of :mod:`geargen.cad.assembly`) at ``size`` inches x ``dpi``.

    ``meshes`` (part name -> ``(n, 3, 3)`` triangles in the assembly frame, mm), e.g. the
    exported STL files, are drawn instead of tessellating those parts again; other parts are
    tessellated (:func:`part_triangles`) with a chordal tolerance of the model's largest size
    over ``detail``.
    """
    parts = list(parts)
    meshes = meshes or {}
    extent = 1.0
    todo = [p for p in parts if p.name not in meshes]
    if todo:
        from geargen.cad.parts import bounding_box
        boxes = [bounding_box(p.world(), optimal=False) for p in todo]
        mins = np.array([lo for lo, _ in boxes])
        maxs = np.array([hi for _, hi in boxes])
        extent = float(np.max(maxs.max(axis=0) - mins.min(axis=0)))
    items = []
    from geargen.cad.export import Tessellations
    made = Tessellations()  # parts sharing a solid are meshed once
    for p in parts:
        tri = meshes.get(p.name)
        if tri is None:
            tri = part_triangles(p, extent / detail, meshes=made)
        items.append((p.name, tri, p.colour))
    out = rasterise(items, view, (round(size[0] * dpi), round(size[1] * dpi)), title)
    out.kinds = [p.kind for p in parts]
    return out


def part_triangles(part, tolerance: float, angular_tolerance: float = 0.5, meshes=None) -> np.ndarray:
    """Triangles ``(n, 3, 3)`` (mm, assembly frame) of a placed part within ``tolerance`` mm.

    A gear (a part carrying its ``GearSolid``) is meshed from its exact geometry
    (:func:`geargen.profile.tessellate.tessellate_layers`, ~50x faster than the kernel and a
    third of the triangles at a view's tolerance), as is a toothed component by its family's own
    mesher (a bevel gear's), and moved by the part's placement; any other
    part, or a gear that mesher cannot lay out, by the kernel. ``meshes``: the
    :class:`geargen.cad.export.Tessellations` of the parts drawn together, so a solid placed more
    than once is meshed once.
    """
    from geargen.cad.export import Tessellations

    source = getattr(part, "mesh_source", None)
    source = part.shape if source is None else source
    return (meshes or Tessellations()).triangles(source, tolerance, angular_tolerance, transform=part.matrix,
                                                 skip_unmeshed=True)[0]


def _shaded(tri: np.ndarray, rgba, basis: np.ndarray, light: np.ndarray):
    """Non-degenerate triangles of one part (back faces dropped when opaque) and their flat RGB."""
    r, g, b, a = rgba
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    norm = np.linalg.norm(n, axis=1)
    keep = norm > 0
    tri, n = tri[keep], n[keep] / norm[keep, None]
    if a >= 0.99:  # opaque: back faces are hidden by the front ones
        sel = n @ basis[2] > 1e-9
        tri, n = tri[sel], n[sel]
    shade = 0.35 + 0.65 * np.abs(n @ light)
    return tri, np.clip(np.outer(shade, [r, g, b]), 0, 1)


def _fragments(xy: np.ndarray, depth: np.ndarray, width: int, height: int):
    """Yield ``(triangle, pixel, depth)`` arrays of the pixel centres inside each projected
    triangle, in chunks. ``xy`` ``(n, 3, 2)`` pixel coordinates (x right, y down), ``depth``
    ``(n, 3)`` (larger is nearer). Scanlines: each triangle's pixel rows, on each row the
    columns between its edges; depth from the triangle's plane. A pixel on an edge shared by two
    triangles belongs to both (the depth test or the blend decides), so no gap opens."""
    a, b, c = xy[:, 0], xy[:, 1], xy[:, 2]
    area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    row_lo = np.clip(np.ceil(xy[:, :, 1].min(axis=1) - 0.5), 0, height).astype(np.int64)
    row_hi = np.clip(np.floor(xy[:, :, 1].max(axis=1) - 0.5), -1, height - 1).astype(np.int64)
    rows = np.maximum(row_hi - row_lo + 1, 0)
    live = np.flatnonzero((rows > 0) & (np.abs(area) > 1e-9))
    xy, depth, area, row_lo, rows = xy[live], depth[live], area[live], row_lo[live], rows[live]
    # depth plane z = gx x + gy y + z0 of each triangle
    a, b, c = xy[:, 0], xy[:, 1], xy[:, 2]
    za, zb, zc = depth[:, 0], depth[:, 1], depth[:, 2]
    gx = ((zb - za) * (c[:, 1] - a[:, 1]) - (zc - za) * (b[:, 1] - a[:, 1])) / area
    gy = ((zc - za) * (b[:, 0] - a[:, 0]) - (zb - za) * (c[:, 0] - a[:, 0])) / area
    z0 = za - gx * a[:, 0] - gy * a[:, 1]
    # each edge's x at height y is x0 + (y - y0) * dx / dy, the products per triangle computed once;
    # each edge's numbers as a contiguous column (a gather from a column is faster than from (n, 3) by
    # (rows, edge)), a level edge (dy 0) given an empty y range so that no row crosses it
    x0, y0 = xy[:, :, 0], xy[:, :, 1]
    dx = np.roll(x0, -1, axis=1) - x0
    dy = np.roll(y0, -1, axis=1) - y0
    level = dy == 0
    y_min = np.where(level, np.inf, np.minimum(y0, np.roll(y0, -1, axis=1))).T.copy()
    y_max = np.where(level, -np.inf, np.maximum(y0, np.roll(y0, -1, axis=1))).T.copy()
    dy_safe = np.where(level, 1.0, dy).T.copy()
    x0, y0, dx = x0.T.copy(), y0.T.copy(), dx.T.copy()
    ends = np.cumsum(rows)
    start = 0
    while start < live.size:
        # a chunk of triangles holding about as many rows as a chunk of fragments allows
        budget = _FRAGMENTS_PER_CHUNK // 64
        stop = max(int(np.searchsorted(ends, (ends[start - 1] if start else 0) + budget, side="right")), start + 1)
        k = np.arange(start, stop)
        t = np.repeat(k, rows[k])
        y = (np.arange(t.size) - np.repeat(np.cumsum(rows[k]) - rows[k] - row_lo[k], rows[k])) + 0.5
        lo = np.full(t.size, np.inf)
        hi = np.full(t.size, -np.inf)
        for i in range(3):
            crosses = (y_min[i][t] <= y) & (y <= y_max[i][t])
            x = x0[i][t] + (y - y0[i][t]) * dx[i][t] / dy_safe[i][t]
            np.minimum(lo, x, out=lo, where=crosses)
            np.maximum(hi, x, out=hi, where=crosses)
        c_lo = np.clip(np.ceil(lo - 0.5 - 1e-9), 0, width).astype(np.int64)
        c_hi = np.clip(np.floor(hi - 0.5 + 1e-9), -1, width - 1).astype(np.int64)
        n = np.maximum(c_hi - c_lo + 1, 0)
        # each row's numbers repeated along its fragments (sequential copies, not gathers)
        col = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n - c_lo, n)
        # per row what does not change along it; z summed in the same order as gx x + gy y + z0
        z = np.repeat(gx[t], n) * (col + 0.5)
        z += np.repeat(gy[t] * y, n)
        z += np.repeat(z0[t], n)
        col += np.repeat((y - 0.5).astype(np.int64) * width, n)
        yield np.repeat(live[t], n), col, z
        start = stop


def rasterise(items, view=(-60.0, 30.0), pixels=(990, 715), title: str = "", margin: int = 12) -> RenderedView:
    """Rasterise ``items`` (``(name, triangles (n, 3, 3) mm, (r, g, b, alpha))``) into a
    :class:`RenderedView` of ``pixels`` (width, height), the model fitted inside ``margin`` pixels."""
    width, height = pixels
    basis = view_basis(*view)
    light = basis.T @ np.array([-0.35, 0.45, 1.0])  # from the viewer's upper left
    light /= np.linalg.norm(light)
    names, colours, tris, rgbs, owner, alphas = [], [], [], [], [], []
    for name, tri, rgba in items:
        names.append(name)
        colours.append(tuple(rgba))
        tri = np.asarray(tri, dtype=float).reshape(-1, 3, 3)
        if tri.size == 0:
            continue
        tri, rgb = _shaded(tri, rgba, basis, light)
        tris.append(tri @ basis.T)  # right, up, towards the viewer
        rgbs.append(rgb)
        owner.append(np.full(len(tri), len(names) - 1))
        alphas.append(np.full(len(tri), float(rgba[3])))
    image = np.empty((height * width, 3))
    image[:] = BACKGROUND
    part_index = np.full(height * width, -1)
    if not tris:
        return RenderedView(image.reshape(height, width, 3), part_index.reshape(height, width), names, colours,
                            (0.0, float(width), 0.0, float(height)), basis, title)
    proj = np.concatenate(tris)
    rgb = np.concatenate(rgbs)
    part = np.concatenate(owner)
    alpha = np.concatenate(alphas)
    xy_lo, xy_hi = proj[:, :, :2].reshape(-1, 2).min(axis=0), proj[:, :, :2].reshape(-1, 2).max(axis=0)
    scale = min((width - 2 * margin) / max(xy_hi[0] - xy_lo[0], 1e-12),
                (height - 2 * margin) / max(xy_hi[1] - xy_lo[1], 1e-12))  # pixels per mm
    centre = (xy_lo + xy_hi) / 2
    left, top = centre[0] - width / 2 / scale, centre[1] + height / 2 / scale
    pix = np.empty(proj.shape[:2] + (2,))
    pix[..., 0] = (proj[..., 0] - left) * scale
    pix[..., 1] = (top - proj[..., 1]) * scale
    depth = proj[..., 2]

    opaque = alpha >= 0.99
    zbuf = np.full(height * width, -np.inf)
    front = np.full(height * width, -1)  # the opaque triangle seen at each pixel
    ids = np.flatnonzero(opaque)
    for t, p, z in _fragments(pix[ids], depth[ids], width, height):
        np.maximum.at(zbuf, p, z)
        win = z >= zbuf[p]  # the nearest fragment of each pixel so far (ties: either)
        front[p[win]] = ids[t[win]]
    seen = front >= 0
    image[seen] = rgb[front[seen]]
    part_index[seen] = part[front[seen]]

    ids = np.flatnonzero(~opaque)
    if ids.size:
        # a translucent surface lying on an opaque one (a housing's bore round its bearing) is
        # behind it: without half a pixel of margin, rounding would show it on scattered pixels
        # t: each fragment's translucent triangle, numbered among them (their tables are small)
        chunks = []
        for t, p, z in _fragments(pix[ids], depth[ids], width, height):
            visible = z > zbuf[p] + 0.5 / scale
            chunks.append((t[visible], p[visible], z[visible]))
        t = np.concatenate([c[0] for c in chunks])
        p = np.concatenate([c[1] for c in chunks])
        z = np.concatenate([c[2] for c in chunks])
    if ids.size and t.size:  # none when the translucent parts lie wholly behind opaque ones
        span = max(float(z.max() - z.min()), 1e-12)
        key = np.subtract(z.max(), z, out=z)  # the key p + 0.5 (z_max - z) / span made in place
        key *= 0.5
        key /= span
        key += p
        order = np.argsort(key)  # by pixel, nearest first (one float key)
        t, p = t[order], p[order]
        # "over" from far to near, in closed form: each layer weighs alpha times the
        # transmittance of the layers in front of it; the background keeps the product of all
        alpha_of = alpha[ids]
        log_keep = np.log1p(-alpha_of)[t]  # each fragment's log(1 - alpha)
        run = np.cumsum(log_keep)
        head = np.empty(p.size, bool)
        head[0] = True
        np.not_equal(p[1:], p[:-1], out=head[1:])
        starts = np.flatnonzero(head)
        sizes = np.diff(starts, append=p.size)
        run_before = np.zeros(starts.size)
        run_before[1:] = run[starts[1:] - 1]
        run -= log_keep
        run -= np.repeat(run_before, sizes)
        weight = np.exp(run, out=run)
        weight *= alpha_of[t]
        pixels_hit = p[starts]
        total_keep = np.exp(np.add.reduceat(log_keep, starts))
        group = np.repeat(np.arange(starts.size), sizes)  # each fragment's pixel among the pixels hit
        # the pixels' rows gathered once, each channel blended as old * keep + the layers' sum
        hit = image[pixels_hit]
        hit *= total_keep[:, None]
        for k, channel in enumerate(rgb[ids].T.copy()):  # each channel contiguous: gathered from faster
            hit[:, k] += np.bincount(group, channel[t] * weight, minlength=starts.size)
        image[pixels_hit] = hit
        # where no opaque part is seen, the pixel shows its nearest translucent one (sorted first)
        bare = part_index[pixels_hit] < 0
        part_index[pixels_hit[bare]] = part[ids[t[starts][bare]]]
    right = left + width / scale
    bottom = top - height / scale
    return RenderedView(image.reshape(height, width, 3), part_index.reshape(height, width), names, colours,
                        (float(left), float(right), float(bottom), float(top)), basis, title)


__all__ = ["view_basis", "part_triangles", "render_parts", "rasterise", "RenderedView"]
