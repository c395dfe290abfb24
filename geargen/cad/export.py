"""STEP and STL export (atomic), the manifest next to the files, and re-import helpers.

- STEP: one file, one product per part, named as given; the file's length unit is the design's
  (``"mm"`` or ``"in"``): coordinates are written in that unit and the unit is declared in the
  file (``SI_UNIT(.MILLI.,.METRE.)`` or ``CONVERSION_BASED_UNIT('INCH')``); geargen's internal
  mm are converted by the kernel (``write.step.unit``, with ``xstep.cascade.unit`` = MM).
  Edges are written as 3-D curves without their curves on the faces (``write.surfacecurve.mode``
  0), which readers rebuild.
- STL: binary, coordinates always in mm, tessellated with a chordal tolerance (largest distance
  between a triangle and the exact surface, mm), recorded in ``manifest.json`` in the same
  folder with the triangle count, the mesher used and each file's unit.
- Atomic: each file is written to a temporary name in its folder and moved into place with
  ``os.replace`` (:func:`geargen.outputs.atomic_path`), with the user's umask mode; a failed
  write leaves no partial file (and the old one, if any, untouched).
- Reproducible: two exports of the same parts give the same bytes. The STEP header's time_stamp
  is :data:`geargen.outputs.EXPORT_DATE` (fixed, not the clock), and the presentation entities an
  assembly's colours become (which the kernel lists in the order of its shapes' memory addresses)
  are put in the order of the geometry they colour (:func:`canonical_styles`).
"""

from __future__ import annotations

import itertools
import json
import operator
import re
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable

from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
from OCP.BRep import BRep_Tool
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.IFSelect import IFSelect_RetDone
from OCP.Interface import Interface_Static
from OCP.STEPCAFControl import STEPCAFControl_Writer
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Controller
from OCP.Standard import Standard_Transient
from OCP.TCollection import TCollection_ExtendedString, TCollection_HAsciiString
from OCP.TColStd import TColStd_SequenceOfAsciiString
from OCP.TDataStd import TDataStd_Name
from OCP.TDF import TDF_Label, TDF_LabelSequence
from OCP.TDocStd import TDocStd_Document
from OCP.TopAbs import TopAbs_FACE, TopAbs_REVERSED
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Shape
from OCP.XCAFDoc import XCAFDoc_DocumentTool, XCAFDoc_ShapeTool

from geargen.cad.kernel import quiet_kernel, threads_usable
from geargen.errors import BuildError
from geargen.outputs import EXPORT_DATE, atomic_path  # noqa: F401 - atomic_path: part of this module's interface

#: STEP unit names by design length unit
STEP_UNITS = {"mm": "MM", "in": "INCH"}
MANIFEST = "manifest.json"


def _parts(parts) -> list[tuple[str, TopoDS_Shape]]:
    """Accept a GearSolid, a (name, shape) pair, or an iterable of either."""
    if hasattr(parts, "shape") and hasattr(parts, "name"):
        return [(parts.name, parts.shape)]
    if isinstance(parts, tuple) and len(parts) == 2 and isinstance(parts[0], str):
        return [parts]
    out = []
    for p in parts:
        out.extend(_parts(p))
    return out


@dataclass(frozen=True)
class ExportRecord:
    """One written file: ``path``, its ``format``, ``length_unit``, seconds taken, size in bytes,
    and for STL the tolerances (mm, rad) and triangle count."""

    path: Path
    format: str
    length_unit: str
    seconds: float
    bytes: int
    chordal_tolerance: float | None = None
    angular_tolerance: float | None = None
    triangles: int | None = None
    parts: tuple[str, ...] = ()
    mesher: str | None = None

    def manifest_entry(self) -> dict:
        entry = {"format": self.format, "length_unit": self.length_unit, "bytes": self.bytes}
        if self.parts:
            entry["parts"] = list(self.parts)
        if self.format == "stl":
            entry.update(chordal_tolerance_mm=self.chordal_tolerance, triangles=self.triangles, mesher=self.mesher)
            if self.angular_tolerance is not None:
                entry["angular_tolerance_rad"] = self.angular_tolerance
        return entry


