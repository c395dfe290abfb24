"""Straight bevel gear geometry: cones, the back-cone (Tredgold) equivalent, the spherical involute.

Frame: apex at the origin, gear axis +z. A point of the tooth is given by its distance R from
the apex and, on the sphere of radius R, its polar angle theta (from +z) and azimuth phi.

Spherical involute (the definition used): the curve a point of a great circle traces on the
sphere when the great circle's plane rolls without slipping on the base cone of half angle
delta_b, with sin delta_b = sin delta cos alpha (delta the pitch cone angle, alpha the pressure
angle). Rolled through the angle t about the axis, the generating plane has turned the point
through psi = t sin delta_b along its great circle, so

    P(t) = R (cos psi g(t) - sin psi e(t)),   g = (sin delta_b cos t, sin delta_b sin t, cos delta_b),
                                              e = (-sin t, cos t, 0),

which gives cos theta = cos delta_b cos psi and phi = t - atan(tan psi / sin delta_b): the
spherical involute function ``inv_s`` (phi at theta, the involute starting at phi = 0 on the base
cone) tends to the plane involute as delta_b -> 0 at constant R sin delta_b.

Every tooth surface is a cone through the apex (flanks over the spherical involute, tip and root
cones), so a tooth's section on the sphere of radius R is the heel's scaled by R / R_e.
Below the base cone (when the root cone is inside it) the flank continues along the meridian.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from geargen.core.involute import length_of_action
from geargen.families.bevel.spec import BevelGearSpec
from geargen.errors import DesignError, GeometryError


def pitch_cone_angles(teeth: int, mate_teeth: int, shaft_angle: float) -> tuple[float, float]:
    """(delta1, delta2) of a pair: tan delta1 = sin Sigma / (z2/z1 + cos Sigma), delta2 = Sigma - delta1."""
    d1 = math.atan2(math.sin(shaft_angle), mate_teeth / teeth + math.cos(shaft_angle))
    return d1, shaft_angle - d1


def base_cone_angle(pitch_cone: float, pressure_angle: float) -> float:
    """delta_b with sin delta_b = sin delta cos alpha."""
    return math.asin(math.sin(pitch_cone) * math.cos(pressure_angle))


def spherical_involute_roll(polar, base_cone: float):
    """psi (rad) at polar angle ``polar`` (>= base_cone): cos psi = cos theta / cos delta_b."""
    th = np.asarray(polar, dtype=float)
    out = np.arccos(np.clip(np.cos(th) / math.cos(base_cone), -1.0, 1.0))
    return float(out) if out.ndim == 0 else out


def spherical_involute_function(polar, base_cone: float):
    """inv_s(theta) = psi / sin delta_b - atan(tan psi / sin delta_b): the azimuth the spherical
    involute has turned back through at polar angle ``polar`` (0 on the base cone)."""
    psi = np.asarray(spherical_involute_roll(polar, base_cone))
    sb = math.sin(base_cone)
    out = psi / sb - np.arctan2(np.sin(psi), np.cos(psi) * sb)
    return float(out) if out.ndim == 0 else out


def spherical_involute_points(roll, base_cone: float, radius: float = 1.0) -> np.ndarray:
    """Points ``(n, 3)`` of the spherical involute starting at azimuth 0 on the base cone, at the
    rolling angles ``roll`` = t (about the axis), on the sphere of ``radius`` (the defining
    parametrisation of the module docstring; the azimuth grows with the polar angle: phi = inv_s(theta))."""
    t = np.atleast_1d(np.asarray(roll, dtype=float))
    sb, cb = math.sin(base_cone), math.cos(base_cone)
    psi = t * sb
    g = np.stack([sb * np.cos(t), sb * np.sin(t), np.full_like(t, cb)], axis=-1)
    e = np.stack([-np.sin(t), np.cos(t), np.zeros_like(t)], axis=-1)
    return radius * (np.cos(psi)[:, None] * g - np.sin(psi)[:, None] * e)


def gleason_profile_shift(teeth: int, mate_teeth: int, shaft_angle: float) -> float:
    """The profile shift x of the pinion (the mate gets -x) that gives Gleason's addendum rule for
    straight bevel gears, h_a2 = 0.54 m + 0.46 m / (z2 cos d1 / (z1 cos d2)), h_a1 = 2 m - h_a2."""
    d1, d2 = pitch_cone_angles(teeth, mate_teeth, shaft_angle)
    ha2 = 0.54 + 0.46 / (mate_teeth * math.cos(d1) / (teeth * math.cos(d2)))
    return (2 - ha2) - 1.0


@dataclass(frozen=True)
class BevelGeometry:
    """One bevel gear's derived quantities (mm, rad). Diameters and mounting distances of the
    standard (back-cone heel) definition: tip diameter d_a = d + 2 h_a cos delta, apex to crown
    X = R_e cos delta - h_a sin delta. ``solid_*``: the same of the built solid, whose heel is the
    sphere of radius R_e about the apex (its crown at R_e on the tip cone, its back at R_e on the axis)."""

    pitch_cone_angle: float
    mate_pitch_cone_angle: float
    base_cone_angle: float
    tip_cone_angle: float  # face angle delta_a = delta + theta_a
    root_cone_angle: float  # delta_f = delta - theta_f
    addendum_angle: float
    dedendum_angle: float
    cone_distance: float  # R_e (heel)
    toe_cone_distance: float  # R_i = R_e - b
    mean_cone_distance: float
    reference_diameter: float
    tip_diameter: float
    root_diameter: float
    apex_to_crown: float
    axial_face_width: float  # X_b = b cos delta_a / cos theta_a
    virtual_teeth: float  # z_v = z / cos delta (back cone)
    virtual_reference_radius: float  # R_e tan delta
    solid_tip_diameter: float
    solid_apex_to_crown: float
    solid_apex_to_back: float
    solid_crown_to_back: float
    warnings: tuple = field(default_factory=tuple)


def bevel_geometry(spec: BevelGearSpec) -> BevelGeometry:
    d = spec.pitch_cone_angle
    re, b = spec.cone_distance, spec.face_width
    ha, hf = spec.addendum, spec.dedendum
    ta, tf = spec.addendum_angle, spec.dedendum_angle
    da = d + ta
    return BevelGeometry(
        pitch_cone_angle=d, mate_pitch_cone_angle=spec.mate_pitch_cone_angle,
        base_cone_angle=base_cone_angle(d, spec.pressure_angle), tip_cone_angle=da, root_cone_angle=d - tf,
        addendum_angle=ta, dedendum_angle=tf, cone_distance=re, toe_cone_distance=re - b,
        mean_cone_distance=re - b / 2, reference_diameter=spec.reference_diameter,
        tip_diameter=spec.reference_diameter + 2 * ha * math.cos(d),
        root_diameter=spec.reference_diameter - 2 * hf * math.cos(d),
        apex_to_crown=re * math.cos(d) - ha * math.sin(d), axial_face_width=b * math.cos(da) / math.cos(ta),
        virtual_teeth=spec.teeth / math.cos(d) if d < math.pi / 2 - 1e-12 else math.inf,
        virtual_reference_radius=re * math.tan(d) if d < math.pi / 2 - 1e-12 else math.inf,
        solid_tip_diameter=2 * re * math.sin(da), solid_apex_to_crown=re * math.cos(da), solid_apex_to_back=re,
        solid_crown_to_back=re * (1 - math.cos(da)), warnings=tuple(spec.warnings))


def tooth_half_angle(spec: BevelGearSpec, polar):
    """Half the azimuth the tooth spans at polar angle ``polar`` (any R: the tooth is a cone).

    phi(theta) = s / d + inv_s(delta) - inv_s(theta) with s = pi m / 2 + 2 x m tan alpha - thinning the
    arc thickness on the heel pitch circle (d = z m its diameter); below the base cone the flank is
    the meridian at phi(delta_b)."""
    d = spec.pitch_cone_angle
    db = base_cone_angle(d, spec.pressure_angle)
    s = math.pi * spec.module / 2 + 2 * spec.profile_shift * spec.module * math.tan(spec.pressure_angle) - spec.thinning
    th = np.maximum(np.asarray(polar, dtype=float), db)
    out = s / spec.reference_diameter + spherical_involute_function(d, db) - spherical_involute_function(th, db)
    return float(out) if np.ndim(out) == 0 else out


def tooth_solid_angle(spec: BevelGearSpec, points: int = 4001) -> float:
    """Solid angle (sr) of one tooth above the root cone: the integral of 2 phi(theta) sin theta
    d theta from delta_f to delta_a (composite Simpson; the integrand is smooth but for a kink at
    the base cone, where the interval is split)."""
    from scipy.integrate import simpson
    g = bevel_geometry(spec)
    lo, hi = g.root_cone_angle, g.tip_cone_angle
    cuts = [lo] + ([g.base_cone_angle] if lo < g.base_cone_angle < hi else []) + [hi]
    total = 0.0
    for a, b in zip(cuts[:-1], cuts[1:]):
        th = np.linspace(a, b, points)
        total += simpson(2 * tooth_half_angle(spec, th) * np.sin(th), x=th)
    return total


def gear_solid_angle(spec: BevelGearSpec) -> float:
    """Solid angle of the whole toothed blank on a sphere about the apex: the cap inside the root
    cone plus the teeth. Times (R_e^3 - R_i^3) / 3 it is the volume between the toe and heel spheres."""
    g = bevel_geometry(spec)
    return 2 * math.pi * (1 - math.cos(g.root_cone_angle)) + spec.teeth * tooth_solid_angle(spec)


def check_tooth(spec: BevelGearSpec) -> None:
    """GeometryError for a tooth that cannot be made: pointed at the tip cone (``pointed_tooth``),
    no space left at the root (``no_tooth_space``), or ``interference``: on the back-cone equivalent
    spur pair, the mate's tip (addendum (h_a* - x) m, the mate of a Gleason-style pair) passes the
    point where the line of action touches this gear's base circle. Below the base cone the flank
    is not generated (it continues along the meridian), so a gear whose mate would reach there is
    refused rather than built without the undercut its generation would cut; a gear the generating
    crown gear would undercut slightly but whose mate clears the base cone is built."""
    g = bevel_geometry(spec)
    tip = tooth_half_angle(spec, g.tip_cone_angle)
    if tip <= 0:
        raise GeometryError("pointed_tooth", f"{spec.name}: the flanks meet below the tip cone")
    if tooth_half_angle(spec, g.root_cone_angle) >= math.pi / spec.teeth * (1 - 1e-6):
        raise GeometryError("no_tooth_space", f"{spec.name}: neighbouring teeth touch at the root cone")
    a = spec.pressure_angle
    mate_addendum = (spec.addendum_coefficient - spec.profile_shift) * spec.module
    rv1 = g.cone_distance * math.tan(g.pitch_cone_angle) if g.pitch_cone_angle < math.pi / 2 - 1e-9 else math.inf
    if g.mate_pitch_cone_angle > math.radians(89.0):  # a crown-like mate: the rack's limit
        reach, room = mate_addendum, rv1 * math.sin(a) ** 2
    else:
        rv2 = g.cone_distance * math.tan(g.mate_pitch_cone_angle)
        reach = math.sqrt((rv2 + mate_addendum) ** 2 - (rv2 * math.cos(a)) ** 2) - rv2 * math.sin(a)
        room = rv1 * math.sin(a)
    if reach > room * (1 + 1e-12):
        raise GeometryError("interference", f"{spec.name}: the mate's tip reaches {reach:.4g} mm along the line of "
                            f"action of the back-cone equivalent pair, past this gear's base circle at {room:.4g} mm "
                            "(its flank below the base cone is not generated)")


@dataclass(frozen=True)
class ToothOutline:
    """Tooth 0's outline on the unit sphere about the apex (rad), the data a solid is built from.

    The tooth is centred on azimuth 0; its lower flank (negative azimuth) is the spherical
    involute of :func:`spherical_involute_points` turned by ``-involute_offset``, from the roll
    angle ``roll_start`` (on the root cone, or 0 on the base cone) to ``roll_tip`` (on the tip
    cone); the upper flank is its mirror image in the xz plane. Below the base cone (``meridian``:
    the root cone lies inside it) each flank continues along the meridian at azimuth
    -/+ ``root_half_angle`` down to the root cone."""

    root: float  # polar angle of the root cone, delta_f
    flank_start: float  # polar angle where the involute starts: max(delta_f, delta_b)
    tip: float  # polar angle of the tip cone, delta_a
    base_cone: float
    root_half_angle: float  # half the tooth's azimuth at flank_start (and along the meridian below it)
    tip_half_angle: float
    involute_offset: float  # phi_0 = s / d + inv_s(delta): the half angle the involute turns back from
    roll_start: float
    roll_tip: float

    @property
    def meridian(self) -> bool:
        return self.flank_start > self.root


def involute_roll(polar, base_cone: float):
    """The rolling angle t (about the axis) at which the spherical involute of ``base_cone`` reaches
    ``polar``: t = psi / sin delta_b (:func:`spherical_involute_roll`)."""
    return spherical_involute_roll(polar, base_cone) / math.sin(base_cone)


def tooth_outline(spec: BevelGearSpec) -> ToothOutline:
    g = bevel_geometry(spec)
    start = max(g.root_cone_angle, g.base_cone_angle)
    return ToothOutline(
        root=g.root_cone_angle, flank_start=start, tip=g.tip_cone_angle, base_cone=g.base_cone_angle,
        root_half_angle=tooth_half_angle(spec, start), tip_half_angle=tooth_half_angle(spec, g.tip_cone_angle),
        involute_offset=tooth_half_angle(spec, g.base_cone_angle),
        roll_start=float(involute_roll(start, g.base_cone_angle)),
        roll_tip=float(involute_roll(g.tip_cone_angle, g.base_cone_angle)))


def lower_flank_points(outline: ToothOutline, roll) -> tuple[np.ndarray, np.ndarray]:
    """Unit vectors ``(n, 3)`` of tooth 0's lower flank at the rolling angles ``roll``, and their
    derivatives d/dt. From the involute's definition: dP/dt = sin psi cos delta_b (cos delta_b cos t,
    cos delta_b sin t, -sin delta_b) (zero on the base cone, where the involute starts), turned
    with the point by -phi_0 about the axis."""
    t = np.atleast_1d(np.asarray(roll, dtype=float))
    sb, cb = math.sin(outline.base_cone), math.cos(outline.base_cone)
    p = spherical_involute_points(t, outline.base_cone)
    speed = np.sin(t * sb) * cb
    d = speed[:, None] * np.stack([cb * np.cos(t), cb * np.sin(t), np.full_like(t, -sb)], axis=-1)
    c, s = math.cos(outline.involute_offset), math.sin(outline.involute_offset)
    turn = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])  # rotation by -phi_0
    return p @ turn.T, d @ turn.T


def back_plane_distance(spec: BevelGearSpec) -> float:
    """Distance from the apex, along the axis, of the plane through the heel's root circle (a flat
    back): every tooth lies nearer the apex than it, only the spherical cap inside the root cone
    reaches beyond."""
    return spec.cone_distance * math.cos(bevel_geometry(spec).root_cone_angle)


@dataclass(frozen=True)
class ChordalTooth:
    """The tooth as a gear-tooth vernier measures it on the sphere of radius ``cone_distance`` about
    the apex (mm): ``thickness`` the chord between the two flanks' points on the pitch cone,
    ``height`` the distance from the crown (the tip cone on that sphere, on the tooth's centre) to
    that chord's midpoint."""

    cone_distance: float
    thickness: float
    height: float


def chordal_tooth(spec: BevelGearSpec, cone_distance: float) -> ChordalTooth:
    """Chordal tooth thickness and height of the built tooth on the sphere ``cone_distance``: the
    flanks cross the pitch cone delta at azimuth +/- phi (:func:`tooth_half_angle`), so the chord is
    2 R sin delta sin phi; its midpoint R (sin delta cos phi, cos delta), the crown R (sin delta_a,
    cos delta_a) in the tooth's meridian plane. (The back-cone rule of thumb, s - s^3 / (6 d^2) and
    h_a + s^2 cos delta / (4 d), is this to leading order.)"""
    g = bevel_geometry(spec)
    d, da = g.pitch_cone_angle, g.tip_cone_angle
    phi = tooth_half_angle(spec, d)
    r = cone_distance
    mid = np.array([r * math.sin(d) * math.cos(phi), r * math.cos(d)])
    crown = np.array([r * math.sin(da), r * math.cos(da)])
    return ChordalTooth(r, 2 * r * math.sin(d) * math.sin(phi), float(np.linalg.norm(crown - mid)))


#: the backs a bevel gear solid is built with
BACKS = ("spherical", "flat")


@dataclass(frozen=True)
class BevelCore:
    """The axisymmetric part of a bevel gear solid inside its root cone (mm, rad; z along the axis
    from the apex, rho from the axis), for the back ``back``:

    - ``"spherical"``: between the toe and heel spheres, less the bore;
    - ``"flat"``: the same cut by the plane z = ``back_z`` through the heel root circle
      (:func:`back_plane_distance`). When the toe sphere lies beyond that plane (R_i >= back_z, a
      gear of large cone angle) nothing would join the toothed ring to the axis: a web (``web``)
      does, a disc rho <= ``web_rim`` from z = ``web_z`` = (R_i + R_e)/2 cos delta_f to the back
      plane, its rim half way between the toe sphere and the root cone at that height, so it stays
      inside the root cone and runs into the ring.

    ``toe_inner``: polar angle of the toe face's inner circle (0: the face reaches the axis),
    ``toe_inner_face`` the face beyond it (``"bore"``, ``"web"``, or None); ``heel_inner`` the same
    on the heel sphere (spherical back); ``bore_z`` the bore's (z_low, z_high), None without a bore."""

    back: str
    back_z: float | None
    web: bool
    web_z: float | None
    web_rim: float | None
    toe_inner: float
    toe_inner_face: str | None
    heel_inner: float | None
    bore_z: tuple[float, float] | None


def bevel_core(spec: BevelGearSpec, back: str = "spherical") -> BevelCore:
    """The core of ``spec``'s solid with ``back`` (one of :data:`BACKS`, else a DesignError naming it)."""
    if back not in BACKS:
        raise DesignError("back", f"{back!r} is not a bevel gear back", ", ".join(map(repr, BACKS)))
    ri, re = spec.toe_cone_distance, spec.cone_distance
    rb = spec.bore_diameter / 2
    root = bevel_geometry(spec).root_cone_angle
    toe_bore = math.asin(rb / ri)
    bore_low = math.sqrt(ri * ri - rb * rb)
    if back == "spherical":
        return BevelCore(back, None, False, None, None, toe_bore, "bore" if rb > 0 else None,
                         math.asin(rb / re), (bore_low, math.sqrt(re * re - rb * rb)) if rb > 0 else None)
    plane = back_plane_distance(spec)
    if ri < plane:
        return BevelCore(back, plane, False, None, None, toe_bore, "bore" if rb > 0 else None, None,
                         (bore_low, plane) if rb > 0 else None)
    web_z = (ri + re) / 2 * math.cos(root)
    rim = (math.sqrt(ri * ri - web_z * web_z) + web_z * math.tan(root)) / 2
    web_meets_toe = math.sqrt(ri * ri - web_z * web_z)  # the web's face at web_z ends on the toe sphere
    if rb >= web_meets_toe:  # the bore takes the web's face away: the bore runs to the toe sphere
        return BevelCore(back, plane, True, web_z, rim, toe_bore, "bore", None, (bore_low, plane))
    return BevelCore(back, plane, True, web_z, rim, math.acos(web_z / ri), "web", None,
                     (web_z, plane) if rb > 0 else None)


def _revolved(pieces) -> float:
    """Volume of the region of the (rho, z) half plane bounded counter-clockwise by ``pieces``,
    turned about the z axis: pi times the loop integral of rho^2 dz (Green). A piece is
    ``("line", (rho0, z0), (rho1, z1))``, on which the integral is (z1 - z0)(rho0^2 + rho0 rho1 +
    rho1^2) / 3, or ``("arc", R, theta0, theta1)`` about the origin (rho = R sin theta, z = R cos
    theta), where it is -R^3 [cos^3 theta / 3 - cos theta] from theta0 to theta1."""
    total = 0.0
    for piece in pieces:
        if piece[0] == "line":
            (r0, z0), (r1, z1) = piece[1], piece[2]
            total += (z1 - z0) * (r0 * r0 + r0 * r1 + r1 * r1) / 3
        else:
            _, radius, t0, t1 = piece

            def f(t):
                return math.cos(t) ** 3 / 3 - math.cos(t)
            total -= radius ** 3 * (f(t1) - f(t0))
    return math.pi * total


def _revolved_moment(pieces) -> float:
    """The integral of rho^2 dV (mm^5) over the region of :func:`_revolved` turned about the z axis:
    2 pi times the area integral of rho^3, which is pi / 2 times the loop integral of rho^4 dz
    (Green). On a line rho^4 integrates to (z1 - z0)(rho1^5 - rho0^5) / (5 (rho1 - rho0)); on an arc
    rho = R sin theta, z = R cos theta, to -R^5 times the integral of sin^5."""
    total = 0.0
    for piece in pieces:
        if piece[0] == "line":
            (r0, z0), (r1, z1) = piece[1], piece[2]
            if abs(r1 - r0) < 1e-15:
                total += (z1 - z0) * r0 ** 4
            else:
                total += (z1 - z0) * (r1 ** 5 - r0 ** 5) / (5 * (r1 - r0))
        else:
            _, radius, t0, t1 = piece

            def f(t):  # an antiderivative of sin^5
                c = math.cos(t)
                return -c + 2 * c ** 3 / 3 - c ** 5 / 5
            total -= radius ** 5 * (f(t1) - f(t0))
    return math.pi / 2 * total


def _core_pieces(spec: BevelGearSpec, back: str) -> list:
    """The meridian outline of the core of :func:`bevel_core` (counter-clockwise pieces)."""
    ri, re = spec.toe_cone_distance, spec.cone_distance
    rb = spec.bore_diameter / 2
    root = bevel_geometry(spec).root_cone_angle
    core = bevel_core(spec, back)
    toe_root, heel_root = (ri * math.sin(root), ri * math.cos(root)), (re * math.sin(root), re * math.cos(root))
    pieces = [("line", toe_root, heel_root)]
    if core.back == "spherical":
        pieces.append(("arc", re, root, core.heel_inner))
        if rb > 0:
            pieces.append(("line", (rb, core.bore_z[1]), (rb, core.bore_z[0])))
    else:
        pieces.append(("line", heel_root, (rb, core.back_z)))
        if rb > 0:
            pieces.append(("line", (rb, core.back_z), (rb, core.bore_z[0])))
        if core.toe_inner_face == "web":
            pieces.append(("line", (rb, core.web_z), (ri * math.sin(core.toe_inner), core.web_z)))
    pieces.append(("arc", ri, core.toe_inner, root))
    return pieces


def bevel_axial_moment(spec: BevelGearSpec, back: str = "spherical", points: int = 4001) -> float:
    """The integral of r^2 dV (mm^5) about the axis of the bevel gear solid with ``back``: the teeth,
    z (R_e^5 - R_i^5) / 5 times the integral of 2 phi(theta) sin^3 theta from delta_f to delta_a
    (r = R sin theta, dV = R^2 sin theta dR dtheta dphi), plus the core's (:func:`_revolved_moment`)."""
    from scipy.integrate import simpson
    g = bevel_geometry(spec)
    lo, hi = g.root_cone_angle, g.tip_cone_angle
    cuts = [lo] + ([g.base_cone_angle] if lo < g.base_cone_angle < hi else []) + [hi]
    angular = 0.0
    for a, b in zip(cuts[:-1], cuts[1:]):
        th = np.linspace(a, b, points)
        angular += simpson(2 * tooth_half_angle(spec, th) * np.sin(th) ** 3, x=th)
    ri, re = spec.toe_cone_distance, spec.cone_distance
    return spec.teeth * angular * (re ** 5 - ri ** 5) / 5 + _revolved_moment(_core_pieces(spec, back))


def bevel_volume(spec: BevelGearSpec, back: str = "spherical") -> float:
    """Volume (mm^3) of the bevel gear solid with the back ``back`` (:func:`bevel_core`), independent
    of the CAD kernel: the teeth, z times the tooth's solid angle (:func:`tooth_solid_angle`) times
    (R_e^3 - R_i^3) / 3 (every tooth lies between the spheres and nearer the apex than the flat back),
    plus the core inside the root cone, the revolution of its meridian outline (:func:`_revolved`):
    root cone, back (heel sphere or plane), bore, web, toe sphere."""
    ri, re = spec.toe_cone_distance, spec.cone_distance
    return spec.teeth * tooth_solid_angle(spec) * (re ** 3 - ri ** 3) / 3 + _revolved(_core_pieces(spec, back))


def virtual_contact_ratio(spec: BevelGearSpec, mate_addendum: float | None = None) -> float:
    """Transverse contact ratio of the back-cone (Tredgold) equivalent spur pair at the heel:
    (sqrt(R_va1^2 - R_vb1^2) + sqrt(R_va2^2 - R_vb2^2) - (R_v1 + R_v2) sin alpha) / (pi m cos alpha),
    R_v = R_e tan delta, R_va = R_v + h_a, R_vb = R_v cos alpha. The mate's addendum defaults to
    the same proportions with shift -x (the mate of a Gleason-style pair)."""
    a = spec.pressure_angle
    m = spec.module
    re = spec.cone_distance
    ha2 = (spec.addendum_coefficient - spec.profile_shift) * m if mate_addendum is None else mate_addendum
    rv1, rv2 = re * math.tan(spec.pitch_cone_angle), re * math.tan(spec.mate_pitch_cone_angle)
    path = length_of_action((rv1 + spec.addendum, rv2 + ha2), (rv1 * math.cos(a), rv2 * math.cos(a)), rv1 + rv2)
    return path / (math.pi * m * math.cos(a))


def spherical_contact_ratio(spec: BevelGearSpec, mate_addendum: float | None = None) -> float:
    """Contact ratio of the spherical-involute pair itself (no back-cone approximation): the arc of the
    great circle of action (through the pitch-cone generator, at the pressure angle to the pitch
    circles' tangent; it touches both base cones) between the two tip cones, over the base pitch
    along it, 2 pi sin(delta_b1) / z1 (the circle rolls on base cone 1 without slipping)."""
    from scipy.optimize import brentq
    d1, d2 = spec.pitch_cone_angle, spec.mate_pitch_cone_angle
    a, re, m = spec.pressure_angle, spec.cone_distance, spec.module
    ha2 = (spec.addendum_coefficient - spec.profile_shift) * m if mate_addendum is None else mate_addendum
    tip1 = d1 + spec.addendum_angle
    tip2 = d2 + math.atan(ha2 / re)
    c = np.array([math.sin(d1), 0.0, math.cos(d1)])
    along = math.cos(a) * np.array([0.0, 1.0, 0.0]) + math.sin(a) * np.array([math.cos(d1), 0.0, -math.sin(d1)])
    axis2 = np.array([math.sin(spec.shaft_angle), 0.0, math.cos(spec.shaft_angle)])

    def point(t):
        return math.cos(t) * c + math.sin(t) * along

    def beyond_tip1(t):
        return math.acos(min(1.0, point(t)[2])) - tip1

    def beyond_tip2(t):
        return math.acos(min(1.0, float(point(t) @ axis2))) - tip2

    # along +t the point leaves gear 1's axis (p_z falls): its tip ends the path there, gear 2's on -t
    ends = [brentq(beyond_tip1, 0.0, math.pi / 2, xtol=1e-15), brentq(beyond_tip2, -math.pi / 2, 0.0, xtol=1e-15)]
    path = abs(ends[0] - ends[1])
    return path / (2 * math.pi * math.sin(base_cone_angle(d1, a)) / spec.teeth)


def flat_back_envelope(spec: BevelGearSpec, points: int = 48) -> list[np.ndarray]:
    """Closed (rho, z) profiles (mm; z along the axis from the apex) whose revolutions hold the
    flat-backed bevel gear solid (:func:`bevel_core` with ``back = "flat"``): between the toe and heel
    spheres, inside the tip cone, outside the bore, nearer the apex than the back plane; and its web
    when it has one. An envelope: the teeth reach the tip cone only at their tips."""
    g = bevel_geometry(spec)
    core = bevel_core(spec, "flat")
    ri, re, da = g.toe_cone_distance, g.cone_distance, g.tip_cone_angle
    back, rb = core.back_z, spec.bore_diameter / 2
    outline = [(ri * math.sin(da), ri * math.cos(da))]
    heel = np.linspace(da, math.acos(min(back / re, 1.0)), points)
    outline += [(re * math.sin(p), re * math.cos(p)) for p in heel]  # heel sphere, tip cone to the back
    if not core.web:
        outline += [(rb, back), (rb, math.sqrt(max(ri * ri - rb * rb, 0.0)))]
        toe = np.linspace(math.asin(min(rb / ri, 1.0)), da, points)
    else:  # the toe sphere lies beyond the back: the ring ends on the back plane
        inner = math.sqrt(ri * ri - back * back)
        outline += [(inner, back)]
        toe = np.linspace(math.asin(inner / ri), da, points)
    outline += [(ri * math.sin(p), ri * math.cos(p)) for p in toe[:-1]]  # toe sphere back to the start
    profiles = [np.array(outline)]
    if core.web:
        profiles.append(np.array([(rb, core.web_z), (core.web_rim, core.web_z), (core.web_rim, back), (rb, back)]))
    return profiles


@dataclass(frozen=True)
class BevelPairGeometry:
    """Pitch cones of a bevel pair with intersecting axes (mm, rad).

    ``pitch_angle_*`` is each gear's pitch-cone half angle (they add up to the shaft angle),
    ``pitch_radius_*`` the pitch radius at the heel (outer end of the face), ``cone_distance``
    the slant length from the common apex to the heel. A gear's frustum runs from its heel
    (radius ``pitch_radius``) a ``face_width`` along the cone towards the apex.
    """

    pinion_teeth: int
    gear_teeth: int
    module: float
    face_width: float
    shaft_angle: float
    pitch_angle_pinion: float
    pitch_angle_gear: float
    pitch_radius_pinion: float
    pitch_radius_gear: float
    cone_distance: float

    @property
    def ratio(self) -> float:
        return self.gear_teeth / self.pinion_teeth

    def apex_height(self, which: str) -> float:
        """Distance along the axis from a gear's heel plane to the common apex (mm)."""
        r, g = self._cone(which)
        return r / math.tan(g)

    def axial_height(self, which: str) -> float:
        """Axial length of a gear's frustum (mm): face width times cos(pitch angle)."""
        return self.face_width * math.cos(self._cone(which)[1])

    def toe_radius(self, which: str) -> float:
        r, g = self._cone(which)
        return r - self.face_width * math.sin(g)

    def _cone(self, which: str) -> tuple[float, float]:
        if which == "pinion":
            return self.pitch_radius_pinion, self.pitch_angle_pinion
        if which == "gear":
            return self.pitch_radius_gear, self.pitch_angle_gear
        raise ValueError("which must be 'pinion' or 'gear'")


def bevel_pair_geometry(pinion_teeth: int, gear_teeth: int, module: float, face_width: float,
                        shaft_angle: float = math.pi / 2) -> BevelPairGeometry:
    """Pitch cones of a bevel pair: ``tan(gamma_p) = sin(S) / (z_g/z_p + cos(S))``, gamma_g = S - gamma_p,
    heel pitch radii ``z m / 2``, cone distance ``r_p / sin(gamma_p)``."""
    for name, v in (("module", module), ("face_width", face_width), ("shaft_angle", shaft_angle)):
        if not (math.isfinite(v) and v > 0):
            raise DesignError(name, f"{v!r} is out of range", "> 0")
    if pinion_teeth < 4 or gear_teeth < 4:
        raise DesignError("teeth", f"{pinion_teeth}, {gear_teeth} are too few", ">= 4 each")
    gp, gg = pitch_cone_angles(pinion_teeth, gear_teeth, shaft_angle)
    rp, rg = pinion_teeth * module / 2, gear_teeth * module / 2
    cone = rp / math.sin(gp)
    if not face_width < cone:
        raise DesignError("face_width", f"{face_width:.6g} mm exceeds the cone distance", f"< {cone:.6g} mm")
    return BevelPairGeometry(pinion_teeth, gear_teeth, module, face_width, shaft_angle, gp, gg, rp, rg, cone)


__all__ = ["ChordalTooth", "chordal_tooth", "bevel_axial_moment", "flat_back_envelope", "BevelPairGeometry", "bevel_pair_geometry", "spherical_contact_ratio", "pitch_cone_angles", "base_cone_angle", "spherical_involute_roll", "spherical_involute_function",
           "spherical_involute_points", "gleason_profile_shift", "BevelGeometry", "bevel_geometry",
           "tooth_half_angle", "tooth_solid_angle", "gear_solid_angle", "check_tooth", "virtual_contact_ratio",
           "ToothOutline", "involute_roll", "tooth_outline", "lower_flank_points", "back_plane_distance", "BACKS",
           "BevelCore", "bevel_core", "bevel_volume"]
