"""The worm's and the wheel's STL meshes straight from the exact geometry
(geargen.profile.worm_tessellate): closed (trimesh's watertight test on the single-precision points
an STL holds), outward, and within the chordal tolerance of the exact surfaces, measured
independently of the mesher (the exact helicoid's axial offset; the exact envelope's points)."""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from geargen.families.worm.geometry import flank_axial_offset, wheel_section, worm_geometry
from geargen.families.worm.spec import WormGearSet
from geargen.profile.tessellate import mesh_volume
from geargen.profile.worm_tessellate import wheel_triangles, worm_triangles


def _test_module(relative: str):
    """A test module of this suite by path (its closed-form volumes: one copy of each)."""
    path = Path(__file__).parents[1] / relative
    spec = importlib.util.spec_from_file_location(f"_{path.stem}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _set(**changes):
    """KHK Gear Technical Reference Table 4.17 (m_x 3, z1 2, z2 30, d1 44), thinned for 0.05 mm."""
    kw = dict(axial_module=3.0, starts=2, wheel_teeth=30, worm_reference_diameter=44.0,
              pressure_angle=math.radians(20), worm_face_length=45.0, wheel_face_width=28.0, backlash=0.05)
    kw.update(changes)
    return WormGearSet(**kw)


def _closed(triangles) -> bool:
    import trimesh
    mesh = trimesh.Trimesh(**trimesh.triangles.to_kwargs(np.asarray(triangles, np.float32)))
    return bool(mesh.is_watertight and mesh.is_winding_consistent)


def worm_surface_distance(s, points):
    """Distance of points on the worm's side to its exact surface: on the tip or root cylinder
    |r - R|; else to the nearest flank helicoid z = p theta + offset(side, r) (+ k p_x, every
    thread and turn), its axial offset times the normal's axial part r / |S_r x S_theta|."""
    g = worm_geometry(s)
    p = s.hand_sign * g.screw_parameter
    rf, ra = g.worm_root_diameter / 2, g.worm_tip_diameter / 2
    x, y, z = np.asarray(points, float).T
    r, theta = np.hypot(x, y), np.arctan2(y, x)
    slope = math.tan(g.axial_pressure_angle)
    out = np.minimum(np.abs(r - ra), np.abs(r - rf))
    for side in (1, -1):
        dz = (z - p * theta - flank_axial_offset(g, side, r)) % g.axial_pitch
        dz = np.minimum(dz, g.axial_pitch - dz)
        out = np.minimum(out, dz * r / np.sqrt(p * p + r * r * (1 + slope * slope)))
    return out


@pytest.mark.parametrize("changes", [{}, {"hand": "left", "starts": 1}, {"starts": 3, "worm_face_length": 30.0}])
@pytest.mark.parametrize("tolerance", [1e-3, 1e-2])
def test_worm_mesh_is_closed_and_within_the_tolerance(changes, tolerance):
    s = _set(**changes)
    tri = worm_triangles(s, tolerance)
    assert _closed(tri)
    # every triangle's centroid and edge midpoints (the side's: the end faces are exactly planar)
    probes = np.concatenate([tri.mean(axis=1), 0.5 * (tri + np.roll(tri, -1, axis=1)).reshape(-1, 3)])
    probes = probes[np.abs(np.abs(probes[:, 2]) - s.worm_face_length / 2) > 1e-9]
    # within the tolerance (the mesher aims at 3/4 of it: half for the helix's sag, half for the twist)
    assert worm_surface_distance(s, probes).max() <= tolerance
    exact = _test_module("cad/test_worm_solid.py").exact_worm_volume(s)
    # chords lie inside a convex helix: the mesh's volume is short by at most ~ area x tolerance;
    # the worm's surface is ~8,000 mm^2 on 68,000 mm^3, so 0.13 tolerance/mm relative
    assert 0 < exact - mesh_volume(tri) < 0.15 * tolerance * exact


def point_triangle_distance(points, triangles):
    """Distance (m,) of each point to each matching triangle (m, 3, 3): the closest point of the
    triangle by its region (Ericson, Real-Time Collision Detection, 5.1.5), written out."""
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    ab, ac, ap = b - a, c - a, points - a
    dot = lambda u, v: np.einsum("ij,ij->i", u, v)  # noqa: E731
    d1, d2 = dot(ab, ap), dot(ac, ap)
    bp, cp = points - b, points - c
    d3, d4, d5, d6 = dot(ab, bp), dot(ac, bp), dot(ab, cp), dot(ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    denom = va + vb + vc
    v, w = vb / np.where(denom == 0, 1, denom), vc / np.where(denom == 0, 1, denom)
    closest = a + ab * v[:, None] + ac * w[:, None]  # inside the face
    with np.errstate(divide="ignore", invalid="ignore"):
        regions = [
            (d1 <= 0) & (d2 <= 0), a,
            (d3 >= 0) & (d4 <= d3), b,
            (d6 >= 0) & (d5 <= d6), c,
            (vc <= 0) & (d1 >= 0) & (d3 <= 0), a + ab * (d1 / (d1 - d3))[:, None],
            (vb <= 0) & (d2 >= 0) & (d6 <= 0), a + ac * (d2 / (d2 - d6))[:, None],
            (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0), b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))[:, None],
        ]
    done = np.zeros(len(points), bool)
    for mask, point in zip(regions[0::2], regions[1::2]):
        take = mask & ~done
        closest[take] = point[take]
        done |= mask
    return np.linalg.norm(points - closest, axis=1)


