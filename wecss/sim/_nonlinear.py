"""The nonlinear MFM runs: fixed-step time loops (Beeman, RK4) and the scipy reference, each returning a
:class:`Record`.

The loop runs in chunks of steps inside a kernel (numba-compiled when available); between chunks it reports
progress. A controller without linear gains is called once per step (its force held over the step), which makes
the chunks one step long.
"""

from __future__ import annotations

import sys
import time as _time
from typing import Any

import numpy as np

from ..compiled import CompiledScene, Plant, RadiationArrays, accelerations, workspace
from ..scene import SceneError
from ._control import ControlLoop
from ._explicit import MAX_ITERATION_FACTOR, beeman_explicit_chunk, iteration_factor, split_added_mass
from ._guards import check_rk4, farthest_body, stiff_pto_hint, translation_bound
from ._integrators import LoopState, LoopStatus, StepSettings, Store, beeman_chunk, rk4_chunk, state_rates
from ._memory import far_sums_array
from ._progress import Progress
from ._result import Record, grouped_hydro_order, stats_start, window_statistics
from ._stream import STREAM_STEPS, ResultStream

CHUNK_STEPS: int = 2000
"""Steps per kernel call (progress is reported between chunks)."""

EXCITATION_TABLE_MAX: int = 2**22
"""Most values (times x hydrodynamic DOFs, 32 MB) of the excitation evaluated once for the whole run; longer runs
evaluate it per chunk of steps (their memory stays flat, their cost per step grows with the wave components)."""

CALM_VELOCITY_LIMIT: float = 1e-6
"""In calm water, a generalised velocity above this [m/s or rad/s] means energy grew without input."""


class SimulationDiverged(RuntimeError):
    """The simulation left the range where its results mean anything.

    Attributes
    ----------
    time : float
        Time of the failing step [s].
    step : int
    state : dict
        ``q`` and ``v`` at the last good step.
    """

    def __init__(self, message: str, time: float, step: int, state: dict[str, np.ndarray]) -> None:
        super().__init__(message)
        self.time = time
        self.step = step
        self.state = state


class PtoLimitExceeded(SimulationDiverged):
    """A PTO stroke passed its ``stroke_limit`` on a PTO without an end stop (the device spec says to stop)."""


class _Excitation:
    """The excitation at the loop's times (steps, or half steps for RK4) [N, N m], (n_t, n_h).

    Evaluated once for the whole run when it fits in EXCITATION_TABLE_MAX values: on the uniform times of a
    record whose components are harmonics of its duration that is one inverse FFT (about 1 us per step, whatever
    the number of components), against 13 us (100 Tp) to 47 us (500 Tp) per step for sums per chunk on m4-134.
    The times are the same floating-point numbers either way, so the forces differ only by round-off.
    """

    def __init__(self, compiled: CompiledScene, per_step: int) -> None:
        self.compiled, self.per_step = compiled, per_step
        n_times = per_step * compiled.n_steps + 1
        self.table: np.ndarray | None = None
        if compiled.excitation is not None and n_times * compiled.plant.hydro_index.size <= EXCITATION_TABLE_MAX:
            self.table = compiled.excitation_at(np.arange(n_times) / per_step * compiled.dt)

    def chunk(self, done: int, m: int) -> np.ndarray:
        """The forces at steps ``done`` to ``done + m`` (with the half steps between them for RK4)."""
        if self.table is not None:
            return self.table[self.per_step * done : self.per_step * (done + m) + 1]
        return self.compiled.excitation_at((done + np.arange(self.per_step * m + 1) / self.per_step) * self.compiled.dt)


def _shift_history(p: Plant, r: RadiationArrays, state: LoopState, held: np.ndarray, command: np.ndarray) -> None:
    """Beeman's acceleration history across a jump of the held PTO command at the present instant.

    Beeman's predictor and corrector extrapolate the accelerations a_n and a_{n-1} as a smooth function; a command
    that jumps at t_n makes them the accelerations of the force that no longer acts, and the step's position
    prediction (never corrected) misses the new force: an error of order h^2 per jump, first order over a run.
    The jump in acceleration at the present state is exactly the difference of two evaluations that differ only in
    the command (the PTO force enters additively, through the same mass and transmission); both history values are
    moved by it, as if the new command had always acted. RK4 needs none of this: it restarts every step.
    """
    q, v, acc, acc_prev = state.q, state.v, state.acc, state.acc_prev
    no_load = np.zeros(p.hydro_index.size)
    no_memory = np.zeros_like(r.newest)
    jump = accelerations(p, q, v, no_load, no_memory, command)[0] - accelerations(p, q, v, no_load, no_memory, held)[0]
    acc += jump
    acc_prev += jump


