"""Gear solids from the exact profile: spur, helical (true helicoid flanks), cluster; bore, keyway, hub.

Conventions (the synthesis and assembly steps rotate and place from these):

- axis on z; the toothed face runs from z = 0 to z = face width;
- tooth 0 is centred on +x in the z = 0 section; the section at height z is the z = 0 section
  turned counter-clockwise by ``geargen.profile.section_rotation(spec, z)`` (positive for a
  right-hand helix, negative for a left-hand one);
- the keyway (if any) is centred on +x, its flat floor at ``bore_radius + keyway_depth``;
- the hub (if any) is a plain cylinder on the z < 0 side, from ``-hub_length`` to 0
  (``hub_side="top"``: from the face width up);
- a cluster's large gear sits at z in [0, b_large], the small gear at
  [b_large + gap, b_large + gap + b_small]; see :mod:`geargen.design.cluster`.

How: the outline is split into two kinds of edge per tooth - the tip arc, and one chain through
the gap (upper flank, fillet, root arc, next tooth's fillet and flank; cut in two where an
undercut makes a corner). Each analytic segment becomes cubic B-spline pieces interpolating
exact points with exact derivatives at nodes chosen by
:func:`geargen.profile.hermite.hermite_nodes` so that the spline stays within ``tolerance`` of
the exact curve; pieces join C1 where the outline is tangent-continuous. Tooth 0's curves and
surfaces are built once and turned for the other teeth. A spur gear is one planar face (the bore
and keyway an inner wire of it, the tip arcs exact circles) extruded once. A helical gear's side
faces are bicubic B-spline surfaces interpolating exact helicoid points, first derivatives and
twist vectors (the same tolerance split between the profile and the axial direction);
neighbouring faces share their boundary curves, so the solid is put together edge by edge
(BRep_Builder) without sewing or booleans. Only hubs and clusters use a boolean fuse.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from OCP.BRep import BRep_Builder
from OCP.BRepAlgoAPI import BRepAlgoAPI_Fuse
from OCP.BRepBuilderAPI import (BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire,
                                BRepBuilderAPI_Transform)
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface, Geom_Circle, Geom_Plane
from OCP.Geom2d import Geom2d_BSplineCurve, Geom2d_Line
from OCP.GProp import GProp_GProps
from OCP.gp import gp_Ax1, gp_Ax2, gp_Ax3, gp_Circ, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d, gp_Trsf, gp_Vec
from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain
from OCP.TColgp import TColgp_Array1OfPnt, TColgp_Array1OfPnt2d, TColgp_Array2OfPnt
from OCP.TColStd import TColStd_Array1OfInteger, TColStd_Array1OfReal
from OCP.TopAbs import TopAbs_FACE, TopAbs_FORWARD, TopAbs_REVERSED, TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import (TopoDS, TopoDS_Edge, TopoDS_Face, TopoDS_Shape, TopoDS_Shell, TopoDS_Solid, TopoDS_Vertex,
                        TopoDS_Wire)

from geargen.design.cluster import ClusterSpec
from geargen.design.gear import GearSpec
from geargen.errors import BuildError
from geargen.profile.hermite import hermite_knots as _hermite_knots
from geargen.profile.hermite import hermite_nodes
from geargen.profile.hermite import hermite_poles as _hermite_poles
from geargen.profile.segments import Segment
from geargen.profile.tessellate import cluster_layers, gear_layers
from geargen.profile.tooth import ToothProfile, tooth_profile, twist_rate

#: default interpolation tolerance of the splines (mm): 0.002 um, or 2e-6 normal modules if smaller
#: (see :func:`default_tolerance`)
DEFAULT_TOLERANCE = 2e-6
#: edge/vertex tolerance given to the kernel (mm)
KERNEL_TOLERANCE = 1e-7


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

    def volume(self) -> float:
        return solid_volume(self.shape)

    def is_valid(self) -> bool:
        return check_solid(self.shape) is None

    def to_cadquery(self):
        """The shape as a ``cadquery.Solid`` (imports cadquery, ~1 s the first time)."""
        import cadquery as cq
        return cq.Solid(self.shape)


# ---------------------------------------------------------------- discretised profile pieces


@dataclass
class _Piece:
    """One edge of the outline for the kernel: a chain of analytic segments (``parts``), each
    given by knots ``tau`` (increasing from 0), exact points and derivatives d/dtau (``(n, 2)``);
    or an exact circle (``radius`` > 0, polar ``angles``). The spline is C1 inside a segment
    (knot multiplicity 2) and C0 at the joints between segments (multiplicity 3)."""

    parts: list
    radius: float = 0.0
    angles: tuple[float, float] = (0.0, 0.0)

    @property
    def start(self) -> np.ndarray:
        return self.parts[0][1][0]

    @property
    def end(self) -> np.ndarray:
        return self.parts[-1][1][-1]

    @property
    def length(self) -> float:
        return float(sum(p[0][-1] for p in self.parts))

    def rotated(self, angle: float) -> "_Piece":
        c, s = math.cos(angle), math.sin(angle)
        rot = np.array([[c, s], [-s, c]])
        return _Piece([(t, x @ rot, d @ rot) for t, x, d in self.parts], self.radius,
                      (self.angles[0] + angle, self.angles[1] + angle))

    def _smooth_joints(self) -> list[bool]:
        """Per joint between consecutive parts: is the chain tangent-continuous there?"""
        out = []
        for (_, _, d0), (_, _, d1) in zip(self.parts[:-1], self.parts[1:]):
            a, b = d0[-1], d1[0]
            cross = abs(a[0] * b[1] - a[1] * b[0])
            out.append(float(a @ b) > 0 and cross <= 1e-9 * float(np.linalg.norm(a) * np.linalg.norm(b)))
        return out

    def knots(self):
        values, mults, offset = [0.0], [4], 0.0
        for (tau, _, _), smooth in zip(self.parts, self._smooth_joints() + [False]):
            values.extend((offset + tau[1:]).tolist())
            mults.extend([2] * (len(tau) - 2) + [2 if smooth else 3])
            offset += tau[-1]
        mults[-1] = 4
        return np.array(values), mults

    def poles(self, transform=None) -> np.ndarray:
        """Cubic B-spline poles along the chain (axis 0) of ``transform(points, derivs)`` (values
        and d/dtau of any trailing shape; default: the planar points themselves)."""
        out = []
        smooth = [False] + self._smooth_joints()
        for i, (tau, x, d) in enumerate(self.parts):
            v, dv = (x, d) if transform is None else transform(x, d)
            hp = _hermite_poles(v, dv, tau)
            if i > 0:
                hp = hp[1:]
                if smooth[i]:  # C1 joint (knot multiplicity 2): the joint point is implied
                    out[-1] = out[-1][:-1]
            out.append(hp)
        return np.concatenate(out)

    def split_at_corners(self) -> list["_Piece"]:
        """The chain cut where it is not tangent-continuous (an undercut's corner): every edge
        (and face) is then at least C1, which the kernel's integrators need to be accurate."""
        out, current = [], [self.parts[0]]
        for part, smooth in zip(self.parts[1:], self._smooth_joints()):
            if not smooth:
                out.append(_Piece(current))
                current = []
            current.append(part)
        return out + [_Piece(current)]

    def c1_scaled(self) -> "_Piece":
        """The same chain with each part's parameter scaled so that the derivative is continuous
        across tangent-continuous joints (so those joints can be C1 knots)."""
        parts = [self.parts[0]]
        for tau, x, d in self.parts[1:]:
            prev = parts[-1][2][-1]
            scale = float(np.linalg.norm(d[0]) / np.linalg.norm(prev)) if np.linalg.norm(prev) > 0 else 1.0
            parts.append((tau * scale, x, d / scale))
        return _Piece(parts, self.radius, self.angles)


def default_tolerance(spec: GearSpec) -> float:
    """:data:`DEFAULT_TOLERANCE`, scaled down with the module below 1 mm (so the relative
    accuracy of small gears - volume, thickness - is as good as that of large ones)."""
    return DEFAULT_TOLERANCE * min(1.0, spec.module)


def _part(segment: Segment, tolerance: float):
    params = hermite_nodes(segment, tolerance)
    sign = 1.0 if segment.t1 >= segment.t0 else -1.0
    return (np.abs(params - params[0]), segment.point(params), segment.derivative(params) * sign)


def _tooth_pieces(profile: ToothProfile, tolerance: float, exact_arcs: bool) -> list[_Piece]:
    """Tooth 0's edges, counter-clockwise: the tip arc (an exact circle with ``exact_arcs``) and
    the chain through the gap to tooth 1 (upper flank, upper fillet, root arc, tooth 1's lower
    fillet and lower flank), cut where it has a corner (undercut). The gear is these pieces
    turned by whole pitches; joints inside the tooth are made bit-identical."""
    segs = profile.pitch_segments()  # lower fillet, lower flank, tip, upper flank, upper fillet[, root]
    parts = [_part(s, tolerance) for s in segs]
    i_tip = [s.kind for s in segs].index("tip_arc")
    tip = segs[i_tip]
    lower, upper = _Piece(parts[:i_tip]), _Piece(parts[i_tip + 1:])
    tip_piece = _Piece([parts[i_tip]], tip.curve.radius if exact_arcs else 0.0, (tip.t0, tip.t1))
    gap = _Piece(upper.parts + lower.rotated(profile.pitch_angle).parts)
    pieces = [tip_piece] + [p.c1_scaled() for p in gap.split_at_corners()]
    flat = [part for piece in pieces for part in piece.parts]
    for i in range(1, len(flat)):
        flat[i][1][0] = flat[i - 1][1][-1]
    return pieces


def _joints(profile: ToothProfile, pieces: list[_Piece]) -> np.ndarray:
    """End points ``(z * n, 2)`` of every piece of the whole gear, in outline order."""
    ends = np.array([p.end for p in pieces])
    a = profile.pitch_angle * np.arange(profile.teeth)
    c, s = np.cos(a)[:, None], np.sin(a)[:, None]
    return np.stack([c * ends[:, 0] - s * ends[:, 1], s * ends[:, 0] + c * ends[:, 1]], axis=-1).reshape(-1, 2)


_Z_AXIS = gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))
_ORIGIN_2D = gp_Pnt2d(0, 0)


