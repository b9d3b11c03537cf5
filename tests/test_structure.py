"""The import structure of wecss: no import cycles between modules or between packages (imports inside functions
count too), and no private module imported from outside the package that owns it (DESIGN.md, issue 12).

Read from the source with ``ast``; nothing is imported. A new cycle or private import fails here with the path.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SOURCES = ("wecss", "controllers", "studies")


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _modules() -> dict[str, Path]:
    return {_module_name(p): p for top in SOURCES for p in sorted((ROOT / top).rglob("*.py"))}


def _imports(name: str, path: Path, known: dict[str, Path]) -> set[str]:
    """Every wecss/controllers module that ``name`` imports, at any depth of the file."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                stem = ".".join([*base, node.module] if node.module else base)
            else:
                stem = node.module or ""
            # "from package import submodule" imports the submodule
            targets = [f"{stem}.{a.name}" if f"{stem}.{a.name}" in known else stem for a in node.names]
        else:
            continue
        for target in targets:
            while target and target not in known:  # "import a.b.c" of a name inside a module
                target = target.rpartition(".")[0]
            if target and target != name:
                out.add(target)
    return out


def _graph() -> dict[str, set[str]]:
    known = _modules()
    return {name: _imports(name, path, known) for name, path in known.items()}


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one member (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def _package(module: str, modules: dict[str, set[str]]) -> str:
    """The wecss package a module belongs to: ``wecss.sim`` for ``wecss.sim._result``, ``wecss.hydro`` for
    ``wecss.hydro.readers.wamit`` (subpackages count as their package), the module itself at the top level."""
    parts = module.split(".")
    if parts[0] != "wecss" or len(parts) == 1:
        return parts[0]
    return ".".join(parts[:2])


def test_no_module_imports_itself_through_a_cycle():
    assert _cycles(_graph()) == []


def test_no_cycle_between_packages():
    graph = _graph()
    packages: dict[str, set[str]] = {}
    for module, targets in graph.items():
        if module.startswith("wecss"):
            source = _package(module, graph)
            edges = packages.setdefault(source, set())
            edges.update(_package(t, graph) for t in targets if t.startswith("wecss") and _package(t, graph) != source)
    # the root package only re-exports the version; it sits below everything
    packages.pop("wecss", None)
    assert _cycles(packages) == []


def test_no_private_module_is_imported_from_another_package():
    wrong = []
    for module, targets in _graph().items():
        for target in targets:
            parts = target.split(".")
            private = [k for k, part in enumerate(parts) if part.startswith("_") and not part.startswith("__")]
            if not private:
                continue
            owner = ".".join(parts[: private[0]])  # the package whose private module it is
            if not (module == owner or module.startswith(owner + ".")):
                wrong.append(f"{module} -> {target}")
    assert wrong == []


def test_the_checks_find_a_cycle_and_a_private_import():
    """The checks themselves: a made-up graph with a cycle, and a private import across packages."""
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []
    modules = _modules()
    path = ROOT / "wecss" / "sim" / "_result.py"
    assert "wecss.compiled" in _imports("wecss.sim._result", path, modules)


@pytest.mark.parametrize("source", SOURCES)
def test_every_source_folder_is_read(source):
    assert any(name.startswith(source) for name in _modules())


def test_wecss_never_imports_its_plugins():
    """The built-in controllers import wecss; wecss finds them through entry points only."""
    wrong = [
        f"{m} -> {t}" for m, ts in _graph().items() if m.startswith("wecss") for t in ts if t.startswith("controllers")
    ]
    assert wrong == []
