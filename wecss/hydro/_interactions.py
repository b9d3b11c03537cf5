"""Radiation between bodies: a database without the body-to-body radiation terms (WEC-Sim's default, its
``body2body`` switch off), for comparing with wecss's default that keeps them."""

from __future__ import annotations

import numpy as np

from ._hydrodata import HydroData
from ._schema import split_dof

#: The radiation variables whose entries between DOFs of different bodies are the body-to-body interactions.
RADIATION_VARIABLES = ("added_mass", "radiation_damping", "added_mass_inf", "added_mass_zero")


def without_body_interactions(hydro: HydroData) -> HydroData:
    """``hydro`` with the added mass (A(omega), A_inf, A(0)) and radiation damping between DOFs of different bodies
    set to zero: each body radiates onto itself only. Excitation and hydrostatics are kept."""
    ds = hydro.dataset.copy(deep=True)
    influenced = [split_dof(str(d))[0] for d in ds["influenced_dof"].values]
    radiating = [split_dof(str(d))[0] for d in ds["radiating_dof"].values]
    same = np.equal.outer(np.array(influenced), np.array(radiating))
    for name in RADIATION_VARIABLES:
        if name in ds:
            var = ds[name]
            mask = same if var.dims[-2:] == ("influenced_dof", "radiating_dof") else same.T
            ds[name] = var.where(mask, 0.0)
    return HydroData(ds)
