"""``geargen stiffness DESIGN.toml [--out DIR] [--overwrite] [--json FILE|-]``: stiffness, preload and preload variation.

Prints each path (its components and their share of the compliance), the drive, the loop, the
preload against the paper's recommendation and the preload band caused by loop errors, and
writes the preload diagram, the torque-deflection curve and the preload band as PNG, with a
``manifest.json``, into ``exports/<design file name>-stiffness/`` (or DIR): a folder of its own,
which ``geargen build`` (``exports/<design file name>/``) never touches. The folder follows the
policy of :mod:`geargen.outputs` (new, empty, or an earlier ``geargen stiffness`` output of the
same design file; ``--overwrite`` also for another design file's) and is written atomically.

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
                   help="folder for the PNG plots (default: exports/<design file name>-stiffness); must not exist, "
                        "be empty, or hold an earlier stiffness output of the same design file, which is replaced")
    p.add_argument("--overwrite", action="store_true",
                   help="also replace an earlier stiffness output of another design file (never a folder holding "
                        "files geargen did not write)")
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


def default_out_dir(design_path) -> Path:
    """``exports/<design file name>-stiffness``: beside the build's ``exports/<design file name>``, never in it."""
    return Path("exports") / f"{Path(design_path).stem}-stiffness"


def output_folder(args, design):
    """The :class:`geargen.outputs.OutputFolder` of the plots."""
    from geargen.outputs import OutputFolder
    source = str(Path(design.path or args.design).resolve())
    target = Path(args.out) if args.out else default_out_dir(args.design)
    return OutputFolder(target, "geargen stiffness", source, f"the design file {source}",
                        overwrite=args.overwrite, flag="--out" if args.out else "output folder")


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
    travels, note = synthesis_travels(design)
    summary = stiffness_summary(design, travels)
    if not summary.variations and travels is None:
        note = "no loop error: give loop_error_* in [preload] or a [synthesis] section"
    from geargen.report.stiffness import format_summary, write_stiffness_plots

    text_out = sys.stderr if args.json == "-" else sys.stdout
    print(format_summary(summary, note), file=text_out)
    data = summary.to_dict()
    data["loop_error_source"] = note
    if output is not None:
        from geargen import __version__
        from geargen.outputs import manifest_files, write_text
        written = write_stiffness_plots(summary, output.work)
        manifest = {"generator": "geargen stiffness", "source": output.source, "version": __version__,
                    "design": {"name": design.name, "file": output.source, "sha256": design.sha256},
                    "files": manifest_files(output.work)}
        write_text(output.work / "manifest.json", json.dumps(manifest, indent=2) + "\n", "--out")
        target = output.commit()
        plots = {k: target / Path(v).name for k, v in written.items()}
        data["plots"] = {k: str(v) for k, v in plots.items()}
        print("\nPlots: " + ", ".join(str(p) for p in plots.values()), file=text_out)
    if args.json:
        from geargen.outputs import write_text
        write_text(args.json, json.dumps(data, indent=2, default=_json_default) + "\n", "--json")
    return 0


def _json_default(value):
    if hasattr(value, "item"):
        return value.item()
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")
