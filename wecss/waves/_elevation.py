"""Sea states as sums of regular components: regular waves, random-phase irregular waves (periodic or not),
measured elevation records, a cosine ramp, and the dropping of components that carry negligible energy.

A component k has angular frequency omega_k and complex amplitude A_k at the reference point x = 0, so that the
undisturbed elevation is eta(x, t) = sum_k Re[A_k exp(i (omega_k t - k_k x))] for waves travelling along +x, and
at a point (x, y) for a component travelling in the direction beta_k, x is replaced by x cos beta_k + y sin beta_k
(:meth:`WaveComponents.at_point`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..constants import GRAVITY
from ._blocks import harmonic_numbers, harmonic_period
from ._spectra import Spectrum, wavenumber

DEFAULT_ENERGY_THRESHOLD: float = 1e-4
"""Default share of the variance that the dropped (smallest) components may carry together [-]."""


@dataclass(frozen=True)
class DroppedComponents:
    """What :func:`drop_negligible` removed: how many components and what share of the variance."""

    count: int
    kept: int
    energy_share: float
    threshold: float

    def __str__(self) -> str:
        return (
            f"dropped {self.count} of {self.count + self.kept} wave components carrying {self.energy_share:.2e} "
            f"of the variance (threshold {self.threshold:.0e})"
        )


@dataclass(frozen=True)
class WaveComponents:
    """A sea state as regular components.

    Attributes
    ----------
    omega : ndarray (n,)
        Angular frequencies [rad/s], positive.
    amplitude : complex ndarray (n,)
        Complex amplitudes A_k at x = 0 [m]: Re[A_k exp(i omega_k t)].
    direction : float
        Direction of propagation [rad] (0: along +x).
    repeat_period : float or None
        The record repeats with this period [s] (periodic records: 2 pi / d_omega), or None.
    dropped : DroppedComponents or None
        What was dropped when the components were made.
    headings : ndarray (n,) or None
        Direction of propagation of each component [rad] in a directional (short-crested) sea, where
        ``direction`` is the mean (``wecss.waves.spread``); None: every component travels along ``direction``.
    """

    omega: np.ndarray
    amplitude: np.ndarray
    direction: float = 0.0
    repeat_period: float | None = None
    dropped: DroppedComponents | None = None
    headings: np.ndarray | None = None

    def __post_init__(self) -> None:
        omega = np.atleast_1d(np.asarray(self.omega, dtype=float))
        amplitude = np.atleast_1d(np.asarray(self.amplitude, dtype=complex))
        if omega.shape != amplitude.shape or omega.ndim != 1:
            raise ValueError(f"omega and amplitude must be 1-D of one length; got {omega.shape} and {amplitude.shape}")
        if np.any(omega <= 0) or not np.all(np.isfinite(omega)):
            raise ValueError("wave component frequencies must be positive and finite [rad/s]")
        if abs(self.direction) > 2 * np.pi + 1e-12:
            raise ValueError(f"direction is in radians; got {self.direction!r}, which looks like degrees")
        object.__setattr__(self, "omega", omega)
        object.__setattr__(self, "amplitude", amplitude)
        if self.headings is not None:
            headings = np.atleast_1d(np.asarray(self.headings, dtype=float))
            if headings.shape != omega.shape or not np.all(np.isfinite(headings)):
                raise ValueError(
                    f"headings must be finite, one per component [rad]; got shape {headings.shape} for {omega.size}"
                )
            object.__setattr__(self, "headings", headings)

    @property
    def directional(self) -> bool:
        """The components travel in several directions (``headings`` per component)."""
        return self.headings is not None

    @property
    def component_directions(self) -> np.ndarray:
        """Direction of propagation of every component [rad] (n,)."""
        return self.headings if self.headings is not None else np.full(self.omega.size, float(self.direction))

    def at_point(self, x: float, y: float, depth: float = np.inf, g: float = GRAVITY) -> np.ndarray:
        """Complex amplitudes of the components at the point (x, y) [m] of the still water plane, in water of
        ``depth`` [m]: A_k exp(-i k_k (x cos beta_k + y sin beta_k)), k_k from the dispersion relation (n,)."""
        beta = self.component_directions
        k = wavenumber(self.omega, depth, g)
        return self.amplitude * np.exp(-1j * k * (x * np.cos(beta) + y * np.sin(beta)))

    def elevation_at(
        self, time: np.ndarray, x: float, y: float, depth: float = np.inf, g: float = GRAVITY
    ) -> np.ndarray:
        """Undisturbed elevation [m] at the point (x, y) [m] at ``time`` [s], in water of ``depth`` [m] (no ramp);
        at the origin it is :meth:`elevation`."""
        coefficients = self.at_point(x, y, depth, g)
        return np.real(evaluate(coefficients[None, :], self.omega, np.asarray(time, dtype=float)))[0]

    @property
    def variance(self) -> float:
        """Variance of the elevation, sum |A_k|^2 / 2 [m^2]."""
        return float(np.sum(np.abs(self.amplitude) ** 2) / 2)

    def elevation(self, time: np.ndarray, *, chunk: int = 2_000_000) -> np.ndarray:
        """Undisturbed elevation at x = 0 [m] at ``time`` [s] (vectorised, in chunks of ``chunk`` products)."""
        return np.real(evaluate(self.amplitude[None, :], self.omega, np.asarray(time, dtype=float), chunk=chunk))[0]


def evaluate(coefficients: np.ndarray, omega: np.ndarray, time: np.ndarray, *, chunk: int = 2_000_000) -> np.ndarray:
    """sum_k C[j, k] exp(i omega_k t) for every row j and time t, as complex (n_rows, n_times).

    Take the real part for Re[...] signals. Three ways, fastest first:

    - uniform times on which the components are periodic (omega_k dt / 2 pi = m_k / P with integers m_k and a
      period of P <= FFT_MAX_PERIOD_FACTOR times the number of times, as for periodic records sampled at a
      divisor of their period): one inverse FFT of length P per row;
    - other uniform times: phasors from a product recurrence, exp(i omega (t0 + k dt)) = exp(i omega t0)
      exp(i omega dt)^k, restarted from an exact exponential every RECURRENCE_RESTART steps (relative error below
      1e-13), in chunks of about ``chunk`` complex products;
    - any times: one complex exponential per product, in chunks.
    """
    coefficients = np.asarray(coefficients)
    omega = np.asarray(omega, dtype=float)
    time = np.atleast_1d(time)
    uniform = time.size > 2 and np.allclose(np.diff(time), time[1] - time[0], rtol=1e-9, atol=0.0)
    if uniform:
        period = _fft_period(omega, float(time[1] - time[0]), time.size)
        if period is not None:
            return _evaluate_fft(coefficients, omega, time, period)
    out = np.empty((coefficients.shape[0], time.size), dtype=complex)
    step = max(1, chunk // max(1, omega.size))
    for start in range(0, time.size, step):
        t = time[start : start + step]
        if uniform and t.size > 2:
            phase = np.empty((omega.size, t.size), dtype=complex)
            rotation = np.exp(1j * omega * (time[1] - time[0]))
            for k0 in range(0, t.size, RECURRENCE_RESTART):
                k1 = min(t.size, k0 + RECURRENCE_RESTART)
                block = np.broadcast_to(rotation[:, None], (omega.size, k1 - k0)).copy()
                block[:, 0] = np.exp(1j * omega * t[k0])
                phase[:, k0:k1] = np.cumprod(block, axis=1)
        else:
            phase = np.exp(1j * np.outer(omega, t))
        out[:, start : start + step] = coefficients @ phase
    return out


FFT_MAX_PERIOD_FACTOR: int = 4
"""The FFT path of :func:`evaluate` is taken when the period in steps is at most this many times the number of
times (else the recurrence is cheaper)."""


def _fft_period(omega: np.ndarray, dt: float, n_times: int) -> int | None:
    """The number of steps P after which every component repeats on the grid of step ``dt``, or None (also when
    it is more than FFT_MAX_PERIOD_FACTOR times ``n_times`` plus 1024)."""
    period = harmonic_period(omega, dt)
    if period is None or period > FFT_MAX_PERIOD_FACTOR * n_times + 1024:
        return None
    return period


def _evaluate_fft(coefficients: np.ndarray, omega: np.ndarray, time: np.ndarray, period: int) -> np.ndarray:
    """:func:`evaluate` on uniform times by one inverse FFT of length ``period`` per row (see there)."""
    dt = time[1] - time[0]
    harmonic = harmonic_numbers(omega, dt, period) % period
    spectrum = np.zeros((coefficients.shape[0], period), dtype=complex)
    shifted = coefficients * np.exp(1j * omega * time[0])[None, :]
    if np.unique(harmonic).size == harmonic.size:
        spectrum[:, harmonic] = shifted
    else:  # components on one grid frequency add up
        np.add.at(spectrum.T, harmonic, shifted.T)
    values = np.fft.ifft(spectrum, axis=1) * period  # sum_m S_m exp(2 pi i m n / P), n = 0 ... P - 1
    return values[:, np.arange(time.size) % period]


RECURRENCE_RESTART: int = 256
"""Steps between exact exponentials in :func:`evaluate`'s phasor recurrence."""


