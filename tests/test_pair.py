"""``geargen pair``: published cases through the command line, the inverse, backlash against a
closed form written out here, units, the printed table against the JSON, bad input."""

import json
import math
import pathlib
import re
import subprocess
import sys
import tomllib

import pytest

from geargen.cli import main

DATA = tomllib.loads((pathlib.Path(__file__).parent / "data" / "published_cases.toml").read_text())
DEG = math.pi / 180


def printed(computed: float, text: str) -> bool:
    """True when ``computed`` rounds to the printed ``text`` (within half a unit of its last digit)."""
    decimals = len(text.split(".")[1]) if "." in text else 0
    return abs(computed - float(text)) <= 0.5 * 10.0 ** (-decimals) * (1 + 1e-9)


def inv(angle: float) -> float:
    return math.tan(angle) - angle


def pair(capsys, *options: str) -> tuple[dict, str]:
    """Run ``geargen pair OPTIONS --json -``; the JSON (standard output) and the table (standard error)."""
    code = main(["pair", *options, "--json", "-"])
    out, err = capsys.readouterr()
    assert code == 0, err
    return json.loads(out), err


def refused(capsys, *options: str) -> str:
    """Run ``geargen pair OPTIONS``, expecting bad input: exit status 2; returns standard error."""
    try:
        code = main(["pair", *options])
    except SystemExit as exc:  # argparse's own refusals
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2, err
    assert "Traceback" not in err
    return err


def args_of(case: dict) -> list[str]:
    return ["--teeth", *map(str, case["teeth"]), "--module", str(case["module_mm"]),
            "--pressure-angle", str(case["pressure_angle_deg"])]


# ---------------------------------------------------------------------------------------------
# Published cases (tests/data/published_cases.toml)
# ---------------------------------------------------------------------------------------------

def test_shifted_spur_pair(capsys):
    # [shifted_spur]: m 3 mm, 20 deg, z 12/24, x 0.6/0.36 (KHK-style profile-shifted pair, issue 2);
    # issue 11 quotes the same pair to more digits: alpha_w 26.08856 deg, a 56.49987 mm
    c = DATA["shifted_spur"]
    data, _ = pair(capsys, *args_of(c), "--profile-shift", *map(str, c["profile_shift"]))
    e = c["expected"]
    assert data["length_unit"] == "mm"
    assert printed(data["working_pressure_angle_transverse_deg"], e["working_pressure_angle_deg"])
    assert printed(data["working_pressure_angle_transverse_deg"], "26.08856")
    assert printed(data["centre_distance"]["operating"], e["centre_distance_mm"])
    assert printed(data["centre_distance"]["working"], "56.49987")
    assert data["centre_distance"]["standard"] == pytest.approx(54.0, rel=1e-15)  # (12 + 24) 3 / 2
    # the published contact ratio uses tips shortened to constant clearance (see the data file)
    assert c["tip_radii"] == "constant_clearance"
    assert printed(data["contact_ratio_constant_clearance"]["transverse"], e["transverse_contact_ratio"])
    # no --centre-distance: zero backlash at the working centre distance, no inverse asked for
    assert data["backlash"]["circumferential_reference"] == pytest.approx(0.0, abs=1e-12)
    assert data["shift_sum_for_zero_backlash"] is None
    assert data["profile_shift_source"].startswith("given")


def test_shifted_spur_pair_inverse(capsys):
    # [shifted_spur.inverse]: a' = 56.4999 mm needs x1 + x2 = 0.9600 (issue 11: 0.96001)
    c = DATA["shifted_spur"]
    a = c["inverse"]["centre_distance_mm"]
    data, table = pair(capsys, *args_of(c), "--centre-distance", str(a))
    assert printed(data["shift_sum_for_zero_backlash"], c["inverse"]["shift_sum"])
    assert printed(data["shift_sum_for_zero_backlash"], "0.96001")
    # without --profile-shift the shifts are the recommended split of that sum, meshing tight at a'
    assert data["profile_shift_source"].startswith("recommended split")
    assert sum(data["profile_shift"]) == pytest.approx(data["shift_sum_for_zero_backlash"], abs=1e-12)
    assert data["centre_distance"]["working"] == pytest.approx(a, rel=1e-12)
    assert data["backlash"]["circumferential_reference"] == pytest.approx(0.0, abs=1e-12)
    assert "with the recommended shifts: from the tooth thinning only" in table


