"""The errors geargen raises for bad input. Each names the offending field and what is allowed."""

from __future__ import annotations

#: the most characters of a key path, and of a problem, a message repeats: a hostile design file's
#: key or value (megabytes of it) is cut in the middle, not printed whole; geargen's own longest
#: problems (an engagement's lead, explained) are a few hundred characters
FIELD_MAX = 300
PROBLEM_MAX = 2000


def clipped(text: str, most: int = FIELD_MAX) -> str:
    """``text``, or its start and end around "..." when it is longer than ``most`` characters."""
    text = str(text)
    if len(text) <= most:
        return text
    return f"{text[:most - 40]}...{text[-30:]} ({len(text):,} characters)"


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
        text = f"{clipped(field)}: {clipped(problem, PROBLEM_MAX)}"
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


class KernelFailure(RuntimeError):
    """The CAD kernel made an unusable shape (not one valid closed solid) from input that was
    checked and valid: a bug in geargen, not bad input (the CLI's exit status 4, with this
    message), so not a GeargenError."""


class EnvironmentProblem(GeargenError):
    """The machine, not the input, stops the command: an output that cannot be written, a missing
    input file, a folder where a file is expected. ``subject`` is the flag or path concerned
    (``--out``, ``design file``); ``hint`` says what would work. The CLI exits with status 3."""

    def __init__(self, subject: str, problem: str, hint: str | None = None):
        self.subject = subject
        self.problem = problem
        self.hint = hint
        text = f"{subject}: {problem}"
        if hint:
            text += f" ({hint})"
        super().__init__(text)


class OutputRefused(EnvironmentProblem):
    """An output folder geargen will not write into or replace: it holds files geargen did not
    write, another command's output, or an earlier output of another source (without --overwrite)."""


class Interrupted(KeyboardInterrupt):
    """SIGTERM during a command: handled like Ctrl-C (temporary files removed, exit status 3).

    A KeyboardInterrupt, so every ``except Exception`` lets it through and every cleanup that
    already runs on Ctrl-C runs on it too."""

    def __init__(self, signal_name: str = "SIGTERM"):
        self.signal_name = signal_name
        super().__init__(signal_name)
