"""Seeded stability sweep of internal (ring) gears: random parameters, each built in a worker
process with a timeout (tests/sweep_support.py).

Every ring either becomes one valid closed solid whose volume is the rim disc less the exact hole
(within 1e-6) and whose flanks lie on the involute (within 0.1 um, mid-face section), or is refused
with a DesignError or one of the GeometryError kinds that mean the parameters cannot make a ring.
Everything else is a tagged failure (``invalid``, ``not_one_solid``, ``wrong_volume``, ``flank``,
``timeout``, ``crash:<exception type>``).

More by hand: ``GEARGEN_SWEEP_COUNT=2000 GEARGEN_SWEEP_SEED=7 pytest tests/test_internal_sweep.py -s``
(``GEARGEN_SWEEP_MAX_TEETH``, default 36).
"""

from __future__ import annotations

import math
import os
import traceback

import numpy as np
import pytest
from sweep_support import assert_sweep, run_sweep

COUNT = int(os.environ.get("GEARGEN_SWEEP_COUNT", "100"))
SEED = int(os.environ.get("GEARGEN_SWEEP_SEED", "20261124"))
#: teeth log-uniform in [16, MAX_TEETH]: the solid's cost grows with the teeth, the coverage does not
MAX_TEETH = int(os.environ.get("GEARGEN_SWEEP_MAX_TEETH", "36"))

#: refusals that are the right answer for rings that cannot be cut (geargen.profile.internal)
EXPECTED_GEOMETRY_KINDS = {"tip_inside_base", "cutter_too_large", "pointed_cutter", "cutter_interference",
                           "no_involute", "pointed_tooth", "fillet_loop", "thin_rim", "cutter_too_thick"}


def random_parameters(rng: np.random.Generator) -> dict:
    helical = rng.random() < 0.5
    return {
        "teeth": int(round(math.exp(rng.uniform(math.log(16), math.log(MAX_TEETH))))),
        "module": float(math.exp(rng.uniform(math.log(0.1), math.log(8.0)))),
        "pressure_angle_deg": float(rng.uniform(14.5, 25.0)),
        "helix_angle_deg": float(rng.uniform(5.0, 35.0)) if helical else 0.0,
        "hand": str(rng.choice(["right", "left"])),
        # rings below ~34 teeth need x > h_a* - z (1 - cos a) / 2 to keep the tip outside the base
        # circle: shifts and addenda are drawn where rings are made, the refusals stay reachable
        "profile_shift": float(rng.uniform(-0.3, 1.2)),
        "addendum_coefficient": float(rng.uniform(0.6, 1.0)),
        "dedendum_coefficient": float(rng.uniform(1.0, 1.5)),
        "cutter_tip_fraction": None if rng.random() < 0.5 else float(rng.uniform(0.0, 0.5)),
        "thinning_modules": float(rng.uniform(0.0, 0.05)) if rng.random() < 0.3 else 0.0,
        "face_modules": float(rng.uniform(1.0, 3.0)),
        "rim_modules": None if rng.random() < 0.5 else float(rng.uniform(0.3, 6.0)),
    }


def make_spec(p: dict):
    from geargen.design.gear import GearSpec
    m = p["module"]
    base = dict(teeth=p["teeth"], module=m, pressure_angle=math.radians(p["pressure_angle_deg"]),
                face_width=p["face_modules"] * m, helix_angle=math.radians(p["helix_angle_deg"]), hand=p["hand"],
                profile_shift=p["profile_shift"], addendum_coefficient=p["addendum_coefficient"],
                dedendum_coefficient=p["dedendum_coefficient"], thinning=p["thinning_modules"] * m, kind="internal")
    plain = GearSpec(**base)
    if p["cutter_tip_fraction"] is not None:
        base["rack_tip_radius_coefficient"] = p["cutter_tip_fraction"] * plain.max_rack_tip_radius_coefficient
    if p["rim_modules"] is not None:
        base["rim_diameter"] = 2 * plain.root_radius_standard + 2 * p["rim_modules"] * m
    return GearSpec(**base)


def check_one(p: dict) -> tuple[str, str]:
    """Build and check one ring; returns (tag, detail). Runs in a worker process."""
    from geargen.errors import DesignError, GeometryError
    try:
        spec = make_spec(p)
        from geargen.cad.gear_solid import check_solid, solid_volume
        from geargen.cad.internal_solid import build_internal
        from geargen.cad.measure import flank_deviation
        # a looser spline than the default 2 nm (still 50x inside the flank bound): a lighter solid
        g = build_internal(spec, tolerance=2e-6 * spec.module)
    except DesignError as exc:
        return "design_error", exc.field.split(".")[-1]
    except GeometryError as exc:
        return f"geometry_error:{exc.kind}", str(exc)[:120]
    except Exception as exc:  # noqa: BLE001 - every other exception is a failure to tag
        return f"crash:{type(exc).__name__}", traceback.format_exc(limit=3)[-300:]
    try:
        problem = check_solid(g.shape)
        if problem:
            return ("not_one_solid" if "solids" in problem else "invalid"), problem
        expected = (math.pi * (spec.rim_diameter / 2) ** 2 - g.profile.hole_area()) * spec.face_width
        vol = solid_volume(g.shape, eps=1e-7)
        if abs(vol / expected - 1) > 1e-6:
            vol = solid_volume(g.shape, eps=1e-9)
        if abs(vol / expected - 1) > 1e-6:
            return "wrong_volume", f"{vol!r} vs {expected!r} ({vol / expected - 1:.2e})"
        dev = flank_deviation(g.shape, g.profile.flank_frame(), 0.5 * spec.face_width, samples_per_face=16)
        if not dev.points or dev.max_abs > 1e-4 * max(1.0, spec.module):
            return "flank", f"{dev}"
    except Exception as exc:  # noqa: BLE001
        return f"crash:{type(exc).__name__}", traceback.format_exc(limit=3)[-300:]
    return "ok", ""


@pytest.mark.slow
def test_random_internal_gears_build_or_are_refused_clearly():
    rng = np.random.default_rng(SEED)
    params = [random_parameters(rng) for _ in range(COUNT)]
    results = run_sweep(params, f"{__file__}:check_one")
    tags = assert_sweep("internal gears", params, results, SEED, EXPECTED_GEOMETRY_KINDS)
    assert tags["ok"] >= 0.5 * COUNT  # mostly rings, not refusals
