"""The human report of ``geargen fit``: Markdown with PNG plots, and the JSON report file.

This module knows nothing of how the fit is made: it takes plain arrays and dictionaries in a
:class:`FitReportInput` (built by :func:`geargen.fit.reporting.report_input`). Matplotlib is
imported only when plots are drawn, with the Agg backend.

Plots: ``fit_data.png`` data and models; ``fit_residuals.png`` residual before (declared) and
after (extended) against time; ``fit_spectrum.png`` the residual's order spectrum with every
shaft and mesh order of the train marked (preload traces); ``fit_dependence.png`` the residual
against load, direction of motion, temperature and time.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

DPI = 80


@dataclass(frozen=True, eq=False)
class FitReportInput:
    """What the report shows. Arrays are (n,) in record order unless said otherwise.

    ``abscissa``/``measured``: the data-and-model plot's axes (output angle and carriage, or
    rotation and torque); ``direction`` +1/-1 per sample (output turning forward/back, or torque
    rising/falling); ``load`` the torque (None for a preload trace); ``spectrum``: ``orders``
    (m,) and residual amplitudes (m,) ``declared`` and ``extended``; ``train_orders`` and
    ``effect_orders`` as (label, order) pairs; ``summary`` the JSON report.
    """

    name: str
    kind: str
    units: str
    description: str
    summary: dict
    time_s: np.ndarray
    abscissa: np.ndarray
    abscissa_label: str
    measured: np.ndarray
    measured_label: str
    declared_prediction: np.ndarray
    extended_prediction: np.ndarray
    residual_declared: np.ndarray
    residual_extended: np.ndarray
    direction: np.ndarray
    direction_label: str
    noise_rms: float
    noise_method: str
    rule_text: str
    temperature_C: np.ndarray | None = None
    load: np.ndarray | None = None
    load_label: str = ""
    spectrum: dict | None = None
    train_orders: list = field(default_factory=list)
    effect_orders: list = field(default_factory=list)
    effects: list = field(default_factory=list)
    candidates: list = field(default_factory=list)
    tests: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    declared_values: dict = field(default_factory=dict)


def write_json(path: str | Path, summary: dict) -> Path:
    """Write the contract's JSON report (NaN-free, indented)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(summary, indent=2, allow_nan=False) + "\n")
    return path


def _fmt(v, digits: int = 4) -> str:
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, float):
        if not math.isfinite(v):
            return str(v)
        return f"{v:.{digits}g}"
    return str(v)


def _cell(text) -> str:
    """Text safe inside a Markdown table cell (a literal | would end the cell)."""
    return str(text).replace("|", "\\|").replace("\n", " ")


def _thin(n: int, max_points: int) -> np.ndarray:
    step = max(1, int(math.ceil(n / max_points)))
    return np.arange(0, n, step)


def _envelope(x: np.ndarray, *ys: np.ndarray, bins: int = 3000):
    """At most ``bins`` points per curve, keeping each bin's largest value (peaks survive)."""
    if x.size <= bins:
        return (x, *ys)
    edges = np.linspace(0, x.size, bins + 1).astype(int)
    out = [x[edges[:-1]]]
    for y in ys:
        out.append(np.maximum.reduceat(y, edges[:-1]))
    return tuple(out)


def _plots(directory: Path, inp: FitReportInput, max_points: int) -> list[tuple[str, str]]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    u = inp.units
    idx = _thin(inp.time_s.size, max_points)
    out = []

    # data and model
    fig, ax = plt.subplots(figsize=(9, 4.2))
    if inp.kind == "torque_deflection":
        ax.plot(inp.abscissa[idx], inp.measured[idx], ".", ms=1.5, color="0.55", label="measured")
        ax.plot(inp.abscissa[idx], inp.declared_prediction[idx], "-", lw=0.8, color="tab:blue", label="declared model (fitted)")
        ax.plot(inp.abscissa[idx], inp.extended_prediction[idx], "-", lw=0.8, color="tab:red", label="extended model")
        ax.set_xlabel(inp.abscissa_label)
    else:
        ax.plot(inp.time_s[idx], inp.measured[idx], ".", ms=1.0, color="0.55", label="measured")
        ax.plot(inp.time_s[idx], inp.declared_prediction[idx], "-", lw=0.6, color="tab:blue", label="declared model (fitted)")
        ax.plot(inp.time_s[idx], inp.extended_prediction[idx], "-", lw=0.6, color="tab:red", label="extended model")
        ax.set_xlabel("time (s)")
    ax.set_ylabel(inp.measured_label)
    ax.legend(loc="best", fontsize=8)
    ax.set_title(f"{inp.name}: data and model")
    fig.subplots_adjust(left=0.08, right=0.92, bottom=0.12, top=0.92)
    fig.savefig(directory / "fit_data.png", dpi=DPI)
    plt.close(fig)
    out.append(("Data and model", "fit_data.png"))

    # residual before / after
    fig, axes = plt.subplots(2, 1, figsize=(9, 5), sharex=True)
    for ax, r, title in ((axes[0], inp.residual_declared, "declared model"), (axes[1], inp.residual_extended, "extended model")):
        ax.plot(inp.time_s[idx], r[idx], ".", ms=1.0, color="tab:blue" if ax is axes[0] else "tab:red")
        ax.axhspan(-2 * inp.noise_rms, 2 * inp.noise_rms, color="0.85", zorder=0, label="±2 x noise")
        ax.set_ylabel(f"residual ({u})")
        ax.set_title(f"residual after the {title}: rms {np.sqrt(np.mean(r ** 2)):.4g} {u}", fontsize=9)
    axes[0].legend(loc="upper right", fontsize=8)
    axes[1].set_xlabel("time (s)")
    fig.subplots_adjust(left=0.08, right=0.97, bottom=0.1, top=0.93, hspace=0.3)
    fig.savefig(directory / "fit_residuals.png", dpi=DPI)
    plt.close(fig)
    out.append(("Residual before (declared) and after (extended)", "fit_residuals.png"))

    # order spectrum
    if inp.spectrum is not None:
        sp = inp.spectrum
        fig, ax = plt.subplots(figsize=(9, 4.2))
        q, a_dec, a_ext = _envelope(sp["orders"], sp["declared"], sp["extended"], bins=3000)
        ax.semilogy(q, np.maximum(a_dec, 1e-12), lw=0.6, color="tab:blue", label="declared-model residual")
        ax.semilogy(q, np.maximum(a_ext, 1e-12), lw=0.6, color="tab:red", label="extended-model residual")
        ymax = max(float(np.max(sp["declared"])), 1e-9) * 2
        for label, q in inp.train_orders:
            ax.axvline(q, color="0.4", ls="--", lw=0.7)
            ax.text(q, ymax, f" {label}\n {q:.4g}", rotation=90, fontsize=7, va="top", ha="left", color="0.3")
        for label, q in inp.effect_orders:
            ax.axvline(q, color="tab:orange", ls=":", lw=1.0)
            ax.text(q, ymax / 30, f" {label}", rotation=90, fontsize=7, va="top", ha="right", color="tab:orange")
        floor = inp.noise_rms * math.sqrt(4.0 / max(inp.time_s.size, 1))
        ax.axhline(floor, color="0.6", lw=0.6, ls="-.", label="noise amplitude floor (2 sigma / sqrt n)")
        ax.set_ylim(bottom=max(floor / 30.0, 1e-12), top=ymax * 1.5)
        ax.set_xscale("log")
        ax.set_xlabel("order (per output revolution)")
        ax.set_ylabel(f"amplitude ({u})")
        ax.set_title("residual order spectrum (least squares, uneven samples and gaps)", fontsize=9)
        ax.legend(loc="lower left", fontsize=8)
        fig.subplots_adjust(left=0.08, right=0.97, bottom=0.12, top=0.92)
        fig.savefig(directory / "fit_spectrum.png", dpi=DPI)
        plt.close(fig)
        out.append(("Residual order spectrum, every shaft and mesh order marked", "fit_spectrum.png"))

    # dependence on load, direction, temperature, time
    fig, axes = plt.subplots(2, 2, figsize=(10, 7))
    ax = axes[0, 0]
    if inp.load is not None:
        ax.plot(inp.load[idx], inp.residual_declared[idx], ".", ms=1.0, color="tab:blue", label="declared")
        ax.plot(inp.load[idx], inp.residual_extended[idx], ".", ms=1.0, color="tab:red", label="extended")
        ax.set_xlabel(inp.load_label)
        ax.set_title("residual against load", fontsize=9)
    else:
        ax.plot(inp.abscissa[idx], inp.residual_declared[idx], ".", ms=1.0, color="tab:blue", label="declared")
        ax.plot(inp.abscissa[idx], inp.residual_extended[idx], ".", ms=1.0, color="tab:red", label="extended")
        ax.set_xlabel(inp.abscissa_label)
        ax.set_title(f"residual against output angle (no load in a {inp.kind.replace('_', ' ')})", fontsize=9)
    ax.set_ylabel(f"residual ({u})")
    ax.legend(fontsize=8, markerscale=6)
    ax = axes[0, 1]
    labels, means, spreads, colours = [], [], [], []
    for r, name, colour in ((inp.residual_declared, "declared", "tab:blue"), (inp.residual_extended, "extended", "tab:red")):
        for d, dname in ((1, "+"), (-1, "−")):
            sel = inp.direction == d
            labels.append(f"{name} {dname}")
            means.append(float(np.mean(r[sel])) if sel.any() else 0.0)
            spreads.append(float(np.std(r[sel])) if sel.any() else 0.0)
            colours.append(colour)
    pos = np.arange(len(labels))
    ax.bar(pos, means, yerr=spreads, color=colours, alpha=0.6, capsize=4)
    ax.axhline(0.0, color="0.3", lw=0.6)
    ax.set_xticks(pos, labels, fontsize=8)
    ax.set_title(f"mean residual ± 1 std by direction ({inp.direction_label})", fontsize=9)
    ax.set_ylabel(f"residual ({u})")
    ax = axes[1, 0]
    if inp.temperature_C is not None:
        ax.plot(inp.temperature_C[idx], inp.residual_declared[idx], ".", ms=1.0, color="tab:blue", label="declared")
        ax.plot(inp.temperature_C[idx], inp.residual_extended[idx], ".", ms=1.0, color="tab:red", label="extended")
        ax.set_xlabel("temperature (C)")
        ax.set_title("residual against temperature", fontsize=9)
    else:
        ax.text(0.5, 0.5, "no temperature column", ha="center", va="center", transform=ax.transAxes)
        ax.set_title("residual against temperature", fontsize=9)
    ax.set_ylabel(f"residual ({u})")
    ax = axes[1, 1]
    ax.plot(inp.time_s[idx], inp.residual_declared[idx], ".", ms=1.0, color="tab:blue", label="declared")
    ax.plot(inp.time_s[idx], inp.residual_extended[idx], ".", ms=1.0, color="tab:red", label="extended")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"residual ({u})")
    ax.set_title("residual against time", fontsize=9)
    fig.subplots_adjust(left=0.08, right=0.97, bottom=0.08, top=0.95, hspace=0.35, wspace=0.25)
    fig.savefig(directory / "fit_dependence.png", dpi=DPI)
    plt.close(fig)
    out.append(("Residual against load, direction of motion, temperature and time", "fit_dependence.png"))
    return out


