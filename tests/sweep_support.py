"""The random stability sweep of every gear family: each family's generator of random parameters,
its check of one case (run in a worker process) and the runner (tests/test_family_sweep.py runs it;
bench/bench_sweep_families.py runs the full set and prints a table).

A case is either refused clearly - a DesignError (tag ``design_error``) or a GeometryError of a kind
that is the right answer for impossible parameters (``geometry_error:<kind>``) - or becomes one valid
closed solid whose volume matches an independent closed form, whose flanks lie on the exact
surface and whose exported STL is watertight. Everything else is a tagged failure: ``invalid``
(BRepCheck), ``not_one_solid``, ``wrong_volume``, ``flank``, ``stl_not_watertight``, ``timeout``,
``crash:<exception type>`` (each family's section says what it checks).

Which cases (:func:`sweep_cases`):

- per push (the default): a sample of ``per_push`` cases a family, sized so the whole sweep is
  about 90 s of one core, drawn from the seed of the checked-out commit (``git rev-parse HEAD``, its
  first 8 hex digits; 20261124 outside git), so each push covers other cases and the summary's
  seed reproduces a failure: ``GEARGEN_SWEEP_SEED=<seed> pytest tests/test_family_sweep.py -k <family>``;
- the full set (``GEARGEN_FULL_SWEEP=1``): ``full_count`` cases a family from its fixed seed (the
  ~720 cases the six family sweeps ran on every push), with the coverage floors (a family's sweep
  mostly builds, not refuses) that a small sample cannot promise;
- ``GEARGEN_SWEEP_SEED`` and ``GEARGEN_SWEEP_COUNT`` replace the seed and the count of either.

A family's cases are the first ``count`` of its generator's stream from the seed, so the per-push
sample of a seed is the start of the full set of that seed. Each case runs in a worker process
(``GEARGEN_SWEEP_WORKERS``, default 2, spawned, not forked: the parent may hold kernel threads),
killed after the family's timeout (``GEARGEN_SWEEP_TIMEOUT`` s, default 60; the worm sets 150): tag
``timeout``; a worker that dies (a kernel segfault) tags ``crash:worker_died``.
"""

from __future__ import annotations

import importlib.util
import math
import multiprocessing as mp
import os
import subprocess
import sys
import time
import traceback
from collections import Counter
from dataclasses import dataclass, field
from multiprocessing.connection import wait
from pathlib import Path
from typing import Callable

import numpy as np

TIMEOUT = float(os.environ.get("GEARGEN_SWEEP_TIMEOUT", "60"))
WORKERS = int(os.environ.get("GEARGEN_SWEEP_WORKERS", "2"))
FULL = os.environ.get("GEARGEN_FULL_SWEEP", "") not in ("", "0")
#: the seed outside git
FALLBACK_SEED = 20261124


# ---------------------------------------------------------------- the runner


def _load(check: str):
    path, function = check.rsplit(":", 1)
    name = f"_sweep_{abs(hash(path))}"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return getattr(module, function)


def _worker(conn, check: str):
    fn = _load(check)
    while True:
        task = conn.recv()
        if task is None:
            return
        conn.send(fn(task))


def run_sweep(params: list[dict], check: str, timeout: float | list[float] = TIMEOUT,
              workers: int = WORKERS) -> list[tuple[str, str, float]]:
    """(tag, detail, seconds) per parameter set; each checked in a worker, killed after ``timeout``
    seconds (one for all, or one per parameter set)."""
    ctx = mp.get_context("spawn")
    limits = timeout if isinstance(timeout, list) else [timeout] * len(params)
    results: list = [None] * len(params)
    todo = list(range(len(params)))[::-1]
    slots = []

    def start():
        parent, child = ctx.Pipe()
        proc = ctx.Process(target=_worker, args=(child, check), daemon=True)
        proc.start()
        return {"proc": proc, "conn": parent, "task": None, "t0": 0.0}

    def give(slot):
        if todo:
            i = todo.pop()
            slot["task"], slot["t0"] = i, time.perf_counter()
            slot["conn"].send(params[i])
        else:
            slot["task"] = None

    for _ in range(min(workers, len(params))):
        slots.append(start())
        give(slots[-1])
    while any(s["task"] is not None for s in slots):
        busy = [s for s in slots if s["task"] is not None]
        ready = wait([s["conn"] for s in busy], timeout=0.5)
        now = time.perf_counter()
        for s in busy:
            if s["conn"] in ready:
                task = s["task"]
                try:
                    tag, detail = s["conn"].recv()
                except (EOFError, OSError):  # the worker died (segfault in the kernel)
                    tag, detail = "crash:worker_died", f"exit code {s['proc'].exitcode}"
                    s.update(start())
                results[task] = (tag, detail, now - s["t0"])
                give(s)
            elif now - s["t0"] > limits[s["task"]]:
                s["proc"].kill()
                results[s["task"]] = ("timeout", f"> {limits[s['task']]} s", now - s["t0"])
                s.update(start())
                give(s)
    for s in slots:
        if s["proc"].is_alive():
            s["conn"].send(None)
            s["proc"].join(5)
    return results


def summary(name: str, params: list[dict], results, seed: int) -> str:
    """One line: the tags counted, the builds' total time and the slowest case."""
    tags = Counter(r[0] for r in results)
    slowest = max(range(len(results)), key=lambda i: results[i][2])
    return (f"{name}: sweep of {len(params)} (seed {seed}): {dict(tags)}; total {sum(r[2] for r in results):.1f} s "
            f"of builds; slowest {results[slowest][2]:.2f} s: {params[slowest]}")


