"""Geometry of an internal pair: an external pinion (z1) meshing inside a ring (z2), mm and rad.

Profile shift convention (ISO 21771, KHK, SDP/SI "Elements of metric gear technology" section
5): ``x2 > 0`` moves the ring's generating profile away from its axis (tip radius
``r2 - m_n (h_a* - x2)``, wider space). With it the internal pair's formulas are those of an
external pair with ``z1 + z2 -> z2 - z1`` and ``x1 + x2 -> x2 - x1``:

- working pressure angle ``inv a_wt = inv a_t + 2 tan(a_n) (x2 - x1) / (z2 - z1)`` (zero backlash);
- centre distance ``a = (z2 - z1) m_t / 2 cos(a_t) / cos(a_wt)``;
- transverse contact ratio ``(sqrt(ra1^2 - rb1^2) - sqrt(ra2^2 - rb2^2) + a sin(a_wt)) / p_bt``.

Both centres lie on the same side of the pitch point, both base circles touch the line of action
on the same side: on it a point's distance from the ring's tangent point is its distance from the
pinion's plus ``(rb2 - rb1) tan(a_wt)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from geargen.core.involute import (involute, inverse_involute, length_of_action, reference_tooth_thickness, roll_length,
                                   working_pressure_angle_at)
from geargen.design.gear import GearSpec
from geargen.errors import DesignError, GeometryError


def check_internal_pair(pinion: GearSpec, ring: GearSpec) -> None:
    """DesignError unless ``pinion`` (external) and ``ring`` (internal) can mesh: same normal
    module and pressure angle, same helix angle and hand, fewer pinion teeth."""
    if pinion.kind != "external":
        raise DesignError("pinion.kind", f"{pinion.kind!r}: the pinion of an internal pair is external", "'external'")
    if ring.kind != "internal":
        raise DesignError("ring.kind", f"{ring.kind!r}: the ring of an internal pair is internal", "'internal'")
    for name in ("module", "pressure_angle", "helix_angle"):
        a, b = getattr(pinion, name), getattr(ring, name)
        if not math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-15):
            raise DesignError(f"ring.{name}", f"{b!r} differs from the pinion's {a!r}", f"{a!r}")
    if pinion.is_helical and pinion.hand != ring.hand:
        raise DesignError("ring.hand", f"{ring.hand!r}: a pinion and its ring have the same hand",
                          repr(pinion.hand))
    if ring.teeth <= pinion.teeth:
        raise DesignError("ring.teeth", f"{ring.teeth} is not more than the pinion's {pinion.teeth}",
                          f"> {pinion.teeth}")


def ring_space_width(ring: GearSpec) -> float:
    """Transverse arc width of the ring's space at its reference circle (mm), thinning included."""
    return (math.pi * ring.transverse_module / 2
            + 2 * ring.profile_shift * ring.module * math.tan(ring.transverse_pressure_angle) + ring.thinning)


def zero_backlash_pressure_angle(pinion: GearSpec, ring: GearSpec) -> float:
    """Transverse working pressure angle of the pair without backlash (rad), thinning included:
    ``inv a_wt = inv a_t + (e2 - s1) / (2 (r2 - r1))`` (``2 m_n tan(a_n) (x2 - x1)`` when unthinned)."""
    value = (involute(pinion.transverse_pressure_angle)
             + (ring_space_width(ring) - reference_tooth_thickness(pinion))
             / (2 * (ring.reference_radius - pinion.reference_radius)))
    if value < 0:
        raise GeometryError("no_working_angle", "the pinion's tooth is too thick for the ring's space at any centre "
                            "distance (inv a_w < 0): lower x1 or raise x2")
    return inverse_involute(value)


