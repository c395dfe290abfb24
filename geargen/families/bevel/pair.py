"""Backlash and tip clearance of a straight bevel pair, measured on the exact tooth outlines on a
sphere about the common apex (:func:`check_bevel_pair`).

Frame: apex at the origin, gear 1's axis +z, gear 2's axis in the xz plane at the shaft angle
Sigma from it; the pitch cones touch along the generator at polar angle delta1, azimuth 0 of
gear 1. At zero rotation gear 1 has a tooth centred on that generator and gear 2 a tooth space.
Both outlines are the exact ones of :func:`geargen.families.bevel.geometry.tooth_half_angle` (every tooth
surface is a cone through the apex, so one sphere serves for the whole face; the heel's is used).

Backlash: gear 1 is turned on its axis, gear 2 held, until a flank of gear 1 touches one of gear
2 (the deepest point of gear 1's flanks inside a gear 2 tooth, found on a dense sampling of the
exact flanks, crosses zero: bisection), both ways; the free angle times the heel pitch radius
R_e sin delta1 is the circumferential backlash at the heel pitch circle, which for thinnings t1,
t2 (arcs of the heel pitch circles) is t1 + t2 exactly. Tip clearance: the smallest arc on the
sphere, in gear 2's meridian, from gear 1's tip cone to gear 2's root cone, and the other way.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geargen.families.bevel.geometry import bevel_geometry, tooth_half_angle
from geargen.families.bevel.spec import BevelGearSpec
from geargen.errors import DesignError


@dataclass(frozen=True)
class BevelPairCheck:
    """Measured on the heel sphere (mm, rad): ``backlash`` circumferential at gear 1's heel pitch
    circle, ``backlash_expected`` t1 + t2, the free angles of gear 1 each way, and the tip
    clearances (gear 1's tip to gear 2's root and back)."""

    backlash: float
    backlash_expected: float
    free_angle_positive: float
    free_angle_negative: float
    tip_clearance_1: float
    tip_clearance_2: float


def mate_frame(shaft_angle: float) -> np.ndarray:
    """Rotation taking gear 2's frame (its axis +z) into gear 1's: about y by Sigma."""
    c, s = math.cos(shaft_angle), math.sin(shaft_angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _flank_points(spec: BevelGearSpec, samples: int) -> tuple[np.ndarray, np.ndarray]:
    """(polar, azimuth offset) of one tooth's two flanks from base/root to tip, ``(2 samples,)`` each."""
    g = bevel_geometry(spec)
    lo = max(g.root_cone_angle, g.base_cone_angle)
    th = np.linspace(lo, g.tip_cone_angle, samples)
    half = tooth_half_angle(spec, th)
    return np.concatenate([th, th]), np.concatenate([half, -half])


def _sph(polar, azimuth) -> np.ndarray:
    return _unit(np.sin(polar), np.cos(polar), azimuth)


def _unit(sin_polar, cos_polar, azimuth) -> np.ndarray:
    """:func:`_sph` with the polar angle's sine and cosine given (the flanks' own, read once)."""
    return np.stack([sin_polar * np.cos(azimuth), sin_polar * np.sin(azimuth), cos_polar], axis=-1)


@dataclass(frozen=True)
class _Reading:
    """Unit vectors read in a gear's frame once: polar angle, azimuth, whether within the tooth band,
    the tooth's half angle there and sin(polar) (all that :func:`_depth` needs but the phase)."""

    azimuth: np.ndarray
    inside: np.ndarray
    half: np.ndarray
    sin_polar: np.ndarray


def _reading(points: np.ndarray, spec: BevelGearSpec) -> _Reading:
    g = bevel_geometry(spec)
    th = np.arccos(np.clip(points[:, 2], -1, 1))
    return _Reading(np.arctan2(points[:, 1], points[:, 0]), (th >= g.root_cone_angle) & (th <= g.tip_cone_angle),
                    tooth_half_angle(spec, th), np.sin(th))


def _depth(r: _Reading, spec: BevelGearSpec, phase: float) -> float:
    """Deepest (angle, rad) of the read points inside one of the gear's teeth, the teeth centred at
    azimuth phase + k pitch; negative: none inside (distance to the nearest)."""
    ph = r.azimuth - phase
    pitch = 2 * math.pi / spec.teeth
    local = np.abs(ph - pitch * np.round(ph / pitch))
    return float(np.where(r.inside, (r.half - local) * r.sin_polar, -np.inf).max())


