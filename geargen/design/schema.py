"""Reading design tables: keys with unit suffixes, ranges, unknown and missing keys.

A :class:`Field` describes one key. Lengths and angles are written with their unit as a
suffix (``face_width_in``, ``pressure_angle_deg``) and come back in internal units (mm, rad);
ranges are given in internal units and reported back in the unit the user wrote.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from geargen.errors import DesignError
from geargen.units import ANGLE_SUFFIXES, LENGTH_SUFFIXES

KINDS = ("length", "angle", "number", "integer", "string", "bool", "table", "list")

_UNIT_SUFFIXES = {"length": LENGTH_SUFFIXES, "angle": ANGLE_SUFFIXES}


@dataclass(frozen=True)
class Field:
    """One design-file key.

    ``name`` is the key without its unit suffix. ``minimum``/``maximum`` are in internal units
    (mm, rad) and inclusive unless ``exclusive_minimum``/``exclusive_maximum``. ``choices``
    restricts strings. A field with ``required=False`` takes ``default`` when absent.
    ``units`` narrows the accepted suffixes of a length or angle (default: all).
    """

    name: str
    kind: str
    required: bool = True
    default: Any = None
    minimum: float | None = None
    maximum: float | None = None
    exclusive_minimum: bool = False
    exclusive_maximum: bool = False
    choices: tuple = ()
    units: tuple[str, ...] = ()
    help: str = ""

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"Field {self.name}: kind must be one of {KINDS}")

    def suffixes(self) -> dict[str, float]:
        table = _UNIT_SUFFIXES.get(self.kind)
        if table is None:
            return {}
        if self.units:
            return {u: table[u] for u in self.units}
        return table

    def keys(self) -> list[str]:
        """The spellings this field accepts in a design file."""
        if self.kind in _UNIT_SUFFIXES:
            return [f"{self.name}_{u}" for u in self.suffixes()]
        return [self.name]


class DesignErrors(DesignError):
    """Several problems of one design file at once; ``errors`` lists them, each a
    :class:`DesignError` naming its key. ``field``, ``problem`` and ``allowed`` are the first's."""

    def __init__(self, errors: list[DesignError], source: str | None = None):
        self.errors = list(errors)
        first = self.errors[0]
        super().__init__(first.field, first.problem, first.allowed)
        where = f" in {source}" if source else ""
        self.args = (f"{len(self.errors)} problems{where}:\n" + "\n".join(f"  {e}" for e in self.errors),)


class Problems:
    """Collects the :class:`DesignError` s of a file so that all of them are reported together."""

    def __init__(self):
        self.errors: list[DesignError] = []

    def add(self, error: DesignError) -> None:
        if isinstance(error, DesignErrors):
            for e in error.errors:
                self.add(e)
        elif str(error) not in {str(e) for e in self.errors}:
            self.errors.append(error)

    def run(self, fn, *args, **kwargs):
        """``fn(*args, **kwargs)``, or None after recording the DesignError it raised."""
        try:
            return fn(*args, **kwargs)
        except DesignError as exc:
            self.add(exc)
            return None

    def raise_any(self, source: str | None = None) -> None:
        if len(self.errors) == 1:
            raise self.errors[0]
        if self.errors:
            raise DesignErrors(self.errors, source)


def _fmt(value: float) -> str:
    return f"{value:.6g}"


def bound_text(value: float, toward: str) -> str:
    """``value`` to 6 significant digits, rounded ``toward`` "down" (an upper bound) or "up" (a
    lower bound), so that the printed limit itself is allowed."""
    if value == 0 or not math.isfinite(value):
        return _fmt(value)
    quantum = 10.0 ** (math.floor(math.log10(abs(value))) - 5)
    steps = value / quantum
    steps = math.floor(steps) if toward == "down" else math.ceil(steps)
    return _fmt(steps * quantum)


def _range_text(field: Field, scale: float, unit: str) -> str:
    lo = None if field.minimum is None else field.minimum / scale
    hi = None if field.maximum is None else field.maximum / scale
    unit_text = f" {unit}" if unit else ""
    if lo is not None and hi is not None:
        left = "(" if field.exclusive_minimum else "["
        right = ")" if field.exclusive_maximum else "]"
        return f"{left}{_fmt(lo)}, {_fmt(hi)}{right}{unit_text}"
    if lo is not None:
        return f"{'>' if field.exclusive_minimum else '>='} {_fmt(lo)}{unit_text}"
    if hi is not None:
        return f"{'<' if field.exclusive_maximum else '<='} {_fmt(hi)}{unit_text}"
    return "any finite value"


