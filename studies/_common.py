"""Helpers shared by the study scripts: timing (in this process and of commands in fresh processes) and writing
sections of ``docs/benchmarks.md``."""

from __future__ import annotations

import os
import resource
import subprocess
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

ENV = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "PYTHONPATH": str(ROOT)}
"""Environment of the commands the benchmarks time in fresh processes: one BLAS thread, this source tree first."""


def bench(func: Callable[[], object], steps: int, repeats: int) -> float:
    """Median time per call [s] over ``repeats`` runs of ``steps`` calls."""
    runs = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(steps):
            func()
        runs.append((time.perf_counter() - start) / steps)
    return float(np.median(runs))


def wall(command: list[str], repeats: int, cwd: Path, before: Callable[[], None] = lambda: None) -> tuple[float, float]:
    """Median (wall time, CPU time: user + system) [s] of a command in a fresh process (environment ``ENV``), with
    ``before`` called ahead of each run. On a shared machine the CPU time is the closer estimate of the wall time on
    an idle one."""
    runs, cpus = [], []
    for _ in range(repeats):
        before()
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(command, env=ENV, cwd=cwd, check=True, capture_output=True)
        runs.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - usage.ru_utime + after.ru_stime - usage.ru_stime)
    return float(np.median(runs)), float(np.median(cpus))


def write_section(path: Path, section: str, text: str) -> None:
    """Replace (or append) the section of a Markdown file that starts with the heading ``section``."""
    old = path.read_text() if path.is_file() else "# Benchmarks\n"
    head, _, rest = old.partition(section)
    tail = ""
    if rest:
        nxt = rest.find("\n## ")
        tail = rest[nxt:] if nxt >= 0 else ""
    path.write_text(head.rstrip() + "\n\n" + text.strip() + "\n" + tail)
