"""Exact geometry of a ZA worm and of the wheel it generates (numpy only; mm and rad).

Dimensions follow DIN 3975-1 / ISO/TR 10828 in the axial system (the relations of the KHK Gear
Technical Reference, section 4.5, axial module system, Table 4.17):
lead angle tan(gamma) = z1 m_x / d1 = z1 / q, lead p_z = pi m_x z1, d2 = z2 m_x,
a = (d1 + d2)/2 + x2 m_x, worm tip d_a1 = d1 + 2 h_a, throat (wheel tip at the mid plane)
d_a2 = d2 + 2 (h_a* + x2) m_x, throat radius r_i = a - d_a2/2 = d1/2 - h_a.

Frames. Fixed frame: the wheel axis is Z; the worm axis is the line (t, a, 0), along +X. The worm
rotates by phi1 about +X; the wheel by phi2 = k phi1 about +Z, with k = p / r2 (p = p_z / 2 pi,
signed by the hand, r2 = d2 / 2): the thread's axial advance equals the wheel's pitch-circle arc.

ZA flank (Archimedean helicoid) in the fixed frame at worm angle phi1, side s = +1 (the +X flank
of the thread centred at X = 0 facing the wheel at phi1 = 0) or -1::

    X = p (theta - pi - phi1) + s (t_x/2 - (r - r1) tan alpha_x),  Y = a + r cos theta,  Z = r sin theta

with t_x the axial thread thickness at the reference cylinder r1 = d1/2. The helicoid is invariant
under the worm's screw motion, so its normal at fixed (r, theta) does not depend on phi1 and the
equation of meshing n . (v_worm - v_wheel) = 0 is linear in X: at (r, theta) the contact is at
``X = r (Y - r2) / n_y`` (derived in :func:`contact_point`). The wheel flank in its transverse plane
Z = z is therefore computed point by point in closed form (no iteration): theta = pi - asin(z / r)
on the side facing the wheel, X from the meshing equation, and the point turned into the wheel frame
by -phi2 of that instant. The wheel root and the flank's lower end come from the hob's tip edge
(the worm's thread extended by the tip clearance), whose trajectory in the wheel frame is the
trochoid joining the flank to the root circle.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass

import numpy as np

from geargen.families.worm.spec import WormGearSet
from geargen.errors import DesignError, GeometryError


@dataclass(frozen=True)
class WormGeometry:
    """The derived dimensions of a worm-gear set (mm, rad); see the module docstring for the
    relations. ``hob_tip_radius`` is the radius of the hob that cuts the wheel: the worm tip plus
    the tip clearance, the minor radius of the wheel's toroidal root."""

    lead_angle: float
    lead: float
    axial_pitch: float
    axial_pressure_angle: float
    normal_pressure_angle: float
    normal_module: float
    worm_reference_diameter: float
    wheel_reference_diameter: float
    centre_distance: float
    worm_tip_diameter: float
    worm_root_diameter: float
    throat_diameter: float
    throat_radius: float
    wheel_root_diameter: float
    wheel_outside_diameter: float
    hob_tip_radius: float
    worm_axial_thickness: float
    hob_axial_thickness: float
    wheel_thinning: float
    ratio: float

    @property
    def screw_parameter(self) -> float:
        """Signed lead per radian (right hand positive)."""
        return self.lead / (2 * math.pi)


#: the least tip land a wheel tooth keeps at the face ends, in axial modules: where the
#: rim's outside cylinder would leave less, the default outside diameter is turned down to keep
#: it, and a given one is refused (a land of zero is a pointed tooth, a space meeting the next)
MIN_TIP_LAND = 0.1