def tagged_failures(params: list[dict], results, expected_kinds=frozenset()) -> list[tuple[dict, tuple]]:
    """The (parameters, result) pairs whose tag is neither ``ok``, a ``design_error`` nor a
    ``geometry_error:KIND`` with KIND in ``expected_kinds`` (the refusals that are the right answer
    for impossible parameters)."""
    def accepted(tag: str) -> bool:
        return tag in ("ok", "design_error") or (tag.startswith("geometry_error:")
                                                  and tag.split(":", 1)[1] in expected_kinds)
    return [(p, r) for p, r in zip(params, results) if not accepted(r[0])]


# ---------------------------------------------------------------- families and their cases


@dataclass(frozen=True)
class Family:
    """A gear family's sweep: ``generate(rng)`` one random parameter dict, ``check(p)`` its
    (tag, detail) in a worker, the refusals it accepts, its full set (``full_count`` cases from
    ``full_seed``), its per-push sample size and its ``coverage(tags, params, results, count)``: the
    floors the full set must reach (messages of those it misses)."""

    name: str
    generate: Callable
    check: Callable
    expected_kinds: frozenset
    full_count: int
    per_push: int
    full_seed: int = FALLBACK_SEED
    timeout: float = TIMEOUT
    coverage: Callable = field(default=lambda tags, params, results, count: [])


def commit_seed(root: Path | None = None) -> int | None:
    """The checked-out commit's first 8 hex digits as a number, None outside git."""
    root = root or Path(__file__).resolve().parents[1]
    try:
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=root, capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.TimeoutExpired):
        return None
    sha = head.stdout.strip()
    return int(sha[:8], 16) if head.returncode == 0 and len(sha) >= 8 else None


def sweep_seed(family: Family, full: bool = FULL) -> int:
    """The seed of ``family``'s cases (module docstring)."""
    if "GEARGEN_SWEEP_SEED" in os.environ:
        return int(os.environ["GEARGEN_SWEEP_SEED"])
    if full:
        return family.full_seed
    seed = commit_seed()
    return FALLBACK_SEED if seed is None else seed


def sweep_cases(family: Family, full: bool = FULL) -> tuple[int, list[dict]]:
    """(seed, parameter dicts) of ``family``: the first ``count`` of its generator's stream."""
    count = int(os.environ.get("GEARGEN_SWEEP_COUNT", family.full_count if full else family.per_push))
    seed = sweep_seed(family, full)
    rng = np.random.default_rng(seed)
    return seed, [dict(family.generate(rng), family=family.name) for _ in range(count)]


def check_case(p: dict) -> tuple[str, str]:
    """The check of one case of any family (dispatched on ``p["family"]``); runs in a worker."""
    family = FAMILIES[p["family"]]
    return family.check({k: v for k, v in p.items() if k != "family"})


CHECK = f"{__file__}:check_case"


# ---------------------------------------------------------------- checks several families share


def _tagged_exception(exc: BaseException) -> tuple[str, str] | None:
    """The tag of an exception a build raised: a refusal or a crash."""
    from geargen.errors import DesignError, GeometryError
    if isinstance(exc, DesignError):
        return "design_error", exc.field.split(".")[-1]
    if isinstance(exc, GeometryError):
        return f"geometry_error:{exc.kind}", str(exc)[:120]
    return f"crash:{type(exc).__name__}", traceback.format_exc(limit=3)[-300:]


def _solid_failure(shape, expected_volume: float, tolerance: float, tag: str = "",
                   eps: float = 1e-7) -> tuple[str, str] | None:
    """The tagged failure of a built solid (``tag`` + not_one_solid / invalid / wrong_volume), or None
    when it is one valid solid whose volume is ``expected_volume`` within ``tolerance`` (relative;
    integrated to ``eps``, and again to 1e-9 before it is called wrong)."""
    from geargen.cad.gear_solid import check_solid, solid_volume
    problem = check_solid(shape)
    if problem:
        return tag + ("not_one_solid" if "solids" in problem else "invalid"), problem
    vol = solid_volume(shape, eps=eps)
    if abs(vol / expected_volume - 1) > tolerance and eps > 1e-9:
        vol = solid_volume(shape, eps=1e-9)  # quick first; where not within, integrate properly
    if abs(vol / expected_volume - 1) > tolerance:
        return tag + "wrong_volume", f"{vol!r} vs {expected_volume!r} ({vol / expected_volume - 1:.2e})"
    return None


def stl_problem(solid, module: float) -> str | None:
    """None if the STL that geargen.cad.export writes of ``solid`` is watertight (trimesh: every edge
    shared by exactly two triangles once equal corners are merged, as STL readers do), else what
    is open. The chordal tolerance, 1e-2 modules, keeps a mesh to ~0.2 s; open edges (issue 31's
    zero-area triangles at a sphere's pole) appear at any tolerance."""
    import tempfile

    import trimesh

    from geargen.cad.export import export_stl, read_stl
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "part.stl"
        export_stl(solid, path, chordal_tolerance=1e-2 * module)
        tri = read_stl(path)
    mesh = trimesh.Trimesh(vertices=tri.reshape(-1, 3), faces=np.arange(3 * len(tri)).reshape(-1, 3))
    if mesh.is_watertight:
        return None
    open_edges = trimesh.grouping.group_rows(mesh.edges_sorted, require_count=1)
    example = mesh.vertices[mesh.edges_sorted[open_edges[:1]]]
    return f"{len(open_edges)} open edges of {len(mesh.edges_unique)}, e.g. {example}"


