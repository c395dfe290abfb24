"""The pure layers must not load the CAD kernel, and imports point down only (STYLE.md)."""

import ast
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1] / "geargen"

# each layer may import only itself and the layers listed after it
LAYERS = ["cli", "api", "commands", "sweep", "pipeline", "cad", "checks", "fit", "report", "model", "profile", "core",
          "design"]
ALLOWED = {
    "cli": set(LAYERS),
    # the Python API composes the commands' option validation and the pipeline's steps
    "api": set(LAYERS) - {"cli"},
    "commands": set(LAYERS) - {"cli", "api"},
    "sweep": {"pipeline", "cad", "checks", "fit", "report", "model", "profile", "core", "design"},
    "pipeline": {"cad", "checks", "fit", "report", "model", "profile", "core", "design"},
    "cad": {"cad", "model", "profile", "core", "design"},
    "checks": {"checks", "cad", "model", "profile", "core", "design"},
    "fit": {"fit", "model", "core", "design", "report"},
    "report": {"report", "model", "core", "design", "profile"},
    "model": {"model", "profile", "core", "design"},
    "profile": {"profile", "core", "design"},
    "core": {"core", "design"},
    "design": {"design"},
}
#: a gear family's file (geargen/families/<kind>/<role>.py) -> the layer it sits in
FAMILY_ROLES = {"spec": "design", "geometry": "core", "solid": "cad", "mesh_solid": "cad", "pair": "checks",
                "data": "model", "options": "commands", "drawing": "report"}
#: the families' registry files (families/family.py, families/registry.py, families/<kind>/family.py): any
#: layer reads a family through them, so at their top they import the design layer only (a family's spec); a role
#: above it is imported inside the function that needs it (reading a design table never loads the kernel)
REGISTRY = "families"
KERNEL = ("cadquery", "OCP", "trimesh")
PURE_MODULES = ["geargen", "geargen.errors", "geargen.units", "geargen.design", "geargen.core", "geargen.profile", "geargen.fit",
                "geargen.model",
                "geargen.api"]  # not pure, but the kernel loads only when a call builds a solid


def _layer_of(path: pathlib.Path) -> str:
    rel = path.relative_to(ROOT)
    if rel.parts[0] == "families":
        return FAMILY_ROLES.get(rel.stem, REGISTRY) if len(rel.parts) == 3 else REGISTRY
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def _layer_of_module(name: str) -> str | None:
    """The layer of an imported ``geargen.*`` module (None: the base, errors.py, units.py)."""
    parts = name.split(".")
    if len(parts) < 2:
        return None
    if parts[1] == "families":
        return FAMILY_ROLES.get(parts[3], REGISTRY) if len(parts) >= 4 else REGISTRY
    return parts[1] if parts[1] in ALLOWED else None


def _pure_submodules():
    for pkg in ("design", "core", "profile", "fit", "model"):
        for f in sorted((ROOT / pkg).glob("*.py")):
            if f.stem != "__init__":
                yield f"geargen.{pkg}.{f.stem}"
    for f in sorted((ROOT / "families").rglob("*.py")):
        if _layer_of(f) in ("design", "core", "model", REGISTRY):
            yield ".".join(("geargen",) + f.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__")


def _imports(tree):
    """(module, whether at the module's top) of every geargen import in ``tree``."""
    top = {id(n) for n in tree.body}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from ((a.name, id(node) in top) for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            yield node.module, id(node) in top


@pytest.mark.parametrize("module", PURE_MODULES + list(_pure_submodules()))
def test_pure_layers_do_not_load_cad_kernel(module):
    code = (f"import sys, importlib; importlib.import_module({module!r}); "
            "bad = [m for m in sys.modules if m.split('.')[0] in ('cadquery', 'OCP', 'trimesh')]; "
            "print(','.join(bad))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "", f"{module} loaded {out}"


def test_imports_point_down_only():
    problems = []
    for f in ROOT.rglob("*.py"):
        layer = _layer_of(f)
        if layer not in ALLOWED and layer != REGISTRY:
            continue  # errors.py, units.py, __init__.py: the base
        for n, at_top in _imports(ast.parse(f.read_text())):
            if not n.startswith("geargen."):
                continue
            target = _layer_of_module(n)
            if target is None or target == REGISTRY:
                continue  # every layer may ask the registry for a family
            if layer == REGISTRY:
                # its top imports a spec (design); a role above it only inside a function, and of its own family
                if at_top and target != "design":
                    problems.append(f"{f.relative_to(ROOT)} (registry) imports {n} at its top")
            elif target not in ALLOWED[layer]:
                problems.append(f"{f.relative_to(ROOT)} ({layer}) imports {n}")
    assert not problems, "\n".join(problems)


def test_only_a_family_solid_imports_the_kernel():
    """In geargen/families/ the kernel is the solid files' alone (the cad layer's role)."""
    problems = []
    for f in (ROOT / "families").rglob("*.py"):
        for n, _ in _imports(ast.parse(f.read_text())):
            if n.split(".")[0] in KERNEL and _layer_of(f) != "cad":
                problems.append(f"{f.relative_to(ROOT)} ({_layer_of(f)}) imports {n}")
    assert not problems, "\n".join(problems)


def test_the_rules_see_a_family_file_in_its_role():
    """The family roles are read from the path: a spec is design, a solid cad, a registry file the registry."""
    assert _layer_of(ROOT / "families" / "bevel" / "spec.py") == "design"
    assert _layer_of(ROOT / "families" / "worm" / "mesh_solid.py") == "cad"
    assert _layer_of(ROOT / "families" / "rack" / "family.py") == REGISTRY
    assert _layer_of_module("geargen.families.rack.solid") == "cad"
    assert _layer_of_module("geargen.families.registry") == REGISTRY
