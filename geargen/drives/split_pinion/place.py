"""The split pinion placed (Fig. 8): both pinions on one axis at the centre distance, the stiff one
driving on its counter-clockwise flank, the compliant one wound against it; every gear, the shared
output too, is made at the ``model_tooth_thickness`` point of its allowance
(:mod:`geargen.model.allowance`: the stiff mesh splits its thinning equally between the stiff
pinion and the output, the compliant pinion takes the rest of its own mesh's).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from geargen.design.assembly import Design
from geargen.design.gear import GearSpec
from geargen.errors import DesignError
from geargen.model.allowance import MeshRange, decide, model_gears, model_source
from geargen.model.layout import GearPlacement, Layout, MeshPlacement, ratio_check, running_backlash
from geargen.profile.tooth import section_rotation
from geargen.units import LENGTH_SUFFIXES, length_text


#: the design keys of each pinion's mesh's backlash range (without their unit suffix)
RANGE_KEYS = ("layout.circumferential_backlash_min", "layout.circumferential_backlash_max")

#: centre distances tried across the range the teeth reach, to find where the allowances exist
#: when the design's does not (a refusal's path only); the ends are then refined by bisection
CENTRE_GRID = 2001


def _mesh_ranges(s: dict, stiff: GearSpec, compliant: GearSpec, out: GearSpec, centre_distance: float):
    """The two meshes as their allowances are decided: the stiff one first (it decides the shared
    output's), both with the design's range at ``centre_distance``."""
    lo, hi = s["circumferential_backlash_min"], s["circumferential_backlash_max"]
    return [MeshRange(stiff, out, lo, hi, centre_distance, RANGE_KEYS),
            MeshRange(compliant, out, lo, hi, centre_distance, RANGE_KEYS)]


def _split_pinion_centre_range(design: Design, s: dict, pinions, out: GearSpec) -> None:
    """Refuse a split pinion's ``layout.centre_distance`` outside the range its teeth can be placed
    at (naming the key, the cause and the range in the file's unit, and a distance in it): above
    the base circles' sum and below the tip circles' (beyond, the teeth do not reach each other);
    with a ``model_tooth_thickness`` point, where every gear has an allowance it can be made to
    (:func:`geargen.model.allowance.decide`): above, the unthinned teeth at the smallest centre
    distance already have more backlash than the range's minimum; below, the range's maximum asks
    for a thinnest tooth that is pointed or thinned past a quarter pitch (the teeth interfere).
    Each gear's thinning falls as the centre distance grows, so the allowances exist on one
    interval, whose ends are bisected."""
    c = s["centre_distance"]
    unit = design.length_unit
    k = LENGTH_SUFFIXES[unit]
    key = f"layout.centre_distance_{s['_units'].get('centre_distance', unit)}"
    standard = (pinions[0].teeth + out.teeth) * out.transverse_module / 2
    base = max(p.base_radius for p in pinions) + out.base_radius
    tips = min(p.tip_radius for p in pinions) + out.tip_radius
    lo_c, hi_c = base * (1 + 1e-12), tips * (1 - 1e-12)
    why_lo = why_hi = ""

    def refusal(x: float) -> DesignError | None:
        try:
            decide(design, _mesh_ranges(s, *pinions, out, x))
        except DesignError as exc:
            return exc
        return None

    if s["model_tooth_thickness"] != "as_designed" and not (lo_c <= c <= hi_c and refusal(c) is None):
        grid = np.linspace(lo_c, hi_c, CENTRE_GRID)
        fits = [refusal(x) is None for x in grid]
        if not any(fits):  # no centre distance helps (e.g. the tolerance eats the range): its own key's refusal
            raise refusal(c)
        first = fits.index(True)
        last = len(fits) - 1 - fits[::-1].index(True)

        def edge(good: float, bad: float) -> float:
            for _ in range(60):
                mid = 0.5 * (good + bad)
                good, bad = (mid, bad) if refusal(mid) is None else (good, mid)
            return good
        if first > 0:
            lo_c = edge(grid[first], grid[first - 1])
            why_lo = (f"below it the range's maximum asks for teeth thinner than a gear can have (the teeth "
                      f"interfere): {refusal(grid[first - 1]).problem}")
        if last < len(grid) - 1:
            hi_c = edge(grid[last], grid[last + 1])
            why_hi = (f"above it the unthinned teeth at the smallest centre distance already have more backlash "
                      f"than the range's minimum: {refusal(grid[last + 1]).problem}")
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
    from geargen.core.synthesis import mate_rotation
    stiff, compliant, out = (design.gear(s[k]) for k in ("pinion_stiff", "pinion_compliant", "output"))
    c = s["centre_distance"]
    lo, hi = s["circumferential_backlash_min"], s["circumferential_backlash_max"]  # given and ordered (on load)
    rule = s["model_tooth_thickness"]
    _split_pinion_centre_range(design, s, (stiff, compliant), out)
    # the stiff mesh decides the output's allowance (split equally with the stiff pinion), the
    # compliant pinion takes the rest of its own mesh's: the model is made at one point of each
    made = model_gears(design, rule, _mesh_ranges(s, stiff, compliant, out, c))
    stiff, compliant, out = (made[g.name] for g in (stiff, compliant, out))
    b_stiff, b_comp = running_backlash(stiff, out, c), running_backlash(compliant, out, c)
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
                              f">= {length_text(zh, design.length_unit)}")
        meshes.append(MeshPlacement(f"mesh_{part}", part, spec, "output", out, (zl + zh) / 2, lo, hi,
                                    running_backlash(spec, out, c), True, flank, c, RANGE_KEYS))
    notes = []
    thinning = {g.name: {"source": model_source(rule)} for g in gears}
    if rule != "as_designed":
        unit = design.length_unit
        notes.append(f"thinning made at {rule} of each allowance: " + ", ".join(
            f"{g.name} {g.thinning / LENGTH_SUFFIXES[unit]:.6g} {unit}" for g in (stiff, compliant, out))
            + " (circumferential, at the reference circle)")
    return Layout(design=design, kind="split_pinion", gears=tuple(gears), meshes=tuple(meshes), settings=s,
                  ratio=ratio_check(design, s, Fraction(out.teeth, stiff.teeth), "input to output"),
                  notes=tuple(notes), thinning=thinning)


__all__ = ["place"]
