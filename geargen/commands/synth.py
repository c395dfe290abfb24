"""``geargen synth DESIGN.toml``: centre synthesis and error budget of a dual-pinion drive.

Prints the Appendix-style table (Hale & Slocum) and what the exact geometry adds; ``--json
FILE`` (``-`` for standard output, then no table) writes the contract JSON
(``../shared/contracts/synthesis.md``); ``--monte-carlo`` runs the tolerance simulation set in
``[monte_carlo]``; ``--histogram PNG`` plots it; ``--sensitivity`` adds the sensitivity tables.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace

from geargen.core.tolerance import exact_error_budget, geometry_sensitivities, monte_carlo, tolerance_sensitivities
from geargen.design.assembly import Design, load_design
from geargen.design.synthesis import GEAR_ROLES, monte_carlo_settings
from geargen.errors import DesignError, GeometryError
from geargen.report.synthesis import SynthesisRun, histogram_png, synthesis_json, text_report, write_json


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("design", help="design file (TOML) with [synthesis] and gears input, cluster_large, "
                                  "cluster_small, output")
    p.add_argument("--json", metavar="FILE", help="write the synthesis JSON to FILE ('-': standard output, no table)")
    p.add_argument("--monte-carlo", action="store_true", help="run the tolerance simulation of [monte_carlo] "
                   "(implied by --samples, --seed, --spring-rate-n-per-mm and --histogram)")
    p.add_argument("--samples", type=int, help="Monte Carlo samples (overrides [monte_carlo] samples)")
    p.add_argument("--seed", type=int, help="Monte Carlo seed (overrides [monte_carlo] seed)")
    p.add_argument("--spring-rate-n-per-mm", type=float, dest="spring_rate",
                   help="preload spring rate (N/mm): also simulate the spring force")
    p.add_argument("--preload-n", type=float, dest="preload", default=0.0,
                   help="spring force at the synthesised position (N), default 0: report the change")
    p.add_argument("--histogram", metavar="PNG", help="plot the Monte Carlo histogram (implies --monte-carlo)")
    p.add_argument("--sensitivity", action="store_true", help="add the sensitivity tables")


def compute(design: Design, run_monte_carlo: bool = False, samples: int | None = None, seed: int | None = None,
            spring_rate: float | None = None, preload: float = 0.0, sensitivity: bool = False) -> SynthesisRun:
    """Every step of ``geargen synth`` on a loaded design; raises DesignError/GeometryError.

    The synthesis and the placement are those of the resolved drive (:func:`geargen.model.resolve`),
    so the centres and backlash printed here are the ones check, build and the exports use."""
    from geargen.drives import resolve

    if not design.section("synthesis"):
        raise DesignError("synthesis", "missing: geargen synth places a dual-pinion drive",
                          "a [synthesis] section (see assemblies/robot_joint.toml)")
    layout = resolve(design)
    run = replace(layout.synthesis, resolved=layout.to_dict())
    synthesis, errors, budget, exact = run.synthesis, run.errors, run.budget, run.exact_budget
    if errors is not None and exact is None:
        raise GeometryError("exact error budget", exact_error_budget(synthesis, errors).message)
    mc = settings = seconds = None
    if run_monte_carlo:
        if errors is None:
            raise DesignError("errors", "missing: the Monte Carlo simulation needs [errors.*] tables",
                              ", ".join(f"[errors.{r}]" for r in GEAR_ROLES))
        settings = monte_carlo_settings(design)
        overrides = {k: v for k, v in (("samples", samples), ("seed", seed)) if v is not None}
        if overrides:
            try:
                settings = replace(settings, **overrides)
            except DesignError as exc:
                raise DesignError(f"--{exc.field}", exc.problem, exc.allowed) from None
        if spring_rate is not None and not spring_rate >= 0:
            raise DesignError("--spring-rate-n-per-mm", f"{spring_rate!r} is out of range", ">= 0 N/mm")
        t0 = time.perf_counter()
        mc = monte_carlo(synthesis, errors, settings.samples, settings.seed, model=settings.model,
                         error_shape=settings.error_shape, include_backlash_tolerance=settings.include_backlash_tolerance,
                         spring_rate=spring_rate, preload=preload)
        seconds = time.perf_counter() - t0
        if not mc.success:
            raise GeometryError("Monte Carlo", mc.message)
    geo = tol = None
    if sensitivity:
        geo = geometry_sensitivities(synthesis)
        if budget is not None:
            tol = tolerance_sensitivities(budget, exact)
    return replace(run, monte_carlo=mc, monte_carlo_settings=settings, monte_carlo_seconds=seconds,
                   geometry_sensitivity=geo, tolerance_sensitivity=tol)


def run(args: argparse.Namespace) -> int:
    design = load_design(args.design)
    wants_mc = args.monte_carlo or any(v is not None for v in (args.histogram, args.samples, args.seed, args.spring_rate))
    result = compute(design, run_monte_carlo=wants_mc, samples=args.samples,
                     seed=args.seed, spring_rate=args.spring_rate, preload=args.preload,
                     sensitivity=args.sensitivity)
    if args.json != "-":
        sys.stdout.write(text_report(result))
    if args.histogram:
        path = histogram_png(result, args.histogram, bins=result.monte_carlo_settings.histogram_bins)
        if args.json != "-":
            print(f"histogram: {path}")
    if args.json:
        write_json(synthesis_json(result), args.json)
    return 0
