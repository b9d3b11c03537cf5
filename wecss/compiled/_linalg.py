"""Small dense linear algebra for the time loop, written as loops into given arrays.

Also the real forms of complex maps on real data (:func:`complex_columns`, :func:`real_part_rows`).

The equations of motion handle matrices of a few to a few dozen rows (M* is nv x nv, nv = 4 ... 7 for the M4
layouts). For these sizes a BLAS or LAPACK call costs more than the arithmetic (and can wake BLAS threads that
spin beside the loop), and each result array is an allocation. These kernels do the arithmetic in place, with no
call out. Without numba each uses the equivalent numpy call instead (:func:`~wecss.compiled._jit.loop_kernel`),
which is faster in the interpreter and gives the same numbers to rounding.
"""

from __future__ import annotations

import numpy as np

from ._jit import loop_kernel


def _numpy_matvec(a: np.ndarray, x: np.ndarray, out: np.ndarray) -> None:
    out[:] = a @ x


@loop_kernel(_numpy_matvec)
def matvec(a: np.ndarray, x: np.ndarray, out: np.ndarray) -> None:
    """out = a @ x for a (n, m), x (m,), out (n,)."""
    for i in range(a.shape[0]):
        s = 0.0
        for k in range(a.shape[1]):
            s += a[i, k] * x[k]
        out[i] = s


def _numpy_matvec_add(a: np.ndarray, x: np.ndarray, out: np.ndarray) -> None:
    out += a @ x


@loop_kernel(_numpy_matvec_add)
def matvec_add(a: np.ndarray, x: np.ndarray, out: np.ndarray) -> None:
    """out += a @ x for a (n, m), x (m,), out (n,)."""
    for i in range(a.shape[0]):
        s = 0.0
        for k in range(a.shape[1]):
            s += a[i, k] * x[k]
        out[i] += s


def _numpy_matvec_t_add(a: np.ndarray, x: np.ndarray, out: np.ndarray) -> None:
    out += a.T @ x


@loop_kernel(_numpy_matvec_t_add)
def matvec_t_add(a: np.ndarray, x: np.ndarray, out: np.ndarray) -> None:
    """out += a.T @ x for a (n, m), x (n,), out (m,) (rows of ``a`` read in order)."""
    for i in range(a.shape[0]):
        xi = x[i]
        for k in range(a.shape[1]):
            out[k] += a[i, k] * xi


def _numpy_congruence(bt: np.ndarray, m: np.ndarray, work: np.ndarray, out: np.ndarray) -> None:
    work[:] = bt @ m
    out[:] = work @ bt.T
    out[:] = 0.5 * (out + out.T)


@loop_kernel(_numpy_congruence)
def congruence(bt: np.ndarray, m: np.ndarray, work: np.ndarray, out: np.ndarray) -> None:
    """out = b' m b from bt = b' (k, n) and a symmetric m (n, n), exactly symmetric; ``work`` (k, n) is scratch.
    (Every sum runs over contiguous rows; m b is gathered from the rows of m that b's nonzero entries pick, which
    skips most of the work for a B with many zeros, such as one whose modes' rows are the identity.)"""
    k, n = bt.shape
    for c in range(k):
        for i in range(n):
            work[c, i] = 0.0
        for j in range(n):
            weight = bt[c, j]
            if weight != 0.0:
                for i in range(n):  # m[j, i] = m[i, j]
                    work[c, i] += weight * m[j, i]
    for r in range(k):
        for c in range(r + 1):
            s = 0.0
            for i in range(n):
                s += bt[r, i] * work[c, i]
            out[r, c] = s
            out[c, r] = s


def _numpy_cholesky(a: np.ndarray, factor: np.ndarray) -> bool:
    try:
        factor[:] = np.linalg.cholesky(a)
    except np.linalg.LinAlgError:
        return False
    return True


@loop_kernel(_numpy_cholesky)
def cholesky(a: np.ndarray, factor: np.ndarray) -> bool:
    """Lower Cholesky factor L of the symmetric positive definite ``a`` (n, n) into ``factor`` (a = L L').

    Returns False (``factor`` then undefined) when a pivot is not positive: ``a`` is not positive definite.
    """
    n = a.shape[0]
    for j in range(n):
        s = a[j, j]
        for k in range(j):
            s -= factor[j, k] * factor[j, k]
        if not s > 0.0:
            return False
        d = np.sqrt(s)
        factor[j, j] = d
        for i in range(j + 1, n):
            t = a[i, j]
            for k in range(j):
                t -= factor[i, k] * factor[j, k]
            factor[i, j] = t / d
        for i in range(j):
            factor[i, j] = 0.0
    return True


