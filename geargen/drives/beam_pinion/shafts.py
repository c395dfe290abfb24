"""The beam-spring pinion's shafts placed (the C-axis, Fig. 12): the dual pinions' shafts in their
sliding quills, the long pinion's shaft on the bearings the beam-spring helper spaces, the housing
block's heights and the drive column under the long pinion's bearings (its stiffness is the beam's
support, :func:`beam_supports`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from geargen.errors import DesignError
from geargen.model.layout import Layout
from geargen.model.shafts import Bearing, Shaft, mid_face


def beam_pinion_shafts(layout: Layout, parts: dict[str, Any]) -> dict[str, Shaft]:
    """The C-axis dual pinions' shafts (Fig. 12): each slides in a quill whose two bearings,
    ``cluster_bearing_spacing`` apart, sit a ``bearing_clearance`` below the large gear; the
    large gear and, beyond it, the pinion meshing the bull gear are overhung above them. The
    shaft runs from its locknut (against the lower bearing's inner ring) to the pinion's top."""
    gap = parts["bearing_clearance"]
    width, outer = parts["cluster_bearing_width"], parts["cluster_bearing_outer_diameter"]
    out: dict[str, Shaft] = {}
    for side in ("a", "b"):
        large, small = layout.gear(f"cluster_large_{side}"), layout.gear(f"cluster_small_{side}")
        diameter = parts["cluster_shaft_diameter"]
        upper = Bearing(f"cluster_bearing_upper_{side}", large.height[0] - gap - width, width, diameter, outer)
        lower = Bearing(f"cluster_bearing_lower_{side}", upper.z - parts["cluster_bearing_spacing"], width, diameter, outer)
        z_nut = lower.z - parts["locknut_width"]
        loads = {g.name: mid_face(p, g) for p in (large, small) for g in p.gears}
        out[f"cluster_{side}"] = Shaft(f"cluster_shaft_{side}", tuple(small.centre), z_nut, small.height[1], diameter,
                                       (lower, upper), loads)
    out["input"] = beam_pinion_input_shaft(layout, parts)
    return out


def beam_pinion_input_shaft(layout: Layout, parts: dict[str, Any]) -> Shaft:
    """The long pinion's shaft: on its two bearings (:func:`beam_pinion_bearings`, at the span the
    beam-spring helper sizes), up through the upper one and a ``bearing_clearance`` into the
    coupling, which it fills for half the coupling's length. The motor's torque enters along that
    half and leaves at the meshes with the large gears: it twists from the middle of the one to the
    large gears' mid-face (engaged)."""
    from geargen.core.stiffness import sized_beam_pinion
    spec = layout.resolved.stiffness.beam_pinion
    if spec is None:
        raise DesignError("beam_pinion", "missing: the long pinion's span comes from it", "a [beam_pinion] section")
    span = sized_beam_pinion(layout.resolved.gears, spec).span
    width, outer, diameter = parts["input_bearing_width"], parts["input_bearing_outer_diameter"], \
        parts["input_shaft_diameter"]
    z_lo, z_hi = beam_pinion_bearings(layout, parts, span)
    lower = Bearing("input_bearing_lower", z_lo, width, diameter, outer)
    upper = Bearing("input_bearing_upper", z_hi, width, diameter, outer)
    in_coupling = parts["coupling_length"] / 2
    top = z_hi + width + parts["bearing_clearance"] + in_coupling
    z_mesh = z_lo + width / 2 + span / 2
    return Shaft("input_shaft", tuple(layout.gear("input").centre), z_lo, top, diameter, (lower, upper),
                 {"input": z_mesh}, twist=(z_mesh, top - in_coupling / 2))


def beam_pinion_bearings(layout: Layout, parts: dict[str, Any], span: float) -> tuple[float, float]:
    """Lower faces (z) of the long pinion's two bearings: ``span`` apart (the beam-spring helper's),
    symmetric about the large gears' engaged mid-face, so the slope at the mesh is zero."""
    large = layout.gear("cluster_large_a")
    z_mesh = sum(large.height) / 2 - layout.axial_shift.get("cluster_a", 0.0)
    width = parts["input_bearing_width"]
    return z_mesh - span / 2 - width / 2, z_mesh + span / 2 - width / 2


def housing_heights(layout: Layout, parts: dict[str, Any], engagement) -> tuple[float, float]:
    """(bottom, top) of the C-axis housing block the quills slide in: its top a clearance below the
    lowest a large gear comes (the trailer retracted, ``engagement``'s strokes), its thickness
    ``housing_thickness``."""
    strokes = {"a": -engagement.leader_retracted_stop, "b": -engagement.trailer_retracted_stop}
    top = min(layout.gear(f"cluster_large_{side}").height[0] - layout.axial_shift.get(f"cluster_{side}", 0.0)
              - strokes[side] for side in ("a", "b")) - parts["bearing_clearance"]
    return top - parts["housing_thickness"], top


@dataclass(frozen=True)
class DriveColumn:
    """The C-axis drive column: a bar ``width`` x ``thickness`` (the thickness along the preload
    motion, x) bolted to the housing block's end face over ``clamp`` (z range), carrying the long
    pinion's bearing plates at ``supports`` (their mid-widths, lower and upper)."""

    width: float
    thickness: float
    clamp: tuple[float, float]
    supports: tuple[float, float]

    def support_stiffness(self, elastic_modulus: float) -> tuple[float, float]:
        """Radial stiffness (N/mm, along x) the column gives each bearing: a cantilever from the
        clamp's nearer edge, ``3 E I / h^3`` with ``I = width thickness^3 / 12``; the bearing plates
        (loaded in their plane) and the bolted joint taken as rigid. Infinite inside the clamp."""
        second_moment = self.width * self.thickness ** 3 / 12
        out = []
        for z in self.supports:
            h = max(self.clamp[0] - z, z - self.clamp[1], 0.0)
            out.append(math.inf if h == 0.0 else 3 * elastic_modulus * second_moment / h ** 3)
        return out[0], out[1]


def drive_column(layout: Layout, parts: dict[str, Any], span: float, engagement) -> DriveColumn:
    """The column as the solids are built (:func:`beam_pinion_bearings`, :func:`housing_heights`)."""
    width = parts["input_bearing_width"]
    return DriveColumn(parts["drive_column_width"], parts["drive_column_thickness"],
                       housing_heights(layout, parts, engagement),
                       tuple(z + width / 2 for z in beam_pinion_bearings(layout, parts, span)))


def beam_supports(layout: Layout, engagement) -> tuple[float, float] | None:
    """Radial stiffness (N/mm) of the drive column under the long pinion's two bearings
    (:func:`drive_column`) where the design builds one and the sliding pinions' strokes
    (``engagement``, which set the housing block's height) are known; else None (rigid supports)."""
    if engagement is None or not layout.resolved.has("parts"):
        return None
    from geargen.core.stiffness import sized_beam_pinion
    parts = layout.resolved.parts
    sd = layout.resolved.stiffness
    span = sized_beam_pinion(layout.resolved.gears, sd.beam_pinion).span
    return drive_column(layout, parts, span, engagement).support_stiffness(sd.beam_pinion.elastic_modulus)


__all__ = ["DriveColumn", "beam_pinion_shafts", "beam_pinion_input_shaft", "beam_pinion_bearings", "housing_heights",
           "drive_column", "beam_supports"]
