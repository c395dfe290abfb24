"""``geargen pair``: the gear-pair calculator (pure math, no CAD import)::

    geargen pair --teeth 12 24 --module 3 --profile-shift 0.6 0.36
    geargen pair --teeth 16 48 --diametral-pitch 32 --centre-distance 1.004 --profile-shift 0 0
    geargen pair --teeth 12 60 --module 3 --helix-angle 30 --hand right --face-width 20 --centre-distance 125
    geargen pair --internal --teeth 16 24 --module 3 --profile-shift 0 0.516

``--internal``: gear 2 is a ring (internal gear, same hand as gear 1) and the pinion meshes inside
it: prints the internal pair's geometry (:mod:`geargen.families.internal.geometry`) and its named checks on the
exact outlines (:mod:`geargen.families.internal.pair`: involute, tip and trochoid interference,
radial-assembly fouling, the minimum tooth difference).

Prints, in the design's unit (mm with ``--module``, inches with ``--diametral-pitch``): the
diameters of each gear (reference, base, tip, root, working pitch), the standard, working and
operating centre distances, the working pressure angle (transverse, and normal for helical
pairs), the contact ratios, the backlash of each kind, undercut and the minimum shift without
it, the tip land, span and over-pins/balls measurements, and a recommended split of the sum
of profile shifts (the rule is printed), and the mesh stiffness per ISO 6336-1:2019 method B
(single stiffness c' and mesh stiffness c_gamma with their factors) beside Eq. 1's ``E w / 11``.
``--json FILE|-`` writes the same numbers (:func:`geargen.report.pair.pair_data`).

``--centre-distance``: the shift sum for zero backlash there (the inverse) is always reported.
With ``--profile-shift`` the pair is taken as given and its backlash at that centre distance is
reported; without it the shifts are the recommended split of that sum (backlash then comes
from ``--thinning`` only). The printout says which.

All gear inputs are in the normal system: ``--module``/``--diametral-pitch``, ``--pressure-angle``
and ``--profile-shift`` are normal values for a helical pair.
"""

from __future__ import annotations

import json
import math
import sys
from dataclasses import replace

from geargen.design.checks import MINIMUM_SAFETY
from geargen.design.gear import GearSpec
from geargen.errors import DesignError
from geargen.families.registry import read_gear
from geargen.units import from_mm, to_mm

#: face width the gears are given when --face-width is not: as wide as GearSpec allows (mm), so
#: that no measurement is refused for want of face; the overlap ratio is then not reported
_UNSTATED_FACE_WIDTH_MM = 5000.0


def add_arguments(p) -> None:
    p.add_argument("--teeth", nargs=2, type=int, metavar=("Z1", "Z2"), required=True,
                   help="teeth of gear 1 (the pinion) and gear 2")
    pitch = p.add_mutually_exclusive_group(required=True)
    pitch.add_argument("--module", type=float, metavar="MM", help="normal module in mm (metric: lengths in mm)")
    pitch.add_argument("--diametral-pitch", type=float, metavar="PER_IN",
                       help="normal diametral pitch, teeth per inch (inch design: lengths in inches)")
    p.add_argument("--pressure-angle", type=float, default=20.0, metavar="DEG",
                   help="normal pressure angle, degrees (default 20)")
    p.add_argument("--helix-angle", type=float, default=0.0, metavar="DEG", help="helix angle, degrees (default 0: spur)")
    p.add_argument("--hand", choices=("right", "left"), default=None,
                   help="helix hand of gear 1 (default right); gear 2 has the opposite hand")
    p.add_argument("--profile-shift", type=float, nargs=2, default=None, metavar=("X1", "X2"),
                   help="normal profile shift coefficients (default 0 0, or with --centre-distance the "
                        "recommended split of the sum it needs)")
    p.add_argument("--face-width", type=float, default=None, metavar="LEN",
                   help="common face width in the design's unit, for the overlap ratio")
    p.add_argument("--centre-distance", type=float, default=None, metavar="LEN",
                   help="operating centre distance in the design's unit (default: the working centre distance "
                        "of the shifts)")
    p.add_argument("--thinning", type=float, nargs=2, default=None, metavar=("T1", "T2"),
                   help="tooth thinning for backlash, circumferential (transverse arc) at the reference circle, "
                        "in the design's unit (default 0 0)")
    p.add_argument("--dedendum-coefficient", type=float, default=None, metavar="H",
                   help="basic rack dedendum over the normal module, both gears (default 1.25); also ISO 6336's "
                        "basic rack factor C_B")
    p.add_argument("--elastic-modulus", type=float, default=None, metavar="GPA",
                   help="Young's modulus of both gears in GPa, for Eq. 1 (E w / 11) and ISO 6336's material factor "
                        "E / E_st (default: geargen's steel, as [stiffness] elastic_modulus)")
    p.add_argument("--load", type=float, default=None, metavar="N",
                   help="F_t K_A: transverse tangential load at the reference circle times the application factor, "
                        "N (needs --face-width); below 100 N/mm of face ISO 6336 lowers c' (default: no load "
                        "correction)")
    p.add_argument("--rack-tip-radius", type=float, default=None, metavar="RHO",
                   help="tip radius of the generating basic rack over the normal module, both gears (default 0.38 "
                        "or the largest that fits); shapes the root fillet and ISO 6336-3's Y_F and Y_S")
    rating = p.add_argument_group(
        "load capacity (ISO 6336-2:2019 pitting and ISO 6336-3:2019 tooth root bending, method B)",
        "Given --torque, the pair is rated and the 'load_capacity' block added; it needs --face-width, --speed, "
        "--life, --material, --accuracy-grade, --roughness and --viscosity. Exit status 1 when a safety factor is "
        "below its minimum.")
    rating.add_argument("--torque", type=float, default=None, metavar="T",
                        help="nominal torque on gear 1: N m (in lbf for an inch pair)")
    rating.add_argument("--speed", type=float, default=None, metavar="N", help="speed of gear 1, rpm")
    rating.add_argument("--life", type=float, default=None, metavar="H", help="required life, hours")
    rating.add_argument("--material", nargs="+", default=None, metavar="M",
                        help="ISO 6336-5 material and heat treatment of gear 1 [and gear 2]: "
                             + ", ".join(_material_names()))
    rating.add_argument("--hardness", type=float, nargs="+", default=None, metavar="HV",
                        help="surface hardness of gear 1 [and gear 2], HV (needed where ISO 6336-5's allowable "
                             "stress is a sloped line in it: through and induction hardened)")
    rating.add_argument("--quality", nargs="+", default=None, metavar="Q",
                        help="ISO 6336-5 material quality ML, MQ or ME of gear 1 [and gear 2] (default MQ)")
    rating.add_argument("--accuracy-grade", type=int, default=None, metavar="A",
                        help="ISO 1328-1:2013 flank tolerance class of both gears (drives K_v, K_Halpha, K_Hbeta)")
    rating.add_argument("--application-factor", type=float, default=1.0, metavar="K_A", help="K_A (default 1.0)")
    rating.add_argument("--face-load-factor", type=float, default=None, metavar="K_HBETA",
                        help="K_Hbeta, given instead of computed (default: ISO 6336-1 method C for a pinion centred "
                             "between its bearings on a stiff shaft, without helix correction: method C needs shaft "
                             "data a pair has not)")
    rating.add_argument("--roughness", type=float, default=None, metavar="RA",
                        help="flank and root roughness R_a, um (R_z taken as 6 R_a)")
    rating.add_argument("--viscosity", type=float, default=None, metavar="NU40",
                        help="lubricant kinematic viscosity at 40 deg C, mm^2/s")
    rating.add_argument("--tip-relief", type=float, default=0.0, metavar="C_A", help="tip relief C_a, um (default 0)")
    rating.add_argument("--minimum-safety", type=float, nargs=2, default=None, metavar=("S_HMIN", "S_FMIN"),
                        help="minimum safety factors for pitting and bending; the pair fails (exit 1) below them. "
                             f"Default {MINIMUM_SAFETY[0]:g} and {MINIMUM_SAFETY[1]:g}: ISO 6336 leaves "
                             "the values to agreement between the parties and recommends none; these are the usual "
                             "industrial values (a root fracture ends the drive, a pit does not at once, hence the "
                             "larger S_Fmin)")
    p.add_argument("--json", metavar="FILE", default=None, help="write the numbers as JSON ('-' for standard output)")
    p.add_argument("--internal", action="store_true",
                   help="gear 2 is an internal gear (a ring, same hand as gear 1): internal pair geometry and checks")


#: N m per in lbf
NM_PER_INLBF = 0.1129848290276167


def _material_names() -> list[str]:
    from geargen.core.iso6336_materials import MATERIALS
    return list(MATERIALS)


