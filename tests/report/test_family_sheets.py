"""Drawings and JSON of the families that are not one cylindrical gear (issue 27): a bevel gear, the
robot joint's bevel pair as built, a worm and its wheel, a rack and the robot joint's one-piece cluster.

Each sheet is read back (the SVG's data block; the PDF's text through pdftotext) and its numbers
compared with the part's JSON; the JSON's numbers are checked against closed forms written out here.
"""

from __future__ import annotations

import math
import re
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from geargen.report.drawing import COLUMNS_MM, DATA_BLOCK, MIN_FONT_PT, MM_PER_PT, PAD_MM, ROW_PAD_MM

SVG_NS = "{http://www.w3.org/2000/svg}"
#: half a unit of the sheet's last decimal (4 in mm, 5 in inches): a value read back from the sheet
#: is the JSON's rounded to it
ROUNDING = {"mm": 0.5e-4, "in": 0.5e-5}


def sheet_rows(svg: Path) -> dict[str, tuple[str, str]]:
    """The data block read back from the SVG: {name: (symbol, value)}, each cell's lines joined. The
    lines of one cell are one line height apart, rows a line height and two row paddings: a name
    line closer than half way between to the one above continues that row's name."""
    texts = []
    for t in ET.parse(svg).getroot().iter(f"{SVG_NS}text"):
        texts.append(("".join(t.itertext()), float(t.get("x")) * MM_PER_PT, float(t.get("y")) * MM_PER_PT))
    cols = [DATA_BLOCK[0] + PAD_MM, DATA_BLOCK[0] + COLUMNS_MM[0] + PAD_MM,
            DATA_BLOCK[0] + COLUMNS_MM[0] + COLUMNS_MM[1] + PAD_MM]
    line_h = MIN_FONT_PT * 1.2 * MM_PER_PT
    starts: list[list] = []  # [y of the row's first line, name]
    for y, text in sorted((y, text) for text, x, y in texts if abs(x - cols[0]) < 1e-3):
        if starts and y - starts[-1][2] < line_h + ROW_PAD_MM:
            starts[-1][1] += " " + text
            starts[-1][2] = y
        else:
            starts.append([y, text, y])
    rows = {}
    for i, (y, name, _) in enumerate(starts):
        below = starts[i + 1][0] if i + 1 < len(starts) else math.inf
        cell = [[text for text, x, yy in sorted(texts, key=lambda t: t[2]) if abs(x - c) < 1e-3 and y - 1e-3 <= yy < below - 1e-3]
                for c in cols[1:]]
        rows.setdefault(name, (" ".join(cell[0]), " ".join(cell[1])))
    return rows


def number(text: str) -> float:
    """The first number of a sheet value (``0.26857 in``, ``⌀0.96374``)."""
    return float(re.search(r"[-+]?\d+\.?\d*(?:e[-+]?\d+)?", text).group())


def assert_lengths(rows, data, pairs, unit):
    """Each sheet row ``name`` shows the JSON's ``key`` to the sheet's rounding."""
    for name, key in pairs:
        assert name in rows, name
        assert number(rows[name][1]) == pytest.approx(data[key], abs=ROUNDING[unit] * 1.0001), (name, key)


def pdf_text(poppler, pdf: Path) -> str:
    out = subprocess.run([poppler["pdftotext"], str(pdf), "-"], capture_output=True, text=True, check=True,
                         timeout=120).stdout
    return "".join(out.split())


def assert_pdf_holds(poppler, pdf, rows):
    """Every name and value of the SVG's data block is in the PDF's text too (one figure, two files)."""
    compact = pdf_text(poppler, pdf)
    for name, (_, value) in rows.items():
        assert "".join(name.split()) in compact, name
        for word in value.split():
            assert word in compact, (name, word)


# ---------------------------------------------------------------- bevel

BEVEL_LENGTHS = [("Outer cone distance", "outer_cone_distance"), ("Mean cone distance", "mean_cone_distance"),
                 ("Face width (along the cone)", "face_width"), ("Reference diameter at the heel", "reference_diameter"),
                 ("Outside diameter as built", "outside_diameter_as_built"),
                 ("Mounting distance (apex to back)", "mounting_distance"), ("Crown to back", "crown_to_back"),
                 ("Heel chordal tooth thickness", "chordal_thickness_heel"),
                 ("Heel chordal height", "chordal_height_heel"),
                 ("Mean chordal tooth thickness", "chordal_thickness_mean"),
                 ("Mean chordal height", "chordal_height_mean")]
