"""The step (and the integrator) chosen from ``solver.tolerance``: the relative error allowed on the statistics a
run reports (mean PTO power and RMS PTO stroke over the statistics window).

How (:func:`choose_step`):

1. **A first guess, a priori**, per candidate runner (the scene's ``solver.method``, or ``rk4`` and ``beeman``):
   the step h = T (tolerance / C)^(1/p) of a runner of order p whose statistics err by C (h / T)^p, T the sea's
   peak period (:data:`ERROR_CONSTANTS`, measured on the M4 layouts: ``docs/benchmarks.md``), capped by what the
   scene allows: RK4's stability region for the plant over the configurations the run may reach and for the
   radiation fit's fastest pole, at least ``MIN_STEPS_PER_PERIOD`` steps per period of the shortest wave
   component, a whole number of steps per control period. Without a named method, the candidate with the least
   work (steps times :data:`STEP_COST`) is taken.
2. **An estimate, a posteriori**: a short pilot run of the scene (its first ``ramp`` + :data:`PILOT_PERIODS` peak
   periods, the statistics over the periods after the ramp, statistics only) at h and h/2. The difference of
   their statistics, times 2 (Richardson: for an order p >= 1 the error at h is (s_h - s_h/2) 2^p / (2^p - 1) <= 2
   (s_h - s_h/2)), is the error estimate at h, relative to the largest statistic of its kind.
3. **The step**: h scaled by (SAFETY tolerance / estimate)^(1/p), at most :data:`MAX_GROWTH` h and within the caps.
   Its estimate, (chosen / h)^p times the pilot's, is recorded with the choice in the result's attributes
   (``solver_tolerance``, ``tolerance_estimate``, ``tolerance_pilot_estimate``, ``tolerance_pilot_dt``,
   ``tolerance_choice``).

The estimate is the pilot's: its statistics over a few periods stand for those of the whole run (the error of a
statistic is a spectrum-weighted mean of the integrator's error per frequency, about the same over any stretch of
a stationary sea). ``tests/sim/test_tolerance.py`` checks the chosen run against the reference solver.
"""

from __future__ import annotations

import dataclasses
import math
import time as _time
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..compiled import MIN_STEPS_PER_PERIOD
from ..control import ControlledScene, Controller, compile_scene
from ..scene import EXPLICIT_RUNNER, Scene, SceneError, resolve_time, runner
from ._guards import beeman_step_limit
from ._rk4 import RK4, RK4_POLE_LIMIT, Rk4
from ._rk4_check import rk4_step_limit

ERROR_CONSTANTS: dict[str, float] = {"beeman": 4.4, "rk4": 50.0, "linear": 4.4}
"""C of the first guess: the relative error of the statistics is about C (h / Tp)^p. Beeman: 1.74e-3 of the mean
power at Tp/50, RK4: 1.24e-4 at Tp/25 (m4-134, default sea, docs/benchmarks.md "Run time against error"); the
linear runner's first-order hold taken as Beeman's (second order too). A guess only: the pilot run measures."""

DEFAULT_ERROR_CONSTANT: float = 50.0
"""C of the first guess for a runner not in :data:`ERROR_CONSTANTS`."""

STEP_COST: dict[str, float] = {"beeman": 1.0, "rk4": 3.1}
"""Cost of one step relative to Beeman's, to choose between candidates: RK4 12.2 / 37.4 us per step on m4-134
(docs/benchmarks.md "Run time against error": 48.9 ms for 4000 Beeman steps, 18.7 ms for 500 RK4 steps)."""

SAFETY: float = 0.25
"""The chosen step's estimated error is at most this share of the tolerance. The pilot's window stands for the
run's only roughly: the relative error of a statistic depends on the stretch of the record it is taken over
(measured: m4-111, 20 Tp, Beeman: the run's window erred 3.1 times the pilot's at the same step; m4-134, 100 Tp,
RK4: 0.4 times)."""

MAX_GROWTH: float = 2.0
"""The chosen step is at most this multiple of the pilot's step (the estimate extrapolated upward no further)."""

MAX_PILOTS: int = 3
"""Most pairs of pilot runs: a pair is run again at the step it asks for when that is below the pilot's step by more
than :data:`REPILOT_RATIO` (the error then was not yet of the integrator's order: components resolved by a few
steps only)."""

REPILOT_RATIO: float = 1.5

PILOT_PERIODS: float = 8.0
"""Peak periods of the pilot run after its ramp (its statistics window)."""

PILOT_RAMP_PERIODS: float = 2.0
"""Longest ramp of the pilot run [peak periods] (the scene's own when shorter)."""


class _PilotRk4(Rk4):
    """RK4 for the pilot runs, without its check per run: the plan bounded the step by RK4's stability region for
    the same plant once (:func:`_plan`)."""

    def prepare(self, controlled: ControlledScene) -> Any:
        return None


