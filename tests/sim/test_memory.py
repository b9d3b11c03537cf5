"""The convolution history in blocks of steps against a plain convolution of the stored kernel values."""

from __future__ import annotations

import numpy as np
import pytest

from tests.radiation.analytic import analytic_hydro
from wecss.compiled import from_impulse_response
from wecss.radiation import impulse_response
from wecss.sim._memory import block_history, block_length, far_sums_array, memory_advance, memory_history


def dense_kernel(arrays) -> np.ndarray:
    """The weights of the stored lags as a dense (lag, row, column) array, lag 0 unused: an independent reading of
    the arrays' layout (fine lags nf ... 1, then the coarse tail nf + stride * (nc ... 1), oldest first)."""
    n_h = arrays.newest.shape[0]
    dense = np.zeros((arrays.depth, n_h, n_h))
    for c in range(n_h):
        rows = arrays.row[arrays.col[c] : arrays.col[c + 1]]
        nf, nc = int(arrays.fine_length[c]), int(arrays.coarse_length[c])
        fine = arrays.fine[arrays.fine_start[c] :][: nf * rows.size].reshape(nf, rows.size)
        coarse = arrays.coarse[arrays.coarse_start[c] :][: nc * rows.size].reshape(nc, rows.size)
        for j in range(nf):
            dense[nf - j, rows, c] = fine[j]
        for j in range(nc):
            dense[nf + arrays.stride * (nc - j), rows, c] = coarse[j]
    return dense


@pytest.mark.parametrize(("fine_memory", "coarse_step"), [(3.0, 0.06), (0.1, 0.06), (3.0, 0.0)])
def test_block_history_is_the_plain_convolution(fine_memory, coarse_step):
    """Random velocities over the ring buffer's length and a few hundred steps more (it wraps; blocks cross it):
    the blocked history and the step-by-step one equal sum_l K_l u_{n+1-l} to rounding. A short fine part
    (0.1 s) shortens the block so that every coarse lag stays far."""
    dt = 0.01
    arrays, _ = from_impulse_response(
        impulse_response(analytic_hydro()), dt, fine_memory=fine_memory, coarse_step=coarse_step
    )
    n_block = block_length(arrays)
    if fine_memory < 1.0:
        assert n_block == arrays.fine_length[0] + arrays.stride < 32
    dense = dense_kernel(arrays)
    n_h = arrays.newest.shape[0]
    rng = np.random.default_rng(3)
    velocities = [rng.normal(size=n_h)]
    buf = np.zeros((n_h, 2 * arrays.depth))
    buf[:, 0] = buf[:, arrays.depth] = velocities[0]
    pos = np.zeros(1, dtype=np.int64)
    far = far_sums_array(arrays)
    z = np.zeros(0, dtype=complex)
    worst_block = worst_step = scale = 0.0
    for n in range(arrays.depth + 300):
        past = np.array(velocities[::-1][: arrays.depth - 1])  # lag 1 first
        exact = np.einsum("lij,lj->i", dense[1 : past.shape[0] + 1], past)
        blocked = block_history(arrays, z, velocities[-1], buf, int(pos[0]), far, n % n_block)
        stepwise = memory_history(arrays, z, velocities[-1], buf, int(pos[0]))
        worst_block = max(worst_block, np.max(np.abs(blocked - exact)))
        worst_step = max(worst_step, np.max(np.abs(stepwise - exact)))
        scale = max(scale, np.max(np.abs(exact)))
        velocities.append(rng.normal(size=n_h))
        memory_advance(arrays, z, velocities[-2], velocities[-1], buf, pos)
    assert scale > 0
    assert worst_block <= 1e-12 * scale
    assert worst_step <= 1e-12 * scale
