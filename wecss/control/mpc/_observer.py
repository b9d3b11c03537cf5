"""A state observer for a known disturbance: the steady-state Kalman filter of a device's linear model whose
generalised disturbance force is known (the scene's own excitation, as a perfect preview gives it) and whose PTO
strokes and rates are measured.

Between two updates the model steps exactly (``HorizonModel.step``: the PTO force held, the disturbance linear in
time); the process noise is a generalised force held over each period, white from period to period, standing for
what the linear model leaves out (the nonlinear terms, the radiation fit's error). As in
:mod:`wecss.control._estimation`, the filter's model decays at LEAK times its lowest wave frequency on top of the
plant's own damping, so that a free mode (m4-134's surge) does not leave the Riccati equation without a solution.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import solve_discrete_are

from ._estimation import LEAK
from ._horizon import HorizonModel


class StateObserver:
    """Steady-state Kalman filter of the state of a :class:`HorizonModel`'s plant (module docstring).

    Parameters
    ----------
    horizon : HorizonModel
        The plant's exact step at the control period.
    process_std : array_like (nv,)
        Standard deviation of the generalised process-noise force per coordinate [N or N m], held per period.
    measurement_std : array_like (2 n_pto,)
        Standard deviation of the measured strokes, then rates [m or rad; m/s or rad/s].
    stroke0 : array_like (n_pto,)
        Strokes at the equilibrium, from rest [m or rad] (measurements are from rest).
    lowest_frequency : float
        The lowest wave frequency of the sea [rad/s] (for the leak).

    Raises
    ------
    ValueError
        On shapes that disagree or non-positive noise.
    """

    def __init__(
        self,
        horizon: HorizonModel,
        process_std: np.ndarray,
        measurement_std: np.ndarray,
        stroke0: np.ndarray,
        lowest_frequency: float,
    ) -> None:
        n = horizon.phi.shape[0]
        nv = horizon.disturbance_now.shape[1]
        n_pto = horizon.n_pto
        process_std = np.asarray(process_std, dtype=float)
        measurement_std = np.asarray(measurement_std, dtype=float)
        if process_std.shape != (nv,) or not np.all(process_std >= 0):
            raise ValueError(f"process_std: expected {nv} non-negative values; got {process_std!r}")
        if measurement_std.shape != (2 * n_pto,) or not np.all(measurement_std > 0):
            raise ValueError(f"measurement_std: expected {2 * n_pto} positive values; got {measurement_std!r}")
        if not lowest_frequency > 0:
            raise ValueError(f"lowest_frequency must be positive [rad/s]; got {lowest_frequency!r}")
        self.horizon = horizon
        self.phi = horizon.phi * np.exp(-LEAK * lowest_frequency * horizon.period)
        held = horizon.disturbance_now + horizon.disturbance_next  # a generalised force held over the period
        q = held @ np.diag(process_std**2) @ held.T
        q = 0.5 * (q + q.T) + 1e-12 * max(float(np.max(np.abs(q))), 1e-300) * np.eye(n)
        measure = np.zeros((2 * n_pto, n))
        measure[:n_pto] = horizon.stroke_of_state
        g = horizon.stroke_of_state[:, :nv]
        measure[n_pto:, nv : 2 * nv] = g
        r = np.diag(measurement_std**2)
        p = solve_discrete_are(self.phi.T, measure.T, q, r)
        self.gain = p @ measure.T @ np.linalg.inv(measure @ p @ measure.T + r)
        self.measure = measure
        self.stroke0 = np.asarray(stroke0, dtype=float).copy()
        self.x = np.zeros(n)

    def reset(self) -> None:
        """Start again from rest."""
        self.x[:] = 0.0

    def update(
        self, stroke: np.ndarray, rate: np.ndarray, force: np.ndarray, before: np.ndarray, now: np.ndarray
    ) -> np.ndarray:
        """One control period: step the estimate with the PTO ``force`` held since the last update and the
        disturbance going from ``before`` to ``now`` (nv) [N or N m], then correct with the measured strokes (from
        rest) and rates; returns the state estimate now."""
        h = self.horizon
        predicted = self.phi @ self.x + h.force_step @ force + h.disturbance_now @ before + h.disturbance_next @ now
        measured = np.concatenate([np.asarray(stroke, dtype=float) - self.stroke0, np.asarray(rate, dtype=float)])
        self.x = predicted + self.gain @ (measured - self.measure @ predicted)
        return self.x
