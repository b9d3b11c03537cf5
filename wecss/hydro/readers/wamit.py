"""Read WAMIT output (``.out`` with the numeric ``.1``, ``.3``, ``.hst``, ``.mmx`` beside it) into the wecss schema.

WAMIT writes non-dimensional coefficients (length scale ULEN = L, water density rho, gravity g):

=====================  ==========================  ================================================
quantity               WAMIT value                 k or m
=====================  ==========================  ================================================
added mass A_ij        A_ij / (rho L^k)            k = 3, 4, 5 for 0, 1, 2 rotational indices
radiation damping      B_ij / (rho omega L^k)      as for A
excitation X_i         X_i / (rho g L^m)           m = 2 (force), 3 (moment), per unit wave amplitude
hydrostatics C_ij      C_ij / (rho g L^k)          k = 2, 3, 4 for 0, 1, 2 rotational indices
=====================  ==========================  ================================================

Complex amplitudes mean Re[X exp(+i omega t)] in WAMIT as in wecss: nothing is conjugated.

Generalised modes (NEWMDS > 0): WAMIT numbers the modes of all bodies in one sequence, body k's 6 rigid-body modes
followed by its NEWMDS(k) generalised modes (its modes 7, 8, ...). The number per body comes from the run's
``.cfg`` beside the ``.out`` (``NEWMDS(k) = n``, or ``NEWMDS = n`` for body 1) or from ``mode_names``. WAMIT
normalises the coefficients of generalised modes as those of translations (its manual, chapter 9: the mode
shape is a displacement field in units of length per unit coordinate), so they count as translations in the
exponents above (k = 3 for generalised-generalised added mass, m = 2 for their excitation, ...): with ULEN = 1
this gives the values WAMIT computed, in SI per unit generalised coordinate.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Literal

import numpy as np
import xarray as xr

from ...constants import RHO_WATER
from .._build import build_dataset
from .._schema import dof_name
from ._wamit_parse import OutFile, WamitFormatError, read_mmx_mass, read_numeric, read_out

__all__ = ["WamitFormatError", "read_wamit"]

PathLike = str | os.PathLike[str]

_DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
_PERIOD_RTOL = 1e-5
"""Relative tolerance when matching the periods of a numeric file to those of the ``.out`` file."""
_HEADING_ATOL_DEG = 0.5
"""Largest difference [deg] between a heading of the ``.3`` file and the (rounded) one in the ``.out`` file."""


def read_wamit(
    path: PathLike,
    *,
    body_names: Sequence[str] | None = None,
    rho: float = RHO_WATER,
    g: float | None = None,
    numeric_files: bool = True,
    excitation: Literal["diffraction", "haskind"] = "diffraction",
    mode_names: Mapping[str, Sequence[str]] | None = None,
) -> xr.Dataset:
    """Read WAMIT results into a wecss hydrodynamic dataset.

    The ``.out`` report gives the run parameters (gravity, ULEN, water depth), the body parameters
    (XBODY, volumes, centre of buoyancy, restoring coefficients, VCG, radii of gyration) and all
    coefficients. When ``numeric_files`` is true, the numeric files with the same stem are preferred
    where present, for their precision (the ``.out`` prints phases in whole degrees and hydrostatics with
    five digits): ``.1`` (added mass, damping), ``.3`` (diffraction excitation; ``.2`` for Haskind), ``.hst``
    (hydrostatics) and ``.mmx`` (mass matrix, for the inertia).

    Conventions of the result:

    - ``omega`` holds the finite periods, as 2 pi / T [rad/s], sorted increasing. WAMIT's special periods
      go to ``added_mass_zero`` ("Wave period = infinite", PER = -1 in ``.1``: omega = 0) and
      ``added_mass_inf`` ("Wave period = zero", PER = 0 in ``.1``: omega = infinity).
    - ``wave_direction`` [rad] is WAMIT's heading beta (0: waves travelling along +x).
    - DOFs are ``<body>__<Dof>``; coefficients are about each body's origin XBODY, which is the
      ``reference_point`` and (plus VCG, zero in most WEC runs) the ``center_of_mass``.
    - ``mass`` = rho * displaced volume (median of VOLX, VOLY, VOLZ), as for a freely floating body.
    - ``center_of_buoyancy`` = XBODY + (Xb, Yb, Zb) of the ``.out`` (which are in body coordinates).
    - ``inertia`` about the centre of mass from the ``.mmx`` mass matrix or the ``.out`` radii of gyration
      (I_ij = m r_ij |r_ij| about XBODY, shifted by the parallel-axis theorem); when WAMIT gives none
      (all zero, the usual case for WEC runs) it is zero and the attribute ``inertia_unknown_bodies``
      lists the bodies concerned.
    - ``hydrostatic_stiffness`` is the buoyancy (hydrostatic pressure) stiffness alone about XBODY. WAMIT's
      "hydrostatic and gravitational" C adds the weight of a freely floating body, m = rho V, acting at
      its centre of gravity (Xg, Yg, Zg) printed in the ``.out`` (body coordinates, Zg = VCG):
      C44 and C55 include -m g Zg, C46 includes +m g Xg and C56 includes +m g Yg. These terms are removed
      (C44 += m g Zg, C55 += m g Zg, C46 -= m g Xg, C56 -= m g Yg), from the ``.hst`` values as from the
      ``.out`` ones; with VCG = 0 (XBODY at the centre of gravity) the C44/C55 terms already vanish.

    Parameters
    ----------
    path : str or os.PathLike
        The ``.out`` file (another file of the run, such as ``rm3.1``, stands for the ``.out`` beside it).
    body_names : sequence of str, optional
        One name per body, in WAMIT's order (for RM3: ``["float", "spar"]``). Default ``body_1``,
        ``body_2``, ...
    rho : float
        Water density [kg/m^3] used to dimensionalise (WAMIT's output does not depend on it).
    g : float, optional
        Gravitational acceleration [m/s^2] used to dimensionalise excitation and hydrostatics. Default:
        the value of the WAMIT run (the ``Gravity:`` line), so that the data keep the g they were made with.
    numeric_files : bool
        Use the numeric files beside the ``.out`` when present (default). ``False`` reads the ``.out`` alone.
    excitation : {"diffraction", "haskind"}
        Which exciting forces to read (``.3`` / ``.2`` numeric files).
    mode_names : mapping of body name to sequence of str, optional
        Names of each body's generalised modes (WAMIT's modes 7, 8, ... of the body), which become the DOFs
        ``<body>__<name>``; they also give the number of modes per body when the run's ``.cfg`` is not beside the
        ``.out``. Default: ``mode7``, ``mode8``, ... for the NEWMDS(k) modes of the ``.cfg``.

    Returns
    -------
    xarray.Dataset
        A dataset in the wecss schema (not yet validated; ``wecss.hydro.HydroData`` validates).

    Raises
    ------
    FileNotFoundError
        If the ``.out`` file does not exist.
    WamitFormatError
        (a ``ValueError``) If a file cannot be interpreted; the message names the file and line. Also when
        a body is rotated (PHIBODY != 0), when there are generalised modes whose number per body is known
        neither from the ``.cfg`` nor from ``mode_names`` (or they disagree), when there are no exciting forces,
        or when a numeric file's periods or headings do not match the ``.out`` file.
    ValueError
        If ``body_names`` has the wrong length, repeats a name or holds an invalid one, or if ``rho``, ``g``
        or ``excitation`` are invalid.

    Examples
    --------
    >>> ds = read_wamit("rm3.out", body_names=["float", "spar"])  # doctest: +SKIP
    >>> ds.added_mass.sel(influenced_dof="float__Heave", radiating_dof="float__Heave")  # doctest: +SKIP
    """
    if excitation not in ("diffraction", "haskind"):
        raise ValueError(f"excitation must be 'diffraction' or 'haskind'; got {excitation!r}")
    for name, value in (("rho", rho), ("g", g)):
        if value is not None and not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a positive number; got {value!r}")
    out_path = _out_path(Path(path))
    counts, cfg = _generalised_counts(out_path, body_names, mode_names)
    out = read_out(out_path, excitation, counts)
    n_bodies = len(out.bodies)
    names = _body_names(body_names, out)
    modes = _mode_names(out, names, mode_names)
    for body in out.bodies:
        if abs(body.phibody_deg) > 0:
            raise WamitFormatError(
                f"{out_path}, line {body.line + 1}: body {body.number} is rotated "
                f"(PHIBODY = {body.phibody_deg:g} deg); coefficients in rotated body frames are not supported"
            )
    if out.excitation is None:
        raise WamitFormatError(
            f"{out_path}: no {excitation} exciting forces ('{excitation.upper()} EXCITING FORCES AND MOMENTS'); "
            f"try excitation={'haskind' if excitation == 'diffraction' else 'diffraction'!r}"
        )
    if out.added_mass_infinite_frequency is None:
        raise WamitFormatError(f"{out_path}: no infinite-frequency added mass ('Wave period = zero' section)")
    gravity = out.gravity if g is None else float(g)
    length = out.length_scale

    added_mass, damping = out.added_mass.copy(), out.damping.copy()
    a_zero = None if out.added_mass_zero_frequency is None else out.added_mass_zero_frequency.copy()
    a_inf = out.added_mass_infinite_frequency.copy()
    exc = out.excitation.copy()
    headings = np.deg2rad(out.headings_deg)
    restoring = _restoring_from_out(out)
    used = [out_path.name] + ([cfg.name] if cfg is not None else [])
    mass_matrices: list[np.ndarray] | None = None
    if numeric_files:
        if (f1 := _beside(out_path, ".1")) is not None:
            a_zero, a_inf = _merge_radiation(f1, out, added_mass, damping, a_zero, a_inf)
            used.append(f1.name)
        if (f3 := _beside(out_path, ".3" if excitation == "diffraction" else ".2")) is not None:
            headings = _merge_excitation(f3, out, exc)
            used.append(f3.name)
        if (fh := _beside(out_path, ".hst")) is not None:
            _merge_hydrostatics(fh, out, restoring)
            used.append(fh.name)
        if (fm := _beside(out_path, ".mmx")) is not None:
            mass_matrices = read_mmx_mass(fm, n_bodies, out.generalised_modes)
            used.append(fm.name)

    # --- frequencies ---------------------------------------------------------------------------
    omega = 2.0 * np.pi / out.periods
    order = np.argsort(omega)
    omega = omega[order]
    if np.any(np.diff(omega) <= 0):
        dup = out.periods[order][1:][np.diff(omega) <= 0]
        raise WamitFormatError(f"{out_path}: repeated wave periods {', '.join(f'{p:g}' for p in dup)} s")

    # --- modes kept and dimensional factors --------------------------------------------------------
    keep = np.flatnonzero(out.radiation_modes | out.excitation_modes)
    body_of, local = _mode_layout(out)
    rot = ((local >= 3) & (local < 6)).astype(int)  # generalised modes count as translations (module docstring)
    k_rad = 3 + rot[:, None] + rot[None, :]
    k_hst = 2 + rot[:, None] + rot[None, :]
    m_exc = 2 + rot
    sub = np.ix_(keep, keep)
    scale_rad = rho * length ** k_rad[sub]
    added = added_mass[order][:, keep][:, :, keep] * scale_rad
    damp = damping[order][:, keep][:, :, keep] * scale_rad * omega[:, None, None]
    exc_dim = exc[order][:, :, keep] * (rho * gravity * length ** m_exc[keep])

    # --- bodies --------------------------------------------------------------------------------
    volumes = np.array([float(np.median(b.volumes)) for b in out.bodies])
    masses = rho * volumes
    origins = np.vstack([b.origin for b in out.bodies])
    cogs = np.vstack([_center_of_gravity(b.center_of_gravity) for b in out.bodies])
    center_of_mass = origins + np.column_stack([np.zeros((n_bodies, 2)), cogs[:, 2]])
    cob = np.vstack(
        [
            b.origin + (b.center_of_buoyancy if b.center_of_buoyancy is not None else np.full(3, np.nan))
            for b in out.bodies
        ]
    )
    missing_cob = [names[k] for k, b in enumerate(out.bodies) if b.center_of_buoyancy is None]
    if missing_cob:
        raise WamitFormatError(f"{out_path}: no 'Center of Buoyancy' line for bodies {', '.join(missing_cob)}")

    stiffness = restoring * (rho * gravity * length**k_hst)
    removed = _remove_gravity_terms(stiffness, out, masses, cogs, gravity)
    inertia, unknown = _inertia(out, masses, cogs, rho, mass_matrices)

    dofs = [
        dof_name(names[body_of[m]], _DOFS[local[m]] if local[m] < 6 else modes[body_of[m]][local[m] - 6]) for m in keep
    ]
    attrs: dict[str, object] = {
        "wamit_version": out.version,
        "wamit_files": ", ".join(used),
        "wamit_gravity": out.gravity,
        "wamit_length_scale": length,
        "excitation_kind": excitation,
        "hydrostatics_note": (
            "buoyancy stiffness about XBODY; WAMIT's gravity terms (m = rho V at Xg, Yg, VCG) removed"
            + ("" if removed else " (none were present)")
        ),
        "center_of_mass_note": "WAMIT body origin XBODY (plus VCG), as the WAMIT run assumes",
    }
    if sum(out.generalised_modes):
        attrs["generalised_modes_note"] = "generalised modes normalised as translations (WAMIT's convention); " + (
            "hydrostatics from the .hst" if "hst" in " ".join(used) else "no .hst: their hydrostatics are the .out's"
        )
    if unknown:
        attrs["inertia_unknown_bodies"] = ", ".join(names[k] for k in unknown)
        attrs["inertia_note"] = "WAMIT output gives no radii of gyration or inertia for these bodies; set to zero"
    return build_dataset(
        omega=omega,
        dofs=dofs,
        wave_direction=headings,
        added_mass=added,
        radiation_damping=damp,
        added_mass_inf=a_inf[sub] * scale_rad,
        added_mass_zero=(a_zero[sub] * scale_rad) if a_zero is not None else None,
        excitation=exc_dim,
        hydrostatic_stiffness=stiffness[sub],
        bodies=names,
        mass=masses,
        inertia=inertia,
        center_of_mass=center_of_mass,
        center_of_buoyancy=cob,
        displaced_volume=volumes,
        reference_point=origins,
        rho=rho,
        g=gravity,
        water_depth=out.water_depth,
        source=f"WAMIT {out.version} output {out_path.name}".replace("  ", " "),
        attrs=attrs,
    )


# --- files ---------------------------------------------------------------------------------------


def _out_path(path: Path) -> Path:
    candidate = path if path.suffix.lower() == ".out" else path.with_suffix(".out")
    if not candidate.is_file():
        alt = candidate.with_suffix(".OUT")
        if alt.is_file():
            return alt
        hint = "" if candidate == path else f" (looked for {str(candidate)!r} beside {str(path)!r})"
        raise FileNotFoundError(f"no WAMIT .out file at {str(candidate)!r}{hint}")
    return candidate


def _beside(out_path: Path, suffix: str) -> Path | None:
    for candidate in (out_path.with_suffix(suffix), out_path.with_suffix(suffix.upper())):
        if candidate.is_file():
            return candidate
    return None


def _body_names(body_names: Sequence[str] | None, out: OutFile) -> list[str]:
    n = len(out.bodies)
    if body_names is None:
        return [f"body_{k + 1}" for k in range(n)]
    if isinstance(body_names, str):
        body_names = [body_names]
    names = [str(b) for b in body_names]
    files = f" (geometry files: {', '.join(out.geometry_files)})" if out.geometry_files else ""
    if len(names) != n:
        raise ValueError(f"body_names has {len(names)} names {names}; {out.path.name} has {n} bodies{files}")
    if len(set(names)) != n:
        raise ValueError(f"body_names must be distinct; got {names}")
    for name in names:
        dof_name(name, "Surge")  # raises ValueError for empty names or names holding '__'
    return names


_NEWMDS = re.compile(r"^\s*NEWMDS\s*(?:\(\s*(\d+)\s*\))?\s*=\s*(\d+)", re.IGNORECASE | re.MULTILINE)


def _generalised_counts(
    out_path: Path, body_names: Sequence[str] | None, mode_names: Mapping[str, Sequence[str]] | None
) -> tuple[dict[int, int], Path | None]:
    """NEWMDS(k) by 1-based body number, from the ``.cfg`` beside the ``.out`` and/or ``mode_names``, and the
    ``.cfg`` read (None when absent).

    Raises
    ------
    ValueError
        If ``mode_names`` is not a mapping of body names to lists of names, or names an unknown body.
    WamitFormatError
        If ``mode_names`` and the ``.cfg`` disagree on a body's number of modes.
    """
    cfg = _beside(out_path, ".cfg")
    from_cfg: dict[int, int] = {}
    if cfg is not None:
        for match in _NEWMDS.finditer(cfg.read_text(errors="replace")):
            from_cfg[int(match.group(1) or 1)] = int(match.group(2))
    if mode_names is None:
        return {k: n for k, n in from_cfg.items() if n}, cfg
    if not isinstance(mode_names, Mapping):
        raise ValueError(f"mode_names must map body names to lists of mode names; got {mode_names!r}")
    known = [str(b) for b in ([body_names] if isinstance(body_names, str) else body_names or [])]
    counts = dict(from_cfg)
    for body, names in mode_names.items():
        if isinstance(names, str) or not isinstance(names, Sequence):
            raise ValueError(f"mode_names[{body!r}] must be a list of mode names; got {names!r}")
        if known and body in known:
            number = known.index(body) + 1
        elif not known and (m := re.fullmatch(r"body_(\d+)", str(body))):
            number = int(m.group(1))
        else:
            accepted = ", ".join(known) if known else "body_1, body_2, ... (or pass body_names)"
            raise ValueError(f"mode_names names unknown body {body!r}; accepted: {accepted}")
        if cfg is not None and from_cfg.get(number, 0) != len(names):
            raise WamitFormatError(
                f"{cfg}: NEWMDS({number}) = {from_cfg.get(number, 0)}, but mode_names gives body {body!r} "
                f"{len(names)} modes {list(names)}"
            )
        counts[number] = len(names)
    return {k: n for k, n in counts.items() if n}, cfg


def _mode_layout(out: OutFile) -> tuple[np.ndarray, np.ndarray]:
    """Per WAMIT mode (0-based): its body (0-based) and its index within the body (0-5 rigid, 6.. generalised)."""
    sizes = np.array([6 + m for m in out.generalised_modes] if out.generalised_modes else [6] * len(out.bodies))
    body_of = np.repeat(np.arange(sizes.size), sizes)
    return body_of, np.arange(body_of.size) - out.mode_start[body_of]


def _mode_names(out: OutFile, names: list[str], given: Mapping[str, Sequence[str]] | None) -> list[list[str]]:
    """Names of each body's generalised modes: the given ones, else ``mode7``, ``mode8``, ..."""
    given = dict(given or {})
    out_names = []
    for k, body in enumerate(names):
        count = out.generalised_modes[k] if out.generalised_modes else 0
        modes = [str(m) for m in given.get(body, [f"mode{7 + j}" for j in range(count)])]
        if len(set(modes)) != len(modes):
            raise ValueError(f"mode_names[{body!r}] repeats a name: {modes}")
        for mode in modes:
            dof_name(body, mode)  # raises ValueError for a name that cannot name a generalised mode
        out_names.append(modes)
    return out_names


