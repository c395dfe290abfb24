"""Seeded stability sweep of double-helical (herringbone) gears, each built in a worker process.

Every gear either becomes one valid closed solid of the right volume (profile area x toothed length
+ groove disc x gap - bore, + hub) whose flanks lie on the involute in both halves, or is refused with
a DesignError / GeometryError. Everything else is a tagged failure: ``invalid`` (BRepCheck),
``not_one_solid``, ``wrong_volume``, ``flank``, ``timeout``, ``crash:<exception type>``.

More by hand: ``GEARGEN_SWEEP_COUNT=2000 GEARGEN_SWEEP_SEED=7 pytest tests/test_double_helical_sweep.py -s``
(``GEARGEN_SWEEP_TIMEOUT``, ``GEARGEN_SWEEP_WORKERS`` as for tests/test_gear_sweep.py;
``GEARGEN_SWEEP_MAX_TEETH``, default 16 here: the boolean of the gap's groove grows with the teeth).
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
MAX_TEETH = int(os.environ.get("GEARGEN_SWEEP_MAX_TEETH", "16"))

#: refusals that are the right answer for impossible parameters (as for the external sweep)
EXPECTED_GEOMETRY_KINDS = {"pointed_tooth", "negative_root", "pointed_rack", "no_involute", "severed_tooth",
                           "fillet_loop"}


def random_parameters(rng: np.random.Generator) -> dict:
    """One random double-helical gear: GearSpec fields plus relative gap/bore/keyway/hub sizes."""
    return {
        "teeth": int(round(math.exp(rng.uniform(math.log(5), math.log(MAX_TEETH))))),
        "module": float(math.exp(rng.uniform(math.log(0.05), math.log(20.0)))),
        "pressure_angle_deg": float(rng.uniform(14.5, 30.0)),
        "helix_angle_deg": float(rng.uniform(5.0, 45.0)),
        "hand": str(rng.choice(["right", "left"])),
        "profile_shift": float(rng.uniform(-0.6, 1.0)),
        "addendum_coefficient": float(rng.uniform(0.8, 1.2)),
        "dedendum_coefficient": float(rng.uniform(1.0, 1.6)),
        "rack_tip_fraction": None if rng.random() < 0.5 else float(rng.uniform(0.0, 1.0)),
        "face_modules": float(rng.uniform(2.0, 8.0)),
        # 40 % herringbones (no gap), else a gap of up to 60 % of the face width
        "gap_fraction": 0.0 if rng.random() < 0.4 else float(rng.uniform(0.02, 0.6)),
        "bore_fraction": float(rng.uniform(0.1, 0.9)) if rng.random() < 0.7 else 0.0,
        "keyway": bool(rng.random() < 0.2),
        "hub": bool(rng.random() < 0.15),
    }


def make_spec(p: dict):
    """The double-helical GearSpec of a parameter set (raises DesignError for values it refuses)."""
    from geargen.design.gear import GearSpec, Hub
    m = p["module"]
    face = p["face_modules"] * m
    base = dict(teeth=p["teeth"], module=m, pressure_angle=math.radians(p["pressure_angle_deg"]), face_width=face,
                helix_angle=math.radians(p["helix_angle_deg"]), hand=p["hand"], profile_shift=p["profile_shift"],
                addendum_coefficient=p["addendum_coefficient"], dedendum_coefficient=p["dedendum_coefficient"],
                kind="double_helical", centre_gap=p["gap_fraction"] * face)
    plain = GearSpec(**base)
    if p["rack_tip_fraction"] is not None:
        base["rack_tip_radius_coefficient"] = p["rack_tip_fraction"] * plain.max_rack_tip_radius_coefficient
    root_d = 2 * plain.root_radius_standard
    bore = p["bore_fraction"] * root_d * 0.9
    hub = Hub()
    if bore > 0:
        kw, kd = (0.25 * bore, 0.1 * bore) if p["keyway"] else (0.0, 0.0)
        hd, hl = ((bore + 2 * kd + root_d) / 2, 2 * m) if p["hub"] else (0.0, 0.0)
        hub = Hub(bore_diameter=bore, keyway_width=kw, keyway_depth=kd, hub_diameter=hd, hub_length=hl)
    return GearSpec(**base, hub=hub)


def _bore_area(hub) -> float:
    if hub.bore_diameter <= 0:
        return 0.0
    r = hub.bore_diameter / 2
    area = math.pi * r * r
    if hub.keyway_width > 0:
        w2 = hub.keyway_width / 2
        xk = math.sqrt(r * r - w2 * w2)
        area += hub.keyway_width * (r + hub.keyway_depth - xk) - (r * r * math.asin(w2 / r) - xk * w2)
    return area


def check_one(p: dict) -> tuple[str, str]:
    """Build and check one gear; returns (tag, detail). Runs in a worker process."""
    import warnings

    from geargen.errors import DesignError, GeometryError
    from geargen.profile.tooth import UndercutWarning
    try:
        warnings.simplefilter("ignore", UndercutWarning)
        spec = make_spec(p)
        from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
        from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Trsf

        from geargen.cad.double_helical import build_double_helical, groove_radius
        from geargen.cad.gear_solid import check_solid, solid_volume
        from geargen.cad.measure import flank_deviation
        g = build_double_helical(spec)
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
        hub, b, gap = spec.hub, spec.face_width, spec.centre_gap
        expected = g.profile.area() * (b - gap) + math.pi * groove_radius(spec, g.profile) ** 2 * gap - _bore_area(hub) * b
        expected += (math.pi * hub.hub_diameter ** 2 / 4 - _bore_area(hub)) * hub.hub_length
        vol = solid_volume(g.shape, eps=1e-7)
        if abs(vol / expected - 1) > 1e-6:
            vol = solid_volume(g.shape, eps=1e-9)
        if abs(vol / expected - 1) > 1e-6:
            return "wrong_volume", f"{vol!r} vs {expected!r} ({vol / expected - 1:.2e})"
        h = spec.half_face_width
        dev = flank_deviation(g.shape, g.profile, 0.5 * h, samples_per_face=32)
        if not dev.points or dev.max_abs > 1e-4:
            return "flank", f"first half: {dev}"
        # the second half: the solid mirrored back in z = b / 2 (exact) brings it to z in [0, h], where
        # its flanks must lie on the involute turning with the spec's hand; a second half of the wrong
        # hand or shape fails here. (measure.section misses some faces of the mirror images as built
        # on 5- and 6-tooth gears; on their mirror images back it does not.)
        mirror = gp_Trsf()
        mirror.SetMirror(gp_Ax2(gp_Pnt(0, 0, b / 2), gp_Dir(0, 0, 1)))
        back = BRepBuilderAPI_Transform(g.shape, mirror, True).Shape()
        dev = flank_deviation(back, g.profile, 0.5 * h, samples_per_face=32)
        if not dev.points or dev.max_abs > 1e-4:
            return "flank", f"second half: {dev}"
    except Exception as exc:  # noqa: BLE001
        return f"crash:{type(exc).__name__}", traceback.format_exc(limit=3)[-300:]
    return "ok", ""


@pytest.mark.slow
def test_random_double_helical_gears_build_or_are_refused_clearly():
    rng = np.random.default_rng(SEED)
    params = [random_parameters(rng) for _ in range(COUNT)]
    results = run_sweep(params, f"{__file__}:check_one")
    tags = assert_sweep("double-helical gears", params, results, SEED, EXPECTED_GEOMETRY_KINDS)
    assert tags["ok"] >= 0.5 * COUNT
    assert sum(1 for p, r in zip(params, results) if r[0] == "ok" and p["gap_fraction"] == 0) >= 0.2 * COUNT