def _occ_knots(knots):
    values, mults = knots
    k = TColStd_Array1OfReal(1, len(values))
    m = TColStd_Array1OfInteger(1, len(values))
    for i, (t, mult) in enumerate(zip(values, mults)):
        k.SetValue(i + 1, float(t))
        m.SetValue(i + 1, int(mult))
    return k, m


def _bspline3d(poles: np.ndarray, knots) -> Geom_BSplineCurve:
    arr = TColgp_Array1OfPnt(1, len(poles))
    for i, (x, y, z) in enumerate(poles.tolist()):
        arr.SetValue(i + 1, gp_Pnt(x, y, z))
    return Geom_BSplineCurve(arr, *_occ_knots(knots), 3)


def _bspline2d(poles: np.ndarray, knots) -> Geom2d_BSplineCurve:
    arr = TColgp_Array1OfPnt2d(1, len(poles))
    for i, (x, y) in enumerate(poles.tolist()):
        arr.SetValue(i + 1, gp_Pnt2d(x, y))
    return Geom2d_BSplineCurve(arr, *_occ_knots(knots), 3)


def _bspline_surface(poles: np.ndarray, knots_u, knots_v) -> Geom_BSplineSurface:
    nu, nv = poles.shape[:2]
    arr = TColgp_Array2OfPnt(1, nu, 1, nv)
    for i, row in enumerate(poles.tolist()):
        for j, (x, y, z) in enumerate(row):
            arr.SetValue(i + 1, j + 1, gp_Pnt(x, y, z))
    ku, mu = _occ_knots(knots_u)
    kv, mv = _occ_knots(knots_v)
    return Geom_BSplineSurface(arr, ku, kv, mu, mv, 3, 3)


