"""The gear-pair calculator behind ``geargen pair``: its numbers (:func:`pair_data`) and its table
(:func:`format_pair`). Pure math from :mod:`geargen.core.geometry`; nothing here builds a solid.

:func:`pair_data` returns one JSON-ready dict in the design's length unit (``length_unit``: mm for
a module design, inches for a diametral-pitch one; angles in degrees, keys say ``_deg``, module in
mm); :func:`format_pair` prints that same dict, so the table and the JSON cannot disagree.

Conventions (those of :mod:`geargen.core.geometry`): gears in the normal system (normal module,
normal pressure angle, normal profile shift coefficients x); tip diameters as built, addendum
(1 + x) m_n, without tip shortening (the diameters that would keep the standard tip clearance at
the operating centre distance are given beside them); backlash positive for clearance, each kind
named with where it is measured.
"""

from __future__ import annotations

import math
from dataclasses import replace

from geargen.core import geometry
from geargen.design.gear import GearSpec
from geargen.errors import GeargenError
from geargen.units import from_mm

SCHEMA = "geargen.pair/1"

#: how the profile shifts of the report were chosen (``profile_shift_source``)
SHIFT_SOURCES = {
    "given": "given (--profile-shift)",
    "default": "default 0 0 (no --profile-shift)",
    "centre_distance": "recommended split of the shift sum for zero backlash at --centre-distance",
}

#: a normal tip land thinner than this many normal modules is reported (a common minimum; case-
#: hardened teeth usually need more, since a thin tip hardens through and chips)
TIP_LAND_MINIMUM_MODULES = 0.2

#: decimals printed for lengths in each unit (the JSON carries full precision)
LENGTH_DECIMALS = {"mm": 5, "in": 6}
ANGLE_DECIMALS = 6
ARCMIN_PER_RAD = 180 * 60 / math.pi


