"""Modal reduction of a flexible body: Craig-Bampton with inertia-relief Ritz vectors, made mass-orthonormal and
stiffness-diagonal.

The body is held (clamped, all six DOFs) at its parent joint: the elastic displacement of a floating frame of
reference attached there. The Ritz vectors are

- constraint modes: the static shape of a unit displacement of one DOF of an interface (a child joint: its node's
  six DOFs; a PTO attachment on a node: its three translations, a point force being all it transmits), the other
  interface DOFs held;
- fixed-interface normal modes: the lowest natural modes with the clamp and every interface DOF held;
- inertia-relief vectors: the static shape, interfaces held, of the loads of the body's own weight and of a
  rigid-body acceleration (g - a and alpha, six load patterns); with ``centrifugal`` also the six patterns of the
  angular velocity's products (centrifugal and gyroscopic loads of a rotation).

So the quasi-static response to any load at the interfaces, to the body's weight and to its rigid-body acceleration
lies in the basis exactly, whatever the number of normal modes. The vectors are then orthonormalised: M-orthonormal
and K-diagonal (the reduced eigenproblem), directions of the span with a mass below ``rank_tolerance`` of the
largest (vectors that repeat others, e.g. with all normal modes kept) are dropped.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import cho_factor, cho_solve, eigh

from ._frame import Frame
from ._solve import natural_modes

INTERFACE_KINDS = ("joint", "force")
"""An interface transmits forces and moments (``"joint"``: a child joint, six DOFs) or a point force only
(``"force"``: a PTO attachment, three DOFs when it sits on a node)."""


@dataclass(frozen=True, eq=False)
class ModalBasis:
    """A flexible body's reduced basis (see the module docstring).

    Attributes
    ----------
    frame : Frame
    basis : ndarray (n_dof, n)
        Phi: nodal displacements per modal coordinate [m, rad per 1], zero on the clamped DOFs; Phi' M Phi = I,
        Phi' K Phi = diag(omega^2).
    omega : ndarray (n,)
        sqrt of the diagonal stiffness, ascending [rad/s] (the natural frequencies of the reduced body, clamped).
    clamp : str
        The point where the body is held.
    clamped : ndarray of int
        The held DOFs.
    boundary : mapping of str to ndarray of int
        The DOFs of each interface.
    damping_ratio : float
        Structural damping ratio of every basis vector [-] (the damping matrix is diag(2 zeta omega)).
    counts : mapping of str to int
        Vectors of each kind before orthonormalisation (``constraint``, ``normal``, ``inertia_relief``,
        ``centrifugal``) and the directions dropped (``dropped``).
    """

    frame: Frame
    basis: np.ndarray
    omega: np.ndarray
    clamp: str
    clamped: np.ndarray
    boundary: Mapping[str, np.ndarray]
    damping_ratio: float = 0.0
    counts: Mapping[str, int] = field(default_factory=dict)

    @property
    def n(self) -> int:
        """Number of modal coordinates."""
        return self.basis.shape[1]

    @property
    def mass(self) -> np.ndarray:
        """Modal mass (n, n): the identity [kg m^2 per unit coordinate, with Phi in m per 1]."""
        return np.eye(self.n)

    @property
    def stiffness(self) -> np.ndarray:
        """Modal stiffness diag(omega^2) (n, n) [N m]."""
        return np.diag(self.omega**2)

    @property
    def damping(self) -> np.ndarray:
        """Modal damping diag(2 zeta omega) (n, n) [N m s]."""
        return np.diag(2 * self.damping_ratio * self.omega)


def craig_bampton(
    frame: Frame,
    clamp: str,
    interfaces: Mapping[str, str] | None = None,
    n_modes: int = 6,
    *,
    inertia_relief: bool = True,
    centrifugal: bool = False,
    damping_ratio: float = 0.0,
    rank_tolerance: float = 1e-10,
) -> ModalBasis:
    """Reduce ``frame`` held at the point ``clamp`` (see the module docstring).

    Parameters
    ----------
    frame : Frame
    clamp : str
        Name of the frame's point where the body is held (its parent joint).
    interfaces : mapping of str to str
        Point name to kind (:data:`INTERFACE_KINDS`): child joints and PTO attachments.
    n_modes : int
        Fixed-interface normal modes to keep (at most the interior DOFs).
    inertia_relief, centrifugal : bool
        Add the six rigid-acceleration load vectors, and the six angular-velocity ones.
    damping_ratio : float
        Structural damping ratio [-], 0 <= zeta < 1.
    rank_tolerance : float
        Relative mass below which a direction of the span is dropped.

    Raises
    ------
    ValueError
        On an unknown kind, an interface on the clamp's node, a negative number of modes, a damping ratio outside
        [0, 1), or a clamp that leaves a mechanism.
    KeyError
        On a point the frame does not have.
    """
    interfaces = dict(interfaces or {})
    if isinstance(n_modes, bool) or not isinstance(n_modes, int) or n_modes < 0:
        raise ValueError(f"n_modes must be an integer >= 0; got {n_modes!r}")
    if not (isinstance(damping_ratio, int | float) and 0.0 <= damping_ratio < 1.0):
        raise ValueError(f"damping_ratio must be a number in [0, 1); got {damping_ratio!r}")
    clamp_node, _ = frame.point(clamp)
    clamped = frame.node_dofs(clamp_node)
    boundary: dict[str, np.ndarray] = {}
    for name, kind in interfaces.items():
        if kind not in INTERFACE_KINDS:
            raise ValueError(f"interface {name!r}: kind {kind!r}; accepted: {list(INTERFACE_KINDS)}")
        node, position = frame.point(name)
        if node == clamp_node:
            raise ValueError(
                f"interface {name!r} rides on the clamp's node {node} (point {clamp!r}): it cannot move elastically; "
                "leave it out of the interfaces"
            )
        on_node = np.allclose(position, frame.nodes[node], rtol=0, atol=1e-12 * max(1.0, float(np.abs(position).max())))
        dofs = frame.node_dofs(node)
        boundary[name] = dofs[:3] if (kind == "force" and on_node) else dofs
    k, m = frame.stiffness, frame.mass
    b = np.unique(np.concatenate(list(boundary.values()))) if boundary else np.zeros(0, dtype=np.int64)
    interior = np.setdiff1d(np.setdiff1d(np.arange(frame.n_dof), clamped), b)
    try:
        factor = cho_factor(k[np.ix_(interior, interior)])
    except np.linalg.LinAlgError:
        raise ValueError(f"held at {clamp!r} and at its interfaces the body is still a mechanism") from None
    columns = []
    constraint = np.zeros((frame.n_dof, b.size))
    constraint[b, np.arange(b.size)] = 1.0
    if b.size:
        constraint[interior] = -cho_solve(factor, k[np.ix_(interior, b)])
    columns.append(constraint)
    n_normal = min(n_modes, interior.size)
    if n_normal:
        _, normal = natural_modes(k, m, fixed=np.concatenate([clamped, b]), n_modes=n_normal)
        columns.append(normal)
    origin = frame.nodes[clamp_node]
    loads = frame.rigid_motion_loads(origin)
    counts = {"constraint": b.size, "normal": n_normal, "inertia_relief": 0, "centrifugal": 0}
    chosen = np.array(
        ([0, 1, 2, 3, 4, 5] if inertia_relief else []) + ([6, 7, 8, 9, 10, 11] if centrifugal else []), dtype=np.int64
    )
    if chosen.size:
        relief = np.zeros((frame.n_dof, len(chosen)))
        relief[interior] = cho_solve(factor, loads[np.ix_(interior, chosen)])
        counts["inertia_relief"] = 6 if inertia_relief else 0
        counts["centrifugal"] = 6 if centrifugal else 0
        columns.append(relief)
    vectors = np.hstack(columns)
    norms = np.sqrt(np.einsum("ij,ik,kj->j", vectors, m, vectors))
    vectors = vectors[:, norms > 0] / norms[norms > 0]
    values, q = eigh(vectors.T @ m @ vectors)
    keep = values > rank_tolerance * values.max() if values.size else np.zeros(0, dtype=bool)
    counts["dropped"] = int(vectors.shape[1] - keep.sum())
    basis = vectors @ (q[:, keep] / np.sqrt(values[keep]))
    for _ in range(2):  # the second pass removes what round-off left of nearly repeated vectors (1e-11 to 1e-15)
        values, q = eigh(basis.T @ m @ basis)
        basis = basis @ (q / np.sqrt(values))
        omega2, r = eigh(basis.T @ k @ basis)
        basis = basis @ r
    return ModalBasis(
        frame, basis, np.sqrt(np.clip(omega2, 0.0, None)), clamp, clamped, boundary, float(damping_ratio), counts
    )
