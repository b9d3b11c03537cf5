"""HydroData: validation errors, netCDF round trip, selection."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from wecss.hydro import HydroData, HydroDataError, dof_name, select, split_dof
from wecss.netcdf import read_netcdf, write_netcdf

from .synthetic import synthetic_dataset


@pytest.fixture
def ds() -> xr.Dataset:
    return synthetic_dataset()


def test_valid_dataset_builds_with_units(ds: xr.Dataset) -> None:
    hd = HydroData(ds)
    assert hd.dofs == ["a__Surge", "a__Heave", "a__Pitch", "b__Surge", "b__Heave", "b__Pitch"]
    assert hd.dataset.omega.attrs["units"] == "rad/s"
    assert "long_name" in hd.dataset.added_mass.attrs
    assert "b: mass 50 kg" in hd.summary()


def test_dof_names_round_trip_and_errors() -> None:
    assert split_dof(dof_name("float_3", "Pitch")) == ("float_3", "Pitch")
    with pytest.raises(ValueError, match="unknown DOF 'pitch'"):
        dof_name("float_3", "pitch")
    with pytest.raises(ValueError, match="not of the form"):
        split_dof("float_3_Pitch")


def test_missing_required_variable_is_named(ds: xr.Dataset) -> None:
    with pytest.raises(HydroDataError, match="missing required variables: added_mass_inf"):
        HydroData(ds.drop_vars("added_mass_inf"))


def test_missing_attribute_is_named(ds: xr.Dataset) -> None:
    del ds.attrs["water_depth"]
    with pytest.raises(HydroDataError, match="missing dataset attributes: water_depth"):
        HydroData(ds)


def test_omega_not_increasing_names_frequency(ds: xr.Dataset) -> None:
    omega = ds.omega.values.copy()
    omega[5] = omega[4]
    with pytest.raises(HydroDataError, match=f"strictly increasing; not so at omega = {omega[5]}"):
        HydroData(ds.assign_coords(omega=omega))


def test_non_finite_value_names_variable_dof_and_frequency(ds: xr.Dataset) -> None:
    values = ds.added_mass.values.copy()
    values[3, 1, 2] = np.nan
    ds["added_mass"] = ds.added_mass.copy(data=values)
    with pytest.raises(HydroDataError, match="'added_mass' has non-finite values") as err:
        HydroData(ds)
    assert "a__Heave" in str(err.value) and "a__Pitch" in str(err.value)
    assert f"{ds.omega.values[3]}" in str(err.value)


def test_asymmetric_damping_names_dofs(ds: xr.Dataset) -> None:
    values = ds.radiation_damping.values.copy()
    values[10, 0, 4] *= 1.5
    ds["radiation_damping"] = ds.radiation_damping.copy(data=values)
    with pytest.raises(HydroDataError, match="'radiation_damping' is not symmetric") as err:
        HydroData(ds)
    assert "a__Surge" in str(err.value) and "b__Heave" in str(err.value)


def test_negative_diagonal_damping_is_rejected(ds: xr.Dataset) -> None:
    values = ds.radiation_damping.values.copy()
    values[2:4, 1, 1] = -0.5 * values[:, 1, 1].max()
    ds["radiation_damping"] = ds.radiation_damping.copy(data=values)
    with pytest.raises(HydroDataError, match=r"negative diagonal values .* for DOFs a__Heave"):
        HydroData(ds)


def test_wrong_dims_and_real_excitation_rejected(ds: xr.Dataset) -> None:
    with pytest.raises(HydroDataError, match="'added_mass_inf' has dimensions"):
        HydroData(ds.assign(added_mass_inf=ds.added_mass_inf.T))
    with pytest.raises(HydroDataError, match="'excitation' must be complex"):
        HydroData(ds.assign(excitation=np.abs(ds.excitation)))


def test_not_a_dataset_is_a_type_error() -> None:
    with pytest.raises(TypeError, match=r"needs an xarray\.Dataset; got dict"):
        HydroData({})  # type: ignore[arg-type]


def test_netcdf_round_trip_is_identical(ds: xr.Dataset, tmp_path) -> None:
    hd = HydroData(ds)
    path = hd.to_netcdf(tmp_path / "db.nc")
    back = HydroData.from_netcdf(path)
    xr.testing.assert_identical(back.dataset, hd.dataset)
    assert np.iscomplexobj(back.dataset.excitation.values)


def test_failed_write_leaves_target_untouched(ds: xr.Dataset, tmp_path) -> None:
    target = tmp_path / "db.nc"
    target.write_bytes(b"old")
    bad = ds.assign_attrs(unserialisable={"a": 1})  # netCDF cannot store a dict attribute
    with pytest.raises((TypeError, ValueError)):
        write_netcdf(bad, target)
    assert target.read_bytes() == b"old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["db.nc"]


def test_read_missing_file_names_path(tmp_path) -> None:
    with pytest.raises(FileNotFoundError, match=r"nope\.nc"):
        read_netcdf(tmp_path / "nope.nc")


def test_select_keeps_cross_body_couplings(ds: xr.Dataset) -> None:
    sub = select(ds, dofs=["Heave", "Pitch"])
    assert list(sub.radiating_dof.values) == ["a__Heave", "a__Pitch", "b__Heave", "b__Pitch"]
    np.testing.assert_array_equal(
        sub.added_mass.sel(influenced_dof="a__Heave", radiating_dof="b__Pitch").values,
        ds.added_mass.sel(influenced_dof="a__Heave", radiating_dof="b__Pitch").values,
    )
    one = HydroData(ds).select(bodies=["b"])
    assert one.bodies == ["b"] and one.dofs == ["b__Surge", "b__Heave", "b__Pitch"]


def test_select_rejects_unknown_names(ds: xr.Dataset) -> None:
    with pytest.raises(ValueError, match=r"unknown bodies \['c'\]"):
        select(ds, bodies=["c"])
    with pytest.raises(ValueError, match=r"unknown DOFs \['heave'\]"):
        select(ds, dofs=["heave"])
