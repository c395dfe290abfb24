"""Real-logger artefacts, each with and without an undeclared effect: time stamps of finite
resolution (read from the CSV), isolated spikes, readings quantised by a dial or an encoder. The
fit must see through each: the true effect found with its parameters, nothing invented, the
residual at the noise actually injected, the spikes named."""

from dataclasses import replace

import numpy as np
import pytest

from fit_cases import NOISE_TOL, RELATIVE_TOL, match
from geargen.fit.measurement import read_measurement, write_measurement
from geargen.fit.noise import isolated_spikes, reading_quantum
from geargen.fit.selection import diagnose
from geargen.fit.simulate import (PreloadSettings, PreloadTruth, TorqueSettings, TorqueTruth, simulate_preload_trace,
                                  simulate_torque_deflection)

EFFECTS = {"preload_trace": {"harmonics": ((2.0, 3.0, 40.0),)}, "torque_deflection": {"hysteresis_half_width": 1.0}}


def _simulate(kind, with_effect, seed, **settings):
    rng = np.random.default_rng(seed)
    truth = EFFECTS[kind] if with_effect else {}
    if kind == "preload_trace":
        return simulate_preload_trace(PreloadTruth(**truth), rng, replace(PreloadSettings(), **settings))
    return simulate_torque_deflection(TorqueTruth(**truth), rng, replace(TorqueSettings(), **settings))


def _stamped(sim, tmp_path, resolution_s):
    """The record through its CSV, the logger stamping time to ``resolution_s`` (floored)."""
    csv = write_measurement(sim.measurement, tmp_path, "logged")
    lines = csv.read_text().splitlines()
    out = [lines[0]]
    for line in lines[1:]:
        t, rest = line.split(",", 1)
        out.append(f"{np.floor(float(t) / resolution_s) * resolution_s:.3f},{rest}")
    csv.write_text("\n".join(out) + "\n")
    return read_measurement(csv)


def _spiked(sim, count, size, seed):
    """``count`` isolated spikes of +-``size`` noise levels on the record's main channel."""
    m = sim.measurement
    rng = np.random.default_rng(seed)
    at = rng.choice(np.arange(10, m.samples - 10, 7), count, replace=False)  # never two side by side
    kick = np.zeros(m.samples)
    kick[at] = rng.choice([-1.0, 1.0], count) * size * sim.true_noise_rms
    if m.kind == "preload_trace":
        return replace(m, carriage_um=m.carriage_um + kick), at
    return replace(m, torque_Nm=m.torque_Nm + kick), at


def _check(report, sim, with_effect):
    assert not report["unexplained"]
    assert report["stages"]["extended"]["rms"] == pytest.approx(sim.true_noise_rms, rel=NOISE_TOL)
    added = report["effects_added"]
    if not with_effect:
        assert added == []
        return
    assert len(added) == len(sim.expected) == 1
    got, want = match(sim.expected[0], added), sim.expected[0]
    for key in ("amplitude", "half_width"):
        if key in want:
            assert got[key] == pytest.approx(want[key], rel=RELATIVE_TOL)
    if "order" in want:
        assert got["order"] == pytest.approx(want["order"], abs=0.01)


@pytest.mark.parametrize("with_effect", [False, True])
@pytest.mark.parametrize("kind", ["preload_trace", "torque_deflection"])
def test_time_stamps_of_finite_resolution(tmp_path, kind, with_effect):
    """Rows every 37-110 ms, stamped to 0.5 s: about ten rows share each stamp."""
    sim = _simulate(kind, with_effect, 201)
    meas = _stamped(sim, tmp_path, 0.5)
    assert any("share their time stamp" in n for n in meas.notes)
    _check(diagnose(meas).to_json(), sim, with_effect)


@pytest.mark.parametrize("with_effect", [False, True])
@pytest.mark.parametrize("kind", ["preload_trace", "torque_deflection"])
def test_isolated_spikes_are_left_out_and_named(kind, with_effect):
    """25 glitches of 30 noise levels: each left out and reported by its time; the rest fits."""
    sim = _simulate(kind, with_effect, 202)
    meas, at = _spiked(sim, 25, 30.0, 7)
    report = diagnose(meas).to_json()
    rejected = report["rejected_samples"]
    assert rejected["count"] == 25
    assert sorted(e["time_s"] for e in rejected["samples"]) == pytest.approx(sorted(meas.time_s[at]), rel=1e-5)  # (6 digits)
    assert all(abs(abs(e["deviation"]) - 30.0 * sim.true_noise_rms / report["noise_rms"]) < 8 for e in rejected["samples"])
    _check(report, sim, with_effect)


