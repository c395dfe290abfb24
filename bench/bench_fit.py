"""Bench: a 100,000-sample preload trace fitted, diagnosed and reported in under 5 s.

    .venv/bin/python bench/bench_fit.py [--samples 100000] [--seed 1] [--keep DIR]

The trace comes from the project's simulator (geargen.fit.simulate): the paper's train
(16/48/21/112 teeth), 3 output revolutions forward and 3 back, uneven sampling, four probe
drop-outs, 0.5 um probe noise, and two effects the sidecar does not declare (an out-of-round
output gear at order 2 and thermal drift). It is written as CSV + TOML, then timed through the
same path as ``geargen fit``: read, fit and diagnose, write the JSON and the Markdown report with
its plots. Simulation and file writing are not timed.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

if "--blas-threads" not in sys.argv:
    # The fit's matrix products are tall and thin (n x ~15): BLAS threads buy nothing there and,
    # on a shared machine, spin-wait for a CPU; the bench runs them single-threaded unless told.
    # (Set before numpy is imported, or it has no effect.)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from geargen.commands.fit import fit_files  # noqa: E402
from geargen.fit.measurement import write_measurement  # noqa: E402
from geargen.fit.simulate import PreloadSettings, PreloadTruth, Sampling, simulate_preload_trace  # noqa: E402

BUDGET_S = 5.0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=100_000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--keep", default=None, help="write the files here instead of a temporary folder")
    ap.add_argument("--blas-threads", action="store_true", help="leave BLAS threading at its default")
    args = ap.parse_args(argv)

    truth = PreloadTruth(harmonics=((2.0, 3.0, 35.0),), drift_per_kelvin=1.2)
    settings = PreloadSettings(sampling=Sampling(samples=args.samples, duration_s=3600.0, dropouts=4),
                               revolutions=3.0, noise_um=0.5)
    t0 = time.perf_counter()
    sim = simulate_preload_trace(truth, np.random.default_rng(args.seed), settings, name="bench_preload")
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(args.keep) if args.keep else Path(tmp)
        csv = write_measurement(sim.measurement, folder)
        t_sim = time.perf_counter() - t0
        out = fit_files(csv, folder / "bench_preload.fit.json", folder / "bench_preload_fit")
    s, sec, cpu = out["summary"], out["seconds"], out["cpu_seconds"]
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"bench_fit: {sim.measurement.samples} samples, simulated and written in {t_sim:.2f} s (not timed); "
          f"load average {load:.1f} on {os.cpu_count()} CPUs")
    print()
    print("| step | wall s | CPU s |")
    print("|---|---|---|")
    names = {"read": "read CSV + TOML", "fit": "fit + diagnose", "report": "JSON + Markdown + 4 plots", "total": "total"}
    for k, label in names.items():
        print(f"| {label} | {sec[k]:.2f} | {cpu[k]:.2f} |")
    print()
    st = s["stages"]
    print("| quantity | value |")
    print("|---|---|")
    print(f"| true noise (um rms) | {sim.true_noise_rms:.4f} |")
    print(f"| noise_rms, model-free (um) | {s['noise_rms']:.4f} |")
    for k in ("nominal", "declared", "extended"):
        print(f"| {k} rms (um) | {st[k]['rms']:.4f} |")
    for e in s["effects_added"]:
        params = ", ".join(f"{k} {v:.5g}" if isinstance(v, float) else f"{k} {v}" for k, v in e.items()
                           if k in ("order", "amplitude", "phase_deg", "shaft", "multiple", "per_kelvin", "per_second", "half_width"))
        print(f"| effect added | {e['effect']}: {params} |")
    print(f"| expected | {'; '.join(str(x) for x in sim.expected)} |")
    print(f"| unexplained | {s['unexplained']} |")
    ok = sec["total"] < BUDGET_S
    print()
    print(f"{'PASS' if ok else 'FAIL'}: total {sec['total']:.2f} s {'<' if ok else '>='} {BUDGET_S:.0f} s")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
