"""The axial-motion preload drive placed (Hale & Slocum, "Type 2 Design": "axial motion of a pair
of right and left handed helical gears"): ``[layout] kind = "axial_preload"``.

The drive. An input shaft at ``(centre_distance, 0)`` carries a left-hand pinion (from z = 0)
and, ``pinion_axial_gap`` above it, a right-hand pinion, fixed to each other; the output shaft
at the origin carries a right-hand gear meshing the left-hand pinion (mesh ``mesh_left``) and a
left-hand gear meshing the right-hand pinion (``mesh_right``), clamped to each other. The loop:
input -> mesh_left -> output -> mesh_right -> input. The input shaft slides along z in its
bearings; a compression spring pushes it along +z. Two output gears rather than one
double-helical gear: each mesh is then a plain external helical pair that the exact checker
(:mod:`geargen.checks.mesh2d`) verifies as it is, and the two halves are phased to each other
when they are clamped (a one-piece herringbone would fix that phase by its cutting).

The slide. A helical flank is a helicoid of lead ``L = 2 pi r / tan(beta)`` (the same at every
radius: ``tan(beta) / r = tan(beta_w) / r_w = tan(beta_b) / r_b``), so sliding a pinion by ``s``
along its axis while its shaft does not turn turns its transverse section, in any fixed plane,
by ``s tan(beta) / r``: an arc ``s tan(beta)`` on the reference circle, whatever radius one
measures at (the backlash of the model is circumferential at the pinion's reference circle, so
that is the radius used). The left hand turns counter-clockwise for +s, the right hand
clockwise: +s closes the left-hand pinion's counter-clockwise flank in ``mesh_left`` and the
right-hand pinion's clockwise flank in ``mesh_right`` (the working flanks). With the shaft's
turn ``theta`` (counter-clockwise) and each mesh's backlash ``j`` centred at s = 0 (the
reference position, where the output halves are phased), the working gaps are
``j_l / 2 - s tan(beta) - r theta`` and ``j_r / 2 - s tan(beta) + r theta``; both equal to the
loaded flank gap ``g`` at

    s = (j_l + j_r - 4 g) / (4 tan(beta)),    theta = (j_l - j_r) / (4 r).

From the free flanks in contact (a slide of the whole loop backlash) it would be
``(j_l + j_r) / (2 tan(beta))`` (:func:`geargen.core.axial_preload.axial_travel_for_backlash`).
The solids are placed at this take-up (rigid teeth, ``g`` left open). Under the preload the
teeth yield and the spring pushes the shaft further by the windup
``(P / k_1 + P / k_2) / (2 lambda)`` with ``lambda = tan(beta) / r_2`` the output rotation of
each path per mm of slide (``r_2`` the output gear's reference radius) and ``k_i`` the mesh
stiffness of Eq. 1 at the output (``E w / 11`` along the line of action, times ``r_b2^2``; or ISO
6336 as ``[stiffness] mesh_stiffness`` says). The loop preload ``P`` and the spring's stiffness
``k_a`` come from ``[preload]`` (``preload_*``, ``preload_spring_stiffness_N_per_mm``), the
modulus from ``[stiffness]``: the same numbers the stiffness summary reads, which takes its
preload lever ``lambda`` from this placement.

Forces. Each path carries the loop preload ``P`` (torque at the output), a tangential force
``F_t = P / r_2`` at the reference circles; each helix takes ``F_t tan(beta)`` axially, so the
spring force is ``F_axial = 2 F_t tan(beta)`` (:mod:`geargen.core.axial_preload`), and with the
drive torque (equal and opposite increments of the two paths' tangential force) the axial
forces' change cancels: the preload is decoupled from the drive torque (Type 2).

Stiffness (Eqs. 5 and 6). The spring of axial stiffness ``k_a`` acts on the loop through the
lever ``lambda`` on each path, so it is ``k_3 = k_a / lambda^2 = k_a (r_2 / tan(beta))^2`` at the
output (:func:`geargen.core.stiffness.preload_spring_at_output`).

Friction. The input shaft slides in its two bearings (their outer rings in the plates' bores,
placed by ``[parts]``: :func:`input_bearing_faces`), and each ring's friction is mu times its
radial reaction (:func:`geargen.core.axial_preload.input_bearing_reactions`). The meshes' forces
on the shaft: the two separating components ``(P / r_b2) sin(alpha_wt)`` add; the two tangential
ones cancel as forces but, a face and the pinions' gap apart, make a couple; the two axial forces
``F_t tan(beta)``, at the working pitch radius on the output's side, make a second couple. The
bearings carry the net force and both couples, so the friction is mu (R_lower + R_upper), more
than mu times the net side force. Over the spring force that is the friction-to-preload ratio;
it grows as the helix angle shrinks (the paper's warning): a design whose ratio exceeds
``max_friction_to_preload`` is refused, naming the helix angle and the smallest that passes (at
its standard centre distance, which the message gives).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from geargen.core.axial_preload import (friction_to_preload_ratio, helix_angle_table, input_bearing_reactions,
                                        preload_band, smallest_helix_angle)
from geargen.core.drive import TwoPathDrive
from geargen.core.involute import working_pressure_angle_at
from geargen.core.stiffness import gear_mesh_stiffness, preload_spring_at_output, torsional_from_linear
from geargen.core.synthesis import mate_rotation
from geargen.design.assembly import Design
from geargen.design.gear import GearSpec
from geargen.errors import DesignError
from geargen.model.allowance import MeshRange, model_gears, model_source
from geargen.model.layout import GearPlacement, Layout, MeshPlacement, ratio_check, running_backlash
from geargen.model.shafts import Bearing, Shaft, bore_of, mid_face
from geargen.profile.tooth import section_rotation
from geargen.units import LENGTH_SUFFIXES

#: the meshes of the loop: (mesh name, pinion role, output role, working flank of the pinion)
MESHES = (("mesh_left", "pinion_left", "output_right", "input ccw"),
          ("mesh_right", "pinion_right", "output_left", "input cw"))


def slide_for_backlash(backlash_left: float, backlash_right: float, helix_angle: float,
                       loaded_flank_gap: float = 0.0) -> float:
    """Slide of the input shaft (mm, along +z) from the reference position (both meshes centred in
    their play) that leaves ``loaded_flank_gap`` on both working flanks; backlash circumferential
    at the pinion's reference circle (mm). See the module docstring."""
    return (backlash_left + backlash_right - 4 * loaded_flank_gap) / (4 * math.tan(helix_angle))


def turn_for_backlash(backlash_left: float, backlash_right: float, pinion_reference_radius: float) -> float:
    """The input shaft's counter-clockwise turn (rad) that shares the slide's take-up between two
    meshes of unequal backlash."""
    return (backlash_left - backlash_right) / (4 * pinion_reference_radius)


def axial_lever(helix_angle: float, output_reference_radius: float) -> float:
    """``lambda``: output rotation of each path per mm of the input's slide (rad/mm)."""
    return math.tan(helix_angle) / output_reference_radius


def input_bearing_faces(lowest_face: float, highest_face: float, parts: dict[str, Any]) \
        -> tuple[tuple[float, float], tuple[float, float]]:
    """The z ranges (mm) of the input shaft's lower and upper bearing at the reference position (no
    slide): a ``bearing_clearance`` beyond the lowest and highest gear face of the drive."""
    gap, width = parts["bearing_clearance"], parts["input_bearing_width"]
    return (lowest_face - gap - width, lowest_face - gap), (highest_face + gap, highest_face + gap + width)


def _windup_slide(preload: float, k1: float, k2: float, lever: float) -> float:
    """Slide (mm) that winds the meshes up to the loop preload ``preload`` (N mm at the output)."""
    return (preload / k1 + preload / k2) / (2 * lever)


def _centred_rotation(pinion: GearSpec, output: GearSpec, rot_output_face: float, z_output: float,
                      z_pinion: float) -> float:
    """Rotation (at the pinion's own face, height ``z_pinion``) that centres the pinion in its play
    with the output gear at the origin (rotation ``rot_output_face`` at its face ``z_output``)."""
    rot_output_there = rot_output_face + section_rotation(output, z_pinion - z_output)
    return float(mate_rotation(math.pi, rot_output_there, pinion.teeth, output.teeth, 0.0, 0))


