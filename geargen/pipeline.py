"""The build of an assembly, step by step: the one place that knows the order of the steps.

    load -> place -> gear solids -> stiffness -> other parts -> mesh checks -> export -> report

(the stiffness step comes before the other parts because it sizes some of them: the beam-spring
pinion's bearing span, the sliding pinions' travel stops)

Each step is a function taking the results of the steps before it, so any step can be run
alone (tests do); :func:`build` runs them all, shows progress on standard error (``quiet``
silences it) and writes the output atomically: everything goes into a temporary folder beside
the target, which replaces ``exports/<design file name>/`` only once every file is written (the
folder policy and the temporary folders are :mod:`geargen.outputs`'). A build whose
mesh checks fail raises :class:`BuildFailed` and leaves nothing behind, unless ``force``: then
the files are written and marked as failing in the manifest and the report. The mesh checks of
the gears need only the layout and the gear solids, so :func:`build` runs them in a second
process (:class:`Alongside`) while this one builds the other parts and writes the view and the
exports into the temporary folder; nothing is moved into place before they have passed. The
drawings (which need only the placed drive) and the figures that need no check result are drawn
in processes of their own too, so nothing waits for matplotlib.

Placement, tooth thickness and every other length of the drive come from one resolved model,
:func:`geargen.model.resolve` (step "place"); the checks, the solids, the stiffness and the
reports all read it, and ``resolved.json`` beside the exports records it.
"""

from __future__ import annotations

import math
import os
import platform
import signal
import sys
import time
from dataclasses import dataclass, field, replace
from fractions import Fraction
from pathlib import Path
from typing import Any, Callable

import numpy as np

from geargen.design.assembly import Design, load_design
from geargen.design.export import export_settings
from geargen.errors import GeargenError
from geargen.model import POSITIONS, GearPlacement, Layout, MeshPlacement
from geargen.drives.resolver import resolve
from geargen.units import from_mm

#: the build folder's sub-folder of the gears' drawings, DXF profiles and gear data
DRAWING_FOLDER = "drawings"
STEPS = ("load", "place", "gear solids", "stiffness", "other parts", "mesh checks", "export", "figures", "drawings",
         "report")
#: how many steps below the build's own priority the drawings' and the view and figures' processes run: on 2
#: cores the build is processor-bound, nothing waits for those two but the report, while the main process,
#: the STEP files and the checks may each end the build, so they get the processor first (figures in
#: bench/bench_build.py; a child with a core to itself runs at full speed whatever its priority)
BEHIND = 5


class BuildFailed(GeargenError):
    """The assembly was built but fails a check (teeth interfere, backlash out of range, parts overlap)."""

    def __init__(self, message: str, result: "BuildResult | None" = None):
        super().__init__(message)
        self.result = result


# ============================================================================ progress


class Progress:
    """Step-by-step progress on standard error: ``[3/8] gear solids ... 0.41 s``."""

    def __init__(self, quiet: bool = False, stream=None, total: int = len(STEPS)):
        self.quiet = quiet
        self.stream = stream or sys.stderr
        self.total = total
        self.timings: dict[str, float] = {}
        self._index = 0

    def run(self, name: str, fn: Callable, *args, **kwargs):
        self._index += 1
        if not self.quiet:
            print(f"[{self._index}/{self.total}] {name} ...", end="", file=self.stream, flush=True)
        t0 = time.perf_counter()
        try:
            out = fn(*args, **kwargs)
        except BaseException:
            if not self.quiet:
                print(" failed", file=self.stream, flush=True)
            raise
        dt = time.perf_counter() - t0
        self.timings[name] = dt
        if not self.quiet:
            print(f" {dt:.2f} s", file=self.stream, flush=True)
        return out

    def run_timed(self, name: str, fn: Callable, *args, **kwargs):
        """Like :meth:`run` for a step whose work was (partly) done elsewhere: ``fn`` returns
        ``(value, seconds of work, note)``; the seconds are the step's time, the note is shown."""
        self._index += 1
        if not self.quiet:
            print(f"[{self._index}/{self.total}] {name} ...", end="", file=self.stream, flush=True)
        try:
            value, seconds, note = fn(*args, **kwargs)
        except BaseException:
            if not self.quiet:
                print(" failed", file=self.stream, flush=True)
            raise
        self.timings[name] = seconds
        if not self.quiet:
            print(f" {seconds:.2f} s {note}".rstrip(), file=self.stream, flush=True)
        return value

    def note(self, text: str) -> None:
        if not self.quiet:
            print(f"      {text}", file=self.stream, flush=True)


def load(path: str | Path) -> Design:
    """Step 1: read and validate the design file."""
    return load_design(path)


def place(design: Design, position: str | None = None) -> Layout:
    """Step 2: the resolved drive (:func:`geargen.model.resolve`)."""
    return resolve(design, position)


# ============================================================================ CAD steps


def gear_solids(layout: Layout) -> dict[str, Any]:
    """Step 3: the solid of every toothed part (identical specs are built once), by part name;
    ``[export] gear_solid_tolerance`` bounds the flank splines' distance from the exact surface."""
    from geargen.cad.assembly import gear_parts
    return gear_parts(layout, layout.resolved.export["gear_solid_tolerance"])


def other_parts(layout: Layout, gears: dict[str, Any] | None = None, stiffness=None) -> Any:
    """Step 4: the solids of the resolved drive's hardware, placed; returns
    ``geargen.cad.assembly.PartSet`` holding the gears too (first) when ``gears`` are given."""
    from geargen.cad.assembly import non_gear_parts
    parts = non_gear_parts(layout, stiffness)
    if gears:
        parts.parts = list(gears.values()) + parts.parts
        parts.notes = [n for g in gears.values() for n in g.notes] + parts.notes
    return parts


# ============================================================================ checks


@dataclass
class CheckOutcome:
    """Mesh checks and the part-overlap check of a build, and whether the build may pass."""

    meshes: list[dict[str, Any]]
    overlaps: Any = None
    failures: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    design_check: Any = None  # geargen.checks.results.DesignCheck when the checker ran
    structure: Any = None  # geargen.checks.structure.StructureReport of the built parts

    @property
    def ok(self) -> bool:
        return not self.failures


def contact_region(setup, settings) -> tuple[np.ndarray, np.ndarray]:
    """Where the other gear's centre lies, in each gear's own frame, over the mesh positions the
    section check visits: ``(q1 (k, 2), q2 (k, 2))`` mm (gear 2's centre seen from gear 1, and
    gear 1's from gear 2). The positions are sampled four times as densely as the check's and one
    step beyond either end, so the region holds every position the check uses."""
    from geargen.checks.mesh2d import mesh_positions
    pos = mesh_positions(setup, settings.steps_per_tooth, settings.revolutions)
    step = float(pos[1] - pos[0]) if pos.size > 1 else 2 * math.pi / setup.gear1.teeth
    dense = np.linspace(pos[0] - step, pos[-1] + step, 4 * (pos.size + 1) + 1)
    st = setup.states(dense)
    d = np.asarray(st.centre2, dtype=float) - np.asarray(st.centre1, dtype=float)

    def turned(v, angle):  # v (k, 2) rotated by -angle (k,)
        c, s = np.cos(angle), np.sin(angle)
        return np.column_stack([c * v[:, 0] + s * v[:, 1], -s * v[:, 0] + c * v[:, 1]])

    return turned(d, np.asarray(st.angle1)), turned(-d, np.asarray(st.angle2))


