"""The radiation memory force in the time loop: the history part of a step, and the move over a completed step.

The force at the end of a step is ``history + newest @ u_new`` (``wecss.compiled.RadiationArrays``). For the
convolution the history is a weighted sum of the past velocities, lags 1 ... L of the ring buffer: on the default
scene (M4 134) 561,024 multiply-adds over 4.5 MB of kernel values per step, which a step-by-step sum reads from
memory every step.

Blocked in time instead: for a block of B steps starting after the newest stored velocity u_n, the terms of
target step n + b (b = 1 ... B) with velocities up to u_n are its lags l >= b. Those *far* sums are formed for all
B targets in one pass over the kernel, each kernel value multiplying the B velocities it meets (a matrix-matrix
product instead of B matrix-vector products; the kernel is read once per block). The *near* terms, lags 1 ... b-1
(velocities of the block itself, known only as it proceeds), are added step by step. The coarse tail's lags are all
at least B (``block_length``), so they are all far. Each entry's sum runs over its lags oldest first (two at a
time) in both the block and the step-by-step form (a block of one step), so the two agree to rounding. On the
default scene the history costs about 50 us of CPU per step in blocks of 32, against about 270 us for the former
step-by-step sum (measured on a loaded machine; blocks of 16 to 128 within 15 %: the far sums are then bound by
the multiply-adds, not by memory).
"""

from __future__ import annotations

import numpy as np

from ..compiled import RadiationArrays, RadiationKind
from ..compiled.kernels import kernel, matvec, matvec_add, reduction_kernel, step_kernel

BLOCK_STEPS: int = 32
"""Steps per block of the convolution's far sums (at most; see :func:`block_length`)."""


def block_length(r: RadiationArrays) -> int:
    """Steps per block of the convolution's far sums: BLOCK_STEPS, or fewer so that every coarse lag is at least
    the block (then all coarse terms are far); 1 without a convolution."""
    if r.kind != RadiationKind.CONVOLUTION:
        return 1
    with_tail = r.coarse_length > 0
    shortest = int(np.min(r.fine_length[with_tail] + r.stride)) if np.any(with_tail) else BLOCK_STEPS
    return max(1, min(BLOCK_STEPS, shortest))


def far_sums_array(r: RadiationArrays) -> np.ndarray:
    """The zeroed array of the far sums (``block_length(r)``, kernel entries) that :func:`block_history` fills."""
    return np.zeros((block_length(r), r.row.size))


@reduction_kernel
def _add_pair(
    acc: np.ndarray, w1: np.ndarray, w2: np.ndarray, history: np.ndarray, i1: int, i2: int, b0: int, b1: int
) -> None:
    """acc[b] += w1 history[i1 + b] + w2 history[i2 + b] for b in [b0, b1): two lags per pass over the sums (half
    their loads and stores)."""
    for b in range(b0, b1):
        u1 = history[i1 + b]
        u2 = history[i2 + b]
        a = acc[b]
        for k in range(a.shape[0]):
            a[k] += w1[k] * u1 + w2[k] * u2


@reduction_kernel
def _add_one(acc: np.ndarray, w: np.ndarray, history: np.ndarray, i0: int, b0: int, b1: int) -> None:
    """acc[b] += w history[i0 + b] for b in [b0, b1)."""
    for b in range(b0, b1):
        u = history[i0 + b]
        a = acc[b]
        for k in range(a.shape[0]):
            a[k] += w[k] * u


@reduction_kernel
def _far_sums(r: RadiationArrays, buf: np.ndarray, pos: int, far: np.ndarray) -> None:
    """far[b, e] <- the history sum of kernel entry e (ordered as ``r.row``) at the end of the b-th step after the
    newest stored velocity (b = 0 ... far.shape[0] - 1), over its lags l > b, all of them in the buffer now.

    Per radiating DOF (column) c, each stored kernel value multiplies the velocities of the block's targets it
    meets, two lags at a time; the sums of the column's rows for all targets stay in a small (block, rows) array.
    The kernel values are taken as slices (numba vectorises those loops, not ones on an offset index)."""
    n_block = far.shape[0]
    fine, coarse, stride = r.fine, r.coarse, r.stride
    zero = pos + r.depth + 1  # target b's lag l sits in column zero + b - l of the doubled ring buffer
    for c in range(r.col.shape[0] - 1):
        lo = r.col[c]
        n_rows = r.col[c + 1] - lo
        if n_rows == 0:
            continue
        history = buf[c]
        acc = np.zeros((n_block, n_rows))
        nf = r.fine_length[c]
        nc = r.coarse_length[c]
        s = r.coarse_start[c]
        base = zero - nf - stride * nc  # the oldest coarse lag, nf + stride * (nc - j) for the j-th stored
        for j in range(0, nc - 1, 2):  # every coarse lag is at least the block (block_length): all far
            k0 = s + j * n_rows
            w1, w2 = coarse[k0 : k0 + n_rows], coarse[k0 + n_rows : k0 + 2 * n_rows]
            _add_pair(acc, w1, w2, history, base + stride * j, base + stride * (j + 1), 0, n_block)
        if nc % 2:
            k0 = s + (nc - 1) * n_rows
            _add_one(acc, coarse[k0 : k0 + n_rows], history, base + stride * (nc - 1), 0, n_block)
        s = r.fine_start[c]
        base = zero - nf  # the oldest fine lag, nf - j for the j-th stored; far for the targets b < nf - j
        for j in range(0, nf - 1, 2):
            k0 = s + j * n_rows
            w1, w2 = fine[k0 : k0 + n_rows], fine[k0 + n_rows : k0 + 2 * n_rows]
            both = min(n_block, nf - j - 1)
            _add_pair(acc, w1, w2, history, base + j, base + j + 1, 0, both)
            _add_one(acc, w1, history, base + j, both, min(n_block, nf - j))
        if nf % 2:
            k0 = s + (nf - 1) * n_rows
            _add_one(acc, fine[k0 : k0 + n_rows], history, base + nf - 1, 0, min(n_block, 1))
        for b in range(n_block):
            for k in range(n_rows):
                far[b, lo + k] = acc[b, k]


