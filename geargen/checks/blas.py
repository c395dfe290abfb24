"""One BLAS thread while the checks run.

The checks' linear algebra is on matrices of a few dozen rows at most (L-BFGS-B's updates in the
tolerance loop's search, small solves); OpenBLAS's thread pool costs far more there than it saves:
on this 2-core machine 20 L-BFGS-B solves of 20 variables took 0.10 s of CPU with the pool and
0.006 s with one thread, and the robot joint's mesh checks spent 1.2 s waiting in L-BFGS-B of which
a few ms were arithmetic. In a build the checks run beside the main process (``pipeline.Alongside``),
where a spinning BLAS thread also takes a core from it. One thread computes the same numbers: each
of these small operations is done whole by one thread either way (bench/verdict_dump.py compares
the whole verdict of every shipped design).

numpy's and scipy's wheels each bundle an OpenBLAS of their own; both are found among the shared
libraries the process has loaded (``/proc/self/maps``) and set through OpenBLAS's own
``openblas_set_num_threads`` (under the prefix and suffix the wheel's build gave its symbols).
Where there is no such file or library (not Linux, another BLAS) nothing is changed.
"""

from __future__ import annotations

import contextlib
import ctypes
import os

# the symbol names a build of OpenBLAS gives its thread-count functions (scipy's wheels prefix
# theirs and add a suffix to the 64-bit integer build's)
_PREFIXES = ("", "scipy_")
_SUFFIXES = ("", "64_", "_64")


def _loaded_openblas() -> list[tuple]:
    """(get, set) thread-count functions of every OpenBLAS loaded in this process."""
    try:
        with open("/proc/self/maps") as f:
            paths = {line.split(None, 5)[5].strip() for line in f if len(line.split(None, 5)) == 6}
    except OSError:
        return []
    found = []
    for path in sorted(paths):
        if "openblas" not in os.path.basename(path).lower():
            continue
        try:
            lib = ctypes.CDLL(path)  # already loaded: the same handle, nothing initialised again
        except OSError:
            continue
        for prefix in _PREFIXES:
            for suffix in _SUFFIXES:
                get = getattr(lib, f"{prefix}openblas_get_num_threads{suffix}", None)
                put = getattr(lib, f"{prefix}openblas_set_num_threads{suffix}", None)
                if get is not None and put is not None:
                    get.restype, put.argtypes = ctypes.c_int, [ctypes.c_int]
                    found.append((get, put))
                    break
            else:
                continue
            break
    return found


@contextlib.contextmanager
def one_blas_thread():
    """Run the body with every loaded OpenBLAS on one thread; the former counts are restored after."""
    import scipy.linalg  # noqa: F401  (loads scipy's OpenBLAS, which L-BFGS-B uses, so that it is set too)
    libs = _loaded_openblas()
    before = [get() for get, _ in libs]
    for _, put in libs:
        put(1)
    try:
        yield
    finally:
        for (_, put), n in zip(libs, before):
            put(n)