def section_check(layout: Layout, mesh: MeshPlacement, shape1, shape2, planes: int = 1, near: bool = True,
                  chord_tolerance: float = 5e-5):
    """Path 2 of one mesh on two solids given in their own frames (``geargen.checks.solids``):
    sections at ``planes`` heights inside the common face (1: mid-face).

    ``near``: section only the faces of each solid that can come within the other gear's tip
    circle plus two modules over the checked positions (:func:`contact_region`,
    :func:`geargen.cad.assembly.faces_near`); the checker drops every segment farther than the
    tip circle plus one module, so its result is the same as with every face, at a fraction of
    the cost (a 112-tooth gear has ~100 teeth nowhere near the mesh). The stated tolerance is
    then that of the sectioned faces. ``near=False`` sections every face (kept to show that the
    two agree). ``chord_tolerance`` (mm): how far the section's chords may lie inside its curves.
    """
    from geargen.checks.solids import check_mesh_sections, section_planes, sections_from_shape
    from geargen.checks.verdict import mesh_settings, mesh_setup
    setup = mesh_setup(layout, mesh)
    settings = mesh_settings(layout.resolved.checks, mesh.backlash_min > 0)
    if near:
        from geargen.cad.assembly import faces_near
        q1, q2 = contact_region(setup, settings)
        g1, g2 = mesh.gear1, mesh.gear2
        shape1 = faces_near(shape1, q1, g2.tip_radius + 2 * g2.module)
        shape2 = faces_near(shape2, q2, g1.tip_radius + 2 * g1.module)
    z1 = section_planes(setup, planes)
    # the planes are in each gear's own face coordinates; a one-piece cluster's small gear stands
    # above its large gear in the part's frame
    lift1, lift2 = (_member_height(layout, part, gear) for part, gear in ((mesh.part1, mesh.gear1),
                                                                           (mesh.part2, mesh.gear2)))
    s1 = sections_from_shape(mesh.gear1, shape1, z1 + lift1, source=mesh.part1, chord_tolerance=chord_tolerance)
    s2 = sections_from_shape(mesh.gear2, shape2, z1 - setup.face_offset2 + lift2, source=mesh.part2,
                             chord_tolerance=chord_tolerance)
    if lift1 or lift2:
        s1, s2 = (replace(s, planes=s.planes - lift) for s, lift in ((s1, lift1), (s2, lift2)))
    return check_mesh_sections(setup, s1, s2, settings)


def _member_height(layout: Layout, part: str, gear) -> float:
    """Height of ``gear``'s face above its part's own z = 0 (a one-piece cluster's small gear)."""
    placed = layout.gear(part)
    return placed.face_z(gear)[0] - placed.z


def mesh_checks(layout: Layout, gears: dict[str, Any] | None = None, path2: bool = True) -> CheckOutcome:
    """Step 5: the verdict of ``geargen check`` on the resolved drive (:func:`geargen.checks.verdict.verify`:
    path 1 of every mesh, the design ranges, the ratio and the error budget), plus path 2 (sections
    of the built gear solids) when ``gears`` are given. Every failure of the verdict fails the build.
    The build computes the two parts in two processes (:func:`design_verdict`, :func:`mesh_sections`)
    and puts them together here (:func:`meshes_outcome`)."""
    sections = mesh_sections(layout, gears) if path2 and gears is not None else None
    return meshes_outcome(layout, design_verdict(layout), sections)


def design_verdict(layout: Layout):
    """Path 1: :func:`geargen.checks.verdict.verify` of the resolved drive, on one BLAS thread
    (:mod:`geargen.checks.blas`). It needs no solid, so the build starts it as soon as the drive is placed."""
    from geargen.checks.blas import one_blas_thread
    from geargen.checks.verdict import verify
    with one_blas_thread():
        return verify(layout)


def mesh_sections(layout: Layout, gears: dict[str, Any]) -> dict[str, Any]:
    """Path 2 of every engaged mesh: mesh name -> its :func:`section_check` on the gear solids, or the
    text of the exception that stopped it (reported as a warning: the exact check still decides)."""
    from geargen.checks.blas import one_blas_thread
    out: dict[str, Any] = {}
    with one_blas_thread():
        for mesh in layout.meshes:
            if not mesh.engaged:
                continue
            try:
                out[mesh.name] = section_check(layout, mesh, gears[mesh.part1].shape, gears[mesh.part2].shape)
            except Exception as exc:  # report, do not hide: the exact check still decides
                out[mesh.name] = f"{exc}"
    return out


def meshes_outcome(layout: Layout, dc, sections: dict[str, Any] | None) -> CheckOutcome:
    """The mesh checks' outcome from the verdict ``dc`` (:func:`design_verdict`) and path 2's
    ``sections`` (:func:`mesh_sections`; None: not made)."""
    from geargen.checks.verdict import design_backlash, sections_decide, undecided
    outcome = CheckOutcome(meshes=[], design_check=dc)
    for f in dc.all_failures:
        outcome.failures.append(f"{f.mesh or layout.identity.name} ({f.kind}): {f.message}")
    exact = {m.mesh: m for m in dc.meshes}
    for mesh, b in zip(layout.meshes, dc.backlash):
        entry: dict[str, Any] = {"mesh": mesh.name, "gear1": mesh.part1, "gear2": mesh.part2, "engaged": mesh.engaged,
                                 "design_min": mesh.backlash_min, "design_max": mesh.backlash_max,
                                 "modelled": mesh.modelled_backlash, "centre_distance": mesh.centre_distance,
                                 "plane_z": mesh.plane, "working_flank": mesh.working_flank}
        if not mesh.engaged:
            entry.update(status="disengaged", axial_clearance=b["axial_clearance"])
            outcome.meshes.append(entry)
            continue
        result = exact[mesh.name]
        entry.update(path1=result, backlash_min=b["min"], backlash_max=b["max"],
                     contact_ratio=result.total_contact_ratio, failures=[f.message for f in result.failures],
                     notes=list(result.notes))
        if sections is not None:
            s2 = sections[mesh.name]
            if isinstance(s2, str):
                outcome.warnings.append(f"{mesh.name}: section check (path 2) failed to run: {s2}")
            else:
                lo2, hi2 = design_backlash(s2, mesh.gear1.reference_radius)
                entry.update(path2=s2, path2_backlash_min=lo2, path2_backlash_max=hi2)
                if sections_decide(s2, layout.settings.get("loaded_flank_gap")):
                    outcome.failures += [f"{mesh.name} (sections of the solids, {f.kind}): {f.message}"
                                         for f in s2.failures]
                else:
                    outcome.warnings += undecided(s2)
        outcome.meshes.append(entry)
        if result.total_contact_ratio < 1.2:
            outcome.warnings.append(f"{mesh.name}: low contact ratio {result.total_contact_ratio:.3g}")
        for n in result.notes:
            if "undercut" in n:
                outcome.warnings.append(f"{mesh.name}: {n}")
    return outcome


def overlap_check(parts, layout: Layout | None = None) -> Any:
    """Pairwise solid intersections of all parts, intended contacts listed (``geargen.cad.assembly``)."""
    from geargen.cad.assembly import pairwise_overlaps
    meshing = [(m.part1, m.part2, "meshing gears: checked by the geometric mesh checker") for m in layout.meshes] \
        if layout is not None else []
    meshing += list(getattr(parts, "meshing", ()))
    return pairwise_overlaps(parts.parts, parts.intended_contacts, delegated=meshing)


# ============================================================================ stiffness


