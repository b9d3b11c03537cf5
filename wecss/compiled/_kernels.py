"""The nonlinear MFM equations of motion on flat arrays (numba-compiled when available, see ``_jit``).

Same mathematics as :mod:`wecss.multibody` (product-of-exponentials kinematics, M* = B'(M + A_inf)B,
N* = B'((M + A_inf) Bdot + D M B), paper Eq. 46), written as loops over small arrays so that numba can compile
it; the tests check it against the object-based implementation.

Loads: hydrodynamic forces act in world axes on the hydro DOFs (linear hydrodynamics), so they enter through the
world-frame Jacobian Bw (CoM velocity and world angular velocity per body): F* = Bw' F_world. The hydro velocity
u = Bw v drives the radiation memory.

Cartesian rows: every body's rows are found through the plant's ``cart_start`` (its first row) and ``cart_body``,
``cart_axis`` (a row's body and axis), never as 6 per body. A generalised mode's row (axis 6..) is the rate of its
coordinate: B is the identity on its column (``cart_column``), Bdot and the gyroscopic term are zero, its world row
of Bw is its B row, its hydrostatic displacement is the coordinate itself (``cart_coordinate``), and its
structural stiffness and damping (``mode_stiffness``, ``mode_damping``) act as generalised forces.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ._body_exact import configure_pressure
from ._jit import inline_kernel, kernel, reshaped, step_kernel
from ._linalg import cholesky, cholesky_solve, congruence, matvec, matvec_add, matvec_t_add
from ._plant import Plant, PtoKind, elastic_of_body, elastic_of_child, elastic_views
from ._pto_law import pto_control_force_kernel
from ._rotation import so3_log_into
from ._viscous import TermsWork, configure_viscous, respond_viscous, terms_work

_SERIES = 1e-2
"""Below this rotation angle [rad] :func:`_screw` takes its coefficients from their Taylor series (to theta^6:
the next terms are below 1e-21 of them)."""


@kernel
def so3_log(r: np.ndarray) -> np.ndarray:
    """The rotation vector of the rotation matrix ``r`` (3, 3) [rad]."""
    out = np.empty(3)
    so3_log_into(r, out)
    return out


@inline_kernel
def _quat_matrix_into(q: np.ndarray, start: int, out: np.ndarray) -> None:
    """The rotation matrix of the quaternion (w, x, y, z) = q[start : start + 4] (normalised here) into ``out``."""
    n = np.sqrt(q[start] ** 2 + q[start + 1] ** 2 + q[start + 2] ** 2 + q[start + 3] ** 2)
    w, x, y, z = q[start] / n, q[start + 1] / n, q[start + 2] / n, q[start + 3] / n
    out[0, 0] = 1 - 2 * (y * y + z * z)
    out[0, 1] = 2 * (x * y - w * z)
    out[0, 2] = 2 * (x * z + w * y)
    out[1, 0] = 2 * (x * y + w * z)
    out[1, 1] = 1 - 2 * (x * x + z * z)
    out[1, 2] = 2 * (y * z - w * x)
    out[2, 0] = 2 * (x * z - w * y)
    out[2, 1] = 2 * (y * z + w * x)
    out[2, 2] = 1 - 2 * (x * x + y * y)


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


@inline_kernel
def _rotate(r: np.ndarray, x: np.ndarray, out: np.ndarray) -> None:
    for a in range(3):
        out[a] = r[a, 0] * x[0] + r[a, 1] * x[1] + r[a, 2] * x[2]


@inline_kernel
def _cross(a: np.ndarray, b: np.ndarray, out: np.ndarray) -> None:
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@inline_kernel
def _screw(xi: np.ndarray, angle: float, rot: np.ndarray, trans: np.ndarray) -> None:
    """exp(xi * angle) as a rotation and a translation (Rodrigues; se3_exp without temporaries):
    R = I + c1 K + c2 K^2, t = v + c2 w x v + c3 w x (w x v), K = hat(w), K^2 = w w' - |w|^2 I, with
    c1 = sin(theta) / theta, c2 = (1 - cos(theta)) / theta^2, c3 = (theta - sin(theta)) / theta^3, theta = |w|."""
    w0, w1, w2 = xi[3] * angle, xi[4] * angle, xi[5] * angle
    v0, v1, v2 = xi[0] * angle, xi[1] * angle, xi[2] * angle
    theta2 = w0 * w0 + w1 * w1 + w2 * w2
    theta = np.sqrt(theta2)
    if theta < _SERIES:  # their Taylor series: exact to round-off here, and no cancellation (nor sin and cos)
        c1 = 1.0 - theta2 / 6.0 * (1.0 - theta2 / 20.0 * (1.0 - theta2 / 42.0))
        c2 = 0.5 * (1.0 - theta2 / 12.0 * (1.0 - theta2 / 30.0 * (1.0 - theta2 / 56.0)))
        c3 = (1.0 - theta2 / 20.0 * (1.0 - theta2 / 42.0 * (1.0 - theta2 / 72.0))) / 6.0
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


@inline_kernel
def _compose(r: np.ndarray, r_step: np.ndarray, out: np.ndarray) -> None:
    for a in range(3):
        for b in range(3):
            out[a, b] = r[a, 0] * r_step[0, b] + r[a, 1] * r_step[1, b] + r[a, 2] * r_step[2, b]


class Workspace(NamedTuple):
    """Arrays the kernels fill in place, made once per run by :func:`workspace` (no allocation per evaluation).

    Configuration (filled by :func:`place` and :func:`configure`, functions of q alone)
        rot (n, 3, 3), trans (n, 3): frame displacement of each body from its reference pose; pos (n, 3) CoM
        positions; cols (6, nv) joint twists S in world axes; b (n_cart, nv) B (rows: CoM velocity, body angular
        velocity, the modes' rates); bat (nv, m) its active rows, transposed; bh (n_h, nv) the hydro rows of the
        world Jacobian Bw; mass (nv, nv) M* and factor its Cholesky factor; gen_config (nv,) the generalised force
        of the configuration's loads (gravity, buoyancy, hydrostatics, the modes' structural stiffness and the given
        hydro force); stroke, gmat (n_pto,), (n_pto, nv) PTO strokes from rest and transmissions
    Velocity (filled by :func:`move` and :func:`respond`)
        spatial (n, 6) spatial twists; cols_dot (6, nv) dS/dt; omega (n, 3) body angular velocities; lin (n, 3) CoM
        velocities; bias (n_cart,) Bdot v; acc (nv,) accelerations; u (n_h,) hydro velocities (world axes); xdot, f
        (n_pto,) PTO rates and forces
    Scratch: force (n_cart,), disp, restoring, load (n_h,), inertial (m,), mass_work (nv, m), gen (nv,), partial (6,),
    vec, vec2, t_step (3,), r_step, r_new (3, 3)
    Hydrodynamic terms beyond the linear database: terms (``wecss.compiled._viscous.TermsWork``)
    Flexible bodies: elastic, one float array holding an :class:`ElasticWork` (:func:`elastic_work`; empty for a
    plant without them: one array rather than nine, see ``Plant.elastic_index``)
    """

    rot: np.ndarray
    trans: np.ndarray
    pos: np.ndarray
    cols: np.ndarray
    b: np.ndarray
    bat: np.ndarray
    bh: np.ndarray
    mass: np.ndarray
    factor: np.ndarray
    gen_config: np.ndarray
    stroke: np.ndarray
    gmat: np.ndarray
    spatial: np.ndarray
    cols_dot: np.ndarray
    omega: np.ndarray
    lin: np.ndarray
    bias: np.ndarray
    acc: np.ndarray
    u: np.ndarray
    xdot: np.ndarray
    f: np.ndarray
    force: np.ndarray
    disp: np.ndarray
    restoring: np.ndarray
    load: np.ndarray
    inertial: np.ndarray
    mass_work: np.ndarray
    gen: np.ndarray
    partial: np.ndarray
    vec: np.ndarray
    vec2: np.ndarray
    r_step: np.ndarray
    r_new: np.ndarray
    t_step: np.ndarray
    terms: TermsWork
    elastic: np.ndarray


class ElasticWork(NamedTuple):
    """The flexible bodies' part of a :class:`Workspace`, views of its ``elastic`` array (:func:`elastic_work`;
    n_el, nm, n_att, m and n_cart as in ``Plant.elastic_index``).

    att_cols, att_cols_dot (n_att, nm, 6): the world twists of the parent's mode columns on each elastic attachment
    and their time derivatives (they differ between the children of one flexible body, so they are kept per
    attachment, not in ``cols``); active_mass (m, m): ``Plant.active_mass`` with the flexible bodies' M(xi) at the
    configuration; mass (n_el, 3 + nm, 3 + nm) M(xi) on its rotation rows and columns (its mode-mode block does
    not depend on xi and is not filled: M(0)'s, in ``Plant.active_mass``), dmass (n_el, nm, 3, 3 + nm) the
    rotation rows of dM/dxi (the mode rows are their transposes' and zero: dM/dxi_k = [[dJ_k, dC_k], [dC_k', 0]]);
    quad (n_cart,)
    their quadratic-velocity vector (D M + Q) Y on the rotation and mode rows; scratch y, my (3 + nm,), pair
    (nm * nm,), pto (54,) (:func:`_elastic_pto_ends`'s) and none (0,) (an empty array, for its ``where``)
    """

    att_cols: np.ndarray
    att_cols_dot: np.ndarray
    active_mass: np.ndarray
    mass: np.ndarray
    dmass: np.ndarray
    y: np.ndarray
    my: np.ndarray
    quad: np.ndarray
    pair: np.ndarray
    pto: np.ndarray
    none: np.ndarray


@inline_kernel
def elastic_work_size(index: np.ndarray) -> int:
    """The length of a Workspace's ``elastic`` array for a plant's ``elastic_index`` (0 without flexible
    bodies)."""
    n_el, nm, n_att, m, n_cart = index[1], index[2], index[3], index[4], index[5]
    if n_el == 0:
        return 0
    k = 3 + nm
    return 2 * n_att * nm * 6 + m * m + n_el * k * k + n_el * nm * 3 * k + 2 * k + n_cart + nm * nm + 54


@inline_kernel
def elastic_work(index: np.ndarray, work: np.ndarray) -> ElasticWork:
    """The :class:`ElasticWork` views of a Workspace's ``elastic`` array (a plant with flexible bodies)."""
    n_el, nm, n_att, m, n_cart = index[1], index[2], index[3], index[4], index[5]
    k = 3 + nm
    o = 0
    att_cols = reshaped(work[o : o + n_att * nm * 6], (n_att, nm, 6))
    o += n_att * nm * 6
    att_cols_dot = reshaped(work[o : o + n_att * nm * 6], (n_att, nm, 6))
    o += n_att * nm * 6
    active_mass = reshaped(work[o : o + m * m], (m, m))
    o += m * m
    mass = reshaped(work[o : o + n_el * k * k], (n_el, k, k))
    o += n_el * k * k
    dmass = reshaped(work[o : o + n_el * nm * 3 * k], (n_el, nm, 3, k))
    o += n_el * nm * 3 * k
    y = work[o : o + k]
    o += k
    my = work[o : o + k]
    o += k
    quad = work[o : o + n_cart]
    o += n_cart
    pair = work[o : o + nm * nm]
    o += nm * nm
    pto = work[o : o + 54]
    o += 54
    return ElasticWork(att_cols, att_cols_dot, active_mass, mass, dmass, y, my, quad, pair, pto, work[o:o])


@kernel
def workspace(p: Plant) -> Workspace:
    """A :class:`Workspace` for the plant ``p``."""
    n = p.com0.shape[0]
    n_cart = p.cart_body.shape[0]
    nv = p.twists.shape[0]
    m = p.active.shape[0]
    n_h = p.hydro_index.shape[0]
    n_pto = p.pto_kind.shape[0]
    return Workspace(
        np.zeros((n, 3, 3)), np.zeros((n, 3)), np.zeros((n, 3)), np.zeros((6, nv)), np.zeros((n_cart, nv)),
        np.zeros((nv, m)), np.zeros((n_h, nv)), np.zeros((nv, nv)), np.zeros((nv, nv)), np.zeros(nv),
        np.zeros(n_pto), np.zeros((n_pto, nv)),
        np.zeros((n, 6)), np.zeros((6, nv)), np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n_cart), np.zeros(nv),
        np.zeros(n_h), np.zeros(n_pto), np.zeros(n_pto),
        np.zeros(n_cart), np.zeros(n_h), np.zeros(n_h), np.zeros(n_h), np.zeros(m), np.zeros((nv, m)), np.zeros(nv),
        np.zeros(6), np.zeros(3), np.zeros(3), np.zeros((3, 3)), np.zeros((3, 3)), np.zeros(3),
        terms_work(p.viscous, n), np.zeros(elastic_work_size(p.elastic_index)),
    )  # fmt: skip


