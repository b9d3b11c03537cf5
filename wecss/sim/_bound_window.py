"""The complex-conjugate power bound on the run's own record and window.

The spectral bound (the sum over the scene's wave components of |F|^2 / (8 B) on one PTO) is an expectation: the
components are orthogonal over the whole record, not over the statistics window (its last part), so a run's mean
power over the window may exceed it by chance. Here the excitation the run saw over the window, at its steps (the
start ramp included), is taken as one period of a periodic record: its Fourier components (frequencies 2 pi m /
T_window, orthogonal over the window by construction) within the band of the scene's wave components have their own
complex-conjugate bound, the best mean power of the linear plant over that record. A run's share of it compares
like with like.
"""

from __future__ import annotations

import numpy as np

from ..control import ControlledScene
from ..control.design import PowerBound, power_bound
from ._record import stats_start

SHARE_TOLERANCE: float = 0.02
"""How far above 1 a run's share of the bound on its own record and window may lie without a note: the bound is
the linear model's over a periodic record; the run's power carries its time step's error, its nonlinear terms and
the energy stored in the device at the window's ends (a relative 2 %)."""

NEGLIGIBLE_SHARE: float = 1e-9
"""Fourier components of the window's excitation below this share of the largest (in squared amplitude summed over
the hydrodynamic DOFs) are left out of the bound."""


BAND_EDGE: float = 1e-6
"""How far outside the band of the scene's wave components a Fourier component of the window may lie and still
count (as a share of the window's frequency step): rounding, not leakage."""


def window_components(controlled: ControlledScene) -> tuple[np.ndarray, np.ndarray]:
    """The Fourier components of the excitation over the run's statistics window: frequencies 2 pi m / T [rad/s]
    (T the window's length: its steps times the step; the mean and the Nyquist term left out) within the band of
    the scene's wave components (outside it the window's leakage meets radiation damping near zero, whose bound
    |F|^2 / (8 B) means nothing), and their amplitudes (n_h, n_omega) [N, N m] as Re[F exp(i omega t)]; negligible
    ones left out."""
    exc = controlled.excitation
    if exc is None:
        raise ValueError("calm water has no power bound")
    start = stats_start(controlled)
    time = np.arange(start, controlled.n_steps + 1) * controlled.dt
    n = time.size
    omega = 2 * np.pi * np.arange(n // 2 + 1) / (n * controlled.dt)
    sampled = exc.sampled(controlled.dt)  # by blocks, at a cost that does not grow with the components
    force = exc.force(time) if sampled is None else sampled(start, n).T
    # the band's ends widened by a small share of the window's frequency step: a window of whole periods of a
    # regular wave has its frequency on the window's grid only to rounding
    edge = BAND_EDGE * 2 * np.pi / (n * controlled.dt)
    in_band = (omega >= exc.omega.min() - edge) & (omega <= exc.omega.max() + edge)
    band = (omega > 0) & (np.arange(omega.size) < (n + 1) // 2) & in_band
    # one row at a time, the band's components only: a long run's window would otherwise hold a few copies of the
    # whole window's transform (0.5 GB of a 10,000-Tp run's peak memory)
    phase = np.exp(-1j * omega[band] * time[0])
    amplitude = np.empty((force.shape[0], int(np.count_nonzero(band))), dtype=complex)
    for row in range(force.shape[0]):
        amplitude[row] = 2 * np.fft.rfft(force[row])[band] / n * phase
    energy = np.sum(np.abs(amplitude) ** 2, axis=0)
    keep = energy >= NEGLIGIBLE_SHARE * (energy.max() if energy.size else 0.0)
    return omega[band][keep], amplitude[:, keep]


def window_bound(controlled: ControlledScene) -> PowerBound:
    """The complex-conjugate bound of the excitation over the run's statistics window taken as a periodic record
    (:func:`window_components`), on the open plant [W].

    Raises
    ------
    ValueError
        In calm water, for a window without components in the database's band, or where the bound does not exist.
    """
    omega, amplitude = window_components(controlled)
    if not omega.size:
        raise ValueError("the excitation over the statistics window has no component in the sea state's band")
    return power_bound(controlled.control_context.linear_model(), omega, amplitude)
