"""Least-squares periodogram over orders: uneven sampling, gaps, a trace that turns back."""

import numpy as np
import pytest

from geargen.fit.periodogram import exact_fit, ls_periodogram, peaks, refine_order
from geargen.fit.simulate import Sampling, output_angle_history, sample_times


@pytest.fixture(scope="module")
def trace():
    rng = np.random.default_rng(7)
    t = sample_times(Sampling(samples=12000, duration_s=600.0, dropouts=3, dropout_fraction=0.08), rng)
    theta = output_angle_history(t, 600.0, 1.5, True, 0.08)
    r = 3.0 * np.cos(2.0 * theta - 0.6) + 0.8 * np.cos(256.0 * theta + 1.0) + 1.2 * np.cos(7.3 * theta)
    return theta, r + 0.3 * rng.normal(size=t.size)


def test_fft_periodogram_matches_the_exact_sums(trace):
    theta, r = trace
    pg = ls_periodogram(theta, r - r.mean(), 0.5, 600.0)
    for i in np.linspace(0, pg.orders.size - 1, 25).astype(int):
        exact = exact_fit(theta, r - r.mean(), pg.orders[i])[2]
        assert pg.reduction[i] == pytest.approx(exact, rel=0.02, abs=1e-3 * r.size * 0.09)


def test_peaks_at_the_true_orders(trace):
    theta, r = trace
    pg = ls_periodogram(theta, r - r.mean(), 0.5, 600.0)
    found = sorted(pg.orders[i] for i in peaks(pg, 3))
    assert found == pytest.approx([2.0, 7.3, 256.0], abs=pg.resolution / 3)


def test_refined_order_of_an_isolated_sinusoid(trace):
    theta, _ = trace
    r = 0.8 * np.cos(256.0 * theta + 1.0) + 0.3 * np.random.default_rng(8).normal(size=theta.size)
    q, _ = refine_order(theta, r, 256.05, 0.2)
    assert q == pytest.approx(256.0, abs=2e-3)
