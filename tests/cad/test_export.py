"""STEP (unit, names, re-imported volume) and STL (tolerance, manifest, watertight), atomic writes."""

import json
import math

import numpy as np
import pytest

from geargen.cad import export
from geargen.cad.export import export_step, export_stl, read_step, read_stl, update_manifest
from geargen.cad.gear_solid import build_cluster, solid_volume
from geargen.cad.measure import mesh_deviation
from geargen.design.cluster import ClusterSpec
from geargen.design.gear import Hub
from geargen.profile.tessellate import mesh_volume

pytestmark = pytest.mark.slow


def test_step_states_the_inch_unit_and_keeps_the_name(spur112, tmp_path):
    rec = export_step(spur112, tmp_path / "output.step", "in")
    text = rec.path.read_text()
    assert "CONVERSION_BASED_UNIT('INCH'" in text
    assert "PRODUCT('output'" in text
    back = read_step(rec.path)
    assert back.units == ["INCH"]
    assert back.names == ["output"]
    # coordinates were written in inches and read back in mm: same solid
    assert solid_volume(back.shape) == pytest.approx(solid_volume(spur112.shape), rel=1e-9)


def test_step_in_mm_with_two_named_parts(make_spec, tmp_path):
    from geargen.cad.gear_solid import build_gear
    helical = build_gear(make_spec(18, helix=25, face=4.0, name="pinion"))
    spur = build_gear(make_spec(19, face=3.0, hub=Hub(bore_diameter=2.0)))
    rec = export_step([helical, ("second", spur.shape)], tmp_path / "two.step", "mm")
    assert "SI_UNIT(.MILLI.,.METRE.)" in rec.path.read_text()
    back = read_step(rec.path)
    assert back.units == ["millimetre"]
    assert sorted(back.names) == ["pinion", "second"]
    total = solid_volume(helical.shape) + solid_volume(spur.shape)
    assert solid_volume(back.shape) == pytest.approx(total, rel=1e-9)


def _edges_are_manifold(tri: np.ndarray) -> bool:
    """Every directed edge appears once and its reverse once: closed, consistently oriented."""
    key = np.round(tri.reshape(-1, 3) * 1e5).astype(np.int64)  # STL is float32: ~1e-6 mm resolution
    _, inv = np.unique(key, axis=0, return_inverse=True)
    f = inv.reshape(-1, 3).astype(np.int64)
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    n = int(f.max()) + 1
    fwd = np.sort(e[:, 0] * n + e[:, 1])
    rev = np.sort(e[:, 1] * n + e[:, 0])
    return bool(np.all(np.diff(fwd) > 0) and np.array_equal(fwd, rev))


@pytest.mark.parametrize("which", ["spur112", "helical21"])
def test_stl_within_chordal_tolerance_and_watertight(which, request, tmp_path):
    solid = request.getfixturevalue(which)
    tol = 1e-3
    rec = export_stl(solid, tmp_path / f"{solid.name}.stl", tol)
    update_manifest(tmp_path, [rec])
    manifest = json.loads((tmp_path / "manifest.json").read_text())
    entry = manifest["files"][f"{solid.name}.stl"]
    assert entry["chordal_tolerance_mm"] == tol and entry["length_unit"] == "mm"
    tri = read_stl(rec.path)
    assert entry["triangles"] == len(tri)
    assert _edges_are_manifold(tri)
    # every checked point within the tolerance of the exact tooth surface (float32 STL: +1e-6)
    assert mesh_deviation(tri, solid.profile, solid.spec.face_width) <= tol + 1e-5
    # chords lie inside convex parts: the mesh volume is within tol x side area of the solid's
    side = 2 * math.pi * solid.profile.tip_radius * 3 * solid.spec.face_width
    assert abs(mesh_volume(tri) - solid_volume(solid.shape)) <= tol * side


def test_stl_of_a_cluster_and_manifest_merge(tmp_path, make_spec):
    large = make_spec(48, face=4.7625, hub=Hub(bore_diameter=6.35))
    small = make_spec(21, face=7.9375, hub=Hub(bore_diameter=6.35))
    g = build_cluster(ClusterSpec(large, small, axial_gap=1.0, name="cluster"))
    r1 = export_stl(g, tmp_path / "cluster.stl", 2e-3)
    r2 = export_step(g, tmp_path / "cluster.step", "in")
    update_manifest(tmp_path, [r1])
    update_manifest(tmp_path, [r2])
    files = json.loads((tmp_path / "manifest.json").read_text())["files"]
    assert set(files) == {"cluster.stl", "cluster.step"}
    assert files["cluster.stl"]["mesher"] == "exact"
    tri = read_stl(r1.path)
    assert _edges_are_manifold(tri)
    assert mesh_volume(tri) == pytest.approx(solid_volume(g.shape), rel=1e-3)


def test_a_failed_write_leaves_nothing_behind(helical21, tmp_path, monkeypatch):
    target = tmp_path / "pinion.stl"
    target.write_bytes(b"old file")

    def broken(path, triangles):
        with open(path, "wb") as fh:
            fh.write(b"half a file")
        raise OSError("disk full")

    monkeypatch.setattr(export, "write_stl", broken)
    with pytest.raises(OSError):
        export_stl(helical21, target)
    assert target.read_bytes() == b"old file"  # untouched
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pinion.stl"]  # no temporary left


