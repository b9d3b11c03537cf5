"""Run Capytaine on a :class:`BEMSpec` and return a wecss hydrodynamic dataset.

All floats are solved together (every body-to-body interaction), each with a lid against irregular
frequencies, at the requested frequencies plus omega = inf (and omega = 0 in deep water), in one call to
``BEMSolver.solve_all``. Hydrostatics are computed on plain copies of the hulls (Capytaine 3.0 cannot on
a ``RotationSymmetricMesh``). Rotations are about each body's centre of mass, so the coefficients are
about the centres of mass as the MFM needs.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
import xarray as xr

from ... import __version__ as wecss_version
from .._validate import relative_asymmetry
from ..readers.capytaine import read_capytaine
from ._lazy import import_capytaine
from ._mesh import hull_mesh, lid_mesh
from ._progress import Progress, print_flush
from ._spec import BEMSpec, FloatBody

_SYMMETRIC = ("added_mass", "radiation_damping", "added_mass_inf", "added_mass_zero")


@dataclass(frozen=True)
class _Built:
    """One float made ready for Capytaine."""

    body: FloatBody
    bem: Any  # capytaine.FloatingBody with hull and lid, for the BEM
    plain: Any  # capytaine.FloatingBody on an area-preserving plain hull, for hydrostatics
    mass: float
    bem_mesh_volume: float
    hull_panels: int
    lid_panels: int


def run_bem(
    spec: BEMSpec,
    *,
    n_jobs: int = 1,
    progress: bool | Callable[[str], None] = True,
    attrs: dict[str, object] | None = None,
) -> xr.Dataset:
    """Solve radiation and diffraction for the floats of ``spec`` with Capytaine.

    Parameters
    ----------
    spec : BEMSpec
        Bodies, frequencies, water and mesh settings.
    n_jobs : int
        Processes for Capytaine (joblib). With 1, Capytaine's Green function and linear solver still use
        all cores through OpenMP/BLAS threads.
    progress : bool or callable
        Report progress: ``True`` prints lines to standard output, a callable receives them, ``False``
        is silent. With ``n_jobs > 1`` Capytaine's own progress bar is shown instead.
    attrs : dict, optional
        Further attributes for the result (netCDF-compatible values).

    Returns
    -------
    xarray.Dataset
        wecss schema, coefficients about each body's centre of mass; added mass and damping symmetrised
        (the ``repairs`` attribute gives the largest asymmetry found). Attributes also record the mesh panel
        counts (``mesh_hull_panels``, ``mesh_lid_panels`` and per body), the largest relative difference
        between a BEM mesh's volume (vertices on the true surface, so a little less) and the float's
        (``mesh_volume_relative_error_max``), the Capytaine version, the run time ``bem_run_time_s`` and the
        specification ``bem_spec`` (JSON).

    Raises
    ------
    ImportError
        If Capytaine is not installed (``pip install "wecss[bem]"``).
    ValueError
        If ``n_jobs`` is not a positive integer.
    RuntimeError
        If Capytaine fails on some problems (the message lists them).
    """
    if not isinstance(n_jobs, int) or n_jobs < 1:
        raise ValueError(f"n_jobs must be a positive integer; got {n_jobs!r}")
    cpt = import_capytaine()
    report = _reporter(progress)
    start = time.perf_counter()

    built = [_bodies(cpt, body, spec, single=len(spec.bodies) == 1) for body in spec.bodies]
    if len(built) == 1:  # a one-body Multibody fails on symmetric meshes in Capytaine 3.0
        bem, plain = built[0].bem, built[0].plain
        capy_dofs = list(spec.bodies[0].dofs)
    else:
        bem = cpt.Multibody([b.bem for b in built], name=spec.name)
        plain = cpt.Multibody([b.plain for b in built], name=spec.name)
        capy_dofs = [f"{b.name}__{d}" for b in spec.bodies for d in b.dofs]
    hull_panels = [b.hull_panels for b in built]
    lid_panels = [b.lid_panels for b in built]
    if report is not None:
        report(
            f"{spec.name}: {len(spec.bodies)} bodies, {sum(hull_panels)} hull + {sum(lid_panels)} lid panels, "
            f"{len(spec.omega)} frequencies {spec.omega[0]:.4g}-{spec.omega[-1]:.4g} rad/s + "
            f"{'0 and ' if spec.zero_frequency else ''}inf, Capytaine {cpt.__version__}"
        )

    problems = _problems(cpt, bem, spec)
    n_freq = len(spec.omega) + 1 + int(spec.zero_frequency)
    tracker = Progress(spec.name, len(problems), n_freq, report) if report is not None and n_jobs == 1 else None
    solver = _solver(cpt, tracker, spec.method)
    results = solver.solve_all(
        problems, n_jobs=n_jobs, keep_details=False, progress_bar=report is not None and n_jobs > 1
    )
    failed = [r for r in results if getattr(r, "exception", None) is not None]
    if failed:
        lines = "; ".join(f"{r.problem}: {r.exception}" for r in failed[:5])
        raise RuntimeError(f"Capytaine failed on {len(failed)} of {len(results)} problems: {lines}")

    dataset = cpt.assemble_dataset(results, hydrostatics=False)
    hydrostatics = cpt.compute_hydrostatics_dataset(plain, rho=spec.rho, g=spec.g)
    merged = xr.merge([dataset, hydrostatics], compat="no_conflicts", join="outer")
    merged = merged.sel(influenced_dof=capy_dofs, radiating_dof=capy_dofs)
    merged.attrs = dict(dataset.attrs)
    out, repairs = _symmetrise(
        read_capytaine(
            merged,
            mass={b.body.name: b.mass for b in built},
            inertia={b.body.name: np.diag(b.body.inertia) for b in built},
        )
    )

    volume_error = [abs(b.bem_mesh_volume / b.body.profile.volume - 1) for b in built]
    out.attrs.update(
        {
            "source": f"wecss.hydro.bem: Capytaine {cpt.__version__}, {spec.name}",
            "wecss_version": wecss_version,
            "capytaine_version": str(cpt.__version__),
            "bem_name": spec.name,
            "bem_run_time_s": round(time.perf_counter() - start, 1),
            "bem_spec": json.dumps(asdict(spec), default=_jsonable),
            "mesh_panel_size_m": spec.panel_size,
            "mesh_panel_aspect_ratio": spec.panel_aspect_ratio,
            "mesh_hull_panels": int(sum(hull_panels)),
            "mesh_lid_panels": int(sum(lid_panels)),
            "mesh_hull_panels_per_body": np.array(hull_panels, dtype=np.int64),
            "mesh_lid_panels_per_body": np.array(lid_panels, dtype=np.int64),
            "mesh_volume_relative_error_max": float(max(volume_error)),
            "hydrostatics_mesh": "area-preserving copy of each hull (true waterplane area and volume)",
            "repairs": repairs,
            **dict(attrs or {}),
        }
    )
    if report is not None:
        report(f"{spec.name}: done in {out.attrs['bem_run_time_s'] / 60:.1f} min")
    return out


def _symmetrise(ds: xr.Dataset) -> tuple[xr.Dataset, str]:
    """Replace added mass and damping by (M + M^T) / 2; say how asymmetric they were.

    A panel method's matrices are symmetric only to its discretisation error (Capytaine's direct method:
    a few tenths of a per cent on the M4 floats), beyond the validation tolerance.
    """
    out = ds.copy()
    notes = []
    for name in _SYMMETRIC:
        if name not in ds:
            continue
        rel = relative_asymmetry(ds, name)
        index = np.unravel_index(np.argmax(rel), rel.shape)
        at = f" at omega = {float(ds.omega.values[index[0]]):.4g} rad/s" if rel.ndim == 3 else ""
        notes.append(
            f"symmetrised {name} (largest asymmetry {float(rel[index]):.3g} between "
            f"{ds.influenced_dof.values[index[-2]]} and {ds.radiating_dof.values[index[-1]]}{at})"
        )
        values = ds[name].values
        out[name] = ds[name].copy(data=0.5 * (values + np.swapaxes(values, -1, -2)))
    return out, "; ".join(notes)


def _reporter(progress: bool | Callable[[str], None]) -> Callable[[str], None] | None:
    if progress is True:
        return print_flush
    if progress is False or progress is None:
        return None
    if callable(progress):
        return progress
    raise ValueError(f"progress must be True, False or a callable taking a message; got {progress!r}")


def _bodies(cpt: Any, body: FloatBody, spec: BEMSpec, *, single: bool) -> _Built:
    """The Capytaine body for the BEM (hull + lid) and its plain twin for hydrostatics."""
    size, aspect = spec.panel_size, spec.panel_aspect_ratio
    hull = hull_mesh(body.profile, size, aspect_ratio=aspect, name=f"{body.name}_hull")
    lid = lid_mesh(body.profile, size, aspect_ratio=aspect, name=f"{body.name}_lid") if spec.lid else None
    shift = (body.position[0], body.position[1], 0.0)
    if single and body.position == (0.0, 0.0):  # keep the rotation symmetry: the solver exploits it
        bem_hull, bem_lid = hull, lid
    else:
        bem_hull = hull.merged().translated(shift)
        bem_lid = None if lid is None else lid.merged().translated(shift)
    # Hydrostatics on a plain (not symmetric) copy that keeps the true waterplane area and volume.
    exact_hull = hull_mesh(body.profile, size, aspect_ratio=aspect, preserve_area=True).merged().translated(shift)
    com = body.center_of_mass
    mass = body.mass if body.mass is not None else spec.rho * float(exact_hull.disp_volume)
    plain = cpt.FloatingBody(
        mesh=exact_hull,
        dofs=cpt.rigid_body_dofs(only=list(body.dofs), rotation_center=com),
        center_of_mass=com,
        mass=mass,
        name=body.name,
    )
    plain.hydrostatic_stiffness = plain.compute_hydrostatic_stiffness(rho=spec.rho, g=spec.g)
    plain.inertia_matrix = _inertia_matrix(body, mass)
    bem = cpt.FloatingBody(
        mesh=bem_hull,
        lid_mesh=bem_lid,
        dofs=cpt.rigid_body_dofs(only=list(body.dofs), rotation_center=com),
        center_of_mass=com,
        mass=mass,
        name=body.name,
    )
    return _Built(
        body=body,
        bem=bem,
        plain=plain,
        mass=mass,
        bem_mesh_volume=float(bem_hull.merged().disp_volume),
        hull_panels=int(hull.nb_faces),
        lid_panels=int(lid.nb_faces) if lid is not None else 0,
    )


def _inertia_matrix(body: FloatBody, mass: float) -> xr.DataArray:
    """6x6 rigid-body mass matrix about the centre of mass, restricted to the body's DOFs."""
    full = np.diag([mass, mass, mass, *body.inertia])
    index = ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]
    keep = [index.index(d) for d in body.dofs]
    return xr.DataArray(
        full[np.ix_(keep, keep)],
        dims=("influenced_dof", "radiating_dof"),
        coords={"influenced_dof": list(body.dofs), "radiating_dof": list(body.dofs)},
        name="inertia_matrix",
    )


