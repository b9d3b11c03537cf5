"""Radiation impulse response functions K(t) = (2/pi) int_0^inf B(omega) cos(omega t) d omega (M4 paper Eq. 48).

B is taken piecewise linear between the data frequencies (B(0) = 0) and continued beyond the last one by a
fitted power-law tail B(omega_N) (omega_N / omega)^p. The cosine integral of a piecewise-linear function is
evaluated exactly segment by segment (Filon's idea), so K(t) stays accurate at times where cos(omega t)
turns many times within one frequency step, up to the limit t <= pi / d_omega of the data's resolution.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..hydro import HydroData

TRUNCATION_RTOL: float = 0.01
"""A kernel entry is truncated where |K| last exceeds this fraction of its peak (the paper used 4 Tp)."""

TAIL_FACTOR: float = 1000.0
"""The fitted high-frequency tail runs to this multiple of the highest data frequency (on a geometric grid of
ratio TAIL_RATIO, where the piecewise-linear interpolation of a power law is accurate to about 1e-4)."""

TAIL_RATIO: float = 1.02
"""Ratio of successive frequencies of the tail's grid."""

TAIL_POINTS: int = 8
"""Number of highest data frequencies used to fit the tail's exponent."""

MIN_TAIL_EXPONENT: float = 2.0
"""Smallest accepted tail exponent p (the tail's integral converges for p > 1)."""


def filon_cosine_weights(omega: np.ndarray, time: np.ndarray) -> np.ndarray:
    """Weights W (n_time, n_omega) with int f(omega) cos(omega t) d omega = W @ f exactly for piecewise-linear f.

    For a segment [a, b] of width h and mid-point c, int (linear f) cos = [f sin(w t)/t]_a^b + m [cos(w t)/t^2]_a^b,
    and (cos(bt) - cos(at)) / (h t^2) = -(sin(c t) / t) sinc(h t / 2 pi) in numpy's sinc convention.
    """
    omega = np.asarray(omega, dtype=float)
    time = np.asarray(time, dtype=float)
    h = np.diff(omega)
    c = 0.5 * (omega[1:] + omega[:-1])
    t = time[:, None]
    small = np.abs(time) < 1e-12
    safe_t = np.where(small, 1.0, time)[:, None]
    d = -(np.sin(c[None, :] * t) / safe_t) * np.sinc(h[None, :] * t / (2 * np.pi))  # (n_t, n_seg)
    w = np.zeros((time.size, omega.size))
    w[:, 1:] += d
    w[:, :-1] -= d
    w[:, -1] += np.sin(omega[-1] * t[:, 0]) / safe_t[:, 0]
    w[:, 0] -= np.sin(omega[0] * t[:, 0]) / safe_t[:, 0]
    if np.any(small):  # trapezoid rule at t = 0
        trap = np.zeros(omega.size)
        trap[1:] += h / 2
        trap[:-1] += h / 2
        w[small] = trap
    return w


@dataclass(frozen=True)
class ImpulseResponse:
    """Radiation impulse response of a database.

    Attributes
    ----------
    time : ndarray (n_t,)
        Times [s], from 0.
    kernel : ndarray (n_t, n_dof, n_dof)
        K_ij(t), influenced DOF i, radiating DOF j [N/m, N, N m/rad per (m/s or rad/s) per s].
    dofs : tuple of str
    truncation_time : ndarray (n_dof, n_dof)
        Where |K_ij| last exceeds TRUNCATION_RTOL of its peak [s].
    k0_integral : ndarray (n_dof, n_dof)
        (2/pi) int B d omega over data and tail, the value K(0) must equal.
    tail_exponent : ndarray (n_dof, n_dof)
        Exponent p of the high-frequency tail.
    tail_share : ndarray (n_dof, n_dof)
        Part of (2/pi) int B that comes from the tail beyond the data, relative to sqrt(K_ii(0) K_jj(0)) [-].
    omega : ndarray
        Frequencies the integral used (data, with 0, and the tail) [rad/s].
    """

    time: np.ndarray
    kernel: np.ndarray
    dofs: tuple[str, ...]
    truncation_time: np.ndarray
    k0_integral: np.ndarray
    tail_exponent: np.ndarray
    tail_share: np.ndarray
    omega: np.ndarray
    damping: np.ndarray
    band: tuple[float, float] | None = None

    @property
    def dt(self) -> float:
        """Time step of the samples [s]."""
        return float(self.time[1] - self.time[0])

    def at(self, time: np.ndarray) -> np.ndarray:
        """K at other times [s] (exact evaluation of the same integral, not interpolation)."""
        weights = filon_cosine_weights(self.omega, np.asarray(time, dtype=float))
        n = len(self.dofs)
        return (2 / np.pi) * (weights @ self.damping.reshape(self.omega.size, n * n)).reshape(-1, n, n)

    def to_dataset(self) -> xr.Dataset:
        """The kernel and its checks as an xarray Dataset (dims time, influenced_dof, radiating_dof)."""
        dims = ("influenced_dof", "radiating_dof")
        return xr.Dataset(
            {
                "kernel": (("time", *dims), self.kernel, {"long_name": "radiation impulse response K(t)"}),
                "truncation_time": (dims, self.truncation_time, {"units": "s"}),
                "k0_integral": (dims, self.k0_integral, {"long_name": "(2/pi) integral of B"}),
                "tail_exponent": (dims, self.tail_exponent),
                "tail_share": (dims, self.tail_share),
            },
            coords={
                "time": ("time", self.time, {"units": "s"}),
                "influenced_dof": list(self.dofs),
                "radiating_dof": list(self.dofs),
            },
        )


