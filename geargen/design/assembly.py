"""An assembly design file: name, length unit, drive type, gears, and the sections each step reads.

Layout of the TOML::

    name = "robot_joint"
    description = "..."
    length_unit = "in"              # the unit reports and exports use ("mm" or "in")

    [drive]
    type = "type2"                  # "type1" or "type2" (Hale & Slocum)
    preload = "radial"              # "radial", "axial", "angular" or "frictional_interface"

    [gear_defaults]                 # keys shared by every gear (pitch, pressure angle, ...)
    diametral_pitch_per_in = 32
    pressure_angle_deg = 20

    [gears.input]                   # one table per gear, keys as in geargen.design.gear
    teeth = 16
    face_width_in = 0.25

    [synthesis] ...                 # each further section is read by the step that owns it

:func:`load_design` reads every section with the module that owns it (the step that uses it
reads it again the same way) and checks the rules between sections and whether the hardware can
be made, so every command refuses a bad file before it computes anything; all the problems of a
file are reported together, each naming its key as the file spells it.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Mapping

from geargen.design.catalogue import Defaulted, Readers
from geargen.design.feasibility import check_tooth
from geargen.design.gear import GearSpec, gear_keys_written
from geargen.design.schema import (GEAR_NAME_MAX, STRING_MAX, DesignErrors, Problems, check_name, read_toml, shown,
                                   unknown_key)
from geargen.design.layout import layout_settings
from geargen.design.parts import hardware_fields
from geargen.design.stiffness import QUANTITY_SUFFIXES, preload_spec_from_table
from geargen.drives.keys import KEYS, kind_of
from geargen.errors import DesignError
from geargen.design.written_units import other_unit_warnings
from geargen.families.registry import read_gear
from geargen.units import LENGTH_SUFFIXES, LENGTH_UNITS, TextUnits, text_units

#: top-level sections a design file may hold, and who reads them
SECTIONS: dict[str, str] = {
    "drive": "drive type and preload method",
    "gear_defaults": "keys shared by every gear",
    "gears": "one table per gear",
    "synthesis": "centre synthesis of a dual-pinion drive (geargen.design.synthesis)",
    "errors": "per-gear error budget, TIR (geargen.design.synthesis)",
    "monte_carlo": "tolerance simulation settings (geargen.design.synthesis)",
    "stiffness": "path stiffness components (geargen.design.stiffness)",
    "preload": "preload setting and load spectrum (geargen.design.stiffness)",
    "flexures": "blade flexures of the preload carriage (geargen.design.stiffness)",
    "springs": "preload compression springs (geargen.design.stiffness)",
    "beam_pinion": "the long pinion used as a beam spring (geargen.design.stiffness)",
    "engagement": "axial engagement of helical dual pinions (geargen.design.stiffness)",
    "checks": "mesh-check settings (geargen.checks)",
    "parts": "non-gear parts of the assembly model (geargen.design.parts)",
    "stages": "gear stages between the motor and the anti-backlash loop (geargen.design.stages)",
    "layout": "placement of the gears in the build (geargen.design.layout)",
    "export": "export settings: STL tolerances, rendered view (geargen.design.export)",
    "train": "materials, motor, load and position loop of the train analysis (geargen.design.train)",
    "dual_motor": "a drive of two motors on one output gear, Fig. 1 (geargen.design.train)",
    "duty": "the load spectrum, speed, life and lubrication every mesh is rated for (geargen.design.duty)",
    "materials": "ISO 6336-5 material of each gear, [materials.GEAR] (geargen.design.duty)",
}

TOP_KEYS = ("name", "description", "length_unit")
DRIVE_TYPES = ("type1", "type2")
PRELOAD_METHODS = ("radial", "axial", "angular", "frictional_interface")


@dataclass(frozen=True)
class Design:
    """A loaded, validated design file. Gears are in internal units (mm, rad)."""

    name: str
    length_unit: str
    gears: dict[str, GearSpec]
    sections: dict[str, dict[str, Any]] = field(default_factory=dict)
    description: str = ""
    drive_type: str | None = None
    preload_method: str | None = None
    path: Path | None = None
    sha256: str = ""
    #: the values the file did not give and the default hardware chose (geargen/drives/<kind>/defaults.py)
    defaulted: tuple = ()
    #: gear table key -> the label its ``name`` key gives it (only gears whose label differs from the
    #: key): for reports and exports; the key stays the gear's identity (``gears``, every section)
    labels: dict[str, str] = field(default_factory=dict)
    #: lengths written in the other unit whose numbers read like the design's own (geargen.design.written_units)
    unit_warnings: tuple[str, ...] = ()

    @property
    def mm_per_unit(self) -> float:
        """mm in one of the design's length units (25.4 for an inch design)."""
        return LENGTH_SUFFIXES[self.length_unit]

    @property
    def text_units(self) -> TextUnits:
        """The units this design's reports, warnings and errors use (:func:`geargen.units.text_units`)."""
        return text_units(self.length_unit, _keys_of(self.sections))

    def section(self, name: str) -> dict[str, Any]:
        """The raw table of a section (empty when the file has none)."""
        if name not in SECTIONS:
            raise KeyError(f"{name!r} is not a design-file section")
        return self.sections.get(name, {})

    def label(self, gear: str) -> str:
        """What reports and exports call the gear of table key ``gear``: its ``name``, else the key."""
        return self.labels.get(gear, gear)

    def gear(self, name: str) -> GearSpec:
        try:
            return self.gears[name]
        except KeyError:
            raise DesignError(f"gears.{name}", "missing", ", ".join(self.gears) or "a [gears.NAME] table") from None

    def resolve(self, relative: str | Path) -> Path:
        """A path written in the design file, relative to the file's folder."""
        base = self.path.parent if self.path else Path.cwd()
        return (base / relative).resolve()


