"""Output files that would overwrite an input of the run, and an output that could not be written (floor 0: paths
only).

A run reads files (the scene, the device spec, the hydrodynamic database, a measured elevation record, the
radiation-fit cache) and writes others (the result, its picture, a sweep's case files). :func:`refuse_overwrite`
refuses, before anything is computed or written, an output that is one of the inputs or lies inside an input
folder (a cache), naming the output, the input's field and the file.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path


class WriteFailed(OSError):
    """An output file could not be written (a full disk, a device error): the message names the file, says what the
    system or the netCDF library said and what became of the file; ``wecss`` exits with status 4 for it
    (``wecss.netcdf.write_failure`` makes it). ``errno`` is the system's code (EIO for the netCDF library's errors,
    which carry none) and ``filename`` the file."""

    def __init__(self, message: str, code: int, filename: str) -> None:
        super().__init__(message)
        self.errno, self.filename = code, filename

    def __str__(self) -> str:
        return str(self.args[0])


class OverwriteError(ValueError):
    """An output file of a run is one of its inputs; the message names both and the file."""


def refuse_overwrite(
    outputs: Mapping[str, str | os.PathLike[str]], inputs: Mapping[str, str | os.PathLike[str]]
) -> None:
    """Refuse outputs that are inputs.

    Parameters
    ----------
    outputs : mapping of label to path
        The files the run writes, under what they are ("result file", "partial result file", ...).
    inputs : mapping of label to path
        The files (or folders, such as a cache, inside which nothing may be written) the run reads, under the field
        that names them ("hydrodynamic database (device.hydro)", ...).

    Raises
    ------
    OverwriteError
        For the first output that resolves to an input file or lies inside an input folder.
    """
    known = {Path(path).resolve(): label for label, path in inputs.items()}
    folders = {path: label for path, label in known.items() if path.is_dir()}
    for label, path in outputs.items():
        resolved = Path(path).resolve()
        if resolved in known and resolved not in folders:
            raise OverwriteError(
                f"the {label} {str(path)!r} is the run's {known[resolved]} ({str(resolved)!r}); nothing was "
                "written: give another output name"
            )
        for folder, what in folders.items():
            if folder in resolved.parents:
                raise OverwriteError(
                    f"the {label} {str(path)!r} is inside the run's {what} ({str(folder)!r}); nothing was written: "
                    "give an output outside that folder"
                )
