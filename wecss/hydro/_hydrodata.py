"""``HydroData``: a validated hydrodynamic database (a thin wrapper around one ``xarray.Dataset``)."""

from __future__ import annotations

import os
import warnings
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..attributes import apply_attrs
from ..netcdf import global_attributes, read_netcdf, write_netcdf
from ._repair import repair as _repair
from ._schema import REQUIRED_ATTRS, split_dof
from ._select import select as _select
from ._transform import move_reference_point, move_to_center_of_mass
from ._validate import HydroDataError, HydroDataWarning, validate

PathLike = str | os.PathLike[str]

MOST_FREQUENCIES: float = 0.5
"""A repair that replaces or drops more than this share of the frequencies is warned about a second time."""

LARGE_A_INF_CHANGE: float = 0.1
"""A repair that changes a diagonal A_inf entry by more than this fraction is warned about a second time."""


def is_wecss_database(path: PathLike) -> bool:
    """True when the netCDF file at ``path`` carries the global attributes of a wecss hydrodynamic database
    (``REQUIRED_ATTRS``: rho, g, water depth, source, convention); Capytaine's own files store rho and g as
    variables instead.

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    wecss.netcdf.NetCDFFileError
        If it is not a readable netCDF file.
    """
    return all(name in global_attributes(path) for name in REQUIRED_ATTRS)


