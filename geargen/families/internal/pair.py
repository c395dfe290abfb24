"""Geometric checks of an internal pair (external pinion inside a ring), on the exact outlines.

Frame: the ring's centre at the origin, its space 0 centred on +x (section z = 0); the pinion's
centre at ``(a, 0)``, its tooth 0 on +x, so that at mesh position 0 pinion tooth 0 sits centred in
ring space 0 at the pitch point. Mesh position ``phi`` turns the pinion by ``phi`` and the ring by
``phi z1 / z2``, both counter-clockwise (an internal pair turns one way).

The named interferences of an internal pair, each with its published rule (KHK "Gear Technical
Reference", section 4.6 "Interference in internal gearing"; the same formulas in SDP/SI "Elements
of Metric Gear Technology", section 5.2) and a margin (positive: passes):

- ``involute_interference``: the ring's tip engages the pinion where the pinion's flank stands
  proud of its involute, or below its base circle (KHK: ``z1 / z2 >= 1 - tan(a_a2) / tan(a_w)``).
  Stricter than KHK: a generated fillet stands proud of the involute extended below the form
  circle, so against a fillet joint the limit is the pinion's form radius. An undercut is a
  recess (the rack tip cut into the involute): the ring's tip runs over it without touching, so
  against an undercut pinion the limit is the base circle (:func:`undercut_recess` measures the
  recess on the exact outline; contact stops at the involute's start, which a note says). Margin:
  mm along the line of action.
- ``tip_to_root_interference``: the pinion's tip engages the ring beyond its usable involute (its
  cutter-generated fillet), or a tip circle reaches the mate's root circle (radial clearance).
  Margin: mm.
- ``trochoid_interference``: leaving mesh, the path of the pinion's tip corner cuts the ring's tip
  corner: ``theta1 z1 / z2 + inv a_w - inv a_a2 >= theta2`` with ``theta1 = acos((ra2^2 - ra1^2 -
  a^2) / (2 a ra1)) + inv a_a1 - inv a_w`` and ``theta2 = acos((a^2 + ra2^2 - ra1^2) / (2 a ra2))``.
  Margin: rad of the ring.
- ``radial_assembly_fouling`` (KHK's "trimming"): the pinion cannot be moved into mesh along the
  line of centres. Found on the exact outlines: the pinion slid from the ring's axis to ``(a, 0)``
  at each of ``phases`` mesh phases of one pitch; the pair passes if one phase slides in freely.

:func:`free_play` measures the backlash on the exact outlines (the pinion turned both ways from a
mesh position until it touches the ring), for comparison with the closed form.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from geargen.checks.results import Failure
from geargen.families.internal.geometry import InternalPairGeometry, internal_pair_geometry, line_of_action_roll
from geargen.core.involute import involute, roll_length
from geargen.design.gear import GearSpec, with_changes
from geargen.errors import GeargenError
from geargen.profile.internal import InternalProfile, internal_profile
from geargen.profile.segments import sample_outline
from geargen.profile.tooth import ToothProfile, tooth_profile


class RingMaterial:
    """Inside-test of the ring's teeth in the ring frame: :meth:`depth` of points (mm, positive
    inside the ring's material). Exact on the involutes (polar form), on the fillet interpolated
    in radius from 4001 exact points (the fillet is monotone in radius)."""

    def __init__(self, ring: InternalProfile):
        self.ring = ring
        fillet = next(s for s in ring.segments if s.kind == "fillet" and s.side == "upper")
        pts = fillet.point(np.linspace(fillet.t1, fillet.t0, 4001))  # form circle -> root
        self._r = np.hypot(pts[:, 0], pts[:, 1])
        self._ang = np.arctan2(pts[:, 1], pts[:, 0])

    def half_angle(self, radius: np.ndarray) -> np.ndarray:
        """Half angle of the ring's space at ``radius`` (rad); -1 beyond the root circle."""
        ring = self.ring
        r = np.asarray(radius, dtype=float)
        inv = (r >= ring.base_radius) & (r <= ring.form_radius)
        if inv.all():  # every radius on the involute (free_play's points past the tip circle): as below, at once
            with np.errstate(invalid="ignore"):
                alpha = np.arccos(np.clip(ring.base_radius / r, -1.0, 1.0))
            return ring.space_base_half_angle - involute(alpha)
        out = np.full(r.shape, -1.0)
        with np.errstate(invalid="ignore"):
            alpha = np.arccos(np.clip(ring.base_radius / r[inv], -1.0, 1.0))
        out[inv] = ring.space_base_half_angle - involute(alpha)
        fil = (r > ring.form_radius) & (r <= ring.root_radius)
        out[fil] = np.interp(r[fil], self._r, self._ang)
        return out

    def depth(self, xy: np.ndarray, rotation: float = 0.0) -> np.ndarray:
        """Signed depth (mm) of points ``(n, 2)`` in the ring (turned by ``rotation``): the smaller of
        the radial depth below the tip circle and the arc depth past the space's flank."""
        r = np.hypot(xy[:, 0], xy[:, 1])
        ang = np.arctan2(xy[:, 1], xy[:, 0]) - rotation
        pitch = self.ring.pitch_angle
        local = np.abs(ang - np.round(ang / pitch) * pitch)
        return np.minimum(r - self.ring.tip_radius, r * (local - self.half_angle(r)))


