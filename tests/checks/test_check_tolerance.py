"""Minimum backlash across the error budget: worst case and Monte Carlo, fixed bearings and the
preloaded loop of the robot joint."""

import math
from dataclasses import replace

import numpy as np
import pytest

from geargen.checks.mesh2d import MeshSetup, free_play, polar_outline, sweep_mesh
from geargen.checks.tolerance import (alternating_flanks, monte_carlo_pair, pair_tolerance, worst_case_pair)
from geargen.design.synthesis import GearErrors

from checks_support import inch_gear, theory_normal_backlash

IN = 25.4
PINION, WHEEL = inch_gear(21, name="pinion", thinning=0.001 * IN), inch_gear(112, name="wheel", thinning=0.0015 * IN)
C2 = 2.078125 * IN


def _circ(g1, g2, a):
    """Backlash of the resolved model's kind (circumferential at gear 1's reference circle) of a
    spur pair: the normal backlash over cos(alpha), the profile angle at the reference circle."""
    return theory_normal_backlash(g1, g2, a) / math.cos(g1.transverse_pressure_angle)


def test_worst_case_of_eccentricities_is_the_backlash_at_the_closest_centres():
    e1 = GearErrors(0.0002 * IN, 0.0016 * IN, 0.0)
    e2 = GearErrors(0.0005 * IN, 0.0012 * IN, 0.0)
    su = MeshSetup.centred(PINION, WHEEL, C2)
    circ, normal, da = worst_case_pair(su, e1, e2)
    assert da == pytest.approx(-(0.0002 + 0.0016 + 0.0005 + 0.0012) / 2 * IN, rel=1e-12)
    assert normal == pytest.approx(theory_normal_backlash(PINION, WHEEL, C2 + da), abs=1e-8)
    assert circ == pytest.approx(_circ(PINION, WHEEL, C2 + da), abs=1e-8)


def test_tooth_to_tooth_worst_case_narrows_the_play_by_the_tir_of_each_gear():
    t = 0.0005 * IN
    e = GearErrors(0.0, 0.0, t)
    su = MeshSetup.centred(PINION, WHEEL, C2)
    nominal = _circ(PINION, WHEEL, C2)
    only1 = nominal - worst_case_pair(su, e, None)[0]
    both = nominal - worst_case_pair(su, e, e)[0]
    r_w1 = C2 * 21 / (21 + 112)
    # neighbouring teeth at opposite limits (+-t/2) take t (reference circle) off the play they bound
    assert only1 == pytest.approx(t * r_w1 / PINION.reference_radius, rel=1e-6)
    assert both == pytest.approx(2 * t * r_w1 / PINION.reference_radius, rel=1e-6)
    # which the alternating state reaches where two different teeth of each gear bound the play
    from geargen.checks.tolerance import alternating_flanks
    alt = replace(su, flanks1=alternating_flanks(PINION, t / 2), flanks2=alternating_flanks(WHEEL, t / 2))
    sw = sweep_mesh(alt, np.linspace(0, 2 * math.pi / 21 * 14, 14 * 24, endpoint=False), areas=False)
    assert nominal - sw.circumferential_backlash.min() == pytest.approx(both, rel=1e-6)


def test_alternating_flanks_move_whole_teeth():
    f = alternating_flanks(PINION, 0.01)
    assert f.shape == (21, 2)
    assert np.allclose(f[:, 0], -f[:, 1])
    assert np.allclose(np.abs(f[:, 1]) * PINION.reference_radius, 0.01)


def test_monte_carlo_is_seeded_and_bounded_by_the_worst_case():
    e1 = GearErrors(0.0002 * IN, 0.0016 * IN, 0.0005 * IN)
    e2 = GearErrors(0.0005 * IN, 0.0012 * IN, 0.0005 * IN)
    su = MeshSetup.centred(PINION, WHEEL, C2)
    a = monte_carlo_pair(su, e1, e2, 40, np.random.default_rng(7))
    b = monte_carlo_pair(su, e1, e2, 40, np.random.default_rng(7))
    c = monte_carlo_pair(su, e1, e2, 40, np.random.default_rng(8))
    assert np.array_equal(a, b) and not np.array_equal(a, c)
    wc = worst_case_pair(su, e1, e2)[0]
    nominal = _circ(PINION, WHEEL, C2)
    assert np.all(a >= wc - 1e-9)
    assert np.all(a < nominal)  # every build is worse than perfect somewhere in its revolutions
    assert np.median(a) < nominal - 0.3 * (nominal - wc)


