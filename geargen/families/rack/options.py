"""``geargen gear --kind rack`` options: a rack's own keys (:mod:`geargen.families.rack.spec`).

Each option sets the rack table key of the same meaning, so the command line and a ``[gear]``
table with ``kind = "rack"`` go through one reader (:func:`geargen.families.rack.spec.rack_from_table`).
"""

from __future__ import annotations

import dataclasses

from geargen.errors import DesignError
from geargen.families.rack.spec import TIP_ROUNDINGS

#: argparse dest -> (flag, design-table key stem, whether the value is a length in the pitch system's unit)
OPTIONS = {
    "rack_pitch_line_height": ("--height", "pitch_line_height", True),
    "rack_back_height": ("--back-height", "back_height", True),
    "rack_length": ("--rack-length", "length", True),
    "rack_tip_rounding": ("--tip-rounding", "tip_rounding", False),
    "rack_tip_radius_coefficient": ("--tip-radius-coefficient", "tip_radius_coefficient", False),
    "rack_root_fillet_coefficient": ("--root-fillet-coefficient", "root_fillet_coefficient", False),
}

#: the common gear options a rack reads (module or pitch, pressure and helix angle, hand, teeth,
#: face width, thinning along the pitch line)
COMMON = ("teeth", "module", "diametral_pitch", "pressure_angle", "helix_angle", "hand", "face_width",
          "face_width_mm", "face_width_in", "thinning")


def add_arguments(group) -> None:
    group.add_argument("--height", dest="rack_pitch_line_height", type=float, default=None, metavar="LEN",
                       help="rack: back face to pitch line, in the pitch system's unit (default: 2 modules of back "
                            "under the root line)")
    group.add_argument("--back-height", dest="rack_back_height", type=float, default=None, metavar="LEN",
                       help="rack: back face to root line (instead of --height)")
    group.add_argument("--rack-length", dest="rack_length", type=float, default=None, metavar="LEN",
                       help="rack: length, a whole number of transverse pitches (instead of --teeth)")
    group.add_argument("--tip-rounding", dest="rack_tip_rounding", choices=TIP_ROUNDINGS, default=None,
                       help="rack: sharp tip corners (default) or rounded like the pinion's generating rack tip")
    group.add_argument("--tip-radius-coefficient", dest="rack_tip_radius_coefficient", type=float, default=None,
                       metavar="RHO", help="rack: generating tip radius over the module (default 0.38 or the "
                                           "largest that fits)")
    group.add_argument("--root-fillet-coefficient", dest="rack_root_fillet_coefficient", type=float, default=None,
                       metavar="RHO", help="rack: root fillet radius over the module (default 0.38 or the largest "
                                           "that fits; 0: sharp)")


def with_allowance(spec, given: tuple[float, float]):
    """The rack with the allowance ``--thickness-allowance UPPER LOWER`` (um) gives it: a rack carries
    its allowance in its spec (its deviations); refused when its design table gives one too."""
    from geargen.core.allowance import ThicknessAllowance
    if spec.thickness_deviations is not None:
        raise DesignError("--thickness-allowance", f"conflicts with the thickness deviations the design file gives "
                          f"rack {spec.name}", "the option or the design keys, not both")
    checked = ThicknessAllowance(given[0] * 1e-3, given[1] * 1e-3, field="--thickness-allowance")
    return dataclasses.replace(spec, thickness_deviations=(checked.upper, checked.lower))
