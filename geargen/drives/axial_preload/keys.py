"""The keys of the axial_preload drive (the Type 2 axial-motion preload: a left- and a right-hand
helical pinion on an input shaft that slides axially under a preload spring): its ``[layout]``
keys, its ``[parts]`` hardware, and its gear tables checked against each other, what the
placement (:mod:`geargen.drives.axial_preload.place`) relies on.

The two pinions sit on one shaft and the two output gears on another, so each pair turns
together: the same teeth (or the meshes would run at two ratios), the same normal module,
pressure angle and helix angle (so one axial slide turns both meshes by the same arc), opposite
hands (so the slide turns them in opposite senses: that is the preload), and each output gear of
the hand opposite to its pinion (an external helical pair).
"""

from __future__ import annotations

import math
from typing import Any

from geargen.design.schema import Field
from geargen.drives.axial_preload import defaults  # noqa: F401  (its default hardware, the loader's)
from geargen.drives.fields import positive_length
from geargen.errors import DesignError

NAME = "axial_preload"
#: the [layout] kind that selects the drive
LAYOUT_KIND = "axial_preload"
#: what it is, in the [layout] kind key's help (the reference's list of kinds)
LAYOUT_HELP = ("a left- and a right-hand helical pinion on an input shaft that slides axially under a preload "
               "spring, each meshing its own output gear of the opposite hand")

#: the [layout] keys this kind reads besides the common ones
LAYOUT_FIELDS = [
    Field("centre_distance", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
        help="split pinion and axial preload: centre distance of both pinions from the output"),
    Field("pinion_axial_gap", "length", required=False, default=0.0, minimum=0.0,
        help="split pinion and axial preload: axial gap between the two pinions"),
    Field("circumferential_backlash_min", "length", required=False, default=None, minimum=0.0,
        help="split pinion and axial preload: smallest backlash of each pinion with the output (circumferential, at "
             "the reference circles)"),
    Field("circumferential_backlash_max", "length", required=False, default=None, minimum=0.0,
        help="split pinion and axial preload: largest backlash of each pinion with the output (circumferential, at "
             "the reference circles)"),
    Field("pinion_left", "string", required=False, default="pinion_left",
        help="axial preload: the gear table of the left-hand pinion (meshes output_right)"),
    Field("pinion_right", "string", required=False, default="pinion_right",
        help="axial preload: the gear table of the right-hand pinion, above the left-hand one (meshes output_left)"),
    Field("output_right", "string", required=False, default="output_right",
        help="axial preload: the gear table of the right-hand output gear, meshing pinion_left"),
    Field("output_left", "string", required=False, default="output_left",
        help="axial preload: the gear table of the left-hand output gear, meshing pinion_right (clamped to "
             "output_right on the output shaft)"),
    Field("input_stroke", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
        help="axial preload: travel the input shaft's sliding bearings allow along +z (the spring's push) from the "
             "reference position where both meshes sit in the middle of their play"),
    Field("sliding_friction_coefficient", "number", required=False, default=0.1, minimum=0.0, maximum=1.0,
        help="axial preload: friction coefficient of the input shaft's sliding fit (the floating bearings' outer "
             "rings in their bores)"),
    Field("max_friction_to_preload", "number", required=False, default=0.15, minimum=0.0, exclusive_minimum=True,
        help="axial preload: the largest friction force of the sliding fit over the spring force the design "
             "accepts (the helix angle must be large enough)"),
]

#: the [parts] keys of its hardware (bearing_clearance besides)
PARTS_FIELDS = [
    positive_length("input_bearing_outer_diameter",
        help="outer diameter of the input shaft's two bearings (bore: the pinions' bore); their outer rings "
        "slide in the housing plates' bores"),
    positive_length("input_bearing_width", help="width of the input shaft's bearings"),
    positive_length("output_bearing_outer_diameter", help="outer diameter of the output shaft's bearings (bore: the output "
        "gears' bore)"),
    positive_length("output_bearing_width", help="width of the output shaft's bearings"),
    positive_length("spring_wire_diameter", help="wire of the preload spring, which pushes the lower input bearing's outer ring"),
    positive_length("spring_mean_diameter", help="mean coil diameter of the preload spring (its coils must lie on the bearing's "
        "outer ring, clear of the shaft)"),
    positive_length("spring_installed_length", help="length of the preload spring at the reference position (shaft not slid)"),
    Field("spring_shear_modulus_GPa", "number", required=False, default=79.3, minimum=1.0,
        help="shear modulus of the spring wire: the active coils follow from layout.preload_spring_rate"),
    positive_length("spring_cup_wall", help="wall and floor of the cup under the bottom plate that holds the spring"),
    positive_length("motor_stub_length", help="the input shaft's end above the upper bearing, for the motor's sliding coupling"),
    positive_length("housing_margin", required=False, default=5.0,
        help="top and bottom plates: material left around the outermost bearing seats"),
]

