"""The reference solver: scipy's DOP853 on (q, v, Re z, Im z) at tight tolerance, for verification (state-space
radiation or none; controllers with linear gains only, whose force is continuous in the state)."""

from __future__ import annotations

import sys
import time as _time
from typing import Any

import numpy as np

from ..compiled.kernels import workspace
from ..control import ControlledScene
from ..scene import Capabilities, Runner
from ._errors import SimulationDiverged
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

    def rates(t: float, y: np.ndarray) -> np.ndarray:
        qd, a, zd, *_ = parts(t, y)
        return np.concatenate([qd, a, zd.real, zd.imag])

    every = scene.outputs.every if not scene.outputs.statistics_only else compiled.n_steps + 1
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


REFERENCE = ReferenceSolver()
