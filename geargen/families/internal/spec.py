"""The ring (internal gear) as designed: :class:`InternalGearSpec`, the cylindrical gear
(:class:`geargen.design.gear.GearSpec`) whose teeth point inward, on a rim instead of a bore.

Its table is the cylindrical gear's (``kind = "internal"``, ``rim_diameter`` among its keys), read by
:func:`ring_from_table`. Tip and root follow ISO 21771 / KHK's convention for internal gears: the
tips point inward and x > 0 moves the profile outward.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar, Mapping

from geargen.design.gear import GearSpec, check_number, cylindrical_from_table
from geargen.errors import DesignError

#: ISO 6336-3 (rim thickness factor Y_B): an internal gear's rim needs s_R >= 3.5 m_n for Y_B = 1
INTERNAL_RIM_MODULES = 3.5
#: default tip radius of an internal gear's shaper cutter over m_n: 0.2 leaves a tip land on
#: cutters of 12 teeth and more (geargen.profile.internal)
INTERNAL_CUTTER_TIP_RADIUS = 0.2
#: the thinnest rim accepted (a ring, not a membrane), in normal modules
MIN_RIM_WALL_MODULES = 0.5


@dataclass(frozen=True)
class InternalGearSpec(GearSpec):
    """A ring: the cylindrical gear's keys, its ``rim_diameter`` (None: :func:`internal_rim_diameter`)
    and no bore, keyway or hub."""

    DEFAULT_TOOL_TIP_RADIUS: ClassVar[float] = INTERNAL_CUTTER_TIP_RADIUS  # its shaper cutter's
    kind: str = field(default="internal", init=False)

    def _check_rim_given(self) -> None:
        """A ring has a rim (checked with its body, :meth:`_check_body`)."""

    def _check_body(self) -> None:
        """A ring has no bore, keyway or hub; its rim must enclose the root circle with some wall."""
        h = self.hub
        if h.bore_diameter or h.hub_diameter or h.keyway_width:
            raise DesignError("bore_diameter", "an internal gear has no bore, keyway or hub", "0 (use rim_diameter)")
        least = 2 * self.root_radius_standard + 2 * MIN_RIM_WALL_MODULES * self.module
        if self.rim_diameter is None:
            object.__setattr__(self, "rim_diameter", internal_rim_diameter(self))
        check_number("rim_diameter", self.rim_diameter, least, 100000.0, "mm", length_unit=self.length_unit)

    @property
    def is_internal(self) -> bool:
        return True

    @property
    def tip_radius(self) -> float:
        """r - m_n (h_a* - x): the tips point inward."""
        return self.reference_radius - self.module * (self.addendum_coefficient - self.profile_shift)

    @property
    def root_radius_standard(self) -> float:
        """Root radius cut by the shaper cutter: r + m_n (h_f* + x)."""
        return self.reference_radius + self.module * (self.dedendum_coefficient + self.profile_shift)


def internal_rim_diameter(spec: GearSpec) -> float:
    """Default ring blank diameter (mm): root diameter + 2 x 3.5 m_n, the rim thickness from which
    ISO 6336-3 takes the rim thickness factor Y_B = 1 for internal gears."""
    return 2 * spec.root_radius_standard + 2 * INTERNAL_RIM_MODULES * spec.module


def ring_from_table(data: Mapping[str, Any], where: str = "gear", name: str | None = None,
                    length_unit: str | None = None) -> InternalGearSpec:
    """An :class:`InternalGearSpec` from a cylindrical gear table with ``kind = "internal"``."""
    return cylindrical_from_table(data, where, name, length_unit, InternalGearSpec)


__all__ = ["INTERNAL_CUTTER_TIP_RADIUS", "INTERNAL_RIM_MODULES", "MIN_RIM_WALL_MODULES", "InternalGearSpec",
           "internal_rim_diameter", "ring_from_table"]
