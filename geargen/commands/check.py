"""``geargen check DESIGN.toml``: geometric checks of every mesh of an assembly.

The meshes are those of the resolved drive (:func:`geargen.model.resolve`: the same teeth,
centres and phases ``geargen build`` exports) and the verdict is
:func:`geargen.checks.verdict.verify`, the one ``build`` gates on. Prints one table row per mesh
(backlash in the resolved model's kind, normal backlash, tip clearance, contact ratio, failure
kinds) and, when the design has an error budget, one row per mesh of the worst-case and Monte
Carlo minimum backlash. ``--json FILE`` writes everything (``-`` for standard output, then no
table); ``--plots DIR`` writes the backlash/clearance plots; ``--sections`` adds path 2
(sections of the gear solids, built here or read from a build's ``--exported`` folder) and its
agreement with path 1. Exit status 0 when every check passes, 1 on any failure, 2 on a bad
design file.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from geargen.checks.results import DesignCheck, Failure
from geargen.checks.verdict import check_design as verdict, mesh_setup, mesh_settings, sections_decide, undecided
from geargen.design.assembly import Design, load_design
from geargen.design.checks import ChecksSettings, checks_settings
from geargen.errors import DesignError
from geargen.model import BACKLASH_KIND, Layout
from geargen.units import LENGTH_SUFFIXES


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("design", help="design file (TOML)")
    p.add_argument("--json", metavar="FILE", help="write the results as JSON ('-': standard output, no table)")
    p.add_argument("--arrays", action="store_true", help="include the per-position sweep arrays in the JSON")
    p.add_argument("--plots", metavar="DIR", help="write backlash/clearance plots (PNG) into DIR")
    p.add_argument("--sections", action="store_true", help="also check sections of the gear solids (path 2)")
    p.add_argument("--exported", metavar="DIR", help="a build's output folder: section its exported STL files "
                                                    "(PART.stl) for --sections instead of building the gears here")
    p.add_argument("--position", choices=("engaged", "disengaged"), default=None,
                   help="sliding pinions engaged or disengaged (overrides [layout] position)")
    p.add_argument("--samples", type=int, help="Monte Carlo samples (overrides [checks] monte_carlo_samples)")
    p.add_argument("--seed", type=int, help="Monte Carlo seed (overrides [checks] seed)")
    p.add_argument("--no-tolerances", action="store_true", help="skip the error-budget analysis")


# ------------------------------------------------------------------------------ the check
def _world_to_gear(layout: Layout, part: str, gear) -> np.ndarray:
    """4x4 matrix taking the assembly frame to ``gear``'s own frame (its z = 0 face, tooth 0 on +x)."""
    p = layout.gear(part)
    rot = p.rotation
    c, s = math.cos(-rot), math.sin(-rot)
    m = np.eye(4)
    m[:2, :2] = [[c, -s], [s, c]]
    m[:3, 3] = m[:3, :3] @ -np.array([p.centre[0], p.centre[1], p.face_z(gear)[0]])
    return m


def _exported_build(design: Design, folder: Path) -> dict:
    """The manifest of a build of ``design`` in ``folder`` (``--exported``), checked to be one."""
    path = folder / "manifest.json"
    try:
        manifest = json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise DesignError("--exported", f"{folder} holds no readable geargen build manifest ({exc})",
                          "the output folder of `geargen build` of this design") from None
    if manifest.get("generator") != "geargen build" or manifest.get("design", {}).get("sha256") != design.sha256:
        raise DesignError("--exported", f"{folder} is not a build of this design file (its manifest names "
                          f"{manifest.get('design', {}).get('file')!r}, another sha256)",
                          "the output folder of `geargen build` of this very design file")
    return manifest


def _sections_of_part(layout: Layout, part: str, gear, planes, folder: Path, manifest: dict):
    """Sections of a build's exported ``PART.stl`` (assembly frame) taken in ``gear``'s own frame,
    with the chordal tolerance the build wrote the file with."""
    import trimesh

    from geargen.checks.solids import sections_from_triangles

    path = folder / f"{part}.stl"
    record = manifest.get("files", {}).get(path.name)
    if record is None or not path.is_file():
        raise DesignError("--exported", f"{path} is missing from the build", "a complete `geargen build` folder")
    tri = np.asarray(trimesh.load(str(path), file_type="stl", process=False).triangles, dtype=float)
    m = _world_to_gear(layout, part, gear)
    tri = tri @ m[:3, :3].T + m[:3, 3]
    return sections_from_triangles(gear, tri, planes, float(record["chordal_tolerance_mm"]), str(path))


