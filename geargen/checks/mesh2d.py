"""Path 1: the exact 2-D mesh check on analytic tooth outlines (numpy only, no CAD kernel).

Method. Each gear's transverse outline comes from :func:`geargen.profile.tooth_profile`
(involute flanks, generated fillet, tip and root arcs, each an analytic segment). Because the
outline is radially monotone, a gear is the set of points ``(rho, phi)`` about its centre with
``|phi - k p| <= psi(rho)`` for some tooth ``k`` (``p = 2 pi / z``), plus the body inside the
deepest outline radius. ``psi`` is the flank's polar angle: closed form on the involute,
``psi_b - inv(arccos(r_b / rho))`` (the involute's normal is tangent to the base circle, so the
point's radius alone fixes the flank's polar angle), and the exact fillet point of that radius
(Newton on the fillet's parameter) below the involute.

So the rotation a gear needs for a flank to reach a given point is a closed form: for a point
at ``(rho, phi)`` in the gap after tooth ``k``, ``phi - k p - psi(rho)`` turning counter-clockwise
(tooth k's upper flank) and ``(k+1) p - psi(rho) - phi`` turning clockwise (tooth k+1's lower
flank); both are negative when the point is already inside a tooth. Turning gear 1 with gear 2
held, the first contact is the minimum of this rotation over gear 2's boundary. That boundary
is walked by each segment's own analytic parameter (roll angle, fillet parameter, polar
angle); the minimum is bracketed on a fixed set of parameter samples and then refined on the
exact curves (golden section keeping the best point) to machine precision: no tessellation.
A tip corner of gear 1 appears as the end of the feasible part of gear 2's flank (points
beyond gear 1's tip circle cannot be reached), a tip corner of gear 2 as a segment end.

The same rotation restricted to involute-on-involute contact (conjugate contact) gives the
conjugate play; where the full play is smaller, a non-conjugate feature (fillet, root, undercut
edge) stops the gear before its flanks meet: interference, with its depth along the line of
action. The tip clearance is the exact distance from each gear's root arcs to the mate's tip
lands (closed forms for both arcs, refined on the root arc's parameter), and the overlap area
follows from Green's theorem on the analytic segments (Gauss-Legendre on each piece inside the
other gear, crossings bisected on the segment parameters).

Failure kinds (:data:`geargen.checks.results.FAILURE_KINDS`): a non-conjugate feature stopping
the gear before its flanks meet is ``involute_interference`` (a fillet or undercut edge) or
``tip_to_root_interference`` (a root arc, or the body below it; also any tip clearance below
zero); flanks overlapping on both sides are ``flank_interference``; no backlash left where it
is required ``no_backlash``; per gear, ``pointed_tooth`` (tip land below the minimum) and
``undercut`` (the mate's tip works below where the undercut involute starts, from the pair
formulas of :mod:`geargen.core.geometry`); ``low_contact_ratio`` from the contact ratio
measured here (tooth pairs in flank-on-flank contact, counted over a tooth cycle).

Conventions: mm, rad; gear 1 is turned, gear 2 held; see :mod:`geargen.checks.results` for
the backlash kinds. Everything is vectorised over mesh positions (arrays ``(n,)``).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from geargen.checks.results import INTERFERENCE_CODES, Failure, MeshCheck, MeshSweep
from geargen.design.gear import GearSpec
from geargen.errors import GeargenError, GeometryError
from geargen.profile.tooth import UndercutWarning, section_rotation, tooth_profile
from geargen.profile.tooth import ToothProfile
from geargen.units import length_text

#: segment kind codes of sampled boundary points
ROOT, FILLET, INVOLUTE, TIP = 0, 1, 2, 3
_KIND_CODE = {"root_arc": ROOT, "fillet": FILLET, "involute": INVOLUTE, "tip_arc": TIP}
#: limiting-feature codes of a play value
CONJUGATE, NON_CONJUGATE, ROOT_BODY = 0, 1, 2

_GOLDEN = 0.3819660112501051  # 2 - golden ratio
#: samples per segment kind for bracketing minima (the refinement is exact)
_SAMPLES = {ROOT: 5, FILLET: 10, INVOLUTE: 18, TIP: 7}
#: refinement iterations (golden section; the bracket shrinks to ~1e-10 of a sample spacing)
_REFINE_ITERATIONS = 40
#: chunk of mesh positions evaluated at once (bounds memory)
_CHUNK = 1024
#: two contacts closer than this (mm along the line of action) count as simultaneous
CONTACT_TOLERANCE = 1e-12
#: overlaps smaller than this (mm) are rounding, not interference
INTERFERENCE_TOLERANCE = 1e-6


class PolarOutline:
    """A gear's exact transverse outline in polar form about its axis (z = 0 section).

    ``half_angle(rho)`` is the polar angle of tooth 0's upper flank at radius ``rho`` (mm), which
    for an outline that is radially monotone describes the whole gear. ``sector_polar(u)``
    evaluates the boundary of tooth 0's pitch sector at the sector parameter ``u`` in
    ``[0, S]`` (``S`` segments; on ``[s, s+1]`` segment ``s`` runs from its ``t0`` to ``t1``).
    """

    def __init__(self, profile: ToothProfile):
        self.profile = profile
        self.spec = profile.spec
        self.teeth = profile.teeth
        self.pitch = 2 * math.pi / self.teeth
        self.r_tip = profile.tip_radius
        self.r_base = profile.base_radius
        self.r_ref = profile.reference_radius
        self.r_start = profile.involute_start_radius
        self.r_root = profile.root_radius
        self.tip_half = profile.tip_half_angle
        self.root_half = profile.root_arc_half_angle
        self.base_half = profile.base_half_angle
        self.segments = profile.segments
        self.kinds = np.array([_KIND_CODE[s.kind] for s in self.segments])
        self.sides = np.array([(-1 if s.side == "lower" else 1) if s.side else 0 for s in self.segments])
        self._kind_side = list(zip(self.kinds.tolist(), self.sides.tolist()))  # per segment, as Python ints
        fillets = [s for s in self.segments if s.kind == "fillet" and s.side == "upper"]
        self._fillet = fillets[0]
        th = np.linspace(self._fillet.t0, self._fillet.t1, 1025)  # joint -> root
        xy = self._fillet.point(th)
        rho = np.hypot(xy[:, 0], xy[:, 1])
        if not np.all(np.diff(rho) < 0):
            raise GeometryError("fillet", f"the fillet of the {self.teeth}-tooth gear is not radially "
                                "monotone; the polar description of the outline does not apply")
        self.r_min = float(rho[-1])  # deepest radius of the outline (the root circle when there is a root arc)
        self._fil_theta = th[::-1].copy()  # rho increasing
        self._fil_rho = rho[::-1].copy()
        self._fil_key = np.sqrt(np.maximum(self._fil_rho - self.r_min, 0.0))
        # table of psi(rho) for bracketing (the refinement evaluates exactly)
        r_inv = self.r_start + (self.r_tip - self.r_start) * np.linspace(0, 1, 513) ** 1.5
        psi_inv = profile.involute_half_angle(r_inv)
        psi_fil = np.arctan2(xy[::-1, 1], xy[::-1, 0])
        self._tab_rho = np.concatenate([self._fil_rho[:-1], r_inv])
        self._tab_psi = np.concatenate([psi_fil[:-1], psi_inv])
        # sector samples
        us, ks = [], []
        for s, kind in enumerate(self.kinds):
            n = _SAMPLES[int(kind)]
            us.append(s + np.linspace(0.0, 1.0, n)[:-1])
        us.append(np.array([float(len(self.segments))]))
        self.sample_u = np.concatenate(us)
        self.segment_count = len(self.segments)
        (self.sample_rho, self.sample_phi, self.sample_wlo, self.sample_wup,
         self.sample_kind) = self.sector_polar(self.sample_u)

    # ---------------------------------------------------------------- polar half angle
    def half_angle(self, rho) -> np.ndarray:
        """Exact polar angle (rad) of tooth 0's upper flank at radius ``rho`` (mm, any shape).

        Above the tip circle the involute continues; inside the deepest outline radius the
        result exceeds half a pitch (``p/2 + (r_min - rho)/r_min``), so every angle is inside.
        """
        rho = np.asarray(rho, dtype=float)
        inv = rho >= self.r_start
        if inv.all():  # every point on the involute (most refinement steps): elementwise as below
            return np.asarray(self.profile.involute_half_angle(rho), dtype=float)
        out = np.empty(rho.shape)
        if np.any(inv):
            out[inv] = self.profile.involute_half_angle(rho[inv])
        fil = ~inv & (rho >= self.r_min)
        if np.any(fil):
            out[fil] = self._fillet_half_angle(rho[fil])
        body = rho < self.r_min
        if np.any(body):
            out[body] = 0.5 * self.pitch + (self.r_min - rho[body]) / self.r_min
        return out

    def half_angle_fast(self, rho) -> np.ndarray:
        """:meth:`half_angle` from a table (for bracketing only; error ~1e-7 rad on the fillet)."""
        rho = np.asarray(rho, dtype=float)
        out = np.interp(rho, self._tab_rho, self._tab_psi)
        body = rho < self.r_min
        if np.any(body):
            out = np.where(body, 0.5 * self.pitch + (self.r_min - rho) / self.r_min, out)
        return out

    def _fillet_half_angle(self, rho: np.ndarray) -> np.ndarray:
        """Polar angle of the upper fillet point at radius ``rho``: Newton on the fillet parameter
        from an interpolated start, kept inside a bracket from the table (bisection where Newton
        would leave it)."""
        key = np.sqrt(np.maximum(rho - self.r_min, 0.0))  # theta is smooth in sqrt(rho - r_min) at the root
        i = np.clip(np.searchsorted(self._fil_key, key), 1, len(self._fil_key) - 1)
        lo, hi = self._fil_theta[i - 1], self._fil_theta[i]  # rho(lo) <= rho <= rho(hi)
        k_lo, k_hi = self._fil_key[i - 1], self._fil_key[i]
        th = lo + (hi - lo) * np.clip((key - k_lo) / np.where(k_hi > k_lo, k_hi - k_lo, 1.0), 0, 1)
        curve = self._fillet.curve
        active = np.ones(th.shape, dtype=bool)
        for _ in range(30):
            idx = np.nonzero(active)[0]
            if idx.size == 0:
                break
            t = th[idx]
            p = curve.point(t)
            d = curve.derivative(t)
            r = np.hypot(p[:, 0], p[:, 1])
            g = r - rho[idx]
            lo[idx] = np.where(g <= 0, t, lo[idx])
            hi[idx] = np.where(g > 0, t, hi[idx])
            dg = (p[:, 0] * d[:, 0] + p[:, 1] * d[:, 1]) / r
            with np.errstate(divide="ignore", invalid="ignore"):
                step = t - g / dg
            bad = ~np.isfinite(step) | ((step - lo[idx]) * (step - hi[idx]) > 0)
            new = np.where(bad, 0.5 * (lo[idx] + hi[idx]), step)
            th[idx] = new
            active[idx] = (np.abs(new - t) > 4e-16 * np.abs(t)) & (g != 0)
        p = curve.point(th)
        return np.arctan2(p[:, 1], p[:, 0])

    # ---------------------------------------------------------------- boundary walk
    def sector_polar(self, u):
        """Exact boundary of tooth 0's sector at sector parameters ``u``.

        Returns ``(rho, phi, w_lo, w_up, kind)`` shaped like ``u``: radius, polar angle, the
        weights with which the tooth's flank offsets move the point (``phi - lo w_lo + up w_up``
        for a tooth whose lower flank is moved out by ``lo`` and upper by ``up``, rad: 1 on the
        flank itself, linear along the tip and root arcs), and the segment kind code.
        """
        u = np.asarray(u, dtype=float)
        shape = u.shape
        u = u.ravel()
        # np.clip of integers, without its wrapper's cost (a refinement calls this thousands of times)
        s = np.minimum(np.maximum(np.floor(u).astype(int), 0), self.segment_count - 1)
        f = u - s
        rho = np.empty(u.shape)
        phi = np.empty(u.shape)
        w_lo = np.zeros(u.shape)
        w_up = np.zeros(u.shape)
        kind = self.kinds[s]
        half_gap = 0.5 * self.pitch - self.root_half
        for k in np.flatnonzero(np.bincount(s, minlength=self.segment_count)).tolist():  # the segments present
            seg = self.segments[k]
            m = s == k
            t = seg.t0 + f[m] * (seg.t1 - seg.t0)
            code, side = self._kind_side[k]
            if code == INVOLUTE:
                r = self.r_base * np.sqrt(1.0 + t * t)
                ph = side * (self.base_half - (t - np.arctan(t)))
                (w_up if side > 0 else w_lo)[m] = 1.0
            elif code == FILLET:
                xy = seg.point(t)
                r = np.hypot(xy[:, 0], xy[:, 1])
                ph = np.arctan2(xy[:, 1], xy[:, 0])
                (w_up if side > 0 else w_lo)[m] = 1.0
            elif code == TIP:
                r = np.full(t.shape, self.r_tip)
                ph = t
                w_up[m] = 0.5 * (1.0 + t / self.tip_half)
                w_lo[m] = 0.5 * (1.0 - t / self.tip_half)
            else:  # root arc half: the lower one at negative angles
                r = np.full(t.shape, self.r_root)
                ph = t
                w_lo[m] = np.where(t < 0, (t + 0.5 * self.pitch) / half_gap, 0.0)
                w_up[m] = np.where(t < 0, 0.0, (0.5 * self.pitch - t) / half_gap)
            rho[m], phi[m] = r, ph
        return (rho.reshape(shape), phi.reshape(shape), w_lo.reshape(shape), w_up.reshape(shape),
                kind.reshape(shape))

    def offset_rate(self, u):
        """d(w_lo)/dphi and d(w_up)/dphi along the sector at ``u`` (zero on flanks and fillets)."""
        u = np.asarray(u, dtype=float)
        s = np.clip(np.floor(u).astype(int), 0, self.segment_count - 1)
        kind = self.kinds[s]
        half_gap = 0.5 * self.pitch - self.root_half
        g = 1.0 / half_gap if half_gap > 0 else 0.0
        lower_root = (kind == ROOT) & (s == 0)  # the sector starts with the lower half root arc
        upper_root = (kind == ROOT) & (s != 0)
        d_lo = np.where(kind == TIP, -0.5 / self.tip_half, np.where(lower_root, g, 0.0))
        d_up = np.where(kind == TIP, 0.5 / self.tip_half, np.where(upper_root, -g, 0.0))
        return d_lo, d_up

    def segment_local(self, u):
        """Points and parameter derivatives of the sector boundary in tooth 0's frame at ``u``
        (``(n, 2)`` each; derivative with respect to ``u``)."""
        u = np.asarray(u, dtype=float).ravel()
        s = np.clip(np.floor(u).astype(int), 0, self.segment_count - 1)
        f = u - s
        p = np.empty((u.size, 2))
        d = np.empty((u.size, 2))
        for k, seg in enumerate(self.segments):
            m = s == k
            if np.any(m):
                t = seg.t0 + f[m] * (seg.t1 - seg.t0)
                p[m] = seg.point(t)
                d[m] = seg.derivative(t) * (seg.t1 - seg.t0)
        return p, d


@lru_cache(maxsize=64)
def polar_outline(spec: GearSpec) -> PolarOutline:
    """The :class:`PolarOutline` of ``spec`` (cached; undercut warnings are recorded, not raised)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UndercutWarning)
        return PolarOutline(tooth_profile(spec))


