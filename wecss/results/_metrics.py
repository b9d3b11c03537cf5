"""Metrics on result Datasets: mean power, capture width ratio (M4 paper Eq. 53), RMS hinge angle (Fig. 8), RAOs
(Eqs. 54, 55) and spectral moments.

Windows: by default the final share of the run given by the scene's ``outputs.window`` (the paper: the final
half, 50 Tp of 100 Tp). A window can also be given as (start, end) in seconds.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..constants import GRAVITY
from ..waves import deep_water_wavelength

PAPER_ENERGY_PERIOD_RATIO = {3.3: 0.84, 1.0: 0.78}
"""The paper's Te/Tp for JONSWAP gamma 3.3 and 1 (these match T01, the mean period, not the energy period)."""

Window = float | tuple[float, float] | None


def _window(ds: xr.Dataset, window: Window) -> xr.Dataset:
    if "time" not in ds.dims:
        raise ValueError("the dataset holds no time series (statistics_only run?); use its mean_pto_power instead")
    t = ds.time.values
    if window is None:
        window = float(ds.attrs.get("statistics_window", 0.5))
    if isinstance(window, tuple):
        start, end = window
    else:
        if not 0 < window <= 1:
            raise ValueError(f"window is a share of the run in (0, 1] or (start, end) in seconds; got {window!r}")
        end = float(t[-1])
        start = end - window * (end - float(t[0]))
    sel = ds.sel(time=slice(start, end))
    if sel.sizes["time"] < 2:
        raise ValueError(f"window {window!r} holds fewer than two saved steps of {t[0]:.4g}-{t[-1]:.4g} s")
    return sel


def _mean(da: xr.DataArray) -> xr.DataArray:
    """Time average by the trapezoidal rule."""
    t = da.time.values
    return da.integrate("time") / (t[-1] - t[0])


def mean_power(ds: xr.Dataset, window: Window = None) -> xr.DataArray:
    """Mean absorbed power per PTO over the window [W].

    Without time series (``statistics_only`` runs), the running statistic ``mean_pto_power`` (over the scene's
    ``outputs.window``) is returned; another window then raises ValueError.
    """
    if "pto_power" not in ds:
        if "mean_pto_power" not in ds:
            raise ValueError("the dataset has neither pto_power nor mean_pto_power (ask for the 'pto' outputs)")
        if window is not None:
            raise ValueError("the dataset holds no time series, only mean_pto_power over the scene's outputs.window")
        return ds.mean_pto_power
    out = _mean(_window(ds, window).pto_power)
    out.attrs = {"long_name": "mean absorbed power", "units": "W"}
    return out


def capture_width_ratio(
    ds: xr.Dataset, window: Window = None, *, convention: str = "energy_period", power: str = "total"
) -> xr.DataArray:
    """Capture width ratio CWR = P_av / (P_wav L_e), L_e = g T_e^2 / (2 pi) (M4 paper Eq. 53).

    Parameters
    ----------
    convention : {"energy_period", "paper"}
        T_e as the energy period 2 pi m_-1 / m_0 of the spectrum (default), or the paper's 0.84 Tp (gamma 3.3) and
        0.78 Tp (gamma 1), which are in fact the mean period T01 of those spectra.
    power : {"total", "per_pto"}
        Total absorbed power of all PTOs, or one ratio per PTO.

    Returns
    -------
    DataArray
        CWR [-], with attributes that say the convention, T_e and P_wav used.
    """
    if convention not in ("energy_period", "paper"):
        raise ValueError(f"convention must be 'energy_period' or 'paper'; got {convention!r}")
    if power not in ("total", "per_pto"):
        raise ValueError(f"power must be 'total' or 'per_pto'; got {power!r}")
    if "wave_energy_flux" not in ds.attrs:
        raise ValueError("the dataset records no wave energy flux (calm water?)")
    if convention == "energy_period":
        te = float(ds.attrs["energy_period"])
    else:
        import json

        sea = json.loads(ds.attrs["scene"])["sea"]
        gamma = 1.0 if sea["kind"] == "pierson-moskowitz" else float(sea["gamma"])
        ratio = PAPER_ENERGY_PERIOD_RATIO.get(round(gamma, 6))
        if sea["kind"] not in ("jonswap", "pierson-moskowitz") or ratio is None:
            raise ValueError(
                f"the paper's convention covers JONSWAP with gamma 3.3 or 1 only; got {sea['kind']}, gamma {gamma}"
            )
        te = ratio * float(sea["period"])
    length = deep_water_wavelength(te, float(ds.attrs.get("g", GRAVITY)))
    p = mean_power(ds, window)
    if power == "total":
        p = p.sum("pto")
    out = p / (float(ds.attrs["wave_energy_flux"]) * length)
    out.attrs = {
        "long_name": "capture width ratio",
        "units": "1",
        "convention": convention,
        "energy_period_used_s": te,
        "wave_energy_flux_W_per_m": float(ds.attrs["wave_energy_flux"]),
        "power": power,
    }
    return out


