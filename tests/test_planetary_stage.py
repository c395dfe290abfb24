"""The planetary upstream stage (geargen.design.planetary_stage, geargen.drives.planetary.place,
geargen.drives.planetary.verdict) in assemblies/planetary_dual_pinion.toml: the placement's phases
against a numeric solve on the exact outlines, the assembly condition (a violating planet count is
refused by name, and numerically cannot be placed), the ratio against a numeric kinematic solve,
named check failures of bad variants, and the one-home rule (the carrier radius moves the solids
and the checks)."""

import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from matplotlib.path import Path as Polygon
from scipy.optimize import brentq

from geargen.families.internal.pair import pinion_points
from geargen.drives.planetary.verdict import placed_ring_play
from geargen.checks.verdict import verify
from geargen.core.planetary import planet_phases, ring_phase_error
from geargen.design.assembly import load_design
from geargen.errors import DesignError
from geargen.drives.resolver import resolve
from geargen.profile.tooth import tooth_profile

ROOT = Path(__file__).resolve().parents[1]
DESIGN = ROOT / "assemblies" / "planetary_dual_pinion.toml"


def _variant(tmp_path, old: str, new: str, name: str = "variant.toml"):
    text = DESIGN.read_text()
    assert old in text
    path = tmp_path / name
    path.write_text(text.replace(old, new))
    return load_design(path)


@pytest.fixture(scope="module")
def layout():
    return resolve(load_design(DESIGN))


def _stage(layout):
    sun, ring = layout.gear("sun"), layout.gear("ring")
    planets = [g for g in layout.gears if "planetary_planet" in g.roles]
    return sun, ring, planets


def _free_turn(moving_pts, held_outline, centre, rotation, sign, pitch):
    """Free rotation (rad) of the moving gear's points about ``centre`` from ``rotation`` until a
    point enters the held gear's polygon (an independent inside test: matplotlib's point in
    polygon on the finely sampled exact outline); bisection to 1e-10 rad."""
    def hits(turn):
        c, s = math.cos(rotation + turn), math.sin(rotation + turn)
        xy = np.column_stack([centre[0] + c * moving_pts[:, 0] - s * moving_pts[:, 1],
                              centre[1] + s * moving_pts[:, 0] + c * moving_pts[:, 1]])
        return bool(held_outline.contains_points(xy).any())
    assert not hits(0.0)
    lo, hi = 0.0, 0.0
    while not hits(sign * hi):
        lo, hi = hi, hi + 0.01 * pitch
        assert hi < pitch
    while hi - lo > 1e-10:
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if hits(sign * mid) else (mid, hi)
    return lo


