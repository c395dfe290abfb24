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


def working_pressure_angle_at(base_radius_sum, centre_distance, clamp: bool = False):
    """Transverse working pressure angle (rad) of a pair at ``centre_distance`` a: cos(alpha_w) = R_b / a.

    ``base_radius_sum`` R_b is r_b1 + r_b2 for an external pair, r_b2 - r_b1 for an internal one
    (the line of action is tangent to both base circles). Where a does not reach R_b the pair has
    no line of action: NaN, or with ``clamp`` (a placement a rounding hair inside) 0. Array in,
    array out (broadcast shape); numpy values go through numpy's arccos, plain floats through
    math.acos (the two differ in the last bit, and each caller keeps the one it had).
    """
    if not any(isinstance(v, (np.ndarray, np.generic)) for v in (base_radius_sum, centre_distance)):
        cos_w = base_radius_sum / centre_distance
        if clamp:
            return math.acos(min(cos_w, 1.0))
        return math.acos(cos_w) if 0 < cos_w <= 1.0 else math.nan
    c = np.asarray(centre_distance, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        cos_w = np.asarray(base_radius_sum, dtype=float) / c
        if clamp:
            out = np.arccos(np.minimum(cos_w, 1.0))
        else:
            out = np.where((cos_w > 0) & (cos_w <= 1.0), np.arccos(np.clip(cos_w, -1.0, 1.0)), np.nan)
    return float(out) if out.ndim == 0 else out


def backlash_change(radius_sum, working_pressure_angle, tight_involute):
    """Backlash (mm) of a pair whose teeth mesh tight at the pressure angle with involute
    ``tight_involute``, run at ``working_pressure_angle`` alpha_w: j = 2 R (inv(alpha_w) - inv_0).

    Measured on one circle of each gear, the two at a common pressure angle, with radii summing to
    ``radius_sum`` R: the base circles (R = r_b1 + r_b2) give the play along the line of action,
    the reference circles (R = the standard centre distance) the arc there, the working pitch
    circles (R = a) the working arc. For a small change da of centre distance the working arc
    grows by 2 tan(alpha_w) da. Array in, array out.
    """
    out = 2 * np.asarray(radius_sum, dtype=float) * (involute(working_pressure_angle) - tight_involute)
    return float(out) if np.ndim(out) == 0 else out


def roll_length(radius, base_radius):
    """Length (mm) along the line of action from the base tangent point to the involute at
    ``radius``: sqrt(r^2 - r_b^2) (0 inside the base circle)."""
    out = np.sqrt(np.maximum(np.asarray(radius, dtype=float) ** 2 - np.asarray(base_radius, dtype=float) ** 2, 0.0))
    return float(out) if np.ndim(out) == 0 else out


def length_of_action(tip_radii, base_radii, centre_distance, internal: bool = False) -> float:
    """Transverse length of the path of contact g_alpha (mm), tip circle to tip circle.

    External pair: g = sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a sin(alpha_w), with
    cos(alpha_w) = (r_b1 + r_b2) / a. Internal pair (gear 2 the ring): g = sqrt(r_a1^2 - r_b1^2) -
    sqrt(r_a2^2 - r_b2^2) + a sin(alpha_w), cos(alpha_w) = (r_b2 - r_b1) / a. The contact ratio is
    g over the transverse base pitch.
    """
    (ra1, ra2), (rb1, rb2) = tip_radii, base_radii
    if internal:
        alpha_w = math.acos((rb2 - rb1) / centre_distance)
        return roll_length(ra1, rb1) - roll_length(ra2, rb2) + centre_distance * math.sin(alpha_w)
    alpha_w = math.acos((rb1 + rb2) / centre_distance)
    return roll_length(ra1, rb1) + roll_length(ra2, rb2) - centre_distance * math.sin(alpha_w)


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
