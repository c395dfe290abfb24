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
    """(span, load position) of the cluster shaft measured on the built bearing and gear solids (mm),
    and the summary's cluster_shaft_bending component."""
    from geargen.pipeline import other_parts
    layout = resolve(design)
    summary, _ = stiffness(design, layout)
    parts = {p.name: p for p in other_parts(layout, None, summary).parts}
    lo = sum(_z_extent(parts["cluster_bearing_lower_a"])) / 2
    hi = sum(_z_extent(parts["cluster_bearing_upper_a"])) / 2
    small = layout.gear("cluster_small_a")
    z0, z1 = small.face_z(small.spec)
    comp = next(c for c in summary.components if c.name == "cluster_shaft_bending")
    return hi - lo, (z0 + z1) / 2 - lo, comp, summary, parts


def test_moving_the_bearings_moves_the_solids_and_changes_the_stiffness(tmp_path):
    span0, a0, comp0, s0, parts0 = _measured(_design(tmp_path, 0.02))
    span1, a1, comp1, s1, parts1 = _measured(_design(tmp_path, 0.06))
    # the solids moved: each cluster bearing 0.04 in further from the gear faces
    dz_lo = _z_extent(parts1["cluster_bearing_lower_a"])[0] - _z_extent(parts0["cluster_bearing_lower_a"])[0]
    dz_hi = _z_extent(parts1["cluster_bearing_upper_a"])[0] - _z_extent(parts0["cluster_bearing_upper_a"])[0]
    assert dz_lo == pytest.approx(-0.04 * IN, abs=1e-6) and dz_hi == pytest.approx(0.04 * IN, abs=1e-6)
    assert span1 - span0 == pytest.approx(0.08 * IN, abs=1e-6)
    # the stiffness is the simply supported beam of the solids' span and load position (closed form)
    E = 207e3
    ei = E * math.pi * (0.25 * IN) ** 4 / 64
    for span, a, comp in ((span0, a0, comp0), (span1, a1, comp1)):
        want = 3 * ei * span / (a * a * (span - a) ** 2)
        assert comp.local == pytest.approx(want, rel=1e-9)
    assert comp1.local < comp0.local  # a longer span is softer
    assert s1.drive.k1 < s0.drive.k1
    # the built geometry the reviewer measured: 0.80 in span, the small gear 0.52 in from a bearing
    assert span0 / IN == pytest.approx(0.7985, abs=1e-9) and a0 / IN == pytest.approx(0.52425, abs=1e-9)
