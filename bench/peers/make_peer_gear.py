"""Write issue 13's bench gear with a peer library (run by bench/bench_step.py in the peers' venv).

    PEERS_PYTHON bench/peers/make_peer_gear.py {bd_warehouse|py_gearworks} OUT.step

21 teeth, normal module 25.4/32 mm, 20 deg normal pressure angle, 20 deg helix (right hand:
the sections turn counter-clockwise going up +z), 12.7 mm face from z = 0, dedendum 1.25 m.
Prints the build and STEP-write times. Only this file imports the peers.
"""

import math
import sys
import time

TEETH, MODULE, PRESSURE_DEG, HELIX_DEG, FACE = 21, 25.4 / 32, 20.0, 20.0, 12.7


def bd_warehouse_gear():
    from bd_warehouse.gear import HelicalGear
    from build123d import Align
    return HelicalGear(module=MODULE, tooth_count=TEETH, pressure_angle=PRESSURE_DEG, helix_angle=HELIX_DEG,
                       thickness=FACE, module_system="normal", align=(Align.CENTER, Align.CENTER, Align.MIN))


def py_gearworks_gear():
    import py_gearworks as pgw
    gear = pgw.HelicalGear(number_of_teeth=TEETH, helix_angle=math.radians(HELIX_DEG), height=FACE,
                           module=MODULE, pressure_angle=math.radians(PRESSURE_DEG), dedendum_coefficient=1.25)
    return gear.build_part()


def main(peer: str, out: str) -> int:
    t0 = time.perf_counter()
    part = {"bd_warehouse": bd_warehouse_gear, "py_gearworks": py_gearworks_gear}[peer]()
    t_build = time.perf_counter() - t0
    from build123d import export_step
    t0 = time.perf_counter()
    export_step(part, out)
    t_step = time.perf_counter() - t0
    print(f"built in {t_build:.2f} s, STEP written in {t_step:.2f} s, volume {part.volume:.3f} mm3")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