# --- merging the numeric files ---------------------------------------------------------------------


def _match_periods(path: Path, per: np.ndarray, lines: np.ndarray, periods: np.ndarray) -> np.ndarray:
    """Index into ``periods`` of each value of ``per`` (raises naming the first unmatched line)."""
    values, inverse = np.unique(per, return_inverse=True)
    nearest = np.argmin(np.abs(values[:, None] - periods[None, :]), axis=1)
    ok = np.abs(periods[nearest] - values) <= _PERIOD_RTOL * values
    if not np.all(ok):
        bad = values[~ok][0]
        k = int(lines[np.flatnonzero(per == bad)[0]])
        raise WamitFormatError(
            f"{path}, line {k + 1}: period {bad:g} s is not among the {periods.size} periods of the .out file "
            "(pass numeric_files=False to read the .out file alone)"
        )
    return nearest[inverse]


def _merge_radiation(
    path: Path,
    out: OutFile,
    added_mass: np.ndarray,
    damping: np.ndarray,
    a_zero: np.ndarray | None,
    a_inf: np.ndarray,
) -> tuple[np.ndarray | None, np.ndarray]:
    """Overwrite the ``.out`` radiation coefficients with those of the ``.1`` file (in place)."""
    n = out.n_modes
    tables = read_numeric(path, (4, 5), "PER I J A(I,J) [B(I,J)]")
    rows, lines = tables[5]
    if rows.size:
        ii, jj = _indices(path, rows[:, 1:3], lines, n)
        k = _match_periods(path, rows[:, 0], lines, out.periods)
        added_mass[k, ii, jj] = rows[:, 3]
        damping[k, ii, jj] = rows[:, 4]
        if len(set(k.tolist())) != out.periods.size:
            raise WamitFormatError(
                f"{path}: holds {len(set(k.tolist()))} of the {out.periods.size} periods of the .out file "
                "(pass numeric_files=False to read the .out file alone)"
            )
    special, slines = tables[4]
    # WAMIT: PER = -1 is the infinite period (omega = 0), PER = 0 the zero period (omega = infinity).
    result: dict[float, np.ndarray] = {}
    for per, base in ((-1.0, a_zero), (0.0, a_inf)):
        at = special[:, 0] == per
        if np.any(at):
            matrix = np.zeros((n, n)) if base is None else base.copy()
            si, sj = _indices(path, special[at, 1:3], slines[at], n)
            matrix[si, sj] = special[at, 3]
            result[per] = matrix
    other = ~np.isin(special[:, 0], (-1.0, 0.0))
    if np.any(other):
        bad_line = int(slines[np.argmax(other)])
        raise WamitFormatError(
            f"{path}, line {bad_line + 1}: rows without damping must have PER = -1 (infinite period) or 0 (zero period)"
        )
    return result.get(-1.0, a_zero), result.get(0.0, a_inf)