def bore_area(hub) -> float:
    """Area of a bore with its keyway (flat floor at bore radius + depth, centred on +x)."""
    if hub.bore_diameter <= 0:
        return 0.0
    r = hub.bore_diameter / 2
    area = math.pi * r * r
    if hub.keyway_width > 0:
        w2 = hub.keyway_width / 2
        xk = math.sqrt(r * r - w2 * w2)
        area += hub.keyway_width * (r + hub.keyway_depth - xk) - (r * r * math.asin(w2 / r) - xk * w2)
    return area


def _random_hub(plain, m: float, p: dict):
    """The bore/keyway/hub of a random external or double-helical gear (relative sizes in ``p``)."""
    from geargen.design.gear import Hub
    root_d = 2 * plain.root_radius_standard
    bore = p["bore_fraction"] * root_d * 0.9
    if bore <= 0:
        return Hub()
    kw, kd = (0.25 * bore, 0.1 * bore) if p["keyway"] else (0.0, 0.0)
    hd, hl = ((bore + 2 * kd + root_d) / 2, 2 * m) if p["hub"] else (0.0, 0.0)
    return Hub(bore_diameter=bore, keyway_width=kw, keyway_depth=kd, hub_diameter=hd, hub_length=hl)


def _fraction(tag: str, share: float):
    def floor(tags, params, results, count):
        return [] if tags[tag] >= share * count else [f"{tags[tag]} {tag} < {share:g} x {count}"]
    return floor


# ---------------------------------------------------------------- external gears


#: external gears: tooth counts log-uniform in [4, 40] (big gears cost time, not coverage: the bench
#: gears' tests build a 112-tooth one)
EXTERNAL_MAX_TEETH = 40
#: refusals that are the right answer for impossible parameters (external and double-helical)
CYLINDRICAL_KINDS = frozenset({"pointed_tooth", "negative_root", "pointed_rack", "no_involute", "severed_tooth",
                               "fillet_loop"})


def external_parameters(rng: np.random.Generator) -> dict:
    """One random gear: GearSpec fields plus relative bore/keyway/hub sizes (plain numbers)."""
    helical = rng.random() < 0.6
    return {
        "teeth": int(round(math.exp(rng.uniform(math.log(4), math.log(EXTERNAL_MAX_TEETH))))),
        "module": float(math.exp(rng.uniform(math.log(0.05), math.log(20.0)))),
        "pressure_angle_deg": float(rng.uniform(14.5, 30.0)),
        "helix_angle_deg": float(rng.uniform(5.0, 40.0)) if helical else 0.0,
        "hand": str(rng.choice(["right", "left"])),
        "profile_shift": float(rng.uniform(-0.6, 1.0)),
        "addendum_coefficient": float(rng.uniform(0.8, 1.2)),
        "dedendum_coefficient": float(rng.uniform(1.0, 1.6)),
        "rack_tip_fraction": None if rng.random() < 0.5 else float(rng.uniform(0.0, 1.0)),
        "thinning_modules": float(rng.uniform(0.0, 0.05)) if rng.random() < 0.3 else 0.0,
        "face_modules": float(rng.uniform(1.0, 8.0)),
        "bore_fraction": float(rng.uniform(0.1, 0.9)) if rng.random() < 0.7 else 0.0,
        "keyway": bool(rng.random() < 0.2),
        "hub": bool(rng.random() < 0.15),
    }


def external_spec(p: dict):
    """The GearSpec of a parameter set (raises DesignError for values it refuses)."""
    from geargen.design.gear import GearSpec
    m = p["module"]
    base = dict(teeth=p["teeth"], module=m, pressure_angle=math.radians(p["pressure_angle_deg"]),
                face_width=p["face_modules"] * m, helix_angle=math.radians(p["helix_angle_deg"]), hand=p["hand"],
                profile_shift=p["profile_shift"], addendum_coefficient=p["addendum_coefficient"],
                dedendum_coefficient=p["dedendum_coefficient"])
    plain = GearSpec(**base)
    if p["rack_tip_fraction"] is not None:
        base["rack_tip_radius_coefficient"] = p["rack_tip_fraction"] * plain.max_rack_tip_radius_coefficient
    base["thinning"] = p["thinning_modules"] * m
    return GearSpec(**base, hub=_random_hub(plain, m, p))


def external_check(p: dict) -> tuple[str, str]:
    """Valid solid, volume (outline area x face - bore, + hub) within 1e-6, flanks within 0.1 um of
    the involute at mid-face, watertight STL."""
    import warnings

    from geargen.profile.tooth import UndercutWarning
    try:
        warnings.simplefilter("ignore", UndercutWarning)
        spec = external_spec(p)
        from geargen.cad.gear_solid import build_gear
        from geargen.cad.measure import flank_deviation
        g = build_gear(spec)
    except Exception as exc:  # noqa: BLE001 - a refusal or a failure to tag
        return _tagged_exception(exc)
    try:
        hub = spec.hub
        expected = (g.profile.area() - bore_area(hub)) * spec.face_width
        expected += (math.pi * hub.hub_diameter ** 2 / 4 - bore_area(hub)) * hub.hub_length
        failure = _solid_failure(g.shape, expected, 1e-6)
        if failure:
            return failure
        dev = flank_deviation(g.shape, g.profile, 0.5 * spec.face_width, samples_per_face=32)
        if not dev.points or dev.max_abs > 1e-4:
            return "flank", f"{dev}"
        problem = stl_problem(g, spec.module)
        if problem:
            return "stl_not_watertight", problem
    except Exception as exc:  # noqa: BLE001
        return _tagged_exception(exc)
    return "ok", ""


# ---------------------------------------------------------------- double-helical (herringbone) gears


#: teeth log-uniform in [5, 16]
DOUBLE_HELICAL_MAX_TEETH = 16