BEVEL_ANGLES = [("Pitch cone angle", "pitch_cone_angle_deg"), ("Face (tip) cone angle", "tip_cone_angle_deg"),
                ("Root cone angle", "root_cone_angle_deg")]


def check_bevel_sheet(files, data, poppler):
    rows = sheet_rows(files["svg"])
    assert_lengths(rows, data, BEVEL_LENGTHS, data["length_unit"])
    for name, key in BEVEL_ANGLES:
        assert number(rows[name][1]) == pytest.approx(data[key], abs=0.5e-4 * 1.0001)  # 4 decimals of a degree
    assert_pdf_holds(poppler, files["pdf"], rows)
    return rows


def bevel_closed_form(z, z_mate, m, b, shaft_deg, back):
    """Cones and mounting distance of a standard straight bevel gear, written out: tan delta = sin S /
    (z2/z1 + cos S), R_e = z m / (2 sin delta), theta_f = atan(1.25 m / R_e); a flat back (the plane
    through the heel root circle) lies R_e cos(delta - theta_f) from the apex, the heel sphere's pole R_e."""
    s = math.radians(shaft_deg)
    delta = math.atan(math.sin(s) / (z_mate / z + math.cos(s)))
    re_ = z * m / (2 * math.sin(delta))
    theta_f = math.atan(1.25 * m / re_)
    return {"delta": delta, "R_e": re_, "mounting": re_ * math.cos(delta - theta_f) if back == "flat" else re_}


def test_bevel_gear_command_json_and_drawing_agree(tmp_path, poppler):
    from geargen.cli import main
    out = tmp_path / "bevel"
    assert main(["gear", "--kind", "bevel", "--teeth", "15", "--mate-teeth", "30", "--module", "1.0",
                 "--face-width", "5", "--accuracy-grade", "7", "--bevel-thinning", "0.02", "--no-stl",
                 "--out", str(out), "--name", "bev"]) == 0
    import json
    data = json.loads((out / "bev.json").read_text())
    assert data["back"] == "flat" and data["accuracy"]["grade"] == 7 and data["accuracy"]["standard"] == "ISO 17485"
    rows = check_bevel_sheet({"svg": out / "bev-drawing.svg", "pdf": out / "bev-drawing.pdf"}, data, poppler)
    assert "ISO 17485 grade 7" in rows["Accuracy grade"][1]
    ref = bevel_closed_form(15, 30, 1.0, 5.0, 90.0, "flat")
    # closed forms in double precision: 1e-12 mm is rounding of a 15 mm quantity
    assert data["mounting_distance"] == pytest.approx(ref["mounting"], abs=1e-12)
    assert data["outer_cone_distance"] == pytest.approx(ref["R_e"], abs=1e-12)
    assert math.radians(data["pitch_cone_angle_deg"]) == pytest.approx(ref["delta"], abs=1e-14)
    # chordal tooth at the heel against the back-cone rule (KHK): s_c = s - s^3 / (6 d^2),
    # h_c = h_a + s^2 cos(delta) / (4 d), s = pi m / 2 - thinning, d = z m. The thickness agrees to the
    # series' next term s^5 / (120 d^4) (8e-8 mm here); the height differs by the sphere's curvature
    # between pitch and tip cone, of order h_a theta_a^2 = 1 * 0.06^2 = 3.5e-3 mm: bound 4e-3
    s, d = math.pi / 2 - 0.02, 15.0
    assert data["chordal_thickness_heel"] == pytest.approx(s - s ** 3 / (6 * d * d), abs=s ** 5 / (120 * d ** 4) * 1.01)
    assert data["chordal_height_heel"] == pytest.approx(1.0 + s * s * math.cos(ref["delta"]) / (4 * d), abs=4e-3)
    # the tooth is a cone through the apex: at the mean sphere every chord is the heel's times R_m / R_e
    # (1e-12: double-precision rounding of millimetre quantities)
    k = data["mean_cone_distance"] / data["outer_cone_distance"]
    assert data["chordal_thickness_mean"] == pytest.approx(k * data["chordal_thickness_heel"], abs=1e-12)
    assert data["chordal_height_mean"] == pytest.approx(k * data["chordal_height_heel"], abs=1e-12)


def test_bevel_grade_out_of_range_names_the_option(tmp_path, capsys):
    from geargen.cli import main
    code = main(["gear", "--kind", "bevel", "--teeth", "15", "--mate-teeth", "30", "--module", "1.0",
                 "--face-width", "5", "--accuracy-grade", "1", "--out", str(tmp_path / "x")])
    assert code != 0 and code != 4
    assert "--accuracy-grade" in capsys.readouterr().err


