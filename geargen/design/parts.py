"""The ``[parts]`` section: the sizes of the non-gear parts, one key table per kind of hardware.

The drive the file describes decides its hardware (:func:`hardware_of`): a split pinion
(``[layout] kind = "split_pinion"``) its concentric shafts, collar and housing plates; a
dual pinion whose long input pinion is a beam spring (``[beam_pinion]``) its sliding dual
pinions, stops and housing; any other dual pinion a preload carriage on blade flexures
(``[flexures]``, ``[springs]``) with its motor, driving the input through a bevel pair or the
``[stages]``. Every key is a size of one part (bearings, shafts, motor, housing, ...), a length
with its unit suffix. :func:`parts_settings` reads the table for the drive's hardware;
:func:`check_parts` adds the relations between sizes that no part can violate (a bearing wider
than its bore, a shaft thinner than the motor it comes out of, walls that leave room inside) and
the sections the hardware is sized from.
"""

from __future__ import annotations

import math
from typing import Any

from geargen.design.layout import is_axial_preload, is_split_pinion
from geargen.design.schema import Field, read_table
from geargen.design.stiffness import SPRING_ENDS, spring_spec_from_table
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES, MM_PER_IN

HARDWARE = ("carriage", "beam_pinion", "split_pinion", "axial_preload", "rack_drive")


def hardware_of(data) -> str:
    """The hardware of a drive (one of :data:`HARDWARE`): from a loaded design or the parsed file."""
    if is_split_pinion(data):
        return "split_pinion"
    if is_axial_preload(data):
        return "axial_preload"
    sections = data.sections if hasattr(data, "sections") else data
    if (sections.get("layout") or {}).get("kind") == "rack_dual_pinion":
        return "rack_drive"
    return "beam_pinion" if sections.get("beam_pinion") else "carriage"


def _L(name, **kw):
    return Field(name, "length", minimum=0.0, exclusive_minimum=True, **kw)


_COMMON = [Field("bearing_clearance", "length", required=False, default=0.5, minimum=0.0,
                 help="axial gap between a bearing and the gear face next to it")]