def _problems(cpt: Any, body: Any, spec: BEMSpec) -> list[Any]:
    """Radiation problems at every frequency (with 0 and inf), diffraction at the finite ones."""
    common = {"water_depth": spec.water_depth, "rho": spec.rho, "g": spec.g}
    omegas = ([0.0] if spec.zero_frequency else []) + list(spec.omega) + [np.inf]
    problems = []
    for omega in omegas:
        problems += [cpt.RadiationProblem(body=body, radiating_dof=d, omega=omega, **common) for d in body.dofs]
        if 0 < omega < np.inf:
            problems += [
                cpt.DiffractionProblem(body=body, wave_direction=beta, omega=omega, **common)
                for beta in spec.wave_directions
            ]
    return problems


def _solver(cpt: Any, tracker: Progress | None, method: str) -> Any:
    """A ``BEMSolver`` that tells ``tracker`` about every solved problem."""
    if tracker is None:
        return cpt.BEMSolver(method=method)

    progress = tracker

    class _TrackedSolver(cpt.BEMSolver):
        def solve(self, problem: Any, *args: Any, **kwargs: Any) -> Any:
            result = super().solve(problem, *args, **kwargs)
            progress.step(f" (last: omega {float(problem.omega):.4g} rad/s)")
            return result

    return _TrackedSolver(method=method)


def _jsonable(value: object) -> object:
    if isinstance(value, float) and not np.isfinite(value):
        return str(value)
    if isinstance(value, np.generic):
        return value.item()
    return str(value)
