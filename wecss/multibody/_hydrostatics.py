"""A hydrodynamic database mapped onto the Cartesian coordinates of a multibody model (6 per body, plus its modes).

The coefficients are moved to each model body's centre of mass first (DESIGN.md), so the model's own mass
distribution decides the reference, whatever the database assumed. Hydrostatics follow DESIGN.md: gravity at
each centre of mass, the equilibrium buoyancy rho g V as a constant upward force at the centre of mass, and the
linear hydrostatic stiffness (about the centre of mass) on the displacement from the database's reference pose.
A linear mooring (``_mooring``) acts on the same displacement and on the hydro DOFs' velocities.

A hydro DOF ``<hydro_body>__<mode>`` is a generalised mode: it maps to the row of the model body's mode of that
name (``Body.modes``), its displacement is the modal coordinate, and its coefficients are left as they are by the
move to the centre of mass. A database mode that the body does not declare is refused (drop it with
``HydroData.select``); a declared mode without data has no hydrodynamics.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..hydro import HydroData, dof_index, is_rigid_dof, split_dof
from ._kinematics import KinematicState
from ._mooring import Mooring, mooring_matrices
from ._se3 import so3_log
from ._tree import Multibody


@dataclass(frozen=True, eq=False)
class HydroCoupling:
    """Hydrodynamic data of a model in its Cartesian coordinates.

    Attributes
    ----------
    hydro : HydroData
        The database restricted to the model's bodies, about the model bodies' centres of mass.
    index : ndarray of int
        Cartesian row (``Multibody.cart_start`` of its body plus its axis) of each hydro DOF, in the database's
        DOF order.
    added_mass_inf, stiffness : ndarray (n_cart, n_cart)
        A_inf [kg, kg m, kg m^2] and the hydrostatic stiffness in Cartesian coordinates (zeros where no data).
    buoyancy : ndarray (n_cart,)
        Constant equilibrium buoyancy rho g V (world z) at each hydro body's centre of mass [N].
    mooring_stiffness, mooring_damping : ndarray (n_cart, n_cart)
        The moorings' springs [N/m, N m/rad] and dampers [N s/m, N m s/rad] (zeros without a mooring); they act
        only on hydro DOFs.
    moorings : tuple of Mooring
    """

    hydro: HydroData
    index: np.ndarray
    added_mass_inf: np.ndarray
    stiffness: np.ndarray
    buoyancy: np.ndarray
    mooring_stiffness: np.ndarray
    mooring_damping: np.ndarray
    moorings: tuple[Mooring, ...] = ()

    @property
    def restoring(self) -> np.ndarray:
        """Hydrostatic plus mooring stiffness (n_cart, n_cart) on the displacement from the reference pose [SI]."""
        return self.stiffness + self.mooring_stiffness

    @classmethod
    def from_hydro(cls, model: Multibody, hydro: HydroData, moorings: tuple[Mooring, ...] = ()) -> HydroCoupling:
        """Map ``hydro`` onto ``model`` through each body's ``hydro_body``, with ``moorings`` on its bodies.

        Raises
        ------
        ValueError
            If a body names a hydro body that is not in the database, or two bodies name the same one; if the
            database has a generalised mode the body does not declare; if a mooring holds a DOF the database has
            no data for (it acts on the hydro DOFs only).
        """
        pairs = [(i, b.hydro_body) for i, b in enumerate(model.bodies) if b.hydro_body is not None]
        names = [h for _, h in pairs]
        if len(set(names)) != len(names):
            raise ValueError(f"two model bodies map to the same hydro body: {names}")
        unknown = [h for h in names if h not in hydro.bodies]
        if unknown:
            raise ValueError(f"hydro bodies {unknown} are not in the database; it has {', '.join(hydro.bodies)}")
        if not pairs:
            raise ValueError("no model body names a hydro body (Body.hydro_body)")
        sub = hydro.select(bodies=names)
        moved = sub.with_reference_points({h: model.bodies[i].center_of_mass for i, h in pairs})
        of_hydro = {h: i for i, h in pairs}
        index = np.array([_cartesian_row(model, of_hydro[split_dof(d)[0]], d) for d in moved.dofs], dtype=np.int64)
        n_cart = model.n_cart
        ds = moved.dataset
        added = np.zeros((n_cart, n_cart))
        added[np.ix_(index, index)] = ds.added_mass_inf.values
        stiffness = np.zeros((n_cart, n_cart))
        stiffness[np.ix_(index, index)] = ds.hydrostatic_stiffness.values
        buoyancy = np.zeros(n_cart)
        for h, i in of_hydro.items():
            buoyancy[model.cart_start[i] + 2] = moved.rho * moved.g * float(ds.displaced_volume.sel(body=h))
        mooring_k, mooring_c = mooring_matrices(model, tuple(moorings))
        held = np.flatnonzero(np.diag(mooring_k) + np.diag(mooring_c))
        outside = [k for k in held if k not in set(index.tolist())]
        if outside:
            names = [model.cartesian_labels[k].replace("__", " ") for k in outside]
            raise ValueError(
                f"mooring on {', '.join(names)}: the hydrodynamic database has no such DOF (a mooring acts on the "
                f"database's DOFs: {', '.join(moved.dofs)})"
            )
        return cls(moved, index, 0.5 * (added + added.T), stiffness, buoyancy, mooring_k, mooring_c, tuple(moorings))

    def expand(self, matrix: np.ndarray) -> np.ndarray:
        """A (..., ndof, ndof) matrix over the hydro DOFs as (..., n_cart, n_cart) Cartesian (zeros elsewhere)."""
        n6 = self.buoyancy.size
        out = np.zeros((*matrix.shape[:-2], n6, n6), dtype=matrix.dtype)
        out[..., self.index[:, None], self.index[None, :]] = matrix
        return out

    def displacement(self, model: Multibody, state: KinematicState) -> np.ndarray:
        """Cartesian displacement from the reference pose: CoM translation and rotation vector (world) [m, rad],
        and the modal coordinates [1]."""
        out = np.zeros(model.n_cart)
        for i, body in enumerate(model.bodies):
            s = model.cart_start[i]
            out[s : s + 3] = state.position[i] - body.center_of_mass
            out[s + 3 : s + 6] = so3_log(state.rotation[i])
        out[model.mode_rows] = state.modal
        return out

    def hydrostatic_force(self, model: Multibody, state: KinematicState) -> np.ndarray:
        """Buoyancy plus linear hydrostatic and mooring restoring force (world forces, body-frame moments)
        [N, N m]."""
        world = self.buoyancy - self.restoring @ self.displacement(model, state)
        return to_body_moments(world, state)


def to_body_moments(world: np.ndarray, state: KinematicState) -> np.ndarray:
    """Convert the moments of a Cartesian load vector from world axes to body axes (forces and the modes'
    generalised forces stay as they are)."""
    out = world.copy()
    for i, s in enumerate(state.cart_start):
        out[s + 3 : s + 6] = state.rotation[i].T @ world[s + 3 : s + 6]
    return out


def _cartesian_row(model: Multibody, body: int, dof: str) -> int:
    """The model's Cartesian row of the hydro DOF ``dof`` acting on model body ``body``.

    Raises
    ------
    ValueError
        If ``dof`` is a generalised mode the body does not declare.
    """
    start = model.cart_start[body]
    part = split_dof(dof)[1]
    if is_rigid_dof(part):
        return start + dof_index(part)
    declared = model.bodies[body].modes.names
    if part not in declared:
        name = model.bodies[body].name
        raise ValueError(
            f"the hydrodynamic database has the generalised mode {dof!r}, which body {name!r} (hydro body "
            f"{split_dof(dof)[0]!r}) does not declare (its modes: {', '.join(declared) or 'none'}); declare it in "
            f"the body's modes (device spec: modes = [{{name = {part!r}, mass = ...}}]) or drop it from the database "
            "(HydroData.select(dofs=[...]))"
        )
    return start + 6 + declared.index(part)
