"""The plot of an annual energy (``annual_energy``): the power matrix in colours with the scatter diagram's
occurrence as contours, and the energy per bin in colours with its number in MWh."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ._annual_energy import JOULES_PER_MWH
from ._plot import _pyplot


def _label(name: str) -> str:
    return f"{name} [s]" if name.lower().startswith("t") else f"{name} [m]"


def plot_annual_energy(result: xr.Dataset, path: str | Path | None = None) -> Any:
    """Two panels: the power matrix [kW] as colours with the scatter diagram's hours per year as contour lines, and
    the energy per bin [MWh] as colours with the value written in each bin (bins of unknown power hatched). The
    title gives the annual energy and the share of the year covered. Saved to ``path`` when given; returns the
    figure."""
    plt = _pyplot()
    dims = [str(d) for d in result.energy.dims]
    matrix = result.power_matrix
    mdims = [str(d) for d in matrix.dims]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    mesh = left.pcolormesh(matrix[mdims[1]], matrix[mdims[0]], matrix.values / 1e3, shading="nearest", cmap="viridis")
    fig.colorbar(mesh, ax=left, label="power matrix [kW]")
    hours = result.hours.values
    if np.count_nonzero(hours) > 1 and min(hours.shape) > 1:
        lines = left.contour(result[dims[1]], result[dims[0]], hours, colors="w", linewidths=0.8)
        left.clabel(lines, fontsize=7, fmt="%.0f h")
    left.set_title("power matrix, occurrence [h/year] as contours", fontsize=9)
    energy = result.energy.values / JOULES_PER_MWH
    mesh = right.pcolormesh(result[dims[1]], result[dims[0]], energy, shading="nearest", cmap="magma_r")
    fig.colorbar(mesh, ax=right, label="energy per bin [MWh/year]")
    for i, hs in enumerate(result[dims[0]].values):
        for j, tp in enumerate(result[dims[1]].values):
            if hours[i, j] <= 0:
                continue
            text = f"{energy[i, j]:.3g}" if np.isfinite(energy[i, j]) else "?"
            right.text(tp, hs, text, ha="center", va="center", fontsize=6)
    right.set_title("energy per bin (? : power unknown)", fontsize=9)
    for ax, names in ((left, mdims), (right, dims)):
        ax.set_xlabel(_label(names[1].removesuffix("_matrix")))
        ax.set_ylabel(_label(names[0].removesuffix("_matrix")))
    fig.suptitle(
        f"annual energy {float(result.annual_energy_mwh):.4g} MWh/year; "
        f"{float(result.covered_share) * 100:.3g} % of the year covered"
        + (f", {float(result.unknown_share) * 100:.3g} % unknown" if float(result.unknown_share) > 0 else ""),
        fontsize=10,
    )
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig
