"""Every fenced code block of README.md and docs/*.md runs as a reader would run it (issue 31).

- ``python`` blocks: the blocks of one page run in order in one namespace, in a temporary working folder of the
  page, so a later block may use the names of an earlier one;
- ``sh`` blocks: every line a ``wecss ...`` command, run by ``wecss.cli.main([...])`` in the page's folder (exit
  status 0);
- ``toml`` blocks: parsed, and read by the project's own readers: a sweep file by ``Sweep.from_dict``, a scene
  (its sections) by ``Scene.from_dict``, a complete device spec by ``Device.from_spec``, a ``hydro`` file with its
  ``[hydro_options]`` by ``Device.hydro``; a part of a device spec (a ``fragment`` marker says which) only parsed;
- ``text`` blocks (diagrams, output) are not code.

The page's folder sits beside a link ``../shared`` to the repository's ``../shared``, so a block reads the public
reference data as ``../shared/data/...``, as from the repository root; a block that names a file there is skipped
when the file is absent (``WECSS_DOCS_SHARED`` names another ``shared`` folder: a git worktree has none beside
it). A ``<!-- docs-test: file (NAME) -->`` marker before a block writes the block to NAME in the
page's folder before the page's first block runs (the scene file a later command reads). Markers (``skip``,
``slow``, ``fragment``, ``file``) are described in ``tests/docs_blocks.py``; each needs its reason.
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import tomllib
import warnings
from pathlib import Path
from typing import Any

import pytest

from tests.docs_blocks import LANGUAGES, ROOT, Block, all_blocks, shell_commands

BLOCKS = all_blocks()
MARKERS = ("skip", "slow", "fragment", "file")
SHARED = Path(os.environ.get("WECSS_DOCS_SHARED", ROOT.parent / "shared"))  # another checkout's, for a worktree
SCENE_SECTIONS = {"device", "sea", "controller", "solver", "radiation", "outputs", "hydrodynamics", "initial"}


def _param(block: Block) -> Any:
    marks = [pytest.mark.slow] if block.marker == "slow" else []
    return pytest.param(block, id=block.id, marks=marks)


RUNNABLE = [b for b in BLOCKS if b.language in ("python", "sh", "toml")]


class _Page:
    """The working folder and namespace of one page, and which of its blocks ran."""

    def __init__(self, page: str, base: Path) -> None:
        self.folder = base / "work"
        self.folder.mkdir(parents=True)
        if SHARED.is_dir():
            (base / "shared").symlink_to(SHARED, target_is_directory=True)
        self.namespace: dict[str, Any] = {"__name__": "__main__"}
        self.done: dict[int, bool] = {}  # line -> ran without error
        for block in BLOCKS:
            if block.page == page and block.marker == "file":
                (self.folder / str(block.reason)).write_text(block.text)


_PAGES: dict[str, _Page] = {}


@pytest.fixture
def page_of(tmp_path_factory: pytest.TempPathFactory):
    def get(page: str) -> _Page:
        if page not in _PAGES:
            _PAGES[page] = _Page(page, tmp_path_factory.mktemp(page.replace("/", "_").replace(".md", "")))
        return _PAGES[page]

    return get


@contextlib.contextmanager
def _inside(folder: Path):
    old = Path.cwd()
    os.chdir(folder)
    try:
        yield
    finally:
        os.chdir(old)


def _missing_shared(block: Block) -> str | None:
    """The first file of ../shared/data that the block names, or that the page's files (``file`` markers) name for
    its commands, and that is absent; None when all are there."""
    texts = [block.text]
    if block.language == "sh":
        texts += [b.text for b in BLOCKS if b.page == block.page and b.marker == "file"]
    for text in texts:
        for name in re.findall(r"\.\./shared/data/[\w./-]*\w", text):
            if not (SHARED / name.removeprefix("../shared/")).exists():
                return name
    return None


def _run_python(block: Block, page: _Page) -> None:
    code = compile(block.text, f"{block.id}", "exec")
    with _inside(page.folder), warnings.catch_warnings():
        warnings.simplefilter("default")  # a reader sees warnings; the block must not fail on them
        exec(code, page.namespace)


def _run_shell(block: Block, page: _Page) -> None:
    """Each ``wecss ...`` line through ``wecss.cli.main(argv)`` in the page's folder: the command's own code, without
    a process's start-up per line (the command line's process settings are tests/test_command_process.py's)."""
    from wecss.cli import main

    for words in shell_commands(block.text):
        assert words[0] == "wecss", f"{block.id}: only wecss commands run in a test; got {' '.join(words)!r}"
        out, err = io.StringIO(), io.StringIO()
        with _inside(page.folder), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            with warnings.catch_warnings():
                warnings.simplefilter("default")
                status = main(words[1:])
        assert status == 0, f"{block.id}: {' '.join(words)} exited {status}:\n{out.getvalue()}\n{err.getvalue()}"


def _check_toml(block: Block, page: _Page) -> None:
    data = tomllib.loads(block.text)
    if block.marker == "fragment":
        return  # a part of a larger file: parsed above
    if "sweep" in data:
        from wecss.sweep import Sweep

        Sweep.from_dict(data, base=page.folder)
    elif set(data) <= SCENE_SECTIONS:
        from wecss.scene import Scene

        Scene.from_dict(data, base=page.folder)
    elif {"name", "bodies", "joints"} <= set(data):
        from wecss.devices import Device

        path = page.folder / f"spec_{block.line}.toml"
        path.write_text(block.text)
        with warnings.catch_warnings():
            warnings.simplefilter("default")
            Device.from_spec(path).hydro()
    elif set(data) == {"hydro", "hydro_options"}:
        import dataclasses

        from wecss.devices import load

        device = dataclasses.replace(
            load("rm3"), hydro_source=str(page.folder / data["hydro"]), hydro_options=data["hydro_options"]
        )
        with warnings.catch_warnings():
            warnings.simplefilter("default")
            device.hydro()
    else:
        pytest.fail(
            f"{block.id}: a TOML block that is neither a sweep, a scene, a device spec nor hydro options "
            f"(tables {sorted(data)}); mark a part of a file <!-- docs-test: fragment (of what) -->"
        )


@pytest.mark.parametrize("block", [_param(b) for b in RUNNABLE])
def test_block_runs(block: Block, page_of) -> None:
    """The block runs (python), its commands succeed (sh) or its file is read (toml)."""
    if block.marker == "skip":
        pytest.skip(f"marked: {block.reason}")
    missing = _missing_shared(block)
    if missing is not None:
        pytest.skip(f"{missing} is absent")
    page = page_of(block.page)
    # the earlier python blocks of the page first (a reader runs them first; with xdist they may be elsewhere)
    if block.language == "python":
        for earlier in RUNNABLE:
            if earlier.page != block.page or earlier.line >= block.line or earlier.language != "python":
                continue
            if earlier.marker == "skip" or earlier.line in page.done or _missing_shared(earlier) is not None:
                if page.done.get(earlier.line) is False:
                    pytest.skip(f"the earlier block {earlier.id} failed")
                continue
            page.done[earlier.line] = False
            _run_python(earlier, page)
            page.done[earlier.line] = True
        page.done[block.line] = False
        _run_python(block, page)
        page.done[block.line] = True
    elif block.language == "sh":
        _run_shell(block, page)
    else:
        _check_toml(block, page)


def test_every_block_has_a_known_language() -> None:
    """A fence names its language, so that the test knows whether to run it."""
    unknown = [f"{b.id} ({b.language!r})" for b in BLOCKS if b.language not in LANGUAGES]
    assert not unknown, f"code blocks without a language of {LANGUAGES}: {unknown}"


def test_markers_have_reasons() -> None:
    """Every docs-test marker is a known kind and gives its reason; the skipped blocks are listed here."""
    bad = [f"{b.id}" for b in BLOCKS if b.marker is not None and (b.marker not in MARKERS or not b.reason)]
    assert not bad, f"docs-test markers of an unknown kind or without a reason: {bad}"
    skipped = {b.id: b.reason for b in BLOCKS if b.marker == "skip"}
    print("blocks not run:", skipped)
    assert len(skipped) <= 5, f"skips should stay rare: {skipped}"


def test_blocks_found() -> None:
    """The extraction finds blocks (a change of fence style would otherwise pass silently)."""
    assert len(RUNNABLE) >= 30
    assert {b.page for b in RUNNABLE} >= {"README.md", "docs/control.md", "docs/simulator.md", "docs/byo-bem.md"}


def test_every_page_is_in_the_site_navigation() -> None:
    """Every docs/*.md is a page of the documentation site's navigation (mkdocs.yml), and every page named there
    exists; ``mkdocs build --strict`` (``make docs``) refuses either, this says which page at once."""
    text = (ROOT / "mkdocs.yml").read_text()
    nav = text[text.index("\nnav:") :]
    named = set(re.findall(r":\s*([\w/.-]+\.md)\s*$", nav, flags=re.MULTILINE))
    pages = {p.relative_to(ROOT / "docs").as_posix() for p in (ROOT / "docs").rglob("*.md")}
    assert pages - named == set(), f"pages missing from the nav of mkdocs.yml: {sorted(pages - named)}"
    assert named - pages == set(), f"mkdocs.yml names pages that do not exist: {sorted(named - pages)}"


def test_generated_passages_have_their_markers_and_their_study() -> None:
    """A passage a study writes between ``<!-- NAME: begin ... -->`` and ``<!-- NAME: end -->`` markers has both,
    once and in order, and the study that writes it names the begin marker (a renamed marker would make the study
    fail, or leave the page's numbers stale)."""
    studies = "\n".join(p.read_text() for p in (ROOT / "studies").glob("*.py"))
    found = 0
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        text = path.read_text()
        for begin in re.finditer(r"<!-- ([\w-]+): begin[^>]*-->", text):
            found += 1
            name, marker = begin[1], begin[0]
            end = f"<!-- {name}: end -->"
            assert text.count(marker) == 1 and text.count(end) == 1, f"{path.name}: {name}'s markers not once each"
            assert text.index(end) > begin.start(), f"{path.name}: {name}'s end marker before its begin"
            assert marker in studies, f"{path.name}: no study under studies/ writes {marker!r}"
    assert found >= 1
