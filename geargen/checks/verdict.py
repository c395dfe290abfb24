"""The one verdict on a resolved drive: what ``geargen check`` prints and what ``geargen build``
gates on (the build adds only what needs its solids: sections of the gear solids and the parts'
overlaps).

For every mesh of the resolved model (:func:`geargen.model.resolve`): path 1 (exact 2-D) at the
placed centres and phases, the design range of the backlash, the range the tooth-thickness
allowances give, analytic against measured (:mod:`geargen.checks.allowance`), the axial clearance of a
disengaged mesh, the exact ratio the design requires, and the error budget (worst case and
Monte Carlo, :mod:`geargen.checks.tolerance`). A design with neither ``[layout]`` nor
``[synthesis]`` names its pairs in ``[checks] meshes``; they are checked centred in their play.

Backlash in the verdict is reported in the resolved model's kind
(:data:`geargen.model.BACKLASH_KIND`: circumferential at gear 1's reference pitch circle), the
same number ``synth``, ``build`` and the exported solids give.
"""

from __future__ import annotations

import math

import numpy as np

from geargen.checks.blas import one_blas_thread
from geargen.checks.hardware import parts_check
from geargen.checks.mesh2d import CheckSettings, MeshSetup, check_mesh
from geargen.checks.results import DesignCheck, Failure
from geargen.checks.structure import drive_structure
from geargen.core.accuracy import gear_errors
from geargen.design.assembly import Design
from geargen.design.checks import ChecksSettings, checks_settings
from geargen.errors import DesignError
from geargen.model import BACKLASH_KIND, Layout, MeshPlacement, is_drive
from geargen.drives.resolver import defaulted, parts_table, resolve
from geargen.units import LENGTH_SUFFIXES

#: below this the design range is met (mm): the path-1 numbers carry ~1e-12 mm of round-off
RANGE_TOLERANCE = 1e-6


def mesh_setup(layout: Layout, mesh: MeshPlacement) -> MeshSetup:
    """The checker's :class:`MeshSetup` of one mesh of the resolved ``layout``."""
    p1, p2 = layout.gear(mesh.part1), layout.gear(mesh.part2)
    z1, z2 = p1.face_z(mesh.gear1)[0], p2.face_z(mesh.gear2)[0]
    return MeshSetup(mesh.name, mesh.gear1, mesh.gear2, tuple(p1.centre), tuple(p2.centre),
                     p1.rotation_at(mesh.gear1, z1), p2.rotation_at(mesh.gear2, z2), face_offset2=z2 - z1)


def design_backlash(check, gear1_reference_radius: float) -> tuple[float, float]:
    """(min, max) backlash of a checker result in the resolved model's kind: gear 1's free
    rotation times its reference radius (mm); NaN when nothing was measured."""
    ang = np.asarray(check.sweep.angular_backlash, dtype=float)
    ang = ang[np.isfinite(ang)]
    if not ang.size:
        return math.nan, math.nan
    return float(np.min(ang) * gear1_reference_radius), float(np.max(ang) * gear1_reference_radius)


def sections_decide(path2, loaded_flank_gap: float = 0.0) -> bool:
    """Whether the failures of a section check (path 2) fail a build or a check: only where the
    sections resolve the working flanks' gap (their stated tolerance below the loaded flank gap,
    and below 1 um). Coarser sections (an STL at its chordal tolerance, helical flanks sampled by
    chords) are reported with their tolerance; the exact path 1 decides, and the agreement of the
    two paths, which allows for the tolerance, is still checked."""
    return path2.tolerance < max(loaded_flank_gap or 0.0, 1e-3)


def undecided(path2) -> list[str]:
    """The failures of a section check that does not decide (:func:`sections_decide`), as notes."""
    return [f"{path2.mesh} (sections of the solids, {f.kind}): {f.message} "
            f"[section tolerance {path2.tolerance:.3g} mm: not decisive]" for f in path2.failures]


