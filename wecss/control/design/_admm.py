"""A first guess of the spectral programme's active set by the alternating direction method of multipliers (ADMM),
for the exact dual active-set solve to start from where it would otherwise cycle.

The programme (``_spectral_qp``) with every constrained signal split off as its own variable z_a (at the samples,
divided by its bound's size so that all rows weigh alike):

    minimise  1/2 sum_m F_m^H H_m F_m - Re sum_m gamma_m^H F_m    subject to  z_a = (S T^a F + u^a_free) / s_a,
                                                                           z_a in [lower_a, upper_a] / s_a,

where S maps harmonic amplitudes to the N samples (S c = Re sum_m c_m exp(i omega_m t_j)). Because the samples
cover the period evenly and the harmonics lie strictly between 0 and N / 2, S^* S = (N / 2) I: the force's step of
ADMM is one n_pto x n_pto solve per harmonic,

    (H_m + rho N / 2 sum_a T^a_m^H T^a_m / s_a^2) F_m = gamma_m - rho sum_a T^a_m^H (S^* r_a)_m / s_a,

with r_a the scaled residual, and every other step is a clip or an FFT. The penalty parameter rho is adapted to
balance the primal and dual residuals (Boyd et al. 2011, section 3.4.1), and the iteration is over-relaxed (1.6).
Rows at a bound with a multiplier pushing on it make the active set. The guess needs no certificate: the active-set
solve that starts from it is exact and certified, or falls back as before.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ._spectral_qp import SpectralProgramme

RELAXATION: float = 1.6
"""Over-relaxation of the z step (Boyd et al. 2011, section 3.4.3)."""


def admm_active_set(
    programme: SpectralProgramme, tolerance: float = 1e-6, max_iterations: int = 5000
) -> tuple[np.ndarray, int]:
    """The rows at their bound after ADMM on ``programme``'s constraints (its penalties are left out).

    Parameters
    ----------
    programme : SpectralProgramme
    tolerance : float
        Stop when the primal and dual residuals are below this share of their scales [-].
    max_iterations : int

    Returns
    -------
    active : bool ndarray (n_constrained, n_pto, N, 2)
        The guessed active set, in the layout of ``SpectralProgramme.solve``'s ``active`` (side 0: lower, 1: upper).
    iterations : int
        ADMM iterations made.
    """
    periodic = programme.periodic
    n, n_pto = periodic.points, periodic.n_pto
    indices = programme.constrained
    size = programme._size[:, :, 0]  # (n_c, n_pto)
    lower = -programme._bound[:, :, 0] / size  # (n_c, n_pto), -inf where none
    upper = programme._bound[:, :, 1] / size
    operators = [programme.signals[k].operator / size[i][None, :, None] for i, k in enumerate(indices)]
    free = np.stack([programme.signals[k].free / size[i][None] for i, k in enumerate(indices)])  # (n_c, N, n_pto)
    gram = sum(np.einsum("mqp,mqr->mpr", np.conj(t), t) for t in operators)  # sum T^H T (M, p, p)
    hessian, linear = programme.hessian, programme.linear

    def values(force: np.ndarray) -> np.ndarray:
        return free + np.stack([periodic.samples(np.einsum("mpq,mq->mp", t, force)) for t in operators])

    start = values(programme.unconstrained)
    z = np.clip(start, lower[:, None, :], upper[:, None, :])
    if np.array_equal(z, start):  # the unconstrained optimum is feasible: nothing binds
        return np.zeros((len(indices), n_pto, n, 2), dtype=bool), 0
    rho = _initial_rho(hessian, gram, n)
    factor = np.linalg.inv(hessian + rho * 0.5 * n * gram)
    w = np.zeros_like(z)  # scaled multipliers (y = rho w)
    iteration = 0
    for iteration in range(1, max_iterations + 1):
        residual = free - z + w
        adjoint = sum(
            np.einsum("mqp,mq->mp", np.conj(t), periodic.spectrum(r)) for t, r in zip(operators, residual, strict=True)
        )
        force = np.einsum("mpq,mq->mp", factor, linear - rho * adjoint)
        u = values(force)
        relaxed = RELAXATION * u + (1.0 - RELAXATION) * z
        z_old = z
        z = np.clip(relaxed + w, lower[:, None, :], upper[:, None, :])
        w = w + relaxed - z
        primal = float(np.max(np.abs(u - z)))
        dual = rho * float(np.max(np.abs(z - z_old)))
        scale_primal = max(float(np.max(np.abs(u))), float(np.max(np.abs(z))), 1e-300)
        scale_dual = max(rho * float(np.max(np.abs(w))), 1e-300)
        if primal <= tolerance * scale_primal and dual <= tolerance * scale_dual:
            break
        if iteration % 25 == 0:  # keep the residuals balanced: rescale rho and the scaled multipliers with it
            ratio = (primal / scale_primal) / max(dual / scale_dual, 1e-300)
            if ratio > 10.0 or ratio < 0.1:
                new = rho * float(np.clip(np.sqrt(ratio), 0.1, 10.0))
                w *= rho / new
                rho = new
                factor = np.linalg.inv(hessian + rho * 0.5 * n * gram)
    at_upper = (z >= upper[:, None, :] - 1e-9) & (w > 0)
    at_lower = (z <= lower[:, None, :] + 1e-9) & (w < 0)
    active = np.stack([at_lower, at_upper], axis=-1)  # (n_c, N, n_pto, 2)
    return np.ascontiguousarray(np.swapaxes(active, 1, 2)), iteration


def _initial_rho(hessian: np.ndarray, gram: np.ndarray, n: int) -> float:
    """rho that makes the constraints' term as large as the Hessian on the average harmonic."""
    h = float(np.mean(np.abs(np.trace(hessian, axis1=1, axis2=2))))
    g = 0.5 * n * float(np.mean(np.abs(np.trace(gram, axis1=1, axis2=2))))
    return h / g if g > 0 and h > 0 else 1.0
