"""Non-gear parts of an assembly model as simple solids (mm, OCCT shapes through OCP).

Every builder works in the part's own frame and says so; :mod:`geargen.cad.assembly` places
them. Each solid has a closed-form volume (given in its docstring, checked by the tests), so a
part that comes out wrong is caught. The parts are design-review bodies, not manufacturing
models: a bearing is a ring of its envelope, a motor its envelope, a bevel gear the frustum of
its pitch cone.

The builders return ``TopoDS_Shape`` and talk to the kernel (OCP) directly, with the same
operations CadQuery would use (primitives, booleans, ``ShapeUpgrade_UnifySameDomain`` as its
``clean``, a pipe shell for the spring): importing CadQuery costs seconds (it pulls in VTK)
that a build does not need. :func:`volume`, :func:`is_valid`, :func:`bounding_box`,
:func:`translate` and :func:`compound` are the few shape queries the rest of ``cad`` uses.

Frames, unless a builder says otherwise: the part's axis is +z, its lowest face at z = 0.
"""

from __future__ import annotations

import math

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Builder
from OCP.BRepAlgoAPI import BRepAlgoAPI_Common, BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import (BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire,
                                BRepBuilderAPI_Transform, BRepBuilderAPI_Transformed)
from OCP.BRepLib import BRepLib
from OCP.BRepOffsetAPI import BRepOffsetAPI_MakePipeShell
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCone, BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakePrism
from OCP.GC import GC_MakeArcOfCircle
from OCP.GCE2d import GCE2d_MakeSegment
from OCP.Geom import Geom_CylindricalSurface
from OCP.Geom2d import Geom2d_Line
from OCP.gp import gp_Ax2, gp_Ax3, gp_Circ, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d, gp_Trsf, gp_Vec
from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain
from OCP.TopAbs import TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Shape, TopoDS_Wire

from geargen.cad.kernel import boolean, volume  # noqa: F401 - volume is part of this module's interface (P.volume)
from geargen.families.bevel.geometry import BevelPairGeometry
from geargen.errors import BuildError


def _internal(field: str, problem: str, allowed: str = "") -> ValueError:
    """Numbers no builder can make: the resolved drive checks its parts before the CAD layer sees
    them (geargen.model.bodies), so reaching here is a bug, not bad input."""
    return ValueError(f"{field}: {problem}" + (f" (allowed: {allowed})" if allowed else ""))


def _positive(**values) -> None:
    for name, v in values.items():
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise _internal(name, f"{v!r} is out of range", "> 0 mm")


# ---------------------------------------------------------------- shape queries and operations


def is_valid(shape: TopoDS_Shape) -> bool:
    """Whether the kernel's checker (``BRepCheck_Analyzer``) finds no defect in ``shape``."""
    return BRepCheck_Analyzer(shape).IsValid()


