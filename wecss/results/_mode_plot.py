"""The plot of a device's structural mode shapes (the Dataset of ``wecss.devices.structural_modes``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ._plot import _pyplot

_COLOURS = {"element": "tab:blue", "body": "tab:orange", "offset": "tab:orange", "pto": "tab:green"}


def plot_structural_modes(
    ds: xr.Dataset, path: str | Path | None = None, *, modes: int | list[int] = 6, scale: float | None = None
) -> Any:
    """The mode shapes in 3D, one panel per mode: the undeformed device in grey, the deformed one in colour (beam
    elements blue, rigid bodies orange, PTOs green), titled with the frequency and the strain-energy shares
    (in-plane / out-of-plane / torsion). Saved to ``path`` when given; returns the figure.

    Parameters
    ----------
    ds : xarray.Dataset
        From ``wecss.devices.structural_modes`` (``point_position``, ``point_displacement``, ``segment_points``).
    modes : int or list of int
        How many of the first modes, or which mode numbers (from 1).
    scale : float, optional
        Largest drawn displacement [m] (default: 15 % of the device's size).

    Raises
    ------
    ValueError
        If the dataset is not a modal analysis, or a mode number is not in it.
    """
    needed = ("point_position", "point_displacement", "segment_points", "frequency")
    missing = [n for n in needed if n not in ds]
    if missing:
        raise ValueError(f"not a structural modal analysis (wecss.devices.structural_modes): no {missing}")
    numbers = list(ds.mode.values[: int(modes)]) if isinstance(modes, int) else list(modes)
    unknown = [m for m in numbers if m not in ds.mode.values]
    if unknown or not numbers:
        raise ValueError(f"modes {unknown or numbers} are not in the dataset (modes {ds.mode.values.tolist()})")
    plt = _pyplot()
    positions = ds.point_position.values
    size = float(np.ptp(positions, axis=0).max()) or 1.0
    amplitude = 0.15 * size if scale is None else float(scale)
    cols = min(3, len(numbers))
    rows = int(np.ceil(len(numbers) / cols))
    fig = plt.figure(figsize=(4.2 * cols, 3.8 * rows))
    segments = ds.segment_points.values
    kinds = [str(k) for k in ds.segment_kind.values]
    for k, number in enumerate(numbers):
        ax = fig.add_subplot(rows, cols, k + 1, projection="3d")
        mode = ds.sel(mode=number)
        moved = positions + amplitude * mode.point_displacement.values
        for (a, b), kind in zip(segments, kinds, strict=True):
            ax.plot(*positions[[a, b]].T, color="0.75", lw=1.0)
            ax.plot(*moved[[a, b]].T, color=_COLOURS.get(kind, "k"), lw=1.6)
        share = mode.energy_share.sel(energy="strain").values
        text = "" if np.any(np.isnan(share)) else " / ".join(f"{100 * s:.0f}" for s in share) + " %"
        frequency = float(mode.frequency)
        ax.set_title(f"mode {number}: {frequency:.3g} Hz\nin / out of plane / torsion {text}", fontsize=8)
        span = positions.min(axis=0), positions.max(axis=0)
        centre, half = (span[0] + span[1]) / 2, max(size, 1e-9) / 2 + amplitude
        for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre, strict=True):
            setter(c - half, c + half)
        ax.set_xlabel("x [m]", fontsize=7)
        ax.set_ylabel("y [m]", fontsize=7)
        ax.set_zlabel("z [m]", fontsize=7)
        ax.tick_params(labelsize=6)
    medium = ds.attrs.get("medium", "")
    fig.suptitle(f"{ds.attrs.get('device', '')} structural modes ({medium}, {ds.attrs.get('model', '')} model)")
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig
