"""``geargen new KIND FILE.toml [--units mm|in]``: write a commented starter design that builds.

KIND is a drive kind with starters (:data:`STARTERS`, from each kind's
:attr:`geargen.drives.kind.DriveKind.starters`: ``dual_pinion``, ``split_pinion``), metric or, with
``--units in``, inch; the design's ``name`` is the file's name. The file is never overwritten: an existing FILE is
refused with exit status 3, naming it. It is written atomically (a temporary file beside it,
linked into place only if FILE still does not exist), with the user's umask; missing folders
above it are created.
"""

from __future__ import annotations

import argparse
import os
import tempfile
from pathlib import Path

from geargen.design.starters import starter_text
from geargen.drives.registry import DRIVES
from geargen.errors import DesignError, EnvironmentProblem, OutputRefused
from geargen.outputs import file_mode


#: each drive kind's starters by length unit, by the kind's name
STARTERS = {d.name: d.starters for d in DRIVES.values() if d.starters}
UNITS = ("mm", "in")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("kind", choices=sorted(STARTERS), help="the drive to start from")
    p.add_argument("file", metavar="FILE.toml", help="the design file to write (never overwritten)")
    p.add_argument("--units", choices=UNITS, default="mm",
                   help="the starter's lengths: mm (metric, modules) or in (inch, diametral pitch; default mm)")


def write_new_file(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` only if ``path`` does not exist, atomically: the complete file
    appears at once (a hard link of a finished temporary file) or not at all."""
    shown = str(path)
    if os.path.lexists(path):
        raise OutputRefused(shown, "exists: geargen new never overwrites a file",
                            "give a new file name, or move the existing file away")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".tmp.toml", dir=path.parent)
    except OSError as exc:
        raise EnvironmentProblem(shown, f"cannot write in {path.parent}: {exc.strerror or exc}") from None
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.chmod(tmp, file_mode())
        try:
            os.link(tmp, path)  # fails if path appeared meanwhile: never replaces it
        except FileExistsError:
            raise OutputRefused(shown, "exists: geargen new never overwrites a file",
                                "give a new file name, or move the existing file away") from None
        except OSError:  # a file system without hard links: create exclusively, then write
            _create_exclusive(path, text)
    except OSError as exc:
        raise EnvironmentProblem(shown, f"cannot write: {exc.strerror or exc}") from None
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def _create_exclusive(path: Path, text: str) -> None:
    try:
        with open(path, "x", encoding="utf-8") as fh:
            fh.write(text)
    except FileExistsError:
        raise OutputRefused(str(path), "exists: geargen new never overwrites a file",
                            "give a new file name, or move the existing file away") from None
    except BaseException:
        if os.path.exists(path):
            os.unlink(path)  # ours: the exclusive create made it
        raise


def run(args: argparse.Namespace) -> int:
    path = Path(args.file).expanduser()
    if path.suffix != ".toml":
        raise DesignError("FILE", f"{args.file!r} is not a .toml file name", "NAME.toml")
    name = path.stem
    if not name or name.startswith(".") or "\\" in name:
        raise DesignError("FILE", f"{args.file!r} does not give the design a name", "NAME.toml, NAME not starting "
                          "with a dot")
    starter = STARTERS[args.kind][args.units]
    write_new_file(path, starter_text(starter, name))
    print(f"wrote {path}: a {args.kind} starter design ({starter.units}) named {name!r}")
    print(f"next: geargen check {path}   then   geargen build {path}")
    return 0


__all__ = ["STARTERS", "UNITS", "add_arguments", "run", "write_new_file"]
