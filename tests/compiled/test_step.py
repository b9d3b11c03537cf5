"""The step of a compiled scene is the scene's, read once, and the radiation arrays were discretised for it: a
compiled scene whose parts disagree on the step cannot be made."""

from __future__ import annotations

import dataclasses

import pytest

from tests.sim.scenes import scene, simple_state_space
from wecss.compiled import compile_plant, from_state_space


def test_the_radiation_arrays_and_the_scene_share_one_step():
    compiled = compile_plant(scene("m4-111", sea={"duration": "4 Tp", "ramp": "1 Tp"}))
    assert compiled.dt == compiled.scene.dt == compiled.radiation.dt
    arrays, summary = from_state_space(simple_state_space(compiled), 2 * compiled.dt)
    with pytest.raises(ValueError, match="discretised for a step of"):
        dataclasses.replace(compiled, radiation=arrays, radiation_summary=summary)
    with pytest.raises(ValueError, match="differs from the scene's"):
        dataclasses.replace(compiled, dt=0.5 * compiled.dt)


def test_the_scene_reads_its_step_once():
    sc = scene("m4-111", solver={"dt": "Tp/200"})
    assert sc.dt == pytest.approx(1.2 / 200)
    assert "dt" in sc.__dict__  # cached: "Tp/200" is not parsed again on every access
