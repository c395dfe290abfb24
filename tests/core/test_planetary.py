"""Planetary stage math against published examples and an independent zero-backlash solve.

Sources:
- SDP/SI (with KHK) "Elements of Metric Gear Technology" (D785), section 13.3, pages T-116..T-118:
  conditions (13-5)..(13-10) and the example z_a = 16, z_b = 16, z_c = 48 with speed ratios 1/4
  (ring fixed), 1/1.3333333 (sun fixed), -1/3 (carrier fixed);
- LECAD (University of Ljubljana), "Analysis of Planetary Transmissions", test run of the pg program
  (lecad.uni-lj.si/~leon/FS/PlanetryTransmissions/node8.html): sun 21, 3 planets of 43, ring 108,
  m_n 1.75 mm, alpha_n 20 deg, x = 0.4380 / 0.0426 / 0.0000, transmission ratio 6.14286, centre
  distance 56.8 mm.
"""

import math

import pytest
from scipy.optimize import brentq

from geargen.core.planetary import (PlanetaryStage, assembly_angles, check_stage, coaxial_ring_shift,
                                    planet_ring_working, ratios, sun_planet_working)
from geargen.errors import DesignError

DEG = math.pi / 180


def sdp(planets=4, **kw):
    return PlanetaryStage(16, 16, 48, planets, 1.0, 20 * DEG, **kw)


def lecad(**kw):
    args = dict(sun_profile_shift=0.4380, planet_profile_shift=0.0426, ring_profile_shift=0.0)
    return PlanetaryStage(21, 43, 108, 3, 1.75, 20 * DEG, **(args | kw))


def test_sdp_speed_ratios():
    r = ratios(sdp())
    assert 1 / r["ring_fixed"] == pytest.approx(1 / 4)
    assert 1 / r["sun_fixed"] == pytest.approx(1 / 1.3333333, rel=1e-7)
    assert 1 / r["carrier_fixed"] == pytest.approx(-1 / 3)


def test_sdp_assembly_condition_13_7_and_13_8():
    assert check_stage(sdp(4)).planet_angles == pytest.approx([0, math.pi / 2, math.pi, 3 * math.pi / 2])
    with pytest.raises(DesignError) as err:
        check_stage(sdp(3))  # (16 + 48) / 3 is not whole
    assert err.value.field == "planets"
    # unequal spacing (13-8): (z_a + z_c) theta / 180 whole, theta half the angle between planets
    angles = assembly_angles(sdp(3), equal_spacing=False)
    for a, b in zip(angles, angles[1:]):
        half_deg = math.degrees(b - a) / 2
        assert (16 + 48) * half_deg / 180 == pytest.approx(round((16 + 48) * half_deg / 180), abs=1e-9)
    assert max(abs(a - 2 * math.pi * i / 3) for i, a in enumerate(angles)) <= math.pi / 64


@pytest.mark.parametrize("planets", [3, 4, 5, 6])
def test_neighbour_condition_matches_13_9(planets):
    """Standard gears (x = 0, tip diameter m (z_b + 2)): z_b + 2 < (z_a + z_b) sin(180 / N)."""
    stage = PlanetaryStage(12, 18, 48, planets, 2.0, 20 * DEG)  # 60 teeth: N = 3..6 all divide
    fits = 18 + 2 < (12 + 18) * math.sin(math.pi / planets)
    if fits:
        assert check_stage(stage).neighbour_gap == pytest.approx(2 * 30 * math.sin(math.pi / planets) - 2.0 * 20)
    else:
        with pytest.raises(DesignError) as err:
            check_stage(stage)
        assert err.value.field == "planets"
    assert fits == (planets <= 4)


