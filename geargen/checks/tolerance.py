"""Minimum backlash of each mesh across the error budget: a worst case that is a true bound, and
Monte Carlo builds, both measured on path 1; the preload carriage's travel against its hardware.

**Error model** (as :mod:`geargen.core.tolerance`): per gear, TIR readings (peak to peak, mm) of
bearing eccentricity, pitch-line eccentricity and tooth-to-tooth error. An eccentricity TIR
``e`` offsets the gear's tooth circle from its axis by ``e/2``, turning with the gear (the
bearing and the pitch-line offset of a gear each at its own phase, so together anywhere between
their difference and their sum); a tooth-to-tooth TIR ``t`` turns each tooth rigidly by up to
``t/2`` along the reference circle either way, independently from tooth to tooth. Backlash is
of the resolved model's kind (circumferential at gear 1's reference circle, mm: the kind of the
design ranges and of every report) unless named normal; every value
reported is measured by the exact 2-D check (:mod:`geargen.checks.mesh2d`).

**A mesh on fixed bearings** (a declared pair; mesh 2 of the dual-pinion loop).
*Worst case*: the tooth circles at their closest approach (every eccentricity pointing at the
mate: centre distance down by the sum of the four offsets) and every flank moved ``t/2`` into
the play (:func:`worst_flanks`). It is a bound: the play of involute gears depends only on the
centre distance, grows with it, and the widened teeth contain every displaced tooth, so no
build at any position has less. It is attained: the closest approach happens at a mesh position
the eccentricity phases choose, and wherever two different teeth of each gear bound the play
(every double-contact stretch) the teeth there can sit at opposite limits (the tests build that
state and find the bound within 1e-9 mm). *Monte Carlo*: each sample is one build (uniform
eccentricity phases, a uniform displacement per tooth); its value is its minimum over the whole
hunting period of the pair, found on the closed-form pair model
(:class:`geargen.checks.pair_model.HuntingSearch`: every tooth cycle whose lower bound is below
the best value found is evaluated at every contact-stretch edge and on a grid, then refined),
and then measured by the exact check at that position. ``monte_carlo_model_difference`` reports
how far the two differ there. While the mesh keeps backlash the model and the exact check agree
within 1e-8 mm (the tip-corner table within 5e-7 mm) and no position of the period has less
play than the value found (the tests sweep whole periods with the exact check); once the teeth
overlap (negative backlash, already a failure) the exact check also counts tips reaching into
roots, which the model does not search for, and the value may be a few micrometres high.

**The preloaded loop (the dual-pinion drive, radial-motion preload).** The input gear rides on
a carriage the preload pushes towards the output until its flanks touch both clusters' large
gears (mesh 1A on the input's counter-clockwise flanks, 1B on its clockwise ones); through the
clusters mesh 2 closes on the output. The carriage position and every gear's rotation come from
the exact loop closure (:func:`geargen.core.synthesis.solve_loop`), followed along the branch
that grows continuously out of the error-free assembly (a closure one input tooth over is
another assembly, not this one). Mesh 1's backlash is then the clearance left on its
non-working flanks: the play at its real centre distance (tooth-circle offsets included) less
the displacement of the tooth pair in contact on the working side (which also moved the
carriage) and of the pair on the non-working side. *Worst case* of mesh 1 and of the carriage
travel: a global search over the whole error state - each offset's phase (every gear's
position over the hunting period), every contact's tooth displacement within its TIR, the
non-working teeth at their limit - by a dense phase grid per gear in turn, then
``scipy.optimize`` (L-BFGS-B) from the best point and from the worst Monte Carlo samples; the
state found is measured by the exact check. *Monte Carlo*: each sample is one build (the same
builds for all four meshes) at one random instant of the loop: its offsets turned to that
instant, the displacements of the teeth in contact drawn uniformly. Mesh 2 sits on bearings and
is analysed as above (its Monte Carlo minimum covers its hunting period). The loop holds its
preload while mesh 1 keeps clearance (else ``preload_contact_lost``) and the carriage stays
within the travel of its flexures and springs (else ``carriage_travel_exceeded``,
:func:`carriage_travel_limits`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from geargen.checks.mesh2d import (Eccentricity, MeshSetup, MeshState, free_play, mesh_positions, polar_outline,
                                   sweep_backlash, sweep_mesh)
from geargen.checks.pair_model import HuntingSearch, PairModel, TipExcess
from geargen.checks.results import CarriageTravelLimits, Failure, ToleranceResult
from geargen.design.synthesis import GearErrors
from geargen.profile.tooth import section_rotation
from geargen.units import LENGTH_SUFFIXES

NO_ERRORS = GearErrors()
#: a Monte Carlo value below the worst case by more than this (mm) means the worst case is not a bound
BOUND_TOLERANCE = 1e-7
#: the loop search's local refinement stops once an iteration lowers the objective by less than this
#: (L-BFGS-B's ftol; the objectives are mm below 1 mm, so it is 1e-12 mm): on the shipped designs it
#: ends within 2e-13 mm of the value 1e-15 gives, with ~45 % fewer loop closures
SEARCH_FTOL = 1e-12


def _amplitudes(e: GearErrors | None) -> tuple[float, float, float]:
    """(bearing, pitch-line) eccentricity offsets and the tooth displacement limit, mm (TIR / 2)."""
    if e is None:
        return 0.0, 0.0, 0.0
    return e.bearing_eccentricity_tir / 2, e.pitch_line_eccentricity_tir / 2, e.tooth_to_tooth_tir / 2


def _length(value: float, unit: str) -> str:
    return f"{value / LENGTH_SUFFIXES[unit]:.4g} {unit}"


def alternating_flanks(spec, displacement: float) -> np.ndarray:
    """Flank offsets ``(z, 2)`` (rad) of teeth displaced alternately by +-``displacement`` (mm along
    the reference circle): every other space narrowed by twice the displacement."""
    d = displacement * np.where(np.arange(spec.teeth) % 2 == 0, 1.0, -1.0) / spec.reference_radius
    return np.column_stack([-d, d])


def worst_flanks(spec, displacement: float) -> np.ndarray:
    """Flank offsets ``(z, 2)`` (rad) of the worst tooth-to-tooth state for backlash: every flank
    ``displacement`` (mm along the reference circle) further out, i.e. each space narrowed by
    twice the displacement wherever two different teeth bound it - what two neighbouring teeth
    displaced to opposite limits do to the play they bound."""
    e = displacement / spec.reference_radius
    return np.tile([e, e], (spec.teeth, 1))


def random_flanks(spec, limit: float, rng: np.random.Generator, n: int) -> np.ndarray:
    """Flank offsets ``(n, z, 2)`` of teeth displaced uniformly in [-limit, limit] (mm)."""
    d = rng.uniform(-limit, limit, (n, spec.teeth)) / spec.reference_radius
    return np.stack([-d, d], axis=-1)


def _circumferential(setup: MeshSetup, angular):
    """Gear 1's free rotation as backlash of the resolved model's kind (geargen.model.BACKLASH_KIND:
    circumferential at gear 1's reference circle), the kind of the design ranges and every report."""
    return angular * setup.gear1.reference_radius


def _exact_play(setup: MeshSetup, centre1, angle1, centre2, angle2, flanks1=None, flanks2=None, planes=None):
    """Exact play of gear 1 (rad) counter-clockwise and clockwise at ``n`` states, each the
    smallest over the section planes (as :func:`sweep_mesh`). ``flanks*``: ``(z, 2)`` or ``(n, z, 2)``."""
    planes = setup.planes(3) if planes is None else np.atleast_1d(planes)
    o1, o2 = polar_outline(setup.gear1), polar_outline(setup.gear2)
    n, P = len(angle1), planes.size
    t1 = np.atleast_1d(section_rotation(setup.gear1, planes))
    t2 = np.atleast_1d(section_rotation(setup.gear2, planes - setup.face_offset2))
    f1 = flanks1 if flanks1 is None or np.ndim(flanks1) == 2 or P == 1 else np.tile(flanks1, (P, 1, 1))
    f2 = flanks2 if flanks2 is None or np.ndim(flanks2) == 2 or P == 1 else np.tile(flanks2, (P, 1, 1))
    st = MeshState(np.tile(centre1, (P, 1)), (np.asarray(angle1)[None, :] + t1[:, None]).ravel(),
                   np.tile(centre2, (P, 1)), (np.asarray(angle2)[None, :] + t2[:, None]).ravel(), f1, f2)
    play = free_play(o1, o2, st)
    return (np.min(play.conjugate_ccw.reshape(P, n), axis=0), np.min(play.conjugate_cw.reshape(P, n), axis=0))


# ------------------------------------------------------------------------- fixed bearings
def worst_case_pair(setup: MeshSetup, errors1: GearErrors | None, errors2: GearErrors | None,
                    steps_per_tooth: int = 24) -> tuple[float, float, float]:
    """Worst-case minimum backlash of a mesh on fixed bearings (a bound, see the module docstring).

    Returns (circumferential, normal, centre-distance change) in mm.
    """
    b1, p1, t1 = _amplitudes(errors1)
    b2, p2, t2 = _amplitudes(errors2)
    c1, c2 = np.asarray(setup.centre1, dtype=float), np.asarray(setup.centre2, dtype=float)
    u = (c2 - c1) / np.linalg.norm(c2 - c1)
    worst = replace(setup, centre1=tuple(c1 + (b1 + p1) * u), centre2=tuple(c2 - (b2 + p2) * u),
                    eccentricity1=(), eccentricity2=(),
                    flanks1=worst_flanks(setup.gear1, t1) if t1 > 0 else None,
                    flanks2=worst_flanks(setup.gear2, t2) if t2 > 0 else None)
    pos = mesh_positions(worst, steps_per_tooth, 1.0 / setup.gear1.teeth)
    angular, normal = sweep_backlash(worst, pos, worst.planes(3))
    return (float(_circumferential(setup, np.nanmin(angular))), float(np.nanmin(normal)), -(b1 + p1 + b2 + p2))


@dataclass
class PairBuilds:
    """Random builds of a pair: eccentricity phases ``(S, 4)`` at mesh position 0 (bearing and
    pitch-line of gear 1, then of gear 2) and tooth displacements ``(S, z)`` (mm along the
    reference circle, counter-clockwise) of each gear."""

    phases: np.ndarray
    displacement1: np.ndarray
    displacement2: np.ndarray

    @classmethod
    def draw(cls, setup: MeshSetup, errors1, errors2, samples: int, rng: np.random.Generator) -> "PairBuilds":
        t1, t2 = _amplitudes(errors1)[2], _amplitudes(errors2)[2]
        phases = rng.uniform(0.0, 2 * math.pi, (samples, 4))
        d1 = rng.uniform(-t1, t1, (samples, setup.gear1.teeth))
        d2 = rng.uniform(-t2, t2, (samples, setup.gear2.teeth))
        return cls(phases, d1, d2)


@dataclass
class PairMonteCarlo:
    """Per-build minimum backlash over the hunting period (mm, ``(S,)``): measured by the exact
    check (``minima``) at the mesh positions the model found (``positions``, rad), where the
    model gives ``model_minima``."""

    minima: np.ndarray
    positions: np.ndarray
    model_minima: np.ndarray
    centre_distances: np.ndarray

    @property
    def model_difference(self) -> float:
        d = np.abs(self.minima - self.model_minima)
        d = d[np.isfinite(d)]
        return float(d.max()) if d.size else float("nan")


def _nominal_angular_play(setup: MeshSetup, steps_per_tooth: int = 24) -> float:
    clean = replace(setup, eccentricity1=(), eccentricity2=(), flanks1=None, flanks2=None)
    sw = sweep_mesh(clean, mesh_positions(clean, steps_per_tooth), clean.planes(3), areas=False)
    return float(np.nanmin(sw.angular_backlash))


def pair_minima(setup: MeshSetup, errors1: GearErrors | None, errors2: GearErrors | None, builds: PairBuilds,
                steps_per_tooth: int = 8, nominal_angular_play: float | None = None) -> PairMonteCarlo:
    """Minimum backlash of each build of ``builds`` over the pair's whole hunting period (see the
    module docstring): found on :class:`~geargen.checks.pair_model.HuntingSearch`, measured by the
    exact check there."""
    S = builds.phases.shape[0]
    if S == 0:
        e = np.empty(0)
        return PairMonteCarlo(e, e, e, e)
    b1, p1, t1 = _amplitudes(errors1)
    b2, p2, t2 = _amplitudes(errors2)
    ang0 = _nominal_angular_play(setup) if nominal_angular_play is None else nominal_angular_play
    planes = setup.planes(3)
    model = PairModel(setup, ang0, planes)
    offsets = b1 + p1 + b2 + p2
    a0 = setup.centre_distance
    g1, g2 = model.gear1, model.gear2
    # displacements of a pair differ by at most this much along the line of action
    spread = 2 * (t1 * g1.base_radius / g1.reference_radius + t2 * g2.base_radius / g2.reference_radius)
    excess = TipExcess(model, np.linspace(a0 - offsets, a0 + offsets, 33 if offsets > 0 else 1), spread)
    search = HuntingSearch(model, (b1, p1, b2, p2), excess, steps_per_tooth)
    e1 = builds.displacement1 / g1.reference_radius
    e2 = builds.displacement2 / g2.reference_radius
    s_min, play_min, a_min = search.search(builds.phases, e1, e2)
    c1, c2 = search.centres(builds.phases, s_min)
    ang1 = setup.rotation1 + s_min
    ang2 = setup.rotation2 - model.ratio * s_min
    # gear 1 in the middle of its play, so both sides are measured across the same tooth space
    gap_ccw = model.side_gap(c1, ang1, c2, ang2, 1, e1, e2)
    gap_cw = model.side_gap(c1, ang1, c2, ang2, -1, e1, e2)
    ang1 = ang1 + np.where(np.isfinite(gap_ccw - gap_cw), (gap_ccw - gap_cw) / (2 * g1.base_radius), 0.0)
    f1 = np.stack([-e1, e1], axis=-1)
    f2 = np.stack([-e2, e2], axis=-1)
    ccw, cw = _exact_play(setup, c1, ang1, c2, ang2, f1, f2, planes)
    exact = _circumferential(setup, ccw + cw)
    modelled = model.circumferential(play_min)
    # where the exact check finds no conjugate contact (teeth out of mesh), keep the model's value
    return PairMonteCarlo(np.where(np.isfinite(exact), exact, modelled), s_min, modelled, a_min)


def monte_carlo_pair(setup: MeshSetup, errors1: GearErrors | None, errors2: GearErrors | None, samples: int,
                     rng: np.random.Generator, steps_per_tooth: int = 8) -> np.ndarray:
    """Per-build minimum backlash (circumferential, mm, ``(samples,)``) of a mesh on fixed bearings
    over its whole hunting period (see the module docstring)."""
    if samples <= 0:
        return np.empty(0)
    builds = PairBuilds.draw(setup, errors1, errors2, samples, rng)
    return pair_minima(setup, errors1, errors2, builds, steps_per_tooth).minima


def eccentric_sweep(setup: MeshSetup, errors1: GearErrors | None, errors2: GearErrors | None,
                    steps_per_tooth: int = 4):
    """The mesh over whole revolutions (its hunting period) with every eccentricity at its limit,
    all pointing at the mate at mesh position 0 and turning with their gears from there: how
    the backlash breathes with the eccentricities (path 1 at every position). None without
    eccentricities."""
    b1, p1, _ = _amplitudes(errors1)
    b2, p2, _ = _amplitudes(errors2)
    if b1 + p1 + b2 + p2 == 0:
        return None
    c1, c2 = np.asarray(setup.centre1, dtype=float), np.asarray(setup.centre2, dtype=float)
    d = c2 - c1
    towards = math.atan2(d[1], d[0])
    su = replace(setup, eccentricity1=(Eccentricity(b1 + p1, towards),),
                 eccentricity2=(Eccentricity(b2 + p2, towards + math.pi),))
    pos = mesh_positions(su, steps_per_tooth)
    return sweep_mesh(su, pos, su.planes(1), areas=False)


def _pair_coverage(setup: MeshSetup) -> str:
    return f"the whole hunting period ({setup.hunting_revolutions} revolutions of {setup.gear1.name})"


def _guard_bound(res: ToleranceResult, unit: str) -> None:
    """If a Monte Carlo sample falls below the worst case, the worst case was not a bound: lower
    it to that sample and say so (the tests hold the bound; this keeps a report consistent)."""
    if res.samples and res.monte_carlo_minimum < res.worst_case_min_backlash - BOUND_TOLERANCE:
        res.notes.append(f"{res.mesh}: a Monte Carlo sample ({_length(res.monte_carlo_minimum, unit)}) fell below "
                         f"the searched worst case ({_length(res.worst_case_min_backlash, unit)}); the worst case "
                         "is lowered to it")
        res.worst_case_min_backlash = res.monte_carlo_minimum


def _pair_result(setup: MeshSetup, errors1, errors2, builds: PairBuilds | None, meant_for: str,
                 steps_per_tooth: int, unit: str) -> ToleranceResult:
    ang0 = _nominal_angular_play(setup, steps_per_tooth)
    nominal = float(_circumferential(setup, ang0))
    wc, wc_n, da = worst_case_pair(setup, errors1, errors2, steps_per_tooth)
    mc = pair_minima(setup, errors1, errors2, builds, nominal_angular_play=ang0) if builds is not None else None
    minima = mc.minima if mc is not None else np.empty(0)
    res = ToleranceResult(mesh=setup.name, meant_for=meant_for, nominal_min_backlash=nominal,
                          worst_case_min_backlash=wc, worst_case_min_normal_backlash=wc_n,
                          monte_carlo_min_backlash=minima, worst_case_centre_distance_change=da,
                          revolutions=eccentric_sweep(setup, errors1, errors2),
                          monte_carlo_coverage=_pair_coverage(setup),
                          monte_carlo_model_difference=mc.model_difference if mc is not None else float("nan"),
                          worst_case_method="closest approach of the tooth circles with every flank at its limit "
                                            "(a bound, attained)")
    _guard_bound(res, unit)
    if res.samples:
        res.notes.append(f"{setup.name}: {res.samples_without_backlash} of {res.samples} Monte Carlo builds have "
                         f"minimum backlash <= 0 over {setup.hunting_revolutions} revolutions of {setup.gear1.name} "
                         "(the hunting period)")
    if meant_for == "backlash" and res.worst_case_min_backlash <= 0:
        res.failures.append(Failure("backlash_lost", setup.name,
                                    f"worst-case minimum backlash {_length(res.worst_case_min_backlash, unit)} across "
                                    f"the error budget (centre distance {_length(da, unit)}, nominal minimum "
                                    f"{_length(nominal, unit)})", "circumferential_backlash",
                                    res.worst_case_min_backlash, 0.0))
    return res


def pair_tolerance(setup: MeshSetup, errors1: GearErrors | None, errors2: GearErrors | None, samples: int,
                   rng: np.random.Generator, meant_for: str = "backlash", steps_per_tooth: int = 24,
                   unit: str = "mm") -> ToleranceResult:
    """Worst case and Monte Carlo minimum backlash of a mesh on fixed bearings.

    ``meant_for`` "backlash": a failure (``backlash_lost``) when the worst case reaches zero;
    "zero_backlash": reported only. ``unit``: length unit of the messages.
    """
    builds = PairBuilds.draw(setup, errors1, errors2, samples, rng) if samples > 0 else None
    return _pair_result(setup, errors1, errors2, builds, meant_for, steps_per_tooth, unit)


# ------------------------------------------------------------------------- carriage travel limits
def carriage_travel_limits(sections, explicit: float | None = None, length_unit: str | None = None) -> CarriageTravelLimits:
    """How far the preload carriage may travel from its nominal position (mm, + away from the
    output), from its hardware: the blade flexures' travel about their unstressed position
    (``[flexures] travel``, ``neutral_offset``), and the springs' stroke (``[springs]``: moving out
    compresses them, down to solid height; moving in lets them extend, up to their free length,
    where they leave their seats). ``explicit`` (``[checks] carriage_travel_limit``, either way)
    applies where it is smaller than the hardware's. ``sections``: the design's stiffness-step
    sections as the resolved drive carries them (:class:`geargen.design.stiffness.StiffnessDesign`,
    with the design's ``length_unit`` for the text), or a design, read here.
    """
    from geargen.core.flexures import spring_solid_height
    from geargen.design.stiffness import StiffnessDesign, stiffness_design

    if not isinstance(sections, StiffnessDesign):
        sections, length_unit = stiffness_design(sections), sections.length_unit
    low, high = [], []  # (limit, source)
    notes = []
    u = length_unit
    if sections.flexures is not None:
        f = sections.flexures
        # the blades are unstressed neutral_offset towards the output from the operating position
        high.append((f.travel - f.neutral_offset, f"[flexures] travel {_length(f.travel, u)}"))
        low.append((-f.travel - f.neutral_offset, f"[flexures] travel {_length(f.travel, u)}"))
    if sections.springs is not None:
        sp = sections.springs
        if sp.installed_length is None:
            notes.append("[springs] has no installed_length: the springs' stroke is not checked")
        else:
            solid = spring_solid_height(sp.wire_diameter, sp.active_coils, sp.end_type)
            high.append((sp.installed_length - solid, f"[springs] solid height {_length(solid, u)} "
                                                      f"(installed {_length(sp.installed_length, u)})"))
            low.append((sp.installed_length - sp.free_length, f"[springs] free length {_length(sp.free_length, u)} "
                                                              f"(installed {_length(sp.installed_length, u)})"))
    if explicit is not None:
        high.append((explicit, f"[checks] carriage_travel_limit {_length(explicit, u)}"))
        low.append((-explicit, f"[checks] carriage_travel_limit {_length(explicit, u)}"))
    lo = max(low, key=lambda t: t[0]) if low else (None, "")
    hi = min(high, key=lambda t: t[0]) if high else (None, "")
    if not low and not high:
        notes.append("no carriage travel limit: the design has no [flexures]/[springs] and no "
                     "[checks] carriage_travel_limit")
    return CarriageTravelLimits(lo[0], hi[0], lo[1], hi[1], tuple(notes))


# ------------------------------------------------------------------------- preloaded loop
#: the four meshes of the dual-pinion loop: name -> (gear 1, gear 2) in the placement
LOOP_MESHES = {
    "mesh1_a": ("input", "cluster_large_a"),
    "mesh1_b": ("input", "cluster_large_b"),
    "mesh2_a": ("cluster_small_a", "output"),
    "mesh2_b": ("cluster_small_b", "output"),
}
_ROLE = {"input": "input", "cluster_large_a": "cluster_large", "cluster_large_b": "cluster_large",
         "cluster_small_a": "cluster_small", "cluster_small_b": "cluster_small", "output": "output"}

#: the meshes of the loop whose centre distance the preload carriage sets
CARRIAGE_MESHES = ("mesh1_a", "mesh1_b")


class LoopModel:
    """The preloaded dual-pinion loop under errors: carriage closure on the continuous branch and
    mesh 1's clearance in closed form (the exact check confirms it; see the module docstring).

    Error state: ``offsets`` ``(n, 6, 2)`` (mm, tooth-circle centre minus axis, gears in
    :data:`geargen.core.synthesis.OFFSET_GEARS` order), ``tooth`` ``(n, 8)`` (mm along the
    reference circle, counter-clockwise, the tooth in contact in each of
    :data:`geargen.core.synthesis.TOOTH_CONTACTS`), and per mesh 1 the displacement into the
    play of the pair on its non-working side (mm along each gear's reference circle).
    """

    def __init__(self, synthesis, setups: dict[str, MeshSetup], errors: dict[str, GearErrors],
                 backlash_mesh1: float, backlash_mesh2: float, steps_per_tooth: int = 24):
        from geargen.core.synthesis import solve_loop
        from geargen.core.tolerance import ROLE_OF_CONTACT, ROLE_OF_OFFSET

        self.synthesis = synthesis
        self.setups = setups
        self.b1, self.b2 = backlash_mesh1, backlash_mesh2
        self.amp_b = np.array([_amplitudes(errors.get(r))[0] for r in ROLE_OF_OFFSET])
        self.amp_p = np.array([_amplitudes(errors.get(r))[1] for r in ROLE_OF_OFFSET])
        self.amp_t = np.array([_amplitudes(errors.get(r))[2] for r in ROLE_OF_CONTACT])
        self.amp_nw = {name: (_amplitudes(errors.get(_ROLE[LOOP_MESHES[name][0]]))[2],
                              _amplitudes(errors.get(_ROLE[LOOP_MESHES[name][1]]))[2]) for name in CARRIAGE_MESHES}
        self._solve = solve_loop
        nominal = solve_loop(synthesis, backlash_mesh1, backlash_mesh2).check()
        self.x0 = float(nominal.carriage_x[0])
        # the loop's rotations hold in the synthesis plane (the clusters' large-gear faces); a mesh
        # setup's at each gear's own z = 0 face, which for helical gears with offset faces differs
        # by the helix's turn between the two: carry that constant into every solved state
        self.phase = {name: (setups[name].rotation1 - float(nominal.input_rotation[0]),
                             setups[name].rotation2 - float((nominal.cluster_rotation_a if name == "mesh1_a"
                                                             else nominal.cluster_rotation_b)[0]))
                      for name in CARRIAGE_MESHES if name in setups}
        # linear predictor of the carriage position (central differences), and how far apart
        # neighbouring closures lie: the input turned one tooth against one cluster
        h = 1e-5 * synthesis.inputs.module_mesh1
        off = np.zeros((40, 6, 2))
        tooth = np.zeros((40, 8))
        for p in range(20):
            for j, sign in enumerate((1.0, -1.0)):
                if p < 12:
                    off[2 * p + j, p // 2, p % 2] = sign * h
                else:
                    tooth[2 * p + j, p - 12] = sign * h
        x = solve_loop(synthesis, backlash_mesh1, backlash_mesh2, offsets=off, tooth_errors=tooth).check().carriage_x
        grad = (x[0::2] - x[1::2]) / (2 * h)
        self.grad_offsets, self.grad_tooth = grad[:12].reshape(6, 2), grad[12:]
        inp = synthesis.inputs
        circular_pitch1 = 2 * math.pi * inp.reference_radius(1) / inp.teeth[0]
        self.spacing = abs(self.grad_tooth[0]) * circular_pitch1
        self.radius = {"input": inp.reference_radius(1), "cluster_large": inp.reference_radius(2)}
        self.models, self.nominal_angular_play = {}, {}
        for name in CARRIAGE_MESHES:
            su = setups[name]
            self.nominal_angular_play[name] = _nominal_angular_play(su, steps_per_tooth)
            self.models[name] = PairModel(su, self.nominal_angular_play[name], su.planes(3))

    # ---------------------------------------------------------------- error states
    def offsets_of(self, phases):
        """Offsets ``(n, 6, 2)`` for bearing and pitch-line phases ``(n, 6, 2)``."""
        ph = np.asarray(phases)
        return (self.amp_b[None, :, None] * np.stack([np.cos(ph[..., 0]), np.sin(ph[..., 0])], -1)
                + self.amp_p[None, :, None] * np.stack([np.cos(ph[..., 1]), np.sin(ph[..., 1])], -1))

    def closure(self, offsets, tooth):
        """The loop closed on the branch continuous with the error-free assembly: a
        :class:`~geargen.core.synthesis.LoopSolution` for each state."""
        offsets = np.asarray(offsets, dtype=float)
        tooth = np.asarray(tooth, dtype=float)
        pred = self.x0 + np.einsum("nkc,kc->n", offsets, self.grad_offsets) + tooth @ self.grad_tooth
        sol = self._solve(self.synthesis, self.b1, self.b2, offsets=offsets, tooth_errors=tooth, x_start=pred)
        off_branch = ~sol.converged | (np.abs(sol.carriage_x - pred) > self.spacing / 4)
        if np.any(off_branch):
            # follow the errors up from zero so each closure stays on the assembly's branch
            idx = np.nonzero(off_branch)[0]
            steps = int(min(64, max(2, math.ceil(np.max(np.abs(pred[idx] - self.x0)) / (self.spacing / 8)))))
            x = np.full(idx.size, self.x0)
            for k in range(1, steps + 1):
                f = k / steps
                step = self._solve(self.synthesis, self.b1, self.b2, offsets=offsets[idx] * f,
                                   tooth_errors=tooth[idx] * f, x_start=x + (pred[idx] - self.x0) / steps)
                x = np.where(np.isfinite(step.carriage_x), step.carriage_x, x)
            again = self._solve(self.synthesis, self.b1, self.b2, offsets=offsets[idx], tooth_errors=tooth[idx],
                                x_start=x)
            sol = _merge_solutions(sol, again, idx)
        return sol

    def centres(self, name: str, sol, offsets):
        """Tooth-circle centres ``(n, 2)`` of the two gears of carriage mesh ``name``."""
        syn = self.synthesis
        x2, y2 = syn.x2, syn.y2
        sign = 1.0 if name == "mesh1_a" else -1.0
        k = 1 if name == "mesh1_a" else 2
        c_in = np.column_stack([sol.carriage_x, np.zeros(len(sol.carriage_x))]) + offsets[:, 0, :]
        c_cl = np.array([x2, sign * y2])[None, :] + offsets[:, k, :]
        return c_in, c_cl

    def into_gap(self, name: str, tooth):
        """Working-side displacement into the play of mesh ``name``'s pair in contact, as angles of
        (input, cluster) (rad): mesh 1A works on the counter-clockwise flanks, 1B on the clockwise."""
        if name == "mesh1_a":
            return tooth[:, 0] / self.radius["input"], tooth[:, 2] / self.radius["cluster_large"]
        return -tooth[:, 1] / self.radius["input"], -tooth[:, 3] / self.radius["cluster_large"]

    def clearance(self, name: str, sol, offsets, tooth, non_working):
        """Mesh 1 clearance (circumferential, mm) in closed form; ``non_working`` ``(n, 2)``: the
        displacement into the play of the non-working pair (mm, input and cluster)."""
        m = self.models[name]
        c_in, c_cl = self.centres(name, sol, offsets)
        a = np.hypot(*(c_cl - c_in).T)
        w1, w2 = self.into_gap(name, tooth)
        g1, g2 = m.gear1, m.gear2
        reduction = (g1.base_radius * (w1 + non_working[:, 0] / g1.reference_radius)
                     + g2.base_radius * (w2 + non_working[:, 1] / g2.reference_radius))
        return m.circumferential(m.total_play(a) - reduction), a

    def exact_clearance(self, name: str, sol, offsets, tooth, non_working):
        """Mesh 1 clearance measured by the exact check at the closed loop's placement: every tooth
        of each gear displaced as the pair in contact (working flank) and the pair on the other
        side (non-working flank). Returns (circumferential, normal, working-side play) in mm."""
        su = self.setups[name]
        g1s, g2s = su.gear1, su.gear2
        c_in, c_cl = self.centres(name, sol, offsets)
        w1, w2 = self.into_gap(name, tooth)
        n1 = non_working[:, 0] / g1s.reference_radius
        n2 = non_working[:, 1] / g2s.reference_radius
        rot_cl = sol.cluster_rotation_a if name == "mesh1_a" else sol.cluster_rotation_b
        # flanks (lower, upper), + adds material: mesh 1A works on the upper flanks, 1B on the lower
        if name == "mesh1_a":
            f1, f2 = np.stack([n1, w1], -1), np.stack([n2, w2], -1)
        else:
            f1, f2 = np.stack([w1, n1], -1), np.stack([w2, n2], -1)
        d1, d2 = self.phase[name]
        ccw, cw = _exact_play(su, c_in, sol.input_rotation + d1, c_cl, rot_cl + d2, f1[:, None, :], f2[:, None, :])
        a = np.hypot(*(c_cl - c_in).T)
        ang = ccw + cw
        normal = ang * polar_outline(g1s).r_base * math.cos(g1s.base_helix_angle)
        working = (ccw if name == "mesh1_a" else cw) * polar_outline(g1s).r_base
        return _circumferential(su, ang), normal, working

    def worst_non_working(self, name: str, n: int):
        t1, t2 = self.amp_nw[name]
        return np.tile([t1, t2], (n, 1))


def _merge_solutions(sol, part, idx):
    """``sol`` with the states ``idx`` replaced by ``part``."""
    def put(a, b):
        a = np.array(a, copy=True)
        a[idx] = b
        return a
    from geargen.core.synthesis import LoopSolution

    conv = put(sol.converged, part.converged)
    bad = int(np.count_nonzero(~conv))
    return LoopSolution(success=bad == 0, message="converged" if bad == 0 else f"{bad} states did not close",
                        carriage_x=put(sol.carriage_x, part.carriage_x),
                        input_rotation=put(sol.input_rotation, part.input_rotation),
                        cluster_rotation_a=put(sol.cluster_rotation_a, part.cluster_rotation_a),
                        cluster_rotation_b=put(sol.cluster_rotation_b, part.cluster_rotation_b),
                        output_rotation=sol.output_rotation, converged=conv,
                        iterations=max(sol.iterations, part.iterations))


# ---------------------------------------------------------------- global search over the error state
@dataclass
class LoopWorstState:
    """The error state a search found (one state) and its objective value."""

    value: float
    phases: np.ndarray  # (6, 2)
    tooth: np.ndarray  # (8,) mm
    evaluations: int


def search_loop(model: LoopModel, objective, starts=(), grid: int = 16, sweeps: int = 2,
                ftol: float = SEARCH_FTOL) -> LoopWorstState:
    """Smallest ``objective(sol, offsets, tooth)`` over every error state of the budget.

    Variables: each gear's bearing and pitch-line phase (free), each contact's tooth
    displacement in [-t/2, t/2]. A phase grid of ``grid`` x ``grid`` per gear in turn (the
    others held; ``sweeps`` passes, tooth displacements at whichever limit is lower), then
    L-BFGS-B on all variables from the best grid point and from ``starts`` ((phases, tooth)
    pairs, e.g. the worst Monte Carlo samples), each until an iteration gains less than ``ftol``.
    """
    from scipy.optimize import minimize

    amp_b, amp_p, amp_t = model.amp_b, model.amp_p, model.amp_t
    count = [0]

    def value_of(off, tooth):
        sol = model.closure(off, tooth)
        count[0] += len(off)
        v = objective(sol, off, tooth)
        return np.where(sol.converged & np.isfinite(v), v, np.inf)

    def value(ph, tooth):
        ph = np.asarray(ph, dtype=float).reshape(-1, 6, 2)
        return value_of(model.offsets_of(ph), np.asarray(tooth, dtype=float).reshape(-1, 8))

    active_b = amp_b > 0
    active_p = amp_p > 0
    active_t = amp_t > 0
    # a start from the linearisation: each gear's offset, alone at full size, turned to where the
    # objective falls fastest; each tooth displacement at the limit that lowers it
    ph = np.zeros((6, 2))
    for k in range(6):
        amp = amp_b[k] + amp_p[k]
        if amp == 0:
            continue
        ang = np.arange(4) * math.pi / 2
        off = np.zeros((4, 6, 2))
        off[:, k, :] = amp * np.stack([np.cos(ang), np.sin(ang)], -1)
        v = value_of(off, np.zeros((4, 8)))
        ph[k] = math.atan2(v[3] - v[1], v[2] - v[0])
    tooth = np.zeros(8)
    if active_t.any():
        eye = np.eye(8)[active_t] * amp_t[None, :]
        vp = value(np.repeat(ph[None], eye.shape[0], 0), eye)
        vm = value(np.repeat(ph[None], eye.shape[0], 0), -eye)
        tooth[active_t] = np.where(vp < vm, amp_t[active_t], -amp_t[active_t])
    best_v = value(ph[None], tooth[None])[0]
    # dense phase grid per gear in turn
    g = np.linspace(0.0, 2 * math.pi, grid, endpoint=False)
    for _ in range(sweeps):
        for k in range(6):
            if not (active_b[k] or active_p[k]):
                continue
            if active_b[k] and active_p[k]:
                A, B = np.meshgrid(g, g, indexing="ij")
                cand = np.stack([A.ravel(), B.ravel()], -1)
            else:
                one = np.linspace(0.0, 2 * math.pi, grid * 4, endpoint=False)
                cand = np.stack([one, one], -1)
            phs = np.repeat(ph[None], cand.shape[0], axis=0)
            phs[:, k, :] = cand
            v = value(phs, np.repeat(tooth[None], cand.shape[0], axis=0))
            i = int(np.argmin(v))
            if v[i] < best_v:
                best_v, ph = v[i], phs[i]
        if active_t.any():
            flips = np.repeat(tooth[None], 8, axis=0)
            flips[np.arange(8), np.arange(8)] *= -1
            v = value(np.repeat(ph[None], 8, axis=0), flips)
            better = (v < best_v) & active_t
            if better.any():
                trial = np.where(better, -tooth, tooth)
                vt = value(ph[None], trial[None])[0]
                if vt < best_v:
                    best_v, tooth = vt, trial
                else:
                    i = int(np.argmin(v))
                    best_v, tooth = v[i], flips[i]
    # local refinement of all variables: phases free, tooth displacements scaled to [-1, 1]
    free_ph = np.stack([active_b, active_p], -1).ravel()
    n_ph = int(free_ph.sum())
    scale = np.where(active_t, amp_t, 1.0)

    def unpack(z):
        """Phases ``(..., 6, 2)`` and tooth displacements ``(..., 8)`` of variables ``z`` ``(..., n)``."""
        z = np.asarray(z)
        p = np.repeat(ph.reshape(1, 12), len(z) if z.ndim > 1 else 1, axis=0)
        p[:, free_ph] = z.reshape(-1, z.shape[-1])[:, :n_ph]
        t = np.zeros((len(p), 8))
        t[:, active_t] = z.reshape(-1, z.shape[-1])[:, n_ph:] * scale[active_t]
        return p.reshape(z.shape[:-1] + (6, 2)), t.reshape(z.shape[:-1] + (8,))

    def fun(z):
        n = z.size
        step = 1e-5
        Z = np.repeat(z[None], 2 * n + 1, axis=0)
        Z[1:n + 1][np.arange(n), np.arange(n)] += step
        Z[n + 1:][np.arange(n), np.arange(n)] -= step
        v = value(*unpack(Z))  # every row at once
        grad = (v[1:n + 1] - v[n + 1:]) / (2 * step)
        return float(v[0]), np.where(np.isfinite(grad), grad, 0.0)

    def pack(p, t):
        return np.concatenate([np.asarray(p).ravel()[free_ph], (np.asarray(t) / scale)[active_t]])

    n_t = int(active_t.sum())
    bounds = [(None, None)] * n_ph + [(-1.0, 1.0)] * n_t
    best_state = (best_v, ph.copy(), tooth.copy())
    for p0, t0 in [(ph, tooth)] + list(starts):
        z0 = pack(p0, np.clip(t0, -amp_t, amp_t))
        if z0.size == 0:
            continue
        r = minimize(fun, z0, jac=True, method="L-BFGS-B", bounds=bounds,
                     options={"maxiter": 60, "ftol": ftol, "gtol": 1e-14})
        p_r, t_r = unpack(r.x)
        v_r = value(p_r[None], t_r[None])[0]
        if v_r < best_state[0]:
            best_state = (v_r, p_r, t_r)
    return LoopWorstState(float(best_state[0]), best_state[1], best_state[2], count[0])


@dataclass
class LoopBuilds:
    """Random builds of the loop at one random instant each: offsets ``(S, 6, 2)``, contact tooth
    displacements ``(S, 8)``, non-working displacements per carriage mesh ``(S, 2)`` (mm), the
    offsets' phases at that instant ``(S, 6, 2)``, and the pair builds of mesh 2A and 2B (the
    same output gear's teeth in both)."""

    phases: np.ndarray
    offsets: np.ndarray
    tooth: np.ndarray
    non_working: dict
    pairs: dict


def _draw_loop_builds(model: LoopModel, setups, errors, samples: int, rng: np.random.Generator) -> LoopBuilds:
    syn = model.synthesis
    z1, z2, z3, z4 = syn.inputs.teeth
    build_phases = rng.uniform(0.0, 2 * math.pi, (samples, 6, 2))  # at the placed state, per offset gear
    teeth = {}
    for gear in ("cluster_small_a", "cluster_small_b", "output"):
        t = _amplitudes(errors.get(_ROLE[gear]))[2]
        spec = setups["mesh2_a" if gear != "cluster_small_b" else "mesh2_b"]
        z = spec.gear2.teeth if gear == "output" else spec.gear1.teeth
        teeth[gear] = rng.uniform(-t, t, (samples, z))
    # one instant of each build: the input turned anywhere over z2 z4 of its revolutions, after
    # which every gear has made whole turns and every tooth pairing recurs
    turn_in = rng.uniform(0.0, 2 * math.pi * z2 * z4, samples)
    turn_cl = -turn_in * z1 / z2
    turn_out = turn_in * z1 * z3 / (z2 * z4)
    turns = np.stack([turn_in, turn_cl, turn_cl, turn_cl, turn_cl, turn_out], -1)
    phases = build_phases + turns[..., None]
    offsets = model.offsets_of(phases)
    tooth = model.amp_t[None, :] * rng.uniform(-1.0, 1.0, (samples, 8))
    non_working = {}
    for name in CARRIAGE_MESHES:
        t1, t2 = model.amp_nw[name]
        non_working[name] = np.column_stack([rng.uniform(-t1, t1, samples), rng.uniform(-t2, t2, samples)])
    pairs = {}
    for name, small, k in (("mesh2_a", "cluster_small_a", 3), ("mesh2_b", "cluster_small_b", 4)):
        ph = np.column_stack([build_phases[:, k, 0], build_phases[:, k, 1], build_phases[:, 5, 0],
                              build_phases[:, 5, 1]])
        pairs[name] = PairBuilds(ph, teeth[small], teeth["output"])
    return LoopBuilds(phases, offsets, tooth, non_working, pairs)


def loop_tolerance(synthesis, setups: dict[str, MeshSetup], errors: dict[str, GearErrors], backlash_mesh1: float,
                   backlash_mesh2: float, samples: int, rng: np.random.Generator,
                   travel_limit: float | CarriageTravelLimits | None = None, steps_per_tooth: int = 24,
                   unit: str = "mm") -> list[ToleranceResult]:
    """Worst case and Monte Carlo backlash of the four meshes of a preloaded dual-pinion loop, and
    the travel of its preload carriage.

    ``setups``: the nominal placed meshes (keys of :data:`LOOP_MESHES`); ``errors`` by gear role
    (``input``, ``cluster_large``, ``cluster_small``, ``output``); ``backlash_mesh*``: the
    circumferential backlash (reference circles) the modelled gears have at the design centre
    distances, as :func:`geargen.core.synthesis.solve_loop` takes it; ``travel_limit``: the
    carriage's limits (:func:`carriage_travel_limits`), or one number either way (mm), or None;
    ``unit``: the length unit of the messages. See the module docstring.
    """
    if travel_limit is None or isinstance(travel_limit, CarriageTravelLimits):
        limits = travel_limit
    else:
        t = float(travel_limit)
        src = f"carriage_travel_limit {_length(t, unit)}"
        limits = CarriageTravelLimits(-t, t, src, src)
    model = LoopModel(synthesis, setups, errors, backlash_mesh1, backlash_mesh2, steps_per_tooth)
    builds = _draw_loop_builds(model, setups, errors, samples, rng) if samples > 0 else None

    results: dict[str, ToleranceResult] = {}
    for name in ("mesh2_a", "mesh2_b"):
        ga, gb = LOOP_MESHES[name]
        results[name] = _pair_result(setups[name], errors.get(_ROLE[ga]), errors.get(_ROLE[gb]),
                                     builds.pairs[name] if builds is not None else None, "backlash",
                                     steps_per_tooth, unit)

    # Monte Carlo of the carriage meshes: each build at its instant, through the exact loop
    mc = {}
    mc_travel = np.empty(0)
    closed = None
    if builds is not None:
        sol = model.closure(builds.offsets, builds.tooth)
        closed = sol.converged
        mc_travel = sol.carriage_x[closed] - model.x0
        for name in CARRIAGE_MESHES:
            nw = builds.non_working[name]
            idx = np.nonzero(closed)[0]
            sub = subset_solution(sol, idx)
            circ, _, _ = model.exact_clearance(name, sub, builds.offsets[idx], builds.tooth[idx], nw[idx])
            model_circ, _ = model.clearance(name, sub, builds.offsets[idx], builds.tooth[idx], nw[idx])
            aligned = np.full(samples, np.nan)  # by build, for the worst-case starts and the loop count
            aligned[idx] = circ
            mc[name] = (circ, float(np.max(np.abs(circ - model_circ))) if idx.size else float("nan"), aligned)

    def worst_starts(values, count=2):
        if values is None:
            return []
        order = np.argsort(values)[:count]
        return [(builds.phases[i], builds.tooth[i]) for i in order if np.isfinite(values[i])]

    # worst cases: the carriage meshes' clearance and the carriage travel, by global search
    worst = {}
    for name in CARRIAGE_MESHES:
        def objective(sol, off, tooth, name=name):
            return model.clearance(name, sol, off, tooth, model.worst_non_working(name, len(off)))[0]

        worst[name] = search_loop(model, objective, worst_starts(mc[name][2] if mc else None))
    travel = {}
    for sign in (1.0, -1.0):
        starts = []
        if builds is not None and mc_travel.size:
            j = np.nonzero(closed)[0][int(np.argmin(sign * mc_travel))]
            starts = [(builds.phases[j], builds.tooth[j])]
        travel[sign] = search_loop(model, lambda sol, off, tooth, s=sign: s * (sol.carriage_x - model.x0), starts)
    travel_low, travel_high = travel[1.0].value, -travel[-1.0].value

    for k, name in enumerate(CARRIAGE_MESHES):
        su = setups[name]
        w = worst[name]
        off = model.offsets_of(w.phases[None])
        sol = model.closure(off, w.tooth[None])
        nw = model.worst_non_working(name, 1)
        circ, normal, working = model.exact_clearance(name, sol, off, w.tooth[None], nw)
        c_in, c_cl = model.centres(name, sol, off)
        res = ToleranceResult(
            mesh=name, meant_for="preloaded",
            nominal_min_backlash=float(_circumferential(su, model.nominal_angular_play[name])),
            worst_case_min_backlash=float(circ[0]), worst_case_min_normal_backlash=float(normal[0]),
            monte_carlo_min_backlash=mc[name][0] if mc else np.empty(0),
            worst_case_centre_distance_change=float(np.hypot(*(c_cl - c_in)[0]) - su.centre_distance),
            carriage_travel=max(abs(travel_low), abs(travel_high)),
            monte_carlo_coverage="one random instant of the loop",
            monte_carlo_model_difference=mc[name][1] if mc else float("nan"),
            worst_case_method=f"global search over the error state ({w.evaluations} loop closures: phase grid "
                              "per gear, then L-BFGS-B), measured by the exact check",
            carriage_travel_low=travel_low, carriage_travel_high=travel_high, monte_carlo_travel=mc_travel,
            carriage_limits=limits)
        if not bool(sol.converged[0]):
            res.failures.append(Failure("preload_contact_lost", name,
                                        "the loop does not close in this mesh's worst error state"))
        _guard_bound(res, unit)
        if res.samples:
            res.notes.append(f"{name}: {res.samples_without_backlash} of {res.samples} Monte Carlo builds have "
                             "backlash <= 0 at their sampled instant"
                             + (f" ({samples - res.samples} more do not close the loop)" if res.samples < samples
                                else ""))
            if closed is not None and not closed.all():
                res.failures.append(Failure("preload_contact_lost", name,
                                            f"the loop does not close in {int((~closed).sum())} of {samples} "
                                            "Monte Carlo builds"))
        if res.worst_case_min_backlash <= 0:
            res.failures.append(Failure(
                "preload_contact_lost", name,
                f"worst-case backlash {_length(res.worst_case_min_backlash, unit)}: the non-working flanks of "
                f"{name} close, the carriage bottoms on them and the springs no longer set the preload",
                "circumferential_backlash", res.worst_case_min_backlash, 0.0))
        results[name] = res

    _carriage_failures(results["mesh1_a"], travel_low, travel_high, mc_travel, limits, unit)
    first = results["mesh1_a"]
    first.notes.append(f"carriage travel from nominal (+ away from the output): worst case "
                       f"{travel_low / LENGTH_SUFFIXES[unit]:+.4g} / {travel_high / LENGTH_SUFFIXES[unit]:+.4g} {unit}"
                       + (f"; Monte Carlo {mc_travel.min() / LENGTH_SUFFIXES[unit]:+.4g} / "
                          f"{mc_travel.max() / LENGTH_SUFFIXES[unit]:+.4g} {unit}" if mc_travel.size else ""))
    if limits is not None:
        if limits.limited:
            k = LENGTH_SUFFIXES[unit]
            first.notes.append("carriage travel limits: "
                               + (f"{limits.low / k:+.4g} {unit} ({limits.low_source})" if limits.low is not None
                                  else "none towards the output")
                               + " / " + (f"{limits.high / k:+.4g} {unit} ({limits.high_source})"
                                          if limits.high is not None else "none away from the output"))
        first.notes.extend(limits.notes)
    if builds is not None:
        lost = ~closed
        for name in CARRIAGE_MESHES:
            lost |= mc[name][2] <= 0
        for name in ("mesh2_a", "mesh2_b"):
            lost |= results[name].monte_carlo_min_backlash <= 0
        for name in LOOP_MESHES:
            results[name].loop_samples_without_backlash = int(lost.sum())
        first.notes.append(f"loop: {int(lost.sum())} of {samples} Monte Carlo builds lose backlash in some mesh "
                           "(mesh 1 at the sampled instant, mesh 2 over its hunting period)")
    return [results[name] for name in LOOP_MESHES]


def subset_solution(sol, idx):
    """The states ``idx`` of a :class:`~geargen.core.synthesis.LoopSolution`."""
    from geargen.core.synthesis import LoopSolution

    conv = sol.converged[idx]
    return LoopSolution(success=bool(conv.all()), message=sol.message, carriage_x=sol.carriage_x[idx],
                        input_rotation=sol.input_rotation[idx], cluster_rotation_a=sol.cluster_rotation_a[idx],
                        cluster_rotation_b=sol.cluster_rotation_b[idx], output_rotation=sol.output_rotation,
                        converged=conv, iterations=sol.iterations)


def _carriage_failures(res: ToleranceResult, low: float, high: float, mc_travel: np.ndarray,
                       limits: CarriageTravelLimits | None, unit: str) -> None:
    """``carriage_travel_exceeded`` on ``res`` for each way the demanded travel passes its limit."""
    if limits is None:
        return
    for demand, mc_demand, limit, source, way in (
            (low, mc_travel.min() if mc_travel.size else None, limits.low, limits.low_source, "towards the output"),
            (high, mc_travel.max() if mc_travel.size else None, limits.high, limits.high_source, "away from the output")):
        if limit is None:
            continue
        beyond = demand < limit if limit <= 0 else demand > limit
        if not beyond:
            continue
        n_mc = int(np.count_nonzero(mc_travel < limit if limit <= 0 else mc_travel > limit))
        mc_text = (f"; Monte Carlo: {n_mc} of {mc_travel.size} builds beyond it (up to "
                   f"{mc_demand / LENGTH_SUFFIXES[unit]:+.4g} {unit})" if mc_demand is not None else "")
        res.failures.append(Failure(
            "carriage_travel_exceeded", "carriage (mesh1_a, mesh1_b)",
            f"the error budget moves the preload carriage {demand / LENGTH_SUFFIXES[unit]:+.4g} {unit} {way} "
            f"(worst case), beyond its limit of {limit / LENGTH_SUFFIXES[unit]:+.4g} {unit} ({source})"
            + mc_text, "carriage_travel", demand, limit))


__all__ = ["alternating_flanks", "worst_flanks", "random_flanks", "worst_case_pair", "PairBuilds", "PairMonteCarlo",
           "pair_minima", "monte_carlo_pair", "eccentric_sweep", "pair_tolerance", "carriage_travel_limits",
           "CARRIAGE_MESHES", "LOOP_MESHES", "SEARCH_FTOL", "LoopModel", "LoopWorstState", "search_loop", "subset_solution",
           "loop_tolerance", "NO_ERRORS"]
