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


def held_state_derivative(compiled: CompiledScene, model: LinearModel) -> Callable[[np.ndarray], np.ndarray]:
    """As :func:`state_derivative` for a model whose held coordinates (``model.held``) are condensed out of its
    states [xi_r, xi_dot_r, r]: at each state the held coordinates' values solve their algebraic equations, the
    kernels' accelerations of the held coordinates zero with their rates zero (what the generalised-alpha runner
    solves), by Newton's method with the derivative of those accelerations taken once at the equilibrium by central
    differences; the kept coordinates' accelerations are then the kernels' at that configuration."""
    p, rad, held = compiled.plant, model.radiation, model.held
    assert rad is not None and held is not None
    kept, out = np.flatnonzero(~held), np.flatnonzero(held)
    nv, n_r, n_h = held.size, kept.size, p.hydro_index.size

    def accelerations_at(xi: np.ndarray, rate: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        q = integrate_configuration(p, compiled.q0, xi)
        a, u, *_ = accelerations(p, q, rate, -(rad.C @ r), np.zeros((n_h, n_h)), np.zeros(p.pto_kind.size))
        return a, u

    at_rest = (np.zeros(nv), np.zeros(nv), np.zeros(rad.n_states))
    derivative = np.zeros((out.size, out.size))
    for k, c in enumerate(out):
        step = np.zeros(nv)
        step[c] = 1e-7
        plus = accelerations_at(at_rest[0] + step, *at_rest[1:])[0][out]
        minus = accelerations_at(at_rest[0] - step, *at_rest[1:])[0][out]
        derivative[:, k] = (plus - minus) / 2e-7

    def rhs(x: np.ndarray) -> np.ndarray:
        xi = np.zeros(nv)
        rate = np.zeros(nv)  # a held coordinate has no rate
        xi[kept], rate[kept], r = x[:n_r], x[n_r : 2 * n_r], x[2 * n_r :]
        for _ in range(50):
            a, u = accelerations_at(xi, rate, r)
            change = np.linalg.solve(derivative, a[out])
            xi[out] -= change
            if np.abs(change).max() <= 1e-17:
                break
        a, u = accelerations_at(xi, rate, r)
        return np.concatenate([x[n_r : 2 * n_r], a[kept], rad.A @ r + rad.B @ u])

    return rhs