@pytest.fixture(scope="module")
def robot_joint_drawings(tmp_path_factory):
    """The robot joint resolved once and its drawings written (as the build's drawings step)."""
    from geargen import pipeline
    root = Path(__file__).resolve().parents[2]
    layout = pipeline.place(pipeline.load(root / "assemblies" / "robot_joint.toml"))
    folder = tmp_path_factory.mktemp("robot_joint")
    files = pipeline.drawings(layout, folder)
    return layout, files


def test_robot_joint_bevel_pair_drawings_and_json(robot_joint_drawings, poppler):
    import json

    from geargen.cad.families import toothed_solid
    from geargen.cad.parts import bounding_box
    from geargen.drives.dual_pinion.bevel import bevel_drive
    from geargen.model.components import Toothed
    from geargen.units import from_mm, to_mm
    layout, files = robot_joint_drawings
    placed = bevel_drive(layout)
    for spec, mate in ((placed.gear, placed.pinion), (placed.pinion, placed.gear)):
        data = json.loads(files[f"drawing:{spec.name}:json"].read_text())
        rows = check_bevel_sheet({"svg": files[f"drawing:{spec.name}:svg"], "pdf": files[f"drawing:{spec.name}:pdf"]},
                                 data, poppler)
        assert data["back"] == "flat"  # as the hardware cuts it (drives/dual_pinion/hardware.py)
        assert data["mating_gear"]["name"] == mate.name
        u = data["length_unit"]
        assert number(rows["Pair backlash, heel pitch arc"][1]) == pytest.approx(
            data["mating_gear"]["backlash_circumferential"], abs=ROUNDING[u] * 1.0001)
        # the pair's backlash is the sum of the two thinnings (bevel_drive splits it equally)
        assert data["mating_gear"]["backlash_circumferential"] == pytest.approx(
            float(from_mm(spec.thinning + mate.thinning, u)), rel=1e-12)
        ref = bevel_closed_form(spec.teeth, spec.mate_teeth, spec.module, spec.face_width, 90.0, "flat")
        assert data["mounting_distance"] == pytest.approx(float(from_mm(ref["mounting"], u)), rel=1e-12)
        # measured on the solid the build cuts (apex at the origin, axis +z, tooth 0 on +x): its back
        # face is the farthest from the apex, the crown of tooth 0 the farthest along +x (2e-7 mm: the
        # kernel's optimal box, enlarged by the edges' 1e-7 mm tolerance; far below the sheet's 0.25 um)
        lo, hi = bounding_box(toothed_solid(Toothed(spec, spec.back)).shape)
        assert hi[2] == pytest.approx(to_mm(data["mounting_distance"], u), abs=2e-7)
        assert hi[0] == pytest.approx(to_mm(data["outside_diameter_as_built"], u) / 2, abs=2e-7)


def test_gear_command_bevel_is_the_builds_solid(robot_joint_drawings):
    """`geargen gear --kind bevel` with the pair's numbers describes the spec the build cuts: same
    spec (back included) and the same solid volume."""
    import argparse

    from geargen.cad.families import build_part
    from geargen.commands.gear import add_arguments, spec_from_args
    from geargen.drives.dual_pinion.bevel import bevel_drive
    from geargen.units import from_mm
    layout, _ = robot_joint_drawings
    gear = bevel_drive(layout).gear
    p = argparse.ArgumentParser()
    add_arguments(p)
    u = gear.length_unit
    args = p.parse_args(["--kind", "bevel", "--teeth", str(gear.teeth), "--mate-teeth", str(gear.mate_teeth),
                         "--diametral-pitch", f"{25.4 / gear.module!r}", "--face-width", repr(float(from_mm(gear.face_width, u))),
                         "--bore", repr(float(from_mm(gear.bore_diameter, u))),
                         "--bevel-thinning", repr(float(from_mm(gear.thinning, u))), "--name", gear.name])
    spec, _ = spec_from_args(args)
    for field in ("teeth", "mate_teeth", "back", "shaft_angle", "pressure_angle", "profile_shift"):
        assert getattr(spec, field) == getattr(gear, field), field
    # lengths through the inch option text and back: 1e-12 relative is double rounding
    for field in ("module", "face_width", "bore_diameter", "thinning"):
        assert getattr(spec, field) == pytest.approx(getattr(gear, field), rel=1e-12), field
    assert build_part(spec).back == "flat"


