"""Placing annotation labels without overlap: the one placement step of the report's figures.

Each label is tried at candidate positions around its anchor (nearest first, in rings of
growing radius); a candidate's box is the text's drawn extent (matplotlib's renderer,
``get_window_extent``), and the first candidate wins whose box stays inside the axes and meets
no box placed before it and no obstacle: a circle outline crossing the box, a line segment
crossing it, or a region it should not cover. When no candidate is free the one with the
fewest conflicts is kept (text overlaps and circle crossings count before the rest). A label
moved away from its anchor gets a leader line.

Obstacles are given in data coordinates and tested in display pixels, after the axes' limits
are final (the caller sets them before placing).
:func:`place_sheet_labels` places the same way on a drawing sheet (sheet mm, each text measured by
the drawing font's advance widths).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

PAD_PX = 2.0  # clearance kept around every text box
RINGS_PT = (5, 14, 26, 40, 58, 80, 105, 135, 170)
DIRECTIONS = 16


@dataclass
class Obstacles:
    """What labels must keep clear of, in data coordinates: circle outlines ``(x, y, r)``, line
    segments ``((x0, y0), (x1, y1))`` and boxes ``(x0, y0, x1, y1)`` (e.g. the picture of a part)."""

    circles: list[tuple[float, float, float]] = field(default_factory=list)
    segments: list[tuple[tuple[float, float], tuple[float, float]]] = field(default_factory=list)
    boxes: list[tuple[float, float, float, float]] = field(default_factory=list)


def circle_crosses_box(centre, radius: float, box) -> bool:
    """Whether the circle outline of ``radius`` about ``centre`` passes through ``box``
    ``(x0, y0, x1, y1)``: the box's nearest point lies inside the circle and its farthest outside."""
    return _circles_crossing(box, np.array([[centre[0], centre[1], radius]])) > 0


def segment_crosses_box(p, q, box) -> bool:
    """Whether the segment ``p``-``q`` meets ``box`` ``(x0, y0, x1, y1)`` (Liang-Barsky clipping)."""
    x0, y0, x1, y1 = box
    t0, t1 = 0.0, 1.0
    dx, dy = q[0] - p[0], q[1] - p[1]
    for d, lo, hi, s in ((dx, x0, x1, p[0]), (dy, y0, y1, p[1])):
        if abs(d) < 1e-12:
            if s < lo or s > hi:
                return False
            continue
        a, b = (lo - s) / d, (hi - s) / d
        a, b = min(a, b), max(a, b)
        t0, t1 = max(t0, a), min(t1, b)
        if t0 > t1:
            return False
    return True


def _segments_crossing(box, segments: np.ndarray) -> int:
    """How many of ``segments`` ``(k, 4)`` (x0, y0, x1, y1) meet ``box``: :func:`segment_crosses_box`
    on all of them at once (the same arithmetic, so the same answers)."""
    return int(_crossing_segments(np.array([box], dtype=float), segments)[0])


def boxes_overlap(a, b) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def _candidates():
    yield 0.0, 0.0, 0
    for ring, radius in enumerate(RINGS_PT):
        for k in range(DIRECTIONS):
            angle = 2 * math.pi * k / DIRECTIONS + math.pi / 4  # up-right first
            yield radius * math.cos(angle), radius * math.sin(angle), ring + 1


#: each ring's candidate offsets (pt) as arrays ``(dx, dy)``, in :func:`_candidates`' order
_RING_OFFSETS = [tuple(np.array([c[i] for c in _candidates() if c[2] == ring]) for i in (0, 1))
                 for ring in range(len(RINGS_PT) + 1)]


def _alignment(dx: float, dy: float) -> tuple[str, str]:
    ha = "left" if dx > 1e-9 else "right" if dx < -1e-9 else "center"
    va = "bottom" if dy > 1e-9 else "top" if dy < -1e-9 else "center"
    return ha, va


def _circles_crossing(box, circles: np.ndarray) -> int:
    """How many of ``circles`` ``(k, 3)`` (x, y, r) have their outline through ``box``."""
    return int(_crossing_circles(np.array([box], dtype=float), circles)[0])


