"""The nonlinear MFM equations of motion on flat arrays (numba-compiled when available, see ``_jit``).

Same mathematics as :mod:`wecss.multibody` (product-of-exponentials kinematics, M* = B'(M + A_inf)B,
N* = B'((M + A_inf) Bdot + D M B), paper Eq. 46), written as loops over small arrays so that numba can compile
it; the tests check it against the object-based implementation.

Loads: hydrodynamic forces act in world axes on the hydro DOFs (linear hydrodynamics), so they enter through the
world-frame Jacobian Bw (CoM velocity and world angular velocity per body): F* = Bw' F_world. The hydro velocity
u = Bw v drives the radiation memory.
"""

from __future__ import annotations

import numpy as np

from ._jit import kernel
from ._plant import Plant, PtoKind

_SMALL = 1e-8


@kernel
def hat(w: np.ndarray) -> np.ndarray:
    out = np.zeros((3, 3))
    out[0, 1] = -w[2]
    out[0, 2] = w[1]
    out[1, 0] = w[2]
    out[1, 2] = -w[0]
    out[2, 0] = -w[1]
    out[2, 1] = w[0]
    return out


@kernel
def so3_log(r: np.ndarray) -> np.ndarray:
    cos = min(1.0, max(-1.0, (r[0, 0] + r[1, 1] + r[2, 2] - 1.0) / 2.0))
    theta = np.arccos(cos)
    v = 0.5 * np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    if theta < _SMALL:
        return v
    if np.pi - theta < 1e-6:
        sym = (r + np.eye(3)) / 2.0
        k = int(np.argmax(np.array([sym[0, 0], sym[1, 1], sym[2, 2]])))
        axis = sym[:, k].copy()
        return theta * axis / np.sqrt(np.sum(axis**2))
    return theta / np.sin(theta) * v


@kernel
def quat_to_matrix(quat: np.ndarray) -> np.ndarray:
    n = np.sqrt(np.sum(quat**2))
    w, x, y, z = quat[0] / n, quat[1] / n, quat[2] / n, quat[3] / n
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


