"""Shafts and their bearings, placed: the one home of every length the solids and the stiffness
model share (bearing positions, spans, where each gear loads its shaft, shaft diameters).

The CAD layer builds the shafts and bearing rings at exactly these positions, and
:mod:`geargen.model.analysis` sizes the shaft components of the stiffness model from them, so
moving a bearing in the design moves the solid and changes the stiffness together. A drive kind
places its own shafts with these (``geargen/drives/<kind>/shafts.py``, :attr:`DriveKind.shafts`).

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
    """A support of a shaft (mm): lower face at ``z``, ``width``, ``bore`` x ``outer_diameter``.

    A rolling bearing to the structure, or (``via`` = another placed shaft's name) a part that
    holds this shaft on that shaft (the split pinion's clamp collar on the hollow shaft): its
    radial support is then that shaft's lateral compliance at this height."""

    name: str
    z: float
    width: float
    bore: float
    outer_diameter: float
    via: str | None = None

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
    bore: float = 0.0  # a hollow shaft's bore
    # heights between which the shaft twists, where they are not the first two loads' mid-faces
    # (the split pinion's inner shaft: from its clamp collar's face to the compliant pinion's face)
    twist: tuple[float, float] | None = None

    @property
    def length(self) -> float:
        return self.z_hi - self.z_lo

    @property
    def twist_length(self) -> float:
        """Length of shaft twisting between the torque's way in and out."""
        if self.twist is not None:
            return abs(self.twist[1] - self.twist[0])
        first, second = list(self.loads)[:2]
        return self.distance(first, second)

    @property
    def lower_support(self) -> float:
        return min(b.centre_z for b in self.bearings)

    def supports(self) -> tuple[Bearing, ...]:
        """The bearings from the lowest up."""
        return tuple(sorted(self.bearings, key=lambda b: b.centre_z))

    @property
    def span(self) -> float:
        """Distance between the outermost bearings' support points."""
        zs = [b.centre_z for b in self.bearings]
        return max(zs) - min(zs)

    def load_position(self, gear: str) -> float:
        """Distance of ``gear``'s mid-face from the lower support (inside the span when between them)."""
        return self.loads[gear] - self.lower_support

    def distance(self, gear_a: str, gear_b: str) -> float:
        """Length of shaft twisting between two gears' mid-faces."""
        return abs(self.loads[gear_a] - self.loads[gear_b])


def bore_of(spec) -> float:
    s = spec.large if isinstance(spec, ClusterSpec) else spec
    return s.hub.bore_diameter


def mid_face(placed, gear) -> float:
    z0, z1 = placed.face_z(gear)
    return (z0 + z1) / 2


def loop_shafts(gears, parts: dict[str, Any]) -> dict[str, Shaft]:
    """The robot joint's loop shafts (Fig. 10) from its placed loop ``gears``
    (:class:`~geargen.model.layout.GearPlacement`): each cluster's, the output's and the
    input's, with two bearings each a ``bearing_clearance`` beyond the faces of the gears they
    carry. ``parts``: the ``[parts]`` settings (:func:`geargen.design.parts.parts_settings`)."""
    gap = parts["bearing_clearance"]
    gears = list(gears)
    by = {p.name: p for p in gears}
    out: dict[str, Shaft] = {}

    def on_shaft(name, bearing_names, members, width, outer):
        z0 = min(p.height[0] for p in members)
        z1 = max(p.height[1] for p in members)
        diameter = bore_of(members[0].spec)  # the shaft fills the gears' bore
        lower = Bearing(bearing_names[0], z0 - gap - width, width, diameter, outer)
        upper = Bearing(bearing_names[1], z1 + gap, width, diameter, outer)
        loads = {g.name: mid_face(p, g) for p in members for g in p.gears}
        return Shaft(name, tuple(members[0].centre), lower.z, upper.z + width, diameter, (lower, upper), loads)

    for side in ("a", "b"):
        members = [p for p in gears if p.group == f"cluster_{side}"]
        out[f"cluster_{side}"] = on_shaft(f"cluster_shaft_{side}", (f"cluster_bearing_lower_{side}",
                                                                    f"cluster_bearing_upper_{side}"), members,
                                          parts["cluster_bearing_width"], parts["cluster_bearing_outer_diameter"])
    out["output"] = on_shaft("output_shaft", ("output_bearing_lower", "output_bearing_upper"), [by["output"]],
                             parts["output_bearing_width"], parts["output_bearing_outer_diameter"])
    out["input"] = on_shaft("input_shaft", ("input_bearing_lower", "input_bearing_upper"), [by["input"]],
                            parts["input_bearing_width"], parts["input_bearing_outer_diameter"])
    return out


def shafts(layout: Layout) -> dict[str, Shaft]:
    """The placed shafts of the resolved drive, as its kind places them (:attr:`geargen.drives.kind.DriveKind.shafts`;
    empty without a [parts] table or for a kind that places none here)."""
    if not layout.resolved.has("parts") or layout.drive is None or layout.drive.shafts is None:
        return {}
    return layout.drive.shafts(layout, layout.resolved.parts)


__all__ = ["Bearing", "Shaft", "loop_shafts", "mid_face", "shafts", "bore_of"]
