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


def music_wire_allowable_shear(wire_diameter: float) -> float:
    """Static allowable wire shear stress of music wire (ASTM A228), MPa: 0.45 of its tensile strength
    S_ut = A / d^m (A 2211 MPa mm^m, m 0.145, d mm; Shigley's Table 10-4), set not removed."""
    from geargen.design.catalogue import music_wire_allowable
    return music_wire_allowable(wire_diameter)


def spring_for_rate(force: float, rate: float, wire_diameter: float, mean_coil_diameter: float,
                    installed_length: float, shear_modulus: float) -> CompressionSpring:
    """The music-wire compression spring (squared and ground ends) of ``rate`` (N/mm) pushing with
    ``force`` (N) at ``installed_length``: its active coils G d^4 / (8 D^3 k), its free length the
    installed one plus F / k; allowable :func:`music_wire_allowable_shear`."""
    _require_positive(force=force, rate=rate, wire_diameter=wire_diameter, mean_coil_diameter=mean_coil_diameter)
    coils = shear_modulus * wire_diameter ** 4 / (8.0 * mean_coil_diameter ** 3 * rate)
    return compression_spring(wire_diameter, mean_coil_diameter, coils, installed_length + force / rate, shear_modulus,
                              music_wire_allowable_shear(wire_diameter), installed_length=installed_length)


def spring_installed_range(spring: CompressionSpring, clearance: float) -> tuple[float, float]:
    """(shortest, longest) installed length (mm) of ``spring`` at its installed force: at least
    ``clearance`` above its solid height, and short enough that closed solid its stress stays within
    the allowable (the force rises by k per mm from the installed length to solid)."""
    solid_force = spring.allowable_shear_stress / float(spring_shear_stress(1.0, spring.wire_diameter,
                                                                            spring.mean_coil_diameter))
    return (spring.solid_height + clearance,
            spring.solid_height + (solid_force - spring.installed_force) / spring.rate)


def smallest_spring_wire(force: float, rate: float, index: float, shear_modulus: float, clearance,
                         wires) -> tuple[CompressionSpring, tuple[float, float]] | None:
    """The thinnest of ``wires`` (mm, ascending) that makes a spring of ``rate`` and spring index
    ``index`` carry ``force`` within its allowable stress both installed and closed solid, at an
    installed length ``clearance(d)`` above solid at least: (the spring, installed in the middle of
    its range; the range); None when none does."""
    for d in wires:
        coils = shear_modulus * d / (8.0 * index ** 3 * rate)  # G d^4 / (8 D^3 k) at D = C d
        shortest = spring_solid_height(d, coils) + clearance(d)
        trial = spring_for_rate(force, rate, d, index * d, shortest, shear_modulus)
        lo, hi = spring_installed_range(trial, clearance(d))
        if trial.installed_stress <= trial.allowable_shear_stress and lo < hi:
            return spring_for_rate(force, rate, d, index * d, (lo + hi) / 2, shear_modulus), (lo, hi)
    return None


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
# ----------------------------------------------------------------------------------------------
# Helical dual pinions engaging axially (C-axis)

#: sign of a helix hand in :attr:`SlidingMesh.turn_rate` (a right-hand helix turns counter-clockwise
#: seen from +z as it advances along +z)
HAND_SIGN = {"right": 1.0, "left": -1.0}


def rotation_from_axial_travel(axial_travel, pitch_radius: float, helix_angle: float):
    """Rotation (rad) of one helical gear slid ``axial_travel`` (mm) along its axis against a mate
    that does not move (its magnitude; :attr:`SlidingMesh.turn_rate` carries the sign).

    The tooth advances ``z tan(beta)`` around the reference cylinder, so ``theta = z tan(beta) / r``
    (one helix lead, ``2 pi r / tan(beta)``, gives one turn). A cluster of two gears turns by
    neither of its gears' rates alone: see :func:`cluster_opening_rate`.
    """
    if not 0 < helix_angle < math.pi / 2:
        raise DesignError("helix_angle", f"{helix_angle!r} rad is out of range", "(0, pi/2): a helical gear")
    return np.asarray(axial_travel, dtype=float) * math.tan(helix_angle) / pitch_radius