def _keys_of(table: Mapping[str, Any]):
    """Every key of a nested table, depth first in file order."""
    for key, value in table.items():
        yield key
        if isinstance(value, Mapping):
            yield from _keys_of(value)


def design_from_dict(data: Mapping[str, Any], path: Path | None = None, sha256: str = "",
                     validate: bool = False) -> Design:
    """A :class:`Design` from the parsed TOML ``data``: top-level keys, drive and gears checked.

    ``validate`` (what :func:`load_design` does) also reads and checks every further section, the
    rules between sections and whether each gear's tooth can be cut
    (:func:`geargen.design.validate.validate_sections`). Every problem found is reported at once:
    one :class:`DesignError`, or :class:`~geargen.design.schema.DesignErrors` listing several.
    """
    if not isinstance(data, Mapping):
        raise DesignError("<top>", "expected a table")
    defaulted: tuple = ()
    if validate:
        data, defaulted = default_hardware(data)
    problems = Problems()
    unknown = [k for k in data if k not in SECTIONS and k not in TOP_KEYS]
    known = list(TOP_KEYS) + list(SECTIONS)
    for key in unknown:
        problems.add(unknown_key(key, key, known, ", ".join(known), "unknown key or section"))
    name = data.get("name", path.stem if path else "design")
    try:
        check_name("name", name)
    except DesignError as exc:
        if "name" not in data:  # the file's name stands in for the key
            exc = DesignError("name", f"missing, and the file's name {shown(name)} is not a valid name",
                              f'name = "..." in the file, {exc.allowed}')
        problems.add(exc)
        name = "design"
    description = data.get("description", "")
    if not isinstance(description, str):
        problems.add(DesignError("description", f"expected a string, got {shown(description)}"))
        description = ""
    elif len(description) > STRING_MAX:
        problems.add(DesignError("description", f"is {len(description):,} characters long",
                                 f"at most {STRING_MAX:,} characters"))
        description = ""
    unit = data.get("length_unit")
    if unit is not None and unit not in LENGTH_UNITS:
        problems.add(DesignError("length_unit", f"{unit!r} is not a valid choice", ", ".join(map(repr, LENGTH_UNITS))))
        unit = None
    drive = data.get("drive", {})
    if not isinstance(drive, dict):
        problems.add(DesignError("drive", f"expected a table, got {type(drive).__name__}"))
        drive = {}
    for key in drive:
        if key not in ("type", "preload"):
            problems.add(unknown_key(f"drive.{key}", key, ("type", "preload"), "type, preload"))
    drive_type = drive.get("type")
    if drive_type is not None and drive_type not in DRIVE_TYPES:
        problems.add(DesignError("drive.type", f"{drive_type!r} is not a valid choice", "'type1', 'type2'"))
        drive_type = None
    preload = drive.get("preload")
    if preload is not None and preload not in PRELOAD_METHODS:
        problems.add(DesignError("drive.preload", f"{preload!r} is not a valid choice",
                                 ", ".join(map(repr, PRELOAD_METHODS))))
        preload = None
    defaults = data.get("gear_defaults", {})
    if not isinstance(defaults, dict):
        problems.add(DesignError("gear_defaults", f"expected a table, got {type(defaults).__name__}",
                                 "a [gear_defaults] table of keys shared by every gear"))
        defaults = {}
    gear_tables = data.get("gears", {})
    if not isinstance(gear_tables, dict):
        problems.add(DesignError("gears", f"expected tables [gears.NAME], got {type(gear_tables).__name__}"))
        gear_tables = {}
    gears: dict[str, GearSpec] = {}
    labels: dict[str, str] = {}
    for gname, table in gear_tables.items():
        if problems.run(check_name, f"gears.{gname}", gname, GEAR_NAME_MAX) is None:
            continue
        if not isinstance(table, dict):
            problems.add(DesignError(f"gears.{gname}", f"expected a table, got {type(table).__name__}"))
            continue
        try:
            # the table's key is the gear's identity (what every other section names it by); its
            # ``name`` key, read and checked with the gear, only labels it
            gears[gname] = read_gear({**defaults, **table}, where=f"gears.{gname}", name=gname, length_unit=unit)
        except DesignError as exc:
            problems.add(_from_defaults(exc, gname, table, defaults))
            continue
        if isinstance(table.get("name"), str) and table["name"] != gname:
            labels[gname] = table["name"]
    for error in _name_clashes(gear_tables, labels):
        problems.add(error)
    if unit is None:
        units = {g.length_unit for g in gears.values()}
        unit = units.pop() if len(units) == 1 else "mm"
    sections = {}
    for k, v in data.items():
        if k in SECTIONS and k not in ("drive", "gear_defaults", "gears"):
            if isinstance(v, dict):
                sections[k] = v
            else:
                problems.add(DesignError(k, f"expected a table, got {type(v).__name__}", f"a [{k}] table"))
    design = Design(name=name, length_unit=unit, gears=gears, sections=sections, description=description,
                    drive_type=drive_type, preload_method=preload, path=path, sha256=sha256,
                    defaulted=defaulted, labels=labels,
                    unit_warnings=tuple(other_unit_warnings({k: v for k, v in data.items() if isinstance(v, Mapping)},
                                                            unit)))
    if validate:
        from geargen.design.validate import validate_sections  # it reads the sections with their own modules

        for gname, spec in gears.items():
            if isinstance(spec, GearSpec):  # the other families check their teeth in their readers
                problems.run(_check_gear_tooth, gname, spec, gear_tables[gname], defaults, unit)
        if design.section("layout") or design.section("synthesis"):
            # the one internal gear a drive may hold: a planetary stage's ring
            rings = {t.get("ring") for t in (design.section("stages") or {}).values()
                     if isinstance(t, Mapping) and t.get("kind") == "planetary" and isinstance(t.get("ring"), str)}
            for gname, spec in gears.items():
                if getattr(spec, "kind", "external") != "external" and not (getattr(spec, "is_internal", False)
                                                                            and gname in rings):
                    problems.add(DesignError(f"gears.{gname}.kind", f"{spec.kind!r}: the drives geargen places "
                                             "([layout] dual_pinion, split_pinion) are of external gears",
                                             "'external', or the gear in its own design file"))
        validate_sections(design, problems, len(gears) == len(gear_tables), tuple(gear_tables))
    problems.raise_any(path.name if path else None)
    return design


