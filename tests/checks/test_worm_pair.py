"""Worm-pair backlash and interference (geargen.families.worm.pair) on the exact surfaces."""

import math

import pytest

from geargen.families.worm.pair import worm_pair_check
from geargen.families.worm.geometry import worm_geometry
from geargen.families.worm.spec import WormGearSet


def _set(**changes):
    # the set of KHK Gear Technical Reference Table 4.17 (m_x 3, z1 2, z2 30, d1 44, alpha_n 20 deg)
    kw = dict(axial_module=3.0, starts=2, wheel_teeth=30, worm_reference_diameter=44.0,
              pressure_angle=math.radians(20), worm_face_length=60.0, wheel_face_width=28.0)
    kw.update(changes)
    return WormGearSet(**kw)


@pytest.mark.parametrize("changes", [dict(backlash=0.05), dict(backlash=0.05, backlash_on="worm"),
                                     dict(backlash=0.02, hand="left"), dict(backlash=0.08, starts=1,
                                                                            wheel_profile_shift=0.3)])
def test_design_backlash_is_measured_at_the_design_centre_distance(changes):
    check = worm_pair_check(_set(**changes))
    assert check.backlash == pytest.approx(changes["backlash"], abs=2e-3 * 1e-3)  # within 2 nm, asked 2 um
    assert not check.interference
    # the thinning is split evenly: each side turns by half of it
    assert check.free_rotation[1] == pytest.approx(check.free_rotation[-1], abs=1e-9)


def test_zero_backlash_touches_without_interference():
    check = worm_pair_check(_set())
    assert abs(check.backlash) < 1e-6 and not check.interference


def test_centre_distance_error_in_the_mid_plane_is_the_rack_result():
    # in the wheel's mid plane the worm's axial section is a straight rack of flank angle alpha_x:
    # moving it out by da opens the circumferential backlash by 2 da tan(alpha_x) (rack and pinion)
    s = _set(backlash=0.03)
    g = worm_geometry(s)
    check = worm_pair_check(s, centre_distance_error=0.01, planes=1)
    assert check.contact_plane[1] == 0.0
    assert check.backlash == pytest.approx(0.03 + 2 * 0.01 * math.tan(g.axial_pressure_angle), abs=1e-6)
    # moved in by more than half the backlash's worth, the flanks interfere
    assert worm_pair_check(s, centre_distance_error=-0.05).interference
