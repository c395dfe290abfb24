"""The errors geargen raises for bad input. Each names the offending field and what is allowed."""

from __future__ import annotations


class GeargenError(Exception):
    """Base class of every error geargen raises on purpose."""


class DesignError(GeargenError, ValueError):
    """A design input is missing, unknown or out of range.

    ``field`` is the dotted path of the key as the user wrote it (``gears.input.teeth``);
    ``allowed`` says what would have been accepted.
    """

    def __init__(self, field: str, problem: str, allowed: str | None = None):
        self.field = field
        self.problem = problem
        self.allowed = allowed
        text = f"{field}: {problem}"
        if allowed:
            text += f" (allowed: {allowed})"
        super().__init__(text)


class GeometryError(GeargenError, ValueError):
    """Valid-looking parameters that cannot make the requested geometry (pointed teeth, no solution)."""

    def __init__(self, kind: str, message: str):
        self.kind = kind
        super().__init__(f"{kind}: {message}")


class BuildError(GeargenError, RuntimeError):
    """The CAD kernel produced something unusable (invalid solid, failed export)."""
