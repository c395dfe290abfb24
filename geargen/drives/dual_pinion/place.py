"""The dual pinion placed (Figs. 10-12): the centre synthesis of Eqs. 7-8 places input, clusters
and output so every mesh runs with its backlash where the preload carriage settles; the upstream
stages stand above it (pairs, or a planetary stage: geargen.drives.planetary); a drive whose
pinions slide into mesh (the beam-spring C-axis) is placed engaged or disengaged.
"""

from __future__ import annotations

import math
from dataclasses import replace
from fractions import Fraction

from geargen.core.involute import reference_tooth_thickness
from geargen.design.assembly import Design
from geargen.design.cluster import ClusterSpec
from geargen.design.gear import GearSpec
from geargen.drives.dual_pinion.keys import cluster_axial_gap
from geargen.errors import DesignError
from geargen.model.allowance import MeshRange, model_gears, model_source
from geargen.model.layout import GearPlacement, Layout, MeshPlacement, ratio_check, running_backlash
from geargen.profile.tooth import section_rotation
from geargen.units import LENGTH_SUFFIXES


def place(design: Design, s: dict) -> Layout:
    """The dual pinion placed (``s``: the [layout] settings, their ``position`` the one to place)."""
    wanted = s["position"]
    layout = replace(_place_dual_pinion(design, {**s, "position": "engaged"}, None), drive=s.get("drive_kind"))
    if not design.section("engagement"):
        return layout
    # the lead and stops of the sliding pinions come from the stiffness of the drive engaged
    # (its preload windup), whose shafts are placed by this very layout
    engagement = _engagement(layout)
    if wanted == "engaged":
        return replace(layout, engagement=engagement)
    return _place_dual_pinion(design, s, engagement)


#: most rounds of the teeth-and-carriage iteration, and the largest move (mm) of a placed centre distance in
#: the last round: a tenth of a nanometre, a millionth of the thinnest allowance
FIXED_POINT_ROUNDS = 30
FIXED_POINT_TOLERANCE = 1e-10


def _range_keys(n: int) -> tuple[str, str]:
    """The design keys of loop mesh ``n``'s backlash range (it holds where the mesh runs: mesh 1 where
    the preload carriage closes the loop)."""
    return f"synthesis.circumferential_backlash_min_mesh{n}", f"synthesis.circumferential_backlash_max_mesh{n}"


