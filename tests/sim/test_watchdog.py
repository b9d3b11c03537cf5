"""The controller call's watchdog (issue 31): a ``compute`` that never returns stops the run with a
ControllerTimeout naming the controller and ``controller.time_limit``; the forces a controller returns are checked
(complex, NaN, inf, wrong size, not numbers refused with the value and what is accepted)."""

from __future__ import annotations

import threading
import time
from typing import Any

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.control import ControlContext, Controller
from wecss.sim import ControllerTimeout, SceneError, simulate
from wecss.sim._control import checked_force

SHORT = {"duration": 2.0, "ramp": 0.5}


class Stuck(Controller):
    """A controller whose ``compute`` never returns (sleeping, or busy in Python) from its third call on."""

    needs_state = False

    def __init__(self, busy: bool = False) -> None:
        self.busy, self.calls = busy, 0

    def setup(self, context: ControlContext) -> None:
        self.n = context.n_pto

    def compute(self, t: float, measurement: Any) -> np.ndarray:
        self.calls += 1
        if self.calls >= 3:
            self.stuck_at = time.perf_counter()
            if self.busy:
                while True:
                    pass
            time.sleep(3600.0)
        return np.zeros(self.n)


class Returns(Controller):
    """A controller that returns ``value`` (whatever it is) at every call."""

    needs_state = False

    def __init__(self, value: Any) -> None:
        self.value = value

    def setup(self, context: ControlContext) -> None:
        self.n = context.n_pto

    def compute(self, t: float, measurement: Any) -> Any:
        return self.value(self.n) if callable(self.value) else self.value


def _scene(**controller: Any):
    return scene(sea=SHORT, radiation={"method": "none"}, controller=controller)


@pytest.mark.parametrize("busy", [False, True], ids=["sleeping", "busy"])
def test_a_compute_that_never_returns_stops_the_run_at_its_time_limit(busy):
    stuck = Stuck(busy)
    with pytest.raises(ControllerTimeout) as info:
        simulate(_scene(time_limit=0.2), controller=stuck)
    waited = time.perf_counter() - stuck.stuck_at
    message = str(info.value)
    assert "controller 'damping' (Stuck): compute at t = " in message
    assert "did not return within controller.time_limit = 0.2 s" in message
    # 0.2 s plus at most one poll of the watchdog (0.05 s); 2 s allows for a loaded machine
    assert 0.2 <= waited < 2.0


def test_the_watchdog_costs_no_signal_to_a_run_whose_calls_return():
    """A run of 1,000 controller calls well within the limit ends normally and says nothing about the limit."""
    ds = simulate(_scene(time_limit=5.0), controller=Returns(np.zeros))
    assert ds.attrs["n_steps"] > 0
    assert "time_limit" not in ds.attrs["notes"]


def test_a_run_outside_the_main_thread_has_no_watchdog_and_its_result_says_so():
    out: dict[str, Any] = {}

    def run() -> None:
        out["ds"] = simulate(_scene(time_limit=5.0), controller=Returns(np.zeros))

    worker = threading.Thread(target=run)
    worker.start()
    worker.join()
    assert "controller.time_limit (5 s) was not enforced: the run is not in the main thread" in out["ds"].attrs["notes"]


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan"), "60", True])
def test_the_time_limit_must_be_a_positive_time(bad):
    with pytest.raises(SceneError, match=r"controller\.time_limit must be"):
        _scene(time_limit=bad)


def test_no_limit_is_inf_and_round_trips():
    sc = _scene(time_limit=float("inf"))
    assert sc.controller.time_limit == float("inf")
    assert type(sc).from_json(sc.to_json()) == sc


@pytest.mark.parametrize(
    ("value", "match"),
    [
        (lambda n: np.ones(n) + 0j, "complex forces"),
        (lambda n: np.ones(n) + 1j, "complex forces"),
        (lambda n: np.full(n, np.nan), "expected 1 real finite forces"),
        (lambda n: np.full(n, np.inf), "expected 1 real finite forces"),
        (lambda n: np.ones(n + 1), "expected 1 real finite forces"),
        (lambda n: ["a"] * n, "expected 1 real finite forces"),
    ],
    ids=["complex-zero-imaginary", "complex", "nan", "inf", "wrong-size", "strings"],
)
def test_a_force_that_is_not_real_and_finite_is_refused_with_the_value(value, match):
    """m4-111 has one PTO (the hinge)."""
    with pytest.raises(ValueError, match=match) as info:
        simulate(_scene(), controller=Returns(value))
    assert "at t = 0 s" in str(info.value)


def test_checked_force_accepts_integers_and_floats_as_they_are():
    assert checked_force([1, 2], 2, 0.0).tolist() == [1.0, 2.0]
    forces = np.array([1.5, -2.0])
    assert checked_force(forces, 2, 0.0) is forces


class Stubborn(Controller):
    """A controller that catches every error in a call that never returns, and goes on waiting."""

    needs_state = False

    def setup(self, context: ControlContext) -> None:
        self.n, self.caught = context.n_pto, 0

    def compute(self, t: float, measurement: Any) -> np.ndarray:
        while self.caught < 2:
            try:
                time.sleep(3600.0)
            except Exception:  # the watchdog's first signals: swallowed
                self.caught += 1
        time.sleep(3600.0)
        return np.zeros(self.n)


def test_a_compute_that_swallows_the_timeout_is_stopped_again():
    """Signalled after 0.2 s, 0.4 s and 0.6 s: the third error escapes."""
    controller = Stubborn()
    with pytest.raises(ControllerTimeout):
        simulate(_scene(time_limit=0.2), controller=controller)
    assert controller.caught == 2
