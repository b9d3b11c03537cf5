"""Third-party plugins made in a test: a module and the ``.dist-info`` that registers it, in a folder to put on
the path."""

from __future__ import annotations

from pathlib import Path


def write_distribution(folder: Path, group: str, name: str, module: str, attribute: str, source: str) -> Path:
    """Write ``module``.py (``source``) and a distribution ``toy-<module>`` registering ``name`` =
    ``module:attribute`` under the entry-point group ``group`` into ``folder``; returns ``folder``."""
    (folder / f"{module}.py").write_text(source)
    info = folder / f"toy_{module}-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: toy-{module}\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(f"[{group}]\n{name} = {module}:{attribute}\n")
    return folder
