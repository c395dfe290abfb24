"""Error budgets, the exact re-solved carriage travel, Monte Carlo statistics and sensitivities."""

from __future__ import annotations

import math
import struct
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import norm

from geargen.cli import main
from geargen.core.synthesis import appendix_carriage_travel, solve_loop, synthesize_centres
from geargen.core.tolerance import (PERCENTILES, appendix_error_budget, combine_monte_carlo, exact_error_budget,
                                    exact_gradients, geometry_sensitivities, monte_carlo, tolerance_sensitivities)
from geargen.design.assembly import load_design
from geargen.core.accuracy import error_budget_inputs
from geargen.design.synthesis import GearErrors, synthesis_inputs

ROBOT = Path(__file__).resolve().parents[2] / "assemblies" / "robot_joint.toml"


@pytest.fixture(scope="module")
def robot():
    d = load_design(ROBOT)
    s = synthesize_centres(synthesis_inputs(d)).check()
    return s, error_budget_inputs(d)


# --- exact geometry ------------------------------------------------------------------------------

def test_zero_errors_leave_the_carriage_at_the_synthesised_position(robot):
    s, _ = robot
    sol = solve_loop(s, offsets=np.zeros((3, 6, 2)), tooth_errors=np.zeros((3, 8))).check()
    assert np.allclose(sol.carriage_x, s.input_x, rtol=0, atol=1e-10)


def test_exact_gradients_match_the_geometry(robot):
    s, _ = robot
    og, tg = exact_gradients(s)
    # moving the input's pitch circle by +d along x moves the carriage by exactly -d; along y, nothing
    assert og[0] == pytest.approx([-1.0, 0.0], abs=1e-6)
    # mirror symmetry: paths A and B respond in mirror image
    assert og[1] == pytest.approx(og[2] * [1, -1], abs=1e-6)
    assert og[3] == pytest.approx(og[4] * [1, -1], abs=1e-6)
    assert tg[0::2] == pytest.approx(-tg[1::2], abs=1e-6)
    # the output's y shift turns the drive, it does not move the carriage (appendix-notes §4)
    assert og[5, 1] == pytest.approx(0.0, abs=1e-6)


def test_exact_budget_confirms_the_appendix_within_its_simplifications(robot):
    s, errors = robot
    b = appendix_error_budget(s, errors)
    e = exact_error_budget(s, errors)
    assert e.success
    # re-solving without linearisation changes a gear's travel by less than 1e-3 of it
    assert e.dx1_resolved == pytest.approx(e.dx1_linear, rel=1e-3)
    assert e.travel_resolved == pytest.approx(e.dx1_sum, rel=1e-3)
    # and the Appendix's simplified factors (appendix-notes §5) are within 3 % per gear here
    # (the tooth-to-tooth errors of gears 1 and 2 move the carriage by 0.94, not 1, per unit TIR)
    assert e.dx1_linear == pytest.approx(b.dx1, rel=0.03)
    assert e.worst_low < 0 < e.worst_high


def test_exact_travel_of_a_single_error_is_half_the_appendix_per_cluster(robot):
    """One cluster's gear-3 tangential error moves the carriage half as far as the Appendix's
    factor says: the Appendix charges both clusters' errors to one gear (appendix-notes §4)."""
    s, _ = robot
    e = 1e-3  # mm
    tooth = np.zeros((2, 8))
    tooth[:, 4] = [e, -e]  # cluster_small_a contact
    sol = solve_loop(s, tooth_errors=tooth).check()
    travel = sol.carriage_x[0] - sol.carriage_x[1]
    r2, r3 = s.inputs.reference_radius(2), s.inputs.reference_radius(3)
    assert abs(travel) == pytest.approx(2 * e * r2 / r3 / 2, rel=0.07)


def test_minimum_backlash_travel_appendix_and_exact(robot):
    s, _ = robot
    inp = s.inputs
    dx_sheet = appendix_carriage_travel(s, inp.circumferential_backlash_min_mesh1, inp.circumferential_backlash_min_mesh2)
    assert dx_sheet == pytest.approx(s.min_backlash_dx1, rel=1e-12)
    exact = solve_loop(s, inp.circumferential_backlash_min_mesh1, inp.circumferential_backlash_min_mesh2).check().carriage_x[0] - s.input_x
    # the Appendix holds B fixed while C1 grows; the growing C1 adds backlash, so less travel is needed
    assert 0 < exact < dx_sheet
    assert exact / 25.4 == pytest.approx(0.00412, abs=1e-5)


# --- Monte Carlo ---------------------------------------------------------------------------------

def test_monte_carlo_is_reproducible_from_its_seed(robot):
    s, errors = robot
    a = monte_carlo(s, errors, 2000, 11)
    b = monte_carlo(s, errors, 2000, np.random.default_rng(11))
    c = monte_carlo(s, errors, 2000, 12)
    assert np.array_equal(a.travel, b.travel) and not np.array_equal(a.travel, c.travel)


