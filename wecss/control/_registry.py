"""Controllers by name: the ``wecss.controllers`` entry-point group, where the built-ins of the ``controllers``
package and third-party packages register theirs (wecss itself never imports a plugin)."""

from __future__ import annotations

from importlib.metadata import entry_points
from typing import Any

from ._protocol import Controller

ENTRY_POINT_GROUP = "wecss.controllers"


def available() -> list[str]:
    """Names registered under the ``wecss.controllers`` entry-point group."""
    return sorted(ep.name for ep in entry_points(group=ENTRY_POINT_GROUP))


def create(name: str, **parameters: Any) -> Controller:
    """Build a registered controller by name with its parameters.

    Raises
    ------
    ValueError
        For an unknown name (the message lists the known ones).
    """
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        if ep.name == name:
            return ep.load()(**parameters)
    raise ValueError(f"unknown controller {name!r}; available: {', '.join(available()) or 'none'}")
