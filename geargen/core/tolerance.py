"""Tolerance analysis of a dual-pinion drive: how far the preload carriage must travel.

Three views of the same question, all in mm along the symmetry line (+ away from the output):

- :func:`appendix_error_budget` -- the Appendix's table, rule for rule (Hale & Slocum; see
  ``../shared/paper/appendix-notes.md`` §4): each gear's total TIR times a gear factor gives
  its Δx1; Sum (worst case), RSS (statistical) and their mean; ΔC1 = Δx1 sin(phi).
- :func:`exact_error_budget` -- the same budget from the exact geometry
  (:func:`geargen.core.synthesis.solve_loop`) with every physical gear (two clusters) and
  every error as what it is: eccentricities offset a gear's pitch circle from its axis, a
  tooth-to-tooth error displaces the tooth in contact along the pitch circle. The worst-case
  travel per gear is found from the exact model's gradients and then re-solved without
  linearisation.
- :func:`monte_carlo` -- carriage travel (and preload-spring force) at random instants of
  operation: eccentricities at random phase, tooth errors uniform; vectorised.

Error model (TIR = total indicator reading, peak to peak): an eccentricity TIR ``e`` is a
pitch-circle offset of magnitude ``e/2`` turning with the gear; a tooth-to-tooth TIR ``t`` is a
tooth displacement in [-t/2, t/2] along the reference pitch circle, independent at each mesh.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from geargen.core.synthesis import (OFFSET_GEARS, TOOTH_CONTACTS, CentreSynthesis, appendix_carriage_travel,
                                    solve_loop, synthesize_centres)
from geargen.design.synthesis import ERROR_KINDS, GEAR_ROLES, GearErrors
from geargen.errors import DesignError

#: for each gear role, the indices of its physical gears in OFFSET_GEARS and of its contacts in TOOTH_CONTACTS
ROLE_OFFSETS = {"input": (0,), "cluster_large": (1, 2), "cluster_small": (3, 4), "output": (5,)}
ROLE_CONTACTS = {"input": (0, 1), "cluster_large": (2, 3), "cluster_small": (4, 5), "output": (6, 7)}
ROLE_OF_OFFSET = tuple(next(r for r, ks in ROLE_OFFSETS.items() if k in ks) for k in range(len(OFFSET_GEARS)))
ROLE_OF_CONTACT = tuple(next(r for r, ks in ROLE_CONTACTS.items() if k in ks) for k in range(len(TOOTH_CONTACTS)))

#: percentiles (%) every Monte Carlo result reports; 0.135/99.865 bound the central 99.73 % (+-3 sigma)
PERCENTILES = (0.135, 2.5, 50.0, 97.5, 99.865)


# --- the Appendix's budget ----------------------------------------------------------------------

@dataclass(frozen=True)
class ErrorBudget:
    """The Appendix's "Variation in x1 to accommodate errors" (mm; tuples in gear order 1..4).

    ``factors`` is Δx1 per unit TIR; ``centre_distance_factor`` is sin(phi) of mesh 1, the
    Appendix's ΔC1 / Δx1.
    """

    total_tir: tuple[float, ...]
    factors: tuple[float, ...]
    dx1: tuple[float, ...]
    dx1_sum: float
    dx1_rss: float
    centre_distance_factor: float

    @property
    def dx1_mean(self) -> float:
        """(Sum + RSS) / 2, the Appendix's design value."""
        return (self.dx1_sum + self.dx1_rss) / 2

    @property
    def percent_of_sum(self) -> tuple[float, ...]:
        return tuple(100 * d / self.dx1_sum for d in self.dx1) if self.dx1_sum > 0 else (0.0,) * 4

    @property
    def percent_of_rss(self) -> tuple[float, ...]:
        """100 Δx1_j / RSS: a plain ratio, as printed (the row does not add up to 100)."""
        return tuple(100 * d / self.dx1_rss for d in self.dx1) if self.dx1_rss > 0 else (0.0,) * 4

    @property
    def dC1_sum(self) -> float:
        return self.dx1_sum * self.centre_distance_factor

    @property
    def dC1_rss(self) -> float:
        return self.dx1_rss * self.centre_distance_factor

    @property
    def dC1_mean(self) -> float:
        return self.dx1_mean * self.centre_distance_factor


