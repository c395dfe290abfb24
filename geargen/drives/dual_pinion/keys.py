"""The keys of the dual_pinion drive (a dual pinion whose input rides a radial-motion preload carriage on blade flexures (the robot joint, Fig. 10)): its ``[layout]`` keys and its ``[parts]`` hardware."""

from __future__ import annotations

import math
from typing import Any

from geargen.design.schema import Field
from geargen.drives.dual_pinion import defaults  # noqa: F401  (its default hardware, the loader's)
from geargen.drives.fields import part_key, positive_length
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES, MM_PER_IN

NAME = "dual_pinion"
#: where sliding pinions stand (the beam-spring kind slides them out of mesh)
POSITIONS = ("engaged", "disengaged")
#: the [layout] kind that selects the drive
LAYOUT_KIND = "dual_pinion"
#: what it is, in the [layout] kind key's help (the reference's list of kinds)
LAYOUT_HELP = "gears placed by the centre synthesis of [synthesis]; the default when there is one"

#: the [layout] keys this kind reads besides the common ones
LAYOUT_FIELDS = [
    Field("position", "string", required=False, default="engaged", choices=POSITIONS,
        help="sliding pinions engaged or disengaged (disengaged needs [engagement])"),
    Field("cluster", "string", required=False, default="one_piece", choices=("one_piece", "separate"),
        help="dual pinion: each cluster one part, or its large and small gear as two parts"),
    Field("cluster_axial_gap", "length", required=False, default=None, minimum=0.0,
        help="dual pinion: axial gap between a cluster's large and small gear (default: a quarter of the narrower "
             "face)"),
    Field("input_face_offset", "length", required=False, default=None,
        help="dual pinion: how far the input's face sits below the cluster's large gear face (default: the input "
             "centred on it)"),
    Field("carriage_travel", "length", required=False, default=None, minimum=0.0,
        help="dual pinion and rack drive: travel of the preload carriage either way, drawn in the layout and the report"),
]

#: the [parts] keys of its hardware (bearing_clearance besides)
PARTS_FIELDS = [
    Field("bevel_pinion_teeth", "integer", required=False, default=None, minimum=4, maximum=500,
        help="teeth of the bevel pinion on the motor shaft (the motor drives the input through a bevel pair; "
        "a design with [stages] drives it through those instead)"),
    Field("bevel_gear_teeth", "integer", required=False, default=None, minimum=4, maximum=500,
        help="teeth of the bevel gear on the input shaft"),
    Field("bevel_diametral_pitch_per_in", "number", required=False, default=None, minimum=0.1,
        help="diametral pitch of the bevel pair (give this or bevel_module_mm)"),
    Field("bevel_module", "length", required=False, default=None, units=("mm",), minimum=0.0,
        exclusive_minimum=True, help="module of the bevel pair (give this or bevel_diametral_pitch_per_in)"),
    positive_length("bevel_face_width", required=False, default=None,
        help="face width of the bevel pair (less than the cone distance)"),
    positive_length("input_shaft_to_bevel", required=False, default=None,
        help="input gear's mid-plane to the bevel gear's heel (its heel pitch circle)"),
    positive_length("bevel_backlash", required=False, default=None,
        help="circumferential backlash of the bevel pair at the heel pitch circles, cut as equal thinnings of "
        "both gears; when absent, the [train] upstream_backlash_arcmin of the pair's [layout] "
        "upstream_stages entry at the bevel gear's heel pitch radius (give one of them)"),
    positive_length("stage_bearing_outer_diameter", required=False, default=None,
        help="with [stages]: outer diameter of the stage shafts' bearings (bore: the shaft's gears' bore)"),
    positive_length("stage_bearing_width", required=False, default=None,
        help="with [stages]: width of the stage shafts' bearings; the lower ones stand on the carriage arm, "
        "the upper ones under its bridge, where the motor stands"),
    positive_length("motor_body_diameter", help="servo motor body (with encoder), envelope diameter"),
    positive_length("motor_body_length", help="servo motor body length"),
    positive_length("motor_flange", help="side of the motor's square mounting flange"),
    positive_length("motor_flange_thickness", help="thickness of the motor flange"),
    positive_length("motor_shaft_diameter", required=False, default=None,
        help="motor shaft diameter (with [stages]: the first stage driver's bore, not given here)"),
    positive_length("motor_shaft_length", required=False, default=None,
        help="motor shaft stub from the flange to the bevel pinion's heel (with [stages]: down through the "
        "bridge to the first driver, not given here)"),
    positive_length("cluster_bearing_outer_diameter",
        help="outer diameter of the cluster shafts' bearings (bore: the cluster_small bore)"),
    positive_length("cluster_bearing_width", help="width of the cluster shafts' bearings"),
    positive_length("input_bearing_outer_diameter",
        help="outer diameter of the input shaft's bearings (bore: the input's bore)"),
    positive_length("input_bearing_width", help="width of the input shaft's bearings"),
    positive_length("output_bearing_outer_diameter",
        help="outer diameter of the output shaft's bearings (bore: the output's bore)"),
    positive_length("output_bearing_width", help="width of the output shaft's bearings"),
    positive_length("carriage_plate_thickness", help="plate, post, arm and spring wall thickness of the preload carriage"),
    positive_length("carriage_width", help="width of the preload carriage"),
    positive_length("link_radius", help="round end of the link about the joint axis (half the link's width)"),
    positive_length("link_wall", help="wall thickness of the link"),
    positive_length("link_floor", help="floor thickness of the link"),
    positive_length("link_top_clearance", help="how far the link's walls reach above the highest part"),
    Field("spring_y_offset", "length", minimum=0.0,
        help="the two preload springs sit at y = +- this, either side of the symmetry line"),
    Field("spring_model", "string", required=False, default="helix", choices=("helix", "envelope"),
        help="preload springs modelled as a swept wire (helix) or as a tube (envelope)"),
]