def test_helical_pair(capsys):
    # [helical_normal_system]: m_n 3, beta 30 deg, z 12/60, x_n 0.09809/0, b 20 mm (issue 2);
    # issue 11 to more digits: a = 125.0000012 mm, alpha_t 22.795877 deg, alpha_wt 23.112634 deg
    c = DATA["helical_normal_system"]
    data, table = pair(capsys, *args_of(c), "--helix-angle", str(c["helix_angle_deg"]), "--hand", c["hands"][0],
                       "--profile-shift", *map(str, c["profile_shift"]), "--face-width", str(c["face_width_mm"]))
    e = c["expected"]
    assert printed(data["centre_distance"]["operating"], e["centre_distance_mm"])
    assert printed(data["centre_distance"]["operating"], "125.0000012")
    assert printed(data["transverse_pressure_angle_deg"], e["transverse_pressure_angle_deg"])
    assert printed(data["transverse_pressure_angle_deg"], "22.795877")
    assert printed(data["working_pressure_angle_transverse_deg"], e["working_pressure_angle_deg"])
    assert printed(data["working_pressure_angle_transverse_deg"], "23.112634")
    assert printed(data["contact_ratio_constant_clearance"]["transverse"], e["transverse_contact_ratio"])
    assert printed(data["contact_ratio"]["overlap"], e["face_contact_ratio"])
    cr = data["contact_ratio"]
    assert cr["total"] == pytest.approx(cr["transverse"] + cr["overlap"], rel=1e-14)
    assert data["hands"] == c["hands"]  # gear 2 gets the opposite hand
    # normal working pressure angle: tan(alpha_wn) = tan(alpha_wt) cos(beta_w), with the working
    # helix angle tan(beta_w) = tan(beta) d_w / d
    g1 = data["gears"][0]
    beta_w = math.atan(math.tan(30 * DEG) * g1["working_pitch_diameter"] / g1["reference_diameter"])
    alpha_wn = math.atan(math.tan(data["working_pressure_angle_transverse_deg"] * DEG) * math.cos(beta_w))
    assert data["working_pressure_angle_normal_deg"] == pytest.approx(alpha_wn / DEG, rel=1e-12)
    assert "working pressure angle, normal (deg)" in table


def test_helical_pair_without_face_width_gives_no_overlap_ratio(capsys):
    c = DATA["helical_normal_system"]
    data, table = pair(capsys, *args_of(c), "--helix-angle", "30")
    assert data["contact_ratio"]["overlap"] is None and data["contact_ratio"]["total"] is None
    assert any("--face-width" in w for w in data["warnings"])


def test_paper_gears_in_inches(capsys):
    # [paper_robot_joint]: Hale & Slocum's Appendix, 16/48 and 21/112 teeth at 32 DP, 20 deg
    c = DATA["paper_robot_joint"]
    e = c["expected"]
    for mesh, text in zip(c["meshes"], e["standard_centre_distance_in"]):
        teeth = [c["teeth"][i] for i in mesh]
        data, table = pair(capsys, "--teeth", *map(str, teeth), "--diametral-pitch", str(c["diametral_pitch_per_in"]),
                           "--pressure-angle", str(c["pressure_angle_deg"]))
        assert data["length_unit"] == "in" and "lengths in in" in table
        for g, i in zip(data["gears"], mesh):
            assert printed(g["reference_diameter"], e["reference_diameter_in"][i])
            assert g["reference_diameter"] == pytest.approx(float(e["reference_diameter_in"][i]), rel=1e-14)
            # full-depth 32 DP: tip d + 2/P, root d - 2.5/P (h_f* = 1.25)
            assert g["tip_diameter"] == pytest.approx(g["reference_diameter"] + 2 / 32, rel=1e-14)
            assert g["root_diameter"] == pytest.approx(g["reference_diameter"] - 2.5 / 32, rel=1e-14)
            assert g["base_diameter"] == pytest.approx(g["reference_diameter"] * math.cos(20 * DEG), rel=1e-14)
        assert printed(data["centre_distance"]["standard"], text)
        assert data["centre_distance"]["standard"] == pytest.approx(float(text), rel=1e-14)


