"""Straight bevel gear geometry (geargen.families.bevel.geometry) against a published example and closed forms."""

import math

import numpy as np
import pytest

from geargen.families.bevel.geometry import (base_cone_angle, bevel_geometry, check_tooth, gear_solid_angle, pitch_cone_angles,
                                spherical_involute_function, spherical_involute_points, tooth_half_angle,
                                virtual_contact_ratio)
from geargen.families.bevel.spec import BevelGearSpec
from geargen.families.registry import read_gear
from geargen.errors import DesignError, GeometryError

DEG = math.pi / 180


def _khk(teeth, mate):
    return read_gear({"kind": "bevel", "teeth": teeth, "mate_teeth": mate, "module_mm": 3,
                            "pressure_angle_deg": 20, "face_width_mm": 22, "shaft_angle_deg": 90})


def test_khk_standard_straight_bevel_example():
    # KHK Gear Technical Reference, calculation of standard straight bevel gears (Sigma = 90 deg,
    # m = 3, alpha = 20 deg, z = 20 / 40, b = 22, h_a = m, h_f = 1.25 m): the published values below
    # (to the table's 5 decimals of a degree, 4-5 of a mm)
    pinion, gear = _khk(20, 40), _khk(40, 20)
    p, g = bevel_geometry(pinion), bevel_geometry(gear)
    assert math.degrees(p.pitch_cone_angle) == pytest.approx(26.56505, abs=1e-5)
    assert math.degrees(g.pitch_cone_angle) == pytest.approx(63.43495, abs=1e-5)
    assert p.cone_distance == pytest.approx(67.08204, abs=1e-5) and g.cone_distance == pytest.approx(67.08204, abs=1e-5)
    assert math.degrees(p.dedendum_angle) == pytest.approx(3.19960, abs=1e-5)
    assert math.degrees(p.addendum_angle) == pytest.approx(2.56064, abs=1e-5)
    assert math.degrees(p.tip_cone_angle) == pytest.approx(29.12569, abs=1e-5)
    assert math.degrees(g.tip_cone_angle) == pytest.approx(65.99559, abs=1e-5)
    assert math.degrees(p.root_cone_angle) == pytest.approx(23.36545, abs=1e-5)
    assert math.degrees(g.root_cone_angle) == pytest.approx(60.23535, abs=1e-5)
    assert p.apex_to_crown == pytest.approx(58.6584, abs=1e-4) and g.apex_to_crown == pytest.approx(27.3167, abs=1e-4)
    assert p.axial_face_width == pytest.approx(19.2374, abs=1e-4) and g.axial_face_width == pytest.approx(8.9587, abs=1e-4)
    assert p.tip_diameter == pytest.approx(65.3666, abs=1e-4) and g.tip_diameter == pytest.approx(122.6833, abs=1e-4)
    # back-cone (Tredgold) equivalent teeth z_v = z / cos delta: 20 / cos 26.56505 = 10 sqrt 5 and
    # 40 / cos 63.43495 = 40 sqrt 5 (tan delta1 = 1/2 exactly)
    assert p.virtual_teeth == pytest.approx(10 * math.sqrt(5), rel=1e-12)
    assert g.virtual_teeth == pytest.approx(40 * math.sqrt(5), rel=1e-12)


def test_virtual_contact_ratio_is_the_equivalent_spur_pairs():
    # independent: the equivalent spur pair (z_v1 = 10 sqrt 5, z_v2 = 40 sqrt 5, m = 3, alpha = 20 deg,
    # h_a = m) by the spur formula with its own radii r = z_v m / 2
    pinion = _khk(20, 40)
    a = 20 * DEG
    r1, r2 = 10 * math.sqrt(5) * 1.5, 40 * math.sqrt(5) * 1.5
    ga = math.sqrt((r1 + 3) ** 2 - (r1 * math.cos(a)) ** 2) + math.sqrt((r2 + 3) ** 2 - (r2 * math.cos(a)) ** 2)
    expected = (ga - (r1 + r2) * math.sin(a)) / (math.pi * 3 * math.cos(a))
    assert virtual_contact_ratio(pinion) == pytest.approx(expected, rel=1e-12)
    assert virtual_contact_ratio(pinion) == pytest.approx(1.71218, abs=1e-5)  # the value itself, for the record


@pytest.mark.parametrize("sigma_deg", [10, 45, 90, 120, 170])
def test_pitch_cones_touch_for_any_shaft_angle(sigma_deg):
    # the two pitch cones share a generator: R_e sin delta_i = z_i m / 2 with one cone distance
    s = sigma_deg * DEG
    d1, d2 = pitch_cone_angles(17, 29, s)
    assert d1 + d2 == pytest.approx(s, abs=1e-15)
    assert 17 / math.sin(d1) == pytest.approx(29 / math.sin(d2), rel=1e-12)


def test_spherical_involute_rolls_without_slipping():
    # independent check of the parametrisation: each point lies on the sphere, on the great circle
    # tangent to the base cone along the generator g(t), at the arc distance from g(t) equal to the
    # base circle's arc rolled off, t sin(delta_b) (unit sphere)
    db = base_cone_angle(40 * DEG, 20 * DEG)
    t = np.linspace(0.0, 1.2, 50)
    p = spherical_involute_points(t, db)
    assert np.allclose(np.linalg.norm(p, axis=1), 1.0, atol=1e-15)
    g = np.stack([math.sin(db) * np.cos(t), math.sin(db) * np.sin(t), np.full_like(t, math.cos(db))], axis=1)
    arc = np.arccos(np.clip(np.sum(p * g, axis=1), -1, 1))
    assert np.allclose(arc, t * math.sin(db), atol=1e-12)
    # the great circle through g is normal to the base cone's tangent plane: p has no component along
    # the cone's outward normal at g
    normal = np.stack([math.cos(db) * np.cos(t), math.cos(db) * np.sin(t), -np.full_like(t, math.sin(db))], axis=1)
    assert np.allclose(np.sum(p * normal, axis=1), 0.0, atol=1e-15)
    # and the closed form of polar angle and azimuth
    polar = np.arccos(p[:, 2])
    assert np.allclose(np.cos(polar), math.cos(db) * np.cos(t * math.sin(db)), atol=1e-15)
    assert np.allclose(np.arctan2(p[:, 1], p[:, 0]), spherical_involute_function(polar, db), atol=1e-12)


def test_spherical_involute_tends_to_the_plane_involute():
    # a small base cone at a large cone distance: R sin(delta_b) = r_b fixed, the involute function of
    # the plane involute at the same radius (inv(a) = tan a - a, cos a = r_b / r)
    rb = 10.0
    for db in (1e-3, 1e-4):
        big = rb / math.sin(db)
        radius = 12.0
        polar = math.asin(radius / big)
        a = math.acos(rb / radius)
        assert spherical_involute_function(polar, db) == pytest.approx(math.tan(a) - a, rel=1e-5)


def test_tooth_thickness_at_the_pitch_cone_and_solid_angle():
    spec = _khk(20, 40)
    # arc thickness on the heel pitch circle is half the circular pitch (no shift, no thinning)
    assert 2 * tooth_half_angle(spec, spec.pitch_cone_angle) * spec.reference_diameter / 2 == pytest.approx(
        math.pi * 3 / 2, rel=1e-14)
    # the solid angle of a toothless cone to the root is 2 pi (1 - cos delta_f); teeth add less than the
    # full ring between root and tip cones
    g = bevel_geometry(spec)
    ring = 2 * math.pi * (math.cos(g.root_cone_angle) - math.cos(g.tip_cone_angle))
    teeth = gear_solid_angle(spec) - 2 * math.pi * (1 - math.cos(g.root_cone_angle))
    assert 0.3 * ring < teeth < 0.7 * ring


def test_volumes_of_the_two_backs_by_hand():
    from geargen.families.bevel.geometry import back_plane_distance, bevel_core, bevel_volume
    spec = read_gear({"kind": "bevel", "teeth": 20, "mate_teeth": 40, "module_mm": 3, "face_width_mm": 22,
                            "bore_diameter_mm": 12})
    ri, re, rb = spec.toe_cone_distance, spec.cone_distance, 6.0
    g = bevel_geometry(spec)
    # spherical back: the solid angle of teeth and cap times (R_e^3 - R_i^3) / 3, less the bore's
    # cylinder inside the shell, (2 pi / 3)(R^3 - (R^2 - r_b^2)^(3/2)) between R_i and R_e
    def bore(r):
        return 2 * math.pi / 3 * (r ** 3 - (r * r - rb * rb) ** 1.5)
    spherical = gear_solid_angle(spec) * (re ** 3 - ri ** 3) / 3 - (bore(re) - bore(ri))
    assert bevel_volume(spec) == pytest.approx(spherical, rel=1e-12)
    # flat back (the toe sphere in front of it: no web): less the heel ball's cap beyond the plane,
    # pi h^2 (3 R_e - h) / 3, of which the bore had taken the cylinder up to z1 and the cap above z1
    back = re * math.cos(g.root_cone_angle)
    assert back_plane_distance(spec) == pytest.approx(back, rel=1e-15) and ri < back
    assert not bevel_core(spec, "flat").web
    h, z1 = re - back, math.sqrt(re * re - rb * rb)
    cap = math.pi * h * h * (3 * re - h) / 3
    bore_in_cap = math.pi * rb * rb * (z1 - back) + math.pi * (re - z1) ** 2 * (2 * re + z1) / 3
    cap -= bore_in_cap
    assert bevel_volume(spec, "flat") == pytest.approx(spherical - cap, rel=1e-12)
    with pytest.raises(DesignError, match="back"):
        bevel_volume(spec, "conical")


def test_refusals_are_named():
    with pytest.raises(DesignError, match="gear.face_width_mm"):
        read_gear({"kind": "bevel", "teeth": 20, "mate_teeth": 40, "module_mm": 3, "face_width_mm": 60})
    with pytest.raises(DesignError, match="shaft_angle"):  # the gear's cone beyond 90 deg: internal bevel
        BevelGearSpec(teeth=40, mate_teeth=10, module=1, face_width=3, shaft_angle=150 * DEG)
    # z1 = 8, z2 = 40: the equivalent pair's gear tip reaches past the pinion's interference point
    with pytest.raises(GeometryError, match="interference"):
        check_tooth(BevelGearSpec(teeth=8, mate_teeth=40, module=1, face_width=3))
    # 15 / 30 at 20 deg (z_v = 16.8, just under the rack's 17.1): the mate clears the base cone
    check_tooth(BevelGearSpec(teeth=15, mate_teeth=30, module=1, face_width=3))
    spec = BevelGearSpec(teeth=20, mate_teeth=40, module=3, face_width=25)
    assert spec.warnings and "third" in spec.warnings[0]


@pytest.mark.parametrize("z1, z2, sigma_deg", [(20, 40, 90), (15, 30, 90), (17, 29, 60), (16, 25, 110)])
def test_spherical_contact_ratio_is_near_the_back_cone_estimate(z1, z2, sigma_deg):
    # the spherical pair's own path of contact (great circle of action between the tip cones) against
    # Tredgold's back-cone equivalent spur pair: the approximation is good to a few tenths of a percent
    # for these proportions (measured 0.05-0.25 %), never exact
    from geargen.families.bevel.geometry import spherical_contact_ratio
    spec = BevelGearSpec(teeth=z1, mate_teeth=z2, module=3, face_width=10, shaft_angle=sigma_deg * DEG)
    sph, tredgold = spherical_contact_ratio(spec), virtual_contact_ratio(spec)
    assert sph == pytest.approx(tredgold, rel=5e-3)
    assert sph != pytest.approx(tredgold, rel=1e-5)
