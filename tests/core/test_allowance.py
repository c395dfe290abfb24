"""Tooth-thickness allowances (geargen.core.allowance): span limits against the textbook closed form,
the centre-distance-tolerance route against its defining conditions, and bad input."""

import math

import pytest

from geargen.core.allowance import (BacklashRoute, at_deviation, ThicknessAllowance, allowances_for_backlash, mesh_backlash_range,
                                    over_pins_limits, span_limits, thickest, thinnest)
from geargen.core.geometry import GearPair, backlash_at_centre_distance, over_pins_measurement, span_measurement
from geargen.core.involute import involute
from geargen.design.gear import GearSpec, gear_from_table
from geargen.errors import DesignError

DEG = math.pi / 180
UM = 1e-3


def helical(teeth=27, shift=0.2, hand="right"):
    return GearSpec(teeth=teeth, module=2.0, pressure_angle=20 * DEG, helix_angle=15 * DEG, hand=hand,
                    face_width=30.0, profile_shift=shift, name=f"h{teeth}")


def spur_inch(teeth=40):
    return GearSpec(teeth=teeth, module=25.4 / 24, pressure_angle=20 * DEG, face_width=12.7, name=f"s{teeth}",
                    length_unit="in")


@pytest.mark.parametrize("spec", [helical(), spur_inch()], ids=["helical metric", "spur inch"])
def test_span_limits_are_the_closed_form_with_the_deviations(spec):
    """W_k = m_n cos(a_n) [(k - 0.5) pi + z inv(a_t)] + 2 x m_n sin(a_n) + E_sn cos(a_n) (ISO 21771 /
    DIN 3960 base tangent length with the normal thickness deviation E_sn), written out here."""
    allowance = ThicknessAllowance(-30 * UM, -80 * UM)
    k = span_measurement(spec).teeth_spanned
    m, an, z, x = spec.module, spec.pressure_angle, spec.teeth, spec.profile_shift
    at = math.atan(math.tan(an) / math.cos(spec.helix_angle))

    def w(e_sn):
        return m * math.cos(an) * ((k - 0.5) * math.pi + z * (math.tan(at) - at)) + 2 * x * m * math.sin(an) \
            + e_sn * math.cos(an)

    smallest, largest = span_limits(spec, allowance, k)
    assert smallest == pytest.approx(w(-80 * UM), abs=1e-9)
    assert largest == pytest.approx(w(-30 * UM), abs=1e-9)
    # 50 um of thickness tolerance opens the span by 50 cos(20 deg) = 46.98 um
    assert largest - smallest == pytest.approx(50 * UM * math.cos(20 * DEG), abs=1e-12)


def test_over_pins_limits_bracket_the_nominal_and_order_by_thickness():
    """The tooth at zero deviation is thicker than both limits; the thinnest tooth gives the smaller dimension.
    Sensitivity, derived by hand for a spur gear with even z (M = 2 r_c + D, r_c = r_b / cos(a_c),
    inv(a_c) = s / (2 r) + ... so d inv(a_c) = dE / (2 r)): dM/dE = cos(a) / sin(a_c). The limits are
    exact; the slope is a linearisation over 40 um, hence 1e-3."""
    spec = spur_inch()
    d = over_pins_measurement(spec).pin_diameter
    lo, hi = over_pins_limits(spec, ThicknessAllowance(-20 * UM, -60 * UM), d)
    nominal = over_pins_measurement(spec, d).dimension
    assert lo < hi < nominal
    pins = over_pins_measurement(at_deviation(spec, -40 * UM), d)  # slope at the middle of the band
    slope = math.cos(spec.pressure_angle) / math.sin(pins.centre_pressure_angle)
    assert (hi - lo) / (40 * UM) == pytest.approx(slope, rel=1e-3)


@pytest.mark.parametrize("f_a", [0.0, 0.015])
@pytest.mark.parametrize("pair", ["helical", "spur"])
def test_route_gives_the_design_range_at_the_tolerance_ends(pair, f_a):
    """Thickest teeth at a - f_a give B_min, thinnest at a + f_a give B_max (the route's two conditions),
    each gear taking half the summed circumferential thinning; the range is wider than B_max - B_min
    without f_a by exactly nothing and narrower in thickness by the tolerance's backlash."""
    if pair == "helical":
        g1, g2 = helical(20, 0.3, "right"), helical(61, -0.1, "left")
    else:
        g1, g2 = spur_inch(18), spur_inch(54)
    a = GearPair(g1, g2).standard_centre_distance + 0.12
    route = BacklashRoute(0.10, 0.20, a, f_a)
    a1, a2 = allowances_for_backlash(g1, g2, route)
    lo = backlash_at_centre_distance(GearPair(thickest(g1, a1), thickest(g2, a2)), a - f_a).circumferential_reference
    hi = backlash_at_centre_distance(GearPair(thinnest(g1, a1), thinnest(g2, a2)), a + f_a).circumferential_reference
    assert (lo, hi) == pytest.approx((0.10, 0.20), abs=1e-12)
    assert mesh_backlash_range(g1, a1, g2, a2, a, f_a) == pytest.approx((0.10, 0.20), abs=1e-12)
    # equal circumferential split: equal normal deviations for equal helix angles
    assert (a1.upper, a1.lower) == pytest.approx((a2.upper, a2.lower), abs=1e-15)
    assert a1.lower < a1.upper <= 0
    # thickness tolerance = (range - the centre distance's own spread) / 2 per gear, normal
    spread = backlash_at_centre_distance(GearPair(g1, g2), [a - f_a, a + f_a]).circumferential_reference
    expected = (0.10 - (spread[1] - spread[0])) / 2 * math.cos(g1.helix_angle)
    assert a1.upper - a1.lower == pytest.approx(expected, abs=1e-12)
    assert "centre-distance-tolerance route" in a1.method and (f"{f_a:.6g} mm" in a1.method)


