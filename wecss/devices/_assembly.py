"""The linearised device with its flexible bodies as matrices, for the modal analysis
(``wecss.devices.structural_modes``, whose docstring says what is modelled).

Coordinates z: the joints' generalised velocities (``Multibody.velocity_names``), then per flexible body its elastic
coordinates, in the floating frame held at its clamp: every nodal DOF of its frame but the clamp's (``"full"``), or
its reduced basis (``"reduced"``). ``frames`` gives every body frame's world velocity (centre of mass, rotation) per
coordinate: the tree's B-matrix (rotations turned into world axes) plus, for every body below a flexible body's
joint point, the elastic motion of that point carrying it (linearised). A flexible body's nodal DOFs (body axes) are
its frame's rigid motion plus its elastic basis (``FlexibleCoordinates.nodal``).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..hydro import HydroData
from ..multibody import ActuatorPTO, HydroCoupling, JointPTO, KinematicState, Multibody, StaticModel, hat, kinematics
from ..structure import Frame, natural_modes

MODELS = ("full", "reduced")
"""Elastic coordinates: every nodal DOF of a flexible body, or its reduced basis."""


@dataclass
class FlexibleCoordinates:
    """One flexible body in the assembly: its frame, elastic basis (n_dof, n), structural damping (n, n), the
    columns of its coordinates, its rotation and centre of mass at the configuration and its reference centre."""

    name: str
    frame: Frame
    basis: np.ndarray
    damping: np.ndarray
    columns: slice
    rotation: np.ndarray
    position: np.ndarray
    reference: np.ndarray
    nodal: np.ndarray | None = None  # N (n_dof, n_z): nodal DOFs (body axes) per coordinate


def _elastic_basis(device: Any, name: str, model_kind: str) -> tuple[Frame, np.ndarray, np.ndarray]:
    """Frame, basis and structural damping of a flexible body: every DOF but the clamp's, or the reduced basis."""
    zeta = device.flexible[name].damping_ratio
    if model_kind == "reduced":
        body = device.flexible_body(name)
        return body.frame, body.basis.basis, body.basis.damping
    frame = device.structure(name)
    clamp = frame.node_dofs(frame.point("clamp")[0])
    free = np.setdiff1d(np.arange(frame.n_dof), clamp)
    basis = np.eye(frame.n_dof)[:, free]
    omega, shapes = natural_modes(frame.stiffness, frame.mass, fixed=clamp)
    mode_forces = frame.mass @ shapes
    damping = basis.T @ (mode_forces * (2 * zeta * omega)) @ mode_forces.T @ basis
    return frame, basis, damping


def _subtrees(model: Multibody) -> dict[int, list[int]]:
    """Each body's subtree (itself and its descendants)."""
    children: dict[int, list[int]] = {i: [] for i in range(len(model.bodies))}
    for i, p in enumerate(model.parent):
        if p >= 0:
            children[p].append(i)
    out = {}
    for i in range(len(model.bodies)):
        stack, found = [i], []
        while stack:
            k = stack.pop()
            found.append(k)
            stack.extend(children[k])
        out[i] = found
    return out


def _hydro_matrices(coupling: HydroCoupling) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """omega (n_w,), A(omega) (n_w, n_h, n_h), B(omega) and A_inf (n_h, n_h) of the database on its DOFs."""
    ds = coupling.hydro.dataset
    dofs = list(coupling.hydro.dofs)
    sel = {"influenced_dof": dofs, "radiating_dof": dofs}
    omega = ds.omega.values
    added = ds.added_mass.sel(sel).transpose("omega", "influenced_dof", "radiating_dof").values
    damping = ds.radiation_damping.sel(sel).transpose("omega", "influenced_dof", "radiating_dof").values
    return omega, added, damping, ds.added_mass_inf.sel(sel).values


def _at(omega: float, grid: np.ndarray, values: np.ndarray, above: np.ndarray) -> np.ndarray:
    """Linear interpolation of ``values`` (n_w, n, n) at omega: the first value below the grid, ``above`` beyond."""
    if omega > grid[-1]:
        return above
    if omega <= grid[0]:
        return values[0]
    k = int(np.searchsorted(grid, omega)) - 1
    t = (omega - grid[k]) / (grid[k + 1] - grid[k])
    return (1 - t) * values[k] + t * values[k + 1]


Transmission = tuple[JointPTO | ActuatorPTO, np.ndarray, str, np.ndarray]
"""A PTO, its transmission (n_z,) (stroke rate per coordinate rate), its kind ("line" for an actuator, else its
joint's) and its direction (the actuator's line or the joint's axis, world)."""


