"""DXF of a gear's exact transverse outline, for wire EDM (ezdxf).

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

Two writes of one gear give the same bytes (:func:`write_reproducibly`): where ezdxf would stamp
the clock and draw random GUIDs, the header's dates are :data:`geargen.outputs.EXPORT_DATE`,
``$FINGERPRINTGUID`` (the drawing's identity, kept by every revision) is a UUID 5 of the gear's
name and ``$VERSIONGUID`` (this revision's) a UUID 5 of the geometry drawn, so the file changes
exactly when the outline does (not when another value of the design file does); the CLASSES
section, which ezdxf fills from a set, is sorted.
"""

from __future__ import annotations

import hashlib
import io
import math
import uuid
from collections import OrderedDict
from dataclasses import dataclass
from datetime import datetime
from pathlib import Path

import numpy as np

from geargen.outputs import EXPORT_DATE, atomic_path
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


def write_profile_dxf(profile, path, tolerance: float = SPLINE_TOLERANCE_MM) -> DxfRecord:
    """Write the DXF of ``profile`` (:class:`geargen.profile.tooth.ToothProfile`) to ``path``
    (atomically) in its gear's length unit; see the module docstring."""
    import ezdxf

    spec = profile.spec
    unit = spec.length_unit
    s = float(from_mm(1.0, unit))  # mm -> the drawing's unit
    doc = ezdxf.new("R2010", units=INSUNITS[unit])
    doc.header["$MEASUREMENT"] = 1 if unit == "mm" else 0
    doc.header["$LUNITS"] = 2  # decimal
    doc.header["$LUPREC"] = 8
    for name, colour in ((OUTLINE_LAYER, 7), (BORE_LAYER, 1)):
        doc.layers.add(name, color=colour)
    msp = doc.modelspace()
    counts: dict[str, int] = {}
    geometry = hashlib.sha256(unit.encode())  # what is drawn, for the revision's GUID

    def drawn(kind, layer, *numbers):
        counts[kind] = counts.get(kind, 0) + 1
        geometry.update(f"{kind} {layer}".encode())
        geometry.update(np.asarray(numbers, dtype=float).tobytes())

    def arc(r, a0, a1, layer):
        msp.add_arc((0.0, 0.0), r * s, math.degrees(a0), math.degrees(a1), dxfattribs={"layer": layer})
        drawn("ARC", layer, r * s, math.degrees(a0), math.degrees(a1))

    for e in outline_entities(profile, tolerance):
        if e[0] == "arc":
            arc(e[1], e[2], e[3], OUTLINE_LAYER)
        else:
            poles, knots = e[1], e[2]
            spline = msp.add_spline(dxfattribs={"layer": OUTLINE_LAYER, "degree": 3, "flags": 8})  # 8: planar
            spline.control_points = [(x * s, y * s, 0.0) for x, y in poles]
            spline.knots = [float(t) * s for t in knots]  # the curve's parameter is its length scale
            drawn("SPLINE", OUTLINE_LAYER, *(np.asarray(poles, dtype=float) * s).ravel(), *(np.asarray(knots) * s))
    for e in bore_entities(spec.hub):
        if e[0] == "circle":
            msp.add_circle((0.0, 0.0), e[1] * s, dxfattribs={"layer": BORE_LAYER})
            drawn("CIRCLE", BORE_LAYER, e[1] * s)
        elif e[0] == "arc":
            arc(e[1], e[2], e[3], BORE_LAYER)
        else:
            (x0, y0), (x1, y1) = e[1], e[2]
            msp.add_line((x0 * s, y0 * s), (x1 * s, y1 * s), dxfattribs={"layer": BORE_LAYER})
            drawn("LINE", BORE_LAYER, x0 * s, y0 * s, x1 * s, y1 * s)
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_bytes(write_reproducibly(doc, uuid.uuid5(GUID_NAMESPACE, f"gear {spec.name}"),
                                           uuid.uuid5(GUID_NAMESPACE, geometry.hexdigest())))
    return DxfRecord(path, unit, counts, path.stat().st_size)


def write_reproducibly(doc, fingerprint: uuid.UUID, version: uuid.UUID) -> bytes:
    """The bytes of ezdxf's ``doc.saveas`` (ASCII DXF) with nothing of the moment in them: the
    creation and update dates :data:`~geargen.outputs.EXPORT_DATE` (also in ezdxf's
    written-by marker), ``$FINGERPRINTGUID`` ``fingerprint`` and ``$VERSIONGUID`` ``version``, the
    CLASSES in order of name (ezdxf adds one per entity type in use from a set, whose order
    follows the interpreter's hash seed). ezdxf's ``Drawing.write`` stamps the clock as it writes, so
    its steps are taken here with those values set between them."""
    import ezdxf
    from ezdxf.document import CREATED_BY_EZDXF, WRITTEN_BY_EZDXF
    from ezdxf.lldxf.tagwriter import TagWriter
    from ezdxf.tools.juliandate import juliandate

    doc.commit_pending_changes()
    doc.update_all()  # the classes, header and metadata, with the clock's values, replaced below
    doc.classes.classes = OrderedDict(sorted(doc.classes.classes.items()))
    date = juliandate(datetime.fromisoformat(EXPORT_DATE))
    for name in ("$TDCREATE", "$TDUCREATE", "$TDUPDATE", "$TDUUPDATE"):
        doc.header[name] = date
    doc.header["$FINGERPRINTGUID"] = "{%s}" % str(fingerprint).upper()
    doc.header["$VERSIONGUID"] = "{%s}" % str(version).upper()
    marker = doc.ezdxf_metadata()
    for key in (CREATED_BY_EZDXF, WRITTEN_BY_EZDXF):
        marker[key] = f"{ezdxf.__version__} @ {EXPORT_DATE}+00:00"
    text = io.StringIO()
    doc.export_sections(TagWriter(text, write_handles=True, dxfversion=doc.dxfversion))
    return doc.encode(text.getvalue())


__all__ = ["SPLINE_TOLERANCE_MM", "INSUNITS", "OUTLINE_LAYER", "BORE_LAYER", "GUID_NAMESPACE", "DxfRecord",
           "outline_entities", "bore_entities", "write_profile_dxf", "write_reproducibly"]
