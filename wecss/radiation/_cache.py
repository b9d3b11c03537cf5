"""A disk cache of radiation fits keyed by a hash of the hydrodynamic data and the fit settings.

Location: ``$WECSS_CACHE_DIR/radiation`` or ``~/.cache/wecss/radiation``. Each entry is a small netCDF file with
A, B, C and the fit report; writes are atomic, so concurrent runs never see half a file. Fits of the shipped
databases ship with the package (``wecss/data/radiation``, made by ``studies/generate_fits.py``) and are found
when the user's cache has no entry for the key.

The cache heals: an entry that cannot be read (truncated, damaged, another format, missing variables) is taken as
absent, with a :class:`CacheWarning`, so the fit is made again and replaces it; a cache folder that cannot be
written (read-only) leaves the fit uncached, with a warning, and the run goes on.
"""

from __future__ import annotations

import hashlib
import os
import warnings
from pathlib import Path

import numpy as np
import xarray as xr

from ..errors import WecssWarning
from ..hydro import HydroData
from ..netcdf import read_netcdf, write_netcdf
from ._statespace import RadiationStateSpace

_HASHED = ("omega", "radiation_damping", "added_mass", "added_mass_inf")


def cache_dir() -> Path:
    """Folder of the radiation cache (created on first use)."""
    root = os.environ.get("WECSS_CACHE_DIR")
    base = Path(root) if root else Path.home() / ".cache" / "wecss"
    return base / "radiation"


def cache_key(hydro: HydroData, *parts: object) -> str:
    """SHA-256 of the radiation data of ``hydro`` (values and DOF names) and the repr of ``parts``."""
    h = hashlib.sha256()
    ds = hydro.dataset
    for name in _HASHED:
        h.update(np.ascontiguousarray(ds[name].values, dtype=float).tobytes())
    h.update("|".join(hydro.dofs).encode())
    for part in parts:
        h.update(repr(part).encode())
    return h.hexdigest()[:32]


SHIPPED_FITS_DIR = Path(__file__).resolve().parent.parent / "data" / "radiation"
"""Folder of the fits shipped with the package."""


class CacheWarning(WecssWarning):
    """The radiation-fit cache could not be used as it is: an entry was unreadable (refitted and replaced) or the
    folder could not be written (the fit was not cached)."""


def store_fit(key: str, model: RadiationStateSpace, report: xr.Dataset, *, folder: Path | None = None) -> Path:
    """Write a fit to the cache (or to ``folder``, compressed); returns the file.

    Raises
    ------
    OSError
        If the folder cannot be created or written (:func:`cache_fit` turns this into a warning).
    """
    compress = folder is not None
    folder = cache_dir() if folder is None else folder
    folder.mkdir(parents=True, exist_ok=True)
    ds = report.copy()
    ds["A"] = (("state", "state_col"), model.A)
    ds["B"] = (("state", "dof"), model.B)
    ds["C"] = (("dof", "state"), model.C)
    ds = ds.assign_coords(dof=list(model.dofs))
    ds.attrs["model_method"] = model.method
    return write_netcdf(ds, folder / f"{key}.nc", compress=compress)


def cache_fit(key: str, model: RadiationStateSpace, report: xr.Dataset) -> Path | None:
    """Store a fit in the user's cache (:func:`store_fit`); a folder that cannot be written leaves it uncached with a
    :class:`CacheWarning` saying so (returns None)."""
    try:
        return store_fit(key, model, report)
    except OSError as err:
        warnings.warn(
            f"the radiation-fit cache folder {str(cache_dir())!r} cannot be written ({err.strerror or err}): the fit "
            "was made for this run and not cached (set WECSS_CACHE_DIR to a writable folder to keep fits)",
            CacheWarning,
            stacklevel=2,
        )
        return None


def load_cached_fit(key: str) -> tuple[RadiationStateSpace, xr.Dataset] | None:
    """A cached fit (the user's cache first, then the shipped fits), or None: also for an entry that cannot be read
    (with a :class:`CacheWarning`; the fit made instead replaces it in the user's cache)."""
    for folder in (cache_dir(), SHIPPED_FITS_DIR):
        path = folder / f"{key}.nc"
        if not path.is_file():
            continue
        try:
            return _read_fit(path)
        except (ValueError, KeyError, OSError) as err:
            warnings.warn(
                f"the radiation-fit cache entry {str(path)!r} cannot be read ({err}); the fit is made again and "
                "replaces it",
                CacheWarning,
                stacklevel=2,
            )
            return None
    return None


def _read_fit(path: Path) -> tuple[RadiationStateSpace, xr.Dataset]:
    """The fit stored in ``path``.

    Raises
    ------
    NetCDFFileError, KeyError, ValueError
        If the file is not a readable netCDF file or lacks the fit's variables or attributes.
    """
    ds = read_netcdf(path)
    model = RadiationStateSpace(
        np.asarray(ds["A"].values).reshape(ds.sizes.get("state", 0), ds.sizes.get("state_col", 0)),
        np.asarray(ds["B"].values).reshape(ds.sizes.get("state", 0), ds.sizes["dof"]),
        np.asarray(ds["C"].values).reshape(ds.sizes["dof"], ds.sizes.get("state", 0)),
        tuple(str(d) for d in ds.dof.values),
        str(ds.attrs["model_method"]),
    )
    report = ds.drop_vars(["A", "B", "C", "dof"])
    report.attrs = {k: v for k, v in ds.attrs.items() if k != "model_method"}
    return model, report
