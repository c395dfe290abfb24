"""The build's report a reviewer can reuse: figures as their own PNG and SVG files listed in the
manifest, key numbers that are the commands' numbers, tables instead of text dumps, labels that
overlap nothing, and a render that shows no part through another part's face."""

import contextlib
import io
import json
import re
import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from geargen import pipeline as pl
from geargen.cli import main
from geargen.outputs import inspect_folder
from geargen.report.labels import boxes_overlap, circle_crosses_box, text_boxes, text_extent
from geargen.report.review import plain_number

ROOT = Path(__file__).resolve().parents[2]
# the shipped drives `geargen build` makes (dual_motor.toml places no drive: a gear set, tests/test_check_build_agree.py)
SHIPPED = [ROOT / "assemblies" / f"{n}.toml" for n in ("robot_joint", "c_axis", "split_pinion", "split_pinion_inch",
                                                      "metric_dual_pinion")]


def assert_apart(boxes) -> None:
    """No two ``(text, box)`` of ``boxes`` overlap; the message names both texts."""
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            assert not boxes_overlap(boxes[i][1], boxes[j][1]), f"{boxes[i][0]!r} overlaps {boxes[j][0]!r}"


# ---------------------------------------------------------------- labels of the layout drawing


@pytest.mark.parametrize("design", SHIPPED, ids=lambda p: p.stem)
def test_layout_drawing_texts_do_not_overlap_and_no_circle_crosses_a_label(design):
    """Every drawn text box (labels, ticks, axis labels, title) against every other, and every
    label box against every drawn circle outline, measured on the drawn figure itself (its
    Circle patches and its renderer's text extents), not on the placement's own bookkeeping.
    The drawing before the placement step failed both (robot joint: "symmetry line" over
    "input 16 T"; "carriage travel" crossed by the cluster gears' circles)."""
    from matplotlib.patches import Circle

    fig = pl.layout_drawing(pl.place(pl.load(design)))
    fig.canvas.draw()
    boxes = text_boxes(fig)
    assert len(boxes) >= 8
    assert_apart(boxes)
    ax = fig.axes[0]
    labels = [(t.get_text(), text_extent(t)) for t in ax.texts]
    assert any("T" in text for text, _ in labels)
    for patch in ax.patches:
        if not isinstance(patch, Circle):
            continue
        centre = ax.transData.transform(patch.center)
        radius = ax.transData.transform((patch.center[0] + patch.radius, patch.center[1]))[0] - centre[0]
        for text, e in labels:
            assert not circle_crosses_box(centre, radius, (e.x0, e.y0, e.x1, e.y1)), \
                f"a circle of radius {patch.radius:.4g} crosses {text!r}"


@pytest.mark.parametrize("design", SHIPPED, ids=lambda p: p.stem)
def test_preload_diagram_texts_do_not_overlap(design):
    """The report's other annotated figure: its texts (labels, legend, ticks) overlap nothing."""
    from geargen.report.stiffness import preload_diagram_figure
    summary = pl.stiffness(pl.place(pl.load(design)))
    if summary is None:
        pytest.skip("no stiffness summary")
    fig = preload_diagram_figure(summary)
    fig.canvas.draw()
    boxes = text_boxes(fig)
    assert len(boxes) >= 6
    assert_apart(boxes)


# ---------------------------------------------------------------- the render's depth order


def _cylinder(radius, z0, z1, segments=24, centre=(0.0, 0.0)):
    """Side triangles (outward normals) and top cap of a cylinder, ``(n, 3, 3)`` mm."""
    a = np.linspace(0, 2 * np.pi, segments + 1)
    ring = np.column_stack([centre[0] + radius * np.cos(a), centre[1] + radius * np.sin(a)])
    tris = []
    for k in range(segments):
        p, q = ring[k], ring[k + 1]
        lo_p, lo_q, hi_p, hi_q = (*p, z0), (*q, z0), (*p, z1), (*q, z1)
        tris += [(lo_p, lo_q, hi_q), (lo_p, hi_q, hi_p)]
        tris.append(((*centre, z1), hi_p, hi_q))
    return np.array(tris, dtype=float)