@pytest.mark.parametrize("with_effect", [False, True])
@pytest.mark.parametrize("kind, settings", [
    ("preload_trace", {"resolution_um": 1.0, "noise_um": 0.4}),   # a 1 um dial
    ("torque_deflection", {"rotation_resolution_urad": 2.0}),     # an encoder's 2 urad counts, 0.05 urad noise
])
def test_quantised_readings(kind, settings, with_effect):
    """A reading quantised coarser than its noise: the reading error (q^2/12 for a signal that
    sweeps across the steps) is counted as noise, so nothing is invented and the fit holds."""
    sim = _simulate(kind, with_effect, 203, **settings)
    _check(diagnose(sim.measurement).to_json(), sim, with_effect)


def test_spike_detector_leaves_kinks_steps_and_reversals_alone():
    """A triangle wave (sharp reversals), a step of 50 noise levels, a sine: no spike; the same
    with five glitches: exactly those."""
    rng = np.random.default_rng(4)
    t = np.cumsum(rng.uniform(0.5, 1.5, 4000))
    clean = np.abs((t % 400) - 200) + np.sin(t / 30) + np.where(t > t[2500], 25.0, 0.0)
    y = clean + 0.5 * rng.normal(size=t.size)
    assert not isolated_spikes(t, y, 0.5).any()
    glitches = np.array([100, 101 + 300, 1700, 2500, 3999 - 5])
    y[glitches] += np.array([20.0, -15.0, 12.0, 30.0, -40.0])
    assert np.flatnonzero(isolated_spikes(t, y, 0.5)).tolist() == sorted(glitches.tolist())


@pytest.mark.parametrize("q", [0.01, 1.0, 2.5e-3])
def test_reading_quantum(q):
    rng = np.random.default_rng(5)
    values = np.round(rng.normal(size=5000) * 50 / q) * q + 7 * q
    assert reading_quantum(values) == pytest.approx(q, rel=1e-6)
    assert reading_quantum(rng.normal(size=5000)) == 0.0  # continuous readings: no grid


def test_a_noise_free_staircase_is_a_dial_reading():
    """A carriage read by a 1 um dial that never flickers (no noise under the divisions): once
    refused as having no noise, it is a quantised reading; its error, q / sqrt(12) = 0.2887 um for
    a signal that sweeps the divisions, is the noise."""
    from geargen.fit.noise import level_of
    t = np.arange(4000) * 0.1
    staircase = np.floor(30.0 * np.sin(t / 60.0))
    level, _ = level_of(t, staircase)
    assert level == pytest.approx(1 / np.sqrt(12), rel=1e-9)
    # and the true reading error of the staircase is that
    assert np.sqrt(np.mean((staircase + 0.5 - 30.0 * np.sin(t / 60.0)) ** 2)) == pytest.approx(1 / np.sqrt(12), rel=0.05)


def _encoder_hold(seed: int, stray: float = 0.0):
    """A 12-bit encoder read at 10 Hz while a slow load moves the output a few counts and holds it
    (runs of tens of equal counts), converted to urad in floating point; ``stray`` of the
    readings are a bus glitch 0.37 of a count off."""
    rng = np.random.default_rng(seed)
    t = np.arange(1300) * 0.1
    counts = np.round(3.0 * np.sin(2 * np.pi * t / 130.0))
    count_urad = 2 * np.pi / 4096 * 1e6
    urad = counts * count_urad * (1.0 + 1e-15 * rng.normal(size=t.size))  # (a conversion's last digits)
    glitch = rng.random(t.size) < stray
    urad[glitch] += 0.37 * count_urad
    return t, urad, count_urad


def test_the_step_of_a_quantised_channel_is_found_despite_stray_readings():
    """3 % of the readings off the grid (a bus glitch) and the float noise of a unit conversion:
    once no step was found (99 % of the readings had to sit within 1 % of the grid), now the count."""
    _, urad, count = _encoder_hold(7, stray=0.03)
    assert reading_quantum(urad) == pytest.approx(count, rel=1e-9)
    assert reading_quantum(_encoder_hold(7, stray=0.2)[1]) == 0.0  # a fifth off the grid: no grid


def test_a_held_encoder_has_its_reading_error_as_noise():
    """Runs of four equal counts give third differences of a float's last digits: their median
    (the estimator without a floor, 1e-10 urad here as in issue 30's 2.1e-10) would weigh every
    fit; the level is floored at the count's reading error q / sqrt(12) = 443 urad."""
    from geargen.fit.noise import MAD_TO_SIGMA, channel_level, contrast_magnitudes
    t, urad, count = _encoder_hold(8)
    assert MAD_TO_SIGMA * np.median(contrast_magnitudes(t, urad)) < 1e-6
    level, _, phi, _ = channel_level(t, urad)
    assert level >= count / np.sqrt(12.0) * (1 - 1e-12) and phi == 0.0