HARDWARE_FIELDS: dict[str, list[Field]] = {
    "carriage": _COMMON + [
        Field("bevel_pinion_teeth", "integer", required=False, default=None, minimum=4, maximum=500,
              help="teeth of the bevel pinion on the motor shaft (the motor drives the input through a bevel pair; "
                   "a design with [stages] drives it through those instead)"),
        Field("bevel_gear_teeth", "integer", required=False, default=None, minimum=4, maximum=500,
              help="teeth of the bevel gear on the input shaft"),
        Field("bevel_diametral_pitch_per_in", "number", required=False, default=None, minimum=0.1,
              help="diametral pitch of the bevel pair (give this or bevel_module_mm)"),
        Field("bevel_module", "length", required=False, default=None, units=("mm",), minimum=0.0,
              exclusive_minimum=True, help="module of the bevel pair (give this or bevel_diametral_pitch_per_in)"),
        _L("bevel_face_width", required=False, default=None,
           help="face width of the bevel pair (less than the cone distance)"),
        _L("input_shaft_to_bevel", required=False, default=None,
           help="input gear's mid-plane to the bevel gear's heel (its heel pitch circle)"),
        _L("bevel_backlash", required=False, default=None,
           help="circumferential backlash of the bevel pair at the heel pitch circles, cut as equal thinnings of "
                "both gears; when absent, the [train] upstream_backlash_arcmin of the pair's [layout] "
                "upstream_stages entry at the bevel gear's heel pitch radius (give one of them)"),
        _L("stage_bearing_outer_diameter", required=False, default=None,
           help="with [stages]: outer diameter of the stage shafts' bearings (bore: the shaft's gears' bore)"),
        _L("stage_bearing_width", required=False, default=None,
           help="with [stages]: width of the stage shafts' bearings; the lower ones stand on the carriage arm, "
                "the upper ones under its bridge, where the motor stands"),
        _L("motor_body_diameter", help="servo motor body (with encoder), envelope diameter"),
        _L("motor_body_length", help="servo motor body length"),
        _L("motor_flange", help="side of the motor's square mounting flange"),
        _L("motor_flange_thickness", help="thickness of the motor flange"),
        _L("motor_shaft_diameter", required=False, default=None,
           help="motor shaft diameter (with [stages]: the first stage driver's bore, not given here)"),
        _L("motor_shaft_length", required=False, default=None,
           help="motor shaft stub from the flange to the bevel pinion's heel (with [stages]: down through the "
                "bridge to the first driver, not given here)"),
        _L("cluster_bearing_outer_diameter",
           help="outer diameter of the cluster shafts' bearings (bore: the cluster_small bore)"),
        _L("cluster_bearing_width", help="width of the cluster shafts' bearings"),
        _L("input_bearing_outer_diameter",
           help="outer diameter of the input shaft's bearings (bore: the input's bore)"),
        _L("input_bearing_width", help="width of the input shaft's bearings"),
        _L("output_bearing_outer_diameter",
           help="outer diameter of the output shaft's bearings (bore: the output's bore)"),
        _L("output_bearing_width", help="width of the output shaft's bearings"),
        _L("carriage_plate_thickness", help="plate, post, arm and spring wall thickness of the preload carriage"),
        _L("carriage_width", help="width of the preload carriage"),
        _L("link_radius", help="round end of the link about the joint axis (half the link's width)"),
        _L("link_wall", help="wall thickness of the link"),
        _L("link_floor", help="floor thickness of the link"),
        _L("link_top_clearance", help="how far the link's walls reach above the highest part"),
        Field("spring_y_offset", "length", minimum=0.0,
              help="the two preload springs sit at y = +- this, either side of the symmetry line"),
        Field("spring_model", "string", required=False, default="helix", choices=("helix", "envelope"),
              help="preload springs modelled as a swept wire (helix) or as a tube (envelope)"),
    ],
    "beam_pinion": _COMMON + [
        _L("spindle_diameter",
           help="lathe spindle through the bull gear (reference; the model takes the output's bore)"),
        _L("spindle_length", help="length of the spindle stub"),
        _L("input_shaft_diameter", help="shaft of the long input pinion"),
        _L("input_bearing_outer_diameter",
           help="outer diameter of the long pinion's bearings (at the beam's supports)"),
        _L("input_bearing_width", help="width of the long pinion's bearings"),
        _L("cluster_shaft_diameter", help="dual-pinion shaft (equal to the cluster gears' bore)"),
        _L("cluster_bearing_outer_diameter", help="outer diameter of the bearings in each sliding quill"),
        _L("cluster_bearing_width", help="width of the bearings in each sliding quill"),
        _L("cluster_bearing_spacing", help="distance between the two bearings of a quill"),
        _L("friction_ring_outer_diameter",
           help="locking ring clamping the large gear to its shaft (the frictional interface)"),
        _L("friction_ring_width", help="width of the locking ring"),
        _L("locknut_outer_diameter",
           help="locknut under each dual pinion's lower bearing, clamping the inner rings to the shaft"),
        _L("locknut_width", help="width of the locknut (the shaft ends at its lower face)"),
        _L("quill_outer_diameter",
           help="sleeve that holds a dual pinion's two bearings by their outer rings and slides in the housing "
                "block's bore (its bore: the bearings' outer diameter)"),
        _L("stop_lug_length", help="how far the quill's lug, which meets the travel stops, reaches beyond the quill"),
        _L("stop_lug_width", help="width of the quill's lug"),
        _L("stop_lug_thickness", help="thickness of the quill's lug along the axis, at the quill's lower end"),
        _L("stop_block_size", help="side of the square travel stops under the housing block"),
        _L("coupling_diameter", help="coupling between gearhead and long pinion shaft"),
        _L("coupling_length", help="length of the coupling"),
        _L("gearhead_diameter", help="planetary gearhead on the motor"),
        _L("gearhead_length", help="length of the gearhead"),
        _L("motor_body_diameter", help="servo motor body (with encoder), envelope diameter"),
        _L("motor_body_length", help="servo motor body length"),
        _L("motor_flange", help="side of the motor's square mounting flange"),
        _L("motor_flange_thickness", help="thickness of the motor flange"),
        _L("housing_thickness",
           help="thickness of the housing block: the length of the bores the quills slide in"),
        _L("housing_margin", help="housing block's wall around the quill bores, the long pinion's hole and the stops"),
        _L("drive_column_width",
           help="width of the column beside the long pinion and of the plates on it that seat the long pinion's "
                "bearings"),
        _L("drive_column_thickness", help="thickness of that column, away from the long pinion"),
        _L("motor_plate_thickness",
           help="plate on the column between gearhead and motor: both bolt to it, the motor's shaft reaches "
                "through it into the gearhead"),
    ],
    "split_pinion": _COMMON + [
        _L("hollow_shaft_outer_diameter", help="hollow shaft of the stiff path (equal to the stiff pinion's bore)"),
        _L("hollow_shaft_length", help="hollow shaft from the stiff pinion's far face to the clamp collar"),
        _L("bearing_outer_diameter", help="outer diameter of the hollow shaft's bearing pair"),
        _L("bearing_width", help="width of each of the hollow shaft's bearings"),
        _L("bearing_spacing", required=False, default=None,
           help="centre distance of the hollow shaft's two bearings (default: side by side, a bearing_clearance "
                "apart); the stiff pinion overhangs the upper one"),
        _L("collar_outer_diameter", help="clamp collar joining inner and hollow shaft (the frictional interface)"),
        _L("collar_width", help="width of the clamp collar"),
        _L("collar_slot", help="width of the collar's clamping slot"),
        _L("compliant_bearing_outer_diameter",
           help="outboard bearing above the compliant pinion (bore: the compliant pinion's), held by the top plate"),
        _L("compliant_bearing_width", help="width of the outboard bearing above the compliant pinion"),
        _L("housing_margin", required=False, default=5.0,
           help="top and bottom plates: material left around the outermost bearing seats"),
        _L("output_shaft_diameter",
           help="output shaft (checked against its bearing; the model takes the output's bore)"),
        _L("output_bearing_outer_diameter", help="outer diameter of the output shaft's bearings"),
        _L("output_bearing_width", help="width of the output shaft's bearings"),
    ],
    # the rack dual-pinion drive (geargen.drives.rack_dual_pinion.hardware): path shafts on a bearing each side of
    # their gears in two housing plates, the input shaft in the preload carriage on a linear guide
    "rack_drive": _COMMON + [
        _L("path_bearing_outer_diameter", help="outer diameter of the path shafts' bearings (bore: the pinion's)"),
        _L("path_bearing_width", help="width of the path shafts' bearings (and of the housing plates that hold them)"),
        _L("input_bearing_outer_diameter", help="outer diameter of the input shaft's two bearings in the carriage "
                                                "(bore: the input gear's)"),
        _L("input_bearing_width", help="width of each of the input shaft's bearings"),
        _L("housing_margin", required=False, default=5.0,
           help="housing plates and carriage: material left around the bearing seats"),
        _L("rail_width", help="linear guide rail under the carriage, across its motion"),
        _L("rail_height", help="height of the linear guide rail"),
        _L("guide_block_length", help="the guide's sliding block along the motion"),
        _L("guide_block_height", help="height of the guide's sliding block (rail top to carriage)"),
        _L("spring_wire_diameter", help="carriage spring wire (its active coils follow from the spring rate)"),
        _L("spring_mean_diameter", help="carriage spring mean coil diameter"),
        _L("spring_installed_length", help="carriage spring length as installed (preloaded)"),
        _L("spring_post_thickness", help="the post on the top plate the spring pushes from, along the motion"),
        Field("spring_shear_modulus_GPa", "number", required=False, default=79.3, minimum=1.0,
              help="shear modulus of the spring wire (music wire: 79.3)"),
    ],
    # geargen.model.axial_drive / geargen.drives.axial_preload.hardware: the sliding input shaft and its spring
    "axial_preload": _COMMON + [
        _L("input_bearing_outer_diameter",
           help="outer diameter of the input shaft's two bearings (bore: the pinions' bore); their outer rings "
                "slide in the housing plates' bores"),
        _L("input_bearing_width", help="width of the input shaft's bearings"),
        _L("output_bearing_outer_diameter", help="outer diameter of the output shaft's bearings (bore: the output "
                                                 "gears' bore)"),
        _L("output_bearing_width", help="width of the output shaft's bearings"),
        _L("spring_wire_diameter", help="wire of the preload spring, which pushes the lower input bearing's outer ring"),
        _L("spring_mean_diameter", help="mean coil diameter of the preload spring (its coils must lie on the bearing's "
                                        "outer ring, clear of the shaft)"),
        _L("spring_installed_length", help="length of the preload spring at the reference position (shaft not slid)"),
        Field("spring_shear_modulus_GPa", "number", required=False, default=79.3, minimum=1.0,
              help="shear modulus of the spring wire: the active coils follow from layout.preload_spring_rate"),
        _L("spring_cup_wall", help="wall and floor of the cup under the bottom plate that holds the spring"),
        _L("motor_stub_length", help="the input shaft's end above the upper bearing, for the motor's sliding coupling"),
        _L("housing_margin", required=False, default=5.0,
           help="top and bottom plates: material left around the outermost bearing seats"),
    ],
}