def _annulus(radii, z, segments=24):
    """An annular face at height ``z`` facing +z, fanned between each pair of successive circles
    of ``radii`` like a gear's end face around its bore, ``(n, 3, 3)`` mm."""
    a = np.linspace(0, 2 * np.pi, segments + 1)
    tris = []
    for inner, outer in zip(radii[:-1], radii[1:]):
        for k in range(segments):
            i0, i1 = ((inner * np.cos(t), inner * np.sin(t), z) for t in a[k:k + 2])
            o0, o1 = ((outer * np.cos(t), outer * np.sin(t), z) for t in a[k:k + 2])
            tris += [(i0, o0, o1), (i0, o1, i1)]
    return np.array(tris, dtype=float)


def _upper_part_pixels(view, part, rim_z, top_z, radius, centre=(0.0, 0.0), bore=0.0):
    """For ``part``, a cylinder (or a ring of inner radius ``bore``) about ``centre`` standing in
    or on another body up to ``rim_z``: the pixels showing it, those of them outside the
    projection of its part between ``rim_z`` and ``top_z`` (nothing below ``rim_z`` can be seen
    from above), and the pixels inside that projection, outside its bore's, that do not show it
    (it hides everything behind it). 1.5 pixels of tolerance."""
    from scipy.spatial import ConvexHull
    rows, cols = np.indices(view.part_index.shape)
    at = view.to_view(rows.ravel(), cols.ravel())
    a = np.linspace(0, 2 * np.pi, 720, endpoint=False)

    def signed_distance(r):  # to the projection of the cylinder of radius r between rim_z and top_z
        rim = np.array([(centre[0] + r * np.cos(t), centre[1] + r * np.sin(t), z) for z in (rim_z, top_z) for t in a])
        hull = ConvexHull(rim @ view.basis[:2].T)
        return (at @ hull.equations[:, :2].T + hull.equations[:, 2]).max(axis=1)
    tol = 1.5 * view.mm_per_pixel
    outer = signed_distance(radius)
    inner = signed_distance(bore) if bore > 0 else np.full(outer.shape, np.inf)
    shows = view.part_index.ravel() == view.names.index(part)
    return (int(shows.sum()), int(np.count_nonzero(shows & (outer > tol))),
            int(np.count_nonzero(~shows & (outer < -tol) & (inner > tol))))


def test_render_hides_the_part_of_a_cylinder_below_the_face_it_stands_in():
    """A cylinder standing in the bore of an opaque annular face (a bearing in a gear), seen from
    above: its part below the face cannot be seen, its part above hides what is behind it.
    Drawing whole triangles sorted by their centroids (the render before) showed the side
    triangles with two corners above the face over the face (a ring of spikes) and hid the
    others' upper halves."""
    from geargen.cad.render import rasterise
    # a narrow first ring of small triangles round the bore, as a gear's end face has
    face = _annulus((10.0, 13.0, 60.0), 0.0)
    cylinder = _cylinder(10.0, -5.0, 15.0)
    view = rasterise([("face", face, (0.3, 0.4, 0.8, 1.0)), ("cylinder", cylinder, (0.8, 0.2, 0.2, 1.0))],
                     (-60.0, 30.0), (600, 450))
    seen, outside, missing = _upper_part_pixels(view, "cylinder", 0.0, 15.0, 10.0)
    assert seen > 2000
    assert (outside, missing) == (0, 0)


def test_render_blends_a_translucent_part_over_what_is_behind_it():
    """A translucent plate (alpha 0.35) over an opaque one: the blend is the "over" operator
    (0.35 of the front colour, 0.65 of the one behind), and the opaque colour is what the
    pixels' part index reports."""
    from geargen.cad.render import rasterise
    square = np.array([[(-50, -50, 0), (50, -50, 0), (50, 50, 0)], [(-50, -50, 0), (50, 50, 0), (-50, 50, 0)]], float)
    view = rasterise([("back", square, (1.0, 0.0, 0.0, 1.0)), ("glass", square + [0, 0, 10], (0.0, 0.0, 1.0, 0.35))],
                     (0.0, 90.0 - 1e-6), (200, 200))
    inner = view.image[60:140, 60:140].reshape(-1, 3)
    shade = 0.35 + 0.65 * abs(np.array([0, 0, 1.0]) @ (view.basis.T @ np.array([-0.35, 0.45, 1.0])) /
                               np.linalg.norm([-0.35, 0.45, 1.0]))
    np.testing.assert_allclose(inner, np.tile([0.65 * shade, 0.0, 0.35 * shade], (len(inner), 1)), atol=1e-9)
    assert np.all(view.part_index[60:140, 60:140] == 0)


