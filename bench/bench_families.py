"""Build time per gear family: geargen beside the open-source peers that build the same case.

    PYTHONPATH=. .venv/bin/python bench/bench_families.py [--peers PYTHON] [--repeat N] [--out DIR]
        [--only CASE ...] [--table CASE=FILE.toml ...] [--timeout S]

``--peers``: the python of a venv made with

    python3.11 -m venv /tmp/geargen-peers && /tmp/geargen-peers/bin/pip install -r bench/peers/requirements.txt

never the project's own; without it only geargen is measured. Peer versions (pinned there):
bd_warehouse 0.4.0 (build123d 0.13.0 on cadquery-ocp-novtk 8.0.1.1), py_gearworks 0.0.24,
wormgear 0.0.8 (the last release for Python 3.11; 0.1+ needs 3.12). cq_gears (meadiode) is not on
PyPI, so it is not a peer here. Which peer builds what (their docs and source):

    family              bd_warehouse            py_gearworks                 wormgear
    external spur/hel.  SpurGear, HelicalGear   SpurGear, HelicalGear        -
    internal            -                       SpurRingGear, HelicalRingGear -
    rack                RackGear                InvoluteRack, HelicalRack    -
    double helical      -                       HelicalGear(herringbone)     -
                                                (no centre gap: gap-0 case only)
    straight bevel      -                       BevelGear                    -
    worm (ZA)           Worm                    -                            WormGeometry
    worm wheel          WormWheel (plain        -                            VirtualHobbingWheelGeometry
                        helical, not throated)                               (boolean hobbing, 36 steps)

The cases (:data:`CASES`; 20 deg pressure angle, addendum 1 m, dedendum 1.25 m throughout;
each peer gets the same numbers in bench/peers/make_peer_family.py; root fillets and rims are
each library's own):

    external spur       30T m2, face 20                external helical  the same, 15 deg RH
    internal spur       60T m1, face 10 (a ring)      internal helical  the same, 15 deg
    rack spur           m2, 30 teeth, face 20         rack helical      the same, 15 deg
    double helical      30T m2 25 deg, face 40, centre gap 6 (geargen only)
    herringbone         30T m2 25 deg, face 40, no gap
    bevel pinion/gear   straight, 15/30 teeth, 32 DP (outer), 90 deg shafts, face 4 mm
    worm                ZA, m3 (axial), 2 starts, q 11, length 70
    worm wheel          40T for that worm, face 24 (geargen allows at most 1.8 x the throat radius, 24.3)

Every build runs in a fresh process (geargen: this script with ``--worker``; a peer:
make_peer_family.py in the peers' venv), ``--repeat`` times (once when a build takes over
``--slow`` seconds); ``build s`` is the median of the runs (the kernel and library import is
measured apart: ``import s``, median too), ``STEP s`` the median STEP write. The geargen side
reads the case's design table with the family's reader (geargen.design.gear.gear_from_table, or
the reader a family registers in FAMILY_READERS) and builds it with
geargen.cad.families.build_part, so a family's row works as soon as it registers; until then the
row says "not in this geargen". ``--table CASE=FILE.toml`` replaces a case's table by FILE's
``[gear]`` table (a family whose keys differ from those guessed here).

The same checks for every STEP, in this process after the runs: the last run's file is read back
(geargen.cad.export.read_step) and checked by geargen.cad.gear_solid.check_solid (one solid,
BRepCheck valid, positive volume) and its volume integrated by solid_volume (Gauss-Kronrod,
relative 1e-7); ``vol/geargen`` is a peer's volume over geargen's for the same case (rims, root
fillets and wheel throats differ by design, so this is a sanity column, not a score).
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

HERE = Path(__file__).resolve().parent
PEER_SCRIPT = HERE / "peers" / "make_peer_family.py"


@dataclass(frozen=True)
class Case:
    name: str  # also the key of make_peer_family.PEERS
    table: dict  # geargen design table ([gear]); its "kind" names the family
    peers: tuple[str, ...] = ()
    note: str = ""  # said in the geargen row


_SPUR = {"teeth": 30, "module_mm": 2.0, "pressure_angle_deg": 20.0, "face_width_mm": 20.0}
_RING = {"kind": "internal", "teeth": 60, "module_mm": 1.0, "pressure_angle_deg": 20.0, "face_width_mm": 10.0}
_RACK = {"kind": "rack", "teeth": 30, "module_mm": 2.0, "pressure_angle_deg": 20.0, "face_width_mm": 20.0}
_DH = {"kind": "double_helical", "teeth": 30, "module_mm": 2.0, "pressure_angle_deg": 20.0, "helix_angle_deg": 25.0,
       "face_width_mm": 40.0}
_BEVEL = {"kind": "bevel", "diametral_pitch_per_in": 32.0, "pressure_angle_deg": 20.0, "shaft_angle_deg": 90.0,
          "face_width_mm": 4.0}
_WORM = {"module_mm": 3.0, "pressure_angle_deg": 20.0, "starts": 2, "wheel_teeth": 40, "diameter_quotient": 11.0,
         "worm_face_length_mm": 70.0, "wheel_face_width_mm": 24.0}  # one set: the worm and its wheel

CASES = [
    Case("external spur", dict(_SPUR), ("bd_warehouse", "py_gearworks")),
    Case("external helical", dict(_SPUR, helix_angle_deg=15.0), ("bd_warehouse", "py_gearworks")),
    Case("internal spur", dict(_RING), ("py_gearworks",)),
    Case("internal helical", dict(_RING, helix_angle_deg=15.0), ("py_gearworks",)),
    Case("rack spur", dict(_RACK), ("bd_warehouse", "py_gearworks")),
    Case("rack helical", dict(_RACK, helix_angle_deg=15.0), ("bd_warehouse", "py_gearworks")),
    Case("double helical", dict(_DH, centre_gap_mm=6.0), (), "no peer has a centre gap"),
    Case("herringbone", dict(_DH), ("py_gearworks",)),
    Case("bevel pinion", dict(_BEVEL, teeth=15, mate_teeth=30), ("py_gearworks",)),
    Case("bevel gear", dict(_BEVEL, teeth=30, mate_teeth=15), ("py_gearworks",)),
    Case("worm", dict(_WORM, kind="worm"), ("bd_warehouse", "wormgear")),
    Case("worm wheel", dict(_WORM, kind="worm_wheel"), ("bd_warehouse", "wormgear")),
]


# ---------------------------------------------------------------- geargen side


def registration_problem(table: dict) -> str | None:
    """Why this geargen cannot build ``table``'s kind (no builder or no table reader), or None."""
    from geargen.cad.families import BUILDERS
    from geargen.design.gear import CYLINDRICAL_KINDS, FAMILY_READERS
    kind = table.get("kind", "external")
    if kind not in BUILDERS or (kind not in CYLINDRICAL_KINDS and kind not in FAMILY_READERS):
        return "not in this geargen"
    return None


