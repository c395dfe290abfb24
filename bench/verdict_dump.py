"""The build's mesh-check outcome of shipped designs, written whole, to show that a change meant to
save CPU moves no number (run by hand).

``python bench/verdict_dump.py dump FOLDER [NAME ...]``: ``pipeline.mesh_checks(layout, gear solids)``
of each design (default: every file in assemblies/) walked into plain values (dataclasses, dicts,
lists, numpy arrays, numbers, strings) and pickled to FOLDER/NAME.pkl, with its CPU seconds.

``python bench/verdict_dump.py compare BEFORE AFTER``: every pair of values that differs, numbers
beyond ``--abs`` (mm, default 1e-9) and ``--rel`` (default 1e-12) both; exit 1 on any difference.

``--root DIR``: run another checkout's geargen and its assemblies (e.g. main's, for BEFORE).

Issue 28 (meshfast branch), on this 2-core machine shared with other jobs (load average 9-15), median
of 3 fresh processes, mesh_checks CPU seconds, main (1ac074a) -> meshfast: robot joint 3.77 -> 2.51,
C-axis 5.11 -> 3.46, metric dual pinion 4.42 -> 2.87, planetary dual pinion 6.46 -> 4.12 (each
includes ~0.2 s compiling the check modules: PYTHONDONTWRITEBYTECODE is set here). The outcome of
every buildable shipped design compared with main's: zero differences, bit for bit (--abs 0 --rel 0).

Issue 28 (verdictcpu branch, 2026-11-28 10:36-10:38 UTC, load average 6-8 on the 2 cores), the verdict
process's work, ``pipeline.design_verdict`` CPU seconds (process_time, 2nd and 3rd call in one process,
main (fd19f92, the branch's base) and the branch alternated twice): planetary_dual_pinion 2.62-2.92 -> 2.33-2.43, robot_joint
1.72-1.82 -> 1.58-1.65, c_axis 2.37-2.54 -> 2.33-2.41, metric_dual_pinion 1.50-1.60 -> 1.50-1.54. Its
parts measured apart, alternated: rate_drive (planetary / c_axis / robot) 0.16 / 0.075 / 0.081 ->
0.095 / 0.046 / 0.048 (ISO 1328 values and root forms kept by their exact inputs); planetary_meshes
0.54 -> 0.38 (the planet's outline sampled once, placed_ring_play's bisection on the reaching points);
robot joint bevel rows 0.153 -> 0.075 (gear 1's points read only when gear 2's do not already penetrate);
planetary parts_check polygon distances 0.55-0.69 -> 0.31-0.44 (the section grid over the tooth band);
parts_check robot / c_axis 0.51-0.55 / 0.99-1.06 -> 0.49-0.50 / 0.92-0.94 (bodies read column by column).
``bench/bench_build.py --stages --repeat 3 c_axis planetary_dual_pinion robot_joint`` with and without
``--root /work/main``, twice (10:40-10:53, load 1.5-8 and changing within a run): cpu column main /
branch c_axis 8.60 / 9.33 and 8.60 / 9.33, planetary 12.26 / 11.73 and 11.76 / 11.85, robot joint
9.21 / 8.65 and 8.54 / 9.51: no comparison (the other jobs' load moved each figure by more than the
0.05-0.3 s saved, and main took the exportcpu and partscpu merges while it ran).
The outcome of the 8 buildable shipped designs against main's: zero differences (--abs 0 --rel 0).

Issue 28 (verdictcpu4 branch, 2026-11-28 14:49-14:51 UTC, load average 5-7 on the 2 cores), ``pipeline.design_verdict``
CPU seconds (process_time, first call in a fresh process, main a4a21a5 and the branch alternated x3): robot_joint
1.375-1.466 -> 1.301-1.396, c_axis 1.796-1.888 -> 1.728-1.853, planetary_dual_pinion 1.851-1.889 -> 1.756-1.833,
metric_dual_pinion 1.353-1.403 -> 1.293-1.317 (rate_mesh and the face width searches kept by their exact inputs,
square frames' local coordinates as one sum, the backlash-only sweeps without the tip clearance). The 8 buildable
designs against main's: zero differences (--abs 0 --rel 0).
"""

from __future__ import annotations

import dataclasses
import math
import pickle
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if "--root" in sys.argv:  # another checkout's geargen (main's, for the "before" of a comparison)
    _i = sys.argv.index("--root")
    ROOT = Path(sys.argv[_i + 1]).resolve()
    del sys.argv[_i:_i + 2]
sys.path.insert(0, str(ROOT))


