"""Plots of the geometric mesh checks: backlash and tip clearance against mesh position, and the
distribution of the minimum backlash across the error budget (PNG, matplotlib's Agg backend,
imported only when a plot is drawn).

The functions take the result objects of :mod:`geargen.checks.results` by their attributes
(this layer does not import the checks); lengths are drawn in the design's unit.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from geargen.units import LENGTH_SUFFIXES
from geargen.report.figures import save_png


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_mesh(checks, path, unit: str = "mm") -> Path:
    """Backlash (circumferential, and normal) and tip clearance against mesh position for one
    mesh: ``checks`` one MeshCheck or several of the same mesh (path 1 and path 2 overlaid).
    Positions where the check found interference are shaded."""
    checks = checks if isinstance(checks, (list, tuple)) else [checks]
    plt = _pyplot()
    s = 1.0 / LENGTH_SUFFIXES[unit]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    styles = {"exact_2d": dict(lw=1.6), "sections": dict(lw=1.0, ls="--", marker=".", ms=3)}
    for c in checks:
        sw = c.sweep
        x = np.degrees(sw.mesh_position)
        st = styles.get(c.path, {})
        ax1.plot(x, sw.circumferential_backlash * s, label=f"{c.path}: circumferential", **st)
        ax1.plot(x, sw.normal_backlash * s, label=f"{c.path}: normal", alpha=0.7, **st)
        clear = np.where(np.isfinite(sw.min_clearance), sw.min_clearance, np.nan)
        ax2.plot(x, clear * s, label=f"{c.path}: tip clearance", **st)
        bad = np.asarray(sw.interference) > 0
        if np.any(bad):
            for ax in (ax1, ax2):
                ax.fill_between(x, 0, 1, where=bad, color="tab:red", alpha=0.15,
                                transform=ax.get_xaxis_transform(), label="interference" if ax is ax1 else None)
    for ax in (ax1, ax2):
        ax.axhline(0.0, color="k", lw=0.6)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    ax1.set_ylabel(f"backlash ({unit})")
    ax2.set_ylabel(f"clearance ({unit})")
    ax2.set_xlabel("mesh position: rotation of gear 1 (deg)")
    c0 = checks[0]
    ax1.set_title(f"{c0.mesh}: {c0.gear1} / {c0.gear2}, centre distance {c0.centre_distance * s:.6g} {unit}")
    fig.tight_layout()
    return save_png(fig, path)


def plot_tolerance(result, path, unit: str = "mm") -> Path:
    """Histogram of the Monte Carlo minimum backlash of one mesh with the nominal and worst-case
    minima marked; below it, when the result has one, the backlash over whole revolutions with
    the eccentricities aligned."""
    plt = _pyplot()
    s = 1.0 / LENGTH_SUFFIXES[unit]
    sweep = getattr(result, "revolutions", None)
    if sweep is not None:
        fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7, 6.5))
        ax2.plot(sweep.mesh_position / (2 * np.pi), sweep.circumferential_backlash * s, lw=0.8)
        ax2.axhline(result.nominal_min_backlash * s, color="k", lw=0.8, ls=":", label="nominal")
        ax2.set_xlabel("revolutions of gear 1 (eccentricities aligned at 0)")
        ax2.set_ylabel(f"backlash ({unit})")
        ax2.grid(True, alpha=0.3)
        ax2.legend(fontsize=8)
    else:
        fig, ax = plt.subplots(figsize=(7, 4))
    mc = np.asarray(result.monte_carlo_min_backlash) * s
    if mc.size:
        ax.hist(mc, bins=min(60, max(10, mc.size // 10)), color="tab:blue", alpha=0.7,
                label=f"Monte Carlo: {mc.size} builds")
    ax.axvline(result.nominal_min_backlash * s, color="k", lw=1.2, label="nominal minimum")
    ax.axvline(result.worst_case_min_backlash * s, color="tab:red", lw=1.2, ls="--", label="worst case (bound)")
    ax.axvline(0.0, color="tab:red", lw=0.6)
    coverage = getattr(result, "monte_carlo_coverage", "")
    ax.set_xlabel(f"minimum circumferential backlash ({unit})" + (f"\nper build: {coverage}" if coverage else ""),
                  fontsize=9)
    ax.set_ylabel("samples")
    ax.set_title(f"{result.mesh} ({result.meant_for}) across the error budget")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save_png(fig, path)


def write_check_plots(result, folder) -> list[Path]:
    """One backlash/clearance plot per mesh (both paths overlaid) and one histogram per mesh with
    a tolerance analysis, into ``folder``; returns the files written."""
    folder = Path(folder)
    unit = result.length_unit
    by_mesh: dict[str, list] = {}
    for m in result.meshes:
        by_mesh.setdefault(m.mesh, []).append(m)
    out = [plot_mesh(ms, folder / f"{name}_backlash.png", unit) for name, ms in by_mesh.items()]
    out += [plot_tolerance(t, folder / f"{t.mesh}_tolerance.png", unit) for t in result.tolerances]
    return out


__all__ = ["plot_mesh", "plot_tolerance", "write_check_plots"]
