"""The bevel gear's exact mesher (geargen.profile.bevel_tessellate, BevelSolid.exact_triangles): closed
and outward (trimesh on the single-precision points an STL holds), every vertex on the solid built by
the kernel, every triangle within the chordal tolerance of it (distances measured by the kernel,
BRepExtrema, against the solid's shell), its volume the closed form's within what the tolerance allows."""

import math

import numpy as np
import pytest

from geargen.families.registry import read_gear

pytestmark = pytest.mark.slow

ROBOT = dict(kind="bevel", diametral_pitch_per_in=32, face_width_in=0.15, thinning_circumferential_in=0.00075)
CROWN = dict(kind="bevel", teeth=30, mate_teeth=15, shaft_angle_deg=120, module_mm=1.0, face_width_mm=4.0,
             bore_diameter_mm=6.0)
#: every core build_bevel makes (geargen.families.bevel.geometry.bevel_core), the robot joint's two first
CASES = {
    # the robot joint's gear: flat back with a web (its toe sphere lies beyond the back plane) and a bore
    "robot_gear": ({**ROBOT, "teeth": 30, "mate_teeth": 15, "bore_diameter_in": 0.1875}, "flat"),
    # the robot joint's pinion: flat back, no bore (the toe face reaches the pole), flank from the base cone
    "robot_pinion": ({**ROBOT, "teeth": 15, "mate_teeth": 30}, "flat"),
    "web_without_bore": ({**ROBOT, "teeth": 30, "mate_teeth": 15}, "flat"),
    "bore_through_web": ({**ROBOT, "teeth": 30, "mate_teeth": 15, "bore_diameter_in": 0.5}, "flat"),
    "spherical_bore": ({**ROBOT, "teeth": 15, "mate_teeth": 30, "bore_diameter_in": 0.1}, "spherical"),
    "spherical_poles": (dict(kind="bevel", teeth=12, mate_teeth=25, module_mm=1.0, face_width_mm=4.0, profile_shift=0.3),
                        "spherical"),
    "crown_spherical": (CROWN, "spherical"),  # tip cone past 90 deg
    "crown_flat": (CROWN, "flat"),
}


def _solid(case):
    from geargen.families.bevel.solid import build_bevel
    table, back = CASES[case]
    return build_bevel(read_gear(table), check=True, back=back)


