"""The two-path drive model (Hale & Slocum Eqs. 2-6, Figs. 6-7) against hand-derived cases, the
paper's limits, and an independent numerical solution of the spring network."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from geargen.core.drive import TwoPathDrive
from geargen.errors import DesignError


# --- hand-derived cases --------------------------------------------------------------------------

def test_type1_equations_2_and_3_by_hand():
    d = TwoPathDrive("type1", k1=3.0, k2=1.0, preload=2.0)
    assert d.drive_stiffness == pytest.approx(4.0, rel=1e-15)  # Eq. 2: 3 + 1
    assert d.loop_stiffness == pytest.approx(0.75, rel=1e-15)  # Eq. 3: 1/(1/3 + 1/1)
    assert d.stiffness_ratio == pytest.approx(16.0 / 3.0, rel=1e-15)  # Eq. 4: 4^2 / 3
    # Fig. 6b: path 1 (stiff) unloads at d = -P/k1, torque -(k1+k2) P/k1; path 2 at +P/k2
    assert d.unloading_rotations == pytest.approx((-2.0 / 3.0, 2.0), rel=1e-15)
    assert d.unloading_torques == pytest.approx((-8.0 / 3.0, 8.0), rel=1e-15)
    assert d.stiffness_beyond(+1) == 3.0 and d.stiffness_beyond(-1) == 1.0  # loaded path alone


def test_type2_equations_5_and_6_by_hand():
    d = TwoPathDrive("type2", k1=4.0, k2=2.0, preload=1.0, k3=1.0)
    assert d.drive_stiffness == pytest.approx(6.0 - 4.0 / 7.0, rel=1e-15)  # Eq. 5: (4+2) - (4-2)^2/(4+2+1)
    assert d.loop_stiffness == pytest.approx(1.0 / (0.25 + 0.5 + 4.0), rel=1e-15)  # Eq. 6
    # Fig. 7a by hand: dF1/dd = k1 (2 k2 + k3)/(k1+k2+k3) = 4*5/7, dF2/dd = 2*9/7
    assert d.path_force_rates == pytest.approx((20.0 / 7.0, 18.0 / 7.0), rel=1e-15)
    assert sum(d.path_force_rates) == pytest.approx(d.drive_stiffness, rel=1e-15)
    # beyond unloading: the loaded path in series with the preload spring
    assert d.stiffness_beyond(+1) == pytest.approx(1 / (1 / 4 + 1), rel=1e-15)
    assert d.stiffness_beyond(-1) == pytest.approx(1 / (1 / 2 + 1), rel=1e-15)


def test_type2_equal_paths_keep_full_drive_stiffness_whatever_k3():
    # "a small k3 can significantly reduce k_L without effecting k_D"
    for k3 in (1e-3, 1.0, 1e3):
        d = TwoPathDrive("type2", 5.0, 5.0, 1.0, k3)
        assert d.drive_stiffness == pytest.approx(10.0, rel=1e-14)
        assert d.loop_stiffness == pytest.approx(1.0 / (0.4 + 4.0 / k3), rel=1e-14)
        # paper: a type 2 path unloads at twice the preload ("preload at least half the max load")
        assert d.unloading_torques == pytest.approx((-2.0, 2.0), rel=1e-14)


# --- the paper's limits ----------------------------------------------------------------------------

@pytest.mark.parametrize("k1, k2", [(1.0, 1.0), (7.0, 2.0), (0.3, 50.0)])
def test_k3_to_infinity_turns_eqs_5_and_6_into_2_and_3(k1, k2):
    t1 = TwoPathDrive("type1", k1, k2, 1.0)
    previous = None
    for k3 in (1e2, 1e4, 1e6, 1e8):
        t2 = TwoPathDrive("type2", k1, k2, 1.0, k3)
        err = abs(t2.drive_stiffness - t1.drive_stiffness) + abs(t2.loop_stiffness - t1.loop_stiffness)
        if previous is not None:
            assert err < previous  # converging
        previous = err
    assert t2.drive_stiffness == pytest.approx(k1 + k2, rel=1e-6)  # Eq. 2
    assert t2.loop_stiffness == pytest.approx(k1 * k2 / (k1 + k2), rel=1e-6)  # Eq. 3
    exact = TwoPathDrive("type2", k1, k2, 1.0, math.inf)  # the limit itself
    assert exact.drive_stiffness == t1.drive_stiffness and exact.loop_stiffness == t1.loop_stiffness


def test_equal_paths_minimise_equation_4():
    total = 10.0
    ratio = lambda k1: TwoPathDrive("type1", k1, total - k1, 1.0).stiffness_ratio  # noqa: E731
    best = minimize_scalar(ratio, bounds=(0.01, total - 0.01), method="bounded", options={"xatol": 1e-10})
    assert best.success
    assert best.x == pytest.approx(total / 2, abs=1e-6)
    assert best.fun == pytest.approx(4.0, rel=1e-12)  # (k1+k2)^2/(k1 k2) = 4 at k1 = k2
    k1 = np.linspace(0.5, 9.5, 37)
    values = np.array([ratio(k) for k in k1])
    assert np.all(values >= 4.0 - 1e-12)
    assert np.allclose(values, total ** 2 / (k1 * (total - k1)), rtol=1e-14)  # Eq. 4 as printed


# --- an independent solution of the spring network ------------------------------------------------

def network(k1, k2, k3, preload, d, loop_error=0.0):
    """Fig. 7 network with one-sided tooth contacts, solved for the carriage position w by root finding.

    Path 1 pushes when d + w + c1 + e > 0, path 2 when w + c2 - d > 0 (opposite flank sense); the
    spring pushes the carriage towards s. c1, c2, s are chosen so that at d = 0, e = 0 each path
    carries the preload. Returns (drive torque, F1, F2, w).
    """
    c1, c2 = preload / k1, preload / k2
    def forces(w):
        f1 = k1 * max(0.0, d + w + c1 + loop_error)
        f2 = -k2 * max(0.0, w + c2 - d)
        return f1, f2
    if k3 == math.inf:
        w = 0.0
    else:
        s = 2.0 * preload / k3
        balance = lambda w: (lambda f: f[0] - f[1] - k3 * (s - w))(forces(w))  # noqa: E731
        w = brentq(balance, -1e6, 1e6, xtol=1e-15, rtol=1e-15, maxiter=500)
    f1, f2 = forces(w)
    return f1 + f2, f1, f2, w


CASES = [("type1", 3.0, 1.0, math.inf, 2.0), ("type1", 1.0, 1.0, math.inf, 0.5),
         ("type2", 4.0, 2.0, 1.0, 1.0), ("type2", 1.0, 1.0, 0.05, 3.0), ("type2", 2.0, 9.0, 30.0, 0.7)]


@pytest.mark.parametrize("kind, k1, k2, k3, preload", CASES)
def test_piecewise_law_matches_network_including_unloaded_regimes(kind, k1, k2, k3, preload):
    drive = TwoPathDrive(kind, k1, k2, preload, k3)
    lo, hi = drive.unloading_rotations
    d = np.concatenate([np.linspace(3 * lo, 3 * hi, 61), [lo, hi, 0.0, 0.999 * hi, 1.001 * hi]])
    regimes = set()
    for di in d:
        t_ref, f1_ref, f2_ref, _ = network(k1, k2, k3, preload, di)
        f1, f2 = drive.path_torques(di)
        assert float(drive.torque(di)) == pytest.approx(t_ref, rel=1e-9, abs=1e-12 * preload)
        assert float(f1) == pytest.approx(f1_ref, rel=1e-9, abs=1e-12 * preload)
        assert float(f2) == pytest.approx(f2_ref, rel=1e-9, abs=1e-12 * preload)
        regimes.add((f1_ref > 0, f2_ref < 0))
    assert regimes == {(True, True), (True, False), (False, True)}  # both loaded, each path unloaded


@pytest.mark.parametrize("kind, k1, k2, k3, preload", CASES)
def test_rotation_inverts_torque(kind, k1, k2, k3, preload):
    drive = TwoPathDrive(kind, k1, k2, preload, k3)
    d = np.linspace(-5 * preload, 5 * preload, 101) / min(k1, k2)
    assert np.allclose(drive.rotation(drive.torque(d)), d, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("kind, k1, k2, k3, preload", CASES)
def test_loop_stiffness_matches_network_with_free_drive(kind, k1, k2, k3, preload):
    # Fig. 7b: a loop displacement with no drive torque; k_L = dF_L / d(delta_L)
    def preload_at(e):
        # the drive rotates freely: find the d at which the drive torque is zero (monotonic in d)
        d = brentq(lambda d: network(k1, k2, k3, preload, d, e)[0], -1e3, 1e3, xtol=1e-15, rtol=1e-15)
        return network(k1, k2, k3, preload, d, e)[1]
    e = 1e-3 * preload / max(k1, k2)
    slope = (preload_at(e) - preload_at(-e)) / (2 * e)
    drive = TwoPathDrive(kind, k1, k2, preload, k3)
    assert slope == pytest.approx(drive.loop_stiffness, rel=1e-7)


def test_zero_preload_has_no_preload_region():
    d = TwoPathDrive("type2", 2.0, 2.0, 0.0, 1.0)
    assert d.unloading_torques == (0.0, 0.0)
    assert float(d.torque(1.0)) == pytest.approx(d.stiffness_beyond(+1), rel=1e-15)
    assert float(d.torque(-1.0)) == pytest.approx(-d.stiffness_beyond(-1), rel=1e-15)


@pytest.mark.parametrize("kwargs, field", [
    (dict(drive_type="type3", k1=1, k2=1, preload=1), "drive"),
    (dict(drive_type="type1", k1=0, k2=1, preload=1), "k1"),
    (dict(drive_type="type1", k1=1, k2=math.inf, preload=1), "k2"),
    (dict(drive_type="type1", k1=1, k2=1, preload=1, k3=5.0), "k3"),
    (dict(drive_type="type2", k1=1, k2=1, preload=1, k3=0.0), "k3"),
    (dict(drive_type="type2", k1=1, k2=1, preload=-1, k3=1.0), "preload"),
])
def test_bad_drive_inputs_name_the_field(kwargs, field):
    with pytest.raises(DesignError) as info:
        TwoPathDrive(**kwargs)
    assert info.value.field == field
