"""Modal analysis of a device with its flexible bodies, in air or in water.

Coordinates: the joints' generalised coordinates of the multibody tree (``Multibody.velocity_names``) and, per
flexible body, its elastic coordinates in the floating frame held at the body's clamp (the parent joint): every
nodal DOF of its frame but the clamp's (``model = "full"``) or its Craig-Bampton basis (``"reduced"``,
``Device.flexible_body``). Linearised about the static equilibrium in water, about the reference configuration in
air; the motion of each body follows from the joints' rates by the tree's B-matrix, and the elastic displacement
of a flexible body's joint point carries the child's whole subtree with it (the floating frame of reference,
linearised).

- Mass: each rigid body's mass and inertia; each flexible body's consistent mass, moved by its frame's rigid motion
  and its elastic coordinates (so the floating frame's inertia coupling is in it exactly); in water the added mass
  A(omega) of the hydrodynamic database at the mode's own frequency (a fixed point per mode, as
  ``wecss.linear.modal_table``; above the database's frequencies A_inf, below them its first frequency).
- Stiffness: the multibody's generalised stiffness of the rigid coordinates (``StaticModel.stiffness``: PTO springs,
  moorings and, in water, hydrostatics and the geometric stiffness of gravity and buoyancy), the flexible bodies'
  stiffness, and the PTO springs, hydrostatics and moorings on the elastic motion of the points they act at. In air
  there is no gravity and no water: the structure's free vibration on its PTO springs and moorings (the setting of
  paper 003's modal analysis). The geometric stiffness of static loads on the elastic coordinates (an axial force in
  a member) is left out.
- Damping, for the modal damping ratio zeta = phi' C phi / (2 omega phi' M phi) (the modal damping matrix's
  diagonal; couplings through damping are neglected): the flexible bodies' structural damping ratio on their normal
  modes, the joints' own damping, moorings, in water the radiation damping B(omega) (0 above the database's
  frequencies) and, with ``pto_damping``, the PTOs' default damping.

Each mode's share of in-plane motion, out-of-plane motion and torsion, of its strain energy and of its kinetic
energy (``energy_share``), about the plane whose normal is ``plane_normal`` (default the y axis: the x-z plane of
the waves and gravity). Beam elements split exactly into axial, torsion and bending in their two planes (their local
stiffness and mass are block diagonal in these); a group counts in-plane by the square of the cosine of the angle
between its motion (the member's axis, the deflection direction) and the plane, torsion as torsion; springs along
their line (a joint PTO by its axis); a body's or an added mass's motion is split into its in-plane part
(translations in the plane, rotation about the normal) and the rest, their cross terms shared equally. The geometric
stiffness of gravity and buoyancy is not in the strain energy's shares.

Mode shapes are normalised to a largest point translation of 1 (m), positive.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from scipy.linalg import eigh

from ..hydro import HydroData
from ..multibody import ActuatorPTO
from ..structure import offset_map
from ._assembly import DeviceSystem, assemble

SHARES = ("in_plane", "out_of_plane", "torsion")
"""Kinds of motion a mode's energy is split into."""
ENERGIES = ("strain", "kinetic")
"""The energies split."""
_GROUPS = (np.array([0, 6]), np.array([3, 9]), np.array([1, 5, 7, 11]), np.array([2, 4, 8, 10]))
"""Local DOFs of an element's axial, torsion, x-y and x-z bending groups."""


def _in_plane(vector: np.ndarray, normal: np.ndarray) -> float:
    """The in-plane weight of a motion along ``vector``: 1 - cos^2 of its angle to the normal."""
    v = vector / np.linalg.norm(vector)
    return float(1.0 - (v @ normal) ** 2)


def _split(x: np.ndarray, matrix: np.ndarray, normal: np.ndarray) -> tuple[float, float]:
    """(in-plane, out-of-plane) parts of 1/2 x' A x for stacked 6-vectors (v, w) in world axes: in-plane the
    translation in the plane and the rotation about the normal; cross terms shared equally."""
    six = x.reshape(-1, 6)
    inside = np.zeros_like(six)
    inside[:, :3] = six[:, :3] - np.outer(six[:, :3] @ normal, normal)
    inside[:, 3:] = np.outer(six[:, 3:] @ normal, normal)
    a, b = inside.ravel(), (six - inside).ravel()
    cross = 0.5 * a @ matrix @ b
    return 0.5 * a @ matrix @ a + cross, 0.5 * b @ matrix @ b + cross


