"""Every registered controller, in both simulators (parametrised over ``wecss.control.available()``, so a new
built-in inherits the suite)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.control import available, create
from wecss.sim import SceneError, simulate

PARAMETERS = {
    "damping": {},
    "spring-damper": {"damping": 6.0, "stiffness": -0.5},
    "optimal-damping": {},
    "reactive": {},
    "mpc": {"horizon": 20},
}
"""Parameters of each built-in for these runs (its defaults where empty)."""

CONTROL_PERIOD = {"mpc": 0.06}
"""Control periods [s] of the built-ins that plan ahead (the others: every solver step)."""


def test_every_registered_controller_has_test_parameters():
    assert set(available()) <= set(PARAMETERS), f"add parameters for {set(available()) - set(PARAMETERS)}"


@pytest.mark.parametrize("name", available())
@pytest.mark.parametrize("method", ["beeman", "linear"])
def test_each_controller_absorbs_power_in_both_simulators(name, method):
    sc = scene(
        "m4-111",
        sea={"height": 0.02, "duration": 24.0, "ramp": 2.4},
        controller={"name": name, "parameters": PARAMETERS[name]}
        | ({"dt": CONTROL_PERIOD[name]} if name in CONTROL_PERIOD else {}),
        solver={"method": method},
        radiation={"method": "state_space"},
        outputs={"variables": ["pto"]},
    )
    ds = simulate(sc)
    power = ds.mean_pto_power.values
    assert np.all(np.isfinite(power)) and power.sum() > 0
    assert ds.attrs["controller"] == name


def test_a_typo_in_a_parameter_is_refused_before_the_run():
    with pytest.raises(SceneError, match=r"unexpected keyword argument 'dampin'.*accepts: damping, stiffness"):
        simulate(scene("m4-111", controller={"name": "spring-damper", "parameters": {"dampin": 1.0}}))
    with pytest.raises(SceneError, match=r"'damping' accepts: damping \(default None\), stiffness \(default 0.0\)"):
        simulate(scene("m4-111", controller={"name": "damping", "parameters": {"gain": 1.0}}))
    with pytest.raises(TypeError, match="missing 1 required positional argument: 'stiffness'"):
        create("spring-damper", damping=1.0)