def test_every_placed_planet_sits_mid_play_with_the_sun_and_the_ring(layout):
    """The phases of geargen.core.planetary.planet_phases (closed form) against the free play
    solved numerically on the exact outlines as placed: each planet turns equally far both ways
    before it touches the sun (point in polygon on the sun's sampled outline, sun frame) and the
    ring (geargen.drives.planetary.verdict.placed_ring_play), and the two sum to the backlash the
    modelled teeth give (0.08 mm, the middle of the 0.04-0.12 mm range, at the planet's reference
    circle)."""
    sun, ring, planets = _stage(layout)
    assert len(planets) == 3
    sun_spec = sun.spec
    # chords of ~4 um: the polygon lies inside the exact outline by h^2 / 8 rho < 4 nm (rho > 0.5 mm)
    sun_pts = pinion_points(tooth_profile(sun_spec, warn=False), 5e-3 * sun_spec.module)
    c, s = math.cos(sun.rotation), math.sin(sun.rotation)
    sun_world = np.column_stack([sun.centre[0] + c * sun_pts[:, 0] - s * sun_pts[:, 1],
                                 sun.centre[1] + s * sun_pts[:, 0] + c * sun_pts[:, 1]])
    for p in planets:
        spec = p.spec
        pitch = 2 * math.pi / spec.teeth
        # the sun's outline facing this planet (one run of the closed outline), closed through the
        # sun's centre: a wedge of the sun that holds every tooth the planet can reach
        gap = np.hypot(*(sun_world - p.centre).T)
        ordered = np.roll(sun_world, -int(np.argmax(gap)), axis=0)  # start opposite the planet
        near = np.flatnonzero(np.roll(gap, -int(np.argmax(gap))) < spec.tip_radius + 0.01)
        run = ordered[near[0]:near[-1] + 1]
        assert len(run) < len(ordered) / 2
        wedge = Polygon(np.vstack([run, [sun.centre]]))
        pts = pinion_points(tooth_profile(spec, warn=False), 2.5e-3 * spec.module)
        c, s = math.cos(p.rotation), math.sin(p.rotation)
        placed = np.column_stack([p.centre[0] + c * pts[:, 0] - s * pts[:, 1], p.centre[1] + s * pts[:, 0] + c * pts[:, 1]])
        pts = pts[np.hypot(*(placed - sun.centre).T) < sun_spec.tip_radius + 0.01]
        ccw = _free_turn(pts, wedge, p.centre, p.rotation, +1, pitch)
        cw = _free_turn(pts, wedge, p.centre, p.rotation, -1, pitch)
        assert ccw == pytest.approx(cw, abs=2e-7)  # centred (the sampling's error is alike both ways)
        # the sun-planet play as the planet's rotation: at the sun's reference circle it is
        # r_p (ccw + cw) z_p / z_p, the same circumferential length
        assert spec.reference_radius * (ccw + cw) == pytest.approx(0.08, abs=5e-6)
        ccw_r, cw_r = placed_ring_play(spec, p.centre, p.rotation, ring.spec, ring.centre, ring.rotation)
        assert ccw_r == pytest.approx(cw_r, abs=1e-9)
        assert spec.reference_radius * (ccw_r + cw_r) == pytest.approx(0.08, abs=1e-6)


def test_a_planet_count_that_breaks_the_assembly_condition_cannot_be_placed(layout):
    """(z_s + z_r) / N = 72 / 5 is not whole: with 5 equally spaced planets phased from the sun,
    some planet needs the ring turned by a fraction of its pitch (ring_phase_error) and, on the
    exact outlines, overlaps the ring; with N = 3 and 4 (72 / N whole) every planet has play on
    both sides."""
    sun, ring, planets = _stage(layout)
    spec = planets[0].spec
    a = math.dist(planets[0].centre, sun.centre)
    for n, ok in ((3, True), (4, True), (5, False)):
        angles = [2 * math.pi * i / n for i in range(n)]
        errors = ring_phase_error(sun.spec.teeth, ring.spec.teeth, angles)
        assert (max(map(abs, errors)) < 1e-12) == ok
        rho, ring_rotation = planet_phases(sun.spec.teeth, spec.teeth, ring.spec.teeth, 0.0, angles)
        plays = [min(placed_ring_play(spec, (a * math.cos(phi), a * math.sin(phi)), r, ring.spec, (0.0, 0.0),
                                      ring_rotation)) for phi, r in zip(angles, rho)]
        assert (min(plays) > 0) == ok, (n, plays)


def test_planets_that_break_the_assembly_condition_are_refused_by_name(tmp_path):
    with pytest.raises(DesignError) as e:
        _variant(tmp_path, "planets = 3", "planets = 5")
    text = str(e.value)
    assert "stages.planetary.planets" in text and "72/5" in text and "1, 2, 3, 4, 6, 8, 9, 12" in text
    # unequal spacing at the assembly angles is taken when asked for: 5 planets at 2 pi k / 72
    design = _variant(tmp_path, "planets = 3", 'planets = 5\nplanet_spacing = "nearest_allowed"', "unequal.toml")
    moved = resolve(design)
    sun, _, placed = _stage(moved)
    steps = [math.atan2(p.centre[1] - sun.centre[1], p.centre[0] - sun.centre[0]) % (2 * math.pi) * 72 / (2 * math.pi)
             for p in placed]
    assert [round(k) for k in steps] == [0, 14, 29, 43, 58]  # round(i 72 / 5)
    assert steps == pytest.approx([round(k) for k in steps], abs=1e-9)
    result = verify(moved, tolerances=False)
    # every planet meshes both sun and ring; but five planets of 18.72 mm do not fit round a 15 T sun:
    # the stage's rule says so, and the parts check finds the neighbours' solids overlapping
    assert {(f.kind, f.mesh) for f in result.failures} == {("planet_neighbour_clearance", "stage_planetary"),
                                                           ("parts_overlap", "parts")}
    overlapping = {frozenset((f.part1, f.part2)) for f in result.parts.findings}
    assert overlapping and all(all(n.startswith("planet_") for n in pair) for pair in overlapping)


