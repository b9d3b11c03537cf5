"""Frequency-domain control design against closed forms (issue 13): the complex-conjugate bound |F|^2 / (8 B),
optimal damping |F|^2 / (4 (B + |Z|)) at c = |Z|, the reactive optimum that reaches the bound, on a one-DOF body
built by hand; and on m4-134 the ordering bound >= optimal spring-damper >= optimal damping >= damping 6, each
optimum better than its neighbours, and the frequency-domain power against the linear time-domain simulation."""

from __future__ import annotations

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.control import compile_scene
from wecss.control.design import gains_power, optimal_damping, optimal_spring_damper, power_bound
from wecss.linear import HydroResponse, LinearModel
from wecss.sim import simulate

MASS, STIFFNESS = 2.0e3, 3.0e4  # a heaving body [kg], hydrostatics [N/m]


def _one_dof(omega_data: np.ndarray) -> LinearModel:
    """A heaving body with A(omega) - A_inf = 800 / (1 + omega^2) kg and B(omega) = 300 omega^2 exp(-omega) N s/m,
    the PTO on the heave coordinate (stroke = heave)."""
    added = (800.0 / (1.0 + omega_data**2))[:, None, None]
    damping = (300.0 * omega_data**2 * np.exp(-omega_data))[:, None, None]
    one = np.ones((1, 1))
    return LinearModel(
        mass=(MASS + 500.0) * one, damping=0 * one, stiffness=STIFFNESS * one, database_mass=(MASS + 500.0) * one,
        hydro_jacobian=one, pto_jacobian=one, hydro=HydroResponse(omega_data, added, damping), q0=np.zeros(1),
        pto_stroke=np.zeros(1), pto_damping=np.zeros(1), pto_stiffness=np.zeros(1), radiation=None, system=None,
    )  # fmt: skip


@pytest.mark.parametrize("omega", [1.5, 3.0, 5.0])
def test_one_dof_closed_forms(omega):
    data = np.unique(np.concatenate([np.linspace(0.1, 10.0, 400), [omega]]))  # omega on the grid: no interpolation
    model = _one_dof(data)
    w = np.array([omega])
    f = np.array([[120.0 - 45.0j]])  # excitation amplitude [N]
    b = 300.0 * omega**2 * np.exp(-omega)
    x = omega * (MASS + 500.0 + 800.0 / (1 + omega**2)) - STIFFNESS / omega  # reactance
    z = abs(b + 1j * x)
    assert power_bound(model, w, f).total == pytest.approx(abs(f[0, 0]) ** 2 / (8 * b), rel=1e-9)
    best = optimal_damping(model, w, f)
    assert best.damping[0] == pytest.approx(z, rel=1e-4)
    assert best.total == pytest.approx(abs(f[0, 0]) ** 2 / (4 * (b + z)), rel=1e-8)
    reactive = optimal_spring_damper(model, w, f)
    assert reactive.total == pytest.approx(abs(f[0, 0]) ** 2 / (8 * b), rel=1e-5)
    assert reactive.damping[0] == pytest.approx(b, rel=1e-2)
    assert reactive.stiffness[0] == pytest.approx(omega * x, rel=1e-2, abs=1e-2 * STIFFNESS)
    # within a force limit the spring-damper keeps 3 x its RMS force below it and gives up power for it
    f_opt = abs(power_bound(model, w, f).force[0, 0]) / np.sqrt(2)  # RMS force at the bound
    limited = optimal_spring_damper(model, w, f, force_limit=1.5 * f_opt)
    assert 3 * limited.force_rms[0] <= 1.5 * f_opt * (1 + 1e-6)
    assert limited.total < reactive.total


def test_bad_inputs_name_what_was_received():
    model = _one_dof(np.linspace(0.1, 10.0, 50))
    with pytest.raises(ValueError, match=r"\(n_h, n_omega\) = \(1, 2\)"):
        power_bound(model, np.array([1.0, 2.0]), np.ones((2, 2)))
    with pytest.raises(ValueError, match="positive and finite"):
        power_bound(model, np.array([-1.0]), np.ones((1, 1)))
    with pytest.raises(ValueError, match="damping gains: expected 1 or 1 finite values"):
        gains_power(model, np.array([1.0]), np.ones((1, 1)), np.array([np.nan]))
    with pytest.raises(ValueError, match="force_limit must be positive"):
        optimal_spring_damper(model, np.array([1.0]), np.ones((1, 1)), force_limit=-1.0)


@pytest.fixture(scope="module")
def m4_134():
    compiled = compile_scene(scene("m4-134", sea={"duration": 60.0, "ramp": 6.0}))
    return compiled.control_context.linear_model(), compiled.excitation


def test_m4_134_ordering_and_local_optimality(m4_134):
    model, exc = m4_134
    w, x = exc.omega, exc.coefficients
    bound = power_bound(model, w, x)
    reactive = optimal_spring_damper(model, w, x)
    best = optimal_damping(model, w, x)
    paper = gains_power(model, w, x, 6.0)
    assert bound.total >= reactive.total >= best.total > paper.total > 0
    assert np.allclose(bound.per_pto.sum(), bound.total)
    for p in range(4):  # every PTO's damping moved alone, either way, loses power
        for factor in (0.8, 1.25):
            c = best.damping.copy()
            c[p] *= factor
            assert gains_power(model, w, x, c).total < best.total


def test_frequency_domain_power_matches_the_linear_simulation():
    """Optimal damping of m4-111 in a regular wave: the linear time-domain run's mean power (exact discretisation,
    after the transient) equals the frequency domain's within 1 %."""
    sea = {"kind": "regular", "height": 0.02, "period": 1.1, "duration": "40 T", "ramp": "5 T"}
    compiled = compile_scene(scene("m4-111", sea=sea, radiation={"method": "state_space"}))
    exc = compiled.excitation
    best = optimal_damping(compiled.control_context.linear_model(), exc.omega, exc.coefficients)
    sc = scene("m4-111", sea=sea, solver={"method": "linear"}, radiation={"method": "state_space"},
               controller={"name": "damping", "parameters": {"damping": float(best.damping[0])}},
               outputs={"variables": ["pto"], "window": 0.5})  # fmt: skip
    ds = simulate(sc)
    assert float(ds.mean_pto_power.values[0]) == pytest.approx(best.total, rel=0.01)