def bounding_box(shape: TopoDS_Shape, optimal: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Corners ``(lo (3,), hi (3,))`` (mm) of the axis-aligned box around ``shape``: ``optimal``
    from the geometry itself (tight), otherwise the kernel's quick box (may be larger)."""
    box = Bnd_Box()
    if optimal:
        BRepBndLib.AddOptimal_s(shape, box)
    else:
        BRepBndLib.Add_s(shape, box, True)
    x0, y0, z0, x1, y1, z1 = box.Get()
    return np.array([x0, y0, z0]), np.array([x1, y1, z1])


def solids(shape: TopoDS_Shape) -> list[TopoDS_Shape]:
    """The solids in ``shape``."""
    out = []
    exp = TopExp_Explorer(shape, TopAbs_SOLID)
    while exp.More():
        out.append(TopoDS.Solid_s(exp.Current()))
        exp.Next()
    return out


def translate(shape: TopoDS_Shape, vector) -> TopoDS_Shape:
    """A copy of ``shape`` moved by ``vector`` (x, y, z) mm."""
    t = gp_Trsf()
    t.SetTranslation(gp_Vec(*(float(v) for v in vector)))
    return BRepBuilderAPI_Transform(shape, t, True).Shape()


def compound(shapes) -> TopoDS_Compound:
    """One compound of ``shapes`` (no boolean: they are only grouped)."""
    out = TopoDS_Compound()
    builder = BRep_Builder()
    builder.MakeCompound(out)
    for s in shapes:
        builder.Add(out, s)
    return out


def cut(shape: TopoDS_Shape, *tools: TopoDS_Shape) -> TopoDS_Shape:
    """``shape`` minus ``tools``."""
    return boolean(BRepAlgoAPI_Cut(), [shape], tools, parallel=True)


def intersect(shape: TopoDS_Shape, *tools: TopoDS_Shape) -> TopoDS_Shape:
    """The common part of ``shape`` and ``tools``."""
    return boolean(BRepAlgoAPI_Common(), [shape], tools, parallel=True)


def union(shape: TopoDS_Shape, *tools: TopoDS_Shape) -> TopoDS_Shape:
    """``shape`` fused with ``tools`` (faces not merged: see :func:`clean`)."""
    return boolean(BRepAlgoAPI_Fuse(), [shape], tools, parallel=True)


def clean(shape: TopoDS_Shape) -> TopoDS_Shape:
    """Coplanar (same-domain) faces and edges merged (``ShapeUpgrade_UnifySameDomain``)."""
    up = ShapeUpgrade_UnifySameDomain(shape, True, True, True)
    up.AllowInternalEdges(False)
    up.Build()
    return up.Shape()


def _valid(shape: TopoDS_Shape, what: str) -> TopoDS_Shape:
    if not is_valid(shape):
        raise BuildError(f"{what}: the kernel made an invalid solid")
    return shape


def one_valid_solid(shape: TopoDS_Shape, what: str) -> TopoDS_Shape:
    """The one solid ``shape`` holds, valid; BuildError naming ``what`` otherwise."""
    found = solids(shape)
    if len(found) != 1:
        raise BuildError(f"{what}: expected one solid, got {len(found)}")
    return _valid(found[0], what)


def fuse(shapes: list[TopoDS_Shape], what: str = "fused part") -> TopoDS_Shape:
    """Fuse touching or overlapping solids into one solid (coplanar faces merged)."""
    out = shapes[0]
    if len(shapes) > 1:
        out = clean(union(out, *shapes[1:]))
    return one_valid_solid(out, what)


def _cylinder(radius: float, height: float, base=(0.0, 0.0, 0.0)) -> TopoDS_Shape:
    return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(*map(float, base)), gp_Dir(0, 0, 1)), radius, height,
                                    2 * math.pi).Shape()


def _box(size_x: float, size_y: float, size_z: float, corner=(0.0, 0.0, 0.0)) -> TopoDS_Shape:
    return BRepPrimAPI_MakeBox(gp_Ax2(gp_Pnt(*map(float, corner)), gp_Dir(0, 0, 1)), size_x, size_y, size_z).Shape()


# Plates and rings as one planar face (outline, holes as inner wires) extruded along +z: the solid a
# box or cylinder less its bores would be, with the same faces, and no boolean (a boolean of
# primitives costs ~4 ms; an extrusion ~0.2 ms).


def _circle_wire(x: float, y: float, z: float, radius: float, hole: bool = False) -> TopoDS_Wire:
    """The circle of ``radius`` about (x, y) in the plane at ``z``: counter-clockwise seen from +z,
    clockwise as a ``hole`` of a face."""
    edge = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(x, y, z), gp_Dir(0, 0, 1)), radius)).Edge()
    wire = BRepBuilderAPI_MakeWire(edge).Wire()
    return TopoDS.Wire_s(wire.Reversed()) if hole else wire


