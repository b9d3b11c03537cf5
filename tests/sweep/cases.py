"""The small sweep cases of the sweep tests, and the combined dataset without what differs between runs."""

from __future__ import annotations

import xarray as xr

# the frequency-domain solution: a case costs a compile and a few hundredths of a second
BASE = {
    "device": {"name": "m4-111"},
    "sea": {"kind": "jonswap", "height": 0.04, "period": 1.2, "duration": 30.0, "ramp": 0.0},
    "solver": {"method": "frequency", "dt": 0.01},
    "outputs": {"statistics_only": True, "variables": []},
}
TIMINGS = ["run_time", "compile_time"]


def statistics(ds: xr.Dataset) -> xr.Dataset:
    """The combined dataset without what differs between runs (timings, the run's counts)."""
    out = ds.drop_vars(TIMINGS)
    out.attrs = {k: v for k, v in ds.attrs.items() if k != "sweep_run"}
    return out