def regular(height: float, period: float, *, phase: float = 0.0, direction: float = 0.0) -> WaveComponents:
    """A regular wave of height ``height`` [m] (crest to trough) and ``period`` [s], phase [rad] at t = 0, x = 0.

    Raises
    ------
    ValueError
        On non-positive height or period.
    """
    if not (height > 0 and period > 0):
        raise ValueError(f"height and period must be positive; got {height!r} m and {period!r} s")
    return WaveComponents(
        np.array([2 * np.pi / period]), np.array([height / 2 * np.exp(1j * phase)]), direction, repeat_period=period
    )


def irregular(
    spectrum: Spectrum,
    *,
    d_omega: float,
    omega_max: float,
    omega_min: float | None = None,
    seed: int | None = None,
    periodic: bool = True,
    energy_threshold: float = DEFAULT_ENERGY_THRESHOLD,
    direction: float = 0.0,
) -> WaveComponents:
    """Random-phase components of a spectrum, |A_k| = sqrt(2 S(omega_k) d_omega), phases uniform on [0, 2 pi).

    Parameters
    ----------
    spectrum : Spectrum
    d_omega : float
        Frequency step [rad/s]. Periodic records use omega_k = k d_omega and repeat every 2 pi / d_omega;
        otherwise each frequency is drawn uniformly within its bin, so that the record does not repeat.
    omega_max, omega_min : float
        Range of the components [rad/s] (default minimum: d_omega).
    seed : int or None
        Seed of ``numpy.random.default_rng``: the same seed gives the same record on every platform.
    energy_threshold : float
        Components carrying together at most this share of the variance are dropped (smallest first).
    direction : float
        Direction of propagation [rad].

    Raises
    ------
    ValueError
        On a non-positive step or an empty range.
    """
    if not (d_omega > 0 and omega_max > 0):
        raise ValueError(f"d_omega and omega_max must be positive [rad/s]; got {d_omega!r} and {omega_max!r}")
    lo = d_omega if omega_min is None else omega_min
    k = np.arange(max(1, int(np.ceil(lo / d_omega - 1e-9))), int(np.floor(omega_max / d_omega + 1e-9)) + 1)
    if k.size == 0:
        raise ValueError(f"no frequency k * {d_omega} lies in [{lo}, {omega_max}] rad/s")
    rng = np.random.default_rng(seed)
    omega = k * d_omega
    if not periodic:
        omega = omega + (rng.uniform(size=omega.size) - 0.5) * d_omega
    phases = rng.uniform(0.0, 2 * np.pi, size=omega.size)
    magnitude = np.sqrt(2 * spectrum.density(omega) * d_omega)
    components = WaveComponents(
        omega, magnitude * np.exp(1j * phases), direction, repeat_period=2 * np.pi / d_omega if periodic else None
    )
    return drop_negligible(components, energy_threshold)


