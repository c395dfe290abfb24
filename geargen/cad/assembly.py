"""The assembly model: every part placed, the assembly STEP (tree, names, colours), overlap checks.

A :class:`PlacedPart` is a solid in its own frame plus a 4x4 placement (numpy, mm) into the
assembly frame of :mod:`geargen.pipeline` (output gear's centre at the origin, +x the symmetry
line towards the input, +z the gear axes). Per-part STEP/STL files are written in the assembly
frame, so they overlay into the assembly (each part's placement is in the manifest; its inverse
brings the part back to its own machining frame).

The non-gear parts are the resolved drive's components (:mod:`geargen.model.components`, laid
out by the drive kind's hardware in :mod:`geargen.drives`), built here body by body
(:mod:`geargen.cad.components`). Every contact that is meant to be there (a shaft in its
bore, a bearing on its shaft, a spring on its seat) is listed in ``intended_contacts``; the
overlap check fails on any other pair of parts that share volume.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping

import numpy as np
from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
from OCP.BRepBndLib import BRepBndLib
from OCP.Bnd import Bnd_Box
from OCP.gp import gp_Trsf
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Shape

from geargen.cad import parts as P
from geargen.cad.families import build_part
from geargen.cad.gear_solid import build_cluster, solid_volume
from geargen.cad.kernel import boolean, volume
from geargen.cad.solid_proofs import SolidFacts, face_set_distance, prism_common_volume, share_no_volume
from geargen.design.cluster import ClusterSpec
from geargen.errors import BuildError
from geargen.model.components import COLOURS, transform
from geargen.units import length_text, pitch_text

# ---------------------------------------------------------------- placements


def _trsf(m: np.ndarray) -> gp_Trsf:
    t = gp_Trsf()
    t.SetValues(*(float(v) for v in m[0]), *(float(v) for v in m[1]), *(float(v) for v in m[2]))
    return t


def location(m: np.ndarray) -> TopLoc_Location:
    """The kernel's location of the 4x4 placement ``m`` (mm)."""
    return TopLoc_Location(_trsf(m))


@dataclass
class PlacedPart:
    """A part: ``shape`` in its own frame, ``matrix`` (4, 4) into the assembly frame (mm).

    ``group`` is the sub-assembly it belongs to (the STEP tree), ``kind`` a colour key of
    :data:`COLOURS`, ``role`` what it is for the report ("gear", "reference", ...).
    """

    name: str
    shape: TopoDS_Shape
    matrix: np.ndarray
    group: str
    kind: str
    role: str = "part"
    description: str = ""
    solid: Any = None  # the GearSolid of a gear (profile, spec), for the checks
    notes: tuple[str, ...] = ()  # what building it reported (an undercut, ...), for the build's report
    # a simple solid holding the part (own frame): the overlap check's first, cheap test (a helical
    # spring's tube); gears have theirs from ``solid`` (:func:`part_envelope`)
    envelope: TopoDS_Shape | None = None
    # what meshes a part that is not a gear from its exact geometry (:attr:`mesh_source`): a toothed
    # component's family solid (a bevel gear's BevelSolid), a spring's SpringSolid
    exact: Any = None
    # a toothed component of the hardware (a bevel gear): not a gear for the checks (``solid``), its flanks
    # a gear's all the same (its STL at the gears' tolerance)
    toothed: bool = False
    _world: TopoDS_Shape | None = field(default=None, repr=False)

    @property
    def mesh_source(self):
        """What the STL and the view mesh (:func:`geargen.cad.export.solid_triangles` picks the mesher): the
        gear's solid, another part's exact mesher (:attr:`exact`), else the shape (the kernel's)."""
        return next((s for s in (self.solid, self.exact) if s is not None), self.shape)

    @property
    def colour(self) -> tuple[float, float, float, float]:
        return COLOURS.get(self.kind, COLOURS["gear"])

    def world(self) -> TopoDS_Shape:
        """The part moved into the assembly frame (cached; it shares the geometry of ``shape``)."""
        if self._world is None:
            self._world = self.shape.Moved(location(self.matrix))
        return self._world


