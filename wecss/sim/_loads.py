"""Loads recovered from a run's record after the run: joint reactions and PTO loads on both of their bodies.

Nothing in the integrators changes: at every saved step the record holds the configuration q, velocities v,
accelerations v_dot, PTO forces and the excitation and radiation-memory forces. The applied Cartesian loads are
rebuilt from them exactly as the equations of motion use them (gravity, buoyancy and hydrostatic restoring, wave
excitation, radiation memory, the PTO forces with their end stops), and a Newton-Euler sweep from the leaves
(``wecss.multibody.joint_reactions``) gives the wrench each joint passes from the parent (or the ground) to its
child's subtree. The infinite-frequency added mass acts through the mass matrix, as in the equations.

Closure: the reactions are constraint loads, so on the free directions of the joints the Cartesian balance
(M + A_inf) a + gyroscopic - applied, projected by B', must vanish; its largest value relative to the largest
projected applied load is the result's ``loads_closure_residual`` (round-off for the nonlinear solvers, the
linearisation error for the linear and frequency-domain runs, whose records follow the linear equations).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..compiled import CompiledScene, Plant, PtoKind
from ..compiled.kernels import (
    elastic_pto_end_points,
    end_stop_force,
    hydro_velocity,
    hydrostatic_force,
    kinematics,
    pto_strokes,
    world_jacobian,
)
from ..multibody import KinematicState, cross3, frame_centre, inertial_terms, joint_reactions
from ._fibre_field import ElasticHistory
from ._sections import BodyHistory, section_loads


@dataclass
class Loads:
    """Recovered loads at the saved steps (world axes unless said).

    Attributes
    ----------
    joint_force, joint_moment : (n_t, n_joint, 3)
        Reaction on the child's subtree at each joint (order ``model.ordered_joints``), the moment about the joint
        point (a revolute joint's hinge point, else the child's centre of mass), world axes [N, N m].
    joint_force_local, joint_moment_local : (n_t, n_joint, 3)
        The same in the joint's frame: the child body's axes [N, N m].
    pto_body_force, pto_body_moment : (n_t, n_pto, 2, 3)
        The PTO's load on its two ends (end 0: body_a, or the joint's child; end 1: body_b, or the joint's parent),
        the force at the attachment point and the moment (a joint PTO's torque), world axes [N, N m]; zeros for an
        end on the ground.
    closure : float
        Largest residual of the generalised balance over the largest generalised applied load [-].
    section : (n_t, n_spot, 6)
        Section loads N, Vy, Vz [N], T, My, Mz [N m] at each hot spot of the device's members, member axes (see
        ``wecss.sim._sections`` for the free body).
    histories : dict of int to BodyHistory
        What each body with members or a flexible structure felt (by body index; see ``BodyHistory``).
    elastic : dict of int to ElasticHistory
        Each elastic body's modal coordinates and its floating frame's motion (by body index).
    """

    joint_force: np.ndarray
    joint_moment: np.ndarray
    joint_force_local: np.ndarray
    joint_moment_local: np.ndarray
    pto_body_force: np.ndarray
    pto_body_moment: np.ndarray
    closure: float
    section: np.ndarray
    histories: dict[int, BodyHistory] = field(default_factory=dict)
    elastic: dict[int, ElasticHistory] = field(default_factory=dict)


def _pto_cartesian(compiled: CompiledScene, rot: np.ndarray, pos: np.ndarray, force: np.ndarray, nodes: dict):
    """World Cartesian loads (n_cart,) of the PTO forces ``force`` (n_pto,) and each PTO's load on its two ends
    (an end on a flexible body at its node: ``nodes`` maps (PTO, end) to where the structure has taken it; the
    Cartesian loads then hold the force and its moment about the body's centre of mass, not the modes' share)."""
    p = compiled.plant
    model = compiled.device.model
    cart = np.zeros(p.cart_body.size)
    n_pto = force.shape[0]
    end_force = np.zeros((n_pto, 2, 3))
    end_moment = np.zeros((n_pto, 2, 3))
    bodies = np.full((n_pto, 2), -1)
    points = np.zeros((n_pto, 2, 3))
    for k, pto in enumerate(compiled.device.ptos):
        if p.pto_kind[k] == PtoKind.JOINT:
            joint = next(j for j in model.joints if j.name == pto.joint)  # type: ignore[union-attr]
            child = model.body_names.index(joint.child)
            parent = model.parent[child]
            assert joint.axis is not None
            axis = rot[child] @ joint.axis
            bodies[k] = (child, parent)
            points[k] = pos[child]
            if joint.kind == "revolute":  # the torque acts at the hinge
                assert joint.point is not None
                points[k] = pos[child] + rot[child] @ (joint.point - model.bodies[child].center_of_mass)
            if joint.kind == "revolute":
                end_moment[k, 0], end_moment[k, 1] = force[k] * axis, -force[k] * axis
            else:
                end_force[k, 0], end_force[k, 1] = force[k] * axis, -force[k] * axis
        else:
            ends = []
            for e, (body, point) in enumerate(
                ((p.pto_body_a[k], p.pto_point_a[k]), (p.pto_body_b[k], p.pto_point_b[k]))
            ):
                bodies[k, e] = body
                ends.append(nodes[(k, e)] if (k, e) in nodes else point if body < 0 else pos[body] + rot[body] @ point)
            d = ends[0] - ends[1]
            d = d / np.linalg.norm(d)
            points[k] = ends
            end_force[k, 0], end_force[k, 1] = force[k] * d, -force[k] * d
        for e in range(2):
            i = bodies[k, e]
            if i < 0:
                end_force[k, e] = end_moment[k, e] = 0.0
                continue
            s = p.cart_start[i]
            cart[s : s + 3] += end_force[k, e]
            cart[s + 3 : s + 6] += end_moment[k, e] + cross3(points[k, e] - pos[i], end_force[k, e])
    return cart, end_force, end_moment, bodies, points


def recover_loads(compiled: CompiledScene, q: np.ndarray, v: np.ndarray, a: np.ndarray, pto: tuple, hydro: np.ndarray):
    """Loads at each saved step.

    Parameters
    ----------
    compiled : CompiledScene
    q, v, a : ndarray (n_t, nq), (n_t, nv), (n_t, nv)
        Configurations, velocities [m/s, rad/s] and accelerations [m/s^2, rad/s^2].
    pto : tuple of ndarray (n_t, n_pto)
        Stroke from rest x [m or rad], its rate [m/s or rad/s] and the PTO force f [N or N m] (without end stops).
    hydro : ndarray (n_t, n_h)
        Excitation plus radiation memory force on the hydro DOFs, world axes [N, N m].

    Returns
    -------
    Loads
    """
    p = compiled.plant
    model = compiled.device.model
    n_t, n_j, n_pto = q.shape[0], len(model.joints), len(compiled.device.ptos)
    rigid, start, modes = p.rigid_mass, p.cart_start, p.cart_column[p.mode_row]
    zj, zp = (n_t, n_j, 3), (n_t, n_pto, 2, 3)
    out = Loads(
        np.zeros(zj), np.zeros(zj), np.zeros(zj), np.zeros(zj), np.zeros(zp), np.zeros(zp), 0.0, np.zeros((n_t, 0, 6))
    )
    child_of_joint = list(model.order)
    members = compiled.device.members
    carriers = sorted({model.body_names.index(m.body) for m in members if m.hot_spots} | set(field_bodies(compiled)))
    gathered: dict[int, list[list[np.ndarray]]] = {i: [] for i in carriers}
    flexible = bool(model.elastic_bodies)
    elastic = [i for i in carriers if model.bodies[i].elastic is not None]
    frames: dict[int, list[list[np.ndarray]]] = {i: [] for i in elastic}
    gravity = np.array([0.0, 0.0, -compiled.hydro.g])
    moored = p.mooring_damping.size > 0  # stored empty without dampers
    worst, scale = 0.0, 0.0
    for t in range(n_t):
        qq, vv = np.ascontiguousarray(q[t]), np.ascontiguousarray(v[t])
        rot, pos, b, bdot, omega = kinematics(p, qq, vv)
        own = hydrostatic_force(p, qq, rot, pos)  # everything but the joints and the PTOs, world axes
        own[p.hydro_index] += hydro[t]
        if moored:  # the moorings' dampers (their springs are in the hydrostatic force)
            own[p.hydro_index] -= p.mooring_damping @ hydro_velocity(p, qq, vv)
        if modes.size:  # the modes' structural damping (their stiffness is in the hydrostatic force)
            own[p.mode_row] -= p.mode_damping @ vv[modes]
        x, xd, f = pto[0][t], pto[1][t], pto[2][t]
        force = f + end_stop_force(p, x, xd) if n_pto else np.zeros(0)
        cart, out.pto_body_force[t], out.pto_body_moment[t], pto_bodies, pto_points = _pto_cartesian(
            compiled, rot, pos, force, _elastic_ends(p, qq, rot, pos, b) if flexible else {}
        )
        world = own + cart
        applied = world.copy()  # world forces, body-axis moments (the convention of B and joint_reactions)
        for i, s in enumerate(start):
            applied[s + 3 : s + 6] = rot[i].T @ world[s + 3 : s + 6]
        mass, quadratic = inertial_terms(model, qq, vv, omega, p.total_mass, rigid)
        # an elastic device's kinematics and inertial terms from the kernels' (the multibody core rides its
        # attachments in Python); a rigid device's reactions keep the core's own arithmetic
        state = KinematicState(rot, pos, b, bdot, omega, model.cart_start) if flexible else None
        inertial = (mass, quadratic) if flexible else None
        f_j, m_j = joint_reactions(model, qq, vv, a[t], applied, p.total_mass, rigid, state, inertial)
        out.joint_force[t], out.joint_moment[t] = f_j, m_j
        for k, i in enumerate(child_of_joint):
            out.joint_force_local[t, k] = rot[i].T @ f_j[k]
            out.joint_moment_local[t, k] = rot[i].T @ m_j[k]
        # closure on the free directions: B' ((M + A_inf)(B a + Bdot v) + H X - applied) = 0
        acc = b @ a[t] + bdot @ vv
        inertia = mass @ acc + quadratic
        if flexible:  # the PTOs' generalised force by their transmissions (on the modes of the bodies they act on)
            own_applied = own.copy()
            for i, s in enumerate(start):
                own_applied[s + 3 : s + 6] = rot[i].T @ own[s + 3 : s + 6]
            balance = b.T @ (inertia - own_applied) - pto_strokes(p, qq, rot, pos, b)[1].T @ force
        else:
            balance = b.T @ (inertia - applied)
        worst = max(worst, float(np.max(np.abs(balance), initial=0.0)))
        scale = max(scale, float(np.max(np.abs(world_jacobian(p, rot, b).T @ world), initial=0.0)))
        for i in carriers:
            pto_loads = (out.pto_body_force[t], out.pto_body_moment[t])
            loads = _body_point_loads(compiled, i, qq, rot, pos, f_j, m_j, pto_loads, pto_bodies, pto_points)
            r, s = rot[i], start[i]
            own_force = r.T @ (own[s : s + 3] - inertia[s : s + 3])
            own_moment = r.T @ own[s + 3 : s + 6] - inertia[s + 3 : s + 6]
            loads.append((frame_centre(model, i, qq), own_force, own_moment))
            pts, frc, mom = (np.array(c) for c in zip(*loads, strict=True))
            gathered[i].append([pts, frc, mom, r.T @ gravity, r.T @ acc[s : s + 3], acc[s + 3 : s + 6],
                                omega[i]])  # fmt: skip
        for i in elastic:
            frames[i].append(_frame_motion(model, i, qq, vv, a[t], acc, rot[i], omega[i]))
    out.closure = worst / scale if scale > 0 else worst
    if carriers and n_t:
        histories = {i: BodyHistory(*(np.array(col) for col in zip(*gathered[i], strict=True))) for i in carriers}
        index = {name: k for k, name in enumerate(model.body_names)}
        out.section = section_loads(members, index, model.bodies, histories)
        out.histories = histories
        for i in elastic:
            xi, xi_dot, xi_ddot, origin_acceleration = (np.array(c) for c in zip(*frames[i], strict=True))
            h, body = histories[i], model.bodies[i].elastic
            assert body is not None
            origin = body.invariants.origin
            out.elastic[i] = ElasticHistory(xi, xi_dot, xi_ddot, h.gravity, origin_acceleration, h.alpha, h.omega,
                                            origin)  # fmt: skip
    return out


def _frame_motion(model, i: int, q: np.ndarray, v: np.ndarray, v_dot: np.ndarray, acc: np.ndarray, rot, omega):
    """Elastic body ``i``'s modal coordinates, their rates and accelerations and the acceleration (body axes) [m/s^2] of
    its floating frame's origin (the undeformed centre of mass c0), from the Cartesian accelerations ``acc`` (its
    rows: the instantaneous centre of mass c = c0 + d, d = Ct xi / m, then the body's angular acceleration): the
    frame point's acceleration is a_c - alpha x d - w x (w x d) - 2 w x d_dot - d_ddot (body axes)."""
    elastic = model.bodies[i].elastic
    inv = elastic.invariants
    coupling = inv.translational_coupling / inv.mass
    own = slice(model.mode_velocity_start[i], model.mode_velocity_start[i + 1])
    xi = q[model.mode_coordinate_start[i] : model.mode_coordinate_start[i + 1]]
    s = model.cart_start[i]
    d, d_dot, d_ddot = coupling @ xi, coupling @ v[own], coupling @ v_dot[own]
    alpha = acc[s + 3 : s + 6]
    origin = rot.T @ acc[s : s + 3] - cross3(alpha, d) - cross3(omega, cross3(omega, d))
    origin -= 2 * cross3(omega, d_dot) + d_ddot
    return [xi.copy(), v[own].copy(), v_dot[own].copy(), origin]


