"""The shipped assemblies build end to end; the exports re-import as valid named solids, no parts
overlap except the listed contacts, and the teeth of every mesh, measured on sections of the
exported solids at mid-face, have backlash in the design's range.

Every test here needs the CAD kernel (marked slow; CI runs them): the builds are shared by the
whole session (tests/conftest.py), so the file costs one build per assembly and the re-imports."""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from geargen import pipeline as pl
from geargen.cad.gear_solid import default_tolerance
from geargen.checks.verdict import design_backlash

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]
DESIGNS = {"robot_joint": ROOT / "assemblies/robot_joint.toml", "c_axis": ROOT / "assemblies/c_axis.toml",
           "split_pinion": ROOT / "assemblies/split_pinion.toml",
           "axial_preload": ROOT / "assemblies/axial_preload.toml",
           "rack_drive": ROOT / "assemblies/rack_drive.toml",
           # design files only: no Python of their own
           "split_pinion_inch": ROOT / "assemblies/split_pinion_inch.toml",
           "metric_dual_pinion": ROOT / "assemblies/metric_dual_pinion.toml",
           "planetary_dual_pinion": ROOT / "assemblies/planetary_dual_pinion.toml",
           # gears and a synthesis only: every other part from the default hardware
           "gears_only": ROOT / "tests/data/metric_dual_pinion.toml"}

# Each assembly is built once per session, through geargen.cli.main (the README's command), by the
# ``built_assemblies`` fixture of tests/conftest.py; its re-imported STEP files are read once too.


def _manifest(folder: Path) -> dict:
    return json.loads((folder / "manifest.json").read_text())


def _volume(shape) -> float:
    """Volume (mm^3) by Gauss-Kronrod integration: with a coarse accuracy target when its error
    estimate already comes out at 1e-6 relative or less, else with the 1e-6 target the manifest's
    volumes were computed with. (Asking 1e-6 of the re-imported spring's swept B-spline takes ~2
    minutes, while a 1e-3 target integrates it to ~5e-7 in milliseconds.)"""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    for eps in (1e-3, 1e-4, 1e-6):
        props = GProp_GProps()
        err = BRepGProp.VolumePropertiesGK_s(shape, props, eps, True, True, False, False, True)
        if err <= 1e-6:
            break
    return props.Mass()


@pytest.mark.parametrize("name", list(DESIGNS))
def test_build_writes_everything_with_a_manifest(built_assemblies, name):
    folder = built_assemblies[name]
    m = _manifest(folder)
    design = pl.load(DESIGNS[name])
    assert m["status"] == "ok" and not m["failures"]
    assert m["design"]["sha256"] == design.sha256
    assert m["versions"]["cadquery"] and m["units"]["stl"] == "mm"
    for f in ("assembly.step", "report.md", "report.html", "manifest.json"):
        assert (folder / f).stat().st_size > 0
    for part, info in m["parts"].items():
        for f in info["files"]:
            assert f in m["files"] and (folder / f).exists()
    html = (folder / "report.html").read_text()
    # the preload diagram is drawn from the stiffness summary of [stiffness]; the rack drive gives
    # its Eqs. 5-6 in its check rows (geargen.drives.rack_dual_pinion.verdict) and has no such section
    figures = ("render", "layout") + (("preload_diagram",) if design.section("stiffness") else ())
    for figure in figures:  # linked files, listed in the manifest
        assert f"src='figures/{figure}.png'" in html and f"figures/{figure}.svg" in m["files"]
    assert not list(folder.parent.glob(".*"))  # the temporary build folder is gone


@pytest.mark.parametrize("name", list(DESIGNS))
def test_every_part_reimports_as_one_valid_solid(built_assemblies, name):
    from geargen.cad.gear_solid import check_solid
    m = _manifest(built_assemblies[name])
    unit = {"mm": "MM", "in": "INCH"}[m["design"]["length_unit"]]
    for part, info in m["parts"].items():
        step = built_assemblies.step(name, part)
        assert check_solid(step.shape) is None, part
        # volume in mm^3 after the unit conversion on reading, as built (STEP carries the design's unit)
        assert _volume(step.shape) == pytest.approx(info["volume_mm3"], rel=1e-5), part
        assert any(unit in u.upper() or (unit == "MM" and "MILLI" in u.upper()) for u in step.units) or step.units