# ---------------------------------------------------------------- cluster


def _tooth_centre(shape, profile, z: float, guess: float) -> float:
    """The azimuth (rad) of the tooth centre nearest ``guess`` on the solid's section at ``z``: the
    mean of the two flanks' crossings of the reference circle (section samples within 2 % of a module
    of it, on either side of the guess, averaged; the flanks are mirror images, so the mean is the
    centre up to the sampling's asymmetry, about one sample step over r: < 1e-3 rad here)."""
    import numpy as np

    from geargen.cad.measure import section
    cut = section(shape, z, 512)
    r = np.hypot(cut.points[:, 0], cut.points[:, 1])
    theta = np.arctan2(cut.points[:, 1], cut.points[:, 0])
    off = (theta - guess + math.pi) % (2 * math.pi) - math.pi
    half_pitch = math.pi / profile.spec.teeth
    near = (np.abs(r - profile.reference_radius) < 0.02 * profile.spec.module) & (np.abs(off) < half_pitch)
    left, right = off[near & (off > 0)], off[near & (off < 0)]
    assert left.size and right.size
    return guess + (left.mean() + right.mean()) / 2


def check_cluster_sheet(files, data, poppler):
    u = data["length_unit"]
    rows = sheet_rows(files["svg"])
    assert number(rows["Tooth phase, large to small"][1]) == pytest.approx(data["tooth_phase_deg"], abs=0.5e-4 * 1.0001)
    assert number(rows["Tooth phase tolerance"][1].lstrip("± ")) == pytest.approx(
        data["tooth_phase_tolerance_deg"], abs=0.5e-4 * 1.0001)
    assert_lengths(rows, data, [("Gap between the faces", "axial_gap"), ("Overall length", "overall_length"),
                                ("Bore (one, through both gears)", "bore_diameter")], u)
    for key, label in (("large", "Large gear"), ("small", "Small gear")):
        assert_lengths(rows, data[key], [(f"{label}: tip diameter", "tip_diameter"),
                                         (f"{label}: face width", "face_width")], u)
        assert rows[f"{label}: tooth data sheet"][1] == data[key]["tooth_data_drawing"]
    assert_pdf_holds(poppler, files["pdf"], rows)


def test_robot_joint_cluster_one_drawing(robot_joint_drawings, poppler):
    """The robot joint's clusters (two identical, each a large gear bonded on the small gear's shaft):
    one cluster sheet and JSON; the phase read from the placements, the tolerance from mesh 1's range."""
    import json
    layout, files = robot_joint_drawings
    data = json.loads(files["drawing:cluster:json"].read_text())
    check_cluster_sheet({"svg": files["drawing:cluster:svg"], "pdf": files["drawing:cluster:pdf"]}, data, poppler)
    assert not any(k.startswith("drawing:cluster_a") or k.startswith("drawing:cluster_b") for k in files)
    # both clusters' placements turn large and small gear together: the phase as placed is that
    # difference (1e-12 rad: rounding)
    by = {p.name: p for p in layout.gears}
    for side in ("a", "b"):
        large, small = by[f"cluster_large_{side}"], by[f"cluster_small_{side}"]
        placed = (small.rotation_at(small.spec, small.face_z(small.spec)[0])
                  - large.rotation_at(large.spec, large.face_z(large.spec)[0]))
        assert math.radians(data["tooth_phase_as_placed_deg"]) == pytest.approx(placed, abs=1e-12)
    # tolerance: min over the clusters' meshes of (j_max - j_min) / (2 r), written out
    expected = min((m.backlash_max - m.backlash_min) / (2 * g.reference_radius)
                   for m in layout.meshes for g in (m.gear1, m.gear2) if g.name in ("cluster_large", "cluster_small"))
    assert math.radians(data["tooth_phase_tolerance_deg"]) == pytest.approx(expected, rel=1e-12)
    for gear in ("cluster_large", "cluster_small"):
        assert json.loads(files[f"drawing:{gear}:json"].read_text())["cluster"]["drawing"] == "cluster-drawing.svg"