def pair_data(gear1: GearSpec, gear2: GearSpec, *, shift_source: str = "given", centre_distance: float | None = None,
              face_width: float | None = None, diametral_pitch: float | None = None,
              elastic_modulus: float | None = None, load: float | None = None) -> dict:
    """Everything ``geargen pair`` reports about two external gears in mesh, as a JSON-ready dict.

    Parameters
    ----------
    gear1, gear2 : GearSpec
        The pinion and the wheel (same normal module, pressure angle and helix angle, opposite
        hands if helical); their ``length_unit`` is the unit of every length in the result.
    shift_source : {"given", "default", "centre_distance"}
        Where the profile shifts come from. ``"centre_distance"``: the gears' shifts are replaced
        by the recommended split (:func:`geargen.core.geometry.split_profile_shift`) of the shift
        sum that meshes without backlash at ``centre_distance`` (which is then required).
    centre_distance : float, optional
        Operating centre distance a' (mm). Default: the working centre distance of the shifts
        (zero backlash without thinning). When given, the shift sum for zero backlash at it is
        reported too (the inverse), and with given shifts the backlash there.
    face_width : float, optional
        Common face width (mm) for the overlap ratio; without it a helical pair's overlap and
        total contact ratios are None (a spur pair's overlap ratio is 0 whatever the width).
    diametral_pitch : float, optional
        Normal diametral pitch (1/in) of an inch design, echoed in the result.
    elastic_modulus : float, optional
        Young's modulus of both gears (MPa) for Eq. 1 and ISO 6336's material factor; default
        geargen's steel (:data:`geargen.design.stiffness.STEEL_ELASTIC_MODULUS`).
    load : float, optional
        F_t K_A (N), spread over ``face_width`` (then required): ISO 6336's load correction of c'
        below 100 N/mm. Default: none (the contract's "no load correction").
    """
    if shift_source not in SHIFT_SOURCES:
        raise ValueError(f"shift_source must be one of {sorted(SHIFT_SOURCES)}")
    if shift_source == "centre_distance" and centre_distance is None:
        raise ValueError("shift_source 'centre_distance' needs a centre distance")
    unit = gear1.length_unit

    def L(value):
        return None if value is None else float(from_mm(value, unit))

    m_n, alpha_n, beta = gear1.module, gear1.pressure_angle, gear1.helix_angle
    teeth_sum = gear1.teeth + gear2.teeth
    zero_backlash_sum = None
    if centre_distance is not None:
        zero_backlash_sum = float(geometry.shift_sum_for_centre_distance(centre_distance, teeth_sum, m_n, alpha_n, beta))
    split = None
    if shift_source == "centre_distance":
        split = geometry.split_profile_shift(geometry.GearPair(gear1, gear2), zero_backlash_sum)
        gear1 = replace(gear1, profile_shift=split.profile_shifts[0])
        gear2 = replace(gear2, profile_shift=split.profile_shifts[1])
    pair = geometry.GearPair(gear1, gear2)
    split_problem = None
    if split is None:
        try:
            split = geometry.split_profile_shift(pair, pair.shift_sum)
        except GeargenError as exc:  # a sum the given gears carry but no other split of it would
            split_problem = str(exc)
    working = float(geometry.working_centre_distance(pair.shift_sum, teeth_sum, m_n, alpha_n, beta))
    operating = working if centre_distance is None else float(centre_distance)

    b = face_width if face_width is not None else min(gear1.face_width, gear2.face_width)
    mesh = geometry.mesh_geometry(pair, operating, "spec", face_width=b)
    warnings: list[str] = []
    try:
        clearance_mesh = geometry.mesh_geometry(pair, operating, "constant_clearance", face_width=b)
    except GeargenError:  # the clearance would need a tip inside the base circle: no such gear
        clearance_mesh = None
        warnings.append("the standard tip clearance cannot be kept at this centre distance: it would take a tip "
                        "inside its base circle")
    backlash = geometry.backlash_at_centre_distance(pair, operating)
    sliding = geometry.specific_sliding(pair, operating)
    overlap_known = face_width is not None or not pair.gear1.is_helical

    def ratios(m):
        return {"transverse": m.transverse_contact_ratio,
                "overlap": m.face_contact_ratio if overlap_known else None,
                "total": m.total_contact_ratio if overlap_known else None}

    if centre_distance is None:
        backlash_source = "at the working centre distance of the shifts: from the tooth thinning only"
    elif shift_source == "centre_distance":
        backlash_source = "at --centre-distance with the recommended shifts: from the tooth thinning only"
    else:
        backlash_source = "at --centre-distance with the given shifts: from the centre distance and the tooth thinning"

    gears = [_gear_data(g, i, mesh, sliding, L, warnings) for i, g in enumerate((gear1, gear2))]
    for i, g in enumerate(gears):
        g["tip_diameter_constant_clearance"] = None if clearance_mesh is None else L(2 * clearance_mesh.tip_radii[i])
    _pair_warnings(mesh, backlash, overlap_known, warnings, L, unit)

    stiffness = _stiffness_data(pair, operating, face_width, elastic_modulus, load)
    warnings += [f"ISO 6336 stiffness: {w}" for w in stiffness["iso6336"]["warnings"]]

    recommended = _split_data(split, pair.shift_sum, split_problem)
    if not recommended["success"]:
        warnings.append(f"recommended profile shift: {recommended['message']}")
    data = {
        "schema": SCHEMA,
        "length_unit": unit,
        "teeth": [gear1.teeth, gear2.teeth],
        "gear_ratio": gear2.teeth / gear1.teeth,
        "normal_module_mm": m_n,
        "transverse_module_mm": gear1.transverse_module,
        "normal_diametral_pitch_per_in": diametral_pitch,
        "transverse_diametral_pitch_per_in": None if diametral_pitch is None else diametral_pitch * math.cos(beta),
        "normal_pressure_angle_deg": math.degrees(alpha_n),
        "transverse_pressure_angle_deg": math.degrees(gear1.transverse_pressure_angle),
        "helix_angle_deg": math.degrees(beta),
        "base_helix_angle_deg": math.degrees(gear1.base_helix_angle),
        "hands": [gear1.hand, gear2.hand] if gear1.is_helical else None,
        "face_width": L(face_width),
        "profile_shift": [gear1.profile_shift, gear2.profile_shift],
        "profile_shift_sum": pair.shift_sum,
        "profile_shift_source": SHIFT_SOURCES[shift_source],
        "thinning_circumferential": [L(gear1.thinning), L(gear2.thinning)],
        "centre_distance": {
            "standard": L(pair.standard_centre_distance),
            "working": L(working),
            "operating": L(operating),
            "operating_source": "given (--centre-distance)" if centre_distance is not None
            else "the working centre distance of the shifts (no --centre-distance)",
        },
        "shift_sum_for_zero_backlash": zero_backlash_sum,
        "working_pressure_angle_transverse_deg": math.degrees(mesh.working_pressure_angle),
        "working_pressure_angle_normal_deg": math.degrees(mesh.normal_working_pressure_angle),
        "contact_ratio": {**ratios(mesh), "tips": "as built, addendum (1 + x) m_n"},
        "contact_ratio_constant_clearance": None if clearance_mesh is None else {**ratios(clearance_mesh),
                                             "tips": "shortened where needed to keep the standard tip clearance "
                                                     "(h_f* - h_a*) m_n at the operating centre distance"},
        "length_of_action": L(mesh.length_of_action),
        "transverse_base_pitch": L(mesh.transverse_base_pitch),
        "backlash": {
            "source": backlash_source,
            "circumferential_reference": L(backlash.circumferential_reference),
            "circumferential_working_pitch": L(backlash.circumferential),
            "line_of_action": L(backlash.base_tangent),
            "normal": L(backlash.normal),
            "angular_arcmin": [backlash.angular1 * ARCMIN_PER_RAD, backlash.angular2 * ARCMIN_PER_RAD],
            "centre_distance_change": L(backlash.centre_distance_change),
            "tight_mesh_centre_distance": None if math.isnan(backlash.tight_mesh_centre_distance)
            else L(backlash.tight_mesh_centre_distance),
            "kinds": {
                "circumferential_reference": "transverse arc at the reference circles (where thinning is stated)",
                "circumferential_working_pitch": "transverse arc at the working pitch circles",
                "line_of_action": "along the transverse line of action (base tangent)",
                "normal": "normal to the flanks (line of action times cos of the base helix angle)",
                "angular_arcmin": "free rotation of each gear, the other held",
                "centre_distance_change": "operating minus tight-mesh centre distance (radial)",
            },
        },
        "recommended_profile_shift": recommended,
        **stiffness,
        "gears": gears,
        "warnings": warnings,
    }
    return data


