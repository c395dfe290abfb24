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


def series_sizes(ideal: float, unit: str) -> list[float]:
    """The sizes (mm) of ``unit``'s series to try for the ideal diameter ``ideal`` (mm): the nearest
    first, then alternately either side of it, three steps each way (none below one step)."""
    step = PIN_SERIES[unit][0]
    n0 = round(ideal / step)
    return [n * step for n in (n0 + k for k in (0, 1, -1, 2, -2, 3, -3)) if n > 0]


def standard_pin(spec, unit: str | None = None) -> tuple[PinMeasurement, str]:
    """The measurement over the series' pin (ball) nearest the ideal diameter, and the series' text."""
    unit = unit or spec.length_unit
    last = None
    for size in series_sizes(ideal_pin_diameter(spec), unit):
        try:
            return over_pins_measurement(spec, size), PIN_SERIES[unit][1]
        except GeargenError as exc:
            last = exc
    raise last


__all__ = ["PIN_SERIES", "series_sizes", "standard_pin"]
