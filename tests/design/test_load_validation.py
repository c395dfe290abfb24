"""Every command refuses a bad design file on load, naming the key as the file spells it and the
allowed range in the design's unit (the reviewer's reproductions of issue 10, and the rules
behind them). The numbers in the messages are checked against independent closed forms."""

import math
import re
from pathlib import Path

import pytest

from geargen.cli import main
from geargen.design.assembly import design_from_dict, load_design
from geargen.design.schema import DesignErrors, load_toml
from geargen.errors import DesignError

ROOT = Path(__file__).resolve().parents[2]
ROBOT = ROOT / "assemblies" / "robot_joint.toml"
C_AXIS = ROOT / "assemblies" / "c_axis.toml"
SPLIT = ROOT / "assemblies" / "split_pinion.toml"
IN = 25.4


def variant(tmp_path, source: Path, *edits: tuple[str, str], name: str = "variant") -> Path:
    """A copy of ``source`` with each (regex, replacement) applied once to a line of it."""
    text = source.read_text()
    for pattern, replacement in edits:
        text, n = re.subn(pattern, replacement, text, count=1, flags=re.MULTILINE)
        assert n == 1, f"{pattern!r} not found in {source.name}"
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return path


def run(capsys, *argv) -> tuple[int, str]:
    code = main([str(a) for a in argv])
    captured = capsys.readouterr()
    assert "Traceback" not in captured.err
    return code, captured.err


def error_of(path: Path) -> DesignError:
    with pytest.raises(DesignError) as info:
        load_design(path)
    return info.value


# ------------------------------------------------------------------ 1. springs below solid height

def test_springs_installed_below_solid_height_are_refused_by_stiffness(tmp_path, capsys):
    bad = variant(tmp_path, ROBOT, (r"^installed_length_in = 0\.35", "installed_length_in = 0.20"))
    code, err = run(capsys, "stiffness", bad, "--out", tmp_path / "plots")
    assert code == 2
    # solid height of a squared-and-ground spring: d (Na + 2) = 0.045 in x (4 + 2) = 0.27 in
    assert "springs.installed_length_in: 0.2 in is at or below the solid height 0.27 in" in err
    assert "(0.27 in, 0.8 in]" in err
    assert "meets the recommendation" not in err
    assert not (tmp_path / "plots").exists()
    code, err = run(capsys, "build", bad, "--out", tmp_path / "out", "--quiet")
    assert code == 2 and "springs.installed_length_in" in err and "closes the coils" not in err
    assert not (tmp_path / "out").exists()


def test_installed_spring_past_its_allowable_stress_names_the_shortest_length(tmp_path):
    # at 0.30 in (above solid) the wire sees K 8 F D / (pi d^3) with F = k (free - installed)
    bad = variant(tmp_path, ROBOT, (r"^installed_length_in = 0\.35", "installed_length_in = 0.30"),
                  (r"^allowable_shear_stress_MPa = 900", "allowable_shear_stress_MPa = 600"))
    err = error_of(bad)
    d, mean, coils, g = 0.045 * IN, 0.45 * IN, 4, 79.3e3
    rate = g * d ** 4 / (8 * mean ** 3 * coils)
    c = mean / d
    wahl = (4 * c - 1) / (4 * c - 4) + 0.615 / c
    stress = wahl * 8 * rate * (0.80 - 0.30) * IN * mean / (math.pi * d ** 3)
    shortest = 0.80 - 600 / (wahl * 8 * mean / (math.pi * d ** 3)) / rate / IN
    assert err.field == "springs.installed_length_in"
    assert f"{stress:.4g} MPa shear, past the allowable 600 MPa" in err.problem
    assert err.allowed == f"[{shortest:.6g} in, 0.8 in]"


def test_wire_thicker_than_the_coil_is_refused(tmp_path, capsys):
    bad = variant(tmp_path, ROBOT, (r"^wire_diameter_in = 0\.045", "wire_diameter_in = 0.5"))
    for command in ("synth", "check"):
        code, err = run(capsys, command, bad)
        assert code == 2
        assert "springs.mean_coil_diameter_in: 0.45 in is not more than twice the wire (0.5 in)" in err
        assert "> 1 in" in err


def test_free_length_at_solid_height_is_refused(tmp_path):
    bad = variant(tmp_path, ROBOT, (r"^free_length_in = 0\.80", "free_length_in = 0.26"),
                  (r"^installed_length_in = 0\.35", "installed_length_in = 0.25"))
    err = error_of(bad)
    assert err.field == "springs.free_length_in" and err.allowed == "> 0.27 in"


