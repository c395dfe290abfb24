"""STEP that a CAM station opens fast: geargen against open-source peers, side by side.

    .venv/bin/python bench/bench_step.py [--peers PYTHON] [--before DIR] [--repeat N] [--out DIR]

The gear of issue 13: 21 teeth, module 25.4/32 mm, 20 deg pressure angle, 20 deg right-hand
helix, 12.7 mm face, no bore. geargen writes it here; each peer writes it in its own venv
(``--peers``: the python of a venv made with

    python3.11 -m venv /tmp/geargen-peers && /tmp/geargen-peers/bin/pip install -r bench/peers/requirements.txt

never the project's own; without ``--peers`` only geargen is measured). ``--before DIR``
adds STEP files written by an older geargen (``helical21.step`` and ``spur112.step`` of
``bench/bench_gear.py --out DIR`` run on the commit before) as extra rows; the 112-tooth spur
gear of bench_gear.py gets rows of its own (geargen only).

Every STEP is then read and re-tessellated by the same kind of process: a fresh interpreter of
this project's python (OCCT 7.9 from cadquery-ocp), ``STEPControl_Reader`` then
``BRepMesh_IncrementalMesh(shape, 0.001 mm, relative=False, angular=ANGLE rad, parallel=False)``
- 1 um, what a CAM station asks for finishing; ``--angle`` default 0.5 rad, OCCT's own default.
Times are the best (and the median) of ``--repeat`` fresh processes (each pays the kernel import, not
counted).
The flank deviation is measured on the STEP read back: transverse sections at five heights
(geargen.cad.measure.section), points on the involute band (radius between the involute start +
0.1 m and the tip - 0.05 m of geargen's profile) compared with the exact involute helicoid;
a peer's tooth may sit at another phase or thickness, so per section and flank side the mean
offset is removed and reported apart (``thickness um``, + = thicker than geargen's zero-backlash
tooth) and the column shows the form deviation that remains.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

HERE = Path(__file__).resolve().parent
DP32 = 25.4 / 32
DEG = math.pi / 180
TEETH, MODULE, PRESSURE_DEG, HELIX_DEG, FACE = 21, DP32, 20.0, 20.0, 12.7


def spec():
    from geargen.design.gear import GearSpec
    return GearSpec(teeth=TEETH, module=MODULE, pressure_angle=PRESSURE_DEG * DEG, face_width=FACE,
                    helix_angle=HELIX_DEG * DEG, name="helical21")


def measure_worker(path: str, deflection: float, angle: float) -> dict:
    """Read ``path`` and tessellate it (runs in a fresh process, see the module docstring)."""
    t0 = time.perf_counter()
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.BRep import BRep_Tool
    from OCP.TopLoc import TopLoc_Location
    from OCP.TopoDS import TopoDS
    t_import = time.perf_counter() - t0
    t0 = time.perf_counter()
    reader = STEPControl_Reader()
    if reader.ReadFile(path) != IFSelect_RetDone:
        raise SystemExit(f"cannot read {path}")
    reader.TransferRoots()
    shape = reader.OneShape()
    t_read = time.perf_counter() - t0
    t0 = time.perf_counter()
    BRepMesh_IncrementalMesh(shape, deflection, False, angle, False)
    t_mesh = time.perf_counter() - t0
    triangles = faces = 0
    kinds = {}  # surface kind -> [faces, triangles, smallest radius of curvature mm]
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        face = TopoDS.Face_s(exp.Current())
        tri = BRep_Tool.Triangulation_s(face, TopLoc_Location())
        faces += 1
        count = tri.NbTriangles() if tri is not None else 0
        triangles += count
        kind, radius = face_kind(face)
        row = kinds.setdefault(kind, [0, 0, radius])
        row[0], row[1], row[2] = row[0] + 1, row[1] + count, min(row[2], radius)
        exp.Next()
    return dict(import_s=t_import, read_s=t_read, mesh_s=t_mesh, triangles=triangles, faces=faces, kinds=kinds)


def face_kind(face) -> tuple[str, float]:
    """(surface type with its pole grid and degrees, smallest radius of curvature (mm) on 21
    points across the face at mid-height): what sets OCCT's triangle count at a fixed deflection
    (its Delaunay refinement makes triangles about as wide as they are long, so their size follows
    the largest curvature)."""
    import numpy as np
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepLProp import BRepLProp_SLProps
    ad = BRepAdaptor_Surface(face)
    kind = str(ad.GetType()).rsplit(".", 1)[-1].replace("GeomAbs_", "")
    if kind == "BSplineSurface":
        kind += f" {ad.NbUPoles()}x{ad.NbVPoles()} deg {ad.UDegree()},{ad.VDegree()}"
    curvature = 0.0
    v = 0.5 * (ad.FirstVParameter() + ad.LastVParameter())
    for u in np.linspace(ad.FirstUParameter(), ad.LastUParameter(), 21):
        props = BRepLProp_SLProps(ad, float(u), v, 2, 1e-9)
        if props.IsCurvatureDefined():
            curvature = max(curvature, abs(props.MaxCurvature()), abs(props.MinCurvature()))
    return kind, (1.0 / curvature if curvature > 0 else math.inf)


def measure(path: Path, deflection: float, angle: float, repeat: int) -> dict:
    runs = []
    for _ in range(repeat):
        out = subprocess.run([sys.executable, __file__, "--worker", str(path), "--deflection", str(deflection),
                              "--angle", str(angle)], capture_output=True, text=True, check=True)
        runs.append(json.loads(out.stdout.strip().splitlines()[-1]))
    best = {key: min(r[key] for r in runs) for key in ("read_s", "mesh_s")}
    return dict(runs[0], **best, mesh_median_s=statistics.median(r["mesh_s"] for r in runs))


def flank_form(path: Path) -> tuple[float, float]:
    """(form deviation um, mean thickness offset um) of the STEP's flanks (module docstring;
    bench_families.gear_flank_form)."""
    import numpy as np
    from bench_families import gear_flank_form
    from geargen.cad.export import read_step
    from geargen.profile.tooth import tooth_profile
    return gear_flank_form(read_step(path).shape, tooth_profile(spec()), np.linspace(0.05, 0.95, 5) * FACE)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--peers", default=None, help="python of the peers' venv (bench/peers/requirements.txt)")
    ap.add_argument("--before", default=None, help="folder with helical21.step written by an older geargen")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--deflection", type=float, default=1e-3)
    ap.add_argument("--angle", type=float, default=0.5)
    ap.add_argument("--out", default=None)
    ap.add_argument("--worker", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        print(json.dumps(measure_worker(args.worker, args.deflection, args.angle)))
        return 0

    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="geargen-step-"))
    out.mkdir(parents=True, exist_ok=True)
    from geargen.cad.export import export_step
    from geargen.cad.gear_solid import build_gear
    files = {}
    solid = build_gear(spec())
    export_step(solid, out / "geargen.step", "mm")
    files["geargen"] = out / "geargen.step"
    if args.before:
        files["geargen before"] = Path(args.before) / "helical21.step"
    # the 112-tooth spur gear of bench_gear.py too (geargen only; no flank column: another gear)
    from geargen.design.gear import GearSpec, Hub
    spur = GearSpec(teeth=112, module=MODULE, pressure_angle=PRESSURE_DEG * DEG, face_width=6.35,
                    hub=Hub(bore_diameter=10.0), name="spur112", length_unit="in")
    export_step(build_gear(spur), out / "geargen-spur112.step", "in")
    extra = {"geargen spur 112T": out / "geargen-spur112.step"}
    if args.before:
        extra["geargen before spur 112T"] = Path(args.before) / "spur112.step"
    if args.peers:
        for peer in ("bd_warehouse", "py_gearworks"):
            target = out / f"{peer}.step"
            res = subprocess.run([args.peers, str(HERE / "peers" / "make_peer_gear.py"), peer, str(target)],
                                 capture_output=True, text=True)
            if res.returncode != 0 or not target.exists():
                files[peer] = None
                print(f"{peer}: could not build the gear: {(res.stderr or res.stdout).strip().splitlines()[-1:]}")
            else:
                files[peer] = target
                print(f"{peer}: {res.stdout.strip()}")

    print(f"\nSTEP re-tessellation at {args.deflection * 1e3:g} um, angular {args.angle:g} rad "
          f"(best of {args.repeat} fresh processes); files in {out}")
    header = ("source", "STEP MB", "faces", "read s", "mesh s", "mesh s median", "triangles", "flank form um",
              "thickness um")
    kinds = {}
    print(" | ".join(header))
    print(" | ".join("---" for _ in header))
    for name, path in files.items():
        if path is None:
            print(" | ".join([name] + ["cannot build"] + [""] * (len(header) - 2)))
            continue
        m = measure(path, args.deflection, args.angle, args.repeat)
        try:
            form, thick = flank_form(path)
            dev = (f"{form:.4f}", f"{thick:+.2f}")
        except Exception as exc:  # a peer's surface the section cannot follow: say so, keep the row
            dev = (f"n/a ({type(exc).__name__})", "")
        print(" | ".join([name, f"{path.stat().st_size / 1e6:.2f}", str(m["faces"]), f"{m['read_s']:.3f}",
                          f"{m['mesh_s']:.3f}", f"{m['mesh_median_s']:.3f}", str(m["triangles"]), *dev]))
        kinds[name] = m["kinds"]
    for name, path in extra.items():
        m = measure(path, args.deflection, args.angle, args.repeat)
        print(" | ".join([name, f"{path.stat().st_size / 1e6:.2f}", str(m["faces"]), f"{m['read_s']:.3f}",
                          f"{m['mesh_s']:.3f}", f"{m['mesh_median_s']:.3f}", str(m["triangles"]), "", ""]))
    print("\nTriangles by face kind (the 21 T gear; smallest radius of curvature across the face)")
    header = ("source", "surface", "faces", "triangles", "per face", "radius mm")
    print(" | ".join(header))
    print(" | ".join("---" for _ in header))
    for name, rows in kinds.items():
        for kind, (count, tris, radius) in sorted(rows.items(), key=lambda kv: -kv[1][1]):
            print(" | ".join([name, kind, str(count), str(tris), str(round(tris / count)), f"{radius:.3g}"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
