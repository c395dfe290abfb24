"""Seeded corruptions of every shipped design file: the loader refuses each one, naming the key.

Each corruption is invalid *by the schema*, and the generator knows it from the schema itself:
it asks :func:`geargen.design.validate.key_schema` for the :class:`Field` (or stiffness
:class:`Quantity`) that owns the key it changes, and makes only changes that field refuses:

* delete a key whose field is ``required`` (for a gear key: when neither the gear's table nor
  ``[gear_defaults]`` still gives the field; the pitch counts as required, module or diametral
  pitch being one required choice);
* swap the type: a string, table, list or boolean for a number; a number, table or list for a
  string or name; a number or string for a list; a string for a boolean; a fraction for a whole
  number; a scalar for a section table;
* out of range: just past the field's minimum (the minimum itself when it is exclusive: zero
  where > 0 is needed), far past its maximum (its own, or the plausible one of its kind,
  :func:`geargen.design.schema.plausible`), NaN or +-infinity for any number (TOML has them),
  a word that is not one of a string field's choices;
* huge: 1e300 and 9.9e307 for every number, 10^30 for every whole number (issue 31's
  flexure length, eccentricity, carriage and bearing widths);
* a hostile name at every place a name becomes a file name: the top-level ``name``, each gear
  table's key and ``name`` label, each stage's key, as ``../../X``, an absolute path, a line
  break and 300 characters;
* the file itself: nested 5000 deep (arrays, inline tables, dotted keys), not UTF-8, an integer
  of 5000 digits; and a UTF-8 byte-order mark, which loads (the one corruption with a clean result);
* physically impossible hardware, from closed forms computed here (solid height, blade stress,
  tooth thinning past the tip land of geargen.core.involute, helical lead, bearing bores).

So a corruption the tool could accept (deleting a key with a default, a value inside its range)
is never generated. The whole pool goes through the loader (:func:`load_design`), each case within
:data:`LOAD_SECONDS`: it raises a DesignError naming the corrupted key (or the file and the cause),
and nothing else (issue 28: the loader directly, once per corruption). A seeded sample then goes
through ``geargen.cli.main`` in-process for ``synth``, ``check``, ``stiffness``, ``train`` and
``build --out``: each must exit 2 naming the key, print no traceback and write nothing.

``GEARGEN_FUZZ_COMMANDS`` (default 12) and ``GEARGEN_FUZZ_SEED`` run more or other samples by hand.
"""

from __future__ import annotations

import json
import math
import os
import time
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest

from geargen.cli import main
from geargen.design.assembly import design_from_dict, load_design
from geargen.design.schema import MAX_NESTING, Field, plausible
from geargen.design.stiffness import QUANTITY_SUFFIXES, Quantity
from geargen.design.validate import key_schema
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES

ROOT = Path(__file__).resolve().parents[2]
#: every shipped design file: the assemblies and the test designs among tests/data (those with gear
#: tables; the others there are tables of published numbers, not designs)
DESIGN_FILES = tuple(sorted((ROOT / "assemblies").glob("*.toml"))) + tuple(
    p for p in sorted((ROOT / "tests" / "data").glob("*.toml")) if "gears" in tomllib.loads(p.read_text()))
COMMAND_SAMPLE = int(os.environ.get("GEARGEN_FUZZ_COMMANDS", "12"))
SEED = int(os.environ.get("GEARGEN_FUZZ_SEED", "1994"))
#: the most one corruption may take the loader (s): a refusal takes milliseconds, a hang would not end
LOAD_SECONDS = 10.0
DELETE = object()
HOSTILE_NAMES = ("../../X", "/tmp/geargen-fuzz-victim/precious", "gear\nX", "n" * 300)
KINDS = {"delete", "type", "range", "huge", "name", "file", "physical"}


# ----------------------------------------------------------------------------- a small TOML writer