@kernel
def quat_multiply(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.array(
        [
            a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
            a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
            a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
        ]
    )


@kernel
def _rotate(r: np.ndarray, x: np.ndarray, out: np.ndarray) -> None:
    for a in range(3):
        out[a] = r[a, 0] * x[0] + r[a, 1] * x[1] + r[a, 2] * x[2]


@kernel
def _cross(a: np.ndarray, b: np.ndarray, out: np.ndarray) -> None:
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@kernel
def _screw(xi: np.ndarray, angle: float, rot: np.ndarray, trans: np.ndarray) -> None:
    """exp(xi * angle) as a rotation and a translation (Rodrigues; se3_exp without temporaries):
    R = I + c1 K + c2 K^2, t = v + c2 w x v + c3 w x (w x v), K = hat(w), K^2 = w w' - |w|^2 I."""
    w0, w1, w2 = xi[3] * angle, xi[4] * angle, xi[5] * angle
    v0, v1, v2 = xi[0] * angle, xi[1] * angle, xi[2] * angle
    theta2 = w0 * w0 + w1 * w1 + w2 * w2
    theta = np.sqrt(theta2)
    if theta < _SMALL:
        c1, c2, c3 = 1.0, 0.5, 1.0 / 6.0
    else:
        c1 = np.sin(theta) / theta
        c2 = (1.0 - np.cos(theta)) / theta2
        c3 = (theta - np.sin(theta)) / (theta2 * theta)
    rot[0, 0] = 1.0 + c2 * (w0 * w0 - theta2)
    rot[1, 1] = 1.0 + c2 * (w1 * w1 - theta2)
    rot[2, 2] = 1.0 + c2 * (w2 * w2 - theta2)
    rot[0, 1] = -c1 * w2 + c2 * w0 * w1
    rot[1, 0] = c1 * w2 + c2 * w0 * w1
    rot[0, 2] = c1 * w1 + c2 * w0 * w2
    rot[2, 0] = -c1 * w1 + c2 * w0 * w2
    rot[1, 2] = -c1 * w0 + c2 * w1 * w2
    rot[2, 1] = c1 * w0 + c2 * w1 * w2
    x0, x1, x2 = w1 * v2 - w2 * v1, w2 * v0 - w0 * v2, w0 * v1 - w1 * v0  # w x v
    y0, y1, y2 = w1 * x2 - w2 * x1, w2 * x0 - w0 * x2, w0 * x1 - w1 * x0  # w x (w x v)
    trans[0] = v0 + c2 * x0 + c3 * y0
    trans[1] = v1 + c2 * x1 + c3 * y1
    trans[2] = v2 + c2 * x2 + c3 * y2


@kernel
def _compose(r: np.ndarray, r_step: np.ndarray, out: np.ndarray) -> None:
    for a in range(3):
        for b in range(3):
            out[a, b] = r[a, 0] * r_step[0, b] + r[a, 1] * r_step[1, b] + r[a, 2] * r_step[2, b]


@kernel
def kinematics(p: Plant, q: np.ndarray, v: np.ndarray):
    """Rotations (n, 3, 3), CoM positions (n, 3), B (6n, nv), Bdot (6n, nv) and body angular velocities (n, 3)."""
    n = p.com0.shape[0]
    nv = p.twists.shape[0]
    rot = np.zeros((n, 3, 3))
    trans = np.zeros((n, 3))  # frame displacement G = (rot, trans) of each body from its reference pose
    spatial = np.zeros((n, 6))
    cols = np.zeros((6, nv))
    cols_dot = np.zeros((6, nv))
    pos = np.zeros((n, 3))
    r_step = np.zeros((3, 3))
    r_new = np.zeros((3, 3))
    t_step = np.zeros(3)
    tmp = np.zeros(3)
    tmp2 = np.zeros(3)
    lin = np.zeros(3)
    w_b = np.zeros(3)
    rts = np.zeros(3)
    rtsd = np.zeros(3)
    for idx in range(n):
        i = p.order[idx]
        par = p.parent[i]
        r = np.eye(3)
        t = np.zeros(3)
        vel = np.zeros(6)
        if par >= 0:
            r[:, :] = rot[par]
            t[:] = trans[par]
            vel[:] = spatial[par]
        iv = p.col_start[i]
        iq = p.q_start[i]
        if p.free[i] == 1:
            x = q[iq : iq + 3].copy()
            r = quat_to_matrix(q[iq + 3 : iq + 7].copy())
            t = x - r @ p.com0[i]
            hx = hat(x)
            wb = v[iv + 3 : iv + 6].copy()
            for a in range(3):
                cols[a, iv + a] = 1.0
            cols[:3, iv + 3 : iv + 6] = hx @ r
            cols[3:, iv + 3 : iv + 6] = r
            cols_dot[:3, iv + 3 : iv + 6] = hat(v[iv : iv + 3].copy()) @ r + hx @ r @ hat(wb)
            cols_dot[3:, iv + 3 : iv + 6] = r @ hat(wb)
            vel = np.ascontiguousarray(cols[:, iv : iv + 6]) @ v[iv : iv + 6].copy()
        else:
            for k in range(p.n_cols[i]):
                col = iv + k
                xi = p.twists[col]
                # S = Ad(G) xi: w' = R w, v' = R v + t x w'
                _rotate(r, xi[3:], tmp)
                _rotate(r, xi[:3], tmp2)
                for a in range(3):
                    cols[3 + a, col] = tmp[a]
                _cross(t, tmp, t_step)
                for a in range(3):
                    cols[a, col] = tmp2[a] + t_step[a]
                # dS/dt = [V, S]: (w_V x v_S - w_S x v_V, w_V x w_S)
                s = cols[:, col]
                _cross(vel[3:], s[:3], tmp)
                _cross(s[3:], vel[:3], tmp2)
                for a in range(3):
                    cols_dot[a, col] = tmp[a] - tmp2[a]
                _cross(vel[3:], s[3:], tmp)
                for a in range(3):
                    cols_dot[3 + a, col] = tmp[a]
                for a in range(6):
                    vel[a] += s[a] * v[col]
                # G <- G exp(xi q)
                _screw(xi, q[iq + k], r_step, t_step)
                _rotate(r, t_step, tmp)
                t = t + tmp
                _compose(r, r_step, r_new)
                r[:, :] = r_new
        rot[i] = r
        trans[i] = t
        spatial[i] = vel
        _rotate(r, p.com0[i], tmp)
        pos[i] = tmp + t
    b = np.zeros((6 * n, nv))
    bdot = np.zeros((6 * n, nv))
    omega = np.zeros((n, 3))
    for i in range(n):
        r = rot[i]
        pi = pos[i]
        # CoM velocity and body angular velocity from the spatial twist of the body
        vel = spatial[i]
        w_world = vel[3:]
        _cross(pi, w_world, tmp)
        for a in range(3):
            lin[a] = vel[a] - tmp[a]
        for a in range(3):
            w_b[a] = r[0, a] * w_world[0] + r[1, a] * w_world[1] + r[2, a] * w_world[2]
        omega[i, :] = w_b
        for c in range(nv):
            if p.chain[i, c] == 0.0:
                continue
            s = cols[:, c]
            sd = cols_dot[:, c]
            # B_i = [[I, -hat(p)], [0, R']] S
            _cross(pi, s[3:], tmp)
            for a in range(3):
                b[6 * i + a, c] = s[a] - tmp[a]
                b[6 * i + 3 + a, c] = r[0, a] * s[3] + r[1, a] * s[4] + r[2, a] * s[5]
            # Bdot_i = [[0, -hat(p_dot)], [0, -hat(w_b) R']] S + [[I, -hat(p)], [0, R']] dS/dt
            _cross(lin, s[3:], tmp)
            _cross(pi, sd[3:], tmp2)
            for a in range(3):
                bdot[6 * i + a, c] = -tmp[a] + sd[a] - tmp2[a]
            for a in range(3):
                rts[a] = r[0, a] * s[3] + r[1, a] * s[4] + r[2, a] * s[5]
                rtsd[a] = r[0, a] * sd[3] + r[1, a] * sd[4] + r[2, a] * sd[5]
            _cross(w_b, rts, tmp)
            for a in range(3):
                bdot[6 * i + 3 + a, c] = -tmp[a] + rtsd[a]
    return rot, pos, b, bdot, omega


@kernel
def world_jacobian(rot: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Bw: rows per body (CoM velocity, world angular velocity) from B (rows CoM velocity, body angular velocity)."""
    out = b.copy()
    nv = b.shape[1]
    for i in range(rot.shape[0]):
        r = rot[i]
        for a in range(3):
            for c in range(nv):
                out[6 * i + 3 + a, c] = (
                    r[a, 0] * b[6 * i + 3, c] + r[a, 1] * b[6 * i + 4, c] + r[a, 2] * b[6 * i + 5, c]
                )
    return out


@kernel
def pto_strokes(p: Plant, q: np.ndarray, rot: np.ndarray, pos: np.ndarray, b: np.ndarray):
    """PTO strokes x (n_pto,) [m or rad] and transmissions G (n_pto, nv) with x_dot = G v."""
    n_pto = p.pto_kind.shape[0]
    nv = b.shape[1]
    x = np.zeros(n_pto)
    gmat = np.zeros((n_pto, nv))
    for k in range(n_pto):
        if p.pto_kind[k] == PtoKind.JOINT:
            x[k] = q[p.pto_coordinate[k]]
            gmat[k, p.pto_velocity[k]] = 1.0
        else:
            ends = np.zeros((2, 3))
            jac = np.zeros((2, 3, nv))
            for e in range(2):
                body = p.pto_body_a[k] if e == 0 else p.pto_body_b[k]
                point = p.pto_point_a[k] if e == 0 else p.pto_point_b[k]
                if body < 0:
                    ends[e] = point
                else:
                    r = np.ascontiguousarray(rot[body])
                    ends[e] = pos[body] + r @ point
                    jac[e] = b[6 * body : 6 * body + 3] - r @ hat(point) @ b[6 * body + 3 : 6 * body + 6]
            d = ends[0] - ends[1]
            length = np.sqrt(np.sum(d**2))
            x[k] = length
            gmat[k] = (d / length) @ (jac[0] - jac[1])
    return x, gmat


@kernel
def hydrostatic_force(p: Plant, rot: np.ndarray, pos: np.ndarray) -> np.ndarray:
    """Gravity, buoyancy and linear hydrostatic and mooring restoring force, world axes (6n,) [N, N m]."""
    hi = p.hydro_index
    disp = np.empty(hi.shape[0])
    for k in range(hi.shape[0]):
        i = hi[k] // 6
        a = hi[k] % 6
        if a < 3:
            disp[k] = pos[i, a] - p.com0[i, a]
        else:
            disp[k] = so3_log(rot[i])[a - 3]
    out = p.static_force.copy()
    restoring = p.hydrostatic_stiffness @ disp
    for k in range(hi.shape[0]):
        out[hi[k]] -= restoring[k]
    return out


@kernel
def end_stop(p: Plant, k: int, x: float, xdot: float) -> float:
    """Force of PTO k's end stop [N or N m] at stroke ``x`` and rate ``xdot``: a spring on the stroke beyond the
    limit and a damper while engaged; zero inside the limit and for a PTO without an end stop."""
    excess = abs(x) - p.pto_stroke_limit[k]
    if excess > 0.0 and p.pto_stop_stiffness[k] > 0.0:
        return -np.sign(x) * p.pto_stop_stiffness[k] * excess - p.pto_stop_damping[k] * xdot
    return 0.0


def end_stop_force(p: Plant, x: np.ndarray, xdot: np.ndarray) -> np.ndarray:
    """Forces of every PTO's end stop (n_pto,) [N or N m] (see :func:`end_stop`)."""
    return np.array([end_stop(p, k, float(x[k]), float(xdot[k])) for k in range(x.shape[0])])


@kernel
def accelerations(
    p: Plant, q: np.ndarray, v: np.ndarray, hydro_force: np.ndarray, newest: np.ndarray, pto_command: np.ndarray
):
    """Generalised accelerations of the MFM equations (Eq. 46) with all loads.

    Parameters
    ----------
    hydro_force : (n_h,)
        Excitation plus the radiation memory force fixed by the past, on the hydro DOFs, world axes [N, N m].
    newest : (n_h, n_h)
        Memory force per unit hydro velocity at this instant (added as ``newest @ u``).
    pto_command : (n_pto,)
        Controller force held over the step [N or N m] (added to the device spring and the linear gains).

    Returns
    -------
    a : (nv,) accelerations; u : (n_h,) hydro velocities; x, x_dot, f : (n_pto,) PTO stroke from rest, rate and
    force (the controller's, saturated at the force limit, plus the device spring; the end stops act besides);
    mass : (nv, nv) M*.
    """
    rot, pos, b, bdot, omega = kinematics(p, q, v)
    n = pos.shape[0]
    nv = v.shape[0]
    bw = world_jacobian(rot, b)
    # only the Cartesian rows that can move (``Plant.active``: x, z and pitch of a planar device)
    act = p.active
    m = act.shape[0]
    ba = np.empty((m, nv))
    bda_v = np.empty(m)
    bdv = bdot @ v
    for k in range(m):
        ba[k] = b[act[k]]
        bda_v[k] = bdv[act[k]]
    mass = ba.T @ (p.active_mass @ ba)
    # N* v = B' ((M + A_inf) Bdot v + D M B v); D M B v = omega_b x (J omega_b) on the rotational rows
    gyro = np.zeros(6 * n)
    for i in range(n):
        jw = p.inertia[i] @ omega[i]
        gyro[6 * i + 3 : 6 * i + 6] = np.cross(omega[i], jw)
    rhs = -(p.active_mass @ bda_v)
    for k in range(m):
        rhs[k] -= gyro[act[k]]
    hi = p.hydro_index
    u = hydro_rows(bw, v, hi)
    load = hydro_force + newest @ u - p.mooring_damping @ u  # the moorings' dampers
    force = hydrostatic_force(p, rot, pos)
    for k in range(hi.shape[0]):
        force[hi[k]] += load[k]
    # generalised force: world loads through Bw; inertial terms (body-axis moments) through B
    gen = bw.T @ force + ba.T @ rhs - p.joint_damping * v  # the joints' own losses
    stroke, gmat = pto_strokes(p, q, rot, pos, b)
    x = stroke - p.pto_rest
    xdot = gmat @ v
    # the controller's force, saturated at the PTO's force limit, and the device spring
    control = pto_command - p.pto_damping * xdot - p.pto_stiffness * x
    f = np.minimum(np.maximum(control, -p.pto_force_limit), p.pto_force_limit) - p.pto_spring * x
    gen += gmat.T @ f
    for k in range(x.shape[0]):  # the end stops, where engaged (no allocation on the usual path)
        stop = end_stop(p, k, x[k], xdot[k])
        if stop != 0.0:
            gen += gmat[k] * stop
    a = np.linalg.solve(0.5 * (mass + mass.T), gen)
    return a, u, x, xdot, f, mass


@kernel
def hydro_velocity(p: Plant, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Velocities of the hydro DOFs (world axes) [m/s, rad/s]."""
    rot, _pos, b, _bdot, _omega = kinematics(p, q, v)
    return hydro_rows(world_jacobian(rot, b), v, p.hydro_index)


@kernel
def hydro_rows(bw: np.ndarray, v: np.ndarray, hydro_index: np.ndarray) -> np.ndarray:
    """The hydro DOFs' rows of Bw v: their velocities in world axes [m/s, rad/s]."""
    bwv = bw @ v
    u = np.zeros(hydro_index.shape[0])
    for k in range(hydro_index.shape[0]):
        u[k] = bwv[hydro_index[k]]
    return u


@kernel
def integrate_configuration(p: Plant, q: np.ndarray, dv: np.ndarray) -> np.ndarray:
    """q moved by the velocity increment dv (free bases on SO(3) through their quaternion)."""
    out = q.copy()
    for i in range(p.com0.shape[0]):
        iq = p.q_start[i]
        iv = p.col_start[i]
        if p.free[i] == 1:
            out[iq : iq + 3] += dv[iv : iv + 3]
            r = dv[iv + 3 : iv + 6].copy()
            angle = np.sqrt(np.sum(r**2))
            e = np.zeros(4)
            if angle < 1e-12:
                e[0] = 1.0
                e[1:] = 0.5 * r
                e /= np.sqrt(np.sum(e**2))
            else:
                e[0] = np.cos(angle / 2)
                e[1:] = np.sin(angle / 2) / angle * r
            quat = quat_multiply(q[iq + 3 : iq + 7].copy(), e)
            out[iq + 3 : iq + 7] = quat / np.sqrt(np.sum(quat**2))
        else:
            for k in range(p.n_cols[i]):
                out[iq + k] += dv[iv + k]
    return out


@kernel
def configuration_rate(p: Plant, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """dq/dt: v for joint coordinates; CoM velocity and quaternion rate for a free base."""
    out = np.zeros(q.shape[0])
    for i in range(p.com0.shape[0]):
        iq = p.q_start[i]
        iv = p.col_start[i]
        if p.free[i] == 1:
            out[iq : iq + 3] = v[iv : iv + 3]
            w = np.zeros(4)
            w[1:] = v[iv + 3 : iv + 6]
            out[iq + 3 : iq + 7] = 0.5 * quat_multiply(q[iq + 3 : iq + 7].copy(), w)
        else:
            for k in range(p.n_cols[i]):
                out[iq + k] = v[iv + k]
    return out


@kernel
def normalise_quaternions(p: Plant, q: np.ndarray) -> None:
    for i in range(p.com0.shape[0]):
        if p.free[i] == 1:
            iq = p.q_start[i]
            q[iq + 3 : iq + 7] /= np.sqrt(np.sum(q[iq + 3 : iq + 7] ** 2))


@kernel
def poses(p: Plant, qs: np.ndarray):
    """CoM positions (n_t, n, 3) and rotation vectors (n_t, n, 3) along a record of configurations."""
    n_t = qs.shape[0]
    n = p.com0.shape[0]
    nv = p.twists.shape[0]
    positions = np.zeros((n_t, n, 3))
    rotations = np.zeros((n_t, n, 3))
    zero = np.zeros(nv)
    for t in range(n_t):
        rot, pos, _b, _bdot, _omega = kinematics(p, qs[t].copy(), zero)
        positions[t] = pos
        for i in range(n):
            rotations[t, i] = so3_log(np.ascontiguousarray(rot[i]))
    return positions, rotations
