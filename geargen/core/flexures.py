"""Compliant parts of a preload device: blade flexures, compression springs, the beam-spring
pinion of the C-axis, and helical dual pinions engaging axially (Hale & Slocum, case studies).

Units: mm, N, MPa (N/mm²), rad. Functions take floats (beam functions also take arrays of
positions ``x``) and return floats or arrays; designs return frozen result dataclasses.

Blade flexures (robot joint, Fig. 10): the carriage carrying motor, bevel pair and input gear
rides on parallel blades clamped at both ends. Each blade bends as a fixed-guided beam in its
thin direction (the motion), so ``k = 12 E I / L^3 = E b t^3 / L^3`` per blade and the bending
stress peaks at both clamps, ``sigma = 3 E t delta / L^2``.

Beam-spring pinion (C-axis, Fig. 12): a long pinion simply supported on two bearings, loaded by
the preload force at the mesh. For a point load ``P`` at ``a`` from one bearing on span ``L``
(``b = L - a``) the deflection, slope and moment are the textbook closed forms below; the slope is
zero at ``x0 = sqrt((L^2 - b^2)/3)`` (for ``a >= b``), which coincides with the load only at
mid-span. So the mesh sits at zero slope, meshing evenly across its face, when the bearings are
symmetric about it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geargen.design.stiffness import SPRING_ENDS
from geargen.errors import DesignError


def _require_positive(**values) -> None:
    for name, v in values.items():
        if not (isinstance(v, (int, float, np.floating)) and math.isfinite(v) and v > 0):
            raise DesignError(name, f"{v!r} is out of range", "> 0 and finite")


def round_section_second_moment(diameter: float, bore: float = 0.0) -> float:
    """Area moment of inertia of a round (hollow) section about a diameter, mm^4: pi (d^4 - di^4)/64."""
    return math.pi * (diameter ** 4 - bore ** 4) / 64.0


def round_section_modulus(diameter: float, bore: float = 0.0) -> float:
    """Bending section modulus Z = I / (d/2) of a round (hollow) section, mm^3."""
    return round_section_second_moment(diameter, bore) / (diameter / 2.0)


# ----------------------------------------------------------------------------------------------
# Blade flexures

def blade_stiffness_along(elastic_modulus: float, width: float, thickness: float, length: float,
                          count: int = 1) -> float:
    """Stiffness of ``count`` parallel fixed-guided blades in the direction of motion, N/mm.

    ``k = count * 12 E I / L^3`` with ``I = width thickness^3 / 12``.
    """
    return count * elastic_modulus * width * thickness ** 3 / length ** 3


def blade_stiffness_lateral(elastic_modulus: float, width: float, thickness: float, length: float,
                            count: int = 1, shear_modulus: float | None = None,
                            shear_coefficient: float = 5.0 / 6.0) -> float:
    """Stiffness across the motion in the blade's plane (along its width), N/mm.

    Fixed-guided bending about the blade's strong axis plus shear (Timoshenko), which matters
    because a blade is seldom much longer than it is wide:
    ``1/k_blade = L^3 / (12 E I_w) + L / (kappa G A)``, ``I_w = t w^3 / 12``, ``A = w t``.
    ``shear_modulus`` None leaves shear out (Euler-Bernoulli).
    """
    compliance = length ** 3 / (elastic_modulus * thickness * width ** 3)
    if shear_modulus is not None:
        compliance += length / (shear_coefficient * shear_modulus * width * thickness)
    return count / compliance


def blade_stiffness_axial(elastic_modulus: float, width: float, thickness: float, length: float,
                          count: int = 1) -> float:
    """Stiffness along the blades' length (tension/compression of straight blades), N/mm."""
    return count * elastic_modulus * width * thickness / length


def blade_max_stress(elastic_modulus: float, thickness: float, length: float, travel: float) -> float:
    """Largest bending stress of a fixed-guided blade deflected by ``travel``, MPa: ``3 E t delta / L^2``.

    It occurs at both clamps (moment ``6 E I delta / L^2``).
    """
    return 3.0 * elastic_modulus * thickness * abs(travel) / length ** 2


def blade_parasitic_shortening(length: float, travel: float) -> float:
    """Shortening of a fixed-guided blade's span at a sideways ``travel``, mm: ``3 delta^2 / (5 L)``.

    Half the integral of the squared slope of the S-shaped deflection; the carriage drops by
    this much as it moves (small-deflection estimate).
    """
    return 0.6 * travel ** 2 / length


