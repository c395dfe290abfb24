"""Path 1 against involute theory: backlash at an increased centre distance, tooth thinning,
contact ratio, and a seeded sweep of random pairs.

The exact check measures backlash as the free rotation of gear 1 on the analytic outlines; the
theory is (z1+z2) m_n cos(alpha_n) (inv alpha_wt' - inv alpha_wt0). Both are computed in double
precision from the same inputs, so they agree to ~1e-13 mm; the issue asks for 0.01 um.
"""

import math

import numpy as np
import pytest

from geargen.checks.mesh2d import MeshSetup, check_mesh, mesh_positions, sweep_mesh
from geargen.core.geometry import GearPair, backlash_at_centre_distance, mesh_geometry
from geargen.errors import GeometryError

from checks_support import gear, inch_gear, theory_normal_backlash, tight_centre_distance

TOL = 1e-5  # mm: 0.01 um, the requirement

PAIRS = {
    "spur metric": (gear(20), gear(41)),
    "spur inch, paper mesh 1": (inch_gear(16), inch_gear(48)),
    "spur inch, paper mesh 2": (inch_gear(21), inch_gear(112)),
    "helical metric": (gear(17, 1.5, beta_deg=18, hand="right"), gear(43, 1.5, beta_deg=18, hand="left")),
    "profile shifted": (gear(12, 2.5, x=0.4), gear(30, 2.5, x=-0.2)),
    "helical inch, shifted, 25 deg": (inch_gear(14, 24, alpha_deg=25, beta_deg=25, x=0.3, hand="left"),
                                      inch_gear(35, 24, alpha_deg=25, beta_deg=25, hand="right")),
}


@pytest.mark.parametrize("name", PAIRS)
@pytest.mark.parametrize("delta_mm", [0.01, 0.1])
def test_backlash_at_increased_centre_distance_matches_theory(name, delta_mm):
    g1, g2 = PAIRS[name]
    a = tight_centre_distance(g1, g2) + delta_mm
    su = MeshSetup.centred(g1, g2, a, name)
    sw = sweep_mesh(su, mesh_positions(su, 12), su.planes(3))
    expected = theory_normal_backlash(g1, g2, a)
    assert np.max(np.abs(sw.normal_backlash - expected)) < TOL
    # and the small-change form 2 da sin(alpha_wt) cos(beta_b), to first order in da
    a_w = math.acos((g1.base_radius + g2.base_radius) / a)
    approx = 2 * delta_mm * math.sin(a_w) * math.cos(g1.base_helix_angle)
    assert sw.normal_backlash[0] == pytest.approx(approx, rel=0.03)
    # circumferential on the operating pitch circle: j_n / (cos alpha_wt cos beta_b)
    assert np.max(np.abs(sw.circumferential_backlash - expected / (math.cos(a_w) * math.cos(g1.base_helix_angle)))) < TOL
    assert not np.any(sw.interference)


@pytest.mark.parametrize("name", ["spur metric", "helical metric", "profile shifted", "spur inch, paper mesh 2"])
def test_tooth_thinning_adds_its_allowance_exactly(name):
    from dataclasses import replace

    g1, g2 = PAIRS[name]
    a = tight_centre_distance(g1, g2) + 0.02
    plain = sweep_mesh(MeshSetup.centred(g1, g2, a), [0.0, 0.1], g1.is_helical and [0.0, 5.0] or None)
    t1, t2 = replace(g1, thinning=0.031), replace(g2, thinning=0.047)
    thin = sweep_mesh(MeshSetup.centred(t1, t2, a), [0.0, 0.1], g1.is_helical and [0.0, 5.0] or None)
    allowance = (0.031 + 0.047) * math.cos(g1.transverse_pressure_angle) * math.cos(g1.base_helix_angle)
    assert np.max(np.abs(thin.normal_backlash - plain.normal_backlash - allowance)) < TOL
    assert np.max(np.abs(thin.normal_backlash - theory_normal_backlash(t1, t2, a))) < TOL
    # the pair-geometry module's formula says the same
    assert thin.normal_backlash[0] == pytest.approx(backlash_at_centre_distance(GearPair(t1, t2), a).normal, abs=TOL)


