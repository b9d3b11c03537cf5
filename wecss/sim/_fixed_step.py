"""The fixed-step time loop of the nonlinear MFM equations, shared by every fixed-step integrator.

An integrator is a :class:`FixedStepRunner`: a kernel that advances a chunk of steps (:meth:`advance`) and a few
declarations; this module owns the rest of a run: the initial state at the equilibrium, the excitation at the
loop's times, the controller calls and their held forces, the checks between chunks (energy in calm water, the
translation bound), the recording into the :class:`~wecss.sim._loop.Store` the output table allocates, the
streaming of saved rows to a file and progress. A new integrator is one module with its runner (see
``docs/architecture.md``).

The loop runs in chunks of steps inside a kernel (numba-compiled when available); between chunks it reports
progress. A controller without linear gains is called once per control period (its force held over it), which
makes the chunks one control period long.
"""

from __future__ import annotations

import time as _time
from abc import abstractmethod
from typing import Any

import numpy as np

from ..compiled import TERM_COLUMNS, CompiledScene, Plant, RadiationArrays, saturate
from ..compiled.kernels import configure, respond, workspace
from ..control import ControlledScene
from ..outputs import CHANNEL_NAMES
from ..scene import Capabilities, Runner
from ..waves import SampledForce
from ._control import ControlLoop
from ._errors import PtoLimitExceeded, SimulationDiverged
from ._guards import farthest_body, stiff_pto_hint, translation_bound
from ._layout import grouped_hydro_order
from ._loop import Chunk, LoopState, LoopStatus, StepSettings, Store, new_store
from ._memory import far_sums_array
from ._progress import Progress
from ._record import Record, stats_start
from ._stream import STREAM_STEPS, ResultStream

CHUNK_STEPS: int = 2000
"""Steps per kernel call (progress is reported between chunks)."""

EXCITATION_TABLE_MAX: int = 2**22
"""Most values (times x hydrodynamic DOFs, 32 MB) of the excitation evaluated once for the whole run; longer runs
evaluate it in blocks of about as many values (their memory and their cost per step stay flat)."""

CALM_VELOCITY_LIMIT: float = 1e-6
"""In calm water, a generalised velocity above this [m/s or rad/s] means energy grew without input."""


class FixedStepRunner(Runner):
    """A fixed-step integrator of the nonlinear MFM equations (see the module docstring).

    Subclasses set ``name``, ``description`` and ``capabilities`` and implement :meth:`advance`; they may
    override :meth:`prepare` (per-run arrays the kernel needs, before the clock starts), :meth:`command_changed`
    (a held PTO command jumps), :meth:`solver_attrs` (what the result's attributes say about the run) and
    :meth:`failure` (the words for a status of theirs).
    """

    capabilities = Capabilities(streaming=True, initial_state=True)
    stages: int = 1
    """Excitation rows per step that :meth:`advance` reads: 1 (the steps' times), 2 (also the half steps)."""

    def prepare(self, controlled: ControlledScene) -> Any:
        """What :meth:`advance` needs besides the plant, made once per run before the clock starts (default
        None); may refuse the scene (``SceneError``)."""
        return None

    @abstractmethod
    def advance(self, prepared: Any, chunk: Chunk) -> tuple[int, int]:
        """Advance the steps whose excitation rows ``chunk.excitation`` holds (``stages`` rows per step after the
        first, at global step ``chunk.step0``), ``chunk.state`` in place, each step recorded into ``chunk.out``
        with ``record_step`` (see :class:`~wecss.sim._loop.Chunk`); ``prepared``: what :meth:`prepare` made.
        Returns (a :class:`LoopStatus`, the global step it ended at)."""

    def command_changed(
        self, p: Plant, r: RadiationArrays, state: LoopState, held: np.ndarray, command: np.ndarray
    ) -> None:
        """The held PTO command jumps from ``held`` to ``command`` at the present state (default: nothing; a
        multistep scheme moves its history)."""

    def solver_attrs(self, out: Store, prepared: Any, n_steps: int) -> dict[str, Any]:
        """What the result's attributes say about the run (at least ``solver``, the runner's name)."""
        return {"solver": self.name}

    def failure(self, status: LoopStatus, controlled: ControlledScene) -> str | None:
        """The words for ``status`` where this runner has its own (default None: the loop's)."""
        return None

    def run(self, controlled: ControlledScene, *, progress: bool = False, stream: ResultStream | None = None) -> Record:
        self.refuse_quasi_static(controlled)
        return run_fixed_step(self, controlled, progress, stream)


