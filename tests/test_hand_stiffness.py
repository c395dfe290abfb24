"""The split pinions' stiffness against a hand calculation from the same dimensions.

Every length comes from the built solids (bounding boxes of the bearings, collar, shafts and gear
bodies; the hollow shaft's bore from its volume) or from the design file read as plain TOML with
this file's own unit factors; materials, bearing stiffness, the typed hollow-shaft component,
preload and loop error come from the design file. Nothing is read from geargen's stiffness code,
so moving a part, mistyping a ratio or changing a formula there makes these tests fail.

The hand calculation (N, mm, rad; torsion at the output):

- mesh (Eq. 1): ``k = E w / 11`` along the line of action, ``w`` the narrower face (the pinion's),
  acting at the output's base radius ``r_b = z m cos(alpha) / 2``: ``k r_b^2``;
- shaft torsion: ``G J / L`` with ``J = pi (D^4 - d^4) / 32``, reflected by the ratio squared
  (the pinions turn ``R = z_output / z_pinion`` times as fast as the output);
- a pinion on its shaft and supports, as lateral compliance at its mid-face: overhung by ``c``
  beyond a bearing pair ``l`` apart, ``c^2 (l + c) / (3 E I)`` plus the bearings through their
  levers ``((c / l)^2 + ((l + c) / l)^2) / k_b``; between two supports ``a`` and ``b`` from them,
  ``a^2 b^2 / (3 E I (a + b))`` plus ``(b / L)^2 / k_1 + (a / L)^2 / k_2``. The compliant pinion's
  lower support is the clamp collar, carried by the hollow shaft's overhung end (the overhung
  formula at the collar's mid-width: the collar taken as rigid). As torsion at the output
  ``k r_b,pinion^2 R^2``;
- each path the series sum of its components, the loop ``k_L = 1 / (1/k_1 + 1/k_2)`` (Eq. 3,
  Type 1: no preload spring), the preload band ``P -+ k_L delta / 2``.

The 1 % tolerance is the acceptance of the issue ("stiffness matching an independent hand
calculation within 1 %"); both sides use the same idealisations, so they agree to rounding.
"""

import math
import tomllib
from pathlib import Path

import pytest

from geargen.design.assembly import load_design
from geargen.model import resolve
from geargen.model.analysis import stiffness

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]

#: this file's own unit factors to N, mm, MPa (the suffixes the two design files use)
LENGTH = {"mm": 1.0, "in": 25.4}
TORQUE = {"Nm": 1e3, "in_lbf": 4.4482216152605 * 25.4}
STRESS = {"GPa": 1e3, "MPa": 1.0}
LINEAR_STIFFNESS = {"N_per_um": 1e3, "N_per_mm": 1.0}


def _value(table: dict, key: str, units: dict) -> float:
    """``table``'s ``key_<unit>`` in internal units (exactly one suffix present)."""
    (found,) = [(u, table[f"{key}_{u}"]) for u in units if f"{key}_{u}" in table]
    return found[1] * units[found[0]]


def _box(part) -> tuple[float, ...]:
    """(xmin, ymin, zmin, xmax, ymax, zmax) of a placed part, mm: the tight box of its exact surfaces."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(part.world(), box, False, False)
    return box.Get()


def _volume(part) -> float:
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(part.world(), props)
    return props.Mass()


def _mid_z(part) -> float:
    box = _box(part)
    return (box[2] + box[5]) / 2


def _diameter(part) -> float:
    box = _box(part)
    return box[3] - box[0]


def _overhung(ei: float, span: float, overhang: float, kb: float) -> float:
    """Lateral compliance (mm/N) at a load ``overhang`` beyond one of two bearings ``span`` apart."""
    c, l = overhang, span
    return c * c * (l + c) / (3 * ei) + ((c / l) ** 2 + ((l + c) / l) ** 2) / kb


def _between(ei: float, a: float, b: float, k_a: float, k_b: float) -> float:
    """Lateral compliance (mm/N) at a load ``a`` from a support of stiffness ``k_a`` and ``b`` from one of ``k_b``."""
    span = a + b
    return a * a * b * b / (3 * ei * span) + (b / span) ** 2 / k_a + (a / span) ** 2 / k_b


def _series(*k: float) -> float:
    return 1.0 / sum(1.0 / x for x in k)


def _built(path: Path):
    """The design ``path`` as its TOML (``data``), its stiffness summary, its built parts by name
    (gears included), the materials ``E`` and ``G`` (MPa), and ``gear(name)`` -> (teeth, base
    radius, face width) read from the TOML with this file's own unit factors."""
    from geargen.pipeline import gear_solids, other_parts

    data = tomllib.loads(path.read_text())
    design = load_design(path)
    layout = resolve(design)
    summary, _ = stiffness(design, layout)
    parts = {p.name: p for p in other_parts(layout, gear_solids(layout), summary).parts}
    st = data["stiffness"]
    E, G = _value(st, "elastic_modulus", STRESS), _value(st, "shear_modulus", STRESS)
    defaults = data.get("gear_defaults", {})

    def gear(name):
        table = {**defaults, **data["gears"][name]}
        module = table["module_mm"] if "module_mm" in table else 25.4 / table["diametral_pitch_per_in"]
        face = next(table[k] * LENGTH[k.rsplit("_", 1)[1]] for k in table if k.startswith("face_width_"))
        base = table["teeth"] * module / 2 * math.cos(math.radians(table["pressure_angle_deg"]))
        return table["teeth"], base, face

    return data, summary, parts, E, G, gear


