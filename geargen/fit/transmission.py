"""The model of a transmission-error record (contracts/measurements.md, ``transmission_error``).

The transmission error, urad at the output, is ``TE = output angle - input angle / ratio`` with
the declared ratio. Against the output angle theta::

    TE = c0 + sum_declared [a_q cos(q theta) + b_q sin(q theta)]          declared
            + effects                                                     (all linear)

The declared orders are once per turn of every shaft and each stage's tooth-mesh order with its
second harmonic (:func:`geargen.fit.orders.transmission_declared_orders`). Every effect is
linear in its coefficients once the parameters that shape its columns are set, so a fit is one
linear least-squares solve (:class:`geargen.fit.model.PreloadModel`'s machinery, in row blocks
for long records); those shaping parameters are searched for (a harmonic's order, a tooth
pulse's angle and width) or iterated (a backlash's half-width):

- ``harmonic``: ``cos``/``sin`` at an order the model lacks;
- ``drift``: temperature or time, centred;
- ``ratio_error``: ``-(theta - mean) x 1e6``; its coefficient is ``relative`` = measured /
  declared ratio - 1 (with input = R_m x output, TE = output (1 - R_m / R_d) = -relative x output);
- ``sidebands``: ``cos``/``sin`` at mesh order -+ shaft order (four columns);
- ``tooth_pulse``: :func:`geargen.fit.effects.tooth_pulse` of the shaft's angle (order x theta);
- ``hysteresis`` (backlash at reversals): the output lags the commanded angle (input / ratio) by a
  play of half-width h, ``TE += play(u, h) - u`` with u the commanded angle in urad. Away from
  the few samples after a reversal this is ``-h`` moving forward and ``+h`` moving back, so the
  column ``(play(u, h0) - u) / h0`` is nearly independent of h0 and its coefficient is h: the fit
  solves, sets h0 to the result and solves again until h0 holds to 0.1 %.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from geargen.fit import effects as fx
from geargen.fit.measurement import Measurement, TransmissionModelSpec
from geargen.fit.model import (Candidate, ModelFit, PreloadModel, Term, contribution_noise_gram, sample_correlation,
                               drift_value, drift_variable, mask_or_all, drift_terms)
from geargen.fit.noise import NoiseEstimate
from geargen.fit.orders import attribute_order, transmission_declared_orders, transmission_orders

#: bins of a shaft's turn for the synchronous average that finds a tooth pulse
PULSE_BINS = 720
#: pulse widths (deg of the shaft's turn) tried before the width is refined
PULSE_WIDTHS_DEG = (2.0, 4.0, 8.0, 16.0, 32.0, 64.0)
#: the output turns back when it retreats by more than this (rad): a backlash shows at reversals
REVERSAL_RAD = math.radians(1.0)


class TransmissionModel(PreloadModel):
    """Declared sinusoids of a transmission-error record and its library effects (module doc)."""

    kind = "transmission_error"

    def __init__(self, meas: Measurement, noise: NoiseEstimate):
        spec: TransmissionModelSpec = meas.model
        self._setup(meas, noise, meas.te_urad, transmission_orders(spec.stages),
                    transmission_declared_orders(spec.stages, spec.declared))
        self.commanded_urad = meas.input_angle_rad / spec.ratio * 1e6
        self.shafts = tuple(t for t in self.train if t.kind == "shaft")
        self.meshes = tuple(t for t in self.train if t.kind == "mesh")
        self.reversals = fx.reversals(self.theta, REVERSAL_RAD)
        self._theta_mean = float(self.theta.mean())

    # ---------------------------------------------------------------- columns
    def _width(self, term: Term) -> int:
        return {"harmonic": 2, "drift": 1, "ratio_error": 1, "sidebands": 4, "tooth_pulse": 1,
                "hysteresis": 1}.get(term.effect, 0)

    def _term_rows(self, term: Term, rows) -> np.ndarray:
        theta = self.theta[rows]
        if term.effect == "harmonic":
            return fx.harmonic_basis(theta, term.order)
        if term.effect == "drift":
            v = drift_variable(self.meas, term.variable)
            return (v[rows] - self._drift_mean(term.variable))[:, None]
        if term.effect == "ratio_error":
            return (-(theta - self._theta_mean) * 1e6)[:, None]
        if term.effect == "sidebands":
            shaft = term.params[0]
            return np.hstack([fx.harmonic_basis(theta, term.order - shaft), fx.harmonic_basis(theta, term.order + shaft)])
        if term.effect == "tooth_pulse":
            angle, width = term.params
            return fx.tooth_pulse(term.order * theta, angle, width)[:, None]
        if term.effect == "hysteresis":
            return self._backlash_column(term.params[0])[rows][:, None]
        raise ValueError(f"{term.effect} does not apply to a transmission_error")

    def _backlash_column(self, half_width: float) -> np.ndarray:
        """``(play(u, h) - u) / h`` over the record, u the commanded output angle (urad); kept."""
        key = ("backlash", float(half_width))
        if key not in self._cache:
            if len(self._cache) > 64:
                self._cache.clear()
            h = max(float(half_width), 1e-9)
            u = self.commanded_urad
            self._cache[key] = (fx.play_operator(u, h) - u) / h
        return self._cache[key]

    def _term_values(self, term: Term, coef: np.ndarray, half_width: float) -> dict:
        if term.effect == "harmonic":
            amp, ph = fx.harmonic_parameters(*coef)
            return {"order": term.order, "amplitude": amp, "phase_deg": ph}
        if term.effect == "drift":
            return drift_value(term.variable, float(coef[0]))
        if term.effect == "ratio_error":
            return {"relative": float(coef[0])}
        if term.effect == "sidebands":
            lower = fx.harmonic_parameters(*coef[:2])[0]
            upper = fx.harmonic_parameters(*coef[2:])[0]
            return {"order": term.order, "shaft": term.variable, "amplitude": 0.5 * (lower + upper),
                    "amplitude_lower": lower, "amplitude_upper": upper,
                    "orders": [term.order - term.params[0], term.order + term.params[0]]}
        if term.effect == "tooth_pulse":
            return {"shaft": term.variable, "angle_deg": float(np.mod(term.params[0], 360.0)), "amplitude": float(coef[0]),
                    "width_deg": float(term.params[1])}
        return {"half_width": float(coef[0])}

    # ---------------------------------------------------------------- fit
    # (nominal: perfect gears keep the error at its mean, as PreloadModel's carriage)
    def fit(self, terms: tuple[Term, ...], mask=None, start: ModelFit | None = None, extra: dict | None = None) -> ModelFit:
        terms = tuple(terms)
        whole = mask is None
        mask = mask_or_all(mask, self.n)
        if not terms and whole:
            self._check_declared_design()
        for _ in range(6):  # (only a backlash's half-width is iterated; everything else is linear)
            coef = self._solve(lambda rows: self._design(terms, rows), mask)
            slices = self._slices(terms)
            moved = False
            for i, term in enumerate(terms):
                if term.effect == "hysteresis":
                    h = abs(float(coef[slices[i]][0]))
                    if h > 0 and abs(h - term.params[0]) > 1e-3 * max(h, 1e-12):
                        terms = terms[:i] + (replace(term, params=(h,)),) + terms[i + 1:]
                        moved = True
            if not moved:
                break
        prediction = self._predict(terms, coef)
        residual = self.x - prediction
        rss = float(np.sum(residual[mask] ** 2))
        values = [self._term_values(term, coef[slices[i]], 0.0) for i, term in enumerate(terms)]
        declared_values = {"offset": float(coef[0])}
        for j, t in enumerate(self.declared):
            amp, ph = fx.harmonic_parameters(coef[1 + 2 * j], coef[2 + 2 * j])
            declared_values[t.name] = {"order": t.order, "amplitude": amp, "phase_deg": ph}
        width = 1 + 2 * len(self.declared) + sum(self._width(t) for t in terms)
        n_params = width + sum(1 for t in terms if t.effect == "harmonic") + sum(2 for t in terms if t.effect == "tooth_pulse")
        return ModelFit(terms=terms, rss=rss, n_fitted=int(mask.sum()), n_params=n_params, values=tuple(values),
                        declared_values=declared_values,
                        state={"coef": coef, "half_width": 0.0, "slices": slices, "mask": mask},
                        prediction=prediction, residual=residual,
                        contributions=tuple(self._predict(terms, coef, columns=sl) for sl in slices))

    def equilibrium(self, fit: ModelFit) -> np.ndarray:
        return fit.prediction

    def contribution_noise(self, fit: ModelFit, index: int) -> float:
        """Mean square by which noise moves term ``index``'s contribution (every term is linear here)."""
        terms, mask = fit.terms, fit.state["mask"]
        sl = fit.state["slices"][index]
        width = 1 + 2 * len(self.declared) + sum(self._width(t) for t in terms)

        def jacobians(rows):
            X = self._design(terms, rows)
            return X, X[:, sl]
        JtJ, CtC = self._two_grams(jacobians, mask)
        return contribution_noise_gram(JtJ, CtC, self.n, self.noise.rms, np.arange(width)[sl])

    def quick_gain(self, fit: ModelFit, term: Term) -> float | None:
        return None

    # ---------------------------------------------------------------- candidates
    def candidates(self, fit: ModelFit, count: int = 3) -> list[Candidate]:
        out: list[Candidate] = []
        r = fit.residual
        sigma2 = max(self.noise.rms, 1e-300) ** 2
        present = set(fit.terms)
        seen_sidebands = set()
        for q, drop, amplitude in self.spectrum_peaks(r, self._occupied_orders(fit.terms), count):
            power = drop / sigma2
            side = self._sideband_of(q)
            if side is not None:
                mesh, shaft = side
                term = Term("sidebands", variable=shaft.name, order=mesh.order, params=(shaft.order,))
                if term in present or term in seen_sidebands:
                    continue
                seen_sidebands.add(term)
                out.append(Candidate(term, f"peak of the residual order spectrum at order {q:.4f}: {mesh.name} "
                                           f"(order {mesh.order:.6g}) {'+' if q > mesh.order else '-'} the {shaft.name} "
                                           f"shaft (order {shaft.order:.6g}), amplitude {amplitude:.3g} urad, "
                                           f"power {power:.1f} x noise variance", statistic=power))
                continue
            where = attribute_order(q, self.train)
            src = f"{where[1]} x {where[0].name} (order {where[0].order:.4f})" if where else "no shaft or mesh"
            out.append(Candidate(Term("harmonic", order=q),
                                 f"peak of the residual order spectrum at order {q:.4f} ({src}), amplitude "
                                 f"{amplitude:.3g} urad, power {power:.1f} x noise variance", statistic=power))
        kinds = {(t.effect, t.variable) for t in fit.terms}
        for term in drift_terms(self.meas):
            if ("drift", term.variable) in kinds:
                continue
            v = drift_variable(self.meas, term.variable)
            corr = sample_correlation(v, r)
            out.append(Candidate(term, f"residual correlates with {term.variable} (r = {corr:+.3f})", statistic=corr))
        if not any(t.effect == "ratio_error" for t in fit.terms):
            corr = sample_correlation(self.theta, r)
            out.append(Candidate(Term("ratio_error"), f"residual correlates with the output angle (r = {corr:+.3f}) "
                                                      f"over {self.revolutions:.3g} revolutions", statistic=corr))
        if not any(t.effect == "hysteresis" for t in fit.terms) and self.reversals.size:
            side = -np.sign(np.diff(self.commanded_urad, prepend=self.commanded_urad[0]))
            gap = float(np.mean(r[side > 0]) - np.mean(r[side < 0])) if (side > 0).any() and (side < 0).any() else 0.0
            h0 = max(0.5 * abs(gap), 1e-3 * math.sqrt(sigma2))
            out.append(Candidate(Term("hysteresis", params=(h0,)),
                                 f"the output turns back {self.reversals.size} times; residual moving back minus moving "
                                 f"forward: {gap:+.3g} urad (a backlash of half-width h gives +2h)", statistic=gap))
        if not any(t.effect == "tooth_pulse" for t in fit.terms):
            best = self._pulse_search(r)
            if best is not None:
                shaft, angle, width, amplitude, drop = best
                out.append(Candidate(Term("tooth_pulse", variable=shaft.name, order=shaft.order, params=(angle, width)),
                                     f"the residual averaged over each turn of the {shaft.name} shaft holds a pulse of "
                                     f"{amplitude:+.3g} urad at {angle:.1f} deg, {width:g} deg wide (drop {drop / sigma2:.1f} "
                                     "x noise variance)", statistic=drop / sigma2))
        return out

    def _sideband_of(self, order: float):
        """(mesh, shaft) when ``order`` is a mesh order (or its second harmonic) +- a shaft order."""
        best = None
        for mesh in self.declared:
            if mesh.kind != "mesh":
                continue
            for shaft in self.shafts:
                for sign in (-1.0, 1.0):
                    miss = abs(order - (mesh.order + sign * shaft.order))
                    if miss <= 0.5 * self.resolution and (best is None or miss < best[0]):
                        best = (miss, mesh, shaft)
        return None if best is None else best[1:]

    def _pulse_search(self, r: np.ndarray):
        """The strongest once-per-turn pulse of any shaft in the residual: (shaft, angle deg, width
        deg, amplitude, drop in the sum of squares), from the residual's synchronous average over
        each shaft's turn (:data:`PULSE_BINS` bins) matched with raised cosines of
        :data:`PULSE_WIDTHS_DEG` at every bin; None when no shaft has bins enough samples."""
        best = None
        rc = r - r.mean()
        centres = (np.arange(PULSE_BINS) + 0.5) * 360.0 / PULSE_BINS
        for shaft in self.shafts:
            if self.revolutions * shaft.order < 1.0:
                continue  # (a shaft that does not turn once has no synchronous average)
            phase = np.mod(np.degrees(shaft.order * self.theta), 360.0)
            index = np.minimum((phase * PULSE_BINS / 360.0).astype(int), PULSE_BINS - 1)
            counts = np.bincount(index, minlength=PULSE_BINS).astype(float)
            if counts.min() < 2:
                continue
            sums = np.bincount(index, weights=rc, minlength=PULSE_BINS)
            for width in PULSE_WIDTHS_DEG:
                offsets = fx.wrap_deg(centres - 180.0)
                kernel = np.where(np.abs(offsets) < 0.5 * width, 0.5 * (1 + np.cos(2 * np.pi * offsets / width)), 0.0)
                kernel = np.roll(kernel, -PULSE_BINS // 2)  # centred on bin 0, for circular correlation
                # sum over samples of r * p and of p^2 for a pulse centred at each bin (p from the bin centres)
                rp = np.real(np.fft.ifft(np.fft.fft(sums) * np.conj(np.fft.fft(kernel))))
                pp = np.real(np.fft.ifft(np.fft.fft(counts) * np.conj(np.fft.fft(kernel ** 2))))
                drop = np.where(pp > 0, rp * rp / np.maximum(pp, 1e-300), 0.0)
                j = int(np.argmax(drop))
                if best is None or drop[j] > best[4]:
                    best = (shaft, float(centres[j]), width, float(rp[j] / pp[j]), float(drop[j]))
        return best

    # ---------------------------------------------------------------- refine, judge, report
    def polish(self, fit: ModelFit) -> ModelFit:
        """Refine harmonic orders (jointly, :meth:`PreloadModel.polish`) and each tooth pulse's angle
        and width (the other terms fitted with it, by variable projection)."""
        fit = super().polish(fit)
        # (only a pulse just added, alone or in a pair: one already in the model was refined then)
        idx = [i for i, t in enumerate(fit.terms) if t.effect == "tooth_pulse" and i >= len(fit.terms) - 2]
        if not idx:
            return fit
        terms = list(fit.terms)
        for i in idx:
            terms[i] = self._refine_pulse(tuple(terms), i)
        return self.fit(tuple(terms), start=fit)

    def _refine_pulse(self, terms: tuple[Term, ...], i: int) -> Term:
        """Term ``i`` (a tooth pulse) with the angle and width that remove most with the rest fitted."""
        from scipy.optimize import minimize

        term = terms[i]
        others = terms[:i] + terms[i + 1:]
        base = self.fit(others)
        r = base.residual
        X, _ = self._columns(tuple(base.terms)) if self._one_block else (None, None)
        if X is None:  # (a streamed record: the pulse is refined on every fourth sample)
            rows = slice(None, None, 4)
            X = self._design(base.terms, rows)
            r = r[rows]
            theta = self.theta[rows]
        else:
            theta = self.theta
        norms = np.sqrt(np.einsum("ij,ij->j", X, X))
        Xs = X / np.where(norms > 0, norms, 1.0)
        G_inv = np.linalg.pinv(Xs.T @ Xs)

        def minus_drop(p):
            angle, width = p
            if not 0.2 < width < 180.0:
                return 0.0
            col = fx.tooth_pulse(term.order * theta, angle, width)
            xb = Xs.T @ col
            m = float(col @ col - xb @ G_inv @ xb)
            g = float(col @ r)
            return -(g * g / m) if m > 0 else 0.0

        start = np.array(term.params, dtype=float)
        res = minimize(minus_drop, start, method="Nelder-Mead",
                       options={"xatol": 1e-3, "fatol": 1e-9 * max(abs(minus_drop(start)), 1e-300),
                                "initial_simplex": [start, start + [0.5 * start[1], 0.0], start + [0.0, 0.3 * start[1]]],
                                "maxiter": 200})
        angle, width = (res.x if res.fun <= minus_drop(start) else start)
        return replace(term, params=(float(np.mod(angle, 360.0)), float(width)))

    def degenerate(self, fit: ModelFit, index: int) -> str | None:
        reason = super().degenerate(fit, index)
        if reason:
            return reason
        term, v = fit.terms[index], fit.values[index]
        if term.effect == "hysteresis" and not v["half_width"] > 0:
            return "the output does not lag its input at the reversals: no backlash"
        return None

    def _occupied_orders(self, terms, skip: int | None = None) -> list[float]:
        return super()._occupied_orders(terms, skip) + [o for j, t in enumerate(terms) if t.effect == "sidebands"
                                                        and j != skip for o in (t.order - t.params[0], t.order + t.params[0])]

    def noise_readings(self, noise: NoiseEstimate) -> list[tuple[str, np.ndarray, float]]:
        return [(f"{self.meas.column('input_angle')} (urad)", self.meas.input_angle_rad * 1e6, noise.channels["input_angle"]),
                (f"{self.meas.column('angle')} (urad)", self.meas.angle_rad * 1e6, noise.channels["output_angle"])]

    def implausible(self, fit: ModelFit, index: int) -> str | None:
        """Why term ``index``'s parameters are physically absurd for this record, or None."""
        term, v = fit.terms[index], fit.values[index]
        span = float(np.ptp(self.x))
        if term.effect == "hysteresis" and 2.0 * v["half_width"] >= span:
            return (f"a backlash of {2 * v['half_width']:.4g} urad is wider than the whole range of the transmission "
                    f"error ({span:.4g} urad)")
        if term.effect == "tooth_pulse" and not 0.0 < v["width_deg"] < 360.0:
            return f"a pulse {v['width_deg']:.4g} deg wide is no pulse within one turn"
        if term.effect == "ratio_error" and not v["relative"] > -1.0:
            return f"a relative ratio error of {v['relative']:.4g} makes the ratio zero or negative"
        return None

    def entry(self, fit: ModelFit, i: int) -> dict:
        term, v = fit.terms[i], fit.values[i]
        if term.effect == "harmonic":
            return super().entry(fit, i)
        if term.effect == "drift":
            return {"effect": "drift", **v, "variable": "temperature_C" if term.variable == "temperature" else "time_s"}
        if term.effect == "ratio_error":
            return {"effect": "ratio_error", "relative": v["relative"],
                    "measured_ratio": self.meas.model.ratio * (1.0 + v["relative"]),
                    "law": "TE = -relative * output angle (urad): the input turns (1 + relative) x the declared ratio"}
        if term.effect == "sidebands":
            return {"effect": "sidebands", **v, "phase_convention": "each line amplitude * cos(order * output_angle - phase)"}
        if term.effect == "tooth_pulse":
            return {"effect": "tooth_pulse", **v,
                    "law": "amplitude * (1 + cos(2 pi d / width)) / 2 for |d| < width / 2, d the shaft's angle from "
                           "angle_deg (urad)"}
        return {"effect": "hysteresis", "half_width": v["half_width"], "backlash_urad": 2.0 * v["half_width"],
                "law": "play operator of half-width h between the commanded angle (input / ratio) and the output: "
                       "backlash at reversals (urad at the output)"}
