"""The external cylindrical involute gear (spur or helical): :class:`geargen.design.gear.GearSpec`
with ``kind = "external"``; its spec, profile, solid and data are the project's common gear
(``design/gear.py``, ``profile/``, ``cad/gear_solid.py``, ``model/gear_data.py``)."""

from __future__ import annotations

from geargen.design.gear import GEAR_FIELDS, gear_from_table
from geargen.families.family import ToothForm

KIND = "external"
FIELDS = GEAR_FIELDS
read_table = gear_from_table
RATING_SCOPE = None  # rated by ISO 6336
TOOTH_FORM = ToothForm(curvature=+1)  # convex flanks, one helix, rim under the root


def build(spec, check: bool = False, tolerance: float | None = None):
    from geargen.cad.gear_solid import build_gear
    return build_gear(spec, tolerance, check=check)


def gear_data(spec) -> None:
    return None  # from the tooth profile: geargen.model.gear_data.gear_data


def drawings(data, spec, folder, name, source, design_file) -> None:
    return None  # the cylindrical gear drawing: geargen.report.drawing.gear_drawings


def toothed_mass(spec, back: str) -> None:
    return None  # a gear of the layout: its outline's mass (geargen.model.mass.gear_mass)


def options() -> None:
    return None  # the common options only
