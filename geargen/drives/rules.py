"""Hardware rules that refuse a drive, and the values that would let it pass.

A drive kind's hardware raises :class:`RuleBroken` where a geometric rule fails (a part runs into
another, a cover has no room): it names the rule, how far it is broken (``margin``, mm, negative)
and the design-file lengths that move it (:class:`Candidate`: a ``[parts]`` key, or another section's
such as ``[flexures] width``, with the direction that helps). The
resolver (:func:`geargen.drives.with_hardware`) then looks for each candidate's value that makes
the rule hold, by laying the drive out again with that value (:func:`find_fixes`): the message
offers only values found to work, and the error carries them (``fixes``: design-file key -> value
in the design's unit) so that a test can apply each and see the refusal go.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Callable

from geargen.errors import DesignError


@dataclass(frozen=True)
class Candidate:
    """A length of the design's ``section`` (``[parts]`` unless said; its name without the unit
    suffix) that moves a rule, and which way helps: +1 a larger value, -1 a smaller one."""

    name: str
    direction: int
    what: str = ""
    section: str = "parts"

    def key(self, unit: str) -> str:
        """The design-file key, spelled in the design's length unit."""
        return f"{self.section}.{self.name}_{unit}"


class RuleBroken(DesignError):
    """A hardware rule the drive breaks. ``rule`` names it (to tell it from others), ``margin``
    says by how much (mm, negative), ``candidates`` the keys that move it, ``fixes`` the values
    found to make it hold (filled in by :func:`find_fixes`: design-file key -> value)."""

    def __init__(self, field: str, problem: str, allowed: str | None, rule: str, margin: float,
                 candidates: tuple[Candidate, ...] = ()):
        super().__init__(field, problem, allowed)
        self.rule = rule
        self.margin = margin
        self.candidates = tuple(candidates)
        self.fixes: dict[str, float] = {}


def _with_value(design, key: str, value: float):
    """``design`` with ``key`` (``section.name``, the file's spelling, unit suffix included) set to
    ``value``."""
    section, name = key.split(".", 1)
    sections = {k: dict(v) if k == section else v for k, v in design.sections.items()}
    table = sections.setdefault(section, {})
    stem = name.rsplit("_", 1)[0]
    for k in list(table):  # one spelling of the key only
        if k.rsplit("_", 1)[0] == stem and k != name:
            del table[k]
    table[name] = value
    return replace(design, sections=sections)


def _still_broken(resolve: Callable, design, rule: str) -> bool | None:
    """Whether ``design`` still breaks ``rule`` (None: it fails otherwise, on another rule or bad sizes)."""
    try:
        resolve(design)
    except RuleBroken as exc:
        return True if exc.rule == rule else None
    except (DesignError, ValueError):
        return None
    return False


def find_fixes(resolve: Callable, design, error: RuleBroken, iterations: int = 30) -> dict[str, float]:
    """For each candidate of ``error``: the value nearest the design's own (in the helping
    direction) at which ``resolve(design)`` no longer breaks the rule, rounded outward to 1e-3 of
    the design's unit and checked again. Returns design-file key -> value; candidates that no value
    within a factor of 10 fixes are left out."""
    unit = design.length_unit
    scale = design.mm_per_unit
    found: dict[str, float] = {}
    from geargen.design.parts import parts_settings
    settings = parts_settings(design)
    for cand in error.candidates:
        key = cand.key(unit)
        if cand.section == "parts":
            current = settings.get(cand.name)
            v0 = current / scale if isinstance(current, (int, float)) else None
        else:  # another section's length, as the file spells it in the design's unit
            v0 = (design.sections.get(cand.section) or {}).get(f"{cand.name}_{unit}")
        if not isinstance(v0, (int, float)) or isinstance(v0, bool) or not v0 > 0:
            continue

        def broken(v):
            return _still_broken(resolve, _with_value(design, key, v), error.rule)

        # walk out in the helping direction until the rule holds, then bisect back towards v0
        bad, good = v0, None
        for factor in (1.02, 1.05, 1.1, 1.25, 1.5, 2.0, 3.0, 5.0, 10.0):
            v = v0 * factor if cand.direction > 0 else v0 / factor
            state = broken(v)
            if state is False:
                good = v
                break
            if state is True:
                bad = v
        if good is None:
            continue
        for _ in range(iterations):
            mid = (bad + good) / 2
            if broken(mid) is False:
                good = mid
            else:
                bad = mid
        step = 1e-3
        rounded = (math.ceil(good / step - 1e-9) if cand.direction > 0 else math.floor(good / step + 1e-9)) * step
        rounded = round(rounded, 6)
        if broken(rounded) is False:
            found[key] = rounded
    return found


def offered(fixes: dict[str, float], error: RuleBroken, unit: str) -> str:
    """The fixes as the refusal's "allowed" text."""
    what = {c.key(unit): c.what for c in error.candidates}
    return " or ".join(f"{key} = {value:g}" + (f" ({what[key]})" if what.get(key) else "")
                       for key, value in fixes.items())


__all__ = ["Candidate", "RuleBroken", "find_fixes", "offered"]
