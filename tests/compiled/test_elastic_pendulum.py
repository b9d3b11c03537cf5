"""The free flexible pendulum through the compiled kernels (issue 28): a pinned beam released horizontal, no
damping, integrated by classic RK4 at a step that carries its elastic modes, on the kernels' accelerations; its
total energy (kinetic, gravity, strain: from the multibody core, not the kernels) stays constant to 1e-7 of
m g L / 2."""

from __future__ import annotations

import numpy as np
import pytest

from tests.multibody.elastic_models import hinged_beam
from wecss.compiled import build_plant
from wecss.compiled.kernels import accelerations
from wecss.multibody import Dynamics, elastic_energy, potential_energy

LENGTH, G = 2.0, 9.81


def _drift(swings: int, steps_per_period: int) -> tuple[float, float]:
    """The largest |E - E0| / (m g L / 2) over ``swings`` periods T = 2 pi sqrt(2 L / 3 g) of the pendulum (checked
    every 50 steps), and h omega of its fastest mode hanging."""
    model = hinged_beam(LENGTH, 2.0e3, 3.0, 1e6, axis=(0.0, 1.0, 0.0), elements=8, n_modes=2, inertia_relief=False,
                        centrifugal=False)  # fmt: skip
    plant = build_plant(model, None, (), G)
    dyn = Dynamics(model)
    none = (np.zeros(0), np.zeros((0, 0)), np.zeros(0))

    def rate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
        return accelerations(plant, q, v, *none)[0]

    def energy(q: np.ndarray, v: np.ndarray) -> float:
        return dyn.kinetic_energy(q, v) + potential_energy(model, q, G) + elastic_energy(model, q)

    period = 2 * np.pi * np.sqrt(2 * LENGTH / (3 * G))
    h = period / steps_per_period
    q, v = np.zeros(3), np.zeros(3)
    e0, scale = energy(q, v), model.bodies[1].mass * G * LENGTH / 2
    worst = 0.0
    for k in range(swings * steps_per_period):
        a1 = rate(q, v)
        a2 = rate(q + h / 2 * v, v + h / 2 * a1)
        a3 = rate(q + h / 2 * (v + h / 2 * a1), v + h / 2 * a2)
        a4 = rate(q + h * (v + h / 2 * a2), v + h * a3)
        q, v = q + h * v + h * h / 6 * (a1 + a2 + a3), v + h / 6 * (a1 + 2 * a2 + 2 * a3 + a4)
        if k % 50 == 49:
            worst = max(worst, abs(energy(q, v) - e0))
    hanging = np.array([np.pi / 2, 0.0, 0.0])
    stiffness = np.zeros((3, 3))  # the structure's, hanging (gravity's pendulum stiffness is far below)
    stiffness[1:, 1:] = model.bodies[1].elastic.invariants.modal_stiffness  # type: ignore[union-attr]
    mass = dyn.terms(hanging, np.zeros(3)).mass
    fastest = float(np.sqrt(np.linalg.eigvals(np.linalg.solve(mass, stiffness)).real.max()))
    return worst / scale, fastest * h


def test_rk4_on_the_kernels_keeps_the_flexible_pendulum_s_energy() -> None:
    drift, h_omega = _drift(2, 2000)
    print(f"flexible pendulum, RK4 on the kernels, 2 periods at T/2000 (h omega {h_omega:.3f}): {drift:.2e}")
    assert drift < 1e-7


@pytest.mark.slow
def test_rk4_on_the_kernels_keeps_the_flexible_pendulum_s_energy_over_100_swings() -> None:
    drift, h_omega = _drift(100, 4000)
    print(f"flexible pendulum, RK4 on the kernels, 100 periods at T/4000 (h omega {h_omega:.3f}): {drift:.2e}")
    assert drift < 1e-7
