"""The hardware of the Type 2 rack drive (:mod:`geargen.drives.rack_dual_pinion.place`), placed from its
resolved layout and the ``[parts]`` sizes of the "rack_drive" hardware.

* each path shaft (the pinion's bore) runs through its pinion and path gear, on a bearing below
  the pinion (in the bottom housing plate) and one above the path gear (in the top plate);
* the input shaft (the input gear's bore) rises from the input gear through a clearance hole in
  the top plate into the preload carriage, which holds it on two bearings; the carriage rides on
  a linear guide (rail on the top plate, sliding block under the carriage) along the symmetry
  line, and a compression spring between a post on the top plate and the carriage pushes it
  toward the path shafts with the ``[layout]`` preload force;
* the spring's active coils follow from the ``[layout]`` spring rate (``G d^4 / (8 D^3 k)``) and
  its free length from the preload (installed + ``F / k``), so the rate has one home;
* the rack is held by the machine slide (its guides are outside the model): ground that moves.

The housing plates are the ground. The motor would stand on the carriage over the input shaft;
it is not modelled.
"""

from __future__ import annotations

import math
from functools import partial
from typing import Any, Mapping

from geargen.core.flexures import spring_for_rate
from geargen.errors import DesignError
from geargen.model import bodies as B
from geargen.model.components import ComponentSet, Hardware, at, transform
from geargen.drives.rack_dual_pinion.place import rack_drive
from geargen.units import sizes_text


