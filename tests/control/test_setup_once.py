"""A controller is set up once, when it is attached to a compiled scene, and reset at the start of every run: two
runs of one compiled scene give the same result, and a controller with memory starts afresh in each."""

from __future__ import annotations

import numpy as np

from tests.sim.scenes import scene
from wecss.control import ControlContext, ControlledScene, Controller, Measurement, compile_scene
from wecss.sim import simulate
from wecss_controllers import LinearDamping


class Counting(Controller):
    """Damping held per step, with a memory (the number of calls since its reset) that changes its force."""

    def __init__(self) -> None:
        self.setups = self.resets = self.calls = 0
        self.inner = LinearDamping(6.0)

    def setup(self, context: ControlContext) -> None:
        self.setups += 1
        self.inner.setup(context)

    def reset(self) -> None:
        self.resets += 1
        self.calls = 0

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        self.calls += 1
        return self.inner.compute(t, measurement) * (1.0 + 1e-3 * min(self.calls, 10))


def test_setup_once_and_reset_per_run():
    controller = Counting()
    compiled = compile_scene(scene("m4-111", sea={"duration": "4 Tp", "ramp": "1 Tp"}), controller)
    assert isinstance(compiled, ControlledScene) and compiled.controller is controller
    assert (controller.setups, controller.resets) == (1, 0)
    first = simulate(compiled)
    second = simulate(compiled)
    assert (controller.setups, controller.resets) == (1, 2)
    np.testing.assert_array_equal(first.pto_torque.values, second.pto_torque.values)
