"""``geargen fit NAME.csv --json REPORT.json [--report DIR]``: fit a bench measurement, find what
the declared model lacks, add it, and report the error before and after
(contracts/measurements.md)."""

from __future__ import annotations

import time
from pathlib import Path


def add_arguments(p) -> None:
    p.add_argument("csv", help="the measurement NAME.csv; its sidecar NAME.toml must sit beside it")
    p.add_argument("--json", dest="json_path", default=None,
                   help="where to write the JSON report (default: NAME.fit.json beside the CSV)")
    p.add_argument("--report", dest="report_dir", default=None,
                   help="folder for the human report, report.md and plots (default: NAME_fit/ beside the JSON)")
    p.add_argument("--no-plots", action="store_true", help="write the Markdown report without plots")


def fit_files(csv_path, json_path=None, report_dir=None, plots: bool = True) -> dict:
    """Read, fit, diagnose and report one measurement. Returns the JSON summary and timings."""
    from geargen.fit.measurement import read_measurement
    from geargen.fit.reporting import report_input
    from geargen.fit.selection import diagnose
    from geargen.report.fit import write_fit_report, write_json

    csv_path = Path(csv_path)
    json_path = Path(json_path) if json_path else csv_path.with_name(f"{csv_path.stem}.fit.json")
    report_dir = Path(report_dir) if report_dir else json_path.with_name(f"{csv_path.stem}_fit")
    t0, c0 = time.perf_counter(), time.process_time()
    meas = read_measurement(csv_path)
    t1, c1 = time.perf_counter(), time.process_time()
    dg = diagnose(meas)
    t2, c2 = time.perf_counter(), time.process_time()
    summary = dg.to_json()
    write_json(json_path, summary)
    report = write_fit_report(report_dir, report_input(dg), plots=plots)
    t3, c3 = time.perf_counter(), time.process_time()
    return {"summary": summary, "json": json_path, "report": report, "diagnosis": dg,
            "seconds": {"read": t1 - t0, "fit": t2 - t1, "report": t3 - t2, "total": t3 - t0},
            "cpu_seconds": {"read": c1 - c0, "fit": c2 - c1, "report": c3 - c2, "total": c3 - c0}}


def run(args) -> int:
    out = fit_files(args.csv, args.json_path, args.report_dir, plots=not args.no_plots)
    s = out["summary"]
    u = s["units"]
    st = s["stages"]
    nominal = f"{st['nominal']['rms']:.4g}" if st["nominal"] else "null"
    print(f"{s['kind']}: {s['samples']} samples, noise {s['noise_rms']:.4g} {u} rms")
    print(f"  rms nominal {nominal} / declared {st['declared']['rms']:.4g} / extended {st['extended']['rms']:.4g} {u}")
    for e in s["effects_added"]:
        params = ", ".join(f"{k}={v:.5g}" if isinstance(v, float) else f"{k}={v}" for k, v in e.items()
                           if k not in ("effect", "evidence", "law", "phase_convention", "attribution", "delta_bic"))
        print(f"  + {e['effect']}: {params}")
    if not s["effects_added"]:
        print("  no effect added")
    print(f"  unexplained: {'yes' if s['unexplained'] else 'no'}")
    print(f"  wrote {out['json']} and {out['report']}")
    return 0