def _elastic_ends(p: Plant, q: np.ndarray, rot: np.ndarray, pos: np.ndarray, b: np.ndarray) -> dict:
    """Where the structure has taken each actuator end on a flexible body (its attachment ``pto:<name>``), world
    [m], by (PTO, end)."""
    where, ends = elastic_pto_end_points(p, q, rot, pos, b), p.elastic.pto_end
    return {(k, e): where[k, e] for k in range(ends.shape[0]) for e in range(2) if ends[k, e] >= 0}


def field_bodies(compiled: CompiledScene) -> list[int]:
    """Indices of the bodies whose stress field a run gives (``wecss.sim._fibre_field``): the elastic bodies (their
    modal coordinates give it), and the flexible bodies with frozen dynamics that are dry (no hydro body, mesh, drag,
    Morison element or mooring: every load on them acts at a point of their structure or is their weight and
    inertia), held at their revolute joint's point, and whose children hang on revolute or welded joints (at fixed
    points of the structure). The scene's ``outputs.every`` must be 1: a rainflow count of every k-th step misses
    the cycles between them."""
    device = compiled.device
    model = device.model
    if compiled.scene.outputs.every != 1:
        return []
    wet = {m.body for m in device.meshes} | {d.body for d in device.drag} | {m.body for m in device.morison}
    wet |= {m.body for m in device.moorings}
    out = []
    for name, flexible in device.flexible.items():
        body = model.body(name)
        own = model.joints[model.joint_of[model.body_names.index(name)]]
        held = own.kind == "revolute" and (flexible.clamp is None or np.allclose(flexible.clamp, own.point))  # type: ignore[arg-type]
        children = [j.kind in ("revolute", "weld") for j in model.joints if j.parent == name]
        frozen = (
            flexible.dynamics == "frozen" and body.hydro_body is None and name not in wet and held and all(children)
        )
        if frozen or body.elastic is not None:
            out.append(model.body_names.index(name))
    return out