def test_the_stage_counts_its_ratio_and_it_is_the_kinematics_of_the_phases(layout):
    """1 + z_r / z_s = 1 + 57/15 = 4.8 in the layout's ratio (72 with the loop's 15); and the
    same from the phase relation alone: turning the carrier by a small angle with the ring held,
    the sun turn that keeps every planet in mesh (solved numerically) is 4.8 times it."""
    assert layout.ratio["ok"] and layout.ratio["total"] == Fraction(72)
    assert "(1 + 57/15)" in layout.ratio["text"]
    zs, zp, zr = 15, 21, 57
    angles = [0.0, 2 * math.pi / 3, 4 * math.pi / 3]
    ring0 = planet_phases(zs, zp, zr, 0.0, angles)[1]
    turn = 1e-3
    moved = [phi + turn for phi in angles]

    pitch = 2 * math.pi / zr

    def ring_slip(sun_turn):  # the ring's required rotation minus where it is held (within a pitch)
        d = planet_phases(zs, zp, zr, sun_turn, moved)[1] - ring0
        return d - pitch * round(d / pitch)

    sun_turn = brentq(ring_slip, 0.0, 10 * turn, xtol=1e-15)
    assert sun_turn / turn == pytest.approx(4.8, rel=1e-9)


def test_the_neighbour_clearance_fails_the_check_by_name(tmp_path):
    """Asking 7 mm between the planets' tip circles (they have 2 a sin 60 deg - d_a = 6.858 mm)."""
    design = _variant(tmp_path, "circumferential_backlash_max_mm = 0.12\n\n[synthesis]",
                      "circumferential_backlash_max_mm = 0.12\nplanet_tip_clearance_mm = 7\n\n[synthesis]")
    result = verify(resolve(design), tolerances=False)
    kinds = {f.kind for f in result.failures}
    assert kinds == {"planet_neighbour_clearance"}
    row = next(r for r in result.planetary if r["mesh"] == "stage_planetary")
    a, d_a = 14.767394073994936, 18.72
    assert row["neighbour_tip_gap"] == pytest.approx(2 * a * math.sin(math.pi / 3) - d_a, abs=1e-9)


def test_a_ring_that_is_not_coaxial_fails_the_check_by_name(tmp_path):
    """Ring shift 0.6 instead of 0.7: the planet-ring zero-backlash centre distance falls short of
    the sun-planet one (coaxiality), and at the carrier radius the ring mesh's backlash leaves the
    range."""
    design = _variant(tmp_path, "module_mm = 0.8\nprofile_shift = 0.7", "module_mm = 0.8\nprofile_shift = 0.6")
    result = verify(resolve(design), tolerances=False)
    kinds = {f.kind for f in result.failures}
    assert "planetary_coaxiality" in kinds


def test_the_carrier_radius_has_one_home(tmp_path, layout):
    """Moving the carrier radius (14.767 -> 14.80 mm) moves the planets, and the checks see it:
    the sun-planet meshes run at the new centre distance with the thinning derived there, and the
    planet-ring backlash measured on the placed outlines follows the closed form there."""
    design = _variant(tmp_path, "planets = 3", "planets = 3\ncarrier_radius_mm = 14.80")
    moved = resolve(design)
    sun, ring, planets = _stage(moved)
    assert all(math.dist(p.centre, sun.centre) == pytest.approx(14.80, abs=1e-12) for p in planets)
    mesh = moved.mesh("stage_planetary_sun_planet_1")
    assert mesh.centre_distance == pytest.approx(14.80)
    old = _stage(layout)[2][0].spec
    assert planets[0].spec.thinning != pytest.approx(old.thinning)  # the modelled teeth follow the radius
    result = verify(moved, tolerances=False)
    assert not result.failures
    rows = [r for r in result.planetary if "gear1" in r]
    for r in rows:
        assert r["centre_distance"] == pytest.approx(14.80, abs=1e-12)
        assert r["backlash"] == pytest.approx(0.08, abs=1e-6)