def check_design(design: Design, settings: ChecksSettings | None = None, sections: bool | None = None,
                 exported: str | Path | None = None, tolerances: bool | None = None,
                 position: str | None = None) -> DesignCheck:
    """Every check of ``geargen check`` on a loaded design (see the module docstring)."""
    settings = checks_settings(design) if settings is None else settings
    result, layout = verdict(design, settings, position, tolerances)
    if not (settings.sections if sections is None else sections):
        return result
    from geargen.checks.mesh2d import MeshSetup
    from geargen.checks.solids import (check_mesh_sections, compare_paths, export_and_section, section_planes)

    if layout is None:
        pairs = [(MeshSetup.centred(design.gear(m.gear1), design.gear(m.gear2), m.centre_distance, m.name), None)
                 for m in settings.meshes]
    else:
        pairs = [(mesh_setup(layout, m), m) for m in layout.meshes if m.engaged]
    if exported is not None and layout is None:
        raise DesignError("--exported", "only a resolved drive ([layout] or [synthesis]) is built and exported",
                          "leave --exported out: the gears are built here")
    manifest = _exported_build(design, Path(exported)) if exported is not None else None
    cs = mesh_settings(settings)
    cache = {}
    for (su, mesh), exact in zip(pairs, result.meshes):
        planes = section_planes(su, settings.sections_planes)
        secs = []
        for g, z, part in ((su.gear1, planes, mesh and mesh.part1), (su.gear2, planes - su.face_offset2,
                                                                     mesh and mesh.part2)):
            key = (part or g.name, g.name, tuple(np.round(z, 12)))
            if key not in cache:
                if exported is not None:
                    cache[key] = _sections_of_part(layout, part, g, z, Path(exported), manifest)
                else:
                    cache[key] = export_and_section(g, z, chordal_tolerance=settings.stl_chordal_tolerance)
            secs.append(cache[key])
        path2 = check_mesh_sections(su, secs[0], secs[1], cs, exact.sweep.mesh_position)
        if not sections_decide(path2, layout.settings.get("loaded_flank_gap") if layout is not None else 0.0):
            path2.notes += undecided(path2)  # the same rule as the build's
            path2.failures = []
        result.meshes.append(path2)
        agreement = compare_paths(su, path2)
        result.agreement.append(agreement)
        if not agreement["agree"]:
            result.failures.append(Failure("paths_disagree", su.name,
                                           f"path 2 differs from path 1 by {agreement['normal_backlash_difference_max']:.3g} mm "
                                           f"(tolerance {agreement['tolerance']:.3g} mm)", "path_difference",
                                           agreement["normal_backlash_difference_max"], agreement["tolerance"]))
    return result


# ------------------------------------------------------------------------------ output
def _fmt(v: float, unit: str) -> str:
    if v is None or not math.isfinite(v):
        return "-"
    return f"{v / LENGTH_SUFFIXES[unit]:.6f}" if unit == "in" else f"{v / LENGTH_SUFFIXES[unit]:.5f}"


def _planetary_lines(result: DesignCheck, u: str) -> list[str]:
    """The planetary stages' rows (:mod:`geargen.checks.planetary_placed`) under one heading: the
    planet-ring meshes, then each stage's conditions."""
    if not result.planetary:
        return []
    lines = ["", "planet-ring meshes (backlash at the planet's reference circle, exact outlines as placed) and the "
             "stage's conditions"]
    for b in result.planetary:
        fails = ", ".join(dict.fromkeys(f.kind for f in result.failures if f.mesh == b["mesh"])) or "ok"
        if "gear1" in b:
            lines.append(f"  {b['mesh']:<30}measured {_fmt(b['backlash'], u)} (over a pitch {_fmt(b['sweep_min'], u)} "
                         f"to {_fmt(b['sweep_max'], u)})  closed form {_fmt(b['closed_form_backlash'], u)}  each side "
                         f"{_fmt(b['play_cw'], u)} / {_fmt(b['play_ccw'], u)}  design {_fmt(b['design_min'], u)} to "
                         f"{_fmt(b['design_max'], u)}  {fails}")
        else:
            lines.append(f"planetary stage {b['stage']}: ratio {b['ratio']:.6g}, carrier radius "
                         f"{_fmt(b['carrier_radius'], u)}, coaxiality difference "
                         f"{b['coaxiality_difference'] / LENGTH_SUFFIXES[u]:.2e}, assembly step error "
                         f"{b['assembly_step_error']:.1e}, planet tip gap {_fmt(b['neighbour_tip_gap'], u)}, "
                         f"minimum tooth difference {b['minimum_tooth_difference']}  {fails}")
    return lines


