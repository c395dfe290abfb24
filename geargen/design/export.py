"""The ``[export]`` section: STL tolerances, the flank-spline tolerance of the gear solids, the view.

Every key is optional::

    [export]
    stl_chordal_tolerance_mm = 0.005        # gear STL within this of the exact flanks
    stl_chordal_tolerance_parts_mm = 0.05   # the other parts' STL
    stl_angular_tolerance_deg = 30
    gear_solid_tolerance_mm = 0.0001        # flank splines within this of the exact surface
    render_view = [-60, 30]                 # azimuth, elevation of the rendered view (deg)
    render_size = [9, 6.5]                  # figure width, height (inches of the PNG at its dpi)
"""

from __future__ import annotations

import math
from typing import Any

from geargen.design.schema import Field, read_table
from geargen.errors import DesignError

EXPORT_FIELDS = [
    Field("stl_chordal_tolerance", "length", required=False, default=0.005, minimum=0.0, exclusive_minimum=True,
          help="gear STL files (a drive's bevel pair too) within this of the exact flanks"),
    Field("stl_chordal_tolerance_parts", "length", required=False, default=0.05, minimum=0.0, exclusive_minimum=True,
          help="the other parts' STL files within this of their solids"),
    Field("stl_angular_tolerance", "angle", required=False, default=0.5, minimum=0.0, exclusive_minimum=True,
          help="angular tolerance of the STL meshing"),
    Field("gear_solid_tolerance", "length", required=False, default=None, minimum=0.0, exclusive_minimum=True,
          help="flank splines of the gear solids within this of the exact surface (default: the gear builder's, "
               "scaled down with modules below 1 mm)"),
    Field("render_view", "list", required=False, default=None,
          help="[azimuth, elevation] of the rendered view, degrees (default [-60, 30])"),
    Field("render_size", "list", required=False, default=None,
          help="[width, height] of the rendered figure, inches at its dpi (default [9, 6.5])"),
]

#: largest figure side of the rendered view (inches at the render's dpi: a few thousand pixels)
MAX_RENDER_SIZE = 50.0


def _two_numbers(value: Any) -> bool:
    return (isinstance(value, list) and len(value) == 2
            and all(isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in value))


def export_settings(design) -> dict[str, Any]:
    """``[export]`` read and checked (lengths mm, angles rad; view in deg as written)."""
    v = read_table(design.section("export"), EXPORT_FIELDS, "export")
    view = v["render_view"]
    if view is not None and not _two_numbers(view):
        raise DesignError("export.render_view", f"{view!r} is not two numbers", "[azimuth_deg, elevation_deg]")
    size = v["render_size"]
    if size is not None and not (_two_numbers(size) and all(0 < x <= MAX_RENDER_SIZE for x in size)):
        raise DesignError("export.render_size", f"{size!r} is not two sizes",
                          f"[width, height], each in (0, {MAX_RENDER_SIZE:g}]")
    return v


__all__ = ["EXPORT_FIELDS", "MAX_RENDER_SIZE", "export_settings"]
