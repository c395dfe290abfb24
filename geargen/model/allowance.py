"""Each gear's tooth-thickness allowance in a drive, and the model's gear made within it: one decision.

The allowances (:func:`decide`). Allowances entered in the gear tables
(``thickness_upper_deviation_*``/``thickness_lower_deviation_*``) are kept; then, mesh by mesh, a
mesh whose gears have none gets them from its design range by the centre-distance-tolerance
route (:func:`geargen.core.allowance.allowances_for_backlash`) at the centre distance where the
mesh runs, +- ``[checks] centre_distance_tolerance_*``. That is where it is placed, except for a
mesh whose centre distance moves with the teeth made (a dual pinion's carriage mesh runs where the
loop closes): there it is where the mesh runs with its gears made at the middle of their
allowances (a fixed point: :mod:`geargen.drives.dual_pinion.place`), so the allowance does not
depend on the point the model is made at. A gear in two meshes
(the split pinion's output) is decided by the first; the second mesh's mate takes the rest of that
mesh's thinning, and a mesh whose two gears are both decided is only checked
(:mod:`geargen.checks.allowance`).

The model's gear (:func:`model_gears`): ``[layout] model_tooth_thickness`` says at which point of
its allowance every gear of the model is made (:data:`geargen.design.layout.MODEL_POINTS`;
``mid_tolerance`` by default), so the split of a mesh's thinning between its gears is the
allowance's, for the model too, and the solids, STEP, STL, DXF and gear data all show a gear that
passes its own drawing's inspection. ``as_designed`` (the default when a gear table gives its
thinning) keeps the gear tables' thinning; the check then holds each gear to its allowance.

The placements (``geargen.drives.*.place``) decide with :func:`model_gears` before they place,
from their meshes at those centre distances; :func:`drive_allowances` decides again from the
placed layout (drawings, gear data, checks; a mesh's ``allowance_centre_distance``): the same
function on the same gears and centre distances, so the same allowances.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable

from geargen.core.allowance import (BacklashRoute, ThicknessAllowance, allowances_for_backlash, made_at, thickest,
                                    thinnest)
from geargen.core.involute import tip_land_thickness
from geargen.design.gear import GearSpec, with_changes
from geargen.design.layout import MODEL_POINTS
from geargen.profile.tooth import MIN_TIP_LAND_MODULES
from geargen.errors import DesignError
from geargen.model.layout import Layout, MeshPlacement
from geargen.units import LENGTH_SUFFIXES

__all__ = ["entered_allowance", "MeshRange", "mesh_range", "design_tolerance", "decide", "model_gears", "model_source", "drive_allowances",
           "TOLERANCE_KEY", "POINT_KEY"]

#: the design key of the centre-distance tolerance (unit suffix appended)
TOLERANCE_KEY = "checks.centre_distance_tolerance"
#: the design key of the model's point in each allowance
POINT_KEY = "layout.model_tooth_thickness"


def entered_allowance(spec: GearSpec, where: str | None = None) -> ThicknessAllowance | None:
    """The allowance the gear table gives (``thickness_*_deviation_*``), or None."""
    if getattr(spec, "thickness_deviations", None) is None:  # a rack states no thickness allowance
        return None
    upper, lower = spec.thickness_deviations
    return ThicknessAllowance(upper, lower, "entered (design file: thickness_upper_deviation, "
                              "thickness_lower_deviation)", where or f"gears.{spec.name}.thickness_upper_deviation_um")


@dataclass(frozen=True)
class MeshRange:
    """What a mesh's allowances are decided from (mm): its two gears, its design range of
    circumferential backlash, the centre distance where it runs, and the design keys of the range
    (without their unit suffix)."""

    gear1: GearSpec
    gear2: GearSpec
    backlash_min: float
    backlash_max: float
    centre_distance: float
    range_keys: tuple[str, str]


def mesh_range(mesh: MeshPlacement) -> MeshRange:
    """A placed mesh as its allowances are decided from it: at its ``allowance_centre_distance``,
    else where it is placed."""
    c = mesh.allowance_centre_distance
    return MeshRange(mesh.gear1, mesh.gear2, mesh.backlash_min, mesh.backlash_max,
                     c if c == c else mesh.centre_distance, mesh.range_keys)


def _route(design, mesh: MeshRange, tolerance: float) -> BacklashRoute:
    u = design.length_unit
    lo_key, hi_key = (f"{key}_{u}" for key in mesh.range_keys)
    return BacklashRoute(mesh.backlash_min, mesh.backlash_max, mesh.centre_distance, tolerance, lo_key, hi_key,
                         f"{TOLERANCE_KEY}_{u}", u, LENGTH_SUFFIXES[u])


def design_tolerance(design) -> float:
    """The design's ``[checks] centre_distance_tolerance`` (mm; 0 when not given)."""
    from geargen.design.checks import checks_settings
    return checks_settings(design).centre_distance_tolerance