def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def to_toml(data: dict, prefix: str = "") -> str:
    """TOML text of nested tables of scalars and lists (tables inside tables become [a.b] headers;
    every key quoted, so any name can be written)."""
    lines = [f"{json.dumps(k)} = {_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    text = "\n".join(lines) + ("\n" if lines else "")
    for k, v in data.items():
        if isinstance(v, dict):
            name = f"{prefix}{json.dumps(k)}"
            text += f"\n[{name}]\n" + to_toml(v, name + ".")
    return text


# ----------------------------------------------------------------------------- the generator

@dataclass(frozen=True)
class Corruption:
    file: str
    kind: str
    names: tuple[str, ...] | None  # fragments one of which the message must contain; None: the file loads
    path: tuple[str, ...] = ()
    value: Any = None
    rename: str | None = None  # the table at ``path`` renamed this
    text: Callable[[bytes], bytes] | None = None  # a change of the file's bytes
    what: str = ""

    def content(self, data: dict, raw: bytes) -> bytes:
        if self.text is not None:
            return self.text(raw)
        out = json.loads(json.dumps(data))  # a deep copy (the files hold no NaN)
        table = out
        for k in self.path[:-1]:
            table = table[k]
        key = self.path[-1]
        if self.rename is not None:
            table[self.rename] = table.pop(key)
        elif self.value is DELETE:
            del table[key]
        else:
            table[key] = self.value
        return to_toml(out).encode()

    def __str__(self):
        if self.text is not None:
            return f"{self.file}: {self.kind} {self.what}"
        if self.rename is not None:
            return f"{self.file}: {self.kind} [{'.'.join(self.path)}] renamed {self.rename!r}"[:200]
        value = "<deleted>" if self.value is DELETE else repr(self.value)[:80]
        return f"{self.file}: {self.kind} {'.'.join(self.path)} = {value}"


def _leaves(table: dict, path=()):
    for k, v in table.items():
        if isinstance(v, dict):
            yield from _leaves(v, path + (k,))
        else:
            yield path + (k,), v


def _names(data: dict, path: tuple[str, ...], schema) -> tuple[str, ...]:
    """Message fragments that name the key at ``path``: the key as written, or its field's name
    (the key without its unit suffix, as a missing key is named)."""
    head = ".".join(path[:-1] + (schema.name,))
    names = (head,)
    if path[0] == "gear_defaults":
        # a shared key is named where the file has it, or per gear when one gear's table lacks it
        names += tuple(f"gears.{g}.{schema.name}" for g in data["gears"])
    if path[0] in ("gears", "gear_defaults") and schema.name in ("module", "diametral_pitch_per_in"):
        # a missing pitch: "gears.NAME.module_mm: give exactly one of module_mm and diametral_pitch_per_in"
        names += tuple(f"gears.{g}.module_mm" for g in data["gears"])
    return names


def _family(schema, key: str) -> str | None:
    return schema.keys()[key][0] if isinstance(schema, Quantity) else None


def _scale(schema, key: str) -> float:
    """Internal units per unit of the key's suffix."""
    if isinstance(schema, Quantity):
        fam, suf = schema.keys()[key]
        return QUANTITY_SUFFIXES[fam][suf]
    if schema.kind in ("length", "angle"):
        return schema.suffixes()[key[len(schema.name) + 1:]]
    return 1.0


def _bounds(schema, key: str) -> Field:
    """The range the loader applies to the key: its own, and the plausible one of its kind where
    it sets none."""
    if isinstance(schema, Quantity):
        field = Field(schema.name, "number", minimum=schema.minimum, maximum=schema.maximum,
                      exclusive_minimum=schema.exclusive_minimum)
        return plausible(field, _family(schema, key))
    return plausible(schema)


def _gear_field_given(data: dict, gear: str, schema: Field, without: tuple[str, ...]) -> bool:
    """Does gear ``gear`` still get ``schema``'s field once the key at ``without`` is deleted?"""
    names = set(schema.keys())
    if schema.name in ("module", "diametral_pitch_per_in"):
        names = {"module_mm", "diametral_pitch_per_in"}
    tables = [("gears", gear), ("gear_defaults",)]
    for t in tables:
        table = data
        for k in t:
            table = table.get(k, {})
        if any(k in table and t + (k,) != without for k in names):
            return True
    return False


def _required(data: dict, path: tuple[str, ...], schema) -> bool:
    if path[0] in ("gears", "gear_defaults"):
        pitch = schema.name in ("module", "diametral_pitch_per_in")
        if not (schema.required or pitch):
            return False
        gears = [path[1]] if path[0] == "gears" else list(data["gears"])
        return any(not _gear_field_given(data, g, schema, path) for g in gears)
    if path[0] == "parts" and schema.required:
        # a [parts] key the default hardware sizes when the file leaves it out is not missing
        from geargen.design.assembly import default_hardware
        trimmed = {k: (dict(v) if k == "parts" else v) for k, v in data.items()}
        del trimmed["parts"][path[-1]]
        try:
            completed, _ = default_hardware(trimmed)
        except DesignError:
            return True  # the defaults refuse it missing (a bearing of a bore no standard bearing has)
        return not any(k.startswith(schema.name) for k in completed.get("parts", {}))
    return bool(schema.required)


def _out_of_range(schema, key: str) -> list:
    """Values of the key's kind that its range refuses (written in the key's unit)."""
    out: list = []
    scale = _scale(schema, key)
    integer = isinstance(schema, Field) and schema.kind == "integer"
    bounds = _bounds(schema, key)
    lo, hi = bounds.minimum, bounds.maximum
    if schema.minimum == 0 and schema.exclusive_minimum:
        out.append(0)  # zero where above zero is needed (a stiffness divided by)
    if lo is not None:
        written = lo / scale
        if bounds.exclusive_minimum:
            out.append(int(written) if integer and written == int(written) else written)
        below = written - max(1.0, abs(written))
        out.append(int(math.floor(below)) if integer else below)
    if hi is not None:
        above = hi / scale * 10 + 1
        out.append(int(math.ceil(above)) if integer else above)
    if not integer:
        out += [math.nan, math.inf, -math.inf]
    return out


def _kind(schema) -> str:
    return "number" if isinstance(schema, Quantity) else schema.kind


def schema_corruptions(name: str, data: dict) -> list[Corruption]:
    out = []
    for path, value in _leaves(data):
        schema = key_schema(data, path)
        assert schema is not None, f"{name}: {'.'.join(path)} has no schema"  # the schema covers every key
        names = _names(data, path, schema)
        kind = _kind(schema)
        if _required(data, path, schema):
            out.append(Corruption(name, "delete", names, path, DELETE))
        if kind in ("length", "angle", "number", "integer"):
            swaps = ["12", {"x": 1}, [1, 2], True] + ([2.5] if kind == "integer" else [])
            out += [Corruption(name, "range", names, path, v) for v in _out_of_range(schema, path[-1])]
            huge = [10 ** 30] if kind == "integer" else [1e300, 9.9e307]
            out += [Corruption(name, "huge", names, path, v) for v in huge]
        elif kind in ("string", "name"):
            swaps = [3, [1], {"x": 1}]
            if schema.choices:
                out.append(Corruption(name, "range", names, path, "not_a_choice"))
            elif kind == "name":
                out += [Corruption(name, "name", names, path, v) for v in HOSTILE_NAMES]
        elif kind == "list":
            swaps = [5, "five"]
        elif kind == "bool":
            swaps = ["yes", 1]
        else:
            swaps = []
        out += [Corruption(name, "type", names, path, v) for v in swaps]
    for section, table in data.items():
        if isinstance(table, dict):
            out.append(Corruption(name, "type", (section,), (section,), 5))
    for gear in data.get("gears", {}):
        out.append(Corruption(name, "type", (f"gears.{gear}",), ("gears", gear), "big"))
    return out


def name_corruptions(name: str, data: dict) -> list[Corruption]:
    """A hostile name at every place a name becomes a file name (the top-level ``name`` is a
    schema key, done above): each gear table's key and a ``name`` label in it, each stage's key."""
    out = []
    for hostile in HOSTILE_NAMES:
        for gear in data.get("gears", {}):
            out.append(Corruption(name, "name", (f"gears.{hostile[:40]}",), ("gears", gear), rename=hostile))
            out.append(Corruption(name, "name", (f"gears.{gear}.name",), ("gears", gear, "name"), hostile))
        for stage in data.get("stages", {}):
            out.append(Corruption(name, "name", (f"stages.{hostile[:40]}",), ("stages", stage), rename=hostile))
    return out


def _insert_after_header(raw: bytes, text: bytes) -> bytes:
    """``text`` as a top-level key: before the first table header (after the leading comments and keys)."""
    at = raw.find(b"\n[")
    return raw[:at + 1] + text + b"\n" + raw[at + 1:]


def file_corruptions(name: str, raw: bytes, rng: np.random.Generator) -> list[Corruption]:
    """The file itself: nested too deep, not UTF-8, a number of too many digits; a byte-order mark."""
    deep = f"nested deeper than {MAX_NESTING} levels"
    arrays = b"junk = " + b"[" * 5000 + b"]" * 5000
    inline = b"junk = " + b"{a = " * 5000 + b"1" + b"}" * 5000
    dotted = b".".join([b"a"] * 5000) + b" = 1"
    at = int(rng.integers(0, len(raw)))
    return [
        Corruption(name, "file", (deep,), text=lambda r: _insert_after_header(r, arrays), what="arrays 5000 deep"),
        Corruption(name, "file", (deep,), text=lambda r: _insert_after_header(r, inline), what="inline tables 5000 deep"),
        Corruption(name, "file", (deep,), text=lambda r: _insert_after_header(r, dotted), what="dotted keys 5000 deep"),
        Corruption(name, "file", (f"not UTF-8 at byte {at}",), text=lambda r: r[:at] + b"\xff" + r[at:],
                   what=f"byte 0xff at {at}"),
        Corruption(name, "file", ("holds a number Python cannot read",),
                   text=lambda r: _insert_after_header(r, b"junk = " + b"7" * 5000), what="an integer of 5000 digits"),
        Corruption(name, "file", None, text=lambda r: b"\xef\xbb\xbf" + r, what="a UTF-8 byte-order mark"),
    ]


def _key(table: dict, stem: str) -> tuple[str, float] | None:
    """(key, value in mm) of the length ``stem`` in ``table``, whatever its unit suffix."""
    for unit, scale in LENGTH_SUFFIXES.items():
        if f"{stem}_{unit}" in table:
            return f"{stem}_{unit}", table[f"{stem}_{unit}"] * scale
    return None


def physical_corruptions(name: str, data: dict, path: Path) -> list[Corruption]:
    """Hardware that cannot exist, each value found from a closed form computed here."""
    from geargen.core.involute import tip_land_thickness
    from geargen.design.gear import GearSpec, with_changes

    def length(section: str, key: str, mm: float, blamed: str) -> Corruption:
        unit = key.rsplit("_", 1)[1]
        return Corruption(name, "physical", (f"{section}.{blamed}",), (section, key), round(mm / LENGTH_SUFFIXES[unit], 8))

    out = []
    springs = data.get("springs")
    if springs:
        (wire_key, d), (mean_key, mean) = _key(springs, "wire_diameter"), _key(springs, "mean_coil_diameter")
        solid = d * (springs["active_coils"] + 2)  # squared and ground ends
        out.append(length("springs", _key(springs, "installed_length")[0], 0.9 * solid,
                          _key(springs, "installed_length")[0]))
        out.append(length("springs", wire_key, mean, mean_key))  # a wire as thick as the coil
    flexures = data.get("flexures")
    if flexures:
        (_, blade), (thick_key, t), (width_key, w) = (_key(flexures, "length"), _key(flexures, "thickness"),
                                                       _key(flexures, "width"))
        # fixed-guided blades: the travel at the allowable stress, sigma L^2 / (3 E t)
        limit = flexures["allowable_stress_MPa"] * blade ** 2 / (3 * flexures["elastic_modulus_GPa"] * 1e3 * t)
        travel_key = _key(flexures, "travel")[0]
        out.append(length("flexures", travel_key, 3 * limit, travel_key))
        out.append(length("flexures", thick_key, w, thick_key))
    design = load_design(path)
    engagement = data.get("engagement")
    if engagement and design.gears.get(engagement.get("gear", "cluster_small")) is not None:
        helix = design.gears[engagement.get("gear", "cluster_small")].helix_angle
        key, engaged = _key(engagement, "engagement_length")
        if helix > 0:  # a lead of backlash / tan(beta) longer than the engagement length
            backlash_key = _key(engagement, "backlash")[0]
            out.append(length("engagement", backlash_key, 2 * engaged * math.tan(helix), backlash_key))
    unit = design.length_unit
    for gear, spec in design.gears.items():
        if not isinstance(spec, GearSpec) or spec.kind != "external":
            continue
        key = next((k for k in data["gears"][gear] if k.startswith("thinning_circumferential_")), None)
        key = key or f"thinning_circumferential_{unit}"
        # past the thinning at which the exact tip land vanishes (linear: d(land)/d(thinning) = -r_a / r),
        # short of the quarter pitch that bounds the key's range (beyond it: a range error, made above)
        unthinned = with_changes(spec, thinning=0.0)
        pointed = tip_land_thickness(unthinned) * spec.reference_radius / spec.tip_radius
        quarter = math.pi * spec.transverse_module / 4
        if pointed < quarter:
            thinning = (pointed + quarter) / 2 / LENGTH_SUFFIXES[key.rsplit("_", 1)[1]]
            out.append(Corruption(name, "physical", (f"gears.{gear}.{key}",), ("gears", gear, key), round(thinning, 8)))
    parts = data.get("parts", {})
    for outer, inner in (("cluster_bearing_outer_diameter", "cluster_shaft_diameter"),
                         ("bearing_outer_diameter", "hollow_shaft_outer_diameter")):
        if _key(parts, outer) and _key(parts, inner):
            out.append(length("parts", _key(parts, outer)[0], _key(parts, inner)[1], _key(parts, outer)[0]))
    return out


def originals() -> dict[str, tuple[dict, bytes, Path]]:
    return {p.stem if p.parent.name == "assemblies" else f"data_{p.stem}": (tomllib.loads(p.read_text()), p.read_bytes(), p)
            for p in DESIGN_FILES}


def all_corruptions() -> list[Corruption]:
    rng = np.random.default_rng(SEED)
    pool = []
    for name, (data, raw, path) in originals().items():
        pool += (schema_corruptions(name, data) + name_corruptions(name, data) + file_corruptions(name, raw, rng)
                 + physical_corruptions(name, data, path))
    return pool


def command_sample(pool: list[Corruption], count: int, seed: int) -> list[Corruption]:
    """``count`` refused corruptions for the commands: one of each kind, then the rest drawn, every
    file in turn."""
    rng = np.random.default_rng(seed)
    refused = [c for c in pool if c.names is not None]
    chosen = []
    for kind in sorted(KINDS):
        of_kind = [c for c in refused if c.kind == kind]
        chosen.append(of_kind[int(rng.integers(len(of_kind)))])
    files = sorted({c.file for c in refused})
    while len(chosen) < count:
        of_file = [c for c in refused if c.file == files[len(chosen) % len(files)] and c not in chosen]
        chosen.append(of_file[int(rng.integers(len(of_file)))])
    return chosen[:max(count, len(KINDS))]


# ----------------------------------------------------------------------------- the tests

@pytest.fixture(scope="module")
def pool():
    return all_corruptions()


def test_the_writer_round_trips_every_shipped_file():
    for name, (data, raw, path) in originals().items():
        assert tomllib.loads(to_toml(data)) == data, name


def test_every_shipped_design_file_is_in_the_pool(pool):
    assert len(DESIGN_FILES) == 10  # the nine assemblies and tests/data/metric_dual_pinion.toml
    files = {c.file for c in pool}
    assert files == set(originals())
    for name in files:
        kinds = {c.kind for c in pool if c.file == name}
        assert kinds >= KINDS - {"physical"}, (name, kinds)
    assert {c.kind for c in pool} == KINDS


def _write(folder: Path, c: Corruption, originals_) -> Path:
    data, raw, path = originals_[c.file]
    folder.mkdir()
    target = folder / path.name
    target.write_bytes(c.content(data, raw))
    return target


def test_the_loader_refuses_every_corruption_naming_the_key(pool, tmp_path):
    originals_ = originals()
    problems, slowest = [], (0.0, None)
    for i, c in enumerate(pool):
        path = _write(tmp_path / f"c{i:05d}", c, originals_)
        t0 = time.perf_counter()
        try:
            load_design(path)
            outcome = None
        except DesignError as exc:
            outcome = str(exc)
        except Exception as exc:  # noqa: BLE001 - any other exception is what the test looks for
            outcome = exc
        seconds = time.perf_counter() - t0
        slowest = max(slowest, (seconds, str(c)), key=lambda s: s[0])
        if isinstance(outcome, Exception):
            problems.append(f"{c}\n    {type(outcome).__name__}: {str(outcome)[:300]}")
        elif c.names is None and outcome is not None:
            problems.append(f"{c}\n    refused, should load: {outcome[:300]}")
        elif c.names is not None and (outcome is None or not any(n in outcome for n in c.names)):
            problems.append(f"{c}\n    {'loaded' if outcome is None else outcome[:300]}; expected one of {c.names}")
        if seconds > LOAD_SECONDS:
            problems.append(f"{c}: {seconds:.1f} s")
    assert not problems, f"{len(problems)} failures of {len(pool)} corruptions:\n" + "\n".join(problems[:20])
    assert slowest[0] < LOAD_SECONDS, slowest


def test_a_sample_is_refused_by_every_command(pool, tmp_path, capsys):
    originals_ = originals()
    problems = []
    sample = command_sample(pool, COMMAND_SAMPLE, SEED)
    assert {c.kind for c in sample} == KINDS
    for i, c in enumerate(sample):
        path = _write(tmp_path / f"c{i:04d}", c, originals_)
        out = path.parent / "out"
        for argv in (["synth", path], ["check", path], ["stiffness", path, "--out", out / "plots"],
                     ["train", path, "--out", out / "train"], ["build", path, "--out", out / "build", "--quiet"]):
            code = main([str(a) for a in argv])
            err = capsys.readouterr().err
            if code != 2 or "Traceback" in err or not any(n in err for n in c.names):
                problems.append(f"{c}\n    geargen {argv[0]}: exit {code}: {err.strip()[:300]}")
        if out.exists():
            problems.append(f"{c}: wrote {sorted(p.name for p in out.rglob('*'))}")
    assert not problems, f"{len(problems)} failures of {len(sample)} corruptions:\n" + "\n".join(problems[:20])
