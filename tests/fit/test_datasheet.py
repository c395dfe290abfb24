"""The datasheet figures (contracts/measurements.md, ``datasheet``) against closed forms of the
two-path law (Eqs. 2-6 of the paper, :class:`geargen.core.drive.TwoPathDrive`) and against a
direct computation from the record written out here."""

import math

import numpy as np
import pytest

from geargen.core.drive import TwoPathDrive
from geargen.fit.datasheet import MIDLINE_LEVELS, STIFFNESS_LIMIT_FRACTIONS, datasheet, split_tests
from geargen.fit.measurement import DatasheetSettings
from geargen.fit.selection import diagnose
from geargen.fit.simulate import (Sampling, TorqueSettings, TorqueTruth, TransmissionSettings, TransmissionTruth,
                                  simulate_torque_deflection, simulate_transmission_error)

# the simulator's default law: k1 = k2 = 4e5, k3 = 4e4 Nm/rad, preload 25 Nm (type 2)
LAW = TorqueTruth().drive()
K_DRIVE = LAW.drive_stiffness * 1e-3  # Nm/rad while both paths carry load (Eq. 5): 8e5
K_ALONE = LAW.stiffness_beyond(+1) * 1e-3  # one path in series with the preload spring: 36,364
UNLOADS_AT = LAW.unloading_torques[1] * 1e-3  # Nm: 50


def _sheet(truth, seed, **settings):
    sim = simulate_torque_deflection(truth, np.random.default_rng(seed), TorqueSettings(**settings))
    return sim, diagnose(sim.measurement).to_json()["datasheet"]


def test_closed_forms_for_the_law_with_friction_and_a_dead_band():
    """Friction h and a dead band w around a linear spring k_D: on the falling branch the spring
    holds +h at zero applied torque, on the rising branch -h, and the dead band puts w between
    them: hysteresis loss 2h / k_D + w. At +-T (T > h) both branches lie beyond the band on the
    same side: mid-line rotation +-(T / k_D + w / 2), lost motion 2T / k_D + w."""
    h, w = 1.0, 10.0
    sim, sheet = _sheet(TorqueTruth(hysteresis_half_width=h, dead_band_urad=w), 21)
    (test,) = sheet["tests"]
    at = 0.03 * test["rated_torque_Nm"]
    assert test["rated_torque_Nm"] == pytest.approx(80.0, abs=0.3)  # the test's largest |torque| (0.1 Nm noise)
    assert test["lost_motion_at_Nm"] == pytest.approx(at)
    # rotation noise 0.05 urad and torque noise 0.1 Nm / k_D = 0.125 urad per crossing, about ten crossings:
    # 0.15 urad leaves three standard errors
    assert test["hysteresis_loss_urad"] == pytest.approx(2 * h / K_DRIVE * 1e6 + w, abs=0.15)
    assert test["lost_motion_urad"] == pytest.approx(2 * at / K_DRIVE * 1e6 + w, abs=0.15)
    assert sheet["transmission_accuracy_urad"] is None
    assert {"hysteresis_loss", "lost_motion", "stiffness"} <= set(test["how"])


def test_three_segment_stiffness_of_the_two_path_law():
    """Loaded to 150 Nm (a path unloads at 50 Nm): T1 = 30 Nm and T2 = 105 Nm by the tool's
    default. K1 is the drive stiffness with both paths loaded (Eq. 5), K3 one path in series with
    the preload spring, and K2, across the kink, the least-squares slope of the noise-free law's
    mid-line over 30-105 Nm computed here from the law itself."""
    h = 1.0
    sim, sheet = _sheet(TorqueTruth(hysteresis_half_width=h), 22, max_torque_Nm=150.0)
    (test,) = sheet["tests"]
    k = test["stiffness"]
    amplitude = test["torque_amplitude_Nm"]
    # (the JSON carries 6 significant digits)
    assert (k["T1_Nm"], k["T2_Nm"]) == pytest.approx(tuple(f * amplitude for f in STIFFNESS_LIMIT_FRACTIONS), rel=2e-6)
    assert k["T1_Nm"] + h < UNLOADS_AT < k["T2_Nm"] - h
    # the rotation spans 37 urad over K1's segment (0.1 urad of noise on each mid-line point: 1 %)
    assert k["K1_Nm_per_rad"] == pytest.approx(K_DRIVE, rel=0.01)
    # 1,240 urad over K3's segment: the noise is 1e-4 of it; 0.5 % covers the torque noise's bias at the peak
    assert k["K3_Nm_per_rad"] == pytest.approx(K_ALONE, rel=0.005)
    # the mid-line at the datasheet's torque levels (MIDLINE_LEVELS a side, up to just below the peak)
    top = amplitude * (1 - 0.5 / MIDLINE_LEVELS)
    levels = np.linspace(top / MIDLINE_LEVELS, top, MIDLINE_LEVELS)
    levels = levels[(levels >= k["T1_Nm"]) & (levels <= k["T2_Nm"])]
    mid = 0.5 * (LAW.rotation((levels - h) * 1e3) + LAW.rotation((levels + h) * 1e3))  # rad, mean of both branches
    k2_law = np.polyfit(mid, levels, 1)[0]  # (the law is odd: the negative side gives the same slope)
    assert k["K2_Nm_per_rad"] == pytest.approx(k2_law, rel=0.01)  # the same convention on the noise-free law


