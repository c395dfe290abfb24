"""Rack solids (spur and helical) from the exact rack outline of :mod:`geargen.families.rack.geometry`.

Frame (see :class:`geargen.families.rack.spec.RackSpec`): x along the rack (0 .. length), y up from the
back face through the pitch line to the tips, z across the face width (0 .. face width).

How: the teeth are prisms along the tooth direction ``(sin beta, 0, cos beta)`` of the exact
normal-section outline (lines and circular arcs: flanks, lands, root fillets, tip arcs), so every
face is exact: the flanks and lands planes, the fillets and tip arcs cylinders, every ruling
straight along the teeth. A spur rack is the prism of the transverse section from x = 0 to the
length (both ends through a space centre, on the root land). A helical rack is cut square to
``[0, length] x [0, face width]``: it is put together face by face (:class:`_HelicalRack`: each
face of the teeth is the strip between two joints of the section clipped by that box, the four
walls carry the section's lines and ellipse arcs), with no boolean - the boolean common of a long
prism with a box it replaced took 10x longer (0.27 s against 0.025 s on the 30-tooth bench rack).
Because the length is a whole number of transverse pitches, every transverse section has the same
area, so the volume is that area times the face width (:func:`geargen.families.rack.geometry.rack_volume`,
checked by the tests and sweep).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

import numpy as np
from OCP.BRep import BRep_Builder
from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
from OCP.Geom import Geom_Circle, Geom_CylindricalSurface, Geom_Ellipse, Geom_Line, Geom_Plane
from OCP.Geom2d import Geom2d_Line
from OCP.GeomAPI import GeomAPI
from OCP.gp import gp_Ax2, gp_Ax3, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d, gp_Vec, gp_Vec2d
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import (TopoDS, TopoDS_Edge, TopoDS_Face, TopoDS_Shape, TopoDS_Solid, TopoDS_Vertex,
                        TopoDS_Wire)

from geargen.cad.gear_solid import check_solid, solid_volume
from geargen.cad.kernel import KERNEL_TOLERANCE, bspline_curve_2d, closed_solid, make_edge
from geargen.families.rack.geometry import RackOutline, rack_outline
from geargen.families.rack.spec import ZERO_SEGMENT, RackSpec
from geargen.errors import BuildError
from geargen.profile.bspline_fit import fit_function


@dataclass
class RackSolid:
    """A built rack: the OCCT shape (one closed solid), its spec and its normal-section outline."""

    shape: TopoDS_Shape
    name: str
    spec: RackSpec
    outline: RackOutline
    length_unit: str

    def volume(self) -> float:
        return solid_volume(self.shape)

    def is_valid(self) -> bool:
        return check_solid(self.shape) is None


def section_segments(spec: RackSpec, outline: RackOutline, first_space: int, last_space: int) -> list[tuple]:
    """The top of the normal section from space ``first_space``'s centre to ``last_space``'s
    (x_n, height above the back face), merged so that each land is one segment."""
    h = spec.pitch_line_height
    p = outline.pitch
    half = outline.vertices()
    n = len(half) // 2
    left, right = half[:n], half[n:]  # left: tooth centre -> space centre; right: space centre -> tooth centre
    pitch = right + [_shift(seg, p) for seg in left]  # space centre -> next space centre
    # a land or flank of zero length (a full-radius form, see RackSpec) has no edge
    shortest = ZERO_SEGMENT * spec.module * 2
    pitch = [seg for seg in pitch if seg[0] == "arc" or math.dist(seg[1], seg[2]) > shortest]
    out: list[tuple] = []
    for k in range(first_space, last_space):
        for seg in pitch:
            seg = _shift(seg, k * p)
            seg = (seg[0], (seg[1][0], seg[1][1] + h), (seg[2][0], seg[2][1] + h), *(
                [(seg[3][0], seg[3][1] + h), seg[4]] if seg[0] == "arc" else []))
            if out and seg[0] == "line" and out[-1][0] == "line" and out[-1][1][1] == out[-1][2][1] == seg[1][1] == seg[2][1]:
                out[-1] = ("line", out[-1][1], seg[2])  # a land continues across a pitch boundary
            else:
                out.append(seg)
    return out


def _shift(seg, dx):
    if seg[0] == "line":
        return ("line", (seg[1][0] + dx, seg[1][1]), (seg[2][0] + dx, seg[2][1]))
    return ("arc", (seg[1][0] + dx, seg[1][1]), (seg[2][0] + dx, seg[2][1]), (seg[3][0] + dx, seg[3][1]), seg[4])


def _section_face(spec: RackSpec, segments: list[tuple]):
    """The spur rack's section at z = 0 as a planar face (its normal -z, the outward one of the
    rack's end there), put together edge by edge (BRep_Builder): the top of the section from
    ``segments`` (lines and arcs, left to right), then down the right end, back along the back
    face, up the left end; each edge a line or the arc's exact circle."""
    builder = BRep_Builder()
    x_left, x_right = segments[0][1][0], segments[-1][2][0]
    closing = [("line", (x_right, segments[-1][2][1]), (x_right, 0.0)), ("line", (x_right, 0.0), (x_left, 0.0)),
               ("line", (x_left, 0.0), (x_left, segments[0][1][1]))]
    loop = segments + closing
    vertices = []
    for seg in loop:
        v = TopoDS_Vertex()
        builder.MakeVertex(v, gp_Pnt(seg[1][0], seg[1][1], 0.0), KERNEL_TOLERANCE)
        vertices.append(v)
    # clockwise seen from +z (the teeth on top, left to right): counter-clockwise about -z
    plane = Geom_Plane(gp_Ax3(gp_Pnt(0.0, 0.0, 0.0), gp_Dir(0.0, 0.0, -1.0), gp_Dir(1.0, 0.0, 0.0)))
    pln = plane.Pln()
    loc = TopLoc_Location()
    wire = TopoDS_Wire()
    builder.MakeWire(wire)
    for k, seg in enumerate(loop):
        v0, v1 = vertices[k], vertices[(k + 1) % len(loop)]
        (x0, y0), (x1, y1) = seg[1], seg[2]
        if seg[0] == "line":
            length = math.hypot(x1 - x0, y1 - y0)
            curve = Geom_Line(gp_Pnt(x0, y0, 0.0), gp_Dir((x1 - x0) / length, (y1 - y0) / length, 0.0))
            edge, forward = make_edge(builder, curve, v0, v1, 0.0, length), True
        else:  # the arc (less than a half circle) on its circle, angles counter-clockwise about +z
            (cx, cy), r = seg[3], seg[4]
            a0, a1 = math.atan2(y0 - cy, x0 - cx), math.atan2(y1 - cy, x1 - cx)
            if abs(a1 - a0) > math.pi:
                a1 += -2 * math.pi if a1 > a0 else 2 * math.pi
            curve = Geom_Circle(gp_Ax2(gp_Pnt(cx, cy, 0.0), gp_Dir(0.0, 0.0, 1.0), gp_Dir(1.0, 0.0, 0.0)), r)
            forward = a0 < a1
            lo, hi = min(a0, a1), max(a0, a1)
            shift = 2 * math.pi * math.floor(lo / (2 * math.pi))  # the circle's parameter runs over [0, 2 pi)
            edge = make_edge(builder, curve, v0 if forward else v1, v1 if forward else v0, lo - shift, hi - shift)
        builder.UpdateEdge(edge, GeomAPI.To2d_s(curve, pln), plane, loc, KERNEL_TOLERANCE)
        builder.Add(wire, edge.Oriented(TopAbs_FORWARD if forward else TopAbs_REVERSED))
    wire.Closed(True)
    face = TopoDS_Face()
    builder.MakeFace(face, plane, loc, KERNEL_TOLERANCE)
    builder.Add(face, wire)
    return face


