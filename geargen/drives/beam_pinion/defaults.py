"""The beam-spring pinion's default hardware (the C-axis): its [parts] sized from the gears, the load and what the file gives.

Every [parts] key of a beam-spring pinion drive may be left out, or the whole table; each is sized
by the rule below from the gears' bores, faces and modules, `[preload] max_output_torque` and the
[parts] values the file does give. Lengths are rounded up to 0.5 mm (1/32 in); an inch design
takes the inch values in brackets and inch bearings.

- `bearing_clearance`: the long pinion's module, at least 0.5 mm (0.02 in);
- `spindle_diameter`: the output's bore; `spindle_length`: four output face widths;
  `input_shaft_diameter`, `cluster_shaft_diameter`: the long pinion's and the cluster gears' bore;
- `input_bearing_*`: the ISO 15 series 02 bearing (62xx; inch: ABMA R series) of the long
  pinion's bore, the beam's supports; `cluster_bearing_*`: the series 10 bearing (60xx, the 70xx
  angular-contact pair's size) of the cluster shaft. A bore that is no standard one needs its
  bearing given (the refusal names the key and the standard bores);
- `cluster_bearing_spacing`: a shaft diameter, at least a bearing width and a clearance;
- `friction_ring_outer_diameter`: 5/3 of the cluster shaft; `friction_ring_width`: the gap between
  a cluster's gears less a clearance; `locknut_outer_diameter`: 1.5 shaft diameters, a clearance
  inside the bearing's outer diameter each side; `locknut_width`: a quarter of the shaft, at least
  3 mm (1/8 in);
- `quill_outer_diameter`: the bearings' outer diameter and a wall of four modules of the pinion
  meshing the output each side; `stop_block_size`: eight of those modules; `stop_lug_width` and
  `stop_lug_thickness`: 0.6 of a stop's side; `stop_lug_length`: a stop's side, a clearance and a
  lug's width (its end beyond the stops);
- `housing_thickness`: 0.8 quill diameters (the bore the quill slides in); `housing_margin`: a
  stop's side;
- `coupling_diameter`, `coupling_length`: 5/3 and 4/3 of the long pinion's shaft;
- `motor_*`: the smallest NEMA frame whose torque covers the output's `[preload]
  max_output_torque` through the train and the `[layout]` upstream stages (the designer adds for
  acceleration), its body as wide as its flange; `gearhead_diameter`, `gearhead_length`: a
  gearhead of the motor's frame, as wide as the flange and as long as the body;
- `drive_column_width`: 1.5 long-pinion bearing diameters; `drive_column_thickness`: the long
  pinion's shaft diameter; `motor_plate_thickness`: 2/3 of the column's thickness.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

from geargen.design.catalogue import (Readers, completing, given, metric_or_inch, motor_for, put_bearing,
                                      put_motor)
from geargen.drives.dual_pinion.keys import cluster_axial_gap
from geargen.errors import DesignError

GEARS = ("input", "cluster_large", "cluster_small", "output")


def complete(data: Mapping[str, Any], readers: Readers, fields: list) -> tuple[dict[str, Any], tuple]:
    """The module's rules on ``data`` (``fields``: the kind's [parts] fields): the file completed,
    and what was added (nothing where :func:`geargen.design.catalogue.completing` says so)."""
    start = completing(data, readers, fields, gears=GEARS)
    if start is None:
        return dict(data), ()
    design, s, (inp, large, small, out), c = start
    gap = c.length("bearing_clearance", max(metric_or_inch(0.5, 0.02, c.unit), inp.module),
                   "the long pinion's module, at least 0.5 mm (0.02 in)")
    c.length("spindle_diameter", out.hub.bore_diameter, f"the bore of gears.{out.name}", exact=True)
    c.length("spindle_length", 4 * out.face_width, "four output face widths")
    d_in = c.length("input_shaft_diameter", inp.hub.bore_diameter, f"the bore of gears.{inp.name}", exact=True)
    d_cs = c.length("cluster_shaft_diameter", small.hub.bore_diameter, f"the bore of gears.{small.name}", exact=True)
    od_in, _ = put_bearing(c, c.unit, "input_bearing", d_in, "02", inp.name, "the beam's supports")
    od_cs, width_cs = put_bearing(c, c.unit, "cluster_bearing", d_cs, "10", small.name, "the pair in each quill")
    c.length("cluster_bearing_spacing", max(d_cs, width_cs + gap), "a shaft diameter, at least a bearing width and "
             "a clearance")
    c.length("friction_ring_outer_diameter", 5 * d_cs / 3, "5/3 of the cluster shaft")
    between = cluster_axial_gap(s, large, small)
    if not between > gap:
        if not given(c.parts, "friction_ring_width"):
            raise DesignError("parts.friction_ring_width", f"missing, and the cluster's gears stand "
                              f"{c.shown(between)} apart: no room for the locking ring a clearance from the pinion",
                              "a larger [layout] cluster_axial_gap_*, or a friction_ring_width_* of your own")
    else:
        c.length("friction_ring_width", between - gap, "the gap between a cluster's gears less a clearance")
    c.length("locknut_outer_diameter", min(1.5 * d_cs, od_cs - 2 * gap), "1.5 shaft diameters, a clearance inside "
             "the bearing's outer diameter")
    c.length("locknut_width", max(metric_or_inch(3.0, 0.125, c.unit), d_cs / 4), "a quarter of the shaft, at least "
             "3 mm (1/8 in)")
    m2 = small.module
    quill = c.length("quill_outer_diameter", od_cs + 8 * m2, "the bearings' outer diameter and a wall of four "
                     "mesh-2 modules each side")
    block = c.length("stop_block_size", 8 * m2, "eight mesh-2 modules")
    lug = c.length("stop_lug_width", 0.6 * block, "0.6 of a stop's side")
    c.length("stop_lug_thickness", 0.6 * block, "0.6 of a stop's side")
    c.length("stop_lug_length", block + gap + lug, "a stop's side, a clearance and a lug's width beyond the stops")
    c.length("housing_thickness", 0.8 * quill, "0.8 quill diameters: the bore the quill slides in")
    c.length("housing_margin", block, "a stop's side")
    c.length("coupling_diameter", 5 * d_in / 3, "5/3 of the long pinion's shaft")
    c.length("coupling_length", 4 * d_in / 3, "4/3 of the long pinion's shaft")
    try:
        max_torque = readers.preload(data.get("preload") or {}).max_output_torque
    except DesignError:
        max_torque = None  # the validating load names the [preload] problem
    if max_torque is not None:
        ratio = out.teeth / small.teeth * large.teeth / inp.teeth
        ratio *= math.prod(b / a for a, b in s.get("upstream_stages", ()))
        torque = max_torque / ratio * 1e-3
        frame = motor_for(torque)
        put_motor(c, frame, torque)
        flange, body = c.number("motor_flange", frame[1]), c.number("motor_body_length", frame[2])
        c.length("gearhead_diameter", flange, f"a gearhead of the {frame[0]} frame: as wide as the motor's flange")
        c.length("gearhead_length", body, f"a gearhead of the {frame[0]} frame: as long as the motor's body")
    c.length("drive_column_width", 1.5 * od_in, "1.5 long-pinion bearing diameters")
    thickness = c.length("drive_column_thickness", d_in, "the long pinion's shaft diameter")
    c.length("motor_plate_thickness", 2 * thickness / 3, "2/3 of the column's thickness")
    return c.result()


__all__ = ["complete"]
