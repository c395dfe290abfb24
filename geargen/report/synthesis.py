"""Reports of centre synthesis and tolerance analysis: the Appendix-style table, JSON, histogram.

Numbers are printed in the design's length unit, rounded half-up (away from zero at a tie) to
the Appendix's decimals. The JSON follows ``../shared/contracts/synthesis.md`` (more keys are
allowed there, and present here); it carries full precision, lengths in ``length_unit``.
matplotlib is imported only by :func:`histogram_png`, with the Agg backend.
"""

from __future__ import annotations

import json
import math
from decimal import ROUND_HALF_UP, Decimal
from pathlib import Path

from geargen.core.synthesis import Placement
from geargen.design.synthesis import ERROR_KINDS, GEAR_ROLES
from geargen.units import MM_PER_IN
from geargen.model.synthesis import SynthesisRun
from geargen.report.figures import save_png

SCHEMA = "geargen.synth/1"

PHASE_CONVENTION = (
    "rotation_rad of a gear is the polar angle, about its own centre in the output frame (+x towards the "
    "input, counter-clockwise positive seen from +z), of the centreline of its tooth 0: model the gear with "
    "a tooth centred on local +x, rotate it by rotation_rad about its axis, move it to its centre. Each "
    "cluster is one part with a tooth of its large and of its small gear centred on the same radial line, "
    "so both carry the cluster's rotation.")

_ERROR_LABELS = ("Bearing Eccentr.", "Pitch Line Eccen", "Tooth To Tooth")


def error_sources(errors) -> list[str]:
    """One line per budget row that was derived, not entered (a gear's accuracy grade), saying
    where it came from; none for a budget typed in (the Appendix table as before)."""
    return [f"{label.strip()} of gear {k} ({GEAR_ROLES[k - 1]}): {src}"
            for i, label in enumerate(_ERROR_LABELS)
            for k, e in enumerate(errors, start=1) if (src := e.sources[i])]


def fixed(value: float, decimals: int) -> str:
    """``value`` rounded half-up (ties away from zero) to ``decimals``, without a negative zero."""
    if not math.isfinite(value):
        return "nan"
    q = Decimal(value).quantize(Decimal(1).scaleb(-decimals), rounding=ROUND_HALF_UP)
    if q == 0:
        q = abs(q)
    return f"{q:.{decimals}f}"


_LABEL, _UNIT, _CELL = 20, 16, 11


def _cells(label: str, unit: str, cells=()) -> tuple[str, ...]:
    return (label, unit, *cells)


def _row(label: str, unit: str, cells=()) -> str:
    return (f"{label:<{_LABEL}}{unit:<{_UNIT}}" + "".join(f"{c:>{_CELL}}" for c in cells)).rstrip()


