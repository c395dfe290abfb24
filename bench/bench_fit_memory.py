"""Bench: peak memory of ``geargen fit`` on a large preload trace, against 5 x the CSV's size.

    .venv/bin/python bench/bench_fit_memory.py [--rows 10000000] [--rows 1000000 ...] [--no-plots]
                                               [--no-temperature] [--keep DIR] [--seed 1]

For each size, a preload trace is made with the project's simulator (geargen.fit.simulate: the
paper's 16/48/21/112 train, 3 output revolutions forward and 3 back over an hour, uneven
sampling, four probe drop-outs, 0.5 um noise, a temperature column (``--no-temperature``: none,
and drift with time instead), and two undeclared effects: an out-of-round output gear at order 2
and thermal drift) and written with
``write_measurement`` to a temporary CSV + TOML. Then ``geargen fit CSV --json OUT --report DIR``
runs exactly as a user runs it, in a fresh interpreter, and its peak resident memory is read
with ``resource.getrusage(RUSAGE_CHILDREN).ru_maxrss``.

The fit runs as the grandchild of a small watcher process that imports nothing heavy: the
bench itself holds the simulated arrays (gigabytes at 10 million rows), and a child forked from
it could show that memory in its own high-water mark before it executes the new interpreter;
RUSAGE_CHILDREN is also the maximum over *all* waited-for children, so the watcher runs one
child only. Simulation and CSV writing are not timed.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TARGET_FACTOR = 5.0
BASELINE_ROWS = 2000

WATCHER = r"""
import json, resource, subprocess, sys, time
t0 = time.perf_counter()
proc = subprocess.run(sys.argv[1:], capture_output=True, text=True)
wall = time.perf_counter() - t0
peak_kib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss  # KiB on Linux
print(json.dumps({"rc": proc.returncode, "wall_s": wall, "peak_kib": peak_kib,
                  "stdout": proc.stdout[-2000:], "stderr": proc.stderr[-4000:]}))
"""


def make_trace(rows: int, seed: int, folder: Path, temperature: bool = True) -> tuple[Path, dict]:
    """Simulate and write a preload trace of ``rows`` rows; (CSV path, facts about it)."""
    import numpy as np

    sys.path.insert(0, str(ROOT))
    from geargen.fit.measurement import write_measurement
    from geargen.fit.simulate import PreloadSettings, PreloadTruth, Sampling, simulate_preload_trace

    drift = {"drift_per_kelvin": 1.2} if temperature else {"drift_per_second": 0.001}
    truth = PreloadTruth(harmonics=((2.0, 3.0, 35.0),), **drift)
    settings = PreloadSettings(sampling=Sampling(samples=rows, duration_s=3600.0, dropouts=4, temperature=temperature),
                               revolutions=3.0, noise_um=0.5)
    sim = simulate_preload_trace(truth, np.random.default_rng(seed), settings, name=f"memory_{rows}")
    csv = write_measurement(sim.measurement, folder)
    return csv, {"true_noise_rms": sim.true_noise_rms, "expected": sim.expected}


def measure(csv: Path, out: Path, plots: bool) -> dict:
    """Run ``geargen fit`` on ``csv`` in a fresh interpreter under the watcher; its figures."""
    cmd = [sys.executable, "-m", "geargen.cli", "fit", str(csv), "--json", str(out / "fit.json"),
           "--report", str(out / "report")]
    if not plots:
        cmd.append("--no-plots")
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    # The fit's matrix products are tall and thin: BLAS threads buy nothing on a shared machine.
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    env.setdefault("OMP_NUM_THREADS", "1")
    res = subprocess.run([sys.executable, "-c", WATCHER, *cmd], capture_output=True, text=True, env=env, check=True)
    return json.loads(res.stdout)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, action="append", help="rows of the trace (repeatable); default 10,000,000")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--no-plots", action="store_true", help="fit without drawing the report's plots")
    ap.add_argument("--no-temperature", action="store_true", help="a trace without a temperature column")
    ap.add_argument("--keep", default=None, help="write the files here instead of a temporary folder")
    args = ap.parse_args(argv)
    sizes = args.rows or [10_000_000]

    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    with tempfile.TemporaryDirectory() as tmp:  # what the interpreter and its imports cost alone
        csv, _ = make_trace(BASELINE_ROWS, args.seed, Path(tmp), temperature=not args.no_temperature)
        baseline = measure(csv, Path(tmp), plots=not args.no_plots)["peak_kib"] * 1024
    print(f"bench_fit_memory: geargen fit{' --no-plots' if args.no_plots else ''} in a fresh interpreter; "
          f"load average {load:.1f} on {os.cpu_count()} CPUs; the same on a {BASELINE_ROWS:,}-row trace peaks at "
          f"{baseline / 1e6:.0f} MB (interpreter, numpy, scipy{', matplotlib' if not args.no_plots else ''}), "
          f"which the 5 x target includes")
    print()
    print("| rows | CSV MB | peak RSS MB | peak / CSV | target (5 x CSV) MB | wall s | effects added | result |")
    print("|---|---|---|---|---|---|---|---|")
    failed = 0
    for rows in sizes:
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(args.keep) / str(rows) if args.keep else Path(tmp)
            folder.mkdir(parents=True, exist_ok=True)
            t0 = time.perf_counter()
            csv, facts = make_trace(rows, args.seed, folder, temperature=not args.no_temperature)
            t_make = time.perf_counter() - t0
            size = csv.stat().st_size
            r = measure(csv, folder, plots=not args.no_plots)
            peak = r["peak_kib"] * 1024
            if r["rc"] != 0:
                failed += 1
                print(f"| {rows:,} | {size / 1e6:.0f} | {peak / 1e6:.0f} | {peak / size:.2f} | "
                      f"{TARGET_FACTOR * size / 1e6:.0f} | {r['wall_s']:.1f} | - | FAIL: exit {r['rc']} |")
                print(r["stderr"], file=sys.stderr)
                continue
            summary = json.loads((folder / "fit.json").read_text())
            added = "; ".join(f"{e['effect']} " + (f"order {e['order']:.4f} amp {e['amplitude']:.3f}" if e["effect"] == "harmonic"
                                                   else ", ".join(f"{k} {v:.4g}" for k, v in e.items()
                                                                  if k in ("per_kelvin", "per_second", "half_width")))
                              for e in summary["effects_added"]) or "none"
            ok = peak < TARGET_FACTOR * size
            failed += not ok
            print(f"| {rows:,} | {size / 1e6:.0f} | {peak / 1e6:.0f} | {peak / size:.2f} | "
                  f"{TARGET_FACTOR * size / 1e6:.0f} | {r['wall_s']:.1f} | {added} | {'PASS' if ok else 'FAIL'} |")
            print(f"  (simulated and written in {t_make:.0f} s, not timed; truth: "
                  f"{'; '.join(str(e) for e in facts['expected'])}; true noise {facts['true_noise_rms']:.4f} um, "
                  f"fitted noise_rms {summary['noise_rms']:.4f}, extended rms {summary['stages']['extended']['rms']:.4f}, "
                  f"unexplained {summary['unexplained']})", flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
