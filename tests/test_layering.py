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
PURE_MODULES = ["geargen", "geargen.errors", "geargen.units", "geargen.design", "geargen.core", "geargen.profile", "geargen.fit",
                "geargen.model",
                "geargen.api"]  # not pure, but the kernel loads only when a call builds a solid


def _layer_of(path: pathlib.Path) -> str:
    rel = path.relative_to(ROOT)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def _pure_submodules():
    for pkg in ("design", "core", "profile", "fit", "model"):
        for f in sorted((ROOT / pkg).glob("*.py")):
            if f.stem != "__init__":
                yield f"geargen.{pkg}.{f.stem}"


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
        if layer not in ALLOWED:
            continue  # errors.py, units.py, __init__.py: the base
        for node in ast.walk(ast.parse(f.read_text())):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                names = [node.module]
            for n in names:
                parts = n.split(".")
                if parts[0] == "geargen" and len(parts) > 1 and parts[1] in ALLOWED and parts[1] not in ALLOWED[layer]:
                    problems.append(f"{f.relative_to(ROOT)} ({layer}) imports {n}")
    assert not problems, "\n".join(problems)
