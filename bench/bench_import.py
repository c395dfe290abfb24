"""Import time of `geargen` and its pure layers (no CAD kernel): target < 0.3 s.

Run by hand: .venv/bin/python bench/bench_import.py. Each row is the best of 7 fresh interpreters.
"""

import subprocess
import sys
import time

ROWS = {
    "python alone": "pass",
    "numpy": "import numpy",
    "geargen": "import geargen",
    "geargen pure layers": ("import geargen, geargen.design.assembly, geargen.core.geometry, geargen.core.synthesis, "
                            "geargen.core.tolerance, geargen.core.stiffness, geargen.core.flexures, "
                            "geargen.core.drive, geargen.profile"),
}


def best_of(code: str, runs: int = 7) -> float:
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True)
        times.append(time.perf_counter() - t)
    return min(times)


if __name__ == "__main__":
    print("| what | seconds (best of 7, interpreter start included) | target |")
    print("|---|---:|---|")
    for name, code in ROWS.items():
        target = "< 0.3" if name.startswith("geargen") else ""
        print(f"| {name} | {best_of(code):.3f} | {target} |")