def _numpy_cholesky_solve(factor: np.ndarray, b: np.ndarray, out: np.ndarray) -> None:
    y = np.linalg.solve(factor, b)
    out[:] = np.linalg.solve(factor.T, y)


@loop_kernel(_numpy_cholesky_solve)
def cholesky_solve(factor: np.ndarray, b: np.ndarray, out: np.ndarray) -> None:
    """out = a^-1 b from the lower Cholesky factor of a (:func:`cholesky`); ``out`` may be ``b``."""
    n = factor.shape[0]
    for i in range(n):  # L y = b
        s = b[i]
        for k in range(i):
            s -= factor[i, k] * out[k]
        out[i] = s / factor[i, i]
    for i in range(n - 1, -1, -1):  # L' x = y
        s = out[i]
        for k in range(i + 1, n):
            s -= factor[k, i] * out[k]
        out[i] = s / factor[i, i]


def _numpy_lu_factor(a: np.ndarray, pivots: np.ndarray) -> bool:
    import scipy.linalg

    lu, piv = scipy.linalg.lu_factor(a, check_finite=False)
    if not np.all(np.isfinite(lu)) or np.any(np.diag(lu) == 0.0):
        return False
    a[:] = lu
    pivots[:] = piv
    return True


@loop_kernel(_numpy_lu_factor)
def lu_factor(a: np.ndarray, pivots: np.ndarray) -> bool:
    """LU factorisation with partial pivoting of the square ``a`` (n, n) in place: P a = L U, L unit lower
    triangular below the diagonal of ``a``, U on and above it; ``pivots`` (n,) the row exchanged with row i at
    step i (LAPACK's convention, 0-based, as ``scipy.linalg.lu_factor``).

    Returns False (``a`` then undefined) when a pivot is zero or not finite: ``a`` is singular (or holds NaN).
    """
    n = a.shape[0]
    for j in range(n):
        p = j
        largest = abs(a[j, j])
        for i in range(j + 1, n):
            if abs(a[i, j]) > largest:
                largest = abs(a[i, j])
                p = i
        if not (largest > 0.0 and np.isfinite(largest)):
            return False
        pivots[j] = p
        if p != j:
            for k in range(n):
                a[j, k], a[p, k] = a[p, k], a[j, k]
        d = 1.0 / a[j, j]
        for i in range(j + 1, n):
            a[i, j] *= d
            factor = a[i, j]
            if factor != 0.0:
                for k in range(j + 1, n):
                    a[i, k] -= factor * a[j, k]
    return True


def _numpy_lu_solve(lu: np.ndarray, pivots: np.ndarray, b: np.ndarray, out: np.ndarray) -> None:
    import scipy.linalg

    out[:] = scipy.linalg.lu_solve((lu, pivots), b, check_finite=False)


@loop_kernel(_numpy_lu_solve)
def lu_solve(lu: np.ndarray, pivots: np.ndarray, b: np.ndarray, out: np.ndarray) -> None:
    """out = a^-1 b from the factors of :func:`lu_factor`; ``out`` may be ``b``."""
    n = lu.shape[0]
    for i in range(n):  # (a no-op when out is b)
        out[i] = b[i]
    for i in range(n):  # the row exchanges, in order
        p = pivots[i]
        if p != i:
            out[i], out[p] = out[p], out[i]
    for i in range(n):  # L y = P b
        s = out[i]
        for k in range(i):
            s -= lu[i, k] * out[k]
        out[i] = s
    for i in range(n - 1, -1, -1):  # U x = y
        s = out[i]
        for k in range(i + 1, n):
            s -= lu[i, k] * out[k]
        out[i] = s / lu[i, i]


def complex_columns(matrix: np.ndarray) -> np.ndarray:
    """The real matrix R with u @ R viewed as complex equal to u @ matrix, for real u: real and imaginary parts
    interleaved by column (one real matrix product instead of a complex one)."""
    out = np.empty((matrix.shape[0], 2 * matrix.shape[1]))
    out[:, 0::2] = matrix.real
    out[:, 1::2] = matrix.imag
    return out


def real_part_rows(matrix: np.ndarray) -> np.ndarray:
    """The real matrix R with z.view(float) @ R = Re(z @ matrix) for complex z (rows interleaved)."""
    out = np.empty((2 * matrix.shape[0], matrix.shape[1]))
    out[0::2] = matrix.real
    out[1::2] = -matrix.imag
    return out