def mesh_settings(settings: ChecksSettings, require_backlash: bool | None = None) -> CheckSettings:
    """The checker's settings from ``[checks]``."""
    return CheckSettings(steps_per_tooth=settings.steps_per_tooth, revolutions=settings.revolutions,
                         planes=settings.section_planes, min_contact_ratio=settings.min_contact_ratio,
                         min_tip_land_modules=settings.min_tip_land_modules,
                         require_backlash=settings.require_backlash if require_backlash is None else require_backlash)


@one_blas_thread()
def verify(layout: Layout, settings: ChecksSettings | None = None, tolerances: bool | None = None) -> DesignCheck:
    """Every check of the resolved drive that needs no solid (see the module docstring)."""
    identity = layout.identity
    settings = layout.resolved.checks if settings is None else settings
    unit = identity.length_unit
    k = LENGTH_SUFFIXES[unit]
    result = DesignCheck(design=identity.name, length_unit=unit, meshes=[],
                         notes=list(identity.unit_warnings) + list(layout.notes))
    setups = {}
    for mesh in layout.meshes:
        entry = {"mesh": mesh.name, "gear1": mesh.part1, "gear2": mesh.part2, "kind": BACKLASH_KIND,
                 "engaged": mesh.engaged, "centre_distance": mesh.centre_distance,
                 "modelled": mesh.modelled_backlash, "design_min": mesh.backlash_min,
                 "design_max": mesh.backlash_max}
        result.backlash.append(entry)
        if not mesh.engaged:
            p1, p2 = layout.gear(mesh.part1), layout.gear(mesh.part2)
            (a0, a1), (b0, b1) = p1.face_z(mesh.gear1), p2.face_z(mesh.gear2)
            clearance = max(b0 - a1, a0 - b1)  # axial gap between the two faces
            entry["axial_clearance"] = clearance
            if clearance <= 0:
                result.failures.append(Failure("disengaged_overlap", mesh.name,
                                               f"the disengaged pinion still overlaps the output axially "
                                               f"({clearance / k:.4g} {unit})", "axial_clearance", clearance, 0.0))
            continue
        setup = mesh_setup(layout, mesh)
        setups[mesh.name] = setup
        # a mesh whose design range allows zero backlash is not required to keep it
        check = check_mesh(setup, mesh_settings(settings, settings.require_backlash and mesh.backlash_min > 0))
        result.meshes.append(check)
        lo, hi = design_backlash(check, mesh.gear1.reference_radius)
        entry.update(min=lo, max=hi)
        if math.isfinite(lo) and not (mesh.backlash_min - RANGE_TOLERANCE <= lo
                                      and hi <= mesh.backlash_max + RANGE_TOLERANCE):
            result.failures.append(Failure(
                "backlash_out_of_range", mesh.name,
                f"backlash {lo / k:.6g} to {hi / k:.6g} {unit} ({BACKLASH_KIND}) is outside the design range "
                f"{mesh.backlash_min / k:.6g} to {mesh.backlash_max / k:.6g} {unit}",
                "circumferential_backlash", lo if lo < mesh.backlash_min else hi,
                mesh.backlash_min if lo < mesh.backlash_min else mesh.backlash_max))
    from geargen.checks.allowance import backlash_ranges
    try:
        ranges, range_failures = backlash_ranges(layout, settings.centre_distance_tolerance, RANGE_TOLERANCE)
    except DesignError as exc:  # no allowance meets a range: reported (naming the key), the rest still checked
        ranges = []
        # the allowances are found for the drive's meshes together: the failure names them all
        engaged = ", ".join(m.name for m in layout.meshes if m.engaged) or "drive"
        range_failures = [Failure("allowance_range_outside_design", engaged, f"no tooth-thickness allowance meets the "
                                  f"backlash range: {exc}")]
    result.backlash_range = ranges
    result.failures += range_failures
    if layout.ratio and not layout.ratio["ok"]:
        result.failures.append(Failure("ratio_mismatch", "train",
                                       f"ratio {layout.ratio['what']} is {layout.ratio['total']}, not one of "
                                       f"{layout.ratio['required']} ({layout.ratio['text']})"))
    # the drive kind's own rows: placed pairs the mesh checker does not check (geargen.drives.kind)
    result.rows = layout.drive.rows(layout, result) if layout.drive is not None else []
    result.defaulted = defaulted(layout)
    result.parts_table = parts_table(layout)
    _load_capacity(layout, result)
    if layout.hardware is not None:
        _parts(layout, result, settings)
    if settings.tolerances if tolerances is None else tolerances:
        result.tolerances = _tolerances(layout, setups, settings)
    return result