def test_lecad_example():
    stage = lecad()
    result = check_stage(stage)
    assert result.ratio_ring_fixed == pytest.approx(6.14286, abs=5e-6)
    assert result.centre_distance == pytest.approx(56.8, abs=5e-4)  # the listing's 56.8 mm
    assert planet_ring_working(stage)[1] == pytest.approx(56.8, abs=5e-4)
    # the listing's shifts have 4 decimals (each +-5e-5, and x_r moves about one for one with x_s + x_p):
    # the ring shift that makes the stage coaxial is its 0.0000 within that rounding
    assert coaxial_ring_shift(stage) == pytest.approx(0.0, abs=1.5e-4)
    assert result.planet_angles == pytest.approx([0, 2 * math.pi / 3, 4 * math.pi / 3])


def zero_backlash_centre_distance(z1, z2, x1, x2, m, alpha, internal):
    """Centre distance at which the working-circle arcs fit with no backlash, solved by brentq:
    external: tooth 1 + tooth 2 = working pitch; internal (gear 2 the ring): planet tooth = ring space.
    Thickness at radius R of a tooth of reference thickness s: 2 R (s / d + inv(alpha) - inv(alpha_R))."""
    inv = lambda a: math.tan(a) - a  # noqa: E731
    s1 = m * (math.pi / 2 + 2 * x1 * math.tan(alpha))
    s2 = m * (math.pi / 2 + 2 * x2 * math.tan(alpha))  # the ring's: space width at its reference circle
    zsum = z2 - z1 if internal else z1 + z2

    def misfit(a):
        alpha_w = math.acos(m * zsum / 2 * math.cos(alpha) / a)
        r1, r2 = a * z1 / zsum, a * z2 / zsum
        t1 = 2 * r1 * (s1 / (m * z1) + inv(alpha) - inv(alpha_w))
        # the ring's space is bounded by involutes of its base circle like an external tooth (it
        # narrows outward), so it has the same thickness formula
        t2 = 2 * r2 * (s2 / (m * z2) + inv(alpha) - inv(alpha_w))
        if internal:
            return t1 - t2
        return t1 + t2 - 2 * math.pi * r1 / z1

    a0 = m * zsum / 2
    return brentq(misfit, a0 * math.cos(alpha) * 1.0001, a0 * 1.2, xtol=1e-14)


def test_working_centre_distances_against_a_zero_backlash_solve():
    stage = lecad()
    assert sun_planet_working(stage)[1] == pytest.approx(
        zero_backlash_centre_distance(21, 43, 0.4380, 0.0426, 1.75, 20 * DEG, False), abs=1e-9)
    for x_r in (0.0, 0.3, -0.2):
        got = planet_ring_working(lecad(ring_profile_shift=x_r))[1]
        assert got == pytest.approx(zero_backlash_centre_distance(43, 108, 0.0426, x_r, 1.75, 20 * DEG, True), abs=1e-9)


def test_coaxiality_failure_names_the_ring_shift():
    with pytest.raises(DesignError) as err:
        check_stage(lecad(ring_profile_shift=0.2))
    assert err.value.field == "ring_profile_shift"
    assert "0.0000" in err.value.allowed or "-0.0000" in err.value.allowed or "x_r = " in err.value.allowed
    # the suggested shift makes it coaxial to well within the tolerance
    fixed = lecad(ring_profile_shift=coaxial_ring_shift(lecad(ring_profile_shift=0.2)), coaxiality_tolerance=1e-9)
    assert abs(check_stage(fixed).coaxiality_error) <= 1e-9


def test_helical_stage_is_the_spur_stage_in_the_transverse_section():
    """A helical stage: the transverse module m_n / cos(beta) scales every centre distance."""
    beta = 15 * DEG
    spur, helical = sdp(4), sdp(4, helix_angle=beta)
    assert sun_planet_working(helical)[1] == pytest.approx(sun_planet_working(spur)[1] / math.cos(beta))
    assert check_stage(helical).coaxiality_error == pytest.approx(0.0, abs=1e-12)


def test_refusals():
    with pytest.raises(DesignError) as err:
        PlanetaryStage(16, 40, 40, 3, 1.0, 20 * DEG)
    assert err.value.field == "ring_teeth"
    with pytest.raises(DesignError) as err:
        PlanetaryStage(16, 16, 48, 0, 1.0, 20 * DEG)
    assert err.value.field == "planets"
