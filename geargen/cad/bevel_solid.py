"""Straight bevel gear solids with spherical-involute flanks (:func:`build_bevel`).

Conventions: apex at the origin, axis +z, the teeth on the pitch cone of half angle delta; tooth 0
centred on the +x half plane (azimuth 0). The toothed body lies between the toe sphere (radius
R_i = R_e - b) and the heel sphere (R_e) about the apex: the ends are spherical, not back cones,
so every other surface is a cone through the apex and the tooth's section on any sphere about
the apex is the heel's scaled (:mod:`geargen.core.bevel`). Inside the root cone the body is the
spherical shell between the two spheres (the blank's back is the heel sphere); a bore runs along
the axis.

How: the blank (revolution of the region between the spheres inside the tip cone) minus one
cutter per tooth space. A cutter is the cone through the apex over the tooth space's outline on
the heel sphere (both flanks, extended past the tip cone, and the root cone between them),
cut by two planes normal to the space's pitch direction, one inside the toe sphere and one
outside the heel sphere: its outline there is the central (gnomonic) projection of the spherical
outline, a planar curve, interpolated by a B-spline through dense exact points; the cutter is the
ruled loft between the outline and its copy scaled about the apex, so every ruling passes through
the apex and the flank is the cone over the projected curve exactly (to the interpolation error,
measured by tests/cad/test_bevel_solid.py on the solid). No root fillet: the flank meets the
root cone (or its meridian continuation below the base cone) at a sharp edge.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepBuilderAPI import (BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon,
                                BRepBuilderAPI_MakeWire, BRepBuilderAPI_Transform)
from OCP.BRepOffsetAPI import BRepOffsetAPI_ThruSections
from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakeRevol
from OCP.GC import GC_MakeArcOfCircle
from OCP.GeomAbs import GeomAbs_C2
from OCP.GeomAPI import GeomAPI_PointsToBSpline
from OCP.gp import gp_Ax1, gp_Ax2, gp_Dir, gp_Pnt, gp_Trsf
from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain
from OCP.TColgp import TColgp_Array1OfPnt
from OCP.TopTools import TopTools_ListOfShape

from geargen.cad.gear_solid import _single_solid, check_solid
from geargen.core.bevel import bevel_geometry, check_tooth, tooth_half_angle
from geargen.design.bevel import BevelGearSpec
from geargen.errors import BuildError

#: exact points per flank / root curve of a cutter outline (cubic interpolation; the flank's distance
#: from the spherical involute is measured on the solid, well under 1 um for these counts)
FLANK_POINTS = 64
ROOT_POINTS = 24
#: tolerance of the degree-7 B-spline approximation of a projected outline curve, relative to the
#: curve's distance from the apex (the cutter's far outline lies 1.05 R_e away)
APPROX_TOLERANCE = 2e-9
#: degree of those B-splines (5 intersects the blank faster than 7 at the same tolerance)
DEG_MIN, DEG_MAX = 5, 5


@dataclass
class BevelSolid:
    """A built bevel gear: the OCCT shape (one closed solid) and its spec."""

    shape: object
    name: str
    spec: BevelGearSpec
    length_unit: str
    profile: object = None  # no transverse profile: a bevel gear has no drawing/DXF

    def is_valid(self) -> bool:
        return check_solid(self.shape) is None


def _sph(polar, azimuth) -> np.ndarray:
    polar, azimuth = np.broadcast_arrays(np.asarray(polar, float), np.asarray(azimuth, float))
    return np.stack([np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)], axis=-1)


def _space_outline(spec: BevelGearSpec) -> list[np.ndarray]:
    """Unit vectors of the outline of the tooth space centred on azimuth 0 (between the teeth at
    -pi/z and +pi/z): root, (meridian), right flank rising, top, left flank falling, (meridian);
    each an ``(n, 3)`` array, consecutive pieces sharing their end points."""
    g = bevel_geometry(spec)
    depth = g.tip_cone_angle - g.root_cone_angle
    top = g.tip_cone_angle + 0.25 * depth  # past the tip cone: the blank ends the flank there
    half_pitch = math.pi / spec.teeth
    lo = g.root_cone_angle
    # cosine spacing: dense at both ends, where the flank meets the root and the tip
    u = 0.5 - 0.5 * np.cos(np.linspace(0.0, math.pi, FLANK_POINTS))
    # below the base cone the flank is the meridian at the involute's start: a separate straight piece
    start = max(lo, g.base_cone_angle)
    th = start + (top - start) * u
    width = half_pitch - tooth_half_angle(spec, th)  # half width of the space
    root_az = np.linspace(-width[0], width[0], ROOT_POINTS)
    pieces = [_sph(np.full_like(root_az, lo), root_az)]  # root, left to right
    if start > lo:
        pieces.append(_sph(np.array([lo, start]), np.full(2, width[0])))  # right meridian, rising
    pieces.append(_sph(th, width))  # right flank rising
    # the top along the circle of latitude past the tip cone (a great-circle chord would dip towards the
    # axis across a wide space and cut the teeth of gears with few teeth)
    top_az = np.linspace(width[-1], -width[-1], ROOT_POINTS)
    pieces.append(_sph(np.full_like(top_az, top), top_az))
    pieces.append(_sph(th[::-1], -width[::-1]))  # left flank falling
    if start > lo:
        pieces.append(_sph(np.array([start, lo]), np.full(2, -width[0])))  # left meridian, falling
    return pieces


def _project(points: np.ndarray, direction: np.ndarray, distance: float) -> np.ndarray:
    """Central projection from the apex onto the plane {p . direction = distance}."""
    return points * (distance / (points @ direction))[:, None]


def _interp_edge(points: np.ndarray):
    arr = TColgp_Array1OfPnt(1, len(points))
    for i, (x, y, z) in enumerate(points.tolist()):
        arr.SetValue(i + 1, gp_Pnt(x, y, z))
    scale = float(np.abs(points).max())
    approx = GeomAPI_PointsToBSpline(arr, DEG_MIN, DEG_MAX, GeomAbs_C2, APPROX_TOLERANCE * scale)
    if not approx.IsDone():
        raise BuildError("bevel cutter: B-spline approximation failed")
    return BRepBuilderAPI_MakeEdge(approx.Curve()).Edge()


def _outline_wire(pieces: list[np.ndarray], direction: np.ndarray, distance: float):
    mk = BRepBuilderAPI_MakeWire()
    projected = [_project(p, direction, distance) for p in pieces]
    for pts in projected:
        mk.Add(_interp_edge(pts) if len(pts) > 2 else BRepBuilderAPI_MakeEdge(gp_Pnt(*pts[0]), gp_Pnt(*pts[1])).Edge())
    if not mk.IsDone():
        raise BuildError("bevel cutter: outline wire not closed")
    return mk.Wire()


def _cutter(spec: BevelGearSpec):
    """The solid removed for the tooth space centred on azimuth 0."""
    g = bevel_geometry(spec)
    pieces = _space_outline(spec)
    direction = _sph(spec.pitch_cone_angle, 0.0)
    allpts = np.concatenate(pieces)
    cos_max = float((allpts @ direction).min())  # the outline's widest angle from the pitch direction
    far = g.cone_distance * 1.05  # plane outside the heel sphere (distance >= far for every ray)
    near = g.toe_cone_distance * cos_max * 0.95  # plane inside the toe sphere for every ray
    loft = BRepOffsetAPI_ThruSections(True, True, 1e-7)
    loft.AddWire(_outline_wire(pieces, direction, near))
    loft.AddWire(_outline_wire(pieces, direction, far))
    loft.CheckCompatibility(False)
    loft.Build()
    if not loft.IsDone():
        raise BuildError("bevel cutter: loft failed")
    return loft.Shape()


def _blank(spec: BevelGearSpec):
    """Solid of revolution between the toe and heel spheres inside the tip cone."""
    g = bevel_geometry(spec)
    ri, re, da = g.toe_cone_distance, g.cone_distance, g.tip_cone_angle

    def p(r, polar):
        return gp_Pnt(r * math.sin(polar), 0.0, r * math.cos(polar))

    inner = GC_MakeArcOfCircle(p(ri, 0.0), p(ri, da / 2), p(ri, da)).Value()
    outer = GC_MakeArcOfCircle(p(re, da), p(re, da / 2), p(re, 0.0)).Value()
    mk = BRepBuilderAPI_MakeWire()
    mk.Add(BRepBuilderAPI_MakeEdge(inner).Edge())
    mk.Add(BRepBuilderAPI_MakeEdge(p(ri, da), p(re, da)).Edge())
    mk.Add(BRepBuilderAPI_MakeEdge(outer).Edge())
    mk.Add(BRepBuilderAPI_MakeEdge(p(re, 0.0), p(ri, 0.0)).Edge())
    face = BRepBuilderAPI_MakeFace(mk.Wire(), True).Face()
    return BRepPrimAPI_MakeRevol(face, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2 * math.pi).Shape()


def _rotated(shape, angle: float):
    trsf = gp_Trsf()
    trsf.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), angle)
    return BRepBuilderAPI_Transform(shape, trsf, True).Shape()


def _cut(body, tools: list):
    op = BRepAlgoAPI_Cut()
    args, tool_list = TopTools_ListOfShape(), TopTools_ListOfShape()
    args.Append(body)
    for t in tools:
        tool_list.Append(t)
    op.SetArguments(args)
    op.SetTools(tool_list)
    op.Build()
    if not op.IsDone():
        raise BuildError("bevel gear: boolean cut failed")
    unify = ShapeUpgrade_UnifySameDomain(op.Shape(), True, True, False)
    unify.Build()
    return _single_solid(unify.Shape())


def build_bevel(spec: BevelGearSpec, check: bool = False) -> BevelSolid:
    """Build ``spec`` as one closed solid (conventions in the module docstring). Raises
    GeometryError for a tooth that cannot be made (:func:`geargen.core.bevel.check_tooth`)."""
    check_tooth(spec)
    cutter = _cutter(spec)
    pitch = 2 * math.pi / spec.teeth
    tools = [_rotated(cutter, pitch * (k + 0.5)) for k in range(spec.teeth)]
    if spec.bore_diameter > 0:
        ax = gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))
        tools.append(BRepPrimAPI_MakeCylinder(ax, spec.bore_diameter / 2, spec.cone_distance * 1.1).Shape())
    shape = _cut(_blank(spec), tools)
    if check:
        problem = check_solid(shape)
        if problem:
            raise BuildError(f"{spec.name}: {problem}")
    return BevelSolid(shape, spec.name, spec, spec.length_unit)


def bevel_volume(spec: BevelGearSpec) -> float:
    """The solid's volume from the tooth's solid angle (independent of the CAD kernel): Omega (R_e^3 -
    R_i^3) / 3, less the bore: the cylinder rho < r_b inside the shell is (2 pi / 3)(R^3 - (R^2 -
    r_b^2)^(3/2)) evaluated between R_i and R_e."""
    from geargen.core.bevel import gear_solid_angle
    re, ri = spec.cone_distance, spec.toe_cone_distance
    vol = gear_solid_angle(spec) * (re ** 3 - ri ** 3) / 3
    rb = spec.bore_diameter / 2
    if rb > 0:
        def cap(r):
            return 2 * math.pi / 3 * (r ** 3 - (r * r - rb * rb) ** 1.5)
        vol -= cap(re) - cap(ri)
    return vol




def flank_deviation(shape, spec: BevelGearSpec, grid: int = 12) -> np.ndarray:
    """Deviations (mm) of points sampled on the solid's flank faces from the spherical involute.

    Each B-spline face is sampled on a ``grid`` x ``grid`` parameter grid (points inside the face
    only); a point between the base (or root) and tip cones, at distance R from the apex, is
    compared, on the sphere of radius R, with the flank of its tooth: the deviation is the arc of
    the circle of latitude between the point and the flank, R sin(theta) (|phi - phi_k| - phi(theta)),
    an upper bound of its distance from the flank surface. Points of the root faces (on the root
    cone) are left out by their polar angle."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepTools import BRepTools
    from OCP.BRepTopAdaptor import BRepTopAdaptor_FClass2d
    from OCP.gp import gp_Pnt2d
    from OCP.TopAbs import TopAbs_FACE, TopAbs_IN
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    g = bevel_geometry(spec)
    lo = max(g.base_cone_angle, g.root_cone_angle) + 0.02 * (g.tip_cone_angle - g.root_cone_angle)
    hi = g.tip_cone_angle - 0.02 * (g.tip_cone_angle - g.root_cone_angle)
    pitch = 2 * math.pi / spec.teeth
    out = []
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        face = TopoDS.Face_s(exp.Current())
        exp.Next()
        surface = BRep_Tool.Surface_s(face)
        if surface.DynamicType().Name() != "Geom_BSplineSurface":
            continue
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        inside = BRepTopAdaptor_FClass2d(face, 1e-9)
        for u in np.linspace(u0, u1, grid + 2)[1:-1]:
            for v in np.linspace(v0, v1, grid + 2)[1:-1]:
                if inside.Perform(gp_Pnt2d(u, v)) != TopAbs_IN:
                    continue
                p = surface.Value(u, v)
                x, y, z = p.X(), p.Y(), p.Z()
                r = math.sqrt(x * x + y * y + z * z)
                theta = math.acos(z / r)
                if not lo <= theta <= hi:
                    continue
                phi = math.atan2(y, x)
                local = abs(phi - pitch * round(phi / pitch))  # from the nearest tooth's centre
                out.append(r * math.sin(theta) * (local - tooth_half_angle(spec, theta)))
    return np.asarray(out)


__all__ = ["BevelSolid", "build_bevel", "bevel_volume", "flank_deviation"]
