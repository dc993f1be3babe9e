"""The import graph of ``emboteam.*`` has no cycles (docs/architecture.md, "No import cycles").

Every ``import`` statement counts, function-level ones included: an import deferred into a
function still makes the two modules depend on each other, it only hides the cycle from
Python's loader. ``from package import name`` is an edge to ``package.name`` when that is a
module, else to the package. Imports under ``if TYPE_CHECKING:`` count too (a type is a
dependency).
"""

from __future__ import annotations

import ast
from pathlib import Path

import emboteam

SRC = Path(emboteam.__file__).resolve().parent


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _modules() -> dict[str, Path]:
    return {_module_name(p): p for p in SRC.rglob("*.py")}


def _imported(node: ast.AST, module: str, is_package: bool) -> list[str]:
    if isinstance(node, ast.Import):
        return [a.name for a in node.names]
    if isinstance(node, ast.ImportFrom):
        base = node.module or ""
        if node.level:
            package = module.split(".") if is_package else module.split(".")[:-1]
            package = package[: len(package) - (node.level - 1)]
            base = ".".join([*package, base] if base else package)
        return [base, *(f"{base}.{a.name}" for a in node.names)]
    return []


def import_graph() -> dict[str, set[str]]:
    """Module -> the emboteam modules it imports (anywhere in its body)."""
    modules = _modules()
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for module, path in modules.items():
        tree = ast.parse(path.read_text(), filename=str(path))
        for node in ast.walk(tree):
            names = _imported(node, module, path.name == "__init__.py")
            if isinstance(node, ast.ImportFrom):
                base, members = names[0], names[1:]
                targets = [m for m in members if m in modules] or [base]
                if len(targets) < len(members):  # some names are attributes of the package
                    targets.append(base)
            else:
                targets = names
            graph[module].update(t for t in targets if t in modules and t != module)
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle as a path ``[a, b, ..., a]``, or None (iterative DFS, three colours)."""
    state: dict[str, int] = {}
    for root in sorted(graph):
        if state.get(root):
            continue
        stack: list[tuple[str, list[str]]] = [(root, sorted(graph[root]))]
        path = [root]
        state[root] = 1
        while stack:
            node, todo = stack[-1]
            if not todo:
                state[node] = 2
                stack.pop()
                path.pop()
                continue
            nxt = todo.pop()
            if state.get(nxt) == 1:
                return [*path[path.index(nxt):], nxt]
            if not state.get(nxt):
                state[nxt] = 1
                path.append(nxt)
                stack.append((nxt, sorted(graph[nxt])))
    return None


def test_the_walker_sees_function_level_imports() -> None:
    graph = import_graph()
    # bench.runner imports the pipeline inside pipeline_episode, the CLI its commands' modules
    assert "emboteam.pipeline" in graph["emboteam.bench.runner"]
    assert "emboteam.bench.runner" in graph["emboteam.cli"]
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_no_import_cycles() -> None:
    cycle = find_cycle(import_graph())
    assert cycle is None, "import cycle: " + " -> ".join(cycle or [])


def test_no_import_cycles_between_packages() -> None:
    """Coarser and stricter: with every subpackage folded into its top-level package
    (``emboteam.bench.runner`` -> ``emboteam.bench``), the graph is still acyclic, so
    e.g. ``bench`` may import ``pipeline`` but nothing ``pipeline`` imports reaches ``bench``."""
    def top(module: str) -> str:
        return ".".join(module.split(".")[:2])

    folded: dict[str, set[str]] = {}
    for module, targets in import_graph().items():
        folded.setdefault(top(module), set()).update(top(t) for t in targets if top(t) != top(module))
    for targets in list(folded.values()):
        for t in targets:
            folded.setdefault(t, set())
    cycle = find_cycle(folded)
    assert cycle is None, "package import cycle: " + " -> ".join(cycle or [])
