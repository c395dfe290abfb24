"""The verdict rows of the Type 2 rack drive (:mod:`geargen.drives.rack_dual_pinion.place`) beyond its two
external input meshes (which the exact 2-D checker of :mod:`geargen.checks.mesh2d` checks as
every other mesh): the two rack meshes on the exact outlines (:mod:`geargen.families.rack.pair`),
the pinions' placed phase on the rack, the carriage's travel and the preload's reach.

Failures (kinds of :data:`geargen.checks.results.FAILURE_KINDS`): each rack mesh's own
(``tip_to_root_interference``, ``involute_interference``, ``flank_interference``,
``no_backlash``), ``undercut`` when the rack works below the pinion's interference point (the
base circle's tangent point on the line of action, the closed form of
:func:`geargen.families.rack.geometry.rack_pinion_geometry`), ``backlash_out_of_range`` when its measured free-flank backlash leaves the
design range or is not the placed value, ``preload_contact_lost`` when a pinion does not stand
a loaded flank gap from its working flank (the loop is not closed as placed) or the drive force
unloads a path, ``flank_interference`` when a placed pinion's free flank overlaps the rack, ``carriage_travel_exceeded`` when the carriage's stroke cannot take its
placement's offset, the anticipated loop error and teeth made anywhere in the backlash ranges,
``spring_overstressed`` when the carriage spring's wire stress passes 0.45 of its tensile
strength at the preload force or closed solid (:func:`carriage_spring_failure`).
"""

from __future__ import annotations

import math

import numpy as np

from geargen.checks.mesh2d import polar_outline
from geargen.families.rack.pair import PlacedRackPair, boundary_extreme, check_rack_pinion_mesh
from geargen.checks.results import DesignCheck, Failure
from geargen.units import LENGTH_SUFFIXES

#: the measured free-flank backlash may differ from the closed form by this much (mm): the
#: checker's refinement is exact to ~1e-12 mm, this allows for its sampling of mesh positions
RACK_BACKLASH_TOLERANCE = 1e-6
#: mesh positions over one pinion pitch
POSITIONS = 8


def placed_rack_gaps(rack, pinion, centre_offset: float, pinion_x: float, pinion_rotation: float,
                     samples: int = 160) -> tuple[float, float]:
    """Free travel (mm) of the rack toward +x and toward -x against a pinion placed at ``pinion_x``
    with ``pinion_rotation`` (tooth 0's centreline, CCW from +x), on the exact outlines of
    :mod:`geargen.families.rack.pair`; the rack's space centred at x = 0.

    The pair of :mod:`geargen.families.rack.pair` ties the pinion's centre to its turn
    (``X = -r theta``); the placed picture is that pair's with the rack moved ``X - pinion_x``
    toward +x, so the placed travels are the pair's less and plus that shift."""
    from geargen.families.rack.geometry import rack_pinion_geometry
    geometry = rack_pinion_geometry(rack, pinion, centre_offset)
    outline = polar_outline(pinion)
    pair = PlacedRackPair(rack, outline, geometry.centre_height)
    # the pair's turn (tooth 0 points down at theta = 0), reduced to one pinion pitch: the pair
    # looks at the teeth near the bottom; the rack and the pinion repeat by a pitch
    pitch = 2 * math.pi / pinion.teeth
    theta = pinion_rotation + math.pi / 2
    theta -= pitch * round(theta / pitch)
    shift = -pinion.reference_radius * theta - pinion_x  # the pair's pinion centre minus the placed one
    shift -= rack.transverse_pitch * round(shift / rack.transverse_pitch)
    n_seg = outline.segment_count
    u1 = np.concatenate([s + np.linspace(0.0, 1.0, samples, endpoint=False) for s in range(n_seg)] + [[float(n_seg)]])
    u_grid, k_grid = np.meshgrid(u1, pair.teeth.astype(float))
    tip_line = rack.addendum - 1e-9 * rack.module

    def below_tips(X, Y, kind):
        return Y < tip_line

    up, _ = boundary_extreme(pair, theta, lambda X, Y: pair.half_width(Y) + pair.offset(X), below_tips, u_grid, k_grid)
    down, _ = boundary_extreme(pair, theta, lambda X, Y: pair.half_width(Y) - pair.offset(X), below_tips, u_grid,
                               k_grid)
    # seen from the pinion, the placed rack stands `shift` further toward +x than the pair's
    return float(up - shift), float(down + shift)


