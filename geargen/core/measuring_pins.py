"""The measuring pin or ball a shop has: the nearest size of the gauge-pin series to the ideal
diameter (the one touching the flanks at the reference circle, :func:`geargen.core.geometry.ideal_pin_diameter`).

Series (stated on the drawing and in the gear JSON): gauge pins are sold in sets stepping by
0.01 mm (metric sets) and 0.001 in (inch sets, ASME B89.1.5 gage pins); a metric design takes the
nearest 0.01 mm, an inch design the nearest 0.001 in. Measuring balls for helical gears are taken
from the same steps. Where the nearest size touches outside the usable involute, the next sizes
towards the ideal one are tried.
"""

from __future__ import annotations

from geargen.core.geometry import PinMeasurement, ideal_pin_diameter, over_pins_measurement
from geargen.errors import GeargenError

#: length unit -> (step in mm, the series as stated)
PIN_SERIES = {"mm": (0.01, "gauge pin sets in 0.01 mm steps"),
              "in": (0.0254, "gauge pin sets in 0.001 in steps (ASME B89.1.5)")}


def standard_pin(spec, unit: str | None = None) -> tuple[PinMeasurement, str]:
    """The measurement over the series' pin (ball) nearest the ideal diameter, and the series' text."""
    unit = unit or spec.length_unit
    step, series = PIN_SERIES[unit]
    ideal = ideal_pin_diameter(spec)
    n0 = round(ideal / step)
    # the nearest first, then alternately either side of it
    tried, last = [n0 + k for k in (0, 1, -1, 2, -2, 3, -3)], None
    for n in tried:
        if n <= 0:
            continue
        try:
            return over_pins_measurement(spec, n * step), series
        except GeargenError as exc:
            last = exc
    raise last


__all__ = ["PIN_SERIES", "standard_pin"]