@inline_kernel
def place(p: Plant, q: np.ndarray, w: Workspace, elastic: bool) -> None:
    """The configuration part of the kinematics: rot, trans, pos, the world twists ``cols`` and B, into ``w`` (a
    generalised mode's row of B: the identity on its column); ``elastic``: the plant has flexible bodies (a
    constant in the per-step kernels, so that the rigid ones compile without their code, see :func:`configure`):
    :func:`_place` on their arrays."""
    _place(
        p.order, p.parent, p.col_start, p.q_start, p.n_cols, p.free, p.twists, p.com0, p.chain, p.cart_start,
        p.mode_row, p.cart_column, q, w.rot, w.trans, w.pos, w.cols, w.b, w.vec, w.vec2, w.t_step, w.r_step, w.r_new,
        elastic, p.elastic_index, p.elastic_data, w.elastic,
    )  # fmt: skip


@inline_kernel
def _place(
    order: np.ndarray, parent: np.ndarray, col_start: np.ndarray, q_start: np.ndarray, n_cols: np.ndarray,
    free: np.ndarray, joint_twists: np.ndarray, com0: np.ndarray, chain: np.ndarray, cart_start: np.ndarray,
    mode_row: np.ndarray, cart_column: np.ndarray, q: np.ndarray, rot: np.ndarray, trans: np.ndarray, pos: np.ndarray,
    cols: np.ndarray, b: np.ndarray, tmp: np.ndarray, tmp2: np.ndarray, t_step: np.ndarray, r_step: np.ndarray,
    r_new: np.ndarray, elastic: bool, el_index: np.ndarray, el_data: np.ndarray, el_work: np.ndarray,
) -> None:  # fmt: skip
    """:func:`place` on the arrays of the Plant and the Workspace of the same names (``joint_twists``: the Plant's
    ``twists``; ``tmp``, ``tmp2``: the Workspace's ``vec``, ``vec2``; the others as in :func:`_frames`)."""
    n = com0.shape[0]
    nv = joint_twists.shape[0]
    _frames(
        order, parent, col_start, q_start, n_cols, free, joint_twists, com0, q, rot, trans, pos, cols, tmp, tmp2,
        t_step, r_step, r_new, True, elastic, el_index, el_data, el_work,
    )  # fmt: skip
    # B_i = [[I, -hat(p)], [0, R']] S on the columns that move body i
    for i in range(n):
        r = rot[i]
        pi = pos[i]
        r0 = cart_start[i]
        for c in range(nv):
            if chain[i, c] == 0.0:
                for a in range(6):
                    b[r0 + a, c] = 0.0
                continue
            s = cols[:, c]
            _cross(pi, s[3:], tmp)
            for a in range(3):
                b[r0 + a, c] = s[a] - tmp[a]
                b[r0 + 3 + a, c] = r[0, a] * s[3] + r[1, a] * s[4] + r[2, a] * s[5]
    for k in range(mode_row.shape[0]):  # a generalised mode: the rate of its own coordinate
        row = mode_row[k]
        for c in range(nv):
            b[row, c] = 0.0
        b[row, cart_column[row]] = 1.0
    if elastic:
        _place_elastic(el_index, el_data, el_work, rot, pos, cart_start, b, tmp)


@step_kernel
def _place_elastic(
    index: np.ndarray, data: np.ndarray, work: np.ndarray, rot: np.ndarray, pos: np.ndarray, cart_start: np.ndarray,
    b: np.ndarray, tmp: np.ndarray,
) -> None:  # fmt: skip
    """B's columns of the flexible bodies' modes (``wecss.multibody._kinematics``; ``index``, ``data``: the plant's
    ``elastic_index``, ``elastic_data``, ``work`` the Workspace's ``elastic``, the others as in the Plant and the
    Workspace): on the rigid rows of a body carried by an elastic attachment, [[I, -hat(p)], [0, R']] times the
    attachment's twist; on the body's own translational rows, R Ct / m (its centre of mass moves with the
    structure). (Not inlined: see :func:`_ride_attachment`.)"""
    el = elastic_views(index, data)
    of_body, att_parent, size, column, mass, coupling, on_path = el.of_body, el.parent, el.size, el.column, \
        el.mass, el.coupling, el.on_path  # fmt: skip
    att_cols = elastic_work(index, work).att_cols
    for i in range(rot.shape[0]):
        r = rot[i]
        pi = pos[i]
        r0 = cart_start[i]
        for att in range(att_parent.shape[0]):
            if on_path[i, att] == 0.0:
                continue
            e = of_body[att_parent[att]]
            for k in range(size[e]):
                c = column[e] + k
                s = att_cols[att, k]
                _cross(pi, s[3:], tmp)
                for a in range(3):
                    b[r0 + a, c] = s[a] - tmp[a]
                    b[r0 + 3 + a, c] = r[0, a] * s[3] + r[1, a] * s[4] + r[2, a] * s[5]
        e = of_body[i]
        if e >= 0:
            m = mass[e]
            for k in range(size[e]):
                c = column[e] + k
                for a in range(3):
                    b[r0 + a, c] = (
                        r[a, 0] * (coupling[e, 0, k] / m)
                        + r[a, 1] * (coupling[e, 1, k] / m)
                        + r[a, 2] * (coupling[e, 2, k] / m)
                    )


@inline_kernel
def _frames(
    order: np.ndarray, parent: np.ndarray, col_start: np.ndarray, q_start: np.ndarray, n_cols: np.ndarray,
    free: np.ndarray, joint_twists: np.ndarray, com0: np.ndarray, q: np.ndarray, rot: np.ndarray, trans: np.ndarray,
    pos: np.ndarray, cols: np.ndarray, tmp: np.ndarray, tmp2: np.ndarray, t_step: np.ndarray, r_step: np.ndarray,
    r_new: np.ndarray, twists: bool, elastic: bool, el_index: np.ndarray, el_data: np.ndarray, el_work: np.ndarray,
) -> None:  # fmt: skip
    """The bodies' frames rot, trans and CoM positions pos at configuration ``q``; with ``twists`` also the world
    twists of the joint columns, ``cols`` (the arrays as in Plant and Workspace). It takes the arrays, not the
    tuples: a call with the Plant and Workspace costs about 1 us (a reference count per array they hold), more than
    the frames of a few bodies, and :func:`poses` calls it once per configuration.

    Flexible bodies (``elastic``: a constant of the caller; ``el_index``, ``el_data`` the plant's ``elastic_index``
    and ``elastic_data``, ``el_work`` the Workspace's ``elastic``): a joint on an elastic attachment of its parent
    rides on prod_k exp(psi_k xi_k) of the attachment's twists (their world twists into ``ElasticWork.att_cols``
    with ``twists``); a flexible body's centre of mass is c0 + (s0 + Ct xi) / m."""
    n = com0.shape[0]
    if twists:
        for a in range(6):
            for c in range(cols.shape[1]):
                cols[a, c] = 0.0
    for idx in range(n):
        i = order[idx]
        par = parent[i]
        r = rot[i]
        t = trans[i]
        for a in range(3):  # element loops: numba's slice assignment costs more than these copies
            t[a] = trans[par, a] if par >= 0 else 0.0
            for b in range(3):
                r[a, b] = rot[par, a, b] if par >= 0 else (1.0 if a == b else 0.0)
        iv = col_start[i]
        iq = q_start[i]
        att = elastic_of_child(el_index, i) if elastic else -1
        if att >= 0:  # on an elastic attachment of the parent
            _ride_attachment(el_index, el_data, el_work, att, q, r, t, twists, tmp, tmp2, t_step, r_step, r_new)
        if free[i] == 1:
            _quat_matrix_into(q, iq + 3, r)
            _rotate(r, com0[i], tmp)
            for a in range(3):
                t[a] = q[iq + a] - tmp[a]
            if twists:  # translation columns: the unit vectors; rotation columns: (x cross R e_b, R e_b)
                x0, x1, x2 = q[iq], q[iq + 1], q[iq + 2]
                for b in range(3):
                    cols[b, iv + b] = 1.0
                    c0, c1, c2 = r[0, b], r[1, b], r[2, b]
                    cols[0, iv + 3 + b] = x1 * c2 - x2 * c1
                    cols[1, iv + 3 + b] = x2 * c0 - x0 * c2
                    cols[2, iv + 3 + b] = x0 * c1 - x1 * c0
                    for a in range(3):
                        cols[3 + a, iv + 3 + b] = r[a, b]
        else:
            for k in range(n_cols[i]):
                col = iv + k
                xi = joint_twists[col]
                if twists:  # S = Ad(G) xi: w' = R w, v' = R v + t x w'
                    _rotate(r, xi[3:], tmp)
                    _rotate(r, xi[:3], tmp2)
                    for a in range(3):
                        cols[3 + a, col] = tmp[a]
                    _cross(t, tmp, t_step)
                    for a in range(3):
                        cols[a, col] = tmp2[a] + t_step[a]
                # G <- G exp(xi q)
                _screw(xi, q[iq + k], r_step, t_step)
                _rotate(r, t_step, tmp)
                for a in range(3):
                    t[a] += tmp[a]
                _compose(r, r_step, r_new)
                for a in range(3):
                    for b in range(3):
                        r[a, b] = r_new[a, b]
        e = elastic_of_body(el_index, i) if elastic else -1
        if e >= 0:  # a flexible body's centre of mass moves with the structure
            _elastic_centre(el_index, el_data, com0, i, e, q, tmp2)
            _rotate(r, tmp2, tmp)
        else:
            _rotate(r, com0[i], tmp)
        for a in range(3):
            pos[i, a] = tmp[a] + t[a]