def export_step(parts, path, length_unit: str = "mm") -> ExportRecord:
    """Write ``parts`` (a GearSolid, ``(name, shape)`` or a list of them) to one STEP file.

    Each part becomes a product named as given; ``length_unit`` (``"mm"`` or ``"in"``) is the
    file's declared unit.
    """
    if length_unit not in STEP_UNITS:
        raise ValueError(f"length_unit must be one of {sorted(STEP_UNITS)}")
    items = _parts(parts)
    t0 = time.perf_counter()
    STEPControl_Controller.Init_s()
    quiet_kernel()
    Interface_Static.SetCVal_s("xstep.cascade.unit", "MM")
    Interface_Static.SetCVal_s("write.step.unit", STEP_UNITS[length_unit])
    Interface_Static.SetIVal_s("write.step.nonmanifold", 0)
    # edges as 3-D curves only: the 2-D curves on each face are implied by the geometry and
    # rebuilt by readers; leaving them out halves the file and a third of the writing time
    Interface_Static.SetIVal_s("write.surfacecurve.mode", 0)
    doc = TDocStd_Document(TCollection_ExtendedString("XmlXCAF"))
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    tool.SetAutoNaming_s(False)
    for name, shape in items:
        label = tool.AddShape(shape, False, False)
        TDataStd_Name.Set_s(label, TCollection_ExtendedString(name))
        # a placed shape is added as a reference to its unplaced self: named too, the file's second
        # product is the part's name, not the kernel's "Open CASCADE STEP translator 7.9 <n>.1" (n: the
        # transfers made before in the process), which a CAM station lists as a component
        prototype = TDF_Label()
        if XCAFDoc_ShapeTool.GetReferredShape_s(label, prototype):
            TDataStd_Name.Set_s(prototype, TCollection_ExtendedString(name))
    writer = unchecked(STEPCAFControl_Writer())
    writer.SetNameMode(True)
    if not writer.Transfer(doc, STEPControl_AsIs):
        raise BuildError(f"STEP transfer failed for {path}")
    write_step_file(writer, path)
    size = Path(path).stat().st_size
    return ExportRecord(Path(path), "step", length_unit, time.perf_counter() - t0, size,
                        parts=tuple(n for n, _ in items))


def unchecked(writer: STEPCAFControl_Writer) -> STEPCAFControl_Writer:
    """``writer`` (new, nothing transferred yet) with its session's check of the model marked done.

    The first time the kernel's session builds the graph of its model (which the writer does after
    transferring the shapes, to find what to name and colour) it also checks every entity against the
    standard (``IFSelect_WorkSession::ComputeCheck``, ``Interface_CheckTool::VerifyCheckList``) and
    keeps the result in the model, where nothing that writes the file reads it: up to half the
    transfer's time for a gear (0.157 s down to 0.090 s for the robot joint's output gear). The session
    checks only once: done here on a model of one bare entity (of no STEP type: nothing to check, and
    handed to the kernel in microseconds where a STEP entity takes a millisecond), which is then emptied, so the transfer
    starts, and numbers its entities, from the same empty model as before. The files are the same
    bytes (bench/diff_builds.py)."""
    session = writer.ChangeWriter().WS()
    model = session.Model()
    model.AddEntity(Standard_Transient())
    session.ComputeGraph(True)
    model.ClearEntities()
    return writer


def write_step_file(writer, path) -> Path:
    """Write a STEP writer's transferred document (a ``STEPControl_Writer`` or
    ``STEPCAFControl_Writer``) to ``path`` (atomically, through :func:`geargen.outputs.atomic_path`),
    reproducibly: the header's time_stamp :data:`~geargen.outputs.EXPORT_DATE`, the colours' entities
    in a stable order (:func:`canonical_styles`). The kernel writes into memory and Python writes the
    file, so a full disk, a quota or a read-only file system is the OSError it is (an environment
    problem, exit 3), not the kernel's bare "write failed"."""
    import io
    step_writer = writer.ChangeWriter() if hasattr(writer, "ChangeWriter") else writer
    header = APIHeaderSection_MakeHeader(step_writer.Model())  # edits the model's own FILE_NAME entity
    header.SetTimeStamp(TCollection_HAsciiString(EXPORT_DATE))
    buffer = io.BytesIO()
    if writer.WriteStream(buffer) != IFSelect_RetDone:
        raise BuildError(f"STEP write failed: {path}")
    with atomic_path(Path(path)) as tmp:
        tmp.write_bytes(canonical_styles(buffer.getvalue()))
    return Path(path)