def test_backlash_is_the_same_at_every_mesh_position_and_plane():
    g1, g2 = PAIRS["helical metric"]
    su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + 0.05)
    sw = sweep_mesh(su, mesh_positions(su, 40, revolutions=3.0 / g1.teeth), su.planes(7))
    assert np.ptp(sw.angular_backlash) < 1e-12
    # gear 1 starts centred in its play: half the play either way
    assert np.allclose(sw.play_ccw[0], sw.play_cw[0], atol=1e-12)


def test_helical_pair_with_equal_hands_is_caught_in_the_sections():
    """Equal hands make the flanks twist apart: some section planes must show overlap."""
    g1 = gear(17, 1.5, beta_deg=18, hand="right")
    g2 = gear(43, 1.5, beta_deg=18, hand="right")
    su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + 0.05)
    sw = sweep_mesh(su, [0.0], su.planes(5), areas=False)
    assert sw.interference[0] == 3  # flank interference
    # while the z = 0 plane alone is fine
    assert sweep_mesh(su, [0.0], [0.0], areas=False).interference[0] == 0


@pytest.mark.parametrize("name", ["spur metric", "spur inch, paper mesh 1", "spur inch, paper mesh 2", "profile shifted"])
def test_measured_contact_ratio_matches_the_formula(name):
    g1, g2 = PAIRS[name]
    a = tight_centre_distance(g1, g2) + 0.05
    c = check_mesh(MeshSetup.centred(g1, g2, a))
    geo = mesh_geometry(GearPair(g1, g2), a)
    if any(geo.involute_interference):
        pytest.skip("the formula's tip-to-tip path does not apply")
    # the measurement bisects the changes of contact count to ~1e-9 of a pitch
    assert c.contact_ratio == pytest.approx(geo.transverse_contact_ratio, abs=1e-5)


def test_seeded_sweep_of_random_pairs():
    """Random spur and helical pairs (teeth, module, pressure angle, helix, shift, thinning,
    centre distance): the exact check matches theory everywhere or tags the pair."""
    rng = np.random.default_rng(20240606)
    tagged = []
    for k in range(16):
        z1, z2 = int(rng.integers(14, 40)), int(rng.integers(20, 90))
        m = float(rng.choice([0.5, 1.0, 2.0, 25.4 / 32, 25.4 / 20]))
        alpha = float(rng.choice([14.5, 20.0, 25.0]))
        beta = float(rng.choice([0.0, 0.0, 15.0, 30.0]))
        x1, x2 = float(rng.uniform(0.0, 0.5)), float(rng.uniform(-0.3, 0.3))
        th1, th2 = float(rng.uniform(0, 0.05)) * m, float(rng.uniform(0, 0.05)) * m
        g1 = gear(z1, m, alpha, beta, "right", x1, th1)
        g2 = gear(z2, m, alpha, beta, "left", x2, th2)
        a = tight_centre_distance(g1, g2) + float(rng.uniform(0.0, 0.2)) * m
        try:
            sw = sweep_mesh(MeshSetup.centred(g1, g2, a), [0.0, 0.05], g1.is_helical and [0.0, 4.0] or None,
                            areas=False)
        except GeometryError as exc:  # the profile cannot be cut (tagged by its kind)
            tagged.append((k, exc.kind))
            continue
        err = float(np.max(np.abs(sw.normal_backlash - theory_normal_backlash(g1, g2, a))))
        if np.any(sw.interference):
            tagged.append((k, "interference"))
            continue
        assert err < TOL, (k, z1, z2, m, alpha, beta, x1, x2, err)
    print("tagged:", tagged)
    assert len(tagged) <= 4, tagged
