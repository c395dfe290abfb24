"""Non-gear parts: every solid against its closed-form volume (and the bevel pitch cones' geometry)."""

import math

import pytest

from geargen.families.bevel.geometry import bevel_pair_geometry

pytestmark = pytest.mark.slow

P = pytest.importorskip("geargen.cad.parts")

# the kernel's volume integration on these analytic solids is exact to ~1e-9 relative; 1e-7 leaves room
REL = 1e-7


def test_cylinder_and_bearing_volumes():
    assert P.volume(P.cylinder(10, 5)) == pytest.approx(math.pi / 4 * 100 * 5, rel=REL)
    assert P.volume(P.bearing(8, 22, 7)) == pytest.approx(math.pi / 4 * (22 ** 2 - 8 ** 2) * 7, rel=REL)
    assert P.volume(P.shaft(16, 78, 9.5)) == pytest.approx(math.pi / 4 * (16 ** 2 - 9.5 ** 2) * 78, rel=REL)


def test_frustum_volume():
    r0, r1, h, bore = 12.0, 7.0, 5.0, 4.0
    expected = math.pi * h * (r0 * r0 + r0 * r1 + r1 * r1) / 3 - math.pi / 4 * bore ** 2 * h
    assert P.volume(P.frustum(r0, r1, h, bore)) == pytest.approx(expected, rel=REL)


def test_bevel_pitch_cones_meet_at_one_apex():
    g = bevel_pair_geometry(15, 30, 0.79375, 3.81)
    assert g.pitch_angle_pinion + g.pitch_angle_gear == pytest.approx(math.pi / 2, rel=1e-15)
    assert math.tan(g.pitch_angle_gear) == pytest.approx(2.0, rel=1e-14)  # ratio 2 at 90 deg shaft angle
    # both heels lie on the same cone distance from the common apex
    assert math.hypot(g.pitch_radius_pinion, g.apex_height("pinion")) == pytest.approx(g.cone_distance, rel=1e-14)
    assert math.hypot(g.pitch_radius_gear, g.apex_height("gear")) == pytest.approx(g.cone_distance, rel=1e-14)
    cone = P.bevel_pitch_cone(g, "gear", bore=4.7625)
    r0, r1, h = g.pitch_radius_gear, g.toe_radius("gear"), g.axial_height("gear")
    expected = math.pi * h * (r0 * r0 + r0 * r1 + r1 * r1) / 3 - math.pi / 4 * 4.7625 ** 2 * h
    assert P.volume(cone) == pytest.approx(expected, rel=REL)


def test_servo_motor_and_blade_volumes():
    m = P.servo_motor(25.4, 38.1, 25.4, 3.175, 4.7625, 2.54)
    expected = 25.4 ** 2 * 3.175 + math.pi / 4 * 25.4 ** 2 * 38.1 + math.pi / 4 * 4.7625 ** 2 * 2.54
    assert P.volume(m) == pytest.approx(expected, rel=REL)
    assert P.volume(P.blade_flexure(0.254, 25.4, 12.7)) == pytest.approx(0.254 * 25.4 * 12.7, rel=REL)


def test_link_tray_volume_matches_formula():
    args = (50.8, 120.0, 70.0, 3.0, 4.0, [(0.0, 0.0, 38.1, 20.0), (47.0, 23.9, 15.9, 25.0)])
    assert P.volume(P.link_tray(*args)) == pytest.approx(P.link_tray_volume(*args), rel=REL)
    relieved = (50.8, 120.0, 70.0, 3.0, 4.0, [(0.0, 0.0, 38.1, 20.0, 31.0), (47.0, 23.9, 15.9, 25.0, 12.0)])
    assert P.volume(P.link_tray(*relieved)) == pytest.approx(P.link_tray_volume(*relieved), rel=REL)
    # the reliefs are blind: down to the floor's top, not through it
    assert P.volume(P.link_tray(*args)) - P.volume(P.link_tray(*relieved)) == pytest.approx(
        math.pi / 4 * (31.0 ** 2 * 20.0 + 12.0 ** 2 * 25.0), rel=REL)


def test_plate_with_holes_volume():
    plate = P.plate_with_holes(100, 60, 20, [(30, 30, 20), (70, 30, 10)], corner=(0, 0, 0))
    assert P.volume(plate) == pytest.approx(100 * 60 * 20 - math.pi / 4 * (400 + 100) * 20, rel=REL)


def test_split_collar_removes_its_slot():
    ring = P.volume(P.cylinder(30, 10, 8.5))
    slot = 1.5 * (30 - 8.5) / 2 * 10  # first order: the slot's ends are flat, the ring's curved
    assert P.volume(P.split_collar(8.5, 30, 10, 1.5)) == pytest.approx(ring - slot, rel=2e-3)