#: gear-table key (without a unit suffix) -> the option that sets it
_FLAGS = {"teeth": "--teeth", "module_mm": "--module", "diametral_pitch_per_in": "--diametral-pitch",
          "pressure_angle_deg": "--pressure-angle", "helix_angle_deg": "--helix-angle", "hand": "--hand",
          "profile_shift": "--profile-shift", "face_width": "--face-width", "thinning_circumferential": "--thinning",
          "dedendum_coefficient": "--dedendum-coefficient", "rack_tip_radius_coefficient": "--rack-tip-radius"}
#: options given once for both gears: their messages need not say which gear
_COMMON = {"--module", "--diametral-pitch", "--pressure-angle", "--helix-angle", "--face-width",
           "--dedendum-coefficient", "--rack-tip-radius"}


def _flag(key: str) -> str:
    for stem, flag in _FLAGS.items():
        if key == stem or key.startswith(stem + "_"):
            return flag
    return f"--{key.replace('_', '-')}"


def gears_from_args(args) -> tuple[GearSpec, GearSpec, str]:
    """The two gears the options describe (validated as a design file's ``[gear]`` table is), and
    the length unit. Errors name the option and, for per-gear values, the gear."""
    unit = "mm" if args.module is not None else "in"
    helical = args.helix_angle != 0
    if args.hand is not None and not helical:
        raise DesignError("--hand", "a spur pair has no hand", "--hand only with --helix-angle > 0")
    hand1 = args.hand or "right"
    internal = getattr(args, "internal", False)
    if internal:
        hands = (hand1, hand1)  # a pinion and its ring have the same hand
    else:
        hands = (hand1, "left" if hand1 == "right" else "right") if helical else ("right", "right")
    shifts = args.profile_shift or (0.0, 0.0)
    thinning = args.thinning or (0.0, 0.0)
    if args.face_width is not None and not (math.isfinite(args.face_width) and args.face_width > 0):
        raise DesignError("--face-width", f"{args.face_width!r} is out of range", f"> 0 {unit}")
    gears = []
    for i in range(2):
        table = {"teeth": args.teeth[i], "pressure_angle_deg": args.pressure_angle,
                 "helix_angle_deg": args.helix_angle, "hand": hands[i], "profile_shift": shifts[i],
                 f"thinning_circumferential_{unit}": thinning[i]}
        if internal and i == 1:
            table["kind"] = "internal"
        if args.dedendum_coefficient is not None:
            table["dedendum_coefficient"] = args.dedendum_coefficient
        if getattr(args, "rack_tip_radius", None) is not None:
            table["rack_tip_radius_coefficient"] = args.rack_tip_radius
        if args.module is not None:
            table["module_mm"] = args.module
        else:
            table["diametral_pitch_per_in"] = args.diametral_pitch
        if args.face_width is None:
            table["face_width_mm"] = _UNSTATED_FACE_WIDTH_MM
        else:
            table[f"face_width_{unit}"] = args.face_width
        try:
            gears.append(read_gear(table, where="options", name=f"gear {i + 1}", length_unit=unit))
        except DesignError as exc:
            flag = _flag(exc.field.split(".", 1)[1]) if exc.field.startswith("options.") else exc.field
            problem = exc.problem if flag in _COMMON else f"gear {i + 1}: {exc.problem}"
            raise DesignError(flag, problem, exc.allowed) from None
    from geargen.core.geometry import profile_shift_limits

    for i, g in enumerate(gears):
        lowest = profile_shift_limits(g)[0]
        if g.tip_radius <= g.base_radius:
            raise DesignError("--profile-shift", f"gear {i + 1}: {g.profile_shift!r} puts the tip circle inside the "
                              "base circle", f"> {lowest:.6g} for {g.teeth} teeth")
    return gears[0], gears[1], unit


