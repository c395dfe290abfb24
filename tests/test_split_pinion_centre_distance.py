"""Issue 31: a split pinion's centre distance outside the range its teeth can be placed at is
refused naming layout.centre_distance_<unit>, the cause and the range in the file's unit, with a
distance that works; near the tip circles the check runs without numpy warnings and names every
failure's mesh. The bounds by hand from the involute function (assemblies/split_pinion_inch.toml:
18 and 90 teeth, 20 DP, 20 deg, standard 2.7 in, backlash range 0.0015 to 0.003 in)."""

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


def variant(tmp_path, centre_in: float, rule: str = "mid_tolerance") -> Path:
    text = DESIGN.read_text()
    assert "centre_distance_in = 2.7 " in text and 'model_tooth_thickness = "mid_tolerance"' in text
    path = tmp_path / "split_pinion_inch.toml"
    path.write_text(text.replace("centre_distance_in = 2.7 ", f"centre_distance_in = {centre_in} ")
                    .replace('model_tooth_thickness = "mid_tolerance"', f'model_tooth_thickness = "{rule}"'))
    return path


def refusal(path, capsys) -> str:
    assert main(["check", str(path)]) == 2
    return capsys.readouterr().err


def inv(a):
    return math.tan(a) - a


def hand_bounds() -> tuple[float, float]:
    """Backlash of the unthinned teeth B_0 = 2 C_std (inv a_w - inv a) with cos a_w = C_std cos a / C
    (inches). Each mesh's allowance has the thickest teeth (summed thinning B_min - B_0, half on the
    pinion, half on the shared output) give the range's minimum and the thinnest (B_max - B_0) its
    maximum, so the allowances exist from where the thinnest pinion is pointed up to where the
    thickest teeth are unthinned (B_0 = B_min). The pinion thinned by T (unshifted, r = 0.45 in, tip
    r_a = 0.5 in) has the tip land 2 r_a ((p / 2 - T) / (2 r) + inv a - inv a_a), cos a_a = r_b / r_a;
    pointed means below 0.001 m_n (the least the profile is built with)."""
    c_std, a, b_min, b_max = 2.7, math.radians(20), 0.0015, 0.003
    p, r, r_a, m = math.pi / 20, 0.45, 0.5, 0.05
    a_a = math.acos(r * math.cos(a) / r_a)
    pointed = p / 2 - 2 * r * (0.001 * m / (2 * r_a) - inv(a) + inv(a_a))

    def centre(b0):
        aw = brentq(lambda x: inv(x) - inv(a) - b0 / (2 * c_std), 1e-6, 1.5)
        return c_std * math.cos(a) / math.cos(aw)
    return centre(b_max - 2 * pointed), centre(b_min)


def test_below_standard_names_the_key_in_inches_and_a_fix_that_works(tmp_path, capsys):
    lo, hi = hand_bounds()
    assert (lo, hi) == pytest.approx((2.60548, 2.70205), abs=5e-6)
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
    assert "already have more backlash than the range's minimum" in err
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
