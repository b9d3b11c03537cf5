"""The plot of a sweep's combined dataset (``wecss.sweep``): a statistic over one axis as a line, over two as a
heat map with the values written in the cells; failed and pending cases marked."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ._plot import _pyplot

AXIS_UNITS = {"sea.height": "m", "sea.period": "s", "sea.gamma": "1", "sea.duration": "s", "solver.dt": "s"}
"""Units of the sweep axes most used (an axis's ``units`` attribute, if any, comes first)."""

MARKS = {"failed": ("failed", "tab:red"), "pending": ("pending", "tab:gray")}


def _label(da: xr.DataArray, name: str) -> str:
    """``name [units]`` of a dimension of ``da`` or (``name`` not a coordinate) of ``da`` itself."""
    units = (da[name] if name in da.coords else da).attrs.get("units") or AXIS_UNITS.get(name)
    return f"{name} [{units}]" if units else name


def _axis_value(da: xr.DataArray, name: str, value: Any) -> Any:
    """The value of axis ``name`` that ``value`` names: itself, or for a number the axis's value within 1e-9 of it
    relative (an axis made by linspace holds 0.30000000000000004 where the user types 0.3)."""
    if name not in da.coords:
        return value
    values = da[name].values
    if value in values.tolist():
        return value
    if np.issubdtype(values.dtype, np.number) and isinstance(value, int | float):
        close = np.isclose(values, value, rtol=1e-9, atol=0.0)
        if np.count_nonzero(close) == 1:
            return values[close][0]
    raise ValueError(f"select {name}={value!r}: not a value of that axis; accepted: {values.tolist()}")


def _select(ds: xr.Dataset, variable: str, select: dict[str, Any] | None) -> tuple[xr.DataArray, xr.DataArray]:
    if variable not in ds:
        numeric = [str(n) for n in ds.data_vars if np.issubdtype(ds[n].dtype, np.number)]
        raise ValueError(f"the combined dataset has no {variable!r}; accepted: {numeric}")
    da = ds[variable]
    status = ds["status"] if "status" in ds else xr.full_like(da, "done", dtype=object)
    for name, value in (select or {}).items():
        if name not in da.dims:
            raise ValueError(f"select names {name!r}, not a dimension of {variable} {da.dims}")
        value = _axis_value(da, name, value)
        da, status = da.sel({name: value}), status.sel({name: value}) if name in status.dims else status
    single = [d for d in da.dims if da.sizes[d] == 1]  # an axis of one value needs no choice
    da = da.squeeze(single)
    status = status.squeeze([d for d in single if d in status.dims])
    if da.ndim > 2:
        listed = {str(d): da[d].values.tolist() if d in da.coords else da.sizes[d] for d in da.dims}
        raise ValueError(
            f"{variable} has {da.ndim} dimensions {listed}: a plot shows one or two; give select={{dim: value}} "
            "for the others (wecss plot: --select dim=value)"
        )
    if da.ndim == 0:
        raise ValueError(f"{variable} has no dimension left to plot against (select took them all)")
    return da, status.broadcast_like(da)


def plot_sweep(
    ds: xr.Dataset,
    variable: str = "total_power",
    *,
    select: dict[str, Any] | None = None,
    path: str | Path | None = None,
) -> Any:
    """A statistic of a sweep's combined dataset against its axes: one dimension as a line with markers, two as
    a heat map (the first dimension along y) with each value written in its cell; failed and pending cases (NaN
    statistics) marked with their status. Dimensions of one value are dropped; more need ``select`` (dimension to
    value) for all but two. Axis and colour-bar labels carry units. Saved to ``path`` when given; returns the figure.

    Raises
    ------
    ValueError
        For an unknown variable, more than two dimensions left, or a ``select`` naming no dimension.
    """
    plt = _pyplot()
    da, status = _select(ds, variable, select)
    values = np.asarray(da.values, dtype=float)
    fig, ax = plt.subplots(figsize=(7, 5) if da.ndim == 2 else (7, 4))
    dims = [str(d) for d in da.dims]
    ticks = [da[d].values if d in da.coords else np.arange(da.sizes[d]) for d in dims]
    if da.ndim == 1:
        x = np.arange(values.size)
        ax.plot(x, values, "o-", color="k")
        ax.set_xticks(x, [f"{v:g}" if isinstance(v, float) else str(v) for v in ticks[0]], rotation=0)
        ax.set_xlabel(_label(da, dims[0]) if dims[0] in da.coords else dims[0])
        ax.set_ylabel(_label(da, variable))
        low = np.nanmin(values) if np.any(np.isfinite(values)) else 0.0
        for k, s in enumerate(np.asarray(status.values).astype(str)):
            if s in MARKS:
                ax.plot(k, low, "x", color=MARKS[s][1], ms=10, mew=2)
                ax.annotate(MARKS[s][0], (k, low), textcoords="offset points", xytext=(0, 8), ha="center", fontsize=8)
        ax.grid(alpha=0.3)
    else:
        cmap = plt.get_cmap("viridis").with_extremes(bad="0.85")
        image = ax.imshow(values, origin="lower", aspect="auto", cmap=cmap, interpolation="nearest")
        fig.colorbar(image, ax=ax, label=_label(da, variable))
        ax.set_xticks(range(len(ticks[1])), [f"{v:g}" if isinstance(v, float) else str(v) for v in ticks[1]])
        ax.set_yticks(range(len(ticks[0])), [f"{v:g}" if isinstance(v, float) else str(v) for v in ticks[0]])
        ax.set_xlabel(_label(da, dims[1]) if dims[1] in da.coords else dims[1])
        ax.set_ylabel(_label(da, dims[0]) if dims[0] in da.coords else dims[0])
        statuses = np.asarray(status.values).astype(str)
        from matplotlib import patheffects

        outline = [patheffects.withStroke(linewidth=2, foreground="w")]
        for i in range(values.shape[0]):
            for j in range(values.shape[1]):
                if statuses[i, j] in MARKS:
                    text, colour = MARKS[statuses[i, j]]
                    ax.text(j, i, text, ha="center", va="center", fontsize=8, color=colour, fontweight="bold")
                elif np.isfinite(values[i, j]):
                    ax.text(j, i, f"{values[i, j]:.3g}", ha="center", va="center", fontsize=8, path_effects=outline)
                else:
                    ax.text(j, i, "NaN", ha="center", va="center", fontsize=8, color="k")
    title = ds.attrs.get("title", "wecss sweep")
    if select:
        title += " (" + ", ".join(f"{k}={v}" for k, v in select.items()) + ")"
    ax.set_title(f"{title}: {da.attrs.get('long_name', variable)}", fontsize=9)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig
