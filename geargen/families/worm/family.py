"""The worm of a worm set: :class:`geargen.families.worm.spec.WormSpec` (``kind = "worm"``), read
from the set's table with its wheel (:mod:`geargen.families.worm_wheel` shares the table)."""

from __future__ import annotations

from geargen.families.worm.spec import WORM_FIELDS, worm_set_from_table

KIND = "worm"
FIELDS = WORM_FIELDS
read_table = worm_set_from_table
RATING_SCOPE = "not rated by ISO 6336: worm gears are rated by ISO/TS 14521 (not implemented)"
TOOTH_FORM = None  # not a cylindrical involute form (nor rated by ISO 6336)


def build(spec, check: bool = False, tolerance: float | None = None):
    from geargen.families.worm.solid import build_worm
    return build_worm(spec, check=check)  # its own fit tolerance


def gear_data(spec) -> dict:
    """The part's data and, for the set, the pair's backlash as the pair check finds it."""
    from geargen.families.worm.data import pair_check_data, worm_part_data
    from geargen.families.worm.pair import worm_pair_check
    return worm_part_data(spec) | {"pair_check": pair_check_data(worm_pair_check(spec.set), spec.length_unit)}


def drawings(data, spec, folder, name, source, design_file) -> dict:
    from geargen.families.worm.drawing import worm_drawings
    return worm_drawings(data, spec, folder, name, source, design_file)


def toothed_mass(spec, back: str) -> None:
    return None  # no drive holds a worm set as a toothed hardware part


def options():
    from geargen.families.worm import options
    return options
