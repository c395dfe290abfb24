"""The browser design review a build writes (review/index.html, geargen.report.review_page).

The data the page gets is checked without a browser: its parts are the manifest's, its mesh
numbers the manifest's check summary, its tables the report's, and the GLB holds one node per
part whose triangles are the exported STL's, in glTF's frame (metres, y up). Then the page is
opened in headless Chromium from file:// (no server, no network): it must load the model,
count the manifest's parts and draw a picture that is not blank.

Every test needs a built assembly (the session's ``built_assemblies``): marked slow, run in CI.
Chromium: /usr/bin/chromium (or on the PATH); else, as root with apt-get, the Debian package is
installed; else the browser tests are skipped, except in CI (``CI`` set), where they fail.
"""

import base64
import io
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

from geargen.report.review import from_markdown
from geargen.report.review_page import read_script

pytestmark = pytest.mark.slow

# the shipped drives the session builds (dual_motor.toml places no drive: built as a gear set, no review page)
DESIGNS = ["robot_joint", "c_axis", "split_pinion", "split_pinion_inch", "metric_dual_pinion"]
MM_PER = {"mm": 1.0, "in": 25.4}


def _manifest(folder: Path) -> dict:
    return json.loads((folder / "manifest.json").read_text())


# ---------------------------------------------------------------- the page's data (no browser)


@pytest.mark.parametrize("name", ["robot_joint", "split_pinion_inch"])
def test_the_page_gets_the_builds_parts_and_check_numbers(built_assemblies, name):
    folder = built_assemblies[name]
    manifest = _manifest(folder)
    data = read_script(folder / "review" / "data.js")
    assert [p["name"] for p in data["parts"]] == list(manifest["parts"])
    assert {p["name"]: p["group"] for p in data["parts"]} == {n: p["group"] for n, p in manifest["parts"].items()}
    # one truth: the very numbers manifest.json records, clearance and interference included
    assert data["meshes"] == manifest["checks"]["meshes"] and data["tolerances"] == manifest["checks"]["tolerances"]
    engaged = [m for m in data["meshes"] if m["engaged"]]
    assert engaged and all("min_tip_clearance" in m and "interference_depth_max" in m for m in engaged)
    for m in engaged:  # a passing build: every backlash in its design range, no interference
        assert m["design_min"] <= m["backlash_min"] <= m["backlash_max"] <= m["design_max"] + 1e-9
        assert m["interference_depth_max"] == 0.0 and m["min_tip_clearance"] > 0
    assert data["length_unit"] == manifest["design"]["length_unit"]
    assert data["mm_per_unit"] == MM_PER[data["length_unit"]]
    # the report's tables, as report.md prints them
    report = from_markdown((folder / "report.md").read_text(), "PASS")
    tables = {title: b for title, b in _tables(report)}
    page = {s["title"]: [blk for blk in s["blocks"] if blk["kind"] == "table"] for s in data["sections"]}
    mesh_table = tables["Mesh checks"]
    assert page["Mesh checks"][0]["header"] == mesh_table[0]
    assert page["Mesh checks"][0]["rows"] == mesh_table[1]
    assert len(mesh_table[1]) == len(data["meshes"])


def _tables(review):
    title = "Summary"
    for kind, payload in review.blocks:
        if kind == "h2":
            title = payload
        elif kind == "table":
            yield title, payload


@pytest.mark.parametrize("name", ["robot_joint", "split_pinion_inch"])
def test_the_glb_holds_every_part_as_exported(built_assemblies, name):
    import trimesh
    folder = built_assemblies[name]
    manifest = _manifest(folder)
    glb = (folder / "review" / "assembly.glb").read_bytes()
    model = read_script(folder / "review" / "model.js")
    assert base64.b64decode(model["glb_base64"]) == glb  # the page shows the file beside it
    scene = trimesh.load(io.BytesIO(glb), file_type="glb", force="scene", process=False)
    parts = list(manifest["parts"])
    assert sorted(scene.graph.nodes_geometry) == sorted(parts)  # one node per part, named as the part
    lo_all, hi_all = np.full(3, np.inf), np.full(3, -np.inf)
    for part in parts:
        stl = trimesh.load(folder / f"{part}.stl", process=False)
        transform, geometry = scene.graph[part]
        mesh = scene.geometry[geometry]
        # the same triangles as the STL export (float32 both), nothing merged away or moved
        assert len(mesh.faces) == len(stl.faces)
        np.testing.assert_allclose(mesh.bounds, stl.bounds, rtol=0, atol=1e-9)
        assert abs(mesh.area - stl.area) <= 1e-6 * stl.area
        lo_all, hi_all = np.minimum(lo_all, stl.bounds[0]), np.maximum(hi_all, stl.bounds[1])
    # the root node turns mm, z up into glTF's metres, y up: (x, y, z) -> (x, z, -y) / 1000
    expected = np.array([[lo_all[0], lo_all[2], -hi_all[1]], [hi_all[0], hi_all[2], -lo_all[1]]]) / 1000
    np.testing.assert_allclose(scene.bounds, expected, rtol=0, atol=1e-9)
    # each gear where the resolved drive puts it: its lowest face at its z, its axis at its centre
    resolved = json.loads((folder / "resolved.json").read_text())
    scale = MM_PER[resolved["length_unit"]]
    for g in resolved["gears"]:
        lo, hi = scene.geometry[scene.graph[g["name"]][1]].bounds
        half = (hi[:2] - lo[:2]) / 2
        # a gear's box is symmetric about its axis to within a tooth's share of the tip circle
        np.testing.assert_allclose((lo[:2] + hi[:2]) / 2, np.array(g["centre"]) * scale, atol=0.03 * half.max())
        assert lo[2] == pytest.approx(g["z"] * scale, abs=1e-3)


