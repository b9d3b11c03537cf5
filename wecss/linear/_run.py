"""Runs of a linear model on given generalised forces: open loop (every step at once, in modal coordinates) or
closed by a feedback called once per control period, its force held over the period."""

from __future__ import annotations

import functools
from collections.abc import Callable

import numpy as np

from ._modal_recursion import input_forcing, outputs, real_part_rows, run
from ._model import LinearModel

Feedback = Callable[[int, np.ndarray, np.ndarray, Callable[[], np.ndarray]], np.ndarray]
"""``feedback(k, stroke, rate, state) -> force``: the PTO forces [N or N m] held over the step from k to k + 1,
from the strokes (from the equilibrium) and rates at step k; ``state()`` gives the model's state x at step k."""


def open_loop(
    model: LinearModel, dt: float, hold: str, force: np.ndarray, rows: np.ndarray, x0: np.ndarray | None = None
) -> np.ndarray:
    """Outputs ``rows @ x`` (n_t, n_out) at every step of the exact ``hold`` discretisation for the generalised
    forces ``force`` (n_t, nv) [one row per step of ``dt`` s], from the state ``x0`` (default: rest)."""
    return run(model.modal_form, model.modal_steps(dt, hold), force, rows, x0)


def closed_loop(
    model: LinearModel,
    dt: float,
    hold: str,
    force: np.ndarray,
    rows: np.ndarray,
    feedback: Feedback,
    x0: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Outputs ``rows @ x`` (n_t, n_out) and the PTO forces (n_t, n_pto), the force at row k acting over the step
    from k to k + 1 (the last row's is zero): ``feedback`` is called at every step but the last and its force held
    (zero-order hold) over the step, while the generalised forces ``force`` keep the ``hold`` given; from the state
    ``x0`` (default: rest). With coordinates held quasi-static (``model.held``) the strokes measured at step k take
    the held values there (``LinearModel.output_maps``: fed through by the generalised force at k, the excitation's
    and the command of the step before, as a nonlinear run's configuration at k); ``rows`` give the state's part
    only."""
    form, steps = model.modal_form, model.modal_steps(dt, hold)
    nv, n_pto = model.mass.shape[0], model.pto_jacobian.shape[0]
    g = model.pto_jacobian
    n_t = force.shape[0]
    held = model.modal_steps(dt, "zoh")  # the PTO force is held over each step
    held_modes = held.input0 @ g.T  # (n_modes, n_pto)
    held_free = held.free_input0 @ g.T
    # strokes and rates from the modal coordinates and the free states
    measure = np.zeros((2 * n_pto, model.n_states))
    through = None
    if model.held is None:
        measure[:n_pto, :nv] = g
        measure[n_pto:, nv : 2 * nv] = g
    else:  # held coordinates condensed: their values are outputs, fed through by the generalised force
        rows, feed = model.output_maps()
        measure[:n_pto] = g @ rows[:nv]
        measure[n_pto:] = g @ rows[nv : 2 * nv]
        through = g @ feed[:nv]  # (n_pto, nv)
    measure_modes, measure_free = form.output_maps(measure)
    forcing, free_forcing = input_forcing(steps, force)
    free_modes = real_part_rows(steps.free_state.T)
    z = np.zeros((n_t, form.n_modes), dtype=complex)
    free = np.zeros((n_t, form.free.size))
    command = np.zeros((n_t, n_pto))
    if x0 is not None:
        z[0] = form.inverse @ np.asarray(x0, dtype=float)[form.rest]
        free[0] = np.asarray(x0, dtype=float)[form.free]

    def state_at(k: int) -> np.ndarray:
        x = np.zeros(model.n_states)
        x[form.rest] = np.real(form.shapes @ z[k])
        x[form.free] = free[k]
        return x

    for k in range(n_t - 1):  # the force of the last row would act beyond the run
        measured = z[k].view(np.float64) @ measure_modes + free[k] @ measure_free
        if through is not None:  # the held values at step k: the force now, the command of the step before
            measured[:n_pto] += through @ (force[k] + (g.T @ command[k - 1] if k else 0.0))
        out = feedback(k, measured[:n_pto], measured[n_pto:], functools.partial(state_at, k))
        command[k] = out
        z[k + 1] = steps.decay * z[k] + forcing[k] + held_modes @ out
        free[k + 1] = free[k] + z[k].view(np.float64) @ free_modes + free_forcing[k] + held_free @ out
    return outputs(form, rows, z, free), command
