"""Path 2's polygon play and root clearance (geargen.checks.solids) after issue 28 (each vertex
shared by two chained segments turned once, not twice) against the code they replaced, kept here
as the reference: the same sweep to the last bit, with and without overlap, on chained sections
and on sections with segments missing (broken chains, as a face's boundary leaves them). Also the
circle crossings and inside test before their per-edge and per-vertex terms were computed once,
the root clearance before it measured only the pairs that can be the nearest, and the play before
it found only the turns within a window (every turn found)."""

import math

import numpy as np
import pytest

from geargen.checks import solids
from geargen.checks.mesh2d import MeshSetup, mesh_positions
from geargen.checks.solids import _circle_crossings, _inside, _wrap, check_mesh_sections, section_planes

from checks_support import gear, tight_centre_distance
from test_check_sections import _sampled_sections


def reference_circle_hits(points, segs):
    """geargen before issue 28's per-edge and per-vertex terms. Where the circles about the origin through ``points`` ``(V, 2)`` cross ``segs`` ``(E, 2, 2)``.

    Returns (vertex index, crossing point (k, 2)) for every crossing. Edges are sorted by their
    nearest radius, so each vertex only meets the edges whose radial span can hold it.
    """
    if points.size == 0 or segs.size == 0:
        return np.empty(0, dtype=int), np.empty((0, 2))
    rho = np.hypot(points[:, 0], points[:, 1])
    a0, a1 = segs[:, 0], segs[:, 1]
    d = a1 - a0
    dd = np.einsum("ij,ij->i", d, d)
    ad = np.einsum("ij,ij->i", a0, d)
    tn = np.clip(-ad / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    foot = a0 + tn[:, None] * d
    rmin = np.hypot(foot[:, 0], foot[:, 1])
    rmax = np.maximum(np.hypot(a0[:, 0], a0[:, 1]), np.hypot(a1[:, 0], a1[:, 1]))
    order = np.argsort(rmin)
    rmin_s = rmin[order]
    span = float(np.max(rmax - rmin)) * (1 + 1e-12) + 1e-15
    lo = np.searchsorted(rmin_s, rho - span, side="left")
    hi = np.searchsorted(rmin_s, rho, side="right")
    count = hi - lo
    v = np.repeat(np.arange(rho.size), count)
    e = order[np.repeat(lo, count) + (np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count))]
    keep = rho[v] <= rmax[e]
    v, e = v[keep], e[keep]
    if v.size == 0:
        return v, np.empty((0, 2))
    r0 = np.einsum("ij,ij->i", a0[e], a0[e])
    A, B, C = dd[e], 2 * ad[e], r0 - rho[v] ** 2
    disc = np.sqrt(np.maximum(B * B - 4 * A * C, 0.0))
    vi, pts = [], []
    for sign in (-1.0, 1.0):
        t = (-B + sign * disc) / (2 * A)
        ok = (t >= -1e-12) & (t <= 1 + 1e-12)
        vi.append(v[ok])
        pts.append(a0[e[ok]] + np.clip(t[ok], 0, 1)[:, None] * d[e[ok]])
    return np.concatenate(vi), np.concatenate(pts)


