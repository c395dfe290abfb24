"""The ``[stages.NAME]`` tables: the gear stages between the motor and the anti-backlash loop.

A dual-pinion drive's loop (input, two clusters, output) is driven through any number of plain
stages. Each table names the stage's two gears (tables of ``[gears]``); the tables are read in
the order written, from the motor to the loop::

    [stages.motor]                    # on the motor shaft
    driver = "motor_pinion"
    driven = "idler_gear"
    circumferential_backlash_min_mm = 0.04
    circumferential_backlash_max_mm = 0.12

    [stages.idler]                    # its driven gear sits on the input gear's shaft
    driver = "idler_pinion"           # on one shaft with the previous stage's driven gear
    driven = "input_drive_gear"
    centre_distance_mm = 30.05        # default: the standard centre distance
    direction_deg = 0                 # where the driver's shaft lies, seen from the driven one

A table with ``kind = "planetary"`` is a planetary stage instead (sun, planets, fixed ring; its
keys and rules in :mod:`geargen.drives.planetary.keys`), the only stage: the carrier drives the
input gear's shaft.

Each stage's driven gear shares a shaft with the next stage's driver; the last driven gear
shares the input gear's shaft, the first driver is on the motor. Outside the preloaded loop a
stage keeps its backlash: its range is checked like any mesh, and its ratio and stiffness count
from the encoder (on the motor) to the output.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from geargen.design.schema import Field, check_name, read_table, shown
from geargen.drives.planetary.keys import read_planetary_stage, stage_gear
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES

STAGE_FIELDS = [
    Field("kind", "string", required=False, default="pair", choices=("pair", "planetary"),
          help="pair: a driver and a driven gear; planetary: sun, planets and a fixed ring "
               "(geargen.drives.planetary.keys, its own keys)"),
    Field("driver", "string", help="the gear table of the stage's driving gear (the first stage's: on the motor)"),
    Field("driven", "string", help="the gear table of the stage's driven gear (the last stage's: on the input "
                                   "gear's shaft)"),
    Field("centre_distance", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="operating centre distance of the pair (default: the standard one, (z1 + z2) m_t / 2)"),
    Field("direction", "angle", required=False, default=0.0, minimum=-2 * math.pi, maximum=2 * math.pi,
          help="direction of the driver's shaft from the driven gear's, from +x (away from the output) towards +y"),
    Field("circumferential_backlash_min", "length", minimum=0.0,
          help="smallest backlash of the pair (circumferential, at the reference circles)"),
    Field("circumferential_backlash_max", "length", minimum=0.0,
          help="largest backlash of the pair (circumferential, at the reference circles)"),
]


@dataclass(frozen=True)
class Stage:
    """One upstream stage (mm, rad): its gears by name, where it runs, its backlash range."""

    name: str
    driver: str
    driven: str
    centre_distance: float  # operating
    standard_centre_distance: float
    direction: float
    backlash_min: float
    backlash_max: float
    kind: str = "pair"

    def ratio(self, gears) -> Fraction:
        """Driver speed over driven speed (``gears``: the design's gears by table name)."""
        return Fraction(gears[self.driven].teeth, gears[self.driver].teeth)


def stages(design) -> tuple[Stage, ...]:
    """The design's upstream stages, from the motor to the loop (empty without ``[stages]``)."""
    table = design.section("stages")
    if not isinstance(table, dict):
        raise DesignError("stages", "expected tables [stages.NAME]")
    out = []
    used: dict[str, str] = {}
    for name, data in table.items():
        where = f"stages.{name}"
        check_name(where, name)  # it names the stage's parts and meshes (carrier_NAME, stage_NAME)
        if not isinstance(data, dict):
            raise DesignError(where, "expected a table")
        if data.get("kind") == "planetary":
            out.append(read_planetary_stage(design, name, data, used))
            continue
        planetary = [k for k in ("sun", "planet", "ring") if k in data]
        if planetary:  # a planetary stage's table whose kind went missing or wrong: say so, not "unknown key"
            kind = data.get("kind")
            raise DesignError(f"{where}.kind", "missing" if kind is None else f"{shown(kind)} is not 'planetary'",
                              f"'planetary': the table gives {', '.join(planetary)}, a planetary stage's keys")
        v = read_table(data, STAGE_FIELDS, where)
        gears = []
        for role in ("driver", "driven"):
            gears.append(stage_gear(design, where, role, v[role], used))
        a, b = gears
        if not (math.isclose(a.module, b.module, rel_tol=1e-9)
                and math.isclose(a.pressure_angle, b.pressure_angle, rel_tol=1e-9)
                and math.isclose(a.helix_angle, b.helix_angle, abs_tol=1e-12)):
            raise DesignError(f"{where}.driven", f"{v['driver']!r} and {v['driven']!r} cannot mesh: module, pressure "
                              "angle and helix angle must match", "a pair cut by one tool")
        if a.is_helical and a.hand == b.hand:
            raise DesignError(f"{where}.driven", f"{v['driver']!r} and {v['driven']!r} have the same hand", "opposite hands")
        standard = (a.teeth + b.teeth) * a.transverse_module / 2
        cd = v["centre_distance"] if v["centre_distance"] is not None else standard
        unit = design.length_unit
        k = LENGTH_SUFFIXES[unit]
        if not v["circumferential_backlash_min"] <= v["circumferential_backlash_max"]:
            raise DesignError(f"{where}.circumferential_backlash_min_{v['_units']['circumferential_backlash_min']}",
                              f"{v['circumferential_backlash_min'] / k:.6g} {unit} is above the maximum",
                              f"<= {v['circumferential_backlash_max'] / k:.6g} {unit}")
        if not abs(cd - standard) < 0.5 * a.module:
            raise DesignError(f"{where}.centre_distance_{v['_units'].get('centre_distance', unit)}",
                              f"{cd / k:.6g} {unit} is far from the standard {standard / k:.6g} {unit}",
                              f"within half a module of it ({(standard - 0.5 * a.module) / k:.6g} to "
                              f"{(standard + 0.5 * a.module) / k:.6g} {unit}; profile shifts are the gears' own)")
        out.append(Stage(name, v["driver"], v["driven"], cd, standard, v["direction"],
                         v["circumferential_backlash_min"], v["circumferential_backlash_max"]))
    if len(out) > 1 and any(st.kind == "planetary" for st in out):
        name = next(st.name for st in out if st.kind == "planetary")
        raise DesignError(f"stages.{name}.kind", "a planetary stage is placed as the only upstream stage (sun on the "
                          "motor, carrier on the input gear's shaft)", "one [stages.NAME] table, or 'pair' stages")
    if out and design.section("layout").get("upstream_stages"):
        raise DesignError("layout.upstream_stages", "the [stages] tables already give the stages before the input",
                          "one of them")
    return tuple(out)


def shaft_speeds(design, stage_list: tuple[Stage, ...], input_speed: float) -> dict[str, float]:
    """Each stage gear's speed (over the output's, given the input's ``input_speed``): the last
    stage's driven gear turns with the input, each driver with the next-higher driven gear."""
    speeds: dict[str, float] = {}
    speed = input_speed
    for s in reversed(stage_list):
        if s.driven is not None:  # a planetary stage's carrier is no gear
            speeds[s.driven] = speed
        speed *= float(s.ratio(design.gears))
        speeds[s.driver] = speed
    return speeds


def check_stages(design, takes_stages: bool) -> None:
    """Stages drive the input gear of a drive whose kind takes them (``TAKES_STAGES`` of its keys:
    the dual pinion's loop)."""
    if design.section("stages") and not takes_stages:
        raise DesignError("stages", "stages drive the input gear of a dual-pinion drive", "a [synthesis] drive")


__all__ = ["STAGE_FIELDS", "Stage", "stages", "shaft_speeds", "check_stages"]