@step_kernel
def _ride_attachment(
    index: np.ndarray, data: np.ndarray, work: np.ndarray, att: int, q: np.ndarray, r: np.ndarray, t: np.ndarray,
    twists: bool, tmp: np.ndarray, tmp2: np.ndarray, t_step: np.ndarray, r_step: np.ndarray, r_new: np.ndarray,
) -> None:  # fmt: skip
    """The frame (r, t) carried along elastic attachment ``att`` (``index``, ``data``, ``work``: see
    :func:`_frames`): G <- G prod_k exp(psi_k xi_k) over the parent's modal coordinates xi; with ``twists`` the
    world twists Ad(G) psi_k before each factor into ``att_cols[att]``. (A kernel of its own, not inlined: the
    per-step kernels stay small enough for numba to prune their reference counts, see ``_jit.inline_kernel``; it
    takes the packed arrays, not the views, for the same reason.)"""
    el = elastic_views(index, data)
    att_twists = el.twists
    att_cols = elastic_work(index, work).att_cols
    e = el.of_body[el.parent[att]]
    n, first = el.size[e], el.coordinate[e]
    for k in range(n):
        psi = att_twists[att, k]
        if twists:
            _rotate(r, psi[3:], tmp)
            _rotate(r, psi[:3], tmp2)
            for a in range(3):
                att_cols[att, k, 3 + a] = tmp[a]
            _cross(t, tmp, t_step)
            for a in range(3):
                att_cols[att, k, a] = tmp2[a] + t_step[a]
        _screw(psi, q[first + k], r_step, t_step)
        _rotate(r, t_step, tmp)
        for a in range(3):
            t[a] += tmp[a]
        _compose(r, r_step, r_new)
        for a in range(3):
            for b in range(3):
                r[a, b] = r_new[a, b]


@step_kernel
def _elastic_centre(
    index: np.ndarray, data: np.ndarray, com0: np.ndarray, i: int, e: int, q: np.ndarray, out: np.ndarray
) -> None:
    """The centre of mass c0 + (s0 + Ct xi) / m of body ``i``, flexible body ``e``, in its frame, into ``out``
    (``index``, ``data``: see :func:`_frames`)."""
    el = elastic_views(index, data)
    el_size, el_coordinate, el_mass, el_first_moment, el_coupling = el.size, el.coordinate, el.mass, \
        el.first_moment, el.coupling  # fmt: skip
    first = el_coordinate[e]
    for a in range(3):
        moment = el_first_moment[e, a]
        for k in range(el_size[e]):
            moment += el_coupling[e, a, k] * q[first + k]
        out[a] = com0[i, a] + moment / el_mass[e]


@inline_kernel
def move(p: Plant, v: np.ndarray, w: Workspace, elastic: bool) -> None:
    """The velocity part of the kinematics at the configuration in ``w`` (:func:`place`): spatial twists, dS/dt,
    body angular velocities, CoM velocities and Bdot v, into ``w`` (:func:`_velocities` on their arrays)."""
    _velocities(
        p.order, p.parent, p.col_start, p.free, p.n_cols, p.chain, p.cart_start, v, w.rot, w.pos, w.cols, w.cols_dot,
        w.spatial, w.omega, w.lin, w.bias, w.partial, w.vec, w.vec2, w.t_step, elastic, p.elastic_index,
        p.elastic_data, w.elastic,
    )  # fmt: skip


@inline_kernel
def _velocities(
    order: np.ndarray, parent: np.ndarray, col_start: np.ndarray, free: np.ndarray, n_cols: np.ndarray,
    chain: np.ndarray, cart_start: np.ndarray, v: np.ndarray, rot: np.ndarray, pos: np.ndarray, cols: np.ndarray,
    cols_dot: np.ndarray, spatial: np.ndarray, omega: np.ndarray, lin: np.ndarray, bias: np.ndarray,
    vel: np.ndarray, tmp: np.ndarray, tmp2: np.ndarray, scratch: np.ndarray, elastic: bool, el_index: np.ndarray,
    el_data: np.ndarray, el_work: np.ndarray,
) -> None:  # fmt: skip
    """:func:`move` on the arrays of the Plant and the Workspace of the same names (``vel`` (6,): the Workspace's
    ``partial``; ``tmp``, ``tmp2``, ``scratch`` (3,): its ``vec``, ``vec2``, ``t_step``; ``elastic``, ``el_index``,
    ``el_data``, ``el_work``: see :func:`_frames`). It takes the arrays, not the tuples: a tuple's array read in a
    loop is a reference count up and down per pass that numba cannot prune in the flexible bodies' kernels."""
    n = order.shape[0]
    nv = chain.shape[1]
    for idx in range(n):
        i = order[idx]
        par = parent[i]
        iv = col_start[i]
        if free[i] == 1:  # dS/dt of a free base: its translation columns are constant
            # rotation column b: with c = R (w_b x e_b), (v x R e_b + p x c, c), i.e. hat(v) R + hat(p) R hat(w_b)
            # and R hat(w_b)
            r = rot[i]
            pi = pos[i]
            wb0, wb1, wb2 = v[iv + 3], v[iv + 4], v[iv + 5]
            for b in range(3):
                for a in range(6):
                    cols_dot[a, iv + b] = 0.0
                e0, e1, e2 = (0.0, wb2, -wb1) if b == 0 else ((-wb2, 0.0, wb0) if b == 1 else (wb1, -wb0, 0.0))
                c0 = r[0, 0] * e0 + r[0, 1] * e1 + r[0, 2] * e2
                c1 = r[1, 0] * e0 + r[1, 1] * e1 + r[1, 2] * e2
                c2 = r[2, 0] * e0 + r[2, 1] * e1 + r[2, 2] * e2
                r0, r1, r2 = r[0, b], r[1, b], r[2, b]
                l0, l1, l2 = v[iv], v[iv + 1], v[iv + 2]
                cols_dot[0, iv + 3 + b] = l1 * r2 - l2 * r1 + pi[1] * c2 - pi[2] * c1
                cols_dot[1, iv + 3 + b] = l2 * r0 - l0 * r2 + pi[2] * c0 - pi[0] * c2
                cols_dot[2, iv + 3 + b] = l0 * r1 - l1 * r0 + pi[0] * c1 - pi[1] * c0
                cols_dot[3, iv + 3 + b] = c0
                cols_dot[4, iv + 3 + b] = c1
                cols_dot[5, iv + 3 + b] = c2
            for a in range(6):
                total = 0.0
                for c in range(iv, iv + 6):
                    total += cols[a, c] * v[c]
                vel[a] = total
        else:
            for a in range(6):  # element loops: a slice assignment is a call (and allocates)
                vel[a] = spatial[par, a] if par >= 0 else 0.0
            att = elastic_of_child(el_index, i) if elastic else -1
            if att >= 0:  # on an elastic attachment: the parent's mode columns come first
                _move_attachment(el_index, el_data, el_work, att, v, vel, tmp, tmp2)
            for k in range(n_cols[i]):
                col = iv + k
                s = cols[:, col]
                # dS/dt = [V, S]: (w_V x v_S - w_S x v_V, w_V x w_S)
                _cross(vel[3:], s[:3], tmp)
                _cross(s[3:], vel[:3], tmp2)
                for a in range(3):
                    cols_dot[a, col] = tmp[a] - tmp2[a]
                _cross(vel[3:], s[3:], tmp)
                for a in range(3):
                    cols_dot[3 + a, col] = tmp[a]
                for a in range(6):
                    vel[a] += s[a] * v[col]
        for a in range(6):
            spatial[i, a] = vel[a]
    # per body: CoM velocity, body angular velocity, and Bdot_i v = [-lin x w + A_lin - p x A_ang; R' A_ang] with
    # A = sum over the body's columns of v_c dS_c/dt (the columns' -hat(w_b) R' terms sum to -w_b x w_b = 0)
    acc = vel
    for i in range(n):
        r = rot[i]
        pi = pos[i]
        twist = spatial[i]
        _cross(pi, twist[3:], tmp)
        for a in range(3):
            lin[i, a] = twist[a] - tmp[a]
            omega[i, a] = r[0, a] * twist[3] + r[1, a] * twist[4] + r[2, a] * twist[5]
        for a in range(6):
            acc[a] = 0.0
        for c in range(nv):
            if chain[i, c] != 0.0:
                for a in range(6):
                    acc[a] += cols_dot[a, c] * v[c]
        e = -1
        if elastic:
            e = _move_elastic(el_index, el_data, el_work, i, v, acc, rot, omega, lin, tmp, tmp2, scratch)
        _cross(lin[i], twist[3:], tmp)
        _cross(pi, acc[3:], tmp2)
        r0 = cart_start[i]
        for a in range(3):  # (a generalised mode's row of Bdot v stays zero)
            bias[r0 + a] = -tmp[a] + acc[a] - tmp2[a]
            bias[r0 + 3 + a] = r[0, a] * acc[3] + r[1, a] * acc[4] + r[2, a] * acc[5]
        if e >= 0:  # Bdot on a flexible body's own mode columns: R hat(w_b) Ct / m
            _rotate(r, scratch, tmp)
            for a in range(3):
                bias[r0 + a] += tmp[a]


@step_kernel
def _move_attachment(
    index: np.ndarray, data: np.ndarray, work: np.ndarray, att: int, v: np.ndarray, vel: np.ndarray,
    tmp: np.ndarray, tmp2: np.ndarray,
) -> None:  # fmt: skip
    """Along elastic attachment ``att`` (over its parent's modal velocities; ``index``, ``data``, ``work``: see
    :func:`_frames`): dS/dt = [V, S] of each of its columns into ``att_cols_dot[att]``, the spatial velocity ``vel``
    advanced past it. (Not inlined: see :func:`_ride_attachment`.)"""
    el = elastic_views(index, data)
    ew = elastic_work(index, work)
    att_cols, att_cols_dot = ew.att_cols, ew.att_cols_dot
    e = el.of_body[el.parent[att]]
    n, first = el.size[e], el.column[e]
    for k in range(n):
        s = att_cols[att, k]
        sd = att_cols_dot[att, k]
        _cross(vel[3:], s[:3], tmp)
        _cross(s[3:], vel[:3], tmp2)
        for a in range(3):
            sd[a] = tmp[a] - tmp2[a]
        _cross(vel[3:], s[3:], tmp)
        for a in range(3):
            sd[3 + a] = tmp[a]
        for a in range(6):
            vel[a] += s[a] * v[first + k]


