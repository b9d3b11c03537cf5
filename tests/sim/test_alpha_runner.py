"""The generalised-alpha runner (``solver.method = "generalized-alpha"``) on a rigid device: its runs converge to
RK4's at a fine step with the scheme's second order, and at the wave step it stays within the accuracy the order
promises."""

from __future__ import annotations

import numpy as np
import pytest

import wecss.hydro
from wecss.sim import simulate

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
