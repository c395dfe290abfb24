"""The radial-motion preload carriage of a dual-pinion drive (the robot joint, Fig. 10), laid out as
components: motor, the motor drive (a bevel pair, or the design's [stages] on the carriage, or a
planetary stage), the carriage on three blade flexures, two preload springs, shafts, bearings, and
the link as a reference tray with its cover.

Heights: the cluster's large gear from z = 0 (see :mod:`geargen.model.layout`). The carriage (a
plate under the input gear, a post and an arm holding the input's upper bearing, a saddle for the
motor, an end wall the springs push on) hangs on three vertical blades standing on the link's
floor; the motor lies along +x, its bevel pinion driving the bevel gear on the input shaft.
Bearings are rings a ``bearing_clearance`` from the gear faces; the lower ones of clusters and
output stand by their outer rings on bosses of the link floor, relieved under the inner ring and
the shaft end (the upper ones sit in the cover).
"""

from __future__ import annotations

import math
from functools import partial
from typing import Any, Mapping

import numpy as np

from geargen.families.bevel.geometry import back_plane_distance, bevel_core, bevel_pair_geometry
from geargen.core.flexures import spring_total_coils
from geargen.drives.planetary.hardware import planetary_drive
from geargen.drives.rules import Candidate, RuleBroken
from geargen.errors import BuildError, DesignError
from geargen.model import bodies as B
from geargen.drives.dual_pinion.bevel import bevel_drive
from geargen.model.bodies import lowest_x_above
from geargen.model.components import (ComponentSet, Hardware, Toothed, along_x, analytic_body, at, placed_box)
from geargen.drives.dual_pinion.shafts import carriage_arm_top, carriage_shafts
from geargen.model.shafts import bore_of
from geargen.units import MM_PER_IN, length_text, sizes_text


def _rim_clearance(x0: float, x1: float, half: float, boss) -> float:
    """How far the footprint [x0, x1] x [-half, half] keeps from the rim of ``boss`` ``(x, y, diameter,
    ...)`` in plan (negative: it reaches into the boss)."""
    bx, by, d = boss[:3]
    return math.hypot(max(x0 - bx, bx - x1, 0.0), max(abs(by) - half, 0.0)) - d / 2


def _carriage_clear_of_bosses(pieces, bosses, z_floor: float, gap: float, identity) -> None:
    """Refuse a carriage piece that stands in a boss of the link floor: ``pieces`` ``(name, (x0, x1), half
    width about y = 0, bottom z, the Candidate that narrows it)``, ``bosses`` ``(x, y, diameter,
    height above the floor's top z_floor, ...)``; where a boss rises within ``gap`` of a piece's bottom,
    the piece's plan must keep ``gap`` from its rim."""
    unit, k = identity.length_unit, identity.mm_per_unit
    for piece, (x0, x1), half, bottom, narrower in pieces:
        for boss in bosses:
            bx, by, _, height = boss[:4]
            if z_floor + height <= bottom - gap:
                continue  # the boss ends below the piece
            clear = _rim_clearance(x0, x1, half, boss)
            if clear < gap:
                raise RuleBroken(narrower.key(unit), f"the carriage's {piece} stands in the boss at x {bx / k:.5g}, "
                                 f"y {by / k:.5g} {unit} on the link floor (clearance {clear / k:.4g} {unit}, at "
                                 f"least {gap / k:.4g} needed)", None, "carriage_clear_of_bosses", clear - gap,
                                 (narrower,))


