"""The nonlinear equations of a compiled scene in a linear model's states, and their Jacobian by central
differences: the oracle of the tests that check a state matrix (``test_model``, ``tests/sim/test_elastic_runs``)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from wecss.compiled.kernels import accelerations, integrate_configuration
from wecss.linear import LinearModel
from wecss.sim import CompiledScene


def state_derivative(compiled: CompiledScene, model: LinearModel) -> Callable[[np.ndarray], np.ndarray]:
    """The right-hand side x -> dx/dt of the compiled plant's equations (its kernels) in ``model``'s states: the
    configuration's increment from the equilibrium q0, the velocities and the radiation states (their memory force
    -C r on the hydro DOFs, driven by the hydro velocities); no excitation and no PTO command."""
    p, rad = compiled.plant, model.radiation
    assert rad is not None
    nv, n_h = model.mass.shape[0], p.hydro_index.size

    def rhs(x: np.ndarray) -> np.ndarray:
        xi, rate, r = x[:nv], x[nv : 2 * nv], x[2 * nv :]
        q = integrate_configuration(p, compiled.q0, xi)
        a, u, *_ = accelerations(p, q, rate, -(rad.C @ r), np.zeros((n_h, n_h)), np.zeros(p.pto_kind.size))
        return np.concatenate([rate, a, rad.A @ r + rad.B @ u])

    return rhs


def central_jacobian(f: Callable[[np.ndarray], np.ndarray], steps: np.ndarray) -> np.ndarray:
    """The Jacobian of ``f`` at zero by central differences, column k with the step ``steps[k]``."""
    columns = []
    for k, size in enumerate(steps):
        step = np.zeros(steps.size)
        step[k] = size
        columns.append((f(step) - f(-step)) / (2 * size))
    return np.stack(columns, axis=1)
