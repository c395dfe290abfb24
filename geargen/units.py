"""Units: geargen computes in mm, rad, N (torques in N·mm). Conversion happens here, once, at the edge.

Design-file keys carry their unit as a suffix (``face_width_in``, ``pressure_angle_deg``,
``runout_um``); :data:`LENGTH_SUFFIXES` and :data:`ANGLE_SUFFIXES` list the accepted ones.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

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
    return sizes_text(unit, value_mm, digits=digits)


def sizes_text(unit: str, *values_mm: float, digits: int = 4, sep: str = " x ") -> str:
    """A part's sizes (mm) as text in the design's ``unit``: ``"0.5 x 1.125 x 0.3125 in"``."""
    return sep.join(f"{from_mm(v, unit):.{digits}g}" for v in values_mm) + f" {unit}"


def small_length_text(value_mm: float, unit: str, digits: int = 4) -> str:
    """A deflection, shift or misalignment (mm): µm in a mm design, the design's ``unit`` otherwise."""
    return f"{value_mm * 1e3:.{digits}g} µm" if unit == "mm" else length_text(value_mm, unit, digits)


def module_from_diametral_pitch(diametral_pitch_per_in: float) -> float:
    """Module in mm of a diametral pitch in teeth per inch of pitch diameter (m = 25.4 / P)."""
    return MM_PER_IN / diametral_pitch_per_in


def diametral_pitch_from_module(module_mm: float) -> float:
    return MM_PER_IN / module_mm


def pitch_text(module_mm: float, unit: str, digits: int = 4) -> str:
    """A gear's (normal) size in the design's terms: ``"m_n 1.27 mm"`` or ``"P_n 20/in"`` (diametral pitch)."""
    if unit == "in":
        return f"P_n {diametral_pitch_from_module(module_mm):.{digits}g}/in"
    return f"m_n {module_mm:.{digits}g} mm"


# ----------------------------------------------------------------------------------------------
# Forces, torques, stiffnesses and stresses: the suffixes a design file may use, and the units its text uses

LBF = 4.4482216152605  # N per pound-force
KG_PER_LB = 0.45359237  # the avoirdupois pound (exact by definition)
PSI = LBF / MM_PER_IN ** 2  # MPa per psi

#: factor turning a value in the suffix's unit into the internal unit, per quantity family
#: (internal: N, N·mm, N/mm, N·mm/rad, MPa; the servo's quantities in SI)
QUANTITY_SUFFIXES: dict[str, dict[str, float]] = {
    "force": {"N": 1.0, "kN": 1e3, "lbf": LBF},
    "torque": {"Nmm": 1.0, "Nm": 1e3, "in_lbf": LBF * MM_PER_IN, "ft_lbf": LBF * 12 * MM_PER_IN},
    "linear_stiffness": {"N_per_mm": 1.0, "N_per_um": 1e3, "N_per_m": 1e-3, "kN_per_mm": 1e3,
                         "lbf_per_in": LBF / MM_PER_IN},
    "torsional_stiffness": {"Nmm_per_rad": 1.0, "Nm_per_rad": 1e3, "kNm_per_rad": 1e6,
                            "Nm_per_deg": 1e3 * 180.0 / math.pi, "Nm_per_arcmin": 1e3 * 10800.0 / math.pi,
                            "in_lbf_per_rad": LBF * MM_PER_IN},
    "stress": {"MPa": 1.0, "GPa": 1e3, "Pa": 1e-6, "kPa": 1e-3, "psi": PSI, "ksi": PSI * 1e3, "Mpsi": PSI * 1e6},
    # the servo's quantities ([train]) stay in SI: a motor data sheet's units
    "inertia": {"kg_m2": 1.0, "kg_cm2": 1e-4, "g_cm2": 1e-7, "kg_mm2": 1e-6, "lb_in2": KG_PER_LB * 0.0254 ** 2,
                "oz_in_s2": LBF / 16 * 0.0254},
    "rotary_damping": {"Nm_s_per_rad": 1.0, "Nmm_s_per_rad": 1e-3},
    "torque_constant": {"Nm_per_A": 1.0},
    "frequency": {"Hz": 1.0},
}

#: how a suffix of :data:`QUANTITY_SUFFIXES` is written in text
SUFFIX_TEXT = {"N": "N", "kN": "kN", "lbf": "lbf", "Nmm": "N·mm", "Nm": "N·m", "in_lbf": "in·lbf", "ft_lbf": "ft·lbf",
               "N_per_mm": "N/mm", "N_per_um": "N/µm", "N_per_m": "N/m", "kN_per_mm": "kN/mm", "lbf_per_in": "lbf/in",
               "MPa": "MPa", "GPa": "GPa", "Pa": "Pa", "kPa": "kPa", "psi": "psi", "ksi": "ksi", "Mpsi": "Mpsi"}

#: the families a design's text shows in a unit of its own (masses and inertias follow the length
#: unit, :data:`MASS_TEXT`; the servo's quantities stay in SI)
TEXT_FAMILIES = ("force", "torque", "linear_stiffness", "stress")
#: length unit -> {family: (text, factor turning the internal SI value into it)}: masses (internal kg)
#: and moments of inertia (internal kg·m²) in kg and kg·m² for a mm design, lb and lb·in^2 for an inch one
MASS_TEXT = {"mm": {"mass": ("kg", 1.0), "inertia": ("kg·m^2", 1.0)},
             "in": {"mass": ("lb", 1.0 / KG_PER_LB), "inertia": ("lb·in^2", 1.0 / QUANTITY_SUFFIXES["inertia"]["lb_in2"])}}
#: a family's text unit when the file wrote no key of that family: the length unit's usual one
DEFAULT_TEXT_SUFFIX = {"mm": {"force": "N", "torque": "Nm", "linear_stiffness": "N_per_mm", "stress": "MPa"},
                       "in": {"force": "lbf", "torque": "in_lbf", "linear_stiffness": "lbf_per_in", "stress": "psi"}}
#: suffixes of the inch-pound system (the rest are SI)
IMPERIAL_SUFFIXES = frozenset({"lbf", "in_lbf", "ft_lbf", "lbf_per_in", "in_lbf_per_rad", "psi", "ksi", "Mpsi"})
#: the text unit of a written suffix: a modulus in GPa makes stresses MPa, a torsional stiffness in
#: N·m/rad makes torques N·m
_TEXT_SUFFIX = {"kN": "N", "kN_per_mm": "N_per_mm", "N_per_m": "N_per_mm", "GPa": "MPa", "Pa": "MPa", "kPa": "MPa",
                "Mpsi": "ksi", "Nmm_per_rad": "Nmm", "Nm_per_rad": "Nm", "kNm_per_rad": "Nm", "Nm_per_deg": "Nm",
                "Nm_per_arcmin": "Nm", "in_lbf_per_rad": "in_lbf"}


def quantity_suffix(key: str) -> tuple[str, str] | None:
    """``(family, suffix)`` of a design key ending in a quantity suffix (the longest that fits:
    ``preload_in_lbf`` is a torque, not a force), else None."""
    best = None
    for family, table in QUANTITY_SUFFIXES.items():
        for suffix in table:
            if key.endswith("_" + suffix) and (best is None or len(suffix) > len(best[1])):
                best = (family, suffix)
    return best


@dataclass(frozen=True)
class TextUnits:
    """The units a design's human-readable output uses: lengths in its ``length_unit``; forces,
    torques, linear stiffnesses and stresses in the suffix its file wrote that family in (the first
    such key), else the length unit's usual one (:data:`DEFAULT_TEXT_SUFFIX`); torsional stiffness
    as the torque unit per rad; masses and moments of inertia (internal kg, kg·m²) by the length unit
    (:data:`MASS_TEXT`). Every report formats these quantities through :meth:`text`."""

    length: str = "mm"
    force: str = "N"
    torque: str = "Nm"
    linear_stiffness: str = "N_per_mm"
    stress: str = "MPa"

    def unit(self, family: str) -> str:
        """The unit's text: ``"in"``, ``"in·lbf"``, ``"in·lbf/rad"``, ``"lbf/in"``."""
        if family == "length":
            return self.length
        if family in ("mass", "inertia"):
            return MASS_TEXT[self.length][family][0]
        if family == "torsional_stiffness":
            return f"{SUFFIX_TEXT[self.torque]}/rad"
        return SUFFIX_TEXT[getattr(self, family)]

    def value(self, family: str, internal: float):
        """``internal`` (mm, N, N·mm, N/mm, N·mm/rad, MPa; kg, kg·m²) in this family's text unit."""
        if family == "length":
            return from_mm(internal, self.length)
        if family in ("mass", "inertia"):
            return internal * MASS_TEXT[self.length][family][1]
        if family == "torsional_stiffness":
            return internal / QUANTITY_SUFFIXES["torque"][self.torque]
        return internal / QUANTITY_SUFFIXES[family][getattr(self, family)]

    def text(self, family: str, internal: float | None, digits: int = 4) -> str:
        """``"13.56 in·lbf"``; ``"-"`` for None."""
        if internal is None:
            return "-"
        return f"{self.value(family, internal):.{digits}g} {self.unit(family)}"

    def small_length(self, internal_mm: float, digits: int = 4) -> str:
        """A deflection or misalignment: µm in a mm design, the length unit otherwise."""
        return small_length_text(internal_mm, self.length, digits)


def text_units(length_unit: str = "mm", keys=()) -> TextUnits:
    """The :class:`TextUnits` of a design of ``length_unit`` whose file wrote ``keys`` (every key of
    every section, in file order). A family takes the length unit's usual unit
    (:data:`DEFAULT_TEXT_SUFFIX`: SI for mm, inch-pound for in) unless the file wrote that family only
    in the other system: then that system's usual unit if the file wrote it, else the first unit it
    wrote (an inch design's ``max_output_torque_Nm`` reports torques in N·m, a mm design's
    ``preload_in_lbf`` in in·lbf). Torsional stiffnesses count as torques."""
    written: dict[str, list[str]] = {}
    for key in keys:
        found = quantity_suffix(key)
        if found is None:
            continue
        family, suffix = found
        if family == "torsional_stiffness":
            family = "torque"
        if family in TEXT_FAMILIES:
            written.setdefault(family, []).append(suffix)
    imperial_design = length_unit == "in"
    chosen = dict(DEFAULT_TEXT_SUFFIX[length_unit])
    other = DEFAULT_TEXT_SUFFIX["mm" if imperial_design else "in"]
    for family, suffixes in written.items():
        if all((s in IMPERIAL_SUFFIXES) != imperial_design for s in suffixes):
            shown = [_TEXT_SUFFIX.get(s, s) for s in suffixes]
            # the other system's usual unit when the file wrote it anywhere (N/mm beside a N/µm), else its first
            chosen[family] = other[family] if other[family] in shown else shown[0]
    return TextUnits(length=length_unit, **chosen)
