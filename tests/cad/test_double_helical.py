"""Double-helical (herringbone) solids: one valid solid, volume against the exact outline, flanks on
the involute in both halves, each half's hand, the centre gap measured on the solid, STEP/STL."""

import math
from dataclasses import replace

import numpy as np
import pytest
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepGProp import BRepGProp
from OCP.GeomAbs import GeomAbs_Plane
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS

from geargen.families.double_helical.solid import build_double_helical, half_spec
from geargen.profile.tooth import centre_gap_radius
from geargen.cad.families import build_part
from geargen.cad.gear_solid import check_solid, solid_volume
from geargen.cad.measure import flank_deviation, section
from geargen.design.gear import GearSpec, Hub
from geargen.families.double_helical.spec import DoubleHelicalGearSpec
from geargen.errors import DesignError
from geargen.profile.tooth import section_rotation
from geargen.profile.tooth import tooth_profile

pytestmark = pytest.mark.slow

DEG = math.pi / 180


def herringbone(gap=0.0, hand="right", hub=Hub(), teeth=19, face=14.0):
    return DoubleHelicalGearSpec(teeth=teeth, module=1.0, pressure_angle=20 * DEG, face_width=face,
                                 helix_angle=30 * DEG, hand=hand, centre_gap=gap, hub=hub, profile_shift=0.2)


@pytest.fixture(scope="module")
def apex():
    """No gap (the flanks meet at the apex), a bore with a keyway and a hub."""
    return build_double_helical(herringbone(0.0, "right", Hub(6.0, 2.0, 1.0, 12.0, 3.0)))


@pytest.fixture(scope="module")
def gapped():
    """A 3 mm relief groove between the halves, left hand first, a plain bore."""
    return build_double_helical(herringbone(3.0, "left", Hub(5.0)))


def bore_area(hub: Hub) -> float:
    """Bore with keyway (flat floor at bore radius + depth): circle plus the keyway's rectangle
    beyond the chord, minus the circular segment beyond that chord."""
    if hub.bore_diameter <= 0:
        return 0.0
    r = hub.bore_diameter / 2
    area = math.pi * r * r
    if hub.keyway_width > 0:
        w2 = hub.keyway_width / 2
        xk = math.sqrt(r * r - w2 * w2)
        area += hub.keyway_width * (r + hub.keyway_depth - xk) - (r * r * math.asin(w2 / r) - xk * w2)
    return area


def expected_volume(spec, profile) -> float:
    """Profile area x toothed length + groove disc x gap - bore x face width, plus the hub. A helical
    half has the volume of its spur twin (every transverse section is the same outline, turned)."""
    hub = spec.hub
    vol = profile.area() * (spec.face_width - spec.centre_gap) + math.pi * centre_gap_radius(spec, profile) ** 2 * spec.centre_gap
    vol -= bore_area(hub) * spec.face_width
    vol += (math.pi * hub.hub_diameter ** 2 / 4 - bore_area(hub)) * hub.hub_length
    return vol


def upper_half_deviation(g, z):
    """Flank deviation at height z of the second half. Its section at z is the z = 0 section turned
    by section_rotation(spec, b - z) (mirror image of the first half); the same turn is
    section_rotation of the opposite-hand gear at z - b, which is what flank_deviation is given."""
    spec = g.spec
    other = tooth_profile(replace(half_spec(spec), hand=spec.half_hands[1]))
    assert section_rotation(other.spec, z - spec.face_width) == pytest.approx(
        section_rotation(spec, spec.face_width - z), abs=1e-15)
    return flank_deviation(g.shape, other, z - spec.face_width, cut=section(g.shape, z))


@pytest.mark.parametrize("which", ["apex", "gapped"])
def test_one_solid_of_the_exact_volume(which, request):
    g = request.getfixturevalue(which)
    assert check_solid(g.shape) is None
    # the issue's bound 1e-6; the flank splines' 2 nm keep it near 1e-9
    assert solid_volume(g.shape) == pytest.approx(expected_volume(g.spec, g.profile), rel=1e-6)


@pytest.mark.parametrize("which", ["apex", "gapped"])
def test_flanks_on_the_involute_in_both_halves(which, request):
    g = request.getfixturevalue(which)
    spec = g.spec
    h = spec.half_face_width
    for z in (0.1, 0.5 * h, h - 0.05):
        dev = flank_deviation(g.shape, g.profile, z)
        assert dev.flanks == 2 * spec.teeth
        assert dev.max_abs <= 1e-4  # 0.1 um: the bound
    for z in (spec.face_width - h + 0.05, spec.face_width - 0.5 * h, spec.face_width - 0.1):
        dev = upper_half_deviation(g, z)
        assert dev.flanks == 2 * spec.teeth
        assert dev.max_abs <= 1e-4


def tip_angle_near(g, z, expected):
    """Polar angle of the tip-land point of the section at z nearest to ``expected`` (rad)."""
    cut = section(g.shape, z)
    rad = np.hypot(cut.points[:, 0], cut.points[:, 1])
    tip = cut.points[np.abs(rad - g.profile.tip_radius) < 1e-6]
    ang = np.arctan2(tip[:, 1], tip[:, 0])
    return ang[np.argmin(np.abs(np.angle(np.exp(1j * (ang - expected)))))]


