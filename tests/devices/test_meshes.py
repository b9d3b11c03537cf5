"""A device spec's ``[[meshes]]``: the shipped devices' meshes against their databases, and the refusals."""

from __future__ import annotations

import pytest

from wecss.devices import Device, DeviceSpecError, load


@pytest.mark.parametrize("name", ["m4-111", "m4-134", "notc-10kw"])
def test_shipped_meshes_hold_the_databases_volume(name: str) -> None:
    device = load(name)
    hydro = device.hydro()
    bodies = {b.name: b for b in device.model.bodies}
    assert {m.body for m in device.meshes} == {n for n, b in bodies.items() if b.hydro_body is not None}
    for entry in device.meshes:
        comparison = device.surface_mesh(entry.body).compare_with(hydro, str(bodies[entry.body].hydro_body))
        assert abs(comparison.volume_difference) < 1e-4, str(comparison)
        assert abs(comparison.stiffness_difference["Heave"]) < 1e-3, str(comparison)


def _spec(**mesh: object) -> dict[str, object]:
    return {
        "name": "one",
        "bodies": [
            {
                "name": "float",
                "mass": 1.0,
                "inertia": [1.0, 1.0, 1.0],
                "center_of_mass": [0.0, 0.0, -0.1],
                "hydro_body": "float_1",
            }
        ],
        "joints": [{"name": "base", "kind": "free", "child": "float"}],
        "meshes": [mesh],
    }


@pytest.mark.parametrize(
    ("mesh", "message"),
    [
        ({"body": "float", "stl": "a.stl", "colour": "red"}, "unknown keys \\['colour'\\]"),
        ({"body": "hull", "stl": "a.stl"}, "body 'hull' is not a body of the device"),
        ({"body": "float", "stl": "a.stl", "geometry": "m4-111", "freeboard": 0.1}, "give either stl"),
        ({"body": "float", "geometry": "m4-111"}, "needs freeboard"),
        ({"body": "float", "geometry": "m4-111", "freeboard": -0.1}, "freeboard \\[m\\] must be a positive number"),
        ({"body": "float", "stl": "a.stl", "freeboard": 0.1}, "apply to a geometry file's float"),
        ({"body": "float", "geometry": "m4-111", "freeboard": 0.1, "sectors": 2}, "sectors must be an integer >= 3"),
    ],
)
def test_bad_mesh_entries_are_refused_with_what_is_accepted(mesh: dict[str, object], message: str) -> None:
    with pytest.raises(DeviceSpecError, match=message):
        Device.from_spec(_spec(**mesh))


def test_a_body_without_a_declared_mesh_is_named() -> None:
    device = Device.from_spec({**_spec(body="float", geometry="m4-111", freeboard=0.1), "name": "one"})
    with pytest.raises(KeyError, match="declares no mesh of body 'ground'"):
        device.surface_mesh("ground")