def test_chunks_combine_into_the_statistics_of_all_their_samples(robot):
    s, errors = robot
    seeds = np.random.SeedSequence(5).spawn(3)
    parts = [monte_carlo(s, errors, n, np.random.default_rng(q), spring_rate=2.0, preload=10.0)
             for n, q in zip((700, 700, 300), seeds)]
    whole = combine_monte_carlo(parts)
    travel = np.concatenate([p.travel for p in parts])
    assert whole.success and whole.samples == 1700 and np.array_equal(whole.travel, travel)
    assert whole.percentiles == dict(zip(PERCENTILES, np.percentile(travel, PERCENTILES)))
    assert whole.force_percentiles[50.0] == 10.0 + 2.0 * np.median(travel)
    assert (whole.bound_low, whole.bound_high) == (parts[0].bound_low, parts[0].bound_high)
    assert whole.minimum >= whole.bound_low and whole.maximum <= whole.bound_high
    with pytest.raises(ValueError):
        combine_monte_carlo([])


@pytest.mark.parametrize("model, shape", [("appendix", "physical"), ("appendix", "uniform"), ("appendix", "normal3"),
                                          ("exact", "physical")])
def test_monte_carlo_never_exceeds_the_worst_case_sum(robot, model, shape):
    s, errors = robot
    n = 1_000_000 if model == "appendix" else 100_000
    mc = monte_carlo(s, errors, n, 3, model=model, error_shape=shape)
    assert mc.success
    b = appendix_error_budget(s, errors)
    if model == "appendix":
        assert mc.worst_case_sum == pytest.approx(b.dx1_sum, rel=1e-12)
    # the bounds are the worst states re-solved exactly; the other samples' nonlinearity is ~1e-4 of the travel
    slack = 1e-3 * mc.worst_case_sum
    assert mc.bound_low - slack <= mc.minimum and mc.maximum <= mc.bound_high + slack
    assert mc.maximum - mc.minimum <= mc.worst_case_sum + slack
    pct = list(mc.percentiles.values())
    assert pct == sorted(pct) and mc.spread_99_73 < mc.worst_case_sum


@pytest.mark.parametrize("shape, sigma_per_range", [
    ("uniform", 1 / (2 * math.sqrt(3))),
    # normal with the range as +-3 sigma, cut at +-3 sigma: sigma of the cut normal over the range
    ("normal3", math.sqrt(1 - 6 * norm.pdf(3) / (2 * norm.cdf(3) - 1)) / 6),
])
def test_monte_carlo_converges_to_the_rss_estimate(robot, shape, sigma_per_range):
    """Independent errors add in variance, so the simulated spread tends to the RSS of the ranges:
    the standard deviation to sigma_per_range * RSS exactly (its sampling error shrinks like
    1/sqrt(n)); for ranges taken as +-3 sigma the central 99.73 % tends to RSS itself, short
    by the few per cent the cut tails take away."""
    s, errors = robot
    rss = appendix_error_budget(s, errors).dx1_rss
    err = {}
    for n in (1_000, 1_000_000):
        dev = [monte_carlo(s, errors, n, seed, model="appendix", error_shape=shape).std / (sigma_per_range * rss) - 1
               for seed in range(3 if n > 1000 else 30)]
        err[n] = float(np.sqrt(np.mean(np.square(dev))))
    assert err[1_000_000] < 0.004
    assert err[1_000_000] < err[1_000] / 5  # ~ sqrt(1000) less scatter
    if shape == "normal3":
        mc = monte_carlo(s, errors, 1_000_000, 5, model="appendix", error_shape=shape)
        assert 0.95 * rss < mc.spread_99_73 < rss


def test_physical_errors_spread_less_than_the_appendix_sum_and_near_its_rss(robot):
    s, errors = robot
    b = appendix_error_budget(s, errors)
    mc = monte_carlo(s, errors, 100_000, 1994, model="exact")
    assert mc.spread_99_73 == pytest.approx(b.dx1_rss, rel=0.05)
    assert mc.spread_99_73 < 0.6 * b.dx1_sum


def test_backlash_tolerance_adds_the_minimum_backlash_travel(robot):
    s, errors = robot
    for model in ("appendix", "exact"):
        plain = monte_carlo(s, errors, 50_000, 2, model=model)
        wide = monte_carlo(s, errors, 50_000, 2, model=model, include_backlash_tolerance=True)
        assert wide.bound_high - plain.bound_high == pytest.approx(
            s.min_backlash_dx1 if model == "appendix" else 0.00412123 * 25.4, rel=1e-4)
        assert wide.mean > plain.mean  # thicker teeth on average hold the carriage further out
        assert wide.maximum <= wide.bound_high + 1e-3 * wide.worst_case_sum