def check_centre_distance(args, gear1: GearSpec, gear2: GearSpec, unit: str) -> float | None:
    """``--centre-distance`` in mm, refused (in the design's unit) where no mesh exists, or, without
    ``--profile-shift``, where the shift sum it needs is beyond what the gears can carry."""
    if args.centre_distance is None:
        return None
    from geargen.core.geometry import profile_shift_limits, working_centre_distance

    base_sum = gear1.base_radius + gear2.base_radius
    value = to_mm(args.centre_distance, unit)
    if not (math.isfinite(value) and value > base_sum):
        raise DesignError("--centre-distance", f"{args.centre_distance!r} {unit} does not clear the base circles",
                          f"> {from_mm(base_sum, unit):.6g} {unit}, the sum of the base radii")
    if args.profile_shift is None:
        # the shifts will be a split of the sum this centre distance needs: that sum must be one
        # the two gears can share (profile_shift_limits)
        (lo1, hi1), (lo2, hi2) = profile_shift_limits(gear1), profile_shift_limits(gear2)
        teeth_sum = gear1.teeth + gear2.teeth

        def centre_distance_of(shift_sum):
            try:
                return float(working_centre_distance(shift_sum, teeth_sum, gear1.module, gear1.pressure_angle,
                                                     gear1.helix_angle))
            except DesignError:  # no working pressure angle: the base circles are the limit
                return base_sum

        smallest, biggest = centre_distance_of(lo1 + lo2), centre_distance_of(hi1 + hi2)
        if not smallest < value <= biggest:
            raise DesignError("--centre-distance", f"{args.centre_distance!r} {unit} needs a profile shift sum that the "
                              f"two gears cannot share (x1 + x2 in ({lo1 + lo2:.6g}, {hi1 + hi2:.6g}])",
                              f"({from_mm(smallest, unit):.6g}, {from_mm(biggest, unit):.6g}] {unit}, or give "
                              "--profile-shift to see the backlash there")
    return value


def stiffness_inputs(args) -> tuple[float | None, float | None]:
    """``--elastic-modulus`` in MPa and ``--load`` in N, refused where out of range (the load needs
    ``--face-width``: ISO 6336's load correction is per unit face width)."""
    modulus = None
    if args.elastic_modulus is not None:
        if not (math.isfinite(args.elastic_modulus) and args.elastic_modulus > 0):
            raise DesignError("--elastic-modulus", f"{args.elastic_modulus!r} GPa is out of range", "> 0 GPa")
        modulus = args.elastic_modulus * 1e3
    if args.load is not None:
        if not (math.isfinite(args.load) and args.load > 0):
            raise DesignError("--load", f"{args.load!r} N is out of range", "> 0 N")
        if args.face_width is None:
            raise DesignError("--load", "a load needs the face width it is spread over", "--load with --face-width")
    return modulus, args.load


#: rating options -> their flags; given without --torque they are refused (they would do nothing)
_RATING_FLAGS = {"speed": "--speed", "life": "--life", "material": "--material", "hardness": "--hardness",
                 "quality": "--quality", "accuracy_grade": "--accuracy-grade", "face_load_factor": "--face-load-factor",
                 "roughness": "--roughness", "viscosity": "--viscosity", "minimum_safety": "--minimum-safety"}
#: what the rating's own fields are called on this command line
_RATING_FIELD_FLAGS = {**_RATING_FLAGS, "tangential_load": "--torque", "application_factor": "--application-factor",
                       "tip_relief": "--tip-relief", "grade": "--accuracy-grade",
                       "reference_diameter": "--accuracy-grade", "normal_module": "--accuracy-grade",
                       "face_width": "--face-width", "rack_tip_radius": "--rack-tip-radius"}


def _per_gear(args, name: str, values, default=None):
    """A one-or-two-value option as (gear 1, gear 2): one value serves both gears."""
    if values is None:
        return default, default
    if len(values) > 2:
        raise DesignError(_RATING_FLAGS[name], f"{len(values)} values given", "one (both gears) or two (gear 1, gear 2)")
    return (values[0], values[-1])


def rating_requested(args) -> bool:
    """True with --torque; the other rating options without it are refused by name."""
    if getattr(args, "torque", None) is not None:
        return True
    extra = [flag for key, flag in _RATING_FLAGS.items() if getattr(args, key, None) is not None]
    if getattr(args, "application_factor", 1.0) != 1.0:
        extra.append("--application-factor")
    if getattr(args, "tip_relief", 0.0) != 0.0:
        extra.append("--tip-relief")
    if extra:
        raise DesignError(extra[0], "rates the pair's load capacity, which needs the torque it carries",
                          "give --torque with it")
    return False


