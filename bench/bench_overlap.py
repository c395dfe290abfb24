"""The build's solid overlap check alone (:func:`geargen.pipeline.overlap_check`, issue 28).

Run by hand: ``python bench/bench_overlap.py [--repeat N] [--root DIR] [NAME ...]``. For each shipped
design that builds (``assemblies/*.toml`` unless named), its parts are built once, then the
check runs N times on them (each part's moved shape rebuilt before each run, so nothing the check
caches carries over); the median and best wall seconds and the median processor seconds (this
process's user + system: on a machine shared with other work the wall time varies with their load,
the processor time much less) are printed, with the check's verdict (pairs checked, ok). ``--root`` measures another checkout (e.g. the commit before the fast paths, for the
"before" numbers): its ``geargen`` is imported instead of this one's.
"""

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--root", type=Path, default=HERE)
    args = parser.parse_args()
    sys.path.insert(0, str(args.root.resolve()))
    from geargen import pipeline
    from geargen.errors import GeargenError
    names = args.names or sorted(p.stem for p in (HERE / "assemblies").glob("*.toml"))
    print(f"overlap_check, {args.repeat} runs each, geargen from {args.root}; load average "
          f"{os.getloadavg()[0]:.2f} on {os.cpu_count()} cores at the start")
    for name in names:
        try:
            layout = pipeline.place(pipeline.load(HERE / "assemblies" / f"{name}.toml"))
            parts = pipeline.other_parts(layout, pipeline.gear_solids(layout))
        except GeargenError as exc:
            print(f"{name:24s} does not build: {str(exc)[:60]}")
            continue
        seconds, cpu = [], []
        for _ in range(args.repeat):
            for p in parts.parts:
                p._world = None
            start, cpu0 = time.perf_counter(), time.process_time()
            report = pipeline.overlap_check(parts, layout)
            seconds.append(time.perf_counter() - start)
            cpu.append(time.process_time() - cpu0)
        print(f"{name:24s} median {statistics.median(seconds):7.3f} s  best {min(seconds):7.3f} s  "
              f"cpu {statistics.median(cpu):7.3f} s  "
              f"parts {report.parts:3d}  pairs {report.pairs_checked:3d}  ok {report.ok}", flush=True)
    print(f"load average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