@functools.lru_cache(maxsize=64)
def worm_geometry(s: WormGearSet) -> WormGeometry:
    """The set's dimensions (module docstring). The wheel's outside diameter: the given one, or
    d_a2 + m_x turned down where that leaves the teeth less than :data:`MIN_TIP_LAND` m_x of tip
    land at the face ends (:func:`outside_radius_limit`); DesignError ``wheel_outside_diameter``
    where a given one does, and GeometryError ``wheel_pointed`` where even the throat does."""
    m, z1, z2, d1 = s.axial_module, s.starts, s.wheel_teeth, s.worm_reference_diameter
    gamma = math.atan(z1 * m / d1)
    alpha_x = math.atan(math.tan(s.pressure_angle) / math.cos(gamma))
    d2 = z2 * m
    a = (d1 + d2) / 2 + s.wheel_profile_shift * m
    ha, hf = s.addendum_coefficient * m, s.dedendum_coefficient * m
    da2 = d2 + 2 * (s.addendum_coefficient + s.wheel_profile_shift) * m
    df2 = d2 - 2 * (s.dedendum_coefficient - s.wheel_profile_shift) * m
    worm_thinning = s.backlash if s.backlash_on == "worm" else 0.0
    g = WormGeometry(
        lead_angle=gamma, lead=math.pi * m * z1, axial_pitch=math.pi * m, axial_pressure_angle=alpha_x,
        normal_pressure_angle=s.pressure_angle, normal_module=m * math.cos(gamma),
        worm_reference_diameter=d1, wheel_reference_diameter=d2, centre_distance=a,
        worm_tip_diameter=d1 + 2 * ha, worm_root_diameter=d1 - 2 * hf, throat_diameter=da2,
        throat_radius=a - da2 / 2, wheel_root_diameter=df2, wheel_outside_diameter=da2 + m,
        hob_tip_radius=a - df2 / 2, worm_axial_thickness=math.pi * m / 2 - worm_thinning,
        hob_axial_thickness=math.pi * m / 2,
        wheel_thinning=s.backlash if s.backlash_on == "wheel" else 0.0, ratio=z2 / z1)
    try:
        limit = outside_radius_limit(s, g, MIN_TIP_LAND * m)
    except GeometryError as exc:
        if exc.kind != "worm_envelope":
            raise
        limit = g.wheel_outside_diameter / 2  # an envelope that folds back: wheel_section says so (wheel_undercut)
    if s.wheel_outside_diameter is None:
        g = dataclasses.replace(g, wheel_outside_diameter=min(da2 + m, 2 * limit))
    elif s.wheel_outside_diameter > 2 * limit + 1e-9:
        raise DesignError("wheel_outside_diameter", f"{s.wheel_outside_diameter:.6g} mm leaves the wheel teeth less than "
                          f"{MIN_TIP_LAND:g} m_x of tip land at the face ends (pointed teeth)",
                          f"[{da2:.6g}, {2 * limit:.6g}] mm")
    else:
        g = dataclasses.replace(g, wheel_outside_diameter=s.wheel_outside_diameter)
    _check_flanks_reach_the_rim(s, g)
    return g


def _flank_inside_rim(s: WormGearSet, g: WormGeometry, z) -> np.ndarray:
    """Per plane z (nz,): how far inside the rim (mm) the envelope of the hob's flank reaches at the
    hob's tip radius, the less of the two sides; negative where the flank's whole envelope lies
    outside the rim, so that inside it only the hob's tip edge cuts the wheel. A side whose envelope
    folds back (its radius not falling from the rim's worm radius to the tip's, in 16 steps) is
    left to the undercut check (:func:`wheel_section`: ``wheel_undercut``)."""
    z = np.asarray(z, float)
    rim = rim_radius(g, z)
    start = np.maximum(np.hypot(g.centre_distance - rim, z), np.abs(z) * (1 + 1e-9) + 1e-12)
    radii = start[:, None] + (g.hob_tip_radius - start)[:, None] * np.linspace(0.0, 1.0, 17)[None, :]
    least = np.full(z.shape, np.inf)
    for side in (1, -1):
        xy = _envelope(s, g, z[:, None], side, radii)[0]
        reach = np.hypot(xy[..., 0], xy[..., 1])
        folds = np.any(np.diff(reach, axis=1) >= 0, axis=1)
        least = np.minimum(least, np.where(folds, np.inf, rim - reach[:, -1]))
    return least