# ---------------------------------------------------------------- edges, wires, faces


def _vertex(builder: BRep_Builder, x: float, y: float, z: float) -> TopoDS_Vertex:
    v = TopoDS_Vertex()
    builder.MakeVertex(v, gp_Pnt(x, y, z), KERNEL_TOLERANCE)
    return v


def _edge(builder: BRep_Builder, curve, v0, v1, p0: float, p1: float) -> TopoDS_Edge:
    e = TopoDS_Edge()
    builder.MakeEdge(e, curve, KERNEL_TOLERANCE)
    builder.Add(e, v0.Oriented(TopAbs_FORWARD))
    builder.Add(e, v1.Oriented(TopAbs_REVERSED))
    builder.Range(e, p0, p1)
    return e


def _planar_edges(builder: BRep_Builder, profile: ToothProfile, pieces: list[_Piece]) -> list[TopoDS_Edge]:
    """The closed outline at z = 0 as edges (tooth 0's curves built once, turned per tooth)."""
    joints = _joints(profile, pieces)
    verts = [_vertex(builder, x, y, 0.0) for x, y in joints]
    curves = []
    for p in pieces:
        if p.radius > 0:
            curves.append((Geom_Circle(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)), p.radius),
                           p.angles[0], p.angles[1]))
        else:
            poles = p.poles()
            curves.append((_bspline3d(np.column_stack([poles, np.zeros(len(poles))]), p.knots()), 0.0, p.length))
    edges = []
    for k in range(profile.teeth):
        angle = k * profile.pitch_angle
        for j, (curve, t0, t1) in enumerate(curves):
            i = k * len(pieces) + j
            c = curve.Rotated(_Z_AXIS, angle) if k else curve
            edges.append(_edge(builder, c, verts[i - 1], verts[i], t0, t1))
    return edges


