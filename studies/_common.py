"""Helpers shared by the study scripts: timing and writing sections of ``docs/benchmarks.md``."""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def bench(func: Callable[[], object], steps: int, repeats: int) -> float:
    """Median time per call [s] over ``repeats`` runs of ``steps`` calls."""
    runs = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(steps):
            func()
        runs.append((time.perf_counter() - start) / steps)
    return float(np.median(runs))


def write_section(path: Path, section: str, text: str) -> None:
    """Replace (or append) the section of a Markdown file that starts with the heading ``section``."""
    old = path.read_text() if path.is_file() else "# Benchmarks\n"
    head, _, rest = old.partition(section)
    tail = ""
    if rest:
        nxt = rest.find("\n## ")
        tail = rest[nxt:] if nxt >= 0 else ""
    path.write_text(head.rstrip() + "\n\n" + text.strip() + "\n" + tail)
