"""Seeded corruptions of the shipped design files: every command refuses each one on load.

Each corruption is invalid *by the schema*, and the generator knows it from the schema itself:
it asks :func:`geargen.design.validate.key_schema` for the :class:`Field` (or stiffness
:class:`Quantity`) that owns the key it changes, and makes only changes that field refuses:

* delete a key whose field is ``required`` (for a gear key: when neither the gear's table nor
  ``[gear_defaults]`` still gives the field; the pitch counts as required, module or diametral
  pitch being one required choice);
* swap the type: a string, table, list or boolean for a number; a number, table or list for a
  string; a number or string for a list; a string for a boolean; a fraction for a whole number;
  a scalar for a section table;
* out of range: just past the field's minimum (the minimum itself when it is exclusive: zero
  where > 0 is needed), far past its maximum, NaN or +-infinity for any number (TOML has them),
  a word that is not one of a string field's choices;
* physically impossible hardware, from closed forms computed here (solid height, blade stress,
  tooth thinning past the tip land of geargen.core.involute, helical lead, bearing bores).

So a corruption the tool could accept (deleting a key with a default, a value inside its range)
is never generated. Each corrupted file goes through ``geargen.cli.main`` in-process for
``synth``, ``check``, ``stiffness`` and ``build --out`` (and ``gear --gear``): each must exit 2
with a message naming the corrupted key, print no traceback and write nothing.

``GEARGEN_FUZZ_COUNT`` (default 200) and ``GEARGEN_FUZZ_SEED`` run more or other corruptions by hand.
"""

from __future__ import annotations

import json
import math
import os
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from geargen.cli import main
from geargen.design.schema import Field
from geargen.design.stiffness import QUANTITY_SUFFIXES, Quantity
from geargen.design.validate import key_schema
from geargen.units import LENGTH_SUFFIXES

ROOT = Path(__file__).resolve().parents[2]
FILES = ("robot_joint", "c_axis", "split_pinion")
COUNT = int(os.environ.get("GEARGEN_FUZZ_COUNT", "200"))
SEED = int(os.environ.get("GEARGEN_FUZZ_SEED", "1994"))
DELETE = object()
IN = 25.4


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
    raise TypeError(type(v))


