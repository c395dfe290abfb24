"""Stiffness report: the text summary, the preload diagram (Fig. 6), the torque-deflection curve and
the loop-error preload band, as PNG.

Plots use matplotlib's object API on an Agg canvas (no pyplot, no global backend switch), and
matplotlib is imported only inside the plotting functions. Values come from
:class:`geargen.core.stiffness.StiffnessSummary` (internal units) and are shown in N·m, µrad,
N/mm and the design's length unit.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from geargen.core.stiffness import LOCATION_NAMES, StiffnessSummary, carriage_force
from geargen.units import LENGTH_SUFFIXES

NM = 1e-3  # N·mm -> N·m
URAD = 1e6  # rad -> µrad


def _g(value: float, digits: int = 4) -> str:
    if value is None:
        return "-"
    if value == math.inf:
        return "inf"
    return f"{value:.{digits}g}"


# ----------------------------------------------------------------------------------------------
# Text

def format_summary(s: StiffnessSummary, loop_error_note: str = "") -> str:
    """The printed stiffness summary: paths, drive, loop, preload, preload variation, hardware."""
    r = s.location_ratio
    where = LOCATION_NAMES[s.location]
    unit = s.length_unit
    per_unit = LENGTH_SUFFIXES[unit]
    d = s.drive_at()
    lines = [f"{s.name}: {s.drive_type} drive, {s.preload_method or 'no'} preload; stiffness as {where}"
             + ("" if r == 1 else f" (ratio {r:.6g} to the output)"), ""]

    lines.append(f"Paths (components in series; N·m/rad as {where})")
    same = [c.name for c in s.path1.components] == [c.name for c in s.path2.components]
    for p in ((s.path1,) if same else (s.path1, s.path2)) + ((s.common,) if s.common.components else ()):
        title = "path 1 = path 2" if same and p is s.path1 else p.name
        if p is s.common:
            title = "common (in series with the drive)"
        lines.append(f"  {title:<44} {_g(p.stiffness * NM / r ** 2, 6):>12}")
        shares = p.compliance_shares()
        for c in p.components:
            local = f"{_g(c.local, 5)} {c.local_unit}" + (f" at r={c.radius:.4g} mm" if c.radius else "")
            lines.append(f"    {c.name:<30} {local:<32} {_g(c.at_output * NM / r ** 2, 6):>12}"
                         f"  {100 * shares[c.name]:5.1f} % of compliance")
    lines.append("")

    lines.append("Drive")
    eq = "Eq. 5" if s.drive_type == "type2" else "Eq. 2"
    lines.append(f"  k_D ({eq}, both paths loaded)          {_g(d.drive_stiffness * NM, 6)} N·m/rad")
    if s.common.components:
        lines.append(f"  with the common parts in series          {_g(s.drive_stiffness_with_common * NM / r ** 2, 6)} N·m/rad")
    t_lo, t_hi = d.unloading_torques
    r_lo, r_hi = d.unloading_rotations
    lines.append(f"  a path unloads at                        {_g(t_lo * NM)} / +{_g(t_hi * NM)} N·m "
                 f"({_g(r_lo * URAD)} / +{_g(r_hi * URAD)} µrad)")
    beyond = "the loaded path alone" if s.drive_type == "type1" else "the loaded path in series with k3"
    lines.append(f"  beyond it ({beyond})   {_g(d.stiffness_beyond(-1) * NM)} / {_g(d.stiffness_beyond(+1) * NM)} N·m/rad")
    lines.append("")

    lines.append("Loop")
    if s.preload_spring is not None:
        ps = s.preload_spring
        parts = ", ".join(f"{n} {_g(k)} N/mm" for n, k in ps.linear_parts)
        parts += "".join(f", {n} {_g(k * NM)} N·m/rad" for n, k in ps.torsional_parts)
        lines.append(f"  k3, preload spring                       {_g(d.k3 * NM, 5)} N·m/rad"
                     + (f" = {_g(ps.linear_stiffness)} N/mm at the carriage ({parts})" if s.lever else f" ({parts})"))
        if s.lever:
            lines.append(f"  preload lever                            {_g(s.lever * 1e3, 5)} mrad of output rotation of each path per mm of carriage")
    eq = "Eq. 6" if s.drive_type == "type2" else "Eq. 3"
    lines.append(f"  k_L ({eq})                              {_g(d.loop_stiffness * NM, 5)} N·m/rad")
    # Eq. 4 is the type 1 ratio; a type 2 drive's ratio is Eq. 5 over Eq. 6
    ratio_eq = "Eq. 4" if s.drive_type != "type2" else "Eq. 5 / Eq. 6"
    lines.append(f"  {'k_D / k_L (' + ratio_eq + ')':<41}{_g(d.stiffness_ratio, 5)}")
    lines.append("")

    lines.append("Preload (torque each path carries at zero drive torque, at the output)")
    lines.append(f"  maximum drive torque                     {_g(s.max_output_torque * NM)} N·m")
    rule = "half the maximum load" if s.drive_type == "type2" else "the maximum load"
    lines.append(f"  required (paper: {rule}) {_g(s.required_preload * NM):>10} N·m;"
                 f" two-path model: {_g(s.preload_to_carry * NM)} N·m")
    ok = "meets the recommendation" if s.preload_ok else "BELOW the recommendation"
    lines.append(f"  set                                      {_g(s.drive.preload * NM)} N·m from {s.preload_source}: {ok}")
    if s.carriage_force is not None:
        lines.append(f"  carriage force                           {_g(s.carriage_force)} N")
    lines.append("")

    lines.append("Preload variation from loop errors (peak-to-peak)" + (f" [{loop_error_note}]" if loop_error_note else ""))
    if not s.variations:
        lines.append("  no loop error given")
    else:
        lines.append(f"  {'budget':<8} {'carriage travel':>22} {'loop error':>13} {'preload band':>22} {'change p-p':>11}"
                     f" {'carriage force':>15}")
        for v in s.variations:
            travel = "-" if v.carriage_travel is None else f"{v.carriage_travel / per_unit:.5g} {unit} ({v.carriage_travel * 1e3:.4g} µm)"
            force = "-" if s.lever is None else f"±{float(carriage_force(v.loop_range, s.lever)) / 2:.3g} N"
            mark = " *" if v.label == s.headline_budget and len(s.variations) > 1 else ""
            lines.append(f"  {v.label + mark:<8} {travel:>22} {v.loop_error * URAD:>8.4g} µrad "
                         f"{v.low * NM:>9.4g} .. {v.high * NM:<7.4g} N·m {100 * v.relative:>7.2f} % {force:>15}")
        friction = s.variations[0].friction_to_preload
        if friction:
            lines.append(f"  with the sliding fit's friction ({friction:.3g} of the spring force): the preload sticks "
                         f"anywhere in F / (1 ± {friction:.3g}); the loop error alone changes it "
                         + ", ".join(f"{100 * v.loop_range / v.preload:.2f} %" for v in s.variations) + " p-p")
    lines.append("")

    if s.flexure is not None:
        f = s.flexure
        lines.append(f"Blade flexures: {f.count} x {f.thickness / per_unit:.4g} x {f.width / per_unit:.4g} {unit}, "
                     f"{f.length / per_unit:.4g} {unit} free")
        lines.append(f"  stiffness along the motion {_g(f.stiffness_along)} N/mm, across {_g(f.stiffness_lateral)} N/mm "
                     f"(in the blade plane), along the blades {_g(f.stiffness_axial)} N/mm")
        lines.append(f"  stress at {f.travel / per_unit:.4g} {unit} travel: {_g(f.stress_at_travel)} MPa of "
                     f"{_g(f.allowable_stress)} allowed (limit travel {f.travel_limit / per_unit:.4g} {unit}); "
                     f"parasitic drop {f.parasitic_shortening * 1e3:.3g} µm")
        for label, b in (("shortest blades", s.flexure_design), ("at this gauge", s.flexure_design_gauge)):
            if b is not None:
                lines.append(f"  design helper, {label} for {_g(b.stiffness)} N/mm: t = {b.thickness / per_unit:.4g} {unit}, "
                             f"L = {b.length / per_unit:.4g} {unit}, stress {_g(b.stress_at_travel)} MPa ({b.message})")
        lines.append("")
    if s.spring is not None:
        sp = s.spring
        lines.append(f"Compression springs: {s.spring_count} x d {sp.wire_diameter / per_unit:.4g} {unit}, "
                     f"D {sp.mean_coil_diameter / per_unit:.4g} {unit}, {sp.active_coils:g} active coils, {sp.end_type}")
        lines.append(f"  rate {_g(sp.rate)} N/mm each, index {sp.index:.3g}, Wahl {sp.wahl_factor:.4f}, "
                     f"solid height {sp.solid_height / per_unit:.4g} {unit}")
        if sp.installed_length is not None:
            lines.append(f"  installed at {sp.installed_length / per_unit:.4g} {unit}: {_g(sp.installed_force)} N, "
                         f"{_g(sp.installed_stress)} MPa; at solid {_g(sp.solid_stress)} MPa "
                         f"(allowed {_g(sp.allowable_shear_stress)} MPa)")
        if s.spring_installed_length_for_preload is not None:
            lines.append(f"  installed length for this preload: {s.spring_installed_length_for_preload / per_unit:.4g} {unit}")
        lines.append("")
    if s.beam is not None:
        b = s.beam
        lines.append(f"Beam-spring pinion: span {b.span / per_unit:.4g} {unit}, mesh at {b.mesh_position / per_unit:.4g} {unit}, "
                     f"zero slope at {b.zero_slope_position / per_unit:.4g} {unit}, section d {b.diameter / per_unit:.4g} {unit}")
        lines.append(f"  stiffness at the mesh {_g(b.stiffness)} N/mm; at {_g(b.force)} N: deflection {b.deflection * 1e3:.4g} µm, "
                     f"slope {b.slope_at_mesh * URAD:.3g} µrad, stress {_g(b.max_stress)} MPa")
        if s.beam_supports is not None:
            lines.append(f"  its bearings on the drive column: {_g(s.beam_supports[0])} N/mm (lower), "
                         f"{_g(s.beam_supports[1])} N/mm (upper); in series: "
                         f"{_g(dict(s.preload_spring.linear_parts)['beam pinion on its column'])} N/mm at the mesh")
        lines.append("")
    if s.engagement is not None:
        e = s.engagement
        lines.append(f"Helical engagement: lead {e.lead / per_unit:.4g} {unit} turns the pinions "
                     f"{e.relative_rotation * 1e3:.4g} mrad apart (backlash {e.backlash * 1e3:.4g} µm + preload windup "
                     f"{e.preload_windup * 1e3:.4g} µm at the reference circle)")
        lines.append(f"  stops: leader {e.leader_retracted_stop / per_unit:.4g} .. {e.leader_engaged_stop:.4g} {unit}, "
                     f"trailer {e.trailer_retracted_stop / per_unit:.4g} .. {e.trailer_engaged_stop:.4g} {unit}")
        lines.append("")
    if s.supports:
        lines.append("Gears on their placed shafts and bearings, under the preload's mesh force")
        for sup in s.supports:
            lines.append(f"  {sup.gear:<22} {sup.force:.4g} N: deflects {sup.deflection * 1e3:.4g} µm "
                         f"({sup.force / sup.deflection * 1e-3:.4g} N/µm), tilts {sup.tilt * 1e6:.4g} µrad = "
                         f"{sup.misalignment * 1e3:.3g} µm across its {sup.face_width:.4g} mm face")
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
    unit = s.length_unit
    per_unit = LENGTH_SUFFIXES[unit]
    d = s.drive_at()
    out = []
    rows = []
    same = [c.name for c in s.path1.components] == [c.name for c in s.path2.components]
    for p in ((s.path1,) if same else (s.path1, s.path2)) + ((s.common,) if s.common.components else ()):
        title = "path 1 = path 2" if same and p is s.path1 else p.name
        if p is s.common:
            title = "common (in series with the drive)"
        rows.append([title, "", _g(p.stiffness * NM / r ** 2, 6), ""])
        shares = p.compliance_shares()
        for c in p.components:
            local = f"{_g(c.local, 5)} {c.local_unit}" + (f" at r={c.radius:.4g} mm" if c.radius else "")
            rows.append([c.name, local, _g(c.at_output * NM / r ** 2, 6), f"{100 * shares[c.name]:.1f} %"])
    out.append((f"Paths (components in series; N·m/rad as {where}"
                + ("" if r == 1 else f", ratio {r:.6g} to the output") + ")",
                ["component", "local stiffness", "N·m/rad", "share of compliance"], rows))
    eq = "Eq. 5" if s.drive_type == "type2" else "Eq. 2"
    t_lo, t_hi = d.unloading_torques
    r_lo, r_hi = d.unloading_rotations
    beyond = "the loaded path alone" if s.drive_type == "type1" else "the loaded path in series with k3"
    rows = [[f"k_D ({eq}, both paths loaded)", f"{_g(d.drive_stiffness * NM, 6)} N·m/rad"]]
    if s.common.components:
        rows.append(["with the common parts in series",
                     f"{_g(s.drive_stiffness_with_common * NM / r ** 2, 6)} N·m/rad"])
    rows += [["a path unloads at",
              f"{_g(t_lo * NM)} / +{_g(t_hi * NM)} N·m ({_g(r_lo * URAD)} / +{_g(r_hi * URAD)} µrad)"],
             [f"beyond it ({beyond})",
              f"{_g(d.stiffness_beyond(-1) * NM)} / {_g(d.stiffness_beyond(+1) * NM)} N·m/rad"]]
    out.append((f"Drive ({s.drive_type}, {s.preload_method or 'no'} preload)", ["quantity", "value"], rows))
    rows = []
    if s.preload_spring is not None:
        ps = s.preload_spring
        parts = ", ".join(f"{n} {_g(k)} N/mm" for n, k in ps.linear_parts)
        parts += "".join(f", {n} {_g(k * NM)} N·m/rad" for n, k in ps.torsional_parts)
        rows.append(["k3, preload spring", f"{_g(d.k3 * NM, 5)} N·m/rad"
                     + (f" = {_g(ps.linear_stiffness)} N/mm at the carriage ({parts})" if s.lever else f" ({parts})")])
        if s.lever:
            rows.append(["preload lever",
                         f"{_g(s.lever * 1e3, 5)} mrad of output rotation of each path per mm of carriage"])
    eq = "Eq. 6" if s.drive_type == "type2" else "Eq. 3"
    ratio_eq = "Eq. 4" if s.drive_type != "type2" else "Eq. 5 / Eq. 6"
    rows += [[f"k_L ({eq})", f"{_g(d.loop_stiffness * NM, 5)} N·m/rad"],
             [f"k_D / k_L ({ratio_eq})", _g(d.stiffness_ratio, 5)]]
    out.append(("Loop", ["quantity", "value"], rows))
    rule = "half the maximum load" if s.drive_type == "type2" else "the maximum load"
    ok = "meets the recommendation" if s.preload_ok else "BELOW the recommendation"
    rows = [["maximum drive torque", f"{_g(s.max_output_torque * NM)} N·m"],
            [f"required (paper: {rule})", f"{_g(s.required_preload * NM)} N·m"],
            ["required (two-path model)", f"{_g(s.preload_to_carry * NM)} N·m"],
            ["set", f"{_g(s.drive.preload * NM)} N·m from {s.preload_source}: {ok}"]]
    if s.carriage_force is not None:
        rows.append(["carriage force", f"{_g(s.carriage_force)} N"])
    out.append(("Preload (torque each path carries at zero drive torque, at the output)", ["quantity", "value"], rows))
    if s.variations:
        rows = []
        for v in s.variations:
            travel = "-" if v.carriage_travel is None else \
                f"{v.carriage_travel / per_unit:.5g} {unit} ({v.carriage_travel * 1e3:.4g} µm)"
            force = "-" if s.lever is None else f"±{float(carriage_force(v.loop_range, s.lever)) / 2:.3g} N"
            mark = " (headline)" if v.label == s.headline_budget and len(s.variations) > 1 else ""
            rows.append([v.label + mark, travel, f"{v.loop_error * URAD:.4g}", f"{v.low * NM:.4g} .. {v.high * NM:.4g}",
                         f"{100 * v.relative:.2f} %", force])
        out.append(("Preload variation from loop errors (peak-to-peak)",
                    ["budget", "carriage travel", "loop error (µrad)", "preload band (N·m)", "change p-p",
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


def preload_diagram_figure(s: StiffnessSummary):
    """Fig. 6: both paths' force against drive displacement, preload point, drive load, backlash.

    Path 2 is mirrored (its force is drawn positive), so the lines cross at the preload point
    (zero drive displacement and torque); the vertical distance between them is the drive torque.
    Slopes are the rates at which each path's force changes with drive displacement (``k1``,
    ``k2`` for type 1; Fig. 7a's coupled rates for type 2). Where a path unloads it runs into its
    backlash ``b``; drive torques are referred to the output.
    """
    d = s.drive
    half = _span(s)
    b = s.path_backlash
    x = np.linspace(-half, half, 801)
    f1, f2 = d.path_torques(x)
    g1, g2 = d.path_force_rates
    x1_0, x2_0 = d.unloading_rotations  # where path 1 / path 2 reach zero force
    fig = _figure()
    ax = fig.add_subplot(1, 1, 1)
    ax.plot(x * URAD, f1 * NM, color="tab:blue", lw=2, label=f"path 1 (rate {_g(g1 * NM)} N·m/rad)", gid="path1")
    ax.plot(x * URAD, -f2 * NM, color="tab:orange", lw=2, label=f"path 2, mirrored (rate {_g(g2 * NM)} N·m/rad)",
            gid="path2")
    # each path's unloaded side: zero force across its backlash, then the other flank
    for x0, g, sign, colour in ((x1_0, g1, -1, "tab:blue"), (x2_0, g2, +1, "tab:orange")):
        if b is None or abs(x0) >= half:  # no backlash, or this path does not unload in the window
            continue
        far = x0 + sign * b
        if abs(far) <= half:
            ax.annotate("", xy=(far * URAD, 0), xytext=(x0 * URAD, 0),
                        arrowprops=dict(arrowstyle="<->", color=colour, lw=1))
            ax.text((x0 + far) / 2 * URAD, 0.04 * d.preload * NM, "b", color=colour, ha="center")
            xs = np.linspace(far, sign * half, 50)
            # the opposite flank: the path's force reverses (drawn negative), not part of the drive model
            ax.plot(xs * URAD, -np.abs(xs - far) * g * NM, color=colour, lw=1, ls="--")
        else:
            ax.text(sign * 0.98 * half * URAD, 0.04 * d.preload * NM, f"backlash b = {b * URAD:.4g} µrad\ncontinues",
                    color=colour, fontsize=8, ha="right" if sign > 0 else "left", va="bottom")
    ax.plot([0], [d.preload * NM], "ko")
    ax.annotate(f"preload F_L = {d.preload * NM:.3g} N·m\n(zero drive torque)", xy=(0, d.preload * NM),
                xytext=(-0.95 * half * URAD, d.preload * NM * 0.45), fontsize=9,
                arrowprops=dict(arrowstyle="->", lw=0.8))
    # the drive load: a vertical line between the two path lines at the maximum drive torque
    t = s.max_output_torque
    xd = float(d.rotation(t))
    fa, fb = d.path_torques(xd)
    ax.vlines(xd * URAD, -fb * NM, fa * NM, colors="k", lw=2.5, gid="drive_load")
    ax.text(xd * URAD, (fa - fb) / 2 * NM, f"  drive load F_D = {t * NM:.3g} N·m", fontsize=9, va="center")
    ax.axhline(0, color="0.5", lw=0.8)
    ax.axvline(0, color="0.5", lw=0.8)
    ax.set_xlim(-half * URAD, half * URAD)
    ax.set_xlabel("drive displacement δ_D at the output (µrad)")
    ax.set_ylabel("path force (torque at the output, N·m)")
    ax.set_title(f"{s.name}: preload diagram ({s.drive_type})")
    ax.legend(loc="upper center", fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    return fig


def plot_preload_diagram(s: StiffnessSummary, path: str | Path) -> Path:
    """Write :func:`preload_diagram_figure` as PNG."""
    path = Path(path)
    preload_diagram_figure(s).savefig(path)
    return path


def torque_deflection_figure(s: StiffnessSummary):
    """Drive torque against drive rotation at the output: the piecewise law with its unloading
    points, the path torques, and the curve with the common parts in series. Left: the preload
    region; right: the whole range up to beyond the maximum drive torque."""
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
        ax.plot(rot * URAD, torque * NM, color="k", lw=2.2, label="drive (two paths)", gid="drive")
        if s.common.components:
            ax.plot((rot + torque / s.common.stiffness) * URAD, torque * NM, color="0.45", lw=1.4, ls=":",
                    label="with common parts in series")
        ax.plot(rot * URAD, f1 * NM, color="tab:blue", lw=1, label="path 1 torque")
        ax.plot(rot * URAD, f2 * NM, color="tab:orange", lw=1, label="path 2 torque")
        ax.plot([r_lo * URAD, r_hi * URAD], [t_lo * NM, t_hi * NM], "o", color="tab:red",
                label=f"a path unloads ({_g(t_lo * NM)} / +{_g(t_hi * NM)} N·m)")
        for sign in (-1, 1):
            ax.axhline(sign * s.max_output_torque * NM, color="tab:green", lw=0.8, ls="--")
        ax.text(rot.min() * URAD, s.max_output_torque * NM, " max drive torque", color="tab:green",
                va="bottom", fontsize=8)
        ax.axhline(0, color="0.5", lw=0.8)
        ax.axvline(0, color="0.5", lw=0.8)
        ax.set_xlabel("drive rotation at the output (µrad)")
        ax.set_ylabel("torque at the output (N·m)")
        ax.set_title(f"{s.name}: torque-deflection, {title}", fontsize=10)
        ax.grid(True, alpha=0.3)
        if i == 0:
            ax.text(0.02, 0.97, f"k_D = {_g(d.drive_stiffness * NM)} N·m/rad ({eq})\n"
                    f"beyond: {_g(d.stiffness_beyond(-1) * NM)} / {_g(d.stiffness_beyond(1) * NM)} N·m/rad",
                    transform=ax.transAxes, va="top", fontsize=9)
            ax.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    return fig


def plot_torque_deflection(s: StiffnessSummary, path: str | Path) -> Path:
    """Write :func:`torque_deflection_figure` as PNG."""
    path = Path(path)
    torque_deflection_figure(s).savefig(path)
    return path


def preload_band_figure(s: StiffnessSummary):
    """Preload against loop error, with the band each loop-error budget spans.

    The x axis is the carriage travel from nominal (µm) when the loop error is a carriage
    travel, else the loop error as output rotation (µrad). Returns None without a loop error.
    """
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
        xs, xlabel = x * 1e3, "carriage travel from nominal (µm)"
    else:
        x_half = widest.loop_error / 2 * 1.25
        x = np.linspace(-x_half, x_half, 201)
        preload = d.preload + kl * x
        xs, xlabel = x * URAD, "loop error at the output (µrad)"
    fig = _figure()
    ax = fig.add_subplot(1, 1, 1)
    ax.plot(xs, preload * NM, color="k", lw=2, label=f"preload, k_L = {_g(kl * NM)} N·m/rad", gid="preload")
    colours = ["tab:red", "tab:blue", "tab:green", "tab:purple", "tab:brown"]
    for i, v in enumerate(sorted(s.variations, key=lambda v: -v.loop_error)):
        c = colours[i % len(colours)]
        half = (v.carriage_travel / 2 * 1e3) if carriage else v.loop_error / 2 * URAD
        ax.axhspan(v.low * NM, v.high * NM, color=c, alpha=0.15)
        ax.axvspan(-half, half, color=c, alpha=0.06)
        ax.plot([-half, half], [v.low * NM, v.high * NM], "s", color=c, gid=f"band_{v.label}",
                label=f"{v.label} ({v.source}): {v.low * NM:.3g}..{v.high * NM:.3g} N·m, ±{50 * v.relative:.2g} %")
    ax.axhline(s.required_preload * NM, color="tab:red", ls="--", lw=1, label=f"required {s.required_preload * NM:.3g} N·m")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("loop preload at the output (N·m)")
    lo = min(s.required_preload, min(v.low for v in s.variations))
    hi = max(v.high for v in s.variations)
    ax.set_ylim(0.9 * lo * NM, 1.05 * hi * NM + 1e-12)
    if s.lever is not None:
        sec = ax.secondary_yaxis("right", functions=(lambda p: p / NM * 2 * s.lever, lambda f: f / (2 * s.lever) * NM))
        sec.set_ylabel("carriage force (N)")
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
    path = Path(path)
    fig.savefig(path)
    return path


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
