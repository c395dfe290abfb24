"""Reading design tables: keys with unit suffixes, ranges, unknown and missing keys.

A :class:`Field` describes one key. Lengths and angles are written with their unit as a
suffix (``face_width_in``, ``pressure_angle_deg``) and come back in internal units (mm, rad);
ranges are given in internal units and reported back in the unit the user wrote.
"""

from __future__ import annotations

import difflib
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterable, Mapping

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
    ``units`` narrows the accepted suffixes of a length or angle (default: all). ``help`` is the
    key's one-line meaning, for the design-file reference (:mod:`geargen.design.reference`) and
    the comments of the starter designs (``geargen new``).
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


# ---------------------------------------------------------------- unknown keys: "did you mean"

_KEYBOARD_ROWS = ("1234567890", "qwertyuiop", "asdfghjkl", "zxcvbnm")
_KEY_POSITION = {c: (row, col + 0.5 * row) for row, keys in enumerate(_KEYBOARD_ROWS) for col, c in enumerate(keys)}


def _substitution_cost(a: str, b: str) -> float:
    """What typing ``a`` for ``b`` costs: nothing for the same letter, a quarter for the wrong
    case (``_nm`` for ``_Nm``), a half for a key next to it on the keyboard (``_mn`` for
    ``_mm``), one otherwise."""
    if a == b:
        return 0.0
    if a.lower() == b.lower():
        return 0.25
    pa, pb = _KEY_POSITION.get(a.lower()), _KEY_POSITION.get(b.lower())
    if pa and pb and abs(pa[0] - pb[0]) <= 1 and abs(pa[1] - pb[1]) <= 1:
        return 0.5
    return 1.0


def typo_distance(written: str, key: str) -> float:
    """Edit distance from ``written`` to ``key`` (insertions, deletions, swaps of two neighbours
    1 each; substitutions priced by :func:`_substitution_cost`), the measure by which
    :func:`close_keys` ranks its suggestions."""
    m, n = len(written), len(key)
    d = [[0.0] * (n + 1) for _ in range(m + 1)]
    for i in range(m + 1):
        d[i][0] = float(i)
    for j in range(n + 1):
        d[0][j] = float(j)
    for i in range(1, m + 1):
        for j in range(1, n + 1):
            d[i][j] = min(d[i - 1][j] + 1, d[i][j - 1] + 1,
                          d[i - 1][j - 1] + _substitution_cost(written[i - 1], key[j - 1]))
            if i > 1 and j > 1 and written[i - 1] == key[j - 2] and written[i - 2] == key[j - 1]:
                d[i][j] = min(d[i][j], d[i - 2][j - 2] + 1)
    return d[m][n]


def close_keys(written: str, known: Iterable[str], most: int = 3) -> list[str]:
    """The known keys ``written`` most likely meant, best first (empty when none is close).

    A key written without its unit suffix (``face_width``) gets the spellings that add one
    (``face_width_mm``, ``face_width_in``, ...); a shortened name with a unit suffix
    (``thinning_mm``) the longer names of that unit (``thinning_circumferential_mm``,
    ``thinning_normal_mm``). Otherwise the candidates are those :func:`difflib.get_close_matches`
    finds similar, ranked by :func:`typo_distance`, so a mistyped unit suffix finds the unit next
    to it on the keyboard (``face_width_mn`` -> ``face_width_mm``, not ``face_width_m``); keys
    tied for the closest are all given.
    """
    known = list(dict.fromkeys(known))
    with_unit = [k for k in known if k.startswith(written + "_")]
    if with_unit:
        return with_unit[:most]
    cuts = [i for i, c in enumerate(written) if c == "_"]
    for i in reversed(cuts):  # the longest name first: the most specific
        stem, suffix = written[:i + 1], "_" + written[i + 1:]
        longer = [k for k in known if k.startswith(stem) and k.endswith(suffix) and len(k) > len(written)]
        if longer:
            return longer[:most]
    similar = difflib.get_close_matches(written, known, n=len(known), cutoff=0.6)
    if not similar:
        return []
    ranked = sorted(similar, key=lambda k: (typo_distance(written, k), known.index(k)))
    best = typo_distance(written, ranked[0])
    return [k for k in ranked if typo_distance(written, k) == best][:most]


def _or_list(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " or " + items[-1]


def unknown_key(where: str, written: str, known: Iterable[str], allowed: str | None = None,
                problem: str = "unknown key") -> DesignError:
    """The error of the unknown key ``written`` (at the dotted path ``where``) of a table whose
    keys are ``known``: ``problem`` with "; did you mean ...?" when some known key is close."""
    suggestions = close_keys(written, known)
    return DesignError(where, problem + (f"; did you mean {_or_list(suggestions)}?" if suggestions else ""), allowed)


def raise_unknown_keys(errors: list[DesignError]) -> None:
    """Raise the unknown-key errors of one table: the error itself when there is one, else all
    of them together (:class:`DesignErrors`, which :class:`Problems` lists one by one)."""
    if len(errors) == 1:
        raise errors[0]
    if errors:
        raise DesignErrors(errors)


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


def read_table(data: Mapping[str, Any], fields: list[Field], where: str = "",
               read_elsewhere: Iterable[str] = ()) -> dict[str, Any]:
    """Validate ``data`` against ``fields``; return ``{field.name: value in internal units}``.

    Also returns, under ``"_units"``, the unit suffix each length/angle field was written in,
    so reports can echo the user's units. ``where`` is the dotted path of the table;
    ``read_elsewhere`` are further keys of the table that the caller reads itself (accepted
    here, offered as suggestions, not returned). Every unknown key of the table is reported, each
    with the closest known keys (:func:`close_keys`).
    """
    read_elsewhere = tuple(read_elsewhere)
    prefix = f"{where}." if where else ""
    if not isinstance(data, Mapping):
        raise DesignError(where or "<top>", "expected a table")
    owner: dict[str, Field] = {}
    for f in fields:
        for k in f.keys():
            owner[k] = f
    unknown = [k for k in data if k not in owner and k not in read_elsewhere]
    if unknown:
        known = list(owner) + list(read_elsewhere)
        allowed = ", ".join(sorted(known))
        raise_unknown_keys([unknown_key(prefix + k, k, known, allowed) for k in unknown])
    out: dict[str, Any] = {}
    units: dict[str, str] = {}
    problems = Problems()  # every problem of the table at once, not one per run
    for f in fields:
        present = [k for k in f.keys() if k in data]
        if len(present) > 1:
            problems.add(DesignError(prefix + present[1], f"given twice, also as {present[0]}", "one spelling"))
            continue
        if not present:
            if f.required:
                problems.add(DesignError(prefix + f.keys()[0] if len(f.keys()) == 1 else prefix + f.name,
                                         "missing", " or ".join(f.keys())))
            out[f.name] = f.default
            continue
        key = present[0]
        out[f.name] = problems.run(_convert, f, key, data[key], prefix + key)
        if f.kind in _UNIT_SUFFIXES:
            units[f.name] = key[len(f.name) + 1:]
    if problems.errors:
        raise problems.errors[0] if len(problems.errors) == 1 else DesignErrors(problems.errors)
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
