"""Tooth stiffness of a cylindrical gear pair per ISO 6336-1:2019, method B (pure math).

The standard's single stiffness ``c'`` (the largest stiffness of one tooth pair) and mesh
stiffness ``c_gamma`` (the mean of all pairs in contact), both per unit face width, N/(mm·µm):
the load along the transverse line of action over 1 mm of face that deflects the teeth 1 µm.
So ``c_gamma_alpha b`` is a linear stiffness along the line of action, ``1e3 c_gamma_alpha b``
in N/mm, the quantity Eq. 1 of the paper (``E w / 11``) estimates.

The chain (symbols of the standard):

* virtual numbers of teeth ``z_n = z / (cos^2(beta_b) cos(beta))``;
* flexibility of a tooth pair, the standard's regression on ``z_n`` and ``x`` (pinion 1, wheel 2)
  ``q' = C1 + C2/z_n1 + C3/z_n2 + C4 x1 + C5 x1/z_n1 + C6 x2 + C7 x2/z_n2 + C8 x1^2 + C9 x2^2``
  (mm·µm/N), and ``c'_th = 1/q'``;
* ``c' = c'_th C_M C_R C_B cos(beta)`` with ``C_M = 0.8``, the gear blank factor
  ``C_R = 1 + ln(b_s/b) / (5 exp(s_R / (5 m_n)))`` (1 for solid discs), the basic rack factor
  ``C_B = (C_B1 + C_B2) / 2``, ``C_Bi = (1 + 0.5 (1.2 - h_fPi/m_n)) (1 - 0.02 (20 deg - alpha_Pn))``;
  for a specific load ``F_t K_A / b`` below 100 N/mm (only when one is given) times
  ``(F_t K_A / b / 100)^0.25``; for other materials than steel times ``E / E_st``,
  ``E = 2 E1 E2 / (E1 + E2)``, ``E_st = 206 000 N/mm²``;
* ``c_gamma_alpha = c' (0.75 eps_alpha + 0.25)``, ``c_gamma_beta = 0.85 c_gamma_alpha``.

Outside the range the regression was fitted on (x1 >= x2, -0.5 <= x1 + x2 <= 2) or the mesh
stiffness formula is stated for (eps_alpha >= 1.2), and where C_R's inputs are clamped to its
range, the standard still gives a value: it is computed and the result carries a warning. Where a
formula cannot be evaluated (no contact, q' <= 0, non-positive widths, moduli or loads) a
:class:`~geargen.errors.DesignError` names the input.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from geargen.errors import DesignError

METHOD = "ISO 6336-1:2019 method B"

#: the regression coefficients C1..C9 of q' (ISO 6336-1, method B), mm·µm/N
Q_COEFFICIENTS = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
#: theoretical correction factor C_M (difference between measured and computed stiffness)
CORRECTION_FACTOR = 0.8
#: E_st, the modulus of steel the standard's values are for, N/mm²
STEEL_MODULUS = 206000.0
#: specific load F_t K_A / b (N/mm) at and above which c' needs no load correction
FULL_LOAD = 100.0
#: the basic rack the C_B formula is referred to: dedendum 1.2 m_n, pressure angle 20 deg
RACK_DEDENDUM_REFERENCE = 1.2
RACK_PRESSURE_ANGLE_REFERENCE_DEG = 20.0
#: c_gamma_alpha = c' (0.75 eps_alpha + 0.25) is stated for eps_alpha at or above this
CONTACT_RATIO_MINIMUM = 1.2
#: C_R's range: 0.2 <= b_s/b <= 1.2 and s_R/m_n >= 1 (values outside are clamped)
WEB_RATIO_RANGE = (0.2, 1.2)
RIM_RATIO_MINIMUM = 1.0
#: q' was fitted for x1 >= x2 and x1 + x2 in this range
SHIFT_SUM_RANGE = (-0.5, 2.0)
#: c_gamma_beta over c_gamma_alpha
HELIX_MESH_RATIO = 0.85


def virtual_teeth(teeth: float, helix_angle: float, base_helix_angle: float) -> float:
    """``z_n = z / (cos^2(beta_b) cos(beta))`` (angles in rad)."""
    return teeth / (math.cos(base_helix_angle) ** 2 * math.cos(helix_angle))


def tooth_pair_flexibility(zn1: float, zn2: float, x1: float, x2: float) -> float:
    """The standard's q' (mm·µm/N) of pinion 1 and wheel 2 (virtual teeth, normal profile shifts)."""
    c1, c2, c3, c4, c5, c6, c7, c8, c9 = Q_COEFFICIENTS
    return (c1 + c2 / zn1 + c3 / zn2 + c4 * x1 + c5 * x1 / zn1 + c6 * x2 + c7 * x2 / zn2
            + c8 * x1 * x1 + c9 * x2 * x2)


def basic_rack_factor(dedendum_coefficient: float, rack_pressure_angle: float) -> float:
    """C_B of one gear: ``(1 + 0.5 (1.2 - h_fP/m_n)) (1 - 0.02 (20 deg - alpha_Pn))`` (alpha in rad)."""
    return ((1.0 + 0.5 * (RACK_DEDENDUM_REFERENCE - dedendum_coefficient))
            * (1.0 - 0.02 * (RACK_PRESSURE_ANGLE_REFERENCE_DEG - math.degrees(rack_pressure_angle))))


def gear_blank_factor(face_width: float | None, normal_module: float, web_thickness: float | None = None,
                      rim_thickness: float | None = None) -> tuple[float, tuple[str, ...]]:
    """C_R and the warnings of clamping its inputs: 1 for a solid disc (no web given), else
    ``1 + ln(b_s/b) / (5 exp(s_R / (5 m_n)))`` with ``b_s/b`` clamped to [0.2, 1.2] and
    ``s_R/m_n`` to >= 1, as the standard does outside its range."""
    if web_thickness is None and rim_thickness is None:
        return 1.0, ()
    if web_thickness is None or rim_thickness is None:
        missing = "web_thickness" if web_thickness is None else "rim_thickness"
        raise DesignError(missing, "missing: C_R needs both the web and the rim thickness",
                          "both, or neither (a solid disc)")
    if face_width is None:
        raise DesignError("face_width", "missing: C_R of a webbed blank needs the face width", "> 0 mm")
    for name, value in (("web_thickness", web_thickness), ("rim_thickness", rim_thickness)):
        if not (math.isfinite(value) and value > 0):
            raise DesignError(name, f"{value!r} mm is out of range", "> 0 mm")
    warnings = []
    web = web_thickness / face_width
    lo, hi = WEB_RATIO_RANGE
    if not lo <= web <= hi:
        clamped = min(max(web, lo), hi)
        warnings.append(f"C_R: web over face width b_s/b = {web:.4g} is outside [{lo:g}, {hi:g}]; "
                        f"taken as {clamped:g}, as ISO 6336-1 does")
        web = clamped
    rim = rim_thickness / normal_module
    if rim < RIM_RATIO_MINIMUM:
        warnings.append(f"C_R: rim thickness over module s_R/m_n = {rim:.4g} is below {RIM_RATIO_MINIMUM:g}; "
                        f"taken as {RIM_RATIO_MINIMUM:g}, as ISO 6336-1 does")
        rim = RIM_RATIO_MINIMUM
    return 1.0 + math.log(web) / (5.0 * math.exp(rim / 5.0)), tuple(warnings)


def load_factor(specific_load: float | None) -> float:
    """``(F_t K_A / b / 100)^0.25`` below 100 N/mm, else 1; 1 when no load is given."""
    if specific_load is None:
        return 1.0
    if not (math.isfinite(specific_load) and specific_load > 0):
        raise DesignError("specific_load", f"{specific_load!r} N/mm is out of range", "> 0 N/mm")
    return (specific_load / FULL_LOAD) ** 0.25 if specific_load < FULL_LOAD else 1.0


def material_factor(elastic_modulus_1: float, elastic_modulus_2: float) -> float:
    """``E / E_st`` with ``E = 2 E1 E2 / (E1 + E2)`` (moduli in N/mm²)."""
    for i, e in enumerate((elastic_modulus_1, elastic_modulus_2), start=1):
        if not (math.isfinite(e) and e > 0):
            raise DesignError("elastic_modulus", f"gear {i}: {e!r} MPa is out of range", "> 0 MPa")
    return 2.0 * elastic_modulus_1 * elastic_modulus_2 / (elastic_modulus_1 + elastic_modulus_2) / STEEL_MODULUS


@dataclass(frozen=True)
class Iso6336Stiffness:
    """c', c_gamma and every intermediate of a pair; per unit face width, N/(mm·µm).

    Pairs are (pinion, wheel) in the standard's numbering: ``pinion`` says which gear of the
    caller's (1 or 2) is the pinion (the one with fewer teeth; gear 1 on a tie).
    """

    pinion: int
    teeth: tuple[int, int]
    virtual_teeth: tuple[float, float]
    profile_shift: tuple[float, float]
    helix_angle: float  # rad
    base_helix_angle: float  # rad
    flexibility: float  # q', mm·µm/N
    theoretical_single_stiffness: float  # c'_th
    correction_factor: float  # C_M
    gear_blank_factor: float  # C_R
    basic_rack_factors: tuple[float, float]  # C_B1, C_B2
    material_factor: float  # E / E_st
    elastic_modulus: float  # E of the pair, N/mm²
    specific_load: float | None  # F_t K_A / b, N/mm; None: no load given (no correction)
    load_factor: float
    transverse_contact_ratio: float
    face_width: float | None  # mm; None: per unit face width only
    warnings: tuple[str, ...] = field(default_factory=tuple)

    @property
    def basic_rack_factor(self) -> float:
        """C_B = (C_B1 + C_B2) / 2."""
        return 0.5 * (self.basic_rack_factors[0] + self.basic_rack_factors[1])

    @property
    def single_stiffness(self) -> float:
        """c' = c'_th C_M C_R C_B cos(beta), with the load and material corrections."""
        return (self.theoretical_single_stiffness * self.correction_factor * self.gear_blank_factor
                * self.basic_rack_factor * math.cos(self.helix_angle) * self.load_factor * self.material_factor)

    @property
    def mesh_stiffness(self) -> float:
        """c_gamma_alpha = c' (0.75 eps_alpha + 0.25), N/(mm·µm)."""
        return self.single_stiffness * (0.75 * self.transverse_contact_ratio + 0.25)

    @property
    def mesh_stiffness_beta(self) -> float:
        """c_gamma_beta = 0.85 c_gamma_alpha, N/(mm·µm)."""
        return HELIX_MESH_RATIO * self.mesh_stiffness

    @property
    def mesh_stiffness_whole(self) -> float | None:
        """c_gamma_alpha b, N/µm along the transverse line of action; None without a face width."""
        return None if self.face_width is None else self.mesh_stiffness * self.face_width

    @property
    def line_of_action_stiffness(self) -> float:
        """c_gamma_alpha b in the stiffness model's unit, N/mm (needs the face width)."""
        if self.face_width is None:
            raise DesignError("face_width", "missing: the whole mesh's stiffness needs the face width", "> 0 mm")
        return self.mesh_stiffness * self.face_width * 1e3

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the contract's keys first, then every intermediate (units in the key names)."""
        whole = self.mesh_stiffness_whole
        return {
            "single_stiffness_N_per_mm_um": self.single_stiffness,
            "mesh_stiffness_N_per_mm_um": self.mesh_stiffness,
            "method": METHOD,
            "mesh_stiffness_beta_N_per_mm_um": self.mesh_stiffness_beta,
            "mesh_stiffness_whole_N_per_um": whole,
            "face_width_mm": self.face_width,
            "theoretical_single_stiffness_N_per_mm_um": self.theoretical_single_stiffness,
            "flexibility_q_prime_mm_um_per_N": self.flexibility,
            "pinion": f"gear {self.pinion}",
            "teeth_pinion_wheel": list(self.teeth),
            "virtual_teeth_pinion_wheel": list(self.virtual_teeth),
            "profile_shift_pinion_wheel": list(self.profile_shift),
            "helix_angle_deg": math.degrees(self.helix_angle),
            "base_helix_angle_deg": math.degrees(self.base_helix_angle),
            "correction_factor_C_M": self.correction_factor,
            "gear_blank_factor_C_R": self.gear_blank_factor,
            "basic_rack_factor_C_B": self.basic_rack_factor,
            "basic_rack_factors_C_B_pinion_wheel": list(self.basic_rack_factors),
            "helix_factor_cos_beta": math.cos(self.helix_angle),
            "material_factor_E_over_E_st": self.material_factor,
            "elastic_modulus_MPa": self.elastic_modulus,
            "steel_modulus_E_st_MPa": STEEL_MODULUS,
            "specific_load_N_per_mm": self.specific_load,
            "load_factor": self.load_factor,
            "load_correction": ("none: no load given (c' as for F_t K_A / b >= 100 N/mm)" if self.specific_load is None
                                else "(F_t K_A / b / 100)^0.25" if self.specific_load < FULL_LOAD
                                else "none: F_t K_A / b >= 100 N/mm"),
            "transverse_contact_ratio": self.transverse_contact_ratio,
            "warnings": list(self.warnings),
        }


def iso6336_stiffness(teeth: tuple[int, int], profile_shift: tuple[float, float], normal_module: float,
                      normal_pressure_angle: float, helix_angle: float, transverse_contact_ratio: float, *,
                      dedendum_coefficients: tuple[float, float] = (1.25, 1.25),
                      rack_pressure_angle: float | None = None,
                      elastic_moduli: tuple[float, float] = (STEEL_MODULUS, STEEL_MODULUS),
                      face_width: float | None = None, web_thickness: float | None = None,
                      rim_thickness: float | None = None, specific_load: float | None = None) -> Iso6336Stiffness:
    """c' and c_gamma of an external pair (gears 1 and 2 in the caller's order; angles in rad,
    lengths in mm, moduli N/mm², ``specific_load`` F_t K_A / b in N/mm).

    ``dedendum_coefficients`` are each gear's basic rack dedendum h_fP/m_n, ``rack_pressure_angle``
    the basic rack's (default the normal pressure angle). ``web_thickness`` and ``rim_thickness``
    (b_s and s_R) describe a webbed blank; without them the blanks are solid discs (C_R = 1).
    """
    z1, z2 = teeth
    for i, z in enumerate(teeth, start=1):
        if isinstance(z, bool) or not isinstance(z, int) or z < 1:
            raise DesignError("teeth", f"gear {i}: {z!r} is out of range", "a whole number >= 1")
    if not (math.isfinite(normal_module) and normal_module > 0):
        raise DesignError("module", f"{normal_module!r} mm is out of range", "> 0 mm")
    if not 0 <= helix_angle < math.pi / 2:
        raise DesignError("helix_angle", f"{math.degrees(helix_angle)!r} deg is out of range", "[0, 90) deg")
    if not (math.isfinite(transverse_contact_ratio) and transverse_contact_ratio > 0):
        raise DesignError("transverse_contact_ratio", f"{transverse_contact_ratio!r}: the teeth do not meet",
                          "> 0 (a mesh with a path of contact)")
    if face_width is not None and not (math.isfinite(face_width) and face_width > 0):
        raise DesignError("face_width", f"{face_width!r} mm is out of range", "> 0 mm")
    pinion = 1 if z1 <= z2 else 2
    order = (0, 1) if pinion == 1 else (1, 0)
    z = tuple(teeth[i] for i in order)
    x = tuple(float(profile_shift[i]) for i in order)
    h_fp = tuple(float(dedendum_coefficients[i]) for i in order)
    alpha_p = normal_pressure_angle if rack_pressure_angle is None else rack_pressure_angle
    beta_b = math.asin(math.sin(helix_angle) * math.cos(normal_pressure_angle))
    zn = tuple(virtual_teeth(t, helix_angle, beta_b) for t in z)
    q = tooth_pair_flexibility(zn[0], zn[1], x[0], x[1])
    if not (math.isfinite(q) and q > 0):
        raise DesignError("profile_shift", f"{x[0]:.6g}, {x[1]:.6g} (pinion, wheel) give a tooth-pair flexibility "
                          f"q' = {q:.4g} mm·µm/N: the standard's regression has no stiffness there",
                          f"x1 >= x2, {SHIFT_SUM_RANGE[0]:g} <= x1 + x2 <= {SHIFT_SUM_RANGE[1]:g}")
    warnings: list[str] = []
    if x[0] < x[1]:
        warnings.append(f"q' was fitted for a pinion shift at least the wheel's (x1 >= x2); here x1 = {x[0]:.6g} "
                        f"< x2 = {x[1]:.6g}: the value is the standard's, outside its fitted range")
    lo, hi = SHIFT_SUM_RANGE
    if not lo <= x[0] + x[1] <= hi:
        warnings.append(f"q' was fitted for {lo:g} <= x1 + x2 <= {hi:g}; here x1 + x2 = {x[0] + x[1]:.6g}: "
                        "the value is the standard's, outside its fitted range")
    if transverse_contact_ratio < CONTACT_RATIO_MINIMUM:
        warnings.append(f"c_gamma_alpha = c' (0.75 eps_alpha + 0.25) is stated for eps_alpha >= "
                        f"{CONTACT_RATIO_MINIMUM:g}; here eps_alpha = {transverse_contact_ratio:.4f} (the standard "
                        "allows spur gears below it up to 10 % less)")
    c_r, blank_warnings = gear_blank_factor(face_width, normal_module, web_thickness, rim_thickness)
    warnings += blank_warnings
    e1, e2 = elastic_moduli
    xi = material_factor(e1, e2)
    return Iso6336Stiffness(
        pinion=pinion, teeth=(z[0], z[1]), virtual_teeth=(zn[0], zn[1]), profile_shift=(x[0], x[1]),
        helix_angle=helix_angle, base_helix_angle=beta_b, flexibility=q, theoretical_single_stiffness=1.0 / q,
        correction_factor=CORRECTION_FACTOR, gear_blank_factor=c_r,
        basic_rack_factors=(basic_rack_factor(h_fp[0], alpha_p), basic_rack_factor(h_fp[1], alpha_p)),
        material_factor=xi, elastic_modulus=xi * STEEL_MODULUS, specific_load=specific_load,
        load_factor=load_factor(specific_load), transverse_contact_ratio=float(transverse_contact_ratio),
        face_width=face_width, warnings=tuple(warnings))


