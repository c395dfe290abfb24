"""Field helpers the drive kinds' keys share (the design layer's schema, no more)."""

from __future__ import annotations

from geargen.design.schema import Field


def positive_length(name: str, **kw) -> Field:
    """A length key that must be above zero."""
    return Field(name, "length", minimum=0.0, exclusive_minimum=True, **kw)


#: the [parts] key every drive's hardware reads
BEARING_CLEARANCE = Field("bearing_clearance", "length", required=False, default=0.5, minimum=0.0,
                          help="axial gap between a bearing and the gear face next to it")



def part_key(v, name: str) -> str:
    """The file's spelling of the [parts] key ``name`` (its unit suffix as written), from the read
    table ``v`` (:func:`geargen.design.schema.read_table`)."""
    unit = v["_units"].get(name)
    return f"parts.{name}_{unit}" if unit else f"parts.{name}"


__all__ = ["positive_length", "BEARING_CLEARANCE", "part_key"]
