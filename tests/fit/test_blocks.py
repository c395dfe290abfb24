"""Long records are read, estimated and fitted in blocks of rows: the results are those of one
block (bit for bit where the arithmetic is the same, to rounding where sums are split), and the
memory grows with the record by a few floats per row, not by the width of the design matrix.

Block sizes are lowered here so that ordinary test records take the long-record paths.
"""

import tracemalloc
from pathlib import Path

import numpy as np
import pytest

from geargen.fit import effects as fx
from geargen.fit import measurement as measurement_module
from geargen.fit import model as model_module
from geargen.fit import noise as noise_module
from geargen.fit import periodogram as periodogram_module
from geargen.fit.measurement import MeasurementError, read_csv, read_measurement, write_measurement
from geargen.fit.noise import difference_contrasts, level_of, noise_of_signal
from geargen.fit.periodogram import ls_periodogram
from geargen.fit.selection import diagnose
from geargen.fit.simulate import PreloadSettings, PreloadTruth, Sampling, sample_times, simulate_preload_trace


def _small_blocks(monkeypatch, rows=2048):
    monkeypatch.setattr(model_module, "ROW_BLOCK", rows)
    monkeypatch.setattr(noise_module, "RUN_BLOCK", rows - 5)
    monkeypatch.setattr(fx, "PLAY_BLOCK", rows + 3)
    monkeypatch.setattr(periodogram_module, "SPREAD_BLOCK", rows - 1)
    monkeypatch.setattr(measurement_module, "CSV_BLOCK_BYTES", 4096)


@pytest.mark.parametrize("h,initial", [(0.0, None), (0.7, None), (3.0, 2.0), (50.0, None)])
def test_play_in_blocks_is_exact(monkeypatch, h, initial):
    u = np.cumsum(np.random.default_rng(3).normal(size=5000))
    whole = fx.play_structure(u, h, initial)
    monkeypatch.setattr(fx, "PLAY_BLOCK", 97)
    for a, b in zip(fx.play_structure(u, h, initial), whole):
        assert np.array_equal(a, b)
    assert np.array_equal(fx.play_operator(u, h, initial), fx.play_operator_reference(u, h, initial))


def test_noise_contrasts_in_blocks_are_exact(monkeypatch):
    rng = np.random.default_rng(4)
    t = sample_times(Sampling(samples=5000, dropouts=3), rng)
    y = np.sin(t / 7.0) + 0.1 * rng.normal(size=t.size)
    whole = difference_contrasts(t, y), level_of(t, y)
    monkeypatch.setattr(noise_module, "RUN_BLOCK", 101)
    c, valid = difference_contrasts(t, y)
    assert np.array_equal(c, whole[0][0]) and np.array_equal(valid, whole[0][1])
    assert level_of(t, y) == whole[1]


def test_noise_level_does_not_depend_on_the_time_unit():
    """Scaling time by 2**-400 (spacings near 1e-120 s, whose cubes underflow) or by 2**300
    leaves the unit-norm contrasts, and so the noise level, exactly as they are."""
    rng = np.random.default_rng(5)
    t = sample_times(Sampling(samples=3000, dropouts=2), rng)
    y = np.cos(t / 5.0) + 0.2 * rng.normal(size=t.size)
    level = noise_of_signal(t, y).rms
    assert level == pytest.approx(0.2, rel=0.1)
    assert noise_of_signal(t * 2.0 ** -400, y).rms == level
    assert noise_of_signal(t * 2.0 ** 300, y).rms == level


def test_periodogram_in_blocks(monkeypatch):
    rng = np.random.default_rng(6)
    theta = np.sort(rng.uniform(0, 6 * np.pi, 9000))
    r = 2.0 * np.cos(7.3 * theta - 1.0) + rng.normal(size=theta.size)
    whole = ls_periodogram(theta, r - r.mean(), 0.3, 40.0)
    assert np.array_equal(ls_periodogram(theta, r, 0.3, 40.0, offset=r.mean()).reduction, whole.reduction)
    monkeypatch.setattr(periodogram_module, "SPREAD_BLOCK", 1000)
    blocks = ls_periodogram(theta, r, 0.3, 40.0, offset=r.mean())
    assert np.array_equal(blocks.orders, whole.orders)
    assert np.allclose(blocks.reduction, whole.reduction, rtol=1e-9, atol=1e-9 * whole.reduction.max())


