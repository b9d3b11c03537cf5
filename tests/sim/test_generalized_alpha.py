"""The generalised-alpha integrator: closed forms on a linear oscillator (the spectral radius at infinite frequency,
second order, the trapezoidal rule's exact energy) and the free flexible pendulum (a pinned beam released
horizontal, no damping) at the wave step with its modes unresolved."""

from __future__ import annotations

import numpy as np
import pytest

from tests.multibody.elastic_models import hinged_beam
from wecss.multibody import Dynamics, elastic_energy, gravity_force, potential_energy, structural_force
from wecss.sim._generalized_alpha import GeneralizedAlpha, NewtonFailure, alpha_step, start


def _oscillator(omega: float, h: float, steps: int, rho: float) -> tuple[np.ndarray, np.ndarray]:
    scheme = GeneralizedAlpha(rho)
    factors = scheme.iteration_matrix(np.eye(1), np.zeros((1, 1)), omega**2 * np.eye(1), h)
    state = start([1.0], [0.0], [-(omega**2)])
    qs, vs = [], []
    for _ in range(steps):
        state, _ = alpha_step(scheme, state, h, lambda q, v, a, t: a + omega**2 * q, lambda q, dv: q + dv, factors)
        qs.append(state.q[0])
        vs.append(state.v[0])
    return np.array(qs), np.array(vs)


@pytest.mark.parametrize("rho", [0.0, 0.5, 0.8, 1.0])
def test_modes_far_above_the_step_are_damped_to_the_spectral_radius(rho: float) -> None:
    """h omega = 1e4: the one-step map of a linear oscillator's (q, v / omega, a / omega^2), found by stepping from
    each unit state, has the characteristic polynomial (lambda + rho_inf)^3 (Chung and Hulbert's design: the
    principal and the spurious root all at -rho_inf; compared by its coefficients, as the triple root's numerical
    eigenvalues are sensitive)."""
    omega, h = 1e4, 1.0
    scheme = GeneralizedAlpha(rho)
    factors = scheme.iteration_matrix(np.eye(1), np.zeros((1, 1)), omega**2 * np.eye(1), h)
    columns = []
    for unit in np.eye(3):
        q, v, a = unit[:1], omega * unit[1:2], omega**2 * unit[2:]
        state = start(q, v, -(omega**2) * q)
        state.a = a
        state, _ = alpha_step(scheme, state, h, lambda q, v, a, t: a + omega**2 * q, lambda q, dv: q + dv, factors)
        columns.append([state.q[0], state.v[0] / omega, state.a[0] / omega**2])
    amplification = np.array(columns).T
    minors = sum(np.linalg.det(np.delete(np.delete(amplification, k, 0), k, 1)) for k in range(3))
    coefficients = [np.trace(amplification), minors, np.linalg.det(amplification)]
    np.testing.assert_allclose(coefficients, [-3 * rho, 3 * rho**2, -(rho**3)], rtol=0, atol=1e-6)


def test_second_order_and_the_trapezoidal_rule_keeps_a_linear_oscillator_s_energy() -> None:
    omega, end = 2.0, 10.0
    errors = []
    for h in (0.02, 0.01):
        q, _ = _oscillator(omega, h, round(end / h), 0.8)
        errors.append(abs(q[-1] - np.cos(omega * end)))
    assert np.log2(errors[0] / errors[1]) == pytest.approx(2.0, abs=0.1)
    q, v = _oscillator(omega, 0.05, 2000, 1.0)
    energy = 0.5 * v**2 + 0.5 * omega**2 * q**2
    assert np.abs(energy / 2.0 - 1).max() < 1e-12


def test_a_newton_failure_says_what_to_do() -> None:
    scheme = GeneralizedAlpha(0.8, max_iterations=2)
    factors = scheme.iteration_matrix(np.eye(1), np.zeros((1, 1)), np.eye(1), 0.1)  # a poor matrix: stiffness 1e6
    with pytest.raises(NewtonFailure, match=r"did not converge in 2 iterations.*smaller step"):
        alpha_step(scheme, start([1.0], [0.0], [-1e6]), 0.1, lambda q, v, a, t: a + 1e6 * q, lambda q, dv: q + dv,
                   factors)  # fmt: skip


