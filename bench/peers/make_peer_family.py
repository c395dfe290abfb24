"""Build one case of bench/bench_families.py with a peer library (run in the peers' venv).

    PEERS_PYTHON bench/peers/make_peer_family.py CASE PEER OUT.step

Prints one JSON line: build and STEP-write seconds (this process; the library import is timed
apart as ``import_s``) and the peer's own note on what it built. The cases' parameters are those
of bench/bench_families.py's CASES (kept in step by hand: this file runs in another venv and
must not import geargen). Only this file and make_peer_gear.py import the peers.
"""

import json
import math
import sys
import time

DEG = math.pi / 180
DP32 = 25.4 / 32

# ---------------------------------------------------------------- bd_warehouse 0.4.0 (build123d)


def _bd_align():
    from build123d import Align
    return (Align.CENTER, Align.CENTER, Align.MIN)


def bd_spur(teeth, module, face, **_):
    from bd_warehouse.gear import SpurGear
    return SpurGear(module=module, tooth_count=teeth, pressure_angle=20.0, thickness=face, addendum=module,
                    dedendum=1.25 * module, align=_bd_align()), "SpurGear"


def bd_helical(teeth, module, face, helix_deg, **_):
    from bd_warehouse.gear import HelicalGear
    return HelicalGear(module=module, tooth_count=teeth, pressure_angle=20.0, helix_angle=helix_deg, thickness=face,
                       module_system="normal", addendum=module, dedendum=1.25 * module,
                       align=_bd_align()), "HelicalGear"


def bd_rack(teeth, module, face, helix_deg=0.0, **_):
    from bd_warehouse.gear import RackGear
    return RackGear(module=module, tooth_count=teeth, pressure_angle=20.0, thickness=face, helix_angle=helix_deg,
                    module_system="normal", addendum=module, dedendum=1.25 * module,
                    base_height=2 * module), "RackGear, 2 m below the root"


def bd_worm(module, starts, q, length, **_):
    from bd_warehouse.gear import Worm
    return Worm(module, starts, q, length, pressure_angle=20.0, flank_form="ZA", addendum=module,
                dedendum=1.25 * module), "Worm ZA (ruled helicoid B-rep)"


def bd_worm_wheel(module, starts, q, teeth, face, **_):
    from bd_warehouse.gear import WormWheel
    return WormWheel(module, teeth, face, starts=starts, diametral_quotient=q, pressure_angle=20.0, addendum=module,
                     dedendum=1.25 * module, align=_bd_align()), "WormWheel: plain helical, NOT throated/enveloped"


# ---------------------------------------------------------------- py_gearworks 0.0.24


def _pgw():
    import py_gearworks as pgw
    return pgw


def pgw_spur(teeth, module, face, **_):
    return _pgw().SpurGear(number_of_teeth=teeth, module=module, height=face, dedendum_coefficient=1.25).build_part(), \
        "SpurGear"


def pgw_helical(teeth, module, face, helix_deg, herringbone=False, **_):
    gear = _pgw().HelicalGear(number_of_teeth=teeth, module=module, height=face, helix_angle=helix_deg * DEG,
                              herringbone=herringbone, dedendum_coefficient=1.25)
    return gear.build_part(), "HelicalGear herringbone=True (no centre gap option)" if herringbone else "HelicalGear"


def pgw_ring(teeth, module, face, helix_deg=0.0, **_):
    pgw = _pgw()
    # a ring's "addendum" is py_gearworks' depth outward of the pitch circle: 1.25 m space, 1 m tooth
    # (checked: a 60T m1 ring's innermost vertex is at r - 1.0 m = 29 mm); the rims are py_gearworks'
    # (outer radius r + 2.5 m spur, r + 2 m_t helical, read off the STEP bounding boxes)
    if helix_deg:
        gear = pgw.HelicalRingGear(number_of_teeth=teeth, module=module, height=face, helix_angle=helix_deg * DEG,
                                   addendum_coefficient=1.25, dedendum_coefficient=1.0)
        return gear.build_part(), "HelicalRingGear, rim r + 2 m_t (no rim option)"
    gear = pgw.SpurRingGear(number_of_teeth=teeth, module=module, height=face, addendum_coefficient=1.25,
                            dedendum_coefficient=1.0)
    return gear.build_part(), "SpurRingGear, rim r + 2.5 m"


def pgw_rack(teeth, module, face, helix_deg=0.0, **_):
    pgw = _pgw()
    if helix_deg:
        rack = pgw.HelicalRack(number_of_teeth=teeth, module=module, height=face, helix_angle=helix_deg * DEG,
                               dedendum_coefficient=1.25)
        return rack.build_part(), "HelicalRack, 1 m below the root (its default)"
    return pgw.InvoluteRack(number_of_teeth=teeth, module=module, height=face,
                            dedendum_coefficient=1.25).build_part(), "InvoluteRack, 1 m below the root (its default)"