# ------------------------------------------------------------------ 2. every section on load, every command

MONTE_CARLO = (r"^samples = 1000000", "samples = -5")


@pytest.mark.parametrize("argv", [
    ["synth", "{f}"], ["check", "{f}"], ["stiffness", "{f}", "--out", "{tmp}/plots"],
    ["build", "{f}", "--out", "{tmp}/out", "--quiet"], ["gear", "{f}", "--gear", "input", "--out", "{tmp}/gear"],
])
def test_a_bad_section_no_command_reads_is_refused_by_every_command(tmp_path, capsys, argv):
    bad = variant(tmp_path, ROBOT, MONTE_CARLO)
    code, err = run(capsys, *(a.format(f=bad, tmp=tmp_path) for a in argv))
    assert code == 2
    assert "monte_carlo.samples: -5 is out of range (allowed: [100, 1e+08])" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["variant.toml"]  # nothing written


def test_fit_refuses_a_bad_assembly(tmp_path, capsys):
    bad = variant(tmp_path, ROBOT, MONTE_CARLO)
    rows = "\n".join(f"{0.1 * i:.3f},{6.0 * i:.4f},{math.sin(0.1 * i):.5f}" for i in range(60))
    (tmp_path / "m.csv").write_text("time_s,output_angle_deg,carriage_x_um\n" + rows + "\n")
    (tmp_path / "m.toml").write_text(f'kind = "preload_trace"\nassembly = "{bad.as_posix()}"\n')
    code, err = run(capsys, "fit", tmp_path / "m.csv", "--json", tmp_path / "m.json", "--no-plots")
    assert code == 2 and "monte_carlo.samples" in err
    assert not (tmp_path / "m.json").exists()


# ------------------------------------------------------------------ 3. a tooth that cannot be cut

def test_thinned_to_a_point_names_the_gear_key_and_the_largest_thinning(tmp_path, capsys):
    bad = variant(tmp_path, ROBOT, (r"^thinning_circumferential_in = 0\.000452", "thinning_circumferential_in = 0.02"))
    code, err = run(capsys, "synth", bad)
    assert code == 2
    assert "gears.input.thinning_circumferential_in: 0.02 in thins the tooth to a point" in err
    most = float(re.search(r"allowed: \[0, ([0-9.e-]+) in\]", err).group(1))
    # independently: the exact outline of the input pinion has a tip land of 0.001 m_n at that thinning
    from geargen.core.involute import tip_land_thickness
    from geargen.design.gear import with_changes
    from geargen.profile.tooth import MIN_TIP_LAND_MODULES
    pinion = load_design(ROBOT).gear("input")
    at_most = with_changes(pinion, thinning=most * IN)
    assert tip_land_thickness(at_most) == pytest.approx(MIN_TIP_LAND_MODULES * pinion.module, abs=1e-6 * IN)
    assert 0.015 < most < 0.02


def test_normal_thinning_is_named_and_bounded_in_the_normal_section(tmp_path):
    bad = variant(tmp_path, C_AXIS, (r"^bore_diameter_mm = 30 +# on its 30 mm shaft",
                                     "bore_diameter_mm = 30\nthinning_normal_mm = 1.5"),
                  (r'^model_tooth_thickness = "mid_tolerance"', 'model_tooth_thickness = "as_designed"'))
    err = error_of(bad)
    assert err.field == "gears.input.thinning_normal_mm"
    most = float(re.match(r"\[0, ([0-9.e-]+) mm\]", err.allowed).group(1))
    from geargen.core.involute import tip_land_thickness
    from geargen.design.gear import with_changes
    pinion = load_design(C_AXIS).gear("input")
    helix = pinion.helix_angle
    at_most = with_changes(pinion, thinning=most / math.cos(helix))
    assert tip_land_thickness(at_most) == pytest.approx(1e-3 * pinion.module, abs=1e-5)


def test_a_pointed_tooth_without_thinning_names_the_profile_shift(tmp_path):
    bad = variant(tmp_path, SPLIT, (r"^teeth = 20\nface_width_mm = 12", "teeth = 20\nprofile_shift = 1.4\nface_width_mm = 12"))
    err = error_of(bad)
    assert err.field == "gears.pinion_stiff.profile_shift" and "comes to a point" in err.problem
    bound = float(err.allowed.split()[-1])
    from geargen.core.involute import tip_land_thickness
    from geargen.design.gear import with_changes
    pinion = load_design(SPLIT).gear("pinion_stiff")
    assert tip_land_thickness(with_changes(pinion, profile_shift=bound)) >= 1e-3 * pinion.module * (1 - 1e-6)
    assert tip_land_thickness(with_changes(pinion, profile_shift=bound + 1e-4)) < 1e-3 * pinion.module


