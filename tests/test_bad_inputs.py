"""Issue 31's battery of bad inputs: each answered by one message naming the file or field, the value received and
what is accepted (``wecss`` exits 2 with one line, no traceback)."""

from __future__ import annotations

import traceback
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from wecss.cli import main
from wecss.control import ControlContext, Controller, compile_scene
from wecss.devices import Device, DeviceSpecError
from wecss.scene import Scene, SceneError
from wecss.sweep import Sweep, prepare_folder

SPEC = Path(__file__).resolve().parents[1] / "wecss" / "data" / "devices" / "m4-134.toml"


def _one_line_error(capsys: pytest.CaptureFixture[str], argv: list[str]) -> str:
    """The command's error line, checked to be its only output on stderr, with exit status 2."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("wecss: error: ") and "Traceback" not in err
    return err


def _spec_with(tmp_path: Path, old: str, new: str) -> Path:
    text = SPEC.read_text()
    assert old in text
    path = tmp_path / "spec.toml"
    path.write_text(text.replace(old, new, 1))
    return path


def test_a_device_with_no_degree_of_freedom_is_refused_at_compile_naming_its_joints(tmp_path, capsys):
    """A spec may describe a still structure (its members' loads), but a run of it is refused before any work."""
    path = tmp_path / "still.toml"
    path.write_text(
        'name = "still"\nhydro = "m4-134"\n[[bodies]]\nname = "float_1"\nmass = 2.345\ninertia = [0.2, 0.2, 0.2]\n'
        'center_of_mass = [0.0, 0.0, -0.06]\nhydro_body = "float_1"\n[[joints]]\nname = "ground"\nkind = "fixed"\n'
        'child = "float_1"\n'
    )
    scene = Scene.from_dict({"device": {"name": str(path)}, "sea": {"kind": "regular", "height": 0.02, "period": 1.2,
                             "duration": 2.0, "ramp": 0.5}})  # fmt: skip
    with pytest.raises(SceneError, match=r"device 'still' has no degree of freedom \(joints: ground fixed\); a run"):
        compile_scene(scene)
    with pytest.raises(ValueError, match="device 'still' has no degree of freedom"):
        Device.from_spec(path).natural_periods()


def test_a_pto_rest_of_nan_is_refused_naming_the_file_and_the_field(tmp_path, capsys):
    path = _spec_with(tmp_path, "damping = 6.0\n", "damping = 6.0\nrest = nan\n")
    with pytest.raises(DeviceSpecError, match=r"spec.toml: device 'm4-134', ptos\[0\]: rest = nan: expected a finite"):
        Device.from_spec(path)
    _one_line_error(capsys, ["info", str(path)])


def test_a_string_for_a_mass_is_refused_naming_the_file_the_body_and_the_value(tmp_path, capsys):
    path = _spec_with(tmp_path, "mass = 2.345", 'mass = "heavy"')
    with pytest.raises(DeviceSpecError, match=r"spec.toml: device 'm4-134', bodies\[0\]: mass = 'heavy': expected a"):
        Device.from_spec(path)
    _one_line_error(capsys, ["info", str(path)])


@pytest.mark.parametrize("value", ["true", "[1.0, nan, 2.0]", "inf"])
def test_other_non_numbers_in_numeric_fields_are_refused(tmp_path, value):
    path = _spec_with(tmp_path, "inertia = [0.204, 0.204, 0.204]", f"inertia = {value}")
    with pytest.raises(DeviceSpecError, match=r"bodies\[0\]: inertia = .*: expected a finite number"):
        Device.from_spec(path)


def test_a_full_inertia_matrix_is_still_accepted_and_a_nan_inside_it_is_not(tmp_path):
    """The spec allows an inertia as 3 x 3 (a nested list): the check of numbers reads its leaves."""
    full = "inertia = [[0.204, 0.0, 0.0], [0.0, 0.204, 0.0], [0.0, 0.0, 0.204]]"
    device = Device.from_spec(_spec_with(tmp_path, "inertia = [0.204, 0.204, 0.204]", full))
    diagonal = Device.from_spec(
        _spec_with(tmp_path, "inertia = [0.204, 0.204, 0.204]", "inertia = [0.204, 0.204, 0.204]")
    )
    assert np.array_equal(device.model.bodies[0].inertia, diagonal.model.bodies[0].inertia)
    bad = full.replace("[0.0, 0.204, 0.0]", "[0.0, nan, 0.0]")
    with pytest.raises(DeviceSpecError, match=r"bodies\[0\]: inertia = .*: expected a finite number"):
        Device.from_spec(_spec_with(tmp_path, "inertia = [0.204, 0.204, 0.204]", bad))


def test_a_binary_device_spec_is_refused_as_not_a_text_file(tmp_path, capsys):
    path = tmp_path / "spec.toml"
    path.write_bytes(b'name = "x"\n\xff\xfe\x00 = 1\n')
    with pytest.raises(
        DeviceSpecError, match=r"spec.toml: not a text file \(byte 11 is b'\\xff', not UTF-8\); a device"
    ):
        Device.from_spec(path)
    _one_line_error(capsys, ["info", str(path)])


def test_a_binary_sweep_file_is_refused_as_not_a_text_file(tmp_path, capsys):
    path = tmp_path / "sweep.toml"
    path.write_bytes(b"[sweep]\n\x89PNG\r\n\x1a\n\x00\x00")
    with pytest.raises(SceneError, match=r"sweep.toml: not a text file \(byte 8 is b'\\x89', not UTF-8\); a sweep"):
        Sweep.from_toml(path)
    _one_line_error(capsys, ["sweep", str(path), "-o", str(tmp_path / "out")])


@pytest.mark.parametrize("content", [b'{"name": "sweep", "axes": [[', b"\x00\xff\x10binary"])
def test_a_corrupt_sweep_json_in_a_sweep_folder_is_named_with_what_to_do(tmp_path, content):
    sweep = Sweep.of(None, {"sea.period": [1.0, 1.2]})
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / "sweep.json").write_bytes(content)
    with pytest.raises(ValueError, match=r"sweep.json: not a readable sweep record .*give a new folder, or remove"):
        prepare_folder(sweep, folder)