@dataclass(frozen=True)
class BladeFlexure:
    """Parallel blade flexure: stiffnesses (N/mm, all blades), stress (MPa) at ``travel`` (mm)."""

    count: int
    thickness: float
    length: float
    width: float
    elastic_modulus: float
    shear_modulus: float
    stiffness_along: float
    stiffness_lateral: float
    stiffness_axial: float
    travel: float
    stress_at_travel: float
    allowable_stress: float
    parasitic_shortening: float

    @property
    def stress_ratio(self) -> float:
        """Stress at the travel over the allowable (<= 1 passes)."""
        return self.stress_at_travel / self.allowable_stress

    @property
    def stress_ok(self) -> bool:
        return self.stress_at_travel <= self.allowable_stress

    @property
    def travel_limit(self) -> float:
        """Deflection at which the clamp stress reaches the allowable, mm."""
        return self.allowable_stress * self.length ** 2 / (3.0 * self.elastic_modulus * self.thickness)


def blade_flexure(count: int, thickness: float, length: float, width: float, elastic_modulus: float,
                  allowable_stress: float, travel: float, poisson_ratio: float = 0.29) -> BladeFlexure:
    """Evaluate ``count`` identical parallel blades for a deflection ``travel`` from unstressed."""
    _require_positive(thickness=thickness, length=length, width=width, elastic_modulus=elastic_modulus,
                      allowable_stress=allowable_stress)
    g = elastic_modulus / (2.0 * (1.0 + poisson_ratio))
    return BladeFlexure(
        count=count, thickness=thickness, length=length, width=width, elastic_modulus=elastic_modulus,
        shear_modulus=g,
        stiffness_along=blade_stiffness_along(elastic_modulus, width, thickness, length, count),
        stiffness_lateral=blade_stiffness_lateral(elastic_modulus, width, thickness, length, count, g),
        stiffness_axial=blade_stiffness_axial(elastic_modulus, width, thickness, length, count),
        travel=abs(travel), stress_at_travel=blade_max_stress(elastic_modulus, thickness, length, travel),
        allowable_stress=allowable_stress, parasitic_shortening=blade_parasitic_shortening(length, travel))


@dataclass(frozen=True)
class BladeDesign:
    """Result of :func:`design_blade_flexure`: a blade that meets the target stiffness and travel."""

    thickness: float
    length: float
    width: float
    count: int
    stiffness: float
    travel: float
    stress_at_travel: float
    allowable_stress: float
    success: bool
    message: str


def design_blade_flexure(target_stiffness: float, travel: float, width: float, elastic_modulus: float,
                         allowable_stress: float, count: int = 3, thickness: float | None = None) -> BladeDesign:
    """Size blade thickness and free length for a target stiffness (all blades) and travel.

    Without ``thickness``: the shortest blades whose clamp stress at ``travel`` equals the
    allowable. From ``k = n E w t^3 / L^3`` and ``sigma = 3 E t delta / L^2``:
    ``L^3 = 27 k E^2 delta^3 / (n w sigma^3)``, ``t = sigma L^2 / (3 E delta)``. At fixed stiffness
    ``t`` is proportional to ``L`` and the stress falls as ``1/L``, so longer blades are safer.
    With ``thickness`` (a stock gauge): the length that gives the stiffness, and its stress;
    ``success`` is False when that stress exceeds the allowable.
    """
    _require_positive(target_stiffness=target_stiffness, travel=travel, width=width,
                      elastic_modulus=elastic_modulus, allowable_stress=allowable_stress)
    e, k, d, s = elastic_modulus, target_stiffness, travel, allowable_stress
    if thickness is None:
        length = (27.0 * k * e ** 2 * d ** 3 / (count * width * s ** 3)) ** (1.0 / 3.0)
        t = s * length ** 2 / (3.0 * e * d)
    else:
        _require_positive(thickness=thickness)
        t = thickness
        length = (count * e * width * t ** 3 / k) ** (1.0 / 3.0)
    stress = blade_max_stress(e, t, length, d)
    ok = stress <= s * (1 + 1e-12) and t < width
    if t >= width:
        msg = f"blade thickness {t:.4g} mm is not less than its width {width:.4g} mm: widen the blades"
    elif not ok:
        msg = f"stress {stress:.4g} MPa exceeds the allowable {s:.4g} MPa at this gauge: use a thinner gauge"
    else:
        msg = "meets stiffness and travel"
    return BladeDesign(thickness=t, length=length, width=width, count=count,
                       stiffness=blade_stiffness_along(e, width, t, length, count), travel=d,
                       stress_at_travel=stress, allowable_stress=s, success=ok, message=msg)