def rate_from_args(args, gear1: GearSpec, gear2: GearSpec, centre_distance_mm: float | None, unit: str):
    """The load capacity block of ``--torque`` and its companions: (the rating's dict, the face
    widths reaching the minimum safety factors in the pair's unit, ok)."""
    from geargen.core.iso6336_materials import Material
    from geargen.core.load_capacity import (RatingConditions, face_width_for_minimum_safety, rate_pair,
                                            rating_geometry)

    missing = [flag for key, flag in (("face_width", "--face-width"), ("speed", "--speed"), ("life", "--life"),
                                      ("material", "--material"), ("accuracy_grade", "--accuracy-grade"),
                                      ("roughness", "--roughness"), ("viscosity", "--viscosity"))
               if getattr(args, key) is None]
    if missing:
        raise DesignError(missing[0], "missing: rating the load capacity (--torque) needs it",
                          "--face-width, --speed, --life, --material, --accuracy-grade, --roughness, --viscosity")
    if not (math.isfinite(args.torque) and args.torque > 0):
        raise DesignError("--torque", f"{args.torque!r} is out of range", f"> 0 {'in lbf' if unit == 'in' else 'N m'}")
    torque_nmm = args.torque * (NM_PER_INLBF if unit == "in" else 1.0) * 1e3
    try:
        names = _per_gear(args, "material", args.material)
        hardness = _per_gear(args, "hardness", args.hardness)
        quality = _per_gear(args, "quality", args.quality, "MQ")
        materials = tuple(Material(names[i], quality[i], hardness[i]) for i in (0, 1))
        conditions = RatingConditions(
            speed=args.speed, life=args.life, accuracy_grade=args.accuracy_grade, roughness=args.roughness,
            viscosity=args.viscosity, application_factor=args.application_factor,
            face_load_factor=args.face_load_factor, tip_relief=args.tip_relief,
            minimum_safety=tuple(args.minimum_safety or MINIMUM_SAFETY))
        geo = rating_geometry(gear1, gear2, centre_distance_mm)
        load = 2 * torque_nmm / geo.reference_diameters[0]
        rating = rate_pair(geo, load, conditions, materials)
        widths = face_width_for_minimum_safety(geo, load, conditions, materials)
    except DesignError as exc:
        flag = _RATING_FIELD_FLAGS.get(exc.field.split(".")[-1])
        if flag is None:
            raise
        raise DesignError(flag, exc.problem, exc.allowed) from None
    block = rating.to_dict()
    block["torque"] = args.torque
    block["torque_unit"] = "in lbf" if unit == "in" else "N m"
    width = {"pitting": None if widths.pitting is None else from_mm(widths.pitting, unit),
             "bending": None if widths.bending is None else from_mm(widths.bending, unit),
             "required": None if widths.required is None else from_mm(widths.required, unit),
             "unit": unit, "message": widths.message,
             "meaning": "narrowest face width at which the weaker gear reaches S_Hmin (pitting) and S_Fmin "
                        "(bending) at this load; required: the larger"}
    block["face_width_for_minimum_safety"] = width
    return block, width, rating.ok


