"""The 2-D layout drawing of an assembly: gear circles, centres, lines of action, the symmetry
line and the preload carriage's travel (matplotlib, Agg canvas, no pyplot), labels placed clear of
each other and of the drawing (:mod:`geargen.report.labels`).

Input is plain data (:class:`LayoutGear`, :class:`LayoutMesh`), in mm in the output gear's
frame (+x the symmetry line towards the input); the drawing is labelled in the design's unit.
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from geargen.core.involute import working_pressure_angle_at
from geargen.units import LENGTH_SUFFIXES


@dataclass(frozen=True)
class LayoutGear:
    """One toothed body seen along the axes: ``centre`` (x, y), radii (mm), its teeth."""

    name: str
    centre: tuple[float, float]
    reference_radius: float
    tip_radius: float
    root_radius: float
    base_radius: float
    teeth: int


@dataclass(frozen=True)
class LayoutMesh:
    """A mesh: the two gear names, and which line of action carries the working flanks
    (``side`` +1 or -1: the tangent to the base circles turned counter-clockwise or clockwise
    from the line of centres; 0: draw both)."""

    name: str
    gear1: str
    gear2: str
    side: int = 0
    working: str = ""  # "ccw" / "cw": gear 1's flank that carries load; picks ``side`` when 0


def line_of_action(c1, rb1: float, c2, rb2: float, side: int) -> np.ndarray:
    """The transverse line of action of two external gears: the internal tangent of their base
    circles from gear 1's tangent point to gear 2's, ``(2, 2)`` (mm).

    ``side`` +1 takes the tangent whose tangent point on gear 1 lies at the line of centres turned
    by +alpha_w, -1 the other: the radius to the tangent point is normal to the line of action,
    and ``cos(alpha_w) = (rb1 + rb2) / a = rb1 / r_w1``, so the line of action crosses the line of
    centres at pi/2 - alpha_w, through the pitch point.
    """
    c1, c2 = np.asarray(c1, float), np.asarray(c2, float)
    d = c2 - c1
    a = float(np.hypot(*d))
    beta = math.atan2(d[1], d[0])
    alpha_w = working_pressure_angle_at(float(rb1 + rb2), a, clamp=True)
    phi = beta + side * alpha_w  # direction from centre 1 to its tangent point
    u = np.array([math.cos(phi), math.sin(phi)])
    return np.vstack([c1 + rb1 * u, c2 - rb2 * u])


def working_side(c1, rb1: float, c2, rb2: float, flank: str) -> int:
    """The ``side`` of :func:`line_of_action` on which gear 1's ``flank`` ("ccw": the flank that
    leads when gear 1 turns counter-clockwise) pushes gear 2: the reaction on gear 1 must then
    turn it clockwise, i.e. (T1 - c1) x (T2 - T1) > 0."""
    for side in (1, -1):
        t1, t2 = line_of_action(c1, rb1, c2, rb2, side)
        u, t = t1 - np.asarray(c1, float), t2 - t1
        cross = u[0] * t[1] - u[1] * t[0]
        if (cross > 0) == (flank == "ccw"):
            return side
    return 0


def layout_figure(gears: list[LayoutGear], meshes: list[LayoutMesh], length_unit: str = "mm", title: str = "",
                  carriage: tuple[tuple[float, float], float] | None = None, symmetry_line: bool = True,
                  notes: list[str] = ()):
    """The layout drawing as a matplotlib ``Figure`` (Agg canvas, no pyplot).

    ``carriage``: ``((x, y), travel)``: the preload carriage's position (the input gear's centre)
    and its travel either way along the symmetry line (mm), drawn as a double arrow. The labels
    are placed by :func:`geargen.report.labels.place_labels`, clear of each other, of every
    circle and of every drawn line.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle, FancyArrowPatch

    from geargen.report.labels import Obstacles, place_labels

    scale = LENGTH_SUFFIXES[length_unit]
    fig = Figure(figsize=(9, 7.5), dpi=110)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    by = {g.name: g for g in gears}
    obstacles = Obstacles()
    seen = set()
    names_at: dict[tuple, list[str]] = {}
    for g in gears:
        x, y = (v / scale for v in g.centre)
        names_at.setdefault((round(x, 9), round(y, 9)), []).append(f"{g.name} {g.teeth} T")
    for (x, y) in names_at:
        ax.plot([x], [y], "+", color="k", ms=9)
    for g in gears:
        x, y = (v / scale for v in g.centre)
        key = (round(x, 9), round(y, 9), g.reference_radius)
        if key in seen:
            continue
        seen.add(key)
        for radius, style in ((g.tip_radius, dict(lw=0.9, color="0.35")),
                              (g.reference_radius, dict(lw=0.8, ls="-.", color="tab:blue")),
                              (g.base_radius, dict(lw=0.6, ls=":", color="tab:green")),
                              (g.root_radius, dict(lw=0.5, color="0.6"))):
            ax.add_patch(Circle((x, y), radius / scale, fill=False, **style))
            obstacles.circles.append((x, y, radius / scale))
    for m in meshes:
        g1, g2 = by[m.gear1], by[m.gear2]
        side = m.side or (working_side(g1.centre, g1.base_radius, g2.centre, g2.base_radius, m.working)
                          if m.working else 0)
        m = LayoutMesh(m.name, m.gear1, m.gear2, side)
        for side in ((m.side,) if m.side else (1, -1)):
            seg = line_of_action(g1.centre, g1.base_radius, g2.centre, g2.base_radius, side) / scale
            ax.plot(seg[:, 0], seg[:, 1], color="tab:red", lw=1.2 if m.side else 0.8, ls="-" if m.side else "--")
            obstacles.segments.append((tuple(seg[0]), tuple(seg[1])))
        centres = ((g1.centre[0] / scale, g1.centre[1] / scale), (g2.centre[0] / scale, g2.centre[1] / scale))
        ax.plot([centres[0][0], centres[1][0]], [centres[0][1], centres[1][1]], color="0.5", lw=0.5, ls=(0, (2, 3)))
        obstacles.segments.append(centres)
    xs = [g.centre[0] / scale for g in gears]
    rs = [g.tip_radius / scale for g in gears]
    lo_x = min(x - r for x, r in zip(xs, rs))
    hi_x = max(x + r for x, r in zip(xs, rs))
    labels = [("\n".join(text), (x, y), dict(fontsize=7)) for (x, y), text in names_at.items()]
    if symmetry_line:
        ax.axhline(0.0, color="tab:purple", lw=0.8, ls=(0, (8, 3, 2, 3)))
        # anchored inside the output gear (at the origin), where the drawing leaves room
        labels.append(("symmetry line", (0.5 * lo_x, 0.0), dict(fontsize=7, color="tab:purple")))
    if carriage is not None:
        (cx, cy), travel = carriage
        cx, cy, t = cx / scale, cy / scale, travel / scale
        span = max(t, 0.04 * (hi_x - lo_x))  # drawn at least visibly long; the label gives the number
        y_arrow = cy - 0.12 * (hi_x - lo_x)
        ax.add_patch(FancyArrowPatch((cx - span, y_arrow), (cx + span, y_arrow),
                                     arrowstyle="<->", mutation_scale=10, color="tab:orange"))
        obstacles.segments.append(((cx - span, y_arrow), (cx + span, y_arrow)))
        labels.append((f"carriage travel ±{t:.4g} {length_unit}", (cx, y_arrow),
                       dict(fontsize=7, color="tab:orange")))
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel(f"x ({length_unit}), output gear centre at the origin")
    ax.set_ylabel(f"y ({length_unit})")
    ax.grid(True, lw=0.3, alpha=0.5)
    legend = ("grey: tip and root circles; blue dash-dot: reference (pitch) circles; green dotted: base circles; "
              "red: lines of action (solid: working flanks)")
    ax.set_title((title + "\n" if title else "") + legend, fontsize=7)
    for i, n in enumerate(notes):
        fig.text(0.01, 0.01 + 0.025 * i, n, fontsize=7)
    if symmetry_line:
        x0, x1 = ax.get_xlim()
        obstacles.segments.append(((x0, 0.0), (x1, 0.0)))
    # the axes' limits and box are final (the equal aspect applied: what the draw would do first; the
    # tick labels are laid out when read): the labels are placed in display space
    ax.apply_aspect()
    ax.set_xlim(ax.get_xlim())
    ax.set_ylim(ax.get_ylim())
    ax.set_autoscale_on(False)
    place_labels(ax, labels, obstacles)
    _hide_colliding_ticks(ax)
    return fig


