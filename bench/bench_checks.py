"""Speed of the geometric mesh checks (run by hand: ``.venv/bin/python bench/bench_checks.py``).

Targets (issue 6):
- path 1: one pair swept over a full revolution at 0.1 deg steps in under 1 s;
- path 2: the section check of one mesh of the robot joint in under 5 s.

Path 2 is timed from the exported STL files (read, section at three planes, check over one
tooth cycle); building and exporting the solids is the build step's cost and is shown apart.
Each figure is the best of ``REPEATS`` runs (the machine may be shared).
"""

from __future__ import annotations

import math
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from geargen.checks.mesh2d import CheckSettings, Eccentricity, MeshSetup, polar_outline, sweep_mesh  # noqa: E402
from geargen.design.assembly import load_design  # noqa: E402

REPEATS = 3
warnings.simplefilter("ignore")


def best_of(fn, repeats=REPEATS):
    times, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main() -> int:
    design = load_design(ROOT / "assemblies" / "robot_joint.toml")
    rows = []
    positions = np.radians(np.arange(0.0, 360.0, 0.1))  # a full revolution of gear 1, 0.1 deg steps
    for label, g1, g2, c in (("16/48, C1 = 1.004 in", "input", "cluster_large", 1.004 * 25.4),
                             ("21/112, C2 = 2.078125 in", "cluster_small", "output", 2.078125 * 25.4)):
        a, b = design.gear(g1), design.gear(g2)
        polar_outline(a), polar_outline(b)  # outlines are built once per gear and cached
        ecc = MeshSetup.centred(a, b, c, label, eccentricity1=(Eccentricity(0.01, 0.3),),
                                eccentricity2=(Eccentricity(0.015, 1.1),))
        plain = MeshSetup.centred(a, b, c, label)
        for what, su in (("with eccentricities", ecc), ("ideal", plain)):
            t, sw = best_of(lambda su=su: sweep_mesh(su, positions, areas=False))
            rows.append(("path 1", f"{label}, {what}", f"{len(positions)} positions, 1 rev", t, 1.0,
                         f"j_n {sw.normal_backlash.min() * 1e3:.3f}..{sw.normal_backlash.max() * 1e3:.3f} um"))

    # path 2: one mesh of the robot joint, placed by the synthesis
    from geargen.checks.solids import check_mesh_sections, section_planes, sections_from_stl
    from geargen.checks.verdict import mesh_setup
    from geargen.model import resolve

    layout = resolve(design)
    su = mesh_setup(layout, next(m for m in layout.meshes if m.engaged))
    planes = section_planes(su, 3)
    chordal = 1e-3
    with tempfile.TemporaryDirectory() as tmp:
        from geargen.cad.export import export_stl
        from geargen.cad.gear_solid import build_gear

        t0 = time.perf_counter()
        spline = 0.0
        for g in (su.gear1, su.gear2):
            solid = build_gear(g)
            spline = max(spline, solid.tolerance)
            export_stl(solid, Path(tmp) / f"{g.name}.stl", chordal_tolerance=chordal)
        t_build = time.perf_counter() - t0
        rows.append(("build", f"{su.name}: build 2 solids + export STL", f"chordal {chordal} mm", t_build, None, ""))

        settings = CheckSettings(steps_per_tooth=24)
        pos = np.linspace(0.0, 2 * math.pi / su.gear1.teeth, 24, endpoint=False)

        def path2():
            s1 = sections_from_stl(su.gear1, Path(tmp) / f"{su.gear1.name}.stl", planes, chordal, spline)
            # gear 2 in its own face coordinates (the narrower gear stands off gear 1's faces)
            s2 = sections_from_stl(su.gear2, Path(tmp) / f"{su.gear2.name}.stl", planes - su.face_offset2, chordal,
                                   spline)
            return check_mesh_sections(su, s1, s2, settings, pos)

        t, c = best_of(path2)
        rows.append(("path 2", f"{su.name}: read STL, 3 sections, check", f"{len(pos)} positions x 3 planes", t, 5.0,
                     f"j_n {c.min_normal_backlash / 25.4:.6f} in (tol {c.tolerance * 1e3:.1f} um)"))

    from geargen.commands.check import check_design
    t, res = best_of(lambda: check_design(design, tolerances=False), 1)
    rows.append(("path 1", "robot joint: 4 meshes, full check", "1 tooth cycle each + contact ratio", t, None,
                 "ok" if res.ok else "failures"))
    t, res = best_of(lambda: check_design(design), 1)
    rows.append(("all", "robot joint: + worst case + Monte Carlo", "400 samples", t, None, "ok" if res.ok else "failures"))

    w = max(len(r[1]) for r in rows)
    print(f"{'path':<7} {'case':<{w}}  {'work':<36} {'seconds':>8} {'target':>7}  {'':<4} result")
    for path, case, work, t, target, note in rows:
        flag = "" if target is None else ("ok" if t < target else "SLOW")
        tgt = "" if target is None else f"< {target:g}"
        print(f"{path:<7} {case:<{w}}  {work:<36} {t:8.3f} {tgt:>7}  {flag:<4} {note}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