# ------------------------------------------------------------------ 4. flexures, engagement

def test_flexure_thickness_zero_and_negative_length(tmp_path, capsys):
    for edit, text in (((r"^thickness_in = 0\.010", "thickness_in = 0"), "flexures.thickness_in: 0 is out of range"),
                       ((r"^length_in = 1\.0$", "length_in = -1.0"), "flexures.length_in: -1 is out of range")):
        bad = variant(tmp_path, ROBOT, edit)
        for command in ("synth", "check"):
            code, err = run(capsys, command, bad)
            # a positive length's plausible range (schema.PLAUSIBLE): 1 nm = 1e-6 / 25.4 in to 10 m = 1e4 / 25.4 in
            assert code == 2 and text in err and "(allowed: [3.93701e-08, 393.701] in)" in err


def test_flexure_past_its_allowable_stress_at_the_travel(tmp_path, capsys):
    bad = variant(tmp_path, ROBOT, (r"^travel_in = 0\.020 ", "travel_in = 0.2 "))
    code, err = run(capsys, "check", bad)
    assert code == 2
    # fixed-guided blade: sigma = 3 E t delta / L^2; the travel at the allowable 500 MPa
    e, t, length = 207e3, 0.010 * IN, 1.0 * IN
    stress = 3 * e * t * 0.2 * IN / length ** 2
    limit = 500 * length ** 2 / (3 * e * t) / IN
    assert f"flexures.travel_in: 0.2 in bends the blades to {stress:.4g} MPa" in err
    printed = float(re.search(r"\(allowed: \(0, ([0-9.e-]+) in\]", err).group(1))
    assert limit * (1 - 1e-5) <= printed <= limit  # rounded down: the printed limit is itself allowed


def test_flexure_thicker_than_wide_and_operating_outside_its_travel(tmp_path):
    err = error_of(variant(tmp_path, ROBOT, (r"^thickness_in = 0\.010", "thickness_in = 0.6")))
    assert err.field == "flexures.thickness_in" and err.allowed == "< width = 0.5 in"
    err = error_of(variant(tmp_path, ROBOT, (r"^neutral_offset_in = 0\.0", "neutral_offset_in = 0.03")))
    assert err.field == "flexures.neutral_offset_in" and err.allowed.startswith("[-0.02 in, 0.02 in]")


def test_travel_stops_that_do_not_allow_the_engagement_lead(tmp_path, capsys):
    bad = variant(tmp_path, C_AXIS, (r"^backlash_mm = 0\.08 ", "backlash_mm = 10 "))
    code, err = run(capsys, "synth", bad)
    assert code == 2
    # lead = (backlash (+ windup, >= 0)) / (|kappa_o - kappa_e| r_e) against the 30 mm engagement length:
    # the whole cluster slides, its large gear (60 x 2 mm) along the long pinion too; both gears
    # left hand at 15 deg, so per mm of lead tan(beta) (1 - r_e / r_o), r_e / r_o = 50 / 120
    per_lead = math.tan(math.radians(15)) * (1 - 50 / 120)
    assert f"engagement.backlash_mm: needs a lead of {10 / per_lead:.6g} mm" in err
    printed = float(re.search(r"\(allowed: \[0, ([0-9.e-]+) mm\]\)", err).group(1))
    assert 30 * per_lead * (1 - 1e-5) <= printed <= 30 * per_lead
    err = error_of(variant(tmp_path, C_AXIS, (r"^engagement_length_mm = 30 ", "engagement_length_mm = 31 ")))
    assert err.field == "engagement.engagement_length_mm" and err.allowed == "(0, 30 mm]"


def test_sliding_a_cluster_that_turns_nothing_cannot_open_backlash(tmp_path):
    # a spur pinion still turns against a spur bull gear when the cluster's large gear is helical
    data = load_toml(C_AXIS)
    data["gears"]["cluster_small"]["helix_angle_deg"] = 0
    data["gears"]["output"]["helix_angle_deg"] = 0
    with pytest.raises(DesignError) as info:  # (the synthesis' centre distance no longer fits spur gears)
        design_from_dict(data, validate=True)
    assert "engagement." not in str(info.value)
    # all spur: nothing turns
    data["gear_defaults"]["helix_angle_deg"] = 0
    with pytest.raises(DesignError) as info:
        design_from_dict(data, validate=True)
    assert "engagement.gear: sliding the cluster cannot turn gears.cluster_small against gears.output" \
        in str(info.value) and "neither gear of the cluster is helical" in str(info.value)


