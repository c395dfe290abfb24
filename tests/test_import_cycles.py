"""No import cycles among geargen's modules (issue 26): every ``import``, at the top of a module or
inside a function, is an edge, and importing ``geargen.a.b`` also runs ``geargen.a`` (its package),
so an import dodged into a function or hidden behind a registry still counts. A cycle is a set of
modules each reachable from the others (a strongly connected component of more than one module).
Pure source reading (ast): nothing is imported."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1] / "geargen"


def _module_name(path: Path) -> str:
    rel = path.relative_to(ROOT.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def import_graph() -> dict[str, set[str]]:
    """Module -> the geargen modules it imports (each import's module, and a name imported from a
    package when that name is a submodule), packages included for their submodules."""
    modules = {_module_name(p): p for p in ROOT.rglob("*.py")}
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        tree = ast.parse(path.read_text(), str(path))
        typing_only = {id(n) for block in ast.walk(tree) if isinstance(block, ast.If)
                       and getattr(block.test, "id", getattr(block.test, "attr", "")) == "TYPE_CHECKING"
                       for n in ast.walk(block)}
        for node in ast.walk(tree):
            if id(node) in typing_only:  # never runs: an annotation's type
                continue
            targets: list[str] = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")
                    base = base[: len(base) - node.level + 1]
                    origin = ".".join(base + ([node.module] if node.module else []))
                else:
                    origin = node.module or ""
                targets = [origin] + [f"{origin}.{a.name}" for a in node.names if f"{origin}.{a.name}" in modules]
            for target in targets:
                if not target.startswith("geargen"):
                    continue
                # importing a.b.c runs a, a.b and a.b.c
                parts = target.split(".")
                for i in range(1, len(parts) + 1):
                    prefix = ".".join(parts[:i])
                    if prefix in modules and prefix != name:
                        graph[name].add(prefix)
    # the drive registry imports each registered kind's kind.py by its keys module's package
    # (geargen.drives.registry: import_module, which the reading above does not see)
    for keys in graph.get("geargen.drives.keys", ()):
        if keys.startswith("geargen.drives.") and keys.endswith(".keys") and keys != "geargen.drives.keys":
            kind = keys.removesuffix(".keys") + ".kind"
            assert kind in modules, f"{keys} is registered but {kind} does not exist"
            graph["geargen.drives.registry"].add(kind)
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    import sys
    sys.setrecursionlimit(10_000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_the_graph_sees_function_level_imports():
    """The reader is not blind: a known function-level import is an edge."""
    graph = import_graph()
    assert "geargen.cad.assembly" in graph["geargen.pipeline"]  # imported inside pipeline's functions
    assert "geargen.drives" in graph["geargen.drives.dual_pinion.keys"]  # the package runs first
    assert "geargen.drives.axial_preload.kind" in graph["geargen.drives.registry"]  # derived from its keys line


def test_no_import_cycles():
    found = cycles(import_graph())
    assert not found, "import cycles:\n" + "\n".join("  " + " <-> ".join(c) for c in found)


def test_a_cycle_is_found_when_there_is_one():
    """The detector itself can fail: two modules importing each other are one cycle."""
    assert cycles({"a": {"b"}, "b": {"a"}, "c": {"a"}}) == [["a", "b"]]