def _rectangle_wire(x0: float, y0: float, x1: float, y1: float, z: float) -> TopoDS_Wire:
    """The rectangle [x0, x1] x [y0, y1] in the plane at ``z``, counter-clockwise seen from +z."""
    corners = [gp_Pnt(x0, y0, z), gp_Pnt(x1, y0, z), gp_Pnt(x1, y1, z), gp_Pnt(x0, y1, z)]
    wire = BRepBuilderAPI_MakeWire()
    for a, b in zip(corners, corners[1:] + corners[:1]):
        wire.Add(BRepBuilderAPI_MakeEdge(a, b).Edge())
    return wire.Wire()


def _round_end_wire(radius: float, x_end: float, z: float) -> TopoDS_Wire:
    """A link's outline in the plane at ``z``: the half disc of ``radius`` about the origin on
    x <= 0 joined to the rectangle [0, x_end] x [-radius, radius]; counter-clockwise seen from +z."""
    def at(x, y):
        return gp_Pnt(x, y, z)
    wire = BRepBuilderAPI_MakeWire()
    wire.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(at(0, radius), at(-radius, 0), at(0, -radius)).Value()).Edge())
    for a, b in ((at(0, -radius), at(x_end, -radius)), (at(x_end, -radius), at(x_end, radius)),
                 (at(x_end, radius), at(0, radius))):
        wire.Add(BRepBuilderAPI_MakeEdge(a, b).Edge())
    return wire.Wire()


def _extruded(outline: TopoDS_Wire, holes, height: float) -> TopoDS_Shape:
    """The planar face inside ``outline`` less ``holes`` (wires from :func:`_circle_wire` with
    ``hole``), extruded by ``height`` along +z."""
    face = BRepBuilderAPI_MakeFace(outline, True)
    for hole in holes:
        face.Add(hole)
    return BRepPrimAPI_MakePrism(face.Face(), gp_Vec(0, 0, height), True).Shape()


def _ring(x: float, y: float, z: float, diameter: float, bore: float, height: float) -> TopoDS_Shape:
    """A (bored) cylinder on +z from (x, y, z): ``diameter``, ``bore`` (0: none), ``height``."""
    holes = [_circle_wire(x, y, z, bore / 2, hole=True)] if bore > 0 else []
    return _extruded(_circle_wire(x, y, z, diameter / 2), holes, height)


# ---------------------------------------------------------------- primitives


def cylinder(diameter: float, height: float, bore: float = 0.0) -> TopoDS_Shape:
    """A (hollow) cylinder on +z, z in [0, height]. Volume ``pi/4 (d^2 - bore^2) h``."""
    _positive(diameter=diameter, height=height)
    if not 0 <= bore < diameter:
        raise _internal("bore", f"{bore!r} mm is out of range", f"[0, {diameter:.6g}) mm")
    # a primitive, or one concentric annulus extruded: valid by construction, no check (0.5 ms each)
    return _cylinder(diameter / 2, height) if bore == 0 else _ring(0.0, 0.0, 0.0, diameter, bore, height)


def box(size_x: float, size_y: float, size_z: float, corner=(0.0, 0.0, 0.0)) -> TopoDS_Shape:
    """An axis-aligned box with its lowest corner at ``corner``. Volume ``x y z``."""
    _positive(size_x=size_x, size_y=size_y, size_z=size_z)
    return _box(size_x, size_y, size_z, corner)


def box_between(lo, hi) -> TopoDS_Shape:
    """The axis-aligned box from corner ``lo`` to corner ``hi`` (each ``(x, y, z)``, mm)."""
    return box(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], lo)


def frustum(bottom_radius: float, top_radius: float, height: float, bore: float = 0.0) -> TopoDS_Shape:
    """A cone frustum on +z, radius ``bottom_radius`` at z = 0 and ``top_radius`` at ``height``.

    Volume ``pi h (R^2 + R r + r^2) / 3 - pi/4 bore^2 h``.
    """
    _positive(bottom_radius=bottom_radius, top_radius=top_radius, height=height)
    if not 0 <= bore < 2 * min(bottom_radius, top_radius):
        raise _internal("bore", f"{bore!r} mm is out of range", "smaller than both end diameters")
    solid = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), bottom_radius, top_radius, height,
                                 2 * math.pi).Shape()
    if bore > 0:
        solid = cut(solid, _cylinder(bore / 2, height))
    return one_valid_solid(solid, "frustum")


