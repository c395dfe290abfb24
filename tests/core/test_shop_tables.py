"""The pure tables of the drawing's shop data: ISO 286-1 limits, DIN 3967 allowances, the gauge-pin
series (geargen.core.iso286, .din3967, .measuring_pins)."""

import math

import pytest

from geargen.core import din3967, iso286
from geargen.core.allowance import series_allowance
from geargen.core.geometry import ideal_pin_diameter, over_pins_dimension
from geargen.core.measuring_pins import standard_pin
from geargen.design.gear import GearSpec
from geargen.errors import DesignError


def test_iso286_published_limits():
    # ISO 286-2 Table 17 / the usual fits charts: 20 H7 = +0 / +21 um, 20 h11 = -130 / 0 um,
    # 6 H7 = 0 / +12 um, 50 h9 = -62 / 0 um (50 is "above 30 up to and including 50")
    assert iso286.tolerance_class("H7", 20.0, "hole").to_dict()["upper_deviation_um"] == 21
    t = iso286.tolerance_class("H7", 20.0, "hole")
    assert (t.lower_um, t.upper_um) == (0.0, 21.0)
    assert (iso286.tolerance_class("h11", 20.0, "shaft").lower_um, iso286.tolerance_class("h11", 20.0, "shaft").upper_um) == (-130.0, 0.0)
    assert iso286.tolerance_class("H7", 6.0, "hole").upper_um == 12.0
    assert iso286.tolerance_class("h9", 50.0, "shaft").lower_um == -62.0
    assert iso286.tolerance_class("js8", 10.0, "shaft").upper_um == 11.0  # IT8 = 22 um up to 10 mm


def test_iso286_table_follows_the_tolerance_unit():
    # ISO 286-1, Annex: IT5..IT13 = (7, 10, 16, 25, 40, 64, 100, 160, 250) i with i = 0.45 D^(1/3) + 0.001 D
    # (um, D the geometric mean of the range's limits); the table rounds to preferred numbers, within
    # 10 % of the formula. The range up to 3 mm is left out: its values are the standard's by
    # convention, not by the formula (IT7 = 10 um where 16 i gives 8.7)
    factors = {5: 7, 6: 10, 7: 16, 8: 25, 9: 40, 10: 64, 11: 100, 12: 160, 13: 250}
    lows = iso286.SIZE_STEPS_MM[:-1]
    for lo, hi, row in zip(lows, iso286.SIZE_STEPS_MM[1:], range(1, 13)):
        d = math.sqrt(lo * hi)
        i = 0.45 * d ** (1 / 3) + 0.001 * d
        for grade, k in factors.items():
            assert iso286.IT_UM[grade][row] == pytest.approx(k * i, rel=0.10), (grade, hi)


def test_iso286_refuses_what_it_does_not_implement():
    with pytest.raises(DesignError, match="H or JS"):
        iso286.tolerance_class("G7", 20.0, "hole", "gears.x.bore_fit")
    with pytest.raises(DesignError, match="h or js"):
        iso286.tolerance_class("H7", 20.0, "shaft")
    with pytest.raises(DesignError, match="outside"):
        iso286.tolerance_class("H7", 600.0, "hole")


def test_din3967_the_standards_own_example():
    # DIN 3967, clause 3.1: 27cd at d = 100 mm: A_sne = -70 um, T_s = 100 um, A_sni = -170 um
    assert din3967.allowance_um(100.0, "cd27") == (-70.0, -170.0)
    assert din3967.allowance_um(100.0, "27cd") == (-70.0, -170.0)
    # cd25 at d = 21 mm (10 < d <= 50): -54 and -54 - 30
    assert din3967.allowance_um(21.0, "cd25") == (-54.0, -84.0)


def test_din3967_tolerance_series_step_by_the_r5_ratio():
    # Table 2's series grow by about the R5 ratio 10^(1/5) = 1.585 (rounded: 1.5 .. 1.67)
    for row in din3967.TOLERANCE_UM:
        for a, b in zip(row, row[1:]):
            assert 1.49 <= b / a <= 1.68, row


def test_din3967_bad_designation_names_the_key():
    with pytest.raises(DesignError) as exc:
        din3967.allowance_um(20.0, "zz25", "gears.p.thickness_allowance_series")
    assert exc.value.field == "gears.p.thickness_allowance_series"


def test_series_allowance_of_a_gear():
    spec = GearSpec(teeth=21, module=1.0, pressure_angle=math.radians(20), face_width=10.0)
    a = series_allowance(spec)
    assert (a.upper_um, a.lower_um) == pytest.approx((-54.0, -84.0), abs=1e-9)
    assert a.method.startswith("DIN 3967:1978-08 cd25")


def test_the_standard_pin_is_the_series_size_nearest_the_ideal():
    # 32 DP, 20 deg, 112 teeth: the pin touching at the pitch circle is 0.05251 in; the nearest
    # 0.001 in gauge pin is 0.053 in
    spec = GearSpec(teeth=112, module=25.4 / 32, pressure_angle=math.radians(20), face_width=6.35, length_unit="in")
    ideal = ideal_pin_diameter(spec)
    pins, series = standard_pin(spec)
    assert "0.001 in" in series
    n = pins.pin_diameter / 0.0254
    assert n == pytest.approx(round(n), abs=1e-9) and abs(pins.pin_diameter - ideal) <= 0.0254 / 2
    assert pins.pin_diameter / 25.4 == pytest.approx(0.053, abs=1e-12)
    assert pins.dimension == pytest.approx(float(over_pins_dimension(spec, pins.pin_diameter)), abs=1e-12)
    metric = GearSpec(teeth=21, module=1.0, pressure_angle=math.radians(20), face_width=10.0)
    pins, series = standard_pin(metric)
    assert pins.pin_diameter == pytest.approx(1.72, abs=1e-12) and "0.01 mm" in series
