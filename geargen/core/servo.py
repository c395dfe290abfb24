"""The drive as its servo sees it (Hale & Slocum, Introduction and Fig. 1): the R^2 law, the
position loop's natural frequency and damping, the first resonance of the train, mesh friction,
and the dual-motor drive.

SI units throughout this module (kg·m², N·m, N·m/rad, N·m·s/rad, rad/s): the servo's world. The
callers convert from geargen's internal N·mm at the edge.

Conventions:

* a part turning ``ratio`` times as fast as the output (``ratio`` = its speed over the output's)
  sees an output inertia ``J`` as ``J / ratio^2``; the motor's own inertia appears at the output as
  ``J ratio^2`` (:func:`reflect_inertia`);
* the position loop is a PD law at the motor, ``tau = -Kp theta_m - Kd dtheta_m/dt`` (gains at the
  motor shaft); on a rigid transmission the load sees ``Kp R^2`` and ``Kd R^2``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def reflect_inertia(inertia: float, speed_ratio: float) -> float:
    """Inertia of a part turning ``speed_ratio`` times as fast as the reference shaft, seen at that
    shaft: ``J speed_ratio^2``. (Reflected to a faster shaft, ``speed_ratio`` < 1: divided.)"""
    return inertia * speed_ratio ** 2


@dataclass(frozen=True)
class ClosedLoop:
    """A rigid-body position loop: natural frequency (rad/s) and damping ratio."""

    natural_frequency: float
    damping_ratio: float

    @property
    def natural_frequency_hz(self) -> float:
        return self.natural_frequency / (2 * math.pi)


def closed_loop(inertia_at_motor: float, position_gain: float, velocity_gain: float) -> ClosedLoop:
    """``J theta'' + Kd theta' + Kp theta = 0`` at the motor: ``w_n = sqrt(Kp / J)``,
    ``zeta = Kd / (2 sqrt(Kp J))``."""
    if not (inertia_at_motor > 0 and position_gain > 0 and velocity_gain >= 0):
        raise ValueError("inertia and position gain must be > 0, velocity gain >= 0")
    wn = math.sqrt(position_gain / inertia_at_motor)
    return ClosedLoop(wn, velocity_gain / (2.0 * math.sqrt(position_gain * inertia_at_motor)))


def gains_for(inertia_at_motor: float, natural_frequency: float, damping_ratio: float) -> tuple[float, float]:
    """The PD gains ``(Kp, Kd)`` that give ``natural_frequency`` (rad/s) and ``damping_ratio`` on
    ``inertia_at_motor``."""
    return (natural_frequency ** 2 * inertia_at_motor, 2.0 * damping_ratio * natural_frequency * inertia_at_motor)


@dataclass(frozen=True)
class TwoMass:
    """The two-mass reduction of a train: motor side ``j_motor`` and load side ``j_load`` (both
    at the output, kg·m²) on a spring ``stiffness`` (N·m/rad at the output)."""

    j_motor: float
    j_load: float
    stiffness: float

    @property
    def resonance(self) -> float:
        """Free-free resonance (rad/s): ``sqrt(k (J1 + J2) / (J1 J2))``."""
        return math.sqrt(self.stiffness * (self.j_motor + self.j_load) / (self.j_motor * self.j_load))

    @property
    def antiresonance(self) -> float:
        """The load alone on the spring, the motor held (rad/s): ``sqrt(k / J2)``."""
        return math.sqrt(self.stiffness / self.j_load)


def chain_modes(inertias, stiffnesses) -> np.ndarray:
    """Natural frequencies (rad/s, ascending) of a free-free chain of ``n`` inertias joined by
    ``n - 1`` springs (all at one reference shaft): the eigenvalues of ``K phi = w^2 M phi``.
    The first is the rigid-body mode (0)."""
    j = np.asarray(inertias, dtype=float)
    k = np.asarray(stiffnesses, dtype=float)
    if j.ndim != 1 or k.shape != (len(j) - 1,) or np.any(j <= 0) or np.any(k <= 0):
        raise ValueError("n > 0 inertias and n - 1 > 0 stiffnesses")
    n = len(j)
    stiff = np.zeros((n, n))
    for i, ki in enumerate(k):
        stiff[i:i + 2, i:i + 2] += ki * np.array([[1.0, -1.0], [-1.0, 1.0]])
    root = 1.0 / np.sqrt(j)  # symmetric form M^-1/2 K M^-1/2
    w2 = np.linalg.eigvalsh(stiff * root[:, None] * root[None, :])
    return np.sqrt(np.clip(w2, 0.0, None))


def mesh_loss_factor(friction_coefficient: float, teeth_1: int, teeth_2: int) -> float:
    """Fraction of the power a spur mesh loses to sliding friction, the classical estimate
    ``pi mu (1/z1 + 1/z2)`` (approach and recess each about half a base pitch; an internal mesh
    would take the difference)."""
    return math.pi * friction_coefficient * (1.0 / teeth_1 + 1.0 / teeth_2)


# ---------------------------------------------------------------------------------------------
# The dual-motor drive (Fig. 1)

DUAL_MOTOR_CONTROLS = ("unidirectional", "bias")


@dataclass(frozen=True)
class DualMotorDrive:
    """Two motors, each driving the output through its own transmission (stiffness ``k1``,
    ``k2`` at the output, N·m/rad; backlash ``backlash`` rad at the output each), coordinated as
    in Fig. 1 (torques at the output, N·m):

    * ``"unidirectional"`` (Fig. 1a): ``T1 = bias + max(c, 0)``, ``T2 = -bias + min(c, 0)``; neither
      transmission reverses, one motor does the work;
    * ``"bias"`` (Fig. 1b): ``T1 = c/2 + bias``, ``T2 = c/2 - bias``; beyond ``|c| = 2 bias`` one
      transmission reverses (it crosses its backlash) and then both motors work together.

    A transmission carrying torque holds the output on its flank; while one crosses its backlash
    only the other holds it. The motors are held by their loops (stiff beside the transmissions).
    ``peak`` is one motor's torque limit at the output.
    """

    k1: float
    k2: float
    bias: float
    control: str
    peak: float
    backlash: float = 0.0

    def __post_init__(self):
        if self.control not in DUAL_MOTOR_CONTROLS:
            raise ValueError(f"control must be one of {DUAL_MOTOR_CONTROLS}")

    def motor_torques(self, command) -> tuple[np.ndarray, np.ndarray]:
        """(T1, T2) at the output for net torque command(s) ``c`` (T1 + T2 = c)."""
        c = np.asarray(command, dtype=float)
        if self.control == "unidirectional":
            return self.bias + np.maximum(c, 0.0), -self.bias + np.minimum(c, 0.0)
        return c / 2 + self.bias, c / 2 - self.bias

    @property
    def capacity(self) -> float:
        """Largest net output torque either way before a motor reaches ``peak``."""
        return self.peak - self.bias if self.control == "unidirectional" else 2.0 * self.peak

    @property
    def reversal_command(self) -> float | None:
        """|command| at which one transmission reverses (crosses its backlash); None if never."""
        return None if self.control == "unidirectional" else 2.0 * self.bias

    def zones(self) -> list[dict]:
        """The command ranges (N·m at the output, 0 to ``capacity``; the negative side mirrors it)
        and the drive stiffness in each: both transmissions opposed, one crossing its backlash, both
        working together."""
        both = self.k1 + self.k2
        cap = self.capacity
        if self.control == "unidirectional" or self.reversal_command >= cap:
            return [dict(zone="opposed", command_from=0.0, command_to=cap, stiffness=both,
                         lost_motion=0.0)]
        c = self.reversal_command
        return [dict(zone="opposed", command_from=0.0, command_to=c, stiffness=both, lost_motion=0.0),
                dict(zone="crossing", command_from=c, command_to=c, stiffness=self.k1, lost_motion=self.backlash),
                dict(zone="together", command_from=c, command_to=cap, stiffness=both, lost_motion=0.0)]

    def bias_for(self, max_load: float) -> float:
        """Smallest bias that keeps both transmissions loaded in opposition up to ``max_load``:
        any positive bias for unidirectional torques (returned 0), ``max_load / 2`` with a constant
        bias (as the paper's Type 2 preload)."""
        return 0.0 if self.control == "unidirectional" else max_load / 2.0

    def peak_needed(self, max_load: float) -> float:
        """Each motor's torque (at the output) to carry ``max_load`` with this drive's bias."""
        if self.control == "unidirectional":
            return max_load + self.bias
        return max_load / 2.0 + self.bias


__all__ = ["reflect_inertia", "ClosedLoop", "closed_loop", "gains_for", "TwoMass", "chain_modes", "mesh_loss_factor",
           "DUAL_MOTOR_CONTROLS", "DualMotorDrive"]
