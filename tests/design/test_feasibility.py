"""The closed forms the load checks with (geargen.design) agree with the full models above them
(the exact outline in geargen.profile.tooth, the involute in geargen.core.involute, springs and
blades in geargen.core.flexures): the design layer may not import those, so this is where the
two are held together."""

import math
import warnings
from collections import Counter

import numpy as np
import pytest

from geargen.core import flexures as fx
from geargen.core.involute import tip_land_thickness
from geargen.design import feasibility as fe
from geargen.design.gear import GearSpec, gear_from_table
from geargen.design.stiffness import FlexureSpec, SpringSpec
from geargen.errors import DesignError, GeometryError
from geargen.profile import tooth


def random_gears(count: int, seed: int):
    """GearSpecs over the whole design-file range of every tooth parameter (module 1 mm)."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        try:
            out.append(GearSpec(
                teeth=int(rng.integers(4, 80)), module=1.0, pressure_angle=math.radians(rng.uniform(10, 35)),
                face_width=5.0, helix_angle=math.radians(rng.uniform(0, 45)) if rng.random() < 0.5 else 0.0,
                profile_shift=float(rng.uniform(-1.5, 1.5)), addendum_coefficient=float(rng.uniform(0.3, 1.5)),
                dedendum_coefficient=float(rng.uniform(0.5, 2.0)),
                thinning=float(rng.uniform(0, 0.75)) if rng.random() < 0.3 else 0.0))
        except DesignError:
            continue  # outside GearSpec's own ranges: not a question for the tooth rules
    return out


def outline_kind(spec) -> str | None:
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", tooth.UndercutWarning)
            tooth.tooth_profile(spec)
    except GeometryError as exc:
        return exc.kind
    return None


def test_tip_land_limit_is_the_outlines():
    assert fe.MIN_TIP_LAND_MODULES == tooth.MIN_TIP_LAND_MODULES


def test_the_load_refuses_exactly_the_teeth_the_outline_refuses_except_deep_undercuts():
    pairs = Counter()
    for spec in random_gears(1500, seed=20261121):
        mine, theirs = fe.tooth_problem(spec), outline_kind(spec)
        pairs[(mine, theirs)] += 1
        # never refuse a tooth the outline can make, and refuse it for the same reason
        assert mine is None or mine == theirs, (spec, mine, theirs)
        if theirs is not None and mine is None:
            # what only the outline finds: how far an undercut climbs (the rack's fillet joint lies
            # below the base circle, t_j < 0) and whether it severs the tooth
            assert theirs in ("no_involute", "severed_tooth") and fe.fillet_joint_roll(spec) < 0, spec
        if theirs is None:
            assert fe.tip_land(spec) == pytest.approx(tip_land_thickness(spec), abs=1e-12)
    # measured at this seed: the closed forms catch all but the deep undercuts (a few per cent)
    refused_by_outline = sum(n for (m, t), n in pairs.items() if t is not None)
    missed = sum(n for (m, t), n in pairs.items() if t is not None and m is None)
    assert refused_by_outline > 400 and missed / refused_by_outline < 0.1, pairs


def test_tip_land_and_tooth_thickness_match_core():
    for spec in random_gears(200, seed=7):
        if spec.tip_radius > spec.base_radius:
            assert fe.tip_land(spec) == pytest.approx(tip_land_thickness(spec), rel=1e-12, abs=1e-12)


def test_boundary_reported_for_the_shift_is_where_the_tip_land_reaches_the_limit():
    spec = GearSpec(teeth=12, module=2.0, pressure_angle=math.radians(20), face_width=10, profile_shift=1.3)
    assert fe.tooth_problem(spec) == "pointed_tooth"
    with pytest.raises(DesignError) as info:
        fe.check_tooth(spec, "gears.p", {"profile_shift": "profile_shift"}, "mm")
    assert info.value.field == "gears.p.profile_shift" and info.value.allowed.startswith("<= ")
    bound = float(info.value.allowed.split()[-1])
    limit = fe.MIN_TIP_LAND_MODULES * spec.module
    land = tip_land_thickness(GearSpec(teeth=12, module=2.0, pressure_angle=math.radians(20), face_width=10,
                                       profile_shift=bound))
    assert limit <= land < limit + 2e-4  # the printed bound is rounded down to 6 digits, so just inside


def test_negative_root_and_pointed_rack_name_the_parameter_that_fixes_them():
    spec = GearSpec(teeth=4, module=1.0, pressure_angle=math.radians(20), face_width=5, profile_shift=-1.0,
                    dedendum_coefficient=1.5)
    assert spec.root_radius_standard < 0 and outline_kind(spec) == "negative_root"
    with pytest.raises(DesignError) as info:
        fe.check_tooth(spec, "gears.g", {"profile_shift": "profile_shift", "teeth": "teeth"}, "mm")
    # r_f = z m / 2 - m (h_f - x) > 0  <=>  x > h_f - z / 2 = -0.5
    assert info.value.field == "gears.g.profile_shift" and float(info.value.allowed.split()[-1]) == pytest.approx(-0.5, abs=1e-5)
    rack = GearSpec(teeth=30, module=1.0, pressure_angle=math.radians(35), face_width=5, dedendum_coefficient=1.5)
    assert outline_kind(rack) == "pointed_rack" and fe.tooth_problem(rack) == "pointed_rack"
    with pytest.raises(DesignError) as info:
        fe.check_tooth(rack, "gears.g", {"dedendum_coefficient": "dedendum_coefficient"}, "mm")
    # h_f tan(alpha) <= pi / 4 with no room for a tip radius
    assert info.value.field == "gears.g.dedendum_coefficient"
    assert float(info.value.allowed.split()[-1]) == pytest.approx(math.pi / 4 / math.tan(math.radians(35)), rel=1e-4)


@pytest.mark.parametrize("end_type", ["plain", "plain_ground", "squared", "squared_ground"])
def test_spring_closed_forms_match_core(end_type):
    spec = SpringSpec(wire_diameter=1.2, mean_coil_diameter=9.0, active_coils=6.5, free_length=40.0,
                      allowable_shear_stress=800.0, end_type=end_type)
    core = fx.compression_spring(1.2, 9.0, 6.5, 40.0, spec.shear_modulus, 800.0, end_type, installed_length=25.0)
    assert spec.solid_height == pytest.approx(core.solid_height, rel=1e-15)
    assert spec.rate == pytest.approx(core.rate, rel=1e-15)
    assert spec.index == pytest.approx(core.index, rel=1e-15)
    assert spec.shear_stress(core.installed_force) == pytest.approx(core.installed_stress, rel=1e-14)
    # at the shortest allowed length the stress is the allowable (or the spring is solid)
    shortest = spec.shortest_installed_length
    at = fx.compression_spring(1.2, 9.0, 6.5, 40.0, spec.shear_modulus, 800.0, end_type, installed_length=shortest)
    assert at.installed_stress == pytest.approx(800.0, rel=1e-12) or shortest == spec.solid_height


def test_flexure_closed_forms_match_core():
    spec = FlexureSpec(thickness=0.3, length=20.0, width=10.0, allowable_stress=400.0, travel=0.5, count=3)
    core = fx.blade_flexure(3, 0.3, 20.0, 10.0, spec.elastic_modulus, 400.0, 0.5)
    assert spec.stress_at_travel == pytest.approx(core.stress_at_travel, rel=1e-15)
    assert spec.travel_limit == pytest.approx(core.travel_limit, rel=1e-15)


def test_engagement_lead_matches_core():
    # the load's lead (backlash + windup) / (|kappa_o - kappa_e| r_e) is the helper's, every hand
    from geargen.design.stiffness import _turn_rate
    for hand_e, hand_o, beta_o in (("left", "left", 15), ("left", "right", 15), ("right", "right", 10),
                                   ("right", "left", 0)):
        pinion = gear_from_table({"teeth": 20, "module_mm": 2.5, "pressure_angle_deg": 20, "helix_angle_deg": 15, "hand": hand_e,
                                  "face_width_mm": 30})
        large = gear_from_table({"teeth": 60, "module_mm": 2.0, "pressure_angle_deg": 20, "helix_angle_deg": beta_o, "hand": hand_o,
                                 "face_width_mm": 20})
        per_lead = abs(_turn_rate(large) - _turn_rate(pinion)) * pinion.reference_radius
        eng = fx.helical_engagement(
            fx.SlidingMesh("small", "out", pinion.helix_angle, pinion.reference_radius, pinion.hand), 0.08, 0.3,
            30.0, 3.0, other=fx.SlidingMesh("large", "in", large.helix_angle, large.reference_radius, large.hand))
        assert eng.lead == pytest.approx((0.08 + 0.3) / per_lead, rel=1e-14)
