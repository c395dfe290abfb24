"""The resolved drive: one place where every gear's final teeth, centre, height and phase are decided.

Every command starts here (``geargen synth``, ``check``, ``stiffness``, ``build`` and ``fit``
with ``assembly =``): :func:`resolve` turns a loaded design into a :class:`Layout` - each
gear's tooth thickness as modelled (the thinning the design states, or the thinning derived for
the backlash ``[layout] model_backlash`` asks for, said so in ``notes``), every centre, height
and rotation, each mesh's operating centre distance and backlash - and nothing downstream
re-derives a placement. :meth:`Layout.to_dict` is what is written beside every export.

Frame: the output gear's centre is the origin, +x the symmetry line towards the input, +z the
gear axes (as :mod:`geargen.core.synthesis`). A gear is placed by ``centre`` (x, y), ``z``
(height of its local z = 0 face) and ``rotation`` (about its own axis; its tooth 0 is on local
+x at local z = 0). For helical gears the synthesis' rotations hold in one transverse plane per
mesh (the cluster's own gear faces); the mate's rotation is carried to its own z = 0 face
through the helix (``section_rotation``).

Tooth thickness. ``model_backlash`` = "as_designed" keeps the gear tables' thinning; "mid",
"max" or "min" derive it so each mesh has that backlash of the design range *where it runs*:
the preload carriage settles where the loop closes, so mesh 1's centre distance is not quite the
design's, and the modelled thickness is iterated until the backlash there is the one asked for.
The thickness deficit comes from :mod:`geargen.core.synthesis` (``thickness_deficit_for_backlash``)
and is split between the two gears of a mesh as the design splits it (equally when it gives none).
Without a ``[layout] model_backlash`` the gear tables decide: "as_designed" when any gear of the
train states its thinning, else "mid".
"""

from __future__ import annotations

import importlib
import math
from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import Any

from geargen.core.involute import reference_tooth_thickness
from geargen.design.assembly import Design
from geargen.design.cluster import ClusterSpec
from geargen.design.gear import GearSpec, with_changes
from geargen.design.layout import LAYOUT_KINDS, MODEL_BACKLASH, POSITIONS
from geargen.errors import DesignError
from geargen.profile.tooth import section_rotation
from geargen.units import LENGTH_SUFFIXES

@dataclass(frozen=True)
class GearPlacement:
    """One toothed part of the assembly (a gear, or a one-piece cluster), placed (mm, rad)."""

    name: str
    spec: GearSpec | ClusterSpec
    centre: tuple[float, float]
    z: float
    rotation: float
    group: str = "gears"
    roles: tuple[str, ...] = ()

    @property
    def gears(self) -> tuple[GearSpec, ...]:
        """The toothed bodies of the part: one gear, or a cluster's large and small gear."""
        if isinstance(self.spec, ClusterSpec):
            return (self.spec.large, self.spec.small)
        return (self.spec,)

    def face_z(self, gear: GearSpec) -> tuple[float, float]:
        """World z range of the toothed face of ``gear`` (one of :attr:`gears`)."""
        if isinstance(self.spec, ClusterSpec) and gear is self.spec.small:
            z0 = self.z + self.spec.small_gear_z
            return z0, z0 + gear.face_width
        return self.z, self.z + gear.face_width

    def rotation_at(self, gear: GearSpec, z: float) -> float:
        """Rotation of ``gear``'s transverse section at world height ``z`` (tooth 0 centreline)."""
        z0 = self.face_z(gear)[0]
        if getattr(gear, "kind", "external") == "rack":
            if gear.is_helical:  # a helical rack's section slides along it: no rotation to give
                raise ValueError(f"{self.name}: a helical rack's section is not a rotation")
            return self.rotation
        return self.rotation + section_rotation(gear, z - z0)

    @property
    def height(self) -> tuple[float, float]:
        lo = min(self.face_z(g)[0] for g in self.gears)
        hi = max(self.face_z(g)[1] for g in self.gears)
        return lo, hi


@dataclass(frozen=True)
class MeshPlacement:
    """One mesh to check: gear 1 (turned by the checker) and gear 2 (held), their placements.

    ``plane`` is the world height of the checked transverse section (the middle of the faces'
    overlap); ``backlash_min``/``backlash_max`` the design range of the circumferential backlash
    (mm, transverse, at the reference pitch circles, positive clearance); ``modelled_backlash``
    what the modelled teeth give where the mesh runs (at ``centre_distance``, the distance of
    the placed centres), in the same kind. ``engaged`` False: the pinions are slid out of this
    mesh (disengaged position), only their axial clearance is checked.
    """

    name: str
    part1: str
    gear1: GearSpec
    part2: str
    gear2: GearSpec
    plane: float
    backlash_min: float
    backlash_max: float
    modelled_backlash: float
    engaged: bool = True
    working_flank: str = ""
    centre_distance: float = math.nan