def place_labels(ax, labels, obstacles: Obstacles | None = None, placed: list | None = None,
                 leader_from_ring: int = 2, leader_colour: str = "0.35") -> list:
    """Add ``labels`` (``(text, (x, y) anchor in data coordinates, text keyword arguments)``) to
    ``ax``, each at its first free candidate position; returns the text artists.

    Each text is drawn once to measure it; its box at every candidate follows from that size.
    ``placed``: display boxes ``(x0, y0, x1, y1)`` already taken (e.g. other text); the boxes of
    the labels placed here are appended. A label set at the ``leader_from_ring``-th ring or
    farther gets a leader line to its anchor.
    """
    fig = ax.figure
    renderer = fig.canvas.get_renderer()
    obstacles = obstacles or Obstacles()
    to_px = ax.transData.transform
    px_per_pt = fig.dpi / 72.0
    circles = np.array([(*to_px((x, y)), abs(to_px((x + r, y))[0] - to_px((x, y))[0]))
                        for x, y, r in obstacles.circles]).reshape(-1, 3)
    segments = np.array([(*to_px(p), *to_px(q)) for p, q in obstacles.segments]).reshape(-1, 4)
    regions = []
    for x0, y0, x1, y1 in obstacles.boxes:
        (a, b), (c, d) = to_px((x0, y0)), to_px((x1, y1))
        regions.append((min(a, c), min(b, d), max(a, c), max(b, d)))
    regions = np.array(regions).reshape(-1, 4)
    frame = ax.get_window_extent(renderer)
    placed = placed if placed is not None else []
    artists = []
    for text, anchor, style in labels:
        probe = ax.annotate(text, anchor, ha="center", va="center", annotation_clip=False, **style)
        extent = text_extent(probe, renderer)
        probe.remove()
        box, dx, dy, ring = _choose((extent.width, extent.height), to_px(anchor), (frame.x0, frame.y0, frame.x1, frame.y1),
                                    np.array(placed).reshape(-1, 4), circles, segments, regions, px_per_pt, PAD_PX)
        ha, va = _alignment(dx, dy)
        leader = dict(arrowprops=dict(arrowstyle="-", color=leader_colour, lw=0.6, shrinkA=1, shrinkB=0)) \
            if ring >= leader_from_ring else {}
        artist = ax.annotate(text, anchor, xytext=(dx, dy), textcoords="offset points", ha=ha, va=va,
                             annotation_clip=False, **leader, **style)
        placed.append(box)
        artists.append(artist)
    return artists


def _choose(size, anchor, frame, taken, circles, segments, regions, unit_per_pt: float, pad: float):
    """The first free candidate position of a text of ``size`` about ``anchor`` (all in one unit: display
    px or sheet mm, ``unit_per_pt`` of them a point), else the one with the fewest conflicts: returns
    its box, offset (pt) and ring.

    A candidate's box is the text aligned as :func:`_alignment` aligns it at the offset, with
    ``pad`` around it. The candidates of a ring are tested together (a ring at a time, ~4x faster
    than one by one): the choice is the first free one, else the first of the fewest conflicts
    (text overlaps, circle crossings and leaving the ``frame`` count before segment crossings and
    covered regions, then the ring)."""
    w, h = size
    best = None
    for ring, (dx, dy) in enumerate(_RING_OFFSETS):
        dx_px, dy_px = dx * unit_per_pt, dy * unit_per_pt
        x, y = anchor[0] + dx_px, anchor[1] + dy_px
        x0 = np.where(dx_px > 1e-9, x, np.where(dx_px < -1e-9, x - w, x - w / 2))
        y0 = np.where(dy_px > 1e-9, y, np.where(dy_px < -1e-9, y - h, y - h / 2))
        boxes = np.column_stack([x0 - pad, y0 - pad, x0 + w + pad, y0 + h + pad])
        inside = (boxes[:, 0] >= frame[0]) & (boxes[:, 1] >= frame[1]) & (boxes[:, 2] <= frame[2]) & \
            (boxes[:, 3] <= frame[3])
        hard = _overlapping(boxes, taken) + _crossing_circles(boxes, circles) + ~inside
        soft = _crossing_segments(boxes, segments) + _overlapping(boxes, regions)
        k = int(np.lexsort((soft, hard))[0])  # the first of the fewest conflicts on this ring
        score = (int(hard[k]), int(soft[k]), ring)
        if best is None or score < best[0]:
            best = (score, tuple(float(v) for v in boxes[k]), float(dx[k]), float(dy[k]), ring)
        if score[:2] == (0, 0):
            break
    return best[1:]


def _overlapping(boxes, others: np.ndarray) -> np.ndarray:
    """How many of ``others`` ``(k, 4)`` each of ``boxes`` ``(c, 4)`` overlaps."""
    if not len(others):
        return np.zeros(len(boxes), int)
    b, o = boxes[:, None, :], others[None, :, :]
    return np.count_nonzero((o[..., 0] < b[..., 2]) & (b[..., 0] < o[..., 2]) & (o[..., 1] < b[..., 3]) &
                            (b[..., 1] < o[..., 3]), axis=1)


def _crossing_circles(boxes, circles: np.ndarray) -> np.ndarray:
    """How many of ``circles`` ``(k, 3)`` (x, y, r) have their outline through each of ``boxes`` ``(c, 4)``:
    the box's nearest point lies inside the circle and its farthest outside."""
    if not len(circles):
        return np.zeros(len(boxes), int)
    cx, cy, r = circles[None, :, 0], circles[None, :, 1], circles[None, :, 2]
    x0, y0, x1, y1 = (boxes[:, i, None] for i in range(4))
    near = np.hypot(np.clip(cx, x0, x1) - cx, np.clip(cy, y0, y1) - cy)
    far = np.max([np.hypot(x - cx, y - cy) for x in (x0, x1) for y in (y0, y1)], axis=0)
    return np.count_nonzero((near <= r) & (r <= far), axis=1)


