"""Double-helical (herringbone) gear solids: two helical halves of opposite hand, one solid.

Conventions (those of :mod:`geargen.cad.gear_solid`, which builds the halves):

- axis on z, face from z = 0 to z = face width ``b``; each half has the face width
  ``h = (b - gap) / 2`` (:attr:`GearSpec.half_face_width`);
- the first half, z in [0, h], has the spec's hand: its section at height z is the z = 0 section
  turned by ``section_rotation(spec, z)``; the second half, z in [h + gap, b], has the other hand
  and its section at ``h + gap`` is the first half's section at ``h`` (the teeth line up across
  the gap, as the hob cuts them), so at height z it is turned by ``section_rotation(spec, b - z)``;
- in the centre gap the blank is a cylinder just below the teeth's root circle (0.01 m_n deeper,
  :data:`geargen.profile.tooth.GROOVE_DEPTH_COEFFICIENT`): a relief groove at the root diameter, the run-out for the hob
  or the shaper between the halves;
- bore and keyway run through; a hub stands below z = 0.

How: the first half is the face-by-face helical body of :mod:`geargen.cad.gear_solid`; the second
is its mirror image in the plane z = b / 2. A mirror in a plane normal to the axis turns a helix
of one hand into the other hand and leaves every transverse section's outline as it is, so the
second half's flanks are the same exact involute helicoids and, with no gap, its apex section is
the first half's apex section edge for edge: the flanks meet at the apex on the edges they share.
Both halves, the groove (a cylinder between the halves' annular inner ends) and the bore are put
together face by face in one shell (:func:`geargen.cad.gear_solid.toothed_body`), with no boolean:
the 30-tooth bench herringbone in 0.03 s, where fusing the two halves with the kernel's glue
option took 0.7 s. Only a hub is fused on (glue option: it only touches the first end face).
"""

from __future__ import annotations

from dataclasses import fields

from OCP.BOPAlgo import BOPAlgo_GlueFull, BOPAlgo_GlueShift

from geargen.cad.gear_solid import GearSolid, check_solid, default_tolerance, hub_body, toothed_body
from geargen.cad.kernel import fused_solid
from geargen.design.gear import GearSpec, Hub
from geargen.families.double_helical.spec import DoubleHelicalGearSpec
from geargen.errors import BuildError
from geargen.profile.tessellate import Layer
from geargen.profile.tooth import ToothProfile, centre_gap_radius, tooth_profile, twist_rate


def _internal(field: str, problem: str, allowed: str = "") -> ValueError:
    """Numbers no builder can make: the resolved drive checks its parts before the CAD layer sees
    them (geargen.model.bodies), so reaching here is a bug, not bad input."""
    return ValueError(f"{field}: {problem}" + (f" (allowed: {allowed})" if allowed else ""))


def half_spec(spec: GearSpec) -> GearSpec:
    """The first (lower) half of a double-helical ``spec`` as an external helical gear: face width
    :attr:`~GearSpec.half_face_width`, the spec's hand, bore and keyway but no hub (the hub belongs
    to the whole gear), no accuracy grade (the grade's scope is the whole gear's face width)."""
    if not isinstance(spec, DoubleHelicalGearSpec):
        raise _internal("kind", f"{spec.kind!r} is not a double_helical gear", "'double_helical'")
    hub = Hub(spec.hub.bore_diameter, spec.hub.keyway_width, spec.hub.keyway_depth)
    given = {f.name: getattr(spec, f.name) for f in fields(GearSpec) if f.init}  # the external gear's keys
    return GearSpec(**{**given, "centre_gap": 0.0, "face_width": spec.half_face_width, "hub": hub,
                       "accuracy_grade": None, "accuracy_standard": None})


def double_helical_layers(spec: GearSpec, profile: ToothProfile) -> list[Layer]:
    """The layers of the solid for the exact STL mesher (:mod:`geargen.profile.tessellate`)."""
    h, gap, k = spec.half_face_width, spec.centre_gap, twist_rate(spec)
    layers = []
    if spec.hub.hub_length > 0:
        layers.append(Layer(-spec.hub.hub_length, 0.0, radius=spec.hub.hub_diameter / 2))
    layers.append(Layer(0.0, h, profile, twist=k))
    if gap > 0:
        layers.append(Layer(h, h + gap, radius=centre_gap_radius(spec, profile)))
    layers.append(Layer(h + gap, spec.face_width, profile, phase=k * h, twist=-k))
    return layers


def _fused(parts: list, glue: str):
    """Fuse solids that only touch (the hub on the first end face): the kernel's glue option
    (``shift``: the faces coincide in part) skips the face-face intersection, the slow part."""
    return fused_solid(parts, "boolean fuse of the double-helical gear's hub failed",
                       glue=BOPAlgo_GlueFull if glue == "full" else BOPAlgo_GlueShift)


def build_double_helical(spec: GearSpec, tolerance: float | None = None, check: bool = False) -> GearSolid:
    """Build a double-helical ``spec`` as one closed solid (conventions in the module docstring).

    ``tolerance`` (mm, default :func:`~geargen.cad.gear_solid.default_tolerance`) bounds the
    flank splines' distance from the exact helicoid, as for a helical gear; the mirror adds
    nothing to it. ``check`` validates the solid (:class:`BuildError` if it is not one valid
    closed solid). Raises :class:`GeometryError` for parameters that cannot make a gear.
    """
    half = half_spec(spec)
    profile = tooth_profile(half)
    mirror = (spec.centre_gap, centre_gap_radius(spec, profile))
    if tolerance is not None:
        shape, faces = toothed_body(half, profile, tolerance, mirror)
    else:
        tolerance = default_tolerance(spec)
        try:
            shape, faces = toothed_body(half, profile, tolerance, mirror)
        except BuildError as exc:
            if "no fit within" not in str(exc):
                raise
            # some fillets of large modules do not fit 2 nm on 64 spans; 10x that (0.02 um) is still
            # 5x inside the 0.1 um flank bound, and GearSolid.tolerance records it
            tolerance *= 10
            shape, faces = toothed_body(half, profile, tolerance, mirror)
    hub = hub_body(spec, "bottom")
    if hub is not None:
        shape = _fused([shape, hub], "shift")
    if check:
        problem = check_solid(shape)
        if problem:
            raise BuildError(f"{spec.name}: {problem}")
    return GearSolid(shape, spec.name, spec, profile, tolerance, spec.length_unit,
                     double_helical_layers(spec, profile), tuple(faces))


__all__ = ["build_double_helical", "half_spec", "double_helical_layers"]