def double_helical_parameters(rng: np.random.Generator) -> dict:
    """One random double-helical gear: GearSpec fields plus relative gap/bore/keyway/hub sizes."""
    return {
        "teeth": int(round(math.exp(rng.uniform(math.log(5), math.log(DOUBLE_HELICAL_MAX_TEETH))))),
        "module": float(math.exp(rng.uniform(math.log(0.05), math.log(20.0)))),
        "pressure_angle_deg": float(rng.uniform(14.5, 30.0)),
        "helix_angle_deg": float(rng.uniform(5.0, 45.0)),
        "hand": str(rng.choice(["right", "left"])),
        "profile_shift": float(rng.uniform(-0.6, 1.0)),
        "addendum_coefficient": float(rng.uniform(0.8, 1.2)),
        "dedendum_coefficient": float(rng.uniform(1.0, 1.6)),
        "rack_tip_fraction": None if rng.random() < 0.5 else float(rng.uniform(0.0, 1.0)),
        "face_modules": float(rng.uniform(2.0, 8.0)),
        # 40 % herringbones (no gap), else a gap of up to 60 % of the face width
        "gap_fraction": 0.0 if rng.random() < 0.4 else float(rng.uniform(0.02, 0.6)),
        "bore_fraction": float(rng.uniform(0.1, 0.9)) if rng.random() < 0.7 else 0.0,
        "keyway": bool(rng.random() < 0.2),
        "hub": bool(rng.random() < 0.15),
    }


def double_helical_spec(p: dict):
    """The double-helical GearSpec of a parameter set (raises DesignError for values it refuses)."""
    from geargen.families.double_helical.spec import DoubleHelicalGearSpec
    m = p["module"]
    face = p["face_modules"] * m
    base = dict(teeth=p["teeth"], module=m, pressure_angle=math.radians(p["pressure_angle_deg"]), face_width=face,
                helix_angle=math.radians(p["helix_angle_deg"]), hand=p["hand"], profile_shift=p["profile_shift"],
                addendum_coefficient=p["addendum_coefficient"], dedendum_coefficient=p["dedendum_coefficient"],
                centre_gap=p["gap_fraction"] * face)
    plain = DoubleHelicalGearSpec(**base)
    if p["rack_tip_fraction"] is not None:
        base["rack_tip_radius_coefficient"] = p["rack_tip_fraction"] * plain.max_rack_tip_radius_coefficient
    return DoubleHelicalGearSpec(**base, hub=_random_hub(plain, m, p))


def double_helical_check(p: dict) -> tuple[str, str]:
    """Valid solid, volume (profile area x toothed length + groove disc x gap - bore, + hub) within
    1e-6, flanks of both halves within 0.1 um of the involute, watertight STL."""
    import warnings

    from geargen.profile.tooth import UndercutWarning
    try:
        warnings.simplefilter("ignore", UndercutWarning)
        spec = double_helical_spec(p)
        from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
        from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Trsf

        from geargen.families.double_helical.solid import build_double_helical
        from geargen.profile.tooth import centre_gap_radius
        from geargen.cad.measure import flank_deviation
        g = build_double_helical(spec)
    except Exception as exc:  # noqa: BLE001 - a refusal or a failure to tag
        return _tagged_exception(exc)
    try:
        hub, b, gap = spec.hub, spec.face_width, spec.centre_gap
        expected = g.profile.area() * (b - gap) + math.pi * centre_gap_radius(spec, g.profile) ** 2 * gap - bore_area(hub) * b
        expected += (math.pi * hub.hub_diameter ** 2 / 4 - bore_area(hub)) * hub.hub_length
        failure = _solid_failure(g.shape, expected, 1e-6)
        if failure:
            return failure
        h = spec.half_face_width
        dev = flank_deviation(g.shape, g.profile, 0.5 * h, samples_per_face=32)
        if not dev.points or dev.max_abs > 1e-4:
            return "flank", f"first half: {dev}"
        # the second half: the solid mirrored back in z = b / 2 (exact) brings it to z in [0, h], where
        # its flanks must lie on the involute turning with the spec's hand; a second half of the wrong
        # hand or shape fails here
        mirror = gp_Trsf()
        mirror.SetMirror(gp_Ax2(gp_Pnt(0, 0, b / 2), gp_Dir(0, 0, 1)))
        back = BRepBuilderAPI_Transform(g.shape, mirror, True).Shape()
        dev = flank_deviation(back, g.profile, 0.5 * h, samples_per_face=32)
        if not dev.points or dev.max_abs > 1e-4:
            return "flank", f"second half: {dev}"
        problem = stl_problem(g, spec.module)
        if problem:
            return "stl_not_watertight", problem
    except Exception as exc:  # noqa: BLE001
        return _tagged_exception(exc)
    return "ok", ""


def _herringbones(tags, params, results, count):
    built = sum(1 for p, r in zip(params, results) if r[0] == "ok" and p["gap_fraction"] == 0)
    return [] if built >= 0.2 * count else [f"{built} herringbones (no gap) built < 0.2 x {count}"]


# ---------------------------------------------------------------- internal (ring) gears


#: teeth log-uniform in [16, 36]: the solid's cost grows with the teeth, the coverage does not
INTERNAL_MAX_TEETH = 36
#: refusals that are the right answer for rings that cannot be cut (geargen.profile.internal)
INTERNAL_KINDS = frozenset({"tip_inside_base", "cutter_too_large", "pointed_cutter", "cutter_interference",
                            "no_involute", "pointed_tooth", "fillet_loop", "thin_rim", "cutter_too_thick"})


