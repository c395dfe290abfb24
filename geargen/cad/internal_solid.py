"""Internal (ring) gear solids: the rim cylinder less the toothed hole, spur or helical.

Conventions as :mod:`geargen.cad.gear_solid`: axis on z, the face from z = 0 to the face width,
space 0 centred on +x at z = 0, the section at height z turned by ``section_rotation(spec, z)``.

How: the hole - the region inside the ring's exact inner outline (:mod:`geargen.profile.internal`)
- is built face by face exactly as an external gear's body (:func:`geargen.cad.gear_solid._toothed_body`:
one degree-7 B-spline face per flank and fillet within the tolerance of the exact curve, exact
cylinders for the tip and root lands, helicoids by the fitted rotation), and cut from the rim
cylinder. A boolean cut keeps the cutting faces' surfaces, so the flanks are those fitted ones.
"""

from __future__ import annotations

from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
from OCP.TopTools import TopTools_ListOfShape

from geargen.cad.gear_solid import (GearSolid, _single_solid, _toothed_body, check_solid, default_tolerance)
from geargen.design.gear import GearSpec
from geargen.errors import BuildError, DesignError
from geargen.profile.internal import InternalProfile, internal_profile


def build_hole(spec: GearSpec, profile: InternalProfile, tolerance: float):
    """The toothed hole as a solid (the external-gear builder on the ring's inner outline)."""
    return _toothed_body(spec, profile, tolerance)


def build_internal(spec: GearSpec, tolerance: float | None = None, check: bool = False) -> GearSolid:
    """Build the ring ``spec`` (kind ``internal``) as one closed solid.

    ``tolerance`` (mm, default :func:`geargen.cad.gear_solid.default_tolerance`) bounds the distance
    of the flank and fillet splines from the exact curves. With ``check`` the solid is validated
    (BuildError if not one valid closed solid). GeometryError for rings that cannot be cut
    (:func:`geargen.profile.internal.internal_profile`).
    """
    if spec.kind != "internal":
        raise DesignError("kind", f"{spec.kind!r}: build_internal builds internal gears", "'internal'")
    if tolerance is None:
        tolerance = default_tolerance(spec)
    profile = internal_profile(spec)
    hole, faces = build_hole(spec, profile, tolerance)
    rim = BRepPrimAPI_MakeCylinder(profile.rim_radius, spec.face_width).Shape()
    op = BRepAlgoAPI_Cut()
    args, tools = TopTools_ListOfShape(), TopTools_ListOfShape()
    args.Append(rim)
    tools.Append(hole)
    op.SetArguments(args)
    op.SetTools(tools)
    op.SetFuzzyValue(0.0)
    op.Build()
    if not op.IsDone():
        raise BuildError(f"{spec.name}: cutting the teeth from the rim failed")
    shape = _single_solid(op.Shape())
    if check:
        problem = check_solid(shape)
        if problem:
            raise BuildError(f"{spec.name}: {problem}")
    return GearSolid(shape, spec.name, spec, profile, tolerance, spec.length_unit, [], tuple(faces))


__all__ = ["build_internal", "build_hole"]