def _check_flanks_reach_the_rim(s: WormGearSet, g: WormGeometry) -> None:
    """DesignError ``wheel_face_width`` where at a face end the worm's flanks cut no wheel flank inside
    the rim (the worm sweep's seed 1: m_x 2.48, z1 1, z2 33, q 17.8, alpha_n 24.6 deg, x2 0.22, face
    32.4 mm = 1.66 r_i; the +1 flank's envelope ends 0.13 mm outside the rim at z = 16.04 mm): the
    face beyond carries no contact, and the wheel's outline (flank from the rim down, geargen.cad.
    worm_wheel_solid) is not that wheel's. The allowed width: the widest whose ends keep it, by
    bisection to 1 um (the reach falls as |z| grows)."""
    half = s.wheel_face_width / 2
    ends = np.array([-half, half])
    if np.min(_flank_inside_rim(s, g, ends)) >= 0:
        return
    lo, hi = 0.0, half
    while hi - lo > 0.5e-3:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.min(_flank_inside_rim(s, g, np.array([-mid, mid]))) >= 0 else (lo, mid)
    raise DesignError("wheel_face_width", f"{s.wheel_face_width:.6g} mm reaches beyond the worm's flanks: at the face "
                      "ends only the hob's tip edge cuts the wheel inside its rim (no flank, no contact there)",
                      f"[{0.5 * s.axial_module:.6g}, {2 * lo:.6g}] mm")


def _signed_p(s: WormGearSet, g: WormGeometry) -> float:
    return s.hand_sign * g.screw_parameter


def flank_axial_offset(g: WormGeometry, side: int, r, thickness: float | None = None):
    """Axial position (X at theta = pi, phi1 = 0) of the thread flank ``side`` at radius ``r``:
    s (t_x/2 - (r - r1) tan alpha_x) -- the straight ZA axial profile."""
    t = g.worm_axial_thickness if thickness is None else thickness
    return side * (t / 2 - (np.asarray(r, float) - g.worm_reference_diameter / 2) * math.tan(g.axial_pressure_angle))


def worm_flank_point(s: WormGearSet, g: WormGeometry, side: int, r, theta, phi1=0.0):
    """Fixed-frame points (..., 3) of the worm flank ``side`` at radius r, angle theta, worm angle phi1."""
    p = _signed_p(s, g)
    r, theta = np.broadcast_arrays(np.asarray(r, float), np.asarray(theta, float))
    x = p * (theta - math.pi - phi1) + flank_axial_offset(g, side, r)
    return np.stack([x, g.centre_distance + r * np.cos(theta), r * np.sin(theta)], axis=-1)


def worm_flank_normal(s: WormGearSet, g: WormGeometry, side: int, r, theta):
    """Normals (..., 3) (not unit) of the flank: d/dr x d/dtheta = (r, p sin th - h' r cos th, -h' r sin th - p cos th)."""
    p = _signed_p(s, g)
    dh = -side * math.tan(g.axial_pressure_angle)
    r, theta = np.broadcast_arrays(np.asarray(r, float), np.asarray(theta, float))
    return np.stack([r, p * np.sin(theta) - dh * r * np.cos(theta), -dh * r * np.sin(theta) - p * np.cos(theta)], axis=-1)


def contact_point(s: WormGearSet, g: WormGeometry, side: int, r, theta):
    """Where and when the hob's flank point (r, theta) touches the wheel it cuts (the hob is the
    worm at its nominal thread thickness p_x/2: a worm thinned for backlash does not cut the wheel
    thinner): (fixed-frame point (..., 3),
    worm angle phi1). With v_worm = e_X x (P - O1) = (0, -r sin th, r cos th) and
    v_wheel = k e_Z x P = k (-Y, X, 0), n . v_worm = -p r for every theta, so the meshing equation
    -p r + k (n_x Y - n_y X) = 0 with k = p / r2 gives X = r (Y - r2) / n_y."""
    p = _signed_p(s, g)
    r2 = g.wheel_reference_diameter / 2
    n = worm_flank_normal(s, g, side, r, theta)
    r, theta = np.broadcast_arrays(np.asarray(r, float), np.asarray(theta, float))
    y = g.centre_distance + r * np.cos(theta)
    if np.any(np.abs(n[..., 1]) < 1e-12 * r):
        raise GeometryError("worm_envelope", "the meshing equation is singular (n_y = 0) on the worm flank")
    x = r * (y - r2) / n[..., 1]
    phi1 = (p * (theta - math.pi) + flank_axial_offset(g, side, r, g.hob_axial_thickness) - x) / p
    return np.stack([x, y, r * np.sin(theta)], axis=-1), phi1


