"""The assembly as one binary glTF (GLB) for the browser design review: part names, groups, colours.

The meshes are the exported STL files' triangles when they exist (the same shapes and
placements as the STEP/STL exports, and no second tessellation); a part without one is
tessellated here at a view's tolerance. Tree: the assembly's root node (which turns geargen's
mm, z up into glTF's metres, y up), one node per group (``<group>_assembly``, as in the assembly
STEP), one node per part (named as the part, ``extras`` holding its name, group and kind) with
one indexed triangle primitive. No normals are
written: a viewer shades the facets flat, which keeps the file small and the tooth flanks crisp.
Colours are the assembly STEP's (:data:`geargen.cad.assembly.COLOURS`, sRGB), written as glTF's
linear base colour; translucent parts (reference bodies, housings) are alpha-blended.
"""

from __future__ import annotations

import json
import struct
from pathlib import Path
from typing import Iterable

import numpy as np

_GLB_MAGIC = 0x46546C67  # "glTF"
_JSON_CHUNK = 0x4E4F534A
_BIN_CHUNK = 0x004E4942
_FLOAT, _UNSIGNED_INT = 5126, 5125
_ARRAY_BUFFER, _ELEMENT_ARRAY_BUFFER = 34962, 34963

#: geargen's assembly frame (mm, z up) into glTF's (metres, y up): (x, y, z) mm -> (x, z, -y) / 1000
MM_Z_UP_TO_GLTF = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, -1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]) \
    @ np.diag([1e-3, 1e-3, 1e-3, 1.0])


def srgb_to_linear(c: np.ndarray) -> np.ndarray:
    """sRGB components ``(k,)`` in [0, 1] to linear light (glTF's ``baseColorFactor``)."""
    c = np.asarray(c, dtype=float)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def indexed(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A triangle soup ``(n, 3, 3)`` as shared vertices ``(v, 3) float32`` and indices ``(n * 3,) uint32``
    (vertices equal in float32 merged; the STL's own precision, so nothing moves)."""
    flat = np.ascontiguousarray(np.asarray(triangles, dtype=np.float32).reshape(-1, 3))
    if not len(flat):
        return np.zeros((0, 3), np.float32), np.zeros(0, np.uint32)
    # each vertex's 12 bytes as two big-endian integers: sorted, they are in the bytes' order (the order
    # np.unique of the rows as raw bytes gives, at ~60 % of its time); the first of equal rows is kept
    keys = flat.view(np.dtype([("high", ">u8"), ("low", ">u4")])).ravel()
    order = np.lexsort((keys["low"], keys["high"]))
    high, low = keys["high"][order], keys["low"][order]
    new = np.empty(len(order), bool)
    new[0] = True
    new[1:] = (high[1:] != high[:-1]) | (low[1:] != low[:-1])
    inverse = np.empty(len(order), np.uint32)
    inverse[order] = np.cumsum(new) - 1
    return flat[order[new]], inverse


class _Buffer:
    """The GLB's binary chunk, one buffer view per accessor, each 4-byte aligned."""

    def __init__(self):
        self.data = bytearray()
        self.views: list[dict] = []
        self.accessors: list[dict] = []

    def add(self, array: np.ndarray, component: int, kind: str, target: int, bounds: bool = False) -> int:
        raw = array.tobytes()
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(raw), "target": target})
        self.data += raw + b"\0" * (-len(raw) % 4)
        acc = {"bufferView": len(self.views) - 1, "componentType": component, "count": int(len(array)), "type": kind}
        if bounds:  # required for POSITION
            acc["min"] = array.min(axis=0).astype(float).tolist()
            acc["max"] = array.max(axis=0).astype(float).tolist()
        self.accessors.append(acc)
        return len(self.accessors) - 1