def _rack_lines(rows: list, u: str) -> list[str]:
    """The rack drive's rows (:mod:`geargen.checks.rack_drive`): rack meshes, carriage, preload, stiffness."""
    lines = []
    for r in rows:
        if r["mesh"] != "carriage":
            lines += ["", f"rack mesh ({r['gear1']} - rack): backlash {r['where']}",
                      f"  {r['mesh']:<22}measured {_fmt(r['backlash_min'], u)} to {_fmt(r['backlash_max'], u)}  "
                      f"design {_fmt(r['design_min'], u)} to {_fmt(r['design_max'], u)}  working flank gap "
                      f"{_fmt(r['working_flank_gap'], u)}  tip clearance {_fmt(r['tip_clearance'], u)}  "
                      f"contact ratio {r['contact_ratio']:.3f}"]
            continue
        k = r["stiffness"]
        lines += ["", "preload carriage (Type 2, radial motion, Fig. 9)",
                  f"  carriage at y {_fmt(r['carriage_y'], u)} ({_fmt(r['carriage_deviation'], u)} from nominal), "
                  f"needs {_fmt(r['carriage_needed'], u)} of its {_fmt(r['carriage_travel'], u)} {u} stroke; "
                  f"{r['sensitivity']:.4g} {u} of carriage per {u} of loop error at the rack",
                  f"  spring {r['spring_force']:.4g} N: each input mesh {r['mesh_force_at_rest']:.4g} N at rest; "
                  f"a path unloads at {r['unloading_rack_force']:.4g} N on the rack",
                  f"  stiffness at the rack (N/mm): paths {k['k1']:.4g}, {k['k2']:.4g}; k3 {k['k3']:.4g}; "
                  f"drive (Eq. 5) {k['drive']:.4g}; loop (Eq. 6) {k['loop']:.4g}"]
    return lines