# ----------------------------------------------------------------------------------------------
# Helical compression springs
# (the end types and their coils, SPRING_ENDS, are the design file's: geargen.design.stiffness)


def spring_index(mean_coil_diameter: float, wire_diameter: float) -> float:
    """C = D / d."""
    return mean_coil_diameter / wire_diameter


def wahl_factor(index: float) -> float:
    """Wahl stress-correction factor ``K = (4C - 1)/(4C - 4) + 0.615/C`` (curvature and direct shear)."""
    c = index
    return (4.0 * c - 1.0) / (4.0 * c - 4.0) + 0.615 / c


def spring_rate(shear_modulus: float, wire_diameter: float, mean_coil_diameter: float, active_coils: float) -> float:
    """Rate of a helical compression spring, N/mm: ``k = G d^4 / (8 D^3 Na)`` (wire torsion)."""
    return shear_modulus * wire_diameter ** 4 / (8.0 * mean_coil_diameter ** 3 * active_coils)


def spring_total_coils(active_coils: float, end_type: str = "squared_ground") -> float:
    return active_coils + SPRING_ENDS[end_type][0]


def spring_solid_height(wire_diameter: float, active_coils: float, end_type: str = "squared_ground") -> float:
    """Length of the spring compressed solid, mm."""
    extra, add = SPRING_ENDS[end_type]
    return wire_diameter * (active_coils + extra + add)


def spring_shear_stress(force, wire_diameter: float, mean_coil_diameter: float, corrected: bool = True):
    """Wire shear stress at ``force``, MPa: ``K 8 F D / (pi d^3)`` (``K`` the Wahl factor, or 1)."""
    k = wahl_factor(spring_index(mean_coil_diameter, wire_diameter)) if corrected else 1.0
    return k * 8.0 * np.asarray(force, dtype=float) * mean_coil_diameter / (math.pi * wire_diameter ** 3)


@dataclass(frozen=True)
class CompressionSpring:
    """One helical compression spring evaluated at its installed length (mm, N, MPa)."""

    wire_diameter: float
    mean_coil_diameter: float
    active_coils: float
    end_type: str
    free_length: float
    rate: float
    index: float
    wahl_factor: float
    total_coils: float
    solid_height: float
    installed_length: float | None
    installed_force: float
    installed_stress: float
    solid_force: float
    solid_stress: float
    allowable_shear_stress: float

    @property
    def installed_ok(self) -> bool:
        """Installed above solid height and below the allowable stress."""
        return (self.installed_length is None or self.installed_length > self.solid_height) and \
            self.installed_stress <= self.allowable_shear_stress

    @property
    def solid_safe(self) -> bool:
        """True when even closing solid keeps the stress below the allowable (no set)."""
        return self.solid_stress <= self.allowable_shear_stress

    @property
    def installed_deflection(self) -> float:
        return 0.0 if self.installed_length is None else self.free_length - self.installed_length


