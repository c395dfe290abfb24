"""The project's own bench simulator: measurements made from a truth model.

Used by the tests and the bench. A truth model holds what the sidecar declares (the train's
shaft and mesh sinusoids, or the two-path law) and may hold what it does not: any library
effect, or an effect outside the library (a chirp, a step, a noise burst, a vibration). The
record is realistic: sample intervals vary (``jitter``), the probe drops out in blocks (rows
missing), the reading is quantised to the probe's resolution, noise is white and Gaussian,
the temperature creeps up non-linearly in time (so drift with temperature and with time can be
told apart) and is read with its own noise.

Every simulation returns the :class:`~geargen.fit.measurement.Measurement`, the noise level
actually injected, expressed in residual units (``true_noise_rms``), and the effects the fit
should find (``expected``) in the contract's parameter names. Randomness comes only from the
``numpy.random.Generator`` passed in.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from geargen.core.drive import TwoPathDrive
from geargen.fit import effects as fx
from geargen.fit.measurement import Measurement, PreloadModelSpec, TorqueModelSpec
from geargen.fit.orders import train_orders


@dataclass(frozen=True, eq=False)
class Simulated:
    """A simulated record: ``measurement``; ``true_noise_rms`` (residual units); ``clean`` (n,)
    the noise-free signal; ``expected`` the undeclared library effects in it (JSON names);
    ``outside`` names any effect outside the library that was put in."""

    measurement: Measurement
    true_noise_rms: float
    clean: np.ndarray
    expected: tuple[dict, ...]
    outside: tuple[str, ...] = ()


# ----------------------------------------------------------------------------- sampling

@dataclass(frozen=True)
class Sampling:
    """How the record is sampled: ``samples`` kept after drop-outs; sample intervals vary by
    +-``jitter`` (relative); ``dropouts`` blocks removing ``dropout_fraction`` of the samples."""

    samples: int = 16384
    duration_s: float = 900.0
    jitter: float = 0.5
    dropouts: int = 3
    dropout_fraction: float = 0.04
    temperature: bool = True
    temperature_rise_K: float = 2.0
    temperature_noise_K: float = 0.003


def unit_noise(rng: np.random.Generator, n: int, ar1: float = 0.0) -> np.ndarray:
    """(n,) Gaussian noise of unit variance: white, or AR(1) with lag-one correlation ``ar1``
    (``e_i = ar1 e_(i-1) + sqrt(1 - ar1^2) w_i``, started in its stationary state)."""
    w = rng.normal(size=n)
    if ar1 == 0.0:
        return w
    from scipy.signal import lfilter
    w[1:] *= math.sqrt(1.0 - ar1 * ar1)
    return lfilter([1.0], [1.0, -ar1], w)


def sample_times(s: Sampling, rng: np.random.Generator) -> np.ndarray:
    """Uneven sample times with drop-out blocks removed: (s.samples,) s, increasing."""
    total = int(round(s.samples / (1.0 - s.dropout_fraction))) if s.dropouts else s.samples
    dt = 1.0 + s.jitter * rng.uniform(-1.0, 1.0, total)
    t = np.cumsum(dt)
    t = (t - t[0]) / (t[-1] - t[0]) * s.duration_s
    keep = np.ones(total, bool)
    lost = total - s.samples
    if s.dropouts and lost > 0:
        sizes = rng.multinomial(lost, np.ones(s.dropouts) / s.dropouts)
        segment = total // s.dropouts
        for k, size in enumerate(sizes):
            lo = k * segment + int(0.1 * segment)
            start = lo + int(rng.integers(0, max(1, int(0.8 * segment) - size)))
            keep[start:start + size] = False
        extra = int(keep.sum()) - s.samples
        if extra > 0:
            keep[np.flatnonzero(keep)[-extra:]] = False
    return t[keep]


def temperature_history(t: np.ndarray, s: Sampling) -> np.ndarray:
    """True temperature, C: warm-up towards +rise plus a slow air-conditioning swing (not linear in t)."""
    d = s.duration_s
    return 20.0 + s.temperature_rise_K * (1.0 - np.exp(-t / (0.35 * d))) + 0.15 * s.temperature_rise_K * np.sin(2 * np.pi * t / (0.45 * d))


def _read_temperature(true_temp, s: Sampling, rng):
    return np.round((true_temp + s.temperature_noise_K * rng.normal(size=true_temp.size)) / 0.001) * 0.001


def _add_drifts(signal: np.ndarray, truth, t: np.ndarray, temp_true: np.ndarray, expected: list) -> None:
    """Add (in place) a truth's drift with temperature and with time, about their means, and
    list them as expected effects."""
    if truth.drift_per_kelvin:
        signal += fx.drift(temp_true, truth.drift_per_kelvin, float(temp_true.mean()))
        expected.append({"effect": "drift", "per_kelvin": truth.drift_per_kelvin})
    if truth.drift_per_second:
        signal += fx.drift(t, truth.drift_per_second, float(t.mean()))
        expected.append({"effect": "drift", "per_second": truth.drift_per_second})


# ----------------------------------------------------------------------------- preload trace

@dataclass(frozen=True)
class PreloadTruth:
    """Truth of a preload trace. Amplitudes in um; phases random unless given.

    ``eccentricity_um``: (output, cluster, input) once-per-revolution amplitudes;
    ``tooth_to_tooth_um``: (mesh1, mesh2). ``declared`` is what the sidecar will declare.
    Undeclared library effects: ``harmonics`` ((order, amplitude, phase_deg), ...),
    ``drift_per_kelvin``, ``drift_per_second``, ``hysteresis_half_width``.
    Outside the library: ``chirp`` (amplitude, order at start, order at end; sweeps with time),
    ``step`` (height, fraction of the record), ``burst`` (noise factor, start fraction, length fraction).
    """

    teeth: tuple[int, int, int, int] = (16, 48, 21, 112)
    declared: tuple[str, ...] = ("eccentricity", "tooth_to_tooth")
    eccentricity_um: tuple[float, float, float] = (20.0, 8.0, 4.0)
    tooth_to_tooth_um: tuple[float, float] = (1.0, 1.5)
    offset_um: float = 50.0
    harmonics: tuple[tuple[float, float, float], ...] = ()
    drift_per_kelvin: float = 0.0
    drift_per_second: float = 0.0
    hysteresis_half_width: float = 0.0
    chirp: tuple[float, float, float] | None = None
    step: tuple[float, float] | None = None
    burst: tuple[float, float, float] | None = None


@dataclass(frozen=True)
class PreloadSettings:
    """The test: ``revolutions`` turned forward (and back again when ``return_trip``), probe
    ``noise_um`` (Gaussian) and ``resolution_um`` (quantisation)."""

    sampling: Sampling = field(default_factory=Sampling)
    revolutions: float = 1.5
    return_trip: bool = True
    noise_um: float = 0.5
    noise_ar1: float = 0.0  # lag-one correlation of the probe's noise (a logger's filter): 0 white
    resolution_um: float = 0.01
    speed_ripple: float = 0.08


def output_angle_history(t: np.ndarray, duration: float, revolutions: float, return_trip: bool,
                         ripple: float) -> np.ndarray:
    """Output angle (rad) over time: smooth start, stop and reversal, a slight speed ripple."""
    grid = np.linspace(0.0, duration, 200001)
    legs = 2 if return_trip else 1
    leg = duration / legs
    tau = np.mod(grid, leg) / leg
    ramp = np.clip(np.minimum(tau, 1 - tau) / 0.03, 0, 1)
    ramp = 0.5 - 0.5 * np.cos(np.pi * ramp)
    direction = np.where(grid < leg, 1.0, -1.0) if return_trip else np.ones_like(grid)
    speed = direction * ramp * (1.0 + ripple * np.sin(2 * np.pi * 3.1 * grid / duration))
    angle = np.concatenate([[0.0], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(grid))])
    forward = angle[np.searchsorted(grid, leg) if return_trip else -1]
    angle *= 2 * np.pi * revolutions / forward
    return np.interp(t, grid, angle)


def simulate_preload_trace(truth: PreloadTruth, rng: np.random.Generator,
                           settings: PreloadSettings | None = None, name: str = "preload_sim") -> Simulated:
    """A preload trace from a truth model (see :class:`PreloadTruth`)."""
    st = settings or PreloadSettings()
    sm = st.sampling
    t = sample_times(sm, rng)
    n = t.size
    theta = output_angle_history(t, sm.duration_s, st.revolutions, st.return_trip, st.speed_ripple)
    temp_true = temperature_history(t, sm)
    orders = {o.name: o.order for o in train_orders(truth.teeth)}
    amps = dict(zip(("output", "cluster", "input"), truth.eccentricity_um)) | dict(zip(("mesh1", "mesh2"), truth.tooth_to_tooth_um))
    x = np.full(n, truth.offset_um)
    for name_, amp in amps.items():
        x += fx.harmonic(theta, orders[name_], amp, float(rng.uniform(0, 360)))
    expected = []
    declared_names = {nm for d in truth.declared for nm in {"eccentricity": ("output", "cluster", "input"),
                                                              "tooth_to_tooth": ("mesh1", "mesh2")}[d]}
    for name_, amp in amps.items():
        if name_ not in declared_names and amp > 0:
            expected.append({"effect": "harmonic", "order": orders[name_], "amplitude": amp})
    for order, amp, phase in truth.harmonics:
        x += fx.harmonic(theta, order, amp, phase)
        expected.append({"effect": "harmonic", "order": order, "amplitude": amp, "phase_deg": phase})
    _add_drifts(x, truth, t, temp_true, expected)
    outside = []
    if truth.chirp:
        amp, q0, q1 = truth.chirp
        mean_rate = 2 * np.pi * st.revolutions * (2 if st.return_trip else 1) / sm.duration_s  # rad/s of output
        f0, f1 = q0 * mean_rate / (2 * np.pi), q1 * mean_rate / (2 * np.pi)
        phase = 2 * np.pi * (f0 * t + 0.5 * (f1 - f0) * t * t / sm.duration_s)
        x += amp * np.sin(phase)
        outside.append("chirp")
    if truth.step:
        height, frac = truth.step
        x += height * (t > frac * sm.duration_s)
        outside.append("step")
    if truth.hysteresis_half_width:
        x = fx.play_operator(x, truth.hysteresis_half_width)
        expected.append({"effect": "hysteresis", "half_width": truth.hysteresis_half_width})
    noise = st.noise_um * unit_noise(rng, n, st.noise_ar1)
    if truth.burst:
        factor, start, length = truth.burst
        inside = (t >= start * sm.duration_s) & (t < (start + length) * sm.duration_s)
        noise[inside] *= factor
        outside.append("burst")
    measured = x + noise
    if st.resolution_um > 0:
        measured = np.round(measured / st.resolution_um) * st.resolution_um
    temperature = _read_temperature(temp_true, sm, rng) if sm.temperature else None
    meas = Measurement(kind="preload_trace", name=name, time_s=t, angle_rad=theta, carriage_um=measured,
                       temperature_C=temperature, model=PreloadModelSpec(teeth=truth.teeth, declared=truth.declared, drive_type="type2"),
                       description="simulated preload trace (geargen.fit.simulate)")
    return Simulated(meas, float(np.sqrt(np.mean((measured - x) ** 2))), x, tuple(expected), tuple(outside))


# ----------------------------------------------------------------------------- torque deflection

@dataclass(frozen=True)
class TorqueTruth:
    """Truth of a torque-deflection test, output-referred, Nm/rad and Nm.

    The sidecar declares ``declared_factors`` x the true (k1, k2, k3, preload): a design estimate
    that is a little off. Undeclared library effects: ``drift_per_kelvin``, ``drift_per_second``
    (Nm per K or s: the torque reading's zero creeping), ``hysteresis_half_width`` (Nm of Coulomb
    friction), ``stiffening`` (amplitude Nm at 1 mrad, exponent), ``dead_band_urad``.
    Outside the library: ``step`` (Nm, fraction of the record: the torque cell slips),
    ``vibration`` (amplitude Nm, period s), ``burst`` (noise factor, start fraction, length fraction).
    ``amplitude_hysteresis`` (h_ref Nm, exponent m): friction of half-width h_ref (A / A_max)^m in a
    test of torque amplitude A (polymer parts, torque from motor current).
    """

    drive_type: str = "type2"
    k1: float = 4.0e5
    k2: float = 4.0e5
    k3: float | None = 4.0e4
    preload: float = 25.0
    theta0_urad: float = 0.4
    declared_factors: tuple[float, float, float, float] = (1.08, 0.95, 1.1, 0.9)
    declare_values: bool = True
    drift_per_kelvin: float = 0.0
    drift_per_second: float = 0.0
    hysteresis_half_width: float = 0.0
    amplitude_hysteresis: tuple[float, float] | None = None  # (half-width at the largest test's amplitude, exponent)
    stiffening: tuple[float, float] | None = None
    dead_band_urad: float = 0.0
    step: tuple[float, float] | None = None
    vibration: tuple[float, float] | None = None
    burst: tuple[float, float, float] | None = None

    def drive(self) -> TwoPathDrive:
        """The true law in geargen's internal units (N*mm/rad, N*mm)."""
        kw = {"k3": self.k3 * 1e3} if self.drive_type == "type2" else {}
        return TwoPathDrive(self.drive_type, k1=self.k1 * 1e3, k2=self.k2 * 1e3, preload=self.preload * 1e3, **kw)

    def declared_spec(self) -> TorqueModelSpec:
        if not self.declare_values:
            return TorqueModelSpec(self.drive_type)
        f1, f2, f3, fp = self.declared_factors
        return TorqueModelSpec(self.drive_type, k1_Nm_per_rad=self.k1 * f1, k2_Nm_per_rad=self.k2 * f2,
                               k3_Nm_per_rad=self.k3 * f3 if self.drive_type == "type2" else None,
                               preload_Nm=self.preload * fp)


