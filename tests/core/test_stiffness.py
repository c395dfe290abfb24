"""Component stiffnesses, their combination and reduction (the paper's four facts and Eq. 1), the
preload rules and the preload variation from loop errors, by hand-derived cases."""

import math

import numpy as np
import pytest

from geargen.core import stiffness as st
from geargen.core.drive import TwoPathDrive
from geargen.design.assembly import design_from_dict
from geargen.design.stiffness import QUANTITY_SUFFIXES, StiffnessSpec
from geargen.errors import DesignError


def test_mesh_stiffness_eq1_in_both_unit_systems():
    # steel E = 207 GPa, face 10 mm: 207000 * 10 / 11 N/mm
    assert float(st.mesh_stiffness(207e3, 10.0)) == pytest.approx(188181.8181818, rel=1e-12)
    # the paper's inch form: E = 30e6 psi, w = 1 in gives 30e6/11 lbf/in; the same in N/mm
    e_mpa = 30e6 * QUANTITY_SUFFIXES["stress"]["psi"]
    k = float(st.mesh_stiffness(e_mpa, 25.4))
    assert k == pytest.approx(30e6 / 11 * QUANTITY_SUFFIXES["linear_stiffness"]["lbf_per_in"], rel=1e-12)
    assert np.allclose(st.mesh_stiffness(207e3, np.array([1.0, 2.0])), [207e3 / 11, 414e3 / 11])


def test_series_and_parallel():
    assert st.series(2.0, 3.0) == pytest.approx(1.2, rel=1e-15)  # compliances add
    assert st.series(2.0, math.inf) == pytest.approx(2.0, rel=1e-15)  # a rigid part adds nothing
    assert st.series(4.0, 4.0, 4.0, 4.0) == pytest.approx(1.0, rel=1e-15)
    assert st.parallel(2.0, 3.0) == 5.0  # stiffnesses add
    assert np.allclose(st.series(np.array([2.0, 6.0]), 3.0), [1.2, 2.0])


def test_reflection_through_a_ratio_by_virtual_work():
    # A torsional spring k on a shaft geared R:1 to the output: output rotation th turns the shaft
    # R th, stores 1/2 k (R th)^2, so the output sees k R^2.
    k, R, th = 250.0, 16.0, 1e-4
    energy = 0.5 * k * (R * th) ** 2
    assert float(st.reflect(k, R)) == pytest.approx(2 * energy / th ** 2, rel=1e-12)
    assert float(st.reflect(st.reflect(k, R), 1 / R)) == pytest.approx(k, rel=1e-15)


def test_linear_stiffness_at_a_radius():
    # a spring k at radius r: rotation th stretches it r th, the force k r th gives torque k r^2 th
    k, r, th = 1000.0, 10.0, 1e-3
    assert float(st.torsional_from_linear(k, r)) == pytest.approx(k * r * th * r / th, rel=1e-15)
    assert float(st.linear_from_torsional(st.torsional_from_linear(k, r), r)) == pytest.approx(k, rel=1e-15)


def test_shaft_torsion_by_hand():
    # d 10 mm, L 100 mm, G 80 GPa: G pi d^4 / (32 L)
    assert st.shaft_torsional_stiffness(80e3, 10.0, 100.0) == pytest.approx(80e3 * math.pi * 1e4 / 3200, rel=1e-14)
    hollow = st.shaft_torsional_stiffness(80e3, 10.0, 100.0, bore=6.0)
    assert hollow == pytest.approx(80e3 * math.pi * (1e4 - 6.0 ** 4) / 3200, rel=1e-14)


def test_shaft_bending_mid_span_by_hand():
    ei = 207e3 * math.pi * 8.0 ** 4 / 64
    assert st.shaft_bending_stiffness(207e3, 8.0, 60.0, 30.0) == pytest.approx(48 * ei / 60 ** 3, rel=1e-14)
    assert st.shaft_bending_stiffness(207e3, 8.0, 60.0, 30.0, "fixed") == pytest.approx(192 * ei / 60 ** 3, rel=1e-14)


# --- preload ------------------------------------------------------------------------------------

