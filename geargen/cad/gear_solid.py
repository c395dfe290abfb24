"""Gear solids from the exact profile: spur, helical (true helicoid flanks), cluster; bore, keyway, hub.

Conventions (the synthesis and assembly steps rotate and place from these):

- axis on z; the toothed face runs from z = 0 to z = face width;
- tooth 0 is centred on +x in the z = 0 section; the section at height z is the z = 0 section
  turned counter-clockwise by ``geargen.profile.section_rotation(spec, z)`` (positive for a
  right-hand helix, negative for a left-hand one);
- the keyway (if any) is centred on +x, its flat floor at ``bore_radius + keyway_depth`` (a
  cluster's too: it is one part with one bore and one keyway, whatever the small gear's phase);
- the hub (if any) is a plain cylinder on the z < 0 side, from ``-hub_length`` to 0
  (``hub_side="top"``: from the face width up);
- a cluster's large gear sits at z in [0, b_large], the small gear at
  [b_large + gap, b_large + gap + b_small]; see :mod:`geargen.design.cluster`.

How: every tooth has its own face for each flank, each fillet, the tip land and the root land
(when the rack's tip line cuts a root circle), so a CAM or inspection program can pick a flank
by itself. The lands are exact cylinders (for helical gears too: their edges are helices on
them), the ends planes, and the flanks and fillets B-spline surfaces with as few poles as their
accuracy needs: each profile segment is one clamped degree-7 B-spline on uniform knots,
parametrised by arc length, exact at its ends with the exact end tangents and least-squares
fitted in between, with as few spans as keep it within the tolerance of the exact curve
(:mod:`geargen.profile.bspline_fit`; an involute takes one to four spans, 8-15 poles, a fillet
9-12). Along the axis a spur gear's surfaces are linear (two rows of poles); a helical gear's are
the profile poles turned by a fitted rotation ``(cos kz, sin kz)``: one span of the lowest degree
within 0.02 nm at the tip over the whole face (5-8 rows), so the helicoid's error is that of the
profile fit plus at most 0.02 nm. A helical gear's poles inside a face are rounded to a 1e-8 mm
grid (:func:`_grid`: its STEP file 4-6 % smaller).

The flanks are not the ruled surfaces the involute helicoid also is (swept by the base helix's
tangents: two rows of poles, 8-10 x 2 against 8-15 x 5-8, and OCCT meshes them in 1 400 triangles
instead of 3 300 at 1 um): a ruled surface's parameter lines are its rulings, which cross the end
planes, so the face's parameter box reaches far beyond it (on the 30-tooth bench gear 43 mm above
and below a 20 mm face) and every fast bounding box of the part (BRepBndLib.Add: the poles over the
face's parameter box, what OCCT readers and geargen's contact checks use) with it.

Tooth 0's curves and surfaces are built once and turned for the other teeth; neighbouring faces
share their boundary curves, so the solid is put together edge by edge (BRep_Builder) without
sewing or booleans; a double-helical gear's second half is the first's mirror image, put together
the same way (:func:`toothed_body`). Only hubs and clusters use a boolean fuse.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepBuilderAPI import (BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire,
                                BRepBuilderAPI_Transform)
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
from OCP.Geom import Geom_Circle, Geom_CylindricalSurface, Geom_Plane
from OCP.Geom2d import Geom2d_BSplineCurve, Geom2d_Circle, Geom2d_Line
from OCP.GProp import GProp_GProps
from OCP.gp import gp_Ax1, gp_Ax2, gp_Ax2d, gp_Ax3, gp_Circ, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d, gp_Trsf, gp_Vec
from OCP.TopAbs import TopAbs_FACE, TopAbs_FORWARD, TopAbs_REVERSED, TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import (TopoDS, TopoDS_Edge, TopoDS_Face, TopoDS_Shape, TopoDS_Vertex,
                        TopoDS_Wire)

from geargen.cad.kernel import (KERNEL_TOLERANCE, ORIGIN_2D, Z_AXIS, bspline_curve_2d, bspline_curve_3d, closed_solid,
                                bspline_surface, fused_solid, make_edge, make_vertex, make_wire, volume)
from geargen.design.cluster import ClusterSpec
from geargen.design.gear import GearSpec
from geargen.errors import BuildError
from geargen.profile.bspline_fit import SplineFit, fit_rotation, fit_segment, greville
from geargen.profile.tessellate import cluster_layers, gear_layers
from geargen.profile.tooth import ToothProfile, tooth_profile, twist_rate

#: default interpolation tolerance of the splines (mm): 0.002 um, or 2e-6 normal modules if smaller
#: (see :func:`default_tolerance`)
DEFAULT_TOLERANCE = 2e-6


@dataclass
class GearSolid:
    """A built gear: the OCCT shape (one closed solid) and what it was built from.

    ``profile`` is the exact outline of the (first) gear; ``tolerance`` the largest distance of
    the flank splines from the exact involute (mm) that the builder allowed.
    """

    shape: TopoDS_Shape
    name: str
    spec: GearSpec | ClusterSpec
    profile: ToothProfile
    tolerance: float
    length_unit: str
    layers: list = field(default_factory=list)  # geargen.profile.tessellate layers, for STL
    faces: tuple = ()  # ToothFace per face of one tooth's pitch sector, in outline order (not for clusters)

    def volume(self) -> float:
        return solid_volume(self.shape)

    def is_valid(self) -> bool:
        return check_solid(self.shape) is None

    def to_cadquery(self):
        """The shape as a ``cadquery.Solid`` (imports cadquery, ~1 s the first time)."""
        import cadquery as cq
        return cq.Solid(self.shape)


# ---------------------------------------------------------------- tooth 0's curves, the axial basis


@dataclass(frozen=True)
class ToothFace:
    """One face of tooth 0's pitch sector (every tooth has the same faces, turned):
    ``kind`` ``involute``/``fillet`` (a B-spline surface), ``tip_arc``/``root_arc`` (a cylinder);
    ``side`` ``upper``/``lower`` for flanks and fillets; ``poles`` (along the profile, along the
    axis), 0 for a cylinder; ``max_error`` (mm) the measured distance of the profile spline from
    the exact curve at the same parameter (0 for a cylinder)."""

    kind: str
    side: str
    poles: tuple[int, int]
    max_error: float


@dataclass(frozen=True)
class _Curve:
    """One segment of tooth 0's pitch sector for the kernel: a fitted B-spline (``fit``) for a
    flank or fillet, parameter 0 .. fit.length; or an exact circle of ``radius`` for a land,
    parameter = polar angle, ``angles`` increasing."""

    kind: str
    side: str
    end: np.ndarray
    fit: SplineFit | None = None
    radius: float = 0.0
    angles: tuple[float, float] = (0.0, 0.0)

    @property
    def range(self) -> tuple[float, float]:
        return (0.0, self.fit.length) if self.fit is not None else self.angles


@dataclass(frozen=True)
class _Axial:
    """The z direction of the side surfaces: a B-spline basis (``degree``, ``knots``, ``mults``)
    and per pole the approximate rotation ``(c, s)`` and height ``z``, so that a profile pole p
    becomes the row ``(c p_x - s p_y, s p_x + c p_y, z)``. Spur: degree 1, no rotation.
    ``error`` bounds ``|R_approx(z) - R(z)|`` (unitless) over the face."""

    degree: int
    knots: np.ndarray
    mults: tuple[int, ...]
    c: np.ndarray
    s: np.ndarray
    z: np.ndarray
    error: float

    def rows(self, points: np.ndarray) -> np.ndarray:
        """``(n, m, 3)`` poles: profile points ``(n, 2)`` turned and lifted per axial pole."""
        x, y = points[:, 0:1], points[:, 1:2]
        px, py = self.c * x - self.s * y, self.s * x + self.c * y
        return np.stack([px, py, np.broadcast_to(self.z, px.shape)], axis=-1)


def default_tolerance(spec: GearSpec) -> float:
    """:data:`DEFAULT_TOLERANCE`, scaled down with the module below 1 mm (so the relative
    accuracy of small gears - volume, thickness - is as good as that of large ones)."""
    return DEFAULT_TOLERANCE * min(1.0, spec.module)


def _tooth_curves(profile: ToothProfile, tolerance: float) -> list[_Curve]:
    """Tooth 0's pitch sector, counter-clockwise: lower fillet, lower flank, tip land, upper
    flank, upper fillet[, root land to tooth 1]; one curve (and face) each. Fitted neighbours
    share their joint point bit for bit."""
    out: list[_Curve] = []
    for s in profile.pitch_segments():
        if s.kind in ("tip_arc", "root_arc"):
            out.append(_Curve(s.kind, s.side, s.end, radius=s.curve.radius, angles=(s.t0, s.t1)))
        else:
            try:
                fit = fit_segment(s, tolerance, by_length=True)
            except ValueError:
                # a fillet whose speed grows steeply toward its end (a trochoid near its cusp) fits in
                # its own parameter where the arc-length map needs too many spans (64: 20 spans on the
                # m 18, x -0.5 sweep case of seed 4187320065)
                try:
                    fit = fit_segment(s, tolerance)
                except ValueError as exc:
                    raise BuildError(f"{profile.spec.name}: {s.side} {s.kind}: {exc}") from exc
            out.append(_Curve(s.kind, s.side, fit.poles[-1], fit=fit))
    for prev, cur in zip(out[:-1], out[1:]):
        if prev.fit is not None and cur.fit is not None:
            cur.fit.poles[0] = prev.fit.poles[-1]
    return out


def _axial(spec: GearSpec, tolerance: float) -> _Axial:
    """The axial basis: degree 1 for a spur gear; for a helical gear the rotation fitted over the
    face to ``tolerance`` (unitless, see :func:`geargen.profile.bspline_fit.fit_rotation`)."""
    length = spec.face_width
    if not spec.is_helical:
        # two rows of poles: a Geom_SurfaceOfLinearExtrusion of the same curve is exact too and
        # makes the 112-tooth STEP 15 % smaller, but OCCT re-tessellates it at 1 um 4x slower
        # (945 912 triangles in 10.8 s against 21 500 in 2.4 s; bench/bench_step.py --worker)
        return _Axial(1, np.array([0.0, length]), (2, 2), np.ones(2), np.zeros(2), np.array([0.0, length]), 0.0)
    fit = fit_rotation(twist_rate(spec), length, tolerance, degree=None)
    return _Axial(fit.degree, fit.knots, fit.mults, fit.poles[:, 0], fit.poles[:, 1], greville(fit), fit.max_error)


def _joints(profile: ToothProfile, ends: np.ndarray) -> np.ndarray:
    """End points ``(z * n, 2)`` of every curve of the whole gear, in outline order."""
    a = profile.pitch_angle * np.arange(profile.teeth)
    c, s = np.cos(a)[:, None], np.sin(a)[:, None]
    return np.stack([c * ends[:, 0] - s * ends[:, 1], s * ends[:, 0] + c * ends[:, 1]], axis=-1).reshape(-1, 2)


def _line2d(u: float, v: float, du: float, dv: float) -> Geom2d_Line:
    """A unit-speed pcurve line from (u, v) along the unit vector (du, dv)."""
    return Geom2d_Line(gp_Pnt2d(u, v), gp_Dir2d(du, dv))


def _helix_pcurve(angle: float, twist: float, length: float) -> Geom2d_BSplineCurve:
    """The pcurve (u = angle + twist z / length, v = z) of a helix on a cylinder, parameter z."""
    poles = np.array([[angle, 0.0], [angle + twist, length]])
    return bspline_curve_2d(poles, [0.0, length], [2, 2], 1)


# ---------------------------------------------------------------- edges, wires, faces


def _bore_wire(spec: GearSpec, z: float = 0.0, keyway_angle: float = 0.0) -> TopoDS_Wire | None:
    """The bore (with keyway) as a clockwise wire (seen from +z) at height ``z``, or None; the
    keyway centred on +x turned counter-clockwise by ``keyway_angle`` (rad)."""
    hub = spec.hub
    if hub.bore_diameter <= 0:
        return None
    rb = hub.bore_diameter / 2
    ax = gp_Ax2(gp_Pnt(0, 0, z), gp_Dir(0, 0, -1), gp_Dir(1, 0, 0))  # -z normal: clockwise seen from +z
    if hub.keyway_width <= 0:
        edge = BRepBuilderAPI_MakeEdge(gp_Circ(ax, rb)).Edge()
        return BRepBuilderAPI_MakeWire(edge).Wire()
    w2 = hub.keyway_width / 2
    xk = math.sqrt(rb * rb - w2 * w2)
    xf = rb + hub.keyway_depth
    a = math.asin(w2 / rb)
    # clockwise: from (xk, -w2) around the bore (through -x) to (xk, w2), then out along the keyway.
    # On the -z circle the parameter angle t maps to the point (cos t, -sin t).
    arc = BRepBuilderAPI_MakeEdge(Geom_Circle(gp_Circ(ax, rb)), a, 2 * math.pi - a).Edge()
    pts = [gp_Pnt(xk, w2, z), gp_Pnt(xf, w2, z), gp_Pnt(xf, -w2, z), gp_Pnt(xk, -w2, z)]
    mk = BRepBuilderAPI_MakeWire()
    mk.Add(arc)
    for p, q in zip(pts[:-1], pts[1:]):
        mk.Add(BRepBuilderAPI_MakeEdge(p, q).Edge())
    if not mk.IsDone():
        raise BuildError("keyway wire could not be closed")
    if keyway_angle == 0.0:
        return mk.Wire()
    turn = gp_Trsf()
    turn.SetRotation(Z_AXIS, keyway_angle)
    return TopoDS.Wire_s(_transform(mk.Wire(), turn))


def _transform(shape: TopoDS_Shape, trsf: gp_Trsf) -> TopoDS_Shape:
    return BRepBuilderAPI_Transform(shape, trsf, False).Shape()


# ---------------------------------------------------------------- the toothed body


def _turned(points: np.ndarray, angle, grid: float = 0.0, interior: int | None = None,
            fine: float = 0.0) -> np.ndarray:
    """``points`` (..., 2 or 3) turned counter-clockwise by ``angle`` about the axis (an array of
    angles: one copy each, stacked first), then put on the ``grid`` (:func:`_grid`). With
    ``interior``, the points at both ends along that axis of ``points`` (the poles an edge passes
    through, which neighbouring faces share) go on the ``fine`` grid (:func:`_fine_grid`), as the
    vertices and helices do."""
    angle = np.asarray(angle, dtype=float)
    c, s = np.cos(angle)[..., None], np.sin(angle)[..., None]
    flat = points.reshape(-1, points.shape[-1])
    out = np.broadcast_to(flat, angle.shape + flat.shape).copy()
    out[..., 0], out[..., 1] = c * flat[:, 0] - s * flat[:, 1], s * flat[:, 0] + c * flat[:, 1]
    out = out.reshape(angle.shape + points.shape)
    if grid and interior is None:
        out = np.round(out / grid) * grid
    elif grid:
        ends, inside = [slice(None)] * out.ndim, [slice(None)] * out.ndim
        ends[angle.ndim + interior], inside[angle.ndim + interior] = [0, -1], slice(1, -1)
        out[tuple(ends)] = np.round(out[tuple(ends)] / fine) * fine
        out[tuple(inside)] = np.round(out[tuple(inside)] / grid) * grid
    return out


def _fine_grid(spec: GearSpec, grid: float) -> float:
    """The grid of the poles an edge passes through, the helices and the vertices of a helical gear:
    a tenth of :func:`_grid`, at most 0.025 nm (a power of ten in the file's unit): they stay within
    a tenth of the edge tolerance of the exact land cylinders and circles."""
    unit = 25.4 if spec.length_unit == "in" else 1.0
    return min(0.1 * grid, unit * 10.0 ** math.floor(math.log10(2.5e-8 / unit)))


def _grid(spec: GearSpec, tolerance: float) -> float:
    """The spacing (mm) the spline poles inside a face are rounded to: the largest power of ten in
    the file's length unit (mm or inch) within 0.057 x ``tolerance`` (1e-7 mm at the default 2 nm),
    so rounding moves a surface by at most 0.05 x the tolerance (a B-spline stays within its
    poles' moves). Only the poles no edge passes through are rounded (:func:`_turned`), so the
    faces still meet edge for edge. A STEP file writes each coordinate to 12 decimals, trailing
    zeros dropped: on the grid 5 digits fewer."""
    unit = 25.4 if spec.length_unit == "in" else 1.0
    return unit * 10.0 ** math.floor(math.log10(0.057 * tolerance / unit))


@dataclass(frozen=True)
class _Side:
    """Tooth 0's geometry of one side face and how to turn it to another tooth.

    A spline face (fillet, flank): ``surface`` (poles ``(n, m, 3)``, u basis, v basis), whose first
    and last rows of poles are its bottom and top edges' curves, ``basis`` their u basis; a land:
    ``land`` (cylinder, bottom circle, top circle, cap circles) of tooth 0.
    ``pcurves``: the edges' curves on the face (bottom, top, start, end), the same for every tooth.
    """

    pcurves: tuple
    surface: tuple | None = None
    basis: tuple | None = None
    land: tuple | None = None

    def instances(self, angles: np.ndarray, grid: float, fine: float, twist: float) -> list[tuple]:
        """(surface, bottom curve, top curve, their curves on the end planes) of the tooth turned by
        each of ``angles``; the top plane's frame is turned by ``twist``. Without a ``grid`` (a spur
        gear: its files are small already) tooth 0's kernel objects turned, with one each tooth's
        poles turned and put on the grid."""
        if self.land is not None or not grid:
            base = self.land if self.land is not None else self.built(twist, np.zeros(1), 0.0)[0]
            out = [base]
            surf, bottom, top, (cap, cap_top) = base
            for angle in angles[1:]:
                out.append((surf.Rotated(Z_AXIS, angle), bottom.Rotated(Z_AXIS, angle), top.Rotated(Z_AXIS, angle),
                            (cap.Rotated(ORIGIN_2D, angle), cap_top.Rotated(ORIGIN_2D, angle))))
            return out
        return self.built(twist, angles, grid, fine)

    def built(self, twist: float, angles: np.ndarray, grid: float, fine: float = 0.0) -> list[tuple]:
        """The spline face's kernel objects turned by each of ``angles`` (see :meth:`instances`)."""
        poles, (uk, um, ud), (vk, vm, vd) = self.surface
        # the poles the face's edges pass through (its first and last columns) stay exact; its edge
        # curves at the ends are its first and last rows of poles: the same numbers
        z_ends = poles[:, [0, -1], 2]
        poles = _turned(poles, angles, grid, interior=0, fine=fine)
        poles[:, :, [0, -1], 2] = z_ends  # the end rows stay in the end planes
        bottoms, tops = poles[:, :, 0, :], poles[:, :, -1, :]
        tops_xy = _turned(tops[..., :2], -twist) if twist else tops[..., :2]  # in the top plane's frame
        return [(bspline_surface(p, uk, um, ud, vk, vm, vd), bspline_curve_3d(b, *self.basis),
                 bspline_curve_3d(t, *self.basis),
                 (bspline_curve_2d(b[:, :2], *self.basis), bspline_curve_2d(t_xy, *self.basis)))
                for p, b, t, t_xy in zip(poles, bottoms, tops, tops_xy)]


def _side(curve: _Curve, axial: _Axial, length: float) -> _Side:
    """Tooth 0's geometry of one curve (:class:`_Side`)."""
    twist = math.atan2(axial.s[-1], axial.c[-1])
    c_top, s_top = float(axial.c[-1]), float(axial.s[-1])
    if curve.fit is not None:
        fit = curve.fit
        poles = axial.rows(fit.poles)
        u0, u1 = curve.range
        pcurves = (_line2d(0.0, 0.0, 1.0, 0.0), _line2d(0.0, length, 1.0, 0.0),
                   _line2d(u0, 0.0, 0.0, 1.0), _line2d(u1, 0.0, 0.0, 1.0))
        basis = (fit.knots, fit.mults, fit.degree)
        return _Side(pcurves, (poles, basis, (axial.knots, axial.mults, axial.degree)), basis)
    # a land: the exact cylinder, circles at both ends, helices (lines u = angle + twist z / L)
    r = curve.radius
    surf = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)), r)
    bottom = Geom_Circle(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)), r)
    top = Geom_Circle(gp_Ax2(gp_Pnt(0, 0, length), gp_Dir(0, 0, 1), gp_Dir(c_top, s_top, 0.0)), r)
    cap = Geom2d_Circle(gp_Ax2d(ORIGIN_2D, gp_Dir2d(1, 0)), r)
    a0, a1 = curve.angles
    pcurves = (_line2d(0.0, 0.0, 1.0, 0.0), _line2d(twist, length, 1.0, 0.0),
               _helix_pcurve(a0, twist, length), _helix_pcurve(a1, twist, length))
    return _Side(pcurves, land=(surf, bottom, top, (cap, cap)))


