"""Stiffness report: the text summary, the preload diagram (Fig. 6), the torque-deflection curve and
the loop-error preload band, as PNG.

Plots use matplotlib's object API on an Agg canvas (no pyplot, no global backend switch), and
matplotlib is imported only inside the plotting functions. Values come from
:class:`geargen.core.stiffness.StiffnessSummary` (internal units) and are shown in the design's
units (:attr:`StiffnessSummary.units`: lengths in its length unit, torques in its file's torque
unit) and µrad.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from geargen.core.stiffness import LOCATION_NAMES, StiffnessSummary, carriage_force
from geargen.report.figures import write_figure
from geargen.units import TextUnits

URAD = 1e6  # rad -> µrad


def _g(value: float, digits: int = 4) -> str:
    if value is None:
        return "-"
    if value == math.inf:
        return "inf"
    return f"{value:.{digits}g}"


# ----------------------------------------------------------------------------------------------
# Text

def _local_stiffness(c, u: TextUnits) -> str:
    """A component's stiffness where it acts: along a line at a radius, or on its shaft."""
    if c.radius is None:
        return u.text('torsional_stiffness', c.local, 5)
    return f"{u.text('linear_stiffness', c.local, 5)} at r={u.text('length', c.radius)}"


def _support_stiffness(sup, u: TextUnits) -> str:
    """A gear's support stiffness: N/µm where the text's linear stiffness is N/mm (tens of thousands of N/mm)."""
    if u.linear_stiffness == "N_per_mm":
        u = replace(u, linear_stiffness="N_per_um")
    return u.text("linear_stiffness", sup.force / sup.deflection)


def _travel(travel_mm: float | None, u: TextUnits) -> str:
    return "-" if travel_mm is None else f"{u.text('length', travel_mm, 5)}" + (
        f" ({travel_mm * 1e3:.4g} µm)" if u.length == "mm" else "")