def test_periodogram_grid_is_bounded():
    """A million revolutions in 2000 samples would need a spreading grid of 2**28 points (2 GiB
    per array); the grid is capped and the spectrum still spans the record's resolution."""
    theta = np.linspace(0.0, 2 * np.pi * 1e6, 2000)
    r = np.random.default_rng(7).normal(size=theta.size)
    tracemalloc.start()
    pg = ls_periodogram(theta, r, 0.9e-6, 5.0)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert peak < 200e6
    assert pg.orders[0] < 2e-6 and np.all(np.isfinite(pg.reduction))


CSV_TEXT = ("\ufeff# bench log\n\ntime_s,output_angle_deg,carriage_x_um\r\n"
            + "".join(f"{i * 0.1:.3f},{i * 3.0:.4f},{np.sin(i / 9.0):.5f}\r\n" if i % 37 else
                      f"# comment at row {i}\r\n\r\n{i * 0.1:.3f},{i * 3.0:.4f},\r\n" for i in range(1, 400)))


def test_csv_in_blocks_equals_one_block(tmp_path, monkeypatch):
    path = tmp_path / "m.csv"
    path.write_bytes(CSV_TEXT.encode())
    header, whole = read_csv(path)
    assert header == ["time_s", "output_angle_deg", "carriage_x_um"] and whole[0].size == 399
    assert np.isnan(whole[2][36]) and whole[0][36] == pytest.approx(3.7)
    monkeypatch.setattr(measurement_module, "CSV_BLOCK_BYTES", 64)
    header_b, blocks = read_csv(path, select=lambda h: [2, 0])
    assert header_b == header
    assert np.array_equal(blocks[0], whole[2], equal_nan=True) and np.array_equal(blocks[1], whole[0])


def test_bad_value_in_a_late_block_names_its_line(tmp_path, monkeypatch):
    lines = ["time_s,output_angle_deg,carriage_x_um"] + [f"{i * 0.1:.3f},{i * 3.0:.4f},{np.sin(i):.5f}"
                                                         for i in range(300)]
    lines[250] = "24.900,747.0000,x7"
    (tmp_path / "m.csv").write_text("\n".join(lines) + "\n")
    (tmp_path / "m.toml").write_text('kind = "preload_trace"\n[model]\nteeth = [16, 48, 21, 112]\n')
    monkeypatch.setattr(measurement_module, "CSV_BLOCK_BYTES", 256)
    with pytest.raises(MeasurementError, match=r"m.csv: line 251, column carriage_x_um.*'x7'"):
        read_measurement(tmp_path / "m.csv")


def _json_numbers(report):
    out = {"noise": report["noise_rms"], "unexplained": report["unexplained"]}
    for stage in ("nominal", "declared", "extended"):
        out.update({f"{stage}.{k}": v for k, v in report["stages"][stage].items()})
    for i, e in enumerate(report["effects_added"]):
        out.update({f"{i}.{k}": v for k, v in e.items() if k not in ("evidence", "delta_bic")})
    return out


@pytest.mark.parametrize("truth", [
    PreloadTruth(harmonics=((2.0, 3.0, 40.0),), drift_per_kelvin=1.0),
    PreloadTruth(hysteresis_half_width=0.8),
], ids=["harmonic and drift", "hysteresis"])
def test_streamed_fit_equals_one_block(monkeypatch, truth):
    sim = simulate_preload_trace(truth, np.random.default_rng(11), PreloadSettings(sampling=Sampling(samples=6000)))
    whole = _json_numbers(diagnose(sim.measurement).to_json())
    _small_blocks(monkeypatch, 1024)
    streamed = _json_numbers(diagnose(sim.measurement).to_json())
    assert streamed.keys() == whole.keys()
    for key, value in whole.items():
        if isinstance(value, float):  # JSON values carry 6 significant digits: one unit in the last
            assert streamed[key] == pytest.approx(value, rel=2e-6, abs=1e-9), key
        else:
            assert streamed[key] == value, key


