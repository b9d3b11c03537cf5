"""The reference solver: scipy's DOP853 on (q, v, Re z, Im z) at tight tolerance, for verification (state-space
radiation or none; controllers with linear gains only, whose force is continuous in the state)."""

from __future__ import annotations

import sys
import time as _time
from typing import Any

import numpy as np

from ..compiled import CompiledScene
from ..compiled.kernels import workspace
from ..control import ControlledScene
from ..limits import REFERENCE_EVALUATIONS, beyond
from ..scene import Capabilities, Runner, SceneError
from ._errors import SimulationDiverged
from ._guards import fastest_mode
from ._record import Record, continuous_power, window_statistics
from ._rk4 import state_rates


class ReferenceSolver(Runner):
    """scipy's DOP853 at ``solver.reference_rtol`` (see the module docstring)."""

    name = "reference"
    description = "scipy DOP853 at tight tolerance on (q, v, radiation states), for verification"
    tolerance_reason = ": its step adapts to its own tolerance, solver.reference_rtol"
    capabilities = Capabilities(
        radiation=("state_space", "none"),
        sampled_controllers=False,
        initial_state=True,
        hydrodynamics=("body-exact", "drag"),
        terms=True,
        order=8,
        options=("allow_large",),
    )
    radiation_reason = (
        "with a convolution the memory at the intermediate stages is not defined, which would drop the scheme to first "
        "order; use 'beeman' for convolutions"
    )

    def run(self, controlled: ControlledScene, *, progress: bool = False, stream: Any = None) -> Record:
        return run_reference(controlled, progress)


def run_reference(compiled: ControlledScene, progress: bool) -> Record:
    """scipy DOP853 on (q, v, Re z, Im z) at tight tolerance (state-space radiation; linear controllers only)."""
    scene = compiled.scene
    p, r = compiled.plant, compiled.radiation
    nq, nv, nz = compiled.q0.size, p.twists.shape[0], r.poles.size
    command = np.zeros(p.pto_kind.size)
    work = workspace(p)

    def parts(t: float, y: np.ndarray):
        """The RK4 kernel's rates at (t, y): qd, a, zd, x, xd, f, rad; and the excitation."""
        q, v = y[:nq], y[nq : nq + nv]
        z = y[nq + nv : nq + nv + nz] + 1j * y[nq + nv + nz :]
        exc = compiled.excitation_at(np.array([t]))[0]
        return (*state_rates(p, r, q, v, z, exc, t, command, work), exc, work.terms.out.reshape(-1).copy())

    budget = np.inf if scene.solver.allow_large else REFERENCE_EVALUATIONS
    evaluations = 0

    def rates(t: float, y: np.ndarray) -> np.ndarray:
        nonlocal evaluations
        evaluations += 1
        if evaluations > budget:  # the estimate below missed: a stiffness the equilibrium does not show
            raise SceneError(_refusal(f"{evaluations - 1} evaluations by t = {t:.6g} s of {time[-1]:.4g} s", budget))
        qd, a, zd, *_ = parts(t, y)
        return np.concatenate([qd, a, zd.real, zd.imag])

    every = scene.outputs.every if not scene.outputs.statistics_only else compiled.n_steps + 1
    if not scene.solver.allow_large:
        check_stiffness(compiled)
    time = compiled.time  # every step, to the end, for the statistics; the saved ones are every ``every``-th
    q0, v0 = compiled.initial_state()
    y0 = np.concatenate([q0, v0, np.zeros(2 * nz)])
    start = _time.perf_counter()
    from scipy.integrate import solve_ivp  # lazy: only the reference solver needs it

    sol = solve_ivp(
        rates, (0.0, time[-1]), y0, method="DOP853", t_eval=time, rtol=scene.solver.reference_rtol, atol=1e-12
    )
    if not sol.success:
        raise SimulationDiverged(f"reference solver failed: {sol.message}", float(sol.t[-1]), -1, {"y": sol.y[:, -1]})
    run_time = _time.perf_counter() - start
    rows = [parts(t, y) for t, y in zip(sol.t, sol.y.T, strict=True)]
    stack = {
        k: np.array([row[i] for row in rows])
        for k, i in (("a", 1), ("x", 3), ("xd", 4), ("f", 5), ("rad", 6), ("exc", 7), ("terms", 8))
    }
    stack["q"], stack["v"] = sol.y[:nq].T.copy(), sol.y[nq : nq + nv].T.copy()
    stack["p"] = continuous_power(compiled, stack["x"], stack["xd"], stack["f"])  # linear gains only
    stats = window_statistics(compiled, stack["x"], stack["p"])
    if progress:
        print(f"reference solver: {sol.nfev} evaluations", file=sys.stderr)
    saved = {k: v[::every] for k, v in stack.items()}
    solver = {"solver": "reference", "function_evaluations": int(sol.nfev)}
    return Record(
        time=time[::every],
        series=saved,
        stats=stats,
        run_time=run_time,
        solver=solver,
        pressure_flags=work.terms.flags.copy(),
    )


EVALUATIONS_PER_STIFFNESS: float = 3.5
"""Right-hand-side evaluations DOP853 spends per unit of |s| T (the fastest rate |s| [1/s] times the run's
duration T [s]) where stability, not accuracy, sets its step: measured 30,512 evaluations for |s| T = 8,648 (m4-111,
PTO damping 1e4 N m s/rad, 2 s): 12 stages per step of |s| h about 3.4."""


def stiffness(compiled: CompiledScene) -> tuple[float, float]:
    """The fastest rate |s| [1/s] of the plant (its mechanical modes with the PTO gains, and the state-space
    radiation poles) and the evaluations DOP853 needs for it over the run, EVALUATIONS_PER_STIFFNESS |s| T."""
    rate = max(fastest_mode(compiled), float(compiled.radiation_summary.max_pole))
    return rate, EVALUATIONS_PER_STIFFNESS * rate * float(compiled.time[-1])


def check_stiffness(compiled: CompiledScene) -> None:
    """Refuse, before it starts, a reference run whose plant is too stiff for an explicit method over its
    duration (more than REFERENCE_EVALUATIONS evaluations estimated).

    Raises
    ------
    SceneError
        Naming the fastest rate, the estimate, the limit and ``solver.allow_large``.
    """
    rate, needed = stiffness(compiled)
    if needed > REFERENCE_EVALUATIONS:
        raise SceneError(
            _refusal(
                f"about {needed:.3g} evaluations estimated (fastest mode |s| = {rate:.4g} rad/s over "
                f"{float(compiled.time[-1]):.4g} s: a stiff plant, an explicit method's step is about 3.4 / |s|)",
                REFERENCE_EVALUATIONS,
            )
        )


def _refusal(value: str, limit: float) -> str:
    return beyond(
        "the reference solver (DOP853)",
        value,
        f"{limit:.3g} evaluations",
        "a stiff PTO gain or a fast radiation pole: reduce the gain, or use solver.method 'linear', exact in the "
        "linear terms",
        "give solver.allow_large = true",
    )


REFERENCE = ReferenceSolver()