def _blades_clear_of_link(xs, fl, room: float, bosses, gap: float, identity) -> None:
    """Refuse blades whose feet run into the link: each blade's footprint on the floor (``fl.thickness``
    along x, ``fl.width`` along y, centred on y = 0 at ``xs``) must lie within ``room`` of the link's
    axis (|y| over its straight part, x >= 0; the distance from the joint axis over its round end)
    and ``gap`` clear of every boss ``(x, y, diameter, ...)`` on the floor. The fixes: narrower
    blades; for the walls, a wider link."""
    half = fl.width / 2
    unit, k = identity.length_unit, identity.mm_per_unit

    def refuse(problem: str, margin: float, candidates) -> None:
        raise RuleBroken(candidates[0].key(unit), problem, None, "blades_clear_of_link", margin, candidates)

    narrower = Candidate("width", -1, "narrower blades", section="flexures")
    corners = [(x + side * fl.thickness / 2, half) for x in xs for side in (-1, 1)]
    worst = max(y if x >= 0 else math.hypot(x, y) for x, y in corners)
    if worst > room:
        refuse(f"the blades reach {worst / k:.5g} {unit} from the link's axis, through its walls (room inside "
               f"them, less the clearance: {room / k:.5g} {unit})", room - worst,
               (narrower, Candidate("link_radius", +1, "a wider link")))
    for boss in bosses:
        bx, by = boss[:2]
        for i, x in enumerate(xs, start=1):
            clear = _rim_clearance(x - fl.thickness / 2, x + fl.thickness / 2, half, boss)
            if clear < gap:
                refuse(f"blade {i}'s foot runs into the boss at x {bx / k:.5g}, y {by / k:.5g} {unit} on the link "
                       f"floor (clearance {clear / k:.4g} {unit}, at least {gap / k:.4g} needed)", clear - gap,
                       (narrower,))


