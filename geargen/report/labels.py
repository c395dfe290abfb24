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

import itertools
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
    return int(_segments_crossing_boxes(np.array([box], dtype=float), segments)[0])


def _segments_crossing_boxes(boxes: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """:func:`_segments_crossing` for each of ``boxes`` ``(m, 4)``: counts ``(m,)``."""
    if not len(segments):
        return np.zeros(len(boxes), dtype=np.int64)
    px, py = segments[:, 0], segments[:, 1]
    t0, t1 = np.zeros((len(boxes), len(segments))), np.ones((len(boxes), len(segments)))
    meets = np.ones((len(boxes), len(segments)), dtype=bool)
    for d, lo, hi, s in ((segments[:, 2] - px, boxes[:, 0:1], boxes[:, 2:3], px),
                         (segments[:, 3] - py, boxes[:, 1:2], boxes[:, 3:4], py)):
        parallel = np.abs(d) < 1e-12
        meets &= ~(parallel & ((s < lo) | (s > hi)))
        step = np.where(parallel, 1.0, d)
        a, b = (lo - s) / step, (hi - s) / step
        t0 = np.where(parallel, t0, np.maximum(t0, np.minimum(a, b)))
        t1 = np.where(parallel, t1, np.minimum(t1, np.maximum(a, b)))
        meets &= ~(t0 > t1)
    return np.count_nonzero(meets, axis=1)


def boxes_overlap(a, b) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def _candidates():
    yield 0.0, 0.0, 0
    for ring, radius in enumerate(RINGS_PT):
        for k in range(DIRECTIONS):
            angle = 2 * math.pi * k / DIRECTIONS + math.pi / 4  # up-right first
            yield radius * math.cos(angle), radius * math.sin(angle), ring + 1


def _alignment(dx: float, dy: float) -> tuple[str, str]:
    ha = "left" if dx > 1e-9 else "right" if dx < -1e-9 else "center"
    va = "bottom" if dy > 1e-9 else "top" if dy < -1e-9 else "center"
    return ha, va


def _box_at(anchor_px, size, dx_px: float, dy_px: float, pad: float = PAD_PX) -> tuple[float, float, float, float]:
    """The display box of a text of ``size`` (w, h) set at ``anchor_px`` + offset, aligned as
    :func:`_alignment` aligns it, with ``pad`` (:data:`PAD_PX`) around it."""
    w, h = size
    ha, va = _alignment(dx_px, dy_px)
    x = anchor_px[0] + dx_px
    y = anchor_px[1] + dy_px
    x0 = x if ha == "left" else x - w if ha == "right" else x - w / 2
    y0 = y if va == "bottom" else y - h if va == "top" else y - h / 2
    return (x0 - pad, y0 - pad, x0 + w + pad, y0 + h + pad)


def _overlaps_boxes(boxes: np.ndarray, others: np.ndarray) -> np.ndarray:
    """How many of ``others`` ``(k, 4)`` each of ``boxes`` ``(m, 4)`` overlaps: counts ``(m,)``."""
    if not len(others):
        return np.zeros(len(boxes), dtype=np.int64)
    b = boxes[:, :, None]
    return np.count_nonzero((others[:, 0] < b[:, 2]) & (b[:, 0] < others[:, 2]) &
                            (others[:, 1] < b[:, 3]) & (b[:, 1] < others[:, 3]), axis=1)


def _circles_crossing(box, circles: np.ndarray) -> int:
    """How many of ``circles`` ``(k, 3)`` (x, y, r) have their outline through ``box``."""
    return int(_circles_crossing_boxes(np.array([box], dtype=float), circles)[0])


def _circles_crossing_boxes(boxes: np.ndarray, circles: np.ndarray) -> np.ndarray:
    """:func:`_circles_crossing` for each of ``boxes`` ``(m, 4)``: counts ``(m,)``."""
    if not len(circles):
        return np.zeros(len(boxes), dtype=np.int64)
    cx, cy, r = circles[:, 0], circles[:, 1], circles[:, 2]
    b = boxes[:, :, None]
    near = np.hypot(np.clip(cx, b[:, 0], b[:, 2]) - cx, np.clip(cy, b[:, 1], b[:, 3]) - cy)
    far = np.max([np.hypot(x - cx, y - cy) for x in (b[:, 0], b[:, 2]) for y in (b[:, 1], b[:, 3])], axis=0)
    return np.count_nonzero((near <= r) & (r <= far), axis=1)


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
    # every box's corners in one transform (the same arithmetic row by row as one call per corner)
    corners = to_px(np.array(obstacles.boxes, dtype=float).reshape(-1, 2)).reshape(-1, 4)
    regions = np.column_stack([np.minimum(corners[:, 0], corners[:, 2]), np.minimum(corners[:, 1], corners[:, 3]),
                               np.maximum(corners[:, 0], corners[:, 2]), np.maximum(corners[:, 1], corners[:, 3])])
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
        leader = {}
        if ring >= leader_from_ring:
            start = _leader_start(box, to_px(anchor), _frame_pad(probe, renderer), px_per_pt)
            if start is not None:
                # drawn from where matplotlib would clip it (the text's frame, then 1 pt short of it),
                # given as the fraction of the text's box it starts at: no clipping by bisection at each draw
                leader = dict(arrowprops=dict(arrowstyle="-", color=leader_colour, lw=0.6, shrinkA=0, shrinkB=0,
                                              patchA=None, relpos=start))
        artist = ax.annotate(text, anchor, xytext=(dx, dy), textcoords="offset points", ha=ha, va=va,
                             annotation_clip=False, **leader, **style)
        placed.append(box)
        artists.append(artist)
    return artists


LEADER_SHORT_PT = 1.0  # a leader stops this far short of its text's frame


def _frame_pad(text, renderer) -> tuple[float, float]:
    """The frame matplotlib clips an annotation's leader to, around the text's box (display px):
    its pad and the size of its rounded corners (0: square): the text's bbox patch if it has one
    (``boxstyle="round,pad=..."`` or ``"square,..."``: sizes in font sizes; grown by half its edge, a
    rounded corner taken as the same curve that much larger), else a rectangle 2 pt out."""
    patch = text.get_bbox_patch()
    if patch is None:
        return renderer.points_to_pixels(4.0) / 2, 0.0
    style = patch.get_boxstyle()
    kind = type(style).__name__
    if kind not in ("Round", "Square"):
        raise ValueError(f"a leader to a text framed as {kind}: only round or square frames are placed")
    font = renderer.points_to_pixels(text.get_size())
    # matplotlib's test of a point inside a patch counts half its edge's width (display px) as inside
    edge = patch.get_linewidth() / 2 if patch.get_edgecolor()[3] > 0 else 0.0
    pad = style.pad * font
    corner = (style.rounding_size * font if getattr(style, "rounding_size", None) else pad) if kind == "Round" else 0.0
    return pad + edge, corner + edge if corner > 0 else 0.0


def _leader_start(box, anchor, frame: tuple[float, float], px_per_pt: float):
    """Where an annotation's leader from its text (``box``: the text's display box with :data:`PAD_PX`
    around it) to ``anchor`` (display px) starts, as matplotlib draws it: on the line from the
    text's centre to the anchor, where it leaves the text's frame (:func:`_frame_pad`; a rounded
    corner is matplotlib's quadratic Bezier, sqrt(a) + sqrt(b) = sqrt(r) in the distances a, b from
    the corner's sides), then :data:`LEADER_SHORT_PT` further. Returned as the fraction of the
    text's box it lies at (matplotlib's ``relpos``); None when that point is not short of the anchor."""
    x0, y0, x1, y1 = box[0] + PAD_PX, box[1] + PAD_PX, box[2] - PAD_PX, box[3] - PAD_PX
    w, h = x1 - x0, y1 - y0
    centre = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    run = np.asarray(anchor, float) - centre
    length = float(np.hypot(*run))
    if length == 0 or w <= 0 or h <= 0:
        return None
    u = run / length
    pad, corner = frame
    half = np.array([w / 2 + pad, h / 2 + pad])
    with np.errstate(divide="ignore"):
        t = float(np.min(np.where(u != 0, half / np.abs(u), np.inf)))  # leaves the padded rectangle

    def inside_corner(t):  # sqrt(a) + sqrt(b) >= sqrt(r): on the frame's side of the corner's curve
        a, b = half - np.abs(t * u)
        return a >= corner or b >= corner or math.sqrt(max(a, 0.0)) + math.sqrt(max(b, 0.0)) >= math.sqrt(corner)

    if corner > 0 and not inside_corner(t):
        lo, hi = max(t - 2 * corner, 0.0), t  # a + b >= 2 r at lo: inside
        for _ in range(40):  # to 2**-40 of the corner: far below a pixel
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if inside_corner(mid) else (lo, mid)
        t = lo
    t += LEADER_SHORT_PT * px_per_pt
    if t >= length:
        return None
    start = centre + t * u
    return (float((start[0] - x0) / w), float((start[1] - y0) / h))


def _choose(size, anchor, frame, taken, circles, segments, regions, unit_per_pt: float, pad: float):
    """The first free candidate position of a text of ``size`` about ``anchor`` (all in one unit: display
    px or sheet mm, ``unit_per_pt`` of them a point), else the one with the fewest conflicts: returns
    its box, offset (pt) and ring. The candidates are counted a ring at a time (the centre, then each
    ring's directions), up to the ring where one is free."""
    best = None
    for _, ring in itertools.groupby(_candidates(), key=lambda candidate: candidate[2]):
        ring = list(ring)
        boxes = np.array([_box_at(anchor, size, dx * unit_per_pt, dy * unit_per_pt, pad) for dx, dy, _ in ring])
        outside = ~((boxes[:, 0] >= frame[0]) & (boxes[:, 1] >= frame[1]) & (boxes[:, 2] <= frame[2]) &
                    (boxes[:, 3] <= frame[3]))
        hard = _overlaps_boxes(boxes, taken) + _circles_crossing_boxes(boxes, circles) + outside
        soft = _segments_crossing_boxes(boxes, segments) + _overlaps_boxes(boxes, regions)
        for k, (dx, dy, r) in enumerate(ring):  # in order: the first of the fewest conflicts
            score = (int(hard[k]), int(soft[k]), r)
            if best is None or score < best[0]:
                best = (score, tuple(float(v) for v in boxes[k]), dx, dy, r)
            if score[:2] == (0, 0):
                return best[1:]
    return best[1:]


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
