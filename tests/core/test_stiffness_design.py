"""The stiffness sections of design files, and whole-design summaries: the robot joint recomputed by
hand from its file's numbers, a Type 1 split pinion, and a C-axis-like beam pinion with helical
engagement."""

import math
from pathlib import Path

import pytest

from geargen.core import flexures as fx
from geargen.core.stiffness import stiffness_summary
from geargen.drives.resolver import drive_from_design
from geargen.design.assembly import design_from_dict, load_design
from geargen.design.stiffness import (component_from_table, convert_quantity, preload_spec_from_table,
                                      stiffness_design)
from geargen.errors import DesignError

ROBOT = Path(__file__).resolve().parents[2] / "assemblies" / "robot_joint.toml"
IN = 25.4
DEG = math.pi / 180


# --- units and parsing ---------------------------------------------------------------------------

@pytest.mark.parametrize("family, suffix, value, internal", [
    ("torsional_stiffness", "Nm_per_rad", 2.0, 2000.0),
    ("torsional_stiffness", "Nm_per_deg", 1.0, 1e3 * 180 / math.pi),
    ("torsional_stiffness", "in_lbf_per_rad", 1.0, 4.4482216152605 * 25.4),
    ("linear_stiffness", "N_per_um", 10.0, 10000.0),
    ("linear_stiffness", "lbf_per_in", 1.0, 4.4482216152605 / 25.4),
    ("torque", "Nm", 5.0, 5000.0),
    ("torque", "in_lbf", 1.0, 112.98482902761670),
    ("force", "lbf", 1.0, 4.4482216152605),
    ("stress", "GPa", 207.0, 207000.0),
    ("stress", "ksi", 1.0, 6.894757293168361),
    ("stress", "Mpsi", 30.0, 206842.71879505),
])
def test_quantity_units_convert_to_internal(family, suffix, value, internal):
    assert convert_quantity(value, family, suffix) == pytest.approx(internal, rel=1e-12)


def test_component_table_reads_units_and_count():
    c = component_from_table("key", {"kind": "torsion", "shaft": "output", "stiffness_kNm_per_rad": 3.0, "count": 2})
    assert c.stiffness == pytest.approx(3e6) and c.count == 2 and c.scope == "each_path"
    b = component_from_table("brg", {"kind": "linear", "gear": "output", "stiffness_lbf_per_in": 1e5})
    assert b.stiffness == pytest.approx(1e5 * 4.4482216152605 / 25.4, rel=1e-14)
    s = component_from_table("s", {"kind": "shaft_torsion", "shaft": "input", "diameter_in": 0.25, "length_mm": 10})
    assert s.diameter == pytest.approx(6.35, rel=1e-15)


@pytest.mark.parametrize("table, field, text", [
    ({"kind": "torsion", "shaft": "output", "stiffness_Nm_per_rad": 1, "colour": "red"},
     "stiffness.components.c.colour", "unknown key"),
    ({"kind": "torsion", "shaft": "output", "stiffness_Nm_per_rad": 1, "diameter_mm": 5},
     "stiffness.components.c.diameter", "not used by kind 'torsion'"),
    ({"kind": "torsion", "shaft": "output", "stiffness_N_per_mm": 1},
     "stiffness.components.c.stiffness", "torsional stiffness"),
    ({"kind": "torsion", "shaft": "output", "stiffness_N_per_mm": 1, "stiffness_N_per_um": 1},
     "stiffness.components.c.stiffness_N_per_um", "given twice"),
    ({"kind": "torsion", "shaft": "output", "stiffness_Nm_per_rad": -1},
     "stiffness.components.c.stiffness_Nm_per_rad", "out of range"),
    ({"kind": "torsion", "stiffness_Nm_per_rad": 1}, "stiffness.components.c.shaft", "missing"),
    ({"kind": "linear", "stiffness_N_per_mm": 1}, "stiffness.components.c.gear", "exactly one"),
    ({"kind": "shaft_bending", "gear": "output", "diameter_mm": 5, "span_mm": 10, "load_position_mm": 12},
     "stiffness.components.c.load_position_mm", "between the supports"),
    ({"kind": "mesh", "gears": ["a"]}, "stiffness.components.c.gears", "pair"),
    ({"kind": "spring"}, "stiffness.components.c.kind", "not a valid choice"),
])
def test_bad_component_tables_name_the_key(table, field, text):
    with pytest.raises(DesignError) as info:
        component_from_table("c", table)
    assert info.value.field == field
    assert text in str(info.value)