def carriage_hardware(layout, s: Mapping[str, Any], stiffness=None) -> Hardware:
    """Motor, bevel pair, carriage on three blade flexures, two preload springs, shafts, bearings,
    and the link as a reference tray, around the gears of the robot joint (Fig. 10).

    Heights: the cluster's large gear from z = 0 (see :mod:`geargen.pipeline`). The carriage (a
    plate under the input gear, a post and an arm holding the input's upper bearing, a saddle
    for the motor, an end wall the springs push on) hangs on three vertical blades standing on
    the link's floor; the motor lies along +x, its bevel pinion driving the bevel gear on the
    input shaft. Bearings are rings a ``bearing_clearance`` from the gear faces; the lower ones
    of clusters and output stand by their outer rings on bosses of the link floor, relieved under
    the inner ring and the shaft end (the upper ones sit in the removed cover, as in the paper's
    figure).
    """
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in descriptions: the design's unit
    identity = layout.identity
    sd = layout.resolved.stiffness
    if sd.flexures is None or sd.springs is None:
        raise DesignError("flexures", "the robot joint's carriage needs [flexures] and [springs]", "both sections")
    fl, sp = sd.flexures, sd.springs
    if sp.installed_length is None:
        raise DesignError("springs.installed_length", "missing (the springs' length in the model)", "a length")
    out = ComponentSet()
    g = {p.name: p for p in layout.gears}
    inp = g["input"]
    # each cluster: one part, or its large and small gear as two parts on one shaft
    members = {side: [p for p in layout.gears if p.group == f"cluster_{side}"] for side in ("a", "b")}
    clusters = [members["a"][0], members["b"][0]]
    gap = s["bearing_clearance"]
    x_in = inp.centre[0]

    # --- shafts and bearings, where the model places them (geargen.model.shafts: the stiffness reads the same)
    placed_shafts = carriage_shafts(layout, s)

    def shaft_with_bearings(sh, group, what, gears, contact):
        part = out.add(sh.name, B.shaft(sh.diameter, sh.length), at(*sh.centre, sh.z_lo), group, "shaft",
                       description=what, shared=True)
        for gear in gears:
            out.join(part, gear, contact)
        for b in sh.bearings:
            ring = out.add(b.name, B.bearing(b.bore, b.outer_diameter, b.width), at(*sh.centre, b.z), group,
                           "bearing", description=size(b.bore, b.outer_diameter, b.width), shared=True)
            out.join(ring, part, "bearing on its shaft", kind="bearing")
        return part

    for side in ("a", "b"):
        sh = placed_shafts[f"cluster_{side}"]
        shaft_with_bearings(sh, f"cluster_{side}", f"d {size(sh.diameter)}", [m.name for m in members[side]],
                            "cluster gear on its shaft (pressed and bonded)")
    shaft_with_bearings(placed_shafts["output"], "output", f"joint shaft d {size(placed_shafts['output'].diameter)}",
                                 ["output"], "shaft in the output gear's bore")
    bw, bod = s["cluster_bearing_width"], s["cluster_bearing_outer_diameter"]
    zb_lo, zb_hi = (b.z for b in placed_shafts["cluster_a"].bearings)
    obw, obod = s["output_bearing_width"], s["output_bearing_outer_diameter"]
    zo_lo, zo_hi = (b.z for b in placed_shafts["output"].bearings)

    stage_list = layout.resolved.stages
    ish = placed_shafts["input"]
    ibod = s["input_bearing_outer_diameter"]
    d_in = bore_of(inp.spec)
    t = s["carriage_plate_thickness"]
    half_w = s["carriage_width"] / 2
    z_plate_top = ish.supports()[0].z  # the lower bearing stands on the base plate
    z_plate_bot = z_plate_top - t
    z_arm_top = carriage_arm_top(ish, s)
    z_arm_bot = z_arm_top - t
    r_in = inp.gears[0].tip_radius
    post_x0 = x_in + max(r_in, ibod / 2) + gap
    post_x1 = post_x0 + t
    arm_half = max(ibod / 2 + gap, d_in)
    spring_r = (sp.mean_coil_diameter + sp.wire_diameter) / 2
    wall_half = s["spring_y_offset"] + spring_r + gap
    holes = []  # through the carriage: (x, y, diameter, z0, z1)
    if stage_list:
        if stage_list[-1].kind == "planetary":
            drive = planetary_drive(out, layout, s, placed_shafts, stage_list[-1], post_x0)
        else:
            drive = _stage_drive(out, layout, s, placed_shafts, stage_list, z_arm_top, post_x0, post_x1)
        pieces = drive["pieces"]
        holes += drive["holes"]
    else:
        drive = _bevel_drive(out, layout, s, ish, x_in, d_in, z_arm_top)
        pieces = [B.box_between((drive["saddle_x0"], -half_w * 0.6, z_plate_top),
                                (drive["x_end"] - gap, half_w * 0.6, drive["z_axis"] - drive["motor_r"]))]
    x_motor_end, z_top_parts = drive["x_end"], drive["z_top"]
    if "motor_mount" not in drive:  # else the drive's own part holds the motor
        out.join("servo_motor", "carriage", "motor on its mount", kind="motor")
    # the input shaft and its bearings (placed by the model), up through the carriage arm to the
    # gear that drives it
    ishaft = out.add("input_shaft", B.shaft(d_in, drive["input_top"] - ish.z_lo), at(x_in, 0, ish.z_lo),
                     "carriage", "shaft", description=f"d {size(d_in)}", shared=True)
    out.join(ishaft, "input", "shaft in the input gear's bore")
    for b in ish.bearings:
        ring = out.add(b.name, B.bearing(b.bore, b.outer_diameter, b.width), at(x_in, 0, b.z), "carriage",
                       "bearing", description=size(b.bore, b.outer_diameter, b.width), shared=True)
        out.join(ring, ishaft, "bearing on its shaft", kind="bearing")

    # --- the carriage, one solid
    x_wall0 = x_motor_end + 2 * gap
    x_wall1 = x_wall0 + t
    z_wall_top = max(z_arm_top, spring_r + gap)
    x_arm1 = max([post_x1] + [p["x_end"] for p in drive.get("arm", ())])
    arm_y = max([arm_half] + [p["half"] for p in drive.get("arm", ())])
    pieces += [
        B.box_between((x_in - arm_half - t, -half_w, z_plate_bot), (x_wall0, half_w, z_plate_top)),  # base plate
        B.box_between((post_x0, -arm_half, z_plate_top), (post_x1, arm_half, z_arm_bot)),  # post
        B.box_between((x_in - arm_half, -arm_y, z_arm_bot), (x_arm1, arm_y, z_arm_top)),  # arm
        B.box_between((x_wall0, -wall_half, z_plate_bot), (x_wall1, wall_half, z_wall_top)),  # spring wall
    ]
    body = B.fuse(pieces, "carriage")
    # through the arm and the base plate under the input shaft: each bearing bears on the carriage by
    # its outer ring only (the hole reaches the ring's middle diameter), the turning shaft runs clear
    relief = max(B.ring_relief(ibod, d_in), d_in + 2 * gap)
    holes += [(x_in, 0.0, relief, z0, z1) for z0, z1 in ((z_arm_bot, z_arm_top), (z_plate_bot, z_plate_top))]
    body = B.single(B.cut(body, *[B.translate(B.cylinder(d, z1 - z0), (x, y, z0)) for x, y, d, z0, z1 in holes]),
                     "carriage")
    carriage = out.add("carriage", body, np.eye(4), "carriage", "carriage",
                       description="carries motor, " + ("stages" if stage_list else "bevel pair")
                                   + " and input gear; rides on the blades")
    for name in ("input_bearing_lower", "input_bearing_upper"):
        out.join(name, carriage, "outer ring held by the carriage", kind="bearing")

    # --- three blade flexures under the carriage, standing on the link floor
    z_floor = z_plate_bot - fl.length
    xs = np.linspace(x_in - arm_half, x_wall0 - 2 * gap, fl.count)
    for i, x in enumerate(xs, start=1):
        b = out.add(f"blade_flexure_{i}", B.blade_flexure(fl.thickness, fl.length, fl.width), at(x, 0, z_floor),
                    "flexures", "flexure", description=f"{size(fl.thickness, fl.width, fl.length)} blade", shared=True)
        out.join(b, carriage, "blade clamped to the carriage", kind="flexure")
        out.join(b, "link", "blade clamped to the link floor", kind="flexure")

    # --- two compression springs between the carriage's wall and the link's end wall
    coils = spring_total_coils(sp.active_coils, sp.end_type)
    tube = B.coil_envelope(sp.wire_diameter, sp.mean_coil_diameter, sp.installed_length)
    if s["spring_model"] == "helix":
        # the wire lies within the tube (its section, normal to the helix, stays within d/2 radially)
        spring_shape, spring_envelope = B.compression_spring(sp.wire_diameter, sp.mean_coil_diameter,
                                                             sp.installed_length, coils,
                                                             ground=sp.end_type.endswith("_ground")), tube
    else:
        spring_shape, spring_envelope = tube, None
    z_spring = (z_plate_bot + z_wall_top) / 2
    for i, y in enumerate((s["spring_y_offset"], -s["spring_y_offset"]), start=1):
        sp_name = out.add(f"preload_spring_{i}", spring_shape, along_x(x_wall1, y, z_spring), "preload", "spring",
                          description=f"d {size(sp.wire_diameter)} wire, D {size(sp.mean_coil_diameter)}, "
                                      f"{coils:g} coils at {size(sp.installed_length)}", envelope=spring_envelope,
                          shared=True)
        out.join(sp_name, carriage, "spring seat on the carriage", kind="spring")
        out.join(sp_name, "link", "spring seat on the link's end wall", kind="spring")

    # --- the link: a tray around everything, bosses under the lower bearings and shafts
    wall, floor = s["link_wall"], s["link_floor"]
    x_end_inner = x_wall1 + sp.installed_length
    length = x_end_inner + wall
    z_top = max(z_top_parts, zo_hi + obw, zb_hi + bw) + s["link_top_clearance"]
    z_bottom = z_floor - floor
    # each boss holds its bearing's outer ring: the relief keeps the inner ring and the rotating
    # shaft end clear of the stationary link
    d_os, d_cs = (placed_shafts[k].diameter for k in ("output", "cluster_a"))
    bosses = [(0.0, 0.0, obod, zo_lo - z_floor, B.ring_relief(obod, d_os))]
    bosses += [(c.centre[0], c.centre[1], bod, zb_lo - z_floor, B.ring_relief(bod, d_cs)) for c in clusters]
    radius = s["link_radius"]
    _blades_clear_of_link(xs, fl, radius - wall - gap, bosses, gap, identity)
    _carriage_clear_of_bosses([("base plate", (x_in - arm_half - t, x_wall0), half_w, z_plate_bot,
                                Candidate("carriage_width", -1, "a narrower base plate")),
                               ("spring wall", (x_wall0, x_wall1), wall_half, z_plate_bot,
                                Candidate("spring_y_offset", -1, "the springs nearer the middle: a narrower wall"))],
                              bosses, z_floor, gap, identity)
    link = B.link_tray(radius, length, z_top - z_bottom, wall, floor, bosses)
    out.ground.append("link")
    out.stationary.append(carriage)
    out.add("link", link, at(0, 0, z_bottom), "link", "reference", "reference",
            "robot link envelope (reference body, covers removed)")
    for name in ("output_bearing_lower", "cluster_bearing_lower_a", "cluster_bearing_lower_b"):
        out.join(name, "link", "outer ring on a boss of the link floor", kind="bearing")
    # --- the cover over the link's round end: seats for the upper bearings' outer rings, its rim on
    # the walls; it stops short of the bevel pinion and motor that rise above it
    uppers = [(placed_shafts[k], placed_shafts[k].supports()[-1]) for k in ("output", "cluster_a", "cluster_b")]
    z_cover = max(b.z + b.width for _, b in uppers)
    # parts the drive lays wholly above the cover (a planetary stage's) may overhang it
    over = set(drive.get("over_cover", ()))
    for c in out.components:
        if c.name in over and not placed_box(analytic_body(c), c.placement)[0][2] >= z_cover + floor:
            raise DesignError(f"stages.{stage_list[-1].name}", f"{c.name} reaches down to the link cover (its top "
                              f"{size(z_cover + floor)})", "a stage that stands clear above the cover")
    rising = [(lowest_x_above(analytic_body(c), c.placement, z_cover), c.name)
              for c in out.components if c.group == "carriage" and c.name not in over]
    x_first, first = min(rising, default=(length + gap, ""))
    x_end = x_first - gap
    reach = max(sh.centre[0] + b.outer_diameter / 2 for sh, b in uppers)
    if not x_end > reach:
        unit = identity.length_unit
        candidates = (Candidate("cluster_bearing_outer_diameter", -1, "smaller cluster bearings"),)
        if stage_list:
            candidates += (Candidate("stage_bearing_outer_diameter", -1, "smaller stage bearings"),)
        else:
            candidates = (Candidate("input_shaft_to_bevel", -1, "the bevel pair lower, less of it above the cover"),
                          Candidate("bevel_face_width", -1, "a narrower bevel pair: its toe further out"),
                          Candidate("motor_shaft_length", +1, "the motor further out")) + candidates
        raise RuleBroken(f"parts.{candidates[0].name}_{unit}",
                         f"{first} rises above the link cover's plane within {(reach - x_end) / identity.mm_per_unit:.4g} "
                         f"{unit} of the upper bearings' seats (x {x_first / identity.mm_per_unit:.5g} {unit}; the seats "
                         f"reach x {reach / identity.mm_per_unit:.5g} {unit}): no room for the cover", None,
                         "link_cover_room", x_end - reach, candidates)
    seats = [(sh.centre[0], sh.centre[1], b.outer_diameter, z_cover - (b.z + b.width),
              B.ring_relief(b.outer_diameter, sh.diameter)) for sh, b in uppers]
    cover = out.add("link_cover", B.link_cover(radius, wall, x_end, floor, seats), at(0, 0, z_cover), "link",
                    "housing", description="link cover over the round end: holds the upper bearings' outer rings")
    out.join(cover, "link", "cover rim on the link's walls")
    out.ground.append(cover)
    for _, b in uppers:
        out.join(cover, b.name, "outer ring in the cover's seat", kind="bearing")
    out.dimensions.update(link=dict(radius=radius, length=length, height=z_top - z_bottom, wall=wall, floor=floor,
                                    bosses=bosses, z_bottom=z_bottom, cover=dict(z=z_cover, x_end=x_end, seats=seats)),
                          carriage=dict(x_min=x_in - arm_half - t, x_max=x_wall1, travel=layout.carriage_travel),
                          blade_x=list(map(float, xs)), spring_total_coils=coils, **drive.get("dims", {}))
    out.notes.append(drive["note"])
    return out.freeze()


