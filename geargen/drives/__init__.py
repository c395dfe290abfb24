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
from geargen.drives.axial_preload.hardware import axial_hardware
from geargen.drives.beam_pinion.hardware import beam_pinion_hardware
from geargen.drives.dual_pinion.hardware import carriage_hardware
from geargen.drives.rack_dual_pinion.hardware import rack_drive_hardware
from geargen.drives.rules import RuleBroken, find_fixes, offered
from geargen.drives.split_pinion.hardware import split_pinion_hardware
from geargen.errors import DesignError
from geargen.model.layout import Layout, place

#: the hardware of each kind (geargen.design.parts.HARDWARE) -> its layout function
HARDWARE: dict[str, Callable[..., Any]] = {
    "axial_preload": axial_hardware,
    "beam_pinion": beam_pinion_hardware,
    "carriage": carriage_hardware,
    "rack_drive": rack_drive_hardware,
    "split_pinion": split_pinion_hardware,
}


def resolve(design: Design, position: str | None = None) -> Layout:
    """The resolved drive: the gears placed and the hardware laid out (see the module docstring).
    ``position`` overrides ``[layout] position``. A hardware rule the drive breaks is refused
    naming its key and the values found to fix it (:mod:`geargen.drives.rules`)."""
    try:
        return with_hardware(place(design, position))
    except RuleBroken as exc:
        fixes = find_fixes(lambda d: with_hardware(place(d, position)), design, exc)
        exc.fixes = fixes
        allowed = offered(fixes, exc, design.length_unit)
        error = RuleBroken(next(iter(fixes), exc.field), exc.problem, allowed or "no value of the keys that move it "
                           "was found to fix it within a factor of 10: change the drive's layout", exc.rule,
                           exc.margin, exc.candidates)
        error.fixes = fixes
        raise error from None


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
    except RuleBroken:
        raise
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


def defaulted(layout: Layout) -> tuple:
    """The values the design file does not give, as the resolved drive uses them: the design's
    defaults (:mod:`geargen.design.hardware_defaults`), those the hardware sized from the placed
    drive replacing theirs (:attr:`geargen.model.components.Hardware.defaults`)."""
    from geargen.design.hardware_defaults import Defaulted
    design = layout.design
    sized = {key: (value / design.mm_per_unit, why) for key, value, why in
             (layout.hardware.defaults if layout.hardware is not None else ())}
    return tuple(Defaulted(d.key, round(sized[d.key][0], 6), sized[d.key][1]) if d.key in sized else d
                 for d in design.defaulted)


def parts_table(layout: Layout) -> str:
    """The resolved drive's ``[parts]`` as TOML a designer can paste into the file: every key the
    drive's hardware reads, the file's value or the default used, lengths in the design's unit."""
    from geargen.design.parts import HARDWARE_FIELDS
    design = layout.design
    if not design.section("parts"):
        return ""
    settings = parts_settings(design)
    sized = {key.split(".", 1)[1]: value for key, value, _ in
             (layout.hardware.defaults if layout.hardware is not None else ())}
    unit = design.length_unit
    lines = [f"[parts]  # resolved ({settings['hardware']} hardware): the file's values and the defaults used"]
    for f in HARDWARE_FIELDS[settings["hardware"]]:
        value = settings.get(f.name)
        if value is None:
            continue
        if f.kind == "length":
            key = f"{f.name}_{unit}"
            value = sized.get(key, value) / design.mm_per_unit
            lines.append(f"{key} = {float(f'{value:.6g}')!r}")
        elif isinstance(value, str):
            lines.append(f'{f.name} = "{value}"')
        else:
            lines.append(f"{f.name} = {value!r}")
    return "\n".join(lines)


__all__ = ["HARDWARE", "resolve", "with_hardware", "defaulted", "parts_table"]
