"""Shafts and their bearings, placed: the one home of every length the solids and the stiffness
model share (bearing positions, spans, where each gear loads its shaft, shaft diameters).

The CAD layer builds the shafts and bearing rings at exactly these positions, and
:mod:`geargen.model.analysis` sizes the shaft components of the stiffness model from them, so
moving a bearing in the design moves the solid and changes the stiffness together.

Frame as :mod:`geargen.model.layout` (mm, z along the gear axes). A bearing is a ring of
``width`` whose lower face is at ``z``; it supports the shaft at its mid-width.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from geargen.design.cluster import ClusterSpec
from geargen.model.layout import Layout


@dataclass(frozen=True)
class Bearing:
    """A rolling bearing on a shaft (mm): lower face at ``z``, ``width``, ``bore`` x ``outer_diameter``."""

    name: str
    z: float
    width: float
    bore: float
    outer_diameter: float

    @property
    def centre_z(self) -> float:
        """Where it supports the shaft: the middle of its width."""
        return self.z + self.width / 2


@dataclass(frozen=True)
class Shaft:
    """A rotating shaft (mm): on the axis through ``centre``, from ``z_lo`` to ``z_hi``, of
    ``diameter``, carried by ``bearings``; ``loads`` maps each gear (by role) on it to the height
    of its face's middle, where its mesh force acts."""

    name: str  # the solid's part name
    centre: tuple[float, float]
    z_lo: float
    z_hi: float
    diameter: float
    bearings: tuple[Bearing, ...]
    loads: dict[str, float]

    @property
    def length(self) -> float:
        return self.z_hi - self.z_lo

    @property
    def span(self) -> float:
        """Distance between the outermost bearings' support points."""
        zs = [b.centre_z for b in self.bearings]
        return max(zs) - min(zs)

    def load_position(self, gear: str) -> float:
        """Distance of ``gear``'s mid-face from the lower support (inside the span when between them)."""
        return self.loads[gear] - min(b.centre_z for b in self.bearings)

    def distance(self, gear_a: str, gear_b: str) -> float:
        """Length of shaft twisting between two gears' mid-faces."""
        return abs(self.loads[gear_a] - self.loads[gear_b])


def _bore(spec) -> float:
    s = spec.large if isinstance(spec, ClusterSpec) else spec
    return s.hub.bore_diameter


def _mid(placed, gear) -> float:
    z0, z1 = placed.face_z(gear)
    return (z0 + z1) / 2


def robot_joint_shafts(layout: Layout, parts: dict[str, Any]) -> dict[str, Shaft]:
    """The robot joint's shafts (Fig. 10): each cluster's, the output's and the input's, with two
    bearings each a ``bearing_clearance`` beyond the faces of the gears they carry. ``parts``:
    the ``[parts]`` settings (:func:`geargen.design.parts.parts_settings`)."""
    gap = parts["bearing_clearance"]
    by = {p.name: p for p in layout.gears}
    out: dict[str, Shaft] = {}

    def on_shaft(name, bearing_names, members, width, outer):
        z0 = min(p.height[0] for p in members)
        z1 = max(p.height[1] for p in members)
        diameter = _bore(members[0].spec)  # the shaft fills the gears' bore
        lower = Bearing(bearing_names[0], z0 - gap - width, width, diameter, outer)
        upper = Bearing(bearing_names[1], z1 + gap, width, diameter, outer)
        loads = {g.name: _mid(p, g) for p in members for g in p.gears}
        return Shaft(name, tuple(members[0].centre), lower.z, upper.z + width, diameter, (lower, upper), loads)

    for side in ("a", "b"):
        members = [p for p in layout.gears if p.group == f"cluster_{side}"]
        out[f"cluster_{side}"] = on_shaft(f"cluster_shaft_{side}", (f"cluster_bearing_lower_{side}",
                                                                    f"cluster_bearing_upper_{side}"), members,
                                          parts["cluster_bearing_width"], parts["cluster_bearing_outer_diameter"])
    out["output"] = on_shaft("output_shaft", ("output_bearing_lower", "output_bearing_upper"), [by["output"]],
                             parts["output_bearing_width"], parts["output_bearing_outer_diameter"])
    shaft = on_shaft("input_shaft", ("input_bearing_lower", "input_bearing_upper"), [by["input"]],
                     parts["input_bearing_width"], parts["input_bearing_outer_diameter"])
    # the input shaft runs on to the bevel gear, whose heel is input_shaft_to_bevel above the input's mid-face
    bevel_heel = shaft.loads["input"] + parts["input_shaft_to_bevel"]
    out["input"] = Shaft(shaft.name, shaft.centre, shaft.z_lo, shaft.z_hi, shaft.diameter, shaft.bearings,
                         {**shaft.loads, "bevel_gear": bevel_heel})
    return out


def c_axis_shafts(layout: Layout, parts: dict[str, Any]) -> dict[str, Shaft]:
    """The C-axis dual pinions' shafts (Fig. 12): each slides in a quill whose two bearings,
    ``cluster_bearing_spacing`` apart, sit a ``bearing_clearance`` below the large gear; the
    large gear and, beyond it, the pinion meshing the bull gear are overhung above them. The
    shaft runs from its stop collar (a clearance below the lower bearing) to the pinion's top."""
    gap = parts["bearing_clearance"]
    width, outer = parts["cluster_bearing_width"], parts["cluster_bearing_outer_diameter"]
    out: dict[str, Shaft] = {}
    for side in ("a", "b"):
        large, small = layout.gear(f"cluster_large_{side}"), layout.gear(f"cluster_small_{side}")
        diameter = parts["cluster_shaft_diameter"]
        upper = Bearing(f"cluster_bearing_upper_{side}", large.height[0] - gap - width, width, diameter, outer)
        lower = Bearing(f"cluster_bearing_lower_{side}", upper.z - parts["cluster_bearing_spacing"], width, diameter, outer)
        z_collar = lower.z - gap - parts["stop_collar_width"]
        loads = {g.name: _mid(p, g) for p in (large, small) for g in p.gears}
        out[f"cluster_{side}"] = Shaft(f"cluster_shaft_{side}", tuple(small.centre), z_collar, small.height[1], diameter,
                                       (lower, upper), loads)
    return out


#: the shafts of each parts template that the model places
SHAFT_BUILDERS = {"robot_joint": robot_joint_shafts, "c_axis": c_axis_shafts}


def shafts(layout: Layout) -> dict[str, Shaft]:
    """The placed shafts of the resolved drive (empty where its parts template has none here yet)."""
    from geargen.design.parts import parts_settings
    if not layout.design.section("parts"):
        return {}
    parts = parts_settings(layout.design)
    builder = SHAFT_BUILDERS.get(parts["template"])
    return builder(layout, parts) if builder is not None else {}


__all__ = ["Bearing", "Shaft", "robot_joint_shafts", "c_axis_shafts", "shafts", "SHAFT_BUILDERS"]
