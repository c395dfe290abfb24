"""The effect library's array functions against their definitions."""

import numpy as np
import pytest

from geargen.fit import effects as fx


@pytest.mark.parametrize("h", [0.0, 0.3, 2.0, 50.0])
@pytest.mark.parametrize("initial", [None, 1.7])
def test_play_operator_matches_its_definition(h, initial):
    rng = np.random.default_rng(3)
    u = np.cumsum(rng.normal(size=3000))
    # the doubling scan only takes min/max of the same numbers: equality is exact
    assert np.array_equal(fx.play_operator(u, h, initial), fx.play_operator_reference(u, h, initial))


def test_play_structure_is_the_local_linear_form():
    rng = np.random.default_rng(4)
    u = np.cumsum(rng.normal(size=2000))
    for h in (0.5, 3.0):
        y, source, side = fx.play_structure(u, h)
        assert np.allclose(y, u[source] + side * h, atol=0)
        assert set(np.unique(side)) <= {-1.0, 0.0, 1.0}


def test_play_lags_by_half_width_on_a_ramp():
    u = np.concatenate([np.linspace(0, 10, 101), np.linspace(10, 0, 101)[1:]])
    y = fx.play_operator(u, 1.0)
    assert np.allclose((u - y)[20:100], 1.0)     # rising: output 1 below the input
    assert np.allclose((u - y)[130:], -1.0)      # falling, once the play is crossed: 1 above


def test_harmonic_parameters_round_trip():
    theta = np.linspace(0, 6 * np.pi, 500)
    sig = fx.harmonic(theta, 2.5, 3.0, 250.0)
    basis = fx.harmonic_basis(theta, 2.5)
    coef = np.linalg.lstsq(basis, sig, rcond=None)[0]
    amp, ph = fx.harmonic_parameters(*coef)
    assert amp == pytest.approx(3.0) and ph == pytest.approx(250.0)


def test_dead_zone_and_its_inverse():
    phi = np.linspace(-30, 30, 61)
    w = 10.0
    dz = fx.dead_zone(phi, w)
    assert np.all(dz[np.abs(phi) <= 5] == 0)
    assert np.allclose(dz[np.abs(phi) > 5], phi[np.abs(phi) > 5] - 5 * np.sign(phi[np.abs(phi) > 5]))
    spring = np.linspace(-20, 20, 41)
    assert np.allclose(fx.dead_zone(fx.dead_zone_inverse(spring, w), w), spring)


def test_stiffening_is_odd_and_hertzian():
    phi = np.array([-2e-3, -1e-3, 0.0, 1e-3, 2e-3])
    t = fx.stiffening(phi, 3.0, 1.5)
    assert t[3] == pytest.approx(3.0)                       # amplitude is the torque at 1 mrad
    assert t[4] == pytest.approx(3.0 * 2 ** 1.5)
    assert np.allclose(t, -t[::-1])


def test_driving_signal_keeps_corners_and_is_monotone_between_reversals():
    t = np.linspace(0, 600, 6000)
    knots = np.array([0, 80, -80, 80, -80, 0.0])
    dist = np.concatenate([[0], np.cumsum(np.abs(np.diff(knots)))])
    prog = np.interp(t / 600 * dist[-1], dist, knots)
    noisy = prog + 0.2 * np.random.default_rng(5).normal(size=t.size)
    s = fx.driving_signal(t, noisy, 0.2)
    # noise-free program: reproduced, corners included (a centred smoother would cut them by ~0.4 Nm)
    assert np.max(np.abs(fx.driving_signal(t, prog, 0.2) - prog)) < 1e-6
    # noisy: noise reduced several-fold and no noise-made reversals
    assert np.std(s - prog) < 0.2 / 2.5
    d = np.diff(s)
    assert np.sum(np.diff(np.sign(d[d != 0])) != 0) == 4   # turns only at the four program corners
    assert fx.reversals(prog, 1.0).tolist() == [np.argmax(prog[:1500]), 1500 + np.argmin(prog[1500:3000]),
                                                3000 + np.argmax(prog[3000:4500]), 4500 + np.argmin(prog[4500:])]


def test_local_linear_smooth_is_exact_on_lines():
    x = np.sort(np.random.default_rng(6).uniform(0, 10, 300))
    y = 3 * x - 2
    assert np.allclose(fx.local_linear_smooth(x, y, 5), y)