@dataclass(frozen=True)
class TorqueSettings:
    """The test: ``cycles`` of 0 -> +T -> -T -> 0 with T = ``max_torque_Nm``; torque-cell noise
    ``torque_noise_Nm``; rotation probe noise ``rotation_noise_urad`` and ``rotation_resolution_urad``."""

    sampling: Sampling = field(default_factory=lambda: Sampling(samples=6000, duration_s=600.0))
    cycles: int = 2
    max_torque_Nm: float = 80.0
    torque_noise_Nm: float = 0.1
    noise_ar1: float = 0.0  # lag-one correlation of the torque cell's noise: 0 white
    torque_resolution_Nm: float = 0.001
    rotation_noise_urad: float = 0.05
    rotation_resolution_urad: float = 0.01
    #: several tests in one record: ((cycles, peak Nm), ...) run in turn (replaces cycles and
    #: max_torque_Nm); ``number_tests`` writes their numbers in a test_nr column
    tests: tuple[tuple[int, float], ...] | None = None
    number_tests: bool = False


def torque_program(t: np.ndarray, duration: float, cycles: int, peak: float,
                   tests: tuple[tuple[int, float], ...] | None = None) -> np.ndarray:
    """Applied torque: ``cycles`` x (0 -> +peak -> -peak -> 0) at a constant rate; or, with
    ``tests`` ((cycles, peak), ...), each test's cycles in turn (:func:`test_program`)."""
    return test_program(t, duration, tests or ((cycles, peak),))[0]


