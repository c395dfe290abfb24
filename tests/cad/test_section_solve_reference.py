"""The section's Newton solve (geargen.cad.measure.SectionCurve._solve_all) after issue 28 (its OCCT
points and vectors made once per face; the last surface evaluation skipped where the last Newton
step left the point where it was evaluated; all of a call's points in one loop; the face's
classifier skipped inside the parameter box of a face bounded by parameter lines) against the
code it replaced, kept here as the reference: the same points to the last bit, in the same order
of calls (each solve starts from the last one's result), on the faces of a spur and a helical
gear solid; and the chords bisected level by level against the bisection chord after chord."""

import math

import numpy as np
import pytest
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepTopAdaptor import BRepTopAdaptor_FClass2d
from OCP.GeomAbs import GeomAbs_Plane
from OCP.gp import gp_Pnt, gp_Pnt2d, gp_Vec
from OCP.TopAbs import TopAbs_FACE, TopAbs_OUT
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS

from geargen.cad.measure import SectionCurve, section

pytestmark = pytest.mark.slow


class ReferenceCurve(SectionCurve):
    def _solve(self, t: float):
        """geargen before issue 28."""
        s = self._guess
        p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
        span = self.s1 - self.s0
        last = math.inf
        for _ in range(40):
            u, v = (t, s) if self.along_u else (s, t)
            self.surface.D1(u, v, p, du, dv)
            f = p.Z() - self.z
            dz = dv.Z() if self.along_u else du.Z()
            if dz == 0.0:
                return None
            step = f / dz
            s = min(max(s - step, self.s0 - 0.01 * span), self.s1 + 0.01 * span)
            if abs(step) <= 1e-15 * max(1.0, abs(s)) or abs(f) < 1e-15 or \
                    (abs(step) >= last and abs(step) <= 1e-12 * max(1.0, abs(span))):
                break
            last = abs(step)
        else:
            return None
        if not (self.s0 - 1e-12 * max(1.0, abs(span)) <= s <= self.s1 + 1e-12 * max(1.0, abs(span))):
            return None
        self._guess = s
        u, v = (t, s) if self.along_u else (s, t)
        if self._classifier is None:
            self._classifier = BRepTopAdaptor_FClass2d(self.face, 1e-9)
        if self._classifier.Perform(gp_Pnt2d(u, v)) == TopAbs_OUT:
            return None
        self.surface.D1(u, v, p, du, dv)
        return np.array([p.X(), p.Y()])

    def _solve_all(self, ts):
        """geargen before issue 28's last change: one call per point (the solve above)."""
        return [ReferenceCurve._solve(self, float(t)) for t in ts]


def _faces(shape):
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        face = TopoDS.Face_s(exp.Current())
        exp.Next()
        ad = BRepAdaptor_Surface(face)
        if not (ad.GetType() == GeomAbs_Plane and abs(abs(ad.Plane().Axis().Direction().Z()) - 1.0) < 1e-12):
            yield face