def wheel_angle(s: WormGearSet, g: WormGeometry, phi1):
    """Wheel rotation phi2 = k phi1 with k = p / r2 (signed by the hand)."""
    return _signed_p(s, g) / (g.wheel_reference_diameter / 2) * np.asarray(phi1, float)


def to_wheel(points, phi2):
    """Fixed-frame points (..., 3) at wheel angle phi2 -> wheel-frame points (rotate by -phi2 about Z)."""
    c, sn = np.cos(phi2), np.sin(phi2)
    x, y = points[..., 0], points[..., 1]
    return np.stack([c * x + sn * y, -sn * x + c * y, points[..., 2]], axis=-1)


@dataclass(frozen=True)
class WheelSection:
    """The tooth space of the wheel centred on +Y in its transverse plane ``z`` (wheel frame, mm).

    ``flank[side]`` (n, 2): the envelope, from outside the rim (index 0) to the flank's lower end;
    ``trochoid[side]`` (m, 2): the hob tip edge's path from that end to the root circle (tangent);
    ``root_radius``: the root circle in this plane. Side +1 is the +X side of the space."""

    z: float
    flank: dict
    trochoid: dict
    root_radius: float
    worm_radii: np.ndarray  # the worm radii of the flank points


def wheel_section(s: WormGearSet, g: WormGeometry | None = None, z: float = 0.0, outer_radius: float | None = None,
                  n_flank: int = 60, n_trochoid: int = 25) -> WheelSection:
    """The wheel's tooth space in plane ``z``, generated by the hob (the worm with its flank carried
    on to the hob tip radius). ``outer_radius``: the flank starts outside this wheel radius (default
    the rim's outside radius plus 0.3 m_x). The wheel's thinning turns each flank away from the
    space's centre by thinning / d2 (a rigid turn of an envelope is the envelope of the turned worm).
    Raises GeometryError ``worm_envelope`` (singular meshing) or ``wheel_undercut`` (the envelope
    folds back: the hob's tip edge would cut the flank)."""
    g = g or worm_geometry(s)
    a, m = g.centre_distance, s.axial_module
    rho = g.hob_tip_radius
    if abs(z) >= 0.98 * rho:
        raise GeometryError("worm_envelope", f"plane z = {z:.4g} mm is outside the hob's reach (|z| < {rho:.4g} mm)")
    r_out = (outer_radius if outer_radius is not None else g.wheel_outside_diameter / 2 + 0.3 * m)
    # the worm radius whose point at X = 0 lies at the wheel radius r_out in this plane
    r_lo = math.hypot(max(a - r_out, 0.0), z)
    r_lo = max(r_lo, abs(z) * 1.0005 + 1e-9)
    flank, troch = {}, {}
    radii = r_lo + (rho - r_lo) * (1 - np.cos(np.linspace(0, math.pi / 2, n_flank)))  # denser at the tip edge
    for side in (1, -1):
        theta = math.pi - np.arcsin(z / radii)
        pts, phi1 = contact_point(s, g, side, radii, theta)
        w = to_wheel(pts, wheel_angle(s, g, phi1))[:, :2]
        if pts[0, 1] < r_out:  # the first point must be outside the rim for the cutter to clear it
            w_r = np.hypot(w[0, 0], w[0, 1])
            if w_r < r_out - 1e-9:
                raise GeometryError("worm_envelope", f"the flank in plane z = {z:.4g} does not reach the rim")
        # the hob tip edge (r = rho) from its contact instant to the line of centres (X = 0)
        th_e = theta[-1]
        p = _signed_p(s, g)
        x_c = pts[-1, 0]
        phi_c = phi1[-1]
        phi_b = phi_c + x_c / p  # X(phi1) = x_c - p (phi1 - phi_c) reaches 0
        phis = np.linspace(phi_c, phi_b, n_trochoid)
        edge = np.stack([x_c - p * (phis - phi_c), np.full_like(phis, a + rho * math.cos(th_e)),
                         np.full_like(phis, z)], axis=-1)
        tr = to_wheel(edge, wheel_angle(s, g, phis))[:, :2]
        turn = side * g.wheel_thinning / g.wheel_reference_diameter  # +X side turned further +X: clockwise
        flank[side], troch[side] = _turn(w, -turn), _turn(tr, -turn)
        _check_no_fold(flank[side], troch[side], side, z)
    root = a - math.sqrt(rho * rho - z * z)
    return WheelSection(z, flank, troch, root, radii)


