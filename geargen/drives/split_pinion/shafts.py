"""The split pinion's two concentric shafts placed (Fig. 8): the hardware builds them here and the
stiffness model reads the same (the inner shaft's torsion, each pinion's support).
"""

from __future__ import annotations

from functools import partial
from typing import Any

from geargen.errors import DesignError
from geargen.model.layout import Layout
from geargen.model.shafts import Bearing, Shaft, bore_of, mid_face
from geargen.units import sizes_text


def split_pinion_shafts(layout: Layout, parts: dict[str, Any]) -> dict[str, Shaft]:
    """The split pinion's two concentric shafts (Fig. 8).

    ``hollow``: the stiff pinion's shaft (its bore, so the inner shaft clears it by a
    ``bearing_clearance`` all round), ``hollow_shaft_length`` from the stiff pinion's far face
    down, on its bearing pair (``bearing_spacing`` apart) just below the stiff pinion, which it
    overhangs. The drive turns it at its lower end; it twists from there to the stiff pinion's
    mid-face.
    ``inner``: the compliant pinion's shaft (the pinion's bore), from the clamp collar below the
    hollow shaft's end, up through it and the compliant pinion to an outboard bearing a
    ``bearing_clearance`` above the compliant pinion and the output gear (the plate that holds
    it clears both). It is carried by the collar (on the hollow shaft) and the outboard bearing,
    so the compliant pinion sits between two supports; it twists from the collar's face to the
    compliant pinion's face."""
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in messages: the design's unit
    gap = parts["bearing_clearance"]
    stiff, compl = layout.gear(layout.settings["pinion_stiff"]), layout.gear(layout.settings["pinion_compliant"])
    output = layout.gear(layout.settings["output"])
    d_hollow, d_inner = parts["hollow_shaft_outer_diameter"], bore_of(compl.spec)
    if not d_inner > 0:
        raise DesignError(f"gears.{compl.name}.bore_diameter", "missing: the inner shaft fills the compliant "
                          "pinion's bore", "bore_diameter_* > 0")
    bore_hollow = d_inner + 2 * gap
    if not bore_hollow < d_hollow:
        raise DesignError("parts.hollow_shaft_outer_diameter", f"{size(d_hollow, digits=6)} leaves no wall around the inner "
                          f"shaft ({size(d_inner, digits=6)} + {size(gap, digits=6)} clearance all round)", f"> {size(bore_hollow, digits=6)}")
    zs0, zs1 = stiff.height
    zc0, zc1 = compl.height
    bw, bod = parts["bearing_width"], parts["bearing_outer_diameter"]
    z_hollow0 = zs1 - parts["hollow_shaft_length"]
    spacing = parts.get("bearing_spacing") or (bw + gap)
    if not spacing >= bw + gap:
        raise DesignError("parts.bearing_spacing", f"{size(spacing, digits=6)} puts the two bearings into each other",
                          f">= {size(bw + gap, digits=6)} (a bearing width and a bearing_clearance)")
    upper = Bearing("pinion_bearing_1", zs0 - gap - bw, bw, d_hollow, bod)
    pair = (Bearing("pinion_bearing_2", upper.z - spacing, bw, d_hollow, bod), upper)
    if not z_hollow0 < pair[0].z:
        raise DesignError("parts.hollow_shaft_length", f"{size(parts['hollow_shaft_length'], digits=6)} does not reach "
                          "through the bearing pair", f"> {size(zs1 - pair[0].z, digits=6)}")
    # the drive turns the hollow shaft at its lower end, where the collar joins the inner shaft to it:
    # the stiff path twists from there to the stiff pinion's mid-face, the compliant one from the
    # collar's face to the compliant pinion
    loads = {g.name: mid_face(stiff, g) for g in stiff.gears}
    hollow = Shaft("hollow_shaft", tuple(stiff.centre), z_hollow0, zs1, d_hollow, pair, loads, bore=bore_hollow,
                   twist=(z_hollow0, next(iter(loads.values()))))
    cw = parts["collar_width"]
    collar = Bearing("friction_collar", z_hollow0 - cw, cw, d_inner, parts["collar_outer_diameter"], via=hollow.name)
    z_top = max(zc1, output.height[1]) + gap
    outboard = Bearing("compliant_bearing", z_top, parts["compliant_bearing_width"], d_inner,
                       parts["compliant_bearing_outer_diameter"])
    inner = Shaft("inner_shaft", tuple(compl.centre), collar.z, outboard.z + outboard.width, d_inner,
                  (collar, outboard), {g.name: mid_face(compl, g) for g in compl.gears}, twist=(z_hollow0, zc0))
    return {"hollow": hollow, "inner": inner}


__all__ = ["split_pinion_shafts"]
