"""The flexible bodies' kernels' structured pieces (issue 28's speed work) against numpy: the views of packed arrays
(``_jit.reshaped``, numba's reshape without its call out) and M* = B'(M + A_inf)B with B's modal rows taken as unit
rows (``_kernels._modal_congruence``)."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.compiled import JIT
from wecss.compiled import _kernels as K
from wecss.compiled._jit import reshaped, step_kernel


@step_kernel
def _views(flat: np.ndarray, block: np.ndarray):  # type: ignore[no-untyped-def]
    """Views of a slice of ``flat`` and of ``block``'s first entry, and a write through each."""
    a = reshaped(flat[2:26], (2, 3, 4))
    b = reshaped(block[1], (6, 2))
    a[1, 2, 3] = -1.0
    b[5, 1] = -2.0
    return a, b, reshaped(flat[3:3], (0, 2, 3))


def test_reshaped_views_match_numpy_and_share_the_memory() -> None:
    flat = np.arange(30.0)
    block = np.arange(36.0).reshape(3, 4, 3)
    ref_a, ref_b = flat[2:26].reshape(2, 3, 4).copy(), block[1].reshape(6, 2).copy()
    a, b, empty = _views(flat, block)
    ref_a[1, 2, 3], ref_b[5, 1] = -1.0, -2.0
    np.testing.assert_array_equal(a, ref_a)
    np.testing.assert_array_equal(b, ref_b)
    assert empty.shape == (0, 2, 3)
    assert flat[2 + 23] == -1.0 and block[1, 3, 2] == -2.0  # written through: views, not copies


@pytest.mark.skipif(not JIT, reason="the compiled form's refusal")
def test_reshaped_refuses_a_strided_array() -> None:
    import numba

    @numba.njit
    def strided(x):  # type: ignore[no-untyped-def]
        return reshaped(x[::2], (2, 2))

    with pytest.raises(numba.core.errors.TypingError, match="C-contiguous"):
        strided(np.arange(8.0))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_modal_congruence_matches_numpy(seed: int) -> None:
    """A plant-like B: 4 general Cartesian rows (dense, with zeros) and 5 modal rows (axis >= 6, the identity on
    their columns), 7 active of them in a shuffled order; M* against numpy's B'AB on the active rows."""
    rng = np.random.default_rng(seed)
    nv, n_cart = 7, 9
    cart_axis = np.array([0, 2, 6, 4, 6, 6, 1, 6, 6])
    cart_column = np.array([0, 0, 2, 0, 3, 4, 0, 5, 6])  # a general row's entry is not read
    b = rng.standard_normal((n_cart, nv))
    b[rng.random((n_cart, nv)) < 0.3] = 0.0
    for row in np.flatnonzero(cart_axis >= 6):
        b[row] = 0.0
        b[row, cart_column[row]] = 1.0
    act = rng.permutation(n_cart)[:7].astype(np.int64)
    root = rng.standard_normal((7, 7))
    active_mass = root @ root.T + 7 * np.eye(7)
    active_mass[0, 3] = active_mass[3, 0] = 0.0  # (zeros are skipped)
    work, out = np.empty((7, nv)), np.empty((nv, nv))
    K._modal_congruence(b, act, cart_axis, cart_column, active_mass, work, out)
    ref = b[act].T @ active_mass @ b[act]
    np.testing.assert_allclose(out, ref, rtol=0, atol=1e-13 * np.abs(ref).max())
    np.testing.assert_array_equal(out, out.T)
