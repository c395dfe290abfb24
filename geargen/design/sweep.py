"""Sweep files: which design-file keys ``geargen sweep`` varies, how, and the Monte Carlo per design.

Layout of the TOML (docs/sweep-files.md)::

    [parameters]                                  # design-file keys by their dotted path
    "gears.input.teeth" = [15, 16, 17]            # a list: grid values (cartesian product)
    "errors.output.pitch_line_eccentricity_tir_in" = { uniform = [0.0006, 0.0018] }   # random

    [random]                                      # needed when a parameter is random
    count = 8                                     # random draws per grid point
    seed = 7

    [monte_carlo]                                 # optional: the carriage-travel Monte Carlo of synth
    samples = 40000
    chunk_size = 10000
    seed = 1994

Designs are the grid's points (in the order of the file's lists, the last parameter fastest),
each with every random draw: ``grid points x count`` designs. Draw ``j`` takes its values from
``default_rng(SeedSequence(seed).spawn(count)[j])``, the same at every grid point (common random
numbers: two grid points differ only by the grid values); the Monte Carlo's chunk ``i`` uses
``SeedSequence(monte_carlo.seed).spawn(chunks)[i]`` for every design. Values are drawn here, with
numpy only; nothing depends on how the work is later spread over processes.
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from geargen.design.schema import Problems, load_toml, unknown_key
from geargen.errors import DesignError

SECTIONS = ("parameters", "random", "monte_carlo")
#: distribution -> what its two-element (or longer, for choice) list means
DISTRIBUTIONS = {
    "uniform": "[low, high]: uniform between the two",
    "normal": "[mean, standard deviation]",
    "integers": "[low, high]: whole numbers, both ends included",
    "choice": "[value, value, ...]: one of the values, equally likely",
}
MAX_DESIGNS = 100_000
MAX_DRAWS = 100_000
MAX_SAMPLES = 1_000_000_000
MAX_CHUNK = 10_000_000
MAX_CHUNKS = 100_000
_PATH = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)+$")


@dataclass(frozen=True)
class Parameter:
    """One varied design-file key: ``values`` (grid) or ``distribution`` with its ``arguments`` (random)."""

    path: str
    values: tuple = ()
    distribution: str | None = None
    arguments: tuple = ()

    @property
    def is_random(self) -> bool:
        return self.distribution is not None

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(self.path.split("."))

    def example(self) -> Any:
        """A value the parameter takes (the first grid value, the distribution's low end or mean)."""
        if not self.is_random:
            return self.values[0]
        return self.arguments[0]

    def draw(self, rng: np.random.Generator) -> Any:
        a = self.arguments
        if self.distribution == "uniform":
            return float(rng.uniform(a[0], a[1]))
        if self.distribution == "normal":
            return float(rng.normal(a[0], a[1]))
        if self.distribution == "integers":
            return int(rng.integers(a[0], a[1], endpoint=True))
        return a[int(rng.integers(len(a)))]


@dataclass(frozen=True)
class MonteCarloBlock:
    """``[monte_carlo]`` of a sweep: ``samples`` per design in chunks of ``chunk_size`` (the last
    may be shorter), chunk ``i`` seeded by ``SeedSequence(seed).spawn(chunks)[i]``."""

    samples: int
    chunk_size: int
    seed: int

    @property
    def chunks(self) -> int:
        return -(-self.samples // self.chunk_size)

    def chunk_sizes(self) -> list[int]:
        return [min(self.chunk_size, self.samples - i * self.chunk_size) for i in range(self.chunks)]

    def seeds(self) -> list[np.random.SeedSequence]:
        return np.random.SeedSequence(self.seed).spawn(self.chunks)


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep file."""

    parameters: tuple[Parameter, ...]
    count: int = 1
    seed: int | None = None
    monte_carlo: MonteCarloBlock | None = None
    path: Path | None = None

    @property
    def grid(self) -> tuple[Parameter, ...]:
        return tuple(p for p in self.parameters if not p.is_random)

    @property
    def random(self) -> tuple[Parameter, ...]:
        return tuple(p for p in self.parameters if p.is_random)

    @property
    def grid_points(self) -> int:
        return math.prod(len(p.values) for p in self.grid)

    @property
    def size(self) -> int:
        return self.grid_points * self.count

    def designs(self) -> list[dict[str, Any]]:
        """Every design's values ``{path: value}`` in the file's parameter order; design
        ``g * count + j`` is grid point ``g`` with random draw ``j``."""
        draws = [{} for _ in range(self.count)]
        if self.random:
            for j, child in enumerate(np.random.SeedSequence(self.seed).spawn(self.count)):
                rng = np.random.default_rng(child)
                draws[j] = {p.path: p.draw(rng) for p in self.random}
        out = []
        for point in itertools.product(*(p.values for p in self.grid)):
            fixed = dict(zip((p.path for p in self.grid), point))
            for draw in draws:
                merged = {**fixed, **draw}
                out.append({p.path: merged[p.path] for p in self.parameters})
        return out


def _int_in(table: Mapping, key: str, where: str, low: int, high: int, problems: Problems,
            required: bool = True) -> int | None:
    if key not in table:
        if required:
            problems.add(DesignError(f"{where}.{key}", "missing", f"a whole number from {low:,} to {high:,}"))
        return None
    v = table[key]
    if isinstance(v, bool) or not isinstance(v, int) or not low <= v <= high:
        problems.add(DesignError(f"{where}.{key}", f"{v!r} is out of range", f"a whole number from {low:,} to {high:,}"))
        return None
    return v


def _number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _parameter(path: str, value, problems: Problems) -> Parameter | None:
    where = f'parameters."{path}"'
    if not _PATH.match(path):
        problems.add(DesignError(where, "not a dotted path of a design-file key",
                                 'section.key or section.table.key as in the design file, quoted: "gears.input.teeth"'))
        return None
    if isinstance(value, list):
        if not value:
            problems.add(DesignError(where, "an empty list", "one value or more (a grid), or a distribution table"))
            return None
        return Parameter(path, values=tuple(value))
    if isinstance(value, dict):
        if len(value) != 1 or next(iter(value)) not in DISTRIBUTIONS:
            given = ", ".join(value) or "an empty table"
            problems.add(DesignError(where, f"{given} is not a distribution",
                                     "one of " + "; ".join(f"{{{k} = {v}}}" for k, v in DISTRIBUTIONS.items())))
            return None
        kind, args = next(iter(value.items()))
        what = f"{where}.{kind}"
        if not isinstance(args, list):
            problems.add(DesignError(what, f"{args!r} is not a list", DISTRIBUTIONS[kind]))
            return None
        if kind == "choice":
            if not args:
                problems.add(DesignError(what, "an empty list", DISTRIBUTIONS[kind]))
                return None
        elif len(args) != 2 or not all(_number(a) for a in args):
            problems.add(DesignError(what, f"{args!r} is not two numbers", DISTRIBUTIONS[kind]))
            return None
        elif kind == "integers" and not all(isinstance(a, int) for a in args):
            problems.add(DesignError(what, f"{args!r} are not whole numbers", DISTRIBUTIONS[kind]))
            return None
        elif kind in ("uniform", "integers") and not args[0] <= args[1]:
            problems.add(DesignError(what, f"low {args[0]!r} is above high {args[1]!r}", DISTRIBUTIONS[kind]))
            return None
        elif kind == "normal" and not args[1] >= 0:
            problems.add(DesignError(what, f"standard deviation {args[1]!r} is negative", DISTRIBUTIONS[kind]))
            return None
        return Parameter(path, distribution=kind, arguments=tuple(args))
    problems.add(DesignError(where, f"{value!r} is neither a list nor a distribution",
                             "a list of values (grid), e.g. [15, 16, 17], or a distribution table, e.g. "
                             "{uniform = [0.0006, 0.0018]}"))
    return None


def sweep_from_dict(data: Mapping[str, Any], path: Path | None = None) -> SweepSpec:
    """A :class:`SweepSpec` from a parsed sweep file; every problem is reported at once, each
    naming its key (``parameters."gears.input.teeth"``, ``monte_carlo.chunk_size``) and what is allowed."""
    problems = Problems()
    for key in data:
        if key not in SECTIONS:
            problems.add(unknown_key(key, key, SECTIONS, ", ".join(f"[{s}]" for s in SECTIONS),
                                     "unknown section of a sweep file"))
    tables = {}
    for s in SECTIONS:
        t = data.get(s, {})
        if not isinstance(t, dict):
            problems.add(DesignError(s, f"expected a table, got {type(t).__name__}", f"a [{s}] table"))
            t = {}
        tables[s] = t
    if not tables["parameters"]:
        problems.add(DesignError("parameters", "missing or empty: nothing to vary",
                                 '[parameters] with design-file keys by dotted path, e.g. "gears.input.teeth" = [15, 16]'))
    parameters = [p for k, v in tables["parameters"].items() if (p := _parameter(k, v, problems)) is not None]
    for a, b in itertools.permutations(parameters, 2):
        if b.path.startswith(a.path + "."):
            problems.add(DesignError(f'parameters."{b.path}"', f'lies inside parameters."{a.path}", which also varies',
                                     "keys that do not contain each other"))
    rnd = tables["random"]
    for key in rnd:
        if key not in ("count", "seed"):
            problems.add(unknown_key(f"random.{key}", key, ("count", "seed"), "count, seed"))
    count, seed = 1, None
    if any(p.is_random for p in parameters):
        count = _int_in(rnd, "count", "random", 1, MAX_DRAWS, problems) or 1
        seed = _int_in(rnd, "seed", "random", 0, 2**63 - 1, problems)
    elif rnd:
        problems.add(DesignError("random", "no parameter is random",
                                 "a parameter given as a distribution, or no [random] table"))
    mc = None
    mct = tables["monte_carlo"]
    if mct:
        for key in mct:
            if key not in ("samples", "chunk_size", "seed"):
                problems.add(unknown_key(f"monte_carlo.{key}", key, ("samples", "chunk_size", "seed"),
                                         "samples, chunk_size, seed"))
        samples = _int_in(mct, "samples", "monte_carlo", 1, MAX_SAMPLES, problems)
        chunk = _int_in(mct, "chunk_size", "monte_carlo", 1, MAX_CHUNK, problems)
        mc_seed = _int_in(mct, "seed", "monte_carlo", 0, 2**63 - 1, problems)
        if None not in (samples, chunk, mc_seed):
            mc = MonteCarloBlock(samples, chunk, mc_seed)
            if mc.chunks > MAX_CHUNKS:
                problems.add(DesignError("monte_carlo.chunk_size", f"{chunk:,} makes {mc.chunks:,} chunks of "
                                         f"{samples:,} samples", f"at least {-(-samples // MAX_CHUNKS):,} "
                                         f"(at most {MAX_CHUNKS:,} chunks)"))
    spec = SweepSpec(tuple(parameters), count, seed, mc, path)
    if parameters and spec.size > MAX_DESIGNS:
        problems.add(DesignError("parameters", f"{spec.size:,} designs ({spec.grid_points:,} grid points x "
                                 f"{spec.count:,} draws)", f"at most {MAX_DESIGNS:,}"))
    problems.raise_any(path.name if path else None)
    return spec


def load_sweep(path: str | Path) -> SweepSpec:
    """Read and validate a sweep file (:func:`sweep_from_dict`)."""
    path = Path(path).resolve()
    return sweep_from_dict(load_toml(path), path)


def missing_table(data: Mapping[str, Any], path: str) -> str | None:
    """The first table on ``path`` that the parsed design ``data`` lacks (``"checks"`` for
    ``"checks.seed"`` in a file without ``[checks]``), or None."""
    keys = path.split(".")
    table = data
    for i, key in enumerate(keys[:-1]):
        table = table.get(key) if isinstance(table, Mapping) else None
        if table is None:
            return ".".join(keys[:i + 1])
    return None


def apply_values(data: Mapping[str, Any], values: Mapping[str, Any]) -> dict[str, Any]:
    """A copy of the parsed design ``data`` with each ``{dotted path: value}`` set, as the file
    could have written it: a missing key or table on the path is added."""
    import copy
    out = copy.deepcopy(dict(data))
    for path, value in values.items():
        keys = path.split(".")
        table = out
        for i, key in enumerate(keys[:-1]):
            nxt = table.setdefault(key, {})
            if not isinstance(nxt, dict):
                raise DesignError(f'parameters."{path}"', f"{'.'.join(keys[:i + 1])} is a value in the design file, "
                                  "not a table", "a path through the design file's tables to a key")
            table = nxt
        table[keys[-1]] = value
    return out


__all__ = ["SECTIONS", "DISTRIBUTIONS", "Parameter", "MonteCarloBlock", "SweepSpec", "sweep_from_dict", "load_sweep",
           "missing_table", "apply_values"]
