"""The ``[parts]`` section: the sizes of the non-gear parts, one key table per drive kind.

The drive the file describes (:func:`geargen.drives.kind_of`) decides which keys its hardware
reads (``PARTS_FIELDS`` of ``geargen/drives/<kind>/keys.py``). Every key is a size of one part
(bearings, shafts, motor, housing, ...), a length with its unit suffix. :func:`parts_settings`
reads the table; :func:`check_parts` adds the relations between sizes that no part can violate
(a bearing wider than its bore, walls that leave room inside), the sections the hardware is
sized from, and the kind's own rules (``check_parts`` of its keys module).
"""

from __future__ import annotations

from typing import Any

from geargen.design.schema import read_table
from geargen.drives.keys import KEYS, kind_of
from geargen.drives.fields import BEARING_CLEARANCE, part_key
from geargen.errors import DesignError
from geargen.units import LENGTH_SUFFIXES


def hardware_fields(kind: str) -> list:
    """The [parts] fields of a drive ``kind``'s hardware."""
    return [BEARING_CLEARANCE] + list(KEYS[kind].PARTS_FIELDS)


def parts_settings(design) -> dict[str, Any]:
    """``[parts]`` read for the drive's hardware (internal units, mm; ``"hardware"``: the drive kind)."""
    table = design.section("parts")
    kind = kind_of(design)
    if not table:
        raise DesignError("parts", "missing", f"a [parts] table sizing the {kind} drive's hardware")
    return {**read_table(table, hardware_fields(kind), "parts"), "hardware": kind}


def check_parts(design, v: dict[str, Any]) -> None:
    """The relations between part sizes, and the sections the hardware reads (see the module docstring)."""
    keys = KEYS[v["hardware"]]
    unit = design.length_unit
    scale = LENGTH_SUFFIXES[unit]
    for section in keys.NEEDS:
        if not design.section(section):
            raise DesignError(section, f"missing: the {keys.NAME} drive's parts are sized from it",
                              f"a [{section}] table")
    own = getattr(keys, "check_parts", None)
    if own is not None:
        own(design, v)
    for outer, inner in keys.MUST_EXCEED:
        if v.get(outer) is None or (not inner.startswith("gears.") and v.get(inner) is None):
            continue  # a key the kind leaves out in this design (another way its motor drives the input)
        if inner.startswith("gears."):
            gear = design.gears.get(inner[len("gears."):])
            if gear is None or gear.hub.bore_diameter <= 0:
                continue  # the layout names the missing gear; a gear without a bore sets no bearing bore
            d_inner, inner_text = gear.hub.bore_diameter, f"the bore of {inner}"
        else:
            d_inner, inner_text = v[inner], part_key(v, inner)
        if not v[outer] > d_inner:
            raise DesignError(part_key(v, outer), f"{v[outer] / scale:.6g} {unit} is not larger than {inner_text} "
                              f"({d_inner / scale:.6g} {unit})", f"> {d_inner / scale:.6g} {unit}")


__all__ = ["hardware_fields", "parts_settings", "check_parts"]
