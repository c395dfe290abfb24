"""The play of an involute pair whose tooth circles are eccentric and whose teeth are displaced,
in closed form: the fast model behind the Monte Carlo search of :mod:`geargen.checks.tolerance`.

Why a model beside the exact check (:mod:`geargen.checks.mesh2d`): the minimum backlash of a
build over its hunting period needs the play at tens of thousands of positions per build, and
the exact check costs about 0.1 ms per position. This module answers the same question for the
contacts that make up the conjugate play (involute on involute, and a tip corner on the mate's
involute) from the involute geometry alone; the tests hold it to the exact check within 1e-8 mm,
and every value the tolerance analysis reports is measured by the exact check at the position
this model finds.

Geometry (transverse section, mm, rad; gear 1 turned, gear 2 held, as in mesh2d). With centres
``c1``, ``c2`` a distance ``a`` apart in direction ``gamma`` and ``cos alpha_w = (r_b1 + r_b2)/a``,
gear 1's counter-clockwise (upper) flanks meet gear 2's upper flanks on the line tangent to the
base circles at polar angle ``tau1 = gamma - alpha_w`` about ``c1`` (``T1``) and ``tau1 + pi``
about ``c2`` (``T2``), ``L = a sin alpha_w`` long; the clockwise (lower) flanks on its mirror,
``tau1 = gamma + alpha_w``. ``side`` is +1 for the first, -1 for the second. A flank of gear 2
crosses its line at ``u`` (distance from ``T1``); a tooth pair is in conjugate contact where
``u`` lies on both active involutes (``u_min <= u <= u_max``: tips and involute starts), and
its gap - gear 1's turn to contact times ``r_b1`` - is the difference of the two flanks' ``u``:
exactly linear in both gears' rotations (base pitches are equal), so a tooth displaced by an
angle ``e`` moves it by ``e r_b``. Outside that stretch a pair still meets by a tip corner on
the mate's involute; its gap exceeds the linear one by an excess ``e(du, a)`` that depends only
on how far ``du`` the flank is past the limit and on the centre distance (:meth:`PairModel.pair_gap`
computes it exactly; :class:`TipExcess` tabulates it). The play of a side is the smallest gap
over the tooth pairs; the total (both sides) is the nominal play at ``a`` (exact involute law,
anchored on the exact check) minus each side's largest ``D - e`` over its pairs, ``D`` being
the pair's displacement into that side's gap along the line of action.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geargen.checks.mesh2d import MeshSetup, polar_outline
from geargen.core.involute import backlash_change, involute, roll_length, working_pressure_angle_at
from geargen.design.gear import GearSpec
from geargen.profile.tooth import section_rotation


def wrap_pi(x):
    """Angles reduced to [-pi, pi)."""
    return (np.asarray(x) + np.pi) % (2 * np.pi) - np.pi


@dataclass(frozen=True)
class GearConstants:
    """One gear's transverse outline as the model needs it (mm, rad): tooth 0's upper flank has
    polar angle ``base_half - inv(arccos(r_b / rho))`` at radius ``rho`` from ``involute_start``
    to ``tip_radius``; ``tip_half`` is its polar angle at the tip corner."""

    teeth: int
    pitch: float
    base_radius: float
    reference_radius: float
    tip_radius: float
    involute_start: float
    base_half: float
    tip_half: float

    @classmethod
    def of(cls, spec: GearSpec) -> "GearConstants":
        o = polar_outline(spec)
        return cls(o.teeth, o.pitch, o.r_base, o.r_ref, o.r_tip, max(o.r_start, o.r_base), o.base_half, o.tip_half)

    def flank_angle(self, rho):
        return self.base_half - involute(np.arccos(np.clip(self.base_radius / rho, -1.0, 1.0)))

    @property
    def tip_roll_length(self) -> float:
        """Length of line of action from the base circle to the tip circle (mm)."""
        return roll_length(self.tip_radius, self.base_radius)

    @property
    def start_roll_length(self) -> float:
        return roll_length(self.involute_start, self.base_radius)


@dataclass
class LineGeometry:
    """Where the lines of action lie for centres ``c1``, ``c2`` (arrays of the positions' shape)."""

    distance: np.ndarray
    direction: np.ndarray
    working_angle: np.ndarray
    length: np.ndarray
    u_min: np.ndarray
    u_max: np.ndarray


class PairModel:
    """Closed-form play of the mesh of ``setup`` (see the module docstring).

    ``nominal_angular_play`` (rad): gear 1's free play (both ways) of the error-free mesh at the
    setup's centre distance, from the exact check; it anchors the involute law of
    :meth:`total_play`. ``planes``: transverse section heights for helical pairs (mm, gear 1's
    face coordinates), as the exact check takes them.
    """

    def __init__(self, setup: MeshSetup, nominal_angular_play: float, planes=None):
        self.setup = setup
        self.gear1, self.gear2 = GearConstants.of(setup.gear1), GearConstants.of(setup.gear2)
        self.planes = np.atleast_1d(setup.planes(3) if planes is None else planes).astype(float)
        self.turn1 = np.atleast_1d(section_rotation(setup.gear1, self.planes)).astype(float)
        self.turn2 = np.atleast_1d(section_rotation(setup.gear2, self.planes - setup.face_offset2)).astype(float)
        self.ratio = self.gear1.teeth / self.gear2.teeth
        self.base_sum = self.gear1.base_radius + self.gear2.base_radius
        self.centre_distance = setup.centre_distance
        self.nominal_play = float(nominal_angular_play) * self.gear1.base_radius
        self._inv_nominal = float(involute(working_pressure_angle_at(float(self.base_sum), float(self.centre_distance))))

    # ---------------------------------------------------------------- the error-free pair
    def total_play(self, distance):
        """Play of both sides along the line of action (mm) of the error-free teeth at centre
        distance ``distance``: ``j(a0) + 2 (r_b1 + r_b2)(inv alpha_w(a) - inv alpha_w(a0))``."""
        a = np.asarray(distance, dtype=float)
        return self.nominal_play + backlash_change(self.base_sum, working_pressure_angle_at(self.base_sum, a, clamp=True),
                                                   self._inv_nominal)

    def circumferential(self, play):
        """Play along the line of action (mm) as backlash of the resolved model's kind
        (circumferential at gear 1's reference circle: gear 1's free rotation times its radius)."""
        return np.asarray(play) / self.gear1.base_radius * self.gear1.reference_radius

    def line_geometry(self, c1, c2) -> LineGeometry:
        d = np.asarray(c2) - np.asarray(c1)
        a = np.hypot(d[..., 0], d[..., 1])
        aw = working_pressure_angle_at(self.base_sum, a, clamp=True)
        L = a * np.sin(aw)
        g1, g2 = self.gear1, self.gear2
        u_min = np.maximum(g1.start_roll_length, L - g2.tip_roll_length)
        u_max = np.minimum(g1.tip_roll_length, L - g2.start_roll_length)
        return LineGeometry(a, np.arctan2(d[..., 1], d[..., 0]), aw, L, u_min, u_max)

    # ---------------------------------------------------------------- one tooth pair
    def flank_position(self, geo: LineGeometry, angle2, side):
        """``u`` (mm from T1) where the ``side`` flank of gear 2's tooth with centreline at
        ``angle2`` (rad) crosses its line of action (the branch nearest the contact stretch)."""
        g2 = self.gear2
        tau2 = geo.direction - side * geo.working_angle + np.pi
        t_mid = (geo.length - 0.5 * (geo.u_min + geo.u_max)) / g2.base_radius
        t2 = side * (angle2 + side * g2.base_half - tau2)
        t2 = t_mid + wrap_pi(t2 - t_mid)
        return geo.length - g2.base_radius * t2

    def mate_tooth(self, geo: LineGeometry, angle1_tooth0, u, side):
        """Index (float, integral) of gear 1's tooth whose ``side`` flank meets gear 2's flank at ``u``."""
        g1 = self.gear1
        tau1 = geo.direction - side * geo.working_angle
        return np.rint((tau1 + side * u / g1.base_radius - angle1_tooth0 - side * g1.base_half) / g1.pitch)

    def linear_gap(self, geo: LineGeometry, angle1, u, side):
        """Gap (mm along the line of action) of gear 1's tooth with centreline ``angle1`` against
        gear 2's flank at ``u``, continuing the involute contact beyond the active stretch."""
        g1 = self.gear1
        tau1 = geo.direction - side * geo.working_angle
        return g1.base_radius * wrap_pi(side * (tau1 + side * u / g1.base_radius - angle1) - g1.base_half)

    def pair_gap(self, c1, angle1, c2, angle2, side, newton_steps: int = 8):
        """Exact gap (mm along the line of action; gear 1's turn to contact times ``r_b1``) of the
        tooth pair whose centrelines are at ``angle1`` (gear 1) and ``angle2`` (gear 2), on
        ``side``: involute contact inside the active stretch, a tip corner on the mate's involute
        outside it, ``inf`` where neither is possible. Also returns the linear gap (the
        involute contact continued) and ``u``. Arrays broadcast; ``c*`` have a last axis of 2."""
        g1, g2 = self.gear1, self.gear2
        geo = self.line_geometry(c1, c2)
        u = self.flank_position(geo, angle2, side)
        lin = self.linear_gap(geo, angle1, u, side)
        inside = (u >= geo.u_min - 1e-12) & (u <= geo.u_max + 1e-12)
        gap = np.where(inside, lin, np.inf)
        c1 = np.asarray(c1, dtype=float)
        c2 = np.asarray(c2, dtype=float)
        # gear 2's tip corner on gear 1's involute: gear 1's turn to bring its flank to that point
        corner = angle2 + side * g2.tip_half
        px = c2[..., 0] + g2.tip_radius * np.cos(corner) - c1[..., 0]
        py = c2[..., 1] + g2.tip_radius * np.sin(corner) - c1[..., 1]
        rho = np.hypot(px, py)
        ok = (rho >= g1.involute_start * (1 - 1e-12)) & (rho <= g1.tip_radius * (1 + 1e-12))
        turn = side * wrap_pi(np.arctan2(py, px) - angle1 - side * g1.flank_angle(np.maximum(rho, g1.base_radius)))
        gap = np.minimum(gap, np.where(ok, g1.base_radius * turn, np.inf))
        # gear 1's tip corner on gear 2's involute: the point of gear 2's flank at distance r_a1 from c1
        rho2 = np.sqrt(g2.base_radius ** 2 + np.maximum(geo.length - g1.tip_roll_length, 0.0) ** 2)
        rho2 = np.maximum(rho2, g2.base_radius * (1 + 1e-9))
        dx0, dy0 = c2[..., 0] - c1[..., 0], c2[..., 1] - c1[..., 1]
        for _ in range(newton_steps):
            al = np.arccos(np.clip(g2.base_radius / rho2, -1.0, 1.0))
            beta = angle2 + side * g2.flank_angle(rho2)
            cb, sb = np.cos(beta), np.sin(beta)
            wx, wy = dx0 + rho2 * cb, dy0 + rho2 * sb
            f = wx * wx + wy * wy - g1.tip_radius ** 2
            dbeta = -side * np.tan(al) / rho2  # d(flank polar angle)/d(radius) of an involute
            fp = 2 * (wx * (cb - rho2 * dbeta * sb) + wy * (sb + rho2 * dbeta * cb))
            with np.errstate(divide="ignore", invalid="ignore"):
                rho2 = np.clip(rho2 - f / fp, g2.base_radius * (1 + 1e-9), 2 * g2.tip_radius)
        beta = angle2 + side * g2.flank_angle(rho2)
        wx, wy = dx0 + rho2 * np.cos(beta), dy0 + rho2 * np.sin(beta)
        ok = ((rho2 >= g2.involute_start * (1 - 1e-12)) & (rho2 <= g2.tip_radius * (1 + 1e-12))
              & (np.abs(wx * wx + wy * wy - g1.tip_radius ** 2) < 1e-9 * g1.tip_radius ** 2))
        turn = side * wrap_pi(np.arctan2(wy, wx) - angle1 - side * g1.tip_half)
        gap = np.minimum(gap, np.where(ok, g1.base_radius * turn, np.inf))
        return gap, lin, u

    def side_gap(self, c1, angle1, c2, angle2, side, displacement1=None, displacement2=None, window: int = 3):
        """Play of gear 1 towards ``side`` (mm along the line of action) at positions ``(n,)``:
        the smallest :meth:`pair_gap` over the pairs near the mesh and over the section planes.
        ``angle*`` ``(n,)``: rotation of tooth 0 in the section z = 0; ``displacement*`` ``(n, z)``
        angles (rad, counter-clockwise) by which each tooth is turned, or None."""
        g1, g2 = self.gear1, self.gear2
        c1 = np.asarray(c1, dtype=float)
        c2 = np.asarray(c2, dtype=float)
        geo = self.line_geometry(c1, c2)
        rows = np.arange(len(angle1))
        best = np.full(len(angle1), np.inf)
        for t1, t2 in zip(self.turn1, self.turn2):
            a1, a2 = np.asarray(angle1) + t1, np.asarray(angle2) + t2
            tau2 = geo.direction - side * geo.working_angle + np.pi
            t_mid = (geo.length - 0.5 * (geo.u_min + geo.u_max)) / g2.base_radius
            j0 = np.rint((tau2 + side * t_mid - a2 - side * g2.base_half) / g2.pitch)
            for dj in range(-window, window + 1):
                j = j0 + dj
                b2 = a2 + j * g2.pitch
                if displacement2 is not None:
                    b2 = b2 + displacement2[rows, j.astype(int) % g2.teeth]
                u = self.flank_position(geo, b2, side)
                k = self.mate_tooth(geo, a1, u, side)
                b1 = a1 + k * g1.pitch
                if displacement1 is not None:
                    b1 = b1 + displacement1[rows, k.astype(int) % g1.teeth]
                gap, _, _ = self.pair_gap(c1, b1, c2, b2, side)
                best = np.minimum(best, gap)
        return best

    # ---------------------------------------------------------------- tip-corner excess
    def tip_excess(self, distances, du, side: int = 1, ends=(0, 1)):
        """Exact excess ``gap - linear gap`` (mm) of a tooth pair whose gear-2 flank is ``du``
        (mm, >= 0) before the start (``du`` row 0) and after the end (row 1) of the active
        stretch, at centre distances ``distances``: array ``(2, len(distances), len(du))``
        (``ends``: only these rows, in this order)."""
        a = np.asarray(distances, dtype=float)[:, None]
        du = np.asarray(du, dtype=float)[None, :]
        shape = np.broadcast_shapes(a.shape, du.shape)
        c1 = np.zeros(shape + (2,))
        c2 = np.zeros(shape + (2,))
        c2[..., 0] = a
        geo = self.line_geometry(c1, c2)
        out = []
        for end in ends:
            u = geo.u_min - du if end == 0 else geo.u_max + du
            t2 = (geo.length - u) / self.gear2.base_radius
            tau2 = geo.direction - side * geo.working_angle + np.pi
            angle2 = side * t2 - side * self.gear2.base_half + tau2
            tau1 = geo.direction - side * geo.working_angle
            angle1 = tau1 + side * u / self.gear1.base_radius - side * self.gear1.base_half  # linear gap 0
            gap, lin, _ = self.pair_gap(c1, angle1, c2, angle2, side)
            out.append(gap - lin)
        return np.stack(out)


class TipExcess:
    """:meth:`PairModel.tip_excess` tabulated over centre distance and distance past the active
    stretch, interpolated linearly; beyond ``reach`` (mm) a pair is out of reach (``inf``).

    ``reach`` is where the excess first exceeds ``limit`` (mm) at every tabulated centre
    distance (plus a margin): a pair that far out cannot be the one that bounds the play when
    displacements differ by at most ``limit``.
    """

    def __init__(self, model: PairModel, distances, limit: float, points: int = 257, margin: float = 1.25):
        g1 = model.gear1
        self.distances = np.unique(np.asarray(distances, dtype=float))
        span = 1.5 * g1.base_radius * g1.pitch  # a base pitch and a half
        probe = np.linspace(0.0, span, 2 * points)
        e = model.tip_excess(self.distances, probe)
        reach = []
        for row in e:
            within = np.isfinite(row) & (row <= limit)  # (distances, probe)
            last = np.where(within.any(axis=1), probe.size - 1 - np.argmax(within[:, ::-1], axis=1), 0)
            reach.append(float(probe[min(int(last.max()) + 1, probe.size - 1)]) * margin)
        self.reach = tuple(reach)  # before the start, after the end
        self.du = [np.linspace(0.0, r, points) for r in self.reach]
        self.table = [model.tip_excess(self.distances, du, ends=(k,))[0] for k, du in enumerate(self.du)]
        # both tables in one flat array ([end, distance row, du]) and their steps and reaches, so
        # that :meth:`past_ends` reads either end's per element
        self._flat = np.concatenate([t.ravel() for t in self.table])
        self._step = np.array([du[1] - du[0] for du in self.du])
        self._reach = np.array(self.reach)

    def __call__(self, which: int, distance, du):
        """Excess (mm) at centre distances ``distance`` and ``du`` past the start (``which`` 0) or
        the end (1) of the active stretch; 0 inside (``du`` <= 0), ``inf`` beyond reach."""
        return self._lookup(which, self.weights(distance), np.asarray(du, dtype=float))

    def weights(self, distance):
        """Where centre distances ``distance`` fall in the table: (row, weight of the next row, next row)."""
        a = np.asarray(distance, dtype=float)
        if self.distances.size == 1:
            ia = np.zeros(a.shape, dtype=int)
            fa = np.zeros(a.shape)
        else:
            ya = np.clip(np.interp(a, self.distances, np.arange(self.distances.size)), 0, self.distances.size - 1 - 1e-9)
            ia = np.floor(ya).astype(int)
            fa = ya - ia
        return ia, fa, np.minimum(ia + 1, self.distances.size - 1)

    def past_ends(self, weights, u, u_min, u_max):
        """Excess (mm) of flanks at ``u`` on lines of action whose active stretch is ``[u_min, u_max]``
        (0 inside it), at centre distances of :meth:`weights` ``weights`` (broadcasting): the two
        ends' tables read in one pass, each element as :meth:`__call__` reads it."""
        return self.read_ends(weights, *self.ends(u, u_min, u_max))

    @staticmethod
    def ends(u, u_min, u_max):
        """Which end of the stretch ``[u_min, u_max]`` flanks at ``u`` are past (0 the start, 1 the
        end; 0 inside) and how far (mm, 0 inside): :meth:`past_ends` in two steps."""
        below, above = u < u_min, u > u_max
        return above.astype(int), np.where(above, u - u_max, np.where(below, u_min - u, 0.0))

    def out_of_reach(self, which, du):
        """Where the excess past end ``which`` at ``du`` is ``inf`` (the pair cannot bound the play)."""
        return du > self._reach[which]

    def read_ends(self, weights, which, du):
        """:meth:`past_ends` of the flanks :meth:`ends` gave ``(which, du)``."""
        return self._lookup(which, weights, du)

    def _lookup(self, which, weights, d):
        """The tables' bilinear interpolation at ``d`` past the end ``which`` (0 or 1, or an array of them)."""
        ia, fa, ia1 = weights
        points = self.du[0].size
        x = np.clip(d / self._step[which], 0.0, points - 1 - 1e-9)
        i = np.floor(x).astype(int)
        fx = x - i
        first = which * (self.distances.size * points) + i
        lo, hi = first + ia * points, first + ia1 * points
        tab = self._flat
        with np.errstate(invalid="ignore"):
            v = ((1 - fa) * ((1 - fx) * tab[lo] + fx * tab[lo + 1])
                 + fa * ((1 - fx) * tab[hi] + fx * tab[hi + 1]))
        v = np.where(np.isnan(v), np.inf, v)
        return np.where(d <= 0, 0.0, np.where(d > self._reach[which], np.inf, v))


# -------------------------------------------------------------------- the hunting-period search
_GOLDEN = 0.3819660112501051
#: positions per block of :meth:`HuntingSearch.evaluate` (its temporaries, positions x window, stay
#: in cache; one block for all 5e4 positions of a search was slower than the pair-at-a-time loop)
_EVALUATE_BLOCK = 2048


class HuntingSearch:
    """The smallest play of each build over the whole hunting period of a pair on fixed bearings.

    A build: each gear's tooth circle offset from its axis by a bearing and a pitch-line
    eccentricity (amplitudes ``(b1, p1, b2, p2)`` mm, phases at mesh position 0), turning with
    the gear, and every tooth turned by its own small angle. Mesh position ``s`` is gear 1's
    rotation; gear 2 follows at the nominal ratio. The play at ``s`` is :meth:`evaluate`.

    The search is exhaustive in this sense: a lower bound of the play over each tooth cycle of
    gear 1 (the smallest centre distance in the cycle, and on each side the largest
    displacement of any tooth pair that can reach the contact stretch during it) rules cycles
    out; every other cycle is evaluated at every contact-stretch edge (where the play has its
    kinks, on both sides of each) and on a grid of ``steps_per_tooth``, and the best local
    minima are refined by golden section. Cycles are taken in order of their bound until no
    cycle's bound is below the best play found.
    """

    def __init__(self, model: PairModel, amplitudes, excess: TipExcess, steps_per_tooth: int = 8,
                 refine: int = 4, iterations: int = 16):
        self.model = model
        self.excess = excess
        self.amplitudes = tuple(float(v) for v in amplitudes)
        self.steps = int(steps_per_tooth)
        self.refine = int(refine)
        self.iterations = int(iterations)
        g1, g2 = model.gear1, model.gear2
        su = model.setup
        self.period = 2 * math.pi * su.hunting_revolutions
        self.cycles = int(round(self.period / g1.pitch))
        b1, p1, b2, p2 = self.amplitudes
        # how far the eccentricities can move a contact-stretch edge, as mesh position (generous)
        # how far the eccentricities can move a contact-stretch edge, as mesh position: the flank's
        # place on the line of action against the stretch's ends moves by at most about
        # (1 + 1/sin(alpha_w) + r_b2/a cot(alpha_w)) times the centre offsets; 8x is generous
        self.shift = 8.0 * (b1 + p1 + b2 + p2) / g1.base_radius + 0.02 * g1.pitch
        c1 = np.asarray(su.centre1, dtype=float)
        c2 = np.asarray(su.centre2, dtype=float)
        geo = model.line_geometry(c1, c2)
        self.tracks = []
        reach_s = (excess.reach[0] / g1.base_radius, excess.reach[1] / g1.base_radius)
        for side in (1, -1):
            for p, (t1, t2) in enumerate(zip(model.turn1, model.turn2)):
                self.tracks.append(self._passages(geo, side, p, t1, t2, reach_s))
        # pairs evaluated around the middle of the stretch: the stretch and the tip-corner reach
        span = (float(geo.u_max - geo.u_min) + sum(excess.reach)) / (g1.base_radius * g1.pitch)
        self.window = int(math.ceil(span / 2)) + 1

    def _passages(self, geo, side, plane, t1, t2, reach_s):
        """Every passage of a gear-2 tooth through the contact stretch of one side and plane over
        the period (and a margin), for the error-free mesh: tooth indices, mate on gear 1,
        nominal entry and exit positions, and the cycles each can touch."""
        m, g1, g2 = self.model, self.model.gear1, self.model.gear2
        su = m.setup
        rho = m.ratio
        L, u_lo, u_hi = float(geo.length), float(geo.u_min), float(geo.u_max)
        tau2 = float(geo.direction) - side * float(geo.working_angle) + math.pi
        t_lo, t_hi = (L - u_hi) / g2.base_radius, (L - u_lo) / g2.base_radius
        const = su.rotation2 + t2 + side * g2.base_half - tau2
        # side +1: t2 = const - rho s + j p2 falls through [t_lo, t_hi] (enter at t_hi);
        # side -1: t2 = -(const - rho s + j p2) rises through it (enter at t_lo)
        if side > 0:
            entry = lambda j: (const + j * g2.pitch - t_hi) / rho
            leave = lambda j: (const + j * g2.pitch - t_lo) / rho
        else:
            entry = lambda j: (const + j * g2.pitch + t_lo) / rho
            leave = lambda j: (const + j * g2.pitch + t_hi) / rho
        margin = max(reach_s) + self.shift + 2 * g1.pitch
        j_first = math.floor((-margin - entry(0)) * rho / g2.pitch) - 1
        j_last = math.ceil((self.period + margin - entry(0)) * rho / g2.pitch) + 1
        j = np.arange(j_first, j_last + 1)
        e0, x0 = entry(j), leave(j)
        keep = (x0 > -margin) & (e0 < self.period + margin)
        j, e0, x0 = j[keep], e0[keep], x0[keep]
        mid = 0.5 * (e0 + x0)
        u_mid = 0.5 * (u_lo + u_hi)
        tau1 = float(geo.direction) - side * float(geo.working_angle)
        a1 = su.rotation1 + mid + t1
        k = np.rint((tau1 + side * u_mid / g1.base_radius - a1 - side * g1.base_half) / g1.pitch)
        lo = e0 - reach_s[0] - self.shift
        hi = x0 + reach_s[1] + self.shift
        return {"side": side, "plane": plane, "turn1": t1, "turn2": t2, "j": j.astype(int), "k": k.astype(int),
                "entry0": e0, "exit0": x0, "reach_lo": lo, "reach_hi": hi}

    # ---------------------------------------------------------------- geometry of the builds
    def offsets(self, phases):
        """Each gear's tooth-circle offset at mesh position 0 (complex, mm) for eccentricity phases
        ``(..., 4)``: its two offsets turn together, one complex amplitude per gear."""
        b1, p1, b2, p2 = self.amplitudes
        ph = np.asarray(phases)
        return (b1 * np.exp(1j * ph[..., 0]) + p1 * np.exp(1j * ph[..., 1]),
                b2 * np.exp(1j * ph[..., 2]) + p2 * np.exp(1j * ph[..., 3]))

    def centres(self, phases, s, offsets=None):
        """Tooth-circle centres ``(..., 2)`` at mesh positions ``s`` for eccentricity phases
        ``phases`` (broadcasting against ``s[..., None]``: ``(..., 4)``), or for the :meth:`offsets`
        ``offsets`` already read from them."""
        x1, y1, x2, y2 = self._centre_columns(phases, s, offsets)
        return np.stack([x1, y1], -1), np.stack([x2, y2], -1)

    def _centre_columns(self, phases, s, offsets=None):
        """:meth:`centres` as their four coordinates (x1, y1, x2, y2), not stacked."""
        su = self.model.setup
        o1, o2 = self.offsets(phases) if offsets is None else offsets
        s = np.asarray(s, dtype=float)
        w1 = o1 * (np.cos(s) + 1j * np.sin(s))
        r2 = self.model.ratio * s
        w2 = o2 * (np.cos(r2) - 1j * np.sin(r2))
        return su.centre1[0] + w1.real, su.centre1[1] + w1.imag, su.centre2[0] + w2.real, su.centre2[1] + w2.imag

    def distance(self, phases, s, offsets=None):
        """Centre distance (mm) at mesh positions ``s``, as :meth:`centres`."""
        x1, y1, x2, y2 = self._centre_columns(phases, s, offsets)
        return np.hypot(x2 - x1, y2 - y1)

    def evaluate(self, phases, disp1, disp2, rows, s, offsets=None):
        """Play of both sides (mm along the line of action) and centre distance at positions
        ``s`` ``(n,)`` of builds ``rows`` ``(n,)``: ``phases`` ``(S, 4)``, ``disp*`` ``(S, z)``
        tooth angles (rad); ``offsets``: the builds' :meth:`offsets` if already read. Tip-corner
        contacts come from the :class:`TipExcess` table."""
        rows, s = np.asarray(rows), np.asarray(s, dtype=float)
        # each build's offsets read once (the same numbers as from its phases at every position)
        offsets = self.offsets(phases) if offsets is None else offsets
        if s.ndim == 1 and s.size > _EVALUATE_BLOCK:
            parts = [self.evaluate(phases, disp1, disp2, rows[i:i + _EVALUATE_BLOCK], s[i:i + _EVALUATE_BLOCK], offsets)
                     for i in range(0, s.size, _EVALUATE_BLOCK)]
            return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])
        m, g1, g2 = self.model, self.model.gear1, self.model.gear2
        su = m.setup
        c1, c2 = self.centres(None, s, (offsets[0][rows], offsets[1][rows]))
        geo = m.line_geometry(c1, c2)
        # the window's tooth pairs all at once (window down, positions across): elementwise the same
        # arithmetic as one pair at a time, a tenth of the numpy calls; a run of window slots is a
        # contiguous block of positions
        wide = LineGeometry(geo.distance[None], geo.direction[None], geo.working_angle[None],
                            geo.length[None], geo.u_min[None], geo.u_max[None])
        window = np.arange(-self.window, self.window + 1).reshape((-1,) + (1,) * s.ndim)
        rows_w = rows[None]
        positions = tuple(range(1, s.ndim + 1))
        # where each position's centre distance falls in the excess table: the same for every pair
        weights = tuple(w[None] for w in self.excess.weights(geo.distance))
        H = {1: np.full(s.shape, -np.inf), -1: np.full(s.shape, -np.inf)}
        for tr in self.tracks:
            side = tr["side"]
            a1 = su.rotation1 + s + tr["turn1"]
            a2 = su.rotation2 - m.ratio * s + tr["turn2"]
            tau2 = geo.direction - side * geo.working_angle + np.pi
            t_mid = (geo.length - 0.5 * (geo.u_min + geo.u_max)) / g2.base_radius
            j0 = np.rint((tau2 + side * t_mid - a2 - side * g2.base_half) / g2.pitch).astype(int)
            j = j0[None] + window
            e2 = disp2[rows_w, j % g2.teeth]
            u = m.flank_position(wide, a2[None] + j * g2.pitch + e2, side)
            # the tip-corner excess of a pair past an end of the stretch (most of the window; 0 inside)
            which, du = self.excess.ends(u, wide.u_min, wide.u_max)
            # a window slot out of reach at every position (its excess inf) adds -inf to the maximum:
            # only the slots from the first to the last within reach somewhere are read on
            # (40-60 % of the shipped designs' windows are out of reach, at the window's ends)
            reachable = np.flatnonzero(~np.all(self.excess.out_of_reach(which, du), axis=positions))
            if reachable.size == 0:
                continue
            slots = slice(int(reachable[0]), int(reachable[-1]) + 1)
            k = m.mate_tooth(wide, a1[None], u[slots], side).astype(int)
            D = side * (g1.base_radius * disp1[rows_w, k % g1.teeth] + g2.base_radius * e2[slots])
            e = self.excess.read_ends(weights, which[slots], du[slots])
            H[side] = np.maximum(H[side], np.max(D - e, axis=0, initial=-np.inf))
        return m.total_play(geo.distance) - H[1] - H[-1], geo.distance

    # ---------------------------------------------------------------- the search
    def _distance_minima(self, phases):
        """Local minima of the centre distance over the period, per build (NaN-padded)."""
        S = phases.shape[0]
        n = max(64 * self.model.setup.hunting_revolutions, 2 * self.cycles)
        n = int(n * max(1.0, self.model.ratio))
        s = np.linspace(0.0, self.period, n, endpoint=False)
        a = self.distance(phases[:, None, :], s[None, :])
        is_min = (a <= np.roll(a, 1, axis=1)) & (a < np.roll(a, -1, axis=1))
        counts = is_min.sum(axis=1)
        M = max(1, int(counts.max()))
        idx = np.argsort(~is_min, axis=1, kind="stable")[:, :M]
        valid = np.arange(M)[None, :] < counts[:, None]
        h = self.period / n
        lo = s[idx] - h
        hi = s[idx] + h
        offsets = self.offsets(phases[:, None, :])  # each build's, once for the 40 steps
        x = s[idx]
        fx = self.distance(None, x, offsets)
        for _ in range(40):
            above, below = hi - x, x - lo
            right = above >= below
            u = np.where(right, x + _GOLDEN * above, x - _GOLDEN * below)
            fu = self.distance(None, u, offsets)
            better = fu < fx
            lo, hi = (np.where(better, np.where(right, x, lo), np.where(right, lo, u)),
                      np.where(better, np.where(right, hi, x), np.where(right, u, hi)))
            x = np.where(better, u, x)
            fx = np.where(better, fu, fx)
        return np.where(valid, np.mod(x, self.period), np.nan), np.where(valid, fx, np.nan)

    def _events(self, tr, phases, disp2, rows, n):
        """Entry and exit positions ``(..., 2)`` of passages ``n`` of track ``tr`` for builds
        ``rows`` (broadcasting index arrays): Newton from the error-free positions."""
        m, g1, g2 = self.model, self.model.gear1, self.model.gear2
        su = m.setup
        side = tr["side"]
        j = tr["j"][n]
        s = np.stack([tr["entry0"][n], tr["exit0"][n]], -1) + np.zeros(np.shape(rows) + (1,))
        e2 = disp2[rows, j % g2.teeth][..., None]
        jp = (j * g2.pitch)[..., None]
        ph = phases[rows][..., None, :]
        for _ in range(3):
            c1, c2 = self.centres(ph, s)
            geo = m.line_geometry(c1, c2)
            u = m.flank_position(geo, su.rotation2 - m.ratio * s + tr["turn2"] + jp + e2, side)
            # side +1 enters at u_min and leaves at u_max; side -1 the other way round
            lim = np.stack([geo.u_min[..., 0], geo.u_max[..., 1]], -1) if side > 0 else \
                np.stack([geo.u_max[..., 0], geo.u_min[..., 1]], -1)
            s = s - (u - lim) / (side * g1.base_radius)
        return s

    def _cycle_bounds(self, phases, disp1, disp2, a_min_pos, a_min_val):
        """Lower bound of the play over each tooth cycle of gear 1, per build ``(S, C)``."""
        m, g1, g2 = self.model, self.model.gear1, self.model.gear2
        S, C = phases.shape[0], self.cycles
        edges = np.arange(C + 1) * g1.pitch
        a_edges = self.distance(phases[:, None, :], edges[None, :])
        a_lo = np.minimum(a_edges[:, :-1], a_edges[:, 1:])
        cyc = np.floor(a_min_pos / g1.pitch)
        ok = np.isfinite(a_min_pos)
        rows = np.repeat(np.arange(S)[:, None], a_min_pos.shape[1], axis=1)
        np.minimum.at(a_lo, (rows[ok], np.clip(cyc[ok].astype(int), 0, C - 1)), a_min_val[ok])
        Hmax = {1: np.full((S, C), -np.inf), -1: np.full((S, C), -np.inf)}
        for tr in self.tracks:
            D = tr["side"] * (g1.base_radius * disp1[:, tr["k"] % g1.teeth] + g2.base_radius * disp2[:, tr["j"] % g2.teeth])
            first = np.searchsorted(tr["reach_hi"], edges[:-1], side="right")  # reach_hi is increasing
            last = np.searchsorted(tr["reach_lo"], edges[1:], side="left") - 1
            width = int(np.max(last - first)) + 1 if C else 0
            tr["first"], tr["last"], tr["width"] = first, last, max(width, 0)
            h = Hmax[tr["side"]]
            for w in range(max(width, 0)):
                n = first + w
                valid = n <= last
                v = D[:, np.clip(n, 0, D.shape[1] - 1)]
                h = np.maximum(h, np.where(valid[None, :], v, -np.inf))
            Hmax[tr["side"]] = h
        return m.total_play(a_lo) - Hmax[1] - Hmax[-1]

    def search(self, phases, disp1, disp2):
        """Smallest play of each build over the hunting period: ``(s_min, play_min, a_at_min)``,
        ``(S,)`` each (mm along the line of action, rad, mm). ``disp*`` ``(S, z)``: tooth angles."""
        phases = np.asarray(phases, dtype=float)
        S = phases.shape[0]
        g1 = self.model.gear1
        p1 = g1.pitch
        a_pos, a_val = self._distance_minima(phases)
        lb = self._cycle_bounds(phases, disp1, disp2, a_pos, a_val)
        order = np.argsort(lb, axis=1)
        lb_sorted = np.take_along_axis(lb, order, axis=1)
        best = np.full(S, np.inf)
        best_s = np.zeros(S)
        positions, values = [], []
        taken = 0
        batch = 8
        grid = (np.arange(self.steps) + 0.5) / self.steps * p1
        while taken < self.cycles:
            cand = lb_sorted[:, taken:taken + batch] <= best[:, None]
            if not cand.any():
                break
            cyc = order[:, taken:taken + batch]
            rows_c, slot = np.nonzero(cand)
            c = cyc[rows_c, slot]
            pts = [c[:, None] * p1 + grid[None, :]]
            lo, hi = c * p1, (c + 1) * p1
            eps = 1e-7 * p1
            for tr in self.tracks:
                n = tr["first"][c][:, None] + np.arange(tr["width"])[None, :]
                n = np.clip(n, 0, tr["j"].size - 1)
                flat = self._events(tr, phases, disp2, rows_c[:, None], n).reshape(rows_c.size, -1)
                inside = (flat >= lo[:, None]) & (flat < hi[:, None])
                pts.append(np.where(inside, flat - eps, np.nan))
                pts.append(np.where(inside, flat + eps, np.nan))
            inside = (a_pos[rows_c] >= lo[:, None]) & (a_pos[rows_c] < hi[:, None])
            pts.append(np.where(inside, a_pos[rows_c], np.nan))
            P = np.concatenate(pts, axis=1)
            P = np.sort(np.clip(P, lo[:, None], hi[:, None] - 1e-12 * p1), axis=1)  # NaN last
            r = np.repeat(rows_c[:, None], P.shape[1], axis=1)
            fin = np.isfinite(P)
            v = np.full(P.shape, np.inf)
            v[fin] = self.evaluate(phases, disp1, disp2, r[fin], P[fin])[0]
            positions.append((rows_c, P))
            values.append(v)
            k = np.argmin(v, axis=1)
            vmin = v[np.arange(v.shape[0]), k]
            upd = np.full(S, np.inf)
            np.minimum.at(upd, rows_c, vmin)
            better = upd < best
            best = np.where(better, upd, best)
            taken += batch
        self.cycles_examined = taken  # tooth cycles whose bound did not rule them out (at most)
        # refine the best local minima of each build by golden section between their neighbours
        rows_all = np.concatenate([p[0] for p in positions])
        P_all = np.concatenate([np.pad(p[1], ((0, 0), (0, max(q[1].shape[1] for q in positions) - p[1].shape[1])),
                                       constant_values=np.nan) for p in positions])
        V_all = np.concatenate([np.pad(v, ((0, 0), (0, P_all.shape[1] - v.shape[1])), constant_values=np.inf)
                                for v in values])
        left = np.concatenate([np.full((V_all.shape[0], 1), np.inf), V_all[:, :-1]], axis=1)
        right = np.concatenate([V_all[:, 1:], np.full((V_all.shape[0], 1), np.inf)], axis=1)
        local = np.isfinite(V_all) & (V_all <= left) & (V_all <= right)
        score = np.where(local, V_all, np.inf)
        # the `refine` best local minima of each build
        flat_rows = np.repeat(rows_all[:, None], V_all.shape[1], axis=1)[np.isfinite(score)]
        flat_score = score[np.isfinite(score)]
        flat_i, flat_col = np.nonzero(np.isfinite(score))
        order = np.lexsort((flat_score, flat_rows))
        rank = np.zeros(order.size, dtype=int)
        fr = flat_rows[order]
        start = np.r_[0, np.nonzero(fr[1:] != fr[:-1])[0] + 1]
        rank_sorted = np.arange(order.size) - np.repeat(start, np.diff(np.r_[start, order.size]))
        rank[order] = rank_sorted
        pick = rank < self.refine
        i, col, rws = flat_i[pick], flat_col[pick], flat_rows[pick]
        x = P_all[i, col]
        fx = V_all[i, col]
        cyc_lo = np.floor(x / p1) * p1
        lo = np.where(col > 0, P_all[i, np.maximum(col - 1, 0)], cyc_lo)
        hi_col = np.minimum(col + 1, P_all.shape[1] - 1)
        hi = np.where((col + 1 < P_all.shape[1]) & np.isfinite(P_all[i, hi_col]), P_all[i, hi_col], cyc_lo + p1)
        lo = np.where(np.isfinite(lo), lo, cyc_lo)
        for _ in range(self.iterations):
            above, below = hi - x, x - lo
            go_right = above >= below
            u = np.where(go_right, x + _GOLDEN * above, x - _GOLDEN * below)
            fu = self.evaluate(phases, disp1, disp2, rws, u)[0]
            better = fu < fx
            lo, hi = (np.where(better, np.where(go_right, x, lo), np.where(go_right, lo, u)),
                      np.where(better, np.where(go_right, hi, x), np.where(go_right, u, hi)))
            x = np.where(better, u, x)
            fx = np.where(better, fu, fx)
        best = np.full(S, np.inf)
        order = np.lexsort((fx, rws))
        first = np.r_[True, rws[order][1:] != rws[order][:-1]]
        sel = order[first]
        best[rws[sel]] = fx[sel]
        best_s[rws[sel]] = x[sel]
        a_best = self.distance(phases, best_s)
        return best_s, best, a_best


__all__ = ["GearConstants", "LineGeometry", "PairModel", "TipExcess", "HuntingSearch", "wrap_pi"]
