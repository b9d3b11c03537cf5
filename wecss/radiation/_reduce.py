"""Balanced truncation of a radiation state-space model (square-root method, scipy Lyapunov solves, no slycot).

The Hankel singular values sigma_k of the stable model give the a-priori bound on the frequency-response error of
the truncated model: max over omega of the largest singular value of K_hat - K_hat_r is at most 2 sum_{k > r}
sigma_k.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_continuous_lyapunov, svd

from ._statespace import RadiationStateSpace


@dataclass(frozen=True)
class Reduction:
    """A reduced model, the Hankel singular values of the original and the error bound.

    Attributes
    ----------
    model : RadiationStateSpace
    hankel_singular_values : ndarray
    error_bound : float
        2 * sum of the discarded Hankel singular values [N s/m, N m s/rad mixed]: a bound on the H-infinity norm of
        the error of K_hat.
    """

    model: RadiationStateSpace
    hankel_singular_values: np.ndarray
    error_bound: float


def _factor(gram: np.ndarray) -> np.ndarray:
    """L with L L' = gram (symmetric, positive semi-definite up to round-off), by eigen-decomposition."""
    values, vectors = np.linalg.eigh(0.5 * (gram + gram.T))
    return vectors * np.sqrt(np.clip(values, 0.0, None))[None, :]


def balanced_truncation(model: RadiationStateSpace, *, order: int | None = None, tol: float | None = None) -> Reduction:
    """Reduce ``model`` to ``order`` states, or to the fewest whose error bound is at most ``tol``.

    Raises
    ------
    ValueError
        If the model is not stable (Gramians do not exist), or neither or both of ``order`` and ``tol`` are given.
    """
    if (order is None) == (tol is None):
        raise ValueError("give exactly one of order (number of states) or tol (error bound)")
    if tol is not None and not tol >= 0:
        raise ValueError(f"tol is an error bound, >= 0; got {tol!r}")
    if model.n_states == 0:
        return Reduction(model, np.zeros(0), 0.0)
    if model.n_states and np.max(model.poles().real) >= 0:
        raise ValueError("balanced truncation needs a stable model (all poles in the left half-plane)")
    a, b, c = model.A, model.B, model.C
    controllability = solve_continuous_lyapunov(a, -b @ b.T)
    observability = solve_continuous_lyapunov(a.T, -c.T @ c)
    lc, lo = _factor(controllability), _factor(observability)
    u, sigma, vh = svd(lo.T @ lc)
    tails = 2 * np.concatenate([np.cumsum(sigma[::-1])[::-1], [0.0]])  # tails[r] = 2 sum_{k >= r} sigma_k
    if order is None:
        assert tol is not None
        order = int(np.argmax(tails <= tol))
    order = int(min(max(order, 0), int(np.sum(sigma > 1e-14 * max(sigma[0], 1e-300)))))
    root = 1.0 / np.sqrt(sigma[:order])
    right = lc @ vh[:order].T * root[None, :]
    left = (root[:, None] * u[:, :order].T) @ lo.T
    reduced = RadiationStateSpace(left @ a @ right, left @ b, c @ right, model.dofs, f"{model.method}+balanced")
    return Reduction(reduced, sigma, float(tails[order]))
