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

Each step validates its own section with :func:`geargen.design.schema.read_table`, so an
unknown key anywhere is an error that names it. Unknown top-level sections are errors here.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from geargen.design.gear import GearSpec, gear_from_table
from geargen.design.schema import load_toml
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES, LENGTH_UNITS

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
    "parts": "non-gear parts of the assembly model (geargen.cad.assembly)",
    "layout": "placement of gears without synthesis (geargen.cad.assembly)",
    "export": "export settings: STL tolerance, colours (geargen.cad.export)",
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

    @property
    def mm_per_unit(self) -> float:
        """mm in one of the design's length units (25.4 for an inch design)."""
        return LENGTH_SUFFIXES[self.length_unit]

    def section(self, name: str) -> dict[str, Any]:
        """The raw table of a section (empty when the file has none)."""
        if name not in SECTIONS:
            raise KeyError(f"{name!r} is not a design-file section")
        return self.sections.get(name, {})

    def gear(self, name: str) -> GearSpec:
        try:
            return self.gears[name]
        except KeyError:
            raise DesignError(f"gears.{name}", "missing", ", ".join(self.gears) or "a [gears.NAME] table") from None

    def resolve(self, relative: str | Path) -> Path:
        """A path written in the design file, relative to the file's folder."""
        base = self.path.parent if self.path else Path.cwd()
        return (base / relative).resolve()


def design_from_dict(data: Mapping[str, Any], path: Path | None = None, sha256: str = "") -> Design:
    unknown = [k for k in data if k not in SECTIONS and k not in TOP_KEYS]
    if unknown:
        raise DesignError(unknown[0], "unknown key or section", ", ".join(list(TOP_KEYS) + list(SECTIONS)))
    name = data.get("name", path.stem if path else "design")
    if not isinstance(name, str) or not name or any(c in name for c in "/\\") or name.startswith("."):
        raise DesignError("name", f"{name!r} is not a valid name", "a non-empty file-name-safe string")
    unit = data.get("length_unit")
    drive = data.get("drive", {})
    if not isinstance(drive, dict):
        raise DesignError("drive", "expected a table")
    bad = [k for k in drive if k not in ("type", "preload")]
    if bad:
        raise DesignError(f"drive.{bad[0]}", "unknown key", "type, preload")
    drive_type = drive.get("type")
    if drive_type is not None and drive_type not in DRIVE_TYPES:
        raise DesignError("drive.type", f"{drive_type!r} is not a valid choice", "'type1', 'type2'")
    preload = drive.get("preload")
    if preload is not None and preload not in PRELOAD_METHODS:
        raise DesignError("drive.preload", f"{preload!r} is not a valid choice", ", ".join(map(repr, PRELOAD_METHODS)))
    defaults = data.get("gear_defaults", {})
    gear_tables = data.get("gears", {})
    if not isinstance(defaults, dict) or not isinstance(gear_tables, dict):
        raise DesignError("gears", "expected tables [gear_defaults] and [gears.NAME]")
    gears: dict[str, GearSpec] = {}
    for gname, table in gear_tables.items():
        if not isinstance(table, dict):
            raise DesignError(f"gears.{gname}", "expected a table")
        merged = {**defaults, **table}
        spec = gear_from_table(merged, where=f"gears.{gname}", name=gname, length_unit=unit)
        gears[gname] = spec
    if unit is None:
        units = {g.length_unit for g in gears.values()}
        unit = units.pop() if len(units) == 1 else "mm"
    if unit not in LENGTH_UNITS:
        raise DesignError("length_unit", f"{unit!r} is not a valid choice", ", ".join(map(repr, LENGTH_UNITS)))
    sections = {k: v for k, v in data.items() if k in SECTIONS and k not in ("drive", "gear_defaults", "gears")}
    for k, v in sections.items():
        if not isinstance(v, dict):
            raise DesignError(k, "expected a table")
    return Design(name=name, length_unit=unit, gears=gears, sections=sections,
                  description=str(data.get("description", "")), drive_type=drive_type,
                  preload_method=preload, path=path, sha256=sha256)


def load_design(path: str | Path) -> Design:
    """Load and validate an assembly design file."""
    path = Path(path).resolve()
    data = load_toml(path)
    digest = hashlib.sha256(path.read_bytes()).hexdigest()
    return design_from_dict(data, path=path, sha256=digest)