def test_paper_backlash_at_c1(capsys):
    # The Appendix runs mesh 1 (16/48, 32 DP, 20 deg, standard C = 1.000 in) at C1 = 1.004 in
    # (../shared/paper/appendix-notes.md: operating pressure angle 20.62 deg there).
    data, table = pair(capsys, "--teeth", "16", "48", "--diametral-pitch", "32", "--profile-shift", "0", "0",
                       "--centre-distance", "1.004")
    assert data["length_unit"] == "in"
    c0, c1, phi = 1.0, 1.004, 20 * DEG
    alpha_w = math.acos(c0 * math.cos(phi) / c1)
    assert printed(data["working_pressure_angle_transverse_deg"], "20.62")
    assert data["working_pressure_angle_transverse_deg"] == pytest.approx(alpha_w / DEG, rel=1e-13)
    # unshifted, unthinned teeth opened from C to C1: the working pitch less the two tooth
    # thicknesses 2 r_w (pi/(2z) + inv(phi) - inv(alpha_w)) leaves j_wt = 2 C1 (inv(alpha_w) - inv(phi));
    # on the reference circles that is j_t = 2 C (inv(alpha_w) - inv(phi)); along the line of action
    # j_wt cos(alpha_w)
    j_wt = 2 * c1 * (inv(alpha_w) - inv(phi))
    b = data["backlash"]
    assert b["circumferential_working_pitch"] == pytest.approx(j_wt, rel=1e-10)
    assert b["circumferential_reference"] == pytest.approx(2 * c0 * (inv(alpha_w) - inv(phi)), rel=1e-10)
    assert b["line_of_action"] == pytest.approx(j_wt * math.cos(alpha_w), rel=1e-10)
    assert b["normal"] == pytest.approx(b["line_of_action"], rel=1e-15)  # spur
    # and the paper's small-change relation, backlash = 2 dC tan(phi) = 0.0029 in (appendix notes §5)
    assert b["circumferential_reference"] == pytest.approx(2 * (c1 - c0) * math.tan(phi), rel=0.02)
    assert printed(b["circumferential_reference"], "0.0030")
    # angular backlash of each gear, the other held: j_wt / r_w
    r_w1 = data["gears"][0]["working_pitch_diameter"] / 2
    assert b["angular_arcmin"][0] == pytest.approx(j_wt / r_w1 * 180 * 60 / math.pi, rel=1e-10)
    assert "at --centre-distance with the given shifts: from the centre distance and the tooth thinning" in table
    # the inverse is reported too: the shift sum that would close the gap at 1.004 in
    x_sum = 64 * (inv(alpha_w) - inv(phi)) / (2 * math.tan(phi))
    assert data["shift_sum_for_zero_backlash"] == pytest.approx(x_sum, rel=1e-10)


def test_thinning_is_the_backlash_at_the_working_centre_distance(capsys):
    data, _ = pair(capsys, "--teeth", "12", "24", "--module", "3", "--profile-shift", "0.6", "0.36",
                   "--thinning", "0.04", "0.06")
    b = data["backlash"]
    # the shifts' working centre distance meshes unthinned teeth tight: the free play on the
    # reference circles is the thinning taken off there, along the line of action times cos(alpha)
    assert b["circumferential_reference"] == pytest.approx(0.10, rel=1e-10)
    assert b["line_of_action"] == pytest.approx(0.10 * math.cos(20 * DEG), rel=1e-10)
    assert data["thinning_circumferential"] == [0.04, 0.06]