def toothed_body(spec: GearSpec, profile: ToothProfile, tolerance: float,
                 mirror: tuple[float, float] | None = None,
                 keyway_angle: float = 0.0) -> tuple[TopoDS_Shape, list[ToothFace]]:
    """The gear body (teeth, bore, keyway; no hub) put together face by face, and tooth 0's faces.

    Side faces: one per curve of :func:`_tooth_curves` per tooth; a flank or fillet is the
    profile spline's poles turned row by row by the axial basis (:class:`_Axial`), a land an exact
    cylinder. 90 % of ``tolerance`` goes to the profile fit, 5 % to the rotation (at most 0.02 nm,
    a fifth of the edge tolerance, so helices stay on the land cylinders) and 5 % to the grid the
    poles inside a helical gear's face are rounded to (:func:`_grid`).

    ``mirror`` (gap, groove radius): a double-helical gear whose first half is ``spec`` (z in [0, h]):
    the second half is the first's mirror image in the plane z = h + gap / 2, every face and edge
    of it mirrored (a mirror turns the helix's hand and keeps the sections), sharing the first
    half's edges at z = h when there is no gap; with a gap the blank between the halves is the
    groove cylinder of that radius between two annular end faces. The bore runs through, its
    keyway turned by ``keyway_angle`` (:func:`_bore_wire`).
    """
    builder = BRep_Builder()
    length = spec.face_width
    curves = _tooth_curves(profile, 0.9 * tolerance)
    reach = max(float(np.max(np.hypot(*c.fit.poles.T))) for c in curves if c.fit is not None)
    reach = max(reach, profile.tip_radius)
    # the helices (the axial basis's) within a fifth of the edge tolerance of the exact ones on the
    # land cylinders, and within 5 % of the stated tolerance (the profile fit has 90 %, the grid of
    # the poles the last 5 %: _grid)
    axial = _axial(spec, min(0.05 * tolerance, 0.2 * KERNEL_TOLERANCE) / reach)
    c_top, s_top = float(axial.c[-1]), float(axial.s[-1])
    n = len(curves)
    grid = _grid(spec, tolerance) if spec.is_helical else 0.0
    fine = _fine_grid(spec, grid) if grid else 0.0
    joints = _joints(profile, np.array([c.end for c in curves]))

    # vertices at both ends of every joint and the joint's helix (straight line on a spur gear):
    # a spur gear's tooth 0 built once, the others turned copies
    helices = [axial.rows(c.end[None, :])[0] for c in curves]
    if grid:  # a helical gear: each tooth's helices turned and on the fine grid (_turned), as the faces' edges
        turned = [_turned(h, profile.pitch_angle * np.arange(profile.teeth), fine) for h in helices]
        helix_c = [bspline_curve_3d(turned[j][tooth], axial.knots, axial.mults, axial.degree)
                   for tooth, j in (divmod(i, n) for i in range(len(joints)))]
        bottom, top = (_turned(np.column_stack([joints, np.full(len(joints), z)]), 0.0, fine)
                       for z in (0.0, length))
        top = _turned(top, math.atan2(s_top, c_top), fine)
    else:
        base = [bspline_curve_3d(h, axial.knots, axial.mults, axial.degree) for h in helices]
        helix_c = [base[j].Rotated(Z_AXIS, tooth * profile.pitch_angle) if tooth else base[j]
                   for tooth, j in (divmod(i, n) for i in range(len(joints)))]
        bottom = np.column_stack([joints, np.zeros(len(joints))])
        top = np.column_stack([c_top * joints[:, 0] - s_top * joints[:, 1], s_top * joints[:, 0] + c_top * joints[:, 1],
                               np.full(len(joints), length)])
    bottom_v = [make_vertex(builder, *p) for p in bottom.tolist()]
    top_v = [make_vertex(builder, *p) for p in top.tolist()]

    loc = TopLoc_Location()
    tol = KERNEL_TOLERANCE
    canon = [_side(c, axial, length) for c in curves]
    angles = profile.pitch_angle * np.arange(profile.teeth)
    per_tooth = [c.instances(angles, grid, fine, math.atan2(s_top, c_top)) for c in canon]
    # per face of the first half: (surface, bottom curve, top curve, its curves on the caps, its range)
    sides = [(*per_tooth[j][tooth], curves[j].range) for tooth, j in (divmod(i, n) for i in range(len(joints)))]

    def half(surfaces, bottoms, tops, helix_curves, vb, vt, reverse):
        """One half's side faces: ``bottoms``/``tops`` the 3-D curves of the edges at parameter
        v = 0 and v = length of the surfaces (None: already built, given as edges in ``tops``)."""
        faces, edges_b, edges_t = [], [], []
        helix_e = [make_edge(builder, c, vb[i], vt[i], 0.0, length) for i, c in enumerate(helix_curves)]
        for i, surf in enumerate(surfaces):
            j = i % n
            pc_bottom, pc_top, pc_start, pc_end = canon[j].pcurves
            u0, u1 = sides[i][4]
            eb = make_edge(builder, bottoms[i], vb[i - 1], vb[i], u0, u1)
            et = tops[i] if isinstance(tops[i], TopoDS_Edge) else make_edge(builder, tops[i], vt[i - 1], vt[i], u0, u1)
            builder.UpdateEdge(eb, pc_bottom, surf, loc, tol)
            builder.UpdateEdge(et, pc_top, surf, loc, tol)
            # the joint helices: this face's end and the next face's start
            builder.UpdateEdge(helix_e[i], pc_end, surf, loc, tol)
            builder.UpdateEdge(helix_e[i - 1], pc_start, surf, loc, tol)
            face = TopoDS_Face()
            builder.MakeFace(face, surf, loc, tol)
            builder.Add(face, make_wire(builder, [eb, helix_e[i], et, helix_e[i - 1]],
                                        [TopAbs_FORWARD, TopAbs_FORWARD, TopAbs_REVERSED, TopAbs_REVERSED]))
            faces.append(face.Reversed() if reverse else face)
            edges_b.append(eb)
            edges_t.append(et)
        return faces, edges_b, edges_t

    faces, bottom_edges, top_edges = half([x[0] for x in sides], [x[1] for x in sides], [x[2] for x in sides],
                                          helix_c, bottom_v, top_v, False)
    caps = []  # (plane, outer edges with their curves on it, z of the plane, inner wire or None, turn over)

    def plane_at(z, twisted):
        if twisted:  # the frame of the section at z = length: its curves are tooth 0's caps
            return Geom_Plane(gp_Ax3(gp_Pnt(0, 0, z), gp_Dir(0, 0, 1), gp_Dir(c_top, s_top, 0)))
        return Geom_Plane(gp_Pnt(0, 0, z), gp_Dir(0, 0, 1))

    # (plane, edges, z, faces +z, [hole]); the edges' curves on the plane: index 0 the bottom
    # edges' (untwisted frame), 1 the top edges' (the frame turned by the twist)
    caps.append((plane_at(0.0, False), bottom_edges, 0.0, False))  # the bottom, turned over to face -z
    far, far_edges = length, None
    extra = []
    if mirror is None:
        caps.append((plane_at(length, True), top_edges, length, True))
    else:
        gap, groove = mirror
        far = 2 * length + gap
        plane = _mirror_ax2(far)
        # the second half: every curve, surface and vertex mirrored; v = 0 is now its far end z = far
        vb2 = [make_vertex(builder, *_mirror_point(v, far)) for v in bottom_v]
        vt2 = top_v if gap == 0 else [make_vertex(builder, *_mirror_point(v, far)) for v in top_v]
        tops2 = top_edges if gap == 0 else [x[2].Mirrored(plane) for x in sides]
        faces2, far_edges, near_edges = half([x[0].Mirrored(plane) for x in sides], [x[1].Mirrored(plane) for x in sides],
                                             tops2, [c.Mirrored(plane) for c in helix_c], vb2, vt2, True)
        faces += faces2
        caps.append((plane_at(far, False), far_edges, far, True))
        if gap > 0:
            # the groove between the halves: a cylinder from z = length up by gap, and the halves'
            # inner ends as annuli around it
            circle = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, length), gp_Dir(0, 0, 1)), groove)).Edge()
            prism = BRepPrimAPI_MakePrism(circle, gp_Vec(0, 0, gap), True)
            ring_low = BRepBuilderAPI_MakeWire(TopoDS.Edge_s(prism.FirstShape())).Wire()
            ring_high = BRepBuilderAPI_MakeWire(TopoDS.Edge_s(prism.LastShape())).Wire()
            caps.append((plane_at(length, True), top_edges, length, True, ring_low))
            caps.append((plane_at(length + gap, True), near_edges, length + gap, False, ring_high))
            extra.append(_outward_face(prism.Shape()))

    # caps: faces of +z normal (outer wire counter-clockwise, holes clockwise), those facing -z turned over
    bore_faces, bores = [], {}
    bore0 = _bore_wire(spec, 0.0, keyway_angle)
    if bore0 is not None:
        prism = BRepPrimAPI_MakePrism(bore0, gp_Vec(0, 0, far), True)
        bores = {0.0: TopoDS.Wire_s(prism.FirstShape()), far: TopoDS.Wire_s(prism.LastShape())}
        exp = TopExp_Explorer(prism.Shape(), TopAbs_FACE)
        while exp.More():
            bore_faces.append(exp.Current().Reversed())
            exp.Next()
    cap_faces = []
    for plane, edges, z, up, *ring in caps:
        which = 0 if edges is bottom_edges or edges is far_edges else 1
        for i, e in enumerate(edges):
            builder.UpdateEdge(e, sides[i][3][which], plane, loc, tol)
        face = TopoDS_Face()
        builder.MakeFace(face, plane, loc, tol)
        builder.Add(face, make_wire(builder, edges))
        hole = ring[0].Reversed() if ring else bores.get(z)
        if hole is not None:
            builder.Add(face, hole)
        cap_faces.append(face if up else face.Reversed())

    solid = closed_solid(builder, faces + cap_faces + bore_faces + extra)
    info = [ToothFace(c.kind, c.side, (len(c.fit.poles), len(axial.z)) if c.fit is not None else (0, 0),
                      c.fit.max_error if c.fit is not None else 0.0) for c in curves]
    return solid, info