#: (id of a profile, step) -> (the profile, kept alive so that its id stays its own; its outline)
_OUTLINES: dict[tuple[int, float], tuple[ToothProfile, np.ndarray]] = {}


def pinion_points(profile: ToothProfile, step: float) -> np.ndarray:
    """The pinion's whole exact outline sampled at most ``step`` mm apart, ``(n, 2)``, pinion frame.
    Sampled once per profile and step (a sweep over mesh positions and a stage's planets read one
    outline many times) and handed out read-only."""
    key = (id(profile), step)
    kept = _OUTLINES.get(key)
    if kept is None:
        if len(_OUTLINES) >= 64:
            _OUTLINES.clear()
        points = sample_outline(profile.outline(), step)
        points.setflags(write=False)
        kept = _OUTLINES[key] = (profile, points)
    return kept[1]


def placed_points(points: np.ndarray, centre: tuple[float, float], turn: float) -> np.ndarray:
    """``points`` ``(n, 2)`` turned by ``turn`` about the origin, then moved to ``centre``."""
    c, s = math.cos(turn), math.sin(turn)
    return np.column_stack([centre[0] + c * points[:, 0] - s * points[:, 1],
                            centre[1] + s * points[:, 0] + c * points[:, 1]])


def _max_depth(material: RingMaterial, pts, a, z1, z2, phase, turn) -> float:
    placed = placed_points(pts, (a, 0.0), phase + turn)
    return float(np.max(material.depth(placed, phase * z1 / z2)))


def _reaching(pts: np.ndarray, a: float, turn: float, half_width: float, tip_radius: float) -> np.ndarray:
    """The pinion points that can reach the ring's tip circle while the pinion turns within
    ``half_width`` (rad) of ``turn``: the others have a negative depth there (below the ring's tip
    circle), so leaving them out answers "does any point reach the ring?" the same. A point at
    ``|p|`` from the pinion's centre moves at most ``|p| half_width``; 1e-9 mm covers rounding."""
    r = np.hypot(*placed_points(pts, (a, 0.0), turn).T)
    return pts[r + np.hypot(pts[:, 0], pts[:, 1]) * half_width + 1e-9 >= tip_radius]


@dataclass(frozen=True)
class InternalPlay:
    """Free rotation of the pinion (rad) counter-clockwise and clockwise from mesh position
    ``phase`` with the ring held; ``transverse`` = rb1 (ccw + cw), the backlash along the line of
    action (mm)."""

    phase: float
    ccw: float
    cw: float
    transverse: float


def free_play(pair: InternalPairGeometry, pinion: ToothProfile, ring: InternalProfile, phase: float = 0.0,
              step: float | None = None, material: RingMaterial | None = None) -> InternalPlay:
    """The pinion's free rotation both ways at mesh position ``phase`` on the exact outlines
    (bisection on the contact, to 1e-13 rad). Raises GeargenError when the pinion already overlaps
    the ring there."""
    # 1e-3 m_n apart: between samples the gap to a touching flank is below h^2 / (8 rho), < 0.1 nm
    step = step or 1e-3 * pair.pinion.module
    material = material or RingMaterial(ring)
    pts = pinion_points(pinion, step)
    z1, z2, a = pair.pinion.teeth, pair.ring.teeth, pair.centre_distance
    # only the points that a turn of up to one pitch can bring to the ring's teeth
    reach = np.hypot(*placed_points(pts, (a, 0.0), phase).T)
    pts = pts[reach > ring.tip_radius - pinion.tip_radius * pinion.pitch_angle]
    if _max_depth(material, pts, a, z1, z2, phase, 0.0) >= 0:
        raise GeargenError(f"the pinion overlaps the ring at mesh position {phase!r} rad")
    limits = []
    stride = 0.01 * pinion.pitch_angle
    for sign in (1.0, -1.0):
        lo, hi = 0.0, 0.0
        # the scan turns at most a pitch and a stride: it reads only the points that can reach the
        # ring's tip circle meanwhile (as the bisection below; the same answers)
        span = pinion.pitch_angle + 2 * stride
        scan = _reaching(pts, a, phase + sign * 0.5 * span, 0.5 * span, ring.tip_radius)
        while True:
            hi += stride
            if len(scan) and _max_depth(material, scan, a, z1, z2, phase, sign * hi) >= 0:
                break
            lo = hi
            if hi > pinion.pitch_angle:
                raise GeargenError("no contact within one pitch")
        near = _reaching(pts, a, phase + sign * 0.5 * (lo + hi), 0.5 * (hi - lo), ring.tip_radius)
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if hi - lo < 1e-13:
                break
            if _max_depth(material, near, a, z1, z2, phase, sign * mid) >= 0:
                hi = mid
            else:
                lo = mid
        limits.append(0.5 * (lo + hi))
    return InternalPlay(phase, limits[0], limits[1], pair.pinion.base_radius * (limits[0] + limits[1]))


