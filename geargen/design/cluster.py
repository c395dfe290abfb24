"""A cluster gear: two gears on one shaft with a fixed angular relation between their teeth.

Axial layout (mm): the large gear's face runs from z = 0 to its face width, then an
``axial_gap`` (a plain spacer of ``spacer_diameter``), then the small gear's face.
``relative_phase`` (rad, counter-clockwise about +z) is the angle of the small gear's tooth 0
(in its lowest transverse section) from the large gear's tooth 0 (in the section z = 0); the
paper's clusters are made "with the same angular orientation", i.e. ``relative_phase = 0``.
Both gears share one bore (and keyway): their hubs must have the same bore and keyway; a hub
of the large gear extends below z = 0, one of the small gear above its top face.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from geargen.design.gear import GearSpec
from geargen.errors import DesignError


@dataclass(frozen=True)
class ClusterSpec:
    large: GearSpec
    small: GearSpec
    axial_gap: float = 0.0
    relative_phase: float = 0.0
    spacer_diameter: float | None = None  # None: 0.9 x the smaller root diameter
    name: str = "cluster"

    def __post_init__(self):
        if not math.isfinite(self.axial_gap) or self.axial_gap < 0:
            raise DesignError("axial_gap", f"{self.axial_gap} is out of range", ">= 0 mm")
        if not math.isfinite(self.relative_phase):
            raise DesignError("relative_phase", "must be a finite angle")
        a, b = self.large.hub, self.small.hub
        if (a.bore_diameter, a.keyway_width, a.keyway_depth) != (b.bore_diameter, b.keyway_width, b.keyway_depth):
            raise DesignError("small.bore_diameter", "the two gears of a cluster share one bore and keyway",
                              f"bore {a.bore_diameter} mm, keyway {a.keyway_width} x {a.keyway_depth} mm as the large gear")
        if self.axial_gap > 0:
            d = self.spacer_diameter_resolved
            lo = a.bore_diameter + 2 * a.keyway_depth
            hi = 2 * min(self.large.root_radius_standard, self.small.root_radius_standard)
            if not (lo < d <= hi):
                raise DesignError("spacer_diameter", f"{d:.6g} mm is out of range", f"({lo:.6g}, {hi:.6g}] mm")

    @property
    def spacer_diameter_resolved(self) -> float:
        if self.spacer_diameter is not None:
            return self.spacer_diameter
        return 0.9 * 2 * min(self.large.root_radius_standard, self.small.root_radius_standard)

    @property
    def length_unit(self) -> str:
        return self.large.length_unit

    @property
    def small_gear_z(self) -> float:
        """Height of the small gear's lowest face (mm)."""
        return self.large.face_width + self.axial_gap


__all__ = ["ClusterSpec"]
