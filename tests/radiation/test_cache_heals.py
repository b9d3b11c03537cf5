"""The radiation-fit cache heals (issue 31, data safety): a corrupt, truncated or incomplete entry is refitted and
replaced with a warning instead of refusing the run, and a read-only cache folder runs without caching and says
so."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from wecss.radiation import CacheWarning, FitSettings, fit_cache_key, fit_radiation, load_cached_fit

from .analytic import analytic_hydro


@pytest.fixture(scope="module")
def hydro():
    return analytic_hydro(np.arange(0.2, 30.0001, 0.2))  # coarse: a fit in a fraction of a second


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.setenv("WECSS_CACHE_DIR", str(tmp_path))
    return tmp_path / "radiation"


def _damage(entry: Path, how: str) -> None:
    if how == "truncated":
        entry.write_bytes(entry.read_bytes()[: entry.stat().st_size // 2])
    elif how == "empty":
        entry.write_bytes(b"")
    elif how == "not netcdf":
        entry.write_text("not a fit")
    else:  # a readable netCDF file without the fit's variables
        xr.Dataset({"x": ("a", np.arange(3.0))}).to_netcdf(entry)


@pytest.mark.parametrize("how", ["truncated", "empty", "not netcdf", "no fit in it"])
def test_a_corrupt_cache_entry_is_refitted_and_replaced_with_a_warning(hydro, cache, how) -> None:
    first = fit_radiation(hydro, cache=True)
    (entry,) = cache.glob("*.nc")
    _damage(entry, how)
    with pytest.warns(CacheWarning, match=r"cache entry .* cannot be read .* made again and replaces it"):
        healed = fit_radiation(hydro, cache=True)
    np.testing.assert_array_equal(healed.model.A, first.model.A)
    key = fit_cache_key(hydro, FitSettings())
    hit = load_cached_fit(key)  # replaced: read again without a warning
    assert hit is not None
    np.testing.assert_array_equal(hit[0].C, first.model.C)


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="file permissions (root writes anywhere)")
def test_a_read_only_cache_folder_runs_without_caching_and_says_so(hydro, cache) -> None:
    cache.mkdir(parents=True)
    cache.chmod(0o500)
    try:
        with pytest.warns(CacheWarning, match="cannot be written .* not cached"):
            fit = fit_radiation(hydro, cache=True)
    finally:
        cache.chmod(0o700)
    assert fit.model.n_states > 0 and not list(cache.iterdir())


def test_a_cache_folder_that_refuses_writes_runs_without_caching_and_says_so(hydro, cache, monkeypatch) -> None:
    def read_only(*args, **kwargs):  # type: ignore[no-untyped-def]
        raise PermissionError(13, "Permission denied", str(cache))

    monkeypatch.setattr("wecss.radiation._cache.write_netcdf", read_only)
    with pytest.warns(CacheWarning, match=r"cannot be written \(Permission denied\).* not cached"):
        fit = fit_radiation(hydro, cache=True)
    assert fit.model.n_states > 0 and not list(cache.glob("*.nc"))
