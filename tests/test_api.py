"""geargen.api: a gear, a pair and the robot joint used as ordinary CadQuery objects."""

import json
import math

import pytest

from geargen import api
from geargen.errors import DesignError
from tests.conftest import ASSEMBLY_DESIGNS

REL = 1e-6  # the Gauss-Kronrod volumes below are good to ~1e-9 relative; booleans keep the faces exact


def _volume(shape) -> float:
    from geargen.cad.gear_solid import solid_volume
    return solid_volume(shape.wrapped)


@pytest.fixture(scope="module")
def gear():
    return api.gear(teeth=21, module=1, pressure_angle=20, face_width=5, bore=6)


@pytest.mark.slow
def test_gear_is_a_solid_in_mm_with_its_bore(gear):
    import cadquery as cq
    assert isinstance(gear, cq.Solid) and gear.isValid()
    box = gear.BoundingBox()
    assert box.zmin == pytest.approx(0, abs=1e-6) and box.zmax == pytest.approx(5, abs=1e-6)
    tip_radius = (21 + 2) * 1 / 2  # standard addendum, no shift
    assert box.xmax == pytest.approx(tip_radius, abs=1e-6)  # tooth 0 on +x
    # a spur gear is a prism: volume = face width x (outline area - bore), the outline between
    # the root and tip circles
    bore_area = math.pi * 3 ** 2
    assert math.pi * 9.25 ** 2 - bore_area < _volume(gear) / 5 < math.pi * 11.5 ** 2 - bore_area


@pytest.mark.slow
def test_gear_in_a_user_plate_boolean_volumes(gear):
    """A plate through the middle of the face, the gear cut out of it; a hub fused under the gear."""
    import cadquery as cq
    v_gear = _volume(gear)
    plate = cq.Workplane("XY").box(40, 40, 3, centered=(True, True, False)).translate((0, 0, 1)).val()
    pocket = plate.cut(gear)
    # the gear is prismatic along z: 3 mm of its 5 mm face lie in the plate
    assert _volume(pocket) == pytest.approx(40 * 40 * 3 - v_gear * 3 / 5, rel=REL)
    hub = cq.Workplane("XY").circle(8).circle(3).extrude(-4).val()  # under the face, around the bore
    fused = gear.fuse(hub).clean()
    assert isinstance(fused, cq.Shape) and len(fused.Solids()) == 1
    assert _volume(fused) == pytest.approx(v_gear + math.pi * (8 ** 2 - 3 ** 2) * 4, rel=REL)


@pytest.mark.slow
def test_gear_exports_as_step_and_reads_back(gear, tmp_path):
    import cadquery as cq
    path = tmp_path / "gear.step"
    cq.exporters.export(gear, str(path))
    back = cq.importers.importStep(str(path)).val()
    assert _volume(back) == pytest.approx(_volume(gear), rel=REL)


@pytest.mark.slow
def test_inch_gear_comes_in_mm():
    g = api.gear(teeth=20, diametral_pitch=32, face_width=0.125)
    assert g.BoundingBox().zlen == pytest.approx(0.125 * 25.4, abs=1e-6)
    assert g.BoundingBox().xmax == pytest.approx((20 + 2) / 32 / 2 * 25.4, abs=1e-6)


@pytest.mark.slow
def test_pair_placed_in_mesh_with_the_backlash_of_its_thinning():
    import cadquery as cq
    pair = api.pair(teeth=(18, 24), module=3, face_width=10, thinning=(0.05, 0.05))
    assert isinstance(pair, cq.Assembly)
    g1, g2 = (pair.objects[f"gears_assembly/gear {i}"] for i in (1, 2))
    s1, s2 = g1.obj.moved(g1.loc), g2.obj.moved(g2.loc)
    assert s2.Center().x == pytest.approx(3 * (18 + 24) / 2, abs=1e-9)  # no shift: the standard centre distance
    # the teeth sit centred in the gaps: each flank pair is half the normal backlash apart, the
    # circumferential thinning of both gears at the reference (= working) circle times cos(alpha)
    assert s1.distance(s2) == pytest.approx((0.05 + 0.05) * math.cos(math.radians(20)) / 2, rel=1e-4)


