"""sample_outline (geargen.profile.segments) evaluates each piece of a tooth and its point count once for
all the teeth and turns the points: the result is, bit for bit, each segment sampled on its own
(Segment.sample with the point count of the chord rule written out here), so every drawing and mass from
it is unchanged."""

import math

import numpy as np
import pytest

from geargen.design.gear import GearSpec, Hub
from geargen.profile.segments import sample_outline
from geargen.profile.tooth import tooth_profile


@pytest.mark.parametrize("helix, rotation", [(0.0, 0.0), (math.radians(20), 0.3)])
def test_the_shared_points_are_each_segments_own(helix, rotation):
    spec = GearSpec(teeth=31, module=1.25, pressure_angle=math.radians(20), face_width=8.0, helix_angle=helix,
                    profile_shift=0.1, hub=Hub(bore_diameter=8.0), name="g")
    segments = tooth_profile(spec, warn=False).outline(rotation)
    first = np.sum(np.linalg.norm(np.diff(segments[0].sample(9), axis=0), axis=1))
    for step in (0.02, 0.3, first / 7):  # the last: a whole number of steps, where a turn's rounding counts
        alone = []
        for s in segments:  # 9 points give the chord length; ~step apart, at least 2 points
            chord = np.sum(np.linalg.norm(np.diff(s.sample(9), axis=0), axis=1))
            alone.append(s.sample(max(2, int(math.ceil(chord / step)) + 1))[:-1])
        assert sample_outline(segments, step).tobytes() == np.concatenate(alone).tobytes()  # exact: no tolerance