def pgw_bevel(teeth, mate_teeth, module, face, shaft_deg=90.0, **_):
    pgw = _pgw()
    cone = pgw.cone_angle_from_teeth(teeth, mate_teeth, shaft_deg * DEG)[0]  # full cone angle 2 delta
    # height is axial: the face width b along the pitch cone's generatrix projects to b cos(delta)
    gear = pgw.BevelGear(number_of_teeth=teeth, cone_angle=cone, module=module, height=face * math.cos(cone / 2),
                         dedendum_coefficient=1.25)
    return gear.build_part(), "BevelGear (spherical involute)"


# ---------------------------------------------------------------- wormgear 0.0.8 (build123d)


def _wormgear_design(module, starts, q, teeth):
    from wormgear.calculator import design_from_module
    return design_from_module(module=module, ratio=teeth // starts, num_starts=starts, worm_pitch_diameter=q * module,
                              pressure_angle=20.0, clearance_factor=0.25, profile="ZA")


def wg_worm(module, starts, q, length, wheel_teeth, **_):
    from wormgear.core import WormGeometry
    design = _wormgear_design(module, starts, q, wheel_teeth)
    return WormGeometry(design.worm, design.assembly, length=length, profile="ZA").build(), \
        "WormGeometry ZA (lofted thread + union)"


def wg_worm_wheel(module, starts, q, teeth, face, **_):
    from wormgear.core import VirtualHobbingWheelGeometry
    design = _wormgear_design(module, starts, q, teeth)
    wheel = VirtualHobbingWheelGeometry(design.wheel, design.worm, design.assembly, face_width=face, hobbing_steps=36,
                                        profile="ZA")
    return wheel.build(), "VirtualHobbingWheelGeometry, 36 boolean steps ('preview')"


# case -> peer -> (builder, parameters); parameters as in bench_families.CASES
_SPUR = dict(teeth=30, module=2.0, face=20.0)
_WORM = dict(module=3.0, starts=2, q=11.0)
PEERS = {
    "external spur": {"bd_warehouse": (bd_spur, _SPUR), "py_gearworks": (pgw_spur, _SPUR)},
    "external helical": {"bd_warehouse": (bd_helical, dict(_SPUR, helix_deg=15.0)),
                         "py_gearworks": (pgw_helical, dict(_SPUR, helix_deg=15.0))},
    "internal spur": {"py_gearworks": (pgw_ring, dict(teeth=60, module=1.0, face=10.0))},
    "internal helical": {"py_gearworks": (pgw_ring, dict(teeth=60, module=1.0, face=10.0, helix_deg=15.0))},
    "rack spur": {"bd_warehouse": (bd_rack, dict(teeth=30, module=2.0, face=20.0)),
                  "py_gearworks": (pgw_rack, dict(teeth=30, module=2.0, face=20.0))},
    "rack helical": {"bd_warehouse": (bd_rack, dict(teeth=30, module=2.0, face=20.0, helix_deg=15.0)),
                     "py_gearworks": (pgw_rack, dict(teeth=30, module=2.0, face=20.0, helix_deg=15.0))},
    "herringbone": {"py_gearworks": (pgw_helical, dict(teeth=30, module=2.0, face=40.0, helix_deg=25.0,
                                                       herringbone=True))},
    "bevel pinion": {"py_gearworks": (pgw_bevel, dict(teeth=15, mate_teeth=30, module=DP32, face=4.0))},
    "bevel gear": {"py_gearworks": (pgw_bevel, dict(teeth=30, mate_teeth=15, module=DP32, face=4.0))},
    "worm": {"bd_warehouse": (bd_worm, dict(_WORM, length=70.0)),
             "wormgear": (wg_worm, dict(_WORM, length=70.0, wheel_teeth=40))},
    "worm wheel": {"bd_warehouse": (bd_worm_wheel, dict(_WORM, teeth=40, face=24.0)),
                   "wormgear": (wg_worm_wheel, dict(_WORM, teeth=40, face=24.0))},
}


def main(case: str, peer: str, out: str) -> int:
    builder, params = PEERS[case][peer]
    t0 = time.perf_counter()
    import build123d  # noqa: F401  the kernel and build123d: common to all peers, not counted
    {"bd_warehouse": lambda: __import__("bd_warehouse.gear"), "py_gearworks": _pgw,
     "wormgear": lambda: __import__("wormgear.core")}[peer]()
    t_import = time.perf_counter() - t0
    t0 = time.perf_counter()
    part, note = builder(**params)
    t_build = time.perf_counter() - t0
    from build123d import export_step
    t0 = time.perf_counter()
    export_step(part, out)
    t_step = time.perf_counter() - t0
    print(json.dumps(dict(import_s=t_import, build_s=t_build, step_s=t_step, note=note)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2], sys.argv[3]))
