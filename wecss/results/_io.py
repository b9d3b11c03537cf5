"""Result files: netCDF with atomic writes (temporary file, then rename)."""

from __future__ import annotations

import os
from pathlib import Path

import xarray as xr

from ..netcdf import read_netcdf, write_netcdf


def save(ds: xr.Dataset, path: str | os.PathLike[str]) -> Path:
    """Write a result atomically [netCDF4]; returns the path."""
    return write_netcdf(ds, path)


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