def _stiffness_data(pair, operating: float, face_width: float | None, elastic_modulus: float | None,
                    load: float | None) -> dict:
    """The contract's ``iso6336`` block (c', c_gamma and their factors at the operating centre
    distance) and Eq. 1 beside it, both per unit face width and, with a face width, for the mesh."""
    from geargen.core.iso6336 import pair_stiffness
    from geargen.core.stiffness import mesh_stiffness
    from geargen.design.stiffness import STEEL_ELASTIC_MODULUS

    e = STEEL_ELASTIC_MODULUS if elastic_modulus is None else float(elastic_modulus)
    if load is not None and face_width is None:
        raise ValueError("a load needs the face width it is spread over")
    iso = pair_stiffness(pair, operating, face_width, e, None if load is None else load / face_width)
    per_width = float(mesh_stiffness(e, 1.0)) * 1e-3  # N/mm per mm of face -> N/(mm·µm)
    return {"iso6336": {**iso.to_dict(), "applied_load_N": load},
            "eq1": {"method": "Eq. 1 of the paper: k = E w / 11 along the line of action", "elastic_modulus_MPa": e,
                    "stiffness_per_face_width_N_per_mm_um": per_width,
                    "stiffness_whole_N_per_um": None if face_width is None else per_width * face_width,
                    "face_width_mm": face_width}}


def _split_data(split, shift_sum: float, problem: str | None) -> dict:
    if split is None:
        return {"rule": geometry.SHIFT_SPLIT_RULE, "shift_sum": shift_sum, "profile_shift": None,
                "balanced_profile_shift": None, "specific_sliding_root": None, "raised_for_undercut": None,
                "success": False, "message": f"no recommendation: {problem}"}
    return {"rule": split.rule, "shift_sum": split.shift_sum, "profile_shift": list(split.profile_shifts),
            "balanced_profile_shift": list(split.balanced_shifts),
            "specific_sliding_root": [_finite(v) for v in split.root_specific_sliding],
            "raised_for_undercut": list(split.raised_for_undercut), "success": split.success,
            "message": split.message}


def _finite(value: float) -> float | None:
    """``value``, or None where it is unbounded (specific sliding at an interfering root)."""
    return value if math.isfinite(value) else None