def _makeable(spec: GearSpec, allowance: ThicknessAllowance, route: BacklashRoute) -> None:
    """Refuse an allowance whose extremes are no teeth ``spec`` can have: thinned past a quarter
    pitch (:func:`geargen.core.allowance.at_deviation`), or the thinnest pointed (its tip land below
    the least the profile is built with), naming the key of the range's maximum."""
    thickest(spec, allowance)
    thin = thinnest(spec, allowance)
    land, least = tip_land_thickness(thin), MIN_TIP_LAND_MODULES * spec.module
    if land < least:
        k, u = route.scale, route.unit
        raise DesignError(route.field_max, f"{spec.name}: its thinnest tooth (lower deviation {allowance.lower_um:.4g} "
                          f"um) is pointed at the tip circle (tip land {land / k:.4g} {u}, below {least / k:.3g} {u}): "
                          f"the teeth interfere at {route.centre_distance / k:.6g} {u} unless thinned that far",
                          f"a smaller {route.field_max}, or a larger centre distance")


def decide(design, meshes: Iterable[MeshRange], tolerance: float | None = None, strict: bool = True,
           gears: Iterable[GearSpec] = ()) -> dict[str, ThicknessAllowance]:
    """Gear name -> allowance for every gear of ``meshes`` (and of ``gears``) that has one (see the
    module docstring); ``tolerance`` the centre-distance tolerance (mm; None: the design's). Of
    ``design`` only its ``length_unit`` is read when ``tolerance`` is given (the resolved drive passes
    its :class:`~geargen.design.resolved.DesignIdentity`). A mesh
    whose range no allowance meets, or whose allowance asks a gear for more thinning than it can
    take, raises the DesignError naming the key; with ``strict`` False its gears are left without
    one (the drawings then say so; the check's verdict has the failure)."""
    meshes = [m for m in meshes if m.backlash_max > 0 and m.centre_distance == m.centre_distance]
    f = design_tolerance(design) if tolerance is None else tolerance
    out: dict[str, ThicknessAllowance] = {}
    for g in [*gears, *(g for m in meshes for g in (m.gear1, m.gear2))]:
        a = entered_allowance(g)
        if a is not None:
            out.setdefault(g.name, a)
    for mesh in meshes:
        g1, g2 = mesh.gear1, mesh.gear2
        if g1.name in out and g2.name in out:
            continue
        try:
            a1, a2 = allowances_for_backlash(with_changes(g1, thinning=0.0), with_changes(g2, thinning=0.0),
                                             _route(design, mesh, f), out.get(g1.name), out.get(g2.name))
            for g, a in ((g1, a1), (g2, a2)):
                _makeable(g, a, _route(design, mesh, f))
        except DesignError:
            if strict:
                raise
            continue
        out.setdefault(g1.name, a1)
        out.setdefault(g2.name, a2)
    return out


def model_gears(design, point: str, meshes: Iterable[MeshRange],
                tolerance: float | None = None) -> dict[str, GearSpec]:
    """Gear name -> the gear as the model makes it, for every gear of ``meshes``: at ``point``
    (``[layout] model_tooth_thickness``, a key of :data:`MODEL_POINTS`) of its allowance
    (:func:`decide`, strict), or with ``"as_designed"`` the gear tables' own teeth."""
    meshes = list(meshes)
    specs = {g.name: g for m in meshes for g in (m.gear1, m.gear2)}
    if point == "as_designed":
        return specs
    allowances = decide(design, meshes, tolerance)
    weight = MODEL_POINTS[point][0]
    return {name: made_at(g, allowances[name], weight) if name in allowances else g for name, g in specs.items()}


def model_source(point: str) -> str:
    """Where a gear's modelled thinning comes from, as the layout and the gear data state it."""
    if point == "as_designed":
        return "design"
    return f"{point}: {MODEL_POINTS[point][1]} ([{POINT_KEY.replace('.', '] ')})"


def drive_allowances(layout: Layout, centre_distance_tolerance: float | None = None,
                     strict: bool = True) -> dict[str, ThicknessAllowance]:
    """Gear name (``GearSpec.name``) -> allowance, for every gear of ``layout`` that has one
    (:func:`decide` over its meshes where they are placed, in order; ``centre_distance_tolerance``
    None: the design's)."""
    f = layout.resolved.checks.centre_distance_tolerance if centre_distance_tolerance is None else centre_distance_tolerance
    return decide(layout.identity, [mesh_range(m) for m in layout.meshes], f, strict,
                  [g for placed in layout.gears for g in placed.gears])
