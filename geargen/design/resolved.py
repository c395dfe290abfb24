"""What the resolved drive carries of its design file: the design's identity and its settings,
read and validated once (issue 26), so nothing downstream of :func:`geargen.drives.resolver.resolve`
reads the design file again.

:class:`DesignIdentity`: the name, source path and length unit the reports and exports name.
:class:`ResolvedSettings`: each section a downstream module needs, read by the module that owns
it (``[checks]`` by :func:`geargen.design.checks.checks_settings`, ...) the first time it is
asked for and kept: a section the drive never needs is never read (a design built without
validation, e.g. while its defaults are sized, is placed without the sections it lacks being
refused), and one it needs is read once per resolved drive.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

from geargen.design.checks import checks_settings
from geargen.design.duty import duty_settings
from geargen.design.export import export_settings
from geargen.design.parts import parts_settings
from geargen.design.stages import stages
from geargen.design.stiffness import stiffness_design
from geargen.design.train import train_settings
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


class ResolvedSettings:
    """The design's sections as the drive's downstream modules read them, each read by its own
    reader once (see the module docstring); internal units."""

    def __init__(self, design) -> None:
        self._design = design

    def has(self, section: str) -> bool:
        """Whether the file gives (or the default hardware fills in) ``[section]``."""
        return bool(self._design.section(section))

    @cached_property
    def checks(self):
        """``[checks]`` (:class:`geargen.design.checks.ChecksSettings`; absent: every default)."""
        return checks_settings(self._design)

    @cached_property
    def export(self) -> dict[str, Any]:
        """``[export]`` (:func:`geargen.design.export.export_settings`)."""
        return export_settings(self._design)

    @cached_property
    def parts(self) -> dict[str, Any]:
        """``[parts]`` for the drive's hardware (:func:`geargen.design.parts.parts_settings`); refused
        when the design has none (ask :meth:`has` first)."""
        return parts_settings(self._design)

    @cached_property
    def train(self):
        """``[train]`` (:class:`geargen.design.train.TrainSettings`; absent: every default)."""
        return train_settings(self._design)

    @cached_property
    def stiffness(self):
        """The stiffness-step sections (:class:`geargen.design.stiffness.StiffnessDesign`)."""
        return stiffness_design(self._design)

    @cached_property
    def stages(self) -> tuple:
        """The upstream stages of ``[stages]`` (:func:`geargen.design.stages.stages`)."""
        return stages(self._design)

    @cached_property
    def duty(self):
        """``[duty]`` (:class:`geargen.design.duty.DutySpec`; absent: every default)."""
        return duty_settings(self._design)


__all__ = ["DesignIdentity", "ResolvedSettings", "identity_of"]