def _params_text(e: dict) -> str:
    skip = {"effect", "evidence", "delta_bic", "phase_convention", "law", "attribution", "held_out"}
    return ", ".join(f"{k} = {_fmt(v, 6)}" for k, v in e.items() if k not in skip)


def markdown(inp: FitReportInput, plots: list[tuple[str, str]]) -> str:
    s = inp.summary
    u = inp.units
    lines = [f"# Fit report: {inp.name}", ""]
    if inp.description:
        lines += [f"*{inp.description}*", ""]
    what = {"preload_trace": " of carriage position against output angle.", "torque_deflection": " of output torque.",
            "transmission_error": " of transmission error at the output (output angle - input angle / ratio)."}
    lines += [f"Kind `{inp.kind}`, {s['samples']} samples, residual in **{u}**" + what.get(inp.kind, "."), ""]
    lines += ["## Result", "", "| stage | rms | max abs |", "|---|---|---|"]
    for stage in ("nominal", "declared", "extended"):
        v = s["stages"][stage]
        rms = f"{v['rms']:#.4g}" if v else "null"
        max_abs = f"{v['max_abs']:#.4g}" if v else "null"
        lines.append(f"| {stage} | {rms} | {max_abs} |")
    channels = ", ".join(f"{k} {_fmt(v)}" for k, v in s.get("noise_channels", {}).items())
    lines += ["", f"Noise level from the data alone: **{_fmt(s['noise_rms'])} {u}** rms (each channel: {channels}).",
              f"Error before and after (declared -> extended): **{s['stages']['declared']['rms']:#.4g} -> "
              f"{s['stages']['extended']['rms']:#.4g} {u}** rms.", ""]
    if s["unexplained"]:
        lines += ["**Unexplained: yes.** The residual after the extended model is still not consistent with noise; "
                  "see the residual tests. No library effect accounts for it.", ""]
    else:
        lines += ["Unexplained: no. The residual after the extended model is consistent with the noise.", ""]
    if s["stages"]["nominal"] is None:
        lines += ["The nominal stage is null: the declared model has no nominal values.", ""]
    elif inp.kind == "preload_trace":
        lines += ["Nominal stage: perfect gears, the carriage stays at its mean position.", ""]
    elif inp.kind == "transmission_error":
        lines += ["Nominal stage: perfect gears at the declared ratio, the transmission error stays at its mean.", ""]
    else:
        lines += ["Nominal stage: the two-path law with the declared stiffnesses and preload and the probe zero as read.", ""]
    if inp.declared_values:
        lines += ["Declared model, fitted values:", ""]
        for k, v in inp.declared_values.items():
            lines.append(f"- {k}: {_params_text(v) if isinstance(v, dict) else _fmt(v, 6)}")
        lines.append("")
    lines += _datasheet_lines(s.get("datasheet"))
    lines += ["## Effects added", ""]
    if not inp.effects:
        lines += ["None: nothing beyond the declared model is justified by the data.", ""]
    else:
        lines += ["Added one at a time, strongest first.", "", "| # | effect | parameters | dBIC |", "|---|---|---|---|"]
        for i, e in enumerate(inp.effects, 1):
            lines.append(f"| {i} | {e['effect']} | {_cell(_params_text(e))} | {_fmt(e.get('delta_bic'), 6)} |")
        lines.append("")
        for i, e in enumerate(inp.effects, 1):
            extra = []
            for key in ("attribution", "law", "phase_convention"):
                if e.get(key):
                    extra.append(f"{key}: {e[key]}")
            lines.append(f"{i}. **{e['effect']}**: {e.get('evidence', '')}" + (f" ({'; '.join(extra)})" if extra else ""))
        lines.append("")
    budget = s.get("budget") or {}
    if budget.get("assembly"):
        lines += ["## Against the design's error budget", "", f"{budget['summary']}.", "",
                  "| term | gears | order | carriage amplitude (um) | budget amplitude (um) | measured TIR (um) | "
                  "budget TIR (um) | verdict |", "|---|---|---|---|---|---|---|---|"]
        for r in budget["terms"]:
            lines.append(f"| {r['term']} | {', '.join(r['gears'])} | {_fmt(r['order'], 5)} | {_fmt(r['amplitude_um'], 4)} | "
                         f"{_fmt(r['budget_amplitude_um'], 4)} | {_fmt(r.get('measured_tir_um'), 4)} | "
                         f"{_fmt(r.get('budget_tir_um'), 4)} | {r['verdict']} |")
        lines += ["", "Measured TIR = 2 x amplitude / (carriage motion per unit of pitch-circle offset, from the "
                  "design's exact loop geometry); a cluster's order is shared by four gears (the TIR each would "
                  "carry in phase: a lower bound of the largest).", ""]
    if s.get("ambiguous"):
        lines += ["## Ambiguous", "", "Effects the data cannot tell apart or pin down: reported, not added (the residual "
                  "tests are made with the strongest of them in the model).", ""]
        for a in s["ambiguous"]:
            fits = "; ".join(f"{f['effect']} ({_params_text(f)}, dBIC {_fmt(f.get('delta_bic'), 5)})" for f in a["fits"])
            lines.append(f"- {' or '.join(a['candidates'])}: {fits}. {a['why']}.")
        lines.append("")
    rejected = s.get("rejected_samples", {})
    if rejected.get("count"):
        lines += ["## Samples left out", "", f"{rejected['count']} isolated spikes (a sample that jumps away from its "
                  "neighbours on both sides by more than the noise allows):", "",
                  "| time (s) | column | value | deviation (noise levels) |", "|---|---|---|---|"]
        lines += [f"| {_fmt(e['time_s'], 7)} | {e['column']} | {_fmt(e['value'])} | {_fmt(e['deviation'], 3)} |"
                  for e in rejected["samples"][:20]]
        lines.append("")
    lines += ["## Diagnosis", "", "Every candidate of every round, on the residual of the model as it stood then.", "",
              "| round | candidate | dBIC | outcome | evidence |", "|---|---|---|---|---|"]
    for c in inp.candidates:
        lines.append(f"| {c['round']} | {_cell(c['label'])} | {_fmt(c['delta_bic'], 5)} | {_cell(c['outcome'])} | "
                     f"{_cell(c['evidence'])} |")
    lines += ["", "## Residual tests", "", "| test | statistic | limit | passed | finding |", "|---|---|---|---|---|"]
    for t in inp.tests:
        lines.append(f"| {t['name']} | {_fmt(t['statistic'])} | {_fmt(t['limit'])} | {_fmt(t['passed'])} | {_cell(t['text'])} |")
    lines += ["", "## How the decision is made", "", inp.rule_text, "", f"Noise estimate: {inp.noise_method}.", ""]
    if inp.notes:
        lines += ["## Notes", ""] + [f"- {n}" for n in inp.notes] + [""]
    lines += ["## Plots", ""]
    for title, fname in plots:
        lines += [f"### {title}", "", f"![{title}]({fname})", ""]
    return "\n".join(lines)


