"""geargen.checks.blas: the checks run on one OpenBLAS thread, and the former count comes back after."""

import sys

import numpy as np
import pytest

from geargen.checks.blas import _loaded_openblas, one_blas_thread


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the loaded libraries are read from /proc/self/maps")
def test_one_thread_inside_and_the_former_counts_after():
    import scipy.linalg  # noqa: F401  (both wheels' OpenBLAS loaded)
    libs = _loaded_openblas()
    # numpy's and scipy's wheels each bundle one; finding none would make the context a no-op
    assert len(libs) >= 1
    for _, put in libs:
        put(2)
    with one_blas_thread():
        assert [get() for get, _ in libs] == [1] * len(libs)
    assert [get() for get, _ in libs] == [2] * len(libs)


def test_same_numbers_on_one_thread():
    """A small L-BFGS-B solve (the tolerance loop's kind) gives the same bits on one thread as on the pool."""
    from scipy.optimize import minimize
    rng = np.random.default_rng(28)
    a = rng.normal(size=(20, 20))
    q = a @ a.T + np.eye(20)
    b = rng.normal(size=20)

    def fun(z):
        return float(0.5 * z @ q @ z - b @ z + np.sum(np.sin(z))), q @ z - b + np.cos(z)

    def solve():
        return minimize(fun, np.zeros(20), jac=True, method="L-BFGS-B", bounds=[(-1.0, 1.0)] * 20,
                        options={"maxiter": 60, "ftol": 1e-14, "gtol": 1e-14}).x

    pooled = solve()
    with one_blas_thread():
        single = solve()
    assert np.array_equal(pooled, single)
