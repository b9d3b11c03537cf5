"""Rigid-body transformation of coefficients between reference points."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from wecss.hydro import HydroData, move_reference_point, move_to_center_of_mass, select
from wecss.hydro._build import build_dataset

from .synthetic import synthetic_dataset


def test_there_and_back_is_identity() -> None:
    ds = synthetic_dataset()
    moved = move_to_center_of_mass(ds)
    back = move_reference_point(moved, ds.reference_point)
    for name in ("added_mass", "radiation_damping", "added_mass_inf", "added_mass_zero", "hydrostatic_stiffness"):
        np.testing.assert_allclose(
            back[name].values, ds[name].values, rtol=0, atol=1e-9 * np.abs(ds[name]).max().item()
        )
    np.testing.assert_allclose(back.excitation.values, ds.excitation.values, atol=1e-9)
    np.testing.assert_array_equal(moved.reference_point.values, ds.center_of_mass.values)


def _single_body(excitation: np.ndarray, reference: tuple[float, float, float]) -> xr.Dataset:
    dofs = ["b__Surge", "b__Heave", "b__Pitch"]
    omega = np.array([1.0, 2.0])
    eye = np.broadcast_to(np.eye(3), (2, 3, 3))
    return build_dataset(
        omega=omega,
        dofs=dofs,
        wave_direction=np.array([0.0]),
        added_mass=eye,
        radiation_damping=eye,
        added_mass_inf=np.eye(3),
        excitation=np.broadcast_to(excitation, (2, 1, 3)),
        hydrostatic_stiffness=np.zeros((3, 3)),
        bodies=["b"],
        mass=[1.0],
        inertia=[np.eye(3)],
        center_of_mass=[reference],
        center_of_buoyancy=[reference],
        displaced_volume=[1e-3],
        reference_point=[reference],
        rho=1000.0,
        g=9.81,
        water_depth=np.inf,
        source="test",
    )


def test_heave_force_at_offset_point_gives_pitch_moment() -> None:
    # A pure heave force of 1 N applied at x = +0.5 m, z = 0 ...
    ds = _single_body(np.array([0.0, 1.0, 0.0], dtype=complex), (0.5, 0.0, 0.0))
    # ... is, about the origin, the same heave force plus a moment r x F = (0.5, 0, 0) x (0, 0, 1) = (0, -0.5, 0).
    moved = move_reference_point(ds, {"b": (0.0, 0.0, 0.0)})
    np.testing.assert_allclose(moved.excitation.values[0, 0], [0.0, 1.0, -0.5], atol=1e-15)


def test_surge_force_below_reference_gives_positive_pitch_moment() -> None:
    # Surge force 2 N at z = -0.1 m: about the origin M_y = (r x F)_y = z F_x - x F_z = -0.2 N m.
    ds = _single_body(np.array([2.0, 0.0, 0.0], dtype=complex), (0.0, 0.0, -0.1))
    moved = move_reference_point(ds, {"b": (0.0, 0.0, 0.0)})
    np.testing.assert_allclose(moved.excitation.values[0, 0], [2.0, 0.0, -0.2], atol=1e-15)


def test_kinetic_energy_is_invariant() -> None:
    """The same rigid motion has the same added-mass energy whichever point describes it."""
    ds = synthetic_dataset()
    moved = move_to_center_of_mass(ds)
    rng = np.random.default_rng(1)
    xi_old = rng.normal(size=6)
    # motion of the same rigid displacement about the new points: u_P = u_O + theta x (P - O)
    xi_new = xi_old.copy()
    for b in range(2):
        r = ds.center_of_mass.values[b] - ds.reference_point.values[b]
        theta_y = xi_old[3 * b + 2]
        # rotation about +y: theta x r = (theta r_z, 0, -theta r_x) -> surge and heave parts
        xi_new[3 * b + 0] += theta_y * r[2]
        xi_new[3 * b + 1] += -theta_y * r[0]
    e_old = xi_old @ ds.added_mass_inf.values @ xi_old
    e_new = xi_new @ moved.added_mass_inf.values @ xi_new
    assert e_new == pytest.approx(e_old, rel=1e-12)


def test_hydrostatic_pitch_stiffness_follows_metacentric_formula() -> None:
    """C55 about point P is rho g (I_wp + V (z_b - z_P)) for a body with its waterplane centred at x_P."""
    ds = synthetic_dataset()
    moved = move_to_center_of_mass(ds)
    rho, g = 1000.0, 9.81
    for b, i_wp in enumerate((0.02, 0.03)):
        volume = ds.displaced_volume.values[b]
        z_b = ds.center_of_buoyancy.values[b, 2]
        z_g = ds.center_of_mass.values[b, 2]
        expected = rho * g * (i_wp + volume * (z_b - z_g))
        pitch = 3 * b + 2
        assert moved.hydrostatic_stiffness.values[pitch, pitch] == pytest.approx(expected, rel=1e-12)


def test_non_closed_dof_subset_is_refused() -> None:
    ds = select(_single_body(np.array([0.0, 1.0, 0.0], dtype=complex), (0.0, 0.0, 0.0)), dofs=["Heave", "Pitch"])
    # raising the point: the pitch moment about it would need the surge force, which is not there
    with pytest.raises(ValueError, match=r"would need the missing DOFs \['Surge'\]"):
        move_reference_point(ds, {"b": (0.0, 0.0, 0.3)})
    # moving along x is fine: pitch moment picks up only the heave force
    moved = move_reference_point(ds, {"b": (0.2, 0.0, 0.0)})
    np.testing.assert_allclose(moved.excitation.values[0, 0], [1.0, 0.2], atol=1e-15)
    with pytest.raises(ValueError, match="unknown body 'c'"):
        move_reference_point(ds, {"c": (0.0, 0.0, 0.0)})


def test_hydrodata_at_center_of_mass() -> None:
    hd = HydroData(synthetic_dataset()).at_center_of_mass()
    np.testing.assert_array_equal(hd.dataset.reference_point.values, hd.dataset.center_of_mass.values)
