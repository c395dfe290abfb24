"""Drive kinds: how each kind of anti-backlash drive places its gears and lays out its hardware.

:func:`resolve` is where every command starts: the design's gears placed
(:func:`geargen.model.layout.place`), then the drive kind's hardware laid out as components and
joints (:mod:`geargen.model.components`), so the resolved drive (:class:`geargen.model.Layout`)
holds every length of every part. ``geargen check`` evaluates the hardware's rules on it, and
``geargen build`` turns the same components into solids.

The hardware a design gets is decided in one place, :func:`geargen.design.parts.hardware_of`;
:data:`HARDWARE` maps each to its layout function ``(layout, parts, stiffness) -> Hardware``
(``parts``: the validated ``[parts]`` settings; ``stiffness``: a callable giving the stiffness
summary, for hardware sized by it).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, Callable

from geargen.design.assembly import Design
from geargen.design.parts import parts_settings
from geargen.drives.beam_pinion.hardware import beam_pinion_hardware
from geargen.drives.dual_pinion.hardware import carriage_hardware
from geargen.drives.split_pinion.hardware import split_pinion_hardware
from geargen.errors import DesignError
from geargen.model.layout import Layout, place

#: the hardware of each kind (geargen.design.parts.HARDWARE) -> its layout function
HARDWARE: dict[str, Callable[..., Any]] = {
    "beam_pinion": beam_pinion_hardware,
    "carriage": carriage_hardware,
    "split_pinion": split_pinion_hardware,
}


def resolve(design: Design, position: str | None = None) -> Layout:
    """The resolved drive: the gears placed and the hardware laid out (see the module docstring).
    ``position`` overrides ``[layout] position``."""
    layout = place(design, position)
    return with_hardware(layout)


def with_hardware(layout: Layout) -> Layout:
    """``layout`` with its hardware laid out, when the design gives (or defaults) a ``[parts]`` table."""
    design = layout.design
    if not design.section("parts"):
        return layout
    settings = parts_settings(design)
    lay_out = HARDWARE.get(settings["hardware"])
    if lay_out is None:
        return layout
    summary: dict[str, Any] = {}

    def stiffness():
        if "summary" not in summary:
            from geargen.model.analysis import stiffness as analyse
            summary["summary"] = analyse(design, layout)[0]
        return summary["summary"]

    try:
        hardware = lay_out(layout, settings, stiffness)
    except DesignError as exc:
        defaulted = {d.key.split(".")[0] for d in design.defaulted}
        section = exc.field.split(".")[0]
        if section not in defaulted:
            raise
        raise DesignError(exc.field, f"{exc.problem} (the default hardware: the file gives no [{section}] table, "
                          "geargen sized it; see geargen check)",
                          f"{exc.allowed}; or a [{section}] table of your own") from None
    except ValueError as exc:
        raise DesignError("parts", f"the hardware cannot be made: {exc}",
                          "other [parts] sizes (the part named is what does not fit)") from None
    return replace(layout, hardware=hardware)


__all__ = ["HARDWARE", "resolve", "with_hardware"]
