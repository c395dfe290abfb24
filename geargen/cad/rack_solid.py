"""Rack solids (spur and helical) from the exact rack outline of :mod:`geargen.core.rack`.

Frame (see :class:`geargen.design.rack.RackSpec`): x along the rack (0 .. length), y up from the
back face through the pitch line to the tips, z across the face width (0 .. face width).

How: the teeth are prisms along the tooth direction, so the rack is one prism of its exact
normal-section outline (lines and circular arcs: flanks, lands, root fillets, tip arcs) along
the tooth direction ``(sin beta, 0, cos beta)``. Its faces are exact: the flanks and lands
planes, the fillets and tip arcs cylinders (surfaces of linear extrusion of circles), every
ruling straight along the teeth. A spur rack is the prism of the transverse section from x = 0 to
the length (both ends through a space centre, on the root land); a helical rack's prism is made
long enough and then cut square to ``[0, length] x [0, face width]`` by one boolean common with a
box (which leaves the back face untouched: the box reaches below it). Because the length is a whole
number of transverse pitches, every transverse section has the same area, so the volume is that
area times the face width (:func:`geargen.core.rack.rack_volume`, checked by the tests and sweep).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakePrism
from OCP.GC import GC_MakeArcOfCircle
from OCP.gp import gp_Pnt, gp_Vec
from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain
from OCP.TopoDS import TopoDS_Shape

from geargen.cad.gear_solid import _single_solid, check_solid, solid_volume
from geargen.core.rack import RackOutline, rack_outline
from geargen.design.rack import ZERO_SEGMENT, RackSpec
from geargen.errors import BuildError


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


def _section_face(spec: RackSpec, segments: list[tuple], beta: float, s0: float):
    """The planar face of the normal section through ``s0`` along the tooth direction: 2D
    ``(x_n, y)`` maps to ``x_n (cos b, 0, -sin b) + y (0, 1, 0) + s0 (sin b, 0, cos b)``."""
    cb, sb = math.cos(beta), math.sin(beta)

    def P(xn, y):
        return gp_Pnt(xn * cb + s0 * sb, y, -xn * sb + s0 * cb)

    wire = BRepBuilderAPI_MakeWire()
    x_left, x_right = segments[0][1][0], segments[-1][2][0]
    closing = [("line", (x_right, segments[-1][2][1]), (x_right, 0.0)), ("line", (x_right, 0.0), (x_left, 0.0)),
               ("line", (x_left, 0.0), (x_left, segments[0][1][1]))]
    for seg in segments + closing:
        a, b = P(*seg[1]), P(*seg[2])
        if seg[0] == "line":
            edge = BRepBuilderAPI_MakeEdge(a, b).Edge()
        else:  # through the arc's middle point (the arcs are less than a half circle)
            (x0, y0), (x1, y1), (cx, cy), r = seg[1], seg[2], seg[3], seg[4]
            a0, a1 = math.atan2(y0 - cy, x0 - cx), math.atan2(y1 - cy, x1 - cx)
            if a1 - a0 > math.pi:
                a1 -= 2 * math.pi
            elif a0 - a1 > math.pi:
                a1 += 2 * math.pi
            am = 0.5 * (a0 + a1)
            edge = BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(a, P(cx + r * math.cos(am), cy + r * math.sin(am)),
                                                              b).Value()).Edge()
        wire.Add(edge)
    if not wire.IsDone():
        raise BuildError(f"rack {spec.name}: the section outline does not close")
    face = BRepBuilderAPI_MakeFace(wire.Wire(), True)
    if not face.IsDone():
        raise BuildError(f"rack {spec.name}: no planar face from the section outline")
    return face.Face()


def build_rack(spec: RackSpec, check: bool = False) -> RackSolid:
    """The rack's solid (see the module's note). ``check``: BuildError unless one valid closed solid."""
    outline = rack_outline(spec)
    beta = spec.signed_helix_angle
    b, length = spec.face_width, spec.length
    if beta == 0.0:
        segments = section_segments(spec, outline, 0, spec.teeth)
        shape = BRepPrimAPI_MakePrism(_section_face(spec, segments, 0.0, 0.0), gp_Vec(0, 0, b)).Shape()
    else:
        cb, sb = math.cos(beta), math.sin(beta)
        corners = [(x, z) for x in (0.0, length) for z in (0.0, b)]
        xn = [x * cb - z * sb for x, z in corners]  # normal-section coordinate of the box's corners
        s = [x * sb + z * cb for x, z in corners]  # coordinate along the teeth
        p = outline.pitch
        first, last = math.floor(min(xn) / p) - 1, math.ceil(max(xn) / p) + 1
        margin = p
        segments = section_segments(spec, outline, first, last)
        face = _section_face(spec, segments, beta, min(s) - margin)
        along = max(s) - min(s) + 2 * margin
        prism = BRepPrimAPI_MakePrism(face, gp_Vec(along * sb, 0.0, along * cb)).Shape()
        box = BRepPrimAPI_MakeBox(gp_Pnt(0.0, -1.0, 0.0), gp_Pnt(length, spec.height + 1.0, b)).Shape()
        common = BRepAlgoAPI_Common(prism, box)
        if not common.IsDone():
            raise BuildError(f"rack {spec.name}: the boolean cutting the helical rack to length failed")
        unify = ShapeUpgrade_UnifySameDomain(common.Shape(), True, True, True)
        unify.Build()
        shape = _single_solid(unify.Shape())
    solid = RackSolid(shape=shape, name=spec.name, spec=spec, outline=outline, length_unit=spec.length_unit)
    if check:
        problem = check_solid(shape)
        if problem:
            raise BuildError(f"rack {spec.name}: {problem}")
    return solid


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