def _body_point_loads(compiled: CompiledScene, i: int, q, rot, pos, f_j, m_j, pto_loads, pto_bodies, pto_points):
    """Point loads on body ``i`` from its joints and PTOs: a list of (point in body reference coordinates [m],
    force, moment about the point [N, N m], body axes); on a flexible body, a point carried by its structure is
    where the structure has taken it."""
    model = compiled.device.model
    r, centre = rot[i], frame_centre(model, i, q)
    to_body = lambda point: centre + r.T @ (point - pos[i])  # noqa: E731

    def joint_point(c: int) -> np.ndarray:
        joint = model.joints[model.joint_of[c]]
        if joint.kind == "revolute":
            assert joint.point is not None
            return pos[c] + rot[c] @ (joint.point - frame_centre(model, c, q))
        return pos[c]

    out = []
    for k, c in enumerate(model.order):
        if c == i:  # the body's own joint: the reaction from its parent
            out.append((to_body(joint_point(c)), r.T @ f_j[k], r.T @ m_j[k]))
        elif model.parent[c] == i:  # a child's joint: the child's reaction, reversed
            out.append((to_body(joint_point(c)), -r.T @ f_j[k], -r.T @ m_j[k]))
    for k in range(pto_bodies.shape[0]):
        for e in range(2):
            if pto_bodies[k, e] == i:
                out.append((to_body(pto_points[k, e]), r.T @ pto_loads[0][k, e], r.T @ pto_loads[1][k, e]))
    return out
