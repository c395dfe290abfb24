"""The manufacturing drawing (SVG, PDF) and the profile DXF of a gear (geargen.report.drawing, .dxf).

- DXF: re-read with ezdxf; every SPLINE evaluated densely lies on the exact flank or fillet
  (against the profile's exact segments, and the flanks also against the closed-form involute
  of geargen.core.involute), every ARC on the tip or root circle, the chain is closed, the unit
  declared; for a metric helical gear with a keyway and an inch spur gear.
- SVG: every field of the ISO 1340 data block is there with the gear data's values; opened in
  headless Chromium, no two text elements overlap (their getBBox mapped by getCTM into the
  sheet) and every font is at least 3.5 mm on the sheet; a screenshot is not blank.
- PDF: turned into PNG by pdftoppm (not blank) and into text by pdftotext (every value there).
- ``geargen gear`` and ``geargen build`` write and list the files, and the sheet's numbers are
  the gear JSON's.
"""

import json
import math
import re
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from geargen.core.involute import involute
from geargen.design.gear import GearSpec, Hub
from geargen.model.gear_data import gear_data
from geargen.profile.tooth import tooth_profile
from geargen.report.drawing import DATA_BLOCK, MM_PER_PT, PAD_MM, COLUMNS_MM, data_rows, write_drawing
from geargen.report.dxf import write_profile_dxf

SVG_NS = "{http://www.w3.org/2000/svg}"


def _metric_helical():
    # the 21-tooth 20 deg helical pinion of bench/ (module 0.79375 mm = 32 DP), with a keyed bore
    return GearSpec(teeth=21, module=0.79375, pressure_angle=math.radians(20), face_width=12.7,
                    helix_angle=math.radians(20), hand="left", profile_shift=0.2,
                    hub=Hub(bore_diameter=6.0, keyway_width=2.0, keyway_depth=1.0), name="pinion_21")


def _inch_spur():
    # the README's 112-tooth 32 DP spur gear, in inches
    return GearSpec(teeth=112, module=25.4 / 32, pressure_angle=math.radians(20), face_width=6.35,
                    hub=Hub(bore_diameter=10.0), name="gear_112", length_unit="in")


def _full_data(spec, profile):
    """Gear data with every contract key filled (values of the right kind; the other branches
    compute the real ones) and one mating gear, as the build gives it."""
    data = gear_data(spec, profile)
    data["accuracy"] = {"standard": "ISO 1328-1:2013", "grade": 6, "single_pitch_um": 5.5, "cumulative_pitch_um": 16.0,
                        "profile_total_um": 6.5, "helix_total_um": 9.0, "runout_um": 13.0}
    data["thickness_allowance"] = {"method": "DIN 3967 series cd25", "upper_um": -28.0, "lower_um": -46.0}
    data["span"]["limits"] = [data["span"]["span_normal"] - 0.0004, data["span"]["span_normal"] - 0.0002]
    data["over_pins"]["limits"] = [data["over_pins"]["dimension"] - 0.0009, data["over_pins"]["dimension"] - 0.0005]
    data["mating_gears"] = [{"name": "output", "teeth": 80, "centre_distance": 40.1234,
                             "centre_distance_tolerance": [-0.01, 0.01]}]
    return data


# ---------------------------------------------------------------- DXF


def _nearest_distance(segment, points, t_lo, t_hi):
    """Distance (mm) from each of ``points`` (k, 2) to the exact ``segment`` on [t_lo, t_hi]:
    nearest of 4001 samples, then Gauss-Newton on the parameter (exact derivatives)."""
    ts = np.linspace(t_lo, t_hi, 1001)
    samples = segment.point(ts)
    t = ts[np.argmin(np.linalg.norm(samples[None, :, :] - points[:, None, :], axis=2), axis=1)]
    for _ in range(8):
        d = segment.point(t) - points
        dp = segment.derivative(t)
        t = np.clip(t - np.sum(d * dp, axis=1) / np.sum(dp * dp, axis=1), t_lo, t_hi)
    return np.linalg.norm(segment.point(t) - points, axis=1)


