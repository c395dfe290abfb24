"""``geargen fit NAME.csv --json REPORT.json [--report DIR]``: fit a bench measurement, find what
the declared model lacks, add it, and report the error before and after
(contracts/measurements.md). ``--json -`` writes the JSON report to standard output (and the
human summary to standard error), like the other commands."""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

STDOUT = "-"


def add_arguments(p) -> None:
    p.add_argument("csv", help="the measurement NAME.csv; its sidecar NAME.toml must sit beside it")
    p.add_argument("--json", dest="json_path", default=None,
                   help="where to write the JSON report, '-' for standard output "
                        "(default: NAME.fit.json beside the CSV)")
    p.add_argument("--report", dest="report_dir", default=None,
                   help="folder for the human report, report.md and plots "
                        "(default: NAME_fit/ beside the JSON, or beside the CSV with --json -)")
    p.add_argument("--no-plots", action="store_true", help="write the Markdown report without plots")
    p.add_argument("--update-design", dest="update_design", default=None, metavar="OUT.toml",
                   help="write a copy of the sidecar's assembly with the measured errors in place of the budgeted "
                        "ones (and the effects found as a comment), and report the preload variation before and after")


def fit_files(csv_path, json_path=None, report_dir=None, plots: bool = True, stdout=None,
              update_design=None) -> dict:
    """Read, fit, diagnose and report one measurement. Returns the JSON summary and timings.

    ``json_path`` ``"-"`` writes the JSON to ``stdout`` (default ``sys.stdout``) instead of a file.
    Nothing is written when reading or fitting fails.
    """
    from geargen.fit.measurement import read_measurement
    from geargen.fit.reporting import report_input
    from geargen.fit.selection import diagnose
    from geargen.report.fit import write_fit_report, write_json

    csv_path = Path(csv_path)
    to_stdout = str(json_path) == STDOUT if json_path is not None else False
    if to_stdout:
        json_file = None
        report_dir = Path(report_dir) if report_dir else csv_path.with_name(f"{csv_path.stem}_fit")
    else:
        json_file = Path(json_path) if json_path else csv_path.with_name(f"{csv_path.stem}.fit.json")
        report_dir = Path(report_dir) if report_dir else json_file.with_name(f"{csv_path.stem}_fit")
    if update_design is not None:
        from geargen.outputs import check_file_target
        check_file_target(update_design, "--update-design")
    t0, c0 = time.perf_counter(), time.process_time()
    meas = read_measurement(csv_path)
    t1, c1 = time.perf_counter(), time.process_time()
    dg = diagnose(meas)
    t2, c2 = time.perf_counter(), time.process_time()
    summary = dg.to_json()
    update_text = None
    if update_design is not None:
        summary["design_update"], update_text = _design_update(meas, summary, csv_path, Path(update_design))
    if json_file is not None:
        write_json(json_file, summary)
    report = write_fit_report(report_dir, report_input(dg), plots=plots)
    if update_text is not None:
        from geargen.outputs import write_text
        write_text(update_design, update_text, "--update-design")
    if to_stdout:  # the same text write_json puts in a file
        out = stdout or sys.stdout
        out.write(json.dumps(summary, indent=2, allow_nan=False) + "\n")
        out.flush()
    t3, c3 = time.perf_counter(), time.process_time()
    return {"summary": summary, "json": json_file if json_file is not None else STDOUT, "report": report,
            "diagnosis": dg,
            "seconds": {"read": t1 - t0, "fit": t2 - t1, "report": t3 - t2, "total": t3 - t0},
            "cpu_seconds": {"read": c1 - c0, "fit": c2 - c1, "report": c3 - c2, "total": c3 - c0}}


def _design_update(meas, summary: dict, csv_path: Path, out: Path) -> tuple[dict, str]:
    """The updated design's text and its JSON entry: what changed and the preload band before and after."""
    from geargen.design.assembly import load_design
    from geargen.errors import DesignError
    from geargen.fit.design_update import design_from_text, preload_band, updated_design
    if meas.assembly is None:
        raise DesignError("--update-design", "the sidecar names no assembly to update",
                          'assembly = "design.toml" in the sidecar')
    text, changes = updated_design(meas.assembly, summary, csv_path.name)
    before = preload_band(load_design(meas.assembly))
    after = preload_band(design_from_text(text, out))
    return {"assembly": meas.assembly.name, "written": str(out), "changes": changes,
            "preload_variation": {"before": before, "after": after}}, text


