"""Unit quaternions (w, x, y, z) for the rotation of a free base, integrated on SO(3)."""

from __future__ import annotations

import numpy as np


def to_matrix(quat: np.ndarray) -> np.ndarray:
    """Rotation matrix of a quaternion (w, x, y, z); the quaternion is normalised first."""
    w, x, y, z = np.asarray(quat, dtype=float) / np.linalg.norm(quat)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def multiply(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product a * b (rotation b then a, as matrices R_a R_b)."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array(
        [
            aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
        ]
    )


def exp(rotation_vector: np.ndarray) -> np.ndarray:
    """Quaternion of the rotation exp(hat(rotation_vector))."""
    r = np.asarray(rotation_vector, dtype=float)
    angle = float(np.linalg.norm(r))
    if angle < 1e-12:
        return np.array([1.0, *(0.5 * r)]) / np.sqrt(1.0 + 0.25 * angle**2)
    return np.array([np.cos(angle / 2), *(np.sin(angle / 2) / angle * r)])


def log(quat: np.ndarray) -> np.ndarray:
    """Rotation vector of a quaternion (angle in [0, pi])."""
    q = np.asarray(quat, dtype=float) / np.linalg.norm(quat)
    if q[0] < 0:
        q = -q
    s = float(np.linalg.norm(q[1:]))
    if s < 1e-12:
        return 2.0 * q[1:]
    return 2.0 * np.arctan2(s, q[0]) / s * q[1:]
