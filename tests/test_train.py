"""geargen train on the shipped designs: the R^2 law exact in the JSON, each stage's lost motion and
stiffness against hand calculations from the design file, the dominant stage, the servo view, the
strategy advice, and the dual-motor drive's zones by hand."""

import json
import math
from functools import lru_cache

import pytest

from geargen.cli import main
from geargen.design.assembly import load_design
from geargen.errors import DesignError

pytestmark = pytest.mark.slow

IN = 25.4


@lru_cache(maxsize=None)
def run_train(name: str, tmp=None) -> dict:
    import tempfile
    out = tempfile.mkdtemp()
    assert main(["train", f"assemblies/{name}.toml", "--no-plots", "--json", f"{out}/t.json"]) == 0
    with open(f"{out}/t.json") as f:
        return json.load(f)


def test_robot_joint_parts_follow_the_R_squared_law():
    data = run_train("robot_joint")
    ratios = {p["name"]: p["ratio_to_motor"] for p in data["parts"]}
    # motor 32:1 to the output: bevel pinion on the motor, input x2 (bevel 15:30), clusters x6, output x32
    assert ratios["bevel_pinion"] == pytest.approx(1.0)
    assert ratios["input"] == ratios["bevel_gear"] == ratios["input_shaft"] == pytest.approx(2.0)
    assert ratios["cluster_large_a"] == ratios["cluster_shaft_b"] == pytest.approx(6.0)
    assert ratios["output"] == ratios["output_shaft"] == pytest.approx(32.0)
    for p in data["parts"]:
        assert p["reflected_to_motor_kg_m2"] == pytest.approx(p["inertia_own_axis_kg_m2"] / p["ratio_to_motor"] ** 2,
                                                              rel=1e-12)
    t = data["totals"]
    load = load_design("assemblies/robot_joint.toml").section("train")["load_inertia_kg_m2"]
    assert t["inertia_at_motor_kg_m2"] == pytest.approx(
        3.0e-6 + sum(p["reflected_to_motor_kg_m2"] for p in data["parts"]) + load / 32 ** 2, rel=1e-12)


def test_robot_joint_stage_lost_motion_by_hand_and_the_output_mesh_dominates():
    from geargen.drives import resolve
    data = run_train("robot_joint")
    st = {s["name"].split(" (")[0]: s for s in data["stages"]}
    # mesh 2: 0.0025 in at the output's 1.75 in pitch radius; mesh 1: its backlash where the carriage
    # settles (0.00450 in, the resolved drive's) at the input's 0.25 in, / 16 (the input turns 16 x the
    # output); the bevel pair: 11 arcmin at the input shaft / 16
    b1 = resolve(load_design("assemblies/robot_joint.toml")).mesh("mesh1_a").modelled_backlash / IN
    assert b1 == pytest.approx(0.0045, abs=2e-6)
    assert st["loop stage 2"]["lost_motion_at_output_urad"] == pytest.approx(0.0025 / 1.75 * 1e6, rel=1e-6)
    assert st["loop stage 1"]["lost_motion_at_output_urad"] == pytest.approx(b1 / 0.25 / 16 * 1e6, rel=1e-9)
    assert st["upstream 15:30"]["lost_motion_at_output_urad"] == pytest.approx(
        math.radians(11 / 60) / 16 * 1e6, rel=1e-9)
    assert data["totals"]["dominant_stage"].startswith("loop stage 2")
    # preloaded: only the bevel pair's backlash is left at the output
    assert data["totals"]["lost_motion_at_output_urad"] == pytest.approx(
        st["upstream 15:30"]["lost_motion_at_output_urad"], rel=1e-12)
    assert sum(s["share_of_lost_motion"] for s in data["stages"]) == pytest.approx(1.0, rel=1e-12)


def test_robot_joint_stages_add_up_to_the_stiffness_command_and_the_bevel_mesh():
    """The loop's stages and the common parts are geargen stiffness' drive with its common parts;
    the bevel stage adds Eq. 1 on the bevel pair (E w / 11 at its mean base radius, x 16^2) by hand."""
    data = run_train("robot_joint")
    t = data["totals"]
    e, w = 207e3, 0.15 * IN
    cone = math.atan2(30, 15)
    r_base = (30 / 32 * IN / 2 - w / 2 * math.sin(cone)) * math.cos(math.radians(20))
    bevel = e * w / 11 * r_base ** 2 * 16 ** 2 / 1e3  # N·m/rad at the output
    expected = 1 / (1 / t["stiffness_command_drive_with_common_Nm_per_rad"] + 1 / bevel)
    assert t["stiffness_at_output_Nm_per_rad"] == pytest.approx(expected, rel=1e-9)
    assert sum(s["compliance_share"] for s in data["stages"]) == pytest.approx(1.0, rel=1e-9)


