"""The controller protocol: what a controller is told once per run (:class:`ControlContext`), what it is given at
every control step (:class:`Measurement`) and what it returns (one force or torque per PTO)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np


@dataclass(frozen=True)
class ControlContext:
    """What a controller learns once per run, before the first :meth:`Controller.compute`.

    Attributes
    ----------
    pto_names : tuple of str
        The device's PTOs, in the order of every force vector.
    control_period : float
        Time between two calls of :meth:`Controller.compute` [s]; the force is held in between.
    default_damping : tuple of float
        The device's default PTO damping per PTO [N s/m or N m s/rad] (its spec's ``damping``; the M4 paper's
        6 N m s/rad). The controller owns the gains it applies: this is only a default it may take.
    """

    pto_names: tuple[str, ...]
    control_period: float
    default_damping: tuple[float, ...]

    def __post_init__(self) -> None:
        if len(self.default_damping) != len(self.pto_names):
            raise ValueError(f"default_damping has {len(self.default_damping)} values for {len(self.pto_names)} PTOs")
        if not self.control_period > 0:
            raise ValueError(f"control_period must be positive [s]; got {self.control_period!r}")

    @property
    def n_pto(self) -> int:
        """Number of PTOs."""
        return len(self.pto_names)


@dataclass(frozen=True)
class Measurement:
    """What a controller is given at a control step.

    Attributes
    ----------
    displacement : ndarray (n_pto,)
        PTO strokes from their rest positions [m or rad].
    velocity : ndarray (n_pto,)
        PTO stroke rates [m/s or rad/s].
    state : ndarray or None
        The full state, for controllers that declare ``needs_state``.
    """

    displacement: np.ndarray
    velocity: np.ndarray
    state: np.ndarray | None = None


@runtime_checkable
class Controller(Protocol):
    """A PTO controller: one force (or torque) per PTO, positive extending the stroke.

    The simulator calls :meth:`setup` once per run and :meth:`compute` once per control period, holding the force
    over the period. A controller that is a linear feedback on the PTO stroke may also offer ``linear_gains() ->
    (damping, stiffness)`` (arrays, one per PTO, valid after :meth:`setup`); the simulator then applies
    f = -c x_dot - k x continuously inside the equations of motion instead (as ``controllers.LinearDamping`` does).
    """

    needs_state: bool

    def setup(self, context: ControlContext) -> None:
        """Called once before a run (see :class:`ControlContext`)."""
        ...

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        """PTO forces [N or N m] at time ``t`` [s]."""
        ...
