"""``geargen gear --kind internal``'s own option: the ring blank's outer diameter.

Every common gear option applies to a ring too (it is a GearSpec); ``--bore`` is refused by the
spec (a ring has no bore)."""

from __future__ import annotations

#: argparse dest -> (flag, design-table key stem, whether it is a length in the pitch system's unit)
OPTIONS = {"rim_diameter": ("--rim-diameter", "rim_diameter", True)}
#: the common options the kind reads (only consulted for non-cylindrical families: all apply)
COMMON = ("teeth", "module", "diametral_pitch", "pitch_system", "pressure_angle", "helix_angle", "hand",
          "profile_shift", "face_width", "face_width_mm", "face_width_in", "thinning", "accuracy_grade")


def add_arguments(group) -> None:
    group.add_argument("--rim-diameter", type=float, default=None, metavar="LEN", dest="rim_diameter",
                       help="outer diameter of the ring blank in the design's unit (default: root diameter + 7 "
                            "modules, ISO 6336-3's rim for Y_B = 1)")