@dataclass(frozen=True)
class SlidingMesh:
    """A mesh whose ``gear`` slides along its own axis while its ``mate`` stays put (mm, rad).

    ``helix_angle`` (at the reference circle, 0 for spur), ``reference_radius`` and ``hand``
    ("right" or "left") are the sliding gear's; on an external mesh the mate has the same helix
    angle and the other hand. ``gear`` and ``mate`` name the two for messages and reports.
    """

    gear: str
    mate: str
    helix_angle: float
    reference_radius: float
    hand: str = "right"

    def __post_init__(self):
        if self.hand not in HAND_SIGN:
            raise DesignError("hand", f"{self.hand!r} is not a valid choice", "'right', 'left'")
        if not (math.isfinite(self.helix_angle) and 0 <= self.helix_angle < math.pi / 2):
            raise DesignError("helix_angle", f"{self.helix_angle!r} rad is out of range", "[0, pi/2)")
        _require_positive(reference_radius=self.reference_radius)

    @property
    def turn_rate(self) -> float:
        """Turn of the sliding gear per mm of slide that keeps its teeth where they were against the
        mate, rad/mm: ``s tan(beta) / r`` (``s`` +1 right hand, -1 left), counter-clockwise seen from
        the side the gear slides towards; ``2 pi / helix lead`` in magnitude, 0 for a spur gear."""
        return HAND_SIGN[self.hand] * math.tan(self.helix_angle) / self.reference_radius


def cluster_opening_rate(engaging: SlidingMesh, other: SlidingMesh | None = None) -> float:
    """Turn of a sliding cluster's engaging gear against its mate per mm of slide, rad/mm (signed).

    The cluster (``engaging`` gear and the ``other`` gear on one shaft, one rigid body) slides
    while both mates are held; the other mesh stays engaged and so sets the cluster's turn, and
    the engaging gear then stands against its mate as if turned by ``other.turn_rate -
    engaging.turn_rate`` per mm without sliding. Counter-clockwise seen from the side the cluster
    slides towards; ``other`` None (or a spur other gear) leaves the engaging gear's helix alone.
    The derivation is in :func:`helical_engagement`.
    """
    return (0.0 if other is None else other.turn_rate) - engaging.turn_rate


@dataclass(frozen=True)
class HelicalEngagement:
    """Axial engagement of two preloaded helical dual pinions (mm, rad).

    Axial positions ``z`` are along the engaging direction, 0 where a pinion is fully engaged.
    The leading pinion runs ``lead`` ahead of the trailing one while they slide; the lead turns
    it (through the helices of both meshes of its cluster, :func:`cluster_opening_rate`) by
    ``relative_rotation`` against the other, which unwinds the loop's preload and opens
    ``backlash`` so both pinions slide into mesh freely. The leader stops at its engaged stop
    first; the trailer closes the lead against its own stop, which winds the loop back up to the
    preload. Retracted stops leave ``clearance`` between the faces, the trailer ``lead`` further
    back.

    ``engaging`` is the mesh the pinions slide into (``helix_angle`` and ``pitch_radius`` are its
    sliding gear's), ``other`` the cluster's other mesh, which stays engaged; ``opening_rate`` is
    the leader's turn against the trailer per mm of lead (rad/mm of the engaging gear,
    counter-clockwise seen from the engaged side, the sign of ``opening_turn``).
    ``backlash`` and ``preload_windup`` are circumferential at the engaging gear's reference
    circle.
    """

    engaging: SlidingMesh
    other: SlidingMesh | None
    helix_angle: float
    pitch_radius: float
    backlash: float
    preload_windup: float
    opening_rate: float
    lead: float
    relative_rotation: float
    engagement_length: float
    clearance: float
    leader_engaged_stop: float
    trailer_engaged_stop: float
    leader_retracted_stop: float
    trailer_retracted_stop: float

    @property
    def circumferential_rate(self) -> float:
        """Circumferential opening at the engaging gear's reference circle per mm of lead (mm/mm)."""
        return abs(self.opening_rate) * self.pitch_radius

    @property
    def opening_turn(self) -> str:
        """How the leader's engaging gear turns against the trailer's as it leads ("ccw" or "cw",
        seen from the engaged side): the leader must be the path whose working flank at the
        engaging mesh this turn lifts off (the flank that turning the other way closes)."""
        return "ccw" if self.opening_rate > 0 else "cw"

    def loop_windup(self, trailer_offset):
        """Windup left in the loop (mm at the reference circle; negative: backlash) with the
        trailer ``trailer_offset`` (mm) behind the leader, both pinions in mesh: ``w - c offset``.
        The preload is this over ``preload_windup`` times the engaged preload (the loop is linear)."""
        return self.preload_windup - self.circumferential_rate * np.asarray(trailer_offset, dtype=float)

    @property
    def leader_stroke(self) -> float:
        return self.leader_engaged_stop - self.leader_retracted_stop

    @property
    def trailer_stroke(self) -> float:
        return self.trailer_engaged_stop - self.trailer_retracted_stop