def _datasheet_lines(sheet: dict | None) -> list[str]:
    """The datasheet section: figures taken from the record itself, without the model."""
    if not sheet:
        return []
    lines = ["## Datasheet figures", "", "Taken from the record itself, without any model (contracts/measurements.md).", ""]
    if sheet.get("tests"):
        lines += ["| test | amplitude (Nm) | rated (Nm) | hysteresis loss (urad) | lost motion (urad) at +- (Nm) | "
                  "torsion (urad) at +- (Nm) | T1 / T2 (Nm) | K1 / K2 / K3 (Nm/rad) |", "|---|---|---|---|---|---|---|---|"]
        for t in sheet["tests"]:
            k = t["stiffness"]
            lines.append(f"| {t['test']} | {_fmt(t['torque_amplitude_Nm'])} | {_fmt(t['rated_torque_Nm'])} | "
                         f"{_fmt(t['hysteresis_loss_urad'])} | {_fmt(t['lost_motion_urad'])} at {_fmt(t['lost_motion_at_Nm'])} | "
                         f"{_fmt(t.get('torsion_urad'))} at {_fmt(t.get('torsion_at_Nm'))} | "
                         f"{_fmt(k['T1_Nm'])} / {_fmt(k['T2_Nm'])} | {_fmt(k['K1_Nm_per_rad'])} / "
                         f"{_fmt(k['K2_Nm_per_rad'])} / {_fmt(k['K3_Nm_per_rad'])} |")
        lines.append("")
        for t in sheet["tests"]:
            lines.append(f"- test {t['test']}: " + "; ".join(f"{key.replace('_', ' ')}: {text}"
                                                             for key, text in t.get("how", {}).items()))
        lines.append("")
    if sheet.get("how") and "transmission_accuracy_urad" in sheet and not sheet.get("tests"):
        acc = sheet["transmission_accuracy_urad"]
        lines += [f"Transmission accuracy: **{_fmt(acc)} urad** ({_fmt(acc * 180 / math.pi * 3600e-6 if acc else None)} "
                  f"arcsec): {sheet['how']}.", ""]
        if sheet.get("per_revolution_urad"):
            lines += ["Per complete output revolution (urad): " + ", ".join(_fmt(v) for v in sheet["per_revolution_urad"]),
                      ""]
    return lines


def write_fit_report(directory: str | Path, inp: FitReportInput, max_points: int = 10000, plots: bool = True) -> Path:
    """Write ``report.md``, ``report.html`` (the same blocks, the figures linked as the PNG files
    beside it) and the plots into ``directory``; returns the Markdown path."""
    from geargen.report.review import from_markdown, to_html
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    made = _plots(directory, inp, max_points) if plots else []
    path = directory / "report.md"
    text = markdown(inp, made)
    path.write_text(text)
    status = "UNEXPLAINED" if inp.summary["unexplained"] else "explained"
    (directory / "report.html").write_text(to_html(from_markdown(text, status)), encoding="utf-8")
    return path