@pytest.mark.parametrize("ground", [True, False])
def test_spring_wire_volume_is_the_swept_circle(ground):
    from geargen.model.bodies import spring_helix
    d, mean, length, coils = 1.143, 11.43, 8.89, 6.0
    z0, pitch = spring_helix((d, mean, length, coils, ground))
    assert (z0, pitch) == ((0.0, length / coils) if ground else (d / 2, (length - d) / coils))
    wire = math.pi * d * d / 4 * coils * math.hypot(math.pi * mean, pitch)
    spring = P.compression_spring(d, mean, length, coils, ground)
    assert P.is_valid(spring) and len(P.solids(spring)) == 1
    # within the slab [0, length] and reaching both ends (a kernel box is loose on a trimmed spline face)
    below, above = P.box_between((-9, -9, -2), (9, 9, 0)), P.box_between((-9, -9, length), (9, 9, length + 2))
    assert P.volume(P.intersect(spring, below)) == pytest.approx(0.0, abs=1e-9)
    assert P.volume(P.intersect(spring, above)) == pytest.approx(0.0, abs=1e-9)
    ends = [P.box_between((-9, -9, z), (9, 9, z + 0.01)) for z in (0.0, length - 0.01)]
    assert all(P.volume(P.intersect(spring, end)) > 0 for end in ends)
    # grinding removes at most the half wire along the end coils' rise through d: well under 20 %
    assert 0.8 * wire < P.volume(spring) < wire


@pytest.mark.parametrize("ground", [True, False])
def test_spring_volume_is_pappus_less_the_ground_ends(ground):
    """The wire circle lies in a plane through the axis: by Pappus the swept volume is
    pi^2 d^2 D n / 4; grinding takes the half discs below each end plane, pi D d^3 / (6 p)."""
    from geargen.cad.gear_solid import solid_volume
    from geargen.model.bodies import spring_helix
    d, mean, length, coils = 1.143, 11.43, 8.89, 6.0
    _, pitch = spring_helix((d, mean, length, coils, ground))
    expected = math.pi ** 2 * d * d * mean * coils / 4 - (math.pi * mean * d ** 3 / (6 * pitch) if ground else 0.0)
    # the kernel's swept surface approximates the tube (measured 2e-7 .. 6e-7 of the volume); the
    # adaptive integration is needed: the default one is 3e-3 off on the trimmed ground ends
    assert solid_volume(P.compression_spring(d, mean, length, coils, ground)) == pytest.approx(expected, rel=2e-6)


def test_ground_spring_is_made_down_to_its_solid_height():
    """d N_t is the solid height of ground ends (geargen.design.stiffness.SPRING_ENDS): 1 % above it
    the spring is one valid solid, at it the body is refused with the solid height named."""
    from geargen.model.bodies import compression_spring
    d, mean, coils = 1.143, 11.43, 6.0
    spring = P.compression_spring(d, mean, 1.01 * d * coils, coils, True)
    assert P.is_valid(spring) and len(P.solids(spring)) == 1
    with pytest.raises(ValueError, match="solid height 6.858"):
        compression_spring(d, mean, d * coils, coils, ground=True)
    with pytest.raises(ValueError, match="solid height 8.001"):
        compression_spring(d, mean, 1.01 * d * coils, coils, ground=False)


def test_intended_contacts_are_verified_not_assumed():
    """An intended contact is checked: touching solids pass, solids 0.5 mm apart are a missing
    contact (the C-axis retracted stop floated above its plate), and a part run into its mate
    is interpenetrating (the C-axis coupling shared 14,137 mm^3 with its shaft)."""
    import numpy as np

    from geargen.cad.assembly import PlacedPart, pairwise_overlaps

    def part(name, shape, dz=0.0):
        m = np.eye(4)
        m[2, 3] = dz
        return PlacedPart(name, shape, m, "g", "shaft")

    shaft = part("shaft", P.cylinder(10.0, 50.0))
    sleeve = part("sleeve", P.cylinder(30.0, 20.0, 10.0), dz=10.0)  # bored to the shaft: touches
    solid_hub = part("hub", P.cylinder(30.0, 20.0), dz=10.0)  # no bore: runs into the shaft
    block = part("block", P.box_between((-5, -5, 0), (5, 5, 5)), dz=50.5)  # 0.5 mm above the shaft's end
    ok = pairwise_overlaps([shaft, sleeve], [("shaft", "sleeve", "sleeve on its shaft")])
    assert ok.ok and not ok.missing_contacts and not ok.interpenetrating
    bad = pairwise_overlaps([shaft, solid_hub, block], [("shaft", "hub", "hub on its shaft"),
                                                        ("shaft", "block", "block on the shaft's end")])
    assert not bad.ok
    assert [(a, b) for a, b, _, _ in bad.missing_contacts] == [("shaft", "block")]
    assert bad.missing_contacts[0][2] == pytest.approx(0.5, abs=1e-6)
    (o,) = bad.interpenetrating
    assert {o.part1, o.part2} == {"shaft", "hub"}
    assert o.volume == pytest.approx(math.pi * 5.0 ** 2 * 20.0, rel=1e-6)


