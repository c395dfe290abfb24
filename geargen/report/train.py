"""``geargen train``'s report: the per-part and per-stage tables, the servo view, the strategy advice
and the alternatives, as text and JSON, and the plots (the position loop against a direct drive;
the dual-motor drive's Fig. 1)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from geargen.report.figures import write_figure
from geargen.units import TextUnits

NM = 1e3


def _urad(x):
    return None if x is None else x * 1e6


def _nm(k):
    return None if k is None or not math.isfinite(k) else k / NM


def _parts(parts) -> list[dict[str, Any]]:
    return [{"name": p.name, "material": p.material, "mass_kg": p.mass_kg,
             "inertia_own_axis_kg_m2": p.inertia_own_axis_kg_m2, "speed_over_output": p.speed,
             "ratio_to_motor": p.ratio_to_motor, "reflected_to_motor_kg_m2": p.reflected_to_motor_kg_m2,
             "turns_with": p.turns_with} for p in parts]


def train_dict(a) -> dict[str, Any]:
    """The JSON of a :class:`geargen.model.train.TrainAnalysis` (keys of issue 16; SI and µrad)."""
    total_lost = a.lost_motion_without_preload
    stages = []
    for s in a.stages:
        stages.append({"name": s.name, "driver": s.driver, "driven": s.driven, "ratio": s.ratio,
                       "driver_speed_over_output": s.speed, "preloaded": s.preloaded,
                       "stiffness_at_output_Nm_per_rad": _nm(s.stiffness),
                       "single_path_stiffness_at_output_Nm_per_rad": _nm(s.single_path_stiffness),
                       "lost_motion_at_output_urad": _urad(s.lost_motion),
                       "lost_motion_min_at_output_urad": _urad(s.lost_motion_min),
                       "lost_motion_max_at_output_urad": _urad(s.lost_motion_max),
                       "lost_motion_left_urad": 0.0 if s.preloaded else _urad(s.lost_motion),
                       "share_of_lost_motion": (s.lost_motion / total_lost) if s.lost_motion and total_lost else 0.0,
                       "compliance_share": (a.stiffness_at_output / s.stiffness) if s.stiffness else 0.0,
                       "mesh_loss_factor": s.loss_factor, "components": list(s.components), "source": s.source})
    dominant = a.dominant_stage()
    out = {
        "design": a.name, "motor_speed_over_output": a.motor_speed,
        "parts": _parts(a.parts),
        "stages": stages,
        "totals": {"inertia_at_motor_kg_m2": a.inertia_at_motor,
                   "parts_inertia_at_motor_kg_m2": a.parts_inertia_at_motor,
                   "motor_rotor_inertia_kg_m2": a.settings.motor_rotor_inertia,
                   "load_inertia_at_motor_kg_m2": a.settings.load_inertia / a.motor_speed ** 2,
                   "stiffness_at_output_Nm_per_rad": _nm(a.stiffness_at_output),
                   "stiffness_command_drive_with_common_Nm_per_rad": _nm(a.summary.drive_stiffness_with_common),
                   "lost_motion_at_output_urad": a.lost_motion * 1e6,
                   "lost_motion_without_preload_urad": total_lost * 1e6,
                   "dominant_stage": dominant.name if dominant else None,
                   "preload_Nm": a.summary.drive.preload / NM,
                   "preload_friction_at_output_Nm": a.preload_friction / NM,
                   "max_output_torque_Nm": a.max_output_torque / NM},
        "servo": a.servo(), "advice": a.advice(), "alternatives": a.alternatives(),
        "warnings": list(a.warnings), "notes": list(a.notes),
    }
    return out


def _fmt(x, spec=".4g", none="-"):
    return none if x is None else format(x, spec)


def format_train(data: dict[str, Any], units: TextUnits = TextUnits()) -> str:
    """The text report of :func:`train_dict`'s data (torques in N·m there) in ``units`` (torques in the
    design file's torque unit)."""
    t = data["totals"]
    tq, ks = units.unit("torque"), units.unit("torsional_stiffness")

    def torque(x_nm):  # a torque, or a torque per rad, of the data in the text's unit
        return None if x_nm is None else units.value("torque", x_nm * NM)

    kg, J = units.unit("mass"), units.unit("inertia")

    def mass(x_kg):
        return units.value("mass", x_kg)

    def inertia(x_kg_m2):  # the data's kg·m² in the text's unit (lb·in^2 for an inch design)
        return None if x_kg_m2 is None else units.value("inertia", x_kg_m2)

    lines = [f"Train of {data['design']}: motor to output {data['motor_speed_over_output']:.6g}:1", "",
             f"Rotating parts (inertia from the parts' geometry, {J}; reflected = own / ratio_to_motor^2)",
             f"  {'part':26s} {'mass ' + kg:>9s} {'J own':>12s} {'ratio':>8s} {'J at motor':>11s}  turns with"]
    for p in data["parts"]:
        lines.append(f"  {p['name']:26s} {mass(p['mass_kg']):9.4g} {inertia(p['inertia_own_axis_kg_m2']):12.4g} "
                     f"{p['ratio_to_motor']:8.4g} {inertia(p['reflected_to_motor_kg_m2']):11.4g}  {p['turns_with']}")
    lines += ["", "Stages, motor first (stiffness and lost motion at the output)",
              f"  {'stage':40s} {'ratio':>6s} {ks:>11s} {'compl.':>7s} {'backlash urad':>13s} {'design range':>13s}"
              f" {'share':>6s} {'left urad':>9s}"]
    for s in data["stages"]:
        lo, hi = s["lost_motion_min_at_output_urad"], s["lost_motion_max_at_output_urad"]
        span = "-" if lo is None or hi is None else f"{lo:.1f}-{hi:.1f}"
        lines.append(f"  {s['name']:40s} {s['ratio']:6.4g} {_fmt(torque(s['stiffness_at_output_Nm_per_rad']), '11.5g'):>11s} "
                     f"{s['compliance_share']:7.1%} {_fmt(s['lost_motion_at_output_urad'], '13.1f'):>13s} {span:>13s} "
                     f"{s['share_of_lost_motion']:6.1%} {_fmt(s['lost_motion_left_urad'], '9.1f'):>9s}"
                     + ("  preloaded" if s["preloaded"] else ""))
    lines.append("  each stage is its mesh with the parts on its driven shaft (geargen stiffness's components):")
    for s in data["stages"]:
        if s["components"]:
            lines.append(f"    {s['name'].split(' (')[0]}: " + ", ".join(s["components"]))
    lines += ["", f"Totals: inertia at the motor {inertia(t['inertia_at_motor_kg_m2']):.4g} {J} (rotor "
              f"{_fmt(inertia(t['motor_rotor_inertia_kg_m2']))}, parts {inertia(t['parts_inertia_at_motor_kg_m2']):.4g}, load "
              f"{inertia(t['load_inertia_at_motor_kg_m2']):.4g}); stiffness at the output {_fmt(torque(t['stiffness_at_output_Nm_per_rad']), '.6g')} "
              f"{ks} (geargen stiffness, without the upstream stages: "
              f"{_fmt(torque(t['stiffness_command_drive_with_common_Nm_per_rad']), '.6g')});",
              f"  lost motion at the output {t['lost_motion_at_output_urad']:.1f} urad as built "
              f"({t['lost_motion_without_preload_urad']:.1f} without the preload); the largest backlash: "
              f"{t['dominant_stage']}; preload {torque(t['preload_Nm']):.4g} {tq} drags {torque(t['preload_friction_at_output_Nm']):.4g} {tq}."]
    sv = data.get("servo")
    if sv:
        lines += ["", "Servo view (PD loop at the motor; direct drive: the same motor, gains and load)",
                  f"  gains Kp {torque(sv['position_gain_Nm_per_rad']):.4g} {ks}, Kd {torque(sv['velocity_gain_Nm_s_per_rad']):.4g} "
                  f"{tq}·s/rad; servo stiffness at the output Kp R^2 = {torque(sv['servo_stiffness_at_output_Nm_per_rad']):.5g} {ks}",
                  f"  geared: natural frequency {sv['natural_frequency_Hz']:.4g} Hz, damping ratio {sv['damping_ratio']:.3g}",
                  f"  direct: natural frequency {sv['direct_natural_frequency_Hz']:.4g} Hz, damping ratio "
                  f"{sv['direct_damping_ratio']:.3g}",
                  f"  gain over direct: frequency x{sv['frequency_gain_over_direct']:.4g} (R = {sv['ratio']:.4g}), damping "
                  f"x{sv['damping_gain_over_direct']:.4g} at equal gains, x{sv['damping_gain_at_equal_bandwidth']:.4g} at "
                  f"equal bandwidth (R^2 = {sv['ratio'] ** 2:.4g})"]
        if "resonance_Hz" in sv:
            lines.append(f"  first resonance (two-mass) {sv['resonance_Hz']:.4g} Hz, antiresonance "
                         f"{sv['antiresonance_Hz']:.4g} Hz; the chain of stages: {_fmt(sv.get('chain_first_mode_Hz'))} Hz")
    ad = data.get("advice")
    if ad:
        verdict = "met" if ad["met"] else "NOT met even with every stage preloaded"
        lines += ["", f"Strategy (the paper's: preload from the output up until the lost motion is allowed): allowed "
                  f"{ad['allowed_lost_motion_urad']:.1f} urad, {verdict}",
                  f"  preload: {', '.join(ad['preload']) or 'none'}; lost motion left {ad['lost_motion_left_urad']:.1f} urad; "
                  f"stiffness {torque(ad['stiffness_no_preload_Nm_per_rad']):.5g} -> {torque(ad['stiffness_advised_Nm_per_rad']):.5g} {ks}; "
                  f"preload {torque(ad['preload_Nm']):.4g} {tq} drags {torque(ad['preload_friction_Nm']):.4g} {tq}",
                  "  this design preloads: " + (", ".join(ad["design_preloads"]) or "none")
                  + (" (as advised)" if ad["design_agrees"] else " (differs from the advice)")]
    if data.get("alternatives"):
        lines += ["", "Alternatives on the same load (max output torque "
                  f"{torque(t['max_output_torque_Nm']):.4g} {tq} either way)",
                  f"  {'':36s} {ks:>10s} {'lost urad':>10s} {'motor ' + tq:>10s} {'friction ' + tq:>12s}"]
        for r in data["alternatives"]:
            motors = f" x{r['motors']}" if r["motors"] > 1 else ""
            lines.append(f"  {r['name']:36s} {torque(r['stiffness_at_output_Nm_per_rad']):10.5g} "
                         f"{r['lost_motion_at_output_urad']:10.1f} {torque(r['motor_torque_Nm']):10.4g}{motors} "
                         f"{torque(r['preload_friction_Nm']):12.4g}")
    for w in data.get("warnings", []):
        lines.append(f"warning: {w}")
    for n in data.get("notes", []):
        lines.append(f"note: {n}")
    return "\n".join(lines)


