"""``geargen sweep DESIGN.toml SWEEP.toml [--out DIR] [--workers N | --scheduler ADDRESS]``: many designs at once.

The sweep file (docs/sweep-files.md) varies design-file keys by their dotted path, as a grid of
values or as random draws, and may ask for the carriage-travel Monte Carlo of ``geargen synth``
per design in fixed chunks. Every design goes through the synthesis, stiffness and checks of
``synth``, ``stiffness`` and ``check`` (:mod:`geargen.sweep`) on Dask: a local cluster of process
workers (``--workers``, default every core) or an existing scheduler (``--scheduler``). The
table (``sweep.parquet``, one row per design: the values, ``status`` ok/rejected and a ``tag``
saying why, the key numbers) and the summary plot (``summary.png``/``.svg``) go into
``exports/<design file name>-sweep/`` (or DIR), which follows the policy of
:mod:`geargen.outputs` and is written atomically. Rejected designs are results, not errors: the
exit status is 0 unless the input is bad (2) or the folder cannot be written (3).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from geargen.errors import DesignError, EnvironmentProblem

MAX_WORKERS = 1024


def add_arguments(p) -> None:
    p.add_argument("design", help="the design file (TOML) the sweep starts from")
    p.add_argument("sweep", help="the sweep file (TOML): [parameters], [random], [monte_carlo] (docs/sweep-files.md)")
    p.add_argument("--out", metavar="DIR", default=None,
                   help="output folder (default: exports/<design file name>-sweep); must not exist, be empty, or "
                        "hold an earlier sweep of the same design and sweep files, which is replaced")
    p.add_argument("--overwrite", action="store_true",
                   help="also replace an earlier sweep of other files (never a folder holding files geargen did "
                        "not write)")
    p.add_argument("--workers", type=int, default=None, metavar="N",
                   help="process workers of the local cluster (default: every core)")
    p.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="run on an existing dask.distributed scheduler (tcp://host:8786) instead of a local cluster")
    p.add_argument("--quiet", action="store_true", help="no progress on standard error")


def output_folder(args, design_path: Path, sweep_path: Path):
    """The :class:`geargen.outputs.OutputFolder` of the sweep: its source is the pair of files."""
    from geargen.outputs import plot_folder
    return plot_folder(args, None, "sweep", "geargen sweep", f"{design_path} + {sweep_path}",
                       f"the design file {design_path} with the sweep file {sweep_path}")


def _options(args) -> None:
    if args.workers is not None and args.scheduler is not None:
        raise DesignError("--workers", "given with --scheduler: the scheduler's cluster has its own workers",
                          "one of --workers and --scheduler")
    if args.workers is not None and not 1 <= args.workers <= MAX_WORKERS:
        raise DesignError("--workers", f"{args.workers} is out of range", f"1 to {MAX_WORKERS}")
    if args.scheduler is not None and not args.scheduler.strip():
        raise DesignError("--scheduler", "an empty address", "tcp://host:port of a dask.distributed scheduler")


def run(args) -> int:
    from geargen.design.assembly import load_design
    from geargen.design.sweep import load_sweep
    from geargen.sweep import check_sweep

    _options(args)
    sweep_path = Path(args.sweep).expanduser()
    if not sweep_path.is_file():
        raise EnvironmentProblem(str(args.sweep), "no such sweep file" if not sweep_path.exists() else
                                 "is a folder, not a sweep file", "give the sweep .toml file")
    design = load_design(args.design)
    spec = load_sweep(sweep_path)
    data = check_sweep(design.path, spec)
    output = output_folder(args, design.path, sweep_path.resolve())
    output.prepare()  # refused or unwritable: said before any work
    try:
        return _run(args, design, spec, data, output)
    except BaseException:
        output.discard()
        raise


def _run(args, design, spec, data, output) -> int:
    from geargen.sweep import dask_client, print_summary, run_sweep, write_outputs

    def progress(done: int, total: int) -> None:
        if not args.quiet and (done == total or done % max(1, total // 20) == 0):
            print(f"  designs {done}/{total}", file=sys.stderr, flush=True)

    if not args.quiet:
        where = f"scheduler {args.scheduler}" if args.scheduler else \
            f"a local cluster of {args.workers or os.cpu_count()} process workers"
        print(f"geargen sweep: {spec.size} designs ({spec.grid_points} grid points x {spec.count} draws) on {where}",
              file=sys.stderr, flush=True)
    with dask_client(args.workers, args.scheduler) as client:
        result = run_sweep(design.path, spec, client, progress, data)
    files = write_outputs(result, output.work, design.name)
    mc = spec.monte_carlo
    target = output.commit_with_manifest(design, str(design.path), {
        "sweep": {"file": str(spec.path), "designs": spec.size, "grid_points": spec.grid_points, "draws": spec.count,
                  "seed": spec.seed, "monte_carlo": None if mc is None else {
                      "samples": mc.samples, "chunk_size": mc.chunk_size, "seed": mc.seed}},
        "counts": result.counts, "seconds": round(result.seconds, 3), "workers": result.workers})
    print_summary(result)
    print("\nWritten: " + ", ".join(str(target / Path(p).name) for p in files.values()))
    return 0


__all__ = ["add_arguments", "run", "output_folder"]
