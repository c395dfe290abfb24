"""Default hardware: a file with only gears and a synthesis gets every other part, each value
sized by a stated rule and checked here against the rule worked by hand (Lewis, the spring
formulas, the bearing tables), and the stiffness model reads what was chosen."""

import math
import tomllib
from pathlib import Path

import pytest

from geargen.design.assembly import default_hardware, load_design
from geargen.design.catalogue import INCH_BEARINGS, METRIC_BEARINGS, standard_bearing
from geargen.drives.dual_pinion.defaults import PRELOAD_FRACTION, STEEL_BENDING_ALLOWABLE_MPA, lewis_form_factor
from geargen.errors import DesignError
from geargen.drives.resolver import resolve
from geargen.model.analysis import stiffness

ROOT = Path(__file__).resolve().parents[2]
GEARS_ONLY = ROOT / "tests/data/metric_dual_pinion.toml"


def _defaults(path: Path) -> dict:
    return {d.key: d.value for d in load_design(path).defaulted}


def test_the_bearing_tables_are_the_standard_series():
    # ISO 15 dimension series 18: D grows with d, and the listed 6805 is 25 x 37 x 7
    assert (25, 37, 7, "6805ZZ") in METRIC_BEARINGS
    assert all(a[0] < b[0] and a[1] < b[1] for a, b in zip(METRIC_BEARINGS, METRIC_BEARINGS[1:]))
    assert all(a[0] < b[0] and a[1] < b[1] for a, b in zip(INCH_BEARINGS, INCH_BEARINGS[1:]))
    # the largest bore not above the limit, in the design's unit
    assert standard_bearing(9.99, "mm")[:3] == (9, 17, 5)
    assert standard_bearing(10.0, "mm")[:3] == (10, 19, 5)
    assert standard_bearing(2.9, "mm") is None
    d, od, w, name = standard_bearing(0.5 * 25.4 + 1e-9, "in")
    assert (d, od, name) == (pytest.approx(12.7), pytest.approx(28.575), "R8ZZ")


def test_lewis_form_factor_is_the_table_between_its_counts():
    assert lewis_form_factor(18) == pytest.approx(0.309)
    assert lewis_form_factor(100) == pytest.approx(0.447)
    y54 = lewis_form_factor(54)
    assert 0.409 < y54 < 0.422  # between 50 and 60 teeth
    with pytest.raises(DesignError, match="Lewis table"):
        lewis_form_factor(10)


def test_a_gears_only_file_gets_bores_from_the_rim_and_reference_diameter_rules():
    got = _defaults(GEARS_ONLY)
    # input 18 T m1: a third of d = 6 mm, rim rule 15.5 - 5 = 10.5 -> 6 (686)
    assert got["gears.input.bore_diameter_mm"] == 6
    # cluster: 54 T m1 (d/3 = 18) and 20 T m1.5 (d/3 = 10, rim 26.25 - 7.5): the smaller, 10 (6800)
    assert got["gears.cluster_large.bore_diameter_mm"] == got["gears.cluster_small.bore_diameter_mm"] == 10
    assert (got["parts.cluster_bearing_outer_diameter_mm"], got["parts.cluster_bearing_width_mm"]) == (19, 5)
    # output 100 T m1.5: d/3 = 50 -> 6810, 50 x 65 x 7
    assert got["gears.output.bore_diameter_mm"] == 50
    assert got["parts.output_bearing_outer_diameter_mm"] == 65


def test_the_rated_torque_is_the_weaker_mesh_by_lewis_by_hand():
    data = tomllib.loads(GEARS_ONLY.read_text())
    face = data["gear_defaults"]["face_width_mm"]
    s = STEEL_BENDING_ALLOWABLE_MPA
    share = 0.5 + PRELOAD_FRACTION  # the loaded path: half the load plus the preload
    # mesh 2: 20 T (Y 0.322) drives 100 T, m 1.5, at the output's 75 mm radius
    mesh2 = s * face * 1.5 * 0.322 * 75.0 / share
    # mesh 1: 18 T (Y 0.309) drives 54 T, m 1, at the large gear's 27 mm x the 5:1 of mesh 2
    mesh1 = s * face * 1.0 * 0.309 * 27.0 * 5.0 / share
    rated = min(mesh1, mesh2) * 1e-3
    got = _defaults(GEARS_ONLY)["preload.max_output_torque_Nm"]
    assert got == float(f"{rated:.2g}")  # written to two figures
    assert mesh2 < mesh1  # mesh 2 decides here


