"""The section's Newton solve (geargen.cad.measure.SectionCurve._solve) after issue 28 (its OCCT
points and vectors made once per face; the last surface evaluation skipped where the last Newton
step left the point where it was evaluated) against the code it replaced, kept here as the
reference: the same points to the last bit, in the same order of calls (each solve starts from
the last one's result), on the faces of a spur and a helical gear solid."""

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
        new, ref = SectionCurve(face, z), ReferenceCurve(face, z)
        # sorted (as the section samples and bisects) and shuffled (far jumps: several Newton steps),
        # and some beyond the face's range (points off the face)
        span = new.t1 - new.t0
        ts = np.concatenate([np.linspace(new.t0, new.t1, 64), rng.uniform(new.t0 - 0.1 * span, new.t1 + 0.1 * span, 64)])
        for t in ts:
            a, b = new.point(t), ref.point(t)
            assert (a is None) == (b is None)
            if a is None:
                off += 1
            else:
                assert np.array_equal(a, b)
                checked += 1
    assert checked > 1000 and off > 0  # both branches were met


def test_whole_section_as_before(helical21, monkeypatch):
    z = 0.61 * helical21.spec.face_width
    got = section(helical21.shape, z, 64)
    monkeypatch.setattr("geargen.cad.measure.SectionCurve._solve", ReferenceCurve._solve)
    want = section(helical21.shape, z, 64)
    assert np.array_equal(got.points, want.points) and np.array_equal(got.params, want.params)
    assert np.array_equal(got.edge_index, want.edge_index)