def internal_parameters(rng: np.random.Generator) -> dict:
    helical = rng.random() < 0.5
    return {
        "teeth": int(round(math.exp(rng.uniform(math.log(16), math.log(INTERNAL_MAX_TEETH))))),
        "module": float(math.exp(rng.uniform(math.log(0.1), math.log(8.0)))),
        "pressure_angle_deg": float(rng.uniform(14.5, 25.0)),
        "helix_angle_deg": float(rng.uniform(5.0, 35.0)) if helical else 0.0,
        "hand": str(rng.choice(["right", "left"])),
        # rings below ~34 teeth need x > h_a* - z (1 - cos a) / 2 to keep the tip outside the base
        # circle: shifts and addenda are drawn where rings are made, the refusals stay reachable
        "profile_shift": float(rng.uniform(-0.3, 1.2)),
        "addendum_coefficient": float(rng.uniform(0.6, 1.0)),
        "dedendum_coefficient": float(rng.uniform(1.0, 1.5)),
        "cutter_tip_fraction": None if rng.random() < 0.5 else float(rng.uniform(0.0, 0.5)),
        "thinning_modules": float(rng.uniform(0.0, 0.05)) if rng.random() < 0.3 else 0.0,
        "face_modules": float(rng.uniform(1.0, 3.0)),
        "rim_modules": None if rng.random() < 0.5 else float(rng.uniform(0.3, 6.0)),
    }


def internal_spec(p: dict):
    from geargen.families.internal.spec import InternalGearSpec
    m = p["module"]
    base = dict(teeth=p["teeth"], module=m, pressure_angle=math.radians(p["pressure_angle_deg"]),
                face_width=p["face_modules"] * m, helix_angle=math.radians(p["helix_angle_deg"]), hand=p["hand"],
                profile_shift=p["profile_shift"], addendum_coefficient=p["addendum_coefficient"],
                dedendum_coefficient=p["dedendum_coefficient"], thinning=p["thinning_modules"] * m)
    plain = InternalGearSpec(**base)
    if p["cutter_tip_fraction"] is not None:
        base["rack_tip_radius_coefficient"] = p["cutter_tip_fraction"] * plain.max_rack_tip_radius_coefficient
    if p["rim_modules"] is not None:
        base["rim_diameter"] = 2 * plain.root_radius_standard + 2 * p["rim_modules"] * m
    return InternalGearSpec(**base)


def internal_check(p: dict) -> tuple[str, str]:
    """Valid solid, volume (rim disc less the exact hole) within 1e-6, flanks within 0.1 um of the
    involute at mid-face, watertight STL."""
    try:
        spec = internal_spec(p)
        from geargen.families.internal.solid import build_internal
        from geargen.cad.measure import flank_deviation
        # a looser spline than the default 2 nm (still 50x inside the flank bound): a lighter solid
        g = build_internal(spec, tolerance=2e-6 * spec.module)
    except Exception as exc:  # noqa: BLE001 - a refusal or a failure to tag
        return _tagged_exception(exc)
    try:
        expected = (math.pi * (spec.rim_diameter / 2) ** 2 - g.profile.hole_area()) * spec.face_width
        failure = _solid_failure(g.shape, expected, 1e-6)
        if failure:
            return failure
        dev = flank_deviation(g.shape, g.profile.flank_frame(), 0.5 * spec.face_width, samples_per_face=16)
        if not dev.points or dev.max_abs > 1e-4 * max(1.0, spec.module):
            return "flank", f"{dev}"
        problem = stl_problem(g, spec.module)
        if problem:
            return "stl_not_watertight", problem
    except Exception as exc:  # noqa: BLE001
        return _tagged_exception(exc)
    return "ok", ""


# ---------------------------------------------------------------- racks


#: teeth along the rack from [1, 12] (a long rack is the same pitch repeated)
RACK_MAX_TEETH = 12


def rack_parameters(rng: np.random.Generator) -> dict:
    """One random rack: RackSpec fields, radii and sizes relative to what fits (plain numbers)."""
    helical = rng.random() < 0.6
    return {
        "teeth": int(rng.integers(1, RACK_MAX_TEETH + 1)),
        "module": float(math.exp(rng.uniform(math.log(0.05), math.log(20.0)))),
        "pressure_angle_deg": float(rng.uniform(14.5, 30.0)),
        "helix_angle_deg": float(rng.uniform(5.0, 40.0)) if helical else 0.0,
        "hand": str(rng.choice(["right", "left"])),
        "addendum_coefficient": float(rng.uniform(0.8, 1.4)),
        "dedendum_coefficient": float(rng.uniform(0.9, 1.7)),
        "tip_rounding": str(rng.choice(["sharp", "generating"])),
        "tip_fraction": None if rng.random() < 0.5 else float(rng.uniform(0.0, 1.0)),
        "root_fraction": None if rng.random() < 0.4 else float(rng.uniform(0.0, 1.0)),
        "thinning_modules": float(rng.uniform(0.0, 0.1)) if rng.random() < 0.3 else 0.0,
        "face_modules": float(rng.uniform(1.0, 8.0)),
        "back_modules": float(rng.uniform(0.3, 4.0)),
    }