def hand_calculation(path: Path) -> dict:
    """Every component, both paths, the loop and the preload band of the split pinion ``path``
    (N·mm/rad at the output, N·mm), by hand from its solids and its TOML."""
    data, summary, parts, E, G, gear = _built(path)
    comps = data["stiffness"]["components"]
    z_out, rb_out, _ = gear("output")
    z_pin, rb_pin, _ = gear("pinion_stiff")
    assert gear("pinion_compliant")[0] == z_pin  # both pinions mesh the one output at one centre
    R = z_out / z_pin

    # heights and diameters of the built solids
    zb_lo, zb_hi = sorted(_mid_z(parts[n]) for n in ("pinion_bearing_1", "pinion_bearing_2"))
    stiff_box, compl_box = _box(parts["pinion_stiff"]), _box(parts["pinion_compliant"])
    collar_box = _box(parts["friction_collar"])
    z_collar = (collar_box[2] + collar_box[5]) / 2
    z_stiff, z_compl = (stiff_box[2] + stiff_box[5]) / 2, (compl_box[2] + compl_box[5]) / 2
    z_outboard = _mid_z(parts["compliant_bearing"])
    hollow = parts["hollow_shaft"]
    hollow_box = _box(hollow)
    D_h = _diameter(hollow)
    d_h = math.sqrt(D_h ** 2 - 4 * _volume(hollow) / (math.pi * (hollow_box[5] - hollow_box[2])))
    d_in = _diameter(parts["inner_shaft"])
    ei_h = E * math.pi * (D_h ** 4 - d_h ** 4) / 64
    ei_in = E * math.pi * d_in ** 4 / 64
    span = zb_hi - zb_lo

    out = {"R": R, "summary": summary, "hollow_lower_end": hollow_box[2], "z_stiff": z_stiff,
           "hollow_measured": (D_h, d_h)}
    # path 1: the wide pinion's mesh, the typed hollow shaft, the wide pinion overhung on the pair
    w_stiff = stiff_box[5] - stiff_box[2]
    out["mesh_stiff"] = E * w_stiff / 11 * rb_out ** 2
    hs = comps["hollow_shaft"]
    D, d, L = (_value(hs, k, LENGTH) for k in ("diameter", "bore_diameter", "length"))
    out["hollow_typed"] = (D, d, L)
    out["hollow_shaft"] = G * math.pi * (D ** 4 - d ** 4) / 32 / L * R ** 2
    kb = _value(comps["stiff_support"], "stiffness", LINEAR_STIFFNESS)
    out["stiff_support"] = rb_pin ** 2 * R ** 2 / _overhung(ei_h, span, z_stiff - zb_hi, kb)
    # path 2: the narrow pinion's mesh, the inner shaft from the collar's face to the pinion's face,
    # the narrow pinion between the collar (on the hollow shaft's overhung end) and the outboard bearing
    w_compl = compl_box[5] - compl_box[2]
    out["mesh_compliant"] = E * w_compl / 11 * rb_out ** 2
    out["inner_shaft"] = G * math.pi * d_in ** 4 / 32 / (compl_box[2] - collar_box[5]) * R ** 2
    kb = _value(comps["compliant_support"], "stiffness", LINEAR_STIFFNESS)
    collar = _overhung(ei_h, span, zb_lo - z_collar, kb)
    out["compliant_support"] = rb_pin ** 2 * R ** 2 / _between(ei_in, z_compl - z_collar, z_outboard - z_compl,
                                                               1 / collar, kb)
    out["path1"] = _series(out["mesh_stiff"], out["hollow_shaft"], out["stiff_support"])
    out["path2"] = _series(out["mesh_compliant"], out["inner_shaft"], out["compliant_support"])
    out["loop"] = _series(out["path1"], out["path2"])
    pre = data["preload"]
    preload = _value(pre, "preload", TORQUE)
    band = out["loop"] * pre["loop_error_rotation_urad"] * 1e-6
    out["band"] = (preload - band / 2, preload + band / 2)
    return out


