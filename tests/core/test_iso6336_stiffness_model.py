"""``[stiffness] mesh_stiffness = "iso6336"``: every mesh of the stiffness model takes ISO 6336-1
method B's ``c_gamma_alpha w`` instead of Eq. 1's ``E w / 11``; the drive stiffness follows by the
series-spring sums worked by hand here from the design's own numbers (teeth, module, faces)."""

import math
import tomllib
from pathlib import Path

import pytest

from geargen.core.drive import TwoPathDrive
from geargen.core.stiffness import stiffness_summary
from geargen.design.assembly import design_from_dict
from geargen.design.stiffness import stiffness_spec_from_table
from geargen.errors import DesignError, GeargenError

ROBOT = Path(__file__).resolve().parents[2] / "assemblies" / "robot_joint.toml"
DEG = math.pi / 180
IN = 25.4
E = 207e3  # MPa, the designs' steel
E_ST = 206e3  # MPa, ISO 6336's steel


def iso_mesh_by_hand(z1: int, z2: int, module: float, face: float) -> float:
    """c_gamma_alpha w (N/mm) of an unshifted 20 deg spur pair of basic rack h_fP 1.25 m, steel of
    207 GPa, from ISO 6336-1:2019 method B written out: q' = C1 + C2/z1 + C3/z2 (x = 0, z_n = z);
    c' = C_M C_B (E/E_st) / q' with C_M 0.8, C_B 1 + 0.5 (1.2 - 1.25); eps_alpha of the standard pair,
    tips at r + m; c_gamma_alpha = c' (0.75 eps_alpha + 0.25) N/(mm um), times w and 1e3 um/mm."""
    q = 0.04723 + 0.15551 / z1 + 0.25791 / z2
    c_prime = 0.8 * 0.975 * (E / E_ST) / q
    r1, r2 = z1 * module / 2, z2 * module / 2
    rb1, rb2 = r1 * math.cos(20 * DEG), r2 * math.cos(20 * DEG)
    eps = ((math.sqrt((r1 + module) ** 2 - rb1 ** 2) + math.sqrt((r2 + module) ** 2 - rb2 ** 2)
            - (r1 + r2) * math.sin(20 * DEG)) / (2 * math.pi * rb1 / z1))
    return c_prime * (0.75 * eps + 0.25) * face * 1e3


def _split_pinion(method: str | None):
    # Type 1 (Fig. 8): two 20-tooth pinions drive two 80-tooth outputs (m 1 mm), the second path
    # softened by a slender shaft; a custom train, so every ratio is typed
    stiffness = {"train": "custom", "components": {
        "mesh_outer": {"kind": "mesh", "gears": ["outer", "out_a"], "ratio": 1.0, "scope": "path1"},
        "mesh_inner": {"kind": "mesh", "gears": ["inner", "out_b"], "ratio": 1.0, "scope": "path2"},
        "inner_shaft": {"kind": "shaft_torsion", "ratio": 4.0, "diameter_mm": 4, "length_mm": 60, "scope": "path2"}}}
    if method is not None:
        stiffness["mesh_stiffness"] = method
    return design_from_dict({
        "name": "split", "drive": {"type": "type1", "preload": "frictional_interface"},
        "gear_defaults": {"module_mm": 1.0, "pressure_angle_deg": 20},
        "gears": {"outer": {"teeth": 20, "face_width_mm": 12}, "inner": {"teeth": 20, "face_width_mm": 6},
                  "out_a": {"teeth": 80, "face_width_mm": 12}, "out_b": {"teeth": 80, "face_width_mm": 6}},
        "stiffness": stiffness, "preload": {"max_output_torque_Nm": 20.0}}, validate=True)


def test_mesh_option_changes_the_paths_and_kD_by_hand():
    eq1, iso = stiffness_summary(_split_pinion(None)), stiffness_summary(_split_pinion("iso6336"))
    rb = 40.0 * math.cos(20 * DEG)  # the meshes act at the output's base radius
    shaft = 79.3e3 * math.pi * 4 ** 4 / 32 / 60 * 4 ** 2  # G J / L, reflected by R = 4 squared
    for s, mesh in ((eq1, lambda w: E * w / 11), (iso, lambda w: iso_mesh_by_hand(20, 80, 1.0, w))):
        k1 = mesh(12.0) * rb ** 2
        k2 = 1 / (1 / (mesh(6.0) * rb ** 2) + 1 / shaft)
        assert s.drive.k1 == pytest.approx(k1, rel=1e-12) and s.drive.k2 == pytest.approx(k2, rel=1e-12)
        assert s.drive_stiffness == pytest.approx(k1 + k2, rel=1e-12)  # Eq. 2, type 1
    # path 1 is the mesh alone: it scales by the ratio of the two mesh stiffnesses per face width
    ratio = iso_mesh_by_hand(20, 80, 1.0, 1.0) / (E / 11)
    assert iso.drive.k1 / eq1.drive.k1 == pytest.approx(ratio, rel=1e-12)
    assert ratio != pytest.approx(1.0, abs=0.02)  # the two methods differ here: the test can tell them apart
    # the detail says which method
    (outer,) = [c for c in iso.components if c.name == "mesh_outer"]
    assert outer.detail.startswith("ISO 6336-1:2019 method B") and "w=12 mm" in outer.detail
    assert [c for c in eq1.components if c.name == "mesh_outer"][0].detail.startswith("Eq. 1")


