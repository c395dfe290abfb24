"""Regenerate ``geargen/report/dxf_frame.txt``, the fixed part of the profile DXFs, from ezdxf.

Run by hand after changing the pinned ezdxf or :data:`geargen.outputs.EXPORT_DATE`:
``PYTHONPATH=$PWD .venv/bin/python tools/dxf_frame.py`` (tests/report/test_dxf.py fails until then).

:func:`geargen.report.dxf.write_profile_dxf` writes the DXF itself (importing and running ezdxf took
half the build's drawings process). What it writes around the outline's entities - the header, the
classes, tables, blocks and objects of ezdxf's new R2010 document with the two layers - is this
frame: the document ezdxf writes (:func:`ezdxf_bytes`) without entities, with markers ``@NAME@``
where a gear's file differs: the unit's header values, the two GUIDs, the entities, and every handle
allocated after the layers (``@handle+K@``: the K-th handle after the gear's entities; ezdxf numbers
the entities from the first free handle and adds two APPIDs and its marker's variable when it
writes). The frame's first line names the first free handle and the model space's handle (the
entities' owner). :func:`ezdxf_bytes` is also the reference tests/report/test_dxf.py compares the
writer's bytes with.
"""

from __future__ import annotations

import io
import math
import sys
import uuid
from collections import OrderedDict
from datetime import datetime
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: group codes whose value is a handle (DXF reference, "Group code value types")
HANDLE_CODES = {5, 105, *range(320, 370), *range(390, 400), 480, 481, 1005}
#: header variables whose value the frame leaves to the writer
HEADER_MARKERS = ("$INSUNITS", "$MEASUREMENT", "$FINGERPRINTGUID", "$VERSIONGUID")


def new_document(unit: str):
    """ezdxf's new R2010 document as the profile DXF sets it up (units, two layers), no entity yet."""
    import ezdxf

    from geargen.report.dxf import BORE_LAYER, INSUNITS, OUTLINE_LAYER

    doc = ezdxf.new("R2010", units=INSUNITS[unit])
    doc.header["$MEASUREMENT"] = 1 if unit == "mm" else 0
    doc.header["$LUNITS"] = 2  # decimal
    doc.header["$LUPREC"] = 8
    for name, colour in ((OUTLINE_LAYER, 7), (BORE_LAYER, 1)):
        doc.layers.add(name, color=colour)
    return doc


def ezdxf_bytes(profile, fingerprint: uuid.UUID, version: uuid.UUID) -> bytes:
    """The profile DXF of ``profile`` as ezdxf writes it: the entities of
    :func:`geargen.report.dxf.outline_entities` and :func:`~geargen.report.dxf.bore_entities` added with
    ezdxf's own calls, written by :func:`write_reproducibly` with the GUIDs given."""
    from geargen.report.dxf import BORE_LAYER, OUTLINE_LAYER, bore_entities, outline_entities
    from geargen.units import from_mm

    spec = profile.spec
    s = float(from_mm(1.0, spec.length_unit))
    doc = new_document(spec.length_unit)
    msp = doc.modelspace()
    for e in outline_entities(profile):
        if e[0] == "arc":
            msp.add_arc((0.0, 0.0), e[1] * s, math.degrees(e[2]), math.degrees(e[3]), dxfattribs={"layer": OUTLINE_LAYER})
        else:
            spline = msp.add_spline(dxfattribs={"layer": OUTLINE_LAYER, "degree": 3, "flags": 8})
            spline.control_points = [(x * s, y * s, 0.0) for x, y in e[1]]
            spline.knots = [float(t) * s for t in e[2]]
    for e in bore_entities(spec.hub):
        if e[0] == "circle":
            msp.add_circle((0.0, 0.0), e[1] * s, dxfattribs={"layer": BORE_LAYER})
        elif e[0] == "arc":
            msp.add_arc((0.0, 0.0), e[1] * s, math.degrees(e[2]), math.degrees(e[3]), dxfattribs={"layer": BORE_LAYER})
        else:
            (x0, y0), (x1, y1) = e[1], e[2]
            msp.add_line((x0 * s, y0 * s), (x1 * s, y1 * s), dxfattribs={"layer": BORE_LAYER})
    return write_reproducibly(doc, fingerprint, version)


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

    from geargen.outputs import EXPORT_DATE

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


def frame(unit: str = "mm") -> str:
    """The frame file's text (module docstring), from the document of ``unit`` without entities."""
    doc = new_document(unit)
    first = int(str(doc.entitydb.handles), 16)  # the first free handle: the first entity's
    owner = doc.modelspace().block_record_handle
    lines = ezdxf_bytes_of(doc).decode("utf-8").split("\n")
    assert lines[-1] == "" and len(lines) % 2 == 1, "an ASCII DXF: code and value lines, newline-ended"
    out = []
    for i in range(0, len(lines) - 1, 2):
        code, value = lines[i], lines[i + 1]
        if int(code) in HANDLE_CODES and int(value, 16) >= first:
            value = f"@handle+{int(value, 16) - first}@"
        elif out and out[-1][1] in HEADER_MARKERS and out[-1][0].strip() == "9":
            value = f"@{out[-1][1][1:]}@"
        out.append((code, value))
        if value == "ENTITIES" and code.strip() == "2":
            out.append(("@ENTITIES@", None))  # the entities' lines go here, before the section's end
    text = "".join(code if value is None else f"{code}\n{value}\n" for code, value in out)
    return f"first free handle {first:X}, model space {owner}\n" + text


def ezdxf_bytes_of(doc) -> bytes:
    """``doc`` written by :func:`write_reproducibly` with GUIDs that cannot occur in a frame's text."""
    return write_reproducibly(doc, uuid.UUID(int=0), uuid.UUID(int=1))


def main() -> None:
    mm, inch = frame("mm"), frame("in")
    if mm != inch:
        sys.exit("the mm and inch documents differ beyond the marked header values: mark what differs")
    path = ROOT / "geargen" / "report" / "dxf_frame.txt"
    path.write_text(mm)
    print(f"wrote {path} ({len(mm)} characters)")


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    main()
