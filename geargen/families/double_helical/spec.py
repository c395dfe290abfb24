"""The double-helical gear as designed: :class:`DoubleHelicalGearSpec`, the cylindrical gear
(:class:`geargen.design.gear.GearSpec`) cut as two helical halves of opposite hand, with a centre
gap between them (a relief groove at the root diameter; 0 is a herringbone whose flanks meet at
the apex).

Its table is the cylindrical gear's (``kind = "double_helical"``, ``centre_gap`` among its keys),
read by :func:`double_helical_from_table`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

from geargen.design.gear import GearSpec, cylindrical_from_table
from geargen.errors import DesignError
from geargen.units import length_text


@dataclass(frozen=True)
class DoubleHelicalGearSpec(GearSpec):
    """Two helical halves of opposite hand, each ``(face_width - centre_gap) / 2`` wide."""

    kind: str = field(default="double_helical", init=False)

    def _check_halves(self) -> None:
        """The centre gap leaves both halves some face; a double-helical gear needs a helix (with
        none it would be a spur gear in two pieces)."""
        gap = self.centre_gap
        if not (isinstance(gap, (int, float)) and math.isfinite(gap) and 0 <= gap < self.face_width):
            written = length_text(gap, self.length_unit, 6) if isinstance(gap, (int, float)) else repr(gap)
            raise DesignError("centre_gap", f"{written} is out of range",
                              f"[0, {length_text(self.face_width, self.length_unit, 6)}) (below the face width)")
        if not self.helix_angle > 0:
            raise DesignError("helix_angle", "a double_helical gear needs a helix", "(0, 45] deg")

    @property
    def half_face_width(self) -> float:
        """Face width of each helical half, (b - gap) / 2 (mm)."""
        return (self.face_width - self.centre_gap) / 2

    @property
    def half_hands(self) -> tuple[str, ...]:
        """Hand of each half from z = 0 up: the first has the spec's hand, the second the other one."""
        return (self.hand, "left" if self.hand == "right" else "right")


def double_helical_from_table(data: Mapping[str, Any], where: str = "gear", name: str | None = None,
                              length_unit: str | None = None) -> DoubleHelicalGearSpec:
    """A :class:`DoubleHelicalGearSpec` from a cylindrical gear table with ``kind = "double_helical"``."""
    return cylindrical_from_table(data, where, name, length_unit, DoubleHelicalGearSpec)


__all__ = ["DoubleHelicalGearSpec", "double_helical_from_table"]