def rack_spec(p: dict):
    """The RackSpec of a parameter set (raises DesignError for values it refuses)."""
    from geargen.families.rack.spec import RackSpec
    m = p["module"]
    base = dict(teeth=p["teeth"], module=m, pressure_angle=math.radians(p["pressure_angle_deg"]),
                face_width=p["face_modules"] * m, helix_angle=math.radians(p["helix_angle_deg"]), hand=p["hand"],
                addendum_coefficient=p["addendum_coefficient"], dedendum_coefficient=p["dedendum_coefficient"],
                pitch_line_height=(p["dedendum_coefficient"] + p["back_modules"]) * m,
                tip_rounding=p["tip_rounding"], thinning=p["thinning_modules"] * m)
    plain = RackSpec(**base, root_fillet_coefficient=0.0)
    if p["tip_rounding"] == "generating" and p["tip_fraction"] is not None:
        base["tip_radius_coefficient"] = p["tip_fraction"] * plain.max_tip_radius_coefficient(0.0)
    tip = base.get("tip_radius_coefficient", RackSpec(**base, root_fillet_coefficient=0.0).tip_radius_coefficient)
    if p["root_fraction"] is not None:
        base["root_fillet_coefficient"] = p["root_fraction"] * plain.max_root_fillet_coefficient(tip)
    return RackSpec(**base)


def rack_check(p: dict) -> tuple[str, str]:
    """Valid solid, volume (transverse section area x face width, geargen.families.rack.geometry) within 1e-6,
    flanks within 0.1 um of the exact lines at mid-face, watertight STL."""
    try:
        spec = rack_spec(p)
        from geargen.families.rack.solid import build_rack, flank_straightness
        from geargen.families.rack.geometry import rack_volume
        rack = build_rack(spec)
    except Exception as exc:  # noqa: BLE001 - a refusal or a failure to tag
        return _tagged_exception(exc)
    try:
        # 1e-6 as the gears: the racks' volumes agree with the closed form to ~1e-12 (exact faces)
        failure = _solid_failure(rack.shape, rack_volume(spec), 1e-6, eps=1e-9)
        if failure:
            return failure
        worst, count = flank_straightness(rack, 0.5 * spec.face_width, samples_per_face=12)
        if count == 0 or not worst <= 1e-4:
            return "flank", f"{worst!r} mm over {count} points"
        problem = stl_problem(rack, spec.module)
        if problem:
            return "stl_not_watertight", problem
    except Exception as exc:  # noqa: BLE001
        return _tagged_exception(exc)
    return "ok", ""


def _racks_built(tags, params, results, count):
    out = _fraction("ok", 0.7)(tags, params, results, count)
    # the generator's refusals are DesignErrors naming their field, never a GeometryError
    if tags["ok"] + tags["design_error"] < 0.8 * count:
        out.append(f"{tags['ok'] + tags['design_error']} ok or design_error < 0.8 x {count}")
    return out


# ---------------------------------------------------------------- straight bevel gears (as on main)


BEVEL_MAX_TEETH = int(os.environ.get("GEARGEN_BEVEL_MAX_TEETH", "10"))
#: refusals that are the right answer for impossible parameters
BEVEL_KINDS = frozenset({"pointed_tooth", "no_tooth_space", "interference"})


def bevel_parameters(rng: np.random.Generator) -> dict:
    """One random bevel gear. Small tooth counts are undercut without a shift, so most gears take a
    shift just above the back-cone equivalent's undercut limit, x = h_a* - z_v sin^2(alpha) / 2; the
    others any shift, to exercise the refusals."""
    from geargen.families.bevel.geometry import pitch_cone_angles
    teeth = int(rng.integers(5, BEVEL_MAX_TEETH + 1))
    mate = int(round(math.exp(rng.uniform(math.log(5), math.log(80)))))
    sigma = float(rng.uniform(10.0, 170.0))
    alpha = float(rng.uniform(14.5, 28.0))
    delta = min(pitch_cone_angles(teeth, mate, math.radians(sigma))[0], math.radians(89.0))
    addendum = float(rng.uniform(0.6, 1.0))  # stub teeth: small tooth counts are pointed at full depth
    no_undercut = addendum - teeth / math.cos(delta) * math.sin(math.radians(alpha)) ** 2 / 2
    shift = float(rng.uniform(-0.2, 0.8)) if rng.random() < 0.2 else no_undercut + float(rng.uniform(0.0, 0.2))
    return {
        "teeth": teeth, "mate_teeth": mate, "shaft_angle_deg": sigma,
        "module": float(math.exp(rng.uniform(math.log(0.1), math.log(10.0)))),
        "pressure_angle_deg": alpha,
        "profile_shift": max(-0.8, min(0.8, shift)),
        "addendum_coefficient": addendum,
        "dedendum_coefficient": addendum + float(rng.uniform(0.15, 0.4)),
        "thinning_modules": float(rng.uniform(0.0, 0.08)) if rng.random() < 0.4 else 0.0,
        "face_fraction": float(rng.uniform(0.1, 0.45)),  # of the outer cone distance
        "bore_fraction": float(rng.uniform(0.1, 0.9)) if rng.random() < 0.4 else 0.0,
        "back": "flat" if rng.random() < 0.5 else "spherical",
    }


def bevel_spec(p: dict):
    from geargen.families.bevel.spec import BevelGearSpec
    m = p["module"]
    base = dict(teeth=p["teeth"], mate_teeth=p["mate_teeth"], module=m, face_width=m,
                shaft_angle=math.radians(p["shaft_angle_deg"]), pressure_angle=math.radians(p["pressure_angle_deg"]),
                profile_shift=p["profile_shift"], addendum_coefficient=p["addendum_coefficient"],
                dedendum_coefficient=p["dedendum_coefficient"],
                thinning=p["thinning_modules"] * m)
    plain = BevelGearSpec(**base)
    base["face_width"] = p["face_fraction"] * plain.cone_distance
    plain = BevelGearSpec(**base)
    toe_root = 2 * plain.toe_cone_distance * math.sin(plain.pitch_cone_angle - plain.dedendum_angle)
    return BevelGearSpec(**base, bore_diameter=p["bore_fraction"] * 0.9 * toe_root)


