"""The resolved drive: where every command starts.

:func:`resolve`: the design's gears placed by its drive kind (:func:`place`), then the kind's
hardware laid out as components and joints (:mod:`geargen.model.components`), so the resolved
drive (:class:`geargen.model.Layout`) holds every length of every part and carries its kind
(``Layout.drive``, :class:`geargen.drives.kind.DriveKind`). ``geargen check`` evaluates the
hardware's rules on it, and ``geargen build`` turns the same components into solids.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from geargen.design.assembly import Design
from geargen.design.layout import POSITIONS, layout_settings
from geargen.design.parts import hardware_fields
from geargen.drives.registry import DRIVES
from geargen.drives.rules import RuleBroken, find_fixes, offered
from geargen.errors import DesignError
from geargen.model.analysis import stiffness
from geargen.model.bodies import SizeError
from geargen.model.layout import Layout, is_drive


def place(design: Design, position: str | None = None) -> Layout:
    """The gears of the drive placed by its kind (:class:`Layout` without its hardware): final
    teeth, centres, heights and rotations of every gear, and the meshes to check. ``position``
    overrides ``[layout] position``."""
    settings = layout_settings(design)
    if position is not None:
        if position not in POSITIONS:
            raise DesignError("--position", f"{position!r} is not a valid choice", ", ".join(map(repr, POSITIONS)))
        if position == "disengaged" and not design.section("engagement"):
            raise DesignError("--position", "'disengaged' needs an [engagement] section", "'engaged'")
        settings["position"] = position
    kind = DRIVES[settings["drive"]]
    # the kind goes with the settings: a placement that reads its own drive on the way (the sliding
    # pinions' engagement from the placed shafts' stiffness) has it
    return replace(kind.place(design, {**settings, "drive_kind": kind}), drive=kind)


def resolve(design: Design, position: str | None = None) -> Layout:
    """The resolved drive: the gears placed and the hardware laid out (see the module docstring).
    ``position`` overrides ``[layout] position``. A hardware rule the drive breaks is refused
    naming its key and the values found to fix it (:mod:`geargen.drives.rules`)."""
    from geargen.model.gear_data import check_gear_tables
    check_gear_tables(design)
    try:
        return with_hardware(place(design, position), design)
    except RuleBroken as exc:
        fixes = find_fixes(lambda d: with_hardware(place(d, position), d), design, exc)
        exc.fixes = fixes
        allowed = offered(fixes, exc, design.length_unit)
        error = RuleBroken(next(iter(fixes), exc.field), exc.problem, allowed or "no value of the keys that move it "
                           "was found to fix it within a factor of 10: change the drive's layout", exc.rule,
                           exc.margin, exc.candidates)
        error.fixes = fixes
        raise error from None


def with_hardware(layout: Layout, design: Design) -> Layout:
    """``layout`` (placed from ``design``) with its hardware laid out, when the design gives (or
    defaults) a ``[parts]`` table, read once into the resolved drive (``layout.resolved.parts``)."""
    if not layout.resolved.has("parts"):
        return layout
    settings = layout.resolved.parts
    lay_out = layout.drive.hardware
    summary: dict[str, Any] = {}

    def summarised():
        if "summary" not in summary:
            summary["summary"] = stiffness(design, layout)[0]
        return summary["summary"]

    try:
        hardware = lay_out(layout, settings, summarised)
    except RuleBroken:
        raise
    except DesignError as exc:
        defaulted = {d.key.split(".")[0] for d in layout.identity.defaulted}
        section = exc.field.split(".")[0]
        if section not in defaulted:
            raise
        raise DesignError(exc.field, f"{exc.problem} (the default hardware: the file gives no [{section}] table, "
                          "geargen sized it; see geargen check)",
                          f"{exc.allowed}; or a [{section}] table of your own") from None
    except ValueError as exc:
        problem = exc.in_unit(layout.identity.length_unit) if isinstance(exc, SizeError) else str(exc)
        raise DesignError("parts", f"the hardware cannot be made: {problem}",
                          "other [parts] sizes (the part named is what does not fit)") from None
    return replace(layout, hardware=hardware)


def defaulted(layout: Layout) -> tuple:
    """The values the design file does not give, as the resolved drive uses them: the design's
    defaults (its kind's ``defaults.py``), those the hardware sized from the placed
    drive replacing theirs (:attr:`geargen.model.components.Hardware.defaults`)."""
    from geargen.design.catalogue import Defaulted
    identity = layout.identity
    sized = {key: (value / identity.mm_per_unit, why) for key, value, why in
             (layout.hardware.defaults if layout.hardware is not None else ())}
    return tuple(Defaulted(d.key, round(sized[d.key][0], 6), sized[d.key][1]) if d.key in sized else d
                 for d in identity.defaulted)


def parts_table(layout: Layout) -> str:
    """The resolved drive's ``[parts]`` as TOML a designer can paste into the file: every key the
    drive's hardware reads, the file's value or the default used, lengths in the design's unit."""
    if not layout.resolved.has("parts"):
        return ""
    settings = layout.resolved.parts
    sized = {key.split(".", 1)[1]: value for key, value, _ in
             (layout.hardware.defaults if layout.hardware is not None else ())}
    unit, mm_per_unit = layout.identity.length_unit, layout.identity.mm_per_unit
    lines = [f"[parts]  # resolved ({settings['hardware']} hardware): the file's values and the defaults used"]
    for f in hardware_fields(settings["hardware"]):
        value = settings.get(f.name)
        if value is None:
            continue
        if f.kind == "length":
            key = f"{f.name}_{unit}"
            value = sized.get(key, value) / mm_per_unit
            lines.append(f"{key} = {float(f'{value:.6g}')!r}")
        elif isinstance(value, str):
            lines.append(f'{f.name} = "{value}"')
        else:
            lines.append(f"{f.name} = {value!r}")
    return "\n".join(lines)


def drive_from_design(design: Design, location: str = "output"):
    """The two-path drive model (:class:`geargen.core.drive.TwoPathDrive`: ``k1``, ``k2``, ``k3``
    and the loop preload) of ``design`` as every command computes it: from the resolved drive
    when the design is one, so the placed shafts size its components.

    Referred to the output by default: torques in N·mm, rotations in rad, stiffnesses in
    N·mm/rad (divide by 1e3 for the N·m of the measurement contract). Components with scope
    "common" are in series with the drive and not part of this model (``StiffnessSummary.common``).
    """
    summary, _ = stiffness(design, place(design) if is_drive(design) else None)
    if summary is None:
        raise DesignError("stiffness", "missing: the drive model needs [stiffness] and [preload] sections",
                          "see assemblies/robot_joint.toml")
    return summary.drive if location == "output" else summary.drive_at(location)


__all__ = ["place", "resolve", "with_hardware", "defaulted", "parts_table", "drive_from_design"]
