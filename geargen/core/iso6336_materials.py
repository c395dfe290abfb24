"""Materials for the load capacity rating: ISO 6336-5 allowable stress numbers and the life factors
of ISO 6336-2 and ISO 6336-3 (pure math, standard library only).

**Allowable stress numbers** (ISO 6336-5:2016, 5.5, Table 8). The standard's figures 1-17 are
straight lines in the surface hardness for each material, heat treatment and quality grade
(ML: modest demands, MQ: what an experienced maker meets at moderate cost, ME: the highest
quality); Table 8 gives each line as ``sigma = A x + B`` with ``x`` the hardness (HV here) and
the hardness range the line is valid in. Those coefficients are encoded in :data:`MATERIALS`;
outside a line's hardness range the standard has no value and a :class:`~geargen.errors.DesignError`
names the range. ``sigma_FE = Y_ST sigma_Flim`` with the stress correction factor of the
reference test gear ``Y_ST = 2`` (ISO 6336-3).

The materials are the four heat treatments the issue names (through hardened wrought steel,
alloyed or plain carbon; case carburised; induction hardened; nitrided nitriding steel). Case
carburised bending numbers are those for a core hardness of at least 30 HRC (the standard gives
lower lines, 425/461 N/mm^2 for MQ, for 25-30 HRC cores); the cast irons, cast steels, normalised
low-carbon steels and nitrocarburised steels of the table are not offered.

**Life factors** Z_NT (ISO 6336-2:2019, Table 2) and Y_NT (ISO 6336-3:2019, Table 3) are
piecewise straight in log-log between the standard's points: static (short life) value up to a
cycle number, 1.0 at the reference (endurance) cycle number, and 0.85 at 1e10 cycles ("normal"
lubrication, material, manufacture and experience; the standard allows up to 1.0 at 1e10 for
optimum conditions, which is not assumed here). ISO/TR 6336-30:2017 example 1 uses the same
0.85 point (its Z_NT 0.91 and 0.962 at 1.08e9 and 1.783e8 cycles).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from geargen.errors import DesignError

QUALITY_GRADES = ("ML", "MQ", "ME")
#: stress correction factor of the standard reference test gear, sigma_FE = Y_ST sigma_Flim
REFERENCE_STRESS_CORRECTION = 2.0
#: the life factor at 1e10 cycles for normal (not optimum) conditions, ISO 6336-2/-3
LONG_LIFE_FACTOR = 0.85
LONG_LIFE_CYCLES = 1e10


@dataclass(frozen=True)
class AllowableLine:
    """One line of ISO 6336-5 Table 8: ``sigma = A x + B`` (N/mm^2) for hardness ``x`` in
    [``hardness_low``, ``hardness_high``] HV."""

    A: float
    B: float
    hardness_low: float
    hardness_high: float

    def value(self, hardness: float) -> float:
        return self.A * hardness + self.B


@dataclass(frozen=True)
class LifeCurve:
    """A life factor curve: ``points`` (cycles, factor) in increasing cycles; constant below the
    first; straight in log-log between points; the last segment's slope continues beyond the last
    point (ISO 6336-6's damage sum needs the curve past 1e10; a continued slope is the conservative
    reading)."""

    name: str
    points: tuple[tuple[float, float], ...]

    @property
    def reference_cycles(self) -> float:
        """The cycle number where the factor reaches 1.0 (the endurance reference)."""
        return next(n for n, f in self.points if f == 1.0)

    def factor(self, cycles: float) -> float:
        if not (math.isfinite(cycles) and cycles > 0):
            raise DesignError("cycles", f"{cycles!r} is out of range", "> 0")
        pts = self.points
        if cycles <= pts[0][0]:
            return pts[0][1]
        for (n0, f0), (n1, f1) in zip(pts, pts[1:]):
            if cycles <= n1:
                return f0 * (f1 / f0) ** (math.log(cycles / n0) / math.log(n1 / n0))
        (n0, f0), (n1, f1) = pts[-2], pts[-1]
        return f1 * (f1 / f0) ** (math.log(cycles / n1) / math.log(n1 / n0))

    def cycles_at(self, factor: float) -> float:
        """The cycle number at which the curve falls to ``factor`` (inf where it never rises that
        high: the static plateau; the continued last slope reaches every factor below it)."""
        pts = self.points
        if factor >= pts[0][1]:
            return 0.0 if factor > pts[0][1] else pts[0][0]
        for (n0, f0), (n1, f1) in zip(pts, pts[1:]):
            if factor >= f1:
                return n0 * (n1 / n0) ** (math.log(factor / f0) / math.log(f1 / f0))
        (n0, f0), (n1, f1) = pts[-2], pts[-1]
        return n1 * (n1 / n0) ** (math.log(factor / f1) / math.log(f1 / f0))


# ISO 6336-2:2019 Table 2 (Z_NT) and ISO 6336-3:2019 Table 3 (Y_NT)
Z_NT_NO_PITTING = LifeCurve("St, V, GGG, GTS, Eh, IF (no pitting permitted)",
                            ((1e5, 1.6), (5e7, 1.0), (LONG_LIFE_CYCLES, LONG_LIFE_FACTOR)))
Z_NT_NITRIDED = LifeCurve("GG, GGG (ferr.), NT (nitr.), NV (nitr.)",
                          ((1e5, 1.3), (2e6, 1.0), (LONG_LIFE_CYCLES, LONG_LIFE_FACTOR)))
Y_NT_THROUGH_HARDENED = LifeCurve("V, GGG (perl., bai.), GTS (perl.)",
                                  ((1e4, 2.5), (3e6, 1.0), (LONG_LIFE_CYCLES, LONG_LIFE_FACTOR)))
Y_NT_SURFACE_HARDENED = LifeCurve("Eh, IF (root)", ((1e3, 2.5), (3e6, 1.0), (LONG_LIFE_CYCLES, LONG_LIFE_FACTOR)))
Y_NT_NITRIDED = LifeCurve("St, NT (nitr.), NV (nitr.), GG, GGG (ferr.)",
                          ((1e3, 1.6), (3e6, 1.0), (LONG_LIFE_CYCLES, LONG_LIFE_FACTOR)))


@dataclass(frozen=True)
class MaterialClass:
    """A material and heat treatment of ISO 6336-5 with what the rating needs of it.

    ``contact``/``bending``: the Table 8 line per quality grade (sigma_Hlim, sigma_Flim).
    ``group``: the material group the factor tables of ISO 6336-2/-3 are keyed by (``V``
    through hardened, ``Eh`` case hardened, ``IF`` induction hardened, ``NT`` nitrided).
    ``slip_layer``: rho' of the relative notch sensitivity factor (ISO 6336-3 method B, mm).
    """

    name: str
    description: str
    group: str
    surface_hardened: bool
    contact: dict
    bending: dict
    z_nt: LifeCurve
    y_nt: LifeCurve
    slip_layer: float
    slip_layer_source: str
    figure: str


def _lines(**rows):
    return {grade: AllowableLine(*row) for grade, row in rows.items()}


#: ISO 6336-5:2016 Table 8 (A, B, hardness range in HV) for the materials offered. Case
#: carburised and nitrided numbers are constant (A = 0) over the surface hardness range.
MATERIALS: dict[str, MaterialClass] = {
    "through_hardened": MaterialClass(
        "through_hardened", "through hardened wrought alloy steel (quenched and tempered)", "V", False,
        contact=_lines(ML=(1.313, 188, 200, 360), MQ=(1.313, 373, 200, 360), ME=(2.213, 260, 200, 390)),
        bending=_lines(ML=(0.423, 104, 200, 360), MQ=(0.425, 187, 200, 360), ME=(0.358, 231, 200, 390)),
        z_nt=Z_NT_NO_PITTING, y_nt=Y_NT_THROUGH_HARDENED, slip_layer=0.0064,
        slip_layer_source="rho' = 0.0064 mm: ISO 6336-3's value for through hardened steel of 0.2 % proof "
                          "stress 800 N/mm^2, typical of quenched and tempered alloy gear steel",
        figure="ISO 6336-5 Figures 5 and 6 (alloy steels)"),
    "through_hardened_carbon": MaterialClass(
        "through_hardened_carbon", "through hardened wrought plain carbon steel", "V", False,
        contact=_lines(ML=(0.963, 283, 135, 210), MQ=(0.925, 360, 135, 210), ME=(0.838, 432, 135, 210)),
        bending=_lines(ML=(0.250, 108, 115, 215), MQ=(0.240, 163, 115, 215), ME=(0.283, 202, 115, 215)),
        z_nt=Z_NT_NO_PITTING, y_nt=Y_NT_THROUGH_HARDENED, slip_layer=0.0281,
        slip_layer_source="rho' = 0.0281 mm: ISO 6336-3's value for through hardened steel of 0.2 % proof "
                          "stress 500 N/mm^2, typical of plain carbon steel",
        figure="ISO 6336-5 Figures 5 and 6 (carbon steels)"),
    "case_carburised": MaterialClass(
        "case_carburised", "case carburised and hardened wrought steel (core hardness >= 30 HRC)", "Eh", True,
        contact=_lines(ML=(0.0, 1300, 600, 800), MQ=(0.0, 1500, 660, 800), ME=(0.0, 1650, 660, 800)),
        bending=_lines(ML=(0.0, 312, 600, 800), MQ=(0.0, 500, 660, 800), ME=(0.0, 525, 660, 800)),
        z_nt=Z_NT_NO_PITTING, y_nt=Y_NT_SURFACE_HARDENED, slip_layer=0.0030,
        slip_layer_source="rho' = 0.0030 mm: ISO 6336-3's value for case hardened steel",
        figure="ISO 6336-5 Figures 9 and 10"),
    "induction_hardened": MaterialClass(
        "induction_hardened", "induction (or flame) hardened wrought steel, root hardened", "IF", True,
        contact=_lines(ML=(0.740, 602, 485, 615), MQ=(0.541, 882, 500, 615), ME=(0.505, 1013, 500, 615)),
        bending=_lines(ML=(0.305, 76, 485, 615), MQ=(0.138, 290, 500, 570), ME=(0.271, 237, 500, 570)),
        z_nt=Z_NT_NO_PITTING, y_nt=Y_NT_SURFACE_HARDENED, slip_layer=0.0030,
        slip_layer_source="rho' = 0.0030 mm: ISO 6336-3's value for induction hardened steel (root hardened)",
        figure="ISO 6336-5 Figures 11 and 12"),
    "nitrided": MaterialClass(
        "nitrided", "gas nitrided nitriding steel", "NT", True,
        contact=_lines(ML=(0.0, 1125, 650, 900), MQ=(0.0, 1125, 650, 900), ME=(0.0, 1450, 650, 900)),
        bending=_lines(ML=(0.0, 270, 650, 900), MQ=(0.0, 420, 650, 900), ME=(0.0, 468, 650, 900)),
        z_nt=Z_NT_NITRIDED, y_nt=Y_NT_NITRIDED, slip_layer=0.1005,
        slip_layer_source="rho' = 0.1005 mm: ISO 6336-3's value for nitrided steel",
        figure="ISO 6336-5 Figures 13 and 14"),
}


@dataclass(frozen=True)
class Material:
    """The material of one gear as the rating takes it: an ISO 6336-5 ``name`` (a key of
    :data:`MATERIALS`), ``quality`` ML/MQ/ME, surface ``hardness`` in HV (None where the line is
    flat and no hardness is stated; the hardening is then assumed to reach the line's range), and
    its elastic constants and density (steel by default, as the standard's tables assume)."""

    name: str
    quality: str = "MQ"
    hardness: float | None = None
    elastic_modulus: float = 206000.0  # N/mm^2
    poisson_ratio: float = 0.3
    density: float = 7.83e-6  # kg/mm^3

    def __post_init__(self):
        if self.name not in MATERIALS:
            raise DesignError("material", f"{self.name!r} is not an ISO 6336-5 material geargen rates",
                              ", ".join(MATERIALS))
        if self.quality not in QUALITY_GRADES:
            raise DesignError("quality", f"{self.quality!r} is not an ISO 6336-5 quality grade", "ML, MQ, ME")
        if self.hardness is not None and not (math.isfinite(self.hardness) and self.hardness > 0):
            raise DesignError("hardness", f"{self.hardness!r} HV is out of range", "> 0 HV")

    @property
    def material_class(self) -> MaterialClass:
        return MATERIALS[self.name]


@dataclass(frozen=True)
class AllowableStress:
    """sigma_Hlim, sigma_Flim and sigma_FE of one gear (N/mm^2), with the Table 8 lines used."""

    sigma_Hlim: float
    sigma_Flim: float
    sigma_FE: float
    contact_line: AllowableLine
    bending_line: AllowableLine
    hardness: float | None
    note: str


def allowable_stress(material: Material, gear: str = "gear") -> AllowableStress:
    """The ISO 6336-5 allowable stress numbers of ``material`` (``gear`` names it in errors)."""
    cls = material.material_class
    contact, bending = cls.contact[material.quality], cls.bending[material.quality]
    x = material.hardness
    note = f"ISO 6336-5:2016 Table 8, {cls.figure}, quality {material.quality}"
    if x is None:
        if contact.A != 0 or bending.A != 0:
            raise DesignError("hardness", f"{gear}: {cls.name} needs its surface hardness (the allowable stress "
                              "numbers are lines in it)",
                              f"{contact.hardness_low:g}..{contact.hardness_high:g} HV for quality {material.quality}")
        note += f"; hardness not stated, taken within {contact.hardness_low:g}..{contact.hardness_high:g} HV"
    else:
        for what, line in (("contact", contact), ("bending", bending)):
            if not line.hardness_low <= x <= line.hardness_high:
                raise DesignError("hardness", f"{gear}: {x:g} HV is outside the range of ISO 6336-5's {what} line "
                                  f"for {cls.name} {material.quality} (the standard gives no value there)",
                                  f"{line.hardness_low:g}..{line.hardness_high:g} HV")
    h = 0.0 if x is None else x
    flim = bending.value(h)
    return AllowableStress(sigma_Hlim=contact.value(h), sigma_Flim=flim, sigma_FE=REFERENCE_STRESS_CORRECTION * flim,
                           contact_line=contact, bending_line=bending, hardness=x, note=note)


__all__ = ["QUALITY_GRADES", "REFERENCE_STRESS_CORRECTION", "AllowableLine", "LifeCurve", "MaterialClass",
           "MATERIALS", "Material", "AllowableStress", "allowable_stress", "Z_NT_NO_PITTING", "Z_NT_NITRIDED",
           "Y_NT_THROUGH_HARDENED", "Y_NT_SURFACE_HARDENED", "Y_NT_NITRIDED"]