def pair_stiffness(pair, centre_distance: float | None = None, face_width: float | None = None,
                   elastic_modulus: float = STEEL_MODULUS, specific_load: float | None = None,
                   web_thickness: float | None = None, rim_thickness: float | None = None) -> Iso6336Stiffness:
    """:func:`iso6336_stiffness` of a :class:`geargen.core.geometry.GearPair`: teeth, shifts, module,
    pressure and helix angle, each gear's dedendum coefficient (its basic rack) from the gears;
    eps_alpha from :func:`geargen.core.geometry.mesh_geometry` at ``centre_distance`` (default the
    working centre distance of the shifts), tips as built. One ``elastic_modulus`` for both gears."""
    from geargen.core.geometry import mesh_geometry

    g1, g2 = pair.gear1, pair.gear2
    mesh = mesh_geometry(pair, centre_distance, "spec", face_width=face_width)
    return iso6336_stiffness((g1.teeth, g2.teeth), (g1.profile_shift, g2.profile_shift), g1.module,
                             g1.pressure_angle, g1.helix_angle, mesh.transverse_contact_ratio,
                             dedendum_coefficients=(g1.dedendum_coefficient, g2.dedendum_coefficient),
                             elastic_moduli=(elastic_modulus, elastic_modulus), face_width=face_width,
                             web_thickness=web_thickness, rim_thickness=rim_thickness, specific_load=specific_load)


__all__ = ["METHOD", "Q_COEFFICIENTS", "CORRECTION_FACTOR", "STEEL_MODULUS", "FULL_LOAD", "Iso6336Stiffness",
           "virtual_teeth", "tooth_pair_flexibility", "basic_rack_factor", "gear_blank_factor", "load_factor",
           "material_factor", "iso6336_stiffness", "pair_stiffness"]
