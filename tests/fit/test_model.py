"""Declared models: the torque law is TwoPathDrive itself, in the contract's units."""

import math

import numpy as np
import pytest

from geargen.core.drive import TwoPathDrive
from geargen.fit.model import PreloadModel, Term, TorqueModel, law_torque_Nm
from geargen.fit.selection import estimate_noise
from geargen.fit.simulate import PreloadSettings, PreloadTruth, TorqueSettings, TorqueTruth, simulate_preload_trace, \
    simulate_torque_deflection


def test_law_is_two_path_drive_in_Nm():
    rot = np.linspace(-2e-3, 2e-3, 41)
    drive = TwoPathDrive("type2", k1=4e8, k2=3e8, preload=25e3, k3=4e7)  # N*mm/rad and N*mm
    expected = drive.torque(rot) / 1000.0
    assert np.allclose(law_torque_Nm("type2", 4e5, 3e5, 4e4, 25.0, rot), expected)
    # Eq. 2 in the middle, k1 alone in series with k3 beyond (type 2): slopes in Nm/rad
    assert (law_torque_Nm("type2", 4e5, 3e5, 4e4, 25.0, np.array([1e-6]))[0] / 1e-6
            == pytest.approx((7e5 - 1e10 / 7.4e5)))


def test_declared_torque_fit_recovers_the_law():
    truth = TorqueTruth(theta0_urad=1.5)
    sim = simulate_torque_deflection(truth, np.random.default_rng(2), TorqueSettings(torque_noise_Nm=0.02))
    model = TorqueModel(sim.measurement, estimate_noise(sim.measurement))
    fit = model.fit(())
    d = fit.declared_values
    # the declared values were 8 %, 5 %, 10 % and 10 % off; the fit finds the truth
    assert d["k1"] == pytest.approx(truth.k1, rel=0.01)
    assert d["k2"] == pytest.approx(truth.k2, rel=0.01)
    assert d["k3"] == pytest.approx(truth.k3, rel=0.01)
    assert d["preload"] == pytest.approx(truth.preload, rel=0.02)
    assert d["theta0_urad"] == pytest.approx(1.5, abs=0.1)
    assert fit.rms == pytest.approx(sim.true_noise_rms, rel=0.05)
    assert model.nominal() is not None and math.sqrt(np.mean(model.nominal() ** 2)) > 5 * fit.rms


def test_torque_without_nominal_values():
    truth = TorqueTruth(declare_values=False)
    sim = simulate_torque_deflection(truth, np.random.default_rng(3))
    model = TorqueModel(sim.measurement, estimate_noise(sim.measurement))
    assert model.nominal() is None
    assert model.fit(()).rms == pytest.approx(sim.true_noise_rms, rel=0.05)


def test_declared_preload_fit_and_nominal_stage():
    sim = simulate_preload_trace(PreloadTruth(), np.random.default_rng(4), PreloadSettings(noise_um=0.3))
    model = PreloadModel(sim.measurement, estimate_noise(sim.measurement))
    fit = model.fit(())
    assert fit.rms == pytest.approx(sim.true_noise_rms, rel=0.02)
    assert fit.declared_values["output"]["amplitude"] == pytest.approx(20.0, rel=0.01)
    assert fit.declared_values["mesh1"]["amplitude"] == pytest.approx(1.0, rel=0.05)
    assert np.allclose(model.nominal(), sim.measurement.carriage_um - sim.measurement.carriage_um.mean())


def test_preload_hysteresis_fit_is_joint():
    sim = simulate_preload_trace(PreloadTruth(hysteresis_half_width=0.8), np.random.default_rng(5),
                                 PreloadSettings(noise_um=0.2))
    model = PreloadModel(sim.measurement, estimate_noise(sim.measurement))
    fit = model.fit((Term("hysteresis"),))
    assert fit.values[0]["half_width"] == pytest.approx(0.8, rel=0.03)
    assert fit.declared_values["output"]["amplitude"] == pytest.approx(20.0, rel=0.01)