_PILOT_RK4 = _PilotRk4()


@dataclass(frozen=True)
class StepChoice:
    """The step and the integrator chosen for a scene's ``solver.tolerance``.

    Attributes
    ----------
    scene : Scene
        The scene to run: the user's with ``solver.method`` and ``solver.dt`` set (and no tolerance).
    tolerance : float
        The relative error asked for [-].
    method : str
    dt : float
        The chosen step [s].
    estimate : float
        The estimated relative error of the statistics at ``dt`` [-] (the pilot's, scaled by (dt / pilot_dt)^p).
    pilot_dt : float
        The pilot's coarse step [s] (its fine step is half of it).
    pilot_estimate : float
        The estimated relative error of the statistics at ``pilot_dt`` [-]: twice the difference of the pilot's
        statistics at ``pilot_dt`` and ``pilot_dt / 2``.
    guess_dt : float
        The a-priori step [s] (before the pilot).
    cap : str
        What bounds the step from above ("" when nothing did).
    sampling : float
        The typical relative difference [-] between a statistic as the run reports it (a mean over the window's
        steps) and the time average it stands for, the same for every solver at this step: [(f_start + f_end) / 2
        - mean] / (N + 1) for the N + 1 steps of the window, its size taken as the pilot's spread of f / sqrt(2)
        (zero for a held force's power, whose work per step is exact). Not part of the tolerance.
    pilot_time : float
        Wall time of the choice [s] (compiles and pilot runs).
    """

    scene: Scene
    tolerance: float
    method: str
    dt: float
    estimate: float
    pilot_dt: float
    pilot_estimate: float
    guess_dt: float
    cap: str
    sampling: float
    pilot_time: float

    def attrs(self) -> dict[str, Any]:
        """What the result's attributes say about the choice."""
        period = self.scene.sea.period
        steps = f" (Tp/{period / self.dt:.4g})" if period else ""
        capped = f", step bounded by {self.cap}" if self.cap else ""
        return {
            "solver_tolerance": self.tolerance,
            "tolerance_estimate": self.estimate,
            "tolerance_pilot_dt": self.pilot_dt,
            "tolerance_pilot_estimate": self.pilot_estimate,
            "tolerance_choice_time_s": self.pilot_time,
            "tolerance_window_sampling": self.sampling,
            "tolerance_choice": (
                f"solver.tolerance = {self.tolerance:g}: {self.method}, dt = {self.dt:.6g} s{steps}, estimated "
                f"relative error of the statistics {self.estimate:.2e} (pilot runs at {self.pilot_dt:.6g} s and half "
                f"of it: {self.pilot_estimate:.2e}; a-priori step {self.guess_dt:.6g} s{capped})"
            ),
        }


def choose_step(scene: Scene, controller: Controller | None = None) -> StepChoice:
    """The integrator and step for ``scene``'s ``solver.tolerance`` (see the module docstring).

    Parameters
    ----------
    scene : Scene
        With ``solver.tolerance`` (and no ``solver.dt``).
    controller : Controller, optional
        The controller instance the run will use instead of the scene's (the pilot runs use it too).

    Returns
    -------
    StepChoice

    Raises
    ------
    SceneError
        For a scene without a tolerance, without waves or PTOs (no statistics to judge), or that no allowed step
        can run.
    """
    tol = scene.solver.tolerance
    if tol is None:
        raise SceneError("choose_step needs a scene with solver.tolerance (this one gives solver.dt)")
    if scene.sea.kind == "calm":
        raise SceneError("solver.tolerance judges the statistics of a run in waves; this sea is calm: give solver.dt")
    start = _time.perf_counter()
    candidates = scene.candidates
    compiled = compile_scene(_provisional(scene, candidates[0], _fine_step(scene)), controller)
    plans = [_plan(scene, compiled, name, tol) for name in candidates]
    plan = min(plans, key=lambda p: p.work)
    order = plan.order
    h = plan.guess
    for attempt in range(MAX_PILOTS):
        coarse = _pilot_run(scene, plan.method, h, h, controller)
        fine = _pilot_run(scene, plan.method, h / 2, h, controller)
        pilot = 2.0 * _relative_difference(coarse.statistics, fine.statistics, plan.kinds)
        wanted = h * (SAFETY * tol / pilot) ** (1.0 / order) if pilot > 0 else math.inf  # inf: equal to round-off
        if wanted >= h / REPILOT_RATIO or attempt == MAX_PILOTS - 1:  # h stays the step the estimate is of
            break
        h = _fitted(scene, wanted, plan.cap_step)  # far below the pilot's step: measure again nearer to it
    chosen = _fitted(scene, min(wanted, MAX_GROWTH * h, plan.cap_step), plan.cap_step)
    estimate = pilot * (chosen / h) ** order
    cap = plan.cap if chosen >= 0.999 * plan.cap_step else ""
    solver = dataclasses.replace(scene.solver, method=plan.method, dt=chosen, tolerance=None)
    resolved = dataclasses.replace(scene, solver=solver)
    window = resolved.n_steps - stats_start_step(resolved) + 1
    spread = fine.spread.copy()
    if not compiled.linear_controller:
        spread[0] = 0.0  # a held force's power per step is its work over the step: no sampling error
    spread[1] /= 2  # the RMS's relative error is half its square's
    sampling = float(np.max(spread, initial=0.0)) / (math.sqrt(2.0) * (window + 1))
    return StepChoice(
        scene=resolved,
        tolerance=tol,
        method=plan.method,
        dt=chosen,
        estimate=estimate,
        pilot_dt=h,
        pilot_estimate=pilot,
        guess_dt=plan.guess,
        cap=cap,
        sampling=sampling,
        pilot_time=_time.perf_counter() - start,
    )