#: (larger, smaller): ring-shaped parts whose outer diameter must exceed the diameter inside them.
#: A name "gears.NAME" stands for that gear's bore (the shaft it sits on).
_MUST_EXCEED: dict[str, tuple[tuple[str, str], ...]] = {
    "carriage": (("cluster_bearing_outer_diameter", "gears.cluster_small"),
                    ("input_bearing_outer_diameter", "gears.input"),
                    ("output_bearing_outer_diameter", "gears.output"),
                    ("motor_body_diameter", "motor_shaft_diameter"),
                    ("motor_flange", "motor_shaft_diameter"),
                    ("link_radius", "link_wall")),
    "beam_pinion": (("input_bearing_outer_diameter", "input_shaft_diameter"),
               ("cluster_bearing_outer_diameter", "cluster_shaft_diameter"),
               ("friction_ring_outer_diameter", "cluster_shaft_diameter"),
               ("locknut_outer_diameter", "cluster_shaft_diameter"),
               ("cluster_bearing_outer_diameter", "locknut_outer_diameter"),
               ("quill_outer_diameter", "cluster_bearing_outer_diameter"),
               ("drive_column_width", "input_bearing_outer_diameter")),
    "split_pinion": (("bearing_outer_diameter", "hollow_shaft_outer_diameter"),
                     ("compliant_bearing_outer_diameter", "gears.pinion_compliant"),
                     ("output_bearing_outer_diameter", "output_shaft_diameter")),
    "rack_drive": (("path_bearing_outer_diameter", "gears.pinion"),
                   ("input_bearing_outer_diameter", "gears.input"),
                   ("spring_mean_diameter", "spring_wire_diameter")),
    "axial_preload": (("input_bearing_outer_diameter", "gears.pinion_left"),
                      ("output_bearing_outer_diameter", "gears.output_right")),
}