def test_preload_section_needs_the_max_load():
    with pytest.raises(DesignError) as info:
        preload_spec_from_table({"preload_Nm": 2})
    assert info.value.field == "preload.max_output_torque"
    p = preload_spec_from_table({"max_output_torque_in_lbf": 10, "loop_error_rotation_urad": 50,
                                 "preload_spring_stiffness_Nm_per_rad": 20})
    assert p.max_output_torque == pytest.approx(112.98482902761670 * 10, rel=1e-14)
    assert p.loop_error_rotation == pytest.approx(50e-6, rel=1e-14)
    assert p.preload_spring_torsional == pytest.approx(2e4) and p.preload_spring_linear is None


# --- the robot joint, recomputed by hand ----------------------------------------------------------

def _robot_joint_summary():
    """The robot joint's summary with the lengths of its from_geometry components from the resolved
    drive's placed shafts (as every command computes it), and the [preload] loop error."""
    from geargen.drives.resolver import resolve
    from geargen.model.analysis import placed_components
    design = load_design(ROBOT)
    return stiffness_summary(design, components=placed_components(design, resolve(design)))


def test_robot_joint_summary_matches_a_hand_computation_from_the_file():
    """Every length below is worked out by hand from the design file: the cluster's large gear
    face 0..0.1875 in, the 0.0625 in gap, the small gear 0.25..0.5625 in; its bearings 0.196 in
    wide a 0.02 in clearance beyond the faces, so supports at -0.118 and 0.6805 in: span
    0.7985 in, the small gear's mid-face (0.40625 in) 0.52425 in from the lower support; the
    shaft twists over 0.3125 in between the gears' mid-planes; the input shaft over 0.525 in
    (input_shaft_to_bevel)."""
    s = _robot_joint_summary()
    E, G = 207e3, 79.3e3
    cos20 = math.cos(20 * DEG)
    R2, R1 = 112 / 21, 3.0
    rb2, rb3, rb4 = 0.75 * IN * cos20, 21 / 64 * IN * cos20, 1.75 * IN * cos20
    mesh1 = E * 0.1875 * IN / 11 * (rb2 * R2) ** 2  # Eq. 1 at the large gear, reflected through R2
    mesh2 = E * 0.25 * IN / 11 * rb4 ** 2
    shaft = G * math.pi * (0.25 * IN) ** 4 / 32 / (0.3125 * IN) * R2 ** 2
    ei = E * math.pi * (0.25 * IN) ** 4 / 64
    span, a, a_large = 0.7985 * IN, 0.52425 * IN, 0.21175 * IN  # the large gear's mid-face 0.09375 in

    def influence(load, at):
        """The shaft on two rigid supports (b x (L^2 - b^2 - x^2) / (6 E I L), x on the load's near
        side) plus the two 10 N/um bearings through their levers, mm/N."""
        if at > load:
            load, at = span - load, span - at
        b = span - load
        return (b * at * (span ** 2 - b ** 2 - at ** 2) / (6 * ei * span)
                + ((span - load) * (span - at) + load * at) / span ** 2 / 10e3)
    b = span - a
    assert influence(a, a) == pytest.approx(a * a * b * b / (3 * ei * span) + ((b / span) ** 2 + (a / span) ** 2)
                                            / 10e3, rel=1e-12)
    # the reviewer's single force: the small gear's alone, through R2 at its base radius
    alone = 1 / influence(a, a) * (rb3 * R2) ** 2
    assert 1 / (1 / mesh1 + 1 / mesh2 + 1 / shaft + 1 / alone) == pytest.approx(15.518e6, rel=1e-4)
    # both mesh forces on the shaft, per unit output torque 1 / (R2 r_b) each, along the working lines
    # of action at the placed centres: the input's on the large gear turns cluster a clockwise (the
    # input's ccw flank works), the output's on the small gear counter-clockwise
    from geargen.drives.resolver import resolve
    layout = resolve(load_design(ROBOT))
    c_cl, c_in, c_out = (layout.gear(n).centre for n in ("cluster_small_a", "input", "output"))

    def push(mate, rb, rb_mate, sense):  # away from the mate, turning the cluster `sense`
        ex, ey = (mate[0] - c_cl[0]) / math.dist(mate, c_cl), (mate[1] - c_cl[1]) / math.dist(mate, c_cl)
        alpha = math.acos((rb + rb_mate) / math.dist(mate, c_cl))
        return (-math.sin(alpha) * ex - sense * math.cos(alpha) * ey, -math.sin(alpha) * ey + sense * math.cos(alpha) * ex)
    n_large, n_small = push(c_in, rb2, 0.25 * IN * cos20, -1), push(c_out, rb3, rb4, +1)
    cos = n_large[0] * n_small[0] + n_large[1] * n_small[1]
    f_large, f_small = 1 / (R2 * rb2), 1 / (R2 * rb3)
    support = 1 / (f_small ** 2 * influence(a, a) + f_large ** 2 * influence(a_large, a_large)
                   + 2 * cos * f_small * f_large * influence(a_large, a))
    k_path = 1 / (1 / mesh1 + 1 / mesh2 + 1 / shaft + 1 / support)
    assert s.drive.k1 == pytest.approx(k_path, rel=1e-12) and s.drive.k2 == pytest.approx(k_path, rel=1e-12)
    # N·mm/rad: the two forces nearly oppose (137 deg): 18,551 N m/rad (17.28e6 with the lengths typed
    # in the file in the first round)
    assert cos == pytest.approx(-0.7315, abs=1e-4)
    assert k_path == pytest.approx(18.551e6, rel=1e-4)
    common = 1 / (1 / (G * math.pi * (0.1875 * IN) ** 4 / 32 / (0.525 * IN) * (R1 * R2) ** 2)
                  + 1 / (G * math.pi * ((1.25 * IN) ** 4 - IN ** 4) / 32 / (0.4 * IN)))
    assert s.common.stiffness == pytest.approx(common, rel=1e-12)
    # preload spring: three blades and two springs along the carriage, through lambda = 1/(R2 r_b2)
    k_blades = 3 * E * 0.5 * IN * (0.010 * IN) ** 3 / (1.0 * IN) ** 3
    k_spring = G * (0.045 * IN) ** 4 / (8 * (0.45 * IN) ** 3 * 4)
    lam = 1 / (R2 * rb2)
    assert s.drive.k3 == pytest.approx((k_blades + 2 * k_spring) / lam ** 2, rel=1e-12)
    # preload from the springs' installed length: F_e = 2 k_s (free - installed), P = F_e / (2 lambda)
    f_e = 2 * k_spring * (0.80 - 0.35) * IN
    assert s.carriage_force == pytest.approx(f_e, rel=1e-12)
    assert s.drive.preload == pytest.approx(f_e / (2 * lam), rel=1e-12)
    # Eq. 5 with equal paths is the parallel sum; Eq. 6
    assert s.drive_stiffness == pytest.approx(2 * k_path, rel=1e-12)
    assert s.loop_stiffness == pytest.approx(1 / (2 / k_path + 4 * lam ** 2 / (k_blades + 2 * k_spring)), rel=1e-12)
    # design intent: preload above half the 5 N·m maximum, no path unloads within it, no warnings
    assert s.required_preload == pytest.approx(2500.0) and s.preload_ok
    assert s.drive.unloading_torques[1] > 5000.0
    assert s.warnings == ()
    # the [preload] loop error (no synthesis passed in): 0.0095 in of carriage travel
    (v,) = s.variations
    assert v.loop_error == pytest.approx(2 * lam * 0.0095 * IN, rel=1e-12)
    assert v.range == pytest.approx(s.loop_stiffness * v.loop_error, rel=1e-12)
    assert v.relative < 0.10