def motor_clear_x(gears, z_axis: float, body_diameter: float, flange: float, gap: float) -> float:
    """The least x (mm) of a motor lying along +x on the axis (y = 0, z = ``z_axis``) for which
    neither its round body nor its square flange reaches any of the placed ``gears`` (their tip
    circles over their faces), a ``gap`` clear: for each gear, the furthest x of its tip circle within
    the band of y the motor's section covers at the gear's nearest height."""
    x = -math.inf
    for placed in gears:
        for gear in placed.gears:
            if not hasattr(gear, "tip_radius"):
                continue
            z0, z1 = placed.face_z(gear)
            cx, cy = placed.centre
            h = 0.0 if z0 <= z_axis <= z1 else min(abs(z0 - z_axis), abs(z1 - z_axis))
            bands = []
            if h < body_diameter / 2 + gap:
                bands.append(math.sqrt(max((body_diameter / 2 + gap) ** 2 - h * h, 0.0)))
            if h < flange / 2 + gap:
                bands.append(flange / 2 + gap)
            if not bands:
                continue
            band, rt = max(bands), gear.tip_radius
            off = abs(cy) - band
            if off <= 0:
                x = max(x, cx + rt + gap)
            elif off < rt:
                x = max(x, cx + math.sqrt(rt * rt - off * off) + gap)
    return x


