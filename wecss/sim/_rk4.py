"""Classic fourth-order Runge-Kutta on (q, v, z), the configuration, the generalised velocities and the state-space
radiation states (no convolution: its memory at the intermediate stages is not defined). Explicit: the step must
lie inside RK4's stability region for the plant's fastest mode and the fit's fastest pole (checked before the run).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..compiled import Plant, RadiationArrays
from ..compiled.kernels import (
    Workspace,
    configuration_rate,
    configure,
    kernel,
    matvec,
    matvec_add,
    normalise_quaternions,
    respond,
    step_kernel,
)
from ..control import ControlledScene
from ..scene import Capabilities, SceneError
from ._fixed_step import FixedStepRunner
from ._guards import check_rk4
from ._loop import Chunk, LoopState, LoopStatus, StepSettings, Store, out_of_bounds, passes_stroke_limit, record_step

RK4_POLE_LIMIT: float = 2.5
"""Largest |s| dt of the radiation fit's poles RK4 is run with (its stability region reaches 2.79 on the real
axis and 2.83 on the imaginary one)."""


@step_kernel
def state_rates(
    p: Plant,
    r: RadiationArrays,
    q: np.ndarray,
    v: np.ndarray,
    z: np.ndarray,
    exc: np.ndarray,
    t: float,
    command: np.ndarray,
    w: Workspace,
):
    """Rates (q_dot, v_dot, z_dot) of the state-space system at time ``t`` [s], with the PTO data (x, x_dot, f) and
    the memory force (``w``: the kernels' workspace)."""
    rad = np.empty(exc.shape[0])
    matvec(r.output_real, z.view(np.float64), rad)
    if configure(p, q, exc + rad, t, w):
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
    qd1, a1, zd1, _, _, _, _ = state_rates(p, r, q, v, z, excitation[0], step0 * h, command, w)
    out.evaluations[0] += 1
    out.evaluations[1] = max(out.evaluations[1], 5)
    for k in range(n_steps):
        n1 = step0 + k + 1
        em = excitation[2 * k + 1]
        e1 = excitation[2 * k + 2]
        tm, t1 = (n1 - 0.5) * h, n1 * h
        qd2, a2, zd2, _, _, _, _ = state_rates(
            p, r, q + 0.5 * h * qd1, v + 0.5 * h * a1, z + 0.5 * h * zd1, em, tm, command, w
        )
        qd3, a3, zd3, _, _, _, _ = state_rates(
            p, r, q + 0.5 * h * qd2, v + 0.5 * h * a2, z + 0.5 * h * zd2, em, tm, command, w
        )
        qd4, a4, zd4, _, _, _, _ = state_rates(p, r, q + h * qd3, v + h * a3, z + h * zd3, e1, t1, command, w)
        q1 = q + h / 6.0 * (qd1 + 2.0 * qd2 + 2.0 * qd3 + qd4)
        normalise_quaternions(p, q1)
        v1 = v + h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)
        if not (np.all(np.isfinite(q1)) and np.all(np.isfinite(v1))):
            return LoopStatus.NOT_FINITE, n1  # q, v keep the last good state
        if out_of_bounds(q1, bounded, bound):
            return LoopStatus.OUT_OF_BOUNDS, n1
        q[:] = q1
        v[:] = v1
        z[:] = z + h / 6.0 * (zd1 + 2.0 * zd2 + 2.0 * zd3 + zd4)
        qd1, a1, zd1, x1, xd1, f1, rad = state_rates(p, r, q, v, z, e1, t1, command, w)
        out.evaluations[0] += 4
        acc[:] = a1
        pto_now[0] = x1
        pto_now[1] = xd1
        pto_now[2] = f1
        if passes_stroke_limit(p, x1):
            return LoopStatus.STROKE_LIMIT, n1
        record_step(out, n1, p, (q, v, acc, x1, xd1, f1, rad, e1, w.terms.out.reshape(-1)))
    return LoopStatus.OK, step0 + n_steps


class Rk4(FixedStepRunner):
    """Classic RK4 (see the module docstring): fourth order, state-space radiation or none, every controller,
    streamed results."""

    name = "rk4"
    description = "classic fourth-order Runge-Kutta on (q, v, radiation states)"
    capabilities = Capabilities(
        radiation=("state_space", "none"),
        streaming=True,
        initial_state=True,
        hydrodynamics=("body-exact", "drag"),
        terms=True,
        order=4,
        tolerance=True,
    )
    stages = 2
    radiation_reason = (
        "with a convolution the memory at the intermediate stages is not defined, which would drop the scheme to first "
        "order; use 'beeman' for convolutions"
    )

    def check_compiled(self, compiled: Any) -> None:
        super().check_compiled(compiled)
        summary, dt = compiled.radiation_summary, compiled.dt
        if summary.max_pole * dt > RK4_POLE_LIMIT:
            raise SceneError(
                f"RK4 is unstable with this state-space fit: its fastest pole |s| = {summary.max_pole:.4g} rad/s "
                f"needs dt < {RK4_POLE_LIMIT / summary.max_pole:.3g} s (given {dt:.3g} s); use 'beeman' (exact in the "
                "radiation states) or a smaller step"
            )

    def prepare(self, controlled: ControlledScene) -> Any:
        check_rk4(controlled)
        return None

    def advance(self, prepared: Any, chunk: Chunk) -> tuple[int, int]:
        return rk4_chunk(*chunk)

    def solver_attrs(self, out: Store, prepared: Any, n_steps: int) -> dict[str, Any]:
        return {"solver": "rk4"}


RK4 = Rk4()