@step_kernel
def _move_elastic(
    index: np.ndarray, data: np.ndarray, work: np.ndarray, i: int, v: np.ndarray, acc: np.ndarray, rot: np.ndarray,
    omega: np.ndarray, lin: np.ndarray, tmp: np.ndarray, u: np.ndarray, out: np.ndarray,
) -> int:  # fmt: skip
    """Body ``i``'s part of :func:`move` from the flexible bodies (``index``, ``data``, ``work``: see
    :func:`_frames`; the others as in the Workspace): the attachments' columns on its path into the sum ``acc`` of
    v_c dS_c/dt; for a flexible body, the elastic part R Ct xi_dot / m of its centre of mass's velocity into ``lin``
    and w_b x Ct xi_dot / m (body axes; Bdot v on its own mode columns is R times it) into ``out`` (3,). Returns the
    body's elastic index (-1 for a rigid body). (Not inlined: see :func:`_ride_attachment`.)"""
    el = elastic_views(index, data)
    on_path, of_body, att_parent, size, column, mass, coupling = el.on_path, el.of_body, el.parent, el.size, \
        el.column, el.mass, el.coupling  # fmt: skip
    att_cols_dot = elastic_work(index, work).att_cols_dot
    for att in range(att_parent.shape[0]):
        if on_path[i, att] == 0.0:
            continue
        e = of_body[att_parent[att]]
        first = column[e]
        for k in range(size[e]):
            for a in range(6):
                acc[a] += att_cols_dot[att, k, a] * v[first + k]
    e = of_body[i]
    if e >= 0:
        first = column[e]
        m = mass[e]
        for a in range(3):
            total = 0.0
            for k in range(size[e]):
                total += (coupling[e, a, k] / m) * v[first + k]
            u[a] = total
        _rotate(rot[i], u, tmp)
        for a in range(3):
            lin[i, a] += tmp[a]
        _cross(omega[i], u, out)
    return e


@inline_kernel
def _bdot_column(
    w: Workspace, i: int, s: np.ndarray, sd: np.ndarray, bdot: np.ndarray, r0: int, c: int, tmp: np.ndarray,
    tmp2: np.ndarray, rts: np.ndarray, rtsd: np.ndarray,
) -> None:  # fmt: skip
    """Body ``i``'s six rows (from row ``r0``) of Bdot's column ``c`` (``w``: the kinematics of :func:`place` and
    :func:`move`) from the column's world twist S = ``s`` (6,) and its rate dS/dt = ``sd`` (6,):
    [[0, -hat(p_dot)], [0, -hat(w_b) R']] S + [[I, -hat(p)], [0, R']] dS/dt, for a joint's column and an elastic
    attachment's alike. ``tmp``, ``tmp2``, ``rts``, ``rtsd``: scratch (3,)."""
    r = w.rot[i]
    _cross(w.lin[i], s[3:], tmp)
    _cross(w.pos[i], sd[3:], tmp2)
    for a in range(3):
        bdot[r0 + a, c] = -tmp[a] + sd[a] - tmp2[a]
    for a in range(3):
        rts[a] = r[0, a] * s[3] + r[1, a] * s[4] + r[2, a] * s[5]
        rtsd[a] = r[0, a] * sd[3] + r[1, a] * sd[4] + r[2, a] * sd[5]
    _cross(w.omega[i], rts, tmp)
    for a in range(3):
        bdot[r0 + 3 + a, c] = -tmp[a] + rtsd[a]


@kernel
def _bdot(p: Plant, w: Workspace) -> np.ndarray:
    """Bdot (n_cart, nv) from the kinematics in ``w`` (:func:`place` and :func:`move`): column by column
    (:func:`_bdot_column`; zero on the modes' rows)."""
    n = p.com0.shape[0]
    nv = p.twists.shape[0]
    bdot = np.zeros((p.cart_body.shape[0], nv))
    tmp, tmp2 = np.zeros(3), np.zeros(3)
    rts, rtsd = np.zeros(3), np.zeros(3)
    for i in range(n):
        r0 = p.cart_start[i]
        for c in range(nv):
            if p.chain[i, c] == 0.0:
                continue
            _bdot_column(w, i, w.cols[:, c], w.cols_dot[:, c], bdot, r0, c, tmp, tmp2, rts, rtsd)
        if p.n_elastic == 0:
            continue
        el = elastic_views(p.elastic_index, p.elastic_data)
        ew = elastic_work(p.elastic_index, w.elastic)
        for att in range(el.child.shape[0]):  # the columns of elastic attachments on the body's path
            if el.on_path[i, att] == 0.0:
                continue
            e = el.of_body[el.parent[att]]
            for k in range(el.size[e]):
                c = el.column[e] + k
                _bdot_column(w, i, ew.att_cols[att, k], ew.att_cols_dot[att, k], bdot, r0, c, tmp, tmp2, rts, rtsd)
        e = el.of_body[i]
        if e >= 0:  # the body's own mode columns: R hat(w_b) Ct / m
            for k in range(el.size[e]):
                for a in range(3):
                    rts[a] = el.coupling[e, a, k] / el.mass[e]
                _cross(w.omega[i], rts, tmp)
                _rotate(w.rot[i], tmp, tmp2)
                for a in range(3):
                    bdot[r0 + a, el.column[e] + k] = tmp2[a]
    return bdot


@kernel
def kinematics(p: Plant, q: np.ndarray, v: np.ndarray):
    """Rotations (n, 3, 3), CoM positions (n, 3), B (n_cart, nv), Bdot (n_cart, nv) and body angular velocities
    (n, 3)."""
    w = workspace(p)
    elastic = p.n_elastic > 0
    place(p, q, w, elastic)
    move(p, v, w, elastic)
    return w.rot, w.pos, w.b, _bdot(p, w), w.omega