@dataclass(frozen=True)
class InternalPairGeometry:
    """An internal pair at ``centre_distance`` (mm). Angles rad, lengths mm, transverse section.

    ``backlash_transverse`` is the play along the line of action (transverse, the rotation of the
    pinion times rb1 with the ring held); ``backlash_circumferential`` the same at the pinion's
    working circle; ``backlash_normal`` normal to the teeth (times cos(beta_b)).
    """

    pinion: GearSpec
    ring: GearSpec
    centre_distance: float
    zero_backlash_centre_distance: float
    reference_centre_distance: float
    centre_distance_modification: float  # y = (a_0 - a_ref) / m_n (zero-backlash distance)
    working_pressure_angle: float
    working_radius_pinion: float
    working_radius_ring: float
    contact_ratio: float
    overlap_ratio: float
    backlash_transverse: float
    backlash_circumferential: float
    backlash_normal: float

    @property
    def tooth_difference(self) -> int:
        return self.ring.teeth - self.pinion.teeth

    @property
    def total_contact_ratio(self) -> float:
        return self.contact_ratio + self.overlap_ratio

    def to_dict(self) -> dict:
        return {"pinion_teeth": self.pinion.teeth, "ring_teeth": self.ring.teeth,
                "tooth_difference": self.tooth_difference,
                "centre_distance_mm": self.centre_distance,
                "zero_backlash_centre_distance_mm": self.zero_backlash_centre_distance,
                "reference_centre_distance_mm": self.reference_centre_distance,
                "centre_distance_modification": self.centre_distance_modification,
                "working_pressure_angle_deg": math.degrees(self.working_pressure_angle),
                "working_diameter_pinion_mm": 2 * self.working_radius_pinion,
                "working_diameter_ring_mm": 2 * self.working_radius_ring,
                "transverse_contact_ratio": self.contact_ratio, "overlap_ratio": self.overlap_ratio,
                "backlash_transverse_mm": self.backlash_transverse,
                "backlash_circumferential_mm": self.backlash_circumferential,
                "backlash_normal_mm": self.backlash_normal}


def internal_pair_geometry(pinion: GearSpec, ring: GearSpec, centre_distance: float | None = None) -> InternalPairGeometry:
    """The pair's geometry at ``centre_distance`` (default: the zero-backlash one).

    Raises GeometryError ``centre_distance`` when the base circles cannot be connected
    (``a <= rb2 - rb1``).
    """
    check_internal_pair(pinion, ring)
    alpha_t = pinion.transverse_pressure_angle
    rb1, rb2 = pinion.base_radius, ring.base_radius
    m_t = pinion.transverse_module
    alpha_0 = zero_backlash_pressure_angle(pinion, ring)
    a_ref = (ring.teeth - pinion.teeth) * m_t / 2
    a_0 = a_ref * math.cos(alpha_t) / math.cos(alpha_0)
    a = a_0 if centre_distance is None else float(centre_distance)
    if not (math.isfinite(a) and a > rb2 - rb1):
        raise GeometryError("centre_distance", f"centre distance {a!r} mm does not reach the base circles' "
                            f"difference rb2 - rb1 = {rb2 - rb1:.6g} mm")
    alpha_w = working_pressure_angle_at(rb2 - rb1, a)
    ra1, ra2 = pinion.tip_radius, ring.tip_radius
    p_bt = math.pi * m_t * math.cos(alpha_t)
    eps_a = length_of_action((ra1, ra2), (rb1, rb2), a, internal=True) / p_bt
    width = min(pinion.face_width, ring.face_width)
    eps_b = width * math.sin(pinion.helix_angle) / (math.pi * pinion.module)
    s1 = reference_tooth_thickness(pinion)
    e2 = ring_space_width(ring)
    inv_t, inv_w = involute(alpha_t), involute(alpha_w)
    # space and tooth at the base circles, less the angle the working circle adds
    j_bt = (2 * rb2 * (e2 / (2 * ring.reference_radius) + inv_t - inv_w)
            - 2 * rb1 * (s1 / (2 * pinion.reference_radius) + inv_t - inv_w))
    return InternalPairGeometry(
        pinion=pinion, ring=ring, centre_distance=a, zero_backlash_centre_distance=a_0,
        reference_centre_distance=a_ref, centre_distance_modification=(a_0 - a_ref) / pinion.module,
        working_pressure_angle=alpha_w, working_radius_pinion=rb1 / math.cos(alpha_w),
        working_radius_ring=rb2 / math.cos(alpha_w), contact_ratio=eps_a, overlap_ratio=eps_b,
        backlash_transverse=j_bt, backlash_circumferential=j_bt / math.cos(alpha_w),
        backlash_normal=j_bt * math.cos(pinion.base_helix_angle))


def line_of_action_roll(pair: InternalPairGeometry, ring_radius: float) -> float:
    """Distance (mm) from the pinion's base tangent point, along the line of action, of the contact
    point at which the ring's flank at ``ring_radius`` engages (negative: behind the pinion's
    tangent point, where the pinion has no involute)."""
    rb1, rb2 = pair.pinion.base_radius, pair.ring.base_radius
    return roll_length(ring_radius, rb2) - (rb2 - rb1) * math.tan(pair.working_pressure_angle)


__all__ = ["InternalPairGeometry", "internal_pair_geometry", "check_internal_pair", "ring_space_width",
           "zero_backlash_pressure_angle", "line_of_action_roll"]
