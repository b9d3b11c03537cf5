"""The controller protocol, the measurement a controller receives, and the registry by entry point."""

from __future__ import annotations

from dataclasses import dataclass
from importlib.metadata import entry_points
from typing import Any, Protocol, runtime_checkable

import numpy as np

ENTRY_POINT_GROUP = "wecss.controllers"


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

    The simulator calls :meth:`compute` at the start of every step and holds the force over the step. A
    controller that is a linear feedback on the PTO stroke may also offer ``linear_gains() -> (damping,
    stiffness)`` (arrays, one per PTO); the simulator then applies f = -c x_dot - k x continuously inside the
    equations of motion instead (as :class:`controllers.LinearDamping` does).
    """

    needs_state: bool

    def setup(self, n_pto: int, dt: float) -> None:
        """Called once before a run with the number of PTOs and the control step [s]."""
        ...

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        """PTO forces [N or N m] at time ``t`` [s]."""
        ...


def available() -> list[str]:
    """Names registered under the ``wecss.controllers`` entry-point group."""
    return sorted(ep.name for ep in entry_points(group=ENTRY_POINT_GROUP))


def create(name: str, **parameters: Any) -> Controller:
    """Build a registered controller by name with its parameters.

    Raises
    ------
    ValueError
        For an unknown name (the message lists the known ones).
    """
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        if ep.name == name:
            return ep.load()(**parameters)
    raise ValueError(f"unknown controller {name!r}; available: {', '.join(available()) or 'none'}")