def _load_capacity(layout: Layout, result: DesignCheck) -> None:
    """Every mesh rated (:func:`geargen.checks.rating.rate_drive`). A safety factor below the minimum
    is a failure when the file states its [duty] or [materials]; on geargen's defaults alone (a
    material and a duty the file never chose) it is a note saying so, with the same fix."""
    from geargen.checks.rating import fix_text, rate_drive
    rating = rate_drive(layout)
    result.load_capacity = rating
    if not rating.rated:
        result.notes.append(f"load capacity not rated: {rating.reason}")
        return
    fix = (" (fix, every mesh rated again with it passes: " + fix_text(rating.fix) + ")"
           if rating.fix is not None else
           " (no ISO 6336-5 material meets the minimum at these loads: a wider face, as the load capacity table's "
           "'b needed', or a lighter [duty])")
    if rating.failures and not rating.duty_stated:
        result.notes.append(f"load capacity on geargen's default duty and materials (the file states no [duty] or "
                            f"[materials]; with either this is a check): {len(rating.failures)} safety factor(s) "
                            f"below the minimum, as the load capacity table shows{fix}")
        return
    for mesh in rating.meshes:
        result.failures += [Failure("load_capacity", mesh.name, text + fix) for text in mesh.failures]


def _parts(layout: Layout, result: DesignCheck, settings: ChecksSettings) -> None:
    """The resolved drive's parts against each other (:func:`geargen.checks.hardware.parts_check`)
    and how they hold together (:func:`geargen.checks.structure.drive_structure`), as failures."""
    report = parts_check(layout)
    result.parts = report
    kinds = {"overlap": "parts_overlap", "interpenetrating": "parts_interpenetrating",
             "missing_contact": "contact_missing"}
    fixes = layout.hardware.fixes
    scale = LENGTH_SUFFIXES[layout.identity.length_unit]
    for f in report.findings:
        offered = [fixes[p] for p in (f.part1, f.part2) if f.kind == "overlap" and p in fixes]
        hint = "".join(f" (fix: {key} = {value / scale:.6g}: {why})" for key, value, why in offered)
        result.failures.append(Failure(kinds[f.kind], "parts", f.message + hint))
    structure = drive_structure(layout)
    result.structure = structure
    if settings.structure == "fail":
        result.failures += [Failure("structure", "parts", text) for text in structure.failures]
    else:
        result.notes += [f"structure ([checks] structure = \"report\"): {text}" for text in structure.failures]


def _tolerances(layout: Layout, setups: dict[str, MeshSetup], settings: ChecksSettings) -> list:
    """The error budget's worst case and Monte Carlo per engaged mesh (seeded by ``[checks] seed``)."""
    from geargen.checks.tolerance import LOOP_MESHES, carriage_travel_limits, loop_tolerance, pair_tolerance
    from geargen.design.synthesis import GEAR_ROLES

    rng = np.random.default_rng(settings.seed)
    if layout.synthesis is not None:  # the loop placed by the centre synthesis: its error budget
        errors = {role: e for role in GEAR_ROLES if (e := layout.resolved.gear_errors(role)) is not None}
        if not errors or set(LOOP_MESHES) - set(setups):
            return []  # no budget, or the pinions are slid out of mesh (disengaged)
        placement = layout.placement
        gap = placement.loaded_flank_gap
        return loop_tolerance(layout.synthesis.synthesis, setups, errors, placement.backlash_mesh1 - 2 * gap,
                              placement.backlash_mesh2 - 2 * gap, settings.monte_carlo_samples, rng,
                              carriage_travel_limits(layout.resolved.stiffness, settings.carriage_travel_limit,
                                                     layout.identity.length_unit),
                              settings.steps_per_tooth, layout.identity.length_unit)
    out = []
    for mesh in layout.meshes:
        if mesh.name not in setups:
            continue
        e1, e2 = layout.resolved.gear_errors(mesh.gear1.name), layout.resolved.gear_errors(mesh.gear2.name)
        if e1 is None and e2 is None:
            continue
        out.append(pair_tolerance(setups[mesh.name], e1, e2, settings.monte_carlo_samples, rng,
                                  "backlash" if settings.require_backlash and mesh.backlash_min > 0 else "zero_backlash",
                                  settings.steps_per_tooth, layout.identity.length_unit))
    return out


def verify_declared(design: Design, settings: ChecksSettings, tolerances: bool | None = None) -> DesignCheck:
    """The pairs of ``[checks] meshes`` (a design that is no drive), each centred in its play."""
    from geargen.checks.tolerance import pair_tolerance
    from geargen.model.gear_data import check_gear_tables

    check_gear_tables(design)
    if not settings.meshes:
        raise DesignError("checks.meshes", "missing: a design without [layout] or [synthesis] must declare the "
                          "pairs to check", '[checks] meshes = [["gear1", "gear2"]] with centre_distance_<unit>')
    cs = mesh_settings(settings)
    setups = [MeshSetup.centred(design.gear(m.gear1), design.gear(m.gear2), m.centre_distance, m.name)
              for m in settings.meshes]
    result = DesignCheck(design=design.name, length_unit=design.length_unit, meshes=[check_mesh(su, cs) for su in setups])
    for su, check in zip(setups, result.meshes):
        lo, hi = design_backlash(check, su.gear1.reference_radius)
        result.backlash.append({"mesh": su.name, "gear1": su.gear1.name, "gear2": su.gear2.name, "kind": BACKLASH_KIND,
                                "engaged": True, "centre_distance": su.centre_distance, "min": lo, "max": hi})
    if settings.tolerances if tolerances is None else tolerances:
        rng = np.random.default_rng(settings.seed)
        for su in setups:
            e1, e2 = gear_errors(design, su.gear1.name), gear_errors(design, su.gear2.name)
            if e1 is None and e2 is None:
                continue
            result.tolerances.append(pair_tolerance(su, e1, e2, settings.monte_carlo_samples, rng,
                                                    "backlash" if settings.require_backlash else "zero_backlash",
                                                    settings.steps_per_tooth, design.length_unit))
    return result


def check_design(design: Design, settings: ChecksSettings | None = None, position: str | None = None,
                 tolerances: bool | None = None) -> tuple[DesignCheck, Layout | None]:
    """The verdict of ``geargen check`` on a loaded design, with the resolved layout it checked.
    ``position`` (engaged or disengaged sliding pinions) is refused for a design that places no drive,
    as ``geargen build`` refuses it (one verdict for both)."""
    settings = checks_settings(design) if settings is None else settings
    if is_drive(design):
        layout = resolve(design, position)
        return verify(layout, settings, tolerances), layout
    if position is not None:
        raise DesignError("--position", "applies to a drive with sliding pinions; this design places no drive",
                          "leave --position out")
    return verify_declared(design, settings, tolerances), None


__all__ = ["RANGE_TOLERANCE", "mesh_setup", "design_backlash", "mesh_settings", "verify", "verify_declared", "check_design"]
