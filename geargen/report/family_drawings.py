"""The drawing of a gear of a family other than the cylindrical gear (:mod:`geargen.report.drawing`):
the family's sheet module by its kind, one entry point for ``geargen gear`` and the build."""

from __future__ import annotations

import importlib

#: kind -> "module:function" writing that kind's sheets, taking ``(data, spec, folder, name, source,
#: design_file)`` and returning ``{"svg"|"pdf": path}``
FAMILY_DRAWINGS: dict[str, str] = {
    "bevel": "geargen.families.bevel.drawing:bevel_drawings",
    "worm": "geargen.families.worm.drawing:worm_drawings",
    "rack": "geargen.families.rack.drawing:rack_drawings",
    "worm_wheel": "geargen.families.worm.drawing:worm_drawings",
}


def family_drawings(data: dict, spec, folder, name: str, source: str, design_file: str) -> dict:
    """The sheets of ``spec``'s kind (none for a kind without a sheet module)."""
    entry = FAMILY_DRAWINGS.get(getattr(spec, "kind", None))
    if entry is None:
        return {}
    module, function = entry.split(":")
    return getattr(importlib.import_module(module), function)(data, spec, folder, name, source, design_file)


__all__ = ["FAMILY_DRAWINGS", "family_drawings"]