#: the entity that holds one product's colours; the kernel adds these to the file last, each with the
#: styles, colours and renderings it refers to, in the order of a hash of its shapes' memory addresses
_PRESENTATION = b"MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION("
_STRING = re.compile(rb"'(?:[^']|'')*'")  # a STEP string literal ('' is a quote inside it)
_REFERENCE = re.compile(rb"#(\d+)")
_RECORD = re.compile(rb"#(\d+) = ")
#: a physical line's length in the rewritten records (the kernel's lines are at most about 80 long)
_LINE = 80


def _outside_strings(body: bytes):
    """``(is_string, piece)`` for the pieces of a record's text, string literals apart."""
    at = 0
    for m in _STRING.finditer(body):
        yield False, body[at:m.start()]
        yield True, m.group()
        at = m.end()
    yield False, body[at:]


def _wrapped(record: bytes) -> bytes:
    """One record (``#n = ...;``) on lines of at most :data:`_LINE` characters where it can be: broken
    after commas outside strings, continuation lines indented, as the kernel writes them."""
    tokens = []
    for is_string, piece in _outside_strings(record):
        tokens.extend([piece] if is_string else re.split(rb"(?<=,)", piece))
    lines, line = [], b""
    for token in tokens:
        if line and len(line) + len(token) > _LINE:
            lines.append(line)
            line = b"  "
        line += token
    return b"\n".join(lines + [line])


def _at_least(number: int) -> bytes:
    """A pattern matching the decimal digits of every integer >= ``number`` (> 0) written without leading
    zeros, and some with them (written with more digits than ``number``)."""
    digits = b"%d" % number
    longer = [rb"\d{%d,}" % (len(digits) + 1)]
    same_length = [digits[:i] + b"[%c-9]" % (digits[i] + 1) + rb"\d" * (len(digits) - i - 1)
                   for i in range(len(digits)) if digits[i] < ord("9")]
    return b"|".join(longer + same_length + [digits])


def _refers_to(text: bytes, start: int, number: int) -> bool:
    """Whether ``text[start:]`` names an entity numbered ``number`` or more outside its string literals.
    One pass of a pattern that finds only such numbers (in strings too) over the whole text, and the
    exact scan string by string only when it finds one: a STEP file's head holds some hundred
    thousand references, none of them (in a file the kernel writes) to its end."""
    if re.compile(rb"#(?:" + _at_least(number) + rb")(?!\d)").search(text, start) is None:
        return False
    return any(int(n) >= number for s, p in _outside_strings(text[start:]) if not s for n in _REFERENCE.findall(p))


