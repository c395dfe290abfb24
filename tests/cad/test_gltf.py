"""The GLB writer (geargen.cad.gltf) on triangles with known answers: no solid is built (fast)."""

import io
import json
import struct

import numpy as np
import pytest

from geargen.cad.gltf import glb, indexed, srgb_to_linear


def _box(lo, hi) -> np.ndarray:
    """The 12 triangles (12, 3, 3) of an axis-aligned box, outward normals."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    c = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return np.array([c[list(tri)] for q0, q1, q2, q3 in quads for tri in ((q0, q1, q2), (q0, q2, q3))])


def _json_chunk(data: bytes) -> dict:
    magic, version, length = struct.unpack_from("<III", data)
    assert (magic, version, length) == (0x46546C67, 2, len(data))
    size, kind = struct.unpack_from("<II", data, 12)
    assert kind == 0x4E4F534A and size % 4 == 0
    return json.loads(data[20:20 + size])


def test_a_box_keeps_its_eight_corners_and_twelve_triangles():
    vertices, indices = indexed(_box((0, 0, 0), (1, 2, 3)))
    assert vertices.shape == (8, 3) and indices.shape == (36,)
    np.testing.assert_array_equal(vertices[indices].reshape(-1, 3, 3), _box((0, 0, 0), (1, 2, 3)).astype(np.float32))


def test_indexed_orders_and_merges_vertices_as_numpy_unique_of_their_bytes():
    """indexed sorts the vertices by two integer keys instead of np.unique of each vertex's 12 bytes:
    on 3000 random triangles drawn from 500 float32 vertices (negative numbers, -0.0 beside 0.0,
    the same x with other y, z) it gives the same vertices in the same order and the same indices,
    exactly (the GLB's bytes must not change)."""
    rng = np.random.default_rng(28)
    pool = rng.normal(0.0, 50.0, (500, 3)).astype(np.float32)
    pool[:40, 0] = pool[40:80, 0]  # rows equal in x only
    pool[80:90] = 0.0
    pool[85:90, 1] = -0.0  # bytes differ from 0.0: two vertices, as the STL keeps them
    triangles = pool[rng.integers(0, 500, (3000, 3))]
    flat = triangles.reshape(-1, 3)
    rows = flat.view(np.dtype((np.void, 12))).ravel()
    _, first, inverse = np.unique(rows, return_index=True, return_inverse=True)
    vertices, indices = indexed(triangles)
    assert len(vertices) > 400  # most of the pool is used, each vertex many times
    np.testing.assert_array_equal(vertices.view(np.uint32), flat[first].view(np.uint32))
    np.testing.assert_array_equal(indices, inverse.ravel())
    assert indices.dtype == np.uint32


def test_two_parts_in_two_groups_read_back_by_trimesh():
    trimesh = pytest.importorskip("trimesh")
    parts = [("plate", "frame", "carriage", (0.78, 0.80, 0.84, 1.0), _box((-10, -20, 0), (10, 20, 5))),
             ("cover", "frame", "housing", (0.62, 0.64, 0.60, 0.35), _box((0, 0, 5), (4, 4, 9))),
             ("gear", "output", "gear_output", (0.55, 0.60, 0.70, 1.0), _box((30, -1, 0), (32, 1, 2)))]
    data = glb("demo", parts)
    doc = _json_chunk(data)
    names = [n["name"] for n in doc["nodes"]]
    assert names == ["demo", "frame_assembly", "plate", "cover", "output_assembly", "gear"]
    assert doc["nodes"][0]["children"] == [1, 4] and doc["nodes"][1]["children"] == [2, 3]
    assert doc["nodes"][3]["extras"] == {"part": "cover", "group": "frame", "kind": "housing"}
    # glTF colours are linear: sRGB 0.5 is 0.214 (IEC 61966-2-1), and translucent parts blend
    assert srgb_to_linear([0.5])[0] == pytest.approx(0.21404, abs=1e-5)
    cover = doc["materials"][doc["meshes"][doc["nodes"][3]["mesh"]]["primitives"][0]["material"]]
    assert cover["alphaMode"] == "BLEND" and cover["pbrMetallicRoughness"]["baseColorFactor"][3] == 0.35
    scene = trimesh.load(io.BytesIO(data), file_type="glb", force="scene", process=False)
    assert sorted(scene.graph.nodes_geometry) == ["cover", "gear", "plate"]
    plate = scene.geometry[scene.graph["plate"][1]]
    np.testing.assert_allclose(plate.bounds, [[-10, -20, 0], [10, 20, 5]])
    assert plate.volume == pytest.approx(20 * 40 * 5)
    # mm, z up -> m, y up: (x, y, z) -> (x, z, -y) / 1000
    np.testing.assert_allclose(scene.bounds, [[-0.010, 0.0, -0.020], [0.032, 0.009, 0.020]])
