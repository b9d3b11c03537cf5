"""A griffe extension for the API reference (mkdocs.yml): a package's names re-exported with the redundant alias
``from ._module import Name as Name`` are its public names (the convention wecss's packages follow, PEP 484), so the
reference documents them on the package's page. Griffe counts only ``__all__`` by default."""

from __future__ import annotations

from typing import Any

import griffe


class RedundantAliasesArePublic(griffe.Extension):
    """Marks ``import X as X`` re-exports of every package ``__init__`` public."""

    def on_package(self, *, pkg: griffe.Module, **kwargs: Any) -> None:
        """Griffe 2: the package and its modules are loaded."""
        self._mark(pkg)

    def on_package_loaded(self, *, pkg: griffe.Module, **kwargs: Any) -> None:
        """Griffe 1's name of the same hook."""
        self._mark(pkg)

    def _mark(self, module: griffe.Module) -> None:
        lines = module.lines if module.is_init_module else []
        for name, member in module.members.items():
            if member.is_alias and not name.startswith("_") and member.alias_lineno:
                line = lines[member.alias_lineno - 1] if member.alias_lineno <= len(lines) else ""
                if f" as {name}" in line:
                    member.public = True
            elif not member.is_alias and member.is_module:
                self._mark(member)  # type: ignore[arg-type]
