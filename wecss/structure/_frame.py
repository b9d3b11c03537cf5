"""A frame: nodes, beam elements, lumped masses and named points, assembled into stiffness, mass and load vectors.

Everything is in the body's axes (the world axes of the reference configuration, as the device spec gives its
members). DOFs: six per node, node after node: u_x, u_y, u_z [m] and theta_x, theta_y, theta_z [rad]
(``Frame.node_dofs``). A named point (a joint point, a PTO attachment, a lumped mass) rides on a node through a rigid
offset r = point - node: its displacement is u_node + theta_node x r and its rotation theta_node.

The mass of the frame is a set of mass points (``Frame.mass_points``): the quadrature points of every element and the
lumped masses, each with a mass, a rotary inertia and the interpolation of displacement and rotation there. The
consistent mass matrix, the loads of a rigid-body motion and the floating-frame invariants are all sums over these
points, so they agree with each other exactly.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ._element import NODE_DOFS, BeamElement

RIGID_LOADS = (
    "gx-ax",
    "gy-ay",
    "gz-az",
    "alpha_x",
    "alpha_y",
    "alpha_z",
    "wx*wx",
    "wy*wy",
    "wz*wz",
    "wx*wy",
    "wy*wz",
    "wz*wx",
)
"""The coordinates r of a rigid-body motion's load on a body, in body axes: gravity minus the acceleration of the
body frame's origin g - a [m/s^2], the angular acceleration alpha [rad/s^2] and the products of the angular velocity's
components [rad^2/s^2]. The loads of the body's own weight and d'Alembert inertia are linear in them."""

PAIRS = ((0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0))
"""The (a, b) of the angular-velocity products w_a w_b of :data:`RIGID_LOADS` (its last six coordinates)."""


def rigid_load_coordinates(gravity_minus_acceleration: np.ndarray, alpha: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """The :data:`RIGID_LOADS` coordinates (..., 12) of a rigid-body motion from g - a [m/s^2], the angular
    acceleration alpha [rad/s^2] and velocity omega [rad/s] (each (..., 3), body axes)."""
    w = np.asarray(omega, dtype=float)
    products = np.stack([w[..., a] * w[..., b] for a, b in PAIRS], axis=-1)
    return np.concatenate([np.asarray(gravity_minus_acceleration, dtype=float), np.asarray(alpha, dtype=float),
                           products], axis=-1)  # fmt: skip


COMPONENTS = ("ux", "uy", "uz", "rx", "ry", "rz")
"""Names of a node's six DOFs, in order: displacements and rotations along the body's x, y, z."""


def hat(v: np.ndarray) -> np.ndarray:
    """The cross-product matrix of ``v`` (3,): hat(v) @ w = v x w."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def offset_map(offset: np.ndarray) -> np.ndarray:
    """(6, 6) map from a node's DOFs to those of a point rigidly attached at ``offset`` = point - node [m]."""
    out = np.eye(6)
    out[:3, 3:] = -hat(np.asarray(offset, dtype=float))
    return out


@dataclass(frozen=True)
class PointMass:
    """A lumped mass on a frame.

    Attributes
    ----------
    name : str
    node : int
        The node it rides on.
    position : ndarray (3,)
        Its centre of mass in body axes [m] (rigidly offset from the node).
    mass : float
        [kg].
    inertia : ndarray (3, 3)
        Rotary inertia about its centre of mass in body axes [kg m^2].
    """

    name: str
    node: int
    position: np.ndarray
    mass: float
    inertia: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))


@dataclass(frozen=True)
class MassGroup:
    """Mass points sharing DOFs: ``dofs`` (k,), ``positions`` (p, 3) [m], ``masses`` (p,) [kg], ``inertias``
    (p, 3, 3) [kg m^2], ``nu``, ``ntheta`` (p, 3, k): displacement and rotation at each point per DOF."""

    dofs: np.ndarray
    positions: np.ndarray
    masses: np.ndarray
    inertias: np.ndarray
    nu: np.ndarray
    ntheta: np.ndarray


