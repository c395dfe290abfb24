"""The servo view (geargen.core.servo) against the paper's scaling claims, an independent time
simulation, hand calculations of Fig. 1, and the R^2 law."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from geargen.core.servo import (DualMotorDrive, TwoMass, chain_modes, closed_loop, gains_for, mesh_loss_factor,
                                reflect_inertia)

ROTOR = 3e-6  # kg m^2
LOAD = 2.0  # kg m^2: load inertia dominant for every R below (LOAD / R^2 >> ROTOR)
KP, KD = 0.2, 0.003  # gains at the motor


def geared(ratio, rotor=ROTOR, load=LOAD):
    return closed_loop(rotor + load / ratio ** 2, KP, KD)


@pytest.mark.parametrize("ratio", [4.0, 8.0, 16.0])
def test_natural_frequency_grows_as_R_and_damping_as_R_with_fixed_gains(ratio):
    """Hale & Slocum: "the closed loop natural frequency increases by R" (load inertia dominant).
    With the gains held, the damping ratio grows by R as well (zeta = Kd R^2 / (2 sqrt(Kp R^2 J)))."""
    direct = closed_loop(ROTOR + LOAD, KP, KD)
    g = geared(ratio)
    exact = ratio * math.sqrt((ROTOR + LOAD) / (ROTOR * ratio ** 2 + LOAD))  # -> R as the load dominates
    assert g.natural_frequency / direct.natural_frequency == pytest.approx(exact, rel=1e-12)
    assert g.damping_ratio / direct.damping_ratio == pytest.approx(exact, rel=1e-12)
    assert exact == pytest.approx(ratio, rel=ROTOR * ratio ** 2 / LOAD)


@pytest.mark.parametrize("ratio", [4.0, 8.0, 16.0])
def test_damping_grows_as_R_squared_at_equal_natural_frequency(ratio):
    """The paper's "damping ratio increases by R^2" holds for the motor's damping (Kd, reflected
    as Kd R^2) when both drives are tuned to one natural frequency: zeta = Kd R^2 / (2 w J_load)."""
    w = 2 * math.pi * 5.0
    direct = closed_loop(ROTOR + LOAD, *gains_for(ROTOR + LOAD, w, 0.0)[:1], KD)
    g = closed_loop(ROTOR + LOAD / ratio ** 2, *gains_for(ROTOR + LOAD / ratio ** 2, w, 0.0)[:1], KD)
    assert g.natural_frequency == pytest.approx(direct.natural_frequency, rel=1e-12)
    exact = (ROTOR + LOAD) / (ROTOR + LOAD / ratio ** 2)
    assert g.damping_ratio / direct.damping_ratio == pytest.approx(exact, rel=1e-12)
    assert exact == pytest.approx(ratio ** 2, rel=ROTOR * ratio ** 2 / LOAD)


def test_closed_loop_matches_a_time_simulation():
    """Independent: integrate J x'' = -Kp x - Kd x' and read the frequency and decay of the ringing."""
    j = ROTOR + LOAD / 16 ** 2
    loop = closed_loop(j, KP, KD * 0.05)
    sol = solve_ivp(lambda t, y: [y[1], (-KP * y[0] - KD * 0.05 * y[1]) / j], (0, 8.0), [1.0, 0.0],
                    max_step=1e-4, rtol=1e-10, atol=1e-12)
    x, t = sol.y[0], sol.t
    peaks = [i for i in range(1, len(x) - 1) if x[i] > x[i - 1] and x[i] > x[i + 1]]
    period = (t[peaks[-1]] - t[peaks[0]]) / (len(peaks) - 1)
    wd = 2 * math.pi / period
    zeta = loop.damping_ratio
    assert wd == pytest.approx(loop.natural_frequency * math.sqrt(1 - zeta ** 2), rel=1e-3)
    decrement = math.log(x[peaks[0]] / x[peaks[1]])
    assert decrement == pytest.approx(2 * math.pi * zeta / math.sqrt(1 - zeta ** 2), rel=1e-3)