def rim_radius(g: WormGeometry, z):
    """The wheel's outer radius in plane(s) z: the throat torus (minor radius r_i about the worm
    axis at the centre distance), capped by the outside cylinder."""
    z = np.asarray(z, float)
    return np.minimum(g.wheel_outside_diameter / 2, g.centre_distance - np.sqrt(np.maximum(g.throat_radius ** 2 - z * z, 0.0)))


def crease_height(g: WormGeometry) -> float:
    """z_c: where the throat torus meets the outside cylinder (0 if the rim is all cylinder)."""
    return math.sqrt(max(g.throat_radius ** 2 - (g.centre_distance - g.wheel_outside_diameter / 2) ** 2, 0.0))


def z_ranges(s: WormGearSet, g: WormGeometry) -> list[tuple[float, float]]:
    """The face split at +-z_c (only the ranges inside the face; a sliver under 1e-6 m_x is dropped
    and its neighbour carried to the end, where the rim's kink is then below any tolerance; an
    outside diameter equal to the throat diameter makes the rim the cylinder alone)."""
    half, zc, tiny = s.wheel_face_width / 2, crease_height(g), 1e-6 * s.axial_module
    if zc < tiny:  # the outside cylinder is the throat's tangent at z = 0: no crease
        return [(-half, half)]
    cuts = [-half] + [c for c in (-zc, zc) if -half + tiny < c < half - tiny] + [half]
    return list(zip(cuts[:-1], cuts[1:]))


def _envelope(s: WormGearSet, g: WormGeometry, z, side: int, radii):
    """Wheel-frame points (..., 2) of the envelope flank ``side`` in planes ``z`` generated by the
    hob's flank at worm radii ``radii`` (broadcast with z), with the contacts' fixed-frame points
    and worm angles: theta = pi - asin(z / r) on the side facing the wheel, the wheel turned back
    by the contact's phi2, then by the thinning."""
    radii = np.asarray(radii, float)
    theta = math.pi - np.arcsin(np.asarray(z, float) / radii)
    pts, phi1 = contact_point(s, g, side, radii, theta)
    w = to_wheel(pts, wheel_angle(s, g, phi1))[..., :2]
    return _turn(w, -side * g.wheel_thinning / g.wheel_reference_diameter), pts, phi1


def _turn(xy, angle):
    c, sn = np.cos(angle), np.sin(angle)
    return np.stack([c * xy[..., 0] - sn * xy[..., 1], sn * xy[..., 0] + c * xy[..., 1]], axis=-1)


