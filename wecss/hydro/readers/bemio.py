"""Read a BEMIO / WEC-Sim ``.h5`` hydrodynamic file into the wecss schema (needs the ``h5`` extra: h5py).

Layout (as h5py sees it; WEC-Sim's MATLAB ``writeBEMIOH5`` and the older Python ``bemio`` give the same
array orientation; n_f frequencies, n_h headings, rows of body b = its n_b = 6 + NEWMDS DOFs, N their sum over the
bodies: WAMIT's one sequence of modes, each body's rigid modes and then its generalised ones)::

    /simulation_parameters/  rho, g, w (n_f) [rad/s], T (n_f) [s], wave_dir (n_h) [deg],
                             water_depth [m] or the string "infinite", scaled (0 or 1)
    /body<b>/properties/     name, cg (3) [m], cb (3) [m], disp_vol [m^3], dof (n_b, default 6), dof_start,
                             dof_end (1-based rows of the body among the N)
    /body<b>/hydro_coeffs/   linear_restoring_stiffness (n_b, n_b)
                             added_mass/all (n_b, N, n_f), added_mass/inf_freq (n_b, N)
                             radiation_damping/all (n_b, N, n_f)
                             excitation/re, excitation/im (n_b, n_h, n_f)
                             excitation/scattering/{re,im}, excitation/froude-krylov/{re,im} (optional)

MATLAB writes vectors as (n, 1) and scalars as (1, 1) arrays; both are accepted. Coefficients follow WAMIT's
conventions: Re[X exp(+i omega t)] (BEMIO conjugates Capytaine's and NEMOH's values when it reads them), row
index = force, column index = motion. With ``scaled = 0`` (what WEC-Sim writes) they are normalised as WAMIT
does with unit length: A / rho, B / (rho omega), X / (rho g), K / (rho g), and WEC-Sim multiplies them back
by rho, rho omega and rho g; with ``scaled = 1`` (Python bemio after ``scale``) they are dimensional.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from .._build import build_dataset
from .._schema import dof_name

__all__ = ["read_bemio"]

PathLike = str | os.PathLike[str]

_DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
_FROUDE_KRYLOV_GROUPS = ("froude-krylov", "froude_krylov", "froud_krylof")


class BemioFormatError(ValueError):
    """A BEMIO ``.h5`` file lacks something or holds arrays of unexpected shape (the message names the dataset)."""


def read_bemio(
    path: PathLike,
    *,
    body_names: Sequence[str] | None = None,
    rho: float | None = None,
    g: float | None = None,
    mode_names: Mapping[str, Sequence[str]] | None = None,
) -> xr.Dataset:
    """Read a BEMIO / WEC-Sim ``.h5`` hydrodynamic file into a wecss hydrodynamic dataset.

    Conventions of the result (see the module docstring for the file layout):

    - coefficients are made dimensional with rho and g (and omega for damping) unless the file says
      ``scaled = 1``;
    - ``omega`` is ``/simulation_parameters/w`` sorted increasing (only finite positive values are kept);
      ``wave_direction`` is ``wave_dir`` converted from degrees to radians (BEMIO stores WAMIT's headings in
      degrees; Python bemio labels them "rad" but writes degrees too);
    - BEMIO holds no zero-frequency added mass, so ``added_mass_zero`` is absent;
    - WEC-Sim takes the BEM coefficients to be about each body's centre of gravity ``cg``, which becomes
      both ``center_of_mass`` and ``reference_point``; ``center_of_buoyancy`` is ``cb`` as stored (global
      coordinates in WEC-Sim's MATLAB BEMIO; the old Python bemio stored WAMIT's body-relative value);
    - ``hydrostatic_stiffness`` is ``linear_restoring_stiffness``: about the centre of gravity the weight has
      no moment arm (the -m g z_g term of a BEM code's total restoring vanishes when its reference point is
      the centre of gravity), so it is the buoyancy stiffness the schema asks for;
    - ``mass`` = rho * ``disp_vol`` (freely floating); BEMIO stores no inertia, so ``inertia`` is zero and the
      attribute ``inertia_unknown_bodies`` lists every body;
    - a body with ``dof`` = 6 + n holds n generalised modes (WAMIT's modes 7..), the DOFs ``<body>__mode7``, ...
      (or ``mode_names``); they are normalised as the rigid DOFs are (unit length: by rho, rho omega, rho g). The
      structural matrices BEMIO keeps for them (``gbm``) are not read: a device spec gives its own.

    Parameters
    ----------
    path : str or os.PathLike
        The ``.h5`` file.
    body_names : sequence of str, optional
        One name per body (``body1``, ``body2``, ... order). Default: each body's ``properties/name``.
    rho : float, optional
        Water density [kg/m^3]. Default: the file's ``simulation_parameters/rho``. It may differ from the
        file's only for normalised data (``scaled = 0``).
    g : float, optional
        Gravitational acceleration [m/s^2]. Default: the file's ``simulation_parameters/g``; same rule.
    mode_names : mapping of body name to sequence of str, optional
        Names of the generalised modes of each body with ``dof`` > 6 (as many as it has; body names as in the
        result). Default: ``mode7``, ``mode8``, ...

    Returns
    -------
    xarray.Dataset
        A dataset in the wecss schema (not yet validated; ``wecss.hydro.HydroData`` validates).

    Raises
    ------
    ImportError
        If h5py is not installed (``pip install "wecss[h5]"``).
    FileNotFoundError
        If ``path`` does not exist.
    BemioFormatError
        (a ``ValueError``) If a required dataset is missing or has an unexpected shape (the message names it and
        gives the shape received and the one expected), a body's ``dof`` is below 6 or its ``dof_start`` disagrees
        with the bodies before it.
    ValueError
        If ``body_names`` has the wrong length, repeats a name or holds an invalid one; if ``rho`` or ``g`` is not
        positive, or differs from the file's value for dimensional (``scaled = 1``) data; if ``mode_names`` names
        an unknown body, gives a body another number of modes than the file, or an invalid name.
    """
    try:
        import h5py
    except ImportError as err:
        raise ImportError('reading BEMIO .h5 files needs h5py; install it with: pip install "wecss[h5]"') from err
    for name, value in (("rho", rho), ("g", g)):
        if value is not None and not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a positive number; got {value!r}")
    source = Path(path)
    if not source.is_file():
        raise FileNotFoundError(f"no BEMIO .h5 file at {str(source)!r}")

    try:
        f = h5py.File(source, "r")
    except OSError as err:
        raise BemioFormatError(_unreadable(source, err)) from None
    try:
        with f:
            reader = _Reader(f, source)
            params = "simulation_parameters"
            scaled = bool(reader.scalar(f"{params}/scaled", default=0.0))
            file_rho = reader.scalar(f"{params}/rho", default=np.nan)
            file_g = reader.scalar(f"{params}/g", default=np.nan)
            rho_used = _choose(rho, file_rho, "rho", scaled, source)
            g_used = _choose(g, file_g, "g", scaled, source)
            omega_all = reader.vector(f"{params}/w")
            wave_dir_deg = reader.vector(f"{params}/wave_dir")
            depth = reader.water_depth(f"{params}/water_depth")

            numbers = sorted(int(m.group(1)) for key in f if (m := re.fullmatch(r"body(\d+)", key)))
            if not numbers:
                raise BemioFormatError(f"{source}: no /body1, /body2, ... groups; is this a BEMIO .h5 file?")
            if numbers != list(range(1, len(numbers) + 1)):
                found = ", ".join(f"body{n}" for n in numbers)
                raise BemioFormatError(f"{source}: body groups must be body1..bodyN; found {found}")
            n_bodies = len(numbers)
            sizes = [_body_dofs(reader, f"body{b + 1}/properties") for b in range(n_bodies)]
            starts = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(int)
            n_dof, n_f, n_h = int(sum(sizes)), omega_all.size, wave_dir_deg.size

            added = np.zeros((n_dof, n_dof, n_f))
            damping = np.zeros((n_dof, n_dof, n_f))
            a_inf = np.zeros((n_dof, n_dof))
            stiffness = np.zeros((n_dof, n_dof))
            exc = np.zeros((n_dof, n_h, n_f), dtype=complex)
            parts: dict[str, np.ndarray | None] = {
                "diffraction": np.zeros_like(exc),
                "froude_krylov": np.zeros_like(exc),
            }
            names, cg, cb, volume = [], np.zeros((n_bodies, 3)), np.zeros((n_bodies, 3)), np.zeros(n_bodies)
            for b in range(n_bodies):
                body = f"body{b + 1}"
                dof = sizes[b]
                start = reader.scalar(f"{body}/properties/dof_start", default=float(starts[b] + 1))
                if int(start) != starts[b] + 1:
                    raise BemioFormatError(
                        f"{source}: /{body}/properties/dof_start = {start:g}; the bodies before it have "
                        f"{starts[b]} DOFs (dof of each body: {sizes}), so it should be {starts[b] + 1}"
                    )
                rows = slice(int(starts[b]), int(starts[b]) + dof)
                names.append(reader.string(f"{body}/properties/name", default=body))
                cg[b] = reader.vector(f"{body}/properties/cg", size=3)
                cb[b] = reader.vector(f"{body}/properties/cb", size=3)
                volume[b] = reader.scalar(f"{body}/properties/disp_vol")
                coeffs = f"{body}/hydro_coeffs"
                stiffness[rows, rows] = reader.array(f"{coeffs}/linear_restoring_stiffness", (dof, dof))
                added[rows] = reader.array(f"{coeffs}/added_mass/all", (dof, n_dof, n_f))
                a_inf[rows] = reader.array(f"{coeffs}/added_mass/inf_freq", (dof, n_dof))
                damping[rows] = reader.array(f"{coeffs}/radiation_damping/all", (dof, n_dof, n_f))
                exc[rows] = reader.complex(f"{coeffs}/excitation", (dof, n_h, n_f))
                for key, groups in (("diffraction", ("scattering",)), ("froude_krylov", _FROUDE_KRYLOV_GROUPS)):
                    part = parts[key]
                    if part is None:
                        continue
                    candidates = [f"{coeffs}/excitation/{group_name}" for group_name in groups]
                    group = next((c for c in candidates if f"{c}/re" in f), None)
                    values = None if group is None else reader.complex(group, (dof, n_h, n_f))
                    if values is None or not np.all(np.isfinite(values)):
                        parts[key] = None  # absent, or WEC-Sim's NaN placeholder
                    else:
                        part[rows] = values
            code = reader.string("bem_data/code", default="")
    except OSError as err:  # a damaged block inside a file whose header reads
        raise BemioFormatError(_unreadable(source, err)) from None

    keep = np.flatnonzero(np.isfinite(omega_all) & (omega_all > 0))
    omega = omega_all[keep]
    order = np.argsort(omega)
    omega, keep = omega[order], keep[order]
    if omega.size and np.any(np.diff(omega) <= 0):
        raise BemioFormatError(f"{source}: /{params}/w holds repeated frequencies")

    f_damp: float | np.ndarray
    if scaled:
        f_mass = f_damp = f_exc = f_stiff = 1.0
    else:
        f_mass, f_exc, f_stiff = rho_used, rho_used * g_used, rho_used * g_used
        f_damp = rho_used * omega[:, None, None]

    def matrices(values: np.ndarray) -> np.ndarray:  # (row, column, frequency) -> (omega, row, column)
        return np.moveaxis(values[..., keep], -1, 0)

    def forces(values: np.ndarray) -> np.ndarray:  # (dof, heading, frequency) -> (omega, heading, dof)
        return np.transpose(values[..., keep], (2, 1, 0))

    names = _body_names(body_names, names, source)
    modes = _mode_names(mode_names, names, [n - 6 for n in sizes])
    dofs = [dof_name(body, d) for body, extra in zip(names, modes, strict=True) for d in (*_DOFS, *extra)]
    attrs: dict[str, object] = {
        "bemio_scaled": int(scaled),
        "bemio_code": code,
        "inertia_unknown_bodies": ", ".join(names),
        "inertia_note": "BEMIO files hold no inertia; set to zero",
        "center_of_mass_note": "BEMIO cg, taken (as WEC-Sim does) as the point the coefficients are about",
    }
    if keep.size != omega_all.size:
        attrs["omega_dropped"] = ", ".join(f"{w:g}" for w in np.delete(omega_all, keep))
    optional = {k: None if v is None else forces(v) * f_exc for k, v in parts.items()}
    return build_dataset(
        omega=omega,
        dofs=dofs,
        wave_direction=np.deg2rad(wave_dir_deg),
        added_mass=matrices(added) * f_mass,
        radiation_damping=matrices(damping) * f_damp,
        added_mass_inf=a_inf * f_mass,
        excitation=forces(exc) * f_exc,
        hydrostatic_stiffness=stiffness * f_stiff,
        bodies=names,
        mass=rho_used * volume,
        inertia=np.zeros((n_bodies, 3, 3)),
        center_of_mass=cg,
        center_of_buoyancy=cb,
        displaced_volume=volume,
        reference_point=cg.copy(),
        rho=rho_used,
        g=g_used,
        water_depth=depth,
        source=f"BEMIO h5 {source.name}" + (f" ({code})" if code else ""),
        froude_krylov=optional["froude_krylov"],
        diffraction=optional["diffraction"],
        attrs=attrs,
    )


def _unreadable(source: Path, err: OSError) -> str:
    """The message for an ``.h5`` file HDF5 cannot read: the file, what is wrong (truncated, not HDF5) and
    HDF5's own words."""
    reason = str(err)
    size = source.stat().st_size
    if "truncated file" in reason:
        what = f"truncated or damaged: {size} bytes, the file's header says more"
    elif "signature not found" in reason:
        what = "the file is empty" if size == 0 else "not an HDF5 file (no HDF5 signature)"
    else:
        what = "damaged"
    return f"cannot read the BEMIO .h5 file {str(source)!r}: {what} (HDF5: {reason}); accepted: a whole BEMIO .h5 file"


def _choose(value: float | None, in_file: float, name: str, scaled: bool, source: Path) -> float:
    if value is None:
        if not (np.isfinite(in_file) and in_file > 0):
            raise BemioFormatError(f"{source}: no valid /simulation_parameters/{name}; pass {name}=...")
        return float(in_file)
    if scaled and np.isfinite(in_file) and not np.isclose(value, in_file, rtol=1e-12, atol=0.0):
        raise ValueError(
            f"{source} holds dimensional data (scaled = 1) made with {name} = {in_file:g}; got {name} = {value:g}. "
            f"Only normalised files (scaled = 0) can be dimensionalised with another {name}"
        )
    return float(value)


def _body_names(body_names: Sequence[str] | None, from_file: list[str], source: Path) -> list[str]:
    if body_names is None:
        names = from_file
        hint = "; pass body_names=[...]"
    else:
        names = [body_names] if isinstance(body_names, str) else [str(b) for b in body_names]
        hint = ""
        if len(names) != len(from_file):
            raise ValueError(
                f"body_names has {len(names)} names {names}; {source.name} has {len(from_file)} bodies {from_file}"
            )
    if len(set(names)) != len(names):
        raise ValueError(f"body names must be distinct; got {names}{hint}")
    for name in names:
        try:
            dof_name(name, "Surge")
        except ValueError as err:
            raise ValueError(f"{err}{hint}") from None
    return names


def _body_dofs(reader: _Reader, properties: str) -> int:
    """A body's number of DOFs, 6 plus its generalised modes (``properties/dof``, default 6)."""
    value = reader.scalar(f"{properties}/dof", default=6.0)
    if value != int(value) or value < 6:
        raise BemioFormatError(
            f"{reader.source}: /{properties}/dof = {value:g}; expected a whole number >= 6 (6 rigid-body DOFs, then "
            "the body's generalised modes)"
        )
    return int(value)


def _mode_names(given: Mapping[str, Sequence[str]] | None, bodies: list[str], counts: list[int]) -> list[list[str]]:
    """Names of each body's generalised modes: ``given`` (checked against the file's counts), else mode7, mode8..."""
    given = dict(given or {})
    unknown = sorted(set(given) - set(bodies))
    if unknown:
        raise ValueError(f"mode_names names unknown bodies {unknown}; bodies: {bodies}")
    out = []
    for body, count in zip(bodies, counts, strict=True):
        names = [str(m) for m in given.get(body, [f"mode{7 + j}" for j in range(count)])]
        if len(names) != count or len(set(names)) != count:
            raise ValueError(
                f"mode_names[{body!r}] must give {count} distinct names (the body's dof is {6 + count}); got {names}"
            )
        for name in names:
            dof_name(body, name)  # raises ValueError for a name that cannot name a generalised mode
        out.append(names)
    return out


class _Reader:
    """Typed access to datasets of an open h5py file, with errors naming the dataset."""

    def __init__(self, f: Any, source: Path) -> None:
        self.f = f
        self.source = source

    def _get(self, key: str) -> Any:
        if key not in self.f:
            raise BemioFormatError(f"{self.source}: missing dataset /{key}")
        return self.f[key][()]

    def array(self, key: str, shape: tuple[int, ...]) -> np.ndarray:
        values = np.asarray(self._get(key), dtype=float)
        if values.shape != shape:
            raise BemioFormatError(
                f"{self.source}: /{key} has shape {values.shape}; expected {shape} (BEMIO layout, as h5py reads it)"
            )
        return values

    def complex(self, group: str, shape: tuple[int, ...]) -> np.ndarray:
        return self.array(f"{group}/re", shape) + 1j * self.array(f"{group}/im", shape)

    def vector(self, key: str, size: int | None = None) -> np.ndarray:
        values = np.asarray(self._get(key), dtype=float)
        if values.ndim > 1 and sum(s > 1 for s in values.shape) > 1:
            raise BemioFormatError(f"{self.source}: /{key} has shape {values.shape}; expected a vector")
        values = values.ravel()
        if size is not None and values.size != size:
            raise BemioFormatError(f"{self.source}: /{key} has {values.size} values; expected {size}")
        return values

    def scalar(self, key: str, default: float | None = None) -> float:
        if key not in self.f and default is not None:
            return default
        values = np.asarray(self._get(key), dtype=float).ravel()
        if values.size != 1:
            raise BemioFormatError(f"{self.source}: /{key} has {values.size} values; expected one")
        return float(values[0])

    def string(self, key: str, default: str) -> str:
        if key not in self.f:
            return default
        value = self._get(key)
        if isinstance(value, np.ndarray):
            value = value.ravel()[0] if value.size else ""
        if isinstance(value, bytes | np.bytes_):
            return bytes(value).decode(errors="replace").strip("\x00 ")
        return str(value).strip()

    def water_depth(self, key: str) -> float:
        value = np.asarray(self._get(key))
        if value.dtype.kind in "fiu":
            depth = float(value.ravel()[0])
        else:
            text = self.string(key, default="").lower()
            if text in ("inf", "infinite", "infinity"):
                return float("inf")
            try:
                depth = float(text)
            except ValueError:
                raise BemioFormatError(
                    f"{self.source}: /{key} is {text!r}; expected a depth [m] or 'infinite'"
                ) from None
        if not depth > 0:
            raise BemioFormatError(f"{self.source}: /{key} = {depth!r}; expected a positive depth [m] or 'infinite'")
        return depth
