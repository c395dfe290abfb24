"""Reading design tables: keys with unit suffixes, ranges, unknown and missing keys.

A :class:`Field` describes one key. Lengths and angles are written with their unit as a
suffix (``face_width_in``, ``pressure_angle_deg``) and come back in internal units (mm, rad);
ranges are given in internal units and reported back in the unit the user wrote.
"""

from __future__ import annotations

import difflib
import math
import os
import re
import tomllib
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Iterable, Mapping

from geargen.errors import DesignError
from geargen.units import ANGLE_SUFFIXES, LENGTH_SUFFIXES

KINDS = ("length", "angle", "number", "integer", "string", "name", "bool", "table", "list")

_UNIT_SUFFIXES = {"length": LENGTH_SUFFIXES, "angle": ANGLE_SUFFIXES}


@dataclass(frozen=True)
class Field:
    """One design-file key.

    ``name`` is the key without its unit suffix. ``minimum``/``maximum`` are in internal units
    (mm, rad) and inclusive unless ``exclusive_minimum``/``exclusive_maximum``. ``choices``
    restricts strings; a string's ``maximum`` makes it a text the drawing prints, of at most that many
    characters (:func:`check_drawn_text`). A field with ``required=False`` takes ``default`` when absent.
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



# ---------------------------------------------------------------- names that become file names

#: what a name may be made of: a design's, a gear's, a stage's name becomes file names
#: (``NAME.step``, ``drawings/NAME.json``, ``carrier_NAME.stl``), STEP product names and labels
#: on drawings. ASCII letters, digits, "_", "-" and ".", not first a "." (a hidden file, "..");
#: no separator, space or control character, so no name can point outside its output folder, and
#: every file system and CAD reader takes it as it is
NAME_PATTERN = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]*")
#: the most characters of a gear's name: what the manufacturing drawing's gear data block
#: (geargen.report.drawing, 235 mm of rows at ISO 3098's 3.5 mm lettering) holds in every case a
#: placed drive gives, a gear with two mating gears (a split pinion's output) all three of names
#: this long in the widest letter ("m") and a design file path of 100 characters: 17 fit, 18
#: overflow it (tests/design/test_names.py draws it)
GEAR_NAME_MAX = 16
#: the most characters of any other name (a design's, a stage's, a stiffness component's): they
#: go into file names with a suffix of up to 25 characters, far inside the 255 bytes a file name may have
NAME_MAX = 64
#: names whose files geargen writes itself into the same folder as a gear's or part's files
#: (``manifest.json``, the build's ``assembly.step``): a gear of that name would overwrite them.
#: Compared without case, as macOS and Windows compare file names.
RESERVED_NAMES = ("manifest", "assembly")
#: the characters a text printed on a drawing as the designer wrote it (part number, revision, material,
#: heat treatment: a Field of kind "string" with a ``maximum``) may hold: one line of Latin-1, Latin
#: Extended-A but the ligatures Œ œ, Greek but the yot U+037F (the font lacks it), the dashes, quotes
#: and ellipsis U+2010..U+2027 and − ≈ ≠ ≤ ≥. The drawing font (DejaVu Sans) draws each, none wider than "m" (3.53 mm at 10 pt), so a
#: length limit measured in "m" holds for any of them (tests/report/test_drawn_text_limits.py)
DRAWN_TEXT_RANGES = ((0x20, 0x7E), (0xA0, 0x17F), (0x370, 0x3FF), (0x2010, 0x2027))
DRAWN_TEXT_EXTRA = "−≈≠≤≥"
DRAWN_TEXT_EXCLUDED = "\u0152\u0153\u037f"  # Œ œ and the Greek yot


def drawn_character(c: str) -> bool:
    """Whether a drawing may print ``c`` in a designer's text (:data:`DRAWN_TEXT_RANGES`)."""
    if not c.isprintable() or c in DRAWN_TEXT_EXCLUDED:
        return False
    return c in DRAWN_TEXT_EXTRA or any(lo <= ord(c) <= hi for lo, hi in DRAWN_TEXT_RANGES)


def drawn_text_rule(most: int) -> str:
    """The allowed values of a drawn text of at most ``most`` characters, as an error states them."""
    return (f"at most {most} characters (what its cell of the drawing holds) on one line: Latin and Greek "
            "letters, digits, punctuation")


def check_drawn_text(where: str, value: str, most: int) -> str:
    """``value`` when the drawing holds it in its cell (:func:`drawn_character`, ``most`` characters),
    else a :class:`DesignError` naming ``where`` and the allowed length."""
    bad = next((i for i, c in enumerate(value) if not drawn_character(c)), None)
    if bad is not None:
        raise DesignError(where, f"{shown(value)} holds {value[bad]!r} (character {bad + 1}), which the drawing "
                          "does not print", drawn_text_rule(most))
    if len(value) > most:
        raise DesignError(where, f"{shown(value)} is {len(value):,} characters long", drawn_text_rule(most))
    return value


#: the most characters of a string that is no name (a description, a material): far more than
#: any sentence a design file needs; a longer one (a 50 MB name) would only slow every writer
STRING_MAX = 2000


def shown(value: Any, most: int = 60) -> str:
    """``repr(value)``, cut to about ``most`` characters (a message never repeats a huge value)."""
    text = repr(value)
    return text if len(text) <= most else f"{text[:most - 15]}...{text[-12:]}"


def name_rule(most: int) -> str:
    """The allowed names, as an error message says them."""
    return (f"at most {most} characters: letters A-Z a-z, digits, '_', '-' and '.', starting with a letter or "
            f"digit; not {' or '.join(map(repr, RESERVED_NAMES))} (it names files)")


def check_name(where: str, value: Any, most: int = NAME_MAX) -> str:
    """``value`` when it is a valid name of at most ``most`` characters (:data:`NAME_PATTERN`),
    else a :class:`DesignError` naming ``where`` and the first thing wrong with it."""
    allowed = name_rule(most)
    if not isinstance(value, str):
        raise DesignError(where, f"expected a name, got {shown(value)}", allowed)
    if not NAME_PATTERN.fullmatch(value):
        if not value:
            raise DesignError(where, "is empty", allowed)
        bad = next((i for i, c in enumerate(value) if not NAME_PATTERN.fullmatch("a" + c)), 0)
        what = f"starts with {value[0]!r}" if bad == 0 else f"holds {value[bad]!r} (character {bad + 1})"
        raise DesignError(where, f"{shown(value)} {what}: not a valid name", allowed)
    if len(value) > most:
        raise DesignError(where, f"{shown(value)} is {len(value):,} characters long", allowed)
    if value.casefold() in RESERVED_NAMES:
        raise DesignError(where, f"{value!r} is the name of a file geargen writes beside it", allowed)
    return value


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
    if len(written) > 2 * max(map(len, known), default=0):  # far longer than any key: no typo of one
        return []
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


def number_text(value: float) -> str:
    return f"{value:.6g}"


def bound_text(value: float, toward: str) -> str:
    """``value`` to 6 significant digits, rounded ``toward`` "down" (an upper bound) or "up" (a
    lower bound), so that the printed limit itself is allowed."""
    if value == 0 or not math.isfinite(value):
        return number_text(value)
    quantum = 10.0 ** (math.floor(math.log10(abs(value))) - 5)
    steps = value / quantum
    steps = math.floor(steps) if toward == "down" else math.ceil(steps)
    return number_text(steps * quantum)


#: The plausible magnitudes of a value of each kind, or quantity family (internal units), as
#: (smallest nonzero, largest): the bounds of a key on each side where it sets none of its own.
#: Far beyond any drive geargen designs, yet finite, so an absurd number (1e300, an exponent typed
#: wrong) is refused naming its key before the model computes with it and overflows to inf or NaN;
#: and a key that must be positive (a stiffness, a length something is divided by) is at least the
#: smallest, never a 1e-300 that divides to infinity.
PLAUSIBLE: dict[str, tuple[float, float]] = {
    "length": (1e-6, 1e4),                # mm: 1 nm, below any measurement here, to 10 m, beyond any gearbox
    "angle": (1e-9, 2 * math.pi),         # rad: 1 nrad to a full turn
    "number": (1e-9, 1e6),                # ratios, coefficients, forces in N, rates in N/mm
    "integer": (1, 2 ** 63 - 1),          # counts and seeds: TOML's own integer range
    "force": (1e-6, 1e8),                 # N: to 10,000 t
    "torque": (1e-6, 1e11),               # N·mm: to 100,000 kN·m
    "linear_stiffness": (1e-9, 1e12),     # N/mm: to 10^9 N/um
    "torsional_stiffness": (1e-6, 1e18),  # N·mm/rad: to 10^15 N·m/rad, far stiffer than a 1 m shaft
    "stress": (1e-6, 1e7),                # MPa: to 10 TPa (diamond's modulus is 1.2 TPa)
    "inertia": (1e-15, 1e9),              # kg·m²
    "rotary_damping": (1e-12, 1e12),      # N·m·s/rad
    "torque_constant": (1e-6, 1e4),       # N·m/A
    "frequency": (1e-6, 1e9),             # Hz
}