#: whether [stages] may drive its input gear (its input gear may be driven through [stages] standing on the carriage)
TAKES_STAGES = True
#: the [stiffness] train it requires (None: the file's, dual_pinion by default, or custom)
STIFFNESS_TRAIN = None
#: [layout] keys it must give (a dual pinion takes its centres and ranges from [synthesis])
REQUIRED = ()
#: (smaller, larger) [layout] ranges
ORDERED = ()
#: the sections its hardware is sized from
NEEDS = ("flexures", "springs")
#: (larger, smaller): ring-shaped parts whose outer diameter must exceed the diameter inside them
#: ("gears.NAME": that gear's bore)
MUST_EXCEED = (("cluster_bearing_outer_diameter", "gears.cluster_small"),
               ("input_bearing_outer_diameter", "gears.input"),
               ("output_bearing_outer_diameter", "gears.output"),
               ("motor_body_diameter", "motor_shaft_diameter"),
               ("motor_flange", "motor_shaft_diameter"),
               ("link_radius", "link_wall"))
#: the layout figure draws the symmetry line the two paths mirror about
SYMMETRY_LINE = True


def cluster_axial_gap(settings, large, small) -> float:
    """The axial gap between a cluster's large and small gear (mm): ``[layout] cluster_axial_gap``,
    else a quarter of the narrower face."""
    gap = settings.get("cluster_axial_gap")
    return 0.25 * min(large.face_width, small.face_width) if gap is None else gap


def check_layout(design, v) -> None:
    """A dual pinion is placed by the centre synthesis: it needs a [synthesis]."""
    if not design.section("synthesis"):
        raise DesignError("synthesis", "missing: layout.kind = 'dual_pinion' places the gears by the centre synthesis",
                          "a [synthesis] table, or another layout.kind")


#: the carriage's keys of each way the motor drives the input gear
_BEVEL_KEYS = ("bevel_pinion_teeth", "bevel_gear_teeth", "bevel_face_width", "input_shaft_to_bevel",
               "motor_shaft_diameter", "motor_shaft_length")
_STAGE_KEYS = ("stage_bearing_outer_diameter", "stage_bearing_width")


def parts_needed(sections) -> tuple[str, ...]:
    """The optional [parts] keys a file (its parsed sections) must still give: its motor drive's,
    the bevel pair's or, with [stages], the stage bearings'. A file that leaves one out gives a
    partial [parts], which the default hardware completes."""
    if sections.get("stages"):
        return _STAGE_KEYS
    table = sections.get("parts") if isinstance(sections.get("parts"), dict) else {}
    pitch = any(k.startswith(("bevel_module_", "bevel_diametral_pitch_")) for k in table)
    return _BEVEL_KEYS if pitch else _BEVEL_KEYS + ("bevel_module",)


def _check_motor_drive(design, v: dict[str, Any]) -> None:
    """The carriage's motor drives the input through a bevel pair, or (a design with [stages])
    through those stages standing on the carriage: each needs its own keys and refuses the other's."""
    staged = bool(design.section("stages"))
    needed, refused = (_STAGE_KEYS, _BEVEL_KEYS + ("bevel_module", "bevel_diametral_pitch_per_in", "bevel_backlash")) if staged \
        else (_BEVEL_KEYS, _STAGE_KEYS)
    why = "the design's [stages] drive the input" if staged else "the motor drives the input through the bevel pair"
    for name in refused:
        if v.get(name) is not None:
            raise DesignError(part_key(v, name), f"not read: {why}", "remove it")
    for name in needed:
        if v.get(name) is None:
            raise DesignError(f"parts.{name}", f"missing: {why}", "a value")
    if not staged and (v["bevel_module"] is None) == (v["bevel_diametral_pitch_per_in"] is None):
        raise DesignError("parts.bevel_module_mm", "give exactly one of bevel_module_mm and "
                          "bevel_diametral_pitch_per_in", "one of them")


def check_parts(design, v) -> None:
    """The carriage's own rules: the springs' installed length, its motor drive (a bevel pair, or the
    design's [stages]), the bevel face short of the cone apex."""
    unit = design.length_unit
    scale = LENGTH_SUFFIXES[unit]
    if "installed_length" not in {k.rsplit("_", 1)[0] for k in design.section("springs")}:
        raise DesignError("springs.installed_length", "missing: the model shows the springs at their installed "
                          "length", " or ".join(f"installed_length_{u}" for u in LENGTH_SUFFIXES))
    _check_motor_drive(design, v)
    if not design.section("stages"):
        module = v["bevel_module"] or MM_PER_IN / v["bevel_diametral_pitch_per_in"]
        # the face must stay short of the cone's apex: cone distance r_p / sin(gamma_p), shaft angle 90 deg
        zp, zg = v["bevel_pinion_teeth"], v["bevel_gear_teeth"]
        cone = math.hypot(zp, zg) * module / 2
        if not v["bevel_face_width"] < cone:
            raise DesignError(part_key(v, "bevel_face_width"), f"{v['bevel_face_width'] / scale:.6g} {unit} reaches "
                              "past the bevel pair's cone apex", f"< {cone / scale:.6g} {unit} (the cone distance)")
