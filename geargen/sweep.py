"""Design sweeps on Dask: every design of a sweep file through the steps the other commands use.

Each design of :class:`geargen.design.sweep.SweepSpec` is one task, :func:`evaluate_design`:
the design file with the sweep's values set is loaded and validated (``geargen.design``),
resolved (:func:`geargen.model.resolve`: the synthesis and placement of ``synth``, ``check``
and ``build``), its stiffness summarised (:func:`geargen.model.analysis.stiffness`, what
``geargen stiffness`` prints) and checked (:func:`geargen.checks.verdict.verify`, the verdict of
``geargen check``, with its error-budget worst case and Monte Carlo per mesh). No step here
computes anything those commands do not.

With a ``[monte_carlo]`` block, each design that passes also gets the carriage-travel Monte Carlo
of ``geargen synth --monte-carlo`` (:func:`geargen.core.tolerance.monte_carlo`, the design's
``[monte_carlo]`` model), split into the sweep file's chunks: chunk ``i`` is its own task with
the generator ``SeedSequence(seed).spawn(chunks)[i]``, and the chunks are joined in chunk order
(:func:`geargen.core.tolerance.combine_monte_carlo`). Its 99.73 % travel range is turned into a
preload band by the stiffness model's own rule (:func:`geargen.core.stiffness.preload_variation`
of the loop error ``2 lambda travel``), like the Appendix budgets ``geargen stiffness`` reports.

Every task is a pure function of its arguments (the random values are drawn before any task
runs, the Monte Carlo chunks are fixed by the sweep file), so the table is the same whatever the
number of workers or the order they finish in. The work runs in processes (the CAD kernel
holds the GIL; none of these steps loads it): a ``distributed.LocalCluster`` of process
workers, one thread each, or an existing scheduler.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np

from geargen.design.sweep import SweepSpec, apply_values
from geargen.errors import DesignError, EnvironmentProblem, GeometryError

#: the Parquet file and the summary plot an output folder holds
TABLE = "sweep.parquet"
PLOT = "summary"
STATUS_OK, STATUS_REJECTED = "ok", "rejected"


@dataclass(frozen=True)
class MonteCarloInput:
    """What a Monte Carlo chunk of one design needs: the synthesis and its error budget, the
    design's ``[monte_carlo]`` model, and the drive model and lever that turn travel into preload
    (None where the preload carriage does not take up the loop errors)."""

    synthesis: Any
    errors: tuple
    model: str
    error_shape: str
    include_backlash_tolerance: bool
    drive: Any = None
    lever: float | None = None


@dataclass(frozen=True)
class DesignOutcome:
    """One design's row of the table, and its Monte Carlo input when it passed and has a budget."""

    row: dict[str, Any]
    monte_carlo: MonteCarloInput | None = None


def _tag(kind: str, where: str | None = None) -> str:
    return f"{kind}:{where}" if where else kind


def evaluate_design(design_path: str, data: dict[str, Any], values: dict[str, Any], index: int) -> DesignOutcome:
    """Load, resolve, summarise and check design ``index`` (``data`` with ``values`` set).

    Never raises for a bad design: the row's ``status`` is ``"rejected"`` and its ``tag`` says
    why (``invalid:<key>`` for the design file's validation, ``synthesis:<kind>`` when no drive
    can be placed, ``stiffness:<key>``, ``<check kind>:<mesh>`` for each failing check, joined by
    ``;``; ``geometry:<kind>`` for a geometry that cannot be made later on, ``error:<type>`` for
    anything else), ``message`` the full text. Numbers computed before
    the design was rejected stay in the row."""
    import hashlib

    from geargen.design.assembly import design_from_dict

    row: dict[str, Any] = {"design": index, **values, "status": STATUS_OK, "tag": "", "message": ""}

    def rejected(tag: str, message: str) -> DesignOutcome:
        row.update(status=STATUS_REJECTED, tag=tag, message=message)
        return DesignOutcome(row)

    path = Path(design_path)
    try:
        # from the parsed file, not the file: a worker of a remote scheduler need not see it
        digest = hashlib.sha256(json.dumps([data, values], sort_keys=True, default=str).encode()).hexdigest()
        design = design_from_dict(apply_values(data, values), path=path, sha256=digest, validate=True)
    except DesignError as exc:
        fields = [e.field for e in getattr(exc, "errors", [exc])]
        return rejected(";".join(_tag("invalid", f) for f in dict.fromkeys(fields)), str(exc))
    try:
        return _evaluate(design, row, rejected)
    except DesignError as exc:
        return rejected(_tag("invalid", exc.field), str(exc))
    except GeometryError as exc:
        return rejected(_tag("geometry", exc.kind), str(exc))
    except Exception as exc:  # noqa: BLE001 - tagged, not hidden: one odd design must not end a sweep
        return rejected(_tag("error", type(exc).__name__), f"{type(exc).__name__}: {exc}")


