"""Tooth-thickness allowances and the inspection limits they give (pure math; mm and rad).

A gear's allowance is its normal tooth-thickness deviation at the reference cylinder from the
zero-backlash tooth (the tooth of its profile shift, unthinned): the upper deviation E_sns
(thickest tooth made) and the lower E_sni (thinnest), both <= 0, E_sns >= E_sni. A tooth made
at deviation E_sn is the :class:`~geargen.design.gear.GearSpec` with circumferential thinning
-E_sn / cos(beta) (:func:`at_deviation`), so every limit below comes from the one formula of
its nominal value in :mod:`geargen.core.geometry` with the thinning set to each deviation:

* span W_k: :func:`geargen.core.geometry.span_length`, which for a deviation reads
  W_k = m_n cos(alpha_n) [(k - 1/2) pi + z inv(alpha_t)] + 2 x m_n sin(alpha_n) + E_sn cos(alpha_n);
* dimension over pins/balls: :func:`geargen.core.geometry.over_pins_dimension`;
* backlash of a mesh: :func:`geargen.core.geometry.backlash_at_centre_distance`
  (``circumferential_reference``: transverse arc at the reference circle of gear 1, the kind the
  design files state their ranges in).

Limits are [smallest, largest]: the thinnest tooth (lower deviation) gives the smallest span
and over-pins dimension, the thickest (upper deviation) the largest.

The model's gear (the one the solids, STEP, STL, DXF and gear data show) is made at one point of
its allowance (:func:`made_at`; the design names it: ``[layout] model_tooth_thickness``): the
middle of the tolerance, the upper deviation (maximum material, thickest) or the lower (minimum
material, thinnest), so every exported gear measures inside its own drawing's limits.

Chosen from backlash (:func:`allowances_for_backlash`), by the centre-distance-tolerance route:
a mesh with the design range [B_min, B_max] at its operating centre distance a, the centre
distance held to +-f_a. Backlash grows one for one with the summed circumferential thinning S
of the two gears (B(S, a) = B(0, a) + S), so the thickest teeth at the smallest centre
distance give B_min and the thinnest at the largest give B_max:

    S_thickest = B_min - B(0, a - f_a),      S_thinnest = B_max - B(0, a + f_a),

split equally between the two gears (circumferential, as the designs split ``thinning_*``), or,
when one gear's allowance is already fixed (entered, or set by another mesh), the mate takes the
rest; normal deviations E_sn = -S_gear cos(beta). The range cannot be met when
S_thinnest <= S_thickest (the centre-distance tolerance, 2 f_a times about 2 tan(alpha_wt) of
backlash, eats it) or when S_thickest < 0 (the centre distance alone gives more than B_min with
unthinned teeth; a positive deviation is not an allowance).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from geargen.core.geometry import (GearPair, backlash_at_centre_distance, over_pins_measurement,
                                   span_measurement)
from geargen.design.gear import GearSpec, with_changes
from geargen.errors import DesignError

__all__ = ["ThicknessAllowance", "at_deviation", "thickest", "thinnest", "span_limits", "over_pins_limits",
           "mesh_backlash_range", "allowances_for_backlash", "BacklashRoute", "ENTERED", "ROUTE_METHOD",
           "deviation_at", "made_at", "series_allowance"]

#: method string of an allowance typed in (design keys or ``--thickness-allowance``)
ENTERED = "entered"

#: method string of the centre-distance-tolerance route (the tolerance is appended)
ROUTE_METHOD = ("centre-distance-tolerance route: thickest teeth at a - f_a give the design's minimum "
                "circumferential backlash, thinnest at a + f_a its maximum; summed thinning split equally "
                "within the mesh (a gear already fixed by another mesh or entered keeps its allowance, the mate "
                "takes the rest)")


@dataclass(frozen=True)
class ThicknessAllowance:
    """Normal tooth-thickness deviations at the reference cylinder (mm, <= 0, ``upper >= lower``).

    ``upper`` is E_sns (thickest tooth made), ``lower`` E_sni (thinnest). ``method`` says where
    they come from. ``field`` names the key (or option) errors report, and ``scale`` the unit
    (mm per unit) they report in.
    """

    upper: float
    lower: float
    method: str = ENTERED
    field: str = "thickness_allowance"
    scale: float = 1e-3  # errors in um unless told

    def __post_init__(self):
        unit = {1e-3: "um", 1.0: "mm", 25.4: "in"}.get(self.scale, "mm")
        for name, v in (("upper", self.upper), ("lower", self.lower)):
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v <= 0):
                raise DesignError(self.field, f"{name} deviation {v / self.scale:.6g} {unit} is out of range "
                                  "(a deviation is a thinning of the zero-backlash tooth)", f"<= 0 {unit}")
        if self.upper < self.lower:
            raise DesignError(self.field, f"upper deviation {self.upper / self.scale:.6g} {unit} is below the lower "
                              f"{self.lower / self.scale:.6g} {unit}", "upper >= lower, both <= 0")

    @property
    def upper_um(self) -> float:
        return self.upper * 1e3

    @property
    def lower_um(self) -> float:
        return self.lower * 1e3


def at_deviation(spec: GearSpec, deviation: float, field: str = "thickness_allowance") -> GearSpec:
    """``spec`` made at the normal thickness deviation ``deviation`` (mm, <= 0): circumferential
    thinning -E_sn / cos(beta) in place of the spec's own. A deviation beyond GearSpec's largest
    thinning (a quarter of the transverse pitch) is a :class:`DesignError` naming ``field``."""
    thinning = -deviation / math.cos(spec.helix_angle)
    most = spec.transverse_pitch / 4
    if thinning > most:
        raise DesignError(field, f"{spec.name}: deviation {deviation * 1e3:.6g} um thins the tooth by more than a "
                          "quarter of the circular pitch", f">= {-most * math.cos(spec.helix_angle) * 1e3:.6g} um")
    return with_changes(spec, thinning=max(thinning, 0.0))


def thickest(spec: GearSpec, allowance: ThicknessAllowance) -> GearSpec:
    """The gear at its upper deviation."""
    return at_deviation(spec, allowance.upper, allowance.field)


def thinnest(spec: GearSpec, allowance: ThicknessAllowance) -> GearSpec:
    """The gear at its lower deviation."""
    return at_deviation(spec, allowance.lower, allowance.field)


def deviation_at(allowance: ThicknessAllowance, upper_weight: float) -> float:
    """The normal thickness deviation (mm) ``w upper + (1 - w) lower`` of ``allowance``, ``w`` =
    ``upper_weight`` in [0, 1]: 1 the thickest tooth made (maximum material), 0 the thinnest."""
    if not 0.0 <= upper_weight <= 1.0:
        raise ValueError(f"upper_weight {upper_weight!r} is not in [0, 1]")
    return upper_weight * allowance.upper + (1 - upper_weight) * allowance.lower


def made_at(spec: GearSpec, allowance: ThicknessAllowance, upper_weight: float) -> GearSpec:
    """``spec`` made at :func:`deviation_at` of its ``allowance``."""
    return at_deviation(spec, deviation_at(allowance, upper_weight), allowance.field)


def span_limits(spec: GearSpec, allowance: ThicknessAllowance, teeth_spanned: int) -> tuple[float, float]:
    """[smallest, largest] span W_k over ``teeth_spanned`` teeth (mm, normal to the teeth): the
    thinnest and the thickest tooth, each checked by :func:`~geargen.core.geometry.span_measurement`
    (anvils on the involute, face wide enough), which raises :class:`GeometryError` otherwise."""
    return (span_measurement(thinnest(spec, allowance), teeth_spanned).span,
            span_measurement(thickest(spec, allowance), teeth_spanned).span)


def over_pins_limits(spec: GearSpec, allowance: ThicknessAllowance, pin_diameter: float) -> tuple[float, float]:
    """[smallest, largest] dimension over two pins (spur) or balls (helical) of ``pin_diameter``
    (mm): the thinnest and the thickest tooth, each checked by
    :func:`~geargen.core.geometry.over_pins_measurement` (contact on the involute)."""
    return (over_pins_measurement(thinnest(spec, allowance), pin_diameter).dimension,
            over_pins_measurement(thickest(spec, allowance), pin_diameter).dimension)


def mesh_backlash_range(gear1: GearSpec, allowance1: ThicknessAllowance, gear2: GearSpec,
                        allowance2: ThicknessAllowance, centre_distance: float,
                        centre_distance_tolerance: float = 0.0) -> tuple[float, float]:
    """[min, max] circumferential backlash (mm, transverse, at gear 1's reference circle) of a
    mesh made within the allowances at ``centre_distance`` +- ``centre_distance_tolerance``: both
    gears at their upper deviations at a - f_a, both at their lower ones at a + f_a."""
    a, f = float(centre_distance), float(centre_distance_tolerance)
    lo = backlash_at_centre_distance(GearPair(thickest(gear1, allowance1), thickest(gear2, allowance2)), a - f)
    hi = backlash_at_centre_distance(GearPair(thinnest(gear1, allowance1), thinnest(gear2, allowance2)), a + f)
    return float(lo.circumferential_reference), float(hi.circumferential_reference)


@dataclass(frozen=True)
class BacklashRoute:
    """What the route asks of one mesh: the design range and where it is stated (mm).

    ``field_min``/``field_max`` name the design keys of the range, ``field_tolerance`` the key
    of the centre-distance tolerance, for errors. ``scale``/``unit``: the design's length unit.
    """

    backlash_min: float
    backlash_max: float
    centre_distance: float
    centre_distance_tolerance: float = 0.0
    field_min: str = "circumferential_backlash_min"
    field_max: str = "circumferential_backlash_max"
    field_tolerance: str = "centre_distance_tolerance"
    unit: str = "mm"
    scale: float = 1.0


def allowances_for_backlash(gear1: GearSpec, gear2: GearSpec, route: BacklashRoute,
                            fixed1: ThicknessAllowance | None = None,
                            fixed2: ThicknessAllowance | None = None) -> tuple[ThicknessAllowance, ThicknessAllowance]:
    """The two gears' allowances that give the mesh exactly ``route``'s range at a -+ f_a (see the
    module docstring for the formula). ``fixed1``/``fixed2``: an allowance already decided for a
    gear (it is kept; the mate takes the rest of the mesh's thinning). Refuses, with a
    :class:`DesignError` naming the design key, a range the tolerance or the centre distance
    leaves no room for, and a split that would ask a gear for a positive deviation."""
    u, k = route.unit, route.scale
    f = route.centre_distance_tolerance
    if not (math.isfinite(f) and f >= 0):
        raise DesignError(route.field_tolerance, f"{f / k:.6g} {u} is out of range", f">= 0 {u}")
    a = route.centre_distance
    bare = GearPair(with_changes(gear1, thinning=0.0), with_changes(gear2, thinning=0.0))
    if not a - f > gear1.base_radius + gear2.base_radius:
        raise DesignError(route.field_tolerance, f"{f / k:.6g} {u} brings the centres inside the base circles",
                          f"< {(a - gear1.base_radius - gear2.base_radius) / k:.6g} {u}")
    b0 = backlash_at_centre_distance(bare, [a - f, a + f]).circumferential_reference
    s_thick = route.backlash_min - float(b0[0])  # summed circumferential thinning, thickest teeth
    s_thin = route.backlash_max - float(b0[1])  # ... thinnest teeth
    if s_thin <= s_thick:
        eaten = float(b0[1] - b0[0])
        raise DesignError(route.field_max, f"the range {route.backlash_min / k:.6g} to {route.backlash_max / k:.6g} "
                          f"{u} leaves no tooth-thickness tolerance: the centre-distance tolerance +-{f / k:.6g} {u} "
                          f"alone spreads the backlash by {eaten / k:.6g} {u}",
                          f"> {(route.backlash_min + eaten) / k:.6g} {u}, or a smaller {route.field_tolerance}")
    if s_thick < 0:
        raise DesignError(route.field_min, f"{route.backlash_min / k:.6g} {u} is less than the unthinned teeth give at "
                          f"the smallest centre distance {(a - f) / k:.6g} {u} ({float(b0[0]) / k:.6g} {u})",
                          f">= {float(b0[0]) / k:.6g} {u}")

    def circ(spec, dev):  # normal deviation -> circumferential thinning
        return -dev / math.cos(spec.helix_angle)

    if fixed1 is not None and fixed2 is not None:
        return fixed1, fixed2
    method = f"{ROUTE_METHOD}; f_a = {f / k:.6g} {u}" + ("" if f > 0 else " (none given)")
    if fixed1 is None and fixed2 is None:
        t1 = (s_thick / 2, s_thin / 2)
        t2 = t1
    elif fixed1 is not None:
        t1 = (circ(gear1, fixed1.upper), circ(gear1, fixed1.lower))
        t2 = (s_thick - t1[0], s_thin - t1[1])
    else:
        t2 = (circ(gear2, fixed2.upper), circ(gear2, fixed2.lower))
        t1 = (s_thick - t2[0], s_thin - t2[1])
    out = []
    for spec, (thick, thin), fixed in ((gear1, t1, fixed1), (gear2, t2, fixed2)):
        if fixed is not None:
            out.append(fixed)
            continue
        if thick < -1e-12 or thin < thick - 1e-12:
            raise DesignError(route.field_min, f"{spec.name}: its mate's allowance leaves this gear "
                              f"{thick / k:.6g} to {thin / k:.6g} {u} of thinning, which is no allowance",
                              "a range that covers the mate's allowance")
        c = math.cos(spec.helix_angle)
        out.append(ThicknessAllowance(-max(thick, 0.0) * c, -max(thin, 0.0) * c, method, route.field_min))
    return out[0], out[1]


def series_allowance(spec: GearSpec, designation: str | None = None,
                     field: str = "thickness_allowance_series") -> ThicknessAllowance:
    """The allowance of a DIN 3967 designation (``"cd25"``; default the gear's
    ``thickness_allowance_series``, else :data:`geargen.core.din3967.DEFAULT_DESIGNATION`) at the
    gear's reference diameter: what a gear made alone (no mesh to take it from) is ordered with."""
    from geargen.core.din3967 import DEFAULT_DESIGNATION, allowance_um, method_text
    shop = getattr(spec, "shop", None)
    designation = designation or (shop.thickness_allowance_series if shop else None) or DEFAULT_DESIGNATION
    d = 2 * spec.reference_radius
    upper, lower = allowance_um(d, designation, field)
    method = method_text(designation) + f" d = {d:.6g} mm"
    return ThicknessAllowance(upper * 1e-3, lower * 1e-3, method, field)