def stiffness(layout: Layout):
    """Step 6: the stiffness summary of the resolved drive (:func:`geargen.model.analysis.stiffness`;
    None when the design has no [stiffness]/[preload])."""
    from geargen.model.analysis import drive_stiffness
    return drive_stiffness(layout)[0]


# ============================================================================ export


def rotating_parts(layout: Layout) -> list:
    """The mass properties of every rotating part of the resolved drive (gears included), each with
    its rigid body (:func:`geargen.checks.structure.drive_structure`) and whether the motor turns
    that body directly (:class:`geargen.model.train.BodyPart`), from the parts' own geometry
    (:mod:`geargen.model.mass`: no solid is built). Bearings, motors and reference parts (the load)
    are not counted: a bearing's turning ring is not a separate part, a motor's rotor is its data
    sheet's inertia."""
    from geargen.checks.structure import drive_structure
    from geargen.model.mass import component_mass, placed_gear_mass
    from geargen.model.train import BodyPart
    if layout.hardware is None:
        return []
    report = drive_structure(layout)
    body_of = {n: body for body in report.bodies for n in body}
    components = {c.name: c for c in layout.hardware.components}
    turning = {g.name for g in layout.gears if "planetary_ring" not in g.roles} | set(layout.hardware.rotating)
    turning_bodies = {body for body in report.bodies if turning & set(body)}
    motors = {n for n, c in components.items() if c.kind == "motor"}
    driven_by_motor = {n for a, b, _ in layout.hardware.contacts for n, m in ((a, b), (b, a)) if m in motors}
    out = []
    parts = [(g.name, "gear", "gear", g) for g in layout.gears] + \
        [(c.name, c.kind, c.role, c) for c in layout.hardware.components]
    for name, kind, role, item in parts:
        body = body_of.get(name, (name,))
        if body not in turning_bodies or kind in ("bearing", "motor") or role == "reference":
            continue
        m = placed_gear_mass(item) if kind == "gear" else component_mass(item)
        out.append(BodyPart(name, m.volume, m.axial_moment, m.off_axis, tuple(body),
                            on_motor=bool(driven_by_motor & set(body))))
    return out


def declared_gear_parts(design: Design) -> list:
    """The mass properties of the gears a ``[dual_motor]`` names (each about its own axis, from its
    outline: :func:`geargen.model.mass.gear_mass`), as :class:`geargen.model.train.BodyPart`."""
    from geargen.design.train import dual_motor_spec
    from geargen.model.mass import gear_mass
    from geargen.model.train import BodyPart
    spec = dual_motor_spec(design)
    out = []
    for name in (*spec.pinions, spec.output):
        m = gear_mass(design.gear(name))
        out.append(BodyPart(name, m.volume, m.axial_moment, m.off_axis, (name,)))
    return out


def versions() -> dict[str, str]:
    import importlib.metadata as md
    out = {"python": platform.python_version()}
    for pkg in ("antibacklash-geargen", "cadquery", "cadquery-ocp", "numpy", "scipy", "matplotlib", "trimesh"):
        try:
            out[pkg] = md.version(pkg)
        except md.PackageNotFoundError:
            out[pkg] = "not installed"
    return out


def export(layout: Layout, parts, folder: Path, outcome: CheckOutcome | None = None,
           export_settings: dict | None = None, step_files: "Alongside | None" = None,
           meanwhile: Callable[[], None] | None = None) -> dict[str, Any]:
    """Step 7: assembly STEP, one STEP and one STL per part, into ``folder``; returns the file records.
    ``step_files``: the process writing the STEP files (:func:`export_step_files`, started before
    this step), collected once the STL files are written here (or the STEP files written here if it
    delivered nothing), after ``meanwhile()``, what the build does while that process finishes."""
    from geargen.cad.assembly import export_parts
    settings = export_settings or layout.resolved.export

    def collected():
        if meanwhile is not None:
            meanwhile()
        return _collect(step_files, export_step_files, layout, parts, folder)[0]

    return export_parts(layout, parts, Path(folder), settings, None if step_files is None else collected)


def export_step_files(layout: Layout, parts, folder: Path) -> dict[str, Any]:
    """The STEP files of the export (:func:`geargen.cad.assembly.export_step_files`)."""
    from geargen.cad.assembly import export_step_files as write_step_files
    return write_step_files(layout, parts, Path(folder))


def export_config(design: Design) -> dict[str, Any]:
    """``[export]`` validated (:func:`geargen.design.export.export_settings`)."""
    return export_settings(design)


# ============================================================================ report


def layout_drawing(layout: Layout, checks: CheckOutcome | None = None):
    """The 2-D layout drawing (a matplotlib ``Figure``) of ``layout`` (``geargen.report.layout``)."""
    from geargen.profile.tooth import tooth_profile
    from geargen.report.layout import LayoutGear, LayoutMesh, layout_figure
    import warnings
    from geargen.design.gear import GearSpec
    gears, names = [], {}
    for g in layout.gears:
        for spec in g.gears:
            if not isinstance(spec, GearSpec):  # a rack drive's rack: not a circle of the layout figure
                continue
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                root = tooth_profile(spec).root_radius
            key = f"{g.name}:{spec.name}"
            names[(g.name, id(spec))] = key
            gears.append(LayoutGear(key if len(g.gears) > 1 else g.name, tuple(g.centre), spec.reference_radius,
                                    spec.tip_radius, root, spec.base_radius, spec.teeth))
    meshes = []
    working = {}
    for entry in (checks.meshes if checks is not None else []):
        if "path1" in entry:
            sw = entry["path1"].sweep
            working[entry["mesh"]] = "ccw" if float(np.min(sw.play_ccw)) < float(np.min(sw.play_cw)) else "cw"
    for m in layout.meshes:
        if not m.engaged:
            continue
        n1 = names[(m.part1, id(m.gear1))] if len(layout.gear(m.part1).gears) > 1 else m.part1
        n2 = names[(m.part2, id(m.gear2))] if len(layout.gear(m.part2).gears) > 1 else m.part2
        meshes.append(LayoutMesh(m.name, n1, n2, 0, working.get(m.name, "")))
    carriage = None
    if layout.carriage_x is not None and layout.carriage_travel:
        carriage = ((layout.carriage_x, 0.0), layout.carriage_travel)
    return layout_figure(gears, meshes, layout.identity.length_unit, layout.identity.name, carriage,
                         symmetry_line=layout.drive is not None and layout.drive.symmetry_line)


def render(parts, design: Design, settings: dict | None = None, folder: Path | None = None):
    """A rendered view (``geargen.cad.render.RenderedView``) of all parts; with ``folder``, the
    parts' exported STL files there are drawn instead of tessellating again."""
    from geargen.cad.export import exported_triangles
    from geargen.cad.render import render_parts
    settings = settings or export_config(design)
    view = tuple(settings["render_view"] or (-60.0, 30.0))
    size = tuple(settings["render_size"] or (9.0, 6.5))
    meshes = exported_triangles(parts.parts, folder)
    return render_parts(parts.parts, view=view, size=size, title=design.name, meshes=meshes)


def view_and_figures(parts, design: Design, summary, folder: Path) -> tuple[tuple, float]:
    """The rendered view of ``parts`` (:func:`render`) and the figures that need no check result
    (:func:`check_free_figures`) written into ``folder``: what the build's figures process does.
    Returns (what :func:`check_free_figures` returns, seconds the view took)."""
    t0 = time.perf_counter()
    view = render(parts, design)
    seconds = time.perf_counter() - t0
    return check_free_figures(design, summary, view, folder), seconds