def build_rack(spec: RackSpec, check: bool = False) -> RackSolid:
    """The rack's solid (see the module's note). ``check``: BuildError unless one valid closed solid."""
    outline = rack_outline(spec)
    if spec.signed_helix_angle == 0.0:
        segments = section_segments(spec, outline, 0, spec.teeth)
        shape = BRepPrimAPI_MakePrism(_section_face(spec, segments), gp_Vec(0, 0, spec.face_width)).Shape()
    else:
        shape = _HelicalRack(spec, outline).solid()
    solid = RackSolid(shape=shape, name=spec.name, spec=spec, outline=outline, length_unit=spec.length_unit)
    if check:
        problem = check_solid(shape)
        if problem:
            raise BuildError(f"rack {spec.name}: {problem}")
    return solid


# ---------------------------------------------------------------- the helical rack, face by face


def _dot(a, b) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@dataclass(frozen=True)
class _WallPoint:
    """A point of the teeth's top boundary on the box's walls (plan view ``x``, ``z``): a corner of
    the box or where a joint of the section crosses a wall; ``xn`` its normal-section coordinate."""

    x: float
    z: float
    xn: float
    wall: int  # the wall it starts (a corner) or lies on
    corner: bool
    joint: int | None  # index into _HelicalRack.joints


@dataclass
class _EdgeRecord:
    edge: TopoDS_Edge
    curve: object  # the 3-D curve (Geom_Curve)
    ends: tuple  # vertex ids at the curve's first and last parameter
    wall: int | None = None  # a top edge: its wall
    segment: int | None = None  # a top edge: its section segment
    angles: tuple[float, float] | None = None  # an arc's top edge: its range of the section angle u
    joint: int | None = None  # a joint edge: its joint


