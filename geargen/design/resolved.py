"""What the resolved drive carries of its design file's identity (issue 26): the name, source path
and length unit the reports and exports name, so nothing downstream of
:func:`geargen.drives.resolver.resolve` reads them off the design (its settings:
:class:`geargen.model.layout.ResolvedSettings`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from geargen.units import LENGTH_SUFFIXES, TextUnits


@dataclass(frozen=True)
class DesignIdentity:
    """Which design a resolved drive is, and the units its reports speak: ``name`` and ``path``
    of the file (``sha256`` of its bytes), ``length_unit`` ("mm" or "in") with the text units
    its reports use, the values the file did not give (``defaulted``), its gears' labels, and the
    gears whose table writes its thinning as a normal thinning (``thinning_normal_*``: a fix to
    it is written in that key)."""

    name: str
    length_unit: str
    text_units: TextUnits
    path: Path | None = None
    sha256: str = ""
    description: str = ""
    drive_type: str | None = None
    preload_method: str | None = None
    defaulted: tuple = ()
    unit_warnings: tuple[str, ...] = ()
    labels: dict[str, str] = field(default_factory=dict)
    normal_thinning: frozenset[str] = frozenset()

    @property
    def mm_per_unit(self) -> float:
        """mm in one of the design's length units (25.4 for an inch design)."""
        return LENGTH_SUFFIXES[self.length_unit]

    def label(self, gear: str) -> str:
        """What reports and exports call the gear of table key ``gear``: its ``name``, else the key."""
        return self.labels.get(gear, gear)


def identity_of(design) -> DesignIdentity:
    """The identity of a loaded :class:`~geargen.design.assembly.Design`."""
    return DesignIdentity(name=design.name, length_unit=design.length_unit, text_units=design.text_units,
                          path=design.path, sha256=design.sha256, description=design.description,
                          drive_type=design.drive_type, preload_method=design.preload_method,
                          defaulted=tuple(design.defaulted), unit_warnings=tuple(design.unit_warnings),
                          labels=dict(design.labels),
                          normal_thinning=frozenset(name for name, table in design.section("gears").items()
                                                    if isinstance(table, dict)
                                                    and any(key.startswith("thinning_normal_") for key in table)))


__all__ = ["DesignIdentity", "identity_of"]
