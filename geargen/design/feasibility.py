"""Can the gear a design table describes be cut? Closed forms checked when a design is loaded.

The design layer imports nothing above it (tests/test_layering.py: design is the bottom layer),
so the few closed forms a load needs live here, on the spec; the full models stay where they
are: the exact outline in :mod:`geargen.profile.tooth`, the involute geometry in
:mod:`geargen.core.involute`. ``tests/design/test_feasibility.py`` checks these formulas against
both: every tooth refused here is refused by the outline, and every one accepted here has a
tip land and a root there.

A tooth is makeable when (transverse section, mm):

* its root circle lies outside the axis: ``r_f = r - m_n (h_f* - x) > 0``;
* the generating rack's tooth, which cuts the dedendum, does not come to a point above its tip
  line (normal section, rack tip radius ``rho``):
  ``h_f* tan(alpha_n) + rho* (1 - sin(alpha_n)) / cos(alpha_n) - j_n / (2 m_n) <= pi / 4``
  (``j_n`` the normal tooth thinning, which widens the rack tooth);
* its tip circle lies outside the base circle (else there is no involute): ``r_a > r_b``;
* its flanks do not meet below the tip circle: the tip land
  ``s_a = 2 r_a (s_t / (2 r) + inv(alpha_t) - inv(alpha_a))`` is at least
  :data:`MIN_TIP_LAND_MODULES` normal modules (``alpha_a = acos(r_b / r_a)``);
* when the rack does not undercut the gear, the involute starts (where the rack's straight
  flank ends, roll ``t_j = (r sin(alpha_t) + v_f / sin(alpha_t)) / r_b``, ``v_f`` the height of
  that point above the rolling line) below the tip circle: ``r_b sqrt(1 + t_j^2) < r_a``.

Where the rack undercuts the gear (``t_j < 0``: few teeth, strongly negative shift), how far the
undercut climbs, and whether it severs the tooth, is found only by the outline itself: such a
gear passes here and is refused at check or build time (a ``GeometryError`` naming the gear).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from typing import Mapping

from geargen.design.schema import bound_text
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES

#: the thinnest tip land the outline accepts, in normal modules (geargen.profile.tooth's limit)
MIN_TIP_LAND_MODULES = 1e-3

#: the design-file range of each gear parameter the checks may move to find the allowed value
_RANGES = {"profile_shift": (-1.5, 1.5), "addendum_coefficient": (0.3, 1.5),
           "dedendum_coefficient": (0.5, 2.0), "teeth": (4, 2000)}


def _involute(angle: float) -> float:
    return math.tan(angle) - angle


def reference_tooth_thickness(spec) -> float:
    """Transverse arc tooth thickness at the reference circle after shift and thinning, mm."""
    return (math.pi * spec.transverse_module / 2
            + 2 * spec.profile_shift * spec.module * math.tan(spec.transverse_pressure_angle) - spec.thinning)


def tip_land(spec) -> float:
    """Transverse arc thickness at the tip circle, mm; <= 0 where the flanks meet below it.

    Needs the tip circle outside the base circle (``spec.tip_radius > spec.base_radius``).
    """
    r, r_a, r_b = spec.reference_radius, spec.tip_radius, spec.base_radius
    alpha_a = math.acos(r_b / r_a)
    return 2 * r_a * (reference_tooth_thickness(spec) / (2 * r) + _involute(spec.transverse_pressure_angle)
                      - _involute(alpha_a))


def rack_point_excess(spec) -> float:
    """How far (in normal modules) the generating rack's tooth half-width at its tip-rounding
    centre passes the quarter pitch: > 0 means the rack tooth comes to a point above its tip line."""
    a = spec.pressure_angle
    rho = spec.rack_tip_radius_coefficient
    return (spec.dedendum_coefficient * math.tan(a) + rho * (1 - math.sin(a)) / math.cos(a)
            - spec.thinning_normal / (2 * spec.module) - math.pi / 4)


def fillet_joint_roll(spec) -> float:
    """Roll parameter ``t_j`` of the involute point the end of the rack's straight flank generates
    (negative: the rack undercuts the gear)."""
    a_n, a_t = spec.pressure_angle, spec.transverse_pressure_angle
    rho = spec.rack_tip_radius_coefficient * spec.module
    v_f = -(spec.dedendum_coefficient - spec.profile_shift) * spec.module + rho - rho * math.sin(a_n)
    return (spec.reference_radius * math.sin(a_t) + v_f / math.sin(a_t)) / spec.base_radius


def tooth_problem(spec) -> str | None:
    """Which rule of the module docstring ``spec`` breaks: "negative_root", "pointed_rack",
    "no_involute", "pointed_tooth" or None (the names of the outline's ``GeometryError`` kinds)."""
    if spec.root_radius_standard <= 0:
        return "negative_root"
    if rack_point_excess(spec) > 1e-12:
        return "pointed_rack"
    if spec.tip_radius <= spec.base_radius:
        return "no_involute"
    if tip_land(spec) < MIN_TIP_LAND_MODULES * spec.module:
        return "pointed_tooth"
    t_joint = fillet_joint_roll(spec)
    if t_joint >= 0 and spec.base_radius * math.sqrt(1 + t_joint * t_joint) >= spec.tip_radius:
        return "no_involute"
    return None


def _with(spec, name: str, value, default_rack_tip: bool = False):
    """``spec`` with one field changed (None if the spec refuses it); ``default_rack_tip``: the
    rack tip radius was not given, so it follows the new proportions as it would in the file."""
    changes = {name: value}
    if default_rack_tip:
        changes["rack_tip_radius_coefficient"] = None
    try:
        return replace(spec, **changes)
    except DesignError:
        return None


def _boundary(spec, name: str, toward, default_rack_tip: bool) -> float | int | None:
    """The value of ``name`` nearest its present one (refused) that makes a makeable tooth, moving
    towards ``toward`` (an end of its range); None when no value on the way does.

    The way is scanned in small steps for the first makeable value (the makeable range of one
    parameter is an interval that need not reach the end of its range), then the crossing is
    bisected."""
    integer = name == "teeth"

    def ok(value) -> bool:
        trial = _with(spec, name, value, default_rack_tip)
        return trial is not None and tooth_problem(trial) is None

    start = getattr(spec, name)
    if integer:
        steps = sorted({int(round(v)) for v in np.geomspace(start, toward, 200)} - {start},
                       reverse=toward < start)
    else:
        steps = list(np.linspace(start, toward, 201)[1:])
    bad_value = start
    for value in steps:
        if ok(value):
            good_value = value
            break
        bad_value = value
    else:
        return None
    for _ in range(200):
        if integer and abs(good_value - bad_value) <= 1:
            break
        mid = (bad_value + good_value) // 2 if integer else (bad_value + good_value) / 2
        if not integer and mid in (bad_value, good_value):
            break
        if ok(mid):
            good_value = mid
        else:
            bad_value = mid
    return int(good_value) if integer else float(good_value)


#: per problem: (parameter, direction that helps) in the order they are named
_REMEDIES = {
    "negative_root": (("profile_shift", +1), ("dedendum_coefficient", -1), ("teeth", +1)),
    "pointed_rack": (("dedendum_coefficient", -1),),
    "no_involute": (("profile_shift", +1), ("addendum_coefficient", +1), ("dedendum_coefficient", -1),
                    ("teeth", +1)),
    "pointed_tooth": (("profile_shift", -1), ("addendum_coefficient", -1), ("teeth", +1)),
}

_WHAT = {
    "negative_root": "the root circle reaches past the gear's axis",
    "pointed_rack": "the generating rack's tooth comes to a point before it reaches this dedendum "
                    "(dedendum x tan(pressure angle) too large)",
    "no_involute": "the tooth has no involute flank below its tip circle",
    "pointed_tooth": "the tooth comes to a point below the tip circle",
}


def _length(value_mm: float, unit: str, toward: str | None = None) -> str:
    value = value_mm / LENGTH_SUFFIXES[unit]
    return f"{bound_text(value, toward) if toward else f'{value:.6g}'} {unit}"


def check_tooth(spec, where: str, written: Mapping[str, str], length_unit: str,
                transverse_shift_factor: float = 1.0) -> None:
    """Raise :class:`DesignError` naming a key of ``written`` when ``spec``'s tooth cannot be cut.

    ``written`` maps the gear's field names to the keys the design file used (``"thinning":
    "thinning_circumferential_in"``); ``where`` is the table's dotted path. The key named is the
    tooth thinning when the unthinned tooth is makeable, else the first parameter the file gives
    that can make it so (profile shift, addendum or dedendum, tooth count), with the allowed range
    in ``length_unit``. ``transverse_shift_factor`` turns the spec's (normal) profile shift into
    the one the file wrote (m_n / m_t for a shift written in the transverse system).
    """
    problem = tooth_problem(spec)
    if problem is None:
        return
    unit = length_unit
    minimum = MIN_TIP_LAND_MODULES * spec.module
    detail = ""
    if problem == "pointed_tooth":
        detail = f" (tip land {_length(tip_land(spec), unit)}, at least {_length(minimum, unit)} needed)"
    elif problem == "negative_root":
        detail = f" (root radius {_length(spec.root_radius_standard, unit)})"
    elif problem == "no_involute":
        detail = f" (tip radius {_length(spec.tip_radius, unit)}, base radius {_length(spec.base_radius, unit)})"
    if problem == "pointed_tooth" and spec.thinning > 0:
        unthinned = _with(spec, "thinning", 0.0)
        if unthinned is not None and tooth_problem(unthinned) is None:
            # the tip land falls linearly with the thinning: d(s_a)/d(thinning) = -r_a / r
            most = (tip_land(unthinned) - minimum) * spec.reference_radius / spec.tip_radius
            key = written.get("thinning_normal") or written.get("thinning_circumferential")
            factor = math.cos(spec.helix_angle) if key.startswith("thinning_normal") else 1.0
            raise DesignError(f"{where}.{key}", f"{_length(spec.thinning * factor, unit)} thins the tooth to a point "
                              f"below the tip circle{detail}", f"[0, {_length(most * factor, unit, 'down')}]")
    fallback = None
    for name, direction in _REMEDIES[problem]:
        lo, hi = _RANGES[name]
        bound = _boundary(spec, name, hi if direction > 0 else lo, "rack_tip_radius_coefficient" not in written)
        if bound is None:
            continue
        value = getattr(spec, name)
        if name == "profile_shift":
            bound, value = bound / transverse_shift_factor, value / transverse_shift_factor
        side = ">=" if direction > 0 else "<="
        text = bound_text(bound, "up" if direction > 0 else "down") if name != "teeth" else str(bound)
        error = DesignError(f"{where}.{name}", f"{value:.6g}: {_WHAT[problem]}{detail}", f"{side} {text}")
        if name in written:
            raise error
        fallback = fallback or error
    if fallback is not None:
        raise fallback
    # no single parameter helps: name the tooth count, which the table always gives
    raise DesignError(f"{where}.teeth", f"{spec.teeth}: {_WHAT[problem]}{detail}",
                      "a gear whose root, tip and tip land the other parameters allow")


__all__ = ["MIN_TIP_LAND_MODULES", "reference_tooth_thickness", "tip_land", "rack_point_excess", "fillet_joint_roll",
           "tooth_problem", "check_tooth"]