MIN_ELEVATION_SAMPLES: int = 4
"""Fewest samples of a measured elevation record."""


def from_elevation(
    time: np.ndarray, elevation: np.ndarray, *, energy_threshold: float = DEFAULT_ENERGY_THRESHOLD
) -> WaveComponents:
    """Components of a measured elevation record (uniform sampling), by FFT: the record repeats with its length.

    The mean is removed.

    Parameters
    ----------
    time : (n,)
        Sample times [s], increasing with a constant step (relative spread below 1e-6).
    elevation : (n,)
        Free-surface elevation [m], finite.

    Raises
    ------
    ValueError
        On records of other shapes or fewer than MIN_ELEVATION_SAMPLES samples, non-finite values, or times that do
        not increase with one step (the message gives what was received).
    """
    time = np.asarray(time, dtype=float)
    elevation = np.asarray(elevation, dtype=float)
    if time.ndim != 1 or time.shape != elevation.shape:
        raise ValueError(f"time and elevation must be 1-D of one length; got shapes {time.shape} and {elevation.shape}")
    if time.size < MIN_ELEVATION_SAMPLES:
        raise ValueError(f"the record has {time.size} samples; at least {MIN_ELEVATION_SAMPLES} are needed")
    for label, values in (("time", time), ("elevation", elevation)):
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            rows = ", ".join(str(int(k) + 1) for k in bad[:5]) + (" ..." if bad.size > 5 else "")
            raise ValueError(
                f"{label} has {bad.size} values that are not finite numbers (NaN or inf) at samples {rows}; "
                "every sample must be finite (fill or cut the gaps)"
            )
    dt = np.diff(time)
    if not np.all(dt > 0):
        k = int(np.flatnonzero(dt <= 0)[0])
        raise ValueError(f"time must increase: sample {k + 2} ({time[k + 1]:.6g} s) follows {time[k]:.6g} s")
    if not np.allclose(dt, dt[0], rtol=1e-6, atol=0):
        k = int(np.argmax(np.abs(dt - dt[0])))
        raise ValueError(
            f"the record must be sampled uniformly in time: the step is {dt[0]:.6g} s at the start but "
            f"{dt[k]:.6g} s between samples {k + 1} and {k + 2} (steps range {dt.min():.6g}-{dt.max():.6g} s); "
            "resample it onto a uniform grid"
        )
    n = time.size
    spectrum = np.fft.rfft(elevation - elevation.mean())
    omega = 2 * np.pi * np.fft.rfftfreq(n, dt[0])
    amplitude = 2 * spectrum / n * np.exp(-1j * omega * time[0])
    if n % 2 == 0:
        amplitude[-1] /= 2  # Nyquist term appears once
    keep = omega > 0
    components = WaveComponents(omega[keep], amplitude[keep], repeat_period=n * dt[0])
    return drop_negligible(components, energy_threshold)