def servo_response(a, frequencies_hz: np.ndarray) -> dict[str, np.ndarray] | None:
    """|load angle / command| of the geared drive (two masses on the train's spring, PD at the motor)
    and of the direct drive (one rigid mass), SI, referred to the output."""
    sv = a.servo()
    two = a.two_mass()
    if sv is None or two is None:
        return None
    w = 2 * np.pi * np.asarray(frequencies_hz, dtype=float)
    s = 1j * w
    R = a.motor_speed
    kp, kd = sv["position_gain_Nm_per_rad"] * R ** 2, sv["velocity_gain_Nm_s_per_rad"] * R ** 2  # at the output
    j1, j2, k = two.j_motor, two.j_load, two.stiffness
    # motor side: j1 s^2 x1 = (kp + kd s)(c - x1) - k (x1 - x2); load: j2 s^2 x2 = k (x1 - x2)
    ctrl = kp + kd * s
    x2_over_x1 = k / (j2 * s ** 2 + k)
    x1 = ctrl / (j1 * s ** 2 + ctrl + k - k * x2_over_x1)
    geared = np.abs(x1 * x2_over_x1)
    kp0, kd0 = sv["position_gain_Nm_per_rad"], sv["velocity_gain_Nm_s_per_rad"]
    jd = sv["direct_drive_inertia_kg_m2"]
    direct = np.abs((kp0 + kd0 * s) / (jd * s ** 2 + kd0 * s + kp0))
    return {"frequency_Hz": np.asarray(frequencies_hz, dtype=float), "geared": geared, "direct": direct}


