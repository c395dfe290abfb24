"""Straight bevel gear solids with spherical-involute flanks (:func:`build_bevel`).

Conventions: apex at the origin, axis +z, the teeth on the pitch cone of half angle delta; tooth 0
centred on the +x half plane (azimuth 0). The toothed body lies between the toe sphere (radius
R_i = R_e - b) and the heel sphere (R_e) about the apex: the ends are spherical, not back cones,
so every other surface is a cone through the apex and the tooth's section on any sphere about
the apex is the heel's scaled (:mod:`geargen.families.bevel.geometry`). Inside the root cone lies the
axisymmetric core (:func:`geargen.families.bevel.geometry.bevel_core`): its back is the heel sphere
(``back="spherical"``) or the plane through the heel root circle (``back="flat"``, with a web to
the bore when the toe sphere lies beyond that plane); a bore runs along the axis.

How: face by face, as the spur and helical gears (:mod:`geargen.cad.gear_solid`), no boolean.
Tooth 0's outline on the unit sphere is a chain of curves (lower meridian below the base cone if
the root cone is inside it, lower flank, tip arc, upper flank, upper meridian, root arc to tooth
1); each curve's side face is the cone through the apex over it, between the toe and heel
spheres: a plane for a meridian, an exact cone (``Geom_ConicalSurface``) for the tip and root
arcs, and for a flank a ruled B-spline surface whose two rows of poles are the heel curve's poles
scaled to the toe and the heel, so every ruling passes through the apex. The heel curve is one
clamped degree-7 B-spline fitted to exact points of the spherical involute (exact ends and end
tangents, :func:`geargen.profile.bspline_fit.fit_function`) together with its curve on the
spheres (azimuth, latitude), so edge and pcurve share knots and parameter; the flank's distance
from the spherical involute is that of the fit (:data:`FLANK_TOLERANCE` of R_e; measured on the
solid by tests/cad/test_bevel_solid.py). Rulings are lines, toe and heel arcs circles. Tooth 0's
surfaces and curves are built once and turned for the other teeth; neighbouring faces share their
edges, so the shell is put together edge by edge (BRep_Builder), not sewn. The toe face (and a
spherical back) is one spherical face bounded by the whole toothed outline, with a seam along the
meridian at azimuth 0 (tooth 0's tip arc is split there) and an inner circle at the bore (or the
web, or a degenerate edge at the pole); a flat back's heel is a patch of the heel sphere per tooth
and the plane within the heel root circle. No root fillet: the flank meets the root cone (or the meridian
below the base cone) at a sharp edge.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from OCP.BRep import BRep_Builder
from OCP.Geom import (Geom_BSplineSurface, Geom_Circle, Geom_ConicalSurface, Geom_CylindricalSurface, Geom_Line,
                      Geom_Plane, Geom_SphericalSurface)
from OCP.Geom2d import Geom2d_Circle, Geom2d_Line
from OCP.gp import gp_Ax1, gp_Ax2, gp_Ax2d, gp_Ax3, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d, gp_Vec2d
from OCP.TColgp import TColgp_Array2OfPnt
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopExp import TopExp
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Edge, TopoDS_Face

from geargen.cad.gear_solid import check_solid
from geargen.cad.kernel import (KERNEL_TOLERANCE, ORIGIN_2D, Z_AXIS, bspline_curve_2d, bspline_curve_3d, closed_solid, make_edge,
                                make_vertex, make_wire, occ_knots)
from geargen.families.bevel.geometry import (bevel_core, bevel_geometry, bevel_volume, check_tooth, lower_flank_points,
                                tooth_half_angle, tooth_outline)
from geargen.families.bevel.spec import BevelGearSpec
from geargen.errors import BuildError
from geargen.profile.bevel_tessellate import bevel_triangles
from geargen.profile.bspline_fit import fit_function

#: largest distance of a flank's B-spline (and of its curve on the spheres) from the spherical
#: involute, relative to the heel cone distance R_e: 1.3e-9 mm on the 13 mm heel of the bench gears,
#: reached with 2 spans (9 poles) on the gear, 7 (14 poles) on the pinion, whose flank starts on the
#: base cone, where the involute's speed is zero
FLANK_TOLERANCE = 1e-10
_LOC = TopLoc_Location()
_F, _R = TopAbs_FORWARD, TopAbs_REVERSED


@dataclass
class BevelSolid:
    """A built bevel gear: the OCCT shape (one closed solid), its spec and its back
    (``"spherical"`` or ``"flat"``, :func:`geargen.families.bevel.geometry.bevel_core`)."""

    shape: object
    name: str
    spec: BevelGearSpec
    length_unit: str
    back: str = "spherical"
    profile: object = None  # no transverse profile: a bevel gear has no drawing/DXF

    def is_valid(self) -> bool:
        return check_solid(self.shape) is None

    def exact_triangles(self, chordal_tolerance: float, angular_tolerance: float | None = None):
        """The closed triangle mesh ``(n, 3, 3)`` of the solid from its exact geometry, within
        ``chordal_tolerance`` mm (:func:`geargen.profile.bevel_tessellate.bevel_triangles`; the STL
        export's and the view's mesher, ~20x faster than the kernel's); ``angular_tolerance`` is not
        used (the chordal tolerance alone sets the facets)."""
        return bevel_triangles(self.spec, self.back, chordal_tolerance)


def _unit(polar: float, azimuth: float) -> np.ndarray:
    return np.array([math.sin(polar) * math.cos(azimuth), math.sin(polar) * math.sin(azimuth), math.cos(polar)])


def _dir(v) -> gp_Dir:
    return gp_Dir(float(v[0]), float(v[1]), float(v[2]))


def _latitude_circle(radius: float, polar: float) -> Geom_Circle:
    """The circle of polar angle ``polar`` on the sphere ``radius``; parameter = azimuth."""
    ax = gp_Ax2(gp_Pnt(0, 0, radius * math.cos(polar)), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0))
    return Geom_Circle(ax, radius * math.sin(polar))


@dataclass
class _Curve:
    """One curve of tooth 0's outline on the unit sphere, traversed counter-clockwise about +z, and
    the cone over it: ``surface`` (the side face's), ``sense`` +1 when the side surface's (u, v)
    turn as (along the curve, away from the apex) do, so that its normal points out of the solid,
    else -1 (the face's loop is laid the other way round and the face turned over);
    ``curve(R)`` the 3-D curve on the sphere of radius R (parameter increasing along the
    traversal, over ``range``); ``on_side(R)`` its pcurve on the side surface, ``ruling(t)`` the
    pcurve (parameter = distance from the apex) of the ruling at curve parameter t;
    ``on_sphere`` the pcurve on the spheres (u = azimuth, v = latitude); ``start``/``end`` the
    unit vectors of its ends; ``tolerance`` the edge tolerance (mm per mm of R) of its toe and heel
    edges."""

    kind: str
    surface: object
    sense: int
    curve: object
    range: tuple[float, float]
    on_side: object
    ruling: object
    on_sphere: object
    start: np.ndarray
    end: np.ndarray
    tolerance: float = 0.0


def _meridian(azimuth: float, polar0: float, polar1: float, rising: bool) -> _Curve:
    """The meridian at ``azimuth`` between two polar angles, rising (away from the axis) or falling.
    Plane and circles with normal N = +/- e_phi and x axis +z: the parameter t = +/- theta."""
    sign = 1.0 if rising else -1.0
    normal = gp_Dir(-sign * math.sin(azimuth), sign * math.cos(azimuth), 0.0)
    surface = Geom_Plane(gp_Ax3(gp_Pnt(0, 0, 0), normal, gp_Dir(0, 0, 1)))
    t0, t1 = (polar0, polar1) if rising else (-polar0, -polar1)

    def curve(r):
        return Geom_Circle(gp_Ax2(gp_Pnt(0, 0, 0), normal, gp_Dir(0, 0, 1)), r)

    def on_side(r):
        return Geom2d_Circle(gp_Ax2d(ORIGIN_2D, gp_Dir2d(1, 0)), r)

    def ruling(t):
        return Geom2d_Line(ORIGIN_2D, gp_Dir2d(math.cos(t), math.sin(t)))

    # the pcurve on the spheres: v = pi/2 - theta = pi/2 - sign t
    on_sphere = Geom2d_Line(gp_Pnt2d(azimuth, math.pi / 2), gp_Dir2d(0.0, -sign))
    # (t, r) -> (r cos t, r sin t) on the plane turns the orientation over: sense -1
    return _Curve("meridian", surface, -1, curve, (t0, t1), on_side, ruling, on_sphere,
                  _unit(polar0, azimuth), _unit(polar1, azimuth))


def _latitude(kind: str, polar: float, azimuth0: float, azimuth1: float) -> _Curve:
    """The arc of polar angle ``polar`` from azimuth0 to azimuth1 (increasing) and the cone over it:
    an exact cone about +z (u = azimuth, v = distance from the apex), about -z past 90 deg
    (u = -azimuth), the plane z = 0 at 90 deg."""
    z = gp_Dir(0, 0, 1)
    if abs(polar - math.pi / 2) < 1e-12:
        surface = Geom_Plane(gp_Ax3(gp_Pnt(0, 0, 0), z, gp_Dir(1, 0, 0)))
        sense = -1  # (t, r) -> (r cos t, r sin t) turns the orientation over

        def on_side(r):
            return Geom2d_Circle(gp_Ax2d(ORIGIN_2D, gp_Dir2d(1, 0)), r)

        def ruling(t):
            return Geom2d_Line(ORIGIN_2D, gp_Dir2d(math.cos(t), math.sin(t)))
    else:
        up = polar < math.pi / 2
        sign = 1.0 if up else -1.0
        surface = Geom_ConicalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, sign), gp_Dir(1, 0, 0)),
                                      polar if up else math.pi - polar, 0.0)
        sense = 1 if up else -1

        def on_side(r):
            return Geom2d_Line(gp_Pnt2d(0.0, r), gp_Dir2d(sign, 0.0))

        def ruling(t):
            return Geom2d_Line(gp_Pnt2d(sign * t, 0.0), gp_Dir2d(0.0, 1.0))

    on_sphere = Geom2d_Line(gp_Pnt2d(0.0, math.pi / 2 - polar), gp_Dir2d(1.0, 0.0))
    return _Curve(kind, surface, sense, lambda r: _latitude_circle(r, polar), (azimuth0, azimuth1), on_side, ruling,
                  on_sphere, _unit(polar, azimuth0), _unit(polar, azimuth1))


def _flanks(spec: BevelGearSpec) -> tuple[_Curve, _Curve]:
    """Tooth 0's lower (rising) and upper (falling) flank. The lower flank is fitted once on the unit
    sphere, parameter s = R_e (t - t_start) in the rolling angle t, as the 5 columns (x, y, z,
    azimuth, latitude): the 3-D curve and its curve on the spheres on the same knots, each within
    the fit's error of the exact point at the same s; the upper flank is its mirror image in the
    xz plane, traversed the other way."""
    outline = tooth_outline(spec)
    re = spec.cone_distance
    t0 = outline.roll_start
    length = re * (outline.roll_tip - t0)

    def columns(p, d):
        # azimuth and latitude of p on the unit sphere and their rates from dp
        xy2 = p[:, 0] ** 2 + p[:, 1] ** 2
        du = (p[:, 0] * d[:, 1] - p[:, 1] * d[:, 0]) / xy2
        dv = d[:, 2] / np.sqrt(xy2)
        return np.column_stack([p, np.arctan2(p[:, 1], p[:, 0]), np.arcsin(p[:, 2])]), np.column_stack([d, du, dv])

    def point(s):
        return columns(*lower_flank_points(outline, t0 + np.asarray(s) / re))[0]

    def deriv(s):
        return columns(*lower_flank_points(outline, t0 + np.asarray(s) / re))[1] / re

    try:
        fit = fit_function(point, deriv, length, FLANK_TOLERANCE)
    except ValueError as exc:
        raise BuildError(f"{spec.name}: flank: {exc}") from exc
    # the 3-D curve and the pcurve each lie within the fit's error of the exact point at the same
    # parameter, so within twice it of each other (x 1.5 for the distance between check points)
    tolerance = 3.0 * fit.max_error
    knots, mults, degree = fit.knots, fit.mults, fit.degree
    mirrored_knots, mirrored_mults = length - knots[::-1], mults[::-1]
    ri = spec.toe_cone_distance
    out = []
    for poles, kn, mu in ((fit.poles, knots, mults), (fit.poles[::-1] * [1, -1, 1, -1, 1], mirrored_knots,
                                                      mirrored_mults)):
        unit_poles = poles[:, :3]
        # the ruled surface: rows of poles at the toe and the heel, v = the distance from the apex
        arr = TColgp_Array2OfPnt(1, len(unit_poles), 1, 2)
        for i, (x, y, z) in enumerate(unit_poles.tolist()):
            for j, r in enumerate((ri, re)):
                arr.SetValue(i + 1, j + 1, gp_Pnt(r * x, r * y, r * z))
        ku, mu_ = occ_knots(kn, mu)
        kv, mv = occ_knots([ri, re], [2, 2])
        surface = Geom_BSplineSurface(arr, ku, kv, mu_, mv, degree, 1)

        def curve(r, unit_poles=unit_poles, kn=kn, mu=mu):
            return bspline_curve_3d(unit_poles * r, kn, mu, degree)

        def on_side(r):
            return Geom2d_Line(gp_Pnt2d(0.0, r), gp_Dir2d(1.0, 0.0))

        def ruling(s):
            return Geom2d_Line(gp_Pnt2d(s, 0.0), gp_Dir2d(0.0, 1.0))

        out.append(_Curve("flank", surface, 1, curve, (0.0, length), on_side, ruling,
                          bspline_curve_2d(poles[:, 3:], kn, mu, degree), unit_poles[0], unit_poles[-1], tolerance))
    return out[0], out[1]


def _tooth_curves(spec: BevelGearSpec) -> list[_Curve]:
    """Tooth 0's outline, counter-clockwise: [lower meridian], lower flank, tip arc, upper flank,
    [upper meridian], root arc to tooth 1."""
    o = tooth_outline(spec)
    pitch = 2 * math.pi / spec.teeth
    lower, upper = _flanks(spec)
    curves = [lower, _latitude("tip", o.tip, -o.tip_half_angle, o.tip_half_angle), upper]
    if o.meridian:
        curves.insert(0, _meridian(-o.root_half_angle, o.root, o.flank_start, rising=True))
        curves.append(_meridian(o.root_half_angle, o.flank_start, o.root, rising=False))
    curves.append(_latitude("root", o.root, o.root_half_angle, pitch - o.root_half_angle))
    return curves


def _rotation_matrix(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


class _Shell:
    """The faces of one bevel solid, put together edge by edge."""

    def __init__(self):
        self.builder = BRep_Builder()
        self.faces: list = []

    def vertex(self, p):
        return make_vertex(self.builder, float(p[0]), float(p[1]), float(p[2]))

    def edge(self, curve, v0, v1, p0: float, p1: float, tolerance: float = KERNEL_TOLERANCE):
        """An edge of ``curve`` over [p0, p1]; a tolerance above the kernel's goes to its vertices too
        (a vertex's is never below its edges')."""
        e = make_edge(self.builder, curve, v0, v1, p0, p1)
        if tolerance > KERNEL_TOLERANCE:
            self.builder.UpdateEdge(e, tolerance)
            for v in (v0, v1):
                self.builder.UpdateVertex(v, tolerance)
        return e

    def pcurve(self, edge, pcurve, surface, tolerance: float = KERNEL_TOLERANCE):
        self.builder.UpdateEdge(edge, pcurve, surface, _LOC, max(tolerance, KERNEL_TOLERANCE))

    def seam(self, edge, forward, reversed_, surface):
        """Pcurves of a seam edge: ``forward`` where the face uses the edge FORWARD, ``reversed_``
        where it uses it REVERSED."""
        self.builder.UpdateEdge(edge, forward, reversed_, surface, _LOC, KERNEL_TOLERANCE)

    def face(self, surface, wires, sense: int = 1):
        """A face of ``surface`` bounded by ``wires``, each a list of (edge, orientation) running
        counter-clockwise in the surface's (u, v) about the face (the material on its left, the
        kernel's rule); ``sense`` -1 turns the face over (its outward normal against the surface's)."""
        f = TopoDS_Face()
        self.builder.MakeFace(f, surface, _LOC, KERNEL_TOLERANCE)
        for w in wires:
            self.builder.Add(f, make_wire(self.builder, [e for e, _ in w], [o for _, o in w]))
        self.faces.append(f if sense > 0 else f.Reversed())
        return f

    def solid(self):
        return closed_solid(self.builder, self.faces)


def _degenerate_edge(shell: _Shell, vertex, pcurve, surface):
    e = TopoDS_Edge()
    b = shell.builder
    b.MakeEdge(e)
    b.UpdateEdge(e, pcurve, surface, _LOC, KERNEL_TOLERANCE)
    b.Degenerated(e, True)
    b.Add(e, vertex.Oriented(_F))
    b.Add(e, vertex.Oriented(_R))
    b.Range(e, 0.0, 2 * math.pi)
    return e


def _body(spec: BevelGearSpec, back: str):
    """The closed solid of ``spec`` with ``back`` (module docstring)."""
    ri, re = spec.toe_cone_distance, spec.cone_distance
    rb = spec.bore_diameter / 2
    core = bevel_core(spec, back)
    o = tooth_outline(spec)
    curves = _tooth_curves(spec)
    n, z = len(curves), spec.teeth
    pitch = 2 * math.pi / z
    shell = _Shell()

    # joints: the end of every curve of every tooth, counter-clockwise; joint i - 1 starts curve i
    ends = np.array([c.end for c in curves])
    joints = np.concatenate([ends @ _rotation_matrix(k * pitch).T for k in range(z)])
    toe_v = [shell.vertex(ri * u) for u in joints]
    heel_v = [shell.vertex(re * u) for u in joints]
    rulings = [shell.edge(Geom_Line(gp_Ax1(gp_Pnt(0, 0, 0), _dir(u))), toe_v[i], heel_v[i], ri, re)
               for i, u in enumerate(joints)]

    toe_sphere = Geom_SphericalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)), ri)
    heel_sphere = Geom_SphericalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)), re)
    flat = core.back == "flat"
    if flat:
        back_plane = Geom_Plane(gp_Ax3(gp_Pnt(0, 0, core.back_z), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)))
        root_circle_2d = Geom2d_Circle(gp_Ax2d(ORIGIN_2D, gp_Dir2d(1, 0)), re * math.sin(o.root))

    # the seam of the whole spheres (and the bore's) runs along azimuth 0, through the middle of tooth 0's
    # tip arc, which is split there: the kernel's own revolved faces start at their x axis too, and its
    # face unification (fusing a hub or a web) fails to merge a bore with a coaxial one whose seam
    # lies elsewhere. On a whole sphere u then runs from 0 to 2 pi: tooth 0's curves before the seam
    # get their pcurves one turn on.
    j_tip = next(j for j, c in enumerate(curves) if c.kind == "tip")
    mid_toe, mid_heel = shell.vertex(ri * _unit(o.tip, 0.0)), shell.vertex(re * _unit(o.tip, 0.0))
    toe_outline, heel_outline, heel_by_tooth, under_teeth = [], [], [[] for _ in range(z)], []
    for i in range(len(joints)):
        k, j = divmod(i, n)
        c = curves[j]
        angle = k * pitch
        surface = c.surface.Rotated(Z_AXIS, angle) if k else c.surface
        t0, t1 = c.range
        toe_curve, heel_curve = c.curve(ri), c.curve(re)
        if k:
            toe_curve, heel_curve = toe_curve.Rotated(Z_AXIS, angle), heel_curve.Rotated(Z_AXIS, angle)
        pieces = [(t0, t1, toe_v[i - 1], toe_v[i], heel_v[i - 1], heel_v[i])]
        if i == j_tip:
            pieces = [(t0, 0.0, toe_v[i - 1], mid_toe, heel_v[i - 1], mid_heel),
                      (0.0, t1, mid_toe, toe_v[i], mid_heel, heel_v[i])]
        toes, heels = [], []
        for a, b, vt0, vt1, vh0, vh1 in pieces:
            e_toe = shell.edge(toe_curve, vt0, vt1, a, b, c.tolerance * ri)
            e_heel = shell.edge(heel_curve, vh0, vh1, a, b, c.tolerance * re)
            shell.pcurve(e_toe, c.on_side(ri), surface)
            shell.pcurve(e_heel, c.on_side(re), surface)
            on_sphere = c.on_sphere.Translated(gp_Vec2d(angle, 0.0)) if k else c.on_sphere
            before_seam = k == 0 and (j < j_tip or (j == j_tip and b <= 0.0))
            on_whole = on_sphere.Translated(gp_Vec2d(2 * math.pi, 0.0)) if before_seam else on_sphere
            shell.pcurve(e_toe, on_whole, toe_sphere, c.tolerance * ri)
            if not flat:
                shell.pcurve(e_heel, on_whole, heel_sphere, c.tolerance * re)
            elif c.kind == "root":
                shell.pcurve(e_heel, root_circle_2d.Rotated(ORIGIN_2D, angle), back_plane)
            else:  # a tooth's own heel patch, whose u runs on across azimuth 0
                shell.pcurve(e_heel, on_sphere, heel_sphere, c.tolerance * re)
                heel_by_tooth[k].append(e_heel)
            toes.append(e_toe)
            heels.append(e_heel)
        shell.pcurve(rulings[i], c.ruling(t1), surface)
        shell.pcurve(rulings[i - 1], c.ruling(t0), surface)
        loop = [(e, _F) for e in toes] + [(rulings[i], _F)] + [(e, _R) for e in heels[::-1]] + [(rulings[i - 1], _R)]
        if c.sense < 0:  # the same loop the other way round is the one counter-clockwise in (u, v)
            loop = [(e, _R if way == _F else _F) for e, way in loop[::-1]]
        shell.face(surface, [loop], c.sense)
        toe_outline += toes
        heel_outline += heels
        if flat and j == n - 1:
            # this tooth's heel end, a patch of the heel sphere from its root circle to its outline
            arc = _latitude_circle(re, o.root).Rotated(Z_AXIS, angle)
            under = shell.edge(arc, heel_v[k * n - 1], heel_v[k * n + n - 2], -o.root_half_angle, o.root_half_angle)
            shell.pcurve(under, Geom2d_Line(gp_Pnt2d(angle, math.pi / 2 - o.root), gp_Dir2d(1, 0)), heel_sphere)
            shell.pcurve(under, root_circle_2d.Rotated(ORIGIN_2D, angle), back_plane)
            shell.face(heel_sphere, [[(e, _F) for e in heel_by_tooth[k]] + [(under, _R)]])
            under_teeth.append((under, heels[-1]))
    seam_at = j_tip + 1  # the outlines from the seam round to it: from the second half of tooth 0's tip
    toe_outline = toe_outline[seam_at:] + toe_outline[:seam_at]
    heel_outline = heel_outline[seam_at:] + heel_outline[:seam_at]

    x_axis = gp_Dir(1, 0, 0)

    def inner_circle(radius: float, height: float):
        """A whole circle about the axis at ``height``, its one vertex on the seam (azimuth 0)."""
        v = shell.vertex((radius, 0.0, height))
        circle = Geom_Circle(gp_Ax2(gp_Pnt(0, 0, height), gp_Dir(0, 0, 1), x_axis), radius)
        return shell.edge(circle, v, v, 0.0, 2 * math.pi), v

    def sphere_face(sphere, radius, outline_edges, seam_vertex, inner_polar, sense):
        """The spherical face bounded by the toothed outline (u from 0 to 2 pi) and the circle of
        ``inner_polar`` (the pole when 0); returns the inner circle's edge."""
        if inner_polar > 0:
            inner, v_in = inner_circle(radius * math.sin(inner_polar), radius * math.cos(inner_polar))
            shell.pcurve(inner, Geom2d_Line(gp_Pnt2d(0.0, math.pi / 2 - inner_polar), gp_Dir2d(1, 0)), sphere)
        else:
            v_in = shell.vertex((0.0, 0.0, radius))
            inner = _degenerate_edge(shell, v_in, Geom2d_Line(gp_Pnt2d(0.0, math.pi / 2), gp_Dir2d(1, 0)), sphere)
        # the meridian at azimuth 0, parameter = polar angle
        arc = Geom_Circle(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0), gp_Dir(0, 0, 1)), radius)
        seam = shell.edge(arc, v_in, seam_vertex, inner_polar, o.tip)
        shell.seam(seam, Geom2d_Line(gp_Pnt2d(0.0, math.pi / 2), gp_Dir2d(0, -1)),
                   Geom2d_Line(gp_Pnt2d(2 * math.pi, math.pi / 2), gp_Dir2d(0, -1)), sphere)
        shell.face(sphere, [[(e, _F) for e in outline_edges] + [(seam, _R), (inner, _R), (seam, _F)]], sense)
        return inner

    toe_inner = sphere_face(toe_sphere, ri, toe_outline, mid_toe, core.toe_inner, -1)
    bore_low = bore_high = None
    if core.toe_inner_face == "bore":
        bore_low = toe_inner
    elif core.toe_inner_face == "web":
        web_plane = Geom_Plane(gp_Ax3(gp_Pnt(0, 0, core.web_z), gp_Dir(0, 0, 1), x_axis))
        meets_toe = ri * math.sin(core.toe_inner)  # the radius where the web's face meets the toe sphere
        shell.pcurve(toe_inner, Geom2d_Circle(gp_Ax2d(ORIGIN_2D, gp_Dir2d(1, 0)), meets_toe), web_plane)
        wires = [[(toe_inner, _F)]]
        if rb > 0:
            bore_low, _ = inner_circle(rb, core.web_z)
            shell.pcurve(bore_low, Geom2d_Circle(gp_Ax2d(ORIGIN_2D, gp_Dir2d(1, 0)), rb), web_plane)
            wires.append([(bore_low, _R)])
        shell.face(web_plane, wires, -1)
    if flat:
        wires = [[(e, _F) for pair in under_teeth for e in pair]]  # each tooth's foot, then its space
        if rb > 0:
            bore_high, _ = inner_circle(rb, core.back_z)
            shell.pcurve(bore_high, Geom2d_Circle(gp_Ax2d(ORIGIN_2D, gp_Dir2d(1, 0)), rb), back_plane)
            wires.append([(bore_high, _R)])
        shell.face(back_plane, wires)
    else:
        heel_inner = sphere_face(heel_sphere, re, heel_outline, mid_heel, core.heel_inner, 1)
        if rb > 0:
            bore_high = heel_inner
    if rb > 0:
        bore = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), x_axis), rb)
        z_low, z_high = core.bore_z
        for circle, height in ((bore_low, z_low), (bore_high, z_high)):
            shell.pcurve(circle, Geom2d_Line(gp_Pnt2d(0.0, height), gp_Dir2d(1, 0)), bore)
        foot = gp_Pnt(rb, 0.0, 0.0)
        v_low, v_high = TopExp.FirstVertex_s(bore_low), TopExp.FirstVertex_s(bore_high)
        line = shell.edge(Geom_Line(gp_Ax1(foot, gp_Dir(0, 0, 1))), v_low, v_high, z_low, z_high)
        shell.seam(line, Geom2d_Line(gp_Pnt2d(2 * math.pi, 0.0), gp_Dir2d(0, 1)),
                   Geom2d_Line(gp_Pnt2d(0.0, 0.0), gp_Dir2d(0, 1)), bore)
        shell.face(bore, [[(bore_low, _F), (line, _F), (bore_high, _R), (line, _R)]], -1)
    return shell.solid()