class HydroData:
    """Hydrodynamic coefficients of one or more bodies, in the wecss schema (see ``wecss.hydro._schema``).

    Parameters
    ----------
    dataset : xarray.Dataset
        The database. It is validated (``wecss.hydro.validate``) and given the central ``long_name`` and
        ``units`` attributes; the object keeps its own copy.

    Raises
    ------
    HydroDataError
        If the dataset does not follow the schema (the message names variable, DOFs and frequencies).

    Examples
    --------
    >>> import wecss.hydro
    >>> hd = wecss.hydro.load("m4-111")          # doctest: +SKIP
    >>> hd.select(dofs=["Heave"]).dofs          # doctest: +SKIP
    """

    def __init__(self, dataset: xr.Dataset) -> None:
        if not isinstance(dataset, xr.Dataset):
            raise TypeError(f"HydroData needs an xarray.Dataset; got {type(dataset).__name__}")
        validate(dataset)
        self._ds = apply_attrs(dataset)

    # --- named constructors -------------------------------------------------------------------
    @classmethod
    def from_netcdf(cls, path: PathLike) -> HydroData:
        """Read a database written by :meth:`to_netcdf`.

        Raises
        ------
        FileNotFoundError
            If ``path`` does not exist.
        wecss.netcdf.NetCDFFileError
            If it is not a readable netCDF file (empty, truncated, damaged).
        HydroDataError
            If it does not follow the schema (the message names the file).
        """
        ds = read_netcdf(path)
        try:
            return cls(ds)
        except HydroDataError as err:
            raise HydroDataError(f"{str(path)!r} is not a valid wecss hydrodynamic database: {err}") from None

    @classmethod
    def from_capytaine(cls, source: PathLike | xr.Dataset, *, repair: bool | str = True, **kwargs: Any) -> HydroData:
        """Read Capytaine results (a netCDF file or the dataset of ``capytaine.assemble_dataset``).

        ``repair``: True or ``"interpolate"`` (default) symmetrises the data and removes irregular-frequency
        artefacts, interpolating inside the range and dropping them at its ends; ``"drop"`` drops every flagged
        frequency; False keeps the data as read (see :func:`wecss.hydro.repair`). A :class:`HydroDataWarning`
        says what changed, and a second one when the repair replaced or dropped most frequencies
        (:data:`MOST_FREQUENCIES`) or changed a diagonal A_inf entry by more than :data:`LARGE_A_INF_CHANGE`.
        Other keyword arguments go to :func:`wecss.hydro.read_capytaine`.

        Raises
        ------
        HydroDataError
            If the data, repaired as asked, are not valid (the message says which repair was applied and which
            to choose instead).
        """
        from .readers.capytaine import read_capytaine

        return cls._repaired(read_capytaine(source, **kwargs), repair)

    @classmethod
    def from_wamit(cls, path: PathLike, *, repair: bool | str = True, **kwargs: Any) -> HydroData:
        """Read WAMIT output (``.out``, and the numeric ``.1``/``.3``/``.hst`` files beside it).

        ``repair`` as in :meth:`from_capytaine`; other keyword arguments go to :func:`wecss.hydro.read_wamit`.
        """
        from .readers.wamit import read_wamit

        return cls._repaired(read_wamit(path, **kwargs), repair)

    @classmethod
    def from_bemio(cls, path: PathLike, *, repair: bool | str = True, **kwargs: Any) -> HydroData:
        """Read a BEMIO / WEC-Sim ``.h5`` file (needs the ``h5`` extra: ``pip install "wecss[h5]"``).

        ``repair`` as in :meth:`from_capytaine`; other keyword arguments go to :func:`wecss.hydro.read_bemio`.
        """
        from .readers.bemio import read_bemio

        return cls._repaired(read_bemio(path, **kwargs), repair)

    @classmethod
    def _repaired(cls, ds: xr.Dataset, repair: bool | str) -> HydroData:
        choices = (True, False, "interpolate", "drop")
        if not any(repair is c or (isinstance(c, str) and repair == c) for c in choices):
            raise ValueError(f"repair must be True, False, 'interpolate' or 'drop'; got {repair!r}")
        source = ds.attrs.get("source", "hydrodynamic data")
        if repair is False:
            return cls(ds)
        method = "interpolate" if repair is True else str(repair)
        try:
            fixed, report = _repair(ds, method=method)
        except ValueError as err:
            raise HydroDataError(f"{source}: the repair ({method!r}) failed: {err}; read with repair=False") from None
        if report.changed:
            warnings.warn(f"{source}: {report}", HydroDataWarning, stacklevel=3)
        loud = []
        if report.share_changed > MOST_FREQUENCIES:
            kept = fixed.omega.values
            loud.append(
                f"the repair replaced or dropped {len(report.irregular.omega)} of {report.n_omega} frequencies "
                f"({report.share_changed:.0%}); the database keeps {kept.size}, {kept[0]:.4g}-{kept[-1]:.4g} rad/s"
            )
        if report.added_mass_inf_change > LARGE_A_INF_CHANGE:
            loud.append(
                f"A_inf changed by up to {report.added_mass_inf_change:.0%} of a diagonal entry "
                f"({fixed.attrs.get('added_mass_inf_source', '')})"
            )
        if loud:
            warnings.warn(
                f"{source}: check these data before use: {'; '.join(loud)}. Compare repair='drop' or give "
                "added_mass_inf, or recompute the BEM data (with a lid against irregular frequencies)",
                HydroDataWarning,
                stacklevel=3,
            )
        try:
            return cls(fixed)
        except HydroDataError as err:
            other = "'drop' (drop every flagged frequency)" if method == "interpolate" else "'interpolate'"
            raise HydroDataError(
                f"{source}: after the repair {method!r} ({report}) the data are still not valid: {err}. "
                f"Choose repair={other}, or read with repair=False and repair with wecss.hydro.repair / "
                "remove_irregular_frequencies"
            ) from None

    # --- output --------------------------------------------------------------------------------
    def to_netcdf(self, path: PathLike) -> Path:
        """Write the database to ``path`` (atomic; complex values split into ``[re, im]``)."""
        return write_netcdf(self._ds, path)

    # --- views ---------------------------------------------------------------------------------
    @property
    def dataset(self) -> xr.Dataset:
        """The underlying dataset (a copy: change it and build a new ``HydroData``)."""
        return self._ds.copy()

    @property
    def omega(self) -> np.ndarray:
        """Angular frequencies [rad/s]."""
        return np.asarray(self._ds.omega.values, dtype=float)

    @property
    def dofs(self) -> list[str]:
        """DOF names, ``<body>__<Dof>``."""
        return [str(d) for d in self._ds.radiating_dof.values]

    @property
    def bodies(self) -> list[str]:
        """Body names."""
        return [str(b) for b in self._ds.body.values]

    @property
    def rho(self) -> float:
        """Water density the data were made with [kg/m^3]."""
        return float(self._ds.attrs["rho"])

    @property
    def g(self) -> float:
        """Gravitational acceleration the data were made with [m/s^2]."""
        return float(self._ds.attrs["g"])

    @property
    def water_depth(self) -> float:
        """Water depth [m] (``inf`` for deep water)."""
        return float(self._ds.attrs["water_depth"])

    def dofs_of(self, body: str) -> list[str]:
        """DOF names of one body."""
        if body not in self.bodies:
            raise ValueError(f"unknown body {body!r}; bodies: {', '.join(self.bodies)}")
        return [d for d in self.dofs if split_dof(d)[0] == body]

    # --- transformations ---------------------------------------------------------------------
    def select(self, *, bodies: Iterable[str] | None = None, dofs: Iterable[str] | None = None) -> HydroData:
        """Keep some bodies and DOFs, with all couplings between them (see :func:`wecss.hydro.select`)."""
        return HydroData(_select(self._ds, bodies=bodies, dofs=dofs))

    def with_reference_points(self, points: Mapping[str, object] | xr.DataArray) -> HydroData:
        """Move each body's coefficients to new reference points [m] (rigid-body transformation)."""
        return HydroData(move_reference_point(self._ds, points))

    def at_center_of_mass(self) -> HydroData:
        """Coefficients of every body about its centre of mass (the MFM's reference, DESIGN.md)."""
        return HydroData(move_to_center_of_mass(self._ds))

    # --- display -------------------------------------------------------------------------------
    def summary(self) -> str:
        """A few lines saying what the database holds."""
        ds = self._ds
        omega = self.omega
        depth = "deep water" if np.isinf(self.water_depth) else f"depth {self.water_depth:g} m"
        lines = [
            f"HydroData from {ds.attrs['source']}: {len(self.bodies)} bodies, {len(self.dofs)} DOFs, "
            f"{omega.size} frequencies {omega[0]:.3g}-{omega[-1]:.3g} rad/s, "
            f"{ds.sizes['wave_direction']} wave directions, {depth}, rho {self.rho:g} kg/m^3, g {self.g:g} m/s^2",
        ]
        for b, body in enumerate(self.bodies):
            dofs = ", ".join(split_dof(d)[1] for d in self.dofs_of(body))
            lines.append(
                f"  {body}: mass {float(ds.mass.values[b]):.4g} kg, "
                f"volume {float(ds.displaced_volume.values[b]):.4g} m^3, "
                f"centre of mass {np.round(ds.center_of_mass.values[b], 4).tolist()} m, DOFs {dofs}"
            )
        return "\n".join(lines)

    def __repr__(self) -> str:
        return self.summary()

    def __eq__(self, other: object) -> bool:
        return isinstance(other, HydroData) and self._ds.identical(other._ds)

    __hash__ = None  # type: ignore[assignment]