@pytest.mark.slow
def test_the_carrier_radius_moves_the_carrier_solids(tmp_path, layout):
    """The carrier's pins stand at the planets' centres and its plates reach a pin diameter past
    them: both follow the carrier radius of the Layout (the non-gear parts built from each)."""
    from geargen.cad.assembly import non_gear_parts
    from geargen.cad.parts import volume
    design = _variant(tmp_path, "planets = 3", "planets = 3\ncarrier_radius_mm = 14.80")
    out = {}
    for key, lay in (("design", layout), ("moved", resolve(design))):
        parts = {p.name: p for p in non_gear_parts(lay).parts}
        pin = parts["carrier_planetary_pin_1"]
        plate = parts["carrier_planetary_lower"]
        out[key] = (np.asarray(pin.matrix)[:2, 3] - np.asarray(plate.matrix)[:2, 3], volume(plate.shape))
    for key, a in (("design", 14.767394073994936), ("moved", 14.80)):
        offset, vol = out[key]
        assert offset == pytest.approx([a, 0.0], abs=1e-9)
        # plate: disc r = a + d_pin, less the input shaft's bore (5 mm) and three pin holes (4 mm)
        r = a + 4.0
        expected = math.pi * (r ** 2 - 2.5 ** 2 - 3 * 2.0 ** 2) * 4.0
        assert vol == pytest.approx(expected, rel=1e-6)


def test_the_sun_teeth_count_in_the_ratio_check(tmp_path):
    """z_s 18 and z_r 60 (still z_s + 2 z_p, coaxial with the same shifts, (18 + 60) / 3 = 26
    whole): the stage is 1 + 60/18 = 13/3, the drive 65, not the required 72: ratio_mismatch."""
    text = DESIGN.read_text()
    for old, new in (("[gears.sun]\nteeth = 15", "[gears.sun]\nteeth = 18"), ("teeth = 57", "teeth = 60")):
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / "sun18.toml"
    path.write_text(text)
    layout = resolve(load_design(path))
    assert layout.ratio["total"] == Fraction(65) and "(1 + 60/18)" in layout.ratio["text"]
    result = verify(layout, tolerances=False)
    assert [f.kind for f in result.failures] == ["ratio_mismatch"]
    # and the sun's placement follows: the carrier radius is the new working centre distance
    sun, _, planets = _stage(layout)
    assert sun.spec.teeth == 18
    assert math.dist(planets[0].centre, sun.centre) > 14.767394073994936 + 1.0


def test_geargen_check_gives_the_verdict(tmp_path, capsys):
    """`geargen check` passes the shipped design and fails a variant whose planets crowd (exit 1)."""
    from geargen.cli import main
    assert main(["check", str(DESIGN)]) == 0
    assert "stage_planetary_planet_3_ring" in capsys.readouterr().out
    text = DESIGN.read_text().replace("circumferential_backlash_max_mm = 0.12\n\n[synthesis]",
                                      "circumferential_backlash_max_mm = 0.12\nplanet_tip_clearance_mm = 7\n\n[synthesis]")
    bad = tmp_path / "crowded.toml"
    bad.write_text(text)
    assert main(["check", str(bad)]) == 1
    assert "planet_neighbour_clearance" in capsys.readouterr().out


def _placed_outline(points, centre, rotation):
    c, s = math.cos(rotation), math.sin(rotation)
    return np.column_stack([centre[0] + c * points[:, 0] - s * points[:, 1], centre[1] + s * points[:, 0] + c * points[:, 1]])


