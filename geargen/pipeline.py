"""The build of an assembly, step by step: the one place that knows the order of the steps.

    load -> place -> gear solids -> stiffness -> other parts -> mesh checks -> export -> report

(the stiffness step comes before the other parts because it sizes some of them: the beam-spring
pinion's bearing span, the sliding pinions' travel stops)

Each step is a function taking the results of the steps before it, so any step can be run
alone (tests do); :func:`build` runs them all, shows progress on standard error (``quiet``
silences it) and writes the output atomically: everything goes into a temporary folder beside
the target, which replaces ``exports/<name>/`` only once every file is written. A build whose
mesh checks fail raises :class:`BuildFailed` and leaves nothing behind, unless ``force``: then
the files are written and marked as failing in the manifest and the report. The mesh checks of
the gears need only the layout and the gear solids, so :func:`build` runs them in a second
process (:class:`Alongside`) while this one builds the other parts and writes the view and the
exports into the temporary folder; nothing is moved into place before they have passed.

Placement (this module, numbers only). Frame: the output gear's centre is the origin, +x the
symmetry line towards the input, +z the gear axes (as :mod:`geargen.core.synthesis`). A gear
is placed by ``centre`` (x, y), ``z`` (height of its local z = 0 face) and ``rotation`` (about
its own axis; its tooth 0 is on local +x at local z = 0). For helical gears the synthesis'
rotations hold in one transverse plane per mesh (the cluster's own gear faces); the mate's
rotation is carried to its own z = 0 face through the helix (``section_rotation``).

Tooth thickness. The gears are modelled with the tooth thinning that gives each mesh the
backlash chosen by ``[layout] model_backlash`` ("mid": the middle of the design's range) where
it runs: the preload carriage settles where the loop closes, so mesh 1's centre distance is not
quite the design's, and the modelled thickness is iterated until the backlash there is the one
asked for. The thickness deficit comes from :mod:`geargen.core.synthesis`
(``thickness_deficit_for_backlash``) and is split equally between the two gears of a mesh.
"""

from __future__ import annotations

import json
import math
import os
import platform
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field, replace
from fractions import Fraction
from pathlib import Path
from typing import Any, Callable

import numpy as np

from geargen.core.involute import reference_tooth_thickness
from geargen.design.assembly import Design, load_design
from geargen.design.cluster import ClusterSpec
from geargen.design.export import EXPORT_FIELDS as _EXPORT_FIELDS
from geargen.design.gear import GearSpec, with_changes
from geargen.design.layout import LAYOUT_FIELDS as _LAYOUT_FIELDS, LAYOUT_KINDS, MODEL_BACKLASH, POSITIONS
from geargen.design.schema import read_table
from geargen.errors import DesignError, GeargenError
from geargen.profile.tooth import section_rotation
from geargen.units import LENGTH_SUFFIXES

STEPS = ("load", "place", "gear solids", "stiffness", "other parts", "mesh checks", "export", "report")


class BuildFailed(GeargenError):
    """The assembly was built but fails a check (teeth interfere, backlash out of range, parts overlap)."""

    def __init__(self, message: str, result: "BuildResult | None" = None):
        super().__init__(message)
        self.result = result


# ============================================================================ progress


class Progress:
    """Step-by-step progress on standard error: ``[3/8] gear solids ... 0.41 s``."""

    def __init__(self, quiet: bool = False, stream=None, total: int = len(STEPS) + 1):
        self.quiet = quiet
        self.stream = stream or sys.stderr
        self.total = total
        self.timings: dict[str, float] = {}
        self._index = 0

    def run(self, name: str, fn: Callable, *args, **kwargs):
        self._index += 1
        if not self.quiet:
            print(f"[{self._index}/{self.total}] {name} ...", end="", file=self.stream, flush=True)
        t0 = time.perf_counter()
        try:
            out = fn(*args, **kwargs)
        except BaseException:
            if not self.quiet:
                print(" failed", file=self.stream, flush=True)
            raise
        dt = time.perf_counter() - t0
        self.timings[name] = dt
        if not self.quiet:
            print(f" {dt:.2f} s", file=self.stream, flush=True)
        return out

    def run_timed(self, name: str, fn: Callable, *args, **kwargs):
        """Like :meth:`run` for a step whose work was (partly) done elsewhere: ``fn`` returns
        ``(value, seconds of work, note)``; the seconds are the step's time, the note is shown."""
        self._index += 1
        if not self.quiet:
            print(f"[{self._index}/{self.total}] {name} ...", end="", file=self.stream, flush=True)
        try:
            value, seconds, note = fn(*args, **kwargs)
        except BaseException:
            if not self.quiet:
                print(" failed", file=self.stream, flush=True)
            raise
        self.timings[name] = seconds
        if not self.quiet:
            print(f" {seconds:.2f} s {note}".rstrip(), file=self.stream, flush=True)
        return value

    def note(self, text: str) -> None:
        if not self.quiet:
            print(f"      {text}", file=self.stream, flush=True)


# ============================================================================ placement (numbers)


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
    what the modelled teeth give at the design centre distance. ``engaged`` False: the pinions
    are slid out of this mesh (disengaged position), only their axial clearance is checked.
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


