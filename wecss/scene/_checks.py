"""Checks of the values a scene's sections are built from: types of fields read from TOML, unknown keys, choices
among accepted names; each refusal names the field, the value and what is accepted."""

from __future__ import annotations

from dataclasses import fields
from typing import Any

from ._errors import SceneError


def check_types(section: str, values: dict[str, tuple[Any, type]]) -> None:
    """Check the types of fields read from TOML (bools are not integers here)."""
    for key, (value, kind) in values.items():
        wrong = not isinstance(value, kind) or (kind is int and isinstance(value, bool))
        if wrong:
            raise SceneError(f"{section}.{key} must be {kind.__name__}; got {value!r} ({type(value).__name__})")


def check_keys(section: str, data: dict[str, Any], cls: type) -> None:
    known = [f.name for f in fields(cls)]
    unknown = sorted(set(data) - set(known))
    if unknown:
        raise SceneError(f"[{section}]: unknown keys {unknown}; accepted: {', '.join(known)}")


def check_choice(name: str, value: str, accepted: tuple[str, ...]) -> None:
    if value not in accepted:
        raise SceneError(f"{name}: unknown {value!r}; accepted: {', '.join(accepted)}")