def test_tests_by_number_and_by_amplitude_agree():
    """Five cycles of +-30 Nm then three of +-80 Nm: numbered by a test_nr column, or found by their
    amplitude, the tests and their figures are the same; the friction that grows with the
    amplitude (1 Nm at 30, 3 Nm at 80) shows in the hysteresis loss, 2h / k_D each."""
    settings = dict(tests=((5, 30.0), (3, 80.0)), sampling=Sampling(samples=8000, duration_s=800.0))
    truth = TorqueTruth(amplitude_hysteresis=(3.0, 1.0))
    numbered = simulate_torque_deflection(truth, np.random.default_rng(23), TorqueSettings(number_tests=True, **settings))
    plain = simulate_torque_deflection(truth, np.random.default_rng(23), TorqueSettings(**settings))
    assert np.array_equal(numbered.measurement.torque_Nm, plain.measurement.torque_Nm)
    by_number = datasheet(numbered.measurement, numbered.clean)["tests"]
    by_amplitude = datasheet(plain.measurement, plain.clean)["tests"]
    assert [t["test"] for t in by_number] == [1, 2] and [t["test"] for t in by_amplitude] == [0, 1]
    rows = [rows for _, rows in split_tests(plain.clean)]
    assert rows[1][0] == np.flatnonzero(numbered.measurement.test_nr == 2)[0]  # the same first row
    for a, b, amplitude in zip(by_number, by_amplitude, (30.0, 80.0)):
        assert a["torque_amplitude_Nm"] == pytest.approx(amplitude, rel=1e-3)
        assert b["hysteresis_loss_urad"] == pytest.approx(a["hysteresis_loss_urad"], rel=1e-9)
        friction = 3.0 * amplitude / 80.0
        # rotation noise 0.05 urad over 8-10 crossings, on 2.5-7.5 urad: 0.1 urad
        assert a["hysteresis_loss_urad"] == pytest.approx(2 * friction / K_DRIVE * 1e6, abs=0.1)


def test_the_sidecar_settings_are_used():
    sim = simulate_torque_deflection(TorqueTruth(), np.random.default_rng(24), TorqueSettings())
    from dataclasses import replace
    meas = replace(sim.measurement, test=DatasheetSettings(rated_torque_Nm=40.0, lost_motion_fraction=0.1,
                                                           stiffness_limits_Nm=(10.0, 30.0)))
    (test,) = datasheet(meas, sim.clean)["tests"]
    assert test["rated_torque_Nm"] == 40.0 and test["lost_motion_at_Nm"] == pytest.approx(4.0)
    assert (test["stiffness"]["T1_Nm"], test["stiffness"]["T2_Nm"]) == (10.0, 30.0)
    assert "sidecar" in test["how"]["stiffness"]
    # no friction, no dead band: lost motion 2 x 4 Nm / k_D = 10 urad
    assert test["lost_motion_urad"] == pytest.approx(8.0 / K_DRIVE * 1e6, abs=0.15)


def _accuracy_by_hand(meas) -> tuple[float, int]:
    """The contract's transmission accuracy computed here, sample by sample, for a record that
    turns forward and then back once: the two runs meet at the largest output angle; within each,
    revolution k holds the samples that have turned between 2 pi k and 2 pi (k + 1) from the run's
    first sample, for each whole turn; the figure is max - min of the error over the revolution."""
    te = (meas.angle_rad - meas.input_angle_rad / meas.model.ratio) * 1e6
    theta = meas.angle_rad
    turn = int(np.argmax(theta))
    figures = []
    for run in (range(0, turn + 1), range(turn + 1, theta.size)):
        start = theta[run[0]]
        travelled = max(abs(theta[i] - start) for i in run)
        k = 0
        while travelled >= 2 * math.pi * (k + 1):
            inside = [te[i] for i in run if 2 * math.pi * k <= abs(theta[i] - start) <= 2 * math.pi * (k + 1)]
            figures.append(max(inside) - min(inside))
            k += 1
    return max(figures), len(figures)


def test_transmission_accuracy_against_a_direct_computation_and_a_closed_form():
    """A pure once-per-turn error of 20 urad on the output gear and nothing else, read without
    noise: over each whole output revolution the error spans 2 x 20 urad (closed form). With all
    the declared terms and encoder noise: the figure against the sample-by-sample computation."""
    clean = TransmissionSettings(output_noise_urad=0.0, input_noise_urad=0.0, output_counts=1 << 40,
                                 input_counts=1 << 40, revolutions=2.5, return_trip=False,
                                 sampling=Sampling(samples=20000, duration_s=600.0, dropouts=0))
    sim = simulate_transmission_error(TransmissionTruth(eccentricity_urad=(0.0, 0.0, 20.0), mesh_urad=((0.0, 0.0),) * 2),
                                      np.random.default_rng(25), clean)
    sheet = datasheet(sim.measurement)
    assert len(sheet["per_revolution_urad"]) == 2  # 2.5 turns forward: two whole ones
    # 8,000 samples a turn: the sampled peak misses the true one by 20 urad x (1 - cos(pi / 8000)), 1.5e-6 urad
    assert sheet["transmission_accuracy_urad"] == pytest.approx(40.0, abs=1e-4)
    sim = simulate_transmission_error(TransmissionTruth(backlash_half_width_urad=5.0), np.random.default_rng(26),
                                      TransmissionSettings(revolutions=2.2))
    sheet = datasheet(sim.measurement)
    by_hand, count = _accuracy_by_hand(sim.measurement)
    assert len(sheet["per_revolution_urad"]) == count == 4  # 2.2 turns forward and back: two whole ones each way
    assert sheet["transmission_accuracy_urad"] == pytest.approx(by_hand, rel=1e-12)