def appendix_sections(run: SynthesisRun) -> tuple[str, list[tuple[list[str], list[list[str]]]]]:
    """The Appendix's "Error Analysis and Center Location Program", for any dual-pinion design:
    its title and its two tables (gears; meshes and the synthesis), each ``(header, rows)``. A
    row is ``[description, symbol/unit, value...]``; a row of one cell is a caption inside the
    table (the Appendix's sub-headings and notes)."""
    u = run.length_unit
    inp, s, b = run.inputs, run.synthesis, run.budget
    L = run.length
    title = f"Error Analysis and Center Location Program: {run.design_name} (lengths in {u})"
    lines = ["General Information",
             _cells("No. of Teeth", "N", [str(z) for z in inp.teeth])]
    modules = (inp.module_mesh1, inp.module_mesh1, inp.module_mesh2, inp.module_mesh2)
    alphas = (inp.pressure_angle_mesh1,) * 2 + (inp.pressure_angle_mesh2,) * 2
    if u == "in":
        lines.append(_cells("Diametral Pitch", "P", [f"{MM_PER_IN / m:.6g}" for m in modules]))
    else:
        lines.append(_cells("Module", "m (mm)", [f"{m:.6g}" for m in modules]))
    lines.append(_cells("Pressure Angle", "Ø (deg)", [f"{math.degrees(a):.6g}" for a in alphas]))
    lines.append(_cells("Pitch Circle Dia.", f"D ({u})", [f"{L(2 * inp.reference_radius(k)):.6g}" for k in (1, 2, 3, 4)]))
    if run.errors is not None and b is not None:
        lines.append("Error Information")
        for label, kind in zip(_ERROR_LABELS, ERROR_KINDS):
            lines.append(_cells(label, f"({u} t.i.r.)", [fixed(L(getattr(e, kind)), 4) for e in run.errors]))
        lines.append(_cells("Total Error", f"({u} t.i.r.)", [fixed(L(t), 4) for t in b.total_tir]))
        lines += error_sources(run.errors)
        lines += ["Variation in x1 to accommodate errors.",
                  _cells("Δx1", f"({u})", [fixed(L(d), 4) for d in b.dx1]),
                  _cells("% of Sum", "", [fixed(p, 0) for p in b.percent_of_sum]),
                  _cells("% of RSS", "", [fixed(p, 0) for p in b.percent_of_rss]),
                  _cells("", "", ["Δx1", "ΔC1"]),
                  _cells("Sum", f"({u})", [fixed(L(b.dx1_sum), 4), fixed(L(b.dC1_sum), 4)]),
                  _cells("RSS", f"({u})", [fixed(L(b.dx1_rss), 4), fixed(L(b.dC1_rss), 4)]),
                  _cells("(Sum + RSS)/2", f"({u})", [fixed(L(b.dx1_mean), 4), fixed(L(b.dC1_mean), 4)])]
    else:
        lines.append("Error Information: none (the design has no [errors.*] tables)")
    gears = lines
    lines = ["Mesh Information",
              _cells("Center Distance", f"Cnom ({u})", [fixed(L(inp.centre_distance(m)), 4) for m in (1, 2)]),
              _cells("Backlash", f"Bmax ({u})", [fixed(L(inp.backlash(m, "max")), 4) for m in (1, 2)]),
              _cells("", f"Bmin ({u})", [fixed(L(inp.backlash(m, "min")), 4) for m in (1, 2)]),
              _cells("Ang. Backlash", "Ba.max (rad)", [fixed(s.angular_backlash(m, "max"), 4) for m in (1, 2)]),
              _cells("", "Ba.min (rad)", [fixed(s.angular_backlash(m, "min"), 4) for m in (1, 2)]),
              _cells("Mesh Ratio", "R", [fixed(s.ratio_mesh1, 4), fixed(s.ratio_mesh2, 4)]),
              "Synthesis of Gear Centers",
              "Calculate A2 and N for maximum backlash given A1 and center distances.",
              _cells("A1", "(rad)", [fixed(s.nominal_A1, 4)]),
              _cells("A2", "(rad)", [fixed(s.nominal_A2, 4)]),
              _cells("N", "", [fixed(s.nominal_teeth_count, 4)]),
              f"Solve for A1 and A2 given N rounded ({inp.rounding}: i = {s.increments} half teeth).",
              _cells("N", "rounded", [f"{s.teeth_count:g}"]),
              _cells("A1", "(rad, deg)", [fixed(s.A1, 4), fixed(math.degrees(s.A1), 4)]),
              _cells("A2", "(rad, deg)", [fixed(s.A2, 4), fixed(math.degrees(s.A2), 4)]),
              _cells("error", "", [fixed(s.eq7_residual, 4)]),
              "Center distance components",
              _cells("x1", f"({u})", [fixed(L(s.x1), 4)]),
              _cells("y1", f"({u})", [fixed(L(s.y1), 4)]),
              _cells("x2", f"({u})", [fixed(L(s.x2), 4)]),
              _cells("y2", f"({u})", [fixed(L(s.y2), 4)]),
              "Allow x1 to change to accommodate minimum backlash.",
              _cells("A1", "(rad, deg)", [fixed(s.min_backlash_A1, 4), fixed(math.degrees(s.min_backlash_A1), 4)]),
              _cells("C1", f"({u})", [fixed(L(s.min_backlash_C1), 4)]),
              _cells("x1", f"({u})", [fixed(L(s.min_backlash_x1), 4)]),
              _cells("Δx1", f"({u})", [fixed(L(s.min_backlash_dx1), 4)])]

    def rows(items):
        return [list(item) if isinstance(item, tuple) else [item] for item in items]
    return title, [(["Description", "Symbol/Unit", "Gear 1", "Gear 2", "Gear 3", "Gear 4"], rows(gears)),
                   (["Description", "Symbol/Unit", "Mesh 1", "Mesh 2"], rows(lines))]