def to_toml(data: dict, prefix: str = "") -> str:
    """TOML text of nested tables of scalars and lists (tables inside tables become [a.b] headers)."""
    lines = [f"{k} = {_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    text = "\n".join(lines) + ("\n" if lines else "")
    for k, v in data.items():
        if isinstance(v, dict):
            name = f"{prefix}{k}"
            text += f"\n[{name}]\n" + to_toml(v, name + ".")
    return text


# ----------------------------------------------------------------------------- the generator

@dataclass(frozen=True)
class Corruption:
    file: str
    kind: str
    path: tuple[str, ...]
    value: Any
    names: tuple[str, ...]  # fragments one of which the message must contain

    def apply(self, data: dict) -> dict:
        out = json.loads(json.dumps(data))  # a deep copy (the files hold no NaN)
        table = out
        for k in self.path[:-1]:
            table = table[k]
        if self.value is DELETE:
            del table[self.path[-1]]
        else:
            table[self.path[-1]] = self.value
        return out

    def __str__(self):
        value = "<deleted>" if self.value is DELETE else repr(self.value)
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


def _scale(schema, key: str) -> float:
    """Internal units per unit of the key's suffix."""
    if isinstance(schema, Quantity):
        fam, suf = schema.keys()[key]
        return QUANTITY_SUFFIXES[fam][suf]
    if schema.kind in ("length", "angle"):
        return schema.suffixes()[key[len(schema.name) + 1:]]
    return 1.0


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
        from geargen.design.hardware_defaults import default_hardware
        trimmed = {k: (dict(v) if k == "parts" else v) for k, v in data.items()}
        del trimmed["parts"][path[-1]]
        completed, _ = default_hardware(trimmed)
        return not any(k.startswith(schema.name) for k in completed.get("parts", {}))
    return bool(schema.required)


def _out_of_range(schema, key: str, value) -> list:
    """Values of the key's kind that the field's range refuses (written in the key's unit)."""
    out: list = []
    scale = _scale(schema, key)
    integer = isinstance(schema, Field) and schema.kind == "integer"
    lo, hi = schema.minimum, schema.maximum
    exclusive_lo = schema.exclusive_minimum
    if lo is not None:
        written = lo / scale
        if exclusive_lo:
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
            out.append(Corruption(name, "delete", path, DELETE, names))
        if kind in ("length", "angle", "number", "integer"):
            swaps = ["12", {"x": 1}, [1, 2], True] + ([2.5] if kind == "integer" else [])
            for v in _out_of_range(schema, path[-1], value):
                out.append(Corruption(name, "range", path, v, names))
        elif kind == "string":
            swaps = [3, [1], {"x": 1}]
            if schema.choices:
                out.append(Corruption(name, "range", path, "not_a_choice", names))
            elif path == ("name",):
                out.append(Corruption(name, "range", path, "a/b", names))
        elif kind == "list":
            swaps = [5, "five"]
        elif kind == "bool":
            swaps = ["yes", 1]
        else:
            swaps = []
        out += [Corruption(name, "type", path, v, names) for v in swaps]
    for section, table in data.items():
        if isinstance(table, dict):
            out.append(Corruption(name, "type", (section,), 5, (section,)))
    for gear in data.get("gears", {}):
        out.append(Corruption(name, "type", ("gears", gear), "big", (f"gears.{gear}",)))
    return out


def physical_corruptions(name: str, data: dict) -> list[Corruption]:
    """Hardware that cannot exist, each value found from a closed form computed here."""
    from geargen.core.involute import tip_land_thickness
    from geargen.design.assembly import load_design
    from geargen.design.gear import with_changes

    out = []
    unit = data.get("length_unit", "mm")
    per = LENGTH_SUFFIXES[unit]
    springs = data.get("springs")
    if springs:
        d = springs["wire_diameter_in"]
        solid = d * (springs["active_coils"] + 2)  # squared and ground ends
        out.append(Corruption(name, "physical", ("springs", "installed_length_in"), round(0.9 * solid, 6),
                              ("springs.installed_length_in",)))
        out.append(Corruption(name, "physical", ("springs", "wire_diameter_in"), springs["mean_coil_diameter_in"],
                              ("springs.mean_coil_diameter_in",)))
    flexures = data.get("flexures")
    if flexures:
        # fixed-guided blades: the travel at the allowable stress, sigma L^2 / (3 E t)
        limit = (flexures["allowable_stress_MPa"] * flexures["length_in"] ** 2
                 / (3 * flexures["elastic_modulus_GPa"] * 1e3 * flexures["thickness_in"]))
        out.append(Corruption(name, "physical", ("flexures", "travel_in"), round(3 * limit, 6), ("flexures.travel_in",)))
        out.append(Corruption(name, "physical", ("flexures", "thickness_in"), flexures["width_in"],
                              ("flexures.thickness_in",)))
    engagement = data.get("engagement")
    if engagement:
        helix = math.radians(data["gear_defaults"]["helix_angle_deg"])
        # a lead of backlash / tan(beta) longer than the engagement length
        backlash = 2 * engagement["engagement_length_mm"] * math.tan(helix)
        out.append(Corruption(name, "physical", ("engagement", "backlash_mm"), round(backlash, 4),
                              ("engagement.backlash_mm",)))
    design = load_design(ROOT / "assemblies" / f"{name}.toml")
    for gear, spec in design.gears.items():
        key = next((k for k in data["gears"][gear] if k.startswith("thinning_circumferential_")), None)
        key = key or f"thinning_circumferential_{unit}"
        # past the thinning at which the exact tip land vanishes (linear: d(land)/d(thinning) = -r_a / r),
        # short of the quarter pitch that bounds the key's range (beyond it: a range error, made above)
        unthinned = with_changes(spec, thinning=0.0)
        pointed = tip_land_thickness(unthinned) * spec.reference_radius / spec.tip_radius
        quarter = math.pi * spec.transverse_module / 4
        if pointed < quarter:
            thinning = (pointed + quarter) / 2 / per
            out.append(Corruption(name, "physical", ("gears", gear, key), round(thinning, 6), (f"gears.{gear}.{key}",)))
    parts = data.get("parts", {})
    for outer, inner in (("cluster_bearing_outer_diameter_mm", "cluster_shaft_diameter_mm"),
                         ("bearing_outer_diameter_mm", "hollow_shaft_outer_diameter_mm")):
        if outer in parts:
            out.append(Corruption(name, "physical", ("parts", outer), parts[inner], (f"parts.{outer}",)))
    return out


def all_corruptions() -> list[Corruption]:
    pool = []
    for name in FILES:
        data = tomllib.loads((ROOT / "assemblies" / f"{name}.toml").read_text())
        pool += schema_corruptions(name, data) + physical_corruptions(name, data)
    return pool


def sample(count: int, seed: int) -> list[Corruption]:
    """``count`` corruptions: every physical one (a few per file), the rest drawn from the pool."""
    pool = all_corruptions()
    physical = [c for c in pool if c.kind == "physical"]
    others = [c for c in pool if c.kind != "physical"]
    rng = np.random.default_rng(seed)
    drawn = rng.choice(len(others), size=min(max(count - len(physical), 0), len(others)), replace=False)
    chosen = physical[:count] + [others[i] for i in drawn]
    return [chosen[i] for i in rng.permutation(len(chosen))]


# ----------------------------------------------------------------------------- the tests

def test_the_writer_round_trips_the_shipped_files():
    for name in FILES:
        data = tomllib.loads((ROOT / "assemblies" / f"{name}.toml").read_text())
        assert tomllib.loads(to_toml(data)) == data


def test_the_pool_has_every_kind_of_corruption_for_every_file():
    pool = all_corruptions()
    for name in FILES:
        kinds = {c.kind for c in pool if c.file == name}
        assert kinds == {"delete", "type", "range", "physical"}, (name, kinds)
    assert len(pool) > 3 * COUNT


@pytest.fixture(scope="module")
def corruptions():
    return sample(COUNT, SEED)


def _commands(path: Path, out: Path, gear: str) -> list[list[str]]:
    return [["synth", str(path)], ["check", str(path)],
            ["stiffness", str(path), "--out", str(out / "plots")],
            ["build", str(path), "--out", str(out / "build"), "--quiet"],
            ["gear", str(path), "--gear", gear, "--out", str(out / "gear")]]


def test_every_corruption_is_refused_on_load_by_every_command(corruptions, tmp_path, capsys):
    originals = {n: tomllib.loads((ROOT / "assemblies" / f"{n}.toml").read_text()) for n in FILES}
    problems = []
    for i, c in enumerate(corruptions):
        folder = tmp_path / f"c{i:04d}"
        folder.mkdir()
        path = folder / f"{c.file}.toml"
        path.write_text(to_toml(c.apply(originals[c.file])))
        gear = next(iter(originals[c.file]["gears"]))
        out = folder / "out"
        for argv in _commands(path, out, gear):
            code = main(argv)
            err = capsys.readouterr().err
            if code != 2 or "Traceback" in err or not any(n in err for n in c.names):
                problems.append(f"{c}\n    geargen {argv[0]}: exit {code}: {err.strip()[:300]}")
        if out.exists():
            problems.append(f"{c}: wrote {sorted(p.name for p in out.rglob('*'))}")
    assert not problems, f"{len(problems)} failures of {len(corruptions)} corruptions:\n" + "\n".join(problems[:20])


def test_the_sample_covers_every_file_and_kind(corruptions):
    assert {c.file for c in corruptions} == set(FILES)
    assert {c.kind for c in corruptions} == {"delete", "type", "range", "physical"}