def run_internal(args, pinion: GearSpec, ring: GearSpec, unit: str) -> int:
    """``--internal``: the internal pair's geometry and named checks, printed and as JSON."""
    from geargen.families.internal.pair import check_internal
    from geargen.errors import GeometryError

    if pinion.teeth >= ring.teeth:
        raise DesignError("--teeth", f"the ring ({ring.teeth}) must have more teeth than the pinion ({pinion.teeth})",
                          "Z1 < Z2")
    centre = None
    if args.centre_distance is not None:
        centre = to_mm(args.centre_distance, unit)
        least = ring.base_radius - pinion.base_radius
        if not (math.isfinite(centre) and centre > least):
            raise DesignError("--centre-distance", f"{args.centre_distance!r} {unit} does not reach the base circles",
                              f"> {from_mm(least, unit):.6g} {unit}, rb2 - rb1")
    try:
        result = check_internal(pinion, ring, centre)
    except GeometryError as exc:
        raise DesignError("--profile-shift", f"the pair cannot be made: {exc}", "another shift or tooth count") from None
    g = result.geometry
    L = lambda v: from_mm(v, unit)  # noqa: E731
    lines = [f"internal pair: pinion {pinion.teeth} teeth inside a {ring.teeth}-tooth ring "
             f"(tooth difference {g.tooth_difference}, the smallest that meshes, assembled axially: {result.minimum_tooth_difference})",
             f"  working pressure angle (transverse)  {math.degrees(g.working_pressure_angle):.4f} deg",
             f"  centre distance                      {L(g.centre_distance):.6g} {unit} (zero backlash "
             f"{L(g.zero_backlash_centre_distance):.6g}, reference {L(g.reference_centre_distance):.6g}, "
             f"y = {g.centre_distance_modification:.4f})",
             f"  working diameters                    {L(2 * g.working_radius_pinion):.6g} / "
             f"{L(2 * g.working_radius_ring):.6g} {unit}",
             f"  contact ratio                        {g.contact_ratio:.4f} transverse, {g.overlap_ratio:.4f} overlap",
             f"  backlash                             {L(g.backlash_circumferential):.6g} {unit} circumferential, "
             f"{L(g.backlash_normal):.6g} {unit} normal",
             "  checks (margin, positive passes):"]
    for key, value in result.margins.items():
        lines.append(f"    {key:34s} {value:.6g}")
    lines += [f"  FAIL {f.kind}: {f.message}" for f in result.failures] or ["  all checks pass"]
    lines += [f"  note: {n}" for n in result.notes]
    from geargen import __version__
    data = {"generator": "geargen pair", "version": __version__, "kind": "internal", "length_unit": "mm",
            **result.to_dict()}
    rated_ok = True
    if rating_requested(args):
        from geargen.report.load_capacity import format_load_capacity
        block, width, rated_ok = rate_from_args(args, pinion, ring, g.centre_distance, unit)
        data["load_capacity"] = block
        lines += format_load_capacity(block, unit, width)
    print("\n".join(lines), file=sys.stderr if args.json == "-" else sys.stdout)
    if args.json:
        from geargen.outputs import json_default, write_text
        write_text(args.json, json.dumps(data, indent=2, allow_nan=False, default=json_default) + "\n", "--json")
    return 0 if result.ok and rated_ok else 1


def run(args) -> int:
    from geargen.report.pair import format_pair, pair_data

    gear1, gear2, unit = gears_from_args(args)
    rated = rating_requested(args)
    if getattr(args, "internal", False):
        return run_internal(args, gear1, gear2, unit)
    centre_distance = check_centre_distance(args, gear1, gear2, unit)
    modulus, load = stiffness_inputs(args)
    if args.profile_shift is not None:
        source = "given"
    else:
        source = "default" if centre_distance is None else "centre_distance"
    try:
        data = pair_data(gear1, gear2, shift_source=source, centre_distance=centre_distance,
                         face_width=None if args.face_width is None else to_mm(args.face_width, unit),
                         diametral_pitch=args.diametral_pitch, elastic_modulus=modulus, load=load)
    except DesignError as exc:
        # the core names its own fields; say which option they came from
        flag = {"shift_sum": "--centre-distance" if source == "centre_distance" else "--profile-shift",
                "profile_shift": "--profile-shift", "centre_distance": "--centre-distance",
                "specific_load": "--load", "elastic_modulus": "--elastic-modulus"}.get(exc.field)
        if flag is None:
            raise
        raise DesignError(flag, exc.problem, exc.allowed) from None
    from geargen import __version__
    data = {"generator": "geargen pair", "version": __version__, **data}
    data["options"] = {k: getattr(args, k) for k in ("teeth", "module", "diametral_pitch", "pressure_angle",
                                                      "helix_angle", "hand", "profile_shift", "face_width",
                                                      "centre_distance", "thinning", "dedendum_coefficient",
                                                      "elastic_modulus", "load")}
    rated_ok = True
    text = format_pair(data)
    if rated:
        from geargen.report.load_capacity import format_load_capacity
        shifted = tuple(replace(g, profile_shift=x) for g, x in zip((gear1, gear2), data["profile_shift"]))
        block, width, rated_ok = rate_from_args(args, *shifted, to_mm(data["centre_distance"]["operating"], unit),
                                                unit)
        data["load_capacity"] = block
        text += "\n" + "\n".join(format_load_capacity(block, unit, width))
    for key in ("rack_tip_radius", "torque", "speed", "life", "material", "hardness", "quality", "accuracy_grade",
                "application_factor", "face_load_factor", "roughness", "viscosity", "tip_relief", "minimum_safety"):
        data["options"][key] = getattr(args, key)
    print(text, file=sys.stderr if args.json == "-" else sys.stdout)
    if args.json:
        from geargen.outputs import json_default, write_text
        write_text(args.json, json.dumps(data, indent=2, allow_nan=False, default=json_default) + "\n", "--json")
    return 0 if rated_ok else 1

