"""The ``[parts]`` section: the non-gear parts of the assembly model, one key table per template.

``template`` picks the assembly ("robot_joint", "c_axis", "split_pinion"); every other key is
a size of one part (bearings, shafts, motor, housing, ...), a length with its unit suffix.
:func:`parts_settings` reads the table for its template; :func:`check_parts` adds the relations
between sizes that no part can violate (a bearing wider than its bore, a shaft thinner than the
motor it comes out of, walls that leave room inside) and the sections each template reads.
"""

from __future__ import annotations

import math
from typing import Any

from geargen.design.schema import Field, read_table
from geargen.design.stiffness import SPRING_ENDS, spring_spec_from_table
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES, MM_PER_IN

TEMPLATES = ("robot_joint", "c_axis", "split_pinion")


def _L(name, **kw):
    return Field(name, "length", minimum=0.0, exclusive_minimum=True, **kw)


_COMMON = [Field("template", "string", choices=TEMPLATES),
           Field("bearing_clearance", "length", required=False, default=0.5, minimum=0.0)]

TEMPLATE_FIELDS: dict[str, list[Field]] = {
    "robot_joint": _COMMON + [
        Field("bevel_pinion_teeth", "integer", minimum=4, maximum=500),
        Field("bevel_gear_teeth", "integer", minimum=4, maximum=500),
        Field("bevel_diametral_pitch_per_in", "number", required=False, default=None, minimum=0.1),
        Field("bevel_module", "length", required=False, default=None, units=("mm",), minimum=0.0,
              exclusive_minimum=True),
        _L("bevel_face_width"), _L("input_shaft_to_bevel"),
        _L("motor_body_diameter"), _L("motor_body_length"), _L("motor_flange"), _L("motor_flange_thickness"),
        _L("motor_shaft_diameter"), _L("motor_shaft_length"),
        _L("cluster_bearing_outer_diameter"), _L("cluster_bearing_width"),
        _L("input_bearing_outer_diameter"), _L("input_bearing_width"),
        _L("output_bearing_outer_diameter"), _L("output_bearing_width"),
        _L("carriage_plate_thickness"), _L("carriage_width"),
        _L("link_radius"), _L("link_wall"), _L("link_floor"), _L("link_top_clearance"),
        Field("spring_y_offset", "length", minimum=0.0),
        Field("spring_model", "string", required=False, default="helix", choices=("helix", "envelope")),
    ],
    "c_axis": _COMMON + [
        _L("spindle_diameter"), _L("spindle_length"),
        _L("input_shaft_diameter"), _L("input_bearing_outer_diameter"), _L("input_bearing_width"),
        _L("cluster_shaft_diameter"), _L("cluster_bearing_outer_diameter"), _L("cluster_bearing_width"),
        _L("cluster_bearing_spacing"),
        _L("friction_ring_outer_diameter"), _L("friction_ring_width"),
        _L("stop_collar_outer_diameter"), _L("stop_collar_width"), _L("stop_lug_length"), _L("stop_block_size"),
        _L("coupling_diameter"), _L("coupling_length"),
        _L("gearhead_diameter"), _L("gearhead_length"),
        _L("motor_body_diameter"), _L("motor_body_length"), _L("motor_flange"), _L("motor_flange_thickness"),
        _L("housing_thickness"), _L("housing_margin"),
    ],
    "split_pinion": _COMMON + [
        _L("hollow_shaft_outer_diameter"), _L("hollow_shaft_length"),
        _L("bearing_outer_diameter"), _L("bearing_width"),
        _L("collar_outer_diameter"), _L("collar_width"), _L("collar_slot"),
        _L("output_shaft_diameter"), _L("output_bearing_outer_diameter"), _L("output_bearing_width"),
    ],
}

#: (larger, smaller): ring-shaped parts whose outer diameter must exceed the diameter inside them.
#: A name "gears.NAME" stands for that gear's bore (the shaft it sits on).
_MUST_EXCEED: dict[str, tuple[tuple[str, str], ...]] = {
    "robot_joint": (("cluster_bearing_outer_diameter", "gears.cluster_small"),
                    ("input_bearing_outer_diameter", "gears.input"),
                    ("output_bearing_outer_diameter", "gears.output"),
                    ("motor_body_diameter", "motor_shaft_diameter"),
                    ("motor_flange", "motor_shaft_diameter"),
                    ("link_radius", "link_wall")),
    "c_axis": (("input_bearing_outer_diameter", "input_shaft_diameter"),
               ("cluster_bearing_outer_diameter", "cluster_shaft_diameter"),
               ("friction_ring_outer_diameter", "cluster_shaft_diameter"),
               ("stop_collar_outer_diameter", "cluster_shaft_diameter")),
    "split_pinion": (("bearing_outer_diameter", "hollow_shaft_outer_diameter"),
                     ("output_bearing_outer_diameter", "output_shaft_diameter")),
}

