"""Kinematics of the whole tree: body poses, the MFM B-matrix (Eq. 28), its time derivative and D.

Cartesian velocities follow the paper: per body, the world-frame velocity of the centre of mass followed
by the body-frame angular velocity, X_dot = B(q) v (in the order of ``Multibody.bodies``), then one row per
generalised mode of the body, the rate of its coordinate: B is the identity on the mode's own column there and
Bdot is zero (rows at ``Multibody.cart_start``).

Derivation used here (product of exponentials). Each joint has a constant twist xi in the world frame at
the reference configuration. The displacement of a body from its reference pose is
G_i = G_parent(i) exp(xi_i q_i), and the spatial velocity of body i is V_i = sum_c S_c v_c over the joint
columns c on its path to the ground, with S_c = Ad(G_before(c)) xi_c. From a spatial twist V = (v, w):
the centre of mass p_i moves at v + w x p_i and the body angular velocity is R_i^T w, so
B_i = Phi_i S, Phi_i = [[I, -hat(p_i)], [0, R_i^T]]. Time derivatives: d/dt S_c = [V_before(c), S_c]
(Lie bracket) and d/dt Phi_i = [[0, -hat(p_dot_i)], [0, -hat(w_body_i) R_i^T]].
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import _quaternion as quaternion
from ._se3 import adjoint, frame, hat, se3_exp, twist_bracket
from ._tree import Multibody

_EX = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
_EZ = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0])


@dataclass(frozen=True)
class KinematicState:
    """Kinematics of every body at one configuration (and velocity, when given).

    Attributes
    ----------
    rotation : ndarray (n_body, 3, 3)
        R_WB of each body (body axes in the world frame).
    position : ndarray (n_body, 3)
        p_WBcm_W: centre of mass of each body in the world frame [m].
    B : ndarray (n_cart, nv)
        The MFM B-matrix: rows per body (world CoM velocity, body angular velocity, its modes' rates).
    Bdot : ndarray (n_cart, nv) or None
        dB/dt along the velocity v.
    angular_velocity : ndarray (n_body, 3) or None
        w_WB_B, body angular velocities in body axes [rad/s].
    cart_start : tuple of int
        First Cartesian row of each body (``Multibody.cart_start``).
    modal : ndarray (n_modes,)
        The generalised modes' coordinates [1] (``Multibody.mode_names``).
    attachments : mapping of (body index, name) to (ndarray (3,), ndarray (3, nv))
        Per attachment of a flexible body (``ElasticBody.attachments``): where its point is (world) [m] and its
        velocity Jacobian (its velocity is J v): the point carried by the structure (:meth:`point`).
    """

    rotation: np.ndarray
    position: np.ndarray
    B: np.ndarray
    Bdot: np.ndarray | None = None
    angular_velocity: np.ndarray | None = None
    cart_start: tuple[int, ...] = ()
    modal: np.ndarray = field(default_factory=lambda: np.zeros(0))
    attachments: dict[tuple[int, str], tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)

    def point(self, body: int, name: str) -> tuple[np.ndarray, np.ndarray]:
        """World position (3,) [m] and velocity Jacobian (3, nv) (its velocity is J v) of the attachment ``name`` of
        the flexible body ``body`` (its reference point carried by the structure).

        Raises
        ------
        KeyError
            If the body has no such attachment.
        """
        if (body, name) not in self.attachments:
            known = sorted(n for b, n in self.attachments if b == body)
            raise KeyError(f"body {body} has no attachment {name!r}; attachments: {known}")
        return self.attachments[(body, name)]

    def D(self) -> np.ndarray:
        """Block-diagonal angular-velocity matrix of the MFM (Eq. 44): diag(0, hat(w_B)) per body, zero on the rows
        of generalised modes."""
        if self.angular_velocity is None:
            raise ValueError("D needs the velocity: call kinematics(model, q, v)")
        n_cart = self.B.shape[0]
        out = np.zeros((n_cart, n_cart))
        for i, s in enumerate(self.cart_start):
            out[s + 3 : s + 6, s + 3 : s + 6] = hat(self.angular_velocity[i])
        return out


def kinematics(model: Multibody, q: np.ndarray, v: np.ndarray | None = None) -> KinematicState:
    """Poses, B and (with ``v``) Bdot and body angular velocities of every body.

    Parameters
    ----------
    model : Multibody
    q : ndarray (nq,)
        Generalised coordinates (``model.coordinate_names``).
    v : ndarray (nv,), optional
        Generalised velocities (``model.velocity_names``).

    Raises
    ------
    ValueError
        If ``q`` or ``v`` has the wrong length.
    """
    q = np.asarray(q, dtype=float)
    if q.shape != (model.nq,):
        raise ValueError(f"q must have {model.nq} entries ({', '.join(model.coordinate_names)}); got shape {q.shape}")
    if v is not None:
        v = np.asarray(v, dtype=float)
        if v.shape != (model.nv,):
            raise ValueError(f"v must have {model.nv} entries ({', '.join(model.velocity_names)}); got shape {v.shape}")
    n = len(model.bodies)
    nv = model.nv
    rotation = np.zeros((n, 3, 3))
    position = np.zeros((n, 3))
    jacobian = [np.zeros((6, nv))] * n  # S of each body: its spatial velocity is S v
    jacobian_dot = [np.zeros((6, nv))] * n  # dS/dt
    displacement = [np.eye(4)] * n
    twist = [np.zeros(6)] * n  # spatial velocity of each body
    points: dict[tuple[int, str], tuple[np.ndarray, np.ndarray]] = {}  # KinematicState.attachments
    iq = iv = 0
    for i in model.order:
        body = model.bodies[i]
        joint = model.joints[model.joint_of[i]]
        par = model.parent[i]
        g = displacement[par] if par >= 0 else np.eye(4)
        vel = twist[par].copy() if par >= 0 else np.zeros(6)
        columns = jacobian[par].copy() if par >= 0 else np.zeros((6, nv))
        columns_dot = jacobian_dot[par].copy() if par >= 0 else np.zeros((6, nv))
        parent_elastic = model.bodies[par].elastic if par >= 0 else None
        if parent_elastic is not None and joint.name in parent_elastic.attachments:
            g, vel = _elastic_attachment(model, par, joint.name, q, v, g, vel, columns, columns_dot)
            where = g[:3, :3] @ parent_elastic.attachments[joint.name].point + g[:3, 3]
            points[(par, joint.name)] = (where, columns[:3] - hat(where) @ columns[3:])
        c0 = body.center_of_mass
        if joint.kind == "free":
            p = q[iq : iq + 3]
            r = quaternion.to_matrix(q[iq + 3 : iq + 7])
            g = frame(r, p - r @ c0)
            columns[:3, iv : iv + 3] = np.eye(3)
            columns[:3, iv + 3 : iv + 6] = hat(p) @ r
            columns[3:, iv + 3 : iv + 6] = r
            if v is not None:
                w_b = v[iv + 3 : iv + 6]
                p_dot = v[iv : iv + 3]
                columns_dot[:3, iv + 3 : iv + 6] = hat(p_dot) @ r + hat(p) @ r @ hat(w_b)
                columns_dot[3:, iv + 3 : iv + 6] = r @ hat(w_b)
                vel = columns[:, iv : iv + 6] @ v[iv : iv + 6]
        else:
            if joint.kind == "planar":
                xis = [_EX, _EZ, np.concatenate([np.cross(c0, [0.0, 1.0, 0.0]), [0.0, 1.0, 0.0]])]
            else:
                xis = list(joint.twists)
            for k, xi in enumerate(xis):
                col = iv + k
                columns[:, col] = adjoint(g) @ xi
                if v is not None:
                    columns_dot[:, col] = twist_bracket(vel, columns[:, col])
                    vel = vel + columns[:, col] * v[col]
                g = g @ se3_exp(xi * q[iq + k])
        displacement[i] = g
        twist[i] = vel
        jacobian[i] = columns
        jacobian_dot[i] = columns_dot
        rotation[i] = g[:3, :3]
        if body.elastic is not None:
            c0 = body.elastic.centre_of_mass(q[model.mode_coordinate_start[i] : model.mode_coordinate_start[i + 1]])
        position[i] = g[:3, :3] @ c0 + g[:3, 3]
        iq += joint.nq
        iv += joint.nv

    for i in model.elastic_bodies:  # the attachments that carry no child: where they are, their velocity Jacobian
        elastic = model.bodies[i].elastic
        assert elastic is not None
        for name, attachment in elastic.attachments.items():
            if (i, name) in points:
                continue
            columns = jacobian[i].copy()
            g, _ = _elastic_attachment(model, i, name, q, None, displacement[i], twist[i], columns, columns)
            where = g[:3, :3] @ attachment.point + g[:3, 3]
            points[(i, name)] = (where, columns[:3] - hat(where) @ columns[3:])

    n_cart = model.n_cart
    b_matrix = np.zeros((n_cart, nv))
    bdot = np.zeros((n_cart, nv)) if v is not None else None
    omega_body = np.zeros((n, 3)) if v is not None else None
    for i in range(n):
        r0 = model.cart_start[i]
        elastic = model.bodies[i].elastic
        own = slice(model.mode_velocity_start[i], model.mode_velocity_start[i + 1])
        phi = np.zeros((6, 6))
        phi[:3, :3] = np.eye(3)
        phi[:3, 3:] = -hat(position[i])
        phi[3:, 3:] = rotation[i].T
        s = jacobian[i]
        b_matrix[r0 : r0 + 6] = phi @ s
        if elastic is not None:  # the centre of mass moves with the structure
            coupling = elastic.invariants.translational_coupling / elastic.invariants.mass
            b_matrix[r0 : r0 + 3, own] = rotation[i] @ coupling
        if v is not None:
            assert bdot is not None and omega_body is not None
            xdot = phi @ (s @ v)
            if elastic is not None:
                xdot[:3] += b_matrix[r0 : r0 + 3, own] @ v[own]
            omega_body[i] = xdot[3:]
            phi_dot = np.zeros((6, 6))
            phi_dot[:3, 3:] = -hat(xdot[:3])
            phi_dot[3:, 3:] = -hat(xdot[3:]) @ rotation[i].T
            bdot[r0 : r0 + 6] = phi_dot @ s + phi @ jacobian_dot[i]
            if elastic is not None:
                bdot[r0 : r0 + 3, own] = rotation[i] @ hat(xdot[3:]) @ coupling
    # generalised modes: the rate of the mode's own coordinate (B = identity on its column, Bdot = 0)
    b_matrix[model.mode_rows, model.mode_velocities] = 1.0
    return KinematicState(
        rotation, position, b_matrix, bdot, omega_body, model.cart_start, q[model.mode_coordinates].copy(), points
    )


def _elastic_attachment(
    model: Multibody,
    parent: int,
    name: str,
    q: np.ndarray,
    v: np.ndarray | None,
    g: np.ndarray,
    vel: np.ndarray,
    columns: np.ndarray,
    columns_dot: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Carry a child's joint on its flexible parent's attachment ``name``: the parent's modal coordinates act as
    joints with the attachment's twists (``wecss.multibody._elastic``), filling their columns of S and dS/dt in place.
    Returns the displacement and spatial velocity at the attachment (``Multibody`` refuses a child joint of a
    flexible body without an attachment of its name; here one without rides on the floating frame)."""
    elastic = model.bodies[parent].elastic
    assert elastic is not None
    if name not in elastic.attachments:
        return g, vel
    first_v = model.mode_velocity_start[parent]
    first_q = model.mode_coordinate_start[parent]
    twists = elastic.attachments[name].twists
    n = len(twists)
    cols = np.zeros((n, 6))
    for k, psi in enumerate(twists):
        cols[k] = adjoint(g) @ psi
        g = g @ se3_exp(psi * q[first_q + k])
    columns[:, first_v : first_v + n] = cols.T
    if v is not None:
        # the spatial velocity before each column: the parent's plus the columns before it
        rates = cols * v[first_v : first_v + n, None]
        before = vel + np.concatenate([np.zeros((1, 6)), np.cumsum(rates, axis=0)[:-1]])
        columns_dot[:, first_v : first_v + n] = twist_bracket(before, cols).T
        vel = vel + rates.sum(axis=0)
    return g, vel


def integrate(model: Multibody, q: np.ndarray, dv: np.ndarray) -> np.ndarray:
    """Configuration reached from ``q`` by the velocity increment ``dv`` (v * dt) [joint units].

    Joint and modal coordinates add; a free base moves its centre of mass by ``dv[:3]`` (world) and rotates by
    ``exp(hat(dv[3:6]))`` in body axes, keeping the quaternion on the unit sphere (SO(3) integration).
    """
    q = np.asarray(q, dtype=float).copy()
    dv = np.asarray(dv, dtype=float)
    iq = iv = 0
    for joint in model.ordered_joints:
        if joint.kind == "free":
            q[iq : iq + 3] += dv[iv : iv + 3]
            quat = quaternion.multiply(q[iq + 3 : iq + 7], quaternion.exp(dv[iv + 3 : iv + 6]))
            q[iq + 3 : iq + 7] = quat / np.linalg.norm(quat)
        else:
            q[iq : iq + joint.nq] += dv[iv : iv + joint.nv]
        iq += joint.nq
        iv += joint.nv
    q[iq:] += dv[iv:]  # the generalised modes
    return q


def difference(model: Multibody, q0: np.ndarray, q1: np.ndarray) -> np.ndarray:
    """Velocity increment dv with ``integrate(model, q0, dv) == q1`` (inverse of :func:`integrate`)."""
    q0 = np.asarray(q0, dtype=float)
    q1 = np.asarray(q1, dtype=float)
    out = np.zeros(model.nv)
    iq = iv = 0
    for joint in model.ordered_joints:
        if joint.kind == "free":
            out[iv : iv + 3] = q1[iq : iq + 3] - q0[iq : iq + 3]
            conj = q0[iq + 3 : iq + 7] * np.array([1.0, -1.0, -1.0, -1.0])
            out[iv + 3 : iv + 6] = quaternion.log(quaternion.multiply(conj, q1[iq + 3 : iq + 7]))
        else:
            out[iv : iv + joint.nv] = q1[iq : iq + joint.nq] - q0[iq : iq + joint.nq]
        iq += joint.nq
        iv += joint.nv
    out[iv:] = q1[iq:] - q0[iq:]  # the generalised modes
    return out


def configuration_rate(model: Multibody, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """dq/dt for velocity ``v``: ``v`` itself for joint and modal coordinates; for a free base, the world velocity
    of the centre of mass and the quaternion rate 1/2 quat * (0, w_body)."""
    q = np.asarray(q, dtype=float)
    v = np.asarray(v, dtype=float)
    out = np.zeros(model.nq)
    iq = iv = 0
    for joint in model.ordered_joints:
        if joint.kind == "free":
            out[iq : iq + 3] = v[iv : iv + 3]
            out[iq + 3 : iq + 7] = 0.5 * quaternion.multiply(q[iq + 3 : iq + 7], np.array([0.0, *v[iv + 3 : iv + 6]]))
        else:
            out[iq : iq + joint.nq] = v[iv : iv + joint.nv]
        iq += joint.nq
        iv += joint.nv
    out[iq:] = v[iv:]  # the generalised modes
    return out
