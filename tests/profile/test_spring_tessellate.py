"""The compression spring's mesh straight from its exact geometry (geargen.profile.spring_tessellate):
closed and outward (trimesh, on the single-precision points an STL holds), every vertex on the
exact surface, every triangle within the chordal tolerance of it, measured independently of the
mesher (distances to points of the exact surface written out below), and its volume tending to
the closed form (Pappus, less the ground ends)."""

import math

import numpy as np
import pytest

from geargen.model.bodies import spring_helix
from geargen.profile.spring_tessellate import spring_triangles
from geargen.profile.tessellate import TessellationError, mesh_volume

#: (d, D, length, total coils, ground): the robot joint's spring, the planetary dual pinion's, the
#: same as plain ends, and the extremes the hardware allows (index D/d just over 2.5, pitch just
#: over d; a fractional coil count; a ground spring of 1.5 coils, its end cuts near each other)
SPRINGS = [(1.143, 11.43, 8.89, 6.0, True), (1.4, 13.0, 11.3, 6.0, True), (1.143, 11.43, 8.89, 6.0, False),
           (2.0, 5.2, 2.05 * 7.5, 7.5, True), (0.5, 20.0, 12.0, 3.25, False), (1.0, 8.0, 3.0, 1.5, True)]


def spring_surface_distance(spring, points):
    """An upper bound (the exact value where the nearest point lies in the point's own half-plane
    through the axis) of the distance of ``points`` (k, 3) from the spring's surface: the least
    distance to points OF that surface, found in the half-plane through the axis at the point's
    angle phi: the wire's circles there (centre (R, z0 + c (phi + 2 pi k)), radius a) where they lie
    in the slab, a ground end's lens in its plane and the ends of its outline, the end discs."""
    d, mean, length, coils, ground = spring
    z0, pitch = spring_helix(spring)
    a, big_r, c, turns = d / 2, mean / 2, pitch / (2 * math.pi), 2 * math.pi * coils
    x, y, z = np.asarray(points, float).T
    r, phi = np.hypot(x, y), np.arctan2(y, x) % (2 * math.pi)
    best = np.full(len(r), np.inf)
    low, high = (0.0, length) if ground else (-np.inf, np.inf)
    for k in range(-1, math.ceil(coils) + 1):
        angle = phi + 2 * math.pi * k
        # a point a rounding past an end (the kernel's nodes on the end edge read ~1e-9 rad past it)
        # is measured from its end half-plane, plus the arc r x excess it is turned back by
        clipped = np.clip(angle, 0.0, turns)
        excess = np.abs(angle - clipped)
        inside = excess <= 1e-6
        angle = clipped
        zc = z0 + c * angle
        dr, dz = r - big_r, z - zc
        far = np.hypot(dr, dz)
        qz = zc + a * dz / np.maximum(far, 1e-300)  # the circle's nearest point
        ok = inside & (qz >= low - 1e-12) & (qz <= high + 1e-12)
        best = np.where(ok, np.minimum(best, np.abs(far - a) + r * excess), best)
        if ground:
            for plane in (0.0, length):
                # the lens: the circle's disc in the plane; the outline: the circle's points in it
                half = np.sqrt(np.maximum(a * a - (plane - zc) ** 2, 0.0))
                meets = inside & (np.abs(plane - zc) <= a)
                in_lens = meets & (np.abs(dr) <= half)
                best = np.where(in_lens, np.minimum(best, np.abs(z - plane) + r * excess), best)
                for side in (-1, 1):
                    best = np.where(meets, np.minimum(best, np.hypot(dr - side * half, z - plane) + r * excess), best)
    # the end discs (half discs of a ground spring) in the half-planes at phi = 0 and at the end
    for angle in (0.0, turns):
        u = x * math.cos(angle) + y * math.sin(angle)  # along the half-plane, from the axis
        off = -x * math.sin(angle) + y * math.cos(angle)  # across it
        zc = z0 + c * angle
        on = np.hypot(u - big_r, z - zc) <= a
        if ground:
            on &= (z >= 0) & (z <= length)
        best = np.where(on & (u > 0), np.minimum(best, np.abs(off)), best)
    return best