def _mirror_ax2(far: float) -> gp_Ax2:
    """The plane z = far / 2, which mirrors [0, far] onto itself."""
    return gp_Ax2(gp_Pnt(0, 0, far / 2), gp_Dir(0, 0, 1))


def _mirror_point(vertex: TopoDS_Vertex, far: float) -> tuple[float, float, float]:
    p = BRep_Tool.Pnt_s(vertex)
    return p.X(), p.Y(), far - p.Z()


def _outward_face(shape: TopoDS_Shape) -> TopoDS_Shape:
    """The one face of ``shape`` (an edge swept into a cylinder), oriented with its normal away
    from the axis."""
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    face = TopoDS.Face_s(exp.Current())
    ad = BRepAdaptor_Surface(face)
    u, v = ad.FirstUParameter(), 0.5 * (ad.FirstVParameter() + ad.LastVParameter())
    p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
    ad.D1(u, v, p, du, dv)
    normal = du.Crossed(dv)
    if face.Orientation() == TopAbs_REVERSED:
        normal.Reverse()
    return face if normal.X() * p.X() + normal.Y() * p.Y() > 0 else face.Reversed()


def hub_body(spec: GearSpec, side: str, keyway_angle: float = 0.0) -> TopoDS_Shape | None:
    hub = spec.hub
    if hub.hub_length <= 0:
        return None
    z0 = -hub.hub_length if side == "bottom" else spec.face_width
    outer_edge = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, z0), gp_Dir(0, 0, 1)), hub.hub_diameter / 2)).Edge()
    mk = BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(outer_edge).Wire(), True)
    bore = _bore_wire(spec, z0, keyway_angle)
    if bore is not None:
        mk.Add(bore)
    return BRepPrimAPI_MakePrism(mk.Face(), gp_Vec(0, 0, hub.hub_length), True).Shape()


