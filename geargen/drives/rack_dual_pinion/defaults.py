"""The rack drive's default hardware: its [parts] sized from the pinions, the input gear, the carriage spring's force and rate, and what the file gives.

Every [parts] key of a rack dual-pinion drive may be left out, or the whole table; each is sized
by the rule below from the gears' bores, the `[layout]` carriage spring and travel and the
[parts] values the file does give. Lengths are rounded up to 0.5 mm (1/32 in); an inch design
takes the inch values in brackets and inch bearings.

- `bearing_clearance`: 0.5 mm (0.02 in) between a bearing and a gear face;
- `path_bearing_*`: the ISO 15 series 19 bearing (619xx; inch: ABMA R series) of the path shafts'
  bore (the pinions'); `input_bearing_*`: the series 10 bearing (60xx) of the input gear's bore,
  the carriage's pair. A bore that is no standard one needs its bearing given (the refusal names
  the key and the standard bores);
- `housing_margin`: 5 mm (0.2 in) around the bearing seats; `spring_post_thickness`: two margins;
- the linear guide: `rail_width`, the widest miniature rail (7, 9, 12, 15 mm) no wider than half
  the input bearing's outer diameter; `rail_height` 2/3 of its width, `guide_block_length` 2.5
  rail widths, `guide_block_height` (above the rail) 5/12 of a rail width: the proportions of the
  size-12 guide (12 x 8 rail, 30 mm block);
- the carriage spring: `spring_wire_diameter` and `spring_mean_diameter`, music wire at spring
  index 5, the thinnest standard wire whose stress at `[layout] carriage_preload_force_N` and
  closed solid stays within 0.45 of its tensile strength, its active coils giving
  `carriage_spring_rate_N_per_mm` (G d / (8 C^3 k)); `spring_installed_length`: the larger of a
  wire, 15 % of its working deflection and the carriage's travel above its solid height (the
  verdict's rule); `spring_shear_modulus_GPa`: 79.3 (music wire).
"""

from __future__ import annotations

from typing import Any, Mapping

from geargen.design.catalogue import (STEEL_G_GPA, WIRE_DIAMETERS, Completion, Readers, coil_rate, completing,
                                      music_wire_allowable, put_bearing, rounded, wahl_stress_per_newton)
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES

#: spring index of the default carriage spring
SPRING_INDEX = 5.0
#: miniature profile rail widths (mm)
RAIL_WIDTHS = (7.0, 9.0, 12.0, 15.0)


def complete(data: Mapping[str, Any], readers: Readers, fields: list) -> tuple[dict[str, Any], tuple]:
    """The module's rules on ``data`` (``fields``: the kind's [parts] fields): the file completed,
    and what was added (nothing where :func:`geargen.design.catalogue.completing` says so)."""
    start = completing(data, readers, fields, gears=("pinion", "input"))
    if start is None:
        return dict(data), ()
    design, s, (pinion, inp), c = start
    c.stated("bearing_clearance", 0.5, 0.02, "0.5 mm (0.02 in) between a bearing and a gear face")
    put_bearing(c, c.unit, "path_bearing", pinion.hub.bore_diameter, "19", pinion.name, "the path shafts' bearings")
    od_in, _ = put_bearing(c, c.unit, "input_bearing", inp.hub.bore_diameter, "10", inp.name,
                           "the input's pair in the carriage")
    margin = c.stated("housing_margin", 5.0, 0.2, "5 mm (0.2 in) around the bearing seats")
    c.length("spring_post_thickness", 2 * margin, "two housing margins")
    fitting = [w for w in RAIL_WIDTHS if w <= od_in / 2] or [RAIL_WIDTHS[0]]
    rail = c.length("rail_width", fitting[-1], "the widest miniature rail (7, 9, 12, 15 mm) no wider than half the "
                    "input bearing's outer diameter")
    guide = "the proportions of the size-12 miniature guide (12 x 8 rail, 30 mm block 5 mm above it)"
    c.length("rail_height", rail * 2 / 3, f"2/3 of the rail's width: {guide}")
    c.length("guide_block_length", rail * 2.5, f"2.5 rail widths: {guide}")
    c.length("guide_block_height", rail * 5 / 12, f"5/12 of the rail's width: {guide}")
    c.put("parts", "spring_shear_modulus_GPa", STEEL_G_GPA, "music wire")
    force, rate, travel = s["carriage_preload_force_N"], s["carriage_spring_rate_N_per_mm"], s["carriage_travel"]
    if force is not None and rate is not None and travel is not None:
        _spring(c, force, rate, travel, c.number("spring_shear_modulus_GPa", STEEL_G_GPA))
    return c.result()


def _spring(c: Completion, force: float, rate: float, travel: float, shear: float) -> None:
    """The carriage spring of the module docstring's rule, put (the file's wire and mean diameter stand)."""
    given_wire = c.number("spring_wire_diameter", 0.0)
    wires = [given_wire] if given_wire else WIRE_DIAMETERS
    for d in wires:
        mean = c.number("spring_mean_diameter", SPRING_INDEX * d) if given_wire else SPRING_INDEX * d
        coils = coil_rate(d, mean, 1.0, shear) / rate
        solid = d * (coils + 2)  # squared and ground ends
        clearance = max(d, 0.15 * force / rate, travel)
        installed = rounded(solid + clearance, c.unit) * LENGTH_SUFFIXES[c.unit]
        solid_force = force + rate * (installed - solid)
        if wahl_stress_per_newton(d, mean) * solid_force <= music_wire_allowable(d) or given_wire:
            why = (f"music wire at spring index {mean / d:.3g}: {force:.4g} N at {rate:.4g} N/mm with "
                   f"{coils:.3g} active coils, {wahl_stress_per_newton(d, mean) * solid_force:.4g} MPa closed solid "
                   f"(0.45 S_ut = {music_wire_allowable(d):.4g} MPa)")
            c.length("spring_wire_diameter", d, why, exact=True)
            c.length("spring_mean_diameter", mean, why, exact=True)
            c.length("spring_installed_length", installed, f"{c.shown(clearance)} above its solid height "
                     f"{c.shown(solid)}: a wire, 15 % of its working deflection, the carriage's travel")
            return
    raise DesignError(f"parts.spring_wire_diameter_{c.unit}", f"missing, and no music wire up to "
                      f"{WIRE_DIAMETERS[-1]:g} mm at spring index {SPRING_INDEX:g} carries {force:.4g} N at "
                      f"{rate:.4g} N/mm closed solid", "a spring of your own (spring_wire_diameter_*, "
                      "spring_mean_diameter_*, spring_installed_length_*), or a smaller [layout] "
                      "carriage_preload_force_N or carriage_spring_rate_N_per_mm")


__all__ = ["complete", "SPRING_INDEX", "RAIL_WIDTHS"]