def _bevel_drive(out: ComponentSet, layout, s: Mapping[str, Any], ish, x_in: float, d_in: float,
                 z_arm_top: float) -> dict[str, Any]:
    """The motor lying along +x on the carriage, driving the input shaft through a toothed bevel
    pair (the robot joint, Fig. 10): the bevel gear's heel (pitch circle) ``input_shaft_to_bevel``
    above the input's mid-face (the placed input shaft's load), the two apexes at the pitch cones'
    common apex, the motor's stub ending on the pinion's back face. The pinion's teeth sit in the
    middle of the gear's spaces (the pair's backlash split to both sides); the pair is a mesh,
    checked on the exact outlines (:func:`geargen.drives.dual_pinion.bevel_verdict.check_placed_bevel_pair`)."""
    placed = bevel_drive(layout, dict(s))
    gear_spec, pinion_spec = placed.gear, placed.pinion
    module = s["bevel_module"] or 25.4 / s["bevel_diametral_pitch_per_in"]
    bev = bevel_pair_geometry(s["bevel_pinion_teeth"], s["bevel_gear_teeth"], module, s["bevel_face_width"])
    gap = s["bearing_clearance"]
    z_heel = ish.loads["bevel_gear"]
    z_apex = z_heel + bev.apex_height("gear")
    apex = (x_in, 0.0, z_apex)
    # one home: the toothed gears' cones and apex are the pitch-cone model's
    for spec, which in ((gear_spec, "gear"), (pinion_spec, "pinion")):
        radius, cone = bev._cone(which)
        if abs(spec.pitch_cone_angle - cone) > 1e-12 or abs(spec.reference_diameter / 2 - radius) > 1e-9 \
                or abs(spec.cone_distance - bev.cone_distance) > 1e-9:
            raise BuildError(f"{spec.name}: its cones differ from the bevel pair's pitch cones")
    if not np.allclose(placed.apex, apex, rtol=0, atol=1e-9) or abs(placed.z_heel - z_heel) > 1e-9:
        raise BuildError("bevel pair: the placed apex is not the pitch cones' apex")
    if not math.isclose(gear_spec.bore_diameter, d_in):
        raise BuildError("bevel gear: its bore is not the input shaft")
    # the gear's back face (its heel root circle's plane) must clear the carriage arm under it
    lowest = z_arm_top + gap + (back_plane_distance(gear_spec) - bev.apex_height("gear"))
    if z_heel < lowest - 1e-9:
        unit = layout.identity.length_unit
        shift = (lowest - z_heel) / layout.identity.mm_per_unit
        raise RuleBroken(f"parts.input_shaft_to_bevel_{unit}", f"puts the bevel gear's back (its heel root circle) "
                         f"{shift:.4g} {unit} into the carriage arm under it", None, "bevel_above_arm",
                         z_heel - lowest, (Candidate("input_shaft_to_bevel", +1, "the bevel pair higher"),
                                           Candidate("carriage_plate_thickness", -1, "a thinner carriage arm")))
    gear_matrix, pinion_matrix = placed.gear_matrix, placed.pinion_matrix
    bevel_gear = out.add("bevel_gear", None, gear_matrix, "carriage", "bevel", toothed=Toothed(gear_spec, gear_spec.back),
                         description=f"bevel gear {bev.gear_teeth} T, pitch cone {math.degrees(bev.pitch_angle_gear):.4g} deg, "
                                     f"spherical involute")
    pinion = out.add("bevel_pinion", None, pinion_matrix, "carriage", "bevel", toothed=Toothed(pinion_spec, pinion_spec.back),
                     description=f"bevel pinion {bev.pinion_teeth} T, pitch cone {math.degrees(bev.pitch_angle_pinion):.4g} deg, "
                                 f"spherical involute")
    out.join(bevel_gear, pinion, "meshing bevel gears: checked by the bevel mesh checker", kind="mesh")
    out.join("input_shaft", bevel_gear, "shaft in the bevel gear's bore")
    out.rotating += [bevel_gear, pinion]
    # motor along +x, its stub ending on the pinion's back face; its flange beyond every gear its
    # body would otherwise reach (a default stub is made that long; a given one is the designer's,
    # and the parts check names the length that clears)
    x_pinion_back = x_in + back_plane_distance(pinion_spec)
    clear = motor_clear_x(layout.gears, z_apex, s["motor_body_diameter"], s["motor_flange"], gap)
    stub_clear = clear - x_pinion_back
    stub = s["motor_shaft_length"]
    unit = layout.identity.length_unit
    key = f"parts.motor_shaft_length_{unit}"
    if stub < stub_clear:
        # the defaults' step: 0.5 mm, or 1/32 in
        step = 0.5 if unit == "mm" else MM_PER_IN / 32
        stub_clear = math.ceil(stub_clear / step - 1e-9) * step
        if key in {d.key for d in layout.identity.defaulted}:
            out.defaults.append((key, stub_clear, "the stub that puts the motor's flange beyond the gears its body "
                                                  "would reach"))
            stub = stub_clear
        else:
            out.fixes["servo_motor"] = (key, stub_clear, "puts the motor's flange beyond the gears")
    x_flange = x_pinion_back + stub
    motor_r = s["motor_body_diameter"] / 2
    motor = out.add("servo_motor", B.servo_motor(s["motor_body_diameter"], s["motor_body_length"], s["motor_flange"],
                                                 s["motor_flange_thickness"], s["motor_shaft_diameter"], stub),
                    along_x(x_flange, 0, z_apex), "carriage", "motor", description="servo motor with encoder (envelope)")
    out.join(motor, pinion, "motor shaft stub on the bevel pinion", kind="motor")
    x_end = x_flange + s["motor_flange_thickness"] + s["motor_body_length"]
    # the input shaft fills the gear's bore from its lower end (the toe, or the web's face)
    input_top = z_apex - bevel_core(gear_spec, gear_spec.back).bore_z[0]
    return dict(x_end=x_end, z_axis=z_apex, motor_r=motor_r, z_top=z_apex + motor_r,
                saddle_x0=x_flange + s["motor_flange_thickness"] + gap, input_top=input_top,
                dims=dict(bevel=bev, bevel_apex=apex),
                note=f"bevel pair {bev.pinion_teeth}:{bev.gear_teeth} (ratio {bev.ratio:.4g}), spherical-involute "
                     f"teeth, thinning {length_text(gear_spec.thinning, unit)} each; "
                     f"motor to output ratio {bev.ratio * layout.ratio['train']:.6g}")


