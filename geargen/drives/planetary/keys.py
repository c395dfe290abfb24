"""A ``[stages.NAME]`` table with ``kind = "planetary"``: a 2K-H planetary stage (sun, N planets,
fixed ring) between the motor and a dual-pinion loop::

    [stages.planetary]
    kind = "planetary"
    sun = "sun"                        # on the motor shaft
    planet = "planet"                  # one gear table for every planet, each on a carrier pin
    ring = "ring"                      # kind = "internal", fixed to the carriage
    planets = 3
    circumferential_backlash_min_mm = 0.04   # of each sun-planet and planet-ring mesh
    circumferential_backlash_max_mm = 0.12
    carrier_radius_mm = 24.0           # default: the sun-planet zero-backlash working centre distance

The carrier drives the input gear's shaft: sun, carrier and ring stand coaxial with it. Ratio
(ring fixed, sun in, carrier out) ``1 + z_r / z_s``. The conditions (:mod:`geargen.core.planetary`):
the assembly condition is checked here, on reading (a stage that cannot be assembled has no
placement to check); coaxiality and the planets' neighbour clearance are reported and checked by
``geargen check`` (:mod:`geargen.drives.planetary.verdict`).

Planet spacing: ``"equal"`` (default) needs ``(z_s + z_r) / N`` whole. ``"nearest_allowed"``
accepts the assembly angles ``2 pi k / (z_s + z_r)`` nearest to equal spacing: they assemble, but
the sun's radial mesh forces no longer cancel and the planets share the load unequally, so it is
only taken when the design asks for it (the paper is silent on planetary stages).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from geargen.design.schema import Field, read_table
from geargen.errors import DesignError

PLANET_SPACINGS = ("equal", "nearest_allowed")

PLANETARY_STAGE_FIELDS = [
    Field("kind", "string", choices=("planetary",), help="planetary: sun, planets and a fixed ring"),
    Field("sun", "string", help="the gear table of the sun (on the motor shaft, or the previous stage's)"),
    Field("planet", "string", help="the gear table of the planets (all alike, each on a carrier pin: its bore)"),
    Field("ring", "string", help="the gear table of the ring (kind internal, fixed to the carriage)"),
    Field("planets", "integer", minimum=1, maximum=32, help="number of planets N"),
    Field("planet_spacing", "string", required=False, default="equal", choices=PLANET_SPACINGS,
          help="equal: N equally spaced planets ((z_s + z_r) / N whole); nearest_allowed: the assembly angles "
               "2 pi k / (z_s + z_r) nearest to equal spacing"),
    Field("carrier_radius", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="planet axes' radius on the carrier: the centre distance of both meshes (default: the sun-planet "
               "zero-backlash working centre distance)"),
    Field("circumferential_backlash_min", "length", minimum=0.0,
          help="smallest backlash of each sun-planet and planet-ring mesh (circumferential, at the reference circle "
               "of the sun, resp. the planet)"),
    Field("circumferential_backlash_max", "length", minimum=0.0,
          help="largest backlash of each sun-planet and planet-ring mesh"),
    Field("planet_tip_clearance", "length", required=False, default=0.0, minimum=0.0,
          help="least gap between neighbouring planets' tip circles (they must not touch in any case)"),
    Field("coaxiality_tolerance", "length", required=False, default=0.001, minimum=0.0,
          help="largest difference of the planet-ring and sun-planet zero-backlash working centre distances"),
]


@dataclass(frozen=True)
class PlanetaryStageSpec:
    """One planetary upstream stage as the design gives it (mm, rad). ``driver`` is the sun (what
    the motor turns); the carrier, on the input gear's shaft, is the driven member (no gear:
    ``driven`` is None)."""

    name: str
    sun: str
    planet: str
    ring: str
    planets: int
    planet_spacing: str
    carrier_radius: float | None
    backlash_min: float
    backlash_max: float
    planet_tip_clearance: float
    coaxiality_tolerance: float
    kind: str = "planetary"

    @property
    def driver(self) -> str:
        return self.sun

    @property
    def driven(self) -> None:
        return None

    def ratio(self, gears) -> Fraction:
        """Sun speed over carrier speed, ring fixed: 1 + z_r / z_s (``gears``: the design's gears by table name)."""
        return 1 + Fraction(gears[self.ring].teeth, gears[self.sun].teeth)



def stage_gear(design, where: str, role: str, gear: str, used: dict[str, str]):
    """The gear table ``gear`` a stage names as its ``role``: in the design, not a gear of the
    loop, in no other stage (``used`` records each gear's role)."""
    if gear not in design.gears:
        raise DesignError(f"{where}.{role}", f"no gear named {gear!r} in the design", ", ".join(design.gears))
    if gear in ("input", "cluster_large", "cluster_small", "output"):
        raise DesignError(f"{where}.{role}", f"{gear!r} is a gear of the anti-backlash loop",
                          "a gear table of its own for each stage gear")
    if gear in used:
        raise DesignError(f"{where}.{role}", f"{gear!r} is already the {used[gear]}", "a gear in one stage only")
    used[gear] = f"{role} of {where}"
    return design.gears[gear]


def read_planetary_stage(design, name: str, data, used: dict[str, str]) -> PlanetaryStageSpec:
    """The table ``[stages.NAME]`` of a planetary stage, validated (errors name ``stages.NAME.<key>``)."""
    where = f"stages.{name}"
    v = read_table(data, PLANETARY_STAGE_FIELDS, where)
    gears = {}
    for role in ("sun", "planet", "ring"):
        gears[role] = stage_gear(design, where, role, v[role], used)
    sun, planet, ring = gears["sun"], gears["planet"], gears["ring"]
    for role, g, kind in (("sun", sun, "external"), ("planet", planet, "external"), ("ring", ring, "internal")):
        if g.kind != kind:
            raise DesignError(f"{where}.{role}", f"{g.name!r} is a {g.kind} gear", f"a gear of kind {kind!r}")
    for g in (planet, ring):
        if not (math.isclose(g.module, sun.module, rel_tol=1e-9)
                and math.isclose(g.pressure_angle, sun.pressure_angle, rel_tol=1e-9)
                and math.isclose(g.helix_angle, sun.helix_angle, abs_tol=1e-12)):
            raise DesignError(f"{where}.{'planet' if g is planet else 'ring'}",
                              f"{g.name!r} cannot mesh with the sun {sun.name!r}: module, pressure angle and helix "
                              "angle must match", "gears cut by one tool")
    if sun.is_helical and (sun.hand == planet.hand or planet.hand != ring.hand):
        raise DesignError(f"{where}.planet", "a helical planet has the sun's opposite hand and the ring's hand",
                          "opposite hands of sun and planet, ring like the planet")
    if not v["circumferential_backlash_min"] <= v["circumferential_backlash_max"]:
        raise DesignError(f"{where}.circumferential_backlash_min_{v['_units']['circumferential_backlash_min']}",
                          "is above the maximum", "<= circumferential_backlash_max")
    spec = PlanetaryStageSpec(name, v["sun"], v["planet"], v["ring"], v["planets"], v["planet_spacing"],
                              v["carrier_radius"], v["circumferential_backlash_min"], v["circumferential_backlash_max"],
                              v["planet_tip_clearance"], v["coaxiality_tolerance"])
    # the assembly condition (geargen.core.planetary.assembly_angles: the design layer reads below
    # core, so the whole-number test is here; the placement asks core again)
    total = sun.teeth + ring.teeth
    if v["planet_spacing"] == "equal" and total % spec.planets:
        allowed = [n for n in range(1, 33) if total % n == 0]
        raise DesignError(f"{where}.planets", f"(z_s + z_r) / N = {total}/{spec.planets} = {total / spec.planets:.4g} "
                          f"is not whole: {spec.planets} equally spaced planets cannot be assembled",
                          f"N dividing z_s + z_r = {total}: {', '.join(map(str, allowed))}; or planet_spacing = "
                          "'nearest_allowed'")
    if spec.planets > total:
        raise DesignError(f"{where}.planets", f"{spec.planets} planets do not fit {total} assembly positions",
                          f"<= {total}")
    return spec


__all__ = ["PLANET_SPACINGS", "PLANETARY_STAGE_FIELDS", "PlanetaryStageSpec", "read_planetary_stage"]