def overlap_depth(pair: InternalPairGeometry, pinion: ToothProfile, ring: InternalProfile, phases,
                  step: float | None = None) -> np.ndarray:
    """Deepest pinion outline point inside the ring (mm, negative: apart) at each mesh position
    (position 0: pinion tooth 0 centred in ring space 0, so a pair with backlash sits mid-play
    there; with zero backlash the flanks touch, depth ~0). Sampled ``step`` apart (default
    2e-3 m_n): an overlap shallower than the sampling's sag can be missed, none is invented."""
    step = step or 2e-3 * pair.pinion.module
    material = RingMaterial(ring)
    pts = pinion_points(pinion, step)
    z1, z2, a = pair.pinion.teeth, pair.ring.teeth, pair.centre_distance
    return np.array([_max_depth(material, pts, a, z1, z2, float(p), 0.0) for p in np.ravel(phases)])


@dataclass(frozen=True)
class InternalCheck:
    """The named checks of an internal pair: ``margins`` per check (units in the module
    docstring, positive passes), ``failures`` (:class:`Failure`), the pair geometry and the
    smallest tooth difference that meshes (pinion teeth varied, everything else kept)."""

    geometry: InternalPairGeometry
    margins: dict
    failures: tuple[Failure, ...]
    minimum_tooth_difference: int | None
    notes: tuple[str, ...] = field(default=())

    @property
    def ok(self) -> bool:
        return not self.failures

    def to_dict(self) -> dict:
        margins = {k: (v if math.isfinite(v) else None) for k, v in self.margins.items()}  # None: cannot meet
        return {"geometry": self.geometry.to_dict(), "margins": margins,
                "failures": [f.to_dict() for f in self.failures],
                "tooth_difference": self.geometry.tooth_difference,
                "minimum_tooth_difference": self.minimum_tooth_difference, "notes": list(self.notes)}


def _alpha(rb: float, r: float) -> float:
    return math.acos(min(1.0, rb / r))


def ring_tip_roll_length(pair: InternalPairGeometry) -> float:
    """mm along the line of action from the pinion's base tangent point to where the ring's tip
    circle crosses it: sqrt(ra2^2 - rb2^2) - (rb2 - rb1) tan(a_w)."""
    return line_of_action_roll(pair, pair.ring.tip_radius)


#: a pinion flank closer to its involute than this (mm) counts as on it (the exact outline's round-off)
ON_INVOLUTE = 1e-9


def undercut_recess(pinion: ToothProfile, r_lo: float, r_hi: float, samples: int = 200001) -> tuple[float, float] | None:
    """(least, deepest) recess (mm, positive: the flank lies inside the involute) of the pinion's
    flank below its involute's start, between radii ``r_lo`` and ``r_hi``, on the exact fillet
    (the undercut) sampled ``samples`` times along its parameter; None when none of its points lies
    there. The involute's half-angle at radius r: psi_b - inv(acos(r_b / r))."""
    fillet = next(seg for seg in pinion.segments if seg.kind == "fillet" and seg.side == "upper")
    pts = fillet.point(np.linspace(fillet.t0, fillet.t1, samples))
    r = np.hypot(pts[:, 0], pts[:, 1])
    inside = (r >= max(r_lo, pinion.base_radius)) & (r <= r_hi)
    if not inside.any():
        return None
    alpha = np.arccos(pinion.base_radius / r[inside])
    recess = r[inside] * (pinion.base_half_angle - involute(alpha) - np.abs(np.arctan2(pts[inside, 1], pts[inside, 0])))
    return float(recess.min()), float(recess.max())


