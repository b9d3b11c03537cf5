"""The electrical objective's programme by nonconvex ADMM: the mean electrical power of an asymmetric efficiency,
eta P absorbing and P / eta supplying, taken whole into ADMM's split variables, where its proximal step is exact.

With P = -f v at each sample, minus the mean electrical power is eta times minus the mean mechanical power (the
quadratic in the force's amplitudes of ``_spectral_qp``) plus k sum_j max(f_j v_j, 0) with k = (1 / eta - eta) / N.
Splitting the force and the stroke rate at the samples (``_admm.Splitting``, scaled x = f / s_f, y = v / s_v), the
z step at each sample and PTO is

    minimise  k' max(x y, 0) + rho / 2 ((x - a)^2 + (y - b)^2)   over x in the force's box and any y,

k' = k s_f s_v. Its minimum lies either where x y <= 0 (the nearest point of that set, on an axis when a b > 0) or
where x y >= 0 at the stationary point of the convex quadratic k' x y + rho / 2 (...) (rho > k', kept so), with
x clipped to its box; the lower of the two is taken. The iteration is the scaled ADMM of ``_admm`` (without
over-relaxation) on this nonconvex function: it converges to a stationary point in practice, not with a
certificate; the convex-concave procedure of ``_optimum`` then starts from its force and cannot lose, and eta
times the mechanical optimum still bounds the result from above.
"""

from __future__ import annotations

import numpy as np

from ._admm import Splitting, _initial_rho, iterate
from ._spectral_qp import SpectralProgramme

RELAXATION: float = 1.0
"""No over-relaxation: with it (1.6) the nonconvex iteration did not settle on the Wavestar (SS5: 20,000 iterations,
limits missed by 1.3 %); without, 1,800 iterations."""

FORCE, RATE = 0, 2
"""The force's and the stroke rate's places among the programme's signals (``_optimum._signals``)."""


def electrical_admm(
    programme: SpectralProgramme, supply: float, tolerance: float = 1e-6, max_iterations: int = 20000
) -> tuple[np.ndarray, int]:
    """A stationary point of eta (mechanical objective) + ``supply`` sum_j max(f_j v_j, 0) (module docstring).

    Parameters
    ----------
    programme : SpectralProgramme
        The mechanical programme with its Hessian and linear term times eta, without penalties.
    supply : float
        k = (1 / eta - eta) / N [-] (the objective, in W, gains k max(f v, 0) per sample).
    tolerance : float
        Stop when the primal and dual residuals are below this share of their scales [-].
    max_iterations : int

    Returns
    -------
    force : complex ndarray (M, n_pto)
    iterations : int
    """
    split = Splitting(programme, with_penalties=False, extra=(FORCE, RATE))
    f_at, v_at = split.used.index(FORCE), split.used.index(RATE)
    n = programme.periodic.points
    k = supply * split.scale[f_at] * split.scale[v_at]  # k' per PTO
    lo, hi = split.lower[f_at][None, :], split.upper[f_at][None, :]
    hessian = programme.hessian
    floor = 2.0 * float(np.max(k))
    rho = max(_initial_rho(hessian, split.gram, n), floor)

    def project(target: np.ndarray, rho: float) -> np.ndarray:
        z = np.clip(target, split.lower[:, None, :], split.upper[:, None, :])
        z[f_at], z[v_at] = _prox(target[f_at], target[v_at], k[None, :], rho, lo, hi)
        return z

    z, w = project(split.start, rho), np.zeros_like(split.start)
    force, _, _, _, iteration = iterate(split, project, rho, z, w, tolerance, max_iterations, RELAXATION, floor)
    return force, iteration


def _prox(a: np.ndarray, b: np.ndarray, k: np.ndarray, rho: float, lo: np.ndarray, hi: np.ndarray):
    """argmin over x in [lo, hi], y of k max(x y, 0) + rho / 2 ((x - a)^2 + (y - b)^2), elementwise (rho > k):
    the least of (a, b) clipped where it supplies no power, its two projections on the axes, and the stationary
    point where x y >= 0 (x clipped, y then optimal)."""
    xa = np.clip(a, lo, hi)
    zero = np.clip(0.0, lo, hi)
    det = rho**2 - k**2
    x3 = np.clip(rho * (rho * a - k * b) / det, lo, hi)
    candidates = [(xa, b, xa * b <= 0), (zero, b, zero * b <= 0), (xa, 0.0 * b, True), (x3, b - k * x3 / rho, None)]
    best_x, best_y, best = xa, 0.0 * b, np.full(np.shape(a), np.inf)
    for x, y, valid in candidates:
        if valid is None:
            valid = x * y >= 0
        c = k * np.maximum(x * y, 0.0) + 0.5 * rho * ((x - a) ** 2 + (y - b) ** 2)
        better = valid & (c < best)
        best_x, best_y, best = np.where(better, x, best_x), np.where(better, y, best_y), np.where(better, c, best)
    return best_x, best_y
