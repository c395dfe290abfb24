"""Seeded stability sweep of racks: random parameters, each built in a worker process with a timeout.

Every rack either becomes one valid closed solid whose volume is the closed form (transverse
section area x face width, geargen.core.rack) and whose flanks, sectioned at mid-face, lie on the
exact flank lines within 0.1 um, or is refused with a DesignError naming its field. Everything
else is a tagged failure: ``invalid`` (BRepCheck), ``not_one_solid``, ``wrong_volume``, ``flank``,
``timeout``, ``crash:<exception type>``.

More by hand: ``GEARGEN_RACK_SWEEP_COUNT=2000 GEARGEN_SWEEP_SEED=7 pytest tests/test_rack_sweep.py -s``
(``GEARGEN_SWEEP_TIMEOUT`` seconds per build, default 60; ``GEARGEN_SWEEP_WORKERS``, default 2).
"""

from __future__ import annotations

import math
import os
import traceback

import numpy as np
import pytest
from sweep_support import assert_sweep, run_sweep

COUNT = int(os.environ.get("GEARGEN_RACK_SWEEP_COUNT", "120"))
SEED = int(os.environ.get("GEARGEN_SWEEP_SEED", "20261124"))
#: teeth along the rack are drawn from [1, MAX_TEETH] (a long rack is the same pitch repeated)
MAX_TEETH = int(os.environ.get("GEARGEN_RACK_SWEEP_MAX_TEETH", "12"))


def random_parameters(rng: np.random.Generator) -> dict:
    """One random rack: RackSpec fields, radii and sizes relative to what fits (plain numbers)."""
    helical = rng.random() < 0.6
    return {
        "teeth": int(rng.integers(1, MAX_TEETH + 1)),
        "module": float(math.exp(rng.uniform(math.log(0.05), math.log(20.0)))),
        "pressure_angle_deg": float(rng.uniform(14.5, 30.0)),
        "helix_angle_deg": float(rng.uniform(5.0, 40.0)) if helical else 0.0,
        "hand": str(rng.choice(["right", "left"])),
        "addendum_coefficient": float(rng.uniform(0.8, 1.4)),
        "dedendum_coefficient": float(rng.uniform(0.9, 1.7)),
        "tip_rounding": str(rng.choice(["sharp", "generating"])),
        "tip_fraction": None if rng.random() < 0.5 else float(rng.uniform(0.0, 1.0)),
        "root_fraction": None if rng.random() < 0.4 else float(rng.uniform(0.0, 1.0)),
        "thinning_modules": float(rng.uniform(0.0, 0.1)) if rng.random() < 0.3 else 0.0,
        "face_modules": float(rng.uniform(1.0, 8.0)),
        "back_modules": float(rng.uniform(0.3, 4.0)),
    }


def make_spec(p: dict):
    """The RackSpec of a parameter set (raises DesignError for values it refuses)."""
    from geargen.design.rack import RackSpec
    m = p["module"]
    base = dict(teeth=p["teeth"], module=m, pressure_angle=math.radians(p["pressure_angle_deg"]),
                face_width=p["face_modules"] * m, helix_angle=math.radians(p["helix_angle_deg"]), hand=p["hand"],
                addendum_coefficient=p["addendum_coefficient"], dedendum_coefficient=p["dedendum_coefficient"],
                pitch_line_height=(p["dedendum_coefficient"] + p["back_modules"]) * m,
                tip_rounding=p["tip_rounding"], thinning=p["thinning_modules"] * m)
    plain = RackSpec(**base, root_fillet_coefficient=0.0)
    if p["tip_rounding"] == "generating" and p["tip_fraction"] is not None:
        base["tip_radius_coefficient"] = p["tip_fraction"] * plain.max_tip_radius_coefficient(0.0)
    tip = base.get("tip_radius_coefficient", RackSpec(**base, root_fillet_coefficient=0.0).tip_radius_coefficient)
    if p["root_fraction"] is not None:
        base["root_fillet_coefficient"] = p["root_fraction"] * plain.max_root_fillet_coefficient(tip)
    return RackSpec(**base)


def check_one(p: dict) -> tuple[str, str]:
    """Build and check one rack; returns (tag, detail). Runs in a worker process."""
    from geargen.errors import DesignError, GeometryError
    try:
        spec = make_spec(p)
        from geargen.cad.gear_solid import check_solid, solid_volume
        from geargen.cad.rack_solid import build_rack, flank_straightness
        from geargen.core.rack import rack_volume
        rack = build_rack(spec)
    except DesignError as exc:
        return "design_error", exc.field.split(".")[-1]
    except GeometryError as exc:
        return f"geometry_error:{exc.kind}", str(exc)[:120]
    except Exception as exc:  # noqa: BLE001 - every other exception is a failure to tag
        return f"crash:{type(exc).__name__}", traceback.format_exc(limit=3)[-300:]
    try:
        problem = check_solid(rack.shape)
        if problem:
            return ("not_one_solid" if "solids" in problem else "invalid"), problem
        expected = rack_volume(spec)
        vol = solid_volume(rack.shape, eps=1e-9)
        # 1e-6 as the gear sweep: a helical rack's ends are one boolean cut, whose edges carry the
        # kernel's tolerance (up to ~6e-7 mm grown on the tangent joints; a few 1e-8 relative on a
        # 0.1 mm module); spur racks and the larger helical ones agree to ~1e-9
        if abs(vol / expected - 1) > 1e-6:
            return "wrong_volume", f"{vol!r} vs {expected!r} ({vol / expected - 1:.2e})"
        worst, count = flank_straightness(rack, 0.5 * spec.face_width, samples_per_face=12)
        if count == 0 or not worst <= 1e-4:
            return "flank", f"{worst!r} mm over {count} points"
    except Exception as exc:  # noqa: BLE001
        return f"crash:{type(exc).__name__}", traceback.format_exc(limit=3)[-300:]
    return "ok", ""


@pytest.mark.slow
def test_random_racks_build_or_are_refused_clearly():
    rng = np.random.default_rng(SEED)
    params = [random_parameters(rng) for _ in range(COUNT)]
    results = run_sweep(params, f"{__file__}:check_one")
    tags = assert_sweep("racks", params, results, SEED)
    assert tags["ok"] >= 0.7 * COUNT  # the sweep mostly builds racks, not refusals
    assert tags["ok"] + tags["design_error"] >= 100