def _evaluate(design, row: dict[str, Any], rejected: Callable) -> DesignOutcome:
    from geargen.checks.verdict import verify
    from geargen.design.synthesis import monte_carlo_settings
    from geargen.drives import resolve
    from geargen.model.analysis import loop_error_travels, stiffness

    try:
        layout = resolve(design)
    except GeometryError as exc:
        return rejected(_tag("synthesis", exc.kind), str(exc))
    if layout.ratio:
        row["ratio"] = float(layout.ratio["total"])
    for m in layout.meshes:
        row[f"centre_distance_mm.{m.name}"] = m.centre_distance
    try:
        summary, _ = stiffness(design, layout)
    except DesignError as exc:
        return rejected(_tag("stiffness", exc.field), str(exc))
    travels, _ = loop_error_travels(layout)
    if summary is not None:
        d = summary.to_dict()  # the numbers of geargen stiffness --json, as it writes them
        row["drive_stiffness_Nm_per_rad"] = d["drive"]["stiffness_Nm_per_rad"]
        row["loop_stiffness_Nm_per_rad"] = d["loop"]["stiffness_Nm_per_rad"]
        row["preload_Nm"] = d["preload_Nm"]
        headline = next((v for v in d["preload_variation"] if v["label"] == d["headline_budget"]), None)
        row["preload_variation_Nm"] = headline["range_Nm"] if headline else math.nan
        row["preload_variation_budget"] = headline["label"] if headline else ""
        row["stiffness_warnings"] = len(d["warnings"])
    check = verify(layout)
    for entry in check.backlash:
        if "min" in entry:
            row[f"backlash_min_mm.{entry['mesh']}"] = entry["min"]
    for t in check.tolerances:
        row[f"worst_case_backlash_mm.{t.mesh}"] = t.worst_case_min_backlash
        row[f"mc_min_backlash_mm.{t.mesh}"] = t.monte_carlo_minimum if t.samples else math.nan
    failures = check.all_failures
    if failures:
        tags = dict.fromkeys(_tag(f.kind, f.mesh) for f in failures)
        return rejected(";".join(tags), "; ".join(f"{f.mesh or design.name}: {f.kind}: {f.message}" for f in failures))
    run = layout.synthesis
    mc = None
    if run is not None and run.errors is not None:
        settings = monte_carlo_settings(design)
        carriage = summary is not None and travels is not None
        mc = MonteCarloInput(run.synthesis, run.errors, settings.model, settings.error_shape,
                             settings.include_backlash_tolerance, summary.drive if carriage else None,
                             summary.lever if carriage else None)
    return DesignOutcome(row, mc)


def monte_carlo_chunk(outcome: DesignOutcome, samples: int, seed: np.random.SeedSequence):
    """One chunk of the carriage-travel Monte Carlo of a design (None for a design without one)."""
    from geargen.core.tolerance import monte_carlo
    mc = outcome.monte_carlo
    if mc is None:
        return None
    return monte_carlo(mc.synthesis, mc.errors, samples, np.random.default_rng(seed), model=mc.model,
                       error_shape=mc.error_shape, include_backlash_tolerance=mc.include_backlash_tolerance)


