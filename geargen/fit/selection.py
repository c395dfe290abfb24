"""Model selection: which library effects the data justify, and is what is left noise?

The rule (thresholds are fields of :class:`SelectionRule`):

1. **Significance, by the Bayesian information criterion.** A candidate effect with k free
   parameters, fitted jointly with everything already in the model, is significant when
   ``dBIC = n ln(RSS_before / RSS_after) - k ln n >= 10`` (n samples; "very strong" evidence on
   the Kass-Raftery scale). A harmonic's order counts as a parameter (k = 3) because it is
   searched for. Candidates are tried strongest first (largest dBIC).
2. **Held-out consistency.** The significant candidate is fitted again, with the whole model, on
   the first half of the record alone and on the second half alone. A library effect is a
   stationary physical law, so each half-record fit must reproduce the full-record effect:
   ``rms(e_half - e_full) / rms(e_full) <= max(0.5, 3 d_noise)`` for both halves, where
   d_noise is the disagreement noise alone would cause (from the fits' parameter covariance:
   a half-record fit of a weak or collinear effect is allowed to scatter as much as noise makes
   it). If not, the effect is not a stationary library effect, and the next candidate is tried.
   When the halves in time cannot determine the effect (noise alone would move a half-record
   fit by more than 50 % of it, e.g. a dead band seen in one load cycle, whose halves hold one
   load direction each), the record is split instead into alternate sixteenths; an effect that
   neither split can determine is not added (nor counted against the residual).
3. One effect is added per round, or two: each round also fits its strongest significant
   candidate jointly with each of the next two; such a pair is added when its dBIC beats the best
   single's by the threshold (the second effect is significant beside the first) and both its
   effects pass 2 (two effects that only separate when fitted together: a harmonic and a drift
   over one revolution). Rounds stop when nothing passes 1 and 2. A candidate whose fit is
   degenerate (a harmonic within half the order resolution of one in the model, a dead band
   narrower than the record resolves at zero torque, a parameter at its bound) or physically
   absurd (below) is rejected.
4. **Residual against noise.** The extended model's residual r is compared with the noise
   level sigma estimated from the data alone (:mod:`geargen.fit.noise`). ``unexplained`` is set
   when any of these fails:

   - level: ``rms(r) / sigma <= 1.15``;
   - structure: block sums of 32 consecutive residuals, each divided by its noise-predicted
     spread, have mean square ``<= 1 + 4 sqrt(2 / blocks) + 0.1`` (white noise gives 1);
   - leftovers: no candidate in the last round was significant but inconsistent between the
     halves (structure that no library effect explains), unless it is smaller than 5 % of the
     noise (rms): a long record makes such trifles significant;
   - plausibility: no effect of the final model has physically absurd parameters (a play wider
     than the record's range, a dead band wider than its rotation ...) and no channel's noise
     level lies below its reading error q / sqrt(12).

A torque-deflection record of more than 20,000 samples is searched on every k-th sample; the
model found is fitted to every sample, and the residual tests are made on all of them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from geargen.fit.effects import PARAMETER_COUNT
from geargen.fit.measurement import Measurement, MeasurementError
from geargen.fit import model as model_module
from geargen.fit.model import ModelFit, PreloadModel, TorqueModel
from geargen.fit.transmission import TransmissionModel
from geargen.fit.noise import (NoiseEstimate, isolated_spikes, noise_of_signal, noise_of_torque_residual,
                               noise_of_transmission, with_stiffness)


@dataclass(frozen=True)
class SelectionRule:
    """Thresholds of the selection rule (see the module docstring)."""

    bic_threshold: float = 10.0
    held_out_limit: float = 0.5
    noise_factor: float = 3.0
    level_limit: float = 1.15
    block: int = 32
    structure_z: float = 4.0
    structure_margin: float = 0.1
    max_effects: int = 6
    #: two look-alike candidates closer than this in dBIC cannot be told apart ("strong" evidence
    #: on the Kass-Raftery scale is a difference of 6 to 10)
    ambiguity_margin: float = 10.0
    #: a leftover smaller than this fraction of the noise (rms) does not make the record unexplained
    leftover_floor: float = 0.05

    def text(self) -> str:
        return (f"An effect is added when dBIC = n ln(RSS_before/RSS_after) - k ln n >= {self.bic_threshold:g} "
                f"(k its free parameters, a harmonic's order included), strongest first, one per round (or a pair, "
                f"fitted jointly, when it beats the best single by {self.bic_threshold:g}), and only if "
                f"fits to the first and to the second half of the record alone each reproduce the full-record effect "
                f"within {self.held_out_limit:.0%} rms, or within {self.noise_factor:g} x the disagreement noise alone "
                f"would cause if that is larger (alternate sixteenths of the record instead of halves when a half cannot "
                f"determine the effect). The final residual is noise when its rms is at most "
                f"{self.level_limit:g} x the model-free noise level, its {self.block}-sample block sums are white "
                f"(mean square <= 1 + {self.structure_z:g} sqrt(2/blocks) + {self.structure_margin:g}), and no significant "
                f"candidate of at least {self.leftover_floor:.0%} of the noise (rms) was left over that the halves "
                f"disagree on, and no effect's parameters are physically absurd (a play wider than the record's range, "
                f"a noise level below a channel's resolution); otherwise `unexplained` is true.")


@dataclass(frozen=True)
class CandidateResult:
    """One candidate of one round: what suggested it, its dBIC and what became of it."""

    round: int
    label: str
    evidence: str
    delta_bic: float
    outcome: str
    held_out: tuple[float, float] | None = None
    inconsistent: bool = False
    size: float = math.inf  # rms of its contribution over the noise level (where measured)


@dataclass(frozen=True, eq=False)
class AddedEffect:
    """An effect the selection added: its JSON entry and the numbers behind it."""

    entry: dict
    delta_bic: float
    held_out: tuple[float, float]
    rms_before: float
    rms_after: float


@dataclass(frozen=True)
class ResidualTest:
    name: str
    statistic: float
    limit: float
    passed: bool
    text: str


@dataclass(frozen=True, eq=False)
class Diagnosis:
    """Everything ``geargen fit`` found. ``to_json()`` gives the contract's report."""

    measurement: Measurement
    noise: NoiseEstimate
    model: object
    nominal_residual: np.ndarray | None
    declared: ModelFit
    extended: ModelFit
    added: tuple[AddedEffect, ...]
    candidates: tuple[CandidateResult, ...]
    tests: tuple[ResidualTest, ...]
    unexplained: bool
    rule: SelectionRule = field(default_factory=SelectionRule)
    rejected: tuple[dict, ...] = ()  # isolated spikes left out of the record (reject_spikes)
    ambiguous: tuple[dict, ...] = ()  # effects the data cannot tell apart or pin down: not added
    budget: tuple[dict, ...] = ()  # the measured errors beside the assembly's budget (geargen.fit.budget)
    budget_note: str = ""
    datasheet: dict | None = None  # the model-free datasheet figures (geargen.fit.datasheet)

    def stage(self, residual: np.ndarray | None) -> dict | None:
        if residual is None:
            return None
        return {"rms": _round(float(np.sqrt(np.mean(residual ** 2)))), "max_abs": _round(float(np.max(np.abs(residual))))}

    def noise_channels(self) -> dict:
        """Each measured channel's own noise level, from the data alone, keyed by its contract column."""
        ch = self.noise.channels
        if self.measurement.kind == "preload_trace":
            return {"carriage_x_um": _round(ch["signal"])}
        if self.measurement.kind == "transmission_error":  # (each encoder in urad at its own shaft)
            return {"input_angle_urad": _round(ch["input_angle"]), "output_angle_urad": _round(ch["output_angle"])}
        return {"output_torque_Nm": _round(ch["torque"]), "output_rotation_urad": _round(ch["rotation"])}

    def to_json(self) -> dict:
        """The report of contracts/measurements.md (plus extra keys inside effect entries)."""
        return {
            "kind": self.measurement.kind,
            "samples": self.measurement.samples,
            "units": self.measurement.units,
            "noise_rms": _round(self.noise.rms),
            "noise_channels": self.noise_channels(),
            "noise_ar1": _round(self.noise.ar1),
            "budget": {"assembly": str(self.measurement.assembly.name) if self.measurement.assembly else None,
                       "summary": self.budget_note,
                       "terms": [_round_entry({k: v for k, v in r.items() if not isinstance(v, list) or k == "gears"})
                                 for r in self.budget]},
            "ambiguous": [{"candidates": a["candidates"], "why": a["why"],
                           "fits": [_round_entry({k: v for k, v in e.items() if k != "evidence"}) for e in a["fits"]]}
                          for a in self.ambiguous],
            "rejected_samples": {"count": len(self.rejected),
                                 "samples": [_round_entry(e) for e in self.rejected[:100]]},
            "stages": {
                "nominal": self.stage(self.nominal_residual),
                "declared": self.stage(self.declared.residual),
                "extended": self.stage(self.extended.residual),
            },
            "effects_added": [_round_entry(a.entry) for a in self.added],
            "unexplained": bool(self.unexplained),
            **({"datasheet": _round_tree(self.datasheet)} if self.datasheet is not None else {}),
        }