def bevel_check(p: dict) -> tuple[str, str]:
    """Valid solid (spherical or flat back at random), volume (geargen.families.bevel.geometry.bevel_volume)
    within 1e-6, flanks on the spherical involute within the fit's tolerance, watertight STL."""
    from geargen.errors import DesignError, GeometryError
    try:
        spec = bevel_spec(p)
        from geargen.families.bevel.solid import FLANK_TOLERANCE, bevel_volume, build_bevel, flank_deviation
        from geargen.cad.gear_solid import check_solid, solid_volume
        g = build_bevel(spec, back=p["back"])
    except DesignError as exc:
        return "design_error", exc.field.split(".")[-1]
    except GeometryError as exc:
        return f"geometry_error:{exc.kind}", str(exc)[:120]
    except Exception as exc:  # noqa: BLE001 - every other exception is a failure to tag
        return f"crash:{type(exc).__name__}", traceback.format_exc(limit=3)[-300:]
    try:
        problem = check_solid(g.shape)
        if problem:
            return ("not_one_solid" if "solids" in problem else "invalid"), problem
        expected = bevel_volume(spec, p["back"])
        vol = solid_volume(g.shape, eps=1e-8)
        # 1e-6: the integration's own accuracy (eps 1e-8 per span) with room for the core's faces
        if abs(vol / expected - 1) > 1e-6:
            return "wrong_volume", f"{vol!r} vs {expected!r} ({vol / expected - 1:.2e})"
        dev = flank_deviation(g.shape, spec, grid=6)
        # the flank B-spline is fitted within FLANK_TOLERANCE of R_e; twice that for the rounding of
        # the measure itself (angles of points up to ~2.5 m from the apex)
        if not len(dev) or np.abs(dev).max() > 2 * FLANK_TOLERANCE * spec.cone_distance:
            return "flank", f"{len(dev)} points, max {np.abs(dev).max() if len(dev) else None}"
        problem = stl_problem(g, spec.module)
        if problem:
            return "stl_not_watertight", problem
    except Exception as exc:  # noqa: BLE001
        return f"crash:{type(exc).__name__}", traceback.format_exc(limit=3)[-300:]
    return "ok", ""


# ---------------------------------------------------------------- worm-gear sets (as on main)


WORM_SOLID_FRACTION = float(os.environ.get("GEARGEN_SWEEP_SOLID_FRACTION", "0.1"))
#: a set with solids builds, checks and exports two (each 1-10 s on a busy 2-core machine, the
#: wheel's 1 um STL the most): more than the runner's default 60 s per set
WORM_TIMEOUT = float(os.environ.get("GEARGEN_SWEEP_TIMEOUT", "150"))
#: refusals that are the right answer for impossible parameters
WORM_KINDS = frozenset({"wheel_undercut"})


def worm_parameters(rng: np.random.Generator) -> dict:
    """One random worm-gear set (plain numbers); small worms (about one and a half leads long)
    to keep the sweep's CI time modest."""
    m = float(math.exp(rng.uniform(math.log(0.3), math.log(5.0))))
    return {
        "module": m,
        "starts": int(rng.integers(1, 5)),
        "wheel_teeth": int(round(math.exp(rng.uniform(math.log(14), math.log(80))))),
        "q": float(rng.uniform(6.0, 18.0)),
        "pressure_angle_deg": float(rng.uniform(14.5, 25.0)),
        "hand": str(rng.choice(["right", "left"])),
        "x2": float(rng.uniform(-0.5, 0.5)),
        "backlash_modules": float(rng.uniform(0.0, 0.05)) if rng.random() < 0.7 else 0.0,
        "backlash_on": str(rng.choice(["wheel", "worm"])),
        "face_fraction": float(rng.uniform(0.2, 1.0)),
        # the worm and wheel solids and their exports for one set in ten: the sweep's CI time; all by hand
        "build_solid": bool(rng.random() < WORM_SOLID_FRACTION),
    }


def worm_set(p: dict):
    from geargen.families.worm.spec import WormGearSet
    m = p["module"]
    d1 = p["q"] * m
    throat_radius = d1 / 2 - m
    return WormGearSet(axial_module=m, starts=p["starts"], wheel_teeth=p["wheel_teeth"], worm_reference_diameter=d1,
                       pressure_angle=math.radians(p["pressure_angle_deg"]), hand=p["hand"],
                       worm_face_length=max(2 * math.pi * m, 1.5 * math.pi * m * p["starts"]),
                       wheel_face_width=max(p["face_fraction"] * 1.7 * throat_radius, 0.5 * m),
                       wheel_profile_shift=p["x2"], backlash=p["backlash_modules"] * m, backlash_on=p["backlash_on"])


def exact_worm_volume(s) -> float:
    """Root cylinder plus thread filling t_x(r)/p_x of each axial line (see tests/cad/test_worm_solid.py)."""
    from scipy.integrate import quad

    from geargen.families.worm.geometry import worm_geometry
    g = worm_geometry(s)
    r1, L = s.worm_reference_diameter / 2, s.worm_face_length
    rf, ra = g.worm_root_diameter / 2, g.worm_tip_diameter / 2
    thread = quad(lambda r: 2 * math.pi * r * (g.worm_axial_thickness - 2 * (r - r1) * math.tan(g.axial_pressure_angle)),
                  rf, ra, epsabs=1e-14)[0]
    return math.pi * rf * rf * L + L * thread / g.axial_pitch