# -------------------------------------------------------------------- placed gears
@dataclass(frozen=True)
class MeshState:
    """Where two gears are, at ``n`` mesh positions, in one transverse plane (mm, rad).

    ``centre*`` ``(n, 2)``: tooth-circle centres; ``angle*`` ``(n,)``: rotation of tooth 0's
    centreline from +x (counter-clockwise). ``flanks*``: per-tooth flank offsets (rad, ``[lower,
    upper]``; positive moves that flank away from the tooth centreline, i.e. adds material):
    ``(z, 2)`` for every position, or ``(n, z, 2)`` / ``(n, 1, 2)`` per position; ``None`` for none.
    A tooth thicker by ``ds`` at the reference circle has ``[ds/(2r), ds/(2r)]``, a tooth
    displaced by ``d`` along the reference circle (counter-clockwise) ``[-d/r, d/r]``.
    """

    centre1: np.ndarray
    angle1: np.ndarray
    centre2: np.ndarray
    angle2: np.ndarray
    flanks1: np.ndarray | None = None
    flanks2: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.angle1)

    def take(self, idx) -> "MeshState":
        def f(o):
            return o[idx] if o is not None and o.ndim == 3 else o
        return MeshState(self.centre1[idx], self.angle1[idx], self.centre2[idx], self.angle2[idx],
                         f(self.flanks1), f(self.flanks2))

    def turned(self, rotation1) -> "MeshState":
        """Gear 1 turned by ``rotation1`` (rad, per position)."""
        return MeshState(self.centre1, self.angle1 + rotation1, self.centre2, self.angle2,
                         self.flanks1, self.flanks2)

    @property
    def centre_distance(self) -> np.ndarray:
        d = self.centre2 - self.centre1
        return np.hypot(d[:, 0], d[:, 1])


