"""Hydrodynamic data generated from a known state-space kernel, so that every radiation quantity has a closed form.

K(t) = C exp(A t) B gives K_hat(omega) = C (i omega - A)^-1 B, B(omega) = Re K_hat and A(omega) - A_inf =
Im K_hat / omega (e^{+i omega t} convention): data consistent by construction.
"""

from __future__ import annotations

import numpy as np

from wecss.hydro import HydroData
from wecss.hydro._build import build_dataset


def known_system(n_dof: int = 2) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A stable, passive, symmetric 2-DOF kernel of three damped oscillatory modes.

    Each mode is r e^{-a t} (cos bt - (a/b) sin bt), whose integral over t vanishes, so that B(0) = 0 as for
    real radiation damping.
    """
    modes = [(0.8, 2.0, [800.0, 0.0]), (1.5, 5.0, [300.0, 150.0]), (2.5, 9.0, [0.0, 200.0])]
    a = np.zeros((6, 6))
    b = np.zeros((6, n_dof))
    c = np.zeros((n_dof, 6))
    for m, (decay, freq, weights) in enumerate(modes):
        k = 2 * m
        a[k : k + 2, k : k + 2] = [[-decay, freq], [-freq, -decay]]
        # exp(A t) e_1 = e^{-a t} (cos bt, -sin bt); input weights w_j and outputs w_i / |w| make a rank-1
        # symmetric residue matrix
        w = np.array(weights)
        norm = np.sqrt(np.max(np.abs(w)))
        b[k, :] = w / norm
        c[:, k] = w / norm
        c[:, k + 1] = w / norm * decay / freq
    return a, b, c


def response(a: np.ndarray, b: np.ndarray, c: np.ndarray, omega: np.ndarray) -> np.ndarray:
    eye = np.eye(a.shape[0])
    return np.array([c @ np.linalg.solve(1j * w * eye - a, b) for w in omega])


def analytic_hydro(omega: np.ndarray | None = None) -> HydroData:
    """Two heaving bodies whose radiation is the known system (with A_inf = 100 kg on the diagonal)."""
    a, b, c = known_system()
    omega = np.arange(0.05, 40.0001, 0.05) if omega is None else omega
    h = response(a, b, c, omega)
    h = 0.5 * (h + np.swapaxes(h, 1, 2))
    a_inf = np.diag([100.0, 120.0])
    return HydroData(
        build_dataset(
            omega=omega,
            dofs=["p__Heave", "q__Heave"],
            wave_direction=np.array([0.0]),
            added_mass=a_inf[None] + h.imag / omega[:, None, None],
            radiation_damping=h.real,
            added_mass_inf=a_inf,
            excitation=np.ones((omega.size, 1, 2), dtype=complex),
            hydrostatic_stiffness=np.diag([1000.0, 1500.0]),
            bodies=["p", "q"],
            mass=[100.0, 100.0],
            inertia=np.stack([np.eye(3)] * 2),
            center_of_mass=[[0.0, 0.0, 0.0], [3.0, 0.0, 0.0]],
            center_of_buoyancy=[[0.0, 0.0, -0.05], [3.0, 0.0, -0.05]],
            displaced_volume=[0.1, 0.1],
            reference_point=[[0.0, 0.0, 0.0], [3.0, 0.0, 0.0]],
            rho=1000.0,
            g=9.81,
            water_depth=np.inf,
            source="analytic state-space kernel",
        )
    )


def analytic_kernel(time: np.ndarray) -> np.ndarray:
    from scipy.linalg import expm

    a, b, c = known_system()
    k = np.array([c @ expm(a * t) @ b for t in time])
    return 0.5 * (k + np.swapaxes(k, 1, 2))