# ------------------------------------------------------------------ 5. all problems at once

def test_all_problems_of_a_file_are_reported_together(tmp_path, capsys):
    bad = variant(tmp_path, ROBOT, MONTE_CARLO, (r"^installed_length_in = 0\.35", "installed_length_in = 0.20"),
                  (r"^thickness_in = 0\.010", "thickness_in = 0"), (r"^teeth = 16", "teeth = 2"),
                  (r"^render_view = \[-60, 30\]", 'render_view = "front"'))
    with pytest.raises(DesignErrors) as info:
        load_design(bad)
    fields = [e.field for e in info.value.errors]
    assert fields == ["gears.input.teeth", "monte_carlo.samples", "flexures.thickness_in",
                      "springs.installed_length_in", "export.render_view"]
    code, err = run(capsys, "synth", bad)
    assert code == 2 and err.startswith("geargen synth: error: 5 problems in variant.toml:\n")
    assert all(f"\n  {f}: " in err for f in fields)


def test_a_default_shared_by_every_gear_is_named_once_where_the_file_has_it(tmp_path):
    err = error_of(variant(tmp_path, ROBOT, (r"^pressure_angle_deg = 20", "pressure_angle_deg = 50")))
    assert not isinstance(err, DesignErrors)
    assert err.field == "gear_defaults.pressure_angle_deg" and err.allowed == "[10, 35] deg"


# ------------------------------------------------------------------ rules between sections

def test_layout_parts_and_export_rules(tmp_path):
    err = error_of(variant(tmp_path, SPLIT, (r"^circumferential_backlash_min_mm = 0\.05",
                                             "circumferential_backlash_min_mm = 0.2")))
    assert err.field == "layout.circumferential_backlash_min_mm" and err.allowed == "[0, 0.1] mm"
    err = error_of(variant(tmp_path, ROBOT, (r'^model_tooth_thickness = "as_designed"',
                                             'model_tooth_thickness = "mid_tolerance"')))
    assert err.field == "layout.model_tooth_thickness" and "gears.input" in err.problem
    # the key it replaced is told where its values went (a file from before would otherwise get a bare
    # "unknown key")
    err = error_of(variant(tmp_path, SPLIT, (r'^model_tooth_thickness = "mid_tolerance"', 'model_backlash = "mid"')))
    assert err.field == "layout.model_backlash" and 'model_tooth_thickness = "mid_tolerance" (was "mid")' in err.allowed
    err = error_of(variant(tmp_path, C_AXIS, (r"^cluster_bearing_outer_diameter_mm = 55", "cluster_bearing_outer_diameter_mm = 25")))
    assert err.field == "parts.cluster_bearing_outer_diameter_mm" and err.allowed == "> 30 mm"
    err = error_of(variant(tmp_path, ROBOT, (r"^bevel_face_width_in = 0\.15", "bevel_face_width_in = 0.8")))
    # cone distance of a 15/30 pair at 32 DP: sqrt(15^2 + 30^2) / 32 / 2 in
    assert err.field == "parts.bevel_face_width_in" and err.allowed == f"< {math.hypot(15, 30) / 64:.6g} in (the cone distance)"
    err = error_of(variant(tmp_path, SPLIT, (r"^render_view = \[-55, 30\]", "render_view = [1, 2, 3]")))
    assert err.field == "export.render_view"
    err = error_of(variant(tmp_path, ROBOT, (r'^kind = "dual_pinion"', 'kind = "split_pinion"')))
    assert isinstance(err, DesignErrors)  # the robot joint's cluster shaft is no shaft of a split pinion either
    # ... and its [layout] cluster key is a dual pinion's (refused before the missing centre distance)
    assert [e.field for e in err.errors][:2] == ["stiffness.components.cluster_shaft.shaft", "layout.cluster"]


