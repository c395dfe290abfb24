"""The load each flank of every mesh carries (geargen.model.mesh_loads, issue 29 phase 2): the
preload, each path's share of the drive torque (Hale & Slocum Eqs. 2-6), the unloaded path, the
upstream stages, recomputed here by hand from the stiffness model's k1, k2, k3 and the springs."""

import math
import tomllib
from pathlib import Path

import pytest

from geargen.design.assembly import design_from_dict
from geargen.design.duty import duty_settings
from geargen.drives.resolver import resolve
from geargen.model.analysis import stiffness
from geargen.model.mesh_loads import ALONE, DRIVE, PRELOAD, SHARED, mesh_loads

ROOT = Path(__file__).resolve().parents[1]
IN = 25.4
#: floating-point agreement of two evaluations of the same closed form
EXACT = 1e-12


def drive(name: str, extra: str = ""):
    data = tomllib.loads((ROOT / "assemblies" / f"{name}.toml").read_text())
    data.update(tomllib.loads(extra))
    design = design_from_dict(data, validate=True)
    layout = resolve(design)
    summary = stiffness(design, layout)[0]
    return summary, {m.name: m for m in mesh_loads(layout, summary, duty_settings(design))}


def test_robot_joint_mesh_2_carries_the_preload_plus_its_eq_5_share():
    summary, meshes = drive("robot_joint")
    # the loop preload from the springs, by hand: two music-wire springs (G 79.3 GPa, d 0.045 in,
    # D 0.45 in, 4 active coils) compressed from 0.80 to 0.35 in push the carriage; the radial
    # preload lever (Fig. 9, gamma = 0) is lambda = 1 / (R2 r_b2), R2 = 112/21, r_b2 the 48-tooth
    # cluster gear's base radius (32 DP, 20 deg); each path carries P = F_e / (2 lambda)
    rate = 79.3e3 * (0.045 * IN) ** 4 / (8 * (0.45 * IN) ** 3 * 4)
    force = 2 * rate * (0.80 - 0.35) * IN
    lever = 1 / (112 / 21 * 48 / 64 * IN * math.cos(math.radians(20)))
    preload = force / (2 * lever)
    d = summary.drive
    assert d.preload == pytest.approx(preload, rel=1e-9)  # the spring rate's closed form, evaluated twice
    # Eq. 5 and the path force rate of the Type 2 model (Fig. 7): path 1 carries P + g1 T / k_D
    k1, k2, k3 = d.k1, d.k2, d.k3
    k_d = (k1 + k2) - (k1 - k2) ** 2 / (k1 + k2 + k3)
    g1 = k1 * (2 * k2 + k3) / (k1 + k2 + k3)
    torque = 5000.0  # [preload] max_output_torque_Nm = 5, both ways
    path1 = preload + g1 * torque / k_d
    assert path1 == pytest.approx(preload + torque / 2, rel=EXACT)  # equal paths: the drive torque halves
    # at the output gear's reference circle (112 T, 32 DP: 1.75 in)
    r_out = 112 / 32 / 2 * IN
    m2a = meshes["mesh2_a"]
    assert m2a.preload == pytest.approx(preload / r_out, rel=1e-9)
    (top,) = [x for x in m2a.loads if x.output_torque == torque]
    assert top.tangential_load == pytest.approx(path1 / r_out, rel=1e-9)
    assert top.source == SHARED and top.share == 0.5 and top.flank == "cw"
    # path 2 at the same torque: P - T/2 on its own working flank; mesh 1 at the cluster's 48 T gear
    (low,) = [x for x in meshes["mesh2_b"].loads if x.output_torque == torque]
    assert low.tangential_load == pytest.approx((preload - torque / 2) / r_out, rel=1e-9)
    (m1,) = [x for x in meshes["mesh1_a"].loads if x.output_torque == torque]
    assert m1.tangential_load == pytest.approx(path1 / (112 / 21) / (48 / 64 * IN), rel=1e-9)
    # each loop mesh loads its working flank only; the output and input gears, shared by both
    # paths over the same face, are loaded on both flanks (reversed bending), the clusters not
    for name in ("mesh1_a", "mesh2_a", "mesh1_b", "mesh2_b"):
        assert {x.flank for x in meshes[name].loads} == {meshes[name].working_flank}
    assert meshes["mesh2_a"].reversed_bending == (False, True)
    assert meshes["mesh1_a"].reversed_bending == (True, False)
    # the bevel pair upstream is named, not rated: ISO 10300
    assert "ISO 10300" in meshes["upstream 15:30"].scope


