"""Time of the build's rendered view, step by step, for each assembly.

Run by hand: ``.venv/bin/python bench/bench_render.py [--repeat N] [--root DIR] [NAME ...]``. Each run
is a fresh interpreter that builds the parts (not timed), then times (processor time, the machine is
shared: compare trees with ``--root``, e.g. ``--root /work/main``, in alternated runs)

- ``render``: the build's render step (:func:`geargen.pipeline.render`: tessellation and the
  depth-buffer rasteriser, no matplotlib);
- ``figure``: the figure with its labels, scale bar and axis triad
  (:func:`geargen.report.view.view_figure`);
- ``save``: writing it as PNG and SVG (:func:`geargen.report.figures.save_figure`);
- ``layout``: the report's layout drawing (:func:`geargen.pipeline.layout_drawing`, without check
  results) and writing it as PNG and SVG;

with matplotlib imported before the clock starts (its import, ~0.3-1 s, is paid once by the
report step whatever it draws). Medians of N runs, best in brackets.

Measured (session 15, 2026-11-28 10:30 UTC, load 8-12 on 2 cores, ``--repeat 2`` twice, main and the
rendercpu branch alternated; processor s, medians): robot_joint render 0.505 / 0.563 -> 0.384 / 0.390,
figure 0.095 / 0.075 -> 0.071 / 0.071, save 0.208 / 0.175 -> 0.169 / 0.164, layout 0.202 / 0.174 ->
0.150 / 0.154; planetary_dual_pinion render 0.516 / 0.497 -> 0.543 / 0.493 (the tessellation dominates
and varies), layout 0.262 / 0.253 -> 0.212 / 0.205. Every PNG and SVG the same bytes (bench/diff_builds.py).
"""

import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ASSEMBLIES = ["robot_joint", "c_axis", "split_pinion"]

ONE_RUN = """
import sys, tempfile, time
import matplotlib.figure, matplotlib.backends.backend_agg  # noqa: F401  (imports outside the clock)
from geargen import pipeline as P
from geargen.report.figures import save_figure
from geargen.report.view import view_figure
design = P.load(sys.argv[1])
layout = P.place(design)
parts = P.other_parts(layout, P.gear_solids(layout), P.stiffness(layout))
t0 = time.process_time()
view = P.render(parts, design)
t1 = time.process_time()
fig = view_figure(view, design.length_unit)
t2 = time.process_time()
save_figure(fig, tempfile.mkdtemp(), "render")
t3 = time.process_time()
save_figure(P.layout_drawing(layout), tempfile.mkdtemp(), "layout")
t4 = time.process_time()
print(f"{t1 - t0:.3f} {t2 - t1:.3f} {t3 - t2:.3f} {t4 - t3:.3f}")
"""


def main(argv: list[str]) -> None:
    repeat, root = 3, ROOT
    while argv[:1] in (["--repeat"], ["--root"]):
        if argv[0] == "--repeat":
            repeat = int(argv[1])
        else:
            root = Path(argv[1]).resolve()
        argv = argv[2:]
    names = argv or ASSEMBLIES
    print(f"{root}: processor s, median [best] of {repeat}")
    print(f"{'assembly':<14}{'render':>16}{'figure':>16}{'save':>16}{'layout':>16}")
    for name in names:
        runs = []
        for _ in range(repeat):
            # run in root: the interpreter imports geargen from its working folder first
            done = subprocess.run([sys.executable, "-c", ONE_RUN, str(root / "assemblies" / f"{name}.toml")],
                                  capture_output=True, text=True, cwd=root, check=True)
            runs.append([float(v) for v in done.stdout.split()])
        cells = [f"{statistics.median(c):.3f} [{min(c):.3f}]" for c in zip(*runs)]
        print(f"{name:<14}" + "".join(f"{c:>16}" for c in cells))


if __name__ == "__main__":
    main(sys.argv[1:])