def compression_spring(wire_diameter: float, mean_coil_diameter: float, active_coils: float, free_length: float,
                       shear_modulus: float, allowable_shear_stress: float, end_type: str = "squared_ground",
                       installed_length: float | None = None) -> CompressionSpring:
    """Rate, solid height and stresses of a helical compression spring."""
    _require_positive(wire_diameter=wire_diameter, mean_coil_diameter=mean_coil_diameter,
                      active_coils=active_coils, free_length=free_length, shear_modulus=shear_modulus)
    if end_type not in SPRING_ENDS:
        raise DesignError("end_type", f"{end_type!r} is not a valid choice", ", ".join(map(repr, SPRING_ENDS)))
    c = spring_index(mean_coil_diameter, wire_diameter)
    if c <= 2:
        raise DesignError("mean_coil_diameter", f"spring index {c:.3g} is too small", "D/d > 2")
    rate = spring_rate(shear_modulus, wire_diameter, mean_coil_diameter, active_coils)
    solid = spring_solid_height(wire_diameter, active_coils, end_type)
    if solid >= free_length:
        raise DesignError("free_length", f"{free_length:.6g} mm is not above the solid height {solid:.6g} mm",
                          f"> {solid:.6g} mm")
    f_inst = 0.0 if installed_length is None else rate * (free_length - installed_length)
    f_solid = rate * (free_length - solid)
    return CompressionSpring(
        wire_diameter=wire_diameter, mean_coil_diameter=mean_coil_diameter, active_coils=active_coils,
        end_type=end_type, free_length=free_length, rate=rate, index=c, wahl_factor=wahl_factor(c),
        total_coils=spring_total_coils(active_coils, end_type), solid_height=solid,
        installed_length=installed_length, installed_force=f_inst,
        installed_stress=float(spring_shear_stress(f_inst, wire_diameter, mean_coil_diameter)),
        solid_force=f_solid, solid_stress=float(spring_shear_stress(f_solid, wire_diameter, mean_coil_diameter)),
        allowable_shear_stress=allowable_shear_stress)


# ----------------------------------------------------------------------------------------------
# Simply supported beam with a point load (the beam-spring pinion)

def _beam_args(span: float, load_position: float) -> tuple[float, float]:
    _require_positive(span=span, load_position=load_position)
    if not load_position < span:
        raise DesignError("load_position", f"{load_position!r} mm is not between the supports", f"(0, {span:.6g}) mm")
    return load_position, span - load_position


def simply_supported_deflection(x, span: float, load_position: float, force: float, flexural_rigidity: float):
    """Deflection (mm, in the direction of the force) at positions ``x`` (mm from the left support).

    ``y = P b x (L^2 - b^2 - x^2) / (6 EI L)`` for ``x <= a``; the mirror form for ``x >= a``.
    """
    a, b = _beam_args(span, load_position)
    x = np.asarray(x, dtype=float)
    xr = span - x
    left = force * b * x * (span ** 2 - b ** 2 - x ** 2)
    right = force * a * xr * (span ** 2 - a ** 2 - xr ** 2)
    return np.where(x <= a, left, right) / (6.0 * flexural_rigidity * span)


def simply_supported_slope(x, span: float, load_position: float, force: float, flexural_rigidity: float):
    """dy/dx (rad) at ``x``: ``P b (L^2 - b^2 - 3x^2) / (6 EI L)`` for ``x <= a``, mirrored beyond."""
    a, b = _beam_args(span, load_position)
    x = np.asarray(x, dtype=float)
    xr = span - x
    left = force * b * (span ** 2 - b ** 2 - 3.0 * x ** 2)
    right = -force * a * (span ** 2 - a ** 2 - 3.0 * xr ** 2)
    return np.where(x <= a, left, right) / (6.0 * flexural_rigidity * span)


def simply_supported_moment(x, span: float, load_position: float, force: float):
    """Bending moment (N·mm) at ``x``: ``P b x / L`` left of the load, ``P a (L - x) / L`` right of it."""
    a, b = _beam_args(span, load_position)
    x = np.asarray(x, dtype=float)
    return np.where(x <= a, force * b * x, force * a * (span - x)) / span


def zero_slope_position(span: float, load_position: float) -> float:
    """Where a simply supported beam with one point load has zero slope (its deepest point), mm.

    Setting the slope to zero in the segment on the far side of mid-span from the load:
    ``x0 = sqrt((L^2 - b^2)/3)`` from the left support when the load is right of centre
    (``a >= b``), and ``L - sqrt((L^2 - a^2)/3)`` otherwise. ``x0`` lies between mid-span and the
    load and equals ``a`` only for ``a = L/2``.
    """
    a, b = _beam_args(span, load_position)
    if a >= b:
        return math.sqrt((span ** 2 - b ** 2) / 3.0)
    return span - math.sqrt((span ** 2 - a ** 2) / 3.0)


def beam_stiffness_at_load(span: float, load_position: float, flexural_rigidity: float) -> float:
    """Stiffness at the load point, N/mm: ``k = 3 EI L / (a^2 b^2)`` (``48 EI / L^3`` at mid-span)."""
    a, b = _beam_args(span, load_position)
    return 3.0 * flexural_rigidity * span / (a * a * b * b)


