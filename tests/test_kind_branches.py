"""No drive-kind branches outside ``geargen/drives/`` (issue 26): which drive a design is, and what
that drive does differently, is asked of the drive kind (its keys module, ``geargen.drives.keys``,
or its :class:`geargen.drives.kind.DriveKind`), never by comparing the kind's name.

Pure source reading (ast): every ``geargen/**/*.py`` outside ``geargen/drives/`` is walked, and a
string constant equal to a drive kind's name (:data:`geargen.drives.keys.KEYS`) fails the test
where it is compared (``==``, ``!=``, ``in``, ``not in``, either side, also inside a tuple, list or
set compared against) or is a dict's key. A name the project uses as another vocabulary is
allowed at the sites listed in :data:`ALLOWED`, each with its reason."""

from __future__ import annotations

import ast
from pathlib import Path

from geargen.drives.keys import KEYS

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "geargen"
KINDS = set(KEYS)

#: (file under geargen/, name) -> why the name is not a drive-kind branch there
ALLOWED = {
    ("design/stiffness.py", "dual_pinion"): "[stiffness] train: the stiffness model's vocabulary for the two "
                                            "meshes of each path (the train a kind requires comes from its keys, "
                                            "STIFFNESS_TRAIN)",
    ("design/stiffness.py", "split_pinion"): "[stiffness] train: one mesh per path, the split pinion's train",
    ("core/stiffness.py", "dual_pinion"): "[stiffness] train: the two-mesh paths are built from the gears",
    ("core/stiffness.py", "split_pinion"): "[stiffness] train: the one-mesh paths are built from the gears",
    ("design/assembly.py", "beam_pinion"): "the [beam_pinion] section's name (the long pinion's beam spring), "
                                           "a section of the file, not a drive kind",
    ("design/validate.py", "beam_pinion"): "the [beam_pinion] section's name: its reader",
    ("design/reference.py", "beam_pinion"): "the [beam_pinion] section's name: the reference's context for "
                                            "the [parts] example",
}


def _strings(node: ast.AST) -> list[ast.Constant]:
    """The string constants ``node`` is or holds as a tuple, list or set of them."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return [node]
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return [c for e in node.elts for c in _strings(e)]
    return []


def kind_branches(path: Path, kinds: set[str] = KINDS) -> list[tuple[int, str, str]]:
    """(line, name, how) of every kind name (of ``kinds``: the drive kinds by default) compared or
    used as a dict key in ``path``."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Compare):
            for side in [node.left, *node.comparators]:
                found += [(c.lineno, c.value, "compared") for c in _strings(side) if c.value in kinds]
        elif isinstance(node, ast.Dict):
            found += [(k.lineno, k.value, "dict key") for k in node.keys
                      if isinstance(k, ast.Constant) and k.value in kinds]
    return found


def _outside_drives() -> list[Path]:
    return sorted(p for p in PACKAGE.rglob("*.py") if "drives" not in p.relative_to(PACKAGE).parts[:1])


def test_no_drive_kind_branches_outside_the_drives():
    problems = []
    for path in _outside_drives():
        rel = path.relative_to(PACKAGE).as_posix()
        problems += [f"geargen/{rel}:{line}: {name!r} {how}" for line, name, how in kind_branches(path)
                     if (rel, name) not in ALLOWED]
    assert not problems, "drive-kind branches outside geargen/drives/ (ask the kind instead):\n" + "\n".join(problems)


def test_every_allowed_site_is_still_one():
    """An allowance whose site is gone is removed (the list stays the sites that exist)."""
    sites = {(p.relative_to(PACKAGE).as_posix(), name) for p in _outside_drives() for _, name, _ in kind_branches(p)}
    assert set(ALLOWED) <= sites, sorted(set(ALLOWED) - sites)


def test_the_walker_finds_each_form_of_branch(tmp_path):
    """The forms the test must catch, in a file written here, and a name it must leave alone."""
    sample = tmp_path / "sample.py"
    sample.write_text('if layout.kind == "split_pinion":\n    pass\n'            # 1: ==
                      'x = kind in ("axial_preload", "other")\n'                # 3: in a tuple
                      'y = {"rack_dual_pinion": 1}\n'                           # 4: dict key
                      'z = "beam_pinion" not in sections\n'                     # 5: not in
                      'w = design.section("beam_pinion")\n')                    # 6: a call's argument: not a branch
    assert [(line, name) for line, name, _ in kind_branches(sample)] == \
        [(1, "split_pinion"), (3, "axial_preload"), (4, "rack_dual_pinion"), (5, "beam_pinion")]
