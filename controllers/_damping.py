"""Linear PTO damping: f = -c x_dot for every PTO (M4 paper Eq. 50)."""

from __future__ import annotations

import numpy as np

from ._base import Measurement


class LinearDamping:
    """Linear damping (and optional stiffness) per PTO.

    Parameters
    ----------
    damping : float or sequence of float
        c [N s/m or N m s/rad]; one value for all PTOs or one per PTO. Default: the M4 paper's 6 N m s/rad.
    stiffness : float or sequence of float
        k [N/m or N m/rad] (default 0).

    Raises
    ------
    ValueError
        On negative or non-finite gains, or a number of gains that does not match the PTOs at setup.
    """

    needs_state = False

    def __init__(self, damping: float | list[float] = 6.0, stiffness: float | list[float] = 0.0) -> None:
        self._damping = np.atleast_1d(np.asarray(damping, dtype=float))
        self._stiffness = np.atleast_1d(np.asarray(stiffness, dtype=float))
        for label, values in (("damping", self._damping), ("stiffness", self._stiffness)):
            if not np.all(np.isfinite(values)):
                raise ValueError(f"{label} must be finite; got {values.tolist()}")
        if np.any(self._damping < 0):
            raise ValueError(f"damping must be >= 0 (a negative damping injects energy); got {self._damping.tolist()}")
        self.c = self._damping
        self.k = self._stiffness

    def setup(self, n_pto: int, dt: float) -> None:
        for label, values in (("damping", self._damping), ("stiffness", self._stiffness)):
            if values.size not in (1, n_pto):
                raise ValueError(f"{label} has {values.size} values; the device has {n_pto} PTOs (give 1 or {n_pto})")
        self.c = np.broadcast_to(self._damping, (n_pto,)).copy()
        self.k = np.broadcast_to(self._stiffness, (n_pto,)).copy()

    def linear_gains(self) -> tuple[np.ndarray, np.ndarray]:
        """(damping, stiffness) per PTO: the simulator applies f = -c x_dot - k x inside the equations of motion
        (continuous in time, as the paper's Eq. 50) instead of sampling :meth:`compute` once per step."""
        return self.c.copy(), self.k.copy()

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        return -self.c * measurement.velocity - self.k * measurement.displacement