@dataclass
class PartSet:
    """All non-gear parts of an assembly (and, after :func:`all_parts`, the gears too)."""

    parts: list[PlacedPart]
    intended_contacts: list[tuple[str, str, str]]  # (part, part, why)
    notes: list[str] = field(default_factory=list)
    dimensions: dict[str, Any] = field(default_factory=dict)  # key sizes for the report (mm)
    # how the parts hold together (geargen.checks.structure): held by the machine (or supported
    # outside the model), never turning, turning besides the gears, contacts that roll (a mesh)
    ground: tuple[str, ...] = ()
    stationary: tuple[str, ...] = ()
    rotating: tuple[str, ...] = ()
    rolling: tuple[tuple[str, str], ...] = ()
    # meshing pairs among these parts (part, part, why): checked by their mesh checker, not the overlap check
    meshing: tuple[tuple[str, str, str], ...] = ()

    def part(self, name: str) -> PlacedPart:
        for p in self.parts:
            if p.name == name:
                return p
        raise KeyError(name)


# ---------------------------------------------------------------- gears


def gear_parts(layout, tolerance: float | None = None) -> dict[str, PlacedPart]:
    """Build every toothed part of ``layout`` (``geargen.pipeline.Layout``); identical specs are
    built once and placed as often as needed. ``tolerance`` (mm) is the gear builder's spline
    tolerance (None: its default). Returns parts by name."""
    import warnings
    cache: dict[Any, Any] = {}
    out: dict[str, PlacedPart] = {}
    for g in layout.gears:
        key = g.spec
        if key not in cache:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                if isinstance(g.spec, ClusterSpec):
                    solid = build_cluster(g.spec, tolerance)
                else:  # any family's part (a planetary stage's ring, a rack drive's rack): its own builder
                    solid = build_part(g.spec, tolerance=tolerance)
            # undercut and the like: reported with the build, not printed
            cache[key] = (solid, tuple(dict.fromkeys(str(w.message) for w in caught)))
        solid, notes = cache[key]
        m = transform((g.centre[0], g.centre[1], g.z), (0, 0, 1), g.rotation)
        kind = "gear_output" if "output" in g.roles else "gear_input" if "input" in g.roles or \
            "pinion_stiff" in g.roles else "gear_cluster"
        desc = _gear_text(g.spec)
        out[g.name] = PlacedPart(g.name, solid.shape, m, g.group, kind, "gear", desc, solid,
                                 tuple(f"{g.name}: {n}" for n in notes))
    return out


def _gear_text(spec) -> str:
    if isinstance(spec, ClusterSpec):
        return f"cluster {spec.large.teeth}/{spec.small.teeth} T"
    helix = f", helix {math.degrees(spec.helix_angle):.4g} deg {spec.hand}" if spec.is_helical else ""
    unit = spec.length_unit
    return f"{spec.teeth} T, {pitch_text(spec.module, unit)}{helix}, face {length_text(spec.face_width, unit)}"


# ---------------------------------------------------------------- the [parts] section

def non_gear_parts(layout, stiffness=None) -> PartSet:
    """The solids of the resolved drive's hardware (none for a drive without it)."""
    if layout.hardware is None:
        return PartSet([], [])
    return parts_from_hardware(layout.hardware)


def parts_from_hardware(hardware) -> PartSet:
    """The solids of the resolved drive's hardware (:class:`geargen.model.components.Hardware`),
    each built by its body's builder and placed as the component says."""
    from geargen.cad.components import SolidBuilder
    builder = SolidBuilder()
    parts = []
    for c in hardware.components:
        shape = builder.component(c)
        parts.append(PlacedPart(c.name, shape, c.placement, c.group, c.kind, c.role, c.description,
                                envelope=builder.envelope(c), exact=builder.exact(c, shape),
                                toothed=c.toothed is not None))
    return PartSet(parts, hardware.contacts, list(hardware.notes), dict(hardware.dimensions), hardware.ground,
                   hardware.stationary, hardware.rotating, hardware.rolling, hardware.meshing)