def plausible(field: Field, family: str | None = None) -> Field:
    """``field`` with the :data:`PLAUSIBLE` bounds of its kind (or of the quantity ``family``) on
    each side where it sets none: a largest value; a smallest, the negative of it, for a signed key;
    the smallest nonzero magnitude for a key that must be above zero."""
    bounds = PLAUSIBLE.get(family or field.kind)
    if bounds is None:
        return field
    smallest, largest = bounds
    minimum, maximum, exclusive_minimum = field.minimum, field.maximum, field.exclusive_minimum
    if maximum is None:
        maximum = largest
    if minimum is None:
        minimum, exclusive_minimum = -largest, False
    elif minimum == 0 and exclusive_minimum:
        minimum, exclusive_minimum = smallest, False
    return replace(field, minimum=minimum, maximum=maximum, exclusive_minimum=exclusive_minimum)


def field_range_text(field: Field, scale: float, unit: str) -> str:
    lo = None if field.minimum is None else field.minimum / scale
    hi = None if field.maximum is None else field.maximum / scale
    unit_text = f" {unit}" if unit else ""
    if lo is not None and hi is not None:
        left = "(" if field.exclusive_minimum else "["
        right = ")" if field.exclusive_maximum else "]"
        return f"{left}{number_text(lo)}, {number_text(hi)}{right}{unit_text}"
    if lo is not None:
        return f"{'>' if field.exclusive_minimum else '>='} {number_text(lo)}{unit_text}"
    if hi is not None:
        return f"{'<' if field.exclusive_maximum else '<='} {number_text(hi)}{unit_text}"
    return "any finite value"


def check_range(field: Field, value: float, where: str, scale: float = 1.0, unit: str = "",
                family: str | None = None) -> None:
    """Raise :class:`DesignError` if ``value`` (internal units) is outside the field's range, or
    outside the :func:`plausible` range of its kind (or quantity ``family``) where it sets none."""
    field = plausible(field, family)
    if not math.isfinite(value):
        raise DesignError(where, "must be a finite number", field_range_text(field, scale, unit))
    bad = False
    if field.minimum is not None:
        bad |= value < field.minimum or (field.exclusive_minimum and value == field.minimum)
    if field.maximum is not None:
        bad |= value > field.maximum or (field.exclusive_maximum and value == field.maximum)
    if bad:
        raise DesignError(where, f"{number_text(value / scale)} is out of range", field_range_text(field, scale, unit))


def as_float(raw: int | float, where: str) -> float:
    """``float(raw)``; an integer too big for a float (TOML integers have any number of digits
    here) is out of range, named."""
    try:
        return float(raw)
    except OverflowError:
        raise DesignError(where, f"{shown(raw)} is out of range", "a number below 1e308") from None


def _convert(field: Field, key: str, raw: Any, where: str) -> Any:
    if field.kind in ("length", "angle", "number"):
        if isinstance(raw, bool) or not isinstance(raw, (int, float)):
            raise DesignError(where, f"expected a number, got {shown(raw)}")
        if field.kind == "number":
            value = as_float(raw, where)
            check_range(field, value, where)
            return value
        unit = key[len(field.name) + 1:]
        scale = field.suffixes()[unit]
        value = as_float(raw, where) * scale
        check_range(field, value, where, scale, unit)
        return value
    if field.kind == "integer":
        if isinstance(raw, bool) or not isinstance(raw, int):
            raise DesignError(where, f"expected a whole number, got {shown(raw)}")
        check_range(field, as_float(raw, where), where)
        return int(raw)
    if field.kind == "name":
        return check_name(where, raw, int(field.maximum) if field.maximum is not None else NAME_MAX)
    if field.kind == "string":
        if not isinstance(raw, str):
            raise DesignError(where, f"expected a string, got {shown(raw)}")
        if field.choices and raw not in field.choices:
            raise DesignError(where, f"{shown(raw)} is not a valid choice", ", ".join(map(repr, field.choices)))
        if len(raw) > STRING_MAX:
            raise DesignError(where, f"{shown(raw)} is {len(raw):,} characters long", f"at most {STRING_MAX:,}")
        if field.maximum is not None:  # a text the drawing prints
            return check_drawn_text(where, raw, int(field.maximum))
        return raw
    if field.kind == "bool":
        if not isinstance(raw, bool):
            raise DesignError(where, f"expected true or false, got {shown(raw)}")
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


#: the largest design file read (bytes): the shipped ones are under 20 kB; a bigger file is not a
#: design someone wrote, and reading it whole would only delay the refusal
MAX_FILE_BYTES = 4 * 1024 * 1024
#: the deepest nesting of tables and arrays a design file may have (the file itself is 1): the
#: shipped ones reach 5 (a list in [stiffness.components.NAME]); far deeper, the TOML reader runs
#: out of Python's stack, and no design has such a structure
MAX_NESTING = 16
_BOM = b"\xef\xbb\xbf"


def _too_big(source: str, size: int) -> DesignError:
    return DesignError(source, f"is {size:,} bytes: too big for a design file",
                       f"a TOML file of at most {MAX_FILE_BYTES:,} bytes")