def test_a_split_pinions_speeds_come_from_its_teeth(tmp_path, capsys):
    """Every component of the split pinion turns at the speed its teeth give (80 / 20 = 4 on the
    pinions' shaft, 1 at the output's mesh); a typed ratio, wrong or right, is refused naming the key."""
    from geargen.drives.resolver import resolve
    from geargen.model.analysis import stiffness

    design = load_design(SPLIT)
    summary, _ = stiffness(design, resolve(design))
    ratios = {c.name: c.ratio for c in summary.components}
    assert ratios == {"mesh_stiff": 1.0, "mesh_compliant": 1.0, "hollow_shaft": 80 / 20, "inner_shaft": 80 / 20,
                      "stiff_support": 80 / 20, "compliant_support": 80 / 20}
    # ratio 5 in the 4:1 drive (the file once typed each ratio, unchecked)
    bad = variant(tmp_path, SPLIT, (r'^gear = "pinion_compliant"\nfrom_geometry = true ',
                                    'gear = "pinion_compliant"\nratio = 5.0\nfrom_geometry = true '))
    code, err = run(capsys, "stiffness", bad, "--no-plots")
    assert code == 2
    assert "stiffness.components.inner_shaft.ratio: 5 typed, but the teeth give 4 for the shaft of " \
           "gears.pinion_compliant" in err
    # a ratio instead of the shaft: the teeth's speeds of both shafts are named, even when it agrees
    hollow = r'^kind = "shaft_torsion"\ngear = "pinion_stiff"\nfrom_geometry = true .*$'
    typed = 'kind = "shaft_torsion"\ndiameter_mm = 16\nbore_diameter_mm = 9.5\nlength_mm = 72\n'
    bad = variant(tmp_path, SPLIT, (hollow, typed + "ratio = 4.0"))
    code, err = run(capsys, "stiffness", bad, "--no-plots")
    assert code == 2
    assert "stiffness.components.hollow_shaft.ratio: 4 typed, but the teeth give the shafts' speeds: 'input' 4, " \
           "'output' 1" in err
    # a split pinion has no cluster, and no other train
    err = error_of(variant(tmp_path, SPLIT, (hollow, typed + 'shaft = "cluster"')))
    assert err.field == "stiffness.components.hollow_shaft.shaft" and err.allowed == "'input', 'output'"
    err = error_of(variant(tmp_path, SPLIT, (r'^reduce_to = "output"', 'reduce_to = "output"\ntrain = "custom"')))
    assert err.field == "stiffness.train" and err.allowed == "'split_pinion' (or leave train out)"
    err = error_of(variant(tmp_path, ROBOT, (r"^reduce_to = ", 'train = "split_pinion"\nreduce_to = ')))
    assert err.field == "stiffness.train" and "needs [layout] kind = 'split_pinion'" in err.problem
    # the two pinions turn together, so they have one tooth count
    err = error_of(variant(tmp_path, SPLIT, (r"^teeth = 20\nface_width_mm = 8", "teeth = 21\nface_width_mm = 8")))
    assert err.field == "gears.pinion_compliant.teeth" and err.allowed == "20"


def test_a_moved_layout_key_names_its_one_home(tmp_path, capsys):
    # [layout] disengaged_clearance was read by no step: the retracted pinions' gap is [engagement] clearance_*
    bad = variant(tmp_path, C_AXIS, (r'^position = "engaged"', 'position = "engaged"\ndisengaged_clearance_mm = 3'))
    code, err = run(capsys, "stiffness", bad, "--no-plots")
    assert code == 2
    assert err.startswith("geargen stiffness: error: layout.disengaged_clearance_mm: no longer a key of [layout]: "
                          "the retracted pinions' axial gap has one home, [engagement] clearance_<unit>")
    assert "unknown key" not in err


def test_shipped_designs_load_and_pass_synth_and_stiffness(tmp_path, capsys):
    for path in (ROBOT, C_AXIS, SPLIT):
        load_design(path)
    for path in (ROBOT, C_AXIS):
        assert run(capsys, "synth", path)[0] == 0
    for path in (ROBOT, C_AXIS, SPLIT):
        assert run(capsys, "stiffness", path, "--no-plots")[0] == 0


# ------------------------------------------------------------------ the printed limit is itself accepted

def _accepts(tmp_path, source, edits, name="ok") -> bool:
    try:
        load_design(variant(tmp_path, source, *edits, name=name))
    except DesignError:
        return False
    return True