def _peak_of_fit(folder: Path, rows: int) -> tuple[int, int]:
    """Peak memory (bytes, above what the measurement holds) of reading and of diagnosing."""
    sim = simulate_preload_trace(PreloadTruth(harmonics=((2.0, 3.0, 40.0),), drift_per_kelvin=1.0),
                                 np.random.default_rng(12),
                                 PreloadSettings(sampling=Sampling(samples=rows, duration_s=3600.0), revolutions=3.0))
    csv = write_measurement(sim.measurement, folder, f"m{rows}")
    del sim
    tracemalloc.start()
    meas = read_measurement(csv)
    held, read_peak = tracemalloc.get_traced_memory()
    tracemalloc.reset_peak()
    diagnose(meas)
    fit_peak = tracemalloc.get_traced_memory()[1] - held
    tracemalloc.stop()
    return read_peak, fit_peak


def test_memory_grows_by_a_few_floats_per_row(tmp_path, monkeypatch):
    """Doubling a streamed record adds a few float64 per added row to the peak of reading it and of
    fitting it, whatever the design's width (the declared model alone has 11 columns; the fit
    used to hold (rows x columns) matrices, 150 floats per row at its peak, and the reader the
    file's text as Python strings, 45 per row).

    The periodogram's grid is capped low here: at these test sizes its fixed 2**19 points would
    otherwise hide the part of the peak that grows with the record.
    """
    _small_blocks(monkeypatch, 4096)
    monkeypatch.setattr(periodogram_module, "MIN_GRID_CAP", 4096)
    small, large = 40_000, 80_000
    read_small, fit_small = _peak_of_fit(tmp_path, small)
    read_large, fit_large = _peak_of_fit(tmp_path, large)
    per_row_read = (read_large - read_small) / (large - small) / 8
    per_row_fit = (fit_large - fit_small) / (large - small) / 8
    # reading keeps 4 columns (time, angle, carriage, temperature) and the checks' temporaries;
    # the fit a dozen arrays of the record's length at most (fits, residuals, play, held-out parts)
    assert per_row_read < 8, per_row_read
    assert per_row_fit < 14, per_row_fit


def test_a_long_torque_record_is_searched_on_every_kth_sample_and_fitted_on_all():
    """45,000 rows: the search runs on one sample in 3 (15,000, at most TORQUE_SEARCH_SAMPLES);
    the friction it finds is fitted to every sample, with the residual at the injected noise."""
    from geargen.fit.selection import TORQUE_SEARCH_SAMPLES
    from geargen.fit.simulate import TorqueSettings, TorqueTruth, simulate_torque_deflection
    sim = simulate_torque_deflection(TorqueTruth(hysteresis_half_width=1.0), np.random.default_rng(13),
                                     TorqueSettings(sampling=Sampling(samples=45_000, duration_s=2400.0), cycles=4))
    assert 2 * TORQUE_SEARCH_SAMPLES < 45_000 <= 3 * TORQUE_SEARCH_SAMPLES
    dg = diagnose(sim.measurement)
    report = dg.to_json()
    assert any("one sample in 3 (15000 of 45000)" in n for n in dg.measurement.notes)
    assert dg.extended.residual.size == 45_000 and not report["unexplained"]
    (e,) = report["effects_added"]
    assert e["effect"] == "hysteresis" and e["half_width"] == pytest.approx(1.0, rel=0.05)
    # the fit to all 45,000 samples: its residual is the injected noise (0.1 Nm) to 5 %
    assert report["stages"]["extended"]["rms"] == pytest.approx(sim.true_noise_rms, rel=0.05)
