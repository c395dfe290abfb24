"""Minimum backlash of each mesh across the error budget: worst case and Monte Carlo, on path 1.

Error model (the same as :mod:`geargen.core.tolerance`): per gear, TIR readings (peak to peak,
mm) of bearing eccentricity, pitch-line eccentricity and tooth-to-tooth error. An eccentricity
TIR ``e`` offsets the gear's tooth circle from its axis by ``e/2``, turning with the gear; a
tooth-to-tooth TIR ``t`` displaces each tooth along the reference circle by up to ``t/2``
either way, independently from tooth to tooth (so neighbouring spaces differ by up to ``t``).
Every backlash value below is measured by the exact 2-D check (:mod:`geargen.checks.mesh2d`) on
the displaced geometry, not by a formula. Backlash is circumferential on gear 1's operating
pitch circle (mm) unless named normal.

**A mesh on fixed bearings.** Worst case: both tooth circles offset straight at each other by
the sum of their eccentricity amplitudes, held for a whole tooth cycle of gear 1 (so every
tooth phase meets the closest approach), with the play narrowed by each gear's ``t``: where
the play is bounded by two different teeth of a gear on its two sides (in every stretch of
double contact), those two teeth at opposite limits take ``t`` off it, which the check models
by making every tooth ``t`` thicker (:func:`worst_flanks`); the minimum over that cycle. Monte
Carlo: each sample draws the eccentricity phases (uniform) and every tooth's displacement
(uniform); the sample's minimum is taken over the two tooth cycles of gear 1 around the closest
approach of the tooth circles within the whole hunting period of the pair (where the minimum
lies, up to the tooth-to-tooth term).

**A preloaded loop (the robot joint, radial-motion preload).** The input gear rides on a
carriage that the springs push towards the output until mesh 1 closes: its working flanks
touch both clusters' large gears, and through the clusters mesh 2 closes on the output. So the
carriage, not a bearing, fixes mesh 1's centre distance, and it moves with every error in the
loop. For each error state the carriage position and every gear's rotation come from the exact
loop closure of :func:`geargen.core.synthesis.solve_loop`; mesh 1 is then placed at its real
centres (tooth-circle offsets included) and its backlash - the clearance left on the
non-working flanks - is measured on path 1. Mesh 2 sits on bearings: the carriage does not
move it, and it is analysed as a mesh on fixed bearings (above). The preloaded meshes stay in contact as long as
the loop closes with backlash left in every mesh (a mesh 1 without it would stop the carriage
on its other flanks, and the springs would no longer set the preload: ``preload_contact_lost``)
and the carriage travel stays within ``carriage_travel_limit``. Worst case of mesh 1: every
error of every gear is set to its limit in the direction that shrinks mesh 1's centre distance
(signs from the exact loop's gradients), the loop is re-solved exactly, and the teeth of the
mesh narrowed as above. Monte Carlo of mesh 1: each sample is one random build
at one random instant (random eccentricity phases, tooth displacements at the loop's contacts,
and independent per-tooth displacements of mesh 1's own teeth), so the samples spread over the
instantaneous backlash; their minimum estimates the minimum over builds and revolutions.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from geargen.checks.mesh2d import (Eccentricity, MeshSetup, MeshState, free_play, mesh_positions, polar_outline,
                                   sweep_mesh)
from geargen.checks.results import Failure, ToleranceResult
from geargen.design.synthesis import GEAR_ROLES, GearErrors
from geargen.units import LENGTH_SUFFIXES

NO_ERRORS = GearErrors()


def _amplitudes(e: GearErrors | None) -> tuple[float, float, float]:
    """(bearing, pitch-line) eccentricity offsets and the tooth displacement limit, mm (TIR / 2)."""
    if e is None:
        return 0.0, 0.0, 0.0
    return e.bearing_eccentricity_tir / 2, e.pitch_line_eccentricity_tir / 2, e.tooth_to_tooth_tir / 2


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


def _circumferential(setup: MeshSetup, angular, centre_distance):
    z1, z2 = setup.gear1.teeth, setup.gear2.teeth
    return angular * centre_distance * z1 / (z1 + z2)


def _backlash(setup: MeshSetup, state: MeshState):
    """Circumferential and normal backlash (mm) at every position of ``state`` (flank play)."""
    play = free_play(polar_outline(setup.gear1), polar_outline(setup.gear2), state)
    ang = play.conjugate_ccw + play.conjugate_cw
    circ = _circumferential(setup, ang, state.centre_distance)
    normal = ang * setup.gear1.base_radius * math.cos(setup.gear1.base_helix_angle)
    return circ, normal


# ------------------------------------------------------------------------- fixed bearings
def worst_case_pair(setup: MeshSetup, errors1: GearErrors | None, errors2: GearErrors | None,
                    steps_per_tooth: int = 24) -> tuple[float, float, float]:
    """Worst-case minimum backlash of a mesh on fixed bearings (see the module docstring).

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
    sw = sweep_mesh(worst, pos, worst.planes(3), areas=False)
    return float(np.nanmin(sw.circumferential_backlash)), float(np.nanmin(sw.normal_backlash)), -(b1 + p1 + b2 + p2)


