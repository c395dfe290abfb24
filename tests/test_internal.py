"""Internal (ring) gears: the pair geometry against a published table, the ring's exact outline,
and each named internal-pair check against an independent numeric mesh on the exact outlines."""

from __future__ import annotations

import math

import numpy as np
import pytest

from geargen.families.internal.pair import (RingMaterial, check_internal, free_play, involute_margin, overlap_depth,
                                          radial_assembly_margin, tip_margin, trochoid_margin, undercut_recess)
from geargen.families.internal.geometry import internal_pair_geometry
from geargen.core.involute import involute
from geargen.design.gear import GearSpec
from geargen.errors import DesignError
from geargen.families.internal.data import between_pins, internal_gear_data, reference_pin_diameter
from geargen.families.internal.spec import InternalGearSpec
from geargen.families.registry import read_gear
from geargen.profile.internal import internal_profile
from geargen.profile.segments import sample_outline
from geargen.profile.tooth import tooth_profile

A20 = math.radians(20)


def pinion(z, x=0.0, m=1.0, **kw):
    return GearSpec(teeth=z, module=m, pressure_angle=A20, face_width=5.0, profile_shift=x, **kw)


def ring(z, x=0.0, m=1.0, **kw):
    return InternalGearSpec(teeth=z, module=m, pressure_angle=A20, face_width=5.0, profile_shift=x, **kw)


def pair_parts(z1, x1, z2, x2, m=1.0, ring_kw=None, pinion_kw=None, centre_distance=None):
    p, r = pinion(z1, x1, m, **(pinion_kw or {})), ring(z2, x2, m, **(ring_kw or {}))
    return internal_pair_geometry(p, r, centre_distance), tooth_profile(p, warn=False), internal_profile(r)


def test_published_internal_pair_table():
    """KHK "Gear Technical Reference", profile-shifted internal gear calculation example (the same
    table is SDP/SI "Elements of Metric Gear Technology", section 5.1, Table 5-1): m 3, alpha 20
    deg, z1 16, z2 24, x1 0, x2 +0.516 gives inv a_w 0.061857, a_w 31.321 deg, y 0.4, a_x 13.2 mm,
    d_w 52.8 / 79.2 mm, d_b 45.105 / 67.658 mm, d_a2 69.096 mm, d_f2 82.596 mm (= d_a2 + 2 x 2.25 m)."""
    p, r = pinion(16, 0.0, 3.0), ring(24, 0.516, 3.0)
    g = internal_pair_geometry(p, r)
    assert involute(g.working_pressure_angle) == pytest.approx(0.061857, abs=5e-7)
    assert math.degrees(g.working_pressure_angle) == pytest.approx(31.321, abs=5e-4)
    assert g.centre_distance_modification == pytest.approx(0.4, abs=5e-5)
    assert g.centre_distance == pytest.approx(13.2, abs=5e-4)
    assert 2 * g.working_radius_pinion == pytest.approx(52.8, abs=5e-4)
    assert 2 * g.working_radius_ring == pytest.approx(79.2, abs=5e-4)
    assert 2 * p.base_radius == pytest.approx(45.105, abs=5e-4)
    assert 2 * r.base_radius == pytest.approx(67.658, abs=5e-4)
    assert 2 * r.tip_radius == pytest.approx(69.096, abs=1e-9)
    assert 2 * r.root_radius_standard == pytest.approx(82.596, abs=1e-9)
    assert g.backlash_transverse == pytest.approx(0.0, abs=1e-12)
    assert g.tooth_difference == 8


def test_contact_ratio_by_construction():
    """Contact ratio against the line of action built in coordinates: the pitch point on the line
    of centres, the line at a_w, its crossings with both tip circles found by a root solve."""
    from scipy.optimize import brentq
    g, p1, p2 = pair_parts(30, 0.0, 40, 0.5)
    a, aw = g.centre_distance, g.working_pressure_angle
    o1, o2 = np.array([a, 0.0]), np.zeros(2)
    pitch = np.array([g.working_radius_ring, 0.0])
    assert np.linalg.norm(pitch - o1) == pytest.approx(g.working_radius_pinion, abs=1e-12)
    direction = np.array([-math.sin(aw), math.cos(aw)])  # the line of action through the pitch point

    def at(t):
        return pitch + t * direction

    # both base tangent points lie at t > 0 (t = r_w sin(a_w)); each tip circle is crossed once
    # before its own tangent point, where the distance from that centre falls monotonically
    t_ring = brentq(lambda t: np.linalg.norm(at(t) - o2) - p2.tip_radius, -50.0, g.working_radius_ring * math.sin(aw))
    t_pinion = brentq(lambda t: np.linalg.norm(at(t) - o1) - p1.tip_radius, -50.0,
                      g.working_radius_pinion * math.sin(aw))
    p_bt = math.pi * p1.spec.transverse_module * math.cos(p1.spec.transverse_pressure_angle)
    assert (t_ring - t_pinion) / p_bt == pytest.approx(g.contact_ratio, abs=1e-10)
    assert 1.2 < g.contact_ratio < 2.5