# ---------------------------------------------------------------- machine elements


def shaft(diameter: float, length: float, bore: float = 0.0) -> TopoDS_Shape:
    """A round (hollow) shaft on +z, z in [0, length]."""
    return cylinder(diameter, length, bore)


def bearing(bore: float, outer_diameter: float, width: float) -> TopoDS_Shape:
    """A rolling bearing as its envelope ring: ``bore`` to ``outer_diameter``, z in [0, width]."""
    if not outer_diameter > bore:
        raise _internal("outer_diameter", f"{outer_diameter!r} mm is not larger than the bore", f"> {bore:.6g} mm")
    return cylinder(outer_diameter, width, bore)


def bevel_pitch_cone(geometry: BevelPairGeometry, which: str, bore: float = 0.0) -> TopoDS_Shape:
    """The pitch-cone frustum of one gear of a bevel pair: heel at z = 0, apex on +z.

    Radius ``pitch_radius`` at z = 0, ``toe_radius`` at z = ``axial_height``; the pair's common
    apex is at z = ``apex_height``. Two such frusta placed on their axes touch along the pitch
    line (the pitch cones roll on each other).
    """
    r0 = geometry._cone(which)[0]
    return frustum(r0, geometry.toe_radius(which), geometry.axial_height(which), bore)


def servo_motor(body_diameter: float, body_length: float, flange_width: float, flange_thickness: float,
                shaft_diameter: float, shaft_length: float) -> TopoDS_Shape:
    """A servo-motor envelope: square mounting flange z in [0, t], round body z in [t, t + L]
    (encoder included), output shaft stub z in [-shaft_length, 0].

    Volume ``w^2 t + pi/4 D^2 L + pi/4 d^2 l``.
    """
    _positive(body_diameter=body_diameter, body_length=body_length, flange_width=flange_width,
              flange_thickness=flange_thickness, shaft_diameter=shaft_diameter, shaft_length=shaft_length)
    if not shaft_diameter < min(body_diameter, flange_width):
        raise _internal("shaft_diameter", "the shaft is not thinner than the motor", "< body diameter")
    flange = box(flange_width, flange_width, flange_thickness, (-flange_width / 2, -flange_width / 2, 0))
    body = translate(cylinder(body_diameter, body_length), (0, 0, flange_thickness))
    stub = translate(cylinder(shaft_diameter, shaft_length), (0, 0, -shaft_length))
    return fuse([flange, body, stub], "servo motor")


def blade_flexure(thickness: float, length: float, width: float) -> TopoDS_Shape:
    """One blade flexure: ``thickness`` along x (the direction it flexes), ``width`` along y,
    ``length`` (free, between the clamps) along z; centred on x = y = 0, z in [0, length]."""
    _positive(thickness=thickness, length=length, width=width)
    return box(thickness, width, length, (-thickness / 2, -width / 2, 0))


