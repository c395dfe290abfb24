"""Processor time of the build's drawings step (:func:`geargen.pipeline.drawings`) per shipped design.

Run by hand: ``PYTHONPATH=$PWD .venv/bin/python bench/bench_drawings.py [--repeat N] [--root DIR] [NAME ...]``
(default names: robot_joint, c_axis, metric_dual_pinion). Each measurement is a fresh interpreter
that first does what the build's parent process does before it forks the drawings' process (imports
geargen.cad.export with the CAD kernel, and matplotlib's figure modules when the checkout still
has ``pipeline._import_figure_modules``), resolves the design, then times the first call of
``drawings(layout, folder)`` in process time (user + system of this process): the step's work as
the build's drawings process does it, first-use costs (fonts, DXF writer) included, and little
moved by other load on the machine, unlike its wall time. ``--root`` measures another checkout
(e.g. main's, for the "before" numbers). Median of N (default 3).

Target (issue 28): the robot joint's drawings step <= 0.6 s.

Measured 2026-11-28 10:17 UTC (session 15, load 7-14, alternated runs, medians of 3), main b589202 ->
branch drawcpu: robot_joint 0.53-0.55 -> 0.15-0.17, metric_dual_pinion 0.79-0.81 -> 0.25-0.28,
planetary_dual_pinion 0.73-0.74 -> 0.21-0.24, c_axis 0.53-0.56 -> 0.16, axial_preload 0.45-0.50 ->
0.13-0.14: the profile DXF written without ezdxf (geargen.report.dxf, its frame from ezdxf), the font
read without fontTools (geargen.report.truetype), each tooth's outline points computed once for all
teeth (profile.segments.sample_outline), the label placer counting a ring of candidates at once.
"""

import argparse
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

ONE = r"""
import sys, tempfile, time
from pathlib import Path
from geargen import pipeline
import geargen.cad.export  # noqa: F401 - imported by the build's parent before it forks
if hasattr(pipeline, "_import_figure_modules"):
    pipeline._import_figure_modules()
layout = pipeline.place(pipeline.load(sys.argv[1]))
with tempfile.TemporaryDirectory() as folder:
    t = time.process_time()
    pipeline.drawings(layout, Path(folder))
    print(time.process_time() - t)
"""


def measure(root: Path, name: str) -> float:
    done = subprocess.run([sys.executable, "-c", ONE, str(root / "assemblies" / f"{name}.toml")], cwd=root,
                          env={"PYTHONPATH": str(root), "PATH": "/usr/bin:/bin"}, capture_output=True, text=True,
                          check=True)
    return float(done.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", default=["robot_joint", "c_axis", "metric_dual_pinion"])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--root", type=Path, default=ROOT)
    args = parser.parse_args()
    with open("/proc/loadavg") as f:
        load = f.read().split()[0]
    print(f"{args.root}: drawings step, process time (s), median of {args.repeat}; load average {load}")
    for name in args.names:
        runs = [measure(args.root.resolve(), name) for _ in range(args.repeat)]
        print(f"{name:24s} {statistics.median(runs):6.3f}  (runs {', '.join(f'{r:.3f}' for r in runs)})")


if __name__ == "__main__":
    main()
