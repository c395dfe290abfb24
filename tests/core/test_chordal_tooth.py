"""Chordal tooth thickness and height (issue 27: the dimension a shop measures with a gear-tooth
caliper on fine-pitch gears), against KHK's worked example and the allowance's limits."""

from __future__ import annotations

import math

import pytest

from geargen.core.allowance import ThicknessAllowance, thickest, thinnest
from geargen.core.geometry import chordal_tooth
from geargen.design.gear import GearSpec
from geargen.model.gear_data import gear_data
from geargen.profile.tooth import tooth_profile

DEG = math.pi / 180


def test_khk_spur_example():
    # KHK Technical Reference, chordal tooth thickness of a profile-shifted spur gear: m 10, z 12,
    # alpha 20 deg, x +0.3, h_a = 13.000: psi = 90/z + 360 x tan(alpha) / (pi z) (deg),
    # s_c = z m sin(psi), h_c = h_a + z m / 2 (1 - cos(psi)) = 13.6657 (printed to 4 decimals)
    spec = GearSpec(teeth=12, module=10.0, pressure_angle=20 * DEG, face_width=20.0, profile_shift=0.3)
    psi = (90 / 12 + 360 * 0.3 * math.tan(20 * DEG) / (math.pi * 12)) * DEG
    chord = chordal_tooth(spec)
    assert spec.tip_radius - spec.reference_radius == pytest.approx(13.0, abs=1e-12)
    assert chord.thickness == pytest.approx(120 * math.sin(psi), rel=1e-12)  # the same closed form
    assert chord.height == pytest.approx(13.6657, abs=5e-5)  # KHK's printed value, 4 decimals


def test_helical_gear_is_measured_on_its_virtual_spur_gear():
    # the normal section's virtual gear: z_v = z / cos^3(beta), d_v = z_v m_n; s_n = m_n (pi/2 + 2 x_n tan alpha_n)
    m, z, x, beta = 2.0, 30, 0.2, 20 * DEG
    spec = GearSpec(teeth=z, module=m, pressure_angle=20 * DEG, face_width=20.0, helix_angle=beta, hand="right",
                    profile_shift=x)
    z_v = z / math.cos(beta) ** 3
    s_n = m * (math.pi / 2 + 2 * x * math.tan(20 * DEG))
    psi = s_n / (z_v * m)
    chord = chordal_tooth(spec)
    assert chord.virtual_diameter == pytest.approx(z_v * m, rel=1e-12)
    assert chord.thickness == pytest.approx(z_v * m * math.sin(psi), rel=1e-12)
    assert chord.height == pytest.approx(m * (1 + x) + z_v * m / 2 * (1 - math.cos(psi)), rel=1e-12)


def test_the_limits_are_the_thinnest_and_thickest_teeth_chords():
    spec = GearSpec(teeth=21, module=1.0, pressure_angle=20 * DEG, face_width=5.0)
    allowance = ThicknessAllowance(-0.054, -0.084)  # DIN 3967 cd25 at d 21 mm
    data = gear_data(spec, tooth_profile(spec, warn=False), allowance)
    lo, hi = data["chordal_tooth"]["limits"]
    assert lo == pytest.approx(chordal_tooth(thinnest(spec, allowance)).thickness, rel=1e-12)
    assert hi == pytest.approx(chordal_tooth(thickest(spec, allowance)).thickness, rel=1e-12)
    # d s_c / d s_n = cos(psi): each limit moves by the deviation times cos(psi), psi = s_n / d
    # (psi = 0.0748 rad here: 0.28 % less than the deviation); 1e-5 mm bounds the second-order term
    # E^2 sin(psi) / (2 d) (5.2e-6 mm for E = 54 um, 1.3e-5 for 84 um)
    nominal = chordal_tooth(spec).thickness
    cos_psi = math.cos(math.pi / 2 / 21)
    assert hi - nominal == pytest.approx(-0.054 * cos_psi, abs=1e-5)
    assert lo - nominal == pytest.approx(-0.084 * cos_psi, abs=2e-5)
