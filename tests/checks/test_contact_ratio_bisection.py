"""measured_contact_ratio bisects several steps per call of the contact count (issue 28,
geargen.checks.mesh2d._bisect_levels); the one-step-a-call bisection it replaced is kept here as the
reference: the brackets, and so the contact ratios, are the same to the last bit."""

from pathlib import Path

import numpy as np
import pytest

from geargen.checks import mesh2d
from geargen.checks.verdict import mesh_setup
from geargen.design.assembly import load_design
from geargen.drives.resolver import resolve

ASSEMBLIES = Path(__file__).resolve().parents[2] / "assemblies"


def sequential_bisection(count, lo, hi, c_lo, iterations):
    """One bisection step per count call (geargen before issue 28)."""
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        same = count(mid) == c_lo
        lo = np.where(same, mid, lo)
        hi = np.where(same, hi, mid)
    return lo, hi


def reference_contact_ratio(setup, steps=32, side="ccw", iterations=26):
    o1, o2 = mesh2d.polar_outline(setup.gear1), mesh2d.polar_outline(setup.gear2)
    p1 = o1.pitch
    pos = np.linspace(0.0, p1, steps + 1)

    def count(x):
        return mesh2d.contact_count(o1, o2, setup.states(x, errors=False), side)

    c = count(pos)
    change = np.nonzero(c[:-1] != c[1:])[0]
    edges = np.diff(pos)
    keep = np.ones(steps, dtype=bool)
    keep[change] = False
    total = float(np.sum(c[:-1][keep] * edges[keep]))
    if change.size:
        lo, hi = sequential_bisection(count, pos[change].copy(), pos[change + 1].copy(), c[change], iterations)
        t = 0.5 * (lo + hi)
        total += float(np.sum(c[change] * (t - pos[change]) + c[change + 1] * (pos[change + 1] - t)))
    return total / p1


def test_random_step_counts_bisect_as_one_step_a_call():
    """A count that steps at random places (several steps a bracket, brackets of different widths,
    a number of steps not a multiple of the levels per call): brackets identical."""
    rng = np.random.default_rng(28)
    for iterations in (1, 3, 4, 7, 26, 40):
        edges = np.sort(rng.uniform(0.0, 1.0, 9))
        count = lambda x: np.searchsorted(edges, x)  # noqa: E731  (number of edges below x)
        lo = np.sort(rng.uniform(0.0, 1.0, 6))
        hi = lo + rng.uniform(1e-6, 0.3, 6)
        c_lo = count(lo)
        want = sequential_bisection(count, lo.copy(), hi.copy(), c_lo, iterations)
        got_lo, got_hi, done = lo.copy(), hi.copy(), 0
        while done < iterations:
            levels = min(mesh2d._BISECTION_LEVELS, iterations - done)
            got_lo, got_hi = mesh2d._bisect_levels(count, got_lo, got_hi, c_lo, levels)
            done += levels
        assert np.array_equal(got_lo, want[0]) and np.array_equal(got_hi, want[1])


@pytest.mark.parametrize("name", ["robot_joint", "split_pinion"])
@pytest.mark.parametrize("side, steps", [("ccw", 32), ("cw", 19)])
def test_shipped_meshes_contact_ratio_as_one_step_a_call(name, side, steps):
    layout = resolve(load_design(ASSEMBLIES / f"{name}.toml"))
    for mesh in layout.meshes[:2]:
        setup = mesh_setup(layout, mesh)
        # exact equality: the same positions counted, the same brackets kept
        assert mesh2d.measured_contact_ratio(setup, steps, side) == reference_contact_ratio(setup, steps, side)
