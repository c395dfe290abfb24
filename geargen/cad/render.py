"""A rendered view of an assembly as PNG, headless: tessellate each part, project, shade, paint.

No display and no OpenGL: every part is tessellated by the kernel (or its exported STL is
reused), the triangles are projected orthographically onto the view plane, shaded by the angle
between their normal and a light from the viewer's upper left, sorted back to front (painter's
algorithm) and drawn as one matplotlib ``PolyCollection`` on an Agg canvas. Transparent parts
(reference bodies) are drawn with their alpha.
"""

from __future__ import annotations

import io
import math
from pathlib import Path
from typing import Iterable

import numpy as np


def view_basis(azimuth_deg: float, elevation_deg: float) -> np.ndarray:
    """Rows: the view's right, up and towards-viewer unit vectors ``(3, 3)`` for a camera at
    ``azimuth`` (from +x towards +y) and ``elevation`` (above the xy plane), z up."""
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    towards = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
    right = np.cross([0.0, 0.0, 1.0], towards)
    right /= np.linalg.norm(right)
    up = np.cross(towards, right)
    return np.vstack([right, up, towards])


def render_parts(parts: Iterable, path: str | Path | None = None, view=(-60.0, 30.0), size=(9.0, 6.5),
                 dpi: int = 110, title: str = "", detail: float = 400.0,
                 meshes: dict[str, np.ndarray] | None = None) -> bytes:
    """Render placed parts (``PlacedPart`` of :mod:`geargen.cad.assembly`) to PNG; returns the bytes
    (and writes ``path`` if given).

    ``meshes`` (part name -> ``(n, 3, 3)`` triangles in the assembly frame, mm), e.g. the
    exported STL files, are drawn instead of tessellating those parts again; other parts are
    tessellated (:func:`part_triangles`) with a chordal tolerance of the model's largest size
    over ``detail``.
    """
    parts = list(parts)
    meshes = meshes or {}
    items = []
    extent = 1.0
    todo = [p for p in parts if p.name not in meshes]
    if todo:
        from geargen.cad.parts import bounding_box
        boxes = [bounding_box(p.world(), optimal=False) for p in todo]
        mins = np.array([lo for lo, _ in boxes])
        maxs = np.array([hi for _, hi in boxes])
        extent = float(np.max(maxs.max(axis=0) - mins.min(axis=0)))
    for p in parts:
        tri = meshes.get(p.name)
        if tri is None:
            tri = part_triangles(p, extent / detail)
        items.append((tri, p.colour))
    return render_triangles(items, path, view, size, dpi, title)


def part_triangles(part, tolerance: float, angular_tolerance: float = 0.5) -> np.ndarray:
    """Triangles ``(n, 3, 3)`` (mm, assembly frame) of a placed part within ``tolerance`` mm.

    A gear (a part carrying its ``GearSolid``) is meshed from its exact geometry
    (:func:`geargen.profile.tessellate.tessellate_layers`, ~50x faster than the kernel and a
    third of the triangles at a view's tolerance) and moved by the part's placement; any other
    part, or a gear that mesher cannot lay out, by the kernel.
    """
    from geargen.cad.export import solid_triangles

    source = part.solid if getattr(part, "solid", None) is not None else part.shape
    return solid_triangles(source, tolerance, angular_tolerance, transform=part.matrix, skip_unmeshed=True)[0]


def render_triangles(items, path: str | Path | None = None, view=(-60.0, 30.0), size=(9.0, 6.5), dpi: int = 110,
                     title: str = "") -> bytes:
    """Render ``items`` (``(triangles (n, 3, 3) mm, (r, g, b, alpha))``) to PNG bytes."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import PolyCollection
    from matplotlib.figure import Figure

    basis = view_basis(*view)
    light = basis.T @ np.array([-0.35, 0.45, 1.0])  # from the viewer's upper left
    light /= np.linalg.norm(light)
    polys, colours, depth = [], [], []
    for tri, (r, g, b, a) in items:
        if tri.size == 0:
            continue
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        norm = np.linalg.norm(n, axis=1)
        keep = norm > 0
        tri, n = tri[keep], n[keep] / norm[keep, None]
        facing = n @ basis[2]
        if a >= 0.99:  # opaque: back faces are hidden by the front ones
            sel = facing > 1e-9
            tri, n = tri[sel], n[sel]
        shade = 0.35 + 0.65 * np.abs(n @ light)
        rgb = np.clip(np.outer(shade, [r, g, b]), 0, 1)
        proj = tri @ basis.T  # (n, 3, 3): right, up, towards the viewer
        polys.append(proj[:, :, :2])
        colours.append(np.column_stack([rgb, np.full(len(rgb), a)]))
        depth.append(proj[:, :, 2].mean(axis=1))
    fig = Figure(figsize=size, dpi=dpi)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0, 0, 1, 0.94 if title else 1))
    if polys:
        P = np.concatenate(polys)
        C = np.concatenate(colours)
        D = np.concatenate(depth)
        order = np.argsort(D)
        ax.add_collection(PolyCollection(P[order], facecolors=C[order], edgecolors="none", antialiased=False))
        xy = P.reshape(-1, 2)
        lo, hi = xy.min(axis=0), xy.max(axis=0)
        pad = 0.03 * float(np.max(hi - lo))
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.axis("off")
    if title:
        fig.suptitle(title, fontsize=11)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, facecolor="white")
    data = buf.getvalue()
    if path is not None:
        Path(path).write_bytes(data)
    return data


__all__ = ["view_basis", "part_triangles", "render_parts", "render_triangles"]
