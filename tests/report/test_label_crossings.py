"""The label placer's tests on all obstacles and candidates at once agree with the one-obstacle tests."""

import math

import numpy as np

from geargen.report.labels import _segments_crossing, segment_crosses_box


def test_segments_crossing_counts_what_the_one_segment_test_finds():
    """4000 random segments (every 7th vertical, every 5th horizontal: the parallel branch) against
    300 random boxes: the vectorised count equals the sum of the scalar Liang-Barsky tests exactly
    (same arithmetic, so no tolerance)."""
    rng = np.random.default_rng(28)
    segments = rng.uniform(0.0, 10.0, (4000, 4))
    segments[::7, 2] = segments[::7, 0]
    segments[::5, 3] = segments[::5, 1]
    counts = []
    for _ in range(300):
        (x0, x1), (y0, y1) = np.sort(rng.uniform(0.0, 10.0, 2)), np.sort(rng.uniform(0.0, 10.0, 2))
        box = (x0, y0, x1, y1)
        expected = sum(segment_crosses_box(s[:2], s[2:], box) for s in segments)
        assert _segments_crossing(box, segments) == expected
        counts.append(expected)
    assert min(counts) < max(counts)  # the boxes do not all meet the same number of segments
    assert _segments_crossing((0.0, 0.0, 1.0, 1.0), np.empty((0, 4))) == 0


def test_the_placer_chooses_what_counting_every_candidate_chooses():
    """_choose counts the candidates a ring at a time, all obstacles at once: on 200 random scenes
    (texts, circles, segments and regions crowding a frame) it picks the candidate that counting each
    obstacle of each candidate in turn, with the one-obstacle tests, picks (the first with no conflict,
    else the fewest: hard, soft, ring)."""
    from geargen.report import labels

    def circle_crosses(circle, box):  # the box's nearest point inside the circle, its farthest corner outside
        cx, cy, r = circle
        near = math.hypot(min(max(cx, box[0]), box[2]) - cx, min(max(cy, box[1]), box[3]) - cy)
        far = max(math.hypot(x - cx, y - cy) for x in (box[0], box[2]) for y in (box[1], box[3]))
        return near <= r <= far

    def every_count(size, anchor, frame, taken, circles, segments, regions, unit, pad):
        best = None
        for dx, dy, ring in labels._candidates():
            box = labels._box_at(anchor, size, dx * unit, dy * unit, pad)
            outside = not (box[0] >= frame[0] and box[1] >= frame[1] and box[2] <= frame[2] and box[3] <= frame[3])
            score = (sum(labels.boxes_overlap(box, t) for t in taken) + sum(circle_crosses(c, box) for c in circles)
                     + outside, sum(labels.segment_crosses_box(q[:2], q[2:], box) for q in segments)
                     + sum(labels.boxes_overlap(box, t) for t in regions), ring)
            if best is None or score < best[0]:
                best = (score, box, dx, dy, ring)
            if score[:2] == (0, 0):
                break
        return best[1:]

    rng = np.random.default_rng(29)
    frame = (0.0, 0.0, 100.0, 80.0)
    rings = set()
    for _ in range(200):
        n_taken, n_circles, n_segments, n_regions = rng.integers(0, 12, 4)
        corners = rng.uniform(0.0, 100.0, (n_taken, 2))
        taken = np.hstack([corners, corners + rng.uniform(2.0, 20.0, (n_taken, 2))])
        circles = np.column_stack([rng.uniform(0.0, 100.0, (n_circles, 2)), rng.uniform(1.0, 60.0, n_circles)])
        segments = rng.uniform(0.0, 100.0, (n_segments * 10, 4))
        corners = rng.uniform(0.0, 100.0, (n_regions, 2))
        regions = np.hstack([corners, corners + rng.uniform(2.0, 30.0, (n_regions, 2))])
        args = (tuple(rng.uniform(3.0, 25.0, 2)), tuple(rng.uniform(0.0, 100.0, 2)), frame, taken.reshape(-1, 4),
                circles.reshape(-1, 3), segments.reshape(-1, 4), regions.reshape(-1, 4), 0.3528, 0.7)
        chosen = labels._choose(*args)
        assert chosen == every_count(*args)
        rings.add(chosen[3])
    assert len(rings) > 3  # crowded and free scenes alike: the choice is not always the first candidate


def test_a_leader_starts_where_matplotlib_clips_one_to_its_text_frame():
    """place_labels gives each leader its start (relpos) instead of letting matplotlib clip it to the
    text's frame by bisection at every draw. On 64 directions round a framed text (round frame, as
    the view's labels; none, as the layout's: a rectangle 2 pt out) and two dpi (PNG 110, SVG 72),
    the start is the first vertex of the leader matplotlib draws when it clips: within the 0.01 px
    its bisection stops at where the leader leaves through a straight side, 0.25 px through a
    rounded corner (agg tests the corner's curve flattened into chords; this takes the curve)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.text import Text

    from geargen.report import labels

    checked = 0
    worst = []
    for dpi in (110, 72):
        for frame in (dict(bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="0.6", lw=0.4)), {}):
            fig = Figure(figsize=(4, 4), dpi=dpi)
            FigureCanvasAgg(fig)
            ax = fig.add_axes((0, 0, 1, 1))
            ax.set_xlim(0, 100)
            ax.set_ylim(0, 100)
            renderer = fig.canvas.get_renderer()
            for k in range(64):
                angle = 2 * math.pi * (k + 0.37) / 64
                dx, dy = 40 * math.cos(angle), 40 * math.sin(angle)
                ha, va = labels._alignment(dx, dy)
                clipped = ax.annotate("label 12 T", (50, 50), xytext=(dx, dy), textcoords="offset points", ha=ha,
                                      va=va, fontsize=7, arrowprops=dict(arrowstyle="-", shrinkA=1, shrinkB=0), **frame)
                fig.canvas.draw()
                e = Text.get_window_extent(clipped, renderer)
                box = (e.x0 - labels.PAD_PX, e.y0 - labels.PAD_PX, e.x1 + labels.PAD_PX, e.y1 + labels.PAD_PX)
                relpos = labels._leader_start(box, ax.transData.transform((50, 50)),
                                              labels._frame_pad(clipped, renderer), dpi / 72)
                start = clipped.arrow_patch._get_path_in_displaycoord()[0][0].vertices[0]
                mine = (e.x0 + relpos[0] * e.width, e.y0 + relpos[1] * e.height)
                worst.append((math.dist(start, mine), dpi, bool(frame), k))
                clipped.remove()
                checked += 1
    assert checked == 256
    misses = sorted(worst)
    # agg tests a point against the frame's rounded corners flattened into chords (inside the exact
    # curve used here): up to 0.18 px seen there; 0.01 px (matplotlib's bisection) on the straight sides
    assert misses[-1][0] < 0.25, misses[-1]
    assert sum(miss < 0.015 for miss, *_ in misses) >= 200, misses[200]