ROLES = ("pinion_left", "pinion_right", "output_right", "output_left")
HAND_OF_ROLE = {"pinion_left": "left", "pinion_right": "right", "output_right": "right", "output_left": "left"}


def _same(name_a: str, a, name_b: str, b, attr: str, label: str, unit: str = "") -> None:
    va, vb = getattr(a, attr), getattr(b, attr)
    if not math.isclose(va, vb, rel_tol=1e-12, abs_tol=1e-12):
        shown = (lambda v: f"{math.degrees(v):.6g} deg") if unit == "deg" else (lambda v: f"{v:.6g}")
        raise DesignError(f"gears.{name_b}.{label}", f"{shown(vb)}, but gears.{name_a} has {shown(va)}: the axial "
                          "preload turns both meshes by one slide", shown(va))


def check_axial_gears(design, v: dict[str, Any]) -> None:
    """The rules of the module docstring on the gear tables named by ``[layout]`` (``v``)."""
    gears = {}
    for role in ROLES:
        name = v[role]
        if name not in design.gears:
            key = f"layout.{role}" if role in (design.section("layout") or {}) else f"gears.{name}"
            raise DesignError(key, f"no gear named {name!r} in the design", ", ".join(design.gears))
        spec = design.gears[name]
        if spec.kind != "external" or not spec.helix_angle > 0:
            raise DesignError(f"gears.{name}.helix_angle_deg", f"gears.{name} is {'a spur' if spec.kind == 'external' else spec.kind} "
                              "gear: the axial preload slides helical gears", "a helical external gear, helix_angle_deg > 0")
        if spec.hand != HAND_OF_ROLE[role]:
            raise DesignError(f"gears.{name}.hand", f"{spec.hand!r}: layout.{role} must be {HAND_OF_ROLE[role]}-hand",
                              repr(HAND_OF_ROLE[role]))
        gears[role] = spec
    pl = gears["pinion_left"]
    for role in ROLES[1:]:
        g = gears[role]
        _same(pl.name, pl, g.name, g, "module", "module")
        _same(pl.name, pl, g.name, g, "pressure_angle", "pressure_angle_deg", "deg")
        _same(pl.name, pl, g.name, g, "helix_angle", "helix_angle_deg", "deg")
    for a, b in (("pinion_left", "pinion_right"), ("output_right", "output_left")):
        if gears[a].teeth != gears[b].teeth:
            raise DesignError(f"gears.{gears[b].name}.teeth", f"{gears[b].teeth} teeth, but gears.{gears[a].name} has "
                              f"{gears[a].teeth}: the two turn together on one shaft", f"{gears[a].teeth}")


#: whether [stages] may drive its input gear (the motor couples to the sliding input shaft)
TAKES_STAGES = False
#: the [stiffness] train it requires (None: the file's, dual_pinion by default, or custom)
STIFFNESS_TRAIN = None
REQUIRED = ("centre_distance", "circumferential_backlash_min", "circumferential_backlash_max", "input_stroke")
ORDERED = (("circumferential_backlash_min", "circumferential_backlash_max"),)
NEEDS = ()
MUST_EXCEED = (("input_bearing_outer_diameter", "gears.pinion_left"),
               ("output_bearing_outer_diameter", "gears.output_right"))
SYMMETRY_LINE = False


#: its [layout] rules with the gear tables
check_layout = check_axial_gears

__all__ = ["ROLES", "HAND_OF_ROLE", "check_axial_gears", "check_layout"]
