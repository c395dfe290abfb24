"""The robot joint's bevel pair, placed: the two toothed bevel gears' specs and their placements,
the one home of the numbers the solids, the mesh check and the stiffness model share.

From the ``[parts]`` bevel keys (teeth, pitch, face width along the cone; heel pitch circle of
the gear ``input_shaft_to_bevel`` above the input gear's mid-face, where
:func:`geargen.model.shafts.carriage_shafts` loads the input shaft) and the pair's backlash, the
``[parts] bevel_backlash`` or the ``[train] upstream_backlash_arcmin`` of this stage (rad at the
driven, input shaft) times the gear's heel pitch radius, split equally between the two thinnings (arcs of the heel pitch
circles: the pair's circumferential backlash is t1 + t2).

Placement (mm, the assembly frame of :mod:`geargen.model.layout`): a bevel solid has its apex at
its frame's origin, its axis +z and tooth 0 centred on azimuth 0 (:mod:`geargen.families.bevel.solid`).
The gear's axis is the input shaft's, its teeth below the apex (towards its heel); the pinion's
axis runs along +x from the apex. The frame of :mod:`geargen.families.bevel.pair` (gear 1 = the
gear, axis +z; gear 2 = the pinion, axis in the xz plane) is the assembly's turned half a turn
about x about the apex, and the phases are that check's at ``turn`` 0: a gear tooth on the pitch
generator, a pinion space on it (the teeth centred in the spaces, the backlash on both sides).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import partial
from typing import Any

import numpy as np

from geargen.families.bevel.spec import BevelGearSpec
from geargen.design.cluster import ClusterSpec
from geargen.errors import DesignError
from geargen.model.layout import Layout
from geargen.units import sizes_text


@dataclass(frozen=True)
class BevelDrive:
    """The placed bevel pair (mm, rad): specs, the common apex, each solid's 4x4 placement, the
    gear's heel height and the design backlash (circumferential at the heel pitch circles)."""

    gear: BevelGearSpec
    pinion: BevelGearSpec
    apex: tuple[float, float, float]
    gear_matrix: np.ndarray
    pinion_matrix: np.ndarray
    z_heel: float
    backlash: float


def _rotation(axis, angle: float) -> np.ndarray:
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    m = np.eye(4)
    m[:3, :3] = np.eye(3) * math.cos(angle) + math.sin(angle) * k + (1 - math.cos(angle)) * np.outer(a, a)
    return m


def bevel_backlash(layout: Layout, parts: dict[str, Any]) -> float:
    """The bevel pair's circumferential backlash at the gear's heel pitch circle (mm): [parts]
    ``bevel_backlash``, or the [train] ``upstream_backlash_arcmin`` of the stage
    ``pinion_teeth:gear_teeth`` of [layout] ``upstream_stages`` (rad at its driven shaft, the bevel
    gear's) times the gear's heel pitch radius; both given: they must agree."""
    size = partial(sizes_text, layout.identity.length_unit)  # lengths in messages: the design's unit
    zp, zg = parts["bevel_pinion_teeth"], parts["bevel_gear_teeth"]
    module = parts["bevel_module"] or 25.4 / parts["bevel_diametral_pitch_per_in"]
    stages = [tuple(p) for p in layout.settings.get("upstream_stages", ())]
    angles = layout.resolved.train.upstream_backlash
    train = None
    if (zp, zg) in stages and len(angles) > stages.index((zp, zg)):
        train = angles[stages.index((zp, zg))] * zg * module / 2
    given = parts.get("bevel_backlash")
    if given is None and train is None:
        raise DesignError("parts.bevel_backlash", f"the bevel pair {zp}:{zg} needs its backlash to cut its teeth",
                          f"a length, or [layout] upstream_stages holding [{zp}, {zg}] with its backlash in "
                          "[train] upstream_backlash_arcmin")
    if given is not None and train is not None and not math.isclose(given, train, rel_tol=1e-9):
        raise DesignError("parts.bevel_backlash", f"{size(given, digits=6)} differs from the [train] upstream_backlash_arcmin "
                          f"of the pair ({size(train, digits=6)} at the gear's heel pitch circle)", "one of the two, or equal")
    return train if given is None else given


def bevel_drive(layout: Layout, parts: dict[str, Any] | None = None) -> BevelDrive | None:
    """The robot joint's bevel pair as placed (see the module docstring); None for a design
    without one (no [parts] bevel keys, or [stages] driving the input)."""
    if not layout.resolved.has("parts") or layout.resolved.stages:
        return None
    s = layout.resolved.parts if parts is None else parts
    if s.get("bevel_pinion_teeth") is None:
        return None
    from geargen.drives.dual_pinion.shafts import carriage_shafts
    zp, zg = s["bevel_pinion_teeth"], s["bevel_gear_teeth"]
    module = s["bevel_module"] or 25.4 / s["bevel_diametral_pitch_per_in"]
    thinning = bevel_backlash(layout, s) / 2
    shaft = carriage_shafts(layout, s)["input"]
    spec_in = layout.gear("input").spec
    bore = (spec_in.large if isinstance(spec_in, ClusterSpec) else spec_in).hub.bore_diameter  # the input shaft
    unit = layout.identity.length_unit if layout.identity.length_unit in ("mm", "in") else "mm"
    common = dict(module=module, face_width=s["bevel_face_width"], thinning=thinning, length_unit=unit)
    gear = BevelGearSpec(teeth=zg, mate_teeth=zp, bore_diameter=bore, name="bevel_gear", **common)
    pinion = BevelGearSpec(teeth=zp, mate_teeth=zg, name="bevel_pinion", **common)
    x_in = float(shaft.centre[0])
    z_heel = shaft.loads["bevel_gear"]
    # the gear's heel pitch circle at z_heel, its apex above on the axis
    z_apex = z_heel + gear.cone_distance * math.cos(gear.pitch_cone_angle)
    apex = (x_in, float(shaft.centre[1]), z_apex)
    flip = _rotation((1, 0, 0), math.pi)
    flip[:3, 3] = apex
    pinion_matrix = flip @ _rotation((0, 1, 0), gear.shaft_angle) @ _rotation((0, 0, 1), math.pi + math.pi / zp)
    return BevelDrive(gear=gear, pinion=pinion, apex=apex, gear_matrix=flip, pinion_matrix=pinion_matrix,
                      z_heel=z_heel, backlash=2 * thinning)


__all__ = ["BevelDrive", "bevel_backlash", "bevel_drive"]
