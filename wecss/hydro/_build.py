"""Assemble a schema-conforming dataset from plain arrays (used by every reader and by BEM generation)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from ..constants import TIME_CONVENTION
from ._schema import AXES, FORCE_DIMS, FREQUENCY_MATRIX_DIMS, MATRIX_DIMS


def build_dataset(
    *,
    omega: np.ndarray,
    dofs: Sequence[str],
    wave_direction: np.ndarray,
    added_mass: np.ndarray,
    radiation_damping: np.ndarray,
    added_mass_inf: np.ndarray,
    excitation: np.ndarray,
    hydrostatic_stiffness: np.ndarray,
    bodies: Sequence[str],
    mass: np.ndarray,
    inertia: np.ndarray,
    center_of_mass: np.ndarray,
    center_of_buoyancy: np.ndarray,
    displaced_volume: np.ndarray,
    reference_point: np.ndarray,
    rho: float,
    g: float,
    water_depth: float,
    source: str,
    added_mass_zero: np.ndarray | None = None,
    froude_krylov: np.ndarray | None = None,
    diffraction: np.ndarray | None = None,
    attrs: Mapping[str, object] | None = None,
) -> xr.Dataset:
    """Return a wecss hydrodynamic dataset from arrays already in the schema's convention.

    Parameters
    ----------
    omega : (n_omega,) angular frequencies [rad/s]
    dofs : DOF names ``<body>__<Dof>``
    wave_direction : (n_dir,) [rad]
    added_mass, radiation_damping : (n_omega, n_dof, n_dof), influenced DOF first
    added_mass_inf, hydrostatic_stiffness, added_mass_zero : (n_dof, n_dof)
    excitation, froude_krylov, diffraction : complex (n_omega, n_dir, n_dof), Re[X exp(+i omega t)]
    bodies : body names
    mass : (n_body,) [kg]; inertia : (n_body, 3, 3) about the centre of mass [kg m^2]
    center_of_mass, center_of_buoyancy, reference_point : (n_body, 3) [m]
    displaced_volume : (n_body,) [m^3]
    rho, g, water_depth : [kg/m^3], [m/s^2], [m] (``inf`` for deep water)
    source : where the data come from (file, code and version)
    attrs : further dataset attributes (netCDF-compatible values only)

    The result is not validated here; ``HydroData(ds)`` does that.
    """
    dofs = [str(d) for d in dofs]
    data_vars: dict[str, tuple[tuple[str, ...], np.ndarray]] = {
        "added_mass": (FREQUENCY_MATRIX_DIMS, np.asarray(added_mass, dtype=float)),
        "radiation_damping": (FREQUENCY_MATRIX_DIMS, np.asarray(radiation_damping, dtype=float)),
        "added_mass_inf": (MATRIX_DIMS, np.asarray(added_mass_inf, dtype=float)),
        "excitation": (FORCE_DIMS, np.asarray(excitation, dtype=complex)),
        "hydrostatic_stiffness": (MATRIX_DIMS, np.asarray(hydrostatic_stiffness, dtype=float)),
        "mass": (("body",), np.asarray(mass, dtype=float)),
        "inertia": (("body", "axis", "axis_col"), np.asarray(inertia, dtype=float)),
        "center_of_mass": (("body", "axis"), np.asarray(center_of_mass, dtype=float)),
        "center_of_buoyancy": (("body", "axis"), np.asarray(center_of_buoyancy, dtype=float)),
        "displaced_volume": (("body",), np.asarray(displaced_volume, dtype=float)),
        "reference_point": (("body", "axis"), np.asarray(reference_point, dtype=float)),
    }
    if added_mass_zero is not None:
        data_vars["added_mass_zero"] = (MATRIX_DIMS, np.asarray(added_mass_zero, dtype=float))
    if froude_krylov is not None:
        data_vars["froude_krylov"] = (FORCE_DIMS, np.asarray(froude_krylov, dtype=complex))
    if diffraction is not None:
        data_vars["diffraction"] = (FORCE_DIMS, np.asarray(diffraction, dtype=complex))
    coords = {
        "omega": np.asarray(omega, dtype=float),
        "influenced_dof": np.array(dofs, dtype=object),
        "radiating_dof": np.array(dofs, dtype=object),
        "wave_direction": np.asarray(wave_direction, dtype=float),
        "body": np.array([str(b) for b in bodies], dtype=object),
        "axis": np.array(list(AXES), dtype=object),
        "axis_col": np.array(list(AXES), dtype=object),
    }
    all_attrs = {
        "rho": float(rho),
        "g": float(g),
        "water_depth": float(water_depth),
        "source": str(source),
        "convention": TIME_CONVENTION,
        **dict(attrs or {}),
    }
    return xr.Dataset(data_vars, coords=coords, attrs=all_attrs)