def test_errors_name_the_keyword():
    with pytest.raises(DesignError) as err:
        api.gear(teeth=21, module=1)
    assert err.value.field == "face_width"
    with pytest.raises(DesignError) as err:
        api.gear(teeth=2, module=1, face_width=5)
    assert err.value.field == "teeth" and "[4, 2000]" in str(err.value)
    with pytest.raises(DesignError) as err:
        api.gear(teeth=12, module=1, face_width=5, profile_shift=-3)
    assert err.value.field == "profile_shift" and "-" in err.value.allowed  # a negative bound stays one
    with pytest.raises(DesignError) as err:
        api.pair(teeth=(12, 24), module=3, face_width=10, centre_distance=10)
    assert err.value.field == "centre_distance"
    with pytest.raises(DesignError) as err:
        api.assembly(ASSEMBLY_DESIGNS["robot_joint"], position="sideways")
    assert err.value.field == "position"


@pytest.mark.slow
def test_robot_joint_assembly_is_the_build(built_assemblies, tmp_path):
    import cadquery as cq
    from OCP.BRepBndLib import BRepBndLib
    from OCP.Bnd import Bnd_Box
    folder = built_assemblies["robot_joint"]
    manifest = json.loads((folder / "manifest.json").read_text())
    joint = api.assembly(ASSEMBLY_DESIGNS["robot_joint"])
    assert isinstance(joint, cq.Assembly) and joint.name == manifest["design"]["name"]
    leaves = {path.split("/")[-1]: a for path, a in joint.objects.items() if a.obj is not None}
    assert sorted(leaves) == sorted(manifest["parts"])
    for name, entry in manifest["parts"].items():
        part = leaves[name]
        assert part.parent.name == f"{entry['group']}_assembly"
        assert part.color.toTuple() == pytest.approx(tuple(entry["colour_rgba"]), abs=1e-6)
        matrix = [part.loc.wrapped.Transformation().Value(i, j) for i in range(1, 4) for j in range(1, 5)]
        assert matrix == pytest.approx(sum(entry["placement_matrix_mm"][:3], []), abs=1e-11)  # manifest: 12 decimals

    def box(shape):
        b = Bnd_Box()
        BRepBndLib.AddOptimal_s(shape, b, False, False)
        return b.Get()

    for name in ("output", "carriage", "input"):
        placed = leaves[name].obj.moved(leaves[name].loc)
        assert box(placed.wrapped) == pytest.approx(box(built_assemblies.step("robot_joint", name).shape), abs=1e-6)
    # the whole assembly exports through CadQuery and reads back with every part's volume
    path = tmp_path / "joint.step"
    joint.export(str(path))
    back = cq.importers.importStep(str(path)).val()
    assert len(back.Solids()) == len(manifest["parts"])
    # the same geometry, solid by solid: the kernel's plain volume (the adaptive one takes minutes on
    # re-read large gears) is deterministic for most faces, but on the re-read bevel gears' B-spline
    # faces it scatters ~1e-6; there the adaptive integration decides (measured 8e-13 apart)
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    def adaptive_volume(solid):
        props = GProp_GProps()
        BRepGProp.VolumeProperties_s(solid.wrapped, props, 1e-10, False)
        return props.Mass()

    for made, read in zip(joint.toCompound().Solids(), back.Solids(), strict=True):
        if read.Volume() != pytest.approx(made.Volume(), rel=1e-9):
            assert adaptive_volume(read) == pytest.approx(adaptive_volume(made), rel=1e-9)
    volume = sum(s.Volume() for s in back.Solids())
    assert volume == pytest.approx(sum(entry["volume_mm3"] for entry in manifest["parts"].values()), rel=1e-3)
