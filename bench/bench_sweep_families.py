"""The random stability sweep of every gear family, run by hand: the full set (or a sample) and a table.

    .venv/bin/python bench/bench_sweep_families.py [--sample] [--family NAME ...] [--count N]
        [--seed S] [--workers W]

The families, their generators and checks are tests/sweep_support.py's (what
tests/test_family_sweep.py runs: a per-push sample there, seeded from the commit). Default here: the
full set (``GEARGEN_FULL_SWEEP=1``'s, ~720 cases from each family's fixed seed) with the coverage
floors; ``--sample`` the per-push sample of this commit instead, to see what it costs. ``--count``,
``--seed``: as ``GEARGEN_SWEEP_COUNT`` and ``GEARGEN_SWEEP_SEED``. Prints a Markdown table per
family: cases, built, refused (design and geometry errors), tagged failures, the seconds of its
cases (one worker each: what it costs a core), their mean and the slowest; then every failure with
its parameters and the seed that reproduces it. Exit status 1 on a tagged failure or a missed floor.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sample", action="store_true", help="the per-push sample of this commit, not the full set")
    ap.add_argument("--family", nargs="*", default=None, help="families to run (default: all)")
    ap.add_argument("--count", type=int, default=None, help="cases per family (GEARGEN_SWEEP_COUNT)")
    ap.add_argument("--seed", type=int, default=None, help="seed of every family (GEARGEN_SWEEP_SEED)")
    ap.add_argument("--workers", type=int, default=None, help="worker processes (GEARGEN_SWEEP_WORKERS)")
    args = ap.parse_args(argv)
    if args.count is not None:
        os.environ["GEARGEN_SWEEP_COUNT"] = str(args.count)
    if args.seed is not None:
        os.environ["GEARGEN_SWEEP_SEED"] = str(args.seed)
    import sweep_support as ss
    full = not args.sample
    names = args.family or list(ss.FAMILIES)
    unknown = [n for n in names if n not in ss.FAMILIES]
    if unknown:
        ap.error(f"--family: no {', '.join(unknown)} (one of {', '.join(ss.FAMILIES)})")
    cases = {name: ss.sweep_cases(ss.FAMILIES[name], full) for name in names}
    params = [p for _, ps in cases.values() for p in ps]
    t0 = time.perf_counter()
    results = ss.run_sweep(params, ss.CHECK, [ss.FAMILIES[p["family"]].timeout for p in params],
                           args.workers or ss.WORKERS)
    wall = time.perf_counter() - t0

    print(f"\n{'Full set' if full else 'Per-push sample'}: {len(params)} cases, {wall:.0f} s wall on "
          f"{args.workers or ss.WORKERS} workers")
    header = ("family", "seed", "cases", "built", "refused", "failures", "case s", "mean s", "slowest s", "floors")
    print(" | ".join(header))
    print(" | ".join("---" for _ in header))
    bad, at = [], 0
    for name, (seed, ps) in cases.items():
        fam = ss.FAMILIES[name]
        rs = results[at:at + len(ps)]
        at += len(ps)
        tags = Counter(r[0] for r in rs)
        failures = ss.tagged_failures(ps, rs, fam.expected_kinds)
        missed = fam.coverage(tags, ps, rs, len(ps)) if full else []
        refused = sum(v for k, v in tags.items() if k == "design_error" or k.startswith("geometry_error:"))
        seconds = [r[2] for r in rs]
        print(" | ".join([name, str(seed), str(len(ps)), str(tags["ok"]), str(refused), str(len(failures)),
                          f"{sum(seconds):.1f}", f"{sum(seconds) / max(len(ps), 1):.2f}",
                          f"{max(seconds, default=0.0):.2f}", "; ".join(missed) or ("met" if full else "")]))
        bad += [(name, seed, p, r) for p, r in failures] + [(name, seed, None, m) for m in missed]
    for name, seed, p, r in bad:
        print(f"\n{name} (GEARGEN_SWEEP_SEED={seed}): {r[0] + ': ' + r[1] if p is not None else r}"
              + (f"\n  {p}" if p is not None else ""))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
