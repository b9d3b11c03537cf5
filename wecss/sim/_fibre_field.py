"""The stress field of a frozen flexible body over a run: the quasi-static elastic response to the loads it felt.

A flexible body with ``flexible.dynamics = "frozen"`` moves rigidly in the equations of motion. Its structure
(``Device.flexible_body``: its frame held at its parent joint) then answers each saved step's loads
quasi-statically, in the basis of the static response to each of them (``static_basis``: the constraint modes of
its interfaces and the inertia-relief and centrifugal vectors, no normal modes). The loads: the point loads at its
interfaces (its children's joint reactions, reversed, at ``joint:<name>``; the PTO loads at ``pto:<name>``; its own
joint's reaction acts at the clamp, which the basis holds) and its own weight and d'Alembert inertia in the
rigid-body motion, spread over its mass (the 12 coordinates of ``wecss.structure.RIGID_LOADS``):

    K_r xi(t) = Phi' (sum_k P_k' w_k(t) + L r(t)),

with K_r = diag(omega^2) the basis's stiffness, P_k the map of a point's wrench to the nodes, L the rigid-motion
loads. The basis holds the static response to every one of these loads (whatever ``flexible.centrifugal`` says of
the dynamic basis), so xi is the exact quasi-static deformation, and the stresses at every fibre point (the stress
modes of the body's points, whose section loads include the rigid-motion loads) equal the free-body cut's wherever
both are defined, to the difference of the two mass models (the structure's sections have rotary inertia; its mass
is the body's to 0.1 %): the free-body cut of the hot spots (``wecss.sim._sections``) is the test oracle. The field
is counted point by point (``wecss.results.StressFieldRecorder``) over the statistics window, chunk by chunk.

Only dry bodies: a wetted body's hydrodynamic loads act over its surface, not at points of its structure.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..devices import FlexibleBody
from ..results import StressFieldRecorder
from ..structure import ModalBasis, StressModes, craig_bampton, rigid_load_coordinates, stress_modes
from ._sections import BodyHistory

CHUNK = 2000
"""Steps recorded at once (the memory is CHUNK times the number of fibre points)."""


def static_basis(body: FlexibleBody) -> tuple[ModalBasis, StressModes]:
    """The basis of the body's quasi-static response (constraint modes, inertia-relief and centrifugal vectors) and
    its stress modes at the body's stress points."""
    basis = craig_bampton(body.frame, body.basis.clamp, body.interfaces, 0, inertia_relief=True, centrifugal=True)
    return basis, stress_modes(body.frame, basis.basis, body.stresses.points, body.invariants.origin)


def quasi_static_coordinates(
    body: FlexibleBody, basis: ModalBasis, history: BodyHistory
) -> tuple[np.ndarray, np.ndarray]:
    """The coordinates xi (n_t, n) of the quasi-static response in ``basis`` (:func:`static_basis`) and the
    rigid-motion load coordinates (n_t, 12) (see the module docstring). The history's first point load (its own
    joint's reaction) acts at the clamp, which the basis holds; its last (the body's own, lumped at its centre of
    mass: its weight and inertia, the body being dry) is replaced by its distributed weight and inertia.

    Raises
    ------
    ValueError
        If a point load of the history is at none of the structure's named points.
    """
    frame, phi = body.frame, basis.basis
    named = {name: position for name, (_, position) in frame.points.items()}
    load = np.zeros((history.points.shape[0], phi.shape[1]))
    # the first point load is the body's own joint's reaction, at the clamp the basis holds (``field_bodies``); the
    # last is its own load at its centre of mass
    for k in range(1, history.points.shape[1] - 1):
        point = history.points[0, k]
        match = [n for n, p in named.items() if np.allclose(p, point, rtol=0, atol=1e-9 * max(1.0, np.abs(p).max()))]
        if not match:
            raise ValueError(
                f"body {body.name!r}: a load acts at {np.round(point, 6).tolist()} m, at none of its structure's "
                f"points {sorted(named)}"
            )
        wrench = np.concatenate([history.forces[:, k], history.moments[:, k]], axis=1)
        load += wrench @ (phi.T @ frame.point_map(match[0]).T).T
    rigid = rigid_load_coordinates(history.gravity - history.acceleration, history.alpha, history.omega)
    origin = body.invariants.origin
    load += rigid @ (phi.T @ frame.rigid_motion_loads(origin)).T
    return load / basis.omega**2, rigid


@dataclass(frozen=True)
class FibreField:
    """The fibre points of the device's frozen flexible bodies and their statistics over the window: ``names``,
    ``life`` [years], ``damage`` [-], ``maximum`` and ``minimum`` of the signed von Mises stress and ``rms`` of the
    von Mises stress [Pa]."""

    names: tuple[str, ...]
    life: np.ndarray
    damage: np.ndarray
    maximum: np.ndarray
    minimum: np.ndarray
    rms: np.ndarray


def fibre_field(bodies: list[tuple[FlexibleBody, BodyHistory]], dt: float, start: int) -> FibreField:
    """Record each body's field from step ``start`` (the statistics window) in chunks of :data:`CHUNK` steps,
    saved steps ``dt`` [s] apart (no field for a window of fewer than two steps)."""
    parts: list[xr.Dataset] = []
    if bodies and bodies[0][1].points.shape[0] - start < 2:
        bodies = []
    for body, history in bodies:
        basis, modes = static_basis(body)
        xi, rigid = quasi_static_coordinates(body, basis, history)
        recorder = StressFieldRecorder(modes, dt)
        for first in range(start, xi.shape[0], CHUNK):
            recorder.update(xi[first : first + CHUNK], None, rigid[first : first + CHUNK])
        parts.append(recorder.result())
    if not parts:
        empty = np.zeros(0)
        return FibreField((), empty, empty, empty, empty, empty)
    field = xr.concat(parts, dim="point")
    return FibreField(
        tuple(str(n) for n in field["point"].values),
        *(np.asarray(field[k].values, dtype=float) for k in ("life_years", "damage", "signed_von_mises_max",
                                                             "signed_von_mises_min", "von_mises_rms")),
    )  # fmt: skip