def toml_text(data: bytes, source: str) -> str:
    """The text of a TOML file's bytes, or a :class:`DesignError` naming ``source`` and why not.

    A UTF-8 byte-order mark is accepted and dropped: it carries no content, TOML's own parsers
    differ on it, and the editors that add it (Windows Notepad) give no visible sign of it, so
    refusing it would leave the user hunting for an invisible character."""
    if len(data) > MAX_FILE_BYTES:
        raise _too_big(source, len(data))
    if data.startswith(_BOM):
        data = data[len(_BOM):]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise DesignError(source, f"not UTF-8 at byte {exc.start} (line {line}): byte 0x{data[exc.start]:02x}",
                          "a TOML file is UTF-8 text: save it as UTF-8") from None


def nesting_depth(data: Any) -> int:
    """How deep tables and arrays nest in ``data`` (a scalar 0, a flat table 1), found without
    recursion so that any depth can be measured."""
    deepest = 0
    stack = [(data, 0)]
    while stack:
        value, depth = stack.pop()
        if isinstance(value, Mapping):
            children = value.values()
        elif isinstance(value, list):
            children = value
        else:
            deepest = max(deepest, depth)
            continue
        deepest = max(deepest, depth + 1)
        if depth + 1 > MAX_NESTING:
            return depth + 1  # deep enough to refuse: no need to walk the rest
        stack.extend((child, depth + 1) for child in children)
    return deepest


#: strings and comments of TOML text (replaced by ``""`` before keys are looked at)
_STRINGS_AND_COMMENTS = re.compile(r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*')
#: a key of more than MAX_NESTING dotted parts (bare or quoted): matched possessively from the start
#: of a word, so a long run of letters costs one pass
_DOTTED_TOO_DEEP = re.compile(r'(?<![A-Za-z0-9_-])(?:(?:[A-Za-z0-9_-]++|"")[ \t]*+\.[ \t]*+){%d}' % MAX_NESTING)


def parse_toml(text: str, source: str) -> dict[str, Any]:
    """Parse TOML ``text``; a syntax error, or nesting deeper than :data:`MAX_NESTING`, is a
    :class:`DesignError` naming ``source`` (and the line, for a syntax error)."""
    too_deep = DesignError(source, f"nested deeper than {MAX_NESTING} levels of tables and arrays",
                           f"at most {MAX_NESTING} levels (the shipped designs reach 5)")
    # dotted keys first: the TOML reader takes time quadratic in their parts (8000 parts: 1 s; a 4 MiB
    # file of them would not end), and they nest without it recursing
    if _DOTTED_TOO_DEEP.search(_STRINGS_AND_COMMENTS.sub('""', text)):
        raise too_deep
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DesignError(source, f"not valid TOML: {exc}") from None
    except ValueError as exc:  # an integer of more digits than Python converts (4300)
        raise DesignError(source, f"holds a number Python cannot read: {str(exc).split(';')[0]}",
                          "numbers a design needs") from None
    except RecursionError:  # the parser recurses once per level of nested arrays or inline tables
        raise too_deep from None
    if nesting_depth(data) > MAX_NESTING:  # dotted keys nest without the parser recursing
        raise too_deep
    return data


def read_toml(path: str | Path) -> tuple[dict[str, Any], bytes]:
    """A TOML design file parsed, and its bytes (for its digest): every way a file can fail to be
    read as a design (not UTF-8, nested too deep, not TOML, too big) is a :class:`DesignError`
    naming the file and the cause."""
    path = Path(path)
    try:
        with path.open("rb") as fh:
            size = os.fstat(fh.fileno()).st_size
            if size > MAX_FILE_BYTES:
                raise _too_big(str(path), size)
            data = fh.read(MAX_FILE_BYTES + 1)  # not more, should the file grow meanwhile
    except FileNotFoundError:
        raise DesignError(str(path), "no such design file") from None
    return parse_toml(toml_text(data, str(path)), str(path)), data


def load_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML design file (see :func:`read_toml`); errors name the file, the cause and the line."""
    return read_toml(path)[0]


def key_comment(schema, key: str) -> str:
    """The one-line comment of ``key`` in a design file: its meaning and the unit it is written in
    (``schema``: its :class:`Field`, or a quantity of the stiffness sections, whose key carries its
    unit family's suffix)."""
    suffix = ""
    if not isinstance(schema, Field) or schema.kind in ("length", "angle"):
        suffix = key[len(schema.name) + 1:]
    text = schema.help
    if suffix:
        text += f" [{suffix}]"
    elif isinstance(schema, Field) and schema.kind == "string" and schema.choices \
            and not all(c in text for c in schema.choices):
        text += ": " + " | ".join(schema.choices)
    return text