def appendix_factors(synthesis: CentreSynthesis) -> tuple[float, float, float, float]:
    """Δx1 per unit TIR of gears 1..4, the Appendix's rules (appendix-notes §4).

    A tangential error e of gear j turns the input by Δθ1 through Eq. 7 and Δx1 = r1 Δθ1:
    gear 1 -> 1 (an x shift of the input), gear 2 -> R1 r1 / r2, gear 3 -> R1 r1 / r3, gear 4 ->
    (R1 r1 / r3)(sin A2 + cos A2 tan phi2) (the x part of the output's eccentricity, through
    rolling and through the backlash change of mesh 2).
    """
    inp = synthesis.inputs
    r1, r2, r3 = (inp.reference_radius(k) for k in (1, 2, 3))
    g3 = synthesis.ratio_mesh1 * r1 / r3
    a2 = synthesis.A2
    return (1.0, synthesis.ratio_mesh1 * r1 / r2, g3,
            g3 * (math.sin(a2) + math.cos(a2) * math.tan(inp.pressure_angle_mesh2)))


def appendix_error_budget(synthesis: CentreSynthesis, errors: tuple[GearErrors, ...]) -> ErrorBudget:
    """The Appendix's error table for ``errors`` of gears 1..4 (input, cluster large, small, output)."""
    synthesis.check()
    factors = appendix_factors(synthesis)
    total = tuple(e.total_tir for e in errors)
    dx1 = tuple(f * t for f, t in zip(factors, total))
    return ErrorBudget(total_tir=total, factors=factors, dx1=dx1, dx1_sum=float(sum(dx1)),
                       dx1_rss=float(math.sqrt(sum(d * d for d in dx1))),
                       centre_distance_factor=math.sin(synthesis.inputs.pressure_angle_mesh1))


# --- the exact budget ---------------------------------------------------------------------------

@dataclass(frozen=True)
class ExactErrorBudget:
    """Carriage travel from the exact geometry (mm; tuples in gear order 1..4).

    offset_gradients : (6, 2) float -- d(carriage x)/d(pitch-circle offset), gears in OFFSET_GEARS order.
    tooth_gradients : (8,) float -- d(carriage x)/d(tooth displacement), contacts in TOOTH_CONTACTS order.
    dx1_linear : travel per gear from the gradients (peak to peak).
    dx1_resolved : travel per gear re-solved exactly between its two worst error states.
    travel_resolved : all gears at their worst at once, re-solved exactly (compare ``dx1_sum``).
    """

    success: bool
    message: str
    offset_gradients: np.ndarray
    tooth_gradients: np.ndarray
    dx1_linear: tuple[float, ...]
    dx1_resolved: tuple[float, ...]
    travel_resolved: float
    worst_low: float
    worst_high: float

    @property
    def dx1_sum(self) -> float:
        return float(sum(self.dx1_linear))

    @property
    def dx1_rss(self) -> float:
        return float(math.sqrt(sum(d * d for d in self.dx1_resolved)))


def _fd_step(synthesis: CentreSynthesis) -> float:
    return 1e-5 * synthesis.inputs.module_mesh1