def write_train_plots(a, folder: Path) -> dict[str, Path]:
    """The servo plot (when the design gives a motor and loop) and the stage chart, as PNG."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    out = {}
    sv = a.servo()
    if sv is not None:
        hi = max(sv.get("resonance_Hz", 0.0), sv["natural_frequency_Hz"], sv["direct_natural_frequency_Hz"]) * 10
        f = np.logspace(-1, math.log10(max(hi, 10.0)), 600)
        resp = servo_response(a, f)
        fig, ax = plt.subplots(figsize=(7, 4.2))
        if resp is not None:
            ax.loglog(f, resp["geared"], label=f"geared {a.motor_speed:.4g}:1 (two-mass)")
            ax.loglog(f, resp["direct"], "--", label="direct drive, same motor and gains")
            if "resonance_Hz" in sv:
                ax.axvline(sv["resonance_Hz"], color="0.5", lw=0.8)
                ax.text(sv["resonance_Hz"], ax.get_ylim()[0] * 2, f" resonance {sv['resonance_Hz']:.3g} Hz",
                        fontsize=8, color="0.3")
        ax.set_xlabel("frequency (Hz)")
        ax.set_ylabel("|load angle / command|")
        ax.set_title(f"{a.name}: position loop, geared vs direct drive")
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        path = write_figure(fig, folder / "servo_response.png", dpi=120)
        plt.close(fig)
        out["servo_response"] = path
    fig, ax = plt.subplots(figsize=(7, 3.6))
    names = [s.name.split(" (")[0] for s in a.stages]
    x = np.arange(len(names))
    lost = [(s.lost_motion or 0.0) * 1e6 for s in a.stages]
    comp = [(a.stiffness_at_output / s.stiffness * 100) if s.stiffness else 0.0 for s in a.stages]
    ax.bar(x - 0.2, lost, 0.4, label="backlash at the output (urad)")
    ax2 = ax.twinx()
    ax2.bar(x + 0.2, comp, 0.4, color="tab:orange", label="share of the compliance (%)")
    ax.set_xticks(x, names, fontsize=8)
    ax.set_ylabel("urad")
    ax2.set_ylabel("%")
    for i, s in enumerate(a.stages):
        if s.preloaded:
            ax.text(i, lost[i], "preloaded", ha="center", va="bottom", fontsize=7)
    fig.legend(fontsize=8, loc="upper left")
    ax.set_title(f"{a.name}: where the lost motion and the compliance sit")
    fig.tight_layout()
    path = write_figure(fig, folder / "stages.png", dpi=120)
    plt.close(fig)
    out["stages"] = path
    return out


def dual_motor_dict(a) -> dict[str, Any]:
    """The JSON of a :class:`geargen.model.train.DualMotorAnalysis` (SI, µrad)."""
    sp = a.spec
    d = a.drive()
    return {"design": a.name, "kind": "dual_motor", "control": sp.control, "motor_speed_over_output": a.motor_speed,
            "parts": _parts(a.parts),
            "path": {"components": [{"name": n, "stiffness_at_output_Nm_per_rad": k} for n, k in a.path_components],
                     "stiffness_at_output_Nm_per_rad": a.path_stiffness,
                     "backlash_at_output_urad": [b * 1e6 for b in a.backlash]},
            "bias_Nm": d.bias, "motor_peak_at_output_Nm": d.peak, "max_output_torque_Nm": sp.max_output_torque / NM,
            "zones": d.zones(), "capacity_Nm": d.capacity, "reversal_command_Nm": d.reversal_command,
            "bias_needed_for_load_Nm": d.bias_for(sp.max_output_torque / NM),
            # at each motor: its rotor, its own pinion and half the output and load (both parts of the
            # pair reflected, halved, is one pinion and half the output)
            "totals": {"inertia_at_motor_kg_m2": sum(p.reflected_to_motor_kg_m2 for p in a.parts) / 2
                       + (a.settings.motor_rotor_inertia or 0.0)
                       + a.settings.load_inertia / a.motor_speed ** 2 / 2,
                       "stiffness_at_output_Nm_per_rad": 2 * a.path_stiffness,
                       "lost_motion_at_output_urad": 0.0},
            "comparison": a.comparison()}


def format_dual_motor(data: dict[str, Any]) -> str:
    path = data["path"]
    lines = [f"Dual-motor drive {data['design']} (Fig. 1), control {data['control']!r}: motor to output "
             f"{data['motor_speed_over_output']:.6g}:1", "",
             "Each motor's path at the output: " + ", ".join(f"{c['name']} {c['stiffness_at_output_Nm_per_rad']:.5g}"
                                                           for c in path["components"])
             + f" -> {path['stiffness_at_output_Nm_per_rad']:.5g} N·m/rad; mesh backlash "
             + ", ".join(f"{b:.1f}" for b in path["backlash_at_output_urad"]) + " urad at the output",
             f"bias {data['bias_Nm']:.4g} N·m, each motor's peak {data['motor_peak_at_output_Nm']:.4g} N·m at the output;"
             f" capacity {data['capacity_Nm']:.4g} N·m; load {data['max_output_torque_Nm']:.4g} N·m needs a bias of "
             f"{data['bias_needed_for_load_Nm']:.4g} N·m", "", "Zones (positive commands; the negative side mirrors):"]
    for z in data["zones"]:
        lines.append(f"  {z['zone']:9s} {z['command_from']:8.4g} to {z['command_to']:8.4g} N·m: stiffness "
                     f"{z['stiffness']:.5g} N·m/rad" + (f", lost motion {z['lost_motion'] * 1e6:.1f} urad"
                                                         if z["lost_motion"] else ""))
    lines += ["", "Both controls on this load:",
              f"  {'control':15s} {'capacity':>9s} {'bias':>7s} {'bias for load':>13s} {'motor N·m':>10s} "
              f"{'friction N·m':>12s}  carries it"]
    for r in data["comparison"]:
        lines.append(f"  {r['control']:15s} {r['capacity_Nm']:9.4g} {r['bias_Nm']:7.4g} {r['bias_needed_for_load_Nm']:13.4g} "
                     f"{r['motor_torque_at_load_Nm']:10.4g} {r['bias_friction_Nm']:12.4g}  "
                     + ("yes" if r["carries_load"] else "no"))
    return "\n".join(lines)


def write_dual_motor_plots(a, folder: Path) -> dict[str, Path]:
    """Fig. 1 for this drive: each motor's torque (solid) and the net (centre line) against the
    command, (a) unidirectional and (b) constant bias, zones shaded, stiffness written in each."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    for ax, control, label in zip(axes, ("unidirectional", "bias"), ("(a) unidirectional torques", "(b) constant bias")):
        d = a.drive(control)
        cap = d.capacity
        c = np.linspace(-cap, cap, 801)
        t1, t2 = d.motor_torques(c)
        ax.plot(c, t1, "tab:blue", lw=2, label="motor 1")
        ax.plot(c, t2, "tab:red", lw=2, label="motor 2")
        ax.plot(c, t1 + t2, "k-.", lw=1, label="net output torque")
        for z in d.zones():
            if z["zone"] == "together":
                for sign in (1, -1):
                    ax.axvspan(sign * z["command_from"], sign * z["command_to"], color="tab:green", alpha=0.12)
                ax.text(z["command_to"] * 0.97, -cap * 0.9, f"together\n{z['stiffness']:.4g} N·m/rad", ha="right",
                        fontsize=7)
            elif z["zone"] == "opposed":
                ax.text(0, cap * 0.8, f"opposed: {z['stiffness']:.4g} N·m/rad", ha="center", fontsize=7)
        ax.axhline(0, color="0.6", lw=0.6)
        ax.set_title(label + f", bias {d.bias:.3g} N·m", fontsize=9)
        ax.set_xlabel("net torque command at the output (N·m)")
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("torque at the output (N·m)")
    axes[0].legend(fontsize=8, loc="lower right")
    fig.suptitle(f"{a.name}: two motors on one output (Hale & Slocum Fig. 1)", fontsize=10)
    fig.tight_layout()
    path = write_figure(fig, folder / "dual_motor.png", dpi=120)
    plt.close(fig)
    return {"dual_motor": path}


__all__ = ["train_dict", "format_train", "servo_response", "write_train_plots", "dual_motor_dict",
           "format_dual_motor", "write_dual_motor_plots"]
