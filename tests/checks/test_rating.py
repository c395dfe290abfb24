"""Load capacity of every mesh of a drive (geargen.checks.rating, issue 29 phase 2): ISO 6336-2/-3
method B over the duty, the ISO 6336-6 sum, S_H and S_F per mesh and flank with the preload in, the
face width a type 1's compliant path needs. A spur (robot joint) and a helical (C-axis) mesh are
worked by hand from the stiffness model's loads; the four shipped drives are rated."""

import json
import math
import tomllib
from pathlib import Path

import pytest

from geargen.checks.rating import rate_drive
from geargen.core.iso6336_materials import Material
from geargen.core.load_capacity import RatingConditions, rate_mesh, rate_pair
from geargen.design.assembly import design_from_dict
from geargen.drives.resolver import resolve
from geargen.model.mesh_loads import PRELOAD

ROOT = Path(__file__).resolve().parents[2]
IN = 25.4
SHIPPED = ("robot_joint", "c_axis", "split_pinion", "split_pinion_inch")
#: the keys of the contract's load_capacity block (shared/contracts/load-capacity.md)
CONTRACT_KEYS = ("standard", "F_t", "v", "K_A", "K_v", "K_Hbeta", "K_Halpha", "K_Fbeta", "K_Falpha", "Z_H", "Z_E",
                 "Z_eps", "Z_beta", "Z_BD", "sigma_H0", "sigma_H", "N_L", "Z_NT", "Z_L", "Z_v", "Z_R", "Z_W", "Z_X",
                 "sigma_HP", "S_H", "Y_F", "Y_S", "Y_beta", "Y_B", "Y_DT", "sigma_F0", "sigma_F", "Y_NT",
                 "Y_deltarelT", "Y_RrelT", "Y_X", "sigma_FP", "S_F", "S_Hmin", "S_Fmin", "ok")
#: a duty under which the shipped gears carry their loads: case carburised, ground (R_a 0.4 um,
#: grade 5), ISO VG 220
HARDENED = ("[duty]\nmaterial = \"case_carburised\"\naccuracy_grade = 5\nroughness_Ra_um = 0.4\n"
            "viscosity_mm2_per_s = 220\n")


def rated(name: str, extra: str = ""):
    """The shipped drive ``name`` rated on geargen's defaults (its own [duty] and [materials] taken
    out), with the sections of ``extra``."""
    data = tomllib.loads((ROOT / "assemblies" / f"{name}.toml").read_text())
    data.pop("duty", None)
    data.pop("materials", None)
    data.update(tomllib.loads(extra))
    return rate_drive(resolve(design_from_dict(data, validate=True)))


def mesh(rating, name):
    return next(m for m in rating.meshes if m.name == name)


def case_at(m, torque):
    """The (load, PairRating) of mesh ``m`` at the duty's output torque ``torque`` (N mm)."""
    return next((load, r) for load, (_, r) in zip(m.loads.loads, m.rating.cases) if load.output_torque == torque)


def involute_contact(z1, z2, m_n, alpha_n, beta, a, tip1, tip2, b):
    """Z_H, Z_eps, Z_beta, eps_alpha, eps_beta of an external pair at centre distance a (ISO 6336-2)."""
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    m_t = m_n / math.cos(beta)
    beta_b = math.atan(math.tan(beta) * math.cos(alpha_t))
    rb1, rb2 = z1 * m_t / 2 * math.cos(alpha_t), z2 * m_t / 2 * math.cos(alpha_t)
    alpha_wt = math.acos((rb1 + rb2) / a)
    z_h = math.sqrt(2 * math.cos(beta_b) * math.cos(alpha_wt) / (math.cos(alpha_t) ** 2 * math.sin(alpha_wt)))
    eps_a = (math.sqrt(tip1 ** 2 - rb1 ** 2) + math.sqrt(tip2 ** 2 - rb2 ** 2) - a * math.sin(alpha_wt)) \
        / (math.pi * m_t * math.cos(alpha_t))
    eps_b = b * math.sin(beta) / (math.pi * m_n)
    z_eps = math.sqrt((4 - eps_a) / 3 * (1 - eps_b) + eps_b / eps_a) if eps_b < 1 else math.sqrt(1 / eps_a)
    return z_h, z_eps, 1 / math.sqrt(math.cos(beta)), eps_a, eps_b


#: Z_E of two steel gears, E 206000 N/mm^2, nu 0.3 (ISO 6336-2)
Z_E = math.sqrt(1 / (math.pi * 2 * (1 - 0.3 ** 2) / 206000))


def test_spur_mesh_of_the_robot_joint_by_hand():
    r = rated("robot_joint")
    m = mesh(r, "mesh2_a")  # cluster_small (21 T) on the output (112 T), 32 DP, spur, standard centres
    summary_preload = r.preload
    torque = 5000.0
    load, pair = case_at(m, torque)
    # the load: preload plus half the drive torque (equal paths, Eq. 5), at the output's 1.75 in radius
    f_t = (summary_preload + torque / 2) / (1.75 * IN)
    assert load.tangential_load == pytest.approx(f_t, rel=1e-9)  # the same closed form twice
    mod = IN / 32
    g1, g2 = m.loads.gear1, m.loads.gear2
    z_h, z_eps, z_beta, eps_a, _ = involute_contact(21, 112, mod, math.radians(20), 0.0, m.loads.centre_distance,
                                                    g1.tip_radius, g2.tip_radius, 0.25 * IN)
    assert pair["Z_H"] == pytest.approx(z_h, rel=1e-9)  # mesh geometry solved numerically: ~1e-12 in alpha_wt
    assert pair["eps_alpha"] == pytest.approx(eps_a, rel=1e-9)
    assert pair["Z_E"] == pytest.approx(Z_E, rel=1e-12)
    u = 112 / 21
    sigma_h0 = z_h * Z_E * z_eps * z_beta * math.sqrt(f_t * (u + 1) / (21 * mod * 0.25 * IN * u))
    assert pair["sigma_H0"] == pytest.approx(sigma_h0, rel=1e-9)
    # the cycles: the cluster turns 112/21 x the output's 60 rpm for 20,000 h; the output once per turn
    n_1 = 60 * 112 / 21
    assert pair["N_L"][0] == pytest.approx(60 * n_1 * 20000, rel=1e-12)
    assert pair["N_L"][1] == pytest.approx(60 * 60 * 20000, rel=1e-12)
    # the output is loaded on both flanks (path a here, path b on the other): Y_M = 0.7 (ISO 6336-3)
    assert pair["Y_M"] == [1.0, 0.7] or pair["Y_M"] == (1.0, 0.7)
    # the flank's spectrum: half the life at P + T/2, half at P - T/2. Its safety factor lies between
    # the top level's rated alone over the whole life (more damage) and over half the life (less)
    (flank,) = m.flanks
    whole = pair.S_H[0]
    half_life = rate_pair(pair.geometry, f_t, RatingConditions(**{**m.conditions.__dict__, "life": 10000.0}),
                          (Material("through_hardened", "MQ", 300.0),) * 2, m.loads.reversed_bending)
    assert whole < flank.S_H[0] < half_life.S_H[0]
    assert flank.basis.startswith("spectrum")


