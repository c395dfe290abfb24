"""Each mesh's backlash range from the tooth-thickness allowances, analytic against measured.

The range a mesh can have once its gears are made within their allowances
(:func:`geargen.model.allowance.drive_allowances`) and its centre distance within +-f_a
(``[checks] centre_distance_tolerance_*``): the minimum from both gears at their upper
deviations (thickest) at a - f_a, the maximum from both at their lower deviations (thinnest) at
a + f_a. The analytic value is :func:`geargen.core.allowance.mesh_backlash_range`; the measured
one is path 1 (:mod:`geargen.checks.mesh2d`, exact outlines) on the two extreme pairs built at
those thicknesses and centre distances, over one tooth cycle in the transverse section (without
errors an involute pair's play is the same in every section and position; the minimum and the
maximum over the positions are taken). Both in the resolved model's kind
(:data:`geargen.model.BACKLASH_KIND`).

The range is taken at the centre distance each mesh's allowances were decided at
(:func:`geargen.model.allowance.mesh_range`: where the mesh runs with its gears made at the middle of
their allowances; a dual pinion's carriage mesh where the loop then closes).

Verdict: ``allowance_range_disagrees`` when measured and analytic differ by more than
:data:`AGREEMENT_TOLERANCE`; ``allowance_range_outside_design`` when the range leaves the design
range (by more than :data:`geargen.checks.verdict.RANGE_TOLERANCE`); ``thinning_outside_allowance``
when a gear's modelled thinning (its solids, STEP, STL, DXF and gear data) lies outside its own
allowance: the exported gear would fail its own drawing's inspection. That failure names the
gear table's thinning key and the value at the middle of the allowance (a fix that works: the
allowance is decided from the unthinned teeth, so it stays where it is), or leaving every
``thinning_*`` out (the model is then made at ``[layout] model_tooth_thickness`` of each allowance).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from geargen.checks.mesh2d import MeshSetup, mesh_positions, sweep_backlash
from geargen.checks.results import Failure
from geargen.core.allowance import ThicknessAllowance, mesh_backlash_range, thickest, thinnest
from geargen.design.gear import GearSpec
from geargen.model.allowance import drive_allowances, mesh_range
from geargen.model.layout import Layout
from geargen.units import LENGTH_SUFFIXES

__all__ = ["AGREEMENT_TOLERANCE", "measured_backlash_range", "backlash_ranges", "thinning_outside_allowances"]

#: analytic and measured backlash ranges must agree within this (mm): path 1 resolves the play to
#: ~1e-9 mm (EXACT_TOLERANCE); 1e-6 mm leaves room for the refinement on coarse tooth cycles
AGREEMENT_TOLERANCE = 1e-6

#: mesh positions per tooth of gear 1 the extreme pairs are swept at
STEPS_PER_TOOTH = 4


def measured_backlash_range(gear1: GearSpec, allowance1: ThicknessAllowance, gear2: GearSpec,
                            allowance2: ThicknessAllowance, centre_distance: float,
                            centre_distance_tolerance: float = 0.0,
                            steps_per_tooth: int = STEPS_PER_TOOTH) -> tuple[float, float]:
    """[min, max] circumferential backlash (mm, at gear 1's reference circle) measured by path 1
    on the thickest pair at a - f_a and the thinnest pair at a + f_a (see the module docstring)."""
    out = []
    for pick, a, fn in ((thickest, centre_distance - centre_distance_tolerance, np.nanmin),
                        (thinnest, centre_distance + centre_distance_tolerance, np.nanmax)):
        g1, g2 = pick(gear1, allowance1), pick(gear2, allowance2)
        setup = MeshSetup.centred(g1, g2, a, "allowance")
        angular, _ = sweep_backlash(setup, mesh_positions(setup, steps_per_tooth), np.zeros(1))
        out.append(float(fn(angular)) * g1.reference_radius)
    return out[0], out[1]


def backlash_ranges(layout: Layout, centre_distance_tolerance: float | None = None,
                    range_tolerance: float = 1e-6) -> tuple[list[dict[str, Any]], list[Failure]]:
    """Per engaged mesh with allowances on both gears: its ``backlash_range`` record (mm), and the
    failures (see the module docstring); ``centre_distance_tolerance`` None: the design's (the one
    its model was made with). Meshes of the same gears at the same centre distance (the two loops
    of a dual pinion) are measured once."""
    unit = layout.identity.length_unit
    k = LENGTH_SUFFIXES[unit]
    f = layout.resolved.checks.centre_distance_tolerance if centre_distance_tolerance is None else centre_distance_tolerance
    allowances = drive_allowances(layout, f)
    records, failures = [], []
    seen: dict[tuple, tuple] = {}
    for mesh in layout.meshes:
        g1, g2 = mesh.gear1, mesh.gear2
        if not mesh.engaged or g1.name not in allowances or g2.name not in allowances:
            continue
        a1, a2 = allowances[g1.name], allowances[g2.name]
        a = mesh_range(mesh).centre_distance  # where its allowances were taken
        key = (g1.name, g2.name, a)
        if key not in seen:
            seen[key] = (mesh_backlash_range(g1, a1, g2, a2, a, f), measured_backlash_range(g1, a1, g2, a2, a, f))
        analytic, measured = seen[key]
        difference = max(abs(analytic[0] - measured[0]), abs(analytic[1] - measured[1]))
        agree = difference <= AGREEMENT_TOLERANCE
        inside = mesh.backlash_min - range_tolerance <= analytic[0] and analytic[1] <= mesh.backlash_max + range_tolerance
        records.append({"mesh": mesh.name, "centre_distance": a, "centre_distance_tolerance": f,
                        "analytic": list(analytic), "measured": list(measured), "difference": difference,
                        "agreement_tolerance": AGREEMENT_TOLERANCE,
                        "design": [mesh.backlash_min, mesh.backlash_max], "ok": agree and inside})
        if not agree:
            failures.append(Failure("allowance_range_disagrees", mesh.name,
                                    f"backlash range from the allowances {analytic[0] / k:.6g} to {analytic[1] / k:.6g} "
                                    f"{unit}, measured on the thinnest and thickest teeth {measured[0] / k:.6g} to "
                                    f"{measured[1] / k:.6g} {unit}: {difference / k:.3g} {unit} apart",
                                    "circumferential_backlash", difference, AGREEMENT_TOLERANCE))
        if not inside:
            low = analytic[0] < mesh.backlash_min - range_tolerance
            failures.append(Failure("allowance_range_outside_design", mesh.name,
                                    f"backlash range from the allowances and +-{f / k:.4g} {unit} of centre distance "
                                    f"{analytic[0] / k:.6g} to {analytic[1] / k:.6g} {unit} leaves the design range "
                                    f"{mesh.backlash_min / k:.6g} to {mesh.backlash_max / k:.6g} {unit}",
                                    "circumferential_backlash", analytic[0] if low else analytic[1],
                                    mesh.backlash_min if low else mesh.backlash_max))
    failures += thinning_outside_allowances(layout, allowances)
    return records, failures


def thinning_outside_allowances(layout: Layout, allowances: dict[str, ThicknessAllowance]) -> list[Failure]:
    """``thinning_outside_allowance`` for every gear of ``layout`` whose modelled thinning lies
    outside its allowance (to 1e-9 mm), naming its gear table's key and the middle of the allowance."""
    unit = layout.identity.length_unit
    k = LENGTH_SUFFIXES[unit]
    out, seen = [], set()
    for placed in layout.gears:
        for spec in placed.gears:
            al = allowances.get(spec.name)
            if al is None or spec.name in seen:  # the second of two identical clusters: the same gear
                continue
            seen.add(spec.name)
            c = math.cos(spec.helix_angle)
            band = (-al.upper / c, -al.lower / c)  # circumferential thinning of the thickest, thinnest
            if band[0] - 1e-9 <= spec.thinning <= band[1] + 1e-9:
                continue
            mesh = next((m.name for m in layout.meshes if spec.name in (m.gear1.name, m.gear2.name)), placed.name)
            normal = spec.name in layout.identity.normal_thinning
            key = f"gears.{spec.name}.{'thinning_normal' if normal else 'thinning_circumferential'}_{unit}"
            fix = (band[0] + band[1]) / 2 * (c if normal else 1.0)
            out.append(Failure(
                "thinning_outside_allowance", mesh,
                f"{spec.name}: modelled thinning {spec.thinning / k:.6g} {unit} (circumferential) is outside its "
                f"allowance's {band[0] / k:.6g} to {band[1] / k:.6g} {unit} (upper {al.upper_um:.4g} um, lower "
                f"{al.lower_um:.4g} um normal; {al.method}): its solids, STEP, DXF and gear data show a gear that "
                f"fails its own drawing's inspection. Fix: {key} = {fix / k:.6g} (the middle of the allowance), or "
                f"leave every gear's thinning_* out (the model is then made at [layout] model_tooth_thickness of each "
                f"allowance)", "circumferential_thinning", spec.thinning,
                band[0] if spec.thinning < band[0] else band[1]))
    return out
