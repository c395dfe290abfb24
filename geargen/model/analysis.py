"""Analysis of the resolved drive: the one stiffness and preload summary every command reports
(``geargen stiffness`` prints it, ``geargen build`` puts it in its report)."""

from __future__ import annotations

import math

from typing import Any

from geargen.core.involute import working_pressure_angle_at
from geargen.design.assembly import Design
from geargen.model.layout import Layout


def loop_error_travels(layout: Layout | None) -> tuple[dict[str, float] | None, str]:
    """The synthesis error budget as carriage travels (mm: ``sum``, ``rss``, ``mean``) when the
    preload carriage of the drive absorbs them, and a note saying where the loop error comes from."""
    run = layout.synthesis if layout is not None else None
    if run is None or run.budget is None:
        return None, "loop error from the design's [preload] (no [synthesis] with [errors] budget)"
    if layout.identity.preload_method not in ("radial", "axial") or (layout.drive is not None
                                                            and not layout.drive.carriage_error_budget):
        return None, ("loop error from the design's [preload]: the synthesis budget is a carriage travel, and this "
                      "drive's preload is not set by a sliding carriage")
    b = run.budget
    return {"sum": b.dx1_sum, "rss": b.dx1_rss, "mean": b.dx1_mean}, \
        "loop error from the synthesis error budget (Appendix rules)"


#: the [stiffness.components] shaft names and the placed shaft (geargen.model.shafts) each means
_PLACED = {"cluster": "cluster_a", "input": "input", "output": "output"}


def placed_components(design, layout: Layout | None) -> tuple:
    """The stiffness components of ``design`` (a design, or its stiffness-step sections already read:
    :class:`geargen.design.stiffness.StiffnessDesign`), those with ``from_geometry = true`` completed from the
    placed shafts (:func:`geargen.model.shafts.shafts`): a shaft in bending, or on its bearings
    (``shaft_support``), gets the shaft's diameter, its bearings' span and the gear's mid-face
    distance from the lower bearing (beyond the span: overhung); a shaft
    in torsion the diameter and the length between the two loads it carries (the cluster's two
    gears, the input gear and its bevel gear)."""
    from dataclasses import replace

    from geargen.design.stiffness import StiffnessDesign, stiffness_design
    from geargen.errors import DesignError
    from geargen.model.shafts import shafts

    sections = design if isinstance(design, StiffnessDesign) else stiffness_design(design)
    components = sections.stiffness.components
    if not any(c.from_geometry for c in components):
        return components
    placed = shafts(layout) if layout is not None else {}
    out = []
    for c in components:
        if not c.from_geometry:
            out.append(c)
            continue
        where = f"stiffness.components.{c.name}.from_geometry"
        if c.kind in ("shaft_bending", "shaft_support"):
            shaft = next((sh for sh in placed.values() if c.gear in sh.loads), None)
            if shaft is None:
                raise DesignError(where, f"no placed shaft carries gears.{c.gear}", "a design whose [parts] places "
                                  "its shafts, or the lengths given here with from_geometry = false")
            if not shaft.diameter > 0:
                raise DesignError(where, f"the shaft of gears.{c.gear} fills its bore, and the gear gives none",
                                  "bore_diameter_* in the gear table")
            if len(shaft.bearings) != 2:
                raise DesignError(where, f"the shaft of gears.{c.gear} has {len(shaft.bearings)} bearings",
                                  "two bearings")
            extra = {}
            if c.kind == "shaft_support":
                e = c.elastic_modulus or sections.stiffness.elastic_modulus
                extra = dict(bore_diameter=shaft.bore or c.bore_diameter,
                             support_stiffness=tuple(_support_stiffness(b, c.stiffness, e, placed)
                                                     for b in shaft.supports()),
                             other_loads=_other_mesh_forces(shaft, c.gear, layout))
            out.append(replace(c, placed=True, diameter=shaft.diameter,
                               span=None if c.support == "cantilever" else shaft.span,
                               load_position=shaft.load_position(c.gear), **extra))
        else:
            if c.gear is not None:
                shaft = next((sh for sh in placed.values() if c.gear in sh.loads), None)
                what = f"shaft carrying gears.{c.gear}"
            else:
                shaft = placed.get(_PLACED.get(c.shaft, ""))
                what = f"{c.shaft} shaft"
            if shaft is None or (shaft.twist is None and len(shaft.loads) < 2):
                raise DesignError(where, f"no placed {what} with two loads", "a design whose [parts] "
                                  "places its shafts, or diameter and length given here with from_geometry = false")
            if not shaft.diameter > 0:
                raise DesignError(where, f"the placed {what} fills the gears' bore, and gears.{next(iter(shaft.loads))} "
                                  "gives none", "bore_diameter_* in the gear table")
            out.append(replace(c, placed=True, diameter=shaft.diameter, bore_diameter=shaft.bore or c.bore_diameter,
                               length=shaft.twist_length))
    return tuple(out)


def _mesh_force_direction(own: tuple[float, float], own_base: float, mate: tuple[float, float], mate_base: float,
                          sense: int) -> float:
    """Angle (rad) of the force a mate exerts on an external gear at ``own`` through their mesh: along
    the line of action, tangent to both base circles (``cos(alpha_w) = (r_b + r_b') / a`` at the placed
    centre distance ``a``), pushing the gear away from its mate and turning it ``sense`` (+1
    counter-clockwise)."""
    towards = math.atan2(mate[1] - own[1], mate[0] - own[0])
    alpha = working_pressure_angle_at(float(own_base + mate_base), math.dist(own, mate), clamp=True)
    # -sin(alpha) along the centre line, sense cos(alpha) across it
    return towards + math.pi - sense * (math.pi / 2 - alpha)