def table(result: DesignCheck) -> str:
    """The text table of a design check (lengths in the design's unit)."""
    u = result.length_unit
    w = max([24] + [len(m.mesh) + 2 for m in result.meshes])  # the mesh column fits the longest name
    lines = [f"geargen check {result.design}  (lengths in {u})", ""]
    if result.backlash:
        lines += [f"backlash: {BACKLASH_KIND}, as modelled and placed (the numbers synth and build report)"]
        head = (f"{'mesh':<{w}}{'centre dist.':>14}{'modelled':>12}{'min':>12}{'max':>12}{'design min':>12}"
                f"{'design max':>12}")
        lines += [head, "-" * len(head)]
        for b in result.backlash:
            if not b.get("engaged", True):
                lines.append(f"{b['mesh']:<{w}}{'disengaged: axial clearance':>36} {_fmt(b.get('axial_clearance'), u)}")
                continue
            lines.append(f"{b['mesh']:<{w}}{_fmt(b['centre_distance'], u):>14}{_fmt(b.get('modelled'), u):>12}"
                         f"{_fmt(b.get('min'), u):>12}{_fmt(b.get('max'), u):>12}{_fmt(b.get('design_min'), u):>12}"
                         f"{_fmt(b.get('design_max'), u):>12}")
        lines.append("")
    if result.backlash_range:
        f_a = result.backlash_range[0]["centre_distance_tolerance"]
        lines += [f"backlash range from the tooth-thickness allowances, centre distance +-{_fmt(f_a, u)} {u}: "
                  "analytic, and measured on the thickest (min) and thinnest (max) teeth"]
        head = (f"{'mesh':<{w}}{'analytic min':>14}{'max':>12}{'measured min':>14}{'max':>12}{'difference':>12}"
                f"  verdict")
        lines += [head, "-" * len(head)]
        for r in result.backlash_range:
            lines.append(f"{r['mesh']:<{w}}{_fmt(r['analytic'][0], u):>14}{_fmt(r['analytic'][1], u):>12}"
                         f"{_fmt(r['measured'][0], u):>14}{_fmt(r['measured'][1], u):>12}"
                         f"{r['difference'] / LENGTH_SUFFIXES[u]:>12.1e}  {'ok' if r['ok'] else 'FAIL'}")
        lines.append("")
    lines += ["geometric checks (normal backlash: between the non-working flanks, normal to the teeth; "
              "clearance: tip to mate root)"]
    head = f"{'mesh':<{w}}{'path':<10}{'normal min':>12}{'clearance':>12}{'contact':>9}  failure"
    lines += [head, "-" * len(head)]
    for m in result.meshes:
        kinds = ", ".join(m.failure_kinds) or "ok"
        eps = f"{m.total_contact_ratio:.3f}" if math.isfinite(m.total_contact_ratio) else "-"
        lines.append(f"{m.mesh:<{w}}{m.path:<10}{_fmt(m.min_normal_backlash, u):>12}{_fmt(m.min_clearance, u):>12}"
                     f"{eps:>9}  {kinds}")
    for b in result.bevel:
        lines += ["", f"bevel pair ({b['gear1']} - {b['gear2']}): backlash {b['where']}",
                  f"  {b['mesh']:<22}measured {_fmt(b['backlash'], u)}  design {_fmt(b['design_backlash'], u)}  "
                  f"difference {(b['backlash'] - b['design_backlash']) / LENGTH_SUFFIXES[u]:.1e}  "
                  f"each side {_fmt(b['play_negative'], u)} / {_fmt(b['play_positive'], u)}  "
                  f"tip clearance {_fmt(b['tip_clearance'], u)}"]
    lines += _planetary_lines(result, u)
    lines += _rack_lines(result.rack, u)
    if result.tolerances:
        lines += ["", f"minimum backlash across the error budget ({BACKLASH_KIND}); MC: the backlash Monte Carlo, "
                  "its samples [checks] monte_carlo_samples (or --samples), not [monte_carlo] (synth's carriage travel)"]
        head = f"{'mesh':<16}{'meant for':<11}{'nominal':>12}{'worst case':>12}{'MC min':>12}{'MC 1%':>12}{'samples':>9}  failure"
        lines += [head, "-" * len(head)]
        for t in result.tolerances:
            kinds = ", ".join(dict.fromkeys(f.kind for f in t.failures)) or "ok"
            lines.append(f"{t.mesh:<16}{t.meant_for:<11}{_fmt(t.nominal_min_backlash, u):>12}"
                         f"{_fmt(t.worst_case_min_backlash, u):>12}{_fmt(t.monte_carlo_minimum, u):>12}"
                         f"{_fmt(t.monte_carlo_quantile(0.01), u):>12}{t.samples:>9}  {kinds}")
    if result.agreement:
        lines += ["", "path 2 (sections of the exported solids) against path 1 (exact)"]
        for a in result.agreement:
            lines.append(f"  {a['mesh']:<14} normal backlash differs by {_fmt(a['normal_backlash_difference_max'], u)} "
                         f"{u} (tolerance {_fmt(a['tolerance'], u)} {u}): {'agree' if a['agree'] else 'DISAGREE'}")
    fails = result.all_failures
    if fails:
        lines += ["", "failures:"]
        lines += [f"  {f.mesh}: {f.kind}: {f.message}" for f in fails]
    notes = list(result.notes) + [n for m in result.meshes for n in m.notes] + [n for t in result.tolerances for n in t.notes]
    if notes:
        lines += ["", "notes:"] + [f"  {n}" for n in dict.fromkeys(notes)]
    lines += ["", "result: " + ("ok" if result.ok else f"{len(fails)} failure(s)")]
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    design = load_design(args.design)
    settings = checks_settings(design)
    overrides = {k: v for k, v in (("monte_carlo_samples", args.samples), ("seed", args.seed)) if v is not None}
    if overrides:
        try:
            settings = replace(settings, **overrides)
        except DesignError as exc:
            raise DesignError(f"--{exc.field.replace('monte_carlo_', '')}", exc.problem, exc.allowed) from None
    result = check_design(design, settings, sections=args.sections or None, exported=args.exported,
                          tolerances=False if args.no_tolerances else None, position=args.position)
    data = result.to_dict(arrays=args.arrays)
    if result.defaulted:
        data["defaulted"] = {d.key: {"value": d.value, "why": d.why} for d in result.defaulted}
    if result.parts_table:
        data["parts_toml"] = result.parts_table
    if args.plots:
        from geargen.report.checks import write_check_plots
        data["plots"] = [str(p) for p in write_check_plots(result, args.plots)]
    if args.json == "-":
        json.dump(data, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        print(table(result))
        if result.defaulted:
            print(f"\ndefault hardware ({len(result.defaulted)} values the file does not give; the build's report "
                  "lists them):")
            print("\n".join(f"  {d}" for d in result.defaulted))
        if result.parts_table:
            print("\nthe hardware as resolved (paste into the design file and change what you like):\n")
            print(result.parts_table)
        if args.json:
            Path(args.json).parent.mkdir(parents=True, exist_ok=True)
            Path(args.json).write_text(json.dumps(data, indent=2) + "\n")
    return 0 if result.ok else 1


__all__ = ["add_arguments", "run", "check_design", "table"]
