"""Wave spectra (JONSWAP, Pierson-Moskowitz, tabulated) and the quantities derived from them.

All spectra are one-sided densities in angular frequency, S(omega) [m^2 s/rad], with m_n = int omega^n S d omega.
Periods: peak Tp, energy period Te = 2 pi m_-1 / m_0 and mean period T01 = 2 pi m_0 / m_1. The M4 paper's
"Te = 0.84 Tp (gamma 3.3), 0.78 Tp (gamma 1)" are T01 values (DESIGN.md); Te is 0.903 Tp and 0.857 Tp.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Protocol

import numpy as np

from ..constants import GRAVITY, RHO_WATER


class Spectrum(Protocol):
    """A one-sided wave spectrum S(omega) [m^2 s/rad]."""

    def density(self, omega: np.ndarray) -> np.ndarray:
        """S at ``omega`` [rad/s]."""
        ...

    def moment(self, n: int) -> float:
        """Spectral moment m_n = int omega^n S(omega) d omega [m^2 (rad/s)^n]."""
        ...


def _jonswap_shape(omega: np.ndarray, omega_p: float, gamma: float) -> np.ndarray:
    omega = np.asarray(omega, dtype=float)
    out = np.zeros_like(omega)
    pos = omega > 0
    w = omega[pos]
    sigma = np.where(w <= omega_p, 0.07, 0.09)
    peak = gamma ** np.exp(-((w - omega_p) ** 2) / (2 * sigma**2 * omega_p**2))
    out[pos] = w**-5 * np.exp(-1.25 * (omega_p / w) ** 4) * peak
    return out


_GAUSS_LEGENDRE = np.polynomial.legendre.leggauss(100)
"""Nodes and weights on [-1, 1] of the quadrature of :func:`_shape_moment` (100 points per piece)."""


@lru_cache(maxsize=256)
def _shape_moment(n: int, gamma: float) -> float:
    """int omega^n shape(omega) d omega for omega_p = 1 (scale-free), n <= 3, to a relative 1e-14.

    Gauss-Legendre on the pieces [0, 0.5], [0.5, 1], [1, 1.5], [1.5, 3] (smooth on each: the peak width changes
    at omega = 1) and on the tail (3, inf) mapped to u = 3 / omega in (0, 1), where the integrand is
    3^(n - 4) u^(3 - n) times a factor going to 1. (numpy only: scipy.integrate.quad costs 0.07-0.2 s at import.)

    Raises
    ------
    ValueError
        For n >= 4: the tail omega^(n - 5) makes the moment infinite.
    """
    if n >= 4:
        raise ValueError(f"the JONSWAP spectral moment m_{n} is infinite (tail omega^-5); n must be <= 3")
    nodes, weights = _GAUSS_LEGENDRE
    total = 0.0
    for lo, hi in ((0.0, 0.5), (0.5, 1.0), (1.0, 1.5), (1.5, 3.0)):
        w = 0.5 * (hi - lo) * nodes + 0.5 * (hi + lo)
        total += 0.5 * (hi - lo) * float(np.sum(weights * w**n * _jonswap_shape(w, 1.0, gamma)))
    u = 0.5 * nodes + 0.5
    w = 3.0 / u
    total += 0.5 * float(np.sum(weights * w**n * _jonswap_shape(w, 1.0, gamma) * 3.0 / u**2))
    return total


def _check_positive(**values: float) -> None:
    for name, value in values.items():
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a positive number; got {value!r}")


@dataclass(frozen=True)
class Jonswap:
    """JONSWAP spectrum normalised so that 4 sqrt(m0) = Hs exactly (integral over 0 < omega < inf).

    Parameters
    ----------
    hs : float
        Significant wave height [m].
    tp : float
        Peak period [s].
    gamma : float
        Peak enhancement factor [-] (1 gives Pierson-Moskowitz); sigma = 0.07 below and 0.09 above the peak.

    Raises
    ------
    ValueError
        On non-positive values, or gamma < 1.
    """

    hs: float
    tp: float
    gamma: float = 3.3

    def __post_init__(self) -> None:
        _check_positive(hs=self.hs, tp=self.tp, gamma=self.gamma)
        if self.gamma < 1:
            raise ValueError(f"gamma must be >= 1; got {self.gamma!r}")

    @property
    def omega_p(self) -> float:
        """Peak angular frequency [rad/s]."""
        return 2 * np.pi / self.tp

    def density(self, omega: np.ndarray) -> np.ndarray:
        """S(omega) [m^2 s/rad]."""
        scale = self.hs**2 / 16 / (_shape_moment(0, float(self.gamma)) * self.omega_p**-4)
        return scale * _jonswap_shape(omega, self.omega_p, float(self.gamma))

    def moment(self, n: int) -> float:
        """m_n, exact to quadrature accuracy (relative 1e-14), for n <= 3.

        Raises
        ------
        ValueError
            For n >= 4: the moment is infinite (the spectrum's tail falls as omega^-5).
        """
        return (
            self.hs**2
            / 16
            * self.omega_p**n
            * _shape_moment(n, float(self.gamma))
            / _shape_moment(0, float(self.gamma))
        )


def PiersonMoskowitz(hs: float, tp: float) -> Jonswap:
    """Pierson-Moskowitz spectrum: JONSWAP with gamma = 1 [Hs in m, Tp in s]."""
    return Jonswap(hs, tp, 1.0)


@dataclass(frozen=True)
class TabulatedSpectrum:
    """A measured or user-given spectrum, linear between the given points and zero outside them.

    Parameters
    ----------
    omega : array_like
        Strictly increasing angular frequencies [rad/s], >= 0.
    values : array_like
        S(omega) [m^2 s/rad], >= 0.
    """

    omega: np.ndarray
    values: np.ndarray
    _grid: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        omega = np.asarray(self.omega, dtype=float)
        values = np.asarray(self.values, dtype=float)
        if omega.ndim != 1 or omega.shape != values.shape or omega.size < 2:
            raise ValueError(f"omega and values must be 1-D of the same length >= 2; got {omega.shape}, {values.shape}")
        if np.any(np.diff(omega) <= 0) or omega[0] < 0:
            raise ValueError("omega must be non-negative and strictly increasing")
        if np.any(values < 0) or not np.all(np.isfinite(values)):
            raise ValueError("spectrum values must be finite and non-negative")
        object.__setattr__(self, "omega", omega)
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "_grid", np.linspace(omega[0], omega[-1], 20001))

    def density(self, omega: np.ndarray) -> np.ndarray:
        """S(omega) [m^2 s/rad]."""
        return np.interp(omega, self.omega, self.values, left=0.0, right=0.0)

    def moment(self, n: int) -> float:
        """m_n by the trapezoidal rule on a fine grid of the table's range."""
        w = self._grid
        s = self.density(w)
        with np.errstate(divide="ignore", invalid="ignore"):
            f = np.where(s > 0, w**n * s, 0.0)
        return float(np.trapezoid(f, w))


def hm0(spectrum: Spectrum) -> float:
    """Spectral significant wave height 4 sqrt(m0) [m]."""
    return 4.0 * np.sqrt(spectrum.moment(0))


def peak_period(spectrum: Spectrum, omega: np.ndarray | None = None) -> float:
    """Peak period [s] (of the given grid, or of a fine grid for tabulated spectra)."""
    if isinstance(spectrum, Jonswap):
        return spectrum.tp
    grid = omega if omega is not None else np.linspace(1e-3, 50.0, 200001)
    return float(2 * np.pi / grid[np.argmax(spectrum.density(grid))])


def energy_period(spectrum: Spectrum) -> float:
    """Te = 2 pi m_-1 / m_0 [s]."""
    return 2 * np.pi * spectrum.moment(-1) / spectrum.moment(0)


def mean_period(spectrum: Spectrum) -> float:
    """T01 = 2 pi m_0 / m_1 [s] (the M4 paper's 'Te = 0.84 Tp')."""
    return 2 * np.pi * spectrum.moment(0) / spectrum.moment(1)


def wavenumber(omega: np.ndarray, depth: float = np.inf, g: float = GRAVITY) -> np.ndarray:
    """Wavenumber k [rad/m] from omega^2 = g k tanh(k h) (Newton iterations; deep water when depth is inf)."""
    omega = np.asarray(omega, dtype=float)
    k = omega**2 / g
    if np.isinf(depth):
        return k
    k = np.where(k * depth < 1, omega / np.sqrt(g * depth), k)  # shallow or deep start
    for _ in range(50):
        tanh = np.tanh(k * depth)
        f = g * k * tanh - omega**2
        df = g * tanh + g * k * depth * (1 - tanh**2)
        step = np.where(df > 0, f / np.where(df > 0, df, 1.0), 0.0)
        k = k - step
        if np.all(np.abs(step) <= 1e-14 * np.maximum(k, 1e-300)):
            break
    return k


def group_velocity(omega: np.ndarray, depth: float = np.inf, g: float = GRAVITY) -> np.ndarray:
    """Group velocity c_g = d omega / d k [m/s]."""
    omega = np.asarray(omega, dtype=float)
    if np.isinf(depth):
        return g / (2 * np.where(omega > 0, omega, np.inf))
    k = wavenumber(omega, depth, g)
    kh = k * depth
    with np.errstate(divide="ignore", invalid="ignore"):
        factor = np.where(kh < 350, 2 * kh / np.sinh(np.minimum(2 * kh, 700)), 0.0)
        return np.where(k > 0, 0.5 * omega / k * (1 + factor), np.sqrt(g * depth))


def energy_flux(spectrum: Spectrum, depth: float = np.inf, rho: float = RHO_WATER, g: float = GRAVITY) -> float:
    """Wave energy flux per metre of crest, rho g int S(omega) c_g(omega) d omega [W/m].

    Deep water: rho g^2 m_-1 / 2 exactly. Finite depth: trapezoidal rule on a geometric grid from 1e-3 to
    1e4 rad/s (relative accuracy about 1e-8 for JONSWAP spectra).
    """
    if np.isinf(depth):
        return rho * g**2 * spectrum.moment(-1) / 2
    w = np.geomspace(1e-3, 1e4, 400001)
    return float(rho * g * np.trapezoid(spectrum.density(w) * group_velocity(w, depth, g), w))


def deep_water_wavelength(period: float, g: float = GRAVITY) -> float:
    """L = g T^2 / (2 pi) [m] (the M4 paper's L_e, Eq. 53)."""
    return g * period**2 / (2 * np.pi)