def appendix_table(run: SynthesisRun) -> str:
    """:func:`appendix_sections` as the Appendix's fixed-width text."""
    title, tables = appendix_sections(run)
    lines = [title]
    for header, rows in tables:
        lines += ["", _row(header[0], header[1], header[2:])]
        lines += [_row(r[0], r[1], r[2:]) if len(r) > 1 else r[0] for r in rows]
    return "\n".join(lines)


def beyond_table(run: SynthesisRun) -> str:
    """What the exact involute geometry adds: minimum-backlash travel, error budget, placement."""
    u = run.length_unit
    s = run.synthesis
    L = run.length
    lines = ["Beyond the Appendix: exact involute geometry",
             "Minimum backlash with B following the centre distance (the Appendix holds B fixed).",
             _row("C1", f"({u})", [fixed(L(run.exact_min_backlash_C1), 4)]),
             _row("x1", f"({u})", [fixed(L(run.exact_min_backlash_x1), 4)]),
             _row("Δx1", f"({u})", [fixed(L(run.exact_min_backlash_x1 - s.x1), 4)])]
    e = run.exact_budget
    if e is not None:
        lines += ["Carriage travel per gear, both clusters' gears and every error as geometry.",
                  _row("", "", ["Gear 1", "Gear 2", "Gear 3", "Gear 4", "Sum", "RSS"]),
                  _row("Δx1 linear", f"({u})", [fixed(L(d), 4) for d in e.dx1_linear] + [fixed(L(e.dx1_sum), 4), ""]),
                  _row("Δx1 re-solved", f"({u})", [fixed(L(d), 4) for d in e.dx1_resolved]
                       + [fixed(L(e.travel_resolved), 4), fixed(L(e.dx1_rss), 4)])]
        if run.budget is not None:
            lines.append(_row("Δx1 Appendix", f"({u})", [fixed(L(d), 4) for d in run.budget.dx1]
                              + [fixed(L(run.budget.dx1_sum), 4), fixed(L(run.budget.dx1_rss), 4)]))
        if not e.success:
            lines.append(f"warning: {e.message}")
    r = run.resolved
    if r is not None:
        lines += ["As built: the resolved drive (the teeth, centres and phases that check, stiffness, build and "
                  "the exported solids use)",
                  f"backlash: {r['backlash_kind']}; solids keep {fixed(r['loaded_flank_gap'], 6)} {u} on the "
                  "working flanks",
                  _row("Mesh", f"({u})", ["centre d.", "backlash", "design min", "design max"])]
        for m in r["meshes"]:
            lines.append(_row(m["name"], "", [fixed(m["centre_distance"], 6), fixed(m["backlash"], 6),
                                              fixed(m["backlash_design_min"], 6), fixed(m["backlash_design_max"], 6)]))
        lines.append(_row("Gear", f"centre ({u})", ["x", "y", "rot (rad)", "rot (deg)"]))
        for g in r["gears"]:
            lines.append(_row(g["name"], "", [fixed(g["centre"][0], 6), fixed(g["centre"][1], 6),
                                              fixed(g["rotation_rad"], 6), fixed(g["rotation_deg"], 4)]))
        lines += [f"note: {n}" for n in r["notes"]]
    return "\n".join(lines)


