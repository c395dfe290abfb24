"""The compression spring meshed from its exact geometry in the build (geargen.cad.parts.SpringSolid,
geargen.cad.export.solid_triangles): the same surface as the kernel's swept solid, used for the STL
and the view, the kernel's mesh where the exact mesher declines."""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from geargen.cad import export
from geargen.cad import parts as P
from geargen.cad.export import export_stl, read_stl, solid_triangles
from geargen.model.bodies import compression_spring, spring_helix
from geargen.profile.tessellate import TessellationError, mesh_volume


def _profile_tests():
    """tests/profile/test_spring_tessellate.py (its exact surface distance and springs: one copy)."""
    path = Path(__file__).parents[1] / "profile" / "test_spring_tessellate.py"
    spec = importlib.util.spec_from_file_location("_spring_tessellate_tests", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


SPRINGS = _profile_tests().SPRINGS[:4]  # the robot joint's, the planetary's, plain, the tight one


def _shell_distance(shape, points):
    """Distance (mm) of each point from the kernel solid's boundary (BRepExtrema on its shell)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer
    shell = TopExp_Explorer(shape, TopAbs_SHELL).Current()
    return np.array([BRepExtrema_DistShapeShape(BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, p))).Vertex(), shell).Value()
                     for p in points])


def _tight_sweep(monkeypatch):
    """geargen.cad.parts' sweep fitted to 1e-7 mm (MakePipeShell's 3-D tolerance, 1e-4 by default)."""
    from OCP.BRepOffsetAPI import BRepOffsetAPI_MakePipeShell

    class Tight(BRepOffsetAPI_MakePipeShell):
        def Build(self):
            self.SetTolerance(1e-7, 1e-7, 1e-6)
            return super().Build()

    monkeypatch.setattr(P, "BRepOffsetAPI_MakePipeShell", Tight)


@pytest.mark.parametrize("spring", SPRINGS)
@pytest.mark.parametrize("tight", [False, True])
def test_exact_spring_mesh_lies_on_the_kernels_solid(spring, tight, monkeypatch):
    """Same helix (z0, pitch, right hand, start at angle 0), same circle, same frame, same cut: the
    exact mesh's vertices lie on the kernel's faces, and the kernel's own mesh nodes on the exact
    surface. As built: within 5e-5 mm (measured 0.5-2.5e-5 mm both ways), the kernel's swept face
    being its B-spline fit of the sweep to MakePipeShell's default 1e-4 mm; with the sweep fitted to
    1e-7 mm, the vertices within 1e-6 mm of it, its nodes within 2e-6 of the exact surface (measured
    2e-7 on the faces, 1.04e-6 at a node on the kernel's cut edge, whose tolerance is 5e-6): the
    exact surface is the one the kernel approximates."""
    if tight:
        _tight_sweep(monkeypatch)
    bound, node_bound = (1e-6, 2e-6) if tight else (5e-5, 5e-5)
    profile = _profile_tests()
    shape = P.compression_spring(*spring)
    solid = P.SpringSolid(shape, spring)
    tri = solid.exact_triangles(0.05)
    vertices = np.unique(tri.reshape(-1, 3), axis=0)
    sample = vertices[:: max(1, len(vertices) // 250)]
    assert _shell_distance(shape, sample).max() < bound
    nodes = np.unique(export.kernel_triangles(shape, 0.01, 0.5).reshape(-1, 3), axis=0)
    assert profile.spring_surface_distance(spring, nodes).max() < node_bound
    # the check resolves a frame 1e-3 rad off (a start angle, a hand): those vertices are ~5 um out
    turn = np.array([[math.cos(1e-3), -math.sin(1e-3), 0], [math.sin(1e-3), math.cos(1e-3), 0], [0, 0, 1]])
    assert _shell_distance(shape, sample @ turn.T).max() > 1e-3


def test_spring_stl_is_exact_closed_and_encloses_the_kernels_volume(tmp_path):
    spring = SPRINGS[0]
    d, mean, length, coils, _ = spring
    shape = P.compression_spring(*spring)
    solid = P.SpringSolid(shape, spring)
    rec = export_stl(solid, tmp_path / "spring.stl", 0.05)
    assert rec.mesher == "exact"
    kernel = export.kernel_triangles(shape, 0.05, 0.5)
    # fewer triangles than the kernel at the same tolerance (13,142 on this spring)
    assert rec.triangles < 0.5 * len(kernel)
    tri = read_stl(rec.path)
    import trimesh
    mesh = trimesh.Trimesh(**trimesh.triangles.to_kwargs(tri))
    assert mesh.is_watertight and mesh.is_winding_consistent
    # inscribed in the solid within 0.05 mm: short of the kernel's volume by less than area x 0.05
    # (area: the wire's lateral pi d x pi D n, and a tenth for the ends)
    area = math.pi * d * math.pi * mean * coils * 1.1
    assert 0 < P.volume(shape) - mesh_volume(tri) < area * 0.05


def test_spring_the_exact_mesher_declines_is_meshed_by_the_kernel(monkeypatch):
    import geargen.profile.spring_tessellate as spring_tessellate

    spring = SPRINGS[0]
    solid = P.SpringSolid(P.compression_spring(*spring), spring)

    def declines(*args, **kwargs):
        raise TessellationError("declined")

    monkeypatch.setattr(spring_tessellate, "spring_triangles", declines)
    triangles, mesher = solid_triangles(solid, 0.05)
    assert mesher == "occt"
    assert np.array_equal(triangles, export.kernel_triangles(solid.shape, 0.05, 0.5))


def test_spring_components_carry_their_exact_mesher_once_per_solid():
    """The view and the STL mesh a part's mesh_source: a gear's solid, a spring's SpringSolid (one per
    solid: two springs alike share it, so they are meshed once), else the shape."""
    from geargen.cad.assembly import PlacedPart
    from geargen.cad.components import SolidBuilder
    from geargen.model.bodies import cylinder
    from geargen.model.components import Component

    body = compression_spring(*SPRINGS[0][:4], ground=True)
    builder = SolidBuilder()
    springs = [Component(f"spring_{i}", body, np.eye(4), "g", "spring", shared=True) for i in (1, 2)]
    shapes = [builder.component(c) for c in springs]
    exact = [builder.exact(c, s) for c, s in zip(springs, shapes)]
    assert shapes[0] is shapes[1] and exact[0] is exact[1] and exact[0].shape is shapes[0]
    assert exact[0].args == SPRINGS[0]
    plain = Component("spacer", cylinder(10.0, 5.0), np.eye(4), "g", "shaft")
    assert builder.exact(plain, builder.component(plain)) is None
    part = PlacedPart("spring_1", shapes[0], np.eye(4), "g", "spring", exact=exact[0])
    assert part.mesh_source is exact[0]
    assert PlacedPart("spacer", shapes[0], np.eye(4), "g", "shaft").mesh_source is shapes[0]
    z0, pitch = spring_helix(SPRINGS[0])
    assert (z0, pitch) == (0.0, SPRINGS[0][2] / SPRINGS[0][3])
