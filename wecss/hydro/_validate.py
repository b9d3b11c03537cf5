"""Checks that a dataset is a consistent wecss hydrodynamic database.

Errors name the variable, the DOFs and the frequencies at fault. Tolerances are module constants so
that they are stated once and can be read by users.
"""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from ..errors import WecssWarning
from ._irregular import describe_bands, find_irregular_frequencies
from ._peaks import diagonal_peaks, negligible_dofs
from ._schema import (
    COMPLEX_VARIABLES,
    OPTIONAL_VARIABLES,
    REQUIRED_ATTRS,
    REQUIRED_VARIABLES,
    is_rigid_dof,
    split_dof,
)

SYMMETRY_RTOL: float = 1e-3
"""Largest accepted |M_ij - M_ji| relative to sqrt(P_i P_j), P_i the peak over omega of |M_ii| (added mass
including A_inf, and damping). The measure has the units of neither entry, so translation-rotation couplings
are judged fairly; BEM codes often miss it on body-to-body couplings (``wecss.hydro.repair`` symmetrises)."""

NEGATIVE_DAMPING_RTOL: float = 1e-3
"""Largest accepted negative diagonal damping, relative to that diagonal entry's peak over omega."""


class HydroDataError(ValueError):
    """A hydrodynamic database is missing something or holds inconsistent values."""


class HydroDataWarning(WecssWarning):
    """Hydrodynamic data were changed on reading (symmetrised, artefacts removed); the message says how much."""


class IrregularFrequencyWarning(WecssWarning):
    """The damping shows bands that look like irregular-frequency artefacts (see ``remove_irregular_frequencies``)."""


def _fmt_list(items: object, limit: int = 6) -> str:
    seq = [str(x) for x in np.atleast_1d(np.asarray(items))]
    if len(seq) > limit:
        return ", ".join(seq[:limit]) + f", ... ({len(seq)} in all)"
    return ", ".join(seq)


def validate(ds: xr.Dataset) -> None:
    """Raise :class:`HydroDataError` unless ``ds`` follows the wecss hydrodynamic schema.

    Checks, in order: required attributes and variables, dimensions of every variable, DOF names and
    their consistency with ``body``, strictly increasing and finite ``omega``, finite values,
    symmetry of added mass and damping (relative tolerance :data:`SYMMETRY_RTOL`), no negative
    diagonal damping beyond :data:`NEGATIVE_DAMPING_RTOL` of its peak, positive masses and volumes.
    A warning (:class:`IrregularFrequencyWarning`) is issued for damping spikes that look like
    irregular-frequency artefacts.

    Raises
    ------
    HydroDataError
        With a message naming the variable, DOFs and frequencies at fault.
    """
    missing_attrs = [a for a in REQUIRED_ATTRS if a not in ds.attrs]
    if missing_attrs:
        raise HydroDataError(
            f"missing dataset attributes: {', '.join(missing_attrs)}; required: {', '.join(REQUIRED_ATTRS)}"
        )
    missing = [v for v in REQUIRED_VARIABLES if v not in ds.data_vars]
    if missing:
        raise HydroDataError(
            f"missing required variables: {', '.join(missing)}; required: {', '.join(REQUIRED_VARIABLES)}"
        )
    for name, dims in {**REQUIRED_VARIABLES, **OPTIONAL_VARIABLES}.items():
        if name in ds.data_vars and tuple(ds[name].dims) != dims:
            raise HydroDataError(f"variable {name!r} has dimensions {tuple(ds[name].dims)}; expected {dims}")
        if name in ds.data_vars and name in COMPLEX_VARIABLES and not np.iscomplexobj(ds[name].values):
            raise HydroDataError(
                f"variable {name!r} must be complex (Re[X exp(+i omega t)]); got dtype {ds[name].dtype}"
            )
    for attr in ("rho", "g"):
        value = ds.attrs[attr]
        if not (np.isfinite(value) and value > 0):
            raise HydroDataError(f"attribute {attr!r} must be a positive number; got {value!r}")
    depth = float(ds.attrs["water_depth"])
    if not depth > 0:
        raise HydroDataError(f"attribute 'water_depth' must be positive or inf (deep water); got {depth!r}")

    _check_dofs(ds)
    _check_omega(ds)
    _check_finite(ds)
    _check_symmetry(ds, "added_mass")
    _check_symmetry(ds, "radiation_damping")
    _check_damping_sign(ds)
    for name in ("mass", "displaced_volume"):
        bad = ds.body.values[~(ds[name].values > 0)]
        if bad.size:
            raise HydroDataError(f"variable {name!r} must be positive; not so for bodies {_fmt_list(bad)}")
    warn_irregular_frequencies(ds)