@dataclass(frozen=True, eq=False)
class Frame:
    """Nodes, beam elements, lumped masses and named points of one structure (see the module docstring).

    Parameters
    ----------
    nodes : array_like (n, 3)
        Node positions in body axes [m].
    elements : sequence of BeamElement
    masses : sequence of PointMass
    points : mapping of str to (node, position)
        Named points and the node each rides on.

    Raises
    ------
    ValueError
        On elements or masses that name nodes that do not exist or whose ends are not at their nodes, or points on
        nodes that do not exist.
    """

    nodes: np.ndarray
    elements: tuple[BeamElement, ...]
    masses: tuple[PointMass, ...] = ()
    points: Mapping[str, tuple[int, np.ndarray]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        nodes = np.asarray(self.nodes, dtype=float)
        if nodes.ndim != 2 or nodes.shape[1] != 3 or not np.all(np.isfinite(nodes)):
            raise ValueError(f"nodes must be an (n, 3) array of positions [m]; got shape {nodes.shape}")
        object.__setattr__(self, "nodes", nodes)
        object.__setattr__(self, "elements", tuple(self.elements))
        object.__setattr__(self, "masses", tuple(self.masses))
        n = len(nodes)
        scale = max(1.0, float(np.abs(nodes).max())) if n else 1.0
        for e in self.elements:
            if not (0 <= e.i < n and 0 <= e.j < n) or e.i == e.j:
                raise ValueError(f"element of member {e.member!r} joins nodes {e.i}, {e.j}; the frame has {n} nodes")
            if not (
                np.allclose(e.start, nodes[e.i], atol=1e-9 * scale)
                and np.allclose(e.end, nodes[e.j], atol=1e-9 * scale)
            ):
                raise ValueError(f"element of member {e.member!r} does not end at its nodes {e.i}, {e.j}")  # fmt: skip
        for m in self.masses:
            if not 0 <= m.node < n:
                raise ValueError(f"mass {m.name!r} rides on node {m.node}; the frame has {n} nodes")
        points = {str(k): (int(v[0]), np.asarray(v[1], dtype=float)) for k, v in self.points.items()}
        for name, (node, _) in points.items():
            if not 0 <= node < n:
                raise ValueError(f"point {name!r} rides on node {node}; the frame has {n} nodes")
        object.__setattr__(self, "points", points)

    # --- sizes and indices --------------------------------------------------------------------------
    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.nodes)

    @property
    def n_dof(self) -> int:
        """Number of DOFs (six per node)."""
        return NODE_DOFS * self.n_nodes

    def node_dofs(self, node: int) -> np.ndarray:
        """The six DOF indices of ``node``."""
        return np.arange(NODE_DOFS * node, NODE_DOFS * (node + 1))

    def element_dofs(self, element: BeamElement) -> np.ndarray:
        """The twelve DOF indices of an element (node i's, then node j's)."""
        return np.concatenate([self.node_dofs(element.i), self.node_dofs(element.j)])

    def point(self, name: str) -> tuple[int, np.ndarray]:
        """(node, position) of a named point.

        Raises
        ------
        KeyError
            If there is no such point (the message lists them).
        """
        if name not in self.points:
            raise KeyError(f"the frame has no point {name!r}; points: {sorted(self.points)}")
        return self.points[name]

    def support(self, name: str, components: tuple[str, ...] = COMPONENTS) -> np.ndarray:
        """The DOF indices that hold a named point in the given components (:data:`COMPONENTS`), for the ``fixed``
        argument of ``static_response`` and ``natural_modes`` (a pin about y: all but ``"ry"``).

        Raises
        ------
        ValueError
            On an unknown component, or a partial support of a point off its node (hold all six there, or give the
            point a node).
        """
        unknown = sorted(set(components) - set(COMPONENTS))
        if unknown:
            raise ValueError(f"support of {name!r}: unknown components {unknown}; accepted: {list(COMPONENTS)}")
        node, position = self.point(name)
        off = not np.allclose(position, self.nodes[node], rtol=0, atol=1e-12 * max(1.0, float(np.abs(position).max())))
        if off and set(components) != set(COMPONENTS):
            raise ValueError(
                f"support of {name!r}: the point is {np.linalg.norm(position - self.nodes[node]):.3g} m off its node "
                f"{node}; a partial support {list(components)} needs the point on a node (hold all six, or mesh it)"
            )
        return self.node_dofs(node)[[COMPONENTS.index(c) for c in components]]

    def basis(self, basis: np.ndarray) -> np.ndarray:
        """``basis`` as a float array (n_dof, n) of fields over the frame's DOFs (one column per coordinate).

        Raises
        ------
        ValueError
            If it does not have one row per DOF of the frame.
        """
        phi = np.asarray(basis, dtype=float)
        if phi.ndim != 2 or phi.shape[0] != self.n_dof:
            raise ValueError(f"basis must be (n_dof = {self.n_dof}, n); got shape {phi.shape}")
        return phi

    def point_map(self, name: str) -> np.ndarray:
        """(6, n_dof): the displacement and rotation of a named point from the DOFs."""
        node, position = self.point(name)
        out = np.zeros((6, self.n_dof))
        out[:, self.node_dofs(node)] = offset_map(position - self.nodes[node])
        return out

    def members(self) -> dict[str, list[BeamElement]]:
        """The elements of each member, in order from its start."""
        out: dict[str, list[BeamElement]] = {}
        for e in self.elements:
            out.setdefault(e.member, []).append(e)
        return {k: sorted(v, key=lambda e: e.station) for k, v in out.items()}

    # --- matrices -----------------------------------------------------------------------------------
    @cached_property
    def stiffness(self) -> np.ndarray:
        """K (n_dof, n_dof) [N/m, N, N m/rad]."""
        out = np.zeros((self.n_dof, self.n_dof))
        for e in self.elements:
            idx = self.element_dofs(e)
            out[np.ix_(idx, idx)] += e.stiffness
        return 0.5 * (out + out.T)

    @cached_property
    def mass(self) -> np.ndarray:
        """Consistent M (n_dof, n_dof) [kg, kg m, kg m^2], the lumped masses included."""
        out = np.zeros((self.n_dof, self.n_dof))
        for g in self.mass_points:
            local = np.einsum("p,pai,paj->ij", g.masses, g.nu, g.nu) + np.einsum(
                "pai,pab,pbj->ij", g.ntheta, g.inertias, g.ntheta
            )
            out[np.ix_(g.dofs, g.dofs)] += local
        return 0.5 * (out + out.T)

    def geometric_stiffness(self, axial_force: Sequence[np.ndarray | float]) -> np.ndarray:
        """K_G (n_dof, n_dof) for the axial force in each element [N] (tension positive; per element one value or
        values at equally spaced stations from node i to node j, see ``BeamElement.local_geometric_stiffness``).

        Raises
        ------
        ValueError
            If the number of entries is not the number of elements.
        """
        if len(axial_force) != len(self.elements):
            raise ValueError(f"need one axial force per element ({len(self.elements)}); got {len(axial_force)}")
        out = np.zeros((self.n_dof, self.n_dof))
        for e, n in zip(self.elements, axial_force, strict=True):
            idx = self.element_dofs(e)
            out[np.ix_(idx, idx)] += e.geometric_stiffness(n)
        return 0.5 * (out + out.T)

    @cached_property
    def mass_points(self) -> tuple[MassGroup, ...]:
        """The frame's mass as mass points: one group per element (its quadrature points) and per lumped mass."""
        groups = []
        for e in self.elements:
            positions, masses, inertias, nu, nth = e.quadrature()
            groups.append(MassGroup(self.element_dofs(e), positions, masses, inertias, nu, nth))
        for m in self.masses:
            local = offset_map(m.position - self.nodes[m.node])
            groups.append(
                MassGroup(
                    self.node_dofs(m.node),
                    np.asarray(m.position, dtype=float)[None],
                    np.array([m.mass]),
                    np.asarray(m.inertia, dtype=float)[None],
                    local[None, :3],
                    local[None, 3:],
                )
            )
        return tuple(groups)

    # --- loads and rigid motion ---------------------------------------------------------------------
    def point_load(self, name: str, force: np.ndarray, moment: np.ndarray | None = None) -> np.ndarray:
        """Nodal loads (n_dof,) of a force [N] and a moment [N m] (body axes) at a named point."""
        wrench = np.concatenate([np.asarray(force, dtype=float), np.zeros(3) if moment is None else moment])
        return self.point_map(name).T @ wrench

    def rigid_modes(self, origin: np.ndarray) -> np.ndarray:
        """(n_dof, 6): the DOFs of a unit translation along x, y, z and a unit (small) rotation about axes through
        ``origin`` [m] (body axes)."""
        out = np.zeros((self.n_dof, 6))
        for k in range(self.n_nodes):
            out[self.node_dofs(k)] = offset_map(self.nodes[k] - np.asarray(origin, dtype=float))
        return out

    def rigid_motion_loads(self, origin: np.ndarray) -> np.ndarray:
        """(n_dof, 12): the consistent nodal loads of the frame's own weight and d'Alembert inertia in a rigid-body
        motion, per coordinate of :data:`RIGID_LOADS` (origin of the motion at ``origin`` [m], body axes).

        A mass point m at r from the origin with rotary inertia J carries the force m (g - a - alpha x r - w x (w x r))
        and the moment -J alpha - w x (J w); the loads are the sums of N_u' force + N_theta' moment.
        """
        origin = np.asarray(origin, dtype=float)
        out = np.zeros((self.n_dof, 12))
        for g in self.mass_points:
            out[g.dofs] += group_rigid_loads(g, origin)
        return out