#: the sections each hardware's parts are sized from
_NEEDS: dict[str, tuple[str, ...]] = {
    "carriage": ("flexures", "springs"),
    "beam_pinion": ("beam_pinion", "engagement"),
    "split_pinion": (),
    "rack_drive": (),
    "axial_preload": (),
}


def parts_settings(design) -> dict[str, Any]:
    """``[parts]`` read for the drive's hardware (internal units, mm; ``"hardware"`` says which)."""
    table = design.section("parts")
    hardware = hardware_of(design)
    if not table:
        raise DesignError("parts", "missing", f"a [parts] table sizing the {hardware} hardware")
    return {**read_table(table, HARDWARE_FIELDS[hardware], "parts"), "hardware": hardware}


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


#: the carriage's keys of each way the motor drives the input gear
_BEVEL_KEYS = ("bevel_pinion_teeth", "bevel_gear_teeth", "bevel_face_width", "input_shaft_to_bevel",
               "motor_shaft_diameter", "motor_shaft_length")
_STAGE_KEYS = ("stage_bearing_outer_diameter", "stage_bearing_width")


def _check_motor_drive(design, v: dict[str, Any]) -> None:
    """The carriage's motor drives the input through a bevel pair, or (a design with [stages])
    through those stages standing on the carriage: each needs its own keys and refuses the other's."""
    staged = bool(design.section("stages"))
    needed, refused = (_STAGE_KEYS, _BEVEL_KEYS + ("bevel_module", "bevel_diametral_pitch_per_in", "bevel_backlash")) if staged \
        else (_BEVEL_KEYS, _STAGE_KEYS)
    why = "the design's [stages] drive the input" if staged else "the motor drives the input through the bevel pair"
    for name in refused:
        if v.get(name) is not None:
            raise DesignError(_key(v, name), f"not read: {why}", "remove it")
    for name in needed:
        if v.get(name) is None:
            raise DesignError(f"parts.{name}", f"missing: {why}", "a value")
    if not staged and (v["bevel_module"] is None) == (v["bevel_diametral_pitch_per_in"] is None):
        raise DesignError("parts.bevel_module_mm", "give exactly one of bevel_module_mm and "
                          "bevel_diametral_pitch_per_in", "one of them")


