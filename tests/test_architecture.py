"""``docs/architecture.md`` is held to the code: every file its table of places ("Where a new piece goes") names
exists, every dotted wecss name resolves, every other name it quotes is found in the files of its row, the rows
the house needs are there, and the page leans on no file outside the repository."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PAGE = ROOT / "docs" / "architecture.md"
REQUIRED_ROWS = ("integrator", "output variable", "controller", "hydrodynamic reader", "force term", "body type")


def _table() -> list[list[str]]:
    text = PAGE.read_text()
    section = text.split("## Where a new piece goes", 1)[1]
    rows = [line for line in section.splitlines() if line.startswith("|") and not line.startswith("|---")]
    return [[cell.strip() for cell in row.strip("|").split("|")] for row in rows[1:]]


def _quoted(row: list[str]) -> list[str]:
    return [token for cell in row for token in re.findall(r"`([^`]+)`", cell)]


def _is_path(token: str) -> bool:
    return "/" in token or token.endswith((".py", ".toml", ".md"))


def _resolves(dotted: str) -> bool:
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        for attribute in parts[cut:]:
            if not hasattr(obj, attribute):
                return False
            obj = getattr(obj, attribute)
        return True
    return False


def test_the_rows_the_house_needs_are_there():
    kinds = [row[0] for row in _table()]
    for required in REQUIRED_ROWS:
        assert any(kind.startswith(required) for kind in kinds), f"no row for {required!r}: {kinds}"


def test_every_file_the_table_names_exists():
    for row in _table():
        for token in _quoted(row):
            if _is_path(token) and not token.startswith(("../", "[")) and "<" not in token:
                path = ROOT / token.split(" ")[0].rstrip(":")
                assert path.exists() or (path.parent.exists() and token.endswith("/")), f"{row[0]}: no {token}"


def test_every_name_the_table_quotes_is_in_its_rows_files():
    for row in _table():
        tokens = _quoted(row)
        files = [ROOT / t for t in tokens if _is_path(t) and (ROOT / t).is_file() and t.endswith(".py")]
        text = "\n".join(f.read_text() for f in files)
        for token in tokens:
            if _is_path(token) or not re.fullmatch(r"[A-Za-z_][\w.]*(\(\))?", token):
                continue
            name = token.removesuffix("()")
            if name.startswith("wecss."):
                assert _resolves(name), f"{row[0]}: {name} does not resolve"
            elif files and name not in ("setup", "reset") and "." not in name:
                assert re.search(rf"\b{re.escape(name)}\b", text), f"{row[0]}: {name} is in none of {files}"


def test_the_page_leans_on_nothing_outside_the_repository():
    text = PAGE.read_text()
    assert "DESIGN.md" not in text
    assert "../shared" not in text.split("## Where a new piece goes")[0]