def canonical_styles(step: bytes) -> bytes:
    """``step`` (a STEP file's bytes) with the presentation entities at its end (one
    ``MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION`` per coloured product and what it
    refers to, :data:`_PRESENTATION`) numbered and ordered by the geometry they colour, not by the
    kernel's memory addresses: the representations sorted by the numbers of the entities before
    them that they reach (then by their own content, for two that colour the same geometry), each
    followed by what it refers to, depth first, in the order written. The same entities with the
    same content, renumbered; a file without colours comes back as it is, and so does one in which
    an earlier entity refers into that end (not a file the kernel writes), rather than be
    reordered wrongly."""
    data = step.find(b"\nDATA;\n")
    start = step.find(b"#", data) if data >= 0 else -1
    first = step.find(b"= " + _PRESENTATION, start) if start >= 0 else -1
    end = step.rfind(b"\nENDSEC;")
    if first < 0 or end < first:
        return step
    first = step.rfind(b"\n#", 0, first) + 1
    bodies: dict[int, bytes] = {}  # number -> the record's text after "#n = ", on one line
    for chunk in step[first:end + 1].split(b"\n#"):
        m = _RECORD.match(b"#" + chunk.lstrip(b"#"))
        if m is None:
            return step
        text = m.string[m.end():].strip()
        bodies[int(m.group(1))] = b"".join(p if s else re.sub(rb"\n\s*", b"", p) for s, p in _outside_strings(text))
    tail = min(bodies)
    if sorted(bodies) != list(range(tail, tail + len(bodies))):
        return step
    head = step[:first]
    if _refers_to(head, start, tail):
        return step

    def references(number):
        return [int(n) for s, p in _outside_strings(bodies[number]) if not s for n in _REFERENCE.findall(p)]

    def reached(number, seen):
        """The entities ``number`` reaches in the tail (depth first, itself first) and the earlier ones it names."""
        inside, before = [], []
        stack = [number]
        while stack:
            n = stack.pop()
            if n < tail:
                before.append(n)
            elif n not in seen:
                seen.add(n)
                inside.append(n)
                stack.extend(reversed(references(n)))
        return inside, before

    def renumbered(body, numbers):
        return b"".join(p if s else _REFERENCE.sub(lambda m: b"#%d" % numbers.get(int(m.group(1)), int(m.group(1))), p)
                        for s, p in _outside_strings(body))

    def sort_key(root):
        inside, before = reached(root, set())
        local = {n: i for i, n in enumerate(inside)}  # its own entities by their place, not their number
        return before, [renumbered(bodies[n], local) for n in inside]

    roots = sorted((n for n, body in bodies.items() if body.startswith(_PRESENTATION)), key=sort_key)
    order: list[int] = []
    seen: set[int] = set()
    for n in roots:
        order += reached(n, seen)[0]
    order += [n for n in sorted(bodies) if n not in seen]
    renumber = {old: tail + i for i, old in enumerate(order)}
    records = [_wrapped(b"#%d = " % renumber[n] + renumbered(bodies[n], renumber)) for n in order]
    return head + b"\n".join(records) + step[end:]


def export_stl(solid, path, chordal_tolerance: float = 1e-3, angular_tolerance: float = 0.5,
               transform=None, meshes: "Tessellations | None" = None) -> ExportRecord:
    """Write a binary STL (mm) of ``solid`` within ``chordal_tolerance`` (mm) of its surface.

    A :class:`~geargen.cad.gear_solid.GearSolid` is meshed from its exact geometry
    (:mod:`geargen.profile.tessellate`: every vertex on the exact surface, every triangle within
    the tolerance, watertight; ~20x faster than the kernel at 1 um); any other shape, or a gear
    whose end faces that mesher cannot lay out, by the kernel's mesher with surface deflection
    control, where ``angular_tolerance`` (rad) also bounds the angle between neighbouring facet
    normals. ``transform``: optional ``(4, 4)`` matrix (mm) applied to the triangles, e.g. to
    place a GearSolid built in its own frame into an assembly frame (rigid motions keep the
    tolerance). ``meshes``: the :class:`Tessellations` of a set of parts, so a solid placed more
    than once is meshed once.
    """
    if chordal_tolerance <= 0 or angular_tolerance <= 0:
        raise ValueError("tolerances must be > 0")
    t0 = time.perf_counter()
    triangles, mesher = (meshes or Tessellations()).triangles(solid, chordal_tolerance, angular_tolerance, transform)
    with atomic_path(Path(path)) as tmp:
        written = write_stl(tmp, triangles)
    size = Path(path).stat().st_size
    return ExportRecord(Path(path), "stl", "mm", time.perf_counter() - t0, size,
                        chordal_tolerance=chordal_tolerance,
                        angular_tolerance=angular_tolerance if mesher == "occt" else None,
                        triangles=written, mesher=mesher)


