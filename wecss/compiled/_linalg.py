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