def default_hardware(data: Mapping[str, Any]) -> tuple[Any, tuple[Defaulted, ...]]:
    """``data`` (the parsed file) completed with the default hardware of its drive kind (the rules
    of ``geargen/drives/<kind>/defaults.py``, reached through the kind's keys module), and what was
    added; unchanged where the file gives its hardware."""
    if not isinstance(data, Mapping):
        return data, ()
    kind = KEYS[kind_of(data)]
    readers = Readers(design=design_from_dict, layout=layout_settings, preload=preload_spec_from_table,
                      torque_units=QUANTITY_SUFFIXES["torque"])
    # the keys the file must give: the required ones and those its kind needs of this file
    needed = getattr(kind, "parts_needed", lambda sections: ())(data)
    fields = [replace(f, required=True) if f.name in needed else f for f in hardware_fields(kind.NAME)]
    return kind.defaults.complete(data, readers, fields)


def _name_clashes(gear_tables: Mapping[str, Any], labels: Mapping[str, str]) -> list[DesignError]:
    """Two gears that one name would stand for: keys alike but for case (their files are one on
    macOS and Windows), or a label that is another gear's key or label."""
    out = []
    seen: dict[str, str] = {}  # casefolded key or label -> the gear table holding it
    for gname in gear_tables:
        folded = str(gname).casefold()
        if folded in seen:
            out.append(DesignError(f"gears.{gname}", f"differs from gears.{seen[folded]} only in case: both name "
                                   "the same files on macOS and Windows", "gear names that differ in more than case"))
        seen.setdefault(folded, gname)
    for gname, label in labels.items():
        other = seen.get(label.casefold())
        if other is not None and other != gname:
            out.append(DesignError(f"gears.{gname}.name", f"{label!r} is also the name of gears.{other}",
                                   "a label no other gear has"))
        seen.setdefault(label.casefold(), gname)
    return out


