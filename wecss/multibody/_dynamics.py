"""MFM dynamics (paper Eq. 46) with the infinite-frequency added mass in the mass matrix:

    M* = B' (M + A_inf) B,   N* = B' ((M + A_inf) Bdot + H B),   F* = B' F,
    v_dot = M*^-1 (F* - N* v)

Cartesian forces F hold, per body, the world-frame force at the centre of mass followed by the moment
about the centre of mass in body axes (as the paper's Cartesian velocities), then the generalised force on each
of its modes [J]. H X is the Cartesian quadratic-velocity vector: D M X (the gyroscopic w x J w) for a rigid body;
for a flexible body (``Body.elastic``) its mass block depends on the modal coordinates and H adds
Mdot and the modes' -1/2 Y' dM/dxi Y (``wecss.multibody._elastic``). The kinetic energy T = 1/2 v' M* v changes at
the rate v' F* (the H term does no work), which the tests check. The modes' structural stiffness and damping (and a
flexible body's geometric stiffening) are generalised forces of their own (:func:`structural_force`); a body's
generalised modes without an elastic model are coupled to the rigid motion only through the added mass (see
``_modes``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._kinematics import KinematicState, kinematics
from ._se3 import cross3
from ._tree import Multibody


def body_mass_matrix(model: Multibody, q: np.ndarray | None = None) -> np.ndarray:
    """Block-diagonal (n_cart, n_cart) mass matrix diag(m I_3, J, M_modes) per body (Eq. 43, with the generalised
    mass of the body's modes [kg m^2]; no inertial coupling between the rigid rows and the modes), a flexible body's
    rotation and modes block its M(xi) about its centre of mass (``ElasticBody.relative_mass``) at the modal
    coordinates of ``q`` (default: undeformed)."""
    out = np.zeros((model.n_cart, model.n_cart))
    for i, body in enumerate(model.bodies):
        s, n = model.cart_start[i], body.modes.n
        out[s : s + 3, s : s + 3] = body.mass * np.eye(3)
        out[s + 3 : s + 6, s + 3 : s + 6] = body.inertia
        out[s + 6 : s + 6 + n, s + 6 : s + 6 + n] = body.modes.mass
    for i in model.elastic_bodies:
        _set_elastic_block(model, i, out, _modal(model, i, q))
    return out


def _modal(model: Multibody, i: int, q: np.ndarray | None) -> np.ndarray:
    """Body ``i``'s modal coordinates in ``q`` (zeros for None)."""
    if q is None:
        return np.zeros(model.bodies[i].modes.n)
    return np.asarray(q, dtype=float)[model.mode_coordinate_start[i] : model.mode_coordinate_start[i + 1]]


def _set_elastic_block(model: Multibody, i: int, mass: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """Write flexible body ``i``'s M(xi) into its rotation and modes rows of ``mass``; return dM/dxi."""
    elastic = model.bodies[i].elastic
    assert elastic is not None
    block, derivative = elastic.relative_mass(xi)
    s = model.cart_start[i] + 3
    mass[s : s + 3 + elastic.n, s : s + 3 + elastic.n] = block
    return derivative


def frame_centre(model: Multibody, i: int, q: np.ndarray) -> np.ndarray:
    """Body ``i``'s centre of mass in its frame's coordinates (the reference configuration's world coordinates) [m]:
    fixed for a rigid body, moving with the modal coordinates of ``q`` for a flexible one. A point P of the frame is
    at ``position + rotation @ (P - frame_centre)`` (``KinematicState``)."""
    body = model.bodies[i]
    if body.elastic is None:
        return body.center_of_mass
    return body.elastic.centre_of_mass(_modal(model, i, q))


def _elastic_quadratic(derivative: np.ndarray, y: np.ndarray) -> np.ndarray:
    """A flexible body's quadratic-velocity matrix beyond D M, on Y = (w, xi_dot): Mdot = sum_k xi_dot_k dM/dxi_k,
    its modes' rows less 1/2 Y' dM/dxi_k (``derivative``: dM/dxi (n, 3 + n, 3 + n))."""
    block = np.einsum("k,kab->ab", y[3:], derivative)
    block[3:] -= 0.5 * np.einsum("a,kab->kb", y, derivative)
    return block


def inertial_terms(
    model: Multibody,
    q: np.ndarray,
    v: np.ndarray,
    angular_velocity: np.ndarray,
    total_mass: np.ndarray,
    rigid_mass: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """The Cartesian mass at ``q`` and the quadratic-velocity load H X, so that the loads the motion takes are
    mass @ a + H X (a = B v_dot + Bdot v, the Cartesian accelerations).

    A rigid body's rows of H X are w x (J w) on its rotation; a flexible body's mass rows (rotation and modes) are
    its M(xi) at the modal coordinates of ``q``, and its H X is w x (J_c w + C_c xi_dot) + Mdot Y on its rotation
    rows and Mdot Y - 1/2 Y' dM/dxi_k Y on its modes' rows, Y = (w, xi_dot) (see ``wecss.multibody._elastic``).
    Flexible bodies are dry: their rows of ``total_mass`` (no added mass) are replaced by M(xi).

    Parameters
    ----------
    model : Multibody
    q, v : ndarray (nq,), (nv,)
        Configuration and generalised velocities.
    angular_velocity : ndarray (n_body, 3)
        Body-axis angular velocities [rad/s] (``KinematicState.angular_velocity``).
    total_mass, rigid_mass : ndarray (n_cart, n_cart)
        The undeformed Cartesian mass with and without the infinite-frequency added mass.

    Returns
    -------
    (mass, quadratic) : ndarrays (n_cart, n_cart), (n_cart,)
        [kg, kg m, kg m^2]; [N, N m, J].
    """
    quadratic = np.zeros(model.n_cart)
    mass = total_mass.copy() if model.elastic_bodies else total_mass
    for i, s in enumerate(model.cart_start):
        w = angular_velocity[i]
        if model.bodies[i].elastic is None:
            quadratic[s + 3 : s + 6] = cross3(w, rigid_mass[s + 3 : s + 6, s + 3 : s + 6] @ w)
            continue
        derivative = _set_elastic_block(model, i, mass, _modal(model, i, q))
        own = slice(model.mode_velocity_start[i], model.mode_velocity_start[i + 1])
        y = np.concatenate([w, np.asarray(v, dtype=float)[own]])
        rows = slice(s + 3, s + 6 + y.size - 3)
        quadratic[rows] = _elastic_quadratic(derivative, y) @ y
        quadratic[s + 3 : s + 6] += cross3(w, mass[s + 3 : s + 6, rows] @ y)
    return mass, quadratic


@dataclass(frozen=True)
class DynamicsTerms:
    """M*, N* and the kinematics at one state."""

    mass: np.ndarray
    nonlinear: np.ndarray
    state: KinematicState


class Dynamics:
    """The MFM equations of motion of a multibody tree, optionally with added mass.

    Parameters
    ----------
    model : Multibody
    added_mass : ndarray (n_cart, n_cart), optional
        Infinite-frequency added mass in Cartesian coordinates at the centres of mass (all body-to-body
        couplings), in the paper's per-body order (3 translations, 3 rotations, then the body's modes).
        Default: none.

    Raises
    ------
    ValueError
        If ``added_mass`` has the wrong shape or is not symmetric.
    """

    def __init__(self, model: Multibody, added_mass: np.ndarray | None = None) -> None:
        n_cart = model.n_cart
        self.model = model
        self.rigid_mass = body_mass_matrix(model)
        if added_mass is None:
            added_mass = np.zeros((n_cart, n_cart))
        added_mass = np.asarray(added_mass, dtype=float)
        if added_mass.shape != (n_cart, n_cart):
            raise ValueError(
                f"added_mass must be {n_cart}x{n_cart} (6 per body plus its modes); got shape {added_mass.shape}"
            )
        if not np.allclose(added_mass, added_mass.T, rtol=0, atol=1e-9 * max(1.0, float(np.abs(added_mass).max()))):
            raise ValueError("added_mass must be symmetric")
        self.added_mass = added_mass
        self.total_mass = self.rigid_mass + added_mass

    def terms(self, q: np.ndarray, v: np.ndarray) -> DynamicsTerms:
        """M*(q) and N*(q, v)."""
        st = kinematics(self.model, q, v)
        assert st.Bdot is not None
        b = st.B
        if not self.model.elastic_bodies:
            mass = b.T @ self.total_mass @ b
            nonlinear = b.T @ (self.total_mass @ st.Bdot + st.D() @ self.rigid_mass @ b)
            return DynamicsTerms(0.5 * (mass + mass.T), nonlinear, st)
        rigid, quadratic = self._elastic_terms(q, b @ np.asarray(v, dtype=float))
        total = rigid + self.added_mass
        mass = b.T @ total @ b
        nonlinear = b.T @ (total @ st.Bdot + (st.D() @ rigid + quadratic) @ b)
        return DynamicsTerms(0.5 * (mass + mass.T), nonlinear, st)

    def _elastic_terms(self, q: np.ndarray, cartesian: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The body mass matrix at ``q`` and the flexible bodies' quadratic-velocity matrix beyond D M (Mdot and
        the modes' -1/2 Y' dM/dxi rows), for the Cartesian velocities ``cartesian``."""
        model = self.model
        rigid = self.rigid_mass.copy()
        quadratic = np.zeros_like(rigid)
        for i in model.elastic_bodies:
            derivative = _set_elastic_block(model, i, rigid, _modal(model, i, q))
            n = derivative.shape[0]
            s = model.cart_start[i] + 3
            quadratic[s : s + 3 + n, s : s + 3 + n] = _elastic_quadratic(derivative, cartesian[s : s + 3 + n])
        return rigid, quadratic

    def accelerations(self, q: np.ndarray, v: np.ndarray, force: np.ndarray) -> np.ndarray:
        """Generalised accelerations v_dot = M*^-1 (B' F - N* v) for Cartesian forces ``force`` (n_cart,) (add
        :func:`structural_force` for the modes' stiffness and damping)."""
        t = self.terms(q, v)
        return np.linalg.solve(t.mass, t.state.B.T @ np.asarray(force, dtype=float) - t.nonlinear @ v)

    def kinetic_energy(self, q: np.ndarray, v: np.ndarray) -> float:
        """T = 1/2 v' M* v [J]."""
        b = kinematics(self.model, q).B
        total = self.total_mass
        if self.model.elastic_bodies:
            total = body_mass_matrix(self.model, q) + self.added_mass
        return 0.5 * float(v @ b.T @ total @ b @ v)


def gravity_force(model: Multibody, g: float) -> np.ndarray:
    """Cartesian gravity force (n_cart,): -m g along world z at each centre of mass, no moment, none on the modes
    [N]."""
    out = np.zeros(model.n_cart)
    for i, body in enumerate(model.bodies):
        out[model.cart_start[i] + 2] = -body.mass * g
    return out


def structural_force(model: Multibody, q: np.ndarray, v: np.ndarray | None = None) -> np.ndarray:
    """Cartesian load (n_cart,) of the modes' structural stiffness and damping: -K xi - C xi_dot on each mode's
    row (zero elsewhere) [J], with xi the modal coordinates of ``q`` and xi_dot of ``v`` (None: no damping); a
    flexible body with a geometric tensor adds its geometric stiffening (``ElasticBody.elastic_force``)."""
    out = np.zeros(model.n_cart)
    if model.n_modes:
        xi = np.asarray(q, dtype=float)[model.mode_coordinates]
        load = -model.mode_stiffness @ xi
        if v is not None:
            load -= model.mode_damping @ np.asarray(v, dtype=float)[model.mode_velocities]
        out[model.mode_rows] = load
    for i in model.elastic_bodies:  # the geometric stiffening of a flexible body's own axial strain
        elastic = model.bodies[i].elastic
        assert elastic is not None
        if elastic.geometric is not None:
            s = model.cart_start[i] + 6
            out[s : s + elastic.n] += elastic.geometric_force(_modal(model, i, q))
    return out


def elastic_energy(model: Multibody, q: np.ndarray) -> float:
    """Strain energy of the modes: 1/2 xi' K xi per body, a flexible body's cubic geometric term with it [J]."""
    out = 0.0
    for i, body in enumerate(model.bodies):
        xi = _modal(model, i, q)
        if body.elastic is not None:
            out += body.elastic.elastic_energy(xi)
        elif body.modes.n:
            out += 0.5 * float(xi @ body.modes.stiffness @ xi)
    return out


def potential_energy(model: Multibody, q: np.ndarray, g: float) -> float:
    """Gravitational potential energy sum m g z_cm [J]."""
    st = kinematics(model, q)
    return float(sum(b.mass * g * st.position[i, 2] for i, b in enumerate(model.bodies)))
