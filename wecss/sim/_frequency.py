"""Frequency-domain runs (``solver.method = "frequency"``): the exact steady state of the linearised equations on
the scene's wave components, evaluated at the scene's time steps and laid out as every other result."""

from __future__ import annotations

import time as _time
from typing import Any

import numpy as np

from ..compiled import pto_control_force
from ..control import ControlledScene
from ..linear import linearize, response_amplitudes
from ..scene import Capabilities, Runner, SceneError
from ..waves import evaluate
from ._load_amplitudes import Spectral
from ._record import Record, continuous_power, no_terms, window_statistics


class FrequencyDomain(Runner):
    """The exact frequency-domain steady state at the scene's steps (see :func:`run_frequency_domain`)."""

    name = "frequency"
    description = "the exact frequency-domain steady state of the linearised equations, from A(omega) and B(omega)"
    tolerance_reason = ": it has no step error (the exact steady state at the scene's steps, whatever dt)"
    capabilities = Capabilities(
        memory_model=False,
        sampled_controllers=False,
        free_base=False,
        transient=False,
        hydrodynamics=("drag",),
        order=0,
        quasi_static=True,
    )

    def check_compiled(self, compiled: Any) -> None:
        super().check_compiled(compiled)
        if compiled.scene.hydrodynamics.drag and compiled.plant.viscous.morison_body.size:
            raise SceneError(
                f"solver.method {self.name!r} linearises the body drag but not the Morison elements of "
                f"{compiled.device.name!r} (their drag and fluid inertia): use a nonlinear runner such as 'beeman'"
            )

    def run(self, controlled: ControlledScene, *, progress: bool = False, stream: Any = None) -> Record:
        return run_frequency_domain(controlled)


FREQUENCY = FrequencyDomain()


def run_frequency_domain(compiled: ControlledScene) -> Record:
    """The steady state at every step (no ramp, no transient), from the database's A(omega) and B(omega). PTO
    limits are not applied (the solution is linear); where the device declares them, the result's ``pto_limits``
    attribute says how close the steady state comes to them.

    Raises
    ------
    ValueError
        For a device with a free base (its coordinates are not linear).

    Modal coordinates held quasi-static (``flexible.quasi_static_above``) are condensed in the linear model
    (``wecss.linear.linearize``): their values move, their rates and accelerations are zero, as a generalised-alpha
    run records them, and so is their part of the PTO stroke rates and of the hydro velocities.
    """
    if compiled.device.model.nq != compiled.device.model.nv:
        raise ValueError("the frequency-domain run needs joint coordinates (no free base)")
    model = linearize(compiled)
    start = _time.perf_counter()
    p = compiled.plant
    time = compiled.time
    nv, n_h = model.mass.shape[0], model.hydro_jacobian.shape[0]
    keep = slice(None, None, compiled.scene.outputs.every)
    if compiled.excitation is None:  # calm water: the equilibrium
        omega = np.zeros(0)
        coefficients = np.zeros((n_h, 0), dtype=complex)
        amplitudes = np.zeros((nv, 0), dtype=complex)
    else:
        omega, coefficients = compiled.excitation.omega, compiled.excitation.coefficients
        amplitudes = response_amplitudes(model, omega, coefficients)  # (nv, n_w)
    moving = amplitudes  # the amplitudes the rates and accelerations see: none of a held coordinate
    if model.held is not None:
        moving = amplitudes.copy()
        moving[model.held] = 0.0

    def signal(values: np.ndarray, times: np.ndarray) -> np.ndarray:
        """Re[sum_k values[:, k] exp(i omega_k t)] at ``times`` (n_t, n_rows)."""
        if omega.size == 0:
            return np.zeros((times.size, values.shape[0]))
        return np.real(evaluate(values, omega, times)).T

    xi = signal(amplitudes, time)
    rate = signal(1j * omega * moving, time)
    stroke = model.pto_stroke[None] + xi @ model.pto_jacobian.T
    stroke_rate = rate @ model.pto_jacobian.T
    pto_force = pto_control_force(0.0, p.pto_damping, p.pto_stiffness, stroke, stroke_rate) - p.pto_spring * stroke
    power = continuous_power(compiled, stroke, stroke_rate, pto_force)  # linear gains: a continuous force
    stats = window_statistics(compiled, stroke, power)
    saved = time[keep]
    velocity_hat = 1j * omega * (model.hydro_jacobian @ moving)  # hydro-DOF velocities (n_h, n_w)
    added, damping = model.hydro.at(omega)
    memory_hat = -np.einsum("wij,jw->iw", damping + 1j * omega[:, None, None] * added, velocity_hat)
    series = {
        "q": compiled.q0[None] + xi[keep],
        "v": rate[keep],
        "a": signal(-(omega**2) * moving, saved),
        "x": stroke[keep],
        "xd": stroke_rate[keep],
        "f": pto_force[keep],
        "rad": signal(memory_hat, saved),
        "exc": signal(coefficients, saved),
        "terms": no_terms(compiled, saved.size),
        "p": power[keep],
    }
    record = Record(
        time=saved,
        series=series,
        stats=stats,
        run_time=0.0,
        solver={
            "solver": "frequency (exact steady state from A(omega) and B(omega); no ramp, no transient)",
            "radiation": "frequency domain: A(omega) and B(omega) of the database (no memory model)",
        },
    )
    record.run_time = _time.perf_counter() - start
    stroke_hat = model.pto_jacobian @ amplitudes
    rate_hat = 1j * omega * stroke_hat if model.held is None else 1j * omega * (model.pto_jacobian @ moving)
    rest = model.pto_stroke
    c, k, spring = p.pto_damping[:, None], p.pto_stiffness[:, None], p.pto_spring[:, None]
    record.spectral = Spectral(
        omega,
        {"q": compiled.q0, "v": np.zeros(nv), "a": np.zeros(nv), "x": rest, "xd": np.zeros_like(rest),
         "f": pto_control_force(0.0, p.pto_damping, p.pto_stiffness, rest, 0.0) - p.pto_spring * rest,
         "h": np.zeros(n_h)},
        {"q": amplitudes, "v": 1j * omega * moving, "a": -(omega**2) * moving, "x": stroke_hat,
         "xd": rate_hat,
         "f": pto_control_force(0.0, c, k, stroke_hat, rate_hat) - spring * stroke_hat,
         "h": memory_hat + coefficients},
    )  # fmt: skip
    limits = (p.pto_force_limit, p.pto_stroke_limit)
    if np.any(np.isfinite(limits[0])) or np.any(np.isfinite(limits[1])):  # declared: say what they would do
        control = pto_force + p.pto_spring * stroke
        reached = [np.max(np.abs(v), axis=0) / lim for v, lim in ((control, limits[0]), (stroke, limits[1]))]
        record.solver["pto_limits"] = (
            "not applied (the frequency domain is linear): the largest force and stroke reach "
            f"{np.max(reached[0]):.3g} and {np.max(reached[1]):.3g} of their limits"
        )
    return record
