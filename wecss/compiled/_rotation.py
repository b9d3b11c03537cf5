"""The rotation vector of a rotation matrix, inside the kernels."""

from __future__ import annotations

import numpy as np

from ._jit import inline_kernel

_SMALL = 1e-8


@inline_kernel
def so3_log_into(r: np.ndarray, out: np.ndarray) -> None:
    """The rotation vector of the rotation matrix ``r`` (3, 3) into ``out`` (3,) [rad]."""
    cos = min(1.0, max(-1.0, (r[0, 0] + r[1, 1] + r[2, 2] - 1.0) / 2.0))
    theta = np.arccos(cos)
    v0, v1, v2 = 0.5 * (r[2, 1] - r[1, 2]), 0.5 * (r[0, 2] - r[2, 0]), 0.5 * (r[1, 0] - r[0, 1])
    if theta < _SMALL:
        out[0], out[1], out[2] = v0, v1, v2
    elif np.pi - theta < 1e-6:
        k = 0  # the column of (R + I)/2 = n n' with the largest diagonal entry (the first of equals)
        if r[1, 1] > r[k, k]:
            k = 1
        if r[2, 2] > r[k, k]:
            k = 2
        a0, a1, a2 = r[0, k], r[1, k], r[2, k]
        if k == 0:
            a0 += 1.0
        elif k == 1:
            a1 += 1.0
        else:
            a2 += 1.0
        scale = theta / np.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
        out[0], out[1], out[2] = scale * a0, scale * a1, scale * a2
    else:
        scale = theta / np.sin(theta)
        out[0], out[1], out[2] = scale * v0, scale * v1, scale * v2