def _stage_drive(out: ComponentSet, layout, s: Mapping[str, Any], placed_shafts, stage_list, z_arm_top: float,
                 post_x0: float, post_x1: float) -> dict[str, Any]:
    """The motor standing on the carriage's bridge, driving the input through the design's
    [stages]: each stage shaft between a lower bearing standing on the carriage arm (extended
    under it) and an upper one under the bridge; two side columns on the base plate carry the
    bridge clear of every stage gear; the first driver sits on the motor's shaft, which comes
    down through the bridge."""
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in descriptions: the design's unit
    gap, t = s["bearing_clearance"], s["carriage_plate_thickness"]
    g = {p.name: p for p in layout.gears}
    shafts = [placed_shafts[k] for k in sorted(k for k in placed_shafts if k.startswith("stage_"))]
    sob, sbw = s["stage_bearing_outer_diameter"], s["stage_bearing_width"]
    for sh in shafts:
        part = out.add(sh.name, B.shaft(sh.diameter, sh.length), at(*sh.centre, sh.z_lo), "carriage",
                       "shaft", description=f"stage shaft d {size(sh.diameter)}", shared=True)
        for gear in sh.loads:
            out.join(part, gear, "stage gear on its shaft")
        for b in sh.bearings:
            ring = out.add(b.name, B.bearing(b.bore, b.outer_diameter, b.width), at(*sh.centre, b.z),
                           "carriage", "bearing", description=size(b.bore, b.outer_diameter, b.width), shared=True)
            out.join(ring, part, "bearing on its shaft", kind="bearing")
            out.join(ring, "carriage", "outer ring seated on the carriage", kind="bearing")
    out.join("input_shaft", stage_list[-1].driven, "shaft in the driving stage gear's bore")
    # the motor on the bridge, its shaft down through it into the first driver's bore
    first = g[stage_list[0].driver]
    d_motor = bore_of(first.spec)
    if not d_motor > 0:
        raise DesignError(f"gears.{first.name}.bore_diameter", "missing: the gear sits on the motor shaft", "> 0")
    gears_top = max(g[n].height[1] for st in stage_list for n in (st.driver, st.driven))
    z_bridge0 = gears_top + gap + sbw
    z_bridge1 = z_bridge0 + t
    stub = z_bridge1 - first.height[0]
    motor = out.add("servo_motor", B.servo_motor(s["motor_body_diameter"], s["motor_body_length"], s["motor_flange"],
                                                 s["motor_flange_thickness"], d_motor, stub),
                    at(*first.centre, z_bridge1), "carriage", "motor",
                    description="servo motor with encoder (envelope), standing on the carriage's bridge")
    out.join(motor, first.name, "first stage driver on the motor shaft", kind="motor")
    # the stage gears' reach: the columns stand outside it, the bridge and arm reach the shafts
    stage_gears = [g[n] for st in stage_list for n in (st.driver, st.driven)]
    reach_y = max(abs(p.centre[1]) + p.gears[0].tip_radius for p in stage_gears)
    y_col = reach_y + gap
    xs = [sh.centre[0] for sh in shafts] + [first.centre[0]]
    r_seat = max(sob, s["motor_flange"]) / 2 + gap
    # the columns rise beside the stage gears from the base plate, past the loop's gears (beyond
    # their tips along +x)
    x_col = max([post_x0] + [p.centre[0] + p.gears[0].tip_radius + gap for p in layout.gears
                             if p.group.startswith("cluster_") or p.group == "output"])
    x_b0, x_b1 = min(min(xs) - r_seat, x_col), max(xs) + r_seat
    half = y_col + t
    pieces = [B.box_between((x_b0, -half, z_bridge0), (x_b1, half, z_bridge1))]  # bridge
    z_plate_top = placed_shafts["input"].supports()[0].z
    for sign in (1, -1):
        y0, y1 = sorted((sign * y_col, sign * half))
        pieces.append(B.box_between((x_col, y0, z_plate_top - t), (x_col + t, y1, z_bridge0)))
    # the base plate reaches out under the columns only (the loop's bearing bosses stand beside it)
    pieces.append(B.box_between((x_col, -half, z_plate_top - t), (x_col + t, half, z_plate_top)))
    holes = [(sh.centre[0], sh.centre[1], B.ring_relief(sob, sh.diameter), z_arm_top - t, z_arm_top) for sh in shafts]
    holes += [(sh.centre[0], sh.centre[1], B.ring_relief(sob, sh.diameter), z_bridge0, z_bridge1) for sh in shafts]
    holes.append((first.centre[0], first.centre[1], d_motor + 2 * gap, z_bridge0, z_bridge1))
    arm = [dict(x_end=max(sh.centre[0] for sh in shafts) + sob / 2 + gap if shafts else post_x1,
                half=max([abs(sh.centre[1]) + sob / 2 + gap for sh in shafts], default=0.0))]
    ratio = layout.ratio
    return dict(pieces=pieces, holes=holes, arm=arm, x_end=x_b1, z_top=z_bridge1,
                input_top=g[stage_list[-1].driven].height[1],
                note=f"{len(stage_list)} stage(s) before the input on the carriage ({ratio['text']})")