@pytest.mark.slow
def test_the_exported_ring_and_planet_stand_as_checked(built_assemblies, layout):
    """On the built assembly's re-imported STEP solids (world frame), the smallest gap between
    planet 1 and the ring at mid-face, sections refined on the B-spline faces, is the gap between
    the exact outlines placed as the Layout says (sampled 0.5 um apart; the flanks run parallel
    along the line of action there, so sampling hardly moves the minimum) within the solids' flank
    tolerance: the ring solid's tooth-space convention and the placed phases are the ones the
    planet-ring check measured."""
    from scipy.spatial import cKDTree
    from geargen.cad.measure import section
    from geargen.profile.internal import internal_profile
    from geargen.profile.segments import sample_outline

    ring, planet = layout.gear("ring"), layout.gear("planet_1")
    z = ring.z + ring.spec.face_width / 2
    # exact: only the ring's teeth near the planet
    ring_exact = _placed_outline(sample_outline(internal_profile(ring.spec).outline(), 5e-4), ring.centre, ring.rotation)
    ring_exact = ring_exact[np.hypot(*(ring_exact - planet.centre).T) < planet.spec.tip_radius + 0.5]
    planet_exact = _placed_outline(sample_outline(tooth_profile(planet.spec, warn=False).outline(), 5e-4),
                                   planet.centre, planet.rotation)
    gap_exact = float(cKDTree(ring_exact).query(planet_exact)[0].min())

    ring_cut = section(built_assemblies.step("planetary_dual_pinion", "ring").shape, z, 64)
    planet_cut = section(built_assemblies.step("planetary_dual_pinion", "planet_1").shape, z, 64)
    near = np.hypot(*(ring_cut.points - planet.centre).T) < planet.spec.tip_radius + 0.5
    d, j = cKDTree(ring_cut.points[near]).query(planet_cut.points)
    candidates = np.argsort(d)[:12]
    ring_curves = sorted(set(ring_cut.edge_index[near].tolist()))
    planet_curves = sorted(set(planet_cut.edge_index.tolist()))
    gap_solid = math.inf
    for i in candidates:  # alternate closest points on the two sections' curves (refined to ~1e-13)
        p = planet_cut.points[i]
        for _ in range(6):
            _, q, _ = ring_cut.closest_point(p, ring_curves)
            _, p, _ = planet_cut.closest_point(q, planet_curves)
        gap_solid = min(gap_solid, float(np.linalg.norm(p - q)))
    assert 0.005 < gap_exact < 0.04  # flanks apart: play on both sides (0.04 mm each way at r_p)
    # each solid's flank lies within 0.1 um of its exact involute (the gear solids' standard): the
    # two flanks within 0.2 um; a wrong phase or an unthinned ring would be 10 um off or more
    # (measured: 13 nm apart)
    assert gap_solid == pytest.approx(gap_exact, abs=2e-4)


def test_a_planet_off_its_assembly_angle_fails_the_check(layout):
    """The check reads the Layout: planet 2 carried round the sun by half an assembly step
    (pi / 72, turning about its own axis as the carrier would carry it) is no longer at an assembly
    angle: planetary_assembly, and its ring mesh, half a ring pitch out of phase, overlaps."""
    import dataclasses
    sun = layout.gear("sun")
    step = math.pi / 72
    moved = []
    for g in layout.gears:
        if g.name == "planet_2":
            x, y = g.centre[0] - sun.centre[0], g.centre[1] - sun.centre[1]
            c, s = math.cos(step), math.sin(step)
            g = dataclasses.replace(g, centre=(sun.centre[0] + c * x - s * y, sun.centre[1] + s * x + c * y),
                                    rotation=g.rotation + step)
        moved.append(g)
    result = verify(dataclasses.replace(layout, gears=tuple(moved), meshes=()), tolerances=False)
    kinds = {(f.kind, f.mesh) for f in result.failures}
    assert ("planetary_assembly", "stage_planetary") in kinds
    assert ("flank_interference", "stage_planetary_planet_2_ring") in kinds
    assert not any(m.endswith(("planet_1_ring", "planet_3_ring")) for _, m in kinds)


