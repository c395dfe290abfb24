"""The measured errors beside the design's error budget: the loop closed back into the design.

A preload trace whose sidecar names ``assembly = "design.toml"`` is fitted with the design's
train; each declared term is a sinusoid of carriage position at the once-per-revolution order of
a rotating part (eccentricity) or at a tooth-mesh order (tooth-to-tooth error). The exact
geometry of the design (:func:`geargen.core.tolerance.exact_gradients`, the loop re-solved with
each pitch circle offset) says how far the carriage moves per unit of each error, so a fitted
amplitude turns back into the error that made it:

- an eccentricity TIR ``e`` offsets the pitch circle by ``e / 2``, turning with the gear; the
  carriage then moves by ``e / 2 |g|`` in amplitude at the gear's order (``g`` the gradient of the
  carriage position with that gear's offset), so ``e = 2 A / |g|``. Bearing and pitch-line
  eccentricity both turn once per revolution: their sum is measured, against the sum budgeted.
- a rotating part of several physical gears (a cluster: large and small gear, two clusters at
  one speed) moves the carriage by the vector sum of their effects: the amplitude is compared
  with the budget's worst case (all in phase), and the TIR it stands for if every gear of the
  part carried it in phase is a lower bound of the largest.
- tooth-to-tooth errors: the periodic part at the mesh order, against the budget's worst case
  (each contact of the mesh displaced by half its TIR, in the carriage's worst direction).

Every row says inside, at the budget (within two standard errors of the fitted amplitude) or
exceeds, and by how much.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from geargen.core.tolerance import ROLE_CONTACTS, ROLE_OF_OFFSET, exact_gradients
from geargen.design.synthesis import GEAR_ROLES

#: the declared model's rotating parts and their physical gears (OFFSET_GEARS indices)
PART_GEARS = {"output": (5,), "cluster": (1, 2, 3, 4), "input": (0,)}
#: each tooth-mesh order's gear roles
MESH_ROLES = {"mesh1": ("input", "cluster_large"), "mesh2": ("cluster_small", "output")}


def _eccentricity(errors, role: str) -> float:
    e = errors[GEAR_ROLES.index(role)]
    return e.bearing_eccentricity_tir + e.pitch_line_eccentricity_tir


def verdict(amplitude: float, budget_amplitude: float, amplitude_se: float) -> str:
    """"exceeds" beyond the budget by more than two standard errors of the fitted amplitude,
    "at the budget" within them, else "inside"."""
    if amplitude > budget_amplitude + 2.0 * amplitude_se:
        return "exceeds"
    if amplitude >= budget_amplitude - 2.0 * amplitude_se:
        return "at the budget"
    return "inside"


def compare_with_budget(declared_values: dict, synthesis_run, amplitude_se: float = 0.0) -> list[dict]:
    """One row per declared term the fit measured (amplitudes in um): the measured error and the
    budget's, in um, and the verdict (:func:`verdict`; ``amplitude_se`` the standard error of a
    fitted amplitude, um). ``synthesis_run``: the design's
    :class:`geargen.model.synthesis.SynthesisRun` (its error budget and exact geometry)."""
    errors = synthesis_run.errors
    exact = synthesis_run.exact_budget
    if exact is not None:
        og, tg = exact.offset_gradients, exact.tooth_gradients
    else:
        og, tg = exact_gradients(synthesis_run.synthesis)
    rows = []
    for part, gears in PART_GEARS.items():
        fitted = declared_values.get(part)
        if not isinstance(fitted, dict):
            continue
        amplitude = fitted["amplitude"]  # um
        sens = [float(np.hypot(*og[k])) for k in gears]
        roles = sorted({ROLE_OF_OFFSET[k] for k in gears}, key=GEAR_ROLES.index)
        budget_amplitude = sum(_eccentricity(errors, ROLE_OF_OFFSET[k]) * 1e3 / 2 * s for k, s in zip(gears, sens))
        row = {"term": "eccentricity", "part": part, "gears": roles, "order": fitted["order"],
               "amplitude_um": amplitude, "budget_amplitude_um": budget_amplitude,
               "carriage_um_per_um_offset": sens}
        if len(gears) == 1:
            (role,) = roles
            measured = 2 * amplitude / sens[0]
            budget = _eccentricity(errors, role) * 1e3
            row.update(measured_tir_um=measured, budget_tir_um=budget,
                       note="bearing + pitch-line eccentricity: both turn once per revolution")
        else:
            measured = 2 * amplitude / sum(sens)
            budget = max(_eccentricity(errors, r) for r in roles) * 1e3
            row.update(measured_tir_um=measured, budget_tir_um=budget,
                       note=(f"{len(gears)} gears turn at this order (both clusters' large and small gears): the "
                             "measured TIR is what each would carry in phase, a lower bound of the largest"))
        row["verdict"] = verdict(amplitude, budget_amplitude, amplitude_se)
        row["excess_tir_um"] = max(measured - budget, 0.0) if row["verdict"] == "exceeds" else 0.0
        row["measured_tir_se_um"] = 2 * amplitude_se / (sens[0] if len(gears) == 1 else sum(sens))
        rows.append(row)
    for mesh, roles in MESH_ROLES.items():
        fitted = declared_values.get(mesh)
        if not isinstance(fitted, dict):
            continue
        contacts = [k for r in roles for k in ROLE_CONTACTS[r]]
        budget_amplitude = sum(errors[GEAR_ROLES.index(r)].tooth_to_tooth_tir * 1e3 / 2 * abs(tg[k])
                               for r in roles for k in ROLE_CONTACTS[r])
        amplitude = fitted["amplitude"]
        rows.append({"term": "tooth_to_tooth", "part": mesh, "gears": list(roles), "order": fitted["order"],
                     "amplitude_um": amplitude, "budget_amplitude_um": budget_amplitude,
                     "carriage_um_per_um_tooth": [float(abs(tg[k])) for k in contacts],
                     "verdict": verdict(amplitude, budget_amplitude, amplitude_se),
                     "note": "the periodic part of the tooth errors of the mesh's two gears, against the "
                             "budget's worst case (every contact displaced by half its TIR the carriage's way)"})
    return rows


def budget_of(assembly: Path, declared_values: dict, amplitude_se: float = 0.0) -> tuple[list[dict], str]:
    """(rows of :func:`compare_with_budget`, note) for the design at ``assembly``; no rows and why
    when the design gives no error budget."""
    from geargen.design.assembly import load_design
    from geargen.drives import resolve
    design = load_design(assembly)
    run = resolve(design).synthesis
    if run is None or run.errors is None:
        return [], f"{Path(assembly).name} gives no error budget ([errors.*]): nothing to compare"
    rows = compare_with_budget(declared_values, run, amplitude_se)
    over = [r for r in rows if r["verdict"] == "exceeds"]
    if not over:
        return rows, f"every measured error is inside the budget of {Path(assembly).name}"
    return rows, "exceeds the budget of " + Path(assembly).name + ": " + "; ".join(
        f"{', '.join(r['gears'])} {r['term'].replace('_', '-')} "
        + (f"TIR {r['measured_tir_um']:.3g} um against {r['budget_tir_um']:.3g}" if "measured_tir_um" in r else
           f"{r['amplitude_um']:.3g} um of carriage against {r['budget_amplitude_um']:.3g}") for r in over)


__all__ = ["compare_with_budget", "budget_of", "PART_GEARS", "MESH_ROLES"]
