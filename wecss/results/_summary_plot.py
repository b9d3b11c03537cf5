"""The summary plot of a run (the PNG ``wecss run`` writes): the sea state and the run in the title, the wave
elevation, PTO strokes and PTO power against time with the statistics window marked, the elevation spectrum against
the scene's target spectrum, and the mean power per PTO; values in units scaled to their size, every PTO with its
own colour and line style."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..waves import Jonswap
from ._metrics import mean_power
from ._plot import _pyplot, refuse_all_nan

LINESTYLES = ("-", "--", "-.", ":")
"""Line styles cycled with the colours, so PTOs stay apart in print and for colour-blind readers."""

PANELS_SIZE = (7.75, 7.5)
"""Width and height of the grid of panels [in]."""

MARGINS = {"left": 0.8, "right": 0.25, "bottom": 0.55, "top": 0.75}
"""Space around the grid of panels [in]: tick labels and axis labels, the title in the top one. Fixed, so that the
figure is drawn once when saved (a tight bounding box draws it twice to measure it)."""

TWIN_AXIS_MARGIN = 0.5
"""More space on the right [in] for the right-hand axis of the linear strokes (a device with both kinds of PTO)."""


def scaled_unit(values: np.ndarray, unit: str) -> tuple[float, str]:
    """A factor and unit that keep the largest finite |value| of a quantity in ``unit`` ("m", "W", "rad") between
    about 0.1 and 1000: m -> mm below 0.5 m; W -> mW below 1 W, kW from 10 kW; rad -> deg always."""
    finite = np.abs(np.asarray(values, dtype=float))
    finite = finite[np.isfinite(finite)]
    peak = float(finite.max()) if finite.size else 0.0
    if unit == "rad":
        return 180 / np.pi, "deg"
    if unit == "m" and peak < 0.5:
        return 1e3, "mm"
    if unit == "W":
        if peak < 1.0:
            return 1e3, "mW"
        if peak >= 1e4:
            return 1e-3, "kW"
    return 1.0, unit


def sea_state_title(ds: xr.Dataset) -> str:
    """The run in one or two lines: device, sea state (kind, height, period, gamma), solver, step, duration."""
    scene = json.loads(ds.attrs["scene"]) if "scene" in ds.attrs else {}
    sea = scene.get("sea", {})
    kind = sea.get("kind", ds.attrs.get("sea_kind", "?"))
    height = sea.get("height", ds.attrs.get("significant_wave_height"))
    period = sea.get("period", ds.attrs.get("peak_period"))
    parts = [str(kind).replace("jonswap", "JONSWAP").replace("pierson-moskowitz", "Pierson-Moskowitz")]
    if kind == "regular" and height is not None:
        parts.append(f"H {_length(float(height))}, T {float(period):.3g} s")
    elif height is not None and kind != "calm":
        parts.append(f"Hs {_length(float(height))}" + (f", Tp {float(period):.3g} s" if period is not None else ""))
        if kind == "jonswap":
            parts.append(f"gamma {float(sea.get('gamma', 3.3)):.3g}")
    first = f"{ds.attrs.get('device', ds.attrs.get('title', 'wecss result'))}: " + ", ".join(parts)
    second = []
    if "solver" in ds.attrs:
        step = ds.attrs.get("time_step")
        second.append(f"{str(ds.attrs['solver']).split(' (')[0]}" + (f" dt {float(step) * 1e3:.3g} ms" if step else ""))
    if "time" in ds.dims:
        second.append(f"{float(ds.time[-1] - ds.time[0]):.4g} s")
    if "controller" in ds.attrs:
        second.append(f"controller {ds.attrs['controller']}")
    return first + ("\n" + ", ".join(second) if second else "")


def _length(metres: float) -> str:
    return f"{metres * 1e3:.3g} mm" if metres < 0.5 else f"{metres:.3g} m"


def statistics_start(ds: xr.Dataset) -> float:
    """Start of the statistics window [s]: the final ``statistics_window`` share of the run (as the metrics)."""
    t = ds.time.values
    share = float(ds.attrs.get("statistics_window", 0.5))
    return float(t[-1] - share * (t[-1] - t[0]))


def plot_summary(ds: xr.Dataset, path: str | Path | None = None) -> Any:
    """The summary figure of a result with time series; saved to ``path`` (PNG) when given. Returns the figure.

    Panels: wave elevation; PTO strokes (rotary in deg, linear in scaled metres); absorbed PTO power, each PTO's
    mean over the statistics window in its legend entry; the statistics window shaded on all three; the recorded
    elevation spectrum (Welch, over the window) against the scene's target spectrum (JONSWAP and
    Pierson-Moskowitz; the component frequency of a regular wave); the mean power per PTO as bars.

    Raises
    ------
    ValueError
        If the result has no time series of wave elevation, PTO strokes or power, or one of them (or the mean
        power) is NaN everywhere.
    """
    plt = _pyplot()
    if "time" not in ds.dims or not any(v in ds for v in ("wave_elevation", "pto_power")):
        raise ValueError("nothing to plot: the result has no wave_elevation or PTO time series (statistics_only run?)")
    refuse_all_nan(ds, ("wave_elevation", "pto_angle", "pto_displacement", "pto_power", "mean_pto_power"))
    from matplotlib.gridspec import GridSpec

    twin = "pto_angle" in ds and "pto_displacement" in ds  # see _stroke_panel
    margins = {**MARGINS, "right": MARGINS["right"] + (TWIN_AXIS_MARGIN if twin else 0.0)}
    width = margins["left"] + PANELS_SIZE[0] + margins["right"]
    height = margins["bottom"] + PANELS_SIZE[1] + margins["top"]
    fig = plt.figure(figsize=(width, height))
    grid = GridSpec(
        4,
        2,
        figure=fig,
        height_ratios=[1, 1, 1, 1.15],
        hspace=0.45,
        wspace=0.28,
        left=margins["left"] / width,
        right=1 - margins["right"] / width,
        bottom=margins["bottom"] / height,
        top=1 - margins["top"] / height,
    )
    top = fig.add_subplot(grid[0, :])
    axes = [top, fig.add_subplot(grid[1, :], sharex=top), fig.add_subplot(grid[2, :], sharex=top)]
    t = ds.time.values
    start = statistics_start(ds)
    styles = _pto_styles(ds)
    means = {str(k): float(v) for k, v in zip(ds.pto.values, mean_power(ds).values, strict=True)} if styles else {}
    power_unit = scaled_unit(np.array(list(means.values()) or [0.0]), "W")  # the means decide: the figure's point
    _elevation_panel(axes[0], ds)
    _stroke_panel(axes[1], ds, styles)
    _power_panel(axes[2], ds, styles, means, power_unit)
    low, high = axes[2].get_ylim()
    axes[2].set_ylim(low, high + 0.3 * (high - low))  # headroom for the legend above the lines
    for k, ax in enumerate(axes):
        ax.axvspan(start, t[-1], color="0.85", zorder=0, label="statistics window" if k == 0 else None)
        ax.grid(alpha=0.3)
        ax.set_xlim(t[0], t[-1])
    axes[0].legend(fontsize=7, loc="upper left")
    axes[2].set_xlabel("time [s]")
    _spectrum_panel(fig.add_subplot(grid[3, 0]), ds, start)
    _bars_panel(fig.add_subplot(grid[3, 1]), means, styles, power_unit)
    # (a device with rotary and linear PTOs has one more axis: the linear strokes', to the right of the angles')
    fig.suptitle(sea_state_title(ds), fontsize=10, y=1 - 0.1 / height)
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig


def _pto_styles(ds: xr.Dataset) -> dict[str, dict[str, Any]]:
    """Colour and line style per PTO (tab10 colours, four line styles)."""
    names = [str(n) for n in ds.pto.values] if "pto" in ds.coords else []
    return {name: {"color": f"C{k % 10}", "linestyle": LINESTYLES[k % len(LINESTYLES)]} for k, name in enumerate(names)}


def _elevation_panel(ax: Any, ds: xr.Dataset) -> None:
    if "wave_elevation" not in ds:
        ax.text(0.5, 0.5, "no wave elevation in the result", ha="center", va="center", transform=ax.transAxes)
        return
    factor, unit = scaled_unit(ds.wave_elevation.values, "m")
    ax.plot(ds.time, ds.wave_elevation * factor, lw=0.7, color="k", label="wave elevation (as applied)")
    ax.set_ylabel(f"elevation [{unit}]", fontsize=8)


def _stroke_panel(ax: Any, ds: xr.Dataset, styles: dict[str, dict[str, Any]]) -> None:
    """Rotary strokes in degrees on the left axis; linear strokes on the left too, or on a right-hand axis of
    their own when the device has both kinds (units never share an axis)."""
    kinds = [(n, u, w) for n, u, w in (("pto_angle", "rad", "angle"), ("pto_displacement", "m", "stroke")) if n in ds]
    if not kinds:
        ax.set_ylabel("no PTO strokes", fontsize=8)
        return
    handles = []
    for k, (name, unit, what) in enumerate(kinds):
        target = ax if k == 0 else ax.twinx()
        factor, shown = scaled_unit(ds[name].values, unit)
        for pto in ds.pto.values:
            values = ds[name].sel(pto=pto).values
            if np.all(np.isnan(values)):
                continue  # a PTO of the other kind
            handles += target.plot(ds.time, values * factor, lw=0.8, label=str(pto), **styles[str(pto)])
        target.set_ylabel(f"PTO {what} [{shown}]", fontsize=8)
        low, high = target.get_ylim()
        target.set_ylim(low, high + 0.3 * (high - low))  # headroom for the legend
    ax.legend(handles=handles, fontsize=7, ncol=min(4, len(styles)), loc="upper left")


def _power_panel(
    ax: Any, ds: xr.Dataset, styles: dict[str, dict[str, Any]], means: dict[str, float], scale: tuple[float, str]
) -> None:
    if "pto_power" not in ds:
        ax.set_ylabel("no PTO power", fontsize=8)
        return
    factor, unit = scale
    for pto in ds.pto.values:
        name = str(pto)
        ax.plot(
            ds.time,
            ds.pto_power.sel(pto=pto) * factor,
            lw=0.7,
            label=f"{name}: mean {means[name] * factor:.3g} {unit}",
            **styles[name],
        )
    ax.set_ylabel(f"absorbed power [{unit}]", fontsize=8)
    ax.legend(fontsize=7, ncol=min(4, len(styles)), loc="upper left")


def _spectrum_panel(ax: Any, ds: xr.Dataset, start: float) -> None:
    ax.set_title("wave elevation spectrum", fontsize=9)
    if "wave_elevation" not in ds:
        ax.text(0.5, 0.5, "no wave elevation", ha="center", va="center", transform=ax.transAxes)
        return
    window = ds.wave_elevation.sel(time=slice(start, None))
    eta = window.values - window.values.mean()
    t = window.time.values
    if t.size < 16 or not np.any(eta):
        ax.text(0.5, 0.5, "calm or too short", ha="center", va="center", transform=ax.transAxes)
        return
    dt = float(np.median(np.diff(t)))
    freq, density = welch_density(eta, dt, nperseg=max(16, t.size // 3))
    omega, s_omega = 2 * np.pi * freq, density / (2 * np.pi)  # S(omega) [m^2 s/rad]
    factor, unit = scaled_unit(eta, "m")
    ax.plot(omega, s_omega * factor**2, color="k", lw=1.0, label="recorded (Welch, statistics window)")
    target = _target_spectrum(ds)
    if target is not None:
        fine = np.linspace(0.0, float(omega[-1]), 2000)
        ax.plot(fine, target.density(fine) * factor**2, color="C3", lw=1.2, ls="--", label="target spectrum")
    else:
        scene = json.loads(ds.attrs.get("scene", "{}")).get("sea", {})
        if scene.get("kind") == "regular":
            ax.axvline(2 * np.pi / float(scene["period"]), color="C3", ls="--", lw=1.2, label="wave frequency")
    peak = omega[np.argmax(s_omega)]
    ax.set_xlim(0, min(float(omega[-1]), 4 * peak))
    ax.set_xlabel("omega [rad/s]")
    ax.set_ylabel(f"S [{unit}^2 s/rad]", fontsize=8)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)


def welch_density(values: np.ndarray, dt: float, nperseg: int) -> tuple[np.ndarray, np.ndarray]:
    """Welch's estimate of the one-sided power spectral density of a 1-D series sampled every ``dt`` [s]:
    frequencies [Hz] and density [unit^2/Hz]. Segments of ``nperseg`` samples overlapping by half, a periodic
    Hann window, each segment's mean removed, density scaling: the defaults of ``scipy.signal.welch``, computed
    with matplotlib's ``mlab.psd`` because matplotlib is loaded for the plot anyway and scipy.signal costs
    0.3-0.5 s to import."""
    from matplotlib import mlab

    window = np.hanning(nperseg + 1)[:-1]  # periodic Hann (scipy's "hann" for spectral analysis)
    density, freq = mlab.psd(
        values, NFFT=nperseg, Fs=1.0 / dt, detrend="mean", window=window, noverlap=nperseg // 2, sides="onesided"
    )
    return np.asarray(freq), np.asarray(density)


def _target_spectrum(ds: xr.Dataset) -> Jonswap | None:
    """The scene's JONSWAP or Pierson-Moskowitz spectrum (None for other seas)."""
    sea = json.loads(ds.attrs.get("scene", "{}")).get("sea", {})
    if sea.get("kind") not in ("jonswap", "pierson-moskowitz"):
        return None
    gamma = 1.0 if sea["kind"] == "pierson-moskowitz" else float(sea.get("gamma", 3.3))
    return Jonswap(float(sea["height"]), float(sea["period"]), gamma)


def _bars_panel(ax: Any, means: dict[str, float], styles: dict[str, dict[str, Any]], scale: tuple[float, str]) -> None:
    if not means:
        ax.set_title("mean absorbed power per PTO", fontsize=9)
        ax.text(0.5, 0.5, "no PTOs", ha="center", va="center", transform=ax.transAxes)
        return
    values = np.array(list(means.values()))
    factor, unit = scale
    ax.set_title(f"mean absorbed power (statistics window): total {values.sum() * factor:.3g} {unit}", fontsize=9)
    names = list(means)
    bars = ax.bar(names, values * factor, color=[styles[n]["color"] for n in names])
    ax.bar_label(bars, fmt="%.3g", fontsize=7)
    ax.margins(y=0.15)
    ax.set_ylabel(f"mean power [{unit}]", fontsize=8)
    ax.tick_params(axis="x", labelsize=7)
    ax.grid(alpha=0.3, axis="y")
