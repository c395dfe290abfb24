"""Issue 31: a split pinion's centre distance outside the range its teeth can be placed at is
refused naming layout.centre_distance_<unit>, the cause and the range in the file's unit, with a
distance that works; near the tip circles the check runs without numpy warnings and names every
failure's mesh. The bounds by hand from the involute function (assemblies/split_pinion_inch.toml:
18 and 90 teeth, 20 DP, 20 deg, standard 2.7 in, mid-range backlash 0.00225 in)."""

import math
import re
import warnings
from pathlib import Path

import pytest
from scipy.optimize import brentq

from geargen.checks.verdict import check_design
from geargen.cli import main
from geargen.design.assembly import load_design

DESIGN = Path(__file__).resolve().parents[1] / "assemblies" / "split_pinion_inch.toml"


def variant(tmp_path, centre_in: float, rule: str = "mid") -> Path:
    text = DESIGN.read_text()
    assert "centre_distance_in = 2.7 " in text and 'model_backlash = "mid"' in text
    path = tmp_path / "split_pinion_inch.toml"
    path.write_text(text.replace("centre_distance_in = 2.7 ", f"centre_distance_in = {centre_in} ")
                    .replace('model_backlash = "mid"', f'model_backlash = "{rule}"'))
    return path


def refusal(path, capsys) -> str:
    assert main(["check", str(path)]) == 2
    return capsys.readouterr().err


def inv(a):
    return math.tan(a) - a


def hand_bounds() -> tuple[float, float]:
    """Backlash B = T + 2 C_std (inv a_w - inv a) with cos a_w = C_std cos a / C (inches): the
    largest centre distance has the unthinned teeth (T = 0) at the modelled 0.00225 in, the smallest
    has the pinion thinned by a quarter pitch (T = pi / 20 / 4)."""
    c_std, a, target = 2.7, math.radians(20), 0.00225

    def centre(deficit):
        aw = brentq(lambda x: inv(x) - inv(a) - (target - deficit) / (2 * c_std), 1e-6, 1.5)
        return c_std * math.cos(a) / math.cos(aw)
    return centre(math.pi / 20 / 4), centre(0.0)


def test_below_standard_names_the_key_in_inches_and_a_fix_that_works(tmp_path, capsys):
    lo, hi = hand_bounds()
    assert (lo, hi) == pytest.approx((2.64448, 2.70308), abs=5e-6)
    err = refusal(variant(tmp_path, 2.6), capsys)
    assert "layout.centre_distance_in: 2.6 in is below the range" in err and "interfere" in err
    assert f"[{lo:.6g}, {hi:.6g}] in" in err and " mm" not in err
    fix = float(re.search(r"e\.g\. layout\.centre_distance_in = ([\d.]+)", err)[1])
    assert fix == 2.7
    result, _ = check_design(load_design(variant(tmp_path, fix)))
    assert result.ok
    # just inside either bound the drive is placed (the check then judges its teeth)
    for inside in (lo + 1e-5, hi - 1e-5):
        check_design(load_design(variant(tmp_path, round(inside, 5))), tolerances=False)


def test_beyond_the_tip_circles_names_the_cause_not_as_designed(tmp_path, capsys):
    err = refusal(variant(tmp_path, 2.9), capsys)
    assert "layout.centre_distance_in: 2.9 in is above the range" in err and "as_designed" not in err
    assert "already have more than the modelled 0.00225 in" in err
    # the teeth as designed: the tip circles' sum (18 + 2) / 40 + (90 + 2) / 40 = 2.8 in bounds it, the
    # base circles' 2.7 cos 20 deg = 2.53717 in from below
    err = refusal(variant(tmp_path, 2.9, "as_designed"), capsys)
    assert "beyond the tip circles' sum 2.8 in" in err and "[2.53717, 2.8] in" in err


def test_near_the_tip_circles_no_numpy_warning_and_every_failure_names_its_mesh(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        result, _ = check_design(load_design(variant(tmp_path, 2.799, "as_designed")), tolerances=False)
    assert not result.ok
    assert all(f.mesh for f in result.all_failures), [f.kind for f in result.all_failures if not f.mesh]
    assert {"low_contact_ratio", "allowance_range_outside_design"} <= {f.kind for f in result.all_failures}
