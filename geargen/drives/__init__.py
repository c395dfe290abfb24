"""Drive kinds: each kind of anti-backlash drive in a folder of its own, ``geargen/drives/<kind>/``.

A kind's folder holds:

- ``keys.py``: its ``[layout]`` and ``[parts]`` keys and their rules (design layer: the loader
  reads them through :data:`KEYS`, this module, which imports nothing else);
- ``place.py``: its gears placed from the design (:class:`geargen.model.Layout`);
- ``hardware.py``: its non-gear parts and joints laid out as data (:mod:`geargen.model.components`);
- ``kind.py``: its :class:`geargen.drives.kind.DriveKind`, what the resolver and the verdict call
  (placement, hardware, extra verdict rows, starter file);

and registers in two lines: its keys module in :data:`KEYS` here, its kind in
:mod:`geargen.drives.registry`. Upstream stages (a planetary stage) live alike in their own folder.
:mod:`geargen.drives.resolver` resolves a design (gears placed, hardware laid out); nothing else
asks which drive a design is: :func:`kind_of` answers once.
"""

from __future__ import annotations

from typing import Any, Mapping

from geargen.drives.axial_preload import keys as axial_preload
from geargen.drives.beam_pinion import keys as beam_pinion
from geargen.drives.dual_pinion import keys as dual_pinion
from geargen.drives.rack_dual_pinion import keys as rack_dual_pinion
from geargen.drives.split_pinion import keys as split_pinion

#: each drive kind's keys module, by the kind's name
KEYS = {k.NAME: k for k in (dual_pinion, beam_pinion, split_pinion, axial_preload, rack_dual_pinion)}

#: the [layout] kinds a file may name (several drive kinds may share one: a dual pinion's hardware)
LAYOUT_KINDS = tuple(dict.fromkeys(k.LAYOUT_KIND for k in KEYS.values()))


def kind_of(data: Any) -> str:
    """The drive kind of a loaded design or of the parsed file: its ``[layout] kind`` (a dual
    pinion when it has none), a dual pinion with a ``[beam_pinion]`` being the beam-spring kind."""
    sections: Mapping[str, Any] = data.sections if hasattr(data, "sections") else data
    layout = sections.get("layout") if isinstance(sections.get("layout"), Mapping) else {}
    named = layout.get("kind") or "dual_pinion"
    if named == "dual_pinion" and sections.get("beam_pinion"):
        return beam_pinion.NAME
    return next((k.NAME for k in KEYS.values() if k.LAYOUT_KIND == named and k.NAME == named), dual_pinion.NAME)


__all__ = ["KEYS", "LAYOUT_KINDS", "kind_of"]
