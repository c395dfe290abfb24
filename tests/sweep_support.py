"""The seeded stability sweep's runner, shared by every gear family's sweep test.

Each parameter set is checked by ``check`` (``"path/to/file.py:function"``, a function of one
parameter dict returning ``(tag, detail)``) in a worker process, killed after ``timeout`` seconds
(tag ``timeout``); a worker that dies (a kernel segfault) tags ``crash:worker_died``. Workers are
spawned, not forked: the parent may hold kernel threads.
"""

from __future__ import annotations

import importlib.util
import multiprocessing as mp
import os
import time
from collections import Counter
from multiprocessing.connection import wait

TIMEOUT = float(os.environ.get("GEARGEN_SWEEP_TIMEOUT", "60"))
WORKERS = int(os.environ.get("GEARGEN_SWEEP_WORKERS", "2"))


def _load(check: str):
    path, function = check.rsplit(":", 1)
    spec = importlib.util.spec_from_file_location(f"_sweep_{abs(hash(path))}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return getattr(module, function)


def _worker(conn, check: str):
    fn = _load(check)
    while True:
        task = conn.recv()
        if task is None:
            return
        conn.send(fn(task))


def run_sweep(params: list[dict], check: str, timeout: float = TIMEOUT,
              workers: int = WORKERS) -> list[tuple[str, str, float]]:
    """(tag, detail, seconds) per parameter set; each checked in a worker, killed after ``timeout``."""
    ctx = mp.get_context("spawn")
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
                try:
                    tag, detail = s["conn"].recv()
                except EOFError:  # the worker died (segfault in the kernel)
                    tag, detail = "crash:worker_died", f"exit code {s['proc'].exitcode}"
                    s.update(start())
                results[s["task"]] = (tag, detail, now - s["t0"])
                give(s)
            elif now - s["t0"] > timeout:
                s["proc"].kill()
                results[s["task"]] = ("timeout", f"> {timeout} s", now - s["t0"])
                s.update(start())
                give(s)
    for s in slots:
        if s["proc"].is_alive():
            s["conn"].send(None)
            s["proc"].join(5)
    return results


def failures_of(params: list[dict], results, accepted) -> list[tuple[dict, tuple]]:
    """The (parameters, result) pairs whose tag ``accepted(tag)`` refuses."""
    return [(p, r) for p, r in zip(params, results) if not accepted(r[0])]


def summary(name: str, params: list[dict], results, seed: int) -> str:
    """One line: the tags counted, the builds' total time and the slowest case."""
    tags = Counter(r[0] for r in results)
    slowest = max(range(len(results)), key=lambda i: results[i][2])
    return (f"{name}: sweep of {len(params)} (seed {seed}): {dict(tags)}; total {sum(r[2] for r in results):.1f} s "
            f"of builds; slowest {results[slowest][2]:.2f} s: {params[slowest]}")


def assert_sweep(name: str, params: list[dict], results, seed: int, expected_kinds=frozenset()) -> Counter:
    """Print the sweep's summary and fail on every result that is neither ``ok``, a ``design_error``
    nor a ``geometry_error:KIND`` with KIND in ``expected_kinds`` (the refusals that are the right
    answer for impossible parameters); the tags counted, for the family's own coverage asserts."""
    print("\n" + summary(name, params, results, seed))

    def accepted(tag: str) -> bool:
        return tag in ("ok", "design_error") or (tag.startswith("geometry_error:")
                                                  and tag.split(":", 1)[1] in expected_kinds)
    failures = failures_of(params, results, accepted)
    for p, r in failures[:10]:
        print(r[0], r[1], p)
    assert not failures, f"{len(failures)} tagged failures: {Counter(r[0] for _, r in failures)}"
    return Counter(r[0] for r in results)
