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
loads (of the undeformed body: the loads of its rotation on its deformation are left out of the solve, and so of its
stresses, ``motion=False``). The basis holds the static response to every one of these loads (whatever
``flexible.centrifugal`` says of the dynamic basis), so xi is the exact quasi-static deformation, and the stresses
at every fibre point (the stress modes of the body's points, whose section loads include the rigid-motion loads)
equal the free-body cut's wherever both are defined, to the difference of the two mass models (the structure's
sections have rotary inertia; its mass is the body's to 0.1 %): the free-body cut of the hot spots
(``wecss.sim._sections``) is the test oracle. The field is counted point by point
(``wecss.results.StressFieldRecorder``) over the statistics window, chunk by chunk.

Only dry bodies: a wetted body's hydrodynamic loads act over its surface, not at points of its structure.

An elastic body (``flexible.dynamics = "elastic"``) carries its deformation in its modal coordinates xi(t): its
stresses are those of its basis's stress modes, sigma = S xi + S_a xi_ddot + S_r r + (S_m r) xi + (S_c w) xi_dot
(+ xi' S_g xi with its geometric stiffening), with r the rigid-motion load coordinates of its floating frame's motion
(``ElasticHistory``) and w its angular velocity: the section loads of the finite-element solution -(K u + M a - f)
element by element, with the d'Alembert loads of the whole acceleration of its mass points in the floating frame,
the Coriolis and centrifugal loads of the elastic motion included (2 w x u_dot, w x (w x u), alpha x u and the
rotary inertia's share: ``wecss.structure._stress``).
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


@dataclass
class ElasticHistory:
    """An elastic body's modal coordinates and its floating frame's motion at the saved steps.

    xi, xi_dot, xi_ddot : (n_t, n) its modal coordinates [1], their rates [1/s] and accelerations [1/s^2]; gravity :
    (n_t, 3) g in body axes [m/s^2]; origin_acceleration : (n_t, 3) the acceleration of the frame's point ``origin``
    [m/s^2], alpha, omega : (n_t, 3) the frame's angular acceleration [rad/s^2] and velocity [rad/s], body axes;
    origin : (3,) that point in the frame's coordinates (the reference configuration's world coordinates) [m].
    """

    xi: np.ndarray
    xi_dot: np.ndarray
    xi_ddot: np.ndarray
    gravity: np.ndarray
    origin_acceleration: np.ndarray
    alpha: np.ndarray
    omega: np.ndarray
    origin: np.ndarray

    def rigid_coordinates(self, origin: np.ndarray) -> np.ndarray:
        """The rigid-motion load coordinates (n_t, 12) (``wecss.structure.RIGID_LOADS``) about the frame's point
        ``origin`` [m]: the frame's acceleration carried there, a + alpha x r + w x (w x r), r = origin - the
        history's origin."""
        arm = np.asarray(origin, dtype=float) - self.origin
        w = self.omega
        acceleration = self.origin_acceleration + np.cross(self.alpha, arm) + np.cross(w, np.cross(w, arm))
        return rigid_load_coordinates(self.gravity - acceleration, self.alpha, w)


@dataclass(frozen=True)
class FibreField:
    """The fibre points of the device's flexible bodies (frozen and elastic) and their statistics over the window:
    ``names``, ``life`` [years], ``damage`` [-], ``maximum`` and ``minimum`` of the signed von Mises stress and
    ``rms`` of the von Mises stress [Pa]."""

    names: tuple[str, ...]
    life: np.ndarray
    damage: np.ndarray
    maximum: np.ndarray
    minimum: np.ndarray
    rms: np.ndarray


def fibre_field(bodies: list[tuple[FlexibleBody, BodyHistory | ElasticHistory]], dt: float, start: int) -> FibreField:
    """Record each body's field from step ``start`` (the statistics window) in chunks of :data:`CHUNK` steps,
    saved steps ``dt`` [s] apart (no field for a window of fewer than two steps): a frozen body's from its history's
    loads (:class:`BodyHistory`), an elastic body's from its modal coordinates (:class:`ElasticHistory`)."""
    parts: list[xr.Dataset] = []
    if bodies and bodies[0][1].gravity.shape[0] - start < 2:
        bodies = []
    for body, history in bodies:
        elastic = isinstance(history, ElasticHistory)
        xi_dot: np.ndarray | None
        xi_ddot: np.ndarray | None
        omega: np.ndarray | None
        if isinstance(history, ElasticHistory):
            modes, xi, xi_dot, xi_ddot = body.stresses, history.xi, history.xi_dot, history.xi_ddot
            rigid, omega = history.rigid_coordinates(body.invariants.origin), history.omega
        else:  # a quasi-static response to the rigid body's loads: no rates, no accelerations, no loads of its motion
            basis, modes = static_basis(body)
            xi, rigid = quasi_static_coordinates(body, basis, history)
            xi_dot = xi_ddot = omega = None
        recorder = StressFieldRecorder(modes, dt, motion=elastic)
        for first in range(start, xi.shape[0], CHUNK):
            chunk = slice(first, first + CHUNK)
            recorder.update(
                xi[chunk], *(None if a is None else a[chunk] for a in (xi_ddot, rigid, xi_dot, omega))
            )  # fmt: skip
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