def solid_triangles(solid, chordal_tolerance: float, angular_tolerance: float = 0.5, transform=None,
                    skip_unmeshed: bool = False):
    """Triangles ``(n, 3, 3)`` (mm) of ``solid`` within ``chordal_tolerance`` and the mesher used.

    A :class:`~geargen.cad.gear_solid.GearSolid` (its layers) or a solid offering
    ``exact_triangles(chordal_tolerance, angular_tolerance)`` (the worm's, the wheel's, a bevel gear's, a spring's
    :class:`~geargen.cad.parts.SpringSolid`) is meshed from its exact geometry ("exact");
    any other shape, or one whose exact mesher declines (TessellationError), by the kernel
    ("occt", see :func:`kernel_triangles`). ``transform``: optional ``(4, 4)`` matrix (mm)
    applied to the triangles (rigid motions keep the tolerance).
    """
    triangles, mesher = None, "occt"
    layers = getattr(solid, "layers", None)
    exact = getattr(solid, "exact_triangles", None)  # a family's own exact mesher (the worm's, the wheel's, a bevel gear's), a spring's
    if exact is not None:
        from geargen.profile.tessellate import TessellationError
        try:
            triangles, mesher = exact(chordal_tolerance, angular_tolerance), "exact"
        except TessellationError:
            triangles = None
    elif layers:
        from geargen.profile.tessellate import TessellationError, tessellate_layers
        hub = solid.spec.large.hub if hasattr(solid.spec, "large") else solid.spec.hub
        try:
            triangles = tessellate_layers(layers, hub, chordal_tolerance)
            mesher = "exact"
        except TessellationError:
            triangles = None
    if triangles is None:
        triangles = kernel_triangles(getattr(solid, "shape", solid), chordal_tolerance, angular_tolerance,
                                     skip_unmeshed)
    return placed_triangles(triangles, transform), mesher


def placed_triangles(triangles, transform=None):
    """``triangles`` ``(n, 3, 3)`` moved by the ``(4, 4)`` matrix ``transform`` (mm; None: as they are)."""
    if transform is None:
        return triangles
    import numpy as np
    m = np.asarray(transform, dtype=float)
    return triangles @ m[:3, :3].T + m[:3, 3]


class Tessellations:
    """Each solid's triangles in its own frame (:func:`solid_triangles`), made once per solid and
    tolerance and placed as often as asked: the parts that share one solid (a cluster's two gears
    alike, a stage's planets, bearings alike) are meshed once, for the STL files as for the view."""

    def __init__(self):
        self._made: dict[tuple, tuple] = {}

    def triangles(self, solid, chordal_tolerance: float, angular_tolerance: float = 0.5, transform=None,
                  skip_unmeshed: bool = False):
        """As :func:`solid_triangles`: ``(triangles (n, 3, 3) mm, mesher)``."""
        key = (id(solid), chordal_tolerance, angular_tolerance, skip_unmeshed)
        made = self._made.get(key)
        if made is None:  # the solid is kept with its triangles, so its id stays its own
            made = self._made[key] = (solid, *solid_triangles(solid, chordal_tolerance, angular_tolerance,
                                                              skip_unmeshed=skip_unmeshed))
        _, triangles, mesher = made
        return placed_triangles(triangles, transform), mesher


def kernel_triangles(shape, chordal_tolerance: float, angular_tolerance: float, skip_unmeshed: bool = False):
    """Triangles ``(n, 3, 3)`` (mm, outward normals) of the kernel's mesh of ``shape`` (surface
    deflection controlled). A face the kernel could not mesh is an error for an export; a picture
    may pass ``skip_unmeshed`` and leave it out."""
    import numpy as np
    from OCP.IMeshTools import IMeshTools_Parameters
    params = IMeshTools_Parameters()
    params.Deflection = chordal_tolerance
    params.Angle = angular_tolerance
    params.Relative = False
    params.InParallel = threads_usable()
    BRepMesh_IncrementalMesh(shape, params)
    out = []
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        face = TopoDS.Face_s(exp.Current())
        loc = TopLoc_Location()
        tri = BRep_Tool.Triangulation_s(face, loc)
        if tri is None:
            if skip_unmeshed:
                exp.Next()
                continue
            raise BuildError("a face was not meshed")
        nodes = _triangulation_nodes(tri, loc)
        _collapse_degenerate_edges(face, nodes)
        idx = _triangulation_triangles(tri)
        if face.Orientation() == TopAbs_REVERSED:
            idx = idx[:, ::-1]
        out.append(nodes[idx])
        exp.Next()
    return _without_repeated_vertices(np.concatenate(out)) if out else np.zeros((0, 3, 3))