def test_program(t: np.ndarray, duration: float, tests: tuple[tuple[int, float], ...]) -> tuple[np.ndarray, np.ndarray]:
    """(applied torque (n,), test index (n,) int) of tests run one after the other, each
    ``cycles`` x (0 -> +peak -> -peak -> 0), the torque changing at one constant rate throughout."""
    knots, owner = [0.0], []
    for k, (cycles, peak) in enumerate(tests):
        for _ in range(cycles):
            knots += [peak, -peak, 0.0]
            owner += [k, k, k]
    knots = np.array(knots)
    dist = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(knots)))])
    travel = t / duration * dist[-1]
    segment = np.clip(np.searchsorted(dist, travel, side="right") - 1, 0, len(owner) - 1)
    return np.interp(travel, dist, knots), np.asarray(owner)[segment]


def _solve_rotation(truth: TorqueTruth, spring_torque: np.ndarray) -> np.ndarray:
    """Rotation (rad) where law + stiffening carries the spring torque (Nm); bisection, monotonic law."""
    drive = truth.drive()
    linear = drive.rotation(spring_torque * 1e3)
    if not truth.stiffening:
        return linear
    amp, ex = truth.stiffening
    lo = np.minimum(0.0, linear)
    hi = np.maximum(0.0, linear)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        f = drive.torque(mid) * 1e-3 + fx.stiffening(mid, amp, ex) - spring_torque
        lo = np.where(f < 0, mid, lo)
        hi = np.where(f >= 0, mid, hi)
    return 0.5 * (lo + hi)