def surface_distance(shape, points) -> np.ndarray:
    """Distance of each point to the boundary of ``shape`` (its shell), by the kernel."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer
    shell = TopExp_Explorer(shape, TopAbs_SHELL).Current()
    out = []
    for p in np.asarray(points, float):
        vertex = BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, p))).Vertex()
        out.append(BRepExtrema_DistShapeShape(vertex, shell).Value())
    return np.array(out)


def _probes(tri: np.ndarray, rng) -> np.ndarray:
    """Points where a flat triangle strays farthest from a curved face: centroids and edge midpoints of
    the 60 largest triangles and of 60 others at random."""
    area = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    pick = np.unique(np.concatenate([np.argsort(area)[-60:], rng.choice(len(tri), 60, replace=False)]))
    t = tri[pick]
    return np.concatenate([t.mean(axis=1), 0.5 * (t + np.roll(t, -1, axis=1)).reshape(-1, 3)])


@pytest.mark.parametrize("tolerance", [0.005, 0.45])  # the robot joint's STL and (about) its view's
@pytest.mark.parametrize("case", list(CASES))
def test_mesh_is_closed_on_the_solid_and_within_the_tolerance(case, tolerance):
    import trimesh

    from geargen.families.bevel.geometry import bevel_volume
    from geargen.profile.tessellate import mesh_volume
    solid = _solid(case)
    tri = solid.exact_triangles(tolerance)
    mesh = trimesh.Trimesh(**trimesh.triangles.to_kwargs(tri.astype(np.float32)))
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    rng = np.random.default_rng(28)
    vertices = np.unique(tri.reshape(-1, 3), axis=0)
    # every vertex an exact surface point: the flank's B-spline lies within 1.3e-9 mm of the spherical
    # involute the vertices are on (FLANK_TOLERANCE), the rest is rounding
    assert surface_distance(solid.shape, vertices[rng.choice(len(vertices), 120, replace=False)]).max() < 1e-6
    # every triangle within the tolerance; 1e-9: the flank's B-spline lies up to 1.3e-9 mm off the involute
    assert surface_distance(solid.shape, _probes(tri, rng)).max() <= tolerance + 1e-9
    # the space between the mesh and the solid lies within the tolerance of the mesh's surface, so the
    # volumes differ by at most its area times the tolerance
    exact = bevel_volume(solid.spec, solid.back)
    assert abs(mesh_volume(tri) - exact) <= mesh.area * tolerance


def test_mesh_volume_converges_to_the_closed_form():
    # chords lie inside the convex flanks and cones: the shortfall shrinks with the tolerance (the
    # volume between a chord and its arc goes as the sag): 8e-4 of the volume at 5 um, so about
    # 8e-4 / 5 = 1.6e-4 at 1 um, below 2e-4
    from geargen.families.bevel.geometry import bevel_volume
    from geargen.profile.tessellate import mesh_volume
    solid = _solid("robot_gear")
    exact = bevel_volume(solid.spec, solid.back)
    shortfall = [exact - mesh_volume(solid.exact_triangles(t)) for t in (0.005, 0.001)]
    assert 0 < shortfall[1] < shortfall[0] < 1e-3 * exact
    assert shortfall[1] < 2e-4 * exact


def test_the_teeth_are_tooth_0_turned():
    # tooth k is tooth 0 turned by k pitches (as the solid is built): the vertices of the teeth (polar
    # angle past the root cone's) are the same set after a turn of one pitch, to rounding
    from scipy.spatial import cKDTree

    from geargen.families.bevel.geometry import bevel_geometry
    solid = _solid("robot_pinion")
    tri = solid.exact_triangles(0.005)
    points = np.unique(tri.reshape(-1, 3), axis=0)
    polar = np.arccos(points[:, 2] / np.linalg.norm(points, axis=1))
    teeth = points[polar > bevel_geometry(solid.spec).root_cone_angle + 1e-9]
    pitch = 2 * math.pi / solid.spec.teeth
    c, s = math.cos(pitch), math.sin(pitch)
    turned = teeth @ np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]).T
    assert len(teeth) > 20 * solid.spec.teeth
    assert cKDTree(teeth).query(turned)[0].max() < 1e-9


def test_export_uses_the_exact_mesher_and_falls_back_to_the_kernel(monkeypatch):
    from geargen.cad import export
    from geargen.profile import bevel_tessellate
    from geargen.profile.tessellate import TessellationError
    solid = _solid("robot_gear")
    tri, mesher = export.solid_triangles(solid, 0.005)
    assert mesher == "exact" and np.array_equal(tri, solid.exact_triangles(0.005))

    def refuse(*args):
        raise TessellationError("not this one")
    monkeypatch.setattr(bevel_tessellate, "bevel_triangles", refuse)
    monkeypatch.setattr("geargen.families.bevel.solid.bevel_triangles", refuse)
    tri, mesher = export.solid_triangles(solid, 0.005)
    assert mesher == "occt" and len(tri) > 0


def test_an_open_mesh_is_refused():
    # the closing check: a triangle left out, or one turned over, is a TessellationError (the kernel
    # then meshes the solid), never a wrong mesh written
    from geargen.profile.bevel_tessellate import _check_closed
    from geargen.profile.tessellate import TessellationError
    tetra = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    _check_closed(tetra, 4)
    with pytest.raises(TessellationError):
        _check_closed(tetra[1:], 4)
    with pytest.raises(TessellationError):
        _check_closed(np.concatenate([tetra[:1, ::-1], tetra[1:]]), 4)


def test_the_robot_joints_bevel_parts_are_meshed_exactly():
    # the build's bevel gears are hardware components (not gears for the checks: no ``solid``), placed
    # with their family's solid, so the STL export and the view mesh them with the exact mesher
    from pathlib import Path

    from geargen import pipeline as P
    from geargen.cad.export import solid_triangles
    from geargen.families.bevel.solid import BevelSolid
    design = P.load(Path(__file__).parents[2] / "assemblies/robot_joint.toml")
    parts = {p.name: p for p in P.other_parts(P.place(design)).parts}
    for name in ("bevel_gear", "bevel_pinion"):
        part = parts[name]
        assert part.solid is None and isinstance(part.exact, BevelSolid) and part.toothed
        assert part.exact.shape.IsSame(part.shape) and part.mesh_source is part.exact
        assert solid_triangles(part.mesh_source, 0.05)[1] == "exact"
    assert parts["link"].mesh_source is parts["link"].shape  # any other part: the kernel's