def rim_worm_radius(s: WormGearSet, g: WormGeometry, z, side: int, radius=None) -> np.ndarray:
    """The hob radius whose envelope point lies on the wheel radius ``radius`` (default the rim
    r(z)), per plane z (nz,): the flank's upper end. Bisection, vectorised over the planes, to
    1e-13 mm (the envelope's radius falls as the hob radius grows)."""
    z = np.asarray(z, float)
    target = rim_radius(g, z) if radius is None else np.broadcast_to(np.asarray(radius, float), z.shape)
    lo = np.maximum(np.hypot(g.centre_distance - target, z), np.abs(z) * (1 + 1e-9) + 1e-12)
    hi = np.full_like(z, g.hob_tip_radius)

    def excess(r):
        return np.hypot(*np.moveaxis(_envelope(s, g, z, side, r)[0], -1, 0)) - target

    # at the worm radius reaching the radius on the line of centres the contact (X != 0) is outside it
    f_lo, f_hi = excess(lo), excess(hi)
    if np.any(f_lo < 0) or np.any(f_hi > 0):
        bad = float(z[np.argmax((f_lo < 0) | (f_hi > 0))])
        raise GeometryError("worm_envelope", f"the wheel flank in plane z = {bad:.4g} mm does not span the rim")
    # regula falsi, Illinois: the end kept twice running has its value halved (superlinear; a
    # dozen steps where bisection took 45)
    kept = np.zeros(z.shape, int)  # +1: lo kept last step, -1: hi kept
    for _ in range(200):
        x = np.where(f_lo == f_hi, 0.5 * (lo + hi), hi - f_hi * (hi - lo) / np.where(f_lo == f_hi, 1.0, f_hi - f_lo))
        fx = excess(x)
        outside = fx > 0
        f_lo = np.where(outside, fx, np.where(kept == 1, 0.5 * f_lo, f_lo))
        f_hi = np.where(~outside, fx, np.where(kept == -1, 0.5 * f_hi, f_hi))
        lo, hi = np.where(outside, x, lo), np.where(outside, hi, x)
        kept = np.where(outside, -1, 1)
        if np.max(np.abs(fx)) < 1e-12 or np.max(hi - lo) < 1e-13:
            break
    return x


def tip_land(s: WormGearSet, g: WormGeometry, z, radius) -> np.ndarray:
    """The tooth's width (arc, mm) at wheel radius ``radius`` in planes ``z``: between this space's
    -1 flank and the next space's +1 flank (one pitch on); negative where the spaces overlap."""
    z = np.asarray(z, float)
    angle = {}
    for side in (1, -1):
        r = rim_worm_radius(s, g, z, side, radius)
        xy = _envelope(s, g, z, side, r)[0]
        angle[side] = np.arctan2(xy[..., 1], xy[..., 0])
    gap = (angle[1] + 2 * math.pi / s.wheel_teeth - angle[-1] + math.pi) % (2 * math.pi) - math.pi
    return np.asarray(radius, float) * gap


def outside_radius_limit(s: WormGearSet, g: WormGeometry, land: float) -> float:
    """The largest outside radius (of the rim's cylinder) that leaves the teeth ``land`` (mm) of
    tip land at both face ends, up to the default d_a2/2 + m_x/2: the teeth narrow outward, and
    the face ends are where the cylinder caps the rim (the throat torus lies lower in between).
    GeometryError ``wheel_pointed`` where not even the throat leaves it."""
    ends = np.array([-1.0, 1.0]) * s.wheel_face_width / 2
    throat, default = g.throat_diameter / 2, g.throat_diameter / 2 + s.axial_module / 2

    def least(radius):  # the rim at the ends is the torus where that lies lower than the cylinder
        rim = np.minimum(radius, g.centre_distance - np.sqrt(np.maximum(g.throat_radius ** 2 - ends ** 2, 0.0)))
        return float(np.min(tip_land(s, g, ends, rim)))

    if least(default) >= land:
        return default
    if least(throat) < land:
        raise GeometryError("wheel_pointed", f"the wheel teeth keep less than {land:.3g} mm of tip land at the face "
                            f"ends even at the throat (d_a2 = {2 * throat:.6g} mm): a smaller wheel_profile_shift or "
                            "face width keeps them from coming to a point")
    lo, hi = throat, default
    while hi - lo > 1e-9:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if least(mid) >= land else (lo, mid)
    return lo