def test_gains_for_round_trip():
    kp, kd = gains_for(1e-4, 2 * math.pi * 20, 0.7)
    loop = closed_loop(1e-4, kp, kd)
    assert loop.natural_frequency_hz == pytest.approx(20.0, rel=1e-12)
    assert loop.damping_ratio == pytest.approx(0.7, rel=1e-12)


def test_reflected_inertia_is_R_squared():
    assert reflect_inertia(2.0, 1 / 8) == pytest.approx(2.0 / 64, rel=1e-15)
    assert reflect_inertia(3e-6, 32.0) == pytest.approx(3e-6 * 1024, rel=1e-15)


def test_two_mass_equals_the_two_node_chain_and_bounds_a_three_node_one():
    two = TwoMass(0.5, 2.0, 1e5)
    # closed form against the eigen solve of the same two masses
    assert chain_modes([0.5, 2.0], [1e5])[1] == pytest.approx(two.resonance, rel=1e-12)
    assert two.antiresonance == pytest.approx(math.sqrt(1e5 / 2.0), rel=1e-12)
    # a light middle mass on two springs in series: the two-mass model with the series spring is
    # its limit (the middle mass -> 0)
    modes = chain_modes([0.5, 1e-9, 2.0], [2e5, 2e5])
    assert modes[1] == pytest.approx(two.resonance, rel=1e-6)
    assert modes[0] == pytest.approx(0.0, abs=1e-3)


def test_mesh_loss_factor_classical_value():
    # pi mu (1/z1 + 1/z2): 20/60 teeth, mu 0.05 -> 1.047 %
    assert mesh_loss_factor(0.05, 20, 60) == pytest.approx(math.pi * 0.05 * (1 / 20 + 1 / 60), rel=1e-15)
    assert mesh_loss_factor(0.05, 20, 60) == pytest.approx(0.010472, rel=1e-4)


# ---------------------------------------------------------------- Fig. 1, by hand


def test_dual_motor_bias_by_hand():
    """Fig. 1b: T1 = c/2 + b, T2 = c/2 - b. With b = 30, k = 7.819e5 each, peak 96 (at the output):
    opposed for |c| < 60 with k1 + k2, motor 2 reverses at c = 60 (path 1 alone, the backlash),
    together to 2 x 96 = 192; the load 60 needs b >= 30."""
    d = DualMotorDrive(k1=7.819e5, k2=7.819e5, bias=30.0, control="bias", peak=96.0, backlash=555.6e-6)
    t1, t2 = d.motor_torques(np.array([-100.0, 0.0, 40.0, 60.0, 100.0]))
    assert np.allclose(t1, [-20.0, 30.0, 50.0, 60.0, 80.0])
    assert np.allclose(t2, [-80.0, -30.0, -10.0, 0.0, 20.0])
    assert np.allclose(t1 + t2, [-100.0, 0.0, 40.0, 60.0, 100.0])
    zones = {z["zone"]: z for z in d.zones()}
    assert zones["opposed"]["command_to"] == 60.0 and zones["opposed"]["stiffness"] == 2 * 7.819e5
    assert zones["crossing"]["stiffness"] == 7.819e5 and zones["crossing"]["lost_motion"] == 555.6e-6
    assert zones["together"]["command_to"] == 192.0 and zones["together"]["stiffness"] == 2 * 7.819e5
    assert d.bias_for(60.0) == 30.0 and d.peak_needed(60.0) == 60.0


def test_dual_motor_unidirectional_by_hand():
    """Fig. 1a: neither torque changes sign; one motor carries the load plus the bias."""
    d = DualMotorDrive(k1=1e5, k2=2e5, bias=5.0, control="unidirectional", peak=50.0)
    c = np.linspace(-45, 45, 181)
    t1, t2 = d.motor_torques(c)
    assert np.all(t1 >= 5.0) and np.all(t2 <= -5.0)
    assert np.allclose(t1 + t2, c)
    assert d.capacity == 45.0
    assert [z["zone"] for z in d.zones()] == ["opposed"] and d.zones()[0]["stiffness"] == 3e5
    assert d.peak_needed(40.0) == 45.0 and d.bias_for(40.0) == 0.0
