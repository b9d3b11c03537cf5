"""How a result lays out a device's columns: the kind of each generalised velocity and hydrodynamic DOF (a
translation, a rotation or a generalised mode: ``wecss.constants.DOF_KINDS``), the order in which the runs store the
forces on the hydrodynamic DOFs, and the PTOs' kinds."""

from __future__ import annotations

import numpy as np

from ..compiled import CompiledScene
from ..constants import DOF_KINDS
from ..hydro import dof_kinds, split_dof


def velocity_kinds(compiled: CompiledScene) -> np.ndarray:
    """The kind of each generalised velocity (n_v,): "linear", "angular" or "generalised"."""
    return np.array(compiled.device.model.velocity_kinds)


def hydro_kinds(compiled: CompiledScene) -> np.ndarray:
    """The kind of each hydrodynamic DOF in the database's order (n_h,): "linear", "angular" or "generalised"."""
    return np.array(dof_kinds(compiled.hydro.dofs))


def natural_hydro_order(compiled: CompiledScene) -> np.ndarray:
    """Indices that put the hydro DOFs in the device spec's body order (the database may list its bodies
    otherwise), each body's DOFs in the database's order."""
    bodies = [b.hydro_body for b in compiled.device.model.bodies if b.hydro_body is not None]
    dofs = list(compiled.hydro.dofs)
    rank = {body: k for k, body in enumerate(bodies)}
    return np.array(
        sorted(range(len(dofs)), key=lambda i: (rank.get(split_dof(dofs[i])[0], len(rank)), i)), dtype=np.int64
    )


def grouped_hydro_order(compiled: CompiledScene) -> np.ndarray:
    """The hydro DOFs grouped by kind (translations, rotations, generalised modes; each in the device spec's body
    order, :func:`natural_hydro_order`): the column order in which the fixed-step runs store forces on them, so
    that each kind is one block of columns (a view, no copy, in the result)."""
    natural = natural_hydro_order(compiled)
    kinds = hydro_kinds(compiled)[natural]
    return np.concatenate([natural[kinds == kind] for kind in DOF_KINDS]).astype(np.int64)


def rotary_ptos(compiled: CompiledScene) -> np.ndarray:
    """Mask of the rotary PTOs (on revolute joints) in the device spec's order."""
    return np.array([kind == "rotary" for kind in compiled.pto_kinds], dtype=bool)


def columns(mask: np.ndarray) -> slice | np.ndarray:
    """The columns ``mask`` selects: a slice where they are consecutive (the variable is then a view of the
    record, no copy: a run of 10^6 saved steps holds its time series once), else their indices."""
    index = np.flatnonzero(mask)
    if index.size and index[-1] - index[0] + 1 == index.size:
        return slice(int(index[0]), int(index[-1]) + 1)
    return index
