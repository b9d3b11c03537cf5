"""Static responses and natural modes of a structure with some DOFs held at zero (supports)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.linalg import cho_factor, cho_solve, eigh


def free_dofs(n_dof: int, fixed: Sequence[int] | np.ndarray) -> np.ndarray:
    """The DOF indices not in ``fixed``.

    Raises
    ------
    ValueError
        If a fixed index is outside 0 .. n_dof - 1.
    """
    held = np.unique(np.asarray(fixed, dtype=np.int64))
    if held.size and (held[0] < 0 or held[-1] >= n_dof):
        raise ValueError(f"fixed DOFs must lie in 0 .. {n_dof - 1}; got {held.tolist()}")
    return np.setdiff1d(np.arange(n_dof), held)


def static_response(stiffness: np.ndarray, loads: np.ndarray, fixed: Sequence[int] | np.ndarray = ()) -> np.ndarray:
    """Displacements u (n_dof, ...) with K u = f on the free DOFs and u = 0 on the fixed ones.

    Raises
    ------
    ValueError
        If the supports leave a mechanism (the free stiffness is not positive definite).
    """
    k = np.asarray(stiffness, dtype=float)
    f = np.asarray(loads, dtype=float)
    free = free_dofs(k.shape[0], fixed)
    try:
        factor = cho_factor(k[np.ix_(free, free)])
    except np.linalg.LinAlgError:
        raise ValueError(
            "the supports leave the structure free to move as a mechanism (stiffness not definite)"
        ) from None
    out = np.zeros(f.shape)
    out[free] = cho_solve(factor, f[free])
    return out


def natural_modes(
    stiffness: np.ndarray, mass: np.ndarray, fixed: Sequence[int] | np.ndarray = (), n_modes: int | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Angular frequencies omega [rad/s] (ascending) and mass-normalised mode shapes (n_dof, n) of K phi = omega^2
    M phi with the fixed DOFs held at zero.

    When the held stiffness is positive definite the reciprocal problem M phi = (1 / omega^2) K phi is solved: its
    largest values, the lowest modes, come with full relative accuracy (the direct problem loses the low modes of a
    stiff structure to the round-off of its highest ones); otherwise the direct problem (rigid-body modes at 0).

    Raises
    ------
    ValueError
        If the held mass is not positive definite.
    """
    k = np.asarray(stiffness, dtype=float)
    m = np.asarray(mass, dtype=float)
    free = free_dofs(k.shape[0], fixed)
    kf, mf = k[np.ix_(free, free)], m[np.ix_(free, free)]
    n = len(free) if n_modes is None else min(int(n_modes), len(free))
    try:
        np.linalg.cholesky(mf)
    except np.linalg.LinAlgError:
        raise ValueError("the mass matrix of the free DOFs is not positive definite (a DOF without mass)") from None
    try:
        np.linalg.cholesky(kf)
        definite = True
    except np.linalg.LinAlgError:
        definite = False
    if definite:
        values, vectors = eigh(mf, kf, subset_by_index=[len(free) - n, len(free) - 1] if n else None)
        values, vectors = 1.0 / values[::-1], vectors[:, ::-1]
    else:
        values, vectors = eigh(kf, mf, subset_by_index=[0, n - 1] if n else None)
    vectors = vectors / np.sqrt(np.einsum("ij,ik,kj->j", vectors, mf, vectors))
    shapes = np.zeros((k.shape[0], vectors.shape[1]))
    shapes[free] = vectors
    return np.sqrt(np.clip(values, 0.0, None)), shapes
