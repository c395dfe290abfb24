"""The two-path spring model of an anti-backlash drive (Hale & Slocum, Eqs. 2-6, Figs. 6-7).

Every stiffness here is referred to one common place and kind (by convention torsion at the
output); torques and rotations are in any consistent unit (N·mm and rad inside geargen).

Model (Fig. 7). Path forces ``F1 = k1 (d + w + c1)``, ``F2 = k2 (d - w - c2)`` with drive
displacement ``d`` and loop coordinate ``w`` (the preload carriage); the preload spring
``k3`` acts on ``w`` with lever 1 on each path, so ``F1 - F2 = k3 (s - w)``. At zero drive
torque each path carries the loop preload ``P`` (path 1 +P, path 2 -P) and the spring 2P,
the radial-motion preload of Fig. 9. Type 1 is the limit ``k3 -> inf`` (``w`` fixed).
Positive drive torque unloads path 2; negative unloads path 1. Beyond unloading the loaded
path carries the whole torque: alone (type 1) or in series with ``k3`` (type 2).
Backlash beyond the unloaded flank is taken as larger than any deflection considered.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geargen.errors import DesignError

DRIVE_TYPES = ("type1", "type2")


@dataclass(frozen=True)
class TwoPathDrive:
    """Two preloaded paths ``k1``, ``k2``, preload spring ``k3`` (type 2 only), loop preload ``preload``."""

    drive_type: str
    k1: float
    k2: float
    preload: float
    k3: float = math.inf

    def __post_init__(self):
        if self.drive_type not in DRIVE_TYPES:
            raise DesignError("drive", f"{self.drive_type!r} is not a valid choice", "'type1', 'type2'")
        for name in ("k1", "k2"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise DesignError(name, f"{v!r} is out of range", "> 0 and finite")
        if self.drive_type == "type2":
            if not (self.k3 > 0 and not math.isnan(self.k3)):
                raise DesignError("k3", f"{self.k3!r} is out of range", "> 0 (type2 needs a preload spring)")
        elif self.k3 != math.inf:
            raise DesignError("k3", "a type1 drive has no preload spring", "omit k3 for type1")
        if not (math.isfinite(self.preload) and self.preload >= 0):
            raise DesignError("preload", f"{self.preload!r} is out of range", ">= 0")

    @property
    def _k3_compliance(self) -> float:
        return 0.0 if self.k3 == math.inf else 1.0 / self.k3

    @property
    def drive_stiffness(self) -> float:
        """k_D while both paths carry load: Eq. 2 (type 1) or Eq. 5 (type 2)."""
        k1, k2 = self.k1, self.k2
        if self.k3 == math.inf:
            return k1 + k2  # Eq. 2
        return (k1 + k2) - (k1 - k2) ** 2 / (k1 + k2 + self.k3)  # Eq. 5

    @property
    def loop_stiffness(self) -> float:
        """k_L: Eq. 3 (type 1) or Eq. 6 (type 2)."""
        return 1.0 / (1.0 / self.k1 + 1.0 / self.k2 + 4.0 * self._k3_compliance)  # Eq. 6; k3=inf gives Eq. 3

    @property
    def stiffness_ratio(self) -> float:
        """k_D / k_L, Eq. 4 for type 1 (minimal at k1 = k2)."""
        return self.drive_stiffness / self.loop_stiffness

    @property
    def path_force_rates(self) -> tuple[float, float]:
        """(dF1/dd, dF2/dd) while both paths are loaded."""
        k1, k2 = self.k1, self.k2
        if self.k3 == math.inf:
            return k1, k2
        s = k1 + k2 + self.k3
        return k1 * (2 * k2 + self.k3) / s, k2 * (2 * k1 + self.k3) / s

    @property
    def unloading_rotations(self) -> tuple[float, float]:
        """Drive displacements (negative, positive) at which path 1 resp. path 2 unloads."""
        g1, g2 = self.path_force_rates
        return -self.preload / g1, self.preload / g2

    @property
    def unloading_torques(self) -> tuple[float, float]:
        """Drive torques (negative, positive) at which one path unloads."""
        lo, hi = self.unloading_rotations
        kd = self.drive_stiffness
        return kd * lo, kd * hi

    def stiffness_beyond(self, side: int) -> float:
        """Drive stiffness once one path has unloaded: side +1 (path 1 alone loaded) or -1 (path 2)."""
        k = self.k1 if side > 0 else self.k2
        return 1.0 / (1.0 / k + self._k3_compliance)

    def torque(self, rotation) -> np.ndarray:
        """Drive torque for drive rotation(s); the piecewise-linear law of the contract."""
        d = np.asarray(rotation, dtype=float)
        lo, hi = self.unloading_rotations
        t_lo, t_hi = self.unloading_torques
        kd = self.drive_stiffness
        return np.where(d > hi, t_hi + self.stiffness_beyond(+1) * (d - hi),
                        np.where(d < lo, t_lo + self.stiffness_beyond(-1) * (d - lo), kd * d))

    def rotation(self, torque) -> np.ndarray:
        """Drive rotation for drive torque(s): the inverse of :meth:`torque` (it is monotonic)."""
        t = np.asarray(torque, dtype=float)
        lo, hi = self.unloading_rotations
        t_lo, t_hi = self.unloading_torques
        kd = self.drive_stiffness
        return np.where(t > t_hi, hi + (t - t_hi) / self.stiffness_beyond(+1),
                        np.where(t < t_lo, lo + (t - t_lo) / self.stiffness_beyond(-1), t / kd))

    def path_torques(self, rotation) -> tuple[np.ndarray, np.ndarray]:
        """Torques (F1, F2) in the two paths; path 1 carries +preload at zero drive."""
        d = np.asarray(rotation, dtype=float)
        lo, hi = self.unloading_rotations
        g1, g2 = self.path_force_rates
        t = self.torque(d)
        f1 = np.where(d > hi, t, np.where(d < lo, 0.0, self.preload + g1 * d))
        f2 = np.where(d > hi, 0.0, np.where(d < lo, t, -self.preload + g2 * d))
        return f1, f2