def test_backlash_on_the_exact_outlines_equals_the_closed_form():
    """Pinion turned both ways on the exact outlines until it touches the ring (bisection): its
    play times rb1 is the closed-form backlash along the line of action, at two centre distances
    and two mesh phases. (For an internal pair a larger centre distance means less backlash.)"""
    zero = internal_pair_geometry(pinion(30), ring(40, 0.5)).centre_distance
    for offset in (-0.05, -0.01):
        g, p1, p2 = pair_parts(30, 0.0, 40, 0.5, centre_distance=zero + offset)
        assert g.backlash_transverse == pytest.approx(-2 * offset * math.sin(g.working_pressure_angle), rel=0.02)
        material = RingMaterial(p2)
        for phase in (0.0, 0.07):
            play = free_play(g, p1, p2, phase, material=material)
            assert play.transverse == pytest.approx(g.backlash_transverse, abs=2e-7)  # 0.2 nm


def test_ring_outline_is_exact_and_closed():
    for r in (ring(24, 0.516, 3.0), ring(60), ring(40, 0.2, helix_angle=math.radians(20))):
        prof = internal_profile(r)
        segs = prof.outline()
        gaps = [np.linalg.norm(s.end - t.start) for s, t in zip(segs, segs[1:] + segs[:1])]
        assert max(gaps) < 1e-12 * r.reference_radius
        upper_fillet, upper_flank = prof.segments[3], prof.segments[4]
        # the generated fillet starts on the involute (parallel-involute distance) with its tangent
        j = upper_flank.start
        rad = np.hypot(*j)
        assert prof.base_radius * abs(math.atan2(j[1], j[0]) - prof.space_half_angle(rad)) < 1e-12
        assert np.allclose(upper_fillet.tangent(upper_fillet.t1)[0], upper_flank.tangent(upper_flank.t0)[0],
                           atol=1e-9)
        # the fillet's exact derivative against a central difference
        t = 0.5 * (upper_fillet.t0 + upper_fillet.t1)
        h = 1e-6
        fd = (upper_fillet.point(t + h) - upper_fillet.point(t - h))[0] / (2 * h)
        assert np.allclose(upper_fillet.derivative(t)[0], fd, atol=1e-8)
        # Green's theorem against the shoelace area of a dense polygon of the same outline
        poly = sample_outline(segs, 2e-3 * r.module)
        shoelace = 0.5 * abs(np.sum(poly[:, 0] * np.roll(poly[:, 1], -1) - poly[:, 1] * np.roll(poly[:, 0], -1)))
        assert prof.hole_area() == pytest.approx(shoelace, rel=1e-6)
        assert prof.root_radius > prof.form_radius > prof.tip_radius > prof.base_radius


def test_between_pins_against_a_pin_placed_on_the_exact_flanks():
    """The pin centre found by bisection on the space centreline: where its distance to the exact
    (densely sampled) flank equals the pin radius."""
    r = ring(60)
    prof = internal_profile(r)
    d = reference_pin_diameter(r)
    flank = prof.segments[4].point(np.linspace(prof.segments[4].t0, prof.segments[4].t1, 200001))
    lo, hi = prof.tip_radius, prof.root_radius
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if np.min(np.hypot(flank[:, 0] - mid, flank[:, 1])) > d / 2:
            lo = mid  # the pin still fits: it can go further out
        else:
            hi = mid
    assert between_pins(r, d) == pytest.approx(2 * lo - d, abs=1e-6)  # even teeth: 2 R_M - d_p
    data = internal_gear_data(r)
    assert data["between_pins"]["dimension"] == pytest.approx(2 * lo - d, abs=1e-6)
    assert data["tip_radius"] == 29.0 and data["root_radius"] == 31.25


