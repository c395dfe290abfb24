"""Axial-motion preload (Hale & Slocum): closed forms against an independent numeric force balance
and gap closure on involute helicoids whose normals are computed numerically (finite differences of
the surface), and a vector sum of the mesh forces."""

import math

import numpy as np
import pytest
from scipy.linalg import solve
from scipy.optimize import brentq, root

from geargen.core.axial_preload import (axial_travel_for_backlash, friction_to_preload_ratio, helix_angle_table,
                                        input_bearing_reactions, lateral_force_factor, preload_band, preload_torque, smallest_helix_angle,
                                        tangential_preload)
from geargen.errors import DesignError

DEG = math.pi / 180
ALPHA_N = 20 * DEG


def helicoid_at_pitch_point(teeth, module_n, helix, hand):
    """Point p, unit normal n of the involute helicoid flank at the reference circle (z = 0), by
    finite differences of the surface S(u, z) = Rot(k z) involute(u) + z e_z; and the radius r."""
    alpha_t = math.atan(math.tan(ALPHA_N) / math.cos(helix))
    r = teeth * module_n / math.cos(helix) / 2
    rb = r * math.cos(alpha_t)
    k = (1 if hand == "right" else -1) * math.tan(helix) / r

    def surface(u, z):
        x, y = rb * (math.cos(u) + u * math.sin(u)), rb * (math.sin(u) - u * math.cos(u))
        c, s = math.cos(k * z), math.sin(k * z)
        return np.array([c * x - s * y, s * x + c * y, z])

    u0 = math.tan(alpha_t)  # roll angle of the reference circle: r = rb sqrt(1 + u^2)
    h = 1e-6
    du = (surface(u0 + h, 0) - surface(u0 - h, 0)) / (2 * h)
    dz = (surface(u0, h) - surface(u0, -h)) / (2 * h)
    n = np.cross(du, dz)
    return surface(u0, 0), n / np.linalg.norm(n), r


@pytest.mark.parametrize("helix_deg", [8, 15, 30, 42])
def test_preload_from_spring_force_balance(helix_deg):
    """Shaft equilibrium with contact forces along the numeric flank normals: axial forces sum to
    the spring force and the mesh torques balance (no drive torque); F_t = moment / r."""
    beta = helix_deg * DEG
    spring = 120.0
    (p1, n1, r), (p2, n2, _) = (helicoid_at_pitch_point(17, 1.5, beta, hand) for hand in ("right", "left"))
    axial = np.array([abs(n1[2]), abs(n2[2])])
    moment = np.array([abs(np.cross(p1, n1)[2]), abs(np.cross(p2, n2)[2])])

    # the balance is linear in the two normal forces
    forces = solve([axial, [moment[0], -moment[1]]], [spring, 0.0])
    tangential = forces * moment / r
    assert tangential == pytest.approx([tangential_preload(spring, beta)] * 2, rel=1e-8)
    assert preload_torque(spring, beta, r) == pytest.approx(tangential[0] * r, rel=1e-8)


@pytest.mark.parametrize("helix_deg", [10, 25, 40])
def test_axial_travel_closes_both_meshes(helix_deg):
    """The shaft's turn theta and slide z move each flank along its numeric normal by
    n . (theta e_z x p + z e_z); opposite hands and opposite torque senses: solve both gaps closed."""
    beta = helix_deg * DEG
    backlash = (0.012, 0.005)  # normal backlash of each mesh, mm
    (p1, n1, r), (p2, n2, _) = (helicoid_at_pitch_point(23, 1.0, beta, hand) for hand in ("right", "left"))
    ez = np.array([0.0, 0.0, 1.0])

    def gaps(v):
        # turning closes mesh 1 and opens mesh 2 (opposite torque senses); sliding closes both
        theta, z = v
        return [backlash[0] - n1 @ (theta * np.cross(ez, p1)) * np.sign(np.cross(p1, n1)[2]) - z * abs(n1[2]),
                backlash[1] + n2 @ (theta * np.cross(ez, p2)) * np.sign(np.cross(p2, n2)[2]) - z * abs(n2[2])]

    sol = root(gaps, [0.0, 0.0])
    assert sol.success
    z = sol.x[1]
    assert axial_travel_for_backlash(sum(backlash), ALPHA_N, beta) == pytest.approx(z, rel=1e-8)
    # the same slide from the transverse circumferential backlash at the reference circle
    alpha_t = math.atan(math.tan(ALPHA_N) / math.cos(beta))
    beta_b = math.asin(math.sin(beta) * math.cos(ALPHA_N))
    j_t = sum(backlash) / (math.cos(alpha_t) * math.cos(beta_b))
    assert axial_travel_for_backlash(j_t, ALPHA_N, beta, kind="transverse_circumferential") == pytest.approx(z, rel=1e-8)


def mesh_force_resultant(phi, alpha_w):
    """|sum of both meshes' forces on the pinion| / F_t by vectors: gear A at angle 0 turning the
    pinion counter-clockwise, gear B at phi turning it clockwise; each pushes the pinion away."""
    total = np.zeros(2)
    for angle, sense in ((0.0, 1.0), (phi, -1.0)):
        towards = np.array([math.cos(angle), math.sin(angle)])
        tangent = np.array([-towards[1], towards[0]])
        total += sense * tangent - math.tan(alpha_w) * towards
    return float(np.linalg.norm(total))