def _gear_data(g: GearSpec, index: int, mesh, sliding, L, warnings: list[str]) -> dict:
    name = f"gear {index + 1}"
    uc = geometry.undercut(g)
    land = geometry.tip_land(g)
    thin = land.normal_thickness < TIP_LAND_MINIMUM_MODULES * g.module
    out = {
        "name": name, "teeth": g.teeth, "hand": g.hand if g.is_helical else None,
        "profile_shift": g.profile_shift,
        "reference_diameter": L(2 * g.reference_radius),
        "base_diameter": L(2 * g.base_radius),
        "tip_diameter": L(2 * g.tip_radius),
        "root_diameter": L(2 * g.root_radius_standard),
        "working_pitch_diameter": L(2 * mesh.working_pitch_radii[index]),
        "involute_start_diameter": L(2 * mesh.involute_start_radii[index]),
        "active_profile_start_diameter": L(2 * mesh.active_profile_start_radii[index]),
        "undercut": uc.is_undercut,
        "minimum_profile_shift_without_undercut": uc.minimum_profile_shift,
        "minimum_teeth_without_undercut": uc.minimum_teeth,
        "specific_sliding_root": _finite(sliding.root[index]),
        "specific_sliding_tip": _finite(sliding.tip[index]),
        "tip_land": {"transverse": L(land.thickness), "normal": L(land.normal_thickness),
                     "pointed_diameter": L(2 * land.pointed_radius), "pointed": land.is_pointed,
                     "below_minimum": thin, "minimum": L(TIP_LAND_MINIMUM_MODULES * g.module)},
    }
    if uc.is_undercut:
        warnings.append(f"{name} is undercut: profile shift {g.profile_shift:.5f} is below its minimum "
                        f"{uc.minimum_profile_shift:.5f} without undercut")
    if land.is_pointed:
        warnings.append(f"{name} has pointed teeth: the flanks meet at diameter {L(2 * land.pointed_radius):.6g} "
                        f"{g.length_unit}, inside the tip diameter {L(2 * g.tip_radius):.6g}; reduce its profile shift")
    elif thin:
        warnings.append(f"{name}: the normal tip land {L(land.normal_thickness):.6g} {g.length_unit} is below "
                        f"{TIP_LAND_MINIMUM_MODULES} m_n = {L(TIP_LAND_MINIMUM_MODULES * g.module):.6g} {g.length_unit}")
    try:
        span = geometry.span_measurement(g)
        out["span"] = {"teeth_spanned": span.teeth_spanned, "span_normal": L(span.span),
                       "span_transverse": L(span.transverse_span), "contact_radius": L(span.contact_radius),
                       "minimum_face_width": L(span.minimum_face_width)}
    except GeargenError as exc:
        out["span"] = None
        warnings.append(f"{name}: no span measurement: {exc}")
    try:
        try:
            pins = geometry.over_pins_measurement(g)  # pins touching at the reference circle, as geargen gear
        except GeargenError:
            # a strongly shifted gear's flank may not reach the reference circle: touch at the
            # middle of the working depth, r + x m_n, kept within the middle half of the usable flank
            start = max(geometry.involute_start_radius(g), g.base_radius)
            quarter = (g.tip_radius - start) / 4
            middle = min(max(g.reference_radius + g.profile_shift * g.module, start + quarter), g.tip_radius - quarter)
            pins = geometry.over_pins_measurement(g, geometry.ideal_pin_diameter(g, middle))
        out["over_pins"] = {"kind": pins.kind, "diameter": L(pins.pin_diameter), "dimension": L(pins.dimension),
                            "centre_radius": L(pins.centre_radius), "contact_radius": L(pins.contact_radius)}
    except GeargenError as exc:
        out["over_pins"] = None
        warnings.append(f"{name}: no measurement over pins: {exc}")
    return out


def _pair_warnings(mesh, backlash, overlap_known, warnings, L, unit) -> None:
    for i in (0, 1):
        if mesh.involute_interference[i]:
            warnings.append(f"involute interference: the tip of gear {2 - i} reaches below the usable involute of "
                            f"gear {i + 1}, which begins at diameter {L(2 * mesh.involute_start_radii[i]):.6g} {unit}")
        if mesh.tip_root_clearances[i] < 0:
            warnings.append(f"the tip of gear {i + 1} runs {L(-mesh.tip_root_clearances[i]):.6g} {unit} into the "
                            f"root of gear {2 - i}: shorten its tip")
    if mesh.transverse_contact_ratio < 1 and (not overlap_known or mesh.total_contact_ratio < 1):
        warnings.append(f"contact ratio {mesh.transverse_contact_ratio:.4f} < 1: the teeth do not mesh continuously")
    # rounding leaves a zero-backlash mesh a few 1e-13 mm either side of zero
    if backlash.circumferential_reference < -1e-9 * backlash.centre_distance:
        warnings.append("negative backlash: the teeth would have to interpenetrate at this centre distance")
    if not overlap_known:
        warnings.append("overlap and total contact ratio need --face-width (helical pair)")


