"""The keys of the beam_pinion drive (a dual pinion whose long input pinion is a beam spring, the pinions sliding axially into mesh (the C-axis, Fig. 12)): its ``[layout]`` keys and its ``[parts]`` hardware."""

from __future__ import annotations

from geargen.drives.beam_pinion import defaults  # noqa: F401  (its default hardware, the loader's)
from geargen.drives.fields import part_key, positive_length
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES

NAME = "beam_pinion"
#: the [layout] kind that selects the drive
LAYOUT_KIND = "dual_pinion"

#: its [layout] keys: the dual pinion's (one layout, another hardware)
from geargen.drives.dual_pinion.keys import LAYOUT_FIELDS, check_layout  # noqa: E402,F401

#: the [parts] keys of its hardware (bearing_clearance besides)
PARTS_FIELDS = [
    positive_length("spindle_diameter",
        help="lathe spindle through the bull gear (reference; the model takes the output's bore)"),
    positive_length("spindle_length", help="length of the spindle stub"),
    positive_length("input_shaft_diameter", help="shaft of the long input pinion"),
    positive_length("input_bearing_outer_diameter",
        help="outer diameter of the long pinion's bearings (at the beam's supports)"),
    positive_length("input_bearing_width", help="width of the long pinion's bearings"),
    positive_length("cluster_shaft_diameter", help="dual-pinion shaft (equal to the cluster gears' bore)"),
    positive_length("cluster_bearing_outer_diameter", help="outer diameter of the bearings in each sliding quill"),
    positive_length("cluster_bearing_width", help="width of the bearings in each sliding quill"),
    positive_length("cluster_bearing_spacing", help="distance between the two bearings of a quill"),
    positive_length("friction_ring_outer_diameter",
        help="locking ring clamping the large gear to its shaft (the frictional interface)"),
    positive_length("friction_ring_width", help="width of the locking ring"),
    positive_length("locknut_outer_diameter",
        help="locknut under each dual pinion's lower bearing, clamping the inner rings to the shaft"),
    positive_length("locknut_width", help="width of the locknut (the shaft ends at its lower face)"),
    positive_length("quill_outer_diameter",
        help="sleeve that holds a dual pinion's two bearings by their outer rings and slides in the housing "
        "block's bore (its bore: the bearings' outer diameter)"),
    positive_length("stop_lug_length", help="how far the quill's lug, which meets the travel stops, reaches beyond the quill"),
    positive_length("stop_lug_width", help="width of the quill's lug"),
    positive_length("stop_lug_thickness", help="thickness of the quill's lug along the axis, at the quill's lower end"),
    positive_length("stop_block_size", help="side of the square travel stops under the housing block"),
    positive_length("coupling_diameter", help="coupling between gearhead and long pinion shaft"),
    positive_length("coupling_length", help="length of the coupling"),
    positive_length("gearhead_diameter", help="planetary gearhead on the motor"),
    positive_length("gearhead_length", help="length of the gearhead"),
    positive_length("motor_body_diameter", help="servo motor body (with encoder), envelope diameter"),
    positive_length("motor_body_length", help="servo motor body length"),
    positive_length("motor_flange", help="side of the motor's square mounting flange"),
    positive_length("motor_flange_thickness", help="thickness of the motor flange"),
    positive_length("housing_thickness",
        help="thickness of the housing block: the length of the bores the quills slide in"),
    positive_length("housing_margin", help="housing block's wall around the quill bores, the long pinion's hole and the stops"),
    positive_length("drive_column_width",
        help="width of the column beside the long pinion and of the plates on it that seat the long pinion's "
        "bearings"),
    positive_length("drive_column_thickness", help="thickness of that column, away from the long pinion"),
    positive_length("motor_plate_thickness",
        help="plate on the column between gearhead and motor: both bolt to it, the motor's shaft reaches "
        "through it into the gearhead"),
]


#: whether [stages] may drive its input gear (a gearhead drives the long pinion: [layout] upstream_stages)
TAKES_STAGES = False
#: the [stiffness] train it requires (None: the file's, dual_pinion by default, or custom)
STIFFNESS_TRAIN = None
REQUIRED = ()
ORDERED = ()
NEEDS = ("beam_pinion", "engagement")
MUST_EXCEED = (("input_bearing_outer_diameter", "input_shaft_diameter"),
               ("cluster_bearing_outer_diameter", "cluster_shaft_diameter"),
               ("friction_ring_outer_diameter", "cluster_shaft_diameter"),
               ("locknut_outer_diameter", "cluster_shaft_diameter"),
               ("cluster_bearing_outer_diameter", "locknut_outer_diameter"),
               ("quill_outer_diameter", "cluster_bearing_outer_diameter"),
               ("drive_column_width", "input_bearing_outer_diameter"))
SYMMETRY_LINE = True


def check_parts(design, v) -> None:
    """The travel stops stand over the lug's outer end, a stop's side from it: they must clear the quill."""
    unit = design.length_unit
    scale = LENGTH_SUFFIXES[unit]
    reach = v["stop_block_size"] + v["bearing_clearance"]
    if not v["stop_lug_length"] > reach:
        raise DesignError(part_key(v, "stop_lug_length"), f"{v['stop_lug_length'] / scale:.6g} {unit} puts the "
                          "travel stops against the quill", f"> {reach / scale:.6g} {unit} (stop_block_size + "
                          "bearing_clearance)")