def _teeth_window(held: PolarOutline, moving: PolarOutline, distance: float) -> int:
    """Half-width (teeth) of the window of ``held``'s teeth that can reach ``moving``'s tip circle."""
    rho = np.linspace(held.r_min, held.r_tip, 65)
    c = (distance ** 2 + rho ** 2 - moving.r_tip ** 2) / (2 * distance * rho)
    gamma = float(np.max(np.arccos(np.clip(c, -1.0, 1.0))))
    return min(int(math.ceil(gamma / held.pitch)) + 1, held.teeth // 2 + 1)


def _flanks(offsets, rows, teeth, z):
    """(lower, upper) flank offsets of ``teeth`` at positions ``rows`` (broadcasting)."""
    if offsets is None:
        return 0.0, 0.0
    if offsets.ndim == 2:
        v = offsets[np.mod(teeth, z)]
    else:
        v = offsets[rows, np.mod(teeth, offsets.shape[1])]
    return v[..., 0], v[..., 1]


def _facing_flanks(offsets, rows, teeth, z):
    """The upper flank offsets of ``teeth`` and the lower ones of ``teeth + 1`` (as :func:`_flanks`
    reads them): one remainder for both teeth, and only the flank used of each gathered."""
    n = z if offsets.ndim == 2 else offsets.shape[1]
    t = np.mod(teeth, n)
    after = np.where(t + 1 == n, 0, t + 1)  # = np.mod(teeth + 1, n)
    if offsets.ndim == 2:
        return offsets[t, 1], offsets[after, 0]
    return offsets[rows, t, 1], offsets[rows, after, 0]


def _place(held: PolarOutline, c, a, offsets, rows, teeth, rho, phi, w_lo, w_up):
    """Mesh-frame x, y of held-gear boundary points (broadcasting)."""
    return _placer(held, c, a, offsets, rows, teeth)(rho, phi, w_lo, w_up)


def _placer(held: PolarOutline, c, a, offsets, rows, teeth):
    """:func:`_place` of fixed teeth as a function of the points: each tooth's angle and flank
    offsets read once (a refinement places the same teeth at every step)."""
    base = a + teeth * held.pitch
    lo, up = _flanks(offsets, rows, teeth, held.teeth) if offsets is not None else (None, None)
    cx, cy = c[..., 0], c[..., 1]

    def place(rho, phi, w_lo, w_up):
        ang = base + phi
        if lo is not None:
            ang = ang + up * w_up - lo * w_lo
        return cx + rho * np.cos(ang), cy + rho * np.sin(ang)
    return place


def _rotations(moving: PolarOutline, c, a, offsets, rows, x, y, exact: bool = True):
    """Signed rotations of the moving gear to reach points ``(x, y)``: (ccw, cw, rho).

    ``ccw``: counter-clockwise turn that brings the upper flank of the tooth behind the point to
    it; ``cw``: clockwise turn for the lower flank of the tooth ahead. Both ``+inf`` beyond the
    tip circle; negative inside a tooth.
    """
    dx = x - c[..., 0]
    dy = y - c[..., 1]
    rho = np.hypot(dx, dy)
    beyond = rho > moving.r_tip * (1 + 1e-13)
    within = ~beyond
    if 2 * np.count_nonzero(within) < within.size:
        # most points beyond the tip circle (a sampled window of teeth): the turns of the others
        # alone, each element as below (the same numbers), the rest inf
        a = np.broadcast_to(a, rho.shape)[within]
        rows = np.broadcast_to(rows, rho.shape)[within] if offsets is not None else rows
        ccw, cw = np.full(rho.shape, np.inf), np.full(rho.shape, np.inf)
        ccw[within], cw[within] = _turns(moving, dx[within], dy[within], rho[within], a, offsets, rows, exact)
        return ccw, cw, rho
    ccw, cw = _turns(moving, dx, dy, rho, a, offsets, rows, exact)
    return np.where(beyond, np.inf, ccw), np.where(beyond, np.inf, cw), rho


def _turns(moving: PolarOutline, dx, dy, rho, a, offsets, rows, exact: bool):
    """:func:`_rotations` (ccw, cw) of points at ``(dx, dy)`` (``rho`` from the moving centre) whatever
    their radius."""
    phi = np.arctan2(dy, dx) - a
    p = moving.pitch
    k = np.floor(phi / p)
    fr = phi - k * p
    psi = moving.half_angle(rho) if exact else moving.half_angle_fast(rho)
    ccw = fr - psi
    cw = p - fr - psi
    if offsets is not None:
        upper, lower = _facing_flanks(offsets, rows, k.astype(int), moving.teeth)
        ccw = ccw - upper
        cw = cw - lower
    return ccw, cw


@dataclass
class Play:
    """Free rotation of gear 1 against gear 2 (rad, arrays ``(n,)``), see :class:`MeshSweep`.

    ``limit_*``: what stops the full play: :data:`CONJUGATE` (flank on flank),
    :data:`NON_CONJUGATE` (a fillet or undercut edge), :data:`ROOT_BODY` (a root arc or the
    body below the root). ``radius_*``: the contact's radius on gear 1.
    """

    ccw: np.ndarray
    cw: np.ndarray
    conjugate_ccw: np.ndarray
    conjugate_cw: np.ndarray
    limit_ccw: np.ndarray
    limit_cw: np.ndarray
    radius_ccw: np.ndarray
    radius_cw: np.ndarray


def _golden(f, a, x, b, fx, iterations=_REFINE_ITERATIONS):
    """Vectorised golden-section minimisation on brackets ``[a, b]`` keeping the best point ``x``."""
    for _ in range(iterations):
        above, below = b - x, x - a  # each difference once
        right = above >= below
        u = np.where(right, x + _GOLDEN * above, x - _GOLDEN * below)
        fu = f(u)
        better = fu < fx
        a_new = np.where(better, np.where(right, x, a), np.where(right, a, u))
        b_new = np.where(better, np.where(right, b, x), np.where(right, u, b))
        x = np.where(better, u, x)
        fx = np.where(better, fu, fx)
        a, b = a_new, b_new
    return x, fx


def _bracket_candidates(F: np.ndarray, all_teeth: bool = False):
    """From sampled values ``F`` ``(n, T, M)``: per (position, tooth) the best sample, and which of
    them may hold the position's minimum (within the local variation around the best sample).

    Returns (i, t, m) index arrays of candidates to refine.
    """
    n, T, M = F.shape
    m = np.argmin(F, axis=2)
    fmin = np.take_along_axis(F, m[..., None], axis=2)[..., 0]
    if all_teeth:
        sel = np.isfinite(fmin)
    else:
        g = np.min(fmin, axis=1)
        left = np.take_along_axis(F, np.maximum(m - 1, 0)[..., None], axis=2)[..., 0]
        right = np.take_along_axis(F, np.minimum(m + 1, M - 1)[..., None], axis=2)[..., 0]
        with np.errstate(invalid="ignore"):
            var = np.fmax(np.where(np.isfinite(left), left - fmin, np.nan),
                          np.where(np.isfinite(right), right - fmin, np.nan))
            var = np.where(np.isnan(var), np.inf, var)  # a lone finite sample: always refine
            sel = np.isfinite(fmin) & (fmin - 2.0 * var - 1e-12 <= g[:, None])
    i, t = np.nonzero(sel)
    return i, t, m[i, t]


def _is_conjugate(kind, rho_m, moving: PolarOutline):
    """Held point on an involute (or the tip land at its end) meeting the moving gear's involute."""
    return ((kind == INVOLUTE) | (kind == TIP)) & (rho_m >= moving.r_start * (1 - 1e-12))


def _refine(moving, held, state: MeshState, teeth, i, t, m, ccw_side, conjugate: bool):
    """Exact minimum of the rotation on held tooth ``teeth[i, t]`` around sample ``m``.

    ``ccw_side`` (bool per candidate) picks the counter-clockwise or clockwise rotation;
    ``conjugate`` restricts to conjugate contact. Returns (value, rho_moving, held_kind, u).
    """
    u_s = held.sample_u
    M = u_s.size
    a = u_s[np.maximum(m - 1, 0)]
    b = u_s[np.minimum(m + 1, M - 1)]
    x0 = u_s[m]
    tooth = teeth[i, t]
    c_h, a_h = state.centre2[i], state.angle2[i]
    c_m, a_m = state.centre1[i], state.angle1[i]

    place = _placer(held, c_h, a_h, state.flanks2, i, tooth)

    def evaluate(u):
        rho, phi, w_lo, w_up, kind = held.sector_polar(u)
        x, y = place(rho, phi, w_lo, w_up)
        ccw, cw, rho_m = _rotations(moving, c_m, a_m, state.flanks1, i, x, y)
        v = np.where(ccw_side, ccw, cw)
        if conjugate:
            v = np.where(_is_conjugate(kind, rho_m, moving), v, np.inf)
        return v, rho_m, kind

    fx = evaluate(x0)[0]
    x, fx = _golden(lambda u: evaluate(u)[0], a, x0, b, fx)
    _, rho_m, kind = evaluate(x)
    return fx, rho_m, kind, x


def _per_position_min(n, i, values, *extra):
    """Minimum of ``values`` per position index ``i`` (``inf`` where none) and the extras at it."""
    out = np.full(n, np.inf)
    ex = [np.zeros(n, dtype=np.asarray(e).dtype) for e in extra]
    if i.size == 0:
        return (out, *ex)
    order = np.lexsort((values, i))
    first = np.ones(order.size, dtype=bool)
    first[1:] = i[order][1:] != i[order][:-1]
    sel = order[first]
    out[i[sel]] = values[sel]
    for e_out, e in zip(ex, extra):
        e_out[i[sel]] = np.asarray(e)[sel]
    return (out, *ex)


def _sampled(moving, held, state: MeshState):
    """Sampled rotations over the window of held teeth: (teeth (n,T), ccw, cw, conjugate mask)."""
    n = len(state)
    d = state.centre1 - state.centre2
    gam = np.arctan2(d[:, 1], d[:, 0])
    j0 = np.rint((gam - state.angle2) / held.pitch).astype(int)
    K = _teeth_window(held, moving, float(np.min(np.hypot(d[:, 0], d[:, 1]))))
    teeth = j0[:, None] + np.arange(-K, K + 1)[None, :]
    rows = np.arange(n)[:, None, None]
    x, y = _place(held, state.centre2[:, None, None, :], state.angle2[:, None, None], state.flanks2, rows,
                  teeth[..., None], held.sample_rho, held.sample_phi, held.sample_wlo, held.sample_wup)
    ccw, cw, rho_m = _rotations(moving, state.centre1[:, None, None, :], state.angle1[:, None, None],
                                state.flanks1, rows, x, y, exact=False)
    return teeth, ccw, cw, _is_conjugate(held.sample_kind, rho_m, moving)


def _candidates_both(F_ccw, F_cw):
    """Bracketing candidates of both sides, stacked: (i, t, m, is_ccw)."""
    i1, t1, m1 = _bracket_candidates(F_ccw)
    i2, t2, m2 = _bracket_candidates(F_cw)
    side = np.concatenate([np.ones(i1.size, dtype=bool), np.zeros(i2.size, dtype=bool)])
    return np.concatenate([i1, i2]), np.concatenate([t1, t2]), np.concatenate([m1, m2]), side


def free_play(gear1: PolarOutline, gear2: PolarOutline, state: MeshState) -> Play:
    """Free rotation of gear 1 (both ways) against gear 2 held, at every position of ``state``."""
    n = len(state)
    out = {k: np.empty(n) for k in ("ccw", "cw", "conjugate_ccw", "conjugate_cw", "radius_ccw", "radius_cw")}
    lim = {k: np.empty(n, dtype=int) for k in ("ccw", "cw")}
    for start in range(0, n, _CHUNK):
        sl = slice(start, min(n, start + _CHUNK))
        st = state.take(sl)
        nn = len(st)
        teeth, ccw, cw, conj = _sampled(gear1, gear2, st)
        i, t, m, side = _candidates_both(ccw, cw)
        v, rho_m, kind, _ = _refine(gear1, gear2, st, teeth, i, t, m, side, conjugate=False)
        code = np.where((rho_m < gear1.r_min * (1 - 1e-12)) | (kind == ROOT), ROOT_BODY,
                        np.where(_is_conjugate(kind, rho_m, gear1), CONJUGATE, NON_CONJUGATE))
        for name, sd in (("ccw", True), ("cw", False)):
            k = side == sd
            val, code_i, rad = _per_position_min(nn, i[k], v[k], code[k], rho_m[k])
            out[name][sl] = val
            lim[name][sl] = code_i
            out[f"radius_{name}"][sl] = rad
            out[f"conjugate_{name}"][sl] = val  # equal wherever the limiting contact is conjugate
        # where a non-conjugate feature limits, find the conjugate play separately
        redo_ccw = lim["ccw"][sl] != CONJUGATE
        redo_cw = lim["cw"][sl] != CONJUGATE
        if np.any(redo_ccw) or np.any(redo_cw):
            Fc = np.where(conj & redo_ccw[:, None, None], ccw, np.inf)
            Fw = np.where(conj & redo_cw[:, None, None], cw, np.inf)
            i, t, m, side = _candidates_both(Fc, Fw)
            v, *_ = _refine(gear1, gear2, st, teeth, i, t, m, side, conjugate=True)
            for name, sd, redo in (("ccw", True, redo_ccw), ("cw", False, redo_cw)):
                k = side == sd
                val = _per_position_min(nn, i[k], v[k])[0]
                cur = out[f"conjugate_{name}"][sl]
                out[f"conjugate_{name}"][sl] = np.where(redo, val, cur)
    return Play(ccw=out["ccw"], cw=out["cw"], conjugate_ccw=out["conjugate_ccw"], conjugate_cw=out["conjugate_cw"],
                limit_ccw=lim["ccw"], limit_cw=lim["cw"], radius_ccw=out["radius_ccw"],
                radius_cw=out["radius_cw"])


def contact_count(gear1: PolarOutline, gear2: PolarOutline, state: MeshState, side: str = "ccw") -> np.ndarray:
    """Number of tooth pairs in involute contact when gear 1 is turned onto its ``side`` flanks.

    A pair counts when its own first contact is flank on flank inside both involutes (not at a
    tip corner) and its rotation equals the position's minimum within
    :data:`CONTACT_TOLERANCE` along the line of action. Where only tip corners touch first
    (a contact ratio below 1), the count is 0.
    """
    n = len(state)
    out = np.zeros(n, dtype=int)
    tol = CONTACT_TOLERANCE / gear1.r_base
    for start in range(0, n, _CHUNK):
        sl = slice(start, min(n, start + _CHUNK))
        st = state.take(sl)
        teeth, ccw, cw, conj = _sampled(gear1, gear2, st)
        F = np.where(conj, ccw if side == "ccw" else cw, np.inf)
        i, t, m = _bracket_candidates(F, all_teeth=True)
        v, rho_m, kind, u = _refine(gear1, gear2, st, teeth, i, t, m, np.full(i.size, side == "ccw"),
                                    conjugate=True)
        g = _per_position_min(len(st), i, v)[0]
        interior = ((kind == INVOLUTE) & (np.abs(u - np.rint(u)) > 1e-7)
                    & (rho_m < gear1.r_tip * (1 - 1e-9)))
        hit = (v <= g[i] + tol) & interior
        out[sl] = np.bincount(i[hit], minlength=len(st))
    return out


# -------------------------------------------------------------------- tip clearance
def _clearance_one_way(tipper: PolarOutline, rooter: PolarOutline, c_t, a_t, off_t, c_r, a_r, off_r):
    """Signed distance (mm, per position) from ``rooter``'s root arcs to ``tipper``'s tip lands.

    Negative where a root point lies inside the tipper's tooth below its tip circle (the radial
    depth under the tip circle). Without a root arc (fillets meeting at the gap centre) the
    deepest point of the gap stands for it.
    """
    n = len(a_t)
    S = rooter.segment_count
    if rooter.kinds[0] == ROOT:
        u_s = rooter.sample_u[rooter.sample_kind == ROOT]
    else:
        u_s = np.array([0.0, float(S)])
    d = c_t - c_r
    gam = np.arctan2(d[:, 1], d[:, 0])
    j0 = np.rint((gam - a_r) / rooter.pitch).astype(int)
    K = _teeth_window(rooter, tipper, float(np.min(np.hypot(d[:, 0], d[:, 1]))))
    teeth = j0[:, None] + np.arange(-K, K + 1)[None, :]

    def dist(u, tooth, rows, ct, at, cr, ar):
        rho, phi, w_lo, w_up, kind = rooter.sector_polar(u)
        x, y = _place(rooter, cr, ar, off_r, rows, tooth, rho, phi, w_lo, w_up)
        dx, dy = x - ct[..., 0], y - ct[..., 1]
        r = np.hypot(dx, dy)
        ph = np.arctan2(dy, dx) - at
        j = np.rint(ph / tipper.pitch)
        dph = ph - j * tipper.pitch
        lo, up = _flanks(off_t, rows, j.astype(int), tipper.teeth)
        half = tipper.tip_half + np.where(dph >= 0, up, lo)
        dph = np.abs(dph)
        corner = np.sqrt(np.maximum(r * r + tipper.r_tip ** 2 - 2 * r * tipper.r_tip * np.cos(dph - half), 0.0))
        return np.where(dph <= half, r - tipper.r_tip, corner)

    rows = np.arange(n)
    F = dist(u_s[None, None, :], teeth[..., None], rows[:, None, None], c_t[:, None, None, :], a_t[:, None, None],
             c_r[:, None, None, :], a_r[:, None, None]).reshape(n, -1)
    ti, m = np.divmod(np.argmin(F, axis=1), u_s.size)
    if rooter.kinds[0] != ROOT:
        return F[rows, ti * u_s.size + m]
    x0 = u_s[m]
    lower = x0 <= 1.0
    step = 1.0 / (_SAMPLES[ROOT] - 1)
    a = np.maximum(x0 - step, np.where(lower, 0.0, S - 1.0))
    b = np.minimum(x0 + step, np.where(lower, 1.0, float(S)))
    tooth = teeth[rows, ti]
    f = lambda u: dist(u, tooth, rows, c_t, a_t, c_r, a_r)
    return _golden(f, a, x0, b, f(x0))[1]


def tip_clearance(gear1: PolarOutline, gear2: PolarOutline, state: MeshState) -> np.ndarray:
    """Tip clearance (mm, ``(n,)``): the smaller of the two tip-land-to-mate's-root-arc distances."""
    v1 = _clearance_one_way(gear2, gear1, state.centre2, state.angle2, state.flanks2,
                            state.centre1, state.angle1, state.flanks1)
    v2 = _clearance_one_way(gear1, gear2, state.centre1, state.angle1, state.flanks1,
                            state.centre2, state.angle2, state.flanks2)
    return np.minimum(v1, v2)


# -------------------------------------------------------------------- overlap area
_GL_X, _GL_W = np.polynomial.legendre.leggauss(12)


def _inside_values(moving: PolarOutline, c, a, offsets, rows, x, y):
    """Negative where points lie inside the placed gear ``moving``, positive outside."""
    ccw, cw, rho = _rotations(moving, c, a, offsets, rows, x, y)
    return np.where(rho > moving.r_tip, rho - moving.r_tip, np.minimum(ccw, cw) * rho)


def _boundary_inside_integral(held: PolarOutline, other: PolarOutline, c_h, a_h, off_h, c_o, a_o, off_o,
                              samples: int = 48):
    """1/2 integral of (x dy - y dx) over the parts of ``held``'s boundary inside ``other``, per position.

    The boundary is walked by each segment's own parameter; where it enters or leaves the other
    gear the crossing is bisected to machine precision, and each inside piece is integrated by
    12-point Gauss-Legendre on the exact curve (``rho^2 dphi`` about the tooth centre plus the
    translation term ``c x dq``).
    """
    n = len(a_h)
    d = c_o - c_h
    gam = np.arctan2(d[:, 1], d[:, 0])
    j0 = np.rint((gam - a_h) / held.pitch).astype(int)
    K = _teeth_window(held, other, float(np.min(np.hypot(d[:, 0], d[:, 1]))))
    T = 2 * K + 1
    teeth = j0[:, None] + np.arange(-K, K + 1)[None, :]
    S = held.segment_count
    # dense towards the segment ends, where slivers of overlap sit (tip corners, fillet joints)
    ends = np.array([1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4])
    f = np.unique(np.concatenate([0.5 - 0.5 * np.cos(np.linspace(0.0, math.pi, samples)), ends, 1.0 - ends]))
    samples = f.size
    u = (np.arange(S)[:, None] + f[None, :] * (1 - 1e-12)).ravel()
    rho, phi, w_lo, w_up, _ = held.sector_polar(u)
    rows = np.arange(n)[:, None, None]
    x, y = _place(held, c_h[:, None, None, :], a_h[:, None, None], off_h, rows, teeth[..., None],
                  rho, phi, w_lo, w_up)
    h = _inside_values(other, c_o[:, None, None, :], a_o[:, None, None], off_o, rows, x, y)
    inside = (h < 0).reshape(n, T, S, samples)
    ua = u.reshape(S, samples)
    ia, ib = inside[..., :-1], inside[..., 1:]
    if not np.any(ia | ib):
        return np.zeros(n)
    pi_, ti_, si_, mi_ = np.nonzero(ia | ib)
    lo = ua[si_, mi_].copy()
    hi = ua[si_, mi_ + 1].copy()
    tooth = teeth[pi_, ti_]
    a_in = ia[pi_, ti_, si_, mi_]
    cross = a_in != ib[pi_, ti_, si_, mi_]
    if np.any(cross):
        ci = np.nonzero(cross)[0]
        a_, b_, ain = lo[ci].copy(), hi[ci].copy(), a_in[ci]
        r_ = pi_[ci]
        for _ in range(60):
            mid = 0.5 * (a_ + b_)
            rr, pp, wl, wu, _k = held.sector_polar(mid)
            xm, ym = _place(held, c_h[r_], a_h[r_], off_h, r_, tooth[ci], rr, pp, wl, wu)
            same = (_inside_values(other, c_o[r_], a_o[r_], off_o, r_, xm, ym) < 0) == ain
            a_ = np.where(same, mid, a_)
            b_ = np.where(same, b_, mid)
        xc = 0.5 * (a_ + b_)
        lo[ci] = np.where(ain, lo[ci], xc)
        hi[ci] = np.where(ain, xc, hi[ci])
    half = 0.5 * (hi - lo)
    nodes = lo[:, None] + half[:, None] * (_GL_X[None, :] + 1.0)
    pts, der = held.segment_local(nodes.ravel())
    cross_local = (pts[:, 0] * der[:, 1] - pts[:, 1] * der[:, 0]).reshape(nodes.shape)  # rho^2 dphi/du
    lo_off, up_off = _flanks(off_h, pi_, tooth, held.teeth)
    lo_off = np.broadcast_to(np.asarray(lo_off, dtype=float), tooth.shape)
    up_off = np.broadcast_to(np.asarray(up_off, dtype=float), tooth.shape)
    d_lo, d_up = held.offset_rate(nodes)
    integrand = cross_local * (1.0 - lo_off[:, None] * d_lo + up_off[:, None] * d_up)
    local = half * np.sum(_GL_W[None, :] * integrand, axis=1)
    ends = []
    for uu in (lo, hi):
        rr, pp, wl, wu, _ = held.sector_polar(uu)
        ang = a_h[pi_] + tooth * held.pitch + pp + up_off * wu - lo_off * wl
        ends.append((rr * np.cos(ang), rr * np.sin(ang)))
    (x0, y0), (x1, y1) = ends
    c = c_h[pi_]
    trans = c[:, 0] * (y1 - y0) - c[:, 1] * (x1 - x0)
    return np.bincount(pi_, weights=0.5 * (local + trans), minlength=n)


def overlap_area(gear1: PolarOutline, gear2: PolarOutline, state: MeshState) -> np.ndarray:
    """Area (mm^2, ``(n,)``) of the overlap of the two placed outlines, by Green's theorem on the
    parts of each boundary inside the other gear."""
    a1 = _boundary_inside_integral(gear2, gear1, state.centre2, state.angle2, state.flanks2,
                                   state.centre1, state.angle1, state.flanks1)
    a2 = _boundary_inside_integral(gear1, gear2, state.centre1, state.angle1, state.flanks1,
                                   state.centre2, state.angle2, state.flanks2)
    return np.maximum(a1 + a2, 0.0)


# -------------------------------------------------------------------- a mesh to check
@dataclass(frozen=True)
class Eccentricity:
    """An offset of a gear's tooth circle from its axis that turns with the gear (mm, rad).

    ``amplitude`` is the offset (half the TIR it shows); ``phase`` its direction (from +x) at
    mesh position 0.
    """

    amplitude: float
    phase: float = 0.0


@dataclass(frozen=True)
class MeshSetup:
    """Two gears placed for a mesh check (mm, rad; see :class:`MeshState` for ``flanks*``).

    ``rotation*`` is the rotation of each gear's tooth 0 at mesh position 0 in the section
    z = 0; gear 2 follows gear 1 at the nominal ratio. ``face_offset2``: height of gear 2's
    z = 0 face above gear 1's (helical section planes are taken in gear 1's face coordinates).
    """

    name: str
    gear1: GearSpec
    gear2: GearSpec
    centre1: tuple[float, float]
    centre2: tuple[float, float]
    rotation1: float
    rotation2: float
    eccentricity1: tuple[Eccentricity, ...] = ()
    eccentricity2: tuple[Eccentricity, ...] = ()
    flanks1: np.ndarray | None = None
    flanks2: np.ndarray | None = None
    face_offset2: float = 0.0

    @classmethod
    def centred(cls, gear1: GearSpec, gear2: GearSpec, centre_distance: float, name: str = "mesh",
                **kwargs) -> "MeshSetup":
        """Gear 1 at the origin, gear 2 at (a, 0); gear 1's tooth 0 on +x in gear 2's space centre,
        so a symmetric pair sits in the middle of its play."""
        rot2 = math.pi + math.pi / gear2.teeth
        return cls(name, gear1, gear2, (0.0, 0.0), (float(centre_distance), 0.0), 0.0, rot2, **kwargs)

    @property
    def centre_distance(self) -> float:
        return math.dist(self.centre1, self.centre2)

    @property
    def has_errors(self) -> bool:
        return bool(self.eccentricity1 or self.eccentricity2 or self.flanks1 is not None
                    or self.flanks2 is not None)

    @property
    def hunting_revolutions(self) -> int:
        """Revolutions of gear 1 after which the same teeth meet again in the same places."""
        return self.gear2.teeth // math.gcd(self.gear1.teeth, self.gear2.teeth)

    def planes(self, count: int | None = None) -> np.ndarray:
        """Section heights (mm, gear 1's face coordinates): one for spur pairs, ``count`` (default 5)
        evenly along the common face of helical pairs."""
        if not (self.gear1.is_helical or self.gear2.is_helical):
            return np.zeros(1)
        lo = max(0.0, self.face_offset2)
        hi = min(self.gear1.face_width, self.face_offset2 + self.gear2.face_width)
        return np.linspace(lo, hi, count or 5)

    def states(self, mesh_positions, planes=None, errors: bool = True) -> MeshState:
        """The mesh at ``mesh_positions`` (gear 1's rotation, rad) in each plane, plane-major."""
        s = np.atleast_1d(np.asarray(mesh_positions, dtype=float))
        planes = np.zeros(1) if planes is None else np.atleast_1d(planes)
        n, P = s.size, planes.size
        t1 = s
        t2 = -(self.gear1.teeth / self.gear2.teeth) * s

        def centre(c, ecc, turn):
            out = np.tile(np.asarray(c, dtype=float), (n, 1))
            if errors:
                for e in ecc:
                    out[:, 0] += e.amplitude * np.cos(e.phase + turn)
                    out[:, 1] += e.amplitude * np.sin(e.phase + turn)
            return out

        c1 = centre(self.centre1, self.eccentricity1, t1)
        c2 = centre(self.centre2, self.eccentricity2, t2)
        a1 = (self.rotation1 + t1)[None, :] + np.atleast_1d(section_rotation(self.gear1, planes))[:, None]
        a2 = (self.rotation2 + t2)[None, :] + np.atleast_1d(
            section_rotation(self.gear2, planes - self.face_offset2))[:, None]
        f1 = self.flanks1 if errors else None
        f2 = self.flanks2 if errors else None
        if P > 1 and f1 is not None and f1.ndim == 3:
            f1 = np.tile(f1, (P, 1, 1))
        if P > 1 and f2 is not None and f2.ndim == 3:
            f2 = np.tile(f2, (P, 1, 1))
        return MeshState(np.tile(c1, (P, 1)), a1.ravel(), np.tile(c2, (P, 1)), a2.ravel(), f1, f2)


def mesh_positions(setup: MeshSetup, steps_per_tooth: int = 24, revolutions: float | None = None) -> np.ndarray:
    """Mesh positions (gear 1's rotation, rad) over ``revolutions`` of gear 1 (default: one tooth
    cycle without errors, the hunting period with them), ``steps_per_tooth`` per tooth of gear 1."""
    z1 = setup.gear1.teeth
    if revolutions is None:
        revolutions = setup.hunting_revolutions if setup.has_errors else 1.0 / z1
    n = max(2, int(round(revolutions * z1 * steps_per_tooth)))
    return np.linspace(0.0, 2 * math.pi * revolutions, n, endpoint=False)


#: the play and tip clearance of recent sweeps without flank errors (:func:`_play_and_clearance`), by their exact inputs
_SWEPT: dict = {}
_SWEPT_KEPT = 16


def _play_and_clearance(setup: MeshSetup, o1: PolarOutline, o2: PolarOutline, st: MeshState,
                        positions: np.ndarray, planes: np.ndarray):
    """:func:`free_play` and :func:`tip_clearance` of ``st`` (``setup`` at ``positions`` in ``planes``,
    plane-major). A verdict sweeps a mesh without errors more than once at the same positions (its
    check, the tolerances' nominal play, in 5 and 3 of the same planes for a helical pair): each
    position's values depend on its own position and plane alone, so a sweep without flank errors is
    kept, by the setup's exact numbers, and a later one in the same or fewer of its planes reads its rows."""
    key = None
    if setup.flanks1 is None and setup.flanks2 is None:
        key = (setup.gear1, setup.gear2, setup.centre1, setup.centre2, setup.rotation1, setup.rotation2,
               setup.eccentricity1, setup.eccentricity2, setup.face_offset2, positions.tobytes())
        try:
            kept = _SWEPT.get(key)
        except TypeError:  # a setup given by unhashable values (centres as lists or arrays): not kept
            key = kept = None
        if kept is not None:
            kept_planes, play, clear = kept
            where = [np.flatnonzero(kept_planes == z) for z in planes]
            if all(w.size for w in where):
                n = positions.size
                rows = np.concatenate([np.arange(w[0] * n, (w[0] + 1) * n) for w in where])
                return Play(*(getattr(play, f)[rows] for f in Play.__dataclass_fields__)), clear[rows]
    play, clear = free_play(o1, o2, st), tip_clearance(o1, o2, st)
    if key is not None:
        if len(_SWEPT) >= _SWEPT_KEPT:
            _SWEPT.pop(next(iter(_SWEPT)))
        _SWEPT[key] = (planes.copy(), play, clear)
    return play, clear


def sweep_mesh(setup: MeshSetup, positions, planes=None, areas: bool = True) -> MeshSweep:
    """Path 1 at every mesh position (and section plane): play, backlash, clearance, interference.

    See :class:`~geargen.checks.results.MeshSweep` for the quantities. ``areas`` computes the
    overlap area where the teeth interfere (at gear 1's running positions).
    """
    positions = np.atleast_1d(np.asarray(positions, dtype=float))
    planes = setup.planes() if planes is None else np.atleast_1d(np.asarray(planes, dtype=float))
    o1, o2 = polar_outline(setup.gear1), polar_outline(setup.gear2)
    n, P = positions.size, planes.size
    st = setup.states(positions, planes)
    play, clear = _play_and_clearance(setup, o1, o2, st, positions, planes)
    clear = clear.reshape(P, n)

    def per_plane(a):
        return np.asarray(a).reshape(P, n)

    ccw, cw = per_plane(play.ccw), per_plane(play.cw)
    cj_ccw, cj_cw = per_plane(play.conjugate_ccw), per_plane(play.conjugate_cw)
    lim_ccw, lim_cw = per_plane(play.limit_ccw), per_plane(play.limit_cw)
    rb1 = o1.r_base
    # candidate interference per plane: (depth mm, code into INTERFERENCE_CODES)
    kind_of_limit = np.array([0, 2, 1])  # CONJUGATE -> none, NON_CONJUGATE -> involute, ROOT_BODY -> tip-to-root

    def intrusion(conj, full, limit):
        with np.errstate(invalid="ignore"):  # inf - inf where nothing touches: no intrusion (NaN, dropped below)
            dep = rb1 * (conj - full)  # turn back from running contact until the feature clears
        # a tip in the mate's root: the radial depth under the tip circle says more than the turn
        return np.where((limit == ROOT_BODY) & (clear < 0), -clear, dep), kind_of_limit[limit]

    cands = [
        intrusion(cj_ccw, ccw, lim_ccw),
        intrusion(cj_cw, cw, lim_cw),
        (-rb1 * (cj_ccw + cj_cw), np.full((P, n), 3)),  # flank interference
        (-clear, np.full((P, n), 1)),  # tip-to-root
    ]
    depth = np.zeros((P, n))
    code = np.zeros((P, n), dtype=int)
    for dep, k in cands:
        dep = np.where(np.isfinite(dep), dep, 0.0)
        hit = (dep > INTERFERENCE_TOLERANCE) & (k > 0) & (dep > depth)
        depth = np.where(hit, dep, depth)
        code = np.where(hit, k, code)
    area = np.zeros((P, n))
    flagged = np.nonzero(code.ravel() > 0)[0]
    if areas and flagged.size:
        sub = st.take(flagged)
        turns = [np.zeros(flagged.size), play.conjugate_ccw[flagged], -play.conjugate_cw[flagged],
                 0.5 * (play.conjugate_ccw[flagged] - play.conjugate_cw[flagged])]
        best = np.zeros(flagged.size)
        for tr in turns:
            tr = np.where(np.isfinite(tr), tr, 0.0)
            best = np.maximum(best, overlap_area(o1, o2, sub.turned(tr)))
        area.ravel()[flagged] = best
    worst_plane = np.argmax(depth, axis=0)
    cols = np.arange(n)
    a = st.centre_distance[:n]
    ang, normal = _backlash(setup, o1, cj_ccw, cj_cw)
    return MeshSweep(
        mesh_position=positions, centre_distance=a,
        play_ccw=np.min(ccw, axis=0), play_cw=np.min(cw, axis=0),
        conjugate_play_ccw=np.min(cj_ccw, axis=0), conjugate_play_cw=np.min(cj_cw, axis=0),
        angular_backlash=ang,
        circumferential_backlash=ang * a * setup.gear1.teeth / (setup.gear1.teeth + setup.gear2.teeth),
        normal_backlash=normal,
        min_clearance=np.min(clear, axis=0),
        interference_depth=depth[worst_plane, cols], interference_area=np.max(area, axis=0),
        interference=code[worst_plane, cols], planes=planes)


def _backlash(setup: MeshSetup, o1: PolarOutline, conjugate_ccw: np.ndarray, conjugate_cw: np.ndarray):
    """(angular, normal) backlash per position from the conjugate play per plane ``(P, n)``: the
    least over the planes both ways (NaN where either side has no contact)."""
    ang = np.min(conjugate_ccw, axis=0) + np.min(conjugate_cw, axis=0)
    ang = np.where(np.isfinite(ang), ang, np.nan)
    return ang, ang * o1.r_base * math.cos(setup.gear1.base_helix_angle)


def sweep_backlash(setup: MeshSetup, positions, planes=None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`sweep_mesh`'s ``angular_backlash`` and ``normal_backlash`` alone, the same numbers: the
    free play without the tip clearance and the interference, which a caller reading only the
    backlash (the worst case of an error budget, the allowances' extreme pairs) does not need."""
    positions = np.atleast_1d(np.asarray(positions, dtype=float))
    planes = setup.planes() if planes is None else np.atleast_1d(np.asarray(planes, dtype=float))
    o1, o2 = polar_outline(setup.gear1), polar_outline(setup.gear2)
    play = free_play(o1, o2, setup.states(positions, planes))
    shape = (planes.size, positions.size)
    return _backlash(setup, o1, play.conjugate_ccw.reshape(shape), play.conjugate_cw.reshape(shape))


# -------------------------------------------------------------------- the check of one mesh
@dataclass(frozen=True)
class CheckSettings:
    """What a mesh check sweeps and what it requires (internal units).

    ``steps_per_tooth`` mesh positions per tooth of gear 1; ``revolutions`` of gear 1 (None:
    one tooth cycle, or the hunting period when errors are given); ``planes`` section planes
    for helical pairs; ``min_contact_ratio`` (transverse for spur, total for helical);
    ``min_tip_land`` in normal modules; ``require_backlash``: the mesh must keep backlash.
    """

    steps_per_tooth: int = 24
    revolutions: float | None = None
    planes: int = 5
    min_contact_ratio: float = 1.1
    min_tip_land_modules: float = 0.2
    require_backlash: bool = True
    contact_ratio_steps: int = 32


#: bisection steps of :func:`measured_contact_ratio` taken per call of the contact count (every
#: midpoint those steps can reach, 2^levels - 1 a bracket, in one call: the count's cost is mostly
#: per call, ~3 ms, against ~0.05 ms a position)
_BISECTION_LEVELS = 4


def _bisect_levels(count, lo, hi, c_lo, levels: int):
    """``levels`` steps of the bisection of :func:`measured_contact_ratio` on the brackets ``[lo, hi]``
    (the count is ``c_lo`` at ``lo``): the midpoints of every path the steps can take are computed
    as the steps compute them and counted in one call, then the steps walk down the tree, so the
    brackets are those of ``levels`` sequential steps, bit for bit (the count of a position does not
    depend on the other positions counted with it)."""
    tree_lo, tree_hi, mids = [lo[:, None]], [hi[:, None]], []
    for _ in range(levels):
        a, b = tree_lo[-1], tree_hi[-1]
        m = 0.5 * (a + b)
        mids.append(m)
        # children of each node: (a, m) then (m, b), interleaved so node j's are 2j and 2j + 1
        tree_lo.append(np.stack([a, m], axis=-1).reshape(len(lo), -1))
        tree_hi.append(np.stack([m, b], axis=-1).reshape(len(lo), -1))
    flat = np.concatenate(mids, axis=1)
    counted = count(flat.ravel()).reshape(flat.shape)
    rows = np.arange(len(lo))
    node, first = np.zeros(len(lo), dtype=int), 0
    for m in mids:
        width = m.shape[1]
        mid = m[rows, node]
        same = counted[rows, first + node] == c_lo
        lo = np.where(same, mid, lo)
        hi = np.where(same, hi, mid)
        node = 2 * node + same
        first += width
    return lo, hi


def measured_contact_ratio(setup: MeshSetup, steps: int = 32, side: str = "ccw", iterations: int = 26) -> float:
    """Transverse contact ratio measured on the exact outlines (no formula).

    Over one tooth cycle of gear 1 (section z = 0, no errors), counts the tooth pairs in
    conjugate contact with gear 1 turned onto its ``side`` flanks; the positions where the count
    changes are bisected to machine precision and the count is integrated over the cycle.
    """
    o1, o2 = polar_outline(setup.gear1), polar_outline(setup.gear2)
    p1 = o1.pitch
    pos = np.linspace(0.0, p1, steps + 1)

    def count(x):
        return contact_count(o1, o2, setup.states(x, errors=False), side)

    c = count(pos)
    change = np.nonzero(c[:-1] != c[1:])[0]
    total = 0.0
    edges = np.diff(pos)
    keep = np.ones(steps, dtype=bool)
    keep[change] = False
    total += float(np.sum(c[:-1][keep] * edges[keep]))
    if change.size:
        lo, hi = pos[change].copy(), pos[change + 1].copy()
        c_lo = c[change]
        done = 0
        while done < iterations:
            levels = min(_BISECTION_LEVELS, iterations - done)
            lo, hi = _bisect_levels(count, lo, hi, c_lo, levels)
            done += levels
        t = 0.5 * (lo + hi)
        total += float(np.sum(c_lo * (t - pos[change]) + c[change + 1] * (pos[change + 1] - t)))
    return total / p1


def _static_failures(setup: MeshSetup, settings: CheckSettings):
    """Per-gear checks that need no sweep: tip land, undercut where the mate's tip works.

    Returns (failures, notes, the pair's :class:`~geargen.core.geometry.MeshGeometry` or None).
    """
    from geargen.core.geometry import GearPair, mesh_geometry  # pair geometry formulas live there

    fails: list[Failure] = []
    notes: list[str] = []
    for g in (setup.gear1, setup.gear2):
        o = polar_outline(g)
        minimum = settings.min_tip_land_modules * g.module
        if o.profile.tip_land < minimum:
            fails.append(Failure("pointed_tooth", setup.name,
                                 f"{g.name}: tip land {length_text(o.profile.tip_land, g.length_unit)} is below "
                                 f"{length_text(minimum, g.length_unit)} ({settings.min_tip_land_modules:g} m_n)",
                                 "tip_land", o.profile.tip_land, minimum))
        if o.profile.undercut:
            notes.append(f"{g.name} is undercut: its involute starts at radius {length_text(o.r_start, g.length_unit, 6)}")
    try:
        geo = mesh_geometry(GearPair(setup.gear1, setup.gear2), setup.centre_distance)
    except GeargenError as exc:  # a pair the formulas reject (e.g. mismatched pitch) is reported, not raised
        notes.append(f"pair geometry not available: {exc}")
        return fails, notes, None
    for k, g in enumerate((setup.gear1, setup.gear2)):
        o = polar_outline(g)
        sap = geo.active_profile_start_radii[k]
        if o.profile.undercut and geo.involute_interference[k]:
            fails.append(Failure("undercut", setup.name,
                                 f"{g.name}: the mate's tip works below where the undercut involute starts "
                                 f"(radius {o.r_start:.6g} mm; start of active profile {sap:.6g} mm"
                                 f"{', beyond the interference point' if sap < o.r_start else ''}): contact is "
                                 "lost there", "start_of_active_profile_length", sap, o.r_start))
        elif geo.involute_interference[k]:
            notes.append(f"{g.name}: the pair formulas put the mate's tip below this gear's involute start; "
                         "the sweep shows whether the tip touches the fillet (involute_interference)")
    return fails, notes, geo


def empty_sweep() -> MeshSweep:
    """A sweep with no positions (for a mesh whose gears cannot be made)."""
    e = np.empty(0)
    return MeshSweep(e, e, e, e, e, e, e, e, e, e, e, e, np.empty(0, dtype=int))


def check_mesh(setup: MeshSetup, settings: CheckSettings = CheckSettings()) -> MeshCheck:
    """Path 1 check of one mesh: sweep, contact ratio, failures (see :mod:`geargen.checks.results`).

    A gear whose outline cannot be cut (flanks meeting below the tip circle, or the undercut
    taking the whole involute) gives a ``pointed_tooth`` or ``undercut`` failure and no sweep.
    """
    for g in (setup.gear1, setup.gear2):
        try:
            polar_outline(g)
        except GeometryError as exc:
            kind = {"pointed_tooth": "pointed_tooth", "no_involute": "undercut"}.get(exc.kind)
            if kind is None:
                raise
            text = str(exc).removeprefix(f"{exc.kind}: ")  # the failure line says its kind
            text = text if text.startswith(f"{g.name}: ") else f"{g.name}: {text}"
            return MeshCheck(mesh=setup.name, gear1=setup.gear1.name, gear2=setup.gear2.name, path="exact_2d",
                             centre_distance=setup.centre_distance, sweep=empty_sweep(),
                             failures=[Failure(kind, setup.name, text)])
    fails, notes, geo = _static_failures(setup, settings)
    pos = mesh_positions(setup, settings.steps_per_tooth, settings.revolutions)
    sw = sweep_mesh(setup, pos, setup.planes(settings.planes))
    eps = measured_contact_ratio(setup, settings.contact_ratio_steps)
    total = eps + (geo.face_contact_ratio if geo is not None else 0.0)  # overlap ratio: 0 for spur pairs
    fails += interference_failures(setup.name, sw)
    if total < settings.min_contact_ratio:
        fails.append(Failure("low_contact_ratio", setup.name,
                             f"contact ratio {total:.4g} (measured transverse {eps:.4g}) is below "
                             f"{settings.min_contact_ratio:g}", "contact_ratio", total, settings.min_contact_ratio))
    # where the teeth never touch there is no backlash to measure (the contact ratio says so)
    if settings.require_backlash and not any(f.kind == "flank_interference" for f in fails) \
            and np.isfinite(sw.normal_backlash).any():
        jmin = float(np.nanmin(sw.normal_backlash))
        if jmin <= INTERFERENCE_TOLERANCE:
            i = int(np.nanargmin(sw.normal_backlash))
            fails.append(Failure("no_backlash", setup.name,
                                 f"normal backlash {jmin:.3g} mm: the flanks touch on both sides",
                                 "normal_backlash", jmin, INTERFERENCE_TOLERANCE, float(sw.mesh_position[i])))
    return MeshCheck(mesh=setup.name, gear1=setup.gear1.name, gear2=setup.gear2.name, path="exact_2d",
                     centre_distance=setup.centre_distance, sweep=sw, failures=fails, contact_ratio=eps,
                     total_contact_ratio=total, notes=notes, tolerance=EXACT_TOLERANCE)


#: stated accuracy of path 1's backlash values (mm): far below the 0.01 um the theory test asks
EXACT_TOLERANCE = 1e-9


def interference_failures(mesh: str, sweep: MeshSweep) -> list[Failure]:
    """One failure per interference kind found in a sweep, at its deepest position."""
    out = []
    for code, kind in enumerate(INTERFERENCE_CODES):
        if code == 0:
            continue
        hit = sweep.interference == code
        if not np.any(hit):
            continue
        depth = np.where(hit, sweep.interference_depth, -np.inf)
        i = int(np.argmax(depth))
        what = {"tip_to_root_interference": "a tip reaches into the mate's root",
                "involute_interference": "a tip works on the mate's fillet (below its involute)",
                "flank_interference": "the flanks overlap on both sides (negative backlash)"}[kind]
        out.append(Failure(kind, mesh, f"{what}: depth {sweep.interference_depth[i]:.4g} mm, area "
                                       f"{sweep.interference_area[i]:.4g} mm^2 at {np.count_nonzero(hit)} of "
                                       f"{len(sweep)} positions",
                           "interference_depth", float(sweep.interference_depth[i]), 0.0,
                           float(sweep.mesh_position[i])))
    return out


__all__ = ["PolarOutline", "polar_outline", "MeshState", "Play", "free_play", "contact_count", "tip_clearance",
           "overlap_area", "Eccentricity", "MeshSetup", "mesh_positions", "sweep_mesh", "sweep_backlash", "CheckSettings",
           "measured_contact_ratio", "check_mesh", "empty_sweep", "interference_failures", "EXACT_TOLERANCE",
           "CONTACT_TOLERANCE", "INTERFERENCE_TOLERANCE"]