def plain(v, depth=0):
    """``v`` as nested dicts, lists, numbers, strings and arrays (objects by their fields)."""
    if depth > 40:
        return repr(v)
    if v is None or isinstance(v, (bool, int, float, str, complex)):
        return v
    if isinstance(v, (np.floating, np.integer, np.bool_)):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.copy() if v.dtype != object else [plain(x, depth + 1) for x in v.ravel()]
    if isinstance(v, dict):
        return {str(k): plain(x, depth + 1) for k, x in v.items()}
    if isinstance(v, (list, tuple, set, frozenset)):
        items = sorted(v, key=repr) if isinstance(v, (set, frozenset)) else v
        return [plain(x, depth + 1) for x in items]
    if dataclasses.is_dataclass(v):
        return {"<type>": type(v).__name__,
                **{f.name: plain(getattr(v, f.name), depth + 1) for f in dataclasses.fields(v)}}
    if hasattr(v, "__dict__"):
        return {"<type>": type(v).__name__, **{k: plain(x, depth + 1) for k, x in vars(v).items()
                                                if not k.startswith("_")}}
    return repr(v)


def differences(a, b, where, abs_tol, rel_tol):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                yield f"{where}/{k}: only in {'after' if k in b else 'before'}"
            else:
                yield from differences(a[k], b[k], f"{where}/{k}", abs_tol, rel_tol)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            yield f"{where}: length {len(a)} != {len(b)}"
        else:
            for i, (x, y) in enumerate(zip(a, b)):
                yield from differences(x, y, f"{where}[{i}]", abs_tol, rel_tol)
    elif isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.shape != b.shape:
            yield f"{where}: shape {a.shape} != {b.shape}"
        elif a.dtype.kind in "fc" or b.dtype.kind in "fc":
            d = np.abs(a - b)
            bad = ~((d <= abs_tol) | (d <= rel_tol * np.maximum(np.abs(a), np.abs(b)))
                    | (np.isnan(a) & np.isnan(b)) | (a == b))
            if np.any(bad):
                i = np.flatnonzero(bad.ravel())[0]
                yield f"{where}: {int(bad.sum())} entries differ, first {a.ravel()[i]!r} != {b.ravel()[i]!r}"
        elif not np.array_equal(a, b):
            yield f"{where}: arrays differ"
    elif isinstance(a, float) and isinstance(b, float):
        if not (a == b or (math.isnan(a) and math.isnan(b)) or abs(a - b) <= abs_tol
                or abs(a - b) <= rel_tol * max(abs(a), abs(b))):
            yield f"{where}: {a!r} != {b!r}"
    elif a != b:
        yield f"{where}: {a!r} != {b!r}"


def dump(folder: Path, names: list[str]) -> None:
    from geargen import pipeline
    from geargen.errors import GeargenError
    folder.mkdir(parents=True, exist_ok=True)
    for name in names or sorted(p.stem for p in (ROOT / "assemblies").glob("*.toml")):
        d = pipeline.load(ROOT / "assemblies" / f"{name}.toml")
        try:
            lay = pipeline.place(d)
        except GeargenError as exc:  # not a buildable assembly (a drive study's input)
            print(f"{name}: skipped, {exc}")
            continue
        g = pipeline.gear_solids(lay)
        t0 = time.process_time()
        out = pipeline.mesh_checks(lay, g)
        cpu = time.process_time() - t0
        (folder / f"{name}.pkl").write_bytes(pickle.dumps(plain(out)))
        print(f"{name}: mesh_checks {cpu:.2f} s CPU", flush=True)


def compare(before: Path, after: Path, abs_tol: float, rel_tol: float) -> int:
    bad = 0
    for p in sorted(before.glob("*.pkl")):
        q = after / p.name
        if not q.exists():
            print(f"{p.stem}: missing in {after}")
            bad += 1
            continue
        diffs = list(differences(pickle.loads(p.read_bytes()), pickle.loads(q.read_bytes()), "", abs_tol, rel_tol))
        print(f"{p.stem}: {len(diffs)} differences")
        for line in diffs[:20]:
            print("   ", line)
        bad += len(diffs)
    return 1 if bad else 0


if __name__ == "__main__":
    args = sys.argv[1:]
    opts = {"--abs": 1e-9, "--rel": 1e-12}
    for key in list(opts):
        if key in args:
            i = args.index(key)
            opts[key] = float(args[i + 1])
            del args[i:i + 2]
    if args[0] == "dump":
        dump(Path(args[1]), args[2:])
    else:
        sys.exit(compare(Path(args[1]), Path(args[2]), opts["--abs"], opts["--rel"]))
