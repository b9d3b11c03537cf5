"""``Scene.replace`` (issue 31): a scene changed from Python by dotted paths (as ``wecss run --set`` takes them), by
a section, or by a dict of a section's keys; the result is validated as a new scene is."""

from __future__ import annotations

import pytest

from wecss.scene import ControllerChoice, Scene, SceneError, SeaState, default_scene_path
from wecss.sweep import apply_overrides


@pytest.fixture(scope="module")
def default() -> Scene:
    return Scene.from_toml(default_scene_path())


def test_a_dotted_path_changes_one_value_and_keeps_the_others(default):
    changed = default.replace(**{"sea.period": 1.4, "controller.parameters.damping": 8.0})
    assert changed.sea.period == 1.4 and changed.controller.parameters == {"damping": 8.0}
    assert changed.sea.height == 0.04 and changed.sea.seed == 1 and changed.device == default.device
    assert changed.dt == pytest.approx(1.4 / 200)  # "Tp/200" read against the new period
    assert default.sea.period == 1.2  # the scene itself is not changed


def test_a_dict_changes_the_keys_of_its_section_only(default):
    changed = default.replace(sea={"height": 0.06, "seed": 7})
    assert (changed.sea.height, changed.sea.seed) == (0.06, 7)
    assert (changed.sea.kind, changed.sea.period, changed.sea.gamma) == ("jonswap", 1.2, 3.3)


def test_a_section_object_replaces_its_section(default):
    sea = SeaState(kind="regular", height=0.02, period=1.0, duration="20 T", ramp="2 T")
    controller = ControllerChoice(name="spring-damper", parameters={"damping": 5.0, "stiffness": -2.0})
    changed = default.replace(sea=sea, controller=controller)
    assert changed.sea == sea and changed.controller == controller
    assert changed.solver == default.solver


def test_the_same_paths_as_set_give_the_same_scene(default):
    assigned = apply_overrides(default, ["sea.period=1.4", "controller.parameters.damping=3", 'device.name="m4-111"'])
    replaced = default.replace(**{"sea.period": 1.4, "controller.parameters.damping": 3, "device.name": "m4-111"})
    assert replaced == assigned and replaced.device.name == "m4-111"


def test_changes_apply_in_the_order_given(default):
    changed = default.replace(**{"controller.parameters": {"damping": 3.0}, "controller.parameters.stiffness": 1.0})
    assert changed.controller.parameters == {"damping": 3.0, "stiffness": 1.0}


@pytest.mark.parametrize(
    ("changes", "said"),
    [
        ({"sea.hs": 0.05}, ["[sea]: unknown keys ['hs']", "accepted: kind, height, period"]),
        ({"sea": {"hs": 0.05}}, ["[sea]: unknown keys ['hs']", "height"]),
        ({"sea.period": -1.0}, ["sea.period must be positive", "got -1.0"]),
        ({"sea.seed": 1.5}, ["sea.seed must be int", "got 1.5"]),
        ({"solver.method": "euler"}, ["solver.method: unknown 'euler'", "accepted:", "beeman"]),
        ({"waves": {"period": 1.0}}, ["unknown section or path 'waves'", "sea, controller", "'sea.period'"]),
        ({"waves.period": 1.0}, ["unknown sections ['waves']", "accepted:"]),
        ({"sea": 1.2}, ["sea takes a SeaState or a dict of its keys", "got 1.2 (float)"]),
        ({"sea": ControllerChoice()}, ["sea takes a SeaState", "(ControllerChoice)"]),
        ({"sea.period.x": 1}, ["sea.period is a value (1.2), not a table"]),
        (
            {"sea.duration": 3.0, "sea.ramp": 0.0, "solver.dt": 4.0},
            ["solver.dt (4 s) must be shorter than sea.duration (3 s)"],
        ),
    ],
)
def test_a_bad_change_names_the_field_the_value_and_what_is_accepted(default, changes, said):
    with pytest.raises(SceneError) as info:
        default.replace(**changes)
    for phrase in said:
        assert phrase in str(info.value)