def format_summary(s: StiffnessSummary, loop_error_note: str = "") -> str:
    """The printed stiffness summary: paths, drive, loop, preload, preload variation, hardware."""
    r = s.location_ratio
    where = LOCATION_NAMES[s.location]
    u = s.units
    tq, ks = u.unit('torque'), u.unit('torsional_stiffness')
    d = s.drive_at()
    lines = [f"{s.name}: {s.drive_type} drive, {s.preload_method or 'no'} preload; stiffness as {where}"
             + ("" if r == 1 else f" (ratio {r:.6g} to the output)"), ""]

    lines.append(f"Paths (components in series; {ks} as {where})")
    same = [c.name for c in s.path1.components] == [c.name for c in s.path2.components]
    for p in ((s.path1,) if same else (s.path1, s.path2)) + ((s.common,) if s.common.components else ()):
        title = "path 1 = path 2" if same and p is s.path1 else p.name
        if p is s.common:
            title = "common (in series with the drive)"
        lines.append(f"  {title:<44} {_g(u.value('torque', p.stiffness / r ** 2), 6):>12}")
        shares = p.compliance_shares()
        for c in p.components:
            local = _local_stiffness(c, u)
            lines.append(f"    {c.name:<30} {local:<32} {_g(u.value('torque', c.at_output / r ** 2), 6):>12}"
                         f"  {100 * shares[c.name]:5.1f} % of compliance")
    lines.append("")

    lines.append("Drive")
    eq = "Eq. 5" if s.drive_type == "type2" else "Eq. 2"
    lines.append(f"  k_D ({eq}, both paths loaded)          {u.text('torsional_stiffness', d.drive_stiffness, 6)}")
    if s.common.components:
        lines.append(f"  with the common parts in series          {u.text('torsional_stiffness', s.drive_stiffness_with_common / r ** 2, 6)}")
    t_lo, t_hi = d.unloading_torques
    r_lo, r_hi = d.unloading_rotations
    lines.append(f"  a path unloads at                        {_g(u.value('torque', t_lo))} / +{u.text('torque', t_hi)} "
                 f"({_g(r_lo * URAD)} / +{_g(r_hi * URAD)} µrad)")
    beyond = "the loaded path alone" if s.drive_type == "type1" else "the loaded path in series with k3"
    lines.append(f"  beyond it ({beyond})   {_g(u.value('torque', d.stiffness_beyond(-1)))} / {u.text('torsional_stiffness', d.stiffness_beyond(+1))}")
    lines.append("")

    lines.append("Loop")
    if s.preload_spring is not None:
        ps = s.preload_spring
        parts = ", ".join(f"{n} {u.text('linear_stiffness', k)}" for n, k in ps.linear_parts)
        parts += "".join(f", {n} {u.text('torsional_stiffness', k)}" for n, k in ps.torsional_parts)
        lines.append(f"  k3, preload spring                       {u.text('torsional_stiffness', d.k3, 5)}"
                     + (f" = {u.text('linear_stiffness', ps.linear_stiffness)} at the carriage ({parts})" if s.lever else f" ({parts})"))
        if s.lever:
            lines.append(f"  preload lever                            {_g(s.lever * 1e3 * u.value('length', 1.0) ** -1, 5)} mrad of output rotation of each path per {u.length} of carriage")
    eq = "Eq. 6" if s.drive_type == "type2" else "Eq. 3"
    lines.append(f"  k_L ({eq})                              {u.text('torsional_stiffness', d.loop_stiffness, 5)}")
    # Eq. 4 is the type 1 ratio; a type 2 drive's ratio is Eq. 5 over Eq. 6
    ratio_eq = "Eq. 4" if s.drive_type != "type2" else "Eq. 5 / Eq. 6"
    lines.append(f"  {'k_D / k_L (' + ratio_eq + ')':<41}{_g(d.stiffness_ratio, 5)}")
    lines.append("")

    lines.append("Preload (torque each path carries at zero drive torque, at the output)")
    lines.append(f"  maximum drive torque                     {u.text('torque', s.max_output_torque)}")
    rule = "half the maximum load" if s.drive_type == "type2" else "the maximum load"
    lines.append(f"  required (paper: {rule}) {u.text('torque', s.required_preload):>14};"
                 f" two-path model: {u.text('torque', s.preload_to_carry)}")
    ok = "meets the recommendation" if s.preload_ok else "BELOW the recommendation"
    lines.append(f"  set                                      {u.text('torque', s.drive.preload)} from {s.preload_source}: {ok}")
    if s.carriage_force is not None:
        lines.append(f"  carriage force                           {u.text('force', s.carriage_force)}")
    lines.append("")

    lines.append("Preload variation from loop errors (peak-to-peak)" + (f" [{loop_error_note}]" if loop_error_note else ""))
    if not s.variations:
        lines.append("  no loop error given")
    else:
        lines.append(f"  {'budget':<8} {'carriage travel':>22} {'loop error':>13} {'preload band':>22} {'change p-p':>11}"
                     f" {'carriage force':>15}")
        for v in s.variations:
            travel = "-" if v.carriage_travel is None else _travel(v.carriage_travel, u)
            force = "-" if s.lever is None else f"±{u.text('force', float(carriage_force(v.loop_range, s.lever)) / 2, 3)}"
            mark = " *" if v.label == s.headline_budget and len(s.variations) > 1 else ""
            lines.append(f"  {v.label + mark:<8} {travel:>22} {v.loop_error * URAD:>8.4g} µrad "
                         f"{u.value('torque', v.low):>9.4g} .. {u.value('torque', v.high):<7.4g} {tq} {100 * v.relative:>7.2f} % {force:>15}")
        friction = s.variations[0].friction_to_preload
        if friction:
            lines.append(f"  with the sliding fit's friction ({friction:.3g} of the spring force): the preload sticks "
                         f"anywhere in F / (1 ± {friction:.3g}); the loop error alone changes it "
                         + ", ".join(f"{100 * v.loop_range / v.preload:.2f} %" for v in s.variations) + " p-p")
    lines.append("")

    if s.flexure is not None:
        f = s.flexure
        lines.append(f"Blade flexures: {f.count} x {u.value('length', f.thickness):.4g} x {u.text('length', f.width)}, "
                     f"{u.text('length', f.length)} free")
        lines.append(f"  stiffness along the motion {u.text('linear_stiffness', f.stiffness_along)}, across {u.text('linear_stiffness', f.stiffness_lateral)} "
                     f"(in the blade plane), along the blades {u.text('linear_stiffness', f.stiffness_axial)}")
        lines.append(f"  stress at {u.text('length', f.travel)} travel: {u.text('stress', f.stress_at_travel)} of "
                     f"{u.text('stress', f.allowable_stress)} allowed (limit travel {u.text('length', f.travel_limit)}); "
                     f"parasitic drop {u.small_length(f.parasitic_shortening, 3)}")
        for label, b in (("shortest blades", s.flexure_design), ("at this gauge", s.flexure_design_gauge)):
            if b is not None:
                lines.append(f"  design helper, {label} for {u.text('linear_stiffness', b.stiffness)}: t = {u.text('length', b.thickness)}, "
                             f"L = {u.text('length', b.length)}, stress {u.text('stress', b.stress_at_travel)} ({b.message})")
        lines.append("")
    if s.spring is not None:
        sp = s.spring
        lines.append(f"Compression springs: {s.spring_count} x d {u.text('length', sp.wire_diameter)}, "
                     f"D {u.text('length', sp.mean_coil_diameter)}, {sp.active_coils:g} active coils, {sp.end_type}")
        lines.append(f"  rate {u.text('linear_stiffness', sp.rate)} each, index {sp.index:.3g}, Wahl {sp.wahl_factor:.4f}, "
                     f"solid height {u.text('length', sp.solid_height)}")
        if sp.installed_length is not None:
            lines.append(f"  installed at {u.text('length', sp.installed_length)}: {u.text('force', sp.installed_force)}, "
                         f"{u.text('stress', sp.installed_stress)}; at solid {u.text('stress', sp.solid_stress)} "
                         f"(allowed {u.text('stress', sp.allowable_shear_stress)})")
        if s.spring_installed_length_for_preload is not None:
            lines.append(f"  installed length for this preload: {u.text('length', s.spring_installed_length_for_preload)}")
        lines.append("")
    if s.beam is not None:
        b = s.beam
        lines.append(f"Beam-spring pinion: span {u.text('length', b.span)}, mesh at {u.text('length', b.mesh_position)}, "
                     f"zero slope at {u.text('length', b.zero_slope_position)}, section d {u.text('length', b.diameter)}")
        lines.append(f"  stiffness at the mesh {u.text('linear_stiffness', b.stiffness)}; at {u.text('force', b.force)}: deflection {u.small_length(b.deflection)}, "
                     f"slope {b.slope_at_mesh * URAD:.3g} µrad, stress {u.text('stress', b.max_stress)}")
        if s.beam_supports is not None:
            lines.append(f"  its bearings on the drive column: {u.text('linear_stiffness', s.beam_supports[0])} (lower), "
                         f"{u.text('linear_stiffness', s.beam_supports[1])} (upper); in series: "
                         f"{u.text('linear_stiffness', dict(s.preload_spring.linear_parts)['beam pinion on its column'])} at the mesh")
        lines.append("")
    if s.engagement is not None:
        e = s.engagement
        lines.append(f"Helical engagement: lead {u.text('length', e.lead)} turns the pinions "
                     f"{e.relative_rotation * 1e3:.4g} mrad apart (backlash {u.small_length(e.backlash)} + preload windup "
                     f"{u.small_length(e.preload_windup)} at the reference circle)")
        lines.append(f"  stops: leader {u.value('length', e.leader_retracted_stop):.4g} .. {u.text('length', e.leader_engaged_stop)}, "
                     f"trailer {u.value('length', e.trailer_retracted_stop):.4g} .. {u.text('length', e.trailer_engaged_stop)}")
        lines.append("")
    if s.supports:
        lines.append("Gears on their placed shafts and bearings, under the preload's mesh force")
        for sup in s.supports:
            lines.append(f"  {sup.gear:<22} {u.text('force', sup.force)}: deflects {u.small_length(sup.deflection)} "
                         f"({_support_stiffness(sup, u)}), tilts {sup.tilt * 1e6:.4g} µrad = "
                         f"{u.small_length(sup.misalignment, 3)} across its {u.text('length', sup.face_width)} face")
        lines.append("")
    if s.warnings:
        lines.append("Warnings")
        lines += [f"  - {w}" for w in s.warnings]
    else:
        lines.append("No warnings.")
    return "\n".join(lines)


