"""The double-helical gear: two helical halves of opposite hand
(:class:`geargen.families.double_helical.spec.DoubleHelicalGearSpec`, ``kind = "double_helical"``,
the cylindrical gear with its ``centre_gap``): rated, described and drawn as the external
cylindrical gear; its own files are its spec (the halves and the gap) and its solid."""

from __future__ import annotations

from geargen.families.double_helical.spec import double_helical_from_table
from geargen.families.external import family as external
from geargen.families.family import ToothForm

KIND = "double_helical"
FIELDS = external.FIELDS
read_table = double_helical_from_table
RATING_SCOPE = external.RATING_SCOPE
TOOTH_FORM = ToothForm(curvature=+1, helices=2)  # two halves of opposite hand, b/2 each
gear_data = external.gear_data
drawings = external.drawings
options = external.options  # the common options (--centre-gap among them)
toothed_mass = external.toothed_mass


def build(spec, check: bool = False, tolerance: float | None = None):
    from geargen.families.double_helical.solid import build_double_helical
    return build_double_helical(spec, tolerance, check=check)