def test_robot_joint_drive_from_design_and_other_locations():
    design = load_design(ROBOT)
    s = _robot_joint_summary()
    d = drive_from_design(design)
    assert (d.drive_type, d.k1, d.k2, d.k3, d.preload) == ("type2", s.drive.k1, s.drive.k2, s.drive.k3, s.drive.preload)
    at_input = drive_from_design(design, location="input")
    r = 16.0  # 48/16 * 112/21
    assert at_input.k1 == pytest.approx(d.k1 / r ** 2, rel=1e-14)
    assert at_input.preload == pytest.approx(d.preload / r, rel=1e-14)
    assert at_input.loop_stiffness == pytest.approx(d.loop_stiffness / r ** 2, rel=1e-12)
    # the contract's units: N·m/rad and N·m
    data = s.to_dict()
    assert data["k1_Nm_per_rad"] == pytest.approx(d.k1 / 1e3) and data["preload_Nm"] == pytest.approx(d.preload / 1e3)


def test_a_torsion_sits_on_the_shaft_of_the_gear_it_names():
    """A torsional stiffness (a key, a coupling) named by its gear turns with that gear's shaft:
    on the cluster, R2 = 112 / 21 times the output, so k R2^2 at the output."""
    from geargen.core.stiffness import component_stiffness, train_from_design

    design = load_design(ROBOT)
    spec = stiffness_design(design).stiffness
    key = component_from_table("key", {"kind": "torsion", "gear": "cluster_small", "stiffness_Nm_per_rad": 100})
    c = component_stiffness(key, design.gears, spec, train_from_design(design, spec))
    assert c.ratio == pytest.approx(112 / 21, rel=1e-15)
    assert c.at_output == pytest.approx(100e3 * (112 / 21) ** 2, rel=1e-12)