def _place_dual_pinion(design: Design, s: dict, engagement) -> Layout:
    from geargen.core.synthesis import place_gears, solve_loop, synthesize_centres
    from geargen.core.tolerance import appendix_error_budget, exact_error_budget
    from geargen.core.accuracy import error_budget_inputs
    from geargen.design.synthesis import synthesis_inputs
    from geargen.model.synthesis import SynthesisRun

    inputs = synthesis_inputs(design)
    syn = synthesize_centres(inputs).check()
    g_in, g_large, g_small, g_out = (design.gear(r) for r in ("input", "cluster_large", "cluster_small", "output"))
    rule = s["model_tooth_thickness"]
    design_notes: list[str] = []
    ranges = {m: (inputs.backlash(m, "min"), inputs.backlash(m, "max")) for m in (1, 2)}

    def at_design_centres(a: GearSpec, b: GearSpec, mesh: int) -> float:
        """The backlash the teeth have at the design's centre distance of ``mesh`` (what the
        synthesis places from)."""
        from geargen.core.synthesis import backlash_from_thickness_deficit
        t = a.transverse_pitch - reference_tooth_thickness(a) - reference_tooth_thickness(b)
        return float(backlash_from_thickness_deficit(t, inputs.centre_distance(mesh), inputs.standard_centre_distance(mesh),
                                                     inputs.pressure_angle(mesh)))

    designed = (g_in, g_large, g_small, g_out)

    def meshes_at(centres: dict[int, float]) -> list[MeshRange]:
        return [MeshRange(g_in, g_large, *ranges[1], centres[1], _range_keys(1)),
                MeshRange(g_small, g_out, *ranges[2], centres[2], _range_keys(2))]

    def placed_with(made: dict[str, GearSpec], gap: float):
        """The backlash of ``made`` at the design's centres, the placement, each mesh's placed centre distance."""
        m_in, m_large, m_small, m_out = (made[g.name] for g in designed)
        at_design = {1: at_design_centres(m_in, m_large, 1), 2: at_design_centres(m_small, m_out, 2)}
        placed = place_gears(syn, at_design[1], at_design[2], loaded_flank_gap=gap).check()
        pg = {g.name: g for g in placed.gears}
        return at_design, placed, {1: math.dist(pg["input"].centre, pg["cluster_large_a"].centre),
                                   2: math.dist(pg["cluster_small_a"].centre, pg["output"].centre)}

    # The allowances hold where the meshes run with every gear made at the middle of its allowance:
    # mesh 1 where the preload carriage then closes the loop, which moves with the teeth made, so teeth
    # and carriage are iterated to their fixed point (the carriage takes up an eighth of a change of the
    # teeth's backlash: the centre distance settles within 1e-10 mm in about eleven rounds). The
    # allowance is then the design's whatever point the model is made at; teeth made anywhere within it
    # move the carriage the way that keeps their backlash inside the range.
    allowance_at = {1: inputs.centre_distance_mesh1, 2: inputs.centre_distance_mesh2}
    try:
        for _ in range(FIXED_POINT_ROUNDS):
            modelled, placement, placed = placed_with(model_gears(design, "mid_tolerance", meshes_at(allowance_at)),
                                                      s["loaded_flank_gap"])
            moved = max(abs(placed[m] - allowance_at[m]) for m in (1, 2))
            allowance_at = placed
            if moved <= FIXED_POINT_TOLERANCE:
                break
        else:
            raise DesignError("synthesis.centre_distance_mesh1", f"the carriage's centre distance does not settle "
                              f"with the teeth made within their allowances (last move {moved:.3g} mm)",
                              "a backlash range the loop closes in")
    except DesignError:
        if rule != "as_designed":
            raise
        allowance_at = {1: math.nan, 2: math.nan}  # teeth as designed are placed; the check finds no allowance
    if rule == "as_designed":
        modelled = {1: at_design_centres(g_in, g_large, 1), 2: at_design_centres(g_small, g_out, 2)}
    else:
        made = model_gears(design, rule, meshes_at(allowance_at))
        modelled, placement, _ = placed_with(made, s["loaded_flank_gap"])
        g_in, g_large, g_small, g_out = (made[g.name] for g in designed)
    if rule == "as_designed":
        # teeth as specified may have no backlash (or interfere): place them touching on both flanks,
        # the checks report it; the solids' flank gap cannot exceed half the backlash there is
        modelled = {m: max(b, 0.0) for m, b in modelled.items()}
        gap = min(s["loaded_flank_gap"], min(modelled.values()) / 2)
        if gap < s["loaded_flank_gap"]:
            k = LENGTH_SUFFIXES[design.length_unit]
            design_notes.append(f"loaded flank gap of the solids reduced to {gap / k:.4g} {design.length_unit} "
                                f"(half the smallest backlash of the gears as specified)")
            s = {**s, "loaded_flank_gap": gap}
        placement = place_gears(syn, modelled[1], modelled[2], loaded_flank_gap=gap).check()
    errors = error_budget_inputs(design)
    budget = exact = None
    if errors is not None:
        budget = appendix_error_budget(syn, errors)
        exact = exact_error_budget(syn, errors)
    run = SynthesisRun(design_name=design.name, design_sha256=design.sha256, length_unit=design.length_unit,
                       inputs=inputs, synthesis=syn,
                       exact_min_backlash=solve_loop(syn, ranges[1][0], ranges[2][0]).check(),
                       placement=place_gears(syn).check(), modelled_backlash=(modelled[1], modelled[2]),
                       placement_modelled=placement, errors=errors, budget=budget,
                       exact_budget=exact if exact is not None and exact.success else None)

    # heights: the cluster's large gear from z = 0, the input centred on it (or offset), the
    # output centred on the cluster's small gear
    gap = cluster_axial_gap(s, g_large, g_small)
    cluster = ClusterSpec(g_large, g_small, axial_gap=gap, relative_phase=0.0, name="cluster")
    z_large = 0.0
    z_small = cluster.small_gear_z
    z_in = (z_large + (g_large.face_width - g_in.face_width) / 2 if s["input_face_offset"] is None
            else z_large - s["input_face_offset"])
    z_out = z_small + (g_small.face_width - g_out.face_width) / 2

    pg = {g.name: g for g in placement.gears}
    rot_in = pg["input"].rotation + section_rotation(g_in, z_in - z_large)
    rot_out = pg["output"].rotation + section_rotation(g_out, z_out - z_small)
    gears: list[GearPlacement] = [
        GearPlacement("output", g_out, pg["output"].centre, z_out, rot_out, "output", ("output",)),
        GearPlacement("input", g_in, pg["input"].centre, z_in, rot_in, "carriage", ("input",)),
    ]
    shifts: dict[str, float] = {}
    position = s["position"]
    notes = list(design_notes)
    for side in ("a", "b"):
        centre = pg[f"cluster_large_{side}"].centre
        rot = pg[f"cluster_large_{side}"].rotation
        shift = 0.0
        if position == "disengaged":
            if engagement is None:
                raise DesignError("layout.position", "'disengaged' needs an [engagement] section", "'engaged'")
            # both pinions against their retracted stops: cluster A leads, cluster B trails by the lead
            stop = engagement.leader_retracted_stop if side == "a" else engagement.trailer_retracted_stop
            shift = stop  # engaging is +z: the pinions slide out along -z, away from the output
            rot += section_rotation(g_large, shift)  # the large gear stays in mesh with the input
        shifts[f"cluster_{side}"] = shift
        if s["cluster"] == "one_piece":
            gears.append(GearPlacement(f"cluster_{side}", cluster, centre, z_large + shift, rot, f"cluster_{side}",
                                       ("cluster_large", "cluster_small")))
        else:
            gears.append(GearPlacement(f"cluster_large_{side}", g_large, centre, z_large + shift, rot,
                                       f"cluster_{side}", ("cluster_large",)))
            gears.append(GearPlacement(f"cluster_small_{side}", g_small, centre, z_small + shift, rot,
                                       f"cluster_{side}", ("cluster_small",)))
    if position == "disengaged":
        notes.append("disengaged position: both dual pinions slid out of the output gear against their retracted "
                     f"stops (cluster B trails by the lead {engagement.lead:.4g} mm)")

    by_name = {g.name: g for g in gears}

    def part_of(role: str, side: str) -> tuple[str, GearSpec]:
        name = f"cluster_{side}" if s["cluster"] == "one_piece" else f"cluster_{'large' if role == 'cluster_large' else 'small'}_{side}"
        gp = by_name[name]
        spec = (gp.spec.large if role == "cluster_large" else gp.spec.small) if isinstance(gp.spec, ClusterSpec) else gp.spec
        return name, spec

    meshes: list[MeshPlacement] = []
    for side in ("a", "b"):
        # mesh 1: the input (gear 1) turned against the cluster's large gear
        name, spec = part_of("cluster_large", side)
        lo = max(by_name["input"].face_z(g_in)[0], by_name[name].face_z(spec)[0])
        hi = min(by_name["input"].face_z(g_in)[1], by_name[name].face_z(spec)[1])
        c = math.dist(by_name["input"].centre, by_name[name].centre)
        meshes.append(MeshPlacement(f"mesh1_{side}", "input", g_in, name, spec, (lo + hi) / 2, *ranges[1],
                                    running_backlash(g_in, spec, c), True, "input ccw" if side == "a" else "input cw",
                                    c, _range_keys(1), allowance_at[1]))
        # mesh 2: the cluster's small gear (gear 1) against the output
        name, spec = part_of("cluster_small", side)
        lo = max(by_name[name].face_z(spec)[0], by_name["output"].face_z(g_out)[0])
        hi = min(by_name[name].face_z(spec)[1], by_name["output"].face_z(g_out)[1])
        engaged = hi - lo > 1e-9
        c = math.dist(by_name[name].centre, by_name["output"].centre)
        meshes.append(MeshPlacement(f"mesh2_{side}", name, spec, "output", g_out,
                                    (lo + hi) / 2 if engaged else by_name[name].face_z(spec)[0],
                                    *ranges[2], running_backlash(spec, g_out, c), engaged,
                                    "cluster cw" if side == "a" else "cluster ccw", c, _range_keys(2),
                                    allowance_at[2]))
    train = Fraction(g_large.teeth, g_in.teeth) * Fraction(g_out.teeth, g_small.teeth)
    stage_gears, stage_meshes, stage_notes = _place_stages(design, s, gears, rule)
    gears += stage_gears
    meshes += stage_meshes
    notes += stage_notes
    thinning = {g.name: {"source": model_source(rule)} for g in gears}
    if rule != "as_designed":
        notes.insert(0, f"thinning made at {rule} of each allowance (where its mesh runs): "
                     + ", ".join(f"{n} {g.thinning / LENGTH_SUFFIXES[design.length_unit]:.6g} {design.length_unit}"
                                 for n, g in (("input", g_in), ("cluster_large", g_large),
                                              ("cluster_small", g_small), ("output", g_out)))
                     + " (circumferential, at the reference circle)")
    return Layout(design=design, kind="dual_pinion", gears=tuple(gears), meshes=tuple(meshes), position=position,
                  synthesis=run, carriage_x=placement.carriage_x, carriage_travel=s["carriage_travel"],
                  engagement=engagement, axial_shift=shifts, ratio=ratio_check(design, s, train, "encoder to output"),
                  notes=tuple(notes), settings=s, placement=placement, thinning=thinning)


def stage_levels(design, loop_gears) -> float:
    """Height (mm) where the lowest upstream stage's gears may start: above the input gear, its
    upper bearing, the preload carriage's arm that holds it and the intermediate shafts' lower
    bearings standing on the arm; and above the link cover that holds the loop's upper bearings
    (the stage gears turn over it). ``loop_gears``: the placed loop gears (the carriage hardware
    of ``[parts]`` sizes the rest)."""
    from geargen.design.parts import parts_settings
    from geargen.drives.dual_pinion.shafts import carriage_arm_top
    from geargen.model.shafts import loop_shafts
    p = parts_settings(design)
    for key in ("stage_bearing_width", "input_bearing_width", "carriage_plate_thickness"):
        if p.get(key) is None:
            raise DesignError(f"parts.{key}", "missing: the upstream stages stand on the preload carriage's arm",
                              "a length")
    gap = p["bearing_clearance"]
    shafts = loop_shafts(loop_gears, p)
    z_arm_top = carriage_arm_top(shafts["input"], p)
    z_cover_top = max(shafts[k].z_hi for k in ("output", "cluster_a", "cluster_b")) + p["link_floor"]
    return max(z_arm_top + p["stage_bearing_width"], z_cover_top) + gap


def _place_stages(design: Design, s: dict, loop_gears: list[GearPlacement], rule: str):
    """The upstream stages (:mod:`geargen.design.stages`) placed: from the input's shaft
    outwards, each stage's driver at its centre distance in its direction from the driven gear;
    stacked in levels above the carriage arm, the last stage lowest, a ``bearing_clearance``
    between levels. Each pair sits in the middle of its play (a stage is not preloaded).
    Returns (gear placements, meshes, notes)."""
    from geargen.design.parts import parts_settings
    from geargen.design.stages import stages
    stage_list = stages(design)
    if not stage_list:
        return [], [], []
    gap = parts_settings(design)["bearing_clearance"]
    level = stage_levels(design, loop_gears)
    centre = next(g for g in loop_gears if g.name == "input").centre
    gears: list[GearPlacement] = []
    meshes: list[MeshPlacement] = []
    notes: list[str] = []
    for st in reversed(stage_list):
        if st.kind == "planetary":
            from geargen.drives.planetary.place import place_planetary_stage
            placed = place_planetary_stage(design, st, centre, level, rule)
            gears += placed.gears
            meshes += placed.meshes
            notes += placed.notes
            level += placed.height + gap
            continue
        driver, driven = design.gear(st.driver), design.gear(st.driven)
        keys = (f"stages.{st.name}.circumferential_backlash_min", f"stages.{st.name}.circumferential_backlash_max")
        made = model_gears(design, rule, [MeshRange(driver, driven, st.backlash_min, st.backlash_max, st.centre_distance,
                                                    keys)])
        driver, driven = made[driver.name], made[driven.name]
        height = max(driver.face_width, driven.face_width)
        z_driver = level + (height - driver.face_width) / 2
        z_driven = level + (height - driven.face_width) / 2
        driven_centre = centre
        driver_centre = (centre[0] + st.centre_distance * math.cos(st.direction),
                         centre[1] + st.centre_distance * math.sin(st.direction))
        # the driver's tooth 0 points at the driven gear, which shows it a tooth space: the middle
        # of the play, in the level's lowest plane (carried to each gear's own face by its helix)
        r_driver = st.direction + math.pi - section_rotation(driver, level - z_driver)
        r_driven = st.direction + math.pi / driven.teeth - section_rotation(driven, level - z_driven)
        group = f"stage_{st.name}"
        gears.append(GearPlacement(st.driven, driven, driven_centre, z_driven, r_driven, group, ("stage_driven",)))
        gears.append(GearPlacement(st.driver, driver, driver_centre, z_driver, r_driver, group, ("stage_driver",)))
        lo = max(z_driver, z_driven)
        hi = min(z_driver + driver.face_width, z_driven + driven.face_width)
        meshes.append(MeshPlacement(f"stage_{st.name}", st.driver, driver, st.driven, driven, (lo + hi) / 2,
                                    st.backlash_min, st.backlash_max,
                                    running_backlash(driver, driven, st.centre_distance), True, "", st.centre_distance,
                                    keys))
        if rule != "as_designed":
            notes.append(f"stage {st.name}: thinning made at {rule} of each allowance: {st.driver} "
                         f"{driver.thinning / LENGTH_SUFFIXES[design.length_unit]:.6g}, {st.driven} "
                         f"{driven.thinning / LENGTH_SUFFIXES[design.length_unit]:.6g} {design.length_unit}")
        centre = driver_centre
        level += height + gap
    return gears, meshes, notes



def _engagement(layout: Layout):
    """The lead and travel stops of helical pinions sliding axially into mesh (the stiffness
    summary's helper, with the shafts placed by the engaged ``layout``)."""
    from geargen.core.stiffness import stiffness_summary
    from geargen.model.analysis import beam_supports, placed_components
    design = layout.design
    components = placed_components(design, layout)
    # The long pinion's column is clamped in the housing block, whose height follows the strokes,
    # which follow the preload windup, which follows k3 on that column: a fixed point. The column's
    # stiffness changes little with a stroke (a few tenths of a mm on a 250 mm arm), so it settles
    # in a few rounds; started on rigid supports.
    engagement = None
    for _ in range(20):
        try:
            summary = stiffness_summary(design, components=components, beam_supports=beam_supports(layout, engagement))
        except DesignError as e:
            if engagement is not None or not e.field.startswith("engagement."):
                raise
            # refused already with the column rigid: on the real column the loop winds up more
            raise DesignError(e.field, f"{e.problem}, with the long pinion's column taken as rigid (on the column "
                              "it needs more)", e.allowed) from None
        if summary.engagement is None:
            raise DesignError("engagement", "missing", "an [engagement] section for the sliding pinions")
        if engagement is not None and abs(summary.engagement.lead - engagement.lead) <= 1e-9:
            return summary.engagement
        engagement = summary.engagement
    raise DesignError("engagement", f"the lead does not settle with the drive column's stiffness (last "
                      f"{engagement.lead:.6g} mm)", "a stiffer column: parts.drive_column_thickness_mm")


__all__ = ["place", "stage_levels"]