@pytest.mark.parametrize("which", ["spur112", "helical21"])
def test_section_points_as_before(which, request):
    gear = request.getfixturevalue(which)
    rng = np.random.default_rng(28)
    faces = list(_faces(gear.shape))
    z = 0.37 * gear.spec.face_width
    checked = off = 0
    for face in faces[:: max(1, len(faces) // 40)]:  # ~40 faces of every kind around the gear
        new, ref, floats = SectionCurve(face, z), ReferenceCurve(face, z), SectionCurve(face, z)
        # sorted (as the section samples and bisects) and shuffled (far jumps: several Newton steps),
        # and some beyond the face's range (points off the face)
        span = new.t1 - new.t0
        ts = np.concatenate([np.linspace(new.t0, new.t1, 64), rng.uniform(new.t0 - 0.1 * span, new.t1 + 0.1 * span, 64)])
        for t in ts:
            a, b = new.point(t), ref.point(t)
            assert floats.xy(t) == (None if a is None else tuple(a))  # the same solve, as floats
            assert (a is None) == (b is None)
            if a is None:
                off += 1
            else:
                assert np.array_equal(a, b)
                checked += 1
    assert checked > 1000 and off > 0  # both branches were met



@pytest.mark.parametrize("which", ["spur112", "helical21"])
def test_points_left_unclassified_are_inside(which, request):
    """The solve skips the face's classifier inside the box :meth:`SectionCurve._make_classifier`
    finds: every point of a grid over that box, its edges 1e-7 of its size inside the face's
    domain, is inside the face by the classifier; the flank and fillet faces (B-spline, bounded
    by parameter lines) have a box, a helical gear's land faces (bounded by helices) none."""
    from OCP.BRepTopAdaptor import BRepTopAdaptor_FClass2d
    from OCP.GeomAbs import GeomAbs_BSplineSurface
    from OCP.TopAbs import TopAbs_IN

    gear = request.getfixturevalue(which)
    faces = list(_faces(gear.shape))
    boxes = {True: 0, False: 0}
    for face in faces[:: max(1, len(faces) // 60)]:
        curve = SectionCurve(face, 0.5 * gear.spec.face_width)
        curve._make_classifier()
        u0, u1, v0, v1 = curve._inner
        spline = curve.surface.GetType() == GeomAbs_BSplineSurface
        if spline:
            assert u0 < u1 and v0 < v1
        if u0 >= u1:
            boxes[False] += 1
            continue
        boxes[True] += 1
        classifier = BRepTopAdaptor_FClass2d(face, 1e-9)
        eps_u, eps_v = 1e-9 * (u1 - u0), 1e-9 * (v1 - v0)
        for u in np.concatenate([np.linspace(u0, u1, 9), [u0 + eps_u, u1 - eps_u]]):
            for v in np.concatenate([np.linspace(v0, v1, 9), [v0 + eps_v, v1 - eps_v]]):
                assert classifier.Perform(gp_Pnt2d(float(u), float(v))) == TopAbs_IN
    assert boxes[True] > 20
    if which == "spur112":  # every face a parameter rectangle (the lands' helices are straight)
        assert boxes[False] == 0
    else:
        assert boxes[False] > 5


def test_whole_section_as_before(helical21, monkeypatch):
    z = 0.61 * helical21.spec.face_width
    got = section(helical21.shape, z, 64)
    monkeypatch.setattr("geargen.cad.measure.SectionCurve._solve_all", ReferenceCurve._solve_all)
    want = section(helical21.shape, z, 64)
    assert np.array_equal(got.points, want.points) and np.array_equal(got.params, want.params)
    assert np.array_equal(got.edge_index, want.edge_index)


def reference_sections_from_shape(spec, shape, planes, samples_per_face=64, source="", chord_tolerance=5e-5):
    """geargen.checks.solids.sections_from_shape before issue 28 (its chords bisected on arrays)."""
    from geargen.checks.solids import GearSections

    segs, worst = [], 0.0
    for z in np.atleast_1d(planes):
        cut = section(shape, float(z), samples_per_face)
        parts = []
        for e, curve in enumerate(cut.curves):
            rows = np.nonzero(cut.edge_index == e)[0]
            if rows.size < 2:
                continue
            t = list(cut.params[rows])
            p = [q for q in cut.points[rows]]
            k = 0
            while k < len(t) - 1:
                if p[k] is None or p[k + 1] is None:
                    k += 1
                    continue
                tm = 0.5 * (t[k] + t[k + 1])
                q = curve.point(tm)
                if q is None:
                    ends = []
                    for on, off in ((t[k], tm), (t[k + 1], tm)):
                        for _ in range(40):
                            mid = 0.5 * (on + off)
                            if curve.point(mid) is None:
                                off = mid
                            else:
                                on = mid
                        ends.append(on)
                    t[k + 1:k + 1] = [ends[0], math.nan, ends[1]]
                    p[k + 1:k + 1] = [curve.point(ends[0]), None, curve.point(ends[1])]
                    continue
                dev = float(np.linalg.norm(q - 0.5 * (p[k] + p[k + 1])))
                if dev > chord_tolerance and abs(t[k + 1] - t[k]) > 1e-12 * max(1.0, abs(tm)):
                    t.insert(k + 1, tm)
                    p.insert(k + 1, q)
                    continue
                worst = max(worst, dev)
                k += 1
            for k in range(len(p) - 1):
                if p[k] is not None and p[k + 1] is not None:
                    parts.append(np.stack([p[k], p[k + 1]]))
        segs.append(np.array(parts) if parts else np.empty((0, 2, 2)))
    return GearSections(spec, np.atleast_1d(np.asarray(planes, dtype=float)), segs, worst, source)


@pytest.mark.parametrize("which", ["spur112", "helical21"])
def test_chord_bisected_sections_as_before(which, request):
    """Coarse and fine chords; a plane near an end face, where section curves end on a face's
    boundary (the bisection onto it)."""
    from geargen.checks.solids import sections_from_shape
    gear = request.getfixturevalue(which)
    planes = np.array([0.3, 0.5, 0.999]) * gear.spec.face_width
    for tolerance in (5e-5, 2e-3):
        got = sections_from_shape(gear.spec, gear.shape, planes, chord_tolerance=tolerance)
        want = reference_sections_from_shape(gear.spec, gear.shape, planes, chord_tolerance=tolerance)
        assert got.deviation == want.deviation
        for a, b in zip(got.segments, want.segments, strict=True):
            assert a.shape == b.shape and np.array_equal(a, b)


def test_still_solves_are_those_of_any_order(helical21):
    """SectionCurve.xy_still: where it gives points (the helical pinion's flanks at mid-face, where
    every solve ends at the parameter it starts from) they are those of xy_all in order and in
    reverse order; where a solve moves the guess (a plane off the middle: the first solve's Newton
    steps) it gives None and leaves the guess as it was."""
    faces = [f for f in _faces(helical21.shape) if BRepAdaptor_Surface(f).GetType() != GeomAbs_Plane]
    width = helical21.spec.face_width
    given = refused = 0
    for face in faces[:: max(1, len(faces) // 30)]:
        probe = SectionCurve(face, 0.5 * width)
        ts = np.linspace(probe.t0, probe.t1, 17)[1:-1]
        got = probe.xy_still(ts)
        if got is not None:
            assert got == SectionCurve(face, 0.5 * width).xy_all(ts)
            assert got[::-1] == SectionCurve(face, 0.5 * width).xy_all(ts[::-1])
            given += 1
        off = SectionCurve(face, 0.3 * width)
        guess = off._guess
        if off.xy_still(ts) is None:
            assert off._guess == guess
            refused += 1
    assert given > 10 and refused > 10
