"""The dual pinion's shafts placed (Fig. 10): the loop's (:func:`geargen.model.shafts.loop_shafts`),
the input's running on to the gear that drives it (the bevel gear, the last of the [stages], or a
planetary stage's carrier), and the stage shafts standing on the preload carriage's arm.
"""

from __future__ import annotations

import math
from functools import partial
from typing import Any

from geargen.drives.planetary.place import carrier
from geargen.errors import DesignError
from geargen.model.layout import Layout
from geargen.model.shafts import Bearing, Shaft, bore_of, loop_shafts, mid_face
from geargen.units import sizes_text


def carriage_arm_top(input_shaft: Shaft, parts: dict[str, Any]) -> float:
    """Top of the preload carriage's arm, which holds the input's upper bearing from above: where
    the stage shafts' lower bearings stand."""
    return max(b.z + b.width for b in input_shaft.bearings) + parts["carriage_plate_thickness"]


def carriage_shafts(layout: Layout, parts: dict[str, Any]) -> dict[str, Shaft]:
    """The robot joint's shafts (Fig. 10): the loop's (:func:`loop_shafts`), the input's running
    on to the gear that drives it (the bevel gear, or the last of the [stages]), and the stage
    shafts (:func:`stage_shafts`)."""
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in messages: the design's unit
    out = loop_shafts(layout.gears, parts)
    shaft = out["input"]
    stage_list = layout.resolved.stages
    if not stage_list:
        # the input shaft runs on to the bevel gear, whose heel is input_shaft_to_bevel above the input's mid-face
        bevel_heel = shaft.loads["input"] + parts["input_shaft_to_bevel"]
        out["input"] = Shaft(shaft.name, shaft.centre, shaft.z_lo, shaft.z_hi, shaft.diameter, shaft.bearings,
                             {**shaft.loads, "bevel_gear": bevel_heel})
        return out
    if stage_list[-1].kind == "planetary":
        # the input shaft runs up through the carriage arm into the planet carrier's lower plate
        c = carrier(layout, parts, stage_list[-1])
        out["input"] = Shaft(shaft.name, shaft.centre, shaft.z_lo, c.lower_top, shaft.diameter, shaft.bearings,
                             {**shaft.loads, c.name: c.z_lower + c.thickness / 2})
        return out
    # the input shaft runs up through the carriage arm to the last stage's driven gear
    last = layout.gear(stage_list[-1].driven)
    if not math.isclose(bore_of(last.spec), shaft.diameter, rel_tol=1e-9):
        raise DesignError(f"gears.{last.name}.bore_diameter", f"{size(bore_of(last.spec), digits=6)}: the gear sits on the input "
                          "gear's shaft", f"the input's bore, {size(shaft.diameter, digits=6)}")
    out["input"] = Shaft(shaft.name, shaft.centre, shaft.z_lo, last.height[1], shaft.diameter, shaft.bearings,
                         {**shaft.loads, last.name: mid_face(last, last.spec)})
    out.update(stage_shafts(layout, parts, stage_list))
    return out


def stage_shafts(layout: Layout, parts: dict[str, Any], stage_list) -> dict[str, Shaft]:
    """The shafts between the upstream stages (:mod:`geargen.design.stages`): each carries one
    stage's driven gear and the next stage's driver, from its lower bearing standing on the
    carriage arm to its upper bearing under the bridge over the highest stage."""
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in messages: the design's unit
    gap, width, outer = parts["bearing_clearance"], parts["stage_bearing_width"], parts["stage_bearing_outer_diameter"]
    by = {p.name: p for p in layout.gears}
    loop = [p for p in layout.gears if not p.group.startswith("stage_")]
    z_lower = carriage_arm_top(loop_shafts(loop, parts)["input"], parts)
    top = max(by[g].height[1] for st in stage_list for g in (st.driver, st.driven))
    z_upper = top + gap
    out: dict[str, Shaft] = {}
    for i, (st, nxt) in enumerate(zip(stage_list, stage_list[1:]), start=1):
        members = [by[st.driven], by[nxt.driver]]
        bores = {bore_of(m.spec) for m in members}
        if len(bores) != 1:
            raise DesignError(f"gears.{nxt.driver}.bore_diameter", f"{size(bore_of(members[1].spec), digits=6)}: it shares a shaft "
                              f"with {st.driven}", f"{size(bore_of(members[0].spec), digits=6)}, the same bore")
        diameter = bores.pop()
        if not diameter > 0:
            raise DesignError(f"gears.{st.driven}.bore_diameter", "missing: the gear sits on a stage shaft", "> 0")
        if not outer > diameter:
            raise DesignError("parts.stage_bearing_outer_diameter", f"not larger than the stage shaft ({size(diameter, digits=6)})",
                              f"> {size(diameter, digits=6)}")
        bearings = (Bearing(f"stage_bearing_lower_{i}", z_lower, width, diameter, outer),
                    Bearing(f"stage_bearing_upper_{i}", z_upper, width, diameter, outer))
        loads = {m.name: mid_face(m, m.spec) for m in members}
        out[f"stage_{i}"] = Shaft(f"stage_shaft_{i}", tuple(members[0].centre), z_lower, z_upper + width, diameter,
                                  bearings, loads)
    return out


__all__ = ["carriage_arm_top", "carriage_shafts", "stage_shafts"]
