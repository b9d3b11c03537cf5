"""Spectral fatigue: the damage rate of a stationary Gaussian stress from its power spectral density, by the
narrow-band (Rayleigh) approximation or Dirlik's range distribution, and the life of every fibre point of a
device's elastic bodies from its stress transfer functions and a sea state.

Conventions as in :mod:`wecss.results._fatigue`: a cycle's range is peak to valley (twice its amplitude), the S-N
curve takes ranges [Pa], no mean-stress correction. Spectra are one-sided in angular frequency, S(omega)
[Pa^2 s/rad], with moments m_n = int_0^inf omega^n S(omega) d omega [Pa^2 (rad/s)^n]: m_0 is the variance. A line
spectrum (components sigma_k cos(omega_k t + phi_k)) has m_n = sum_k omega_k^n |sigma_k|^2 / 2.

Rates in hertz (Rice): zero up-crossings nu_0 = sqrt(m_2 / m_0) / (2 pi), peaks nu_p = sqrt(m_4 / m_2) / (2 pi);
bandwidth parameters alpha_1 = m_1 / sqrt(m_0 m_2) and alpha_2 = m_2 / sqrt(m_0 m_4) = nu_0 / nu_p (1 for a
narrow band). In terms of the normalised range Z = Delta S / (2 sqrt(m_0)), with the damage rate

    D = nu int_0^inf p_Z(z) / N(SCF 2 sqrt(m_0) z) dz     [1/s]

- narrow band: p_Z(z) = z exp(-z^2 / 2) (Rayleigh amplitudes of standard deviation sqrt(m_0)), nu = nu_0. For
  N = K Delta S^-m this is D = nu_0 (2 sqrt(2 m_0))^m Gamma(1 + m / 2) / K; it is an upper bound of the expected
  rainflow damage of a Gaussian process for m >= 1 (Rychlik 1993);
- Dirlik (1985, PhD thesis, University of Warwick), nu = nu_p, with x_m = (m_1 / m_0) sqrt(m_2 / m_4),
  gamma = alpha_2,

      D1 = 2 (x_m - gamma^2) / (1 + gamma^2),    R = (gamma - x_m - D1^2) / (1 - gamma - D1 + D1^2),
      D2 = (1 - gamma - D1 + D1^2) / (1 - R),    D3 = 1 - D1 - D2,    Q = 5 (gamma - D3 - D2 R) / (4 D1),
      p_Z(z) = D1 / Q exp(-z / Q) + D2 z / R^2 exp(-z^2 / (2 R^2)) + D3 z exp(-z^2 / 2).

  R comes out negative for many single-peaked spectra with a long tail (alpha_1 above about 0.92, e.g. JONSWAP
  spectra cut off far above the peak); it enters the density squared, so |R| is that Rayleigh term's scale. As
  gamma -> 1 the density goes to the narrow-band one (D1 -> 0, R -> 1); within 1e-9 of it (one line, or an
  ideally narrow band) the Rayleigh limit is taken, where Dirlik's fractions are 0 / 0.

The integral is numerical, through :meth:`SNCurve.cycles_to_failure`, so curves of several slopes work: Gauss-
Legendre in ln z on panels between the curve's knees (where 1/N has a kink), from z = 1e-4 (below it about 1e-8
of the damage or less for slopes >= 1) to where the heaviest tail is negligible (z = (m_max + 60) times the
largest scale, Q or |R| or 1). It matches the closed forms (Gamma functions for one slope, incomplete Gamma
functions for two) to rounding (measured 2e-15; ``tests/results/test_spectral_fatigue.py``).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from ._fatigue import SECONDS_PER_YEAR
from ._sn_curves import SNCurve, sn_curve

SPECTRAL_METHODS = ("dirlik", "narrow-band")
"""The damage-rate methods of :func:`spectral_damage_rate`."""

DEFAULT_ORDERS = (0, 1, 2, 4)
"""The moments the damage rates need (m_1 only for Dirlik's x_m)."""

NARROW_BAND_LIMIT = 1e-9
"""Dirlik's distribution is taken as the Rayleigh limit where 1 - alpha_2 or its fractions' denominator
1 - gamma - D1 + D1^2 is below this (one line, or an ideally narrow band)."""

Z_FLOOR = 1e-4
"""Lower end of the integral in the normalised range Z = Delta S / (2 sqrt(m_0)) [-]."""

PANELS = 48
NODES = 8
CHUNK = 2048
"""Panels per interval between knees, Gauss-Legendre nodes per panel, spectra per block of the integral."""

_LEGENDRE = np.polynomial.legendre.leggauss(NODES)


def _orders(orders: Sequence[int]) -> tuple[int, ...]:
    out = tuple(orders)
    if not out or any(isinstance(n, bool) or not isinstance(n, int | np.integer) for n in out):
        raise ValueError(f"orders must be a non-empty sequence of integers, got {orders!r}")
    return tuple(int(n) for n in out)


def _powers(omega: np.ndarray, n: int) -> np.ndarray:
    if n < 0 and np.any(omega <= 0.0):
        raise ValueError(f"moment order {n} needs every omega > 0 [rad/s]; the smallest is {float(omega.min())!r}")
    return omega**n


def _last_axis(values: np.ndarray, axis: int, size: int, what: str) -> np.ndarray:
    if values.ndim == 0 or not -values.ndim <= axis < values.ndim:
        raise ValueError(f"{what} of shape {values.shape} has no axis {axis}")
    moved = np.moveaxis(values, axis, -1)
    if moved.shape[-1] != size:
        raise ValueError(
            f"{what} has {moved.shape[-1]} values along axis {axis} (shape {values.shape}) but omega has {size}; "
            "give one value per frequency"
        )
    return moved


def psd_moments(
    omega: np.ndarray, psd: np.ndarray, orders: Sequence[int] = DEFAULT_ORDERS, *, axis: int = -1
) -> dict[int, np.ndarray]:
    """Spectral moments m_n = int omega^n S(omega) d omega of one-sided densities, by the trapezoidal rule.

    Parameters
    ----------
    omega : array_like (n,)
        Angular frequencies [rad/s], at least two, not negative, strictly increasing.
    psd : array_like
        One-sided densities S(omega) [Pa^2 s/rad] (or any unit^2 s/rad), not negative; ``n`` values along
        ``axis``, any other dimensions (e.g. one spectrum per fibre point).
    orders : sequence of int
        The moments wanted (default 0, 1, 2, 4: what :func:`spectral_damage_rate` needs). Negative orders need
        omega > 0.
    axis : int
        The axis of ``psd`` along omega.

    Returns
    -------
    dict
        m_n per order [Pa^2 (rad/s)^n], arrays of the shape of ``psd`` without ``axis``.

    Raises
    ------
    ValueError
        If omega is not 1-D, has fewer than two values, is negative or not increasing; if ``psd`` has another
        number of values along ``axis``, is negative or not finite; on orders that are not integers.
    """
    w = np.asarray(omega, dtype=float)
    if w.ndim != 1 or w.size < 2:
        raise ValueError(f"omega must be 1-D with at least two frequencies [rad/s], got shape {w.shape}")
    if not np.all(np.isfinite(w)) or w[0] < 0.0 or np.any(np.diff(w) <= 0.0):
        raise ValueError("omega must be finite, not negative and strictly increasing [rad/s]")
    s = _last_axis(np.asarray(psd, dtype=float), axis, w.size, "psd")
    if not np.all(np.isfinite(s)):
        raise ValueError("the spectral density holds NaN or infinite values; every value must be finite")
    if np.any(s < 0.0):
        k = np.unravel_index(int(np.argmin(s)), s.shape)
        raise ValueError(
            f"a spectral density cannot be negative: got {float(s[k])!r} at omega = {float(w[k[-1]])!r} rad/s; "
            "give S(omega) >= 0 (a one-sided power spectral density, not an amplitude spectrum)"
        )
    return {n: np.asarray(np.trapezoid(_powers(w, n) * s, w, axis=-1)) for n in _orders(orders)}


def line_moments(
    omega: np.ndarray, amplitude: np.ndarray, orders: Sequence[int] = DEFAULT_ORDERS, *, axis: int = -1
) -> dict[int, np.ndarray]:
    """Spectral moments of a line spectrum, m_n = sum_k omega_k^n |a_k|^2 / 2 (components Re[a_k e^{i omega_k t}]).

    Parameters
    ----------
    omega : array_like (n,)
        The components' angular frequencies [rad/s], positive, in any order.
    amplitude : array_like
        Their amplitudes a_k [Pa] (complex or real; only |a_k| counts), ``n`` values along ``axis``, any other
        dimensions.
    orders, axis
        As in :func:`psd_moments`.

    Returns
    -------
    dict
        m_n per order [Pa^2 (rad/s)^n], arrays of the shape of ``amplitude`` without ``axis``.

    Raises
    ------
    ValueError
        If omega is not 1-D, empty or not positive; if ``amplitude`` has another number of values along ``axis``
        or is not finite; on orders that are not integers.
    """
    w = np.asarray(omega, dtype=float)
    if w.ndim != 1 or w.size == 0:
        raise ValueError(f"omega must be 1-D with at least one frequency [rad/s], got shape {w.shape}")
    if not np.all(np.isfinite(w)) or np.any(w <= 0.0):
        raise ValueError(f"the components' frequencies must be positive and finite [rad/s], got {w!r}")
    a = _last_axis(np.asarray(amplitude), axis, w.size, "amplitude")
    if not np.all(np.isfinite(a)):
        raise ValueError("the component amplitudes hold NaN or infinite values; every amplitude must be finite")
    power = np.abs(a) ** 2 / 2.0
    return {n: np.asarray(np.sum(_powers(w, n) * power, axis=-1)) for n in _orders(orders)}


def _moment_arrays(moments: Mapping[int, Any], needed: tuple[int, ...]) -> list[np.ndarray]:
    if not isinstance(moments, Mapping):
        raise ValueError(
            f"moments must be a mapping from order to m_n (psd_moments, line_moments), got {type(moments).__name__}"
        )
    missing = [n for n in needed if n not in moments]
    if missing:
        raise ValueError(f"moments of orders {list(needed)} are needed, missing {missing} (got {sorted(moments)})")
    arrays = np.broadcast_arrays(*(np.asarray(moments[n], dtype=float) for n in needed))
    for n, m in zip(needed, arrays, strict=True):
        if not np.all(np.isfinite(m)) or np.any(m < 0.0):
            raise ValueError(f"the moment m_{n} must be finite and not negative, got {m!r}")
    return [np.array(m) for m in arrays]


def _irregularity(m0: np.ndarray, m1: np.ndarray, m2: np.ndarray, m4: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """alpha_1, alpha_2 where m_0, m_2 > 0 (1 elsewhere).

    Raises
    ------
    ValueError
        If they exceed 1 by more than rounding: the moments are not those of one spectrum.
    """
    live = (m0 > 0.0) & (m2 > 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        a1 = np.where(live, m1 / np.sqrt(m0 * m2), 1.0)
        a2 = np.where(live, m2 / np.sqrt(m0 * m4), 1.0)
    if np.any(a1 > 1.0 + 1e-9) or np.any(a2 > 1.0 + 1e-9):
        raise ValueError(
            "the moments are not those of one spectrum: alpha_1 = m_1 / sqrt(m_0 m_2) and alpha_2 = "
            f"m_2 / sqrt(m_0 m_4) must not exceed 1, got up to {float(a1.max())!r} and {float(a2.max())!r}"
        )
    return np.minimum(a1, 1.0), np.minimum(a2, 1.0)


def _dirlik(moments: Mapping[int, Any]) -> dict[str, np.ndarray]:
    """Dirlik's weights D1, D2, D3 and scales Q, R of the normalised range (module docstring), with m_0 and m_4."""
    m0, m1, m2, m4 = _moment_arrays(moments, DEFAULT_ORDERS)
    a1, gamma = _irregularity(m0, m1, m2, m4)
    xm = a1 * gamma  # (m1 / m0) sqrt(m2 / m4)
    d1 = 2.0 * (xm - gamma**2) / (1.0 + gamma**2)
    den = 1.0 - gamma - d1 + d1**2
    rayleigh = (1.0 - gamma < NARROW_BAND_LIMIT) | (den < NARROW_BAND_LIMIT)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(rayleigh, 1.0, (gamma - xm - d1**2) / np.where(rayleigh, 1.0, den))
        d2 = np.where(rayleigh, 0.0, den / (1.0 - r))
        d1 = np.where(rayleigh, 0.0, d1)
        d3 = 1.0 - d1 - d2
        q = np.where(d1 > 0.0, 1.25 * (gamma - d3 - d2 * r) / d1, 1.0)
    bad = ~rayleigh & ~((r != 0.0) & (q > 0.0) & (d2 >= 0.0) & (d3 >= 0.0))
    if np.any(bad):
        k = np.flatnonzero(bad.ravel())[0]
        a1k, gk, rk, qk, d2k, d3k = (float(v.ravel()[k]) for v in (a1, gamma, r, q, d2, d3))
        raise ValueError(
            f"Dirlik's range distribution is not defined for alpha_1 = {a1k!r}, alpha_2 = {gk!r} (R = {rk!r}, "
            f"Q = {qk!r}, D2 = {d2k!r}, D3 = {d3k!r}: Q must be positive, R not zero, D2 and D3 not negative); "
            "use method='narrow-band'"
        )
    return {"d1": d1, "d2": d2, "d3": d3, "q": q, "r": r, "m0": m0, "m2": m2, "m4": m4}


def _dirlik_pdf_z(z: np.ndarray, p: Mapping[str, np.ndarray]) -> np.ndarray:
    d1, d2, d3, q, r = p["d1"], p["d2"], p["d3"], p["q"], p["r"]
    return d1 / q * np.exp(-z / q) + d2 * z / r**2 * np.exp(-(z**2) / (2.0 * r**2)) + d3 * z * np.exp(-(z**2) / 2.0)


def _rayleigh_pdf_z(z: np.ndarray, p: Mapping[str, np.ndarray]) -> np.ndarray:
    return z * np.exp(-(z**2) / 2.0)


def _range_pdf(ranges: np.ndarray, m0: np.ndarray, pdf_z: Callable, params: Mapping[str, np.ndarray]) -> np.ndarray:
    s = np.asarray(ranges, dtype=float)
    if not np.all(np.isfinite(s)) or np.any(s < 0.0):
        raise ValueError(f"stress ranges must be finite and not negative [Pa], got {s!r}")
    if np.any(m0 <= 0.0):
        raise ValueError(f"the range distribution needs a positive variance m_0 [Pa^2], got {m0!r}")
    scale = 2.0 * np.sqrt(m0)
    return pdf_z(s / scale, params) / scale


def narrow_band_range_pdf(ranges: np.ndarray, moments: Mapping[int, Any]) -> np.ndarray:
    """Rayleigh density of stress ranges, p(Delta S) = Delta S / (4 m_0) exp(-Delta S^2 / (8 m_0)) [1/Pa].

    Parameters
    ----------
    ranges : array_like
        Stress ranges Delta S [Pa], not negative (peak to valley).
    moments : mapping
        At least m_0 [Pa^2] (:func:`psd_moments`), positive, broadcast against ``ranges``.

    Raises
    ------
    ValueError
        On negative ranges, a missing or non-positive m_0.
    """
    (m0,) = _moment_arrays(moments, (0,))
    return _range_pdf(ranges, m0, _rayleigh_pdf_z, {})


def dirlik_range_pdf(ranges: np.ndarray, moments: Mapping[int, Any]) -> np.ndarray:
    """Dirlik's (1985) density of rainflow stress ranges of a Gaussian process [1/Pa] (module docstring).

    Parameters
    ----------
    ranges : array_like
        Stress ranges Delta S [Pa], not negative (peak to valley: Z = Delta S / (2 sqrt(m_0))).
    moments : mapping
        m_0, m_1, m_2, m_4 (:func:`psd_moments`), broadcast against ``ranges``; m_0 positive.

    Raises
    ------
    ValueError
        On negative ranges, missing or inconsistent moments, or where Dirlik's parameters are not defined.
    """
    params = _dirlik(moments)
    return _range_pdf(ranges, params["m0"], _dirlik_pdf_z, params)


def _inverse_life(
    pdf_z: Callable, params: Mapping[str, np.ndarray], scale: np.ndarray, z_top: np.ndarray, curve: SNCurve
) -> np.ndarray:
    """int_{Z_FLOOR}^{z_top} p_Z(z) / N(scale z) dz for 1-D ``scale`` (> 0) and ``z_top``, params of that shape:
    Gauss-Legendre in ln z, PANELS panels of NODES nodes on each interval between the knees."""
    nodes, weights = _LEGENDRE
    knees = np.sort(curve.knee_ranges())[None, :] / scale[:, None]
    edges = np.log(
        np.concatenate(
            [np.full((scale.size, 1), Z_FLOOR), np.clip(knees, Z_FLOOR, z_top[:, None]), z_top[:, None]], axis=1
        )
    )  # (b, n_knees + 2), increasing
    width = np.diff(edges, axis=1) / PANELS  # (b, n_int)
    start = edges[:, :-1, None] + width[:, :, None] * np.arange(PANELS)  # (b, n_int, P)
    u = start[..., None] + width[:, :, None, None] * (nodes + 1.0) / 2.0  # (b, n_int, P, G)
    z = np.exp(u)
    shaped = {k: v[:, None, None, None] for k, v in params.items()}
    with np.errstate(over="ignore", under="ignore"):
        n = curve.cycles_to_failure(scale[:, None, None, None] * z)
    f = pdf_z(z, shaped) * z / n
    return np.sum(np.sum(f * weights, axis=3) * width[:, :, None] / 2.0, axis=(1, 2))


def _damage_per_cycle(
    pdf_z: Callable, params: Mapping[str, np.ndarray], z_top: np.ndarray, curve: SNCurve, scf: np.ndarray
) -> np.ndarray:
    """E[1 / N] per cycle over the flattened spectra with m_0 > 0 (0 where m_0 = 0)."""
    m0 = params["m0"]
    out = np.zeros(m0.size)
    live = np.flatnonzero(m0.ravel() > 0.0)
    scale = np.broadcast_to(scf * 2.0 * np.sqrt(m0), m0.shape).ravel()
    flat = {k: np.broadcast_to(v, m0.shape).ravel() for k, v in params.items()}
    top = np.broadcast_to(z_top, m0.shape).ravel()
    for start in range(0, live.size, CHUNK):
        k = live[start : start + CHUNK]
        out[k] = _inverse_life(pdf_z, {n: v[k] for n, v in flat.items()}, scale[k], top[k], curve)
    return out.reshape(m0.shape)


def spectral_damage_rate(
    moments: Mapping[int, Any],
    method: str = "dirlik",
    curve: str | SNCurve = "paper-003-table-5",
    scf: float | np.ndarray = 1.0,
) -> np.ndarray:
    """Expected Miner damage per second of a stationary Gaussian stress from its spectral moments [1/s].

    Parameters
    ----------
    moments : mapping
        m_0, m_2 (narrow band), and m_1, m_4 (Dirlik) [Pa^2 (rad/s)^n] of one-sided spectra in angular frequency:
        :func:`psd_moments`, :func:`line_moments` or :func:`wecss.results.spectral_moments` of a record. Arrays
        broadcast together (one spectrum per element, e.g. per fibre point).
    method : {"dirlik", "narrow-band"}
        Dirlik's range distribution at the peak rate nu_p (default), or Rayleigh ranges at the zero up-crossing
        rate nu_0 (conservative).
    curve : str or SNCurve
        The S-N curve of ranges (default the paper's Table 5; curves of several slopes are integrated piecewise).
    scf : float or array_like
        Stress concentration factor on the ranges [-], positive; broadcast against the moments.

    Returns
    -------
    ndarray
        Damage per second [1/s], the broadcast shape of the moments (and ``scf``); 0 where m_0 or m_2 is 0.
        Life in years: ``1 / (rate * SECONDS_PER_YEAR)``; over a scatter diagram: :func:`long_term_life`.

    Raises
    ------
    ValueError
        On an unknown method or curve, a non-positive SCF, missing, negative or inconsistent moments, or spectra
        whose Dirlik parameters are not defined.
    """
    if method not in SPECTRAL_METHODS:
        raise ValueError(f"unknown spectral fatigue method {method!r}; known methods: {list(SPECTRAL_METHODS)}")
    sn = sn_curve(curve)
    factor = np.asarray(scf, dtype=float)
    if not np.all(np.isfinite(factor)) or np.any(factor <= 0.0):
        raise ValueError(f"the stress concentration factor must be positive and finite, got {scf!r}")
    tail = max(sn.slopes) + 60.0
    if method == "narrow-band":
        m0, m2 = _moment_arrays(moments, (0, 2))
        m0, m2, factor = np.broadcast_arrays(m0, m2, factor)
        m0 = np.where(m2 > 0.0, m0, 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            rate = np.where(m0 > 0.0, np.sqrt(m2 / m0) / (2.0 * np.pi), 0.0)
        per_cycle = _damage_per_cycle(_rayleigh_pdf_z, {"m0": m0}, np.full(m0.shape, tail), sn, factor)
        return rate * per_cycle
    params = _dirlik(moments)
    m0, m2, m4 = params["m0"], params["m2"], params["m4"]
    shape = np.broadcast_shapes(m0.shape, factor.shape)
    live = (m0 > 0.0) & (m2 > 0.0)
    params = {k: np.broadcast_to(v, shape) for k, v in params.items()}
    params["m0"] = np.broadcast_to(np.where(live, m0, 0.0), shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = np.where(live, np.sqrt(m4 / m2) / (2.0 * np.pi), 0.0)
    scales = np.where(params["d1"] > 0.0, params["q"], 0.0)
    z_top = tail * np.maximum(np.maximum(scales, np.where(params["d2"] > 0.0, np.abs(params["r"]), 0.0)), 1.0)
    per_cycle = _damage_per_cycle(_dirlik_pdf_z, params, z_top, sn, np.broadcast_to(factor, shape))
    return np.broadcast_to(rate, shape) * per_cycle


def spectral_fatigue(
    response: xr.Dataset,
    spectrum: Any = None,
    *,
    method: str = "dirlik",
    curve: str | SNCurve = "paper-003-table-5",
    scf: float | np.ndarray = 1.0,
) -> xr.DataArray:
    """Fatigue life [years] of every fibre point from its stress transfer function and a sea state.

    The stress spectrum is S_sigma(omega) = |H(omega)|^2 S_eta(omega), H the ``normal_stress_rao`` [Pa/m] of
    :func:`wecss.linear.stress_response`, on the response's frequencies (the scene's wave components; moments by
    the trapezoidal rule); without a spectrum, the line spectrum of the response's own components, sigma_k =
    H(omega_k) a_k with a_k its ``wave_amplitude`` (the scene's record). The bandwidth, and so Dirlik's estimate,
    depends on m_4: on how far the components reach.

    Parameters
    ----------
    response : Dataset
        The output of :func:`wecss.linear.stress_response` (``normal_stress_rao`` on ``omega`` and ``fibre_point``,
        ``wave_amplitude`` on ``omega``).
    spectrum : wecss.waves.Spectrum, optional
        The wave spectrum S_eta(omega) [m^2 s/rad] (``Jonswap``, ``TabulatedSpectrum``, ...); the response needs at
        least two components then.
    method : {"dirlik", "narrow-band"}
        As in :func:`spectral_damage_rate`.
    curve, scf
        As in :func:`spectral_damage_rate`; ``scf`` a float or one value per fibre point. The response's stresses
        hold each hot spot's own SCF already (its stress modes'): an ``scf`` here multiplies them again.

    Returns
    -------
    DataArray
        Life [year] on ``fibre_point`` (``inf`` where the stress does not vary): 1 / (D SECONDS_PER_YEAR) with
        D the damage per second. Attributes: method, curve, SCF and where the stress spectrum came from.

    Raises
    ------
    TypeError
        If ``response`` is not a Dataset, or ``spectrum`` has no ``density``.
    ValueError
        Without the variables needed, on non-finite transfer functions, too few components, or bad settings (see
        :func:`spectral_damage_rate`).
    """
    if not isinstance(response, xr.Dataset):
        raise TypeError(f"response must be the Dataset of wecss.linear.stress_response, got {type(response).__name__}")
    needed = ["normal_stress_rao"] + ([] if spectrum is not None else ["wave_amplitude"])
    missing = [name for name in needed if name not in response]
    if missing:
        raise ValueError(
            f"the response lacks {missing}; give the Dataset of wecss.linear.stress_response (it has "
            f"{sorted(map(str, response.data_vars))})"
        )
    rao = response["normal_stress_rao"]
    if set(rao.dims) != {"omega", "fibre_point"}:
        raise ValueError(f"normal_stress_rao must be on dims ('omega', 'fibre_point'), got {rao.dims}")
    rao = rao.sortby("omega").transpose("fibre_point", "omega")
    omega = rao["omega"].values.astype(float)
    h = rao.values
    if spectrum is not None:
        if not callable(getattr(spectrum, "density", None)):
            raise TypeError(
                f"spectrum must be a wave spectrum with density(omega) (wecss.waves.Spectrum), got "
                f"{type(spectrum).__name__}"
            )
        _check_finite(h, omega)
        psd = np.abs(h) ** 2 * np.asarray(spectrum.density(omega), dtype=float)[None, :]
        moments = psd_moments(omega, psd)
        source = f"|normal_stress_rao|^2 S_eta(omega) of {type(spectrum).__name__}, trapezoidal rule"
    else:
        wave = response["wave_amplitude"].sortby("omega").values
        if not np.all(np.isfinite(wave)):
            raise ValueError("the response's wave_amplitude holds NaN values: components without a known amplitude")
        quiet = wave == 0.0
        _check_finite(h[:, ~quiet], omega[~quiet])
        amplitude = np.where(quiet[None, :], 0.0, h * np.where(quiet, 1.0, wave)[None, :])
        moments = line_moments(omega, amplitude)
        source = "line spectrum of the response's wave components (normal_stress_rao * wave_amplitude)"
    factor = np.asarray(scf, dtype=float)
    if factor.ndim > 1 or (factor.ndim == 1 and factor.size != h.shape[0]):
        raise ValueError(f"scf must be a float or one value per fibre point ({h.shape[0]}), got shape {factor.shape}")
    rate = spectral_damage_rate(moments, method, curve, factor)
    with np.errstate(divide="ignore"):
        life = np.where(rate > 0.0, 1.0 / (rate * SECONDS_PER_YEAR), np.inf)
    return xr.DataArray(
        life,
        dims=("fibre_point",),
        coords={"fibre_point": rao["fibre_point"].values},
        name="fatigue_life",
        attrs={
            "long_name": f"fatigue life, spectral ({method})",
            "units": "year",
            "method": method,
            "curve": sn_curve(curve).name,
            "scf": float(factor) if factor.ndim == 0 else "per fibre point",
            "stress_spectrum": source,
        },
    )


def _check_finite(h: np.ndarray, omega: np.ndarray) -> None:
    bad = ~np.all(np.isfinite(h), axis=0)
    if np.any(bad):
        raise ValueError(
            f"normal_stress_rao is not finite at omega = {omega[bad][:5]} rad/s (components of zero wave amplitude?); "
            "drop those components"
        )