def _facing_out(spring, triangles):
    """Per triangle, its normal's component along the solid's outward direction at its centroid:
    -z / +z on a ground spring's end planes, -e_phi / +e_phi on its end half-planes, elsewhere from
    the nearest of the wire's centres (R, z0 + c phi) in the centroid's half-plane."""
    d, mean, length, coils, ground = spring
    z0, pitch = spring_helix(spring)
    c, turns, end = pitch / (2 * math.pi), 2 * math.pi * coils, 2 * math.pi * coils
    normal = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    x, y, z = triangles.mean(axis=1).T
    r, phi = np.hypot(x, y), np.arctan2(y, x) % (2 * math.pi)
    k = np.clip(np.round((z - z0 - c * phi) / pitch), -phi // (2 * math.pi), (turns - phi) // (2 * math.pi))
    zc = z0 + c * (phi + 2 * math.pi * k)
    out = np.stack([(r - mean / 2) * x / r, (r - mean / 2) * y / r, z - zc], axis=1)
    on = lambda v: np.all(np.abs(v) < 1e-9, axis=1)  # noqa: E731 - every corner in a plane
    low = z < z0 + c * turns / 2  # the two end half-planes are one for whole coils: told apart by z
    planes = [(on(triangles[..., 1]) & (x > 0) & low, [0.0, -1.0, 0.0]),
              (on(-triangles[..., 0] * math.sin(end) + triangles[..., 1] * math.cos(end)) & ~low,
               [-math.sin(end), math.cos(end), 0.0])]
    if ground:
        planes += [(on(triangles[..., 2]), [0.0, 0.0, -1.0]), (on(triangles[..., 2] - length), [0.0, 0.0, 1.0])]
    for mask, direction in planes:
        out[mask] = direction
    return np.einsum("ij,ij->i", normal, out)


def _closed(triangles):
    import trimesh
    mesh = trimesh.Trimesh(**trimesh.triangles.to_kwargs(np.asarray(triangles, np.float32)))
    return mesh.is_watertight, mesh.is_winding_consistent, mesh.volume


def _probes(triangles, n: int = 6):
    """Points spread over each triangle: the barycentric grid of step 1/n (corners, edges, inside)."""
    weights = np.array([(i, j, n - i - j) for i in range(n + 1) for j in range(n + 1 - i)], float) / n
    return np.einsum("pk,tkc->tpc", weights, triangles).reshape(-1, 3)


def exact_volume(spring) -> float:
    """Pappus (the wire circle lies in a half-plane through the axis) less the ground ends' half discs
    below each end plane (geargen.cad.parts.compression_spring's docstring)."""
    d, mean, _, coils, ground = spring
    _, pitch = spring_helix(spring)
    return math.pi ** 2 * d * d * mean * coils / 4 - (math.pi * mean * d ** 3 / (6 * pitch) if ground else 0.0)


@pytest.mark.parametrize("spring", SPRINGS)
@pytest.mark.parametrize("tolerance", [0.45, 0.05, 1e-3])
def test_spring_mesh_is_closed_on_the_surface_and_within_the_tolerance(spring, tolerance):
    d, mean, length, coils, ground = spring
    z0, pitch = spring_helix(spring)
    tri = spring_triangles(d, mean, z0, pitch, coils, tolerance, (0.0, length) if ground else None)
    watertight, consistent, volume = _closed(tri)
    assert watertight and consistent and volume > 0
    # every facet faces out, not only the mesh as a whole: on the flat faces along their outward
    # normal, on the side away from the wire's centre line in the facet's half-plane through the axis
    assert np.all(_facing_out(spring, tri) > 0)
    # every vertex on the exact surface (1e-12 mm: the rounding of coordinates of ~10 mm)
    vertices = np.unique(tri.reshape(-1, 3), axis=0)
    assert spring_surface_distance(spring, vertices).max() < 1e-12
    # a ground spring in the slab, reaching both of its planes (its cut faces lie in them); a plain
    # one within the tolerance of its wire's lowest and highest points (on its end discs)
    if ground:
        assert (vertices[:, 2].min(), vertices[:, 2].max()) == (0.0, pytest.approx(length, abs=1e-12))
    else:
        assert 0 <= vertices[:, 2].min() - (z0 - d / 2) <= tolerance
        assert 0 <= z0 + pitch * coils + d / 2 - vertices[:, 2].max() <= tolerance
    # every triangle within the tolerance: 28 points a triangle (corners, edges, inside), their
    # distance to the surface bounded above by the nearest surface point found; at 1 um every 7th
    # triangle (7 is prime to the 2 m triangles of a row)
    sample = tri if len(tri) < 20000 else tri[::7]
    assert spring_surface_distance(spring, _probes(sample)).max() <= tolerance
    # the mesh lies within the tolerance of the surface, so its volume differs from the solid's by
    # less than the band of that width round the surface: area (lateral pi d x pi D n, the ends
    # within it) times the tolerance; it is inscribed (chords cut inside the convex wire), so short
    area = math.pi * d * math.pi * mean * coils * 1.1
    exact = exact_volume(spring)
    assert 0 < exact - mesh_volume(tri) < area * tolerance
    assert mesh_volume(tri) == pytest.approx(volume, rel=1e-6)  # single precision


@pytest.mark.parametrize("spring", SPRINGS)
def test_spring_mesh_turns_by_at_most_the_angular_tolerance(spring):
    """Asked an angular tolerance too (the view's 0.5 rad at its 0.45 mm, where the chordal one alone
    would leave a square wire), neighbouring facets of the side turn by at most that much; the
    edges where the side meets a flat face are the solid's own (90 deg down to 0 at a lens's tip)."""
    import trimesh
    d, mean, length, coils, ground = spring
    z0, pitch = spring_helix(spring)
    angle = 0.5
    tri = spring_triangles(d, mean, z0, pitch, coils, 0.45, (0.0, length) if ground else None, angle)
    mesh = trimesh.Trimesh(**trimesh.triangles.to_kwargs(tri))
    corners = mesh.vertices[mesh.faces]
    end = 2 * math.pi * coils
    across_end = -corners[..., 0] * math.sin(end) + corners[..., 1] * math.cos(end)
    flat = (np.all(np.abs(corners[..., 2]) < 1e-12, axis=1) | np.all(np.abs(corners[..., 2] - length) < 1e-12, axis=1)
            if ground else np.zeros(len(corners), bool))
    flat |= np.all(np.abs(corners[..., 1]) < 1e-12, axis=1) | np.all(np.abs(across_end) < 1e-9, axis=1)
    side = ~flat[mesh.face_adjacency].any(axis=1)
    # the grid's steps round the wire (2 pi / m) and along it (dphi) are at most the angle; a facet
    # leans from its corners' normals, so neighbours turn a little more where the helix is steep
    # (measured at most 1.04 x, the tight spring of pitch 1.025 d; 0.91-1.0 x the others): 1.1 x
    assert mesh.face_adjacency_angles[side].max() <= 1.1 * angle
    # and the tolerance alone (no angle asked) takes far fewer columns round a wire of a = 0.57 mm
    assert len(spring_triangles(d, mean, z0, pitch, coils, 0.45, (0.0, length) if ground else None)) < len(tri)


def test_spring_mesh_volume_converges_to_the_closed_form():
    """The volume's shortfall goes as the tolerance (every chord's sag is chosen by it) down to
    1 um, the ground robot spring, against pi^2 d^2 D n / 4 - pi D d^3 / (6 p)."""
    spring = SPRINGS[0]
    d, mean, length, coils, _ = spring
    z0, pitch = spring_helix(spring)
    tolerances = np.array([4e-3, 2e-3, 1e-3])
    short = np.array([exact_volume(spring) - mesh_volume(spring_triangles(d, mean, z0, pitch, coils, t, (0.0, length)))
                      for t in tolerances])
    assert np.all(short > 0)
    # per unit tolerance the same within 30 %: the columns are a whole (even) number, so the
    # circle's share of the tolerance moves from one tolerance to the next (measured 205, 202 and
    # 244 mm^3/mm); a shortfall not going as the tolerance (a face missing: a constant) fails
    per_unit = short / tolerances
    assert per_unit.max() < 1.3 * per_unit.min()


def test_spring_mesh_has_fewer_triangles_than_the_kernel_needed():
    """Counted on the kernel's mesh of the robot joint's spring (geargen.cad.export.kernel_triangles,
    angular 0.5 rad: 8,254 at the view's 0.45 mm, 13,160 at the STL's 0.05 mm)."""
    d, mean, length, coils, _ = SPRINGS[0]
    z0, pitch = spring_helix(SPRINGS[0])
    assert len(spring_triangles(d, mean, z0, pitch, coils, 0.45, (0.0, length))) < 8254 / 4
    assert len(spring_triangles(d, mean, z0, pitch, coils, 0.05, (0.0, length))) < 13160 * 0.6


@pytest.mark.parametrize("args, problem", [((1.0, 2.0, 0.0, 2.0, 3.0, None), "not a spring"),  # index 2
                                           ((1.0, 8.0, 0.0, 1.0, 3.0, None), "not a spring"),  # coils touch
                                           ((1.0, 8.0, 0.0, 1.5, 0.3, (0.0, 0.45)), "end cuts meet"),
                                           ((1.0, 8.0, 0.0, 1.5, 3.0, (0.0, 4.0)), "helix's ends")])
def test_spring_mesher_refuses_what_it_cannot_lay_out(args, problem):
    *spring, slab = args
    with pytest.raises(TessellationError, match=problem):
        spring_triangles(*spring, 0.05, slab)