def test_render_of_a_translucent_part_wholly_behind_an_opaque_one_shows_the_opaque_one():
    """A reference body hidden behind an opaque plate leaves no fragment to blend: the picture is
    the plate alone (the rasteriser raised on the empty blend before)."""
    from geargen.cad.render import rasterise
    square = np.array([[(-50, -50, 0), (50, -50, 0), (50, 50, 0)], [(-50, -50, 0), (50, 50, 0), (-50, 50, 0)]], float)
    view = rasterise([("plate", square + [0, 0, 10], (1.0, 0.0, 0.0, 1.0)), ("glass", 0.5 * square, (0.0, 0.0, 1.0, 0.35))],
                     (0.0, 90.0 - 1e-6), (200, 200))
    shade = 0.35 + 0.65 * abs(np.array([0, 0, 1.0]) @ (view.basis.T @ np.array([-0.35, 0.45, 1.0])) /
                               np.linalg.norm([-0.35, 0.45, 1.0]))
    inner = view.image[20:180, 20:180].reshape(-1, 3)
    # the plate's flat shade exactly: nothing of the blue glass is added (1e-12: rounding of the shade only)
    np.testing.assert_allclose(inner, np.tile([shade, 0.0, 0.0], (len(inner), 1)), atol=1e-12)
    assert np.all(view.part_index[20:180, 20:180] == 0)


@pytest.mark.slow
def test_render_of_the_split_pinion_shows_its_output_bearing_whole(built_assemblies):
    """The artefact the issue reported, on the shipped design's exported meshes: the output
    gear's upper bearing stands just above the gear's face, so all of it is seen and nothing
    outside it is. Drawing whole triangles sorted by their centroids (the render before) painted
    the face's small triangles round the bore over the lower halves of the bearing's side
    triangles whose centroids lay lower: a ring of spikes."""
    from geargen.cad.export import read_stl
    from geargen.cad.render import rasterise
    folder = built_assemblies["split_pinion"]
    gear, bearing = read_stl(folder / "output.stl"), read_stl(folder / "output_bearing_upper.stl")
    points = bearing.reshape(-1, 3)
    bottom, top = float(points[:, 2].min()), float(points[:, 2].max())
    assert 0 < bottom - float(gear[:, :, 2].max()) < 1.0  # standing just above the face
    centre = points[:, :2].mean(axis=0)
    radial = np.hypot(*(points[:, :2] - centre).T)
    radius, bore = float(radial.max()), float(radial.min())
    view = rasterise([("output", gear, (0.55, 0.6, 0.7, 1.0)), ("bearing", bearing, (0.2, 0.45, 0.3, 1.0))],
                     (-60.0, 30.0), (990, 715))
    seen, outside, missing = _upper_part_pixels(view, "bearing", bottom, top, radius, centre, bore)
    assert seen > 2000
    assert (outside, missing) == (0, 0)


def test_render_figure_has_labels_clear_of_each_other_a_scale_bar_and_a_triad():
    """The view's figure: a label per part (bearings and shafts left to the parts table), no two
    text boxes overlapping, the scale bar a round length in the design's unit drawn at its length."""
    from geargen.cad.render import rasterise
    from geargen.report.view import view_figure
    plate = np.array([[(-60, -60, 0), (60, -60, 0), (60, 60, 0)], [(-60, -60, 0), (60, 60, 0), (-60, 60, 0)]], float)
    view = rasterise([("plate", plate, (0.3, 0.4, 0.8, 1.0)),
                      ("pin", _cylinder(10.0, -30.0, 15.0), (0.8, 0.2, 0.2, 1.0)),
                      ("pin_bearing", _cylinder(14.0, 0.0, 4.0), (0.2, 0.45, 0.3, 1.0))], (-60.0, 30.0), (700, 500))
    view.kinds = ["housing", "gear", "bearing"]
    fig = view_figure(view, "in")
    fig.canvas.draw()
    texts = [t for t, _ in text_boxes(fig)]
    assert "plate" in texts and "pin" in texts and "pin_bearing" not in texts
    assert {"x", "y", "z"} <= set(texts)
    boxes = text_boxes(fig)
    assert_apart(boxes)
    bar = next(t for t in texts if t.endswith(" in"))
    length_in = float(bar.split()[0])
    ax = fig.axes[0]
    line = next(ln for ln in ax.lines if ln.get_linewidth() == 2.5)
    assert np.ptp(line.get_xdata()) == pytest.approx(length_in * 25.4)
    assert length_in in (0.5, 1.0, 2.0)  # a round length near a fifth of the ~150 mm wide picture


