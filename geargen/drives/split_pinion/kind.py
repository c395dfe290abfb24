"""The concentric Type 1 split pinion (Fig. 8)."""

from geargen.drives.kind import DriveKind
from geargen.drives.split_pinion import hardware, keys, place, starter
from geargen.drives.split_pinion.shafts import split_pinion_shafts


def loop_stages(layout, gear_ratio) -> list:
    """The loop as one stage: both pinions on the output, turning with the input."""
    mesh = layout.meshes[0]
    pinions = ", ".join(m.gear1.name for m in layout.meshes)
    return [(mesh, f"split pinion ({pinions} - {mesh.gear2.name})", 1.0, "loop: both pinions preloaded")]


DRIVE = DriveKind(name=keys.NAME, keys=keys, place=place.place, hardware=hardware.split_pinion_hardware,
                  shafts=split_pinion_shafts, symmetry_line=keys.SYMMETRY_LINE, loop_stages=loop_stages,
                  starters=starter.STARTERS)