# ---------------------------------------------------------------- the page in headless Chromium


def _run_chromium(chromium: str, page: Path, profile: Path, *args: str,
                  fragment: str = "") -> subprocess.CompletedProcess:
    """Chromium headless on ``page`` (file://): software WebGL (SwiftShader), no network services,
    a fresh profile; virtual time lets the page's scripts and the model's decoding finish."""
    cmd = [chromium, "--headless", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
           "--disable-quic", "--no-first-run", "--disable-background-networking", "--disable-component-update",
           "--disable-sync", "--disable-default-apps", "--disable-extensions", f"--user-data-dir={profile}",
           "--virtual-time-budget=30000", *args, page.resolve().as_uri() + fragment]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=180)


def _body_attributes(dom: str) -> dict[str, str]:
    import re
    tag = re.search(r"<body\b([^>]*)>", dom)
    assert tag, dom[:2000]
    return dict(re.findall(r'([\w-]+)="([^"]*)"', tag.group(1)))


@pytest.mark.parametrize("name", ["robot_joint", "split_pinion_inch"])
def test_the_page_loads_the_model_offline_in_chromium(built_assemblies, chromium, tmp_path, name):
    folder = built_assemblies[name]
    page = folder / "review" / "index.html"
    done = _run_chromium(chromium, page, tmp_path / "profile", "--dump-dom")
    attrs = _body_attributes(done.stdout)
    assert "data-error" not in attrs, attrs["data-error"]
    assert attrs.get("data-loaded") == "true", done.stderr[-3000:]
    assert int(attrs["data-parts"]) == len(_manifest(folder)["parts"])
    # the part tree and the mesh list were built from the data
    assert done.stdout.count('class="part"') == len(_manifest(folder)["parts"])
    assert done.stdout.count('class="meshrow') == len(_manifest(folder)["checks"]["meshes"])


def test_a_mesh_shows_the_manifests_numbers_and_the_section_its_position(built_assemblies, chromium, tmp_path):
    """What a click on a mesh shows (index.html#mesh=NAME selects it as a click does): the
    manifest's numbers in the design's unit, to the page's five digits; and a section plane."""
    import html
    import re
    folder = built_assemblies["robot_joint"]
    manifest = _manifest(folder)
    mesh = manifest["checks"]["meshes"][0]
    tolerance = next(t for t in manifest["checks"]["tolerances"] if t["mesh"] == mesh["mesh"])
    page = folder / "review" / "index.html"
    done = _run_chromium(chromium, page, tmp_path / "profile", "--dump-dom",
                         fragment=f"#mesh={mesh['mesh']}&section=z&at=0.25")
    info = re.search(r'<div id="info">(.*?)</div>', done.stdout, re.S)
    assert info, done.stdout[-3000:]
    cells = dict(re.findall(r"<tr><th>(.*?)</th><td>(.*?)</td></tr>", html.unescape(info.group(1))))
    unit = manifest["design"]["length_unit"]

    def shown(mm):  # JavaScript's Number(x.toPrecision(5)).toString() for these magnitudes
        return f"{float(f'{mm / MM_PER[unit]:.5g}'):.10g}"
    assert cells["mesh"] == f"{mesh['mesh']} ({mesh['gear1']} / {mesh['gear2']})"
    assert cells["verdict"] == "ok"
    assert cells[f"backlash, exact outlines ({unit})"] == \
        f"{shown(mesh['backlash_min'])} to {shown(mesh['backlash_max'])}"
    assert cells[f"design backlash ({unit})"] == f"{shown(mesh['design_min'])} to {shown(mesh['design_max'])}"
    assert cells[f"min tip clearance ({unit})"] == shown(mesh["min_tip_clearance"])
    assert cells[f"worst-case min backlash ({unit})"] == shown(tolerance["worst_case_min_backlash"])
    # both gears of the mesh selected in the part tree
    selected = re.findall(r'class="part selected" data-part="([^"]+)"', done.stdout)
    assert sorted(selected) == sorted([mesh["gear1"], mesh["gear2"]])
    # a quarter of the way up the model's height (GLB bounds: the STL files')
    label = re.search(r'<div id="section-value">z = ([-\d.e]+) ' + unit + "</div>", done.stdout)
    assert label, done.stdout[-3000:]
    import trimesh
    z = trimesh.load(folder / "review" / "assembly.glb", force="scene").bounds[:, 1] * 1000 / MM_PER[unit]
    assert float(label.group(1)) == pytest.approx(z[0] + 0.25 * (z[1] - z[0]), rel=1e-4)


def test_the_screenshot_shows_the_model(built_assemblies, chromium, tmp_path):
    from PIL import Image
    folder = built_assemblies["robot_joint"]
    shot = tmp_path / "shot.png"
    _run_chromium(chromium, folder / "review" / "index.html", tmp_path / "profile", "--window-size=1400,900",
                  f"--screenshot={shot}")
    image = np.asarray(Image.open(shot).convert("RGB"), dtype=float)
    assert image.shape[:2] == (900, 1400)
    # the 3-D view lies between the part tree (270 px) and the tables (440 px), under the header
    view = image[120:800, 320:900]
    distinct = len(np.unique(view.reshape(-1, 3).astype(np.uint8), axis=0))
    assert view.std(axis=(0, 1)).mean() > 15 and distinct > 200, (view.std(axis=(0, 1)), distinct)
    # not only grey: the coloured parts (gears, springs, bearings) are drawn
    saturation = view.max(axis=2) - view.min(axis=2)
    assert (saturation > 40).mean() > 0.01