def check_free_figures(design: Design, summary, view, folder: Path) -> tuple[dict[str, Path], dict[str, str], list[str]]:
    """The figures that need no check result (the rendered ``view``, the preload diagram of the
    stiffness ``summary``) written into ``folder`` (:func:`geargen.report.review.write_figures`)."""
    from geargen.report.review import write_figures
    return write_figures(design.length_unit, summary, Path(folder), view)


def drawings(layout: Layout, folder: Path) -> dict[str, Path]:
    """``drawings/``: for every gear of the resolved drive its manufacturing drawing
    (``NAME-drawing.svg``/``.pdf``), the DXF of its exact transverse profile (``NAME.dxf``) and its
    gear data (``NAME.json``, as ``geargen gear`` writes it, with the mating gears and working
    centre distances of the resolved drive). Needs no check result: the build draws them while the
    second process checks the meshes. Returns ``{"drawing:NAME:svg"|...: path}``."""
    from geargen.cad.export import write_json
    from geargen.design.gear import GearSpec
    from geargen.profile.tooth import tooth_profile
    from geargen.report.drawing import gear_drawings

    design = layout.identity
    out_folder = Path(folder) / DRAWING_FOLDER
    source = design_source(design)
    allowances = drive_allowances_of(layout)
    files = {}
    drawn = set()
    from geargen.model.cluster_data import drive_clusters
    clusters = drive_clusters(layout)
    cluster_of = {g.name: c.name for c in clusters for g in (c.large, c.small)}
    for placed in layout.gears:
        for spec in placed.gears:
            if spec.name in drawn:  # the second of two identical clusters: the same gear, one drawing
                continue
            drawn.add(spec.name)
            if not isinstance(spec, GearSpec):  # another family's part (a rack drive's rack): its own sheet
                from geargen.families.registry import family_of
                family = family_of(spec)
                data = family.gear_data(spec)
                made = family.drawings(data, spec, out_folder, spec.name, f"gear {spec.name} of {source}",
                                       str(design.path) if design.path else design.name) or {}
                path = out_folder / f"{spec.name}.json"
                out_folder.mkdir(parents=True, exist_ok=True)
                write_json(path, _jsonable(data))
                files[f"drawing:{spec.name}:json"] = path
                files |= {f"drawing:{spec.name}:{kind}": p for kind, p in made.items()}
                continue
            profile = tooth_profile(spec, warn=False)  # the solids' profile (undercut warned at the build)
            data = drive_gear_data(layout, spec, profile, allowances.get(spec.name))
            if spec.name in cluster_of:  # its tooth data sheet belongs to the cluster's drawing
                data["cluster"] = {"name": cluster_of[spec.name], "drawing": f"{cluster_of[spec.name]}-drawing.svg"}
            made = gear_drawings(data, profile, out_folder, spec.name, f"gear {spec.name} of {source}",
                                 str(design.path) if design.path else design.name)
            made["json"] = out_folder / f"{spec.name}.json"
            write_json(made["json"], _jsonable(data))
            files |= {f"drawing:{spec.name}:{kind}": path for kind, path in made.items()}
    design_file = str(design.path) if design.path else design.name
    files |= bevel_pair_drawings(layout, out_folder, source, design_file)
    files |= cluster_sheets(layout, clusters, out_folder, source, design_file)
    return files


def cluster_sheets(layout: Layout, clusters, out_folder: Path, source: str, design_file: str) -> dict[str, Path]:
    """Each cluster article's drawing of the part as made and its data (``NAME.json``):
    :mod:`geargen.model.cluster_data`, :mod:`geargen.report.drawing_cluster`."""
    from geargen.cad.export import write_json
    from geargen.model.cluster_data import cluster_data
    from geargen.report.drawing_cluster import cluster_drawings

    files = {}
    for cluster in clusters:
        data = cluster_data(layout, cluster)
        made = cluster_drawings(data, cluster.large, cluster.small, out_folder, cluster.name,
                                f"cluster {cluster.name} of {source}", design_file)
        made["json"] = out_folder / f"{cluster.name}.json"
        write_json(made["json"], _jsonable(data))
        files |= {f"drawing:{cluster.name}:{kind}": path for kind, path in made.items()}
    return files


def bevel_pair_drawings(layout: Layout, out_folder: Path, source: str, design_file: str) -> dict[str, Path]:
    """The drive's bevel pair (:func:`geargen.drives.dual_pinion.bevel.bevel_drive`, none without one):
    each gear's data (``NAME.json``, with its mate and the pair's backlash) and drawing, of the specs
    the solids are built from (their back included)."""
    from geargen.cad.export import write_json
    from geargen.drives.dual_pinion.bevel import bevel_drive
    from geargen.families.bevel.data import bevel_gear_data
    from geargen.families.bevel.drawing import bevel_drawings

    placed = bevel_drive(layout)
    if placed is None:
        return {}
    files = {}
    for spec, mate in ((placed.gear, placed.pinion), (placed.pinion, placed.gear)):
        data = bevel_gear_data(spec)
        # the pair's circumferential backlash: one arc length on both heel pitch circles (they roll together)
        data["mating_gear"] = {"name": mate.name, "teeth": mate.teeth,
                               "backlash_circumferential": float(from_mm(placed.backlash, spec.length_unit))}
        made = bevel_drawings(data, spec, out_folder, spec.name, f"gear {spec.name} of {source}", design_file)
        made["json"] = out_folder / f"{spec.name}.json"
        write_json(made["json"], _jsonable(data))
        files |= {f"drawing:{spec.name}:{kind}": path for kind, path in made.items()}
    return files


def drive_allowances_of(layout: Layout) -> dict:
    """Every gear's thickness allowance in the resolved drive (entered, or chosen from its meshes'
    backlash ranges at the design's ``[checks] centre_distance_tolerance``)."""
    from geargen.model.allowance import drive_allowances
    return drive_allowances(layout, layout.resolved.checks.centre_distance_tolerance, strict=False)


def drive_gear_data(layout: Layout, spec, profile, allowance) -> dict:
    """The gear data of one gear of the resolved drive, as the build's drawings and ``geargen gear
    --gear`` write it: its ``allowance``, the grade its error budget holds when it has no grade of
    its own (or the finer one its rating assumed, :func:`geargen.model.gear_data.hold_rated_grade`), where its
    thinning comes from, and its mating gears with the working centre distances."""
    from geargen.model.gear_data import gear_data, hold_rated_grade
    from geargen.report.drawing import mates_from_layout

    resolved = layout.resolved
    data = gear_data(spec, profile, allowance, resolved.gear_errors(spec.name), resolved.rated_material(spec.name))
    if resolved.has("duty") or resolved.has("materials"):  # the rating is then a check: hold its grade
        hold_rated_grade(data, spec, resolved.duty.accuracy_grade)
    data["thinning_source"] = next((layout.thinning.get(p.name, {}).get("source", "design")
                                    for p in layout.gears if any(g.name == spec.name for g in p.gears)), "design")
    data["mating_gears"] = [m.to_dict() for m in mates_from_layout(layout, spec.name, spec.length_unit)]
    return data


