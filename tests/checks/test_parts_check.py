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
