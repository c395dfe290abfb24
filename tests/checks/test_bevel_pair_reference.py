"""The bevel pair check (geargen.families.bevel.pair) reads the held gear's flanks once (issue 28);
against the reading it replaced, kept here as the reference (every flank point turned and read at
every bisection step), its free angles are the same to the last bit on the robot joint's placed
pair and on random pairs: the same float operations on every point, in the same order."""

import math
from pathlib import Path

import numpy as np
import pytest

from geargen.design.assembly import load_design
from geargen.drives.dual_pinion.bevel import bevel_drive
from geargen.drives.resolver import resolve
from geargen.families.bevel.geometry import bevel_geometry, tooth_half_angle
from geargen.families.bevel.pair import check_bevel_pair, mate_frame
from geargen.families.bevel.spec import BevelGearSpec

ASSEMBLIES = Path(__file__).resolve().parents[2] / "assemblies"


def reference_free_angles(gear1, gear2, samples=4000, turn=0.0):
    """(free angle +, free angle -) of gear 1 as geargen measured them before issue 28."""
    def flank_points(spec):
        g = bevel_geometry(spec)
        th = np.linspace(max(g.root_cone_angle, g.base_cone_angle), g.tip_cone_angle, samples)
        half = tooth_half_angle(spec, th)
        return np.concatenate([th, th]), np.concatenate([half, -half])

    def sph(polar, azimuth):
        return np.stack([np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)], axis=-1)

    def penetration(points, spec, phase):
        g = bevel_geometry(spec)
        th = np.arccos(np.clip(points[:, 2], -1, 1))
        ph = np.arctan2(points[:, 1], points[:, 0]) - phase
        pitch = 2 * math.pi / spec.teeth
        local = np.abs(ph - pitch * np.round(ph / pitch))
        inside = (th >= g.root_cone_angle) & (th <= g.tip_cone_angle)
        return float(np.where(inside, (tooth_half_angle(spec, th) - local) * np.sin(th), -np.inf).max())

    rot = mate_frame(gear1.shaft_angle)
    th1, off1 = flank_points(gear1)
    th2, off2 = flank_points(gear2)
    phase2 = math.pi + math.pi / gear2.teeth + turn
    start = -turn * gear2.teeth / gear1.teeth
    pitch1 = 2 * math.pi / gear1.teeth

    def overlap(phi1):
        worst = -np.inf
        for k in (-1, 0, 1):
            worst = max(worst, penetration(sph(th1, off1 + phi1 + k * pitch1) @ rot, gear2, phase2))
        for k in (-1, 0, 1):
            worst = max(worst, penetration(sph(th2, off2 + phase2 + k * 2 * math.pi / gear2.teeth) @ rot.T, gear1, phi1))
        return worst

    def contact(direction):
        lo, hi = start, start + direction * pitch1 / 2
        if overlap(lo) > 0:
            return start
        for _ in range(45):
            mid = 0.5 * (lo + hi)
            if overlap(mid) > 0:
                hi = mid
            else:
                lo = mid
        return lo

    return contact(1.0) - start, contact(-1.0) - start


def _same_as_reference(gear1, gear2, turn, samples=4000):
    r = check_bevel_pair(gear1, gear2, samples=samples, turn=turn)
    assert (r.free_angle_positive, r.free_angle_negative) == reference_free_angles(gear1, gear2, samples, turn)


def test_robot_joint_bevel_pair_reads_as_before():
    placed = bevel_drive(resolve(load_design(ASSEMBLIES / "robot_joint.toml")))
    for turn in (0.0, 0.013):
        _same_as_reference(placed.gear, placed.pinion, turn)


def test_random_bevel_pairs_read_as_before():
    rng = np.random.default_rng(28)
    for _ in range(4):
        z1, z2 = int(rng.integers(12, 30)), int(rng.integers(20, 60))
        sigma, x = rng.uniform(60, 120) * math.pi / 180, rng.uniform(-0.2, 0.2)
        t1, t2 = rng.uniform(0, 0.1, 2)
        a = BevelGearSpec(teeth=z1, mate_teeth=z2, module=2.5, face_width=12, thinning=t1, shaft_angle=sigma,
                          profile_shift=x)
        b = BevelGearSpec(teeth=z2, mate_teeth=z1, module=2.5, face_width=12, thinning=t2, shaft_angle=sigma,
                          profile_shift=-x)
        _same_as_reference(a, b, rng.uniform(-0.05, 0.05), samples=int(rng.integers(500, 4000)))
