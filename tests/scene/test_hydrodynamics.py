"""The scene's [hydrodynamics] switches and [initial] state: defaults that change nothing, values refused where they
have no effect, runners that cannot honour a switch refusing the scene, and the initial state's names checked."""

from __future__ import annotations

import pytest

from tests.sim.scenes import scene
from wecss.scene import Hydrodynamics, Initial, SceneError
from wecss.sim import compile_scene


def test_the_defaults_switch_nothing_on():
    h = Hydrodynamics()
    assert not h.nonlinear and not h.body_exact and not h.drag
    assert Initial().at_rest


@pytest.mark.parametrize(
    ("section", "message"),
    [
        ({"hydrostatics": "exact"}, "hydrodynamics.hydrostatics: unknown 'exact'; accepted: linear, body-exact"),
        ({"free_surface": "mean"}, "applies to body-exact forces"),
        ({"formulation": "replace"}, "applies to body-exact forces"),
        ({"drag_velocity": "body"}, "applies to the drag; set hydrodynamics.drag = true"),
        ({"drag": "yes"}, "hydrodynamics.drag must be bool"),
    ],
)
def test_bad_switches_are_refused_with_the_field(section, message):
    with pytest.raises(SceneError) as info:
        scene("m4-111", hydrodynamics=section)
    assert message in str(info.value)


def test_a_runner_that_cannot_honour_a_switch_refuses_the_scene():
    with pytest.raises(SceneError, match="does not compute the body-exact hydrodynamics"):
        scene("m4-111", solver={"method": "linear"}, hydrodynamics={"hydrostatics": "body-exact"})
    with pytest.raises(SceneError, match="does not compute the drag hydrodynamics"):
        scene("m4-111", solver={"method": "beeman-explicit"}, hydrodynamics={"drag": True})
    with pytest.raises(SceneError, match="switches none on"):
        scene("m4-111", outputs={"variables": ["motion", "hydrodynamics"]})
    with pytest.raises(SceneError, match="does not fill the group 'hydrodynamics'"):
        scene(
            "m4-111",
            solver={"method": "linear"},
            hydrodynamics={"drag": True},
            outputs={"variables": ["hydrodynamics"]},
        )


def test_drag_without_drag_entries_is_refused_at_compile():
    with pytest.raises(SceneError, match=r"declares no \[\[drag\]\] or \[\[morison\]\]"):
        compile_scene(scene("m4-111", hydrodynamics={"drag": True}))


def test_the_initial_state_names_coordinates_of_the_device():
    with pytest.raises(SceneError, match=r"initial\.displacement: 'nope' is no generalised coordinate"):
        compile_scene(scene("m4-111", initial={"displacement": {"nope": 0.1}}))
    with pytest.raises(SceneError, match="must be a finite number"):
        scene("m4-111", initial={"velocity": {"bow__heave": "fast"}})
    with pytest.raises(SceneError, match="starts from the equilibrium at rest"):
        scene("m4-111", solver={"method": "frequency"}, initial={"displacement": {"bow__heave": 0.01}})
    compiled = compile_scene(
        scene("m4-111", initial={"displacement": {"bow__heave": 0.01}, "velocity": {"bow__pitch": 0.1}})
    )
    q, v = compiled.initial_state()
    names = list(compiled.device.model.velocity_names)
    assert q[names.index("bow__heave")] == pytest.approx(compiled.q0[names.index("bow__heave")] + 0.01)
    assert v[names.index("bow__pitch")] == 0.1