def usable_roll(pair: InternalPairGeometry, pinion: ToothProfile) -> float:
    """The lowest roll angle of the pinion's flank the ring's tip may reach without interference:
    its involute's start against a fillet joint (the fillet stands proud of the involute extended
    below it); its base circle under an undercut that lies inside the involute all the way down
    to where the ring's tip engages (measured: :func:`undercut_recess`)."""
    if not pinion.undercut:
        return pinion.involute_start_roll
    engage = math.hypot(pair.pinion.base_radius, max(ring_tip_roll_length(pair), 0.0))
    recess = undercut_recess(pinion, engage, pinion.involute_start_radius)
    return 0.0 if recess is None or recess[0] >= -ON_INVOLUTE else pinion.involute_start_roll


def involute_margin(pair: InternalPairGeometry, pinion: ToothProfile) -> float:
    """mm along the line of action from the lowest usable point of the pinion's flank
    (:func:`usable_roll`) to where the ring's tip engages."""
    return ring_tip_roll_length(pair) - pair.pinion.base_radius * usable_roll(pair, pinion)


def tip_margin(pair: InternalPairGeometry, pinion: ToothProfile, ring: InternalProfile) -> tuple[float, str]:
    """Smallest of: (ring's form radius - radius where the pinion's tip engages the ring), the
    radial clearances of the pinion's tip at the ring's root and of the ring's tip at the
    pinion's root; and which one it is."""
    rb1, rb2, a = pair.pinion.base_radius, pair.ring.base_radius, pair.centre_distance
    ra1 = pinion.tip_radius
    roll_ring = roll_length(ra1, rb1) + (rb2 - rb1) * math.tan(pair.working_pressure_angle)
    engage = math.hypot(rb2, roll_ring)
    options = [(ring.form_radius - engage, "the pinion's tip engages the ring's fillet"),
               (ring.root_radius - (a + ra1), "the pinion's tip circle reaches the ring's root circle"),
               (ring.tip_radius - (a + pinion.root_radius), "the ring's tip circle reaches the pinion's root circle")]
    return min(options)


def trochoid_margin(pair: InternalPairGeometry) -> float:
    """KHK's trochoid-interference margin (rad of the ring), see the module docstring."""
    a, z1, z2 = pair.centre_distance, pair.pinion.teeth, pair.ring.teeth
    ra1, ra2 = pair.pinion.tip_radius, pair.ring.tip_radius
    aw = pair.working_pressure_angle
    inv_w = involute(aw)
    c1 = (ra2 ** 2 - ra1 ** 2 - a ** 2) / (2 * a * ra1)
    c2 = (a ** 2 + ra2 ** 2 - ra1 ** 2) / (2 * a * ra2)
    if abs(c1) > 1 or abs(c2) > 1:
        # the tip circles do not cross: the pinion's lies inside the ring's (the teeth never reach
        # each other) or encloses it (the pinion's teeth overlap the ring's all the way round)
        return -math.inf if ra1 >= a + ra2 else math.inf
    theta1 = math.acos(c1) + involute(_alpha(pair.pinion.base_radius, ra1)) - inv_w
    theta2 = math.acos(c2)
    return theta1 * z1 / z2 + inv_w - involute(_alpha(pair.ring.base_radius, ra2)) - theta2


#: a pinion touching the ring by this much (over m_n) at its final position is the zero-backlash
#: flank contact, not fouling
RADIAL_TOUCH = 1e-5


def radial_assembly_margin(pair: InternalPairGeometry, pinion: ToothProfile, ring: InternalProfile,
                           phases: int = 16, steps: int = 120, step: float | None = None) -> float:
    """Best over ``phases`` mesh phases of one pinion pitch of the deepest overlap (negated, mm)
    met while sliding the pinion along the line of centres into ``(a, 0)`` in ``steps`` steps,
    starting where its tip circle fits inside the ring's tip circle (or on the ring's axis).
    Positive: it slides in; within ``RADIAL_TOUCH`` m_n of 0 at the final position: flanks
    touching without backlash."""
    step = step or 5e-3 * pair.pinion.module
    material = RingMaterial(ring)
    pts = pinion_points(pinion, step)
    z1, z2, a = pair.pinion.teeth, pair.ring.teeth, pair.centre_distance
    start = max(0.0, min(a, ring.tip_radius - pinion.tip_radius))
    touch = RADIAL_TOUCH * pair.pinion.module
    best = -math.inf
    for phase in np.linspace(0.0, 2 * math.pi / z1, phases, endpoint=False):
        ring_turn = phase * z1 / z2
        worst = -math.inf
        for e in np.linspace(start, a, steps):
            placed = placed_points(pts, (float(e), 0.0), float(phase))
            depth = float(np.max(material.depth(placed, ring_turn)))
            if e == a and depth <= touch:
                depth = min(depth, 0.0)
            worst = max(worst, depth)
            if worst > touch:
                break  # this phase fouls
        best = max(best, -worst)
        if best >= 0:
            break  # one phase slides in
    return best


