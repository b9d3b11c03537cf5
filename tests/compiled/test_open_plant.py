"""``compile_plant`` (issue 31, docs/control_design.md): the open plant of any scene, without its controller."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.compiled import compile_plant
from wecss.control import compile_scene
from wecss.scene import Scene


def test_the_open_plant_has_no_pto_gains_whatever_the_scenes_controller():
    scene = Scene().replace(
        device={"name": "m4-111"},
        sea={"kind": "regular", "height": 0.02, "period": 1.2, "duration": "10 T", "ramp": "2 T"},
        controller={"name": "spring-damper", "parameters": {"damping": 3.0, "stiffness": 2.0}},
    )
    open_plant = compile_plant(scene)
    np.testing.assert_array_equal(open_plant.plant.pto_damping, [0.0])
    np.testing.assert_array_equal(open_plant.plant.pto_stiffness, [0.0])
    closed = compile_scene(scene)  # the same scene with its controller: the gains folded in
    np.testing.assert_array_equal(closed.plant.pto_damping, [3.0])
    np.testing.assert_array_equal(closed.plant.pto_stiffness, [2.0])


def test_anything_but_a_scene_is_refused_naming_what_it_got():
    with pytest.raises(TypeError, match=r"compile_plant takes a wecss\.scene\.Scene; got dict"):
        compile_plant({"device": {"name": "m4-111"}})
