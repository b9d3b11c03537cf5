"""The controller call, written once for every simulator: a fresh start per run and one checked force per call."""

from __future__ import annotations

import numpy as np

from ..compiled import CompiledScene
from ..control import Measurement


def start_controller(compiled: CompiledScene) -> None:
    """Set the scene's controller up afresh for a run (controllers with memory start from scratch)."""
    compiled.controller.setup(compiled.control_context)


def controller_force(compiled: CompiledScene, t: float, displacement: np.ndarray, velocity: np.ndarray) -> np.ndarray:
    """The PTO forces [N or N m] the scene's controller commands at time ``t`` [s] for the PTO strokes
    ``displacement`` (from their rest positions) and ``velocity``.

    Raises
    ------
    ValueError
        If the controller returns anything but one finite force per PTO.
    """
    n_pto = compiled.control_context.n_pto
    measurement = Measurement(np.array(displacement, dtype=float), np.array(velocity, dtype=float))
    out = np.asarray(compiled.controller.compute(t, measurement), dtype=float)
    if out.shape != (n_pto,) or not np.all(np.isfinite(out)):
        raise ValueError(f"controller returned {out!r}; expected {n_pto} finite forces")
    return out