def group_rigid_loads(group: MassGroup, origin: np.ndarray) -> np.ndarray:
    """(k, 12): the consistent loads of a group of mass points on its DOFs per coordinate of :data:`RIGID_LOADS`
    (see :meth:`Frame.rigid_motion_loads`)."""
    g = group
    eye = np.eye(3)
    r = g.positions - np.asarray(origin, dtype=float)
    forces = np.zeros((len(g.masses), 12, 3))
    moments = np.zeros((len(g.masses), 12, 3))
    for k in range(3):
        forces[:, k] = g.masses[:, None] * eye[k]
        forces[:, 3 + k] = -g.masses[:, None] * np.cross(eye[k], r)
        moments[:, 3 + k] = -g.inertias @ eye[k]
    for c, (a, b) in enumerate(PAIRS):
        # -w x (w x r) = |w|^2 r - w (w . r) and -w x (J w), coefficient of w_a w_b (both orders for a != b)
        if a == b:
            forces[:, 6 + c] = g.masses[:, None] * (r - np.outer(r[:, a], eye[a]))
            moments[:, 6 + c] = -np.cross(eye[a], g.inertias @ eye[a])
        else:
            forces[:, 6 + c] = -g.masses[:, None] * (np.outer(r[:, b], eye[a]) + np.outer(r[:, a], eye[b]))
            moments[:, 6 + c] = -np.cross(eye[a], g.inertias @ eye[b]) - np.cross(eye[b], g.inertias @ eye[a])
    return np.einsum("pai,pca->ic", g.nu, forces) + np.einsum("pai,pca->ic", g.ntheta, moments)