def _check_dofs(ds: xr.Dataset) -> None:
    rad = [str(x) for x in ds.radiating_dof.values]
    inf = [str(x) for x in ds.influenced_dof.values]
    if rad != inf:
        raise HydroDataError(
            f"radiating_dof and influenced_dof must hold the same DOFs in the same order; got {rad} and {inf}"
        )
    if len(set(rad)) != len(rad):
        raise HydroDataError(f"duplicate DOF names in {rad}")
    bodies = [str(b) for b in ds.body.values]
    try:
        dof_bodies = [split_dof(d)[0] for d in rad]
    except ValueError as err:
        raise HydroDataError(str(err)) from None
    unknown = sorted(set(dof_bodies) - set(bodies))
    if unknown:
        raise HydroDataError(f"DOFs refer to bodies {unknown} that are not in the 'body' coordinate {bodies}")
    seen_mode: dict[str, str] = {}
    for name in rad:
        body, dof = split_dof(name)
        if not is_rigid_dof(dof):
            seen_mode.setdefault(body, name)
        elif body in seen_mode:
            raise HydroDataError(
                f"DOF {name!r} comes after the generalised mode {seen_mode[body]!r} of its body; each body's rigid "
                "DOFs (Surge ... Yaw) must come before its generalised modes"
            )
    if list(ds.axis.values) != ["x", "y", "z"] or list(ds.axis_col.values) != ["x", "y", "z"]:
        raise HydroDataError("coordinates 'axis' and 'axis_col' must be ['x', 'y', 'z']")


def _check_omega(ds: xr.Dataset) -> None:
    omega = np.asarray(ds.omega.values, dtype=float)
    if omega.size < 2:
        raise HydroDataError(f"need at least two frequencies; got {omega.size}")
    if not np.all(np.isfinite(omega)) or np.any(omega <= 0):
        raise HydroDataError(
            f"omega must be finite and positive (keep omega = 0 and inf in added_mass_zero/added_mass_inf); "
            f"bad values: {_fmt_list(omega[~(np.isfinite(omega) & (omega > 0))])}"
        )
    steps = np.diff(omega)
    if np.any(steps <= 0):
        at = omega[1:][steps <= 0]
        raise HydroDataError(f"omega must be strictly increasing; not so at omega = {_fmt_list(at)} rad/s")


def _check_finite(ds: xr.Dataset) -> None:
    for name, da in ds.data_vars.items():
        values = da.values
        if values.dtype.kind not in "fc":
            continue
        if name == "water_depth":
            continue
        bad = ~np.isfinite(values)
        if np.any(bad):
            where = []
            for dim, idx in zip(da.dims, np.nonzero(bad), strict=True):
                coord = ds[dim].values if dim in ds.coords else np.arange(da.sizes[dim])
                where.append(f"{dim} = {_fmt_list(np.unique(coord[idx]))}")
            raise HydroDataError(f"variable {name!r} has non-finite values at " + "; ".join(where))


def relative_asymmetry(ds: xr.Dataset, name: str) -> np.ndarray:
    """|M_ij - M_ji| / sqrt(P_i P_j) over (omega, i, j), P the diagonal peaks (see :data:`SYMMETRY_RTOL`)."""
    values = ds[name].values
    peak = diagonal_peaks(ds, name)
    scale = np.sqrt(np.outer(peak, peak))
    scale = np.where(scale > 0, scale, np.inf)
    return np.abs(values - np.swapaxes(values, -1, -2)) / scale


def _check_symmetry(ds: xr.Dataset, name: str) -> None:
    rel = relative_asymmetry(ds, name)
    if np.any(rel > SYMMETRY_RTOL):
        k, i, j = np.unravel_index(np.argmax(rel), rel.shape)
        bad_omega = ds.omega.values[np.any(rel > SYMMETRY_RTOL, axis=(1, 2))]
        raise HydroDataError(
            f"variable {name!r} is not symmetric within {SYMMETRY_RTOL:g} (|M_ij - M_ji| / sqrt(P_i P_j)): "
            f"worst between {ds.influenced_dof.values[i]} and {ds.radiating_dof.values[j]} at omega = "
            f"{ds.omega.values[k]:.4g} rad/s (relative asymmetry {rel[k, i, j]:.3g}); "
            f"frequencies at fault: {_fmt_list(np.round(bad_omega, 4))}; wecss.hydro.repair symmetrises"
        )


def _check_damping_sign(ds: xr.Dataset) -> None:
    diag = np.diagonal(ds.radiation_damping.values, axis1=1, axis2=2)  # (omega, dof)
    peak = np.max(np.abs(diag), axis=0)
    peak = np.where(peak > 0, peak, 1.0)
    bad = (diag < -NEGATIVE_DAMPING_RTOL * peak) & ~negligible_dofs(ds)
    if np.any(bad):
        dofs = ds.radiating_dof.values[np.any(bad, axis=0)]
        omegas = ds.omega.values[np.any(bad, axis=1)]
        raise HydroDataError(
            f"variable 'radiation_damping' has negative diagonal values beyond {NEGATIVE_DAMPING_RTOL:g} of their peak "
            f"for DOFs {_fmt_list(dofs)} at omega = {_fmt_list(np.round(omegas, 4))} rad/s; "
            "see wecss.hydro.repair"
        )


def warn_irregular_frequencies(ds: xr.Dataset) -> None:
    """Warn with :class:`IrregularFrequencyWarning` when :func:`find_irregular_frequencies` finds bands."""
    bands = find_irregular_frequencies(ds)
    if bands:
        text = describe_bands(bands)
        warnings.warn(
            f"radiation damping shows spikes or negative bands that look like irregular-frequency artefacts ({text}); "
            "wecss.hydro.repair (or remove_irregular_frequencies) removes and interpolates them",
            IrregularFrequencyWarning,
            stacklevel=3,
        )