def _eig(stiffness: np.ndarray, mass: np.ndarray, shift: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues omega^2 (ascending) and mass-normalised vectors of K phi = omega^2 M phi, by the reciprocal of
    the shifted problem M phi = 1 / (omega^2 + s) (K + s M) phi (s = ``shift`` [rad^2/s^2]): its largest values, the
    low modes, come with full relative accuracy, where the direct problem gives them only to the round-off of the
    highest (a full finite-element model spans 10 orders of magnitude); the direct problem when K + s M is not
    definite (a strongly unstable equilibrium)."""
    try:
        values, vectors = eigh(mass, stiffness + shift * mass)
        values, vectors = 1.0 / values[::-1] - shift, vectors[:, ::-1]
    except np.linalg.LinAlgError:
        values, vectors = eigh(stiffness, mass)
    return values, vectors / np.sqrt(np.einsum("ij,ik,kj->j", vectors, mass, vectors))


class _Points:
    """Points to draw: position (world), displacement Jacobian (3, n_z), a kind, and the segments between them."""

    def __init__(self, nz: int) -> None:
        self.nz = nz
        self.labels: list[str] = []
        self.kinds: list[str] = []
        self.positions: list[np.ndarray] = []
        self.jacobians: list[np.ndarray] = []
        self.segments: list[tuple[int, int]] = []
        self.segment_kinds: list[str] = []

    def add(self, label: str, kind: str, position: np.ndarray, jacobian: np.ndarray) -> int:
        if label in self.labels:
            return self.labels.index(label)
        self.labels.append(label)
        self.kinds.append(kind)
        self.positions.append(np.asarray(position, dtype=float))
        self.jacobians.append(jacobian)
        return len(self.labels) - 1

    def join(self, a: int, b: int, kind: str) -> None:
        if a != b:
            self.segments.append((a, b))
            self.segment_kinds.append(kind)


def structural_modes(
    device: Any,
    *,
    water: bool = True,
    hydro: str | Path | HydroData | None = None,
    model: str = "full",
    n_modes: int = 12,
    plane_normal: Any = (0.0, 1.0, 0.0),
    pto_damping: bool = False,
    iterations: int = 50,
) -> xr.Dataset:
    """The lowest natural modes of ``device`` (a :class:`wecss.devices.Device`) with its flexible bodies (see the
    module docstring).

    Parameters
    ----------
    device : Device
    water : bool
        In water about the static equilibrium (hydrostatics, gravity, A(omega), B(omega)), or in air about the
        reference configuration (no gravity, no water).
    hydro : str, Path or HydroData, optional
        Overrides the device's database (in water).
    model : {"full", "reduced"}
        The flexible bodies' elastic coordinates: every nodal DOF, or their reduced bases.
    n_modes : int
        How many of the lowest modes.
    plane_normal : array_like (3,)
        Normal of the plane of in-plane motion (world axes).
    pto_damping : bool
        Include the PTOs' default damping in the damping ratios.
    iterations : int
        Fixed-point iterations per mode for A(omega) (to 1e-10 in the frequency; 0: A_inf).

    Returns
    -------
    xarray.Dataset
        ``frequency`` [Hz], ``damping_ratio``, ``converged``, ``energy_share`` (mode, energy, share),
        ``rigid_shape_linear`` (mode, dof_linear) and ``rigid_shape_angular`` (mode, dof_angular) (the joints'
        coordinates, translations and rotations apart), the flexible bodies' nodes (``node_position``,
        ``node_body``, ``node_displacement``, ``node_rotation``) and points and segments to draw
        (``point_position``, ``point_displacement``, ``point_kind``, ``segment_points``, ``segment_kind``).

    Raises
    ------
    ValueError
        On an unknown model, a bad number of modes or plane normal, a body with generalised modes, or (in water) a
        device without a database or equilibrium.
    """
    if isinstance(n_modes, bool) or not isinstance(n_modes, int) or n_modes < 1:
        raise ValueError(f"n_modes must be an integer >= 1; got {n_modes!r}")
    normal = np.asarray(plane_normal, dtype=float)
    if normal.shape != (3,) or not np.linalg.norm(normal) > 0:
        raise ValueError(f"plane_normal must be a non-zero vector [x, y, z]; got {plane_normal!r}")
    normal = normal / np.linalg.norm(normal)
    system = assemble(device, water=water, hydro=hydro, model=model, pto_damping=pto_damping)
    mb, st, nv, nz, flex, jw = system.model, system.state, system.nv, system.nz, system.flexible, system.frames
    stiffness, coupling, point = system.stiffness, system.coupling, system.point
    mass_at = system.mass_at
    values, vectors = _eig(stiffness, mass_at(np.inf))
    tiny = 1e-8  # [rad^2/s^2]: a mode without stiffness (a mechanism, a free float), at round-off
    count = min(n_modes, nz)
    omegas, shapes, converged = np.zeros(count), np.zeros((count, nz)), np.ones(count, dtype=bool)
    for j in range(count):
        phi, omega = vectors[:, j], float(np.sqrt(max(values[j], 0.0)))
        if coupling is not None and values[j] > tiny and iterations > 0:
            converged[j] = False
            for _ in range(iterations):
                current = mass_at(omega)
                vals, vecs = _eig(stiffness, current)
                k = int(np.argmax(np.abs(vecs.T @ current @ phi)))
                phi, new = vecs[:, k], float(np.sqrt(max(vals[k], 0.0)))
                if abs(new - omega) <= 1e-10 * omega:
                    omega, converged[j] = new, True
                    break
                omega = new
        omegas[j], shapes[j] = omega, phi
    order = np.argsort(omegas, kind="stable")
    omegas, shapes, converged = omegas[order], shapes[order], converged[order]
    # points and segments to draw
    pts = _Points(nz)
    node_index: list[int] = []
    node_body: list[str] = []
    node_rotations: list[np.ndarray] = []
    for f in flex.values():
        assert f.nodal is not None
        first = len(pts.labels)
        for k in range(f.frame.n_nodes):
            rows = f.frame.node_dofs(k)
            at = f.position + f.rotation @ (f.frame.nodes[k] - f.reference)
            node_index.append(pts.add(f"{f.name}.n{k}", "node", at, f.rotation @ f.nodal[rows[:3]]))
            node_body.append(f.name)
            node_rotations.append(f.rotation @ f.nodal[rows[3:]])
        for e in f.frame.elements:
            pts.join(first + e.i, first + e.j, "element")
    attached: dict[str, list[tuple[str, np.ndarray, str | None]]] = {b.name: [] for b in mb.bodies}
    for joint in mb.joints:
        where = joint.point if joint.point is not None else mb.body(joint.child).center_of_mass
        attached[joint.child].append((f"joint:{joint.name}", where, None))
        if joint.parent is not None:
            attached[joint.parent].append((f"joint:{joint.name}", where, f"joint:{joint.name}"))
    for pto in device.ptos:
        if isinstance(pto, ActuatorPTO):
            ends = []
            for carrier, where in ((pto.body_a, pto.point_a), (pto.body_b, pto.point_b)):
                at, jac = point(carrier, where, f"pto:{pto.name}")
                owner = carrier or "ground"
                ends.append(pts.add(f"{owner}:pto:{pto.name}", "attachment" if carrier else "ground", at, jac))
                if carrier is not None:
                    attached[carrier].append((f"pto:{pto.name}", where, f"pto:{pto.name}"))
            pts.join(ends[0], ends[1], "pto")
    for i, body in enumerate(mb.bodies):
        if i in flex:
            f = flex[i]
            for label, where, name in attached[body.name]:
                if name is None:
                    continue
                node, position = f.frame.point(name)
                if np.allclose(position, f.frame.nodes[node], rtol=0, atol=1e-12 * max(1.0, np.abs(position).max())):
                    continue  # on its node
                at, jac = point(body.name, where, name)
                end = pts.add(f"{body.name}:{label}", "attachment", at, jac)
                pts.join(pts.labels.index(f"{body.name}.n{node}"), end, "offset")
            continue
        centre = pts.add(body.name, "centre", st.position[i], jw[i, :3])
        for label, where, _ in attached[body.name]:
            at, jac = point(body.name, where)
            pts.join(centre, pts.add(f"{body.name}:{label}", "attachment", at, jac), "body")
    jac_all = np.array(pts.jacobians)  # (n_point, 3, n_z)
    displacement = np.einsum("paz,mz->mpa", jac_all, shapes)
    size = np.linalg.norm(displacement, axis=2)
    for m in range(count):
        p = int(np.argmax(size[m]))
        a = int(np.argmax(np.abs(displacement[m, p])))
        scale = size[m, p] * np.sign(displacement[m, p, a]) if size[m, p] > 0 else 1.0
        shapes[m] /= scale
        displacement[m] /= scale
    # damping ratios and energy shares
    ratios = np.full(count, np.nan)
    share = np.full((count, len(ENERGIES), len(SHARES)), np.nan)
    for m in range(count):
        phi, omega = shapes[m], omegas[m]
        if omega**2 > tiny:
            mj = float(phi @ mass_at(omega) @ phi)
            ratios[m] = float(phi @ system.damping_at(omega) @ phi) / (2 * mj * omega)
        strain, kinetic = _energies(phi, system, system.added_mass(omega), normal)
        for k, energy in enumerate((strain, kinetic)):
            if energy.sum() > 0 and (k == 1 or omega**2 > tiny):  # a mode without stiffness has no strain energy
                share[m, k] = energy / energy.sum()
    nodes = np.array(node_index, dtype=np.int64)
    positions = np.array(pts.positions)
    segments = np.array(pts.segments, dtype=np.int64).reshape(-1, 2)
    notes = (
        "in air: no gravity, no water, about the reference configuration; " if not water
        else "in water: about the static equilibrium, A(omega) at each mode's frequency (A_inf above the database's "
        "frequencies), hydrostatics and the geometric stiffness of gravity and buoyancy on the rigid coordinates; "
    ) + (
        "PTO springs; damping ratios from the modal damping matrix's diagonal (structural, joints, moorings"
        + (", radiation" if water else "") + (", PTO damping" if pto_damping else "") + "); the geometric stiffness "
        "of static loads on the elastic coordinates is left out"
    )  # fmt: skip
    mode = np.arange(1, count + 1)
    names, kinds = mb.velocity_names, mb.velocity_kinds  # no generalised modes here (refused)
    linear = [k for k in range(nv) if kinds[k] == "linear"]
    angular = [k for k in range(nv) if kinds[k] == "angular"]
    data = {
        "frequency": (("mode",), omegas / (2 * np.pi), {"long_name": "natural frequency (undamped)", "units": "Hz"}),
        "damping_ratio": (("mode",), ratios, {"long_name": "modal damping ratio", "units": "1"}),
        "converged": (("mode",), converged, {"long_name": "added-mass fixed point converged"}),
        "energy_share": (("mode", "energy", "share"), share,
                         {"long_name": "share of the mode's energy in in-plane motion, out-of-plane motion, torsion",
                          "units": "1"}),
        "rigid_shape_linear": (("mode", "dof_linear"), shapes[:, linear],
                               {"long_name": "mode shape: translational generalised coordinates, per unit largest "
                                "point translation", "units": "1"}),
        "rigid_shape_angular": (("mode", "dof_angular"), shapes[:, angular],
                                {"long_name": "mode shape: rotational generalised coordinates, per unit largest "
                                 "point translation", "units": "rad/m"}),
        "node_position": (("node", "axis"), positions[nodes] if nodes.size else np.zeros((0, 3)),
                          {"long_name": "finite-element node position (world)", "units": "m"}),
        "node_body": (("node",), np.array(node_body, dtype=object), {"long_name": "flexible body of the node"}),
        "node_displacement": (("mode", "node", "axis"), displacement[:, nodes],
                              {"long_name": "mode shape: node translation (world), largest point translation 1",
                               "units": "1"}),
        "node_rotation": (("mode", "node", "axis"),
                          np.einsum("naz,mz->mna", np.array(node_rotations).reshape(-1, 3, nz), shapes),
                          {"long_name": "mode shape: node rotation (world) per unit largest point translation",
                           "units": "rad/m"}),
        "point_position": (("point", "axis"), positions, {"long_name": "point to draw (world)", "units": "m"}),
        "point_kind": (("point",), np.array(pts.kinds, dtype=object),
                       {"long_name": "node, centre (of a rigid body), attachment (joint, PTO) or ground"}),
        "point_displacement": (("mode", "point", "axis"), displacement,
                               {"long_name": "mode shape: point translation (world), largest 1", "units": "1"}),
        "segment_points": (("segment", "end"), segments, {"long_name": "the two points of a segment to draw"}),
        "segment_kind": (("segment",), np.array(pts.segment_kinds, dtype=object),
                         {"long_name": "element, body (rigid), offset (rigid link) or pto"}),
    }  # fmt: skip
    ds = xr.Dataset(
        data,
        coords={
            "mode": mode, "energy": list(ENERGIES), "share": list(SHARES),
            "dof_linear": [names[k] for k in linear], "dof_angular": [names[k] for k in angular],
            "node": [pts.labels[k] for k in nodes], "point": pts.labels, "axis": ["x", "y", "z"],
        },
        attrs={
            "device": device.name, "medium": "water" if water else "air", "model": model,
            "plane_normal": normal.tolist(), "coordinates": nz, "notes": notes,
            "flexible_bodies": ", ".join(device.flexible) or "none",
        },
    )  # fmt: skip
    ds.mode.attrs.update(long_name="mode number, by frequency")
    return ds


def _energies(
    phi: np.ndarray, system: DeviceSystem, added: np.ndarray, normal: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Strain and kinetic energy of a mode shape split into (in-plane, out-of-plane, torsion)."""
    strain, kinetic = np.zeros(3), np.zeros(3)
    mb, jw, rotation, jc = system.model, system.frames, system.state.rotation, system.cartesian
    flex = system.flexible
    for f in flex.values():
        assert f.nodal is not None
        u = f.nodal @ phi
        for e in f.frame.elements:
            local = e.transform @ u[f.frame.element_dofs(e)]
            axes = (f.rotation @ np.asarray(e.axes).T).T
            for group, direction in zip(_GROUPS, (axes[0], None, axes[1], axes[2]), strict=True):
                ks = 0.5 * local[group] @ e.local_stiffness[np.ix_(group, group)] @ local[group]
                ke = 0.5 * local[group] @ e.local_mass[np.ix_(group, group)] @ local[group]
                if direction is None:
                    strain[2] += ks
                    kinetic[2] += ke
                    continue
                w = _in_plane(direction, normal)
                strain[:2] += (w * ks, (1 - w) * ks)
                kinetic[:2] += (w * ke, (1 - w) * ke)
        for pm in f.frame.masses:
            x = (
                np.kron(np.eye(2), f.rotation)
                @ offset_map(pm.position - f.frame.nodes[pm.node])
                @ u[f.frame.node_dofs(pm.node)]
            )
            mw = np.zeros((6, 6))
            mw[:3, :3] = pm.mass * np.eye(3)
            mw[3:, 3:] = f.rotation @ pm.inertia @ f.rotation.T
            kinetic[:2] += _split(x, mw, normal)
    for i, body in enumerate(mb.bodies):
        if i in flex:
            continue
        mw = np.zeros((6, 6))
        mw[:3, :3] = body.mass * np.eye(3)
        mw[3:, 3:] = rotation[i] @ body.inertia @ rotation[i].T
        kinetic[:2] += _split(jw[i] @ phi, mw, normal)
    x = jc @ phi
    strain[:2] += _split(x, system.restoring, normal)
    kinetic[:2] += _split(x, added, normal)
    for pto, g, kind, direction in system.transmissions:
        spring = 0.5 * pto.stiffness * float(g @ phi) ** 2
        w = float((direction @ normal) ** 2) if kind == "revolute" else _in_plane(direction, normal)
        strain[:2] += (w * spring, (1 - w) * spring)
    return strain, kinetic
