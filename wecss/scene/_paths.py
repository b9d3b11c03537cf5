"""Dotted scene paths (``"sea.period"``, ``"controller.parameters.damping"``): a value set in a scene's nested dict
(``Scene.to_dict`` layout). ``wecss run --set``, a sweep's axes and ``Scene.replace`` change a scene through them."""

from __future__ import annotations

from typing import Any

from ._errors import SceneError


def set_path(data: dict[str, Any], path: str, value: Any) -> dict[str, Any]:
    """A copy of the scene dict ``data`` with the dotted ``path`` set to ``value``.

    Paths such as ``"sea.period"`` or ``"controller.parameters.damping"``.

    Raises
    ------
    SceneError
        If the path has fewer than two parts or crosses a value that is not a table.
    """
    parts = path.split(".") if isinstance(path, str) else []
    if len(parts) < 2 or not all(parts):
        raise SceneError(f"a scene path is 'section.key' (such as 'sea.period'); got {path!r}")
    out = plain_copy(data)
    node = out
    for depth, part in enumerate(parts[:-1]):
        child = node.setdefault(part, {})
        if not isinstance(child, dict):
            raise SceneError(f"{'.'.join(parts[: depth + 1])} is a value ({child!r}), not a table: cannot set {path!r}")
        node = child
    node[parts[-1]] = value
    return out


def plain_copy(value: Any) -> Any:
    """A deep copy with every table a plain (writable) dict and every sequence a list."""
    if isinstance(value, dict):
        return {k: plain_copy(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [plain_copy(v) for v in value]
    return value