def test_a_helical_stage_meshes_mid_play_on_every_plane(tmp_path):
    """Sun left-hand, planets and ring right-hand, 15 deg: the phases set in the stage's lowest
    plane are carried through each gear's helix; every planet has equal play both ways with the
    ring on the lowest and the highest plane of the faces, and the check passes."""
    text = DESIGN.read_text()
    for gear in ("[gears.sun]\nteeth = 15", "[gears.planet]\nteeth = 21", "[gears.ring]\nkind = \"internal\"\nteeth = 57"):
        assert gear in text
        hand = "left" if "sun" in gear else "right"
        text = text.replace(gear, f'{gear}\nhelix_angle_deg = 15\nhand = "{hand}"')
    path = tmp_path / "helical.toml"
    path.write_text(text)
    layout = resolve(load_design(path))
    sun, ring, planets = _stage(layout)
    assert planets[0].spec.helix_angle == pytest.approx(math.radians(15))
    assert not verify(layout, tolerances=False).failures
    for p in planets:
        for z in p.face_z(p.spec):
            ccw, cw = placed_ring_play(p.spec, p.centre, p.rotation_at(p.spec, z), ring.spec, ring.centre,
                                       ring.rotation_at(ring.spec, z))
            assert ccw == pytest.approx(cw, abs=1e-9) and ccw > 0


def test_the_stiffness_model_twists_the_input_shaft_up_to_the_carrier(tmp_path, layout):
    """The input shaft's torsion component (from_geometry) runs from the input gear's mid-face to
    the middle of the carrier's lower plate, which stands a clearance under the stage's gears: the
    length read from the Layout's placements by hand, and a thicker plate ([parts]
    carriage_plate_thickness 4 -> 5 mm) lengthens it in the analysis as it thickens the carrier."""
    from geargen.design.parts import parts_settings
    from geargen.model.analysis import placed_components
    from geargen.drives.planetary.place import carrier
    from geargen.design.stages import stages

    def twist(lay):
        comp = next(c for c in placed_components(lay.design, lay) if c.name == "input_shaft")
        parts = parts_settings(lay.design)
        t, gap = parts["carriage_plate_thickness"], parts["bearing_clearance"]
        inp, sun = lay.gear("input"), lay.gear("sun")
        by_hand = (sun.z - gap - t / 2) - (inp.z + inp.spec.face_width / 2)  # all stage faces 6 mm: one level
        assert comp.length == pytest.approx(by_hand, abs=1e-12)
        return comp.length, carrier(lay, parts, stages(lay.design)[0]).thickness

    length, plate = twist(layout)
    design = _variant(tmp_path, "carriage_plate_thickness_mm = 4", "carriage_plate_thickness_mm = 5")
    longer, thicker = twist(resolve(design))
    assert (plate, thicker) == (4.0, 5.0)
    # the stage stands on the link cover's level (unchanged): its gears rise by the 1 mm the plate
    # grew, the plate's middle by half of it
    assert longer == pytest.approx(length + 0.5, abs=1e-12)


def test_a_ring_cut_too_wide_fails_the_ring_meshes_by_name(layout):
    """The check reads the ring as the Layout models it: its spaces widened by 0.05 mm more, each
    planet-ring mesh has 0.08 + 0.05 = 0.13 mm of backlash (as placed and over a planet pitch of
    mesh positions), above the 0.12 mm maximum: backlash_out_of_range for each, nothing else."""
    import dataclasses
    from geargen.design.gear import with_changes
    gears = tuple(dataclasses.replace(g, spec=with_changes(g.spec, thinning=g.spec.thinning + 0.05))
                  if g.name == "ring" else g for g in layout.gears)
    result = verify(dataclasses.replace(layout, gears=gears), tolerances=False)
    assert {(f.kind, f.mesh) for f in result.failures} == {
        ("backlash_out_of_range", f"stage_planetary_planet_{i}_ring") for i in (1, 2, 3)}
    for row in (r for r in result.planetary if "gear1" in r):
        assert row["backlash"] == pytest.approx(0.13, abs=1e-6)
        assert row["sweep_min"] == pytest.approx(0.13, abs=1e-6) and row["sweep_max"] == pytest.approx(0.13, abs=1e-6)
