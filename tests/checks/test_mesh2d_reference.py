"""The exact 2-D checker's boundary walk and placement (geargen.checks.mesh2d) after issue 28 (only the
segments present visited; a refinement's teeth placed once for all its steps) against the code they
replaced, kept here as the reference: the same to the last bit on the shipped gears' outlines."""

from pathlib import Path

import numpy as np
import pytest

from geargen.checks import mesh2d
from geargen.checks.mesh2d import FILLET, INVOLUTE, TIP, polar_outline
from geargen.checks.verdict import mesh_setup
from geargen.design.assembly import load_design
from geargen.drives.resolver import resolve

ASSEMBLIES = Path(__file__).resolve().parents[2] / "assemblies"


def reference_sector_polar(o, u):
    """Every segment tested in turn (geargen before issue 28)."""
    u = np.asarray(u, dtype=float).ravel()
    s = np.clip(np.floor(u).astype(int), 0, o.segment_count - 1)
    f = u - s
    rho, phi, w_lo, w_up = np.empty(u.shape), np.empty(u.shape), np.zeros(u.shape), np.zeros(u.shape)
    half_gap = 0.5 * o.pitch - o.root_half
    for k, seg in enumerate(o.segments):
        m = s == k
        if not np.any(m):
            continue
        t = seg.t0 + f[m] * (seg.t1 - seg.t0)
        code = o.kinds[k]
        if code == INVOLUTE:
            r = o.r_base * np.sqrt(1.0 + t * t)
            ph = o.sides[k] * (o.base_half - (t - np.arctan(t)))
            (w_up if o.sides[k] > 0 else w_lo)[m] = 1.0
        elif code == FILLET:
            xy = seg.point(t)
            r = np.hypot(xy[:, 0], xy[:, 1])
            ph = np.arctan2(xy[:, 1], xy[:, 0])
            (w_up if o.sides[k] > 0 else w_lo)[m] = 1.0
        elif code == TIP:
            r = np.full(t.shape, o.r_tip)
            ph = t
            w_up[m] = 0.5 * (1.0 + t / o.tip_half)
            w_lo[m] = 0.5 * (1.0 - t / o.tip_half)
        else:
            r = np.full(t.shape, o.r_root)
            ph = t
            w_lo[m] = np.where(t < 0, (t + 0.5 * o.pitch) / half_gap, 0.0)
            w_up[m] = np.where(t < 0, 0.0, (0.5 * o.pitch - t) / half_gap)
        rho[m], phi[m] = r, ph
    return rho, phi, w_lo, w_up, o.kinds[s]


def reference_place(held, c, a, offsets, rows, teeth, rho, phi, w_lo, w_up):
    ang = a + teeth * held.pitch + phi
    if offsets is not None:
        lo, up = mesh2d._flanks(offsets, rows, teeth, held.teeth)
        ang = ang + up * w_up - lo * w_lo
    return c[..., 0] + rho * np.cos(ang), c[..., 1] + rho * np.sin(ang)


def _outlines():
    out = []
    for name in ("robot_joint", "c_axis", "split_pinion"):
        layout = resolve(load_design(ASSEMBLIES / f"{name}.toml"))
        setup = mesh_setup(layout, layout.meshes[0])
        out += [(f"{name}:{g.name}", polar_outline(g)) for g in (setup.gear1, setup.gear2)]
    return out


@pytest.mark.parametrize("label, outline", _outlines(), ids=lambda v: v if isinstance(v, str) else "")
def test_boundary_walk_and_placement_as_before(label, outline):
    rng = np.random.default_rng(28)
    S = outline.segment_count
    # a few segments only (as a refinement's steps are), every segment, and the segments' ends
    for u in (rng.uniform(1.0, 2.5, 40), rng.uniform(0.0, S, 3000), np.arange(S + 1, dtype=float)):
        for got, want in zip(outline.sector_polar(u), reference_sector_polar(outline, u)):
            assert np.array_equal(got, want)
        rho, phi, w_lo, w_up, _ = outline.sector_polar(u)
        n, z = u.size, outline.teeth
        rows = np.arange(n)
        teeth = rng.integers(-z, 2 * z, n)
        c, a = rng.uniform(-50, 50, (n, 2)), rng.uniform(-3, 3, n)
        for offsets in (None, rng.uniform(-1e-4, 1e-4, (z, 2)), rng.uniform(-1e-4, 1e-4, (n, z, 2))):
            got = mesh2d._place(outline, c, a, offsets, rows, teeth, rho, phi, w_lo, w_up)
            want = reference_place(outline, c, a, offsets, rows, teeth, rho, phi, w_lo, w_up)
            assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1])


@pytest.mark.parametrize("design", ["robot_joint", "c_axis"])
def test_sweep_backlash_is_the_sweeps_backlash_to_the_bit(design):
    """sweep_backlash (the free play alone, for callers that read only the backlash) gives
    sweep_mesh's angular and normal backlash bit for bit: on every engaged mesh of a shipped drive
    (spur and helical, planes 1 and 3) and with the error states the tolerances give them
    (tooth displacements as flank offsets, eccentricities)."""
    from dataclasses import replace

    from geargen.checks.mesh2d import Eccentricity, mesh_positions, sweep_backlash, sweep_mesh
    from geargen.checks.tolerance import worst_flanks

    layout = resolve(load_design(ASSEMBLIES / f"{design}.toml"))
    for mesh in (m for m in layout.meshes if m.engaged):
        setup = mesh_setup(layout, mesh)
        erred = replace(setup, flanks1=worst_flanks(setup.gear1, 0.004), flanks2=worst_flanks(setup.gear2, 0.003),
                        eccentricity1=(Eccentricity(0.01, 0.3),))
        for su, planes in ((setup, setup.planes(1)), (setup, setup.planes(3)), (erred, erred.planes(3))):
            positions = mesh_positions(su, 8, 1.0 / su.gear1.teeth)
            sweep = sweep_mesh(su, positions, planes, areas=False)
            angular, normal = sweep_backlash(su, positions, planes)
            assert angular.tobytes() == sweep.angular_backlash.tobytes()
            assert normal.tobytes() == sweep.normal_backlash.tobytes()
