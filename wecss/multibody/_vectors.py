"""The check of a 3-vector given to the multibody objects (points, axes)."""

from __future__ import annotations

import numpy as np


def vector3(value: object, where: str, units: str = "m") -> np.ndarray:
    """``value`` as a float array (3,).

    Raises
    ------
    ValueError
        If it is not 3 finite numbers (the message names ``where``, the units and the value).
    """
    arr = np.asarray(value, dtype=float)
    if arr.shape != (3,) or not np.all(np.isfinite(arr)):
        raise ValueError(f"{where} must be 3 finite numbers [{units}]; got {value!r}")
    return arr