def span_for_stiffness(target_stiffness: float, flexural_rigidity: float, mesh_position: float | None = None) -> float:
    """Bearing span that gives ``target_stiffness`` at the mesh, mm.

    ``mesh_position`` None: the mesh at mid-span (zero slope), ``L = (48 EI / k)^(1/3)``.
    Otherwise the mesh at a fixed distance ``a`` from one bearing: the root ``L > a`` of
    ``k a^2 (L - a)^2 = 3 EI L`` (the stiffness falls monotonically as L grows).
    """
    _require_positive(target_stiffness=target_stiffness, flexural_rigidity=flexural_rigidity)
    k, ei = target_stiffness, flexural_rigidity
    if mesh_position is None:
        return (48.0 * ei / k) ** (1.0 / 3.0)
    a = mesh_position
    _require_positive(mesh_position=a)
    p = 2.0 * k * a ** 3 + 3.0 * ei
    return (p + math.sqrt(p * p - 4.0 * k * k * a ** 6)) / (2.0 * k * a * a)


@dataclass(frozen=True)
class BeamPinion:
    """A long pinion on two bearings used as the preload spring (mm, N, MPa, rad).

    ``stiffness`` is the linear stiffness at the mesh along the preload force; the values
    ``deflection``, ``slope_at_mesh``, ``face_misalignment`` and ``max_stress`` are at ``force``.
    ``face_misalignment`` is the difference in deflection between the two ends of the mesh face
    (zero-slope designs keep it near zero).
    """

    span: float
    mesh_position: float
    diameter: float
    bore: float
    elastic_modulus: float
    flexural_rigidity: float
    stiffness: float
    zero_slope_position: float
    force: float
    deflection: float
    slope_at_mesh: float
    face_width: float
    face_misalignment: float
    max_stress: float
    allowable_stress: float | None

    @property
    def stress_ok(self) -> bool | None:
        return None if self.allowable_stress is None else self.max_stress <= self.allowable_stress

    @property
    def zero_slope_offset(self) -> float:
        """Distance from the mesh to the zero-slope point, mm (0 for a symmetric span)."""
        return self.zero_slope_position - self.mesh_position


def beam_pinion(diameter: float, elastic_modulus: float, force: float = 0.0, *, span: float | None = None,
                mesh_position: float | None = None, target_stiffness: float | None = None,
                face_width: float = 0.0, allowable_stress: float | None = None, bore: float = 0.0) -> BeamPinion:
    """Evaluate (``span`` given) or size (``target_stiffness`` given) the beam-spring pinion.

    The beam section is a round bar of ``diameter`` (the pinion's root diameter is a safe
    choice); ``force`` is the preload force at the mesh (N). ``mesh_position`` defaults to
    mid-span, the one place where the load point has zero slope.
    """
    _require_positive(diameter=diameter, elastic_modulus=elastic_modulus)
    ei = elastic_modulus * round_section_second_moment(diameter, bore)
    if span is None:
        if target_stiffness is None:
            raise DesignError("span", "missing", "span or target_stiffness")
        span = span_for_stiffness(target_stiffness, ei, mesh_position)
    a = span / 2.0 if mesh_position is None else mesh_position
    k = beam_stiffness_at_load(span, a, ei)
    x0 = zero_slope_position(span, a)
    half = min(face_width / 2.0, a, span - a)
    ends = simply_supported_deflection([a - half, a + half], span, a, force, ei)
    moment = float(simply_supported_moment(a, span, a, force))
    return BeamPinion(span=span, mesh_position=a, diameter=diameter, bore=bore, elastic_modulus=elastic_modulus,
                      flexural_rigidity=ei, stiffness=k, zero_slope_position=x0, force=force,
                      deflection=force / k, slope_at_mesh=float(simply_supported_slope(a, span, a, force, ei)),
                      face_width=face_width, face_misalignment=float(abs(ends[1] - ends[0])),
                      max_stress=abs(moment) / round_section_modulus(diameter, bore),
                      allowable_stress=allowable_stress)


# ----------------------------------------------------------------------------------------------
# Helical dual pinions engaging axially (C-axis)

