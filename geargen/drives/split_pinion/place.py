"""The split pinion placed (Fig. 8): both pinions on one axis at the centre distance, the stiff one
driving on its counter-clockwise flank, the compliant one wound against it; the output keeps the
design's teeth, the pinions are thinned for the modelled backlash.
"""

from __future__ import annotations

import math
from fractions import Fraction

from geargen.core.involute import reference_tooth_thickness
from geargen.design.assembly import Design
from geargen.design.gear import GearSpec, with_changes
from geargen.errors import DesignError
from geargen.model.layout import GearPlacement, Layout, MeshPlacement, modelled_backlash, ratio_check, running_backlash
from geargen.profile.tooth import section_rotation
from geargen.units import LENGTH_SUFFIXES


def _split_pinion_centre_range(design: Design, s: dict, pinions, out: GearSpec) -> None:
    """Refuse a split pinion's ``layout.centre_distance`` outside the range its teeth can be placed
    at (naming the key, the cause and the range in the file's unit, and a distance in it): above
    the base circles' sum and below the tip circles' (beyond, the teeth do not reach each other);
    with a ``model_backlash`` rule, where the pinions, thinned at most to a quarter pitch (half their
    tooth), reach the modelled backlash (below: the teeth interfere even then) and where they are
    not already looser than it as designed (above). The backlash rises with the centre distance
    (B = T + 2 C_std (inv alpha_w - inv alpha)), so each bound is one root."""
    from scipy.optimize import brentq

    from geargen.core.synthesis import backlash_from_thickness_deficit
    c = s["centre_distance"]
    unit = design.length_unit
    k = LENGTH_SUFFIXES[unit]
    key = f"layout.centre_distance_{s['_units'].get('centre_distance', unit)}"
    standard = (pinions[0].teeth + out.teeth) * out.transverse_module / 2
    alpha = out.transverse_pressure_angle
    base = max(p.base_radius for p in pinions) + out.base_radius
    tips = min(p.tip_radius for p in pinions) + out.tip_radius
    lo_c, hi_c = base * (1 + 1e-12), tips * (1 - 1e-12)
    why_lo = why_hi = ""
    rule = s["model_backlash"]
    if rule != "as_designed":
        target = modelled_backlash(s["circumferential_backlash_min"], s["circumferential_backlash_max"], rule)
        for p in pinions:
            present = p.transverse_pitch - reference_tooth_thickness(p) - reference_tooth_thickness(out)
            deepest = present + p.transverse_pitch / 4 - p.thinning  # thinned to a quarter pitch

            def short(x, deficit):
                return float(backlash_from_thickness_deficit(deficit, x, standard, alpha)) - target
            if short(lo_c, deepest) < 0 < short(hi_c, deepest):
                root = brentq(short, lo_c, hi_c, args=(deepest,), xtol=1e-12)
                if root > lo_c:
                    lo_c, why_lo = root, (f"below it {p.name}'s teeth, thinned even to a quarter pitch, do not "
                                          f"reach the modelled {target / k:.6g} {unit} of backlash (they interfere)")
            if short(lo_c, present) < 0 < short(hi_c, present):
                root = brentq(short, lo_c, hi_c, args=(present,), xtol=1e-12)
                if root < hi_c:
                    hi_c, why_hi = root, (f"above it {p.name}'s teeth as designed already have more than the "
                                          f"modelled {target / k:.6g} {unit} of backlash ({rule}-range)")
    if lo_c <= c <= hi_c:
        return
    below = c < lo_c
    if below:
        cause = why_lo or f"at or inside the base circles' sum {base / k:.6g} {unit}: the teeth have no involute action"
    else:
        cause = why_hi or f"at or beyond the tip circles' sum {tips / k:.6g} {unit}: the teeth do not reach each other"
    fix = min(max(standard, lo_c), hi_c)
    raise DesignError(key, f"{c / k:.6g} {unit} is {'below' if below else 'above'} the range the split pinion can be "
                      f"placed in: {cause}",
                      f"[{lo_c / k:.6g}, {hi_c / k:.6g}] {unit}, e.g. {key} = {fix / k:.6g} "
                      + ("(standard)" if fix == standard else "(nearest the standard)"))


