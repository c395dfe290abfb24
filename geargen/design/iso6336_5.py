"""ISO 6336-5:2016 Table 8 for the materials geargen rates: the one home of these numbers.

Each row is one line of the standard's figures 1-17, ``sigma = A x + B`` (N/mm^2) for the surface
hardness ``x`` in HV within ``[low, high]``, per quality grade (ML: modest demands; MQ: what an
experienced maker meets at moderate cost; ME: the highest quality). The design loader checks a
``[materials.GEAR]`` or ``[duty]`` hardness against these ranges
(:mod:`geargen.design.duty`); :mod:`geargen.core.iso6336_materials` builds its allowable stress
lines, life curves and the rest of each material from them. Case carburised bending numbers are
those for a core hardness of at least 30 HRC.
"""

from __future__ import annotations

QUALITY_GRADES = ("ML", "MQ", "ME")

#: material name -> (description, {"contact": {grade: (A, B, low HV, high HV)}, "bending": {...}})
TABLE_8: dict[str, tuple[str, dict[str, dict[str, tuple[float, float, float, float]]]]] = {
    "through_hardened": (
        "through hardened wrought alloy steel (quenched and tempered)",
        {"contact": {"ML": (1.313, 188, 200, 360), "MQ": (1.313, 373, 200, 360), "ME": (2.213, 260, 200, 390)},
         "bending": {"ML": (0.423, 104, 200, 360), "MQ": (0.425, 187, 200, 360), "ME": (0.358, 231, 200, 390)}}),
    "through_hardened_carbon": (
        "through hardened wrought plain carbon steel",
        {"contact": {"ML": (0.963, 283, 135, 210), "MQ": (0.925, 360, 135, 210), "ME": (0.838, 432, 135, 210)},
         "bending": {"ML": (0.250, 108, 115, 215), "MQ": (0.240, 163, 115, 215), "ME": (0.283, 202, 115, 215)}}),
    "case_carburised": (
        "case carburised and hardened wrought steel (core hardness >= 30 HRC)",
        {"contact": {"ML": (0.0, 1300, 600, 800), "MQ": (0.0, 1500, 660, 800), "ME": (0.0, 1650, 660, 800)},
         "bending": {"ML": (0.0, 312, 600, 800), "MQ": (0.0, 500, 660, 800), "ME": (0.0, 525, 660, 800)}}),
    "induction_hardened": (
        "induction (or flame) hardened wrought steel, root hardened",
        {"contact": {"ML": (0.740, 602, 485, 615), "MQ": (0.541, 882, 500, 615), "ME": (0.505, 1013, 500, 615)},
         "bending": {"ML": (0.305, 76, 485, 615), "MQ": (0.138, 290, 500, 570), "ME": (0.271, 237, 500, 570)}}),
    "nitrided": (
        "gas nitrided nitriding steel",
        {"contact": {"ML": (0.0, 1125, 650, 900), "MQ": (0.0, 1125, 650, 900), "ME": (0.0, 1450, 650, 900)},
         "bending": {"ML": (0.0, 270, 650, 900), "MQ": (0.0, 420, 650, 900), "ME": (0.0, 468, 650, 900)}}),
}

MATERIAL_NAMES = tuple(TABLE_8)


def hardness_range(material: str, quality: str) -> tuple[float, float]:
    """The surface hardness (HV) both of the material's lines cover for ``quality``: where the
    standard gives an allowable contact and bending stress number."""
    lines = TABLE_8[material][1]
    return (max(lines["contact"][quality][2], lines["bending"][quality][2]),
            min(lines["contact"][quality][3], lines["bending"][quality][3]))


def hardness_needed(material: str, quality: str) -> bool:
    """True when the material's numbers grow with the hardness (a sloped line): then it must be given."""
    lines = TABLE_8[material][1]
    return lines["contact"][quality][0] != 0 or lines["bending"][quality][0] != 0


__all__ = ["QUALITY_GRADES", "TABLE_8", "MATERIAL_NAMES", "hardness_range", "hardness_needed"]
