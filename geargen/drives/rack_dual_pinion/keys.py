"""The keys of the rack_dual_pinion drive (the Type 2 dual-pinion rack drive (Fig. 4 done as Type 2)): its ``[layout]`` keys and its ``[parts]`` hardware."""

from __future__ import annotations

from geargen.design.schema import Field
from geargen.drives.fields import positive_length
from geargen.drives.rack_dual_pinion import defaults  # noqa: F401  (its default hardware, the loader's)

NAME = "rack_dual_pinion"
#: the [layout] kind that selects the drive
LAYOUT_KIND = "rack_dual_pinion"
#: what it is, in the [layout] kind key's help (the reference's list of kinds)
LAYOUT_HELP = "two rack pinions driven through a preload carriage"

#: the [layout] keys this kind reads besides the common ones
LAYOUT_FIELDS = [
    Field("carriage_travel", "length", required=False, default=None, minimum=0.0,
        help="dual pinion and rack drive: travel of the preload carriage either way, drawn in the layout and the report"),
    Field("pinion_spacing", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
        help="rack drive: distance along the rack between the two path shafts (each carries a rack pinion and a "
             "path gear)"),
    Field("input_centre_distance", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
        help="rack drive: design centre distance of the input gear (on the preload carriage) from each path gear: "
             "the carriage's nominal height"),
    Field("rack_backlash_min", "length", required=False, default=None, minimum=0.0,
        help="rack drive: smallest circumferential backlash of each pinion on the rack (set by the pinions' centre "
             "height)"),
    Field("rack_backlash_max", "length", required=False, default=None, minimum=0.0,
        help="rack drive: largest circumferential backlash of each pinion on the rack"),
    Field("path_backlash_min", "length", required=False, default=None, minimum=0.0,
        help="rack drive: smallest circumferential backlash of the input with each path gear (at the input's "
             "reference circle)"),
    Field("path_backlash_max", "length", required=False, default=None, minimum=0.0,
        help="rack drive: largest circumferential backlash of the input with each path gear"),
    Field("slide_travel", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
        help="rack drive: travel of the machine slide; the rack is this plus the pinions' span long"),
    Field("rack_face_width", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
        help="rack drive: face width of the rack (default: the pinion's)"),
    Field("rack_back_height", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
        help="rack drive: rack back face to its root line (default: 2 modules)"),
    Field("path_gear_axial_gap", "length", required=False, default=2.0, minimum=0.0,
        help="rack drive: axial gap between the pinion and the path gear on each path shaft"),
    Field("rack_loop_error", "length", required=False, default=0.0, minimum=0.0,
        help="rack drive: anticipated loop error as a rack displacement, peak to peak (rack pitch error over the "
             "pinion span, runouts); the carriage must travel far enough to absorb it, and teeth made anywhere in the "
             "backlash ranges"),
    Field("carriage_preload_force_N", "number", required=False, default=None, minimum=0.0, exclusive_minimum=True,
        help="rack drive: the carriage spring's force on the input gear, toward the path shafts (N)"),
    Field("carriage_spring_rate_N_per_mm", "number", required=False, default=None, minimum=0.0,
        exclusive_minimum=True, help="rack drive: the carriage spring's rate along its motion (N/mm)"),
    Field("gear_elastic_modulus_GPa", "number", required=False, default=207.0, minimum=1.0, maximum=1000.0,
        help="rack drive: Young's modulus of the gears and rack for the mesh stiffness of Eq. 1 (steel: 207)"),
    Field("shaft_shear_modulus_GPa", "number", required=False, default=79.3, minimum=1.0, maximum=1000.0,
        help="rack drive: shear modulus of the path shafts, whose torsion between pinion and path gear is in each "
             "path (steel: 79.3)"),
    Field("max_rack_force_N", "number", required=False, default=None, minimum=0.0,
        help="rack drive: largest drive force on the rack (N); both paths must stay loaded up to it"),
]

#: the [parts] keys of its hardware (bearing_clearance besides)
PARTS_FIELDS = [
    positive_length("path_bearing_outer_diameter", help="outer diameter of the path shafts' bearings (bore: the pinion's)"),
    positive_length("path_bearing_width", help="width of the path shafts' bearings (and of the housing plates that hold them)"),
    positive_length("input_bearing_outer_diameter", help="outer diameter of the input shaft's two bearings in the carriage "
        "(bore: the input gear's)"),
    positive_length("input_bearing_width", help="width of each of the input shaft's bearings"),
    positive_length("housing_margin", required=False, default=5.0,
        help="housing plates and carriage: material left around the bearing seats"),
    positive_length("rail_width", help="linear guide rail under the carriage, across its motion"),
    positive_length("rail_height", help="height of the linear guide rail"),
    positive_length("guide_block_length", help="the guide's sliding block along the motion"),
    positive_length("guide_block_height", help="height of the guide's sliding block (rail top to carriage)"),
    positive_length("spring_wire_diameter", help="carriage spring wire (its active coils follow from the spring rate)"),
    positive_length("spring_mean_diameter", help="carriage spring mean coil diameter"),
    positive_length("spring_installed_length", help="carriage spring length as installed (preloaded)"),
    positive_length("spring_post_thickness", help="the post on the top plate the spring pushes from, along the motion"),
    Field("spring_shear_modulus_GPa", "number", required=False, default=79.3, minimum=1.0,
        help="shear modulus of the spring wire (music wire: 79.3)"),
]


#: whether [stages] may drive its input gear (the motor stands on the carriage over the input shaft)
TAKES_STAGES = False
#: the [stiffness] train it requires (None: the file's, dual_pinion by default, or custom)
STIFFNESS_TRAIN = None
REQUIRED = ("pinion_spacing", "input_centre_distance", "rack_backlash_min", "rack_backlash_max",
            "path_backlash_min", "path_backlash_max", "slide_travel", "carriage_travel",
            "carriage_preload_force_N", "carriage_spring_rate_N_per_mm")
ORDERED = (("rack_backlash_min", "rack_backlash_max"), ("path_backlash_min", "path_backlash_max"))
NEEDS = ()
MUST_EXCEED = (("path_bearing_outer_diameter", "gears.pinion"),
               ("input_bearing_outer_diameter", "gears.input"),
               ("spring_mean_diameter", "spring_wire_diameter"))
SYMMETRY_LINE = False
