"""Rigid-body transformation of hydrodynamic coefficients to another reference point.

For a body whose coefficients are given about point O, motions and forces about point P follow from
r = P - O:

    xi_P = T xi_O,   T = [[I, -hat(r)], [0, I]]        (small displacement and rotation)
    f_P = T^-T f_O,  T^-T = [[I, 0], [-hat(r), I]]    (moment about P = moment about O + (O - P) x F)

so that matrices move by congruence, A_P = T^-T A_O T^-1, and forces by f_P = T^-T f_O.
The hydrostatic stiffness is the exception: the static buoyancy force rho g V (world-vertical,
acting at the centre of buoyancy c) adds a geometric stiffness that depends on the reference point,
K_geo(P) = (F0 . d) I - d F0^T with d = c - P (rotation-rotation block only), which congruence does not
carry over. It is removed before and added back after the congruence.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..constants import RIGID_BODY_DOFS
from ._schema import dof_index, is_rigid_dof, split_dof


def hat(r: np.ndarray) -> np.ndarray:
    """Skew-symmetric matrix of a 3-vector: ``hat(r) @ v == np.cross(r, v)``."""
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


def force_transform(offset: np.ndarray) -> np.ndarray:
    """6x6 matrix T^-T mapping a force/moment about O to the same load about P = O + offset."""
    out = np.eye(6)
    out[3:, :3] = -hat(np.asarray(offset, dtype=float))
    return out


def buoyancy_geometric_stiffness(force: np.ndarray, arm: np.ndarray) -> np.ndarray:
    """3x3 rotational stiffness of a constant world-frame force acting at a body point.

    Parameters
    ----------
    force : array of shape (3,)
        The constant force F0 [N].
    arm : array of shape (3,)
        d = (point of action) - (reference point) [m].

    Returns
    -------
    ndarray of shape (3, 3)
        K with dM = -K dtheta for small rotations dtheta [N m/rad].
    """
    force = np.asarray(force, dtype=float)
    arm = np.asarray(arm, dtype=float)
    return float(force @ arm) * np.eye(3) - np.outer(arm, force)


def _dof_transform(ds: xr.Dataset, new_points: np.ndarray) -> np.ndarray:
    """Block matrix T^-T over all DOFs of ``ds`` for moving every body to ``new_points`` (body, axis)."""
    dofs = [str(d) for d in ds.influenced_dof.values]
    bodies = [str(b) for b in ds.body.values]
    old_points = ds.reference_point.values
    n = len(dofs)
    out = np.zeros((n, n))
    by_body: dict[str, list[tuple[int, int]]] = {}
    for k, name in enumerate(dofs):
        body, dof = split_dof(name)
        if is_rigid_dof(dof):
            by_body.setdefault(body, []).append((k, dof_index(dof)))
        else:  # a generalised mode: the identity
            out[k, k] = 1.0
    for body, entries in by_body.items():
        b = bodies.index(body)
        full = force_transform(new_points[b] - old_points[b])
        rows = [k for k, _ in entries]
        local = [j for _, j in entries]
        missing = [j for j in range(6) if j not in local]
        leak = full[np.ix_(local, missing)]
        if np.any(np.abs(leak) > 0):
            need = sorted({RIGID_BODY_DOFS[missing[c]] for c in np.nonzero(np.abs(leak) > 0)[1]})
            raise ValueError(
                f"cannot move body {body!r} by {new_points[b] - old_points[b]} m: its DOFs "
                f"{[RIGID_BODY_DOFS[j] for j in local]} would need the missing DOFs {need}"
            )
        out[np.ix_(rows, rows)] = full[np.ix_(local, local)]
    return out


def _geometric_stiffness(ds: xr.Dataset, points: np.ndarray) -> np.ndarray:
    """Geometric stiffness of each body's static buoyancy about ``points``, over all DOFs of ``ds``."""
    dofs = [str(d) for d in ds.influenced_dof.values]
    bodies = [str(b) for b in ds.body.values]
    rho, g = float(ds.attrs["rho"]), float(ds.attrs["g"])
    out = np.zeros((len(dofs), len(dofs)))
    index = {
        name: (bodies.index(split_dof(name)[0]), dof_index(split_dof(name)[1]) if is_rigid_dof(name) else -1)
        for name in dofs
    }
    for b, _ in enumerate(bodies):
        force = np.array([0.0, 0.0, rho * g * float(ds.displaced_volume.values[b])])
        k_rot = buoyancy_geometric_stiffness(force, ds.center_of_buoyancy.values[b] - points[b])
        rot = [(k, j - 3) for k, (bb, j) in enumerate(index.values()) if bb == b and j >= 3]
        for k1, j1 in rot:
            for k2, j2 in rot:
                out[k1, k2] = k_rot[j1, j2]
    return out


def move_reference_point(ds: xr.Dataset, new_points: Mapping[str, object] | xr.DataArray) -> xr.Dataset:
    """Return ``ds`` with every body's coefficients moved to a new reference point.

    Parameters
    ----------
    ds : xarray.Dataset
        A wecss hydrodynamic database.
    new_points : mapping body -> (x, y, z) [m], or DataArray with dims (body, axis)
        The new reference point of each body; bodies left out keep theirs.

    Returns
    -------
    xarray.Dataset
        Added mass (all frequencies, zero and infinity), damping, excitation (and its Froude-Krylov and
        diffraction parts) and hydrostatic stiffness about the new points; ``reference_point`` updated.

    Raises
    ------
    ValueError
        If a body is unknown or a body's DOF subset is not closed under the move (for example heave
        alone moved sideways, which would need roll).
    """
    bodies = [str(b) for b in ds.body.values]
    points = np.array(ds.reference_point.values, dtype=float)
    if isinstance(new_points, xr.DataArray):
        new_points = {str(b): new_points.sel(body=b).values for b in new_points.body.values}
    for body, point in new_points.items():
        if body not in bodies:
            raise ValueError(f"unknown body {body!r}; bodies: {', '.join(bodies)}")
        p = np.asarray(point, dtype=float)
        if p.shape != (3,):
            raise ValueError(f"reference point of body {body!r} must have 3 coordinates [m]; got shape {p.shape}")
        points[bodies.index(body)] = p

    transform = _dof_transform(ds, points)
    out = ds.copy()
    for name in ("added_mass", "radiation_damping", "added_mass_inf", "added_mass_zero"):
        if name in ds:
            da = ds[name]
            out[name] = da.copy(data=transform @ da.values @ transform.T)
    for name in ("excitation", "froude_krylov", "diffraction"):
        if name in ds:
            da = ds[name]
            out[name] = da.copy(data=np.einsum("ij,...j->...i", transform, da.values))
    old_geo = _geometric_stiffness(ds, ds.reference_point.values)
    new_geo = _geometric_stiffness(ds, points)
    stiff = ds.hydrostatic_stiffness.values
    out["hydrostatic_stiffness"] = ds.hydrostatic_stiffness.copy(
        data=transform @ (stiff - old_geo) @ transform.T + new_geo
    )
    out["reference_point"] = ds.reference_point.copy(data=points)
    return out


def move_to_center_of_mass(ds: xr.Dataset) -> xr.Dataset:
    """Return ``ds`` with every body's coefficients about its centre of mass (DESIGN.md convention)."""
    return move_reference_point(ds, ds.center_of_mass)