def test_robot_joint_with_a_synthesis_budget():
    from geargen.drives.resolver import resolve
    from geargen.model.analysis import placed_components
    design = load_design(ROBOT)
    travels = {"sum": 0.0121648 * IN, "rss": 0.0068853 * IN, "mean": 0.00952505 * IN}
    s = stiffness_summary(design, travels, components=placed_components(design, resolve(design)))
    assert [v.label for v in s.variations] == ["sum", "rss", "mean"]
    assert s.headline.label == "mean" and all(v.source == "synthesis" for v in s.variations)
    lam = s.lever
    for v in s.variations:
        assert v.range == pytest.approx(s.loop_stiffness * 2 * lam * travels[v.label], rel=1e-12)
    assert s.variations[0].range > s.variations[2].range > s.variations[1].range


# --- other designs built in the test -------------------------------------------------------------

def _split_pinion(preload_table=None, **preload):
    # Type 1 (Fig. 8): two 20-tooth pinions on concentric shafts drive two 80-tooth output gears;
    # the inner path is made compliant by its slender shaft.
    if preload_table is None:
        preload_table = {"max_output_torque_Nm": 20.0, "loop_error_rotation_urad": 300.0, **preload}
    return design_from_dict({
        "name": "split",
        "drive": {"type": "type1", "preload": "frictional_interface"},
        "gear_defaults": {"module_mm": 1.0, "pressure_angle_deg": 20},
        "gears": {"outer": {"teeth": 20, "face_width_mm": 12}, "inner": {"teeth": 20, "face_width_mm": 6},
                  "out_a": {"teeth": 80, "face_width_mm": 12}, "out_b": {"teeth": 80, "face_width_mm": 6}},
        "stiffness": {"train": "custom", "components": {
            "mesh_outer": {"kind": "mesh", "gears": ["outer", "out_a"], "ratio": 1.0, "scope": "path1"},
            "mesh_inner": {"kind": "mesh", "gears": ["inner", "out_b"], "ratio": 1.0, "scope": "path2"},
            "inner_shaft": {"kind": "shaft_torsion", "ratio": 4.0, "diameter_mm": 4, "length_mm": 60, "scope": "path2"},
            "motor_coupling": {"kind": "torsion", "ratio": 4.0, "stiffness_Nm_per_rad": 800, "scope": "common"}}},
        "preload": preload_table})