def place(design: Design, s: dict) -> Layout:
    from geargen.core.synthesis import backlash_from_thickness_deficit as backlash_at_centre_distance, mate_rotation
    stiff, compliant, out = (design.gear(s[k]) for k in ("pinion_stiff", "pinion_compliant", "output"))
    c = s["centre_distance"]
    lo, hi = s["circumferential_backlash_min"], s["circumferential_backlash_max"]  # given and ordered (on load)
    rule = s["model_backlash"]
    standard = (stiff.teeth + out.teeth) * out.transverse_module / 2
    alpha = out.transverse_pressure_angle
    _split_pinion_centre_range(design, s, (stiff, compliant), out)
    if rule == "as_designed":
        def b_of(p):
            t = p.transverse_pitch - reference_tooth_thickness(p) - reference_tooth_thickness(out)
            return float(backlash_at_centre_distance(t, c, standard, alpha))
        b_stiff, b_comp = b_of(stiff), b_of(compliant)
    else:
        b_stiff = b_comp = modelled_backlash(lo, hi, rule)
        # the output is shared: thin only the pinions (the output keeps the design's teeth)
        from geargen.core.synthesis import thickness_deficit_for_backlash as thickness_deficit
        need = thickness_deficit(b_stiff, c, standard, alpha)
        for label in ("stiff", "comp"):
            p = stiff if label == "stiff" else compliant
            present = p.transverse_pitch - reference_tooth_thickness(p) - reference_tooth_thickness(out)
            extra = need - present
            if extra < -1e-12:  # the centre distance's range (above) keeps it out
                raise DesignError(f"gears.{p.name}", "already thinner than the modelled backlash allows",
                                  "a smaller layout.centre_distance")
            p = with_changes(p, thinning=p.thinning + max(extra, 0.0))
            if label == "stiff":
                stiff = p
            else:
                compliant = p
    gap = s["loaded_flank_gap"]
    # axial stack on the pinion axis: the stiff pinion from z = 0, the compliant one above it
    z_stiff = 0.0
    z_comp = stiff.face_width + s["pinion_axial_gap"]
    z_out = 0.0
    rot_out = math.pi / out.teeth  # a tooth space of the output on +x, facing the pinion
    centre_p = (c, 0.0)
    # the stiff pinion drives on its counter-clockwise flank, the compliant one is wound against it
    towards_output = math.atan2(-centre_p[1], -centre_p[0])  # direction pinion -> output centre
    rot_stiff = float(mate_rotation(towards_output, rot_out, stiff.teeth, out.teeth,
                                    (b_stiff - 2 * gap) / stiff.reference_radius, +1))
    rot_comp = float(mate_rotation(towards_output, rot_out + section_rotation(out, z_comp - z_out),
                                   compliant.teeth, out.teeth, (b_comp - 2 * gap) / compliant.reference_radius, -1))
    gears = [GearPlacement("output", out, (0.0, 0.0), z_out, rot_out, "output", ("output",)),
             GearPlacement(s["pinion_stiff"], stiff, centre_p, z_stiff, rot_stiff, "split_pinion", ("pinion_stiff",)),
             GearPlacement(s["pinion_compliant"], compliant, centre_p, z_comp, rot_comp, "split_pinion",
                           ("pinion_compliant",))]
    by = {g.name: g for g in gears}
    meshes = []
    for part, spec, flank in ((s["pinion_stiff"], stiff, "pinion ccw (stiff path)"),
                              (s["pinion_compliant"], compliant, "pinion cw (compliant path)")):
        zl = max(by[part].face_z(spec)[0], by["output"].face_z(out)[0])
        zh = min(by[part].face_z(spec)[1], by["output"].face_z(out)[1])
        if zh - zl <= 0:
            raise DesignError("gears.output.face_width", f"the output's face does not reach {part}",
                              f">= {zh:.4g} mm")
        meshes.append(MeshPlacement(f"mesh_{part}", part, spec, "output", out, (zl + zh) / 2, lo, hi,
                                    running_backlash(spec, out, c), True, flank, c,
                                    ("layout.circumferential_backlash_min", "layout.circumferential_backlash_max")))
    notes = []
    thinning = {g.name: {"source": "design"} for g in gears}
    if rule != "as_designed":
        unit = design.length_unit
        notes.append(f"thinning derived for {rule}-range backlash: {s['pinion_stiff']} "
                     f"{stiff.thinning / LENGTH_SUFFIXES[unit]:.6g} {unit}, {s['pinion_compliant']} "
                     f"{compliant.thinning / LENGTH_SUFFIXES[unit]:.6g} {unit} (circumferential, at the reference "
                     "circle; the output keeps the design's teeth)")
        for name in (s["pinion_stiff"], s["pinion_compliant"]):
            thinning[name] = {"source": f"derived for {rule}-range backlash ([layout] model_backlash)"}
    return Layout(design=design, kind="split_pinion", gears=tuple(gears), meshes=tuple(meshes), settings=s,
                  ratio=ratio_check(design, s, Fraction(out.teeth, stiff.teeth), "input to output"),
                  notes=tuple(notes), thinning=thinning)


__all__ = ["place"]