def _preload_inputs(design: Design) -> tuple[float, float, float, str]:
    """(loop preload N mm at the output, the spring's axial stiffness N/mm, the gears' elastic
    modulus MPa, the mesh stiffness method) from their homes: ``[preload]`` (``preload_*``, else
    the paper's rule for a Type 2 drive, half the largest load; ``preload_spring_stiffness_*``
    linear) and ``[stiffness]``; the drive must say ``[drive] type = "type2"``,
    ``preload = "axial"``."""
    from geargen.core.stiffness import required_preload
    from geargen.design.stiffness import stiffness_design
    if design.drive_type != "type2" or design.preload_method != "axial":
        raise DesignError("drive.preload" if design.drive_type == "type2" else "drive.type",
                          f"type {design.drive_type!r}, preload {design.preload_method!r}: the axial preload is a Type 2 "
                          "drive whose preload device slides the input", "[drive] type = 'type2', preload = 'axial'")
    if not design.section("stiffness") or not design.section("preload"):
        raise DesignError("preload" if design.section("stiffness") else "stiffness", "missing: the slide, the spring "
                          "force and the loop's stiffness follow from the preload and the meshes' stiffness",
                          "[stiffness] (the gears' elastic modulus, the meshes as components) and [preload] "
                          "(max_output_torque_*, preload_*, preload_spring_stiffness_N_per_mm)")
    sd = stiffness_design(design)
    pre = sd.preload
    if pre.preload_spring_linear is None:
        raise DesignError("preload.preload_spring_stiffness", "missing: the axial preload's spring pushes the input "
                          "shaft along its axis", "preload_spring_stiffness_N_per_mm (linear, along the slide)")
    preload = pre.preload if pre.preload is not None else required_preload(pre.max_output_torque, "type2")
    return preload, pre.preload_spring_linear, sd.stiffness.elastic_modulus, sd.stiffness.mesh_stiffness


#: the design keys of each mesh's backlash range
RANGE_KEYS = ("layout.circumferential_backlash_min", "layout.circumferential_backlash_max")


