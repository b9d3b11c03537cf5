"""A free decay from the scene's [initial] state: the nonlinear runners and the linear model, started from the same
small displacement and velocity in calm water, give the same motion (to the runners' accuracy)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from wecss.scene import Scene
from wecss.sim import simulate

FLOAT = Path(__file__).parents[1] / "control" / "heaving_float.toml"  # the M4 stern float on a vertical slider


def _decay(method: str) -> np.ndarray:
    scene = Scene.from_dict(
        {
            "device": {"name": str(FLOAT)},
            "sea": {"kind": "calm", "period": None, "duration": 6.0, "ramp": 0.0},
            "solver": {"method": method, "dt": 0.002},
            "initial": {"displacement": {"slider__heave": 0.005}, "velocity": {"slider__heave": 0.02}},
            "outputs": {"variables": ["motion"]},
        }
    )
    return simulate(scene).displacement.sel(dof_linear="slider__heave").values


def test_free_decays_of_every_runner_agree():
    linear, beeman, rk4, reference = (_decay(m) for m in ("linear", "beeman", "rk4", "reference"))
    scale = np.max(np.abs(reference - reference[-1]))
    assert scale > 3e-3  # it decays from the given displacement
    for run, tolerance in ((linear, 1e-6), (rk4, 1e-6), (beeman, 1e-3)):
        assert np.max(np.abs(run - reference)) < tolerance * scale
