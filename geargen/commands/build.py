"""``geargen build DESIGN.toml [--out DIR] [--overwrite] [--quiet] [--force] [--position engaged|disengaged]``.

Builds the whole assembly (gears placed by the synthesis, the other parts, the mesh checks, the
stiffness summary) and writes ``exports/<design file name>/`` (or DIR) atomically:
``assembly.step``, one STEP and one STL per part, ``manifest.json``, ``report.md`` and
``report.html`` (key numbers first), and each of the report's figures (the rendered view, the
layout drawing, the preload diagram) as ``figures/<name>.png`` and ``.svg``.

The output folder must be new, empty, or an earlier build of the same design file (replaced
whole); ``--overwrite`` also replaces an earlier build of another design file or one whose files
were changed; a folder holding anything else is never written (:mod:`geargen.outputs`).

A design file that places no drive (no ``[layout]``, no ``[synthesis]``: gears and the meshes
``[checks]`` declares, as a study for ``geargen train`` or ``geargen check``) is built as its gear
set: the verdict is that of ``geargen check DESIGN`` (the same call), and each ``[gears.NAME]`` is
written as ``geargen gear DESIGN --gear NAME`` writes it (``NAME.step``, ``.stl``, ``.json``, the
drawing and DXF) into one folder with ``report.md`` (the check's table) and ``manifest.json``.
There is no assembly file: where the gears sit around each other is not in the design.

Exit status 0 on success, 1 when a check fails (nothing written unless ``--force``, which writes
the build marked as failing), 2 for a bad design file or option, 3 when the output folder is
refused or cannot be written, the design file is missing, or the build is interrupted.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from geargen.pipeline import POSITIONS, BuildFailed, build


def add_arguments(p) -> None:
    p.add_argument("design", help="assembly design file (TOML)")
    p.add_argument("--out", metavar="DIR", default=None,
                   help="output folder (default: exports/<design file name without .toml>); must not exist, be "
                        "empty, or hold an earlier build of the same design file, which is replaced")
    p.add_argument("--overwrite", action="store_true",
                   help="also replace an earlier geargen build of another design file, or one whose files were "
                        "changed (never a folder holding files geargen did not write)")
    p.add_argument("--quiet", action="store_true", help="no progress display")
    p.add_argument("--force", action="store_true",
                   help="write the build even when a check fails (marked as failing in manifest and report)")
    p.add_argument("--position", choices=POSITIONS, default=None,
                   help="sliding pinions engaged or disengaged (overrides [layout] position)")


def files_written(folder: Path) -> int:
    """The files a build wrote: exports, drawings, figures, report, review page and manifest (once the
    build is swapped into place its folder holds nothing else)."""
    return sum(1 for p in Path(folder).rglob("*") if p.is_file())


def run(args) -> int:
    t0 = time.perf_counter()
    from geargen.design.assembly import load_design
    from geargen.model import is_drive
    design = load_design(args.design)
    if not is_drive(design):
        return build_gear_set(args, design, t0)
    try:
        result = build(args.design, out=args.out, quiet=args.quiet, force=args.force, position=args.position,
                       overwrite=args.overwrite)
    except BuildFailed as exc:
        print(f"geargen build: FAILED: {exc}", file=sys.stderr)
        return 1
    total = time.perf_counter() - t0  # the steps' times overlap (the mesh checks run alongside)
    if not args.quiet:
        status = "ok" if result.ok else "FAILING (written with --force)"
        print(f"{result.design.name}: {status}, {files_written(result.out_dir)} files in {result.out_dir} "
              f"({total:.1f} s)", file=sys.stderr)
    print(result.out_dir)
    return 0 if result.ok else 1


def build_gear_set(args, design, t0: float) -> int:
    """``geargen build`` of a design that places no drive: its gears (see the module docstring)."""
    import argparse
    import json

    from geargen.cad.export import write_json
    from geargen.commands import check as check_command, gear as gear_command
    from geargen.pipeline import design_source, output_folder, versions

    # the verdict of `geargen check DESIGN`, first: a design it refuses is refused here in its words
    result = check_command.check_design(design, position=args.position)
    gear_parser = argparse.ArgumentParser(prog="geargen gear", add_help=False)
    gear_command.add_arguments(gear_parser)
    prepared = []  # every gear's options and drawing keys checked before anything is built
    for name in design.gears:
        gear_args = gear_parser.parse_args([str(args.design), "--gear", name])
        prepared.append((gear_args, *gear_command.prepared_gear(gear_args)))
    failures = [f"{f.mesh or design.name} ({f.kind}): {f.message}" for f in result.all_failures]  # as a drive's
    forced = args.force and not result.ok
    if not result.ok and not args.force:
        print(f"geargen build: FAILED: {design.name}: the gear set fails its checks (nothing written; --force writes "
              "it marked as failing):\n  " + "\n  ".join(failures), file=sys.stderr)
        return 1
    output = output_folder(design, args.out, args.overwrite, args.design)
    work = output.prepare()
    try:
        files = {}
        for gear_args, spec, thinning_source, allowance in prepared:
            if not args.quiet:
                print(f"gear {spec.name}", file=sys.stderr)
            records, data_file, drawn = gear_command.gear_files(gear_args, spec, thinning_source, work,
                                                                gear_command.gear_source(gear_args, spec), allowance)
            for r in records:
                files[r.path.name] = r.manifest_entry() | {"gear": spec.name}
            for path in [data_file, *drawn.values()]:
                files[path.name] = {"format": path.suffix.lstrip("."), "gear": spec.name,
                                    "length_unit": spec.length_unit, "bytes": path.stat().st_size}
        report = work / "report.md"
        report.write_text(f"# {design.name}: gear set\n\n{design.description or ''}\n\nThe design places no drive "
                          "([layout] or [synthesis]): each gear is built alone, as `geargen gear DESIGN --gear NAME` "
                          "builds it; the meshes are those [checks] declares.\n\n```\n"
                          f"{check_command.table(result)}\n```\n")
        files[report.name] = {"format": "md", "role": "report", "bytes": report.stat().st_size}
        write_json(work / "manifest.json", {
            "generator": "geargen build", "kind": "gear set", "source": design_source(design, args.design),
            "design": {"name": design.name, "file": str(design.path) if design.path else None,
                       "sha256": design.sha256, "length_unit": design.length_unit},
            "status": "ok" if result.ok else "failing", "forced": forced,
            "failures": failures,
            "units": {"step": f"{design.length_unit} (declared in each file)", "stl": "mm"},
            "checks": json.loads(json.dumps(result.to_dict(), default=str)),
            "files": files, "versions": versions()})
        target = output.commit()
    except BaseException:
        output.discard()
        raise
    if not args.quiet:
        status = "ok" if result.ok else "FAILING (written with --force)"
        print(f"{design.name}: gear set {status}, {files_written(target)} files in {target} "
              f"({time.perf_counter() - t0:.1f} s)", file=sys.stderr)
    print(target)
    return 0 if result.ok else 1