def _triangulation_nodes(tri, loc):
    """The nodes ``(n, 3)`` (mm) of the kernel's triangulation ``tri`` of a face at location ``loc``:
    one call per node into the kernel and none per coordinate, streamed into the array (a third of
    the time of a list of lists); moved only when the location is not the identity (the same numbers)."""
    import numpy as np
    points = map(tri.Node, range(1, tri.NbNodes() + 1))
    if not loc.IsIdentity():
        points = map(operator.methodcaller("Transformed", loc.Transformation()), points)
    coordinates = itertools.chain.from_iterable(map(operator.methodcaller("Coord"), points))
    return np.fromiter(coordinates, float, 3 * tri.NbNodes()).reshape(-1, 3)


def _triangulation_triangles(tri):
    """The triangles ``(m, 3)`` of ``tri`` as 0-based node indices, in the kernel's order."""
    import numpy as np
    from OCP.Poly import Poly_Triangle
    corners = itertools.chain.from_iterable(map(Poly_Triangle.Get, map(tri.Triangle, range(1, tri.NbTriangles() + 1))))
    return np.fromiter(corners, np.int64, 3 * tri.NbTriangles()).reshape(-1, 3) - 1


def _collapse_degenerate_edges(face, nodes) -> None:
    """Put the mesh nodes of ``face`` that lie on a degenerated edge (a sphere's pole) exactly on its
    vertex. The kernel's mesher evaluates the surface at each node of such an edge, so the pole
    comes out as several points ~1e-16 mm apart, and the triangles between them, of zero area, leave
    edges that no other triangle shares: an STL that is not watertight (issue 31)."""
    import numpy as np
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp
    exp = TopExp_Explorer(face, TopAbs_EDGE)
    while exp.More():
        edge = TopoDS.Edge_s(exp.Current())
        exp.Next()
        if not BRep_Tool.Degenerated_s(edge):
            continue
        vertex = TopExp.FirstVertex_s(edge)
        p = BRep_Tool.Pnt_s(vertex)
        point = np.array([p.X(), p.Y(), p.Z()])
        near = np.linalg.norm(nodes - point, axis=1) <= BRep_Tool.Tolerance_s(vertex)
        nodes[near] = point


def _without_repeated_vertices(triangles):
    """``triangles`` less those with two equal corners (zero area: their two other edges cancel,
    so leaving them out keeps a closed mesh closed and removes the zero-length edge)."""
    t = triangles
    repeated = (t[:, 0] == t[:, 1]).all(1) | (t[:, 1] == t[:, 2]).all(1) | (t[:, 2] == t[:, 0]).all(1)
    return t[~repeated]


