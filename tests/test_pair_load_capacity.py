"""``geargen pair --torque ...``: the contract's options (../shared/contracts/load-capacity.md), the
exit status, inch units, refusals that name the option."""

import json

import pytest

from geargen.cli import main

MM_PER_IN = 25.4
NM_PER_INLBF = 0.1129848290276167  # 1 lbf = 4.4482216152605 N, 1 in = 0.0254 m

# ISO/TR 6336-30:2017 example 1 (see tests/core/test_load_capacity.py)
METRIC = ["--teeth", "17", "103", "--module", "8", "--helix-angle", "15.8", "--profile-shift", "0.145", "0",
          "--face-width", "100", "--centre-distance", "500", "--dedendum-coefficient", "1.4",
          "--rack-tip-radius", "0.39"]
RATING = ["--speed", "360", "--life", "50000", "--material", "case_carburised", "--quality", "MQ",
          "--face-load-factor", "1.16", "--accuracy-grade", "5", "--roughness", "1", "--viscosity", "320",
          "--tip-relief", "70"]


def run(capsys, *options):
    code = main(["pair", *options, "--json", "-"])
    out, err = capsys.readouterr()
    return code, (json.loads(out) if out else None), err


def test_below_the_minimum_safety_the_pair_fails_with_exit_status_1(capsys):
    # S_H of the pinion is 1.0285 (published): a minimum of 1.05 fails it, 1.0 passes
    code, data, table = run(capsys, *METRIC, "--torque", "9000", *RATING, "--minimum-safety", "1.05", "1.4")
    assert code == 1 and data["load_capacity"]["ok"] is False
    assert data["load_capacity"]["S_Hmin"] == 1.05 and data["load_capacity"]["S_Fmin"] == 1.4
    assert "FAILS: S_H of gear 1 = 1.0285 < 1.05" in table
    code, data, table = run(capsys, *METRIC, "--torque", "9000", *RATING, "--minimum-safety", "1.0", "1.4")
    assert code == 0 and "both gears reach the minimum safety factors" in table


def test_default_minimum_safety_factors_are_1_and_1_4(capsys):
    _, data, _ = run(capsys, *METRIC, "--torque", "9000", *RATING)
    assert (data["load_capacity"]["S_Hmin"], data["load_capacity"]["S_Fmin"]) == (1.0, 1.4)


def test_an_inch_pair_takes_in_lbf_and_prints_inches(capsys):
    # the same pair written in inches (P = 25.4/8 per inch, lengths / 25.4) and its torque in in lbf rates
    # the same: F_t, S_H, S_F to 1e-9 (the unit conversions only)
    _, metric, _ = run(capsys, *METRIC, "--torque", "9000", *RATING)
    inch = ["--teeth", "17", "103", "--diametral-pitch", str(MM_PER_IN / 8), "--helix-angle", "15.8",
            "--profile-shift", "0.145", "0", "--face-width", str(100 / MM_PER_IN),
            "--centre-distance", str(500 / MM_PER_IN), "--dedendum-coefficient", "1.4", "--rack-tip-radius", "0.39"]
    code, imperial, table = run(capsys, *inch, "--torque", str(9000 / NM_PER_INLBF), *RATING)
    a, b = metric["load_capacity"], imperial["load_capacity"]
    for key in ("F_t", "sigma_H0"):
        assert b[key] == pytest.approx(a[key], rel=1e-9)
    for key in ("S_H", "S_F"):
        assert b[key] == pytest.approx(a[key], rel=1e-9)
    assert b["torque_unit"] == "in lbf" and b["F_t"] == pytest.approx(127352.4, rel=1e-6)
    assert b["face_width_for_minimum_safety"]["unit"] == "in"
    assert b["face_width_for_minimum_safety"]["pitting"] == pytest.approx(
        a["face_width_for_minimum_safety"]["pitting"] / MM_PER_IN, rel=1e-6)  # the solve's own tolerance
    assert f"b = {100 / MM_PER_IN:.6f} in" in table and "lbf)" in table


@pytest.mark.parametrize("extra, flag", [
    (["--speed", "300"], "--speed"),
    (["--material", "nitrided"], "--material"),
    (["--minimum-safety", "1", "1.5"], "--minimum-safety"),
    (["--tip-relief", "20"], "--tip-relief"),
])
def test_rating_options_without_a_torque_are_refused_by_name(capsys, extra, flag):
    code, _, err = run(capsys, *METRIC, *extra)
    assert code == 2 and f"geargen pair: error: {flag}: " in err and "--torque" in err


@pytest.mark.parametrize("drop, flag", [("--speed", "--speed"), ("--viscosity", "--viscosity"),
                                        ("--accuracy-grade", "--accuracy-grade")])
def test_a_missing_rating_input_is_named(capsys, drop, flag):
    options = list(RATING)
    i = options.index(drop)
    del options[i:i + 2]
    code, _, err = run(capsys, *METRIC, "--torque", "9000", *options)
    assert code == 2 and f"error: {flag}: missing" in err


def test_a_hardness_outside_the_iso6336_5_line_is_refused_with_its_range(capsys):
    options = [o if o != "case_carburised" else "through_hardened" for o in RATING]
    code, _, err = run(capsys, *METRIC, "--torque", "9000", *options, "--hardness", "420")
    assert code == 2 and "--hardness: gear 1: 420 HV is outside the range" in err and "200..360 HV" in err
    code, _, err = run(capsys, *METRIC, "--torque", "9000", *options)
    assert code == 2 and "--hardness: gear 1: through_hardened needs its surface hardness" in err


def test_internal_pair_is_rated_with_the_ring_as_gear_2(capsys):
    code, data, table = run(capsys, "--internal", "--teeth", "18", "60", "--module", "2", "--profile-shift", "0", "0",
                            "--face-width", "20", "--torque", "40", "--speed", "600", "--life", "5000",
                            "--material", "through_hardened", "--hardness", "300", "280", "--accuracy-grade", "6",
                            "--roughness", "0.8", "--viscosity", "100", "--face-load-factor", "1.2")
    block = data["load_capacity"]
    assert block["u"] == pytest.approx(-60 / 18, rel=1e-15) and block["Z_BD"][1] == 1.0
    assert "internal gear root: ISO 6336-3's approximation by a rack" in " ".join(block["notes"])
    assert code == (0 if block["ok"] else 1) and "Load capacity: ISO 6336-2:2019" in table