@pytest.mark.parametrize("which", ["apex", "gapped"])
def test_each_half_has_its_hand(which, request):
    """The tip lands turn with height as section_rotation says for the half's hand: the first
    half with the spec's hand, the second with the other (+ counter-clockwise for right hand)."""
    g = request.getfixturevalue(which)
    spec = g.spec
    b, h = spec.face_width, spec.half_face_width
    for hand, (z0, z1) in zip(spec.half_hands, ((0.2 * h, 0.8 * h), (b - 0.8 * h, b - 0.2 * h))):
        twin = replace(half_spec(spec), hand=hand)
        turn = section_rotation(twin, z1 - z0)  # expected turn from z0 to z1
        assert (turn > 0) == (hand == "right")
        assert abs(turn) > 2 * g.profile.tip_half_angle  # large enough for the sign to be seen
        a0 = tip_angle_near(g, z0, section_rotation(spec, z0) if z0 < h else section_rotation(spec, b - z0))
        a1 = tip_angle_near(g, z1, a0 + turn)
        # the same tip land followed from z0 to z1: its angle moved by the hand's turn
        assert abs(np.angle(np.exp(1j * (a1 - a0 - turn)))) <= 2 * g.profile.tip_half_angle + 1e-9
        assert abs(np.angle(np.exp(1j * (a1 - a0 + turn)))) > 2 * g.profile.tip_half_angle


def plane_heights(shape) -> list[float]:
    """Heights of the solid's planar faces normal to z (its end faces and the groove's walls)."""
    out = []
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        ad = BRepAdaptor_Surface(TopoDS.Face_s(exp.Current()))
        if ad.GetType() == GeomAbs_Plane and abs(abs(ad.Plane().Axis().Direction().Z()) - 1) < 1e-12:
            out.append(round(ad.Plane().Location().Z(), 9))
        exp.Next()
    return sorted(set(out))


def test_gap_measured_on_the_solid(gapped, apex):
    spec = gapped.spec
    h, gap = spec.half_face_width, spec.centre_gap
    assert plane_heights(gapped.shape) == pytest.approx([0.0, h, h + gap, spec.face_width], abs=1e-9)
    # in the gap the outline is the groove circle, 0.01 m_n inside the root circle
    mid = section(gapped.shape, h + gap / 2).points
    rad = np.hypot(mid[:, 0], mid[:, 1])
    assert rad.max() == pytest.approx(gapped.profile.root_radius - 0.01 * spec.module, abs=1e-7)
    # the herringbone's halves meet at the apex: no plane there, only the hub's and the ends
    assert plane_heights(apex.shape) == pytest.approx([-apex.spec.hub.hub_length, 0.0, apex.spec.face_width], abs=1e-9)


def test_registered_builder_and_exports(tmp_path):
    from geargen.cad.export import export_step, export_stl, read_step, read_stl
    from geargen.profile.tessellate import mesh_volume

    spec = herringbone(gap=1.0, teeth=13, face=6.0)  # small: the export's time is not what is tested
    g = build_part(spec, check=True)
    assert solid_volume(g.shape) == pytest.approx(expected_volume(spec, g.profile), rel=1e-6)
    export_step([g], tmp_path / "dh.step")
    step = read_step(tmp_path / "dh.step")
    assert solid_volume(step.shape) == pytest.approx(solid_volume(g.shape), rel=1e-6)
    record = export_stl(g, tmp_path / "dh.stl", chordal_tolerance=5e-3)
    tri = read_stl(tmp_path / "dh.stl")
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(g.shape, props)
    # every triangle within 5 um of the surface: the volumes differ by at most area x 5 um
    assert abs(mesh_volume(tri) - solid_volume(g.shape)) <= props.Mass() * 5e-3
    assert record.triangles == len(tri)


def test_spec_refusals():
    with pytest.raises(DesignError) as err:
        herringbone(gap=14.0)
    assert err.value.field == "centre_gap"
    with pytest.raises(DesignError) as err:
        GearSpec(teeth=19, module=1.0, pressure_angle=20 * DEG, face_width=10, helix_angle=20 * DEG, centre_gap=2.0)
    assert err.value.field == "centre_gap"  # only a double-helical gear has one
    with pytest.raises(DesignError) as err:
        DoubleHelicalGearSpec(teeth=19, module=1.0, pressure_angle=20 * DEG, face_width=10)
    assert err.value.field == "helix_angle"
    assert herringbone(gap=4.0).half_face_width == pytest.approx(5.0)
    assert herringbone(hand="left").half_hands == ("left", "right")


def test_command_builds_a_double_helical_gear(tmp_path):
    """geargen gear --kind double_helical ... --centre-gap: STEP and the gear data with gap and hands."""
    import json

    from geargen.cli import main
    rc = main(["gear", "--kind", "double_helical", "--teeth", "13", "--module", "1", "--helix-angle", "30",
               "--hand", "left", "--face-width", "6", "--centre-gap", "1", "--no-stl", "--out", str(tmp_path / "o")])
    assert rc == 0
    data = json.loads((tmp_path / "o" / "double_helical_13.json").read_text())
    assert data["double_helical"] == {"centre_gap": 1.0, "half_face_width": 2.5, "half_hands": ["left", "right"]}
    assert (tmp_path / "o" / "double_helical_13.step").stat().st_size > 0


def test_put_together_without_split_faces(gapped):
    """Face by face, no boolean: per half every tooth has exactly its profile's faces (none split at
    the apex or cut by a fuse), plus the two ends, the halves' two inner ends, the groove and the
    bore."""
    count = 0
    exp = TopExp_Explorer(gapped.shape, TopAbs_FACE)
    while exp.More():
        count += 1
        exp.Next()
    assert count == 2 * len(gapped.faces) * gapped.spec.teeth + 2 + 2 + 1 + 1
