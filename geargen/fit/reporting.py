"""Turn a :class:`~geargen.fit.selection.Diagnosis` into the report layer's plain input."""

from __future__ import annotations

import numpy as np

from geargen.fit.selection import Diagnosis
from geargen.report.fit import FitReportInput


def _direction(values: np.ndarray) -> np.ndarray:
    d = np.sign(np.diff(values, prepend=values[0]))
    d[0] = d[1] if d.size > 1 else 1
    return np.where(d == 0, 1, d)


def report_input(dg: Diagnosis) -> FitReportInput:
    meas = dg.measurement
    model = dg.model
    summary = dg.to_json()
    common = dict(
        name=meas.name, kind=meas.kind, units=meas.units, description=meas.description, summary=summary,
        time_s=meas.time_s, declared_prediction=dg.declared.prediction, extended_prediction=dg.extended.prediction,
        residual_declared=dg.declared.residual, residual_extended=dg.extended.residual, noise_rms=dg.noise.rms,
        noise_method=dg.noise.method, rule_text=dg.rule.text(), temperature_C=meas.temperature_C,
        effects=summary["effects_added"],
        candidates=[{"round": c.round, "label": c.label, "delta_bic": c.delta_bic, "outcome": c.outcome,
                     "evidence": c.evidence} for c in dg.candidates],
        tests=[{"name": t.name, "statistic": t.statistic, "limit": t.limit, "passed": t.passed, "text": t.text} for t in dg.tests],
        notes=list(meas.notes), declared_values=_declared_text(dg),
    )
    if meas.kind in ("preload_trace", "transmission_error"):
        pg_d = model.periodogram(dg.declared.residual)
        pg_e = model.periodogram(dg.extended.residual)
        spectrum = {"orders": pg_d.orders, "declared": pg_d.amplitude, "extended": np.interp(pg_d.orders, pg_e.orders, pg_e.amplitude)}
        found = [(f"found {e['order']:.4g}", e["order"]) for e in summary["effects_added"] if e["effect"] == "harmonic"]
        found += [(f"sideband {q:.4g}", q) for e in summary["effects_added"] if e["effect"] == "sidebands"
                  for q in e["orders"]]
        measured, label = ((meas.carriage_um, "carriage position (um)") if meas.kind == "preload_trace" else
                           (meas.te_urad, "transmission error (urad at the output)"))
        return FitReportInput(
            abscissa=np.degrees(meas.angle_rad), abscissa_label="output angle (deg)", measured=measured,
            measured_label=label, direction=_direction(meas.angle_rad),
            direction_label="output turning forward + / back −", spectrum=spectrum,
            train_orders=[(t.name, t.order) for t in model.train], effect_orders=found, **common)
    return FitReportInput(
        abscissa=meas.rotation_rad * 1e6, abscissa_label="output rotation (urad)", measured=meas.torque_Nm,
        measured_label="output torque (Nm)", direction=_direction(model.T_smooth),
        direction_label="torque rising + / falling −", load=meas.torque_Nm, load_label="output torque (Nm)", **common)


def _declared_text(dg: Diagnosis) -> dict:
    v = dg.extended.declared_values
    if dg.measurement.kind in ("preload_trace", "transmission_error"):
        return {k: val for k, val in v.items()}
    out = {f"{k}_Nm_per_rad": v[k] for k in ("k1", "k2", "k3") if k in v}
    out["preload_Nm"] = v["preload"]
    out["probe_zero_urad"] = v["theta0_urad"]
    return out