def make_model(meas: Measurement, noise: NoiseEstimate):
    """The model class for a measurement's kind."""
    if meas.kind == "transmission_error":
        return TransmissionModel(meas, noise)
    return PreloadModel(meas, noise) if meas.kind == "preload_trace" else TorqueModel(meas, noise)


def _round(v, digits: int = 6):
    if v is None or isinstance(v, (bool, int, str)):
        return v
    if not math.isfinite(v) or v == 0:
        return float(v)
    return float(f"{v:.{digits}g}")


def _round_entry(e: dict) -> dict:
    return {k: (_round(v) if isinstance(v, float) else v) for k, v in e.items()}


def _round_tree(v):
    """Every float in nested dicts and lists rounded to 6 significant digits."""
    if isinstance(v, dict):
        return {k: _round_tree(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_round_tree(x) for x in v]
    return _round(v) if isinstance(v, float) else v


#: a noise level below this fraction of a channel's largest reading is rounding error, not noise
ROUNDING_LEVEL = 1e3 * float(np.finfo(float).eps)


def estimate_noise(meas: Measurement) -> NoiseEstimate:
    """Model-free noise of the residual, in residual units.

    Raises :class:`MeasurementError` naming the file and the column when a channel has no noise
    level (every selection statistic is measured against it): no run of four readings free of
    a gap, or a level at the rounding error of the readings (a computed signal, whose runs of four
    readings are mostly exactly smooth; a quantised one -- a dial, an encoder -- is read as such,
    its step's q / sqrt(12) counted as noise: geargen.fit.noise.level_of).
    """
    if meas.kind == "preload_trace":
        est = noise_of_signal(meas.time_s, meas.carriage_um)
        _require_level(meas, "carriage", est.rms, meas.carriage_um)
        return est
    if meas.kind == "transmission_error":
        est = noise_of_transmission(meas.time_s, meas.input_angle_rad * 1e6, meas.angle_rad * 1e6, meas.te_urad)
        _require_level(meas, "angle", est.rms, meas.te_urad)
        return est
    est = noise_of_torque_residual(meas.time_s, meas.torque_Nm, meas.rotation_rad * 1e6)
    _require_level(meas, "torque", est.channels["torque"], meas.torque_Nm)
    _require_level(meas, "rotation", est.rms, None)
    return est


def _require_level(meas: Measurement, channel: str, level: float, readings: np.ndarray | None) -> None:
    if math.isnan(level):
        raise MeasurementError(meas.where(channel), "no noise level can be estimated: no run of four consecutive "
                               "readings is free of a drop-out gap", "a record sampled without a gap in most places")
    floor = ROUNDING_LEVEL * float(np.max(np.abs(readings))) if readings is not None else 0.0
    if not (math.isfinite(level) and level > floor):
        raise MeasurementError(meas.where(channel), f"no noise level can be estimated: {level:.3g} is rounding error; "
                               "most runs of four consecutive readings are exactly smooth in time (a quadratic or "
                               "less), as the readings of a computed signal are",
                               "a measured signal with its noise")


def _lag_one(r: np.ndarray) -> float:
    """Lag-one autocorrelation of a residual (in record order)."""
    r = r - r.mean()
    return float(np.dot(r[1:], r[:-1]) / max(float(np.dot(r, r)), 1e-300))


def bic_gain(rss_before: float, rss_after: float, n: int, k: int) -> float:
    """dBIC of adding k parameters that take the sum of squares from rss_before to rss_after."""
    if rss_after <= 0:
        return math.inf
    return n * math.log(rss_before / rss_after) - k * math.log(n)


def _rms(v: np.ndarray) -> float:
    return float(np.sqrt(np.mean(v ** 2)))


def _rms_centred_difference(a: np.ndarray, b: np.ndarray) -> float:
    """rms((a - mean a) - b), block by block for a long record (no full-length temporaries)."""
    n = a.size
    if n <= model_module.ROW_BLOCK:
        return _rms((a - a.mean()) - b)
    mean = a.mean()
    total = 0.0
    for lo in range(0, n, model_module.ROW_BLOCK):
        d = (a[lo:lo + model_module.ROW_BLOCK] - mean) - b[lo:lo + model_module.ROW_BLOCK]
        total += float(d @ d)
    return math.sqrt(total / n)


SPLITS = {
    "time": "the first and the second half of the record",
    "interleaved": "alternate sixteenths of the record",
}


def split_masks(n: int, split: str) -> tuple[np.ndarray, np.ndarray]:
    """Two complementary sample masks: halves in time, or alternate sixteenths interleaved."""
    i = np.arange(n)
    first = i < n // 2 if split == "time" else (i * 16 // n) % 2 == 0
    return first, ~first


def held_out(model, fit: ModelFit, index: int, noise: NoiseEstimate, rule: SelectionRule,
             split: str = "time") -> tuple[float, float, float]:
    """(disagreement of part A, of part B, disagreement noise alone would cause) of term ``index``.

    Each part is fitted alone (the whole model). Disagreement: rms of (part effect - full-record
    effect) / rms of the full-record effect, both evaluated over the whole record. The noise-alone
    value is the larger over the parts of ``sqrt(E_part - E_full) / rms(e_full)``, E the mean
    square by which noise moves the effect in a fit (from the fit's parameter covariance; for
    nested fits Var(part - full) = Var(part) - Var(full)).
    """
    return held_out_terms(model, fit, (index,), noise, split)[0]


def held_out_terms(model, fit: ModelFit, indices, noise: NoiseEstimate, split: str = "time"
                   ) -> list[tuple[float, float, float]]:
    """:func:`held_out` of several terms of one fit, from the same two part fits."""
    n = model.n  # (not fit.residual.size: a long fit makes its arrays only when asked)
    # (AR(1) noise moves a fit more than white noise of its level: by the inverse of the
    # independent fraction, for effects that vary slowly from sample to sample)
    inflation = 1.0 / noise.independent_fraction
    wanted = []
    for index in indices:
        e = fit.contributions[index]
        e = e - e.mean()
        size = _rms(e)
        wanted.append((index, e, size, model.contribution_noise(fit, index) * inflation if size > 0 else math.inf))
    out = [[] for _ in indices]
    expected = [[] for _ in indices]
    for mask in split_masks(n, split):
        try:
            part = model.fit(fit.terms, mask=mask, start=fit)
        except Exception:  # a part that cannot determine the effect counts as disagreement
            part = None
        for k, (index, e, size, e_full) in enumerate(wanted):
            if part is None or size == 0:
                out[k].append(math.inf)
                expected[k].append(math.inf)
                continue
            ep = part.contributions[index]
            out[k].append(_rms_centred_difference(ep, e) / size)
            del ep
            e_part = model.contribution_noise(part, index) * inflation
            expected[k].append(math.inf if not math.isfinite(e_part - e_full) else
                               math.sqrt(max(e_part - e_full, 0.0)) / size)
    return [(o[0], o[1], max(x)) for o, x in zip(out, expected)]


def residual_tests(fit: ModelFit, noise: NoiseEstimate, leftovers: list[CandidateResult], rule: SelectionRule,
                   units: str) -> list[ResidualTest]:
    r = fit.residual
    var = noise.variance
    tests = []
    level = _rms(r) / max(noise.rms, 1e-300)
    tests.append(ResidualTest("level", level, rule.level_limit, level <= rule.level_limit,
                              f"residual rms {_rms(r):.4g} {units} is {level:.3f} x the model-free noise level {noise.rms:.4g} {units}"))
    b = rule.block
    nb = r.size // b
    if nb >= 4:
        phi = noise.ar1
        if phi:
            # coloured noise: the model-free correlation is known to its scatter; within that band
            # the residual's own lag-one correlation (far less scattered) says where it is. Beyond
            # the band, structure the model left is not taken for the noise's colour.
            phi = float(np.clip(_lag_one(r / np.sqrt(var)), phi - 3.0 * noise.ar1_scatter, phi + 3.0 * noise.ar1_scatter))
        rs = r[: nb * b].reshape(nb, b).sum(axis=1)
        vs = var[: nb * b].reshape(nb, b).sum(axis=1) * noise.block_variance_factor(b, phi)
        s = float(np.mean(rs ** 2 / np.maximum(vs, 1e-300)))
        limit = 1.0 + rule.structure_z * math.sqrt(2.0 / nb) + rule.structure_margin
        tests.append(ResidualTest("structure", s, limit, s <= limit,
                                  f"mean square of {nb} normalised {b}-sample block sums is {s:.3f} (white noise: 1)"))
    # a long record finds structure far below what matters (3 million samples make an effect of a
    # few thousandths of the noise significant): such leftovers are listed, not held against it
    bad = [c for c in leftovers if c.inconsistent and c.size >= rule.leftover_floor]
    tests.append(ResidualTest("leftovers", float(len(bad)), 0.0, not bad,
                              "no significant structure left that the library explains inconsistently" if not bad else
                              "significant but not a library effect: " + "; ".join(
                                  f"{c.label} (dBIC {c.delta_bic:.0f}, " + (f"half-record disagreement {max(c.held_out):.1%})"
                                                                           if c.held_out else "degenerate)") for c in bad)))
    return tests


def _judge(model, fit: ModelFit, indices, noise: NoiseEstimate, rule: SelectionRule) -> dict:
    """Whether the new terms ``indices`` of ``fit`` (polished) are added: ``verdict`` "added",
    "rejected" or "unconfirmed"; ``outcome`` the text; ``held_out`` ((da, db) per term); ``dn``
    the largest noise-alone disagreement; ``split``; ``inconsistent`` (a significant effect the
    parts disagree on); ``size`` its rms over the noise."""
    for i in indices:
        reason = model.degenerate(fit, i) or model.implausible(fit, i)
        if reason:
            what = fit.terms[i].label
            # (not "inconsistent": no library effect of its kind is there; what it fitted is left to
            # the residual tests, or explained by a rival)
            return {"verdict": "rejected", "outcome": f"rejected: {what}: {reason}" if len(indices) > 1 else
                    f"rejected: {reason}", "held_out": None, "dn": math.nan, "split": "", "inconsistent": False,
                    "size": math.inf}
    split = "time"
    parts = held_out_terms(model, fit, indices, noise, split)
    if max(p[2] for p in parts) > rule.held_out_limit:  # a half in time cannot see it (one load cycle): interleave
        split = "interleaved"
        parts = held_out_terms(model, fit, indices, noise, split)
    dn = max(p[2] for p in parts)
    held = tuple((p[0], p[1]) for p in parts)
    if dn > rule.held_out_limit:
        return {"verdict": "unconfirmed", "held_out": held, "dn": dn, "split": split, "inconsistent": False,
                "size": math.inf,
                "outcome": f"not added: cannot be confirmed on part of the record (noise alone would move a fit to "
                           f"{SPLITS[split]} by {dn:.0%} of the effect)"}
    worst = None
    for i, (da, db, dn_i) in zip(indices, parts):
        limit = max(rule.held_out_limit, rule.noise_factor * dn_i)
        if max(da, db) > limit and worst is None:
            worst = (i, da, db, dn_i, limit)
    if worst is None:
        return {"verdict": "added", "outcome": "added", "held_out": held, "dn": dn, "split": split,
                "inconsistent": False, "size": math.inf}
    i, da, db, dn_i, limit = worst
    size = _rms(fit.contributions[i] - np.mean(fit.contributions[i])) / max(noise.rms, 1e-300)
    which = f"{fit.terms[i].label}: " if len(indices) > 1 else ""
    return {"verdict": "rejected", "held_out": held, "dn": dn, "split": split, "inconsistent": True, "size": size,
            "outcome": f"rejected: {which}fits to {SPLITS[split]} alone disagree with the full-record effect by {da:.1%} / "
                       f"{db:.1%} (limit {limit:.1%}: the larger of {rule.held_out_limit:.0%} and {rule.noise_factor:g} x "
                       f"the {dn_i:.1%} noise alone would cause); its size {size:.3g} x the noise"}


#: significant single candidates of a round whose pairs are tried
PAIR_CANDIDATES = 3


@dataclass
class _Pass:
    """What one pass of the search found."""

    current: ModelFit
    added: list
    log: list
    last_round: list
    ambiguous: list
    tested: ModelFit | None


def _search(model, declared: ModelFit, noise: NoiseEstimate, n: int, rule: SelectionRule, units: str) -> _Pass:
    """The search: effects added one per round, or two (see the module docstring): each round
    also fits the pairs of its strongest significant candidates jointly and adds a pair whose
    dBIC beats the best single's by the threshold (the second effect is significant beside the
    first) when both its effects pass the held-out test; else the strongest single that passes."""
    current = declared
    added: list[AddedEffect] = []
    log: list[CandidateResult] = []
    last_round: list[CandidateResult] = []
    ambiguous: list[dict] = []
    tested = None  # the model the residual is tested with when an ambiguous effect explains it
    for rnd in range(1, rule.max_effects + 2):
        evaluated = []
        this_round: list[CandidateResult] = []
        for cand in model.candidates(current):
            k = PARAMETER_COUNT[cand.term.effect]
            quick = model.quick_gain(current, cand.term)
            if quick is not None:  # a cheap first-order estimate screens out hopeless candidates
                approx = bic_gain(current.rss, max(current.rss - quick, 1e-300), n, k)
                if approx < 0.5 * rule.bic_threshold:
                    this_round.append(CandidateResult(rnd, cand.term.label, cand.evidence, approx,
                                                      f"not significant (first-order dBIC {approx:.1f} < "
                                                      f"{0.5 * rule.bic_threshold:g}: not fitted further)"))
                    continue
            terms = current.terms + (cand.term,)
            f = model.fit(terms, start=current, extra=cand.start)
            dbic = bic_gain(current.rss, f.rss, n, k)
            evaluated.append((dbic, cand, f))
        evaluated.sort(key=lambda e: -e[0])
        chosen = None  # (dbic, candidates, fit, judgement)
        if len(added) + 2 <= rule.max_effects:
            chosen = _best_pair(model, current, evaluated, noise, n, rule, rnd, this_round)
        unconfirmed = []  # significant, but parts of the record cannot pin them down
        for dbic, cand, f in evaluated:
            if chosen is not None:
                this_round.append(CandidateResult(rnd, cand.term.label, cand.evidence, dbic,
                                                  "weaker than the effect added"))
                continue
            if dbic < rule.bic_threshold or rnd > rule.max_effects:
                why = f"not significant (dBIC {dbic:.1f} < {rule.bic_threshold:g})" if dbic < rule.bic_threshold else \
                    f"not tried: {rule.max_effects} effects is the limit"
                this_round.append(CandidateResult(rnd, cand.term.label, cand.evidence, dbic, why))
                continue
            f = model.polish(f)  # harmonic orders (and pulses) refined jointly before the effect is judged
            dbic = max(dbic, bic_gain(current.rss, f.rss, n, PARAMETER_COUNT[cand.term.effect]))
            judged = _judge(model, f, (len(f.terms) - 1,), noise, rule)
            held = judged["held_out"][0] if judged["held_out"] else None
            this_round.append(CandidateResult(rnd, f.terms[-1].label, cand.evidence, dbic, judged["outcome"], held,
                                              judged["inconsistent"], judged["size"]))
            if judged["verdict"] == "added":
                chosen = (dbic, [cand], f, judged)
            elif judged["verdict"] == "unconfirmed":
                unconfirmed.append((dbic, cand, f, judged["dn"]))
        log.extend(this_round)
        last_round = this_round
        if chosen is not None and len(chosen[1]) == 1:
            rivals = look_alike_rivals(chosen[1][0].term.effect, chosen[0], evaluated, rule)
            if rivals:
                group = next(g for g in LOOK_ALIKES if chosen[1][0].term.effect in g)
                why = next(text for key, text in LOOK_ALIKE_EVIDENCE.items() if key in group)
                ambiguous.append(_ambiguity(chosen[0], rivals, model, chosen[2], "the data fit each about as well: " + why))
                tested = chosen[2]
                break
        if chosen is None:
            if unconfirmed:
                dbic, cand, f, dn = unconfirmed[0]
                ambiguous.append(_ambiguity(dbic, [], model, f,
                                            f"significant (dBIC {dbic:.0f}) but the record cannot pin it down: noise "
                                            f"alone would move a fit to part of it by {dn:.0%} of the effect, as when "
                                            "the test does not load far enough beyond where a path unloads to tell it "
                                            "from the declared law's stiffness there"))
                tested = f
            break
        dbic, cands, f, judged = chosen
        rms_before = current.rms
        if current is not declared:
            current.release()
        declared.release()  # a long record's fit makes its arrays again when the report asks for them
        current = f
        first = len(current.terms) - len(cands)
        for j, cand in enumerate(cands):
            entry = model.entry(current, first + j)
            ho = judged["held_out"][j]
            jointly = " (added as a pair with " + " and ".join(c.term.label for c in cands if c is not cand) + \
                ": each alone was not enough)" if len(cands) > 1 else ""
            entry["evidence"] = (f"{cand.evidence}. Fitted jointly with the model{jointly}: dBIC = {dbic:.1f} "
                                 f"(>= {rule.bic_threshold:g}); fits to {SPLITS[judged['split']]} alone reproduce it "
                                 f"within {ho[0]:.1%} and {ho[1]:.1%} (noise alone: {judged['dn']:.1%}); residual rms "
                                 f"{rms_before:#.4g} -> {current.rms:#.4g} {units}")
            entry["delta_bic"] = dbic
            added.append(AddedEffect(entry, dbic, ho, rms_before, current.rms))
    return _Pass(current, added, log, last_round, ambiguous, tested)


def _best_pair(model, current: ModelFit, evaluated, noise: NoiseEstimate, n: int, rule: SelectionRule, rnd: int,
               this_round: list):
    """The best pair of this round's strongest significant candidate with one of the next
    strongest, fitted jointly, that beats the best single by the dBIC threshold and passes the
    held-out test on both; None if none."""
    significant = [(d, c, f) for d, c, f in evaluated if d >= rule.bic_threshold][:PAIR_CANDIDATES]
    if len(significant) < 2:
        return None
    best_single = significant[0][0]
    tried = []
    for a in range(1):  # (pairs with the strongest: each round's best single is in every good pair seen)
        for b in range(a + 1, len(significant)):
            da, ca, fa = significant[a]
            db, cb, fb = significant[b]
            if ca.term.effect == cb.term.effect and ca.term.effect not in ("harmonic", "drift"):
                continue  # (two of one effect that only exists once)
            f = model.fit(fa.terms + (cb.term,), start=fa, extra=cb.start)
            k = PARAMETER_COUNT[ca.term.effect] + PARAMETER_COUNT[cb.term.effect]
            tried.append((bic_gain(current.rss, f.rss, n, k), ca, cb, f, k))
    tried.sort(key=lambda e: -e[0])
    for dbic, ca, cb, f, k in tried:
        label = f"pair: {ca.term.label} + {cb.term.label}"
        if dbic < best_single + rule.bic_threshold:
            this_round.append(CandidateResult(rnd, label, "the two fitted jointly", dbic,
                                              f"not better than the best single ({best_single:.1f}) by "
                                              f"{rule.bic_threshold:g}"))
            continue
        f = model.polish(f)
        dbic = max(dbic, bic_gain(current.rss, f.rss, n, k))
        indices = (len(f.terms) - 2, len(f.terms) - 1)
        judged = _judge(model, f, indices, noise, rule)
        this_round.append(CandidateResult(rnd, f"pair: {f.terms[-2].label} + {f.terms[-1].label}", "the two fitted jointly",
                                          dbic, judged["outcome"], None, judged["inconsistent"], judged["size"]))
        if judged["verdict"] == "added":
            return dbic, [ca, cb], f, judged
    return None


def plausibility(model, fit: ModelFit, noise: NoiseEstimate) -> ResidualTest:
    """No effect of the final model may have physically absurd parameters (a play wider than the
    record's range, a dead band wider than the rotation it spans ...: ``model.implausible``), and
    no channel's noise level may lie below its reading error, q / sqrt(12) of its quantisation
    step (:func:`geargen.fit.noise.reading_quantum`): either makes the record unexplained."""
    from geargen.fit.noise import reading_quantum
    reasons = [f"{fit.terms[i].label}: {why}" for i in range(len(fit.terms))
               if (why := model.implausible(fit, i))]
    for column, values, level in model.noise_readings(noise):
        q = reading_quantum(values)
        if q > 0 and level < q / math.sqrt(12.0) * (1.0 - 1e-9):
            reasons.append(f"the noise level of {column} ({level:.3g}) is below its reading error q / sqrt(12) = "
                           f"{q / math.sqrt(12.0):.3g} (q = {q:.4g})")
    text = ("every effect's parameters are physically possible for this record and no noise level is below its "
            "channel's resolution" if not reasons else "physically absurd: " + "; ".join(reasons))
    return ResidualTest("plausibility", float(len(reasons)), 0.0, not reasons, text)


#: a torque-deflection record longer than this is searched on every k-th sample (the fewest k that
#: leaves no more); the model found is then fitted to every sample. Its fits are nonlinear least
#: squares through the play operator, tens of them per search: 20,000 samples already hold
#: thousands per load cycle, and 100,000 rows are fitted in about a second that way
TORQUE_SEARCH_SAMPLES = 20_000


def _prepared(meas: Measurement, noise: NoiseEstimate | None = None):
    """(noise, model, declared fit) of a record: the noise from the data (``noise`` if given), the
    declared model fitted; for a torque record the rotation's noise then carried into torque by
    the fitted law."""
    noise = noise if noise is not None else estimate_noise(meas)
    model = make_model(meas, noise)
    declared = model.fit(())
    if meas.kind == "torque_deflection" and noise.channels["rotation"] > 0:
        noise = _through_the_law(noise, model, declared)
        model = make_model(meas, noise)
        declared = model.fit(())
    return noise, model, declared


def _through_the_law(noise: NoiseEstimate, model, declared: ModelFit, rotation_urad: np.ndarray | None = None):
    """A torque record's noise with the rotation's noise carried into torque by ``declared``'s law
    (at ``rotation_urad``, default the model's record): errors in both channels, by effective
    variance. The fitted law knows the drive's stiffness far better than a local slope of the
    noisy data can (where the drive is stiff the rotation barely moves)."""
    return with_stiffness(noise, model.law_slope(declared, noise.channels["rotation"], rotation_urad),
                          "the stiffness dT/dtheta of the fitted declared law (effective variance; its rms "
                          "over the rotation channel's noise, near a kink)")


def _independent(meas: Measurement, noise: NoiseEstimate) -> int:
    """Independent samples of a record (AR(1) noise carries less evidence than white)."""
    return max(int(round(meas.samples * noise.independent_fraction)), 2)


def diagnose(meas: Measurement, rule: SelectionRule | None = None) -> Diagnosis:
    """Fit the declared model, add the effects the data justify (one or, when two only separate
    when fitted together, a pair per round), and test what is left."""
    from geargen.fit.datasheet import datasheet

    rule = rule or SelectionRule()
    noise = estimate_noise(meas)
    meas, rejected = reject_spikes(meas, noise)
    if rejected:
        noise = estimate_noise(meas)
    step = math.ceil(meas.samples / TORQUE_SEARCH_SAMPLES) if meas.kind == "torque_deflection" else 1
    if step > 1:
        keep = np.zeros(meas.samples, dtype=bool)
        keep[::step] = True
        part = meas.without(~keep, f"the search for effects ran on one sample in {step} ({int(keep.sum())} of "
                                   f"{meas.samples}); the model it found was then fitted to every sample")
        noise_part, model_part, declared_part = _prepared(part)
        if noise.channels["rotation"] > 0:  # (the part's law carries the rotation's noise into torque)
            noise = _through_the_law(noise, model_part, declared_part, meas.rotation_rad * 1e6)
        model = make_model(meas, noise)
        declared = model.fit((), start=declared_part)
        n = _independent(meas, noise)
        found = _search(model_part, declared_part, noise_part, _independent(part, noise_part), rule, meas.units)
        found.current = model.fit(found.current.terms, start=found.current) if found.current.terms else declared
        if found.tested is not None:
            found.tested = model.fit(found.tested.terms, start=found.tested)
        meas = replace(meas, notes=meas.notes + (part.notes[-1],))
        model.meas = meas
    else:
        noise, model, declared = _prepared(meas, noise)
        n = _independent(meas, noise)
        found = _search(model, declared, noise, n, rule, meas.units)
    tests = residual_tests(found.current if found.tested is None else found.tested, noise, found.last_round, rule,
                           meas.units)
    tests.append(plausibility(model, found.current, noise))
    unexplained = not all(t.passed for t in tests)
    final = found.current
    added = found.added
    for i, a in enumerate(added):  # report the parameters of the final joint fit
        fresh = model.entry(final, i)
        fresh.update({k: v for k, v in a.entry.items() if k in ("evidence", "delta_bic")})
        added[i] = AddedEffect(fresh, a.delta_bic, a.held_out, a.rms_before, a.rms_after)
    budget, budget_note = (), ""
    if meas.assembly is not None and meas.kind == "preload_trace":
        from geargen.fit.budget import budget_of
        # a fitted sinusoid's amplitude scatters by sigma sqrt(2 / n) (n independent samples)
        amplitude_se = noise.rms * math.sqrt(2.0 / n)
        rows, budget_note = budget_of(meas.assembly, final.declared_values, amplitude_se)
        budget = tuple(rows)
    sheet = datasheet(meas, model.T_smooth if meas.kind == "torque_deflection" else None)
    nominal = model.nominal()  # (made last: it is one more array of the record's length)
    return Diagnosis(measurement=meas, noise=noise, model=model, nominal_residual=nominal, declared=declared,
                     extended=final, added=tuple(added), candidates=tuple(found.log), tests=tuple(tests),
                     unexplained=unexplained, rule=rule, rejected=rejected, ambiguous=tuple(found.ambiguous),
                     budget=budget, budget_note=budget_note, datasheet=sheet)


#: effects that bend a torque-deflection curve alike, and what tells them apart physically
LOOK_ALIKES = ({"stiffening", "dead_band", "hysteresis"}, {"ratio_error", "drift"})
LOOK_ALIKE_EVIDENCE = {
    "stiffening": ("stiffening bends the curve over the whole load range, a dead band is a flat zone at zero torque, "
                   "friction depends on the direction of loading; a test that loads further, or cycles more slowly "
                   "through zero, separates them"),
    "ratio_error": ("a ratio error grows with the output angle, a drift with time or temperature: turning at a steady "
                    "speed one way, the two are the same line; a test that turns back separates them"),
}


def look_alike_rivals(effect: str, dbic: float, evaluated, rule: SelectionRule) -> list:
    """The significant candidates of ``effect``'s look-alike group within the ambiguity margin of it."""
    group = next((g for g in LOOK_ALIKES if effect in g), set())
    return [(d, c, f) for d, c, f in evaluated if c.term.effect in group and c.term.effect != effect
            and d >= rule.bic_threshold and d >= dbic - rule.ambiguity_margin]


def _ambiguity(dbic: float, rivals: list, model, fit, why: str) -> dict:
    """A report entry for effects the data cannot tell apart or pin down: ``fit``'s last term
    (of ``dbic``) and each rival's."""
    entries = [{**model.entry(fit, len(fit.terms) - 1), "delta_bic": dbic}]
    for d, c, f in rivals:
        entries.append({**model.entry(f, len(f.terms) - 1), "delta_bic": d})
    return {"candidates": [e["effect"] for e in entries], "fits": entries, "why": why}


def reject_spikes(meas: Measurement, noise: NoiseEstimate) -> tuple[Measurement, tuple[dict, ...]]:
    """The record without its isolated spikes (:func:`geargen.fit.noise.isolated_spikes`, on each
    measured channel against that channel's own noise level), and the samples left out: each
    ``{"time_s", "column", "value", "deviation"}`` (deviation in that channel's noise levels)."""
    ch = noise.channels
    if meas.kind == "preload_trace":
        channels = [("carriage", meas.carriage_um, ch["signal"])]
    elif meas.kind == "transmission_error":  # (a glitch of either encoder is a spike of the error)
        channels = [("angle", meas.te_urad, ch["signal"])]
    else:
        channels = [("torque", meas.torque_Nm, ch["torque"]), ("rotation", meas.rotation_rad * 1e6, ch["rotation"])]
    rows = np.zeros(meas.samples, dtype=bool)
    found = []
    for channel, values, sigma in channels:
        spikes = isolated_spikes(meas.time_s, values, sigma)
        if spikes.any():
            local = np.interp(meas.time_s[spikes], meas.time_s[~spikes], values[~spikes])
            found += [{"time_s": float(t), "column": meas.column(channel), "value": float(v),
                       "deviation": float((v - m) / sigma)}
                      for t, v, m in zip(meas.time_s[spikes], values[spikes], local)]
            rows |= spikes
    if not found:
        return meas, ()
    found.sort(key=lambda e: e["time_s"])
    note = (f"{int(rows.sum())} isolated spikes left out (samples that jump away from both neighbours by more "
            "than the noise allows): " + ", ".join(f"{e['column']} at {e['time_s']:.6g} s" for e in found[:5])
            + (", ..." if len(found) > 5 else ""))
    return meas.without(rows, note), tuple(found)