def rms_hinge_angle(ds: xr.Dataset, window: Window = None) -> xr.DataArray:
    """RMS of each rotary PTO's angle about its mean over the window [rad] (paper Fig. 8); on the ``pto``
    dimension, NaN for linear PTOs."""
    if "pto_angle" not in ds:
        if "rms_pto_angle" in ds:
            if window is not None:
                raise ValueError("the dataset holds no time series, only rms_pto_angle over the scene's outputs.window")
            return ds.rms_pto_angle
        raise ValueError("the dataset has no rotary PTO angles (ask for the 'pto' outputs)")
    angle = _window(ds, window).pto_angle
    out = _mean((angle - _mean(angle)) ** 2) ** 0.5
    out.attrs = {"long_name": "RMS relative hinge angle", "units": "rad"}
    return out


def rao_irregular(
    ds: xr.Dataset, variable: str = "pto_angle", window: Window = None, *, segments: int = 8
) -> xr.DataArray:
    """RAO = sqrt(S_rr / S_eta_eta) from an irregular run by Welch's method (paper Eq. 54).

    Units: those of ``variable`` per metre of wave elevation.
    """
    sel = _window(ds, window)
    if variable not in sel or "wave_elevation" not in sel:
        raise ValueError(f"need {variable!r} and wave_elevation time series")
    t = sel.time.values
    fs = 1.0 / float(np.median(np.diff(t)))
    nperseg = max(16, t.size // max(1, segments))
    from scipy.signal import welch  # lazy: scipy.signal costs ~0.3 s at import

    freq, s_eta = welch(sel.wave_elevation.values, fs=fs, nperseg=nperseg)
    resp = sel[variable]
    other = [d for d in resp.dims if d != "time"]
    values = resp.transpose("time", *other).values.reshape(t.size, -1)
    _, s_resp = welch(values, fs=fs, nperseg=nperseg, axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        rao = np.sqrt(s_resp / s_eta[:, None])
    omega = 2 * np.pi * freq
    out = xr.DataArray(
        rao.reshape(omega.size, *[resp.sizes[d] for d in other]),
        dims=("omega", *other),
        coords={"omega": omega, **{d: resp[d].values for d in other}},
        attrs={"long_name": f"RAO of {variable} (Welch)", "units": f"{resp.attrs.get('units', '')}/m"},
    )
    # where the waves carry no energy the ratio is noise over noise: only where S_eta >= 1 % of its peak
    keep = xr.DataArray(s_eta >= 1e-2 * s_eta.max(), dims="omega", coords={"omega": omega})
    return out.where(keep)


def response_amplitude(ds: xr.Dataset, variable: str, omega: float, window: Window = None) -> xr.DataArray:
    """Amplitude of the ``omega`` [rad/s] component of ``variable`` over the window (least squares)."""
    sel = _window(ds, window)
    t = sel.time.values
    basis = np.stack([np.cos(omega * t), np.sin(omega * t), np.ones_like(t)], axis=1)
    resp = sel[variable]
    other = [d for d in resp.dims if d != "time"]
    values = resp.transpose("time", *other).values.reshape(t.size, -1)
    coef, *_ = np.linalg.lstsq(basis, values, rcond=None)
    amplitude = np.hypot(coef[0], coef[1]).reshape([resp.sizes[d] for d in other])
    return xr.DataArray(amplitude, dims=other, coords={d: resp[d].values for d in other})


def rao_regular(runs: list[xr.Dataset], variable: str = "pto_angle", window: Window = None) -> xr.DataArray:
    """RAO from regular-wave runs: response amplitude / wave amplitude at each run's frequency (paper Eq. 55,
    where S = A^2 / (2 d omega) links it to Eq. 54)."""
    import json

    rows, omegas = [], []
    for ds in runs:
        sea = json.loads(ds.attrs["scene"])["sea"]
        if sea["kind"] != "regular":
            raise ValueError(f"rao_regular needs regular-wave runs; got {sea['kind']!r}")
        omega = 2 * np.pi / float(sea["period"])
        rows.append(response_amplitude(ds, variable, omega, window) / (float(sea["height"]) / 2))
        omegas.append(omega)
    out = xr.concat(rows, dim="omega").assign_coords(omega=omegas).sortby("omega")
    out.attrs = {"long_name": f"RAO of {variable} (regular waves)"}
    return out


def spectral_moments(
    ds: xr.Dataset, variable: str = "wave_elevation", orders=(-1, 0, 1, 2), window: Window = None
) -> dict[int, float]:
    """Spectral moments m_n = int omega^n S(omega) d omega of a record (one-sided periodogram) [units^2 (rad/s)^n]."""
    sel = _window(ds, window)
    x = sel[variable].values - sel[variable].values.mean()
    t = sel.time.values
    dt = float(np.median(np.diff(t)))
    spectrum = np.abs(np.fft.rfft(x)) ** 2 * dt / (np.pi * x.size)  # S(omega), one-sided
    spectrum[0] = 0.0
    omega = 2 * np.pi * np.fft.rfftfreq(x.size, dt)
    d_omega = omega[1] - omega[0]
    out = {}
    for n in orders:
        with np.errstate(divide="ignore"):
            w = np.where(omega > 0, omega, np.inf) ** n if n < 0 else omega**n
        out[n] = float(np.sum(w * spectrum) * d_omega)
    return out


def _linear_ptos(ds: xr.Dataset) -> list[str]:
    """Names of the result's linear PTOs (``pto_kind`` "linear"; without that coordinate, the PTOs whose
    ``pto_displacement`` is not all NaN), in the result's order."""
    if "pto_kind" in ds.coords:
        return [str(n) for n, kind in zip(ds.pto.values, ds.pto_kind.values, strict=True) if kind == "linear"]
    if "pto_displacement" not in ds:
        return []
    has = ds.pto_displacement.notnull().any([d for d in ds.pto_displacement.dims if d != "pto"])
    return [str(n) for n, h in zip(ds.pto.values, has.values, strict=True) if h]


def wecccomp_score(
    ds: xr.Dataset,
    *,
    force_max: float = 60.0,
    stroke_max: float = 0.08,
    efficiency: float = 0.7,
    start: float = 25.0,
    pto: str | None = None,
) -> dict[str, float]:
    """The WEC Control Competition's evaluation criterion of one run and one linear PTO (the Wavestar's motor):

        EC = mean(P_elec) / (2 + |f|98 / F_max + |z|98 / Z_max - mean|P_elec| / |P_elec|98)

    with P_elec = efficiency P_abs when absorbing and P_abs / efficiency when supplying, |x|98 the 98th
    percentile of |x|, f the PTO force and z the stroke from its value at the run's start (the static
    equilibrium), over the saved steps from ``start`` [s] on (the competition discards the first 25 s).

    Parameters
    ----------
    ds : Dataset
        A result with the "pto" outputs of a device with a linear PTO.
    force_max, stroke_max : float
        F_max [N] and Z_max [m] (the Wavestar motor's: 60 N, 0.08 m).
    efficiency : float
        Conversion efficiency in (0, 1] (the competition's 0.7).
    start : float
        Start of the scored part [s].
    pto : str or None
        The PTO (default: the only linear one).

    Returns
    -------
    dict
        ``ec`` [W], ``mean_electrical_power`` and ``mean_absorbed_power`` [W], ``force_98`` [N], ``stroke_98``
        [m].

    Raises
    ------
    ValueError
        Without the time series needed, with no linear PTO or several and no ``pto``, or bad settings.
    """
    if not 0 < efficiency <= 1:
        raise ValueError(f"efficiency must lie in (0, 1]; got {efficiency!r}")
    if not (force_max > 0 and stroke_max > 0):
        raise ValueError(f"force_max and stroke_max must be positive; got {force_max!r}, {stroke_max!r}")
    needed = ("pto_power", "pto_force", "pto_displacement")
    if any(name not in ds for name in needed):
        raise ValueError(f"the result needs {', '.join(needed)} (a linear PTO and the 'pto' outputs)")
    names = _linear_ptos(ds)
    if pto is None:
        if len(names) != 1:
            raise ValueError(f"the device has linear PTOs {names}: say which with pto=")
        pto = names[0]
    if pto not in names:
        raise ValueError(f"pto {pto!r} is not a linear PTO of the result; linear PTOs: {names}")
    t = ds.time.values
    if not t[0] <= start < t[-1]:
        raise ValueError(f"start ({start!r} s) must lie within the run ({t[0]:.4g}-{t[-1]:.4g} s)")
    stroke = ds.pto_displacement.sel(pto=pto).values
    stroke = stroke - stroke[0]
    keep = t >= start
    power = ds.pto_power.sel(pto=pto).values[keep]
    electrical = np.where(power >= 0, efficiency * power, power / efficiency)
    force = np.percentile(np.abs(ds.pto_force.sel(pto=pto).values[keep]), 98)
    travel = np.percentile(np.abs(stroke[keep]), 98)
    peak = np.percentile(np.abs(electrical), 98)
    mean = float(np.mean(electrical))
    ratio = float(np.mean(np.abs(electrical)) / peak) if peak > 0 else 0.0
    return {
        "ec": mean / (2 + force / force_max + travel / stroke_max - ratio),
        "mean_electrical_power": mean,
        "mean_absorbed_power": float(np.mean(power)),
        "force_98": float(force),
        "stroke_98": float(travel),
    }
