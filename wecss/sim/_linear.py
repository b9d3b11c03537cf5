"""Linear runs: the scene's linear model stepped exactly (``solver.method = "linear"``), open loop for a controller
with linear gains (folded into the model) or closed by any other controller."""

from __future__ import annotations

import time as _time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..compiled import initial_increments, pto_control_force, saturate
from ..compiled.kernels import end_stop_force
from ..control import ControlledScene, compile_scene
from ..linear import Feedback, LinearModel, closed_loop, linearize, open_loop
from ..scene import LINEAR_HOLDS, Capabilities, Runner, Scene, SceneError
from ..waves import evaluate
from ._control import ControlLoop
from ._dataset import build_result
from ._errors import PtoLimitExceeded
from ._record import Record, continuous_power, held_power, limit_counts, no_terms, window_statistics


class LinearRunner(Runner):
    """The linearised model stepped exactly (see :func:`simulate_linear`)."""

    name = "linear"
    description = "the equations linearised about the equilibrium, stepped exactly in modal coordinates"
    capabilities = Capabilities(
        radiation=("state_space",),
        free_base=False,
        options=("hold",),
        initial_state=True,
        hydrodynamics=("drag",),
        order=2,
        tolerance=True,
        quasi_static=True,
    )
    radiation_reason = "the linear model carries the radiation memory as states"

    def check_compiled(self, compiled: Any) -> None:
        super().check_compiled(compiled)
        if compiled.scene.hydrodynamics.drag and compiled.plant.viscous.morison_body.size:
            raise SceneError(
                f"solver.method {self.name!r} linearises the body drag but not the Morison elements of "
                f"{compiled.device.name!r} (their drag and fluid inertia): use a nonlinear runner such as 'beeman'"
            )

    def run(self, controlled: ControlledScene, *, progress: bool = False, stream: Any = None) -> Record:
        return linear_record(controlled, hold=controlled.scene.solver.linear_hold)


LINEAR = LinearRunner()


def simulate_linear(
    compiled: ControlledScene | Scene | str | Path, model: LinearModel | None = None, *, hold: str = "foh"
) -> xr.Dataset:
    """Time-domain run of the linear model on the scene's waves, with the exact discretisation (in modal
    coordinates: see ``wecss.linear.ModalForm``).

    A controller with linear gains is folded into the model (open loop in the remaining inputs). Any other
    controller closes the loop: it is called once per control period (``controller.dt``, default every step)
    with the PTO strokes and rates and its force is held until the next call (zero-order hold, as in the
    nonlinear simulator); the excitation keeps the ``hold`` given. The device's PTO limits act as in the
    nonlinear simulator: the controller's force saturated at ``force_limit``, the end stops beyond
    ``stroke_limit`` (or a stop of the run). A folded linear controller that never reaches a limit runs open
    loop, exactly; where it does, its gains come out of the model and act through the PTO inputs, limited and held
    over each step (first order in dt, said in the result's solver attribute). ``simulate`` runs this for scenes with
    ``solver.method = "linear"``; call it directly for another ``model`` (a reduced one, say).

    ``compiled`` may also be a scene or a scene file (compiled here). Returns a Dataset laid out as
    :func:`wecss.sim.simulate`'s (so every metric works on both).

    Raises
    ------
    ValueError
        For a device with a free base (its coordinates are not linear), an unknown ``hold``, or a scene whose
        radiation memory is not a state-space model (``wecss.linear.NoStateSpace``).
    SceneError
        If ``initial`` gives a modal coordinate held quasi-static a displacement or a velocity.

    Modal coordinates held quasi-static (``flexible.quasi_static_above``) are condensed in the model
    (``wecss.linear.linearize``): its states are the kept coordinates, their values the outputs with the
    generalised force's feedthrough, their rates and accelerations zero, as a generalised-alpha run records them;
    a controller's ``measurement.state`` is then the condensed model's state.
    """
    if isinstance(compiled, str | Path):
        compiled = Scene.from_toml(compiled)
    if isinstance(compiled, Scene):
        compiled = compile_scene(compiled)
    return build_result(compiled, linear_record(compiled, model, hold=hold))


def linear_record(controlled: ControlledScene, model: LinearModel | None = None, *, hold: str = "foh") -> Record:
    """The :class:`Record` of a linear run of ``controlled`` (see :func:`simulate_linear`)."""
    compiled = controlled
    if compiled.device.model.nq != compiled.device.model.nv:
        raise ValueError("the linear simulation needs joint coordinates (no free base)")
    if hold not in LINEAR_HOLDS:
        raise ValueError(f"hold must be one of {', '.join(LINEAR_HOLDS)}; got {hold!r}")
    model = model or linearize(compiled)
    model.modal_steps(compiled.dt, hold)  # the modal form and step are made (and cached) before the clock starts
    if not (compiled.linear_controller or model.pto_jacobian.shape[0] == 0):
        model.modal_steps(compiled.dt, "zoh")
    start = _time.perf_counter()
    p = compiled.plant
    nv, n_h, n_pto = model.mass.shape[0], model.hydro_jacobian.shape[0], model.pto_jacobian.shape[0]
    g = model.pto_jacobian
    time = compiled.time
    exc = compiled.excitation_at(time)
    force = exc @ model.hydro_jacobian  # generalised excitation (n_t, nv)
    if model.drag is not None and model.drag.forcing.size:  # the linearised drag's forcing by the fluid's velocity
        ramp = compiled.excitation.ramp if compiled.excitation is not None else None
        drag = np.real(evaluate(model.drag.forcing, model.drag.omega, time)).T
        force += drag if ramp is None else drag * ramp(time)[:, None]
    stroke0 = model.pto_stroke
    with_radiation = bool({"radiation", "loads"} & set(compiled.scene.outputs.variables))  # loads need the memory
    limited = bool(np.any(np.isfinite(p.pto_force_limit)) or np.any(np.isfinite(p.pto_stroke_limit)))
    applied = np.zeros((time.size, n_pto))  # the controller's force held over each step (not folded in)
    wanted = np.zeros((time.size, n_pto))  # what the controller asked for, before the force limit
    closed = not (compiled.linear_controller or n_pto == 0)
    x0 = _initial_state(compiled, model)
    if not closed:
        y = open_loop(model, compiled.dt, hold, force, _output_rows(model, with_radiation), x0)
        stroke = stroke0[None] + _coordinates(model, y, force) @ g.T
        wanted = pto_control_force(0.0, p.pto_damping, p.pto_stiffness, stroke, y[:, nv : 2 * nv] @ g.T)
        closed = limited and bool(
            np.any(np.abs(wanted) > p.pto_force_limit) or np.any(np.abs(stroke) > p.pto_stroke_limit)
        )
        if closed:  # a limit is reached: the folded gains come out and act, limited, through the PTO inputs
            model = model.with_pto_gains(0.0, 0.0)
    if closed:
        feedback = _feedback(compiled, model, applied, wanted)
        y, command = closed_loop(model, compiled.dt, hold, force, _output_rows(model, with_radiation), feedback, x0)
        # recorded at t_k, as by the nonlinear simulator: the force that acted over the step ending at t_k
        force[1:] += command[:-1] @ g
        applied = np.concatenate([np.zeros((1, n_pto)), applied[:-1]])
    every = compiled.scene.outputs.every
    keep = slice(None, None, every)
    if model.held is None:
        acc = y[keep, 2 * nv : 3 * nv] + force[keep] @ model.force_input[nv : 2 * nv].T
    else:  # the kept accelerations' feedthrough of the force (a held coordinate's acceleration is zero)
        acc = y[keep, 2 * nv : 3 * nv] + force[keep] @ model.output_maps()[1][2 * nv :].T
    rad = y[keep, 3 * nv :] if with_radiation else np.zeros((acc.shape[0], n_h))
    xi, rate = _coordinates(model, y, force), y[:, nv : 2 * nv]
    stroke = stroke0[None] + xi @ g.T
    stroke_rate = rate @ g.T
    pto_force = pto_control_force(applied, model.pto_damping, model.pto_stiffness, stroke, stroke_rate)
    pto_force -= p.pto_spring * stroke  # the device spring
    sampled = not (compiled.linear_controller or n_pto == 0)
    # a sampled controller's force is held over each step: its work is exact; a continuous law (linear gains, also
    # where the limits make this run hold it over each step) keeps the quadrature of its power at the steps
    power = (
        held_power(applied, stroke, compiled.dt)
        if sampled
        else continuous_power(compiled, stroke, stroke_rate, pto_force)
    )
    stats = window_statistics(compiled, stroke, power)
    run_time = _time.perf_counter() - start
    assert model.radiation is not None
    solver = {
        "solver": f"linear ({hold}, exact discretisation in {model.modal_form.n_modes} modal coordinates)",
        "radiation": f"state space, {model.radiation.n_states} real states (linear model)",
    }
    if closed and limited:
        solver["solver"] += "; PTO limits as a force held over each step"
    series = {
        "q": (compiled.q0[None] + xi)[keep], "v": rate[keep], "a": acc, "x": stroke[keep], "xd": stroke_rate[keep],
        "f": pto_force[keep], "rad": rad, "exc": exc[keep], "terms": no_terms(compiled, acc.shape[0]),
        "p": power[keep],
    }  # fmt: skip
    return Record(
        time=time[keep],
        series=series,
        stats=stats,
        run_time=run_time,
        solver=solver,
        limits=limit_counts(stroke[1:], wanted[1:], (p.pto_force_limit, p.pto_stroke_limit)),
    )


def _initial_state(compiled: ControlledScene, model: LinearModel) -> np.ndarray | None:
    """The linear model's initial state for the scene's ``[initial]`` (None: at rest in the equilibrium): the
    displacement and velocity increments as xi and xi_dot, no radiation memory.

    Raises
    ------
    SceneError
        If it gives a coordinate held quasi-static a displacement or a velocity (the condensed model has neither).
    """
    if compiled.scene.initial.at_rest:
        return None
    delta, velocity = initial_increments(compiled.scene, compiled.device)
    nv = model.mass.shape[0]
    x0 = np.zeros(model.n_states)
    if model.held is not None:  # the kept coordinates' (the held ones' values follow from their equations)
        given = model.held & ((delta != 0) | (velocity != 0))
        if np.any(given):
            names = [name for name, g in zip(compiled.device.model.velocity_names, given, strict=True) if g]
            raise SceneError(
                f"initial.displacement or initial.velocity gives {names} a value, and they are held quasi-static "
                "(flexible.quasi_static_above): in the linear model their values follow from their equations and "
                "they have no rate; leave them out"
            )
        kept = ~model.held
        n_r = int(np.count_nonzero(kept))
        x0[:n_r], x0[n_r : 2 * n_r] = delta[kept], velocity[kept]
        return x0
    x0[:nv], x0[nv : 2 * nv] = delta, velocity
    return x0


def _output_rows(model: LinearModel, with_radiation: bool) -> np.ndarray:
    """Output rows of a linear run: xi, xi_dot, the acceleration's state part and (if asked for) the radiation
    force (with held coordinates, ``LinearModel.output_maps``'s rows: the state's part of each)."""
    nv, n_h = model.mass.shape[0], model.hydro_jacobian.shape[0]
    rows = np.zeros((3 * nv + (n_h if with_radiation else 0), model.n_states))
    if model.held is None:
        rows[: 2 * nv, : 2 * nv] = np.eye(2 * nv)
        rows[2 * nv : 3 * nv] = np.asarray(model.state_space.A)[nv : 2 * nv]
    else:
        rows[: 3 * nv] = model.output_maps()[0]
    if with_radiation:
        assert model.radiation is not None
        rows[3 * nv :, 2 * model.n_kept :] = -model.radiation.C
    return rows


def _coordinates(model: LinearModel, y: np.ndarray, force: np.ndarray) -> np.ndarray:
    """The generalised displacements xi (n_t, nv) of a linear run's outputs ``y`` (:func:`_output_rows`) and its
    generalised forces ``force`` (n_t, nv): the held coordinates' values take their feedthrough."""
    if model.held is None:
        return y[:, : model.mass.shape[0]]
    nv = model.mass.shape[0]
    return y[:, :nv] + force @ model.output_maps()[1][:nv].T


def _linear_state(model: LinearModel, x: np.ndarray) -> np.ndarray:
    """The measurement's state of a linear run: q0 + xi, xi_dot and the radiation states (with coordinates held
    quasi-static, the condensed model's state: the kept coordinates' q0 + xi, their rates and the radiation
    states)."""
    if model.held is not None:
        out = x.copy()
        out[: model.n_kept] += model.q0[~model.held]
        return out
    nv = model.mass.shape[0]
    out = x.copy()
    out[:nv] += model.q0
    return out


def _feedback(compiled: ControlledScene, model: LinearModel, applied: np.ndarray, wanted: np.ndarray) -> Feedback:
    """The PTO force of a closed linear run held over each step: the controller's (at its control period, or the
    scene's linear gains at every step), saturated at the force limits, plus the end stops. Writes the
    controller's part into ``applied`` and its unsaturated wish into ``wanted`` (per step)."""
    p = compiled.plant
    time, stroke0 = compiled.time, model.pto_stroke
    loop = None if compiled.linear_controller else ControlLoop.start(compiled)
    control_steps = compiled.scene.control_steps
    held = np.zeros(p.pto_kind.size)

    def feedback(k: int, stroke: np.ndarray, rate: np.ndarray, state: Callable[[], np.ndarray]) -> np.ndarray:
        nonlocal held
        x = stroke0 + stroke
        if np.any((np.abs(x) > p.pto_stroke_limit) & (p.pto_stop_stiffness == 0)):
            raise PtoLimitExceeded(
                f"a PTO stroke passed its stroke_limit at t = {time[k]:.6g} s (step {k}) and the PTO has no end "
                "stop: give end_stop_stiffness in the device spec for one, or reduce the motion",
                float(time[k]),
                k,
                {"x": state()},
            )
        if loop is None:  # the scene's linear gains, taken out of the model, act held and limited
            wanted[k] = pto_control_force(0.0, p.pto_damping, p.pto_stiffness, x, rate)
            applied[k] = saturate(wanted[k], p.pto_force_limit)
        else:
            if k % control_steps == 0:  # a control step: the force is held until the next one
                held = loop.force(float(time[k]), x, rate, lambda: _linear_state(model, state()))
            wanted[k] = held
            applied[k] = saturate(held, p.pto_force_limit)
        return applied[k] + end_stop_force(p, x, rate)

    return feedback
