"""Rack geometry and the rack-and-pinion closed forms (geargen.families.rack.geometry, geargen.families.rack.spec)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from geargen.core.geometry import GearPair, mesh_geometry
from geargen.families.rack.geometry import (centre_offset_for_backlash, normal_section_area_per_pitch, rack_outline,
                               rack_pinion_geometry, transverse_section_area)
from geargen.design.gear import GearSpec
from geargen.families.registry import read_gear
from geargen.families.rack.spec import RackSpec, rack_from_table
from geargen.errors import DesignError

A20 = math.radians(20)


def rack(**kw) -> RackSpec:
    base = dict(teeth=10, module=2.0, pressure_angle=A20, face_width=20.0, pitch_line_height=12.0)
    return RackSpec(**{**base, **kw})


def _polygon_area(outline, height: float) -> float:
    """Shoelace area of one pitch of the outline, arcs walked densely (independent of the closed form)."""
    pts = []
    for seg in outline.vertices():
        if seg[0] == "line":
            pts.append(seg[1])
        else:
            (x0, u0), (x1, u1), (cx, cu), r = seg[1:]
            a0, a1 = math.atan2(u0 - cu, x0 - cx), math.atan2(u1 - cu, x1 - cx)
            a1 += -2 * math.pi if a1 - a0 > math.pi else 2 * math.pi if a0 - a1 > math.pi else 0.0
            t = np.linspace(a0, a1, 200001)[:-1]
            pts.extend(zip(cx + r * np.cos(t), cu + r * np.sin(t)))
    pts.append(outline.vertices()[-1][2])
    p = np.array([(x, u + height) for x, u in pts] + [(outline.pitch / 2, 0.0), (-outline.pitch / 2, 0.0)])
    return 0.5 * abs(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]))


@pytest.mark.parametrize("kw", [dict(), dict(tip_rounding="generating"), dict(root_fillet_coefficient=0.0),
                                dict(tip_rounding="generating", tip_radius_coefficient=0.2, helix_angle=0.4,
                                     thinning=0.05, pressure_angle=math.radians(25))])
def test_section_area_closed_form_against_the_outline_polygon(kw):
    spec = rack(**kw)
    o = rack_outline(spec)
    # 200000 chords per arc: the polygon's area deficit is ~r^2 theta^3 / 12 / n^2, below 1e-12 mm^2
    assert normal_section_area_per_pitch(spec) == pytest.approx(_polygon_area(o, spec.pitch_line_height), rel=1e-11)
    assert transverse_section_area(spec) == pytest.approx(
        spec.teeth * normal_section_area_per_pitch(spec) / math.cos(spec.helix_angle), rel=1e-15)


def test_outline_is_a_graph_both_ways_and_tangent_at_the_joints():
    spec = rack(tip_rounding="generating", thinning=0.03)
    o = rack_outline(spec)
    u = np.linspace(-spec.dedendum, spec.addendum, 2001)[1:-1]
    assert np.max(np.abs(o.height_at(o.space_half_width(u)) - u)) < 1e-12
    # at the tangent points the arcs meet the flank line
    for uj in (o.flank_root_u, o.flank_tip_u):
        assert o.space_half_width(np.array([uj - 1e-9, uj + 1e-9])) == pytest.approx(o.flank_x([uj, uj]), abs=1e-8)
    # tooth thickness at the pitch line: pi m / 2 - normal thinning
    assert o.pitch - 2 * o.space_half_width(0.0) == pytest.approx(math.pi * 2 / 2 - 0.03, abs=1e-14)


def test_rack_and_pinion_backlash_closed_form():
    # j_t = T_rack + T_pinion + 2 dy tan(alpha_t) (derivation in geargen.families.rack.geometry); alpha_t of a 20 deg
    # normal, 15 deg helix: tan(alpha_t) = tan 20 / cos 15 = 0.376801...
    beta = math.radians(15)
    r = rack(helix_angle=beta, thinning=0.01)
    p = GearSpec(teeth=17, module=2.0, pressure_angle=A20, face_width=20.0, helix_angle=beta, thinning=0.02)
    g0 = rack_pinion_geometry(r, p)
    g1 = rack_pinion_geometry(r, p, 0.1)
    assert g0.backlash_circumferential == pytest.approx(0.03, abs=1e-15)
    assert g1.backlash_circumferential - g0.backlash_circumferential == pytest.approx(
        2 * 0.1 * math.tan(A20) / math.cos(beta), rel=1e-14)
    assert centre_offset_for_backlash(r, p, g1.backlash_circumferential) == pytest.approx(0.1, rel=1e-12)
    # centre height: r + x m + dy; pitch r = z m_n / (2 cos beta)
    assert g1.centre_height == pytest.approx(17 * 2 / (2 * math.cos(beta)) + 0.1, rel=1e-15)
    assert g1.travel_per_revolution == pytest.approx(math.pi * 17 * 2 / math.cos(beta), rel=1e-15)


@pytest.mark.parametrize("teeth,shift", [(20, 0.0), (14, 0.3), (30, -0.2)])
def test_contact_ratio_is_the_limit_of_a_growing_gear(teeth, shift):
    """A rack is the limit of an external gear whose tooth count grows (same basic rack, ha* = 1):
    the pair contact ratio of geargen.core.geometry (independent code) tends to the rack's as a
    series in 1/z2; Richardson's extrapolation from z2 = 500, 1000, 2000 (removing the 1/z2 and
    1/z2^2 terms) leaves a few 1e-6."""
    pin = GearSpec(teeth=teeth, module=1.0, pressure_angle=A20, face_width=10.0, profile_shift=shift)
    eps = {}
    for z2 in (500, 1000, 2000):
        big = GearSpec(teeth=z2, module=1.0, pressure_angle=A20, face_width=10.0)
        eps[z2] = mesh_geometry(GearPair(pin, big)).transverse_contact_ratio
    first, second = 2 * eps[1000] - eps[500], 2 * eps[2000] - eps[1000]
    limit = (4 * second - first) / 3
    r = RackSpec(teeth=10, module=1.0, pressure_angle=A20, face_width=10.0, pitch_line_height=5.0)
    got = rack_pinion_geometry(r, pin).contact_ratio_transverse
    assert got == pytest.approx(limit, abs=1e-5)
    if teeth == 20 and shift == 0:
        # by hand: (sqrt(11^2 - (10 cos 20)^2) - 10 sin 20 + 1 / sin 20) / (pi cos 20) = 1.7689
        assert got == pytest.approx(1.7689, abs=1e-4)


def test_small_pinion_on_a_rack_is_named_involute_interference():
    # z = 12 < 2 / sin^2(20 deg) = 17.1: the rack's flank reaches past the pinion's interference point
    pin = GearSpec(teeth=12, module=1.0, pressure_angle=A20, face_width=10.0)
    r = RackSpec(teeth=10, module=1.0, pressure_angle=A20, face_width=10.0, pitch_line_height=5.0)
    assert "involute" in rack_pinion_geometry(r, pin).interference
    pin18 = GearSpec(teeth=18, module=1.0, pressure_angle=A20, face_width=10.0)
    assert rack_pinion_geometry(r, pin18).interference == ()


def test_pinion_must_match_the_rack():
    r = rack(helix_angle=0.3)
    with pytest.raises(DesignError) as e:
        rack_pinion_geometry(r, GearSpec(teeth=17, module=2.0, pressure_angle=A20, face_width=20.0, helix_angle=0.3,
                                         hand="left"))
    assert e.value.field == "pinion.hand"
    with pytest.raises(DesignError) as e:
        rack_pinion_geometry(r, GearSpec(teeth=17, module=2.5, pressure_angle=A20, face_width=20.0, helix_angle=0.3))
    assert e.value.field == "pinion.module"


def test_table_reader_and_its_errors():
    t = {"kind": "rack", "module_mm": 2, "teeth": 30, "face_width_mm": 20}
    spec = read_gear(t)  # the gear reader hands a rack table to the rack's reader
    assert isinstance(spec, RackSpec) and spec.back_height == pytest.approx(4.0)  # default 2 modules
    assert spec.length == pytest.approx(30 * math.pi * 2)
    assert spec.root_fillet_coefficient == 0.38 and spec.tip_radius_coefficient == 0.0
    by_length = rack_from_table({**{k: v for k, v in t.items() if k != "teeth"}, "length_mm": 30 * math.pi * 2})
    assert by_length.teeth == 30
    with pytest.raises(DesignError) as e:
        rack_from_table({**{k: v for k, v in t.items() if k != "teeth"}, "length_mm": 100})
    assert e.value.field == "gear.length_mm" and "94.2477796" in e.value.allowed
    with pytest.raises(DesignError) as e:
        rack_from_table({**t, "addendum_coefficient": 1.5, "thinning_normal_mm": 1.0})
    assert e.value.field == "gear.addendum_coefficient"
    with pytest.raises(DesignError) as e:
        rack_from_table({**t, "tip_rounding": "generating", "tip_radius_coefficient": 0.9})
    # largest tip arc: tip half-land (pi/4 - tan 20) m over (1 - sin 20) / cos 20, over m = 0.601861
    assert e.value.field == "gear.tip_radius_coefficient" and "0.601861" in e.value.allowed
    with pytest.raises(DesignError) as e:
        rack_from_table({**t, "thinning_circumferential_mm": 2.0})
    assert e.value.field == "gear.thinning_circumferential_mm"
    with pytest.raises(DesignError) as e:  # normal: a quarter of the normal pitch, pi m / 4 = 1.5708 mm at 0 deg
        rack_from_table({**t, "thinning_normal_mm": 2.0, "helix_angle_deg": 30})
    assert e.value.field == "gear.thinning_normal_mm" and e.value.allowed.startswith("[0, 1.5708]")
    with pytest.raises(DesignError) as e:
        rack_from_table({**t, "back_height_mm": 2, "pitch_line_height_mm": 9})
    assert e.value.field == "gear.back_height"
    with pytest.raises(DesignError) as e:
        rack_from_table({**t, "pitch_line_height_mm": 2})  # below the root line
    assert e.value.field == "gear.pitch_line_height_mm"
    full = rack()
    largest = full.max_root_fillet_coefficient(0.0)
    assert rack(root_fillet_coefficient=largest).root_fillet_coefficient == largest  # the full radius: no land
    with pytest.raises(DesignError) as e:  # a land of ~1e-7 mm: below what the kernel can build
        rack(root_fillet_coefficient=largest * (1 - 1e-7))
    assert e.value.field == "root_fillet_coefficient" and "root land" in e.value.problem
    inch = rack_from_table({"kind": "rack", "diametral_pitch_per_in": 16, "teeth": 12, "face_width_in": 0.5})
    assert inch.length_unit == "in" and inch.module == pytest.approx(25.4 / 16)
