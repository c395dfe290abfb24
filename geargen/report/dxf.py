"""DXF of a gear's exact transverse outline, for wire EDM (R2010, the file ezdxf 1.4.5 writes).

What the file holds, in the z = 0 transverse section (tooth 0 centred on +x, as
:mod:`geargen.profile.tooth`), in the gear's length unit (``$INSUNITS`` 4 = mm, 1 = inch):

- layer ``GEAR_OUTLINE``: the closed outline of the whole gear, counter-clockwise, tooth by
  tooth: tip and root circles as ARCs (exact), each involute flank and each trochoidal fillet as
  one cubic SPLINE - the C1 Hermite B-spline of :func:`geargen.profile.hermite.segment_spline`
  interpolating exact points and tangents, within :data:`SPLINE_TOLERANCE_MM` of the exact curve
  (cubic, not the solids' degree-7 fit of :mod:`geargen.profile.bspline_fit`: wire-EDM and 2-D CAM
  readers take degree-3 SPLINEs, many nothing higher);
- layer ``BORE``: the bore as a CIRCLE, or with a keyway (centred on +x, as the solids have it)
  as an ARC (counter-clockwise, as every DXF arc) and the keyway's three LINEs.

Consecutive entities share their end points (each spline starts and ends on the exact joint the
arcs end on), so the chain is closed to rounding (~1e-12 of the radius). Tooth 0's splines are
fitted once and turned for the other teeth.

The entities are written here, into a fixed frame (:data:`FRAME_PATH`: header, classes, tables,
blocks and objects of ezdxf's new R2010 document with the two layers, written by ezdxf with
tools/dxf_frame.py): byte for byte what ezdxf writes (tests/report/test_dxf.py compares), without
importing and running ezdxf (half the build's drawings process's time). Two writes of one gear give
the same bytes: where ezdxf would stamp the clock and draw random GUIDs, the header's dates are
:data:`geargen.outputs.EXPORT_DATE`, ``$FINGERPRINTGUID`` (the drawing's identity, kept by every
revision) is a UUID 5 of the gear's name and ``$VERSIONGUID`` (this revision's) a UUID 5 of the
geometry drawn, so the file changes exactly when the outline does (not when another value of the
design file does); the CLASSES section, which ezdxf fills from a set, is sorted.
"""

from __future__ import annotations

import hashlib
import math
import re
import uuid
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from geargen.outputs import atomic_path
from geargen.profile.hermite import segment_spline
from geargen.units import from_mm

#: largest distance (mm) between a fitted SPLINE and the exact flank or fillet (0.01 um)
SPLINE_TOLERANCE_MM = 1e-5
#: $INSUNITS codes of the DXF reference
INSUNITS = {"mm": 4, "in": 1}
OUTLINE_LAYER = "GEAR_OUTLINE"
BORE_LAYER = "BORE"
#: the name space of the DXF's UUID 5 GUIDs
GUID_NAMESPACE = uuid.uuid5(uuid.NAMESPACE_URL, "geargen:dxf")


@dataclass(frozen=True)
class DxfRecord:
    """What :func:`write_profile_dxf` wrote: path, unit, entity counts by DXF type, bytes."""

    path: Path
    length_unit: str
    entities: dict[str, int]
    bytes: int


