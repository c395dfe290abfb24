"""Build times of double-helical (herringbone) gears, and the fuse the face-by-face build replaced.

    .venv/bin/python bench/bench_double_helical.py [--repeat N] [--fuse]

Gears: 19 teeth, m 1 mm, 30 deg helix, 14 mm face: a herringbone (no gap, flanks meeting at the apex)
and one with a 3 mm relief groove, each with a 6 mm bore. Times are the best of ``--repeat`` builds
after one warm-up, wall clock, this process. The builder puts both halves together face by face
(geargen.cad.gear_solid.toothed_body with ``mirror``); ``--fuse`` also times what it did before:
the first half built alone, mirrored and fused to it with the kernel's glue option (``full``: the
faces coincide whole), for the record. No open-source peer with exact herringbone flanks was
benchmarked here (py_gearworks' herringbone=True writes a straight extrusion: bench_families.py).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from geargen.design.gear import Hub  # noqa: E402
from geargen.families.double_helical.spec import DoubleHelicalGearSpec  # noqa: E402

DEG = math.pi / 180


def spec(gap: float) -> DoubleHelicalGearSpec:
    return DoubleHelicalGearSpec(teeth=19, module=1.0, pressure_angle=20 * DEG, face_width=14.0,
                                 helix_angle=30 * DEG, centre_gap=gap, hub=Hub(6.0), name=f"dh_gap{gap:g}")


def best(fn, repeat: int) -> float:
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--fuse", action="store_true", help="also time the halves fused with the glue option")
    args = ap.parse_args()
    from geargen.families.double_helical.solid import build_double_helical
    from geargen.cad.gear_solid import check_solid
    for gap in (0.0, 3.0):
        s = spec(gap)
        t = best(lambda: build_double_helical(s), args.repeat)
        g = build_double_helical(s)
        print(f"{s.name:10s} build {t:6.3f} s  valid={check_solid(g.shape) is None}")
    if args.fuse:
        from OCP.BOPAlgo import BOPAlgo_GlueFull
        from OCP.BRepAlgoAPI import BRepAlgoAPI_Fuse
        from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Trsf
        from OCP.TopTools import TopTools_ListOfShape

        from geargen.families.double_helical.solid import half_spec
        from geargen.cad.gear_solid import toothed_body, _transform
        from geargen.profile.tooth import tooth_profile
        half = half_spec(spec(0.0))
        lower, _ = toothed_body(half, tooth_profile(half), 2e-6)
        mirror = gp_Trsf()
        mirror.SetMirror(gp_Ax2(gp_Pnt(0, 0, 7.0), gp_Dir(0, 0, 1)))
        t0 = time.perf_counter()
        op = BRepAlgoAPI_Fuse()
        args_, tools = TopTools_ListOfShape(), TopTools_ListOfShape()
        args_.Append(lower)
        tools.Append(_transform(lower, mirror))
        op.SetArguments(args_)
        op.SetTools(tools)
        op.SetGlue(BOPAlgo_GlueFull)
        op.Build()
        print(f"glued fuse of the halves: {time.perf_counter() - t0:.2f} s (valid={check_solid(op.Shape()) is None})")


if __name__ == "__main__":
    main()