def compression_spring(wire_diameter: float, mean_coil_diameter: float, length: float, total_coils: float,
                       ground: bool) -> TopoDS_Shape:
    """A helical compression spring at ``length`` (installed), z in [0, length]: the round wire swept
    along the helix of :func:`geargen.model.bodies.spring_helix` (``total_coils`` turns), cut to the
    slab [0, length] (with ``ground`` ends, the cut is the grinding: half the wire off each end;
    plain ends only touch the slab's faces, so nothing is cut).
    The wire circle lies in a plane through the axis, so by Pappus the swept volume is
    ``pi^2 d^2 D n / 4``; the grinding takes ``pi D d^3 / (6 p)`` off it (the half discs below
    each end plane, first moment ``2 (d/2)^3 / 3`` about it, over the wire's rise ``p / 2 pi``
    per radian at radius ``D/2``)."""
    from geargen.model.bodies import spring_helix
    _positive(wire_diameter=wire_diameter, mean_coil_diameter=mean_coil_diameter, length=length,
              total_coils=total_coils)
    d, mean = wire_diameter, mean_coil_diameter
    if not mean > 2 * d:
        raise _internal("mean_coil_diameter", "spring index D/d must exceed 2", f"> {2 * d:.6g} mm")
    z0, pitch = spring_helix((d, mean, length, total_coils, ground))
    if not pitch > d:
        raise _internal("length", f"{length:.6g} mm closes the coils (pitch {pitch:.4g} <= wire {d:.4g} mm)",
                        "longer than the solid height")
    # ground: the end half turns are edges (so faces) of their own, and the slab's planes meet only
    # them (p > d: the grinding reaches d / 2p < 1/2 turn in): the cut intersects two small faces,
    # not the whole coil's (robot joint spring 0.26 -> 0.08 s). The middle face keeps the whole
    # sweep's spans over fewer turns, so it meshes finer: STL 7,792 -> 13,142 triangles, +0.07 s
    # (planetary's spring 15,408 -> 15,448), less than the cut saves
    ends = (0.5, total_coils - 0.5) if ground else ()
    helix = _helix(pitch, pitch * total_coils, mean / 2, ends)
    circle = BRepBuilderAPI_MakeWire(
        BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(mean / 2, 0, 0), gp_Dir(0, 1, 0)), d / 2)).Edge()).Wire()
    sweep = BRepOffsetAPI_MakePipeShell(helix)
    sweep.SetMode(True)  # Frenet frame along the helix
    sweep.SetTransitionMode(BRepBuilderAPI_Transformed)
    sweep.Add(circle, False, False)
    sweep.Build()
    sweep.MakeSolid()
    wire = translate(sweep.Shape(), (0, 0, z0))
    if not ground:
        return one_valid_solid(wire, "compression spring")
    # the slab as a box whose sides stand well clear of the coil: only its two end planes meet it
    half = mean
    slab = _box(2 * half, 2 * half, length, (-half, -half, 0.0))
    return one_valid_solid(intersect(wire, slab), "compression spring")


class SpringSolid:
    """A :func:`compression_spring`'s kernel solid (``shape``) and its body's arguments ``args``
    (d, D, length, total coils, ground): what :func:`geargen.cad.export.solid_triangles` meshes
    from the exact geometry (:func:`geargen.profile.spring_tessellate.spring_triangles`; the robot
    joint's spring at the STL's 0.05 mm and 30 deg: 6,016 triangles in ~2 ms against the kernel's
    13,142 in 0.13 s), the kernel meshing ``shape`` where that mesher declines."""

    def __init__(self, shape: TopoDS_Shape, args: tuple):
        self.shape, self.args = shape, tuple(args)

    def exact_triangles(self, chordal_tolerance: float, angular_tolerance: float | None = None):
        """The closed mesh (n, 3, 3) mm of the spring within ``chordal_tolerance`` mm, every vertex on
        the surface :func:`compression_spring` sweeps (the helix of
        :func:`geargen.model.bodies.spring_helix`; ground: cut by the slab's planes z = 0, length),
        its facets turning by at most ``angular_tolerance`` rad from one to the next."""
        from geargen.model.bodies import spring_helix
        from geargen.profile.spring_tessellate import spring_triangles
        d, mean, length, coils, ground = self.args
        z0, pitch = spring_helix(self.args)
        return spring_triangles(d, mean, z0, pitch, coils, chordal_tolerance, (0.0, length) if ground else None,
                                angular_tolerance)