def _wire(builder: BRep_Builder, edges, orientations=None) -> TopoDS_Wire:
    w = TopoDS_Wire()
    builder.MakeWire(w)
    for i, e in enumerate(edges):
        builder.Add(w, e if orientations is None else e.Oriented(orientations[i]))
    w.Closed(True)
    return w


def _bore_wire(spec: GearSpec, z: float = 0.0) -> TopoDS_Wire | None:
    """The bore (with keyway) as a clockwise wire (seen from +z) at height ``z``, or None."""
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
    return mk.Wire()


def _transform(shape: TopoDS_Shape, trsf: gp_Trsf) -> TopoDS_Shape:
    return BRepBuilderAPI_Transform(shape, trsf, False).Shape()


# ---------------------------------------------------------------- spur and helical bodies


def _spur_body(spec: GearSpec, profile: ToothProfile, tolerance: float) -> TopoDS_Shape:
    builder = BRep_Builder()
    pieces = _tooth_pieces(profile, tolerance, exact_arcs=True)
    outer = _wire(builder, _planar_edges(builder, profile, pieces))
    mk = BRepBuilderAPI_MakeFace(Geom_Plane(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), outer, True)
    bore = _bore_wire(spec)
    if bore is not None:
        mk.Add(bore)
    if not mk.IsDone():
        raise BuildError(f"{spec.name}: planar face of the outline failed")
    prism = BRepPrimAPI_MakePrism(mk.Face(), gp_Vec(0, 0, spec.face_width), True)
    return prism.Shape()


