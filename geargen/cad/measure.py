"""Measurements on a built solid: transverse sections, flank deviation, span and over-ball size.

Everything here is measured on the solid's own section with the plane z = const, never on the
points the solid was built from, and compared with the exact profile.

The section is taken face by face: on each face that crosses the plane, points with
z(u, v) = const are found by Newton's method on the face's own surface (to ~1e-15 mm), stepping
along the parameter that runs across the plane and keeping the face's parameter bounds and
boundary (a point outside the face is dropped). This costs ~0.3 ms per face where OCCT's boolean
section (:func:`boolean_section`, kept as a cross-check) takes ~10 ms per face.

Sign convention of the flank deviation: positive where the section lies outside the exact
involute (material added, tooth too thick), in mm, measured along the involute normal (the
tangent to the base circle) - what a gear checker reports as the profile deviation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepAlgoAPI import BRepAlgoAPI_Section
from OCP.BRepTools import BRepTools
from OCP.BRepTopAdaptor import BRepTopAdaptor_FClass2d
from OCP.GeomAbs import GeomAbs_BSplineCurve, GeomAbs_Line, GeomAbs_Plane
from OCP.gp import gp_Dir, gp_Pln, gp_Pnt, gp_Pnt2d, gp_Vec
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_IN, TopAbs_OUT
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Shape
from scipy.optimize import brentq, minimize_scalar
from scipy.spatial import cKDTree

from geargen.core.involute import involute
from geargen.profile.segments import sample_outline
from geargen.profile.tooth import ToothProfile, section_rotation


class SectionCurve:
    """The section of one face with the plane z = ``z``: ``point(t)`` for t in [t0, t1].

    ``t`` is the face parameter that runs along the section (u or v); the other one is solved
    for by Newton's method so that the surface point lies at height z. ``point`` returns None
    where the plane misses the face.
    """

    def __init__(self, face, z: float, surface: BRepAdaptor_Surface | None = None):
        self.face = face
        self.z = z
        self.surface = BRepAdaptor_Surface(face) if surface is None else surface  # the face's, if made already
        self.u0, self.u1, self.v0, self.v1 = BRepTools.UVBounds_s(face)
        um, vm = 0.5 * (self.u0 + self.u1), 0.5 * (self.v0 + self.v1)
        p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
        self.surface.D1(um, vm, p, du, dv)
        # march along the parameter in which z varies least; solve the other one
        self.along_u = abs(dv.Z()) * (self.v1 - self.v0) >= abs(du.Z()) * (self.u1 - self.u0)
        self.t0, self.t1 = (self.u0, self.u1) if self.along_u else (self.v0, self.v1)
        self.s0, self.s1 = (self.v0, self.v1) if self.along_u else (self.u0, self.u1)
        self._guess = 0.5 * (self.s0 + self.s1)
        self._classifier = None
        self._inner = None  # the box of parameters certainly inside the face (made with the classifier)
        # what every solve uses, made once (a section solves ~40,000 points, most in one Newton step)
        self._p, self._du, self._dv = gp_Pnt(), gp_Vec(), gp_Vec()
        span = self.s1 - self.s0
        self._clip_lo, self._clip_hi = self.s0 - 0.01 * span, self.s1 + 0.01 * span
        self._rounding = 1e-12 * max(1.0, abs(span))

    def _make_classifier(self):
        """The face's classifier, and the parameter box (u0, u1, v0, v1) whose points need none: the
        face's domain shrunk by 1e-7 of its size where every edge of the face lies on a side of that
        domain (a rectangle in (u, v), as the gear solids' flank, fillet and spur land faces are:
        their points inside it are inside the face), and the classifier agrees at its middle;
        else an empty box (every point classified)."""
        self._classifier = BRepTopAdaptor_FClass2d(self.face, 1e-9)
        self._inner = (math.inf, -math.inf, math.inf, -math.inf)
        sides = []
        exp = TopExp_Explorer(self.face, TopAbs_EDGE)
        while exp.More():
            curve = BRepAdaptor_Curve2d(TopoDS.Edge_s(exp.Current()), self.face)
            exp.Next()
            kind = curve.GetType()
            if kind == GeomAbs_Line:
                ends = [curve.Value(curve.FirstParameter()), curve.Value(curve.LastParameter())]
            elif kind == GeomAbs_BSplineCurve:  # straight only if its poles are (they bound it)
                spline = curve.BSpline()
                ends = [spline.Pole(i) for i in range(1, spline.NbPoles() + 1)]
            else:
                return
            us, vs = {q.X() for q in ends}, {q.Y() for q in ends}
            if len(us) == 1:
                sides.append((0, us.pop()))
            elif len(vs) == 1:
                sides.append((1, vs.pop()))
            else:
                return
        u = [c for axis, c in sides if axis == 0]
        v = [c for axis, c in sides if axis == 1]
        if not u or not v:
            return
        box = (min(u), max(u), min(v), max(v))
        if any(c not in box[2 * axis:2 * axis + 2] for axis, c in sides):
            return
        if self._classifier.Perform(gp_Pnt2d(0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3]))) != TopAbs_IN:
            return
        mu, mv = 1e-7 * max(1.0, box[1] - box[0]), 1e-7 * max(1.0, box[3] - box[2])
        self._inner = (box[0] + mu, box[1] - mu, box[2] + mv, box[3] - mv)

    def _solve_all(self, ts, still: bool = False) -> list | None:
        """Section points (x, y) at the face parameters ``ts``, in order (each solve starts from the
        last one's result), None where the plane misses the face. One loop for all of them: the
        solves are OCCT surface evaluations (most points need one), each a few microseconds, which
        the overhead of a call per point would double.

        ``still``: None instead as soon as a solve misses the face or ends at another parameter
        than it started from (the guess left as it was before the call)."""
        start = guess = self._guess
        p, du, dv = self._p, self._du, self._dv
        d1, z, along_u = self.surface.D1, self.z, self.along_u
        lo, hi = self.s0 - self._rounding, self.s1 + self._rounding
        # the box needing no classifier (no point is inside a NaN box: the classifier is made first)
        u0, u1, v0, v1 = self._inner if self._inner is not None else (math.nan,) * 4
        out = []
        for t in ts:
            s = at = guess
            if along_u:
                d1(t, s, p, du, dv)
                dz = dv.Z()
            else:
                d1(s, t, p, du, dv)
                dz = du.Z()
            x, y, pz = p.Coord()  # one call for the three (a call costs as much as a solve's arithmetic)
            f = pz - z
            # most points lie on the plane at the last solve's parameter (the guess, in range: the
            # face's middle or a solve's result): Newton's step would be 0 and leave it there
            if f != 0.0 or dz == 0.0:
                s, at = self._newton(t, s, f, dz)
                x, y, _ = p.Coord()  # where the surface was last evaluated, at ``at``
                if s is None or not (lo <= s <= hi):
                    if still:
                        return None
                    out.append(None)
                    continue
                if still and s != start:
                    return None
                self._guess = guess = s
            u, v = (t, s) if along_u else (s, t)
            if not (u0 < u < u1 and v0 < v < v1):
                if self._inner is None:
                    self._make_classifier()
                    u0, u1, v0, v1 = self._inner
                if not (u0 < u < u1 and v0 < v < v1) and self._classifier.Perform(gp_Pnt2d(u, v)) == TopAbs_OUT:
                    if still:
                        return None
                    out.append(None)
                    continue
            if s != at:  # the last step moved the point
                d1(u, v, p, du, dv)
                x, y, _ = p.Coord()
            out.append((x, y))
        return out

    def _newton(self, t: float, s: float, f: float, dz: float):
        """Newton's method for the parameter across the plane at ``t``, from ``s``, where the surface
        lies ``f`` above the plane and rises ``dz`` per unit (the first evaluation, already made):
        (the parameter, the one the surface was last evaluated at), or (None, None)."""
        p, du, dv = self._p, self._du, self._dv
        d1, z, along_u = self.surface.D1, self.z, self.along_u
        clip_lo, clip_hi, rounding = self._clip_lo, self._clip_hi, self._rounding
        last = math.inf
        at = s
        for i in range(40):
            if i:
                at = s
                if along_u:
                    d1(t, s, p, du, dv)
                    dz = dv.Z()
                else:
                    d1(s, t, p, du, dv)
                    dz = du.Z()
                f = p.Z() - z
            if f == 0.0 and dz != 0.0:  # on the plane where evaluated: the step would be 0
                return s, at
            if dz == 0.0:
                return None, None
            step = f / dz
            s = min(max(s - step, clip_lo), clip_hi)
            # converged, or down to rounding: a step no smaller than the last one once it is below
            # 1e-12 of the range (z of a point tens of mm up is only good to ~1e-14)
            if abs(step) <= 1e-15 * max(1.0, abs(s)) or abs(f) < 1e-15 or \
                    (abs(step) >= last and abs(step) <= rounding):
                return s, at
            last = abs(step)
        return None, None

    def point(self, t: float):
        """Section point (x, y) at face parameter ``t``, or None off the face."""
        xy = self._solve_all((float(t),))[0]
        return None if xy is None else np.array(xy)

    def xy(self, t: float):
        """:meth:`point` as a tuple of two floats (no array: for a caller that solves thousands of
        points one at a time and does its arithmetic on floats)."""
        return self._solve_all((float(t),))[0]

    def xy_all(self, ts) -> list:
        """:meth:`xy` at each of ``ts`` in turn, in one call."""
        return self._solve_all([float(t) for t in ts])

    def xy_still(self, ts) -> list | None:
        """:meth:`xy_all` if every point lies on the face and its solve ends at the parameter it
        started from (the last solve's result): then each point is the same whatever was solved
        before it, in any order. Else None, the curve as before the call."""
        return self._solve_all([float(t) for t in ts], still=True)


@dataclass
class Section:
    """The section of a solid with the plane at height ``z`` (mm).

    ``curves`` one :class:`SectionCurve` per face that crosses the plane; ``points`` ``(n, 2)``
    samples along them, ``edge_index`` ``(n,)`` which curve each came from, ``params`` ``(n,)``
    the curve parameter of each.
    """

    z: float
    curves: list
    points: np.ndarray
    edge_index: np.ndarray
    params: np.ndarray

    def closest_point(self, xy, candidates) -> tuple[float, np.ndarray, int]:
        """Nearest point of the section curves ``candidates`` to ``xy``: (distance, point, curve).

        Starts from the nearest sample and refines on the curve to ~1e-13 of its parameter.
        """
        xy = np.asarray(xy, dtype=float)
        best = (math.inf, None, -1)
        for e in candidates:
            rows = np.nonzero(self.edge_index == e)[0]
            d = np.linalg.norm(self.points[rows] - xy, axis=1)
            j = int(np.argmin(d))
            t, p = _refine(self, e, rows, j, lambda q: float(np.linalg.norm(q - xy)))
            dist = float(np.linalg.norm(p - xy))
            if dist < best[0]:
                best = (dist, p, e)
        return best


def _refine(cut: Section, e: int, rows: np.ndarray, j: int, objective):
    """Minimise ``objective(point)`` over curve ``e`` between the samples either side of row j."""
    curve = cut.curves[e]
    params = cut.params[rows]
    lo = params[max(0, j - 1)]
    hi = params[min(len(rows) - 1, j + 1)]

    def f(t):
        p = curve.point(t)
        return math.inf if p is None else objective(p)

    res = minimize_scalar(f, bounds=(min(lo, hi), max(lo, hi)), method="bounded",
                          options={"xatol": 1e-14 * max(1.0, abs(hi))})
    p = curve.point(res.x)
    if p is None or objective(p) > objective(cut.points[rows[j]]):
        return params[j], cut.points[rows[j]]
    return res.x, p


def section(shape: TopoDS_Shape, z: float, samples_per_face: int = 64) -> Section:
    """Cut ``shape`` with the plane at height ``z``: every face that crosses it, sampled at
    ``samples_per_face`` evenly spaced parameters (points off the face are dropped)."""
    curves, pts, idx, prm = [], [], [], []
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        face = TopoDS.Face_s(exp.Current())
        exp.Next()
        ad = BRepAdaptor_Surface(face)
        if ad.GetType() == GeomAbs_Plane and abs(abs(ad.Plane().Axis().Direction().Z()) - 1.0) < 1e-12:
            continue  # parallel to the section plane
        curve = SectionCurve(face, z, ad)
        # two passes: even in the parameter, then even in arc length along the first pass
        t, xy = _on_face(curve, np.linspace(curve.t0, curve.t1, samples_per_face))
        if not xy.size:
            continue
        if len(xy) > 2:
            gap = np.diff(xy, axis=0)
            steps = np.sqrt(gap[:, 0] * gap[:, 0] + gap[:, 1] * gap[:, 1])  # numpy's norm of each, the same bits
        # the second pass only where the first is uneven (the gear solids' faces run by arc
        # length, so theirs is even already: one pass halves the cost of a section)
        if len(xy) > 2 and (len(xy) < samples_per_face or steps.max() > 2.0 * max(steps.min(), 1e-300)):
            arc = np.concatenate([[0.0], np.cumsum(steps)])
            again = np.interp(np.linspace(0.0, arc[-1], samples_per_face), arc, t)
            t, xy = _on_face(curve, np.unique(np.concatenate([again, t[[0, -1]]])))
        pts.append(xy)
        prm.append(t)
        idx.append(np.full(len(t), len(curves)))
        curves.append(curve)
    if not curves:
        return Section(z, [], np.empty((0, 2)), np.empty(0, int), np.empty(0))
    return Section(z, curves, np.concatenate(pts), np.concatenate(idx), np.concatenate(prm))


def _on_face(curve: SectionCurve, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The parameters ``t`` at which ``curve`` lies on its face, and its points there ``(k, 2)``."""
    xy = curve.xy_all(t)
    on = [j for j, q in enumerate(xy) if q is not None]
    if len(on) < len(xy):
        t, xy = t[on], [xy[j] for j in on]
    return t, (np.array(xy) if xy else np.empty((0, 2)))


def boolean_section(shape: TopoDS_Shape, z: float, samples_per_edge: int = 64) -> np.ndarray:
    """Points ``(n, 2)`` of OCCT's boolean section (``BRepAlgoAPI_Section``) at height ``z``:
    slow (~10 ms per face), kept to cross-check :func:`section`."""
    op = BRepAlgoAPI_Section(shape, gp_Pln(gp_Pnt(0, 0, z), gp_Dir(0, 0, 1)), False)
    op.Approximation(True)
    op.ComputePCurveOn1(False)
    op.Build()
    if not op.IsDone():
        raise RuntimeError(f"section at z={z} failed")
    out = []
    exp = TopExp_Explorer(op.Shape(), TopAbs_EDGE)
    while exp.More():
        ad = BRepAdaptor_Curve(TopoDS.Edge_s(exp.Current()))
        for t in np.linspace(ad.FirstParameter(), ad.LastParameter(), samples_per_edge):
            p = ad.Value(float(t))
            out.append((p.X(), p.Y()))
        exp.Next()
    return np.array(out).reshape(-1, 2)


def _polar_in_tooth_frame(profile: ToothProfile, z: float, xy: np.ndarray):
    """Radius, tooth index and signed polar angle from that tooth's centreline, section at z."""
    ang = np.arctan2(xy[:, 1], xy[:, 0]) - section_rotation(profile.spec, z)
    tooth = np.round(ang / profile.pitch_angle)
    local = ang - tooth * profile.pitch_angle
    return np.hypot(xy[:, 0], xy[:, 1]), tooth.astype(int) % profile.teeth, local


def involute_deviation(profile: ToothProfile, z: float, xy: np.ndarray) -> np.ndarray:
    """Signed deviation (mm, + = outside the tooth) of points ``(n, 2)`` of a section at height
    ``z`` from the exact involute flank on their side of their tooth, along the involute normal.

    Points below the base circle get NaN. Uses the fact that involutes of one base circle are
    parallel curves r_b * (difference of their base-circle angles) apart.
    """
    rad, _, local = _polar_in_tooth_frame(profile, z, xy)
    with np.errstate(invalid="ignore"):
        alpha = np.arccos(profile.base_radius / rad)
    inv = involute(alpha)
    return profile.base_radius * (np.abs(local) + inv - profile.base_half_angle)


@dataclass(frozen=True)
class FlankDeviation:
    """Deviation of a section's flanks from the exact involute (mm); ``flanks`` how many of the
    2 z flanks had sample points; ``points`` how many points were compared."""

    z: float
    max_abs: float
    rms: float
    mean: float
    points: int
    flanks: int


def flank_deviation(shape: TopoDS_Shape, profile: ToothProfile, z: float, samples_per_face: int = 64,
                    margin: float | None = None, cut: Section | None = None) -> FlankDeviation:
    """Section ``shape`` at height ``z`` and compare every flank point with the exact involute.

    Flank points are those with radius strictly between the start of the usable involute and
    the tip circle, ``margin`` (default 1e-4 m_n) away from both.
    """
    cut = cut or section(shape, z, samples_per_face)
    if margin is None:
        margin = 1e-4 * profile.spec.module
    rad, tooth, local = _polar_in_tooth_frame(profile, z, cut.points)
    sel = (rad > profile.involute_start_radius + margin) & (rad < profile.tip_radius - margin)
    dev = involute_deviation(profile, z, cut.points[sel])
    flanks = len(set(zip(tooth[sel].tolist(), (local[sel] > 0).tolist())))
    if dev.size == 0:
        return FlankDeviation(z, math.nan, math.nan, math.nan, 0, 0)
    return FlankDeviation(z, float(np.max(np.abs(dev))), float(np.sqrt(np.mean(dev ** 2))),
                          float(np.mean(dev)), int(dev.size), flanks)


def _flank_samples(profile: ToothProfile, cut: Section, tooth: int, upper: bool):
    rad, t, local = _polar_in_tooth_frame(profile, cut.z, cut.points)
    sel = (t == tooth % profile.teeth) & ((local > 0) == upper)
    sel &= (rad >= profile.involute_start_radius) & (rad <= profile.tip_radius)
    return np.nonzero(sel)[0]


def _support(cut: Section, rows: np.ndarray, direction: np.ndarray) -> tuple[float, np.ndarray]:
    """max of p . direction over the section curves of ``rows``, refined on the curve."""
    proj = cut.points[rows] @ direction
    j = rows[int(np.argmax(proj))]
    e = int(cut.edge_index[j])
    same = np.nonzero(cut.edge_index == e)[0]
    _, p = _refine(cut, e, same, int(np.nonzero(same == j)[0][0]), lambda q: -float(q @ direction))
    return float(p @ direction), p


def _on_flank(profile: ToothProfile, radius: float) -> bool:
    """Inside the usable involute, not on its ends (a contact at the tip corner is no flank contact)."""
    return profile.involute_start_radius * (1 - 1e-12) <= radius < profile.tip_radius * (1 - 1e-9)


@dataclass(frozen=True)
class SpanMeasurement:
    """Span (base tangent length) over ``k`` teeth measured on a section (mm).

    ``transverse`` is the caliper width in the transverse plane; ``normal`` = transverse x
    cos(base helix angle), the value a disc micrometer reads on a helical gear. ``contact_radii``
    are the radii where the anvils touch; ``on_involute`` whether both lie on the usable flank.
    """

    k: int
    transverse: float
    normal: float
    contact_radii: tuple[float, float]
    on_involute: bool


def span_on_section(shape: TopoDS_Shape, profile: ToothProfile, k: int, z: float = 0.0,
                    first_tooth: int = 0, cut: Section | None = None) -> SpanMeasurement:
    """Measure the span over teeth ``first_tooth .. first_tooth + k - 1`` on the section at ``z``:
    two parallel anvils perpendicular to the group's bisector touch the outer flanks."""
    if not 1 <= k < profile.teeth:
        raise ValueError(f"k must be in [1, {profile.teeth - 1}]")
    cut = cut or section(shape, z, 128)
    spec = profile.spec
    gamma = (first_tooth + (k - 1) / 2) * profile.pitch_angle + section_rotation(spec, z)
    d = np.array([-math.sin(gamma), math.cos(gamma)])
    hi, p_hi = _support(cut, _flank_samples(profile, cut, first_tooth + k - 1, True), d)
    lo, p_lo = _support(cut, _flank_samples(profile, cut, first_tooth, False), -d)
    width = hi + lo
    radii = (float(np.hypot(*p_lo)), float(np.hypot(*p_hi)))
    on = all(_on_flank(profile, r) for r in radii)
    return SpanMeasurement(k, width, width * math.cos(spec.base_helix_angle), radii, on)


@dataclass(frozen=True)
class BallMeasurement:
    """Size over two balls (pins for a spur gear) of ``diameter`` measured on a section (mm).

    ``size`` = distance between the ball centres + diameter (the two spaces are opposite for an
    even tooth count, as nearly opposite as possible for an odd one, in one transverse plane).
    ``centre_radius`` is the radius of the ball centres; ``contact_radius`` where a ball touches
    the flank; ``on_involute`` whether that lies on the usable involute.
    """

    diameter: float
    size: float
    centre_radius: float
    contact_radius: float
    on_involute: bool


def over_balls_on_section(shape: TopoDS_Shape, profile: ToothProfile, diameter: float, z: float = 0.0,
                          cut: Section | None = None) -> BallMeasurement:
    """Measurement over balls of ``diameter`` (pins for spur gears) on the section at height z.

    In a transverse plane through its centre, a ball of radius d/2 touching a helicoid flank is
    d / (2 cos(base helix angle)) from the involute section (involute helicoids of one base
    cylinder are parallel surfaces r_b delta cos(beta_b) apart); for a spur gear that is d/2.
    """
    cut = cut or section(shape, z, 128)
    spec = profile.spec
    need = diameter / 2 / math.cos(spec.base_helix_angle)
    z_teeth = profile.teeth
    phi = section_rotation(spec, z)
    spaces = (0, z_teeth // 2)  # space j lies between tooth j and tooth j + 1

    def centre(space: int):
        gamma = (space + 0.5) * profile.pitch_angle + phi
        u = np.array([math.cos(gamma), math.sin(gamma)])
        rows = np.concatenate([_flank_samples(profile, cut, space, True),
                               _flank_samples(profile, cut, space + 1, False)])
        cands = sorted(set(cut.edge_index[rows].tolist()))

        def gap(radius):
            return cut.closest_point(radius * u, cands)[0] - need

        # a centre nearer the root circle than the ball's radius would put the ball into the root: below
        # it the flanks' distance (they start at the involute) need not fall with the radius
        r_lo, r_hi = profile.root_radius + need, profile.tip_radius + diameter
        if gap(r_lo) >= 0 or gap(r_hi) <= 0:
            raise ValueError(f"a ball of {diameter} mm does not sit between the flanks of space {space}")
        rc = brentq(gap, r_lo, r_hi, xtol=1e-14, rtol=1e-15)
        _, contact, _ = cut.closest_point(rc * u, cands)
        return rc * u, float(np.hypot(*contact))

    c1, contact1 = centre(spaces[0])
    c2, contact2 = centre(spaces[1])
    size = float(np.linalg.norm(c1 - c2)) + diameter
    on = all(_on_flank(profile, r) for r in (contact1, contact2))
    return BallMeasurement(diameter, size, float(np.hypot(*c1)), contact1, on)


def mesh_deviation(triangles: np.ndarray, profile: ToothProfile, face_width: float, step: float = 2e-4,
                   z0: float = 0.0) -> float:
    """Largest distance (mm) of a tessellated gear body's side from the exact tooth surface.

    ``triangles`` ``(n, 3, 3)`` (mm, the gear in its build position, face from ``z0`` to
    ``z0 + face_width``). Checks the centroid and edge midpoints of every triangle that is not
    on an end face and lies outside the root circle: each point is turned back by the section
    rotation at its height and into tooth 0's pitch sector, and its distance to a polyline of the
    exact outline (points ``step`` mm apart, so the polyline itself is good to ~step^2/(8 rho)) is
    taken. For a helical gear that transverse distance bounds the true 3-D distance from above.
    """
    tri = np.asarray(triangles, dtype=float)
    pts = np.concatenate([tri.mean(axis=1), 0.5 * (tri[:, 0] + tri[:, 1]), 0.5 * (tri[:, 1] + tri[:, 2]),
                          0.5 * (tri[:, 2] + tri[:, 0])])
    z = pts[:, 2] - z0
    zt = 1e-6 * max(1.0, face_width)  # end faces, allowing for STL single precision
    rad = np.hypot(pts[:, 0], pts[:, 1])
    keep = (z > zt) & (z < face_width - zt) & (rad > profile.root_radius * (1 - 1e-9))
    pts, z = pts[keep], z[keep]
    ang = np.arctan2(pts[:, 1], pts[:, 0]) - section_rotation(profile.spec, z)
    ang = ang - np.round(ang / profile.pitch_angle) * profile.pitch_angle
    rad = np.hypot(pts[:, 0], pts[:, 1])
    xy = np.column_stack([rad * np.cos(ang), rad * np.sin(ang)])
    # tooth 0 with the half root arcs either side covers the sector [-pi/z, pi/z]
    lower_root = [s.rotated(-profile.pitch_angle) for s in profile.pitch_segments() if s.kind == "root_arc"]
    chain = lower_root + profile.pitch_segments()
    dense = sample_outline(chain, step)
    d, i = cKDTree(dense).query(xy)
    # refine against the two polyline pieces around the nearest vertex
    best = d.copy()
    for off in (-1, 0):
        a = dense[np.clip(i + off, 0, len(dense) - 1)]
        b = dense[np.clip(i + off + 1, 0, len(dense) - 1)]
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", xy - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
        best = np.minimum(best, np.linalg.norm(a + t[:, None] * ab - xy, axis=1))
    return float(np.max(best)) if best.size else 0.0


__all__ = ["Section", "SectionCurve", "section", "boolean_section", "involute_deviation", "FlankDeviation", "flank_deviation",
           "SpanMeasurement", "span_on_section", "BallMeasurement", "over_balls_on_section", "mesh_deviation"]
