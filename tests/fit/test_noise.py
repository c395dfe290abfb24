"""The model-free noise estimate: immune to the signal's slope and curvature, uneven sampling, gaps."""

import numpy as np
import pytest

from geargen.fit.noise import difference_contrasts, noise_of_signal, noise_of_torque_residual
from geargen.fit.simulate import Sampling, TorqueSettings, TorqueTruth, sample_times, simulate_torque_deflection


def test_contrasts_annihilate_quadratics_at_any_spacing():
    t = np.cumsum(np.random.default_rng(1).uniform(0.2, 1.8, 500))
    c, valid = difference_contrasts(t, 5.0 + 3.0 * t - 0.02 * t * t)
    assert np.max(np.abs(c)) < 1e-8 * 0.02 * t.max() ** 2


@pytest.mark.parametrize("sigma", [0.05, 0.5, 2.0])
def test_noise_level_under_a_large_smooth_signal(sigma):
    rng = np.random.default_rng(2)
    t = sample_times(Sampling(samples=20000, duration_s=1000.0, dropouts=5, dropout_fraction=0.1), rng)
    # a signal 1000x the noise with slope, curvature and a sinusoid sampled ~60 times per period
    signal = 3000 * sigma * (t / 1000) ** 2 + 200 * sigma * np.sin(2 * np.pi * t / 3.0) + 50 * t
    est = noise_of_signal(t, signal + sigma * rng.normal(size=t.size))
    # the median of ~20000 |contrasts| has a relative standard error near 1.5 %
    assert est.rms == pytest.approx(sigma, rel=0.05)


def test_torque_residual_noise_from_both_channels():
    sim = simulate_torque_deflection(TorqueTruth(), np.random.default_rng(3),
                                     TorqueSettings(torque_noise_Nm=0.05, rotation_noise_urad=0.1))
    m = sim.measurement
    est = noise_of_torque_residual(m.time_s, m.torque_Nm, m.rotation_rad * 1e6)
    assert est.channels["torque"] == pytest.approx(0.05, rel=0.1)
    assert est.channels["rotation"] == pytest.approx(np.hypot(0.1, 0.01 / np.sqrt(12)), rel=0.1)
    # the rotation noise reaches the residual through the local stiffness: 0.1 urad x 8e5 Nm/rad = 0.08 Nm
    assert est.rms == pytest.approx(sim.true_noise_rms, rel=0.1)
