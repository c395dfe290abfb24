"""One entry point to build any gear kind's solid: :func:`build_part`.

Cylindrical involute gears (:class:`geargen.design.gear.GearSpec`: external, and the kinds each
family registers) and the other families' specs (racks, bevel gears, worms, worm wheels) each
have their own builder module; :data:`BUILDERS` maps a kind to ``"module:function"`` taking
``(spec, check=False)`` and returning an object with ``shape``, ``name``, ``spec`` and
``length_unit`` (a :class:`geargen.cad.gear_solid.GearSolid` or the family's own).
"""

from __future__ import annotations

import importlib

#: kind -> "module:function" building that kind's solid
BUILDERS: dict[str, str] = {
    "external": "geargen.cad.gear_solid:build_gear",
    "rack": "geargen.families.rack.solid:build_rack",
    "internal": "geargen.families.internal.solid:build_internal",
    "double_helical": "geargen.families.double_helical.solid:build_double_helical",
    "worm": "geargen.families.worm.solid:build_worm",
    "worm_wheel": "geargen.families.worm_wheel.solid:build_worm_wheel",
    "bevel": "geargen.families.bevel.solid:build_bevel",
}


def part_kind(spec) -> str:
    """The kind of a gear spec: its ``kind`` attribute (every family spec has one)."""
    return getattr(spec, "kind", "external")


def build_part(spec, check: bool = False):
    """Build ``spec``'s solid with its kind's builder; ``check`` validates it (BuildError if not one
    valid closed solid)."""
    kind = part_kind(spec)
    if kind not in BUILDERS:
        raise ValueError(f"{kind!r} has no solid builder (the design reader knows {', '.join(map(repr, BUILDERS))})")
    module, function = BUILDERS[kind].split(":")
    if kind == "bevel":  # the back the spec states (flat by default, as the drive's pair is built)
        return getattr(importlib.import_module(module), function)(spec, check=check, back=spec.back)
    return getattr(importlib.import_module(module), function)(spec, check=check)


def build_toothed(toothed):
    """The solid of a toothed component of a drive's hardware (:class:`geargen.model.components.Toothed`):
    its family's solid, a bevel gear with the back the component asks for."""
    if getattr(toothed.spec, "kind", "") == "bevel":
        from geargen.families.bevel.solid import build_bevel
        return build_bevel(toothed.spec, check=True, back=toothed.back).shape
    return build_part(toothed.spec, check=True).shape
