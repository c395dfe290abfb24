"""The dual pinion with a radial-motion preload carriage (the robot joint, Fig. 10)."""

from geargen.drives.dual_pinion import bevel_verdict, hardware, keys, place, starter
from geargen.drives.kind import DriveKind
from geargen.drives.planetary import verdict as planetary_verdict
from geargen.drives.dual_pinion.shafts import carriage_shafts


def rows(layout, result) -> list:
    """The bevel pair's rows and an upstream planetary stage's (the meshes the mesh checker leaves)."""
    return bevel_verdict.rows(layout, result) + planetary_verdict.planetary_meshes(layout, result)


DRIVE = DriveKind(name=keys.NAME, keys=keys, place=place.place, hardware=hardware.carriage_hardware,
                  shafts=carriage_shafts, rows=rows, symmetry_line=keys.SYMMETRY_LINE,
                  starters=starter.STARTERS)
