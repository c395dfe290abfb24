"""The keys of the split_pinion drive (the concentric Type 1 split pinion (Fig. 8)): its ``[layout]`` keys and its ``[parts]`` hardware."""

from __future__ import annotations

from geargen.design.schema import Field
from geargen.drives.fields import positive_length
from geargen.drives.split_pinion import defaults  # noqa: F401  (its default hardware, the loader's)
from geargen.errors import DesignError

NAME = "split_pinion"
#: the [layout] kind that selects the drive
LAYOUT_KIND = "split_pinion"
#: what it is, in the [layout] kind key's help (the reference's list of kinds)
LAYOUT_HELP = "two pinions side by side on one output"

#: the [layout] keys this kind reads besides the common ones
LAYOUT_FIELDS = [
    Field("centre_distance", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
        help="split pinion and axial preload: centre distance of both pinions from the output"),
    Field("pinion_stiff", "string", required=False, default="pinion_stiff",
        help="split pinion: the gear table of the stiff (outer) path's pinion"),
    Field("pinion_compliant", "string", required=False, default="pinion_compliant",
        help="split pinion: the gear table of the compliant (inner) path's pinion"),
    Field("output", "string", required=False, default="output",
        help="split pinion: the gear table of the output gear"),
    Field("pinion_axial_gap", "length", required=False, default=0.0, minimum=0.0,
        help="split pinion and axial preload: axial gap between the two pinions"),
    Field("circumferential_backlash_min", "length", required=False, default=None, minimum=0.0,
        help="split pinion and axial preload: smallest backlash of each pinion with the output (circumferential, at "
             "the reference circles)"),
    Field("circumferential_backlash_max", "length", required=False, default=None, minimum=0.0,
        help="split pinion and axial preload: largest backlash of each pinion with the output (circumferential, at "
             "the reference circles)"),
]

#: the [parts] keys of its hardware (bearing_clearance besides)
PARTS_FIELDS = [
    positive_length("hollow_shaft_outer_diameter", help="hollow shaft of the stiff path (equal to the stiff pinion's bore)"),
    positive_length("hollow_shaft_length", help="hollow shaft from the stiff pinion's far face to the clamp collar"),
    positive_length("bearing_outer_diameter", help="outer diameter of the hollow shaft's bearing pair"),
    positive_length("bearing_width", help="width of each of the hollow shaft's bearings"),
    positive_length("bearing_spacing", required=False, default=None,
        help="centre distance of the hollow shaft's two bearings (default: side by side, a bearing_clearance "
        "apart); the stiff pinion overhangs the upper one"),
    positive_length("collar_outer_diameter", help="clamp collar joining inner and hollow shaft (the frictional interface)"),
    positive_length("collar_width", help="width of the clamp collar"),
    positive_length("collar_slot", help="width of the collar's clamping slot"),
    positive_length("compliant_bearing_outer_diameter",
        help="outboard bearing above the compliant pinion (bore: the compliant pinion's), held by the top plate"),
    positive_length("compliant_bearing_width", help="width of the outboard bearing above the compliant pinion"),
    positive_length("housing_margin", required=False, default=5.0,
        help="top and bottom plates: material left around the outermost bearing seats"),
    positive_length("output_shaft_diameter",
        help="output shaft (checked against its bearing; the model takes the output's bore)"),
    positive_length("output_bearing_outer_diameter", help="outer diameter of the output shaft's bearings"),
    positive_length("output_bearing_width", help="width of the output shaft's bearings"),
]


#: whether [stages] may drive its input gear (the pinions turn with the input: no stages before them)
TAKES_STAGES = False
#: the [stiffness] train it requires (its own, and the only one it takes)
STIFFNESS_TRAIN = "split_pinion"
REQUIRED = ("centre_distance", "circumferential_backlash_min", "circumferential_backlash_max")
ORDERED = (("circumferential_backlash_min", "circumferential_backlash_max"),)
NEEDS = ()
MUST_EXCEED = (("bearing_outer_diameter", "hollow_shaft_outer_diameter"),
               ("compliant_bearing_outer_diameter", "gears.pinion_compliant"),
               ("output_bearing_outer_diameter", "output_shaft_diameter"))
SYMMETRY_LINE = False


def check_layout(design, v) -> None:
    """The gear tables [layout] names exist, and the two pinions have one tooth count."""
    for role in ("pinion_stiff", "pinion_compliant", "output"):
        if v[role] not in design.gears:
            key = f"layout.{role}" if role in design.section("layout") else f"gears.{v[role]}"
            raise DesignError(key, f"no gear named {v[role]!r} in the design", ", ".join(design.gears))
    stiff, compliant = design.gears[v["pinion_stiff"]], design.gears[v["pinion_compliant"]]
    if compliant.teeth != stiff.teeth:
        # the pinions turn together: with other teeth they would drive the output at two speeds
        raise DesignError(f"gears.{v['pinion_compliant']}.teeth", f"{compliant.teeth} teeth, but "
                          f"gears.{v['pinion_stiff']} has {stiff.teeth}: the two pinions turn together on one "
                          "axis and mesh one output", f"{stiff.teeth}")