def helical_engagement(engaging: SlidingMesh, backlash: float, preload_windup: float, engagement_length: float,
                       clearance: float = 0.0, other: SlidingMesh | None = None) -> HelicalEngagement:
    """The lead and travel stops that let two preloaded helical dual pinions slide into mesh.

    ``engaging``: the mesh the pinions slide into (the pinion against the bull gear); ``other``:
    the cluster's other mesh, which stays engaged while it slides (the large gear along the long
    input pinion); None when the cluster's other gear does not slide against anything.
    ``backlash`` and ``preload_windup`` are circumferential at the engaging gear's reference
    circle; the lead may not exceed ``engagement_length`` (the trailer must be in mesh when it
    closes the lead), else DesignError.

    Derivation (z along the axes, +z the engaging direction, turns counter-clockwise seen from
    +z). A helical gear's transverse section at height ``z`` is its ``z = 0`` section turned by
    ``kappa z``, ``kappa = s tan(beta) / r`` (:attr:`SlidingMesh.turn_rate`). Slid by ``dz`` and
    turned by ``psi``, the gear's section at a fixed height ``Z`` is the one it had at ``Z - dz``
    turned by ``psi``: at angle ``psi + kappa (Z - dz)``. Its teeth are where they were at every
    height, so a held mate meshes as before, exactly when::

        psi = kappa dz                                                            (1)

    A cluster is one rigid body: its gear ``o`` in the other mesh (always engaged, mate held) sets
    ``psi = kappa_o dz`` by (1); its engaging gear ``e`` then stands against its held mate as if
    turned, without sliding, by::

        psi - kappa_e dz = (kappa_o - kappa_e) dz = omega dz                      (2)

    which opens (or closes) that mesh by ``|omega| r_e dz`` at its reference circle. The two
    clusters mesh the same input and output, so their gears have the same hands (the clusters
    are mirror images in placement only) and (2) holds for each: with the leader ``delta`` ahead
    of the trailer, the leader's pinion stands turned ``omega delta`` against the bull gear
    relative to the trailer's, and nothing else in the loop changes. The preload loads the two
    paths on opposite flanks; the lead opens the loop when the leader is the path whose working
    flank that turn lifts off (:attr:`HelicalEngagement.opening_turn`). Engaged (``delta = 0``) the
    loop is wound ``w`` past contact; to slide in with ``b`` of backlash::

        lead = (b + w) / (|kappa_o - kappa_e| r_e)                                (3)

    With a spur (or no) other mesh, ``kappa_o = 0`` and (3) is ``(b + w) / tan(beta_e)``, the
    pinion's helix alone. Both gears of one hand (usual for a cluster: their axial thrusts
    oppose) subtract: at one helix angle, ``|kappa_o - kappa_e| r_e = tan(beta) (1 - r_e / r_o)``;
    opposite hands add. The C-axis (15 deg, both left hand, r_e = 25.88, r_o = 62.12 mm):
    ``kappa_o = -4.314``, ``kappa_e = -10.353`` mrad/mm, ``omega = +6.039`` mrad/mm, so 0.1563 mm
    of opening at the pinion's reference circle per mm of lead instead of tan(15 deg) = 0.268.
    """
    if not (math.isfinite(backlash) and backlash >= 0):
        raise DesignError("engagement.backlash", f"{backlash!r} is out of range", ">= 0 mm")
    if not (math.isfinite(preload_windup) and preload_windup >= 0):
        raise DesignError("engagement.preload_windup", f"{preload_windup!r} is out of range", ">= 0 mm")
    _require_positive(engagement_length=engagement_length)
    omega = cluster_opening_rate(engaging, other)
    scale = abs(engaging.turn_rate) + (0.0 if other is None else abs(other.turn_rate))
    if not abs(omega) > 1e-12 * scale or scale == 0:
        what = (f"the helices of {engaging.gear} and {other.gear} have one helix lead and hand: the cluster slides "
                "like a screw" if other is not None and scale > 0 else "no mesh of the sliding cluster is helical")
        raise DesignError("engagement.gear", f"sliding the cluster turns {engaging.gear} nothing against "
                          f"{engaging.mate}: {what}", "a cluster whose two meshes turn it by different rates")
    circumferential = abs(omega) * engaging.reference_radius
    needed = backlash + preload_windup
    lead = needed / circumferential
    if lead > engagement_length * (1 + 1e-12):
        # as the load-time check (geargen.design.stiffness.engagement_spec_from_table) names it
        capacity = engagement_length * circumferential  # what the whole engagement length opens
        name = "backlash" if preload_windup < capacity else "preload_windup"
        most = capacity - (preload_windup if name == "backlash" else backlash)
        raise DesignError(f"engagement.{name}",
                          f"needs a lead of {lead:.6g} mm between the sliding pinions ((backlash {backlash:.6g} + "
                          f"preload windup {preload_windup:.6g} mm) / {circumferential:.6g} mm opened per mm of lead), "
                          f"more than the engagement length {engagement_length:.6g} mm: the trailing pinion would "
                          "reach the bull gear before the lead has opened the backlash for it", f"[0, {max(most, 0.0):.6g}] mm")
    return HelicalEngagement(
        engaging=engaging, other=other, helix_angle=engaging.helix_angle, pitch_radius=engaging.reference_radius,
        backlash=backlash, preload_windup=preload_windup, opening_rate=omega, lead=lead,
        relative_rotation=abs(omega) * lead, engagement_length=engagement_length, clearance=clearance,
        leader_engaged_stop=0.0, trailer_engaged_stop=0.0,
        leader_retracted_stop=-(engagement_length + clearance),
        trailer_retracted_stop=-(engagement_length + clearance + lead))


__all__ = [
    "round_section_second_moment", "round_section_modulus",
    "blade_stiffness_along", "blade_stiffness_lateral", "blade_stiffness_axial", "blade_max_stress",
    "blade_parasitic_shortening", "BladeFlexure", "blade_flexure", "BladeDesign", "design_blade_flexure",
    "SPRING_ENDS", "spring_index", "wahl_factor", "spring_rate", "music_wire_allowable_shear", "spring_for_rate",
    "spring_installed_range", "smallest_spring_wire", "spring_total_coils", "spring_solid_height",
    "spring_shear_stress", "CompressionSpring", "compression_spring",
    "simply_supported_deflection", "simply_supported_slope", "simply_supported_moment", "zero_slope_position",
    "beam_stiffness_at_load", "span_for_stiffness", "BeamPinion", "beam_pinion",
    "HAND_SIGN", "rotation_from_axial_travel", "SlidingMesh", "cluster_opening_rate", "HelicalEngagement",
    "helical_engagement",
]