def _figure_bytes(view, resample: bool, dpi: int = 110) -> dict[str, bytes]:
    """The view figure's PNG and SVG as save_figure writes them; ``resample``: every draw of the
    picture through matplotlib's resampling (the one-pixel shortcut switched off)."""
    import matplotlib

    from geargen.report import view as view_module
    from geargen.report.view import view_figure
    image_class = view_module._one_pixel_image()
    taken = []
    rows_flipped = image_class._rows_flipped

    def counted(self, magnification):
        out = None if resample else rows_flipped(self, magnification)
        taken.append(out is not None)
        return out
    out = {}
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(image_class, "_rows_flipped", counted)
        fig = view_figure(view, "mm", dpi=110)
        with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "geargen"}):
            for fmt in ("png", "svg"):
                buffer = io.BytesIO()
                fig.savefig(buffer, format=fmt, dpi=dpi, facecolor="white",
                            metadata={"Date": None} if fmt == "svg" else None)
                out[fmt] = buffer.getvalue()
    out["taken"] = taken
    return out


def test_render_figure_drawn_without_resampling_has_the_bytes_of_the_resampled_one():
    """The view's picture is drawn as its rows bottom to top where it lies one pixel on one output
    pixel (no resampling, ~35 ms less a build): the PNG and the SVG are byte for byte those of
    matplotlib's resampling, on a picture of every 8-bit level (random, seeded) with parts to
    label; at another dpi the picture is resampled (the shortcut is not taken) and the bytes
    again agree."""
    from geargen.cad.render import rasterise
    plate = np.array([[(-60, -60, 0), (60, -60, 0), (60, 60, 0)], [(-60, -60, 0), (60, 60, 0), (-60, 60, 0)]], float)
    view = rasterise([("plate", plate, (0.3, 0.4, 0.8, 1.0)), ("pin", _cylinder(10.0, -30.0, 15.0), (0.8, 0.2, 0.2, 1.0)),
                      ("glass", _cylinder(40.0, 0.0, 10.0), (0.6, 0.6, 0.6, 0.3))], (-60.0, 30.0), (537, 391),
                     title="one pixel")
    view.kinds = ["housing", "gear", "housing"]
    view.image = np.random.default_rng(28).random(view.image.shape)
    view.image[:2] = [[0.0, 1.0, 254.5 / 255]]  # the extreme levels and a value just below a level's edge
    fast, slow = _figure_bytes(view, resample=False), _figure_bytes(view, resample=True)
    assert fast["taken"] == [True, True] and slow["taken"] == [False, False]  # one draw each for the PNG and the SVG
    assert fast["png"] == slow["png"]
    assert fast["svg"] == slow["svg"]
    # at 72 dpi the picture (sized for 110) is scaled in both: resampled by matplotlib
    fast, slow = _figure_bytes(view, resample=False, dpi=72), _figure_bytes(view, resample=True, dpi=72)
    assert fast["taken"] == [False, False]
    assert fast["png"] == slow["png"] and fast["svg"] == slow["svg"]


# ---------------------------------------------------------------- files, manifest, key numbers, tables