def monte_carlo_columns(outcome: DesignOutcome, chunks: list) -> dict[str, Any]:
    """The Monte Carlo columns of a design's row from its chunks in chunk order."""
    from geargen.core.stiffness import loop_error_from_carriage_travel, preload_variation
    from geargen.core.tolerance import combine_monte_carlo
    if outcome.monte_carlo is None or not chunks:
        return {}
    res = combine_monte_carlo(chunks)
    out: dict[str, Any] = {"mc_samples": res.samples, "mc_failed": res.failed}
    if not res.success:
        return out
    out.update(mc_travel_mean_mm=res.mean, mc_travel_std_mm=res.std, mc_travel_min_mm=res.minimum,
               mc_travel_max_mm=res.maximum, mc_travel_spread_99_73_mm=res.spread_99_73)
    mc = outcome.monte_carlo
    if mc.drive is not None:
        band = preload_variation(mc.drive, float(loop_error_from_carriage_travel(res.spread_99_73, mc.lever)),
                                 "monte carlo 99.73 %", res.spread_99_73, "monte carlo")
        out["mc_preload_variation_Nm"] = band.range * 1e-3  # N·mm -> N·m, as the stiffness columns
    return out


# ---------------------------------------------------------------- the parameters against the design


def check_parameters(design_path: Path, data: dict[str, Any], spec: SweepSpec) -> None:
    """Refuse, before any work, a parameter that names no key a design file may hold: each one's
    example value is set alone and the design read; an unknown-key error at that path, or any
    error inside a table the path added (``gears.inptu.teeth``), is the sweep file's mistake,
    raised naming ``parameters."<path>"``. (Values out of a key's range are not refused here:
    such designs are rejected and tagged.)"""
    from geargen.design.assembly import design_from_dict
    from geargen.design.sweep import missing_table
    for p in spec.parameters:
        added = missing_table(data, p.path)
        try:
            design_from_dict(apply_values(data, {p.path: p.example()}), path=design_path, validate=True)
        except DesignError as exc:
            for e in getattr(exc, "errors", [exc]):
                where = f'parameters."{p.path}"'
                if e.problem.startswith("unknown") and (p.path == e.field or p.path.startswith(e.field + ".")):
                    raise DesignError(where, f"names no key a design file may hold ({e.field}: {e.problem})",
                                      e.allowed) from None
                if added is not None and (e.field == added or e.field.startswith(added + ".")):
                    raise DesignError(where, f"the design file has no [{added}], and this key alone does not make "
                                      f"one ({e.field}: {e.problem})", "a key of a table the design file has "
                                      "(docs/design-files.md)") from None


# ---------------------------------------------------------------- running on Dask


@contextlib.contextmanager
def dask_client(workers: int | None = None, scheduler: str | None = None):
    """A ``distributed.Client``: on ``scheduler`` (an address) or on a new local cluster of
    ``workers`` process workers (default: every core), one thread each; closed on exit."""
    import logging

    from distributed import Client, LocalCluster
    if scheduler is not None:
        try:
            client = Client(scheduler, timeout=20)
        except (OSError, TimeoutError) as exc:
            raise EnvironmentProblem(f"--scheduler {scheduler}", f"cannot connect: {exc}",
                                     "the address of a running dask.distributed scheduler, e.g. tcp://host:8786") from None
        try:
            yield client
        finally:
            client.close()
        return
    import dask
    # distributed's default MALLOC_TRIM_THRESHOLD_ fixes glibc's mmap threshold, so every large
    # numpy temporary is mapped and faulted in afresh: the exact Monte Carlo ran 2.5x slower
    with dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
        cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                               dashboard_address=":0", silence_logs=logging.ERROR)
    try:
        with Client(cluster) as client:
            yield client
    finally:
        cluster.close()


