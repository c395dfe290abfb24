"""The exact transverse outline of an external involute gear cut by a generating rack.

Frame and conventions (every solid and mesh check uses these):

- transverse plane, gear axis through the origin, mm and rad;
- tooth 0 is centred on the +x axis; tooth k is tooth 0 turned by ``2 pi k / z``
  counter-clockwise;
- the outline runs counter-clockwise: one pitch sector goes lower fillet, lower flank, tip arc,
  upper flank, upper fillet, then the root arc to the next tooth. "Upper" is the flank on the
  +y side of tooth 0 (the one facing tooth 1).
- helical gears: the transverse section at height z (the face runs from z = 0 to the face
  width) is the z = 0 section turned by :func:`section_rotation` ``= s z tan(beta) / r``
  counter-clockwise, with ``s = +1`` for a right-hand and ``-1`` for a left-hand helix
  (a right-hand helix advances along +z while turning counter-clockwise seen from +z).

The rack (transverse section of the normal basic rack, after profile shift and thinning)
rolls on the reference circle. Its straight flank cuts the involute; its rounded tip - a circle
of radius ``rack_tip_radius_coefficient m_n`` in the normal section, so an ellipse with
semi-axes ``rho / cos(beta)`` (tangential) and ``rho`` (radial) in the transverse one - cuts the
fillet as the envelope of its positions; its tip line cuts the root circle. Where the fillet
envelope cuts into the involute (low tooth counts), the involute starts at their intersection
(undercut), which :func:`tooth_profile` reports and warns about.

Rack coordinates used below: ``u`` along the rolling line (+y at the pitch point ``(r, 0)``),
``v`` radially outward from the rolling line. When the gear has turned by ``phi`` the rack has
moved by ``sigma = r phi`` along +y; a rack point ``(u, v)`` sits in the gear frame at
``R(-sigma/r) (r + v, u + sigma)``. A rack point generates the gear where its normal passes
through the pitch point: ``sigma = -u + v n_u / n_v``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from geargen.core.involute import involute, reference_tooth_thickness
from geargen.design.gear import GearSpec
from geargen.errors import GeometryError
from geargen.profile.segments import ArcCurve, InvoluteCurve, Segment, outline_area
from geargen.units import length_text

#: the tip land (transverse arc at the tip circle) must be at least this many normal modules
MIN_TIP_LAND_MODULES = 1e-3


class UndercutWarning(UserWarning):
    """The generating rack's tip cuts into the involute: the usable flank starts above the fillet joint."""


def section_rotation(spec: GearSpec, z) -> float | np.ndarray:
    """Counter-clockwise turn (rad) of the transverse section at height ``z`` (mm) against z = 0.

    ``+z tan(beta) / r`` for a right-hand helix, ``-z tan(beta) / r`` for a left-hand one
    (``r`` the reference radius); 0 for a spur gear.
    """
    k = math.tan(spec.helix_angle) / spec.reference_radius * (1.0 if spec.hand == "right" else -1.0)
    out = k * np.asarray(z, dtype=float)
    return float(out) if out.ndim == 0 else out


def twist_rate(spec: GearSpec) -> float:
    """d(section rotation)/dz in rad/mm (signed by hand, see :func:`section_rotation`)."""
    return section_rotation(spec, 1.0)