# ---------------------------------------------------------------- the whole assembly


def all_parts(gears: Mapping[str, PlacedPart], others: PartSet) -> list[PlacedPart]:
    return list(gears.values()) + list(others.parts)


def assembly_document(name: str, parts: Iterable[PlacedPart]):
    """The assembly as an XCAF document: root ``name``, one sub-assembly ``<group>_assembly`` per
    group, each part an occurrence named as the part, placed by its matrix, coloured (surface
    colour, alpha kept). Parts sharing one shape and colour share one product (named after the
    first). Names must be unique in the whole tree. The tree is the one CadQuery's ``Assembly``
    writes, built here with the kernel directly."""
    from OCP.Quantity import Quantity_Color, Quantity_ColorRGBA, Quantity_TOC_sRGB
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFDoc import XCAFDoc_ColorType, XCAFDoc_DocumentTool

    parts = list(parts)
    names = [p.name for p in parts]
    if len(set(names)) != len(names):
        raise BuildError(f"assembly {name}: part names are not unique")
    doc = TDocStd_Document(TCollection_ExtendedString("XmlXCAF"))
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    tool.SetAutoNaming_s(False)
    colours = XCAFDoc_DocumentTool.ColorTool_s(doc.Main())

    def named(label, text):
        TDataStd_Name.Set_s(label, TCollection_ExtendedString(text))
        return label

    root = named(tool.NewShape(), name)
    groups: dict[str, Any] = {}
    products: list[tuple[TopoDS_Shape, tuple, Any]] = []  # (shape, colour, label)
    for p in parts:
        if p.group not in groups:
            groups[p.group] = named(tool.NewShape(), f"{p.group}_assembly")
        label = next((lab for shape, colour, lab in products if colour == p.colour and shape.IsSame(p.shape)), None)
        if label is None:
            label = named(tool.NewShape(), p.name)
            tool.SetShape(label, p.shape)
            r, g, b, a = p.colour
            colours.SetColor(label, Quantity_ColorRGBA(Quantity_Color(r, g, b, Quantity_TOC_sRGB), a),
                             XCAFDoc_ColorType.XCAFDoc_ColorSurf)
            products.append((p.shape, p.colour, label))
        named(tool.AddComponent(groups[p.group], label, location(p.matrix)), p.name)
    for grp in groups.values():
        tool.AddComponent(root, grp, TopLoc_Location())
    tool.UpdateAssemblies()
    return doc


def write_assembly_step(name: str, parts: Iterable[PlacedPart], path: Path, length_unit: str = "mm") -> Path:
    """The assembly STEP: tree root/group/part, names and colours, declared in ``length_unit``
    (geometry in mm, converted by the writer); edges as 3-D curves only, as the part files."""
    from OCP.Interface import Interface_Static
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Controller
    from OCP.XSControl import XSControl_WorkSession
    from geargen.cad.export import STEP_UNITS, unchecked, write_step_file
    from geargen.cad.kernel import quiet_kernel

    doc = assembly_document(name, parts)
    STEPControl_Controller.Init_s()
    quiet_kernel()
    writer = unchecked(STEPCAFControl_Writer(XSControl_WorkSession(), False))
    writer.SetColorMode(True)
    writer.SetLayerMode(True)
    writer.SetNameMode(True)
    Interface_Static.SetIVal_s("write.surfacecurve.mode", 0)
    Interface_Static.SetIVal_s("write.precision.mode", 0)
    Interface_Static.SetCVal_s("xstep.cascade.unit", "MM")
    Interface_Static.SetCVal_s("write.step.unit", STEP_UNITS[length_unit])
    if not writer.Transfer(doc, STEPControl_AsIs):
        raise BuildError(f"assembly STEP transfer failed: {path}")
    return write_step_file(writer, path)  # reproducible bytes: a fixed header date, colours in a stable order


