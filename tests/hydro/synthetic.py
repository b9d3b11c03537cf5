"""A small synthetic hydrodynamic database for unit tests (two bodies, surge/heave/pitch)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from wecss.hydro._build import build_dataset


def spd(rng: np.random.Generator, n: int, scale: float = 1.0) -> np.ndarray:
    """A random symmetric positive definite matrix."""
    m = rng.normal(size=(n, n))
    return scale * (m @ m.T + n * np.eye(n))


def synthetic_dataset(seed: int = 0, n_omega: int = 40) -> xr.Dataset:
    """Two floating bodies with smooth, symmetric, passive coefficients about their centres of buoyancy."""
    rng = np.random.default_rng(seed)
    bodies = ["a", "b"]
    dofs = [f"{b}__{d}" for b in bodies for d in ("Surge", "Heave", "Pitch")]
    n = len(dofs)
    omega = np.linspace(0.2, 8.0, n_omega)
    a_inf = spd(rng, n, 10.0)
    shape_a = spd(rng, n, 2.0)
    shape_b = spd(rng, n, 3.0)
    bump = omega**2 / (1.0 + (omega - 2.0) ** 4)
    added_mass = a_inf + (1.0 / (1.0 + omega**2))[:, None, None] * shape_a
    damping = bump[:, None, None] * shape_b
    excitation = (rng.normal(size=(n_omega, 1, n)) + 1j * rng.normal(size=(n_omega, 1, n))) * 100.0
    volume = np.array([0.02, 0.05])
    rho, g = 1000.0, 9.81
    cob = np.array([[0.0, 0.0, -0.05], [1.0, 0.0, -0.1]])
    com = np.array([[0.0, 0.0, -0.03], [1.0, 0.0, -0.08]])
    stiffness = np.zeros((n, n))
    for k, _ in enumerate(bodies):
        area, i_wp = 0.3 + k * 0.1, 0.02 + k * 0.01
        heave, pitch = 3 * k + 1, 3 * k + 2
        stiffness[heave, heave] = rho * g * area
        # about the centre of buoyancy: rho g (I_wp + V (z_b - z_ref)) with z_ref = z_b
        stiffness[pitch, pitch] = rho * g * i_wp
    return build_dataset(
        omega=omega,
        dofs=dofs,
        wave_direction=np.array([0.0]),
        added_mass=added_mass,
        radiation_damping=damping,
        added_mass_inf=a_inf,
        excitation=excitation,
        hydrostatic_stiffness=stiffness,
        bodies=bodies,
        mass=rho * volume,
        inertia=np.stack([np.diag([1.0, 2.0, 3.0]), np.diag([2.0, 3.0, 4.0])]),
        center_of_mass=com,
        center_of_buoyancy=cob,
        displaced_volume=volume,
        reference_point=cob.copy(),
        rho=rho,
        g=g,
        water_depth=np.inf,
        source="synthetic test data",
        added_mass_zero=a_inf + shape_a,
    )
