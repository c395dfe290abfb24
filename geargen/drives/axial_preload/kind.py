"""The Type 2 axial-motion preload: helical pinions of both hands on a sliding input shaft."""

from geargen.drives.axial_preload import hardware, keys, place
from geargen.drives.kind import DriveKind

DRIVE = DriveKind(name=keys.NAME, keys=keys, place=place.place_axial_preload, hardware=hardware.axial_hardware,
                  symmetry_line=keys.SYMMETRY_LINE)