def _hide_colliding_ticks(ax) -> None:
    """Hide an x tick label that runs into a y tick label (at the axes' lower left corner when
    both axes start at a tick)."""
    from geargen.report.labels import boxes_overlap, text_extent
    y_boxes = [(e.x0, e.y0, e.x1, e.y1) for e in (text_extent(t) for t in ax.get_yticklabels()
                                                  if t.get_visible() and t.get_text())]
    for t in ax.get_xticklabels():
        if t.get_visible() and t.get_text():
            e = text_extent(t)
            if any(boxes_overlap((e.x0, e.y0, e.x1, e.y1), b) for b in y_boxes):
                t.set_visible(False)


def plot_layout(gears: list[LayoutGear], meshes: list[LayoutMesh], path: str | Path | None = None,
                length_unit: str = "mm", title: str = "", carriage: tuple[tuple[float, float], float] | None = None,
                symmetry_line: bool = True, notes: list[str] = ()) -> bytes:
    """:func:`layout_figure` as PNG bytes (and written to ``path`` if given)."""
    fig = layout_figure(gears, meshes, length_unit, title, carriage, symmetry_line, notes)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", facecolor="white")
    data = buf.getvalue()
    if path is not None:
        from geargen.outputs import write_file
        write_file(path, data)
    return data


__all__ = ["LayoutGear", "LayoutMesh", "line_of_action", "working_side", "layout_figure", "plot_layout"]