def export_parts(layout, parts_set: PartSet | list, folder: Path, settings: Mapping[str, Any],
                 step_files: Callable[[], dict[str, Any]] | None = None) -> dict[str, Any]:
    """Write assembly.step and, per part, ``<name>.step`` and ``<name>.stl`` (assembly frame).

    ``step_files``: called once the STL files are written here, returns what
    :func:`export_step_files` returned for these parts into ``folder`` (the STEP files written by
    another process meanwhile); None: the STEP files written here, before the STL files.

    Returns ``{"records": {file: manifest entry}, "parts": {name: placement and files},
    "tolerances": {...}}``.
    """
    parts = parts_set if isinstance(parts_set, list) else parts_set.parts
    steps = export_step_files(layout, parts, folder) if step_files is None else None
    meshes = export_meshes(parts, folder, settings)
    steps = steps if steps is not None else step_files()
    records: dict[str, Any] = {"assembly.step": steps["assembly"]}
    info: dict[str, Any] = {}
    for p in parts:
        step, step_entry = steps["parts"][p.name]
        stl, stl_entry = meshes["stl"][p.name]
        records[step] = step_entry
        records[stl] = stl_entry
        info[p.name] = {"group": p.group, "kind": p.kind, "role": p.role, "description": p.description,
                        "colour_rgba": list(p.colour), "placement_matrix_mm": p.matrix.round(12).tolist(),
                        "files": [step, stl], "volume_mm3": meshes["volumes"][p.name]}
    return {"records": records, "parts": info, "tolerances": meshes["tolerances"]}


def export_step_files(layout, parts_set: PartSet | list, folder: Path) -> dict[str, Any]:
    """assembly.step, then per part ``<name>.step`` (:func:`part_step_files`), into ``folder``:
    ``{"assembly": manifest entry, "parts": {part: (file name, manifest entry)}}``. Each file's usage ids
    count the kernel's assembly usages made before it in its process, so the files are always written in
    this one order, all in one process that has written no STEP file before; no STEP writer reads a mesh,
    so the STL files may be written meanwhile elsewhere."""
    parts = parts_set if isinstance(parts_set, list) else parts_set.parts
    unit = layout.identity.length_unit
    folder.mkdir(parents=True, exist_ok=True)
    asm = write_assembly_step(layout.identity.name, parts, folder / "assembly.step", unit)
    assembly = {"format": "step", "length_unit": unit, "bytes": asm.stat().st_size, "role": "assembly",
                "parts": [p.name for p in parts]}
    return {"assembly": assembly, "parts": part_step_files(layout, parts, folder)}


def part_step_files(layout, parts: list[PlacedPart], folder: Path) -> dict[str, tuple[str, dict]]:
    """Per part, ``<name>.step`` in ``folder`` (the design's length unit): its solid placed in the
    assembly frame, named after the part (:func:`geargen.cad.export.export_step`). Returns ``{part:
    (file name, manifest entry)}``."""
    from geargen.cad.export import export_step

    unit = layout.identity.length_unit
    folder.mkdir(parents=True, exist_ok=True)
    files = {}
    for p in parts:
        rs = export_step((p.name, p.world()), folder / f"{p.name}.step", unit)
        files[p.name] = (rs.path.name, rs.manifest_entry())
    return files


