"""``geargen stiffness DESIGN.toml [--out DIR] [--overwrite] [--json FILE|-]``: stiffness, preload and preload variation.

Prints each path (its components and their share of the compliance), the drive, the loop, the
preload against the paper's recommendation and the preload band caused by loop errors, and
writes the preload diagram, the torque-deflection curve and the preload band as PNG, with a
``manifest.json``, into ``exports/<design file name>-stiffness/`` (or DIR): a folder of its own,
which ``geargen build`` (``exports/<design file name>/``) never touches. The folder follows the
policy of :mod:`geargen.outputs` (new, empty, or an earlier ``geargen stiffness`` output of the
same design file; ``--overwrite`` also for another design file's) and is written atomically.

The drive is the resolved one (:func:`geargen.model.resolve`) and the summary is
:func:`geargen.model.analysis.stiffness`, the one ``geargen build`` reports. Loop errors: the
synthesis error budget as carriage travels where a sliding carriage absorbs them, otherwise the
``[preload]`` section's loop error; the printout says which.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from geargen.design.assembly import load_design
from geargen.errors import DesignError
from geargen.model import is_drive
from geargen.drives import resolve
from geargen.model.analysis import stiffness


def add_arguments(p) -> None:
    from geargen.outputs import add_plot_arguments
    p.add_argument("design", help="design file (TOML) with [stiffness] and [preload] sections")
    add_plot_arguments(p, "stiffness")
    p.add_argument("--json", metavar="FILE", default=None, help="write the summary as JSON ('-' for standard output)")


def output_folder(args, design):
    """The :class:`geargen.outputs.OutputFolder` of the plots."""
    from geargen.outputs import plot_folder
    return plot_folder(args, design, "stiffness", "geargen stiffness")


def run(args) -> int:
    design = load_design(args.design)
    output = None if args.no_plots else output_folder(args, design)
    if output is not None:
        output.prepare()  # refused or unwritable: said before any work
    try:
        return _run(args, design, output)
    except BaseException:
        if output is not None:
            output.discard()
        raise


def _run(args, design, output) -> int:
    layout = resolve(design) if is_drive(design) else None
    summary, note = stiffness(design, layout)
    if summary is None:
        raise DesignError("stiffness", "missing: geargen stiffness needs [stiffness] and [preload] sections",
                          "see assemblies/robot_joint.toml")
    if not summary.variations and note.startswith("loop error from the design"):
        note = "no loop error: give loop_error_* in [preload] or a [synthesis] section"
    from geargen.report.stiffness import format_summary, write_stiffness_plots

    text_out = sys.stderr if args.json == "-" else sys.stdout
    print(format_summary(summary, note), file=text_out)
    data = summary.to_dict()
    data["loop_error_source"] = note
    if output is not None:
        written = write_stiffness_plots(summary, output.work)
        target = output.commit_with_manifest(design, output.source)
        plots = {k: target / Path(v).name for k, v in written.items()}
        data["plots"] = {k: str(v) for k, v in plots.items()}
        print("\nPlots: " + ", ".join(str(p) for p in plots.values()), file=text_out)
    if args.json:
        from geargen.outputs import json_default, write_text
        write_text(args.json, json.dumps(data, indent=2, default=json_default) + "\n", "--json")
    return 0

