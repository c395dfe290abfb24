"""The machine-tool C-axis hardware (Fig. 12), laid out as components: spindle stub, the long
beam-spring pinion with its shaft, bearings, coupling, gearhead and motor, and per dual pinion:
its shaft, two bearings in a sliding quill, the frictional preload interface (a locking ring
clamping the large gear to the shaft), a locknut on the bearings' inner rings, and the engaged
and retracted travel stops that meet the quill's lug; the housing block the quills slide in (the
ground), and the drive column bolted to it that carries the long pinion's bearing plates and the
motor plate.
"""

from __future__ import annotations

import math
from functools import partial
from typing import Any, Mapping

import numpy as np

from geargen.errors import DesignError
from geargen.model import bodies as B
from geargen.model.components import ComponentSet, Hardware, at, placed_box, transform
from geargen.drives.beam_pinion.shafts import beam_pinion_shafts, housing_heights
from geargen.model.shafts import bore_of
from geargen.units import sizes_text, small_length_text


def beam_pinion_hardware(layout, s: Mapping[str, Any], stiffness) -> Hardware:
    """Spindle stub, the long beam-spring pinion with its shaft, bearings, coupling, gearhead and
    motor, and per dual pinion: its shaft, two bearings in a sliding quill, the frictional preload
    interface (a locking ring clamping the large gear to the shaft), a locknut on the bearings'
    inner rings, and the engaged and retracted travel stops that meet the quill's lug; the
    housing block the quills slide in (the ground), and the drive column bolted to it that
    carries the long pinion's bearing plates and the motor plate.

    Heights: the pinions engage the bull gear moving along +z and slide out along -z, away from
    it (the large gears stay in mesh with the long pinion). The long pinion's bearings are
    symmetric about its engaged mesh (zero slope there) at the span the beam-spring helper
    sized (``StiffnessSummary.beam``); the stops come from the engagement helper (lead and
    strokes, ``StiffnessSummary.engagement``). The housing block's top is a clearance below the
    lowest a large gear comes (the trailer retracted); the quills reach down through it to their
    lugs, which play between the stops under it.
    """
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in descriptions: the design's unit
    summary = stiffness()
    beam = summary.beam
    eng = layout.engagement if layout.engagement is not None else summary.engagement
    if beam is None or eng is None:
        raise DesignError("beam_pinion", "the C-axis needs [beam_pinion] (the long pinion) and [engagement]",
                          "both sections")
    out = ComponentSet()
    g = {p.name: p for p in layout.gears}
    inp, bull = g["input"], g["output"]
    gap = s["bearing_clearance"]
    x_in = inp.centre[0]

    # --- spindle stub through the bull gear
    z_b0, z_b1 = bull.height
    d_sp = bore_of(bull.spec)
    sp_len = s["spindle_length"]
    spindle = out.add("spindle", B.shaft(d_sp, sp_len), at(0, 0, (z_b0 + z_b1 - sp_len) / 2), "spindle",
                      "reference", "reference", f"lathe spindle (reference), d {size(d_sp)}", shared=True)
    out.join(spindle, "output", "bull gear on the spindle")
    out.ground.append(spindle)  # turns in the machine's own spindle bearings, outside the model
    out.rotating.append(spindle)

    # --- the long pinion: bearings at the beam span, symmetric about the engaged mesh
    span = beam.span
    d_ish = s["input_shaft_diameter"]
    if not math.isclose(d_ish, bore_of(inp.spec)):
        raise DesignError("parts.input_shaft_diameter_mm", "must equal the long pinion's bore", size(bore_of(inp.spec), digits=6))
    ibw, ibod = s["input_bearing_width"], s["input_bearing_outer_diameter"]
    placed_shafts = beam_pinion_shafts(layout, s)
    placed_input = placed_shafts["input"]
    z_mesh = placed_input.loads["input"]
    cl = s["coupling_length"]
    ish_lo, ish_hi = placed_input.z_lo, placed_input.z_hi
    ishaft = out.add("input_shaft", B.shaft(d_ish, ish_hi - ish_lo), at(x_in, 0, ish_lo), "drive", "shaft",
                     description=f"long pinion's shaft d {size(d_ish)}, bearing span {size(span)} (beam spring)", shared=True)
    out.join(ishaft, "input", "pinion teeth on their shaft")
    input_bearings = []
    for bearing in placed_input.supports():
        b = out.add(bearing.name, B.bearing(d_ish, ibod, ibw), at(x_in, 0, bearing.z), "drive", "bearing",
                    description=f"{size(d_ish, ibod, ibw)}, simple support of the beam at "
                                f"z = {size(bearing.centre_z, digits=5)}", shared=True)
        out.join(b, ishaft, "bearing on its shaft", kind="bearing")
        input_bearings.append((b, bearing.z))
    z_lo_bearing = placed_input.supports()[0].z
    # coupling (half on the shaft), gearhead (the exact upstream ratio), motor with the encoder
    zc = ish_hi - cl / 2
    coupling = out.add("coupling", B.cylinder(s["coupling_diameter"], cl, d_ish), at(x_in, 0, zc), "drive", "shaft",
                       description="shaft coupling (bored for the pinion shaft, which fills half its length)")
    out.join(coupling, ishaft, "coupling on the pinion shaft")
    zg = zc + cl
    stages = " x ".join(f"{b}:{a}" for a, b in layout.settings.get("upstream_stages", ()))
    gearhead = out.add("gearhead", B.cylinder(s["gearhead_diameter"], s["gearhead_length"]), at(x_in, 0, zg), "drive",
                       "motor", description=f"planetary gearhead {stages}")
    out.join(gearhead, coupling, "gearhead output in the coupling", kind="motor")
    # gearhead and motor both bolt to the motor plate, from below and above; the motor's shaft reaches
    # through the plate into the gearhead's input. Each is a joint between the plate (its housing) and
    # what it turns: the gearhead the coupling, the motor the gearhead's input
    z_plate = zg + s["gearhead_length"]
    t_plate = s["motor_plate_thickness"]
    d_stub = d_ish * 0.5
    motor = out.add("servo_motor", B.servo_motor(s["motor_body_diameter"], s["motor_body_length"], s["motor_flange"],
                                                 s["motor_flange_thickness"], d_stub, t_plate),
                    at(x_in, 0, z_plate + t_plate), "drive", "motor", description="servo motor with the C-axis encoder")
    out.join(motor, gearhead, "motor shaft in the gearhead's input", kind="motor")

    # --- the housing block's heights: its top a clearance below the lowest a large gear comes (the
    # trailer retracted), its thickness the length of the bores the quills slide in
    clusters = {side: (g[f"cluster_small_{side}"], g[f"cluster_large_{side}"],
                       layout.axial_shift.get(f"cluster_{side}", 0.0)) for side in ("a", "b")}
    z_block, z_block_top = housing_heights(layout, s, eng)
    strokes = {"a": -eng.leader_retracted_stop, "b": -eng.trailer_retracted_stop}

    # --- each dual pinion: shaft, bearings, quill, stops
    d_cs = s["cluster_shaft_diameter"]
    d_quill = s["quill_outer_diameter"]
    lug, lug_w, lug_t, block = s["stop_lug_length"], s["stop_lug_width"], s["stop_lug_thickness"], s["stop_block_size"]
    hole = max(ibod, 2 * inp.gears[0].tip_radius) + 2 * gap  # the long pinion (and its bearing) pass the block
    for small, _, _ in clusters.values():
        wall = math.hypot(small.centre[0] - x_in, small.centre[1]) - (d_quill + hole) / 2
        if not wall > 0:
            raise DesignError("parts.quill_outer_diameter_mm", f"{size(d_quill, digits=6)}: the quill's bore in the housing "
                              f"block runs {size(-wall)} into the hole the long pinion passes",
                              f"< {size(d_quill + 2 * wall, digits=6)}")
    quills = []
    for side, (small, large, shift) in clusters.items():
        for part in (small, large):
            if not math.isclose(bore_of(part.spec), d_cs):
                raise DesignError("parts.cluster_shaft_diameter_mm", f"must equal the bore of {part.name}",
                                  size(bore_of(part.spec), digits=6))
        x, y = small.centre
        zl1 = large.height[1]
        ring_w = s["friction_ring_width"]
        ring = out.add(f"friction_ring_{side}", B.cylinder(s["friction_ring_outer_diameter"], ring_w, d_cs),
                       at(x, y, zl1), f"cluster_{side}", "friction",
                       description="frictional preload interface: locking ring clamping the large gear to the "
                                   "pinion shaft (released, turned to wind the loop, clamped)")
        out.join(ring, large.name, "frictional interface on the large gear")
        # shaft and quill bearings where the model places them (the stiffness reads the same)
        sh = placed_shafts[f"cluster_{side}"]
        shaft = out.add(sh.name, B.shaft(sh.diameter, sh.length), at(x, y, sh.z_lo), f"cluster_{side}",
                        "shaft", description=f"dual pinion shaft d {size(sh.diameter)} (slides with the pinion)", shared=True)
        for part in (small.name, large.name, ring):
            out.join(shaft, part, "on the pinion shaft")
        for b in sh.bearings:
            ring_b = out.add(b.name, B.bearing(b.bore, b.outer_diameter, b.width), at(x, y, b.z),
                             f"cluster_{side}", "bearing",
                             description=f"{size(b.bore, b.outer_diameter, b.width)} in the sliding quill", shared=True)
            out.join(ring_b, shaft, "bearing on its shaft", kind="bearing")
        lower, upper = sh.supports()
        nut = out.add(f"locknut_{side}", B.cylinder(s["locknut_outer_diameter"], s["locknut_width"], d_cs),
                      at(x, y, sh.z_lo), f"cluster_{side}", "shaft",
                      description="locknut clamping the bearings' inner rings to the shaft", shared=True)
        out.join(nut, shaft, "locknut on the shaft")
        out.join(nut, lower.name, "locknut against the lower bearing's inner ring")
        # The quill holds both outer rings (a shoulder between them, the shaft and inner rings clear
        # by the ring relief) and slides in the housing block without turning. The travel stops act
        # on a lug of the quill: stop and lug are both stationary in rotation, so the stops need no
        # thrust bearing (a lug on the turning shaft would rub on them at speed, or need a collar and
        # a thrust bearing to hold the quill); the angular-contact pair already carries the axial
        # force between shaft and quill.
        z_top = upper.z + upper.width
        z_lug_engaged = z_block - block - lug_t  # the lug's lower face, engaged: its top on the engaged stop
        z_bottom = z_lug_engaged + shift
        relief = B.ring_relief(lower.outer_diameter, d_cs)
        steps = [(0.0, lower.z + lower.width - z_bottom, lower.outer_diameter),
                 (lower.z + lower.width - z_bottom, upper.z - z_bottom, relief),
                 (upper.z - z_bottom, z_top - z_bottom, upper.outer_diameter)]
        # the lug points away from the long pinion: its stops stay clear of the drive line
        direction = math.atan2(y, x - x_in)
        quill = out.add(f"quill_{side}", B.quill(d_quill, z_top - z_bottom, [st for st in steps if st[1] > st[0]], lug,
                                                 lug_w, lug_t),
                        transform((x, y, z_bottom), (0, 0, 1), direction), f"cluster_{side}", "quill",
                        description=f"quill {size(d_quill)}, {size(z_top - z_bottom)} long: holds both bearings' "
                                    "outer rings, slides in the housing block, its lug between the travel stops")
        for b in (lower, upper):
            out.join(quill, b.name, "outer ring seated in the quill", kind="bearing")
        out.join(quill, "housing", "quill in the housing block's bore (a sliding fit; the quill does not turn)", kind="sliding")
        out.stationary.append(quill)
        quills.append((x, y))
        out.dimensions.setdefault("quills", {})[side] = dict(z=(z_bottom, z_top), steps=steps, direction=direction)
        # the stops, in the quill's frame at the engaged position: the engaged stop a block under the
        # housing over the lug's end; the retracted stop a foot under the lug on a column just beyond
        # the lug's end, up to the housing
        place = transform((x, y, 0.0), (0, 0, 1), direction)
        x_end = d_quill / 2 + lug
        engaged_stop = out.add(f"travel_stop_engaged_{side}",
                     B.box_between((x_end - block, -block / 2, z_block - block), (x_end, block / 2, z_block)),
                     place, "housing", "stop", description="engaged travel stop under the housing block: the "
                                                           "pinion fully in mesh")
        z_foot = z_lug_engaged - strokes[side]
        foot_and_column = B.fuse([B.box_between((x_end - block, -block / 2, z_foot - block),
                                                (x_end + gap + block, block / 2, z_foot)),
                                  B.box_between((x_end + gap, -block / 2, z_foot), (x_end + gap + block, block / 2, z_block))],
                                 "retracted stop")
        retracted_stop = out.add(f"travel_stop_retracted_{side}", foot_and_column, place, "housing", "stop",
                     description=f"retracted travel stop, stroke {size(strokes[side])}"
                                 + (f" (the trailing pinion: {size(eng.lead)} lead further)" if side == "b" else ""))
        out.join(quill, engaged_stop if shift == 0 else retracted_stop, "the quill's lug against its travel stop")
        out.join(engaged_stop, "housing", "stop bolted under the housing block")
        out.join(retracted_stop, "housing", "stop's column bolted under the housing block")
        out.stationary += [engaged_stop, retracted_stop]

    # --- the drive column beside the long pinion, a clearance beyond the drive line and the large gears
    width, thick = s["drive_column_width"], s["drive_column_thickness"]
    margin = s["housing_margin"]
    reach = max(s["coupling_diameter"], s["gearhead_diameter"], ibod, 2 * inp.gears[0].tip_radius) / 2 + gap
    large_reach = max(large.centre[0] + large.gears[0].tip_radius for _, large, _ in clusters.values()) + gap
    x_col = max(x_in + width / 2, x_in + hole / 2 + margin, x_in + reach, large_reach)
    column = out.add("drive_column", B.box_between((x_col, -width / 2, z_lo_bearing), (x_col + thick, width / 2, z_plate)),
                     np.eye(4), "housing", "housing",
                     description="column bolted to the housing block: carries the long pinion's bearing plates and "
                                 "the motor plate")
    out.join(column, "housing", "column bolted to the housing block's end")
    # the long pinion's bearings seated in plates on the column (each as thick as its bearing)
    for b, z in input_bearings:
        plate = out.add(f"{b}_plate", B.plate_with_holes(x_col - (x_in - width / 2), width, ibw, [(x_in, 0.0, ibod)],
                                                         corner=(x_in - width / 2, -width / 2, z)),
                        np.eye(4), "housing", "housing", description="bearing plate on the drive column")
        out.join(plate, b, "outer ring seated in the plate", kind="bearing")
        out.join(plate, column, "plate bolted to the column")
        out.stationary.append(plate)
    flange = max(width, s["motor_flange"], s["gearhead_diameter"])
    x_plate1 = max(x_col + thick, x_in + flange / 2)
    mplate = out.add("motor_plate", B.plate_with_holes(x_plate1 - (x_in - flange / 2), flange, t_plate,
                                                       [(x_in, 0.0, d_stub + 2 * gap)],
                                                       corner=(x_in - flange / 2, -flange / 2, z_plate)),
                     np.eye(4), "housing", "housing", description="motor plate on the drive column: the gearhead hangs "
                                                                  "under it, the motor stands on it")
    out.join(mplate, column, "plate on the column's top")
    out.join(gearhead, mplate, "gearhead housing bolted under the motor plate")
    out.join(motor, mplate, "motor flange bolted on the motor plate", kind="motor")
    out.stationary += [column, mplate]

    # --- the housing block: the quills' bores, the long pinion's hole, over the stops; it ends at the column
    holes = [(x, y, d_quill) for x, y in quills] + [(x_in, 0.0, hole)]
    boxes = [((hx - hd / 2, hy - hd / 2), (hx + hd / 2, hy + hd / 2)) for hx, hy, hd in holes]
    boxes += [placed_box(c.body, c.placement) for c in out.components if c.kind == "stop"]
    lo = (float(min(b[0][0] for b in boxes)) - margin, float(min(b[0][1] for b in boxes)) - margin, z_block)
    hi = (x_col, float(max(b[1][1] for b in boxes)) + margin, z_block_top)
    housing = B.plate_with_holes(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], holes, corner=lo)
    out.ground.append("housing")
    out.add("housing", housing, np.eye(4), "housing", "housing",
            description="C-axis housing block, bolted to the headstock: the quills slide in its bores, the stops hang under it")
    out.dimensions.update(beam=beam, engagement=eng, z_mesh=z_mesh, housing=dict(lo=lo, hi=hi),
                    drive_column=dict(x=x_col, width=width, thickness=thick, z=(z_lo_bearing, z_plate)))
    out.notes.append(f"long pinion: bearing span {size(span)} symmetric about the engaged mesh at z = {size(z_mesh)} "
                     f"(zero slope there), beam stiffness {layout.identity.text_units.text('linear_stiffness', beam.stiffness)}; static deflection at the preload "
                     f"{small_length_text(beam.deflection, layout.identity.length_unit, 3)} (the model shows the straight beam)")
    out.notes.append(f"axial engagement: lead {size(eng.lead)} between the pinions, strokes "
                     f"{-eng.leader_retracted_stop:.4g} / {size(-eng.trailer_retracted_stop)}, relative rotation "
                     f"{eng.relative_rotation * 1e3:.3g} mrad")
    return out.freeze()