def _tail_exponents(omega: np.ndarray, damping: np.ndarray) -> np.ndarray:
    """Power-law exponents of the diagonal damping's decay (log-log slope of the last points), averaged for
    off-diagonal entries, and at least MIN_TAIL_EXPONENT."""
    n = damping.shape[1]
    m = min(TAIL_POINTS, omega.size)
    w = np.log(omega[-m:])
    p = np.full(n, 4.0)
    for i in range(n):
        b = damping[-m:, i, i]
        if np.all(b > 0):
            slope = np.polyfit(w, np.log(b), 1)[0]
            p[i] = max(-slope, MIN_TAIL_EXPONENT)
    return 0.5 * (p[:, None] + p[None, :])


def impulse_response(
    hydro: HydroData,
    *,
    dt: float | None = None,
    t_max: float | None = None,
    tail: bool = True,
    band: tuple[float, float] | None = None,
) -> ImpulseResponse:
    """Impulse response functions of every pair of DOFs.

    Parameters
    ----------
    hydro : HydroData
    dt : float, optional
        Time step [s] (default: pi / (4 omega_max), four samples per period of the highest data frequency).
    t_max : float, optional
        Last time [s]; at most pi / d_omega of the data (default: that limit).
    band : (float, float), optional
        Band-limit the kernel: B is multiplied by a cosine roll-off from 1 at ``band[0]`` to 0 at ``band[1]``
        [rad/s] (and the tail, if any, ends there). A band-limited kernel has no sharp peak at t = 0, so a
        state-space fit needs far fewer states; the content above the band, where a sea state has no energy,
        is dropped (its added-mass effect in the band is a constant, see ``wecss.sim``'s A_inf correction).
    tail : bool
        Continue B beyond the data with a fitted power law up to TAIL_FACTOR times the highest frequency. The
        tail shapes K near t = 0 (its share of K(0) is reported); beyond the data its content is unresolved by
        samples coarser than pi / (TAIL_FACTOR omega_max), which matters only within the first steps.

    Raises
    ------
    ValueError
        If ``t_max`` exceeds pi / d_omega (the data cannot resolve longer memory) or ``dt`` is not positive.
    """
    omega = hydro.omega
    damping = hydro.dataset.radiation_damping.values
    d_omega = float(np.max(np.diff(omega)))
    limit = np.pi / d_omega
    if t_max is None:
        t_max = limit
    if t_max > limit * (1 + 1e-9):
        raise ValueError(f"t_max = {t_max} s exceeds pi / d_omega = {limit:.4g} s, the longest memory the data resolve")
    if dt is None:
        dt = np.pi / (4 * omega[-1])
    if not dt > 0:
        raise ValueError(f"dt must be positive [s]; got {dt!r}")
    n = damping.shape[1]
    grid = np.concatenate([[0.0], omega])
    values = np.concatenate([np.zeros((1, n, n)), damping])
    exponents = _tail_exponents(omega, damping)
    if tail:
        count = int(np.ceil(np.log(TAIL_FACTOR) / np.log(TAIL_RATIO)))
        extra = omega[-1] * TAIL_RATIO ** np.arange(1, count + 1)
        tail_values = damping[-1][None] * (omega[-1] / extra[:, None, None]) ** exponents[None]
        grid = np.concatenate([grid, extra])
        values = np.concatenate([values, tail_values])
    if band is not None:
        lo, hi = band
        if not 0 < lo < hi:
            raise ValueError(f"band must be (start, end) of the roll-off with 0 < start < end [rad/s]; got {band!r}")
        if tail and grid[-1] < hi:
            raise ValueError(f"band end {hi} rad/s lies beyond the tail ({grid[-1]:.4g} rad/s)")
        keep = grid <= hi
        if grid[keep][-1] < hi:  # close the roll-off exactly at hi
            grid = np.concatenate([grid[keep], [hi]])
            values = np.concatenate([values[keep], values[keep][-1:]])
        else:
            grid, values = grid[keep], values[keep]
        roll = np.where(grid <= lo, 1.0, np.cos(0.5 * np.pi * np.clip((grid - lo) / (hi - lo), 0.0, 1.0)) ** 2)
        values = values * roll[:, None, None]
    time = np.arange(0.0, t_max + dt / 2, dt)
    weights = filon_cosine_weights(grid, time)
    kernel = (2 / np.pi) * (weights @ values.reshape(grid.size, n * n)).reshape(time.size, n, n)
    trap = filon_cosine_weights(grid, np.array([0.0]))[0]
    k0 = (2 / np.pi) * np.tensordot(trap, values, axes=(0, 0))
    data_part = (2 / np.pi) * np.tensordot(trap[: omega.size + 1], values[: omega.size + 1], axes=(0, 0))
    diag = np.sqrt(np.abs(np.outer(np.diag(k0), np.diag(k0))))
    share = np.where(diag > 0, (k0 - data_part) / np.where(diag > 0, diag, 1.0), 0.0)
    peak = np.max(np.abs(kernel), axis=0)
    above = np.abs(kernel) > TRUNCATION_RTOL * peak[None]
    last = np.where(above.any(axis=0), time.size - 1 - np.argmax(above[::-1], axis=0), 0)
    return ImpulseResponse(time, kernel, tuple(hydro.dofs), time[last], k0, exponents, share, grid, values, band)
