"""The involute function and the tooth thickness of one gear (transverse section, mm and rad).

Array in, array out: every function accepts floats or numpy arrays of any shape.
"""

from __future__ import annotations

import math

import numpy as np

from geargen.design.gear import GearSpec


def involute(angle):
    """inv(a) = tan(a) - a, for pressure angles a in [0, pi/2) (rad)."""
    a = np.asarray(angle, dtype=float)
    out = np.tan(a) - a
    return float(out) if out.ndim == 0 else out


def inverse_involute(value, tol: float = 1e-15):
    """The angle a in [0, pi/2) with inv(a) = value (value >= 0), by Newton's method.

    Converges to machine precision for inv values up to ~1e3 (angles up to ~89.9 deg).
    """
    v = np.asarray(value, dtype=float)
    if np.any(v < 0) or not np.all(np.isfinite(v)):
        raise ValueError("inverse_involute needs finite values >= 0")
    # start: cube-root series inv(a) ~ a^3/3 for small a, atan-like growth for large ones
    a = np.minimum(np.cbrt(3.0 * v), 1.5)
    for _ in range(60):
        t = np.tan(a)
        f = t - a - v
        step = f / np.maximum(t * t, 1e-300)  # d/da inv(a) = tan^2(a)
        a_new = np.clip(a - step, 0.0, math.pi / 2 - 1e-12)
        if np.all(np.abs(a_new - a) <= tol * np.maximum(1.0, a_new)):
            a = a_new
            break
        a = a_new
    return float(a) if a.ndim == 0 else a


def reference_tooth_thickness(spec: GearSpec) -> float:
    """Transverse arc tooth thickness at the reference circle, after thinning (mm).

    s_t = pi m_t / 2 + 2 x_n m_n tan(alpha_t) - thinning.
    """
    return (math.pi * spec.transverse_module / 2
            + 2 * spec.profile_shift * spec.module * math.tan(spec.transverse_pressure_angle)
            - spec.thinning)


def pressure_angle_at_radius(spec: GearSpec, radius):
    """Transverse pressure angle of the involute at ``radius`` (>= base radius), rad."""
    r = np.asarray(radius, dtype=float)
    if np.any(r < spec.base_radius * (1 - 1e-12)):
        raise ValueError(f"radius below the base circle ({spec.base_radius:.6g} mm) has no involute")
    out = np.arccos(np.clip(spec.base_radius / r, -1.0, 1.0))
    return float(out) if out.ndim == 0 else out


def tooth_half_angle(spec: GearSpec, radius):
    """Half the angle the tooth subtends at ``radius`` on the involute flanks (rad).

    psi(r) = s_t / (2 r_ref) + inv(alpha_t) - inv(alpha_r); the flank at ``radius`` lies at
    polar angle +-psi from the tooth centreline.
    """
    return (reference_tooth_thickness(spec) / (2 * spec.reference_radius)
            + involute(spec.transverse_pressure_angle) - involute(pressure_angle_at_radius(spec, radius)))


def tooth_thickness_at_radius(spec: GearSpec, radius):
    """Transverse arc tooth thickness at ``radius`` (mm); negative where the tooth has come to a point."""
    r = np.asarray(radius, dtype=float)
    out = 2 * r * tooth_half_angle(spec, r)
    return float(out) if np.ndim(out) == 0 else out


def tip_land_thickness(spec: GearSpec) -> float:
    """Transverse arc thickness of the tooth at the tip circle (mm); <= 0 means a pointed tooth."""
    return tooth_thickness_at_radius(spec, spec.tip_radius)


def pointed_tip_radius(spec: GearSpec) -> float:
    """Radius at which the two involute flanks of a tooth meet (mm)."""
    # psi(r) = 0  <=>  inv(alpha_r) = s_t/(2 r_ref) + inv(alpha_t)
    alpha = inverse_involute(reference_tooth_thickness(spec) / (2 * spec.reference_radius)
                             + involute(spec.transverse_pressure_angle))
    return spec.base_radius / math.cos(alpha)