def simulate_torque_deflection(truth: TorqueTruth, rng: np.random.Generator,
                               settings: TorqueSettings | None = None, name: str = "torque_sim") -> Simulated:
    """A torque-deflection record from a truth model (see :class:`TorqueTruth`)."""
    st = settings or TorqueSettings()
    sm = st.sampling
    t = sample_times(sm, rng)
    n = t.size
    tests = st.tests or ((st.cycles, st.max_torque_Nm),)
    applied, test_index = test_program(t, sm.duration_s, tests)
    spring = fx.play_operator(applied, truth.hysteresis_half_width) if truth.hysteresis_half_width else applied
    if truth.amplitude_hysteresis:
        h_ref, growth = truth.amplitude_hysteresis
        peaks = np.array([abs(p) for _, p in tests])
        spring = fx.play_operator(applied, h_ref * (peaks[test_index] / peaks.max()) ** growth)
    phi = _solve_rotation(truth, spring)
    rotation_urad = truth.theta0_urad + fx.dead_zone_inverse(phi * 1e6, truth.dead_band_urad)
    temp_true = temperature_history(t, sm)
    reading = applied.copy()
    expected = []
    if truth.drift_per_kelvin:
        reading += fx.drift(temp_true, truth.drift_per_kelvin, float(temp_true[0]))
        expected.append({"effect": "drift", "per_kelvin": truth.drift_per_kelvin})
    if truth.drift_per_second:
        reading += fx.drift(t, truth.drift_per_second, float(t[0]))
        expected.append({"effect": "drift", "per_second": truth.drift_per_second})
    if truth.hysteresis_half_width:
        expected.append({"effect": "hysteresis", "half_width": truth.hysteresis_half_width})
    if truth.amplitude_hysteresis:
        expected.append({"effect": "amplitude_hysteresis", "half_width": truth.amplitude_hysteresis[0],
                         "exponent": truth.amplitude_hysteresis[1]})
    if truth.stiffening:
        expected.append({"effect": "stiffening", "amplitude": truth.stiffening[0], "exponent": truth.stiffening[1]})
    if truth.dead_band_urad:
        expected.append({"effect": "dead_band", "width_urad": truth.dead_band_urad})
    outside = []
    if truth.step:
        height, frac = truth.step
        reading += height * (t > frac * sm.duration_s)
        outside.append("step")
    if truth.vibration:
        amp, period = truth.vibration
        reading += amp * np.sin(2 * np.pi * t / period)
        outside.append("vibration")
    e_t = st.torque_noise_Nm * unit_noise(rng, n, st.noise_ar1)
    if truth.burst:
        factor, start, length = truth.burst
        inside = (t >= start * sm.duration_s) & (t < (start + length) * sm.duration_s)
        e_t[inside] *= factor
        outside.append("burst")
    torque = reading + e_t
    if st.torque_resolution_Nm > 0:
        torque = np.round(torque / st.torque_resolution_Nm) * st.torque_resolution_Nm
    rot = rotation_urad + st.rotation_noise_urad * rng.normal(size=n)
    if st.rotation_resolution_urad > 0:
        rot = np.round(rot / st.rotation_resolution_urad) * st.rotation_resolution_urad
    # injected noise in residual units: torque error minus local stiffness x rotation error
    drive = truth.drive()
    d = 1e-8

    def total(p):
        out = drive.torque(p) * 1e-3
        if truth.stiffening:
            out = out + fx.stiffening(p, *truth.stiffening)
        return out

    k = (total(phi + d) - total(phi - d)) / (2 * d)
    noise_residual = (torque - reading) - k * (rot - rotation_urad) * 1e-6
    temperature = _read_temperature(temp_true, sm, rng) if sm.temperature else None
    meas = Measurement(kind="torque_deflection", name=name, time_s=t, torque_Nm=torque, rotation_rad=rot * 1e-6,
                       temperature_C=temperature, model=truth.declared_spec(),
                       test_nr=(test_index + 1).astype(float) if st.number_tests else None,
                       description="simulated torque-deflection test (geargen.fit.simulate)")
    return Simulated(meas, float(np.sqrt(np.mean(noise_residual ** 2))), reading, tuple(expected), tuple(outside))