# ---------------------------------------------------------------------------------------------
# The table
# ---------------------------------------------------------------------------------------------

_LABEL = 50


def _fixed(value, decimals: int) -> str:
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if not math.isfinite(value):
        return "-inf" if value < 0 else ("inf" if value > 0 else "nan")
    text = f"{value:.{decimals}f}"
    return text[1:] if text.startswith("-") and float(text) == 0 else text


def _row(label: str, *cells: str) -> str:
    return (f"{label:<{_LABEL}}" + "".join(f"{c:>14}" for c in cells)).rstrip()


def format_pair(data: dict) -> str:
    """The table of :func:`pair_data`'s dict, in its length unit."""
    u = data["length_unit"]
    n = LENGTH_DECIMALS[u]
    A = ANGLE_DECIMALS
    g1, g2 = data["gears"]
    helical = data["helix_angle_deg"] > 0
    if u == "in":
        pitch = f"normal diametral pitch {_compact(data['normal_diametral_pitch_per_in'])}/in"
    else:
        pitch = f"normal module {_compact(data['normal_module_mm'])} mm"
    kind = (f"helical, helix angle {_compact(data['helix_angle_deg'])} deg, gear 1 {data['hands'][0]}-hand"
            if helical else "spur")
    lines = [f"geargen pair: {g1['teeth']}/{g2['teeth']} teeth, {pitch}, pressure angle "
             f"{_compact(data['normal_pressure_angle_deg'])} deg, {kind}",
             f"lengths in {u}, angles in degrees; profile shifts {data['profile_shift_source']}", ""]

    def both(label, key, decimals, sub=None):
        cells = []
        for g in (g1, g2):
            v = g[key] if sub is None else (g[key] or {}).get(sub)
            cells.append(_fixed(v, decimals))
        lines.append(_row(label, *cells))

    lines.append(_row("", "gear 1", "gear 2"))
    both("teeth z", "teeth", 0)
    both("profile shift x (normal)", "profile_shift", 5)
    if any(data["thinning_circumferential"]):
        lines.append(_row(f"thinning, circumferential at d ({u})",
                          *(_fixed(v, n) for v in data["thinning_circumferential"])))
    both(f"reference diameter d ({u})", "reference_diameter", n)
    both(f"base diameter d_b ({u})", "base_diameter", n)
    both(f"tip diameter d_a ({u})", "tip_diameter", n)
    if any(g["tip_diameter_constant_clearance"] not in (None, g["tip_diameter"]) for g in (g1, g2)):
        both(f"  tip diameter for standard clearance ({u})", "tip_diameter_constant_clearance", n)
    both(f"root diameter d_f ({u})", "root_diameter", n)
    both(f"working pitch diameter d_w ({u})", "working_pitch_diameter", n)
    both("undercut", "undercut", 0)
    both("minimum profile shift without undercut", "minimum_profile_shift_without_undercut", 5)
    both(f"tip land, normal ({u})", "tip_land", n, "normal")
    both("specific sliding at the root", "specific_sliding_root", 3)
    both("span: teeth spanned k", "span", 0, "teeth_spanned")
    both(f"span W_k, normal ({u})", "span", n, "span_normal")
    what = "balls" if helical else "pins"  # GearPair: both gears spur or both helical
    both(f"{what[:-1]} diameter D ({u})", "over_pins", n, "diameter")
    both(f"dimension over {what} M ({u})", "over_pins", n, "dimension")

    c = data["centre_distance"]
    lines += ["", "Pair"]
    lines.append(_row(f"standard centre distance a ({u})", _fixed(c["standard"], n)))
    lines.append(_row(f"working centre distance a_w of the shifts ({u})", _fixed(c["working"], n)))
    lines.append(_row(f"operating centre distance a' ({u})", _fixed(c["operating"], n)) + f"   {c['operating_source']}")
    lines.append(_row("transverse pressure angle alpha_t (deg)", _fixed(data["transverse_pressure_angle_deg"], A)))
    lines.append(_row("working pressure angle, transverse (deg)", _fixed(data["working_pressure_angle_transverse_deg"], A)))
    if helical:
        lines.append(_row("working pressure angle, normal (deg)", _fixed(data["working_pressure_angle_normal_deg"], A)))
    cr, cc = data["contact_ratio"], data["contact_ratio_constant_clearance"]
    lines.append(_row("contact ratio: transverse eps_alpha", _fixed(cr["transverse"], 4)))
    lines.append(_row("               overlap eps_beta", _fixed(cr["overlap"], 4)))
    lines.append(_row("               total eps_gamma", _fixed(cr["total"], 4)))
    if cc is not None and cc["transverse"] != cr["transverse"]:
        lines.append(_row("  transverse, tips for standard clearance", _fixed(cc["transverse"], 4)))
    if data["shift_sum_for_zero_backlash"] is not None:
        lines.append(_row("x1 + x2 for zero backlash at a' (unthinned teeth)", _fixed(data["shift_sum_for_zero_backlash"], 5)))

    bl = data["backlash"]
    lines += ["", f"Backlash (positive = clearance), {bl['source']}"]
    lines.append(_row(f"circumferential, at the reference circles ({u})", _fixed(bl["circumferential_reference"], n)))
    lines.append(_row(f"circumferential, at the working pitch circles ({u})",
                      _fixed(bl["circumferential_working_pitch"], n)))
    lines.append(_row(f"along the line of action ({u})", _fixed(bl["line_of_action"], n)))
    lines.append(_row(f"normal to the flanks ({u})", _fixed(bl["normal"], n)))
    lines.append(_row("angular, the other gear held (arcmin)", *(_fixed(v, 3) for v in bl["angular_arcmin"])))

    _stiffness_lines(lines, data)

    rec = data["recommended_profile_shift"]
    lines += ["", f"Recommended profile shifts for the sum {_fixed(rec['shift_sum'], 5)}"]
    if rec["profile_shift"] is not None:
        lines.append(_row("profile shift x (normal)", *(_fixed(v, 5) for v in rec["profile_shift"])))
        lines.append(_row("specific sliding at the root", *(_fixed(v, 3) for v in rec["specific_sliding_root"])))
    lines.append(f"rule: {rec['rule']}")
    lines.append(f"result: {rec['message']}")
    if data["warnings"]:
        lines += ["", "Warnings"] + [f"- {w}" for w in data["warnings"]]
    return "\n".join(lines)


