"""The worm pair's backlash measured on the built SOLIDS (the wheel of
geargen.families.worm_wheel.solid, the worm of geargen.families.worm.solid placed by ``worm_to_mesh``), read
as the exact check reads it (geargen.families.worm.pair): the wheel's free rotation with the worm
held, per side, over the same transverse planes, as an arc at the wheel reference circle.

In each plane both solids are sectioned face by face (a boolean section of the whole solids took
~15 s a plane each). The wheel's section near the mesh is sampled densely and cut into pieces
monotone in radius (flanks, trochoids; the root and tip arcs, of constant radius, cross no circle
of another radius), each piece's material side read from its face's outward normal. For a worm
section point at wheel radius R,
the pieces' crossings of the circle R nearest on each side give how far the wheel turns that way
before its boundary reaches the point; if the nearest crossing has the material on the point's
side, the point is inside the wheel (interference: a negative turn). The worm's edges are sampled
coarsely, then densely around the points closest to contact.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geargen.families.worm.solid import worm_to_mesh
from geargen.families.worm.geometry import worm_geometry
from geargen.families.worm.spec import WormGearSet
from geargen.errors import BuildError


@dataclass(frozen=True)
class SolidWormPlay:
    """What geargen.families.worm.pair.WormPairCheck reports, read from the solids: ``free_rotation``
    (rad) of the wheel per side (+1: toward +X at the mesh), ``backlash`` (mm, arc at the wheel
    reference circle), ``interference``, the plane of first contact per side, the centre distance."""

    free_rotation: dict
    backlash: float
    interference: bool
    contact_plane: dict
    centre_distance: float


class _Section:
    """The section of a set of faces by a plane, face by face (GeomInt_IntSS of each face's surface
    with the plane, its points kept where the face's own boundary keeps them: BRepTopAdaptor_FClass2d
    on the intersection's curve on the face, or the point's projection where the kernel gives none).
    ``lines``: (face, 3D curve, curve on the face or None, first, last parameter)."""

    def __init__(self, faces, plane, extent: float):
        from OCP.BRep import BRep_Tool
        from OCP.Geom import Geom_Plane
        from OCP.GeomInt import GeomInt_IntSS
        from OCP.BRepTopAdaptor import BRepTopAdaptor_FClass2d
        from OCP.ShapeAnalysis import ShapeAnalysis_Surface
        self.lines = []
        geom_plane = Geom_Plane(plane)
        for face in faces:
            surface = BRep_Tool.Surface_s(face)
            iso = _z_isoline(surface, plane)
            if iso is not None:  # exact, and the kernel's intersection strays at the surface's C0 knots
                tools = (face, surface, BRepTopAdaptor_FClass2d(face, 1e-9), ShapeAnalysis_Surface(surface))
                self.lines.append((tools, *iso))
                continue
            inter = GeomInt_IntSS(surface, geom_plane, 1e-9, True, True, False)
            if not inter.IsDone():
                raise BuildError("worm pair: a face's section with the check plane failed")
            tools = (face, surface, BRepTopAdaptor_FClass2d(face, 1e-9), ShapeAnalysis_Surface(surface))
            for i in range(1, inter.NbLines() + 1):
                curve = inter.Line(i)
                first, last = max(curve.FirstParameter(), -extent), min(curve.LastParameter(), extent)  # lines: bounded
                self.lines.append((tools, curve, inter.LineOnS1(i), first, last))

    @staticmethod
    def points(line, params):
        """(points (n, 3), on the face (n,) bool) of ``line`` at ``params``."""
        from OCP.TopAbs import TopAbs_OUT
        (face, surface, classifier, projector), curve, on_face, _, _ = line
        pts, keep = np.empty((len(params), 3)), np.empty(len(params), bool)
        for i, t in enumerate(params):
            q = curve.Value(float(t))
            uv = on_face.Value(float(t)) if on_face is not None else projector.ValueOfUV(q, 1e-9)
            pts[i] = q.X(), q.Y(), q.Z()
            keep[i] = classifier.Perform(uv) != TopAbs_OUT
        return pts, keep

    @staticmethod
    def params(line, step: float):
        """Parameters of ``line`` about ``step`` apart along it: the arc length of a polyline four
        times as dense, inverted (the kernel's GCPnts_UniformAbscissa took over a minute for 800
        points on the wheel's section curves, degree 8 with C1 knots)."""
        from OCP.GCPnts import GCPnts_AbscissaPoint
        from OCP.GeomAdaptor import GeomAdaptor_Curve
        _, curve, _, first, last = line
        n = max(int(math.ceil(GCPnts_AbscissaPoint.Length_s(GeomAdaptor_Curve(curve, first, last)) / step)), 2) + 1
        dense = np.linspace(first, last, 4 * n)
        pts = np.array([(q.X(), q.Y(), q.Z()) for q in (curve.Value(float(t)) for t in dense)])
        length = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
        return np.interp(np.linspace(0.0, length[-1], n), length, dense)


def _z_isoline(surface, plane):
    """(3D curve, curve on the surface, first, last) of the section of ``surface`` by ``plane`` when
    that is an isoline: a B-spline surface whose v is its z (the wheel's, geargen.families.worm_wheel.solid)
    cut by a plane z = const; else None."""
    from OCP.Geom import Geom_BSplineSurface
    from OCP.Geom2d import Geom2d_Line
    from OCP.gp import gp_Dir2d, gp_Pnt2d
    if not isinstance(surface, Geom_BSplineSurface) or abs(abs(plane.Axis().Direction().Z()) - 1) > 1e-12:
        return None
    u0, u1, v0, v1 = surface.Bounds()
    z = plane.Location().Z()
    for u in (u0, 0.5 * (u0 + u1), u1):
        for v in (v0, 0.5 * (v0 + v1), v1):
            if abs(surface.Value(u, v).Z() - v) > 1e-9:
                return None
    if not v0 <= z <= v1:
        return None
    return surface.VIso(z), Geom2d_Line(gp_Pnt2d(0.0, z), gp_Dir2d(1.0, 0.0)), u0, u1


def _faces(shape):
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    out = []
    while exp.More():
        out.append(TopoDS.Face_s(exp.Current()))
        exp.Next()
    return out


def _box(face):
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    box = Bnd_Box()
    BRepBndLib.Add_s(face, box)
    return box.Get()


def _angle(xy):
    """Polar angle from +Y toward +X (the wheel's turn toward +X at the mesh is positive)."""
    return np.arctan2(xy[..., 0], xy[..., 1])


def _wheel_pieces(section: _Section, step: float, min_span: float):
    """The wheel's section as pieces monotone in radius: (radii increasing, angles, material side)
    with side +1 if the wheel's material lies at larger angle than the piece (from the face's
    outward normal at the piece's middle)."""
    from OCP.BRepLProp import BRepLProp_SLProps
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.TopAbs import TopAbs_REVERSED
    pieces = []
    for line in section.lines:
        params = _Section.params(line, step)
        pts, keep = _Section.points(line, params)
        for run in np.split(np.arange(len(params)), np.flatnonzero(np.diff(keep.astype(int)) != 0) + 1):
            if not keep[run[0]] or len(run) < 2:
                continue
            xy = pts[run, :2]
            radius = np.hypot(xy[:, 0], xy[:, 1])
            turns = np.flatnonzero(np.diff(np.sign(np.diff(radius))) != 0) + 1  # where the radius turns back
            for lo, hi in zip(np.r_[0, turns], np.r_[turns, len(xy) - 1]):
                r, ang = radius[lo:hi + 1], _angle(xy[lo:hi + 1])
                if abs(r[-1] - r[0]) < min_span:
                    continue
                mid = run[(lo + hi) // 2]
                face = line[0][0]
                q = line[1].Value(float(params[mid]))
                uv = line[2].Value(float(params[mid])) if line[2] is not None else line[0][3].ValueOfUV(q, 1e-9)
                props = BRepLProp_SLProps(BRepAdaptor_Surface(face), uv.X(), uv.Y(), 1, 1e-9)
                n = props.Normal()
                sign = -1.0 if face.Orientation() == TopAbs_REVERSED else 1.0
                psi = math.atan2(q.X(), q.Y())  # d(point)/d(angle) is (cos psi, -sin psi): outward normal
                outward_along = sign * (n.X() * math.cos(psi) - n.Y() * math.sin(psi))
                if r[-1] < r[0]:
                    r, ang = r[::-1], ang[::-1]
                pieces.append((r, ang, -1 if outward_along > 0 else 1))
    return pieces


def _turns(pieces, points: np.ndarray) -> np.ndarray:
    """(m, 2): per worm point (wheel-frame xy) the wheel's turn toward +X and toward -X until its
    outline reaches the point (inf: no outline at that radius; negative: the point is inside)."""
    R, ang = np.hypot(points[:, 0], points[:, 1]), _angle(points)
    near = np.full((2, len(points)), np.inf)
    material = np.zeros((2, len(points)))
    for r, a, side in pieces:
        mask = (R >= r[0]) & (R <= r[-1])
        d = np.interp(R[mask], r, a) - ang[mask]
        for k, sign in ((0, 1), (1, -1)):
            dist = np.where(sign * d > 0, sign * d, np.inf)
            closer = dist < near[k, mask]
            idx = np.flatnonzero(mask)[closer]
            near[k, idx], material[k, idx] = dist[closer], side * sign
    inside = (material[0] < 0) | (material[1] < 0)  # the nearest crossing has the material on this side
    out = near.T.copy()
    out[inside] = -near.T[inside][:, ::-1]
    return out


def solid_worm_backlash(s: WormGearSet, wheel_shape, worm_shape, planes: int = 9, step: float | None = None,
                        centre_distance_error: float = 0.0, axial_window: float | None = None) -> SolidWormPlay:
    """The pair of solids at the design centre distance plus ``centre_distance_error`` (the worm
    moved away from the wheel), worm angle 0, wheel angle 0: the wheel's
    free rotation per side (+1: toward +X at the mesh) over ``planes`` transverse planes across 95 %
    of the face (those of geargen.families.worm.pair), backlash = their sum times r2. ``step``: the
    sampling of the wheel's section and of the worm's near contact (default 0.005 m_x: chord sag
    under 20 nm on the flanks). ``axial_window``: only the worm's points within it of the line of
    centres (|X| <= window), e.g. p_x / 2 for the one thread geargen.families.worm.pair reads; by
    default every thread that meets the wheel (off the design centre distance the other engaged
    teeth, at other phases of the mesh, may touch first)."""
    from OCP.gp import gp_Dir, gp_Pln, gp_Pnt
    g = worm_geometry(s)
    m = s.axial_module
    step = 0.005 * m if step is None else step
    a, r2 = g.centre_distance + centre_distance_error, g.wheel_reference_diameter / 2
    rim = g.wheel_outside_diameter / 2
    reach = math.sqrt(max(rim * rim - (a - g.worm_tip_diameter / 2) ** 2, 0.0)) + g.axial_pitch  # worm near the wheel
    best = {1: (math.inf, None), -1: (math.inf, None)}
    wheel_faces = [(f, _box(f)) for f in _faces(wheel_shape)]
    worm_faces = _faces(worm_shape)
    extent = 4 * (a + s.worm_face_length)  # bounds the infinite section lines of the worm's tip cylinder
    for z in np.linspace(-0.95 * s.wheel_face_width / 2, 0.95 * s.wheel_face_width / 2, planes):
        z = float(z)
        near = [f for f, (x0, y0, z0, x1, y1, z1) in wheel_faces
                if z0 <= z <= z1 and x0 < reach and x1 > -reach and y1 > 0]
        pieces = _wheel_pieces(_Section(near, gp_Pln(gp_Pnt(0, 0, z), gp_Dir(0, 0, 1)), extent), step, 1e-6 * m)
        # the mesh plane Z = z is the worm's plane y = -z (worm_to_mesh: Z = -y)
        candidates = {0: [], 1: []}
        for line in _Section(worm_faces, gp_Pln(gp_Pnt(0, -z, 0), gp_Dir(0, 1, 0)), extent).lines:
            params = _Section.params(line, 20 * step)
            pts, keep = _Section.points(line, params)
            mesh = worm_to_mesh(pts, a)
            turns = _turns(pieces, mesh[:, :2])
            turns[~keep | (np.abs(mesh[:, 0]) > (math.inf if axial_window is None else axial_window))] = np.inf
            for k in range(2):
                for i in np.argsort(turns[:, k])[:3]:  # each side's closest coarse points of this line
                    if np.isfinite(turns[i, k]):
                        candidates[k].append((turns[i, k], line, params[max(i - 1, 0)],
                                              params[min(i + 1, len(params) - 1)]))
        for k, side in ((0, 1), (1, -1)):
            for _, line, lo, hi in sorted(candidates[k], key=lambda c: c[0])[:12]:
                pts, keep = _Section.points(line, np.linspace(lo, hi, 41))
                mesh = worm_to_mesh(pts, a)
                if axial_window is not None:
                    keep &= np.abs(mesh[:, 0]) <= axial_window
                turns = _turns(pieces, mesh[:, :2])[keep]
                value = float(turns[:, k].min()) if len(turns) else math.inf
                if value < best[side][0]:
                    best[side] = (value, z)
    rotation = {side: best[side][0] for side in (1, -1)}
    return SolidWormPlay(free_rotation=rotation, backlash=(rotation[1] + rotation[-1]) * r2,
                         interference=min(rotation.values()) * r2 < -1e-7,
                         contact_plane={side: best[side][1] for side in (1, -1)}, centre_distance=a)


__all__ = ["SolidWormPlay", "solid_worm_backlash"]
