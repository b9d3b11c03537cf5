"""Reader of Capytaine results: a netCDF file written by Capytaine, or the dataset of ``capytaine.assemble_dataset``.

What changes on the way in:

- complex values stored with a ``complex = [re, im]`` dimension (netCDF files) are merged;
- Capytaine's time convention exp(-i omega t) becomes wecss's exp(+i omega t): the excitation, Froude-Krylov
  and diffraction forces are complex-conjugated (added mass and damping are real and unchanged);
- matrices are ordered (omega, influenced_dof, radiating_dof), the force index first;
- omega = 0 and omega = inf leave the frequency axis for ``added_mass_zero`` and ``added_mass_inf``;
- DOF names become ``<body>__<Dof>`` (a single body's DOFs get its name as prefix); the six rigid-body DOFs are
  recognised in any case (``heave``), any other DOF is a generalised mode of its body (a Capytaine custom DOF,
  ``body.dofs["flex1"] = <displacement per unit coordinate at the faces>``) and keeps its name; each body's rigid
  DOFs come first, then its generalised modes, in the order of the data;
- the hydrostatic stiffness loses its gravity part. Capytaine's rigid-body stiffness about the rotation
  centre c holds, besides the buoyancy (pressure) terms, the terms of the weight m g acting at the centre of
  mass G: -m g (z_G - z_c) in roll-roll and pitch-pitch, +m g (x_G - x_c) in roll-yaw and +m g (y_G - y_c)
  in pitch-yaw (``FloatingBody.each_hydrostatic_stiffness``). wecss stores the buoyancy alone, so these are
  removed with the mass and centre of mass this reader settles on for each body.

Per-body data (mass, inertia, centres of mass and buoyancy, volume, reference point) come from the dataset
where Capytaine stored them (``inertia_matrix``, ``center_of_mass``, ``center_of_buoyancy``, ``disp_mass``,
``rotation_center``) and may be given, or overridden, by keyword. Everything missing is reported at once.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Literal

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from ...constants import RIGID_BODY_DOFS
from ...netcdf import unreadable
from .._build import build_dataset
from .._repair import HIGHEST_FREQUENCY_SOURCE
from .._schema import check_mode_name, dof_index, split_dof
from .._validate import HydroDataError

PathLike = str | os.PathLike[str]

HIGHEST_FREQUENCY = "highest_frequency"
"""Value of ``added_mass_inf`` that takes the added mass at the highest frequency as the infinite-frequency limit."""

_FREQUENCY_TYPES = ("omega", "freq", "period", "wavenumber", "wavelength")
_FORCE_NAMES = {
    "excitation": "excitation_force",
    "froude_krylov": "Froude_Krylov_force",
    "diffraction": "diffraction_force",
}


def read_capytaine(
    source: PathLike | xr.Dataset,
    *,
    rho: float | None = None,
    g: float | None = None,
    added_mass_inf: ArrayLike | xr.DataArray | Literal["highest_frequency"] | None = None,
    mass: Mapping[str, float] | None = None,
    inertia: Mapping[str, ArrayLike] | None = None,
    center_of_mass: Mapping[str, ArrayLike] | None = None,
    center_of_buoyancy: Mapping[str, ArrayLike] | None = None,
    displaced_volume: Mapping[str, float] | None = None,
    reference_point: Mapping[str, ArrayLike] | None = None,
    hydrostatic_stiffness: ArrayLike | xr.DataArray | None = None,
) -> xr.Dataset:
    """Read Capytaine results into a wecss hydrodynamic dataset (not validated: ``HydroData(ds)`` does that).

    Parameters
    ----------
    source : path or xarray.Dataset
        A netCDF file written by Capytaine (``capytaine.export_dataset``), or the dataset returned by
        ``capytaine.assemble_dataset`` / ``BEMSolver.fill_dataset``.
    rho, g : float, optional
        Water density [kg/m^3] and gravity [m/s^2]. Taken from the dataset; a value given here must agree
        with it, and is used only when the dataset has none.
    added_mass_inf : array (n_dof, n_dof), DataArray, "highest_frequency" or None
        Infinite-frequency added mass when the dataset has no omega = inf: a matrix [kg, kg m, kg m^2]
        in this reader's DOF order (influenced DOF first) or a DataArray with dimensions
        ``influenced_dof`` and ``radiating_dof`` (wecss DOF names), or ``"highest_frequency"`` to take
        A(omega_max), an approximation recorded in the ``added_mass_inf_source`` attribute. When given, it
        replaces the dataset's own omega = inf values. ``None`` (default) requires omega = inf in the data.
    mass : mapping body -> float, optional
        Body masses [kg]. Default: the translational diagonal of Capytaine's ``inertia_matrix``, else the
        displaced mass ``disp_mass`` (Capytaine's own default for a body without mass).
    inertia : mapping body -> (3, 3) or (3,), optional
        Inertia tensor about the centre of mass [kg m^2] (a 3-vector is the diagonal). Default: from the
        rotational block of ``inertia_matrix`` (about the rotation centre) by the parallel-axis theorem,
        which needs all three rotations of the body in the data.
    center_of_mass, center_of_buoyancy : mapping body -> (3,), optional
        [m]. Default: the dataset's ``center_of_mass`` and ``center_of_buoyancy``.
    displaced_volume : mapping body -> float, optional
        [m^3]. Default: ``disp_mass / rho``.
    reference_point : mapping body -> (3,), optional
        Point the coefficients of the body are given about [m]: the rotation centre of its rotation DOFs.
        Default: the dataset's ``rotation_center`` (for a body without rotation DOFs, its centre of mass).
    hydrostatic_stiffness : array (n_dof, n_dof) or DataArray, optional
        Replaces the dataset's ``hydrostatic_stiffness``, in its convention (about the rotation centre, with the
        weight terms of ``FloatingBody.compute_hydrostatic_stiffness``, which the reader removes as for the
        dataset's own): a matrix in this reader's DOF order or a DataArray with dimensions ``influenced_dof`` and
        ``radiating_dof`` (wecss DOF names). Capytaine computes no hydrostatics for a body with custom DOFs
        (generalised modes) unless it is given their divergence; pass the rigid body's stiffness with the
        generalised modes' rows and columns [SI per unit coordinate] here.

    Returns
    -------
    xarray.Dataset
        In the wecss schema, complex amplitudes in Re[X exp(+i omega t)], hydrostatic stiffness of the
        buoyancy alone about ``reference_point``.

    Raises
    ------
    FileNotFoundError
        If ``source`` is a path that does not exist.
    TypeError
        If ``source`` is neither a path nor an ``xarray.Dataset``.
    HydroDataError
        If the data lack something the schema needs (radiation or diffraction results, omega = inf, per-body
        data, hydrostatic stiffness, ...): one message lists everything missing and how to supply it; or if
        they hold several values of rho, g, water depth, or a forward speed.
    ValueError
        If a keyword value is malformed, names an unknown body, or ``rho``/``g`` disagree with the data.

    Examples
    --------
    >>> ds = read_capytaine("rm3.nc", added_mass_inf="highest_frequency",
    ...                     center_of_mass={"rm3_float": (0, 0, -0.72), "rm3_spar": (0, 0, -21.29)})  # doctest: +SKIP
    """
    raw, label = _open(source)
    ds = _merge_complex(raw)
    ds = _frequency_dimension(ds)
    rho_, g_ = _constant(ds, "rho", rho), _constant(ds, "g", g)
    depth = _scalar(ds, "water_depth")
    if depth is None:
        raise HydroDataError("the Capytaine dataset has no 'water_depth'; expected a coordinate (inf for deep water)")
    speed = _scalar(ds, "forward_speed")
    if speed not in (None, 0.0):
        raise HydroDataError(f"forward speed {speed} m/s is not supported; wecss databases are for zero forward speed")

    capy_dofs, dofs = _dof_names(ds)
    bodies = list(dict.fromkeys(split_dof(d)[0] for d in dofs))
    _check_keys(
        bodies,
        mass=mass,
        inertia=inertia,
        center_of_mass=center_of_mass,
        center_of_buoyancy=center_of_buoyancy,
        displaced_volume=displaced_volume,
        reference_point=reference_point,
    )

    radiation = _radiation(ds, capy_dofs)
    forces = _forces(ds, capy_dofs)
    excitation = _excitation(forces)
    omega_all = np.asarray(ds.omega.values, dtype=float)
    finite = np.isfinite(omega_all) & (omega_all > 0)
    if np.count_nonzero(finite) == 0:
        raise HydroDataError("the Capytaine dataset has no finite, positive frequency")
    main = np.flatnonzero(finite)
    _check_complete(omega_all[main], radiation, excitation, main)

    missing: list[str] = []
    a_inf, a_inf_note = _added_mass_inf(omega_all, radiation["added_mass"], main, added_mass_inf, dofs, missing)
    zero = np.flatnonzero(omega_all == 0)
    a_zero = radiation["added_mass"][zero[0]] if zero.size else None

    props = _BodyData(ds, capy_dofs, dofs, bodies, rho_, missing)
    masses = props.mass(mass)
    com = props.vectors("center_of_mass", center_of_mass)
    ref = props.reference_points(reference_point, com)
    cob = props.vectors("center_of_buoyancy", center_of_buoyancy)
    volume = props.volumes(displaced_volume)
    tensor = props.inertia(inertia, masses, com, ref)
    stiffness = (
        _hydrostatic_stiffness(ds, capy_dofs, missing)
        if hydrostatic_stiffness is None
        else _given_matrix(hydrostatic_stiffness, dofs, "hydrostatic_stiffness")
    )
    if missing or stiffness is None or a_inf is None:
        raise HydroDataError(f"cannot read {label} into a wecss database; missing:\n  - " + "\n  - ".join(missing))
    stiffness = stiffness + _gravity_terms(dofs, bodies, masses, com, ref, g_)

    attrs: dict[str, object] = {
        (k if k.startswith("capytaine") else f"capytaine_{k}"): v for k, v in raw.attrs.items() if _netcdf_attr(v)
    }
    attrs["added_mass_inf_source"] = a_inf_note
    return build_dataset(
        omega=omega_all[main],
        dofs=dofs,
        wave_direction=np.asarray(excitation.wave_direction.values, dtype=float),
        added_mass=radiation["added_mass"][main],
        radiation_damping=radiation["radiation_damping"][main],
        added_mass_inf=a_inf,
        added_mass_zero=a_zero,
        excitation=np.conj(excitation.values[main]),
        froude_krylov=_conjugate(forces["froude_krylov"], main),
        diffraction=_conjugate(forces["diffraction"], main),
        hydrostatic_stiffness=stiffness,
        bodies=bodies,
        mass=np.array([masses[b] for b in bodies]),
        inertia=np.array([tensor[b] for b in bodies]),
        center_of_mass=np.array([com[b] for b in bodies]),
        center_of_buoyancy=np.array([cob[b] for b in bodies]),
        displaced_volume=np.array([volume[b] for b in bodies]),
        reference_point=np.array([ref[b] for b in bodies]),
        rho=rho_,
        g=g_,
        water_depth=depth,
        source=f"{label} (Capytaine {raw.attrs.get('capytaine_version', 'unknown version')})",
        attrs=attrs,
    )


# --- input ---------------------------------------------------------------------------------------------
def _open(source: PathLike | xr.Dataset) -> tuple[xr.Dataset, str]:
    if isinstance(source, xr.Dataset):
        return source.copy(), "Capytaine dataset"
    if not isinstance(source, str | os.PathLike):
        raise TypeError(f"source must be a path or an xarray.Dataset; got {type(source).__name__}")
    path = Path(source)
    if not path.is_file():
        raise FileNotFoundError(f"no Capytaine netCDF file at {str(path)!r}")
    try:
        with xr.open_dataset(path) as ds:
            return ds.load(), f"Capytaine file {path.name}"
    except (OSError, RuntimeError, ValueError, KeyError, IndexError) as err:
        raise unreadable(path, err) from None


def _merge_complex(ds: xr.Dataset) -> xr.Dataset:
    """Merge a ``complex`` dimension of length 2 (real part first, or labelled ``re``/``im``)."""
    if "complex" not in ds.dims:
        return ds
    if ds.sizes["complex"] != 2:
        raise HydroDataError(f"dimension 'complex' must have length 2 (re, im); got {ds.sizes['complex']}")
    labels = [str(v) for v in ds["complex"].values] if "complex" in ds.coords else ["re", "im"]
    if sorted(labels) != ["im", "re"]:
        raise HydroDataError(f"coordinate 'complex' must hold 're' and 'im'; got {labels}")
    i_re, i_im = labels.index("re"), labels.index("im")
    out = ds.copy()
    for name in list(out.data_vars):
        da = out[name]
        if "complex" in da.dims:
            merged = da.isel(complex=i_re, drop=True) + 1j * da.isel(complex=i_im, drop=True)
            merged.attrs = da.attrs
            out[name] = merged
    return out.drop_vars("complex", errors="ignore")


def _frequency_dimension(ds: xr.Dataset) -> xr.Dataset:
    """Make ``omega`` the frequency dimension (Capytaine may index by period, freq, ...) and sort it."""
    if "omega" not in ds.dims:
        dims = [d for d in _FREQUENCY_TYPES if d in ds.dims]
        if not dims or "omega" not in ds.coords:
            raise HydroDataError(f"the Capytaine dataset has no 'omega' coordinate; its dimensions are {list(ds.dims)}")
        ds = ds.swap_dims({dims[0]: "omega"})
    return ds.sortby("omega")


def _scalar(ds: xr.Dataset, name: str) -> float | None:
    """Value of a scalar setting that may be a coordinate, a length-1 dimension or absent."""
    if name not in ds.variables:
        return None
    values = np.atleast_1d(np.asarray(ds[name].values, dtype=float))
    if values.size != 1:
        raise HydroDataError(
            f"the Capytaine dataset holds {values.size} values of {name!r} ({values.tolist()}); "
            f"select one first, e.g. ds.sel({name}={values[0]!r})"
        )
    return float(values[0])


def _constant(ds: xr.Dataset, name: str, given: float | None) -> float:
    stored = _scalar(ds, name)
    if given is not None and not (np.isfinite(given) and given > 0):
        raise ValueError(f"{name} must be a positive finite number; got {given!r}")
    if stored is not None and given is not None and not np.isclose(stored, given, rtol=1e-9):
        raise ValueError(f"{name} = {given} disagrees with the value {stored} the Capytaine results were computed with")
    value = stored if stored is not None else given
    if value is None:
        raise HydroDataError(f"the Capytaine dataset has no {name!r}; pass {name}= to read_capytaine")
    return float(value)


def _dof_names(ds: xr.Dataset) -> tuple[list[str], list[str]]:
    """Capytaine's radiating DOF names (in influenced order) and the wecss names ``<body>__<Dof>``."""
    for dim in ("influenced_dof", "radiating_dof"):
        if dim not in ds.dims:
            raise HydroDataError(f"the Capytaine dataset has no {dim!r} dimension (no radiation results?)")
    radiating = {str(d) for d in ds.radiating_dof.values}
    capy = [str(d) for d in ds.influenced_dof.values if str(d) in radiating]
    prefix = None
    for name in ("body", "body_name"):
        if name in ds.variables and ds[name].ndim == 0:
            prefix = str(ds[name].values)
    named: list[tuple[str, str, str, bool]] = []  # (Capytaine name, body, DOF part, rigid)
    for name in capy:
        body, sep, dof = name.rpartition("__")
        if not sep:
            if prefix is None:
                raise HydroDataError(f"DOF {name!r} has no body prefix and the dataset names no single body")
            body, dof = prefix, name
        folded = dof[:1].upper() + dof[1:].lower()
        if folded in RIGID_BODY_DOFS:
            named.append((name, body, folded, True))
            continue
        try:
            check_mode_name(dof)
        except ValueError as err:
            raise HydroDataError(
                f"DOF {name!r} is neither a rigid-body DOF ({', '.join(RIGID_BODY_DOFS)}) nor a usable generalised "
                f"mode name: {err}"
            ) from None
        named.append((name, body, dof, False))
    bodies = list(dict.fromkeys(body for _, body, _, _ in named))
    # each body's rigid DOFs first, then its generalised modes (the schema's order), each in the data's order
    ordered = [
        entry for b in bodies for rigid in (True, False) for entry in named if entry[1] == b and entry[3] == rigid
    ]
    return [c for c, *_ in ordered], [f"{body}__{dof}" for _, body, dof, _ in ordered]


def _check_keys(bodies: list[str], **mappings: Mapping[str, object] | None) -> None:
    for keyword, mapping in mappings.items():
        if mapping is None:
            continue
        if not isinstance(mapping, Mapping):
            raise ValueError(f"{keyword} must be a mapping body name -> value; got {type(mapping).__name__}")
        unknown = sorted(set(mapping) - set(bodies))
        if unknown:
            raise ValueError(f"{keyword} names unknown bodies {unknown}; bodies in the data: {bodies}")


# --- frequency-dependent data --------------------------------------------------------------------------
def _radiation(ds: xr.Dataset, capy_dofs: list[str]) -> dict[str, np.ndarray]:
    out = {}
    for name in ("added_mass", "radiation_damping"):
        if name not in ds:
            raise HydroDataError(f"the Capytaine dataset has no {name!r} (no radiation results)")
        da = ds[name]
        extra = [d for d in da.dims if d not in ("omega", "influenced_dof", "radiating_dof")]
        if extra:
            raise HydroDataError(f"{name!r} has unexpected dimensions {extra}; select single values first")
        da = da.sel(influenced_dof=capy_dofs, radiating_dof=capy_dofs)
        out[name] = np.asarray(da.transpose("omega", "influenced_dof", "radiating_dof").values, dtype=float)
    return out


def _forces(ds: xr.Dataset, capy_dofs: list[str]) -> dict[str, xr.DataArray | None]:
    found: dict[str, xr.DataArray | None] = {}
    for key, name in _FORCE_NAMES.items():
        if name not in ds:
            found[key] = None
            continue
        da = ds[name]
        if "wave_direction" not in da.dims:
            da = da.expand_dims("wave_direction")
        extra = [d for d in da.dims if d not in ("omega", "wave_direction", "influenced_dof")]
        if extra:
            raise HydroDataError(f"{name!r} has unexpected dimensions {extra}; select single values first")
        found[key] = da.sel(influenced_dof=capy_dofs).transpose("omega", "wave_direction", "influenced_dof")
    return found


def _excitation(forces: dict[str, xr.DataArray | None]) -> xr.DataArray:
    """The excitation force, or the sum of its Froude-Krylov and diffraction parts."""
    excitation, froude_krylov, diffraction = forces["excitation"], forces["froude_krylov"], forces["diffraction"]
    if excitation is not None:
        return excitation
    if froude_krylov is None or diffraction is None:
        raise HydroDataError(
            "the Capytaine dataset has no 'excitation_force' (nor both 'Froude_Krylov_force' and "
            "'diffraction_force'): solve diffraction problems too"
        )
    return froude_krylov + diffraction


def _conjugate(force: xr.DataArray | None, main: np.ndarray) -> np.ndarray | None:
    """exp(-i omega t) to exp(+i omega t) at the finite frequencies."""
    return None if force is None else np.conj(force.values[main])


def _check_complete(
    omega: np.ndarray, radiation: dict[str, np.ndarray], excitation: xr.DataArray, main: np.ndarray
) -> None:
    bad = np.zeros(main.size, dtype=bool)
    for values in radiation.values():
        bad |= ~np.all(np.isfinite(values[main]), axis=(1, 2))
    bad |= ~np.all(np.isfinite(excitation.values[main]), axis=(1, 2))
    if np.any(bad):
        where = ", ".join(f"{w:.4g}" for w in omega[bad][:8]) + (" ..." if np.count_nonzero(bad) > 8 else "")
        raise HydroDataError(
            f"radiation or diffraction results are missing (NaN) at omega = {where} rad/s; every finite frequency "
            "needs both radiation problems for all DOFs and diffraction problems"
        )


def _added_mass_inf(
    omega: np.ndarray,
    added_mass: np.ndarray,
    main: np.ndarray,
    given: object,
    dofs: list[str],
    missing: list[str],
) -> tuple[np.ndarray | None, str]:
    if isinstance(given, str):
        if given != HIGHEST_FREQUENCY:
            raise ValueError(f"added_mass_inf must be a matrix, {HIGHEST_FREQUENCY!r} or None; got {given!r}")
        w = omega[main[-1]]
        return added_mass[main[-1]], f"{HIGHEST_FREQUENCY_SOURCE}, omega = {w:.6g} rad/s (approximation)"
    if given is not None:
        return _given_matrix(given, dofs, "added_mass_inf"), "given to read_capytaine"
    at_inf = np.flatnonzero(np.isinf(omega))
    if at_inf.size and np.all(np.isfinite(added_mass[at_inf[0]])):
        return added_mass[at_inf[0]], "Capytaine, omega = inf"
    w = omega[main]
    missing.append(
        f"infinite-frequency added mass: no omega = inf in the data (frequencies {w[0]:.4g}-{w[-1]:.4g} rad/s); "
        "add omega=np.inf to the radiation problems, or pass added_mass_inf=<matrix> or "
        f"added_mass_inf={HIGHEST_FREQUENCY!r} (A at {w[-1]:.4g} rad/s, an approximation)"
    )
    return None, ""


def _given_matrix(given: object, dofs: list[str], keyword: str) -> np.ndarray:
    """A matrix over ``dofs`` given by keyword: a DataArray with wecss DOF names, or an array in the reader's order."""
    n = len(dofs)
    if isinstance(given, xr.DataArray):
        try:
            values = given.sel(influenced_dof=dofs, radiating_dof=dofs).transpose("influenced_dof", "radiating_dof")
        except (KeyError, ValueError) as err:
            raise ValueError(
                f"{keyword} must have dimensions influenced_dof and radiating_dof holding {dofs}: {err}"
            ) from None
        matrix = np.asarray(values.values, dtype=float)
    else:
        matrix = np.asarray(given, dtype=float)
    if matrix.shape != (n, n) or not np.all(np.isfinite(matrix)):
        raise ValueError(f"{keyword} must be a finite ({n}, {n}) matrix for DOFs {dofs}; got shape {matrix.shape}")
    return matrix


# --- per-body data -------------------------------------------------------------------------------------
class _BodyData:
    """Per-body values from the dataset or from keyword overrides; records what is missing."""

    def __init__(
        self, ds: xr.Dataset, capy_dofs: list[str], dofs: list[str], bodies: list[str], rho: float, missing: list[str]
    ) -> None:
        self.ds = ds
        self.capy_dofs = capy_dofs
        self.dofs = dofs
        self.bodies = bodies
        self.rho = rho
        self.missing = missing
        self.body_dofs = {b: [(k, split_dof(d)[1]) for k, d in enumerate(dofs) if split_dof(d)[0] == b] for b in bodies}

    def _stored(self, name: str) -> dict[str, np.ndarray]:
        """Per-body values of a Capytaine variable with an optional ``body`` dimension (NaN entries left out)."""
        if name not in self.ds.variables:
            return {}
        da = self.ds[name]
        if "body" in da.dims:
            names = [str(b) for b in da["body"].values]
            values = {b: np.asarray(da.isel(body=i).values, dtype=float) for i, b in enumerate(names)}
        elif len(self.bodies) == 1:
            values = {self.bodies[0]: np.asarray(da.values, dtype=float)}
        else:
            return {}
        return {b: v for b, v in values.items() if np.all(np.isfinite(v))}

    def _inertia_block(self, body: str) -> tuple[list[str], np.ndarray] | None:
        if "inertia_matrix" not in self.ds:
            return None
        idx = [k for k, dof in self.body_dofs[body] if dof in RIGID_BODY_DOFS]  # Capytaine: NaN on custom DOFs
        names = [self.capy_dofs[k] for k in idx]
        da = self.ds["inertia_matrix"]
        try:
            block = da.sel(influenced_dof=names, radiating_dof=names).transpose("influenced_dof", "radiating_dof")
        except KeyError:
            return None
        values = np.asarray(block.values, dtype=float)
        if not np.all(np.isfinite(values)):
            return None
        return [dof for _, dof in self.body_dofs[body] if dof in RIGID_BODY_DOFS], values

    def mass(self, given: Mapping[str, float] | None) -> dict[str, float]:
        given = dict(given or {})
        disp = self._stored("disp_mass")
        out = {}
        for b in self.bodies:
            if b in given:
                out[b] = _positive(given[b], f"mass of body {b!r}")
                continue
            block = self._inertia_block(b)
            translational = (
                [] if block is None else [block[1][i, i] for i, d in enumerate(block[0]) if d in RIGID_BODY_DOFS[:3]]
            )
            if translational:
                out[b] = float(np.mean(translational))
            elif b in disp:
                out[b] = float(disp[b])
            else:
                self.missing.append(f"mass of body {b!r}: pass mass={{{b!r}: <kg>}}")
                out[b] = np.nan
        return out

    def vectors(self, name: str, given: Mapping[str, ArrayLike] | None) -> dict[str, np.ndarray]:
        stored = self._stored(name)
        out = {}
        for b in self.bodies:
            if given is not None and b in given:
                out[b] = _vector(given[b], f"{name} of body {b!r}")
            elif b in stored and stored[b].shape == (3,):
                out[b] = stored[b]
            else:
                self.missing.append(f"{name.replace('_', ' ')} of body {b!r}: pass {name}={{{b!r}: (x, y, z)}}")
                out[b] = np.full(3, np.nan)
        return out

    def reference_points(
        self, given: Mapping[str, ArrayLike] | None, com: dict[str, np.ndarray]
    ) -> dict[str, np.ndarray]:
        stored = self._stored("rotation_center")
        out = {}
        for b in self.bodies:
            rotates = any(d in RIGID_BODY_DOFS[3:] for _, d in self.body_dofs[b])
            if given is not None and b in given:
                out[b] = _vector(given[b], f"reference point of body {b!r}")
            elif b in stored and stored[b].shape == (3,):
                out[b] = stored[b]
            elif not rotates:
                out[b] = com[b]  # translations do not depend on the reference point
            else:
                self.missing.append(
                    f"rotation centre (reference point) of body {b!r}: pass reference_point={{{b!r}: (x, y, z)}}"
                )
                out[b] = np.full(3, np.nan)
        return out

    def volumes(self, given: Mapping[str, float] | None) -> dict[str, float]:
        disp = self._stored("disp_mass")
        out = {}
        for b in self.bodies:
            if given is not None and b in given:
                out[b] = _positive(given[b], f"displaced volume of body {b!r}")
            elif b in disp:
                out[b] = float(disp[b]) / self.rho
            else:
                self.missing.append(f"displaced volume of body {b!r}: pass displaced_volume={{{b!r}: <m^3>}}")
                out[b] = np.nan
        return out

    def inertia(
        self,
        given: Mapping[str, ArrayLike] | None,
        masses: dict[str, float],
        com: dict[str, np.ndarray],
        ref: dict[str, np.ndarray],
    ) -> dict[str, np.ndarray]:
        out = {}
        for b in self.bodies:
            if given is not None and b in given:
                out[b] = _tensor(given[b], f"inertia of body {b!r}")
                continue
            block = self._inertia_block(b)
            rot = [] if block is None else [i for i, d in enumerate(block[0]) if d in RIGID_BODY_DOFS[3:]]
            if block is not None and len(rot) == 3:
                order = np.argsort([dof_index(block[0][i]) for i in rot])
                about_ref = block[1][np.ix_(np.array(rot)[order], np.array(rot)[order])]
                c = com[b] - ref[b]
                out[b] = about_ref - masses[b] * (float(c @ c) * np.eye(3) - np.outer(c, c))
            else:
                have = "none" if block is None or not rot else ", ".join(block[0][i] for i in rot)
                self.missing.append(
                    f"inertia of body {b!r} (the dataset's inertia_matrix covers rotations: {have}): "
                    f"pass inertia={{{b!r}: 3x3 about the centre of mass}}"
                )
                out[b] = np.full((3, 3), np.nan)
        return out


def _hydrostatic_stiffness(ds: xr.Dataset, capy_dofs: list[str], missing: list[str]) -> np.ndarray | None:
    if "hydrostatic_stiffness" not in ds:
        missing.append(
            "hydrostatic_stiffness: let Capytaine compute hydrostatics (bodies with a center_of_mass, "
            "assemble_dataset(..., hydrostatics=True))"
        )
        return None
    da = ds["hydrostatic_stiffness"]
    extra = [d for d in da.dims if d not in ("influenced_dof", "radiating_dof")]
    if extra:
        raise HydroDataError(f"'hydrostatic_stiffness' has unexpected dimensions {extra}; select single values first")
    values = np.asarray(
        da.sel(influenced_dof=capy_dofs, radiating_dof=capy_dofs).transpose("influenced_dof", "radiating_dof").values,
        dtype=float,
    )
    if not np.all(np.isfinite(values)):
        missing.append("hydrostatic_stiffness has NaN entries (Capytaine could not compute hydrostatics for some body)")
        return None
    return values


def _gravity_terms(
    dofs: list[str],
    bodies: list[str],
    masses: dict[str, float],
    com: dict[str, np.ndarray],
    ref: dict[str, np.ndarray],
    g: float,
) -> np.ndarray:
    """What to add to Capytaine's stiffness to remove its weight terms (see the module docstring)."""
    index = {name: k for k, name in enumerate(dofs)}
    out = np.zeros((len(dofs), len(dofs)))
    for b in bodies:
        weight = masses[b] * g
        dx, dy, dz = com[b] - ref[b]
        terms = {
            ("Roll", "Roll"): weight * dz,
            ("Pitch", "Pitch"): weight * dz,
            ("Roll", "Yaw"): -weight * dx,
            ("Pitch", "Yaw"): -weight * dy,
        }
        for (row, col), value in terms.items():
            i, j = index.get(f"{b}__{row}"), index.get(f"{b}__{col}")
            if i is not None and j is not None:
                out[i, j] += value
    return out


# --- small validators ------------------------------------------------------------------------------------
def _positive(value: object, what: str) -> float:
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a number; got {value!r}") from None
    if not (np.isfinite(number) and number > 0):
        raise ValueError(f"{what} must be positive and finite; got {value!r}")
    return number


def _vector(value: ArrayLike, what: str) -> np.ndarray:
    vector = np.asarray(value, dtype=float)
    if vector.shape != (3,) or not np.all(np.isfinite(vector)):
        raise ValueError(f"{what} must be 3 finite coordinates [m]; got {value!r}")
    return vector


def _tensor(value: ArrayLike, what: str) -> np.ndarray:
    tensor = np.asarray(value, dtype=float)
    if tensor.shape == (3,):
        tensor = np.diag(tensor)
    if tensor.shape != (3, 3) or not np.all(np.isfinite(tensor)):
        raise ValueError(f"{what} must be a 3x3 tensor or its diagonal (3 values) [kg m^2]; got shape {tensor.shape}")
    if not np.allclose(tensor, tensor.T, rtol=1e-9, atol=0):
        raise ValueError(f"{what} must be symmetric; got {tensor.tolist()}")
    return tensor


def _netcdf_attr(value: object) -> bool:
    return isinstance(value, str | int | float | np.integer | np.floating) and not isinstance(value, bool)
