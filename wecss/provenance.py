"""The input files a result records: for each, the field that named it, its path, its size and its SHA-256, and,
once the result is written, its path relative to the result's folder; and the check that a run made again from a
result (``wecss run --from``) reads the same files, found where they were or where they moved with the result.

A result keeps the list as JSON in its ``input_files`` attribute (netCDF attributes are text, numbers or arrays of
numbers): ``[{"field": ..., "path": ..., "bytes": ..., "sha256": ..., "relative_path": ...}, ...]``.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

INPUTS_ATTR = "input_files"
"""The result attribute holding the JSON list of input files."""

SPEC_ATTR = "device_spec"
"""The result attribute holding the device spec's text (TOML) as the run read it."""


def sha256(path: str | os.PathLike[str]) -> str:
    """The SHA-256 of a file's bytes, as 64 hexadecimal digits."""
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def array_digest(*arrays: Any) -> str:
    """The SHA-256 of arrays' shapes and float64 values (a fitted model's matrices), as 64 hexadecimal digits."""
    digest = hashlib.sha256()
    for a in arrays:
        values = np.ascontiguousarray(a, dtype=float)
        digest.update(repr(values.shape).encode())
        digest.update(values.tobytes())
    return digest.hexdigest()


def input_records(files: Mapping[str, Path], shipped: Path | None = None) -> list[dict[str, Any]]:
    """One record per file of ``files`` (field to path; folders and missing paths are left out): the field, the
    absolute path, the size [bytes] and the SHA-256; for a file inside ``shipped`` (the data shipped with wecss),
    also ``shipped_path``, its path inside that folder (found there again in another installation)."""
    records = []
    for field, path in files.items():
        path = Path(path).resolve()
        if not path.is_file():
            continue
        record: dict[str, Any] = {"field": field, "path": str(path), "bytes": path.stat().st_size}
        record["sha256"] = sha256(path)
        if shipped is not None and path.is_relative_to(shipped.resolve()):
            record["shipped_path"] = path.relative_to(shipped.resolve()).as_posix()
        records.append(record)
    return records


def with_relative_paths(attrs: Mapping[str, Any], target: str | os.PathLike[str]) -> dict[str, Any]:
    """``attrs`` with each input record's ``relative_path`` set to its path relative to the folder of ``target``
    (the result file about to be written); ``attrs`` as they are when they hold no records."""
    out = dict(attrs)
    text = out.get(INPUTS_ATTR)
    if not isinstance(text, str):
        return out
    try:
        records = json.loads(text)
    except json.JSONDecodeError:
        return out
    folder = Path(target).resolve().parent
    for record in records:
        if not isinstance(record, dict) or "shipped_path" in record:  # shipped files are found in wecss's data
            continue
        try:
            record["relative_path"] = Path(os.path.relpath(record["path"], folder)).as_posix()
        except (ValueError, KeyError, TypeError):  # another drive (Windows), or not a record
            record.pop("relative_path", None)
    out[INPUTS_ATTR] = json.dumps(records)
    return out


class InputChangedError(ValueError):
    """An input file of a recorded run differs from the file the run read (or cannot be found)."""


@dataclass(frozen=True)
class FoundInput:
    """An input file of a recorded run as found again: the record and where it is now."""

    field: str
    recorded: Path
    found: Path

    @property
    def moved(self) -> bool:
        """True when it was found beside the result (by its relative path), not where the run read it."""
        return self.found != self.recorded


def find_inputs(
    attrs: Mapping[str, Any], result: str | os.PathLike[str], shipped: Path | None = None
) -> list[FoundInput]:
    """Every input file a result records (its ``input_files``), found where the run read it or, when that path
    holds no file with the recorded SHA-256, by its path relative to the folder of ``result`` (a file shipped with
    wecss: by its path inside ``shipped``, this installation's data folder); each checked against its recorded
    SHA-256.

    Raises
    ------
    InputChangedError
        (a ValueError) Naming the field, the file, the recorded and the present SHA-256, when a file's content
        changed; or the paths looked at, when no file is found.
    """
    text = attrs.get(INPUTS_ATTR)
    if not isinstance(text, str):
        return []
    folder = Path(result).resolve().parent
    found = []
    for record in json.loads(text):
        recorded = Path(record["path"])
        candidates = [recorded]
        if record.get("relative_path"):
            candidates.append((folder / record["relative_path"]).resolve())
        if record.get("shipped_path") and shipped is not None:
            candidates.append((shipped / record["shipped_path"]).resolve())
        present = [(p, sha256(p)) for p in dict.fromkeys(candidates) if p.is_file()]
        match = next((p for p, digest in present if digest == record["sha256"]), None)
        if match is not None:
            found.append(FoundInput(record["field"], recorded, match))
            continue
        if not present:
            raise InputChangedError(
                f"the {record['field']} of this run is missing: no file at "
                + " nor at ".join(repr(str(p)) for p in dict.fromkeys(candidates))
            )
        path, digest = present[0]
        raise InputChangedError(
            f"the {record['field']} changed since the run: {str(path)!r} has SHA-256 {digest}, the run read "
            f"{record['sha256']} ({record['bytes']} bytes); restore the file, or run the scene again without --from"
        )
    return found
