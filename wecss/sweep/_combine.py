"""The combined dataset of a sweep: the statistics of every case, with the sweep's axes as dimensions (grid) or along
``case`` (list), and each case's status and error."""

from __future__ import annotations

import json
import math
from collections.abc import Hashable
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..results import capture_width_ratio, open_result
from ._files import case_paths, case_status
from ._spec import Case, Sweep

STATUSES = ("done", "failed", "pending")


def case_statistics(ds: xr.Dataset) -> xr.Dataset:
    """Statistics of one result: mean power per PTO and total [W], CWR (both conventions where defined), RMS PTO
    angles [rad] and strokes [m], run time [s]."""
    out = xr.Dataset()
    if "mean_pto_power" in ds:
        power = ds.mean_pto_power
    elif "pto_power" in ds:
        from ..results import mean_power

        power = mean_power(ds)
    else:
        power = None
    if power is not None:
        out["mean_pto_power"] = power.astype(float)
        out["total_power"] = power.sum("pto")
        out["total_power"].attrs = {"long_name": "total mean absorbed power", "units": "W"}
    if power is not None and "wave_energy_flux" in ds.attrs:
        cwr = capture_width_ratio(ds)
        out["cwr"] = xr.DataArray(float(cwr), attrs={"long_name": "capture width ratio (energy period)", "units": "1"})
        try:
            paper = float(capture_width_ratio(ds, convention="paper"))
        except ValueError:
            paper = math.nan
        out["cwr_paper"] = xr.DataArray(
            paper, attrs={"long_name": "capture width ratio (the M4 paper's Te = 0.84 or 0.78 Tp)", "units": "1"}
        )
    for name in ("rms_pto_angle", "rms_pto_displacement"):
        if name in ds:
            out[name] = ds[name].astype(float)
    out["run_time"] = xr.DataArray(float(ds.attrs.get("run_time_s", math.nan)), attrs={"units": "s"})
    out["compile_time"] = xr.DataArray(float(ds.attrs.get("sweep_compile_time_s", math.nan)), attrs={"units": "s"})
    return out


def _case_row(folder: Path, case: Case) -> xr.Dataset:
    status = case_status(folder, case)
    result, failure = case_paths(folder, case)
    row = case_statistics(open_result(result)) if status == "done" else xr.Dataset()
    error = _failure_error(failure) if status == "failed" else ""
    row["status"] = xr.DataArray(status)
    row["error"] = xr.DataArray(error)
    return row


def _failure_error(failure: Path) -> str:
    """The error a failed case's record holds, or what is wrong with the record (damaged: a crash or a full disk
    while it was written)."""
    try:
        return str(json.loads(failure.read_text(encoding="utf-8"))["error"])
    except (json.JSONDecodeError, UnicodeDecodeError, KeyError, TypeError) as err:
        return f"the failure record {str(failure)!r} is unreadable ({type(err).__name__}: {err}); run the case again"


def combine(sweep: Sweep, folder: str | Path) -> xr.Dataset:
    """The combined dataset of the cases found in ``folder`` (pending and failed cases hold NaN statistics).

    Grid sweeps have one dimension per axis, named by its scene path (``sea.period``), with the values as
    coordinates; list sweeps have the dimension ``case`` with one coordinate per axis. ``status`` says
    "done", "failed" or "pending" and ``error`` holds a failed case's error.
    """
    path = Path(folder)
    rows = [_case_row(path, case) for case in sweep.cases]
    stacked = xr.concat(rows, dim="case", join="outer", data_vars="all", coords="minimal", compat="override")
    for name in ("status", "error"):
        stacked[name] = stacked[name].astype(str)
    paths = [p for p, _ in sweep.axes]
    if sweep.mode == "list":
        stacked = stacked.assign_coords({p: ("case", list(v)) for p, v in sweep.axes})
        stacked = stacked.assign_coords(case=[c.name for c in sweep.cases])
        out = stacked
    else:
        shape = sweep.shape
        data_vars: dict[Hashable, Any] = {}
        for key, da in stacked.data_vars.items():
            rest = da.dims[1:]
            values = np.asarray(da.values).reshape(shape + da.shape[1:])
            data_vars[key] = ((*paths, *rest), values, da.attrs)
        coords: dict[Hashable, Any] = {p: list(v) for p, v in sweep.axes}
        coords.update({d: stacked[d].values for d in stacked.dims if d != "case" and d in stacked.coords})
        out = xr.Dataset(data_vars, coords=coords)
    counts = {s: int((out.status == s).sum()) for s in STATUSES}
    out.attrs = {
        "title": f"wecss sweep {sweep.name}",
        "sweep_mode": sweep.mode,
        "sweep_axes": json.dumps([[p, list(v)] for p, v in sweep.axes]),
        "base_scene": json.dumps(sweep.base, sort_keys=True),
        **{f"cases_{s}": n for s, n in counts.items()},
    }
    return out