def test_one_piece_cluster_phase_is_the_solids(tmp_path, poppler):
    """A one-piece cluster whose small gear is turned by 0.1 rad: the JSON's phase is the placed
    model's, measured on the built cluster solid's sections (tooth centres of both gears)."""
    import dataclasses
    import json

    from geargen import pipeline
    from geargen.cad.gear_solid import build_cluster
    from geargen.design.cluster import ClusterSpec
    from geargen.model.cluster_data import cluster_data, drive_clusters
    from geargen.profile.tooth import tooth_profile
    from geargen.report.drawing_cluster import cluster_drawings
    root = Path(__file__).resolve().parents[2]
    text = (root / "assemblies" / "robot_joint.toml").read_text().replace('cluster = "separate"', 'cluster = "one_piece"')
    design_file = tmp_path / "one_piece.toml"
    design_file.write_text(text)
    layout = pipeline.place(pipeline.load(design_file))
    gears = tuple(dataclasses.replace(p, spec=dataclasses.replace(p.spec, relative_phase=0.1))
                  if isinstance(p.spec, ClusterSpec) else p for p in layout.gears)
    layout = dataclasses.replace(layout, gears=gears)
    (cluster,) = drive_clusters(layout)
    assert cluster.one_piece
    data = cluster_data(layout, cluster)
    files = cluster_drawings(data, cluster.large, cluster.small, tmp_path, cluster.name, "test", str(design_file))
    check_cluster_sheet(files, data, poppler)
    spec = cluster.large_placement.spec
    solid = build_cluster(spec)
    lp, sp = tooth_profile(spec.large, warn=False), tooth_profile(spec.small, warn=False)
    eps = 0.01 * spec.large.face_width  # just inside each face (spur gears: the section is the face's)
    large_centre = _tooth_centre(solid.shape, lp, eps, 0.0)
    small_centre = _tooth_centre(solid.shape, sp, spec.small_gear_z + eps, math.radians(data["tooth_phase_deg"]))
    # 2e-3 rad: the two centres' sampling error (< 1e-3 rad each, _tooth_centre)
    assert small_centre - large_centre == pytest.approx(math.radians(data["tooth_phase_deg"]), abs=2e-3)
    assert math.radians(data["tooth_phase_deg"]) == pytest.approx(0.1, abs=1e-12)  # within half a pitch: as set
    assert json.loads(json.dumps(data))["construction"] == "one piece"


# ---------------------------------------------------------------- worm and worm wheel

WORM_OPTIONS = ["--module", "3", "--starts", "2", "--wheel-teeth", "30", "--worm-diameter", "44", "--worm-length", "45",
                "--wheel-width", "28", "--wheel-profile-shift", "0.3", "--backlash", "0.02", "--no-stl"]


@pytest.fixture(scope="module")
def worm_set_outputs(tmp_path_factory):
    import json

    from geargen.cli import main
    out = {}
    for kind in ("worm", "worm_wheel"):
        folder = tmp_path_factory.mktemp(kind)
        assert main(["gear", "--kind", kind, *WORM_OPTIONS, "--out", str(folder / "o"), "--name", kind]) == 0
        o = folder / "o"
        out[kind] = (json.loads((o / f"{kind}.json").read_text()),
                     {"svg": o / f"{kind}-drawing.svg", "pdf": o / f"{kind}-drawing.pdf"})
    return out


def test_worm_json_closed_forms(worm_set_outputs):
    data, _ = worm_set_outputs["worm"]
    m, z1, z2, d1, x2 = 3.0, 2, 30, 44.0, 0.3
    gamma = math.atan(z1 * m / d1)  # tan(gamma) = z1 m_x / d1
    # closed forms in double precision: 1e-12 is rounding of quantities of tens of mm
    assert data["lead"] == pytest.approx(z1 * math.pi * m, abs=1e-12)
    assert data["axial_pitch"] == pytest.approx(math.pi * m, abs=1e-12)
    assert math.radians(data["lead_angle_deg"]) == pytest.approx(gamma, abs=1e-14)
    assert data["centre_distance"] == pytest.approx((d1 + z2 * m) / 2 + x2 * m, abs=1e-12)
    assert data["worm_axial_thread_thickness"] == pytest.approx(math.pi * m / 2, abs=1e-12)  # backlash on the wheel
    assert data["worm_normal_thread_thickness"] == pytest.approx(math.pi * m / 2 * math.cos(gamma), abs=1e-12)
    hob = data["hob"]
    # the hob: the worm's thread, tip raised by c = (1.25 - 1) m_x: d_a0 = d1 + 2 * 1.25 m_x
    assert hob["tip_diameter"] == pytest.approx(d1 + 2 * 1.25 * m, abs=1e-12)
    assert hob["tip_clearance"] == pytest.approx(0.25 * m, abs=1e-12)
    assert hob["lead"] == data["lead"] and hob["reference_diameter"] == data["worm_reference_diameter"]
    # the pair check finds the design backlash at the design centre distance (its search tolerance 1e-7 mm)
    assert data["pair_check"]["backlash_circumferential"] == pytest.approx(0.02, abs=1e-6)
    assert not data["pair_check"]["interference"]