COMPONENTS = ("mesh_stiff", "hollow_shaft", "stiff_support", "mesh_compliant", "inner_shaft", "compliant_support")


def _assert_matches(hand: dict) -> None:
    summary = hand["summary"]
    by_name = {c.name: c.at_output for c in summary.components}
    for name in COMPONENTS:
        assert by_name[name] == pytest.approx(hand[name], rel=0.01), name
    assert summary.drive.k1 == pytest.approx(hand["path1"], rel=0.01)
    assert summary.drive.k2 == pytest.approx(hand["path2"], rel=0.01)
    assert summary.drive.loop_stiffness == pytest.approx(hand["loop"], rel=0.01)
    band = summary.headline
    assert (band.low, band.high) == pytest.approx(hand["band"], rel=0.01)


def test_split_pinion_by_hand():
    """assemblies/split_pinion.toml (module 1.5, 20/80, ratio 4; preload 22 N·m, loop error 500 urad).

    By hand, N·m/rad at the output: path 1 = mesh 717,849 + hollow shaft 238,295 (typed: 16/9.5 mm
    over 30 mm) + wide pinion overhung 10 mm on its 30 mm pair 79,345 -> 54,967; path 2 = mesh
    478,566 + inner shaft (8.5 mm over 80 mm) 8,128 + narrow pinion between collar and outboard
    bearing 46,537 -> 6,821; k_L = 6,068; preload band 20.48 to 23.52 N·m.
    """
    hand = hand_calculation(ROOT / "assemblies/split_pinion.toml")
    assert hand["R"] == 4
    D, d, _ = hand["hollow_typed"]
    assert hand["hollow_measured"] == pytest.approx((D, d), rel=1e-6)  # the typed tube is the built one
    _assert_matches(hand)
    assert hand["path2"] / 1e3 == pytest.approx(6821, rel=1e-3)
    assert hand["loop"] / 1e3 == pytest.approx(6068, rel=1e-3)


def test_split_pinion_inch_by_hand():
    """assemblies/split_pinion_inch.toml (20 DP, 18/90, ratio 5; preload 132 in·lbf = 14.91 N·m,
    loop error 444 urad).

    By hand, N·m/rad at the output: path 1 = mesh 689,264 + hollow shaft 80,815 (1/2 in over 0.29 in
    bore, 2.1875 in from its lower end, where the input drives it, to the wide pinion's mid-face) +
    wide pinion overhung 0.43 in on its 1.5 in pair 43,820 -> 27,289; path 2 = mesh 258,474 + inner
    shaft (1/4 in over 2.5 in) 4,984 + narrow pinion between collar and outboard bearing 35,180
    -> 4,293; k_L = 3,709; preload band 14.09 to 15.74 N·m (11 % peak to peak).
    """
    hand = hand_calculation(ROOT / "assemblies/split_pinion_inch.toml")
    assert hand["R"] == 5
    D, d, L = hand["hollow_typed"]
    assert hand["hollow_measured"] == pytest.approx((D, d), rel=1e-6)
    # the typed twisting length is the built one: the hollow shaft's lower end to the wide pinion's mid-face
    assert hand["z_stiff"] - hand["hollow_lower_end"] == pytest.approx(L, rel=1e-6)
    _assert_matches(hand)
    assert hand["path2"] / 1e3 == pytest.approx(4293, rel=1e-3)
    assert hand["loop"] / 1e3 == pytest.approx(3709, rel=1e-3)


# ---------------------------------------------------------------- dual pinion on a carriage