def mesh_distance(points, triangles, nearest: int = 48):
    """Distance of each point to the mesh: the least over the triangles with the ``nearest``
    centroids (the mesh's triangles are far smaller than the radius of curvature)."""
    from scipy.spatial import cKDTree
    _, idx = cKDTree(triangles.mean(axis=1)).query(points, k=nearest)
    d = point_triangle_distance(np.repeat(points, nearest, axis=0), triangles[idx.ravel()])
    return d.reshape(len(points), nearest).min(axis=1)


@pytest.mark.slow
@pytest.mark.parametrize("changes", [{}, {"hand": "left", "wheel_teeth": 40, "worm_reference_diameter": 33.0,
                                          "wheel_face_width": 24.0}])
def test_wheel_mesh_is_closed_and_within_the_tolerance(changes):
    tolerance = 1e-3
    s = _set(**changes)
    g = worm_geometry(s)
    tri = wheel_triangles(s, tolerance)
    assert _closed(tri)
    # the exact envelope (flanks inside the rim, trochoids) in 9 planes, to the mesh
    pts = []
    for z in np.linspace(-0.97, 0.97, 9) * s.wheel_face_width / 2:
        sec = wheel_section(s, g, float(z), n_flank=300, n_trochoid=60)
        rim = min(g.wheel_outside_diameter / 2, g.centre_distance - math.sqrt(g.throat_radius ** 2 - z * z))
        for side in (1, -1):
            f = sec.flank[side]
            run = np.vstack([f[np.hypot(f[:, 0], f[:, 1]) < rim - 1e-3], sec.trochoid[side]])
            pts.append(np.column_stack([run, np.full(len(run), z)]))
    pts = np.concatenate(pts)
    assert mesh_distance(pts, tri).max() <= tolerance
    exact = _test_module("cad/test_worm_wheel_solid.py").exact_wheel_volume(s, nodes=8)
    # measured -1e-5 and -7e-6 relative; the chords' sags (< 1 um) over ~23,000 mm^2 bound it by 1.2e-4
    assert mesh_volume(tri) == pytest.approx(exact, rel=1.2e-4)


@pytest.mark.slow
@pytest.mark.parametrize("tolerance", [1e-3, 1e-2])
def test_wheel_mesh_closed_where_a_trochoid_shrinks_to_nanometres(tolerance):
    """The worm sweep's set 2 of seed 3: at the face ends the trochoids are 7.5 and 22 nm long, their
    points a few single-precision steps apart, rounded differently in each tooth's sector (the 22
    points of one round to 13 distinct ones in one sector, 3 in another); the ends' triangles,
    sector 0's repeated by index, then missed the side's edges: 452 (1 um) and 400 (10 um) open
    edges. Neighbours are made one point by sector 0's exact points, in every sector alike."""
    s = _test_module("cad/test_worm_wheel_solid.py")._sweep_set(3, 2)
    assert (s.axial_module, s.starts, s.wheel_teeth) == (pytest.approx(4.640262, abs=1e-6), 4, 24)
    assert _closed(wheel_triangles(s, tolerance))