def export_meshes(parts_set: PartSet | list, folder: Path, settings: Mapping[str, Any]) -> dict[str, Any]:
    """Per part, ``<name>.stl`` (assembly frame) written into ``folder``, and each part's volume
    (mm^3, the kernel's integration of its solid): ``{"stl": {part: (file name, manifest entry)},
    "volumes": {part: mm^3}, "tolerances": {...}}``. Independent of the STEP files (no STEP writer
    reads a mesh), so a build writes them while another process writes the STEP files."""
    from geargen.cad.export import Tessellations, export_stl

    parts = parts_set if isinstance(parts_set, list) else parts_set.parts
    folder.mkdir(parents=True, exist_ok=True)
    chord = settings["stl_chordal_tolerance"]
    chord_parts = settings.get("stl_chordal_tolerance_parts") or chord
    ang = settings["stl_angular_tolerance"]
    meshes = Tessellations()
    stl: dict[str, tuple[str, dict]] = {}
    volumes: dict[str, float] = {}
    integrated: list[tuple[Any, float]] = []  # (shape, mm^3) already integrated
    for p in parts:
        # every part meshed in its own frame and moved by its placement: gears (and toothed components,
        # a bevel gear) by their exact mesher (20-50x faster than the kernel) within the gears' tolerance (a
        # toothed component's flanks are a gear's), springs by theirs, the others by the kernel; parts
        # sharing a solid (two bearings alike) are meshed once
        rl = export_stl(p.mesh_source, folder / f"{p.name}.stl",
                        chordal_tolerance=chord if p.role == "gear" or p.toothed else chord_parts,
                        angular_tolerance=ang,
                        transform=p.matrix, meshes=meshes)
        stl[p.name] = (rl.path.name, rl.manifest_entry())
        vol = next((v for shape, v in integrated if shape.IsSame(p.shape)), None)
        if vol is None:  # parts sharing a shape (the two clusters, bearings alike) share its volume
            vol = solid_volume(p.shape, 1e-6)
            integrated.append((p.shape, vol))
        volumes[p.name] = vol
    return {"stl": stl, "volumes": volumes,
            "tolerances": {"stl_chordal_mm_gears": chord, "stl_chordal_mm_other_parts": chord_parts,
                           "stl_angular_rad": ang,
                           "step_frame": "assembly frame (placement_matrix_mm maps the part's own frame into it)"}}


# ---------------------------------------------------------------- faces near a mesh