def carriage_spring_failure(placed, parts: dict, unit: str) -> Failure | None:
    """The carriage spring (``[parts]`` wire, mean diameter, installed length; ``[layout]`` force
    and rate) against its allowable stress (:func:`geargen.core.flexures.spring_for_rate`): at the
    preload force, and closed solid (a spring that takes a set when closed loses its preload). The
    failure names the key to change and a change that passes: the installed length when the wire
    carries the working force and a shorter spring keeps it off solid stress, else the thinnest
    stock music wire (geargen.design.catalogue.WIRE_DIAMETERS) at the same spring index with
    its installed length. Installed at least max(d, 15 % of the working deflection, the carriage's
    stroke) above solid: the swept coils' pitch, Shigley's clash allowance, the carriage's travel."""
    from geargen.core.flexures import smallest_spring_wire, spring_for_rate, spring_installed_range
    from geargen.design.catalogue import WIRE_DIAMETERS
    force, rate = placed.spring_force, placed.spring_rate
    d, mean, installed = parts["spring_wire_diameter"], parts["spring_mean_diameter"], parts["spring_installed_length"]
    shear = parts["spring_shear_modulus_GPa"] * 1e3
    spring = spring_for_rate(force, rate, d, mean, installed, shear)
    allowed = spring.allowable_shear_stress
    if spring.installed_stress <= allowed and spring.solid_stress <= allowed:
        return None
    k = LENGTH_SUFFIXES[unit]

    def clearance(wire: float) -> float:
        return max(wire, 0.15 * force / rate, placed.carriage_travel)

    stress = (f"carriage spring ({d / k:.4g} {unit} wire on {mean / k:.4g} {unit}, index {spring.index:.3g}, Wahl "
              f"{spring.wahl_factor:.4f}): {spring.installed_stress:.4g} MPa at the preload's {force:.4g} N, "
              f"{spring.solid_stress:.4g} MPa closed solid ({spring.solid_force:.4g} N), against 0.45 S_ut = "
              f"{allowed:.4g} MPa")
    lo, hi = spring_installed_range(spring, clearance(d))
    if spring.installed_stress <= allowed and lo < hi:
        fix = (f"parts.spring_installed_length_{unit}: {lo / k:.4g} to {hi / k:.4g} {unit} (solid at "
               f"{spring.solid_height / k:.4g} {unit})")
    else:
        found = smallest_spring_wire(force, rate, spring.index, shear, clearance, [w for w in WIRE_DIAMETERS if w >= d])
        if found is None:
            fix = (f"parts.spring_wire_diameter_{unit}: no music wire up to {WIRE_DIAMETERS[-1]:.4g} mm at index "
                   f"{spring.index:.3g} carries it; a smaller [layout] carriage_preload_force_N or a softer "
                   "carriage_spring_rate_N_per_mm")
        else:
            better, (lo, hi) = found
            fix = (f"parts.spring_wire_diameter_{unit} = {better.wire_diameter / k:.4g} with "
                   f"spring_mean_diameter_{unit} = {better.mean_coil_diameter / k:.4g} (index {spring.index:.3g} "
                   f"kept) and spring_installed_length_{unit} {lo / k:.4g} to {hi / k:.4g} ({better.installed_stress:.4g} "
                   f"MPa installed; installed at {better.installed_length / k:.4g} {unit}, {better.solid_stress:.4g} "
                   f"MPa closed solid; of {better.allowable_shear_stress:.4g} MPa)")
    worst = max(spring.installed_stress, spring.solid_stress)
    return Failure("spring_overstressed", "carriage_spring", f"{stress}; change {fix}", "shear_stress_MPa", worst,
                   allowed)