def build_bevel(spec: BevelGearSpec, check: bool = False, back: str = "spherical") -> BevelSolid:
    """Build ``spec`` as one closed solid (conventions in the module docstring) with its ``back``
    ``"spherical"`` (the heel sphere) or ``"flat"`` (the plane through the heel root circle, with a
    web to the bore when the toe sphere lies beyond it: :func:`geargen.families.bevel.geometry.bevel_core`).
    Raises GeometryError for a tooth that cannot be made (:func:`geargen.families.bevel.geometry.check_tooth`)."""
    check_tooth(spec)
    bevel_core(spec, back)  # a wrong back is refused (geargen.families.bevel.geometry) before any kernel work
    shape = _body(spec, back)
    if check:
        problem = check_solid(shape)
        if problem:
            raise BuildError(f"{spec.name}: {problem}")
    return BevelSolid(shape, spec.name, spec, spec.length_unit, back)


def face_points(shape, grid: int = 12) -> np.ndarray:
    """Points ``(n, 3)`` on the B-spline faces of ``shape`` (a bevel gear's flanks are its only ones;
    a peer's may include others): each face sampled on a ``grid`` x ``grid`` parameter grid, points
    inside the face only."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepTools import BRepTools
    from OCP.BRepTopAdaptor import BRepTopAdaptor_FClass2d
    from OCP.TopAbs import TopAbs_FACE, TopAbs_IN
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS
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
                if inside.Perform(gp_Pnt2d(u, v)) == TopAbs_IN:
                    p = surface.Value(u, v)
                    out.append((p.X(), p.Y(), p.Z()))
    return np.array(out).reshape(-1, 3)


def involute_deviation(spec: BevelGearSpec, points: np.ndarray, phase: float = 0.0,
                       margins: tuple[float, float] = (0.02, 0.02)) -> tuple[np.ndarray, np.ndarray]:
    """Signed deviations (mm, + = outside the tooth) of ``points`` ``(n, 3)`` (apex at the origin,
    axis +z) from the spherical-involute flank of their tooth, and their side (-1 lower, +1 upper),
    for tooth 0 centred on azimuth ``phase``. Only points between the base (or root) and tip cones
    count, ``margins`` (fractions of the tooth depth) inside each: on the sphere of radius R the
    deviation is the arc of the circle of latitude between the point and the flank,
    R sin(theta) (|phi - phi_k| - phi(theta)), an upper bound of its distance from the flank."""
    g = bevel_geometry(spec)
    depth = g.tip_cone_angle - g.root_cone_angle
    lo = max(g.base_cone_angle, g.root_cone_angle) + margins[0] * depth
    hi = g.tip_cone_angle - margins[1] * depth
    r = np.linalg.norm(points, axis=1)
    theta = np.arccos(np.clip(points[:, 2] / np.maximum(r, 1e-300), -1.0, 1.0))
    keep = (theta >= lo) & (theta <= hi)
    r, theta, pts = r[keep], theta[keep], points[keep]
    pitch = 2 * math.pi / spec.teeth
    phi = np.arctan2(pts[:, 1], pts[:, 0]) - phase
    local = phi - pitch * np.round(phi / pitch)  # from the nearest tooth's centre
    dev = r * np.sin(theta) * (np.abs(local) - tooth_half_angle(spec, theta))
    return dev, np.where(local < 0, -1, 1)


def flank_deviation(shape, spec: BevelGearSpec, grid: int = 12) -> np.ndarray:
    """Deviations (mm) of points sampled on the solid's flank faces (:func:`face_points`) from the
    spherical involute (:func:`involute_deviation`, tooth 0 on azimuth 0); points of the root
    faces (on the root cone) are left out by their polar angle."""
    return involute_deviation(spec, face_points(shape, grid))[0]


__all__ = ["BevelSolid", "build_bevel", "bevel_volume", "face_points", "involute_deviation", "flank_deviation",
           "FLANK_TOLERANCE"]
