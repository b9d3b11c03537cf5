"""The controller owns the PTO gains: the device's PTO damping reaches it only as the context's default."""

from __future__ import annotations

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.control import ControlContext, Measurement, available, create
from wecss.devices import load as load_device
from wecss.sim import compile_scene
from wecss_controllers import LinearDamping


@pytest.mark.parametrize("device", ["m4-134", "notc-10kw"])
def test_damping_without_parameters_takes_the_device_default(device):
    sea = {"period": 6.2, "height": 0.28, "duration": 40.0} if device == "notc-10kw" else {}
    compiled = compile_scene(scene(device, sea=sea, controller={"name": "damping", "parameters": {}}))
    expected = [p.damping for p in load_device(device).ptos]
    assert compiled.control_context.default_damping == tuple(expected)
    np.testing.assert_array_equal(compiled.plant.pto_damping, expected)


def test_the_controllers_gain_wins_over_the_device_default():
    compiled = compile_scene(scene("m4-134", controller={"name": "damping", "parameters": {"damping": 2.5}}))
    np.testing.assert_array_equal(compiled.plant.pto_damping, [2.5] * 4)
    assert compiled.control_context.default_damping == (6.0,) * 4


def test_context_checks_and_a_registered_controller():
    context = ControlContext(("a", "b"), 0.01, (1.0, 2.0))
    controller = create("damping")
    controller.setup(context)
    force = controller.compute(0.0, Measurement(np.zeros(2), np.array([1.0, -1.0])))
    np.testing.assert_array_equal(force, [-1.0, 2.0])
    assert "damping" in available() and isinstance(controller, LinearDamping)
    with pytest.raises(ValueError, match="default_damping has 1 values for 2 PTOs"):
        ControlContext(("a", "b"), 0.01, (1.0,))
    with pytest.raises(ValueError, match="control_period must be positive"):
        ControlContext(("a",), 0.0, (1.0,))
    with pytest.raises(ValueError, match="damping has 3 values; the device has 2 PTOs"):
        LinearDamping([1.0, 2.0, 3.0]).setup(context)