def reference_inside(points, segs, centre):
    """geargen before issue 28's per-edge and per-vertex terms. Whether ``points`` ``(V, 2)`` lie inside the gear whose nearby outline is ``segs``, centred
    at ``centre``: the parity of the crossings of the ray from the centre outward beyond each
    point (a tooth outline is radially monotone, so a point in a tooth is left through one flank
    or the tip land; one in a space never meets the outline further out). Edges are sorted by
    polar angle, so each point meets only the edges at its own angle."""
    if points.size == 0 or segs.size == 0:
        return np.zeros(points.shape[0], dtype=bool)
    c = np.asarray(centre, dtype=float)
    q = segs - c
    ref = math.atan2(float(np.mean(q[..., 1])), float(np.mean(q[..., 0])))  # the outline lies around here
    ang = _wrap(np.arctan2(q[..., 1], q[..., 0]) - ref)
    lo, hi = ang.min(axis=1), ang.max(axis=1)
    order = np.argsort(lo)
    lo_s = lo[order]
    span = float(np.max(hi - lo)) + 1e-15
    u = points - c
    pa = _wrap(np.arctan2(u[:, 1], u[:, 0]) - ref)
    first = np.searchsorted(lo_s, pa - span, side="left")
    last = np.searchsorted(lo_s, pa, side="right")
    count = last - first
    v = np.repeat(np.arange(points.shape[0]), count)
    e = order[np.repeat(first, count) + (np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count))]
    keep = pa[v] <= hi[e]
    v, e = v[keep], e[keep]
    rad = np.hypot(u[:, 0], u[:, 1])
    un = u[v] / np.where(rad[v] > 0, rad[v], 1.0)[:, None]
    q0, dq = q[e, 0], q[e, 1] - q[e, 0]
    den = un[:, 0] * dq[:, 1] - un[:, 1] * dq[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        lam = (q0[:, 0] * dq[:, 1] - q0[:, 1] * dq[:, 0]) / den  # distance along the ray
        t = (q0[:, 0] * un[:, 1] - q0[:, 1] * un[:, 0]) / den  # parameter along the edge
    hit = (den != 0) & (t >= 0) & (t < 1) & (lam > rad[v])
    return np.bincount(v[hit], minlength=points.shape[0]) % 2 == 1


def reference_polygon_play(seg1, seg2, centre1, centre2=None):
    """geargen before issue 28: every segment's two ends turned."""
    c = np.asarray(centre1, dtype=float)
    c2 = c if centre2 is None else np.asarray(centre2, dtype=float)
    ccw_c, cw_c = [math.inf], [math.inf]
    for verts, edges, own, inside_of in ((seg2.reshape(-1, 2), seg1, False, (seg1, c)),
                                         (seg1.reshape(-1, 2), seg2, True, (seg2, c2))):
        vi, x = reference_circle_hits(verts - c, edges - c)
        if vi.size == 0:
            continue
        pv = verts[vi] - c
        if own:
            d = _wrap(np.arctan2(x[:, 1], x[:, 0]) - np.arctan2(pv[:, 1], pv[:, 0]))
        else:
            d = _wrap(np.arctan2(pv[:, 1], pv[:, 0]) - np.arctan2(x[:, 1], x[:, 0]))
        n = verts.shape[0]
        pos = np.full(n, np.inf)
        neg = np.full(n, np.inf)
        np.minimum.at(pos, vi[d >= 0], d[d >= 0])
        np.minimum.at(neg, vi[d < 0], -d[d < 0])
        inside = reference_inside(verts, *inside_of)
        out = ~inside
        ccw_c.append(np.min(pos[out], initial=math.inf))
        cw_c.append(np.min(neg[out], initial=math.inf))
        free_ccw = inside & (pos <= neg)
        free_cw = inside & (neg < pos)
        cw_c.append(np.min(-pos[free_ccw], initial=math.inf))
        ccw_c.append(np.min(-neg[free_cw], initial=math.inf))
    return float(min(ccw_c)), float(min(cw_c))


def reference_root_clearance(own, own_centre, r_root, other, other_centre, r_tip, deviation=0.0):
    """geargen before issue 28: every segment's two ends measured."""
    v = own.reshape(-1, 2)
    oc = np.asarray(other_centre, dtype=float)
    r = np.linalg.norm(v - np.asarray(own_centre), axis=1)
    v = v[r <= r_root + max(deviation, 2e-6, 2e-7 * r_root)]
    ends = np.linalg.norm(other - oc, axis=2)
    land = other[np.all(ends >= r_tip - max(deviation, 2e-6, 2e-7 * r_tip), axis=1)]
    if v.size == 0 or land.size == 0:
        return math.inf
    a0, d = land[:, 0], land[:, 1] - land[:, 0]
    wx, wy = v[:, None, 0] - a0[None, :, 0], v[:, None, 1] - a0[None, :, 1]
    dx, dy = d[None, :, 0], d[None, :, 1]
    t = np.clip((wx * dx + wy * dy) / np.maximum(dx * dx + dy * dy, 1e-300), 0, 1)
    dist = np.hypot(wx - t * dx, wy - t * dy).min(axis=1)
    u = v - oc
    rad = np.linalg.norm(u, axis=1)
    cand = np.nonzero(rad < r_tip)[0]
    inside = np.zeros(v.shape[0], dtype=bool)
    if cand.size:
        un = u[cand] / rad[cand, None]
        q0 = other[:, 0] - oc
        dq = other[:, 1] - other[:, 0]
        cross_d = un[:, None, 0] * dq[None, :, 1] - un[:, None, 1] * dq[None, :, 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            s = (un[:, None, 0] * q0[None, :, 1] - un[:, None, 1] * q0[None, :, 0]) / -cross_d
            lam = (q0[None, :, 0] * dq[None, :, 1] - q0[None, :, 1] * dq[None, :, 0]) / cross_d
        hits = (s >= 0) & (s < 1) & (lam > rad[cand, None])
        inside[cand] = np.count_nonzero(hits, axis=1) % 2 == 1
    return float(np.min(np.where(inside, -dist, dist)))


def _placed(segs1, segs2, st, i, g1, g2):
    """The two gears' segments at mesh position ``i``, as check_mesh_sections places them
    (solids.placed_near: each gear's segments within the other's reach): (p1, p2, c1, c2)."""
    return solids.placed_near(segs1, segs2, st, i, g1.tip_radius + g1.module, g2.tip_radius + g2.module)


def _broken(sections, rng):
    """The sections with one segment in 40 dropped (chains broken where a face's boundary would)."""
    segs = [s[rng.uniform(size=len(s)) > 1 / 40] for s in sections.segments]
    return type(sections)(sections.spec, sections.planes, segs, sections.deviation, sections.source)


@pytest.mark.parametrize("pair, gap", [((gear(20), gear(41)), 0.02), ((gear(20), gear(41)), -0.03),
                                       ((gear(17, 1.5, beta_deg=18), gear(43, 1.5, beta_deg=18, hand="left")), 0.01)],
                         ids=["apart", "overlapping", "helical"])
def test_sections_sweep_as_before(pair, gap, monkeypatch):
    g1, g2 = pair
    su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + gap)
    planes = section_planes(su, 2)
    s1, s2 = _sampled_sections(g1, planes, 0.01), _sampled_sections(g2, planes, 0.01)
    rng = np.random.default_rng(28)
    pos = mesh_positions(su, 8)
    for a, b in ((s1, s2), (_broken(s1, rng), _broken(s2, rng))):
        got = check_mesh_sections(su, a, b, positions=pos).sweep
        with monkeypatch.context() as m:
            m.setattr(solids, "polygon_play", reference_polygon_play)
            m.setattr(solids, "_root_clearance", reference_root_clearance)
            want = check_mesh_sections(su, a, b, positions=pos).sweep
        for name in ("play_ccw", "play_cw", "min_clearance", "normal_backlash", "interference"):
            assert np.array_equal(getattr(got, name), getattr(want, name)), name
    if gap < 0:  # the inside branches were taken
        assert np.min(got.play_ccw + got.play_cw) < 0


def test_root_clearance_as_before_over_a_pitch():
    """The root clearance with no vertex inside the other gear (only the pairs that can be the
    nearest are measured) against every pair measured, bit for bit: a spur pair at 20 rotations
    over one pitch and three centre distances (the last one 0.6 mm short: tips in the roots, the
    inside branch), both gears' roots, sections whole and with segments missing."""
    g1, g2 = gear(20), gear(41)
    rng = np.random.default_rng(2028)
    planes = np.array([5.0])
    s1, s2 = _sampled_sections(g1, planes, 0.01), _sampled_sections(g2, planes, 0.01)
    compared = inside = 0
    for gap in (0.3, 0.0, -0.6):
        su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + gap)
        pos = mesh_positions(su, 20)[:20]
        st = su.states(pos)
        for a, b in ((s1, s2), (_broken(s1, rng), _broken(s2, rng))):
            for i in range(pos.size):
                p1, p2, c1, c2 = _placed(a.segments[0], b.segments[0], st, i, g1, g2)
                for own, oc, rr, other, occ, rt in ((p1, c1, g1.root_radius_standard, p2, c2, g2.tip_radius),
                                                    (p2, c2, g2.root_radius_standard, p1, c1, g1.tip_radius)):
                    got = solids._root_clearance(own, oc, rr, other, occ, rt, 1e-6)
                    want = reference_root_clearance(own, oc, rr, other, occ, rt, 1e-6)
                    assert got == want
                    compared += 1
                    inside += want < 0
    assert compared == 240 and 0 < inside < compared  # both branches were met