class FilletCurve:
    """Envelope cut by the rack's rounded tip on the upper side of tooth 0 (tooth 0 to tooth 1 gap).

    Parametrised by the angle ``theta`` of the tip rounding in the normal section:
    ``theta = pi + alpha_n`` is where the rounding meets the rack flank, ``theta = 3 pi / 2``
    where it meets the tip line. Rack point (transverse): ``(u_c + rho cos(theta) / cos(beta),
    v_c + rho sin(theta))``, outward normal along ``(cos(beta) cos(theta), sin(theta))``.
    ``rho = 0`` (sharp rack corner) gives the corner's own path.
    """

    def __init__(self, reference_radius, centre_u, centre_v, tip_radius, cos_beta):
        self.r = float(reference_radius)
        self.uc = float(centre_u)
        self.vc = float(centre_v)
        self.rho = float(tip_radius)
        self.cb = float(cos_beta)

    def _parts(self, theta):
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        c, s = np.cos(th), np.sin(th)
        u = self.uc + self.rho * c / self.cb
        v = self.vc + self.rho * s
        sigma = -u + v * self.cb * c / s
        return c, s, u, v, sigma

    def point(self, theta):
        c, s, u, v, sigma = self._parts(theta)
        phi = -sigma / self.r
        x, y = self.r + v, u + sigma
        cp, sp = np.cos(phi), np.sin(phi)
        return np.column_stack([cp * x - sp * y, sp * x + cp * y])

    def derivative(self, theta):
        c, s, u, v, sigma = self._parts(theta)
        du = -self.rho * s / self.cb
        dv = self.rho * c
        dsigma = -du + dv * self.cb * c / s - v * self.cb / (s * s)
        phi = -sigma / self.r
        dphi = -dsigma / self.r
        x, y = self.r + v, u + sigma
        # d/dtheta [R(phi) q] = R(phi) (q' + phi' J q), J q = (-y, x)
        qx = dv - dphi * y
        qy = du + dsigma + dphi * x
        cp, sp = np.cos(phi), np.sin(phi)
        return np.column_stack([cp * qx - sp * qy, sp * qx + cp * qy])


@dataclass(frozen=True)
class ToothProfile:
    """The exact outline of a gear's transverse section at z = 0 (see the module docstring).

    ``segments`` is one pitch sector of tooth 0, counter-clockwise from the gap centre at polar
    angle ``-pi/z`` to the gap centre at ``+pi/z`` (half root arcs at both ends when the rack's
    tip line cuts a root circle). :meth:`outline` gives the whole gear.

    Radii in mm. ``involute_start_radius`` is where the usable involute begins (the fillet
    joint, or the undercut intersection); ``involute_start_roll`` the roll angle there.
    ``undercut`` is true when the rack tip cuts into the involute; ``fillet_joint_roll`` is then
    the (negative) roll angle of the point the rack flank's end would generate.
    """

    spec: GearSpec
    segments: tuple[Segment, ...]
    reference_radius: float
    base_radius: float
    tip_radius: float
    root_radius: float
    involute_start_radius: float
    involute_start_roll: float
    tip_roll: float
    base_half_angle: float
    tip_half_angle: float
    root_arc_half_angle: float  # polar angle where the root arc starts (0 < ... <= pi/z)
    undercut: bool
    fillet_joint_roll: float
    warnings: tuple[str, ...] = field(default=())

    @property
    def teeth(self) -> int:
        return self.spec.teeth

    @property
    def pitch_angle(self) -> float:
        return 2 * math.pi / self.spec.teeth

    @property
    def tip_land(self) -> float:
        """Transverse arc thickness at the tip circle (mm)."""
        return 2 * self.tip_radius * self.tip_half_angle

    def tooth_segments(self) -> tuple[Segment, ...]:
        """Tooth 0 without the root arcs: lower fillet, lower flank, tip, upper flank, upper fillet."""
        return tuple(s for s in self.segments if s.kind != "root_arc")

    def pitch_segments(self) -> list[Segment]:
        """Tooth 0 and the root arc to tooth 1 (when there is a root circle): the piece of the
        outline that repeats ``z`` times."""
        out = list(self.tooth_segments())
        if self.root_arc_half_angle < math.pi / self.teeth:
            out.append(Segment("root_arc", "", ArcCurve(self.root_radius), self.root_arc_half_angle,
                               self.pitch_angle - self.root_arc_half_angle))
        return out

    def outline(self, rotation: float = 0.0) -> list[Segment]:
        """The whole gear outline, counter-clockwise, turned by ``rotation`` (rad).

        Per tooth k: lower fillet, lower flank, tip arc, upper flank, upper fillet, then one root
        arc to tooth k+1 (when there is a root circle). Joints coincide to machine precision.
        """
        base = self.pitch_segments()
        return [s.rotated(rotation + k * self.pitch_angle, tooth=k) for k in range(self.teeth) for s in base]

    def section_outline(self, z: float) -> list[Segment]:
        """The outline of the transverse section at height ``z`` (mm), see :func:`section_rotation`."""
        return self.outline(section_rotation(self.spec, z))

    def area(self) -> float:
        """Area of the gear outline (mm^2, bore not subtracted), Green's theorem on the segments."""
        return self.teeth * outline_area(self.segments)

    def involute_half_angle(self, radius):
        """Polar angle of the upper flank of tooth 0 at ``radius`` (>= base radius), rad."""
        r = np.asarray(radius, dtype=float)
        alpha = np.arccos(np.clip(self.base_radius / r, -1.0, 1.0))
        out = self.base_half_angle - involute(alpha)
        return float(out) if np.ndim(out) == 0 else out