def read_spec(table: dict, name: str):
    """The family's spec from its design table, through the reader the kind registers."""
    import importlib
    from geargen.design.gear import FAMILY_READERS, gear_from_table
    kind = table.get("kind", "external")
    reader = gear_from_table
    if kind in FAMILY_READERS:
        module, function = FAMILY_READERS[kind].split(":")
        reader = getattr(importlib.import_module(module), function)
    return reader(table, where="gear", name=name.replace(" ", "_"))


def geargen_worker(table: dict, name: str, out: str) -> dict:
    """One fresh-process build of a case (see the module docstring); a JSON-able dict."""
    t0 = time.perf_counter()
    from geargen.cad.export import export_step
    from geargen.cad.families import build_part
    from geargen.cad.gear_solid import check_solid
    from geargen.errors import DesignError, GeometryError
    t_import = time.perf_counter() - t0
    try:
        t0 = time.perf_counter()
        spec = read_spec(table, name)
        t_read = time.perf_counter() - t0
        t0 = time.perf_counter()
        part = build_part(spec)
        t_build = time.perf_counter() - t0
    except (DesignError, GeometryError) as exc:  # the case's table or geometry refused: say so in the row
        return dict(refused=f"{type(exc).__name__}: {exc}")
    t0 = time.perf_counter()
    export_step(part, out, getattr(part, "length_unit", "mm"))
    t_step = time.perf_counter() - t0
    note = type(part).__name__
    if getattr(part, "flank_error", 0.0):  # the builder's own measure of its flanks (worm and wheel)
        note += f", flanks within {part.flank_error * 1e3:.3g} um of exact"
    return dict(import_s=t_import, read_s=t_read, build_s=t_build, step_s=t_step,
                check=check_solid(part.shape), note=note)


# ---------------------------------------------------------------- runs and checks


def run_json(cmd: list[str], timeout: float) -> dict:
    try:
        res = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return dict(failed=f"timeout after {timeout:g} s")
    lines = [ln for ln in res.stdout.strip().splitlines() if ln.startswith("{")]
    if res.returncode != 0 or not lines:
        tail = (res.stderr or res.stdout).strip().splitlines()[-1:] or ["no output"]
        return dict(failed=f"exit {res.returncode}: {tail[0][:120]}")
    return json.loads(lines[-1])