def rack_meshes(layout, result: DesignCheck) -> list[dict]:
    """The rack drive's own verdict rows (see the module docstring); [] for another drive."""
    from geargen.drives.rack_dual_pinion.place import rack_drive, report
    placed = rack_drive(layout)
    if placed is None:
        return []
    unit = layout.identity.length_unit
    k = LENGTH_SUFFIXES[unit]
    lo, hi = placed.rack_backlash_range
    rows = []
    for side, sense in (("a", +1), ("b", -1)):
        name = f"rack_{side}"
        part = layout.gear(f"pinion_{side}")
        check = check_rack_pinion_mesh(placed.rack, placed.pinion, placed.rack_offset, POSITIONS, min_backlash=lo)
        for f in check.failures:
            result.failures.append(Failure(f.kind, name, f.message, f.quantity, f.value, f.limit, f.mesh_position))
        geometry = check.geometry
        if "involute" in geometry.interference:
            # the rack that cut the pinion also meshes with it without touching the undercut, but
            # the active profile then starts inside the undercut: contact is lost there
            limit = placed.pinion.reference_radius * math.sin(geometry.transverse_pressure_angle)
            reach = (placed.rack.addendum - placed.rack.tip_radius * (1 - math.sin(placed.rack.pressure_angle))
                     - geometry.rolling_line_height) / math.sin(geometry.transverse_pressure_angle)
            result.failures.append(Failure("undercut", name, f"the rack's straight flank works {reach / k:.4g} {unit} "
                                           f"down the line of action, past the pinion's interference point at "
                                           f"{limit / k:.4g} {unit}: the {placed.pinion.teeth}-tooth pinion is "
                                           "undercut where the rack works", "path_difference", reach, limit))
        j_min = float(check.circumferential_backlash.min())
        j_max = float(check.circumferential_backlash.max())
        if not (lo - RACK_BACKLASH_TOLERANCE <= j_min and j_max <= hi + RACK_BACKLASH_TOLERANCE):
            result.failures.append(Failure("backlash_out_of_range", name, f"rack backlash {j_min / k:.6g} to "
                                           f"{j_max / k:.6g} {unit} is outside the design range {lo / k:.6g} to "
                                           f"{hi / k:.6g} {unit}", "circumferential_backlash",
                                           j_min if j_min < lo else j_max, lo if j_min < lo else hi))
        elif max(abs(j_min - placed.rack_backlash), abs(j_max - placed.rack_backlash)) > RACK_BACKLASH_TOLERANCE:
            result.failures.append(Failure("backlash_out_of_range", name, f"rack backlash {j_min / k:.6g} to "
                                           f"{j_max / k:.6g} {unit} is not the placed {placed.rack_backlash / k:.6g} "
                                           f"{unit} (the centre offset's closed form)", "circumferential_backlash",
                                           j_min, placed.rack_backlash))
        up, down = placed_rack_gaps(placed.rack, placed.pinion, placed.rack_offset, part.centre[0], part.rotation)
        # pinion a bears on the rack toward +x: the rack moving -x meets it after the loaded flank gap
        working, free = (down, up) if sense > 0 else (up, down)
        if abs(working - placed.loaded_flank_gap) > RACK_BACKLASH_TOLERANCE:
            result.failures.append(Failure("preload_contact_lost", name, f"pinion {side} stands {working / k:.4g} "
                                           f"{unit} from its working flank on the rack, not the loaded flank gap "
                                           f"{placed.loaded_flank_gap / k:.4g} {unit}: the loop is not closed as "
                                           "placed", "circumferential_backlash", working, placed.loaded_flank_gap))
        if free < -RACK_BACKLASH_TOLERANCE:
            result.failures.append(Failure("flank_interference", name, f"pinion {side}'s free flank overlaps the "
                                           f"rack by {-free / k:.4g} {unit} as placed", "circumferential_backlash",
                                           free, 0.0))
        rows.append(dict(table="rack", mesh=name, gear1=f"pinion_{side}", gear2="rack", backlash_min=j_min, backlash_max=j_max,
                         design_min=lo, design_max=hi, placed_backlash=placed.rack_backlash,
                         working_flank_gap=working, free_flank_gap=free,
                         tip_clearance=float(min(check.tip_clearance_pinion.min(), check.tip_clearance_rack.min())),
                         contact_ratio=check.geometry.contact_ratio_transverse, centre_offset=placed.rack_offset,
                         where="circumferential along the rack's rolling line (the pinion's reference circle), "
                               "on the exact outlines"))
    values = report(placed)
    needed = abs(placed.carriage_deviation) + placed.loop_error_travel + placed.tolerance_travel
    if needed > placed.carriage_travel:
        result.failures.append(Failure("carriage_travel_exceeded", "carriage", f"the carriage must travel "
                                       f"{needed / k:.4g} {unit} (placed {placed.carriage_deviation / k:+.4g} {unit} "
                                       f"from nominal, {placed.loop_error_travel / k:.4g} {unit} for the "
                                       f"{placed.loop_error / k:.4g} {unit} loop error, "
                                       f"{placed.tolerance_travel / k:.4g} {unit} for teeth anywhere in the backlash "
                                       f"ranges) but its stroke is "
                                       f"{placed.carriage_travel / k:.4g} {unit}", "carriage_travel", needed,
                                       placed.carriage_travel))
    if placed.max_rack_force is not None and placed.max_rack_force > values["unloading_rack_force"]:
        result.failures.append(Failure("preload_contact_lost", "carriage", f"a drive force of "
                                       f"{placed.max_rack_force:.4g} N on the rack unloads a path at "
                                       f"{values['unloading_rack_force']:.4g} N: the carriage spring's "
                                       f"{placed.spring_force:.4g} N is too weak (Fig. 9)", "rack_force_N",
                                       placed.max_rack_force, values["unloading_rack_force"]))
    spring = carriage_spring_failure(placed, layout.resolved.parts, unit)
    if spring is not None:
        result.failures.append(spring)
    rows.append(dict(table="rack", mesh="carriage", gear1="input", gear2="", carriage_y=placed.carriage_y,
                     carriage_deviation=placed.carriage_deviation, carriage_needed=needed,
                     carriage_travel=placed.carriage_travel, **{k_: v for k_, v in values.items()
                                                                if k_ not in ("carriage_y", "carriage_deviation",
                                                                              "carriage_travel")}))
    return rows


__all__ = ["rack_meshes", "carriage_spring_failure", "placed_rack_gaps", "RACK_BACKLASH_TOLERANCE"]
