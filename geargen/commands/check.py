"""``geargen check DESIGN.toml``: geometric checks of every mesh of an assembly.

Prints one table row per mesh (mesh, minimum and maximum backlash, minimum tip clearance,
contact ratio, kind of failure) and, when the design has an error budget, one row per mesh of
the worst-case and Monte Carlo minimum backlash. ``--json FILE`` writes everything (``-`` for
standard output, then no table); ``--plots DIR`` writes the backlash/clearance plots;
``--sections`` adds path 2 (sections of the exported solids) and its agreement with path 1.
Exit status 0 when every check passes, 1 on any failure, 2 on a bad design file.

Which meshes: a design with ``[synthesis]`` (the dual-pinion drive) is placed by
:func:`geargen.core.synthesis.place_gears` - centres and rotations of every gear - with the
backlash its gears as specified actually have at the design centre distances (measured on
path 1), and its four meshes are checked there. Otherwise the pairs of ``[checks] meshes`` are
checked at their centre distances, each centred in its play.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from geargen.checks.mesh2d import CheckSettings, MeshSetup, check_mesh, free_play, polar_outline
from geargen.checks.results import DesignCheck, Failure
from geargen.design.assembly import Design, load_design
from geargen.design.checks import ChecksSettings, checks_settings, gear_errors
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("design", help="design file (TOML)")
    p.add_argument("--json", metavar="FILE", help="write the results as JSON ('-': standard output, no table)")
    p.add_argument("--arrays", action="store_true", help="include the per-position sweep arrays in the JSON")
    p.add_argument("--plots", metavar="DIR", help="write backlash/clearance plots (PNG) into DIR")
    p.add_argument("--sections", action="store_true", help="also check sections of the exported solids (path 2)")
    p.add_argument("--exported", metavar="DIR", help="folder with the exported STL files (NAME.stl) for --sections; "
                                                    "default: build and export them to a temporary folder")
    p.add_argument("--samples", type=int, help="Monte Carlo samples (overrides [checks] monte_carlo_samples)")
    p.add_argument("--seed", type=int, help="Monte Carlo seed (overrides [checks] seed)")
    p.add_argument("--no-tolerances", action="store_true", help="skip the error-budget analysis")


# ------------------------------------------------------------------------------ which meshes
class LoopContext:
    """The placed dual-pinion loop: synthesis, placement and the modelled gears' backlash (mm)."""

    def __init__(self, synthesis, placement, backlash_mesh1: float, backlash_mesh2: float, errors):
        self.synthesis = synthesis
        self.placement = placement
        self.backlash_mesh1 = backlash_mesh1
        self.backlash_mesh2 = backlash_mesh2
        self.errors = errors


def _measured_backlash(gear_a, gear_b, centre_distance: float) -> float:
    """Circumferential backlash on gear a's reference circle (the synthesis' B), measured on path 1."""
    su = MeshSetup.centred(gear_a, gear_b, centre_distance)
    play = free_play(polar_outline(gear_a), polar_outline(gear_b), su.states([0.0]))
    return float((play.conjugate_ccw[0] + play.conjugate_cw[0]) * gear_a.reference_radius)


def mesh_setups(design: Design, settings: ChecksSettings) -> tuple[list[MeshSetup], LoopContext | None, list[str]]:
    """The meshes to check: placed by the synthesis, or declared in ``[checks] meshes``."""
    notes: list[str] = []
    if design.section("synthesis"):
        from geargen.core.synthesis import place_gears, synthesize_centres
        from geargen.design.synthesis import GEAR_ROLES, synthesis_inputs
        from geargen.checks.tolerance import LOOP_MESHES

        inputs = synthesis_inputs(design)
        syn = synthesize_centres(inputs).check()
        g = {role: design.gear(role) for role in GEAR_ROLES}
        b1 = _measured_backlash(g["input"], g["cluster_large"], inputs.centre_distance_mesh1)
        b2 = _measured_backlash(g["cluster_small"], g["output"], inputs.centre_distance_mesh2)
        tight = 1e-9 * inputs.module_mesh1
        for mesh, b in ((1, b1), (2, b2)):
            design_max = inputs.backlash(mesh, "max")
            if abs(b - design_max) > 1e-4 * inputs.module_mesh1:
                u = design.length_unit
                s = LENGTH_SUFFIXES[u]
                notes.append(f"mesh {mesh}: the gears as specified have {b / s:.6g} {u} circumferential backlash "
                             f"at the design centre distance; [synthesis] gives {design_max / s:.6g} {u} (max) - "
                             "the meshes are placed and checked with the gears as specified")
        placement = place_gears(syn, max(b1, 0.0) if b1 > -tight else 0.0, max(b2, 0.0) if b2 > -tight else 0.0)
        placement.check()
        where = {pg.name: pg for pg in placement.gears}
        setups = []
        for name, (ga, gb) in LOOP_MESHES.items():
            pa, pb = where[ga], where[gb]
            setups.append(MeshSetup(name, replace(design.gear(pa.role), name=ga), replace(design.gear(pb.role), name=gb),
                                    tuple(pa.centre), tuple(pb.centre), pa.rotation, pb.rotation))
        errors = {role: e for role in GEAR_ROLES if (e := gear_errors(design, role)) is not None}
        return setups, LoopContext(syn, placement, max(b1, 0.0), max(b2, 0.0), errors), notes
    if not settings.meshes:
        raise DesignError("checks.meshes", "missing: a design without [synthesis] must declare the pairs to check",
                          '[checks] meshes = [["gear1", "gear2"]] with centre_distance_<unit>')
    setups = [MeshSetup.centred(design.gear(m.gear1), design.gear(m.gear2), m.centre_distance, m.name)
              for m in settings.meshes]
    return setups, None, notes


