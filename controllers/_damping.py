"""Linear PTO damping: f = -c x_dot for every PTO (M4 paper Eq. 50)."""

from __future__ import annotations

import numpy as np

from wecss.control import ControlContext, Controller, Measurement, pto_control_force


class LinearDamping(Controller):
    """Linear damping (and optional stiffness) per PTO.

    Parameters
    ----------
    damping : float or sequence of float or None
        c [N s/m or N m s/rad]; one value for all PTOs or one per PTO. Default (None): the device's PTO damping
        (:attr:`wecss.control.ControlContext.default_damping`; the M4 paper's 6 N m s/rad for the M4 devices).
    stiffness : float or sequence of float
        k [N/m or N m/rad] (default 0).

    Raises
    ------
    ValueError
        On negative or non-finite gains, or a number of gains that does not match the PTOs at setup.
    """

    needs_state = False

    def __init__(self, damping: float | list[float] | None = None, stiffness: float | list[float] = 0.0) -> None:
        self._damping = None if damping is None else _gains("damping", damping)
        self._stiffness = _gains("stiffness", stiffness)
        self.c = self._damping if self._damping is not None else np.zeros(0)  # per PTO once set up
        self.k = self._stiffness

    def setup(self, context: ControlContext) -> None:
        n_pto = context.n_pto
        damping = np.asarray(context.default_damping, dtype=float) if self._damping is None else self._damping
        for label, values in (("damping", damping), ("stiffness", self._stiffness)):
            if values.size not in (1, n_pto):
                raise ValueError(f"{label} has {values.size} values; the device has {n_pto} PTOs (give 1 or {n_pto})")
        self.c = np.broadcast_to(damping, (n_pto,)).copy()
        self.k = np.broadcast_to(self._stiffness, (n_pto,)).copy()

    def linear_gains(self) -> tuple[np.ndarray, np.ndarray]:
        """(damping, stiffness) per PTO: the simulator applies f = -c x_dot - k x inside the equations of motion
        (continuous in time, as the paper's Eq. 50) instead of sampling :meth:`compute` once per step."""
        return self.c.copy(), self.k.copy()

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        return pto_control_force(0.0, self.c, self.k, measurement.displacement, measurement.velocity)


def _gains(label: str, values: float | list[float] | tuple[float, ...]) -> np.ndarray:
    """Gains as a 1-d float array, checked finite (and non-negative for damping)."""
    out = np.atleast_1d(np.asarray(values, dtype=float))
    if not np.all(np.isfinite(out)):
        raise ValueError(f"{label} must be finite; got {out.tolist()}")
    if "damping" in label and np.any(out < 0):
        raise ValueError(f"{label} must be >= 0 (a negative damping injects energy); got {out.tolist()}")
    return out