class _Excitation:
    """The excitation at the loop's times (steps, or half steps for RK4) [N, N m], (n_t, n_h).

    Evaluated once for the whole run when it fits in EXCITATION_TABLE_MAX values: on the uniform times of a
    record whose components are harmonics of its duration that is one inverse FFT (0.6 us per step on m4-134,
    whatever the number of components). Longer runs of such records evaluate it in blocks of about as many values,
    one chirp-z transform each (``wecss.waves.SampledForce``: 1.3-1.7 us per step, whatever the number of
    components and the run's length; both on a loaded machine, docs/benchmarks.md "Long runs"); records that do not
    repeat are summed per chunk of steps (a cost per step that grows with the components: 113 us at 1000 Tp). The
    forces agree to round-off whichever way they are evaluated.
    """

    def __init__(self, compiled: CompiledScene, per_step: int) -> None:
        self.compiled, self.per_step = compiled, per_step
        n_times = per_step * compiled.n_steps + 1
        n_h = compiled.plant.hydro_index.size
        self.table: np.ndarray | None = None
        self.sampled: SampledForce | None = None
        self.start = 0  # the first sample of the table
        if compiled.excitation is None:
            return
        if n_times * n_h <= EXCITATION_TABLE_MAX:
            self.table = compiled.excitation_at(np.arange(n_times) / per_step * compiled.dt)
        else:
            self.sampled = compiled.excitation.sampled(compiled.dt / per_step, max(1, EXCITATION_TABLE_MAX // n_h))

    def chunk(self, done: int, m: int) -> np.ndarray:
        """The forces at steps ``done`` to ``done + m`` (with the stages between them)."""
        first, count = self.per_step * done, self.per_step * m + 1
        if self.sampled is not None and (
            self.table is None or first < self.start or first + count > self.start + self.table.shape[0]
        ):  # the next block of samples
            self.table = self.sampled(first, max(count, self.sampled.block))
            self.start = first
        if self.table is not None:
            return self.table[first - self.start : first - self.start + count]
        return self.compiled.excitation_at((done + np.arange(self.per_step * m + 1) / self.per_step) * self.compiled.dt)


def _diverged(
    runner: FixedStepRunner, status: LoopStatus, step: int, controlled: ControlledScene, q: np.ndarray, v: np.ndarray
) -> SimulationDiverged:
    t = step * controlled.dt
    if status == LoopStatus.STROKE_LIMIT:
        return PtoLimitExceeded(
            f"a PTO stroke passed its stroke_limit at t = {t:.6g} s (step {step}) and the PTO has no end stop: give "
            "end_stop_stiffness (and end_stop_damping) in the device spec for one, or reduce the motion",
            t,
            step,
            {"q": q.copy(), "v": v.copy()},
        )
    reason = runner.failure(status, controlled) or {
        LoopStatus.NOT_FINITE: "the state became non-finite",
        LoopStatus.OUT_OF_BOUNDS: f"a revolute joint angle passed the bound {controlled.scene.solver.angle_bound} rad",
        LoopStatus.CORRECTOR_FAILED: "the corrector did not converge",
    }.get(status, f"status {status}")
    names = controlled.device.model.coordinate_names
    return SimulationDiverged(
        f"simulation diverged at t = {t:.6g} s (step {step}): {reason}; last good q = "
        + ", ".join(f"{n} {x:.4g}" for n, x in zip(names, q, strict=True))
        + "."
        + stiff_pto_hint(controlled),
        t,
        step,
        {"q": q.copy(), "v": v.copy()},
    )


def _sizes(controlled: ControlledScene) -> dict[str, int]:
    """Columns per channel size name (``wecss.outputs.Channel.size``)."""
    p = controlled.plant
    n_terms = TERM_COLUMNS * p.com0.shape[0]
    return {
        "nq": controlled.q0.size,
        "nv": p.twists.shape[0],
        "n_pto": p.pto_kind.size,
        "n_h": p.hydro_index.size,
        "n_terms": n_terms,
    }


def run_fixed_step(
    runner: FixedStepRunner, controlled: ControlledScene, progress: bool, stream: ResultStream | None = None
) -> Record:
    """``runner``'s steps over the whole run (see the module docstring). With a ``stream``, the saved rows go to it
    about every ``STREAM_STEPS`` steps and the loop's arrays hold only those since the last part (the Record
    returned then has no saved rows: its statistics, counts and solver only)."""
    scene = controlled.scene
    p, r = controlled.plant, controlled.radiation
    h, n = controlled.dt, controlled.n_steps
    every = scene.outputs.every if not scene.outputs.statistics_only else 0
    n_save = n // every + 1 if every else 0
    # a control period's chunk can pass the next part's step: room for both, and the row at step 0
    chunk = CHUNK_STEPS if controlled.linear_controller else scene.control_steps
    n_rows = min(n_save, (STREAM_STEPS + chunk) // every + 2) if stream is not None and every else n_save
    n_pto = p.pto_kind.size
    hydro_order = grouped_hydro_order(controlled)
    sampled = not controlled.linear_controller and n_pto > 0  # a controller's force, held over its period
    out = new_store(
        every,
        stats_start(controlled),
        n_rows,
        _sizes(controlled),
        scene.outputs.variables,
        {"rad": hydro_order, "exc": hydro_order},
        sampled=sampled,
        h=h,
    )
    q, v = controlled.initial_state()
    command = np.zeros(n_pto)
    exc0 = controlled.excitation_at(np.zeros(1))[0]
    work = workspace(p)
    if configure(p, q, exc0, 0.0, work):  # the initial state's accelerations and outputs
        respond(p, v, r.newest, command, work)
    else:
        work.acc[:] = np.nan
    a0, u0, x0, xd0, f0 = (work.acc.copy(), work.u.copy(), work.stroke.copy(), work.xdot.copy(), work.f.copy())
    a0[controlled.device.model.quasi_static_velocities] = 0.0  # a held coordinate has no acceleration
    terms0 = work.terms.out.reshape(-1).copy()
    acc, acc_prev = a0.copy(), a0.copy()
    z = np.zeros(r.poles.size, dtype=complex)
    u_now = u0.copy()
    buf = np.zeros((r.newest.shape[0], 2 * r.depth))
    buf[:, 0] = buf[:, r.depth] = u0
    pos = np.zeros(1, dtype=np.int64)
    pto_now = np.stack([x0, xd0, f0])
    out.last_stroke[:] = x0
    p0 = np.zeros(n_pto) if sampled else -(f0 + p.pto_spring * x0) * xd0  # the recorder's power at step 0
    state = LoopState(q, v, acc, acc_prev, z, u_now, buf, pos, pto_now, far_sums_array(r))
    settings = StepSettings(
        h,
        scene.solver.corrector_tol,
        scene.solver.max_corrector_iterations,
        controlled.bounded,
        scene.solver.angle_bound,
    )
    if n_save:  # the row at step 0: the initial state (no memory force yet)
        first = {
            "q": q, "v": v, "a": a0, "x": x0, "xd": xd0, "f": f0, "rad": np.zeros(u0.size), "exc": exc0,
            "terms": terms0, "p": p0,
        }  # fmt: skip
        for name, rows, order in zip(CHANNEL_NAMES, out.series, out.columns, strict=True):
            rows[0] = first[name][order]
        out.save_index[0] = 1
    prepared = runner.prepare(controlled)
    bound, next_check, shift, body = translation_bound(controlled), CHUNK_STEPS, 0.0, ""
    # a controller without linear gains is called once per control period (chunk) and its force held over it
    loop = None if controlled.linear_controller else ControlLoop.start(controlled)

    def full_state() -> np.ndarray:
        return np.concatenate([q, v, z.real, z.imag])

    bar = Progress(n, progress)
    start = _time.perf_counter()
    excitation = _Excitation(controlled, runner.stages)  # (timed: it is part of the loop's work)
    done = 0
    calm = controlled.excitation is None and scene.initial.at_rest  # no input: no motion may start
    written, next_part = 0, STREAM_STEPS  # saved rows handed to the stream; the step of its next part
    streaming = 0.0  # time spent deriving and writing the parts (not the loop's)

    def part() -> Record:
        """The saved rows since the last part (their number is the store's save index)."""
        k = int(out.save_index[0])
        series = {name: values[:k] for name, values in zip(CHANNEL_NAMES, out.series, strict=True)}
        time = (written + np.arange(k)) * every * h
        return Record(time=time, series=series, stats=out.stats, run_time=0.0, hydro_order=hydro_order)

    while done < n:
        m = min(chunk, n - done)
        if loop is not None:
            held = command
            command = loop.force(done * h, pto_now[0], pto_now[1], full_state)
            if np.any(command != held):
                runner.command_changed(p, r, state, held, command)
            out.held[:] = saturate(command, p.pto_force_limit)  # what the kernels apply over the chunk's steps
        status, at = runner.advance(
            prepared, Chunk(p, r, excitation.chunk(done, m), command, done, settings, state, out, work)
        )
        if status != LoopStatus.OK:
            raise _diverged(runner, LoopStatus(status), at, controlled, q, v)
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
            body, shift = farthest_body(controlled, q)
        if shift > bound:
            raise SimulationDiverged(
                f"body {body} moved {shift:.4g} m from its equilibrium by t = {done * h:.6g} s, beyond "
                f"solver.translation_bound ({bound:.4g} m): a drift (nothing restores horizontal motion without a "
                "mooring), the integrator's error (a run at half the step or with solver.method 'rk4' tells) or a "
                "divergence; give a larger solver.translation_bound if the motion is meant",
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
    return Record(
        time=saved,
        series=dict(zip(CHANNEL_NAMES, out.series, strict=True)),
        stats=out.stats,
        run_time=run_time,
        solver=runner.solver_attrs(out, prepared, n),
        limits=out.limits,
        hydro_order=hydro_order,
        pressure_flags=work.terms.flags.copy(),
    )
