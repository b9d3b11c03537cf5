"""Static loads, equilibrium and the linearised generalised stiffness (with geometric stiffness from static loads)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ._dynamics import gravity_force, structural_force
from ._hydrostatics import HydroCoupling
from ._kinematics import integrate, kinematics
from ._pto import PTO
from ._tree import Multibody

EQUILIBRIUM_TOL: float = 1e-10
"""Largest accepted |F*| at equilibrium, relative to the largest static load in generalised form [-]."""


class EquilibriumError(RuntimeError):
    """The static equilibrium could not be found."""


FREE_COLUMN_TOL: float = 1e-9
"""Relative size below which a stiffness column is round-off (central differences at step 1e-6 in double precision
are accurate to about 1e-10 of the static loads)."""


@dataclass(frozen=True, eq=False)
class StaticModel:
    """Gravity, buoyancy, hydrostatic stiffness, the modes' structural stiffness and PTO springs (with preload) of a
    model at rest.

    Parameters
    ----------
    model : Multibody
    g : float
        Gravitational acceleration [m/s^2].
    coupling : HydroCoupling or None
        Hydrostatics (None: gravity and PTO springs only).
    ptos : sequence of PTO
        Their spring part k (x - x_rest) acts; damping does no static work.
    preload : sequence of float, optional
        Constant PTO forces [N or N m] (positive extends), one per PTO.
    """

    model: Multibody
    g: float
    coupling: HydroCoupling | None = None
    ptos: Sequence[PTO] = ()
    preload: Sequence[float] | None = None

    def generalized_force(self, q: np.ndarray) -> np.ndarray:
        """Static generalised force F*(q) = B' F + sum of PTO spring forces [N, N m], with the modes' structural
        stiffness [J]."""
        st = kinematics(self.model, q)
        force = gravity_force(self.model, self.g)
        if self.coupling is not None:
            force = force + self.coupling.hydrostatic_force(self.model, st)
        if self.model.n_modes:
            force = force + structural_force(self.model, q)
        out = st.B.T @ force
        preload = self.preload if self.preload is not None else [0.0] * len(self.ptos)
        for pto, f0 in zip(self.ptos, preload, strict=True):
            x, g = pto.stroke(self.model, q, st)
            out += g * (f0 - pto.stiffness * (x - pto.rest))
        return out

    def scale(self) -> float:
        """Typical size of the static loads in generalised form (for relative tolerances) [N, N m]."""
        st = kinematics(self.model, self.model.neutral_configuration())
        gravity = np.abs(st.B.T) @ np.abs(gravity_force(self.model, self.g))
        return float(max(1.0, np.max(gravity)))

    def equilibrium(self, guess: np.ndarray | None = None, *, max_iterations: int = 50) -> np.ndarray:
        """Configuration q where F*(q) = 0, by Newton iterations from ``guess`` (default: reference configuration).

        Each step is the least-squares, minimum-norm solution of K* dq = F*, so coordinates without stiffness (the
        surge of a floating device) stay where the guess puts them instead of wandering along the free direction.

        Raises
        ------
        EquilibriumError
            If the residual stays above EQUILIBRIUM_TOL times :meth:`scale` (the message gives it).
        """
        q = self.model.neutral_configuration() if guess is None else np.asarray(guess, dtype=float)
        scale = self.scale()
        residual = float(np.max(np.abs(self.generalized_force(q)))) if self.model.nv else 0.0
        for _ in range(max_iterations):
            # iterate to round-off (a calm-water run must stay at rest to 1e-12), not only to the tolerance
            if residual <= 1e-3 * EQUILIBRIUM_TOL * scale:
                break
            force = self.generalized_force(q)
            step, *_ = np.linalg.lstsq(self.stiffness(q), force, rcond=1e-10)
            # halve the step until the residual falls (large rotations can overshoot)
            for _ in range(30):
                trial = integrate(self.model, q, step)
                trial_residual = float(np.max(np.abs(self.generalized_force(trial))))
                if trial_residual < residual:
                    break
                step = step / 2
            else:
                break
            q, residual = trial, trial_residual
        if not residual <= EQUILIBRIUM_TOL * scale:
            raise EquilibriumError(
                f"no static equilibrium found: largest generalised force {residual:.3g} (tolerance "
                f"{EQUILIBRIUM_TOL * scale:.3g}) at q = {np.round(q, 6).tolist()}"
            )
        return q

    def stiffness(self, q: np.ndarray, step: float = 1e-6) -> np.ndarray:
        """Generalised stiffness K* = -dF*/dq at ``q`` (central differences in the tangent space) [N/m, N m/rad].

        It includes the geometric stiffness of the static loads (gravity, buoyancy, PTO preload), which vanishes
        only when every body is in its own equilibrium. A column below FREE_COLUMN_TOL of the largest entry
        belongs to a coordinate no static load depends on (a free surge): it is round-off and set to zero, so
        that such a coordinate is an exact integrator in the linear models.
        """
        nv = self.model.nv
        out = np.zeros((nv, nv))
        for k in range(nv):
            dv = np.zeros(nv)
            dv[k] = step
            plus = self.generalized_force(integrate(self.model, q, dv))
            minus = self.generalized_force(integrate(self.model, q, -dv))
            out[:, k] = -(plus - minus) / (2 * step)
        free = np.max(np.abs(out), axis=0) <= FREE_COLUMN_TOL * np.max(np.abs(out), initial=0.0)
        out[:, free] = 0.0
        return out