def glb(name: str, parts: Iterable[tuple[str, str, str, tuple[float, float, float, float], np.ndarray]]) -> bytes:
    """The GLB of ``parts``: ``(name, group, kind, (r, g, b, alpha) sRGB, triangles (n, 3, 3) mm in the
    assembly frame)``, grouped in the order the groups first appear."""
    buf = _Buffer()
    nodes: list[dict] = [{"name": name, "matrix": MM_Z_UP_TO_GLTF.T.ravel().tolist(), "children": []}]
    groups: dict[str, int] = {}
    materials: list[dict] = []
    material_of: dict[tuple, int] = {}
    meshes: list[dict] = []
    for part, group, kind, colour, triangles in parts:
        if group not in groups:
            groups[group] = len(nodes)
            nodes[0]["children"].append(len(nodes))
            nodes.append({"name": f"{group}_assembly", "children": [], "extras": {"group": group}})
        node = {"name": part, "extras": {"part": part, "group": group, "kind": kind}}
        vertices, indices = indexed(triangles)
        if len(indices):
            key = (kind, tuple(colour))
            if key not in material_of:
                r, g, b, a = colour
                mat = {"name": kind, "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorFactor": [*srgb_to_linear([r, g, b]).tolist(), float(a)],
                                                "metallicFactor": 0.2, "roughnessFactor": 0.55}}
                if a < 1.0:
                    mat["alphaMode"] = "BLEND"
                material_of[key] = len(materials)
                materials.append(mat)
            position = buf.add(vertices, _FLOAT, "VEC3", _ARRAY_BUFFER, bounds=True)
            index = buf.add(indices, _UNSIGNED_INT, "SCALAR", _ELEMENT_ARRAY_BUFFER)
            node["mesh"] = len(meshes)
            meshes.append({"name": part, "primitives": [{"attributes": {"POSITION": position}, "indices": index,
                                                         "material": material_of[key]}]})
        nodes[groups[group]]["children"].append(len(nodes))
        nodes.append(node)
    doc = {"asset": {"version": "2.0", "generator": "geargen"}, "scene": 0, "scenes": [{"name": name, "nodes": [0]}],
           "nodes": nodes, "meshes": meshes, "materials": materials, "accessors": buf.accessors,
           "bufferViews": buf.views, "buffers": [{"byteLength": len(buf.data)}]}
    if not meshes:  # glTF forbids empty arrays
        for key in ("meshes", "materials", "accessors", "bufferViews", "buffers"):
            del doc[key]
    text = json.dumps(doc, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)
    chunks = struct.pack("<II", len(text), _JSON_CHUNK) + text
    if meshes:
        chunks += struct.pack("<II", len(buf.data), _BIN_CHUNK) + bytes(buf.data)
    return struct.pack("<III", _GLB_MAGIC, 2, 12 + len(chunks)) + chunks


def assembly_glb(name: str, parts: Iterable, folder: Path | None = None, detail: float = 400.0) -> bytes:
    """The GLB of placed parts (:class:`geargen.cad.assembly.PlacedPart`): each part's triangles from
    ``folder/<part>.stl`` (the export) when it exists, else tessellated here within the model's
    largest size over ``detail`` (:func:`geargen.cad.render.part_triangles`, the rendered view's)."""
    from geargen.cad.export import exported_triangles
    parts = list(parts)
    meshes = exported_triangles(parts, folder)
    todo = [p for p in parts if p.name not in meshes]
    if todo:
        from geargen.cad.export import Tessellations
        from geargen.cad.parts import bounding_box
        from geargen.cad.render import part_triangles
        boxes = np.array([np.concatenate(bounding_box(p.world(), optimal=False)) for p in todo])
        extent = float(np.max(boxes[:, 3:].max(axis=0) - boxes[:, :3].min(axis=0)))
        made = Tessellations()  # parts sharing a solid are meshed once
        meshes.update({p.name: part_triangles(p, extent / detail, meshes=made) for p in todo})
    return glb(name, ((p.name, p.group, p.kind, p.colour, meshes[p.name]) for p in parts))


__all__ = ["glb", "assembly_glb", "indexed", "srgb_to_linear", "MM_Z_UP_TO_GLTF"]