def test_type1_split_pinion_by_hand():
    s = stiffness_summary(_split_pinion(preload_Nm=20.0))
    E, G = 207e3, 79.3e3
    rb_out = 40.0 * math.cos(20 * DEG)
    k1 = E * 12 / 11 * rb_out ** 2
    k2 = 1 / (1 / (E * 6 / 11 * rb_out ** 2) + 1 / (G * math.pi * 4 ** 4 / 32 / 60 * 16))
    assert s.drive.k1 == pytest.approx(k1, rel=1e-12) and s.drive.k2 == pytest.approx(k2, rel=1e-12)
    assert s.drive.k3 == math.inf and s.preload_spring is None
    assert s.drive_stiffness == pytest.approx(k1 + k2, rel=1e-12)  # Eq. 2
    assert s.loop_stiffness == pytest.approx(k1 * k2 / (k1 + k2), rel=1e-12)  # Eq. 3
    assert s.common.stiffness == pytest.approx(800e3 * 16, rel=1e-12)
    assert s.required_preload == 20000.0 and s.preload_ok  # type 1: the maximum load
    assert s.preload_to_carry == pytest.approx(20000.0 * k1 / (k1 + k2), rel=1e-12)
    (v,) = s.variations
    assert v.range == pytest.approx(k1 * k2 / (k1 + k2) * 300e-6, rel=1e-12)
    # below the rule: a warning, and the band is reported against it
    low = stiffness_summary(_split_pinion(preload_Nm=12.0))
    assert not low.preload_ok and any("below the paper's recommendation" in w for w in low.warnings)


def test_type1_rejects_a_preload_spring_and_carriage_travel():
    with pytest.raises(DesignError) as info:
        stiffness_summary(_split_pinion(preload_spring_stiffness_N_per_mm=10))
    assert info.value.field == "drive.type"
    bad = _split_pinion({"max_output_torque_Nm": 20.0, "loop_error_carriage_travel_mm": 0.1})
    with pytest.raises(DesignError) as info:
        stiffness_summary(bad)  # a split pinion has no carriage to travel
    assert info.value.field == "preload.loop_error_carriage_travel"


def _gear_table(g):
    table = {"teeth": g.teeth, "module_mm": g.module, "pressure_angle_rad": g.pressure_angle, "face_width_mm": g.face_width}
    if g.hub.bore_diameter:
        table["bore_diameter_mm"] = g.hub.bore_diameter  # the placed shafts fill the bores
    return table


def _c_axis(**extra):
    # A C-axis-like type 2 drive: a long helical input pinion (the beam spring) between two helical
    # clusters whose pinions engage the spindle's bull gear axially.
    return design_from_dict({
        "name": "c_axis",
        "drive": {"type": "type2", "preload": "radial"},
        "gear_defaults": {"module_mm": 2.0, "pressure_angle_deg": 20, "helix_angle_deg": 15},
        "gears": {"input": {"teeth": 18, "face_width_mm": 30, "hand": "left"},
                  "cluster_large": {"teeth": 54, "face_width_mm": 20},
                  "cluster_small": {"teeth": 17, "face_width_mm": 30, "hand": "left"},
                  "output": {"teeth": 120, "face_width_mm": 30}},
        "stiffness": {"components": {"cluster_bearings": {"kind": "linear", "gear": "cluster_small",
                                                          "stiffness_N_per_um": 200}}},
        "preload": {"max_output_torque_Nm": 400.0, "preload_Nm": 250.0, "loop_error_carriage_travel_mm": 0.02},
        "beam_pinion": {"gear": "input", "span_mm": 160.0, "allowable_stress_MPa": 300},
        "engagement": {"gear": "cluster_small", "backlash_mm": 0.10, "clearance_mm": 3.0},
        **extra})