def report(result: "BuildResult", folder: Path, layout_sheet: "Alongside | None" = None) -> dict[str, Path]:
    """The last step: the figures (rendered view, layout drawing, preload diagram) as
    ``figures/*.png|svg`` (those of :func:`check_free_figures` as ``result.figures`` if drawn
    already), report.md and report.html, and the browser design review (:func:`review_page`).
    ``layout_sheet``: the process drawing the layout (:func:`layout_figure_files`, started once the
    checks were known), collected after the report and the review, which only link to it; drawn here
    if there is none or it delivered nothing."""
    from geargen.report.review import compose, figure_link, write_review
    folder = Path(folder)
    if result.figures is None:
        if result.render_view is None:
            result.render_view = render(result.parts, result.design)
        result.figures = check_free_figures(result.design, result.stiffness, result.render_view, folder)
    early_files, early_links, early_notes = result.figures
    links = early_links | {"layout": figure_link("layout")}
    review = compose(result, links, early_notes)
    written = write_review(review, folder) | review_page(result, folder, review)
    figures = _collect(layout_sheet, layout_figure_files, result.layout, result.checks, folder)[0]
    return early_files | figures | written


def layout_figure_files(layout: Layout, checks: CheckOutcome | None, folder: Path) -> dict[str, Path]:
    """figures/layout.png and .svg in ``folder``: the layout drawing (:func:`layout_drawing`) of
    ``layout`` with the working flanks of ``checks``; returns the files by role."""
    from geargen.report.review import write_figures
    return write_figures(layout.identity.length_unit, None, folder, layout_figure=layout_drawing(layout, checks))[0]


def review_page(result: "BuildResult", folder: Path, review) -> dict[str, Path]:
    """``review/``: the browser design review (:mod:`geargen.report.review_page`) of the built parts
    as a GLB made from their STL files in ``folder`` (tessellated only where there are none), with
    the mesh checks as the manifest records them and the sections of ``review`` (the report)."""
    from geargen.cad.gltf import assembly_glb
    from geargen.report.review_page import page_data, write_review_page
    glb = assembly_glb(result.design.name, result.parts.parts, folder)
    return write_review_page(folder / "review", glb, page_data(result, _jsonable(_checks_summary(result)), review))


# ============================================================================ the whole build


@dataclass
class BuildResult:
    """Everything a build made; ``out_dir`` is where it was written (None if nothing was)."""

    design: Design
    layout: Layout
    gears: dict[str, Any]
    parts: Any
    checks: CheckOutcome
    stiffness: Any
    files: dict[str, Any] = field(default_factory=dict)
    out_dir: Path | None = None
    timings: dict[str, float] = field(default_factory=dict)
    forced: bool = False
    render_view: Any = None  # geargen.cad.render.RenderedView
    figures: tuple | None = None  # what check_free_figures wrote: (files, links, notes)
    drawings: dict[str, Path] | None = None  # what drawings() wrote

    @property
    def ok(self) -> bool:
        return self.checks.ok

    @property
    def warnings(self) -> list[str]:
        out = list(self.layout.notes and [] or [])
        out += self.checks.warnings
        if self.stiffness is not None:
            out += list(self.stiffness.warnings)
        return out


def default_out_dir(design: Design) -> Path:
    """``exports/<design file name without .toml>``: two design files that share a ``name =``
    never share a folder (the folder policy of :mod:`geargen.outputs` guards the rest)."""
    return Path("exports") / (Path(design.path).stem if design.path else design.name)


def design_source(design: Design, design_path: str | Path | None = None) -> str:
    """What a build is of, as its manifest records it (``"source"``): the design file's absolute path
    (``design``: a Design, or a resolved drive's :class:`~geargen.design.resolved.DesignIdentity`)."""
    return str(Path(design.path or design_path).resolve()) if (design.path or design_path) else design.name


def output_folder(design: Design, out: str | Path | None = None, overwrite: bool = False,
                  design_path: str | Path | None = None):
    """The :class:`geargen.outputs.OutputFolder` a build of ``design`` writes (``out`` or the default)."""
    from geargen.outputs import OutputFolder
    target = Path(out) if out is not None else default_out_dir(design)
    return OutputFolder(target, "geargen build", design_source(design, design_path),
                        f"the design file {design.path or design_path}", overwrite=overwrite,
                        flag="--out" if out is not None else "output folder")


def build(design_path: str | Path, out: str | Path | None = None, quiet: bool = False, force: bool = False,
          position: str | None = None, progress: Progress | None = None, parallel: bool = True,
          overwrite: bool = False) -> BuildResult:
    """Run every step and write the exports atomically into ``out`` (default ``exports/<file stem>``).

    Raises :class:`BuildFailed` when a check fails (nothing written) unless ``force``.

    The output folder follows the policy of :mod:`geargen.outputs` (a new or empty folder, or an
    earlier build of the same design file; ``overwrite``: also an earlier build of another design
    file, or one whose files were changed): it is checked, and the temporary folder beside it
    made, right after the design file is read and before anything is built, so a refused or
    unwritable target costs nothing (:class:`geargen.errors.OutputRefused`,
    :class:`geargen.errors.EnvironmentProblem`). Every file is written into that temporary
    folder, which replaces the target in one step once the checks have passed; any failure or
    interruption (Ctrl-C, SIGTERM) removes it, and one left by a killed build is removed by the
    next build into the same parent folder.

    ``parallel``: the checks run in three processes of their own (:class:`Alongside`): the verdict
    (:func:`design_verdict`) from the moment the drive is placed, path 2's sections of the solids
    (:func:`mesh_sections`) from the moment the gear solids exist, the parts' overlaps
    (:func:`overlap_check`) from the moment the other parts do, while this one writes the view
    and the exports into the temporary folder; the build waits for them before anything is moved
    into place, so a failing build still leaves nothing behind. Where no process
    can be had the checks run here, in order, as with ``parallel=False``; a part whose process
    delivers nothing is made here. The drawings need
    only the resolved drive: with ``parallel`` they are drawn in a process of their own from the
    moment it is placed, the view and the figures that need no check result
    (:func:`view_and_figures`) in another from the moment the other parts exist (:func:`_collect`),
    and the STEP files (:func:`export_step_files`) in another while this one writes the STL files,
    else (or if one delivers nothing) here.
    """
    progress = progress or Progress(quiet)
    design = progress.run("load", load, design_path)
    output = output_folder(design, out, overwrite, design_path)
    work = output.prepare()
    for folder in output.cleanup.removed:
        progress.note(f"removed the temporary folder of an interrupted build: {folder}")
    children = Alongside.started()
    try:
        layout = progress.run("place", place, design, position)
        # the verdict needs only the resolved drive, and no kernel: checked in a process of its own
        # from here, before the kernel is imported (the longest step starts first)
        verdict_alongside = Alongside.start(design_verdict, layout) if parallel else None
        if parallel:
            _import_figure_modules()
            _import_kernel_modules()
        # the drawings need only the resolved drive: drawn in a process of their own from here
        sheets_alongside = Alongside.start(drawings, layout, work, nice=BEHIND) if parallel else None
        sections_alongside = figures_alongside = overlaps_alongside = steps_alongside = layout_sheet = None
        try:
            gears = progress.run("gear solids", gear_solids, layout)
            # path 2 (sections of the gear solids) in another from the moment the solids exist
            sections_alongside = Alongside.start(mesh_sections, layout, gears) if parallel else None
            if verdict_alongside is not None or sections_alongside is not None:
                progress.note("mesh checks: started in processes of their own, alongside the next steps")
            summary = progress.run("stiffness", stiffness, layout)
            parts = progress.run("other parts", other_parts, layout, gears, summary)
            # the parts' overlap check reads the finished solids with the kernel's serial calls only:
            # checked in a process of its own from here (the main process is the build's longest path)
            overlaps_alongside = Alongside.start(overlap_check, parts, layout) if parallel else None
            result = None
            if verdict_alongside is None and sections_alongside is None:
                checks = progress.run("mesh checks", _all_checks, layout, gears, parts)
                result = _checked(BuildResult(design, layout, gears, parts, checks, summary), force, progress)
            # the view and the figures that need no check result: in a process of their own while this
            # one exports; made here first otherwise, so that in both the view meshes the solids before
            # the STL export does (a solid meshed finer first would be drawn from its finer mesh)
            figures_alongside = (Alongside.start(view_and_figures, parts, design, summary, work, nice=BEHIND)
                                 if parallel else None)

            def figures_step():
                return progress.run_timed("figures", _collect, figures_alongside, view_and_figures, parts, design,
                                          summary, work)

            made = figures_step() if figures_alongside is None else None
            # the STEP files in a process of their own (its kernel has written no STEP file yet, as this one
            # has not: assembly.step's usage ids the same) while this one writes the STL files (the main
            # process is the build's longest path; no STEP writer reads a mesh)
            steps_alongside = Alongside.start(export_step_files, layout, parts, work) if parallel else None
            collected_checks = None

            def checks_step():
                """The checks collected and, if they pass (or ``force``), the layout drawing, which needs
                them, started in a process of its own: done once the STL files are written, while the STEP
                files' process finishes, so the drawing is not left to the build's end (reported after
                the export's line)."""
                nonlocal collected_checks, layout_sheet
                if result is None and collected_checks is None:
                    collected_checks = _collect_checks(verdict_alongside, sections_alongside, layout, gears, parts,
                                                       overlaps_alongside)
                checks = result.checks if result is not None else collected_checks[0]
                if parallel and layout_sheet is None and (checks.ok or force):
                    layout_sheet = Alongside.start(layout_figure_files, layout, checks, work)

            files = progress.run("export", export, layout, parts, work, step_files=steps_alongside,
                                 meanwhile=checks_step)
            checks_step()  # done already, unless the STEP files were written here
            if result is None:
                checks = progress.run_timed("mesh checks", lambda: collected_checks)
                result = _checked(BuildResult(design, layout, gears, parts, checks, summary), force, progress)
            drawn, progress.timings["render"] = made or figures_step()
            sheets = progress.run_timed("drawings", _collect, sheets_alongside, drawings, layout, work)
            result.files, result.figures = files, drawn
            result.drawings = sheets
            result.timings = dict(progress.timings)
            progress.run("report", _report_and_manifest, result, work, layout_sheet)
            target = output.commit()
        finally:
            for child in (verdict_alongside, sections_alongside, sheets_alongside, figures_alongside,
                          overlaps_alongside, steps_alongside, layout_sheet):
                if child is not None:
                    child.close()
    except BaseException:
        Alongside.end_started_since(children)
        output.discard()
        raise
    Alongside.end_started_since(children)
    result.out_dir = target
    result.timings = dict(progress.timings)
    return result


