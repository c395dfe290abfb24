"""``geargen gear --kind worm`` / ``--kind worm_wheel``: the worm-gear set's own options.

Both parts of a set take the same options (a set is defined together); each option maps to the
key of the ``[gear]`` table with ``kind = "worm"`` or ``"worm_wheel"`` (geargen.families.worm.spec)."""

from __future__ import annotations

#: argparse dest -> (flag, design-table key stem, whether the value is a length in the pitch system's unit)
OPTIONS = {
    "starts": ("--starts", "starts", False),
    "wheel_teeth": ("--wheel-teeth", "wheel_teeth", False),
    "diameter_quotient": ("--diameter-quotient", "diameter_quotient", False),
    "worm_reference_diameter": ("--worm-diameter", "worm_reference_diameter", True),
    "worm_face_length": ("--worm-length", "worm_face_length", True),
    "wheel_face_width": ("--wheel-width", "wheel_face_width", True),
    "wheel_outside_diameter": ("--wheel-outside-diameter", "wheel_outside_diameter", True),
    "wheel_profile_shift": ("--wheel-profile-shift", "wheel_profile_shift", False),
    "pressure_angle_system": ("--pressure-angle-system", "pressure_angle_system", False),
    "worm_backlash": ("--backlash", "backlash", True),
    "backlash_on": ("--backlash-on", "backlash_on", False),
}

#: the common gear options a worm set reads (module or diametral pitch is the axial one)
COMMON = ("module", "diametral_pitch", "pressure_angle", "hand")


def add_arguments(group) -> None:
    group.add_argument("--starts", type=int, metavar="Z1", help="threads (starts) of the worm")
    group.add_argument("--wheel-teeth", type=int, metavar="Z2", help="teeth of the worm wheel")
    group.add_argument("--diameter-quotient", type=float, metavar="Q", help="q = d1 / m_x (or --worm-diameter)")
    group.add_argument("--worm-diameter", dest="worm_reference_diameter", type=float, metavar="LEN",
                       help="worm reference diameter d1 (or --diameter-quotient)")
    group.add_argument("--worm-length", dest="worm_face_length", type=float, metavar="LEN",
                       help="length of the worm's thread")
    group.add_argument("--wheel-width", dest="wheel_face_width", type=float, metavar="LEN", help="wheel face width")
    group.add_argument("--wheel-outside-diameter", type=float, metavar="LEN",
                       help="outside diameter of the wheel rim (default: throat diameter + m_x, less where the "
                            "teeth would keep under 0.1 m_x of tip land at the face ends)")
    group.add_argument("--wheel-profile-shift", type=float, metavar="X2", help="wheel profile shift coefficient")
    group.add_argument("--pressure-angle-system", choices=("normal", "axial"),
                       help="whether --pressure-angle is the thread's normal (default) or axial angle")
    group.add_argument("--backlash", dest="worm_backlash", type=float, metavar="LEN",
                       help="design backlash, circumferential at the wheel reference circle")
    group.add_argument("--backlash-on", choices=("wheel", "worm"), help="which part is thinned by the backlash")
