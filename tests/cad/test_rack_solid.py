"""Rack solids: one valid closed solid, volume = transverse section area x face width (closed form,
geargen.families.rack.geometry, itself checked against the outline polygon in tests/core/test_rack.py), flanks
straight and on the exact flank lines measured on sections of the solid, STEP/STL/JSON from
``geargen gear --kind rack`` and from a ``[gear] kind = "rack"`` file."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from OCP.Bnd import Bnd_Box
from OCP.BRepBndLib import BRepBndLib

from geargen.cad.export import read_step
from geargen.cad.families import build_part
from geargen.cad.gear_solid import check_solid, solid_volume
from geargen.cad.measure import section
from geargen.families.rack.solid import build_rack, flank_straightness
from geargen.cli import main
from geargen.families.rack.geometry import rack_volume
from geargen.families.rack.spec import RackSpec

pytestmark = pytest.mark.slow

A20 = math.radians(20)

CASES = {
    "spur": dict(),
    "spur_generating_tip": dict(tip_rounding="generating", thinning=0.05),
    "helical_right": dict(helix_angle=math.radians(20)),
    "helical_left_generating": dict(helix_angle=math.radians(30), hand="left", tip_rounding="generating",
                                    root_fillet_coefficient=0.2, pressure_angle=math.radians(25)),
    "sharp_root": dict(root_fillet_coefficient=0.0, helix_angle=math.radians(10)),
    # h_f* = 1.6: ISO 53's 0.38 m fillet does not fit; the default is the full radius (no root land)
    "full_radius_root": dict(dedendum_coefficient=1.6, helix_angle=math.radians(15)),
}


def spec_of(case: str) -> RackSpec:
    kw = {"pressure_angle": A20, **CASES[case]}
    return RackSpec(teeth=12, module=2.0, face_width=16.0, pitch_line_height=9.0, name=case, **kw)


def bounds(shape) -> tuple[float, ...]:
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, box, False, False)
    return box.Get()


@pytest.mark.parametrize("case", list(CASES))
def test_rack_is_one_valid_solid_of_the_closed_form_volume(case):
    spec = spec_of(case)
    if case == "full_radius_root":
        assert spec.root_fillet_coefficient == pytest.approx(spec.max_root_fillet_coefficient(0.0), rel=1e-15)
        assert spec.root_fillet_coefficient < 0.38
    rack = build_part(spec, check=True)  # through the family registry
    assert check_solid(rack.shape) is None
    # the kernel's volume integration converges to ~1e-12; the closed form is exact
    assert solid_volume(rack.shape) == pytest.approx(rack_volume(spec), rel=1e-9)
    x0, y0, z0, x1, y1, z1 = bounds(rack.shape)
    assert (x0, y0, z0) == pytest.approx((0.0, 0.0, 0.0), abs=1e-7)
    assert (x1, y1, z1) == pytest.approx((spec.length, spec.height, spec.face_width), abs=1e-7)


@pytest.mark.parametrize("case", list(CASES))
def test_flanks_measured_on_the_solid_are_the_exact_straight_lines(case):
    """Sections of the solid at three heights (points found by Newton on the faces' own surfaces),
    every point on a straight flank within 0.1 um of the exact flank line (in practice ~1e-14 mm:
    the flanks are planes); and the points of one flank are collinear by their own fit."""
    spec = spec_of(case)
    rack = build_rack(spec)
    for z in (0.05 * spec.face_width, 0.5 * spec.face_width, 0.95 * spec.face_width):
        worst, count = flank_straightness(rack, z, samples_per_face=32)
        assert count > 4 * spec.teeth * 10  # both flanks of every tooth sampled
        assert worst < 1e-4  # mm = 0.1 um
    # straightness by itself: a line fitted to one flank's section points (no reference line)
    cut = section(rack.shape, 0.5 * spec.face_width, 32)
    o = rack.outline
    fitted = 0
    for e in set(cut.edge_index.tolist()):
        pts = cut.points[cut.edge_index == e]
        u = pts[:, 1] - spec.pitch_line_height
        if len(pts) < 8 or np.ptp(u) < 0.5 * (o.flank_tip_u - o.flank_root_u):
            continue  # not a flank (a land, an arc, an end face)
        if not ((u.min() >= o.flank_root_u - 1e-9) and (u.max() <= o.flank_tip_u + 1e-9)):
            continue
        centred = pts - pts.mean(axis=0)
        residual = np.linalg.svd(centred, compute_uv=False)[1] / math.sqrt(len(pts))
        assert residual < 1e-10
        fitted += 1
    assert fitted >= 2 * spec.teeth - 2  # the flanks cut by the ends may be short


def test_rack_command_writes_step_stl_json(tmp_path):
    out = tmp_path / "r"
    rc = main(["gear", "--kind", "rack", "--module", "2", "--teeth", "30", "--face-width", "20", "--height", "8",
               "--helix-angle", "15", "--tip-rounding", "generating", "--out", str(out), "--name", "slide"])
    assert rc == 0
    assert {p.name for p in out.iterdir()} == {"slide.step", "slide.stl", "slide.json", "manifest.json",
                                               "slide-drawing.svg", "slide-drawing.pdf"}
    data = json.loads((out / "slide.json").read_text())
    spec = RackSpec(teeth=30, module=2.0, pressure_angle=A20, face_width=20.0, pitch_line_height=8.0,
                    helix_angle=math.radians(15), tip_rounding="generating")
    assert data["kind"] == "rack" and data["teeth"] == 30
    assert data["length"] == pytest.approx(30 * math.pi * 2 / math.cos(math.radians(15)), rel=1e-14)
    assert data["volume"] == pytest.approx(rack_volume(spec), rel=1e-14)
    back = read_step(out / "slide.step")
    assert solid_volume(back.shape) == pytest.approx(rack_volume(spec), rel=1e-9)


def test_rack_design_file_and_option_errors(tmp_path, capsys):
    design = tmp_path / "slide.toml"
    design.write_text('[gear]\nkind = "rack"\ndiametral_pitch_per_in = 16\nteeth = 8\nface_width_in = 0.5\n'
                      'back_height_in = 0.25\nroot_fillet_coefficient = 0\n')
    assert main(["gear", str(design), "--out", str(tmp_path / "o"), "--no-stl"]) == 0
    data = json.loads((tmp_path / "o" / "slide.json").read_text())
    assert data["length_unit"] == "in" and data["back_height"] == pytest.approx(0.25, rel=1e-12)
    assert data["length"] == pytest.approx(8 * math.pi / 16, rel=1e-12)
    # an option a rack does not read, and a rack option on another kind, are refused by name
    assert main(["gear", "--kind", "rack", "--module", "2", "--teeth", "10", "--face-width", "5",
                 "--profile-shift", "0.2", "--out", str(tmp_path / "x")]) == 2
    assert "--profile-shift" in capsys.readouterr().err
    assert main(["gear", "--teeth", "10", "--module", "2", "--face-width", "5", "--height", "8",
                 "--out", str(tmp_path / "y")]) == 2
    assert "--height" in capsys.readouterr().err
    assert main(["gear", "--kind", "rack", "--module", "2", "--teeth", "10", "--face-width", "5",
                 "--tip-radius-coefficient", "0.9", "--tip-rounding", "generating", "--out", str(tmp_path / "z")]) == 2
    assert "--tip-radius-coefficient" in capsys.readouterr().err


@pytest.mark.parametrize("hand", ["right", "left"])
def test_helical_rack_teeth_follow_the_pinion_of_its_hand(hand):
    """The rack's hand is its pinion's: measured on the solid, a flank's crossing of the pitch line
    moves along the rack between the sections z = 0.1 b and 0.9 b by exactly what the pinion of the
    same hand (geargen.profile.section_rotation: its sections turn counter-clockwise for a right
    hand) carries its lowest tooth's pitch point, r * rotation, so the rack rolls with the pinion
    in every section. Crossing found by bisection on the section's flank points."""
    from geargen.design.gear import GearSpec
    from geargen.profile.tooth import section_rotation

    beta = math.radians(25)
    spec = RackSpec(teeth=6, module=2.0, pressure_angle=A20, face_width=16.0, pitch_line_height=9.0,
                    helix_angle=beta, hand=hand)
    pinion = GearSpec(teeth=15, module=2.0, pressure_angle=A20, face_width=16.0, helix_angle=beta, hand=hand)
    rack = build_rack(spec)

    def crossing(z):
        """x where the right flank of the space nearest x = L/2 crosses the pitch line, at height z."""
        cut = section(rack.shape, z, 64)
        u = cut.points[:, 1] - spec.pitch_line_height
        best = None
        for e in set(cut.edge_index.tolist()):
            rows = np.nonzero(cut.edge_index == e)[0]
            pu = u[rows]
            if pu.min() < 0 < pu.max() and np.ptp(cut.points[rows, 0]) < spec.transverse_pitch / 2:
                lo, hi = cut.params[rows][np.argmin(pu)], cut.params[rows][np.argmax(pu)]
                curve = cut.curves[e]
                for _ in range(80):  # bisection on the face parameter for height = pitch line
                    mid = 0.5 * (lo + hi)
                    if curve.point(mid)[1] - spec.pitch_line_height < 0:
                        lo = mid
                    else:
                        hi = mid
                x = curve.point(0.5 * (lo + hi))[0]
                # a right flank of a space leans outward going up: x grows with u
                rising = (cut.points[rows[np.argmax(pu)], 0] - cut.points[rows[np.argmin(pu)], 0]) > 0
                if rising and (best is None or abs(x - spec.length / 2) < abs(best - spec.length / 2)):
                    best = x
        return best

    z0, z1 = 0.1 * spec.face_width, 0.9 * spec.face_width
    moved = crossing(z1) - crossing(z0)
    expected = pinion.reference_radius * (section_rotation(pinion, z1) - section_rotation(pinion, z0))
    # the nearest space may be another one at z1: equal up to whole transverse pitches
    pt = spec.transverse_pitch
    assert abs((moved - expected) - pt * round((moved - expected) / pt)) < 1e-9
    wrong = moved + expected  # what a rack of the other hand would give: not a whole number of pitches
    assert abs(wrong - pt * round(wrong / pt)) > 0.1


@pytest.mark.parametrize("case", [c for c in CASES if "helical" in c or CASES[c].get("helix_angle")])
def test_helical_rack_faces_are_exact_prism_faces(case):
    """A helical rack put together face by face keeps every face exact: planes, and cylinders whose
    axes run along the teeth ((sin beta, 0, cos beta), signed by hand) with the section's arc radii;
    one face per section segment whose strip meets the box, plus the four walls and the back."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Cylinder, GeomAbs_Plane
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS
    spec = spec_of(case)
    rack = build_rack(spec)
    beta = spec.signed_helix_angle
    teeth = np.array([math.sin(beta), 0.0, math.cos(beta)])
    radii = {round(r, 9) for r in (rack.outline.tip_radius, rack.outline.root_radius) if r > 0}
    kinds = []
    exp = TopExp_Explorer(rack.shape, TopAbs_FACE)
    while exp.More():
        ad = BRepAdaptor_Surface(TopoDS.Face_s(exp.Current()))
        kinds.append(ad.GetType())
        if ad.GetType() == GeomAbs_Cylinder:
            axis = ad.Cylinder().Axis().Direction()
            assert abs(abs(np.dot([axis.X(), axis.Y(), axis.Z()], teeth)) - 1) < 1e-14
            assert round(ad.Cylinder().Radius(), 9) in radii
        exp.Next()
    assert set(kinds) <= {GeomAbs_Plane, GeomAbs_Cylinder}
    # every tooth's arcs (two a rounded tip, two a root fillet; the ends may cut one off)
    arcs = 2 * (rack.outline.tip_radius > 0) + 2 * (rack.outline.root_radius > 0)
    assert kinds.count(GeomAbs_Cylinder) >= arcs * (spec.teeth - 1)
