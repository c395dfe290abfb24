"""ISO 286-1:2010 limits of sizes: standard tolerance grades and the fundamental deviations of the
tolerance classes a gear drawing uses (pure tables; sizes in mm, deviations in um).

A tolerance class is a letter and a grade: ``H7`` (a hole), ``h11`` (a shaft). Its limit
deviations are computed from ISO 286-1 Table 1 (the standard tolerance IT of the grade for the
nominal size's range) and the fundamental deviation of the letter:

* ``H`` (holes): lower deviation EI = 0, upper ES = +IT;
* ``h`` (shafts): upper deviation es = 0, lower ei = -IT;
* ``JS`` / ``js``: symmetric, +-IT/2.

The letters that need ISO 286-1's fundamental-deviation tables (F, G, K, ... f, g, k, ...) are
not implemented and are refused naming the ones that are.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from geargen.errors import DesignError

#: ISO 286-1 Table 1: upper limits (mm) of the nominal size ranges ("above .. up to and including"),
#: the first range being 0 < D <= 3
SIZE_STEPS_MM = (3, 6, 10, 18, 30, 50, 80, 120, 180, 250, 315, 400, 500)

#: ISO 286-1 Table 1: standard tolerance values (um) of grades IT4..IT13, one per size range
IT_UM: dict[int, tuple[float, ...]] = {
    4: (3, 4, 4, 5, 6, 7, 8, 10, 12, 14, 16, 18, 20),
    5: (4, 5, 6, 8, 9, 11, 13, 15, 18, 20, 23, 25, 27),
    6: (6, 8, 9, 11, 13, 16, 19, 22, 25, 29, 32, 36, 40),
    7: (10, 12, 15, 18, 21, 25, 30, 35, 40, 46, 52, 57, 63),
    8: (14, 18, 22, 27, 33, 39, 46, 54, 63, 72, 81, 89, 97),
    9: (25, 30, 36, 43, 52, 62, 74, 87, 100, 115, 130, 140, 155),
    10: (40, 48, 58, 70, 84, 100, 120, 140, 160, 185, 210, 230, 250),
    11: (60, 75, 90, 110, 130, 160, 190, 220, 250, 290, 320, 360, 400),
    12: (100, 120, 150, 180, 210, 250, 300, 350, 400, 460, 520, 570, 630),
    13: (140, 180, 220, 270, 330, 390, 460, 540, 630, 720, 810, 890, 970),
}

#: the letters implemented: holes (upper case) and shafts (lower case)
HOLE_LETTERS = ("H", "JS")
SHAFT_LETTERS = ("h", "js")
_CODE = re.compile(r"^(JS|js|[A-Za-z])(\d{1,2})$")


@dataclass(frozen=True)
class ToleranceClass:
    """A tolerance class of ISO 286-1 at a nominal size: ``code`` (``H7``), ``size`` (mm) and its
    ``lower``/``upper`` limit deviations (um)."""

    code: str
    size: float
    lower_um: float
    upper_um: float

    def to_dict(self) -> dict:
        return {"standard": "ISO 286-1:2010", "code": self.code, "lower_deviation_um": self.lower_um,
                "upper_deviation_um": self.upper_um}


def _allowed(feature: str) -> str:
    letters = HOLE_LETTERS if feature == "hole" else SHAFT_LETTERS
    return f"a {feature} tolerance class of ISO 286-1: {' or '.join(letters)} with a grade {min(IT_UM)}..{max(IT_UM)} " \
           f"(e.g. {letters[0]}7)"


def standard_tolerance_um(size_mm: float, grade: int, field: str = "tolerance_class") -> float:
    """IT``grade`` (um) of ISO 286-1 Table 1 for the nominal size ``size_mm``."""
    if grade not in IT_UM:
        raise DesignError(field, f"IT{grade} is not tabulated here", f"IT{min(IT_UM)}..IT{max(IT_UM)}")
    if not (0 < size_mm <= SIZE_STEPS_MM[-1]):
        raise DesignError(field, f"the nominal size {size_mm:.6g} mm is outside ISO 286-1 Table 1 as implemented",
                          f"(0, {SIZE_STEPS_MM[-1]}] mm")
    row = next(i for i, top in enumerate(SIZE_STEPS_MM) if size_mm <= top)
    return float(IT_UM[grade][row])


def tolerance_class(code: str, size_mm: float, feature: str, field: str = "tolerance_class") -> ToleranceClass:
    """The limits of ``code`` (``"H7"``, ``"h11"``, ``"JS8"``) at ``size_mm``; ``feature`` is
    ``"hole"`` or ``"shaft"`` (a hole letter on a shaft is refused, naming ``field``)."""
    m = _CODE.match(code.strip()) if isinstance(code, str) else None
    letters = HOLE_LETTERS if feature == "hole" else SHAFT_LETTERS
    if not m or m.group(1) not in letters:
        raise DesignError(field, f"{code!r} is not an implemented {feature} tolerance class", _allowed(feature))
    letter, grade = m.group(1), int(m.group(2))
    it = standard_tolerance_um(size_mm, grade, field)
    if letter in ("H",):
        lower, upper = 0.0, it
    elif letter == "h":
        lower, upper = -it, 0.0
    else:  # JS / js
        lower, upper = -it / 2, it / 2
    return ToleranceClass(f"{letter}{grade}", float(size_mm), lower, upper)


__all__ = ["SIZE_STEPS_MM", "IT_UM", "HOLE_LETTERS", "SHAFT_LETTERS", "ToleranceClass", "standard_tolerance_um",
           "tolerance_class"]
