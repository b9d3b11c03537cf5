"""The phi-functions of exact (exponential) steps: phi_j(s) = sum_k s^k / (k + j)!, so phi_1 = (e^s - 1)/s,
phi_2 = (e^s - 1 - s)/s^2, phi_3 = (e^s - 1 - s - s^2/2)/s^3. Over a step h, x' = s/h x + b u(t) with u linear in
time gives x+ = e^s x + h [(phi_1 - phi_2) u_k + phi_2 u_k+1] b."""

from __future__ import annotations

import math

import numpy as np

SERIES_BELOW: float = 0.1
"""Below this |s| the closed forms cancel and the series (to s^11, truncation below 1e-16) is used."""


def phi_functions(s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """phi_1, phi_2 and phi_3 of the (complex) array ``s``."""
    s = np.asarray(s)
    small = np.abs(s) < SERIES_BELOW
    ss = np.where(small, 1.0, s)
    e = np.expm1(ss)
    closed = (e / ss, (e - ss) / ss**2, (e - ss - ss**2 / 2) / ss**3)
    out = []
    for j, value in zip((1, 2, 3), closed, strict=True):
        series = sum(s**k / math.factorial(k + j) for k in range(12))
        out.append(np.where(small, series, value))
    return out[0], out[1], out[2]
