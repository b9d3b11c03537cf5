"""The re-run at half the step that splits a run's drift into the integrator's error and the physics (issue 31:
Beeman at the default step drifted +0.159 m in surge on m4-134 in Hs 0.16 m over 120 s where RK4 and the linear
model drifted -0.035 m; its note blamed the missing mooring).

When a run's drift note fires (a body's horizontal mean position moves by more than ``DRIFT_LIMIT`` x its size,
``wecss.sim._drift``), the scene is run again at dt/2, with its motion only and every other saved row, and the
drift of that run is kept (:class:`DriftCheck`): for a runner of order p the drift at a step h is the physical
drift plus c h^p, so the numerical part at dt is (d(dt) - d(dt/2)) 2^p / (2^p - 1) and the rest is physical
(Richardson, as the pilot runs of ``solver.tolerance`` estimate the statistics' error). The re-run costs about
twice the run; runs longer than :data:`MAX_CHECK_STEPS` steps are not re-run (the note says so).
"""

from __future__ import annotations

import copy
import dataclasses

import numpy as np

from ..compiled import CompiledScene
from ..control import ControlledScene, compile_scene
from ._drift import DriftCheck, drifting
from ._errors import SimulationDiverged
from ._guards import MotionSummary, body_sizes

MAX_CHECK_STEPS: int = 400_000
"""Longest run (in steps) whose drift is checked by a re-run at half the step (which takes twice its steps)."""

NO_STEP_ERROR: tuple[str, ...] = ("frequency", "reference")
"""Runners whose drift holds no step error to estimate: the exact steady state, the tight-tolerance reference."""


def record_drift(compiled: CompiledScene, q: np.ndarray) -> np.ndarray:
    """:meth:`MotionSummary.drift` of the saved configurations ``q`` (n_t, nq), from the poses of their first and
    last tenths only."""
    summary = MotionSummary(compiled, q.shape[0])
    tenth = summary.tenth
    if q.shape[0] <= 2 * tenth:
        summary.add(q)
    else:
        summary.add(q[:tenth])
        summary.seen = q.shape[0] - tenth  # the middle rows count for neither tenth
        summary.add(q[-tenth:])
    return summary.drift()


def drift_check(controlled: ControlledScene, drift: np.ndarray) -> DriftCheck | None:
    """The re-run at half the step of a run whose ``drift`` (n_body, 2) [m] passes the note's limit (None when it
    does not, or for a runner without step error)."""
    runner = controlled.scene.runner
    if (
        runner.name in NO_STEP_ERROR
        or runner.capabilities.order < 1
        or not drifting(list(controlled.device.model.body_names), body_sizes(controlled), drift)
    ):
        return None
    dt, order = controlled.dt, runner.capabilities.order
    if controlled.n_steps > MAX_CHECK_STEPS:
        return DriftCheck(dt, order, None, f"the run has {controlled.n_steps} steps, more than {MAX_CHECK_STEPS}")
    scene = controlled.scene
    half = dataclasses.replace(
        scene,
        solver=dataclasses.replace(scene.solver, dt=dt / 2, tolerance=None),
        outputs=dataclasses.replace(scene.outputs, variables=("motion",), every=2 * scene.outputs.every, probes=()),
    )
    controller = None  # the scene's controller section makes a new one
    if controlled.controller_given:  # a copy: the run's own controller keeps its state for the result's report
        try:
            controller = copy.deepcopy(controlled.controller)
        except Exception as err:  # any object may refuse to be copied
            return DriftCheck(dt, order, None, f"the given controller could not be copied for a re-run: {err}")
    try:
        rerun = compile_scene(half, controller)
        record = rerun.scene.runner.run(rerun)
    except SimulationDiverged as err:
        return DriftCheck(dt, order, None, f"the re-run at dt/2 diverged: {str(err).split(';')[0]}")
    except Exception as err:  # the run itself is done: a failed check must not lose it
        return DriftCheck(dt, order, None, f"the re-run at dt/2 failed ({type(err).__name__}: {err})")
    return DriftCheck(dt, order, record_drift(rerun, record["q"]))
