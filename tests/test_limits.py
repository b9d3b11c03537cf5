"""Limits on the size of work (issue 31, ``wecss.limits``): an MPC horizon, a sweep's cases and the reference
solver's evaluations on a stiff plant are refused beyond their limit, at once, naming the field, the value, the
limit and the override; the override runs them."""

from __future__ import annotations

import time

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.control import compile_scene
from wecss.limits import MPC_PLANNED_FORCES, REFERENCE_EVALUATIONS, SWEEP_CASES, LimitError
from wecss.linear import linearize
from wecss.sim import SceneError, simulate
from wecss.sim._reference import EVALUATIONS_PER_STIFFNESS, check_stiffness, stiffness
from wecss.sweep import Sweep
from wecss_controllers import MPC


def test_an_mpc_horizon_of_5000_periods_is_refused_when_made_naming_the_limit_and_the_override():
    start = time.perf_counter()
    with pytest.raises(LimitError) as info:
        MPC(horizon=5000)
    assert time.perf_counter() - start < 0.5
    message = str(info.value)
    assert "horizon = 5000 control periods (x 1 PTO: 5000 planned forces)" in message
    assert f"beyond the limit of {MPC_PLANNED_FORCES} planned forces" in message
    assert "give allow_large = true among the controller's parameters" in message
    assert MPC(horizon=5000, allow_large=True).horizon == 5000
    assert MPC(horizon=MPC_PLANNED_FORCES).horizon == MPC_PLANNED_FORCES


def test_the_limit_counts_every_pto_of_the_device_at_setup():
    """m4-134 has 4 PTOs: 600 periods plan 2400 forces, past 2000, refused at setup (before the linear model); the
    scene's error names the controller."""
    horizon = MPC_PLANNED_FORCES // 4 + 100
    sc = scene("m4-134", sea={"duration": 4.0, "ramp": 1.0}, radiation={"method": "state_space"},
               controller={"name": "mpc", "parameters": {"horizon": horizon}, "dt": "Tp/20"})  # fmt: skip
    with pytest.raises(SceneError, match=r"x 4 PTOs: 2400 planned forces\).*horizon <= 500 here"):
        compile_scene(sc)


@pytest.mark.parametrize("bad", [1, "yes"])
def test_allow_large_of_mpc_is_a_bool(bad):
    with pytest.raises(ValueError, match="allow_large must be true or false"):
        MPC(allow_large=bad)


def test_a_300_by_300_sweep_is_refused_at_once_with_its_size_and_the_override():
    values = [0.8 + 0.001 * i for i in range(300)]
    start = time.perf_counter()
    with pytest.raises(SceneError) as info:
        Sweep.of(None, {"sea.period": values, "sea.height": [0.01 + 1e-4 * i for i in range(300)]})
    assert time.perf_counter() - start < 2.0  # the grid is counted, not expanded
    message = str(info.value)
    assert "cases = 90000 (300 x 300) is beyond the limit of 10000" in message
    assert "give allow_large = true in the [sweep] table" in message


def test_a_large_allowed_sweep_says_its_size_before_checking_its_cases(capsys):
    """1100 cases (past the announcement's 1000) in a list: allowed below the limit, the size printed first."""
    sweep = Sweep.of(None, {"sea.period": [0.8 + 1e-4 * i for i in range(1100)]}, mode="list")
    assert len(sweep.cases) == 1100
    assert "sweep 'sweep': 1100 cases (a list of 1100); checking every case's scene" in capsys.readouterr().err
    Sweep.of(None, {"sea.period": [0.8, 1.0]})
    assert capsys.readouterr().err == ""


def test_a_sweep_file_takes_allow_large_and_checks_its_type():
    grid = {"sea": {"period": [0.8 + 1e-3 * i for i in range(101)], "height": [0.01 + 1e-3 * i for i in range(100)]}}
    with pytest.raises(SceneError, match=f"beyond the limit of {SWEEP_CASES}"):
        Sweep.from_dict({"sweep": {"axes": grid}, "scene": {}})
    with pytest.raises(SceneError, match=r"sweep\.allow_large must be true or false; got 'yes'"):
        Sweep.from_dict({"sweep": {"axes": {"sea": {"period": [1.0]}}, "allow_large": "yes"}, "scene": {}})


def _reference(damping: float, **solver):
    return compile_scene(
        scene(
            solver={"method": "reference", **solver},
            radiation={"method": "none"},
            controller={"name": "damping", "parameters": {"damping": damping}},
            sea={"duration": 20.0, "ramp": 1.0},
        )
    )


def test_the_reference_solver_refuses_a_pto_damping_of_1e7_at_once_with_the_estimate():
    """The issue's case: no answer and no warning before. The fastest mode of a damper c on m4-111's hinge is
    about c / m_eff (``tests/sim/test_guards.py``): 4.3e6 rad/s at 1e7 N m s/rad, so some 3e8 evaluations over 20 s."""
    compiled = _reference(1e7)
    rate, needed = stiffness(compiled)
    g = linearize(compiled).pto_jacobian
    m_eff = 1.0 / (g @ np.linalg.solve(linearize(compiled).mass, g.T)).item()
    assert rate == pytest.approx(1e7 / m_eff, rel=1e-2)
    assert needed == pytest.approx(EVALUATIONS_PER_STIFFNESS * rate * 20.0, rel=1e-3)  # the run's last time
    assert needed > 100 * REFERENCE_EVALUATIONS
    start = time.perf_counter()
    with pytest.raises(SceneError) as info:
        simulate(compiled)
    assert time.perf_counter() - start < 5.0
    message = str(info.value)
    assert f"fastest mode |s| = {rate:.4g} rad/s over 20 s" in message
    assert "beyond the limit of 2e+06 evaluations" in message
    assert "give solver.allow_large = true" in message


def test_the_estimate_lets_the_default_damping_through():
    check_stiffness(_reference(6.0))  # |s| about 8 rad/s: some 600 evaluations


def test_solver_allow_large_is_for_the_reference_solver_only():
    with pytest.raises(SceneError, match=r"solver\.allow_large applies to solver\.method 'reference' only"):
        scene(solver={"method": "beeman", "allow_large": True})
    with pytest.raises(SceneError, match=r"solver\.allow_large must be true or false"):
        scene(solver={"method": "reference", "allow_large": 1}, radiation={"method": "none"})
    assert _reference(1e7, allow_large=True).scene.solver.allow_large is True


def test_the_reference_solver_stops_at_its_budget_when_the_estimate_missed(monkeypatch):
    """A stiffness the equilibrium does not show: with the estimate made blind (0 evaluations per |s| T) and a
    budget of 100 evaluations, the run stops at the 101st, naming the count and the time it reached."""
    import wecss.sim._reference as reference

    monkeypatch.setattr(reference, "EVALUATIONS_PER_STIFFNESS", 0.0)
    monkeypatch.setattr(reference, "REFERENCE_EVALUATIONS", 100)
    with pytest.raises(SceneError, match=r"reference solver \(DOP853\) = 100 evaluations by t = .* of 20 s"):
        simulate(_reference(6.0))
