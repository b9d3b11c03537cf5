"""The generalised-alpha runner (``solver.method = "generalized-alpha"``) on a rigid device: its runs converge to
RK4's at a fine step with the scheme's second order, and at the wave step it stays within the accuracy the order
promises."""

from __future__ import annotations

import numpy as np
import pytest

import wecss.hydro
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
    the linear model's: the Newton steps overshoot, the first step (from zero accelerations) stops contracting and
    makes the matrix again from the equations' differences, and its new step ends the iteration there. The PTO
    rate and torque recorded at that step are the PTO law's at the recorded state (the hinge's rate, -6 times
    it), not those of the differences' last, perturbed evaluation (off by 8e-8 of the run's largest rate)."""
    prepare = GeneralizedAlphaRunner.prepare

    def overshooting(self, controlled):
        coefficients, jacobian, *rest = prepare(self, controlled)
        return coefficients, np.ascontiguousarray(1.6 * jacobian), *rest

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
