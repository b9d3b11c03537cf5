"""Sums of wave components on a uniform time grid, block by block, at a cost per time and a memory that depend on
neither the number of components nor where the block lies in the record (a chirp-z transform per block).

A periodic record sampled at a divisor of its period has components that are harmonics of it on the grid of times
t_n = n tau: omega_k tau / (2 pi) = m_k / P with integers m_k and a period of P samples. On the block of times
n = n0 + j, j = 0 ... M - 1, with u = m_k - m0 in [0, W) counted from the lowest harmonic m0,

    sum_k C_k exp(2 pi i m_k n / P) = exp(2 pi i m0 n / P) sum_u c_u exp(2 pi i u j / P),
    c_u = C_u exp(2 pi i u n0 / P),

and with u j = (u^2 + j^2 - (j - u)^2) / 2 (Bluestein's chirp-z transform) the inner sum is exp(i pi j^2 / P)
times the convolution of c_u exp(i pi u^2 / P) with exp(-i pi v^2 / P): two FFTs of length L >= M + W - 1 per row
and block (the chirp's transform is made once per FFT length; a call for fewer samples than a block transforms a
length fitted to them) and W products to move the components to the block's start. Every phase is reduced modulo
2 P in integers, so its round-off does not grow with the time or the harmonic number: the values equal the direct
sum of the components to the round-off of the FFTs.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

BLOCK_VALUES: int = 2**22
"""Values (rows x samples) of one block of results (32 MB real): blocks are as long as this allows, and at
least as long as the band of harmonics W (then the FFT length is at most twice the block)."""

WORK_VALUES: int = 2**19
"""Complex values (rows x FFT length) of the FFTs' work array (8 MB): the rows are transformed in groups of this
size, which bounds the transforms' temporaries."""


def fast_length(n: int) -> int:
    """The smallest 2^a 3^b 5^c >= ``n`` >= 1 (a length numpy's FFT is fast at)."""
    best = 1 << max(0, int(n) - 1).bit_length()  # the power of 2
    p5 = 1
    while p5 < best:
        p35 = p5
        while p35 < best:
            length = p35
            while length < n:
                length *= 2
            best = min(best, length)
            p35 *= 3
        p5 *= 5
    return best


PHASE_TOL: float = 1e-10
"""Largest drift from integers of the components' harmonic numbers omega_k tau P / (2 pi) [cycles per period]: the
phase error stays below 2 pi 1e-10 per period of the record (round-off of the harmonic numbers is about 1e-13)."""


def harmonic_period(omega: np.ndarray, tau: float) -> int | None:
    """The number of samples P after which every component of frequency ``omega`` [rad/s] repeats on the grid of
    step ``tau`` [s] (omega_k tau P / (2 pi) integers within PHASE_TOL), or None."""
    omega = np.asarray(omega, dtype=float)
    if omega.size == 0 or tau <= 0:
        return None
    cycles = np.sort(omega) * tau / (2 * np.pi)  # cycles per sample
    gaps = np.diff(cycles)
    base = float(gaps[gaps > 1e-12 * cycles[-1]].min()) if omega.size > 1 and np.any(gaps > 0) else float(cycles[0])
    period = round(1.0 / base)
    if period < 1:
        return None
    harmonics = cycles * period
    if np.max(np.abs(harmonics - np.round(harmonics))) > PHASE_TOL:
        return None
    return period


def harmonic_numbers(omega: np.ndarray, tau: float, period: int) -> np.ndarray:
    """The harmonic numbers m_k = omega_k tau P / (2 pi) (int64) of the period ``period`` [samples] (see
    :func:`harmonic_period`)."""
    return np.round(np.asarray(omega, dtype=float) * tau * period / (2 * np.pi)).astype(np.int64)


def _phase(r: np.ndarray, period: int) -> np.ndarray:
    """exp(i pi r / P) for integers ``r`` (reduced modulo 2 P first)."""
    return np.exp(1j * np.pi * (np.mod(r, 2 * period) / period))