def test_metric_and_inch_give_the_same_pair_in_their_units(capsys):
    mm, _ = pair(capsys, "--teeth", "16", "48", "--module", str(25.4 / 32), "--profile-shift", "0.2", "0.1",
                 "--centre-distance", str(1.01 * 25.4))
    inch, _ = pair(capsys, "--teeth", "16", "48", "--diametral-pitch", "32", "--profile-shift", "0.2", "0.1",
                   "--centre-distance", "1.01")
    assert (mm["length_unit"], inch["length_unit"]) == ("mm", "in")
    for key in ("reference_diameter", "tip_diameter", "root_diameter", "working_pitch_diameter"):
        for g_mm, g_in in zip(mm["gears"], inch["gears"]):
            assert g_mm[key] == pytest.approx(25.4 * g_in[key], rel=1e-12)
    for key in ("circumferential_reference", "line_of_action", "normal"):
        assert mm["backlash"][key] == pytest.approx(25.4 * inch["backlash"][key], rel=1e-9)
    assert mm["working_pressure_angle_transverse_deg"] == pytest.approx(inch["working_pressure_angle_transverse_deg"],
                                                                         rel=1e-12)


# ---------------------------------------------------------------------------------------------
# Per-gear quantities
# ---------------------------------------------------------------------------------------------

def test_undercut_and_minimum_shift(capsys):
    data, table = pair(capsys, "--teeth", "16", "48", "--diametral-pitch", "32")
    g1, g2 = data["gears"]
    # the default rack: h_f* 1.25 with the full 0.25 m clearance rounded (tip radius 0.25/(1 - sin 20 deg)),
    # so its straight flank ends 1.0 m beyond the datum: x_min = 1 - z sin^2(20 deg) / 2
    assert g1["minimum_profile_shift_without_undercut"] == pytest.approx(1 - 16 * math.sin(20 * DEG) ** 2 / 2, abs=1e-12)
    assert g1["undercut"] and not g2["undercut"]  # 16 teeth unshifted: below the classical 17.1
    assert any("gear 1 is undercut" in w for w in data["warnings"])


def test_span_matches_published_case(capsys):
    # [span_spur]: m 2, 20 deg, z 20, x 0: k = 3, W = 15.321 mm (gear 1 of a 20/40 pair)
    c = DATA["span_spur"]
    data, _ = pair(capsys, "--teeth", str(c["teeth"]), "40", "--module", str(c["module_mm"]))
    span = data["gears"][0]["span"]
    assert span["teeth_spanned"] == c["expected"]["teeth_spanned"]
    assert printed(span["span_normal"], c["expected"]["span_mm"])
    assert printed(2 * span["contact_radius"], c["expected"]["contact_diameter_mm"])


def test_over_pins_of_an_unshifted_spur_gear(capsys):
    # pins touching at the reference circle of an unshifted spur gear: the pin centre's pressure
    # angle has inv(alpha_c) = pi/(2z) + inv(alpha) + D/d_b - pi/z and tan(alpha_c) = tan(alpha) + D/d_b
    # (the pin's contact point is D/2 along the base tangent from its centre); even z: M = d_b/cos(alpha_c) + D
    data, _ = pair(capsys, "--teeth", "20", "40", "--module", "2")
    g = data["gears"][0]
    d_b, D = g["base_diameter"], g["over_pins"]["diameter"]
    alpha = 20 * DEG
    assert inv(math.atan(math.tan(alpha) + D / d_b)) == pytest.approx(inv(alpha) + D / d_b - math.pi / 40, abs=1e-12)
    alpha_c = math.atan(math.tan(alpha) + D / d_b)
    assert g["over_pins"]["dimension"] == pytest.approx(d_b / math.cos(alpha_c) + D, rel=1e-12)
    assert g["over_pins"]["kind"] == "pins"


def test_pointed_teeth_are_reported(capsys):
    data, table = pair(capsys, "--teeth", "8", "60", "--module", "1", "--profile-shift", "1.2", "0")
    land = data["gears"][0]["tip_land"]
    assert land["pointed"] and land["transverse"] <= 0
    assert any("pointed teeth" in w for w in data["warnings"]) and "pointed teeth" in table


def test_recommended_split_is_stated_and_sums(capsys):
    data, table = pair(capsys, "--teeth", "12", "24", "--module", "3")
    rec = data["recommended_profile_shift"]
    assert rec["shift_sum"] == 0.0 and sum(rec["profile_shift"]) == pytest.approx(0.0, abs=1e-12)
    assert rec["specific_sliding_root"][0] == pytest.approx(rec["specific_sliding_root"][1], rel=1e-8)
    assert rec["profile_shift"][0] >= data["gears"][0]["minimum_profile_shift_without_undercut"]
    assert "rule: equal specific sliding at the two roots" in table


