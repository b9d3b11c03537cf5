"""Fixed-step integrators of the nonlinear MFM equations, as kernels over a chunk of steps.

Beeman predictor-corrector (M4 paper Eq. 52; Beeman 1976), with a velocity-dependent force:

    q_{n+1}   = q_n + h v_n + h^2/6 (4 a_n - a_{n-1})            (on SO(3) for a free base)
    v^p_{n+1} = v_n + h/2 (3 a_n - a_{n-1})                       predictor
    v^c_{n+1} = v_n + h/6 (2 a_{n+1} + 5 a_n - a_{n-1})            corrector, a_{n+1} = a(q_{n+1}, v^c_{n+1})

The corrector is iterated until the change of a_{n+1} is below ``tol`` relative to |a_{n+1}|. When it does
not contract (stiff PTO damping, h c / M large: for a linear damper the fixed point diverges exactly where
Beeman's scheme itself turns unstable, h c / M > 3) the step is taken instead by the A-stable implicit
trapezoidal rule, solved by Newton's method with a finite-difference Jacobian (second order, like Beeman); if that
fails too the step reports failure (never a silent result).

Classic RK4 on (q, v, z) with the state-space radiation states z (fourth order). Both kernels return a
status (:class:`LoopStatus`).
"""

from __future__ import annotations

from enum import IntEnum
from typing import NamedTuple

import numpy as np

from ..compiled import (
    Plant,
    RadiationArrays,
    Workspace,
    configuration_rate,
    configure,
    integrate_configuration,
    kernel,
    matvec,
    matvec_add,
    normalise_quaternions,
    respond,
    step_kernel,
)
from ._memory import block_history, memory_advance
from ._memory import memory_history as memory_history  # (the step-by-step history, for the tests)


class LoopStatus(IntEnum):
    """How a chunk of steps ended (numba returns the members)."""

    OK = 0
    NOT_FINITE = 1
    """The state became non-finite."""
    OUT_OF_BOUNDS = 2
    """A bounded coordinate (revolute angle) passed its bound."""
    CORRECTOR_FAILED = 3
    """The Beeman corrector (fixed point and Newton) did not converge."""
    STROKE_LIMIT = 4
    """A PTO stroke passed its limit where the PTO has no end stop."""


class Store(NamedTuple):
    """Where the integrators record a run: every ``every``-th step (0: none) into the saved rows from
    ``save_index[0]`` on, running sums over the steps from ``stats_start`` on into ``stats`` (absorbed power,
    stroke^2, count, stroke per PTO), [corrector evaluations, largest per step, Newton steps] into
    ``evaluations``, and per PTO into ``limits`` (4, n_pto): the steps with the force at its limit, the episodes
    of it (steps where it starts), the steps with the stroke beyond its limit (the end stop engaged), the episodes
    of that. The saved arrays ``a``, ``x``, ``xd``, ``f``, ``rad`` and ``exc`` may have a single row instead of one
    per saved step: a scratch row, overwritten, for what no output of the run reads. The columns of ``rad`` and
    ``exc`` are the hydro DOFs in ``hydro_order`` (translations first: each kind is then a view, no copy, in the
    result)."""

    every: int
    stats_start: int
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    x: np.ndarray
    xd: np.ndarray
    f: np.ndarray
    rad: np.ndarray
    exc: np.ndarray
    save_index: np.ndarray
    stats: np.ndarray
    evaluations: np.ndarray
    limits: np.ndarray
    limit_last: np.ndarray
    hydro_order: np.ndarray


class StepSettings(NamedTuple):
    """What stays fixed over a run's steps: the step ``h`` [s], the Beeman corrector's relative tolerance ``tol``
    and ``max_iterations``, and the coordinates ``bounded`` whose size may not pass ``angle_bound`` [rad]."""

    h: float
    tol: float
    max_iterations: int
    bounded: np.ndarray
    angle_bound: float


class LoopState(NamedTuple):
    """The state the integrators advance in place: configuration ``q``, velocities ``v``, accelerations ``acc``
    and those of the step before ``acc_prev`` (Beeman), complex radiation states ``z``, the newest hydro velocity
    ``u_now`` and the convolution's velocity ring buffer ``buf`` with its position ``pos`` (1,), ``pto_now``
    (3, n_pto): PTO strokes, rates and forces at the current state (what controllers measure), and ``far`` the
    convolution's far sums of the current block (``wecss.sim._memory``; a block of ``far.shape[0]`` steps starts
    at every global step that is a multiple of it)."""

    q: np.ndarray
    v: np.ndarray
    acc: np.ndarray
    acc_prev: np.ndarray
    z: np.ndarray
    u_now: np.ndarray
    buf: np.ndarray
    pos: np.ndarray
    pto_now: np.ndarray
    far: np.ndarray


ACCELERATION_FLOOR: float = 1e-11
"""Absolute floor [m/s^2 or rad/s^2] of the corrector's convergence test: changes of the accelerations below it are
round-off (static loads of order m g cancel in them), so a body at rest converges too."""


@kernel
def _passes_stroke_limit(p: Plant, x: np.ndarray) -> bool:
    """A stroke beyond its limit on a PTO without an end stop (the run must stop)."""
    for k in range(x.shape[0]):
        if abs(x[k]) > p.pto_stroke_limit[k] and p.pto_stop_stiffness[k] == 0.0:
            return True
    return False