@pytest.mark.parametrize("pair, gap", [((gear(20), gear(41)), 0.02), ((gear(20), gear(41)), -0.6),
                                       ((gear(17, 1.5, beta_deg=18), gear(43, 1.5, beta_deg=18, hand="left")), 0.01)],
                         ids=["apart", "overlapping", "helical"])
def test_crossings_and_inside_test_as_before(pair, gap):
    """The circle crossings and the inside test with their per-edge and per-vertex terms computed
    once against the code that computed them per pair: the same arrays bit for bit, vertices of
    either gear against the other placed as the check places them, over a pitch."""
    g1, g2 = pair
    su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + gap)
    planes = section_planes(su, 1)
    s1, s2 = _sampled_sections(g1, planes, 0.01), _sampled_sections(g2, planes, 0.01)
    pos = mesh_positions(su, 12)[:12]
    st = su.states(pos)
    crossings = inside = 0
    for i in range(pos.size):
        p1, p2, c1, c2 = _placed(s1.segments[0], s2.segments[0], st, i, g1, g2)
        for verts, edges, centre in ((p2.reshape(-1, 2), p1, c1), (p1.reshape(-1, 2), p2, c2)):
            (vi, x, y), want = _circle_crossings(verts - c1, edges - c1), reference_circle_hits(verts - c1, edges - c1)
            assert np.array_equal(vi, want[0]) and np.array_equal(np.column_stack([x, y]), want[1])
            crossings += want[0].size
            got, want = _inside(verts, edges, centre), reference_inside(verts, edges, centre)
            assert np.array_equal(got, want)
            inside += int(np.count_nonzero(want))
    assert crossings > 1000
    assert inside > 0 if gap < 0 else inside == 0  # the overlapping pair has vertices inside


