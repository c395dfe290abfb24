"""The ``geargen`` command. Each subcommand lives in ``geargen.commands.<name>`` and is imported
only when run, so ``geargen synth`` never pays for the CAD kernel."""

from __future__ import annotations

import argparse
import importlib
import sys

from geargen.errors import GeargenError

#: subcommand -> one-line help; the module geargen.commands.<name> provides add_arguments(p) and run(args)
COMMANDS = {
    "gear": "build one gear (STEP, STL, derived quantities JSON)",
    "synth": "centre synthesis and error budget of a dual-pinion drive",
    "stiffness": "stiffness, preload and compliance summary with plots",
    "check": "geometric mesh checks of every mesh of an assembly",
    "build": "build a whole assembly into exports/<name>/",
    "fit": "fit a bench measurement, diagnose and report what the model missed",
}


def _command_module(name: str):
    return importlib.import_module(f"geargen.commands.{name}")


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    parser = argparse.ArgumentParser(prog="geargen", description="Anti-backlash gear assemblies, from design file to STEP.")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    wanted = argv[0] if argv and argv[0] in COMMANDS else None
    for name, help_text in COMMANDS.items():
        p = sub.add_parser(name, help=help_text)
        if name == wanted:  # only the command being run is imported
            _command_module(name).add_arguments(p)
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 2
    try:
        return int(_command_module(args.command).run(args) or 0)
    except GeargenError as exc:
        print(f"geargen {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
