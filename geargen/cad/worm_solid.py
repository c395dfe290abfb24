"""The solid of a ZA worm (geargen.core.worm gives the exact geometry).

The thread spaces are screw solids bounded by ruled faces between B-spline helices that
interpolate the exact helices at ``points_per_turn`` angles with the angle as parameter, so each
ruling joins points of one angle: the straight ZA generator of the Archimedean helicoid (flank
within ~10 nm of it at 64 points a turn; tests/cad/test_worm_solid.py measures it). The spaces run
past the tip and the ends; they are cut from the exact tip cylinder, and the face length by two
planes. The root is the spaces' ruled face between the two root helices (on the root cylinder).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geargen.core.worm import WormGeometry, flank_axial_offset, worm_geometry
from geargen.design.worm import WormSpec
from geargen.errors import BuildError


@dataclass
class WormPartSolid:
    """A built worm or worm wheel: the OCCT shape and what it was built from."""

    shape: object
    name: str
    spec: object
    geometry: WormGeometry
    length_unit: str
    profile: object = None  # the cylindrical gears' ToothProfile; none here

    def volume(self) -> float:
        from geargen.cad.gear_solid import solid_volume
        return solid_volume(self.shape)

    def is_valid(self) -> bool:
        from geargen.cad.gear_solid import check_solid
        return check_solid(self.shape) is None


def _checked(shape, name: str, check: bool):
    from geargen.cad.gear_solid import check_solid
    if check:
        problem = check_solid(shape)
        if problem is not None:
            raise BuildError(f"{name}: not one valid closed solid: {problem}")
    return shape


def _single(shape):
    """The one solid of a boolean result (a compound of one solid), or the shape if several."""
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer
    exp = TopExp_Explorer(shape, TopAbs_SOLID)
    found = []
    while exp.More():
        found.append(exp.Current())
        exp.Next()
    return found[0] if len(found) == 1 else shape


def _helix_curve(radius: float, p: float, offset: float, thetas: np.ndarray):
    """A B-spline interpolating the helix (r cos t, r sin t, p t + offset) at ``thetas``, with the
    angles as parameters: curves of one thread share their parameter, so a ruled surface between
    two of them joins points of the same angle (the straight ZA generator in the axial half-plane)."""
    from OCP.GeomAPI import GeomAPI_Interpolate
    from OCP.gp import gp_Pnt
    from OCP.TColgp import TColgp_HArray1OfPnt
    from OCP.TColStd import TColStd_HArray1OfReal
    pts = TColgp_HArray1OfPnt(1, len(thetas))
    params = TColStd_HArray1OfReal(1, len(thetas))
    for i, th in enumerate(thetas, 1):
        pts.SetValue(i, gp_Pnt(radius * math.cos(th), radius * math.sin(th), p * th + offset))
        params.SetValue(i, float(th))
    interp = GeomAPI_Interpolate(pts, params, False, 1e-9)
    interp.Perform()
    if not interp.IsDone():
        raise BuildError("worm: helix interpolation failed")
    return interp.Curve()


def _screw_solid(g: WormGeometry, p: float, corners, thetas: np.ndarray):
    """The screw solid whose axial section is the quadrilateral ``corners`` ((r, flank side, axial
    shift) each, at angle 0) swept over the angles ``thetas``: four ruled faces on interpolated
    helices and two planar end caps, sewn into a solid."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakePolygon, BRepBuilderAPI_MakeFace, \
        BRepBuilderAPI_MakeSolid, BRepBuilderAPI_Sewing
    from OCP.BRepFill import BRepFill
    from OCP.gp import gp_Pnt
    from OCP.TopoDS import TopoDS
    edges = [BRepBuilderAPI_MakeEdge(_helix_curve(r, p, shift + float(flank_axial_offset(g, side, r)), thetas)).Edge()
             for r, side, shift in corners]
    sewing = BRepBuilderAPI_Sewing(1e-6)
    for i in range(4):
        sewing.Add(BRepFill.Face_s(edges[i], edges[(i + 1) % 4]))
    for th in (thetas[0], thetas[-1]):
        poly = BRepBuilderAPI_MakePolygon()
        for r, side, shift in corners:
            poly.Add(gp_Pnt(r * math.cos(th), r * math.sin(th), p * th + shift + float(flank_axial_offset(g, side, r))))
        poly.Close()
        sewing.Add(BRepBuilderAPI_MakeFace(poly.Wire(), True).Face())
    sewing.Perform()
    shell = TopoDS.Shell_s(sewing.SewedShape())
    solid = BRepBuilderAPI_MakeSolid(shell).Solid()
    from OCP.BRepLib import BRepLib
    BRepLib.OrientClosedSolid_s(solid)
    return solid


