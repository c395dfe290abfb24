"""A planetary (2K-H) stage: sun, N planets, fixed ring; its ratio and the conditions its tooth
numbers and profile shifts must meet (mm, rad; normal system like :class:`GearSpec`).

- ratio, ring fixed, sun in, carrier out: 1 + z_r / z_s (sun fixed, ring in: 1 + z_s / z_r;
  carrier fixed: -z_r / z_s);
- coaxiality: the sun-planet (external) and planet-ring (internal) working centre distances are
  equal. External pair: inv(alpha_w) = inv(alpha_t) + 2 tan(alpha_n) (x_s + x_p) / (z_s + z_p);
  internal pair: inv(alpha_w) = inv(alpha_t) + 2 tan(alpha_n) (x_r - x_p) / (z_r - z_p); each
  a_w = m_t (z_sum or z_diff) / 2 cos(alpha_t) / cos(alpha_w) (zero-backlash meshes);
- assembly: a planet can be put in at carrier angle phi when (z_s + z_r) phi / (2 pi) is whole, so N
  equally spaced planets need (z_s + z_r) / N whole; otherwise the planets go at the nearest
  allowed angles 2 pi k_i / (z_s + z_r), k_i = round(i (z_s + z_r) / N);
- neighbours: the tip circles of neighbouring planets, 2 a_w sin(delta / 2) apart (delta the angle
  between them), must clear: 2 a_w sin(delta / 2) > d_a,planet + clearance.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from geargen.core.involute import involute, inverse_involute, working_pressure_angle_at
from geargen.design.gear import HelicalTeeth
from geargen.errors import DesignError


@dataclass(frozen=True)
class PlanetaryStage(HelicalTeeth):
    """Tooth numbers, the number of planets, the normal module and pressure angle, the helix angle
    (0: spur), the normal profile shifts (the ring's x_r widens its tooth spaces, 2 x_r tan(alpha_n)
    m_n at the reference circle, and so increases the planet-ring working centre distance), the
    planets' tip diameter (None:
    m_t z_p + 2 m_n (1 + x_p)), the neighbour clearance between planet tips (mm) and the largest
    difference of the two working centre distances taken as coaxial (mm)."""

    sun_teeth: int
    planet_teeth: int
    ring_teeth: int
    planets: int
    module: float
    pressure_angle: float
    helix_angle: float = 0.0
    sun_profile_shift: float = 0.0
    planet_profile_shift: float = 0.0
    ring_profile_shift: float = 0.0
    planet_tip_diameter: float | None = None
    neighbour_clearance: float = 0.0
    coaxiality_tolerance: float = 1e-3

    def __post_init__(self):
        for name, lo in (("sun_teeth", 4), ("planet_teeth", 4), ("ring_teeth", 8), ("planets", 1)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < lo:
                raise DesignError(name, f"{v!r} is out of range", f"a whole number >= {lo}")
        if self.ring_teeth <= self.planet_teeth:
            raise DesignError("ring_teeth", f"{self.ring_teeth} is not more than the planet's {self.planet_teeth}",
                              f"> {self.planet_teeth}")
        for name in ("module", "neighbour_clearance", "coaxiality_tolerance"):
            v = getattr(self, name)
            if not (math.isfinite(v) and (v > 0 if name == "module" else v >= 0)):
                raise DesignError(name, f"{v!r} is out of range", "> 0 mm" if name == "module" else ">= 0 mm")
        if not 10 * math.pi / 180 <= self.pressure_angle <= 35 * math.pi / 180:
            raise DesignError("pressure_angle", f"{self.pressure_angle!r} rad is out of range", "[10, 35] deg")
        if not 0 <= self.helix_angle <= math.pi / 4:
            raise DesignError("helix_angle", f"{self.helix_angle!r} rad is out of range", "[0, 45] deg")

    @property
    def planet_tip_diameter_resolved(self) -> float:
        if self.planet_tip_diameter is not None:
            return self.planet_tip_diameter
        return self.transverse_module * self.planet_teeth + 2 * self.module * (1 + self.planet_profile_shift)


def ratios(stage: PlanetaryStage) -> dict[str, float]:
    """Input over output speed of the three ways to hold one member."""
    zs, zr = stage.sun_teeth, stage.ring_teeth
    return {"ring_fixed": 1 + zr / zs, "sun_fixed": 1 + zs / zr, "carrier_fixed": -zr / zs}


def _working(stage: PlanetaryStage, teeth: int, shift: float, field: str) -> tuple[float, float]:
    """(working transverse pressure angle, working centre distance) of a zero-backlash pair whose
    tooth sum (external) or difference (internal) is ``teeth`` and shift sum or difference ``shift``."""
    alpha_t = stage.transverse_pressure_angle
    inv_w = involute(alpha_t) + 2 * math.tan(stage.pressure_angle) * shift / teeth
    if inv_w <= 0:
        raise DesignError(field, f"the profile shifts leave no working pressure angle (inv = {inv_w:.3g})",
                          "a larger shift sum (external) or ring-minus-planet shift (internal)")
    alpha_w = inverse_involute(inv_w)
    return alpha_w, stage.transverse_module * teeth / 2 * math.cos(alpha_t) / math.cos(alpha_w)


def sun_planet_working(stage: PlanetaryStage) -> tuple[float, float]:
    """Working pressure angle (rad) and centre distance (mm) of the sun-planet (external) pair."""
    return _working(stage, stage.sun_teeth + stage.planet_teeth,
                    stage.sun_profile_shift + stage.planet_profile_shift, "planet_profile_shift")


def planet_ring_working(stage: PlanetaryStage) -> tuple[float, float]:
    """Working pressure angle (rad) and centre distance (mm) of the planet-ring (internal) pair."""
    return _working(stage, stage.ring_teeth - stage.planet_teeth,
                    stage.ring_profile_shift - stage.planet_profile_shift, "ring_profile_shift")


def coaxial_ring_shift(stage: PlanetaryStage) -> float:
    """The ring's profile shift that makes the planet-ring working centre distance equal the
    sun-planet one (the sun and planet shifts as given)."""
    a_w = sun_planet_working(stage)[1]
    diff = stage.ring_teeth - stage.planet_teeth
    alpha_t = stage.transverse_pressure_angle
    alpha_w = working_pressure_angle_at(float(stage.transverse_module * diff / 2 * math.cos(alpha_t)), float(a_w))
    if not 0 < alpha_w < math.pi / 2:  # NaN: a_w inside the base circles
        raise DesignError("ring_teeth", f"no internal working pressure angle reaches a_w = {a_w:.6g} mm",
                          "tooth numbers with z_r - z_p close to z_s + z_p")
    inv_w = involute(alpha_w)
    return stage.planet_profile_shift + (inv_w - involute(alpha_t)) * diff / (2 * math.tan(stage.pressure_angle))


def assembly_angles(stage: PlanetaryStage, equal_spacing: bool = True) -> list[float]:
    """Carrier angles (rad) of the planets, planet 0 at 0. Equally spaced: needs (z_s + z_r) / N whole
    (DesignError naming ``planets`` otherwise); unequal: the allowed angles 2 pi k / (z_s + z_r)
    nearest to equal spacing."""
    total, n = stage.sun_teeth + stage.ring_teeth, stage.planets
    if total % n == 0:
        return [2 * math.pi * i / n for i in range(n)]
    if equal_spacing:
        raise DesignError("planets", f"{n} planets cannot be equally spaced: (z_s + z_r) / N = {total}/{n} is not "
                          "whole", "N dividing z_s + z_r = " + str(total) + ", or unequal spacing")
    steps = [round(i * total / n) for i in range(n)]
    if len(set(steps)) < n:
        raise DesignError("planets", f"{n} planets do not fit {total} assembly positions", f"<= {total}")
    return [2 * math.pi * k / total for k in steps]


def planet_phases(sun_teeth: int, planet_teeth: int, ring_teeth: int, sun_rotation: float,
                  angles) -> tuple[list[float], float]:
    """Rotations (rad, tooth 0 centreline; the ring's: its tooth space 0) of planets at carrier
    angles ``angles`` and of the ring, so that every planet sits in the middle of its play with
    the sun (rotation ``sun_rotation``) and with the ring (both meshes symmetric about the line of
    centres: a tooth centred in the mate's space there).

    Sun-planet (external): a sun tooth ``d = sun_rotation - phi`` off the line of centres puts a
    planet space ``- d z_s / z_p`` off it on the far side: ``rho = phi + pi + pi / z_p - (sun_rotation
    - phi) z_s / z_p``. Planet-ring (internal, both turn the same way): the planet's tooth ``rho -
    phi`` off the outward line puts the ring's space ``(rho - phi) z_p / z_r`` off it:
    ``ring = phi + (rho - phi) z_p / z_r (mod 2 pi / z_r)``. Planet 0 fixes the ring; planet i
    needs ``phi_i (z_s + z_r) / (2 pi)`` whole: the assembly condition (mismatches stay in the
    returned rotations; :func:`ring_phase_error` measures them)."""
    zs, zp, zr = sun_teeth, planet_teeth, ring_teeth
    rho = [phi + math.pi + math.pi / zp - (sun_rotation - phi) * zs / zp for phi in angles]
    ring = angles[0] + (rho[0] - angles[0]) * zp / zr
    return rho, ring % (2 * math.pi / zr)


def ring_phase_error(sun_teeth: int, ring_teeth: int, angles) -> list[float]:
    """Per planet, how far (rad of the ring, in (-pi / z_r, pi / z_r]) the ring's space it needs
    lies from the ring placed for planet 0: ``phi_i (z_s + z_r) / z_r`` reduced by the ring's pitch
    (zero for every planet exactly when the assembly condition holds)."""
    pitch = 2 * math.pi / ring_teeth
    out = []
    for phi in angles:
        d = (phi - angles[0]) * (sun_teeth + ring_teeth) / ring_teeth
        out.append(d - pitch * math.floor(d / pitch + 0.5))
    return out


@dataclass(frozen=True)
class PlanetaryCheck:
    """The stage's numbers once all conditions hold (mm, rad)."""

    ratio_ring_fixed: float
    centre_distance: float  # sun-planet working centre distance (the carrier's planet radius)
    sun_planet_pressure_angle: float
    planet_ring_pressure_angle: float
    coaxiality_error: float  # planet-ring minus sun-planet working centre distance
    planet_angles: tuple[float, ...]
    neighbour_gap: float  # closest planets' centre distance minus tip diameter (before the clearance)


def check_stage(stage: PlanetaryStage, equal_spacing: bool = True) -> PlanetaryCheck:
    """All conditions of the module docstring; a DesignError names the field of the first that fails."""
    alpha_sp, a_sp = sun_planet_working(stage)
    alpha_pr, a_pr = planet_ring_working(stage)
    if abs(a_pr - a_sp) > stage.coaxiality_tolerance:
        raise DesignError("ring_profile_shift", f"planet-ring centre distance {a_pr:.6f} mm is not the sun-planet "
                          f"{a_sp:.6f} mm (within {stage.coaxiality_tolerance:g} mm)",
                          f"x_r = {coaxial_ring_shift(stage):.6f} for these sun and planet shifts")
    angles = assembly_angles(stage, equal_spacing)
    spacing = min((b - a) % (2 * math.pi) for a, b in zip(angles, angles[1:] + angles[:1])) if len(angles) > 1 else 2 * math.pi
    gap = 2 * a_sp * math.sin(spacing / 2) - stage.planet_tip_diameter_resolved if len(angles) > 1 else math.inf
    if gap <= stage.neighbour_clearance:
        raise DesignError("planets", f"neighbouring planets' tips are {gap:.4g} mm apart (clearance "
                          f"{stage.neighbour_clearance:g} mm wanted)",
                          "fewer planets, or a larger sun (2 a_w sin(pi / N) > d_a,planet + clearance)")
    return PlanetaryCheck(ratios(stage)["ring_fixed"], a_sp, alpha_sp, alpha_pr, a_pr - a_sp, tuple(angles), gap)


__all__ = ["PlanetaryStage", "PlanetaryCheck", "ratios", "sun_planet_working", "planet_ring_working",
           "coaxial_ring_shift", "assembly_angles", "check_stage", "planet_phases", "ring_phase_error"]
