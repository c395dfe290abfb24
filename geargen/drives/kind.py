"""What a drive kind provides (:class:`DriveKind`): the interface the resolver, the verdict and
the commands call, so that none of them asks which drive a design is.

Each kind's ``kind.py`` builds one :class:`DriveKind` from its own modules (``keys``, ``place``,
``hardware``, ``verdict``) and :mod:`geargen.drives.registry` collects them (from the kinds registered
in :mod:`geargen.drives.keys`). The resolved drive
carries its kind (:attr:`geargen.model.Layout.drive`), so the verdict and the reports reach the
kind's own rows through the data, never by importing a kind.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType
from typing import Any, Callable, Mapping


def _no_rows(layout, result) -> list[dict[str, Any]]:
    return []


def two_loop_meshes(layout, gear_ratio) -> list[tuple[Any, str, float, str]]:
    """The loop's stages of a dual pinion: mesh 1 and mesh 2 (the engaged ones), each with the
    parts on its driven shaft (``gear_ratio(gear)``: that gear's speed over the output's)."""
    out = []
    for label in ("mesh1", "mesh2"):
        mesh = next(m for m in layout.meshes if m.name.startswith(label) and m.engaged)
        out.append((mesh, f"loop stage {label[-1]} ({mesh.gear1.name}-{mesh.gear2.name})",
                    gear_ratio(mesh.gear2.name), "loop: preloaded"))
    return out


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
    - ``loop_stages(layout, gear_ratio) -> [(mesh, name, ratio, source)]``: the preloaded loop as
      the train's stages (``geargen train``), each a placed mesh with the speed of its driven
      shaft over the output's;
    - ``beam_supports(layout, engagement) -> (lower, upper) N/mm``: the structure's stiffness
      under a beam-spring pinion's bearings, or None (no beam-spring pinion: rigid);
    - ``carriage_error_budget``: the synthesis error budget is a travel of its preload carriage
      (a radial or axial carriage sets the preload; the beam-spring pinion's does not);
    - ``starters``: its ``geargen new`` starters by length unit (``{"mm": Starter, "in": Starter}``,
      :class:`geargen.design.starters.Starter`), or None;
    - ``frame``: how the model's frame lies, for the reports.
    """

    name: str
    keys: ModuleType
    place: Callable[..., Any]
    hardware: Callable[..., Any]
    shafts: Callable[..., Any] | None = None
    rows: Callable[..., list] = _no_rows
    symmetry_line: bool = False
    loop_stages: Callable[..., list] = two_loop_meshes
    beam_supports: Callable[..., Any] | None = None
    carriage_error_budget: bool = True
    starters: Mapping[str, Any] | None = None
    frame: str = "the output gear's centre at the origin, +x along the symmetry line towards the input"


__all__ = ["DriveKind", "two_loop_meshes"]