def test_robot_joint_servo_and_strategy():
    data = run_train("robot_joint")
    sv = data["servo"]
    assert sv["natural_frequency_Hz"] == pytest.approx(15.0, rel=1e-12)  # the design's bandwidth
    # the load dominates (2.0e-5 of 2.3e-5 kg m^2 at the motor): frequency gain close to R = 32
    assert 25 < sv["frequency_gain_over_direct"] < 32
    assert sv["damping_gain_over_direct"] == pytest.approx(sv["frequency_gain_over_direct"], rel=1e-12)
    assert sv["resonance_Hz"] > 10 * sv["natural_frequency_Hz"]
    assert sv["chain_first_mode_Hz"] == pytest.approx(sv["resonance_Hz"], rel=0.15)
    ad = data["advice"]
    assert ad["met"] and ad["design_agrees"] and sorted(ad["preload"]) == sorted(ad["design_preloads"])


def test_metric_design_advice_asks_for_one_more_stage():
    """30 arcsec allowed, the two plain stages keep 124 + 296 urad: the idler stage must be preloaded too."""
    data = run_train("metric_dual_pinion")
    names = [s["name"].split(" (")[0] for s in data["stages"]]
    assert names == ["stage motor", "stage idler", "loop stage 1", "loop stage 2"]
    ad = data["advice"]
    assert ad["met"] and not ad["design_agrees"]
    assert [n.split(" (")[0] for n in ad["preload"]] == ["loop stage 2", "loop stage 1", "stage idler"]
    assert ad["lost_motion_left_urad"] <= ad["allowed_lost_motion_urad"]


def test_dual_motor_zones_match_the_hand_calculation():
    data = run_train("dual_motor")
    # one path at the output: Eq. 1 (E w / 11 at the output's base radius), the 20 x 30 mm pinion
    # shaft and the 6 N·m/arcmin gearhead, both x 8^2 (144 / 18)
    r_b = 144 * 2.0 / 2 * math.cos(math.radians(20))
    mesh = 207e3 * 20 / 11 * r_b ** 2 / 1e3
    shaft = 79.3e3 * math.pi * 20 ** 4 / 32 / 30 * 64 / 1e3
    gearhead = 6 * 10800 / math.pi * 64
    path = 1 / (1 / mesh + 1 / shaft + 1 / gearhead)
    assert data["path"]["stiffness_at_output_Nm_per_rad"] == pytest.approx(path, rel=1e-9)
    zones = {z["zone"]: z for z in data["zones"]}
    assert zones["opposed"]["stiffness"] == pytest.approx(2 * path, rel=1e-12)
    assert zones["opposed"]["command_to"] == pytest.approx(60.0)  # 2 x the 30 N·m bias
    assert zones["crossing"]["stiffness"] == pytest.approx(path, rel=1e-12)
    assert zones["together"]["command_to"] == pytest.approx(2 * 2.4 * 5 * 8)  # both motors at peak
    assert data["bias_needed_for_load_Nm"] == pytest.approx(30.0)
    uni = next(r for r in data["comparison"] if r["control"] == "unidirectional")
    assert uni["capacity_Nm"] == pytest.approx(2.4 * 40 - 30)


def test_bevel_backlash_from_parts_and_one_name_per_thing(tmp_path):
    """Issue 31: with the bevel pair's backlash given as [parts] bevel_backlash_in (what its teeth are
    cut to) and no [train] upstream_backlash_arcmin, train said "backlash not known" and 0.0 urad.
    By hand: 0.0015 in at the 30-tooth gear's heel pitch radius 30 / 32 / 2 = 0.46875 in is 3.2 mrad at
    the input shaft, / 16 (the input turns 16 x the output) = 200.0 urad. Names: the train's stage is
    "loop stage 1", holding geargen stiffness's component "mesh 1 (...)" and its driven shaft's parts."""
    text = open("assemblies/robot_joint.toml").read()
    assert "upstream_backlash_arcmin = [11]" in text and "\nbevel_pinion_teeth = 15" in text
    path = tmp_path / "robot_joint.toml"
    path.write_text(text.replace("upstream_backlash_arcmin = [11]", "")
                    .replace("\nbevel_pinion_teeth = 15", "\nbevel_backlash_in = 0.0015\nbevel_pinion_teeth = 15"))
    assert main(["train", str(path), "--no-plots", "--json", str(tmp_path / "t.json")]) == 0
    data = json.loads((tmp_path / "t.json").read_text())
    st = {s["name"].split(" (")[0]: s for s in data["stages"]}
    assert st["upstream 15:30"]["lost_motion_at_output_urad"] == pytest.approx(0.0015 / 0.46875 / 16 * 1e6, rel=1e-9)
    assert not any("not known" in w for w in data["warnings"])
    assert data["totals"]["lost_motion_at_output_urad"] == pytest.approx(200.0, rel=1e-9)
    # one word, one thing: the stiffness command's "mesh 1" is one component of train's "loop stage 1"
    assert st["loop stage 1"]["components"][0].startswith("mesh 1 (")
    assert set(st["loop stage 1"]["components"]) == {"mesh 1 (input-cluster_large)", "cluster_shaft", "cluster_support"}
    assert not any(name.startswith("mesh") for name in st)