@pytest.mark.parametrize("name", list(DESIGNS))
def test_assembly_step_holds_the_named_parts(built_assemblies, name):
    folder = built_assemblies[name]
    text = (folder / "assembly.step").read_text(errors="replace")
    # identical solids are one product; each placement is an occurrence carrying the part's name
    names = set(re.findall(r"PRODUCT\('([^']*)'", text)) | set(re.findall(r"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('[^']*','([^']*)'", text))
    parts = _manifest(folder)["parts"]
    for part in parts:
        assert part in names, part
    assert "COLOUR_RGB" in text  # colours travel with the parts
    # and the geometry: one solid per part, each with the volume of its part
    from geargen.cad.export import read_step
    from geargen.cad.parts import solids
    found = sorted(_volume(s) for s in solids(read_step(folder / "assembly.step").shape))
    assert found == pytest.approx(sorted(p["volume_mm3"] for p in parts.values()), rel=1e-5)


@pytest.mark.parametrize("name", list(DESIGNS))
def test_no_parts_overlap_except_intended_contacts(built_assemblies, name):
    ov = _manifest(built_assemblies[name])["checks"]["overlaps"]
    assert ov["unintended"] == []
    assert ov["pairs_checked"] > 0 and ov["intended_contacts"]
    # every meshing pair is left to the mesh checker, which measured backlash on both flanks there
    meshes = _manifest(built_assemblies[name])["checks"]["meshes"]
    # (and the bevel pair of the robot joint, by the bevel mesh checker: tests/test_robot_bevel.py)
    bevel = _manifest(built_assemblies[name])["checks"].get("bevel_meshes", [])
    # (and the rack meshes of the rack drive, by the rack pair checker: tests/test_rack_drive.py)
    rack = _manifest(built_assemblies[name])["checks"].get("rack_meshes", [])
    assert len(ov["meshing_pairs"]) == len(meshes) + len(bevel) + len(rack)