def check_parts(design, v: dict[str, Any]) -> None:
    """The relations between part sizes, and the sections the hardware reads (see the module docstring)."""
    hardware = v["hardware"]
    unit = design.length_unit
    scale = LENGTH_SUFFIXES[unit]
    for section in _NEEDS[hardware]:
        if not design.section(section):
            raise DesignError(section, f"missing: the {hardware} parts are sized from it", f"a [{section}] table")
    if hardware == "carriage":
        if "installed_length" not in {k.rsplit("_", 1)[0] for k in design.section("springs")}:
            raise DesignError("springs.installed_length", "missing: the model shows the springs at their installed "
                              "length", " or ".join(f"installed_length_{u}" for u in LENGTH_SUFFIXES))
        _check_motor_drive(design, v)
    if hardware == "carriage" and not design.section("stages"):
        module = v["bevel_module"] or MM_PER_IN / v["bevel_diametral_pitch_per_in"]
        # the face must stay short of the cone's apex: cone distance r_p / sin(gamma_p), shaft angle 90 deg
        zp, zg = v["bevel_pinion_teeth"], v["bevel_gear_teeth"]
        cone = math.hypot(zp, zg) * module / 2
        if not v["bevel_face_width"] < cone:
            raise DesignError(_key(v, "bevel_face_width"), f"{v['bevel_face_width'] / scale:.6g} {unit} reaches past "
                              "the bevel pair's cone apex", f"< {cone / scale:.6g} {unit} (the cone distance)")
    if hardware == "carriage" and v["spring_model"] == "helix":
        _check_swept_spring(design, unit)
    if hardware == "beam_pinion":
        # the stops stand over the lug's outer end, a stop's side from it: they must clear the quill
        reach = v["stop_block_size"] + v["bearing_clearance"]
        if not v["stop_lug_length"] > reach:
            raise DesignError(_key(v, "stop_lug_length"), f"{v['stop_lug_length'] / scale:.6g} {unit} puts the travel "
                              "stops against the quill", f"> {reach / scale:.6g} {unit} (stop_block_size + "
                              "bearing_clearance)")
    for outer, inner in _MUST_EXCEED[hardware]:
        if v.get(outer) is None or (not inner.startswith("gears.") and v.get(inner) is None):
            continue  # a key of the other motor drive (_check_motor_drive)
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


__all__ = ["HARDWARE", "HARDWARE_FIELDS", "hardware_of", "parts_settings", "check_parts"]
