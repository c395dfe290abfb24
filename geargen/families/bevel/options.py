"""``geargen gear --kind bevel`` options: the mate, the shaft angle and the thinning of a straight bevel gear.

Each option maps to a key of the ``[gear] kind = "bevel"`` table (:mod:`geargen.families.bevel.spec`), so the
command line and a design file are read by the same reader.
"""

from __future__ import annotations

#: argparse dest -> (flag, design-table key stem, whether a length in the pitch system's unit)
OPTIONS = {
    "mate_teeth": ("--mate-teeth", "mate_teeth", False),
    "shaft_angle": ("--shaft-angle", "shaft_angle_deg", False),
    "bevel_thinning": ("--bevel-thinning", "thinning_circumferential", True),
    "bevel_back": ("--back", "back", False),
}

#: the common gear options a bevel gear reads
COMMON = ("teeth", "module", "diametral_pitch", "pressure_angle", "profile_shift", "face_width", "face_width_mm",
          "face_width_in", "bore", "bore_mm", "bore_in", "accuracy_grade")


def add_arguments(group) -> None:
    group.add_argument("--mate-teeth", type=int, default=None, metavar="Z",
                       help="teeth of the mating bevel gear (sets the pitch cone angle)")
    group.add_argument("--shaft-angle", type=float, default=None, metavar="DEG",
                       help="angle between the two gears' axes, degrees (default 90)")
    group.add_argument("--bevel-thinning", type=float, default=None, metavar="LEN",
                       help="tooth thinning for backlash, an arc of the heel pitch circle, in the unit of the pitch "
                            "system (default 0)")
    group.add_argument("--back", dest="bevel_back", choices=("flat", "spherical"), default=None,
                       help="the gear's back: flat through the heel root circle (default, as the robot joint's pair "
                            "is built) or the heel sphere")