@pytest.mark.parametrize("make", [_metric_helical, _inch_spur])
def test_dxf_lies_on_the_exact_profile_and_closes(make, tmp_path):
    import ezdxf
    spec = make()
    profile = tooth_profile(spec, warn=False)
    path = write_profile_dxf(profile, tmp_path / "g.dxf").path
    doc = ezdxf.readfile(path)
    scale = 25.4 if spec.length_unit == "in" else 1.0  # file unit -> mm
    assert doc.header["$INSUNITS"] == {"mm": 4, "in": 1}[spec.length_unit]  # DXF reference: 4 mm, 1 inch
    outline = [e for e in doc.modelspace() if e.dxf.layer == "GEAR_OUTLINE"]
    exact = profile.outline()
    assert len(outline) == len(exact)  # one entity per exact segment, in outline order
    ends = []
    worst = 0.0
    for entity, seg in zip(outline, exact):
        if seg.kind in ("tip_arc", "root_arc"):
            assert entity.dxftype() == "ARC"
            assert entity.dxf.radius * scale == pytest.approx(seg.curve.radius, rel=1e-14)
            a0, a1 = math.radians(entity.dxf.start_angle), math.radians(entity.dxf.end_angle)
            # the arc spans the exact segment's polar angles (mod 2 pi)
            d0 = (a0 - (seg.t0 + seg.rotation) + math.pi) % (2 * math.pi) - math.pi
            d1 = (a1 - (seg.t1 + seg.rotation) + math.pi) % (2 * math.pi) - math.pi
            assert abs(d0) < 1e-12 and abs(d1) < 1e-12
            ends.append((np.array(entity.start_point)[:2] * scale, np.array(entity.end_point)[:2] * scale))
            continue
        assert entity.dxftype() == "SPLINE" and entity.dxf.degree == 3
        cp = np.array(entity.control_points)[:, :2] * scale
        ends.append((cp[0], cp[-1]))
        if seg.tooth not in (0, spec.teeth - 1):
            # the other teeth: tooth 0's spline turned by whole pitches (evaluated densely on two teeth)
            per_tooth = len(exact) // spec.teeth
            i0 = outline.index(entity) % per_tooth
            a = seg.tooth * profile.pitch_angle
            ref = np.array(outline[i0].control_points)[:, :2] * scale
            turned = ref @ np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]])
            assert np.max(np.abs(turned - cp)) < 1e-9
            continue
        tool = entity.construction_tool()
        knots = tool.knots()
        pts = np.array([(p.x, p.y) for p in tool.points(np.linspace(knots[0], knots[-1], 600))]) * scale
        lo, hi = sorted((seg.t0, seg.t1))
        dist = _nearest_distance(seg, pts, lo, hi)
        worst = max(worst, float(dist.max()))
        if seg.kind == "involute":
            # independently: the involute's polar angle at radius r is +/-(psi_b - inv(alpha)) about the
            # tooth centre line, cos(alpha) = r_b / r; the distance along the circle bounds the normal one
            r = np.hypot(pts[:, 0], pts[:, 1])
            alpha = np.arccos(np.clip(profile.base_radius / r, -1, 1))
            half = profile.base_half_angle - involute(alpha)
            centre = seg.tooth * profile.pitch_angle
            polar = np.arctan2(pts[:, 1], pts[:, 0]) - centre
            polar = (polar + math.pi) % (2 * math.pi) - math.pi
            side = -1.0 if seg.side == "lower" else 1.0
            assert np.max(np.abs(polar - side * half) * r) < 1e-4  # 0.1 um
    assert worst < 1e-4, worst  # 0.1 um (fitted to 0.01 um)
    # closed chain: each entity starts where the one before ends (the last one before the first)
    gaps = [np.linalg.norm(ends[i][0] - ends[i - 1][1]) for i in range(len(ends))]
    assert max(gaps) < 1e-9
    # the bore: its radius in the file's unit
    bore = [e for e in doc.modelspace() if e.dxf.layer == "BORE"]
    radii = {round(e.dxf.radius * scale, 9) for e in bore if e.dxftype() in ("ARC", "CIRCLE")}
    assert radii == {round(spec.hub.bore_diameter / 2, 9)}
    if spec.hub.keyway_width:
        lines = [e for e in bore if e.dxftype() == "LINE"]
        floor = [e for e in lines if abs(e.dxf.start[0] - e.dxf.end[0]) < 1e-12]
        assert len(lines) == 3 and floor[0].dxf.start[0] * scale == pytest.approx(3.0 + 1.0)  # bore r + depth


# ---------------------------------------------------------------- SVG and PDF

#: the fields of the data block (ISO 1340:1976 clause 3 order, then the drawing's own)
FIELDS = ["Number of teeth", "Normal module", "Normal diametral pitch", "Basic rack tooth proportions",
          "Normal pressure angle", "Helix angle and hand", "Profile shift coefficient", "Reference diameter",
          "Tip diameter", "Root diameter", "Accuracy grade", "Tooth thickness allowance, upper",
          "Tooth thickness allowance, lower", "Span limits", "Dimension over balls",
          "Over-balls limits", "Ball diameter", "Mating gear", "Centre distance to output", "Drawing units",
          "Drawing scale", "Generator", "Source"]


def svg_texts(path):
    """Every <text> of the SVG: (text, x, y) in sheet mm from the top left."""
    out = []
    for t in ET.parse(path).getroot().iter(f"{SVG_NS}text"):
        out.append(("".join(t.itertext()), float(t.get("x")) * MM_PER_PT, float(t.get("y")) * MM_PER_PT))
    return out


def svg_rows(path):
    """The data block read back from the SVG: {name: (symbol, value)} (first line of each cell)."""
    texts = svg_texts(path)
    cols = np.cumsum((DATA_BLOCK[0],) + COLUMNS_MM)[:3] + PAD_MM
    rows = {}
    for text, x, y in texts:
        if abs(x - cols[0]) < 1e-3:
            same = {j: s for s, xx, yy in texts for j in (1, 2) if abs(yy - y) < 1e-3 and abs(xx - cols[j]) < 1e-3}
            rows.setdefault(text, (same.get(1, ""), same.get(2, "")))
    return rows


@pytest.fixture(scope="module")
def drawn(tmp_path_factory):
    spec = _metric_helical()
    profile = tooth_profile(spec, warn=False)
    data = _full_data(spec, profile)
    folder = tmp_path_factory.mktemp("drawing")
    files = write_drawing(data, profile, folder, spec.name, f"gear {spec.name} from " + "/a/long/path" * 12 +
                          "/design.toml [gear]", "/a/long/path/design.toml")
    return data, files


def test_every_field_is_on_the_sheet_with_the_gear_datas_value(drawn):
    data, files = drawn
    rows = svg_rows(files["svg"])
    missing = [f for f in FIELDS if f not in rows]
    assert not missing, missing
    # the values are the gear data's (recomputed here from the dict: 2 r to 4 decimals in mm)
    assert rows["Number of teeth"] == ("z", "21")
    assert rows["Tip diameter"] == ("d_a", f"{2 * data['tip_radius']:.4f} mm")
    assert rows["Root diameter"][1] == f"{2 * data['root_radius']:.4f} mm"
    assert rows["Reference diameter"][1] == f"{2 * data['reference_radius']:.4f} mm"
    assert rows["Normal module"][1] == "0.79375 mm" and rows["Normal diametral pitch"][1] == "32 1/in"
    assert rows["Helix angle and hand"][1] == "20.0000° left hand"
    assert rows["Profile shift coefficient"][1] == "+0.2000"
    assert rows["Accuracy grade"][1] == "ISO 1328-1:2013 grade 6"
    assert rows["Tooth thickness allowance, upper"][1] == "-0.0280 mm (-28.0 µm)"
    k = data["span"]["teeth_spanned"]
    w_lo, w_hi = data["span"]["limits"]
    assert rows[f"Span over k = {k} teeth"][1] == f"{data['span']['span_normal']:.4f} mm"
    assert rows["Span limits"][1] == f"{w_hi:.4f} / {w_lo:.4f} mm (max / min)"
    assert rows["Ball diameter"][1] == f"{data['over_pins']['diameter']:.4f} mm"
    assert rows["Centre distance to output"][1] == "40.1234 mm +0.0100 / -0.0100"
    assert rows["Mating gear"][1] == "output (80 teeth)"
    # the module's design is metric: module first
    names = list(rows)
    assert names.index("Normal module") < names.index("Normal diametral pitch")