def _fuse(shapes: list[TopoDS_Shape]) -> TopoDS_Shape:
    return fused_solid(shapes, "boolean fuse failed", fuzzy=0.0)


# ---------------------------------------------------------------- public API


def check_solid(shape: TopoDS_Shape) -> str | None:
    """None if ``shape`` is one valid closed solid (BRepCheck), else what is wrong."""
    exp = TopExp_Explorer(shape, TopAbs_SOLID)
    count = 0
    while exp.More():
        count += 1
        exp.Next()
    if count != 1:
        return f"{count} solids"
    if not BRepCheck_Analyzer(shape).IsValid():
        return "BRepCheck_Analyzer: invalid"
    if volume(shape) <= 0:  # the sign is all that is needed here: quick rule
        return "non-positive volume (inside out)"
    return None


def solid_volume(shape: TopoDS_Shape, eps: float = 1e-9) -> float:
    """Volume (mm^3) by Gauss-Kronrod integration per B-spline span to relative accuracy ``eps``.

    (OCCT's default ``VolumeProperties``, which other readers call, agrees within ~1e-8 on the
    face-per-segment solids: tests/cad/test_gear_solid.py.)
    """
    props = GProp_GProps()
    BRepGProp.VolumePropertiesGK_s(shape, props, eps, True, True, False, False, True)
    return props.Mass()