@dataclass(eq=False)
class DeviceSystem:
    """The device linearised (see the module docstring): ``q`` the configuration, ``state`` its kinematics, ``nv``
    rigid and ``nz`` coordinates in all, ``flexible`` by body index, ``frames`` (n_body, 6, n_z), the PTOs'
    ``transmissions``, the ``stiffness``, dry ``mass`` and ``damping`` (n_z, n_z) without the radiation, the
    hydrostatic and mooring ``restoring`` (n_cart, n_cart) in world rows, the ``coupling`` (None in air)."""

    model: Multibody
    q: np.ndarray
    state: KinematicState
    nv: int
    nz: int
    flexible: dict[int, FlexibleCoordinates]
    frames: np.ndarray
    transmissions: list[Transmission]
    stiffness: np.ndarray
    mass: np.ndarray
    damping: np.ndarray
    restoring: np.ndarray
    coupling: HydroCoupling | None
    hydro: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None

    @property
    def cartesian(self) -> np.ndarray:
        """(n_cart, n_z): the world rows of every body (6 each) per coordinate."""
        return self.frames.reshape(-1, self.nz)

    def added_mass(self, omega: float) -> np.ndarray:
        """A(omega) (n_cart, n_cart) in world rows: above the database's frequencies A_inf, below its first (zero in
        air)."""
        if self.coupling is None or self.hydro is None:
            return np.zeros((self.cartesian.shape[0],) * 2)
        grid, added, _, a_inf = self.hydro
        return self.coupling.expand(_at(omega, grid, added, a_inf))

    def radiation_damping(self, omega: float) -> np.ndarray:
        """B(omega) (n_cart, n_cart) in world rows: 0 above the database's frequencies (zero in air)."""
        if self.coupling is None or self.hydro is None:
            return np.zeros((self.cartesian.shape[0],) * 2)
        grid, _, radiation, a_inf = self.hydro
        return self.coupling.expand(_at(omega, grid, radiation, np.zeros_like(a_inf)))

    def mass_at(self, omega: float) -> np.ndarray:
        """The mass with A(omega) (n_z, n_z)."""
        jc = self.cartesian
        return self.mass + jc.T @ self.added_mass(omega) @ jc

    def damping_at(self, omega: float) -> np.ndarray:
        """The damping with B(omega) (n_z, n_z)."""
        jc = self.cartesian
        return self.damping + jc.T @ self.radiation_damping(omega) @ jc

    def point(self, body: str | None, position: np.ndarray, label: str | None = None) -> tuple[np.ndarray, np.ndarray]:
        """World position and displacement per coordinate (3, n_z) of a point of a body (None: the ground), with the
        elastic motion of a flexible body's named point ``label``."""
        mb, st = self.model, self.state
        if body is None:
            return np.asarray(position, dtype=float), np.zeros((3, self.nz))
        b = mb.body_names.index(body)
        at = st.position[b] + st.rotation[b] @ (np.asarray(position, dtype=float) - mb.bodies[b].center_of_mass)
        jac = self.frames[b, :3] - hat(at - st.position[b]) @ self.frames[b, 3:]
        if b in self.flexible and label is not None:
            f = self.flexible[b]
            jac = jac.copy()
            jac[:, f.columns] += f.rotation @ (f.frame.point_map(label)[:3] @ f.basis)
        return at, jac