def check_range(field: Field, value: float, where: str, scale: float = 1.0, unit: str = "") -> None:
    """Raise :class:`DesignError` if ``value`` (internal units) is outside the field's range."""
    if not math.isfinite(value):
        raise DesignError(where, "must be a finite number", _range_text(field, scale, unit))
    bad = False
    if field.minimum is not None:
        bad |= value < field.minimum or (field.exclusive_minimum and value == field.minimum)
    if field.maximum is not None:
        bad |= value > field.maximum or (field.exclusive_maximum and value == field.maximum)
    if bad:
        raise DesignError(where, f"{_fmt(value / scale)} is out of range", _range_text(field, scale, unit))


def _convert(field: Field, key: str, raw: Any, where: str) -> Any:
    if field.kind in ("length", "angle", "number"):
        if isinstance(raw, bool) or not isinstance(raw, (int, float)):
            raise DesignError(where, f"expected a number, got {raw!r}")
        if field.kind == "number":
            value = float(raw)
            check_range(field, value, where)
            return value
        unit = key[len(field.name) + 1:]
        scale = field.suffixes()[unit]
        value = float(raw) * scale
        check_range(field, value, where, scale, unit)
        return value
    if field.kind == "integer":
        if isinstance(raw, bool) or not isinstance(raw, int):
            raise DesignError(where, f"expected a whole number, got {raw!r}")
        check_range(field, float(raw), where)
        return int(raw)
    if field.kind == "string":
        if not isinstance(raw, str):
            raise DesignError(where, f"expected a string, got {raw!r}")
        if field.choices and raw not in field.choices:
            raise DesignError(where, f"{raw!r} is not a valid choice", ", ".join(map(repr, field.choices)))
        return raw
    if field.kind == "bool":
        if not isinstance(raw, bool):
            raise DesignError(where, f"expected true or false, got {raw!r}")
        return raw
    if field.kind == "table":
        if not isinstance(raw, dict):
            raise DesignError(where, f"expected a table, got {type(raw).__name__}")
        return raw
    if not isinstance(raw, list):
        raise DesignError(where, f"expected a list, got {type(raw).__name__}")
    return raw


def read_table(data: Mapping[str, Any], fields: list[Field], where: str = "") -> dict[str, Any]:
    """Validate ``data`` against ``fields``; return ``{field.name: value in internal units}``.

    Also returns, under ``"_units"``, the unit suffix each length/angle field was written in,
    so reports can echo the user's units. ``where`` is the dotted path of the table.
    """
    prefix = f"{where}." if where else ""
    if not isinstance(data, Mapping):
        raise DesignError(where or "<top>", "expected a table")
    owner: dict[str, Field] = {}
    for f in fields:
        for k in f.keys():
            owner[k] = f
    unknown = [k for k in data if k not in owner]
    if unknown:
        allowed = ", ".join(sorted(owner))
        raise DesignError(prefix + unknown[0], "unknown key", allowed)
    out: dict[str, Any] = {}
    units: dict[str, str] = {}
    for f in fields:
        present = [k for k in f.keys() if k in data]
        if len(present) > 1:
            raise DesignError(prefix + present[1], f"given twice, also as {present[0]}", "one spelling")
        if not present:
            if f.required:
                raise DesignError(prefix + f.keys()[0] if len(f.keys()) == 1 else prefix + f.name,
                                  "missing", " or ".join(f.keys()))
            out[f.name] = f.default
            continue
        key = present[0]
        out[f.name] = _convert(f, key, data[key], prefix + key)
        if f.kind in _UNIT_SUFFIXES:
            units[f.name] = key[len(f.name) + 1:]
    out["_units"] = units
    return out


def load_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML design file; syntax errors name the file and the line."""
    path = Path(path)
    try:
        with path.open("rb") as fh:
            return tomllib.load(fh)
    except FileNotFoundError:
        raise DesignError(str(path), "no such design file") from None
    except tomllib.TOMLDecodeError as exc:
        raise DesignError(str(path), f"not valid TOML: {exc}") from None
