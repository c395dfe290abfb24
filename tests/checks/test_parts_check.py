"""The analytic parts check's two readers (geargen.checks.hardware): the octree's shared volume and
the closest approach of two parts, against closed forms on bodies whose answer is known."""

import math

import numpy as np
import pytest

from geargen.checks.hardware import AnalyticPart, closest_approach, read_pair
from geargen.model.bodies import box_between, cylinder, distance_function, world_box


def part(name, body, at=(0.0, 0.0, 0.0)):
    placement = np.eye(4)
    placement[:3, 3] = at
    lo, hi = world_box(body, placement)
    distance = distance_function(body)
    return AnalyticPart(name, lo, hi, lambda p: distance(np.asarray(p) - np.asarray(at)))


@pytest.mark.parametrize("gap", [0.5, 0.01, 0.002])
def test_closest_approach_of_two_blocks_is_half_their_gap(gap):
    """Two 10 mm cubes ``gap`` apart along x: max(d_a, d_b) is least (gap / 2) on the mid-plane;
    found to 1e-5 mm (the last cloud is 3.7e-5 of the 0.4 mm radius, 1/70 of the 1 um contact tolerance)."""
    a = part("a", box_between((0, 0, 0), (10, 10, 10)))
    b = part("b", box_between((10 + gap, 0, 0), (20 + gap, 10, 10)))
    reading = read_pair(a, b, 0.4, margin=0.4)
    assert reading.volume == 0.0
    assert closest_approach(a, b, reading.near[:3], 0.4) == pytest.approx(gap / 2, abs=1e-5)


def test_touching_blocks_and_a_shaft_in_its_bore_are_in_contact():
    a = part("a", box_between((0, 0, 0), (10, 10, 10)))
    b = part("b", box_between((10, 2, 2), (20, 8, 8)))
    reading = read_pair(a, b, 0.4, margin=0.4)
    assert abs(closest_approach(a, b, reading.near[:3], 0.4)) < 1e-5
    shaft, sleeve = part("shaft", cylinder(10.0, 50.0)), part("sleeve", cylinder(30.0, 20.0, 10.0), (0, 0, 10))
    reading = read_pair(shaft, sleeve, 0.4, margin=0.4)
    assert abs(closest_approach(shaft, sleeve, reading.near[:3], 0.4)) < 1e-5
    assert reading.volume < 1e-3


def test_overlap_volume_of_a_pin_in_a_plate():
    """A 10 mm pin 3 mm into a solid plate: pi 5^2 3 = 235.6 mm^3 shared, to the octree's finest
    cells (0.05 mm: the band of boundary cells is 2 % of the volume at most)."""
    plate = part("plate", box_between((-20, -20, -10), (20, 20, 0)))
    pin = part("pin", cylinder(10.0, 20.0), (0, 0, -3))
    reading = read_pair(plate, pin, 0.05)
    assert reading.volume == pytest.approx(math.pi * 25 * 3, rel=0.02)
    assert reading.closest < 0


@pytest.mark.parametrize("tolerance", [0.0, 1e-3])
def test_overlap_volume_alone_reads_the_same_volume(tolerance):
    """Without the nearest cells (nearest=False: the costlier part read only where the cheaper one is
    within a cell's half-diagonal) the octree decides the same cells: the same shared volume to the
    last bit, for a pin in a plate with the cheaper part given first and second, and for parts apart
    whose boxes overlap."""
    plate = part("plate", box_between((-20, -20, -10), (20, 20, 0)))
    pin = AnalyticPart(**{**part("pin", cylinder(10.0, 20.0), (0, 0, -3)).__dict__, "cost": 5.0})
    # a post by the plate's corner: the boxes share a 1 mm column, the bodies nothing (5.66 mm > 5 mm)
    away = part("away", cylinder(10.0, 10.0), (24, 24, -5))
    for a, b in ((plate, pin), (pin, plate), (plate, away)):
        full = read_pair(a, b, 0.05, tolerance=tolerance)
        alone = read_pair(a, b, 0.05, tolerance=tolerance, nearest=False)
        assert alone.volume == full.volume
    assert full.volume == 0.0 and read_pair(plate, pin, 0.05, nearest=False).volume > 200.0


def test_square_frames_read_the_same_local_coordinates():
    """A part placed square (each row of its frame a signed axis) reads each such coordinate as one
    sum or difference (hardware._local_function): bit for bit the general sums of _local, for every
    turn of the axes, signed zeros in the frame, shifts +0.0, -0.0 (read the general way) and
    nonzero, and points with signed zero coordinates; a frame turned off the axes reads the general way."""
    import itertools

    from geargen.checks.hardware import _axis_of, _local, _local_function

    rng = np.random.default_rng(1)
    points = rng.normal(size=(2000, 3)) * 50
    points[:200] = 0.0
    points[200:400] = -0.0
    points[400:500, 1] = -0.0
    points[500:600] = rng.choice([0.0, -0.0, 1.0, -1.0, 2.5], size=(100, 3))
    square = 0
    for order in itertools.permutations(range(3)):
        for signs in itertools.product([1.0, -1.0], repeat=3):
            for zero in (0.0, -0.0):
                for shift in ([0.0, -0.0, 3.5], [-2.0, 0.0, -0.0], [1e-300, -7.25, 0.0]):
                    frame = np.eye(4)
                    turn = np.full((3, 3), zero)
                    for i, j in enumerate(order):
                        turn[i, j] = signs[i]
                    frame[:3, :3], frame[:3, 3] = turn, shift
                    square += sum(_axis_of(turn[i], shift[i]) is not None for i in range(3))
                    for general, fast in zip(_local(points, frame), _local_function(frame)(points)):
                        assert general.tobytes() == fast.tobytes()
    assert square == 6 * 8 * 2 * (2 + 2 + 3)  # every row whose shift is not -0.0 is summed as one
    turned = np.eye(4)
    turned[:2, :2] = [[0.6, -0.8], [0.8, 0.6]]
    assert _axis_of(turned[0, :3], 1.0) is None and _axis_of(turned[2, :3], 1.0) is not None
    for general, fast in zip(_local(points, turned), _local_function(turned)(points)):
        assert general.tobytes() == fast.tobytes()
