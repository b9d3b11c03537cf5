"""Peaks of frequency-dependent matrices over omega, and the DOFs whose damping is numerical noise (shared by the
validation and the irregular-frequency detection)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from ._schema import dof_kinds

NEGLIGIBLE_RTOL: float = 1e-6
"""A DOF whose damping peak is below this fraction of the largest damping peak of its kind (translation,
rotation or generalised mode) is numerical noise (yaw of an axisymmetric body): its sign and spikes are not checked."""


def diagonal_peaks(ds: xr.Dataset, name: str) -> np.ndarray:
    """Peak over omega of each diagonal entry |M_ii| of a frequency-dependent matrix (A_inf included for added mass)."""
    diag = np.abs(np.diagonal(ds[name].values, axis1=-2, axis2=-1))
    peak = np.max(diag, axis=0)
    if name == "added_mass" and "added_mass_inf" in ds:
        peak = np.maximum(peak, np.abs(np.diag(ds.added_mass_inf.values)))
    return peak


def negligible_dofs(ds: xr.Dataset) -> np.ndarray:
    """Boolean per DOF: damping peak below :data:`NEGLIGIBLE_RTOL` of the largest peak of its kind."""
    peak = diagonal_peaks(ds, "radiation_damping")
    kinds = np.array(dof_kinds([str(d) for d in ds.radiating_dof.values]))
    rotation = kinds == "angular"
    generalised = kinds == "generalised"
    out = np.zeros(peak.shape, dtype=bool)
    for kind in (rotation, ~rotation & ~generalised, generalised):
        if np.any(kind):
            out[kind] = peak[kind] < NEGLIGIBLE_RTOL * np.max(peak[kind])
    return out
