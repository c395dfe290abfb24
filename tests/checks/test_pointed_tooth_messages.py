"""Issue 31: pointed_tooth errors name the gear and speak the design's length unit. The tip land by
hand: s_a = 2 r_a (s / (2 r) + inv alpha - inv alpha_a), s = m (pi / 2 + 2 x tan alpha)."""

import math
from pathlib import Path

import pytest

from geargen.checks.verdict import check_design
from geargen.core.geometry import check_tip_land
from geargen.core.involute import involute
from geargen.design.assembly import load_design
from geargen.design.gear import GearSpec
from geargen.errors import GeometryError
from geargen.profile.tooth import tooth_profile

A20 = math.radians(20)
M20DP = 25.4 / 20  # 20 diametral pitch


def tip_land_by_hand(z: int, m: float, x: float, thinning: float = 0.0) -> float:
    r, r_a = z * m / 2, z * m / 2 + (1 + x) * m
    s = m * (math.pi / 2 + 2 * x * math.tan(A20)) - thinning
    alpha_a = math.acos(r * math.cos(A20) / r_a)
    return 2 * r_a * (s / (2 * r) + involute(A20) - involute(alpha_a))


def test_a_pointed_inch_gear_is_named_and_in_inches():
    spec = GearSpec(teeth=12, module=M20DP, pressure_angle=A20, face_width=6.35, profile_shift=1.2, name="pg",
                    length_unit="in")
    land = tip_land_by_hand(12, M20DP, 1.2) / 25.4  # -0.0203 in
    with pytest.raises(GeometryError) as err:
        tooth_profile(spec)
    text = str(err.value)
    assert text.startswith("pointed_tooth: pg: tip land ") and " mm" not in text
    assert f"tip land {land:.4g} in" in text and "radius 0.41 in" in text  # r_a = (12 / 2 + 2.2) / 20 in
    with pytest.raises(GeometryError) as err:
        check_tip_land(spec)
    assert str(err.value).startswith("pointed_tooth: pg: the tooth is pointed") and " mm" not in str(err.value)


def test_the_check_names_the_gear_in_the_files_unit():
    """split_pinion_inch with the compliant pinion shifted +0.45 at the standard 2.7 in: the layout
    makes its mesh the mid-range 0.00225 in of backlash, taking back the shift's 2 x tan(alpha) m as
    well, less the output's share (the stiff mesh gives the output the middle of its allowance,
    0.001125 in); its tip land is then 0.00309 in (by hand) below 0.2 m_n = 0.01 in; the failure
    line names the pinion and speaks inches."""
    text = (Path(__file__).resolve().parents[2] / "assemblies" / "split_pinion_inch.toml").read_text()
    path = Path(__file__).parent / "_pointed.toml"
    try:
        path.write_text(text.replace("[gears.pinion_compliant]", "[gears.pinion_compliant]\nprofile_shift = 0.45", 1))
        result, _ = check_design(load_design(path), tolerances=False)
    finally:
        path.unlink(missing_ok=True)
    failure = next(f for f in result.all_failures if f.kind == "pointed_tooth")
    land = tip_land_by_hand(18, M20DP, 0.45, (0.00225 - 0.001125) * 25.4 + 2 * 0.45 * math.tan(A20) * M20DP) / 25.4
    assert failure.message == f"pinion_compliant: tip land {land:.4g} in is below 0.01 in (0.2 m_n)"