# ----------------------------------------------------------------------------- transmission error

@dataclass(frozen=True)
class TransmissionTruth:
    """Truth of a transmission-error record, urad at the output; phases random unless given.

    ``stages`` (driver, driven) teeth, input to output; ``eccentricity_urad``: once-per-turn
    amplitude of each shaft (input first, output last); ``mesh_urad``: (first harmonic, second
    harmonic) of each stage's tooth mesh. ``declared`` is what the sidecar will declare.
    Undeclared library effects: ``harmonics`` ((order, amplitude, phase_deg), ...);
    ``tooth_pulse`` (shaft index, angle_deg, amplitude, width_deg); ``sidebands`` (stage index,
    shaft index, amplitude of each line); ``ratio_relative`` (measured / declared ratio - 1);
    ``backlash_half_width_urad``; ``drift_per_kelvin``, ``drift_per_second``."""

    stages: tuple[tuple[int, int], ...] = ((12, 36), (15, 45))
    declared: tuple[str, ...] = ("eccentricity", "tooth_to_tooth")
    eccentricity_urad: tuple[float, ...] = (3.0, 6.0, 20.0)
    mesh_urad: tuple[tuple[float, float], ...] = ((4.0, 1.5), (6.0, 2.0))
    harmonics: tuple[tuple[float, float, float], ...] = ()
    tooth_pulse: tuple[int, float, float, float] | None = None
    sidebands: tuple[int, int, float] | None = None
    ratio_relative: float = 0.0
    backlash_half_width_urad: float = 0.0
    drift_per_kelvin: float = 0.0
    drift_per_second: float = 0.0