# ------------------------------------------------------------------------------ the check
def check_design(design: Design, settings: ChecksSettings | None = None, sections: bool | None = None,
                 exported: str | Path | None = None, tolerances: bool | None = None) -> DesignCheck:
    """Every check of ``geargen check`` on a loaded design (see the module docstring)."""
    settings = checks_settings(design) if settings is None else settings
    setups, loop, notes = mesh_setups(design, settings)
    cs = CheckSettings(steps_per_tooth=settings.steps_per_tooth, revolutions=settings.revolutions,
                       planes=settings.section_planes, min_contact_ratio=settings.min_contact_ratio,
                       min_tip_land_modules=settings.min_tip_land_modules,
                       require_backlash=settings.require_backlash)
    meshes = [check_mesh(su, cs) for su in setups]
    result = DesignCheck(design=design.name, length_unit=design.length_unit, meshes=meshes, notes=notes)

    do_tol = settings.tolerances if tolerances is None else tolerances
    if do_tol:
        from geargen.checks.tolerance import carriage_travel_limits, loop_tolerance, pair_tolerance

        rng = np.random.default_rng(settings.seed)
        if loop is not None:
            if loop.errors:
                result.tolerances = loop_tolerance(loop.synthesis, {su.name: su for su in setups}, loop.errors,
                                                   loop.backlash_mesh1, loop.backlash_mesh2,
                                                   settings.monte_carlo_samples, rng,
                                                   carriage_travel_limits(design, settings.carriage_travel_limit),
                                                   settings.steps_per_tooth, design.length_unit)
        else:
            for su in setups:
                e1, e2 = gear_errors(design, su.gear1.name), gear_errors(design, su.gear2.name)
                if e1 is None and e2 is None:
                    continue
                result.tolerances.append(pair_tolerance(su, e1, e2, settings.monte_carlo_samples, rng,
                                                        "backlash" if settings.require_backlash else "zero_backlash",
                                                        settings.steps_per_tooth, design.length_unit))

    if settings.sections if sections is None else sections:
        from geargen.checks.solids import (check_mesh_sections, compare_paths, export_and_section, section_planes,
                                           sections_from_stl)

        cache = {}
        for su, exact in zip(setups, meshes):
            planes = section_planes(su, settings.sections_planes)
            secs = []
            for g, z in ((su.gear1, planes), (su.gear2, planes - su.face_offset2)):
                key = (g.name, tuple(np.round(z, 12)))
                if key not in cache:
                    stl = Path(exported) / f"{g.name}.stl" if exported else None
                    if stl is not None and stl.exists():
                        cache[key] = sections_from_stl(g, stl, z, settings.stl_chordal_tolerance)
                    else:
                        cache[key] = export_and_section(g, z, chordal_tolerance=settings.stl_chordal_tolerance)
                secs.append(cache[key])
            path2 = check_mesh_sections(su, secs[0], secs[1], cs, exact.sweep.mesh_position)
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


def table(result: DesignCheck) -> str:
    """The text table of a design check (lengths in the design's unit)."""
    u = result.length_unit
    lines = [f"geargen check {result.design}  (lengths in {u}; backlash circumferential on gear 1's operating "
             "pitch circle, normal = normal to the flanks)", ""]
    head = (f"{'mesh':<16}{'path':<10}{'backlash min':>14}{'max':>12}{'normal min':>12}{'clearance':>12}"
            f"{'contact':>9}  failure")
    lines += [head, "-" * len(head)]
    for m in result.meshes:
        kinds = ", ".join(m.failure_kinds) or "ok"
        eps = f"{m.total_contact_ratio:.3f}" if math.isfinite(m.total_contact_ratio) else "-"
        lines.append(f"{m.mesh:<16}{m.path:<10}{_fmt(m.min_backlash, u):>14}{_fmt(m.max_backlash, u):>12}"
                     f"{_fmt(m.min_normal_backlash, u):>12}{_fmt(m.min_clearance, u):>12}{eps:>9}  {kinds}")
    if result.tolerances:
        lines += ["", "minimum backlash across the error budget (circumferential)"]
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
                          tolerances=False if args.no_tolerances else None)
    data = result.to_dict(arrays=args.arrays)
    if args.plots:
        from geargen.report.checks import write_check_plots
        data["plots"] = [str(p) for p in write_check_plots(result, args.plots)]
    if args.json == "-":
        json.dump(data, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        print(table(result))
        if args.json:
            Path(args.json).parent.mkdir(parents=True, exist_ok=True)
            Path(args.json).write_text(json.dumps(data, indent=2) + "\n")
    return 0 if result.ok else 1


__all__ = ["add_arguments", "run", "check_design", "mesh_setups", "table", "LoopContext"]
