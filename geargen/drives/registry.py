"""Every drive kind (:class:`geargen.drives.kind.DriveKind`), by name: one line per kind."""

from geargen.drives.axial_preload.kind import DRIVE as AXIAL_PRELOAD
from geargen.drives.beam_pinion.kind import DRIVE as BEAM_PINION
from geargen.drives.dual_pinion.kind import DRIVE as DUAL_PINION
from geargen.drives.rack_dual_pinion.kind import DRIVE as RACK_DUAL_PINION
from geargen.drives.split_pinion.kind import DRIVE as SPLIT_PINION

DRIVES = {d.name: d for d in (DUAL_PINION, BEAM_PINION, SPLIT_PINION, AXIAL_PRELOAD, RACK_DUAL_PINION)}

__all__ = ["DRIVES"]
