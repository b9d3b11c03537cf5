"""A body's generalised modes in a device spec: both forms read, errors say where, ``info`` lists them."""

from __future__ import annotations

import pytest

from wecss.devices import Device, DeviceSpecError


def _spec(modes: object) -> dict:
    return {
        "name": "hull",
        "bodies": [
            {"name": "hull", "mass": 10.0, "inertia": [1.0, 1.0, 1.0], "center_of_mass": [0, 0, 0], "modes": modes}
        ],
        "joints": [{"name": "base", "kind": "planar", "child": "hull"}],
    }


def test_the_spec_reader_takes_both_forms() -> None:
    listed = Device.from_spec(_spec([{"name": "flex1", "mass": 2.0, "stiffness": 80.0, "damping": 0.1}]))
    assert listed.model.velocity_names[-1] == "hull__flex1"
    assert "generalised modes flex1: mass diag [2.0] kg m^2, stiffness diag [80.0] N m" in listed.info()
    table = Device.from_spec(_spec({"names": ["a", "b"], "mass": [[2.0, 0.1], [0.1, 3.0]], "stiffness": [1.0, 2.0]}))
    assert table.model.mode_names == ("hull__a", "hull__b")


def test_a_bad_mode_is_refused_naming_the_body_entry_and_field() -> None:
    with pytest.raises(DeviceSpecError, match=r"device 'hull', bodies\[0\]: body 'hull': modes\[0\]\.stiffness must be "
                       r"a number \[N m\]; got 'stiff'"):  # fmt: skip
        Device.from_spec(_spec([{"name": "flex1", "mass": 2.0, "stiffness": "stiff"}]))
