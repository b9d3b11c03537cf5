"""Mode shapes on the nodes of a device's elastic bodies (``flexible.dynamics = "elastic"``), for the modal table.

A node of an elastic body's structure (``FlexibleBody.frame``) sits, at a configuration q, at
x = p + R (X + u(xi) - c(xi)): p and R the body's centre of mass and rotation (``wecss.multibody.kinematics``),
X the node's reference position, u = Phi xi its elastic displacement in the Craig-Bampton basis ``FlexibleBody.basis``
(body axes) and c(xi) the deformed body's centre of mass at the reference pose (``ElasticBody.centre_of_mass``).
Its displacement per generalised coordinate (tangent coordinates, ``Multibody.velocity_names``) splits into

- a global part, the rigid motion of the body's floating frame carried to the node: v_o + w x (x - p), where v_o is
  the frame's velocity at p (the body's B-matrix translation rows without its own modal columns, which move the
  centre of mass with the structure) and w = R w_B its world angular velocity; the node's rotation: w;
- an elastic part, on the body's own modal coordinates: R Phi_u (translation rows of the node) and R Phi_theta
  (rotation rows),

world axes. Exact to first order about any configuration (u is linear in xi); the parent's elastic motion of a body
that rides on another elastic body's node is in its frame's motion (global).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..multibody import hat, kinematics

PARTS = ("global", "elastic")
"""The parts of a node's motion: the floating frame's rigid motion carried to it, and the structure's deformation."""


@dataclass(frozen=True)
class NodeMaps:
    """The nodes of a device's elastic bodies at a configuration.

    Attributes
    ----------
    labels : tuple of str
        ``<body>.n<k>``, the structure's node k.
    bodies : tuple of str
        The elastic body of each node.
    position : ndarray (n_node, 3)
        Where each node is at the configuration (its elastic deflection included), world axes [m].
    displacement : ndarray (2, n_node, 3, nv)
        Its translation per generalised coordinate, the :data:`PARTS` apart, world axes [m per coordinate unit].
    rotation : ndarray (2, n_node, 3, nv)
        Its rotation per generalised coordinate, the :data:`PARTS` apart, world axes [rad per coordinate unit].
    """

    labels: tuple[str, ...]
    bodies: tuple[str, ...]
    position: np.ndarray
    displacement: np.ndarray
    rotation: np.ndarray


def node_maps(device: Any, q: np.ndarray) -> NodeMaps:
    """The nodes of the elastic bodies of ``device`` (a ``wecss.devices.Device`` whose model carries them,
    ``Device.with_elastic_model``) at the configuration ``q`` (see the module docstring)."""
    model = device.model
    q = np.asarray(q, dtype=float)
    state = kinematics(model, q)
    nv = model.nv
    labels: list[str] = []
    bodies: list[str] = []
    positions: list[np.ndarray] = []
    moves: list[np.ndarray] = []  # (2, 3, nv) per node: translation, global and elastic
    turns: list[np.ndarray] = []
    for i in model.elastic_bodies:
        body = model.bodies[i]
        elastic = body.elastic
        assert elastic is not None
        structure = device.flexible_body(body.name)
        frame, phi = structure.frame, structure.basis.basis
        own = slice(model.mode_velocity_start[i], model.mode_velocity_start[i + 1])
        xi = q[model.mode_coordinate_start[i] : model.mode_coordinate_start[i + 1]]
        rotation, centre = state.rotation[i], state.position[i]
        start = model.cart_start[i]
        frame_velocity = state.B[start : start + 3].copy()
        frame_velocity[:, own] = 0.0  # the centre of mass moving with the structure is elastic motion
        spin = rotation @ state.B[start + 3 : start + 6]  # world angular velocity per coordinate
        deformation = phi @ xi
        reference_centre = elastic.centre_of_mass(xi)
        for k in range(frame.n_nodes):
            rows = frame.node_dofs(k)
            at = centre + rotation @ (frame.nodes[k] + deformation[rows[:3]] - reference_centre)
            move = np.zeros((2, 3, nv))
            turn = np.zeros((2, 3, nv))
            move[0] = frame_velocity - hat(at - centre) @ spin
            move[1][:, own] = rotation @ phi[rows[:3]]
            turn[0] = spin
            turn[1][:, own] = rotation @ phi[rows[3:]]
            labels.append(f"{body.name}.n{k}")
            bodies.append(body.name)
            positions.append(at)
            moves.append(move)
            turns.append(turn)
    if not labels:
        empty = np.zeros((len(PARTS), 0, 3, nv))
        return NodeMaps((), (), np.zeros((0, 3)), empty, empty.copy())
    return NodeMaps(
        tuple(labels),
        tuple(bodies),
        np.array(positions),
        np.stack(moves, axis=1),
        np.stack(turns, axis=1),
    )
