"""The resolved drive (pure data, no CAD kernel): :func:`geargen.drives.resolve` decides every gear's teeth,
centre, height and phase once; every command and every export reads that one model."""

from geargen.model.layout import (BACKLASH_KIND, MODEL_TOOTH_THICKNESS, POSITIONS, GearPlacement, Layout,
                                  MeshPlacement, is_drive, layout_settings, running_backlash)

__all__ = ["BACKLASH_KIND", "MODEL_TOOTH_THICKNESS", "POSITIONS", "GearPlacement", "Layout", "MeshPlacement",
           "is_drive", "layout_settings", "running_backlash"]
