"""``geargen train DESIGN.toml [--json FILE|-] [--out DIR] [--overwrite] [--no-plots]``: the drive
as its servo sees it.

Builds the assembly's solids (as ``geargen build`` does, without writing them), takes every
rotating part's mass and moment of inertia about its own axis from its solid (densities from
``[train]``), and prints per part its ratio to the motor and its inertia reflected there, per stage
its stiffness and lost motion at the output, the totals, the position loop against a direct drive
(with a motor and a loop in ``[train]``), the paper's strategy advice and the alternatives on the
same load. A ``[dual_motor]`` design gets the Fig. 1 analysis instead. Plots and a
``manifest.json`` go to ``exports/<design file name>-train/`` (or DIR), under the policy of
:mod:`geargen.outputs`, written atomically.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from geargen.design.assembly import load_design
from geargen.errors import DesignError


def add_arguments(p) -> None:
    from geargen.outputs import add_plot_arguments
    p.add_argument("design", help="design file (TOML): a dual or split pinion drive, or a [dual_motor] drive")
    add_plot_arguments(p, "train")
    p.add_argument("--json", metavar="FILE", default=None, help="write the analysis as JSON ('-' for standard output)")


def output_folder(args, design):
    """The :class:`geargen.outputs.OutputFolder` of the plots."""
    from geargen.outputs import plot_folder
    return plot_folder(args, design, "train", "geargen train")


def run(args) -> int:
    design = load_design(args.design)
    output = None if args.no_plots else output_folder(args, design)
    if output is not None:
        output.prepare()
    try:
        return _run(args, design, output)
    except BaseException:
        if output is not None:
            output.discard()
        raise


def analysis(design):
    """``(kind, analysis)``: the train of a drive (:func:`geargen.model.train.analyse`) or the
    dual-motor drive (:func:`geargen.model.train.dual_motor_analysis`), from the parts' geometry (no solid built)."""
    from geargen import pipeline
    if design.section("dual_motor"):
        from geargen.model.train import dual_motor_analysis
        return "dual_motor", dual_motor_analysis(design, pipeline.declared_gear_parts(design))
    from geargen.model import is_drive
    if not is_drive(design):
        raise DesignError("layout", "missing: geargen train needs a drive ([layout] or [synthesis]) or a [dual_motor]",
                          "see assemblies/robot_joint.toml or assemblies/dual_motor.toml")
    layout = pipeline.place(design)
    summary = pipeline.stiffness(layout)
    if summary is None:
        raise DesignError("stiffness", "missing: geargen train needs [stiffness] and [preload] sections",
                          "see assemblies/robot_joint.toml")
    from geargen.model.train import analyse
    return "drive", analyse(layout, summary, pipeline.rotating_parts(layout))


def _run(args, design, output) -> int:
    from geargen.report import train as report
    kind, result = analysis(design)
    data = report.train_dict(result) if kind == "drive" else report.dual_motor_dict(result)
    text_out = sys.stderr if args.json == "-" else sys.stdout
    print(report.format_train(data, design.text_units) if kind == "drive" else report.format_dual_motor(data), file=text_out)
    if output is not None:
        written = (report.write_train_plots(result, output.work) if kind == "drive"
                   else report.write_dual_motor_plots(result, output.work))
        target = output.commit_with_manifest(design, output.source)
        data["plots"] = {k: str(target / Path(v).name) for k, v in written.items()}
        print("\nPlots: " + ", ".join(data["plots"].values()), file=text_out)
    if args.json:
        from geargen.outputs import json_default, write_text
        write_text(args.json, json.dumps(data, indent=2, default=json_default) + "\n", "--json")
    return 0

