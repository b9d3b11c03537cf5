"""The fatigue life map of a body's members (the Dataset of ``StressFieldRecorder.result``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..structure import Frame
from ._plot import _pyplot

PLANES = {"xz": (0, 2), "xy": (0, 1), "yz": (1, 2)}
"""The planes a member can be drawn in, by the body axes they keep."""


def station_lives(ds: xr.Dataset) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Per member, its stations [m] (increasing) and the smallest life over each station's points [year]."""
    out = {}
    members = ds.member.values
    for member in dict.fromkeys(str(m) for m in members):
        mine = members == member
        stations = ds.station.values[mine]
        lives = ds.life_years.values[mine]
        unique = np.unique(stations)
        out[member] = (unique, np.array([lives[stations == s].min() for s in unique]))
    return out


def _positions(frame: Frame, member: str, stations: np.ndarray) -> np.ndarray:
    """Body-axes positions of a member's stations (n, 3) [m], along its elements.

    Raises
    ------
    ValueError
        If the frame has no such member.
    """
    elements = frame.members().get(member)
    if not elements:
        raise ValueError(f"member {member!r} of the dataset is not in the frame (members {sorted(frame.members())})")
    out = np.zeros((stations.size, 3))
    for k, s in enumerate(stations):
        e = next((e for e in elements if s <= e.station + e.length * (1 + 1e-9)), elements[-1])
        xi = np.clip((s - e.station) / e.length, 0.0, 1.0)
        out[k] = (1 - xi) * np.asarray(e.start) + xi * np.asarray(e.end)
    return out


def plot_life_map(
    ds: xr.Dataset, path: str | Path | None = None, *, frame: Frame | None = None, plane: str = "xz"
) -> Any:
    """The members coloured by fatigue life: at each station the smallest life over its section's points (log
    colour scale, shortest life darkest), the point of shortest life marked with its name and life. Saved to
    ``path`` when given; returns the figure.

    Parameters
    ----------
    ds : xarray.Dataset
        From :meth:`StressFieldRecorder.result` (``life_years``, ``member``, ``station`` on dim ``point``).
    frame : wecss.structure.Frame, optional
        The body's frame (``FlexibleBody.frame``): members drawn where they are, in ``plane`` of the body axes.
        Without it each member is a row, its station along the horizontal axis.
    plane : {"xz", "xy", "yz"}
        The body axes the drawing keeps (with ``frame``).

    Raises
    ------
    ValueError
        If the dataset has no life map, the plane is unknown, or a member is not in the frame.
    """
    missing = [n for n in ("life_years", "member", "station") if n not in ds.variables]
    if missing:
        raise ValueError(f"not a stress field (StressFieldRecorder.result): no {missing}")
    if plane not in PLANES:
        raise ValueError(f"plane must be one of {sorted(PLANES)}, got {plane!r}")
    if ds.sizes.get("point", 0) == 0:
        raise ValueError("nothing to plot: the stress field has no points")
    from matplotlib.collections import LineCollection
    from matplotlib.colors import LogNorm

    plt = _pyplot()
    lives = station_lives(ds)
    life = ds.life_years.values
    finite = life[np.isfinite(life) & (life > 0)]
    low, high = (finite.min(), finite.max()) if finite.size else (1.0, 10.0)
    norm = LogNorm(vmin=low, vmax=high if high > low else low * 10)
    cmap = plt.get_cmap("viridis").with_extremes(over="0.7")  # grey: no damage counted, infinite life
    fig, ax = plt.subplots(figsize=(8, 3.2 + 0.3 * len(lives)))
    axes = PLANES[plane]
    where: dict[str, np.ndarray] = {}
    for row, (member, (stations, member_life)) in enumerate(lives.items()):
        if frame is not None:
            xy = _positions(frame, member, stations)[:, axes]
        else:
            xy = np.column_stack([stations, np.full(stations.size, float(row))])
        where[member] = xy
        shown = np.where(np.isfinite(member_life), member_life, np.inf)
        # each segment takes the shorter life of its two stations; the stations are dots of their own life
        segments = np.stack([xy[:-1], xy[1:]], axis=1)
        if len(segments):
            lines = LineCollection(list(segments), cmap=cmap, norm=norm, linewidths=6)
            lines.set_array(np.minimum(np.minimum(shown[:-1], shown[1:]), 1e300))
            ax.add_collection(lines)
        ax.scatter(*xy.T, c=np.minimum(shown, 1e300), cmap=cmap, norm=norm, s=22, edgecolors="k", linewidths=0.4,
                   zorder=3)  # fmt: skip
        if frame is None:
            ax.annotate(member, xy[0], xytext=(-6, 0), textcoords="offset points", ha="right", va="center")
    worst = int(np.argmin(life))
    if np.isfinite(life[worst]):
        member = str(ds.member.values[worst])
        stations = lives[member][0]
        spot = where[member][int(np.argmin(np.abs(stations - float(ds.station.values[worst]))))]
        ax.plot(*spot, marker="*", ms=16, color="red", mec="k", zorder=4)
        right = spot[0] > np.mean([xy[:, 0].mean() for xy in where.values()])
        ax.annotate(f"{ds.point.values[worst]}: {life[worst]:.3g} years", spot, xytext=(-8 if right else 8, 10),
                    textcoords="offset points", fontsize=8, color="red", ha="right" if right else "left")  # fmt: skip
    else:
        ax.set_title("no damage counted: every life is infinite (grey)", fontsize=9)
    colourbar = fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, extend="max")
    colourbar.set_label("fatigue life, shortest over the section [years]")
    ax.autoscale_view()
    if frame is not None:
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(f"{plane[0]} [m] (body axes)")
        ax.set_ylabel(f"{plane[1]} [m] (body axes)")
    else:
        ax.set_xlabel("station along the member [m]")
        ax.set_yticks([])
        ax.margins(x=0.08, y=0.3)
    curve = ds.attrs.get("sn_curve", "")
    duration = ds.attrs.get("duration")
    record = f", record of {duration:.4g} s" if isinstance(duration, int | float) else ""
    fig.suptitle(f"fatigue life map (S-N curve {curve}{record})", fontsize=10)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig
