"""ISO 6336-1:2019 method B tooth stiffness (geargen.core.iso6336) against the published worked
example, a spur pair worked by hand from the standard's equations, and the limits of its factors."""

import math

import pytest

from geargen.core import iso6336 as iso
from geargen.core.geometry import GearPair, mesh_geometry
from geargen.design.gear import gear_from_table
from geargen.errors import DesignError

DEG = math.pi / 180


def _gear(teeth, shift, hand="right", helix=0.0, module=8.0, dedendum=1.25, face=100.0):
    return gear_from_table({"teeth": teeth, "module_mm": module, "pressure_angle_deg": 20, "helix_angle_deg": helix,
                            "hand": hand, "profile_shift": shift, "face_width_mm": face,
                            "dedendum_coefficient": dedendum}, where="t", name=f"z{teeth}", length_unit="mm")


def _tr_example_1():
    """ISO/TR 6336-30:2017 example 1 inputs: m_n 8 mm, alpha_n 20 deg, z 17/103, b 100 mm, x 0.145/0,
    beta 15.8 deg, a_w 500 mm; basic rack h_fP = 1.4 m_n (ISO 53 profile D, as the example's rack)."""
    pinion = _gear(17, 0.145, "right", 15.8, dedendum=1.4)
    wheel = _gear(103, 0.0, "left", 15.8, dedendum=1.4)
    return GearPair(pinion, wheel)


# The published values of ISO/TR 6336-30:2017 Annex A, example 1 (single helical carburized pair), as
# tabulated in the "Reference" column of MATISO_6336.example_01 in github.com/gfsReboucas/Drivetrain
# (MATISO_6336.m: z_n1 18.905, z_n2 114.543, c'_th 17.85584, c' 12.37047, c_gamma_alpha 17.46485,
# c_gamma_beta 14.84512 N/(mm um)). Its load F_t K_A / b = 127352 N / 100 mm is above 100 N/mm: no
# load correction; steel (E = E_st); solid discs.
PUBLISHED = {"z_n1": 18.905, "z_n2": 114.543, "c_th": 17.85584, "c_prime": 12.37047, "c_gamma_alpha": 17.46485,
             "c_gamma_beta": 14.84512}


def test_tr_6336_30_example_1_against_the_published_values():
    r = iso.pair_stiffness(_tr_example_1(), centre_distance=500.0, face_width=100.0,
                           elastic_modulus=iso.STEEL_MODULUS, specific_load=127352.0 / 100.0)
    assert r.virtual_teeth[0] == pytest.approx(PUBLISHED["z_n1"], rel=1e-4)
    assert r.virtual_teeth[1] == pytest.approx(PUBLISHED["z_n2"], rel=1e-4)
    assert r.theoretical_single_stiffness == pytest.approx(PUBLISHED["c_th"], rel=1e-3)
    assert r.single_stiffness == pytest.approx(PUBLISHED["c_prime"], rel=1e-3)
    # c_gamma depends on eps_alpha too (here 1.5493 from the tips as built at a_w 500 mm): the 1 %
    assert r.mesh_stiffness == pytest.approx(PUBLISHED["c_gamma_alpha"], rel=1e-2)
    assert r.mesh_stiffness_beta == pytest.approx(PUBLISHED["c_gamma_beta"], rel=1e-2)
    assert r.load_factor == 1.0 and r.gear_blank_factor == 1.0 and r.warnings == ()
    # the whole mesh: c_gamma_alpha b, N/um, and in the stiffness model's N/mm
    assert r.mesh_stiffness_whole == pytest.approx(r.mesh_stiffness * 100.0, rel=1e-15)
    assert r.line_of_action_stiffness == pytest.approx(r.mesh_stiffness * 100.0e3, rel=1e-15)


def test_spur_pair_worked_by_hand():
    # z 20/40, m 2 mm, alpha 20 deg, x 0/0, h_fP 1.25 m, spur: z_n = z, and from the standard's
    # equations written out here: q' = C1 + C2/20 + C3/40 (the shift terms vanish)
    q = 0.04723 + 0.15551 / 20 + 0.25791 / 40
    assert q == pytest.approx(0.06145325, abs=1e-12)
    c_th = 1 / q
    c_b = 1 + 0.5 * (1.2 - 1.25)  # 20 deg rack: the second bracket is 1
    c_prime = c_th * 0.8 * 1.0 * c_b * 1.0  # C_M C_R C_B cos(0)
    # eps_alpha of the standard pair by hand: (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a sin(alpha)) / p_bt
    a20 = 20 * DEG
    rb1, rb2 = 20 * math.cos(a20), 40 * math.cos(a20)
    eps = (math.sqrt(22 ** 2 - rb1 ** 2) + math.sqrt(42 ** 2 - rb2 ** 2) - 60 * math.sin(a20)) / (2 * math.pi * math.cos(a20))
    r = iso.pair_stiffness(GearPair(_gear(20, 0, module=2.0), _gear(40, 0, module=2.0)))
    assert r.virtual_teeth == pytest.approx((20.0, 40.0), rel=1e-15)
    assert r.flexibility == pytest.approx(q, rel=1e-14)
    assert r.theoretical_single_stiffness == pytest.approx(16.272532, rel=1e-7)  # 1 / 0.06145325
    assert r.basic_rack_factor == pytest.approx(0.975, rel=1e-15)
    assert r.transverse_contact_ratio == pytest.approx(eps, rel=1e-12)
    assert r.single_stiffness == pytest.approx(c_prime, rel=1e-12)
    assert r.mesh_stiffness == pytest.approx(c_prime * (0.75 * eps + 0.25), rel=1e-12)
    assert r.mesh_stiffness_beta == pytest.approx(0.85 * r.mesh_stiffness, rel=1e-15)


def test_the_pinion_is_the_gear_with_fewer_teeth_whatever_the_order():
    a = iso.iso6336_stiffness((17, 103), (0.145, 0.0), 8.0, 20 * DEG, 15.8 * DEG, 1.55)
    b = iso.iso6336_stiffness((103, 17), (0.0, 0.145), 8.0, 20 * DEG, 15.8 * DEG, 1.55)
    assert (a.pinion, b.pinion) == (1, 2)
    assert b.single_stiffness == a.single_stiffness and b.virtual_teeth == a.virtual_teeth


def test_gear_blank_factor_limits_and_thin_rims():
    # a web as wide as the face: ln(1) = 0, C_R = 1 whatever the rim
    assert iso.gear_blank_factor(20.0, 2.0, 20.0, 3.0)[0] == 1.0
    # the standard's corner: b_s/b = 0.2, s_R/m_n = 1: 1 + ln(0.2) / (5 e^0.2)
    assert iso.gear_blank_factor(20.0, 2.0, 4.0, 2.0)[0] == pytest.approx(1 + math.log(0.2) / (5 * math.exp(0.2)),
                                                                           rel=1e-15)
    assert iso.gear_blank_factor(20.0, 2.0, 4.0, 2.0)[0] == pytest.approx(0.736461, abs=1e-6)
    # thinner webs and thinner rims make the blank softer, monotonically
    webs = [iso.gear_blank_factor(20.0, 2.0, w, 4.0)[0] for w in (4.0, 8.0, 12.0, 16.0, 20.0)]
    rims = [iso.gear_blank_factor(20.0, 2.0, 8.0, s)[0] for s in (2.0, 4.0, 8.0, 16.0, 32.0)]
    assert all(x < y for x, y in zip(webs, webs[1:])) and all(x < y for x, y in zip(rims, rims[1:]))
    assert rims[-1] > 0.99  # a very thick rim: close to a solid disc
    # outside the range the standard clamps (b_s/b to 0.2, s_R/m_n to 1) and says so
    thin_web, notes = iso.gear_blank_factor(20.0, 2.0, 1.0, 2.0)
    assert thin_web == iso.gear_blank_factor(20.0, 2.0, 4.0, 2.0)[0] and "b_s/b" in notes[0]
    thin_rim, notes = iso.gear_blank_factor(20.0, 2.0, 4.0, 0.5)
    assert thin_rim == iso.gear_blank_factor(20.0, 2.0, 4.0, 2.0)[0] and "s_R/m_n" in notes[0]
    # through the pair: c' scales by C_R
    solid = iso.iso6336_stiffness((20, 40), (0, 0), 2.0, 20 * DEG, 0.0, 1.6, face_width=20.0)
    webbed = iso.iso6336_stiffness((20, 40), (0, 0), 2.0, 20 * DEG, 0.0, 1.6, face_width=20.0, web_thickness=4.0,
                                   rim_thickness=2.0)
    assert webbed.single_stiffness / solid.single_stiffness == pytest.approx(0.736461, abs=1e-6)