def _helix(pitch: float, height: float, radius: float, breaks=()):
    """A right-hand helix on +z from (radius, 0, 0) as a wire: a line on the cylinder's (u, v)
    plane, its 3-D curve built by the kernel (as CadQuery's ``Wire.makeHelix``); ``breaks``: turns
    (counted from the start) where one edge ends and the next begins."""
    surface = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), radius)
    line = Geom2d_Line(gp_Pnt2d(0.0, 0.0), gp_Dir2d(2 * math.pi, pitch))
    turns = height / pitch
    per_turn = math.hypot(2 * math.pi, pitch)
    stops = [0.0] + sorted({t for t in breaks if 0 < t < turns}) + [turns]
    wire = BRepBuilderAPI_MakeWire()
    for start, end in zip(stops, stops[1:]):
        segment = GCE2d_MakeSegment(line.Value(start * per_turn), line.Value(end * per_turn)).Value()
        wire.Add(BRepBuilderAPI_MakeEdge(segment, surface).Edge())
    wire = wire.Wire()
    BRepLib.BuildCurves3d_s(wire, 1e-6, MaxSegment=2000)
    return wire


def coil_envelope(wire_diameter: float, mean_coil_diameter: float, length: float) -> TopoDS_Shape:
    """A spring as its envelope tube: inner diameter D - d, outer D + d, z in [0, length]."""
    return cylinder(mean_coil_diameter + wire_diameter, length, mean_coil_diameter - wire_diameter)


def plate_with_holes(size_x: float, size_y: float, thickness: float, holes: list[tuple[float, float, float]],
                     corner=(0.0, 0.0, 0.0)) -> TopoDS_Shape:
    """An axis-aligned plate (box from ``corner``) with through holes along z.

    ``holes``: ``(x, y, diameter)`` in the same frame as ``corner``. Volume
    ``x y t - sum pi/4 d_i^2 t`` (holes must lie wholly inside the plate and apart).
    """
    _positive(size_x=size_x, size_y=size_y, thickness=thickness)
    if not holes:
        return _box(size_x, size_y, thickness, corner)
    x0, y0, z0 = (float(c) for c in corner)
    outline = _rectangle_wire(x0, y0, x0 + size_x, y0 + size_y, z0)
    return one_valid_solid(_extruded(outline, [_circle_wire(xh, yh, z0, dh / 2, hole=True) for xh, yh, dh in holes],
                                     thickness), "plate")


def link_tray(radius: float, length: float, height: float, wall: float, floor: float,
              bosses: list[tuple[float, ...]] = ()) -> TopoDS_Shape:
    """The envelope of a robot link as an open-top tray: a round end of ``radius`` about the
    origin joined to a straight part out to x = ``length`` (width ``2 radius``), walls
    ``wall`` thick, floor ``floor`` thick, z in [0, height]; ``bosses`` ``(x, y, diameter,
    height[, relief])`` stand on the floor (their height counted from the floor's top), each
    with a blind relief bore of diameter ``relief`` from its top down to the floor (so a bearing's
    outer ring sits on the boss while its inner ring and the shaft end run clear).

    Volume ``A(R) h - A(R - wall) (h - floor) + sum pi/4 (d^2 - relief^2) h_b`` with
    ``A(R) = pi R^2 / 2 + 2 R length`` (half disc plus rectangle).
    """
    _positive(radius=radius, length=length, height=height, wall=wall, floor=floor)
    if not (wall < radius and floor < height):
        raise _internal("wall", "walls and floor leave no room inside", "wall < radius, floor < height")

    inner = radius - wall
    tray = cut(_extruded(_round_end_wire(radius, length, 0.0), [], height),
               _extruded(_round_end_wire(inner, length - wall, floor), [], height - floor))
    # a boss and its relief span the same heights: one bored ring standing on the floor
    rings = [_ring(x, y, floor, d, r, h) for x, y, d, h, r in _relieved(bosses)]
    if rings:
        tray = union(tray, *rings)
    return one_valid_solid(clean(tray), "link tray")


def _relieved(bosses) -> list[tuple[float, float, float, float, float]]:
    """Bosses ``(x, y, diameter, height[, relief])`` with their relief (0: none), checked."""
    out = [tuple(b) + (0.0,) * (5 - len(b)) for b in bosses]
    for _, _, d, _, r in out:
        if not 0 <= r < d:
            raise _internal("relief", f"{r!r} mm leaves no boss around it", f"[0, {d:.6g}) mm")
    return out


