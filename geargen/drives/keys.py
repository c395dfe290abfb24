"""The drive-kind registry: one import line per drive kind, which is its registration. :data:`KEYS`
holds every kind's keys module imported here (its ``[layout]`` and ``[parts]`` keys and rules), by
the kind's name, in the order of the lines; the design loader reads it, and
:mod:`geargen.drives.registry` derives each kind's :class:`~geargen.drives.kind.DriveKind` from the
same module's package. :func:`kind_of` is the one place that says which drive a design is. Imports
only the kinds' keys modules (the design layer), so reading a design never loads a kind's placement
or hardware."""

from __future__ import annotations

from types import ModuleType
from typing import Any, Mapping

# a drive kind's line: its registration (in KEYS' order, not sorted: the order of the reference's
# and the refusals' lists of kinds)
from geargen.drives.dual_pinion import keys as dual_pinion
from geargen.drives.beam_pinion import keys as beam_pinion
from geargen.drives.split_pinion import keys as split_pinion
from geargen.drives.axial_preload import keys as axial_preload
from geargen.drives.rack_dual_pinion import keys as rack_dual_pinion

#: each drive kind's keys module, by the kind's name
KEYS: dict[str, ModuleType] = {module.NAME: module for module in dict(globals()).values()
                               if isinstance(module, ModuleType) and module.__name__.startswith("geargen.drives.")
                               and module.__name__.endswith(".keys") and hasattr(module, "NAME")}

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