#: the sections each template's parts are sized from
_NEEDS: dict[str, tuple[str, ...]] = {
    "robot_joint": ("flexures", "springs"),
    "c_axis": ("beam_pinion", "engagement"),
    "split_pinion": (),
}


def parts_settings(design) -> dict[str, Any]:
    """``[parts]`` read for its template (internal units, mm)."""
    table = design.section("parts")
    if not table:
        raise DesignError("parts", "missing", "a [parts] table with template = " + " | ".join(map(repr, TEMPLATES)))
    template = table.get("template")
    if not isinstance(template, str) or template not in TEMPLATE_FIELDS:
        raise DesignError("parts.template", f"{template!r} is not a valid choice", ", ".join(map(repr, TEMPLATES)))
    return read_table(table, TEMPLATE_FIELDS[template], "parts")


def _key(v: dict[str, Any], name: str) -> str:
    unit = v["_units"].get(name)
    return f"parts.{name}_{unit}" if unit else f"parts.{name}"


def _check_swept_spring(design, unit: str) -> None:
    """The swept-wire spring model (all ``Nt`` coils as one helix between ground ends) needs a
    pitch above the wire: an installed length above ``d (Nt + 1)``, a wire more than the solid
    height of a squared-and-ground spring."""
    table = design.section("springs")
    spring = spring_spec_from_table(table, unit)
    if spring.installed_length is None:
        return
    coils = spring.active_coils + SPRING_ENDS[spring.end_type][0]
    shortest = spring.wire_diameter * (coils + 1)
    if not spring.installed_length > shortest:
        key = next(k for k in table if k.startswith("installed_length_"))
        scale = LENGTH_SUFFIXES[unit]
        raise DesignError(f"springs.{key}", f"{spring.installed_length / scale:.6g} {unit} is too short for the "
                          f"swept-wire model of the spring ({coils:g} coils of {spring.wire_diameter / scale:.6g} {unit} "
                          "wire would touch)", f"> {shortest / scale:.6g} {unit}, or parts.spring_model = 'envelope'")


def check_parts(design, v: dict[str, Any]) -> None:
    """The relations between part sizes, and the sections the template reads (see the module docstring)."""
    template = v["template"]
    unit = design.length_unit
    scale = LENGTH_SUFFIXES[unit]
    for section in _NEEDS[template]:
        if not design.section(section):
            raise DesignError(section, f"missing: the {template} parts are sized from it", f"a [{section}] table")
    if template == "robot_joint":
        if "installed_length" not in {k.rsplit("_", 1)[0] for k in design.section("springs")}:
            raise DesignError("springs.installed_length", "missing: the model shows the springs at their installed "
                              "length", " or ".join(f"installed_length_{u}" for u in LENGTH_SUFFIXES))
        if (v["bevel_module"] is None) == (v["bevel_diametral_pitch_per_in"] is None):
            raise DesignError("parts.bevel_module_mm", "give exactly one of bevel_module_mm and "
                              "bevel_diametral_pitch_per_in", "one of them")
        module = v["bevel_module"] or MM_PER_IN / v["bevel_diametral_pitch_per_in"]
        # the face must stay short of the cone's apex: cone distance r_p / sin(gamma_p), shaft angle 90 deg
        zp, zg = v["bevel_pinion_teeth"], v["bevel_gear_teeth"]
        cone = math.hypot(zp, zg) * module / 2
        if not v["bevel_face_width"] < cone:
            raise DesignError(_key(v, "bevel_face_width"), f"{v['bevel_face_width'] / scale:.6g} {unit} reaches past "
                              "the bevel pair's cone apex", f"< {cone / scale:.6g} {unit} (the cone distance)")
        if v["spring_model"] == "helix":
            _check_swept_spring(design, unit)
    for outer, inner in _MUST_EXCEED[template]:
        if inner.startswith("gears."):
            gear = design.gears.get(inner[len("gears."):])
            if gear is None or gear.hub.bore_diameter <= 0:
                continue  # the layout names the missing gear; a gear without a bore sets no bearing bore
            d_inner, inner_text = gear.hub.bore_diameter, f"the bore of {inner}"
        else:
            d_inner, inner_text = v[inner], _key(v, inner)
        if not v[outer] > d_inner:
            raise DesignError(_key(v, outer), f"{v[outer] / scale:.6g} {unit} is not larger than {inner_text} "
                              f"({d_inner / scale:.6g} {unit})", f"> {d_inner / scale:.6g} {unit}")


__all__ = ["TEMPLATES", "TEMPLATE_FIELDS", "parts_settings", "check_parts"]