@kernel
def world_jacobian(p: Plant, rot: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Bw: rows per body (CoM velocity, world angular velocity, the modes' rates) from B (rows CoM velocity, body
    angular velocity, the modes' rates)."""
    out = b.copy()
    nv = b.shape[1]
    for i in range(rot.shape[0]):
        r = rot[i]
        r3 = p.cart_start[i] + 3
        for a in range(3):
            for c in range(nv):
                out[r3 + a, c] = r[a, 0] * b[r3, c] + r[a, 1] * b[r3 + 1, c] + r[a, 2] * b[r3 + 2, c]
    return out


@inline_kernel
def _hydro_jacobian(
    hi: np.ndarray, cart_body: np.ndarray, cart_axis: np.ndarray, cart_start: np.ndarray, rot: np.ndarray,
    b: np.ndarray, bh: np.ndarray,
) -> None:  # fmt: skip
    """The hydro DOFs' rows of Bw into ``bh`` (world axes: rotational rows are R times B's body-axis rows; the
    translations' and the modes' rows are B's; ``hi`` the Plant's ``hydro_index``, the others as in the Plant and
    the Workspace)."""
    nv = b.shape[1]
    for k in range(hi.shape[0]):
        i = cart_body[hi[k]]
        a = cart_axis[hi[k]]
        if a < 3 or a >= 6:
            for c in range(nv):
                bh[k, c] = b[hi[k], c]
        else:
            r = rot[i]
            r3 = cart_start[i] + 3
            for c in range(nv):
                bh[k, c] = r[a - 3, 0] * b[r3, c] + r[a - 3, 1] * b[r3 + 1, c] + r[a - 3, 2] * b[r3 + 2, c]


@inline_kernel
def _end_point(rot: np.ndarray, pos: np.ndarray, body: int, point: np.ndarray) -> tuple[float, float, float]:
    """World position [m] of an actuator's end: ``point`` in the axes of ``body`` from its centre of mass, or the
    world point for the ground (body -1)."""
    if body < 0:
        return point[0], point[1], point[2]
    r = rot[body]
    return (
        pos[body, 0] + r[0, 0] * point[0] + r[0, 1] * point[1] + r[0, 2] * point[2],
        pos[body, 1] + r[1, 0] * point[0] + r[1, 1] * point[1] + r[1, 2] * point[2],
        pos[body, 2] + r[2, 0] * point[0] + r[2, 1] * point[1] + r[2, 2] * point[2],
    )


@inline_kernel
def _pto_strokes_into(
    kind: np.ndarray, coordinate: np.ndarray, velocity: np.ndarray, body_a: np.ndarray, body_b: np.ndarray,
    point_a: np.ndarray, point_b: np.ndarray, cart_start: np.ndarray, q: np.ndarray, rot: np.ndarray, pos: np.ndarray,
    b: np.ndarray, x: np.ndarray, gmat: np.ndarray,
) -> None:  # fmt: skip
    """PTO strokes (n_pto,) [m or rad] into ``x`` and transmissions (n_pto, nv) into ``gmat`` (x_dot = G v), from
    the Plant's ``pto_kind``, ``pto_coordinate``, ``pto_velocity``, ``pto_body_a``, ``pto_body_b``,
    ``pto_point_a``, ``pto_point_b`` (``kind`` ... ``point_b``) and ``cart_start``.

    An actuator's rate is n . (J_a - J_b) v with n the unit vector from end b to end a and J_e the Jacobian of
    end e's velocity: per column, the body's CoM velocity column minus R (point x its body-axis angular velocity
    column)."""
    nv = b.shape[1]
    for k in range(kind.shape[0]):
        if kind[k] == PtoKind.JOINT:
            x[k] = q[coordinate[k]]
            for c in range(nv):
                gmat[k, c] = 0.0
            gmat[k, velocity[k]] = 1.0
        else:
            a0, a1, a2 = _end_point(rot, pos, body_a[k], point_a[k])
            b0, b1, b2 = _end_point(rot, pos, body_b[k], point_b[k])
            d0, d1, d2 = a0 - b0, a1 - b1, a2 - b2
            length = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
            x[k] = length
            n0, n1, n2 = d0 / length, d1 / length, d2 / length
            for c in range(nv):
                g = 0.0
                for e in range(2):
                    body = body_a[k] if e == 0 else body_b[k]
                    if body < 0:
                        continue
                    point = point_a[k] if e == 0 else point_b[k]
                    r = rot[body]
                    r0 = cart_start[body]
                    w0, w1, w2 = b[r0 + 3, c], b[r0 + 4, c], b[r0 + 5, c]
                    y0 = point[1] * w2 - point[2] * w1
                    y1 = point[2] * w0 - point[0] * w2
                    y2 = point[0] * w1 - point[1] * w0
                    j0 = b[r0, c] - (r[0, 0] * y0 + r[0, 1] * y1 + r[0, 2] * y2)
                    j1 = b[r0 + 1, c] - (r[1, 0] * y0 + r[1, 1] * y1 + r[1, 2] * y2)
                    j2 = b[r0 + 2, c] - (r[2, 0] * y0 + r[2, 1] * y1 + r[2, 2] * y2)
                    sign = 1.0 if e == 0 else -1.0
                    g += sign * (n0 * j0 + n1 * j1 + n2 * j2)
                gmat[k, c] = g


@kernel
def pto_strokes(p: Plant, q: np.ndarray, rot: np.ndarray, pos: np.ndarray, b: np.ndarray):
    """PTO strokes x (n_pto,) [m or rad] and transmissions G (n_pto, nv) with x_dot = G v."""
    n_pto = p.pto_kind.shape[0]
    x = np.zeros(n_pto)
    gmat = np.zeros((n_pto, b.shape[1]))
    _pto_strokes_into(
        p.pto_kind, p.pto_coordinate, p.pto_velocity, p.pto_body_a, p.pto_body_b, p.pto_point_a, p.pto_point_b,
        p.cart_start, q, rot, pos, b, x, gmat,
    )  # fmt: skip
    if p.n_elastic > 0:
        work = np.zeros(elastic_work_size(p.elastic_index))
        _elastic_pto_ends(
            p.elastic_index, p.elastic_data, work, q, rot, pos, b, p.com0, p.cart_start, p.pto_body_a, p.pto_body_b,
            p.pto_point_a, p.pto_point_b, x, gmat, np.zeros((0, 2, 3)),
        )  # fmt: skip
    return x, gmat


@kernel
def elastic_pto_end_points(p: Plant, q: np.ndarray, rot: np.ndarray, pos: np.ndarray, b: np.ndarray) -> np.ndarray:
    """World points (n_pto, 2, 3) [m] of both ends of every actuator with an end on a flexible body, that end on its
    node (:func:`_elastic_pto_ends`); zeros for the other PTOs."""
    n_pto = p.pto_kind.shape[0]
    where = np.zeros((n_pto, 2, 3))
    if p.n_elastic > 0:
        work = np.zeros(elastic_work_size(p.elastic_index))
        _elastic_pto_ends(
            p.elastic_index, p.elastic_data, work, q, rot, pos, b, p.com0, p.cart_start, p.pto_body_a, p.pto_body_b,
            p.pto_point_a, p.pto_point_b, np.zeros(n_pto), np.zeros((n_pto, b.shape[1])), where,
        )  # fmt: skip
    return where


@step_kernel
def _elastic_pto_ends(
    index: np.ndarray, data: np.ndarray, work: np.ndarray, q: np.ndarray, rot: np.ndarray, pos: np.ndarray,
    b: np.ndarray, com0: np.ndarray, cart_start: np.ndarray, body_a: np.ndarray, body_b: np.ndarray,
    point_a: np.ndarray, point_b: np.ndarray, x: np.ndarray, gmat: np.ndarray, where: np.ndarray,
) -> None:  # fmt: skip
    """The strokes and transmissions of the actuators with an end on a flexible body, over
    :func:`_pto_strokes_into`'s (``index``, ``data``, ``work``: see :func:`_frames`; the others as in the Plant),
    and their ends' world points into ``where`` (n_pto, 2, 3) when it has a row per PTO (none: shape (0, 2, 3)).

    Such an end rides on its attachment (``wecss.multibody``: ``KinematicState.point``): at
    G_i prod_k exp(psi_k xi_k) X0 (X0 its reference point, G_i its body's frame: t_i = p_i - R_i c_i(xi)), with
    the velocity Jacobian v_c + w_c x (X - p_i) on the columns that move the body's frame (B's rows: the centre of
    mass's velocity v_c, R times the body-axis angular velocity w_c) and u_k + w_k x X on the body's own mode
    columns ((u_k, w_k) = Ad(G) psi_k, the attachment's world twists). An end on a rigid body: as in
    :func:`_pto_strokes_into`."""
    el = elastic_views(index, data)
    ew = elastic_work(index, work)
    att_cols, scratch = ew.att_cols, ew.pto  # (views of the workspace: no allocation per call)
    nv = b.shape[1]
    ends = reshaped(scratch[0:6], (2, 3))
    arms = reshaped(scratch[6:12], (2, 3))
    r = reshaped(scratch[12:21], (3, 3))
    t = scratch[21:24]
    centre = scratch[24:27]
    tmp = scratch[27:30]
    tmp2 = scratch[30:33]
    t_step = scratch[33:36]
    r_step = reshaped(scratch[36:45], (3, 3))
    r_new = reshaped(scratch[45:54], (3, 3))
    for k in range(el.pto_end.shape[0]):
        if el.pto_end[k, 0] < 0 and el.pto_end[k, 1] < 0:
            continue
        for e in range(2):
            body = body_a[k] if e == 0 else body_b[k]
            point = point_a[k] if e == 0 else point_b[k]
            att = el.pto_end[k, e]
            if body < 0:
                for a in range(3):
                    ends[e, a] = point[a]
                continue
            if att < 0:  # a rigid body's point: R point from its centre of mass
                _rotate(rot[body], point, tmp)
                for a in range(3):
                    arms[e, a] = tmp[a]
                    ends[e, a] = pos[body, a] + tmp[a]
                continue
            _elastic_centre(index, data, com0, body, el.of_body[body], q, centre)
            _rotate(rot[body], centre, tmp)
            for a in range(3):
                t[a] = pos[body, a] - tmp[a]
                for c in range(3):
                    r[a, c] = rot[body, a, c]
            _ride_attachment(index, data, work, att, q, r, t, True, tmp, tmp2, t_step, r_step, r_new)
            for a in range(3):
                centre[a] = com0[body, a] + point[a]  # the reference point X0
            _rotate(r, centre, tmp)
            for a in range(3):
                ends[e, a] = tmp[a] + t[a]
                arms[e, a] = ends[e, a] - pos[body, a]
        if where.shape[0] > 0:
            for e in range(2):
                for a in range(3):
                    where[k, e, a] = ends[e, a]
        d0, d1, d2 = ends[0, 0] - ends[1, 0], ends[0, 1] - ends[1, 1], ends[0, 2] - ends[1, 2]
        length = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
        x[k] = length
        n0, n1, n2 = d0 / length, d1 / length, d2 / length
        for c in range(nv):
            gmat[k, c] = 0.0
        for e in range(2):
            body = body_a[k] if e == 0 else body_b[k]
            if body < 0:
                continue
            sign = 1.0 if e == 0 else -1.0
            att = el.pto_end[k, e]
            fe = el.of_body[body] if att >= 0 else -1
            own0 = el.column[fe] if fe >= 0 else 0
            own1 = own0 + el.size[fe] if fe >= 0 else 0
            rb = rot[body]
            r0 = cart_start[body]
            for c in range(nv):
                if own0 <= c < own1:  # the body's own mode: the attachment's world twist at the end
                    s = att_cols[att, c - own0]
                    j0 = s[0] + s[4] * ends[e, 2] - s[5] * ends[e, 1]
                    j1 = s[1] + s[5] * ends[e, 0] - s[3] * ends[e, 2]
                    j2 = s[2] + s[3] * ends[e, 1] - s[4] * ends[e, 0]
                else:  # the body's frame: its centre of mass's velocity and (R w) x arm
                    w0, w1, w2 = b[r0 + 3, c], b[r0 + 4, c], b[r0 + 5, c]
                    o0 = rb[0, 0] * w0 + rb[0, 1] * w1 + rb[0, 2] * w2
                    o1 = rb[1, 0] * w0 + rb[1, 1] * w1 + rb[1, 2] * w2
                    o2 = rb[2, 0] * w0 + rb[2, 1] * w1 + rb[2, 2] * w2
                    j0 = b[r0, c] + o1 * arms[e, 2] - o2 * arms[e, 1]
                    j1 = b[r0 + 1, c] + o2 * arms[e, 0] - o0 * arms[e, 2]
                    j2 = b[r0 + 2, c] + o0 * arms[e, 1] - o1 * arms[e, 0]
                gmat[k, c] += sign * (n0 * j0 + n1 * j1 + n2 * j2)


@inline_kernel
def _hydrostatic_into(
    hi: np.ndarray, cart_body: np.ndarray, cart_axis: np.ndarray, cart_coordinate: np.ndarray, com0: np.ndarray,
    static_force: np.ndarray, hydrostatic_stiffness: np.ndarray, modes: np.ndarray, mode_stiffness: np.ndarray,
    q: np.ndarray, rot: np.ndarray, pos: np.ndarray, disp: np.ndarray, restoring: np.ndarray, rv: np.ndarray,
    out: np.ndarray, elastic: bool, el_index: np.ndarray, el_data: np.ndarray, el_work: np.ndarray,
) -> None:  # fmt: skip
    """Gravity, buoyancy, the linear hydrostatic and mooring restoring force (world axes) and the modes' structural
    stiffness (a flexible body's geometric stiffening with it) into ``out`` (n_cart,) [N, N m, J] at configuration
    ``q`` (``hi`` the Plant's ``hydro_index``, ``modes`` its ``mode_row``, the others as in the Plant; ``disp`` and
    ``restoring`` (n_h,) and ``rv`` (3,) are scratch; ``elastic``, ``el_index``, ``el_data``, ``el_work``: see
    :func:`_frames`, ``el_work`` scratch too)."""
    for k in range(hi.shape[0]):
        i = cart_body[hi[k]]
        a = cart_axis[hi[k]]
        if a < 3:
            disp[k] = pos[i, a] - com0[i, a]
        elif a < 6:
            so3_log_into(rot[i], rv)
            disp[k] = rv[a - 3]
        else:  # a generalised mode: its coordinate
            disp[k] = q[cart_coordinate[hi[k]]]
    for k in range(out.shape[0]):
        out[k] = static_force[k]
    matvec(hydrostatic_stiffness, disp, restoring)
    for k in range(hi.shape[0]):
        out[hi[k]] -= restoring[k]
    for k in range(modes.shape[0]):  # the modes' structural stiffness, -K xi
        s = 0.0
        for j in range(modes.shape[0]):
            s += mode_stiffness[k, j] * q[cart_coordinate[modes[j]]]
        out[modes[k]] -= s
    if elastic:
        _geometric_into(el_index, el_data, el_work, q, out)


@step_kernel
def _geometric_into(index: np.ndarray, data: np.ndarray, work: np.ndarray, q: np.ndarray, out: np.ndarray) -> None:
    """The flexible bodies' geometric stiffening -dU3/dxi, U3 = 1/2 sum G_mkl xi_m xi_k xi_l, added to their mode
    rows of ``out``: -sum_kl H_jkl xi_k xi_l on mode j's row with the packed force tensor H (``ElasticArrays``;
    ``index``, ``data``: the plant's ``elastic_index``, ``elastic_data``, ``work`` the Workspace's ``elastic``;
    not inlined: see :func:`_ride_attachment`). The products xi_k xi_l are formed once, so that each row is one
    contiguous dot product of H_j's nm^2 entries with them (vectorised; about 3 times faster than a sum of nm
    matrix-vector rows for 21 modes)."""
    el = elastic_views(index, data)
    size, coordinate, row, geometric = el.size, el.coordinate, el.row, el.geometric
    pair = elastic_work(index, work).pair
    nm = geometric.shape[1]
    for e in range(size.shape[0]):
        first = coordinate[e]
        r6 = row[e] + 6
        n_e = size[e]
        for k in range(nm):  # xi_k xi_l (zero beyond the body's own modes: H's padding is not read)
            xk = q[first + k] if k < n_e else 0.0
            for m in range(nm):
                pair[k * nm + m] = xk * q[first + m] if m < n_e else 0.0
        h = reshaped(geometric[e], (nm, nm * nm))  # (a view)
        for j in range(n_e):
            h_j = h[j]
            s = 0.0
            for km in range(nm * nm):
                s += h_j[km] * pair[km]
            out[r6 + j] -= s


@kernel
def hydrostatic_force(p: Plant, q: np.ndarray, rot: np.ndarray, pos: np.ndarray) -> np.ndarray:
    """Gravity, buoyancy and linear hydrostatic restoring force, world axes, and the modes' structural stiffness
    (n_cart,) [N, N m, J] at configuration ``q`` (with its frames ``rot``, ``pos``)."""
    n_h = p.hydro_index.shape[0]
    out = np.empty(p.static_force.shape[0])
    work = np.zeros(elastic_work_size(p.elastic_index))
    _hydrostatic_into(
        p.hydro_index, p.cart_body, p.cart_axis, p.cart_coordinate, p.com0, p.static_force, p.hydrostatic_stiffness,
        p.mode_row, p.mode_stiffness, q, rot, pos, np.empty(n_h), np.empty(n_h), np.empty(3), out, p.n_elastic > 0,
        p.elastic_index, p.elastic_data, work,
    )  # fmt: skip
    return out


@inline_kernel
def end_stop(p: Plant, k: int, x: float, xdot: float) -> float:
    """Force of PTO k's end stop [N or N m] at stroke ``x`` and rate ``xdot``: a spring on the stroke beyond the
    limit and a damper while engaged; zero inside the limit and for a PTO without an end stop."""
    return _end_stop(p.pto_stroke_limit[k], p.pto_stop_stiffness[k], p.pto_stop_damping[k], x, xdot)


@inline_kernel
def _end_stop(limit: float, stiffness: float, damping: float, x: float, xdot: float) -> float:
    """:func:`end_stop` from the PTO's stroke limit [m or rad], the stop's stiffness [N/m or N m/rad] and damping
    [N s/m or N m s/rad]."""
    excess = abs(x) - limit
    if excess > 0.0 and stiffness > 0.0:
        return -np.sign(x) * stiffness * excess - damping * xdot
    return 0.0


def end_stop_force(p: Plant, x: np.ndarray, xdot: np.ndarray) -> np.ndarray:
    """Forces of every PTO's end stop (n_pto,) [N or N m] (see :func:`end_stop`)."""
    return np.array([end_stop(p, k, float(x[k]), float(xdot[k])) for k in range(x.shape[0])])


@inline_kernel
def configure(p: Plant, q: np.ndarray, hydro_force: np.ndarray, t: float, w: Workspace) -> bool:
    """Everything of the equations of motion (Eq. 46) that depends on the configuration ``q`` and the time ``t`` [s]
    alone, into ``w``: :func:`configure_core`, then the body-exact pressure forces when the plant has them
    (``wecss.compiled._body_exact``: a call of its own, which numba cannot inline; the mesh kernels are large and
    an opaque call inside ``configure_core`` would keep numba from pruning its reference counts). Returns False
    when M* is not positive definite (a degenerate configuration).

    A plant with flexible bodies (``Plant.n_elastic`` > 0) goes through :func:`configure_elastic` instead: the same
    kernel compiled with their code, which the rigid one is compiled without (a constant flag through the inlined
    helpers; their loops would keep numba from pruning the rigid kernel's reference counts)."""
    if p.n_elastic == 0:
        ok = configure_core(p, q, hydro_force, t, w)
    else:
        ok = configure_elastic(p, q, hydro_force, t, w)
    if not ok:
        return False
    if p.pressure.owner.shape[0] > 0:
        configure_pressure(p.pressure, t, w.rot, w.pos, p.com0, p.cart_start, w.b, w.terms, w.gen_config)
    return True


@step_kernel
def configure_core(p: Plant, q: np.ndarray, hydro_force: np.ndarray, t: float, w: Workspace) -> bool:
    """Everything of the equations of motion (Eq. 46) that depends on the configuration ``q`` and the time ``t`` [s]
    alone but the body-exact pressure forces, into ``w``: the kinematics, M* = B'(M + A_inf)B and its Cholesky
    factor, the generalised force of gravity, buoyancy, hydrostatics, the modes' structural stiffness,
    ``hydro_force`` (n_h,) [N, N m] (excitation plus the memory force fixed by the past, world axes) and the
    hydrodynamic terms of the scene that depend on the configuration and the waves at ``t``
    (``wecss.compiled._viscous``), the PTO strokes and transmissions. Within a step of a predictor-corrector only
    the velocity changes: :func:`respond` then reuses all of this.

    Returns False when M* is not positive definite (a degenerate configuration). For a plant without flexible
    bodies (:func:`configure_elastic` for the others).
    """
    return _configure_body(p, q, hydro_force, t, w, False)


@step_kernel
def configure_elastic(p: Plant, q: np.ndarray, hydro_force: np.ndarray, t: float, w: Workspace) -> bool:
    """:func:`configure_core` for a plant with flexible bodies: their centres of mass, attachments and mode
    columns in the kinematics, their geometric stiffening, and M* from their M(xi)."""
    return _configure_body(p, q, hydro_force, t, w, True)


@inline_kernel
def _configure_body(
    p: Plant, q: np.ndarray, hydro_force: np.ndarray, t: float, w: Workspace, elastic: bool
) -> bool:  # fmt: skip
    """The body of :func:`configure_core` (``elastic`` False) and :func:`configure_elastic` (True). Every array of
    the tuples it needs is bound first and the tuples are not read after (see :func:`_respond_body`)."""
    com0, cart_start, cart_body, cart_axis, cart_column = p.com0, p.cart_start, p.cart_body, p.cart_axis, \
        p.cart_column  # fmt: skip
    hi, act, active_mass, pto_rest, viscous = p.hydro_index, p.active, p.active_mass, p.pto_rest, p.viscous
    el_index, el_data, el_work = p.elastic_index, p.elastic_data, w.elastic
    pto_body_a, pto_body_b, pto_point_a, pto_point_b = p.pto_body_a, p.pto_body_b, p.pto_point_a, p.pto_point_b
    rot, pos, b, bh, force, gen_config, stroke, gmat, bat = w.rot, w.pos, w.b, w.bh, w.force, w.gen_config, \
        w.stroke, w.gmat, w.bat  # fmt: skip
    mass_work, mass, factor, tmp, r_step, terms = w.mass_work, w.mass, w.factor, w.vec, w.r_step, w.terms
    cart_coordinate, static_force, stiffness = p.cart_coordinate, p.static_force, p.hydrostatic_stiffness
    mode_row, mode_stiffness, pto_kind, pto_coordinate, pto_velocity = p.mode_row, p.mode_stiffness, p.pto_kind, \
        p.pto_coordinate, p.pto_velocity  # fmt: skip
    disp, restoring = w.disp, w.restoring
    _place(
        p.order, p.parent, p.col_start, p.q_start, p.n_cols, p.free, p.twists, com0, p.chain, cart_start,
        mode_row, cart_column, q, rot, w.trans, pos, w.cols, b, tmp, w.vec2, w.t_step, r_step, w.r_new, elastic,
        el_index, el_data, el_work,
    )  # fmt: skip
    _hydro_jacobian(hi, cart_body, cart_axis, cart_start, rot, b, bh)
    # world loads: gravity, buoyancy, hydrostatics and the given hydro force; through Bw, that is B with the
    # moments in body axes
    _hydrostatic_into(
        hi, cart_body, cart_axis, cart_coordinate, com0, static_force, stiffness, mode_row, mode_stiffness, q, rot,
        pos, disp, restoring, tmp, force, elastic, el_index, el_data, el_work,
    )  # fmt: skip
    for k in range(hi.shape[0]):
        force[hi[k]] += hydro_force[k]
    configure_viscous(viscous, t, rot, pos, cart_start, terms, force)
    for i in range(com0.shape[0]):
        r3 = cart_start[i] + 3
        _rotate(rot[i].T, force[r3 : r3 + 3], tmp)
        for a in range(3):
            force[r3 + a] = tmp[a]
    for c in range(gen_config.shape[0]):
        gen_config[c] = 0.0
    matvec_t_add(b, force, gen_config)
    _pto_strokes_into(
        pto_kind, pto_coordinate, pto_velocity, pto_body_a, pto_body_b, pto_point_a, pto_point_b, cart_start, q, rot,
        pos, b, stroke, gmat,
    )  # fmt: skip
    if elastic:  # an actuator's end on a flexible body rides on its node
        _elastic_pto_ends(
            el_index, el_data, el_work, q, rot, pos, b, com0, cart_start, pto_body_a, pto_body_b, pto_point_a,
            pto_point_b, stroke, gmat, reshaped(el_work[0:0], (0, 2, 3)),
        )  # fmt: skip
    for k in range(stroke.shape[0]):
        stroke[k] -= pto_rest[k]
    for k in range(act.shape[0]):  # only the Cartesian rows that can move (x, z and pitch of a planar device)
        for c in range(bat.shape[0]):
            bat[c, k] = b[act[k], c]
    if not elastic:
        # last, and a kernel of its own: inlined here, its loops keep numba from pruning the reference counts of
        # the tuples' arrays (measured, not understood); a call as the last statement costs only its own
        # arguments' counts
        return _factor_mass(bat, active_mass, mass_work, mass, factor)
    # flexible bodies: M(xi) in place of M(0)
    return _elastic_mass(
        el_index, el_data, el_work, q, active_mass, b, act, cart_axis, cart_column, mass_work, mass, factor, tmp,
        r_step,
    )  # fmt: skip


@step_kernel
def _elastic_mass(
    index: np.ndarray, data: np.ndarray, work: np.ndarray, q: np.ndarray, plant_active_mass: np.ndarray,
    b_rows: np.ndarray, act: np.ndarray, cart_axis: np.ndarray, cart_column: np.ndarray, mass_work: np.ndarray,
    mass_out: np.ndarray, factor: np.ndarray, sv: np.ndarray, pm: np.ndarray,
) -> bool:  # fmt: skip
    """Each flexible body's M(xi) and dM/dxi about its instantaneous centre of mass (``ElasticBody.relative_mass``)
    into ``ElasticWork.mass``, ``dmass`` (their rotation rows), and into ``ElasticWork.active_mass``:
    ``plant_active_mass`` with M(xi) - M(0) added on their active rotation rows and columns; then M* and its
    factor from it (:func:`_modal_congruence` and its Cholesky factor: False when M* is not positive definite).
    ``index``, ``data``, ``work``: see :func:`_frames`; ``act``: the plant's ``active``, the others as in the Plant
    and the Workspace (``b_rows``: its B); ``sv`` (3,) and ``pm`` (3, 3) are scratch; not inlined: see
    :func:`_ride_attachment`."""
    el = elastic_views(index, data)
    size, coordinate, mass, first_moment, coupling, rotational = el.size, el.coordinate, el.mass, el.first_moment, \
        el.coupling, el.rotational  # fmt: skip
    second_moment, inertia_first, inertia_second, gyroscopic = el.second_moment, el.inertia_first, \
        el.inertia_second, el.gyroscopic  # fmt: skip
    undeformed, active_rows = el.undeformed, el.active
    ew = elastic_work(index, work)
    active, el_mass, el_dmass = ew.active_mass, ew.mass, ew.dmass
    for e in range(size.shape[0]):
        n_e = size[e]
        first = coordinate[e]
        m = mass[e]
        ct = coupling[e]
        out = el_mass[e]
        d = el_dmass[e]  # the rotation rows of dM/dxi_k (ElasticWork)
        xi = q[first : first + n_e]
        for a in range(3):  # s = s0 + Ct xi
            total = first_moment[e, a]
            for k in range(n_e):
                total += ct[a, k] * q[first + k]
            sv[a] = total
            for b in range(3):  # out[:3, :3] gathers P = P0 + sum_k xi_k (P1s_k + 1/2 sum_j xi_j P2s_kj) first
                out[a, b] = second_moment[e, a, b]
        for k in range(n_e):
            # dP_k = P1s_k + sum_j xi_j P2s_kj (P1s_k = P1_k + P1_k', P2s_kj = P2_kj + P2_jk: the packed invariants)
            for a in range(3):
                for b in range(3):
                    p2_kab = inertia_second[e, k, a, b]  # (nm,) over j: a view, vectorised
                    total = inertia_first[e, k, a, b]
                    for j in range(n_e):
                        total += p2_kab[j] * xi[j]
                    pm[a, b] = total
            xk = q[first + k]
            c0, c1, c2 = ct[0, k], ct[1, k], ct[2, k]
            sc = sv[0] * c0 + sv[1] * c1 + sv[2] * c2
            trace = pm[0, 0] + pm[1, 1] + pm[2, 2]
            for a in range(3):
                ca = c0 if a == 0 else (c1 if a == 1 else c2)
                sa = sv[a]
                for b in range(3):
                    out[a, b] += 0.5 * xk * (inertia_first[e, k, a, b] + pm[a, b])
                    eye = 1.0 if a == b else 0.0
                    cb = c0 if b == 0 else (c1 if b == 1 else c2)
                    d[k, a, b] = trace * eye - pm[a, b] - (2.0 * sc * eye - ca * sv[b] - sa * cb) / m
            for j in range(n_e):  # dM/dxi_k's rotation-mode block: G_k' - c x Ct_j / m
                x0 = c1 * ct[2, j] - c2 * ct[1, j]
                x1 = c2 * ct[0, j] - c0 * ct[2, j]
                x2 = c0 * ct[1, j] - c1 * ct[0, j]
                for a in range(3):
                    d[k, a, 3 + j] = gyroscopic[e, k, j, a] - (x0 if a == 0 else (x1 if a == 1 else x2)) / m
        ss = sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]
        trace = out[0, 0] + out[1, 1] + out[2, 2]
        for a in range(3):  # J_c = tr(P) I - P - (|s|^2 I - s s') / m, in place of P
            for b in range(3):
                eye = 1.0 if a == b else 0.0
                pm[a, b] = trace * eye - out[a, b] - (ss * eye - sv[a] * sv[b]) / m
        for a in range(3):
            for b in range(3):
                out[a, b] = 0.5 * (pm[a, b] + pm[b, a])
        for k in range(n_e):  # C_c = Cr + sum_j xi_j G_jk - s x Ct_k / m
            c0, c1, c2 = ct[0, k], ct[1, k], ct[2, k]
            x0 = sv[1] * c2 - sv[2] * c1
            x1 = sv[2] * c0 - sv[0] * c2
            x2 = sv[0] * c1 - sv[1] * c0
            for a in range(3):
                total = rotational[e, a, k]
                for j in range(n_e):
                    total += q[first + j] * gyroscopic[e, j, k, a]
                out[a, 3 + k] = total - (x0 if a == 0 else (x1 if a == 1 else x2)) / m
                out[3 + k, a] = out[a, 3 + k]
        # (the mode-mode block M_ee - Ct' Ct / m does not depend on xi: M(0)'s, in the plant's active_mass)
    for a in range(active.shape[0]):
        for b in range(active.shape[1]):
            active[a, b] = plant_active_mass[a, b]
    for e in range(size.shape[0]):
        for a in range(3 + size[e]):
            ka = active_rows[e, a]
            if ka < 0:
                continue
            for b in range(3 + size[e] if a < 3 else 3):  # the rotation rows and columns change with xi
                kb = active_rows[e, b]
                if kb >= 0:
                    active[ka, kb] += el_mass[e, a, b] - undeformed[e, a, b]
    product = reshaped(mass_work, (act.shape[0], b_rows.shape[1]))
    _modal_congruence(b_rows, act, cart_axis, cart_column, active, product, mass_out)
    return cholesky(mass_out, factor)


@inline_kernel
def _modal_congruence(
    b: np.ndarray, act: np.ndarray, cart_axis: np.ndarray, cart_column: np.ndarray, active_mass: np.ndarray,
    work: np.ndarray, out: np.ndarray,
) -> None:  # fmt: skip
    """M* = B'(M + A_inf)B into ``out`` (nv, nv), exactly symmetric, from B (``b``, (n_cart, nv)) and the
    active rows' (M + A_inf) (``active_mass``, (m, m), symmetric; ``act``, ``cart_axis``, ``cart_column`` as in the
    Plant), for a B whose rows of generalised modes (axis >= 6) are unit rows (``place``: the mode's rate is its
    own velocity): such a row adds one entry, not a product. ``work`` (m, nv) is scratch: (M + A_inf) B, row by
    row. (The same sums as :func:`~wecss.compiled._linalg.congruence` to round-off, a third of its products for
    the elastic NOTC arm: 21 of its 31 active rows are modes.)"""
    m = act.shape[0]
    nv = b.shape[1]
    for j in range(m):  # work = (M + A_inf) B: row j gathers the rows of B that its nonzero entries pick
        wj = work[j]
        for c in range(nv):
            wj[c] = 0.0
        for i in range(m):
            a = active_mass[j, i]
            if a == 0.0:
                continue
            row = act[i]
            if cart_axis[row] >= 6:
                wj[cart_column[row]] += a
            else:
                bi = b[row]
                for c in range(nv):
                    wj[c] += a * bi[c]
    for r in range(nv):
        for c in range(r + 1):
            out[r, c] = 0.0
    for j in range(m):  # out = B' work, its lower triangle: row j of B times row j of work
        row = act[j]
        wj = work[j]
        if cart_axis[row] >= 6:
            col = cart_column[row]
            for c in range(col + 1):
                out[col, c] += wj[c]
        else:
            bj = b[row]
            for r in range(nv):
                weight = bj[r]
                if weight != 0.0:
                    for c in range(r + 1):
                        out[r, c] += weight * wj[c]
    for r in range(nv):
        for c in range(r):
            out[c, r] = out[r, c]


@step_kernel
def _factor_mass(
    bat: np.ndarray, active_mass: np.ndarray, work: np.ndarray, mass: np.ndarray, factor: np.ndarray
) -> bool:
    """M* = B'(M + A_inf)B from ``bat`` (B's active rows, transposed) into ``mass`` and its lower Cholesky factor
    into ``factor`` (``work`` is scratch); False when M* is not positive definite."""
    congruence(bat, active_mass, work, mass)
    return cholesky(mass, factor)


@inline_kernel
def respond(p: Plant, v: np.ndarray, newest: np.ndarray, command: np.ndarray, w: Workspace) -> None:
    """Generalised accelerations at the velocities ``v`` and the configuration in ``w`` (:func:`configure`), into
    ``w.acc``, and the hydro velocities, PTO rates and forces: :func:`respond_core`, or :func:`respond_elastic` for
    a plant with flexible bodies (see :func:`configure`)."""
    if p.n_elastic == 0:
        respond_core(p, v, newest, command, w)
    else:
        respond_elastic(p, v, newest, command, w)


@step_kernel
def respond_core(p: Plant, v: np.ndarray, newest: np.ndarray, command: np.ndarray, w: Workspace) -> None:
    """:func:`respond` for a plant without flexible bodies."""
    _respond_body(p, v, newest, command, w, False)


@step_kernel
def respond_elastic(p: Plant, v: np.ndarray, newest: np.ndarray, command: np.ndarray, w: Workspace) -> None:
    """:func:`respond` for a plant with flexible bodies: their M(xi) and quadratic-velocity terms."""
    _respond_body(p, v, newest, command, w, True)


@inline_kernel
def _respond_body(
    p: Plant, v: np.ndarray, newest: np.ndarray, command: np.ndarray, w: Workspace, elastic: bool
) -> None:  # fmt: skip
    """Generalised accelerations at the velocities ``v`` and the configuration in ``w`` (:func:`configure`), into
    ``w.acc``; also the hydro velocities ``w.u``, the PTO rates ``w.xdot`` and forces ``w.f`` (the controller's,
    saturated at the force limit, plus the device spring; the end stops act besides).

    Parameters
    ----------
    newest : (n_h, n_h)
        Memory force per unit hydro velocity at this instant (added as ``newest @ u``).
    command : (n_pto,)
        Controller force held over the step [N or N m] (added to the device spring and the linear gains).
    """
    # Every array of the tuples this needs is bound first, and the tuples are not read after: numba counts a
    # reference up on each of their arrays on entry and down after their last read, and cannot prune those counts
    # across a call it does not inline (the flexible bodies' helpers), nor a tuple's array read in a loop.
    act, cart_axis, cart_body, cart_column, inertia = p.active, p.cart_axis, p.cart_body, p.cart_column, p.inertia
    active_mass, joint_damping, modes, mode_damping = p.active_mass, p.joint_damping, p.mode_row, p.mode_damping
    mooring_damping, viscous, cart_start = p.mooring_damping, p.viscous, p.cart_start
    pto_damping, pto_stiffness, pto_force_limit, pto_spring = p.pto_damping, p.pto_stiffness, p.pto_force_limit, \
        p.pto_spring  # fmt: skip
    stroke_limit, stop_stiffness, stop_damping = p.pto_stroke_limit, p.pto_stop_stiffness, p.pto_stop_damping
    el_index, el_data, el_work = p.elastic_index, p.elastic_data, w.elastic
    rot, pos, lin, bias, omega, inertial, gen, tmp, tmp2 = w.rot, w.pos, w.lin, w.bias, w.omega, w.inertial, w.gen, \
        w.vec, w.vec2  # fmt: skip
    gen_config, bat, u, load, bh, b, terms, factor, acc = w.gen_config, w.bat, w.u, w.load, w.bh, w.b, w.terms, \
        w.factor, w.acc  # fmt: skip
    stroke, xdot, f, gmat = w.stroke, w.xdot, w.f, w.gmat
    _velocities(
        p.order, p.parent, p.col_start, p.free, p.n_cols, p.chain, cart_start, v, rot, pos, w.cols, w.cols_dot,
        w.spatial, omega, lin, bias, w.partial, tmp, tmp2, w.t_step, elastic, el_index, el_data, el_work,
    )  # fmt: skip
    m = act.shape[0]
    # N* v = B' ((M + A_inf) Bdot v + D M B v); D M B v = omega_b x (J omega_b) on the rotational rows (none on the
    # rows of generalised modes); a flexible body's M(xi) and its quadratic-velocity vector instead
    if elastic:
        _elastic_inertial(
            el_index, el_data, el_work, act, bias, cart_axis, cart_body, inertia, omega, v, tmp, tmp2, inertial
        )
    for k in range(0 if elastic else m):
        s = 0.0
        for j in range(m):
            s += active_mass[k, j] * bias[act[j]]
        row = act[k]
        axis = cart_axis[row]
        if axis >= 3 and axis < 6:
            i = cart_body[row]
            _rotate(inertia[i], omega[i], tmp)
            _cross(omega[i], tmp, tmp2)
            s += tmp2[axis - 3]
        inertial[k] = -s
    for c in range(gen.shape[0]):
        gen[c] = gen_config[c]
    matvec_add(bat, inertial, gen)
    for c in range(gen.shape[0]):
        gen[c] -= joint_damping[c] * v[c]  # the joints' own losses
    for k in range(modes.shape[0]):  # the modes' structural damping, -C xi_dot
        s = 0.0
        for j in range(modes.shape[0]):
            s += mode_damping[k, j] * v[cart_column[modes[j]]]
        gen[cart_column[modes[k]]] -= s
    # the memory force of the newest hydro velocity, through Bw
    matvec(bh, v, u)
    matvec(newest, u, load)
    for i in range(mooring_damping.shape[0]):  # the moorings' dampers ((0, 0) without moorings: no work)
        s = 0.0
        for k in range(mooring_damping.shape[1]):
            s += mooring_damping[i, k] * u[k]
        load[i] -= s
    matvec_t_add(bh, load, gen)
    # the controller's force, saturated at the PTO's force limit, the device spring, and the end stops
    matvec(gmat, v, xdot)
    for k in range(stroke.shape[0]):
        x, rate = stroke[k], xdot[k]
        control = pto_control_force_kernel(command[k], pto_damping[k], pto_stiffness[k], x, rate)
        limit = pto_force_limit[k]
        f[k] = min(max(control, -limit), limit) - pto_spring[k] * x
        total = f[k] + _end_stop(stroke_limit[k], stop_stiffness[k], stop_damping[k], x, rate)
        for c in range(gen.shape[0]):
            gen[c] += gmat[k, c] * total
    respond_viscous(viscous, rot, lin, omega, b, cart_start, terms, gen)  # drag (none: no work)
    cholesky_solve(factor, gen, acc)


@step_kernel
def _elastic_inertial(
    index: np.ndarray, data: np.ndarray, work: np.ndarray, act: np.ndarray, bias: np.ndarray, cart_axis: np.ndarray,
    cart_body: np.ndarray, inertia: np.ndarray, omega: np.ndarray, v: np.ndarray, tmp: np.ndarray, tmp2: np.ndarray,
    inertial: np.ndarray,
) -> None:  # fmt: skip
    """:func:`respond`'s -((M + A_inf) Bdot v + H B v) on the active rows, into ``inertial``, for a plant with
    flexible bodies (``index``, ``data``, ``work``: see :func:`_frames`; the others as in the Plant and the
    Workspace): ``ElasticWork.active_mass`` holds their M(xi); on a rigid body's rotation rows H B v = w_b x J w_b,
    on a flexible body's rotation and mode rows its quadratic-velocity vector (into ``ElasticWork.quad``): with
    Y = (w_b, xi_dot), w_b x (M(xi) Y)[:3] (D M) plus Mdot Y = sum_k xi_dot_k dM/dxi_k Y, and -1/2 Y' dM/dxi_j Y on
    mode j's row (``wecss.multibody._dynamics``). (Not inlined: see :func:`_ride_attachment`.)"""
    el = elastic_views(index, data)
    of_body, body, size, column, row = el.of_body, el.body, el.size, el.column, el.row
    ew = elastic_work(index, work)
    active_mass, el_mass, el_dmass, y, my, quad = ew.active_mass, ew.mass, ew.dmass, ew.y, ew.my, ew.quad
    for e in range(body.shape[0]):
        i = body[e]
        n3 = 3 + size[e]
        first = column[e]
        for a in range(3):
            y[a] = omega[i, a]
        for k in range(size[e]):
            y[3 + k] = v[first + k]
        mass = el_mass[e]
        d = el_dmass[e]
        n_e = size[e]
        for a in range(3):
            total = 0.0
            for b in range(n3):
                total += mass[a, b] * y[b]
            my[a] = total
        _cross(y, my, tmp)  # (y[:3] is w_b)
        r3 = row[e] + 3
        # dM/dxi_k = [[dJ_k, dC_k], [dC_k', 0]] (its mode-mode block is zero): with u_k = dJ_k w_b and
        # c_k = dC_k xi_dot, Mdot Y = (sum_k xi_dot_k (u_k + c_k), sum_k xi_dot_k dC_k' w_b) and
        # Y' dM/dxi_k Y = w_b . (u_k + 2 c_k)
        for a in range(3):
            quad[r3 + a] = tmp[a]
        for i in range(n_e):
            quad[r3 + 3 + i] = 0.0
        for k in range(n_e):
            yk = y[3 + k]
            half = 0.0
            for a in range(3):
                u = d[k, a, 0] * y[0] + d[k, a, 1] * y[1] + d[k, a, 2] * y[2]
                c = 0.0
                for i in range(n_e):
                    c += d[k, a, 3 + i] * y[3 + i]
                quad[r3 + a] += yk * (u + c)
                half += y[a] * (u + 2.0 * c)
                wy = y[a] * yk
                for i in range(n_e):
                    quad[r3 + 3 + i] += wy * d[k, a, 3 + i]
            my[3 + k] = half
        for k in range(n_e):
            quad[r3 + 3 + k] -= 0.5 * my[3 + k]
    m = act.shape[0]
    for k in range(m):
        s = 0.0
        for j in range(m):
            s += active_mass[k, j] * bias[act[j]]
        r = act[k]
        axis = cart_axis[r]
        i = cart_body[r]
        if of_body[i] >= 0:
            if axis >= 3:
                s += quad[r]
        elif axis >= 3 and axis < 6:
            _rotate(inertia[i], omega[i], tmp)
            _cross(omega[i], tmp, tmp2)
            s += tmp2[axis - 3]
        inertial[k] = -s


@kernel
def accelerations(
    p: Plant,
    q: np.ndarray,
    v: np.ndarray,
    hydro_force: np.ndarray,
    newest: np.ndarray,
    pto_command: np.ndarray,
    t: float = 0.0,
):
    """Generalised accelerations of the MFM equations (Eq. 46) with all loads (:func:`configure` and
    :func:`respond` in a new workspace; the time loops call those two on their own workspace).

    Parameters
    ----------
    hydro_force : (n_h,)
        Excitation plus the radiation memory force fixed by the past, on the hydro DOFs, world axes [N, N m].
    newest : (n_h, n_h)
        Memory force per unit hydro velocity at this instant (added as ``newest @ u``).
    pto_command : (n_pto,)
        Controller force held over the step [N or N m] (added to the device spring and the linear gains).
    t : float
        Time [s] of the waves the scene's hydrodynamic terms see (default 0).

    Returns
    -------
    a : (nv,) accelerations (NaN where M* is not positive definite); u : (n_h,) hydro velocities; x, x_dot, f :
    (n_pto,) PTO stroke from rest, rate and force (the controller's, saturated at the force limit, plus the device
    spring; the end stops act besides); mass : (nv, nv) M*.
    """
    w = workspace(p)
    if configure(p, q, hydro_force, t, w):
        respond(p, v, newest, pto_command, w)
    else:
        w.acc[:] = np.nan
    return w.acc, w.u, w.stroke, w.xdot, w.f, w.mass


@kernel
def hydro_velocity(p: Plant, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Velocities of the hydro DOFs (world axes) [m/s, rad/s]."""
    w = workspace(p)
    place(p, q, w, p.n_elastic > 0)
    _hydro_jacobian(p.hydro_index, p.cart_body, p.cart_axis, p.cart_start, w.rot, w.b, w.bh)
    matvec(w.bh, v, w.u)
    return w.u


@inline_kernel
def integrate_configuration(p: Plant, q: np.ndarray, dv: np.ndarray) -> np.ndarray:
    """q moved by the velocity increment dv (free bases on SO(3) through their quaternion; joint and modal
    coordinates add). (Inlined, so that its callers do not pass the Plant through a call, whose reference counts
    cost about 1 us: see ``_jit.inline_kernel``; :func:`_integrate` takes the arrays it needs.)"""
    return _integrate(p.q_start, p.col_start, p.free, p.n_cols, p.mode_row, p.cart_coordinate, p.cart_column, q, dv)


@kernel
def _integrate(
    q_start: np.ndarray, col_start: np.ndarray, free: np.ndarray, n_cols: np.ndarray, mode_row: np.ndarray,
    cart_coordinate: np.ndarray, cart_column: np.ndarray, q: np.ndarray, dv: np.ndarray,
) -> np.ndarray:  # fmt: skip
    """:func:`integrate_configuration` from the Plant's arrays of the same names."""
    out = q.copy()
    for i in range(q_start.shape[0]):
        iq = q_start[i]
        iv = col_start[i]
        if free[i] == 1:
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
            for k in range(n_cols[i]):
                out[iq + k] += dv[iv + k]
    for k in range(mode_row.shape[0]):
        row = mode_row[k]
        out[cart_coordinate[row]] += dv[cart_column[row]]
    return out


@kernel
def configuration_rate(p: Plant, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """dq/dt: v for joint and modal coordinates; CoM velocity and quaternion rate for a free base."""
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
    for k in range(p.mode_row.shape[0]):
        row = p.mode_row[k]
        out[p.cart_coordinate[row]] = v[p.cart_column[row]]
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
    positions = np.zeros((n_t, n, 3))
    rotations = np.zeros((n_t, n, 3))
    w = workspace(p)
    order, parent, col_start, q_start, n_cols, free = p.order, p.parent, p.col_start, p.q_start, p.n_cols, p.free
    joint_twists, com0 = p.twists, p.com0
    rot, trans, pos, cols, vec, vec2, t_step, r_step, r_new = w.rot, w.trans, w.pos, w.cols, w.vec, w.vec2, \
        w.t_step, w.r_step, w.r_new  # fmt: skip
    elastic = p.n_elastic > 0
    el_index, el_data, el_work = p.elastic_index, p.elastic_data, w.elastic
    for t in range(n_t):  # the arrays, not the tuples, in the call (see _frames)
        _frames(
            order, parent, col_start, q_start, n_cols, free, joint_twists, com0, qs[t], rot, trans, pos, cols, vec,
            vec2, t_step, r_step, r_new, False, elastic, el_index, el_data, el_work,
        )  # fmt: skip
        for i in range(n):
            for a in range(3):
                positions[t, i, a] = pos[i, a]
            so3_log_into(rot[i], rotations[t, i])
    return positions, rotations