def _other_mesh_forces(shaft, gear: str, layout: Layout) -> tuple[tuple[float, float, float], ...]:
    """The mesh forces on ``shaft`` besides ``gear``'s, for a shaft that passes torque from one gear to
    another (a cluster): each ``(distance from the lower support, force over gear's force, angle from
    gear's force)``. Both carry the shaft's torque, so each is ``r_b(gear) / r_b(other)`` of it; each
    acts on the line of action of its mesh's working flank (:attr:`MeshPlacement.working_flank`, the
    flank the preload loads). Empty when no other gear on the shaft meshes."""
    from geargen.errors import DesignError
    where = f"stiffness.components (the shaft of gears.{gear})"
    forces = {}
    for m in layout.meshes:
        if not m.engaged:
            continue
        for own_part, own, mate_part, mate in ((m.part1, m.gear1, m.part2, m.gear2), (m.part2, m.gear2, m.part1, m.gear1)):
            if own.name not in shaft.loads or math.dist(layout.gear(own_part).centre, shaft.centre) > 1e-9:
                continue
            if not m.working_flank:
                raise DesignError(where, f"{m.name} has no working flank to say which line of action it loads",
                                  "a mesh of the preloaded loop")
            # gear 1's flank leading in that turn carries the load; the mesh force turns both gears back
            sense = -1 if m.working_flank.split()[-1] == "ccw" else 1
            forces[own.name] = (own.base_radius, _mesh_force_direction(
                shaft.centre, own.base_radius, layout.gear(mate_part).centre, mate.base_radius, sense))
    if gear not in forces or len(forces) == 1:
        return ()
    if len(forces) > 2:
        raise DesignError(where, f"{len(forces)} gears mesh on one shaft: how the torque divides between them is not "
                          "known", "two meshing gears on a supported shaft")
    (other,) = [n for n in forces if n != gear]
    (base, angle), (other_base, other_angle) = forces[gear], forces[other]
    return ((shaft.load_position(other), base / other_base, other_angle - angle),)


def _support_stiffness(bearing, bearing_stiffness: float, elastic_modulus: float, placed: dict) -> float:
    """Radial stiffness (N/mm) of one support of a shaft: a bearing's own, or, for a part that
    holds the shaft on another placed shaft (``via``), that shaft's lateral stiffness at this
    height on its own bearings (each ``bearing_stiffness``)."""
    from geargen.core.stiffness import supported_shaft_compliance
    if bearing.via is None:
        return bearing_stiffness
    host = next(sh for sh in placed.values() if sh.name == bearing.via)
    compliance, _ = supported_shaft_compliance(elastic_modulus, host.diameter, host.span,
                                               bearing.centre_z - host.lower_support,
                                               (bearing_stiffness, bearing_stiffness), host.bore)
    return 1.0 / compliance


def stiffness(design: Design | None, layout: Layout | None) -> tuple[Any, str]:
    """``(StiffnessSummary or None, note)``: None when the design has no [stiffness]/[preload]. With
    ``layout`` (the resolved drive of ``design``) the sections it carries are read, not the design's
    again (``design`` may then be None: :func:`drive_stiffness`)."""
    given = layout.resolved.has if layout is not None else design.section
    if not given("stiffness") or not given("preload"):
        return None, "no [stiffness] and [preload] sections"
    from geargen.core.stiffness import stiffness_summary
    travels, note = loop_error_travels(layout)
    # a drive that places its own preload lever (the axial preload: the output rotation per mm of the
    # input's slide) reports it, and its sliding fit's friction, which widens the preload band
    report = layout.drive_report if layout is not None else {}
    lever = report.get("stiffness", {}).get("lever_rad_per_mm")
    friction = report.get("friction", {}).get("friction_to_preload", 0.0)
    source, sections = ((layout.resolved.stiffness_inputs, layout.resolved.stiffness) if layout is not None
                        else (design, design))
    return stiffness_summary(source, travels, components=placed_components(sections, layout),
                             beam_supports=beam_supports(layout, layout.engagement if layout else None),
                             placed_lever=lever, placed_friction=friction), note


def drive_stiffness(layout: Layout) -> tuple[Any, str]:
    """:func:`stiffness` of the resolved drive ``layout``, from the sections it carries."""
    return stiffness(None, layout)


def beam_supports(layout: Layout | None, engagement) -> tuple[float, float] | None:
    """Radial stiffness (N/mm) of the structure under a beam-spring pinion's two bearings, as the
    drive kind gives it (:attr:`geargen.drives.kind.DriveKind.beam_supports`: the C-axis's drive
    column, once the sliding pinions' strokes, ``engagement``, are known); None for rigid supports
    or a drive without a beam-spring pinion."""
    if layout is None or layout.drive is None or layout.drive.beam_supports is None:
        return None
    return layout.drive.beam_supports(layout, engagement)


__all__ = ["loop_error_travels", "placed_components", "stiffness", "drive_stiffness", "beam_supports"]
