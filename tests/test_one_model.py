"""One home for every length: the solids and the stiffness read the same placed shafts.

Moving the bearings in the design file ([parts] bearing_clearance) moves the bearing solids and
changes the computed shaft stiffness, and the stiffness is the closed form of the beam measured
on the solids themselves (bearing mid-widths and the gear's mid-face from the bodies' extents).
"""

import math
from pathlib import Path

import pytest

from geargen.design.assembly import load_design
from geargen.model import resolve
from geargen.model.analysis import stiffness

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]
IN = 25.4


def _design(tmp_path, clearance_in: float):
    text = (ROOT / "assemblies/robot_joint.toml").read_text()
    old = "bearing_clearance_in = 0.02 "
    assert old in text
    path = tmp_path / f"robot_joint_{clearance_in}.toml"
    path.write_text(text.replace(old, f"bearing_clearance_in = {clearance_in} "))
    return load_design(path)


def _z_extent(part) -> tuple[float, float]:
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    box = Bnd_Box()
    BRepBndLib.Add_s(part.world(), box, False)
    box.SetGap(0.0)
    _, _, z0, _, _, z1 = box.Get()
    return z0, z1


def _measured(design):
    """(span, load position from the lower support) of cluster A's shaft measured on the built
    bearing and gear solids (mm), the summary's cluster_support component, the summary, the parts."""
    from geargen.pipeline import other_parts
    layout = resolve(design)
    summary, _ = stiffness(design, layout)
    parts = {p.name: p for p in other_parts(layout, None, summary).parts}
    lo = sum(_z_extent(parts["cluster_bearing_lower_a"])) / 2
    hi = sum(_z_extent(parts["cluster_bearing_upper_a"])) / 2
    small = layout.gear("cluster_small_a")
    z0, z1 = small.face_z(small.spec)
    comp = next(c for c in summary.components if c.name == "cluster_support")
    return hi - lo, (z0 + z1) / 2 - lo, comp, summary, parts


def test_moving_the_bearings_moves_the_solids_and_changes_the_stiffness(tmp_path):
    span0, a0, comp0, s0, parts0 = _measured(_design(tmp_path, 0.02))
    span1, a1, comp1, s1, parts1 = _measured(_design(tmp_path, 0.06))
    # the solids moved: each cluster bearing 0.04 in further from the gear faces
    dz_lo = _z_extent(parts1["cluster_bearing_lower_a"])[0] - _z_extent(parts0["cluster_bearing_lower_a"])[0]
    dz_hi = _z_extent(parts1["cluster_bearing_upper_a"])[0] - _z_extent(parts0["cluster_bearing_upper_a"])[0]
    assert dz_lo == pytest.approx(-0.04 * IN, abs=1e-6) and dz_hi == pytest.approx(0.04 * IN, abs=1e-6)
    assert span1 - span0 == pytest.approx(0.08 * IN, abs=1e-6)
    # the stiffness is the simply supported beam of the solids' span and load position on two
    # 10 N/um bearings (closed form: beam on rigid supports + the bearings through their levers)
    E, kb = 207e3, 10e3
    ei = E * math.pi * (0.25 * IN) ** 4 / 64
    for span, a, comp in ((span0, a0, comp0), (span1, a1, comp1)):
        b = span - a
        want = 1 / (a * a * b * b / (3 * ei * span) + ((b / span) ** 2 + (a / span) ** 2) / kb)
        assert comp.local == pytest.approx(want, rel=1e-9)
    assert comp1.local < comp0.local  # a longer span is softer
    assert s1.drive.k1 < s0.drive.k1
    # the built geometry the reviewer measured: 0.80 in span, the small gear 0.52 in from a bearing
    assert span0 / IN == pytest.approx(0.7985, abs=1e-9) and a0 / IN == pytest.approx(0.52425, abs=1e-9)


def test_c_axis_pinion_overhung_on_its_quill_bearings():
    """The C-axis dual pinion sits 53.5 mm beyond the upper of two 150 N/um bearings 30 mm apart
    (measured on the solids): about 12 N/um at the pinion, not the 300 N/um of two bearings in
    parallel, each path about 2.4e5 N m/rad (was 2.39e6), and 78 um of misalignment across the
    30 mm face at the preload (the reviewer's numbers, from a hand calculation)."""
    span, load, comp, summary, _ = _measured(load_design(ROOT / "assemblies/c_axis.toml"))
    c = load - span  # overhang beyond the upper support
    assert span == pytest.approx(30.0, abs=1e-6) and c == pytest.approx(53.5, abs=1e-6)
    E, kb, d = 207e3, 150e3, 30.0
    ei = E * math.pi * d ** 4 / 64
    # overhung beam c beyond two rigid supports, plus the bearings through their levers
    compliance = c * c * (span + c) / (3 * ei) + (((span + c) / span) ** 2 + (c / span) ** 2) / kb
    assert comp.local == pytest.approx(1 / compliance, rel=1e-9)
    assert comp.local / 1e3 == pytest.approx(12.1, abs=0.1)  # N/um
    assert summary.drive.k1 / 1e3 == pytest.approx(2.40e5, rel=0.01)  # N m/rad
    (sup,) = [x for x in summary.supports if x.component == "cluster_support"]
    # tilt at the overhang's end: rigid-body rotation on the bearings plus the beam's slope
    tilt = ((span + c) / span / kb + c / span / kb) / span + c * (2 * span + 3 * c) / (6 * ei)
    assert sup.tilt == pytest.approx(sup.force * tilt, rel=1e-9)
    assert sup.misalignment * 1e3 == pytest.approx(78, abs=1)  # um across the 30 mm face
    assert any("misalignment" in w for w in summary.warnings)