@pytest.mark.parametrize("phi_deg", [40, 90, 120, 180, 250])
def test_lateral_force_factor_is_the_vector_sum(phi_deg):
    alpha_w = 21.3 * DEG
    assert lateral_force_factor(phi_deg * DEG, alpha_w) == pytest.approx(mesh_force_resultant(phi_deg * DEG, alpha_w),
                                                                         rel=1e-12)


def test_figure9_optimum_has_no_lateral_force_and_180_deg_gives_mu_over_tan_beta():
    alpha_w = 20 * DEG
    assert lateral_force_factor(2 * alpha_w, alpha_w) == pytest.approx(0.0, abs=1e-15)
    # opposite gears: the tangential forces add (N = 2 F_t), ratio mu / tan(beta)
    k = lateral_force_factor(math.pi, alpha_w)
    assert k == pytest.approx(2.0)
    assert friction_to_preload_ratio(0.15, 10 * DEG, k) == pytest.approx(0.15 / math.tan(10 * DEG))


@pytest.mark.parametrize("helix_deg", [12, 30])
def test_hysteresis_band_solves_the_axial_balance_with_friction(helix_deg):
    """Sliding in, friction mu N opposes the spring: F_s - mu N(F_t) = 2 F_t tan(beta); out, it adds.
    N(F_t) from the vector sum; each balance solved by brentq."""
    beta, mu, spring, phi, alpha_w = helix_deg * DEG, 0.2, 50.0, 150 * DEG, 20 * DEG
    n_per_ft = mesh_force_resultant(phi, alpha_w)
    low = brentq(lambda f: spring - mu * n_per_ft * f - 2 * f * math.tan(beta), 0, 1e6)
    high = brentq(lambda f: spring + mu * n_per_ft * f - 2 * f * math.tan(beta), 0, 1e6)
    band = preload_band(spring, beta, mu, lateral_force_factor(phi, alpha_w))
    assert not band.locks
    assert (band.low, band.high) == pytest.approx((low, high), rel=1e-10)
    assert band.low < band.nominal < band.high


def test_small_helix_angle_locks_and_table_falls_with_angle():
    k = lateral_force_factor(math.pi, 20 * DEG)
    assert preload_band(10.0, 5 * DEG, 0.2, k).locks  # mu k = 0.4 > 2 tan 5 deg = 0.175
    rows = helix_angle_table(0.2, ALPHA_N, k)
    ratios = [row.friction_to_preload for row in rows]
    assert ratios == sorted(ratios, reverse=True)
    assert math.isinf(rows[0].hysteresis) and rows[-1].hysteresis < 0.5
    beta = smallest_helix_angle(0.2, k, 0.25)
    assert friction_to_preload_ratio(0.2, beta, k) == pytest.approx(0.25)


def test_bearing_reactions_by_hand():
    """Bearings in the meshes' own planes each carry their own mesh, hypot(F_r, F_t), and the axial
    forces' moment 2 F_a r moves 2 F_a r / span from one to the other in the plane of centres.
    Hand numbers: F_t 100, F_r 40, F_a 30 N at r 10 mm; meshes at z 0 and 20."""
    lower, upper = input_bearing_reactions((0.0, 20.0), (0.0, 20.0), 100.0, 40.0, 0.0, 10.0)
    assert (lower, upper) == pytest.approx((math.hypot(40, 100), math.hypot(40, 100)), rel=1e-15)
    # with the axial forces: 2 x 30 x 10 / 20 = 30 N moved in the plane of centres, to the lower one
    lower, upper = input_bearing_reactions((0.0, 20.0), (0.0, 20.0), 100.0, 40.0, 30.0, 10.0)
    assert (lower, upper) == pytest.approx((math.hypot(70, 100), math.hypot(10, 100)), rel=1e-15)
    # bearings 10 mm beyond each mesh (span 40): the tangential couple 100 x 20 / 40 = 50 N each
    lower, upper = input_bearing_reactions((0.0, 20.0), (-10.0, 30.0), 100.0, 40.0, 30.0, 10.0)
    assert (lower, upper) == pytest.approx((math.hypot(55, 50), math.hypot(25, 50)), rel=1e-15)


def test_smallest_helix_angle_of_a_helix_dependent_load():
    """k a function of the helix angle: the first angle whose ratio meets the limit (bisection to
    1e-9 rad), the closed form when k is constant; None when k grows faster than tan(beta)."""
    k = lateral_force_factor(math.pi, 20 * DEG)
    assert smallest_helix_angle(0.2, lambda beta: k, 0.25) == pytest.approx(smallest_helix_angle(0.2, k, 0.25),
                                                                            abs=1e-8)
    # k = 1 + 2 tan(beta): ratio mu (1 / (2 tan) + 1) never falls below mu = 0.2
    assert smallest_helix_angle(0.2, lambda beta: 1 + 2 * math.tan(beta), 0.15) is None
    # k = 1 + tan(beta): mu (1 / (2 tan) + 1 / 2) = 0.15 at tan(beta) = 0.1 / (0.15 - 0.1) = 2
    assert smallest_helix_angle(0.2, lambda beta: 1 + math.tan(beta), 0.15) == pytest.approx(math.atan(2.0),
                                                                                              abs=1e-8)


def test_refusals_name_the_field():
    with pytest.raises(DesignError) as err:
        tangential_preload(10.0, 0.0)
    assert err.value.field == "helix_angle"
    with pytest.raises(DesignError) as err:
        axial_travel_for_backlash(0.01, ALPHA_N, 0.3, kind="radial")
    assert err.value.field == "kind"
