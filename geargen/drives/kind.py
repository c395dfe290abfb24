"""What a drive kind provides (:class:`DriveKind`): the interface the resolver, the verdict and
the commands call, so that none of them asks which drive a design is.

Each kind's ``kind.py`` builds one :class:`DriveKind` from its own modules (``keys``, ``place``,
``hardware``, ``verdict``) and :mod:`geargen.drives.registry` lists them. The resolved drive
carries its kind (:attr:`geargen.model.Layout.drive`), so the verdict and the reports reach the
kind's own rows through the data, never by importing a kind.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType
from typing import Any, Callable


def _no_rows(layout, result) -> list[dict[str, Any]]:
    return []


@dataclass(frozen=True)
class DriveKind:
    """A drive kind.

    - ``name``: the kind's name (its folder, ``keys.NAME``); ``keys``: its keys module;
    - ``place(design, settings) -> Layout``: its gears placed (``settings``: the [layout] read);
    - ``hardware(layout, parts, stiffness) -> Hardware``: its non-gear parts and joints
      (``parts``: the [parts] read; ``stiffness``: a callable giving the stiffness summary);
    - ``shafts(layout, parts) -> {name: Shaft}``: its placed shafts (the stiffness model and the
      hardware read the same), or None;
    - ``rows(layout, result) -> rows``: its own verdict rows (placed pairs the mesh checker does not
      check: a bevel pair, a planetary stage's ring meshes, rack meshes), each a dict with ``mesh``,
      ``kind`` and its numbers (mm, rad), failures appended to ``result``;
    - ``symmetry_line``: the layout figure draws the line the two paths mirror about;
    - ``starter``: the commented starter file of ``geargen new`` (metric and inch), or None;
    - ``frame``: how the model's frame lies, for the reports.
    """

    name: str
    keys: ModuleType
    place: Callable[..., Any]
    hardware: Callable[..., Any]
    shafts: Callable[..., Any] | None = None
    rows: Callable[..., list] = _no_rows
    symmetry_line: bool = False
    starter: Callable[[str], str] | None = None
    frame: str = "the output gear's centre at the origin, +x along the symmetry line towards the input"


__all__ = ["DriveKind"]
