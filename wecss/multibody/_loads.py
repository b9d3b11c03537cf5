"""Joint reaction loads recovered by a Newton-Euler sweep from the leaves to the base.

The MFM eliminates the constraint forces; structural and fatigue studies need them back. Given the motion
(q, v, v_dot) and the applied Cartesian loads, each body needs the wrench W_i = M_tot a_i + w_i x (J_i w_i) -
F_applied,i, with a = B v_dot + Bdot v; the joint of body i carries W_i plus what its children's joints carry. A
flexible body's wrench is its momentum rate about its instantaneous centre of mass: m a_c, and Euler's equation of a
deformable body (``inertial_terms``); its modes' rows are not a joint load.
"""

from __future__ import annotations

import numpy as np

from ._dynamics import frame_centre, inertial_terms
from ._kinematics import KinematicState, kinematics
from ._se3 import cross3
from ._tree import Multibody


def joint_reactions(
    model: Multibody,
    q: np.ndarray,
    v: np.ndarray,
    v_dot: np.ndarray,
    applied: np.ndarray,
    total_mass: np.ndarray,
    rigid_mass: np.ndarray,
    state: KinematicState | None = None,
    inertial: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Wrench each joint transmits from the parent (or ground) to its child's subtree.

    Parameters
    ----------
    model : Multibody
    q, v, v_dot : ndarray
        Configuration, generalised velocities [m/s, rad/s] and accelerations [m/s^2, rad/s^2].
    applied : ndarray (n_cart,)
        Applied Cartesian loads: world forces at the centres of mass [N], body-frame moments [N m], the modes'
        generalised forces [J] (everything except the joint loads: gravity, hydrodynamics, and the PTO loads if
        they are applied as Cartesian loads).
    total_mass, rigid_mass : ndarray (n_cart, n_cart)
        Rigid mass plus infinite-frequency added mass, and the rigid mass alone (for the gyroscopic term). The
        joints carry the rigid rows' balance (with the added-mass coupling to the modes' accelerations); the modes'
        own rows are not a joint load. A flexible body's rows are its M(xi) at ``q`` (``inertial_terms``).
    state : KinematicState, optional
        The kinematics at (q, v) with Bdot and the angular velocities, when the caller has them (default: computed).
    inertial : (ndarray, ndarray), optional
        ``inertial_terms`` at this state, when the caller has them (default: computed).

    Returns
    -------
    (force, moment) : ndarrays (n_joint, 3)
        In world axes, in the order of ``model.ordered_joints``; the moment is about the joint point (a revolute
        joint's hinge point as it moves; the child's centre of mass otherwise) [N, N m]. The component of the
        moment along a revolute joint's axis is the torque the joint itself supplies (its PTO torque).
    """
    st = kinematics(model, q, v) if state is None else state
    assert st.Bdot is not None and st.angular_velocity is not None
    acc = st.B @ v_dot + st.Bdot @ v
    if inertial is None:
        inertial = inertial_terms(model, q, v, st.angular_velocity, total_mass, rigid_mass)
    mass, quadratic = inertial
    need = mass @ acc - applied
    n = len(model.bodies)
    force = np.zeros((n, 3))
    moment_origin = np.zeros((n, 3))  # about the world origin
    for i in range(n):
        s = model.cart_start[i]
        m_body = need[s + 3 : s + 6] + quadratic[s + 3 : s + 6]
        f = need[s : s + 3]
        force[i] = f
        moment_origin[i] = st.rotation[i] @ m_body + cross3(st.position[i], f)
    for i in reversed(model.order):
        par = model.parent[i]
        if par >= 0:
            force[par] += force[i]
            moment_origin[par] += moment_origin[i]
    out_f = np.zeros((n, 3))
    out_m = np.zeros((n, 3))
    for k, i in enumerate(model.order):
        joint = model.joints[model.joint_of[i]]
        if joint.kind == "revolute":
            assert joint.point is not None
            point = st.position[i] + st.rotation[i] @ (joint.point - frame_centre(model, i, q))
        else:
            point = st.position[i]
        out_f[k] = force[i]
        out_m[k] = moment_origin[i] - cross3(point, force[i])
    return out_f, out_m
