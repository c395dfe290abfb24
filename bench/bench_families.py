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
``--slow`` seconds); ``build s`` is the median of the runs (the kernel and library import, the
family's own module included on both sides, is measured apart: ``import s``, median too), ``STEP s`` the median STEP write. The geargen side
reads the case's design table with the family's reader (geargen.families.registry.read_gear) and
builds it with geargen.cad.families.build_part, so a family's row works as soon as it registers
(geargen/families/registry.py); until then the
row says "not in this geargen". ``--table CASE=FILE.toml`` replaces a case's table by FILE's
``[gear]`` table (a family whose keys differ from those guessed here).

The same checks for every STEP, in this process after the runs: the last run's file is read back
(geargen.cad.export.read_step) and checked by geargen.cad.gear_solid.check_solid (one solid,
BRepCheck valid, positive volume) and its volume integrated by solid_volume (Gauss-Kronrod,
relative 1e-7); ``vol/geargen`` is a peer's volume over geargen's for the same case (rims, root
fillets and wheel throats differ by design, so this is a sanity column, not a score). The flank
accuracy of every STEP read back, beside its size, every source measured alike, in ``flank um
(offset um)``: for the cylindrical gears the largest deviation of section points on the usable
involute from geargen's exact involute helicoid, after one phase for the whole gear and the mean
offset of each flank side removed (the offset, a thicker or thinner tooth, in brackets;
:func:`gear_flank_form`); for the racks the flatness of the flanks and lands
(:func:`rack_flank_form`); for the bevel cases the flank's form deviation from the exact spherical
involute (:func:`bevel_flank_accuracy`), with the tooth's mean thickness offset from the case's
zero-backlash tooth in brackets; the worm rows are measured by their own bench.

Measured (this machine, load ~6 on 2 cores from other agents, median of 3; build s / STEP kB /
flank um, geargen against the fastest peer): external spur 0.026 / 692 / 0.00075 against
py_gearworks 0.121 / 1065 / 0.42; external helical 0.070 / 1050 / 0.00095 against bd_warehouse
0.590 / 2490 / 0.11 (py_gearworks 1193 kB); internal spur 0.072 / 1151 / 0.0006 against 0.366 /
2042 / 6.5; internal helical 0.112 / 1548 / 0.0003 against 0.755 / 1575 / 0.17; rack spur 0.013 /
264 against bd_warehouse 0.061 / 464; rack helical 0.049 / 288 against py_gearworks 0.181 / 477
(every rack's flanks exact planes); herringbone 0.099 / 2175 / 0.0009 against py_gearworks 2.64 /
1065 / 2000 (its herringbone=True STEP is a straight extrusion, no twist: not a peer for size);
double helical with a 6 mm gap 0.106 / 2070 (no peer). Bevel pinion geargen
0.066 s, STEP 305 kB, flank 8e-9 um against py_gearworks 5.9 s, 1195 kB, 0.29 um; bevel gear
geargen 0.086 s, 381 kB, 6e-8 um against 5.0 s, 977 kB, 1.3 um (the boolean build was 16.5 s /
7.7 s, 795 / 724 kB, 4e-6 / 1e-5 um on the same load).
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
    """Why this geargen cannot build ``table``'s kind (no family registered), or None."""
    from geargen.families.registry import FAMILIES
    if table.get("kind", "external") not in FAMILIES:
        return "not in this geargen"
    return None


def read_spec(table: dict, name: str):
    """The family's spec from its design table, through its family's reader."""
    from geargen.families.registry import read_gear
    return read_gear(table, where="gear", name=name.replace(" ", "_"))


def geargen_worker(table: dict, name: str, out: str) -> dict:
    """One fresh-process build of a case (see the module docstring); a JSON-able dict."""
    t0 = time.perf_counter()
    import importlib
    import importlib.util

    from geargen.cad.export import export_step
    from geargen.cad.families import build_part
    from geargen.cad.gear_solid import check_solid
    from geargen.errors import DesignError, GeometryError
    # the family's solid module too (its family imports it on first use): the peers' import time
    # holds theirs
    solid_module = f"geargen.families.{table.get('kind', 'external')}.solid"
    if importlib.util.find_spec(solid_module) is not None:
        importlib.import_module(solid_module)
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


def gear_flank_form(shape, profile, heights, apparent_height=lambda z: z) -> tuple[float, float]:
    """(form deviation um, mean offset um) of a gear's flanks read back from a STEP file: sections
    at ``heights`` (geargen.cad.measure.section), the points on the usable involute band of
    geargen's ``profile`` (0.1 m_n above its start, 0.05 m_n below its tip) compared with the exact
    involute helicoid (geargen.cad.measure.involute_deviation; ``apparent_height(z)``: the height
    of the first helical half whose section the one at z is, for a double-helical gear). A peer's
    teeth may sit at another phase or thickness: the sections are first turned, all by the same
    angle, so their tooth centres fall on geargen's (the mean polar offset of the band's points,
    folded into one pitch: a constant phase, so a wrong twist along the face still shows), then per
    section and flank side the mean deviation is removed and reported apart (``offset``, + = the
    tooth, or a ring's space, wider than geargen's); the form deviation is what remains."""
    import math

    import numpy as np

    from geargen.cad.measure import _polar_in_tooth_frame, involute_deviation, section
    from geargen.profile.tooth import section_rotation
    m = profile.spec.module
    bands, phase = [], []
    for z in heights:
        at = apparent_height(z)
        cut = section(shape, float(z), 64)
        rad = np.hypot(cut.points[:, 0], cut.points[:, 1])
        sel = (rad > profile.involute_start_radius + 0.1 * m) & (rad < profile.tip_radius - 0.05 * m)
        ang = np.arctan2(cut.points[sel, 1], cut.points[sel, 0]) - section_rotation(profile.spec, at)
        bands.append((at, cut.points[sel]))
        phase.append(np.exp(1j * profile.teeth * ang))
    shift = float(np.angle(np.mean(np.concatenate(phase)))) / profile.teeth

    def measured(shift):
        c, s = math.cos(-shift), math.sin(-shift)
        form, offsets = 0.0, []
        for at, band in bands:
            pts = band @ np.array([[c, s], [-s, c]])
            dev = involute_deviation(profile, at, pts)
            _, _, local = _polar_in_tooth_frame(profile, at, pts)
            for side in (local > 0, local < 0):
                if np.any(side):
                    mean = float(np.mean(dev[side]))
                    offsets.append(mean)
                    form = max(form, float(np.max(np.abs(dev[side] - mean))))
        return form * 1e3, float(np.mean(offsets)) * 1e3

    # the band's two flanks lie either side of a tooth centre and of a space centre alike: the mean
    # finds one of the two, half a pitch apart; the right one fits
    return min(measured(shift), measured(shift + profile.pitch_angle / 2))


def rack_flank_form(shape, module: float) -> float:
    """Flatness (um) of a rack's flanks read back from a STEP file: every plane or B-spline face
    sampled on a 12 x 12 grid of its parameters, a plane fitted to each (least squares); over the
    faces within 0.005 m_n of their plane (the flanks and lands; a fillet or tip arc bows out by
    more), the largest distance of a sample from its plane. Exact planes give 0."""
    import numpy as np
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepTools import BRepTools
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS
    from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Plane
    worst = 0.0
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        face = TopoDS.Face_s(exp.Current())
        exp.Next()
        ad = BRepAdaptor_Surface(face)
        if ad.GetType() not in (GeomAbs_Plane, GeomAbs_BSplineSurface):
            continue  # an arc's cylinder: a fillet or a tip, not a flank
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        pts = np.array([[(p := ad.Value(float(u), float(v))).X(), p.Y(), p.Z()]
                        for u in np.linspace(u0, u1, 12) for v in np.linspace(v0, v1, 12)])
        centred = pts - pts.mean(axis=0)
        normal = np.linalg.svd(centred, full_matrices=False)[2][-1]
        residual = float(np.max(np.abs(centred @ normal)))
        if residual < 0.005 * module:
            worst = max(worst, residual)
    return worst * 1e3


def flank_accuracy(table: dict, name: str, source: str, path: Path) -> str:
    """``form (offset)`` in um of the case's STEP file as text (module docstring), "" where not
    measured here (the worm rows: their own bench)."""
    import numpy as np

    from geargen.cad.export import read_step
    kind = table.get("kind", "external")
    if kind == "bevel":
        if source not in BEVEL_FRAMES:
            return ""
        flank = bevel_flank_accuracy(path, table, source)
        return "" if flank["form_um"] is None else f"{flank['form_um']:.2g} ({flank['thickness_um']:+.3g})"
    if kind not in ("external", "internal", "double_helical", "rack"):
        return ""
    shape = read_step(path).shape
    spec = read_spec(table, name)
    if kind == "rack":
        return f"{rack_flank_form(shape, spec.module):.2g}"
    b = spec.face_width
    heights = np.linspace(0.05, 0.95, 5) * b
    if kind == "internal":
        from geargen.profile.internal import internal_profile
        form, offset = gear_flank_form(shape, internal_profile(spec).flank_frame(), heights)
    elif kind == "double_helical":
        from geargen.families.double_helical.solid import half_spec
        from geargen.profile.tooth import tooth_profile
        h = spec.half_face_width
        heights = [z for z in heights if z <= h or z >= b - h]  # not in the centre gap
        form, offset = gear_flank_form(shape, tooth_profile(half_spec(spec)), heights,
                                       lambda z: z if z <= h else b - z)
    else:
        from geargen.profile.tooth import tooth_profile
        form, offset = gear_flank_form(shape, tooth_profile(spec), heights)
    return f"{form:.2g} ({offset:+.3g})"


#: where each source's bevel gear has its apex and axis, to bring its STEP into geargen's frame (apex at
#: the origin, teeth towards +z): py_gearworks puts the heel pitch circle in the xy plane, the apex on
#: +z at r_p / tan(delta) (its BevelGear docstring; the bounding boxes agree)
BEVEL_FRAMES = {"geargen": lambda spec: (0.0, 1.0),
                "py_gearworks": lambda spec: (spec.reference_diameter / 2 / math.tan(spec.pitch_cone_angle), -1.0)}


def bevel_flank_accuracy(path: Path, table: dict, source: str) -> dict:
    """The flank deviation of a bevel gear's STEP read back, the same measure for every source: points
    on its B-spline faces (geargen.families.bevel.solid.face_points, 12 x 12 per face), brought into
    geargen's frame (:data:`BEVEL_FRAMES`), compared with the exact spherical involute of the case
    (involute_deviation) over the middle of the flank (10 % of the depth off the base or root cone,
    20 % off the tip cone: py_gearworks truncates its tips by 0.1 m). The tooth's phase is searched
    (median |deviation| least); a source's tooth may be thicker or thinner than the case's
    zero-backlash tooth, so per flank side the mean offset is removed and reported as ``thickness_um``
    (+ = thicker) and ``form_um`` is the largest deviation that remains."""
    import numpy as np
    from scipy.optimize import minimize_scalar

    from geargen.families.bevel.solid import face_points, involute_deviation
    from geargen.cad.export import read_step
    spec = read_spec(table, "bench")
    apex_z, sense = BEVEL_FRAMES[source](spec)
    pts = face_points(read_step(path).shape)
    pts = np.column_stack([pts[:, 0], pts[:, 1], sense * (pts[:, 2] - apex_z)])
    margins = (0.1, 0.2)
    pitch = 2 * math.pi / spec.teeth

    def spread(phase):
        return float(np.median(np.abs(involute_deviation(spec, pts, phase, margins)[0])))
    coarse = np.linspace(0.0, pitch, 721)
    best = coarse[int(np.argmin([spread(p) for p in coarse]))]
    step = pitch / 720
    phase = minimize_scalar(spread, bounds=(best - step, best + step), method="bounded",
                            options={"xatol": 1e-12}).x
    dev, side = involute_deviation(spec, pts, phase, margins)
    if not len(dev):
        return dict(form_um=None, thickness_um=None, points=0)
    offsets = {s: float(dev[side == s].mean()) for s in (-1, 1) if np.any(side == s)}
    form = max(float(np.abs(dev[side == s] - m).max()) for s, m in offsets.items())
    return dict(form_um=form * 1e3, thickness_um=sum(offsets.values()) * 1e3, points=int(len(dev)))


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
                try:
                    r["flank"] = flank_accuracy(table, case.name, source, r["path"])
                except Exception as exc:  # a peer's surface the section cannot follow: say so, keep the row
                    r["flank"] = f"n/a ({type(exc).__name__})"
            rows.append((case, source, r))
            print(f"{case.name} / {source}: {({k: v for k, v in r.items() if k != 'path'})}", file=sys.stderr)

    print(f"\nBuild times, fresh process each, median of {args.repeat}; STEP files in {out}")
    header = ("case", "source", "import s", "build s", "STEP s", "STEP kB", "flank um (offset um)", "STEP read back",
              "volume mm3", "vol/geargen", "what was built")
    print(" | ".join(header))
    print(" | ".join("---" for _ in header))
    geargen_volume = {case.name: r.get("volume") for case, source, r in rows if source == "geargen"}
    for case, source, r in rows:
        if "failed" in r or "refused" in r:
            print(" | ".join([case.name, source] + [""] * (len(header) - 3) + [r.get("failed") or r["refused"]]))
            continue
        ref = geargen_volume.get(case.name)
        ratio = f"{r['volume'] / ref:.4f}" if source != "geargen" and ref and r["volume"] else ""
        note = r["note"] + (f"; in memory: {r['check']}" if source == "geargen" and r.get("check") else "")
        if source == "geargen" and case.note:
            note += f"; {case.note}"
        if r.get("runs", args.repeat) < args.repeat:
            note += f" ({r['runs']} runs)"
        print(" | ".join([case.name, source, f"{r['import_s']:.2f}", f"{r['build_s']:.3f}", f"{r['step_s']:.3f}",
                          f"{r['kb']:.0f}", r.get("flank", ""), r["valid"],
                          f"{r['volume']:.1f}" if r["volume"] else "n/a", ratio, note]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
