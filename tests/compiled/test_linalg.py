"""The loop kernels' small linear algebra and the real form of the state-space memory, against numpy and the
complex formulas they replace."""

from __future__ import annotations

import numpy as np
import pytest

from tests.radiation.analytic import known_system
from wecss.compiled import from_state_space
from wecss.compiled._linalg import congruence, matvec_t_add
from wecss.compiled.kernels import cholesky, cholesky_solve, lu_factor, lu_solve, matvec, matvec_add
from wecss.radiation import RadiationStateSpace
from wecss.sim._memory import memory_advance, memory_history


def _spd(rng: np.random.Generator, n: int) -> np.ndarray:
    a = rng.standard_normal((n, n))
    return a @ a.T + 0.1 * np.eye(n)


@pytest.mark.parametrize("n", [1, 3, 7, 12])
def test_cholesky_solve_matches_numpy_on_random_spd_matrices(n):
    rng = np.random.default_rng(n)
    for _ in range(5):
        a = _spd(rng, n)
        b = rng.standard_normal(n)
        factor = np.full((n, n), np.nan)  # every entry must be written, the upper triangle with zeros
        assert cholesky(a, factor)
        np.testing.assert_allclose(factor, np.linalg.cholesky(a), rtol=1e-12, atol=1e-12)
        out = np.empty(n)
        cholesky_solve(factor, b, out)
        np.testing.assert_allclose(out, np.linalg.solve(a, b), rtol=1e-10, atol=1e-12)


def test_cholesky_refuses_a_matrix_that_is_not_positive_definite():
    a = np.diag([1.0, -1e-3, 2.0])
    assert not cholesky(a, np.zeros((3, 3)))
    assert not cholesky(np.zeros((2, 2)), np.zeros((2, 2)))


@pytest.mark.parametrize("n", [1, 4, 23])
def test_lu_solve_matches_numpy_and_scipys_factors(n):
    """Non-symmetric matrices, some with a zero leading entry (a pivot must be exchanged): the factors are
    LAPACK's (scipy.linalg.lu_factor) and the solution numpy's; the solve works in place too."""
    import scipy.linalg

    rng = np.random.default_rng(n)
    for trial in range(5):
        a = rng.standard_normal((n, n)) + (0.0 if trial % 2 else 3.0) * np.eye(n)
        if trial == 1 and n > 1:
            a[0, 0] = 0.0
        b = rng.standard_normal(n)
        lu, pivots = a.copy(), np.full(n, -1, dtype=np.int64)
        assert lu_factor(lu, pivots)
        want_lu, want_pivots = scipy.linalg.lu_factor(a)
        np.testing.assert_array_equal(pivots, want_pivots)
        np.testing.assert_allclose(lu, want_lu, rtol=1e-10, atol=1e-12)
        out = np.empty(n)
        lu_solve(lu, pivots, b, out)
        np.testing.assert_allclose(out, np.linalg.solve(a, b), rtol=1e-9, atol=1e-12)
        lu_solve(lu, pivots, b, b)
        np.testing.assert_allclose(b, out, rtol=1e-14, atol=0.0)


def test_lu_refuses_a_singular_matrix():
    a = np.array([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]])
    assert not lu_factor(a, np.zeros(3, dtype=np.int64))
    assert not lu_factor(np.zeros((2, 2)), np.zeros(2, dtype=np.int64))
    assert not lu_factor(np.array([[np.nan]]), np.zeros(1, dtype=np.int64))


def test_products_match_numpy():
    rng = np.random.default_rng(7)
    a, x, y = rng.standard_normal((5, 9)), rng.standard_normal(9), rng.standard_normal(5)
    out = np.empty(5)
    matvec(a, x, out)
    np.testing.assert_allclose(out, a @ x, rtol=1e-13)
    start = rng.standard_normal(5)
    out = start.copy()
    matvec_add(a, x, out)
    np.testing.assert_allclose(out, start + a @ x, rtol=1e-13)
    start = rng.standard_normal(9)
    out = start.copy()
    matvec_t_add(a, y, out)
    np.testing.assert_allclose(out, start + a.T @ y, rtol=1e-13)
    m, b = _spd(rng, 9), rng.standard_normal((9, 4))
    out, work = np.empty((4, 4)), np.empty((4, 9))
    congruence(np.ascontiguousarray(b.T), m, work, out)
    np.testing.assert_allclose(out, b.T @ m @ b, rtol=1e-12)
    np.testing.assert_array_equal(out, out.T)


def test_real_form_of_the_state_space_memory_matches_the_complex_update():
    """memory_history / memory_advance (real products on the interleaved parts of z) against the complex modal
    formulas of the module docstring, z1 = e^{lambda h} z0 + hold0 u0 + hold1 u1 and F = -Re(c z), over many
    steps of random velocities."""
    a, b, c = known_system()
    arrays, _ = from_state_space(RadiationStateSpace(a, b, c, ("p__Heave", "q__Heave")), 0.02)
    rng = np.random.default_rng(11)
    z = np.zeros(arrays.poles.size, dtype=complex)
    reference = z.copy()
    buf, pos = np.zeros((2, 2)), np.zeros(1, dtype=np.int64)
    u_now = np.zeros(2)
    for _ in range(60):
        u_new = rng.standard_normal(2)
        force = memory_history(arrays, z, u_now, buf, 0) + arrays.newest @ u_new
        memory_advance(arrays, z, u_now, u_new, buf, pos)
        reference = arrays.decay * reference + arrays.hold0 @ u_now + arrays.hold1 @ u_new
        np.testing.assert_allclose(z, reference, rtol=1e-12, atol=1e-14)
        np.testing.assert_allclose(force, -np.real(arrays.output @ reference), rtol=1e-11, atol=1e-13)
        u_now = u_new


def test_congruence_of_a_sparse_b_matches_numpy():
    """A B with many zeros (identity rows, as a flexible body's mode rows, and empty columns): the rows of m that
    the nonzero entries pick give b' m b as the dense product does."""
    rng = np.random.default_rng(8)
    m = _spd(rng, 9)
    b = np.zeros((9, 5))
    b[:4, :2] = rng.standard_normal((4, 2))
    b[4:8, 1:5] = np.eye(4)
    b[8, 4] = 0.7
    out, work = np.empty((5, 5)), np.empty((5, 9))
    congruence(np.ascontiguousarray(b.T), m, work, out)
    np.testing.assert_allclose(out, b.T @ m @ b, rtol=1e-12, atol=1e-14)
    np.testing.assert_array_equal(out, out.T)