def test_preload_force_follows_the_spring(robot):
    s, errors = robot
    mc = monte_carlo(s, errors, 20_000, 4, model="appendix", spring_rate=5.66, preload=64.8)
    assert np.allclose(mc.force, 64.8 + 5.66 * mc.travel)
    assert list(mc.force_percentiles) == list(PERCENTILES)
    assert mc.force_percentiles[50.0] == pytest.approx(64.8 + 5.66 * mc.percentiles[50.0])
    with pytest.raises(ValueError):
        monte_carlo(s, errors, 100, 4, spring_rate=-1.0)
    with pytest.raises(ValueError):
        monte_carlo(s, errors, 100, 4, model="exact", error_shape="uniform")


def test_zero_errors_give_zero_travel(robot):
    s, _ = robot
    zero = (GearErrors(),) * 4
    for model in ("appendix", "exact"):
        mc = monte_carlo(s, zero, 1000, 0, model=model)
        assert np.abs(mc.travel).max() < 1e-9


# --- sensitivities -------------------------------------------------------------------------------

def test_geometry_sensitivities_agree_with_a_larger_step(robot):
    s, _ = robot
    t = geometry_sensitivities(s)
    inp = s.inputs
    from dataclasses import replace

    h = 1e-3  # mm
    up = synthesize_centres(replace(inp, centre_distance_mesh1=inp.centre_distance_mesh1 + h), s.increments).check()
    dn = synthesize_centres(replace(inp, centre_distance_mesh1=inp.centre_distance_mesh1 - h), s.increments).check()
    assert t.value("centre_distance_mesh1", "A1") == pytest.approx((up.A1 - dn.A1) / (2 * h), rel=1e-4)
    assert t.value("centre_distance_mesh1", "input_x") == pytest.approx((up.input_x - dn.input_x) / (2 * h), rel=1e-4)
    # the Appendix's step 3 is linear in the backlash change: d(Δx1)/d(B min) = -d(Δx1)/d(B max) holds to first order
    assert t.value("circumferential_backlash_min_mesh1", "dx1_min_backlash") < 0 < t.value("circumferential_backlash_max_mesh1", "dx1_min_backlash")
    # the minimum backlash does not move the synthesised position
    assert t.value("circumferential_backlash_min_mesh2", "A1") == 0.0 and t.value("circumferential_backlash_min_mesh2", "input_x") == 0.0


def test_tolerance_sensitivities_rank_the_tolerances(robot):
    s, errors = robot
    b = appendix_error_budget(s, errors)
    t = tolerance_sensitivities(b, exact_error_budget(s, errors))
    assert t.value("cluster_small.pitch_line_eccentricity_tir", "dx1_sum") == pytest.approx(b.factors[2])
    assert t.value("input.bearing_eccentricity_tir", "dx1_exact_worst") == pytest.approx(1.0, abs=1e-6)
    # Sum = sum(factor * TIR): the sensitivities reproduce it
    total = sum(t.value(f"{r}.{k}", "dx1_sum") * getattr(e, k)
                for r, e in zip(("input", "cluster_large", "cluster_small", "output"), errors)
                for k in ("bearing_eccentricity_tir", "pitch_line_eccentricity_tir", "tooth_to_tooth_tir"))
    assert total == pytest.approx(b.dx1_sum)
    # cluster_small errors cost the most carriage travel per unit TIR (r2/r3 = 2.29)
    col = t.values[:, t.outputs.index("dx1_exact_worst")]
    assert t.inputs[int(np.argmax(col))].startswith("cluster_small") or t.inputs[int(np.argmax(col))].startswith("output")


# --- the command ---------------------------------------------------------------------------------

def test_command_runs_monte_carlo_with_histogram_and_json(tmp_path, capsys):
    png, out = tmp_path / "hist.png", tmp_path / "synth.json"
    assert main(["synth", str(ROBOT), "--samples", "20000", "--seed", "3", "--spring-rate-n-per-mm", "5.66",
                 "--preload-n", "64.8", "--histogram", str(png), "--sensitivity", "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "Carriage-travel Monte Carlo ([monte_carlo]): 20000 samples, model 'exact'" in text and "Which tolerance to buy" in text
    head = png.read_bytes()[:24]
    assert head[:8] == b"\x89PNG\r\n\x1a\n" and struct.unpack(">II", head[16:24])[0] > 400
    import json

    data = json.loads(out.read_text())
    mc = data["monte_carlo"]
    assert mc["samples"] == 20000 and mc["seed"] == 3 and mc["model"] == "exact"
    assert mc["travel_bound_low"] <= mc["travel_min"] <= mc["travel_max"] <= mc["travel_bound_high"]
    assert set(mc["force_percentiles_N"]) == {"p0.135", "p2.5", "p50", "p97.5", "p99.865"}
    assert "cluster_small.tooth_to_tooth_tir" in data["sensitivities"]["tolerance"]["values"]
    assert main(["synth", str(ROBOT), "--samples", "5"]) == 2  # out of range, named
    assert "--samples" in capsys.readouterr().err
