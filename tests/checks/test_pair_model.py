"""The closed-form pair model (geargen.checks.pair_model) against the exact 2-D check, and the
hunting-period search against brute force."""

import math

import numpy as np
import pytest

from geargen.checks.mesh2d import MeshSetup, MeshState, free_play, polar_outline
from geargen.checks.pair_model import HuntingSearch, PairModel, TipExcess

from checks_support import gear, inch_gear

IN = 25.4

PAIRS = {
    # (gear 1, gear 2, centre distance mm, tooth-to-tooth TIR of each gear mm, eccentricity amplitude mm)
    "inch_21_112": (inch_gear(21, thinning=0.001 * IN), inch_gear(112, thinning=0.0015 * IN), 2.078125 * IN,
                    0.0005 * IN, 0.001 * IN),
    "inch_16_48": (inch_gear(16, thinning=0.000452 * IN), inch_gear(48, thinning=0.000452 * IN), 1.004 * IN,
                   0.0005 * IN, 0.0005 * IN),
    "metric_18_45": (gear(18, thinning=0.04), gear(45, thinning=0.04), 63.05, 0.012, 0.02),
}


def _model(g1, g2, a):
    su = MeshSetup.centred(g1, g2, a)
    play = free_play(polar_outline(g1), polar_outline(g2), su.states([0.0]))
    return su, PairModel(su, play.conjugate_ccw[0] + play.conjugate_cw[0], planes=[0.0])


@pytest.mark.parametrize("name", PAIRS)
def test_side_gaps_equal_the_exact_check(name):
    """Random positions, eccentric centres and a random displacement of every tooth: each side's
    play from the model equals the exact check's conjugate play. 1e-8 mm: the exact check
    refines its contacts to about 1e-11 mm; the model is closed form (tip corners by Newton)."""
    g1, g2, a0, t, ecc = PAIRS[name]
    su, m = _model(g1, g2, a0)
    o1, o2 = polar_outline(g1), polar_outline(g2)
    rng = np.random.default_rng(11)
    n = 1500
    d1 = rng.uniform(-t / 2, t / 2, g1.teeth) / o1.r_ref
    d2 = rng.uniform(-t / 2, t / 2, g2.teeth) / o2.r_ref
    s = rng.uniform(0, 2 * math.pi, n)
    ph = rng.uniform(0, 2 * math.pi, (2, n))
    c1 = np.column_stack([ecc * np.cos(ph[0] + s), ecc * np.sin(ph[0] + s)])
    c2 = np.column_stack([a0 + ecc * np.cos(ph[1] - s), ecc * np.sin(ph[1] - s)])
    a1 = su.rotation1 + s
    a2 = su.rotation2 - g1.teeth / g2.teeth * s
    # gear 1 in the middle of its play (as the tolerance analysis places it)
    a1 = a1 + (m.side_gap(c1, a1, c2, a2, 1) - m.side_gap(c1, a1, c2, a2, -1)) / (2 * o1.r_base)
    D1, D2 = np.tile(d1, (n, 1)), np.tile(d2, (n, 1))
    exact = free_play(o1, o2, MeshState(c1, a1, c2, a2, np.column_stack([-d1, d1]), np.column_stack([-d2, d2])))
    for side, ex in ((1, exact.conjugate_ccw), (-1, exact.conjugate_cw)):
        model = m.side_gap(c1, a1, c2, a2, side, D1, D2)
        assert np.max(np.abs(model - ex * o1.r_base)) < 1e-8


def test_total_play_follows_the_involute_law():
    g1, g2, a0, _, _ = PAIRS["inch_21_112"]
    su, m = _model(g1, g2, a0)
    o1, o2 = polar_outline(g1), polar_outline(g2)
    for a in (a0 - 0.05, a0 + 0.05):
        st = MeshSetup.centred(g1, g2, a).states([0.0])
        p = free_play(o1, o2, st)
        assert m.total_play(a) == pytest.approx((p.conjugate_ccw[0] + p.conjugate_cw[0]) * o1.r_base, abs=1e-10)


def test_tip_excess_table_matches_the_exact_tip_contact():
    """The tabulated tip-corner excess against the exact one between table points, within 5e-7 mm
    where it matters (excess below the displacement spread; the table is linear in both centre
    distance and distance past the stretch, 33 x 257 points as the tolerance analysis builds it)."""
    g1, g2, a0, t, ecc = PAIRS["inch_21_112"]
    su, m = _model(g1, g2, a0)
    table = TipExcess(m, np.linspace(a0 - 2 * ecc, a0 + 2 * ecc, 33), 2 * t)
    for which in (0, 1):
        du = np.linspace(0.0, table.reach[which], 1001)[1:-1]
        a = a0 + 0.37 * ecc
        exact = m.tip_excess([a], du)[which, 0]
        assert np.all(exact >= -1e-12)  # a tip corner never reaches further than the involute would
        err = np.abs(table(which, np.full(du.shape, a), du) - exact)
        assert np.max(err[exact <= 2 * t]) < 5e-7
    assert table.reach[0] > 0 and table.reach[1] > 0


def test_hunting_search_finds_the_minimum_over_the_period():
    """For random builds the search's minimum is no higher than the model on a dense grid of the
    whole hunting period (64 positions per tooth), and within 1e-9 mm of that grid wherever the
    grid lands on the minimiser's neighbourhood (the grid cannot be lower: the search also
    evaluates every contact-stretch edge, where the play has its kinks)."""
    g1, g2, a0, t, ecc = PAIRS["metric_18_45"]
    su, m = _model(g1, g2, a0)
    amps = (0.3 * ecc, ecc, 0.5 * ecc, ecc)
    o1, o2 = polar_outline(g1), polar_outline(g2)
    spread = 2 * t * (o1.r_base / o1.r_ref + o2.r_base / o2.r_ref) / 2
    excess = TipExcess(m, np.linspace(a0 - sum(amps), a0 + sum(amps), 9), spread)
    search = HuntingSearch(m, amps, excess)
    rng = np.random.default_rng(3)
    S = 12
    ph = rng.uniform(0, 2 * math.pi, (S, 4))
    d1 = rng.uniform(-t / 2, t / 2, (S, g1.teeth)) / o1.r_ref
    d2 = rng.uniform(-t / 2, t / 2, (S, g2.teeth)) / o2.r_ref
    s_min, v_min, a_min = search.search(ph, d1, d2)
    grid = np.arange(search.cycles * 64) / 64 * o1.pitch
    for i in range(S):
        v, _ = search.evaluate(ph, d1, d2, np.full(grid.size, i), grid)
        assert v_min[i] <= v.min() + 1e-9
        # and the search's value is really attained where it says
        again, _ = search.evaluate(ph, d1, d2, np.array([i]), np.array([s_min[i]]))
        assert again[0] == pytest.approx(v_min[i], abs=1e-12)