def tooth_profile(spec: GearSpec, warn: bool = True) -> ToothProfile:
    """The exact outline of ``spec`` (z = 0 section); raises :class:`GeometryError` if impossible.

    Error kinds: ``negative_root`` (root circle at or below the axis), ``pointed_rack`` (the
    generating rack's teeth come to a point above its tip line: the dedendum cannot be cut),
    ``no_involute`` (tip circle inside the base circle, or the undercut removes the whole
    flank), ``pointed_tooth`` (tip land below ``MIN_TIP_LAND_MODULES`` normal modules),
    ``severed_tooth`` (an undercut so deep that the rack tip's paths from both flanks meet
    inside the tooth), ``fillet_loop`` (the fillet envelope loops back on itself).
    With ``warn``, an undercut also raises an :class:`UndercutWarning` (it is always listed
    in ``ToothProfile.warnings``).
    """
    z = spec.teeth
    m_n = spec.module
    alpha_n = spec.pressure_angle
    alpha_t = spec.transverse_pressure_angle
    cb = math.cos(spec.helix_angle)
    r = spec.reference_radius
    r_b = spec.base_radius
    r_a = spec.tip_radius
    p_t = spec.transverse_pitch
    s_t = reference_tooth_thickness(spec)

    h_f = (spec.dedendum_coefficient - spec.profile_shift) * m_n  # tip line below the rolling line
    r_f = r - h_f
    if r_f <= 0:
        raise GeometryError("negative_root", f"root radius {r_f:.6g} mm <= 0: dedendum "
                            f"{spec.dedendum_coefficient} - profile shift {spec.profile_shift} "
                            f"reaches past the axis of a {z}-tooth gear")
    if r_a <= r_f:
        raise GeometryError("no_involute", f"tip radius {r_a:.6g} mm is not above the root radius {r_f:.6g} mm")

    # rack tip rounding: centre (u_c, v_c), normal-section radius rho
    rho = spec.rack_tip_radius_coefficient * m_n
    v_c = -h_f + rho
    u_cn = s_t * cb / 2 - v_c * math.tan(alpha_n) + rho / math.cos(alpha_n)
    u_c = u_cn / cb
    if u_c > p_t / 2 * (1 + 1e-12):
        raise GeometryError("pointed_rack", f"the generating rack's teeth come to a point above its tip "
                            f"line (dedendum coefficient {spec.dedendum_coefficient}, pressure angle "
                            f"{math.degrees(alpha_n):.4g} deg, rack tip radius coefficient "
                            f"{spec.rack_tip_radius_coefficient:.4g}): lower the dedendum or the pressure angle")
    u_c = min(u_c, p_t / 2)
    fillet = FilletCurve(r, u_c, v_c, rho, cb)
    theta_joint = math.pi + alpha_n
    theta_root = 1.5 * math.pi

    psi_b = s_t / (2 * r) + involute(alpha_t)  # half angle of the tooth at the base circle
    flank = InvoluteCurve(r_b, psi_b)

    if r_a <= r_b:
        raise GeometryError("no_involute", f"tip radius {r_a:.6g} mm is inside the base circle {r_b:.6g} mm")
    t_a = math.sqrt((r_a / r_b) ** 2 - 1.0)
    psi_a = psi_b - involute(math.acos(r_b / r_a))
    land = 2 * r_a * psi_a
    if land < MIN_TIP_LAND_MODULES * m_n:
        unit = spec.length_unit
        raise GeometryError("pointed_tooth", f"{spec.name}: tip land {length_text(land, unit)} (transverse arc at the "
                            f"tip circle, radius {length_text(r_a, unit, 6)}) is below {MIN_TIP_LAND_MODULES:g} m_n "
                            f"({length_text(MIN_TIP_LAND_MODULES * m_n, unit)}): the flanks meet below the tip "
                            "circle; reduce the profile shift or the addendum")

    # roll angle of the involute point generated by the end of the rack's straight flank
    v_f = v_c - rho * math.sin(alpha_n)
    t_joint = (r * math.sin(alpha_t) + v_f / math.sin(alpha_t)) / r_b
    undercut = t_joint < 0.0
    notes: list[str] = []
    if not undercut:
        t_start, theta_start = t_joint, theta_joint
    else:
        theta_start, t_start = _undercut_intersection(fillet, flank, r_b, theta_joint, theta_root)
        if theta_start is None and math.sqrt(1.0 + t_joint * t_joint) - 1.0 <= 1e-9:
            # so slight an undercut that the crossing is lost in rounding (within 1e-9 r_b of the
            # base circle): the involute starts at the base circle
            theta_start, t_start = theta_joint, 0.0
        if theta_start is None:
            raise GeometryError("no_involute", "the rack tip's fillet cuts the whole involute flank away")
    r_start = r_b * math.sqrt(1.0 + t_start * t_start)
    start = length_text(r_start, spec.length_unit, 6)  # messages in the design's unit
    if t_start >= t_a or r_start >= r_a:
        raise GeometryError("no_involute", f"the involute would start at radius {start}, at or above the tip "
                            f"circle {length_text(r_a, spec.length_unit, 6)} (undercut removes the flank)")
    if undercut:
        msg = (f"undercut: the rack tip cuts into the involute of this {z}-tooth gear (profile shift "
               f"{spec.profile_shift:g}); the usable involute starts at radius {start} instead of at the "
               f"fillet joint")
        notes.append(msg)
        if warn:
            warnings.warn(msg, UndercutWarning, stacklevel=2)

    # the fillet may not cross the gap centre line (polar angle pi/z): clip it there if it does
    half_pitch = math.pi / z
    theta_end = theta_root
    root_half = u_c / r
    th = np.linspace(theta_start, theta_root, 257)
    ang = np.arctan2(fillet.point(th)[:, 1], fillet.point(th)[:, 0])
    if np.max(ang) > half_pitch:
        i = int(np.argmax(ang > half_pitch))
        theta_end = _bisect(lambda t: math.atan2(*fillet.point(t)[0][::-1]) - half_pitch, th[i - 1], th[i])
        root_half = half_pitch
    if root_half > half_pitch * (1 - 1e-12):
        root_half = half_pitch
    # a deep undercut: the paths of the rack tips from both sides must not meet inside the tooth
    pts = fillet.point(np.linspace(theta_start, theta_end, 513))
    ang = np.arctan2(pts[:, 1], pts[:, 0])
    rad = np.hypot(pts[:, 0], pts[:, 1])
    if np.min(ang) <= 0.0:
        r_cut = float(rad[int(np.argmin(ang))])
        raise GeometryError("severed_tooth", f"undercut so deep that the rack tip cuts through the tooth "
                            f"near radius {r_cut:.6g} mm (the tooth would come off): raise the profile shift "
                            f"or the tooth count")
    if np.any(np.diff(rad) > 1e-9 * r):
        raise GeometryError("fillet_loop", "the fillet cut by the rack tip loops back on itself "
                            "(radius not falling towards the root): the rack cannot generate this gear")

    upper = [
        Segment("involute", "upper", flank, t_a, t_start),
        Segment("fillet", "upper", fillet, theta_start, theta_end),
    ]
    lower = [
        Segment("fillet", "lower", fillet, theta_end, theta_start, mirrored=True),
        Segment("involute", "lower", flank, t_start, t_a, mirrored=True),
    ]
    tip = Segment("tip_arc", "", ArcCurve(r_a), -psi_a, psi_a)
    segs = []
    if root_half < half_pitch:
        segs.append(Segment("root_arc", "", ArcCurve(r_f), -half_pitch, -root_half))
    segs += lower + [tip] + upper
    if root_half < half_pitch:
        segs.append(Segment("root_arc", "", ArcCurve(r_f), root_half, half_pitch))

    return ToothProfile(spec=spec, segments=tuple(segs), reference_radius=r, base_radius=r_b,
                        tip_radius=r_a, root_radius=r_f, involute_start_radius=r_start,
                        involute_start_roll=t_start, tip_roll=t_a, base_half_angle=psi_b,
                        tip_half_angle=psi_a, root_arc_half_angle=root_half, undercut=undercut,
                        fillet_joint_roll=t_joint, warnings=tuple(notes))


