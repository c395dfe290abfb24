"""Every gear family (:class:`geargen.families.family.GearFamily`), by kind: one import line per
family, which is its registration (:data:`FAMILIES` holds every ``family`` module imported here, in
the order of the lines)."""

from __future__ import annotations

from types import ModuleType

from geargen.errors import DesignError
from geargen.families.family import GearFamily, ToothForm

# a family's line: its registration (in FAMILIES' order, not sorted)
from geargen.families.external import family as external
from geargen.families.internal import family as internal
from geargen.families.double_helical import family as double_helical
from geargen.families.rack import family as rack
from geargen.families.worm import family as worm
from geargen.families.worm_wheel import family as worm_wheel
from geargen.families.bevel import family as bevel

FAMILIES: dict[str, GearFamily] = {module.KIND: module for module in dict(globals()).values()
                                   if isinstance(module, ModuleType) and module.__name__.startswith("geargen.families.")
                                   and module.__name__.endswith(".family") and hasattr(module, "KIND")}


def family_of(spec) -> GearFamily:
    """The family of a gear spec (by its ``kind``; a spec without one is an external gear's)."""
    return FAMILIES[getattr(spec, "kind", "external")]


def tooth_form(spec) -> ToothForm | None:
    """The :class:`~geargen.families.family.ToothForm` of a spec's family (a spec without a ``kind``
    is an external gear's); None for a form that is not cylindrical involute (bevel, worm) or a
    ``kind`` no family has."""
    family = FAMILIES.get(getattr(spec, "kind", "external"))
    return None if family is None else family.TOOTH_FORM


def read_gear(data, where: str = "gear", name: str | None = None, length_unit: str | None = None):
    """Any family's spec from a ``[gear]``/``[gears.NAME]`` table, by its ``kind`` key (default
    external; a kind no family has is refused, naming the kinds)."""
    kind = data.get("kind", "external") if hasattr(data, "get") else "external"
    family = FAMILIES.get(kind) if isinstance(kind, str) else None
    if family is None and isinstance(kind, str):
        raise DesignError(f"{where}.kind", f"{kind!r} is not a valid choice", ", ".join(map(repr, FAMILIES)))
    return (family or external).read_table(data, where=where, name=name, length_unit=length_unit)


__all__ = ["FAMILIES", "family_of", "read_gear", "tooth_form"]
