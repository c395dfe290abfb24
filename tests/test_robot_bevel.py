"""The robot joint's bevel pair as toothed bevel gears (geargen.drives.dual_pinion.bevel, placed by
geargen.cad.assembly._bevel_drive, checked by geargen.checks.verdict._bevel_meshes).

Independent references: the pitch cones of a 15:30 pair at 90 deg are tan delta_p = 15/30 (any
bevel text, e.g. KHK Gear Technical Reference, straight bevel gears: delta_1 = atan(sin S / (z2/z1 +
cos S))); the heel pitch radii z m / 2 with m = 25.4 / 32 mm; the design backlash is the design
file's own statement ([train] comment: 0.0015 in circumferential at the 30-tooth gear's pitch
radius, the 11 arcmin of upstream_backlash_arcmin at the input shaft).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from geargen.design.assembly import load_design
from geargen.drives.resolver import resolve
from geargen.drives.dual_pinion.bevel import bevel_drive

ROBOT = Path(__file__).resolve().parents[1] / "assemblies/robot_joint.toml"
IN = 25.4
MODULE = IN / 32


def _layout(tmp_path=None, **changes):
    if not changes:
        return resolve(load_design(ROBOT))
    text = ROBOT.read_text()
    for key, value in changes.items():
        text, n = re.subn(rf"^{key} = [^ #\n]+", f"{key} = {value}", text, flags=re.M)
        assert n == 1, key
    path = tmp_path / "robot_joint.toml"
    path.write_text(text)
    return resolve(load_design(path))


def test_placed_apexes_coincide_on_the_pitch_cone_models_apex():
    from geargen.families.bevel.geometry import bevel_pair_geometry
    from geargen.design.parts import parts_settings
    from geargen.drives.dual_pinion.shafts import carriage_shafts
    layout = _layout()
    placed = bevel_drive(layout)
    bev = bevel_pair_geometry(15, 30, MODULE, 0.15 * IN)
    ish = carriage_shafts(layout, parts_settings(layout.design))["input"]
    apex = np.array([ish.centre[0], ish.centre[1], ish.loads["bevel_gear"] + bev.apex_height("gear")])
    assert np.allclose(placed.gear_matrix[:3, 3], apex, rtol=0, atol=1e-12)
    assert np.allclose(placed.pinion_matrix[:3, 3], apex, rtol=0, atol=1e-12)
    # the pitch-cone model's cones and the closed form tan delta_p = 15/30, at the same heel radii
    assert placed.pinion.pitch_cone_angle == pytest.approx(math.atan(0.5), abs=1e-14)
    assert placed.gear.pitch_cone_angle == pytest.approx(math.pi / 2 - math.atan(0.5), abs=1e-14)
    assert placed.pinion.pitch_cone_angle == pytest.approx(bev.pitch_angle_pinion, abs=1e-14)
    assert placed.gear.pitch_cone_angle == pytest.approx(bev.pitch_angle_gear, abs=1e-14)
    assert placed.gear.reference_diameter / 2 == pytest.approx(30 * MODULE / 2, rel=1e-14)
    assert placed.gear.cone_distance == pytest.approx(bev.cone_distance, rel=1e-14)
    # the gear's teeth point down its (the input shaft's) axis, the pinion's along +x, 90 deg apart
    assert np.allclose(placed.gear_matrix[:3, 2], [0, 0, -1], atol=1e-15)
    assert np.allclose(placed.pinion_matrix[:3, 2], [1, 0, 0], atol=1e-15)
    assert placed.gear.bore_diameter == pytest.approx(0.1875 * IN, rel=1e-14)  # the input shaft


def test_bevel_mesh_backlash_is_the_design_value_centred():
    from geargen.checks.verdict import verify
    layout = _layout()
    result = verify(layout, tolerances=False)
    (b,) = result.bevel
    design = 0.0015 * IN  # [train] comment of robot_joint.toml
    assert b["design_backlash"] == pytest.approx(design, rel=2e-4)  # 11 arcmin * 0.46875 in = 0.0014999 in
    assert b["design_backlash"] == pytest.approx(11 / 60 * math.pi / 180 * 30 * MODULE / 2, rel=1e-14)
    assert abs(b["backlash"] - b["design_backlash"]) < 1e-6  # mm
    assert b["play_positive"] == pytest.approx(b["design_backlash"] / 2, abs=1e-6)
    assert b["play_negative"] == pytest.approx(b["design_backlash"] / 2, abs=1e-6)
    assert b["tip_clearance"] > 0 and b["apex_distance"] < 1e-9
    assert not [f for f in result.failures if f.mesh == "bevel"] and result.ok


def test_a_misphased_or_misplaced_pinion_fails_the_bevel_check():
    from geargen.drives.dual_pinion.bevel_verdict import check_placed_bevel_pair
    from geargen.errors import GeometryError
    from geargen.drives.dual_pinion.bevel import _rotation
    placed = bevel_drive(_layout())
    r_pinion = placed.pinion.reference_diameter / 2
    # turn the pinion on its own axis by 0.8 of the backlash (arc at its pitch circle): one side
    # keeps 1.3 of the half backlash, the other runs 0.3 of it into the gear's flank
    turn = 0.8 * placed.backlash / r_pinion
    c = check_placed_bevel_pair(placed.gear, placed.gear_matrix, placed.pinion,
                                placed.pinion_matrix @ _rotation((0, 0, 1), turn))
    assert sorted([c.play_positive, c.play_negative]) == pytest.approx(
        [-0.3 * placed.backlash, 1.3 * placed.backlash], abs=2e-6)
    moved = placed.pinion_matrix.copy()
    moved[0, 3] += 0.01
    with pytest.raises(GeometryError, match="apexes"):
        check_placed_bevel_pair(placed.gear, placed.gear_matrix, placed.pinion, moved)


def test_moving_the_bevel_moves_the_solids_and_the_stiffness_together(tmp_path):
    """One home: input_shaft_to_bevel moves both gears (their apex) and the input shaft's twisting
    length; the face width changes the solids and the bevel mesh stiffness (Eq. 1 at the mean radius)."""
    from geargen.model.analysis import placed_components
    from geargen.model.train import _bevel_stiffness
    from geargen.design.stiffness import stiffness_design
    from geargen.core.stiffness import mesh_stiffness, torsional_from_linear

    def shaft_length(layout):
        (c,) = [c for c in placed_components(layout.design, layout) if c.name == "input_shaft"]
        return c.length

    base = _layout()
    # 0.075 in up (0.1 in puts the bevel gear's heel above the link cover's plane over the cluster
    # bearings: refused, test_a_bevel_too_high_is_refused_with_fixes_that_work)
    up = _layout(tmp_path, input_shaft_to_bevel_in=0.6)
    a, b = bevel_drive(base), bevel_drive(up)
    assert b.apex[2] - a.apex[2] == pytest.approx(0.075 * IN, abs=1e-12)
    assert np.allclose(b.pinion_matrix[:3, 3] - a.pinion_matrix[:3, 3], [0, 0, 0.075 * IN], atol=1e-12)
    assert shaft_length(up) - shaft_length(base) == pytest.approx(0.075 * IN, abs=1e-12)

    wide = _layout(tmp_path, bevel_face_width_in=0.2)
    w = bevel_drive(wide)
    assert w.gear.face_width == pytest.approx(0.2 * IN) and w.pinion.face_width == pytest.approx(0.2 * IN)
    for layout, face in ((base, 0.15 * IN), (wide, 0.2 * IN)):
        delta = math.atan(2.0)  # the gear's pitch cone
        r_base = (30 * MODULE / 2 - face / 2 * math.sin(delta)) * math.cos(math.radians(20))
        k = float(mesh_stiffness(stiffness_design(layout.design).stiffness.elastic_modulus, face))
        assert _bevel_stiffness(layout, 15, 30, 1.0) == pytest.approx(float(torsional_from_linear(k, r_base)), rel=1e-12)
    assert _bevel_stiffness(wide, 15, 30, 1.0) > _bevel_stiffness(base, 15, 30, 1.0)


@pytest.mark.parametrize("value, rule", [(0.50, "bevel_above_arm"), (0.625, "link_cover_room")])
def test_a_bevel_too_low_or_too_high_is_refused_with_fixes_that_work(tmp_path, value, rule):
    """The rules are the hardware's, evaluated when the drive is resolved (check refuses as build
    does). Too low, the bevel gear's back runs into the carriage arm; too high, its heel rises above
    the link cover's plane where the cover must seat the cluster bearings. Each refusal offers
    values found by laying the drive out again: each, written into the file, lets the drive resolve
    (or at least changes the refusal)."""
    from geargen.drives.rules import RuleBroken
    with pytest.raises(RuleBroken) as e:
        _layout(tmp_path, input_shaft_to_bevel_in=value)
    assert e.value.rule == rule and e.value.fixes and "input_shaft_to_bevel_in" in str(e.value)
    for key, fixed in e.value.fixes.items():
        text = (tmp_path / "robot_joint.toml").read_text()
        name = key.split(".", 1)[1]
        text, n = re.subn(rf"^{name} = [^ #\n]+", f"{name} = {fixed}", text, flags=re.M)
        assert n == 1, key
        path = tmp_path / "fixed.toml"
        path.write_text(text)
        try:
            resolve(load_design(path))
        except RuleBroken as again:
            assert again.rule != rule, (key, fixed, str(again))


@pytest.mark.slow
def test_built_robot_joint_has_the_toothed_bevel_pair_and_its_mesh(built_assemblies):
    import json
    folder = built_assemblies["robot_joint"]
    manifest = json.loads((folder / "manifest.json").read_text())
    checks = manifest["checks"]
    (b,) = checks["bevel_meshes"]  # mm
    assert abs(b["backlash"] - 0.0015 * IN) < 2e-4 * 0.0015 * IN
    placed = bevel_drive(_layout())
    for name, matrix in (("bevel_gear", placed.gear_matrix), ("bevel_pinion", placed.pinion_matrix)):
        assert np.allclose(np.asarray(manifest["parts"][name]["placement_matrix_mm"], float), matrix, atol=1e-9)
    meshing = [sorted(p[:2]) for p in checks["overlaps"]["meshing_pairs"]]
    assert ["bevel_gear", "bevel_pinion"] in meshing
