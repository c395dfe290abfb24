"""The axial preload's default hardware: its [parts] sized from the helical pinions, the output gears, the preload spring's rate and what the file gives.

Every [parts] key of an axial-preload drive may be left out, or the whole table; each is sized by
the rule below from the gears' bores and modules, the `[preload]` spring rate and the [parts]
values the file does give. Lengths are rounded up to 0.5 mm (1/32 in); an inch design takes the
inch values in brackets and inch bearings.

- `bearing_clearance`: 0.5 mm (0.02 in) between a bearing and a gear face;
- `input_bearing_*`: the ISO 15 series 10 bearing (60xx; inch: ABMA R series) of the pinions'
  bore: a wide outer ring slides in its bore without tipping; `output_bearing_*`: the series 19
  bearing (619xx) of the output gears' bore. A bore that is no standard one needs its bearing
  given (the refusal names the key and the standard bores);
- `spring_mean_diameter`: midway between the shaft and the input bearing's outer diameter, so the
  coils bear on the ring's face; `spring_wire_diameter`: the thinnest standard music wire giving
  `[preload] preload_spring_stiffness_N_per_mm` with at least 6 active coils (G d^4 / (8 D^3 k)),
  its coils clear of the shaft and inside the ring; `spring_installed_length`: its solid height
  (the active coils and two closed ends) and two wires more; `spring_shear_modulus_GPa`: 79.3
  (music wire);
- `spring_cup_wall`: two modules, at least 3 mm (1/8 in); `motor_stub_length`: 1.5 input-shaft
  diameters, at least 10 mm (3/8 in), for the motor's coupling;
- `housing_margin`: 5 mm (0.2 in) of plate around the outermost bearing seats.
"""

from __future__ import annotations

from typing import Any, Mapping

from geargen.design.catalogue import (STEEL_G_GPA, WIRE_DIAMETERS, Completion, Readers, coil_rate, completing,
                                      metric_or_inch, put_bearing)
from geargen.errors import DesignError

#: the fewest active coils of a default preload spring: fewer make no spring of even pitch
MIN_ACTIVE_COILS = 6.0


def complete(data: Mapping[str, Any], readers: Readers, fields: list) -> tuple[dict[str, Any], tuple]:
    """The module's rules on ``data`` (``fields``: the kind's [parts] fields): the file completed,
    and what was added (nothing where :func:`geargen.design.catalogue.completing` says so)."""
    start = completing(data, readers, fields, roles=("pinion_left", "output_right"))
    if start is None:
        return dict(data), ()
    design, s, (pinion, output), c = start
    c.stated("bearing_clearance", 0.5, 0.02, "0.5 mm (0.02 in) between a bearing and a gear face")
    d_in = pinion.hub.bore_diameter
    od_in, _ = put_bearing(c, c.unit, "input_bearing", d_in, "10", pinion.name,
                           "a wide outer ring slides in its bore without tipping")
    put_bearing(c, c.unit, "output_bearing", output.hub.bore_diameter, "19", output.name, "the output shaft's pair")
    mean = c.length("spring_mean_diameter", (d_in + od_in) / 2, "midway between the shaft and the input bearing's "
                    "outer diameter: the coils bear on its outer ring")
    shear = c.number("spring_shear_modulus_GPa", STEEL_G_GPA)
    c.put("parts", "spring_shear_modulus_GPa", STEEL_G_GPA, "music wire")
    wire = c.number("spring_wire_diameter", 0.0) or _wire(c, readers, data, mean, d_in, od_in, shear)
    rate = _rate(readers, data)
    if rate is not None:
        coils = shear * 1e3 * wire ** 4 / (8 * mean ** 3 * rate)
        c.length("spring_installed_length", wire * (coils + 4), f"solid height ({coils:.3g} active coils and two "
                 "closed ends) and two wires more")
    m = pinion.module
    c.length("spring_cup_wall", max(metric_or_inch(3.0, 0.125, c.unit), 2 * m), "two modules, at least 3 mm (1/8 in)")
    c.length("motor_stub_length", max(metric_or_inch(10.0, 0.375, c.unit), 1.5 * d_in),
             "1.5 input-shaft diameters, at least 10 mm (3/8 in): the motor's coupling")
    c.stated("housing_margin", 5.0, 0.2, "5 mm (0.2 in) of plate around the outermost bearing seats")
    return c.result()


def _rate(readers: Readers, data: Mapping[str, Any]) -> float | None:
    """The preload spring's rate (N/mm) from ``[preload]``, or None (the validating load names what is missing)."""
    try:
        return readers.preload(data.get("preload") or {}).preload_spring_linear
    except DesignError:
        return None


def _wire(c: Completion, readers: Readers, data, mean: float, shaft: float, ring: float, shear: float) -> float:
    """The ``spring_wire_diameter`` rule of the module docstring (mm), put; 0 without a rate to size from."""
    rate = _rate(readers, data)
    if rate is None:
        return 0.0
    for d in WIRE_DIAMETERS:
        if mean - d <= shaft or mean + d >= ring:
            break  # thicker wire leaves the ring's face
        coils = coil_rate(d, mean, 1.0, shear) / rate
        if coils >= MIN_ACTIVE_COILS:
            c.length("spring_wire_diameter", d, f"the thinnest music wire giving {rate:.4g} N/mm with at least "
                     f"{MIN_ACTIVE_COILS:g} active coils ({coils:.3g}) on {c.shown(mean)}", exact=True)
            return d
    raise DesignError(f"parts.spring_wire_diameter_{c.unit}", f"missing, and no standard music wire gives "
                      f"{rate:.4g} N/mm with {MIN_ACTIVE_COILS:g} active coils on the {c.shown(mean)} the input "
                      "bearing's ring holds", "spring_wire_diameter_* and spring_mean_diameter_* of your own, or a "
                      "stiffer [preload] preload_spring_stiffness_N_per_mm")


__all__ = ["complete", "MIN_ACTIVE_COILS"]
