"""Design files: unit suffixes convert exactly, bad input names the key and the allowed range."""

import math

import pytest

from geargen.design.assembly import design_from_dict, load_design
from geargen.design.gear import GearSpec, gear_from_table
from geargen.design.schema import Field, read_table
from geargen.errors import DesignError

ROBOT = "assemblies/robot_joint.toml"


def test_inch_and_metric_pitch_give_the_same_gear():
    inch = gear_from_table({"teeth": 21, "diametral_pitch_per_in": 32, "pressure_angle_deg": 20, "face_width_in": 0.5})
    metric = gear_from_table({"teeth": 21, "module_mm": 25.4 / 32, "pressure_angle_rad": math.radians(20),
                              "face_width_mm": 12.7})
    assert inch.length_unit == "in" and metric.length_unit == "mm"
    assert inch.reference_radius == pytest.approx(0.65625 / 2 * 25.4, rel=1e-15)
    assert inch.module == pytest.approx(metric.module, rel=1e-15)
    assert inch.face_width == pytest.approx(metric.face_width, rel=1e-15)


def test_transverse_system_converts_to_normal():
    # m_t = 3 / cos 30deg, alpha_t = 22.79588 deg is the transverse equivalent of m_n 3, alpha_n 20
    mt = 3 / math.cos(math.radians(30))
    g = gear_from_table({"teeth": 12, "module_mm": mt, "pitch_system": "transverse", "pressure_angle_deg": 22.795884,
                         "helix_angle_deg": 30, "face_width_mm": 20, "profile_shift": 0.1})
    assert g.module == pytest.approx(3.0, rel=1e-12)
    assert math.degrees(g.pressure_angle) == pytest.approx(20.0, abs=1e-5)
    assert g.profile_shift * g.module == pytest.approx(0.1 * mt, rel=1e-12)  # same shift in mm


def test_normal_thinning_is_converted_to_circumferential():
    g = gear_from_table({"teeth": 30, "module_mm": 2, "pressure_angle_deg": 20, "helix_angle_deg": 25,
                         "face_width_mm": 10, "thinning_normal_mm": 0.05})
    assert g.thinning == pytest.approx(0.05 / math.cos(math.radians(25)), rel=1e-14)
    assert g.thinning_normal == pytest.approx(0.05, rel=1e-14)


@pytest.mark.parametrize("table, key, allowed", [
    ({"teeth": 2, "module_mm": 1, "pressure_angle_deg": 20, "face_width_mm": 5}, "gear.teeth", "[4, 2000]"),
    ({"teeth": 20, "module_mm": 1, "pressure_angle_deg": 50, "face_width_mm": 5}, "gear.pressure_angle_deg", "[10, 35] deg"),
    ({"teeth": 20, "module_mm": 1, "pressure_angle_deg": 20, "face_width_in": -1}, "gear.face_width_in",
     "[3.93701e-08, 196.85] in"),  # the key's own 5000 mm; above zero, a length's plausible 1 nm (schema.PLAUSIBLE)
    ({"teeth": 20, "module_mm": 1, "pressure_angle_deg": 20, "face_width_mm": 5, "colour": 1}, "gear.colour", "teeth"),
    ({"teeth": 20, "pressure_angle_deg": 20, "face_width_mm": 5}, "gear.module_mm", "diametral_pitch_per_in"),
    ({"teeth": 20, "module_mm": 1, "diametral_pitch_per_in": 32, "pressure_angle_deg": 20, "face_width_mm": 5},
     "gear.module_mm", "exactly one" ),
    ({"teeth": 20, "module_mm": 1, "pressure_angle_deg": 20, "face_width_mm": 5, "hand": "up"}, "gear.hand", "'left'"),
    ({"teeth": 20, "module_mm": 1, "pressure_angle_deg": 20, "face_width_mm": 5, "bore_diameter_mm": 30},
     "gear.bore_diameter_mm", "<"),
])
def test_bad_input_names_key_and_allowed_range(table, key, allowed):
    with pytest.raises(DesignError) as info:
        gear_from_table(table)
    assert info.value.field == key
    assert allowed in str(info.value)


def test_range_is_reported_in_the_unit_the_user_wrote():
    f = Field("travel", "length", minimum=0.0, maximum=2.54)
    with pytest.raises(DesignError) as info:
        read_table({"travel_in": 0.2}, [f], "carriage")
    assert info.value.field == "carriage.travel_in"
    assert info.value.allowed == "[0, 0.1] in"
    assert read_table({"travel_um": 2000}, [f])["travel"] == pytest.approx(2.0)


def test_gear_spec_validates_on_construction():
    with pytest.raises(DesignError, match="rack_tip_radius_coefficient"):
        GearSpec(teeth=20, module=1, pressure_angle=math.radians(20), face_width=5, rack_tip_radius_coefficient=0.5)
    g = GearSpec(teeth=20, module=1, pressure_angle=math.radians(20), face_width=5)
    # the full-radius fillet of a 0.25 m clearance rack at 20 deg: 0.25 / (1 - sin 20deg)
    assert g.rack_tip_radius_coefficient == pytest.approx(0.25 / (1 - math.sin(math.radians(20))), rel=1e-12)


def test_robot_joint_design_loads_in_inches():
    d = load_design(ROBOT)
    assert d.length_unit == "in" and d.drive_type == "type2" and d.preload_method == "radial"
    assert {k: g.teeth for k, g in d.gears.items()} == {"input": 16, "cluster_large": 48, "cluster_small": 21, "output": 112}
    diameters = [2 * d.gears[k].reference_radius / 25.4 for k in ("input", "cluster_large", "cluster_small", "output")]
    assert diameters == pytest.approx([0.5, 1.5, 0.65625, 3.5], rel=1e-14)  # Appendix "Pitch Circle Dia."
    assert len(d.sha256) == 64


def test_unknown_section_and_bad_drive_type_are_named():
    with pytest.raises(DesignError) as info:
        design_from_dict({"name": "x", "gearz": {}})
    assert info.value.field == "gearz"
    with pytest.raises(DesignError) as info:
        design_from_dict({"name": "x", "drive": {"type": "type3"}})
    assert info.value.field == "drive.type" and "'type2'" in str(info.value)