@dataclass(frozen=True)
class TransmissionSettings:
    """The test: ``revolutions`` of the output forward (and back when ``return_trip``); each
    encoder's noise (urad at its own shaft) and resolution (counts per revolution)."""

    sampling: Sampling = field(default_factory=lambda: Sampling(samples=12000, duration_s=600.0))
    revolutions: float = 1.2
    return_trip: bool = True
    output_noise_urad: float = 0.5
    input_noise_urad: float = 2.0
    output_counts: int = 1 << 24
    input_counts: int = 1 << 18
    speed_ripple: float = 0.08


def simulate_transmission_error(truth: TransmissionTruth, rng: np.random.Generator,
                                settings: TransmissionSettings | None = None, name: str = "te_sim") -> Simulated:
    """A transmission-error record from a truth model (see :class:`TransmissionTruth`).

    The input is driven along a smooth program (forward, and back again); the output follows at
    the true ratio (declared x (1 + ``ratio_relative``)), through the backlash (a play on the
    commanded angle), plus the periodic errors, the pulse, the sidebands and the drift. Each
    encoder reads its shaft with Gaussian noise, then rounds to its counts."""
    from geargen.fit.measurement import TransmissionModelSpec
    from geargen.fit.orders import transmission_orders

    st = settings or TransmissionSettings()
    sm = st.sampling
    t = sample_times(sm, rng)
    n = t.size
    spec = TransmissionModelSpec(stages=tuple(tuple(s) for s in truth.stages), declared=truth.declared)
    orders = transmission_orders(spec.stages)
    shafts = [o for o in orders if o.kind == "shaft"]
    meshes = [o for o in orders if o.kind == "mesh"]
    nominal = output_angle_history(t, sm.duration_s, st.revolutions, st.return_trip, st.speed_ripple)
    true_ratio = spec.ratio * (1.0 + truth.ratio_relative)
    input_angle = true_ratio * nominal
    commanded_urad = input_angle / true_ratio * 1e6  # (= nominal, urad)
    te = np.zeros(n)
    for shaft, amp in zip(shafts, truth.eccentricity_urad):
        te += fx.harmonic(nominal, shaft.order, amp, float(rng.uniform(0, 360)))
    for mesh, (a1, a2) in zip(meshes, truth.mesh_urad):
        te += fx.harmonic(nominal, mesh.order, a1, float(rng.uniform(0, 360)))
        te += fx.harmonic(nominal, 2 * mesh.order, a2, float(rng.uniform(0, 360)))
    expected = []
    declared_names = {"eccentricity"} & set(truth.declared), {"tooth_to_tooth"} & set(truth.declared)
    if not declared_names[0]:
        expected += [{"effect": "harmonic", "order": s.order, "amplitude": a} for s, a in zip(shafts, truth.eccentricity_urad)]
    for order, amp, phase in truth.harmonics:
        te += fx.harmonic(nominal, order, amp, phase)
        expected.append({"effect": "harmonic", "order": order, "amplitude": amp, "phase_deg": phase})
    if truth.tooth_pulse:
        k, angle, amp, width = truth.tooth_pulse
        te += amp * fx.tooth_pulse(shafts[k].order * nominal, angle, width)
        expected.append({"effect": "tooth_pulse", "shaft": shafts[k].name, "angle_deg": angle, "amplitude": amp,
                         "width_deg": width})
    if truth.sidebands:
        j, k, amp = truth.sidebands
        q, s = meshes[j].order, shafts[k].order
        te += fx.harmonic(nominal, q - s, amp, float(rng.uniform(0, 360)))
        te += fx.harmonic(nominal, q + s, amp, float(rng.uniform(0, 360)))
        expected.append({"effect": "sidebands", "order": q, "shaft": shafts[k].name, "amplitude": amp})
    temp_true = temperature_history(t, sm)
    _add_drifts(te, truth, t, temp_true, expected)
    follows = commanded_urad
    if truth.backlash_half_width_urad:
        follows = fx.play_operator(commanded_urad, truth.backlash_half_width_urad)
        expected.append({"effect": "hysteresis", "half_width": truth.backlash_half_width_urad})
    if truth.ratio_relative:
        expected.append({"effect": "ratio_error", "relative": truth.ratio_relative})
    output_true = (follows + te) * 1e-6
    out_read = output_true + st.output_noise_urad * 1e-6 * rng.normal(size=n)
    in_read = input_angle + st.input_noise_urad * 1e-6 * rng.normal(size=n)
    out_step, in_step = 2 * math.pi / st.output_counts, 2 * math.pi / st.input_counts
    out_read = np.round(out_read / out_step) * out_step
    in_read = np.round(in_read / in_step) * in_step
    temperature = _read_temperature(temp_true, sm, rng) if sm.temperature else None
    meas = Measurement(kind="transmission_error", name=name, time_s=t, input_angle_rad=in_read, angle_rad=out_read,
                       temperature_C=temperature, model=spec,
                       description="simulated transmission error record (geargen.fit.simulate)")
    te_clean = (output_true - input_angle / spec.ratio) * 1e6
    return Simulated(meas, float(np.sqrt(np.mean((meas.te_urad - te_clean) ** 2))), te_clean, tuple(expected))