def test_helical_mesh_of_the_c_axis_by_hand():
    r = rated("c_axis")
    m = mesh(r, "mesh2_a")  # cluster_small (20 T) on the bull gear (120 T), m_n 2.5, beta 15 deg
    load, pair = case_at(m, 500000.0)
    r_out = 120 * 2.5 / math.cos(math.radians(15)) / 2
    f_t = (300000.0 + 500000.0 / 2) / r_out  # [preload] preload_Nm = 300, max_output_torque_Nm = 500
    assert load.tangential_load == pytest.approx(f_t, rel=1e-9)
    g1, g2 = m.loads.gear1, m.loads.gear2
    z_h, z_eps, z_beta, eps_a, eps_b = involute_contact(20, 120, 2.5, math.radians(20), math.radians(15),
                                                        m.loads.centre_distance, g1.tip_radius, g2.tip_radius, 30.0)
    assert pair["eps_beta"] == pytest.approx(eps_b, rel=1e-12)
    assert pair["eps_alpha"] == pytest.approx(eps_a, rel=1e-9)  # mesh geometry solved numerically
    assert pair["Z_eps"] == pytest.approx(z_eps, rel=1e-9)
    assert pair["Z_beta"] == pytest.approx(z_beta, rel=1e-12)
    u = 120 / 20
    d1 = 20 * 2.5 / math.cos(math.radians(15))
    sigma_h0 = z_h * Z_E * z_eps * z_beta * math.sqrt(f_t * (u + 1) / (d1 * 30.0 * u))
    assert pair["sigma_H0"] == pytest.approx(sigma_h0, rel=1e-9)
    # its preload case: P alone on the working flank
    preload, _ = case_at(m, 0.0)
    assert preload.source == PRELOAD and preload.tangential_load == pytest.approx(300000.0 / r_out, rel=1e-9)


@pytest.mark.parametrize("name", SHIPPED)
def test_every_mesh_and_flank_of_the_shipped_drives_is_rated(name):
    r = rated(name)
    assert r.rated
    loop = [m for m in r.meshes if m.loads.role in ("path 1", "path 2")]
    assert len(loop) in (2, 4)
    for m in loop:
        assert m.rated
        # a preloaded mesh loads its working flank only, and carries its preload in every case
        assert [f.flank for f in m.flanks] == [m.loads.working_flank]
        sources = [load.source for load in m.loads.loads]
        assert sources[0] == PRELOAD
        assert all(load.tangential_load >= m.loads.preload * (1 - 1e-12) or load.output_torque != 0
                   for load in m.loads.loads)
        for f in m.flanks:
            assert all(0 < s < math.inf for s in f.S_H + f.S_F)
            for i, part in enumerate((m.loads.part1, m.loads.part2)):
                below = f.S_H[i] < r.minimum_safety[0] or f.S_F[i] < r.minimum_safety[1]
                assert below == any(f" of {part} " in failure for failure in m.failures)
    data = r.to_dict()
    text = json.dumps(data, allow_nan=False)
    assert json.loads(text)["meshes"][0]["cases"][0]["source"] == PRELOAD
    for block in data["meshes"]:
        for case in block.get("cases", ()):
            assert set(CONTRACT_KEYS) <= set(case["load_capacity"])
            assert {"F_t_N", "source", "flank", "output_torque_Nm", "share"} <= set(case)


@pytest.mark.parametrize("name, unit", [("split_pinion", "mm"), ("split_pinion_inch", "in")])
def test_the_compliant_path_of_a_type_1_needs_a_narrower_face(name, unit):
    r = rated(name, HARDENED)
    (compliant,) = r.compliant_path
    (stiff,) = [m for m in r.meshes if m.loads.role == "path 1"]
    needed = compliant.face_width_needed
    assert needed < stiff.face_width_needed  # "accordingly the gear face widths differ"
    # rated at that width the spectrum's weaker safety factor is the minimum
    fw = compliant.rating.spectrum_face_width
    cases = [case for case, _ in compliant.rating.cases]
    again = rate_mesh(compliant.loads.gear1, compliant.loads.gear2, compliant.loads.centre_distance, cases,
                      compliant.conditions, (Material("case_carburised", "MQ"),) * 2, face_width=needed,
                      reversed_bending=compliant.loads.reversed_bending)
    (spectrum,) = again.spectra
    kind, minimum = ("pitting", r.minimum_safety[0]) if fw.pitting >= fw.bending else ("bending", r.minimum_safety[1])
    assert min(spectrum.safety(kind)) == pytest.approx(minimum, rel=1e-8)  # brentq on log b to 1e-13
    text = "\n".join(r.lines())
    assert f"compliant path {compliant.name}" in text and f" {unit} of face" in text
    if unit == "in":
        assert "in·lbf" in text and "lbf" in text


