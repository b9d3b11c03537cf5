"""The steady-state Kalman filter of a device's linear model augmented with a bank of noise-driven oscillators whose
outputs are generalised forces on it (the excitation): the exact discrete model at the control period (the PTO
force held, the oscillators' noise integrated by Van Loan's method) and the gain from the discrete algebraic
Riccati equation. The estimators of the excitation (:mod:`._estimation`, :mod:`._wave_estimation`) build their
oscillator banks and measurements and share this.

The filter's plant decays at LEAK times the lowest oscillator frequency on top of its own damping, so that modes at
zero frequency (a free surge and its rate: no restoring force, no radiation damping at DC), which the measurements
cannot see, do not leave the Riccati equation without a solution; wave-frequency dynamics change by 1e-3.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm, solve_discrete_are

from ...linear import LinearModel

LEAK: float = 1e-3
"""Extra decay rate of the filter's plant model, relative to the lowest oscillator frequency [-]."""


@dataclass(frozen=True)
class SteadyKalman:
    """One exact step of the augmented system z = (plant state, oscillator states) and its steady-state gain.

    Attributes
    ----------
    phi : ndarray (n + m, n + m)
        State transition over a control period.
    gamma : ndarray (n + m, n_pto)
        Response to the PTO force held over the period.
    measure : ndarray (n_y, n + m)
        Measured signals as a map of the state.
    gain : ndarray (n + m, n_y)
        Steady-state Kalman gain.
    predicted, corrected : ndarray (n + m, n + m)
        The steady-state error covariance before and after a measurement update.
    """

    phi: np.ndarray
    gamma: np.ndarray
    measure: np.ndarray
    gain: np.ndarray
    predicted: np.ndarray
    corrected: np.ndarray


class RunningFilter:
    """A steady-state Kalman filter at run time, shared by the excitation estimators: the augmented state z (plant
    state, then oscillator states), one predict-and-correct step per control period with the PTO force held since
    the last one, and the plant state's estimate. A subclass calls :meth:`_start` once its :class:`SteadyKalman` is
    built."""

    phi: np.ndarray
    gamma: np.ndarray
    measure: np.ndarray
    gain: np.ndarray
    n_plant: int
    stroke0: np.ndarray
    x: np.ndarray
    _force: np.ndarray

    def _start(self, kalman: SteadyKalman, model: LinearModel) -> None:
        """Keep ``kalman``'s step and gain, the PTO strokes at rest, and start from rest."""
        self.phi, self.gamma, self.measure, self.gain = kalman.phi, kalman.gamma, kalman.measure, kalman.gain
        self.n_plant, self.stroke0 = model.n_states, model.pto_stroke.copy()
        self.x = np.zeros(kalman.phi.shape[0])
        self._force = np.zeros(kalman.gamma.shape[1])

    def _correct(self, stroke: np.ndarray, rate: np.ndarray, *more: np.ndarray) -> None:
        """Predict over the period with the held force, then correct with the measured PTO strokes (from their rest
        positions), rates and any ``more`` measured signals, in the order of ``measure``'s rows."""
        predicted = self.phi @ self.x + self.gamma @ self._force
        parts = [np.asarray(stroke, dtype=float) - self.stroke0, np.asarray(rate, dtype=float)]
        measured = np.concatenate([*parts, *(np.asarray(m, dtype=float) for m in more)])
        self.x = predicted + self.gain @ (measured - self.measure @ predicted)

    def reset(self) -> None:
        """Start again from rest (no excitation known)."""
        self.x[:] = 0.0
        self._force[:] = 0.0

    def hold(self, force: np.ndarray) -> None:
        """The PTO force [N or N m] applied from now until the next update (for a controller that computes its
        force from this update's estimate)."""
        self._force = np.asarray(force, dtype=float).copy()

    @property
    def state(self) -> np.ndarray:
        """The estimated plant state (the linear model's x: xi, xi_dot, radiation states)."""
        return self.x[: self.n_plant].copy()


def steady_kalman(
    model: LinearModel,
    dt: float,
    oscillators: np.ndarray,
    noise: np.ndarray,
    forcing: np.ndarray,
    measure: np.ndarray,
    measurement_std: np.ndarray,
    lowest_frequency: float,
) -> SteadyKalman:
    """The filter of ``model``'s plant (n states) driven by the generalised force ``forcing`` @ z_osc of an
    oscillator bank z_osc' = ``oscillators`` z_osc + white noise of intensity diag(``noise``) (m,) [force^2 s per
    state], measured through ``measure`` (n_y, n) (a map of the plant state; (n_y, n + m) when the measurements
    see oscillator states too, such as a bias) with noise ``measurement_std``
    (n_y,), stepped every ``dt`` [s]; the leak is LEAK x ``lowest_frequency`` [rad/s]."""
    n = model.n_states
    m = oscillators.shape[0]
    a = np.array(model.state_space.A, dtype=float) - LEAK * lowest_frequency * np.eye(n)
    force_input = model.force_input  # generalised force -> state derivative (n, nv)
    big = np.zeros((n + m, n + m))
    big[:n, :n] = a
    big[:n, n:] = force_input @ forcing
    big[n:, n:] = oscillators
    q_big = np.zeros((n + m, n + m))
    q_big[n:, n:] = np.diag(noise)
    van_loan = np.zeros((2 * (n + m), 2 * (n + m)))
    van_loan[: n + m, : n + m] = -big
    van_loan[: n + m, n + m :] = q_big
    van_loan[n + m :, n + m :] = big.T
    e = expm(van_loan * dt)
    phi = e[n + m :, n + m :].T
    q_d = phi @ e[: n + m, n + m :]
    pto_input = force_input @ model.pto_jacobian.T  # (n, n_pto)
    n_pto = pto_input.shape[1]
    held = np.zeros((n + m + n_pto, n + m + n_pto))
    held[: n + m, : n + m] = big * dt
    held[:n, n + m :] = pto_input * dt
    gamma = expm(held)[: n + m, n + m :]
    full_measure = np.zeros((measure.shape[0], n + m))
    full_measure[:, : measure.shape[1]] = measure  # a map of the plant state, or of the whole augmented state
    r = np.diag(np.asarray(measurement_std, dtype=float) ** 2)
    q_d = 0.5 * (q_d + q_d.T) + 1e-12 * np.max(np.abs(q_d)) * np.eye(n + m)
    p = solve_discrete_are(phi.T, full_measure.T, q_d, r)
    innovation = full_measure @ p @ full_measure.T + r
    gain = p @ full_measure.T @ np.linalg.inv(innovation)
    return SteadyKalman(phi, gamma, full_measure, gain, p, p - gain @ full_measure @ p)


def pto_measure(model: LinearModel) -> np.ndarray:
    """The PTO strokes (from the equilibrium), then their rates, as a map (2 n_pto, n) of the plant state."""
    g = model.pto_jacobian
    n_pto, nv = g.shape
    measure = np.zeros((2 * n_pto, model.n_states))
    measure[:n_pto, :nv] = g
    measure[n_pto:, nv : 2 * nv] = g
    return measure