def _bisect(f, a: float, b: float, iterations: int = 200) -> float:
    """Root of ``f`` in [a, b] (sign change assumed), to the last bit of the bracket."""
    fa = f(a)
    for _ in range(iterations):
        m = 0.5 * (a + b)
        if m <= a or m >= b:
            break
        fm = f(m)
        if (fm > 0) == (fa > 0):
            a, fa = m, fm
        else:
            b = m
    return 0.5 * (a + b)


def _undercut_intersection(fillet: FilletCurve, flank: InvoluteCurve, r_b: float,
                           theta_joint: float, theta_root: float):
    """Where the fillet envelope crosses the upper involute: (theta, roll) or (None, None).

    f(theta) = polar angle of the fillet point - polar angle of the involute at the same radius;
    positive in the gap, negative inside the tooth.
    """
    def f(theta):
        p = fillet.point(theta)
        rad = np.hypot(p[:, 0], p[:, 1])
        alpha = np.arccos(np.clip(r_b / rad, -1.0, 1.0))
        return np.arctan2(p[:, 1], p[:, 0]) - (flank.base_half_angle - involute(alpha)), rad

    lo, hi = theta_joint, theta_root
    for _ in range(8):  # a slight undercut crosses just past the joint: zoom in on it
        th = np.linspace(lo, hi, 2049)
        val, rad = f(th)
        inside = (val < 0) & (rad >= r_b)
        if np.any(inside):
            i = int(np.argmax(inside))
            if i > 0 and rad[i - 1] >= r_b:
                break
        below = np.nonzero(rad < r_b)[0]
        if len(below) == 0 or below[0] == 0:
            return None, None
        hi = th[below[0]]
    else:
        return None, None
    theta = _bisect(lambda t: float(f(t)[0][0]), th[i - 1], th[i])
    p = fillet.point(theta)[0]
    rad = math.hypot(p[0], p[1])
    roll = math.sqrt(max((rad / r_b) ** 2 - 1.0, 0.0))
    return theta, roll


#: depth of a double-helical gear's centre-gap groove below the teeth's root circle, over the normal
#: module. A groove at the root radius itself would coincide with the root lands and touch the
#: fillets (the kernel's fuse then gave invalid solids); 0.01 m_n deeper it is clear of them, and a
#: hob or shaper needs the run-out anyway.
GROOVE_DEPTH_COEFFICIENT = 0.01


def centre_gap_radius(spec: GearSpec, profile: ToothProfile) -> float:
    """Radius of a double-helical gear's blank in its centre gap (mm): the root radius less 0.01 m_n."""
    return profile.root_radius - GROOVE_DEPTH_COEFFICIENT * spec.module


__all__ = ["GROOVE_DEPTH_COEFFICIENT", "centre_gap_radius", "ToothProfile", "tooth_profile", "section_rotation", "twist_rate", "FilletCurve",
           "UndercutWarning", "MIN_TIP_LAND_MODULES"]