class _SetupFails(Controller):
    """A user controller whose ``setup`` fails deep in its own code (a helper it calls)."""

    needs_state = False

    def setup(self, context: ControlContext) -> None:
        self._table(context.n_pto)

    def _table(self, n: int) -> None:
        raise ValueError(f"table of {n} PTOs has no row for the sea state")

    def compute(self, t: float, measurement: Any) -> np.ndarray:
        return np.zeros(1)


_REGULAR = {"kind": "regular", "height": 0.02, "period": 1.2, "duration": 2.0, "ramp": 0.5}


def test_an_error_inside_a_controllers_setup_keeps_its_traceback_and_says_where():
    scene = Scene.from_dict({"device": {"name": "m4-111"}, "sea": _REGULAR, "radiation": {"method": "none"}})
    with pytest.raises(SceneError) as info:
        compile_scene(scene, controller=_SetupFails())
    message = str(info.value)
    assert message.startswith("controller _SetupFails: table of 1 PTOs has no row for the sea state (raised in _table")
    assert f"at {__file__}:" in message
    cause = info.value.__cause__
    assert isinstance(cause, ValueError)  # chained: its traceback reaches the controller's helper
    assert [f.name for f in traceback.extract_tb(cause.__traceback__)][-2:] == ["setup", "_table"]


def test_mpc_with_the_frequency_solver_is_told_to_use_a_runner_that_calls_it_not_state_space():
    """MPC plans on the state-space model already: the frequency domain refuses it because it never calls a
    controller during the run (it needs constant linear gains); the runners named instead are those that call it."""
    scene = Scene.from_dict(
        {
            "device": {"name": "m4-111"},
            "sea": _REGULAR,
            "controller": {"name": "mpc"},
            "solver": {"method": "frequency"},
        }
    )
    with pytest.raises(SceneError) as info:
        compile_scene(scene)
    message = str(info.value)
    assert "'frequency' needs a controller with linear gains" in message
    assert "it never calls the controller during the run; MPC has none" in message
    named = message.split("one of ")[1].split(" (")[0].split(", ")
    assert "linear" in named and "beeman" in named and "frequency" not in named and "reference" not in named
    assert "state space" not in message and "state_space" not in message


@pytest.mark.parametrize("content", [b'{"error": "Simulation', b"\xff\xfe", b'{"no": 1}'])
def test_a_damaged_failure_record_of_a_sweep_case_is_named_in_the_combined_result(tmp_path, content):
    from wecss.sweep import case_paths, combine

    sweep = Sweep.of(None, {"sea.period": [1.0, 1.2]})
    case = sweep.cases[0]
    _, failure = case_paths(tmp_path, case)
    failure.write_bytes(content)
    ds = combine(sweep, tmp_path)
    error = str(ds["error"].sel({"sea.period": 1.0}).values)
    assert error.startswith(f"the failure record '{failure}' is unreadable (") and error.endswith("run the case again")
    assert list(ds["status"].values) == ["failed", "pending"]
