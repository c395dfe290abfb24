"""Every section of a design file, read and checked when the file is loaded.

:func:`validate_sections` is what :func:`geargen.design.assembly.load_design` runs after the
top-level keys, the drive and the gears: each further section is read by the module that owns
it (the same reader the step that uses it calls), then the rules between sections and whether
the hardware can be made:

=================  ==============================================================================
section            read and checked by
=================  ==============================================================================
[synthesis]        geargen.design.synthesis.synthesis_inputs (the four gears, Eq. 8 solvable)
[errors.*]         .synthesis.validate_error_budget, or .synthesis.error_table without [synthesis]
[monte_carlo]      .synthesis.monte_carlo_settings
[checks]           .checks.checks_settings (declared meshes name gears of the file)
[stiffness] ...    .stiffness: components, preload, flexures (stress at the travel), springs
                   (solid height, index, installed stress), beam pinion, engagement (lead)
[stages.*]         .stages.stages, check_stages
[layout]           .layout.layout_settings, check_layout
[parts]            .parts.parts_settings, check_parts
[export]           .export.export_settings
[train]            .train.train_settings
[dual_motor]       .train.dual_motor_spec ([checks] meshes declare its pairs)
[duty]             .duty.duty_settings (the spectrum, or [preload]'s maximum load)
[materials.*]      .duty.gear_materials (gear tables of the file, ISO 6336-5 hardness ranges)
=================  ==============================================================================

Whether each gear's tooth can be cut is checked where the gear tables are read
(:func:`geargen.design.feasibility.check_tooth`, from ``design_from_dict``).

Every problem is recorded in a :class:`~geargen.design.schema.Problems` and reported together.
A check that needs the gears runs only when every gear table was read: a broken gear is
reported once, not again by each section that names it.

:func:`key_schema` answers "what does the schema allow at this key" (the :class:`Field` or
:class:`~geargen.design.stiffness.Quantity` that owns it), for tools and tests that generate or
document design files.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, Mapping

from geargen.design.checks import CHECKS_FIELDS, CENTRE_KEYS, checks_settings
from geargen.design.duty import DUTY_FIELDS, DUTY_QUANTITIES, MATERIAL_FIELDS, duty_settings, gear_materials
from geargen.design.export import EXPORT_FIELDS, export_settings
from geargen.design.gear import GEAR_FIELDS
from geargen.design.layout import check_layout, layout_fields, layout_settings
from geargen.design.parts import check_parts, hardware_fields, parts_settings
from geargen.design.schema import Field, Problems
from geargen.design.stages import STAGE_FIELDS, check_stages, stages
from geargen.design.stiffness import (BEAM_FIELDS, BEAM_QUANTITIES, COMPONENT_FIELDS, COMPONENT_QUANTITIES,
                                      ENGAGEMENT_FIELDS, FLEXURE_FIELDS, FLEXURE_QUANTITIES, MODULI,
                                      PRELOAD_FIELDS, PRELOAD_QUANTITIES, SPRING_FIELDS, SPRING_QUANTITIES,
                                      STIFFNESS_FIELDS, Quantity, beam_pinion_spec_from_table,
                                      check_stiffness_gears, check_swept_spring, engagement_spec_from_table, flexure_spec_from_table,
                                      preload_spec_from_table, spring_spec_from_table, stiffness_spec_from_table)
from geargen.design.synthesis import (ERROR_FIELDS, GEAR_ROLES, MONTE_CARLO_FIELDS, SYNTHESIS_FIELDS,
                                      error_table, monte_carlo_settings, synthesis_inputs, validate_error_budget)
from geargen.design.train import (DUAL_MOTOR_FIELDS, DUAL_MOTOR_QUANTITIES, TRAIN_FIELDS, TRAIN_QUANTITIES,
                                  dual_motor_spec, train_settings)
from geargen.drives.keys import KEYS, kind_of
from geargen.errors import DesignError
from geargen.families.registry import FAMILIES

#: sections that need the drive type (the stiffness step reads it)
_NEED_DRIVE_TYPE = ("stiffness", "preload", "flexures", "springs", "beam_pinion", "engagement")


def validate_sections(design, problems: Problems, gears_complete: bool = True,
                      gear_names: tuple[str, ...] | None = None) -> None:
    """Read and check every section of ``design`` past its gears, recording each problem in
    ``problems``. ``gears_complete``: every gear table was read (else the checks that need the
    gears are skipped); ``gear_names``: the gear tables the file has, read or not."""
    run = problems.run
    sections = design.sections
    unit = design.length_unit
    gears = design.gears if gears_complete else None
    names = tuple(gear_names if gear_names is not None else design.gears)

    if "synthesis" in sections and gears_complete:
        run(synthesis_inputs, design)
    if "errors" in sections:
        if "synthesis" in sections:
            run(validate_error_budget, design)
        else:
            for gear in sections["errors"]:
                if gear not in names:
                    problems.add(DesignError(f"errors.{gear}", "no gear of this name", ", ".join(names)))
                elif not isinstance(sections["errors"][gear], Mapping):
                    problems.add(DesignError(f"errors.{gear}", "expected a table"))
                else:
                    run(error_table, design, gear, False)
    if "monte_carlo" in sections:
        run(monte_carlo_settings, design)
    if "checks" in sections and gears_complete:
        run(checks_settings, design)

    if design.drive_type is None and any(s in sections for s in _NEED_DRIVE_TYPE):
        present = next(s for s in _NEED_DRIVE_TYPE if s in sections)
        problems.add(DesignError("drive.type", f"missing: [{present}] describes a drive of a type", "'type1', 'type2'"))
    stiffness = None  # the gear roles the [engagement] check needs (defaults without [stiffness])
    if "stiffness" in sections:
        stiffness = spec = run(stiffness_spec_from_table, sections["stiffness"], KEYS[kind_of(design)].STIFFNESS_TRAIN)
        if spec is not None and gears_complete:
            run(check_stiffness_gears, spec, design.gears)
    if "preload" in sections:
        run(preload_spec_from_table, sections["preload"])
    if "flexures" in sections:
        run(flexure_spec_from_table, sections["flexures"], unit)
    if "springs" in sections:
        run(spring_spec_from_table, sections["springs"], unit)
    if "beam_pinion" in sections:
        run(beam_pinion_spec_from_table, sections["beam_pinion"], gears)
    if "engagement" in sections:
        roles_read = stiffness is not None or "stiffness" not in sections
        run(engagement_spec_from_table, sections["engagement"], gears if roles_read else None, unit, stiffness)

    settings = None
    if "layout" in sections or "synthesis" in sections:  # a synthesis alone is a dual-pinion layout
        settings = run(layout_settings, design)
        if settings is not None and gears_complete:
            run(check_layout, design, settings)
    if "stages" in sections and gears_complete:
        if run(stages, design) is not None:
            # a [layout] that cannot be read names no drive that takes stages
            run(check_stages, design, settings is not None and KEYS[kind_of(design)].TAKES_STAGES)
    if "parts" in sections:
        settings = run(parts_settings, design)
        if settings is not None and gears_complete:
            run(check_parts, design, settings)
        if settings is not None and settings.get("spring_model") == "helix" and "springs" in sections:
            run(check_swept_spring, design, unit)
    if "export" in sections:
        run(export_settings, design)
    if "train" in sections:
        run(train_settings, design)
    if "dual_motor" in sections and gears_complete:
        run(dual_motor_spec, design)
    if "duty" in sections or "materials" in sections:
        duty = run(duty_settings, design)
        if duty is not None and "materials" in sections and gears_complete:
            run(gear_materials, design, duty)


# ---------------------------------------------------------------------------------------------
# the schema of one key

_TABLE_SCHEMA: dict[str, tuple[list[Field], list[Quantity]]] = {
    "synthesis": (SYNTHESIS_FIELDS, []),
    "monte_carlo": (MONTE_CARLO_FIELDS, []),
    "checks": (CHECKS_FIELDS + [Field("centre_distance", "length", required=False, minimum=0.0,
                                      exclusive_minimum=True,
                                      help="centre distance of the pairs in meshes: one number, or a list of "
                                           "one per pair")], []),
    "stiffness": (STIFFNESS_FIELDS, MODULI),
    "preload": (PRELOAD_FIELDS, PRELOAD_QUANTITIES),
    "flexures": (FLEXURE_FIELDS, FLEXURE_QUANTITIES),
    "springs": (SPRING_FIELDS, SPRING_QUANTITIES),
    "beam_pinion": (BEAM_FIELDS, BEAM_QUANTITIES),
    "engagement": (ENGAGEMENT_FIELDS, []),
    "layout": (layout_fields(), []),
    "export": (EXPORT_FIELDS, []),
    "train": (TRAIN_FIELDS, TRAIN_QUANTITIES),
    "dual_motor": (DUAL_MOTOR_FIELDS, DUAL_MOTOR_QUANTITIES),
    "duty": (DUTY_FIELDS, DUTY_QUANTITIES),
}

#: the top-level keys and [drive], as fields (all optional)
TOP_FIELDS = [Field("name", "name", required=False,
                    help="the design's name in reports and manifests (default: the file name)"),
              Field("description", "string", required=False, help="one line describing the design, shown in the report"),
              Field("length_unit", "string", required=False, choices=("mm", "in"),
                    help="the unit of reports and exports (default: mm for module gears, in for diametral pitch)")]
DRIVE_FIELDS = [Field("type", "string", required=False, choices=("type1", "type2"),
                      help="Hale & Slocum's drive type: type1 (the compliant path carries the preload only) or "
                           "type2 (both paths alike)"),
                Field("preload", "string", required=False,
                      choices=("radial", "axial", "angular", "frictional_interface"),
                      help="how the preload is applied")]


def table_schema(data: Mapping[str, Any], path: tuple[str, ...]) -> tuple[list[Field], list[Quantity]] | None:
    """The fields and quantities of the table at ``path`` (``("springs",)``, ``("gears", "input")``,
    ``("stiffness", "components", "cluster_shaft")``) of the parsed file ``data``; None for a
    table the schema does not describe key by key."""
    if path == ():
        return TOP_FIELDS, []
    head = path[0]
    if path == ("drive",):
        return DRIVE_FIELDS, []
    if head in ("gears", "gear_defaults") and len(path) == (2 if head == "gears" else 1):
        # a gear table is read merged with [gear_defaults]: a key is required when neither gives it
        table = data.get(head, {}).get(path[1], {}) if head == "gears" else data.get(head, {})
        kind = table.get("kind") if isinstance(table, Mapping) else None
        family = FAMILIES.get(kind) if isinstance(kind, str) else None  # another family's own table
        return (family.FIELDS if family is not None else GEAR_FIELDS), []
    if head == "errors" and len(path) == 2:
        required = "synthesis" in data
        return [replace(f, required=required, default=0.0) for f in ERROR_FIELDS], []
    if path[:2] == ("stiffness", "components") and len(path) == 3:
        return COMPONENT_FIELDS, COMPONENT_QUANTITIES
    if head == "stages" and len(path) == 2:
        table = data.get("stages", {}).get(path[1], {})
        if isinstance(table, Mapping) and table.get("kind") == "planetary":
            from geargen.drives.planetary.keys import PLANETARY_STAGE_FIELDS
            return PLANETARY_STAGE_FIELDS, []
        return STAGE_FIELDS, []
    if head == "materials" and len(path) == 2:
        return MATERIAL_FIELDS, []
    if head == "parts" and len(path) == 1:
        return hardware_fields(kind_of(data)), []
    if len(path) == 1 and head in _TABLE_SCHEMA:
        return _TABLE_SCHEMA[head]
    return None


def key_schema(data: Mapping[str, Any], path: tuple[str, ...]) -> Field | Quantity | None:
    """The :class:`Field` or :class:`Quantity` that owns the key ``path[-1]`` of the table ``path[:-1]``."""
    schema = table_schema(data, path[:-1])
    if schema is None:
        return None
    fields, quantities = schema
    key = path[-1]
    if path[0] == "checks" and key in CENTRE_KEYS:
        return next(f for f in fields if f.name == "centre_distance")
    for f in fields:
        if key in f.keys():
            return f
    for q in quantities:
        if key in q.keys():
            return q
    return None


__all__ = ["validate_sections", "table_schema", "key_schema", "TOP_FIELDS", "DRIVE_FIELDS", "GEAR_ROLES"]
