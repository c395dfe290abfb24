"""Mass properties from the solids (geargen.cad.mass) against closed forms and the exact outline."""

import math

import numpy as np
import pytest

from geargen.cad import parts as P
from geargen.cad.gear_solid import build_gear
from geargen.cad.mass import mass_properties
from geargen.design.gear import gear_from_table
from geargen.model.mass import polygon_moments
from geargen.profile.segments import sample_outline

STEEL = 7850.0


def test_plain_disc_against_closed_form():
    """Disc d 80, 12 thick: m = rho pi r^2 h, J = m r^2 / 2 (well within the 0.1 % asked)."""
    m = mass_properties(P.cylinder(80.0, 12.0), eps=1e-4)
    mass = STEEL * math.pi * 0.04 ** 2 * 0.012
    assert m.mass(STEEL) == pytest.approx(mass, rel=1e-9)
    assert m.inertia(STEEL) == pytest.approx(mass * 0.04 ** 2 / 2, rel=1e-9)
    assert m.off_axis < 1e-9


def test_hollow_shaft_against_closed_form():
    """Tube d 30 / bore 18, 150 long: J = m (r_o^2 + r_i^2) / 2."""
    m = mass_properties(P.cylinder(30.0, 150.0, 18.0), eps=1e-4)
    mass = STEEL * math.pi * (0.015 ** 2 - 0.009 ** 2) * 0.150
    assert m.mass(STEEL) == pytest.approx(mass, rel=1e-9)
    assert m.inertia(STEEL) == pytest.approx(mass * (0.015 ** 2 + 0.009 ** 2) / 2, rel=1e-9)


@pytest.mark.slow
def test_gear_inertia_against_its_exact_outline():
    """Independent geometry: a spur gear's axial moment is the polar moment of its exact transverse
    outline (a 0.5 um polygon of the analytic segments) times the face width, less the bore."""
    spec = gear_from_table({"module_mm": 1.0, "teeth": 40, "face_width_mm": 8.0, "pressure_angle_deg": 20.0,
                            "bore_diameter_mm": 10.0}, where="g", name="g", length_unit="mm")
    solid = build_gear(spec)
    outline = sample_outline(solid.profile.outline(), 5e-4)
    expected = (abs(polygon_moments(outline)[1]) - math.pi * 5.0 ** 4 / 2) * spec.face_width
    m = mass_properties(solid.shape, eps=1e-4)
    assert m.axial_moment == pytest.approx(expected, rel=1e-5)
    assert m.off_axis < 1e-4  # 0.1 um: the integration at eps 1e-4
