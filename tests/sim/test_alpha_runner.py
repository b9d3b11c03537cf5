"""The generalised-alpha runner (``solver.method = "generalized-alpha"``) on a rigid device: its runs converge to
RK4's at a fine step with the scheme's second order, and at the wave step it stays within the accuracy the order
promises."""

from __future__ import annotations

import numpy as np
import pytest

import wecss.hydro
from wecss.linear import linearize
from wecss.sim import simulate
from wecss.sim._alpha import REFRESH_AFTER, GeneralizedAlphaRunner

from .scenes import scene

T = 6.2


@pytest.fixture(scope="module", autouse=True)
def _database():
    if "notc-10kw" not in wecss.hydro.available():
        pytest.skip("shipped database notc-10kw not generated yet")


def _run(method: str, dt: float):
    sea = {"kind": "regular", "height": 0.28, "period": T, "duration": 8 * T, "ramp": T}
    return simulate(
        scene(
            "notc-10kw", sea=sea, controller={"name": "damping", "parameters": {}}, radiation={"method": "state_space"},
            solver={"method": method, "dt": dt}, outputs={"variables": ["motion", "pto"]},
        )
    )  # fmt: skip


def test_generalised_alpha_converges_to_rk4_with_second_order():
    """The pivot angle over the last two periods against RK4 at dt 0.00625 s (fourth order: its own error is far
    below the scheme's), at the times both have: the error falls about fourfold per halving of the step."""
    reference = _run("rk4", 0.00625).angle.sel(dof_angular="pivot__pitch")
    errors = []
    for dt in (0.05, 0.025, 0.0125):
        ds = _run("generalized-alpha", dt)
        assert ds.attrs["solver"] == "generalized-alpha"
        got = ds.angle.sel(dof_angular="pivot__pitch")
        got = got[got.time >= 6 * T]
        want = reference.sel(time=got.time, method="nearest")
        assert np.abs(want.time.values - got.time.values).max() < 1e-9
        errors.append(float(np.max(np.abs(got.values - want.values)) / np.max(np.abs(want.values))))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    print(f"generalised-alpha against RK4: errors {errors}, orders {orders}")
    assert errors[0] < 1e-2
    assert np.all((orders > 1.7) & (orders < 2.4)), orders


def test_a_step_whose_iteration_matrix_is_made_again_records_its_accepted_state(monkeypatch):
    """The M4 111 device from rest (its hinge's PTO a damper, 6 N m s/rad) with the iteration's matrix 1.6 times
    the linear model's (S at the equilibrium divided by 1.6): the Newton steps overshoot, the first step (from zero
    accelerations) stops contracting and makes the matrix again from the equations' differences, and its new step
    ends the iteration there. The PTO rate and torque recorded at that step are the PTO law's at the recorded
    state (the hinge's rate, -6 times it), not those of the differences' last, perturbed evaluation (off by 8e-8
    of the run's largest rate)."""
    prepare = GeneralizedAlphaRunner.prepare

    def overshooting(self, controlled):
        coefficients, fixed, pto_weight, *rest = prepare(self, controlled)
        model = linearize(controlled)
        g = model.pto_jacobian
        s = fixed + model.mass + (g.T * pto_weight) @ g  # S at the equilibrium
        return coefficients, np.ascontiguousarray(fixed - (1.0 - 1.0 / 1.6) * s), pto_weight, *rest

    monkeypatch.setattr(GeneralizedAlphaRunner, "prepare", overshooting)
    sea = {"kind": "regular", "height": 0.04, "period": 1.2, "duration": 2.4, "ramp": 1.2}
    solver = {"method": "generalized-alpha", "dt": 0.01, "corrector_tol": 0.08}
    ds = simulate(
        scene(
            "m4-111", sea=sea, controller={"name": "damping", "parameters": {"damping": 6.0}},
            radiation={"method": "state_space"}, solver=solver, outputs={"variables": ["motion", "pto"]},
        )
    )  # fmt: skip
    assert ds.attrs["iteration_matrix_refreshes"] == 1
    rate = ds.angular_velocity.sel(dof_angular="hinge_3__pitch").values[1]
    assert rate != 0.0
    assert ds.pto_angular_velocity.values[1, 0] == pytest.approx(rate, rel=1e-12, abs=0.0)
    assert ds.pto_torque.values[1, 0] == pytest.approx(-6.0 * rate, rel=1e-12, abs=0.0)
    # the refresh in the first step's pass REFRESH_AFTER, which ended the iteration: its passes, the differences
    # and the evaluation at the accepted state
    nv = ds.sizes["dof_linear"] + ds.sizes["dof_angular"]
    assert ds.attrs["max_evaluations_per_step"] == REFRESH_AFTER + 1 + nv + 1