class BlockSum:
    """sum_k C[j, k] exp(2 pi i m_k n / P) for every row j on blocks of consecutive samples n (see the module
    docstring): the components' sum on the times n tau of a grid on which they are harmonics.

    Parameters
    ----------
    coefficients : complex ndarray (n_rows, n)
        C[j, k].
    harmonic : int ndarray (n,)
        m_k: the components' harmonic numbers of the period (taken modulo ``period``; equal ones add up).
    period : int
        P, the period [samples].
    block : int or None
        Samples per block M (default: BLOCK_VALUES / n_rows, at least the band of harmonics W); a call for more
        samples is made of several blocks, a call for fewer of one block just long enough for them (its FFT
        length from the call's samples, not from M).

    Attributes
    ----------
    block : int
        Samples per block M.
    length : int
        FFT length L >= M + W - 1.
    """

    def __init__(self, coefficients: np.ndarray, harmonic: np.ndarray, period: int, block: int | None = None) -> None:
        coefficients = np.atleast_2d(np.asarray(coefficients, dtype=complex))
        harmonic = np.asarray(harmonic, dtype=np.int64)
        if coefficients.shape[1] != harmonic.size or period < 1 or (block is not None and block < 1):
            raise ValueError(
                f"one harmonic number per coefficient column, a positive period and block are needed; got "
                f"{harmonic.size} harmonics for {coefficients.shape[1]} columns, period {period}, block {block}"
            )
        harmonic = np.mod(harmonic, period)
        self.period, self.rows = int(period), coefficients.shape[0]
        self.lowest = int(harmonic.min()) if harmonic.size else 0
        u = harmonic - self.lowest
        width = int(u.max()) + 1 if harmonic.size else 1
        self.spectrum = np.zeros((self.rows, width), dtype=complex)  # C on the band of harmonics
        np.add.at(self.spectrum.T, u, coefficients.T)
        if block is None:
            block = max(width, BLOCK_VALUES // max(1, self.rows))
        self.band = np.arange(width, dtype=np.int64)
        self.chirp_in = _phase(self.band * self.band, self.period)  # exp(i pi u^2 / P)
        self._plans: dict[int, tuple[int, np.ndarray, np.ndarray]] = {}
        self.length = fast_length(block + width - 1)
        self.block = self.length - width + 1  # (the FFT length's slack lengthens the block)

    def _plan(self, length: int) -> tuple[int, np.ndarray, np.ndarray]:
        """For the FFT length ``length`` (>= W): the block it transforms (``length`` - W + 1 samples), the
        transform of the chirp exp(-i pi v^2 / P) on it (circular) and exp(i pi j^2 / P) on the block; made once
        per length, on first use."""
        if length not in self._plans:
            width = self.band.size
            block = length - width + 1
            v = np.arange(-(width - 1), block, dtype=np.int64)
            kernel = np.zeros(length, dtype=complex)
            kernel[np.mod(v, length)] = _phase(-(v * v), self.period)
            j = np.arange(block, dtype=np.int64)
            self._plans[length] = (block, np.fft.fft(kernel), _phase(j * j, self.period))
        return self._plans[length]

    def fft_length(self, m: int) -> int:
        """The FFT length a call for ``m`` samples transforms: :attr:`length`, or for fewer samples than a block
        the smallest fast length that holds them."""
        width = self.band.size
        return self.length if m >= self.block else min(self.length, fast_length(max(1, m) + width - 1))

    @classmethod
    def on_grid(
        cls, coefficients: np.ndarray, omega: np.ndarray, tau: float, block: int | None = None
    ) -> BlockSum | None:
        """sum_k C[j, k] exp(i omega_k t) on the times t = n tau [s], or None when the frequencies ``omega``
        [rad/s] are not harmonics of one period on that grid (a record that does not repeat)."""
        period = harmonic_period(omega, tau)
        if period is None:
            return None
        return cls(coefficients, harmonic_numbers(omega, tau, period), period, block)

    def __call__(self, n0: int, m: int) -> np.ndarray:
        """The sums at samples ``n0`` to ``n0 + m - 1``, complex (n_rows, m)."""
        out = np.empty((self.rows, m), dtype=complex)
        for rows, part, values in self._parts(n0, m):
            out[rows, part] = values
        return out

    def real(self, n0: int, m: int) -> np.ndarray:
        """The real parts of the sums at samples ``n0`` to ``n0 + m - 1``, time-major (m, n_rows), C-contiguous
        (the layout the time loop reads; no complex array of the whole block is made)."""
        out = np.empty((m, self.rows))
        for rows, part, values in self._parts(n0, m):
            out[part, rows] = values.real.T
        return out

    def _parts(self, n0: int, m: int) -> Iterator[tuple[slice, slice, np.ndarray]]:
        """The sums by groups of rows and blocks of samples: (rows, samples from ``n0``, complex values)."""
        if m < 0:
            raise ValueError(f"the number of samples must be >= 0; got {m!r}")
        width = self.band.size
        length = self.fft_length(m)
        block, kernel_fft, chirp_out = self._plan(length)
        group = max(1, min(self.rows, WORK_VALUES // length))
        work = np.zeros((group, length), dtype=complex)
        for start in range(0, m, block):
            count = min(block, m - start)
            n = int(n0) + start
            shift = _phase(2 * self.band * n, self.period) * self.chirp_in  # exp(2 pi i u n / P) exp(i pi u^2 / P)
            j = np.arange(count, dtype=np.int64)
            # exp(2 pi i m0 (n + j) / P) exp(i pi j^2 / P)
            after = _phase(2 * self.lowest * np.mod(n + j, self.period), self.period) * chirp_out[:count]
            for r0 in range(0, self.rows, group):
                rows = slice(r0, min(self.rows, r0 + group))
                k = rows.stop - r0
                np.multiply(self.spectrum[rows], shift, out=work[:k, :width])
                work[:k, width:] = 0.0
                spectrum = np.fft.fft(work[:k], axis=1)
                spectrum *= kernel_fft
                values = np.fft.ifft(spectrum, axis=1)[:, :count]
                values *= after
                yield rows, slice(start, start + count), values