# ---------------------------------------------------------------------------------------------
# The table and the JSON agree
# ---------------------------------------------------------------------------------------------

ROWS = [  # printed label, the JSON value(s) it shows, whether they are lengths
    ("reference diameter d", lambda d: [g["reference_diameter"] for g in d["gears"]], True),
    ("base diameter d_b", lambda d: [g["base_diameter"] for g in d["gears"]], True),
    ("tip diameter d_a", lambda d: [g["tip_diameter"] for g in d["gears"]], True),
    ("root diameter d_f", lambda d: [g["root_diameter"] for g in d["gears"]], True),
    ("working pitch diameter d_w", lambda d: [g["working_pitch_diameter"] for g in d["gears"]], True),
    ("span W_k, normal", lambda d: [g["span"]["span_normal"] for g in d["gears"]], True),
    ("dimension over pins M", lambda d: [g["over_pins"]["dimension"] for g in d["gears"]], True),
    ("profile shift x (normal)", lambda d: d["profile_shift"], False),
    ("standard centre distance a", lambda d: [d["centre_distance"]["standard"]], True),
    ("operating centre distance a'", lambda d: [d["centre_distance"]["operating"]], True),
    ("working pressure angle, transverse", lambda d: [d["working_pressure_angle_transverse_deg"]], False),
    ("contact ratio: transverse eps_alpha", lambda d: [d["contact_ratio"]["transverse"]], False),
    ("circumferential, at the reference circles", lambda d: [d["backlash"]["circumferential_reference"]], True),
    ("along the line of action", lambda d: [d["backlash"]["line_of_action"]], True),
    ("normal to the flanks", lambda d: [d["backlash"]["normal"]], True),
    ("angular, the other gear held (arcmin)", lambda d: d["backlash"]["angular_arcmin"], False),
    ("x1 + x2 for zero backlash at a'", lambda d: [d["shift_sum_for_zero_backlash"]], False),
    ("per face width c_gamma_alpha | E/11", lambda d: [d["iso6336"]["mesh_stiffness_N_per_mm_um"],
                                                       d["eq1"]["stiffness_per_face_width_N_per_mm_um"]], False),
    ("single stiffness c'", lambda d: [d["iso6336"]["single_stiffness_N_per_mm_um"]], False),
]