@pytest.mark.parametrize("helix", [0.0, 15.0])
def test_stl_of_keyway_and_hub(helix, tmp_path, make_spec):
    from geargen.cad.gear_solid import build_gear
    spec = make_spec(24, module=1.0, helix=helix, face=6.0,
                     hub=Hub(bore_diameter=5.0, keyway_width=2.0, keyway_depth=1.0, hub_diameter=12.0, hub_length=4.0))
    g = build_gear(spec)
    rec = export_stl(g, tmp_path / "g.stl", 1e-3)
    assert rec.mesher == "exact"
    tri = read_stl(rec.path)
    assert _edges_are_manifold(tri)
    assert mesh_deviation(tri, g.profile, spec.face_width) <= 1e-3 + 1e-5
    assert mesh_volume(tri) == pytest.approx(solid_volume(g.shape), rel=2e-4)


def test_stl_transform_places_the_exact_mesh(helical21, tmp_path):
    angle = 0.3
    m = np.eye(4)
    m[:2, :2] = [[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]]
    m[:3, 3] = [10.0, -5.0, 2.0]
    a = read_stl(export_stl(helical21, tmp_path / "a.stl").path)
    b = read_stl(export_stl(helical21, tmp_path / "b.stl", transform=m).path)
    np.testing.assert_allclose(b, a @ m[:3, :3].T + m[:3, 3], atol=1e-5)  # float32 STL


def test_kernel_stl_of_a_sphere_is_watertight(tmp_path):
    # issue 31: the kernel meshes a sphere's poles (degenerated edges) into zero-area triangles whose
    # corners lie ~1e-16 mm apart; once an STL reader merges them, each pole leaves an open edge
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeSphere
    rec = export_stl(BRepPrimAPI_MakeSphere(10.0).Shape(), tmp_path / "ball.stl", 1e-2)
    tri = read_stl(tmp_path / "ball.stl")
    assert rec.triangles == len(tri)
    assert _edges_are_manifold(tri)
    # no triangle lost but the degenerate ones: the mesh (vertices on the sphere, chords inside it
    # by at most the 0.01 mm tolerance) encloses a volume between the balls of radius 9.99 and 10
    assert 4 / 3 * math.pi * 9.99 ** 3 < mesh_volume(tri) < 4 / 3 * math.pi * 10 ** 3


def test_a_solid_placed_twice_is_meshed_once_into_the_same_triangles(helical21, monkeypatch):
    # the build meshes each solid once (Tessellations) and places it per part: the placed triangles
    # must be exactly those of meshing it for that placement, and the mesher must run once
    angle = 0.7
    m = np.eye(4)
    m[:2, :2] = [[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]]
    m[:3, 3] = [4.0, 3.0, -1.0]
    direct = [export.solid_triangles(helical21, 2e-3, transform=t)[0] for t in (None, m)]
    calls = []
    meshing = export.solid_triangles
    monkeypatch.setattr(export, "solid_triangles", lambda *a, **k: calls.append(a) or meshing(*a, **k))
    meshes = export.Tessellations()
    placed = [meshes.triangles(helical21, 2e-3, transform=t)[0] for t in (None, m)]
    assert len(calls) == 1
    for a, b in zip(direct, placed):
        assert np.array_equal(a, b)  # bit for bit: the files written from them stay the same
    # another tolerance is another mesh
    meshes.triangles(helical21, 4e-3)
    assert len(calls) == 2


def test_the_step_writer_skips_the_kernels_model_check_and_writes_the_same_bytes(helical21, tmp_path, monkeypatch):
    """The kernel's check of every entity (which nothing written reads) is marked done before the
    transfer: the model ends up without its results, and the file is byte for byte the one a writer
    that checks writes."""
    writers = []
    skip_check = export.unchecked
    monkeypatch.setattr(export, "unchecked", lambda writer: writers.append(skip_check(writer)) or writer)
    fast = export_step(helical21, tmp_path / "fast.step").path.read_bytes()
    monkeypatch.setattr(export, "unchecked", lambda writer: writers.append(writer) or writer)
    checked = export_step(helical21, tmp_path / "checked.step").path.read_bytes()
    assert [w.ChangeWriter().WS().Model().HasSemanticChecks() for w in writers] == [False, True]
    assert fast == checked


def test_kernel_triangles_of_a_located_shape_are_moved_by_its_location():
    """A shape placed by a location (its faces' triangulations are the unplaced shape's, read at that
    location) comes out moved by it: the same triangles as the unplaced shape's moved in numpy."""
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt, gp_Trsf, gp_Vec
    from OCP.TopLoc import TopLoc_Location
    box = BRepPrimAPI_MakeBox(10.0, 20.0, 30.0).Shape()
    trsf = gp_Trsf()
    trsf.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(1, 1, 1)), 0.7)
    trsf.SetTranslationPart(gp_Vec(5.0, -3.0, 2.0))
    placed = export.kernel_triangles(box.Moved(TopLoc_Location(trsf)), 0.01, 0.5)
    matrix = np.array([[trsf.Value(i, j) for j in range(1, 5)] for i in range(1, 4)])
    expected = export.kernel_triangles(box, 0.01, 0.5) @ matrix[:, :3].T + matrix[:, 3]
    assert placed.shape == (12, 3, 3)  # a box's six faces, two triangles each
    # two roundings of a product of 30 mm coordinates and unit rotation terms: ~1e-14 mm apart
    assert np.abs(placed - expected).max() < 1e-12
