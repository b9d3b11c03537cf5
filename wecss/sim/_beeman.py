"""The Beeman predictor-corrector (M4 paper Eq. 52; Beeman 1976), wecss's default integrator of the nonlinear MFM
equations, with a velocity-dependent force:

    q_{n+1}   = q_n + h v_n + h^2/6 (4 a_n - a_{n-1})            (on SO(3) for a free base)
    v^p_{n+1} = v_n + h/2 (3 a_n - a_{n-1})                       predictor
    v^c_{n+1} = v_n + h/6 (2 a_{n+1} + 5 a_n - a_{n-1})            corrector, a_{n+1} = a(q_{n+1}, v^c_{n+1})

The corrector is iterated until the change of a_{n+1} is below ``tol`` relative to |a_{n+1}|. When it does
not contract (stiff PTO damping, h c / M large: for a linear damper the fixed point diverges exactly where
Beeman's scheme itself turns unstable, h c / M > 3) the step is taken instead by the A-stable implicit
trapezoidal rule, solved by Newton's method with a finite-difference Jacobian (second order, like Beeman); if that
fails too the step reports failure (never a silent result).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..compiled import Plant, RadiationArrays
from ..compiled.kernels import Workspace, accelerations, configure, integrate_configuration, kernel, matvec, respond
from ..control import ControlledScene
from ..scene import Capabilities
from ._fixed_step import FixedStepRunner
from ._guards import check_beeman_elastic, check_beeman_step
from ._loop import (
    ACCELERATION_FLOOR,
    Chunk,
    LoopState,
    LoopStatus,
    StepSettings,
    Store,
    out_of_bounds,
    passes_stroke_limit,
    record_step,
)
from ._memory import block_history, memory_advance


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
        t1 = n1 * h
        hist = block_history(r, z, u_now, buf, pos[0], far, (n1 - 1) % far.shape[0])
        base = excitation[k + 1] + hist
        dv = h * v + h * h / 6.0 * (4.0 * acc - acc_prev)
        q1 = integrate_configuration(p, q, dv)
        if not np.all(np.isfinite(q1)):
            return LoopStatus.NOT_FINITE, n1
        if out_of_bounds(q1, bounded, bound):
            return LoopStatus.OUT_OF_BOUNDS, n1
        if not configure(p, q1, base, t1, w):
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
                configure(p, q1, base, t1, w)
                respond(p, vc, r.newest, command, w)
                a_v = w.acc.copy()
                residual = vc - v - 0.5 * h * (acc + a_v)
                jac = np.eye(nv)
                for c in range(nv):
                    eps = 1e-7 * (1.0 + abs(vc[c]))
                    vp = vc.copy()
                    vp[c] += eps
                    configure(p, integrate_configuration(p, q, 0.5 * h * (v + vp)), base, t1, w)
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
            if out_of_bounds(q1, bounded, bound):
                return LoopStatus.OUT_OF_BOUNDS, n1
            configure(p, q1, base, t1, w)
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
        if passes_stroke_limit(p, x1):
            return LoopStatus.STROKE_LIMIT, n1
        record_step(out, n1, p, (q, v, acc, x1, xd1, f1, rad, excitation[k + 1], w.terms.out.reshape(-1)))
    return LoopStatus.OK, step0 + n_steps


def shift_history(p: Plant, r: RadiationArrays, state: LoopState, held: np.ndarray, command: np.ndarray) -> None:
    """Beeman's acceleration history across a jump of the held PTO command at the present instant.

    Beeman's predictor and corrector extrapolate the accelerations a_n and a_{n-1} as a smooth function; a command
    that jumps at t_n makes them the accelerations of the force that no longer acts, and the step's position
    prediction (never corrected) misses the new force: an error of order h^2 per jump, first order over a run.
    The jump in acceleration at the present state is exactly the difference of two evaluations that differ only in
    the command (the PTO force enters additively, through the same mass and transmission); both history values are
    moved by it, as if the new command had always acted.
    """
    q, v, acc, acc_prev = state.q, state.v, state.acc, state.acc_prev
    no_load = np.zeros(p.hydro_index.size)
    no_memory = np.zeros_like(r.newest)
    jump = accelerations(p, q, v, no_load, no_memory, command)[0] - accelerations(p, q, v, no_load, no_memory, held)[0]
    acc += jump
    acc_prev += jump


class Beeman(FixedStepRunner):
    """The Beeman predictor-corrector (see the module docstring): second order, implicit added mass, any radiation
    memory, every controller, streamed results."""

    name = "beeman"
    description = (
        "Beeman predictor-corrector (M4 paper Eq. 52), implicit added mass, trapezoidal fallback on stiff steps"
    )
    capabilities = Capabilities(
        streaming=True,
        initial_state=True,
        hydrodynamics=("body-exact", "drag"),
        terms=True,
        order=2,
        tolerance=True,
    )

    def prepare(self, controlled: ControlledScene) -> Any:
        check_beeman_elastic(controlled)
        check_beeman_step(controlled)
        return None

    def advance(self, prepared: Any, chunk: Chunk) -> tuple[int, int]:
        return beeman_chunk(*chunk)

    def command_changed(
        self, p: Plant, r: RadiationArrays, state: LoopState, held: np.ndarray, command: np.ndarray
    ) -> None:
        shift_history(p, r, state, held, command)

    def solver_attrs(self, out: Store, prepared: Any, n_steps: int) -> dict[str, Any]:
        evaluations = out.evaluations
        return {
            "solver": "beeman",
            "evaluations_per_step": float(evaluations[0]) / max(1, n_steps),
            "max_evaluations_per_step": int(evaluations[1]),
            "newton_corrector_steps": int(evaluations[2]),
        }

    def failure(self, status: LoopStatus, controlled: ControlledScene) -> str | None:
        if status == LoopStatus.CORRECTOR_FAILED:
            return "the Beeman corrector (fixed point and Newton) did not converge"
        return None


BEEMAN = Beeman()