def repeated(cmd: list[str], repeat: int, timeout: float, slow: float) -> dict:
    """Medians over ``repeat`` fresh processes; a failure or refusal ends the series, and so does a
    build slower than ``slow`` seconds (one such run says enough)."""
    runs = []
    for _ in range(repeat):
        r = run_json(cmd, timeout)
        if "failed" in r or "refused" in r:
            return r
        runs.append(r)
        if r["build_s"] > slow:
            break
    out = dict(runs[-1])
    for key in ("import_s", "build_s", "step_s"):
        out[key] = statistics.median(r[key] for r in runs)
    out["runs"] = len(runs)
    return out


def step_check(path: Path) -> tuple[str, float | None]:
    """(validity, volume mm3) of a STEP read back, the same for geargen and the peers."""
    from geargen.cad.export import read_step
    from geargen.cad.gear_solid import check_solid, solid_volume
    shape = read_step(path).shape
    problem = check_solid(shape)
    try:
        volume = solid_volume(shape, 1e-7)
    except Exception:  # a shape OCCT cannot integrate: the row says so
        volume = None
    return ("valid" if problem is None else problem), volume


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--peers", default=None, help="python of the peers' venv (bench/peers/requirements.txt)")
    ap.add_argument("--repeat", type=int, default=3, help="fresh processes per build (median)")
    ap.add_argument("--out", default=None, help="keep the STEP files here (default: a temporary folder)")
    ap.add_argument("--only", nargs="*", default=None, help="case names to run (default: all)")
    ap.add_argument("--table", action="append", default=[], metavar="CASE=FILE.toml",
                    help="take CASE's geargen table from FILE's [gear] table")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds per build process")
    ap.add_argument("--slow", type=float, default=60.0, help="a build slower than this (s) is not repeated")
    ap.add_argument("--worker", nargs=2, default=None, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        case, out = args.worker
        print(json.dumps(geargen_worker(json.loads(case), "bench", out)))
        return 0

    tables = {c.name: c.table for c in CASES}
    for item in args.table:
        case, _, path = item.partition("=")
        if case not in tables:
            ap.error(f"--table: no case {case!r} (one of {', '.join(tables)})")
        from geargen.design.schema import load_toml
        tables[case] = load_toml(path)["gear"]
    cases = [c for c in CASES if args.only is None or c.name in args.only]
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="geargen-families-"))
    out.mkdir(parents=True, exist_ok=True)

    rows = []
    for case in cases:
        slug = case.name.replace(" ", "_")
        table = tables[case.name]
        problem = registration_problem(table)
        results = {}
        if problem:
            results["geargen"] = dict(failed=problem)
        else:
            target = out / f"{slug}-geargen.step"
            results["geargen"] = dict(repeated([sys.executable, __file__, "--worker", json.dumps(table), str(target)],
                                               args.repeat, args.timeout, args.slow), path=target)
        for peer in case.peers if args.peers else ():
            target = out / f"{slug}-{peer}.step"
            results[peer] = dict(repeated([args.peers, str(PEER_SCRIPT), case.name, peer, str(target)], args.repeat,
                                          args.timeout, args.slow), path=target)
        for source, r in results.items():
            if "failed" not in r and "refused" not in r:
                r["valid"], r["volume"] = step_check(r["path"])
                r["kb"] = r["path"].stat().st_size / 1e3
            rows.append((case, source, r))
            print(f"{case.name} / {source}: {({k: v for k, v in r.items() if k != 'path'})}", file=sys.stderr)

    print(f"\nBuild times, fresh process each, median of {args.repeat}; STEP files in {out}")
    header = ("case", "source", "import s", "build s", "STEP s", "STEP kB", "STEP read back", "volume mm3",
              "vol/geargen", "what was built")
    print(" | ".join(header))
    print(" | ".join("---" for _ in header))
    geargen_volume = {case.name: r.get("volume") for case, source, r in rows if source == "geargen"}
    for case, source, r in rows:
        if "failed" in r or "refused" in r:
            print(" | ".join([case.name, source, "", "", "", "", "", "", "", r.get("failed") or r["refused"]]))
            continue
        ref = geargen_volume.get(case.name)
        ratio = f"{r['volume'] / ref:.4f}" if source != "geargen" and ref and r["volume"] else ""
        note = r["note"] + (f"; in memory: {r['check']}" if source == "geargen" and r.get("check") else "")
        if source == "geargen" and case.note:
            note += f"; {case.note}"
        if r.get("runs", args.repeat) < args.repeat:
            note += f" ({r['runs']} runs)"
        print(" | ".join([case.name, source, f"{r['import_s']:.2f}", f"{r['build_s']:.3f}", f"{r['step_s']:.3f}",
                          f"{r['kb']:.0f}", r["valid"], f"{r['volume']:.1f}" if r["volume"] else "n/a", ratio, note]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
