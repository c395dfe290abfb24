"""The ``geargen`` command. Each subcommand lives in ``geargen.commands.<name>`` and is imported
only when run, so ``geargen synth`` never pays for the CAD kernel.

Exit status, for every subcommand (:data:`EXIT_STATUS`; also in ``geargen --help`` and the README):
0 ok, 1 a check failed, 2 bad input, 3 an environment problem or an interruption, 4 a bug. No
traceback reaches the user for 1-3; for 4 one is printed only with ``GEARGEN_DEBUG=1``.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import os
import signal
import sys
import threading
from pathlib import Path

# Set before numpy loads OpenBLAS. The numerics here are many tiny matrix operations (L-BFGS-B on
# ~20 variables in the tolerance search): OpenBLAS's worker threads add only their wake-ups there
# (the search ran 70x slower on a busy 2-core machine), and a build already checks its meshes in a
# second process. The builds of the shipped designs are identical either way (bench/diff_builds.py).
# A user's own setting is kept.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from geargen import __version__  # noqa: E402 - after the setting above
from geargen.errors import EnvironmentProblem, GeargenError, Interrupted, OutputRefused

#: subcommand -> one-line help; the module geargen.commands.<name> provides add_arguments(p) and run(args)
COMMANDS = {
    "gear": "build one gear (STEP, STL, derived quantities JSON)",
    "synth": "centre synthesis and error budget of a dual-pinion drive",
    "stiffness": "stiffness, preload and compliance summary with plots",
    "check": "geometric mesh checks of every mesh of an assembly",
    "build": "build a whole assembly into exports/<design file name>/",
    "fit": "fit a bench measurement, diagnose and report what the model missed",
    "pair": "gear-pair calculator: centre distance, pressure angle, contact ratio, backlash, shifts",
    "new": "write a commented starter design file that builds (dual_pinion, split_pinion)",
    "train": "inertia, stiffness and lost motion per stage, the servo view, strategy and alternatives",
    "sweep": "a grid or random designs through synthesis, checks, stiffness and Monte Carlo on Dask (Parquet)",
}

EXIT_OK = 0
EXIT_CHECK_FAILED = 1
EXIT_BAD_INPUT = 2
EXIT_ENVIRONMENT = 3
EXIT_BUG = 4

EXIT_STATUS = {
    EXIT_OK: "ok",
    EXIT_CHECK_FAILED: "a check failed (a mesh, an overlap, a ratio: the build writes nothing unless --force)",
    EXIT_BAD_INPUT: "bad input: the design file's content, a bad or conflicting option",
    EXIT_ENVIRONMENT: "environment: an output that cannot be written or that geargen will not replace, a missing "
                      "input file, a folder where a file is expected; or interrupted (Ctrl-C, SIGTERM)",
    EXIT_BUG: "internal error, a bug in geargen (GEARGEN_DEBUG=1 prints the traceback)",
}

DEBUG_VARIABLE = "GEARGEN_DEBUG"


def _epilog() -> str:
    lines = ["exit status:"] + [f"  {code}  {text}" for code, text in EXIT_STATUS.items()]
    lines += ["", "'-' as the file of --json writes to standard output. build, gear, stiffness and sweep write only into a",
              "new or empty folder or over their own earlier output, never over other files (README: Output folders)."]
    return "\n".join(lines)


def _command_module(name: str):
    return importlib.import_module(f"geargen.commands.{name}")


def _debug() -> bool:
    return os.environ.get(DEBUG_VARIABLE, "") not in ("", "0")


@contextlib.contextmanager
def _sigterm_as_interrupt():
    """SIGTERM raises :class:`Interrupted` (a KeyboardInterrupt) for the time of the command, so it
    cleans up exactly as Ctrl-C does; the previous handler is restored afterwards."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum, frame):
        raise Interrupted(signal.Signals(signum).name)

    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _check_input_file(path, what: str) -> None:
    p = Path(path).expanduser()
    if not p.exists():
        raise EnvironmentProblem(str(path), f"no such {what}")
    if p.is_dir():
        raise EnvironmentProblem(str(path), f"is a folder, not a {what}", "give the .toml file")
    if not os.access(p, os.R_OK):
        raise EnvironmentProblem(str(path), f"cannot read the {what}: permission denied")


def _check_before_work(args) -> None:
    """What can be refused before any work: an input design file that is missing or a folder,
    a ``--json`` file that cannot be written, an ``--out`` that is a file. (The output folder's
    policy is applied by the command itself, still before it builds anything.)"""
    from geargen.outputs import check_file_target
    design = getattr(args, "design", None)
    if isinstance(design, (str, Path)):
        _check_input_file(design, "design file")
    json_target = getattr(args, "json", None)
    if isinstance(json_target, (str, Path)):
        check_file_target(json_target, "--json")
    out = getattr(args, "out", None)
    if isinstance(out, (str, Path)) and os.path.lexists(out) and not Path(out).is_dir():
        raise OutputRefused(f"--out {out}", "is a file, not a folder", "give a folder that does not exist yet")


def _os_problem(exc: OSError) -> str:
    """``"no space left on device: PATH"``: the cause (geargen.outputs.os_cause), then the file."""
    from geargen.outputs import os_cause
    where = f": {exc.filename}" if exc.filename else ""
    return f"{os_cause(exc)}{where}"


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    name = argv[0] if argv and argv[0] in COMMANDS else None
    err = sys.stderr
    with _sigterm_as_interrupt():
        try:
            parser = argparse.ArgumentParser(prog="geargen",
                                             description="Anti-backlash gear assemblies, from design file to STEP.",
                                             epilog=_epilog(), formatter_class=argparse.RawDescriptionHelpFormatter)
            parser.add_argument("--version", action="version", version=f"geargen {__version__}")
            sub = parser.add_subparsers(dest="command", metavar="COMMAND")
            for command, help_text in COMMANDS.items():
                p = sub.add_parser(command, help=help_text, epilog=_epilog(),
                                   formatter_class=argparse.RawDescriptionHelpFormatter)
                if command == name:  # only the command being run is imported
                    _command_module(command).add_arguments(p)
            args = parser.parse_args(argv)  # bad flags: argparse exits with status 2
            if args.command is None:
                parser.print_help()
                return EXIT_BAD_INPUT
            _check_before_work(args)
            return int(_command_module(args.command).run(args) or 0)
        except KeyboardInterrupt as exc:
            how = exc.signal_name if isinstance(exc, Interrupted) else "Ctrl-C"
            print(f"geargen{' ' + name if name else ''}: interrupted ({how})", file=err)
            return EXIT_ENVIRONMENT
        except EnvironmentProblem as exc:
            _report(name, f"error: {exc}", exc)
            return EXIT_ENVIRONMENT
        except GeargenError as exc:
            _report(name, f"error: {exc}", exc)
            return EXIT_BAD_INPUT
        except OSError as exc:  # the file system said no where no check foresaw it
            _report(name, f"error: {_os_problem(exc)}", exc)
            return EXIT_ENVIRONMENT
        except Exception as exc:  # noqa: BLE001 - the last line between a bug and a raw traceback
            hint = "" if _debug() else f" (set {DEBUG_VARIABLE}=1 to see the traceback)"
            _report(name, f"internal error: {type(exc).__name__}: {exc}\nthis is a bug in geargen; please report it"
                    f"{hint}", exc)
            return EXIT_BUG


def _report(name: str | None, text: str, exc: BaseException) -> None:
    if _debug():
        import traceback
        traceback.print_exception(exc, file=sys.stderr)
    print(f"geargen{' ' + name if name else ''}: {text}", file=sys.stderr)


def command() -> None:
    """The ``geargen`` console command (and ``python -m geargen.cli``): :func:`main`, then exit.

    Every object the command made is frozen out of the garbage collector's sight before the
    interpreter ends: its final collection would otherwise walk them all (0.5-0.7 s of processor
    time after a build, more than the report step) only to free memory the exit frees anyway. The
    exit itself is the ordinary one (buffers flushed, exit handlers run); an in-process caller of
    :func:`main` (the tests, the Python API) keeps its collector as it was."""
    code = main()
    import gc
    gc.freeze()
    sys.exit(code)


if __name__ == "__main__":
    command()
