"""Benchmark of racks: build, STEP, STL times, volume against the closed form, flank straightness.

    .venv/bin/python bench/bench_rack.py [--repeat N] [--out DIR]

Racks: a spur rack for a machine slide (module 2, 20 deg, 60 teeth = 377 mm, 20 mm face) and its
helical twin (20 deg helix, right hand), the latter with the generating tip rounding. Times are
the best of ``--repeat`` runs (median in brackets) after one warm-up, wall clock, this process
only; the kernel import is not counted. ``flank`` is the largest distance of sectioned flank
points from the exact flank line at mid-face (geargen.families.rack.solid.flank_straightness).

Peers: not measured here. The peers' venv of bench/peers (bd_warehouse, py_gearworks) was not
installed on the machine this was written on; a rack of a peer would be added to
bench/peers/make_peer_gear.py and timed the same way.
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

from geargen.families.rack.spec import RackSpec  # noqa: E402

DEG = math.pi / 180

RACKS = {
    "spur rack m2 60T, 20 mm face": RackSpec(teeth=60, module=2.0, pressure_angle=20 * DEG, face_width=20.0,
                                             pitch_line_height=20.0, name="rack_spur"),
    "helical rack m2 60T 20 deg RH, generating tips": RackSpec(
        teeth=60, module=2.0, pressure_angle=20 * DEG, face_width=20.0, pitch_line_height=20.0,
        helix_angle=20 * DEG, tip_rounding="generating", name="rack_helical"),
}


def timed(fn, repeat):
    fn()  # warm-up
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, min(times), statistics.median(times)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default=None)
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    from geargen.cad.export import export_step, export_stl
    from geargen.cad.gear_solid import check_solid, solid_volume
    from geargen.families.rack.solid import build_rack, flank_straightness
    from geargen.families.rack.geometry import rack_volume
    t_import = time.perf_counter() - t0
    out = Path(args.out or tempfile.mkdtemp(prefix="bench_rack_"))
    out.mkdir(parents=True, exist_ok=True)
    print(f"geargen rack bench (kernel import {t_import:.2f} s, not counted; best of {args.repeat}, median in brackets)")
    header = ["rack", "valid", "build s", "STEP s", "STL s", "volume rel. error", "flank um"]
    print(" | ".join(header))
    print(" | ".join("---" for _ in header))
    for label, spec in RACKS.items():
        rack, b, bm = timed(lambda: build_rack(spec), args.repeat)
        _, s, sm = timed(lambda: export_step(rack, out / f"{spec.name}.step"), args.repeat)
        _, l, lm = timed(lambda: export_stl(rack, out / f"{spec.name}.stl", 1e-3), args.repeat)
        vol = solid_volume(rack.shape) / rack_volume(spec) - 1
        flank, _ = flank_straightness(rack, 0.5 * spec.face_width)
        print(" | ".join([label, str(check_solid(rack.shape) is None), f"{b:.3f} ({bm:.3f})", f"{s:.3f} ({sm:.3f})",
                          f"{l:.3f} ({lm:.3f})", f"{vol:.1e}", f"{flank * 1e3:.1e}"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
