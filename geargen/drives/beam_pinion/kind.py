"""The dual pinion whose long input pinion is a beam spring, sliding into mesh (the C-axis, Fig. 12)."""

from geargen.drives.beam_pinion import hardware, keys
from geargen.drives.dual_pinion import place
from geargen.drives.kind import DriveKind
from geargen.drives.beam_pinion.shafts import beam_pinion_shafts, beam_supports

DRIVE = DriveKind(name=keys.NAME, keys=keys, place=place.place, hardware=hardware.beam_pinion_hardware,
                  shafts=beam_pinion_shafts, symmetry_line=keys.SYMMETRY_LINE,
                  beam_supports=beam_supports, carriage_error_budget=False)
