"""The hardware of a planetary upstream stage on the preload carriage (the gears are the Layout's):
the planet carrier (two plates and a pin per planet), the frame that holds the ring and the motor,
and the motor with its shaft in the sun's bore.

Every size comes from the placement (:func:`geargen.drives.planetary.place.carrier`: plates from
the gears' heights, pins of the planets' bore at the planets' centres) and from ``[parts]``
(plate thickness, clearance, motor). The frame is one part: a tube standing on the ring's top
face (its bore a clearance outside the ring's root circle, its outside the ring's rim) under a
bridge that the carriage's two side columns carry; the motor stands on the bridge, its shaft down
through the bridge and the carrier's upper plate into the sun. The frame and the motor lie wholly
above the link cover (the stage stands a clearance above it): they may overhang it.
"""

from __future__ import annotations

import math
from functools import partial
from typing import Any, Mapping

from geargen.errors import DesignError
from geargen.model import bodies as B
from geargen.model.components import ComponentSet, at
from geargen.drives.planetary.place import carrier
from geargen.model.shafts import bore_of
from geargen.profile.internal import internal_profile
from geargen.units import sizes_text


def planetary_drive(out: ComponentSet, layout, s: Mapping[str, Any], placed_shafts, st,
                    post_x0: float) -> dict[str, Any]:
    """Add the stage's hardware to ``out``; returns what the carriage
    (:func:`geargen.drives.dual_pinion.hardware.carriage_hardware`) reads of its motor drive."""
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in descriptions: the design's unit

    gap, t = s["bearing_clearance"], s["carriage_plate_thickness"]
    c = carrier(layout, s, st)
    sun, ring = layout.gear(st.sun), layout.gear(st.ring)
    planets = [g for g in layout.gears if g.group == f"stage_{st.name}" and "planetary_planet" in g.roles]
    cx, cy = c.centre
    group = "carriage"
    # the carrier: the input's shaft ends in the lower plate's bore, the motor's shaft passes the upper's hole
    pins = [(x - cx, y - cy, c.pin_diameter) for x, y in c.pins]
    for which, z0, hole in (("lower", c.z_lower, c.bore), ("upper", c.z_upper, c.hole)):
        plate = B.single(B.cut(B.cylinder(2 * c.radius, c.thickness, hole),
                                *[B.translate(B.cylinder(d, c.thickness), (x, y, 0.0)) for x, y, d in pins]),
                          "carrier plate")
        out.add(f"{c.name}_{which}", plate, at(cx, cy, z0), group, "carrier",
                description=f"planet carrier {which} plate, {len(pins)} pins on r {size(math.dist(c.pins[0], c.centre), digits=5)}")
    out.join("input_shaft", f"{c.name}_lower", "input shaft in the carrier's bore")
    for i, (p, (x, y)) in enumerate(zip(planets, c.pins), start=1):
        pin = out.add(f"{c.name}_pin_{i}", B.shaft(c.pin_diameter, c.top - c.z_lower), at(x, y, c.z_lower),
                      group, "shaft", description=f"planet pin d {size(c.pin_diameter)}", shared=True)
        out.join(pin, p.name, "planet on its pin")
        for which in ("lower", "upper"):
            out.join(pin, f"{c.name}_{which}", "pin pressed in the carrier plate")
    # the frame: the bridge a clearance over the carrier, the ring tube down to the ring's top face
    rim = ring.spec.rim_diameter
    root = 2 * internal_profile(ring.spec).root_radius
    if not root + 2 * gap < rim:
        raise DesignError(f"gears.{st.ring}.rim_diameter", f"{size(rim, digits=6)} leaves no wall for the ring's frame outside "
                          f"its root circle", f"> {size(root + 2 * gap, digits=6)}")
    if not 2 * c.radius < root:
        raise DesignError(f"gears.{st.planet}.bore_diameter", "the carrier plates reach the ring's frame",
                          f"< {size(root / 2 - math.dist(c.pins[0], c.centre))}")
    z_ring_top = ring.height[1]
    z_bridge0 = c.top + gap
    z_bridge1 = z_bridge0 + t
    d_motor = bore_of(sun.spec)
    if not d_motor > 0:
        raise DesignError(f"gears.{st.sun}.bore_diameter", "missing: the sun sits on the motor shaft", "> 0")
    reach_y = abs(cy) + rim / 2
    y_col = reach_y + gap
    half = y_col + t
    # the columns stand beyond the loop's gears along +x (as for the stages of pairs)
    x_col = max([post_x0] + [p.centre[0] + p.gears[0].tip_radius + gap for p in layout.gears
                             if p.group.startswith("cluster_") or p.group == "output"])
    x_b0 = min(cx - rim / 2 - gap, cx - s["motor_flange"] / 2 - gap)
    x_b1 = max(cx + rim / 2 + gap, cx + s["motor_flange"] / 2 + gap, x_col + t)
    bridge = B.box_between((x_b0, -half, z_bridge0), (x_b1, half, z_bridge1))
    tube = B.translate(B.cylinder(rim, z_bridge0 - z_ring_top, root + 2 * gap), (cx, cy, z_ring_top))
    frame = B.single(B.cut(B.fuse([bridge, tube], "planetary frame"),
                            B.translate(B.cylinder(d_motor + 2 * gap, t), (cx, cy, z_bridge0))), "planetary frame")
    frame_name = out.add(f"frame_{st.name}", frame, at(), group, "housing",
                         description="holds the fixed ring and the motor; on the carriage's columns")
    out.stationary.append(frame_name)
    out.stationary.append(st.ring)  # the ring is fixed: the reaction member
    out.join(frame_name, st.ring, "ring fixed in its frame")
    out.join(frame_name, "carriage", "frame on the carriage's columns")
    stub = z_bridge1 - sun.height[0]
    motor = out.add("servo_motor", B.servo_motor(s["motor_body_diameter"], s["motor_body_length"], s["motor_flange"],
                                                 s["motor_flange_thickness"], d_motor, stub),
                    at(cx, cy, z_bridge1), group, "motor",
                    description="servo motor with encoder (envelope), standing on the planetary stage's frame")
    out.join(motor, st.sun, "sun on the motor shaft", kind="motor")
    out.join(motor, frame_name, "motor on its mount", kind="motor")
    # the carriage's columns rise from its base plate, beside the ring's rim, to the bridge
    z_plate_top = placed_shafts["input"].supports()[0].z
    pieces = []
    for sign in (1, -1):
        y0, y1 = sorted((sign * y_col, sign * half))
        pieces.append(B.box_between((x_col, y0, z_plate_top - t), (x_col + t, y1, z_bridge0)))
    # the base plate reaches out under the columns only (the loop's bearing bosses stand beside it)
    pieces.append(B.box_between((x_col, -half, z_plate_top - t), (x_col + t, half, z_plate_top)))
    return dict(pieces=pieces, holes=[], arm=[], x_end=x_b1, z_top=z_bridge1, input_top=c.lower_top,
                over_cover=[f"{c.name}_lower", f"{c.name}_upper", frame_name, motor]
                + [f"{c.name}_pin_{i}" for i in range(1, len(planets) + 1)],
                motor_mount=frame_name,
                note=f"planetary stage {st.name} before the input on the carriage ({layout.ratio['text']})")


__all__ = ["planetary_drive"]

