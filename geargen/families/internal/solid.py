"""Internal (ring) gear solids: the rim cylinder less the toothed hole, spur or helical.

Conventions as :mod:`geargen.cad.gear_solid`: axis on z, the face from z = 0 to the face width,
space 0 centred on +x at z = 0, the section at height z turned by ``section_rotation(spec, z)``.

How: the hole - the region inside the ring's exact inner outline (:mod:`geargen.profile.internal`)
- is built face by face exactly as an external gear's body (:func:`geargen.cad.gear_solid.toothed_body`:
one degree-7 B-spline face per flank and fillet within the tolerance of the exact curve, exact
cylinders for the tip and root lands, helicoids by the fitted rotation). The ring's shell is then
put together from the hole's side faces (turned inside out), the rim cylinder's side, and two
annular caps: the rim's end discs with the hole's end wires added as holes. No boolean: the
faces and edges are the hole's own (a boolean cut gives the same solid 50x slower).
"""

from __future__ import annotations

from OCP.BRep import BRep_Builder
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
from OCP.GeomAbs import GeomAbs_Plane
from OCP.TopAbs import TopAbs_FACE, TopAbs_FORWARD, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS

from geargen.cad.gear_solid import GearSolid, check_solid, default_tolerance, toothed_body
from geargen.cad.kernel import closed_solid
from geargen.design.gear import GearSpec
from geargen.errors import BuildError
from geargen.profile.internal import InternalProfile, internal_profile


def _internal(field: str, problem: str, allowed: str = "") -> ValueError:
    """Numbers no builder can make: the resolved drive checks its parts before the CAD layer sees
    them (geargen.model.bodies), so reaching here is a bug, not bad input."""
    return ValueError(f"{field}: {problem}" + (f" (allowed: {allowed})" if allowed else ""))


def build_hole(spec: GearSpec, profile: InternalProfile, tolerance: float):
    """The toothed hole as a solid (the external-gear builder on the ring's inner outline)."""
    return toothed_body(spec, profile, tolerance)


def _faces(shape):
    out = []
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        out.append(TopoDS.Face_s(exp.Current()))
        exp.Next()
    return out


def _plane_height(face) -> float | None:
    """z of a face on a plane normal to the axis, None for any other face."""
    ad = BRepAdaptor_Surface(face)
    if ad.GetType() != GeomAbs_Plane:
        return None
    plane = ad.Plane()
    if abs(abs(plane.Axis().Direction().Z()) - 1.0) > 1e-12:
        return None
    return plane.Location().Z()


def _plane_normal_z(face) -> float:
    """z component of the normal of the face's underlying plane (the face taken FORWARD)."""
    return BRepAdaptor_Surface(TopoDS.Face_s(face.Oriented(TopAbs_FORWARD))).Plane().Axis().Direction().Z()


def _annulus(builder: BRep_Builder, disc, hole_cap):
    """The rim's end disc with the hole's end wire as a hole; the disc's orientation."""
    disc_f = TopoDS.Face_s(disc.Oriented(TopAbs_FORWARD))
    face = TopoDS.Face_s(disc_f.EmptyCopied())
    exp = TopExp_Explorer(disc_f, TopAbs_WIRE)
    while exp.More():
        builder.Add(face, exp.Current())
        exp.Next()
    # a hole runs against the outer wire: reverse the hole's own (outer) wire when both faces' planes
    # point the same way
    flip = _plane_normal_z(disc) * _plane_normal_z(hole_cap) > 0
    exp = TopExp_Explorer(hole_cap.Oriented(TopAbs_FORWARD), TopAbs_WIRE)
    while exp.More():
        builder.Add(face, exp.Current().Reversed() if flip else exp.Current())
        exp.Next()
    return face.Oriented(disc.Orientation())


def ring_from_hole(hole, rim_radius: float, length: float):
    """The ring solid around ``hole`` (a closed solid spanning z = 0 .. length inside the rim)."""
    builder = BRep_Builder()
    rim = BRepPrimAPI_MakeCylinder(rim_radius, length).Shape()
    rim_side, discs = None, {}
    for f in _faces(rim):
        z = _plane_height(f)
        if z is None:
            rim_side = f
        else:
            discs[round(z / length)] = f
    sides, caps = [], {}
    for f in _faces(hole):
        z = _plane_height(f)
        if z is None:
            sides.append(f)
        else:
            caps[round(z / length)] = f
    if rim_side is None or set(discs) != {0, 1} or set(caps) != {0, 1}:
        raise BuildError("the hole or the rim does not have two end caps")
    # the hole's sides turned: the hole's outside is the ring's inside
    return closed_solid(builder, [f.Reversed() for f in sides] + [rim_side]
                        + [_annulus(builder, discs[end], caps[end]) for end in (0, 1)])


def build_internal(spec: GearSpec, tolerance: float | None = None, check: bool = False) -> GearSolid:
    """Build the ring ``spec`` (kind ``internal``) as one closed solid.

    ``tolerance`` (mm, default :func:`geargen.cad.gear_solid.default_tolerance`) bounds the distance
    of the flank and fillet splines from the exact curves. With ``check`` the solid is validated
    (BuildError if not one valid closed solid). GeometryError for rings that cannot be cut
    (:func:`geargen.profile.internal.internal_profile`).
    """
    if spec.kind != "internal":
        raise _internal("kind", f"{spec.kind!r}: build_internal builds internal gears", "'internal'")
    if tolerance is None:
        tolerance = default_tolerance(spec)
    profile = internal_profile(spec)
    hole, faces = build_hole(spec, profile, tolerance)
    shape = ring_from_hole(hole, profile.rim_radius, spec.face_width)
    if check:
        problem = check_solid(shape)
        if problem:
            raise BuildError(f"{spec.name}: {problem}")
    return GearSolid(shape, spec.name, spec, profile, tolerance, spec.length_unit, [], tuple(faces))


__all__ = ["build_internal", "build_hole", "ring_from_hole"]