def ring_relief(outer_diameter: float, bore: float) -> float:
    """Diameter of the relief under a bearing seated by its outer ring: the ring's middle diameter,
    so the seat bears on the outer ring only and the inner ring and the shaft end run clear (by
    ``(outer_diameter - bore) / 4`` radially)."""
    return (outer_diameter + bore) / 2


def link_tray_volume(radius: float, length: float, height: float, wall: float, floor: float,
                     bosses: list[tuple[float, ...]] = ()) -> float:
    """The closed-form volume of :func:`link_tray` (mm^3)."""
    def area(r):
        return math.pi * r * r / 2 + 2 * r * (length - (radius - r))

    bosses = _relieved(bosses)
    return (area(radius) * height - area(radius - wall) * (height - floor)
            + sum(math.pi * (d * d - r * r) / 4 * h for _, _, d, h, r in bosses))


def link_cover(radius: float, wall: float, x_end: float, thickness: float,
               seats: list[tuple[float, float, float, float, float]] = ()) -> TopoDS_Shape:
    """The part of a robot link's cover over its round end, z in [0, thickness]: the tray's inner
    outline (:func:`link_tray` with ``radius``, ``wall``: a half disc of ``radius - wall`` joined
    to a rectangle) up to x = ``x_end``, so its rim bears on the tray's walls. ``seats``
    ``(x, y, diameter, depth, relief)``: a boss of ``diameter`` hanging ``depth`` below the cover
    (0: none) onto a bearing's outer ring, with a through relief bore of ``relief`` for the
    shaft and the inner ring.

    Volume ``(pi r^2 / 2 + 2 r x_end) t + sum pi/4 (d^2 depth - relief^2 (t + depth))``,
    ``r = radius - wall``, for ``x_end >= r`` (the half disc lies wholly on the x < 0 side)."""
    _positive(radius=radius, wall=wall, x_end=x_end, thickness=thickness)
    r = radius - wall
    if not r > 0:
        raise _internal("wall", "walls leave no room inside", "wall < radius")
    bores = [_circle_wire(x, y, 0.0, rl / 2, hole=True) for x, y, _, _, rl in seats if rl > 0]
    cover = _extruded(_round_end_wire(r, x_end, 0.0), bores, thickness)
    # each boss hangs below the cover, bored through with its seat's relief
    bosses = [_ring(x, y, -depth, d, rl, depth) for x, y, d, depth, rl in seats if depth > 0]
    if bosses:
        cover = union(cover, *bosses)
    return one_valid_solid(clean(cover), "link cover")


def link_cover_volume(radius: float, wall: float, x_end: float, thickness: float,
                      seats: list[tuple[float, float, float, float, float]] = ()) -> float:
    """The closed-form volume of :func:`link_cover` (mm^3)."""
    r = radius - wall
    return ((math.pi * r * r / 2 + 2 * r * x_end) * thickness
            + sum(math.pi / 4 * (d * d * depth - rl * rl * (thickness + depth)) for _, _, d, depth, rl in seats))


