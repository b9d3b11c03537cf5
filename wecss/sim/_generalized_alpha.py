"""The generalised-alpha integrator (Chung and Hulbert 1993) for stiff second-order equations on a configuration
manifold (Arnold and Bruls 2007): M(q) v_dot = F(q, v, t), q moved by a velocity increment (``integrate``).

One step from (q0, v0, a0, v_dot0) to t0 + h, with a the algorithmic acceleration:

    q1 = q0 (+) (h v0 + h^2 (1/2 - beta) a0 + h^2 beta a1)
    v1 = v0 + h (1 - gamma) a0 + h gamma a1
    (1 - alpha_m) a1 + alpha_m a0 = (1 - alpha_f) v_dot1 + alpha_f v_dot0

and the equations of motion at the end of the step, M(q1) v_dot1 = F(q1, v1, t1), solved for v_dot1 by a modified
Newton iteration: its matrix S = M + h gamma c C + h^2 beta c K (c = (1 - alpha_f) / (1 - alpha_m); C, K the
tangent damping and stiffness, -dF/dv and -dF/dq) is given once (from the linear model) and kept, so a step costs
a few evaluations of the residual and back-substitutions, whatever the stiffness.

With the spectral radius at infinite frequency rho_inf in [0, 1]: alpha_m = (2 rho_inf - 1) / (rho_inf + 1),
alpha_f = rho_inf / (rho_inf + 1), gamma = 1/2 + alpha_f - alpha_m, beta = (gamma + 1/2)^2 / 4: second order,
unconditionally stable for linear systems, modes far above 1/h damped to rho_inf per step and the low ones
nearly untouched (rho_inf = 1: the trapezoidal rule, no numerical damping).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.linalg import lu_factor, lu_solve


class NewtonFailure(RuntimeError):
    """The modified Newton iteration of a step did not converge (the message says where and by how much)."""


@dataclass(frozen=True)
class GeneralizedAlpha:
    """The scheme's parameters (see the module docstring).

    Parameters
    ----------
    spectral_radius : float
        rho_inf in [0, 1] (default 0.8: the modes far above the step lose 20 % of their amplitude per step).
    tolerance : float
        Change of v_dot, relative to the largest acceleration of the step (at least 1), at which the Newton
        iteration stops (default 1e-10).
    max_iterations : int
        Newton iterations per step before :class:`NewtonFailure` (default 25).

    Raises
    ------
    ValueError
        On a spectral radius outside [0, 1], a non-positive tolerance or fewer than one iteration.
    """

    spectral_radius: float = 0.8
    tolerance: float = 1e-10
    max_iterations: int = 25

    def __post_init__(self) -> None:
        rho = self.spectral_radius
        if isinstance(rho, bool) or not isinstance(rho, int | float) or not 0.0 <= rho <= 1.0:
            raise ValueError(f"spectral_radius must be a number in [0, 1]; got {rho!r}")
        if not (isinstance(self.tolerance, int | float) and self.tolerance > 0):
            raise ValueError(f"tolerance must be a positive number; got {self.tolerance!r}")
        if isinstance(self.max_iterations, bool) or not isinstance(self.max_iterations, int) or self.max_iterations < 1:
            raise ValueError(f"max_iterations must be an integer >= 1; got {self.max_iterations!r}")

    @property
    def coefficients(self) -> tuple[float, float, float, float]:
        """(alpha_m, alpha_f, gamma, beta)."""
        rho = float(self.spectral_radius)
        alpha_m = (2 * rho - 1) / (rho + 1)
        alpha_f = rho / (rho + 1)
        gamma = 0.5 + alpha_f - alpha_m
        return alpha_m, alpha_f, gamma, 0.25 * (gamma + 0.5) ** 2

    def iteration_matrix(self, mass: np.ndarray, damping: np.ndarray, stiffness: np.ndarray, h: float) -> tuple:
        """LU factors of S = M + h gamma c C + h^2 beta c K for the step ``h`` [s] (see the module docstring)."""
        alpha_m, alpha_f, gamma, beta = self.coefficients
        c = (1 - alpha_f) / (1 - alpha_m)
        return lu_factor(
            np.asarray(mass) + h * gamma * c * np.asarray(damping) + h * h * beta * c * np.asarray(stiffness)
        )


@dataclass
class AlphaState:
    """Where a generalised-alpha integration is: time t [s], configuration q, velocity v, algorithmic acceleration a
    and the acceleration v_dot of the equations of motion."""

    t: float
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    v_dot: np.ndarray


def alpha_step(
    scheme: GeneralizedAlpha,
    state: AlphaState,
    h: float,
    residual: Callable[[np.ndarray, np.ndarray, np.ndarray, float], np.ndarray],
    integrate: Callable[[np.ndarray, np.ndarray], np.ndarray],
    factors: tuple | Callable[[np.ndarray, np.ndarray], tuple],
) -> tuple[AlphaState, int]:
    """One step of ``h`` [s] from ``state``: the new state and the Newton iterations it took.

    Parameters
    ----------
    residual : callable (q, v, v_dot, t) -> (n,)
        M(q) v_dot - F(q, v, t).
    integrate : callable (q, dv) -> q
        The configuration reached from q by the velocity increment dv.
    factors : tuple, or callable (q, v) -> tuple
        :meth:`GeneralizedAlpha.iteration_matrix` for this ``h``, kept through the step; or a function of the first
        predicted state that makes it (a matrix nearer the state: fewer iterations for a nonlinear system).

    Raises
    ------
    NewtonFailure
        If the iteration has not converged after ``scheme.max_iterations`` (the last change of v_dot is said).
    """
    alpha_m, alpha_f, gamma, beta = scheme.coefficients
    s = state
    v_dot = s.v_dot.copy()  # predictor: the last acceleration
    t1 = s.t + h
    change = np.inf
    for iteration in range(1, scheme.max_iterations + 1):
        a1 = ((1 - alpha_f) * v_dot + alpha_f * s.v_dot - alpha_m * s.a) / (1 - alpha_m)
        q1 = integrate(s.q, h * s.v + h * h * ((0.5 - beta) * s.a + beta * a1))
        v1 = s.v + h * ((1 - gamma) * s.a + gamma * a1)
        if callable(factors):
            factors = factors(q1, v1)
        step = -lu_solve(factors, residual(q1, v1, v_dot, t1))
        v_dot = v_dot + step
        change = float(np.abs(step).max())
        scale = max(1.0, float(np.abs(v_dot).max()), float(np.abs(s.v_dot).max()), float(np.abs(s.a).max()))
        if change <= scheme.tolerance * scale:
            a1 = ((1 - alpha_f) * v_dot + alpha_f * s.v_dot - alpha_m * s.a) / (1 - alpha_m)
            q1 = integrate(s.q, h * s.v + h * h * ((0.5 - beta) * s.a + beta * a1))
            v1 = s.v + h * ((1 - gamma) * s.a + gamma * a1)
            return AlphaState(t1, q1, v1, a1, v_dot), iteration
    raise NewtonFailure(
        f"generalised-alpha step from t = {s.t:.6g} s (h = {h:.3g} s): the modified Newton iteration did not converge "
        f"in {scheme.max_iterations} iterations (last change of the accelerations {change:.3g}, tolerance "
        f"{scheme.tolerance:.3g} of the largest acceleration); a smaller step, or "
        "an iteration matrix nearer the state (a linear model about it), converges"
    )


def start(q: np.ndarray, v: np.ndarray, v_dot: np.ndarray, t: float = 0.0) -> AlphaState:
    """The state at the start: the algorithmic acceleration equal to the acceleration."""
    return AlphaState(t, np.asarray(q, dtype=float).copy(), np.asarray(v, dtype=float).copy(),
                      np.asarray(v_dot, dtype=float).copy(), np.asarray(v_dot, dtype=float).copy())  # fmt: skip