def _pendulum_drift(swings: int) -> tuple[float, float]:
    """The largest |E - E0| / (m g L / 2) of the free flexible pendulum over ``swings`` periods of small swings,
    at the step T/200 (T = 2 pi sqrt(2 L / 3 g)), with rho_inf = 1; and the ratio of the first elastic mode's frequency
    to the step's Nyquist-like 1 / h."""
    length, g = 2.0, 9.81
    model = hinged_beam(length, 2.0e3, 3.0, 1e6, axis=(0.0, 1.0, 0.0), elements=8, n_modes=2, inertia_relief=False,
                        centrifugal=False)  # fmt: skip
    dyn = Dynamics(model)
    gravity = gravity_force(model, g)

    def force(q: np.ndarray, v: np.ndarray) -> np.ndarray:
        terms = dyn.terms(q, v)
        return terms.state.B.T @ (gravity + structural_force(model, q, v)) - terms.nonlinear @ v

    def residual(q: np.ndarray, v: np.ndarray, a: np.ndarray, _t: float) -> np.ndarray:
        terms = dyn.terms(q, v)
        return terms.mass @ a + terms.nonlinear @ v - terms.state.B.T @ (gravity + structural_force(model, q, v))

    def energy(q: np.ndarray, v: np.ndarray) -> float:
        return dyn.kinetic_energy(q, v) + potential_energy(model, q, g) + elastic_energy(model, q)

    # the tangent stiffness of the hanging pendulum: the modified Newton matrix, with the mass at each step
    hanging, rest, eps = np.array([np.pi / 2, 0.0, 0.0]), np.zeros(3), 1e-6
    stiffness = -np.array([(force(hanging + eps * e, rest) - force(hanging - eps * e, rest)) / (2 * eps)
                           for e in np.eye(3)]).T  # fmt: skip
    period = 2 * np.pi * np.sqrt(2 * length / (3 * g))
    h = period / 200
    scheme = GeneralizedAlpha(1.0, tolerance=1e-11)
    q, v = np.zeros(3), np.zeros(3)
    state = start(q, v, np.linalg.solve(dyn.terms(q, v).mass, force(q, v)))
    e0, scale = energy(q, v), model.bodies[1].mass * g * length / 2
    worst = 0.0
    for _ in range(round(swings * period / h)):
        state, _ = alpha_step(
            scheme, state, h, residual, lambda q, dv: q + dv,
            lambda q, v: scheme.iteration_matrix(dyn.terms(q, v).mass, np.zeros((3, 3)), stiffness, h),
        )  # fmt: skip
        worst = max(worst, abs(energy(state.q, state.v) - e0))
    mode = np.sqrt(np.linalg.eigvals(np.linalg.solve(dyn.terms(hanging, rest).mass, stiffness)).real.max())
    return worst / scale, mode * h


def test_a_free_flexible_pendulum_keeps_its_energy_at_the_wave_step() -> None:
    """Released horizontal: 5 periods at T/200 with the beam's first pinned-free mode (132 rad/s) at h omega = 1.5
    (unresolved by an explicit scheme of this step): the energy stays within 1e-4 of m g L / 2."""
    drift, h_omega = _pendulum_drift(5)
    print(f"flexible pendulum, 5 periods at T/200 (h omega of its mode {h_omega:.2f}): energy within {drift:.2e}")
    assert h_omega > 1.0
    assert drift < 1e-4


@pytest.mark.slow
def test_a_free_flexible_pendulum_keeps_its_energy_over_100_swings() -> None:
    drift, _ = _pendulum_drift(100)
    print(f"flexible pendulum, 100 periods at T/200: energy within {drift:.2e} of m g L / 2")
    assert drift < 1e-4