def _checked(result: BuildResult, force: bool, progress: Progress) -> BuildResult:
    """``result`` if its checks pass (or ``force``: marked as forced); else :class:`BuildFailed`."""
    for f in result.checks.failures:
        progress.note(f"FAIL {f}")
    result.forced = force and not result.checks.ok
    if not result.checks.ok and not force:
        raise BuildFailed(f"{result.design.name}: the assembly fails its checks (nothing written; --force writes it "
                          "marked as failing):\n  " + "\n  ".join(result.checks.failures), result)
    return result


def _all_checks(layout: Layout, gears, parts, meshes: CheckOutcome | None = None, overlaps=None) -> CheckOutcome:
    """The mesh checks (``meshes`` if already made), the parts' overlaps (``overlaps`` if already
    checked) and the exact ratio."""
    outcome = meshes if meshes is not None else mesh_checks(layout, gears)
    outcome.overlaps = overlaps if overlaps is not None else overlap_check(parts, layout)
    ov = outcome.overlaps
    # path 2 of the parts check: the solids intersected (path 1, the analytic reading, is the verdict's)
    for o in ov.unintended:
        outcome.failures.append(f"parts overlap (solids): {o.part1} and {o.part2} share {o.volume:.4g} mm^3")
    for o in ov.interpenetrating:
        outcome.failures.append(f"parts meant to touch run into each other (solids): {o.part1} and {o.part2} "
                                f"share {o.volume:.4g} mm^3 ({o.why})")
    for a, b, gap, why in ov.missing_contacts:
        outcome.failures.append(f"intended contact missing (solids): {a} and {b} are {gap:.4g} mm apart, not "
                                f"touching ({why})")
    dc = outcome.design_check
    outcome.structure = dc.structure if dc is not None and dc.structure is not None else structure_check(parts, layout)
    return outcome


def structure_check(parts, layout: Layout):
    """How the drive's parts hold together (:func:`geargen.checks.structure.drive_structure`): the
    resolved drive's joints, which the overlap check verified on the solids."""
    from geargen.checks.structure import drive_structure
    return drive_structure(layout)


def _collect_checks(verdict: "Alongside | None", sections: "Alongside | None", layout: Layout, gears,
                    parts, overlaps: "Alongside | None" = None) -> tuple[CheckOutcome, float, str]:
    """The mesh checks from their processes (``verdict``: :func:`design_verdict`, started when the
    drive was placed; ``sections``: :func:`mesh_sections`, started when the gear solids were built;
    ``overlaps``: :func:`overlap_check`, started when the other parts were), each made here if its
    process is missing or delivered nothing, completed by :func:`_all_checks`; returns (outcome,
    seconds of checking, a note for the progress line)."""
    busy = 0.0
    t0 = time.perf_counter()
    got = [child.result() if child is not None else None for child in (verdict, sections, overlaps)]
    waited = time.perf_counter() - t0
    here = []
    values = []
    for what, child, fn, args, delivered in (("verdict", verdict, design_verdict, (layout,), got[0]),
                                             ("sections", sections, mesh_sections, (layout, gears), got[1]),
                                             ("overlaps", overlaps, overlap_check, (parts, layout), got[2])):
        if delivered is None:
            t0 = time.perf_counter()
            values.append(fn(*args))
            busy += time.perf_counter() - t0
            if child is not None:  # started, and delivered nothing (one never started is simply made here)
                here.append(what)
        else:
            busy += delivered[0]
            values.append(delivered[1])
    t0 = time.perf_counter()
    outcome = _all_checks(layout, gears, parts, meshes_outcome(layout, *values[:2]), values[2])
    busy += time.perf_counter() - t0
    if here:
        return outcome, busy, f"(the {' and the '.join(here)} of a second process delivered nothing: checked here)"
    return outcome, busy, (f"(verdict, sections and overlaps checked in processes of their own alongside the "
                           f"solids and exports; waited {waited:.2f} s)")


def _import_figure_modules() -> None:
    """Import matplotlib's figure and its PNG and SVG writers, the report's figure modules, and read the
    figures' font files: the report needs them in this process anyway; done before the drawings' and the
    figures' processes are forked, each inherits them instead of loading them again (~0.2 s of processor
    time each)."""
    import matplotlib.backends.backend_agg  # noqa: F401
    import matplotlib.backends.backend_svg  # noqa: F401
    import matplotlib.figure  # noqa: F401
    from matplotlib.font_manager import FontProperties, findfont, get_font
    from PIL import Image

    import geargen.report.labels  # noqa: F401
    import geargen.report.review  # noqa: F401
    import geargen.report.stiffness  # noqa: F401
    import geargen.report.view  # noqa: F401
    Image.preinit()  # the image plugins the first PNG written loads (each process its own, else)
    for weight in ("normal", "bold"):  # the figures' and sheets' font files, read once here
        get_font(findfont(FontProperties(weight=weight)))