@dataclass(frozen=True)
class Layout:
    """The resolved drive: where every gear is, its teeth as modelled, and what each mesh must
    satisfy (mm, rad). Immutable: every command reads the same one (see the module docstring).

    ``thinning``: per gear part name, the circumferential tooth thinning at the reference circle
    the solids are built with (mm) and where it comes from (``"design"`` or ``"derived for <rule>
    backlash"``). ``placement``: the synthesis' placement of the modelled gears
    (:class:`geargen.core.synthesis.Placement`) for a dual-pinion drive.
    """

    design: Design
    kind: str
    gears: tuple[GearPlacement, ...]
    meshes: tuple[MeshPlacement, ...]
    position: str = "engaged"
    synthesis: Any = None  # geargen.model.synthesis.SynthesisRun for a dual-pinion drive
    carriage_x: float | None = None
    carriage_travel: float | None = None
    engagement: Any = None  # geargen.core.flexures.HelicalEngagement when the pinions slide
    axial_shift: dict[str, float] = field(default_factory=dict)  # part -> slide along +z (disengaged)
    ratio: dict[str, Any] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    settings: dict[str, Any] = field(default_factory=dict)
    placement: Any = None
    thinning: dict[str, dict[str, Any]] = field(default_factory=dict)
    # what a drive kind placed by its own module reports about itself (mm, rad, N; e.g. the axial
    # preload's slide, spring force and stiffnesses): written beside every export, in internal units
    drive_report: dict[str, Any] = field(default_factory=dict)
    # the non-gear parts and every joint (geargen.model.components.Hardware), laid out by the
    # drive kind's hardware when the drive is resolved (geargen.drives.resolve); None: no hardware
    hardware: Any = None

    def gear(self, name: str) -> GearPlacement:
        for g in self.gears:
            if g.name == name:
                return g
        raise KeyError(name)

    def mesh(self, name: str) -> MeshPlacement:
        for m in self.meshes:
            if m.name == name:
                return m
        raise KeyError(name)

    def to_dict(self) -> dict[str, Any]:
        """The resolved values in the design's length unit (angles in rad and deg): what is
        written beside every export and what every command reports."""
        unit = self.design.length_unit
        k = 1.0 / LENGTH_SUFFIXES[unit]
        gears = []
        for g in self.gears:
            gears.append({"name": g.name, "centre": [g.centre[0] * k, g.centre[1] * k], "z": g.z * k,
                          "rotation_rad": g.rotation, "rotation_deg": math.degrees(g.rotation),
                          "teeth": [b.teeth for b in g.gears],
                          "thinning_circumferential": [b.thinning * k for b in g.gears],
                          "thinning_source": self.thinning.get(g.name, {}).get("source", "design")})
        meshes = []
        for m in self.meshes:
            meshes.append({"name": m.name, "gear1": m.part1, "gear2": m.part2, "engaged": m.engaged,
                           "centre_distance": m.centre_distance * k,
                           "backlash": m.modelled_backlash * k,
                           "backlash_design_min": m.backlash_min * k, "backlash_design_max": m.backlash_max * k,
                           "working_flank": m.working_flank, "plane_z": m.plane * k})
        return {"length_unit": unit, "kind": self.kind, "position": self.position,
                "backlash_kind": BACKLASH_KIND,
                "rotation_convention": "tooth 0 centreline of the gear's section at its own z = 0 face, "
                                       "CCW from +x about the gear's centre",
                "loaded_flank_gap": (self.settings.get("loaded_flank_gap") or 0.0) * k,
                "carriage_x": None if self.carriage_x is None else self.carriage_x * k,
                "gears": gears, "meshes": meshes, "notes": list(self.notes),
                "defaulted": {d.key: d.value for d in self.design.defaulted},
                **({"drive_report (mm, rad, N, N mm)": self.drive_report} if self.drive_report else {}),
                **({"hardware": self.hardware.to_dict(1.0 / k)} if self.hardware is not None else {})}


#: the one kind of backlash the resolved model, the checks' design range and the reports share
BACKLASH_KIND = "circumferential, transverse, at the reference pitch circle of gear 1 (j_bt / cos alpha_t)"


def layout_settings(design: Design) -> dict[str, Any]:
    """``[layout]`` validated (:func:`geargen.design.layout.layout_settings`; internal units)."""
    from geargen.design.layout import layout_settings as read
    return read(design)


