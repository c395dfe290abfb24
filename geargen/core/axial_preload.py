"""Axial-motion preload (Hale & Slocum, "Design of anti-backlash transmissions", Design section):
a left- and a right-hand helical pinion (or one herringbone pinion) on an input shaft that slides
axially, pushed by a spring, each hand meshing with one of the drive's two paths.

The model (mm, rad, N). The input shaft has two freedoms, its turn theta and its axial slide z.
Mesh 1 (one hand) and mesh 2 (the other) load the pinion in opposite senses of rotation, so the
turn shares the preload between the paths while the slide closes both at once:

- a helical flank is an involute helicoid whose normal has the axial component sin(beta_b) and
  the moment r_b cos(beta_b) about the axis; a normal contact force F_n therefore gives the axial
  force F_a = F_n sin(beta_b) and the tangential force at the reference circle
  F_t = F_n r_b cos(beta_b) / r = F_n cos(alpha_t) cos(beta_b), so F_a = F_t tan(beta)
  (tan(beta_b) = tan(beta) cos(alpha_t));
- axial balance of the shaft with no drive torque: F_spring = F_a1 + F_a2 = 2 F_t tan(beta), so each
  path carries the tangential preload F_t = F_spring / (2 tan(beta)) and the preload torque on the
  pinion per path is F_t r;
- the slide z moves each flank along its normal by z sin(beta_b) (the turn adds to one mesh what it
  takes from the other), so taking up the loop's total normal backlash j_bn (both meshes) needs
  z = j_bn / (2 sin(beta_b)); in transverse circumferential backlash at the reference circle
  j_t = j_bn / (cos(alpha_t) cos(beta_b)) that is z = j_t / (2 tan(beta));
- the sliding fit's friction mu N opposes the slide; N is the sum of the radial loads the sliding
  fit carries, N = k F_t with the lateral-force factor k. With one sliding fit at the meshes (a
  bushing under both) k is the transverse resultant of the two meshes' forces,
  k = 2 |sin(phi / 2 - alpha_wt)| / cos(alpha_wt) for gear centres phi apart (0 when phi = 2 alpha_wt:
  the paper's Figure 9 optimum, lines of action parallel, no lateral force). With a shaft sliding
  in two bearings (:func:`input_bearing_reactions`) N is the sum of the two bearings' reactions,
  which also carry the couples of the meshes: their tangential forces, opposite and a face apart,
  and their axial forces, at the pitch radius off the axis; k then grows with tan(beta). The
  friction-to-preload ratio (friction force over the axial preload force) is mu k / (2 tan(beta)):
  it grows as the helix angle shrinks, as the paper warns. Friction makes the preload a hysteresis band:
  F_spring / (2 tan(beta) + mu k) while the shaft slides in, F_spring / (2 tan(beta) - mu k) while it
  slides out; at mu k >= 2 tan(beta) the shaft locks (the spring no longer sets the preload).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from geargen.errors import DesignError

BACKLASH_KINDS = ("normal", "transverse_circumferential")


def _positive(name: str, value: float, allowed: str = "> 0") -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise DesignError(name, f"{value!r} is out of range", allowed)


def _helix(helix_angle: float) -> None:
    if not (isinstance(helix_angle, (int, float)) and 0 < helix_angle < math.pi / 2):
        raise DesignError("helix_angle", f"{helix_angle!r} rad is out of range: axial preload needs a helix",
                          "(0, 90) deg")


def base_helix_angle(normal_pressure_angle: float, helix_angle: float) -> float:
    """beta_b: sin(beta_b) = sin(beta) cos(alpha_n)."""
    return math.asin(math.sin(helix_angle) * math.cos(normal_pressure_angle))


def tangential_preload(spring_force: float, helix_angle: float) -> float:
    """Tangential preload per path at the reference circle (N) from the spring's axial force (N)
    shared by the two opposite-hand meshes: F_spring / (2 tan(beta))."""
    _positive("spring_force", spring_force)
    _helix(helix_angle)
    return spring_force / (2 * math.tan(helix_angle))


def preload_torque(spring_force: float, helix_angle: float, reference_radius: float) -> float:
    """Preload torque per path on the pinion (N mm): tangential preload x reference radius."""
    _positive("reference_radius", reference_radius)
    return tangential_preload(spring_force, helix_angle) * reference_radius


def lateral_force_factor(placement_angle: float, working_pressure_angle: float) -> float:
    """k = N / F_t: the transverse resultant of both meshes' forces on the pinion over the
    tangential preload, for gear centres ``placement_angle`` apart (rad, counted from the gear whose
    mesh force turns the pinion counter-clockwise toward the other), each mesh force the tangential
    preload plus its separating force F_t tan(alpha_wt): 2 |sin(phi / 2 - alpha_wt)| / cos(alpha_wt)."""
    return 2 * abs(math.sin(placement_angle / 2 - working_pressure_angle)) / math.cos(working_pressure_angle)


def input_bearing_reactions(mesh_heights: tuple[float, float], bearing_heights: tuple[float, float],
                            tangential_force: float, separating_force: float, axial_force: float,
                            pitch_radius: float) -> tuple[float, float]:
    """The radial reactions (N, magnitudes) at the sliding input shaft's two bearings (mid-planes at
    ``bearing_heights``, mm along the shaft) from the two meshes' forces on its pinions (mid-faces at
    ``mesh_heights``) at no drive torque. Each mesh, at the pitch point on the output's side of the
    shaft, pushes its pinion away from the output with ``separating_force``, turns it with
    ``tangential_force`` (the two meshes in opposite senses: a couple over their distance) and pushes
    it back along the axis with ``axial_force`` (both meshes the same way, against the spring): a
    moment ``axial_force x pitch_radius`` each about the transverse axis, in the plane of centres.
    Statics of a shaft on two supports (moments about the lower bearing)."""
    (z1, z2), (za, zb) = mesh_heights, bearing_heights
    span = zb - za
    _positive("bearing span", span)
    # in the plane of centres (x away from the output): both separating forces, less the axial forces'
    # moment (it tilts the shaft toward the output at the top: F_z = -F_a at x = -r_w)
    upper_x = -(separating_force * (z1 - za) + separating_force * (z2 - za) - 2 * axial_force * pitch_radius) / span
    lower_x = -2 * separating_force - upper_x
    # across it: the tangential forces, opposite, a couple
    upper_y = -tangential_force * ((z1 - za) - (z2 - za)) / span
    return math.hypot(lower_x, upper_y), math.hypot(upper_x, upper_y)


def friction_to_preload_ratio(friction_coefficient: float, helix_angle: float, lateral_factor: float) -> float:
    """Friction force in the sliding fit over the axial preload force: mu k / (2 tan(beta))."""
    if not (math.isfinite(friction_coefficient) and friction_coefficient >= 0):
        raise DesignError("friction_coefficient", f"{friction_coefficient!r} is out of range", ">= 0")
    _helix(helix_angle)
    return friction_coefficient * lateral_factor / (2 * math.tan(helix_angle))


@dataclass(frozen=True)
class PreloadBand:
    """The tangential preload per path (N) while the shaft slides in (``low``: friction against
    the spring), with no friction (``nominal``) and while it slides out (``high``: friction with the
    spring); ``high`` is inf when the shaft locks (``locks``)."""

    low: float
    nominal: float
    high: float
    friction_to_preload: float
    locks: bool

    @property
    def hysteresis(self) -> float:
        """Width of the band over its nominal preload (inf when the shaft locks)."""
        return (self.high - self.low) / self.nominal


def preload_band(spring_force: float, helix_angle: float, friction_coefficient: float,
                 lateral_factor: float) -> PreloadBand:
    """The preload's hysteresis band from the sliding fit's friction mu k F_t (see the module)."""
    nominal = tangential_preload(spring_force, helix_angle)
    ratio = friction_to_preload_ratio(friction_coefficient, helix_angle, lateral_factor)
    t2 = 2 * math.tan(helix_angle)
    friction = friction_coefficient * lateral_factor
    locks = friction >= t2
    high = math.inf if locks else spring_force / (t2 - friction)
    return PreloadBand(spring_force / (t2 + friction), nominal, high, ratio, locks)


def axial_travel_for_backlash(backlash: float, normal_pressure_angle: float, helix_angle: float,
                              kind: str = "normal") -> float:
    """Axial slide of the input shaft (mm) that takes up the loop's total backlash (both meshes,
    mm): ``kind`` ``normal`` (along the line of action in the normal plane): j_bn / (2 sin(beta_b));
    ``transverse_circumferential`` (arc at the reference circle): j_t / (2 tan(beta))."""
    if not (math.isfinite(backlash) and backlash >= 0):
        raise DesignError("backlash", f"{backlash!r} mm is out of range", ">= 0 mm")
    _helix(helix_angle)
    if kind == "normal":
        return backlash / (2 * math.sin(base_helix_angle(normal_pressure_angle, helix_angle)))
    if kind == "transverse_circumferential":
        return backlash / (2 * math.tan(helix_angle))
    raise DesignError("kind", f"{kind!r} is not a backlash kind", ", ".join(map(repr, BACKLASH_KINDS)))


@dataclass(frozen=True)
class HelixChoice:
    """One row of the helix-angle choice table (per newton of spring force, per um of backlash)."""

    helix_angle_deg: float
    preload_per_spring_force: float  # F_t / F_spring
    friction_to_preload: float
    hysteresis: float  # band width over nominal preload (inf: the shaft locks)
    travel_per_um_normal_backlash: float  # um of slide per um of loop normal backlash


def _lateral_at(lateral_factor, helix_angle: float) -> float:
    """k at ``helix_angle``: a number, or a function of the helix angle (the bearings' reactions)."""
    return float(lateral_factor(helix_angle)) if callable(lateral_factor) else float(lateral_factor)


def helix_angle_table(friction_coefficient: float, normal_pressure_angle: float, lateral_factor,
                      helix_angles_deg=(5, 10, 15, 20, 25, 30, 35, 40, 45)) -> list[HelixChoice]:
    """The helix-angle choice: what each angle gives for the sliding fit's friction ``mu`` and the
    layout's lateral-force factor k (:func:`lateral_force_factor`, a number; or a function of the
    helix angle, rad, when the shaft's bearings carry the meshes' couples)."""
    rows = []
    for deg in helix_angles_deg:
        beta = math.radians(deg)
        band = preload_band(1.0, beta, friction_coefficient, _lateral_at(lateral_factor, beta))
        rows.append(HelixChoice(float(deg), band.nominal, band.friction_to_preload,
                                band.hysteresis, axial_travel_for_backlash(1.0, normal_pressure_angle, beta)))
    return rows


def smallest_helix_angle(friction_coefficient: float, lateral_factor, max_friction_to_preload: float) -> float | None:
    """The smallest helix angle (rad) whose friction-to-preload ratio stays within the limit. With a
    constant k the closed form atan(mu k / (2 limit)); with k a function of the helix angle the first
    crossing of the limit (a 0.1 deg scan, then bisection to 1e-9 rad): the bearings' share of the
    axial forces' moment grows with the pitch radius, 1 / cos(beta), so the ratio has a least value
    and None says that no helix angle reaches the limit."""
    _positive("max_friction_to_preload", max_friction_to_preload)
    if not callable(lateral_factor):
        return math.atan(friction_coefficient * lateral_factor / (2 * max_friction_to_preload))

    def excess(beta: float) -> float:
        return friction_to_preload_ratio(friction_coefficient, beta, lateral_factor(beta)) - max_friction_to_preload
    previous = math.radians(0.1)
    if excess(previous) <= 0:
        return previous
    for tenth in range(2, 900):
        beta = math.radians(tenth / 10)
        if excess(beta) <= 0:
            lo, hi = previous, beta
            while hi - lo > 1e-9:
                mid = (lo + hi) / 2
                lo, hi = (lo, mid) if excess(mid) <= 0 else (mid, hi)
            return hi
        previous = beta
    return None


__all__ = ["tangential_preload", "preload_torque", "lateral_force_factor", "input_bearing_reactions",
           "friction_to_preload_ratio",
           "PreloadBand", "preload_band", "axial_travel_for_backlash", "HelixChoice", "helix_angle_table",
           "smallest_helix_angle", "base_helix_angle", "BACKLASH_KINDS"]
