"""Which radiation couplings matter: the one rule shared by the convolution and the state-space fits.

An entry (i, j) of the radiation kernel K(t) is kept when its peak over time is at least ``threshold`` times
sqrt(P_i P_j), P_i = max_t |K_ii(t)| the diagonal peaks, and is not zero. The geometric mean of the two diagonal
peaks has the units of the entry, so a heave-pitch coupling [N/m] is judged against heave [N/m ... ] and pitch
[N m/rad ...] alike; judging every entry against the largest diagonal peak instead would drop every coupling of
the (numerically small) pitch DOFs. The scene's ``radiation.coupling_threshold`` (default 1e-3) is this threshold
for both radiation methods.
"""

from __future__ import annotations

import numpy as np


def significant_couplings(peak: np.ndarray, threshold: float) -> np.ndarray:
    """Boolean (n, n) mask of the kernel entries kept by the rule of the module docstring.

    Parameters
    ----------
    peak : ndarray (n, n)
        Peak over time of |K_ij(t)| [SI of each entry].
    threshold : float
        Share of sqrt(P_i P_j) [-], in [0, 1).

    Raises
    ------
    ValueError
        If ``threshold`` lies outside [0, 1) or ``peak`` is not square.
    """
    peak = np.asarray(peak, dtype=float)
    if peak.ndim != 2 or peak.shape[0] != peak.shape[1]:
        raise ValueError(f"peak must be a square matrix; got shape {peak.shape}")
    if not 0 <= threshold < 1:
        raise ValueError(f"the coupling threshold is a share of sqrt(P_i P_j) in [0, 1); got {threshold!r}")
    diagonal = np.diag(peak)
    return (peak >= threshold * np.sqrt(np.outer(diagonal, diagonal))) & (peak > 0)