def _merge_excitation(path: Path, out: OutFile, exc: np.ndarray) -> np.ndarray:
    """Overwrite the ``.out`` excitation with the ``.3`` (or ``.2``) values (in place); return headings [rad]."""
    n = out.n_modes
    rows, lines = read_numeric(path, (7,), "PER BETA I Mod Pha Re Im")[7]
    (ii,) = _indices(path, rows[:, 2:3], lines, n)
    k = _match_periods(path, rows[:, 0], lines, out.periods)
    betas, inverse = np.unique(rows[:, 1], return_inverse=True)
    nearest = np.argmin(np.abs(betas[:, None] - out.headings_deg[None, :]), axis=1)
    ok = np.abs(out.headings_deg[nearest] - betas) <= _HEADING_ATOL_DEG
    if not np.all(ok) or len(set(nearest.tolist())) != out.headings_deg.size:
        raise WamitFormatError(
            f"{path}: headings {betas.tolist()} deg do not match those of the .out file {out.headings_deg.tolist()} "
            "(pass numeric_files=False to read the .out file alone)"
        )
    exc[k, nearest[inverse], ii] = rows[:, 5] + 1j * rows[:, 6]
    headings = np.deg2rad(out.headings_deg.copy())
    headings[nearest] = np.deg2rad(betas)
    return headings