def test_a_load_stepped_within_a_few_samples_is_no_coloured_noise():
    """A torque stepped between 0 and +-0.15 N·m in three samples of a 10 Hz logger and held: the
    differences over every other sample exceed those over consecutive ones by more than any AR(1)
    noise can (the steps are signal the sampling does not resolve), so no lag-one correlation is
    inferred; it was 0.95, multiplying the level by 5.7."""
    from geargen.fit.noise import channel_level
    rng = np.random.default_rng(9)
    t = np.arange(600) * 0.1
    cycle = np.concatenate([np.zeros(6), [0.05, 0.12, 0.15, 0.15, 0.12, 0.05], np.zeros(6),
                            [-0.05, -0.12, -0.15, -0.15, -0.12, -0.05]])
    torque = np.resize(cycle, t.size) + 0.001 * rng.normal(size=t.size)
    level, _, phi, resolved = channel_level(t, torque)
    assert not resolved and phi == 0.0
    assert level < 0.05  # the median of the contrasts: the held samples' noise and a few step edges


def test_a_printed_actuator_log_is_never_explained_with_absurd_parameters():
    """Issue 30's log shape: two +-100 N·m cycles in 1,300 rows, a 12-bit output encoder, torque
    from motor current (0.05 N·m steps, 0.3 N·m noise), a 0.02 rad dead band and friction that
    grows with the load. Whatever the fit finds, no play is wider than the torque range, no dead
    band wider than the rotation, the rotation's noise is at least its reading error, and a record
    with an absurd parameter is never called explained."""
    from geargen.fit import effects as fx
    from geargen.fit.measurement import Measurement, TorqueModelSpec
    rng = np.random.default_rng(10)
    t = np.arange(1300) * 0.1
    applied = 100.0 * np.sin(2 * np.pi * t / 65.0)
    spring = fx.play_operator(applied, 15.0 + 0.1 * np.abs(applied))
    rotation = fx.dead_zone_inverse(spring / 2500.0, 0.02)  # rad, 2,500 N·m/rad outside the band
    count = 2 * np.pi / 4096
    meas = Measurement(kind="torque_deflection", name="printed", time_s=t, model=TorqueModelSpec("type1"),
                       torque_Nm=np.round((applied + 0.3 * rng.normal(size=t.size)) / 0.05) * 0.05,
                       rotation_rad=np.round(rotation / count) * count)
    dg = diagnose(meas)
    report = dg.to_json()
    span_t, span_r = np.ptp(meas.torque_Nm), np.ptp(meas.rotation_rad) * 1e6
    assert report["noise_channels"]["output_rotation_urad"] >= count * 1e6 / np.sqrt(12) * (1 - 1e-5)
    for e in report["effects_added"]:
        assert not (e["effect"] == "hysteresis" and 2 * e["half_width"] >= span_t), e
        assert not (e["effect"] == "dead_band" and e["width_urad"] >= span_r), e
    plausibility = next(x for x in dg.tests if x.name == "plausibility")
    assert plausibility.passed or report["unexplained"]


def test_an_absurd_effect_or_noise_level_makes_the_record_unexplained():
    """The plausibility test: a friction play as wide as the whole torque range (issue 30's
    half_width 100.11 N·m on a +-100 N·m log, then called explained), a dead band wider than the
    rotation recorded, or a channel's noise level below its reading error each fail it."""
    from dataclasses import replace as with_values

    from geargen.fit.model import ModelFit, Term
    from geargen.fit.selection import make_model
    from geargen.fit.selection import estimate_noise, plausibility
    sim = _simulate("torque_deflection", False, 204, rotation_resolution_urad=2.0)
    m = sim.measurement
    noise = estimate_noise(m)
    model = make_model(m, noise)
    span = float(np.ptp(model.T_smooth))

    def verdict(values, terms=(Term("hysteresis"), Term("dead_band")), level_noise=noise):
        fit = ModelFit(terms=terms, rss=1.0, n_fitted=m.samples, n_params=2, values=values, declared_values={})
        return plausibility(model, fit, level_noise)

    fine = ({"half_width": 0.4 * span}, {"width_urad": 10.0})
    assert verdict(fine).passed
    wide = verdict(({"half_width": 0.5 * span * 1.001}, {"width_urad": 10.0}))
    assert not wide.passed and "wider than the whole torque range" in wide.text
    band = verdict(({"half_width": 1.0}, {"width_urad": 1.01 * np.ptp(m.rotation_rad) * 1e6}))
    assert not band.passed and "wider than the whole rotation" in band.text
    # the rotation read in 2 urad steps: a level below 2 / sqrt(12) = 0.577 urad is below its reading error
    low = with_values(noise, channels={**noise.channels, "rotation": 0.5})
    below = verdict(fine, level_noise=low)
    assert not below.passed and "below its reading error" in below.text
