"""The split pinion's hardware (Fig. 8), laid out as components: the stiff pinion on a hollow shaft
(outer path), the compliant pinion on the inner shaft that runs through it from the clamp collar
(the frictional interface where preload is set) to an outboard bearing, a preloaded bearing pair
on the hollow shaft, the output shaft and bearings, and the housing's two plates that hold every
bearing.

Shafts and bearings stand where :func:`geargen.drives.split_pinion.shafts.split_pinion_shafts` places them:
the stiffness model reads the same shafts (the inner shaft's torsion, each pinion's support).
"""

from __future__ import annotations

from functools import partial
from typing import Any, Mapping

from geargen.errors import DesignError
from geargen.model import bodies as B
from geargen.model.components import ComponentSet, Hardware, at
from geargen.drives.split_pinion.shafts import split_pinion_shafts
from geargen.model.shafts import bore_of
from geargen.units import sizes_text


def split_pinion_hardware(layout, s: Mapping[str, Any], stiffness=None) -> Hardware:
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in descriptions: the design's unit
    out = ComponentSet()
    g = {p.name: p for p in layout.gears}
    st = layout.settings
    stiff, compl, outg = g[st["pinion_stiff"]], g[st["pinion_compliant"]], g[st["output"]]
    gap = s["bearing_clearance"]
    if not bore_of(stiff.spec) == s["hollow_shaft_outer_diameter"]:
        raise DesignError("parts.hollow_shaft_outer_diameter", "must equal the stiff pinion's bore",
                          size(bore_of(stiff.spec), digits=6))
    placed = split_pinion_shafts(layout, s)
    hollow, inner = placed["hollow"], placed["inner"]
    x_p = hollow.centre[0]
    hollow_part = out.add("hollow_shaft", B.shaft(hollow.diameter, hollow.length, hollow.bore),
                          at(x_p, 0, hollow.z_lo), "split_pinion", "shaft", shared=True,
                          description=f"outer (stiff) path: hollow shaft {size(hollow.diameter, hollow.bore, sep='/')}")
    out.join(hollow_part, stiff.name, "stiff pinion on the hollow shaft")
    for b in hollow.bearings:
        name = out.add(b.name, B.bearing(b.bore, b.outer_diameter, b.width), at(x_p, 0, b.z), "split_pinion",
                       "bearing", shared=True, description="angular-contact pair (preloaded), "
                                                           + size(b.bore, b.outer_diameter, b.width))
        out.join(name, hollow_part, "bearing on the hollow shaft", kind="bearing")
    collar, outboard = inner.supports()
    collar_part = out.add(collar.name, B.split_collar(collar.bore, collar.outer_diameter, collar.width,
                                                      s["collar_slot"]),
                          at(x_p, 0, collar.z), "split_pinion", "friction",
                          description="frictional interface: clamp collar joining the inner shaft to the hollow shaft; "
                                      "set screws wind the inner shaft before clamping")
    out.join(collar_part, hollow_part, "collar against the hollow shaft's end")
    inner_part = out.add("inner_shaft", B.shaft(inner.diameter, inner.length), at(x_p, 0, inner.z_lo),
                         "split_pinion", "shaft", shared=True,
                         description=f"inner (compliant) path: d {size(inner.diameter)}, twisting over "
                                     f"{size(inner.twist_length)}, collar to compliant pinion")
    out.join(inner_part, collar_part, "clamped in the collar")
    out.join(inner_part, compl.name, "compliant pinion on the inner shaft")
    top = out.add(outboard.name, B.bearing(outboard.bore, outboard.outer_diameter, outboard.width),
                  at(x_p, 0, outboard.z), "split_pinion", "bearing", shared=True,
                  description="outboard bearing of the compliant pinion, "
                              + size(outboard.bore, outboard.outer_diameter, outboard.width))
    out.join(top, inner_part, "bearing on the inner shaft", kind="bearing")
    out.dimensions["inner_shaft"] = dict(diameter=inner.diameter, twist_length=inner.twist_length)
    # output shaft and bearings: the lower one level with the pinion pair's upper bearing, the upper
    # one level with the outboard bearing, so that one plate holds each level
    d_os = bore_of(outg.spec)
    obw, obod = s["output_bearing_width"], s["output_bearing_outer_diameter"]
    zo0, zo1 = outg.height
    z_low, z_high = zo0 - gap - obw, max(zo1 + gap, outboard.z)
    oshaft = out.add("output_shaft", B.shaft(d_os, z_high + obw - z_low), at(0, 0, z_low), "output", "shaft",
                     shared=True, description=f"d {size(d_os)}")
    out.join(oshaft, outg.name, "output gear on its shaft")
    output_bearings = {}
    for where, z in (("lower", z_low), ("upper", z_high)):
        output_bearings[where] = out.add(f"output_bearing_{where}", B.bearing(d_os, obod, obw), at(0, 0, z), "output",
                                         "bearing", shared=True, description=size(d_os, obod, obw))
        out.join(output_bearings[where], oshaft, "bearing on its shaft", kind="bearing")
    # the housing: a bottom plate holding the pinion pair and the lower output bearing, a top plate
    # holding the outboard and the upper output bearing (both fixed to the machine: the ground)
    margin = s["housing_margin"]
    lo_pair = min(b.z for b in hollow.bearings)
    hi_pair = max(b.z + b.width for b in hollow.bearings)
    pair_od = max(b.outer_diameter for b in hollow.bearings)
    plates = (("bottom_plate", lo_pair, hi_pair - lo_pair, pair_od, [*hollow.bearings], output_bearings["lower"]),
              ("top_plate", outboard.z, outboard.width, outboard.outer_diameter, [outboard], output_bearings["upper"]))
    for name, z, thickness, od_pinion, held, held_output in plates:
        half_y = max(od_pinion, obod) / 2 + margin
        x0, x1 = -obod / 2 - margin, x_p + od_pinion / 2 + margin
        plate = out.add(name, B.plate_with_holes(x1 - x0, 2 * half_y, thickness,
                                                 [(0.0, 0.0, obod), (x_p, 0.0, od_pinion)], corner=(x0, -half_y, 0.0)),
                        at(0, 0, z), "housing", "housing",
                        description=f"housing plate, {size(thickness)}, holds the bearings at this level")
        for b in held:
            out.join(plate, b.name, "bearing seated in the plate", kind="bearing")
        out.join(plate, held_output, "bearing seated in the plate", kind="bearing")
        out.ground.append(plate)
    return out.freeze()