def test_beyond_twice_the_preload_one_path_of_a_type_2_carries_all():
    summary, meshes = drive("robot_joint", "[duty]\ndirection = \"signed\"\noutput_torque_levels_Nm = [8]")
    r_out = 112 / 32 / 2 * IN
    assert 8000.0 > 2 * summary.drive.preload  # the level unloads path 2 (Eqs. 5/6: at 2P)
    (top,) = [x for x in meshes["mesh2_a"].loads if x.level == 1]
    assert top.tangential_load == pytest.approx(8000.0 / r_out, rel=1e-9)
    assert top.source == ALONE
    assert [x.source for x in meshes["mesh2_b"].loads] == [PRELOAD]  # only its preload case is left


def test_split_pinion_the_stiff_path_takes_what_the_compliant_one_does_not():
    summary, meshes = drive("split_pinion", "[duty]\ndirection = \"signed\"\n"
                                            "output_torque_levels_Nm = [20, -20, -30]\nlevel_shares = [0.4, 0.4, 0.2]")
    d = summary.drive
    k1, k2, p = d.k1, d.k2, d.preload
    assert d.k3 == math.inf and p == 22000.0  # type 1, [preload] preload_Nm = 22
    r_out = 80 * 1.5 / 2
    stiff, compliant = meshes["mesh_pinion_stiff"], meshes["mesh_pinion_compliant"]
    loads = {x.output_torque: x for x in stiff.loads if x.level}
    # Eqs. 2/3: while both carry, the drive torque divides as the stiffnesses
    assert loads[20000.0].tangential_load == pytest.approx((p + k1 / (k1 + k2) * 20000) / r_out, rel=1e-9)
    comp = {x.output_torque: x for x in compliant.loads if x.level}
    assert comp[20000.0].tangential_load == pytest.approx((p - k2 / (k1 + k2) * 20000) / r_out, rel=1e-9)
    assert comp[-20000.0].tangential_load == pytest.approx((p + k2 / (k1 + k2) * 20000) / r_out, rel=1e-9)
    # the stiff path unloads at T = -P (k1 + k2) / k1 (about the preload): at -30 N m the compliant
    # path carries the whole drive torque and the stiff one nothing
    assert -p * (k1 + k2) / k1 > -30000.0
    assert comp[-30000.0].tangential_load == pytest.approx(30000.0 / r_out, rel=1e-9)
    assert -30000.0 not in loads
    # the compliant path carries less at the load that matters most for it (the paper)
    assert max(x.tangential_load for x in compliant.loads if x.level != 3) < stiff.peak_load
    # the two pinions load the output's two flanks on faces 2 mm apart: no reversed bending
    assert stiff.reversed_bending == (False, False) and compliant.reversed_bending == (False, False)
    assert stiff.working_flank != compliant.working_flank


def test_upstream_stages_carry_the_drive_torque_only():
    _, meshes = drive("metric_dual_pinion")
    st = meshes["stage_idler"]  # idler pinion (18 T) drives the 36 T gear on the input's shaft (15 x output)
    assert st.preload is None and st.speed == pytest.approx(30.0, rel=EXACT)
    r1 = st.gear1.reference_radius
    assert {x.flank for x in st.loads} == {"cw", "ccw"}  # both ways
    for x in st.loads:
        assert x.tangential_load == pytest.approx(10000.0 / (30.0 * r1), rel=1e-12)
        assert x.source == DRIVE
    assert st.reversed_bending == (True, True)
    _, planetary = drive("planetary_dual_pinion")
    sun = planetary["stage_planetary_sun_planet_1"]
    # ring 57 / sun 15: the sun turns 72 x the output, the carrier 15 x; three planets share the sun's torque
    assert sun.speed == pytest.approx(72 - 15, rel=EXACT)
    assert sun.loads[0].tangential_load == pytest.approx(10000.0 / 72 / sun.gear1.reference_radius / 3, rel=1e-12)
    assert sun.load_cycles_per_turn == (3.0, 1.0)
    ring = planetary["stage_planetary_planet_ring_1"]
    assert ring.loads[0].tangential_load == pytest.approx(sun.loads[0].tangential_load, rel=EXACT)
    assert ring.load_cycles_per_turn == (1.0, 3.0)
    assert sun.reversed_bending[1] and ring.reversed_bending[0]  # the planet is an idler
