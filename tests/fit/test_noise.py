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


def test_contrast_variance_of_ar1_noise_against_its_definition():
    """(1 - rho)(1 - rho/2 + rho^2/10) is w' R w for the unit third difference w = (-1, 3, -3, 1)
    / sqrt 20 and R_jk = rho^|j - k|."""
    from geargen.fit.noise import contrast_variance
    w = np.array([-1.0, 3.0, -3.0, 1.0]) / np.sqrt(20.0)
    for rho in (-0.4, 0.0, 0.3, 0.6, 0.9):
        R = rho ** np.abs(np.subtract.outer(np.arange(4), np.arange(4)))
        assert contrast_variance(rho) == pytest.approx(w @ R @ w, rel=1e-12)


@pytest.mark.parametrize("jitter, bias", [(0.0, 0.02), (0.5, 0.035)])
@pytest.mark.parametrize("phi", [0.0, 0.3, 0.6])
def test_coloured_noise_level_and_correlation_from_the_data(phi, jitter, bias):
    """AR(1) noise of unit variance on a smooth signal, 16384 samples, 12 records: the level
    within 3 % and the lag-one correlation within 0.02 on average for even spacing (the formula
    is exact there); sample intervals varying +-50 % bias it by up to 0.035 low. Each record's
    within four of its own stated scatter."""
    from geargen.fit.noise import ar1_scatter, coloured_level
    from geargen.fit.simulate import unit_noise
    rng = np.random.default_rng(31)
    levels, phis = [], []
    for _ in range(12):
        t = np.cumsum(rng.uniform(1 - jitter, 1 + jitter, 16384))
        y = 20 * np.sin(t / 900.0) + unit_noise(rng, t.size, phi)
        level, _, got = coloured_level(t, y)
        levels.append(level)
        phis.append(got)
        if phi:
            assert abs(got - phi) < 4 * max(ar1_scatter(t, y), 0.01) + bias
    assert np.mean(levels) == pytest.approx(1.0, rel=0.03)
    assert np.mean(phis) == pytest.approx(phi, abs=bias)