@dataclass
class SweepResult:
    """A finished sweep: the table (one row per design, in design order) and what it took."""

    table: Any  # pandas.DataFrame
    spec: SweepSpec
    seconds: float
    workers: int
    notes: list[str] = field(default_factory=list)

    @property
    def counts(self) -> dict[str, int]:
        """Designs per tag ("ok" for those that passed)."""
        out: dict[str, int] = {}
        for status, tag in zip(self.table["status"], self.table["tag"]):
            key = STATUS_OK if status == STATUS_OK else tag
            out[key] = out.get(key, 0) + 1
        return out


def check_sweep(design_path: str | Path, spec: SweepSpec) -> dict[str, Any]:
    """What can be refused before any work: a bad base design (the user's error, not a rejected
    design) or one that is no drive, a parameter naming no key (:func:`check_parameters`), a Monte
    Carlo without an error budget. Returns the parsed design file the designs are made from."""
    from geargen.design.assembly import load_design
    from geargen.design.schema import load_toml
    from geargen.model import is_drive
    design_path = Path(design_path).resolve()
    base = load_design(design_path)
    if not is_drive(base):
        raise DesignError("layout", f"the design {design_path.name} is no drive: geargen sweep places each design",
                          "a design with [synthesis] or [layout], as geargen synth, check and build take")
    data = load_toml(design_path)
    check_parameters(design_path, data, spec)
    if spec.monte_carlo is not None and not base.section("errors"):
        raise DesignError("monte_carlo", f"the design {design_path.name} has no error budget ([errors.*]) to simulate",
                          "a design with [synthesis] and [errors.*], or no [monte_carlo] in the sweep file")
    return data


def run_sweep(design_path: str | Path, spec: SweepSpec, client, progress: Callable[[int, int], None] | None = None,
              data: dict[str, Any] | None = None) -> SweepResult:
    """Every design of ``spec`` on ``client``; the table comes back in design order. ``data``:
    the result of :func:`check_sweep` when the caller already ran it."""
    from distributed import as_completed

    t0 = time.perf_counter()
    design_path = Path(design_path).resolve()
    if data is None:
        data = check_sweep(design_path, spec)
    values = spec.designs()
    designs = [client.submit(evaluate_design, str(design_path), data, v, i, pure=False) for i, v in enumerate(values)]
    chunks: list[list] = []
    if spec.monte_carlo is not None:
        sizes, seeds = spec.monte_carlo.chunk_sizes(), spec.monte_carlo.seeds()
        chunks = [[client.submit(monte_carlo_chunk, f, n, s, pure=False) for n, s in zip(sizes, seeds)] for f in designs]
    if progress is not None:
        done = 0
        for _ in as_completed(designs):
            done += 1
            progress(done, len(designs))
    outcomes = client.gather(designs)
    rows = []
    for i, outcome in enumerate(outcomes):
        row = dict(outcome.row)
        if chunks:
            parts = client.gather(chunks[i])
            row.update(monte_carlo_columns(outcome, parts))
            if row.get("mc_failed"):
                row.update(status=STATUS_REJECTED, tag="monte_carlo:loop_not_closed",
                           message=f"{row['mc_failed']} of {row['mc_samples']} Monte Carlo samples do not close the loop")
        rows.append(row)
    table = _table(rows, spec)
    workers = len(client.nthreads())
    return SweepResult(table, spec, time.perf_counter() - t0, workers)


def _table(rows: list[dict[str, Any]], spec: SweepSpec):
    """The rows as a DataFrame: parameters as given (a column of lists or mixed kinds as JSON text),
    a ``pareto`` column marking the designs no other passing design beats on both drive stiffness
    and preload variation."""
    import pandas as pd
    for p in spec.parameters:
        col = [r[p.path] for r in rows]
        kinds = {type(v) for v in col}
        if kinds & {list, dict} or (str in kinds and len(kinds) > 1):
            for r in rows:
                r[p.path] = json.dumps(r[p.path])
    table = pd.DataFrame.from_records(rows)
    stiff, variation = preferred_axes(table)
    ok = (table["status"] == STATUS_OK).to_numpy()
    table["pareto"] = pareto_front(np.where(ok, stiff, np.nan), np.where(ok, variation, np.nan))
    return table