def summary_tables(s: StiffnessSummary) -> list[tuple[str, list[str] | None, list[list[str]]]]:
    """The numbers of :func:`format_summary` as report tables: ``(title, header, rows)``; a
    section without a ``header`` is a list of its lines (the hardware sections and the warnings,
    taken from :func:`format_summary` itself so no number is formatted twice)."""
    r = s.location_ratio
    where = LOCATION_NAMES[s.location]
    u = s.units
    tq, ks = u.unit('torque'), u.unit('torsional_stiffness')
    d = s.drive_at()
    out = []
    rows = []
    same = [c.name for c in s.path1.components] == [c.name for c in s.path2.components]
    for p in ((s.path1,) if same else (s.path1, s.path2)) + ((s.common,) if s.common.components else ()):
        title = "path 1 = path 2" if same and p is s.path1 else p.name
        if p is s.common:
            title = "common (in series with the drive)"
        rows.append([title, "", _g(u.value('torque', p.stiffness / r ** 2), 6), ""])
        shares = p.compliance_shares()
        for c in p.components:
            local = _local_stiffness(c, u)
            rows.append([c.name, local, _g(u.value('torque', c.at_output / r ** 2), 6), f"{100 * shares[c.name]:.1f} %"])
    out.append((f"Paths (components in series; {ks} as {where}"
                + ("" if r == 1 else f", ratio {r:.6g} to the output") + ")",
                ["component", "local stiffness", ks, "share of compliance"], rows))
    eq = "Eq. 5" if s.drive_type == "type2" else "Eq. 2"
    t_lo, t_hi = d.unloading_torques
    r_lo, r_hi = d.unloading_rotations
    beyond = "the loaded path alone" if s.drive_type == "type1" else "the loaded path in series with k3"
    rows = [[f"k_D ({eq}, both paths loaded)", f"{u.text('torsional_stiffness', d.drive_stiffness, 6)}"]]
    if s.common.components:
        rows.append(["with the common parts in series",
                     f"{u.text('torsional_stiffness', s.drive_stiffness_with_common / r ** 2, 6)}"])
    rows += [["a path unloads at",
              f"{_g(u.value('torque', t_lo))} / +{u.text('torque', t_hi)} ({_g(r_lo * URAD)} / +{_g(r_hi * URAD)} µrad)"],
             [f"beyond it ({beyond})",
              f"{_g(u.value('torque', d.stiffness_beyond(-1)))} / {u.text('torsional_stiffness', d.stiffness_beyond(+1))}"]]
    out.append((f"Drive ({s.drive_type}, {s.preload_method or 'no'} preload)", ["quantity", "value"], rows))
    rows = []
    if s.preload_spring is not None:
        ps = s.preload_spring
        parts = ", ".join(f"{n} {u.text('linear_stiffness', k)}" for n, k in ps.linear_parts)
        parts += "".join(f", {n} {u.text('torsional_stiffness', k)}" for n, k in ps.torsional_parts)
        rows.append(["k3, preload spring", f"{u.text('torsional_stiffness', d.k3, 5)}"
                     + (f" = {u.text('linear_stiffness', ps.linear_stiffness)} at the carriage ({parts})" if s.lever else f" ({parts})")])
        if s.lever:
            rows.append(["preload lever",
                         f"{_g(s.lever * 1e3 * u.value('length', 1.0) ** -1, 5)} mrad of output rotation of each path per {u.length} of carriage"])
    eq = "Eq. 6" if s.drive_type == "type2" else "Eq. 3"
    ratio_eq = "Eq. 4" if s.drive_type != "type2" else "Eq. 5 / Eq. 6"
    rows += [[f"k_L ({eq})", f"{u.text('torsional_stiffness', d.loop_stiffness, 5)}"],
             [f"k_D / k_L ({ratio_eq})", _g(d.stiffness_ratio, 5)]]
    out.append(("Loop", ["quantity", "value"], rows))
    rule = "half the maximum load" if s.drive_type == "type2" else "the maximum load"
    ok = "meets the recommendation" if s.preload_ok else "BELOW the recommendation"
    rows = [["maximum drive torque", f"{u.text('torque', s.max_output_torque)}"],
            [f"required (paper: {rule})", f"{u.text('torque', s.required_preload)}"],
            ["required (two-path model)", f"{u.text('torque', s.preload_to_carry)}"],
            ["set", f"{u.text('torque', s.drive.preload)} from {s.preload_source}: {ok}"]]
    if s.carriage_force is not None:
        rows.append(["carriage force", f"{u.text('force', s.carriage_force)}"])
    out.append(("Preload (torque each path carries at zero drive torque, at the output)", ["quantity", "value"], rows))
    if s.variations:
        rows = []
        for v in s.variations:
            travel = "-" if v.carriage_travel is None else \
                _travel(v.carriage_travel, u)
            force = "-" if s.lever is None else f"±{u.text('force', float(carriage_force(v.loop_range, s.lever)) / 2, 3)}"
            mark = " (headline)" if v.label == s.headline_budget and len(s.variations) > 1 else ""
            rows.append([v.label + mark, travel, f"{v.loop_error * URAD:.4g}", f"{u.value('torque', v.low):.4g} .. {u.value('torque', v.high):.4g}",
                         f"{100 * v.relative:.2f} %", force])
        out.append(("Preload variation from loop errors (peak-to-peak)",
                    ["budget", "carriage travel", "loop error (µrad)", f"preload band ({tq})", "change p-p",
                     "carriage force"], rows))
    else:
        out.append(("Preload variation from loop errors (peak-to-peak)", None, [["no loop error given"]]))
    # the hardware sections and the warnings: the text summary's own paragraphs after the variation's
    paragraphs = format_summary(s).split("\n\n")
    start = next(i for i, par in enumerate(paragraphs) if par.startswith("Preload variation")) + 1
    for par in paragraphs[start:]:
        lines = [ln.strip().removeprefix("- ") for ln in par.splitlines() if ln.strip()]
        if not lines:
            continue
        if lines[0] == "Warnings" or lines[0] == "No warnings.":
            out.append(("Warnings", None, [[ln] for ln in lines[1:]] or [["none"]]))
        else:
            title = lines[0].split(":")[0]
            out.append((title, None, [[ln] for ln in (lines[1:] if title == lines[0] else lines)]))
    return out


