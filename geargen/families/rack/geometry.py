"""Exact rack geometry and the rack-and-pinion pair (numpy only).

The rack's outline (normal section, :class:`geargen.families.rack.spec.RackSpec`): straight flanks at the
normal pressure angle, tip and root lands, optional circular tip arcs ("generating" tip rounding)
and root fillets, each tangent to its flank and land. Heights ``u`` are measured from the pitch
line, positive toward the tips. Across the space centred on ``x = 0`` the outline is the graph of
the space half-width ``E(u)``; in the transverse section (perpendicular to the width, the plane of
the pinion's transverse section) every length along the rack is the normal one over ``cos(beta)``
(the teeth are prisms along the tooth direction), heights are unchanged.

Rack and pinion (derivation, transverse section). The pinion's reference circle rolls without
slip on the rack line at height ``u_w = x m_n + dy`` above the rack's pitch line (``x m_n`` the
pinion's profile shift, ``dy`` the centre offset away from the rack). Its transverse tooth
thickness on that circle is ``s_p = p_t/2 + 2 x m_n tan(alpha_t) - T_p`` (thinning ``T_p``); the rack's
space width on the rolling line is ``e_r = p_t/2 + T_r + 2 u_w tan(alpha_t)`` (its flanks lean at
``alpha_t``). The circumferential backlash (transverse, along the rolling line = on the pinion's
reference circle) is their difference::

    j_t = e_r - s_p = T_r + T_p + 2 dy tan(alpha_t)

so moving the pinion away from the rack by ``dy`` adds ``2 dy tan(alpha_t)``; the normal backlash
is ``j_n = j_t cos(alpha_t) cos(beta_b)``. The working pressure angle stays ``alpha_t`` and the
pinion's working pitch circle stays its reference circle for every ``dy`` (the rack's flank angle
fixes the line of action).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geargen.design.gear import GearSpec
from geargen.families.rack.spec import RackSpec, corner_tangent_length
from geargen.errors import DesignError


# ---------------------------------------------------------------------------- the rack outline
@dataclass(frozen=True)
class RackOutline:
    """The rack's normal-section outline over one pitch, the space centred on ``x = 0`` (mm).

    Heights from the pitch line. ``flank_root_u``/``flank_tip_u``: heights where the straight
    flank meets the root fillet / tip arc (the lands' heights when sharp). ``root_centre`` and
    ``tip_centre`` (x, u) are the arc centres on the right side of the space (``x > 0``), the left
    side is the mirror image. ``root_land_half``: half the root land (x of the fillet's start),
    ``tip_land_start``: x where the tip land starts (the tip arc's end); the tooth's centre line is
    at ``x = p_n / 2``.
    """

    pitch: float
    pressure_angle: float
    addendum: float
    dedendum: float
    tooth_thickness: float  # at the pitch line
    tip_radius: float
    root_radius: float
    flank_root_u: float
    flank_tip_u: float
    root_centre: tuple[float, float]
    tip_centre: tuple[float, float]
    root_land_half: float
    tip_land_start: float

    def flank_x(self, u):
        """x of the right flank line (extended) at height ``u``: ``p/2 - s/2 + u tan(alpha)``."""
        return self.pitch / 2 - self.tooth_thickness / 2 + np.asarray(u, dtype=float) * math.tan(self.pressure_angle)

    def space_half_width(self, u):
        """Exact half-width of the space at heights ``u`` (array), ``-h_f <= u <= h_a`` (mm)."""
        u = np.asarray(u, dtype=float)
        out = self.flank_x(u)
        if self.root_radius > 0:
            cx, cu = self.root_centre
            m = u < self.flank_root_u
            # the fillet is the arc below and right of its centre: x = cx + sqrt(r^2 - (u - cu)^2)
            out = np.where(m, cx + np.sqrt(np.maximum(self.root_radius ** 2 - (u - cu) ** 2, 0.0)), out)
        if self.tip_radius > 0:
            cx, cu = self.tip_centre
            m = u > self.flank_tip_u
            out = np.where(m, cx - np.sqrt(np.maximum(self.tip_radius ** 2 - (u - cu) ** 2, 0.0)), out)
        return out

    def height_at(self, x):
        """Height of the rack's top boundary at ``x`` (any x; periodic), mm."""
        x = np.asarray(x, dtype=float)
        d = np.abs(x - self.pitch * np.round(x / self.pitch))  # distance from the nearest space centre
        ta = math.tan(self.pressure_angle)
        u = (d - (self.pitch / 2 - self.tooth_thickness / 2)) / ta  # on the straight flank
        if self.root_radius > 0:  # the root land and the straight flank come from the clip below
            cx, cu = self.root_centre
            arc = (d > cx) & (d < cx + self.root_radius * math.cos(self.pressure_angle))
            u = np.where(arc, cu - np.sqrt(np.maximum(self.root_radius ** 2 - (d - cx) ** 2, 0.0)), u)
        if self.tip_radius > 0:
            cx, cu = self.tip_centre
            arc = (d > cx - self.tip_radius * math.cos(self.pressure_angle)) & (d < self.tip_land_start)
            u = np.where(arc, cu + np.sqrt(np.maximum(self.tip_radius ** 2 - (d - cx) ** 2, 0.0)), u)
        return np.clip(u, -self.dedendum, self.addendum)

    def vertices(self) -> list[tuple[str, tuple]]:
        """One pitch of the outline as segments from the left tooth's centre line to the right's:
        ``("line", (x0, u0), (x1, u1))`` and ``("arc", (x0, u0), (x1, u1), (cx, cu), radius)``."""
        p = self.pitch
        ha, hf = self.addendum, self.dedendum
        right = []
        # from the space centre up the right flank to the right tooth's centre line
        rx0 = self.root_land_half
        right.append(("line", (0.0, -hf), (rx0, -hf)))
        if self.root_radius > 0:
            right.append(("arc", (rx0, -hf), (float(self.flank_x(self.flank_root_u)), self.flank_root_u),
                          self.root_centre, self.root_radius))
        right.append(("line", (float(self.flank_x(self.flank_root_u)), self.flank_root_u),
                      (float(self.flank_x(self.flank_tip_u)), self.flank_tip_u)))
        if self.tip_radius > 0:
            right.append(("arc", (float(self.flank_x(self.flank_tip_u)), self.flank_tip_u), (self.tip_land_start, ha),
                          self.tip_centre, self.tip_radius))
        right.append(("line", (self.tip_land_start, ha), (p / 2, ha)))
        left = []
        for seg in reversed(right):
            mirror = [(-q[0], q[1]) for q in seg[1:3]]
            if seg[0] == "line":
                left.append(("line", mirror[1], mirror[0]))
            else:
                cx, cu = seg[3]
                left.append(("arc", mirror[1], mirror[0], (-cx, cu), seg[4]))
        return left + right


def rack_outline(spec: RackSpec) -> RackOutline:
    """The normal-section outline of ``spec`` (one pitch, the space centred on x = 0)."""
    a = spec.pressure_angle
    t = corner_tangent_length(a)
    ha, hf, s = spec.addendum, spec.dedendum, spec.normal_tooth_thickness
    p = spec.normal_pitch
    rf, ra = spec.root_fillet_radius, spec.tip_radius
    # a fillet tangent to the flank and a land touches the flank at t*r from the corner, along the flank
    flank_root_u = -hf + rf * t * math.cos(a)
    flank_tip_u = ha - ra * t * math.cos(a)
    root_corner_x = p / 2 - s / 2 - hf * math.tan(a)
    tip_corner_x = p / 2 - s / 2 + ha * math.tan(a)
    # centres: the root fillet's is above the root land by r, the tip arc's below the tip land by r
    root_centre = (root_corner_x - rf * t, -hf + rf)
    tip_centre = (tip_corner_x + ra * t, ha - ra)
    return RackOutline(pitch=p, pressure_angle=a, addendum=ha, dedendum=hf, tooth_thickness=s, tip_radius=ra,
                       root_radius=rf, flank_root_u=flank_root_u, flank_tip_u=flank_tip_u, root_centre=root_centre,
                       tip_centre=tip_centre, root_land_half=root_corner_x - rf * t, tip_land_start=tip_corner_x + ra * t)


def pitch_line_pin_diameter(spec: RackSpec) -> float:
    """The pin (ball, for a helical rack: in the normal section) that touches the zero-backlash
    tooth's flanks at the pitch line: the space there is e = p_n / 2 wide, so D = e / cos(alpha_n)."""
    return spec.normal_pitch / 2 / math.cos(spec.pressure_angle)


def standard_rack_pin(spec: RackSpec, deviations) -> tuple[float, str]:
    """The measuring pin (ball) of the shop's series nearest :func:`pitch_line_pin_diameter`
    (:func:`geargen.core.measuring_pins.series_sizes`, the cylindrical gears' series in the rack's
    length unit) whose contact lies on the straight flank for every tooth thickness deviation of
    ``deviations`` (mm, <= 0); the nearest size when none does (the caller warns). Returns the
    diameter (mm) and the series' text."""
    from geargen.core.measuring_pins import PIN_SERIES, series_sizes

    outline = rack_outline(spec)
    sizes = series_sizes(pitch_line_pin_diameter(spec), spec.length_unit)
    on_flank = (d for d in sizes if all(outline.flank_root_u <= pin_contact_height(spec, d, dev)[1]
                                        <= outline.flank_tip_u for dev in deviations))
    return next(on_flank, sizes[0]), PIN_SERIES[spec.length_unit][1]


def pin_contact_height(spec: RackSpec, pin_diameter: float, deviation: float) -> tuple[float, float]:
    """(centre, contact) heights above the pitch line (mm) of a pin of ``pin_diameter`` resting in a
    space of a rack whose normal tooth thickness at the pitch line is p_n / 2 + ``deviation``
    (deviation <= 0): the flank through (e / 2, 0) of slope alpha_n lies D / 2 from the centre when
    e / 2 cos(alpha) + y sin(alpha) = D / 2, so y = (D / (2 cos alpha) - e / 2) / tan alpha; the
    contact is D / 2 sin(alpha) below the centre."""
    a = spec.pressure_angle
    e = spec.normal_pitch / 2 - deviation
    y = (pin_diameter / (2 * math.cos(a)) - e / 2) / math.tan(a)
    return y, y - pin_diameter / 2 * math.sin(a)


def over_pin_to_back(spec: RackSpec, pin_diameter: float, deviation: float) -> float:
    """Back face to the top of the pin (mm): pitch-line height + centre height + D / 2
    (:func:`pin_contact_height`)."""
    return spec.pitch_line_height + pin_contact_height(spec, pin_diameter, deviation)[0] + pin_diameter / 2


def corner_area(radius: float, pressure_angle: float) -> float:
    """Area between a rack corner (inner angle pi/2 + alpha) and its tangent arc of ``radius``:
    ``r^2 (cot(theta/2) - (pi - theta)/2)`` with ``theta = pi/2 + alpha``."""
    return radius ** 2 * (corner_tangent_length(pressure_angle) - (math.pi / 2 - pressure_angle) / 2)


def normal_section_area_per_pitch(spec: RackSpec) -> float:
    """Closed form: area of the rack's normal section over one normal pitch (mm^2): the back up
    to the root line, the straight-sided tooth (a trapezoid), plus the two root fillets, minus
    the two rounded tip corners."""
    ha, hf, s, a = spec.addendum, spec.dedendum, spec.normal_tooth_thickness, spec.pressure_angle
    trapezoid = (ha + hf) * (s + (hf - ha) * math.tan(a))
    return (spec.normal_pitch * spec.back_height + trapezoid + 2 * corner_area(spec.root_fillet_radius, a)
            - 2 * corner_area(spec.tip_radius, a))


def transverse_section_area(spec: RackSpec) -> float:
    """Area of the rack's transverse section (z = const) over its whole length (mm^2). The length is
    a whole number of transverse pitches, so the area is the same in every section (the outline
    is periodic), and the volume is this times the face width."""
    return spec.teeth * normal_section_area_per_pitch(spec) / math.cos(spec.helix_angle)


def rack_volume(spec: RackSpec) -> float:
    return transverse_section_area(spec) * spec.face_width


# ---------------------------------------------------------------------------- rack and pinion
@dataclass(frozen=True)
class RackPinionGeometry:
    """Closed-form geometry of a pinion on a rack (mm, rad), see the module's derivation.

    ``centre_height``: pinion axis above the rack's pitch line (``r + x m_n + dy``);
    ``centre_height_above_back``: above the rack's back face. Backlash is positive clearance.
    ``path_of_contact``: length on the line of action (transverse), approach (rack tip side) plus
    recess (pinion tip side). ``interference``: named problems of the pair's closed form
    (``involute`` when the rack's straight flank reaches past the pinion's base-circle
    tangent point - the pinion undercut the rack would cut; the approach is then counted up to
    that point only, an upper bound, as the undercut pinion's involute starts above it - ,
    ``pinion_tip_vs_rack_root``, ``rack_tip_vs_pinion_root`` for a tip clearance below zero).
    ``contact_ratio_transverse``: path of contact over the transverse base pitch, the rack's part
    ending where its straight flank meets its tip arc; ``contact_ratio_overlap``:
    ``b sin(beta) / (pi m_n)`` over the narrower face.
    """

    centre_offset: float
    centre_height: float
    centre_height_above_back: float
    rolling_line_height: float  # above the rack's pitch line
    transverse_pressure_angle: float
    backlash_circumferential: float
    backlash_normal: float
    tip_clearance_pinion: float  # pinion tip circle to the rack's root line
    tip_clearance_rack: float  # rack tip line to the pinion's root circle
    path_approach: float
    path_recess: float
    contact_ratio_transverse: float
    contact_ratio_overlap: float
    travel_per_revolution: float
    interference: tuple[str, ...]

    @property
    def path_of_contact(self) -> float:
        return self.path_approach + self.path_recess

    @property
    def contact_ratio_total(self) -> float:
        return self.contact_ratio_transverse + self.contact_ratio_overlap


def check_rack_pinion(rack: RackSpec, pinion: GearSpec) -> None:
    """Refuse a pinion that cannot mesh with the rack (DesignError naming the pinion's field)."""
    if pinion.kind != "external":
        raise DesignError("pinion.kind", f"a rack meshes with an external gear, not {pinion.kind!r}", "'external'")
    for name, a, b in (("module", pinion.module, rack.module), ("pressure_angle", pinion.pressure_angle,
                                                                    rack.pressure_angle),
                       ("helix_angle", pinion.helix_angle, rack.helix_angle)):
        if abs(a - b) > 1e-12 * max(1.0, abs(b)):
            raise DesignError(f"pinion.{name}", f"{a!r} differs from the rack's {b!r}", f"{b!r} (the rack's)")
    if rack.is_helical and pinion.hand != rack.hand:
        raise DesignError("pinion.hand", f"{pinion.hand!r}: a helical pinion meshes with a rack of its own hand "
                          "(the rack's hand is named after its pinion's)", repr(rack.hand))


def rack_pinion_geometry(rack: RackSpec, pinion: GearSpec, centre_offset: float = 0.0) -> RackPinionGeometry:
    """The pair's geometry with the pinion moved ``centre_offset`` (mm, + away from the rack) from
    its nominal height ``r + x m_n`` above the rack's pitch line."""
    check_rack_pinion(rack, pinion)
    at = rack.transverse_pressure_angle
    m_n = rack.module
    r, rb, ra = pinion.reference_radius, pinion.base_radius, pinion.tip_radius
    rolling = pinion.profile_shift * m_n + centre_offset
    centre = r + rolling
    jt = rack.thinning + pinion.thinning + 2 * centre_offset * math.tan(at)
    jn = jt * math.cos(at) * math.cos(pinion.base_helix_angle)
    # rack's straight flank ends below its tip arc; that end point is where contact stops on its side
    flank_top = rack.addendum - rack.tip_radius * (1 - math.sin(rack.pressure_angle))
    interference = []
    approach = (flank_top - rolling) / math.sin(at)  # from the pitch point down the line of action
    limit = r * math.sin(at)  # the pinion's base-circle tangent point (interference point)
    if approach > limit * (1 + 1e-12):
        interference.append("involute")
        approach = limit
    recess = math.sqrt(max(ra * ra - rb * rb, 0.0)) - r * math.sin(at)
    p_bt = math.pi * rack.transverse_module * math.cos(at)
    eps_a = (approach + recess) / p_bt
    width = min(rack.face_width, pinion.face_width)
    eps_b = width * math.sin(rack.helix_angle) / (math.pi * m_n)
    c_pinion = centre - ra + rack.dedendum
    c_rack = centre - pinion.root_radius_standard - rack.addendum
    if c_pinion < 0:
        interference.append("pinion_tip_vs_rack_root")
    if c_rack < 0:
        interference.append("rack_tip_vs_pinion_root")
    return RackPinionGeometry(
        centre_offset=centre_offset, centre_height=centre, centre_height_above_back=centre + rack.pitch_line_height,
        rolling_line_height=rolling, transverse_pressure_angle=at, backlash_circumferential=jt, backlash_normal=jn,
        tip_clearance_pinion=c_pinion, tip_clearance_rack=c_rack, path_approach=approach, path_recess=recess,
        contact_ratio_transverse=eps_a, contact_ratio_overlap=eps_b,
        travel_per_revolution=2 * math.pi * r, interference=tuple(interference))


def centre_offset_for_backlash(rack: RackSpec, pinion: GearSpec, backlash_circumferential: float) -> float:
    """The centre offset ``dy`` giving a circumferential backlash ``j_t`` (inverse of the closed form)."""
    check_rack_pinion(rack, pinion)
    return (backlash_circumferential - rack.thinning - pinion.thinning) / (2 * math.tan(rack.transverse_pressure_angle))


__all__ = ["RackOutline", "rack_outline", "pitch_line_pin_diameter", "standard_rack_pin", "pin_contact_height", "over_pin_to_back", "corner_area", "normal_section_area_per_pitch", "transverse_section_area",
           "rack_volume", "RackPinionGeometry", "rack_pinion_geometry", "check_rack_pinion",
           "centre_offset_for_backlash"]
