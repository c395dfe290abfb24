"""The double-helical gear: two helical halves of opposite hand (a :class:`geargen.design.gear.GearSpec`
with ``kind = "double_helical"`` and its ``centre_gap``): read, rated, described and drawn as the
external cylindrical gear; its own file is the solid."""

from __future__ import annotations

from geargen.families.external import family as external
from geargen.families.family import ToothForm

KIND = "double_helical"
FIELDS = external.FIELDS
read_table = external.read_table
RATING_SCOPE = external.RATING_SCOPE
TOOTH_FORM = ToothForm(curvature=+1, helices=2)  # two halves of opposite hand, b/2 each
gear_data = external.gear_data
drawings = external.drawings
options = external.options  # the common options (--centre-gap among them)


def build(spec, check: bool = False, tolerance: float | None = None):
    from geargen.families.double_helical.solid import build_double_helical
    return build_double_helical(spec, tolerance, check=check)