def _helical_body(spec: GearSpec, profile: ToothProfile, tolerance: float) -> TopoDS_Shape:
    builder = BRep_Builder()
    length = spec.face_width
    k = twist_rate(spec)  # rad/mm; the helicoid closure below reads it
    pieces = _tooth_pieces(profile, tolerance / 2, exact_arcs=False)
    # z nodes: Hermite of a rotation about the axis, error ~ R (k h)^4 / 384 at the tip radius
    ztol = tolerance / 2
    step = (384.0 * ztol / profile.tip_radius) ** 0.25 / abs(k)
    nz = max(1, int(math.ceil(length / step)))
    zeta = np.linspace(0.0, length, nz + 1)
    angles = k * zeta
    cz, sz = np.cos(angles), np.sin(angles)

    def helicoid(points: np.ndarray, derivs: np.ndarray):
        """P, P_u, P_z, P_uz on the grid (nodes x z-nodes x 3) for planar points/derivs at z=0."""
        x, y = points[:, 0:1], points[:, 1:2]
        dx, dy = derivs[:, 0:1], derivs[:, 1:2]
        px, py = cz * x - sz * y, sz * x + cz * y
        ux, uy = cz * dx - sz * dy, sz * dx + cz * dy
        shape = px.shape
        p = np.stack([px, py, np.broadcast_to(zeta, shape)], axis=-1)
        pu = np.stack([ux, uy, np.zeros(shape)], axis=-1)
        pz = np.stack([-k * py, k * px, np.ones(shape)], axis=-1)
        puz = np.stack([-k * uy, k * ux, np.zeros(shape)], axis=-1)
        return p, pu, pz, puz

    npc = len(pieces)
    zknots = _hermite_knots(zeta)
    joints = _joints(profile, pieces)
    # joints j (end of piece j of the whole outline): bottom and top vertex and the helix edge;
    # the helix edges of tooth 0 are built, the others turned copies
    bottom_v, top_v, helix_e = [], [], []
    helices = []
    for p in pieces:
        pts, _, dz, _ = helicoid(p.end[None, :], np.zeros((1, 2)))
        helices.append(_bspline3d(_hermite_poles(pts[0], dz[0], zeta), zknots))
    turn_top = gp_Trsf()
    turn_top.SetRotation(_Z_AXIS, angles[-1])
    for i, (x, y) in enumerate(joints):
        tooth, j = divmod(i, npc)
        vb = _vertex(builder, x, y, 0.0)
        top = gp_Pnt(x, y, length).Transformed(turn_top)
        vt = _vertex(builder, top.X(), top.Y(), top.Z())
        curve = helices[j].Rotated(_Z_AXIS, tooth * profile.pitch_angle) if tooth else helices[j]
        bottom_v.append(vb)
        top_v.append(vt)
        helix_e.append(_edge(builder, curve, vb, vt, 0.0, length))

    top_plane = Geom_Plane(gp_Ax3(gp_Pnt(0, 0, length), gp_Dir(0, 0, 1), gp_Dir(cz[-1], sz[-1], 0)))
    bottom_plane = Geom_Plane(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))
    loc = TopLoc_Location()
    tol = KERNEL_TOLERANCE
    # tooth 0's side surfaces, bottom and top curves and plane pcurves, built once
    canon = []
    for p in pieces:
        uknots = p.knots()
        q = p.poles(lambda x, d: helicoid(x, d)[0:2])
        qz = p.poles(lambda x, d: helicoid(x, d)[2:4])
        poles = _hermite_poles(np.swapaxes(q, 0, 1), np.swapaxes(qz, 0, 1), zeta)
        planar = p.poles()
        canon.append((_bspline_surface(np.swapaxes(poles, 0, 1), uknots, zknots),
                      _bspline3d(np.column_stack([planar, np.zeros(len(planar))]), uknots),
                      _bspline3d(q[:, -1, :], uknots), _bspline2d(planar, uknots), p.length))
    faces, bottom_edges, top_edges = [], [], []
    for i in range(len(joints)):
        tooth, j = divmod(i, npc)
        surf, bottom, top, c2d, u1 = canon[j]
        if tooth:
            angle = tooth * profile.pitch_angle
            surf, bottom, top = (g.Rotated(_Z_AXIS, angle) for g in (surf, bottom, top))
            c2d = c2d.Rotated(_ORIGIN_2D, angle)
        eb = _edge(builder, bottom, bottom_v[i - 1], bottom_v[i], 0.0, u1)
        et = _edge(builder, top, top_v[i - 1], top_v[i], 0.0, u1)
        builder.UpdateEdge(eb, Geom2d_Line(gp_Pnt2d(0, 0), gp_Dir2d(1, 0)), surf, loc, tol)
        builder.UpdateEdge(eb, c2d, bottom_plane, loc, tol)
        builder.UpdateEdge(et, Geom2d_Line(gp_Pnt2d(0, length), gp_Dir2d(1, 0)), surf, loc, tol)
        builder.UpdateEdge(et, c2d, top_plane, loc, tol)
        # the helix edges: pcurves u = u1 on this face (end) and u = 0 on the next one (start)
        builder.UpdateEdge(helix_e[i], Geom2d_Line(gp_Pnt2d(u1, 0), gp_Dir2d(0, 1)), surf, loc, tol)
        builder.UpdateEdge(helix_e[i - 1], Geom2d_Line(gp_Pnt2d(0, 0), gp_Dir2d(0, 1)), surf, loc, tol)
        face = TopoDS_Face()
        builder.MakeFace(face, surf, loc, tol)
        builder.Add(face, _wire(builder, [eb, helix_e[i], et, helix_e[i - 1]],
                                [TopAbs_FORWARD, TopAbs_FORWARD, TopAbs_REVERSED, TopAbs_REVERSED]))
        faces.append(face)
        bottom_edges.append(eb)
        top_edges.append(et)

    # caps: the top cap is a face of +z normal (outer wire counter-clockwise); the bottom cap
    # is the same construction at z = 0, reversed
    bore0 = _bore_wire(spec, 0.0)
    bore_faces = []
    bore1 = None
    if bore0 is not None:
        prism = BRepPrimAPI_MakePrism(bore0, gp_Vec(0, 0, length), True)
        bore0 = TopoDS.Wire_s(prism.FirstShape())  # the prism's copy, whose edges its faces share
        bore1 = TopoDS.Wire_s(prism.LastShape())
        exp = TopExp_Explorer(prism.Shape(), TopAbs_FACE)
        while exp.More():
            bore_faces.append(exp.Current().Reversed())
            exp.Next()
    caps = []
    for plane, edges, hole in ((bottom_plane, bottom_edges, bore0), (top_plane, top_edges, bore1)):
        face = TopoDS_Face()
        builder.MakeFace(face, plane, loc, tol)
        builder.Add(face, _wire(builder, edges))
        if hole is not None:
            builder.Add(face, hole)
        caps.append(face)
    caps[0] = caps[0].Reversed()

    shell = TopoDS_Shell()
    builder.MakeShell(shell)
    for f in faces + caps + bore_faces:
        builder.Add(shell, f)
    shell.Closed(True)
    solid = TopoDS_Solid()
    builder.MakeSolid(solid)
    builder.Add(solid, shell)
    return solid


