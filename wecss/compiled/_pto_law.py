"""The PTO force law, written once: the controller's force is its held command plus its linear feedback on the
stroke, f_c = command - c x_dot - k x, saturated at the PTO's force limit; the device spring -k_s (x) acts beside
it (and the end stops beyond the stroke limit, ``_kernels.end_stop``).

:func:`pto_control_force` is plain arithmetic, so the same function serves the numba kernels (inlined as
:data:`pto_control_force_kernel`), the linear runs on arrays and the frequency domain on complex amplitudes
(x_dot = i omega x); :func:`pto_gains` checks the gains a controller folds into the equations, once, on their way
into the plant.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._jit import inline_kernel


def pto_control_force(command: Any, damping: Any, stiffness: Any, stroke: Any, rate: Any) -> Any:
    """The controller's PTO force before its limit, f_c = command - c x_dot - k x [N or N m].

    Parameters
    ----------
    command : float or ndarray
        The held command (0 for a pure linear feedback) [N or N m].
    damping, stiffness : float or ndarray
        The linear gains c [N s/m or N m s/rad] and k [N/m or N m/rad].
    stroke, rate : float or ndarray
        x from the spring's rest [m or rad] and x_dot [m/s or rad/s]; complex amplitudes work too.
    """
    return command - damping * rate - stiffness * stroke


pto_control_force_kernel = inline_kernel(pto_control_force)
""":func:`pto_control_force` for the compiled kernels (inlined: its operations are the caller's)."""


def saturate(force: Any, limit: Any) -> Any:
    """``force`` clipped to [-limit, limit] (arrays; ``limit`` inf for none)."""
    return np.minimum(np.maximum(force, -limit), limit)


def pto_gains(damping: Any, stiffness: Any, n_pto: int) -> tuple[np.ndarray, np.ndarray]:
    """Linear PTO gains as one finite value per PTO (a single value applies to all).

    Raises
    ------
    ValueError
        If a gain is not finite, a damping is negative, or there are neither 1 nor ``n_pto`` values.
    """
    out = []
    for label, values in (("damping", damping), ("stiffness", stiffness)):
        gains = np.atleast_1d(np.asarray(values, dtype=float))
        if gains.ndim != 1 or gains.size not in (1, n_pto) or not np.all(np.isfinite(gains)):
            raise ValueError(f"linear {label} gains: expected 1 or {n_pto} finite values; got {values!r}")
        if label == "damping" and np.any(gains < 0):
            raise ValueError(f"linear damping gains must be >= 0 (a negative damping injects energy); got {values!r}")
        out.append(np.broadcast_to(gains, (n_pto,)).copy())
    return out[0], out[1]