def test_the_steps_iteration_matrix_follows_the_configuration():
    """At a configuration far from the equilibrium (pivot +0.05 rad, floater hinge +0.25 rad, both turning), the
    Newton iteration's matrix J = S^-1 M* that a step makes there (``_iteration_matrix``: M* and the PTO's lever
    arm at the configuration) against the residual's derivative D taken by differences of the equations (the
    reference): the iteration's contraction, the spectral radius of I - J D, is below 0.01 and under a third of
    that of the equilibrium's matrix (M* and G of the linear model), about 0.03 here."""
    import scipy.linalg

    from wecss.compiled.kernels import configure, integrate_configuration, respond, workspace
    from wecss.sim import compile_scene
    from wecss.sim._alpha import _iteration_matrix

    sea = {"kind": "regular", "height": 0.28, "period": T, "duration": 2 * T, "ramp": T}
    controlled = compile_scene(
        scene(
            "notc-10kw", sea=sea, controller={"name": "damping", "parameters": {}}, radiation={"method": "state_space"},
            solver={"method": "generalized-alpha", "dt": 0.05}, outputs={"variables": ["motion"]},
        )
    )  # fmt: skip
    (alpha_m, alpha_f, gamma, beta), fixed, pto_weight, held, *_ = GeneralizedAlphaRunner().prepare(controlled)
    p, h = controlled.plant, controlled.dt
    c = (1 - alpha_f) / (1 - alpha_m)
    nv = p.twists.shape[0]
    assert nv == 2 and controlled.q0.size == 2
    q = controlled.q0 + np.array([0.05, 0.25])
    v = np.array([0.08, -0.3])
    w = workspace(p)
    hydro, none, command = np.zeros(p.hydro_index.size), np.zeros((p.hydro_index.size,) * 2), np.zeros(1)

    def accelerations(increment: np.ndarray, velocity: np.ndarray) -> np.ndarray:
        assert configure(p, integrate_configuration(p, q, increment), hydro, 0.0, w)
        respond(p, velocity, none, command, w)
        return w.acc.copy()

    at = accelerations(np.zeros(nv), v)
    derivative = np.eye(nv)
    for col in range(nv):
        eps = np.zeros(nv)
        eps[col] = 1e-6
        derivative[:, col] -= (accelerations(h * h * beta * c * eps, v + h * gamma * c * eps) - at) / 1e-6
    accelerations(np.zeros(nv), v)  # the workspace at the configuration
    mass, lu, pivots = np.empty((nv, nv)), np.empty((nv, nv)), np.empty(nv, dtype=np.int64)
    assert _iteration_matrix(fixed, pto_weight, held, w.mass, w.gmat, mass, lu, pivots)
    np.testing.assert_array_equal(mass, w.mass)
    step = scipy.linalg.lu_solve((lu, pivots), mass @ derivative)
    contraction = np.max(np.abs(np.linalg.eigvals(np.eye(nv) - step)))
    model = linearize(controlled)
    g = model.pto_jacobian
    equilibrium = np.linalg.solve(fixed + model.mass + (g.T * pto_weight) @ g, model.mass) @ derivative
    contraction_equilibrium = np.max(np.abs(np.linalg.eigvals(np.eye(nv) - equilibrium)))
    print(f"contraction: the step's matrix {contraction:.3g}, the equilibrium's {contraction_equilibrium:.3g}")
    assert contraction < 0.01
    assert contraction < contraction_equilibrium / 3


def test_a_run_does_not_depend_on_its_chunks(monkeypatch):
    """The predictor's history (the accelerations of the step before, the held coordinates' changes) is carried
    from chunk to chunk: the run in chunks of 7 steps is the run in one chunk, bit for bit."""
    import wecss.sim._fixed_step as fixed_step

    def run():
        sea = {"kind": "regular", "height": 0.28, "period": T, "duration": 2 * T, "ramp": T}
        return simulate(
            scene(
                "notc-10kw", sea=sea, controller={"name": "damping", "parameters": {}},
                radiation={"method": "state_space"}, solver={"method": "generalized-alpha", "dt": 0.05},
                outputs={"variables": ["motion", "pto"]},
            )
        )  # fmt: skip

    whole = run()
    monkeypatch.setattr(fixed_step, "CHUNK_STEPS", 7)
    chunked = run()
    assert whole.sizes["time"] > 7 * 20
    for name in ("angle", "angular_velocity", "pto_force"):
        np.testing.assert_array_equal(chunked[name].values, whole[name].values)
