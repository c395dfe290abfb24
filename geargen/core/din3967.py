"""DIN 3967:1978-08 (system of gear fits): the tooth-thickness allowance of a gear from its
designation, e.g. ``cd25``: upper allowance series ``cd`` (Table 1: A_sne, in DIN 21773 / ISO
21771 notation E_sns) and tolerance series ``25`` (Table 2: T_s), both by reference diameter d.
The lower allowance is A_sni = A_sne - T_s. Pure tables, um and mm.

The standard's own example (DIN 3967, clause 3.1): ``27cd`` at d = 100 mm gives A_sne = -70 um and
A_sni = -170 um.
"""

from __future__ import annotations

import re

from geargen.errors import DesignError

#: Tables 1 and 2: upper limits of the reference-diameter ranges (mm): "above .. up to and including"
DIAMETER_STEPS_MM = (10, 50, 125, 280, 560, 1000, 1600, 2500, 4000, 6300, 10000)
UPPER_SERIES = ("a", "ab", "b", "bc", "c", "cd", "d", "e", "f", "g", "h")
TOLERANCE_SERIES = (21, 22, 23, 24, 25, 26, 27, 28, 29, 30)

#: Table 1: upper tooth-thickness allowance A_sne (um), one row per diameter range, one column per series
UPPER_UM = (
    (-100, -85, -70, -58, -48, -40, -33, -22, -10, -5, 0),
    (-135, -110, -95, -75, -65, -54, -44, -30, -14, -7, 0),
    (-180, -150, -125, -105, -85, -70, -60, -40, -19, -9, 0),
    (-250, -200, -170, -140, -115, -95, -80, -56, -26, -12, 0),
    (-330, -280, -230, -190, -155, -130, -110, -75, -35, -17, 0),
    (-450, -370, -310, -260, -210, -175, -145, -100, -48, -22, 0),
    (-600, -500, -420, -340, -290, -240, -200, -135, -64, -30, 0),
    (-820, -680, -560, -460, -390, -320, -270, -180, -85, -41, 0),
    (-1100, -920, -760, -620, -520, -430, -360, -250, -115, -56, 0),
    (-1500, -1250, -1020, -840, -700, -580, -480, -330, -155, -75, 0),
    (-2000, -1650, -1350, -1150, -940, -780, -640, -450, -210, -100, 0),
)
#: Table 2: tooth-thickness tolerance T_s (um), one row per diameter range, one column per series
TOLERANCE_UM = (
    (3, 5, 8, 12, 20, 30, 50, 80, 130, 200),
    (5, 8, 12, 20, 30, 50, 80, 130, 200, 300),
    (6, 10, 16, 25, 40, 60, 100, 160, 250, 400),
    (8, 12, 20, 30, 50, 80, 130, 200, 300, 500),
    (10, 16, 25, 40, 60, 100, 160, 250, 400, 600),
    (12, 20, 30, 50, 80, 130, 200, 300, 500, 800),
    (16, 25, 40, 60, 100, 160, 250, 400, 600, 1000),
    (20, 30, 50, 80, 130, 200, 300, 500, 800, 1300),
    (25, 40, 60, 100, 160, 250, 400, 600, 1000, 1600),
    (30, 50, 80, 130, 200, 300, 500, 800, 1300, 2000),
    (40, 60, 100, 160, 250, 400, 600, 1000, 1600, 2400),
)

#: the designation a gear without an allowance of its own is given: series cd (the one DIN 3967 shows
#: for machine-tool gearing, backlash without crowding the tooth) with tolerance series 25 (ISO 1328
#: grades 6 to 7, what the default accuracy grade 7 is cut to)
DEFAULT_DESIGNATION = "cd25"
_DESIGNATION = re.compile(r"^(?:([a-h]{1,2})(\d{2})|(\d{2})([a-h]{1,2}))$")
STANDARD = "DIN 3967:1978-08"


def parse_designation(text: str, field: str = "thickness_allowance_series") -> tuple[str, int]:
    """``"cd25"`` or ``"25cd"`` -> ``("cd", 25)``; anything else a DesignError naming ``field``."""
    m = _DESIGNATION.match(text.strip()) if isinstance(text, str) else None
    series, tol = (m.group(1) or m.group(4), int(m.group(2) or m.group(3))) if m else (None, None)
    if series not in UPPER_SERIES or tol not in TOLERANCE_SERIES:
        raise DesignError(field, f"{text!r} is not a DIN 3967 designation",
                          f"an upper series {', '.join(UPPER_SERIES)} and a tolerance series 21..30, e.g. "
                          f"{DEFAULT_DESIGNATION!r}")
    return series, tol


def _row(reference_diameter_mm: float, field: str) -> int:
    if not 0 < reference_diameter_mm <= DIAMETER_STEPS_MM[-1]:
        raise DesignError(field, f"reference diameter {reference_diameter_mm:.6g} mm is outside {STANDARD}'s tables",
                          f"(0, {DIAMETER_STEPS_MM[-1]}] mm")
    return next(i for i, top in enumerate(DIAMETER_STEPS_MM) if reference_diameter_mm <= top)


def allowance_um(reference_diameter_mm: float, designation: str,
                 field: str = "thickness_allowance_series") -> tuple[float, float]:
    """(A_sne, A_sni) in um of ``designation`` (``"cd25"``) at the reference diameter (mm)."""
    series, tol = parse_designation(designation, field)
    row = _row(reference_diameter_mm, field)
    upper = float(UPPER_UM[row][UPPER_SERIES.index(series)])
    return upper, upper - float(TOLERANCE_UM[row][TOLERANCE_SERIES.index(tol)])


def method_text(designation: str) -> str:
    """How the allowance was chosen, as the JSON and the drawing state it."""
    series, tol = parse_designation(designation)
    return (f"{STANDARD} {series}{tol} (Tables 1 and 2): upper allowance series {series}, tolerance series {tol}, "
            "by reference diameter")


__all__ = ["DIAMETER_STEPS_MM", "UPPER_SERIES", "TOLERANCE_SERIES", "UPPER_UM", "TOLERANCE_UM",
           "DEFAULT_DESIGNATION", "STANDARD", "parse_designation", "allowance_um", "method_text"]