def test_placed_sections_as_before():
    """A section placed as one (2m, 2) matrix product against the m stacked (2, 2) products it
    replaced: the same ends bit for bit, a spur and a helical section at 200 placements."""
    rng = np.random.default_rng(2028)
    for spec in (gear(20), gear(43, 1.5, beta_deg=18, hand="left")):
        segs = _sampled_sections(spec, np.array([3.0]), 0.01).segments[0]
        for angle, x, y in zip(rng.uniform(-7, 7, 100), rng.uniform(-90, 90, 100), rng.uniform(-90, 90, 100)):
            c, s = math.cos(angle), math.sin(angle)
            want = segs @ np.array([[c, -s], [s, c]]).T + np.array([x, y])
            assert np.array_equal(solids._place(segs, (x, y), angle), want)


def test_wrap_as_before():
    """The angle wrap taking the modulo only outside [0, 2 pi) against (a + pi) mod 2 pi - pi for
    every element, bit for bit (signed zeros, the ends of the range, infinities and NaN too)."""
    rng = np.random.default_rng(28)
    edges = [0.0, -0.0, math.pi, -math.pi, np.nextafter(math.pi, 0), np.nextafter(-math.pi, 0), 2 * math.pi,
             -2 * math.pi, math.inf, -math.inf, math.nan]
    a = np.concatenate([rng.normal(size=20000) * 2, rng.uniform(-math.pi, math.pi, 20000), rng.normal(size=200) * 100,
                        edges])
    with np.errstate(invalid="ignore"):
        want = (a + math.pi) % (2 * math.pi) - math.pi
        got = _wrap(a)
        assert all(_wrap(x) == w or (math.isnan(w) and math.isnan(_wrap(x))) for x, w in zip(edges, want[-len(edges):]))
    same = (got == want) | (np.isnan(got) & np.isnan(want))
    assert same.all() and np.array_equal(np.signbit(got), np.signbit(want))