def test_spring_tube_screens_only_what_cannot_overlap():
    """A helical spring is first tested through its tube (:func:`geargen.cad.assembly.part_envelope`):
    seated on its wall it passes without intersecting the helix; pushed 0.5 mm into the wall it is
    interpenetrating with the helix's own shared volume, as without the tube."""
    import numpy as np

    from geargen.cad.assembly import PlacedPart, pairwise_overlaps

    d, mean, length = 1.143, 11.43, 8.89
    helix, tube = P.compression_spring(d, mean, length, 6.0, True), P.coil_envelope(d, mean, length)
    wall = PlacedPart("wall", P.box_between((-10, -10, -5), (10, 10, 0)), np.eye(4), "g", "carriage")

    def checked(dz, envelope):
        m = np.eye(4)
        m[2, 3] = dz
        spring = PlacedPart("spring", helix, m, "g", "spring", envelope=envelope)
        return pairwise_overlaps([wall, spring], [("wall", "spring", "spring on its seat")])

    assert checked(0.0, tube).ok and checked(0.0, None).ok
    pushed, plain = checked(-0.5, tube), checked(-0.5, None)
    assert not pushed.ok
    assert pushed.interpenetrating[0].volume == plain.interpenetrating[0].volume > 0


def test_link_cover_volume_matches_formula():
    seats = [(0.0, 0.0, 38.1, 0.0, 31.75), (47.07, 23.89, 15.875, 0.58, 11.1125), (47.07, -23.89, 15.875, 0.58, 11.1125)]
    args = (50.8, 3.048, 64.0, 3.81, seats)
    cover = P.link_cover(*args)
    assert P.is_valid(cover)
    assert P.volume(cover) == pytest.approx(P.link_cover_volume(*args), rel=REL)
    lo, hi = P.bounding_box(cover)
    # the rim lies on the tray's inner walls (radius - wall), the bosses hang below the cover
    assert hi[0] == pytest.approx(64.0, abs=1e-6) and lo[0] == pytest.approx(-(50.8 - 3.048), abs=1e-6)
    assert lo[2] == pytest.approx(-0.58, abs=1e-6) and hi[2] == pytest.approx(3.81, abs=1e-6)


def test_quill_volume_matches_formula():
    """The C-axis quill: a sleeve bored to two bearing seats with a shoulder between them, and a lug
    at its lower end; the lug adds its box less the circular segment inside the sleeve's cylinder."""
    bores = [(0.0, 100.0, 55.0), (100.0, 117.0, 42.5), (117.0, 130.0, 55.0)]
    args = (75.0, 130.0, bores, 35.0, 12.0, 12.0)
    quill = P.quill(*args)
    assert P.is_valid(quill) and len(P.solids(quill)) == 1
    assert P.volume(quill) == pytest.approx(P.quill_volume(*args), rel=REL)
    sleeve = math.pi / 4 * (75.0 ** 2 * 130 - 55.0 ** 2 * 113 - 42.5 ** 2 * 17)
    r, w, t = 37.5, 12.0, 12.0
    segment = r * r * math.asin(w / (2 * r)) - math.sqrt(r * r - w * w / 4) * w / 2
    assert P.volume(quill) - sleeve == pytest.approx((r + 35.0 - math.sqrt(r * r - w * w / 4)) * w * t - segment * t,
                                                     rel=1e-6)
    lo, hi = P.bounding_box(quill)
    assert hi[0] == pytest.approx(r + 35.0, abs=1e-6) and lo[0] == pytest.approx(-r, abs=1e-6)
    assert lo[2] == pytest.approx(0.0, abs=1e-6) and hi[2] == pytest.approx(130.0, abs=1e-6)
    # impossible numbers are the resolved drive's to refuse (geargen.model.bodies): here a bug
    with pytest.raises(ValueError):
        P.quill(75.0, 130.0, [(0.0, 130.0, 80.0)], 35.0, 12.0, 12.0)  # bored through its wall
    with pytest.raises(ValueError):
        P.quill(75.0, 130.0, bores, 35.0, 40.0, 12.0)  # a lug wider than the wall can hold