def _modelled_backlash(lo: float, hi: float, rule: str) -> float:
    return {"mid": (lo + hi) / 2, "max": hi, "min": lo}[rule]


def _thin_pair(a: GearSpec, b: GearSpec, backlash: float, centre_distance: float, where: str) -> tuple[GearSpec, GearSpec]:
    """``a`` and ``b`` with the tooth thinning that makes the mesh's backlash ``backlash`` at
    ``centre_distance``: it replaces any the design gives, shared between the gears as the
    design shares it (equally when it gives none)."""
    from geargen.core.synthesis import thickness_deficit_for_backlash

    share_a = 0.5 if a.thinning + b.thinning <= 0 else a.thinning / (a.thinning + b.thinning)
    a0, b0 = with_changes(a, thinning=0.0), with_changes(b, thinning=0.0)
    standard = (a.teeth + b.teeth) * a.transverse_module / 2
    needed = thickness_deficit_for_backlash(backlash, centre_distance, standard, a.transverse_pressure_angle)
    present = a0.transverse_pitch - reference_tooth_thickness(a0) - reference_tooth_thickness(b0)
    extra = needed - present
    if extra < -1e-12:
        raise DesignError(where, f"the unthinned teeth already have more than {backlash:.4g} mm of backlash at "
                          f"{centre_distance:.6g} mm", "a smaller centre distance or a larger backlash range")
    extra = max(extra, 0.0)
    return with_changes(a0, thinning=extra * share_a), with_changes(b0, thinning=extra * (1 - share_a))


def _ratio_check(design: Design, settings: dict, train_ratio: Fraction, what: str) -> dict[str, Any]:
    """The exact ratio from encoder to output: the upstream stages (the gears of ``[stages]``, or
    ``[layout] upstream_stages`` as driver and driven teeth) times the train."""
    total = Fraction(train_ratio)
    described = []
    from geargen.design.stages import stages
    stage_list = stages(design)
    for st in stage_list:
        total *= st.ratio(design)
        if st.kind == "planetary":  # ring fixed, sun in, carrier out
            described.append(f"(1 + {design.gear(st.ring).teeth}/{design.gear(st.sun).teeth})")
        else:
            described.append(f"{design.gear(st.driven).teeth}/{design.gear(st.driver).teeth}")
    for driver, driven in () if stage_list else settings["upstream_stages"]:
        total *= Fraction(driven, driver)
        described.append(f"{driven}/{driver}")
    required = settings["required_ratios"]
    ok = (not required) or any(total == Fraction(r) for r in required)
    text = " x ".join(described + [f"{train_ratio}"]) + f" = {total}"
    return {"train": train_ratio, "total": total, "required": list(required), "ok": ok,
            "text": text, "what": what}


#: layout kinds placed by their own module ("module:function(design, settings) -> Layout"); the
#: dual- and split-pinion drives are placed here
PLACERS: dict[str, str] = {
    "rack_dual_pinion": "geargen.model.rack_drive:place_rack_drive",
    "axial_preload": "geargen.model.axial_drive:place_axial_preload",
}


def is_drive(design: Design) -> bool:
    """Whether the design describes a drive to resolve (a [layout] or a [synthesis]); a design
    without either only declares gear pairs to check ([checks] meshes) or a gear."""
    return bool(design.section("layout") or design.section("synthesis"))


def place(design: Design, position: str | None = None) -> Layout:
    """The gears of the drive placed (:class:`Layout` without its hardware): final teeth, centres,
    heights and rotations of every gear, and the meshes to check. ``position`` overrides ``[layout]
    position``. :func:`geargen.drives.resolve` adds the hardware."""
    settings = layout_settings(design)
    if position is not None:
        if position not in POSITIONS:
            raise DesignError("--position", f"{position!r} is not a valid choice", ", ".join(map(repr, POSITIONS)))
        if position == "disengaged" and not design.section("engagement"):
            raise DesignError("--position", "'disengaged' needs an [engagement] section", "'engaged'")
        settings["position"] = position
    if settings["kind"] == "split_pinion":
        return _place_split_pinion(design, settings)
    if settings["kind"] in PLACERS:
        module, function = PLACERS[settings["kind"]].split(":")
        return getattr(importlib.import_module(module), function)(design, settings)
    wanted = settings["position"]
    layout = _place_dual_pinion(design, {**settings, "position": "engaged"}, None)
    if not design.section("engagement"):
        return layout
    # the lead and stops of the sliding pinions come from the stiffness of the drive engaged
    # (its preload windup), whose shafts are placed by this very layout
    engagement = _engagement(layout)
    if wanted == "engaged":
        return replace(layout, engagement=engagement)
    return _place_dual_pinion(design, settings, engagement)


