"""Bench: geargen sweep on Dask, 1 against 2 process workers, and 1e7 Monte Carlo samples split over workers.

    .venv/bin/python bench/bench_sweep.py [--sweep assemblies/sweeps/robot_joint_stiffness.toml]
        [--samples 10000000] [--chunk-size 250000] [--workers 1 2] [--no-single]

Two parts, on assemblies/robot_joint.toml and through the functions `geargen sweep` runs:

1. The sweep file's designs (load, resolve, stiffness, the check verdict with its error-budget
   Monte Carlo, and the sweep's carriage Monte Carlo in its chunks) on a local cluster of each
   ``--workers`` count: wall time (the cluster's start apart), time per design, speed-up over
   one worker, and whether the tables are identical (they must be).
2. ``--samples`` samples of the exact loop model's carriage travel (:func:`geargen.core.tolerance.monte_carlo`,
   model "exact") in chunks of ``--chunk-size``, chunk ``i`` seeded by ``SeedSequence(1994).spawn(n)[i]``,
   on each worker count: time, samples/s, and the statistics against one process running the
   same chunks in order (must be equal, not close).

The machine is shared: the figures are indicative. Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from geargen.core.tolerance import combine_monte_carlo  # noqa: E402
from geargen.design.assembly import load_design  # noqa: E402
from geargen.design.sweep import MonteCarloBlock, load_sweep  # noqa: E402
from geargen.design.synthesis import monte_carlo_settings  # noqa: E402
from geargen.model import resolve  # noqa: E402
from geargen.sweep import DesignOutcome, MonteCarloInput, dask_client, monte_carlo_chunk, run_sweep  # noqa: E402

DESIGN = ROOT / "assemblies" / "robot_joint.toml"
SWEEP = ROOT / "assemblies" / "sweeps" / "robot_joint_stiffness.toml"
SEED = 1994


def robot_joint_monte_carlo() -> DesignOutcome:
    """The robot joint's exact loop model as a sweep's Monte Carlo chunks receive it."""
    design = load_design(DESIGN)
    run = resolve(design).synthesis
    s = monte_carlo_settings(design)
    return DesignOutcome({}, MonteCarloInput(run.synthesis, run.errors, s.model, s.error_shape,
                                             s.include_backlash_tolerance))


def statistics(res) -> tuple:
    return (res.samples, res.mean, res.std, res.minimum, res.maximum, *res.percentiles.values())


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sweep", default=str(SWEEP))
    ap.add_argument("--samples", type=int, default=10_000_000)
    ap.add_argument("--chunk-size", type=int, default=250_000)
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--no-single", action="store_true", help="skip the single-process Monte Carlo reference")
    args = ap.parse_args(argv)

    spec = load_sweep(args.sweep)
    block = MonteCarloBlock(args.samples, args.chunk_size, SEED)
    outcome = robot_joint_monte_carlo()
    rows, tables, mc = [], {}, {}
    for n in args.workers:
        t0 = time.perf_counter()
        with dask_client(n) as client:
            started = time.perf_counter() - t0
            result = run_sweep(DESIGN, spec, client)
            tables[n] = result.table
            rows.append((f"sweep: {spec.size} designs", n, started, result.seconds,
                         f"{result.seconds / spec.size:.2f} s/design"))
            remote = client.scatter(outcome, broadcast=True)
            t0 = time.perf_counter()
            futures = [client.submit(monte_carlo_chunk, remote, k, s, pure=False)
                       for k, s in zip(block.chunk_sizes(), block.seeds())]
            mc[n] = combine_monte_carlo(client.gather(futures))
            t = time.perf_counter() - t0
            rows.append((f"Monte Carlo {args.samples:.0e} samples, {block.chunks} chunks", n, started, t,
                         f"{args.samples / t:,.0f} samples/s"))
            del futures, remote
    single = None
    if not args.no_single:
        t0 = time.perf_counter()
        single = combine_monte_carlo([monte_carlo_chunk(outcome, k, s)
                                      for k, s in zip(block.chunk_sizes(), block.seeds())])
        t = time.perf_counter() - t0
        rows.append((f"Monte Carlo {args.samples:.0e} samples, one process, no Dask", 0, 0.0, t,
                     f"{args.samples / t:,.0f} samples/s"))

    base = {r[0]: r[3] for r in rows if r[1] == args.workers[0]}
    print(f"geargen sweep bench ({DESIGN.name}, {Path(args.sweep).name}; shared 2-core machine: indicative)\n")
    print("| what | workers | cluster start (s) | wall (s) | speed-up | rate |")
    print("|---|---:|---:|---:|---:|---|")
    for what, n, started, t, rate in rows:
        speed = f"{base[what] / t:.2f}" if what in base and n else "-"
        print(f"| {what} | {n or '-'} | {started:.1f} | {t:.1f} | {speed} | {rate} |")
    first = args.workers[0]
    same_tables = all(tables[n].equals(tables[first]) for n in args.workers)
    same_mc = all(statistics(mc[n]) == statistics(mc[first]) and np.array_equal(mc[n].travel, mc[first].travel)
                  for n in args.workers)
    print(f"\nsweep tables identical on {args.workers} workers: {same_tables}")
    print(f"Monte Carlo identical on {args.workers} workers: {same_mc}")
    if single is not None:
        equal = statistics(single) == statistics(mc[first]) and np.array_equal(single.travel, mc[first].travel)
        print(f"Monte Carlo equal to one process running the same chunks: {equal}")
    r = mc[first]
    print(f"carriage travel (mm): mean {r.mean:.6g}, std {r.std:.6g}, min {r.minimum:.6g}, max {r.maximum:.6g}, "
          f"99.73 % range {r.spread_99_73:.6g}; worst-case bounds {r.bound_low:.6g} to {r.bound_high:.6g}")
    return 0 if same_tables and same_mc else 1


if __name__ == "__main__":
    sys.exit(main())
