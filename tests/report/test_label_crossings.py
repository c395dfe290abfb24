"""The label placer's segment test on all segments at once agrees with the one-segment test."""

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
