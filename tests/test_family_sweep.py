"""The random stability sweep of every gear family (tests/sweep_support.py: the families, their
checks, which cases run). Per push a sample seeded from the commit; ``GEARGEN_FULL_SWEEP=1`` the
full set with its coverage floors (bench/bench_sweep_families.py runs it and prints a table).

Reproduce a family's failure with the seed its summary line prints:
``GEARGEN_SWEEP_SEED=<seed> pytest tests/test_family_sweep.py -k <family> -s``.
"""

from __future__ import annotations

import pytest
from sweep_support import CHECK, FAMILIES, FULL, run_sweep, summary, sweep_cases, tagged_failures


@pytest.fixture(scope="module")
def sweep(request):
    """Every selected family's cases, checked in one pool of workers: {family: (seed, params, results)}."""
    chosen = {item.callspec.params["family"] for item in request.session.items
              if item.module is request.module and hasattr(item, "callspec")}
    cases = {name: sweep_cases(FAMILIES[name]) for name in FAMILIES if name in chosen}
    params = [p for _, ps in cases.values() for p in ps]
    results = run_sweep(params, CHECK, [FAMILIES[p["family"]].timeout for p in params])
    out, at = {}, 0
    for name, (seed, ps) in cases.items():
        out[name] = (seed, ps, results[at:at + len(ps)])
        at += len(ps)
    return out


@pytest.mark.slow
@pytest.mark.parametrize("family", list(FAMILIES))
def test_random_cases_build_or_are_refused_clearly(family, sweep):
    """No tagged failure (module docstring of tests/sweep_support.py); in the full set the family's
    coverage floors too (it mostly builds, not refuses)."""
    from collections import Counter
    seed, params, results = sweep[family]
    fam = FAMILIES[family]
    print("\n" + summary(family, params, results, seed))
    failures = tagged_failures(params, results, fam.expected_kinds)
    for p, r in failures[:10]:
        print(r[0], r[1], p)
    assert not failures, f"{len(failures)} tagged failures: {Counter(r[0] for _, r in failures)} (seed {seed})"
    if FULL:
        missed = fam.coverage(Counter(r[0] for r in results), params, results, len(params))
        assert not missed, missed