def test_a_lone_gear_reads_not_specified_never_a_made_up_value(tmp_path):
    spec = _inch_spur()
    profile = tooth_profile(spec, warn=False)
    data = gear_data(spec, profile)  # no accuracy, allowance, limits or mate
    rows = svg_rows(write_drawing(data, profile, tmp_path, spec.name, "options", "options")["svg"])
    for field in ("Accuracy grade", "Tooth thickness allowance, upper", "Tooth thickness allowance, lower",
                  "Span limits", "Over-pins limits", "Mating gear", "Centre distance"):
        assert rows[field][1] == "not specified", field
    for field in ("Single pitch tolerance", "Runout tolerance"):
        assert rows[field][1] == "-", field
    # an inch design: its diametral pitch and no module (no mm on an inch sheet), lengths in inches to 5 decimals
    assert rows["Normal diametral pitch"][1] == "32 1/in" and "Normal module" not in rows
    assert rows["Tip diameter"][1] == f"{2 * data['tip_radius']:.5f} in"
    assert data["tip_radius"] == pytest.approx((112 + 2) / 32 / 2, rel=1e-12)  # (z + 2) / P


_BOXES_PAGE = """<!DOCTYPE html><html><head><meta charset="utf-8"></head><body style="margin:0">{svg}
<pre id="boxes"></pre><script>
const root = document.querySelector("svg");
const out = [];
for (const t of root.querySelectorAll("text")) {{
  const b = t.getBBox(), m = t.getCTM(), r = root.getCTM().inverse().multiply(m);
  const pts = [[b.x, b.y], [b.x + b.width, b.y], [b.x, b.y + b.height], [b.x + b.width, b.y + b.height]]
    .map(([x, y]) => [r.a * x + r.c * y + r.e, r.b * x + r.d * y + r.f]);
  const xs = pts.map(p => p[0]), ys = pts.map(p => p[1]);
  const size = parseFloat(getComputedStyle(t).fontSize) * Math.sqrt(Math.abs(r.a * r.d - r.b * r.c));
  out.push({{text: t.textContent, x0: Math.min(...xs), y0: Math.min(...ys), x1: Math.max(...xs), y1: Math.max(...ys),
            size: size}});
}}
document.getElementById("boxes").textContent = JSON.stringify(out);
document.title = "boxes:" + out.length;
</script></body></html>"""


def _chromium(chromium, page, profile, *args):
    cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-extensions",
           "--disable-background-networking", "--disable-component-update", "--disable-sync",
           f"--user-data-dir={profile}", "--virtual-time-budget=5000", *args, Path(page).resolve().as_uri()]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=120)


def test_in_chromium_no_text_overlaps_and_every_font_is_legible(drawn, chromium, tmp_path):
    import html
    data, files = drawn
    svg = Path(files["svg"]).read_text(encoding="utf-8")
    svg = svg[svg.index("<svg"):]  # inline: without the XML prolog and doctype
    page = tmp_path / "boxes.html"
    page.write_text(_BOXES_PAGE.format(svg=svg), encoding="utf-8")
    done = _chromium(chromium, page, tmp_path / "profile", "--dump-dom")
    found = re.search(r'<pre id="boxes">(.*?)</pre>', done.stdout, re.S)
    assert found and found.group(1), done.stderr[-2000:]
    boxes = json.loads(html.unescape(found.group(1)))
    assert len(boxes) == len(svg_texts(files["svg"])) > 100
    mm = MM_PER_PT  # the SVG's user unit is the point
    small = [(b["text"], b["size"] * mm) for b in boxes if b["size"] * mm < 3.5 - 1e-6]
    assert not small, small  # 10 pt: capitals of 2.5 mm, ISO 3098's smallest on A3
    overlaps = []
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            if a["x0"] < b["x1"] and b["x0"] < a["x1"] and a["y0"] < b["y1"] and b["y0"] < a["y1"]:
                overlaps.append((a["text"], b["text"]))
    assert not overlaps, overlaps
    # every text on the sheet (420 x 297 mm)
    assert all(b["x0"] >= 0 and b["y0"] >= 0 and b["x1"] * mm <= 420 and b["y1"] * mm <= 297 for b in boxes)


def test_the_screenshot_is_not_blank(drawn, chromium, tmp_path):
    from PIL import Image
    _, files = drawn
    shot = tmp_path / "shot.png"
    _chromium(chromium, files["svg"], tmp_path / "profile", "--window-size=1588,1123", f"--screenshot={shot}")
    image = np.asarray(Image.open(shot).convert("L"), dtype=float)
    # the views (left) and the data block (right) both have ink
    for part in (image[100:700, 100:850], image[50:800, 900:1500]):
        assert (part < 128).mean() > 0.005 and part.std() > 20