def test_wheel_tooth_thickness_is_the_generated_wheels(worm_set_outputs):
    """The wheel's tooth thickness at d_2 in the mid plane: the JSON's closed form (rack of m_x, alpha_x,
    shifted x2 m_x, less the thinning) against the wheel the worm generates there, measured on its
    envelope section (geargen.families.worm.geometry.wheel_section, 2000 flank samples)."""
    from geargen.families.worm.geometry import space_width_at_radius, wheel_section, worm_geometry
    from geargen.families.worm.spec import WormGearSet
    data, _ = worm_set_outputs["worm_wheel"]
    m, x2 = 3.0, 0.3
    alpha_x = math.radians(data["axial_pressure_angle_deg"])
    assert data["wheel_tooth_thickness_transverse"] == pytest.approx(
        m * (math.pi / 2 + 2 * x2 * math.tan(alpha_x)) - 0.02, abs=1e-12)
    s = WormGearSet(axial_module=m, starts=2, wheel_teeth=30, worm_reference_diameter=44.0,
                    pressure_angle=math.radians(20), worm_face_length=45, wheel_face_width=28, wheel_profile_shift=x2,
                    backlash=0.02)
    g = worm_geometry(s)
    r2 = g.wheel_reference_diameter / 2
    measured = 2 * math.pi * r2 / 30 - space_width_at_radius(wheel_section(s, g, 0.0, n_flank=2000), r2)
    # 2e-6 mm: linear interpolation between envelope samples, 2.3e-7 mm at 2000 samples (1.8e-5 at 400:
    # it falls as 1 / n^2)
    assert measured == pytest.approx(data["wheel_tooth_thickness_transverse"], abs=2e-6)


def test_worm_and_wheel_sheets_read_back(worm_set_outputs, poppler):
    worm, worm_files = worm_set_outputs["worm"]
    rows = sheet_rows(worm_files["svg"])
    assert_lengths(rows, worm, [("Lead", "lead"), ("Axial pitch", "axial_pitch"),
                                ("Reference diameter", "worm_reference_diameter"),
                                ("Tip diameter", "worm_tip_diameter"), ("Root diameter", "worm_root_diameter"),
                                ("Axial thread thickness at d_1", "worm_axial_thread_thickness"),
                                ("Normal thread thickness at d_1", "worm_normal_thread_thickness"),
                                ("Centre distance", "centre_distance"),
                                ("Design backlash (arc at wheel d)", "backlash_circumferential")], "mm")
    assert number(rows["Lead angle"][1]) == pytest.approx(worm["lead_angle_deg"], abs=0.5e-4 * 1.0001)
    assert number(rows["Backlash, pair check"][1]) == pytest.approx(worm["pair_check"]["backlash_circumferential"],
                                                                  abs=ROUNDING["mm"] * 1.0001)
    assert_pdf_holds(poppler, worm_files["pdf"], rows)
    wheel, wheel_files = worm_set_outputs["worm_wheel"]
    rows = sheet_rows(wheel_files["svg"])
    assert_lengths(rows, wheel, [("Throat diameter", "throat_diameter"), ("Outside diameter", "wheel_outside_diameter"),
                                 ("Root diameter", "wheel_root_diameter"), ("Face width", "wheel_face_width"),
                                 ("Tooth thickness at d_2, mid plane", "wheel_tooth_thickness_transverse"),
                                 ("Centre distance", "centre_distance")], "mm")
    assert_lengths(rows, wheel["hob"], [("Hob tip diameter", "tip_diameter"), ("Hob tip clearance", "tip_clearance"),
                                        ("Hob lead", "lead"), ("Hob axial thread thickness", "axial_thread_thickness"),
                                        ("Hob normal thread thickness", "normal_thread_thickness")], "mm")
    assert_pdf_holds(poppler, wheel_files["pdf"], rows)


# ---------------------------------------------------------------- rack


