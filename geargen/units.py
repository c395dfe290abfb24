"""Units: geargen computes in mm, rad, N (torques in N·mm). Conversion happens here, once, at the edge.

Design-file keys carry their unit as a suffix (``face_width_in``, ``pressure_angle_deg``,
``runout_um``); :data:`LENGTH_SUFFIXES` and :data:`ANGLE_SUFFIXES` list the accepted ones.
"""

from __future__ import annotations

import math

MM_PER_IN = 25.4

#: factor that turns a value in the suffix's unit into mm
LENGTH_SUFFIXES: dict[str, float] = {"mm": 1.0, "in": MM_PER_IN, "um": 1e-3, "m": 1e3}
#: factor that turns a value in the suffix's unit into rad
ANGLE_SUFFIXES: dict[str, float] = {"deg": math.pi / 180.0, "rad": 1.0, "urad": 1e-6, "arcsec": math.pi / 648000.0,
                                   "arcmin": math.pi / 10800.0}

#: design length units a file may declare (the unit exports and reports use)
LENGTH_UNITS = ("mm", "in")


def to_mm(value: float, unit: str) -> float:
    """Length in ``unit`` (one of :data:`LENGTH_SUFFIXES`) to mm."""
    return value * LENGTH_SUFFIXES[unit]


def from_mm(value_mm, unit: str):
    """Length in mm to ``unit``; works on floats and numpy arrays."""
    return value_mm / LENGTH_SUFFIXES[unit]


def length_text(value_mm: float, unit: str, digits: int = 4) -> str:
    """A length (mm) as text in the design's ``unit``: ``"0.02033 in"``."""
    return f"{from_mm(value_mm, unit):.{digits}g} {unit}"


def module_from_diametral_pitch(diametral_pitch_per_in: float) -> float:
    """Module in mm of a diametral pitch in teeth per inch of pitch diameter (m = 25.4 / P)."""
    return MM_PER_IN / diametral_pitch_per_in


def diametral_pitch_from_module(module_mm: float) -> float:
    return MM_PER_IN / module_mm
