"""Declared models and their extension by library effects, fitted jointly by least squares.

``preload_trace`` (residual in um of carriage position, against output angle theta in rad)::

    x = c0 + sum_declared [a_q cos(q theta) + b_q sin(q theta)]          declared
          + sum_harmonics [...]  + c_d (v - mean v)                         effects, linear
    measured = play_h[x]   when hysteresis is added (friction on the carriage)

All linear coefficients are solved together; harmonic orders are refined by variable
projection; the hysteresis half-width is fitted with the linear coefficients by Gauss-Newton on
the play operator's local linear structure (``play = x[source] + side*h``).

``torque_deflection`` (residual in Nm of torque, against output rotation)::

    T = law(phi) + stiffening(phi) + drift + (T_s - play_h[T_s])
    phi = dead_zone(rotation - theta0, w)

``law`` is :class:`geargen.core.drive.TwoPathDrive` (Eqs. 2-6) built from the fitted k1, k2, k3,
preload; the contract's Nm/rad and Nm are turned into the law's N*mm/rad and N*mm in
:func:`law_torque_Nm` and nowhere else. T_s is the measured torque smoothed along time (the
applied torque without its noise), the input of the friction play. All parameters are fitted
together with :func:`scipy.optimize.least_squares`; weak priors (one unit of noise per factor
e of a stiffness) keep the law's parameters the data cannot see (a path that never unloads)
at their declared values instead of letting them wander.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares

from geargen.core.drive import TwoPathDrive
from geargen.fit import effects as fx
from geargen.fit.measurement import Measurement, MeasurementError, PreloadModelSpec, TorqueModelSpec
from geargen.fit.noise import NoiseEstimate
from geargen.fit.orders import TrainOrder, attribute_order, declared_orders, train_orders
from geargen.fit.periodogram import ls_periodogram, peaks

NM_PER_NMM = 1e-3
#: stiffening exponents are fitted in (EXPONENT_MIN, EXPONENT_MIN + EXPONENT_SPAN): Hertzian contact
#: laws lie there (line contact ~1.1, point contact 1.5); below ~1.1 a power law cannot be told
#: from the declared law's straight lines over a finite load range
EXPONENT_MIN = 1.1
EXPONENT_SPAN = 2.9
#: exponents a new stiffening is also started from (Hertzian line and point contact, and steeper)
STIFFENING_STARTS = (1.25, 1.5, 2.0, 3.0)
#: a dead band must be at least this many times as wide as one reading's uncertainty of the
#: rotation at zero torque, or the record shows no flat zone (TorqueModel.degenerate)
DEAD_BAND_RESOLUTION = 2.0


@dataclass(frozen=True)
class Term:
    """One library effect in a model: ``effect`` name; ``variable`` for drift ("temperature" or
    "time") or the shaft of a tooth pulse or of sidebands; ``order`` for a harmonic (per output
    revolution) or the mesh order of sidebands; ``params`` the parameters that shape its columns
    (a tooth pulse's angle and width, the sidebands' shaft order, a backlash's half-width)."""

    effect: str
    variable: str = ""
    order: float = 0.0
    params: tuple = ()

    @property
    def label(self) -> str:
        if self.effect == "harmonic":
            return f"harmonic at order {self.order:.4f}"
        if self.effect == "drift":
            return f"drift with {self.variable}"
        if self.effect == "sidebands":
            return f"sidebands of order {self.order:.4g} at +-{self.params[0]:.4g} ({self.variable})"
        if self.effect == "tooth_pulse":
            return f"tooth pulse on the {self.variable} shaft at {self.params[0]:.1f} deg"
        return self.effect


class ModelFit:
    """A fitted model. ``prediction``/``residual`` (n,) over all samples; ``rss`` over the fitted
    samples (the mask); ``n_params`` counts the declared and effect parameters;
    ``contributions`` (one (n,) array per term) is what each effect adds to the prediction;
    ``values`` (one dict per term) its parameters in the contract's names; ``state`` internal
    parameters for warm starts.

    The arrays are either given, or made on first use by ``arrays`` (an object with
    ``prediction()``, ``residual()`` and ``contribution(index)``): a fit of a long record then
    costs memory only once its arrays are asked for. ``prediction`` and ``residual`` are kept
    once made; each contribution is made anew when asked for (they are asked for once or twice).
    """

    def __init__(self, terms: tuple[Term, ...], rss: float, n_fitted: int, n_params: int, values: tuple[dict, ...],
                 declared_values: dict, state: dict | None = None, success: bool = True, message: str = "",
                 prediction: np.ndarray | None = None, residual: np.ndarray | None = None,
                 contributions: tuple[np.ndarray, ...] | None = None, arrays=None):
        self.terms = tuple(terms)
        self.rss = rss
        self.n_fitted = n_fitted
        self.n_params = n_params
        self.values = tuple(values)
        self.declared_values = declared_values
        self.state = state if state is not None else {}
        self.success = success
        self.message = message
        self._prediction = prediction
        self._residual = residual
        self._contributions = tuple(contributions) if contributions is not None else None
        self._arrays = arrays

    @property
    def prediction(self) -> np.ndarray:
        if self._prediction is None:
            self._prediction = self._arrays.prediction()
        return self._prediction

    @property
    def residual(self) -> np.ndarray:
        if self._residual is None:  # (the prediction made on the way is not kept unless asked for)
            prediction = self._prediction if self._prediction is not None else self._arrays.prediction()
            self._residual = self._arrays.residual(prediction)
        return self._residual

    @property
    def arrays_kept(self) -> bool:
        """True when the prediction or the residual is held in memory."""
        return self._prediction is not None or self._residual is not None

    def release(self) -> None:
        """Let go of the prediction and residual when they can be made again (a streamed fit)."""
        if self._arrays is not None and getattr(self._arrays, "remakeable", False):
            self._prediction = self._residual = None

    @property
    def contributions(self):
        if self._contributions is not None:
            return self._contributions
        return _Contributions(self._arrays, len(self.terms))

    @property
    def rms(self) -> float:
        return float(np.sqrt(np.mean(self.residual ** 2)))


class _Contributions:
    """The contributions of a fit's terms, each made when asked for: ``fit.contributions[i]``."""

    def __init__(self, arrays, count: int):
        self._arrays = arrays
        self._count = count

    def __len__(self) -> int:
        return self._count

    def __getitem__(self, index: int) -> np.ndarray:
        if not -self._count <= index < self._count:
            raise IndexError(index)
        return self._arrays.contribution(index % self._count)

    def __iter__(self):
        return (self[i] for i in range(self._count))


@dataclass(frozen=True)
class Candidate:
    """An effect to try next, with the evidence that suggested it and a start for its parameters."""

    term: Term
    evidence: str
    start: dict = field(default_factory=dict)
    statistic: float = 0.0


#: condition number of the column-scaled normal equations above which they are not trusted
CONDITION_LIMIT = 1e10


def solve_linear(X: np.ndarray, y: np.ndarray, mask: np.ndarray | None = None) -> np.ndarray:
    """Least-squares coefficients (p,) of y (n,) on the columns of X (n, p), over ``mask`` rows.

    Normal equations with the columns scaled to unit norm (fast for n >> p, and accurate here:
    the columns are sinusoids, centred drifts and play structure, far from collinear); falls
    back to an SVD solution when they are ill-conditioned.
    """
    if mask is not None and not mask.all():
        X, y = X[mask], y[mask]
    G = X.T @ X
    b = X.T @ y
    coef = _solve_normal(G, b)
    return coef if coef is not None else np.linalg.lstsq(X, y, rcond=None)[0]


def _solve_normal(G: np.ndarray, b: np.ndarray) -> np.ndarray | None:
    """Solution of the column-scaled normal equations, or None when they are ill-conditioned."""
    norms = np.sqrt(np.diag(G))
    norms = np.where(norms > 0, norms, 1.0)
    Gs = G / np.outer(norms, norms)
    try:
        if np.linalg.cond(Gs) < CONDITION_LIMIT:
            return np.linalg.solve(Gs, b / norms) / norms
    except np.linalg.LinAlgError:
        pass
    return None


def _condition(G: np.ndarray) -> float:
    """Condition number of a normal matrix with its columns scaled to unit norm."""
    norms = np.sqrt(np.diag(G))
    norms = np.where(norms > 0, norms, 1.0)
    try:
        return float(np.linalg.cond(G / np.outer(norms, norms)))
    except np.linalg.LinAlgError:
        return math.inf


def mask_or_all(mask, n):
    return np.ones(n, bool) if mask is None else np.asarray(mask, bool)


def drift_variable(meas: Measurement, variable: str) -> np.ndarray:
    return meas.temperature_C if variable == "temperature" else meas.time_s


def drift_terms(meas: Measurement) -> list[Term]:
    """Drift with temperature when the file has a temperature column, and always with time."""
    out = [Term("drift", "time")]
    if meas.temperature_C is not None and np.ptp(meas.temperature_C) > 0:
        out.insert(0, Term("drift", "temperature"))
    return out


def drift_value(variable: str, rate: float) -> dict:
    return {"per_kelvin": rate} if variable == "temperature" else {"per_second": rate}


# ======================================================================== preload trace

#: Rows of a design matrix made at a time. A record of at most this many rows is fitted from one
#: block, whose columns are kept between fits (as fast as one matrix); a longer record is
#: streamed through blocks: normal equations, Gram matrices and products are summed block by
#: block, so the fit holds a few arrays of the record's length, never (rows x columns) ones.
ROW_BLOCK = 1 << 17


class _PreloadArrays:
    """Makes the arrays of one preload fit when they are asked for (see :class:`ModelFit`)."""

    def __init__(self, model: "PreloadModel", terms, coef, half_width: float, hysteresis: bool):
        self.model, self.terms, self.coef, self.h, self.hysteresis = model, terms, coef, half_width, hysteresis
        self.remakeable = not model._one_block

    def equilibrium(self) -> np.ndarray:
        return self.model._predict(self.terms, self.coef)

    def prediction(self) -> np.ndarray:
        m = self.equilibrium()
        return fx.play_operator(m, self.h) if self.hysteresis else m

    def residual(self, prediction: np.ndarray) -> np.ndarray:
        return self.model.x - prediction

    def contribution(self, index: int) -> np.ndarray:
        if self.terms[index].effect == "hysteresis":
            m = self.equilibrium()
            return fx.play_operator(m, self.h) - m
        sl = self.model._slices(self.terms)[index]
        return self.model._predict(self.terms, self.coef, columns=sl)


class PreloadModel:
    """Declared sinusoids at the train's shaft and mesh orders, plus library effects."""

    kind = "preload_trace"

    def __init__(self, meas: Measurement, noise: NoiseEstimate):
        spec: PreloadModelSpec = meas.model
        self._setup(meas, noise, meas.carriage_um, train_orders(spec.teeth), declared_orders(spec.teeth, spec.declared))

    def _setup(self, meas: Measurement, noise: NoiseEstimate, signal: np.ndarray, train: tuple[TrainOrder, ...],
               declared: tuple[TrainOrder, ...]) -> None:
        """What every model of sinusoids against the output angle holds: the signal fitted, the
        train's orders and the declared ones, the order range the residual spectrum covers."""
        self.meas = meas
        self.noise = noise
        self.theta = meas.angle_rad
        self.x = signal
        self.n = meas.samples
        self.train: tuple[TrainOrder, ...] = train
        self.declared: tuple[TrainOrder, ...] = declared
        revs = float(np.ptp(self.theta)) / (2 * math.pi)
        self.revolutions = max(revs, 1e-9)
        self.resolution = 1.0 / self.revolutions
        top = max([t.order for t in self.train])
        per_rev = self.n / max(self.revolutions, 1e-9)
        self.order_min = 0.9 * self.resolution
        self.order_max = max(min(2.2 * top, 0.25 * per_rev), 4 * self.order_min)
        self._base = None
        self._cache: dict = {}
        self._columns_cache: dict = {}
        self._means: dict = {}

    # ---------------------------------------------------------------- design, in row blocks
    @property
    def _one_block(self) -> bool:
        return self.n <= ROW_BLOCK

    def _blocks(self):
        """Row slices covering the record, :data:`ROW_BLOCK` rows each."""
        return [slice(lo, min(lo + ROW_BLOCK, self.n)) for lo in range(0, self.n, ROW_BLOCK)]

    def _drift_mean(self, variable: str) -> float:
        if variable not in self._means:
            self._means[variable] = drift_variable(self.meas, variable).mean()
        return self._means[variable]

    def _width(self, term: Term) -> int:
        return 2 if term.effect == "harmonic" else 1 if term.effect == "drift" else 0

    def _slices(self, terms) -> list[slice]:
        out, width = [], 1 + 2 * len(self.declared)
        for term in terms:
            out.append(slice(width, width + self._width(term)))
            width += self._width(term)
        return out

    def _term_rows(self, term: Term, rows) -> np.ndarray:
        """A term's columns at the given rows (a slice or an index array)."""
        if term.effect == "harmonic":
            return fx.harmonic_basis(self.theta[rows], term.order)
        if term.effect == "drift":
            v = drift_variable(self.meas, term.variable)
            return (v[rows] - self._drift_mean(term.variable))[:, None]
        return np.zeros((self.theta[rows].shape[0], 0))

    def _base_rows(self, rows) -> np.ndarray:
        theta = self.theta[rows]
        cols = [np.ones(theta.size)]
        for t in self.declared:
            cols.extend(fx.harmonic_basis(theta, t.order).T)
        return np.column_stack(cols)

    def _design(self, terms, rows, extra: np.ndarray | None = None) -> np.ndarray:
        """Columns (offset, declared sinusoids, then each term's, then ``extra`` if given) at the
        given rows: a slice or an index array. For a one-block record the whole matrix is made
        once and kept; otherwise each block is filled in place, column by column."""
        if self._one_block:
            X, _ = self._columns(tuple(terms))
            return X[rows] if extra is None else np.column_stack([X[rows], extra])
        theta = self.theta[rows]
        width = 1 + 2 * len(self.declared) + sum(self._width(t) for t in terms)
        X = np.empty((theta.size, width + (extra is not None)), order="F")
        X[:, 0] = 1.0
        phase = np.empty(theta.size)
        col = 1
        orders = [t.order for t in self.declared]
        for q in orders:
            np.multiply(q, theta, out=phase)
            np.cos(phase, out=X[:, col])
            np.sin(phase, out=X[:, col + 1])
            col += 2
        for term in terms:
            if term.effect == "harmonic":
                np.multiply(term.order, theta, out=phase)
                np.cos(phase, out=X[:, col])
                np.sin(phase, out=X[:, col + 1])
                col += 2
            elif term.effect == "drift":
                v = drift_variable(self.meas, term.variable)
                np.subtract(v[rows], self._drift_mean(term.variable), out=X[:, col])
                col += 1
            elif self._width(term):
                term_width = self._width(term)
                X[:, col:col + term_width] = self._term_rows(term, rows)
                col += term_width
        if extra is not None:
            X[:, col] = extra
        return X

    def _base_columns(self) -> np.ndarray:
        """Offset and declared sinusoids, (n, 1 + 2 x declared orders); one-block records only."""
        if self._base is None:
            self._base = self._base_rows(slice(None))
        return self._base

    def _term_columns(self, term: Term) -> np.ndarray:
        key = term
        if key not in self._cache:
            if len(self._cache) > 64:
                self._cache.clear()
            self._cache[key] = self._term_rows(term, slice(None))
        return self._cache[key]

    def _columns(self, terms: tuple[Term, ...]):
        key = tuple(terms)
        hit = self._columns_cache.get(key)
        if hit is None:
            hit = self._build_columns(terms)
            if len(self._columns_cache) >= 6:
                self._columns_cache.pop(next(iter(self._columns_cache)))
            self._columns_cache[key] = hit
        return hit

    def _build_columns(self, terms: tuple[Term, ...]):
        base = self._base_columns()
        blocks = [base]
        slices = []
        width = base.shape[1]
        for term in terms:
            c = self._term_columns(term)
            blocks.append(c)
            slices.append(slice(width, width + c.shape[1]))
            width += c.shape[1]
        return (np.hstack(blocks) if len(blocks) > 1 else base), slices

    def _predict(self, terms, coef, columns: slice | None = None) -> np.ndarray:
        """X @ coef over all samples (n,), or the part of it from ``columns`` alone."""
        coef = np.asarray(coef)
        if self._one_block:
            X, _ = self._columns(tuple(terms))
            return X @ coef if columns is None else X[:, columns] @ coef[columns]
        out = np.empty(self.n)
        for rows in self._blocks():
            X = self._design(terms, rows)
            out[rows] = X @ coef if columns is None else X[:, columns] @ coef[columns]
        return out

    def _solve(self, make, mask) -> np.ndarray:
        """Least squares of the carriage on the columns ``make(rows)`` over the masked rows.

        One block: :func:`solve_linear` itself. Several: the normal equations summed block by
        block; if they are ill-conditioned, the R factor of the QR decomposition of [A | y] is
        built block by block (each block's rows stacked under the R so far) and the problem
        solved on it, which is the least-squares problem on A itself.
        """
        if self._one_block:
            return solve_linear(make(slice(None)), self.x, mask)
        G = b = None
        for rows in self._blocks():
            A, y = make(rows), self.x[rows]
            if mask is not None and not mask[rows].all():
                A, y = A[mask[rows]], y[mask[rows]]
            G = A.T @ A if G is None else G + A.T @ A
            b = A.T @ y if b is None else b + A.T @ y
        coef = _solve_normal(G, b)
        if coef is not None:
            return coef
        R = None
        for rows in self._blocks():
            A = np.column_stack([make(rows), self.x[rows]])
            if mask is not None:
                A = A[mask[rows]]
            R = np.linalg.qr(A if R is None else np.vstack([R, A]), mode="r")
        p = G.shape[0]
        return np.linalg.lstsq(R[:p, :p], R[:p, p], rcond=None)[0]

    def _gram(self, make, mask=None) -> np.ndarray:
        """Sum over the (masked) rows of A^T A for the columns ``make(rows)``."""
        G = None
        for rows in (self._blocks() if not self._one_block else [slice(None)]):
            A = make(rows)
            if mask is not None and not mask[rows].all():
                A = A[mask[rows]]
            G = A.T @ A if G is None else G + A.T @ A
        return G

    def _rss(self, prediction: np.ndarray, mask) -> float:
        """Sum over the masked samples of (carriage - prediction)^2 (block by block when long)."""
        if self._one_block:
            return float(np.sum((self.x - prediction)[mask] ** 2))
        total = 0.0
        for rows in self._blocks():
            part = (self.x[rows] - prediction[rows])[mask[rows]]
            total += float(part @ part)
        return total

    # ---------------------------------------------------------------- stages
    def nominal(self) -> np.ndarray:
        """Ideal gears: the carriage stays at its mean position."""
        return self.x - self.x.mean()

    def fit(self, terms: tuple[Term, ...], mask=None, start: ModelFit | None = None, extra: dict | None = None) -> ModelFit:
        terms = tuple(terms)
        whole = mask is None
        mask = mask_or_all(mask, self.n)
        slices = self._slices(terms)
        hyst = [i for i, t in enumerate(terms) if t.effect == "hysteresis"]
        if not terms and whole:
            self._check_declared_design()
        coef = self._solve(lambda rows: self._design(terms, rows), mask)
        h = 0.0
        message = "linear least squares"
        success = True
        if hyst:
            h0 = None
            if extra and "half_width" in extra:
                h0 = extra["half_width"]
            elif start is not None and "half_width" in start.state:
                h0 = start.state["half_width"]
            coef, h, success, message = self._fit_play(terms, coef, mask, h0)
        arrays = _PreloadArrays(self, terms, coef, h, bool(hyst))
        prediction = arrays.prediction()
        if self._one_block:
            residual = self.x - prediction
            rss = float(np.sum(residual[mask] ** 2))
        else:  # made again when asked for: most fits are only compared by their rss
            rss = self._rss(prediction, mask)
            prediction = residual = None
        values = [self._term_values(term, coef[slices[i]], h) for i, term in enumerate(terms)]
        declared_values = {"offset": float(coef[0])}
        for j, t in enumerate(self.declared):
            amp, ph = fx.harmonic_parameters(coef[1 + 2 * j], coef[2 + 2 * j])
            declared_values[t.name] = {"order": t.order, "amplitude": amp, "phase_deg": ph}
        width = 1 + 2 * len(self.declared) + sum(self._width(t) for t in terms)
        n_params = width + sum(1 for t in terms if t.effect == "harmonic") + len(hyst)
        return ModelFit(terms=terms, rss=rss, n_fitted=int(mask.sum()), n_params=n_params, values=tuple(values),
                        declared_values=declared_values,
                        state={"coef": coef, "half_width": h, "slices": slices, "mask": mask},
                        success=success, message=message, prediction=prediction, residual=residual, arrays=arrays)

    def _term_values(self, term: Term, coef: np.ndarray, half_width: float) -> dict:
        """A term's parameters (contract names) from its fitted coefficients."""
        if term.effect == "hysteresis":
            return {"half_width": half_width}
        if term.effect == "harmonic":
            amp, ph = fx.harmonic_parameters(*coef)
            return {"order": term.order, "amplitude": amp, "phase_deg": ph}
        return drift_value(term.variable, float(coef[0]))

    def _check_declared_design(self) -> None:
        """The recorded output angles must tell the declared sinusoids and the offset apart."""
        cond = _condition(self._gram(lambda rows: self._design((), rows)))
        if cond >= CONDITION_LIMIT:
            raise MeasurementError(
                self.meas.where("angle"),
                f"the recorded output angles cannot tell the declared orders "
                f"({', '.join(f'{t.order:.4g}' for t in self.declared)}) and the offset apart: their sinusoids are "
                f"linearly dependent over these angles (condition number {cond:.3g})",
                "angles spread over the turn, as a trace turned through one or more revolutions has")

    def equilibrium(self, fit: ModelFit) -> np.ndarray:
        """The model carriage before the play (the prediction itself without hysteresis); made
        anew, and not kept, for a streamed fit."""
        if any(t.effect == "hysteresis" for t in fit.terms) or not self._one_block:
            return self._predict(fit.terms, fit.state["coef"])
        return fit.prediction

    def _fit_play(self, terms, coef, mask, h0):
        """Gauss-Newton on (linear coefficients, h) using the play's local structure."""
        x = self.x
        if h0 is None:  # the side the play takes as h grows from 0 gives h's first estimate
            side = fx.play_structure(self._predict(terms, coef), 0.0)[2]
            sol = self._solve(lambda rows: self._design(terms, rows, extra=side[rows]), mask)
            coef, h0 = sol[:-1], max(float(sol[-1]), 0.0)
            if h0 == 0.0:
                h0 = 0.1 * self.noise.rms
        h = float(h0)

        def rss_of(c, hh, m=None):
            m = self._predict(terms, c) if m is None else m
            return self._rss(fx.play_operator(m, hh), mask)

        rss = rss_of(coef, h)
        converged = False
        for _ in range(60):
            m = self._predict(terms, coef)
            src, side = fx.play_structure(m, h)[1:]
            sol = self._solve(lambda rows: self._design(terms, src[rows], extra=side[rows]), mask)
            del src, side
            d_coef, d_h = sol[:-1] - coef, float(sol[-1]) - h
            # a long record's line search moves along X d_coef, made once, not through the columns again
            dm = None if self._one_block else self._predict(terms, d_coef)
            step = 1.0
            while step > 1e-3:
                c_new, h_new = coef + step * d_coef, max(h + step * d_h, 0.0)
                r_new = rss_of(c_new, h_new, None if dm is None else m + step * dm)
                if r_new <= rss * (1 + 1e-12):
                    break
                step *= 0.5
            else:
                converged = True
                break
            improvement = rss - r_new
            coef, h, rss = c_new, h_new, r_new
            if improvement <= 1e-10 * max(rss, 1e-300):
                converged = True
                break
        return coef, h, True, "Gauss-Newton on the play structure" + ("" if converged else " (iteration limit)")

    def contribution_noise(self, fit: ModelFit, index: int) -> float:
        """Mean square by which noise alone moves term ``index``'s contribution in this fit:
        ``trace(C Cov C^T) / n`` with ``Cov = sigma^2 (J^T J)^-1`` over the fitted samples, J the
        prediction's Jacobian w.r.t. (coefficients[, h]) and C the contribution's, both from the
        model's (locally) linear structure (the play: ``y = m[source] + side * h``). Only the
        Gram matrices J^T J and C^T C are formed, block by block."""
        terms, coef, h, mask = fit.terms, fit.state["coef"], fit.state["half_width"], fit.state["mask"]
        hyst = any(t.effect == "hysteresis" for t in terms)
        width = 1 + 2 * len(self.declared) + sum(self._width(t) for t in terms)
        if not hyst:
            sl = fit.state["slices"][index]

            def jacobians(rows):
                X = self._design(terms, rows)
                return X, X[:, sl]
            JtJ, CtC = self._two_grams(jacobians, mask)
            return contribution_noise_gram(JtJ, CtC, self.n, self.noise.rms, np.arange(width)[sl])
        src, side = fx.play_structure(self._predict(terms, coef), h)[1:]
        if terms[index].effect == "hysteresis":
            cols = None

            def jacobians(rows):
                J = self._design(terms, src[rows], extra=side[rows])
                return J, np.column_stack([J[:, :-1] - self._design(terms, rows), side[rows]])
        else:
            sl = fit.state["slices"][index]
            cols = np.arange(width + 1)[sl]

            def jacobians(rows):
                return self._design(terms, src[rows], extra=side[rows]), self._design(terms, rows)[:, sl]
        JtJ, CtC = self._two_grams(jacobians, mask)
        return contribution_noise_gram(JtJ, CtC, self.n, self.noise.rms, cols)

    def _two_grams(self, make, mask) -> tuple[np.ndarray, np.ndarray]:
        """(J^T J over the masked rows, C^T C over all rows) for ``make(rows) -> (J, C)`` blocks."""
        JtJ = CtC = None
        for rows in (self._blocks() if not self._one_block else [slice(None)]):
            J, C = make(rows)
            if not mask[rows].all():
                J = J[mask[rows]]
            JtJ = J.T @ J if JtJ is None else JtJ + J.T @ J
            CtC = C.T @ C if CtC is None else CtC + C.T @ C
        return JtJ, CtC

    # ---------------------------------------------------------------- effects
    def periodogram(self, residual: np.ndarray):
        return ls_periodogram(self.theta, residual, self.order_min, self.order_max, offset=residual.mean())

    def model_orders(self, terms) -> list[float]:
        return [t.order for t in self.declared] + [t.order for t in terms if t.effect == "harmonic"]

    def refine_order(self, fit: ModelFit, order: float, half_width: float) -> tuple[float, float]:
        """Order near ``order`` where a new sinusoid, fitted jointly with the current model's
        linear part (projection on the complement of its columns), removes most."""
        from scipy.optimize import minimize_scalar

        terms = tuple(t for t in fit.terms if t.effect != "hysteresis")
        r = fit.residual
        if self._one_block:
            X, _ = self._columns(terms)
            norms = np.sqrt(np.einsum("ij,ij->j", X, X))
            Xs = X / np.where(norms > 0, norms, 1.0)
            G_inv = np.linalg.pinv(Xs.T @ Xs)

            def sums(q):
                B = fx.harmonic_basis(self.theta, q)
                return Xs.T @ B, B.T @ r, B.T @ B
        else:
            G = self._gram(lambda rows: self._design(terms, rows))
            norms = np.sqrt(np.diag(G))
            norms = np.where(norms > 0, norms, 1.0)
            G_inv = np.linalg.pinv(G / np.outer(norms, norms))

            def sums(q):
                XtB, g, BtB = 0.0, 0.0, 0.0
                for rows in self._blocks():
                    B = fx.harmonic_basis(self.theta[rows], q)
                    XtB = XtB + self._design(terms, rows).T @ B
                    g = g + B.T @ r[rows]
                    BtB = BtB + B.T @ B
                return XtB / norms[:, None], g, BtB

        def drop(q):
            XtB, g, BtB = sums(q)
            M = BtB - XtB.T @ G_inv @ XtB
            try:
                return float(g @ np.linalg.solve(M, g))
            except np.linalg.LinAlgError:
                return 0.0

        res = minimize_scalar(lambda q: -drop(q), bounds=(order - half_width, order + half_width), method="bounded",
                              options={"xatol": 1e-7 * max(1.0, order)})
        return float(res.x), drop(float(res.x))

    def spectrum_peaks(self, residual: np.ndarray, taken: list[float], count: int):
        """The ``count`` highest peaks of the residual's order spectrum away from the orders
        ``taken``: (order, drop in the sum of squares, amplitude) each. The peak order is
        interpolated on the grid (a parabola; the grid's step is resolution / 5); it is refined
        exactly, jointly with the model, once the candidate is the one being judged."""
        pg = self.periodogram(residual)
        step = float(pg.orders[1] - pg.orders[0]) if pg.orders.size > 1 else 0.0
        out = []
        for i in peaks(pg, count, exclude=taken, exclusion=0.5 * self.resolution):
            q = float(pg.orders[i])
            if 0 < i < pg.orders.size - 1:
                a, b, c = pg.reduction[i - 1], pg.reduction[i], pg.reduction[i + 1]
                den = a - 2 * b + c
                if den < 0:
                    q += 0.5 * step * (a - c) / den
            if not any(abs(q - o) <= 0.5 * self.resolution for o in taken):
                out.append((q, float(pg.reduction[i]), float(pg.amplitude[i])))
        return out

    def candidates(self, fit: ModelFit, count: int = 3) -> list[Candidate]:
        out: list[Candidate] = []
        r = fit.residual
        sigma = max(self.noise.rms, 1e-300)
        for q, drop, amplitude in self.spectrum_peaks(r, self.model_orders(fit.terms), count):
            where = attribute_order(q, self.train)
            src = f"{where[1]} x {where[0].name} (order {where[0].order:.4f})" if where else "no shaft or mesh"
            sigma2 = sigma ** 2
            power = drop / sigma2 if sigma2 >= np.finfo(float).tiny else drop / sigma / sigma  # sigma**2 may underflow
            out.append(Candidate(Term("harmonic", order=q),
                                 f"peak of the residual order spectrum at order {q:.4f} ({src}), amplitude "
                                 f"{amplitude:.3g} {self.meas.units}, power {power:.1f} x noise variance",
                                 statistic=power))
        present = {(t.effect, t.variable) for t in fit.terms}
        for term in drift_terms(self.meas):
            if ("drift", term.variable) in present:
                continue
            v = drift_variable(self.meas, term.variable)
            corr = sample_correlation(v, r)
            unit = "K" if term.variable == "temperature" else "s"
            out.append(Candidate(term, f"residual correlates with {term.variable} (r = {corr:+.3f}) over a range of "
                                       f"{np.ptp(v):.3g} {unit}", statistic=corr))
        if ("hysteresis", "") not in present:
            up, down = _means_by_direction(self.equilibrium(fit), r)
            if up is not None:
                gap = float(down - up)
                out.append(Candidate(Term("hysteresis"),
                                     f"residual while the model carriage moves down minus while it moves up: {gap:+.3g} "
                                     f"{self.meas.units} (friction lag gives +2h)", statistic=gap))
        return out

    def _occupied_orders(self, terms, skip: int | None = None) -> list[float]:
        """Orders the model's sinusoids sit at (declared, and harmonics other than term ``skip``)."""
        return [t.order for t in self.declared] + [t.order for j, t in enumerate(terms)
                                                   if t.effect == "harmonic" and j != skip]

    def degenerate(self, fit: ModelFit, index: int) -> str | None:
        """Why term ``index`` is no real effect although it fits, or None: a harmonic closer than
        half the record's order resolution (1 / revolutions) to an order already in the model
        (over one revolution orders 1 and 1.4 are nearly the same sinusoid, and a pair of them
        fits anything slow with two large amplitudes that cancel)."""
        term = fit.terms[index]
        if term.effect != "harmonic":
            return None
        others = self._occupied_orders(fit.terms, index)
        if not others:
            return None
        near = min(others, key=lambda o: abs(o - term.order))
        if abs(near - term.order) < 0.5 * self.resolution:
            return (f"order {term.order:.4f} is within half the record's order resolution ({self.resolution:.3g}: "
                    f"{self.revolutions:.3g} revolutions) of order {near:.4f}, already in the model: the record "
                    "cannot tell the two apart")
        return None

    def implausible(self, fit: ModelFit, index: int) -> str | None:
        """Why term ``index``'s parameters are physically absurd for this record, or None: a play
        wider than the whole range of the signal explains nothing (it never lets go)."""
        term, v = fit.terms[index], fit.values[index]
        span = float(np.ptp(self.x))
        if term.effect == "hysteresis" and 2.0 * v["half_width"] >= span:
            return (f"a play of full width {2 * v['half_width']:.4g} {self.meas.units} is wider than the whole range of "
                    f"the record ({span:.4g} {self.meas.units})")
        return None

    def noise_readings(self, noise: NoiseEstimate) -> list[tuple[str, np.ndarray, float]]:
        """(column, readings, noise level) of each measured channel, for the plausibility test."""
        return [(self.meas.column("carriage"), self.x, noise.channels["signal"])]

    def quick_gain(self, fit: ModelFit, term: Term) -> float | None:
        """Drop in the sum of squares a candidate gives to first order, or None when there is no
        cheap estimate. Hysteresis: the play at h -> 0+ adds ``h * side`` (side = -sign of the
        model carriage's motion), a linear column, projected off the current model's columns."""
        if term.effect != "hysteresis":
            return None
        terms = fit.terms
        m = self.equilibrium(fit)
        if self._one_block:
            side = -np.sign(np.diff(m, prepend=m[0]))
            X, _ = self._columns(tuple(terms))
            norms = np.sqrt(np.einsum("ij,ij->j", X, X))
            Xs = X / np.where(norms > 0, norms, 1.0)
            xs = Xs.T @ side
            G = Xs.T @ Xs
            side_sq, g = float(side @ side), float(side @ fit.residual)
        else:  # block by block: no full-length temporaries
            G = xs = 0.0
            side_sq = g = 0.0
            r = fit.residual
            for rows in self._blocks():
                lo = rows.start
                side = -np.sign(np.diff(m[rows], prepend=m[lo - 1] if lo else m[0]))
                X = self._design(terms, rows)
                G = G + X.T @ X
                xs = xs + X.T @ side
                side_sq += float(side @ side)
                g += float(side @ r[rows])
            norms = np.sqrt(np.diag(G))
            norms = np.where(norms > 0, norms, 1.0)
            xs = xs / norms
            G = G / np.outer(norms, norms)
        del m
        ss = float(side_sq - xs @ np.linalg.pinv(G) @ xs)
        return g * g / ss if ss > 0 else 0.0

    def polish(self, fit: ModelFit) -> ModelFit:
        """Refine every added harmonic's order with all others fitted jointly (variable projection)."""
        idx = [i for i, t in enumerate(fit.terms) if t.effect == "harmonic"]
        if not idx:
            return fit
        terms = list(fit.terms)
        for _ in range(1 if len(idx) == 1 else 2):
            for i in idx:
                others = tuple(t for j, t in enumerate(terms) if j != i)
                base = self.fit(others, start=fit)
                q, _ = self.refine_order(base, terms[i].order, 0.2 * self.resolution)
                terms[i] = Term("harmonic", order=q)
        return self.fit(tuple(terms), start=fit)

    def entry(self, fit: ModelFit, i: int) -> dict:
        """JSON entry (contract names) of the i-th term of a fit."""
        term, v = fit.terms[i], fit.values[i]
        if term.effect == "harmonic":
            where = attribute_order(v["order"], self.train)
            e = {"effect": "harmonic", "order": v["order"], "amplitude": v["amplitude"], "phase_deg": v["phase_deg"],
                 "shaft": where[0].name if where else None, "multiple": where[1] if where else None}
            if where:
                e["attribution"] = f"{where[1]} x {where[0].description} (order {where[0].order:.6g})"
            e["phase_convention"] = "amplitude * cos(order * output_angle - phase)"
            return e
        if term.effect == "drift":
            return {"effect": "drift", **v, "variable": "temperature_C" if term.variable == "temperature" else "time_s"}
        return {"effect": "hysteresis", "half_width": v["half_width"],
                "law": "play operator on the model carriage position (friction on the preload carriage)"}


def _means_by_direction(m: np.ndarray, r: np.ndarray, minimum: int = 10):
    """(mean of r where m rises, mean where it falls), None for both when either has <= minimum
    samples; block by block (no full-length temporaries)."""
    n = m.size
    if n <= ROW_BLOCK:
        direction = np.sign(np.diff(m, prepend=m[0]))
        up, down = r[direction > 0], r[direction < 0]
        return (up.mean(), down.mean()) if up.size > minimum and down.size > minimum else (None, None)
    sums = [0.0, 0.0]
    counts = [0, 0]
    for lo in range(0, n, ROW_BLOCK):
        hi = min(lo + ROW_BLOCK, n)
        d = np.diff(m[lo:hi], prepend=m[lo - 1] if lo else m[0])
        for k, sel in enumerate((d > 0, d < 0)):
            part = r[lo:hi][sel]
            sums[k] += float(part.sum())
            counts[k] += part.size
    if min(counts) <= minimum:
        return None, None
    return sums[0] / counts[0], sums[1] / counts[1]


# ======================================================================== torque deflection

def law_torque_Nm(drive_type: str, k1_Nm_per_rad: float, k2_Nm_per_rad: float, k3_Nm_per_rad: float | None,
                  preload_Nm: float, rotation_rad: np.ndarray) -> np.ndarray:
    """Drive torque (Nm) of the two-path law at output rotation(s) (rad): TwoPathDrive, converted once.

    TwoPathDrive works in N*mm and rad: stiffness Nm/rad x 1e3 = N*mm/rad, preload Nm x 1e3 = N*mm,
    torque N*mm x 1e-3 = Nm.
    """
    kw = {} if drive_type == "type1" else {"k3": k3_Nm_per_rad / NM_PER_NMM}
    drive = TwoPathDrive(drive_type, k1=k1_Nm_per_rad / NM_PER_NMM, k2=k2_Nm_per_rad / NM_PER_NMM,
                         preload=preload_Nm / NM_PER_NMM, **kw)
    return drive.torque(rotation_rad) * NM_PER_NMM


class TorqueModel:
    """The two-path law of the declared drive, plus library effects, fitted by least_squares."""

    kind = "torque_deflection"
    SMOOTH_HALF_WINDOW = 8

    def __init__(self, meas: Measurement, noise: NoiseEstimate):
        self.meas = meas
        self.noise = noise
        self.spec: TorqueModelSpec = meas.model
        self.T = meas.torque_Nm
        self.rot_urad = meas.rotation_rad * 1e6
        self.t = meas.time_s
        self.n = meas.samples
        self.type2 = self.spec.drive_type == "type2"
        self._cache: dict = {}
        self._kinds: dict = {}  # parameter names -> how each is transformed
        self._check_slope()
        # a torque the sampling does not resolve (a load stepped within a few samples) is not
        # smoothed: a line over 17 samples would round its steps off and overshoot its plateaus
        window = self.SMOOTH_HALF_WINDOW if (noise.resolved or {}).get("torque", True) else 0
        self.T_smooth = fx.driving_signal(self.t, self.T, noise.channels.get("torque", noise.rms), window)
        self.declared_start = self._declared_start()
        # the amplitude of the test each sample belongs to (geargen.fit.datasheet.split_tests): a
        # friction that grows with the cycle's amplitude scales with it
        from geargen.fit.datasheet import split_tests
        self.tests = split_tests(self.T_smooth, meas.test_nr)
        self.test_amplitude = np.empty(self.n)
        for _, rows in self.tests:
            self.test_amplitude[rows] = np.max(np.abs(self.T_smooth[rows])) if rows.size else 1.0
        self.reference_amplitude = float(np.max(self.test_amplitude))
        amplitudes = [float(np.max(np.abs(self.T_smooth[rows]))) for _, rows in self.tests if rows.size]
        # an amplitude-dependent friction needs tests of different amplitudes to be seen
        self.amplitudes_differ = len(amplitudes) >= 2 and max(amplitudes) >= 1.3 * min(amplitudes)
        # weighted least squares (effective variance): each residual over its noise level, relative
        # to the mean level, so that the rss stays in torque units and the noise of the fit is noise.rms
        variance = np.asarray(noise.variance, dtype=float)
        self.residual_scale = np.sqrt(np.maximum(variance, 1e-300) / max(float(np.mean(variance)), 1e-300))

    def _check_slope(self) -> None:
        """The torque must rise with the rotation where both paths carry it (|T| < 25 % of its
        peak): a drive is a spring. A falling or flat curve is a probe read with the wrong sign,
        or not a torque-deflection test; the two-path law cannot be fitted to it."""
        T, rot = self.T, self.rot_urad * 1e-6
        inner = np.abs(T) < 0.25 * np.max(np.abs(T))
        slope = _slope(rot[inner], T[inner]) if inner.sum() > 5 else _slope(rot, T)
        if not (math.isfinite(slope) and slope > 0):
            m = self.meas
            raise MeasurementError(
                f"{m.file}: columns {m.column('torque')}, {m.column('rotation')}",
                f"the torque does not rise with the rotation: its slope near zero torque is {slope:.3g} Nm/rad "
                "(is the rotation read with the wrong sign?)",
                "torque rising with rotation, as a drive's stiffness makes it")

    # ---------------------------------------------------------------- declared law
    def _declared_start(self) -> dict:
        s = self.spec
        if s.has_nominal:
            d = {"k1": s.k1_Nm_per_rad, "k2": s.k2_Nm_per_rad, "preload": s.preload_Nm, "theta0_urad": 0.0}
            if self.type2:
                d["k3"] = s.k3_Nm_per_rad
            return d
        # from the data: central slope gives k1 + k2, outer slopes the single-path stiffness
        T, rot = self.T, self.rot_urad * 1e-6
        tmax = np.max(np.abs(T))
        inner = np.abs(T) < 0.25 * tmax
        outer = np.abs(T) > 0.8 * tmax
        kd = _slope(rot[inner], T[inner]) if inner.sum() > 5 else tmax / max(np.ptp(rot), 1e-12)
        kb = _slope(np.abs(rot[outer]), np.abs(T[outer])) if outer.sum() > 5 else 0.5 * kd
        k1 = s.k1_Nm_per_rad or 0.5 * kd
        k2 = s.k2_Nm_per_rad or 0.5 * kd
        d = {"k1": k1, "k2": k2, "preload": s.preload_Nm if s.preload_Nm is not None else 0.3 * tmax, "theta0_urad": 0.0}
        if self.type2:
            if s.k3_Nm_per_rad is not None:
                d["k3"] = s.k3_Nm_per_rad
            else:
                d["k3"] = 1.0 / (1.0 / kb - 1.0 / k1) if 0 < kb < 0.95 * k1 else 10.0 * k1
        return d

    def _law(self, d: dict, phi_rad: np.ndarray) -> np.ndarray:
        return law_torque_Nm(self.spec.drive_type, d["k1"], d["k2"], d.get("k3"), d["preload"], phi_rad)

    def law_slope(self, fit: ModelFit, spread_urad: float = 0.0, rotation_urad: np.ndarray | None = None) -> np.ndarray:
        """rms dT/dtheta (Nm per urad) of ``fit``'s two-path law over the rotations the reading may
        stand for: each sample's rotation plus a normal error of ``spread_urad`` (the rotation
        channel's noise), by 9-point Gauss-Hermite quadrature. Near a kink of the law a noisy
        reading falls on either side of it, so the slope it carries into the residual is a mix
        of the two. The law is piecewise linear: a central difference over 1e-3 urad is exact.
        ``rotation_urad``: other rotations (another record's) to take it at."""
        d = fit.declared_values
        phi_urad = (self.rot_urad if rotation_urad is None else rotation_urad) - d["theta0_urad"]
        step = 1e-3
        nodes, weights = np.polynomial.hermite_e.hermegauss(9 if spread_urad > 0 else 1)
        weights = weights / weights.sum()
        square = np.zeros(phi_urad.size)
        for z, w in zip(nodes, weights):
            at = phi_urad + z * spread_urad
            k = (self._law(d, (at + step) * 1e-6) - self._law(d, (at - step) * 1e-6)) / (2 * step)
            square += w * k * k
        return np.sqrt(square)

    def nominal(self) -> np.ndarray | None:
        """Residual of the law with the declared values and the probe zero as read; None without values."""
        if not self.spec.has_nominal:
            return None
        d = self._declared_start()
        return self.T - self._law(d, self.rot_urad * 1e-6)

    # ---------------------------------------------------------------- parameter layout
    def _layout(self, terms):
        names = ["ln_k1", "ln_k2"] + (["ln_k3"] if self.type2 else []) + ["preload", "theta0_urad"]
        for i, term in enumerate(terms):
            if term.effect == "drift":
                names.append(f"{i}:rate")
            elif term.effect == "hysteresis":
                names.append(f"{i}:half_width")
            elif term.effect == "stiffening":
                names += [f"{i}:amplitude", f"{i}:exponent"]
            elif term.effect == "dead_band":
                names.append(f"{i}:width_urad")
            elif term.effect == "amplitude_hysteresis":
                names += [f"{i}:half_width", f"{i}:growth"]
        return names

    def _drift_ref(self, variable: str) -> tuple[np.ndarray, float]:
        v = drift_variable(self.meas, variable)
        ref = float(v[0]) if variable == "time" else float(np.mean(v[: min(10, v.size)]))
        return v, ref

    def _memo(self, key: tuple, make):
        """``make()`` remembered under ``key`` (the component and the parameters it depends on): a
        finite-difference Jacobian moves one parameter at a time, so the play, the law and the
        stiffening are each remade only when a parameter of their own moved. Keeps the last few
        (fewer for very long records)."""
        hit = self._cache.get(key)
        if hit is None:
            if len(self._cache) >= (24 if self.n <= 2_000_000 else 6):
                self._cache.pop(next(iter(self._cache)))
            hit = self._cache[key] = make()
        return hit

    def _evaluate(self, names, p, terms):
        """(prediction, contributions per term, declared dict, effect values per term)."""
        val = self._transform(names, p)
        d = {"k1": math.exp(val["ln_k1"]), "k2": math.exp(val["ln_k2"]), "preload": val["preload"],
             "theta0_urad": val["theta0_urad"]}
        if self.type2:
            d["k3"] = math.exp(val["ln_k3"])
        law_key = tuple(d[k] for k in ("k1", "k2", "preload")) + (d.get("k3"),)
        theta0 = d["theta0_urad"]
        idx = {t.effect: i for i, t in enumerate(terms)}
        width = val[f"{idx['dead_band']}:width_urad"] if "dead_band" in idx else None

        def phi_of(w):  # the rotation the springs see, rad
            return self._memo(("phi", theta0, w), lambda: (fx.dead_zone(self.rot_urad - theta0, w) if w is not None
                                                             else self.rot_urad - theta0) * 1e-6)
        phi = phi_of(width)
        base = self._memo(("law", law_key, theta0, width), lambda: self._law(d, phi))
        pred = base.copy()
        contributions, values = [None] * len(terms), [None] * len(terms)
        for i, term in enumerate(terms):
            if term.effect == "drift":
                v, ref = self._drift_ref(term.variable)
                c = fx.drift(v, val[f"{i}:rate"], ref)
                values[i] = drift_value(term.variable, val[f"{i}:rate"])
            elif term.effect == "hysteresis":
                h = val[f"{i}:half_width"]
                c = self._memo(("play", h), lambda: self.T_smooth - fx.play_operator(self.T_smooth, h))
                values[i] = {"half_width": h}
            elif term.effect == "stiffening":
                amp, ex = val[f"{i}:amplitude"], val[f"{i}:exponent"]
                c = amp * self._memo(("stiffening", theta0, width, ex), lambda: fx.stiffening(phi, 1.0, ex))
                values[i] = {"exponent": ex, "amplitude": amp}
            elif term.effect == "dead_band":
                w = val[f"{i}:width_urad"]
                c = base - self._memo(("law", law_key, theta0, None), lambda: self._law(d, phi_of(None)))
                values[i] = {"width_urad": w}
            elif term.effect == "amplitude_hysteresis":
                h, growth = val[f"{i}:half_width"], val[f"{i}:growth"]
                c = self._memo(("play", h, growth), lambda: self.T_smooth - fx.play_operator(
                    self.T_smooth, self._friction_widths(h, growth)))
                values[i] = {"half_width": h, "reference_amplitude": self.reference_amplitude, "exponent": growth}
            else:
                raise ValueError(f"{term.effect} does not apply to a torque_deflection")
            contributions[i] = c
            if term.effect != "dead_band":
                pred = pred + c
        return pred, contributions, d, values

    # Parameters that must not be negative are fitted through |p|, the exponent through
    # EXPONENT_MIN + EXPONENT_SPAN / (1 + exp(-p)), so that the unbounded Levenberg-Marquardt
    # solver can be used: it is fast and robust here.
    @staticmethod
    def _is_magnitude(name: str) -> bool:
        return (name == "preload" or name.endswith(":half_width") or name.endswith(":width_urad")
                or name.endswith(":amplitude")  # stiffening stiffens: a negative amplitude would soften
                or name.endswith(":growth"))  # (friction that grows with the amplitude, as the library says)

    def _transform(self, names, p) -> dict:
        kinds = self._kinds.get(tuple(names))
        if kinds is None:
            kinds = self._kinds[tuple(names)] = tuple(
                "magnitude" if self._is_magnitude(nm) else "exponent" if nm.endswith(":exponent") else "" for nm in names)
        val = {}
        for nm, kind, v in zip(names, kinds, p):
            if kind == "magnitude":
                v = abs(v)
            elif kind == "exponent":
                v = EXPONENT_MIN + EXPONENT_SPAN / (1.0 + math.exp(-min(max(v, -50.0), 50.0)))
            val[nm] = float(v)
        return val

    def _untransform(self, name: str, value: float) -> float:
        if name.endswith(":exponent"):
            f = min(max((value - EXPONENT_MIN) / EXPONENT_SPAN, 1e-6), 1 - 1e-6)
            return math.log(f / (1.0 - f))
        return value

    def fit(self, terms: tuple[Term, ...], mask=None, start: ModelFit | None = None, extra: dict | None = None) -> ModelFit:
        terms = tuple(terms)
        mask = mask_or_all(mask, self.n)
        names = self._layout(terms)
        centre = dict(self.declared_start) if start is None else dict(start.declared_values)
        p0 = {"ln_k1": math.log(centre["k1"]), "ln_k2": math.log(centre["k2"]), "preload": centre["preload"],
              "theta0_urad": centre["theta0_urad"]}
        if self.type2:
            p0["ln_k3"] = math.log(centre["k3"])
        prior_centre = dict(p0)
        if start is not None:  # effect parameters from the previous fit
            old = self._layout(start.terms)
            for nm, v in zip(old, start.state["p"]):
                if ":" in nm:
                    i = int(nm.split(":")[0])
                    key = nm.split(":")[1]
                    if i < len(start.terms) and start.terms[i] in terms:
                        p0[f"{terms.index(start.terms[i])}:{key}"] = v
        for i, term in enumerate(terms):
            for key, default in self._effect_defaults(term).items():
                p0.setdefault(f"{i}:{key}", default)
        extra = dict(extra or {})
        starts = extra.pop("starts", ())  # further (exponent, amplitude) starts of a new stiffening
        for k, v in extra.items():  # start values for the last term (the candidate)
            p0[f"{len(terms) - 1}:{k}"] = v
        x0 = np.array([self._untransform(nm, p0[nm]) for nm in names], dtype=float)
        sigma = max(self.noise.rms, 1e-12)
        prior_names = [nm for nm in ("ln_k1", "ln_k2", "ln_k3") if nm in names]
        pscale = max(prior_centre["preload"], 1.0)
        T = self.T
        scale = self.residual_scale[mask]

        inverse_scale = 1.0 / scale
        every_row = bool(mask.all())
        fitted = int(mask.sum())
        prior_index = [names.index(nm) for nm in prior_names]
        preload_index = names.index("preload")

        def fun(p):
            pred, *_ = self._evaluate(names, p, terms)
            out = np.empty(fitted + len(prior_index) + 1)
            r = out[:fitted]
            if every_row:
                np.subtract(T, pred, out=r)
            else:
                r[:] = (T - pred)[mask]
            r *= inverse_scale
            for j, (k, nm) in enumerate(zip(prior_index, prior_names)):  # (ln k: fitted as is)
                out[fitted + j] = sigma * (p[k] - prior_centre[nm])
            out[-1] = sigma * (abs(p[preload_index]) - prior_centre["preload"]) / pscale
            return out

        # (a relative change of the sum of squares below 1e-7 moves a dBIC by n x 1e-7, hundredths)
        res = least_squares(fun, x0, x_scale="jac", method="lm", max_nfev=60 * (len(names) + 1), ftol=1e-7, xtol=1e-7)
        at_bound = starts and terms[-1].effect == "stiffening" and not (
            EXPONENT_MIN + 0.01 * EXPONENT_SPAN < self._transform(names, res.x)[f"{len(terms) - 1}:exponent"]
            < EXPONENT_MIN + 0.99 * EXPONENT_SPAN)
        if at_bound:
            # a stiffening's exponent trades against k3 and the preload: from one start the solver
            # can end at an exponent bound (a local minimum) where another start finds the law
            i = len(terms) - 1
            j_ex, j_amp = names.index(f"{i}:exponent"), names.index(f"{i}:amplitude")
            for ex, amp in starts:
                if abs(self._transform(names, res.x)[f"{i}:exponent"] - ex) < 0.05 * EXPONENT_SPAN:
                    continue
                x1 = x0.copy()
                x1[j_ex], x1[j_amp] = self._untransform(f"{i}:exponent", ex), amp
                other = least_squares(fun, x1, x_scale="jac", method="lm", max_nfev=60 * (len(names) + 1),
                                      ftol=1e-7, xtol=1e-7)
                if other.cost < res.cost * (1 - 1e-9):
                    res = other
        pred, contributions, d, values = self._evaluate(names, res.x, terms)
        resid = T - pred
        n_params = len(names)
        val = self._transform(names, res.x)
        return ModelFit(terms=terms, prediction=pred, residual=resid, rss=float(np.sum((resid[mask] / scale) ** 2)),
                        n_fitted=int(mask.sum()), n_params=n_params, contributions=tuple(contributions),
                        values=tuple(values), declared_values=d, state={"p": [val[nm] for nm in names], "names": names,
                                                                       "x": res.x, "jac": res.jac, "mask": mask},
                        success=bool(res.success), message=str(res.message))

    def contribution_noise(self, fit: ModelFit, index: int) -> float:
        """Mean square by which noise alone moves term ``index``'s contribution in this fit
        (linearised: the solver's Jacobian, and the contribution's by finite differences)."""
        names, x, terms = fit.state["names"], np.asarray(fit.state["x"], float), fit.terms
        base = self._evaluate(names, x, terms)[1][index]
        C = np.empty((self.n, x.size))
        for j in range(x.size):
            step = 1e-6 * max(1.0, abs(x[j]))
            xp = x.copy()
            xp[j] += step
            C[:, j] = (self._evaluate(names, xp, terms)[1][index] - base) / step
        return _contribution_noise(fit.state["jac"], C, self.noise.rms)

    def _friction_widths(self, half_width: float, growth: float) -> np.ndarray:
        """Per-sample play half-width of an amplitude hysteresis: h (A / A_ref)^growth, A the
        amplitude of the sample's test."""
        return half_width * (self.test_amplitude / self.reference_amplitude) ** growth

    def _effect_defaults(self, term: Term) -> dict:
        if term.effect == "drift":
            return {"rate": 0.0}
        if term.effect in ("hysteresis", "amplitude_hysteresis"):
            return {"half_width": 0.5 * self.noise.rms, "growth": 1.0} if term.effect != "hysteresis" else \
                {"half_width": 0.5 * self.noise.rms}
        if term.effect == "stiffening":
            return {"amplitude": 0.0, "exponent": 1.5}
        if term.effect == "dead_band":
            return {"width_urad": 1.0}
        return {}

    # ---------------------------------------------------------------- effects
    def _phi_urad(self, fit: ModelFit) -> np.ndarray:
        return self.rot_urad - fit.declared_values["theta0_urad"]

    def candidates(self, fit: ModelFit) -> list[Candidate]:
        r = fit.residual
        present = {(t.effect, t.variable) for t in fit.terms}
        out: list[Candidate] = []
        for term in drift_terms(self.meas):
            if ("drift", term.variable) in present:
                continue
            v, ref = self._drift_ref(term.variable)
            rate = _slope(v - ref, r)
            corr = sample_correlation(v, r)
            out.append(Candidate(term, f"residual correlates with {term.variable} (r = {corr:+.3f})",
                                 start={"rate": rate}, statistic=corr))
        friction = ("hysteresis", "") in present or ("amplitude_hysteresis", "") in present
        if not friction:
            dT = np.diff(self.T_smooth, prepend=self.T_smooth[0])
            up, down = r[dT > 0], r[dT < 0]
            if up.size > 10 and down.size > 10:
                gap = float(up.mean() - down.mean())
                out.append(Candidate(Term("hysteresis"),
                                     f"residual while torque rises minus while it falls: {gap:+.3g} Nm (friction gives +2h)",
                                     start={"half_width": max(0.5 * gap, 0.1 * self.noise.rms)}, statistic=gap))
            if self.amplitudes_differ:
                widths = []
                for _, rows in self.tests:
                    u, dn = r[rows][dT[rows] > 0], r[rows][dT[rows] < 0]
                    if u.size > 3 and dn.size > 3:
                        widths.append((float(np.max(np.abs(self.T_smooth[rows]))), 0.5 * float(u.mean() - dn.mean())))
                good = [(a, h) for a, h in widths if h > 0]
                growth = 1.0
                if len(good) >= 2 and np.ptp([a for a, _ in good]) > 0:
                    growth = float(np.clip(np.polyfit(np.log([a for a, _ in good]), np.log([h for _, h in good]), 1)[0],
                                           0.0, 4.0))
                h_ref = max((h for a, h in good if a == max(a for a, _ in good)), default=0.1 * self.noise.rms)
                text = ", ".join(f"{h:+.3g} Nm at {a:.3g} Nm" for a, h in widths)
                out.append(Candidate(Term("amplitude_hysteresis"),
                                     f"half the residual gap between rising and falling torque, test by test: {text} "
                                     f"(friction that grows with the amplitude: exponent about {growth:.2g})",
                                     start={"half_width": max(h_ref, 0.1 * self.noise.rms), "growth": growth},
                                     statistic=growth))
        phi = self._phi_urad(fit) * 1e-6
        if ("stiffening", "") not in present:
            best = None
            tried = []
            for ex in (1.25, 1.5, 2.0, 2.5, 3.0, 3.5):
                b = fx.stiffening(phi, 1.0, ex)
                amp = max(float(b @ r / max(b @ b, 1e-300)), 0.0)
                drop = amp * (b @ r)
                # (the declared fit's k3 has taken up part of the bend: the projection starts the
                # amplitude low; the other start is a stiffening worth 5 % of the peak torque)
                reach = float(np.max(np.abs(phi))) / fx.STIFFENING_REFERENCE_RAD
                tried.append((ex, max(amp, 0.05 * float(np.max(np.abs(self.T))) / max(reach, 1e-12) ** ex)))
                if best is None or drop > best[2]:
                    best = (amp, ex, drop)
            curv = _side_curvature(phi, r)
            out.append(Candidate(Term("stiffening"),
                                 f"residual bends with load: quadratic coefficient {curv[0]:+.3g} (phi > 0) and {curv[1]:+.3g} "
                                 f"(phi < 0) Nm/mrad^2; best power law exponent {best[1]}",
                                 start={"amplitude": max(best[0], 1e-3), "exponent": best[1],
                                        "starts": tuple(e for e in tried if e[0] in STIFFENING_STARTS or e[0] == 1.25)},
                                 statistic=best[2]))
        if ("dead_band", "") not in present:
            scale = max(np.ptp(self.rot_urad), 1.0)
            best = (0.0, fit.rss)
            d = fit.declared_values
            other = fit.prediction - self._law(d, phi)
            for w in scale * np.geomspace(1e-3, 0.3, 24):
                pred = other + self._law(d, fx.dead_zone(self._phi_urad(fit), w) * 1e-6)
                rss = float(np.sum((self.T - pred) ** 2))
                if rss < best[1]:
                    best = (w, rss)
            near = np.abs(self.T) < 0.05 * np.max(np.abs(self.T))
            spread = float(np.ptp(self._phi_urad(fit)[near])) if near.sum() > 2 else 0.0
            out.append(Candidate(Term("dead_band"),
                                 f"rotation spreads over {spread:.3g} urad while |torque| < 5 % of its peak; "
                                 f"a flat zone of {best[0]:.3g} urad fits best",
                                 start={"width_urad": max(best[0], 1e-3)}, statistic=best[0]))
        return out

    def polish(self, fit: ModelFit) -> ModelFit:
        return fit

    def degenerate(self, fit: ModelFit, index: int) -> str | None:
        """Why term ``index`` is no real effect although it fits (a parameter at its bound), or None."""
        term, v = fit.terms[index], fit.values[index]
        if term.effect == "stiffening":
            if v["exponent"] < EXPONENT_MIN + 0.01 * EXPONENT_SPAN:
                return (f"exponent {v['exponent']:.3f} at the lower bound {EXPONENT_MIN:g}: the term is then "
                        "nearly a linear stiffness, which the declared law already has")
            if v["exponent"] > EXPONENT_MIN + 0.99 * EXPONENT_SPAN:
                return (f"exponent {v['exponent']:.3f} at the upper bound {EXPONENT_MIN + EXPONENT_SPAN:g}: "
                        "outside the Hertzian range")
        if term.effect == "dead_band":
            resolved = self.zero_torque_spread(fit)
            if v["width_urad"] < DEAD_BAND_RESOLUTION * resolved:
                return (f"a band of {v['width_urad']:.3g} urad is narrower than {DEAD_BAND_RESOLUTION:g} x the "
                        f"{resolved:.3g} urad by which a single reading places the rotation at zero torque (the rotation "
                        "channel's noise and the torque's carried through the drive stiffness): the record shows no "
                        "flat zone there, which is what a dead band is; the kink it puts in the law only bends the "
                        "curve")
        if term.effect == "amplitude_hysteresis" and v["exponent"] < 0.05:
            return (f"exponent {v['exponent']:.3g}: a friction that does not grow with the amplitude is the "
                    "constant-width hysteresis")
        return None

    def zero_torque_spread(self, fit: ModelFit) -> float:
        """urad by which one reading places the rotation at zero torque: the rotation channel's
        noise and the torque channel's through the drive stiffness of ``fit``'s law, in quadrature."""
        d = fit.declared_values
        step = 1e-3  # urad: the law is linear within a path's unloading torque, far beyond this
        k_drive = float(np.diff(self._law(d, np.array([-step, step]) * 1e-6))[0] / (2 * step))  # Nm per urad at zero
        sigma_t, sigma_r = self.noise.channels.get("torque", 0.0), self.noise.channels.get("rotation", 0.0)
        torque_part = sigma_t / k_drive if k_drive > 0 else 0.0  # (k_drive in Nm per urad)
        return math.hypot(sigma_r, torque_part)

    def implausible(self, fit: ModelFit, index: int) -> str | None:
        """Why term ``index``'s parameters are physically absurd for this record, or None: a
        friction play (of any test) wider than the torque range it plays across never lets go and
        explains nothing; a dead band wider than the whole rotation recorded has no sides."""
        term, v = fit.terms[index], fit.values[index]
        span = float(np.ptp(self.T_smooth))
        if term.effect == "hysteresis" and 2.0 * v["half_width"] >= span:
            return (f"a friction play of full width {2 * v['half_width']:.4g} Nm is wider than the whole torque range "
                    f"of the record ({span:.4g} Nm)")
        if term.effect == "amplitude_hysteresis":
            for test, rows in self.tests:
                a = float(np.max(np.abs(self.T_smooth[rows]))) if rows.size else 0.0
                h = v["half_width"] * (a / self.reference_amplitude) ** v["exponent"]
                if rows.size and 2.0 * h >= float(np.ptp(self.T_smooth[rows])):
                    return (f"in test {test} the friction play of full width {2 * h:.4g} Nm is wider than the test's "
                            f"torque range ({np.ptp(self.T_smooth[rows]):.4g} Nm)")
        if term.effect == "dead_band" and v["width_urad"] >= float(np.ptp(self.rot_urad)):
            return (f"a dead band of {v['width_urad']:.4g} urad is wider than the whole rotation recorded "
                    f"({np.ptp(self.rot_urad):.4g} urad)")
        return None

    def noise_readings(self, noise: NoiseEstimate) -> list[tuple[str, np.ndarray, float]]:
        return [(self.meas.column("torque"), self.T, noise.channels["torque"]),
                (self.meas.column("rotation"), self.rot_urad, noise.channels["rotation"])]

    def quick_gain(self, fit: ModelFit, term: Term) -> float | None:
        return None

    def entry(self, fit: ModelFit, i: int) -> dict:
        term, v = fit.terms[i], fit.values[i]
        if term.effect == "drift":
            return {"effect": "drift", **v, "variable": "temperature_C" if term.variable == "temperature" else "time_s"}
        if term.effect == "hysteresis":
            return {"effect": "hysteresis", "half_width": v["half_width"],
                    "law": "play operator on the applied torque (Coulomb friction, Nm)"}
        if term.effect == "stiffening":
            return {"effect": "stiffening", "exponent": v["exponent"], "amplitude": v["amplitude"],
                    "reference_rotation_urad": fx.STIFFENING_REFERENCE_RAD * 1e6,
                    "law": "amplitude * sign(phi) * |phi / reference_rotation| ** exponent (Nm)"}
        if term.effect == "amplitude_hysteresis":
            per_test = [{"test": int(test), "torque_amplitude_Nm": float(np.max(np.abs(self.T_smooth[rows]))),
                         "half_width": float(v["half_width"] * (np.max(np.abs(self.T_smooth[rows]))
                                                                / self.reference_amplitude) ** v["exponent"])}
                        for test, rows in self.tests if rows.size]
            return {"effect": "amplitude_hysteresis", "half_width": v["half_width"],
                    "reference_amplitude": v["reference_amplitude"], "exponent": v["exponent"], "tests": per_test,
                    "law": "play operator on the applied torque of half-width half_width * (A / reference_amplitude) "
                           "** exponent, A the torque amplitude of the sample's test (Nm)"}
        return {"effect": "dead_band", "width_urad": v["width_urad"]}


# ======================================================================== helpers

def _contribution_noise(J: np.ndarray, C: np.ndarray, sigma: float, columns=None) -> float:
    """trace(C Cov C^T) / n with Cov = sigma^2 (J^T J)^-1: J (m, p); C (n, p), or (n, k) holding
    only the given ``columns`` of it (the rest zero). See :func:`contribution_noise_gram`."""
    return contribution_noise_gram(J.T @ J, C.T @ C, C.shape[0], sigma, columns)


def contribution_noise_gram(JtJ: np.ndarray, CtC: np.ndarray, n: int, sigma: float, columns=None) -> float:
    """trace(C Cov C^T) / n = sum(Cov * C^T C) / n with Cov = sigma^2 (J^T J)^-1, from the Gram
    matrices alone: J^T J (p, p) and C^T C (p, p), or (k, k) for the given ``columns`` of C.

    Infinite when J^T J is singular (a parameter the fitted samples cannot determine: a dead
    band seen from one side only is the probe zero): noise then moves the effect without bound.
    """
    G = JtJ
    norms = np.sqrt(np.diag(G))
    if np.any(norms == 0):
        return math.inf
    Gs = G / np.outer(norms, norms)
    if np.linalg.cond(Gs) > 1e12:
        return math.inf
    cov = np.linalg.inv(Gs) / np.outer(norms, norms) * sigma ** 2
    if columns is not None:
        cov = cov[np.ix_(columns, columns)]
    return float(np.sum(cov * CtC) / n)


def _slope(x: np.ndarray, y: np.ndarray) -> float:
    x = x - x.mean()
    den = float(x @ x)
    return float(x @ (y - y.mean()) / den) if den > 0 else 0.0


def sample_correlation(x: np.ndarray, y: np.ndarray) -> float:
    x = x - x.mean()
    y = y - y.mean()
    den = math.sqrt(float(x @ x) * float(y @ y))
    return float(x @ y / den) if den > 0 else 0.0


def _side_curvature(phi_rad: np.ndarray, r: np.ndarray) -> tuple[float, float]:
    """Quadratic coefficient of the residual against rotation (mrad) on each side of zero."""
    out = []
    for side in (phi_rad > 0, phi_rad < 0):
        if side.sum() < 10:
            out.append(0.0)
            continue
        p = phi_rad[side] * 1e3
        with warnings.catch_warnings():  # a poorly spread side only blurs this evidence text
            warnings.simplefilter("ignore", np.exceptions.RankWarning)
            coef = np.polyfit(p, r[side], 2)
        out.append(float(coef[0]))
    return out[0], out[1]
