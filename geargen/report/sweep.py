"""The summary plot of a design sweep (``geargen sweep``): the Pareto front of drive stiffness
against preload variation, and where the designs fail over two swept parameters."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from geargen.report.figures import save_png, write_figure

OK_COLOUR = "#2ca02c"
#: colours of the rejection tags, in order of first appearance (tab10 without its green)
TAG_COLOURS = ("#d62728", "#1f77b4", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf")
MARKERS = ("X", "s", "^", "D", "v", "P", "<", ">", "*")


def _positions(column) -> tuple[np.ndarray, list[str] | None]:
    """Plot positions of a parameter column: its numbers, or the index of each distinct text (the labels)."""
    values = list(column)
    if all(isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool) for v in values):
        return np.asarray(values, dtype=float), None
    labels = list(dict.fromkeys(str(v) for v in values))
    return np.array([labels.index(str(v)) for v in values], dtype=float), labels


def _short(tag: str, most: int = 60) -> str:
    """A legend label of a tag: ``kind (mesh, mesh)`` per kind of failure, cut at ``most`` characters."""
    kinds: dict[str, list[str]] = {}
    for part in tag.split(";"):
        kind, _, where = part.partition(":")
        kinds.setdefault(kind, [])
        if where:
            kinds[kind].append(where)
    text = "; ".join(f"{k} ({', '.join(w)})" if w else k for k, w in kinds.items())
    return text if len(text) <= most else text[:most - 3] + "..."


def _varied(table, parameters: list[str]) -> list[str]:
    return [p for p in parameters if p in table and table[p].astype(str).nunique() > 1]


def pareto_axes(ax, table) -> None:
    """Drive stiffness (N·m/rad) against preload variation (N·m) of the designs that passed; the
    Pareto front (the table's ``pareto`` column) joined by a line."""
    ok = (table["status"] == "ok").to_numpy()
    mc = "mc_preload_variation_Nm" in table
    column = "mc_preload_variation_Nm" if mc else "preload_variation_Nm"
    if "drive_stiffness_Nm_per_rad" not in table or column not in table or not ok.any():
        ax.text(0.5, 0.5, "no design passed its checks", ha="center", va="center", transform=ax.transAxes)
        ax.set_axis_off()
        return
    x = table["drive_stiffness_Nm_per_rad"].to_numpy(float)
    y = table[column].to_numpy(float)
    front = table["pareto"].to_numpy(bool)
    ax.scatter(x[ok & ~front], y[ok & ~front], s=22, color="0.55", label="passed")
    order = np.argsort(x[front])
    ax.plot(x[front][order], y[front][order], "-o", color="#d62728", ms=6, lw=1.5, label="Pareto front")
    for xi, yi, d in zip(x[front], y[front], table["design"].to_numpy()[front]):
        ax.annotate(str(int(d)), (xi, yi), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_xlabel("drive stiffness at the output (N·m/rad)")
    what = "Monte Carlo 99.73 % travel" if mc else "headline error budget"
    ax.set_ylabel(f"preload variation, peak to peak (N·m)\n({what})")
    ax.set_title("Pareto front: stiffer (right) with a steadier preload (down)", fontsize=9)
    from matplotlib.ticker import MaxNLocator
    ax.xaxis.set_major_locator(MaxNLocator(5))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")


def failure_axes(ax, table, parameters: list[str]) -> None:
    """Each design at its values of the first two varied parameters (one: against the design
    number), coloured by what rejected it."""
    varied = _varied(table, parameters) or [p for p in parameters if p in table][:1]
    xs, xlabels = _positions(table[varied[0]])
    if len(varied) > 1:
        ys, ylabels = _positions(table[varied[1]])
        ylabel = varied[1]
    else:
        ys, ylabels, ylabel = table["design"].to_numpy(float), None, "design"
    # a small spread keeps designs that share a grid point (random draws) apart
    step_x = np.min(np.diff(np.unique(xs))) if np.unique(xs).size > 1 else 1.0
    offsets = (np.arange(len(table)) % 7 - 3) * 0.04 * step_x
    shared = np.array([np.sum((xs == a) & (ys == b)) > 1 for a, b in zip(xs, ys)])
    xs = xs + np.where(shared, offsets, 0.0)
    tags = ["ok" if s == "ok" else t for s, t in zip(table["status"], table["tag"])]
    rejections = 0
    for tag in dict.fromkeys(tags):
        sel = np.array([t == tag for t in tags])
        if tag == "ok":
            style = dict(color=OK_COLOUR, marker="o")
        else:
            style = dict(color=TAG_COLOURS[rejections % len(TAG_COLOURS)], marker=MARKERS[rejections % len(MARKERS)])
            rejections += 1
        label = _short(tag)
        ax.scatter(xs[sel], ys[sel], s=36, label=f"{label} ({int(sel.sum())})", alpha=0.85, **style)
    ax.set_xlabel(varied[0])
    ax.set_ylabel(ylabel)
    if xlabels is not None:
        ax.set_xticks(range(len(xlabels)), xlabels, rotation=30, fontsize=7)
    if ylabels is not None:
        ax.set_yticks(range(len(ylabels)), ylabels, fontsize=7)
    ax.set_title("what rejects the designs", fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)


def summary_figure(table, parameters: list[str], design_name: str):
    """The two panels side by side."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(13.0, 5.2), dpi=110)
    FigureCanvasAgg(fig)
    left, right = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.0, 1.0]})
    pareto_axes(left, table)
    failure_axes(right, table, parameters)
    n_ok = int((table["status"] == "ok").sum())
    fig.suptitle(f"{design_name}: sweep of {len(table)} designs, {n_ok} passed", fontsize=11)
    fig.tight_layout()
    return fig


def write_summary_plot(table, parameters: list[str], stem: str | Path, design_name: str) -> dict[str, Path]:
    """``<stem>.png`` and ``<stem>.svg`` of :func:`summary_figure`."""
    stem = Path(stem)
    fig = summary_figure(table, parameters, design_name)
    svg = write_figure(fig, stem.with_suffix(".svg"))
    png = save_png(fig, stem.with_suffix(".png"))
    return {"plot_png": png, "plot_svg": svg}


__all__ = ["pareto_axes", "failure_axes", "summary_figure", "write_summary_plot"]
