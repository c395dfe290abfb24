"""Blade flexures, compression springs, the beam-spring pinion and helical engagement: hand-derived
cases and closed-form limits. (Numerical references -- a frame FE model and the elastica -- are in
test_flexures_fe.py.)"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from geargen.core import flexures as fx
from geargen.design.gear import gear_from_table
from geargen.errors import DesignError

E_STEEL = 200e3  # MPa


# --- blades --------------------------------------------------------------------------------------

def test_blade_stiffness_and_stress_by_hand():
    # 3 blades 10 wide, 0.5 thick, 20 long: k = 3 * 200000 * 10 * 0.125 / 8000
    assert fx.blade_stiffness_along(E_STEEL, 10, 0.5, 20, 3) == pytest.approx(93.75, rel=1e-15)
    # sigma = 3 E t delta / L^2 = 3 * 200000 * 0.5 * 1 / 400
    assert fx.blade_max_stress(E_STEEL, 0.5, 20, 1.0) == pytest.approx(750.0, rel=1e-15)
    assert fx.blade_max_stress(E_STEEL, 0.5, 20, -1.0) == pytest.approx(750.0, rel=1e-15)
    # in-plane without shear: n E t w^3 / L^3; with shear the compliance L / (5/6 G w t) adds
    assert fx.blade_stiffness_lateral(E_STEEL, 10, 0.5, 20, 3) == pytest.approx(37500.0, rel=1e-15)
    g = E_STEEL / 2.6
    with_shear = 3 / (8000 / (E_STEEL * 0.5 * 1000) + 20 / (5 / 6 * g * 5.0))
    assert fx.blade_stiffness_lateral(E_STEEL, 10, 0.5, 20, 3, g) == pytest.approx(with_shear, rel=1e-14)
    assert fx.blade_stiffness_axial(E_STEEL, 10, 0.5, 20, 3) == pytest.approx(3 * E_STEEL * 5 / 20, rel=1e-15)


def test_parasitic_shortening_integrates_the_s_curve():
    # fixed-guided small-deflection shape y = d (3 xi^2 - 2 xi^3); shortening = 1/2 int y'^2 dx
    L, d = 25.0, 0.7
    slope = lambda x: d * (6 * x / L ** 2 - 6 * x ** 2 / L ** 3)  # noqa: E731
    value, err = quad(lambda x: 0.5 * slope(x) ** 2, 0, L, epsabs=1e-14)
    assert fx.blade_parasitic_shortening(L, d) == pytest.approx(value, rel=1e-10)


def test_blade_flexure_result_and_travel_limit():
    b = fx.blade_flexure(3, 0.254, 25.4, 12.7, 207e3, 500.0, 0.508, poisson_ratio=0.29)
    assert b.stiffness_along == pytest.approx(3 * 207e3 * 12.7 * 0.254 ** 3 / 25.4 ** 3, rel=1e-14)
    assert b.stress_at_travel == pytest.approx(3 * 207e3 * 0.254 * 0.508 / 25.4 ** 2, rel=1e-14)
    assert b.stress_ok and b.stress_ratio < 1
    # at the travel limit the stress is exactly the allowable
    assert fx.blade_max_stress(207e3, 0.254, 25.4, b.travel_limit) == pytest.approx(500.0, rel=1e-14)
    assert b.shear_modulus == pytest.approx(207e3 / 2.58, rel=1e-14)


@pytest.mark.parametrize("count, width, target, travel", [(3, 12.7, 8.0, 0.5), (2, 20.0, 50.0, 1.0), (4, 6.0, 2.0, 2.0)])
def test_blade_design_helper_meets_target_exactly(count, width, target, travel):
    res = fx.design_blade_flexure(target, travel, width, 207e3, 400.0, count)
    assert res.success, res.message
    assert fx.blade_stiffness_along(207e3, width, res.thickness, res.length, count) == pytest.approx(target, rel=1e-12)
    assert fx.blade_max_stress(207e3, res.thickness, res.length, travel) == pytest.approx(400.0, rel=1e-12)
    # longer blades of the same stiffness are less stressed: the helper gives the shortest
    longer = 1.2 * res.length
    t_longer = longer * (target / (count * 207e3 * width)) ** (1 / 3)
    assert fx.blade_max_stress(207e3, t_longer, longer, travel) < 400.0


def test_blade_design_helper_at_a_stock_gauge():
    ok = fx.design_blade_flexure(8.0, 0.5, 12.7, 207e3, 500.0, 3, thickness=0.254)
    assert ok.success and ok.length == pytest.approx((3 * 207e3 * 12.7 * 0.254 ** 3 / 8.0) ** (1 / 3), rel=1e-14)
    # a 0.5 mm gauge needs 49.8 mm blades for 8 N/mm and then sees 62.7 MPa at 0.5 mm travel
    thick = fx.design_blade_flexure(8.0, 0.5, 12.7, 207e3, 50.0, 3, thickness=0.5)
    assert thick.stress_at_travel == pytest.approx(3 * 207e3 * 0.5 * 0.5 / thick.length ** 2, rel=1e-14)
    assert not thick.success and "exceeds" in thick.message


# --- compression springs -------------------------------------------------------------------------

def test_spring_rate_wahl_and_stress_by_hand():
    # d 1, D 8, 10 active coils, G 79300: k = 79300 / (8 * 512 * 10)
    assert fx.spring_rate(79300.0, 1.0, 8.0, 10) == pytest.approx(1.9360351562, rel=1e-10)
    assert fx.wahl_factor(8.0) == pytest.approx(31 / 28 + 0.615 / 8, rel=1e-15)
    # textbook table values of K (Wahl): C = 4 -> 1.40, 6 -> 1.25, 10 -> 1.14
    assert [round(fx.wahl_factor(c), 2) for c in (4, 6, 10)] == [1.40, 1.25, 1.14]
    tau = fx.spring_shear_stress(10.0, 1.0, 8.0)
    assert float(tau) == pytest.approx(fx.wahl_factor(8.0) * 8 * 10 * 8 / math.pi, rel=1e-14)
    assert float(fx.spring_shear_stress(10.0, 1.0, 8.0, corrected=False)) == pytest.approx(640 / math.pi, rel=1e-14)


@pytest.mark.parametrize("end, total, solid", [("plain", 10, 11), ("plain_ground", 11, 11),
                                               ("squared", 12, 13), ("squared_ground", 12, 12)])
def test_spring_ends(end, total, solid):
    assert fx.spring_total_coils(10, end) == total
    assert fx.spring_solid_height(1.0, 10, end) == pytest.approx(solid, rel=1e-15)


def test_spring_rate_against_castigliano_on_the_helix():
    # Energy of the exact helix (pitch angle alpha) under an axial force F through the axis:
    # torsion F R cos(a), bending F R sin(a), transverse shear F cos(a), axial F sin(a).
    G, E, d, D, n, pitch = 79300.0, 206000.0, 1.0, 8.0, 10, 2.5
    R = D / 2
    alpha = math.atan(pitch / (math.pi * D))
    length = 2 * math.pi * R * n / math.cos(alpha)
    A, I, J = math.pi * d ** 2 / 4, math.pi * d ** 4 / 64, math.pi * d ** 4 / 32
    def deflection(terms):
        dens = {"torsion": R ** 2 * math.cos(alpha) ** 2 / (G * J), "bending": R ** 2 * math.sin(alpha) ** 2 / (E * I),
                "shear": math.cos(alpha) ** 2 / (0.9 * G * A), "axial": math.sin(alpha) ** 2 / (E * A)}
        # dU/dF with U = F^2/2 int(density) ds along the wire
        return quad(lambda s: sum(dens[t] for t in terms), 0, length)[0]
    k = fx.spring_rate(G, d, D, n)
    # torsion alone: the textbook formula, stiffened by 1/cos(alpha) (the wire is longer, the torque
    # component smaller); here alpha = 5.7 deg
    assert 1 / deflection(["torsion"]) == pytest.approx(k / math.cos(alpha), rel=1e-10)
    # the full energy is softer by about the direct-shear term 1/(2 C^2) that the rate formula omits
    full = 1 / deflection(["torsion", "bending", "shear", "axial"])
    assert full == pytest.approx(k, rel=0.015)
    flat = 1 / quad(lambda s: R ** 2 / (G * J) + 1 / (0.9 * G * A), 0, 2 * math.pi * R * n)[0]
    assert flat < k and k / flat - 1 == pytest.approx(1 / (2 * 0.9 * (D / d) ** 2), rel=1e-10)


def test_compression_spring_result():
    s = fx.compression_spring(1.143, 11.43, 4, 20.32, 79.3e3, 900.0, "squared_ground", installed_length=8.89)
    assert s.rate == pytest.approx(79.3e3 * 1.143 ** 4 / (8 * 11.43 ** 3 * 4), rel=1e-14)
    assert s.installed_force == pytest.approx(s.rate * (20.32 - 8.89), rel=1e-14)
    assert s.solid_height == pytest.approx(6 * 1.143, rel=1e-14)
    assert s.solid_force == pytest.approx(s.rate * (20.32 - 6 * 1.143), rel=1e-14)
    assert s.installed_ok and s.solid_safe
    assert s.installed_deflection == pytest.approx(11.43, rel=1e-14)
    with pytest.raises(DesignError):
        fx.compression_spring(1.0, 1.5, 4, 20, 79.3e3, 900.0)  # index below 2
    with pytest.raises(DesignError):
        fx.compression_spring(1.0, 8.0, 20, 20, 79.3e3, 900.0)  # solid at 22 mm > free length


# --- the beam-spring pinion ------------------------------------------------------------------------

def test_simply_supported_closed_forms_by_hand():
    EI, L, P = 2.0e7, 100.0, 50.0
    assert fx.beam_stiffness_at_load(L, 50, EI) == pytest.approx(48 * EI / L ** 3, rel=1e-15)
    assert fx.beam_stiffness_at_load(L, 75, EI) == pytest.approx(3 * EI * L / (75 ** 2 * 25 ** 2), rel=1e-15)
    # mid-span: zero slope at the load, deflection P L^3 / 48 EI, moment P L / 4
    assert float(fx.simply_supported_slope(50, L, 50, P, EI)) == pytest.approx(0.0, abs=1e-18)
    assert float(fx.simply_supported_deflection(50, L, 50, P, EI)) == pytest.approx(P * L ** 3 / (48 * EI), rel=1e-14)
    assert float(fx.simply_supported_moment(50, L, 50, P)) == pytest.approx(P * L / 4, rel=1e-15)
    # the slopes at the supports of an off-centre load: P a b (L + b) / (6 EI L) and -P a b (L + a) / (6 EI L)
    assert float(fx.simply_supported_slope(0, L, 75, P, EI)) == pytest.approx(P * 75 * 25 * 125 / (6 * EI * L), rel=1e-14)
    assert float(fx.simply_supported_slope(L, L, 75, P, EI)) == pytest.approx(-P * 75 * 25 * 175 / (6 * EI * L), rel=1e-14)
    # the slope at the load: P a b (b - a) / (3 EI L)
    assert float(fx.simply_supported_slope(75, L, 75, P, EI)) == pytest.approx(P * 75 * 25 * (25 - 75) / (3 * EI * L), rel=1e-14)


def test_zero_slope_position_limits():
    assert fx.zero_slope_position(100.0, 50.0) == pytest.approx(50.0, rel=1e-15)
    assert fx.zero_slope_position(100.0, 75.0) == pytest.approx(math.sqrt((100 ** 2 - 25 ** 2) / 3), rel=1e-15)
    assert fx.zero_slope_position(100.0, 25.0) == pytest.approx(100 - math.sqrt((100 ** 2 - 25 ** 2) / 3), rel=1e-15)
    # load at a support: the classic L / sqrt(3)
    assert fx.zero_slope_position(100.0, 100.0 - 1e-9) == pytest.approx(100 / math.sqrt(3), rel=1e-9)
    # it lies between mid-span and the load, and the slope there is zero
    for a in (10.0, 30.0, 62.0, 90.0):
        x0 = fx.zero_slope_position(100.0, a)
        assert min(a, 50.0) <= x0 <= max(a, 50.0)
        assert float(fx.simply_supported_slope(x0, 100.0, a, 1.0, 1.0)) == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("mesh_position", [None, 20.0, 60.0])
def test_span_for_stiffness_round_trip(mesh_position):
    ei, k = 3.0e6, 400.0
    span = fx.span_for_stiffness(k, ei, mesh_position)
    a = span / 2 if mesh_position is None else mesh_position
    assert span > a
    assert fx.beam_stiffness_at_load(span, a, ei) == pytest.approx(k, rel=1e-12)


def test_beam_pinion_at_mid_span():
    d, e, f = 12.0, 207e3, 300.0
    b = fx.beam_pinion(d, e, f, target_stiffness=2000.0, face_width=15.0, allowable_stress=400.0)
    ei = e * math.pi * d ** 4 / 64
    assert b.span == pytest.approx((48 * ei / 2000.0) ** (1 / 3), rel=1e-14)
    assert b.mesh_position == pytest.approx(b.span / 2, rel=1e-15)
    assert b.zero_slope_offset == pytest.approx(0.0, abs=1e-12)
    assert b.slope_at_mesh == pytest.approx(0.0, abs=1e-15)
    assert b.face_misalignment == pytest.approx(0.0, abs=1e-15)  # symmetric face: even contact
    assert b.deflection == pytest.approx(f / 2000.0, rel=1e-12)
    assert b.max_stress == pytest.approx(f * b.span / 4 / (math.pi * d ** 3 / 32), rel=1e-12)
    assert b.stress_ok is True


def test_beam_pinion_off_centre_mesh_is_tilted():
    b = fx.beam_pinion(12.0, 207e3, 300.0, span=150.0, mesh_position=100.0, face_width=20.0)
    ei = 207e3 * math.pi * 12.0 ** 4 / 64
    assert b.zero_slope_position == pytest.approx(fx.zero_slope_position(150.0, 100.0), rel=1e-15)
    assert b.zero_slope_offset < 0  # the deepest point lies towards mid-span
    assert b.slope_at_mesh == pytest.approx(300.0 * 100 * 50 * (50 - 100) / (3 * ei * 150), rel=1e-12)
    ends = fx.simply_supported_deflection([90.0, 110.0], 150.0, 100.0, 300.0, ei)
    assert b.face_misalignment == pytest.approx(abs(ends[1] - ends[0]), rel=1e-14)
    assert b.face_misalignment > 0


# --- helical engagement ----------------------------------------------------------------------------

def test_one_lead_of_axial_travel_turns_the_gear_once():
    g = gear_from_table({"teeth": 30, "module_mm": 2, "pressure_angle_deg": 20, "helix_angle_deg": 25,
                         "face_width_mm": 20})
    turn = fx.rotation_from_axial_travel(g.lead, g.reference_radius, g.helix_angle)
    assert float(turn) == pytest.approx(2 * math.pi, rel=1e-14)


def test_helical_engagement_lead_and_stops_by_hand():
    beta, r = math.radians(20.0), 20.0
    pinion = fx.SlidingMesh("pinion", "bull", beta, r, "left")
    # a cluster whose other gear is spur: the pinion's helix alone turns it, lead = (b + w) / tan(beta)
    e = fx.helical_engagement(pinion, backlash=0.05, preload_windup=0.03, engagement_length=25.0, clearance=2.0,
                              other=fx.SlidingMesh("large", "input", 0.0, 60.0))
    assert e.lead == pytest.approx(0.08 / math.tan(beta), rel=1e-14)
    assert e.relative_rotation == pytest.approx(0.08 / r, rel=1e-14)  # z tan(beta) / r
    assert (e.leader_engaged_stop, e.trailer_engaged_stop) == (0.0, 0.0)
    assert e.leader_retracted_stop == pytest.approx(-27.0, rel=1e-15)
    assert e.trailer_retracted_stop == pytest.approx(-27.0 - e.lead, rel=1e-15)
    assert e.trailer_stroke - e.leader_stroke == pytest.approx(e.lead, rel=1e-14)
    # a helical other gear of the same hand (a 60 mm gear at 20 deg) takes back r / 60 of it
    both = fx.helical_engagement(pinion, 0.05, 0.03, 25.0, 2.0, other=fx.SlidingMesh("large", "input", beta, 60.0, "left"))
    assert both.lead == pytest.approx(0.08 / (math.tan(beta) * (1 - r / 60.0)), rel=1e-14)
    assert both.relative_rotation == pytest.approx(0.08 / r, rel=1e-14)
    assert both.trailer_retracted_stop == pytest.approx(-27.0 - both.lead, rel=1e-15)
    with pytest.raises(DesignError):
        fx.helical_engagement(fx.SlidingMesh("pinion", "bull", 0.0, r), 0.05, 0.03, 25.0)  # a spur gear turns nothing


def test_beam_and_blade_inputs_are_checked():
    with pytest.raises(DesignError):
        fx.simply_supported_deflection(0.0, 100.0, 100.0, 1.0, 1.0)  # load on a support
    with pytest.raises(DesignError):
        fx.blade_flexure(3, -0.1, 25.0, 10.0, 2e5, 500.0, 1.0)
    with pytest.raises(DesignError):
        fx.beam_pinion(10.0, 2e5, 1.0)  # neither span nor target
    assert np.all(np.isfinite(fx.simply_supported_deflection(np.linspace(0, 100, 11), 100.0, 30.0, 1.0, 1.0)))