def _penetration(points: np.ndarray, spec: BevelGearSpec, phase: float) -> float:
    """Deepest (angle, rad) of unit vectors ``points`` (in the gear's frame) inside one of its teeth,
    the teeth centred at azimuth phase + k pitch; negative: none inside (distance to the nearest)."""
    return _depth(_reading(points, spec), spec, phase)


def check_bevel_pair(gear1: BevelGearSpec, gear2: BevelGearSpec, samples: int = 4000,
                     turn: float = 0.0) -> BevelPairCheck:
    """Measure backlash and tip clearance of the pair (see the module docstring), with gear 2 turned
    by ``turn`` (rad) on its axis and gear 1 by the ratio, so that any phase of the mesh is measured."""
    if (gear1.teeth, gear1.mate_teeth) != (gear2.mate_teeth, gear2.teeth) or abs(gear1.shaft_angle - gear2.shaft_angle) > 1e-12:
        raise DesignError("mate_teeth", "the two bevel gears are not each other's mate",
                          "gear1.mate_teeth = gear2.teeth, gear2.mate_teeth = gear1.teeth, the same shaft angle")
    if abs(gear1.cone_distance - gear2.cone_distance) > 1e-9 * gear1.cone_distance:
        raise DesignError("module", "the two bevel gears have different cone distances", "the same module")
    rot = mate_frame(gear1.shaft_angle)
    th1, off1 = _flank_points(gear1, samples)
    th2, off2 = _flank_points(gear2, samples)
    phase2 = math.pi + math.pi / gear2.teeth + turn  # at turn 0, a tooth space of gear 2 on the generator
    start = -turn * gear2.teeth / gear1.teeth  # gear 1 turned with it (the pitch cones roll)
    pitch1 = 2 * math.pi / gear1.teeth

    # gear 2 is held: its flank points in gear 1's frame are read once; only gear 1's phase moves
    gear2_in_1 = _reading(np.concatenate([_sph(th2, off2 + phase2 + k * 2 * math.pi / gear2.teeth) @ rot.T
                                          for k in (-1, 0, 1)]), gear1)
    sin1, cos1 = np.sin(th1), np.cos(th1)

    def overlaps(phi1: float) -> bool:
        # gear 2's flank points in gear 1's frame (read once: cheap), then gear 1's flank points (its
        # tooth nearest the generator and its neighbours) in gear 2's frame: whether either penetrates
        # (the second is not read when the first already does: only the answer is used)
        if _depth(gear2_in_1, gear1, phi1) > 0:
            return True
        p1 = np.concatenate([_unit(sin1, cos1, off1 + phi1 + k * pitch1) @ rot  # rot.T applied to row vectors
                             for k in (-1, 0, 1)])
        return _penetration(p1, gear2, phase2) > 0

    def contact(direction: float) -> float:
        lo, hi = start, start + direction * pitch1 / 2
        if overlaps(lo):
            return start
        for _ in range(45):  # pitch / 2^46: far below the sampling error
            mid = 0.5 * (lo + hi)
            if overlaps(mid):
                hi = mid
            else:
                lo = mid
        return lo

    plus, minus = contact(1.0), contact(-1.0)
    re = gear1.cone_distance
    g1, g2 = bevel_geometry(gear1), bevel_geometry(gear2)
    # tip cone of one to the root cone of the other, in the plane of the axes on the heel sphere
    c1 = re * (gear1.shaft_angle - g1.tip_cone_angle - g2.root_cone_angle)
    c2 = re * (gear1.shaft_angle - g2.tip_cone_angle - g1.root_cone_angle)
    plus, minus = plus - start, minus - start
    return BevelPairCheck(backlash=(plus - minus) * re * math.sin(g1.pitch_cone_angle),
                          backlash_expected=gear1.thinning + gear2.thinning, free_angle_positive=plus,
                          free_angle_negative=minus, tip_clearance_1=c1, tip_clearance_2=c2)


__all__ = ["BevelPairCheck", "check_bevel_pair"]