def test_play_from_the_turns_within_a_window_as_before(monkeypatch):
    """Polygon play from the turns within a window (1/32 rad, then 1/4, then every turn; a side with
    a vertex inside the other gear from every turn) against every turn found, bit for bit: a spur
    pair finely sampled from 0.02 mm apart (plays ~4e-4 rad, the first window) to 3.8 and 3.95 mm
    apart (plays ~0.1 rad: the second window; tips out of reach at some positions: no turn at all,
    every pair tried), and coarsely sampled (0.3 mm chords) 2-4 um into each other, where an
    overlap shorter than a chord leaves one side's vertices inside and not the other's; sections
    whole and with segments missing."""
    windows = set()
    within = solids._play_within

    def recorded(sides, window):
        windows.add((window, tuple(bool(side[5]) for side in sides)))
        return within(sides, window)

    monkeypatch.setattr(solids, "_play_within", recorded)
    g1, g2 = gear(20), gear(41)
    rng = np.random.default_rng(2028)
    compared = 0
    for step, gaps in ((0.01, (0.02, 2.5, 3.8, 3.95)), (0.3, (-0.002, -0.004))):
        s1, s2 = (_sampled_sections(g, np.array([5.0]), step) for g in (g1, g2))
        for gap in gaps:
            su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + gap)
            pos = mesh_positions(su, 12)[:12]
            st = su.states(pos)
            for a, b in ((s1, s2), (_broken(s1, rng), _broken(s2, rng))):
                for i in range(pos.size):
                    p1, p2, c1, c2 = _placed(a.segments[0], b.segments[0], st, i, g1, g2)
                    assert solids.polygon_play(p1, p2, c1, c2) == reference_polygon_play(p1, p2, c1, c2)
                    compared += 1
    assert compared == 144
    used = {w for w, _ in windows}
    assert {1 / 32, 0.25, None} <= used  # every window, and every turn
    sides = {s for _, s in windows}
    assert (True, False) in sides and (False, True) in sides and (True, True) in sides and (False, False) in sides


def test_pairs_left_out_turn_beyond_the_window():
    """Every (vertex, edge) pair whose circle crossing lies at a turn within the window passes
    :func:`solids._within_turn` (the crossings of every pair, turned as the play turns them), and
    most pairs do not (what the window saves): a spur pair 0.02 and 2.5 mm apart, either gear's
    vertices, windows 1/32 and 1/4 rad, over a pitch."""
    g1, g2 = gear(20), gear(41)
    s1, s2 = (_sampled_sections(g, np.array([5.0]), 0.01) for g in (g1, g2))
    within, pairs = {1 / 32: 0, 0.25: 0}, 0
    for gap in (0.02, 2.5):
        su = MeshSetup.centred(g1, g2, tight_centre_distance(g1, g2) + gap)
        pos = mesh_positions(su, 12)[:12]
        st = su.states(pos)
        for i in range(pos.size):
            p1, p2, c1, c2 = _placed(s1.segments[0], s2.segments[0], st, i, g1, g2)
            for verts, edges in ((solids._vertices(p2), p1), (solids._vertices(p1), p2)):
                u, q = verts - c1, edges - c1
                rho = np.hypot(u[:, 0], u[:, 1])
                terms = solids._edge_terms(q)
                v, e = solids._radial_pairs(rho, terms)
                # each crossing with the index of its pair
                k, x, y = solids._pair_crossings(rho[v], terms, np.arange(v.size), e)
                turn = np.abs(_wrap(np.arctan2(y, x) - np.arctan2(u[v[k], 1], u[v[k], 0])))
                for window in (1 / 32, 0.25):
                    near = solids._within_turn(u, q, rho, terms, v, e, window)
                    assert near[k[turn <= window]].all()
                    within[window] += int(np.count_nonzero(near))
                pairs += v.size
    # the first window keeps ~8 % of the pairs, the second ~46 %
    assert 0 < within[1 / 32] < 0.1 * pairs and within[1 / 32] < within[0.25] < 0.6 * pairs
