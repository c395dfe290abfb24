"""Bevel pair check: backlash measured on the exact outlines on the heel sphere equals the thinnings'."""

import math

import pytest

from geargen.families.bevel.pair import check_bevel_pair
from geargen.families.bevel.spec import BevelGearSpec

DEG = math.pi / 180


@pytest.mark.parametrize("z1, z2, sigma_deg, x, turn", [
    (20, 40, 90, 0.0, 0.0),      # the KHK example pair
    (20, 40, 90, 0.0, 0.061),    # another phase of the mesh: spherical involutes are conjugate
    (17, 29, 60, 0.2, 0.02),     # Gleason-style shift (x on the pinion, -x on the gear)
    (16, 25, 110, 0.1, 0.01),
])
def test_measured_backlash_is_the_thinnings(z1, z2, sigma_deg, x, turn):
    t1, t2 = 0.05, 0.03
    a = BevelGearSpec(teeth=z1, mate_teeth=z2, module=3, face_width=15, thinning=t1, shaft_angle=sigma_deg * DEG,
                      profile_shift=x)
    b = BevelGearSpec(teeth=z2, mate_teeth=z1, module=3, face_width=15, thinning=t2, shaft_angle=sigma_deg * DEG,
                      profile_shift=-x)
    r = check_bevel_pair(a, b, turn=turn)
    # analytic: the circumferential backlash at the heel pitch circle is t1 + t2 (arcs of the rolling
    # pitch circles); the brief asks for 1e-3 of it, the sampled flanks give ~1e-6
    assert r.backlash == pytest.approx(t1 + t2, rel=1e-3)
    assert r.backlash_expected == t1 + t2
    # tip clearance: R_e (theta_f2 - theta_a1) ~ (h_f* - h_a*) m = 0.25 m, less (h_a^2 + h_a h_f + h_f^2) / (3 R_e^2)
    # of it (atan's series): under 2 % for these cone distances
    assert r.tip_clearance_1 == pytest.approx(0.25 * 3, rel=2e-2)


def test_zero_thinning_meshes_without_backlash():
    a = BevelGearSpec(teeth=20, mate_teeth=40, module=3, face_width=15)
    b = BevelGearSpec(teeth=40, mate_teeth=20, module=3, face_width=15)
    assert abs(check_bevel_pair(a, b, turn=0.02).backlash) < 1e-6


def test_not_mates_is_refused():
    from geargen.errors import DesignError
    a = BevelGearSpec(teeth=20, mate_teeth=40, module=3, face_width=15)
    with pytest.raises(DesignError, match="mate"):
        check_bevel_pair(a, a)
