"""The device catalogue: every entry builds, its equilibrium is at rest, spec errors are explained."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

import wecss.devices
import wecss.hydro
from wecss.devices import Device, DeviceSpecError
from wecss.multibody import kinematics

SHARED = Path(__file__).resolve().parents[3] / "shared" / "data"
EXTERNAL_HYDRO = {
    "wavestar": SHARED / "wamit" / "wavestar" / "wavestar.out",
    "rm3": SHARED / "wamit" / "rm3" / "rm3.out",
}


def _hydro_for(name: str):
    """The device's hydrodynamic data, or skip when it is not available here."""
    if name in EXTERNAL_HYDRO:
        path = EXTERNAL_HYDRO[name]
        if not path.is_file():
            pytest.skip(f"reference data not found: {path}")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", wecss.hydro.HydroDataWarning)  # the repair is tested with the readers
            return wecss.hydro.HydroData.from_wamit(path)
    device = wecss.devices.load(name)
    if device.hydro_source not in wecss.hydro.available():
        pytest.skip(f"shipped database {device.hydro_source!r} not generated yet")
    return device.hydro()


def test_catalogue_lists_every_device() -> None:
    assert set(wecss.devices.available()) >= {"m4-111", "m4-132", "m4-134", "notc-10kw", "wavestar", "rm3"}


@pytest.mark.parametrize("name", wecss.devices.available())
def test_every_device_builds(name: str) -> None:
    device = wecss.devices.load(name)
    assert device.model.nv >= 1
    assert device.assumptions, "every catalogue device states its assumptions"
    st = kinematics(device.model, device.model.neutral_configuration())
    np.testing.assert_allclose(st.position, [b.center_of_mass for b in device.model.bodies])


@pytest.mark.parametrize("name", wecss.devices.available())
def test_equilibrium_is_at_rest(name: str) -> None:
    device = wecss.devices.load(name)
    statics = device.statics(_hydro_for(name))
    q = statics.equilibrium()
    assert np.max(np.abs(statics.generalized_force(q))) <= 1e-10 * statics.scale()


def test_m4_coordinates_are_named_as_documented() -> None:
    assert wecss.devices.load("m4-111").model.velocity_names == (
        "bow__surge",
        "bow__heave",
        "bow__pitch",
        "hinge_3__pitch",
    )
    names = wecss.devices.load("m4-134").model.velocity_names
    assert len(names) == 7 and all(f"hinge_{k}__pitch" in names for k in (3, 6, 7, 8))


def test_unknown_device_lists_the_catalogue() -> None:
    with pytest.raises(ValueError, match=r"no catalogue device 'm4-999'; available: .*m4-111"):
        wecss.devices.load("m4-999")


def _tiny_spec() -> dict:
    return {
        "name": "tiny",
        "bodies": [{"name": "b", "mass": 1.0, "inertia": [1, 1, 1], "center_of_mass": [0, 0, 0]}],
        "joints": [{"name": "base", "kind": "planar", "child": "b"}],
    }


def test_spec_errors_say_where_and_what() -> None:
    spec = _tiny_spec()
    spec["bodies"][0]["masss"] = 2.0
    with pytest.raises(DeviceSpecError, match=r"bodies\[0\]: unknown keys \['masss'\]"):
        Device.from_spec(spec)
    spec = _tiny_spec()
    spec["joints"][0]["kind"] = "hinge"
    with pytest.raises(DeviceSpecError, match=r"joints\[0\]: .*unknown kind 'hinge'; accepted: fixed, planar"):
        Device.from_spec(spec)
    spec = _tiny_spec()
    spec["bodies"][0]["mass"] = -1.0
    with pytest.raises(DeviceSpecError, match="mass must be positive"):
        Device.from_spec(spec)
    spec = _tiny_spec()
    spec["ptos"] = [{"name": "p", "kind": "joint", "joint": "base"}]
    with pytest.raises(DeviceSpecError, match="a joint PTO needs a revolute or prismatic joint"):
        Device.from_spec(spec)
    with pytest.raises(FileNotFoundError, match=r"no device spec"):
        Device.from_spec("nope.toml")


def test_spec_round_trips_through_toml(tmp_path: Path) -> None:
    source = wecss.devices._catalogue.DEVICE_DIR / "m4-132.toml"
    copy = tmp_path / "copy.toml"
    copy.write_bytes(source.read_bytes())
    a, b = Device.from_spec(source), Device.from_spec(copy)
    assert a.model.velocity_names == b.model.velocity_names
    assert a.spec == b.spec


def test_a_spec_file_with_a_utf8_byte_order_mark_is_read(tmp_path: Path) -> None:
    """Issue 31: a spec saved by an editor that writes a byte-order mark was refused as invalid TOML."""
    shipped = Path(wecss.devices.__file__).resolve().parent.parent / "data" / "devices" / "m4-111.toml"
    spec = tmp_path / "bom.toml"
    spec.write_bytes(b"\xef\xbb\xbf" + shipped.read_bytes())
    device = Device.from_spec(spec)
    assert device.name == "m4-111" and device.info() == Device.from_spec(shipped).info()
