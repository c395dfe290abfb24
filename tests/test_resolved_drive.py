"""The resolved drive carries its design's settings read once (issue 26): nothing downstream of the
resolution reads the design file again through the drive.

The scan: every ``<something layout>.design`` (or ``getattr(layout, "design")``) in geargen outside
the design layer and the resolution modules (the Layout itself, the resolver, each drive kind's
placement) is a module downstream reading the design through the resolved drive. The readers not
yet moved onto the drive's own values (``Layout.identity``, ``Layout.resolved``) are listed with
why; the list may only shrink: a file with more reads than listed fails, and so does one with
fewer (take it off the list).

Then the values the drive carries are checked against the design they were read from, on a
shipped design of each unit."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "geargen"

#: where the design is the input: the design layer, the Layout that is made from it, the resolver
#: and each drive kind's placement (they read the design to resolve it)
RESOLUTION = ("geargen/design/", "geargen/model/layout.py", "geargen/drives/resolver.py")
RESOLUTION_NAMES = ("place.py",)  # geargen/drives/<kind>/place.py

#: file -> (reads of the design through a Layout, why it still reads it): 75 reads in 28 files before
#: the settings were resolved once; the last three (the stiffness summary and the carriage's travel
#: limits, which took the Design) read the resolved drive's StiffnessInputs and sections now. A read
#: that must stay is listed here with its reason; the test fails on any other.
REMAINING: dict[str, tuple[int, str]] = {}


def _is_resolution(rel: str) -> bool:
    return rel.startswith(RESOLUTION) or (rel.startswith("geargen/drives/") and rel.endswith(RESOLUTION_NAMES))


def _names_a_layout(node: ast.AST) -> bool:
    """Whether an expression names a resolved drive: ``layout``, ``lay``, ``self.layout``,
    ``run.placed_layout``, ..."""
    if isinstance(node, ast.Name):
        return "layout" in node.id.lower() or node.id == "lay"
    if isinstance(node, ast.Attribute):
        return "layout" in node.attr.lower()
    return False


def design_reads(tree: ast.AST) -> list[int]:
    """Line numbers where ``tree`` reads ``.design`` off a Layout."""
    lines = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and node.attr == "design" and _names_a_layout(node.value):
            lines.append(node.lineno)
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "getattr"
              and len(node.args) >= 2 and _names_a_layout(node.args[0])
              and isinstance(node.args[1], ast.Constant) and node.args[1].value == "design"):
            lines.append(node.lineno)
    return lines


def readers() -> dict[str, list[int]]:
    out = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        if _is_resolution(rel):
            continue
        lines = design_reads(ast.parse(path.read_text(), rel))
        if lines:
            out[rel] = lines
    return out


def test_the_scan_finds_a_read_of_the_design_through_a_layout():
    # the scan's own check: each spelling it must catch, and the names it must leave alone (a build
    # result's design, a module named design)
    source = ("layout.design.name\nx = lay.design\nself.layout.design\nrun.placed_layout.design\n"
              "getattr(layout, 'design')\nresult.design.name\nimport geargen.design.gear\n")
    assert sorted(design_reads(ast.parse(source))) == [1, 2, 3, 4, 5]


def test_nothing_downstream_reads_the_design_through_the_layout():
    found = readers()
    new = {f: lines for f, lines in found.items() if len(lines) > REMAINING.get(f, (0, ""))[0]}
    assert not new, ("reads of the design through the resolved drive (read Layout.identity or Layout.resolved, "
                     f"or add the setting there): {new}")
    moved = {f: (n, len(found.get(f, ()))) for f, (n, _) in REMAINING.items() if len(found.get(f, ())) < n}
    assert not moved, f"fewer reads than listed (listed, found): take them off REMAINING: {moved}"


@pytest.mark.parametrize("name", ["robot_joint", "split_pinion"])
def test_the_drive_carries_what_the_design_says(name):
    # the values carried are the design's own, read by the section's own reader (an inch and a mm design)
    from geargen.core.stiffness import drive_train
    from geargen.design.assembly import load_design
    from geargen.design.checks import checks_settings
    from geargen.design.export import export_settings
    from geargen.design.parts import parts_settings
    from geargen.design.stages import stages
    from geargen.design.stiffness import stiffness_design
    from geargen.design.train import train_settings
    from geargen.drives.resolver import resolve

    design = load_design(ROOT / "assemblies" / f"{name}.toml")
    layout = resolve(design)
    ident = layout.identity
    assert (ident.name, ident.length_unit, ident.path, ident.defaulted) == \
           (design.name, design.length_unit, design.path, design.defaulted)
    assert ident.mm_per_unit == {"mm": 1.0, "in": 25.4}[design.length_unit]
    assert ident.text_units == design.text_units
    assert layout.resolved.checks == checks_settings(design)
    assert layout.resolved.export == export_settings(design)
    assert layout.resolved.parts == parts_settings(design)
    assert layout.resolved.train == train_settings(design)
    assert layout.resolved.stiffness == stiffness_design(design)
    assert layout.resolved.stages == stages(design)
    assert layout.resolved.drive_train == drive_train(design, stiffness_design(design).stiffness)
    # read once: the second ask is the same object, not a second reading
    assert layout.resolved.checks is layout.resolved.checks
    assert layout.resolved.parts is layout.resolved.parts