def test_involute_interference():
    """KHK 4.6: z1/z2 >= 1 - tan(a_a2)/tan(a_w) keeps the ring's tip off the pinion's base circle;
    the check also holds it off the pinion's fillet. A standard 40-tooth ring fails with 24 teeth
    (the numeric mesh overlaps), a +0.5 ring with a 30-tooth pinion passes (no overlap)."""
    g, p1, p2 = pair_parts(24, 0.0, 40, 0.0)
    assert involute_margin(g, p1) < 0
    phases = np.linspace(0.0, 2 * math.pi / 24, 41)
    assert overlap_depth(g, p1, p2, phases).max() > 1e-3
    g, p1, p2 = pair_parts(30, 0.0, 40, 0.5)
    assert involute_margin(g, p1) > 0
    rule = 1 - math.tan(math.acos(p2.base_radius / p2.tip_radius)) / math.tan(g.working_pressure_angle)
    assert 30 / 40 >= rule
    assert overlap_depth(g, p1, p2, np.linspace(0.0, 2 * math.pi / 30, 41)).max() < 1e-9
    kinds = [f.kind for f in check_internal(pinion(24), ring(40), radial_assembly=False).failures]
    assert "involute_interference" in kinds


def test_an_undercut_recess_is_not_interference():
    """Issue 31: the KHK / SDP-SI textbook pair (m 3, 16 / 24, x2 +0.516) failed for involute
    interference by 0.1248 mm. By hand: the ring's tip crosses the line of action
    sqrt(ra2^2 - rb2^2) - (rb2 - rb1) tan(a_w) = sqrt(34.548^2 - 33.829^2) - 11.276 tan 31.321 deg
    = 0.1502 mm past the pinion's base tangent point, above its base circle (KHK's rule holds);
    the 16-tooth pinion is undercut, its involute starting 0.2750 mm along the line (rb1 x its
    start roll), and the old margin was their difference. Below that start the undercut lies inside
    the involute (measured: 0 to 0.04 um deep where the ring's tip runs), so the ring's tip touches
    nothing: the exact outlines over one pitch (81 phases) overlap by none."""
    g, p1, p2 = pair_parts(16, 0.0, 24, 0.516, m=3.0)
    rb1, rb2, ra2 = g.pinion.base_radius, g.ring.base_radius, p2.tip_radius
    ring_tip = math.sqrt(ra2 ** 2 - rb2 ** 2) - (rb2 - rb1) * math.tan(g.working_pressure_angle)
    assert ring_tip == pytest.approx(0.1502, abs=5e-5)
    assert p1.undercut and rb1 * p1.involute_start_roll == pytest.approx(0.2750, abs=5e-5)
    assert ring_tip - rb1 * p1.involute_start_roll == pytest.approx(-0.1248, abs=5e-5)  # the old margin
    assert involute_margin(g, p1) == pytest.approx(ring_tip, rel=1e-12)
    recess = undercut_recess(p1, math.hypot(rb1, ring_tip), p1.involute_start_radius)
    assert -1e-9 < recess[0] and recess[1] < 5e-5  # mm: inside the involute, by at most 0.05 um
    # the exact outlines: no overlap (1e-9 mm: the outline's round-off; a real overlap is the 0.1 mm)
    assert overlap_depth(g, p1, p2, np.linspace(0.0, 2 * math.pi / 16, 81)).max() < 1e-9
    result = check_internal(g.pinion, g.ring, radial_assembly=False)
    assert result.ok
    # the contact stops at the pinion's involute start: 0.1248 mm less of the line of action
    p_bt = 2 * math.pi * rb1 / 16
    assert any(f"contact ratio {g.contact_ratio - 0.12481 / p_bt:.4f}" in n for n in result.notes)


def test_tip_interference():
    """A pinion addendum of 1.6 m reaches past the ring's form circle into its fillet and root."""
    g, p1, p2 = pair_parts(30, 0.0, 40, 0.5, pinion_kw={"addendum_coefficient": 1.5, "dedendum_coefficient": 1.8})
    margin, what = tip_margin(g, p1, p2)
    assert margin < 0
    assert overlap_depth(g, p1, p2, np.linspace(0.0, 2 * math.pi / 30, 41)).max() > 0
    assert tip_margin(*pair_parts(30, 0.0, 40, 0.5)[0:3])[0] > 0
    kinds = [f.kind for f in check_internal(g.pinion, g.ring, radial_assembly=False).failures]
    assert "tip_to_root_interference" in kinds