@reduction_kernel
def _add_near(r: RadiationArrays, buf: np.ndarray, pos: int, far_row: np.ndarray, offset: int) -> np.ndarray:
    """The history sum at the end of the coming step, ``offset`` steps into its block: the far sums ``far_row``
    plus the fine lags 1 ... offset (oldest first), gathered onto the rows (world axes) [N, N m]."""
    out = np.zeros(r.newest.shape[0])
    zero = pos + r.depth + 1  # lag l sits in column zero - l (lag 1: the newest stored velocity)
    for c in range(r.col.shape[0] - 1):
        lo = r.col[c]
        n_rows = r.col[c + 1] - lo
        if n_rows == 0:
            continue
        history = buf[c]
        acc = far_row[lo : lo + n_rows].copy()
        nf = r.fine_length[c]
        s = r.fine_start[c]
        for lag in range(min(offset, nf), 0, -1):
            u = history[zero - lag]
            k0 = s + (nf - lag) * n_rows
            w = r.fine[k0 : k0 + n_rows]
            for k in range(n_rows):
                acc[k] += w[k] * u
        for k in range(n_rows):
            out[r.row[lo + k]] += acc[k]
    return out


@step_kernel
def _state_space_history(r: RadiationArrays, z: np.ndarray, u_now: np.ndarray) -> np.ndarray:
    out = np.zeros(u_now.shape[0])
    if r.kind == RadiationKind.STATE_SPACE:
        matvec(r.history_state, z.view(np.float64), out)
        matvec_add(r.history_input, u_now, out)
    return out


@kernel
def memory_history(r: RadiationArrays, z: np.ndarray, u_now: np.ndarray, buf: np.ndarray, pos: int) -> np.ndarray:
    """Memory force at the end of the coming step without the newest-velocity term (world axes) [N, N m]; the
    convolution summed step by step (a block of one step)."""
    if r.kind == RadiationKind.CONVOLUTION:
        far = np.empty((1, r.row.shape[0]))
        _far_sums(r, buf, pos, far)
        return _add_near(r, buf, pos, far[0], 0)
    return _state_space_history(r, z, u_now)


@kernel
def block_history(
    r: RadiationArrays, z: np.ndarray, u_now: np.ndarray, buf: np.ndarray, pos: int, far: np.ndarray, offset: int
) -> np.ndarray:
    """As :func:`memory_history`, the convolution's far sums formed for a block of ``far.shape[0]`` steps at its
    first step (``offset`` 0: ``far`` filled) and read at the others (``offset`` steps into the block, ``far``
    untouched since, the buffer advanced by :func:`memory_advance` once per step)."""
    if r.kind == RadiationKind.CONVOLUTION:
        if offset == 0:
            _far_sums(r, buf, pos, far)
        return _add_near(r, buf, pos, far[offset], offset)
    return _state_space_history(r, z, u_now)


@step_kernel
def _advance_states(r: RadiationArrays, z: np.ndarray, u_now: np.ndarray, u_new: np.ndarray) -> None:
    """z <- e^{lambda h} z + hold0 u_now + hold1 u_new, on the real and imaginary parts (``r.hold_real``)."""
    n_h = u_now.shape[0]
    both = np.empty(2 * n_h)
    both[:n_h] = u_now
    both[n_h:] = u_new
    z *= r.decay
    matvec_add(r.hold_real, both, z.view(np.float64))


@kernel
def memory_advance(
    r: RadiationArrays, z: np.ndarray, u_now: np.ndarray, u_new: np.ndarray, buf: np.ndarray, pos: np.ndarray
) -> None:
    """Move the memory over a completed step (states, or the velocity ring buffer, one row per DOF)."""
    if r.kind == RadiationKind.STATE_SPACE:
        _advance_states(r, z, u_now, u_new)
    elif r.kind == RadiationKind.CONVOLUTION:
        k = (pos[0] + 1) % r.depth
        buf[:, k] = u_new
        buf[:, k + r.depth] = u_new
        pos[0] = k
