"""The straight bevel gear: :class:`geargen.families.bevel.spec.BevelGearSpec` (``kind = "bevel"``)."""

from __future__ import annotations

from geargen.families.bevel.spec import BEVEL_FIELDS, bevel_from_table

KIND = "bevel"
FIELDS = BEVEL_FIELDS
read_table = bevel_from_table
RATING_SCOPE = "not rated by ISO 6336: bevel gears are rated by ISO 10300 (not implemented)"
TOOTH_FORM = None  # not a cylindrical involute form (nor rated by ISO 6336)


def build(spec, check: bool = False, tolerance: float | None = None):
    from geargen.families.bevel.solid import build_bevel
    return build_bevel(spec, check=check, back=spec.back)  # the back the spec states; its own fit tolerance


def gear_data(spec) -> dict:
    from geargen.families.bevel.data import bevel_gear_data
    return bevel_gear_data(spec)


def drawings(data, spec, folder, name, source, design_file) -> dict:
    from geargen.families.bevel.drawing import bevel_drawings
    return bevel_drawings(data, spec, folder, name, source, design_file)


def toothed_mass(spec, back: str) -> tuple[float, float]:
    """Its closed forms: volume (mm^3) and axial moment (mm^5) of the solid with ``back``."""
    from geargen.families.bevel.geometry import bevel_axial_moment, bevel_volume
    return bevel_volume(spec, back), bevel_axial_moment(spec, back)


def options():
    from geargen.families.bevel import options
    return options
