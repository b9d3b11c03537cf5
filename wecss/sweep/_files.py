"""Where a sweep's cases live on disk and what state they are in."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from ._spec import Case


def case_paths(folder: Path, case: Case) -> tuple[Path, Path]:
    """The result file and the failure record of a case."""
    return folder / f"{case.name}.nc", folder / f"{case.name}.failed.json"


def case_status(folder: Path, case: Case) -> str:
    """ "done" (its file exists), "failed" (its failure record exists) or "pending"."""
    result, failure = case_paths(folder, case)
    if result.is_file():
        return "done"
    return "failed" if failure.is_file() else "pending"


def write_text(path: Path, text: str) -> None:
    """Write a small text file atomically (temporary file, then rename)."""
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