def _hub_body(spec: GearSpec, side: str) -> TopoDS_Shape | None:
    hub = spec.hub
    if hub.hub_length <= 0:
        return None
    z0 = -hub.hub_length if side == "bottom" else spec.face_width
    outer_edge = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, z0), gp_Dir(0, 0, 1)), hub.hub_diameter / 2)).Edge()
    mk = BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(outer_edge).Wire(), True)
    bore = _bore_wire(spec, z0)
    if bore is not None:
        mk.Add(bore)
    return BRepPrimAPI_MakePrism(mk.Face(), gp_Vec(0, 0, hub.hub_length), True).Shape()


def _fuse(shapes: list[TopoDS_Shape]) -> TopoDS_Shape:
    from OCP.TopTools import TopTools_ListOfShape
    op = BRepAlgoAPI_Fuse()
    args, tools = TopTools_ListOfShape(), TopTools_ListOfShape()
    args.Append(shapes[0])
    for s in shapes[1:]:
        tools.Append(s)
    op.SetArguments(args)
    op.SetTools(tools)
    op.SetFuzzyValue(0.0)
    op.Build()
    if not op.IsDone():
        raise BuildError("boolean fuse failed")
    unify = ShapeUpgrade_UnifySameDomain(op.Shape(), True, True, False)
    unify.Build()
    return _single_solid(unify.Shape())


def _single_solid(shape: TopoDS_Shape) -> TopoDS_Shape:
    exp = TopExp_Explorer(shape, TopAbs_SOLID)
    solids = []
    while exp.More():
        solids.append(exp.Current())
        exp.Next()
    if len(solids) != 1:
        raise BuildError(f"expected one solid, got {len(solids)}")
    return TopoDS.Solid_s(solids[0])


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
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)  # the sign is all that is needed here: quick rule
    if props.Mass() <= 0:
        return "non-positive volume (inside out)"
    return None


def solid_volume(shape: TopoDS_Shape, eps: float = 1e-9) -> float:
    """Volume (mm^3) by Gauss-Kronrod integration per B-spline span to relative accuracy ``eps``.

    (OCCT's plain adaptive ``VolumeProperties`` scatters by ~1e-5 relative on these shapes.)
    """
    props = GProp_GProps()
    BRepGProp.VolumePropertiesGK_s(shape, props, eps, True, True, False, False, True)
    return props.Mass()


def build_body(spec: GearSpec, tolerance: float | None = None, profile: ToothProfile | None = None,
               hub_side: str = "bottom") -> TopoDS_Shape:
    """The solid of one gear (with bore, keyway and hub) as an OCCT shape; see the module docstring."""
    if tolerance is None:
        tolerance = default_tolerance(spec)
    if profile is None:
        profile = tooth_profile(spec)
    body = _helical_body(spec, profile, tolerance) if spec.is_helical else _spur_body(spec, profile, tolerance)
    hub = _hub_body(spec, hub_side)
    if hub is not None:
        body = _fuse([body, hub])
    return body


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
    shape = build_body(spec, tolerance, profile, hub_side)
    if check:
        problem = check_solid(shape)
        if problem:
            raise BuildError(f"{spec.name}: {problem}")
    return GearSolid(shape, spec.name, spec, profile, tolerance, spec.length_unit,
                     gear_layers(spec, profile, hub_side))


def build_cluster(cluster: ClusterSpec, tolerance: float | None = None, check: bool = False) -> GearSolid:
    """Build a cluster gear: large gear at z in [0, b_L], spacer, small gear above it, one solid.

    The small gear is turned by ``cluster.relative_phase`` counter-clockwise (its tooth 0 at
    its own lowest face against the large gear's tooth 0 at z = 0); the bore runs through both.
    """
    large, small = cluster.large, cluster.small
    if tolerance is None:
        tolerance = min(default_tolerance(large), default_tolerance(small))
    large_profile, small_profile = tooth_profile(large), tooth_profile(small)
    large_body = build_body(large, tolerance, large_profile, hub_side="bottom")
    small_body = build_body(small, tolerance, small_profile, hub_side="top")
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


__all__ = ["GearSolid", "build_gear", "build_body", "build_cluster", "check_solid", "solid_volume",
           "default_tolerance", "DEFAULT_TOLERANCE"]