def exact_gradients(synthesis: CentreSynthesis, backlash_mesh1=None, backlash_mesh2=None):
    """d(carriage x)/d(each elementary error) by central differences of :func:`solve_loop`.

    Returns (offset_gradients (6, 2), tooth_gradients (8,)), dimensionless (mm per mm).
    """
    h = _fd_step(synthesis)
    n_par = 6 * 2 + 8
    offsets = np.zeros((2 * n_par, 6, 2))
    tooth = np.zeros((2 * n_par, 8))
    for p in range(n_par):
        for j, sign in enumerate((1.0, -1.0)):
            row = 2 * p + j
            if p < 12:
                offsets[row, p // 2, p % 2] = sign * h
            else:
                tooth[row, p - 12] = sign * h
    sol = solve_loop(synthesis, backlash_mesh1, backlash_mesh2, offsets=offsets, tooth_errors=tooth).check()
    grad = (sol.carriage_x[0::2] - sol.carriage_x[1::2]) / (2 * h)
    return grad[:12].reshape(6, 2), grad[12:]


def _worst_state(errors, offset_grad, tooth_grad, roles, sign):
    """Pitch-circle offsets and tooth displacements that push the carriage furthest (sign +1 or -1)."""
    offsets = np.zeros((1, 6, 2))
    tooth = np.zeros((1, 8))
    for k, role in enumerate(ROLE_OF_OFFSET):
        if role in roles:
            e = errors[GEAR_ROLES.index(role)]
            g = offset_grad[k]
            norm = np.hypot(*g)
            if norm > 0:
                offsets[0, k] = sign * (e.bearing_eccentricity_tir + e.pitch_line_eccentricity_tir) / 2 * g / norm
    for k, role in enumerate(ROLE_OF_CONTACT):
        if role in roles:
            e = errors[GEAR_ROLES.index(role)]
            tooth[0, k] = sign * e.tooth_to_tooth_tir / 2 * np.sign(tooth_grad[k])
    return offsets, tooth


def exact_error_budget(synthesis: CentreSynthesis, errors: tuple[GearErrors, ...]) -> ExactErrorBudget:
    """The carriage-travel budget of :class:`ErrorBudget`, from the exact geometry (maximum backlash).

    Per gear: linear travel from the gradients, and the travel re-solved exactly between the
    gear's two worst error states (every one of its errors aligned to push the carriage one way,
    then the other). ``travel_resolved`` does the same with all gears at once.
    """
    og, tg = exact_gradients(synthesis)
    lin = []
    for role in GEAR_ROLES:
        e = errors[GEAR_ROLES.index(role)]
        ecc = e.bearing_eccentricity_tir + e.pitch_line_eccentricity_tir
        lin.append(float(sum(ecc * np.hypot(*og[k]) for k in ROLE_OFFSETS[role])
                         + sum(e.tooth_to_tooth_tir * abs(tg[k]) for k in ROLE_CONTACTS[role])))
    cases = [(role,) for role in GEAR_ROLES] + [GEAR_ROLES]
    offsets = np.zeros((2 * len(cases), 6, 2))
    tooth = np.zeros((2 * len(cases), 8))
    for c, roles in enumerate(cases):
        for j, sign in enumerate((1, -1)):
            offsets[2 * c + j], tooth[2 * c + j] = (a[0] for a in _worst_state(errors, og, tg, roles, sign))
    sol = solve_loop(synthesis, offsets=offsets, tooth_errors=tooth)
    x = sol.carriage_x - synthesis.input_x
    resolved = tuple(float(x[2 * c] - x[2 * c + 1]) for c in range(len(cases)))
    return ExactErrorBudget(success=sol.success, message=sol.message, offset_gradients=og, tooth_gradients=tg,
                            dx1_linear=tuple(lin), dx1_resolved=resolved[:4], travel_resolved=resolved[4],
                            worst_low=float(x[-1]), worst_high=float(x[-2]))


# --- Monte Carlo --------------------------------------------------------------------------------

@dataclass(frozen=True)
class MonteCarloResult:
    """Carriage travel at random instants (and builds), mm; preload-spring force in N.

    travel : (n,) float -- carriage position minus the synthesised position (+ away from the output).
    percentiles : {percent: travel} for PERCENTILES.
    bound_low, bound_high : the model's worst-case limits of ``travel`` (Sum, split about the
        mean state), which no sample can pass.
    rss : the model's RSS estimate of the travel range (peak to peak).
    force : (n,) float or None -- ``preload + spring_rate * travel`` (the spring pushes the
        carriage towards the output, so moving out compresses it).
    """

    success: bool
    message: str
    model: str
    error_shape: str
    samples: int
    travel: np.ndarray
    bound_low: float
    bound_high: float
    rss: float
    percentiles: dict[float, float]
    spring_rate: float | None = None
    preload: float = 0.0
    force: np.ndarray | None = None
    force_percentiles: dict[float, float] = field(default_factory=dict)
    failed: int = 0

    @property
    def mean(self) -> float:
        return float(np.mean(self.travel))

    @property
    def std(self) -> float:
        return float(np.std(self.travel))

    @property
    def minimum(self) -> float:
        return float(np.min(self.travel))

    @property
    def maximum(self) -> float:
        return float(np.max(self.travel))

    @property
    def spread_99_73(self) -> float:
        """Width of the central 99.73 % of the travel (the +-3 sigma range of a normal)."""
        return self.percentiles[99.865] - self.percentiles[0.135]

    @property
    def worst_case_sum(self) -> float:
        return self.bound_high - self.bound_low


def _random_directions(rng: np.random.Generator, shape) -> tuple[np.ndarray, np.ndarray]:
    """(cos, sin) of angles uniform on the circle, from one tangent: t = tan(theta/2)."""
    t = np.tan(rng.uniform(-np.pi / 2, np.pi / 2, shape))
    d = 1.0 / (1.0 + t * t)
    return (1.0 - t * t) * d, 2.0 * t * d


def _unit_samples(rng: np.random.Generator, shape, kind: str) -> np.ndarray:
    """Samples in [-1, 1]: 'sinusoid' cos(uniform phase), 'uniform', or 'normal3' (N(0, 1/3) cut at +-1)."""
    if kind == "sinusoid":
        return _random_directions(rng, shape)[0]
    if kind == "uniform":
        return rng.uniform(-1.0, 1.0, shape)
    out = rng.normal(0.0, 1.0 / 3.0, shape)
    bad = np.abs(out) > 1.0
    while bad.any():
        out[bad] = rng.normal(0.0, 1.0 / 3.0, int(bad.sum()))
        bad = np.abs(out) > 1.0
    return out


_CHUNK = 250_000


def monte_carlo(synthesis: CentreSynthesis, errors: tuple[GearErrors, ...], samples: int,
                rng: np.random.Generator | int, model: str = "exact", error_shape: str = "physical",
                include_backlash_tolerance: bool = False, spring_rate: float | None = None,
                preload: float = 0.0) -> MonteCarloResult:
    """Simulate the carriage travel (and preload-spring force) for ``samples`` random states.

    model : "exact" re-solves the geometry (:func:`solve_loop`) per sample, every physical gear
        with its own errors: eccentricities at a uniformly random phase (offset e/2 turning with
        the gear), tooth errors uniform in [-t/2, t/2] at each contact. "appendix" sums the
        Appendix's per-gear factors times the gear's three errors.
    error_shape : for "appendix" only: "physical" (as above), or one error per gear, its Δx1 as
        the full range: "uniform", or "normal3" (normal, the range as +-3 sigma, cut there) --
        the statistics the Appendix's RSS assumes.
    include_backlash_tolerance : also draw each mesh's backlash uniformly in [min, max] per
        sample (the build-to-build tooth-thickness tolerance).
    rng : a numpy Generator, or a seed for ``numpy.random.default_rng``.
    spring_rate : preload-spring rate (N/mm), with ``preload`` (N) at the synthesised position;
        gives the spring force per sample.
    """
    synthesis.check()
    if model not in ("exact", "appendix"):
        raise ValueError(f"model must be 'exact' or 'appendix', got {model!r}")
    if error_shape not in ("physical", "uniform", "normal3") or (model == "exact" and error_shape != "physical"):
        raise ValueError(f"error_shape {error_shape!r} is not available for model {model!r}")
    if samples < 1:
        raise ValueError("samples must be >= 1")
    rng = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(rng)
    inp = synthesis.inputs
    travel = np.empty(samples)
    failed = 0
    if model == "appendix":
        budget = appendix_error_budget(synthesis, errors)
        bound_low, bound_high, rss = -budget.dx1_sum / 2, budget.dx1_sum / 2, budget.dx1_rss
    else:
        exact = exact_error_budget(synthesis, errors)
        bound_low, bound_high = exact.worst_low, exact.worst_high
        rss = exact.dx1_rss
        og, tg = exact.offset_gradients, exact.tooth_gradients
    if include_backlash_tolerance:
        b_min = (inp.circumferential_backlash_min_mesh1, inp.circumferential_backlash_min_mesh2)
        if model == "appendix":
            dx_b = float(appendix_carriage_travel(synthesis, *b_min))
        else:
            dx_b = float(solve_loop(synthesis, *b_min).check().carriage_x[0] - synthesis.input_x)
        bound_low, bound_high = bound_low + min(0.0, dx_b), bound_high + max(0.0, dx_b)
    for start in range(0, samples, _CHUNK):
        n = min(_CHUNK, samples - start)
        if include_backlash_tolerance:
            b1 = rng.uniform(inp.circumferential_backlash_min_mesh1, inp.circumferential_backlash_max_mesh1, n)
            b2 = rng.uniform(inp.circumferential_backlash_min_mesh2, inp.circumferential_backlash_max_mesh2, n)
        else:
            b1 = b2 = None
        if model == "appendix":
            x = np.zeros(n)
            for f, e in zip(appendix_factors(synthesis), errors):
                if error_shape == "physical":
                    u = _unit_samples(rng, (2, n), "sinusoid")
                    x += f * (e.bearing_eccentricity_tir * u[0] + e.pitch_line_eccentricity_tir * u[1]
                              + e.tooth_to_tooth_tir * _unit_samples(rng, n, "uniform")) / 2
                else:  # the gear's total error as one error, as the Appendix's RSS takes it
                    x += f * e.total_tir * _unit_samples(rng, n, error_shape) / 2
            if b1 is not None:
                x += appendix_carriage_travel(synthesis, b1, b2)
        else:
            amp_b = np.array([errors[GEAR_ROLES.index(r)].bearing_eccentricity_tir / 2 for r in ROLE_OF_OFFSET])
            amp_p = np.array([errors[GEAR_ROLES.index(r)].pitch_line_eccentricity_tir / 2 for r in ROLE_OF_OFFSET])
            amp_t = np.array([errors[GEAR_ROLES.index(r)].tooth_to_tooth_tir / 2 for r in ROLE_OF_CONTACT])
            # drawn gear by gear (contiguous rows); offsets and tooth are (n, 6, 2) and (n, 8) views
            cos_b, sin_b = _random_directions(rng, (6, n))
            cos_p, sin_p = _random_directions(rng, (6, n))
            rows = np.empty((6, 2, n))
            rows[:, 0] = amp_b[:, None] * cos_b + amp_p[:, None] * cos_p
            rows[:, 1] = amp_b[:, None] * sin_b + amp_p[:, None] * sin_p
            offsets = rows.transpose(2, 0, 1)
            tooth = (amp_t[:, None] * rng.uniform(-1.0, 1.0, (8, n))).T
            # start Newton from the linear prediction: one or two steps then reach the exact state
            x_start = synthesis.input_x + np.einsum("kcn,kc->n", rows, og) + tg @ tooth.T
            sol = solve_loop(synthesis, b1, b2, offsets=offsets, tooth_errors=tooth, x_start=x_start)
            x = sol.carriage_x - synthesis.input_x
            failed += int(np.count_nonzero(~sol.converged))
        travel[start:start + n] = x
    if spring_rate is not None and not (math.isfinite(spring_rate) and spring_rate >= 0):
        raise ValueError(f"spring_rate must be >= 0 N/mm, got {spring_rate!r}")
    return _summarised(MonteCarloResult(success=False, message="", model=model, error_shape=error_shape,
                                        samples=samples, travel=travel, bound_low=bound_low, bound_high=bound_high,
                                        rss=rss, percentiles={}, spring_rate=spring_rate, preload=preload,
                                        failed=failed))


def _summarised(raw: MonteCarloResult) -> MonteCarloResult:
    """``raw`` (its travel and failure count) with success, message, percentiles and spring force."""
    ok = raw.failed == 0
    travel, preload, spring_rate = raw.travel, raw.preload, raw.spring_rate
    pct = dict(zip(PERCENTILES, (float(v) for v in np.percentile(travel, PERCENTILES)))) if ok else {}
    force = None
    force_pct: dict[float, float] = {}
    if spring_rate is not None:
        force = preload + spring_rate * travel
        if ok:
            force_pct = {p: preload + spring_rate * v for p, v in pct.items()}
    msg = "done" if ok else f"{raw.failed} of {raw.samples} samples did not close the loop"
    return replace(raw, success=ok, message=msg, percentiles=pct, force=force, force_percentiles=force_pct)


def combine_monte_carlo(parts: list[MonteCarloResult]) -> MonteCarloResult:
    """One result of a simulation run in chunks (:func:`monte_carlo` on the same drive and settings,
    each chunk with its own generator), given in chunk order: the samples concatenated and the
    statistics taken over all of them, so the result depends on the chunks and their seeds only,
    not on where or in which order they ran."""
    if not parts:
        raise ValueError("no Monte Carlo chunks to combine")
    travel = np.concatenate([p.travel for p in parts])
    return _summarised(replace(parts[0], samples=int(travel.size), travel=travel,
                               failed=sum(p.failed for p in parts)))


# --- sensitivities ------------------------------------------------------------------------------

@dataclass(frozen=True)
class SensitivityTable:
    """d(output)/d(input): ``values[i, j]`` for ``inputs[i]`` and ``outputs[j]``, internal units
    (mm per mm, rad per mm); ``input_units``/``output_units`` name them ("length", "angle")."""

    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    values: np.ndarray
    input_units: tuple[str, ...]
    output_units: tuple[str, ...]

    def value(self, input_name: str, output_name: str) -> float:
        return float(self.values[self.inputs.index(input_name), self.outputs.index(output_name)])


GEOMETRY_INPUTS = ("centre_distance_mesh1", "centre_distance_mesh2", "circumferential_backlash_max_mesh1", "circumferential_backlash_min_mesh1",
                   "circumferential_backlash_max_mesh2", "circumferential_backlash_min_mesh2")
GEOMETRY_OUTPUTS = ("A1", "A2", "input_x", "cluster_y", "dx1_min_backlash", "dx1_min_backlash_exact")


def _geometry_outputs(s: CentreSynthesis) -> np.ndarray:
    s.check()
    exact = solve_loop(s, s.inputs.circumferential_backlash_min_mesh1, s.inputs.circumferential_backlash_min_mesh2).check()
    return np.array([s.A1, s.A2, s.input_x, s.y2, s.min_backlash_dx1, exact.carriage_x[0] - s.input_x])


def geometry_sensitivities(synthesis: CentreSynthesis) -> SensitivityTable:
    """How A1, A2, the carriage position, the cluster offset y2 and the minimum-backlash travel
    (Appendix and exact) change with each centre distance and backlash limit.

    Central differences with the rounded increment count held fixed (a different count is a
    different solution branch); one-sided where an input sits on a limit (e.g. min = max).
    """
    inp = synthesis.inputs
    base = _geometry_outputs(synthesis)
    h = 1e-6 * inp.module_mesh1
    rows = []
    for name in GEOMETRY_INPUTS:
        vals = []
        for sign in (1.0, -1.0):
            try:
                s = synthesize_centres(replace(inp, **{name: getattr(inp, name) + sign * h}), synthesis.increments)
                vals.append(_geometry_outputs(s) if s.success else None)
            except DesignError:
                vals.append(None)
        if vals[0] is not None and vals[1] is not None:
            rows.append((vals[0] - vals[1]) / (2 * h))
        elif vals[0] is not None:
            rows.append((vals[0] - base) / h)
        elif vals[1] is not None:
            rows.append((base - vals[1]) / h)
        else:
            rows.append(np.full(len(GEOMETRY_OUTPUTS), np.nan))
    return SensitivityTable(GEOMETRY_INPUTS, GEOMETRY_OUTPUTS, np.array(rows), ("length",) * len(GEOMETRY_INPUTS),
                            ("angle", "angle", "length", "length", "length", "length"))


TOLERANCE_OUTPUTS = ("dx1_sum", "dx1_rss", "dx1_exact_worst")


def tolerance_sensitivities(budget: ErrorBudget, exact: ExactErrorBudget) -> SensitivityTable:
    """Which tolerance to buy: d(travel)/d(TIR) for each gear and error kind.

    Outputs: the Appendix's Sum and RSS, and the exact model's worst-case travel (linear).
    Inputs are named ``ROLE.KIND`` (e.g. ``cluster_small.pitch_line_eccentricity_tir``). Multiply
    by the preload-spring rate for the change of preload-force range.
    """
    names, rows = [], []
    for j, role in enumerate(GEAR_ROLES):
        f = budget.factors[j]
        d_rss = f * budget.dx1[j] / budget.dx1_rss if budget.dx1_rss > 0 else f
        ecc = float(sum(np.hypot(*exact.offset_gradients[k]) for k in ROLE_OFFSETS[role]))
        tooth = float(sum(abs(exact.tooth_gradients[k]) for k in ROLE_CONTACTS[role]))
        for kind in ERROR_KINDS:
            names.append(f"{role}.{kind}")
            rows.append((f, d_rss, tooth if kind == "tooth_to_tooth_tir" else ecc))
    return SensitivityTable(tuple(names), TOLERANCE_OUTPUTS, np.array(rows), ("length",) * len(names),
                            ("length",) * 3)


__all__ = ["ErrorBudget", "appendix_factors", "appendix_error_budget", "ExactErrorBudget", "exact_gradients",
           "exact_error_budget", "MonteCarloResult", "monte_carlo", "combine_monte_carlo", "SensitivityTable", "geometry_sensitivities",
           "tolerance_sensitivities", "PERCENTILES", "GEOMETRY_INPUTS", "GEOMETRY_OUTPUTS", "TOLERANCE_OUTPUTS"]