def _import_kernel_modules() -> None:
    """Import the kernel's bindings and the build's CAD modules: this process needs them from the gear
    solids on, and the drawings' process imports them too (its JSON writer lives in
    :mod:`geargen.cad.export`); imported before that process is forked, it inherits them instead of
    loading OCP again (~0.5 s of processor time, a sixth of the drawings' own)."""
    import geargen.cad.assembly  # noqa: F401
    import geargen.cad.export  # noqa: F401


def _collect(alongside: "Alongside | None", fn: Callable, *args) -> tuple[Any, float, str]:
    """``fn(*args)`` as the process started for it (:class:`Alongside`) computed it, or computed here
    if there is none or it delivered nothing; returns (value, seconds of work, note). For steps that
    only write files into the build's temporary folder and return their names (drawings, figures)."""
    got = alongside.result() if alongside is not None else None
    if got is not None:
        seconds, value = got
        return value, seconds, "(in a process of their own)"
    t0 = time.perf_counter()
    value = fn(*args)
    return value, time.perf_counter() - t0, "" if alongside is None else "(their process delivered nothing: made here)"


_PR_SET_PDEATHSIG = 1  # linux/prctl.h


def _die_with_parent(parent_pid: int) -> None:
    """Make this (forked) process end when its parent does, however the parent ends.

    ``prctl(PR_SET_PDEATHSIG, SIGKILL)`` asks the kernel to kill this process when the thread
    that forked it exits, SIGKILL of the parent included (no cleanup runs there); the parent
    may already be gone before the request is made, so the parent's pid is compared after it
    (an orphan has been re-parented). SIGTERM gets its default action back (the parent's
    handler would turn it into an interruption here) and SIGINT is ignored: Ctrl-C reaches the
    whole process group, and the parent, which handles it, ends this process itself."""
    import ctypes
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
    except (OSError, AttributeError):
        pass  # not Linux's libc: the parent's close() still ends this process on every clean exit
    if os.getppid() != parent_pid:
        os._exit(1)


def _run_in_child(conn, fn, args, parent_pid: int | None = None, nice: int = 0) -> None:
    """Body of the second process: send ``("ok", seconds, fn(*args))`` or ``("error", 0, text)``."""
    if parent_pid is not None:
        _die_with_parent(parent_pid)  # its own signal dispositions first, then what was held arrives
    if nice:
        try:
            os.nice(nice)
        except OSError:  # a priority it may not lower: it runs as it is
            pass
    kernel = sys.modules.get("geargen.cad.kernel")  # not imported here if the parent had not (the verdict)
    if kernel is not None:
        kernel.forked()  # the parent's kernel thread pool did not come along
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT, signal.SIGTERM})  # held by Alongside.start
    try:
        t0 = time.perf_counter()
        value = fn(*args)
        conn.send(("ok", time.perf_counter() - t0, value))
    except BaseException as exc:  # the parent runs fn itself and raises what it raises
        try:
            conn.send(("error", 0.0, f"{type(exc).__name__}: {exc}"))
        except Exception:
            pass
    finally:
        conn.close()


class Alongside:
    """``fn(*args)`` computed in a forked process while the caller goes on; :meth:`result` collects it.

    The child shares the caller's memory as it was at :meth:`start` (nothing is pickled on the
    way in; the result comes back pickled through a pipe). It must not use the kernel's thread
    pools (a forked process has only the forking thread): the mesh checks read the gear solids
    and compute with numpy, nothing more. Linux only (fork); :meth:`start` returns None where a
    child cannot be had, and :meth:`result` returns None when the child delivers nothing (error,
    crash, ``timeout`` seconds): the caller then computes ``fn`` itself.

    The child never outlives the caller: :meth:`close` ends it on every exit of the caller that
    runs Python code (return, exception, Ctrl-C, SIGTERM), and on Linux the kernel kills it
    when the caller dies without running anything (SIGKILL, a crash): :func:`_die_with_parent`.
    """

    #: every child started and not yet ended by :meth:`end_started_since` (a signal held while forking
    #: is raised once the child exists, possibly before the caller holds it to :meth:`close` it)
    _started: list = []

    def __init__(self, process, receiver):
        self._process = process
        self._receiver = receiver

    @classmethod
    def started(cls) -> int:
        """A mark for :meth:`end_started_since`: how many children are recorded now."""
        return len(cls._started)

    @classmethod
    def end_started_since(cls, mark: int) -> None:
        """End every child started since ``mark`` that still runs, held by its caller or not: an
        interrupted build must not leave one writing into the folder it removes."""
        for process in cls._started[mark:]:
            if process.is_alive():
                process.terminate()
            process.join(timeout=5.0)
            if process.is_alive():
                process.kill()
                process.join(timeout=5.0)
        del cls._started[mark:]

    @classmethod
    def start(cls, fn: Callable, *args, nice: int = 0) -> "Alongside | None":
        """``fn(*args)`` started in a forked process, ``nice`` steps below this one's priority (it then
        yields the processor to this one and to its other children whenever they compete; alone, it
        runs at full speed); None where no process can be had."""
        if not (sys.platform.startswith("linux") and hasattr(os, "fork")):
            return None
        try:
            import multiprocessing
            import gc
            ctx = multiprocessing.get_context("fork")
            receiver, sender = ctx.Pipe(duplex=False)
            process = ctx.Process(target=_run_in_child, args=(sender, fn, args, os.getpid(), nice), daemon=True)
            # the objects made so far out of the garbage collector's sight while forking: its passes
            # in the child would write to every one and copy the pages it shares with this process
            gc.freeze()
            # Ctrl-C and SIGTERM held while forking: one arriving in the fork's at-fork hooks raised
            # Interrupted where Python ignores exceptions, and the build went on and exited 0; held,
            # it is raised here once the child exists (which unblocks them, _run_in_child)
            held = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
            try:
                process.start()
            finally:
                gc.unfreeze()
                if process.pid is not None:  # recorded before a held signal can be raised
                    cls._started.append(process)
                signal.pthread_sigmask(signal.SIG_SETMASK, held)
        except Exception:  # e.g. inside a daemonic worker, which may not have children
            return None
        sender.close()
        return cls(process, receiver)

    def result(self, timeout: float = 600.0) -> tuple[float, Any] | None:
        """``(seconds the child computed, fn's value)``, or None if it delivered nothing."""
        try:
            if not self._receiver.poll(timeout):
                return None
            status, seconds, value = self._receiver.recv()
        except Exception:  # EOF (the child died), an unpicklable value, ...
            return None
        finally:
            self.close()
        return (seconds, value) if status == "ok" else None

    def close(self) -> None:
        """Close the pipe and end the child if it is still running."""
        self._receiver.close()
        if self._process.is_alive():
            self._process.terminate()
        self._process.join(timeout=5.0)
        if self._process.is_alive():  # SIGTERM is the default action there; this is the last resort
            self._process.kill()
            self._process.join(timeout=5.0)


def _report_and_manifest(result: BuildResult, folder: Path, layout_sheet: "Alongside | None" = None) -> None:
    if result.drawings is None:
        result.drawings = drawings(result.layout, folder)
    files = report(result, folder, layout_sheet) | result.drawings
    files["resolved"] = write_resolved(result.layout, folder)
    manifest(result, folder, files)


