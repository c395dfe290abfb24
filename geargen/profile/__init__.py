"""2-D tooth outlines as numpy arrays (exact involute and trochoid), no CAD kernel."""

from geargen.profile.segments import ArcCurve, InvoluteCurve, Segment, outline_area, sample_outline
from geargen.profile.tooth import (FilletCurve, ToothProfile, UndercutWarning, section_rotation,
                                   tooth_profile, twist_rate)

__all__ = ["ArcCurve", "InvoluteCurve", "Segment", "outline_area", "sample_outline", "FilletCurve",
           "ToothProfile", "UndercutWarning", "section_rotation", "tooth_profile", "twist_rate"]