def _diverged(
    status: LoopStatus, step: int, compiled: CompiledScene, q: np.ndarray, v: np.ndarray
) -> SimulationDiverged:
    t = step * compiled.dt
    if status == LoopStatus.STROKE_LIMIT:
        return PtoLimitExceeded(
            f"a PTO stroke passed its stroke_limit at t = {t:.6g} s (step {step}) and the PTO has no end stop: give "
            "end_stop_stiffness (and end_stop_damping) in the device spec for one, or reduce the motion",
            t,
            step,
            {"q": q.copy(), "v": v.copy()},
        )
    reason = {
        LoopStatus.NOT_FINITE: "the state became non-finite",
        LoopStatus.OUT_OF_BOUNDS: f"a revolute joint angle passed the bound {compiled.scene.solver.angle_bound} rad",
        LoopStatus.CORRECTOR_FAILED: (
            "the explicit added-mass iteration (solver.added_mass 'explicit') did not reach solver.corrector_tol in "
            f"{compiled.scene.solver.max_corrector_iterations} iterations (solver.max_corrector_iterations); "
            "'implicit' needs no iteration"
            if compiled.scene.solver.added_mass == "explicit"
            else "the Beeman corrector (fixed point and Newton) did not converge"
        ),
    }.get(status, f"status {status}")
    names = compiled.device.model.coordinate_names
    return SimulationDiverged(
        f"simulation diverged at t = {t:.6g} s (step {step}): {reason}; last good q = "
        + ", ".join(f"{n} {x:.4g}" for n, x in zip(names, q, strict=True))
        + "."
        + stiff_pto_hint(compiled),
        t,
        step,
        {"q": q.copy(), "v": v.copy()},
    )


def _saved_rows(groups: tuple[str, ...], n_save: int) -> dict[str, int]:
    """Rows of the store's optional arrays: ``n_save`` where an output group reads them, else one (a scratch row
    the kernels overwrite, so that a run keeps only what its outputs need; configurations and velocities are always
    kept, for the notes). Keys: ``a`` accelerations, ``pto`` PTO strokes, rates and forces, ``rad`` memory forces,
    ``exc`` excitation."""
    needs = {
        "a": ("motion", "loads"),
        "pto": ("pto", "loads"),
        "rad": ("radiation", "loads"),
        "exc": ("excitation", "loads"),
    }
    return {key: n_save if n_save and any(g in groups for g in wanted) else 1 for key, wanted in needs.items()}


def _explicit_added_mass(compiled: CompiledScene) -> tuple[Plant, np.ndarray, float]:
    """The rigid plant, the added mass and the iteration's spectral radius at the equilibrium for
    ``solver.added_mass = "explicit"`` (see ``_explicit``); refuses a scene where the iteration cannot converge."""
    factor = iteration_factor(compiled.plant, compiled.q0)
    if factor > MAX_ITERATION_FACTOR:
        raise SceneError(
            f"solver.added_mass 'explicit': the added-mass iteration cannot converge on {compiled.device.name}: its "
            f"spectral radius (B'MB)^-1 B'A_inf B at the equilibrium is {factor:.3g} (the added mass outweighs the "
            f"rigid mass in some mode; at most {MAX_ITERATION_FACTOR} is accepted); use solver.added_mass 'implicit'"
        )
    rigid, added = split_added_mass(compiled.plant)
    return rigid, added, factor


