"""Placed gears really mesh: other trains checked against an independent involute computation.

For each train the test makes gears whose tooth thinning gives a known backlash, synthesises the
centres from a design dictionary (the path `geargen synth` takes), places the gears and then
checks every mesh (1A, 1B, 2A, 2B) with geometry computed here from geargen.core.involute alone:

* pitch-point gaps: on the operating pitch circles (radius r_b / cos alpha_w) the flanks of two
  involute gears reach the pitch point together exactly when they touch (conjugate action), so
  the arc between a tooth of gear a and the neighbouring teeth of gear b, measured along the
  pitch circles from the flank polar angles +-psi(r_w) of geargen.core.involute.tooth_half_angle,
  is the free play on each side. Converted to the reference circle of a it must be 0 on the
  working flank and the whole backlash B on the other;
* flank distances: the shortest distance between the sampled involute flanks themselves (no
  pitch-point argument) must be 0 on the working flank and j_bt = B cos(alpha_t) on the other.
  Flanks are sampled with 4000 points and measured point-to-polyline, which bounds the
  discretisation error to ~1e-8 mm (chord sag), hence the 2e-7 module tolerance.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import cKDTree

from geargen.core.involute import tooth_half_angle, tooth_thickness_at_radius
from geargen.cli import main
from geargen.core.synthesis import Placement, PlacedGear, modelled_backlash, place_gears, solve_loop, synthesize_centres
from geargen.design.assembly import design_from_dict, load_design
from geargen.design.synthesis import synthesis_inputs
from geargen.units import LENGTH_SUFFIXES

ROOT = Path(__file__).resolve().parents[2]
METRIC = ROOT / "tests" / "data" / "metric_dual_pinion.toml"
ROLES = ("input", "cluster_large", "cluster_small", "output")
# (placed gear a, placed gear b, working flank of a: +1 counter-clockwise, -1 clockwise)
MESHES = (("input", "cluster_large_a", +1), ("input", "cluster_large_b", -1),
          ("cluster_small_a", "output", -1), ("cluster_small_b", "output", +1))


def wrap_pi(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def operating(spec_a, spec_b, c):
    aw = math.acos((spec_a.base_radius + spec_b.base_radius) / c)
    return spec_a.base_radius / math.cos(aw), spec_b.base_radius / math.cos(aw)


def backlash_of(spec_a, spec_b, c):
    """Circumferential backlash B at the reference circles of gears made to ``spec_a``/``spec_b`` at ``c``."""
    rwa, rwb = operating(spec_a, spec_b, c)
    jt = 2 * math.pi * rwa / spec_a.teeth - tooth_thickness_at_radius(spec_a, rwa) - tooth_thickness_at_radius(spec_b, rwb)
    return jt * spec_a.reference_radius / rwa


def pitch_point_gaps(spec_a, ga, spec_b, gb):
    """(gap on a's counter-clockwise side, gap on its clockwise side), mm at a's reference circle."""
    ca, cb = np.array(ga.centre), np.array(gb.centre)
    d = cb - ca
    beta = math.atan2(d[1], d[0])
    rwa, rwb = operating(spec_a, spec_b, math.hypot(*d))
    sa = 2 * rwa * tooth_half_angle(spec_a, rwa)
    sb = 2 * rwb * tooth_half_angle(spec_b, rwb)
    ua = rwa * wrap_pi(ga.rotation + 2 * np.pi * np.arange(spec_a.teeth) / spec_a.teeth - beta)
    u0 = ua[np.argmin(np.abs(ua))]
    ub = -rwb * wrap_pi(gb.rotation + 2 * np.pi * np.arange(spec_b.teeth) / spec_b.teeth - beta - np.pi)
    ccw = (ub[ub > u0].min() - sb / 2) - (u0 + sa / 2)
    cw = (u0 - sa / 2) - (ub[ub < u0].max() + sb / 2)
    return ccw * spec_a.reference_radius / rwa, cw * spec_a.reference_radius / rwa


def _flank(spec, centre, centreline, side, n=4000):
    r = np.linspace(spec.base_radius * (1 + 1e-12), spec.tip_radius, n)
    th = centreline + side * tooth_half_angle(spec, r)
    return np.column_stack([centre[0] + r * np.cos(th), centre[1] + r * np.sin(th)])


def _point_to_polyline(points, poly):
    _, j = cKDTree(poly).query(points)
    best = np.full(len(points), np.inf)
    for k in (np.clip(j - 1, 0, len(poly) - 2), np.clip(j, 0, len(poly) - 2)):
        a, ab = poly[k], poly[k + 1] - poly[k]
        t = np.clip(((points - a) * ab).sum(1) / (ab * ab).sum(1), 0, 1)
        best = np.minimum(best, np.hypot(*(points - (a + t[:, None] * ab)).T))
    return best.min()


def flank_distances(spec_a, ga, spec_b, gb):
    """Shortest distances between facing flanks: (a's counter-clockwise side, clockwise side), mm."""
    ca, cb = np.array(ga.centre), np.array(gb.centre)
    beta = math.atan2(*(cb - ca)[::-1])
    ka = ga.rotation + 2 * np.pi * np.arange(spec_a.teeth) / spec_a.teeth
    theta_a = ka[np.argmin(np.abs(wrap_pi(ka - beta)))]
    off = wrap_pi(gb.rotation + 2 * np.pi * np.arange(spec_b.teeth) / spec_b.teeth - beta - np.pi)
    out = []
    for side in (+1, -1):  # the b tooth on a's `side` lies at -side of b's line of centres; same-named flanks face
        cand = off[-side * off > 0]
        theta_b = cand[np.argmin(np.abs(cand))] + beta + np.pi
        out.append(_point_to_polyline(_flank(spec_a, ca, theta_a, side), _flank(spec_b, cb, theta_b, side)))
    return tuple(out)


def check_placement(placement, specs, gap=0.0):
    """Every mesh: working flank gap ``gap``, other flank ``B - gap`` with B the backlash of ``specs``
    at the placed centre distance; both by pitch point and by flank distance."""
    tol = 1e-9 * max(s.module for s in specs.values())
    tol_flank = 2e-7 * max(s.module for s in specs.values())
    for a, b, flank in MESHES:
        sa, sb = specs[placement.gear(a).role], specs[placement.gear(b).role]
        B = backlash_of(sa, sb, math.dist(placement.gear(a).centre, placement.gear(b).centre))
        ccw, cw = pitch_point_gaps(sa, placement.gear(a), sb, placement.gear(b))
        working, other = (ccw, cw) if flank > 0 else (cw, ccw)
        assert working == pytest.approx(gap, abs=tol), (a, b)
        assert other == pytest.approx(B - gap, abs=tol), (a, b)
        d_ccw, d_cw = flank_distances(sa, placement.gear(a), sb, placement.gear(b))
        d_work, d_other = (d_ccw, d_cw) if flank > 0 else (d_cw, d_ccw)
        cos_t = math.cos(sa.transverse_pressure_angle)
        assert d_work == pytest.approx(gap * cos_t, abs=tol_flank), (a, b)
        assert d_other == pytest.approx((B - gap) * cos_t, abs=tol_flank), (a, b)


# --- trains -------------------------------------------------------------------------------------

def _design(unit, pitch_key, pitch, pa_deg, teeth, shifts, dc, start_deg, rounding):
    gears = {}
    for role, z, x in zip(ROLES, teeth, shifts):
        p = pitch[0] if role in ("input", "cluster_large") else pitch[1]
        gears[role] = {"teeth": z, pitch_key: p, "pressure_angle_deg": pa_deg, f"face_width_{unit}": 10 / LENGTH_SUFFIXES[unit],
                       "profile_shift": x}
    data = {"name": "train", "length_unit": unit, "gears": gears}
    d0 = design_from_dict(data)
    c = []
    for mesh, (a, b) in ((1, ("input", "cluster_large")), (2, ("cluster_small", "output"))):
        ga, gb = d0.gears[a], d0.gears[b]
        c.append((ga.reference_radius + gb.reference_radius + ga.module * (ga.profile_shift + gb.profile_shift)
                  + dc[mesh - 1]) / LENGTH_SUFFIXES[unit])
    return data, c, start_deg, rounding


TRAINS = {
    # metric, a different module per mesh, 20 deg, whole teeth to the nearest
    "metric_two_modules": _design("mm", "module_mm", (1.0, 1.5), 20, (18, 54, 20, 100), (0, 0, 0, 0), (0.15, 0.0), -70,
                                  "whole_nearest"),
    # metric, 25 deg, profile shifts, half-tooth rounding to the nearest (gives an odd increment count)
    "metric_25deg_shifted_half_nearest": _design("mm", "module_mm", (2.0, 2.0), 25, (15, 47, 19, 83),
                                                 (0.3, -0.1, 0.2, 0.0), (0.2, 0.1), -70, "half_nearest"),
    # inch, 24 diametral pitch, half-tooth rounding down (odd count again)
    "inch_dp24_half_down": _design("in", "diametral_pitch_per_in", (24, 24), 20, (20, 60, 24, 120), (0, 0, 0, 0),
                                   (0.1, 0.0), -69, "half_down"),
}
ODD = {"metric_25deg_shifted_half_nearest": 73, "inch_dp24_half_down": 93}


def _thinned(specs, thin):
    """Copies of the specs with tooth thinning (mm) on each gear."""
    return {k: replace(v, thinning=thin[k]) for k, v in specs.items()}


@pytest.fixture(scope="module", params=sorted(TRAINS))
def train(request):
    data, c, start, rounding = TRAINS[request.param]
    unit = data["length_unit"]
    scale = LENGTH_SUFFIXES[unit]
    specs = design_from_dict(data).gears
    m = specs["input"].module
    thin_max = _thinned(specs, {"input": 0.02 * m, "cluster_large": 0.04 * m, "cluster_small": 0.03 * m, "output": 0.05 * m})
    thin_min = _thinned(specs, {"input": 0.01 * m, "cluster_large": 0.01 * m, "cluster_small": 0.0, "output": 0.01 * m})
    b_max = (backlash_of(thin_max["input"], thin_max["cluster_large"], c[0] * scale),
             backlash_of(thin_max["cluster_small"], thin_max["output"], c[1] * scale))
    b_min = (backlash_of(thin_min["input"], thin_min["cluster_large"], c[0] * scale),
             backlash_of(thin_min["cluster_small"], thin_min["output"], c[1] * scale))
    data = dict(data, synthesis={
        f"centre_distance_mesh1_{unit}": c[0], f"centre_distance_mesh2_{unit}": c[1],
        f"circumferential_backlash_max_mesh1_{unit}": b_max[0] / scale,
        f"circumferential_backlash_min_mesh1_{unit}": b_min[0] / scale,
        f"circumferential_backlash_max_mesh2_{unit}": b_max[1] / scale,
        f"circumferential_backlash_min_mesh2_{unit}": b_min[1] / scale,
        "start_angle_A1_deg": start, "rounding": rounding})
    s = synthesize_centres(synthesis_inputs(design_from_dict(data))).check()
    return request.param, s, thin_max, thin_min, b_max, b_min


def test_synthesised_position_meshes_at_maximum_backlash(train):
    name, s, thin_max, _, _, _ = train
    p = place_gears(s).check()
    check_placement(p, thin_max)
    # the Eq. 7-8 centres and the exact loop closure agree
    assert p.carriage_x == pytest.approx(s.input_x, abs=1e-9)
    assert p.gear("cluster_large_a").centre == pytest.approx(s.centres["gear2a"], abs=1e-12)
    if name in ODD:
        assert s.increments == ODD[name]  # an odd count: the input turns by a half tooth


def test_minimum_backlash_position_meshes(train):
    _, s, _, thin_min, _, b_min = train
    p = place_gears(s, *b_min).check()
    check_placement(p, thin_min)
    # at the max-backlash position the thick teeth would interfere: the carriage had to move
    assert pitch_point_gaps(thin_min["input"], place_gears(s).gear("input"), thin_min["cluster_large"],
                            place_gears(s).gear("cluster_large_a"))[0] < 0
    exact = solve_loop(s, *b_min).check()
    assert p.carriage_x == pytest.approx(exact.carriage_x[0], abs=1e-12)
    assert p.carriage_x > s.input_x  # thicker teeth hold the carriage further out


def test_loaded_flank_gap_is_left_on_the_working_flanks(train):
    _, s, thin_max, _, b_max, _ = train
    gap = 0.25 * min(b_max)
    check_placement(place_gears(s, loaded_flank_gap=gap).check(), thin_max, gap)


def test_placement_is_mirror_symmetric_and_rotations_reduced(train):
    _, s, _, _, _, _ = train
    p = place_gears(s).check()
    z1, _, _, z4 = s.inputs.teeth
    for name, z in (("input", z1), ("output", z4)):
        rot = p.gear(name).rotation
        assert -math.pi / z < rot <= math.pi / z + 1e-15
        k = 2 * rot / (2 * math.pi / z)  # a tooth or a space on the symmetry line
        assert k == pytest.approx(round(k), abs=1e-9)
    assert p.gear("cluster_small_a").rotation == p.gear("cluster_large_a").rotation
    assert p.gear("cluster_small_b").rotation == pytest.approx(-p.gear("cluster_small_a").rotation, abs=1e-12)
    assert p.gear("cluster_large_b").centre == pytest.approx((s.x2, -s.y2))


def test_carriage_is_pushed_towards_the_output(train):
    """Moving the input towards the output closes the working flanks (interference), away opens them."""
    _, s, thin_max, _, _, _ = train
    p = place_gears(s).check()
    g_in = p.gear("input")
    for dx, sign in ((-1e-4, -1), (1e-4, +1)):
        moved = replace(g_in, centre=(g_in.centre[0] + dx, 0.0))
        ccw, _ = pitch_point_gaps(thin_max["input"], moved, thin_max["cluster_large"], p.gear("cluster_large_a"))
        assert np.sign(ccw) == sign


def test_robot_joint_gears_thinned_to_the_appendix_backlash_mesh():
    d = load_design("assemblies/robot_joint.toml")
    inp = synthesis_inputs(d)
    s = synthesize_centres(inp).check()
    specs = dict(d.gears)
    # thinning one gear of a mesh by t raises B by exactly t; thin the large gears to reach B max
    for (a, b), mesh in ((("input", "cluster_large"), 1), (("cluster_small", "output"), 2)):
        b0 = backlash_of(specs[a], specs[b], inp.centre_distance(mesh))
        specs[b] = replace(specs[b], thinning=specs[b].thinning + inp.backlash(mesh, "max") - b0)
    p = place_gears(s).check()
    assert backlash_of(specs["input"], specs["cluster_large"], math.dist(p.gear("input").centre, p.gear("cluster_large_a").centre)) \
        == pytest.approx(inp.circumferential_backlash_max_mesh1, abs=1e-12)  # at the synthesised position the mesh has B max
    check_placement(p, specs)


def test_metric_design_file_through_the_command(tmp_path, capsys):
    """`geargen synth` on a metric design: JSON in mm, and its placement of the gears as modelled
    (the design's own tooth thinning) meshes by the independent check."""
    out = tmp_path / "metric.json"
    assert main(["synth", str(METRIC), "--json", str(out)]) == 0
    assert "Module              m (mm)" in capsys.readouterr().out
    data = json.loads(out.read_text())
    assert data["length_unit"] == "mm" and data["rounding"] == "half_nearest"
    d = load_design(METRIC)
    s = synthesize_centres(synthesis_inputs(d)).check()
    assert data["solved"]["x1"] == s.x1 and data["centres"]["gear1"] == [s.input_x, 0.0]
    specs = d.gears
    for mesh, (a, b) in zip(data["meshes"], (("input", "cluster_large"), ("cluster_small", "output"))):
        c = mesh["centre_distance"]
        assert mesh["backlash_of_modelled_gears"] == pytest.approx(backlash_of(specs[a], specs[b], c), abs=1e-12)
        assert modelled_backlash(specs[a], specs[b], c) == pytest.approx(backlash_of(specs[a], specs[b], c), abs=1e-12)
    block = data["placement_modelled_gears"]
    gears = tuple(PlacedGear(g["name"], g["role"], tuple(g["centre"]), g["rotation_rad"]) for g in block["gears"])
    check_placement(Placement(True, "from JSON", gears, gears[-1].centre[0], *block["backlash"], 0.0), specs)