def assemble(
    device: Any, *, water: bool, hydro: str | Path | HydroData | None = None, model: str = "full",
    pto_damping: bool = False,
) -> DeviceSystem:  # fmt: skip
    """The device's coordinates and matrices, in water about its static equilibrium or in air (no gravity) about its
    reference configuration (see ``wecss.devices.structural_modes``).

    Raises
    ------
    ValueError
        On an unknown model, a body with generalised modes, or (in water) no database or equilibrium.
    """
    mb = device.model
    if model not in MODELS:
        raise ValueError(f"model {model!r}; accepted: {list(MODELS)}")
    if mb.n_modes:
        raise ValueError(
            f"device {device.name!r}: bodies with generalised modes ({', '.join(mb.mode_names)}) are not supported by "
            "the structural modal analysis; declare flexible bodies instead"
        )
    coupling: HydroCoupling | None
    if water:
        statics = device.rigid_statics(hydro)
        q = statics.equilibrium()
        coupling = statics.coupling
    else:
        statics = StaticModel(mb, 0.0, None, device.ptos)
        q = mb.neutral_configuration()
        coupling = None
    st = kinematics(mb, q)
    nv = mb.nv
    flex: dict[int, FlexibleCoordinates] = {}
    column = nv
    for name in device.flexible:
        i = mb.body_names.index(name)
        frame, basis, damping = _elastic_basis(device, name, model)
        n = basis.shape[1]
        flex[i] = FlexibleCoordinates(
            name, frame, basis, damping, slice(column, column + n), st.rotation[i], st.position[i],
            mb.bodies[i].center_of_mass,
        )  # fmt: skip
        column += n
    nz = column
    # world velocities (CoM, rotation) of every body's frame per coordinate
    frames = np.zeros((len(mb.bodies), 6, nz))
    for i in range(len(mb.bodies)):
        s = mb.cart_start[i]
        frames[i, :3, :nv] = st.B[s : s + 3]
        frames[i, 3:, :nv] = st.rotation[i] @ st.B[s + 3 : s + 6]
    subtree = _subtrees(mb)
    for f in flex.values():  # the elastic motion of a joint point carries the child's subtree
        for joint in mb.joints:
            if joint.parent != f.name:
                continue
            label = f"joint:{joint.name}"
            d = f.frame.point_map(label) @ f.basis
            at = f.position + f.rotation @ (f.frame.point(label)[1] - f.reference)
            dt, dr = f.rotation @ d[:3], f.rotation @ d[3:]
            for b in subtree[mb.body_names.index(joint.child)]:
                frames[b, :3, f.columns] += dt - hat(st.position[b] - at) @ dr
                frames[b, 3:, f.columns] += dr
    for i, f in flex.items():
        nodal = f.frame.rigid_modes(f.reference) @ np.kron(np.eye(2), f.rotation.T) @ frames[i]
        nodal[:, f.columns] += f.basis
        f.nodal = nodal
    n_cart = frames.shape[0] * 6
    system = DeviceSystem(
        mb, q, st, nv, nz, flex, frames, [], np.zeros((nz, nz)), np.zeros((nz, nz)), np.zeros((nz, nz)),
        np.zeros((n_cart, n_cart)), coupling, None if coupling is None else _hydro_matrices(coupling),
    )  # fmt: skip
    for pto in device.ptos:
        if isinstance(pto, ActuatorPTO):
            pa, ja = system.point(pto.body_a, pto.point_a, f"pto:{pto.name}")
            pb, jb = system.point(pto.body_b, pto.point_b, f"pto:{pto.name}")
            d = (pa - pb) / np.linalg.norm(pa - pb)
            system.transmissions.append((pto, d @ (ja - jb), "line", d))
        else:
            g = np.zeros(nz)
            g[:nv] = pto.stroke(mb, q, st)[1]
            joint = mb.joint(pto.joint)
            axis = st.rotation[mb.body_names.index(joint.child)] @ np.asarray(joint.axis, dtype=float)
            system.transmissions.append((pto, g, joint.kind, axis))

    def outside_rigid(block: np.ndarray) -> np.ndarray:
        """The block without its rigid-rigid part (the multibody's stiffness has that, geometric terms included)."""
        out = block.copy()
        out[:nv, :nv] = 0.0
        return out

    stiffness, mass, damping = system.stiffness, system.mass, system.damping
    stiffness[:nv, :nv] = statics.stiffness(q) if nv else np.zeros((0, 0))
    damping[:nv, :nv] = np.diag(mb.joint_damping)
    for i, body in enumerate(mb.bodies):
        if i in flex:
            f = flex[i]
            assert f.nodal is not None
            stiffness[f.columns, f.columns] += f.basis.T @ f.frame.stiffness @ f.basis
            mass += f.nodal.T @ f.frame.mass @ f.nodal
            damping[f.columns, f.columns] += f.damping
        else:
            mw = np.zeros((6, 6))
            mw[:3, :3] = body.mass * np.eye(3)
            mw[3:, 3:] = st.rotation[i] @ body.inertia @ st.rotation[i].T
            mass += frames[i].T @ mw @ frames[i]
    for pto, g, _, _ in system.transmissions:
        stiffness += outside_rigid(pto.stiffness * np.outer(g, g))
        if pto_damping:
            damping += pto.damping * np.outer(g, g)
    if coupling is not None:
        jc = system.cartesian
        system.restoring = coupling.restoring
        stiffness += outside_rigid(jc.T @ coupling.restoring @ jc)
        damping += jc.T @ coupling.mooring_damping @ jc
    system.stiffness = 0.5 * (stiffness + stiffness.T)
    system.mass = 0.5 * (mass + mass.T)
    return system