def wheel_outline(s: WormGearSet, g: WormGeometry, z, u_flank, u_trochoid, u_arc) -> dict:
    """The wheel's outline in planes ``z`` (nz,) for the tooth space centred on +Y, exact, as point
    runs (nz, n, 2) at the same parameters in every plane (GeometryError ``wheel_undercut`` where a
    flank folds back or a trochoid cuts it, as :func:`wheel_section`): ``("flank", side)`` from the rim
    (u_flank 0) to the flank's lower end at the hob tip edge (1), the worm radius linear in
    u_flank; ``("trochoid", side)`` the hob tip edge's path from there (u_trochoid 0) to the root
    circle on the line of centres (1), the worm angle linear; ``"root"`` the root arc from the +1
    trochoid's end to the -1 one's, ``"tip"`` the rim arc from the -1 flank's top to the next
    space's +1 flank top (one pitch on), the polar angle linear in u_arc. Side +1 is the +X side."""
    z = np.asarray(z, float)
    rho, a = g.hob_tip_radius, g.centre_distance
    p = _signed_p(s, g)
    zc = z[:, None]
    u_flank, u_trochoid, u_arc = (np.asarray(u, float)[None, :] for u in (u_flank, u_trochoid, u_arc))
    out = {}
    for side in (1, -1):
        r_top = rim_worm_radius(s, g, z, side)[:, None]
        flank, pts, phi1 = _envelope(s, g, zc, side, r_top + (rho - r_top) * u_flank)
        # the hob tip edge from its contact instant until it crosses the line of centres (X = 0)
        x_c, phi_c = pts[:, -1:, 0], phi1[:, -1:]
        phis = phi_c + (x_c / p) * u_trochoid
        y_edge = a + rho * np.cos(math.pi - np.arcsin(zc / rho))
        edge = np.stack(np.broadcast_arrays(x_c - p * (phis - phi_c), y_edge, zc), axis=-1)
        trochoid = _turn(to_wheel(edge, wheel_angle(s, g, phis))[..., :2], -side * g.wheel_thinning / g.wheel_reference_diameter)
        if u_flank[0, 0] == 0.0:  # on the rim, to rounding
            flank[:, 0] *= (rim_radius(g, z) / np.hypot(flank[:, 0, 0], flank[:, 0, 1]))[:, None]
        if u_flank[0, -1] == 1.0 and u_trochoid[0, 0] == 0.0:
            trochoid[:, 0] = flank[:, -1]  # the same point (the contact at the edge), to rounding
        _check_no_fold(flank, trochoid, side, z)
        out["flank", side], out["trochoid", side] = flank, trochoid

    def arc(radius, start, end):
        a0, a1 = np.arctan2(start[:, 1], start[:, 0]), np.arctan2(end[:, 1], end[:, 0])
        angle = a0[:, None] + ((a1 - a0 + math.pi) % (2 * math.pi) - math.pi)[:, None] * u_arc
        run = radius[:, None, None] * np.stack([np.cos(angle), np.sin(angle)], axis=-1)
        if u_arc[0, 0] == 0.0 and u_arc[0, -1] == 1.0:  # its ends the joints' points, to rounding
            run[:, 0], run[:, -1] = start, end
        return run

    out["root"] = arc(a - np.sqrt(rho * rho - z * z), out["trochoid", 1][:, -1], out["trochoid", -1][:, -1])
    out["tip"] = arc(rim_radius(g, z), out["flank", -1][:, 0], _turn(out["flank", 1][:, 0], 2 * math.pi / s.wheel_teeth))
    return out


def _check_no_fold(flank, trochoid, side, z):
    """The flank's radius must fall monotonically from the rim to its lower end, and the trochoid
    must stay inside the space (on the space side of the flank's lower end), or it is undercut.
    ``flank``, ``trochoid`` (..., n, 2) in the planes ``z`` (...)."""
    rad = np.hypot(flank[..., 0], flank[..., 1])
    folds = np.any(np.diff(rad, axis=-1) >= 0, axis=-1)
    if np.any(folds):
        raise GeometryError("wheel_undercut", f"the wheel flank folds back in plane z = {float(np.ravel(z)[np.argmax(np.ravel(folds))]):.4g} mm")
    # polar angle measured from +Y toward +X (the space centre is 0, side +1 positive)
    ang = np.arctan2(trochoid[..., 0], trochoid[..., 1]) * side
    cuts = np.any(np.diff(ang, axis=-1) > 1e-12, axis=-1)
    if np.any(cuts):
        raise GeometryError("wheel_undercut", f"the hob tip edge cuts the flank in plane z = {float(np.ravel(z)[np.argmax(np.ravel(cuts))]):.4g} mm")