def monte_carlo_table(run: SynthesisRun) -> str:
    mc = run.monte_carlo
    if mc is None:
        return ""
    u = run.length_unit
    L = run.length
    # named apart from geargen check's backlash Monte Carlo ([checks] monte_carlo_samples)
    head = (f"Carriage-travel Monte Carlo ([monte_carlo]): {mc.samples} samples, model {mc.model!r}, error shape "
            f"{mc.error_shape!r}"
            + (f", seed {run.monte_carlo_settings.seed}" if run.monte_carlo_settings else "")
            + (f", {run.monte_carlo_seconds:.2f} s" if run.monte_carlo_seconds is not None else ""))
    lines = [head, "Carriage travel from the synthesised position (+ away from the output)."]
    if not mc.success:
        return "\n".join(lines + [f"failed: {mc.message}"])
    cells = [f"p{p:g}" for p in mc.percentiles]
    lines.append(_row("", "", cells))
    lines.append(_row("travel", f"({u})", [fixed(L(v), 5) for v in mc.percentiles.values()]))
    if mc.force is not None:
        lines.append(_row("spring force", "(N)", [fixed(v, 3) for v in mc.force_percentiles.values()]))
    lines += [_row("", "", ["min", "max", "std", "99.73%", "RSS", "worst Sum"]),
              _row("travel", f"({u})", [fixed(L(v), 5) for v in (mc.minimum, mc.maximum, mc.std, mc.spread_99_73,
                                                                     mc.rss, mc.worst_case_sum)])]
    if mc.force is not None:
        k = mc.spring_rate
        lines.append(_row("spring force", "(N)", [fixed(v, 3) for v in (mc.preload + k * mc.minimum,
                                                                       mc.preload + k * mc.maximum, k * mc.std,
                                                                       k * mc.spread_99_73, k * mc.rss,
                                                                       k * mc.worst_case_sum)]))
        lines.append(f"spring rate {k:.6g} N/mm, preload {mc.preload:.6g} N at the synthesised position")
    return "\n".join(lines)


def sensitivity_tables(run: SynthesisRun) -> str:
    u = run.length_unit
    lines = []
    g = run.geometry_sensitivity
    if g is not None:
        lines += [f"Sensitivity of the geometry (per {u} of input; angles in rad, lengths in {u})",
                  _row("input", "", list(g.outputs[:4]) + ["Δx1 min", "Δx1 exact"])]
        for i, name in enumerate(g.inputs):
            vals = [v * (run.scale if ou == "angle" else 1.0) for v, ou in zip(g.values[i], g.output_units)]
            lines.append(f"{name:<{_LABEL + _UNIT}}" + "".join(f"{v:>{_CELL}.4g}" for v in vals))
    t = run.tolerance_sensitivity
    if t is not None:
        lines += ["", f"Which tolerance to buy: carriage travel per unit TIR ({u}/{u})",
                  f"{'gear.error':<{_LABEL + _UNIT + 10}}" + "".join(f"{c:>{_CELL}}" for c in ("Sum", "RSS", "exact"))]
        for i, name in enumerate(t.inputs):
            lines.append(f"{name:<{_LABEL + _UNIT + 10}}" + "".join(f"{v:>{_CELL}.4g}" for v in t.values[i]))
    return "\n".join(lines)


def text_report(run: SynthesisRun) -> str:
    parts = [appendix_table(run), beyond_table(run)]
    if run.monte_carlo is not None:
        parts.append(monte_carlo_table(run))
    if run.geometry_sensitivity is not None or run.tolerance_sensitivity is not None:
        parts.append(sensitivity_tables(run))
    return "\n\n".join(parts) + "\n"


def _pair(run: SynthesisRun, xy) -> list[float]:
    return [float(run.length(xy[0])), float(run.length(xy[1]))]


def _placed(run: SynthesisRun, placement: Placement) -> list[dict]:
    return [{"name": g.name, "role": g.role, "centre": _pair(run, g.centre), "rotation_rad": g.rotation}
            for g in placement.gears]