# ----------------------------------------------------------------------------------------------
# Plots

def _figure(width: float = 7.5, height: float = 5.0):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height), dpi=110)
    FigureCanvasAgg(fig)
    return fig


def _span(s: StiffnessSummary) -> float:
    """Half-width (rad, output) of the drive-rotation window the plots show."""
    d = s.drive
    r_max = max(abs(float(d.rotation(s.max_output_torque))), abs(float(d.rotation(-s.max_output_torque))))
    first_unloading = min(abs(x) for x in d.unloading_rotations)
    return 1.4 * max(r_max, first_unloading, 1e-12)


def _torque_units(s: StiffnessSummary) -> tuple[float, str, str]:
    """The plots' torque scale (N·mm -> the text's torque unit) and the torque and torsional-stiffness unit texts."""
    return s.units.value("torque", 1.0), s.units.unit("torque"), s.units.unit("torsional_stiffness")


def _travel_axis(travel_mm, u: TextUnits):
    """A carriage travel (mm) on a plot's axis: µm in a mm design, the design's unit otherwise."""
    if u.length == "mm":
        return travel_mm * 1e3, "carriage travel from nominal (µm)"
    return u.value("length", travel_mm), f"carriage travel from nominal ({u.length})"


def preload_diagram_figure(s: StiffnessSummary):
    """Fig. 6: both paths' force against drive displacement, preload point, drive load, backlash.

    Path 2 is mirrored (its force is drawn positive), so the lines cross at the preload point
    (zero drive displacement and torque); the vertical distance between them is the drive torque.
    Slopes are the rates at which each path's force changes with drive displacement (``k1``,
    ``k2`` for type 1; Fig. 7a's coupled rates for type 2). Where a path unloads it runs into its
    backlash ``b``; drive torques are referred to the output.
    """
    T, tq, ks = _torque_units(s)
    d = s.drive
    half = _span(s)
    b = s.path_backlash
    x = np.linspace(-half, half, 801)
    f1, f2 = d.path_torques(x)
    g1, g2 = d.path_force_rates
    x1_0, x2_0 = d.unloading_rotations  # where path 1 / path 2 reach zero force
    fig = _figure()
    ax = fig.add_subplot(1, 1, 1)
    ax.plot(x * URAD, f1 * T, color="tab:blue", lw=2, label=f"path 1 (rate {_g(g1 * T)} {ks})", gid="path1")
    ax.plot(x * URAD, -f2 * T, color="tab:orange", lw=2, label=f"path 2, mirrored (rate {_g(g2 * T)} {ks})",
            gid="path2")
    # each path's unloaded side: zero force across its backlash, then the other flank
    for x0, g, sign, colour in ((x1_0, g1, -1, "tab:blue"), (x2_0, g2, +1, "tab:orange")):
        if b is None or abs(x0) >= half:  # no backlash, or this path does not unload in the window
            continue
        far = x0 + sign * b
        if abs(far) <= half:
            ax.annotate("", xy=(far * URAD, 0), xytext=(x0 * URAD, 0),
                        arrowprops=dict(arrowstyle="<->", color=colour, lw=1))
            ax.text((x0 + far) / 2 * URAD, 0.04 * d.preload * T, "b", color=colour, ha="center")
            xs = np.linspace(far, sign * half, 50)
            # the opposite flank: the path's force reverses (drawn negative), not part of the drive model
            ax.plot(xs * URAD, -np.abs(xs - far) * g * T, color=colour, lw=1, ls="--")
        else:
            ax.text(sign * 0.98 * half * URAD, 0.04 * d.preload * T, f"backlash b = {b * URAD:.4g} µrad\ncontinues",
                    color=colour, fontsize=8, ha="right" if sign > 0 else "left", va="bottom")
    ax.plot([0], [d.preload * T], "ko")
    ax.annotate(f"preload F_L = {d.preload * T:.3g} {tq}\n(zero drive torque)", xy=(0, d.preload * T),
                xytext=(-0.95 * half * URAD, d.preload * T * 0.45), fontsize=9,
                arrowprops=dict(arrowstyle="->", lw=0.8))
    # the drive load: a vertical line between the two path lines at the maximum drive torque
    t = s.max_output_torque
    xd = float(d.rotation(t))
    fa, fb = d.path_torques(xd)
    ax.vlines(xd * URAD, -fb * T, fa * T, colors="k", lw=2.5, gid="drive_load")
    ax.text(xd * URAD, (fa - fb) / 2 * T, f"  drive load F_D = {t * T:.3g} {tq}", fontsize=9, va="center")
    ax.axhline(0, color="0.5", lw=0.8)
    ax.axvline(0, color="0.5", lw=0.8)
    ax.set_xlim(-half * URAD, half * URAD)
    ax.set_xlabel("drive displacement δ_D at the output (µrad)")
    ax.set_ylabel("path force (torque at the output, {tq})")
    ax.set_title(f"{s.name}: preload diagram ({s.drive_type})")
    ax.legend(loc="upper center", fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    return fig


def plot_preload_diagram(s: StiffnessSummary, path: str | Path) -> Path:
    """Write :func:`preload_diagram_figure` as PNG."""
    return write_figure(preload_diagram_figure(s), path)


def torque_deflection_figure(s: StiffnessSummary):
    """Drive torque against drive rotation at the output: the piecewise law with its unloading
    points, the path torques, and the curve with the common parts in series. Left: the preload
    region; right: the whole range up to beyond the maximum drive torque."""
    T, tq, ks = _torque_units(s)
    d = s.drive
    t_lo, t_hi = d.unloading_torques
    r_lo, r_hi = d.unloading_rotations
    t_span = 1.35 * max(s.max_output_torque, abs(t_lo), abs(t_hi))
    fig = _figure(12.0, 5.0)
    eq = "Eq. 5" if s.drive_type == "type2" else "Eq. 2"
    zoom = 2.0 * max(abs(r_lo), abs(r_hi), abs(float(d.rotation(s.max_output_torque))), 1e-12)
    for i, (title, rot) in enumerate((("preload region", np.linspace(-zoom, zoom, 801)),
                                      ("whole range", d.rotation(np.linspace(-t_span, t_span, 801))))):
        ax = fig.add_subplot(1, 2, i + 1)
        torque = d.torque(rot)
        f1, f2 = d.path_torques(rot)
        ax.plot(rot * URAD, torque * T, color="k", lw=2.2, label="drive (two paths)", gid="drive")
        if s.common.components:
            ax.plot((rot + torque / s.common.stiffness) * URAD, torque * T, color="0.45", lw=1.4, ls=":",
                    label="with common parts in series")
        ax.plot(rot * URAD, f1 * T, color="tab:blue", lw=1, label="path 1 torque")
        ax.plot(rot * URAD, f2 * T, color="tab:orange", lw=1, label="path 2 torque")
        ax.plot([r_lo * URAD, r_hi * URAD], [t_lo * T, t_hi * T], "o", color="tab:red",
                label=f"a path unloads ({_g(t_lo * T)} / +{_g(t_hi * T)} {tq})")
        for sign in (-1, 1):
            ax.axhline(sign * s.max_output_torque * T, color="tab:green", lw=0.8, ls="--")
        ax.text(rot.min() * URAD, s.max_output_torque * T, " max drive torque", color="tab:green",
                va="bottom", fontsize=8)
        ax.axhline(0, color="0.5", lw=0.8)
        ax.axvline(0, color="0.5", lw=0.8)
        ax.set_xlabel("drive rotation at the output (µrad)")
        ax.set_ylabel(f"torque at the output ({tq})")
        ax.set_title(f"{s.name}: torque-deflection, {title}", fontsize=10)
        ax.grid(True, alpha=0.3)
        if i == 0:
            ax.text(0.02, 0.97, f"k_D = {_g(d.drive_stiffness * T)} {ks} ({eq})\n"
                    f"beyond: {_g(d.stiffness_beyond(-1) * T)} / {_g(d.stiffness_beyond(1) * T)} {ks}",
                    transform=ax.transAxes, va="top", fontsize=9)
            ax.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    return fig


def plot_torque_deflection(s: StiffnessSummary, path: str | Path) -> Path:
    """Write :func:`torque_deflection_figure` as PNG."""
    return write_figure(torque_deflection_figure(s), path)


def preload_band_figure(s: StiffnessSummary):
    """Preload against loop error, with the band each loop-error budget spans.

    The x axis is the carriage travel from nominal (µm) when the loop error is a carriage
    travel, else the loop error as output rotation (µrad). Returns None without a loop error.
    """
    T, tq, ks = _torque_units(s)
    if not s.variations:
        return None
    d = s.drive
    kl = d.loop_stiffness
    carriage = s.lever is not None and all(v.carriage_travel is not None for v in s.variations)
    widest = max(s.variations, key=lambda v: v.loop_error)
    if carriage:
        x_half = widest.carriage_travel / 2 * 1.25
        x = np.linspace(-x_half, x_half, 201)
        preload = d.preload + kl * 2 * s.lever * x
        xs, xlabel = _travel_axis(x, s.units)
    else:
        x_half = widest.loop_error / 2 * 1.25
        x = np.linspace(-x_half, x_half, 201)
        preload = d.preload + kl * x
        xs, xlabel = x * URAD, "loop error at the output (µrad)"
    fig = _figure()
    ax = fig.add_subplot(1, 1, 1)
    ax.plot(xs, preload * T, color="k", lw=2, label=f"preload, k_L = {_g(kl * T)} {ks}", gid="preload")
    colours = ["tab:red", "tab:blue", "tab:green", "tab:purple", "tab:brown"]
    for i, v in enumerate(sorted(s.variations, key=lambda v: -v.loop_error)):
        c = colours[i % len(colours)]
        half = _travel_axis(v.carriage_travel / 2, s.units)[0] if carriage else v.loop_error / 2 * URAD
        ax.axhspan(v.low * T, v.high * T, color=c, alpha=0.15)
        ax.axvspan(-half, half, color=c, alpha=0.06)
        ax.plot([-half, half], [v.low * T, v.high * T], "s", color=c, gid=f"band_{v.label}",
                label=f"{v.label} ({v.source}): {v.low * T:.3g}..{v.high * T:.3g} {tq}, ±{50 * v.relative:.2g} %")
    ax.axhline(s.required_preload * T, color="tab:red", ls="--", lw=1, label=f"required {s.required_preload * T:.3g} {tq}")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"loop preload at the output ({tq})")
    lo = min(s.required_preload, min(v.low for v in s.variations))
    hi = max(v.high for v in s.variations)
    ax.set_ylim(0.9 * lo * T, 1.05 * hi * T + 1e-12)
    if s.lever is not None:
        F = s.units.value("force", 1.0)  # N -> the text's force unit
        sec = ax.secondary_yaxis("right", functions=(lambda p: p / T * 2 * s.lever * F,
                                                     lambda f: f / F / (2 * s.lever) * T))
        sec.set_ylabel(f"carriage force ({s.units.unit('force')})")
    ax.set_title(f"{s.name}: preload variation from loop errors")
    ax.legend(loc="lower right", fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    return fig


def plot_preload_band(s: StiffnessSummary, path: str | Path) -> Path | None:
    """Write :func:`preload_band_figure` as PNG; None (nothing written) without a loop error."""
    fig = preload_band_figure(s)
    if fig is None:
        return None
    return write_figure(fig, path)


def write_stiffness_plots(s: StiffnessSummary, out_dir: str | Path) -> dict[str, Path]:
    """Write the three PNGs into ``out_dir`` (created); returns {kind: path} of those written."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = {"preload_diagram": plot_preload_diagram(s, out / f"{s.name}_preload_diagram.png"),
               "torque_deflection": plot_torque_deflection(s, out / f"{s.name}_torque_deflection.png")}
    band = plot_preload_band(s, out / f"{s.name}_preload_band.png")
    if band is not None:
        written["preload_band"] = band
    return written


__all__ = ["format_summary", "summary_tables", "preload_diagram_figure", "torque_deflection_figure", "preload_band_figure",
           "plot_preload_diagram", "plot_torque_deflection", "plot_preload_band",
           "write_stiffness_plots"]
