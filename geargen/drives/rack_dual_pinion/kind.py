"""The Type 2 dual-pinion rack drive (Fig. 4 done as Type 2)."""

from geargen.drives.kind import DriveKind
from geargen.drives.rack_dual_pinion import hardware, keys, place, verdict

DRIVE = DriveKind(name=keys.NAME, keys=keys, place=place.place_rack_drive, hardware=hardware.rack_drive_hardware,
                  rows=verdict.rack_meshes, symmetry_line=keys.SYMMETRY_LINE,
                  frame="the rack's pitch line along x, its teeth toward +y, the symmetry line (the preload "
                        "carriage's motion) on the y axis")