def _from_defaults(error: DesignError, gear: str, table: Mapping[str, Any], defaults: Mapping[str, Any]) -> DesignError:
    """A gear's error about a key it took from ``[gear_defaults]``, named where the file has it."""
    if isinstance(error, DesignErrors):  # several unknown keys of one table
        return DesignErrors([_from_defaults(e, gear, table, defaults) for e in error.errors])
    prefix = f"gears.{gear}."
    if error.field.startswith(prefix):
        key = error.field[len(prefix):].split("[")[0]
        if key not in table and key in defaults:
            return DesignError(f"gear_defaults.{error.field[len(prefix):]}", error.problem, error.allowed)
    return error


def _check_gear_tooth(gear: str, spec: GearSpec, table: Mapping[str, Any], defaults: Mapping[str, Any],
                      unit: str) -> None:
    """:func:`geargen.design.feasibility.check_tooth` for ``[gears.GEAR]`` (merged with the defaults)."""
    merged = {**defaults, **table}
    # a profile shift written in the transverse system is x_t = x_n cos(beta)
    transverse = merged.get("pitch_system") == "transverse" and spec.helix_angle > 0
    try:
        check_tooth(spec, f"gears.{gear}", gear_keys_written(merged), unit,
                    1.0 / math.cos(spec.helix_angle) if transverse else 1.0)
    except DesignError as exc:
        raise _from_defaults(exc, gear, table, defaults) from None


def load_design(path: str | Path) -> Design:
    """Load a design file and validate all of it: every section, the rules between sections, and
    whether its gears, springs and flexures can be made (see :func:`design_from_dict`)."""
    path = Path(path).resolve()
    data, raw = read_toml(path)
    digest = hashlib.sha256(raw).hexdigest()
    return design_from_dict(data, path=path, sha256=digest, validate=True)