def build_body(spec: GearSpec, tolerance: float | None = None, profile: ToothProfile | None = None,
               hub_side: str = "bottom", keyway_angle: float = 0.0) -> TopoDS_Shape:
    """The solid of one gear (with bore, keyway and hub) as an OCCT shape; see the module docstring.
    ``keyway_angle`` (rad): the keyway turned counter-clockwise from +x, the teeth not."""
    if tolerance is None:
        tolerance = default_tolerance(spec)
    return _body_and_faces(spec, tolerance, profile, hub_side, keyway_angle)[0]


def _body_and_faces(spec: GearSpec, tolerance: float | None, profile: ToothProfile | None,
                    hub_side: str, keyway_angle: float = 0.0) -> tuple[TopoDS_Shape, list[ToothFace]]:
    if tolerance is None:
        tolerance = default_tolerance(spec)
    if profile is None:
        profile = tooth_profile(spec)
    body, faces = toothed_body(spec, profile, tolerance, keyway_angle=keyway_angle)
    hub = hub_body(spec, hub_side, keyway_angle)
    if hub is not None:
        body = _fuse([body, hub])
    return body, faces


def build_gear(spec: GearSpec, tolerance: float | None = None, check: bool = False,
               hub_side: str = "bottom") -> GearSolid:
    """Build ``spec`` as one closed solid (conventions in the module docstring).

    ``tolerance`` (mm, default :func:`default_tolerance`) bounds the distance of every spline
    (flanks, fillets; for a helical gear both directions of its side surfaces together) from
    the exact surface.
    With ``check``, the solid is validated (BRepCheck, one solid, positive volume) and a
    :class:`BuildError` raised if it fails. Raises :class:`GeometryError` for parameters that
    cannot make a gear (see :func:`geargen.profile.tooth_profile`).
    """
    if tolerance is None:
        tolerance = default_tolerance(spec)
    profile = tooth_profile(spec)
    shape, faces = _body_and_faces(spec, tolerance, profile, hub_side)
    if check:
        problem = check_solid(shape)
        if problem:
            raise BuildError(f"{spec.name}: {problem}")
    return GearSolid(shape, spec.name, spec, profile, tolerance, spec.length_unit,
                     gear_layers(spec, profile, hub_side), tuple(faces))


