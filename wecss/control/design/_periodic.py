"""A linear device on the harmonics of a periodic wave record: the PTO response to a force at every harmonic of the
record's repeat period, and the record's time grid, for programmes over whole force trajectories (the non-causal
optimum).

A record that repeats every T_r holds wave components at whole multiples of omega_0 = 2 pi / T_r (wecss's periodic
irregular waves: ``sea.d_omega`` = omega_0). A PTO force that repeats with the record is a Fourier series,

    f(t) = Re sum_{m=L}^{M} F_m exp(i m omega_0 t),

from the waves' lowest harmonic L (by default) or from the first (``lowest = 1``) to M. No constant part: a constant
force does no work over a period. The harmonics below the waves' cost almost no power (the PTO admittance's real part
falls as omega^2 towards zero frequency: 9e-9 at the first harmonic of WECCCOMP's sea state 6 against 9e-3 at its
peak), but where a force limit binds they shape the saturated force (its wave groups' envelope), and the non-causal
optimum takes them (``noncausal_optimum``: +3.7 % in that sea state's optimum within 60 N). The linear device answers
the force harmonic by
harmonic: the PTO stroke rates are v_m = v_e,m + Y_m F_m (``wecss.control.design.pto_response``: v_e the rates the
waves drive with no PTO force, Y the PTO admittance), the strokes x_m = v_m / (i m omega_0) about their equilibrium
values. Sampled at N >= 2 M + 1 points of the period (``points``), such a series is given exactly by its samples (a
real FFT of length N), and the mean of a product of two of them is the mean of their samples.

The response is the database's exact frequency response (``response = "database"``, as the complex-conjugate bound)
or the state-space radiation fit's, which the simulators integrate (``"fit"``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...linear import LinearModel

RESPONSES = ("database", "fit")

HARMONIC_TOLERANCE: float = 1e-6
"""Largest distance of a wave frequency from a whole multiple of omega_0, relative to omega_0."""


@dataclass(frozen=True)
class PeriodicResponse:
    """A linear device's PTO response on the harmonics m = 1 ... M of a periodic record (module docstring).

    Attributes
    ----------
    period : float
        T_r, the record's repeat period [s].
    harmonic : ndarray of int (n_m,)
        The force basis's harmonics m (L ... M).
    omega : ndarray (n_m,)
        Their frequencies m omega_0 [rad/s].
    free_rate : complex ndarray (n_m, n_pto)
        v_e: PTO stroke-rate amplitudes with no PTO force [m/s or rad/s] (zero off the waves' harmonics).
    admittance : complex ndarray (n_m, n_pto, n_pto)
        Y: PTO stroke-rate amplitude per PTO force amplitude [m/s per N or rad/s per N m].
    stroke_at_equilibrium : ndarray (n_pto,)
        The strokes at the static equilibrium, from rest [m or rad].
    points : int
        N, the samples of the period (> 2 M).
    wave_harmonics : ndarray of int
        The harmonics m that carry waves.
    response : str
        "database" or "fit".
    """

    period: float
    harmonic: np.ndarray
    omega: np.ndarray
    free_rate: np.ndarray
    admittance: np.ndarray
    stroke_at_equilibrium: np.ndarray
    points: int
    wave_harmonics: np.ndarray
    response: str

    @property
    def n_harmonics(self) -> int:
        """n_m, the harmonics in the force basis."""
        return int(self.omega.size)

    @property
    def n_pto(self) -> int:
        """Number of PTOs."""
        return int(self.free_rate.shape[1])

    @property
    def time(self) -> np.ndarray:
        """The sample times j T_r / N of the period [s] (N,)."""
        return np.arange(self.points) * self.period / self.points

    def samples(self, amplitudes: np.ndarray) -> np.ndarray:
        """The real signals Re sum_m A_m exp(i omega_m t) at :attr:`time` (N, k) of amplitudes ``A`` (n_m, k) on
        the basis's harmonics."""
        n = self.points
        spectrum = np.zeros((n // 2 + 1, amplitudes.shape[1]), dtype=complex)
        spectrum[self.harmonic] = 0.5 * n * amplitudes
        return np.fft.irfft(spectrum, n=n, axis=0)

    def spectrum(self, samples: np.ndarray) -> np.ndarray:
        """sum_j x_j exp(-i omega_m t_j) (n_m, k) of samples (N, k) on the basis's harmonics (half the amplitude
        times N for signals of those harmonics: :meth:`samples` inverted by 2 / N times this)."""
        return np.fft.rfft(samples, axis=0)[self.harmonic]


def periodic_response(
    model: LinearModel,
    omega: np.ndarray,
    coefficients: np.ndarray,
    period: float,
    *,
    harmonics: int | None = None,
    basis: float = 2.0,
    lowest: int | None = None,
    points: int | None = None,
    response: str = "database",
) -> PeriodicResponse:
    """The PTO response of ``model`` (the open plant) on the harmonics of a record of ``period`` T_r [s] whose wave
    components are ``omega`` [rad/s] (whole multiples of 2 pi / T_r) with excitation ``coefficients`` (n_h, n_w)
    [N, N m].

    Parameters
    ----------
    harmonics : int or None
        M, the force's highest harmonic (default: ``basis`` times the waves' highest).
    basis : float
        The force basis's width relative to the waves' highest harmonic (>= 1; used without ``harmonics``).
    lowest : int or None
        L, the force's lowest harmonic (default: the waves' lowest; 1 for every one).
    points : int or None
        N, samples of the period (default: the least fast FFT length above 2 M + 1).
    response : str
        "database" (the exact frequency response from A(omega) and B(omega)) or "fit" (the model's state-space
        radiation fit, as the simulators integrate it).

    Raises
    ------
    ValueError
        If a wave frequency is not a whole multiple of 2 pi / T_r (or two fall on one harmonic), the basis is
        narrower than the waves, N <= 2 M, the response is unknown, or "fit" is asked of a model without one.
    """
    from scipy.fft import next_fast_len

    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    coefficients = np.asarray(coefficients, dtype=complex)
    if not (isinstance(period, int | float | np.integer | np.floating) and period > 0 and np.isfinite(period)):
        raise ValueError(f"period must be positive and finite [s]; got {period!r}")
    if response not in RESPONSES:
        raise ValueError(f"response must be one of {RESPONSES}; got {response!r}")
    if coefficients.shape != (model.hydro_jacobian.shape[0], omega.size) or omega.size == 0:
        raise ValueError(
            f"coefficients must be (n_h, n_omega) = ({model.hydro_jacobian.shape[0]}, {omega.size}) with at least "
            f"one wave component; got {coefficients.shape}"
        )
    omega0 = 2 * np.pi / period
    index = np.rint(omega / omega0).astype(np.int64)
    if np.any(index < 1) or np.max(np.abs(omega / omega0 - index)) > HARMONIC_TOLERANCE:
        raise ValueError(
            f"the wave frequencies must be whole multiples of 2 pi / period = {omega0:.6g} rad/s (a periodic record "
            f"of {period:.6g} s); the farthest is {np.max(np.abs(omega / omega0 - index)):.3g} omega_0 off"
        )
    if np.unique(index).size != index.size:
        raise ValueError("two wave components fall on the same harmonic of the record")
    top = int(index.max())
    if harmonics is None:
        if not basis >= 1:
            raise ValueError(f"basis must be >= 1 (the force spans at least the waves' harmonics); got {basis!r}")
        harmonics = int(np.ceil(basis * top))
    if not (isinstance(harmonics, int | np.integer) and harmonics >= top):
        raise ValueError(f"harmonics must be a whole number >= the waves' highest harmonic {top}; got {harmonics!r}")
    m = int(harmonics)
    low = int(index.min()) if lowest is None else lowest
    if not (isinstance(low, int | np.integer) and 1 <= low <= index.min()):
        raise ValueError(
            f"lowest must be a whole number from 1 to the waves' lowest harmonic {index.min()}; got {low!r}"
        )
    n = next_fast_len(2 * m + 2, real=True) if points is None else int(points)
    if n <= 2 * m:
        raise ValueError(f"points must exceed 2 x harmonics = {2 * m}; got {n}")
    harmonic = np.arange(low, m + 1)
    w = omega0 * harmonic
    z = _dynamic_stiffness(model, w, response)
    g = model.pto_jacobian
    forcing = np.zeros((harmonic.size, model.mass.shape[0]), dtype=complex)
    forcing[index - low] = (model.hydro_jacobian.T @ coefficients).T
    inputs = np.broadcast_to(g.T.astype(complex), (harmonic.size, *g.T.shape))
    solved = np.linalg.solve(z, np.concatenate([forcing[:, :, None], inputs], axis=2))
    moving = g if model.held is None else g * ~model.held  # a held coordinate has no rate
    rate = 1j * w[:, None, None] * (moving @ solved)  # (n_m, n_pto, 1 + n_pto)
    return PeriodicResponse(
        period=float(period), harmonic=harmonic, omega=w, free_rate=rate[:, :, 0], admittance=rate[:, :, 1:],
        stroke_at_equilibrium=np.asarray(model.pto_stroke, dtype=float).copy(), points=n,
        wave_harmonics=np.sort(index), response=response,
    )  # fmt: skip


def _dynamic_stiffness(model: LinearModel, omega: np.ndarray, response: str) -> np.ndarray:
    """Z(omega) (n_w, nv, nv) of the open plant: the database's, or with the state-space fit's memory
    K_hat(omega) = C_r (i omega - A_r)^-1 B_r in place of B(omega) + i omega (A(omega) - A_inf)."""
    if response == "database":
        return model.dynamic_stiffness(omega)
    if model.radiation is None:
        raise ValueError('response "fit" needs a model with a state-space radiation fit')
    bw = model.hydro_jacobian
    memory = model.radiation.frequency_response(omega)  # (n_w, n_h, n_h)
    if model.held is not None:  # held coordinates: no rate, no acceleration (their columns of M and C out)
        kept = (~model.held).astype(float)
        return (
            -(omega**2)[:, None, None] * (model.mass * kept)[None]
            + 1j * omega[:, None, None] * ((model.damping * kept)[None] + bw.T @ memory @ (bw * kept))
            + model.stiffness[None]
        )
    return (
        -(omega**2)[:, None, None] * model.mass[None]
        + 1j * omega[:, None, None] * (model.damping[None] + bw.T @ memory @ bw)
        + model.stiffness[None]
    )
