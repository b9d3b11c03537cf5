"""Reading TOML files (floor 0): scenes, sweeps, device specs and geometry files are UTF-8 text, with or without
the byte-order mark some editors write first (TOML itself has no room for one)."""

from __future__ import annotations

import os
import tomllib
from typing import Any


def read_toml(path: str | os.PathLike[str]) -> dict[str, Any]:
    """The table of the TOML file ``path``, read as UTF-8 with or without a byte-order mark.

    Raises
    ------
    FileNotFoundError
        If there is no file at ``path``.
    tomllib.TOMLDecodeError
        If the text is not valid TOML.
    UnicodeDecodeError
        If the file is not UTF-8 text.
    """
    with open(path, encoding="utf-8-sig") as fh:
        return tomllib.loads(fh.read())
