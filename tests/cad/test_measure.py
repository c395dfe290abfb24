"""Measurements on a solid's section against the closed forms of geargen.core.geometry."""

import math

import numpy as np
import pytest

from geargen.cad.gear_solid import build_gear
from geargen.cad.measure import (boolean_section, flank_deviation, involute_deviation, over_balls_on_section,
                                 section, span_on_section)

geometry = pytest.importorskip("geargen.core.geometry")

pytestmark = pytest.mark.slow

UM = 1e-3  # mm

CASES = {
    # name: (teeth, helix deg, shift, thinning mm)
    "spur even (bench)": None,
    "spur odd": (21, 0.0, 0.25, 0.0),
    "helical odd (bench)": None,
    "helical even, left, thinned": (20, 30.0, -0.2, 0.01),
}


@pytest.fixture(params=list(CASES))
def gear(request, spur112, helical21, make_spec):
    name = request.param
    if name == "spur even (bench)":
        return spur112
    if name == "helical odd (bench)":
        return helical21
    teeth, helix, shift, thinning = CASES[name]
    return build_gear(make_spec(teeth, module=1.25, helix=helix, face=10.0, profile_shift=shift,
                                thinning=thinning, hand="left"))


def test_span_and_over_pins_on_the_section_agree_with_the_formulas(gear):
    spec, profile = gear.spec, gear.profile
    z = 0.5 * spec.face_width
    cut = section(gear.shape, z, 128)
    span = geometry.span_measurement(spec)
    measured = span_on_section(gear.shape, profile, span.teeth_spanned, z, cut=cut)
    assert measured.on_involute
    assert measured.normal == pytest.approx(span.span, abs=0.1 * UM)
    assert measured.transverse == pytest.approx(span.transverse_span, abs=0.1 * UM)
    pins = geometry.over_pins_measurement(spec)
    balls = over_balls_on_section(gear.shape, profile, pins.pin_diameter, z, cut=cut)
    assert balls.on_involute
    assert balls.size == pytest.approx(pins.dimension, abs=0.1 * UM)
    assert balls.centre_radius == pytest.approx(pins.centre_radius, abs=0.1 * UM)


def test_the_span_steps_by_one_base_pitch(gear):
    """W(k+1) - W(k) is one transverse base pitch, 2 pi r_b / z: a check free of any formula."""
    spec, profile = gear.spec, gear.profile
    k = geometry.recommended_teeth_spanned(spec)
    z = 0.5 * spec.face_width
    cut = section(gear.shape, z, 128)
    a = span_on_section(gear.shape, profile, k, z, cut=cut)
    b = span_on_section(gear.shape, profile, k + 1, z, cut=cut)
    if not (a.on_involute and b.on_involute):
        pytest.skip("k + 1 teeth do not touch the involute")
    assert b.transverse - a.transverse == pytest.approx(2 * math.pi * profile.base_radius / spec.teeth, abs=0.1 * UM)


def test_boolean_section_agrees(make_spec):
    """OCCT's own boolean section (a different algorithm) sees the same involute flanks."""
    g = build_gear(make_spec(17, helix=15, face=3.0))
    z = 1.3
    pts = boolean_section(g.shape, z, 256)
    rad = np.hypot(pts[:, 0], pts[:, 1])
    p = g.profile
    flank = pts[(rad > p.involute_start_radius + 1e-4) & (rad < p.tip_radius - 1e-4)]
    assert len(flank) > 200
    assert np.max(np.abs(involute_deviation(p, z, flank))) < 0.1 * UM
    assert flank_deviation(g.shape, p, z).max_abs < 0.1 * UM
