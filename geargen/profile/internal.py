"""The exact transverse outline of an internal (ring) gear cut by a pinion-type shaper cutter.

Conventions (as :mod:`geargen.profile.tooth`, with the ring's *tooth space* in the place of the
external gear's tooth): transverse plane, ring axis through the origin, mm and rad; tooth space
0 is centred on the +x axis, space k is space 0 turned by ``2 pi k / z``; the outline (the ring's
inner boundary) runs counter-clockwise around the hole, one pitch sector being: lower involute
(outward), lower fillet, root arc, upper fillet, upper involute (inward), tip arc to the next
space. Helical rings: the section at height z is the z = 0 section turned by
:func:`geargen.profile.tooth.section_rotation` (right hand: counter-clockwise with +z), the same
rule as external gears, so a pinion and its ring of the same hand mesh.

Profile shift (ISO 21771 / KHK convention): ``x > 0`` moves the generating profile away from the
ring axis, into the rim: tip radius ``r - m_n (h_a* - x)``, root radius ``r + m_n (h_f* + x)``,
space width at the reference circle ``pi m_t / 2 + 2 x m_n tan(alpha_t)`` (plus the thinning of
the ring's teeth). The tooth space is then exactly the tooth of an external gear of the same
z, m, alpha and x.

Why a shaper cutter, not a rack: a rack cannot cut an internal gear. The generating cutter here is
a standard (unshifted) external involute gear of ``z_0`` teeth, the ring's module and pressure
angle and addendum ``h_f* m_n`` (the ring's dedendum coefficient), that meshes with the ring without backlash at the cutting centre distance (the internal-pair
formula ``inv a_w = inv a_t + (e_2 - s_0) / (2 (r - r_0))``); its tip circle cuts the ring's
root circle ``r_f = a_0 + r_a0`` (DIN 3960's d_f2 = 2 a_0 + d_a0; the spec's nominal
``r + m_n (h_f* + x)`` is the rack-equivalent value), and its tip corners are rounded with radius ``rho = rack_tip_radius_coefficient m_n``
in the transverse section. The
cutter's involute generates the ring's involute; each tip rounding generates a fillet, the
envelope of the rounding circle in the ring's frame (the offset by ``rho`` of the trochoid of the
rounding's centre); the tip land generates the root circle. :func:`cutter_teeth` is the default
cutter size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geargen.core.involute import involute, inverse_involute
from geargen.design.gear import GearSpec
from geargen.families.internal.spec import MIN_RIM_WALL_MODULES, InternalGearSpec
from geargen.errors import GeometryError
from geargen.profile.segments import ArcCurve, InvoluteCurve, Segment, outline_area
from geargen.units import length_text

#: the ring's tooth land (transverse arc at the tip circle) must be at least this many normal modules
MIN_TIP_LAND_MODULES = 1e-3
#: complex-step size for the fillet's exact derivative (no subtraction, so no cancellation)
_COMPLEX_STEP = 1e-30


def cutter_teeth(spec: GearSpec) -> int:
    """Where the default cutter search starts: half the ring's teeth, at least 12, at most ``z - 3``.

    :func:`internal_profile` without a cutter takes the first tooth count from here up to
    ``z - 3`` that generates the ring (not pointed, and free of involute interference with the
    ring: its involute reaches the ring's tip circle). Half the ring keeps the cutter clear of the
    ring's teeth while it is fed in; 12 teeth is about the smallest disc shaper cutter.
    """
    return int(min(max(12, spec.teeth // 2), spec.teeth - 3))


def space_width(spec: GearSpec) -> float:
    """Transverse arc width of the ring's tooth space at the reference circle (mm):
    ``pi m_t / 2 + 2 x m_n tan(alpha_t) + thinning`` (thinning the ring's teeth widens the space)."""
    return (math.pi * spec.transverse_module / 2
            + 2 * spec.profile_shift * spec.module * math.tan(spec.transverse_pressure_angle) + spec.thinning)


class CutterFilletCurve:
    """Fillet cut in the ring by the upper tip rounding of the shaper cutter (canonical, upper side
    of space 0), parametrised by the direction ``theta`` (rad, cutter frame) of the rounding's
    outward normal: from the involute joint ``theta_j`` down to the tip-land joint ``theta_t``.

    For each ``theta`` the contact point ``Q = C + rho n(theta)`` generates the ring where the
    normal line through ``Q`` passes through the pitch point, which lies on the cutter's pitch
    circle (radius ``r_0``) at polar angle ``psi``; the cutter has then turned by ``-psi`` and the
    ring by ``-psi r_0 / r``. Everything is analytic in ``theta``, so the derivative is taken by
    complex step (exact to rounding).
    """

    def __init__(self, ring_radius, cutter_radius, centre_distance, centre, rho):
        self.r2 = float(ring_radius)
        self.r0 = float(cutter_radius)
        self.a0 = float(centre_distance)
        self.cx, self.cy = float(centre[0]), float(centre[1])
        self.rho = float(rho)

    def _eval(self, theta):
        nx, ny = np.cos(theta), np.sin(theta)
        qx, qy = self.cx + self.rho * nx, self.cy + self.rho * ny
        qn = qx * nx + qy * ny
        # the nearer crossing of the normal line with the pitch circle (behind Q)
        s = -qn + np.sqrt(qn * qn - (qx * qx + qy * qy) + self.r0 ** 2)
        px, py = qx + s * nx, qy + s * ny
        psi = np.arctan(py / px)  # |psi| < pi/2 near the cutter's tooth 0; complex-safe
        phi0 = -psi
        phi2 = phi0 * self.r0 / self.r2
        c0, s0 = np.cos(phi0), np.sin(phi0)
        wx, wy = self.a0 + c0 * qx - s0 * qy, s0 * qx + c0 * qy
        c2, s2 = np.cos(-phi2), np.sin(-phi2)
        return c2 * wx - s2 * wy, s2 * wx + c2 * wy

    def point(self, t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        x, y = self._eval(t)
        return np.column_stack([x, y])

    def derivative(self, t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        x, y = self._eval(t + 1j * _COMPLEX_STEP)
        return np.column_stack([x.imag, y.imag]) / _COMPLEX_STEP


@dataclass(frozen=True)
class InternalProfile:
    """The exact outline of a ring's transverse section at z = 0 (see the module docstring).

    Radii in mm: ``tip_radius`` the ring's tip circle (inner), ``root_radius`` its root circle
    (outer, cut by the cutter's tip land), ``form_radius`` where the generated fillet meets the
    involute (the usable involute runs from ``tip_radius`` out to it). Angles: ``space_base_half_angle``
    the polar angle of the upper flank of space 0 at the base circle; ``space_tip_half_angle`` at the
    tip circle; ``root_arc_half_angle`` where the root arc begins.
    """

    spec: GearSpec
    segments: tuple[Segment, ...]
    reference_radius: float
    base_radius: float
    tip_radius: float
    root_radius: float
    rim_radius: float
    form_radius: float
    tip_roll: float
    form_roll: float
    space_base_half_angle: float
    space_tip_half_angle: float
    root_arc_half_angle: float
    cutter_teeth: int
    warnings: tuple[str, ...] = ()

    @property
    def teeth(self) -> int:
        return self.spec.teeth

    @property
    def pitch_angle(self) -> float:
        return 2 * math.pi / self.spec.teeth

    @property
    def tip_land(self) -> float:
        """Transverse arc thickness of a ring tooth at its tip circle (mm)."""
        return self.tip_radius * (self.pitch_angle - 2 * self.space_tip_half_angle)

    def pitch_segments(self) -> list[Segment]:
        """Space 0 and the tip arc to space 1: the piece of the outline that repeats ``z`` times."""
        return list(self.segments)

    def outline(self, rotation: float = 0.0) -> list[Segment]:
        """The ring's whole inner outline, counter-clockwise, turned by ``rotation`` (rad)."""
        base = self.pitch_segments()
        return [s.rotated(rotation + k * self.pitch_angle, tooth=k) for k in range(self.teeth) for s in base]

    def hole_area(self) -> float:
        """Area enclosed by the inner outline (mm^2)."""
        return self.teeth * outline_area(self.segments)

    def area(self) -> float:
        """Area of the ring's transverse section: rim disc minus the hole (mm^2)."""
        return math.pi * self.rim_radius ** 2 - self.hole_area()

    def space_half_angle(self, radius):
        """Polar angle of the upper flank of space 0 at ``radius`` (involute range), rad."""
        r = np.asarray(radius, dtype=float)
        alpha = np.arccos(np.clip(self.base_radius / r, -1.0, 1.0))
        out = self.space_base_half_angle - involute(alpha)
        return float(out) if np.ndim(out) == 0 else out

    def flank_frame(self) -> "SpaceAsTooth":
        """The ring's spaces seen as the teeth of an external gear, in the terms
        :func:`geargen.cad.measure.flank_deviation` reads (usable involute ``tip_radius`` ..
        ``form_radius``)."""
        return SpaceAsTooth(self.spec, self.pitch_angle, self.teeth, self.base_radius, self.space_base_half_angle,
                            self.tip_radius, self.form_radius)


@dataclass(frozen=True)
class SpaceAsTooth:
    """An internal profile's spaces in the attributes of a :class:`ToothProfile` that the flank
    measurements read: the usable involute runs from ``involute_start_radius`` (the ring's tip
    circle) to ``tip_radius`` (the ring's form circle)."""

    spec: GearSpec
    pitch_angle: float
    teeth: int
    base_radius: float
    base_half_angle: float
    involute_start_radius: float
    tip_radius: float


def internal_profile(spec: GearSpec, cutter: int | None = None) -> InternalProfile:
    """The exact outline of the ring ``spec`` (kind ``internal``) cut by a shaper cutter of
    ``cutter`` teeth (default: see :func:`cutter_teeth`); raises :class:`GeometryError`.

    Error kinds: ``cutter_too_thick`` (a standard cutter's tooth does not fit the ring's space),
    ``thin_rim`` (the rim leaves less than 0.5 m_n outside the cut root circle), ``tip_inside_base`` (the ring's tip circle is inside its base circle: no involute
    there; ISO 21771 requires d_a2 > d_b2), ``cutter_too_large`` (cutter not smaller than the ring by
    2 teeth), ``pointed_cutter`` (the cutter's tip rounding leaves no tip land: lower the rounding
    or the dedendum), ``cutter_interference`` (the cutter's involute cannot reach the ring's tip
    circle: the ring's tip would be cut below its involute), ``no_involute`` (the fillet reaches
    the tip circle), ``pointed_tooth`` (ring tooth land below ``MIN_TIP_LAND_MODULES`` m_n),
    ``fillet_loop`` (the generated fillet is not monotone in radius).
    """
    if not isinstance(spec, InternalGearSpec):
        raise GeometryError("not_internal", f"{spec.name} is an {spec.kind} gear, not an internal one")
    if cutter is not None:
        return _cut_by(spec, int(cutter))
    start = cutter_teeth(spec)
    first_error = None
    for z0 in range(start, spec.teeth - 2):
        try:
            return _cut_by(spec, z0)
        except GeometryError as exc:
            if exc.kind not in ("pointed_cutter", "cutter_interference", "cutter_too_thick"):
                raise
            first_error = first_error or exc
    raise first_error or GeometryError("cutter_too_large", f"no shaper cutter fits a {spec.teeth}-tooth ring")


def _cut_by(spec: GearSpec, z0: int) -> InternalProfile:
    z = spec.teeth
    if z0 > z - 2:
        raise GeometryError("cutter_too_large", f"a {z0}-tooth cutter cannot cut a {z}-tooth ring (at most {z - 2})")
    m_n = spec.module
    m_t = spec.transverse_module
    alpha_t = spec.transverse_pressure_angle
    r2, rb2 = spec.reference_radius, spec.base_radius
    ra2 = spec.tip_radius
    if ra2 <= rb2:
        raise GeometryError("tip_inside_base", f"the ring's tip circle (radius {ra2:.6g} mm) is inside its base "
                            f"circle ({rb2:.6g} mm): its teeth have no involute there; raise the profile shift "
                            f"(x = {spec.profile_shift:g}) or lower the addendum")
    e2 = space_width(spec)
    psi_b = e2 / (2 * r2) + involute(alpha_t)  # half angle of the space at the base circle

    # the cutter: a standard (unshifted) external gear of z0 teeth whose addendum reaches the ring's
    # root circle, cutting without backlash at the working centre distance of the pair (cutter, ring)
    r0 = z0 * m_t / 2
    rb0 = r0 * math.cos(alpha_t)
    s0 = math.pi * m_t / 2
    inv_w = involute(alpha_t) + (e2 - s0) / (2 * (r2 - r0))
    if inv_w <= 0:
        raise GeometryError("cutter_too_thick", f"the {z0}-tooth standard cutter's tooth is thicker than the ring's "
                            f"space ({e2:.4g} mm at the reference circle) at any centre distance: raise the profile "
                            "shift or the thinning")
    alpha_w = inverse_involute(inv_w)
    a0 = (rb2 - rb0) / math.cos(alpha_w)
    rw0, rw2 = rb0 / math.cos(alpha_w), rb2 / math.cos(alpha_w)
    ra0 = r0 + spec.dedendum_coefficient * m_n
    rf2 = a0 + ra0  # DIN 3960 / ISO 21771: d_f2 = 2 a_0 + d_a0, the root the cutter cuts
    if spec.rim_diameter / 2 < rf2 + MIN_RIM_WALL_MODULES * m_n:
        raise GeometryError("thin_rim", f"the rim (diameter {spec.rim_diameter:.6g} mm) leaves less than "
                            f"{MIN_RIM_WALL_MODULES:g} m_n outside the cut root circle (diameter {2 * rf2:.6g} mm)")
    rho = spec.rack_tip_radius_coefficient * m_n
    psi_b0 = s0 / (2 * r0) + involute(alpha_t)
    rc = ra0 - rho  # the rounding's centre, on the involute offset by rho into the tooth
    if rc <= rb0:
        raise GeometryError("pointed_cutter", f"the cutter's tip rounding ({rho:.4g} mm) reaches below its base circle")
    lc = math.sqrt(rc * rc - rb0 * rb0)
    gamma_c = psi_b0 - rho / rb0 - involute(math.acos(rb0 / rc))
    if gamma_c <= 0:
        raise GeometryError("pointed_cutter", f"the {z0}-tooth cutter's tip roundings (radius {rho:.4g} mm) meet "
                            f"at its tip radius {ra0:.6g} mm: no tip land to cut the root circle; lower the "
                            "dedendum, the profile shift or rack_tip_radius_coefficient")
    tau_c = psi_b0 - rho / rb0 - lc / rb0  # polar angle of the base tangent point of C's involute
    theta_j, theta_t = tau_c + math.pi / 2, gamma_c

    # the cutter's involute must reach down to the point that generates the ring's tip
    roll_len_tip = rb2 * math.tan(math.acos(rb2 / ra2)) - (rb2 - rb0) * math.tan(alpha_w)
    if roll_len_tip < 0:
        raise GeometryError("cutter_interference", f"the ring's tip circle ({ra2:.6g} mm) lies inside the "
                            f"{z0}-tooth cutter's base circle on the line of action: its tip cannot be generated "
                            "as an involute; raise the profile shift or the tooth count")

    fillet = CutterFilletCurve(rw2, rw0, a0, (rc * math.cos(gamma_c), rc * math.sin(gamma_c)), rho)
    p_joint = fillet.point(theta_j)[0]
    r_form = float(np.hypot(*p_joint))
    t_form = math.sqrt(max((r_form / rb2) ** 2 - 1.0, 0.0))
    t_tip = math.sqrt((ra2 / rb2) ** 2 - 1.0)
    if r_form <= ra2 * (1 + 1e-12):
        raise GeometryError("no_involute", f"the generated fillet reaches the ring's tip circle ({ra2:.6g} mm)")
    th = np.linspace(theta_j, theta_t, 257)
    rad = np.hypot(*fillet.point(th).T)
    if np.any(np.diff(rad) < -1e-9 * r2):
        raise GeometryError("fillet_loop", "the fillet cut by the shaper cutter is not monotone in radius")
    root_half = gamma_c * rw0 / rw2
    psi_a = psi_b - involute(math.acos(rb2 / ra2))
    half_pitch = math.pi / z
    land = ra2 * (2 * half_pitch - 2 * psi_a)
    if land < MIN_TIP_LAND_MODULES * m_n:
        raise GeometryError("pointed_tooth", f"{spec.name}: the ring's tooth land {length_text(land, spec.length_unit)} at "
                            f"its tip circle is below {MIN_TIP_LAND_MODULES:g} m_n "
                            f"({length_text(MIN_TIP_LAND_MODULES * m_n, spec.length_unit)}): lower the profile shift "
                            "or the thinning")
    flank = InvoluteCurve(rb2, psi_b)
    segs = (
        Segment("involute", "lower", flank, t_tip, t_form, mirrored=True),
        Segment("fillet", "lower", fillet, theta_j, theta_t, mirrored=True),
        Segment("root_arc", "", ArcCurve(rf2), -root_half, root_half),
        Segment("fillet", "upper", fillet, theta_t, theta_j),
        Segment("involute", "upper", flank, t_form, t_tip),
        Segment("tip_arc", "", ArcCurve(ra2), psi_a, 2 * half_pitch - psi_a),
    )
    return InternalProfile(spec=spec, segments=segs, reference_radius=r2, base_radius=rb2, tip_radius=ra2,
                           root_radius=rf2, rim_radius=spec.rim_diameter / 2, form_radius=r_form, tip_roll=t_tip,
                           form_roll=t_form, space_base_half_angle=psi_b, space_tip_half_angle=psi_a,
                           root_arc_half_angle=root_half, cutter_teeth=z0)


__all__ = ["InternalProfile", "SpaceAsTooth", "CutterFilletCurve", "internal_profile", "cutter_teeth", "space_width"]
