"""``geargen stiffness DESIGN.toml [--out DIR] [--json FILE]``: stiffness, preload and preload variation.

Prints each path (its components and their share of the compliance), the drive, the loop, the
preload against the paper's recommendation and the preload band caused by loop errors, and
writes the preload diagram, the torque-deflection curve and the preload band as PNG.

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
from geargen.model import is_drive, resolve
from geargen.model.analysis import stiffness

def add_arguments(p) -> None:
    p.add_argument("design", help="design file (TOML) with [stiffness] and [preload] sections")
    p.add_argument("--out", metavar="DIR", default=None,
                   help="folder for the PNG plots (default: exports/<name>/stiffness)")
    p.add_argument("--json", metavar="FILE", default=None, help="write the summary as JSON ('-' for standard output)")
    p.add_argument("--no-plots", action="store_true", help="skip the plots")


def run(args) -> int:
    design = load_design(args.design)
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
    if not args.no_plots:
        out = Path(args.out) if args.out else Path("exports") / design.name / "stiffness"
        plots = write_stiffness_plots(summary, out)
        data["plots"] = {k: str(v) for k, v in plots.items()}
        print("\nPlots: " + ", ".join(str(p) for p in plots.values()), file=text_out)
    if args.json:
        text = json.dumps(data, indent=2, default=_json_default)
        if args.json == "-":
            print(text)
        else:
            Path(args.json).write_text(text + "\n")
    return 0


def _json_default(value):
    if hasattr(value, "item"):
        return value.item()
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")
