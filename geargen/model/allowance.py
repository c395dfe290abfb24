"""Each gear's tooth-thickness allowance in a design: entered, or chosen from the backlash ranges.

One place decides them (:func:`drive_allowances`), so the gear JSON, the drawings and the
backlash-range check read the same numbers. Order: allowances entered in the gear tables
(``thickness_upper_deviation_*``/``thickness_lower_deviation_*``) are kept; then, mesh by mesh
of the resolved drive (:func:`geargen.model.resolve`), a mesh whose gears have none gets them
from its design range by the centre-distance-tolerance route
(:func:`geargen.core.allowance.allowances_for_backlash`) at the centre distance where it runs,
+- ``[checks] centre_distance_tolerance_*``. A gear in two meshes (the split pinion's output,
the dual pinion's input and clusters in their two loops) is decided by the first; the second
mesh's mate takes the rest of that mesh's thinning, and a mesh whose two gears are both decided
is only checked (:mod:`geargen.checks.allowance`).
"""

from __future__ import annotations

from geargen.core.allowance import BacklashRoute, ThicknessAllowance, allowances_for_backlash
from geargen.errors import DesignError
from geargen.design.gear import GearSpec, with_changes
from geargen.model.layout import Layout, MeshPlacement
from geargen.units import LENGTH_SUFFIXES

__all__ = ["entered_allowance", "range_fields", "design_centre_distance", "mesh_route", "drive_allowances", "TOLERANCE_KEY"]

#: the design key of the centre-distance tolerance (unit suffix appended)
TOLERANCE_KEY = "checks.centre_distance_tolerance"


def entered_allowance(spec: GearSpec, where: str | None = None) -> ThicknessAllowance | None:
    """The allowance the gear table gives (``thickness_*_deviation_*``), or None."""
    if getattr(spec, "thickness_deviations", None) is None:  # a rack states no thickness allowance
        return None
    upper, lower = spec.thickness_deviations
    return ThicknessAllowance(upper, lower, "entered (design file: thickness_upper_deviation, "
                              "thickness_lower_deviation)", where or f"gears.{spec.name}.thickness_upper_deviation_um")


def range_fields(layout: Layout, mesh: MeshPlacement) -> tuple[str, str]:
    """The design keys of ``mesh``'s backlash range (min, max), in the design's length unit."""
    u = layout.design.length_unit
    if mesh.name.startswith("stage_"):
        from geargen.design.stages import stages
        # a planetary stage's sun-planet meshes are stage_NAME_sun_PLANET: the stage's range
        name = next((st.name for st in stages(layout.design) if st.kind == "planetary"
                     and mesh.name.startswith(f"stage_{st.name}_sun_")), mesh.name[len('stage_'):])
        base = f"stages.{name}.circumferential_backlash_"
        return f"{base}min_{u}", f"{base}max_{u}"
    if layout.kind in ("split_pinion", "axial_preload"):
        return f"layout.circumferential_backlash_min_{u}", f"layout.circumferential_backlash_max_{u}"
    if layout.kind == "rack_dual_pinion":
        return f"layout.path_backlash_min_{u}", f"layout.path_backlash_max_{u}"
    n = mesh.name.split("_")[0][len("mesh"):]  # mesh1_a -> 1
    return (f"synthesis.circumferential_backlash_min_mesh{n}_{u}",
            f"synthesis.circumferential_backlash_max_mesh{n}_{u}")


def design_centre_distance(layout: Layout, mesh: MeshPlacement) -> float:
    """The operating centre distance (mm) at which the design file states ``mesh``'s backlash
    range: a dual-pinion loop mesh's ``[synthesis] centre_distance_meshN`` (the preload carriage
    places mesh 1 where the loop closes, which moves with the teeth made: not a size to tolerance),
    else where the mesh is placed (a stage's or the split pinion's centre distance)."""
    if layout.kind == "dual_pinion" and mesh.name.startswith("mesh") and layout.synthesis is not None:
        return float(layout.synthesis.inputs.centre_distance(int(mesh.name.split("_")[0][len("mesh"):])))
    return mesh.centre_distance


def mesh_route(layout: Layout, mesh: MeshPlacement, centre_distance_tolerance: float) -> BacklashRoute:
    """What the route asks of ``mesh``: its design range at the design's centre distance
    (:func:`design_centre_distance`), +- the tolerance."""
    u = layout.design.length_unit
    lo_key, hi_key = range_fields(layout, mesh)
    return BacklashRoute(mesh.backlash_min, mesh.backlash_max, design_centre_distance(layout, mesh),
                         centre_distance_tolerance,
                         lo_key, hi_key, f"{TOLERANCE_KEY}_{u}", u, LENGTH_SUFFIXES[u])


def drive_allowances(layout: Layout, centre_distance_tolerance: float = 0.0,
                     strict: bool = True) -> dict[str, ThicknessAllowance]:
    """Gear name (``GearSpec.name``) -> allowance, for every gear of ``layout`` that has one
    (entered, or chosen from a mesh's backlash range; see the module docstring). A mesh whose
    range no allowance meets raises the DesignError naming it; with ``strict`` False its gears are
    left without one (the drawings then say so; the check's verdict has the failure)."""
    out: dict[str, ThicknessAllowance] = {}
    for placed in layout.gears:
        for g in placed.gears:
            a = entered_allowance(g)
            if a is not None:
                out[g.name] = a
    for mesh in layout.meshes:
        if not (mesh.backlash_max > 0 and mesh.centre_distance == mesh.centre_distance):
            continue
        g1, g2 = mesh.gear1, mesh.gear2
        if g1.name in out and g2.name in out:
            continue
        try:
            a1, a2 = allowances_for_backlash(with_changes(g1, thinning=0.0), with_changes(g2, thinning=0.0),
                                             mesh_route(layout, mesh, centre_distance_tolerance),
                                             out.get(g1.name), out.get(g2.name))
        except DesignError:
            if strict:
                raise
            continue
        out.setdefault(g1.name, a1)
        out.setdefault(g2.name, a2)
    return out