def stats_start_step(scene: Scene) -> int:
    """The first step of a (step-given) scene's statistics window (as ``wecss.sim`` computes it)."""
    n = scene.n_steps
    return n - max(1, round(scene.outputs.window * n)) + 1


def _fine_step(scene: Scene) -> float:
    """A step [s] to compile the scene at before its step is chosen (Tp/200, at most a tenth of the run)."""
    period = scene.sea.period or scene.sea.duration_s / 100
    return _fitted(scene, min(period / 200, scene.sea.duration_s / 10), math.inf)


@dataclass(frozen=True)
class _Plan:
    """A candidate runner's a-priori step [s], its largest allowed step [s] and why, its order, its work (steps
    per second of run times the cost of a step) and the kinds of the PTOs (statistics are judged per kind)."""

    method: str
    guess: float
    cap_step: float
    cap: str
    order: int
    work: float
    kinds: np.ndarray


def _reference_period(scene: Scene, compiled: ControlledScene) -> float:
    """The sea's peak period [s], or 2 pi / the energy-weighted mean frequency of its components."""
    if scene.sea.period is not None:
        return float(scene.sea.period)
    waves = compiled.waves
    if waves is None:
        raise SceneError("solver.tolerance judges the statistics of a run in waves; this scene has none")
    variance = np.abs(waves.amplitude) ** 2
    return float(2 * np.pi * np.sum(variance) / np.sum(variance * waves.omega))


def _provisional(scene: Scene, method: str, dt: float) -> Scene:
    return dataclasses.replace(scene, solver=dataclasses.replace(scene.solver, method=method, dt=dt, tolerance=None))


def _plan(scene: Scene, compiled: ControlledScene, method: str, tol: float) -> _Plan:
    """The a-priori step of ``method`` and its caps, from the scene ``compiled`` at a fine step."""
    if not compiled.device.ptos:
        raise SceneError(
            "solver.tolerance judges the statistics of the PTOs (mean power, RMS stroke); this device has no PTO: "
            "give solver.dt"
        )
    order = runner(method).capabilities.order
    period = _reference_period(scene, compiled)
    guess = period * (tol / ERROR_CONSTANTS.get(method, DEFAULT_ERROR_CONSTANT)) ** (1.0 / order)
    caps: list[tuple[float, str]] = [(scene.sea.duration_s / 20, "a twentieth of the run")]
    if compiled.waves is not None:
        shortest = 2 * np.pi / float(np.max(compiled.waves.omega))
        caps.append((shortest / MIN_STEPS_PER_PERIOD, f"{MIN_STEPS_PER_PERIOD} steps per shortest wave period"))
    if method in ("beeman", EXPLICIT_RUNNER):  # refused past it (``check_beeman_step``)
        beeman_limit, rate = beeman_step_limit(compiled)
        caps.append((0.99 * beeman_limit, f"Beeman's stability for the fastest undamped mode ({rate:.4g} rad/s)"))
    if method == RK4.name:
        limit, cause = rk4_step_limit(compiled)
        caps.append((0.99 * limit, f"RK4's stability region ({cause})"))
        pole = compiled.radiation_summary.max_pole
        if pole > 0:
            caps.append((0.99 * RK4_POLE_LIMIT / pole, "RK4's stability for the radiation fit's fastest pole"))
    cap_step, cap = min(caps, key=lambda c: c[0])
    guess = _fitted(scene, min(guess, cap_step), cap_step)
    work = STEP_COST.get(method, 1.0) / guess
    return _Plan(method, guess, cap_step, cap, order, work, np.asarray(compiled.pto_kinds))