def test_planetary_stage_lost_motion_stiffness_and_planets_by_hand():
    """Issue 31: geargen train refused the planetary design. By hand from the design file: sun 15 T,
    planets 21 T, ring 57 T, m 0.8 (reference radii r_s 6, r_r 22.8 mm); the carrier turns with the
    loop's input, 54/18 x 100/20 = 15 x the output. Sun held, the carrier's free turn is
    (j_sp + j_pr) / (r_s + r_r) (each planet's two meshes along lines of action r_bs and r_br from the
    axis): as built (mid-range, 0.08 mm in each mesh) 0.16 / 28.8 / 15 = 370.4 urad at the output;
    over the design's range 0.08 / 432 = 185.2 to 0.24 / 432 = 555.6 urad. Stiffness: per planet
    (r_bs + r_br)^2 / (2 / k) with k = E w / 11 = 207e3 x 6 / 11 N/mm, 3 planets, x 15^2, in series with
    the input shaft (the stage's driven shaft). Planets spin at 15 |1 - 57/21| = 25.71 x the output
    (72 / 2.8 from the motor) and orbit at the carrier radius 14.767 mm (m a^2 at the carrier)."""
    from geargen import pipeline
    data = run_train("planetary_dual_pinion")
    st = {s["name"].split(" (")[0]: s for s in data["stages"]}
    plan = st["stage planetary"]
    assert plan["lost_motion_at_output_urad"] == pytest.approx(0.16 / 28.8 / 15 * 1e6, rel=1e-6)  # 370.37
    assert plan["lost_motion_min_at_output_urad"] == pytest.approx(0.08 / 28.8 / 15 * 1e6, rel=1e-12)  # 185.19
    assert plan["lost_motion_max_at_output_urad"] == pytest.approx(0.24 / 28.8 / 15 * 1e6, rel=1e-12)  # 555.56
    assert not plan["preloaded"] and data["totals"]["lost_motion_at_output_urad"] == pytest.approx(
        plan["lost_motion_at_output_urad"], rel=1e-12)  # the loop keeps none
    cos20 = math.cos(math.radians(20))
    k = 207e3 * 6 / 11
    meshes = 3 * ((6 + 22.8) * cos20) ** 2 / (2 / k) * 15 ** 2 / 1e3  # N·m/rad at the output
    summary = pipeline.stiffness(pipeline.place(load_design("assemblies/planetary_dual_pinion.toml")))
    shaft = next(c for c in summary.common.components if c.name == "input_shaft").at_output / 1e3
    assert plan["components"] == ["input_shaft"]
    assert plan["stiffness_at_output_Nm_per_rad"] == pytest.approx(1 / (1 / meshes + 1 / shaft), rel=1e-9)
    parts = {p["name"]: p for p in data["parts"]}
    assert parts["planet_1"]["ratio_to_motor"] == pytest.approx(2.8, rel=1e-12)
    orbit = parts["planet_1 orbit"]
    assert orbit["ratio_to_motor"] == pytest.approx(4.8, rel=1e-12)
    assert orbit["inertia_own_axis_kg_m2"] == pytest.approx(parts["planet_1"]["mass_kg"] * 14.767e-3 ** 2, rel=1e-4)


def test_bad_train_input_names_the_field(tmp_path):
    text = open("assemblies/dual_motor.toml").read()
    for old, new, field in (("load_inertia_kg_m2 = 1.5", "load_inertia_kg_m2 = 1.5\nbandwidth_Hz = 10", "train.damping_ratio"),
                            ('material = "steel"', 'material = "unobtainium"', "train.material"),
                            ("bias_torque_Nm = 30", "bias_torque_Nm = 80", "dual_motor.bias_torque")):
        p = tmp_path / "bad.toml"
        p.write_text(text.replace(old, new))
        with pytest.raises(DesignError) as err:
            load_design(p)
        assert field in str(err.value)