@pytest.mark.slow
def test_figures_are_files_linked_from_the_report_and_listed_in_the_manifest(built_assemblies, tmp_path):
    folder = built_assemblies["robot_joint"]
    manifest = json.loads((folder / "manifest.json").read_text())
    html = (folder / "report.html").read_text()
    md = (folder / "report.md").read_text()
    assert "data:image" not in html and "data:image" not in md
    assert (folder / "report.html").stat().st_size < 60_000  # was ~530 KB with the figures inside
    for name in ("render", "layout", "preload_diagram"):
        for fmt in ("png", "svg"):
            rel = f"figures/{name}.{fmt}"
            path = folder / rel
            assert manifest["files"][rel]["bytes"] == path.stat().st_size > 10_000
        assert f"src='figures/{name}.png'" in html and f"(figures/{name}.png)" in md
        assert (folder / f"figures/{name}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert ET.parse(folder / f"figures/{name}.svg").getroot().tag.endswith("svg")
    state = inspect_folder(folder)
    assert (state.kind, state.generator, state.unknown, state.changed) == ("output", "geargen build", [], [])
    # a reviewer's change inside figures/ is seen like one at the top
    copy = tmp_path / "copy"
    shutil.copytree(folder, copy)
    (copy / "figures/layout.svg").write_text("<svg xmlns='http://www.w3.org/2000/svg'/>")
    (copy / "figures/mine.png").write_bytes(b"x")
    (copy / "figures/notes").mkdir()
    state = inspect_folder(copy)
    assert state.changed == ["figures/layout.svg"]
    assert state.unknown == ["figures/mine.png", "figures/notes"]


def _run(argv) -> dict:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        assert main(argv) == 0
    return json.loads(out.getvalue())


def test_plain_number_has_one_format():
    """Positional, at most 5 significant digits, whole numbers whole, no trailing zeros."""
    assert [plain_number(v) for v in (1305026.4, 37101.44, 77.1423, 5.0, 0.00123456, 5e-5, None)] == \
        ["1305026", "37101", "77.142", "5", "0.0012346", "0.00005", "-"]


@pytest.mark.slow
def test_the_build_counts_the_files_it_writes_and_names_each_monte_carlo(built_assemblies):
    """Issue 31: the build said "ok, 59 files" and wrote 93 (it counted the exports only): the count is
    every file of the folder, which is the manifest's list and the manifest. The robot joint's
    [monte_carlo] samples = 1000000 (synth's carriage travel) beside the report's backlash Monte Carlo
    of [checks] monte_carlo_samples (400 by default): the report says which setting each uses."""
    from geargen.commands.build import files_written
    folder = built_assemblies["robot_joint"]
    manifest = json.loads((folder / "manifest.json").read_text())
    exports = sum(1 for v in manifest["files"].values() if v.get("role") is None)
    assert files_written(folder) == len(manifest["files"]) + 1 > exports
    md = (folder / "report.md").read_text()
    section = md.split("## Backlash across the error budget", 1)[1].split("\n## ", 1)[0]
    assert "backlash Monte Carlo, 400 builds per mesh ([checks] monte_carlo_samples)" in section
    assert "[monte_carlo] samples = 1000000 is another Monte Carlo, the centre synthesis's carriage travel" in section
    assert "builds ([checks] monte_carlo_samples)" in section
    rows = [line for line in section.splitlines() if line.startswith("| mesh1") or line.startswith("| mesh2")]
    assert rows and all("| 400 |" in line for line in rows)


@pytest.mark.slow
def test_key_numbers_are_the_stiffness_and_check_commands_numbers(built_assemblies):
    design = ROOT / "assemblies/robot_joint.toml"
    folder = built_assemblies["robot_joint"]
    numbers = json.loads((folder / "manifest.json").read_text())["key_numbers"]
    stiffness = _run(["stiffness", str(design), "--json", "-", "--no-plots"])
    check = _run(["check", str(design), "--json", "-"])
    assert numbers["drive_stiffness_Nm_per_rad"] == pytest.approx(stiffness["drive"]["stiffness_Nm_per_rad"], rel=1e-12)
    assert numbers["drive_stiffness_with_common_Nm_per_rad"] == pytest.approx(
        stiffness["drive"]["stiffness_with_common_Nm_per_rad"], rel=1e-12)
    assert numbers["drive_stiffness_with_common_Nm_per_rad"] < numbers["drive_stiffness_Nm_per_rad"]
    assert numbers["loop_stiffness_Nm_per_rad"] == pytest.approx(stiffness["loop"]["stiffness_Nm_per_rad"], rel=1e-12)
    assert numbers["preload_Nm"] == pytest.approx(stiffness["preload"]["preload_Nm"], rel=1e-12)
    head = next(v for v in stiffness["preload_variation"] if v["label"] == stiffness["headline_budget"])
    assert numbers["preload_variation"]["range_Nm"] == pytest.approx(head["range_Nm"], rel=1e-12)
    assert numbers["preload_variation"]["relative"] == pytest.approx(head["relative"], rel=1e-12)
    worst = {t["mesh"]: t["worst_case_min_backlash"] for t in check["tolerances"]}
    built = {b["mesh"]: b["min"] for b in check["backlash"]}
    assert check["length_unit"] == numbers["length_unit"] == "in"
    assert [m["mesh"] for m in numbers["meshes"]] == [b["mesh"] for b in check["backlash"] if b["engaged"]]
    for m in numbers["meshes"]:
        assert m["worst_case_min_backlash"] == pytest.approx(worst[m["mesh"]], rel=1e-9)
        assert m["min_backlash"] == pytest.approx(built[m["mesh"]], rel=1e-12)
    assert numbers["ratio"] == "30/15 x 16 = 32" or "32" in numbers["ratio"]
    md = (folder / "report.md").read_text()
    block = md.split("## Key numbers", 1)[1].split("\n## ", 1)[0]
    # one number format (issue 31: scientific notation stood beside plain numbers)
    g = plain_number
    assert f"| drive stiffness k_D (N·m/rad) | {g(numbers['drive_stiffness_Nm_per_rad'])} |" in block
    assert (f"| drive stiffness with common parts (N·m/rad) | {g(numbers['drive_stiffness_with_common_Nm_per_rad'])} |"
            in block)
    assert f"| loop stiffness k_L (N·m/rad) | {g(numbers['loop_stiffness_Nm_per_rad'])} |" in block
    assert f"| preload (N·m) | {g(numbers['preload_Nm'])} |" in block
    assert f"{g(head['range_Nm'], 4)} ({100 * head['relative']:.2f} %" in block
    for m in numbers["meshes"]:
        assert f"{g(worst[m['mesh']])} worst case" in block
    assert not re.search(r"\d[eE][+-]\d", block)
    assert f"| warnings | {numbers['warnings']} |" in block
    assert md.index("## Key numbers") < md.index("## Warnings")


def test_load_capacity_of_the_build_is_the_checks(built_assemblies):
    """The build's manifest, key numbers and report carry the load capacity ``geargen check --json``
    gives (one rating, read three ways): every mesh's S_H and S_F per flank, the least of each."""
    design = ROOT / "assemblies/robot_joint.toml"
    folder = built_assemblies["robot_joint"]
    manifest = json.loads((folder / "manifest.json").read_text())
    check = _run(["check", str(design), "--json", "-"])["load_capacity"]
    built = manifest["checks"]["load_capacity"]
    assert built["duty_stated"] and built["ok"] and check["ok"]
    def flanks(lc):
        return {(m["name"], f["flank"]): (tuple(f["S_H"]), tuple(f["S_F"])) for m in lc["meshes"]
                for f in m.get("flanks", ())}

    assert flanks(built) == flanks(check) and len(flanks(built)) == 4
    least = min(v for s_h, _ in flanks(built).values() for v in s_h)
    assert manifest["key_numbers"]["load_capacity"]["min_S_H"] == pytest.approx(least, rel=1e-12)
    md = (folder / "report.md").read_text()
    block = md.split("## Load capacity", 1)[1].split("\n## ", 1)[0]
    assert "| mesh | role | flank | preload | peak F_t | b | b needed | S_H gear 1/2 | S_F gear 1/2 |" in block
    s_h = flanks(built)[("mesh2_a", "cw")][0]
    assert f"{s_h[0]:#.3g}/{s_h[1]:#.3g}" in block


_NUMBER = re.compile(r"(?<![\w.])[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


@pytest.mark.slow
def test_synthesis_and_stiffness_are_tables_with_every_number_of_the_text(built_assemblies):
    """Each number the text summaries print (``geargen stiffness``' summary and the Appendix
    table of ``geargen synth``) is in the report, now in pipe tables, not fenced text."""
    from geargen.report.stiffness import format_summary
    from geargen.report.synthesis import appendix_table
    design = ROOT / "assemblies/robot_joint.toml"
    md = (built_assemblies["robot_joint"] / "report.md").read_text()
    html = (built_assemblies["robot_joint"] / "report.html").read_text()
    assert "```" not in md and "<pre>" not in html
    assert "| Description | Symbol/Unit | Gear 1 | Gear 2 | Gear 3 | Gear 4 |" in md
    assert "| component | local stiffness | N·m/rad | share of compliance |" in md
    assert "<th>Symbol/Unit</th>" in html and "<th>share of compliance</th>" in html
    layout = pl.place(pl.load(design))
    in_report = set(_NUMBER.findall(md))
    for text in (format_summary(pl.stiffness(layout)), appendix_table(layout.synthesis)):
        missing = sorted(set(_NUMBER.findall(text)) - in_report)
        assert not missing, missing