def test_beam_pinion_is_the_preload_spring_and_engagement_lead_follows():
    design = _c_axis()
    s = stiffness_summary(design)
    inp = design.gears["input"]
    d_root = 2 * inp.root_radius_standard
    ei = 207e3 * math.pi * d_root ** 4 / 64
    k_beam = 48 * ei / 160.0 ** 3
    large = design.gears["cluster_large"]
    lam = 1 / (120 / 17 * large.base_radius)
    assert s.preload_spring.linear_parts == (("beam pinion", pytest.approx(k_beam, rel=1e-12)),)
    assert s.drive.k3 == pytest.approx(k_beam / lam ** 2, rel=1e-12)
    # the beam carries the whole carriage force at the mesh, at mid-span (zero slope)
    assert s.beam.force == pytest.approx(2 * lam * 250e3, rel=1e-12)
    assert s.beam.zero_slope_offset == pytest.approx(0.0, abs=1e-12) and s.beam.slope_at_mesh == 0.0
    assert s.beam.max_stress == pytest.approx(s.beam.force * 160 / 4 / (math.pi * d_root ** 3 / 32), rel=1e-12)
    # engagement: the loop's preload windup at the pinion's reference circle, plus the backlash
    pin = design.gears["cluster_small"]
    windup = 250e3 / s.loop_stiffness * (120 / 17) * pin.reference_radius
    assert s.engagement.preload_windup == pytest.approx(windup, rel=1e-12)
    # the whole cluster slides: its right-hand large gear along the left-hand input turns it the
    # other way from the left-hand pinion's helix, so the two add: tan(beta) (1 + r_e / r_o)
    per_lead = math.tan(15 * DEG) * (1 + pin.reference_radius / large.reference_radius)
    assert (large.hand, pin.hand) == ("right", "left")
    assert s.engagement.lead == pytest.approx((0.10 + windup) / per_lead, rel=1e-12)
    assert s.engagement.engagement_length == pytest.approx(30.0)
    assert s.engagement.trailer_retracted_stop == pytest.approx(-33.0 - s.engagement.lead, rel=1e-12)


def test_off_centre_beam_pinion_is_flagged():
    s = stiffness_summary(_c_axis(beam_pinion={"gear": "input", "span_mm": 160.0, "mesh_position_mm": 60.0}))
    assert s.beam.zero_slope_position == pytest.approx(fx.zero_slope_position(160.0, 60.0), rel=1e-14)
    assert any("zero-slope point" in w for w in s.warnings)


def test_preload_set_twice_is_an_error():
    design = load_design(ROBOT)
    raw = dict(design.sections)
    raw["preload"] = {**raw["preload"], "preload_Nm": 3.0}  # the springs' installed length also sets it
    twice = design_from_dict({"name": "rj", "length_unit": "in", "drive": {"type": "type2", "preload": "radial"},
                              "gears": {n: _gear_table(g) for n, g in design.gears.items()}, **raw})
    from geargen.drives.resolver import resolve
    from geargen.model.analysis import stiffness
    with pytest.raises(DesignError) as info:
        stiffness(twice, resolve(twice))
    assert info.value.field == "preload.preload"


def test_stiffness_design_reads_every_robot_section():
    sd = stiffness_design(load_design(ROBOT))
    assert sd.flexures.count == 3 and sd.flexures.thickness == pytest.approx(0.254)
    assert sd.springs.count == 2 and sd.springs.installed_length == pytest.approx(0.35 * IN)
    assert sd.preload.max_output_torque == pytest.approx(5000.0)
    assert sd.beam_pinion is None and sd.engagement is None
    assert [c.name for c in sd.stiffness.components] == ["cluster_shaft", "cluster_support", "input_shaft", "output_hub"]
    assert [c.from_geometry for c in sd.stiffness.components] == [True, True, True, False]