def test_the_pdf_renders_and_holds_every_value(drawn, poppler, tmp_path):
    from PIL import Image
    data, files = drawn
    subprocess.run([poppler["pdftoppm"], "-r", "60", "-png", "-singlefile", str(files["pdf"]), str(tmp_path / "page")],
                   check=True, timeout=120)
    image = np.asarray(Image.open(tmp_path / "page.png").convert("L"), dtype=float)
    assert image.shape[1] > image.shape[0]  # landscape
    assert (image < 128).mean() > 0.01 and image.std() > 20
    text = subprocess.run([poppler["pdftotext"], str(files["pdf"]), "-"], capture_output=True, text=True,
                          check=True, timeout=120).stdout
    compact = "".join(text.split())
    rows = data_rows(data, *_scale_version_source(files["svg"]))
    for name, symbol, value in rows:
        assert "".join(name.split()) in compact, name
        # a wrapped value (the long source path) comes out in pieces: each line's words are there
        for word in value.split():
            assert word in compact, (name, word)


def _scale_version_source(svg):
    rows = svg_rows(svg)
    return rows["Drawing scale"][1], rows["Generator"][1].split()[-1], "x"


# ---------------------------------------------------------------- the writers


@pytest.mark.slow
def test_geargen_gear_writes_and_lists_the_drawings(tmp_path):
    from geargen.cli import main
    out = tmp_path / "g"
    assert main(["gear", "--teeth", "21", "--module", "0.79375", "--helix-angle", "20", "--face-width", "12.7",
                 "--no-stl", "--out", str(out)]) == 0
    data = json.loads((out / "gear_21.json").read_text())
    assert data["drawing"] == {"svg": "gear_21-drawing.svg", "pdf": "gear_21-drawing.pdf", "dxf": "gear_21.dxf"}
    listed = json.loads((out / "manifest.json").read_text())["files"]
    for name in data["drawing"].values():
        assert (out / name).stat().st_size == listed[name]["bytes"] > 0
    rows = svg_rows(out / data["drawing"]["svg"])
    # one truth: the sheet's numbers are the JSON's
    assert rows["Tip diameter"][1] == f"{2 * data['tip_radius']:.4f} mm"
    assert rows[f"Span over k = {data['span']['teeth_spanned']} teeth"][1] == f"{data['span']['span_normal']:.4f} mm"
    assert rows["Dimension over balls"][1] == f"{data['over_pins']['dimension']:.4f} mm"
    assert rows["Mating gear"][1] == "not specified" and data["mating_gears"] == []


@pytest.mark.slow
def test_geargen_build_draws_every_gear_with_its_mates(built_assemblies):
    folder = built_assemblies["split_pinion"]
    manifest = json.loads((folder / "manifest.json").read_text())
    resolved = json.loads((folder / "resolved.json").read_text())
    gears = [g["name"] for g in resolved["gears"]]
    assert gears
    for gear in gears:
        for name in (f"{gear}-drawing.svg", f"{gear}-drawing.pdf", f"{gear}.dxf", f"{gear}.json"):
            assert manifest["files"][f"drawings/{name}"]["bytes"] == (folder / "drawings" / name).stat().st_size
        data = json.loads((folder / "drawings" / f"{gear}.json").read_text())
        rows = svg_rows(folder / "drawings" / f"{gear}-drawing.svg")
        assert rows["Tip diameter"][1] == f"{2 * data['tip_radius']:.4f} mm"
        assert rows["Root diameter"][1] == f"{2 * data['root_radius']:.4f} mm"
        # the mates and working centre distances are the mesh checks' (manifest, mm)
        meshes = [m for m in manifest["checks"]["meshes"] if m["engaged"] and gear in (m["gear1"], m["gear2"])]
        assert len(data["mating_gears"]) == len(meshes) > 0
        for m in meshes:
            other = m["gear2"] if m["gear1"] == gear else m["gear1"]
            assert rows[f"Centre distance to {other}"][1].startswith(f"{m['centre_distance']:.4f} mm")
    report = (folder / "report.html").read_text()
    assert all(f"href='drawings/{g}-drawing.svg'" in report for g in gears)