def check_internal(pinion: GearSpec, ring: GearSpec, centre_distance: float | None = None,
                   radial_assembly: bool = True, mesh: str = "internal") -> InternalCheck:
    """Every named check of the pair at ``centre_distance`` (default: zero backlash)."""
    pair = internal_pair_geometry(pinion, ring, centre_distance)
    p1 = tooth_profile(pinion, warn=False)
    p2 = internal_profile(ring)
    failures = []
    margins = {}
    margins["involute_interference_mm"] = m = involute_margin(pair, p1)
    notes = []
    if m < 0:
        failures.append(Failure("involute_interference", mesh, "the ring's tip engages the pinion below its usable "
                                "involute (KHK 4.6: z1/z2 >= 1 - tan a_a2 / tan a_w)", "interference_depth", -m, 0.0))
    short = pair.pinion.base_radius * p1.involute_start_roll - ring_tip_roll_length(pair)
    if m >= 0 and short > 0:
        # the ring's tip runs into the pinion's undercut: no interference, but no contact there
        engage = math.hypot(pair.pinion.base_radius, ring_tip_roll_length(pair))
        recess = undercut_recess(p1, engage, p1.involute_start_radius)
        p_bt = 2 * math.pi * pair.pinion.base_radius / pair.pinion.teeth
        notes.append(f"the ring's tip runs {short:.4g} mm along the line of action over the pinion's undercut "
                     f"(recessed up to {recess[1] * 1e3:.2g} um from its involute: no interference); contact stops at "
                     f"the involute's start, contact ratio {pair.contact_ratio - short / p_bt:.4f} "
                     f"(not {pair.contact_ratio:.4f})")
    m, what = tip_margin(pair, p1, p2)
    margins["tip_interference_mm"] = m
    if m < 0:
        failures.append(Failure("tip_to_root_interference", mesh, what, "interference_depth", -m, 0.0))
    margins["trochoid_interference_rad"] = m = trochoid_margin(pair)
    if m < 0:
        failures.append(Failure("trochoid_interference", mesh, "leaving mesh, the pinion's tip corner cuts the "
                                "ring's tip (KHK 4.6)", "margin_rad", m, 0.0))
    if radial_assembly:
        margins["radial_assembly_mm"] = m = radial_assembly_margin(pair, p1, p2)
        if m < -RADIAL_TOUCH * pinion.module:
            failures.append(Failure("radial_assembly_fouling", mesh, "the pinion cannot be moved into mesh along "
                                    "the line of centres at any phase (assemble it axially)", "interference_depth",
                                    -m, 0.0))
    return InternalCheck(pair, margins, tuple(failures), minimum_tooth_difference(pinion, ring), tuple(notes))


def minimum_tooth_difference(pinion: GearSpec, ring: GearSpec) -> int | None:
    """The smallest ``z2 - z1`` (pinion teeth varied, ring and everything else kept) free of
    involute, tip and trochoid interference at the zero-backlash centre distance; None if none."""
    for diff in range(1, ring.teeth - 3):
        z1 = ring.teeth - diff
        try:
            p = with_changes(pinion, teeth=z1)
            pair = internal_pair_geometry(p, ring)
            p1 = tooth_profile(p, warn=False)
            p2 = internal_profile(ring)
        except GeargenError:
            continue
        if (involute_margin(pair, p1) >= 0 and tip_margin(pair, p1, p2)[0] >= 0
                and trochoid_margin(pair) >= 0):
            return diff
    return None


__all__ = ["RingMaterial", "InternalPlay", "pinion_points", "placed_points", "InternalCheck", "free_play", "overlap_depth", "check_internal",
           "involute_margin", "ring_tip_roll_length", "undercut_recess", "usable_roll", "tip_margin", "trochoid_margin", "radial_assembly_margin", "minimum_tooth_difference"]