def build_cluster(cluster: ClusterSpec, tolerance: float | None = None, check: bool = False) -> GearSolid:
    """Build a cluster gear: large gear at z in [0, b_L], spacer, small gear above it, one solid.

    The small gear's teeth are turned by ``cluster.relative_phase`` counter-clockwise (its tooth 0
    at its own lowest face against the large gear's tooth 0 at z = 0); the bore runs through
    both, its one keyway on +x (the small gear's built turned back by the phase).
    """
    large, small = cluster.large, cluster.small
    if tolerance is None:
        tolerance = min(default_tolerance(large), default_tolerance(small))
    large_profile, small_profile = tooth_profile(large), tooth_profile(small)
    large_body = build_body(large, tolerance, large_profile, hub_side="bottom")
    small_body = build_body(small, tolerance, small_profile, hub_side="top", keyway_angle=-cluster.relative_phase)
    z_small = large.face_width + cluster.axial_gap
    trsf = gp_Trsf()
    trsf.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), cluster.relative_phase)
    move = gp_Trsf()
    move.SetTranslation(gp_Vec(0, 0, z_small))
    small_body = _transform(small_body, move.Multiplied(trsf))
    parts = [large_body, small_body]
    if cluster.axial_gap > 0:
        edge = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, large.face_width), gp_Dir(0, 0, 1)),
                                               cluster.spacer_diameter_resolved / 2)).Edge()
        mk = BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(edge).Wire(), True)
        bore = _bore_wire(large, large.face_width)
        if bore is not None:
            mk.Add(bore)
        parts.append(BRepPrimAPI_MakePrism(mk.Face(), gp_Vec(0, 0, cluster.axial_gap), True).Shape())
    shape = _fuse(parts)
    if check:
        problem = check_solid(shape)
        if problem:
            raise BuildError(f"{cluster.name}: {problem}")
    return GearSolid(shape, cluster.name, cluster, large_profile, tolerance, large.length_unit,
                     cluster_layers(cluster, large_profile, small_profile))


__all__ = ["GearSolid", "ToothFace", "build_gear", "build_body", "build_cluster", "check_solid", "solid_volume",
           "default_tolerance", "DEFAULT_TOLERANCE"]