def carriage_hand_calculation(path: Path) -> dict:
    """The paths and the common part of a dual-pinion drive on a preload carriage (the robot joint,
    the metric dual pinion), by hand from its solids and its TOML (N·mm/rad at the output):

    - meshes (Eq. 1) ``E w / 11`` at the driven gear's base radius, reflected by that gear's speed
      over the output's squared (mesh 1 at the cluster's large gear, R2; mesh 2 at the output);
    - the cluster shaft twisting between its two gears' mid-faces (measured), ``G J / L`` x R2^2;
    - the cluster's small gear between its two bearings (measured mid-widths), ``a^2 b^2 / (3 E I L)``
      plus the bearings through their levers, at the small gear's base radius, x R2^2;
    - common: the input shaft from the input's mid-face to the mid-face of the gear that drives it
      (the bevel gear's heel for the robot joint: its typed distance), each stage mesh at its driven
      gear's speed (teeth ratios counted here), the output hub as typed."""
    data, summary, parts, E, G, gear = _built(path)
    comps = data["stiffness"]["components"]
    (z_in, _, w_in), (z_cl, rb_cl, w_cl) = gear("input"), gear("cluster_large")
    (z_cs, rb_cs, w_cs), (z_out, rb_out, w_out) = gear("cluster_small"), gear("output")
    r2 = z_out / z_cs
    ratio = z_cl / z_in * r2

    def cluster_part(role):
        return parts[f"{role}_a"] if f"{role}_a" in parts else parts["cluster_a"]

    out = {"mesh1": E * min(w_in, w_cl) / 11 * rb_cl ** 2 * r2 ** 2,
           "mesh2": E * min(w_cs, w_out) / 11 * rb_out ** 2}
    d_cl = _diameter(parts["cluster_shaft_a"])
    twist = abs(_mid_z(cluster_part("cluster_small")) - _mid_z(cluster_part("cluster_large")))
    out["cluster_shaft"] = G * math.pi * d_cl ** 4 / 32 / twist * r2 ** 2
    kb = _value(comps["cluster_support"], "stiffness", LINEAR_STIFFNESS)
    lo, hi = _mid_z(parts["cluster_bearing_lower_a"]), _mid_z(parts["cluster_bearing_upper_a"])
    z_gear = _mid_z(cluster_part("cluster_small"))
    ei = E * math.pi * d_cl ** 4 / 64
    out["cluster_support"] = 1 / _between(ei, z_gear - lo, hi - z_gear, kb, kb) * rb_cs ** 2 * r2 ** 2
    path = _series(*out.values())

    d_in = _diameter(parts["input_shaft"])
    z_input = _mid_z(parts["input"])
    stages = list(data.get("stages", {}).values())
    if stages:
        length = _mid_z(parts[stages[-1]["driven"]]) - z_input
    else:
        length = data["parts"]["input_shaft_to_bevel_in"] * 25.4
    common = {"input_shaft": G * math.pi * d_in ** 4 / 32 / length * ratio ** 2}
    speed = ratio
    for stage in reversed(stages):
        z_driver, _, w_driver = gear(stage["driver"])
        z_driven, rb_driven, w_driven = gear(stage["driven"])
        common[stage["driven"]] = E * min(w_driver, w_driven) / 11 * rb_driven ** 2 * speed ** 2
        speed *= z_driven / z_driver
    hub = comps["output_hub"]
    unit = next(k.rsplit("_", 1)[1] for k in hub if k.startswith("length_"))
    dh, bh, lh = (hub[f"{k}_{unit}"] * LENGTH[unit] for k in ("diameter", "bore_diameter", "length"))
    common["output_hub"] = G * math.pi * (dh ** 4 - bh ** 4) / 32 / lh
    return {"summary": summary, "path": path, "common": _series(*common.values()), "components": {**out, **common}}


@pytest.mark.parametrize("name", ["robot_joint", "metric_dual_pinion"])
def test_carriage_drives_match_the_hand_calculation(name):
    """Robot joint: path 15,518 N·m/rad, common 68,673; metric dual pinion (two stages before the
    loop): path 38,534, common 33,875 (mesh 1 1.817e6, mesh 2 7.478e5, cluster shaft 83,917,
    cluster support 82,326; input shaft 36,493 up to the drive gear over the link cover, idler mesh
    7.27e6, motor mesh 3.49e7, hub 5.12e5)."""
    hand = carriage_hand_calculation(ROOT / f"assemblies/{name}.toml")
    s = hand["summary"]
    assert s.path1.stiffness == pytest.approx(hand["path"], rel=0.01)
    assert s.path2.stiffness == pytest.approx(hand["path"], rel=0.01)
    assert s.common.stiffness == pytest.approx(hand["common"], rel=0.01)
    # and each component on its own, well inside the 1 % (the same idealisations on both sides)
    by_name = {c.name.split(" ")[0]: c.at_output for c in s.components}
    for comp, value in hand["components"].items():
        key = {"mesh1": "mesh", "mesh2": "mesh"}.get(comp, comp)
        if key == "mesh":
            continue  # the train's meshes carry descriptive names; their sum is in the path above
        if comp not in by_name:  # a stage mesh, named in [stiffness.components] by its pair
            matches = [c.at_output for c in s.components if c.kind == "mesh" and c.name.split(" ")[0] != "mesh"
                       and math.isclose(c.at_output, value, rel_tol=1e-3)]
            assert matches, comp
            continue
        assert by_name[comp] == pytest.approx(value, rel=1e-3), comp