def build_worm(spec: WormSpec, check: bool = False, points_per_turn: int = 64) -> WormPartSolid:
    """The worm, axis Z, mid plane z = 0; its flank ``side`` at radius r and angle t is at
    z = p t + s (t_x/2 - (r - r1) tan alpha_x) (thread k shifted by k p_x): the core's fixed frame
    at phi1 = 0 with X = z, Y = a - x, Z = -y (:func:`worm_to_mesh`)."""
    import cadquery as cq

    s = spec.set
    g = worm_geometry(s)
    m = s.axial_module
    ra, rf = g.worm_tip_diameter / 2, g.worm_root_diameter / 2
    length = s.worm_face_length
    p = s.hand_sign * g.screw_parameter
    r_out = ra + 0.2 * m  # the spaces run out past the tip cylinder (a transverse cut, not a tangent one)
    extra = g.axial_pitch + 0.5 * m
    half_turns = (length / 2 + extra) / g.lead
    n = max(int(math.ceil(2 * half_turns * points_per_turn)), 16)
    thetas = np.linspace(-2 * math.pi * half_turns, 2 * math.pi * half_turns, n + 1)
    # the space after thread 0: its +1 flank, thread 1's -1 flank (an axial pitch on), the root
    # helicoid at r_f; the other starts' spaces are it turned by -k p_x / p (a screw shift of k p_x).
    # (Building them shifted instead gave a solid that OCCT cut only in part.)
    space = cq.Solid(_screw_solid(g, p, ((rf, 1, 0.0), (r_out, 1, 0.0), (r_out, -1, g.axial_pitch),
                                         (rf, -1, g.axial_pitch)), thetas))
    spaces = [space.rotate(cq.Vector(0, 0, 0), cq.Vector(0, 0, 1), math.degrees(-k * g.axial_pitch / p))
              for k in range(s.starts)]
    # the spaces end (their planar caps) inside a longer blank, then the face length is cut by two
    # planes across the threads: a cut whose caps lie outside the blank fails in OCCT (0 solids)
    long_length = length + 2 * extra + 2 * g.axial_pitch + 2 * m  # the spaces reach +-(L/2 + extra + p_x)
    blank = cq.Solid.makeCylinder(ra, long_length, cq.Vector(0, 0, -long_length / 2))
    threaded = blank
    for space in spaces:  # one at a time: OCCT mis-cut two threads' spaces given together
        threaded = threaded.cut(space)
    slab = cq.Solid.makeCylinder(ra + m, length, cq.Vector(0, 0, -length / 2))
    shape = _single(threaded.intersect(slab).wrapped)
    return WormPartSolid(_checked(shape, spec.name, check), spec.name, spec, g, s.length_unit)


def worm_to_mesh(points, centre_distance: float):
    """Worm-solid points (..., 3) -> the core's fixed mesh frame (wheel axis Z, worm axis the line
    (t, a, 0)) at worm angle 0: X = z, Y = a - x, Z = -y (a proper rotation and a shift)."""
    pts = np.asarray(points, float)
    return np.stack([pts[..., 2], centre_distance - pts[..., 0], -pts[..., 1]], axis=-1)


__all__ = ["WormPartSolid", "build_worm", "worm_to_mesh"]