def _crossing_segments(boxes, segments: np.ndarray) -> np.ndarray:
    """How many of ``segments`` ``(k, 4)`` meet each of ``boxes`` ``(c, 4)`` (Liang-Barsky clipping)."""
    if not len(segments):
        return np.zeros(len(boxes), int)
    px, py = segments[None, :, 0], segments[None, :, 1]
    shape = (len(boxes), len(segments))
    t0, t1 = np.zeros(shape), np.ones(shape)
    meets = np.ones(shape, dtype=bool)
    for d, lo, hi, s in ((segments[None, :, 2] - px, boxes[:, 0, None], boxes[:, 2, None], px),
                         (segments[None, :, 3] - py, boxes[:, 1, None], boxes[:, 3, None], py)):
        parallel = np.abs(d) < 1e-12
        meets &= ~(parallel & ((s < lo) | (s > hi)))
        step = np.where(parallel, 1.0, d)
        a, b = (lo - s) / step, (hi - s) / step
        t0 = np.where(parallel, t0, np.maximum(t0, np.minimum(a, b)))
        t1 = np.where(parallel, t1, np.minimum(t1, np.maximum(a, b)))
        meets &= ~(t0 > t1)
    return np.count_nonzero(meets, axis=1)


def place_sheet_labels(sheet, frame, labels, obstacles: Obstacles | None = None, leader_from_ring: int = 2,
                       leader_colour: str = "0.35") -> list:
    """:func:`place_labels` on a drawing sheet (:class:`geargen.report.drawing.Sheet`, sheet mm):
    ``labels`` ``(text, (x, y) anchor, {"size": pt, "color": ...})`` placed inside ``frame`` (x0, y0,
    x1, y1) by the same candidates and rules, each text measured by the sheet's font metrics; a
    label at the ``leader_from_ring``-th ring or farther gets a leader line to its anchor. Returns the
    recorded texts."""
    from geargen.report.vector import MM_PER_PT

    obstacles = obstacles or Obstacles()
    circles = np.array(obstacles.circles, dtype=float).reshape(-1, 3)
    segments = np.array([(*p, *q) for p, q in obstacles.segments], dtype=float).reshape(-1, 4)
    regions = np.array(obstacles.boxes, dtype=float).reshape(-1, 4)
    placed, out = [], []
    for text, anchor, style in labels:
        probe = sheet.text(anchor[0], anchor[1], text, ha="center", va="center", **style)
        sheet.drawing.items.remove(probe)
        size = (probe.box[2] - probe.box[0], probe.box[3] - probe.box[1])
        box, dx, dy, ring = _choose(size, anchor, frame, np.array(placed).reshape(-1, 4), circles, segments, regions,
                                    MM_PER_PT, PAD_PX * MM_PER_PT)
        ha, va = _alignment(dx, dy)
        x, y = anchor[0] + dx * MM_PER_PT, anchor[1] + dy * MM_PER_PT
        if ring >= leader_from_ring:
            # from the anchor to the text's box (its nearest point, 1 pt short of it)
            t0 = probe.box
            w, h = t0[2] - t0[0], t0[3] - t0[1]
            bx0 = x if ha == "left" else x - w if ha == "right" else x - w / 2
            by0 = y if va == "bottom" else y - h if va == "top" else y - h / 2
            nx, ny = min(max(anchor[0], bx0), bx0 + w), min(max(anchor[1], by0), by0 + h)
            sheet.line([anchor[0], nx], [anchor[1], ny], lw=0.6 * MM_PER_PT, color=leader_colour)
        out.append(sheet.text(x, y, text, ha=ha, va=va, **style))
        placed.append(box)
    return out


def text_extent(text, renderer=None):
    """The drawn extent of a text artist's text alone (an annotation's own extent includes its
    leader line)."""
    from matplotlib.text import Text
    return Text.get_window_extent(text, renderer or text.figure.canvas.get_renderer())


def text_boxes(fig) -> list[tuple[str, tuple[float, float, float, float]]]:
    """Every visible, non-empty text of ``fig`` with its drawn display box ``(x0, y0, x1, y1)``
    (for tests and for callers that place around existing text)."""
    from matplotlib.text import Text
    renderer = fig.canvas.get_renderer()
    out = []
    for t in fig.findobj(lambda a: isinstance(a, Text)):
        if not t.get_visible() or not t.get_text().strip():
            continue
        e = text_extent(t, renderer)
        if e.width > 0 and e.height > 0 and np.all(np.isfinite([e.x0, e.y0, e.x1, e.y1])):
            out.append((t.get_text(), (e.x0, e.y0, e.x1, e.y1)))
    return out


__all__ = ["Obstacles", "place_labels", "place_sheet_labels", "text_boxes", "text_extent", "circle_crosses_box", "segment_crosses_box",
           "boxes_overlap"]