def test_paper_preload_rules():
    assert st.required_preload(10.0, "type2") == 5.0  # at least half the maximum load
    assert st.required_preload(10.0, "type1") == 10.0  # the maximum load


@pytest.mark.parametrize("kind, k1, k2, k3", [("type2", 5.0, 5.0, 0.1), ("type2", 8.0, 2.0, 1.0),
                                             ("type1", 9.0, 1.0, math.inf), ("type1", 1.0, 1.0, math.inf)])
def test_preload_to_carry_makes_a_path_unload_exactly_at_the_max_load(kind, k1, k2, k3):
    t_max = 7.0
    p = st.preload_to_carry(t_max, kind, k1, k2, k3)
    d = TwoPathDrive(kind, k1, k2, p, k3)
    t_lo, t_hi = d.unloading_torques
    assert min(-t_lo, t_hi) == pytest.approx(t_max, rel=1e-12)
    if kind == "type2" and k1 == k2:
        assert p == pytest.approx(t_max / 2, rel=1e-14)  # the paper's rule is exact for equal paths
    if kind == "type1":
        # stiff path 1 unloads first, at -(k1 + k2) P / k1: the paper's rule P = T is conservative
        assert p == pytest.approx(t_max * max(k1, k2) / (k1 + k2), rel=1e-14)
        assert p <= st.required_preload(t_max, "type1")


def test_preload_variation_band():
    d = TwoPathDrive("type2", 1000.0, 1000.0, 50.0, 10.0)
    v = st.preload_variation(d, 0.8, "x")
    assert v.range == pytest.approx(d.loop_stiffness * 0.8, rel=1e-15)  # dF_L = k_L delta_L
    assert (v.low, v.high) == pytest.approx((50.0 - v.range / 2, 50.0 + v.range / 2), rel=1e-15)
    assert v.relative == pytest.approx(v.range / 50.0, rel=1e-15) and not v.unloads
    assert st.preload_variation(d, 100.0).unloads


def test_carriage_spring_as_k3_by_energy_and_force():
    # A carriage x turns the paths +/- lambda x. With rigid paths a carriage travel dx must change
    # the spring force by k_c dx: check k3 = k_c / lambda^2, delta_L = 2 lambda dx, F_e = 2 lambda P.
    lam, kc, dx, p = 0.0105, 13.5, 0.24, 3000.0
    k3 = float(st.preload_spring_at_output(kc, lam))
    assert 0.5 * k3 * (lam * dx) ** 2 == pytest.approx(0.5 * kc * dx ** 2, rel=1e-14)  # same stored energy
    d = TwoPathDrive("type2", 1e15, 1e15, p, k3)
    v = st.preload_variation(d, float(st.loop_error_from_carriage_travel(dx, lam)))
    assert float(st.carriage_force(v.range, lam)) == pytest.approx(kc * dx, rel=1e-9)
    # F_e from the preload: each path's torque P needs P / (R2 r_b2) = lambda P on each mesh-1 flank
    assert float(st.carriage_force(p, lam)) == pytest.approx(2 * lam * p, rel=1e-15)


def test_preload_lever_geometry():
    design = design_from_dict({
        "drive": {"type": "type2", "preload": "radial"},
        "gear_defaults": {"module_mm": 1.0, "pressure_angle_deg": 20, "face_width_mm": 5},
        "gears": {"input": {"teeth": 20}, "cluster_large": {"teeth": 60}, "cluster_small": {"teeth": 15},
                  "output": {"teeth": 90}}})
    train = st.train_from_design(design, StiffnessSpec())
    assert train.ratio == pytest.approx(18.0, rel=1e-15)
    # carriage x along the line of action turns the large gear x / r_b2, the output x / (r_b2 R2)
    r_b2 = 30.0 * math.cos(math.radians(20))
    assert st.preload_lever(train, "radial") == pytest.approx(1 / (r_b2 * 6.0), rel=1e-14)
    assert st.preload_lever(train, "radial", math.radians(10)) == pytest.approx(math.cos(math.radians(10)) / (r_b2 * 6), rel=1e-14)
    with pytest.raises(DesignError):
        st.preload_lever(train, "axial")  # a spur input cannot preload axially