def test_minimum_safety_factors_come_from_checks_and_decide_the_failures():
    strict = rated("split_pinion", HARDENED)
    assert strict.ok and strict.minimum_safety == (1.0, 1.4)
    assert strict.duty_stated and not rated("split_pinion").duty_stated
    weakest = min(min(f.S_H) for m in strict.meshes for f in m.flanks)
    demanding = rated("split_pinion", HARDENED + f"[checks]\nmin_S_H = {weakest * 1.01}\n")
    assert not demanding.ok and demanding.minimum_safety[0] == pytest.approx(weakest * 1.01)
    assert all("S_H" in f for f in demanding.failures)


def test_what_iso_6336_does_not_rate_is_named():
    robot = rated("robot_joint")
    (bevel,) = [m for m in robot.meshes if not m.rated]
    assert "ISO 10300" in bevel.scope and "bevel" in bevel.scope
    assert any("ISO 10300" in line for line in robot.lines())
    c_axis = rated("c_axis")
    (gearhead,) = [m for m in c_axis.meshes if not m.rated]
    assert "gearhead" in gearhead.scope
    rack = rate_drive(resolve(design_from_dict(tomllib.loads((ROOT / "assemblies" / "rack_drive.toml").read_text()),
                                               validate=True)))
    assert not rack.rated and "[stiffness]" in rack.reason


def _verdict(name: str, extra: str = "", tables: dict | None = None):
    from geargen.checks.verdict import verify
    data = tomllib.loads((ROOT / "assemblies" / f"{name}.toml").read_text())
    data.pop("duty", None)
    data.pop("materials", None)
    for key, table in {**tomllib.loads(extra), **(tables or {})}.items():
        data[key] = {**data.get(key, {}), **table}
    return verify(resolve(design_from_dict(data, validate=True)), tolerances=False)


@pytest.mark.parametrize("name", ["robot_joint", "split_pinion_inch"])
def test_a_stated_duty_makes_the_rating_a_check_and_the_fix_it_names_passes(name):
    """With a [duty] stated, a safety factor below the minimum is a check failure naming the keys
    that fix it; the file with those keys pasted in passes (the split pinion's fix needs ground flanks)."""
    from geargen.checks.rating import fix_lines, fix_tables
    failing = _verdict(name, "[duty]\nlife_hours = 20000\n")
    fails = [f for f in failing.failures if f.kind == "load_capacity"]
    assert fails and not failing.ok
    rating = failing.load_capacity
    assert rating.fix is not None
    assert all("[materials." in f.message and "fix" in f.message for f in fails)
    tables = fix_tables(rating.fix)
    assert tomllib.loads("\n".join(fix_lines(rating.fix))) == tables  # what the check prints to paste
    tables["duty"] = {"life_hours": 20000, **tables.get("duty", {})}
    fixed = _verdict(name, tables=tables)
    assert not [f for f in fixed.failures if f.kind == "load_capacity"]
    assert fixed.load_capacity.ok and fixed.load_capacity.duty_stated


def test_on_the_defaults_alone_the_rating_is_a_note_not_a_failure():
    """A file that states no [duty] or [materials] is rated on geargen's defaults and told so: the
    shortfall is a note with the fix, the verdict is not refused for a material the file never chose."""
    result = _verdict("robot_joint")
    assert not [f for f in result.failures if f.kind == "load_capacity"]
    assert not result.load_capacity.duty_stated and result.load_capacity.failures
    (note,) = [n for n in result.notes if n.startswith("load capacity on geargen's default")]
    assert "case_carburised" in note


def test_the_shipped_drives_pass_with_the_materials_they_state():
    for name in ("robot_joint", "c_axis", "split_pinion", "split_pinion_inch"):
        rating = rate_drive(resolve(design_from_dict(tomllib.loads((ROOT / "assemblies" / f"{name}.toml").read_text()),
                                                     validate=True)))
        assert rating.duty_stated and rating.ok, (name, rating.failures)