@pytest.mark.parametrize("source, line, key, bad, bound_of", [
    (ROBOT, r"^thinning_circumferential_in = 0\.000452", "thinning_circumferential_in", "0.02",
     lambda allowed: allowed.split(", ")[1].split()[0]),
    (ROBOT, r"^travel_in = 0\.020 ", "travel_in", "0.2", lambda allowed: allowed.split(", ")[1].split()[0]),
    (C_AXIS, r"^backlash_mm = 0\.08 ", "backlash_mm", "10", lambda allowed: allowed.split(", ")[1].split()[0]),
    (SPLIT, r"^teeth = 20\nface_width_mm = 12", "profile_shift", "1.4", lambda allowed: allowed.split()[-1]),
])
def test_the_printed_limit_is_accepted_and_a_little_past_it_is_not(tmp_path, source, line, key, bad, bound_of):
    def edit(value):
        if key == "profile_shift":
            return (line, f"teeth = 20\nprofile_shift = {value}\nface_width_mm = 12")
        return (line, f"{key} = {value} ")

    err = error_of(variant(tmp_path, source, edit(bad), name="bad"))
    limit = float(bound_of(err.allowed))
    assert _accepts(tmp_path, source, [edit(repr(limit))])
    assert not _accepts(tmp_path, source, [edit(repr(limit * 1.001))])


def test_a_transverse_profile_shift_is_bounded_in_the_transverse_system(tmp_path):
    data = load_toml(C_AXIS)
    pinion = data["gears"]["cluster_small"]
    pinion.update(pitch_system="transverse", module_mm=2.5 / math.cos(math.radians(15)), profile_shift=1.4,
                  pressure_angle_deg=math.degrees(math.atan(math.tan(math.radians(20)) / math.cos(math.radians(15)))))
    with pytest.raises(DesignError) as info:
        design_from_dict(data, validate=True)
    assert info.value.field == "gears.cluster_small.profile_shift"
    bound = float(info.value.allowed.split()[-1])
    # the same tooth in the normal system: x_n = x_t / cos(beta); its tip land is just the limit
    from geargen.core.involute import tip_land_thickness
    from geargen.design.gear import with_changes
    spec = load_design(C_AXIS).gear("cluster_small")
    land = tip_land_thickness(with_changes(spec, profile_shift=bound / math.cos(math.radians(15))))
    assert 1e-3 * spec.module <= land < 1e-3 * spec.module + 1e-3


def test_springs_too_short_for_the_swept_wire_model_name_the_key_and_the_alternative(tmp_path, capsys):
    # above the solid height (0.27 in) but below d (Nt + 1) = 0.045 x 7 = 0.315 in, where the swept
    # helix of the parts model would close
    bad = variant(tmp_path, ROBOT, (r"^installed_length_in = 0\.35", "installed_length_in = 0.30"))
    code, err = run(capsys, "build", bad, "--out", tmp_path / "out", "--quiet")
    assert code == 2 and not (tmp_path / "out").exists()
    assert "springs.installed_length_in: 0.3 in is too short for the swept-wire model" in err
    assert "> 0.315 in, or parts.spring_model = 'envelope'" in err
    assert _accepts(tmp_path, ROBOT, [(r"^installed_length_in = 0\.35", "installed_length_in = 0.30"),
                                      (r'^spring_model = "helix"', 'spring_model = "envelope"')])


@pytest.mark.parametrize("source, edit, key, owner", [
    # a rack drive given the split pinion's centre distance: it would place nothing
    ("rack_drive.toml", (r"^pinion_spacing_mm", "centre_distance_mm = 50\npinion_spacing_mm"), "centre_distance_mm",
     "'split_pinion' and 'axial_preload'"),
    ("axial_preload.toml", (r"^input_stroke_mm", "slide_travel_mm = 100\ninput_stroke_mm"), "slide_travel_mm",
     "'rack_dual_pinion'"),
    ("split_pinion.toml", (r"^\[layout\]", "[layout]\ncluster = \"separate\""), "cluster", "'dual_pinion'"),
    ("robot_joint.toml", (r"^\[layout\]", "[layout]\ninput_stroke_in = 0.02"), "input_stroke_in", "'axial_preload'"),
])
def test_a_layout_key_of_another_kind_is_refused_by_name(tmp_path, capsys, source, edit, key, owner):
    """[layout] holds the keys of every drive kind; one the design's kind does not read is refused
    (it would change nothing quietly), naming the key and the kind that reads it."""
    code, err = run(capsys, "check", variant(tmp_path, ROOT / "assemblies" / source, edit))
    assert code == 2
    assert f"layout.{key}: does not apply to layout.kind" in err and f"(a key of {owner})" in err
