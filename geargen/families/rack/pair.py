"""The exact 2-D check of a pinion on a rack: backlash, tip clearances and interference, measured on
the exact outlines (numpy only, no CAD kernel).

Method (transverse section of the pinion = the section of the rack across its width; in every
such plane the picture is the same, turned and slid together, so one plane serves a helical pair
too). The pinion's outline is :class:`geargen.checks.mesh2d.PolarOutline` (involute flanks,
generated fillets, tip and root arcs, each evaluated exactly at its own parameter); the rack's is
:class:`geargen.families.rack.geometry.RackOutline` (lines and arcs), which is a graph in both directions: at
a height ``u`` above its pitch line the space around ``x = 0`` is ``|x| <= E_t(u)`` (``E_t`` the
normal half-width over ``cos(beta)``), and above a point ``x`` the rack's top is at ``g(x)``.

The pinion's centre stands at ``(-r theta, C)`` over the rack's space (``C`` its height above the
pitch line), turned by ``theta`` (the rack rolled with it). Holding the pinion, the rack can slide
along its length by ``s`` with ``d - E_t(Y) <= s <= d + E_t(Y)`` for every pinion boundary point
``(X, Y)`` below the rack's tips (``d`` the point's offset from its space's centre), so the
rack's free travel is ``min(d + E_t) - max(d - E_t)`` over the pinion's boundary: the
circumferential backlash (transverse, on the pinion's reference circle: the rack rolls on it).
Each extreme is bracketed on samples of every boundary segment and refined on the exact curve
(golden section, keeping the best point), so the result is exact to ~1e-12 mm, not to a
tessellation. Counting only involute points against the rack's straight flanks gives the
conjugate play; where the full play is smaller a non-conjugate feature stops the rack first and
is named: ``involute_interference`` when the rack's tip works on the pinion's fillet (its
generated trochoidal root or an undercut edge) or the pinion's tip corner on the rack's root
fillet, ``tip_to_root_interference`` when a tip reaches the mate's root land or below.
Tip clearances are the vertical gaps from the pinion's tip arcs to the rack's root outline and
from the pinion's root arcs to the rack's tips.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from geargen.checks.mesh2d import FILLET, INVOLUTE, ROOT, TIP, PolarOutline, polar_outline
from geargen.checks.results import Failure
from geargen.families.rack.geometry import RackPinionGeometry, rack_outline, rack_pinion_geometry
from geargen.design.gear import GearSpec
from geargen.families.rack.spec import RackSpec

_GOLDEN = 0.3819660112501051
#: samples per boundary segment for bracketing (the refinement is exact)
_SAMPLES = 160
_ITERATIONS = 60
#: differences smaller than this (mm) are rounding
TOLERANCE = 1e-9


@dataclass
class RackMeshCheck:
    """A pinion on a rack checked at mesh positions ``theta`` (pinion rotation, rad, arrays ``(n,)``).

    Backlash (positive clearance; mm): ``circumferential_backlash`` the rack's free travel along its
    length with the pinion held (= arc on the pinion's reference circle), ``conjugate_backlash``
    the same counting flank-on-flank contact only; ``normal_backlash`` = circumferential x
    cos(alpha_t) cos(beta_b). Clearances (mm): ``tip_clearance_pinion`` pinion tip arcs to the rack's
    root outline, ``tip_clearance_rack`` the pinion's root arcs to the rack's tips (vertical gaps).
    ``failures`` (:class:`geargen.checks.results.Failure`): interference named, no backlash.
    ``geometry``: the closed forms of :func:`geargen.families.rack.geometry.rack_pinion_geometry`.
    """

    mesh_position: np.ndarray
    circumferential_backlash: np.ndarray
    conjugate_backlash: np.ndarray
    normal_backlash: np.ndarray
    tip_clearance_pinion: np.ndarray
    tip_clearance_rack: np.ndarray
    limit: list  # per position: what stops the rack (the pinion segment kind on each side)
    geometry: RackPinionGeometry
    failures: list = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.failures


class PlacedRackPair:
    """The placed outlines: pinion boundary as a function of (tooth, sector parameter)."""

    def __init__(self, rack: RackSpec, pinion: PolarOutline, centre: float):
        self.rack, self.pinion, self.centre = rack, pinion, centre
        self.outline = rack_outline(rack)
        self.cos_b = math.cos(rack.helix_angle)
        self.pt = rack.transverse_pitch
        self.r = pinion.r_ref
        ha = rack.addendum
        reach = math.acos(max(-1.0, min(1.0, (centre - ha) / pinion.r_tip))) if pinion.r_tip > centre - ha else 0.0
        self.teeth = np.arange(-(int(reach / pinion.pitch) + 2), int(reach / pinion.pitch) + 3)

    def points(self, theta: float, u: np.ndarray, k: np.ndarray):
        """Rack-frame (X, Y) and segment kind of pinion boundary points at sector parameter ``u``
        of tooth ``k`` (arrays of one shape)."""
        rho, phi, _, _, kind = self.pinion.sector_polar(u)
        ang = phi + k * self.pinion.pitch - math.pi / 2 + theta
        return -self.r * theta + rho * np.cos(ang), self.centre + rho * np.sin(ang), kind

    def half_width(self, y):
        """Transverse space half-width at height ``y``; below the root line (inside the rack's body)
        minus a pitch, so that such a point blocks the travel either way."""
        o = self.outline
        e = o.space_half_width(np.clip(y, -o.dedendum, o.addendum)) / self.cos_b
        return np.where(y < -o.dedendum, -self.pt, e)

    def offset(self, x):
        return x - self.pt * np.round(x / self.pt)

    def rack_top(self, x):
        return self.outline.height_at(self.offset(x) * self.cos_b)

    def straight_flank(self, y):
        o = self.outline
        return (y >= o.flank_root_u) & (y <= o.flank_tip_u)


def _golden(f, a, b, iterations=_ITERATIONS):
    """Minimise f on [a, b] (golden section, keeping the best point seen)."""
    best_x, best = (a, f(a)) if f(a) <= f(b) else (b, f(b))
    x1, x2 = a + _GOLDEN * (b - a), b - _GOLDEN * (b - a)
    f1, f2 = f(x1), f(x2)
    for _ in range(iterations):
        for x, v in ((x1, f1), (x2, f2)):
            if v < best:
                best_x, best = x, v
        if f1 <= f2:
            b, x2, f2 = x2, x1, f1
            x1 = a + _GOLDEN * (b - a)
            f1 = f(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = b - _GOLDEN * (b - a)
            f2 = f(x2)
    return best_x, best


def boundary_extreme(pair: PlacedRackPair, theta: float, objective, mask_of, u_grid, k_grid):
    """Minimum over the pinion's boundary of ``objective(X, Y)`` (points ``mask_of`` admits),
    bracketed on the grid and refined on the exact segment; returns (value, kind of the point)."""
    X, Y, kind = pair.points(theta, u_grid, k_grid)
    vals = np.where(mask_of(X, Y, kind), objective(X, Y), np.inf)
    if not np.any(np.isfinite(vals)):
        return math.inf, -1
    flat = np.argmin(vals, axis=None)
    i, j = np.unravel_index(flat, vals.shape)
    k = float(k_grid[i, j])
    lo = u_grid[i, max(j - 1, 0)]  # the boundary is continuous across segment joints
    hi = u_grid[i, min(j + 1, u_grid.shape[1] - 1)]

    def f(t):
        x, y, kd = pair.points(theta, np.array([t]), np.array([k]))
        return float(np.where(mask_of(x, y, kd), objective(x, y), np.inf)[0])

    _, best = _golden(f, lo, hi) if hi > lo else (lo, f(lo))
    best = min(best, float(vals[i, j]))
    return best, int(kind[i, j])


def check_rack_pinion_mesh(rack: RackSpec, pinion: GearSpec, centre_offset: float = 0.0,
                           positions: int = 8, min_backlash: float = 0.0) -> RackMeshCheck:
    """Check ``pinion`` on ``rack`` with its centre ``centre_offset`` (mm, + away from the rack)
    from the nominal height, at ``positions`` pinion rotations over one tooth pitch."""
    geometry = rack_pinion_geometry(rack, pinion, centre_offset)
    outline = polar_outline(pinion)
    pair = PlacedRackPair(rack, outline, geometry.centre_height)
    n_seg = outline.segment_count
    u1 = np.concatenate([s + np.linspace(0.0, 1.0, _SAMPLES, endpoint=False) for s in range(n_seg)] + [[float(n_seg)]])
    u_grid, k_grid = np.meshgrid(u1, pair.teeth.astype(float))
    ha = rack.addendum
    thetas = np.arange(positions) * outline.pitch / positions
    cos_bb, cos_at = math.cos(pinion.base_helix_angle), math.cos(rack.transverse_pressure_angle)

    tip_line = ha - 1e-9 * rack.module  # a point on the tip line touches it without blocking the travel

    def below_tips(X, Y, kind):
        return Y < tip_line

    def conjugate(X, Y, kind):
        return (kind == INVOLUTE) & pair.straight_flank(Y) & (Y < tip_line)

    def up(X, Y):  # the rack's travel toward +x
        return pair.half_width(Y) + pair.offset(X)

    def down(X, Y):  # toward -x (as a positive number)
        return pair.half_width(Y) - pair.offset(X)

    o = pair.outline
    # where the root outline ends (the fillet's flank tangent point, or the sharp corner) and the
    # tip outline starts, as the normal offset from the space centre
    root_end = float(o.flank_x(o.flank_root_u))
    tip_start = float(o.flank_x(o.flank_tip_u))
    full, conj, lims, c_pin, c_rack = [], [], [], [], []
    for theta in thetas:
        a, ka = boundary_extreme(pair, theta, up, below_tips, u_grid, k_grid)
        b, kb = boundary_extreme(pair, theta, down, below_tips, u_grid, k_grid)
        ca, _ = boundary_extreme(pair, theta, up, conjugate, u_grid, k_grid)
        cd, _ = boundary_extreme(pair, theta, down, conjugate, u_grid, k_grid)
        full.append(a + b)
        conj.append(ca + cd)
        lims.append((ka, kb))
        shift = 0.5 * (ca - cd)  # the rack in the middle of its flanks' travel (its running position)

        def gap(X, Y, shift=shift):
            return Y - pair.rack_top(X - shift)

        def over_root(X, Y, kd, shift=shift):  # a pinion tip point above the rack's root land or fillet
            return (kd == TIP) & (np.abs(pair.offset(X - shift)) * pair.cos_b <= root_end)

        def over_tip(X, Y, kd, shift=shift):  # a pinion root point above the rack's tip land or tip arc
            return (kd == ROOT) & (np.abs(pair.offset(X - shift)) * pair.cos_b >= tip_start)

        c_pin.append(boundary_extreme(pair, theta, gap, over_root, u_grid, k_grid)[0])
        c_rack.append(boundary_extreme(pair, theta, gap, over_tip, u_grid, k_grid)[0])
    full, conj = np.array(full), np.array(conj)
    result = RackMeshCheck(mesh_position=thetas, circumferential_backlash=full, conjugate_backlash=conj,
                           normal_backlash=full * cos_at * cos_bb, tip_clearance_pinion=np.array(c_pin),
                           tip_clearance_rack=np.array(c_rack), limit=lims, geometry=geometry)
    result.failures = _failures(result, rack, pinion, min_backlash)
    return result


def _failures(res: RackMeshCheck, rack: RackSpec, pinion: GearSpec, min_backlash: float) -> list[Failure]:
    mesh = f"{pinion.name}-{rack.name}"
    out = []
    for values, what in ((res.tip_clearance_pinion, "the pinion's tip reaches below the rack's root"),
                         (res.tip_clearance_rack, "the rack's tip reaches into the pinion's root")):
        if values.min() < -TOLERANCE:
            i = int(np.argmin(values))
            out.append(Failure("tip_to_root_interference", mesh, f"{what} ({values[i] * 1e3:.4g} um)",
                               "min_clearance", float(values[i]), 0.0, float(res.mesh_position[i])))
    worst = int(np.argmax(res.conjugate_backlash - res.circumferential_backlash))
    lost = float(res.conjugate_backlash[worst] - res.circumferential_backlash[worst])
    if lost > TOLERANCE and not out:
        kinds = res.limit[worst]
        what = ("the rack's tip works on the pinion's generated root (trochoid) or undercut edge"
                if FILLET in kinds else "a tip corner works on the mate's non-involute root outline")
        out.append(Failure("involute_interference", mesh, f"{what}: the rack's travel is stopped {lost * 1e3:.4g} um "
                           "before the flanks meet", "interference_depth", lost, 0.0, float(res.mesh_position[worst])))
    j = float(res.conjugate_backlash.min())
    if j < -TOLERANCE:
        out.append(Failure("flank_interference", mesh, f"the pinion's teeth do not fit the rack's spaces "
                           f"(flank backlash {j * 1e3:.4g} um)", "circumferential_backlash", j, 0.0))
    elif min_backlash > 0 and float(res.circumferential_backlash.min()) < min_backlash - TOLERANCE:
        j = float(res.circumferential_backlash.min())
        out.append(Failure("no_backlash", mesh, f"backlash {j * 1e3:.4g} um is below the {min_backlash * 1e3:.4g} um "
                           "required", "circumferential_backlash", j, min_backlash))
    return out


__all__ = ["RackMeshCheck", "check_rack_pinion_mesh", "TOLERANCE"]
