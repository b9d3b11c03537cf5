"""The entry points of wecss's plugin groups (``wecss.controllers``, ``wecss.runners``), read once per process.

``importlib.metadata.entry_points`` reads the metadata of every installed distribution on each call (about 10 ms
here, more with many packages installed), and a run asks several times: the scene's controller by name, its
registered name for the result, the runners. :func:`entry_points` reads a group once and keeps it. It reads again
by itself when ``sys.path`` changed (a test that puts a folder with a ``.dist-info`` on the path, a notebook that
adds a source tree) or when ``importlib.metadata.entry_points`` was replaced (a test's monkeypatch); a package
installed into a folder already on the path during the process is seen after :func:`refresh`.
"""

from __future__ import annotations

import importlib.metadata
import sys
from collections.abc import Callable
from typing import Any

_GROUPS: dict[str, tuple[tuple[Callable[..., Any], tuple[str, ...]], tuple[importlib.metadata.EntryPoint, ...]]] = {}
"""Per group: what it was read with (the reading function and ``sys.path``) and its entry points."""


def entry_points(group: str) -> tuple[importlib.metadata.EntryPoint, ...]:
    """The entry points registered under ``group``, in the order of ``importlib.metadata.entry_points``."""
    scan = importlib.metadata.entry_points  # looked up on each call: a test may have replaced it
    key = (scan, tuple(sys.path))
    kept = _GROUPS.get(group)
    if kept is None or kept[0] != key:
        kept = (key, tuple(scan(group=group)))
        _GROUPS[group] = kept
    return kept[1]


def refresh() -> None:
    """Forget the groups read so far: the next :func:`entry_points` reads the installed metadata again (after
    installing or removing a package in the running process)."""
    _GROUPS.clear()
