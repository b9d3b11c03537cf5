"""The layout of a result a user analyses with xarray (issue 18, "results that are easy to analyse"): one ``pto``
dimension for every per-PTO variable, with ``pto_kind``; bodies, PTOs and hydro DOFs in the device spec's order."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import wecss
from tests.sim.scenes import scene
from wecss.results import mean_power, open_result, rms_hinge_angle, save
from wecss.sim import compile_scene, simulate

DEVICES = Path(wecss.__file__).resolve().parent / "data" / "devices"

STRUT = """
[[ptos]]
name = "strut"
kind = "actuator"
body_a = "float_3"
point_a = [2.12, 0.0, 0.1]
point_b = [2.12, 0.0, 1.1]
damping = 20.0
"""


@pytest.fixture(scope="module")
def mixed(tmp_path_factory) -> xr.Dataset:
    """M4 111 with a vertical damper from the stern float to the ground next to its hinge PTO: one rotary and one
    linear PTO."""
    spec = (DEVICES / "m4-111.toml").read_text().replace('name = "m4-111"', 'name = "m4-111-strut"', 1) + STRUT
    path = tmp_path_factory.mktemp("device") / "m4-111-strut.toml"
    path.write_text(spec)
    return simulate(scene(str(path), sea={"duration": 12.0}, outputs={"variables": ["motion", "pto"]}))


def test_per_pto_variables_share_the_one_pto_dimension(mixed):
    assert (mixed.pto_angle * mixed.pto_power).dims == ("time", "pto")
    assert (mixed.pto_displacement * mixed.pto_power).dims == ("time", "pto")
    assert list(mixed.pto.values) == ["pto_3", "strut"]
    assert list(mixed.pto_kind.values) == ["rotary", "linear"]
    assert "rotary_pto" not in mixed.dims and "linear_pto" not in mixed.dims
    for name in mixed.data_vars:  # nothing per PTO on another dimension
        assert not any("pto" in str(d) and d not in ("pto", "pto_end") for d in mixed[name].dims), name


@pytest.mark.parametrize(
    ("rotary", "linear"),
    [
        ("pto_angle", "pto_displacement"),
        ("pto_angular_velocity", "pto_velocity"),
        ("pto_torque", "pto_force"),
        ("rms_pto_angle", "rms_pto_displacement"),
    ],
)
def test_a_variable_of_one_kind_is_nan_for_the_other_kind(mixed, rotary, linear):
    assert bool(mixed[rotary].sel(pto="pto_3").notnull().all())
    assert bool(mixed[rotary].sel(pto="strut").isnull().all())
    assert bool(mixed[linear].sel(pto="strut").notnull().all())
    assert bool(mixed[linear].sel(pto="pto_3").isnull().all())
    assert "NaN" in mixed[rotary].attrs["long_name"] and "NaN" in mixed[linear].attrs["long_name"]


def test_power_is_force_times_rate_for_both_kinds(mixed):
    """Absorbed power from the kind's own force and rate (no device springs here): -f v per PTO."""
    torque = mixed.pto_torque.fillna(mixed.pto_force)
    rate = mixed.pto_angular_velocity.fillna(mixed.pto_velocity)
    np.testing.assert_allclose(mixed.pto_power, -torque * rate, rtol=1e-12, atol=1e-15)
    assert mean_power(mixed).dims == ("pto",)
    assert np.isnan(float(rms_hinge_angle(mixed).sel(pto="strut")))


def test_mixed_result_round_trips_through_netcdf(mixed, tmp_path):
    xr.testing.assert_identical(open_result(save(mixed, tmp_path / "r.nc")), mixed)


def test_a_device_with_one_kind_has_no_variables_of_the_other():
    ds = simulate(scene(sea={"duration": 6.0}, outputs={"variables": ["pto"]}))
    assert "pto_displacement" not in ds and "rms_pto_displacement" not in ds
    assert bool(ds.pto_angle.notnull().all())


def test_bodies_ptos_and_hydro_dofs_follow_the_device_spec():
    """M4 134's spec lists its floats 1, 4, 2, 5, 7, 3, 6, 8 and its PTOs 7, 3, 6, 8; its database lists the bodies
    1 to 8. The result keeps the spec's order everywhere, and each hydro-DOF column still holds its own DOF."""
    spec = tomllib.loads((DEVICES / "m4-134.toml").read_text())
    bodies = [b["name"] for b in spec["bodies"]]
    assert bodies != sorted(bodies)
    compiled = compile_scene(
        scene("m4-134", sea={"duration": 3.0, "ramp": 1.0}, outputs={"variables": ["pto", "excitation", "poses"]})
    )
    assert compiled.hydro.dofs != sorted(compiled.hydro.dofs, key=lambda d: bodies.index(d.split("__")[0]))
    ds = simulate(compiled)
    assert list(ds.body.values) == bodies
    assert list(ds.pto.values) == [p["name"] for p in spec["ptos"]]
    for dim in ("hydro_dof_linear", "hydro_dof_angular"):
        owners = [bodies.index(str(d).split("__")[0]) for d in ds[dim].values]
        assert owners == sorted(owners), dim
    # the columns moved with their labels: the excitation applied, from the compiled scene in database order
    applied = compiled.excitation_at(ds.time.values)
    for k, dof in enumerate(compiled.hydro.dofs):
        name, dim = (
            ("excitation_moment", "hydro_dof_angular")
            if dof.endswith("Pitch")
            else ("excitation_force", "hydro_dof_linear")
        )
        np.testing.assert_allclose(ds[name].sel({dim: dof}).values, applied[:, k], rtol=1e-12, atol=1e-12)


def test_results_of_the_earlier_layout_open_in_todays(mixed, tmp_path):
    """A file written before the one pto dimension (per-PTO variables on rotary_pto / linear_pto) opens with
    open_result in today's layout, equal to today's result."""
    from wecss.netcdf import write_netcdf

    rotary = mixed.pto_kind.values == "rotary"
    old = mixed.drop_vars("pto_kind")
    for name in list(old.data_vars):
        if "pto" in old[name].dims and (name.startswith(("pto_angle", "pto_angular", "pto_torque", "rms_pto_angle"))):
            old[name] = old[name].isel(pto=np.flatnonzero(rotary)).rename(pto="rotary_pto")
        elif "pto" in old[name].dims and name.startswith(
            ("pto_displacement", "pto_velocity", "pto_force", "rms_pto_d")
        ):
            old[name] = old[name].isel(pto=np.flatnonzero(~rotary)).rename(pto="linear_pto")
    assert {"rotary_pto", "linear_pto"} <= set(old.dims)
    again = open_result(write_netcdf(old, tmp_path / "old.nc"))
    xr.testing.assert_identical(again[list(mixed.data_vars)], mixed)