def test_a_fixed_gear_keeps_its_allowance_and_the_mate_takes_the_rest():
    g1, g2 = spur_inch(18), spur_inch(54)
    a = GearPair(g1, g2).standard_centre_distance
    fixed = ThicknessAllowance(-10 * UM, -30 * UM)
    a1, a2 = allowances_for_backlash(g1, g2, BacklashRoute(0.05, 0.12, a), fixed1=fixed)
    assert a1 is fixed
    assert mesh_backlash_range(g1, a1, g2, a2, a) == pytest.approx((0.05, 0.12), abs=1e-12)


def test_route_refuses_a_range_the_tolerance_eats():
    g1, g2 = spur_inch(18), spur_inch(54)
    a = GearPair(g1, g2).standard_centre_distance
    # +-0.1 mm of centre distance alone spreads the backlash by ~4 x 0.1 tan(20 deg) = 0.146 mm > 0.1 mm
    route = BacklashRoute(0.05, 0.15, a, 0.1, field_max="synthesis.circumferential_backlash_max_mesh1_mm",
                          field_tolerance="checks.centre_distance_tolerance_mm")
    with pytest.raises(DesignError) as e:
        allowances_for_backlash(g1, g2, route)
    assert e.value.field == "synthesis.circumferential_backlash_max_mesh1_mm"
    assert "centre-distance tolerance" in e.value.problem and "checks.centre_distance_tolerance_mm" in e.value.allowed


def test_route_refuses_a_minimum_below_what_the_centre_distance_gives():
    g1, g2 = spur_inch(18), spur_inch(54)
    a = GearPair(g1, g2).standard_centre_distance + 0.5  # ~2 x 0.5 tan(20 deg) = 0.36 mm from the centres alone
    with pytest.raises(DesignError) as e:
        allowances_for_backlash(g1, g2, BacklashRoute(0.05, 0.5, a, field_min="layout.circumferential_backlash_min_mm"))
    assert e.value.field == "layout.circumferential_backlash_min_mm" and e.value.allowed.startswith(">= 0.3")


@pytest.mark.parametrize("upper, lower, problem", [(5.0, -10.0, "upper deviation 5 um"),
                                                   (-20.0, -10.0, "below the lower")])
def test_bad_allowance_names_the_option_and_the_range(upper, lower, problem):
    with pytest.raises(DesignError) as e:
        ThicknessAllowance(upper * UM, lower * UM, field="--thickness-allowance")
    assert e.value.field == "--thickness-allowance" and problem in e.value.problem
    assert "<= 0" in e.value.allowed


def _table(**extra):
    return {"teeth": 30, "module_mm": 2, "pressure_angle_deg": 20, "face_width_mm": 10, **extra}


def test_design_keys_give_the_entered_allowance():
    spec = gear_from_table(_table(thickness_upper_deviation_um=-25, thickness_lower_deviation_um=-60), "gears.g")
    assert spec.thickness_deviations == pytest.approx((-25 * UM, -60 * UM))
    inch = gear_from_table({**_table(thickness_upper_deviation_in=-0.001, thickness_lower_deviation_in=-0.002)},
                           "gears.g")
    assert inch.thickness_deviations == pytest.approx((-0.0254, -0.0508))


@pytest.mark.parametrize("keys, field, allowed", [
    ({"thickness_upper_deviation_um": 10, "thickness_lower_deviation_um": -10},
     "gears.g.thickness_upper_deviation_um", "[-1e+07, 0] um"),  # no own lower bound: a length's plausible -10 m = -1e7 um
    ({"thickness_upper_deviation_um": -30, "thickness_lower_deviation_um": -10},
     "gears.g.thickness_lower_deviation_um", "<= -30 um"),
    ({"thickness_upper_deviation_um": -30}, "gears.g.thickness_lower_deviation_um", "or neither"),
])
def test_bad_design_keys_name_the_key_and_the_range(keys, field, allowed):
    with pytest.raises(DesignError) as e:
        gear_from_table(_table(**keys), "gears.g")
    assert e.value.field == field and allowed in e.value.allowed
