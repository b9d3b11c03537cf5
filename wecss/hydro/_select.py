"""Selection of bodies and DOFs from a hydrodynamic database, keeping every cross-body coupling."""

from __future__ import annotations

from collections.abc import Iterable

import xarray as xr

from ..constants import RIGID_BODY_DOFS
from ._schema import split_dof


def select(ds: xr.Dataset, *, bodies: Iterable[str] | None = None, dofs: Iterable[str] | None = None) -> xr.Dataset:
    """Keep only some bodies and DOFs.

    Parameters
    ----------
    ds : xarray.Dataset
        A wecss hydrodynamic database.
    bodies : iterable of str, optional
        Bodies to keep (default: all).
    dofs : iterable of str, optional
        DOFs to keep, either DOF parts applied to every kept body (``["Surge", "Heave", "Pitch"]``, or a
        generalised mode's name such as ``"flex1"``) or full names (``["bow__Heave"]``). Default: all.

    Returns
    -------
    xarray.Dataset
        The sub-database; couplings between every kept pair of DOFs (within and across bodies) are kept.

    Raises
    ------
    ValueError
        If a body or DOF is unknown, or nothing is left.
    """
    all_bodies = [str(b) for b in ds.body.values]
    all_dofs = [str(d) for d in ds.radiating_dof.values]
    keep_bodies = all_bodies if bodies is None else [str(b) for b in bodies]
    unknown = [b for b in keep_bodies if b not in all_bodies]
    if unknown:
        raise ValueError(f"unknown bodies {unknown}; bodies in the database: {all_bodies}")
    kept = [d for d in all_dofs if split_dof(d)[0] in keep_bodies]
    if dofs is not None:
        wanted = [str(d) for d in dofs]
        short = [d for d in wanted if "__" not in d]
        full = [d for d in wanted if "__" in d]
        modes = sorted({split_dof(d)[1] for d in all_dofs} - set(RIGID_BODY_DOFS))
        bad_short = [d for d in short if d not in RIGID_BODY_DOFS and d not in modes]
        bad_full = [d for d in full if d not in all_dofs]
        if bad_short or bad_full:
            named = f", the generalised modes {', '.join(modes)}" if modes else ""
            raise ValueError(
                f"unknown DOFs {bad_short + bad_full}; accepted: {', '.join(RIGID_BODY_DOFS)}{named} or full names "
                f"such as {all_dofs[0]!r} (the database has {', '.join(all_dofs)})"
            )
        kept = [d for d in kept if d in full or split_dof(d)[1] in short]
    if not kept:
        raise ValueError(f"the selection bodies={keep_bodies}, dofs={dofs} leaves no DOF")
    out = ds.sel(body=keep_bodies, radiating_dof=kept, influenced_dof=kept)
    return out