def _robot_joint(method: str | None):
    data = tomllib.loads(ROBOT.read_text())
    if method is not None:
        data["stiffness"]["mesh_stiffness"] = method
    return design_from_dict(data, path=ROBOT, validate=True)


def test_robot_joint_kD_with_iso6336_by_hand_from_the_file():
    """The robot joint's two meshes of each path by hand (32 diametral pitch, unshifted 20 deg spur):
    mesh 1, 16/48 teeth, the large gear's 0.1875 in face, at the large gear's base radius and
    reflected through R2 = 112/21; mesh 2, 21/112 teeth, the output's 0.25 in face, at the output's
    base radius. The paths' other components are the same under either method, so each path's
    compliance changes by the two meshes' compliance changes, and k_D follows Eq. 5 with k3 as it is."""
    from geargen.drives import resolve
    from geargen.model.analysis import placed_components

    summaries = {}
    for method in (None, "iso6336"):
        design = _robot_joint(method)
        summaries[method] = stiffness_summary(design, components=placed_components(design, resolve(design)))
    eq1, iso = summaries[None], summaries["iso6336"]
    m = IN / 32
    rb2, rb4 = 48 * m / 2 * math.cos(20 * DEG), 112 * m / 2 * math.cos(20 * DEG)
    reflect2 = (rb2 * 112 / 21) ** 2
    meshes = (  # (Eq. 1, ISO) at the output, N mm/rad
        (E * 0.1875 * IN / 11 * reflect2, iso_mesh_by_hand(16, 48, m, 0.1875 * IN) * reflect2),
        (E * 0.25 * IN / 11 * rb4 ** 2, iso_mesh_by_hand(21, 112, m, 0.25 * IN) * rb4 ** 2))
    change = sum(1 / k_iso - 1 / k_eq1 for k_eq1, k_iso in meshes)
    k1 = 1 / (1 / eq1.drive.k1 + change)
    k2 = 1 / (1 / eq1.drive.k2 + change)
    assert iso.drive.k1 == pytest.approx(k1, rel=1e-9) and iso.drive.k2 == pytest.approx(k2, rel=1e-9)
    assert iso.drive.k3 == eq1.drive.k3  # the preload spring does not depend on the meshes
    hand = TwoPathDrive(eq1.drive_type, k1, k2, eq1.drive.preload, eq1.drive.k3)
    assert iso.drive_stiffness == pytest.approx(hand.drive_stiffness, rel=1e-9)
    assert abs(iso.drive_stiffness / eq1.drive_stiffness - 1) > 1e-3  # a change the test can see


def test_a_bad_option_value_names_the_key():
    with pytest.raises(DesignError) as info:
        stiffness_spec_from_table({"mesh_stiffness": "iso"})
    assert info.value.field == "stiffness.mesh_stiffness"
    assert "'eq1'" in info.value.allowed and "'iso6336'" in info.value.allowed
    with pytest.raises(GeargenError) as info:
        _split_pinion("ISO 6336")
    assert "stiffness.mesh_stiffness" in str(info.value) and "iso6336" in str(info.value)


def test_dual_motor_mesh_follows_its_option():
    # [dual_motor] mesh_stiffness: the pinion's mesh (18/144 teeth, m 2 mm, spur, unshifted, the output's
    # 20 mm face) at the output's base radius, by hand both ways; the other components unchanged
    from geargen.model.train import dual_motor_analysis

    path = ROBOT.parent / "dual_motor.toml"
    analyses = {}
    for method in ("eq1", "iso6336"):
        data = tomllib.loads(path.read_text())
        data["dual_motor"]["mesh_stiffness"] = method
        analyses[method] = dual_motor_analysis(design_from_dict(data, path=path, validate=True), [])
    rb = 144 * 2.0 / 2 * math.cos(20 * DEG)
    eq1, iso = (dict(analyses[m].path_components) for m in ("eq1", "iso6336"))
    assert eq1["mesh (Eq. 1)"] == pytest.approx(E * 20 / 11 * rb ** 2 * 1e-3, rel=1e-12)  # N·m/rad
    assert iso["mesh (ISO 6336-1 method B)"] == pytest.approx(iso_mesh_by_hand(18, 144, 2.0, 20.0) * rb ** 2 * 1e-3,
                                                               rel=1e-12)
    assert eq1["pinion shaft"] == iso["pinion shaft"] and eq1["gearhead"] == iso["gearhead"]