def _merge_hydrostatics(path: Path, out: OutFile, restoring: np.ndarray) -> None:
    """Overwrite the ``.out`` restoring coefficients with the ``.hst`` values (in place)."""
    rows, lines = read_numeric(path, (3,), "I J C(I,J)")[3]
    ii, jj = _indices(path, rows[:, :2], lines, restoring.shape[0])
    restoring[ii, jj] = rows[:, 2]


def _indices(path: Path, columns: np.ndarray, lines: np.ndarray, n: int) -> tuple[np.ndarray, ...]:
    idx = np.rint(columns).astype(int)
    bad = np.any((idx < 1) | (idx > n), axis=1)
    if np.any(bad):
        k = int(np.argmax(bad))
        raise WamitFormatError(
            f"{path}, line {int(lines[k]) + 1}: mode index outside 1..{n} (6 per body plus its generalised modes); "
            "generalised modes (NEWMDS) need their number per body: keep the run's .cfg beside the .out or pass "
            "mode_names"
        )
    return tuple(idx[:, c] - 1 for c in range(idx.shape[1]))


# --- hydrostatics and inertia ------------------------------------------------------------------------


def _restoring_from_out(out: OutFile) -> np.ndarray:
    """WAMIT's non-dimensional C (N x N, block diagonal by body) from the ``.out`` body parameters.

    C(i, j) with i, j in {3, 4, 5} is symmetric; C(4,6) and C(5,6) are not (C(6,4) = C(6,5) = 0), as in ``.hst``.
    Indices i, j are within the body (7.. its generalised modes, when the header prints them).
    """
    n = out.n_modes
    c = np.zeros((n, n))
    for k, body in enumerate(out.bodies):
        if not body.restoring:
            raise WamitFormatError(f"{out.path}: body {body.number} has no restoring coefficients in the header")
        o = int(out.mode_start[k])
        size = 6 + (out.generalised_modes[k] if out.generalised_modes else 0)
        for (i, j), value in body.restoring.items():
            if max(i, j) > size:
                raise WamitFormatError(
                    f"{out.path}, line {body.line + 1}: body {body.number}'s C({i},{j}) is beyond its {size} modes"
                )
            c[o + i - 1, o + j - 1] = value
            if i in (3, 4, 5) and j in (3, 4, 5):
                c[o + j - 1, o + i - 1] = value
    return c


