"""Result files: netCDF with atomic writes (temporary file, then rename)."""

from __future__ import annotations

import os
from pathlib import Path

import xarray as xr

from ..attributes import apply_attrs
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
    return upgrade_layout(read_netcdf(path))


OLD_PTO_DIMS = {"rotary_pto": "rotary", "linear_pto": "linear"}
"""The per-kind PTO dimensions of results written before the one ``pto`` dimension (issue 18)."""


def upgrade_layout(ds: xr.Dataset) -> xr.Dataset:
    """A result of the earlier layout (per-PTO variables on ``rotary_pto`` / ``linear_pto``) in today's: every
    such variable on ``pto``, NaN for the PTOs of the other kind, and the ``pto_kind`` coordinate. Results of
    today's layout are returned as they are."""
    old = [dim for dim in OLD_PTO_DIMS if dim in ds.dims]
    if not old or "pto" not in ds.coords:
        return ds
    names = [str(n) for n in ds.pto.values]
    kinds = {str(n): OLD_PTO_DIMS[dim] for dim in old for n in ds[dim].values}
    out = ds.copy()
    for name in list(ds.data_vars):
        dim = next((d for d in ds[name].dims if d in OLD_PTO_DIMS), None)
        if dim is not None:
            attrs = ds[name].attrs
            out[name] = ds[name].rename({dim: "pto"}).reindex(pto=names).assign_attrs(attrs)
    out = out.drop_vars(old).assign_coords(pto_kind=("pto", [kinds.get(n, "") for n in names]))
    return apply_attrs(out)  # today's long names (they say where a variable is NaN)
