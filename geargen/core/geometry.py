"""Gear-pair and measurement geometry of external involute gears (numpy; mm and rad).

Everything here works on :class:`~geargen.design.gear.GearSpec` (normal system) and on plain
numbers; nothing builds a solid. Conventions used throughout:

* Lengths in mm, angles in rad. "Transverse" is the section normal to the gear axis, "normal"
  the section normal to the tooth (reference helix).
* Tooth thinning (``GearSpec.thinning``) is the transverse arc removed from the tooth thickness
  at the reference circle; every thickness, backlash and measurement below includes it. It is
  taken as cut by a correspondingly thicker generating-rack tooth at the standard infeed, so it
  changes no radius (root, form, tip).
* Backlash is positive for clearance and names its kind and where it is measured.
* Tip radii are ``GearSpec.tip_radius`` (no tip shortening) unless a function says otherwise.

scipy is imported lazily, only where a root must be found numerically (undercut boundary).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from geargen.core.involute import (backlash_change, involute, inverse_involute, length_of_action, pointed_tip_radius,
                                   reference_tooth_thickness, roll_length, working_pressure_angle_at,
                                   tooth_thickness_at_radius)
from geargen.design.gear import GearSpec
from geargen.errors import DesignError, GeometryError
from geargen.units import length_text

__all__ = [
    "GearPair", "MeshGeometry", "MeshBacklash", "Undercut", "TipLand", "SpanMeasurement", "PinMeasurement",
    "working_pressure_angle", "working_centre_distance", "shift_sum_for_centre_distance",
    "mesh_geometry", "tight_mesh_centre_distance", "backlash_at_centre_distance",
    "SpecificSliding", "specific_sliding", "ShiftSplit", "split_profile_shift", "SHIFT_SPLIT_RULE",
    "profile_shift_limits",
    "minimum_teeth_without_undercut", "rack_flank_addendum_coefficient", "undercut", "involute_start_radius",
    "tip_land", "check_tip_land",
    "span_length", "span_contact_radius", "recommended_teeth_spanned", "span_measurement",
    "pin_centre_radius", "over_pins_dimension", "ideal_pin_diameter", "over_pins_measurement",
    "ChordalTooth", "chordal_tooth",
]

_REL = 1e-9  # relative tolerance when two specs must agree (module, angles)


def _out(a):
    """A 0-d array as a Python float, anything else unchanged."""
    a = np.asarray(a, dtype=float)
    return float(a) if a.ndim == 0 else a


def _transverse_pressure_angle(normal_pressure_angle, helix_angle):
    return np.arctan(np.tan(normal_pressure_angle) / np.cos(helix_angle))


# ---------------------------------------------------------------------------------------------
# Gear pair: centre distance, working pressure angle, contact ratio
# ---------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class GearPair:
    """Two external gears in mesh (spur or helical), validated on construction.

    Both gears need the same normal module, normal pressure angle and helix angle; helical
    gears need opposite hands. A mismatch raises :class:`DesignError` naming gear 2's field
    (``gear2.module``, ``gear2.pressure_angle``, ``gear2.helix_angle``, ``gear2.hand``).
    """

    gear1: GearSpec
    gear2: GearSpec

    def __post_init__(self):
        for name in ("gear1", "gear2"):
            if not isinstance(getattr(self, name), GearSpec):
                raise DesignError(name, f"expected a GearSpec, got {type(getattr(self, name)).__name__}")
        g1, g2 = self.gear1, self.gear2
        if not math.isclose(g1.module, g2.module, rel_tol=_REL):
            raise DesignError("gear2.module", f"normal module {g2.module:.6g} mm differs from gear 1's "
                              f"{g1.module:.6g} mm; meshing gears need equal normal modules", f"{g1.module:.6g} mm")
        if not math.isclose(g1.pressure_angle, g2.pressure_angle, rel_tol=_REL):
            raise DesignError("gear2.pressure_angle",
                              f"normal pressure angle {math.degrees(g2.pressure_angle):.6g} deg "
                              f"differs from gear 1's", f"{math.degrees(g1.pressure_angle):.6g} deg")
        if not math.isclose(g1.helix_angle, g2.helix_angle, rel_tol=_REL, abs_tol=1e-15):
            raise DesignError("gear2.helix_angle", f"helix angle {math.degrees(g2.helix_angle):.6g} deg differs from "
                              f"gear 1's; parallel-axis gears need equal helix angles",
                              f"{math.degrees(g1.helix_angle):.6g} deg")
        if g1.is_helical and g1.hand == g2.hand:
            other = "left" if g1.hand == "right" else "right"
            raise DesignError("gear2.hand", f"both gears are {g1.hand}-handed; external helical gears mesh only "
                              "with opposite hands", repr(other))

    @property
    def teeth_sum(self) -> int:
        return self.gear1.teeth + self.gear2.teeth

    @property
    def shift_sum(self) -> float:
        """x_n1 + x_n2 (normal profile shift coefficients)."""
        return self.gear1.profile_shift + self.gear2.profile_shift

    @property
    def standard_centre_distance(self) -> float:
        """(z1 + z2) m_t / 2, mm: the centre distance of the unshifted pair."""
        return self.gear1.reference_radius + self.gear2.reference_radius


def working_pressure_angle(shift_sum, teeth_sum, normal_pressure_angle, helix_angle=0.0):
    """Transverse working pressure angle of a zero-backlash mesh of profile-shifted gears (rad).

    inv(alpha_wt) = 2 tan(alpha_n) (x1 + x2) / (z1 + z2) + inv(alpha_t).

    Parameters
    ----------
    shift_sum : float or array
        x_n1 + x_n2, normal profile shift coefficients.
    teeth_sum : int or array
        z1 + z2.
    normal_pressure_angle, helix_angle : float or array
        alpha_n and beta (rad); beta = 0 for spur gears.

    Returns
    -------
    float or array, broadcast shape of the inputs. Raises :class:`DesignError` (``profile_shift``)
    when the shift sum is so negative that no working pressure angle exists.
    """
    alpha_t = _transverse_pressure_angle(normal_pressure_angle, helix_angle)
    inv_wt = 2.0 * np.tan(normal_pressure_angle) * np.asarray(shift_sum, float) / np.asarray(teeth_sum, float) \
        + involute(alpha_t)
    if np.any(np.asarray(inv_wt) < 0):
        raise DesignError("profile_shift", "the profile shift sum is too negative: no working pressure angle",
                          "x1 + x2 > -(z1 + z2) inv(alpha_t) / (2 tan(alpha_n))")
    return inverse_involute(inv_wt)


def working_centre_distance(shift_sum, teeth_sum, normal_module, normal_pressure_angle, helix_angle=0.0):
    """Zero-backlash centre distance of profile-shifted gears without thinning (mm).

    a_w = a cos(alpha_t) / cos(alpha_wt), a = (z1 + z2) m_n / (2 cos beta); alpha_wt from
    :func:`working_pressure_angle`. Array in, array out (broadcast shape).
    """
    alpha_t = _transverse_pressure_angle(normal_pressure_angle, helix_angle)
    a = np.asarray(teeth_sum, float) * normal_module / (2.0 * np.cos(helix_angle))
    alpha_wt = working_pressure_angle(shift_sum, teeth_sum, normal_pressure_angle, helix_angle)
    return _out(a * np.cos(alpha_t) / np.cos(alpha_wt))


def shift_sum_for_centre_distance(centre_distance, teeth_sum, normal_module, normal_pressure_angle,
                                  helix_angle=0.0):
    """The profile shift sum x_n1 + x_n2 that makes a zero-backlash mesh at ``centre_distance``.

    The inverse of :func:`working_centre_distance`: cos(alpha_wt) = a cos(alpha_t) / a_w, then
    x1 + x2 = (z1 + z2) (inv(alpha_wt) - inv(alpha_t)) / (2 tan(alpha_n)).

    Parameters
    ----------
    centre_distance : float or array
        a_w, mm; must exceed the sum of the base radii a cos(alpha_t).
    teeth_sum, normal_module, normal_pressure_angle, helix_angle
        z1 + z2, m_n (mm), alpha_n and beta (rad).

    Returns
    -------
    float or array (broadcast shape). Raises :class:`DesignError` (``centre_distance``) when the
    centre distance is not beyond the base circles.
    """
    alpha_t = _transverse_pressure_angle(normal_pressure_angle, helix_angle)
    a = np.asarray(teeth_sum, float) * normal_module / (2.0 * np.cos(helix_angle))
    aw = np.asarray(centre_distance, float)
    base_sum = a * np.cos(alpha_t)
    if np.any(~np.isfinite(aw)) or np.any(aw <= base_sum):
        raise DesignError("centre_distance", "must be larger than the sum of the base radii",
                          f"> {np.min(base_sum):.6g} mm")
    alpha_wt = working_pressure_angle_at(base_sum, aw)
    return _out(np.asarray(teeth_sum, float) * (involute(alpha_wt) - involute(alpha_t))
                / (2.0 * np.tan(normal_pressure_angle)))


@dataclass(frozen=True)
class MeshGeometry:
    """Geometry of a gear pair at one operating centre distance (mm, rad); see :func:`mesh_geometry`.

    Pairs ``(gear 1, gear 2)`` are tuples. Contact ratios are dimensionless.
    """

    centre_distance: float  # operating centre distance a'
    standard_centre_distance: float  # (z1 + z2) m_t / 2
    working_centre_distance: float  # zero-backlash distance from the profile shifts (no thinning)
    transverse_pressure_angle: float  # alpha_t of the generating rack
    working_pressure_angle: float  # transverse, at the operating centre distance
    working_pitch_radii: tuple[float, float]
    base_radii: tuple[float, float]
    tip_radii: tuple[float, float]  # as used for the contact ratio
    transverse_base_pitch: float
    length_of_action: float  # transverse path of contact g_alpha
    transverse_contact_ratio: float
    face_width: float  # common face width used for the face contact ratio
    face_contact_ratio: float
    total_contact_ratio: float
    active_profile_start_radii: tuple[float, float]  # lowest radius on each gear reached by the mate's tip
    involute_start_radii: tuple[float, float]  # where each gear's usable involute begins
    involute_interference: tuple[bool, bool]  # the mate's tip reaches below the usable involute
    tip_root_clearances: tuple[float, float]  # a' - r_a1 - r_f2, a' - r_a2 - r_f1
    normal_working_pressure_angle: float  # sin(alpha_wn) = sin(alpha_wt) cos(beta_b); = alpha_wt for spur


TIP_RADII_MODES = ("spec", "constant_clearance")


def mesh_geometry(pair: GearPair, centre_distance: float | None = None, tip_radii="spec",
                  face_width: float | None = None) -> MeshGeometry:
    """Working pressure angle, contact ratios and related geometry of a pair.

    Parameters
    ----------
    pair : GearPair
    centre_distance : float, optional
        Operating centre distance a' (mm). Default: the working centre distance from the profile
        shifts, a_w = a cos(alpha_t) / cos(alpha_wt) (zero backlash for unthinned teeth; thinned
        teeth then have exactly their thinning as circumferential backlash).
    tip_radii : {"spec", "constant_clearance"} or (float, float)
        ``"spec"``: each gear's ``tip_radius`` (no tip shortening). ``"constant_clearance"``: tips
        shortened where needed to keep the standard tip-to-root clearance of the unshifted pair,
        r_a1 = min(r_a1, a' - r_f2 - (h_f2* - h_a1*) m_n), i.e. h_a1 = (h_a* + y - x_2) m_n for
        equal racks (y = (a' - a)/m_n). Or two radii in mm.
    face_width : float, optional
        Face width for the face contact ratio; default the smaller of the two gears'.

    Returns
    -------
    MeshGeometry
        with eps_alpha = (sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a' sin(alpha_wt)) / p_bt,
        p_bt = pi m_t cos(alpha_t), eps_beta = b sin(beta) / (pi m_n), eps_gamma = eps_alpha + eps_beta.
        The path is taken tip to tip; where a tip reaches below the mate's usable involute
        (``involute_interference``) the real path of contact is shorter than this.
    """
    g1, g2 = pair.gear1, pair.gear2
    m_n, alpha_n, beta = g1.module, g1.pressure_angle, g1.helix_angle
    alpha_t = g1.transverse_pressure_angle
    a0 = pair.standard_centre_distance
    aw_shift = working_centre_distance(pair.shift_sum, pair.teeth_sum, m_n, alpha_n, beta)
    a = aw_shift if centre_distance is None else float(centre_distance)
    rb1, rb2 = g1.base_radius, g2.base_radius
    if not (math.isfinite(a) and a > rb1 + rb2):
        raise DesignError("centre_distance", f"{a!r} mm does not clear the base circles", f"> {rb1 + rb2:.6g} mm")
    alpha_w = working_pressure_angle_at(rb1 + rb2, a)

    if isinstance(tip_radii, str):
        if tip_radii not in TIP_RADII_MODES:
            raise DesignError("tip_radii", f"{tip_radii!r} is not a valid choice",
                              ", ".join(map(repr, TIP_RADII_MODES)))
        ra1, ra2 = g1.tip_radius, g2.tip_radius
        if tip_radii == "constant_clearance":
            ra1 = min(ra1, a - g2.root_radius_standard - (g2.dedendum_coefficient - g1.addendum_coefficient) * m_n)
            ra2 = min(ra2, a - g1.root_radius_standard - (g1.dedendum_coefficient - g2.addendum_coefficient) * m_n)
    else:
        try:
            ra1, ra2 = (float(v) for v in tip_radii)
        except (TypeError, ValueError):
            raise DesignError("tip_radii", f"{tip_radii!r} is not a mode or two radii",
                              "'spec', 'constant_clearance' or (r_a1, r_a2) in mm") from None
    for i, (ra, rb) in enumerate(((ra1, rb1), (ra2, rb2)), start=1):
        if not (math.isfinite(ra) and ra > rb):
            raise DesignError(f"gear{i}.tip_radius", f"{ra:.6g} mm is not above the base circle", f"> {rb:.6g} mm")

    roll_tip1 = roll_length(ra1, rb1)  # roll length from base tangent point to tip, on each gear
    roll_tip2 = roll_length(ra2, rb2)
    line = a * math.sin(alpha_w)  # T1T2, the line of action between the base tangent points
    g_alpha = length_of_action((ra1, ra2), (rb1, rb2), a)
    p_bt = 2 * math.pi * rb1 / g1.teeth
    eps_a = g_alpha / p_bt
    b = min(g1.face_width, g2.face_width) if face_width is None else float(face_width)
    if not (math.isfinite(b) and b > 0):
        raise DesignError("face_width", f"{b!r} is out of range", "> 0 mm")
    eps_b = b * math.sin(beta) / (math.pi * m_n)

    # the mate's tip reaches down to roll length (T1T2 - roll_tip_mate) on this gear
    roll_sap1 = line - roll_tip2
    roll_sap2 = line - roll_tip1
    sap1 = math.hypot(rb1, roll_sap1)
    sap2 = math.hypot(rb2, roll_sap2)
    start1, start2 = involute_start_radius(g1), involute_start_radius(g2)
    interf1 = roll_sap1 < 0 or sap1 < start1 * (1 - 1e-12)
    interf2 = roll_sap2 < 0 or sap2 < start2 * (1 - 1e-12)
    return MeshGeometry(
        centre_distance=a, standard_centre_distance=a0, working_centre_distance=aw_shift,
        transverse_pressure_angle=alpha_t, working_pressure_angle=alpha_w,
        working_pitch_radii=(rb1 / math.cos(alpha_w), rb2 / math.cos(alpha_w)), base_radii=(rb1, rb2),
        tip_radii=(ra1, ra2), transverse_base_pitch=p_bt, length_of_action=g_alpha,
        transverse_contact_ratio=eps_a, face_width=b, face_contact_ratio=eps_b, total_contact_ratio=eps_a + eps_b,
        active_profile_start_radii=(sap1, sap2), involute_start_radii=(start1, start2),
        involute_interference=(bool(interf1), bool(interf2)),
        tip_root_clearances=(a - ra1 - g2.root_radius_standard, a - ra2 - g1.root_radius_standard),
        # the flank normal at the working pitch cylinder: its transverse part is inclined alpha_wt,
        # and the normal itself is tilted beta_b out of the transverse plane
        normal_working_pressure_angle=math.asin(math.sin(alpha_w) * math.cos(g1.base_helix_angle)),
    )


# ---------------------------------------------------------------------------------------------
# Backlash from centre distance and tooth thickness
# ---------------------------------------------------------------------------------------------

def _tight_mesh_inv(pair: GearPair) -> float:
    """inv of the transverse pressure angle at which the thinned teeth mesh without backlash.

    Teeth fill the working pitch exactly when s_w1 + s_w2 = p_w; with s_w = 2 r_w (s/(2r) +
    inv(alpha_t) - inv(alpha_w)) this gives inv(alpha_w) = inv(alpha_t) + (s1 + s2 - p_t) / ((z1 + z2) m_t).
    """
    g1, g2 = pair.gear1, pair.gear2
    s_sum = reference_tooth_thickness(g1) + reference_tooth_thickness(g2)
    return (involute(g1.transverse_pressure_angle)
            + (s_sum - g1.transverse_pitch) / (pair.teeth_sum * g1.transverse_module))


def tight_mesh_centre_distance(pair: GearPair) -> float:
    """Centre distance (mm) at which the pair, thinning included, meshes with zero backlash.

    Equals :func:`working_centre_distance` when neither gear is thinned. Raises
    :class:`GeometryError` (``tight_mesh``) when the teeth are so thin that no such distance exists.
    """
    inv_w = _tight_mesh_inv(pair)
    if inv_w < 0:
        raise GeometryError("tight_mesh", "the teeth are too thin to mesh without backlash at any centre distance")
    return (pair.gear1.base_radius + pair.gear2.base_radius) / math.cos(inverse_involute(inv_w))


@dataclass(frozen=True)
class MeshBacklash:
    """Backlash of a pair at a centre distance; see :func:`backlash_at_centre_distance`.

    All lengths in mm, angles in rad; positive means clearance, negative means the teeth would
    have to interpenetrate. Fields are floats, or arrays shaped like the centre distances given.
    """

    centre_distance: float | np.ndarray
    tight_mesh_centre_distance: float  # zero backlash here (nan if the teeth are too thin for any)
    working_pressure_angle: float | np.ndarray  # transverse, at the centre distance
    circumferential: float | np.ndarray  # j_wt: transverse arc at the working pitch circles
    circumferential_reference: float | np.ndarray  # j_t = j_bt / cos(alpha_t): transverse arc at the reference circles
    base_tangent: float | np.ndarray  # j_bt = j_wt cos(alpha_wt): along the transverse line of action
    normal: float | np.ndarray  # j_bn = j_wt cos(alpha_wt) cos(beta_b): normal to the flanks
    angular1: float | np.ndarray  # free rotation of gear 1 with gear 2 held: j_wt / r_w1
    angular2: float | np.ndarray  # free rotation of gear 2 with gear 1 held: j_wt / r_w2
    centre_distance_change: float | np.ndarray  # radial: a' - tight-mesh centre distance


def backlash_at_centre_distance(pair: GearPair, centre_distance) -> MeshBacklash:
    """Backlash of the pair at the given centre distance(s), from the tooth thicknesses.

    Conventions (positive = clearance, thinning of both gears included):

    * ``circumferential`` j_wt: the transverse circumferential backlash, i.e. the working pitch
      p_w minus the two transverse arc tooth thicknesses, all on the working pitch circles
      r_wi = r_bi / cos(alpha_wt) of this centre distance:
      j_wt = (z1 + z2) m_t cos(alpha_t) / cos(alpha_wt) * (inv(alpha_wt) - inv(alpha_w0)),
      alpha_w0 the tight-mesh angle (:func:`tight_mesh_centre_distance`).
    * ``circumferential_reference`` j_t = j_bt / cos(alpha_t): the same free play as a transverse
      arc on the reference circles (where tooth thinning is stated); = 2 a (inv(alpha_wt) -
      inv(alpha_w0)) with a the standard centre distance, and equal to the summed thinning at the
      working centre distance of the profile shifts.
    * ``base_tangent`` j_bt = j_wt cos(alpha_wt) = 2 (r_b1 + r_b2)(inv(alpha_wt) - inv(alpha_w0)):
      the gap along the transverse line of action (for spur gears this is the normal backlash).
    * ``normal`` j_bn = j_wt cos(alpha_wt) cos(beta_b): the shortest distance between the
      non-working flanks, normal to the tooth surfaces (ISO/TR 10064-2 convention).
    * ``angular1``/``angular2``: rotation of one gear, rad, the other held.

    For a small change da of centre distance from the tight mesh, j_bt ~ 2 da sin(alpha_wt).

    Parameters
    ----------
    pair : GearPair
    centre_distance : float or array of any shape
        Operating centre distance(s), mm; each beyond the sum of the base radii.
    """
    g1, g2 = pair.gear1, pair.gear2
    a = np.asarray(centre_distance, dtype=float)
    rb1, rb2 = g1.base_radius, g2.base_radius
    if np.any(~np.isfinite(a)) or np.any(a <= rb1 + rb2):
        raise DesignError("centre_distance", "must be larger than the sum of the base radii", f"> {rb1 + rb2:.6g} mm")
    inv0 = _tight_mesh_inv(pair)
    alpha_w = working_pressure_angle_at(rb1 + rb2, a)
    j_bt = backlash_change(rb1 + rb2, alpha_w, inv0)
    j_wt = j_bt / np.cos(alpha_w)
    try:
        a_tight = tight_mesh_centre_distance(pair)
    except GeometryError:
        a_tight = math.nan
    return MeshBacklash(
        centre_distance=_out(a), tight_mesh_centre_distance=a_tight, working_pressure_angle=_out(alpha_w),
        circumferential=_out(j_wt), circumferential_reference=_out(j_bt / math.cos(g1.transverse_pressure_angle)),
        base_tangent=_out(j_bt), normal=_out(j_bt * math.cos(g1.base_helix_angle)),
        angular1=_out(j_bt / rb1), angular2=_out(j_bt / rb2), centre_distance_change=_out(a - a_tight),
    )


# ---------------------------------------------------------------------------------------------
# Undercut, start of the involute, tip land
# ---------------------------------------------------------------------------------------------

def rack_flank_addendum_coefficient(normal_pressure_angle, dedendum_coefficient=1.25, rack_tip_radius_coefficient=0.0):
    """Height of the generating rack's straight flank beyond its datum line, over m_n.

    The rack tooth that cuts the gear's root reaches h_f* m_n beyond the datum line; its tip
    radius rho is tangent to the tip line and to the flank. The fillet centre sits rho inside the
    tip line and the flank is tangent to the fillet where the flank normal, inclined alpha_n to
    the datum line, passes through that centre: rho sin(alpha_n) nearer the tip than the centre.
    So the straight flank ends at h_ae* = h_f* - rho* (1 - sin(alpha_n)) (same in the transverse
    section: heights do not change with the section). Array in, array out.
    """
    return _out(np.asarray(dedendum_coefficient, float)
                - np.asarray(rack_tip_radius_coefficient, float) * (1.0 - np.sin(normal_pressure_angle)))


def minimum_teeth_without_undercut(normal_pressure_angle, helix_angle=0.0, profile_shift=0.0,
                                   dedendum_coefficient=1.25, rack_tip_radius_coefficient=0.0):
    """Smallest (real-valued) tooth count that the given rack generates without undercut.

    Undercut starts when the end of the rack's straight flank (height h_ae* m_n - x m_n inside
    the rolling line, :func:`rack_flank_addendum_coefficient`) passes the interference point,
    the base tangent point of the line of action, which lies r sin^2(alpha_t) inside the rolling
    line. With r = z m_n / (2 cos beta):

        z_min = 2 (h_ae* - x) cos(beta) / sin^2(alpha_t).

    The smallest whole tooth count is ``ceil(z_min)`` (a gear with exactly z_min teeth touches
    the limit). Array in, array out (broadcast shape); values <= 0 mean "never undercut".
    """
    alpha_t = _transverse_pressure_angle(normal_pressure_angle, helix_angle)
    h_ae = rack_flank_addendum_coefficient(normal_pressure_angle, dedendum_coefficient, rack_tip_radius_coefficient)
    return _out(2.0 * (h_ae - np.asarray(profile_shift, float)) * np.cos(helix_angle) / np.sin(alpha_t) ** 2)


def _generated_form_roll(spec: GearSpec) -> float:
    """Roll length (mm) from the base tangent point to where the rack's flank end generates.

    The rack point at depth h = (h_ae* - x) m_n inside the rolling line touches the gear on the
    line of action h / sin(alpha_t) from the pitch point, i.e. at r sin(alpha_t) - h / sin(alpha_t)
    from the interference point. Negative means undercut.
    """
    a_t = spec.transverse_pressure_angle
    h_ae = rack_flank_addendum_coefficient(spec.pressure_angle, spec.dedendum_coefficient,
                                           spec.rack_tip_radius_coefficient)
    depth = (h_ae - spec.profile_shift) * spec.module
    return spec.reference_radius * math.sin(a_t) - depth / math.sin(a_t)


def _rack_fillet_in_gear(spec: GearSpec, tau):
    """Points the generating rack's tip fillet leaves on the gear, transverse section.

    ``tau`` (array) parameterises the fillet from the tip line (-pi/2) to the flank (-alpha_n).
    Frame: gear centre at the origin, the tooth space cut by this rack tooth centred on +y; the
    rack's rolling line touches the reference circle, the rack moves -r phi while the gear turns
    phi. In the transverse section the normal-section fillet circle (radius rho) is an ellipse
    with semi-axes rho / cos(beta) along the rack and rho across it. Each fillet point generates
    the gear point at the roll phi where its normal passes through the pitch point (Willis).

    Returns (radius, polar angle) arrays shaped like ``tau``.
    """
    m_n, beta = spec.module, spec.helix_angle
    a_n, a_t, r = spec.pressure_angle, spec.transverse_pressure_angle, spec.reference_radius
    rho = spec.rack_tip_radius_coefficient * m_n
    depth = (spec.dedendum_coefficient - spec.profile_shift) * m_n  # rack tip line inside the rolling line
    space = spec.transverse_pitch - reference_tooth_thickness(spec)  # = rack tooth width on the rolling line
    v_c = -depth + rho  # fillet centre, across the rack (outward from the gear positive)
    u_c = (space * math.cos(beta) / 2 + v_c * math.tan(a_n) - rho / math.cos(a_n)) / math.cos(beta)
    tau = np.asarray(tau, float)
    u = u_c + rho / math.cos(beta) * np.cos(tau)
    v = v_c + rho * np.sin(tau)
    n_u, n_v = math.cos(beta) * np.cos(tau), np.sin(tau)  # outward normal of the ellipse
    phi = (u - v * n_u / n_v) / r
    fx, fy = u - r * phi, r + v
    c, s = np.cos(phi), np.sin(phi)
    gx, gy = c * fx + s * fy, -s * fx + c * fy  # rotate by -phi into the gear frame
    return np.hypot(gx, gy), np.arctan2(gy, gx)


def _flank_polar_angle(spec: GearSpec, radius):
    """Polar angle of the involute flank at ``radius`` bordering the space of :func:`_rack_fillet_in_gear`."""
    alpha = np.arccos(np.clip(spec.base_radius / np.asarray(radius, float), -1.0, 1.0))
    return (math.pi / 2 - math.pi / spec.teeth + reference_tooth_thickness(spec) / (2 * spec.reference_radius)
            + involute(spec.transverse_pressure_angle) - involute(alpha))


def involute_start_radius(spec: GearSpec) -> float:
    """Radius (mm) where the usable involute flank begins (the true involute form radius).

    Without undercut this is the point generated by the end of the rack's straight flank,
    sqrt(r_b^2 + L^2) with L from the rack geometry (see :func:`minimum_teeth_without_undercut`).
    With undercut the rack's tip fillet cuts into the involute; the involute then begins where
    the fillet's envelope crosses it, found numerically (outermost crossing). Uses the same rack
    as the root: tip radius ``rack_tip_radius_coefficient`` m_n, depth h_f* m_n.
    """
    roll = _generated_form_roll(spec)
    if roll >= 0:
        return math.hypot(spec.base_radius, roll)
    from scipy.optimize import brentq  # lazily: only undercut gears need it

    rb = spec.base_radius
    lo, hi = -math.pi / 2, -spec.pressure_angle

    def radius_excess(t):
        return float(_rack_fillet_in_gear(spec, t)[0]) - rb

    def side(t):  # > 0: the fillet point lies in the tooth space; < 0: inside the tooth (it cuts)
        rad, ang = _rack_fillet_in_gear(spec, t)
        return float(ang - _flank_polar_angle(spec, max(float(rad), rb)))

    taus = np.linspace(lo, hi, 2001)
    excess = _rack_fillet_in_gear(spec, taus)[0] - rb
    # parts of the fillet envelope outside the base circle (the only place an involute exists)
    edges = [lo] if excess[0] >= 0 else []
    for i in np.nonzero(np.sign(excess[:-1]) != np.sign(excess[1:]))[0]:
        edges.append(brentq(radius_excess, taus[i], taus[i + 1], xtol=1e-15, rtol=1e-15))
    if excess[-1] >= 0:
        edges.append(hi)
    best = -math.inf
    for t0, t1 in zip(edges[::2], edges[1::2]):
        ts = np.linspace(t0, t1, 1001)
        rad, ang = _rack_fillet_in_gear(spec, ts)
        sides = ang - _flank_polar_angle(spec, np.maximum(rad, rb))
        for i in np.nonzero(np.sign(sides[:-1]) != np.sign(sides[1:]))[0]:
            t = brentq(side, ts[i], ts[i + 1], xtol=1e-15, rtol=1e-15)
            best = max(best, float(_rack_fillet_in_gear(spec, t)[0]))
    if not math.isfinite(best):
        # so slight an undercut that the crossing is lost in rounding: it lies between the base
        # circle and the point the straight flank would generate, both within 1e-9 r_b
        nominal = math.hypot(rb, roll)
        if nominal - rb <= 1e-9 * rb:
            return nominal
        raise GeometryError("undercut", f"{spec.name}: could not locate where the undercut meets the involute")
    return best


@dataclass(frozen=True)
class Undercut:
    """Undercut check of one gear; see :func:`undercut`."""

    is_undercut: bool
    minimum_teeth: float  # real-valued z_min for this rack, shift and helix angle (ceil for whole teeth)
    minimum_profile_shift: float  # smallest x_n that avoids undercut at this tooth count
    rack_flank_addendum_coefficient: float  # h_ae*: where the rack's straight flank ends, over m_n
    involute_start_radius: float  # mm, see involute_start_radius()
    base_radius: float  # mm


def undercut(spec: GearSpec) -> Undercut:
    """Whether the generating rack undercuts ``spec``, and the profile shift that would avoid it.

    x_min = h_ae* - z sin^2(alpha_t) / (2 cos beta) (the shift at which z_min equals z).
    """
    a_n, beta = spec.pressure_angle, spec.helix_angle
    h_ae = rack_flank_addendum_coefficient(a_n, spec.dedendum_coefficient, spec.rack_tip_radius_coefficient)
    z_min = minimum_teeth_without_undercut(a_n, beta, spec.profile_shift, spec.dedendum_coefficient,
                                           spec.rack_tip_radius_coefficient)
    x_min = h_ae - spec.teeth * math.sin(spec.transverse_pressure_angle) ** 2 / (2 * math.cos(beta))
    return Undercut(is_undercut=_generated_form_roll(spec) < 0, minimum_teeth=z_min, minimum_profile_shift=x_min,
                    rack_flank_addendum_coefficient=h_ae, involute_start_radius=involute_start_radius(spec),
                    base_radius=spec.base_radius)


@dataclass(frozen=True)
class TipLand:
    """Tooth thickness at the tip; see :func:`tip_land`. Lengths in mm."""

    tip_radius: float
    thickness: float  # transverse arc at the tip circle; <= 0: pointed
    normal_thickness: float  # normal arc at the tip cylinder: thickness * cos(beta_a)
    pointed_radius: float  # where the two involute flanks meet
    is_pointed: bool


def tip_land(spec: GearSpec) -> TipLand:
    """Tip land thickness and the radius at which the tooth would come to a point.

    The normal thickness uses the helix angle at the tip, tan(beta_a) = tan(beta) r_a / r.
    """
    s_at = float(tooth_thickness_at_radius(spec, spec.tip_radius))
    beta_a = math.atan(math.tan(spec.helix_angle) * spec.tip_radius / spec.reference_radius)
    return TipLand(tip_radius=spec.tip_radius, thickness=s_at, normal_thickness=s_at * math.cos(beta_a),
                   pointed_radius=pointed_tip_radius(spec), is_pointed=s_at <= 0)


def check_tip_land(spec: GearSpec, minimum_thickness: float = 0.0) -> TipLand:
    """:func:`tip_land`, raising :class:`GeometryError` (``pointed_tooth``) if the transverse tip land is
    thinner than ``minimum_thickness`` (mm; 0 rejects only pointed teeth)."""
    land = tip_land(spec)
    if land.thickness <= 0 or land.thickness < minimum_thickness:
        unit = spec.length_unit
        what = "pointed" if land.thickness <= 0 else f"only {length_text(land.thickness, unit, 6)} thick at the tip"
        raise GeometryError("pointed_tooth", f"{spec.name}: the tooth is {what} (tip radius "
                            f"{length_text(land.tip_radius, unit, 6)}, flanks meet at "
                            f"{length_text(land.pointed_radius, unit, 6)}, required tip land >= "
                            f"{length_text(minimum_thickness, unit, 6)}); reduce profile_shift, addendum_coefficient "
                            "or thinning")
    return land


# ---------------------------------------------------------------------------------------------
# Specific sliding, and how to split a sum of profile shifts between the two gears
# ---------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class SpecificSliding:
    """Specific sliding at the two ends of the path of contact; see :func:`specific_sliding`.

    Pairs are (gear 1, gear 2), dimensionless. ``root``: at each gear's lowest contact point, where
    the mate's tip touches it (negative and largest in magnitude on a normal mesh; -inf when the
    mate's tip reaches the base tangent point or beyond, i.e. involute interference). ``tip``: at
    each gear's own tip.
    """

    centre_distance: float  # mm
    root: tuple[float, float]
    tip: tuple[float, float]


def specific_sliding(pair: GearPair, centre_distance: float | None = None,
                     tip_radii: tuple[float, float] | None = None) -> SpecificSliding:
    """Specific sliding of each flank at the ends of the path of contact (transverse section).

    A contact point on the line of action lies at roll length rho_i (the flank's radius of
    curvature) from gear i's base tangent point, rho_1 + rho_2 = a' sin(alpha_wt). Each flank
    passes the contact at rho_i omega_i, so the sliding speed over gear 1's own speed is
    zeta_1 = 1 - rho_2 omega_2 / (rho_1 omega_1) = 1 - rho_2 z_1 / (rho_1 z_2), and
    zeta_2 = 1 - rho_1 z_2 / (rho_2 z_1); zero at the pitch point. A gear's root contact has the
    mate's tip at rho_mate = sqrt(r_a,mate^2 - r_b,mate^2).

    Parameters
    ----------
    pair : GearPair
    centre_distance : float, optional
        a' (mm); default the working centre distance of the profile shifts.
    tip_radii : (float, float), optional
        Tip radii (mm); default each gear's ``tip_radius``.
    """
    g1, g2 = pair.gear1, pair.gear2
    a = (working_centre_distance(pair.shift_sum, pair.teeth_sum, g1.module, g1.pressure_angle, g1.helix_angle)
         if centre_distance is None else float(centre_distance))
    rb1, rb2 = g1.base_radius, g2.base_radius
    if not (math.isfinite(a) and a > rb1 + rb2):
        raise DesignError("centre_distance", f"{a!r} mm does not clear the base circles", f"> {rb1 + rb2:.6g} mm")
    ra1, ra2 = (g1.tip_radius, g2.tip_radius) if tip_radii is None else (float(v) for v in tip_radii)
    for i, (ra, rb) in enumerate(((ra1, rb1), (ra2, rb2)), start=1):
        if not (math.isfinite(ra) and ra >= rb):
            raise DesignError(f"gear{i}.tip_radius", f"{ra:.6g} mm is below the base circle", f">= {rb:.6g} mm")
    line = math.sqrt(a * a - (rb1 + rb2) ** 2)  # a' sin(alpha_wt), between the base tangent points
    roll_tip1, roll_tip2 = math.sqrt(ra1 * ra1 - rb1 * rb1), math.sqrt(ra2 * ra2 - rb2 * rb2)
    speed_2_over_1 = g1.teeth / g2.teeth  # omega_2 / omega_1

    def zeta(rho_own, rho_mate, mate_speed_over_own):
        if rho_own <= 0:
            return -math.inf
        return 1.0 - rho_mate * mate_speed_over_own / rho_own

    root = (zeta(line - roll_tip2, roll_tip2, speed_2_over_1), zeta(line - roll_tip1, roll_tip1, 1 / speed_2_over_1))
    tip = (zeta(roll_tip1, line - roll_tip1, speed_2_over_1), zeta(roll_tip2, line - roll_tip2, 1 / speed_2_over_1))
    return SpecificSliding(centre_distance=a, root=root, tip=tip)


SHIFT_SPLIT_RULE = (
    "equal specific sliding at the two roots (the lowest contact point of each gear, tips as built, "
    "addendum (h_a* + x) m_n, at the working centre distance of the sum); a shift below its minimum "
    "without undercut is then raised to that minimum and the other gear takes the rest of the sum")


@dataclass(frozen=True)
class ShiftSplit:
    """A sum of normal profile shifts split between two gears; see :func:`split_profile_shift`.

    ``success`` is False (and ``message`` says why) when no split balances the sliding within the
    gears' range of shifts, or when the sum is too small for both gears to escape undercut; the
    shifts are then the best the rule gives, not a recommendation to use blindly.
    """

    shift_sum: float
    profile_shifts: tuple[float, float]  # the recommendation
    balanced_shifts: tuple[float, float]  # equal root specific sliding, before the undercut rule
    root_specific_sliding: tuple[float, float]  # at ``profile_shifts``
    minimum_profile_shifts: tuple[float, float]  # each gear's minimum without undercut
    raised_for_undercut: tuple[bool, bool]
    success: bool
    message: str
    rule: str = SHIFT_SPLIT_RULE


_SHIFT_LIMIT = 1.5  # GearSpec's range of profile shift coefficients


def profile_shift_limits(spec: GearSpec) -> tuple[float, float]:
    """(lowest, highest) normal profile shift coefficient x for which ``spec`` (its teeth, rack and
    helix as they are) is a gear: GearSpec's -1.5 <= x <= 1.5, and the tip circle outside the base
    circle, r + (h_a* + x) m_n > r_b, i.e. x > (r_b - r) / m_n - h_a* (a strict bound where it
    is the lowest)."""
    lowest = (spec.base_radius - spec.reference_radius) / spec.module - spec.addendum_coefficient
    return max(-_SHIFT_LIMIT, lowest), _SHIFT_LIMIT


def split_profile_shift(pair: GearPair, shift_sum: float) -> ShiftSplit:
    """Split ``shift_sum`` = x_n1 + x_n2 between the gears of ``pair`` by :data:`SHIFT_SPLIT_RULE`.

    The profile shifts the pair carries are ignored; everything else (teeth, rack, thinning) is
    used as given. Sliding is balanced by bracketing the shift of gear 1: raising it shortens
    the path of contact on gear 1's root and lengthens it on gear 2's, so the difference of the
    two root slidings (compared through atan, which keeps interference's -inf finite) changes
    sign once. Each shift stays within :func:`profile_shift_limits` (GearSpec's range, tip
    outside the base circle).
    Raises :class:`DesignError` (``shift_sum``) when the sum cannot be split within those limits.
    """
    from scipy.optimize import brentq  # lazily, as for the undercut boundary

    g1, g2 = pair.gear1, pair.gear2
    shift_sum = float(shift_sum)

    (lo1, hi1), (lo2, hi2) = profile_shift_limits(g1), profile_shift_limits(g2)
    # a margin keeps each tip strictly outside its base circle at the ends of the range
    margin = 1e-9
    lo = max(lo1, shift_sum - hi2) + margin
    hi = min(hi1, shift_sum - lo2) - margin
    if not (math.isfinite(shift_sum) and lo < hi):
        raise DesignError("shift_sum", f"{shift_sum!r} cannot be split between the two gears",
                          f"({lo1 + lo2:.6g}, {hi1 + hi2:.6g})")
    # the sum fixes the centre distance; it raises DesignError (profile_shift) if none exists
    centre_distance = working_centre_distance(shift_sum, pair.teeth_sum, g1.module, g1.pressure_angle, g1.helix_angle)

    def shifted(x1):
        x1 = min(max(x1, lo), hi)
        return GearPair(replace(g1, profile_shift=x1), replace(g2, profile_shift=shift_sum - x1))

    def imbalance(x1):
        root = specific_sliding(shifted(x1), centre_distance).root
        return math.atan(root[0]) - math.atan(root[1])

    f_lo, f_hi = imbalance(lo), imbalance(hi)
    success, message = True, "balanced"
    if f_lo == 0:
        x1 = lo
    elif f_hi == 0:
        x1 = hi
    elif (f_lo < 0) != (f_hi < 0):
        x1 = brentq(imbalance, lo, hi, xtol=1e-12, rtol=1e-14)
    else:
        x1 = lo if abs(f_lo) < abs(f_hi) else hi
        success, message = False, "no split of the sum balances the sliding within the range of shifts; nearest end taken"
    balanced = (x1, shift_sum - x1)

    minimum = (undercut(g1).minimum_profile_shift, undercut(g2).minimum_profile_shift)
    x = list(balanced)
    raised = [False, False]
    below = [x[i] < minimum[i] for i in (0, 1)]
    if any(below):
        if shift_sum < minimum[0] + minimum[1]:
            success = False
            message = (f"the sum {shift_sum:.6g} is below the two minimum shifts without undercut together "
                       f"({minimum[0]:.6g} + {minimum[1]:.6g}): no split avoids undercut on both gears")
        else:
            i = 0 if below[0] else 1
            x[i] = minimum[i]
            x[1 - i] = shift_sum - minimum[i]
            raised[i] = True
            message = f"gear {i + 1} raised to its minimum shift without undercut"
    final = shifted(x[0])
    return ShiftSplit(shift_sum=shift_sum, profile_shifts=(final.gear1.profile_shift, final.gear2.profile_shift),
                      balanced_shifts=balanced,
                      root_specific_sliding=specific_sliding(final, centre_distance).root,
                      minimum_profile_shifts=minimum, raised_for_undercut=(raised[0], raised[1]),
                      success=success, message=message)


# ---------------------------------------------------------------------------------------------
# Span measurement (base tangent length) over k teeth
# ---------------------------------------------------------------------------------------------

def _check_teeth_spanned(spec: GearSpec, teeth_spanned):
    k = np.asarray(teeth_spanned)
    kf = k.astype(float)
    if k.dtype == bool or np.any(~np.isfinite(kf)) or np.any(kf != np.round(kf)) or np.any(kf < 1) \
            or np.any(kf > spec.teeth - 1):
        raise DesignError("teeth_spanned", f"{teeth_spanned!r} is out of range",
                          f"whole numbers in [1, {spec.teeth - 1}]")
    return kf


def span_length(spec: GearSpec, teeth_spanned):
    """Span (base tangent length) W_k over k teeth, measured normal to the teeth (mm).

    W_k = m_n cos(alpha_n) [(k - 1/2) pi + z inv(alpha_t)] + 2 x_n m_n sin(alpha_n)
          - thinning cos(alpha_t) cos(beta_b).

    Derivation: in the transverse section the two anvils touch opposite flanks along a common
    tangent of the base circle; its length is (k - 1) base pitches plus the base-circle tooth
    thickness, W_t = (k - 1) p_bt + r_b (s_t / r + 2 inv(alpha_t)). The flanks' normals are tilted
    by beta_b out of the transverse plane, so the anvil gap is W = W_t cos(beta_b); the thinning
    (transverse arc at the reference circle) shortens W_t by thinning cos(alpha_t). No check
    that the anvils touch the involute: see :func:`span_measurement`.

    Parameters
    ----------
    spec : GearSpec
    teeth_spanned : int or int array, values in [1, z - 1]

    Returns
    -------
    float or array shaped like ``teeth_spanned``.
    """
    k = _check_teeth_spanned(spec, teeth_spanned)
    a_n, a_t = spec.pressure_angle, spec.transverse_pressure_angle
    m_n = spec.module
    w = (m_n * math.cos(a_n) * ((k - 0.5) * math.pi + spec.teeth * involute(a_t))
         + 2 * spec.profile_shift * m_n * math.sin(a_n)
         - spec.thinning * math.cos(a_t) * math.cos(spec.base_helix_angle))
    return _out(w)


def span_contact_radius(spec: GearSpec, teeth_spanned):
    """Radius (mm) at which the span anvils touch the flanks, in the symmetric transverse section.

    The transverse common tangent W_t = W / cos(beta_b) touches the base circle at its midpoint,
    so each contact is W_t / 2 along the tangent: r_M = sqrt(r_b^2 + (W_t / 2)^2). Shape of
    ``teeth_spanned``.
    """
    w_t = np.asarray(span_length(spec, teeth_spanned)) / math.cos(spec.base_helix_angle)
    return _out(np.sqrt(spec.base_radius ** 2 + (w_t / 2) ** 2))


def _span_problem(spec: GearSpec, k: int, w: float, r_m: float, start: float) -> str | None:
    if w <= 0:
        return f"teeth_spanned={k}: the span {w:.6g} mm is not positive (teeth too thin)"
    if r_m > spec.tip_radius:
        return (f"teeth_spanned={k}: the anvils would touch at radius {r_m:.6g} mm, above the tip radius "
                f"{spec.tip_radius:.6g} mm (span fewer teeth)")
    if r_m < start:
        return (f"teeth_spanned={k}: the anvils would touch at radius {r_m:.6g} mm, below the start of the involute "
                f"at {start:.6g} mm (base radius {spec.base_radius:.6g} mm; span more teeth)")
    return None


def recommended_teeth_spanned(spec: GearSpec, contact_radius: float | None = None) -> int:
    """Number of teeth to span so that the anvils touch nearest ``contact_radius`` (mm).

    Default target: r + x_n m_n, the middle of the working depth (the circle on which the rack's
    datum line rolls). Solves W(k) for the target contact radius, then takes the nearest whole k
    whose contact lies on the involute. Raises :class:`GeometryError` (``span_contact``) if none does.
    """
    start = involute_start_radius(spec)
    if contact_radius is None:
        target = spec.reference_radius + spec.profile_shift * spec.module
    else:
        target = float(contact_radius)
    target = min(max(target, start, spec.base_radius), spec.tip_radius)
    cos_bb = math.cos(spec.base_helix_angle)
    w_target = 2 * math.sqrt(max(target ** 2 - spec.base_radius ** 2, 0.0)) * cos_bb
    w_half = float(span_length(spec, 1))  # W at k = 1, i.e. (k - 1/2) = 1/2
    step = spec.module * math.cos(spec.pressure_angle) * math.pi  # normal base pitch
    k_ideal = 1 + (w_target - w_half) / step
    candidates = sorted(range(1, spec.teeth), key=lambda k: (abs(k - k_ideal), k))
    for k in candidates[:4]:
        w = float(span_length(spec, k))
        if _span_problem(spec, k, w, float(span_contact_radius(spec, k)), start) is None:
            return k
    raise GeometryError("span_contact", f"{spec.name}: no number of teeth spanned puts the anvils on the involute "
                        f"(involute from {start:.6g} mm to the tip at {spec.tip_radius:.6g} mm, "
                        f"ideal k = {k_ideal:.3g})")


@dataclass(frozen=True)
class SpanMeasurement:
    """A checked span measurement; see :func:`span_measurement`. Lengths in mm."""

    teeth_spanned: int
    span: float  # W_k, normal to the teeth
    transverse_span: float  # W_k / cos(beta_b)
    contact_radius: float  # r_M
    involute_start_radius: float
    tip_radius: float
    minimum_face_width: float  # W_k sin(beta_b): axial extent of the anvils' common normal (0 for spur)


def span_measurement(spec: GearSpec, teeth_spanned: int | None = None) -> SpanMeasurement:
    """Span over ``teeth_spanned`` teeth (default :func:`recommended_teeth_spanned`), checked.

    Raises :class:`GeometryError` ``span_contact`` when the anvils would touch outside the usable
    involute (below :func:`involute_start_radius` or above the tip), and ``span_face_width`` when
    a helical gear's face is narrower than W sin(beta_b), the axial extent of the common normal
    between the two contact lines (the anvils cannot then touch both flanks in the symmetric
    section). :class:`DesignError` ``teeth_spanned`` for a count outside [1, z - 1].
    """
    k = recommended_teeth_spanned(spec) if teeth_spanned is None else teeth_spanned
    if np.ndim(k) != 0:
        raise DesignError("teeth_spanned", "expected a single whole number", f"[1, {spec.teeth - 1}]")
    _check_teeth_spanned(spec, k)
    k = int(k)
    w = float(span_length(spec, k))
    r_m = float(span_contact_radius(spec, k))
    start = involute_start_radius(spec)
    problem = _span_problem(spec, k, w, r_m, start)
    if problem:
        raise GeometryError("span_contact", f"{spec.name}: {problem}")
    b_min = w * math.sin(spec.base_helix_angle)
    if b_min > spec.face_width:
        raise GeometryError("span_face_width", f"{spec.name}: teeth_spanned={k} needs a face width of at least "
                            f"{b_min:.6g} mm (W sin(beta_b)); the face is {spec.face_width:.6g} mm")
    return SpanMeasurement(teeth_spanned=k, span=w, transverse_span=w / math.cos(spec.base_helix_angle),
                           contact_radius=r_m, involute_start_radius=start, tip_radius=spec.tip_radius,
                           minimum_face_width=b_min)


# ---------------------------------------------------------------------------------------------
# Measurement over pins (spur) and balls (helical)
# ---------------------------------------------------------------------------------------------

def _check_pin_diameter(pin_diameter):
    d = np.asarray(pin_diameter, dtype=float)
    if np.any(~np.isfinite(d)) or np.any(d <= 0):
        raise DesignError("pin_diameter", f"{pin_diameter!r} is out of range", "> 0 mm")
    return d


def _pin_centre_inv(spec: GearSpec, pin_diameter):
    """inv(alpha_c) of the pin/ball centre circle (transverse), see :func:`pin_centre_radius`."""
    d = _check_pin_diameter(pin_diameter)
    return (reference_tooth_thickness(spec) / (2 * spec.reference_radius) + involute(spec.transverse_pressure_angle)
            + d / (2 * spec.base_radius * math.cos(spec.base_helix_angle)) - math.pi / spec.teeth)


def pin_centre_radius(spec: GearSpec, pin_diameter):
    """Radius (mm) of the centre of a pin (spur) or ball (helical) touching both flanks of a space.

    Every normal of an involute flank is tangent to the base circle, so the points at distance
    D/2 from the flank along its normals form an involute of the same base circle, turned away
    from the tooth by (D/2) / r_b. For a helical gear the flank normals are tilted beta_b out of
    the transverse plane; the ball centre is then D/2 cos(beta_b) further along the base tangent
    and D/2 sin(beta_b) along the axis, where the flank has turned by (D/2) sin(beta_b) tan(beta_b)
    / r_b; together the centre lies on the transverse involute turned by D / (2 r_b cos(beta_b)),
    exactly. On the space centreline (half a pitch from the tooth centre):

        inv(alpha_c) = s_t / (2 r) + inv(alpha_t) + D / (2 r_b cos(beta_b)) - pi / z,
        r_c = r_b / cos(alpha_c).

    ``pin_diameter`` float or array; result has its shape. Raises :class:`GeometryError`
    (``pin_contact``) when the pin is too small to reach the flanks above the base circle.
    """
    inv_c = np.asarray(_pin_centre_inv(spec, pin_diameter))
    if np.any(inv_c < 0):
        raise GeometryError("pin_contact", f"{spec.name}: pin diameter {pin_diameter!r} mm is too small for the flanks "
                            "to hold it above the base circle")
    return _out(spec.base_radius / np.cos(np.asarray(inverse_involute(inv_c))))


def over_pins_dimension(spec: GearSpec, pin_diameter):
    """Dimension over two pins (spur) or balls (helical) of diameter D, mm; no contact check.

    Both pins lie in one transverse plane. Even z: in opposite spaces, M = 2 r_c + D. Odd z: in
    the spaces nearest opposite, pi (1 - 1/z) apart, M = 2 r_c cos(pi / (2 z)) + D.
    """
    d = _check_pin_diameter(pin_diameter)
    r_c = np.asarray(pin_centre_radius(spec, d))
    factor = 1.0 if spec.teeth % 2 == 0 else math.cos(math.pi / (2 * spec.teeth))
    return _out(2 * r_c * factor + d)


def _pin_contact_radius(spec: GearSpec, pin_diameter, centre_radius):
    """Radius where the pin touches the flank: D/2 cos(beta_b) back along the base tangent from the centre."""
    rb = spec.base_radius
    roll = (np.sqrt(np.asarray(centre_radius) ** 2 - rb ** 2)
            - np.asarray(pin_diameter) / 2 * math.cos(spec.base_helix_angle))
    return roll, np.sqrt(rb ** 2 + roll ** 2)


def ideal_pin_diameter(spec: GearSpec, contact_radius: float | None = None) -> float:
    """Pin (spur) or ball (helical) diameter that touches the flanks at ``contact_radius`` (mm).

    Default: the reference circle. With t = tan of the flank's pressure angle at the contact and
    c = 1 / cos^2(beta_b), the centre satisfies tan(alpha_c) = t + (D/2) cos(beta_b) / r_b and
    :func:`pin_centre_radius`; eliminating D:

        (c - 1) tan(alpha_c) + alpha_c = c t + pi / z - s_t / (2 r) - inv(alpha_t),

    monotonic in alpha_c (solved by Newton's method; for spur gears alpha_c is the right side).
    """
    rb = spec.base_radius
    r_y = spec.reference_radius if contact_radius is None else float(contact_radius)
    if not (math.isfinite(r_y) and rb < r_y <= spec.tip_radius):
        raise DesignError("contact_radius", f"{r_y!r} mm is not on the flank", f"({rb:.6g}, {spec.tip_radius:.6g}] mm")
    t = math.sqrt(r_y * r_y - rb * rb) / rb
    cos_bb = math.cos(spec.base_helix_angle)
    c = 1.0 / cos_bb ** 2
    rhs = c * t + math.pi / spec.teeth - reference_tooth_thickness(spec) / (2 * spec.reference_radius) \
        - involute(spec.transverse_pressure_angle)
    alpha = rhs
    if c > 1.0:
        # f(alpha) = (c - 1) tan(alpha) + alpha - rhs is increasing and convex: Newton's method
        # started where f >= 0 descends monotonically onto the root
        alpha = min(rhs, 1.5)
        for _ in range(200):
            f = (c - 1) * math.tan(alpha) + alpha - rhs
            step = f / ((c - 1) / math.cos(alpha) ** 2 + 1)
            alpha -= step
            if abs(step) <= 1e-15 * max(1.0, abs(alpha)):
                break
    if not 0 < alpha < math.pi / 2:
        raise GeometryError("pin_contact", f"{spec.name}: no pin touches the flanks at radius {r_y:.6g} mm")
    d = 2 * rb * (math.tan(alpha) - t) / cos_bb
    if d <= 0:
        raise GeometryError("pin_contact", f"{spec.name}: no pin touches the flanks at radius {r_y:.6g} mm "
                            "(the space is closed there)")
    return d


@dataclass(frozen=True)
class ChordalTooth:
    """The tooth as a gear-tooth vernier caliper measures it: the normal chordal thickness at the
    reference circle and the chordal height from the tip down to that chord (mm)."""

    thickness: float
    height: float
    virtual_diameter: float  # d_v = d / cos^2(beta): the normal section's virtual spur gear


def chordal_tooth(spec: GearSpec) -> ChordalTooth:
    """The chordal tooth thickness and height of an external gear (with its thinning), on the virtual
    spur gear of the normal section (d_v = d / cos^2 beta, the usual shop convention; exact for a
    spur gear): psi = s_n / d_v, s_c = d_v sin(psi), h_c = h_a + d_v / 2 (1 - cos(psi)), with s_n the
    normal tooth thickness at the reference cylinder and h_a = r_a - r."""
    beta = spec.helix_angle
    d_v = 2 * spec.reference_radius / math.cos(beta) ** 2
    psi = reference_tooth_thickness(spec) * math.cos(beta) / d_v
    return ChordalTooth(thickness=d_v * math.sin(psi),
                        height=spec.tip_radius - spec.reference_radius + d_v / 2 * (1 - math.cos(psi)),
                        virtual_diameter=d_v)


@dataclass(frozen=True)
class PinMeasurement:
    """A checked measurement over pins or balls; see :func:`over_pins_measurement`. Lengths in mm."""

    kind: str  # "pins" (spur) or "balls" (helical)
    pin_diameter: float
    dimension: float  # M
    centre_radius: float
    centre_pressure_angle: float  # transverse alpha_c at the centre circle, rad
    contact_radius: float
    involute_start_radius: float
    tip_radius: float
    protrudes: bool  # the pins stand out beyond the tip circle (needed to measure with flat anvils)


def over_pins_measurement(spec: GearSpec, pin_diameter: float | None = None) -> PinMeasurement:
    """Measurement over pins or balls of ``pin_diameter`` (default :func:`ideal_pin_diameter`), checked.

    Raises :class:`GeometryError` ``pin_contact`` when the pins would touch outside the usable
    involute (below :func:`involute_start_radius` or above the tip); :class:`DesignError`
    ``pin_diameter`` for a non-positive diameter.
    """
    d = ideal_pin_diameter(spec) if pin_diameter is None else pin_diameter
    if np.ndim(d) != 0:
        raise DesignError("pin_diameter", "expected a single diameter", "> 0 mm")
    d = float(_check_pin_diameter(d))
    r_c = float(pin_centre_radius(spec, d))
    roll, r_y = (float(v) for v in _pin_contact_radius(spec, d, r_c))
    start = involute_start_radius(spec)
    if roll <= 0 or r_y < start:
        raise GeometryError("pin_contact", f"{spec.name}: a {d:.6g} mm pin touches the flanks at radius {r_y:.6g} mm, "
                            f"below the start of the involute at {start:.6g} mm; use a larger pin")
    if r_y > spec.tip_radius:
        raise GeometryError("pin_contact", f"{spec.name}: a {d:.6g} mm pin would touch at radius {r_y:.6g} mm, above "
                            f"the tip radius {spec.tip_radius:.6g} mm; use a smaller pin")
    return PinMeasurement(kind="balls" if spec.is_helical else "pins", pin_diameter=d,
                          dimension=float(over_pins_dimension(spec, d)), centre_radius=r_c,
                          centre_pressure_angle=math.acos(spec.base_radius / r_c), contact_radius=r_y,
                          involute_start_radius=start, tip_radius=spec.tip_radius,
                          protrudes=r_c + d / 2 > spec.tip_radius)