@dataclass
class Layout:
    """Where every gear is and what each mesh must satisfy (mm, rad)."""

    design: Design
    kind: str
    gears: list[GearPlacement]
    meshes: list[MeshPlacement]
    position: str = "engaged"
    synthesis: Any = None  # geargen.report.synthesis.SynthesisRun for a dual-pinion drive
    carriage_x: float | None = None
    carriage_travel: float | None = None
    engagement: Any = None  # geargen.core.flexures.HelicalEngagement when the pinions slide
    axial_shift: dict[str, float] = field(default_factory=dict)  # part -> slide along +z (disengaged)
    ratio: dict[str, Any] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    settings: dict[str, Any] = field(default_factory=dict)

    def gear(self, name: str) -> GearPlacement:
        for g in self.gears:
            if g.name == name:
                return g
        raise KeyError(name)


def layout_settings(design: Design) -> dict[str, Any]:
    """``[layout]`` validated (internal units)."""
    table = design.section("layout")
    if not table:
        raise DesignError("layout", "missing", "a [layout] table with kind = " + " | ".join(map(repr, LAYOUT_KINDS)))
    return read_table(table, _LAYOUT_FIELDS, "layout")


def load(path: str | Path) -> Design:
    """Step 1: read and validate the design file."""
    return load_design(path)


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
    """The exact ratio from encoder to output: upstream stages (driver, driven teeth) times the train."""
    stages = settings["upstream_stages"]
    total = Fraction(train_ratio)
    described = []
    for i, st in enumerate(stages):
        if not (isinstance(st, list) and len(st) == 2 and all(isinstance(t, int) and t > 0 for t in st)):
            raise DesignError(f"layout.upstream_stages[{i}]", f"{st!r} is not [driver_teeth, driven_teeth]",
                              "two whole numbers > 0")
        total *= Fraction(st[1], st[0])
        described.append(f"{st[1]}/{st[0]}")
    required = settings["required_ratios"]
    for i, r in enumerate(required):
        if isinstance(r, bool) or not isinstance(r, int) or r <= 0:
            raise DesignError(f"layout.required_ratios[{i}]", f"{r!r} is not a whole-number ratio", "e.g. 180 or 360")
    ok = (not required) or any(total == Fraction(r) for r in required)
    text = " x ".join(described + [f"{train_ratio}"]) + f" = {total}"
    return {"train": train_ratio, "total": total, "required": list(required), "ok": ok,
            "text": text, "what": what}


def place(design: Design, position: str | None = None) -> Layout:
    """Step 2: the centres, heights and rotations of every gear, and the meshes to check."""
    settings = layout_settings(design)
    if position is not None:
        if position not in POSITIONS:
            raise DesignError("--position", f"{position!r} is not a valid choice", ", ".join(map(repr, POSITIONS)))
        settings["position"] = position
    if settings["kind"] == "dual_pinion":
        return _place_dual_pinion(design, settings)
    return _place_split_pinion(design, settings)


def _refuse_override_of_thinning(design: Design, rule: str) -> None:
    """A gear's own tooth thinning is never replaced quietly: only 'as_designed' may use it."""
    if rule == "as_designed":
        return
    thinned = [name for name, g in design.gears.items() if g.thinning > 0]
    if thinned:
        raise DesignError("layout.model_backlash", f"{rule!r} would replace the tooth thinning given for "
                          f"gears.{thinned[0]}", "'as_designed' when a gear table gives thinning_*")


