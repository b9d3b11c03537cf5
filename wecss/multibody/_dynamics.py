"""MFM dynamics (paper Eq. 46) with the infinite-frequency added mass in the mass matrix:

    M* = B' (M + A_inf) B,   N* = B' ((M + A_inf) Bdot + D M B),   F* = B' F,
    v_dot = M*^-1 (F* - N* v)

Cartesian forces F hold, per body, the world-frame force at the centre of mass followed by the moment
about the centre of mass in body axes (as the paper's Cartesian velocities). The kinetic energy
T = 1/2 v' M* v changes at the rate v' F* (the D M B term does no work), which the tests check.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._kinematics import KinematicState, kinematics
from ._tree import Multibody


def body_mass_matrix(model: Multibody) -> np.ndarray:
    """Block-diagonal 6n x 6n rigid-body mass matrix diag(m I_3, J) per body (Eq. 43)."""
    n = len(model.bodies)
    out = np.zeros((6 * n, 6 * n))
    for i, body in enumerate(model.bodies):
        out[6 * i : 6 * i + 3, 6 * i : 6 * i + 3] = body.mass * np.eye(3)
        out[6 * i + 3 : 6 * i + 6, 6 * i + 3 : 6 * i + 6] = body.inertia
    return out


@dataclass(frozen=True)
class DynamicsTerms:
    """M*, N* and the kinematics at one state."""

    mass: np.ndarray
    nonlinear: np.ndarray
    state: KinematicState


class Dynamics:
    """The MFM equations of motion of a multibody tree, optionally with added mass.

    Parameters
    ----------
    model : Multibody
    added_mass : ndarray (6n, 6n), optional
        Infinite-frequency added mass in Cartesian coordinates at the centres of mass (all body-to-body
        couplings), in the paper's per-body order (3 translations, 3 rotations). Default: none.

    Raises
    ------
    ValueError
        If ``added_mass`` has the wrong shape or is not symmetric.
    """

    def __init__(self, model: Multibody, added_mass: np.ndarray | None = None) -> None:
        n6 = 6 * len(model.bodies)
        self.model = model
        self.rigid_mass = body_mass_matrix(model)
        if added_mass is None:
            added_mass = np.zeros((n6, n6))
        added_mass = np.asarray(added_mass, dtype=float)
        if added_mass.shape != (n6, n6):
            raise ValueError(f"added_mass must be {n6}x{n6} (6 per body); got shape {added_mass.shape}")
        if not np.allclose(added_mass, added_mass.T, rtol=0, atol=1e-9 * max(1.0, float(np.abs(added_mass).max()))):
            raise ValueError("added_mass must be symmetric")
        self.added_mass = added_mass
        self.total_mass = self.rigid_mass + added_mass

    def terms(self, q: np.ndarray, v: np.ndarray) -> DynamicsTerms:
        """M*(q) and N*(q, v)."""
        st = kinematics(self.model, q, v)
        assert st.Bdot is not None
        b = st.B
        mass = b.T @ self.total_mass @ b
        nonlinear = b.T @ (self.total_mass @ st.Bdot + st.D() @ self.rigid_mass @ b)
        return DynamicsTerms(0.5 * (mass + mass.T), nonlinear, st)

    def accelerations(self, q: np.ndarray, v: np.ndarray, force: np.ndarray) -> np.ndarray:
        """Generalised accelerations v_dot = M*^-1 (B' F - N* v) for Cartesian forces ``force`` (6n,)."""
        t = self.terms(q, v)
        return np.linalg.solve(t.mass, t.state.B.T @ np.asarray(force, dtype=float) - t.nonlinear @ v)

    def kinetic_energy(self, q: np.ndarray, v: np.ndarray) -> float:
        """T = 1/2 v' M* v [J]."""
        b = kinematics(self.model, q).B
        return 0.5 * float(v @ b.T @ self.total_mass @ b @ v)


def gravity_force(model: Multibody, g: float) -> np.ndarray:
    """Cartesian gravity force (6n,): -m g along world z at each centre of mass, no moment [N]."""
    out = np.zeros(6 * len(model.bodies))
    for i, body in enumerate(model.bodies):
        out[6 * i + 2] = -body.mass * g
    return out


def potential_energy(model: Multibody, q: np.ndarray, g: float) -> float:
    """Gravitational potential energy sum m g z_cm [J]."""
    st = kinematics(model, q)
    return float(sum(b.mass * g * st.position[i, 2] for i, b in enumerate(model.bodies)))