def space_width_at_radius(section: WheelSection, radius: float) -> float:
    """Arc width of the tooth space at ``radius`` in the section (angle between the two flanks x radius)."""
    angles = []
    for side in (1, -1):
        f = section.flank[side]
        rad = np.hypot(f[:, 0], f[:, 1])
        ang = np.arctan2(f[:, 0], f[:, 1])
        i = np.searchsorted(-rad, -radius)  # rad decreasing
        if i == 0 or i >= len(rad):
            raise GeometryError("worm_envelope", f"radius {radius:.4g} is outside the flank's span")
        t = (radius - rad[i - 1]) / (rad[i] - rad[i - 1])
        angles.append(ang[i - 1] + t * (ang[i] - ang[i - 1]))
    return (angles[0] - angles[1]) * radius


@dataclass(frozen=True)
class HelixSpline:
    """The unit circle (cos t, sin t), t from ``t0`` to at least ``t1``, as a B-spline of degree
    ``degree`` on uniform simple knots ``knots`` (unclamped: the curve runs from knots[degree] =
    t0 to knots[-degree - 1]), ``poles`` (n, 2) on a circle, pole j at the angle of knot j turned
    and scaled by one complex factor; ``greville`` (n,) the Greville abscissae (poles of t -> t:
    a helix's z poles are p greville + offset, exactly linear). ``max_error``: the largest distance
    from the unit circle at the same parameter (the radial ripple of period one span)."""

    degree: int
    knots: np.ndarray
    poles: np.ndarray
    greville: np.ndarray
    max_error: float


def _circle_ripple(spans_per_turn: int, degree: int, samples: int = 64):
    """The complex factor that centres a uniform periodic B-spline with poles e^(i t_j) (t_j its
    knots) on the unit circle, and the distance left (its curve is e^(it) times a factor of period
    one span; measured on ``samples`` points of a middle span)."""
    from scipy.interpolate import BSpline
    h = 2 * math.pi / spans_per_turn
    n = 3 * degree
    knots = np.arange(n + degree + 1) * h
    angles = knots[:n]
    curve = BSpline(knots, np.column_stack([np.cos(angles), np.sin(angles)]), degree)
    t = knots[n // 2] + h * np.arange(samples) / samples
    xy = curve(t)
    factor = (xy[:, 0] + 1j * xy[:, 1]) * np.exp(-1j * t)
    scale = 1 / np.mean(factor)
    return scale, float(np.max(np.abs(scale * factor - 1)))


def helix_spline(t0: float, t1: float, tolerance: float, degree: int = 7) -> HelixSpline:
    """The unit circle over [t0, t1] within ``tolerance`` (relative: a helix of radius r is within
    r tolerance): the fewest uniform spans a turn (from 8) whose periodic B-spline, its poles on a
    circle, stays within it. Every span is the same, so the cost and the error do not grow with
    the number of turns (a least-squares fit over 60 turns would)."""
    for spans in range(8, 257):
        scale, error = _circle_ripple(spans, degree)
        if error <= tolerance:
            break
    else:
        raise ValueError(f"no uniform B-spline of degree {degree} within {tolerance:g} of the circle")
    h = 2 * math.pi / spans
    n = int(math.ceil((t1 - t0) / h - 1e-12)) + degree
    knots = t0 + (np.arange(n + degree + 1) - degree) * h
    unit = scale * np.exp(1j * knots[:n])
    greville = np.array([knots[j + 1:j + degree + 1].mean() for j in range(n)])
    return HelixSpline(degree, knots, np.column_stack([unit.real, unit.imag]), greville, error)


__all__ = ["WormGeometry", "worm_geometry", "worm_flank_point", "worm_flank_normal", "contact_point",
           "wheel_angle", "to_wheel", "WheelSection", "wheel_section", "space_width_at_radius", "flank_axial_offset",
           "HelixSpline", "helix_spline",
           "rim_radius", "crease_height", "z_ranges", "rim_worm_radius", "wheel_outline", "tip_land", "outside_radius_limit",
           "MIN_TIP_LAND"]
