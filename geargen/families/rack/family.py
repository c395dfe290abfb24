"""The rack: :class:`geargen.families.rack.spec.RackSpec` (``kind = "rack"``)."""

from __future__ import annotations

from geargen.families.rack.spec import RACK_FIELDS, rack_from_table
from geargen.families.family import ToothForm

KIND = "rack"
FIELDS = RACK_FIELDS
read_table = rack_from_table
RATING_SCOPE = None  # rated by ISO 6336
TOOTH_FORM = ToothForm(curvature=0)  # straight flanks: rho and u infinite, its root a rack's


def build(spec, check: bool = False, tolerance: float | None = None):
    from geargen.families.rack.solid import build_rack
    return build_rack(spec, check=check)  # fits its outline with its own tolerance


def gear_data(spec) -> dict:
    from geargen.families.rack.data import rack_data
    return rack_data(spec)


def drawings(data, spec, folder, name, source, design_file) -> dict:
    from geargen.families.rack.drawing import rack_drawings
    return rack_drawings(data, spec, folder, name, source, design_file)


def toothed_mass(spec, back: str) -> None:
    return None  # a drive's rack is a gear of the layout, not a toothed hardware part


def options():
    from geargen.families.rack import options
    return options