def _pin_rest_height(outline, diameter: float) -> float:
    """Height of the centre of a pin resting in the space at x = 0 on the rack's modelled outline
    (:meth:`geargen.families.rack.geometry.RackOutline.height_at`, fillets and lands included), found numerically:
    the centre height where the nearest outline point (200001 samples over two pitches) is D / 2 away
    (bisection; the nearest distance falls as the pin is lowered)."""
    import numpy as np
    x = np.linspace(-outline.pitch, outline.pitch, 200001)
    u = outline.height_at(x)

    def clearance(y):
        return np.min(np.hypot(x, u - y)) - diameter / 2

    lo, hi = -outline.dedendum, outline.addendum + diameter
    for _ in range(100):
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if clearance(mid) > 0 else (mid, hi)
    return (lo + hi) / 2


@pytest.mark.parametrize("helix", [0.0, 15.0])
def test_rack_allowance_pin_dimension_and_sheet(tmp_path, poppler, helix):
    import json

    from geargen.cli import main
    from geargen.families.rack.geometry import rack_outline
    from geargen.families.rack.spec import rack_from_table
    out = tmp_path / "rack"
    options = ["gear", "--kind", "rack", "--module", "2", "--teeth", "10", "--face-width", "10", "--thinning", "0.03",
               "--thickness-allowance", "-20", "-50", "--no-stl", "--out", str(out), "--name", "r"]
    if helix:
        options += ["--helix-angle", str(helix)]
    assert main(options) == 0
    data = json.loads((out / "r.json").read_text())
    assert data["warnings"] == []  # the model's 0.03 cos(beta) mm thinning lies inside [20, 50] um
    p_n = math.pi * 2.0
    # limits: p_n / 2 + E_sni .. p_n / 2 + E_sns (1e-12 mm: rounding)
    assert data["tooth_thickness_normal_limits"] == pytest.approx([p_n / 2 - 0.050, p_n / 2 - 0.020], abs=1e-12)
    beta = math.radians(helix)
    assert data["tooth_thickness_normal_model"] == pytest.approx(p_n / 2 - 0.03 * math.cos(beta), abs=1e-12)
    # the ideal pin touches the zero-backlash tooth at the pitch line: D = (p_n / 2) / cos(20 deg) = 3.3432 mm;
    # the shop's is the nearest of the 0.01 mm gauge-pin series, 3.34 mm (1e-12 mm: rounding)
    pin = data["over_pin"]
    ideal = p_n / 2 / math.cos(math.radians(20))
    assert pin["ideal_diameter"] == pytest.approx(ideal, abs=1e-12)
    assert pin["diameter"] == pytest.approx(3.34, abs=1e-12) and abs(pin["diameter"] - ideal) <= 0.005
    assert pin["series"] == "gauge pin sets in 0.01 mm steps"
    # over the pin to the back face against the pin resting on the modelled outline, found numerically
    # for the model's tooth and each limit (2e-6 mm: the samples' spacing 6e-5 mm gives a distance error
    # of (6e-5)^2 / D, below 1e-9, and bisection to 1e-15; the bound is the sampled flank's chords)
    table = {"kind": "rack", "teeth": 10, "module_mm": 2, "face_width_mm": 10, "helix_angle_deg": helix,
             "thinning_circumferential_mm": 0.03}
    spec = rack_from_table(table)
    for thinning_normal, value in ((0.03 * math.cos(beta), pin["dimension_to_back"]), (0.050, pin["limits"][0]),
                                   (0.020, pin["limits"][1])):
        made = rack_from_table({**table, "thinning_circumferential_mm": thinning_normal / math.cos(beta)})
        y = _pin_rest_height(rack_outline(made), pin["diameter"])
        assert value == pytest.approx(spec.pitch_line_height + y + pin["diameter"] / 2, abs=2e-6)
    rows = sheet_rows(out / "r-drawing.svg")
    kind = pin["kind"]
    assert_lengths(rows, data, [("Tooth thickness at the pitch line (normal)", "tooth_thickness_normal_model"),
                                ("Back face to pitch line", "pitch_line_height")], "mm")
    assert_lengths(rows, pin, [(f"{kind.capitalize()} diameter", "diameter"),
                               (f"Back face over {kind}", "dimension_to_back")], "mm")
    assert rows[f"{kind.capitalize()} series"][1] == pin["series"]
    hi, lo = (float(v) for v in re.findall(r"\d+\.\d+", rows[f"Over-{kind} limits"][1]))
    assert (lo, hi) == pytest.approx(tuple(pin["limits"]), abs=ROUNDING["mm"] * 1.0001)
    hi, lo = (float(v) for v in re.findall(r"\d+\.\d+", rows["Tooth thickness limits"][1]))
    assert (lo, hi) == pytest.approx(tuple(data["tooth_thickness_normal_limits"]), abs=ROUNDING["mm"] * 1.0001)
    assert "-20.0 µm" in rows["Tooth thickness allowance, upper"][1]
    assert_pdf_holds(poppler, out / "r-drawing.pdf", rows)


