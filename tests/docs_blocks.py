"""The fenced code blocks of README.md and docs/*.md, for tests/test_docs_run.py.

A block is a fence of three backticks with a language (``python``, ``sh``, ``toml`` or ``text``) and its lines. A
comment just before the fence (blank lines between allowed) marks a block the test treats differently:

- ``<!-- docs-test: skip (reason) -->``: not run (a command that builds a virtual environment, a cluster address);
- ``<!-- docs-test: slow (reason) -->``: run only with ``-m slow``;
- ``<!-- docs-test: fragment (of what) -->``: a TOML block that is a part of a file (tables of a device spec): parsed
  only;
- ``<!-- docs-test: file (NAME) -->``: the block is a file the page's other blocks read; the test writes it as NAME in
  the page's folder (and reads it as its kind).

Every marker must give its reason (or file name) in parentheses.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LANGUAGES = ("python", "sh", "toml", "text")
MARKER = re.compile(r"<!--\s*docs-test:\s*(?P<kind>[a-z]+)\s*(?:\((?P<reason>[^)]*)\))?\s*-->")
FENCE = re.compile(r"^(?P<indent> *)```(?P<info>[^`]*)$")


@dataclass(frozen=True)
class Block:
    """One fenced block: its page (relative to the repository root), first line number (of the fence), language,
    text and the marker before it (kind and reason, or None)."""

    page: str
    line: int
    language: str
    text: str
    marker: str | None = None
    reason: str | None = None

    @property
    def id(self) -> str:
        return f"{self.page}:{self.line}"


def pages(root: Path = ROOT) -> list[Path]:
    """README.md and every docs/*.md, in a fixed order."""
    return [root / "README.md", *sorted((root / "docs").glob("*.md"))]


def blocks_of(path: Path, root: Path = ROOT) -> list[Block]:
    """The fenced blocks of one markdown page, in order."""
    lines = path.read_text(encoding="utf-8").splitlines()
    page = path.relative_to(root).as_posix()
    found: list[Block] = []
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if m is None:
            i += 1
            continue
        start = i
        indent = len(m["indent"])
        j = i + 1
        while j < len(lines) and lines[j].strip() != "```":
            j += 1
        if j == len(lines):
            raise ValueError(f"{page}:{start + 1}: a code fence that is never closed")
        text = "\n".join(line[indent:] for line in lines[start + 1 : j]) + "\n"
        marker = reason = None
        k = start - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        if k >= 0:
            mm = MARKER.search(lines[k])
            if mm is not None:
                marker, reason = mm["kind"], (mm["reason"] or "").strip() or None
        found.append(Block(page, start + 1, m["info"].strip(), text, marker, reason))
        i = j + 1
    return found


def all_blocks(root: Path = ROOT) -> list[Block]:
    """Every fenced block of README.md and docs/*.md."""
    return [b for p in pages(root) for b in blocks_of(p, root)]


def shell_commands(text: str) -> list[list[str]]:
    """The commands of a shell block, one per line, split like a shell would (comments dropped)."""
    import shlex

    commands = []
    for line in text.splitlines():
        words = shlex.split(line, comments=True)
        if words:
            commands.append(words)
    return commands
