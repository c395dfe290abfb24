"""Processor time of meshing the robot joint's two bevel gears: the kernel's mesher against the
exact one (:func:`geargen.profile.bevel_tessellate.bevel_triangles`, what
:func:`geargen.cad.export.solid_triangles` now uses for a ``BevelSolid``).

Run by hand: ``.venv/bin/python bench/bench_bevel_mesh.py [--repeat N]``. One interpreter builds
the two solids as the build does (their specs and backs from ``assemblies/robot_joint.toml``), then
for each tolerance (the gears' STL 0.005 mm; the other parts' 0.05 mm, which the build's bevel STLs
use; the rendered view's ~0.45 mm) times, alternated N times, the kernel (:func:`geargen.cad.export.kernel_triangles` on the solid's shape, its earlier mesh
removed first so each run meshes afresh; the STL's angular tolerance 30 deg) and the exact mesher.
Prints medians (processor ms) and triangle counts.

Measured (session 17, 2026-11-28 14:40 UTC, load ~3 on 2 cores, --repeat 7), kernel -> exact, ms
(triangles): bevel_gear 0.005 mm 102.7 (11488) -> 1.9 (3986), 0.05 mm 30.2 (1932) -> 1.1 (974),
0.45 mm 26.9 (1480) -> 1.0 (536); bevel_pinion 0.005 mm 134.1 (15582) -> 2.0 (2708), 0.05 mm 22.4
(1586) -> 1.1 (516), 0.45 mm 19.3 (1190) -> 0.8 (360). The exact mesh holds fewer triangles: it
has no angular limit (as the gears' and the worm's exact meshes), only the chordal tolerance.
"""

import math
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main(argv: list[str]) -> None:
    repeat = int(argv[argv.index("--repeat") + 1]) if "--repeat" in argv else 5
    from OCP.BRepTools import BRepTools

    from geargen.cad.export import kernel_triangles, solid_triangles
    from geargen.design.assembly import load_design
    from geargen.drives.dual_pinion.bevel import bevel_drive
    from geargen.drives.resolver import resolve
    from geargen.families.bevel.solid import build_bevel

    placed = bevel_drive(resolve(load_design(ROOT / "assemblies/robot_joint.toml")))
    solids = [build_bevel(spec, back=spec.back) for spec in (placed.gear, placed.pinion)]
    print("solid           tol mm   kernel ms (tri)     exact ms (tri)   speed-up")
    for solid in solids:
        for tol in (0.005, 0.05, 0.45):  # the gears' STL tolerance, the parts' (the bevels' in the build), the view's
            times = {"kernel": [], "exact": []}
            counts = {}
            for _ in range(repeat):
                BRepTools.Clean_s(solid.shape)
                t0 = time.process_time()
                tri = kernel_triangles(solid.shape, tol, math.radians(30))
                times["kernel"].append(time.process_time() - t0)
                counts["kernel"] = len(tri)
                t0 = time.process_time()
                tri, mesher = solid_triangles(solid, tol)
                times["exact"].append(time.process_time() - t0)
                counts["exact"] = len(tri)
                assert mesher == "exact"
            k, e = (1000 * statistics.median(times[m]) for m in ("kernel", "exact"))
            print(f"{solid.name:14s} {tol:6.3f}  {k:8.1f} ({counts['kernel']:6d})  {e:8.1f} ({counts['exact']:6d})"
                  f"   {k / e:6.1f}x")


if __name__ == "__main__":
    main(sys.argv[1:])