def test_rack_table_allowance_keys():
    from geargen.families.rack.spec import rack_from_table
    from geargen.errors import DesignError
    base = {"kind": "rack", "teeth": 10, "module_mm": 2, "face_width_mm": 10}
    spec = rack_from_table({**base, "thickness_upper_deviation_um": -20, "thickness_lower_deviation_um": -50})
    assert spec.thickness_deviations == pytest.approx((-0.020, -0.050), abs=1e-15)
    with pytest.raises(DesignError) as err:
        rack_from_table({**base, "thickness_upper_deviation_um": -20})
    assert err.value.field == "gear.thickness_lower_deviation_um"
    with pytest.raises(DesignError) as err:
        rack_from_table({**base, "thickness_upper_deviation_um": -50, "thickness_lower_deviation_um": -20})
    assert err.value.field == "gear.thickness_lower_deviation_um"


# ---------------------------------------------------------------- every sheet in Chromium


def _boxes(svg: Path, chromium, tmp_path) -> list[dict]:
    """Every text's box as Chromium lays the SVG out (sheet points), by the gear drawing test's page."""
    import html
    import json

    from tests.report.test_drawing import _BOXES_PAGE, _chromium
    text = svg.read_text(encoding="utf-8")
    page = tmp_path / f"{svg.stem}.html"
    page.write_text(_BOXES_PAGE.format(svg=text[text.index("<svg"):]), encoding="utf-8")
    done = _chromium(chromium, page, tmp_path / "profile", "--dump-dom")
    found = re.search(r'<pre id="boxes">(.*?)</pre>', done.stdout, re.S)
    assert found and found.group(1), done.stderr[-2000:]
    return json.loads(html.unescape(found.group(1)))


def test_in_chromium_every_text_inside_its_cell_and_none_overlap(robot_joint_drawings, worm_set_outputs, chromium,
                                                                  tmp_path):
    """The family sheets as a browser draws them: no two texts overlap, every text of the data block
    lies inside its column and the block, every text on the sheet (0.05 mm: sub-pixel rounding of the
    browser's boxes)."""
    from geargen.cli import main
    _, files = robot_joint_drawings
    sheets = [files[f"drawing:{n}:svg"] for n in ("bevel_gear", "bevel_pinion", "cluster")]
    sheets += [worm_set_outputs[k][1]["svg"] for k in ("worm", "worm_wheel")]
    assert main(["gear", "--kind", "rack", "--module", "2", "--teeth", "10", "--face-width", "10",
                 "--thickness-allowance", "-20", "-50", "--no-stl", "--out", str(tmp_path / "rack"), "--name", "r"]) == 0
    sheets.append(tmp_path / "rack" / "r-drawing.svg")
    cols = [DATA_BLOCK[0], DATA_BLOCK[0] + COLUMNS_MM[0], DATA_BLOCK[0] + COLUMNS_MM[0] + COLUMNS_MM[1], DATA_BLOCK[2]]
    slack = 0.05
    for svg in sheets:
        boxes = [{k: (v * MM_PER_PT if k != "text" else v) for k, v in b.items()} for b in _boxes(svg, chromium, tmp_path)]
        overlaps = [(a["text"], b["text"]) for i, a in enumerate(boxes) for b in boxes[i + 1:]
                    if a["x0"] < b["x1"] - slack and b["x0"] < a["x1"] - slack and a["y0"] < b["y1"] - slack
                    and b["y0"] < a["y1"] - slack]
        assert not overlaps, (svg.name, overlaps)
        top = 297.0 - DATA_BLOCK[3]  # the SVG's y runs down from the top edge
        for b in boxes:
            assert b["x0"] >= 0 and b["y0"] >= 0 and b["x1"] <= 420 and b["y1"] <= 297, (svg.name, b["text"])
            if b["x0"] >= DATA_BLOCK[0] - slack and b["y0"] >= top - slack and b["y1"] <= 297.0 - DATA_BLOCK[1]:
                col = max(j for j in range(3) if b["x0"] >= cols[j] - slack)
                assert b["x1"] <= cols[col + 1] + slack, (svg.name, b["text"], b["x1"], cols[col + 1])