def _fitted(scene: Scene, h: float, cap: float) -> float:
    """``h`` [s], at most ``cap``, made a whole fraction of the control period when the scene gives one, else of the
    wave record's period (:func:`record_period`): on such a grid the excitation of the whole run is one inverse FFT
    (or blocks of chirp-z transforms), not sums of the components at every step."""
    h = min(h, cap)
    if scene.controller.dt is not None:
        control = resolve_time(scene.controller.dt, scene.sea.period, "controller.dt")
        return float(control / math.ceil(control / h * (1 - 1e-12)))
    period = record_period(scene)
    if period is not None:
        h = period / math.ceil(period / h * (1 - 1e-12))
    return float(h)


def record_period(scene: Scene) -> float | None:
    """The period [s] after which the scene's wave record repeats (2 pi / d_omega for a periodic irregular sea, the
    wave period for a regular one), or None."""
    sea = scene.sea
    if sea.kind == "regular":
        return float(sea.period) if sea.period else None
    if sea.kind in ("jonswap", "pierson-moskowitz", "tabulated") and sea.periodic:
        return 2 * math.pi / sea.d_omega if sea.d_omega is not None else sea.duration_s
    return None


def _pilot_scene(scene: Scene, method: str, dt: float, coarse: float) -> Scene:
    """The scene's first ramp + PILOT_PERIODS periods at ``dt`` (the ramp and the window whole numbers of the pair's
    coarse step ``coarse`` [s]), the same wave record, the PTO series saved at every step."""
    sea = scene.sea
    period = sea.period or sea.duration_s / 100
    ramp = coarse * math.ceil(min(sea.ramp_s, PILOT_RAMP_PERIODS * period) / coarse - 1e-9)
    window = coarse * max(2, round(PILOT_PERIODS * period / coarse))
    duration = ramp + window
    changes: dict[str, Any] = {"duration": duration, "ramp": ramp}
    if sea.periodic and sea.d_omega is None and sea.kind not in ("regular", "elevation", "calm"):
        changes["d_omega"] = 2 * np.pi / sea.duration_s  # the run's components, not the pilot's
    outputs = dataclasses.replace(scene.outputs, statistics_only=False, variables=("pto",), every=1)
    pilot = dataclasses.replace(scene, sea=dataclasses.replace(sea, **changes), outputs=outputs)
    return _provisional(pilot, method, dt)


@dataclass(frozen=True)
class _PilotRun:
    """A pilot run's statistics (2, n_pto): mean absorbed power [W] and RMS stroke about its mean [rad or m] as
    time averages over the window (trapezoidal rule; a held force's power per step as it is, exact), and the
    relative spread of what each is the mean of (the power, the squared stroke) [-]."""

    statistics: np.ndarray
    spread: np.ndarray


def _pilot_run(scene: Scene, method: str, dt: float, coarse: float, controller: Controller | None) -> _PilotRun:
    """The pilot of ``scene`` by ``method`` at the step ``dt`` [s] of the pair whose coarse step is ``coarse``
    (see :func:`_pilot_scene`)."""
    pilot = compile_scene(_pilot_scene(scene, method, dt, coarse), controller)
    runner = _PILOT_RK4 if method == RK4.name else pilot.scene.runner
    record = runner.run(pilot)
    start = round(pilot.scene.sea.ramp_s / dt)  # the ramp's end, a step of both pilots
    x, power = record["x"][start:], record["p"][start:]
    weights = np.ones(x.shape[0])
    weights[[0, -1]] = 0.5
    weights /= weights.sum()
    mean_x = weights @ x
    square = x - mean_x
    if pilot.linear_controller:  # a continuous force law: its power at the steps
        mean_power = weights @ power
    else:  # a held force: the work of each step over the step, exact
        mean_power = power[1:].mean(axis=0)
    statistics = np.stack([mean_power, np.sqrt(np.maximum(weights @ square**2, 0.0))])
    scale = np.stack([np.abs(mean_power), statistics[1] ** 2])
    deviation = np.stack([np.std(power, axis=0), np.std(square**2, axis=0)])
    spread = np.divide(deviation, scale, out=np.zeros_like(deviation), where=scale > 0)
    return _PilotRun(statistics, spread)


def _relative_difference(a: np.ndarray, b: np.ndarray, kinds: np.ndarray) -> float:
    """Largest difference of statistics ``a`` and ``b`` (2, n_pto), relative to the largest |b| of the same
    statistic and PTO kind."""
    worst = 0.0
    for row in range(a.shape[0]):
        for kind in np.unique(kinds):
            cols = kinds == kind
            scale = float(np.max(np.abs(b[row, cols])))
            if scale > 0:
                worst = max(worst, float(np.max(np.abs(a[row, cols] - b[row, cols]))) / scale)
    return worst
