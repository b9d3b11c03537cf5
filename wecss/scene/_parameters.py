"""Controller parameters frozen for hashing: a read-only dict whose lists are tuples."""

from __future__ import annotations

from typing import Any


def _freeze(value: Any) -> Any:
    """A hashable copy of a parameter value: lists and tuples become tuples, tables :class:`Parameters`."""
    if isinstance(value, dict):
        return Parameters(value)
    if isinstance(value, list | tuple):
        return tuple(_freeze(v) for v in value)
    if hasattr(value, "tolist") and not isinstance(value, str):  # numpy arrays and scalars
        return _freeze(value.tolist())
    return value


class Parameters(dict):
    """Controller parameters: a read-only dict whose lists are frozen to tuples, so that scenes can be hashed and
    used as keys. Build a changed scene with ``dataclasses.replace`` instead of changing one in place."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        for key, value in dict.items(self):
            if not isinstance(key, str):
                raise TypeError(f"controller.parameters: keys are names (str); got {key!r}")
            dict.__setitem__(self, key, _freeze(value))

    def _read_only(self, *args: Any, **kwargs: Any) -> None:
        raise TypeError("scene parameters are read-only; make a new scene with dataclasses.replace")

    __setitem__ = __delitem__ = _read_only
    clear = pop = popitem = setdefault = update = __ior__ = _read_only  # type: ignore[assignment]

    def __hash__(self) -> int:  # type: ignore[override]
        return hash(tuple(sorted(self.items())))

    def __reduce__(self) -> tuple[type, tuple[dict[str, Any]]]:
        return Parameters, (dict(self),)
