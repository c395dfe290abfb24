"""HuntingSearch.evaluate reads the whole window of tooth pairs at once (issue 28); the pair-at-a-time
loop it replaced is kept here as the reference. On shipped meshes (robot joint, split pinion: helical,
three planes) and a spur pair, at random builds and positions, the plays are the same to the last bit
(the same float operations on every pair, in the same order; the maximum is exact), and so is
the whole hunting-period search."""

import math
from pathlib import Path

import numpy as np
import pytest

from geargen.checks.mesh2d import MeshSetup, free_play, polar_outline
from geargen.checks.pair_model import HuntingSearch, PairModel, TipExcess
from geargen.checks.verdict import mesh_setup
from geargen.design.assembly import load_design
from geargen.drives.resolver import resolve

from checks_support import gear

ASSEMBLIES = Path(__file__).resolve().parents[2] / "assemblies"


def reference_evaluate(self, phases, disp1, disp2, rows, s):
    """One tooth pair of the window at a time (geargen before issue 28)."""
    m, g1, g2 = self.model, self.model.gear1, self.model.gear2
    su = m.setup
    c1, c2 = self.centres(phases[rows], s)
    geo = m.line_geometry(c1, c2)
    H = {1: np.full(s.shape, -np.inf), -1: np.full(s.shape, -np.inf)}
    for tr in self.tracks:
        side = tr["side"]
        a1 = su.rotation1 + s + tr["turn1"]
        a2 = su.rotation2 - m.ratio * s + tr["turn2"]
        tau2 = geo.direction - side * geo.working_angle + np.pi
        t_mid = (geo.length - 0.5 * (geo.u_min + geo.u_max)) / g2.base_radius
        j0 = np.rint((tau2 + side * t_mid - a2 - side * g2.base_half) / g2.pitch).astype(int)
        h = H[side]
        for dj in range(-self.window, self.window + 1):
            j = j0 + dj
            e2 = disp2[rows, j % g2.teeth]
            u = m.flank_position(geo, a2 + j * g2.pitch + e2, side)
            k = m.mate_tooth(geo, a1, u, side).astype(int)
            D = side * (g1.base_radius * disp1[rows, k % g1.teeth] + g2.base_radius * e2)
            e = np.where(u < geo.u_min, self.excess(0, geo.distance, geo.u_min - u),
                         np.where(u > geo.u_max, self.excess(1, geo.distance, u - geo.u_max), 0.0))
            h = np.maximum(h, D - e)
        H[side] = h
    return m.total_play(geo.distance) - H[1] - H[-1], geo.distance


def _setups():
    out = []
    for name in ("robot_joint", "split_pinion"):
        layout = resolve(load_design(ASSEMBLIES / f"{name}.toml"))
        out.append((f"{name}:{layout.meshes[0].name}", mesh_setup(layout, layout.meshes[0])))
    out.append(("spur_18_45", MeshSetup.centred(gear(18, thinning=0.04), gear(45, thinning=0.04), 63.05)))
    return out


@pytest.mark.parametrize("label, setup", _setups(), ids=lambda v: v if isinstance(v, str) else "")
def test_window_at_once_is_the_pair_at_a_time_loop(label, setup, monkeypatch):
    o1, o2 = polar_outline(setup.gear1), polar_outline(setup.gear2)
    play = free_play(o1, o2, setup.states([0.0], errors=False))
    model = PairModel(setup, play.conjugate_ccw[0] + play.conjugate_cw[0], setup.planes(3))
    rng = np.random.default_rng(28)
    ecc, tir = 0.01 * o1.r_ref / 20, 0.005 * o1.r_ref / 20  # errors of a few um: a fine-grade pair
    amps = tuple(rng.uniform(0.2, 1.0, 4) * ecc)
    a0 = setup.centre_distance
    spread = 2 * tir * (o1.r_base / o1.r_ref + o2.r_base / o2.r_ref)
    excess = TipExcess(model, np.linspace(a0 - sum(amps), a0 + sum(amps), 9), spread)
    search = HuntingSearch(model, amps, excess)
    S = 6
    ph = rng.uniform(0, 2 * math.pi, (S, 4))
    d1 = rng.uniform(-tir / 2, tir / 2, (S, setup.gear1.teeth)) / o1.r_ref
    d2 = rng.uniform(-tir / 2, tir / 2, (S, setup.gear2.teeth)) / o2.r_ref
    rows = rng.integers(0, S, 2000)
    s = rng.uniform(0.0, search.period, 2000)
    new, new_a = search.evaluate(ph, d1, d2, rows, s)
    old, old_a = reference_evaluate(search, ph, d1, d2, rows, s)
    assert np.array_equal(new, old) and np.array_equal(new_a, old_a)
    got = search.search(ph, d1, d2)
    monkeypatch.setattr(HuntingSearch, "evaluate", reference_evaluate)
    want = search.search(ph, d1, d2)
    for g, w in zip(got, want):
        assert np.array_equal(g, w)
