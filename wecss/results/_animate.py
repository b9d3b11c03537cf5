"""An animation of a run's bodies: a side view (x-z) and a top view (x-y) of each body's centre of mass with a bar
along its body x axis, from the result's poses (``body_position``, ``body_rotation``), written as GIF (Pillow) or
MP4 (ffmpeg)."""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Any, TextIO

import numpy as np
import xarray as xr

from ._plot import _pyplot

MAX_FRAMES = 150
"""Frames drawn with the default stride (every ``ceil(steps / MAX_FRAMES)``-th saved step)."""

COLOURS = ("#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf")
"""One colour per body (cycled)."""

PROGRESS_AFTER_S = 3.0
"""A progress line is printed once writing has taken this long [s]."""

POSES = ("body_position", "body_rotation")


def rotation_matrices(rotvec: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of rotation vectors (..., 3) [rad] (Rodrigues' formula)."""
    theta = np.linalg.norm(rotvec, axis=-1)[..., None, None]
    safe = np.where(theta > 0, theta, 1.0)
    k = rotvec / safe[..., 0]
    kx = np.zeros((*rotvec.shape[:-1], 3, 3))
    kx[..., 0, 1], kx[..., 0, 2], kx[..., 1, 2] = -k[..., 2], k[..., 1], -k[..., 0]
    kx[..., 1, 0], kx[..., 2, 0], kx[..., 2, 1] = k[..., 2], -k[..., 1], k[..., 0]
    return np.eye(3) + np.sin(theta) * kx + (1 - np.cos(theta)) * (kx @ kx)


def _writer(path: Path, fps: int) -> Any:
    from matplotlib import animation

    suffix = path.suffix.lower()
    if suffix == ".gif":
        return animation.PillowWriter(fps=fps)
    if suffix == ".mp4":
        if not animation.writers.is_available("ffmpeg"):
            raise ValueError(
                f"writing {str(path)!r} (MP4) needs ffmpeg on the PATH, and there is none; install ffmpeg or "
                "write a GIF (.gif)"
            )
        return animation.FFMpegWriter(fps=fps)
    raise ValueError(f"the animation file must end in .gif or .mp4; got {str(path)!r}")


def check_animation(ds: xr.Dataset, *, stride: int | None = None, fps: int = 20) -> int:
    """Refuse, before any drawing, a result without poses or a bad ``stride`` / ``fps``; returns the stride.

    Raises
    ------
    ValueError
        Naming the missing variables and how to ask for them, or the bad value and what is accepted.
    """
    missing = [name for name in POSES if name not in ds]
    if missing or "time" not in ds.dims:
        raise ValueError(
            f"the result has no body poses ({', '.join(missing) or 'time'} missing): run the scene with the "
            '\'poses\' output group, e.g. [outputs] variables = ["motion", "pto", "elevation", "poses"] '
            "(it is among the defaults) and statistics_only = false"
        )
    if isinstance(fps, bool) or not isinstance(fps, (int, np.integer)) or fps < 1:
        raise ValueError(f"fps must be a whole number of frames per second >= 1; got {fps!r}")
    steps = ds.sizes["time"]
    if stride is None:
        return max(1, math.ceil(steps / MAX_FRAMES))
    if isinstance(stride, bool) or not isinstance(stride, (int, np.integer)) or stride < 1:
        raise ValueError(f"stride must be a whole number of saved steps >= 1; got {stride!r}")
    if stride >= steps and steps > 1:
        raise ValueError(f"stride {stride} leaves one frame of the {steps} saved steps; accepted: below {steps}")
    return int(stride)


def animate(
    ds: xr.Dataset,
    path: str | Path,
    *,
    stride: int | None = None,
    fps: int = 20,
    progress: TextIO | None = sys.stderr,
) -> Path:
    """Write an animation of the bodies of a result: above, the side view (x right, z up) with the still water
    line and, where the result has it, the wave elevation at the origin (a blue dot at x = 0; the result holds no
    elevation along x); below, the top view (x right, y up). Each body is a dot at its centre of mass in its own
    colour with a grey bar along its body x axis; equal scales, fixed limits.

    Parameters
    ----------
    path : str or Path
        ``.gif`` (matplotlib's PillowWriter) or ``.mp4`` (ffmpeg, refused when ffmpeg is not on the PATH).
    stride : int, optional
        Saved steps per frame; default: at most :data:`MAX_FRAMES` frames.
    fps : int
        Frames per second.
    progress : text stream, optional
        Where a progress line goes once writing takes more than :data:`PROGRESS_AFTER_S`; None: nowhere.

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    ValueError
        For a result without poses (naming the output group to ask for), a bad stride or fps, a suffix other than
        .gif or .mp4, or MP4 without ffmpeg.
    """
    step = check_animation(ds, stride=stride, fps=fps)
    path = Path(path)
    writer = _writer(path, fps)
    plt = _pyplot()
    from matplotlib.animation import FuncAnimation

    frames = np.arange(0, ds.sizes["time"], step)
    position = np.asarray(ds.body_position.transpose("time", "body", "axis").values, dtype=float)
    axes_x = rotation_matrices(np.asarray(ds.body_rotation.transpose("time", "body", "axis").values, dtype=float))
    axes_x = axes_x[..., :, 0]  # the body x axis in world axes, per time and body
    names = [str(b) for b in ds.body.values]
    low, high = np.nanmin(position, axis=(0, 1)), np.nanmax(position, axis=(0, 1))
    span = float(max(np.max(high - low), 0.1))
    bar = 0.15 * span
    pad = bar + 0.1 * span
    elevation = np.asarray(ds.wave_elevation.values, dtype=float) if "wave_elevation" in ds else None
    z_low = min(low[2], 0.0 if elevation is None else float(np.nanmin(elevation)))
    z_high = max(high[2], 0.0 if elevation is None else float(np.nanmax(elevation)))
    fig, (side, top) = plt.subplots(2, 1, figsize=(7, 7))
    for ax, (j, name) in ((side, (2, "z")), (top, (1, "y"))):
        ax.set_xlim(low[0] - pad, high[0] + pad)
        ax.set_ylim((z_low if j == 2 else low[j]) - pad, (z_high if j == 2 else high[j]) + pad)
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel("x [m]")
        ax.set_ylabel(f"{name} [m]")
        ax.grid(alpha=0.3)
    side.axhline(0.0, color="tab:blue", lw=0.6, ls="--")
    side.set_title("side view", fontsize=9)
    top.set_title("top view", fontsize=9)
    colours = [COLOURS[k % len(COLOURS)] for k in range(len(names))]
    artists: list[tuple[Any, Any, Any, Any]] = []
    for k, name in enumerate(names):
        bars = (side.plot([], [], color="0.5", lw=2)[0], top.plot([], [], color="0.5", lw=2)[0])
        dots = (
            side.plot([], [], "o", color=colours[k], ms=8, label=name)[0],
            top.plot([], [], "o", color=colours[k], ms=8)[0],
        )
        artists.append((*bars, *dots))
    surface = side.plot([], [], "^", color="navy", ms=5, label="wave elevation at x = 0")[0]
    side.legend(fontsize=7, loc="upper right")
    fig.tight_layout()

    def draw(n: int) -> list[Any]:
        p, e = position[n], axes_x[n]
        for k in range(len(names)):
            side_bar, top_bar, side_dot, top_dot = artists[k]
            ends = p[k] + np.outer([-bar / 2, bar / 2], e[k])
            side_bar.set_data(ends[:, 0], ends[:, 2])
            top_bar.set_data(ends[:, 0], ends[:, 1])
            side_dot.set_data([p[k, 0]], [p[k, 2]])
            top_dot.set_data([p[k, 0]], [p[k, 1]])
        if elevation is not None:
            surface.set_data([0.0], [elevation[n]])
        fig.suptitle(f"{ds.attrs.get('device', 'wecss result')}: t = {float(ds.time[n]):.2f} s", fontsize=10)
        return [a for group in artists for a in group]

    start = time.monotonic()

    def report(i: int, total: int) -> None:
        if progress is not None and time.monotonic() - start > PROGRESS_AFTER_S:
            progress.write(f"\rframe {i + 1}/{total}" + ("\n" if i + 1 == total else ""))
            progress.flush()

    movie = FuncAnimation(fig, draw, frames=frames, blit=False)
    try:
        movie.save(str(path), writer=writer, progress_callback=report)
    finally:
        plt.close(fig)
    return path