def _place_dual_pinion(design: Design, s: dict, engagement) -> Layout:
    from geargen.core.synthesis import place_gears, solve_loop, synthesize_centres
    from geargen.core.tolerance import appendix_error_budget, exact_error_budget
    from geargen.core.accuracy import error_budget_inputs
    from geargen.design.synthesis import synthesis_inputs
    from geargen.model.synthesis import SynthesisRun

    inputs = synthesis_inputs(design)
    syn = synthesize_centres(inputs).check()
    g_in, g_large, g_small, g_out = (design.gear(r) for r in ("input", "cluster_large", "cluster_small", "output"))
    rule = s["model_backlash"]
    design_notes: list[str] = []
    ranges = {m: (inputs.backlash(m, "min"), inputs.backlash(m, "max")) for m in (1, 2)}
    if rule == "as_designed":
        from geargen.core.synthesis import backlash_from_thickness_deficit as backlash_at_centre_distance
        modelled = {}
        for mesh, (a, b) in ((1, (g_in, g_large)), (2, (g_small, g_out))):
            t = a.transverse_pitch - reference_tooth_thickness(a) - reference_tooth_thickness(b)
            modelled[mesh] = float(backlash_at_centre_distance(t, inputs.centre_distance(mesh),
                                                               inputs.standard_centre_distance(mesh),
                                                               inputs.pressure_angle(mesh)))
    else:
        # the carriage settles where the loop closes, so mesh 1 runs at another centre distance than
        # the design's: iterate the modelled teeth until the backlash *there* is the one asked for
        from geargen.core.synthesis import backlash_from_thickness_deficit, thickness_deficit_for_backlash
        target = {m: _modelled_backlash(*ranges[m], rule) for m in (1, 2)}
        modelled = dict(target)
        for _ in range(12):
            placement = place_gears(syn, modelled[1], modelled[2], loaded_flank_gap=s["loaded_flank_gap"]).check()
            pg = {g.name: g for g in placement.gears}
            c1 = math.dist(pg["input"].centre, pg["cluster_large_a"].centre)
            t1 = thickness_deficit_for_backlash(modelled[1], inputs.centre_distance_mesh1,
                                                inputs.standard_centre_distance(1), inputs.pressure_angle(1))
            actual = float(backlash_from_thickness_deficit(t1, c1, inputs.standard_centre_distance(1),
                                                           inputs.pressure_angle(1)))
            if abs(actual - target[1]) < 1e-9:
                break
            modelled[1] += target[1] - actual
        designed = {1: (g_in, g_large), 2: (g_small, g_out)}
        g_in, g_large = _thin_pair(g_in, g_large, modelled[1], inputs.centre_distance_mesh1, "gears.input")
        g_small, g_out = _thin_pair(g_small, g_out, modelled[2], inputs.centre_distance_mesh2, "gears.cluster_small")
        for mesh, (a, b), (ma, mb) in ((1, designed[1], (g_in, g_large)), (2, designed[2], (g_small, g_out))):
            if (a.thinning or b.thinning) and not (math.isclose(a.thinning, ma.thinning, rel_tol=1e-6)
                                                  and math.isclose(b.thinning, mb.thinning, rel_tol=1e-6)):
                design_notes.append(
                    f"mesh {mesh}: teeth modelled with thinning {ma.thinning:.4g} + {mb.thinning:.4g} mm (backlash "
                    f"{target[mesh]:.4g} mm where the mesh runs, model_backlash = {rule!r}) instead of the design's "
                    f"{a.thinning:.4g} + {b.thinning:.4g} mm")
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
    gap = s["cluster_axial_gap"]
    if gap is None:
        gap = 0.25 * min(g_large.face_width, g_small.face_width)
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
                                    c))
        # mesh 2: the cluster's small gear (gear 1) against the output
        name, spec = part_of("cluster_small", side)
        lo = max(by_name[name].face_z(spec)[0], by_name["output"].face_z(g_out)[0])
        hi = min(by_name[name].face_z(spec)[1], by_name["output"].face_z(g_out)[1])
        engaged = hi - lo > 1e-9
        c = math.dist(by_name[name].centre, by_name["output"].centre)
        meshes.append(MeshPlacement(f"mesh2_{side}", name, spec, "output", g_out,
                                    (lo + hi) / 2 if engaged else by_name[name].face_z(spec)[0],
                                    *ranges[2], running_backlash(spec, g_out, c), engaged,
                                    "cluster cw" if side == "a" else "cluster ccw", c))
    train = Fraction(g_large.teeth, g_in.teeth) * Fraction(g_out.teeth, g_small.teeth)
    stage_gears, stage_meshes, stage_notes = _place_stages(design, s, gears, rule)
    gears += stage_gears
    meshes += stage_meshes
    notes += stage_notes
    source = "design" if rule == "as_designed" else f"derived for {rule}-range backlash ([layout] model_backlash)"
    thinning = {g.name: {"source": source} for g in gears}
    if rule != "as_designed":
        notes.insert(0, "thinning derived for " + rule + "-range backlash: "
                     + ", ".join(f"{n} {g.thinning / LENGTH_SUFFIXES[design.length_unit]:.6g} {design.length_unit}"
                                 for n, g in (("input", g_in), ("cluster_large", g_large),
                                              ("cluster_small", g_small), ("output", g_out)))
                     + " (circumferential, at the reference circle)")
    return Layout(design=design, kind="dual_pinion", gears=tuple(gears), meshes=tuple(meshes), position=position,
                  synthesis=run, carriage_x=placement.carriage_x, carriage_travel=s["carriage_travel"],
                  engagement=engagement, axial_shift=shifts, ratio=_ratio_check(design, s, train, "encoder to output"),
                  notes=tuple(notes), settings=s, placement=placement, thinning=thinning)


def stage_levels(design, loop_gears) -> float:
    """Height (mm) where the lowest upstream stage's gears may start: above the input gear, its
    upper bearing, the preload carriage's arm that holds it and the intermediate shafts' lower
    bearings standing on the arm; and above the link cover that holds the loop's upper bearings
    (the stage gears turn over it). ``loop_gears``: the placed loop gears (the carriage hardware
    of ``[parts]`` sizes the rest)."""
    from geargen.design.parts import parts_settings
    from geargen.model.shafts import carriage_arm_top, loop_shafts
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
            from geargen.model.planetary_stage import place_planetary_stage
            placed = place_planetary_stage(design, st, centre, level, rule)
            gears += placed.gears
            meshes += placed.meshes
            notes += placed.notes
            level += placed.height + gap
            continue
        driver, driven = design.gear(st.driver), design.gear(st.driven)
        if rule != "as_designed":
            driver, driven = _thin_pair(driver, driven, _modelled_backlash(st.backlash_min, st.backlash_max, rule),
                                        st.centre_distance, f"stages.{st.name}")
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
                                    running_backlash(driver, driven, st.centre_distance), True, "", st.centre_distance))
        if rule != "as_designed":
            notes.append(f"stage {st.name}: thinning derived for {rule}-range backlash: {st.driver} "
                         f"{driver.thinning / LENGTH_SUFFIXES[design.length_unit]:.6g}, {st.driven} "
                         f"{driven.thinning / LENGTH_SUFFIXES[design.length_unit]:.6g} {design.length_unit}")
        centre = driver_centre
        level += height + gap
    return gears, meshes, notes


def running_backlash(a: GearSpec, b: GearSpec, centre_distance: float) -> float:
    """Backlash of the modelled gears ``a`` (gear 1) and ``b`` at ``centre_distance`` (mm), in
    the kind of :data:`BACKLASH_KIND`: from their tooth-thickness deficit at the reference circle
    and the change of the working pressure angle with the centre distance."""
    from geargen.core.synthesis import backlash_from_thickness_deficit
    deficit = a.transverse_pitch - reference_tooth_thickness(a) - reference_tooth_thickness(b)
    standard = (a.teeth + b.teeth) * a.transverse_module / 2
    return float(backlash_from_thickness_deficit(deficit, centre_distance, standard, a.transverse_pressure_angle))


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
        target = _modelled_backlash(s["circumferential_backlash_min"], s["circumferential_backlash_max"], rule)
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


def _place_split_pinion(design: Design, s: dict) -> Layout:
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
        b_stiff = b_comp = _modelled_backlash(lo, hi, rule)
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
                                    running_backlash(spec, out, c), True, flank, c))
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
                  ratio=_ratio_check(design, s, Fraction(out.teeth, stiff.teeth), "input to output"),
                  notes=tuple(notes), thinning=thinning)


__all__ = ["LAYOUT_KINDS", "MODEL_BACKLASH", "POSITIONS", "BACKLASH_KIND", "GearPlacement", "MeshPlacement", "Layout",
           "layout_settings", "is_drive", "place", "running_backlash"]