def place_axial_preload(design: Design, s: dict) -> Layout:
    """The resolved axial-preload drive (see the module docstring)."""
    k = LENGTH_SUFFIXES[design.length_unit]
    unit = design.length_unit
    spec = {role: design.gear(s[role]) for role in ("pinion_left", "pinion_right", "output_right", "output_left")}
    c = s["centre_distance"]
    lo, hi = s["circumferential_backlash_min"], s["circumferential_backlash_max"]
    if lo > hi:
        raise DesignError(f"layout.circumferential_backlash_min_{unit}", f"{lo / k:.6g} {unit} is larger than the "
                          f"maximum {hi / k:.6g} {unit}", f"[0, {hi / k:.6g}] {unit}")
    rule = s["model_tooth_thickness"]
    gap = s["loaded_flank_gap"]
    notes: list[str] = []
    thinning_source = model_source(rule)
    if rule != "as_designed":
        made = model_gears(design, rule, [MeshRange(spec[p], spec[o], lo, hi, c, RANGE_KEYS) for _, p, o, _ in MESHES])
        spec = {role: made[g.name] for role, g in spec.items()}
        notes.append(f"thinning made at {rule} of each allowance: " + ", ".join(
            f"{s[r]} {spec[r].thinning / k:.6g} {unit}" for r in spec) + " (circumferential, at the reference circle)")
    pl, pr, o_r, o_l = (spec[r] for r in ("pinion_left", "pinion_right", "output_right", "output_left"))
    backlash = {m: running_backlash(spec[p], spec[o], c) for m, p, o, _ in MESHES}
    for m, p, o, _ in MESHES:
        if not backlash[m] > 2 * gap:
            raise DesignError(f"gears.{s[p]}", f"{m}: the teeth have {backlash[m] / k:.4g} {unit} of backlash at "
                              f"{c / k:.6g} {unit}, not more than twice the loaded flank gap {gap / k:.4g} {unit}",
                              "thinner teeth or a larger backlash range")

    beta = pl.helix_angle
    r_p, r_o = pl.reference_radius, o_r.reference_radius
    # heights at the reference position: the pinions stacked, each output gear centred on its pinion
    z_pl = 0.0
    z_pr = pl.face_width + s["pinion_axial_gap"]
    z_or = z_pl + (pl.face_width - o_r.face_width) / 2
    z_ol = z_pr + (pr.face_width - o_l.face_width) / 2
    if z_or + o_r.face_width > z_ol + 1e-9:
        raise DesignError(f"layout.pinion_axial_gap_{unit}", f"the output gears' faces overlap: {s['output_right']} "
                          f"reaches {(z_or + o_r.face_width) / k:.6g} {unit}, {s['output_left']} starts at {z_ol / k:.6g} {unit}",
                          f">= {(s['pinion_axial_gap'] + z_or + o_r.face_width - z_ol) / k:.6g} {unit}")
    # the output halves are phased with a tooth space on +x (facing the pinion) at their own faces
    rot_or, rot_ol = math.pi / o_r.teeth, math.pi / o_l.teeth
    ref_pl = _centred_rotation(pl, o_r, rot_or, z_or, z_pl)
    ref_pr = _centred_rotation(pr, o_l, rot_ol, z_ol, z_pr)

    # the slide that closes the loop: take-up (the solids) and windup (the preload)
    take_up = slide_for_backlash(backlash["mesh_left"], backlash["mesh_right"], beta, gap)
    theta = turn_for_backlash(backlash["mesh_left"], backlash["mesh_right"], r_p)
    preload, k_axial, elastic, method = _preload_inputs(design)
    engaged = {m: min(spec[p].face_width, spec[o].face_width) for m, p, o, _ in MESHES}
    k_mesh = {m: gear_mesh_stiffness(spec[p], spec[o], engaged[m], elastic, method, "stiffness.mesh_stiffness")[0]
              for m, p, o, _ in MESHES}  # N/mm along the line of action (Eq. 1 or ISO 6336)
    k_path = {m: float(torsional_from_linear(k_mesh[m], o_r.base_radius)) for m in k_mesh}  # N mm/rad at the output
    lever = axial_lever(beta, r_o)
    windup = _windup_slide(preload, k_path["mesh_left"], k_path["mesh_right"], lever)
    k3 = float(preload_spring_at_output(k_axial, lever))
    drive = TwoPathDrive("type2", k_path["mesh_left"], k_path["mesh_right"], preload, k3)
    tangential = preload / r_o
    spring_force = 2 * tangential * math.tan(beta)
    # the slide at either end of the design's backlash range (teeth in contact, preloaded)
    slide_range = (slide_for_backlash(lo, lo, beta) + windup, slide_for_backlash(hi, hi, beta) + windup)
    stroke = s["input_stroke"]
    # the stroke must hold the slide of the largest backlash of the range, and of the teeth as modelled
    # (as designed, they may lie outside the range: the check then says so, the slide still happens)
    needed = max(slide_range[1], take_up + gap / math.tan(beta) + windup)  # flanks touching, wound up
    if stroke < needed:
        raise DesignError(f"layout.input_stroke_{s['_units'].get('input_stroke', unit)}",
                          f"{stroke / k:.6g} {unit} is shorter than the slide the preload needs with the largest "
                          f"backlash ({needed / k:.6g} {unit}: take-up {(needed - windup) / k:.6g} + windup "
                          f"{windup / k:.6g})", f">= {needed / k:.6g} {unit}")
    # friction of the sliding fit against the preload: the outer rings of the input's two bearings
    # slide in their bores, each pressed by its reaction to the meshes' forces and couples
    from geargen.design.parts import parts_settings
    if not design.section("parts"):
        raise DesignError("parts", "missing: the sliding fit's friction acts on the input shaft's two bearings, "
                          "which [parts] places", "a [parts] table sizing the axial_preload hardware "
                          "(bearing_clearance_*, input_bearing_width_*, ...)")
    alpha_wt = working_pressure_angle_at(float(pl.base_radius + o_r.base_radius), float(c))
    mu = s["sliding_friction_coefficient"]
    # at the reference position (the slide, tens of um, moves the arms by less than 0.1 %): each mesh
    # at the middle of its faces' overlap
    bearings = tuple(sum(faces) / 2 for faces in input_bearing_faces(
        min(z_pl, z_or), max(z_pr + pr.face_width, z_ol + o_l.face_width), parts_settings(design)))
    mesh_z = ((max(z_pl, z_or) + min(z_pl + pl.face_width, z_or + o_r.face_width)) / 2,
              (max(z_pr, z_ol) + min(z_pr + pr.face_width, z_ol + o_l.face_width)) / 2)

    def lateral_at(helix: float, alpha_t: float | None = None, alpha_w: float | None = None,
                   pitch_radius: float | None = None) -> float:
        """k: the bearings' reactions over the reference tangential preload F_t = P / r_2. Each mesh
        pushes along its line of action with P / r_b2 = F_t / cos(alpha_t) (separating part
        sin(alpha_wt), tangential cos(alpha_wt)) and axially with F_t tan(beta) at the pinion's working
        pitch radius. Other helix angles: standard centres, the same teeth, module and faces."""
        if alpha_t is None:
            alpha_t = math.atan(math.tan(pl.pressure_angle) / math.cos(helix))
            alpha_w, pitch_radius = alpha_t, pl.teeth * pl.module / (2 * math.cos(helix))
        line = 1 / math.cos(alpha_t)
        return sum(input_bearing_reactions(mesh_z, bearings, line * math.cos(alpha_w), line * math.sin(alpha_w),
                                           math.tan(helix), pitch_radius))

    lateral = lateral_at(beta, pl.transverse_pressure_angle, alpha_wt, c * pl.base_radius / (pl.base_radius + o_r.base_radius))
    ratio = friction_to_preload_ratio(mu, beta, lateral)
    limit = s["max_friction_to_preload"]
    smallest = smallest_helix_angle(mu, lateral_at, limit)
    if ratio > limit:
        if smallest is None:
            allowed = (f"no helix angle reaches it with these bearings and mu {mu:.3g}: a longer bearing span "
                       f"([parts] bearing_clearance_{unit}), a lower sliding_friction_coefficient (a ball bushing) or a larger limit")
        else:
            # rounded up so that the angle given passes; its standard centre distance goes with it
            deg = math.ceil(math.degrees(smallest) * 100) / 100
            standard = (pl.teeth + o_r.teeth) * pl.module / (2 * math.cos(math.radians(deg)))
            allowed = (f">= {deg:.2f} deg (all four gears), with layout.centre_distance_{unit} "
                       f"{standard / k:.6g} (standard there)")
        raise DesignError(f"gears.{s['pinion_left']}.helix_angle_deg",
                          f"{math.degrees(beta):.4g} deg: the sliding fit's friction is {ratio:.3g} of the spring force "
                          f"(mu {mu:.3g}; the input bearings' reactions {lateral:.3g} F_t, from the meshes' forces "
                          f"and couples over their {(bearings[1] - bearings[0]) / k:.4g} {unit} span), above "
                          f"layout.max_friction_to_preload {limit:.3g}", allowed)
    band = preload_band(spring_force, beta, mu, lateral)
    table = [dict(helix_angle_deg=row.helix_angle_deg, friction_to_preload=row.friction_to_preload,
                  hysteresis=row.hysteresis, tangential_preload_per_spring_force=row.preload_per_spring_force)
             for row in helix_angle_table(mu, pl.pressure_angle, lateral_at)]

    gears = [
        GearPlacement(s["output_right"], o_r, (0.0, 0.0), z_or, rot_or, "output", ("output",)),
        GearPlacement(s["output_left"], o_l, (0.0, 0.0), z_ol, rot_ol, "output", ("output",)),
        GearPlacement(s["pinion_left"], pl, (c, 0.0), z_pl + take_up, ref_pl + theta, "input", ("input",)),
        GearPlacement(s["pinion_right"], pr, (c, 0.0), z_pr + take_up, ref_pr + theta, "input", ("input",)),
    ]
    by = {g.name: g for g in gears}
    meshes = []
    for m, p, o, flank in MESHES:
        gp, go = by[s[p]], by[s[o]]
        zl = max(gp.face_z(spec[p])[0], go.face_z(spec[o])[0])
        zh = min(gp.face_z(spec[p])[1], go.face_z(spec[o])[1])
        meshes.append(MeshPlacement(m, s[p], spec[p], s[o], spec[o], (zl + zh) / 2, lo, hi, backlash[m], True,
                                    flank, c, RANGE_KEYS))
    report: dict[str, Any] = {
        "slide": {"take_up": take_up, "windup": windup, "total": take_up + windup, "turn_rad": theta,
                  "at_backlash_min": slide_range[0], "at_backlash_max": slide_range[1], "stroke": stroke,
                  "stroke_margin": stroke - slide_range[1],
                  "radius": "reference circle of the pinion (s tan(beta) of arc there; the lead is one at every radius)"},
        "forces": {"preload_torque_output_Nmm": preload, "preload_torque_input_Nmm": tangential * r_p,
                   "tangential_preload_N": tangential, "spring_force_N": spring_force,
                   "spring_compression": spring_force / k_axial, "lateral_load_N": lateral * tangential},
        "friction": {"coefficient": mu, "lateral_force_factor": lateral, "working_pressure_angle_rad": alpha_wt,
                     "friction_to_preload": ratio, "max_friction_to_preload": limit,
                     "smallest_helix_angle_rad": smallest, "preload_band_N": [band.low, band.nominal, band.high],
                     "hysteresis": band.hysteresis, "helix_angle_table": table},
        "stiffness": {"mesh_N_per_mm": k_mesh, "k1": drive.k1, "k2": drive.k2, "lever_rad_per_mm": lever,
                      "spring_axial_N_per_mm": k_axial, "k3": k3, "drive_eq5": drive.drive_stiffness,
                      "loop_eq6": drive.loop_stiffness, "loop_windup_rad": preload / k_path["mesh_left"]
                      + preload / k_path["mesh_right"], "units": "N mm/rad at the output"},
    }
    notes += [
        f"axial preload: the input slides {take_up * 1e3:.4g} um to take up the backlash "
        f"({backlash['mesh_left'] / k:.4g} + {backlash['mesh_right'] / k:.4g} {unit}, the solids placed there, "
        f"{gap / k:.4g} {unit} left on the working flanks) and {windup * 1e3:.4g} um more to wind the meshes "
        f"up to the preload: {(take_up + windup) * 1e3:.4g} um of a {stroke / k:.4g} {unit} stroke "
        f"({slide_range[0] * 1e3:.4g} to {slide_range[1] * 1e3:.4g} um over the backlash range)",
        f"axial preload: spring force {spring_force:.4g} N = 2 F_t tan(beta) for the loop preload "
        f"{preload / 1e3:.4g} N m at the output (F_t {tangential:.4g} N per path); spring compressed "
        f"{spring_force / k_axial / k:.4g} {unit} at {k_axial:.4g} N/mm",
        f"axial preload: friction-to-preload {ratio:.3g} at helix {math.degrees(beta):.4g} deg (mu {mu:.3g}, "
        f"input bearings' reactions {lateral * tangential:.4g} N = {lateral:.3g} F_t; limit {limit:.3g} needs "
        + ("a longer bearing span or less friction" if smallest is None else f">= {math.degrees(smallest):.4g} deg")
        + f"); preload band "
        f"{band.low:.4g} to {band.high:.4g} N of F_t; by helix angle: " + ", ".join(
            f"{row['helix_angle_deg']:.0f} deg {row['friction_to_preload']:.3g}" for row in table),
        f"axial preload: stiffness at the output, meshes only: k1 = k2 = {drive.k1 / 1e3:.4g} N m/rad, "
        f"k3 = {k3 / 1e3:.4g} N m/rad (spring {k_axial:.4g} N/mm x (r_2 / tan(beta))^2); drive (Eq. 5) "
        f"{drive.drive_stiffness / 1e3:.4g} N m/rad, loop (Eq. 6) {drive.loop_stiffness / 1e3:.4g} N m/rad",
    ]
    ratio = ratio_check(design, s, Fraction(o_r.teeth, pl.teeth), "input to output")
    return Layout(design=design, kind="axial_preload", gears=tuple(gears), meshes=tuple(meshes), settings=s,
                  ratio=ratio, notes=tuple(notes), axial_shift={"input": take_up},
                  thinning={g.name: {"source": thinning_source} for g in gears}, drive_report=report)


