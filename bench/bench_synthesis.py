"""Bench: centre synthesis and a 1,000,000-sample Monte Carlo of the carriage travel in under 5 s.

    .venv/bin/python bench/bench_synthesis.py [--samples 1000000] [--seed 1994] [--repeat 3]

Times, on assemblies/robot_joint.toml and through the functions `geargen synth` calls: loading
the design, the Appendix synthesis (Eqs. 7-8), the exact placement, the Appendix and exact error
budgets, and the Monte Carlo simulation with both models (best of ``--repeat`` runs each).
The "exact" model re-solves the loop geometry for every sample (vectorised Newton); the
"appendix" model sums the sheet's per-gear factors. Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from geargen.core.synthesis import place_gears, synthesize_centres  # noqa: E402
from geargen.core.tolerance import appendix_error_budget, exact_error_budget, monte_carlo  # noqa: E402
from geargen.design.assembly import load_design  # noqa: E402
from geargen.core.accuracy import error_budget_inputs  # noqa: E402
from geargen.design.synthesis import synthesis_inputs  # noqa: E402

BUDGET_S = 5.0
DESIGN = ROOT / "assemblies" / "robot_joint.toml"


def best_of(repeat: int, fn):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=1_000_000)
    ap.add_argument("--seed", type=int, default=1994)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)

    rows = []
    t, design = best_of(args.repeat, lambda: load_design(DESIGN))
    rows.append(("load design", "", t))
    t, s = best_of(args.repeat, lambda: synthesize_centres(synthesis_inputs(design)).check())
    rows.append(("synthesis, Eqs. 7-8 (3 Appendix steps)", "", t))
    t, _ = best_of(args.repeat, lambda: place_gears(s).check())
    rows.append(("place gears (exact loop closure)", "", t))
    errors = error_budget_inputs(design)
    t, _ = best_of(args.repeat, lambda: appendix_error_budget(s, errors))
    rows.append(("Appendix error budget", "", t))
    t, _ = best_of(args.repeat, lambda: exact_error_budget(s, errors))
    rows.append(("exact error budget (gradients + re-solves)", "", t))
    results = {}
    for model in ("appendix", "exact"):
        for n in sorted({10_000, 100_000, args.samples}):
            t, mc = best_of(args.repeat, lambda: monte_carlo(s, errors, n, args.seed, model=model, spring_rate=5.66,
                                                             preload=64.8))
            if not mc.success:
                print(f"bench_synthesis: Monte Carlo failed: {mc.message}", file=sys.stderr)
                return 1
            rows.append((f"Monte Carlo, {model} model", f"{n:,}", t))
            results[(model, n)] = (t, mc)

    print(f"bench_synthesis: {DESIGN.name}, best of {args.repeat} runs")
    print()
    print("| step | samples | seconds | samples/s |")
    print("|---|---:|---:|---:|")
    for name, n, t in rows:
        rate = f"{int(n.replace(',', '')) / t:,.0f}" if n else ""
        print(f"| {name} | {n} | {t:.4f} | {rate} |")
    print()
    scale = 25.4  # the robot joint is an inch design
    print("| model | samples | p0.135 (in) | p99.865 (in) | 99.73 % wide (in) | RSS (in) | worst Sum (in) |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for (model, n), (_, mc) in results.items():
        if n == args.samples:
            print(f"| {model} | {n:,} | {mc.percentiles[0.135] / scale:.5f} | {mc.percentiles[99.865] / scale:.5f} | "
                  f"{mc.spread_99_73 / scale:.5f} | {mc.rss / scale:.5f} | {mc.worst_case_sum / scale:.5f} |")
    print()
    worst = max(results[(m, args.samples)][0] for m in ("appendix", "exact"))
    verdict = "within" if worst < BUDGET_S else "OVER"
    print(f"{args.samples:,} samples: {worst:.2f} s for the slower model, {verdict} the {BUDGET_S:.0f} s budget")
    return 0 if worst < BUDGET_S else 1


if __name__ == "__main__":
    sys.exit(main())
