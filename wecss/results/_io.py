"""Result files: netCDF with atomic writes (temporary file, then rename)."""

from __future__ import annotations

import os
from pathlib import Path

import xarray as xr

from ..netcdf import read_netcdf, write_netcdf


def save(ds: xr.Dataset, path: str | os.PathLike[str], *, compress: int = 0, float32: bool = False) -> Path:
    """Write a result atomically [netCDF4]; returns the path.

    Parameters
    ----------
    compress : int
        zlib level of every variable, 0 (none, the default) to 9 (smallest); lossless.
    float32 : bool
        Store the floating-point variables in single precision (half the size; values within a relative 6e-8;
        coordinates such as time keep double precision).

    Raises
    ------
    ValueError
        For a ``compress`` level outside 0-9.
    """
    return write_netcdf(ds, path, compress=compress, float32=float32)


def open_result(path: str | os.PathLike[str]) -> xr.Dataset:
    """Read a result written by :func:`save` (loaded into memory; the file is closed).

    Raises
    ------
    FileNotFoundError
        If there is no file at ``path``.
    """
    if not Path(path).is_file():
        raise FileNotFoundError(f"no result file at {str(path)!r}")
    return read_netcdf(path)
