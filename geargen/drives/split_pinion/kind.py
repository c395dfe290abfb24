"""The concentric Type 1 split pinion (Fig. 8)."""

from geargen.drives.kind import DriveKind
from geargen.drives.split_pinion import hardware, keys, place
from geargen.model.shafts import split_pinion_shafts

DRIVE = DriveKind(name=keys.NAME, keys=keys, place=place.place, hardware=hardware.split_pinion_hardware,
                  shafts=split_pinion_shafts, symmetry_line=keys.SYMMETRY_LINE)
