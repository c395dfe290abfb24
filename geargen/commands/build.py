"""``geargen build DESIGN.toml [--out DIR] [--overwrite] [--quiet] [--force] [--position engaged|disengaged]``.

Builds the whole assembly (gears placed by the synthesis, the other parts, the mesh checks, the
stiffness summary) and writes ``exports/<design file name>/`` (or DIR) atomically:
``assembly.step``, one STEP and one STL per part, ``manifest.json``, ``report.md`` and
``report.html`` (key numbers first), and each of the report's figures (the rendered view, the
layout drawing, the preload diagram) as ``figures/<name>.png`` and ``.svg``.

The output folder must be new, empty, or an earlier build of the same design file (replaced
whole); ``--overwrite`` also replaces an earlier build of another design file or one whose files
were changed; a folder holding anything else is never written (:mod:`geargen.outputs`).

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
