"""The plot of an annual energy (``annual_energy``): the power matrix in colours with the scatter diagram's
occurrence as contours, and the energy per bin in colours with its value written in the bin."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ._plot import _pyplot
from ._summary_plot import scaled_unit

ENERGY_UNITS = ((3.6e9, "MWh"), (3.6e6, "kWh"), (3.6e3, "Wh"))
"""Units of energy per year, the largest whose value is at least 1 chosen [J per unit]."""


def energy_unit(joules: float) -> tuple[float, str]:
    """[J per unit] and the name of the unit (MWh, kWh, Wh) that keeps ``joules`` at 1 or more (Wh below)."""
    return next(((j, u) for j, u in ENERGY_UNITS if abs(joules) >= j), ENERGY_UNITS[-1])


def _outlined() -> list[Any]:
    from matplotlib import patheffects

    return [patheffects.withStroke(linewidth=2, foreground="w")]


def _label(name: str) -> str:
    return f"{name} [s]" if name.lower().startswith("t") else f"{name} [m]"


def plot_annual_energy(result: xr.Dataset, path: str | Path | None = None) -> Any:
    """Two panels: the power matrix as colours (W, or mW or kW by its size) with the scatter diagram's hours per
    year as contour lines; the energy per bin as colours (MWh, kWh or Wh per year by its size) with its value
    written in each bin of occurrence ("?" where the power is unknown). The title gives the annual energy and the
    share of the year covered (and unknown). Saved to ``path`` when given; returns the figure."""
    plt = _pyplot()
    dims = [str(d) for d in result.energy.dims]
    matrix = result.power_matrix
    mdims = [str(d) for d in matrix.dims]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    factor, unit = scaled_unit(matrix.values, "W")
    mesh = left.pcolormesh(matrix[mdims[1]], matrix[mdims[0]], matrix.values * factor, shading="nearest")
    fig.colorbar(mesh, ax=left, label=f"power matrix [{unit}]")
    hours = result.hours.values
    if np.count_nonzero(hours) > 1 and min(hours.shape) > 1:
        lines = left.contour(result[dims[1]], result[dims[0]], hours, colors="w", linewidths=0.8)
        left.clabel(lines, fontsize=7, fmt="%.0f h")
    left.set_title("power matrix, occurrence [h/year] as contours", fontsize=9)
    joules = result.energy.values
    per_unit, unit = energy_unit(float(np.nanmax(np.abs(joules))) if np.any(np.isfinite(joules)) else 0.0)
    energy = joules / per_unit
    mesh = right.pcolormesh(result[dims[1]], result[dims[0]], energy, shading="nearest", cmap="magma_r")
    fig.colorbar(mesh, ax=right, label=f"energy per bin [{unit}/year]")
    for i, hs in enumerate(result[dims[0]].values):
        for j, tp in enumerate(result[dims[1]].values):
            if hours[i, j] <= 0:
                continue
            text = f"{energy[i, j]:.3g}" if np.isfinite(energy[i, j]) else "?"
            right.text(tp, hs, text, ha="center", va="center", fontsize=7, path_effects=_outlined())
    right.set_title(f"energy per bin [{unit}/year] (? : power unknown)", fontsize=9)
    for ax, names in ((left, mdims), (right, dims)):
        ax.set_xlabel(_label(names[1].removesuffix("_matrix")))
        ax.set_ylabel(_label(names[0].removesuffix("_matrix")))
    total_per_unit, total_unit = energy_unit(float(result.annual_energy))
    fig.suptitle(
        f"annual energy {float(result.annual_energy) / total_per_unit:.4g} {total_unit}/year; "
        f"{float(result.covered_share) * 100:.3g} % of the year covered"
        + (f", {float(result.unknown_share) * 100:.3g} % unknown" if float(result.unknown_share) > 0 else ""),
        fontsize=10,
    )
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig
