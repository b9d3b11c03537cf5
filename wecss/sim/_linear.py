"""Linear runs: the scene's linear model stepped exactly (``solver.method = "linear"``), open loop for a controller
with linear gains (folded into the model) or closed by any other controller."""

from __future__ import annotations

import time as _time
from pathlib import Path

import numpy as np
import xarray as xr

from ..compiled import CompiledScene, compile_scene
from ..linear import LinearModel, closed_loop, linearize, open_loop
from ..scene import LINEAR_HOLDS, Scene
from ._control import controller_force, start_controller
from ._result import Record, build_result, window_statistics


def simulate_linear(
    compiled: CompiledScene | Scene | str | Path, model: LinearModel | None = None, *, hold: str = "foh"
) -> xr.Dataset:
    """Time-domain run of the linear model on the scene's waves, with the exact discretisation (in modal
    coordinates: see ``wecss.linear.ModalForm``).

    A controller with linear gains is folded into the model (open loop in the remaining inputs). Any other
    controller closes the loop: it is called once per control period (``controller.dt``, default every step)
    with the PTO strokes and rates and its force is held until the next call (zero-order hold, as in the
    nonlinear simulator); the excitation keeps the ``hold`` given. ``simulate`` runs this for scenes with
    ``solver.method = "linear"``; call it directly for another ``model`` (a reduced one, say).

    ``compiled`` may also be a scene or a scene file (compiled here). Returns a Dataset laid out as
    :func:`wecss.sim.simulate`'s (so every metric works on both).

    Raises
    ------
    ValueError
        For a device with a free base (its coordinates are not linear), an unknown ``hold``, or a scene whose
        radiation memory is not a state-space model (``wecss.linear.NoStateSpace``).
    """
    if isinstance(compiled, str | Path):
        compiled = Scene.from_toml(compiled)
    if isinstance(compiled, Scene):
        compiled = compile_scene(compiled)
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
    exc = (
        np.ascontiguousarray(compiled.excitation.force(time).T)
        if compiled.excitation is not None
        else np.zeros((time.size, n_h))
    )
    force = exc @ model.hydro_jacobian  # generalised excitation (n_t, nv)
    stroke0 = model.pto_stroke
    # outputs: xi, xi_dot, the acceleration's state part and (if asked for) the radiation force
    n_states = model.n_states
    with_radiation = "radiation" in compiled.scene.outputs.variables
    rows = np.zeros((3 * nv + (n_h if with_radiation else 0), n_states))
    rows[: 2 * nv, : 2 * nv] = np.eye(2 * nv)
    rows[2 * nv : 3 * nv] = np.asarray(model.state_space.A)[nv : 2 * nv]
    if with_radiation:
        assert model.radiation is not None
        rows[3 * nv :, 2 * nv :] = -model.radiation.C
    if compiled.linear_controller or n_pto == 0:
        command = np.zeros((time.size, n_pto))
        y = open_loop(model, compiled.dt, hold, force, rows)
    else:
        start_controller(compiled)

        def feedback(k: int, stroke: np.ndarray, rate: np.ndarray) -> np.ndarray:
            return controller_force(compiled, float(time[k]), stroke0 + stroke, rate)

        y, command = closed_loop(model, compiled.dt, hold, force, rows, feedback, compiled.scene.control_steps)
        # recorded at t_k, as by the nonlinear simulator: the force that acted over the step ending at t_k
        command = np.concatenate([np.zeros((1, n_pto)), command[:-1]])
        force += command @ g
    every = compiled.scene.outputs.every
    keep = slice(None, None, every)
    acc = y[keep, 2 * nv : 3 * nv] + force[keep] @ model.force_input[nv : 2 * nv].T
    rad = y[keep, 3 * nv :] if with_radiation else np.zeros((acc.shape[0], n_h))
    xi, rate = y[:, :nv], y[:, nv : 2 * nv]
    stroke = stroke0[None] + xi @ g.T
    stroke_rate = rate @ g.T
    pto_force = command - (p.pto_spring + p.pto_stiffness) * stroke - p.pto_damping * stroke_rate
    stats = window_statistics(compiled, stroke, stroke_rate, pto_force)
    run_time = _time.perf_counter() - start
    assert model.radiation is not None
    solver = {
        "solver": f"linear ({hold}, exact discretisation in {model.modal_form.n_modes} modal coordinates)",
        "radiation": f"state space, {model.radiation.n_states} real states (linear model)",
    }
    record = Record(
        time[keep], (compiled.q0[None] + xi)[keep], rate[keep], acc, stroke[keep], stroke_rate[keep],
        pto_force[keep], rad, exc[keep], stats, run_time, solver,
    )  # fmt: skip
    return build_result(compiled, record)