def _place_dual_pinion(design: Design, s: dict) -> Layout:
    from geargen.core.synthesis import place_gears, solve_loop, synthesize_centres
    from geargen.core.tolerance import appendix_error_budget, exact_error_budget
    from geargen.design.synthesis import error_budget_inputs, synthesis_inputs
    from geargen.report.synthesis import SynthesisRun

    inputs = synthesis_inputs(design)
    syn = synthesize_centres(inputs).check()
    g_in, g_large, g_small, g_out = (design.gear(r) for r in ("input", "cluster_large", "cluster_small", "output"))
    rule = s["model_backlash"]
    _refuse_override_of_thinning(design, rule)
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
        modelled = target
    if rule == "as_designed":
        placement = place_gears(syn, modelled[1], modelled[2], loaded_flank_gap=s["loaded_flank_gap"]).check()
    errors = error_budget_inputs(design)
    budget = exact = None
    if errors is not None:
        budget = appendix_error_budget(syn, errors)
        exact = exact_error_budget(syn, errors)
    run = SynthesisRun(design_name=design.name, design_sha256=design.sha256, length_unit=design.length_unit,
                       inputs=inputs, synthesis=syn,
                       exact_min_backlash=solve_loop(syn, ranges[1][0], ranges[2][0]).check(),
                       placement=place_gears(syn).check(), errors=errors, budget=budget,
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
    engagement = None
    shifts: dict[str, float] = {}
    position = s["position"]
    notes = list(design_notes)
    if position == "disengaged" or design.section("engagement"):
        engagement = _engagement(design)
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

    layout = Layout(design=design, kind="dual_pinion", gears=gears, meshes=[], position=position, synthesis=run,
                    carriage_x=placement.carriage_x, carriage_travel=s["carriage_travel"], engagement=engagement,
                    axial_shift=shifts, notes=notes, settings=s)
    by_name = {g.name: g for g in gears}

    def part_of(role: str, side: str) -> tuple[str, GearSpec]:
        name = f"cluster_{side}" if s["cluster"] == "one_piece" else f"cluster_{'large' if role == 'cluster_large' else 'small'}_{side}"
        gp = by_name[name]
        spec = (gp.spec.large if role == "cluster_large" else gp.spec.small) if isinstance(gp.spec, ClusterSpec) else gp.spec
        return name, spec

    for side in ("a", "b"):
        # mesh 1: the input (gear 1) turned against the cluster's large gear
        name, spec = part_of("cluster_large", side)
        lo = max(by_name["input"].face_z(g_in)[0], by_name[name].face_z(spec)[0])
        hi = min(by_name["input"].face_z(g_in)[1], by_name[name].face_z(spec)[1])
        layout.meshes.append(MeshPlacement(f"mesh1_{side}", "input", g_in, name, spec, (lo + hi) / 2, *ranges[1],
                                           modelled[1], True, "input ccw" if side == "a" else "input cw"))
        # mesh 2: the cluster's small gear (gear 1) against the output
        name, spec = part_of("cluster_small", side)
        lo = max(by_name[name].face_z(spec)[0], by_name["output"].face_z(g_out)[0])
        hi = min(by_name[name].face_z(spec)[1], by_name["output"].face_z(g_out)[1])
        engaged = hi - lo > 1e-9
        layout.meshes.append(MeshPlacement(f"mesh2_{side}", name, spec, "output", g_out,
                                           (lo + hi) / 2 if engaged else by_name[name].face_z(spec)[0],
                                           *ranges[2], modelled[2], engaged,
                                           "cluster cw" if side == "a" else "cluster ccw"))
    train = Fraction(g_large.teeth, g_in.teeth) * Fraction(g_out.teeth, g_small.teeth)
    layout.ratio = _ratio_check(design, s, train, "encoder to output")
    return layout


def _engagement(design: Design):
    """The lead and travel stops of helical pinions sliding axially into mesh (stiffness step's helper)."""
    from geargen.core.stiffness import stiffness_summary
    summary = stiffness_summary(design)
    if summary.engagement is None:
        raise DesignError("engagement", "missing", "an [engagement] section for the sliding pinions")
    return summary.engagement


def _place_split_pinion(design: Design, s: dict) -> Layout:
    from geargen.core.synthesis import backlash_from_thickness_deficit as backlash_at_centre_distance, mate_rotation
    stiff, compliant, out = (design.gear(s[k]) for k in ("pinion_stiff", "pinion_compliant", "output"))
    c = s["centre_distance"]
    lo, hi = s["circumferential_backlash_min"], s["circumferential_backlash_max"]
    for key, v in (("centre_distance", c), ("circumferential_backlash_min", lo), ("circumferential_backlash_max", hi)):
        if v is None:
            raise DesignError(f"layout.{key}", "missing for a split pinion", "a length, e.g. _mm")
    if hi < lo:
        raise DesignError("layout.circumferential_backlash_min", "is larger than the maximum", "min <= max")
    rule = s["model_backlash"]
    _refuse_override_of_thinning(design, rule)
    standard = (stiff.teeth + out.teeth) * out.transverse_module / 2
    alpha = out.transverse_pressure_angle
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
            if extra < -1e-12:
                raise DesignError(f"gears.{p.name}", "already thinner than the modelled backlash allows",
                                  "model_backlash = 'as_designed'")
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
    layout = Layout(design=design, kind="split_pinion", gears=gears, meshes=[], settings=s)
    by = {g.name: g for g in gears}
    for part, spec, b, flank in ((s["pinion_stiff"], stiff, b_stiff, "pinion ccw (stiff path)"),
                                 (s["pinion_compliant"], compliant, b_comp, "pinion cw (compliant path)")):
        zl = max(by[part].face_z(spec)[0], by["output"].face_z(out)[0])
        zh = min(by[part].face_z(spec)[1], by["output"].face_z(out)[1])
        if zh - zl <= 0:
            raise DesignError("gears.output.face_width", f"the output's face does not reach {part}",
                              f">= {zh:.4g} mm")
        layout.meshes.append(MeshPlacement(f"mesh_{part}", part, spec, "output", out, (zl + zh) / 2, lo, hi, b, True,
                                           flank))
    layout.ratio = _ratio_check(design, s, Fraction(out.teeth, stiff.teeth), "input to output")
    return layout


# ============================================================================ CAD steps


def gear_solids(layout: Layout) -> dict[str, Any]:
    """Step 3: the solid of every toothed part (identical specs are built once), by part name;
    ``[export] gear_solid_tolerance`` bounds the flank splines' distance from the exact surface."""
    from geargen.cad.assembly import gear_parts
    return gear_parts(layout, export_config(layout.design)["gear_solid_tolerance"])


def other_parts(layout: Layout, gears: dict[str, Any] | None = None, stiffness=None) -> Any:
    """Step 4: every non-gear part, placed; returns ``geargen.cad.assembly.PartSet`` holding the
    gears too (first) when ``gears`` are given."""
    from geargen.cad.assembly import non_gear_parts
    parts = non_gear_parts(layout, stiffness)
    if gears:
        parts.parts = list(gears.values()) + parts.parts
    return parts


# ============================================================================ checks


@dataclass
class CheckOutcome:
    """Mesh checks and the part-overlap check of a build, and whether the build may pass."""

    meshes: list[dict[str, Any]]
    overlaps: Any = None
    failures: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    design_check: Any = None  # geargen.checks.results.DesignCheck when the checker ran

    @property
    def ok(self) -> bool:
        return not self.failures


def mesh_setup(layout: Layout, mesh: MeshPlacement):
    """The checker's :class:`geargen.checks.mesh2d.MeshSetup` of one mesh of ``layout``."""
    from geargen.checks.mesh2d import MeshSetup
    p1, p2 = layout.gear(mesh.part1), layout.gear(mesh.part2)
    z1, z2 = p1.face_z(mesh.gear1)[0], p2.face_z(mesh.gear2)[0]
    return MeshSetup(mesh.name, mesh.gear1, mesh.gear2, tuple(p1.centre), tuple(p2.centre),
                     p1.rotation_at(mesh.gear1, z1), p2.rotation_at(mesh.gear2, z2), face_offset2=z2 - z1)


def design_backlash(check, mesh: MeshPlacement) -> tuple[float, float]:
    """(min, max) backlash of a checker result in the design's kind: circumferential at the
    reference pitch circles, i.e. gear 1's free rotation times its reference radius (mm)."""
    ang = np.asarray(check.sweep.angular_backlash, dtype=float)
    ang = ang[np.isfinite(ang)]
    r = mesh.gear1.reference_radius
    if not ang.size:
        return math.nan, math.nan
    return float(np.min(ang) * r), float(np.max(ang) * r)


def contact_region(setup, settings) -> tuple[np.ndarray, np.ndarray]:
    """Where the other gear's centre lies, in each gear's own frame, over the mesh positions the
    section check visits: ``(q1 (k, 2), q2 (k, 2))`` mm (gear 2's centre seen from gear 1, and
    gear 1's from gear 2). The positions are sampled four times as densely as the check's and one
    step beyond either end, so the region holds every position the check uses."""
    from geargen.checks.mesh2d import mesh_positions
    pos = mesh_positions(setup, settings.steps_per_tooth, settings.revolutions)
    step = float(pos[1] - pos[0]) if pos.size > 1 else 2 * math.pi / setup.gear1.teeth
    dense = np.linspace(pos[0] - step, pos[-1] + step, 4 * (pos.size + 1) + 1)
    st = setup.states(dense)
    d = np.asarray(st.centre2, dtype=float) - np.asarray(st.centre1, dtype=float)

    def turned(v, angle):  # v (k, 2) rotated by -angle (k,)
        c, s = np.cos(angle), np.sin(angle)
        return np.column_stack([c * v[:, 0] + s * v[:, 1], -s * v[:, 0] + c * v[:, 1]])

    return turned(d, np.asarray(st.angle1)), turned(-d, np.asarray(st.angle2))


def section_check(layout: Layout, mesh: MeshPlacement, shape1, shape2, planes: int = 1, near: bool = True):
    """Path 2 of one mesh on two solids given in their own frames (``geargen.checks.solids``):
    sections at ``planes`` heights inside the common face (1: mid-face).

    ``near``: section only the faces of each solid that can come within the other gear's tip
    circle plus two modules over the checked positions (:func:`contact_region`,
    :func:`geargen.cad.assembly.faces_near`); the checker drops every segment farther than the
    tip circle plus one module, so its result is the same as with every face, at a fraction of
    the cost (a 112-tooth gear has ~100 teeth nowhere near the mesh). The stated tolerance is
    then that of the sectioned faces. ``near=False`` sections every face (kept to show that the
    two agree).
    """
    from geargen.checks.mesh2d import CheckSettings
    from geargen.checks.solids import check_mesh_sections, section_planes, sections_from_shape
    setup = mesh_setup(layout, mesh)
    settings = CheckSettings(require_backlash=mesh.backlash_min > 0)
    if near:
        from geargen.cad.assembly import faces_near
        q1, q2 = contact_region(setup, settings)
        g1, g2 = mesh.gear1, mesh.gear2
        shape1 = faces_near(shape1, q1, g2.tip_radius + 2 * g2.module)
        shape2 = faces_near(shape2, q2, g1.tip_radius + 2 * g1.module)
    z1 = section_planes(setup, planes)
    s1 = sections_from_shape(mesh.gear1, shape1, z1, source=mesh.part1)
    s2 = sections_from_shape(mesh.gear2, shape2, z1 - setup.face_offset2, source=mesh.part2)
    return check_mesh_sections(setup, s1, s2, settings)


def mesh_checks(layout: Layout, gears: dict[str, Any] | None = None, path2: bool = True) -> CheckOutcome:
    """Step 5: every engaged mesh with the geometric mesh checker: path 1 (exact 2-D) always, path 2
    (sections of the built solids) when the checker provides it and ``gears`` are given.

    A mesh fails on any checker failure (interference, no backlash, low contact ratio, ...) and
    when its backlash (design kind: circumferential at the reference circles) leaves the design
    range ``[backlash_min, backlash_max]``.
    """
    from geargen.checks.mesh2d import CheckSettings, check_mesh
    outcome = CheckOutcome(meshes=[])
    unit = layout.design.length_unit
    scale = LENGTH_SUFFIXES[unit]
    sections = path2 and gears is not None
    for mesh in layout.meshes:
        entry: dict[str, Any] = {"mesh": mesh.name, "gear1": mesh.part1, "gear2": mesh.part2, "engaged": mesh.engaged,
                                 "design_min": mesh.backlash_min, "design_max": mesh.backlash_max,
                                 "modelled": mesh.modelled_backlash, "plane_z": mesh.plane,
                                 "working_flank": mesh.working_flank}
        if not mesh.engaged:
            p1, p2 = layout.gear(mesh.part1), layout.gear(mesh.part2)
            (a0, a1), (b0, b1) = p1.face_z(mesh.gear1), p2.face_z(mesh.gear2)
            clearance = max(b0 - a1, a0 - b1)  # axial gap between the two faces
            entry.update(status="disengaged", axial_clearance=clearance)
            if clearance <= 0:
                outcome.failures.append(f"{mesh.name}: disengaged pinion still overlaps the output axially "
                                        f"({clearance / scale:.4g} {unit})")
            outcome.meshes.append(entry)
            continue
        setup = mesh_setup(layout, mesh)
        result = check_mesh(setup, CheckSettings(require_backlash=mesh.backlash_min > 0))
        lo, hi = design_backlash(result, mesh)
        entry.update(path1=result, backlash_min=lo, backlash_max=hi, contact_ratio=result.total_contact_ratio,
                     failures=[f.message for f in result.failures], notes=list(result.notes))
        for f in result.failures:
            outcome.failures.append(f"{mesh.name} ({f.kind}): {f.message}")
        tol = 1e-6
        if not (mesh.backlash_min - tol <= lo and hi <= mesh.backlash_max + tol):
            outcome.failures.append(
                f"{mesh.name}: backlash {lo / scale:.5g} to {hi / scale:.5g} {unit} (circumferential, reference "
                f"circles) is outside the design range {mesh.backlash_min / scale:.5g} to "
                f"{mesh.backlash_max / scale:.5g} {unit}")
        if sections:
            try:
                s2 = section_check(layout, mesh, gears[mesh.part1].shape, gears[mesh.part2].shape)
                lo2, hi2 = design_backlash(s2, mesh)
                entry.update(path2=s2, path2_backlash_min=lo2, path2_backlash_max=hi2)
                # the sections decide only where they resolve the working flanks' gap; coarser ones
                # (helical flanks sampled by chords) are reported, the exact path 1 decides
                resolves = s2.tolerance < max(layout.settings.get("loaded_flank_gap") or 0.0, 1e-3)
                for f in s2.failures:
                    text = f"{mesh.name} (sections of the solids, {f.kind}): {f.message}"
                    (outcome.failures if resolves else outcome.warnings).append(
                        text if resolves else text + f" [section tolerance {s2.tolerance:.3g} mm: not decisive]")
            except Exception as exc:  # report, do not hide: the exact check still decides
                outcome.warnings.append(f"{mesh.name}: section check (path 2) failed to run: {exc}")
        outcome.meshes.append(entry)
        if result.total_contact_ratio < 1.2:
            outcome.warnings.append(f"{mesh.name}: low contact ratio {result.total_contact_ratio:.3g}")
        for n in result.notes:
            if "undercut" in n:
                outcome.warnings.append(f"{mesh.name}: {n}")
    return outcome


def overlap_check(parts, layout: Layout | None = None) -> Any:
    """Pairwise solid intersections of all parts, intended contacts listed (``geargen.cad.assembly``)."""
    from geargen.cad.assembly import pairwise_overlaps
    meshing = [(m.part1, m.part2, "meshing gears: checked by the geometric mesh checker") for m in layout.meshes] \
        if layout is not None else []
    return pairwise_overlaps(parts.parts, parts.intended_contacts, delegated=meshing)


# ============================================================================ stiffness


def stiffness(layout: Layout):
    """Step 6: the stiffness summary (None when the design has no [stiffness]/[preload])."""
    design = layout.design
    if not design.section("stiffness") or not design.section("preload"):
        return None
    from geargen.core.stiffness import stiffness_summary
    travels = None
    run = layout.synthesis
    if run is not None and run.budget is not None and design.preload_method in ("radial", "axial") \
            and not design.section("beam_pinion"):
        b = run.budget
        travels = {"sum": b.dx1_sum, "rss": b.dx1_rss, "mean": b.dx1_mean}
    return stiffness_summary(design, travels)


# ============================================================================ export


def versions() -> dict[str, str]:
    import importlib.metadata as md
    out = {"python": platform.python_version()}
    for pkg in ("antibacklash-geargen", "cadquery", "cadquery-ocp", "numpy", "scipy", "matplotlib", "trimesh"):
        try:
            out[pkg] = md.version(pkg)
        except md.PackageNotFoundError:
            out[pkg] = "not installed"
    return out


def export(layout: Layout, parts, folder: Path, outcome: CheckOutcome | None = None,
           export_settings: dict | None = None) -> dict[str, Any]:
    """Step 7: assembly STEP, one STEP and one STL per part, into ``folder``; returns the file records."""
    from geargen.cad.assembly import export_parts
    return export_parts(layout, parts, Path(folder), export_settings or export_config(layout.design))


def export_config(design: Design) -> dict[str, Any]:
    """``[export]`` validated: STL tolerances (mm, rad), render view (azimuth, elevation deg)."""
    v = read_table(design.section("export"), _EXPORT_FIELDS, "export")
    for key in ("render_view", "render_size"):
        val = v[key]
        if val is not None and not (len(val) == 2 and all(isinstance(x, (int, float)) for x in val)):
            raise DesignError(f"export.{key}", f"{val!r} is not two numbers", "[a, b]")
    return v


# ============================================================================ report


def layout_drawing(layout: Layout, checks: CheckOutcome | None = None) -> bytes:
    """The 2-D layout drawing (PNG bytes) of ``layout`` (``geargen.report.layout``)."""
    from geargen.profile import tooth_profile
    from geargen.report.layout import LayoutGear, LayoutMesh, plot_layout
    import warnings
    gears, names = [], {}
    for g in layout.gears:
        for spec in g.gears:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                root = tooth_profile(spec).root_radius
            key = f"{g.name}:{spec.name}"
            names[(g.name, id(spec))] = key
            gears.append(LayoutGear(key if len(g.gears) > 1 else g.name, tuple(g.centre), spec.reference_radius,
                                    spec.tip_radius, root, spec.base_radius, spec.teeth))
    meshes = []
    working = {}
    for entry in (checks.meshes if checks is not None else []):
        if "path1" in entry:
            sw = entry["path1"].sweep
            working[entry["mesh"]] = "ccw" if float(np.min(sw.play_ccw)) < float(np.min(sw.play_cw)) else "cw"
    for m in layout.meshes:
        if not m.engaged:
            continue
        n1 = names[(m.part1, id(m.gear1))] if len(layout.gear(m.part1).gears) > 1 else m.part1
        n2 = names[(m.part2, id(m.gear2))] if len(layout.gear(m.part2).gears) > 1 else m.part2
        meshes.append(LayoutMesh(m.name, n1, n2, 0, working.get(m.name, "")))
    carriage = None
    if layout.carriage_x is not None and layout.carriage_travel:
        carriage = ((layout.carriage_x, 0.0), layout.carriage_travel)
    return plot_layout(gears, meshes, None, layout.design.length_unit, layout.design.name, carriage,
                       symmetry_line=layout.kind == "dual_pinion")


def render(parts, design: Design, settings: dict | None = None, folder: Path | None = None) -> bytes:
    """A rendered view (PNG bytes) of all parts (``geargen.cad.render``); with ``folder``, the
    parts' exported STL files there are drawn instead of tessellating again."""
    from geargen.cad.export import read_stl
    from geargen.cad.render import render_parts
    settings = settings or export_config(design)
    view = tuple(settings["render_view"] or (-60.0, 30.0))
    size = tuple(settings["render_size"] or (9.0, 6.5))
    meshes = {}
    if folder is not None:
        for p in parts.parts:
            stl = Path(folder) / f"{p.name}.stl"
            if stl.exists():
                meshes[p.name] = read_stl(stl)
    return render_parts(parts.parts, None, view=view, size=size, title=design.name, meshes=meshes)


def report(result: "BuildResult", folder: Path) -> dict[str, Path]:
    """Step 8: rendered view, layout drawing, stiffness plots, report.md and report.html."""
    from geargen.report.review import write_build_review
    if result.render_png is None:
        result.render_png = render(result.parts, result.design)
    return write_build_review(result, Path(folder), result.render_png, layout_drawing(result.layout, result.checks))


# ============================================================================ the whole build


@dataclass
class BuildResult:
    """Everything a build made; ``out_dir`` is where it was written (None if nothing was)."""

    design: Design
    layout: Layout
    gears: dict[str, Any]
    parts: Any
    checks: CheckOutcome
    stiffness: Any
    files: dict[str, Any] = field(default_factory=dict)
    out_dir: Path | None = None
    timings: dict[str, float] = field(default_factory=dict)
    forced: bool = False
    render_png: bytes | None = None

    @property
    def ok(self) -> bool:
        return self.checks.ok

    @property
    def warnings(self) -> list[str]:
        out = list(self.layout.notes and [] or [])
        out += self.checks.warnings
        if self.stiffness is not None:
            out += list(self.stiffness.warnings)
        return out


def default_out_dir(design: Design) -> Path:
    return Path("exports") / design.name


def _swap_into_place(tmp: Path, target: Path) -> None:
    """Move the finished folder ``tmp`` onto ``target`` (an old ``target`` is replaced whole)."""
    old = None
    if target.exists():
        old = Path(tempfile.mkdtemp(prefix=f".{target.name}.old.", dir=target.parent))
        os.rmdir(old)
        os.replace(target, old)
    try:
        os.replace(tmp, target)
    except BaseException:
        if old is not None:
            os.replace(old, target)
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def build(design_path: str | Path, out: str | Path | None = None, quiet: bool = False, force: bool = False,
          position: str | None = None, progress: Progress | None = None, parallel: bool = True) -> BuildResult:
    """Run every step and write the exports atomically into ``out`` (default ``exports/<name>``).

    Raises :class:`BuildFailed` when a check fails (nothing written) unless ``force``.

    ``parallel``: the mesh checks of the gears (:func:`mesh_checks`, the longest step) run in a
    second process (:class:`Alongside`) from the moment the gear solids exist, while this one
    builds the other parts and writes the view and the exports into the temporary folder; the
    build waits for them (and checks the parts' overlaps) before anything is moved into place,
    so a failing build still leaves nothing behind. Where no second process can be had, or it
    delivers nothing, the checks run here, in order, as with ``parallel=False``.
    """
    progress = progress or Progress(quiet)
    design = progress.run("load", load, design_path)
    layout = progress.run("place", place, design, position)
    gears = progress.run("gear solids", gear_solids, layout)
    alongside = Alongside.start(mesh_checks, layout, gears) if parallel else None
    if alongside is not None:
        progress.note("mesh checks: started in a second process, alongside the next steps")
    try:
        summary = progress.run("stiffness", stiffness, layout)
        parts = progress.run("other parts", other_parts, layout, gears, summary)
        result = None
        if alongside is None:
            checks = progress.run("mesh checks", _all_checks, layout, gears, parts)
            result = _checked(BuildResult(design, layout, gears, parts, checks, summary), force, progress)
        target = Path(out) if out is not None else default_out_dir(design)
        target = target.resolve()
        target.parent.mkdir(parents=True, exist_ok=True)
        tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.build.", dir=target.parent))
        try:
            # the view first: its coarse tessellation is refined by the STL export (not the reverse)
            render_png = progress.run("render", render, parts, design)
            files = progress.run("export", export, layout, parts, tmp)
            if result is None:
                checks = progress.run_timed("mesh checks", _collect_checks, alongside, layout, gears, parts)
                result = _checked(BuildResult(design, layout, gears, parts, checks, summary), force, progress)
            result.render_png, result.files = render_png, files
            result.timings = dict(progress.timings)
            progress.run("report", _report_and_manifest, result, tmp)
            _swap_into_place(tmp, target)
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise
    finally:
        if alongside is not None:
            alongside.close()
    result.out_dir = target
    result.timings = dict(progress.timings)
    return result


def _checked(result: BuildResult, force: bool, progress: Progress) -> BuildResult:
    """``result`` if its checks pass (or ``force``: marked as forced); else :class:`BuildFailed`."""
    for f in result.checks.failures:
        progress.note(f"FAIL {f}")
    result.forced = force and not result.checks.ok
    if not result.checks.ok and not force:
        raise BuildFailed(f"{result.design.name}: the assembly fails its checks (nothing written; --force writes it "
                          "marked as failing):\n  " + "\n  ".join(result.checks.failures), result)
    return result


def _all_checks(layout: Layout, gears, parts, meshes: CheckOutcome | None = None) -> CheckOutcome:
    """The mesh checks (``meshes`` if already made), the parts' overlaps and the exact ratio."""
    outcome = meshes if meshes is not None else mesh_checks(layout, gears)
    outcome.overlaps = overlap_check(parts, layout)
    for o in outcome.overlaps.unintended:
        outcome.failures.append(f"parts overlap: {o.part1} and {o.part2} share {o.volume:.4g} mm^3")
    if layout.ratio and not layout.ratio["ok"]:
        outcome.failures.append(f"ratio {layout.ratio['what']} is {layout.ratio['total']}, not one of "
                                f"{layout.ratio['required']} ({layout.ratio['text']})")
    return outcome


def _collect_checks(alongside: "Alongside", layout: Layout, gears, parts) -> tuple[CheckOutcome, float, str]:
    """The mesh checks from the second process (or made here if it delivered nothing), completed by
    :func:`_all_checks`; returns (outcome, seconds of checking, a note for the progress line)."""
    t0 = time.perf_counter()
    got = alongside.result()
    waited = time.perf_counter() - t0
    if got is None:
        t0 = time.perf_counter()
        outcome = _all_checks(layout, gears, parts)
        return outcome, time.perf_counter() - t0, "(the second process delivered nothing: checked here)"
    busy, meshes = got
    t0 = time.perf_counter()
    outcome = _all_checks(layout, gears, parts, meshes)
    busy += time.perf_counter() - t0
    return outcome, busy, f"(meshes checked in a second process alongside stiffness to export; waited {waited:.2f} s)"


def _run_in_child(conn, fn, args) -> None:
    """Body of the second process: send ``("ok", seconds, fn(*args))`` or ``("error", 0, text)``."""
    try:
        t0 = time.perf_counter()
        value = fn(*args)
        conn.send(("ok", time.perf_counter() - t0, value))
    except BaseException as exc:  # the parent runs fn itself and raises what it raises
        try:
            conn.send(("error", 0.0, f"{type(exc).__name__}: {exc}"))
        except Exception:
            pass
    finally:
        conn.close()


class Alongside:
    """``fn(*args)`` computed in a forked process while the caller goes on; :meth:`result` collects it.

    The child shares the caller's memory as it was at :meth:`start` (nothing is pickled on the
    way in; the result comes back pickled through a pipe). It must not use the kernel's thread
    pools (a forked process has only the forking thread): the mesh checks read the gear solids
    and compute with numpy, nothing more. Linux only (fork); :meth:`start` returns None where a
    child cannot be had, and :meth:`result` returns None when the child delivers nothing (error,
    crash, ``timeout`` seconds): the caller then computes ``fn`` itself.
    """

    def __init__(self, process, receiver):
        self._process = process
        self._receiver = receiver

    @classmethod
    def start(cls, fn: Callable, *args) -> "Alongside | None":
        if not (sys.platform.startswith("linux") and hasattr(os, "fork")):
            return None
        try:
            import multiprocessing
            ctx = multiprocessing.get_context("fork")
            receiver, sender = ctx.Pipe(duplex=False)
            process = ctx.Process(target=_run_in_child, args=(sender, fn, args), daemon=True)
            process.start()
        except Exception:  # e.g. inside a daemonic worker, which may not have children
            return None
        sender.close()
        return cls(process, receiver)

    def result(self, timeout: float = 600.0) -> tuple[float, Any] | None:
        """``(seconds the child computed, fn's value)``, or None if it delivered nothing."""
        try:
            if not self._receiver.poll(timeout):
                return None
            status, seconds, value = self._receiver.recv()
        except Exception:  # EOF (the child died), an unpicklable value, ...
            return None
        finally:
            self.close()
        return (seconds, value) if status == "ok" else None

    def close(self) -> None:
        """Close the pipe and end the child if it is still running."""
        self._receiver.close()
        if self._process.is_alive():
            self._process.terminate()
        self._process.join(timeout=5.0)


def _report_and_manifest(result: BuildResult, folder: Path) -> None:
    files = report(result, folder)
    manifest(result, folder, files)


def manifest(result: BuildResult, folder: Path, report_files: dict[str, Path] | None = None) -> Path:
    """manifest.json: files, units, tolerances, the design's sha256, versions, check status."""
    from geargen.cad.export import write_json
    design = result.design
    entries = {}
    for name, rec in result.files.get("records", {}).items():
        entries[name] = rec
    for key, p in (report_files or {}).items():
        entries[Path(p).name] = {"format": Path(p).suffix.lstrip("."), "role": key, "bytes": Path(p).stat().st_size}
    status = "ok" if result.ok else "failing"
    data = {
        "generator": "geargen build",
        "design": {"name": design.name, "file": str(design.path) if design.path else None, "sha256": design.sha256,
                   "length_unit": design.length_unit},
        "status": status,
        "forced": result.forced,
        "failures": list(result.checks.failures),
        "units": {"step": f"{design.length_unit} (declared in each file)", "stl": "mm",
                  "internal": "mm, rad, N"},
        "tolerances": result.files.get("tolerances", {}),
        "position": result.layout.position,
        "checks": _checks_summary(result),
        "parts": result.files.get("parts", {}),
        "files": entries,
        "versions": versions(),
        "timings_s": {k: round(v, 4) for k, v in result.timings.items()},
    }
    path = Path(folder) / "manifest.json"
    write_json(path, _jsonable(data))
    return path


def _checks_summary(result: BuildResult) -> dict[str, Any]:
    """Mesh-check and overlap results for the manifest (lengths in mm)."""
    meshes = []
    for m in result.checks.meshes:
        e = {k: m[k] for k in ("mesh", "gear1", "gear2", "engaged", "design_min", "design_max", "plane_z")}
        for k in ("backlash_min", "backlash_max", "path2_backlash_min", "path2_backlash_max", "contact_ratio",
                  "axial_clearance", "failures"):
            if k in m:
                e[k] = m[k]
        meshes.append(e)
    ov = result.checks.overlaps
    overlaps = None if ov is None else {
        "parts": ov.parts, "pairs_checked": ov.pairs_checked, "tolerance_mm3": ov.tolerance,
        "unintended": [[o.part1, o.part2, o.volume] for o in ov.unintended],
        "intended_contacts": [list(c) for c in ov.intended], "meshing_pairs": [list(c) for c in ov.delegated]}
    return {"length_unit": "mm", "backlash_kind": "circumferential at the reference pitch circles",
            "meshes": meshes, "overlaps": overlaps}


def _jsonable(value):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, Path):
        return str(value)
    if isinstance(value, Fraction):
        return str(value)
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


__all__ = ["STEPS", "Progress", "GearPlacement", "MeshPlacement", "Layout", "CheckOutcome", "BuildResult",
           "BuildFailed", "load", "place", "gear_solids", "other_parts", "mesh_checks", "overlap_check",
           "stiffness", "export", "report", "manifest", "build", "layout_settings", "export_config", "versions",
           "section_check", "contact_region", "Alongside"]