def drop_negligible(components: WaveComponents, threshold: float = DEFAULT_ENERGY_THRESHOLD) -> WaveComponents:
    """Drop the smallest components while together they carry at most ``threshold`` of the variance."""
    if not 0 <= threshold < 1:
        raise ValueError(f"threshold is a share of the variance in [0, 1); got {threshold!r}")
    energy = np.abs(components.amplitude) ** 2
    total = energy.sum()
    if total == 0:
        return components
    order = np.argsort(energy)
    cumulative = np.cumsum(energy[order]) / total
    n_drop = int(np.searchsorted(cumulative, threshold, side="right"))
    keep = np.sort(order[n_drop:])
    report = DroppedComponents(n_drop, keep.size, float(cumulative[n_drop - 1]) if n_drop else 0.0, threshold)
    headings = None if components.headings is None else components.headings[keep]
    return WaveComponents(
        components.omega[keep],
        components.amplitude[keep],
        components.direction,
        components.repeat_period,
        report,
        headings,
    )


@dataclass(frozen=True)
class Ramp:
    """Cosine ramp from 0 to 1 over ``duration`` [s]: r(t) = (1 - cos(pi t / duration)) / 2 for t < duration."""

    duration: float

    def __post_init__(self) -> None:
        if not self.duration >= 0:
            raise ValueError(f"ramp duration must be >= 0 [s]; got {self.duration!r}")

    def __call__(self, time: np.ndarray) -> np.ndarray:
        t = np.asarray(time, dtype=float)
        if self.duration == 0:
            return np.ones_like(t)
        return np.where(t >= self.duration, 1.0, 0.5 * (1 - np.cos(np.pi * np.clip(t, 0.0, None) / self.duration)))