def _number(v, unit: str) -> str:
    return "not measured" if v is None else f"{v:.4g} {unit}"


def _datasheet_summary(sheet: dict | None) -> list[str]:
    """One line per datasheet test (lost motion, hysteresis loss, stiffness), or the accuracy."""
    if not sheet:
        return []
    out = []
    for t in sheet.get("tests", []):
        k = t["stiffness"]
        out.append(f"datasheet test {t['test']} (+-{t['torque_amplitude_Nm']:.4g} N·m): lost motion "
                   f"{_number(t['lost_motion_urad'], 'urad')} at +-{t['lost_motion_at_Nm']:.4g} N·m, torsion "
                   f"{_number(t.get('torsion_urad'), 'urad')} at +-{t['torsion_at_Nm']:.4g} N·m, hysteresis loss "
                   f"{_number(t['hysteresis_loss_urad'], 'urad')}, K1/K2/K3 "
                   + " / ".join("-" if k[key] is None else f"{k[key]:.4g}" for key in ("K1_Nm_per_rad", "K2_Nm_per_rad",
                                                                                    "K3_Nm_per_rad"))
                   + f" N·m/rad (T1 {k['T1_Nm']:.4g}, T2 {k['T2_Nm']:.4g} N·m)")
    if not sheet.get("tests") and "transmission_accuracy_urad" in sheet:
        out.append(f"datasheet: transmission accuracy {_number(sheet['transmission_accuracy_urad'], 'urad')}")
    return out


def run(args) -> int:
    to_stdout = args.json_path == STDOUT
    text = sys.stderr if to_stdout else sys.stdout  # standard output carries the JSON alone
    out = fit_files(args.csv, args.json_path, args.report_dir, plots=not args.no_plots,
                    update_design=args.update_design)
    s = out["summary"]
    u = s["units"]
    st = s["stages"]
    nominal = f"{st['nominal']['rms']:.4g}" if st["nominal"] else "null"
    channels = ", ".join(f"{k} {v:.4g}" for k, v in s["noise_channels"].items())
    print(f"{s['kind']}: {s['samples']} samples, noise {s['noise_rms']:.4g} {u} rms ({channels})", file=text)
    print(f"  rms nominal {nominal} / declared {st['declared']['rms']:.4g} / extended {st['extended']['rms']:.4g} {u}",
          file=text)
    if s["budget"]["assembly"]:
        print(f"  budget: {s['budget']['summary']}", file=text)
    for a in s["ambiguous"]:
        print(f"  ambiguous: {' or '.join(a['candidates'])} ({a['why']})", file=text)
    if s["rejected_samples"]["count"]:
        print(f"  {s['rejected_samples']['count']} isolated spikes left out", file=text)
    for e in s["effects_added"]:
        params = ", ".join(f"{k}={v:.5g}" if isinstance(v, float) else f"{k}={v}" for k, v in e.items()
                           if k not in ("effect", "evidence", "law", "phase_convention", "attribution", "delta_bic"))
        print(f"  + {e['effect']}: {params}", file=text)
    if not s["effects_added"]:
        print("  no effect added", file=text)
    print(f"  unexplained: {'yes' if s['unexplained'] else 'no'}", file=text)
    for line in _datasheet_summary(s.get("datasheet")):
        print(f"  {line}", file=text)
    update = s.get("design_update")
    if update:
        print(f"  wrote {update['written']}: {len(update['changes'])} error values from the bench", file=text)
        pv = update["preload_variation"]
        if pv["before"] and pv["after"]:
            print(f"  preload band ({pv['before']['label']}): {pv['before']['low_Nm']:.4g}-{pv['before']['high_Nm']:.4g} "
                  f"N·m as designed, {pv['after']['low_Nm']:.4g}-{pv['after']['high_Nm']:.4g} N·m as measured", file=text)
    where = "standard output" if to_stdout else out["json"]
    print(f"  wrote {where} and {out['report']}", file=text)
    return 0