def synthesis_json(run: SynthesisRun) -> dict:
    """The contract's JSON (``../shared/contracts/synthesis.md``), with extra keys."""
    inp, s, L = run.inputs, run.synthesis, run.length
    gears = []
    for k, role in enumerate(GEAR_ROLES, start=1):
        m = inp.module_mesh1 if k <= 2 else inp.module_mesh2
        entry = {"name": role, "teeth": inp.teeth[k - 1], "pitch_diameter": L(2 * inp.reference_radius(k)),
                 "module_mm": m, "pressure_angle_deg": math.degrees(inp.pressure_angle(1 if k <= 2 else 2))}
        if run.length_unit == "in":
            entry["diametral_pitch_per_in"] = MM_PER_IN / m
        gears.append(entry)
    meshes = []
    for mesh, gear in ((1, "gear1"), (2, "gear3")):
        meshes.append({"centre_distance": L(inp.centre_distance(mesh)),
                       "ratio": s.ratio_mesh1 if mesh == 1 else s.ratio_mesh2,
                       "backlash_max": L(inp.backlash(mesh, "max")), "backlash_min": L(inp.backlash(mesh, "min")),
                       "angular_backlash_max_rad": s.angular_backlash(mesh, "max"),
                       "angular_backlash_min_rad": s.angular_backlash(mesh, "min"),
                       "angular_backlash_of": gear,
                       "backlash_kind": "circumferential, at the reference pitch circles: j_bt / cos(alpha_t)",
                       "standard_centre_distance": L(inp.standard_centre_distance(mesh))})
    out = {
        "schema": SCHEMA,
        "design": {"name": run.design_name, "sha256": run.design_sha256},
        "length_unit": run.length_unit,
        "gears": gears,
        "meshes": meshes,
        "rounding": inp.rounding,
        "nominal": {"A1_rad": s.nominal_A1, "A2_rad": s.nominal_A2, "N": s.nominal_teeth_count,
                    "increments": s.nominal_increments, "A1_deg": math.degrees(s.nominal_A1),
                    "A2_deg": math.degrees(s.nominal_A2)},
        "solved": {"N": int(s.teeth_count) if s.increments % 2 == 0 else s.teeth_count, "increments": s.increments,
                   "A1_rad": s.A1, "A2_rad": s.A2, "A1_deg": math.degrees(s.A1), "A2_deg": math.degrees(s.A2),
                   "eq7_residual_rad": s.eq7_residual,
                   "x1": L(s.x1), "y1": L(s.y1), "x2": L(s.x2), "y2": L(s.y2)},
        "min_backlash": {"A1_rad": s.min_backlash_A1, "A1_deg": math.degrees(s.min_backlash_A1),
                         "C1": L(s.min_backlash_C1), "x1": L(s.min_backlash_x1), "dx1": L(s.min_backlash_dx1)},
        "min_backlash_exact": {"C1": L(run.exact_min_backlash_C1), "x1": L(run.exact_min_backlash_x1),
                               "dx1": L(run.exact_min_backlash_x1 - s.x1)},
        "centres": {k: _pair(run, v) for k, v in s.centres.items()},
        "placement": {"state": "preloaded, maximum backlash", "phase_convention": PHASE_CONVENTION,
                      "gears": _placed(run, run.placement)},
    }
    if run.resolved is not None:
        out["resolved"] = run.resolved
    for mesh, b in zip(out["meshes"], run.modelled_backlash):
        mesh["backlash_of_modelled_gears"] = L(b)
    if run.placement_modelled is not None:
        out["placement_modelled_gears"] = {
            "state": "preloaded, backlash of the modelled gears", "phase_convention": PHASE_CONVENTION,
            "backlash": [L(run.placement_modelled.backlash_mesh1), L(run.placement_modelled.backlash_mesh2)],
            "gears": _placed(run, run.placement_modelled)}
    b = run.budget
    if b is not None:
        out["error_budget"] = {
            "total_error": [L(v) for v in b.total_tir], "dx1": [L(v) for v in b.dx1],
            "dx1_sum": L(b.dx1_sum), "dx1_rss": L(b.dx1_rss), "dx1_mean": L(b.dx1_mean),
            "dC1_sum": L(b.dC1_sum), "dC1_rss": L(b.dC1_rss), "dC1_mean": L(b.dC1_mean),
            "percent_of_sum": list(b.percent_of_sum), "percent_of_rss": list(b.percent_of_rss),
            "factors": list(b.factors), "dC1_per_dx1": b.centre_distance_factor,
            **{kind: [L(getattr(e, kind)) for e in run.errors] for kind in ERROR_KINDS},
        }
        if any(any(e.sources) for e in run.errors):  # rows an accuracy grade set: where each came from
            out["error_budget"]["sources"] = {kind: [e.sources[i] for e in run.errors]
                                              for i, kind in enumerate(ERROR_KINDS)}
    e = run.exact_budget
    if e is not None:
        out["exact_error_budget"] = {"success": e.success, "dx1_linear": [L(v) for v in e.dx1_linear],
                                     "dx1_resolved": [L(v) for v in e.dx1_resolved], "dx1_sum": L(e.dx1_sum),
                                     "dx1_rss": L(e.dx1_rss), "travel_resolved": L(e.travel_resolved)}
    mc = run.monte_carlo
    if mc is not None:
        entry = {"success": mc.success, "message": mc.message, "model": mc.model, "error_shape": mc.error_shape,
                 "samples": mc.samples, "seed": run.monte_carlo_settings.seed if run.monte_carlo_settings else None,
                 "travel_percentiles": {f"p{p:g}": L(v) for p, v in mc.percentiles.items()},
                 "travel_min": L(mc.minimum), "travel_max": L(mc.maximum), "travel_mean": L(mc.mean),
                 "travel_std": L(mc.std), "travel_bound_low": L(mc.bound_low), "travel_bound_high": L(mc.bound_high),
                 "travel_rss": L(mc.rss)}
        if mc.force is not None:
            entry.update({"spring_rate_N_per_mm": mc.spring_rate, "preload_N": mc.preload,
                          "force_percentiles_N": {f"p{p:g}": v for p, v in mc.force_percentiles.items()},
                          "force_min_N": float(mc.force.min()), "force_max_N": float(mc.force.max())})
        out["monte_carlo"] = entry
    sens = {}
    for key, t in (("geometry", run.geometry_sensitivity), ("tolerance", run.tolerance_sensitivity)):
        if t is not None:
            table = {}
            for i, name in enumerate(t.inputs):
                table[name] = {o: float(v * (run.scale if ou == "angle" else 1.0))
                               for o, v, ou in zip(t.outputs, t.values[i], t.output_units)}
            sens[key] = {"units": f"output per input, lengths in {run.length_unit}, angles in rad", "values": table}
    if sens:
        out["sensitivities"] = sens
    return out


