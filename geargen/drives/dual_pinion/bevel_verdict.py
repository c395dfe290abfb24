"""The bevel pair of an assembly as placed: apexes, shaft angle and tooth phases read from the two
parts' placements, then backlash measured on the exact outlines (:func:`check_placed_bevel_pair`).

Each bevel solid has its apex at its frame's origin, its axis +z and tooth 0 centred on azimuth 0
(:mod:`geargen.families.bevel.solid`). :func:`geargen.families.bevel.pair.check_bevel_pair` measures a
pair in its own frame (gear 1's axis +z, gear 2's axis in the xz plane) with gear 2 turned by
``turn`` and gear 1 rolled with it; a placement is brought to that frame, ``turn`` read from gear
2's phase, and gear 1's departure ``offset`` from the rolled position shifts the free play of
the two sides (the measured free angles are taken from the rolled position).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geargen.families.bevel.pair import BevelPairCheck, mate_frame, check_bevel_pair
from geargen.checks.results import Failure
from geargen.families.bevel.spec import BevelGearSpec
from geargen.drives.dual_pinion.bevel import bevel_drive
from geargen.errors import GeometryError
from geargen.units import LENGTH_SUFFIXES


@dataclass(frozen=True)
class PlacedBevelCheck:
    """The placed pair (mm, rad): apex distance, shaft angle, gear 1's phase offset from the
    rolled position, the free play each way at gear 1's heel pitch circle (circumferential) and
    the exact check at the placed phase (``pair``)."""

    apex_distance: float
    shaft_angle: float
    offset: float
    play_positive: float
    play_negative: float
    pair: BevelPairCheck

    @property
    def backlash(self) -> float:
        return self.play_positive + self.play_negative


def _wrap(angle: float, period: float) -> float:
    """``angle`` reduced to [-period/2, period/2)."""
    return (angle + period / 2) % period - period / 2


def check_placed_bevel_pair(gear1: BevelGearSpec, matrix1: np.ndarray, gear2: BevelGearSpec, matrix2: np.ndarray,
                            apex_tolerance: float = 1e-6, angle_tolerance: float = 1e-9,
                            samples: int = 4000) -> PlacedBevelCheck:
    """Check the pair placed by the 4x4 matrices (solid frame to assembly frame, mm). Raises
    GeometryError (kind ``bevel_placement``) when the apexes do not coincide or the axes are not at
    the shaft angle: the exact check would not describe the parts."""
    m1, m2 = np.asarray(matrix1, float), np.asarray(matrix2, float)
    apex = float(np.linalg.norm(m1[:3, 3] - m2[:3, 3]))
    if apex > apex_tolerance:
        raise GeometryError("bevel_placement", f"the bevel pair's cone apexes are {apex:.4g} mm apart")
    rel = m1[:3, :3].T @ m2[:3, :3]  # gear 2's frame in gear 1's
    axis2 = rel[:, 2]
    shaft = math.acos(max(-1.0, min(1.0, axis2[2])))
    if abs(shaft - gear1.shaft_angle) > angle_tolerance:
        raise GeometryError("bevel_placement", f"the bevel pair's axes are at {math.degrees(shaft):.6g} deg, the "
                            f"gears are cut for {math.degrees(gear1.shaft_angle):.6g} deg")
    # turn gear 1's frame so that gear 2's axis lies in its xz plane (the check's frame)
    alpha = math.atan2(axis2[1], axis2[0])
    ca, sa = math.cos(alpha), math.sin(alpha)
    rz = np.array([[ca, -sa, 0.0], [sa, ca, 0.0], [0.0, 0.0, 1.0]])
    own2 = mate_frame(gear1.shaft_angle).T @ rz.T @ rel  # what is left: gear 2 turned about its own axis
    gamma = math.atan2(own2[1, 0], own2[0, 0])
    pitch1, pitch2 = 2 * math.pi / gear1.teeth, 2 * math.pi / gear2.teeth
    turn = _wrap(gamma - math.pi - math.pi / gear2.teeth, pitch2)
    offset = _wrap(-alpha + turn * gear2.teeth / gear1.teeth, pitch1)  # gear 1's tooth 0 sits at azimuth -alpha
    pair = check_bevel_pair(gear1, gear2, samples=samples, turn=turn)
    r1 = gear1.cone_distance * math.sin(gear1.pitch_cone_angle)
    return PlacedBevelCheck(apex_distance=apex, shaft_angle=shaft, offset=offset,
                            play_positive=(pair.free_angle_positive - offset) * r1,
                            play_negative=(offset - pair.free_angle_negative) * r1, pair=pair)


#: the placed bevel pair's measured backlash may differ from its design value (t1 + t2) by this
#: much (mm): the bisection on the sampled exact flanks (geargen.families.bevel.pair) is far finer
BEVEL_BACKLASH_TOLERANCE = 1e-4


def rows(layout, result) -> list[dict]:
    """The robot joint's bevel pair as placed (:mod:`geargen.drives.dual_pinion.bevel`): backlash each way
    and tip clearances on the exact outlines on the heel sphere
    (:func:`geargen.drives.dual_pinion.bevel_verdict.check_placed_bevel_pair`); a failure when the flanks overlap,
    a tip reaches the mate's root, there is no backlash, or it is not the design value."""
    placed = bevel_drive(layout)
    if placed is None:
        return []
    name = "bevel"
    k, unit = LENGTH_SUFFIXES[layout.identity.length_unit], layout.identity.length_unit
    c = check_placed_bevel_pair(placed.gear, placed.gear_matrix, placed.pinion, placed.pinion_matrix)
    clearance = min(c.pair.tip_clearance_1, c.pair.tip_clearance_2)
    if min(c.play_positive, c.play_negative) < 0:
        side = min(c.play_positive, c.play_negative)
        result.failures.append(Failure("flank_interference", name, f"the bevel teeth overlap by {-side / k:.4g} {unit} "
                                       "(circumferential at the heel pitch circle)", "circumferential_backlash",
                                       side, 0.0))
    elif min(c.play_positive, c.play_negative) == 0:
        result.failures.append(Failure("no_backlash", name, "the bevel flanks touch on both sides",
                                       "circumferential_backlash", 0.0, 0.0))
    if clearance <= 0:
        result.failures.append(Failure("tip_to_root_interference", name, f"a bevel tip reaches the mate's root cone "
                                       f"({clearance / k:.4g} {unit})", "min_clearance", clearance, 0.0))
    if abs(c.backlash - placed.backlash) > BEVEL_BACKLASH_TOLERANCE:
        result.failures.append(Failure("backlash_out_of_range", name,
                                       f"bevel backlash {c.backlash / k:.6g} {unit} is not the design's "
                                       f"{placed.backlash / k:.6g} {unit}", "circumferential_backlash",
                                       c.backlash, placed.backlash))
    return [dict(table="bevel", mesh=name, gear1="bevel_gear", gear2="bevel_pinion", backlash=c.backlash,
                 design_backlash=placed.backlash, play_positive=c.play_positive, play_negative=c.play_negative,
                 tip_clearance=clearance, apex_distance=c.apex_distance, shaft_angle=c.shaft_angle,
                 where="heel pitch circle, circumferential, on the exact spherical-involute outlines")]


__all__ = ["PlacedBevelCheck", "check_placed_bevel_pair", "rows", "BEVEL_BACKLASH_TOLERANCE"]