@kernel
def _record(
    out: Store,
    n1: int,
    p: Plant,
    q: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    x: np.ndarray,
    xd: np.ndarray,
    f: np.ndarray,
    rad: np.ndarray,
    exc: np.ndarray,
) -> None:
    if out.every > 0 and n1 % out.every == 0 and out.save_index[0] < out.q.shape[0]:
        j = out.save_index[0]
        out.q[j] = q
        out.v[j] = v
        # the optional arrays have one row when no output reads them (see ``Store``)
        out.a[min(j, out.a.shape[0] - 1)] = a
        out.x[min(j, out.x.shape[0] - 1)] = x
        out.xd[min(j, out.xd.shape[0] - 1)] = xd
        out.f[min(j, out.f.shape[0] - 1)] = f
        jr = min(j, out.rad.shape[0] - 1)
        je = min(j, out.exc.shape[0] - 1)
        for c in range(exc.shape[0]):  # the hydro DOFs in the store's order
            out.rad[jr, c] = rad[out.hydro_order[c]]
            out.exc[je, c] = exc[out.hydro_order[c]]
        out.save_index[0] = j + 1
    for k in range(x.shape[0]):
        saturated = abs(f[k] + p.pto_spring[k] * x[k]) >= p.pto_force_limit[k] * (1.0 - 1e-12)
        stopped = abs(x[k]) > p.pto_stroke_limit[k]
        for row, active in ((0, saturated), (2, stopped)):  # force at its limit; stroke beyond it (end stop)
            if active:
                if out.limit_last[row // 2, k] != n1 - 1:
                    out.limits[row + 1, k] += 1  # an episode starts
                out.limits[row, k] += 1
                out.limit_last[row // 2, k] = n1
    spring = p.pto_spring
    if n1 >= out.stats_start:
        out.stats[0] += -(f + spring * x) * xd  # absorbed power: the device spring's force is conservative, left out
        out.stats[1] += x * x
        out.stats[2] += 1.0
        out.stats[3] += x


@kernel
def _out_of_bounds(q: np.ndarray, bounded: np.ndarray, bound: float) -> bool:
    for k in bounded:
        if abs(q[k]) > bound:
            return True
    return False


@kernel
def beeman_chunk(
    p: Plant,
    r: RadiationArrays,
    excitation: np.ndarray,
    command: np.ndarray,
    step0: int,
    settings: StepSettings,
    state: LoopState,
    out: Store,
    w: Workspace,
) -> tuple[int, int]:
    """Advance ``excitation.shape[0] - 1`` Beeman steps from global step ``step0`` (``state`` updated in place).

    ``excitation`` holds the excitation on the hydro DOFs at the chunk's times t_step0 ... (rows).
    ``state.pto_now`` receives x, x_dot, f at the last state (for controllers); ``out`` records the run; ``w`` is
    the kernels' workspace. The position is predicted once per step, so the corrector's evaluations share the
    configuration's terms (mass matrix and its factor, static loads: :func:`configure`) and only redo the
    velocity's (:func:`respond`). Returns (status, global step of the failure).
    """
    h, tol, max_iter, bounded, bound = settings
    q, v, acc, acc_prev, z, u_now, buf, pos, pto_now, far = state
    nv = v.shape[0]
    n_steps = excitation.shape[0] - 1
    a1 = np.empty(nv)
    known = np.empty(nv)
    vc = np.empty(nv)
    rad = np.empty(u_now.shape[0])
    for k in range(n_steps):
        n1 = step0 + k + 1
        hist = block_history(r, z, u_now, buf, pos[0], far, (n1 - 1) % far.shape[0])
        base = excitation[k + 1] + hist
        dv = h * v + h * h / 6.0 * (4.0 * acc - acc_prev)
        q1 = integrate_configuration(p, q, dv)
        if not np.all(np.isfinite(q1)):
            return LoopStatus.NOT_FINITE, n1
        if _out_of_bounds(q1, bounded, bound):
            return LoopStatus.OUT_OF_BOUNDS, n1
        if not configure(p, q1, base, w):
            return LoopStatus.NOT_FINITE, n1
        for c in range(nv):
            known[c] = v[c] + h / 6.0 * (5.0 * acc[c] - acc_prev[c])
            vc[c] = v[c] + h / 2.0 * (3.0 * acc[c] - acc_prev[c])
        respond(p, vc, r.newest, command, w)
        a1[:] = w.acc
        count = 1
        converged = False
        previous = np.inf
        for _ in range(max_iter):
            for c in range(nv):
                vc[c] = known[c] + h / 3.0 * a1[c]
            respond(p, vc, r.newest, command, w)
            count += 1
            change = 0.0
            scale = 0.0
            for c in range(nv):
                change = max(change, abs(w.acc[c] - a1[c]))
                scale = max(scale, abs(w.acc[c]))
                a1[c] = w.acc[c]
            if change <= tol * scale + ACCELERATION_FLOOR:
                converged = True
                break
            if change > previous or not np.isfinite(change):
                break
            previous = change
        if not converged:
            # Stiff step (h |dA/dv| / 3 > 1, where Beeman itself is unstable): the A-stable implicit trapezoidal
            # step q1 = q + h/2 (v + v1), v1 = v + h/2 (a + a(q1, v1)), by Newton with a finite-difference Jacobian.
            vc[:] = v + h * acc
            for _ in range(max_iter):
                q1 = integrate_configuration(p, q, 0.5 * h * (v + vc))
                configure(p, q1, base, w)
                respond(p, vc, r.newest, command, w)
                a_v = w.acc.copy()
                residual = vc - v - 0.5 * h * (acc + a_v)
                jac = np.eye(nv)
                for c in range(nv):
                    eps = 1e-7 * (1.0 + abs(vc[c]))
                    vp = vc.copy()
                    vp[c] += eps
                    configure(p, integrate_configuration(p, q, 0.5 * h * (v + vp)), base, w)
                    respond(p, vp, r.newest, command, w)
                    jac[:, c] -= 0.5 * h * (w.acc - a_v) / eps
                count += nv + 1
                out.evaluations[2] += 1
                delta = np.linalg.solve(jac, -residual)
                vc += delta
                if not np.all(np.isfinite(vc)):
                    return LoopStatus.NOT_FINITE, n1
                if np.max(np.abs(delta)) <= tol * np.max(np.abs(vc)) + h / 3.0 * ACCELERATION_FLOOR:
                    converged = True
                    break
            if not converged:
                return LoopStatus.CORRECTOR_FAILED, n1
            q1 = integrate_configuration(p, q, 0.5 * h * (v + vc))
            if not np.all(np.isfinite(q1)):
                return LoopStatus.NOT_FINITE, n1
            if _out_of_bounds(q1, bounded, bound):
                return LoopStatus.OUT_OF_BOUNDS, n1
            configure(p, q1, base, w)
            respond(p, vc, r.newest, command, w)
            a1[:] = w.acc
            count += 1
        if not np.all(np.isfinite(vc)):
            return LoopStatus.NOT_FINITE, n1
        out.evaluations[0] += count
        out.evaluations[1] = max(out.evaluations[1], count)
        u1, x1, xd1, f1 = w.u, w.stroke, w.xdot, w.f  # of the last evaluation, at (q1, vc)
        matvec(r.newest, u1, rad)
        rad += hist
        memory_advance(r, z, u_now, u1, buf, pos)
        u_now[:] = u1
        q[:] = q1
        v[:] = vc
        acc_prev[:] = acc
        acc[:] = a1
        pto_now[0] = x1
        pto_now[1] = xd1
        pto_now[2] = f1
        if _passes_stroke_limit(p, x1):
            return LoopStatus.STROKE_LIMIT, n1
        _record(out, n1, p, q, v, acc, x1, xd1, f1, rad, excitation[k + 1])
    return LoopStatus.OK, step0 + n_steps


@step_kernel
def state_rates(
    p: Plant,
    r: RadiationArrays,
    q: np.ndarray,
    v: np.ndarray,
    z: np.ndarray,
    exc: np.ndarray,
    command: np.ndarray,
    w: Workspace,
):
    """Rates (q_dot, v_dot, z_dot) of the state-space system, with the PTO data (x, x_dot, f) and the memory force
    (``w``: the kernels' workspace)."""
    rad = np.empty(exc.shape[0])
    matvec(r.output_real, z.view(np.float64), rad)
    if configure(p, q, exc + rad, w):
        respond(p, v, np.zeros((exc.shape[0], exc.shape[0])), command, w)  # the memory is all in z
    else:
        w.acc[:] = np.nan
    qd = configuration_rate(p, q, v)
    zd = r.poles * z
    matvec_add(r.input_real, w.u, zd.view(np.float64))
    return qd, w.acc.copy(), zd, w.stroke.copy(), w.xdot.copy(), w.f.copy(), rad


@kernel
def rk4_chunk(
    p: Plant,
    r: RadiationArrays,
    excitation: np.ndarray,
    command: np.ndarray,
    step0: int,
    settings: StepSettings,
    state: LoopState,
    out: Store,
    w: Workspace,
) -> tuple[int, int]:
    """Advance ``(excitation.shape[0] - 1) // 2`` RK4 steps; ``excitation`` rows are at half steps from t_step0.

    The rates at the end of a step, evaluated for the record, are the first stage of the next step (same state,
    time, command): four evaluations per step, five for a chunk's first."""
    h, bounded, bound = settings.h, settings.bounded, settings.angle_bound
    q, v, acc, z, pto_now = state.q, state.v, state.acc, state.z, state.pto_now
    n_steps = (excitation.shape[0] - 1) // 2
    qd1, a1, zd1, _, _, _, _ = state_rates(p, r, q, v, z, excitation[0], command, w)
    out.evaluations[0] += 1
    out.evaluations[1] = max(out.evaluations[1], 5)
    for k in range(n_steps):
        n1 = step0 + k + 1
        em = excitation[2 * k + 1]
        e1 = excitation[2 * k + 2]
        qd2, a2, zd2, _, _, _, _ = state_rates(
            p, r, q + 0.5 * h * qd1, v + 0.5 * h * a1, z + 0.5 * h * zd1, em, command, w
        )
        qd3, a3, zd3, _, _, _, _ = state_rates(
            p, r, q + 0.5 * h * qd2, v + 0.5 * h * a2, z + 0.5 * h * zd2, em, command, w
        )
        qd4, a4, zd4, _, _, _, _ = state_rates(p, r, q + h * qd3, v + h * a3, z + h * zd3, e1, command, w)
        q1 = q + h / 6.0 * (qd1 + 2.0 * qd2 + 2.0 * qd3 + qd4)
        normalise_quaternions(p, q1)
        v1 = v + h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)
        if not (np.all(np.isfinite(q1)) and np.all(np.isfinite(v1))):
            return LoopStatus.NOT_FINITE, n1  # q, v keep the last good state
        if _out_of_bounds(q1, bounded, bound):
            return LoopStatus.OUT_OF_BOUNDS, n1
        q[:] = q1
        v[:] = v1
        z[:] = z + h / 6.0 * (zd1 + 2.0 * zd2 + 2.0 * zd3 + zd4)
        qd1, a1, zd1, x1, xd1, f1, rad = state_rates(p, r, q, v, z, e1, command, w)
        out.evaluations[0] += 4
        acc[:] = a1
        pto_now[0] = x1
        pto_now[1] = xd1
        pto_now[2] = f1
        if _passes_stroke_limit(p, x1):
            return LoopStatus.STROKE_LIMIT, n1
        _record(out, n1, p, q, v, acc, x1, xd1, f1, rad, e1)
    return LoopStatus.OK, step0 + n_steps