def preferred_axes(table) -> tuple[np.ndarray, np.ndarray]:
    """(drive stiffness N·m/rad, preload variation N·m) per row: the Monte Carlo's variation
    where the sweep ran one, else the design's headline budget's; NaN where not computed."""
    n = len(table)
    stiff = table["drive_stiffness_Nm_per_rad"].to_numpy(float) if "drive_stiffness_Nm_per_rad" in table else np.full(n, np.nan)
    column = "mc_preload_variation_Nm" if "mc_preload_variation_Nm" in table else "preload_variation_Nm"
    variation = table[column].to_numpy(float) if column in table else np.full(n, np.nan)
    return stiff, variation


def pareto_front(stiffness: np.ndarray, variation: np.ndarray) -> np.ndarray:
    """(n,) bool: the points no other point beats, that is none has at least the stiffness and at
    most the variation with one of the two strictly better; NaN points are never on the front."""
    x, y = np.asarray(stiffness, float), np.asarray(variation, float)
    finite = np.isfinite(x) & np.isfinite(y)
    out = np.zeros(x.size, bool)
    for i in np.flatnonzero(finite):
        others = finite.copy()
        others[i] = False
        beaten = others & (x >= x[i]) & (y <= y[i]) & ((x > x[i]) | (y < y[i]))
        out[i] = not beaten.any()
    return out


# ---------------------------------------------------------------- writing


def write_outputs(result: SweepResult, folder: Path, design_name: str) -> dict[str, Path]:
    """The Parquet table and the summary plot (PNG and SVG) into ``folder`` (an output folder's
    temporary work folder: the caller commits it)."""
    from geargen.outputs import atomic_path
    from geargen.report.sweep import write_summary_plot
    folder = Path(folder)
    path = folder / TABLE
    with atomic_path(path) as tmp:
        result.table.to_parquet(tmp, engine="pyarrow", index=False)
    files = {"table": path}
    files.update(write_summary_plot(result.table, [p.path for p in result.spec.parameters], folder / PLOT, design_name))
    return files


def print_summary(result: SweepResult, stream=None) -> None:
    """Counts per tag and the Pareto front, on ``stream`` (standard output)."""
    stream = stream or sys.stdout
    t = result.table
    n = len(t)
    print(f"{n} designs in {result.seconds:.1f} s on {result.workers} worker(s) "
          f"({result.seconds / max(n, 1):.2f} s per design)", file=stream)
    for tag, count in sorted(result.counts.items(), key=lambda kv: (kv[0] != STATUS_OK, -kv[1], kv[0])):
        print(f"  {count:>6}  {tag}", file=stream)
    front = t[t["pareto"]]
    if len(front):
        stiff, variation = preferred_axes(front)
        params = [p.path for p in result.spec.parameters]
        print("Pareto front (drive stiffness against preload variation):", file=stream)
        for (_, r), k, v in sorted(zip(front.iterrows(), stiff, variation), key=lambda x: -x[1]):
            values = ", ".join(f"{p} = {r[p]}" for p in params)
            print(f"  design {int(r['design']):>5}: {k:10.4g} N·m/rad, {v:10.4g} N·m   ({values})", file=stream)


__all__ = ["TABLE", "PLOT", "MonteCarloInput", "DesignOutcome", "evaluate_design", "monte_carlo_chunk",
           "monte_carlo_columns", "check_parameters", "check_sweep", "dask_client", "SweepResult", "run_sweep", "pareto_front",
           "preferred_axes", "write_outputs", "print_summary"]