def write_stl(path, triangles) -> int:
    """Binary STL of ``triangles`` ``(n, 3, 3)`` (facet normals from the vertex order); returns the
    number written: a triangle two of whose corners are the same point in the file's single
    precision is left out (see :func:`_without_repeated_vertices`)."""
    import numpy as np
    tri = _without_repeated_vertices(np.asarray(triangles, dtype=np.float32)).astype(float)
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = normals / np.where(length > 0, length, 1.0)
    rec = np.zeros(len(tri), dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    rec["n"] = normals
    rec["v"] = tri
    header = b"geargen binary STL, units mm".ljust(80, b" ")
    with open(path, "wb") as fh:
        fh.write(header)
        fh.write(np.uint32(len(tri)).tobytes())
        fh.write(rec.tobytes())
    return len(tri)


def write_json(path, data) -> None:
    """Write ``data`` as indented JSON, atomically."""
    with atomic_path(Path(path)) as tmp:
        tmp.write_text(json.dumps(data, indent=2, sort_keys=False) + "\n")


def update_manifest(folder, records: Iterable[ExportRecord], extra: dict | None = None) -> Path:
    """Add ``records`` to ``folder/manifest.json`` (created if missing; entries by file name)."""
    folder = Path(folder)
    path = folder / MANIFEST
    data = {}
    if path.exists():
        try:
            data = json.loads(path.read_text())
        except json.JSONDecodeError:
            data = {}
    from geargen import __version__
    data["generator"] = f"geargen {__version__}"
    files = data.setdefault("files", {})
    for r in records:
        files[Path(r.path).name] = r.manifest_entry()
    if extra:
        data.update(extra)
    write_json(path, data)
    return path


# ---------------------------------------------------------------- re-import (tests, checks)


@dataclass
class StepContents:
    """A re-imported STEP file: the shape (in mm), the declared length unit names, product names."""

    shape: TopoDS_Shape
    units: list[str]
    names: list[str]


def read_step(path) -> StepContents:
    """Read a STEP file back: shape converted to mm (one shape, or a compound of the top-level
    parts), the file's declared length units and the top-level product names."""
    from OCP.BRep import BRep_Builder
    from OCP.STEPCAFControl import STEPCAFControl_Reader
    from OCP.TopoDS import TopoDS_Compound
    STEPControl_Controller.Init_s()
    quiet_kernel()
    Interface_Static.SetCVal_s("xstep.cascade.unit", "MM")
    doc = TDocStd_Document(TCollection_ExtendedString("XmlXCAF"))
    caf = STEPCAFControl_Reader()
    caf.SetNameMode(True)
    if caf.ReadFile(str(path)) != IFSelect_RetDone or not caf.Transfer(doc):
        raise BuildError(f"cannot read STEP file {path}")
    lengths, angles, solids = (TColStd_SequenceOfAsciiString() for _ in range(3))
    caf.Reader().FileUnits(lengths, angles, solids)
    units = [lengths.Value(i + 1).ToCString() for i in range(lengths.Length())]
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    labels = TDF_LabelSequence()
    tool.GetFreeShapes(labels)
    names, shapes = [], []
    for i in range(labels.Length()):
        lab: TDF_Label = labels.Value(i + 1)
        shapes.append(tool.GetShape_s(lab))
        attr = TDataStd_Name()
        if lab.FindAttribute(TDataStd_Name.GetID_s(), attr):
            names.append(attr.Get().ToExtString())
    if len(shapes) == 1:
        shape = shapes[0]
    else:
        shape = TopoDS_Compound()
        builder = BRep_Builder()
        builder.MakeCompound(shape)
        for sh in shapes:
            builder.Add(shape, sh)
    return StepContents(shape, units, names)


def read_stl(path):
    """Triangles of a binary or ASCII STL as ``(n, 3, 3) float`` (mm), via numpy only."""
    import numpy as np
    data = Path(path).read_bytes()
    if len(data) >= 84:
        n = int.from_bytes(data[80:84], "little")
        if 84 + 50 * n == len(data):
            rec = np.frombuffer(data, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]),
                                count=n, offset=84)
            return rec["v"].astype(float)
    pts = [list(map(float, line.split()[1:4])) for line in data.decode().splitlines()
           if line.strip().startswith("vertex")]
    return np.array(pts, dtype=float).reshape(-1, 3, 3)


def exported_triangles(parts, folder) -> dict:
    """Part name -> triangles of its exported ``folder/<name>.stl``, for each of ``parts`` (placed
    parts) that has one; none with no ``folder``."""
    if folder is None:
        return {}
    stls = {p.name: Path(folder) / f"{p.name}.stl" for p in parts}
    return {name: read_stl(path) for name, path in stls.items() if path.is_file()}


__all__ = ["export_step", "unchecked", "write_step_file", "canonical_styles", "export_stl", "Tessellations", "placed_triangles", "solid_triangles", "write_stl", "update_manifest", "write_json", "atomic_path", "ExportRecord",
           "read_step", "read_stl", "exported_triangles", "StepContents", "STEP_UNITS", "MANIFEST"]