def _center_of_gravity(cog: np.ndarray | None) -> np.ndarray:
    return np.zeros(3) if cog is None else np.asarray(cog, dtype=float)


def _remove_gravity_terms(stiffness: np.ndarray, out: OutFile, masses: np.ndarray, cogs: np.ndarray, g: float) -> bool:
    """Remove WAMIT's weight terms from the dimensional C (in place); return whether any were nonzero."""
    removed = False
    for k, body in enumerate(out.bodies):
        if not body.restoring_includes_gravity or body.center_of_gravity is None:
            continue
        xg, yg, zg = cogs[k]
        weight = masses[k] * g
        o = int(out.mode_start[k])
        stiffness[o + 3, o + 3] += weight * zg
        stiffness[o + 4, o + 4] += weight * zg
        stiffness[o + 3, o + 5] -= weight * xg
        stiffness[o + 4, o + 5] -= weight * yg
        removed = removed or bool(np.any(np.array([xg, yg, zg]) != 0))
    return removed


def _inertia(
    out: OutFile, masses: np.ndarray, cogs: np.ndarray, rho: float, mass_matrices: list[np.ndarray] | None
) -> tuple[np.ndarray, list[int]]:
    """Inertia tensors about the centres of mass [kg m^2] and the indices of bodies whose inertia is unknown."""
    n = len(out.bodies)
    inertia = np.zeros((n, 3, 3))
    unknown = []
    for k, body in enumerate(out.bodies):
        about_origin = None
        if mass_matrices is not None and np.any(mass_matrices[k][3:, 3:] != 0):
            about_origin = rho * mass_matrices[k][3:, 3:]
        elif body.radii_of_gyration is not None and np.any(body.radii_of_gyration != 0):
            r = body.radii_of_gyration
            about_origin = masses[k] * r * np.abs(r)
        if about_origin is None:
            unknown.append(k)
            continue
        c = np.array([0.0, 0.0, cogs[k][2]])  # centre of mass relative to XBODY, as in center_of_mass
        inertia[k] = about_origin - masses[k] * (np.dot(c, c) * np.eye(3) - np.outer(c, c))
    return inertia, unknown