def _stiffness_lines(lines: list[str], data: dict) -> None:
    """ISO 6336's c_gamma beside Eq. 1's E / 11, per unit face width and for the mesh, then c' and its factors."""
    iso, eq1 = data["iso6336"], data["eq1"]
    lines += ["", f"Mesh stiffness: {iso['method']} beside Eq. 1 (E w / 11), E = "
                  f"{_compact(eq1['elastic_modulus_MPa'] * 1e-3)} GPa, {iso['load_correction']}"]
    lines.append(_row("", "ISO 6336", "Eq. 1"))
    lines.append(_row("per face width c_gamma_alpha | E/11, N/(mm um)", _fixed(iso["mesh_stiffness_N_per_mm_um"], 4),
                      _fixed(eq1["stiffness_per_face_width_N_per_mm_um"], 4)))
    if eq1["stiffness_whole_N_per_um"] is not None:
        lines.append(_row("whole mesh c_gamma_alpha b | E b/11, N/um",
                          _fixed(iso["mesh_stiffness_whole_N_per_um"], 2), _fixed(eq1["stiffness_whole_N_per_um"], 2)))
    lines.append(_row("single stiffness c', N/(mm um)", _fixed(iso["single_stiffness_N_per_mm_um"], 4)))
    lines.append(_row("mesh stiffness c_gamma_beta, N/(mm um)", _fixed(iso["mesh_stiffness_beta_N_per_mm_um"], 4)))
    lines.append(_row("theoretical single stiffness c'_th, N/(mm um)",
                      _fixed(iso["theoretical_single_stiffness_N_per_mm_um"], 4)))
    lines.append(_row("flexibility q', mm um/N", _fixed(iso["flexibility_q_prime_mm_um_per_N"], 6)))
    lines.append(_row(f"virtual teeth z_n (pinion = {iso['pinion']}, wheel)",
                      *(_fixed(v, 3) for v in iso["virtual_teeth_pinion_wheel"])))
    lines.append(_row("factors C_M, C_R, C_B", *(_fixed(iso[k], 4) for k in
                                                 ("correction_factor_C_M", "gear_blank_factor_C_R",
                                                  "basic_rack_factor_C_B"))))
    lines.append(_row("cos(beta), E/E_st, load factor", *(_fixed(iso[k], 4) for k in
                                                         ("helix_factor_cos_beta", "material_factor_E_over_E_st",
                                                          "load_factor"))))


def _compact(value: float) -> str:
    return f"{value:.10g}"