def test_load_correction_only_below_100_N_per_mm_and_only_when_given():
    assert iso.load_factor(None) == 1.0
    assert iso.load_factor(100.0) == 1.0 and iso.load_factor(500.0) == 1.0
    assert iso.load_factor(50.0) == pytest.approx(0.5 ** 0.25, rel=1e-15)
    assert iso.load_factor(99.999) == pytest.approx(1.0, abs=1e-5)  # continuous at 100 N/mm
    with pytest.raises(DesignError) as e:
        iso.load_factor(0.0)
    assert e.value.field == "specific_load"


def test_material_factor_of_a_non_steel_pair():
    assert iso.material_factor(206e3, 206e3) == 1.0
    # aluminium (70 GPa) on steel: E = 2 E1 E2 / (E1 + E2)
    assert iso.material_factor(70e3, 206e3) == pytest.approx(2 * 70 * 206 / (70 + 206) / 206, rel=1e-15)
    steel = iso.iso6336_stiffness((20, 40), (0, 0), 2.0, 20 * DEG, 0.0, 1.6)
    alu = iso.iso6336_stiffness((20, 40), (0, 0), 2.0, 20 * DEG, 0.0, 1.6, elastic_moduli=(70e3, 70e3))
    assert alu.single_stiffness / steel.single_stiffness == pytest.approx(70 / 206, rel=1e-14)


def test_outside_the_fitted_range_warns_and_unevaluable_input_is_refused():
    r = iso.iso6336_stiffness((20, 40), (-0.3, 0.4), 2.0, 20 * DEG, 0.0, 1.1)
    text = " ".join(r.warnings)
    assert "x1 >= x2" in text and "eps_alpha >= 1.2" in text
    assert math.isfinite(r.mesh_stiffness) and r.mesh_stiffness > 0  # the standard still gives a value
    r = iso.iso6336_stiffness((20, 40), (1.5, 1.0), 2.0, 20 * DEG, 0.0, 1.3)
    assert any("x1 + x2" in w for w in r.warnings)
    with pytest.raises(DesignError) as e:
        iso.iso6336_stiffness((20, 40), (0, 0), 2.0, 20 * DEG, 0.0, 0.0)
    assert e.value.field == "transverse_contact_ratio"
    with pytest.raises(DesignError) as e:
        iso.iso6336_stiffness((20, 40), (0, 0), 2.0, 20 * DEG, 0.0, 1.5, web_thickness=4.0, rim_thickness=2.0)
    assert e.value.field == "face_width"


def test_eps_alpha_is_the_pair_geometry_at_the_centre_distance_given():
    pair = _tr_example_1()
    r = iso.pair_stiffness(pair, centre_distance=500.0)
    assert r.transverse_contact_ratio == mesh_geometry(pair, 500.0).transverse_contact_ratio