def run_fixed_step(compiled: CompiledScene, progress: bool, stream: ResultStream | None = None) -> Record:
    """Beeman or RK4 (the scene's ``solver.method``) over every step. With a ``stream``, the saved rows go to it
    about every ``STREAM_STEPS`` steps and the loop's arrays hold only those since the last part (the Record
    returned then has no saved rows: its statistics, counts and solver only)."""
    scene = compiled.scene
    p, r = compiled.plant, compiled.radiation
    h, n = compiled.dt, compiled.n_steps
    every = scene.outputs.every if not scene.outputs.statistics_only else 0
    n_save = n // every + 1 if every else 0
    # a control period's chunk can pass the next part's step: room for both, and the row at step 0
    chunk = CHUNK_STEPS if compiled.linear_controller else scene.control_steps
    n_rows = min(n_save, (STREAM_STEPS + chunk) // every + 2) if stream is not None and every else n_save
    nq, nv, n_pto, n_h = compiled.q0.size, p.twists.shape[0], p.pto_kind.size, p.hydro_index.size
    rows = _saved_rows(scene.outputs.variables, n_rows)
    hydro_order = grouped_hydro_order(compiled)
    out = Store(
        every=every,
        stats_start=stats_start(compiled),
        q=np.zeros((n_rows, nq)),
        v=np.zeros((n_rows, nv)),
        a=np.zeros((rows["a"], nv)),
        x=np.zeros((rows["pto"], n_pto)),
        xd=np.zeros((rows["pto"], n_pto)),
        f=np.zeros((rows["pto"], n_pto)),
        rad=np.zeros((rows["rad"], n_h)),
        exc=np.zeros((rows["exc"], n_h)),
        save_index=np.zeros(1, dtype=np.int64),
        stats=np.zeros((4, n_pto)),  # sums over the window: absorbed power, stroke^2, count, stroke
        evaluations=np.zeros(3, dtype=np.int64),
        limits=np.zeros((4, n_pto), dtype=np.int64),
        limit_last=np.full((2, n_pto), -2, dtype=np.int64),
        hydro_order=hydro_order,
    )
    q = compiled.q0.copy()
    v = np.zeros(nv)
    command = np.zeros(n_pto)
    exc0 = compiled.excitation_at(np.zeros(1))[0]
    a0, u0, x0, xd0, f0, _ = accelerations(p, q, v, exc0, r.newest, command)
    acc, acc_prev = a0.copy(), a0.copy()
    z = np.zeros(r.poles.size, dtype=complex)
    u_now = u0.copy()
    buf = np.zeros((n_h, 2 * r.depth))
    buf[:, 0] = buf[:, r.depth] = u0
    pos = np.zeros(1, dtype=np.int64)
    pto_now = np.stack([x0, xd0, f0])
    state = LoopState(q, v, acc, acc_prev, z, u_now, buf, pos, pto_now, far_sums_array(r))
    settings = StepSettings(
        h, scene.solver.corrector_tol, scene.solver.max_corrector_iterations, compiled.bounded, scene.solver.angle_bound
    )
    if n_save:
        for row, value in (
            (out.q, q),
            (out.v, v),
            (out.a, a0),
            (out.x, x0),
            (out.xd, xd0),
            (out.f, f0),
            (out.exc, exc0[hydro_order]),
        ):
            row[0] = value
        out.save_index[0] = 1
    rk4 = scene.solver.method == "rk4"
    explicit = _explicit_added_mass(compiled) if scene.solver.added_mass == "explicit" else None
    bound, next_check, shift, body = translation_bound(compiled), CHUNK_STEPS, 0.0, ""
    if rk4:
        check_rk4(compiled)
    # a controller without linear gains is called once per control period (chunk) and its force held over it
    loop = None if compiled.linear_controller else ControlLoop.start(compiled)

    def full_state() -> np.ndarray:
        return np.concatenate([q, v, z.real, z.imag])

    bar = Progress(n, progress)
    work = workspace(p)
    start = _time.perf_counter()
    excitation = _Excitation(compiled, 2 if rk4 else 1)  # (timed: it is part of the loop's work)
    done = 0
    calm = compiled.excitation is None
    written, next_part = 0, STREAM_STEPS  # saved rows handed to the stream; the step of its next part
    streaming = 0.0  # time spent deriving and writing the parts (not the loop's)

    def part() -> Record:
        """The saved rows since the last part (their number is the store's save index)."""
        k = int(out.save_index[0])
        a, x, xd, f, rad, exc = (values[:k] for values in (out.a, out.x, out.xd, out.f, out.rad, out.exc))
        time = (written + np.arange(k)) * every * h
        record = Record(time, out.q[:k], out.v[:k], a, x, xd, f, rad, exc, out.stats, 0.0)
        record.hydro_order = hydro_order
        return record

    while done < n:
        m = min(chunk, n - done)
        if loop is not None:
            held = command
            command = loop.force(done * h, pto_now[0], pto_now[1], full_state)
            if not rk4 and np.any(command != held):
                _shift_history(p, r, state, held, command)
        if rk4:
            status, at = rk4_chunk(p, r, excitation.chunk(done, m), command, done, settings, state, out, work)
        elif explicit is not None:
            rigid, added, _ = explicit
            status, at = beeman_explicit_chunk(
                rigid, added, r, excitation.chunk(done, m), command, done, settings, state, out
            )
        else:
            status, at = beeman_chunk(p, r, excitation.chunk(done, m), command, done, settings, state, out, work)
        if status != LoopStatus.OK:
            raise _diverged(LoopStatus(status), at, compiled, q, v)
        if calm and np.max(np.abs(v)) > CALM_VELOCITY_LIMIT:
            raise SimulationDiverged(
                f"energy grew without input: in calm water the largest velocity reached {np.max(np.abs(v)):.3g} "
                f"by t = {(done + m) * h:.6g} s (limit {CALM_VELOCITY_LIMIT:g}); the static equilibrium or the "
                "integration is wrong",
                (done + m) * h,
                done + m,
                {"q": q.copy(), "v": v.copy()},
            )
        done += m
        if done >= next_check or done == n:  # about every CHUNK_STEPS steps, whatever the chunk, and at the end
            next_check = done + CHUNK_STEPS
            body, shift = farthest_body(compiled, q)
        if shift > bound:
            raise SimulationDiverged(
                f"body {body} moved {shift:.4g} m from its equilibrium by t = {done * h:.6g} s, beyond "
                f"solver.translation_bound ({bound:.4g} m): a drift (nothing restores horizontal motion without a "
                "mooring) or a divergence; give a larger solver.translation_bound if the motion is meant",
                done * h,
                done,
                {"q": q.copy(), "v": v.copy()},
            )
        if stream is not None and n_save and (done >= next_part or done == n):
            writing = _time.perf_counter()
            stream.add(part())
            streaming += _time.perf_counter() - writing
            written += int(out.save_index[0])
            out.save_index[0] = 0
            next_part = done + STREAM_STEPS
        bar.update(done)
    run_time = _time.perf_counter() - start - streaming
    saved = np.arange(0 if stream is not None else n_save) * every * h
    solver: dict[str, Any]
    if rk4:
        solver = {"solver": "rk4"}
    else:
        evaluations = out.evaluations
        solver = {
            "solver": "beeman",
            "evaluations_per_step": float(evaluations[0]) / max(1, n),
            "max_evaluations_per_step": int(evaluations[1]),
            "newton_corrector_steps": int(evaluations[2]),
        }
        if explicit is not None:
            solver["added_mass"] = "explicit"
            solver["added_mass_iteration_factor"] = explicit[2]
    record = Record(saved, out.q, out.v, out.a, out.x, out.xd, out.f, out.rad, out.exc, out.stats, run_time, solver)
    record.limits = out.limits
    record.hydro_order = hydro_order
    return record


def run_reference(compiled: CompiledScene, progress: bool) -> Record:
    """scipy DOP853 on (q, v, Re z, Im z) at tight tolerance (state-space radiation; linear controllers only)."""
    if not compiled.linear_controller:
        raise SceneError("the reference solver needs a controller with linear gains (such as 'damping')")
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
        return (*state_rates(p, r, q, v, z, exc, command, work), exc)

    def rates(t: float, y: np.ndarray) -> np.ndarray:
        qd, a, zd, *_ = parts(t, y)
        return np.concatenate([qd, a, zd.real, zd.imag])

    every = scene.outputs.every if not scene.outputs.statistics_only else compiled.n_steps + 1
    time = compiled.time  # every step, to the end, for the statistics; the saved ones are every ``every``-th
    y0 = np.concatenate([compiled.q0, np.zeros(nv + 2 * nz)])
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
        for k, i in (("a", 1), ("x", 3), ("xd", 4), ("f", 5), ("rad", 6), ("exc", 7))
    }
    stack["q"], stack["v"] = sol.y[:nq].T.copy(), sol.y[nq : nq + nv].T.copy()
    stats = window_statistics(compiled, stack["x"], stack["xd"], stack["f"])
    if progress:
        print(f"reference solver: {sol.nfev} evaluations", file=sys.stderr)
    saved = {k: v[::every] for k, v in stack.items()}
    solver = {"solver": "reference", "function_evaluations": int(sol.nfev)}
    return Record(time[::every], **saved, stats=stats, run_time=run_time, solver=solver)