@pytest.mark.parametrize("options", [
    ["--teeth", "16", "48", "--diametral-pitch", "32", "--profile-shift", "0", "0", "--centre-distance", "1.004"],
    ["--teeth", "12", "24", "--module", "3", "--profile-shift", "0.6", "0.36", "--centre-distance", "56.6",
     "--thinning", "0.02", "0.03"],
])
def test_printed_table_agrees_with_json_file(tmp_path, options):
    # through the real command line: the table on standard output, the JSON into a file
    target = tmp_path / "pair.json"
    run = subprocess.run([sys.executable, "-m", "geargen.cli", "pair", *options, "--json", str(target)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    data = json.loads(target.read_text())
    lines = run.stdout.splitlines()
    unit = data["length_unit"]
    assert f"lengths in {unit}" in run.stdout
    for label, values, is_length in ROWS:
        line = next(l for l in lines if l.startswith(label))  # the first such row: the gears' table
        numbers = re.findall(r"-?\d+\.\d+", line[50:])[:len(values(data))]
        assert len(numbers) == len(values(data)), line
        for text, value in zip(numbers, values(data)):
            assert printed(value, text), f"{line!r}: JSON {value}"
        if is_length:
            assert f"({unit})" in line  # every printed length names its unit


def test_json_to_standard_output_moves_the_table_to_standard_error(capsys):
    code = main(["pair", "--teeth", "20", "40", "--module", "2", "--json", "-"])
    out, err = capsys.readouterr()
    assert code == 0
    data = json.loads(out)  # nothing but the JSON
    assert data["generator"] == "geargen pair" and "reference diameter d (mm)" in err


# ---------------------------------------------------------------------------------------------
# Mesh stiffness per ISO 6336-1:2019 method B, beside Eq. 1
# ---------------------------------------------------------------------------------------------

TR_6336_30_EXAMPLE_1 = ["--teeth", "17", "103", "--module", "8", "--pressure-angle", "20", "--helix-angle", "15.8",
                        "--profile-shift", "0.145", "0", "--face-width", "100", "--centre-distance", "500",
                        "--dedendum-coefficient", "1.4", "--elastic-modulus", "206"]


def test_iso6336_block_of_the_tr_6336_30_example_1(capsys):
    # ISO/TR 6336-30:2017 Annex A example 1 (basic rack h_fP 1.4 m_n, steel E_st 206 GPa): the published
    # c' 12.37047 and c_gamma_alpha 17.46485 N/(mm um), as tabulated in the "Reference" column of
    # MATISO_6336.example_01 in github.com/gfsReboucas/Drivetrain; its load (1273 N/mm) needs no correction
    data, table = pair(capsys, *TR_6336_30_EXAMPLE_1)
    block = data["iso6336"]
    assert block["method"] == "ISO 6336-1:2019 method B"
    assert block["single_stiffness_N_per_mm_um"] == pytest.approx(12.37047, rel=1e-3)
    assert block["mesh_stiffness_N_per_mm_um"] == pytest.approx(17.46485, rel=1e-2)
    assert block["mesh_stiffness_beta_N_per_mm_um"] == pytest.approx(14.84512, rel=1e-2)
    # one truth: eps_alpha is the pair's reported contact ratio; the whole mesh is c_gamma_alpha b
    assert block["transverse_contact_ratio"] == data["contact_ratio"]["transverse"]
    assert block["mesh_stiffness_whole_N_per_um"] == pytest.approx(block["mesh_stiffness_N_per_mm_um"] * 100, rel=1e-15)
    assert block["load_factor"] == 1.0 and block["specific_load_N_per_mm"] is None
    # Eq. 1 beside it for the same face: E / 11 per mm of face, E b / 11 for the mesh (N/um)
    assert data["eq1"]["stiffness_per_face_width_N_per_mm_um"] == pytest.approx(206.0 / 11, rel=1e-15)
    assert data["eq1"]["stiffness_whole_N_per_um"] == pytest.approx(206.0 * 100 / 11, rel=1e-15)
    line = next(l for l in table.splitlines() if l.startswith("whole mesh c_gamma_alpha b | E b/11"))
    assert line.split()[-2:] == [f"{block['mesh_stiffness_whole_N_per_um']:.2f}", f"{206.0 * 100 / 11:.2f}"]


def test_a_light_load_lowers_c_prime_by_the_fourth_root(capsys):
    # 2000 N over 100 mm: 20 N/mm < 100 N/mm, c' times (20/100)^0.25 (ISO 6336-1 method B)
    full, _ = pair(capsys, *TR_6336_30_EXAMPLE_1)
    light, _ = pair(capsys, *TR_6336_30_EXAMPLE_1, "--load", "2000")
    ratio = light["iso6336"]["single_stiffness_N_per_mm_um"] / full["iso6336"]["single_stiffness_N_per_mm_um"]
    assert ratio == pytest.approx(0.2 ** 0.25, rel=1e-14)
    assert light["iso6336"]["specific_load_N_per_mm"] == pytest.approx(20.0, rel=1e-15)
    # a heavy one changes nothing
    heavy, _ = pair(capsys, *TR_6336_30_EXAMPLE_1, "--load", "127352")
    assert heavy["iso6336"]["single_stiffness_N_per_mm_um"] == full["iso6336"]["single_stiffness_N_per_mm_um"]


def test_default_material_is_geargens_steel_for_both_methods(capsys):
    # no --elastic-modulus: geargen's steel (207 GPa, the [stiffness] default) in Eq. 1 and as E / E_st
    data, _ = pair(capsys, "--teeth", "20", "40", "--module", "2")
    assert data["eq1"]["elastic_modulus_MPa"] == 207e3
    assert data["iso6336"]["material_factor_E_over_E_st"] == pytest.approx(207 / 206, rel=1e-15)
    assert data["eq1"]["stiffness_whole_N_per_um"] is None and data["iso6336"]["mesh_stiffness_whole_N_per_um"] is None


# ---------------------------------------------------------------------------------------------
# Bad input: exit status 2, naming the option and what it allows
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("options, flag, allowed", [
    (["--teeth", "3", "24", "--module", "3"], "--teeth", "[4, 2000]"),
    (["--teeth", "12", "2001", "--module", "3"], "--teeth", "gear 2"),
    (["--teeth", "12", "24", "--module", "0"], "--module", "(0.01, 200] mm"),
    (["--teeth", "12", "24", "--diametral-pitch", "-32"], "--diametral-pitch", "[0.127, 2540)"),
    (["--teeth", "12", "24", "--module", "3", "--pressure-angle", "50"], "--pressure-angle", "[10, 35] deg"),
    (["--teeth", "12", "24", "--module", "3", "--helix-angle", "60"], "--helix-angle", "[0, 45] deg"),
    (["--teeth", "12", "24", "--module", "3", "--profile-shift", "2", "0"], "--profile-shift", "[-1.5, 1.5]"),
    (["--teeth", "12", "24", "--module", "3", "--profile-shift", "-1.5", "0"], "--profile-shift", "> -1.36184"),
    (["--teeth", "12", "24", "--module", "3", "--profile-shift", "-1.3", "-1.5"], "--profile-shift",
     "x1 + x2 >"),
    (["--teeth", "12", "24", "--module", "3", "--face-width", "0"], "--face-width", "> 0 mm"),
    (["--teeth", "12", "24", "--module", "3", "--thinning", "0", "5"], "--thinning", "[0, 2.35619] mm"),
    (["--teeth", "12", "24", "--module", "3", "--centre-distance", "40"], "--centre-distance", "> 50.7434 mm"),
    (["--teeth", "12", "24", "--diametral-pitch", "8", "--centre-distance", "1"], "--centre-distance", "> 2.11431 in"),
    (["--teeth", "12", "24", "--module", "3", "--centre-distance", "80"], "--centre-distance", "60.7011] mm"),
    (["--teeth", "12", "24", "--module", "3", "--centre-distance", "nan"], "--centre-distance", "> 50.7434 mm"),
    (["--teeth", "12", "24", "--module", "3", "--hand", "left"], "--hand", "--helix-angle > 0"),
    (["--teeth", "12", "24"], "--module", "--diametral-pitch"),
    (["--teeth", "12", "24", "--module", "3", "--diametral-pitch", "8"], "--diametral-pitch", "--module"),
    (["--teeth", "12", "--module", "3"], "--teeth", "2 arguments"),
    (["--teeth", "12", "24", "--module", "3", "--load", "500"], "--load", "--load with --face-width"),
    (["--teeth", "12", "24", "--module", "3", "--face-width", "10", "--load", "-5"], "--load", "> 0 N"),
    (["--teeth", "12", "24", "--module", "3", "--elastic-modulus", "0"], "--elastic-modulus", "> 0 GPa"),
    (["--teeth", "12", "24", "--module", "3", "--dedendum-coefficient", "3"], "--dedendum-coefficient", "[0.5, 2]"),
])
def test_bad_input_names_the_option(capsys, options, flag, allowed):
    err = refused(capsys, *options)
    assert flag in err and allowed in err


def test_centre_distance_error_without_shifts_is_in_inches_for_an_inch_design(capsys):
    err = refused(capsys, "--teeth", "16", "48", "--diametral-pitch", "32", "--centre-distance", "1.2")
    assert "--centre-distance" in err and "] in" in err and "mm" not in err


# ---------------------------------------------------------------------------------------------
# Fast: no CAD kernel
# ---------------------------------------------------------------------------------------------

def test_pair_command_does_not_load_the_cad_kernel():
    code = ("import sys; import geargen.commands.pair, geargen.report.pair; "
            "from geargen.cli import main; import io, contextlib\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    assert main(['pair', '--teeth', '12', '24', '--module', '3', '--centre-distance', '56.5']) == 0\n"
            "print(','.join(m for m in sys.modules if m.split('.')[0] in ('cadquery', 'OCP', 'trimesh', 'matplotlib')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == ""
