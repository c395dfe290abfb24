"""Benchmark of the issue's two gears: build, STEP, STL times, file sizes, measured flank deviation.

    .venv/bin/python bench/bench_gear.py [--repeat N] [--out DIR]

Gears: a 112-tooth 32 DP spur gear (6.35 mm face, 10 mm bore) and a 21-tooth 32 DP helical
pinion (20 deg helix, 12.7 mm face). Times are the best of ``--repeat`` runs (median in
brackets) after one warm-up, wall clock, this process only; the kernel import is not counted.
The flank deviation is the largest distance of sectioned flank points from the exact involute
over sections at five heights (see geargen.cad.measure). ``default vol`` is OCCT's default
volume integration (``BRepGProp.VolumeProperties_s``, what other readers call) against the
exact volume (outline area x face width - bore), relative; ``poles`` the B-spline poles of
tooth 0's faces (profile x axial rows; cylinders have none). Re-tessellation of the STEP at
1 um against peers: bench/bench_step.py.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from geargen.design.gear import GearSpec, Hub  # noqa: E402

DP32 = 25.4 / 32
DEG = math.pi / 180

GEARS = {
    "spur 112T 32DP, 6.35 mm face, 10 mm bore": (
        GearSpec(teeth=112, module=DP32, pressure_angle=20 * DEG, face_width=6.35, hub=Hub(bore_diameter=10.0),
                 name="spur112", length_unit="in"),
        {"build": 0.4, "step": 0.4, "stl": 1.0, "flank_um": 0.01}),
    "helical 21T 32DP 20 deg, 12.7 mm face": (
        GearSpec(teeth=21, module=DP32, pressure_angle=20 * DEG, face_width=12.7, helix_angle=20 * DEG,
                 name="helical21", length_unit="in"),
        {"build": 0.25, "step": None, "stl": 1.0, "flank_um": 0.02}),
}


def timed(fn, repeat):
    fn()  # warm-up
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), statistics.median(times), out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--out", default=None, help="keep the files here (default: a temporary folder)")
    args = ap.parse_args(argv)

    t0 = time.perf_counter()
    from geargen.cad.export import export_step, export_stl
    from geargen.cad.gear_solid import build_gear, check_solid
    from geargen.cad.measure import flank_deviation
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    t_import = time.perf_counter() - t0
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="geargen-bench-"))
    out.mkdir(parents=True, exist_ok=True)

    rows = []
    for label, (spec, target) in GEARS.items():
        b_best, b_med, solid = timed(lambda: build_gear(spec), args.repeat)
        problem = check_solid(solid.shape)
        s_best, s_med, step = timed(lambda: export_step(solid, out / f"{spec.name}.step", spec.length_unit), args.repeat)
        l_best, l_med, stl = timed(lambda: export_stl(solid, out / f"{spec.name}.stl", 1e-3), args.repeat)
        heights = [f * spec.face_width for f in (0.02, 0.25, 0.5, 0.75, 0.98)]
        dev = max(flank_deviation(solid.shape, solid.profile, z).max_abs for z in heights) * 1e3
        exact = (solid.profile.area() - math.pi * spec.hub.bore_diameter ** 2 / 4) * spec.face_width
        props = GProp_GProps()
        BRepGProp.VolumeProperties_s(solid.shape, props)
        poles = ", ".join(f"{f.kind} {f.poles[0]}x{f.poles[1]}" if f.poles[0] else f"{f.kind} cylinder"
                          for f in solid.faces if f.side != "lower")
        rows.append((label, problem or "valid", (b_best, b_med, target["build"]), (s_best, s_med, target["step"]),
                     (l_best, l_med, target["stl"]), step.bytes, stl.bytes, stl.triangles, (dev, target["flank_um"]),
                     props.Mass() / exact - 1, poles))

    def t(v):
        best, med, tgt = v
        return f"{best:6.3f} ({med:.3f})" + (f" <= {tgt:g}" if tgt is not None else "")

    print(f"geargen bench (kernel import {t_import:.2f} s, not counted; best of {args.repeat}, median in brackets)")
    print(f"files in {out}")
    header = ("gear", "solid", "build s", "STEP s", "STL 1 um s", "STEP MB", "STL MB", "triangles", "flank dev um",
              "default vol", "poles (upper side, tip, root)")
    print(" | ".join(header))
    print(" | ".join("---" for _ in header))
    ok = True
    for label, valid, b, s, l, step_bytes, stl_bytes, tris, (dev, dev_t), vol_err, poles in rows:
        print(" | ".join([label, valid, t(b), t(s), t(l), f"{step_bytes / 1e6:.2f}", f"{stl_bytes / 1e6:.2f}",
                          str(tris), f"{dev:.5f} <= {dev_t:g}", f"{vol_err:+.1e} <= 1e-6", poles]))
        ok &= valid == "valid" and dev <= dev_t and abs(vol_err) <= 1e-6
        ok &= all(x[0] <= x[2] for x in (b, s, l) if x[2] is not None)
    print("all targets met" if ok else "SOME TARGETS MISSED (see above; timings depend on the machine's load)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
