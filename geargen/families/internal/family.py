"""The internal (ring) gear: :class:`geargen.families.internal.spec.InternalGearSpec`
(``kind = "internal"``), the cylindrical gear's table with its ``rim_diameter``."""

from __future__ import annotations

from geargen.families.external import family as external
from geargen.families.family import ToothForm
from geargen.families.internal.spec import ring_from_table

KIND = "internal"
FIELDS = external.FIELDS  # the cylindrical gear's table (rim_diameter among its keys)
read_table = ring_from_table
RATING_SCOPE = external.RATING_SCOPE
#: concave flanks; its root rated as a rack's with its own basic rack, its rim outside the root circle
TOOTH_FORM = ToothForm(curvature=-1, rim_outside_root=True, root_note=(
    "internal gear root: ISO 6336-3's approximation by a rack (z_n -> infinity) with the ring's basic rack "
    "and tooth height"))


def build(spec, check: bool = False, tolerance: float | None = None):
    from geargen.families.internal.solid import build_internal
    return build_internal(spec, tolerance, check=check)


def gear_data(spec) -> dict:
    from geargen.families.internal.data import internal_gear_data
    return internal_gear_data(spec)


def drawings(data, spec, folder, name, source, design_file) -> None:
    return None  # no sheet of its own yet: the gear command writes its data only


def toothed_mass(spec, back: str) -> None:
    return None  # a drive's ring is a gear of the layout (geargen.model.mass.gear_mass)


def options():
    from geargen.families.internal import options
    return options