def test_trochoid_interference_agrees_with_the_numeric_mesh():
    """KHK's trochoid condition against the mesh turned through one pitch on the exact outlines
    (161 phases): 38 teeth in a +0.45 ring of 40 interfere, 37 in a +0.5 ring do not."""
    g, p1, p2 = pair_parts(38, 0.0, 40, 0.45)
    assert involute_margin(g, p1) > 0 and tip_margin(g, p1, p2)[0] > 0  # only the trochoid fails
    assert trochoid_margin(g) < 0
    assert overlap_depth(g, p1, p2, np.linspace(0.0, 2 * math.pi / 38, 161)).max() > 1e-2
    g, p1, p2 = pair_parts(37, 0.0, 40, 0.5)
    assert trochoid_margin(g) > 0
    assert overlap_depth(g, p1, p2, np.linspace(0.0, 2 * math.pi / 37, 161)).max() < 1e-9
    # a pinion tip circle enclosing the ring's: its teeth cut the ring's all round
    g, p1, p2 = pair_parts(39, 0.0, 40, 0.5)
    assert trochoid_margin(g) == -math.inf


def test_radial_assembly_fouling():
    """A small tooth difference cannot be assembled radially (KHK's trimming interference); a
    large one slides in."""
    g, p1, p2 = pair_parts(36, 0.0, 40, 0.5)
    assert radial_assembly_margin(g, p1, p2) < 0
    g, p1, p2 = pair_parts(20, 0.5, 60, 0.5)
    assert radial_assembly_margin(g, p1, p2) >= 0


def test_minimum_tooth_difference_and_a_passing_pair():
    result = check_internal(pinion(30), ring(40, 0.5), radial_assembly=False)
    assert result.ok and result.margins["trochoid_interference_rad"] > 0
    # 38 teeth fail the trochoid check in this ring (above), 37 pass: difference 3
    assert result.minimum_tooth_difference == 3
    assert result.to_dict()["tooth_difference"] == 10


def test_design_inputs_are_validated():
    with pytest.raises(DesignError, match="rim_diameter"):
        pinion(20, rim_diameter=50.0)
    with pytest.raises(DesignError, match="rim_diameter"):
        ring(60, rim_diameter=62.0)  # inside the root circle + 0.5 m
    from geargen.design.gear import Hub
    with pytest.raises(DesignError, match="bore"):
        ring(60, hub=Hub(bore_diameter=10.0))
    spec = read_gear({"kind": "internal", "teeth": 60, "module_mm": 1, "pressure_angle_deg": 20,
                            "face_width_mm": 10, "rim_diameter_mm": 80})
    assert spec.rim_diameter == 80.0 and spec.tip_radius == 29.0
    # ISO 6336-3's Y_B = 1 rim by default: root diameter + 2 x 3.5 m
    assert ring(60).rim_diameter == pytest.approx(62.5 + 7.0)


def test_pair_command_internal(capsys):
    from geargen.cli import main
    assert main(["pair", "--internal", "--teeth", "30", "40", "--module", "1", "--profile-shift", "0", "0.5"]) == 0
    out = capsys.readouterr().out
    assert "all checks pass" in out and "tooth difference 10" in out
    assert main(["pair", "--internal", "--teeth", "24", "40", "--module", "1"]) == 1
    assert "involute_interference" in capsys.readouterr().out


def test_helical_pair_backlash_on_the_transverse_outlines():
    """Helical pair (same hand): inv a_wt = inv a_t + 2 tan(a_n) (x2 - x1) / (z2 - z1) with normal
    shifts, and the play of the transverse outlines equals the closed-form backlash."""
    beta = math.radians(15)
    p = pinion(30, 0.1, helix_angle=beta, hand="left")
    r = ring(42, 0.6, helix_angle=beta, hand="left")
    g0 = internal_pair_geometry(p, r)
    alpha_t = p.transverse_pressure_angle
    assert involute(g0.working_pressure_angle) == pytest.approx(
        involute(alpha_t) + 2 * math.tan(A20) * 0.5 / 12, rel=1e-12)
    with pytest.raises(DesignError, match="hand"):
        internal_pair_geometry(p, ring(42, 0.6, helix_angle=beta, hand="right"))
    g = internal_pair_geometry(p, r, g0.centre_distance - 0.03)
    play = free_play(g, tooth_profile(p, warn=False), internal_profile(r), 0.02)
    assert play.transverse == pytest.approx(g.backlash_transverse, abs=2e-7)
    assert g.backlash_normal == pytest.approx(g.backlash_transverse * math.cos(p.base_helix_angle))
