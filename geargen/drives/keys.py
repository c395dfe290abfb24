"""Every drive kind's keys module (its [layout] and [parts] keys and rules), by the kind's name: what
the design loader reads (one line per kind), and :func:`kind_of`, the one place that says which
drive a design is. Imports only the kinds' keys modules (the design layer)."""

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
