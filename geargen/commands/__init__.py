"""One module per ``geargen`` subcommand: ``add_arguments(parser)`` and ``run(args) -> exit code``."""
