"""The whole diagnosis on synthetic bench data, several seeds and noise levels per effect.

For each library effect: data with that effect undeclared -> that effect, and only it, is added,
its parameters recovered (orders to 0.01, magnitudes to 10 %), and the extended residual is within
20 % of the noise actually injected. Data with no undeclared effect -> nothing added. Data with
an effect outside the library -> ``unexplained`` and nothing added. The cases live in fit_cases.py, which also
prints their before/after table.
"""

import math

import pytest

from fit_cases import CASES, run_case
from geargen.fit.effects import LIBRARY
from geargen.fit.selection import SelectionRule, bic_gain


@pytest.mark.parametrize("case", CASES, ids=[f"{c.name} seed {c.seed}" for c in CASES])
def test_case(case):
    result = run_case(case)
    assert not result["problems"], "; ".join(result["problems"])


def test_every_library_effect_has_a_case():
    covered = {e["effect"] for c in CASES if c.expect == "effects" for e in _expected(c)}
    assert covered == set(LIBRARY)


def _expected(case):
    from fit_cases import simulate
    return simulate(case).expected


def test_bic_gain_threshold_arithmetic():
    # 8192 samples: one parameter must cut the sum of squares by more than (10 + ln 8192) / 8192
    n = 8192
    need = math.exp(-(SelectionRule().bic_threshold + math.log(n)) / n)
    assert bic_gain(1.0, need * 1.0001, n, 1) < 10 < bic_gain(1.0, need * 0.9999, n, 1)


def test_json_has_the_contract_keys():
    result = run_case(next(c for c in CASES if c.name == "preload/harmonic 2 x output"))
    j = result["report"]
    contract = ["kind", "samples", "units", "noise_rms", "stages", "effects_added", "unexplained"]
    assert [k for k in j if k in contract] == contract
    assert set(j) - set(contract) == {"noise_channels", "noise_ar1", "rejected_samples", "ambiguous", "budget"}
    assert j["noise_channels"]["carriage_x_um"] == pytest.approx(result["sim"].true_noise_rms, rel=0.1)
    assert set(j["stages"]) == {"nominal", "declared", "extended"}
    for stage in j["stages"].values():
        assert set(stage) == {"rms", "max_abs"}
    e = j["effects_added"][0]
    assert {"effect", "order", "amplitude", "phase_deg", "shaft", "multiple", "evidence"} <= set(e)
    assert (e["shaft"], e["multiple"]) == ("output", 2)
    assert e["phase_deg"] == pytest.approx(40.0, abs=2.0)


def test_nominal_stage_is_null_without_nominal_values():
    result = run_case(next(c for c in CASES if c.name == "torque/none, no nominal values"))
    assert result["report"]["stages"]["nominal"] is None
    assert result["report"]["stages"]["declared"]["rms"] > 0
