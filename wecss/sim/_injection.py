"""A note on energy a controller puts into the device (issue 31): a PTO whose mean absorbed power over the
statistics window is negative (the PTO drove the device: a reactive controller returns energy in part of each
cycle, never on average when it absorbs). Linear gains with a negative damping are refused before a run
(``wecss.compiled.pto_gains``)."""

from __future__ import annotations

import numpy as np

from ..control import ControlledScene

INJECTION_TOL_W: float = 1e-9
"""A mean PTO power below minus this [W] is noted (round-off in calm water stays far below it)."""


def injection_notes(controlled: ControlledScene, mean_power: np.ndarray | None) -> list[str]:
    """The note for a run's ``mean_power`` [W] per PTO (None: the run has no PTO power)."""
    if mean_power is None:
        return []
    names = [pto.name for pto in controlled.device.ptos]
    power = np.asarray(mean_power, dtype=float).reshape(-1)
    which = ", ".join(f"{n} {p:.4g} W" for n, p in zip(names, power, strict=True) if p < -INJECTION_TOL_W)
    if not which:
        return []
    return [
        f"energy injected: the mean absorbed PTO power over the statistics window is negative ({which}); the "
        f"controller {controlled.scene.controller.name!r} ({type(controlled.controller).__name__}) drove the device "
        "with more energy than it took"
    ]
