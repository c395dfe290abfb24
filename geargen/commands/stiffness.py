"""``geargen stiffness DESIGN.toml [--out DIR] [--json FILE]``: stiffness, preload and preload variation.

Prints each path (its components and their share of the compliance), the drive, the loop, the
preload against the paper's recommendation and the preload band caused by loop errors, and
writes the preload diagram, the torque-deflection curve and the preload band as PNG.

Loop errors: when :mod:`geargen.core.synthesis` is importable and gives an error budget for the
design (carriage travels ``dx1_sum``, ``dx1_rss``, ``dx1_mean``), those are used; otherwise the
``[preload]`` section's loop error. The printout says which.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from geargen.core.stiffness import stiffness_summary
from geargen.design.assembly import load_design

BUDGET_KEYS = {"sum": "dx1_sum", "rss": "dx1_rss", "mean": "dx1_mean"}


def add_arguments(p) -> None:
    p.add_argument("design", help="design file (TOML) with [stiffness] and [preload] sections")
    p.add_argument("--out", metavar="DIR", default=None,
                   help="folder for the PNG plots (default: exports/<name>/stiffness)")
    p.add_argument("--json", metavar="FILE", default=None, help="write the summary as JSON ('-' for standard output)")
    p.add_argument("--no-plots", action="store_true", help="skip the plots")


def synthesis_travels(design) -> tuple[dict[str, float] | None, str]:
    """The synthesis error budget as carriage travels (mm), and a note saying where the loop error came from."""
    from geargen.core.synthesis import synthesize_centres
    from geargen.core.tolerance import appendix_error_budget
    from geargen.design.synthesis import error_budget_inputs, synthesis_inputs

    if not design.section("synthesis") or not design.section("errors"):
        return None, "loop error from the design's [preload] (no [synthesis]/[errors] sections)"
    centres = synthesize_centres(synthesis_inputs(design)).check()
    budget = appendix_error_budget(centres, error_budget_inputs(design))
    travels = {label: float(getattr(budget, key)) for label, key in BUDGET_KEYS.items()}
    return travels, "loop error from the synthesis error budget (Appendix rules)"


def run(args) -> int:
    design = load_design(args.design)
    travels, note = synthesis_travels(design)
    summary = stiffness_summary(design, travels)
    if not summary.variations and travels is None:
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
