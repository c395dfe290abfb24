"""The hardware of an axial-preload drive (``[layout] kind = "axial_preload"``), built where
:func:`geargen.drives.axial_preload.place.axial_preload_hardware` places them: the input shaft through
both helical pinions on two bearings whose outer rings slide in the housing plates' bores (the
shaft slid by the placement's take-up), the
preload spring in a cup under the bottom plate pushing the lower input bearing, the stop over the
upper input bearing that ends the stroke, the output shaft
on its bearings, and the housing's bottom and top plates (the ground)."""

from __future__ import annotations

from functools import partial
from typing import Any, Mapping

from geargen.model import bodies as B
from geargen.drives.axial_preload.place import axial_preload_hardware
from geargen.model.components import ComponentSet, Hardware, at
from geargen.units import sizes_text, small_length_text


def _cup(bore: float, wall: float, depth: float):
    """A cup on +z: a floor ``wall`` thick under a tube of ``bore``, its rim at z = depth + wall."""
    tube = B.translate(B.cylinder(bore + 2 * wall, depth, bore), (0.0, 0.0, wall))
    return B.fuse([B.cylinder(bore + 2 * wall, wall), tube], "spring cup")


def axial_hardware(layout, s: Mapping[str, Any], stiffness=None) -> Hardware:
    """The parts of the module docstring, with their joints and how they hold together."""
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in descriptions: the design's unit
    hw = axial_preload_hardware(layout, dict(s))
    out = ComponentSet()
    ish, osh = hw.input, hw.output
    x_in = ish.centre[0]
    shaft_in = out.add(ish.name, B.shaft(ish.diameter, ish.length), at(x_in, 0, ish.z_lo), "input", "shaft",
                       description=f"input shaft d {size(ish.diameter)}, slid {small_length_text(hw.shift, layout.identity.length_unit)} along +z by the "
                                   "preload spring (the placement's take-up)")
    for name in ish.loads:
        out.join(shaft_in, name, "pinion on the input shaft")
    for b in ish.bearings:
        part = out.add(b.name, B.bearing(b.bore, b.outer_diameter, b.width), at(x_in, 0, b.z), "input",
                       "bearing", description=f"{size(b.bore, b.outer_diameter, b.width)}, outer ring "
                                              "sliding in its bore", shared=True)
        out.join(part, shaft_in, "bearing on the input shaft", kind="bearing")
    for b in osh.bearings:
        part = out.add(b.name, B.bearing(b.bore, b.outer_diameter, b.width), at(0, 0, b.z), "output",
                       "bearing", description=size(b.bore, b.outer_diameter, b.width), shared=True)
    shaft_out = out.add(osh.name, B.shaft(osh.diameter, osh.length), at(0, 0, osh.z_lo), "output", "shaft",
                        description=f"output shaft d {size(osh.diameter)}; the two output gears clamped on it")
    for name in osh.loads:
        out.join(shaft_out, name, "output gear on the output shaft")
    for b in osh.bearings:
        out.join(b.name, shaft_out, "bearing on the output shaft", kind="bearing")
    # the housing: a plate at each level of bearings, holding both shafts' bearings (the ground)
    margin = s["housing_margin"]
    lower_in, upper_in = ish.supports()
    lower_out, upper_out = osh.supports()
    od_in, od_out = lower_in.outer_diameter, lower_out.outer_diameter
    half_y = max(od_in, od_out) / 2 + s["spring_cup_wall"] + margin
    x0, x1 = -od_out / 2 - margin, x_in + od_in / 2 + s["spring_cup_wall"] + margin
    for name, (z0, z1), held in (("bottom_plate", hw.bottom_plate, (lower_in, lower_out)),
                                 ("top_plate", hw.top_plate, (upper_in, upper_out))):
        plate = out.add(name, B.plate_with_holes(x1 - x0, 2 * half_y, z1 - z0, [(0.0, 0.0, od_out), (x_in, 0.0, od_in)],
                                                 corner=(x0, -half_y, 0.0)), at(0, 0, z0), "housing", "housing",
                        description=f"housing plate, {size(z1 - z0)}: the bearings' seats (the input's a sliding fit)")
        for b in held:
            out.join(plate, b.name, "bearing seated in the plate" if b in (lower_out, upper_out)
                     else "bearing's outer ring sliding in the plate's bore", kind="bearing")
        out.ground.append(plate)
    # the preload spring, in its cup under the bottom plate, on the lower input bearing's face
    wall = s["spring_cup_wall"]
    depth = hw.bottom_plate[0] - hw.cup_floor_z
    cup = out.add("spring_cup", _cup(od_in, wall, depth), at(x_in, 0, hw.cup_floor_z - wall), "housing", "housing",
                  description=f"spring cup, bore {size(od_in)}, bolted under the bottom plate")
    out.join(cup, "bottom_plate", "cup bolted under the plate")
    out.stationary.append(cup)
    d, mean = s["spring_wire_diameter"], s["spring_mean_diameter"]
    z0, z1 = hw.spring_z
    # the wire swept along its helix: the active coils and a closed, ground coil at each end
    total_coils = hw.spring_active_coils + 2
    spring = out.add("preload_spring", B.compression_spring(d, mean, z1 - z0, total_coils, ground=True), at(x_in, 0, z0),
                     "housing", "spring", description=f"preload spring: {hw.spring_active_coils:.3g} active coils "
                                                      f"({total_coils:.3g} in all) of {size(d)} wire on {size(mean)}, "
                                                      f"{size(z1 - z0)} long as placed",
                     envelope=B.coil_envelope(d, mean, z1 - z0))
    out.join(spring, cup, "spring on the cup's floor", kind="spring")
    out.join(spring, lower_in.name, "spring on the lower input bearing's outer ring", kind="spring")
    # the stroke: a stop over the upper input bearing's outer ring, input_stroke above its face at the
    # reference position (a spacer tube on the top plate, then a lip over the ring)
    lip_bore = (upper_in.outer_diameter + upper_in.bore) / 2
    spacer = B.cylinder(od_in + 2 * wall, hw.stroke_z - hw.top_plate[1], od_in + 1.0)
    lip = B.translate(B.cylinder(od_in + 2 * wall, wall, lip_bore), (0.0, 0.0, hw.stroke_z - hw.top_plate[1]))
    stop = out.add("stroke_stop", B.fuse([spacer, lip], "stroke stop"), at(x_in, 0, hw.top_plate[1]), "housing",
                   "stop", description=f"stop of the input's slide: {size(layout.settings['input_stroke'])} above the "
                                       "upper bearing's reference position")
    out.join(stop, "top_plate", "stop bolted on the top plate")
    out.stationary.append(stop)
    travel = hw.stroke_z - (upper_in.z + upper_in.width)
    out.dimensions["axial_preload"] = dict(shift=hw.shift, spring_length=z1 - z0, spring_active_coils=hw.spring_active_coils,
                                     stroke_left=travel)
    out.notes.append(f"axial preload: input shaft slid {small_length_text(hw.shift, layout.identity.length_unit)}; spring {size(z1 - z0)} long "
                     f"({hw.spring_active_coils:.3g} active coils); {size(travel)} of stroke left")
    return out.freeze()


__all__ = ["axial_hardware"]

