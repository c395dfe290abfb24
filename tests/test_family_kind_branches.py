"""No new gear-family branches outside ``geargen/families/`` (issue 26): what a family does
differently is asked of its :class:`geargen.families.family.GearFamily` (through
:mod:`geargen.families.registry`), never by comparing its kind's name.

The walker is the drive-kind test's (:func:`test_kind_branches.kind_branches`) with the family kinds:
a string constant equal to a family's kind, compared (``==``, ``!=``, ``in``, ``not in``, either
side, also inside a tuple, list or set) or used as a dict key, in any ``geargen/**/*.py`` outside
``geargen/families/``. ``"external"`` is not searched: it is the default every spec without a
``kind`` has (``getattr(spec, "kind", "external")``), so it names the cylindrical gear, not a family
with files of its own.

The sites that remain are listed with how many each has and why: :data:`VOCABULARY` (the word is
another vocabulary's there: a JSON section, a colour, a units key) and :data:`NOT_YET_MOVED` (a
real branch still to be moved into its family). The counts are exact, so a new branch fails the
test and a removed one must be struck off the list: the list only shrinks.
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

from geargen.families.registry import FAMILIES
from test_kind_branches import kind_branches

PACKAGE = Path(__file__).resolve().parents[1] / "geargen"
FAMILY_KINDS = set(FAMILIES) - {"external"}

#: (file under geargen/, kind) -> (count, why the word is not a family branch there)
VOCABULARY = {
    ("checks/results.py", "bevel"): (1, "the verdict JSON's 'bevel' section (a drive's bevel pair rows)"),
    ("checks/results.py", "rack"): (1, "the verdict JSON's 'rack' section (a rack drive's mesh rows)"),
    ("model/components.py", "bevel"): (1, "a hardware component kind's colour (the bevel pair's parts)"),
    ("pipeline.py", "internal"): (1, "the units key 'internal' (mm, rad, N) of the build manifest"),
}
#: (file under geargen/, kind) -> (count, what the branch decides): still to move into the family; none
#: since the double-helical gear's halves and gap and the ring's tip, root, rim and cutter became their
#: families' subclasses of GearSpec (families/<kind>/spec.py), the rack's entered allowance its options'
#: ``with_allowance`` and the bevel's closed-form mass its family's ``toothed_mass``
NOT_YET_MOVED: dict[tuple[str, str], tuple[int, str]] = {}


def family_branch_sites() -> Counter:
    """(file under geargen/, kind) -> how many family-kind branches it holds, outside geargen/families/."""
    found: Counter = Counter()
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE)
        if rel.parts[0] == "families":
            continue
        for _, name, _ in kind_branches(path, FAMILY_KINDS):
            found[(rel.as_posix(), name)] += 1
    return found


def test_no_new_family_kind_branches_outside_the_families():
    listed = {site: count for site, (count, _) in {**VOCABULARY, **NOT_YET_MOVED}.items()}
    found = dict(family_branch_sites())
    new = {site: n for site, n in found.items() if n > listed.get(site, 0)}
    assert not new, ("family-kind branches outside geargen/families/ (ask the family, "
                     f"geargen.families.registry, instead): {sorted(new.items())}")
    gone = {site: (found.get(site, 0), n) for site, n in listed.items() if found.get(site, 0) < n}
    assert not gone, f"branches removed: strike them off the list (found, listed): {sorted(gone.items())}"


def test_the_count_of_branches_left():
    """85 sites outside the family files before the one registry (95 with them), 52 after it
    replaced the five string registries, 46 after the load-capacity scope asked the family
    (``RATING_SCOPE``), 27 after the rating read a ring's and a rack's ISO 6336 geometry from the family
    (``TOOTH_FORM``: 19 branches of ``core/load_capacity.py``), 18 after the hardware check, the
    mass, the mesh loads, the layout and the gear data read the same form (9 more), 4 after the
    cylindrical families' specs moved into their folders (the 14 branches of ``GearSpec``, the
    ring profile, the rack's allowance option, the bevel's mass and the planetary ring's rule): the 4
    of another vocabulary."""
    assert sum(family_branch_sites().values()) == 4
    assert sum(n for n, _ in VOCABULARY.values()) == 4


def test_the_walker_sees_a_family_branch(tmp_path):
    """The family kinds are searched: a comparison with "worm_wheel" and a dict key "rack" are found,
    "external" (the default kind) is not."""
    sample = tmp_path / "sample.py"
    sample.write_text('if spec.kind == "worm_wheel":\n    pass\n'
                      'x = {"rack": 1}\n'
                      'y = kind == "external"\n')
    assert [(line, name) for line, name, _ in kind_branches(sample, FAMILY_KINDS)] == [(1, "worm_wheel"), (3, "rack")]