def test_the_default_springs_set_the_preload_and_stay_below_their_stress_closed_solid():
    design = load_design(GEARS_ONLY)
    got = {d.key: d.value for d in design.defaulted}
    d, D, na = got["springs.wire_diameter_mm"], got["springs.mean_coil_diameter_mm"], got["springs.active_coils"]
    rate = 79.3e3 * d ** 4 / (8 * D ** 3 * na)  # G d^4 / (8 D^3 Na), N/mm
    force = 2 * rate * (got["springs.free_length_mm"] - got["springs.installed_length_mm"])
    # the carriage force 2 lambda P, lambda = 1 / (R2 r_b,large): P = 0.6 of the rated torque
    r_b = 27.0 * math.cos(math.radians(20))
    preload = force / (2 / (5.0 * r_b))
    # (the lengths are written to 1 nm)
    assert preload == pytest.approx(PRELOAD_FRACTION * got["preload.max_output_torque_Nm"] * 1e3, rel=1e-6)
    summary = stiffness(design, resolve(design))[0]
    assert summary.drive.preload == pytest.approx(preload, rel=1e-9)
    assert summary.preload_source == "springs (installed length)"
    # closed solid the stress stays below the allowable the defaults wrote (0.45 of 2211 / d^0.145)
    assert summary.spring.solid_safe and summary.spring.allowable_shear_stress == pytest.approx(
        0.45 * 2211 / d ** 0.145, abs=0.05)
    # the blades: 3 E t x / L^2 at the travel, below half their allowable
    t, length, x = got["flexures.thickness_mm"], got["flexures.length_mm"], got["flexures.travel_mm"]
    assert 3 * 207e3 * t * x / length ** 2 <= 0.5 * got["flexures.allowable_stress_MPa"]
    # a soft preload spring, as the paper asks: k3 far below each path
    assert summary.preload_spring.stiffness < min(summary.path1.stiffness, summary.path2.stiffness) / 10


def test_a_file_that_gives_its_hardware_gets_nothing_added():
    for name in ("robot_joint", "metric_dual_pinion", "split_pinion", "c_axis", "split_pinion_inch"):
        assert load_design(ROOT / "assemblies" / f"{name}.toml").defaulted == (), name


def test_a_given_section_is_kept_and_only_the_missing_ones_are_sized():
    data = tomllib.loads(GEARS_ONLY.read_text())
    data["preload"] = {"max_output_torque_Nm": 5}
    out, added = default_hardware(data)
    assert out["preload"] == {"max_output_torque_Nm": 5}
    assert not any(d.key.startswith("preload.") for d in added)
    # the springs are sized for 0.6 x 5 N·m, not for the Lewis rating
    springs = out["springs"]
    rate = 79.3e3 * springs["wire_diameter_mm"] ** 4 / (8 * springs["mean_coil_diameter_mm"] ** 3
                                                         * springs["active_coils"])
    force = 2 * rate * (springs["free_length_mm"] - springs["installed_length_mm"])
    r_b = 27.0 * math.cos(math.radians(20))
    assert force * 5.0 * r_b / 2 == pytest.approx(0.6 * 5e3, rel=1e-6)  # lengths written to 1 nm
    assert data.get("parts") is None  # the caller's data is not changed


def test_a_bore_that_is_no_standard_bearing_needs_its_bearing_given():
    """A bore no standard bearing has cannot size its bearing: the refusal names the [parts] key to
    give, and a partial [parts] giving that bearing (the rest defaulted) is taken."""
    text = GEARS_ONLY.read_text().replace("[gears.input]\n", "[gears.input]\nbore_diameter_mm = 5.5\n")
    data = tomllib.loads(text)
    with pytest.raises(DesignError, match="no standard bearing bore") as exc:
        default_hardware(data)
    assert exc.value.field == "parts.input_bearing_outer_diameter_mm"
    data["parts"] = {"input_bearing_outer_diameter_mm": 14.0, "input_bearing_width_mm": 5.0}
    completed, added = default_hardware(data)
    assert completed["parts"]["input_bearing_outer_diameter_mm"] == 14.0  # the file's values stand
    assert "parts.input_bearing_outer_diameter_mm" not in {d.key for d in added}
    assert {"parts.cluster_bearing_outer_diameter_mm", "parts.motor_body_diameter_mm"} <= {d.key for d in added}


def test_an_inch_design_gets_inch_bearings_and_inch_keys():
    text = (ROOT / "assemblies/robot_joint.toml").read_text()
    data = tomllib.loads(text)
    for section in ("parts", "flexures", "springs", "preload", "stiffness"):
        data.pop(section)
    for gear in data["gears"].values():
        for key in [k for k in gear if k.startswith(("bore_", "hub_", "keyway_"))]:
            del gear[key]
    out, added = default_hardware(data)
    keys = {d.key for d in added}
    assert "parts.cluster_bearing_outer_diameter_in" in keys and "preload.max_output_torque_in_lbf" in keys
    inch_bores = {b[0] for b in INCH_BEARINGS}
    assert {out["gears"][g]["bore_diameter_in"] for g in ("input", "cluster_large", "output")} <= inch_bores
