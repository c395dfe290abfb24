"""Analysis of the resolved drive: the one stiffness and preload summary every command reports
(``geargen stiffness`` prints it, ``geargen build`` puts it in its report)."""

from __future__ import annotations

from typing import Any

from geargen.design.assembly import Design
from geargen.model.layout import Layout


def loop_error_travels(layout: Layout | None) -> tuple[dict[str, float] | None, str]:
    """The synthesis error budget as carriage travels (mm: ``sum``, ``rss``, ``mean``) when the
    preload carriage of the drive absorbs them, and a note saying where the loop error comes from."""
    run = layout.synthesis if layout is not None else None
    design = layout.design if layout is not None else None
    if run is None or run.budget is None:
        return None, "loop error from the design's [preload] (no [synthesis] with [errors] budget)"
    if design.preload_method not in ("radial", "axial") or design.section("beam_pinion"):
        return None, ("loop error from the design's [preload]: the synthesis budget is a carriage travel, and this "
                      "drive's preload is not set by a sliding carriage")
    b = run.budget
    return {"sum": b.dx1_sum, "rss": b.dx1_rss, "mean": b.dx1_mean}, \
        "loop error from the synthesis error budget (Appendix rules)"


def stiffness(design: Design, layout: Layout | None) -> tuple[Any, str]:
    """``(StiffnessSummary or None, note)``: None when the design has no [stiffness]/[preload]."""
    if not design.section("stiffness") or not design.section("preload"):
        return None, "no [stiffness] and [preload] sections"
    from geargen.core.stiffness import stiffness_summary
    travels, note = loop_error_travels(layout)
    return stiffness_summary(design, travels), note


__all__ = ["loop_error_travels", "stiffness"]
