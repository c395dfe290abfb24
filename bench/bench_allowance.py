"""What the backlash range of the thickness allowances adds to a check or build (issue 13).

Run by hand: ``.venv/bin/python bench/bench_allowance.py``. For each shipped drive: the full
verdict of ``geargen check`` without the error budget (:func:`geargen.checks.verdict.verify`,
which the build's mesh-check step runs, range included) and the range alone
(:func:`geargen.checks.allowance.backlash_ranges`: path 1 on the thickest and thinnest pair of
each mesh), best of ``REPEATS``; the share is what the range adds to the step. The largest
difference between the analytic and the measured range is shown too.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from geargen.checks.allowance import backlash_ranges  # noqa: E402
from geargen.checks.verdict import verify  # noqa: E402
from geargen.design.assembly import load_design  # noqa: E402
from geargen.model import resolve  # noqa: E402

REPEATS = 3
DRIVES = ["robot_joint", "c_axis", "split_pinion", "split_pinion_inch", "metric_dual_pinion"]


def best_of(fn):
    best, out = float("inf"), None
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> int:
    print(f"{'design':<20}{'meshes':>7}{'verify (s)':>12}{'range (s)':>11}{'share':>8}  analytic vs measured (mm)")
    for name in DRIVES:
        layout = resolve(load_design(ROOT / "assemblies" / f"{name}.toml"))
        t_verify, _ = best_of(lambda: verify(layout, tolerances=False))
        t_range, (ranges, _, _) = best_of(lambda: backlash_ranges(layout))
        worst = max((r["difference"] for r in ranges), default=float("nan"))
        print(f"{name:<20}{len(ranges):>7}{t_verify:>12.3f}{t_range:>11.3f}{t_range / t_verify:>8.1%}  {worst:.1e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