def _rotate(xy: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return xy @ np.array([[c, s], [-s, c]])


def outline_entities(profile, tolerance: float = SPLINE_TOLERANCE_MM) -> list[tuple]:
    """The whole outline (mm) as ``("arc", radius, start_rad, end_rad)`` (counter-clockwise) and
    ``("spline", poles (n, 2), knots (n + 4,))`` entries, in outline order."""
    pitch = profile.pitch_segments()
    tooth0 = []
    for seg in pitch:
        if seg.kind in ("tip_arc", "root_arc"):
            tooth0.append(("arc", seg.curve.radius, seg.t0 + seg.rotation, seg.t1 + seg.rotation))
        else:
            tooth0.append(("spline",) + segment_spline(seg, tolerance))
    out = []
    for k in range(profile.teeth):
        a = k * profile.pitch_angle
        for e in tooth0:
            if e[0] == "arc":
                out.append(("arc", e[1], e[2] + a, e[3] + a))
            else:
                out.append(("spline", _rotate(e[1], a) if k else e[1], e[2]))
    return out


def bore_entities(hub) -> list[tuple]:
    """The bore (mm): ``[("circle", r)]``, or with a keyway ``("arc", r, a0, a1)`` and
    ``("line", p, q)`` entries; ``[]`` without a bore."""
    if hub.bore_diameter <= 0:
        return []
    rb = hub.bore_diameter / 2
    if hub.keyway_width <= 0:
        return [("circle", rb)]
    w2 = hub.keyway_width / 2
    xk = math.sqrt(rb * rb - w2 * w2)
    xf = rb + hub.keyway_depth
    a = math.asin(w2 / rb)
    pts = [(xk, w2), (xf, w2), (xf, -w2), (xk, -w2)]
    return [("arc", rb, a, 2 * math.pi - a)] + [("line", p, q) for p, q in zip(pts[:-1], pts[1:])]


#: the fixed part of every profile DXF: ezdxf's R2010 document with the two layers, as ezdxf 1.4.5 writes
#: it, with ``@NAME@`` markers where a gear's file differs (tools/dxf_frame.py writes it from ezdxf)
FRAME_PATH = Path(__file__).with_name("dxf_frame.txt")
_MARKER = re.compile(r"@([A-Za-z][A-Za-z0-9_+]*)@")


@dataclass(frozen=True)
class _Frame:
    first_handle: int  # the first entity's handle
    owner: str  # the model space's block record: the entities' owner
    pieces: tuple[str, ...]  # literal text and marker names alternately (re.split)


@lru_cache(maxsize=None)
def _frame() -> _Frame:
    first_line, text = FRAME_PATH.read_text(encoding="utf-8").split("\n", 1)
    words = first_line.split()  # "first free handle 31, model space 17"
    return _Frame(int(words[3].rstrip(","), 16), words[6], tuple(_MARKER.split(text)))


def write_profile_dxf(profile, path, tolerance: float = SPLINE_TOLERANCE_MM) -> DxfRecord:
    """Write the DXF of ``profile`` (:class:`geargen.profile.tooth.ToothProfile`) to ``path``
    (atomically) in its gear's length unit; see the module docstring."""
    spec = profile.spec
    unit = spec.length_unit
    s = float(from_mm(1.0, unit))  # mm -> the drawing's unit
    frame = _frame()
    entities: list[str] = []
    counts: dict[str, int] = {}
    geometry = hashlib.sha256(unit.encode())  # what is drawn, for the revision's GUID

    def drawn(kind, layer, numbers, body):
        handle = f"{frame.first_handle + len(entities):X}"
        entities.append(f"  0\n{kind}\n  5\n{handle}\n330\n{frame.owner}\n100\nAcDbEntity\n  8\n{layer}\n{body}")
        counts[kind] = counts.get(kind, 0) + 1
        geometry.update(f"{kind} {layer}".encode())
        geometry.update(np.asarray(numbers, dtype=float).tobytes())  # the numbers drawn, as doubles

    def arc(r, a0, a1, layer):
        r, d0, d1 = float(r * s), math.degrees(a0), math.degrees(a1)
        drawn("ARC", layer, (r, d0, d1), f"100\nAcDbCircle\n{_CENTRE} 40\n{r!r}\n100\nAcDbArc\n 50\n{d0!r}\n 51\n{d1!r}\n")

    knots_text: dict[int, tuple[str, np.ndarray]] = {}  # every tooth's splines share tooth 0's knots
    for e in outline_entities(profile, tolerance):
        if e[0] == "arc":
            arc(e[1], e[2], e[3], OUTLINE_LAYER)
        else:
            poles = np.asarray(e[1], dtype=float) * s
            if id(e[2]) not in knots_text:
                knots = [float(t) * s for t in e[2]]  # the curve's parameter is its length scale
                knots_text[id(e[2])] = ((f"100\nAcDbSpline\n 70\n8\n 71\n3\n 72\n{len(knots)}\n 73\n{len(poles)}\n"
                                         " 74\n0\n") + (" 40\n%r\n" * len(knots)) % tuple(knots),  # 70: 8 planar
                                        np.asarray(e[2]) * s)
            head, knots = knots_text[id(e[2])]
            body = head + (" 10\n%r\n 20\n%r\n 30\n0.0\n" * len(poles)) % tuple(poles.ravel().tolist())
            drawn("SPLINE", OUTLINE_LAYER, np.concatenate([poles.ravel(), knots]), body)
    for e in bore_entities(spec.hub):
        if e[0] == "circle":
            r = float(e[1] * s)
            drawn("CIRCLE", BORE_LAYER, (r,), f"100\nAcDbCircle\n{_CENTRE} 40\n{r!r}\n")
        elif e[0] == "arc":
            arc(e[1], e[2], e[3], BORE_LAYER)
        else:
            (x0, y0), (x1, y1) = e[1], e[2]
            x0, y0, x1, y1 = float(x0 * s), float(y0 * s), float(x1 * s), float(y1 * s)
            drawn("LINE", BORE_LAYER, (x0, y0, x1, y1),
                  f"100\nAcDbLine\n 10\n{x0!r}\n 20\n{y0!r}\n 30\n0.0\n 11\n{x1!r}\n 21\n{y1!r}\n 31\n0.0\n")
    after = frame.first_handle + len(entities)  # ezdxf's handles allocated at writing follow the entities
    values = {"INSUNITS": str(INSUNITS[unit]), "MEASUREMENT": "1" if unit == "mm" else "0",
              "FINGERPRINTGUID": _guid(uuid.uuid5(GUID_NAMESPACE, f"gear {spec.name}")),
              "VERSIONGUID": _guid(uuid.uuid5(GUID_NAMESPACE, geometry.hexdigest())),
              "ENTITIES": "".join(entities)}
    text = "".join(piece if i % 2 == 0 else values[piece] if piece in values else f"{after + int(piece[7:]):X}"
                   for i, piece in enumerate(frame.pieces))  # the rest of the markers: "handle+K"
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_bytes(text.encode("utf-8"))
    return DxfRecord(path, unit, counts, path.stat().st_size)


#: an ARC's or CIRCLE's centre, the origin (group codes 10, 20, 30)
_CENTRE = " 10\n0.0\n 20\n0.0\n 30\n0.0\n"


def _guid(value: uuid.UUID) -> str:
    return "{%s}" % str(value).upper()


__all__ = ["SPLINE_TOLERANCE_MM", "INSUNITS", "OUTLINE_LAYER", "BORE_LAYER", "GUID_NAMESPACE", "DxfRecord",
           "outline_entities", "bore_entities", "write_profile_dxf"]
