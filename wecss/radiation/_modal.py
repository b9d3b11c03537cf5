"""Exponential fits of one kernel entry, K(t) ~ sum of damped exponentials, by two methods:

- Prony in its matrix-pencil form (Hua and Sarkar 1990): the poles are the eigenvalues of the pencil
  (V1^+ V2) of the dominant right singular vectors of the Hankel matrix of samples; the residues follow by least
  squares in a real basis (e^{st}, e^{st} cos wt, e^{st} sin wt).
- Hankel-SVD realisation (Kung 1978 / ERA, Juang and Pappa 1985): A_d = S^-1/2 U' H1 V S^-1/2 from the
  shifted Hankel matrix, then A = log(A_d) / dt.

Both return a real single-input single-output realisation (A, b, c) with K(t) = c exp(A t) b.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.linalg import hankel


def _real_basis(poles: np.ndarray, time: np.ndarray) -> tuple[np.ndarray, list[tuple[float, float]]]:
    """Columns e^{s t} (real s) or e^{sigma t} cos(w t), e^{sigma t} sin(w t) (one per conjugate pair)."""
    kept: list[tuple[float, float]] = []
    for s in poles:
        sigma, w = float(s.real), float(abs(s.imag))
        if w < 1e-9 * max(1.0, abs(sigma)):
            w = 0.0
        if not any(abs(sigma - a) < 1e-9 * max(1.0, abs(a)) and abs(w - b) < 1e-9 * max(1.0, b) for a, b in kept):
            kept.append((sigma, w))
    cols = []
    for sigma, w in kept:
        decay = np.exp(sigma * time)
        if w == 0.0:
            cols.append(decay)
        else:
            cols.append(decay * np.cos(w * time))
            cols.append(decay * np.sin(w * time))
    return np.array(cols).T, kept


def _basis_integrals(kept: list[tuple[float, float]]) -> np.ndarray:
    """int_0^inf of each real basis function (stable poles): -1/s, -s/(s^2+w^2) and w/(s^2+w^2)."""
    out = []
    for sigma, w in kept:
        if w == 0.0:
            out.append(-1.0 / sigma)
        else:
            out.extend([-sigma / (sigma**2 + w**2), w / (sigma**2 + w**2)])
    return np.array(out)


def realise(
    poles: np.ndarray, time: np.ndarray, samples: np.ndarray, *, zero_integral: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Least-squares residues for ``poles`` on the samples, and the real realisation (A, b, c).

    Unstable poles are reflected into the left half-plane first (s -> -|Re s| + i Im s). With ``zero_integral``
    the residues satisfy int_0^inf K dt = 0 exactly (equality-constrained least squares), as radiation kernels
    do (B(0) = 0): without it a tiny error in the integral makes Re K_hat(0) indefinite, i.e. the fitted
    model non-passive at low frequency, where a free surge mode would drift.
    """
    poles = np.where(poles.real > 0, -poles.real + 1j * poles.imag, poles)
    basis, kept = _real_basis(poles, time)
    if not kept:
        return np.zeros((0, 0)), np.zeros(0), np.zeros(0)
    if zero_integral:
        integrals = _basis_integrals(kept)
        m = basis.shape[1]
        kkt = np.zeros((m + 1, m + 1))
        kkt[:m, :m] = basis.T @ basis
        kkt[:m, m] = kkt[m, :m] = integrals
        rhs = np.concatenate([basis.T @ samples, [0.0]])
        coef = np.linalg.lstsq(kkt, rhs, rcond=None)[0][:m]
    else:
        coef = np.linalg.lstsq(basis, samples, rcond=None)[0]
    n = basis.shape[1]
    a = np.zeros((n, n))
    b = np.zeros(n)
    c = np.zeros(n)
    k = m = 0
    for sigma, w in kept:
        if w == 0.0:
            a[k, k], b[k], c[k] = sigma, 1.0, coef[m]
            k += 1
            m += 1
        else:
            a[k : k + 2, k : k + 2] = [[sigma, w], [-w, sigma]]
            b[k] = 1.0
            c[k], c[k + 1] = coef[m], -coef[m + 1]
            k += 2
            m += 2
    return a, b, c


def matrix_pencil(samples: np.ndarray, dt: float) -> Callable[[int], np.ndarray]:
    """Poles of the matrix-pencil method as a function of the order (one SVD, then cheap per order)."""
    m = samples.size
    pencil = m // 3
    y = hankel(samples[: m - pencil], samples[m - pencil - 1 :])  # (m - L) x (L + 1)
    _, _, vh = np.linalg.svd(y, full_matrices=False)

    def poles(order: int) -> np.ndarray:
        v = vh[:order].conj().T  # (L + 1, order)
        return _continuous(np.linalg.eigvals(np.linalg.pinv(v[:-1]) @ v[1:]), dt)

    return poles


def hankel_realisation(samples: np.ndarray, dt: float) -> Callable[[int], np.ndarray]:
    """Poles of a rank-``order`` Hankel-SVD realisation (Kung / ERA), as a function of the order."""
    m = samples.size
    rows = (m - 1) // 2
    h0 = hankel(samples[:rows], samples[rows - 1 : 2 * rows - 1])
    h1 = hankel(samples[1 : rows + 1], samples[rows : 2 * rows])
    u, s, vh = np.linalg.svd(h0)

    def poles(order: int) -> np.ndarray:
        root = 1.0 / np.sqrt(s[:order])
        a_d = (root[:, None] * (u[:, :order].T @ h1 @ vh[:order].T)) * root[None, :]
        return _continuous(np.linalg.eigvals(a_d), dt)

    return poles


def _continuous(z: np.ndarray, dt: float) -> np.ndarray:
    """s = log(z) / dt, dropping modes at the Nyquist limit (negative real z), which no real pair can carry."""
    z = z[np.abs(z) > 1e-12]
    s = np.log(z.astype(complex)) / dt
    return s[np.abs(s.imag) < 0.9 * np.pi / dt]