@dataclass(frozen=True)
class AxialPreloadHardware:
    """The placed shafts, bearings and preload spring of an axial-preload drive (mm): the one home
    of the lengths the parts are built from. ``input`` slides with the pinions (its bearings too:
    their outer rings float in the plates' bores); the plates stand where the reference position
    (no slide) puts the bearings, so the slide ``shift`` shows as the input bearings' offset in
    their bores and a longer spring. ``spring_z``: the spring from the cup's floor to the lower
    input bearing's face (its installed length plus the slide); ``stroke_z``: the face of the stop
    over the upper input bearing, the highest its face may reach (the reference plus
    ``[layout] input_stroke``)."""

    input: Shaft
    output: Shaft
    shift: float
    bottom_plate: tuple[float, float]  # z range
    top_plate: tuple[float, float]
    spring_z: tuple[float, float]
    spring_active_coils: float
    cup_floor_z: float
    stroke_z: float


def axial_preload_hardware(layout: Layout, parts: dict[str, Any]) -> AxialPreloadHardware:
    """The shafts and spring of the drive placed by :func:`place_axial_preload` (see
    :class:`AxialPreloadHardware`): each shaft on two bearings a ``bearing_clearance`` beyond its
    gears' faces; the plates as thick as the narrower bearing, level with the bearings' inner faces
    at the reference position; the spring's active coils from its rate ``G d^4 / (8 D^3 n)``."""
    from geargen.core.flexures import spring_rate
    st = layout.settings
    gap = parts["bearing_clearance"]
    shift = layout.axial_shift["input"]
    pin = [layout.gear(st[r]) for r in ("pinion_left", "pinion_right")]
    out = [layout.gear(st[r]) for r in ("output_right", "output_left")]
    d_in, d_out = bore_of(pin[0].spec), bore_of(out[0].spec)
    for placed in pin + out:
        own = bore_of(placed.spec)
        if not own > 0 or own != bore_of((pin if placed in pin else out)[0].spec):
            raise DesignError(f"gears.{placed.name}.bore_diameter", f"{own:.6g} mm: the gears on one shaft share its "
                              "diameter, which their bore gives", f"{bore_of((pin if placed in pin else out)[0].spec):.6g} mm")
    ibw, ibod = parts["input_bearing_width"], parts["input_bearing_outer_diameter"]
    obw, obod = parts["output_bearing_width"], parts["output_bearing_outer_diameter"]
    lo_in = min(p.height[0] for p in pin) - shift  # the pinions' faces at the reference position
    hi_in = max(p.height[1] for p in pin) - shift
    lo_out, hi_out = min(p.height[0] for p in out), max(p.height[1] for p in out)
    plate_t = min(ibw, obw)
    bottom = (min(lo_in, lo_out) - gap - plate_t, min(lo_in, lo_out) - gap)
    top = (max(hi_in, hi_out) + gap, max(hi_in, hi_out) + gap + plate_t)
    lower, upper = input_bearing_faces(min(lo_in, lo_out), max(hi_in, hi_out), parts)
    in_bearings = (Bearing("input_bearing_lower", lower[0] + shift, ibw, d_in, ibod),
                   Bearing("input_bearing_upper", upper[0] + shift, ibw, d_in, ibod))
    out_bearings = (Bearing("output_bearing_lower", bottom[1] - obw, obw, d_out, obod),
                    Bearing("output_bearing_upper", top[0], obw, d_out, obod))
    c = tuple(pin[0].centre)
    shaft_in = Shaft("input_shaft", c, in_bearings[0].z, in_bearings[1].z + ibw + parts["motor_stub_length"], d_in,
                     in_bearings, {p.name: mid_face(p, p.spec) for p in pin})
    shaft_out = Shaft("output_shaft", tuple(out[0].centre), out_bearings[0].z, out_bearings[1].z + obw, d_out,
                      out_bearings, {p.name: mid_face(p, p.spec) for p in out})
    d, mean = parts["spring_wire_diameter"], parts["spring_mean_diameter"]
    if not (mean - d > d_in and mean + d < ibod):
        raise DesignError("parts.spring_mean_diameter", f"{mean:.6g} mm: the coils ({mean - d:.6g} to {mean + d:.6g} mm) "
                          f"must bear on the lower bearing's face, clear of the shaft ({d_in:.6g} mm) and inside its "
                          f"outer diameter ({ibod:.6g} mm)", f"({d_in + d:.6g}, {ibod - d:.6g}) mm")
    rate = layout.drive_report["stiffness"]["spring_axial_N_per_mm"]
    coils = float(spring_rate(parts["spring_shear_modulus_GPa"] * 1e3, d, mean, 1.0)) / rate
    floor = bottom[1] - ibw - parts["spring_installed_length"]
    length = in_bearings[0].z - floor
    if not length > d * (coils + 3):  # the swept wire's coils (active + two closed ends) must stay apart
        raise DesignError("parts.spring_installed_length", f"{parts['spring_installed_length']:.6g} mm closes the "
                          f"spring's {coils:.3g} active coils of {d:.6g} mm wire", f"> {d * (coils + 3):.6g} mm")
    return AxialPreloadHardware(shaft_in, shaft_out, shift, bottom, top, (floor, in_bearings[0].z), coils, floor,
                                top[1] + layout.settings["input_stroke"])


__all__ = ["MESHES", "input_bearing_faces", "slide_for_backlash", "turn_for_backlash", "axial_lever", "place_axial_preload",
           "AxialPreloadHardware", "axial_preload_hardware"]