def monte_carlo_pair(setup: MeshSetup, errors1: GearErrors | None, errors2: GearErrors | None, samples: int,
                     rng: np.random.Generator, steps_per_tooth: int = 8, cycles: int = 2,
                     grid_per_tooth: int = 4) -> np.ndarray:
    """Per-sample minimum backlash (circumferential, mm, ``(samples,)``) of a mesh on fixed
    bearings over its hunting period (see the module docstring)."""
    if samples <= 0:
        return np.empty(0)
    g1, g2 = setup.gear1, setup.gear2
    z1, z2 = g1.teeth, g2.teeth
    b1, p1, t1 = _amplitudes(errors1)
    b2, p2, t2 = _amplitudes(errors2)
    phases = rng.uniform(0.0, 2 * math.pi, (samples, 4))
    c1 = np.asarray(setup.centre1, dtype=float)
    c2 = np.asarray(setup.centre2, dtype=float)

    def centres(s, ph):
        """Tooth-circle centres at mesh positions ``s`` (..., ) for phases ``ph`` (..., 4)."""
        r1, r2 = s, -(z1 / z2) * s
        o1 = (b1 * np.stack([np.cos(ph[..., 0] + r1), np.sin(ph[..., 0] + r1)], -1)
              + p1 * np.stack([np.cos(ph[..., 1] + r1), np.sin(ph[..., 1] + r1)], -1))
        o2 = (b2 * np.stack([np.cos(ph[..., 2] + r2), np.sin(ph[..., 2] + r2)], -1)
              + p2 * np.stack([np.cos(ph[..., 3] + r2), np.sin(ph[..., 3] + r2)], -1))
        return c1 + o1, c2 + o2

    period = 2 * math.pi * setup.hunting_revolutions
    grid = np.linspace(0.0, period, max(8, int(period / (2 * math.pi / z1) * grid_per_tooth)), endpoint=False)
    out = np.empty(samples)
    chunk = max(1, 20000 // (cycles * steps_per_tooth))
    for start in range(0, samples, chunk):
        ph = phases[start:start + chunk]
        S = ph.shape[0]
        a1, a2 = centres(grid[None, :], ph[:, None, :])
        dist = np.linalg.norm(a2 - a1, axis=-1)
        s0 = grid[np.argmin(dist, axis=1)]
        offs = np.linspace(-0.5 * cycles, 0.5 * cycles, cycles * steps_per_tooth, endpoint=False) * (2 * math.pi / z1)
        s = (s0[:, None] + offs[None, :])
        Q = s.shape[1]
        q1, q2 = centres(s, np.repeat(ph[:, None, :], Q, axis=1))
        n = S * Q
        f1 = np.repeat(random_flanks(g1, t1, rng, S), Q, axis=0) if t1 > 0 else None
        f2 = np.repeat(random_flanks(g2, t2, rng, S), Q, axis=0) if t2 > 0 else None
        sf = s.ravel()
        st = MeshState(q1.reshape(n, 2), setup.rotation1 + sf, q2.reshape(n, 2),
                       setup.rotation2 - (z1 / z2) * sf, f1, f2)
        circ, _ = _backlash(setup, st)
        out[start:start + S] = np.nanmin(circ.reshape(S, Q), axis=1)
    return out


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


def pair_tolerance(setup: MeshSetup, errors1: GearErrors | None, errors2: GearErrors | None, samples: int,
                   rng: np.random.Generator, meant_for: str = "backlash", steps_per_tooth: int = 24) -> ToleranceResult:
    """Worst case and Monte Carlo minimum backlash of a mesh on fixed bearings.

    ``meant_for`` "backlash": a failure (``backlash_lost``) when the worst case reaches zero;
    "zero_backlash": reported only.
    """
    pos = mesh_positions(replace(setup, eccentricity1=(), eccentricity2=(), flanks1=None, flanks2=None),
                         steps_per_tooth)
    nominal = float(np.nanmin(sweep_mesh(setup, pos, setup.planes(3), areas=False).circumferential_backlash))
    wc, wc_n, da = worst_case_pair(setup, errors1, errors2, steps_per_tooth)
    mc = monte_carlo_pair(setup, errors1, errors2, samples, rng)
    res = ToleranceResult(mesh=setup.name, meant_for=meant_for, nominal_min_backlash=nominal,
                          worst_case_min_backlash=wc, worst_case_min_normal_backlash=wc_n,
                          monte_carlo_min_backlash=mc, worst_case_centre_distance_change=da,
                          revolutions=eccentric_sweep(setup, errors1, errors2))
    if mc.size:
        res.notes.append(f"{np.count_nonzero(mc <= 0)} of {mc.size} Monte Carlo samples without backlash")
    if meant_for == "backlash" and wc <= 0:
        res.failures.append(Failure("backlash_lost", setup.name,
                                    f"worst-case minimum backlash {wc:.4g} mm across the error budget "
                                    f"(centre distance {da:+.4g} mm, nominal minimum {nominal:.4g} mm)",
                                    "circumferential_backlash", wc, 0.0))
    return res


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


def _loop_centres(synthesis, carriage_x, offsets):
    """Tooth-circle centres ``{gear: (n, 2)}`` of the placed loop for carriage positions and offsets."""
    from geargen.core.synthesis import OFFSET_GEARS

    n = len(carriage_x)
    x2, y2 = synthesis.x2, synthesis.y2
    axes = {"input": np.column_stack([carriage_x, np.zeros(n)]),
            "cluster_large_a": np.tile([x2, y2], (n, 1)), "cluster_large_b": np.tile([x2, -y2], (n, 1)),
            "cluster_small_a": np.tile([x2, y2], (n, 1)), "cluster_small_b": np.tile([x2, -y2], (n, 1)),
            "output": np.zeros((n, 2))}
    if offsets is not None:
        for k, g in enumerate(OFFSET_GEARS):
            axes[g] = axes[g] + offsets[:, k, :]
    return axes


def _loop_rotations(sol):
    return {"input": sol.input_rotation, "cluster_large_a": sol.cluster_rotation_a,
            "cluster_small_a": sol.cluster_rotation_a, "cluster_large_b": sol.cluster_rotation_b,
            "cluster_small_b": sol.cluster_rotation_b,
            "output": np.full(len(sol.carriage_x), sol.output_rotation)}


def _loop_errors(errors: dict[str, GearErrors]):
    """Amplitude arrays in the loop's offset and contact order."""
    from geargen.core.tolerance import ROLE_OF_CONTACT, ROLE_OF_OFFSET

    amp_b = np.array([_amplitudes(errors.get(r))[0] for r in ROLE_OF_OFFSET])
    amp_p = np.array([_amplitudes(errors.get(r))[1] for r in ROLE_OF_OFFSET])
    amp_t = np.array([_amplitudes(errors.get(r))[2] for r in ROLE_OF_CONTACT])
    return amp_b, amp_p, amp_t


#: the meshes of the loop whose centre distance the preload carriage sets
CARRIAGE_MESHES = ("mesh1_a", "mesh1_b")


def loop_tolerance(synthesis, setups: dict[str, MeshSetup], errors: dict[str, GearErrors], backlash_mesh1: float,
                   backlash_mesh2: float, samples: int, rng: np.random.Generator,
                   travel_limit: float | None = None, steps_per_tooth: int = 24,
                   unit: str = "mm") -> list[ToleranceResult]:
    """Worst case and Monte Carlo backlash of the four meshes of a preloaded dual-pinion loop.

    ``setups``: the nominal placed meshes (keys of :data:`LOOP_MESHES`); ``errors`` by gear role
    (``input``, ``cluster_large``, ``cluster_small``, ``output``); ``backlash_mesh*``: the
    circumferential backlash (reference circles) the modelled gears have at the design centre
    distances, as :func:`geargen.core.synthesis.solve_loop` takes it; ``unit`` is the length
    unit of the notes. Mesh 2 sits on bearings and gets :func:`pair_tolerance`; the carriage
    meshes (mesh 1) go through the exact loop. See the module docstring.
    """
    from geargen.core.synthesis import solve_loop
    from geargen.core.tolerance import exact_error_budget

    results: dict[str, ToleranceResult] = {}
    for name, (ga, gb) in LOOP_MESHES.items():
        if name not in CARRIAGE_MESHES:
            results[name] = pair_tolerance(setups[name], errors.get(_ROLE[ga]), errors.get(_ROLE[gb]), samples, rng,
                                           "backlash", steps_per_tooth)

    amp_b, amp_p, amp_t = _loop_errors(errors)
    # worst case of each carriage mesh: every error at its limit in the direction that shrinks
    # its centre distance, by the gradients of the exact loop (central differences)
    h = 1e-5 * synthesis.inputs.module_mesh1
    n_par = 6 * 2 + 8
    offsets = np.zeros((2 * n_par, 6, 2))
    tooth = np.zeros((2 * n_par, 8))
    for p in range(n_par):
        for j, sign in enumerate((1.0, -1.0)):
            if p < 12:
                offsets[2 * p + j, p // 2, p % 2] = sign * h
            else:
                tooth[2 * p + j, p - 12] = sign * h
    sol = solve_loop(synthesis, backlash_mesh1, backlash_mesh2, offsets=offsets, tooth_errors=tooth)
    centres = _loop_centres(synthesis, sol.carriage_x, offsets)
    w_off, w_tooth = [], []
    for name in CARRIAGE_MESHES:
        ga, gb = LOOP_MESHES[name]
        dist = np.linalg.norm(centres[gb] - centres[ga], axis=1)
        grad = (dist[0::2] - dist[1::2]) / (2 * h)
        og, tg = grad[:12].reshape(6, 2), grad[12:]
        norm = np.linalg.norm(og, axis=1, keepdims=True)
        direction = np.divide(og, norm, out=np.zeros_like(og), where=norm > 0)
        w_off.append(-(amp_b + amp_p)[:, None] * direction)
        w_tooth.append(-amp_t * np.sign(tg))
    w_off, w_tooth = np.stack(w_off), np.stack(w_tooth)
    wsol = solve_loop(synthesis, backlash_mesh1, backlash_mesh2, offsets=w_off, tooth_errors=w_tooth)
    wcentres = _loop_centres(synthesis, wsol.carriage_x, w_off)
    wrot = _loop_rotations(wsol)
    budget = exact_error_budget(synthesis, tuple(errors.get(r, NO_ERRORS) for r in GEAR_ROLES))
    travel = (budget.worst_low, budget.worst_high)  # every error pushing the carriage one way, then the other
    for k, name in enumerate(CARRIAGE_MESHES):
        ga, gb = LOOP_MESHES[name]
        su = setups[name]
        pos = mesh_positions(su, steps_per_tooth)
        nominal = float(np.nanmin(sweep_mesh(su, pos, su.planes(3), areas=False).circumferential_backlash))
        r1, r2 = _amplitudes(errors.get(_ROLE[ga]))[2], _amplitudes(errors.get(_ROLE[gb]))[2]
        worst = replace(su, centre1=tuple(wcentres[ga][k]), centre2=tuple(wcentres[gb][k]),
                        rotation1=float(wrot[ga][k]), rotation2=float(wrot[gb][k]), eccentricity1=(), eccentricity2=(),
                        flanks1=worst_flanks(su.gear1, r1) if r1 > 0 else None,
                        flanks2=worst_flanks(su.gear2, r2) if r2 > 0 else None)
        sw = sweep_mesh(worst, mesh_positions(worst, steps_per_tooth, 1.0 / su.gear1.teeth), worst.planes(3),
                        areas=False)
        res = ToleranceResult(mesh=name, meant_for="preloaded", nominal_min_backlash=nominal,
                              worst_case_min_backlash=float(np.nanmin(sw.circumferential_backlash)),
                              worst_case_min_normal_backlash=float(np.nanmin(sw.normal_backlash)),
                              monte_carlo_min_backlash=np.empty(0),
                              worst_case_centre_distance_change=float(worst.centre_distance - su.centre_distance),
                              carriage_travel=max(abs(travel[0]), abs(travel[1])))
        if not wsol.converged[k]:
            res.failures.append(Failure("preload_contact_lost", name,
                                        "the loop does not close in this mesh's worst error state"))
        results[name] = res

    # Monte Carlo: random builds at random instants through the exact loop
    mc_travel = np.empty(0)
    if samples > 0:
        phases = rng.uniform(0.0, 2 * math.pi, (samples, 6, 2))
        offs = (amp_b[None, :, None] * np.stack([np.cos(phases[..., 0]), np.sin(phases[..., 0])], -1)
                + amp_p[None, :, None] * np.stack([np.cos(phases[..., 1]), np.sin(phases[..., 1])], -1))
        tooth = amp_t * rng.uniform(-1.0, 1.0, (samples, 8))
        msol = solve_loop(synthesis, backlash_mesh1, backlash_mesh2, offsets=offs, tooth_errors=tooth)
        ok = msol.converged
        mcentres = _loop_centres(synthesis, msol.carriage_x, offs)
        mrot = _loop_rotations(msol)
        x0 = float(solve_loop(synthesis, backlash_mesh1, backlash_mesh2).carriage_x[0])  # error-free position
        mc_travel = msol.carriage_x[ok] - x0
        for name in CARRIAGE_MESHES:
            ga, gb = LOOP_MESHES[name]
            su = setups[name]
            r1, r2 = _amplitudes(errors.get(_ROLE[ga]))[2], _amplitudes(errors.get(_ROLE[gb]))[2]
            st = MeshState(mcentres[ga][ok], mrot[ga][ok], mcentres[gb][ok], mrot[gb][ok],
                           random_flanks(su.gear1, r1, rng, int(ok.sum())) if r1 > 0 else None,
                           random_flanks(su.gear2, r2, rng, int(ok.sum())) if r2 > 0 else None)
            res = results[name]
            res.monte_carlo_min_backlash = _backlash(su, st)[0]
            res.notes.append(f"Monte Carlo: {samples} random builds, each at a random instant, through the exact "
                             f"loop; {np.count_nonzero(res.monte_carlo_min_backlash <= 0)} without backlash")
            if not ok.all():
                res.failures.append(Failure("preload_contact_lost", name,
                                            f"the loop does not close in {int((~ok).sum())} of {samples} samples"))

    k = LENGTH_SUFFIXES[unit]
    for name in CARRIAGE_MESHES:
        res = results[name]
        res.notes.append(f"carriage travel from nominal (+ away from the output), worst case "
                         f"{travel[0] / k:+.4g} / {travel[1] / k:+.4g} {unit}"
                         + (f"; Monte Carlo {mc_travel.min() / k:+.4g} / {mc_travel.max() / k:+.4g} {unit}"
                            if mc_travel.size else ""))
        if res.worst_case_min_backlash <= 0:
            res.failures.append(Failure(
                "preload_contact_lost", name,
                f"worst-case backlash {res.worst_case_min_backlash:.4g} mm: the carriage would bottom on the "
                "other flanks of mesh 1 and the springs would no longer set the preload",
                "circumferential_backlash", res.worst_case_min_backlash, 0.0))
        if travel_limit is not None and res.carriage_travel > travel_limit:
            res.failures.append(Failure(
                "preload_contact_lost", name,
                f"worst-case carriage travel {res.carriage_travel:.4g} mm exceeds the limit {travel_limit:.4g} mm",
                "carriage_travel_length", res.carriage_travel, travel_limit))
    return [results[name] for name in LOOP_MESHES]


__all__ = ["alternating_flanks", "worst_flanks", "random_flanks", "worst_case_pair", "monte_carlo_pair", "eccentric_sweep",
           "pair_tolerance", "CARRIAGE_MESHES",
           "LOOP_MESHES", "loop_tolerance", "NO_ERRORS"]
