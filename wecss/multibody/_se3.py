"""SO(3) and SE(3) helpers: hat/vee, exponential and logarithm maps, frame connection matrices (MFM Eq. 4),
their analytic inverse (Eq. 8), the adjoint map and the Lie bracket of twists.

Twists are 6-vectors ``(v, w)``: linear part first, angular part second, matching the order of the
Cartesian velocities in the MFM (translational then rotational per body). A spatial twist ``(v, w)`` of a
rigid motion means: the body point at the world origin moves with velocity ``v`` and the body turns at ``w``.
"""

from __future__ import annotations

import numpy as np

_SMALL = 1e-8


def cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b of two 3-vectors (3,): ``np.cross``'s arithmetic, term for term (the same numbers), without its
    overhead on single vectors (about ten times faster; the loads' recovery makes some 16 per step)."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def hat(w: np.ndarray) -> np.ndarray:
    """Skew-symmetric 3x3 matrix of a 3-vector (``hat(w) @ v == cross(w, v)``); works on stacks (..., 3)."""
    w = np.asarray(w, dtype=float)
    out = np.zeros((*w.shape[:-1], 3, 3))
    out[..., 0, 1], out[..., 0, 2] = -w[..., 2], w[..., 1]
    out[..., 1, 0], out[..., 1, 2] = w[..., 2], -w[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -w[..., 1], w[..., 0]
    return out


def vee(m: np.ndarray) -> np.ndarray:
    """Inverse of :func:`hat`: the 3-vector of a skew-symmetric matrix (its skew part if not exactly skew)."""
    m = np.asarray(m, dtype=float)
    return 0.5 * np.stack([m[..., 2, 1] - m[..., 1, 2], m[..., 0, 2] - m[..., 2, 0], m[..., 1, 0] - m[..., 0, 1]], -1)


def so3_exp(w: np.ndarray) -> np.ndarray:
    """Rotation matrix exp(hat(w)) (Rodrigues' formula; accurate for small angles)."""
    w = np.asarray(w, dtype=float)
    theta = float(np.linalg.norm(w))
    k = hat(w)
    if theta < _SMALL:
        return np.eye(3) + k + 0.5 * k @ k
    return np.eye(3) + np.sin(theta) / theta * k + (1.0 - np.cos(theta)) / theta**2 * k @ k


def so3_log(r: np.ndarray) -> np.ndarray:
    """Rotation vector w with exp(hat(w)) = r, |w| <= pi.

    Raises
    ------
    ValueError
        If ``r`` is not a rotation matrix (orthonormal with determinant +1 to 1e-6).
    """
    r = np.asarray(r, dtype=float)
    if r.shape != (3, 3) or not np.allclose(r.T @ r, np.eye(3), atol=1e-6) or np.linalg.det(r) < 0:
        raise ValueError("so3_log needs a 3x3 rotation matrix (orthonormal, determinant +1)")
    cos = np.clip((np.trace(r) - 1.0) / 2.0, -1.0, 1.0)
    theta = float(np.arccos(cos))
    if theta < _SMALL:
        return vee(r)
    if np.pi - theta < 1e-6:
        # near pi: axis from the symmetric part, r = 2 a a^T - I
        sym = (r + np.eye(3)) / 2.0
        axis = sym[:, int(np.argmax(np.diag(sym)))]
        axis = axis / np.linalg.norm(axis)
        return theta * axis
    return theta / np.sin(theta) * vee(r)


def frame(r: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Frame connection matrix E = [[R, x], [0, 1]] (MFM Eq. 4)."""
    e = np.eye(4)
    e[:3, :3] = r
    e[:3, 3] = x
    return e


def frame_inverse(e: np.ndarray) -> np.ndarray:
    """Analytic inverse of a frame connection matrix, [[R^T, -R^T x], [0, 1]] (MFM Eq. 8)."""
    r, x = e[:3, :3], e[:3, 3]
    return frame(r.T, -r.T @ x)


def se3_exp(twist: np.ndarray) -> np.ndarray:
    """Frame connection matrix exp of a twist ``(v, w)`` (screw motion for unit time)."""
    twist = np.asarray(twist, dtype=float)
    v, w = twist[:3], twist[3:]
    theta = float(np.linalg.norm(w))
    k = hat(w)
    if theta < _SMALL:
        jac = np.eye(3) + 0.5 * k
    else:
        jac = np.eye(3) + (1.0 - np.cos(theta)) / theta**2 * k + (theta - np.sin(theta)) / theta**3 * k @ k
    return frame(so3_exp(w), jac @ v)


def se3_log(e: np.ndarray) -> np.ndarray:
    """Twist ``(v, w)`` with se3_exp(twist) = e (inverse of :func:`se3_exp` for rotation angles below pi)."""
    w = so3_log(e[:3, :3])
    theta = float(np.linalg.norm(w))
    k = hat(w)
    if theta < _SMALL:
        jac_inv = np.eye(3) - 0.5 * k
    else:
        half = theta / 2.0
        jac_inv = np.eye(3) - 0.5 * k + (1.0 - half / np.tan(half)) / theta**2 * k @ k
    return np.concatenate([jac_inv @ e[:3, 3], w])


def adjoint(e: np.ndarray) -> np.ndarray:
    """6x6 adjoint of a frame connection matrix acting on twists ``(v, w)``: [[R, hat(x) R], [0, R]]."""
    r, x = e[:3, :3], e[:3, 3]
    out = np.zeros((6, 6))
    out[:3, :3] = r
    out[:3, 3:] = hat(x) @ r
    out[3:, 3:] = r
    return out


def twist_bracket(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Lie bracket [a, b] of twists ``(v, w)``: ``(w_a x v_b - w_b x v_a, w_a x w_b)``.

    ``d/dt (Ad(G(t)) xi) = [V, Ad(G(t)) xi]`` for a constant twist xi when G has spatial velocity V.
    Works on stacks (..., 6).
    """
    va, wa = a[..., :3], a[..., 3:]
    vb, wb = b[..., :3], b[..., 3:]
    return np.concatenate([np.cross(wa, vb) - np.cross(wb, va), np.cross(wa, wb)], axis=-1)