def test_pair_tolerance_fails_a_mesh_whose_backlash_is_eaten():
    e = GearErrors(0.0005 * IN, 0.0016 * IN, 0.0005 * IN)
    tight = replace(PINION, thinning=0.0), replace(WHEEL, thinning=0.0005 * IN)
    res = pair_tolerance(MeshSetup.centred(*tight, C2, "tight"), e, e, 20, np.random.default_rng(1))
    assert res.worst_case_min_backlash < 0 < res.nominal_min_backlash
    assert [f.kind for f in res.failures] == ["backlash_lost"]
    ok = pair_tolerance(MeshSetup.centred(PINION, WHEEL, C2 + 0.004 * IN, "roomy"), e, e, 20,
                        np.random.default_rng(1))
    assert ok.ok and ok.worst_case_min_backlash > 0


# ------------------------------------------------------------------------- the robot joint
@pytest.fixture(scope="module")
def joint(robot_joint):
    from geargen.checks.verdict import mesh_setup
    from geargen.drives import resolve

    layout = resolve(robot_joint)
    return robot_joint, [mesh_setup(layout, m) for m in layout.meshes], layout


def test_placed_robot_joint_has_its_working_flanks_in_contact(joint):
    """The resolved drive places every gear with its working flanks the design's loaded flank gap
    apart (the solids must not touch; the gap is circumferential at the reference circle): the
    exact 2-D check of the placed outlines agrees to 1 nm along the line of action."""
    design, setups, layout = joint
    assert sorted(s.name for s in setups) == ["mesh1_a", "mesh1_b", "mesh2_a", "mesh2_b"]
    gap = layout.placement.loaded_flank_gap
    assert gap > 0
    for su in setups:
        play = free_play(polar_outline(su.gear1), polar_outline(su.gear2), su.states([0.0]))
        working = min(play.ccw[0], play.cw[0]) * su.gear1.base_radius
        other = max(play.ccw[0], play.cw[0]) * su.gear1.base_radius
        assert abs(working - gap * np.cos(su.gear1.transverse_pressure_angle)) < 1e-6, su.name
        assert other > 0.01


def test_robot_joint_loop_tolerance(joint):
    from geargen.checks.tolerance import loop_tolerance
    from geargen.core.tolerance import exact_error_budget
    from geargen.design.synthesis import GEAR_ROLES

    from geargen.core.accuracy import gear_errors

    design, setups, layout = joint
    errors = {r: gear_errors(design, r) for r in GEAR_ROLES}
    syn, gap = layout.synthesis.synthesis, layout.placement.loaded_flank_gap
    res = loop_tolerance(syn, {s.name: s for s in setups}, errors, layout.placement.backlash_mesh1 - 2 * gap,
                         layout.placement.backlash_mesh2 - 2 * gap, 60, np.random.default_rng(1994))
    by = {r.mesh: r for r in res}
    assert by["mesh1_a"].meant_for == "preloaded" and by["mesh2_a"].meant_for == "backlash"
    for r in res:
        assert 0 < r.worst_case_min_backlash < r.nominal_min_backlash
        assert r.worst_case_centre_distance_change < 0
        assert np.all(r.monte_carlo_min_backlash >= r.worst_case_min_backlash - 1e-6)
        assert r.ok, r.failures
    # the carriage mesh: its centre distance shrinks by about the Appendix's dC1 half-range
    budget = exact_error_budget(syn, tuple(errors[r] for r in GEAR_ROLES))
    assert by["mesh1_a"].carriage_travel == pytest.approx(max(-budget.worst_low, budget.worst_high))
    # mirror symmetry of the two paths
    assert by["mesh1_a"].worst_case_min_backlash == pytest.approx(by["mesh1_b"].worst_case_min_backlash, rel=1e-6)


def test_robot_joint_without_thinning_loses_mesh2_backlash(robot_joint):
    """At standard centres, gears without allowance have no backlash in mesh 2 to lose."""
    from geargen.commands.check import check_design
    from geargen.design.assembly import Design

    gears = {k: (replace(g, thinning=0.0) if k in ("cluster_small", "output") else g)
             for k, g in robot_joint.gears.items()}
    d = Design(**{**robot_joint.__dict__, "gears": gears})
    res = check_design(d, tolerances=False)
    kinds = {m.mesh: m.failure_kinds for m in res.meshes}
    assert kinds["mesh2_a"] == ["no_backlash"] and kinds["mesh1_a"] == []
