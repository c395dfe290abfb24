"""The one drive-kind registry (geargen/drives/keys.py): a drive kind's folder (one with a
``kind.py``) is registered by one import line of its keys module, and both what the design loader
reads (:data:`geargen.drives.keys.KEYS`) and what the resolver calls
(:data:`geargen.drives.registry.DRIVES`) are derived from that line: a folder without its line, a
line without its folder and two lines for one kind fail here."""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from collections import Counter
from importlib import import_module
from pathlib import Path

import pytest

import geargen.drives as package
from geargen.drives.keys import KEYS
from geargen.drives.registry import DRIVES, KIND_MODULE

DRIVES_DIR = Path(package.__file__).parent
KEYS_REGISTRY = DRIVES_DIR / "keys.py"
#: a kind's registration line, as docs/adding-a-family.md writes it
LINE = re.compile(r"^from geargen\.drives\.(\w+) import keys as (\w+)\s*$")


def drive_folders() -> set[str]:
    """The drive kinds' folders: those holding a ``kind.py`` (an upstream stage, the planetary, has none)."""
    return {p.parent.name for p in DRIVES_DIR.glob(f"*/{KIND_MODULE}.py")}


def registration_lines(text: str) -> list[tuple[str, str]]:
    """(folder, name it is imported as) of each registration line of the keys registry's text."""
    return [m.groups() for m in map(LINE.match, text.splitlines()) if m]


def registration_problems(folders: set[str], text: str) -> list[str]:
    """What is wrong between the drive folders and the registry's lines (empty: each folder has
    exactly one line, under its own name, and each line its folder)."""
    lines = registration_lines(text)
    registered = [folder for folder, _ in lines]
    problems = [f"{k}: a folder without its line" for k in sorted(folders - set(registered))]
    problems += [f"{k}: a line without its folder" for k in sorted(set(registered) - folders)]
    problems += [f"{k}: {n} lines" for k, n in sorted(Counter(registered).items()) if n > 1]
    problems += [f"{k}: imported as {alias}" for k, alias in lines if alias != k]
    return problems


def test_every_drive_folder_is_registered_by_its_one_line():
    text = KEYS_REGISTRY.read_text()
    assert registration_problems(drive_folders(), text) == []
    # KEYS and DRIVES hold exactly the registered kinds, in the order of the lines
    assert list(KEYS) == list(DRIVES) == [folder for folder, _ in registration_lines(text)]


@pytest.mark.parametrize("defect, expected", [
    ("folder without line", "worm_drive: a folder without its line"),
    ("line without folder", "worm_drive: a line without its folder"),
    ("two lines", "axial_preload: 2 lines"),
    ("wrong name", "axial_preload: imported as axial"),
])
def test_a_registration_defect_is_found(defect, expected):
    """The check is not blind: each defect, made in a copy of the real folders and lines, is named."""
    folders, text = drive_folders(), KEYS_REGISTRY.read_text()
    line = "from geargen.drives.axial_preload import keys as axial_preload"
    assert line in text.splitlines()
    if defect == "folder without line":
        folders = folders | {"worm_drive"}
    elif defect == "line without folder":
        text += "\nfrom geargen.drives.worm_drive import keys as worm_drive\n"
    elif defect == "two lines":
        text += "\n" + line + "\n"
    else:
        text = text.replace(line, line.removesuffix("_preload"))
    assert registration_problems(folders, text) == [expected]


@pytest.mark.parametrize("name", sorted(KEYS))
def test_each_drive_is_the_kind_module_of_its_keys_package(name):
    keys = KEYS[name]
    assert keys.__name__ == f"geargen.drives.{name}.keys" and keys.NAME == name
    drive = DRIVES[name]
    assert drive is import_module(f"geargen.drives.{name}.kind").DRIVE
    assert drive.name == name and drive.keys is keys
    if keys.LAYOUT_KIND == name:  # selected by a [layout] kind of its own: the key's help says what it is
        assert keys.LAYOUT_HELP and f"{name} ({keys.LAYOUT_HELP})" in next(
            f.help for f in import_module("geargen.design.layout").COMMON_FIELDS if f.name == "kind")


def test_the_drive_registry_names_no_kind():
    """DRIVES is derived: geargen/drives/registry.py imports no kind and holds no kind's name (the
    one line per kind is in geargen/drives/keys.py)."""
    tree = ast.parse((DRIVES_DIR / "registry.py").read_text())
    imported = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
    assert imported == {"__future__", "importlib", "geargen.drives.keys", "geargen.drives.kind"}
    names = {n.value for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)}
    assert not names & set(KEYS)


def test_reading_a_design_loads_no_drive_kind():
    """The loader reads the keys registry, not the kinds: importing it loads no kind's ``kind.py``,
    placement or hardware, nor the DriveKind registry."""
    code = ("import sys, geargen.design.assembly; "
            "print(sorted(m for m in sys.modules if m == 'geargen.drives.registry' "
            "or m.rsplit('.', 1)[-1] in ('kind', 'place', 'hardware', 'verdict')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "[]"