def write_json(data: dict, target: str | Path) -> None:
    """Write ``data`` to the file ``target``, or to standard output when it is ``-``."""
    from geargen.outputs import write_text
    write_text(target, json.dumps(data, indent=2, allow_nan=False) + "\n", "--json")  # strict JSON: no NaN or Infinity


def histogram_png(run: SynthesisRun, path: str | Path, bins: int = 80) -> Path:
    """Histogram of the Monte Carlo carriage travel (and spring force), with percentiles, RSS and Sum."""
    mc = run.monte_carlo
    if mc is None or not mc.success:
        raise ValueError("no successful Monte Carlo result to plot")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    u = run.length_unit
    travel = run.length(mc.travel)
    panels = 2 if mc.force is not None else 1
    fig, axes = plt.subplots(1, panels, figsize=(6.5 * panels, 4.2), squeeze=False)
    ax = axes[0, 0]
    ax.hist(travel, bins=bins, color="#4a7ab5", density=True)
    lo, hi = run.length(mc.bound_low), run.length(mc.bound_high)
    centre = run.length(mc.percentiles[50.0])
    ax.axvspan(lo, hi, color="#cccccc", alpha=0.35, label=f"worst case (Sum) {hi - lo:.4g} {u}")
    rss = run.length(mc.rss)
    ax.axvline(centre - rss / 2, color="k", ls="--", lw=1, label=f"RSS {rss:.4g} {u} about the median")
    ax.axvline(centre + rss / 2, color="k", ls="--", lw=1)
    for p in (0.135, 99.865):
        ax.axvline(run.length(mc.percentiles[p]), color="#c0392b", lw=1)
    ax.plot([], [], color="#c0392b", label=f"central 99.73 %: {run.length(mc.spread_99_73):.4g} {u}")
    ax.set_xlabel(f"carriage travel from the synthesised position ({u}, + away from the output)")
    ax.set_ylabel("probability density")
    ax.set_title(f"{run.design_name}: {mc.samples:,} samples, {mc.model} model")
    ax.legend(fontsize=8)
    if mc.force is not None:
        ax2 = axes[0, 1]
        ax2.hist(mc.force, bins=bins, color="#6aa84f", density=True)
        for p in (0.135, 99.865):
            ax2.axvline(mc.force_percentiles[p], color="#c0392b", lw=1)
        ax2.set_xlabel(f"preload spring force (N), rate {mc.spring_rate:.4g} N/mm")
        ax2.set_ylabel("probability density")
    fig.tight_layout()
    return save_png(fig, path)


__all__ = ["SynthesisRun", "fixed", "appendix_sections", "appendix_table", "beyond_table", "monte_carlo_table", "sensitivity_tables",
           "text_report", "synthesis_json", "write_json", "histogram_png", "PHASE_CONVENTION", "SCHEMA"]
