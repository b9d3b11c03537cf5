"""The import structure of wecss: no import cycles between modules or between packages (imports inside functions
count too), and no private module imported from outside the package that owns it (DESIGN.md, issue 12).

Read from the source with ``ast``; nothing is imported. A new cycle or private import fails here with the path.
The study scripts import each other by bare name (``from _common import ROOT``: a script's folder is first on
``sys.path``); such an import of a module ``studies/X.py`` from a study counts as an import of ``studies.X``.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SOURCES = ("wecss", "controllers", "studies")
IMPORTED_AS = {"controllers": "wecss_controllers"}
"""Source folders whose package imports under another name (pyproject.toml's ``[tool.setuptools.package-dir]``)."""


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    parts[0] = IMPORTED_AS.get(parts[0], parts[0])
    return ".".join(parts)


def _modules() -> dict[str, Path]:
    return {_module_name(p): p for top in SOURCES for p in sorted((ROOT / top).rglob("*.py"))}


def _absolute(stem: str, name: str, known: dict[str, Path]) -> str:
    """The module an absolute import of ``stem`` in module ``name`` reaches: a study's bare-name import of a sibling
    script (``import _common`` in ``studies/bench_mpc.py``) is ``studies._common``; any other stays as written."""
    if name.startswith("studies.") and stem and f"studies.{stem.split('.')[0]}" in known:
        return f"studies.{stem}"
    return stem


def _imports(name: str, path: Path, known: dict[str, Path], source: str | None = None) -> set[str]:
    """Every wecss/controllers module that ``name`` imports, at any depth of the file (``source``: the file's text,
    read from ``path`` when not given)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out: set[str] = set()
    text = path.read_text() if source is None else source
    for node in ast.walk(ast.parse(text, filename=str(path))):
        if isinstance(node, ast.Import):
            targets = [_absolute(alias.name, name, known) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                stem = ".".join([*base, node.module] if node.module else base)
            else:
                stem = _absolute(node.module or "", name, known)
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


def _is_private(part: str) -> bool:
    return part.startswith("_") and not part.startswith("__")


def _private_modules_imported_across(graph: dict[str, set[str]]) -> list[str]:
    """``module -> target`` for every private module (a path part with a leading underscore) imported from
    outside the package that holds it (subpackages may use their parent's private modules)."""
    wrong = []
    for module, targets in graph.items():
        for target in targets:
            parts = target.split(".")
            private = [k for k, part in enumerate(parts) if _is_private(part)]
            if not private:
                continue
            owner = ".".join(parts[: private[0]])  # the package whose private module it is
            if not (module == owner or module.startswith(owner + ".")):
                wrong.append(f"{module} -> {target}")
    return sorted(wrong)


def _private_names_imported_across(
    name: str, path: Path, known: dict[str, Path], source: str | None = None
) -> list[str]:
    """``module -> target:name`` for every private name (function, class, constant) that ``name`` imports with
    ``from X import _name`` from a module of another package (the package holding X, or its subpackages, may)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    wrong = []
    text = path.read_text() if source is None else source
    for node in ast.walk(ast.parse(text, filename=str(path))):
        if not isinstance(node, ast.ImportFrom):
            continue
        if node.level:
            base = package.split(".")
            base = base[: len(base) - node.level + 1]
            stem = ".".join([*base, node.module] if node.module else base)
        else:
            stem = _absolute(node.module or "", name, known)
        if stem.split(".")[0] not in SOURCES:
            continue
        for alias in node.names:
            if not _is_private(alias.name) or f"{stem}.{alias.name}" in known:
                continue  # a public name, or a module (the module check covers those)
            owner = stem if (stem in known and known[stem].name == "__init__.py") else stem.rpartition(".")[0]
            if not (name == owner or name.startswith(owner + ".")):
                wrong.append(f"{name} -> {stem}:{alias.name}")
    return wrong


def test_no_private_module_is_imported_from_another_package():
    assert _private_modules_imported_across(_graph()) == []


def test_no_private_name_is_imported_from_another_package():
    known = _modules()
    wrong = [w for name, path in known.items() for w in _private_names_imported_across(name, path, known)]
    assert wrong == []


def test_the_checks_find_a_cycle_and_a_private_import():
    """The checks themselves: a made-up graph with a cycle, and a private import across packages."""
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []
    modules = _modules()
    path = ROOT / "wecss" / "sim" / "_dataset.py"
    assert "wecss.control" in _imports("wecss.sim._dataset", path, modules)


def test_the_studies_imports_by_bare_name_are_resolved():
    """``from _common import ROOT`` in a study is an edge to ``studies._common``; so is an import of another study."""
    graph = _graph()
    assert {"studies._common", "studies.m4_control", "studies.wecccomp"} <= graph["studies.bench_mpc"]
    assert "studies._scenes" in graph["studies.bench_startup"]


def test_the_checks_find_a_cycle_between_studies_imported_by_bare_name():
    """Made-up studies: ``made_up_a`` imports ``made_up_b`` by bare name, ``made_up_b`` imports it back inside a
    function. The cycle is found; a bare name that is no study (numpy), and the same bare name in a library module
    (which does not run with ``studies/`` on its path), are not study imports."""
    folder = ROOT / "studies"
    known = {**_modules(), "studies.made_up_a": folder / "made_up_a.py", "studies.made_up_b": folder / "made_up_b.py"}
    sources = {
        "studies.made_up_a": "import numpy as np\nfrom made_up_b import helper\nfrom _common import ROOT\n",
        "studies.made_up_b": "def helper():\n    import made_up_a\n",
    }
    graph = {name: _imports(name, known[name], known, text) for name, text in sources.items()}
    assert graph == {
        "studies.made_up_a": {"studies.made_up_b", "studies._common"},
        "studies.made_up_b": {"studies.made_up_a"},
    }
    assert _cycles(graph) == [["studies.made_up_a", "studies.made_up_b"]]
    assert _imports("wecss.cli", ROOT / "wecss" / "cli.py", known, "import made_up_a\nimport _common\n") == set()


def test_the_private_checks_read_the_studies_bare_name_imports():
    """A study may use the studies' own private helpers (one folder, one package); a library module may not, and a
    study reaching into a library's private module or name is found."""
    known = _modules()
    path = ROOT / "studies" / "bench_mpc.py"
    own = "from _common import _private_helper\nimport _scenes\n"
    graph = {"studies.bench_mpc": _imports("studies.bench_mpc", path, known, own)}
    assert graph["studies.bench_mpc"] == {"studies._common", "studies._scenes"}
    assert _private_modules_imported_across(graph) == []
    assert _private_names_imported_across("studies.bench_mpc", path, known, own) == []
    into_wecss = "from wecss.sim._dataset import build_result\nfrom wecss.sim import _notes\n"
    graph = {"studies.bench_mpc": _imports("studies.bench_mpc", path, known, into_wecss)}
    assert _private_modules_imported_across(graph) == ["studies.bench_mpc -> wecss.sim._dataset"]
    assert _private_names_imported_across("studies.bench_mpc", path, known, into_wecss) == [
        "studies.bench_mpc -> wecss.sim:_notes"
    ]
    library = "from studies._common import ROOT\n"
    graph = {"wecss.cli": _imports("wecss.cli", ROOT / "wecss" / "cli.py", known, library)}
    assert _private_modules_imported_across(graph) == ["wecss.cli -> studies._common"]


@pytest.mark.parametrize(
    ("source", "found"),
    [
        ("from wecss.compiled._kernels import accelerations\n", ["wecss.cli -> wecss.compiled._kernels"]),
        ("from .compiled._compile import compile_plant\n", ["wecss.cli -> wecss.compiled._compile"]),
        ("import wecss.linear._model as m\n", ["wecss.cli -> wecss.linear._model"]),
        ("def f():\n    from .compiled import _kernels\n", ["wecss.cli -> wecss.compiled._kernels"]),
        ("from wecss.compiled import compile_plant\n", []),
    ],
)
def test_the_lint_rule_finds_private_modules_at_any_depth(source, found):
    """A made-up ``wecss/cli.py`` reaching into another package's private module, absolutely, relatively, as a
    plain import or inside a function: each is found."""
    known = _modules()
    graph = {"wecss.cli": _imports("wecss.cli", ROOT / "wecss" / "cli.py", known, source)}
    assert _private_modules_imported_across(graph) == found


def test_the_lint_rule_finds_private_names_of_another_package():
    known = _modules()
    path = ROOT / "wecss" / "results" / "_plot.py"
    bad = "from ..sim import _notes\nfrom ..compiled import _private_helper as helper\n"
    assert _private_names_imported_across("wecss.results._plot", path, known, bad) == [
        "wecss.results._plot -> wecss.sim:_notes",
        "wecss.results._plot -> wecss.compiled:_private_helper",
    ]
    inside = "from ._plot import _pyplot\nfrom . import _metrics\n"  # the same package, and a module
    assert _private_names_imported_across("wecss.results._summary_plot", path, known, inside) == []


@pytest.mark.parametrize("source", SOURCES)
def test_every_source_folder_is_read(source):
    assert any(name.startswith(IMPORTED_AS.get(source, source)) for name in _modules())


def test_wecss_never_imports_its_plugins():
    """The built-in controllers import wecss; wecss finds them through entry points only."""
    wrong = [
        f"{m} -> {t}"
        for m, ts in _graph().items()
        if m.partition(".")[0] == "wecss"
        for t in ts
        if t.startswith("wecss_controllers")
    ]
    assert wrong == []


_SIX = re.compile(r"\b6 \* [A-Za-z_(]|// 6\b|% 6\b")
_SIX_HOMES = ("wecss/multibody/", "wecss/compiled/_plant.py")
"""Where a body's six rigid rows may be counted: the multibody model and the plant's offset arrays."""
_SIX_ELSEWHERE = {
    "wecss/sim/_progress.py": "hours and minutes (// 60, % 60 ... no body)",
    "wecss/devices/_beam_modes.py": "the Euler-Bernoulli element matrix (6 h)",
    "wecss/structure/_element.py": "the frame element's matrices and shape functions (6 L, 6 xi; no body)",
    "wecss/hydro/readers/_wamit_parse.py": "WAMIT's own mode numbering (6 per body plus NEWMDS)",
}


def test_bodies_are_indexed_through_the_offsets_only():
    """No ``6 * i`` body indexing outside the multibody model and the plant's offset arrays (a body may carry
    generalised modes besides its six rigid rows)."""
    found = []
    for path in sorted((ROOT / "wecss").rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        if rel.startswith(_SIX_HOMES) or rel in _SIX_ELSEWHERE:
            continue
        for number, line in enumerate(path.read_text().splitlines(), 1):
            code = line.split("#", 1)[0]
            if _SIX.search(code):
                found.append(f"{rel}:{number}: {line.strip()}")
    assert found == []


def test_the_six_check_finds_body_indexing():
    assert _SIX.search("out[6 * i : 6 * i + 3] = x")
    assert _SIX.search("body = row // 6")
    assert not _SIX.search("x = 16 * i")