def faces_near(shape, points, radius: float) -> TopoDS_Shape:
    """The faces of ``shape`` that come within ``radius`` (mm) of any of ``points`` ``(k, 2)``
    (x, y in the shape's own frame, mm), as one compound, for sectioning only where two gears
    can meet.

    A face is kept when its bounding box, projected on z = 0, is within ``radius`` of a point.
    The boxes come from the faces' geometry (B-spline poles, analytic bounds), so they hold the
    whole face: every point of a dropped face is farther than ``radius`` from every point.
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    kept = []
    for face, box in _faces_with_boxes(shape):
        x0, y0, _, x1, y1, _ = box.Get()
        dx = np.maximum(np.maximum(x0 - pts[:, 0], pts[:, 0] - x1), 0.0)
        dy = np.maximum(np.maximum(y0 - pts[:, 1], pts[:, 1] - y1), 0.0)
        if float(np.min(np.hypot(dx, dy))) <= radius:
            kept.append(face)
    return P.compound(kept)


# ---------------------------------------------------------------- overlap check


@dataclass(frozen=True)
class Overlap:
    """Two parts sharing ``volume`` mm^3 (``intended``: listed as meant to touch, with ``why``)."""

    part1: str
    part2: str
    volume: float
    intended: bool
    why: str = ""


@dataclass
class OverlapReport:
    """Pairwise intersections: ``pairs_checked`` (bounding boxes touching), the overlaps found,
    the tolerance (mm^3) below which a shared volume counts as touching, not overlapping."""

    parts: int
    pairs_checked: int
    overlaps: list[Overlap]
    tolerance: float
    intended: list[tuple[str, str, str]]
    delegated: list[tuple[str, str, str]] = field(default_factory=list)
    # intended contacts whose solids do not touch: (part, part, gap mm, why)
    missing_contacts: list[tuple[str, str, float, str]] = field(default_factory=list)
    contact_tolerance: float = 1e-3

    @property
    def unintended(self) -> list[Overlap]:
        return [o for o in self.overlaps if not o.intended and o.volume > self.tolerance]

    @property
    def interpenetrating(self) -> list[Overlap]:
        """Intended contacts whose solids share volume: parts meant to touch that run into each other."""
        return [o for o in self.overlaps if o.intended and o.volume > self.tolerance]

    @property
    def ok(self) -> bool:
        return not (self.unintended or self.interpenetrating or self.missing_contacts)


def _bbox(shape) -> Bnd_Box:
    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box, True)
    return box


def _faces_with_boxes(shape):
    """Each face of ``shape`` with its bounding box, taken from the face's geometry (B-spline
    poles, analytic bounds), not from a possibly coarse mesh: the box holds the whole face."""
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        face = exp.Current()
        exp.Next()
        box = Bnd_Box()
        BRepBndLib.Add_s(face, box, False)
        yield face, box


def contact_gap(a, b, tolerance: float, facts: dict | None = None) -> float:
    """The smallest distance (mm) between the solids ``a`` and ``b``. Where they come within
    ``tolerance`` of each other only the faces of each that can are measured (a gear's teeth
    never come near its shaft), pair by pair from the closest bound up
    (:func:`geargen.cad.solid_proofs.face_set_distance`), so a shaft in a 112-tooth gear's bore,
    or a ring gear in its housing, costs milliseconds. ``facts`` as for :func:`intersection_volume`."""
    fa, fb = _facts(a, facts), _facts(b, facts)
    box_a, box_b = Bnd_Box(), Bnd_Box()
    box_a.Add(fa.kernel_box)
    box_b.Add(fb.kernel_box)
    box_a.Enlarge(tolerance)
    box_b.Enlarge(tolerance)
    if not box_a.IsOut(box_b):
        faces_a, surfaces_a, boxes_a = fa.faces_meeting(box_b)
        faces_b, surfaces_b, boxes_b = fb.faces_meeting(box_a)
        if faces_a and faces_b:
            return face_set_distance(faces_a, faces_b, surfaces_a, boxes_a, surfaces_b, boxes_b)
    # apart: measured on the whole solids (only a missing contact, the failure, pays for that)
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    dist = BRepExtrema_DistShapeShape(a, b)
    return float(dist.Value()) if dist.IsDone() else math.inf


def intersection_volume(a, b, facts: dict | None = None) -> float:
    """Volume (mm^3) of the boolean common of two shapes (0 if they only touch).

    Before the solid boolean, two proofs read from the shapes' own faces
    (:mod:`geargen.cad.solid_proofs`): boundaries that do not come near each other, no piece of
    either inside the other, is no shared volume (a shaft beside a plate); two right prisms along
    z (spur gears, shafts, bearings, plates) share their end regions' common area times their
    common height, a planar boolean (a ring gear with a planet: 0.1 s instead of 2.5 s).
    ``facts`` caches what is learnt of each shape (by ``id``; the facts keep the shape alive)."""
    fa, fb = (_facts(s, facts) for s in (a, b))
    if share_no_volume(fa, fb):
        return 0.0
    if fa.prism is not None and fb.prism is not None:
        return prism_common_volume(fa.prism, fb.prism)
    op = BRepAlgoAPI_Common()
    # the parts are closed solids with outward faces (a gear's checked by check_solid, the others made of
    # primitives), so the kernel's test of each argument for being inside out (a point classified at
    # infinity) changes nothing here and is a quarter of this boolean's time
    op.SetCheckInverted(False)
    common = boolean(op, [a], [b], parallel=False, failure="boolean common failed")
    return abs(volume(common))


def _facts(shape, cache: dict | None) -> SolidFacts:
    if cache is None:
        return SolidFacts(shape)
    if id(shape) not in cache:
        cache[id(shape)] = SolidFacts(shape)
    return cache[id(shape)]


def gear_core(part: PlacedPart) -> TopoDS_Shape | None:
    """The material of a gear part between its bore and its root circle (and its hubs; a ring
    gear's between its root circle and its rim), in the assembly frame: a cheap solid wholly inside
    the gear, so what runs into it runs into the gear (a shaft too big for the bore). None for a part that is not a gear, or one with a keyway
    (the core would not be all material)."""
    solid = part.solid
    if solid is None:
        return None
    spec = solid.spec
    gears = (spec.large, spec.small) if isinstance(spec, ClusterSpec) else (spec,)
    if not all(hasattr(g, "hub") for g in gears):  # a rack: no bore, nothing runs into a core
        return None
    if any(g.hub.keyway_width > 0 for g in gears):
        return None
    pieces = []
    for g, z0 in zip(gears, (0.0, spec.small_gear_z) if isinstance(spec, ClusterSpec) else (0.0,)):
        if getattr(g, "is_internal", False):
            # a ring gear's material is outside its teeth: from 2 % outside the root circle (or
            # halfway to the rim, if the rim is thinner than that) to the rim
            inner = min(1.02 * g.root_radius_standard, (g.root_radius_standard + g.rim_diameter / 2) / 2)
            pieces.append(P.translate(P.cylinder(g.rim_diameter, g.face_width, 2 * inner), (0, 0, z0)))
            continue
        bore = g.hub.bore_diameter
        # 2 % inside the root circle (the margin the design rules keep a bore from it): all material
        pieces.append(P.translate(P.cylinder(2 * 0.98 * g.root_radius_standard, g.face_width, bore), (0, 0, z0)))
        if g.hub.hub_length > 0:
            pieces.append(P.translate(P.cylinder(g.hub.hub_diameter, g.hub.hub_length, bore),
                                      (0, 0, z0 - g.hub.hub_length)))
    return P.compound(pieces).Moved(location(part.matrix))


def part_envelope(part: PlacedPart) -> TopoDS_Shape | None:
    """A cheap solid that contains the part, in the assembly frame: a gear's tip cylinders (a ring
    gear's annulus from its tip circle to its rim; with hubs and spacer), another part's ``envelope``; None if the part has none."""
    solid = part.solid
    if solid is None:
        return None if part.envelope is None else part.envelope.Moved(location(part.matrix))
    spec = solid.spec
    if not isinstance(spec, ClusterSpec) and not hasattr(spec, "hub"):  # a rack: its own (prismatic) solid
        return part.shape.Moved(location(part.matrix))
    pieces = []

    def gear_body(g, z0):
        if getattr(g, "is_internal", False):
            # a ring gear's material lies between its tip circle (its teeth point inwards) and its
            # rim: that annulus, its bore 1 % inside the tip circle (the built tips lie on it to float
            # noise), clears the sun and what passes through the ring without a boolean
            body = P.cylinder(g.rim_diameter, g.face_width, 2 * 0.99 * g.tip_radius)
        else:
            body = P.cylinder(2 * g.tip_radius, g.face_width)
        pieces.append(P.translate(body, (0, 0, z0)))
        if g.hub.hub_length > 0:
            pieces.append(P.translate(P.cylinder(g.hub.hub_diameter, g.hub.hub_length), (0, 0, z0 - g.hub.hub_length)))

    if isinstance(spec, ClusterSpec):
        gear_body(spec.large, 0.0)
        gear_body(spec.small, spec.small_gear_z)
        if spec.axial_gap > 0:
            pieces.append(P.translate(P.cylinder(spec.spacer_diameter_resolved, spec.axial_gap),
                                      (0, 0, spec.large.face_width)))
    else:
        gear_body(spec, 0.0)
    return P.compound(pieces).Moved(location(part.matrix))


def pairwise_overlaps(parts: Iterable[PlacedPart], intended: Iterable[tuple[str, str, str]] = (),
                      tolerance: float = 1e-3, skip_intended: bool = True,
                      delegated: Iterable[tuple[str, str, str]] = (), contact_tolerance: float = 1e-3) -> OverlapReport:
    """Check every pair of parts for shared volume (boolean common, after a bounding-box test).

    Pairs listed in ``intended`` (part, part, why) are meant to touch: with ``skip_intended``
    they are not intersected (their contact is by construction, a shaft in its bore). Pairs in
    ``delegated`` (meshing gears) are checked elsewhere, by the geometric mesh checker, and
    skipped here. A gear is first tested through its tip-cylinder envelope (a helical spring
    through its tube: :func:`part_envelope`); only when that shares volume with the other part
    are the exact solids intersected. Any other pair sharing
    more than ``tolerance`` mm^3 is an overlap.

    Every intended contact is verified: its two solids must come within ``contact_tolerance``
    (mm) of each other (:func:`contact_gap`), else it is a missing contact, and must not share
    more than ``tolerance`` mm^3 (interpenetrating).
    """
    parts, intended = list(parts), list(intended)
    wanted = {frozenset((a, b)): why for a, b, why in intended}
    skip = {frozenset((a, b)) for a, b, _ in delegated}
    facts: dict = {}  # what is learnt of each solid, once (intersection_volume, contact_gap)
    boxes = [_facts(p.world(), facts).kernel_box for p in parts]  # _bbox's box, kept for contact_gap
    envelopes = [part_envelope(p) for p in parts]
    overlaps: list[Overlap] = []
    checked = 0
    for i in range(len(parts)):
        for j in range(i + 1, len(parts)):
            if boxes[i].IsOut(boxes[j]):
                continue
            key = frozenset((parts[i].name, parts[j].name))
            if key in skip or (key in wanted and skip_intended):
                continue
            checked += 1
            a = envelopes[i] if envelopes[i] is not None else parts[i].world()
            b = envelopes[j] if envelopes[j] is not None else parts[j].world()
            if envelopes[i] is not None or envelopes[j] is not None:
                if intersection_volume(a, b, facts) <= tolerance:
                    continue
            v = intersection_volume(parts[i].world(), parts[j].world(), facts)
            if v > tolerance or key in wanted:
                overlaps.append(Overlap(parts[i].name, parts[j].name, v, key in wanted, wanted.get(key, "")))
    # every intended contact must be one: the two solids touch (a check that can fail), and
    # (when not intersected above) do not run into each other
    by_name = {p.name: p for p in parts}
    envelope_of = {p.name: e for p, e in zip(parts, envelopes)}
    cores: dict[str, TopoDS_Shape | None] = {}  # each gear's core made once, so its facts are learnt once

    def core(name):
        if name not in cores:
            cores[name] = gear_core(by_name[name])
        return cores[name]

    missing = []
    for a, b, why in intended:
        if a not in by_name or b not in by_name:
            missing.append((a, b, math.inf, why + " (no such part)"))
            continue
        gap = contact_gap(by_name[a].world(), by_name[b].world(), contact_tolerance, facts)
        if gap > contact_tolerance:
            missing.append((a, b, gap, why))
        elif skip_intended:
            # a spring seated on a wall: its tube only touches the wall, so the helix cannot
            # run into it (the exact helix is intersected only when the tube shares volume)
            tubes = [envelope_of[n] if by_name[n].envelope is not None else None for n in (a, b)]
            if any(t is not None for t in tubes) and intersection_volume(
                    *(t if t is not None else by_name[n].world() for t, n in zip(tubes, (a, b))), facts) <= tolerance:
                continue
            # a gear is represented by its core (bore to root circle): exact for what comes in
            # through the bore, and milliseconds instead of a boolean with every tooth
            core_a, core_b = core(a), core(b)
            v = intersection_volume(core_a if core_a is not None else by_name[a].world(),
                                    core_b if core_b is not None else by_name[b].world(), facts)
            if v > tolerance:
                overlaps.append(Overlap(a, b, v, True, why))
    report = OverlapReport(len(parts), checked, overlaps, tolerance, list(intended), missing_contacts=missing,
                           contact_tolerance=contact_tolerance)
    report.delegated = list(delegated)
    return report


__all__ = ["COLOURS", "transform", "location", "PlacedPart", "PartSet", "gear_parts",
           "non_gear_parts", "parts_from_hardware", "all_parts", "assembly_document",
           "write_assembly_step", "export_parts", "export_step_files", "part_step_files", "export_meshes", "faces_near", "Overlap", "OverlapReport", "intersection_volume",
           "pairwise_overlaps"]