def _own_frame(shape, matrix):
    """A re-imported (assembly-frame) shape moved back into its part's own frame."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from geargen.cad.assembly import _trsf
    inv = np.linalg.inv(np.asarray(matrix, dtype=float))
    return BRepBuilderAPI_Transform(shape, _trsf(inv), True).Shape()


def _exported_gears(built_assemblies, name, mesh, manifest):
    return [_own_frame(built_assemblies.step(name, p).shape, manifest["parts"][p]["placement_matrix_mm"])
            for p in (mesh.part1, mesh.part2)]


@pytest.mark.parametrize("name", list(DESIGNS))
def test_backlash_measured_on_the_exported_solids_is_in_the_design_range(built_assemblies, name):
    """Sections of the re-imported STEP solids at mid-face (geargen.checks.solids), gear 1 turned
    against gear 2 over a tooth cycle: the backlash (design kind) lies in [min, max]; and it is the
    one the build measured on the solids in memory (the manifest's path-2 numbers)."""
    m = _manifest(built_assemblies[name])
    built = {e["mesh"]: e for e in m["checks"]["meshes"]}
    layout = pl.place(pl.load(DESIGNS[name]))
    checked = 0
    for mesh in layout.meshes:
        if not mesh.engaged:
            continue
        result = pl.section_check(layout, mesh, *_exported_gears(built_assemblies, name, mesh, m))
        assert result.ok, result.failures
        lo, hi = design_backlash(result, mesh.gear1.reference_radius)
        # the sections' chords lie inside the exact flanks by up to the stated tolerance
        tol = result.tolerance
        assert mesh.backlash_min - tol <= lo and hi <= mesh.backlash_max + tol, (mesh.name, lo, hi)
        # STEP keeps the geometry to ~1e-15 relative: the exported teeth are the checked ones (1 nm)
        assert lo == pytest.approx(built[mesh.name]["path2_backlash_min"], abs=1e-6), mesh.name
        assert hi == pytest.approx(built[mesh.name]["path2_backlash_max"], abs=1e-6), mesh.name
        # and the exact path 1's, to the chords' tolerance plus the solids' own: each gear's flank
        # spline lies within [export] gear_solid_tolerance of the exact surface (normal to it), so
        # the two flanks move the circumferential play by up to twice that / cos(alpha_t). A
        # section of the wrong gear (a one-piece cluster's large gear where its small one meshes)
        # lands far from it
        spline = pl.export_config(layout.design)["gear_solid_tolerance"] or min(
            default_tolerance(g) for g in (mesh.gear1, mesh.gear2))
        solids = 2 * spline / math.cos(mesh.gear1.transverse_pressure_angle)
        assert lo == pytest.approx(built[mesh.name]["backlash_min"], abs=tol + solids + 1e-6), mesh.name
        assert hi == pytest.approx(built[mesh.name]["backlash_max"], abs=tol + solids + 1e-6), mesh.name
        checked += 1
    assert checked == len([x for x in layout.meshes if x.engaged]) >= 2


def test_sections_near_the_mesh_are_those_of_every_face(built_assemblies):
    """The build sections only the faces that can reach the other gear (``near=True``): on the
    exported solids of a mesh, every quantity of the sweep is the one from sectioning every face."""
    name = "robot_joint"
    m = _manifest(built_assemblies[name])
    layout = pl.place(pl.load(DESIGNS[name]))
    mesh = next(x for x in layout.meshes if x.name == "mesh1_a")
    shapes = _exported_gears(built_assemblies, name, mesh, m)
    near = pl.section_check(layout, mesh, *shapes, near=True)
    every = pl.section_check(layout, mesh, *shapes, near=False)
    for key in ("play_ccw", "play_cw", "angular_backlash", "normal_backlash", "min_clearance", "interference"):
        np.testing.assert_array_equal(getattr(near.sweep, key), getattr(every.sweep, key), err_msg=key)
    assert [f.kind for f in near.failures] == [f.kind for f in every.failures]
    # the stated tolerance covers the sectioned faces only: never more than over every face
    assert near.tolerance <= every.tolerance * (1 + 1e-9)


def test_c_axis_ratio_is_exact_and_allowed():
    layout = pl.place(pl.load(DESIGNS["c_axis"]))
    assert layout.ratio["ok"] and layout.ratio["total"] == 180  # Fraction: exact, no rounding


def test_c_axis_disengaged_slides_the_pinions_out_with_the_lead():
    design = pl.load(DESIGNS["c_axis"])
    engaged, out = pl.place(design), pl.place(design, "disengaged")
    eng = out.engagement
    za = out.gear("cluster_small_a").z - engaged.gear("cluster_small_a").z
    zb = out.gear("cluster_small_b").z - engaged.gear("cluster_small_b").z
    assert za == pytest.approx(eng.leader_retracted_stop) and zb == pytest.approx(eng.trailer_retracted_stop)
    assert za - zb == pytest.approx(eng.lead)
    assert [m.engaged for m in out.meshes if m.name.startswith("mesh2")] == [False, False]
    checks = pl.mesh_checks(out)
    assert checks.ok, checks.failures
    assert all(e["axial_clearance"] > 0 for e in checks.meshes if e.get("status") == "disengaged")


@pytest.mark.parametrize("name", ["split_pinion", "split_pinion_inch"])
def test_split_pinion_inner_shaft_keeps_the_preload_band(name):
    s = pl.stiffness(pl.place(pl.load(DESIGNS[name])))
    v = s.headline
    assert s.drive_type == "type1" and s.preload_ok
    assert v.relative < 0.2 and not v.unloads  # sized for a 20 % band at the anticipated loop error


def _exit_at_once():
    import os
    os._exit(3)


def _raise():
    raise ValueError("no")


def test_a_second_process_that_delivers_nothing_leaves_the_work_to_the_caller():
    """The build runs the mesh checks here whenever the second process gives no result."""
    got = pl.Alongside.start(divmod, 7, 2)
    if got is None:
        pytest.skip("no fork on this platform")
    seconds, value = got.result()
    assert value == (3, 1) and seconds >= 0
    assert pl.Alongside.start(_exit_at_once).result() is None  # died
    assert pl.Alongside.start(_raise).result() is None  # raised: the caller's own run raises it


def test_a_child_started_behind_runs_at_a_lower_priority():
    """``nice`` lowers the child's priority by that many steps (the build's checks, drawings and figures
    yield to its STEP files' process); without it the child keeps the caller's."""
    import os
    behind = pl.Alongside.start(os.nice, 0, nice=pl.BEHIND)
    if behind is None:
        pytest.skip("no fork on this platform")
    mine = os.nice(0)
    assert behind.result()[1] == min(mine + pl.BEHIND, 19)
    assert pl.Alongside.start(os.nice, 0).result()[1] == mine


def test_a_build_runs_its_drawings_and_figures_behind(monkeypatch, tmp_path):
    """The policy of pipeline.BEHIND: the drawings' and the view and figures' processes yield, which nothing
    waits for but the report; the checks' and the STEP files' processes, which may each end the build, do not."""
    started = []
    start = pl.Alongside.start.__func__

    def recording(cls, fn, *args, nice=0):
        started.append((fn.__name__, nice))
        return start(cls, fn, *args, nice=nice)

    monkeypatch.setattr(pl.Alongside, "start", classmethod(recording))
    pl.build(DESIGNS["split_pinion"], out=tmp_path / "out", quiet=True)
    assert dict(started) == {"design_verdict": 0, "drawings": pl.BEHIND, "mesh_sections": 0, "overlap_check": 0,
                             "view_and_figures": pl.BEHIND, "export_step_files": 0, "layout_figure_files": 0}


def _ring_volume(outer: float, inner: float, height: float) -> float:
    from geargen.cad import parts as P
    from geargen.cad.kernel import volume
    return volume(P.cylinder(outer, height, inner))  # a parallel boolean (cut) unless in a forked child


def test_a_forked_process_runs_the_kernel_on_its_one_thread():
    """A process forked after the kernel's thread pool started has no pool threads: a parallel
    boolean there waited for them for ever (the overlap check's process hung on a gear's core). In
    the child the kernel runs serially, and computes the same solid."""
    here = _ring_volume(20.0, 8.0, 5.0)  # starts the pool in this process
    child = pl.Alongside.start(_ring_volume, 20.0, 8.0, 5.0)
    if child is None:
        pytest.skip("no fork on this platform")
    got = child.result(timeout=60.0)  # seconds of a serial cut; hung for ever before
    assert got is not None
    # closed form pi/4 (D^2 - d^2) h; the kernel's integration is exact to ~1e-12 for a ring
    assert got[1] == pytest.approx(here, rel=1e-12)
    assert here == pytest.approx(math.pi / 4 * (20.0 ** 2 - 8.0 ** 2) * 5.0, rel=1e-9)


class _DeliversNothing:
    """A second process that died: its result is None."""

    def result(self):
        return None


def test_collected_checks_are_those_of_the_build_in_order():
    """Three processes check the meshes (the verdict, path 2's sections) and the parts' overlaps; the
    collected outcome is the in-order one, from the processes or made here for the one that
    delivers nothing (or was never started)."""
    layout = pl.place(pl.load(DESIGNS["split_pinion"]))
    gears = pl.gear_solids(layout)
    parts = pl.other_parts(layout, gears, pl.stiffness(layout))
    in_order = pl._all_checks(layout, gears, parts)

    def summary(outcome):
        ov = outcome.overlaps
        return (outcome.failures, outcome.warnings, ov.pairs_checked, [(o.part1, o.part2, o.volume) for o in ov.overlaps],
                ov.missing_contacts, outcome.structure.to_dict(),
                [(m["mesh"], m.get("backlash_min"), m.get("backlash_max"), m.get("path2_backlash_min"))
                 for m in outcome.meshes])

    here, seconds, note = pl._collect_checks(_DeliversNothing(), _DeliversNothing(), layout, gears, parts)
    assert "verdict and the sections" in note and "checked here" in note and seconds > 0
    assert summary(here) == summary(in_order)
    verdict = pl.Alongside.start(pl.design_verdict, layout)
    if verdict is None:
        pytest.skip("no fork on this platform")
    # either process may fail alone: the other's part is still the one delivered
    half, _, note = pl._collect_checks(verdict, _DeliversNothing(), layout, gears, parts)
    assert "the sections of a second process delivered nothing" in note
    assert summary(half) == summary(in_order)
    verdict = pl.Alongside.start(pl.design_verdict, layout)
    sections = pl.Alongside.start(pl.mesh_sections, layout, gears)
    there, _, note = pl._collect_checks(verdict, sections, layout, gears, parts)
    assert "processes of their own" in note
    assert summary(there) == summary(in_order)
    verdict = pl.Alongside.start(pl.design_verdict, layout)
    sections = pl.Alongside.start(pl.mesh_sections, layout, gears)
    overlaps = pl.Alongside.start(pl.overlap_check, parts, layout)
    there, _, note = pl._collect_checks(verdict, sections, layout, gears, parts, overlaps)
    assert "processes of their own" in note
    assert summary(there) == summary(in_order)
    lost, _, note = pl._collect_checks(pl.Alongside.start(pl.design_verdict, layout), _DeliversNothing(),
                                       layout, gears, parts, _DeliversNothing())
    assert "the sections and the overlaps of a second process delivered nothing" in note
    assert summary(lost) == summary(in_order)


def test_drawings_from_their_own_process_are_those_drawn_here(tmp_path):
    """The build draws the drawings in a process of their own (issue 28): the files it collects are
    byte for byte those drawn here in order (no file carries a date or a random id: the DXF's header
    too, tests/test_reproducible_build.py), and a process that delivers nothing leaves the drawing
    to the caller."""
    layout = pl.place(pl.load(DESIGNS["split_pinion"]))
    here = pl.drawings(layout, tmp_path / "here")
    child = pl.Alongside.start(pl.drawings, layout, tmp_path / "there")
    if child is None:
        pytest.skip("no fork on this platform")
    there, seconds, note = pl._collect(child, pl.drawings, layout, tmp_path / "there")
    assert "own" in note and seconds > 0
    assert set(there) == set(here) and any(k.endswith(":pdf") for k in here)

    for key, path in here.items():
        assert Path(there[key]).read_bytes() == Path(path).read_bytes(), key
    fallback, _, note = pl._collect(_DeliversNothing(), pl.drawings, layout, tmp_path / "fallback")
    assert "made here" in note and set(fallback) == set(here)


@pytest.mark.parametrize("parallel", [True, False], ids=["checks-alongside", "checks-in-order"])
def test_failing_build_writes_nothing_unless_forced(tmp_path, parallel):
    """With the mesh checks in a second process the exports are written meanwhile: they must go too."""
    from geargen.cli import main
    text = DESIGNS["split_pinion"].read_text().replace('model_tooth_thickness = "mid_tolerance"',
                                                       'model_tooth_thickness = "as_designed"')
    bad = tmp_path / "split_pinion.toml"
    bad.write_text(text)  # unthinned pinions at the standard centre distance: no backlash at all
    out = tmp_path / "out"
    if parallel:
        assert main(["build", str(bad), "--out", str(out), "--quiet"]) == 1
    else:
        with pytest.raises(pl.BuildFailed, match="fails its checks"):
            pl.build(bad, out=out, quiet=True, parallel=False)
    assert not out.exists() and not list(tmp_path.glob(".out*"))


def test_rack_drive_build_and_check_give_one_verdict(built_assemblies):
    """The rack drive's build passed its checks; ``geargen check`` on the same file gives the same
    verdict (no failures) with the rack meshes' rows, and the manifest lists the rack's data."""
    from geargen.checks.verdict import check_design
    folder = built_assemblies["rack_drive"]
    result, _ = check_design(pl.load(DESIGNS["rack_drive"]))
    assert result.ok and _manifest(folder)["status"] == "ok"
    assert {r["mesh"] for r in result.rack} == {"rack_a", "rack_b", "carriage"}
    data = json.loads((folder / "drawings" / "rack.json").read_text())
    assert data["kind"] == "rack" and data["teeth"] % 2 == 0
