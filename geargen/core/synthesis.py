"""Centre synthesis of a dual-pinion drive (Hale & Slocum, Fig. 11, Eqs. 7 and 8, Appendix).

Frame, as in the Appendix and the ``geargen synth --json`` contract: origin at the output gear's
centre (gear 4), +x along the symmetry line towards the input gear (gear 1), +z along the gear
axes; angles are counter-clockwise positive seen from +z. Cluster A (gears 2 and 3 on one
shaft) sits at +y, cluster B is its mirror image at -y. Lengths in mm, angles in rad.

- ``A2``: direction angle of the vector output -> cluster A, from +x (positive).
- ``A1``: direction angle of the vector cluster A -> input, from +x (negative). Eq. 8 with
  these signs, ``C1 sin A1 = -C2 sin A2``, puts the input on the symmetry line.
- Eq. 7: ``[A2 (R2+1) - Ba2/2] R1 - A1 (R1+1) - Ba1/2 = i pi / z1``; the left side is the
  input's clockwise rotation from the crowded straight-line start of Fig. 11, ``i`` the number
  of half-tooth increments of the input gear (the Appendix's "N" is i/2, whole teeth).
  ``Ba1 = B1 / r1`` and ``Ba2 = B2 / r3``: the angular backlash of the gear whose rotation the
  term carries (gear 1 in mesh 1, gear 3 in mesh 2; the smaller gear of a reduction).

Backlash ``B`` is circumferential, referred to the reference pitch circles: ``B = j_bt / cos
alpha_t`` with j_bt the base-tangent backlash (the gap along the transverse line of action; the
normal backlash of spur gears), so each gear's free play with its mate held is ``B / r`` (see
:mod:`geargen.design.synthesis`); positive is clearance. From modelled gears:
:func:`modelled_backlash`.

**Operating state.** The preload carriage pushes the input gear towards the output (-x). In
each mesh one flank pair touches and the other carries the whole backlash: in mesh 1A the
input's counter-clockwise flank touches cluster A's large gear, in mesh 2A cluster A's small
gear touches the output with its clockwise flank; path B is the mirror image. These are the
signs of Eq. 7 as the Appendix uses it (more backlash moves the carriage towards the output).

**Rotation ("phase") of a gear.** The polar angle, about the gear's own centre in the frame
above, of the centreline of the gear's tooth 0. To place a gear, model it with a tooth
centreline on its local +x axis, rotate it by ``rotation`` about its own axis, move it to its
centre. Each cluster is one rigid part made with a tooth of its large gear and a tooth of its
small gear centred on the same radial line (both tooth 0 on local +x); both gears of a cluster
therefore carry the same rotation. Single gears' rotations are reported in (-pi/z, pi/z], a
cluster's in (-pi, pi]. For helical gears the rotations hold in the transverse plane z = 0.

**Exact model.** Between two perfect involute gears a, b at centres ``c_a``, ``c_b`` (distance
C, direction beta of a -> b), the flank of a on side ``flank`` (+1 counter-clockwise, -1
clockwise) touches b when ``rot_a = beta - (z_b/z_a)(rot_b - beta - pi) - pi/z_a + flank B(C) /
(2 r_a)`` (mod 2 pi / z_a) -- :func:`mate_rotation`; it places any further gear too. This needs no tooth thicknesses beyond the
backlash, whose change with centre distance is exact for involutes:
``B(C) = T + 2 C_std (inv alpha_w - inv alpha)`` with ``cos alpha_w = C_std cos alpha / C`` and
T the mesh's tooth-thickness deficit (circular pitch minus both reference tooth thicknesses).
With errors zero and B fixed, the exact loop closes at the Eq. 7-8 solution; the functions
below use it to place the gears and to re-solve the carriage position for given errors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from geargen.core.involute import backlash_change, involute, tooth_thickness_at_radius, working_pressure_angle_at
from geargen.design.gear import GearSpec
from geargen.design.synthesis import ROUNDING_RULES, SynthesisInputs
from geargen.errors import GeometryError

#: gears whose pitch-circle centre may be offset from its ideal axis, in the order of ``offsets[..., k, :]``
OFFSET_GEARS = ("input", "cluster_large_a", "cluster_large_b", "cluster_small_a", "cluster_small_b", "output")
#: tooth contacts whose tooth may be displaced along its pitch circle, in the order of ``tooth_errors[..., k]``
TOOTH_CONTACTS = ("input_a", "input_b", "cluster_large_a", "cluster_large_b",
                  "cluster_small_a", "cluster_small_b", "output_a", "output_b")
#: placed gears, in the order :func:`place_gears` returns them
PLACED_GEARS = ("output", "cluster_small_a", "cluster_large_a", "cluster_small_b", "cluster_large_b", "input")


# --- Eqs. 7 and 8 -----------------------------------------------------------------------------

def cluster_angle(A1, C1, C2):
    """A2 from Eq. 8 with the Appendix's signs, ``C1 sin A1 = -C2 sin A2`` (rad).

    NaN where ``|C1 sin A1| > C2`` (no solution). Arrays broadcast.
    """
    s = -np.asarray(C1, dtype=float) * np.sin(A1) / C2
    with np.errstate(invalid="ignore"):
        out = np.where(np.abs(s) <= 1.0, np.arcsin(np.clip(s, -1.0, 1.0)), np.nan)
    return float(out) if out.ndim == 0 else out


def input_rotation(A1, A2, ratio1, ratio2, angular_backlash1, angular_backlash2):
    """Left side of Eq. 7: the input's clockwise rotation from the crowded start (rad).

    ``[A2 (R2+1) - Ba2/2] R1 - A1 (R1+1) - Ba1/2``; ``angular_backlash1`` is B1/r1,
    ``angular_backlash2`` is B2/r3. Arrays broadcast.
    """
    return (A2 * (ratio2 + 1) - angular_backlash2 / 2) * ratio1 - A1 * (ratio1 + 1) - angular_backlash1 / 2  # Eq. 7


def round_increments(increments: float, rule: str) -> int:
    """Round a half-tooth increment count i by ``rule`` (see ROUNDING_RULES).

    "whole_*" round i/2 (whole teeth, the Appendix's "N") and return an even i; "half_*" round i.
    """
    if rule not in ROUNDING_RULES:
        raise ValueError(f"rounding rule must be one of {ROUNDING_RULES}, got {rule!r}")
    if not math.isfinite(increments):
        raise ValueError("increment count is not finite")
    if rule == "whole_down":
        return 2 * math.floor(increments / 2)
    if rule == "whole_nearest":
        return 2 * math.floor(increments / 2 + 0.5)
    if rule == "half_down":
        return math.floor(increments)
    return math.floor(increments + 0.5)


# --- exact involute relations -------------------------------------------------------------------

def operating_pressure_angle(centre_distance, standard_centre_distance, pressure_angle):
    """alpha_w with cos alpha_w = C_std cos alpha / C (rad); NaN where C is inside the base circles."""
    return working_pressure_angle_at(standard_centre_distance * np.cos(pressure_angle), centre_distance)


def backlash_from_thickness_deficit(thickness_deficit, centre_distance, standard_centre_distance, pressure_angle):
    """Circumferential backlash B (mm) of a mesh at centre distance C.

    ``B = T + 2 C_std (inv alpha_w - inv alpha)``; ``thickness_deficit`` T is the circular pitch
    minus the two reference tooth thicknesses (transverse, mm). Arrays broadcast.
    """
    a_w = operating_pressure_angle(centre_distance, standard_centre_distance, pressure_angle)
    return thickness_deficit + backlash_change(standard_centre_distance, a_w, involute(pressure_angle))


def thickness_deficit_for_backlash(backlash, centre_distance, standard_centre_distance, pressure_angle):
    """The T for which a mesh has circumferential backlash ``backlash`` at ``centre_distance``."""
    return backlash - backlash_from_thickness_deficit(0.0, centre_distance, standard_centre_distance, pressure_angle)


def modelled_backlash(spec_a: GearSpec, spec_b: GearSpec, centre_distance: float) -> float:
    """Circumferential backlash B (mm, at the reference circles) of gears made to these specs.

    Tooth thinning and profile shift included: ``B = (r_a / r_wa)(p_w - s_wa - s_wb)`` on the
    operating pitch circles of ``centre_distance`` (mm). Negative: the teeth cannot reach it.
    Pass the results to :func:`place_gears` to place gears modelled from these specs.
    """
    a_w = float(operating_pressure_angle(centre_distance, spec_a.reference_radius + spec_b.reference_radius,
                                         spec_a.transverse_pressure_angle))
    if not math.isfinite(a_w):
        raise GeometryError("backlash", f"centre distance {centre_distance:.6g} mm is inside the base circles")
    r_wa, r_wb = spec_a.base_radius / math.cos(a_w), spec_b.base_radius / math.cos(a_w)
    j_t = (2 * math.pi * r_wa / spec_a.teeth - tooth_thickness_at_radius(spec_a, r_wa)
           - tooth_thickness_at_radius(spec_b, r_wb))
    return j_t * spec_a.reference_radius / r_wa


def mate_rotation(direction, rotation_b, teeth_a: int, teeth_b: int, angular_backlash_a, flank):
    """Rotation of gear a that puts its ``flank`` in contact with gear b (rad, mod 2 pi / z_a).

    direction : (...) float -- direction angle of the vector from a's centre to b's centre.
    rotation_b : (...) float -- rotation of b (polar angle of a tooth centreline).
    angular_backlash_a : (...) float -- B / r_a at this centre distance.
    flank : +1 (a's counter-clockwise flank touches) or -1 (clockwise); 0 centres the tooth.

    Involute action is conjugate, so two facing flanks touch exactly when their crossings of
    the operating pitch circles reach the pitch point together; the tooth of a then sits half
    a pitch minus half the angular backlash from b's tooth, measured along the pitch circles.
    """
    return (direction - (teeth_b / teeth_a) * (rotation_b - direction - np.pi) - np.pi / teeth_a
            + flank * angular_backlash_a / 2)


def wrap(angle, period):
    """``angle`` reduced to (-period/2, period/2]."""
    a = np.asarray(angle, dtype=float)
    out = a - period * np.ceil(a / period - 0.5)
    return float(out) if out.ndim == 0 else out


# --- the solver ---------------------------------------------------------------------------------

@dataclass(frozen=True)
class CentreSynthesis:
    """Result of :func:`synthesize_centres` (mm, rad). Check ``success`` before using numbers.

    ``nominal_*`` is step 1 of the Appendix (A2 and the increment count at the start angle),
    ``A1``/``A2`` step 2 (Eqs. 7-8 with the rounded count, maximum backlash), ``min_backlash_*``
    step 3 as the Appendix does it (clusters fixed, carriage moves along x, Eq. 7 with minimum
    backlash, B held at its value for the design centre distance). Increments count half teeth
    of the input gear; ``teeth_count`` is the Appendix's "N" (= increments / 2).
    """

    success: bool
    message: str
    inputs: SynthesisInputs
    nominal_A1: float
    nominal_A2: float
    nominal_increments: float
    increments: int
    A1: float = math.nan
    A2: float = math.nan
    eq7_residual: float = math.nan
    min_backlash_A1: float = math.nan
    min_backlash_C1: float = math.nan

    def check(self) -> "CentreSynthesis":
        """Return self, or raise :class:`GeometryError` with the solver's message."""
        if not self.success:
            raise GeometryError("centre synthesis", self.message)
        return self

    # derived quantities
    @property
    def ratio_mesh1(self) -> float:
        return self.inputs.ratio_mesh1

    @property
    def ratio_mesh2(self) -> float:
        return self.inputs.ratio_mesh2

    def angular_backlash(self, mesh: int, kind: str) -> float:
        """Ba of the Appendix: B / r1 (mesh 1) or B / r3 (mesh 2), rad; ``kind`` "max" or "min"."""
        return self.inputs.backlash(mesh, kind) / self.inputs.reference_radius(1 if mesh == 1 else 3)

    @property
    def nominal_teeth_count(self) -> float:
        return self.nominal_increments / 2

    @property
    def teeth_count(self) -> float:
        return self.increments / 2

    @property
    def x1(self) -> float:
        return self.inputs.centre_distance_mesh1 * math.cos(self.A1)

    @property
    def y1(self) -> float:
        return self.inputs.centre_distance_mesh1 * math.sin(self.A1)

    @property
    def x2(self) -> float:
        return self.inputs.centre_distance_mesh2 * math.cos(self.A2)

    @property
    def y2(self) -> float:
        return self.inputs.centre_distance_mesh2 * math.sin(self.A2)

    @property
    def input_x(self) -> float:
        """Carriage position: x of the input gear's centre at maximum backlash (mm)."""
        return self.x2 + self.x1

    @property
    def min_backlash_x1(self) -> float:
        return self.y1 / math.tan(self.min_backlash_A1)

    @property
    def min_backlash_dx1(self) -> float:
        """Carriage travel from maximum to minimum backlash, the Appendix's way (mm, + away from the output)."""
        return self.min_backlash_x1 - self.x1

    @property
    def centres(self) -> dict[str, tuple[float, float]]:
        """Gear centres (mm) as in the contract: gear1, gear2a, gear2b (clusters), gear4."""
        return {"gear1": (self.input_x, 0.0), "gear2a": (self.x2, self.y2), "gear2b": (self.x2, -self.y2),
                "gear4": (0.0, 0.0)}

    @property
    def output_rotation(self) -> float:
        """The output gear's rotation: a tooth space centred on +x (rad)."""
        return math.pi / self.inputs.teeth[3]

    @property
    def cluster_rotation(self) -> float:
        """Cluster A's rotation at maximum backlash (cluster B's is minus this), in (-pi, pi]."""
        return wrap(self.A2 * (self.ratio_mesh2 + 1) + math.pi - self.angular_backlash(2, "max") / 2, 2 * math.pi)


def _eq7_input_angle(inputs: SynthesisInputs, increments: int, A2, backlash_mesh1, backlash_mesh2):
    """A1 solving Eq. 7 for fixed clusters (A2) and increments; linear in A1. Arrays broadcast."""
    r1_, r2_ = inputs.ratio_mesh1, inputs.ratio_mesh2
    ba1 = np.asarray(backlash_mesh1, dtype=float) / inputs.reference_radius(1)
    ba2 = np.asarray(backlash_mesh2, dtype=float) / inputs.reference_radius(3)
    return ((A2 * (r2_ + 1) - ba2 / 2) * r1_ - ba1 / 2 - increments * math.pi / inputs.teeth[0]) / (r1_ + 1)  # Eq. 7


def appendix_carriage_travel(synthesis: "CentreSynthesis", backlash_mesh1, backlash_mesh2):
    """Carriage travel (mm, + away from the output) from the synthesised position when the
    backlash becomes ``backlash_mesh1``/``backlash_mesh2``, the Appendix's way (step 3: clusters
    and y1 fixed, Eq. 7, B not updated for the new centre distance). Arrays broadcast."""
    a1 = _eq7_input_angle(synthesis.inputs, synthesis.increments, synthesis.A2, backlash_mesh1, backlash_mesh2)
    return synthesis.y1 / np.tan(a1) - synthesis.x1


def synthesize_centres(inputs: SynthesisInputs, increments: int | None = None) -> CentreSynthesis:
    """Place the dual-pinion train: the Appendix's three steps for any tooth counts.

    ``increments`` overrides the rounded half-tooth count (used for sensitivities). Returns a
    :class:`CentreSynthesis`; ``success`` is False (with a message) when Eq. 8 has no solution
    at the start angle, when no A1 in the valid range satisfies Eqs. 7-8 with the rounded
    count, or when the minimum-backlash step leaves the valid range.
    """
    z1 = inputs.teeth[0]
    r1_, r2_ = inputs.ratio_mesh1, inputs.ratio_mesh2
    c1, c2 = inputs.centre_distance_mesh1, inputs.centre_distance_mesh2
    ba1 = inputs.circumferential_backlash_max_mesh1 / inputs.reference_radius(1)
    ba2 = inputs.circumferential_backlash_max_mesh2 / inputs.reference_radius(3)
    step = math.pi / z1  # one half-tooth increment of input rotation

    def theta(a1):
        return input_rotation(a1, cluster_angle(a1, c1, c2), r1_, r2_, ba1, ba2)

    a1_0 = inputs.start_angle_A1
    a2_0 = cluster_angle(a1_0, c1, c2)
    base = dict(inputs=inputs, nominal_A1=a1_0, nominal_A2=a2_0, nominal_increments=math.nan, increments=-1)
    if not math.isfinite(a2_0):
        return CentreSynthesis(success=False, message=(
            f"Eq. 8 has no solution at the start angle: |C1 sin A1| = {abs(c1 * math.sin(a1_0)):.6g} mm "
            f"exceeds C2 = {c2:.6g} mm"), **base)
    i_nom = theta(a1_0) / step
    i = round_increments(i_nom, inputs.rounding) if increments is None else int(increments)
    base.update(nominal_increments=i_nom, increments=i)

    # theta(A1) decreases strictly on A1 in (lo, 0): both terms of dtheta/dA1 are negative there
    lo = -math.pi / 2 if c1 <= c2 else -math.asin(c2 / c1)
    f_lo, f_hi = theta(lo) - i * step, theta(0.0) - i * step
    if not (f_lo > 0 > f_hi):
        reach = (theta(0.0) / (2 * step), theta(lo) / (2 * step))
        return CentreSynthesis(success=False, message=(
            f"no solution of Eqs. 7-8 near the start angle {math.degrees(a1_0):.4g} deg: the rounded count "
            f"N = {i / 2:g} whole teeth (i = {i}, rule {inputs.rounding!r}, from {i_nom / 2:.6g}) needs A1 outside "
            f"({math.degrees(lo):.4g}, 0) deg, where N can only range over ({reach[0]:.4g}, {reach[1]:.4g}); "
            "choose another start angle, rounding rule or centre distances"), **base)
    from scipy.optimize import brentq  # lazily: importing scipy.optimize costs ~0.5 s

    a1, info = brentq(lambda a: theta(a) - i * step, lo, 0.0, xtol=1e-15, rtol=4 * np.finfo(float).eps,
                      maxiter=200, full_output=True, disp=False)
    residual = theta(a1) - i * step
    if not info.converged or abs(residual) > 1e-12 or not lo < a1 < 0:
        return CentreSynthesis(success=False, message=f"Eqs. 7-8 did not converge ({info.flag}, residual {residual:.3g} rad)",
                               **base)
    a2 = cluster_angle(a1, c1, c2)

    # Appendix step 3: clusters (A2) and y1 frozen, Eq. 7 with minimum backlash
    a1_min = float(_eq7_input_angle(inputs, i, a2, inputs.circumferential_backlash_min_mesh1, inputs.circumferential_backlash_min_mesh2))
    y1 = c1 * math.sin(a1)
    if not -math.pi < a1_min < 0:
        return CentreSynthesis(success=False, message=f"minimum-backlash step gives A1 = {a1_min:.6g} rad, outside (-pi, 0)",
                               A1=a1, A2=a2, eq7_residual=residual, **base)
    return CentreSynthesis(success=True, message="converged", A1=a1, A2=a2, eq7_residual=residual,
                           min_backlash_A1=a1_min, min_backlash_C1=y1 / math.sin(a1_min), **base)


# --- exact loop closure -------------------------------------------------------------------------

@dataclass(frozen=True)
class LoopSolution:
    """Result of :func:`solve_loop`: the preloaded state for each sample (mm, rad).

    carriage_x : (n,) float -- x of the input gear's axis (its nominal centre line).
    input_rotation : (n,) float -- rotation of the input gear, in (-pi/z1, pi/z1].
    cluster_rotation_a, cluster_rotation_b : (n,) float -- rigid rotations of the cluster parts.
    converged : (n,) bool. ``success`` is True when every sample converged.
    """

    success: bool
    message: str
    carriage_x: np.ndarray
    input_rotation: np.ndarray
    cluster_rotation_a: np.ndarray
    cluster_rotation_b: np.ndarray
    output_rotation: float
    converged: np.ndarray
    iterations: int

    def check(self) -> "LoopSolution":
        if not self.success:
            raise GeometryError("loop closure", self.message)
        return self


def solve_loop(synthesis: CentreSynthesis, backlash_mesh1=None, backlash_mesh2=None, offsets=None, tooth_errors=None,
               x_start=None, tol: float = 1e-11, max_iter: int = 30) -> LoopSolution:
    """Re-solve the preloaded drive exactly: where must the carriage sit to close the loop?

    The clusters' axes stay at (x2, +-y2), the output's at the origin; the carriage moves the
    input's axis along x only. Each gear is a perfect involute gear whose pitch circle may be
    offset from its axis and whose tooth in contact may be displaced along its pitch circle.

    backlash_mesh1, backlash_mesh2 : float or (n,) float, mm -- circumferential backlash of each
        mesh at its *design* centre distance (default: the maximum); at other centre distances
        it follows the involute law of the module docstring.
    offsets : (n, 6, 2) float, mm -- pitch-circle centre minus axis, gears in OFFSET_GEARS order.
    tooth_errors : (n, 8) float, mm -- displacement (counter-clockwise positive) of the tooth in
        each contact of TOOTH_CONTACTS along its gear's reference pitch circle.

    Newton's method on the input-rotation mismatch between the two paths, from ``x_start``
    ((n,) float, mm; default the design position); ``converged`` flags samples whose step fell
    below ``tol`` (mm).
    """
    synthesis.check()
    inp = synthesis.inputs
    z1, z2, z3, z4 = inp.teeth
    r1, r2, r3, r4 = (inp.reference_radius(k) for k in (1, 2, 3, 4))
    cs1, al1 = inp.standard_centre_distance(1), inp.pressure_angle(1)
    cs2, al2 = inp.standard_centre_distance(2), inp.pressure_angle(2)
    b1 = inp.circumferential_backlash_max_mesh1 if backlash_mesh1 is None else np.asarray(backlash_mesh1, dtype=float)
    b2 = inp.circumferential_backlash_max_mesh2 if backlash_mesh2 is None else np.asarray(backlash_mesh2, dtype=float)
    t1 = thickness_deficit_for_backlash(b1, inp.centre_distance_mesh1, cs1, al1)
    t2 = thickness_deficit_for_backlash(b2, inp.centre_distance_mesh2, cs2, al2)
    shapes = [np.shape(b1), np.shape(b2)]
    if offsets is not None:
        offsets = np.asarray(offsets, dtype=float)
        if offsets.ndim != 3 or offsets.shape[1:] != (6, 2):
            raise ValueError(f"offsets must be (n, 6, 2), got {offsets.shape}")
        shapes.append(offsets.shape[:1])
    if tooth_errors is not None:
        tooth_errors = np.asarray(tooth_errors, dtype=float)
        if tooth_errors.ndim != 2 or tooth_errors.shape[1] != 8:
            raise ValueError(f"tooth_errors must be (n, 8), got {tooth_errors.shape}")
        shapes.append(tooth_errors.shape[:1])
    n = np.broadcast_shapes(*shapes, (1,))

    def off(k):
        return (0.0, 0.0) if offsets is None else (offsets[:, k, 0], offsets[:, k, 1])

    def tooth(k):
        return 0.0 if tooth_errors is None else tooth_errors[:, k]

    x2, y2 = synthesis.x2, synthesis.y2
    phi4 = synthesis.output_rotation
    rho_nominal = synthesis.cluster_rotation
    ratio1 = z2 / z1
    o4x, o4y = off(5)
    paths = []
    for side, (k_large, k_small, k_in, k_t_large, k_t_small, k_t_out) in ((+1, (1, 3, 0, 2, 4, 6)), (-1, (2, 4, 1, 3, 5, 7))):
        # mesh 2: the cluster's small gear (a) against the output (b); its flank -side touches
        ox, oy = off(k_small)
        dx, dy = o4x - (x2 + ox), o4y - (side * y2 + oy)
        beta = np.arctan2(dy, dx)
        ba3 = backlash_from_thickness_deficit(t2, np.hypot(dx, dy), cs2, al2) / r3
        phi3_seen = mate_rotation(beta, phi4 + tooth(k_t_out) / r4, z3, z4, ba3, -side)
        rho_ref = side * rho_nominal
        rho = rho_ref + wrap(phi3_seen - tooth(k_t_small) / r3 - rho_ref, 2 * np.pi / z3)
        ox, oy = off(k_large)
        paths.append((side, rho, x2 + ox, side * y2 + oy, rho + tooth(k_t_large) / r2, tooth(k_in) / r1))
    i1x, i1y = off(0)
    inv_al1 = involute(al1)
    k_cos = cs1 * math.cos(al1)

    def input_phase(x, path):
        """Input rotation that closes mesh 1 of ``path`` with the carriage at ``x``, and its x derivative."""
        side, _, c2x, c2y, phi2_seen, tooth_in = path
        dx = c2x - (x + i1x)
        dy = c2y - i1y
        c_sq = dx * dx + dy * dy
        c = np.sqrt(c_sq)
        beta = np.arctan2(dy, dx)
        a_w = working_pressure_angle_at(k_cos, c)  # NaN inside the base circles
        tan_w = np.tan(a_w)
        b_mesh1 = t1 + backlash_change(cs1, a_w, inv_al1)
        phi1 = mate_rotation(beta, phi2_seen, z1, z2, b_mesh1 / r1, side) - tooth_in
        dphi1 = ((1 + ratio1) * dy - side * cs1 * tan_w * dx / r1) / c_sq
        return phi1, dphi1

    pitch1 = 2 * np.pi / z1
    x = np.array(np.broadcast_to(synthesis.input_x if x_start is None else x_start, n), dtype=float)
    converged = np.zeros(n, dtype=bool)
    phi1 = np.full(n, np.nan)
    it = 0
    for it in range(1, max_iter + 1):
        pa, da = input_phase(x, paths[0])
        pb, db = input_phase(x, paths[1])
        with np.errstate(invalid="ignore", divide="ignore"):
            step = wrap(pa - pb, pitch1) / (da - db)
        x = x - step
        phi1 = pa - da * step  # path A's input rotation at the new x, to first order in the (tiny) last step
        converged = np.abs(step) <= tol
        if converged.all() or not np.isfinite(x).any():
            break
    converged &= np.isfinite(x)
    bad = int(np.count_nonzero(~converged))
    msg = "converged" if bad == 0 else (
        f"{bad} of {converged.size} samples did not close the loop in {max_iter} Newton steps "
        "(a centre distance inside the base circles, or errors too large for the teeth to mesh)")
    rho_a, rho_b = (np.broadcast_to(p[1], n) for p in paths)
    return LoopSolution(success=bad == 0, message=msg, carriage_x=x, input_rotation=wrap(phi1, pitch1),
                        cluster_rotation_a=wrap(rho_a, 2 * np.pi), cluster_rotation_b=wrap(rho_b, 2 * np.pi),
                        output_rotation=phi4, converged=converged, iterations=it)


# --- placement for CAD --------------------------------------------------------------------------

@dataclass(frozen=True)
class PlacedGear:
    """One gear of the assembly: ``centre`` (mm, output frame) and ``rotation`` (rad, module docstring)."""

    name: str
    role: str
    centre: tuple[float, float]
    rotation: float


@dataclass(frozen=True)
class Placement:
    """Result of :func:`place_gears`.

    ``backlash_mesh1``/``backlash_mesh2`` are the circumferential backlash the gears were taken
    to have at the design centre distances; ``carriage_x`` is where the preload carriage then
    sits; ``loaded_flank_gap`` the clearance left on the working flanks (circumferential, mm).
    """

    success: bool
    message: str
    gears: tuple[PlacedGear, ...]
    carriage_x: float
    backlash_mesh1: float
    backlash_mesh2: float
    loaded_flank_gap: float

    def check(self) -> "Placement":
        if not self.success:
            raise GeometryError("gear placement", self.message)
        return self

    def gear(self, name: str) -> PlacedGear:
        for g in self.gears:
            if g.name == name:
                return g
        raise KeyError(name)


def place_gears(synthesis: CentreSynthesis, backlash_mesh1: float | None = None, backlash_mesh2: float | None = None,
                loaded_flank_gap: float = 0.0) -> Placement:
    """Centres and rotations of every gear for the CAD layer (mm, rad), teeth in mesh.

    ``backlash_mesh1``/``backlash_mesh2``: the circumferential backlash the modelled gears have
    at the design centre distances (default: the design maximum, i.e. the synthesised
    position). The carriage is re-solved exactly, so the working flank of every mesh touches;
    ``loaded_flank_gap`` > 0 leaves that much clearance (circumferential, mm) on the working
    flanks instead (the other flanks keep B - gap), e.g. to keep CAD solids apart.

    Gears, in order: output, cluster_small_a, cluster_large_a, cluster_small_b,
    cluster_large_b, input. Cluster A is at +y; each cluster's two gears share one rotation.
    """
    synthesis.check()
    inp = synthesis.inputs
    b1 = inp.circumferential_backlash_max_mesh1 if backlash_mesh1 is None else float(backlash_mesh1)
    b2 = inp.circumferential_backlash_max_mesh2 if backlash_mesh2 is None else float(backlash_mesh2)
    g = float(loaded_flank_gap)
    fail = dict(gears=(), carriage_x=math.nan, backlash_mesh1=b1, backlash_mesh2=b2, loaded_flank_gap=g)
    if not (math.isfinite(g) and g >= 0):
        return Placement(False, f"loaded_flank_gap must be >= 0, got {g!r}", **fail)
    if g > min(b1, b2):
        return Placement(False, f"loaded_flank_gap {g:.6g} mm exceeds a mesh's backlash ({b1:.6g}, {b2:.6g} mm)", **fail)
    sol = solve_loop(synthesis, b1 - 2 * g, b2 - 2 * g)
    if not sol.success:
        return Placement(False, sol.message, **fail)
    x = float(sol.carriage_x[0])
    rho_a, rho_b = float(sol.cluster_rotation_a[0]), float(sol.cluster_rotation_b[0])
    x2, y2 = synthesis.x2, synthesis.y2
    gears = (
        PlacedGear("output", "output", (0.0, 0.0), sol.output_rotation),
        PlacedGear("cluster_small_a", "cluster_small", (x2, y2), rho_a),
        PlacedGear("cluster_large_a", "cluster_large", (x2, y2), rho_a),
        PlacedGear("cluster_small_b", "cluster_small", (x2, -y2), rho_b),
        PlacedGear("cluster_large_b", "cluster_large", (x2, -y2), rho_b),
        PlacedGear("input", "input", (x, 0.0), float(sol.input_rotation[0])),
    )
    return Placement(True, "placed", gears, x, b1, b2, g)


__all__ = ["cluster_angle", "input_rotation", "appendix_carriage_travel", "round_increments", "operating_pressure_angle",
           "backlash_from_thickness_deficit", "thickness_deficit_for_backlash", "modelled_backlash", "mate_rotation", "wrap", "CentreSynthesis",
           "synthesize_centres", "LoopSolution", "solve_loop", "PlacedGear", "Placement", "place_gears",
           "OFFSET_GEARS", "TOOTH_CONTACTS", "PLACED_GEARS"]