def _area(shape) -> float:
    """The solid's surface area (mm^2)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(shape, props)
    return props.Mass()


def _export_failure(part, expected_volume: float, tag: str, tolerance: float = 1e-7) -> tuple[str, str] | None:
    """The tagged failure of ``part``'s exports as the gear command writes them (issue 31: STEPs
    that read back with the wrong volume, STLs that were not closed), or None."""
    import tempfile

    import trimesh

    from geargen.cad.export import export_step, export_stl, read_step
    from geargen.cad.gear_solid import check_solid, solid_volume
    with tempfile.TemporaryDirectory() as folder:
        export_step(part, Path(folder) / "part.step")
        shape = read_step(Path(folder) / "part.step").shape
        problem = check_solid(shape)
        if problem:
            return tag + "step_invalid", problem
        vol = solid_volume(shape, 1e-9)
        # the in-memory solid's tolerance (relative): read back, the volume is the same
        if abs(vol / expected_volume - 1) > tolerance:
            return tag + "step_volume", f"{vol!r} vs {expected_volume!r} ({vol / expected_volume - 1:.2e})"
        export_stl(part, Path(folder) / "part.stl")
        mesh = trimesh.load(Path(folder) / "part.stl")
        if not (mesh.is_watertight and mesh.is_winding_consistent):
            return tag + "stl_open", f"{len(mesh.faces)} triangles"
    return None


def _wheel_volume(s) -> float:
    """Gauss-Legendre over z of the exact section areas (tests/cad/test_worm_wheel_solid.py)."""
    path = Path(__file__).parent / "cad" / "test_worm_wheel_solid.py"
    spec = importlib.util.spec_from_file_location("_wheel_solid_test", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.exact_wheel_volume(s, nodes=8)


def worm_check(p: dict) -> tuple[str, str]:
    """The wheel's envelope sections across the face, the pair check at the design centre distance
    (the design backlash within 2 um, no interference); for ``build_solid`` sets the worm (volume
    against the exact screw-solid formula) and the wheel (against Gauss-Legendre over z of the exact
    section areas) as valid solids."""
    from geargen.errors import DesignError, GeometryError
    try:
        s = worm_set(p)
        from geargen.families.worm.pair import worm_pair_check
        check = worm_pair_check(s, planes=5, samples=80)
    except DesignError as exc:
        return "design_error", exc.field.split(".")[-1]
    except GeometryError as exc:
        return f"geometry_error:{exc.kind}", str(exc)[:120]
    except Exception as exc:  # noqa: BLE001 - every other exception is a failure to tag
        return f"crash:{type(exc).__name__}", traceback.format_exc(limit=3)[-300:]
    try:
        if check.interference:
            return "interference", f"{check.to_dict()}"
        if abs(check.backlash - s.backlash) > 2e-3:
            return "backlash", f"{check.backlash!r} vs {s.backlash!r}"
        if not p["build_solid"]:
            return "ok", "sections and pair check"
        from geargen.families.worm.solid import build_worm
        from geargen.families.worm.spec import WormSpec
        worm = build_worm(WormSpec(s))
        exact = exact_worm_volume(s)
        # the 0.01 nm helices: measured within 2e-9 of the closed form (quad's own error ~1e-12)
        failure = _solid_failure(worm.shape, exact, 1e-7, "", eps=1e-7) or _export_failure(worm, exact, "")
        if failure:
            return failure
        from geargen.families.worm_wheel.solid import build_worm_wheel
        from geargen.families.worm.spec import WormWheelSpec
        wheel = build_worm_wheel(WormWheelSpec(s))
        exact = _wheel_volume(s)
        # the least-squares surfaces' mean offset from the envelope: within 1 nm over the wheel's
        # area (measured 0.14 nm on the two small wheels of seed 7 that were 1.0-1.5e-7 of their volume)
        tolerance = 1e-6 * _area(wheel.shape) / exact
        failure = (_solid_failure(wheel.shape, exact, tolerance, "wheel_", eps=1e-7)
                   or _export_failure(wheel, exact, "wheel_", tolerance))
        if failure:
            return failure
    except GeometryError as exc:  # the wheel's fit samples more planes than the pair check's five
        return f"geometry_error:{exc.kind}", str(exc)[:120]
    except Exception as exc:  # noqa: BLE001
        return f"crash:{type(exc).__name__}", traceback.format_exc(limit=3)[-300:]
    return "ok", ""


# ---------------------------------------------------------------- the registry


#: the families; ``per_push`` sized from each case's cost on one core (bench/bench_sweep_families.py
#: prints it; unloaded: external 0.2 s, double-helical 0.3, internal 0.1, rack 0.03, bevel 0.08, a
#: worm set 0.35 s, or ~30 s the one in ten that builds its two solids): ~30 s for the cylindrical
#: families, racks and bevels, ~25 s expected for the worm sets, within 90 s of one core
FAMILIES = {f.name: f for f in (
    Family("external", external_parameters, external_check, CYLINDRICAL_KINDS, full_count=200, per_push=40,
           full_seed=20261121, coverage=_fraction("ok", 0.5)),
    Family("double_helical", double_helical_parameters, double_helical_check, CYLINDRICAL_KINDS, full_count=100,
           per_push=24, coverage=lambda *a: _fraction("ok", 0.5)(*a) + _herringbones(*a)),
    Family("internal", internal_parameters, internal_check, INTERNAL_KINDS, full_count=100, per_push=40,
           coverage=_fraction("ok", 0.5)),
    Family("rack", rack_parameters, rack_check, frozenset(), full_count=120, per_push=60, coverage=_racks_built),
    Family("bevel", bevel_parameters, bevel_check, BEVEL_KINDS, full_count=100, per_push=60,
           coverage=_fraction("ok", 0.4)),
    Family("worm", worm_parameters, worm_check, WORM_KINDS, full_count=100, per_push=8, timeout=WORM_TIMEOUT,
           coverage=_fraction("ok", 0.5)),
)}