def rotation_from_axial_travel(axial_travel, pitch_radius: float, helix_angle: float):
    """Rotation (rad) of a helical gear slid ``axial_travel`` (mm) along its axis while in mesh.

    The tooth advances ``z tan(beta)`` around the reference cylinder, so ``theta = z tan(beta) / r``
    (one lead, ``2 pi r / tan(beta)``, gives one turn).
    """
    if not 0 < helix_angle < math.pi / 2:
        raise DesignError("helix_angle", f"{helix_angle!r} rad is out of range", "(0, pi/2): a helical gear")
    return np.asarray(axial_travel, dtype=float) * math.tan(helix_angle) / pitch_radius


def axial_travel_for_circumferential(circumferential, helix_angle: float):
    """Axial travel (mm) whose helix turns a gear by ``circumferential`` mm at its reference circle."""
    if not 0 < helix_angle < math.pi / 2:
        raise DesignError("helix_angle", f"{helix_angle!r} rad is out of range", "(0, pi/2): a helical gear")
    return np.asarray(circumferential, dtype=float) / math.tan(helix_angle)


@dataclass(frozen=True)
class HelicalEngagement:
    """Axial engagement of two preloaded helical dual pinions (mm, rad).

    Axial positions ``z`` are along the engaging direction, 0 where a pinion is fully engaged.
    The leading pinion runs ``lead`` ahead of the trailing one while they slide; the lead turns
    it (through the helix) by ``relative_rotation`` against the other, which unwinds the loop's
    preload and opens ``backlash`` so both pinions slide into mesh freely. The leader stops at its
    engaged stop first; the trailer closes the lead against its own stop, which winds the loop
    back up to the preload. Retracted stops leave ``clearance`` between the faces, the trailer
    ``lead`` further back.
    """

    helix_angle: float
    pitch_radius: float
    backlash: float
    preload_windup: float
    lead: float
    relative_rotation: float
    engagement_length: float
    clearance: float
    leader_engaged_stop: float
    trailer_engaged_stop: float
    leader_retracted_stop: float
    trailer_retracted_stop: float

    @property
    def leader_stroke(self) -> float:
        return self.leader_engaged_stop - self.leader_retracted_stop

    @property
    def trailer_stroke(self) -> float:
        return self.trailer_engaged_stop - self.trailer_retracted_stop


def helical_engagement(helix_angle: float, pitch_radius: float, backlash: float, preload_windup: float,
                       engagement_length: float, clearance: float = 0.0) -> HelicalEngagement:
    """The lead and travel stops that let two preloaded helical pinions slide into mesh.

    ``backlash`` and ``preload_windup`` are circumferential at the reference circle of the mesh
    where the pinions slide. In the engaged position the loop is wound ``preload_windup`` past
    contact; to slide in with ``backlash`` of clearance the lead must turn the pinions apart by
    their sum: ``lead = (backlash + windup) / tan(beta)``.
    """
    if backlash < 0 or preload_windup < 0:
        raise DesignError("backlash", "backlash and preload windup must be >= 0", ">= 0 mm")
    _require_positive(pitch_radius=pitch_radius, engagement_length=engagement_length)
    needed = backlash + preload_windup
    lead = float(axial_travel_for_circumferential(needed, helix_angle))
    return HelicalEngagement(
        helix_angle=helix_angle, pitch_radius=pitch_radius, backlash=backlash, preload_windup=preload_windup,
        lead=lead, relative_rotation=float(rotation_from_axial_travel(lead, pitch_radius, helix_angle)),
        engagement_length=engagement_length, clearance=clearance,
        leader_engaged_stop=0.0, trailer_engaged_stop=0.0,
        leader_retracted_stop=-(engagement_length + clearance),
        trailer_retracted_stop=-(engagement_length + clearance + lead))


__all__ = [
    "round_section_second_moment", "round_section_modulus",
    "blade_stiffness_along", "blade_stiffness_lateral", "blade_stiffness_axial", "blade_max_stress",
    "blade_parasitic_shortening", "BladeFlexure", "blade_flexure", "BladeDesign", "design_blade_flexure",
    "SPRING_ENDS", "spring_index", "wahl_factor", "spring_rate", "spring_total_coils", "spring_solid_height",
    "spring_shear_stress", "CompressionSpring", "compression_spring",
    "simply_supported_deflection", "simply_supported_slope", "simply_supported_moment", "zero_slope_position",
    "beam_stiffness_at_load", "span_for_stiffness", "BeamPinion", "beam_pinion",
    "rotation_from_axial_travel", "axial_travel_for_circumferential", "HelicalEngagement", "helical_engagement",
]