class _HelicalRack:
    """A helical rack put together face by face (BRep_Builder; no boolean, no sewing).

    Plan view (x, z): the box [0, L] x [0, b]. Every face of the teeth is the strip between two
    joints of the normal section (lines ``xn = x cos(beta) - z sin(beta)`` constant) clipped by the
    box: a plane for a line of the section, a surface of linear extrusion of the arc's transverse
    ellipse along the teeth for an arc (its ends on z = 0 and z = b are then parameter lines). The
    four walls (z = 0, x = L, z = b, x = 0, in that order around the box) are planes whose top edges
    are the section's segments carried along the teeth into the wall: lines and ellipse arcs; the
    back is the plane y = 0. Each edge is built once, with its curve on both of its faces: exact
    lines and ellipses, except on an extrusion the curves of its edges on the walls x = 0 and x = L
    (fitted 2-D splines, within 1e-9 of the section angle and the length along the teeth).
    """

    WALLS = 4
    #: the walls' outward normals, in order around the box
    NORMALS = ((0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (-1.0, 0.0, 0.0))

    def __init__(self, spec: RackSpec, outline: RackOutline):
        self.spec = spec
        beta = spec.signed_helix_angle
        self.cb, self.sb = math.cos(beta), math.sin(beta)
        self.length, self.width = spec.length, spec.face_width
        self.builder = BRep_Builder()
        self.scale = max(self.length, self.width, spec.height)
        self.corners = [(0.0, 0.0), (self.length, 0.0), (self.length, self.width), (0.0, self.width)]
        xn = [self._xn(x, z) for x, z in self.corners]
        p = outline.pitch
        self.segments = section_segments(spec, outline, math.floor(min(xn) / p) - 1, math.ceil(max(xn) / p) + 1)
        self.joints = [seg[1] for seg in self.segments[1:]]  # joint j: where segment j meets segment j + 1
        self.starts = [seg[1][0] for seg in self.segments]
        self.teeth_dir = (self.sb, 0.0, self.cb)
        self.pcurve_cache: dict[tuple, object] = {}

    # -- the section and the plan view

    def _xn(self, x: float, z: float) -> float:
        return x * self.cb - z * self.sb

    def _segment_at(self, xn: float) -> int:
        i = bisect.bisect_right(self.starts, xn) - 1
        if not 0 <= i < len(self.segments) or xn > self.segments[i][2][0]:
            raise BuildError(f"rack {self.spec.name}: no section segment at xn = {xn:g}")
        return i

    def _height(self, i: int, xn: float) -> float:
        """Height of segment ``i`` at ``xn``."""
        seg = self.segments[i]
        (x0, y0), (x1, y1) = seg[1], seg[2]
        if seg[0] == "line":
            return y0 + (y1 - y0) * (xn - x0) / (x1 - x0)
        (cx, cy), r = seg[3], seg[4]
        above = 0.5 * (y0 + y1) > cy  # a tip arc lies above its centre, a root fillet below
        return cy + (1.0 if above else -1.0) * math.sqrt(max(r * r - (xn - cx) ** 2, 0.0))

    def _wall_map(self, wall: int) -> tuple[tuple, tuple]:
        """(origin, e): the point (xn, y) of the section, carried along the teeth into the wall, is
        ``origin + xn e + (0, y, 0)`` (plain floats: a few hundred small vectors)."""
        cb, sb, L, b = self.cb, self.sb, self.length, self.width
        if wall in (0, 2):
            return (b * sb / cb if wall == 2 else 0.0, 0.0, b if wall == 2 else 0.0), (1 / cb, 0.0, 0.0)
        return (L if wall == 1 else 0.0, 0.0, L * cb / sb if wall == 1 else 0.0), (0.0, 0.0, -1 / sb)

    def _perimeter(self) -> list[_WallPoint]:
        """Corners and joint crossings around the box's top, in order (a joint through a corner is
        that corner)."""
        eps = 1e-12 * self.scale
        pts: list[_WallPoint] = []
        for wall in range(self.WALLS):
            (xa, za), (xb, zb) = self.corners[wall], self.corners[(wall + 1) % self.WALLS]
            na, nb = self._xn(xa, za), self._xn(xb, zb)
            at_corner = next((j for j, (xn, _) in enumerate(self.joints) if abs(xn - na) <= eps), None)
            pts.append(_WallPoint(xa, za, na, wall, True, at_corner))
            inside = sorted(((xn - na) / (nb - na), j) for j, (xn, _) in enumerate(self.joints)
                            if min(na, nb) + eps < xn < max(na, nb) - eps)
            pts += [_WallPoint(xa + t * (xb - xa), za + t * (zb - za), self.joints[j][0], wall, False, j)
                    for t, j in inside]
        return pts

    # -- kernel objects

    def _vertex(self, p: tuple) -> TopoDS_Vertex:
        v = TopoDS_Vertex()
        self.builder.MakeVertex(v, gp_Pnt(*p), KERNEL_TOLERANCE)
        return v

    def _line(self, p: tuple, q: tuple, ends: tuple, vertices: dict) -> _EdgeRecord:
        """A straight edge from p to q, parameter the distance from p."""
        length = math.dist(p, q)
        curve = Geom_Line(gp_Pnt(*p), gp_Dir(*((b - a) / length for a, b in zip(p, q))))
        return _EdgeRecord(make_edge(self.builder, curve, vertices[ends[0]], vertices[ends[1]], 0.0, length), curve,
                           ends)

    def _ellipse(self, wall: int, seg) -> Geom_Ellipse:
        """The wall's image of the arc of ``seg``: an ellipse whose parameter is the section's angle u."""
        origin, e = self._wall_map(wall)
        (cx, cy), r = seg[3], seg[4]
        centre = (origin[0] + cx * e[0], cy, origin[2] + cx * e[2])
        stretch = math.hypot(*e)
        x_dir = tuple(c / stretch for c in e)
        normal = (-x_dir[2], 0.0, x_dir[0])  # x_dir x (0, 1, 0): the ellipse's own y axis is then +y
        return Geom_Ellipse(gp_Ax2(gp_Pnt(*centre), gp_Dir(*normal), gp_Dir(*x_dir)), r * stretch, r)

    def _side_surface(self, seg):
        """The surface of a section segment and whether its own normal points out of the rack: a
        plane (parameters: along the segment, along the teeth) or a cylinder about the arc's axis
        (u the section angle from the xn axis, v the length along the teeth from the plane s = 0)."""
        (x0, y0), (x1, y1) = seg[1], seg[2]
        n_dir = (self.cb, 0.0, -self.sb)  # the section's xn axis
        if seg[0] == "line":
            length = math.hypot(x1 - x0, y1 - y0)
            along = ((x1 - x0) * self.cb / length, (y1 - y0) / length, -(x1 - x0) * self.sb / length)
            # teeth_dir x along: left of the segment (xn increasing), up, out of the rack
            outward = (-self.cb * along[1], self.cb * along[0] - self.sb * along[2], self.sb * along[1])
            origin = (x0 * self.cb, y0, -x0 * self.sb)
            return Geom_Plane(gp_Ax3(gp_Pnt(*origin), gp_Dir(*outward), gp_Dir(*along))), True
        (cx, cy), r = seg[3], seg[4]
        axis = gp_Ax3(gp_Pnt(cx * self.cb, cy, -cx * self.sb), gp_Dir(*self.teeth_dir), gp_Dir(*n_dir))
        # y axis: teeth_dir x n_dir = +y, so u is the section's angle; the normal points away from the
        # axis: out of a tip arc (above its centre), into a root fillet
        return Geom_CylindricalSurface(axis, r), 0.5 * (y0 + y1) > cy

    def _arc_wall_pcurve(self, record: _EdgeRecord, seg):
        """The curve on an arc's cylinder of its top edge on a wall: (u, A + B cos u) for u in the
        edge's range, v = A + B cos u the length along the teeth of the wall's point at angle u. The
        2-D spline (u, B cos u) is fitted once per B and range (the teeth repeat) and moved by A."""
        origin, e = self._wall_map(record.wall)
        (cx, _), r = seg[3], seg[4]
        along = _dot(e, self.teeth_dir)
        a, bc = _dot(origin, self.teeth_dir) + cx * along, r * along
        u0, u1 = record.angles
        key = (round(bc, 12), round(u0, 12), round(u1, 12))
        if key not in self.pcurve_cache:  # the fit's parameter s runs from 0: u = u0 + s
            fit = fit_function(lambda s: np.column_stack([u0 + s, bc * np.cos(u0 + s)]),
                               lambda s: np.column_stack([np.ones_like(s), -bc * np.sin(u0 + s)]), u1 - u0,
                               1e-3 * KERNEL_TOLERANCE)
            self.pcurve_cache[key] = bspline_curve_2d(fit.poles, fit.knots + u0, fit.mults, fit.degree)
        return self.pcurve_cache[key].Translated(gp_Vec2d(0.0, a))

    def _face(self, surface, records: list[_EdgeRecord], pcurves: list, points: dict, normal_hint: tuple,
              forward: bool) -> TopoDS_Face:
        """A face of ``surface`` bounded by ``records`` (one closed loop), each edge given its curve
        on the surface (``pcurves``; None: computed, planes only). ``normal_hint``: a direction on the
        side of the surface's own normal; ``forward``: whether that normal points out of the rack."""
        b = self.builder
        loc = TopLoc_Location()
        plane = surface.Pln() if isinstance(surface, Geom_Plane) else None
        for rec, pc in zip(records, pcurves):
            b.UpdateEdge(rec.edge, pc if pc is not None else GeomAPI.To2d_s(rec.curve, plane), surface, loc,
                         KERNEL_TOLERANCE)
        # chain the edges into a loop from vertex to vertex
        loop = [(records[0], True)]
        at = records[0].ends[1]
        rest = records[1:]
        while rest:
            k = next((k for k, r in enumerate(rest) if at in r.ends), None)
            if k is None:
                raise BuildError(f"rack {self.spec.name}: a face's edges do not close")
            rec = rest.pop(k)
            forward_edge = rec.ends[0] == at
            loop.append((rec, forward_edge))
            at = rec.ends[1] if forward_edge else rec.ends[0]
        corners = [points[r.ends[0] if fwd else r.ends[1]] for r, fwd in loop]
        hx, hy, hz = normal_hint
        area = 0.0  # twice the loop's area about normal_hint (sum of p x q . hint), plain floats: few points
        for (px, py, pz), (qx, qy, qz) in zip(corners, corners[1:] + corners[:1]):
            area += (py * qz - pz * qy) * hx + (pz * qx - px * qz) * hy + (px * qy - py * qx) * hz
        if area < 0:  # counter-clockwise about the surface's own normal
            loop = [(r, not fwd) for r, fwd in reversed(loop)]
        w = TopoDS_Wire()
        b.MakeWire(w)
        for rec, fwd in loop:
            b.Add(w, rec.edge.Oriented(TopAbs_FORWARD if fwd else TopAbs_REVERSED))
        w.Closed(True)
        face = TopoDS_Face()
        b.MakeFace(face, surface, loc, KERNEL_TOLERANCE)
        b.Add(face, w)
        return face if forward else TopoDS.Face_s(face.Reversed())

    def solid(self) -> TopoDS_Solid:
        perimeter = self._perimeter()
        n = len(perimeter)
        points, vertices = {}, {}
        for k, pt in enumerate(perimeter):
            y = (self.joints[pt.joint][1] if pt.joint is not None
                 else self._height(self._segment_at(pt.xn), pt.xn))
            points["top", k] = (pt.x, y, pt.z)
            if pt.corner:
                points["bottom", k] = (pt.x, 0.0, pt.z)
        for key, p in points.items():
            vertices[key] = self._vertex(p)
        corner_k = [k for k, pt in enumerate(perimeter) if pt.corner]

        # top edges along the walls, between neighbouring perimeter points
        tops = []
        for k in range(n):
            k1 = (k + 1) % n
            a, c = perimeter[k], perimeter[k1]
            i = self._segment_at(0.5 * (a.xn + c.xn))
            seg = self.segments[i]
            if seg[0] == "line":
                rec = self._line(points["top", k], points["top", k1], (("top", k), ("top", k1)), vertices)
            else:
                cx, cy = seg[3]
                ua = math.atan2(points["top", k][1] - cy, a.xn - cx)
                uc = math.atan2(points["top", k1][1] - cy, c.xn - cx)
                curve = self._ellipse(a.wall, seg)
                ends = (("top", k), ("top", k1)) if ua <= uc else (("top", k1), ("top", k))
                lo, hi = min(ua, uc), max(ua, uc)
                rec = _EdgeRecord(make_edge(self.builder, curve, vertices[ends[0]], vertices[ends[1]], lo, hi),
                                  curve, ends, angles=(lo, hi))
            rec.wall, rec.segment = a.wall, i
            tops.append(rec)

        # joint edges along the teeth, parameter the length along the teeth (s = p . teeth_dir)
        crossings: dict[int, list[int]] = {}
        for k, pt in enumerate(perimeter):
            if pt.joint is not None:
                crossings.setdefault(pt.joint, []).append(k)
        joints = {}
        for j, ks in crossings.items():
            if len(ks) != 2:
                continue  # a joint that only touches the box at a corner bounds no face
            ka, kc = sorted(ks, key=lambda k: perimeter[k].z)
            pa, pc = points["top", ka], points["top", kc]
            sa, sc = _dot(pa, self.teeth_dir), _dot(pc, self.teeth_dir)
            origin = tuple(a - sa * d for a, d in zip(pa, self.teeth_dir))  # the line's parameter is then s
            curve = Geom_Line(gp_Pnt(*origin), gp_Dir(*self.teeth_dir))
            edge = make_edge(self.builder, curve, vertices["top", ka], vertices["top", kc], sa, sc)
            joints[j] = _EdgeRecord(edge, curve, (("top", ka), ("top", kc)), joint=j)

        # the walls' other edges: the corners' verticals and the bottom edges
        verticals = {k: self._line(points["bottom", k], points["top", k], (("bottom", k), ("top", k)), vertices)
                     for k in corner_k}
        bottoms = [self._line(points["bottom", ka], points["bottom", kc], (("bottom", ka), ("bottom", kc)), vertices)
                   for ka, kc in zip(corner_k, corner_k[1:] + corner_k[:1])]

        up, down = (0.0, 1.0, 0.0), (0.0, -1.0, 0.0)
        faces = []
        by_segment: dict[int, list[_EdgeRecord]] = {}
        for r in tops:
            by_segment.setdefault(r.segment, []).append(r)
        for i, records in sorted(by_segment.items()):
            seg = self.segments[i]
            records += [joints[j] for j in (i - 1, i) if j in joints]
            surface, own_normal_out = self._side_surface(seg)
            if seg[0] == "line":
                pcurves = [None] * len(records)
            else:
                pcurves = []
                for r in records:
                    if r.joint is not None:  # u = the joint's section angle, v = the length along the teeth
                        (xn, y), (cx, cy) = self.joints[r.joint], seg[3]
                        pcurves.append(Geom2d_Line(gp_Pnt2d(math.atan2(y - cy, xn - cx), 0.0), gp_Dir2d(0.0, 1.0)))
                    else:
                        pcurves.append(self._arc_wall_pcurve(r, seg))
            # every side face's own normal has an upward part when it points out of the rack
            faces.append(self._face(surface, records, pcurves, points, up if own_normal_out else down, own_normal_out))
        for w in range(self.WALLS):
            ka, kc = corner_k[w], corner_k[(w + 1) % self.WALLS]
            normal = self.NORMALS[w]
            plane = Geom_Plane(gp_Pnt(*points["bottom", ka]), gp_Dir(*normal))
            records = [r for r in tops if r.wall == w] + [bottoms[w], verticals[ka], verticals[kc]]
            faces.append(self._face(plane, records, [None] * len(records), points, normal, True))
        back = Geom_Plane(gp_Pnt(0.0, 0.0, 0.0), gp_Dir(0.0, -1.0, 0.0))
        faces.append(self._face(back, bottoms, [None] * 4, points, down, True))

        return closed_solid(self.builder, faces)


def flank_straightness(solid: RackSolid, z: float, samples_per_face: int = 64) -> tuple[float, int]:
    """Largest distance (mm) of the solid's section at height ``z`` from the exact flank lines,
    over the section points on the straight flanks (away from the fillet and tip-arc tangent
    points), and the number of points measured. The exact right flank of the space centred on
    ``x_t = k p_t + z tan(beta)`` is ``|x_t - centre| = flank_x(u) / cos(beta)``; the distance is that
    difference along x times ``cos(alpha_t)``."""
    from geargen.cad.measure import section

    spec, outline = solid.spec, solid.outline
    cut = section(solid.shape, z, samples_per_face)
    pts = cut.points
    u = pts[:, 1] - spec.pitch_line_height
    span = outline.flank_tip_u - outline.flank_root_u
    on_flank = (u > outline.flank_root_u + 1e-3 * span) & (u < outline.flank_tip_u - 1e-3 * span)
    # the end faces (x = 0 and x = length) cross the flanks' heights too
    on_flank &= (pts[:, 0] > 1e-6 * spec.length) & (pts[:, 0] < (1 - 1e-6) * spec.length)
    cb = math.cos(spec.helix_angle)
    x = pts[on_flank, 0] - z * math.tan(spec.signed_helix_angle)
    pt = spec.transverse_pitch
    d = np.abs(x - pt * np.round(x / pt))
    err = (d - outline.flank_x(u[on_flank]) / cb) * math.cos(spec.transverse_pressure_angle)
    return (float(np.max(np.abs(err))) if err.size else math.nan), int(err.size)


__all__ = ["RackSolid", "build_rack", "section_segments", "flank_straightness"]