def quill(outer_diameter: float, length: float, bores: list[tuple[float, float, float]], lug_length: float,
          lug_width: float, lug_thickness: float) -> TopoDS_Shape:
    """A bearing quill: a non-rotating sleeve of ``outer_diameter`` on +z, z in [0, length], bored
    in steps ``bores`` ``(z0, z1, diameter)`` (apart, each inside [0, length] and thinner than the
    sleeve: bearing seats and the shoulders between them), with a lug on +x at its lower end, z in
    [0, lug_thickness], ``lug_width`` along y, reaching ``lug_length`` beyond the sleeve. The lug
    grows out of the middle of the wall, so it meets the sleeve in an area, not along an edge.

    Volume ``pi/4 (D^2 L - sum d_i^2 (z1 - z0)) + t (w (R + l) - w x0 / 2 - R^2 asin(w / 2R))``,
    ``R = D/2``, ``x0 = sqrt(R^2 - w^2/4)``: the lug's box less the part of it inside the sleeve's
    outer cylinder, for a lug whose root (inside that cylinder) clears the bores."""
    _positive(outer_diameter=outer_diameter, length=length, lug_length=lug_length, lug_width=lug_width,
              lug_thickness=lug_thickness)
    radius = outer_diameter / 2
    spans = sorted(bores)
    for (z0, z1, d), following in zip(spans, spans[1:] + [(length, length, 0.0)]):
        if not (0 <= z0 < z1 <= following[0] and 0 < d < outer_diameter):
            raise _internal("bores", f"({z0:.6g}, {z1:.6g}, {d:.6g}) mm is out of range",
                              f"apart, inside [0, {length:.6g}] mm, diameters in (0, {outer_diameter:.6g}) mm")
    if not lug_width < outer_diameter:
        raise _internal("lug_width", f"{lug_width:.6g} mm is not narrower than the sleeve", f"< {outer_diameter:.6g} mm")
    # the lug's root: the middle of the wall around the widest bore at the lug's height
    widest = max((d for z0, z1, d in spans if z0 < lug_thickness), default=0.0)
    root = (widest / 2 + radius) / 2
    # the root's corners inside the outer cylinder: the lug meets the sleeve across its whole section
    if not math.hypot(root, lug_width / 2) < radius:
        raise _internal("lug_width", f"{lug_width:.6g} mm is too wide for the sleeve's wall",
                          f"< {2 * math.sqrt(radius ** 2 - root ** 2):.6g} mm")
    solid = _cylinder(radius, length)
    solid = cut(solid, *[_cylinder(d / 2, z1 - z0, (0.0, 0.0, z0)) for z0, z1, d in spans]) if spans else solid
    lug = _box(radius + lug_length - root, lug_width, lug_thickness, (root, -lug_width / 2, 0.0))
    return one_valid_solid(clean(union(solid, lug)), "quill")


def quill_volume(outer_diameter: float, length: float, bores: list[tuple[float, float, float]], lug_length: float,
                 lug_width: float, lug_thickness: float) -> float:
    """The closed-form volume of :func:`quill` (mm^3)."""
    r, w = outer_diameter / 2, lug_width
    x0 = math.sqrt(r * r - w * w / 4)
    sleeve = math.pi / 4 * (outer_diameter ** 2 * length - sum(d * d * (z1 - z0) for z0, z1, d in bores))
    return sleeve + lug_thickness * (w * (r + lug_length) - w * x0 / 2 - r * r * math.asin(w / (2 * r)))


def split_collar(bore: float, outer_diameter: float, width: float, slot: float) -> TopoDS_Shape:
    """A clamp collar (the frictional interface of a split pinion): a ring with one radial slot
    of width ``slot`` through the wall on +x, z in [0, width].

    Volume ``pi/4 (D^2 - d^2) w - slot ((D - d)/2) w`` (to first order; the slot's ends are
    flat, the ring's curved).
    """
    ring = cylinder(outer_diameter, width, bore)
    if slot <= 0:
        return ring
    cutter = box(outer_diameter, slot, width, (0, -slot / 2, 0))
    return one_valid_solid(cut(ring, cutter), "split collar")


__all__ = ["is_valid", "one_valid_solid", "volume", "bounding_box", "solids", "translate", "compound", "cut", "intersect", "union",
           "clean", "fuse", "cylinder", "box", "box_between", "frustum", "shaft", "bearing", "bevel_pitch_cone", "servo_motor", "blade_flexure", "compression_spring", "SpringSolid",
           "coil_envelope", "plate_with_holes", "link_tray", "link_tray_volume", "link_cover",
           "link_cover_volume", "ring_relief", "quill", "quill_volume", "split_collar"]
