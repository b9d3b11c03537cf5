"""A joint's own viscous damping (``Joint.damping``, a device loss such as the WECCCOMP hinge friction): it must act
exactly as the same damping applied by a linear PTO controller on that joint's coordinate, in the nonlinear and the
linear simulators and in the frequency domain, while the PTO absorbs nothing."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from wecss.devices import DeviceSpecError
from wecss.linear import linearize
from wecss.sim import Scene, compile_scene, simulate

FLOAT = Path(__file__).parents[1] / "control" / "heaving_float.toml"  # the M4 stern float on a vertical slider
DAMPING = 40.0  # N s/m, about a third of the float's radiation damping at 1 Hz


def _spec(joint_damping: float) -> dict:
    spec = tomllib.loads(FLOAT.read_text())
    spec["joints"][1]["damping"] = joint_damping
    return spec


def _scene(tmp_path: Path, joint_damping: float, pto_damping: float, method: str) -> Scene:
    path = tmp_path / f"float-{joint_damping:g}.toml"
    text = FLOAT.read_text().replace(
        "point = [2.12, 0.0, -0.1227]", f"point = [2.12, 0.0, -0.1227]\ndamping = {joint_damping}"
    )
    path.write_text(text)
    return Scene.from_dict(
        {
            "device": {"name": str(path)},
            "sea": {"kind": "jonswap", "height": 0.03, "period": 1.0, "duration": 20.0, "ramp": 3.0},
            "controller": {"name": "damping", "parameters": {"damping": pto_damping}},
            "solver": {"method": method},
            "radiation": {"method": "state_space"},
            "outputs": {"variables": ["motion", "pto"]},
        }
    )


@pytest.mark.parametrize("method", ["beeman", "rk4", "linear", "frequency"])
def test_joint_damping_moves_the_device_as_the_same_pto_damping(tmp_path, method):
    as_loss = simulate(_scene(tmp_path, DAMPING, 0.0, method))
    as_pto = simulate(_scene(tmp_path, 0.0, DAMPING, method))
    free = simulate(_scene(tmp_path, 0.0, 0.0, method))
    stroke, same, other = (ds.pto_displacement.values for ds in (as_pto, as_loss, free))
    scale = np.max(np.abs(stroke))
    assert np.max(np.abs(same - stroke)) <= 1e-9 * scale
    assert np.max(np.abs(other - stroke)) > 0.05 * scale  # the damping matters
    assert float(as_loss.mean_pto_power.sum()) == 0.0  # a loss, not PTO power
    assert float(as_pto.mean_pto_power.sum()) > 0.0


def test_the_linear_model_carries_the_joint_damping(tmp_path):
    model = linearize(compile_scene(_scene(tmp_path, DAMPING, 0.0, "linear")))
    k = list(model.state_space.state_labels).index("slider__heave")
    assert model.damping[k, k] == pytest.approx(DAMPING, rel=1e-12)
    assert model.pto_damping[0] == 0.0


@pytest.mark.parametrize(("kind", "value"), [("revolute", -1.0), ("revolute", float("nan")), ("weld", 1.0)])
def test_bad_joint_damping_is_refused(kind, value):
    from wecss.multibody import Joint

    with pytest.raises(ValueError, match="damping"):
        Joint("j", kind, "b", parent="a", axis=[0, 1, 0], point=[0, 0, 0], damping=value)


def test_the_spec_reader_accepts_joint_damping_and_names_the_joint():
    from wecss.devices import Device

    device = Device.from_spec(_spec(2.5))
    assert device.model.joint_damping.tolist() == [2.5]
    with pytest.raises(DeviceSpecError, match=r"joints\[1\].*damping"):
        Device.from_spec(_spec(-2.5))