def manifest(result: BuildResult, folder: Path, report_files: dict[str, Path] | None = None) -> Path:
    """manifest.json: files, units, tolerances, the design's sha256, versions, check status, the
    report's key numbers."""
    from geargen.cad.export import write_json
    from geargen.report.review import key_numbers
    design = result.design
    entries = {}
    for name, rec in result.files.get("records", {}).items():
        entries[name] = rec
    for key, p in (report_files or {}).items():
        entries[Path(p).relative_to(Path(folder)).as_posix()] = {"format": Path(p).suffix.lstrip("."), "role": key,
                                                           "bytes": Path(p).stat().st_size}
    status = "ok" if result.ok else "failing"
    data = {
        "generator": "geargen build",
        "source": design_source(design),  # what geargen.outputs recognises an earlier build of this design by
        "design": {"name": design.name, "file": str(design.path) if design.path else None, "sha256": design.sha256,
                   "length_unit": design.length_unit},
        "status": status,
        "forced": result.forced,
        "failures": list(result.checks.failures),
        "units": {"step": f"{design.length_unit} (declared in each file)", "stl": "mm",
                  "internal": "mm, rad, N"},
        "tolerances": result.files.get("tolerances", {}),
        "position": result.layout.position,
        "checks": _checks_summary(result),
        "parts": result.files.get("parts", {}),
        "files": entries,
        "versions": versions(),
        "timings_s": {k: round(v, 4) for k, v in result.timings.items()},
        "key_numbers": key_numbers(result),
    }
    path = Path(folder) / "manifest.json"
    write_json(path, _jsonable(data))
    return path


def write_resolved(layout: Layout, folder: Path) -> Path:
    """resolved.json: the resolved drive (:meth:`geargen.model.Layout.to_dict`) the exports were built from."""
    from geargen.cad.export import write_json
    path = Path(folder) / "resolved.json"
    write_json(path, _jsonable({"generator": "geargen build", "design": layout.identity.name, **layout.to_dict()}))
    return path


#: the lengths (mm) of the manifest's check records, each also written under ``<key>_<design unit>``
#: (issue 27: JSON keys carry their unit, and an inch design's numbers are read in inches)
_MESH_LENGTHS = ("design_min", "design_max", "modelled", "centre_distance", "plane_z", "backlash_min", "backlash_max",
                 "path2_backlash_min", "path2_backlash_max", "axial_clearance", "min_tip_clearance",
                 "interference_depth_max")
_TOLERANCE_LENGTHS = ("nominal_min_backlash", "worst_case_min_backlash", "worst_case_min_normal_backlash",
                      "worst_case_centre_distance_change", "monte_carlo_min_backlash", "monte_carlo_min_backlash_p01",
                      "monte_carlo_min_backlash_median", "monte_carlo_model_difference", "carriage_travel",
                      "carriage_travel_low", "carriage_travel_high", "monte_carlo_carriage_travel_low",
                      "monte_carlo_carriage_travel_high", "carriage_travel_limit_low", "carriage_travel_limit_high")


def _in_design_unit(records: list[dict], lengths, unit: str) -> list[dict]:
    """``records`` (lengths in mm) with every number of ``lengths`` also under ``<key>_<unit>`` in the
    design's ``unit``: keys are added, none changes meaning."""
    def converted(v):
        return float(from_mm(v, unit)) if isinstance(v, (int, float, np.floating)) and not isinstance(v, bool) else v
    return [r | {f"{k}_{unit}": converted(r[k]) for k in lengths if k in r} for r in records]


def _checks_summary(result: BuildResult) -> dict[str, Any]:
    """Mesh-check and overlap results for the manifest: lengths in mm under the plain keys (the
    block's ``length_unit``), each also under ``<key>_<design unit>`` (``design_length_unit``)."""
    meshes = []
    for m in result.checks.meshes:
        e = {k: m[k] for k in ("mesh", "gear1", "gear2", "engaged", "design_min", "design_max", "modelled",
                               "centre_distance", "plane_z")}
        for k in ("backlash_min", "backlash_max", "path2_backlash_min", "path2_backlash_max", "contact_ratio",
                  "axial_clearance", "failures"):
            if k in m:
                e[k] = m[k]
        if "path1" in m:
            path1 = m["path1"]
            e.update(min_tip_clearance=path1.min_clearance, interference_depth_max=path1.max_interference_depth)
        meshes.append(e)
    ov = result.checks.overlaps
    overlaps = None if ov is None else {
        "parts": ov.parts, "pairs_checked": ov.pairs_checked, "tolerance_mm3": ov.tolerance,
        "unintended": [[o.part1, o.part2, o.volume] for o in ov.unintended],
        "interpenetrating_contacts": [[o.part1, o.part2, o.volume] for o in ov.interpenetrating],
        "missing_contacts": [[a, b, gap] for a, b, gap, _ in ov.missing_contacts],
        "contact_tolerance_mm": ov.contact_tolerance,
        "intended_contacts": [list(c) for c in ov.intended], "meshing_pairs": [list(c) for c in ov.delegated]}
    from geargen.model import BACKLASH_KIND
    dc = result.checks.design_check
    tolerances = [t.to_dict("mm") for t in dc.tolerances] if dc is not None else []
    bevel = list(dc.bevel) if dc is not None else []  # mm, rad (geargen.checks.verdict._bevel_meshes)
    planetary = list(dc.planetary) if dc is not None else []  # mm, rad (geargen.drives.planetary.verdict)
    rack = list(dc.rack) if dc is not None else []  # mm, N (geargen.drives.rack_dual_pinion.verdict)
    structure = result.checks.structure
    from geargen.checks.results import BEVEL_LENGTHS, PLANETARY_LENGTHS, RACK_LENGTHS
    u = result.design.length_unit
    meshes, tolerances = _in_design_unit(meshes, _MESH_LENGTHS, u), _in_design_unit(tolerances, _TOLERANCE_LENGTHS, u)
    bevel, planetary = _in_design_unit(bevel, BEVEL_LENGTHS, u), _in_design_unit(planetary, PLANETARY_LENGTHS, u)
    rack = _in_design_unit(rack, RACK_LENGTHS, u)
    if overlaps is not None:
        overlaps[f"contact_tolerance_{u}"] = float(from_mm(ov.contact_tolerance, u))
        overlaps[f"missing_contacts_{u}"] = [[a, b, float(from_mm(gap, u))] for a, b, gap in overlaps["missing_contacts"]]
    return {"length_unit": "mm", "design_length_unit": u, "backlash_kind": BACKLASH_KIND,
            "meshes": meshes, "bevel_meshes": bevel, "planetary_meshes": planetary, "tolerances": tolerances,
            "overlaps": overlaps,
            "rack_meshes": [r for r in rack if r["mesh"] != "carriage"],
            "rack_carriage": next((r for r in rack if r["mesh"] == "carriage"), None),
            "structure": None if structure is None else structure.to_dict(),
            "load_capacity": None if dc is None or dc.load_capacity is None else dc.load_capacity.to_dict()}


def _jsonable(value):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, Path):
        return str(value)
    if isinstance(value, Fraction):
        return str(value)
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


__all__ = ["STEPS", "Progress", "GearPlacement", "MeshPlacement", "Layout", "CheckOutcome", "BuildResult",
           "check_free_figures", "BuildFailed", "load", "place", "gear_solids", "other_parts", "mesh_checks", "design_verdict", "mesh_sections",
           "meshes_outcome", "overlap_check",
           "stiffness", "export", "report", "manifest", "build", "export_config", "versions",
           "section_check", "contact_region", "Alongside"]
