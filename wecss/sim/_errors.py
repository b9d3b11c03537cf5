"""The simulator's errors: a run that left the range where its results mean anything."""

from __future__ import annotations

import numpy as np


class SimulationDiverged(RuntimeError):
    """The simulation left the range where its results mean anything.

    Attributes
    ----------
    time : float
        Time of the failing step [s].
    step : int
    state : dict
        ``q`` and ``v`` at the last good step.
    """

    def __init__(self, message: str, time: float, step: int, state: dict[str, np.ndarray]) -> None:
        super().__init__(message)
        self.time = time
        self.step = step
        self.state = state


class PtoLimitExceeded(SimulationDiverged):
    """A PTO stroke passed its ``stroke_limit`` on a PTO without an end stop (the device spec says to stop)."""


class ControllerTimeout(RuntimeError):
    """A controller's ``compute`` ran past the scene's ``controller.time_limit`` (the message names the controller,
    the simulation time of the call and the limit)."""