def rack_drive_hardware(layout, s: Mapping[str, Any], stiffness=None) -> Hardware:
    """The parts listed in the module docstring, placed, with their joints."""
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in descriptions: the design's unit
    placed = rack_drive(layout)
    out = ComponentSet()
    gap = s["bearing_clearance"]
    margin = s["housing_margin"]
    g = {p.name: p for p in layout.gears}
    bw, bod = s["path_bearing_width"], s["path_bearing_outer_diameter"]
    d_path = placed.pinion.hub.bore_diameter
    if placed.path_gear.hub.bore_diameter != d_path:
        raise DesignError("gears.path_gear.bore_diameter_mm", "the path gear sits on the pinion's shaft",
                          f"{size(d_path, digits=6)} (the pinion's bore)")
    z_low = g["pinion_a"].z - gap - bw  # lower bearing under the pinion
    z_top = g["path_gear_a"].z + placed.path_gear.face_width + gap  # upper bearing over the path gear
    out.ground += ["rack"]
    out.rotating += ["rack"]  # the slide moves it: held by the machine, not by this housing
    for side in ("a", "b"):
        x, y = g[f"pinion_{side}"].centre
        shaft = out.add(f"path_shaft_{side}", B.shaft(d_path, z_top + bw - z_low), at(x, y, z_low),
                        f"path_{side}", "shaft", description=f"path shaft {side}, d {size(d_path)}", shared=True)
        out.join(shaft, f"pinion_{side}", "rack pinion on its path shaft")
        out.join(shaft, f"path_gear_{side}", "path gear keyed on its path shaft (timing mark)")
        for where, z in (("lower", z_low), ("upper", z_top)):
            b = out.add(f"path_bearing_{side}_{where}", B.bearing(d_path, bod, bw), at(x, y, z),
                        f"path_{side}", "bearing", description=size(d_path, bod, bw), shared=True)
            out.join(b, shaft, "bearing on the path shaft", kind="bearing")
        out.join(f"pinion_{side}", "rack", "rack mesh: checked by geargen.drives.rack_dual_pinion.verdict", kind="mesh")
    xa, ys = g["pinion_a"].centre
    xi, yi = g["input"].centre
    d_in = placed.input.hub.bore_diameter
    clearance_hole = d_in + 2 * (placed.carriage_travel + 2 * margin)
    # the housing: bottom plate at the lower bearings' level, top plate at the upper ones'
    x0, x1 = -xa - bod / 2 - margin, xa + bod / 2 + margin
    y0 = ys - bod / 2 - margin
    post_t = s["spring_post_thickness"]
    # the carriage: a block over the top plate holding the input's two bearings
    ibw, ibod = s["input_bearing_width"], s["input_bearing_outer_diameter"]
    rail_w, rail_h = s["rail_width"], s["rail_height"]
    block_l, block_h = s["guide_block_length"], s["guide_block_height"]
    z_plate_top = z_top + bw
    z_carriage = z_plate_top + rail_h + block_h
    carriage_half_y = max(ibod / 2, block_l / 2) + margin
    # the guide beside the input's clearance hole, toward +x
    rail_x = clearance_hole / 2 + margin + rail_w / 2
    carriage_x0 = xi - ibod / 2 - margin
    carriage_x1 = rail_x + rail_w / 2 + margin
    # the spring pushes the carriage toward the shafts (-y) from a post beyond its +y face
    spring_d, spring_mean = s["spring_wire_diameter"], s["spring_mean_diameter"]
    rate = placed.spring_rate
    coils = spring_for_rate(placed.spring_force, rate, spring_d, spring_mean, s["spring_installed_length"],
                            s["spring_shear_modulus_GPa"] * 1e3).active_coils
    installed = s["spring_installed_length"]
    total = coils + 2  # squared and ground ends
    if not installed > spring_d * (total + 1):
        raise DesignError("parts.spring_installed_length_mm", f"{size(installed, digits=6)} closes the spring's {total:.3g} "
                          f"coils of {size(spring_d)} wire", f"> {size(spring_d * (total + 1), digits=6)}")
    z_spring = z_carriage + max(ibw * 2, spring_mean + spring_d) / 2
    carriage_h = 2 * (z_spring - z_carriage)
    y_face = yi + carriage_half_y
    y_post = y_face + installed
    y1 = max(y_post + post_t, yi + clearance_hole / 2) + margin
    holes_bottom = [(-xa, ys, bod), (xa, ys, bod)]
    holes_top = holes_bottom + [(xi, yi, clearance_hole)]
    for name, z, holes in (("bottom_plate", z_low, holes_bottom), ("top_plate", z_top, holes_top)):
        plate = out.add(name, B.plate_with_holes(x1 - x0, y1 - y0, bw, holes, corner=(x0, y0, 0.0)), at(0, 0, z),
                        "housing", "housing", description=f"housing plate, {size(bw)}, holds the path bearings")
        for side in ("a", "b"):
            out.join(plate, f"path_bearing_{side}_{'lower' if name == 'bottom_plate' else 'upper'}",
                      "bearing seated in the plate", kind="bearing")
        out.ground.append(plate)
    rail = out.add("guide_rail", B.box(rail_w, 2 * (carriage_half_y + placed.carriage_travel) + block_l, rail_h,
                                       (rail_x - rail_w / 2, yi - carriage_half_y - placed.carriage_travel - block_l / 2,
                                        0.0)),
                   at(0, 0, z_plate_top), "carriage", "housing", description="linear guide rail, bolted to the top plate")
    out.join(rail, "top_plate", "rail bolted to the top plate")
    block = out.add("guide_block", B.box(rail_w + 2 * margin, block_l, block_h,
                                         (rail_x - rail_w / 2 - margin, yi - block_l / 2, 0.0)),
                    at(0, 0, z_plate_top + rail_h), "carriage", "bearing",
                    description="the linear guide's sliding block (rolling elements): the carriage's one freedom")
    out.join(block, rail, "guide block on its rail", kind="sliding")
    carriage = out.add("carriage", B.plate_with_holes(carriage_x1 - carriage_x0, 2 * carriage_half_y, carriage_h,
                                                      [(xi, yi, ibod)], corner=(carriage_x0, yi - carriage_half_y, 0.0)),
                       at(0, 0, z_carriage), "carriage", "carriage",
                       description=f"preload carriage: {size(placed.carriage_travel)} stroke either way along the "
                                   "symmetry line")
    out.join(carriage, block, "carriage bolted to the guide block")
    out.stationary.append(carriage)
    shaft = out.add("input_shaft", B.shaft(d_in, z_carriage + carriage_h - g["input"].z),
                    at(xi, yi, g["input"].z), "input", "shaft", description=f"input (motor) shaft, d {size(d_in)}", shared=True)
    out.join(shaft, "input", "input gear on the motor's shaft")
    for i, z in enumerate((z_carriage, z_carriage + carriage_h - ibw)):
        b = out.add(f"input_bearing_{i + 1}", B.bearing(d_in, ibod, ibw), at(xi, yi, z), "input",
                    "bearing", description=size(d_in, ibod, ibw), shared=True)
        out.join(b, shaft, "bearing on the input shaft", kind="bearing")
        out.join(b, carriage, "bearing seated in the carriage", kind="bearing")
    # the spring along -y: local +z turned onto world -y (a quarter turn about +x)
    spring_matrix = transform((xi, y_post, z_spring), (1, 0, 0), math.pi / 2)
    spring = out.add("carriage_spring", B.coil_envelope(spring_d, spring_mean, installed), spring_matrix, "carriage",
                     "spring", description=f"compression spring d {size(spring_d)} x D {size(spring_mean)}, "
                                           f"{coils:.3g} active coils ({layout.identity.text_units.text('linear_stiffness', rate)}), "
                                           f"installed {size(installed)}, "
                                           f"free {size(installed + placed.spring_force / rate)}: "
                                           f"{layout.identity.text_units.text('force', placed.spring_force)}")
    post = out.add("spring_post", B.box(2 * (spring_mean / 2 + spring_d + margin), post_t, z_spring + spring_mean / 2
                                        + spring_d + margin - z_plate_top,
                                        (xi - spring_mean / 2 - spring_d - margin, y_post, 0.0)),
                   at(0, 0, z_plate_top), "housing", "housing", description="spring post on the top plate")
    out.join(post, "top_plate", "post bolted to the top plate")
    out.join(spring, post, "spring seated on the post", kind="spring")
    out.join(spring, carriage, "spring pushing the carriage toward the path shafts", kind="spring")
    out.dimensions["carriage_spring"] = dict(active_coils=coils, installed=installed,
                                       free=installed + placed.spring_force / rate)
    return out.freeze()


__all__ = ["rack_drive_hardware"]

