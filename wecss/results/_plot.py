"""Plots of results: a run's summary, power and CWR against period, RAOs (matplotlib, imported lazily)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr


def _pyplot() -> Any:
    import matplotlib

    if matplotlib.get_backend().lower() not in ("agg", "pdf", "svg") and not _has_display():
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _has_display() -> bool:
    import os

    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def refuse_all_nan(ds: xr.Dataset, names: tuple[str, ...]) -> None:
    """Refuse to plot a result whose variable among ``names`` is NaN at every value (a picture of nothing that
    looks like a result).

    Raises
    ------
    ValueError
        Naming the variable and its number of values.
    """
    for name in names:
        if name in ds and ds[name].size and bool(np.all(np.isnan(ds[name].values))):
            raise ValueError(
                f"nothing to plot: {name} is NaN at all of its {ds[name].size} values; accepted: a result with "
                "numbers in it (a run that diverged, or a result edited by hand?)"
            )


def plot_timeseries(ds: xr.Dataset, path: str | Path | None = None) -> Any:
    """Wave elevation, PTO strokes and PTO power against time; saved to ``path`` when given. Returns the figure."""
    plt = _pyplot()
    panels = [v for v in ("wave_elevation", "pto_angle", "pto_displacement", "pto_power") if v in ds]
    if not panels:
        raise ValueError("nothing to plot: the dataset has no wave_elevation, PTO or power time series")
    refuse_all_nan(ds, tuple(panels))
    fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(9, 2.2 * len(panels) + 0.6), squeeze=False)
    for ax, name in zip(axes[:, 0], panels, strict=True):
        da = ds[name]
        if da.ndim == 1:
            ax.plot(ds.time, da, lw=0.8, color="k")
        else:
            other = next(d for d in da.dims if d != "time")
            for label in da[other].values:
                ax.plot(ds.time, da.sel({other: label}), lw=0.8, label=str(label))
            if da.sizes[other] <= 8:
                ax.legend(fontsize=7, ncol=4, loc="upper left")
        ax.set_ylabel(f"{name}\n[{da.attrs.get('units', '')}]", fontsize=8)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    fig.suptitle(ds.attrs.get("title", "wecss result"), fontsize=10)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig


def plot_power_curve(
    periods: np.ndarray, values: np.ndarray, *, ylabel: str, path: str | Path | None = None, label=None
) -> Any:
    """A metric (mean power, CWR, RMS angle) against the peak period [s]."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(periods, values, "o-", label=label)
    ax.set_xlabel("peak period Tp [s]")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    if label:
        ax.legend()
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig


def plot_rao(*raos: xr.DataArray, labels=None, path: str | Path | None = None) -> Any:
    """RAOs against angular frequency (one line per PTO and per RAO given)."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    for k, rao in enumerate(raos):
        other = [d for d in rao.dims if d != "omega"]
        lines = [rao] if not other else [rao.isel({other[0]: i}) for i in range(rao.sizes[other[0]])]
        for line in lines:
            tag = labels[k] if labels else rao.attrs.get("long_name", "RAO")
            ax.plot(line.omega, line, label=tag, marker="o" if line.omega.size < 40 else None)
    ax.set_xlabel("omega [rad/s]")
    ax.set_ylabel("RAO")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig
